// Throttles repeated error messages per text rather than per call site: a camera sending the
// same bad frame 30 times a second logs once every few seconds, but a new kind of problem is
// logged at once (ROS's *_THROTTLE macros would hide it behind the first one).
#pragma once

#include <map>
#include <mutex>
#include <string>

#include <ros/time.h>

namespace rle_vision {

class ErrorThrottle {
 public:
  explicit ErrorThrottle(double period_s = 5.0) : period_s_(period_s) {}

  // True when `text` was not logged in the last period (the caller then logs it).
  bool shouldLog(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::WallTime now = ros::WallTime::now();
    if (last_logged_.size() > 64) last_logged_.clear();  // bounded: texts may carry numbers
    auto it = last_logged_.find(text);
    if (it != last_logged_.end() && (now - it->second).toSec() < period_s_) return false;
    last_logged_[text] = now;
    return true;
  }

 private:
  const double period_s_;
  std::mutex mutex_;
  std::map<std::string, ros::WallTime> last_logged_;
};

}  // namespace rle_vision

// A bounded wait for something that normally arrives right after start-up (camera_info after
// the first images): waiting() is true from its first call until `duration_s` later.
#pragma once

#include <algorithm>

namespace rle_vision {

class StartupWait {
 public:
  explicit StartupWait(double duration_s) : duration_s_(duration_s) {}
  bool waiting(double now_s) {
    if (start_s_ < 0) start_s_ = now_s;
    return now_s - start_s_ < duration_s_;
  }
  // Seconds left to wait (0 once over; the full duration before the first call).
  double remaining(double now_s) const {
    return start_s_ < 0 ? duration_s_ : std::max(0.0, duration_s_ - (now_s - start_s_));
  }

 private:
  double duration_s_;
  double start_s_ = -1;
};

}  // namespace rle_vision

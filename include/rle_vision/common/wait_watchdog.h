// Says when inputs have waited too long for something they need (e.g. blobs for the camera
// pose from tf): from the oldest input not handled since the last one that was, in wall time,
// however long a queue may hold them. A queue overflow says it only after the queue fills,
// seconds later at camera rate, and never for a short bag.
#pragma once

#include <mutex>

namespace rle_vision {

class WaitWatchdog {
 public:
  explicit WaitWatchdog(double limit_s) : limit_s_(limit_s) {}

  // An input arrived and waits.
  void received(double now_s) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (waiting_since_s_ < 0) waiting_since_s_ = now_s;
  }
  // An input was handled: nothing is stuck; the next input starts a new wait.
  void handled() {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting_since_s_ = -1;
  }
  // Seconds waited so far when that is at least the limit, else 0.
  double overdueS(double now_s) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const double waited = waiting_since_s_ < 0 ? 0.0 : now_s - waiting_since_s_;
    return waited >= limit_s_ ? waited : 0.0;
  }

 private:
  const double limit_s_;
  mutable std::mutex mutex_;
  double waiting_since_s_ = -1;
};

}  // namespace rle_vision

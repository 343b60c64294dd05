// A one-slot "latest item" mailbox between a producer that must never wait (a camera-rate
// callback) and a slower consumer thread: a new item replaces one not yet taken, which counts
// as dropped. The consumer always gets the newest item and never a queue of stale ones.
#pragma once

#include <condition_variable>
#include <mutex>
#include <optional>
#include <utility>

namespace rle_vision {

template <typename T>
class LatestMailbox {
 public:
  // Leaves `item` for the consumer. Returns true when it replaced an item nobody took.
  bool put(T item) {
    bool replaced;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      replaced = slot_.has_value();
      slot_ = std::move(item);
    }
    ready_.notify_one();
    return replaced;
  }

  // Waits for an item and takes it; false once close() was called.
  bool take(T* item) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return closed_ || slot_.has_value(); });
    if (closed_) return false;
    *item = std::move(*slot_);
    slot_.reset();
    return true;
  }

  // Wakes the consumer for good (take() returns false from now on).
  void close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }

  bool empty() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !slot_.has_value();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<T> slot_;
  bool closed_ = false;
};

}  // namespace rle_vision

// A callback queue that runs each callback at once, in the thread that delivers the message:
// the camera driver's publish when it shares the nodelet manager (zero-copy hand-over), else
// roscpp's receive thread. A frame then waits for no thread to wake up. The tracker uses it at
// normal priority, where a thread of its own only adds a wake-up that the scheduler may delay
// by milliseconds when both cores are busy; with SCHED_FIFO its own thread wins instead.
// A callback that cannot run now (its subscription is busy in another thread) goes to
// `fallback`, which a thread serves.
#pragma once

#include <ros/callback_queue.h>
#include <ros/callback_queue_interface.h>

namespace rle_vision {

class InlineCallbackQueue : public ros::CallbackQueueInterface {
 public:
  explicit InlineCallbackQueue(ros::CallbackQueue* fallback) : fallback_(fallback) {}

  void addCallback(const ros::CallbackInterfacePtr& callback, uint64_t owner_id) override {
    if (callback->ready() && callback->call() != ros::CallbackInterface::TryAgain) return;
    fallback_->addCallback(callback, owner_id);
  }
  void removeByID(uint64_t owner_id) override { fallback_->removeByID(owner_id); }

 private:
  ros::CallbackQueue* const fallback_;
};

}  // namespace rle_vision

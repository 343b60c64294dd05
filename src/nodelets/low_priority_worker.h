// A thread that takes the newest image from a one-slot mailbox and processes it at low
// priority (nice 19, and SCHED_IDLE where the kernel allows it), so work that may lag (edges,
// landmarks) never takes a core from the real-time tracker in the same nodelet manager. A new
// image replaces one not yet taken, which counts as dropped.
#pragma once

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <exception>
#include <functional>
#include <string>
#include <thread>

#include <sensor_msgs/Image.h>

#include "rle_vision/common/latest_mailbox.h"

namespace rle_vision {

class LowPriorityWorker {
 public:
  using Process = std::function<void(const sensor_msgs::ImageConstPtr&)>;
  // `started(niced, idled)` runs on the worker thread once its priority is set.
  using Started = std::function<void(bool niced, bool idled)>;
  // `failed(what)` gets an exception `process` threw: one bad frame must not end the thread
  // (an exception escaping it would terminate the whole nodelet manager, tracker included).
  using Failed = std::function<void(const char* what)>;

  void start(bool low_priority, Process process, Started started, Failed failed) {
    thread_ = std::thread([this, low_priority, process, started, failed] {
      bool niced = false, idled = false;
      if (low_priority) {
        niced = setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19) == 0;
        sched_param idle{};
        idled = pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle) == 0;
      }
      started(niced, idled);
      sensor_msgs::ImageConstPtr msg;
      while (mailbox_.take(&msg)) {
        try {
          process(msg);
        } catch (const std::exception& e) {
          failed(e.what());
        }
      }
    });
  }

  // Hands over the newest image; true when it replaced one the worker had not taken.
  bool put(const sensor_msgs::ImageConstPtr& msg) { return mailbox_.put(msg); }

  void stop() {
    mailbox_.close();
    if (thread_.joinable()) thread_.join();
  }

  ~LowPriorityWorker() { stop(); }

 private:
  LatestMailbox<sensor_msgs::ImageConstPtr> mailbox_;
  std::thread thread_;
};

}  // namespace rle_vision

// Per-nodelet processing statistics for diagnostics: input rate, time per frame (mean and
// max, and the largest thread CPU time of a frame), frames dropped, CPU used. Thread-safe; each report covers the time since the previous
// one, except the totals.
#pragma once

#include <time.h>

#include <algorithm>
#include <chrono>
#include <mutex>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/time.h>

namespace rle_vision {

// CPU time of the calling thread (ms): what one callback really costs, whatever else the
// nodelet manager's process runs.
inline double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

// When a frame's processing started, by the wall clock and by the thread's CPU time.
struct FrameClock {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double cpu_start_ms = threadCpuMs();
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  double cpuMs() const { return threadCpuMs() - cpu_start_ms; }
};

class ProcessingStats {
 public:
  ProcessingStats() : started_(ros::WallTime::now()) {}

  // `cpu_ms`: thread CPU time the frame took (threadCpuMs() after minus before).
  void addFrame(double processing_ms, double cpu_ms = 0.0) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++frames_;
    sum_ms_ += processing_ms;
    max_ms_ = std::max(max_ms_, processing_ms);
    max_cpu_ms_ = std::max(max_cpu_ms_, cpu_ms);
    cpu_ms_total_ += cpu_ms;
  }
  void addDrop() {
    std::lock_guard<std::mutex> lock(mutex_);
    ++dropped_;
    ++dropped_total_;
  }

  // Fills `status`; WARN when frames were dropped or the mean time exceeds warn_ms.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status, double warn_ms) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::WallTime now = ros::WallTime::now();
    const double seconds = last_report_.isZero() ? 0.0 : (now - last_report_).toSec();
    last_report_ = now;
    const double mean_ms = frames_ ? sum_ms_ / frames_ : 0.0;
    status.add("input rate (Hz)", seconds > 0 ? frames_ / seconds : 0.0);
    status.add("processing time mean (ms)", mean_ms);
    status.add("processing time max (ms)", max_ms_);
    // The nodelet's own work, without the time the machine ran something else instead.
    status.add("processing cpu time max (ms)", max_cpu_ms_);
    status.add("frames dropped (since last report)", dropped_);
    status.add("frames dropped (total)", dropped_total_);
    const double running_s = (now - started_).toSec();
    status.add("cpu load since start (% of one core)", running_s > 0 ? 100.0 * cpu_ms_total_ / 1e3 / running_s : 0.0);
    if (dropped_ > 0) {
      status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%d frames dropped (processing slower than input)", dropped_);
    } else if (mean_ms > warn_ms) {
      status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "mean processing time %.2f ms above %.2f ms", mean_ms, warn_ms);
    } else if (frames_ == 0) {
      status.summary(diagnostic_msgs::DiagnosticStatus::OK, "no input (subscribed lazily: nobody listens, or no images)");
    } else {
      status.summaryf(diagnostic_msgs::DiagnosticStatus::OK, "%.2f ms per frame", mean_ms);
    }
    frames_ = dropped_ = 0;
    sum_ms_ = max_ms_ = max_cpu_ms_ = 0;
  }

 private:
  std::mutex mutex_;
  int frames_ = 0, dropped_ = 0, dropped_total_ = 0;
  double sum_ms_ = 0, max_ms_ = 0, max_cpu_ms_ = 0;
  double cpu_ms_total_ = 0;
  ros::WallTime last_report_;
  const ros::WallTime started_;
};

}  // namespace rle_vision

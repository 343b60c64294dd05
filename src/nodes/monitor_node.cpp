// rle_vision_monitor: one summary line per second for `make demo`: frame rate, blobs per class,
// tracker time per frame, image-stamp-to-blobs latency, and (when the landmark node runs)
// lines per frame, the horizon's roll and pitch, the landmark time and how many colour classes
// have learned ranges (with the updates this second), and the obstacles placed on the ground
// (how many, the nearest). Exits after
// ~duration_s (> 0).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <vector>

#include <ros/ros.h>

#include "rle_vision/BlobArray.h"
#include "rle_vision/ColorRangeArray.h"
#include "rle_vision/Horizon.h"
#include "rle_vision/LineArray.h"
#include "rle_vision/ObstacleArray.h"

namespace rle_vision {

class Monitor {
 public:
  Monitor() {
    ros::NodeHandle nh, pnh("~");
    pnh.param("duration_s", duration_s_, 0.0);
    sub_blobs_ = nh.subscribe("blobs", 10, &Monitor::blobsCb, this);
    sub_lines_ = nh.subscribe("lines", 10, &Monitor::linesCb, this);
    sub_horizon_ = nh.subscribe("horizon", 10, &Monitor::horizonCb, this);
    sub_ranges_ = nh.subscribe("color_ranges", 10, &Monitor::rangesCb, this);
    sub_obstacles_ = nh.subscribe("obstacles", 10, &Monitor::obstaclesCb, this);
    start_ = ros::WallTime::now();
    timer_ = nh.createWallTimer(ros::WallDuration(1.0), &Monitor::report, this);
  }

 private:
  void blobsCb(const BlobArrayConstPtr& msg) {
    const double latency_ms = (ros::Time::now() - msg->header.stamp).toSec() * 1e3;
    std::lock_guard<std::mutex> lock(mutex_);
    ++frames_;
    tracker_ms_sum_ += msg->processing_time_ms;
    tracker_ms_max_ = std::max(tracker_ms_max_, static_cast<double>(msg->processing_time_ms));
    latencies_ms_.push_back(latency_ms);
    last_counts_.clear();
    for (const Blob& b : msg->blobs) ++last_counts_[b.color];
  }

  void linesCb(const LineArrayConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++landmark_frames_;
    lines_ += msg->lines.size();
    landmark_ms_sum_ += msg->processing_time_ms;
  }

  void horizonCb(const HorizonConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++horizon_frames_;
    if (!msg->found) return;
    ++horizon_found_;
    // Min and max over the second: the gait sways at about 1 Hz, a single sample would alias.
    const double roll = msg->roll * 180.0 / M_PI, pitch = msg->pitch * 180.0 / M_PI;
    roll_deg_[0] = std::min(roll_deg_[0], roll);
    roll_deg_[1] = std::max(roll_deg_[1], roll);
    if (std::isfinite(pitch)) {
      pitch_deg_[0] = std::min(pitch_deg_[0], pitch);
      pitch_deg_[1] = std::max(pitch_deg_[1], pitch);
    }
  }

  void rangesCb(const ColorRangeArrayConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++range_updates_;
    classes_ = static_cast<int>(msg->ranges.size());
    learned_classes_ = static_cast<int>(
        std::count_if(msg->ranges.begin(), msg->ranges.end(), [](const ColorRange& r) { return r.source == "learned"; }));
  }

  void obstaclesCb(const ObstacleArrayConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++obstacle_frames_;
    obstacles_ = static_cast<int>(msg->obstacles.size());
    nearest_ = nullptr;
    last_obstacles_ = msg;
    for (const Obstacle& o : msg->obstacles) {
      if (!nearest_ || o.range_m < nearest_->range_m) nearest_ = &o;
    }
  }

  static double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(p * v.size()));
    std::nth_element(v.begin(), v.begin() + i, v.end());
    return v[i];
  }

  void report(const ros::WallTimerEvent&) {
    const double elapsed = (ros::WallTime::now() - start_).toSec();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::printf("[rle_vision] t=%3.0fs %5.1f fps | blobs:", elapsed, frames_ / 1.0);
      if (last_counts_.empty()) std::printf(" none");
      for (const auto& entry : last_counts_) std::printf(" %s %d", entry.first.c_str(), entry.second);
      if (frames_ > 0) {
        std::printf(" | tracker %.2f ms/frame (max %.2f) | stamp->blobs p50 %.2f ms p99 %.2f ms",
                    tracker_ms_sum_ / frames_, tracker_ms_max_, percentile(latencies_ms_, 0.5),
                    percentile(latencies_ms_, 0.99));
      } else {
        std::printf(" | waiting for %s", sub_blobs_.getTopic().c_str());
      }
      if (landmark_frames_ > 0) {
        std::printf(" | %.1f lines/frame, landmark %.2f ms", static_cast<double>(lines_) / landmark_frames_,
                    landmark_ms_sum_ / landmark_frames_);
      }
      if (horizon_frames_ > 0) {
        std::printf(" | horizon %d%%", 100 * horizon_found_ / horizon_frames_);
        if (horizon_found_ > 0) std::printf(" roll %+.1f..%+.1f", roll_deg_[0], roll_deg_[1]);
        if (pitch_deg_[0] <= pitch_deg_[1]) std::printf(" pitch %+.1f..%+.1f", pitch_deg_[0], pitch_deg_[1]);
        if (horizon_found_ > 0) std::printf(" deg");
      }
      if (classes_ > 0) std::printf(" | ranges learned %d/%d (%d updates)", learned_classes_, classes_, range_updates_);
      if (obstacle_frames_ > 0) {
        std::printf(" | %d obstacles", obstacles_);
        if (nearest_) std::printf(", nearest %s %.2f m at %+.0f deg", nearest_->color.c_str(), nearest_->range_m,
                                  nearest_->bearing_rad * 180 / M_PI);
      }
      std::printf("\n");
      std::fflush(stdout);
      range_updates_ = 0;
      obstacle_frames_ = 0;
      frames_ = 0;
      tracker_ms_sum_ = tracker_ms_max_ = 0;
      landmark_frames_ = horizon_frames_ = horizon_found_ = 0;
      lines_ = 0;
      landmark_ms_sum_ = 0;
      roll_deg_[0] = pitch_deg_[0] = INFINITY;
      roll_deg_[1] = pitch_deg_[1] = -INFINITY;
      latencies_ms_.clear();
    }
    if (duration_s_ > 0 && elapsed >= duration_s_ - 0.05) {
      std::printf("[rle_vision] demo ran %.0f s, stopping (roslaunch then reports that the required "
                  "monitor finished: expected)\n", elapsed);
      std::fflush(stdout);
      ros::shutdown();
    }
  }

  ros::Subscriber sub_blobs_, sub_lines_, sub_horizon_, sub_ranges_, sub_obstacles_;
  ros::WallTimer timer_;
  ros::WallTime start_;
  double duration_s_ = 0;
  std::mutex mutex_;
  int frames_ = 0;
  double tracker_ms_sum_ = 0, tracker_ms_max_ = 0;
  std::vector<double> latencies_ms_;
  std::map<std::string, int> last_counts_;
  int landmark_frames_ = 0, horizon_frames_ = 0, horizon_found_ = 0;
  size_t lines_ = 0;
  double landmark_ms_sum_ = 0;
  double roll_deg_[2] = {INFINITY, -INFINITY}, pitch_deg_[2] = {INFINITY, -INFINITY};  // min, max
  int range_updates_ = 0, classes_ = 0, learned_classes_ = 0;
  int obstacle_frames_ = 0, obstacles_ = 0;
  ObstacleArrayConstPtr last_obstacles_;  // owns what nearest_ points into
  const Obstacle* nearest_ = nullptr;
};

}  // namespace rle_vision

int main(int argc, char** argv) {
  ros::init(argc, argv, "rle_vision_monitor");
  rle_vision::Monitor monitor;
  ros::spin();
  return 0;
}

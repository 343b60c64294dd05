// The Landmark node's colour-learning loop without ROS: per processed frame, the learner
// measures the objects the lines bound; changed class sets go out at most once per publish
// period; a restarted node resumes from the ranges the tracker still uses; switching learning
// off hands the tracker its configured ranges back, once.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/color/color_class.h"
#include "rle_vision/learning/color_learning.h"

namespace rle_vision {

// The parameters (enabled: the ROS parameter `learning`, publish_period_s) are the
// LEARNING_LOOP group of landmark_params.def, with their defaults and meanings.
struct LearningLoopOptions {
#define RLE_LEARNING_LOOP_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/landmark_params.def"
};

// Reason the options are unusable (NaN, out of range), or "" when they are fine.
std::string validateLearningLoopOptions(const LearningLoopOptions& options);

class ColorLearningLoop {
 public:
  explicit ColorLearningLoop(std::vector<ColorClass> configured);

  // What a frame asks the node to do.
  struct Step {
    bool publish = false;            // send `classes` on color_ranges now
    std::vector<ColorClass> classes;  // the whole set (learned ranges say source "learned")
    int resumed = 0;                 // classes taken over from offerResume() in this step
  };

  // Ranges learned before (a restarted node: the tracker's active set). Taken by the next
  // learn() if nothing was published yet. May be called from any thread.
  void offerResume(std::vector<ColorClass> learned);

  // One frame with learning on: `bgr` and the landmark result computed on it (see
  // ColorLearner::update). `stamp_s` is the image time, `now_s` a clock for the publish period.
  Step learn(const cv::Mat& bgr, const LandmarkResult& landmarks, const EdgeObjectFinder& objects, double stamp_s,
             double now_s, const LearningOptions& learning, double publish_period_s);

  // Learning is off: the configured set to hand back once, if learned ranges went out before;
  // learning starts over from the configured ranges.
  Step stop(const LearningOptions& learning);

  const ColorLearner& learner() const { return *learner_; }

 private:
  std::vector<ColorClass> configured_;
  std::unique_ptr<ColorLearner> learner_;
  bool published_learned_ = false;  // the tracker holds learned ranges from us
  bool changes_pending_ = false;    // changed ranges not yet published
  bool published_once_ = false;
  double last_publish_s_ = 0;
  std::mutex resume_mutex_;
  std::unique_ptr<std::vector<ColorClass>> pending_resume_;
};

}  // namespace rle_vision

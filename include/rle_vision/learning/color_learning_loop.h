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

  // The floor's colour as the field stage follows it (options field_class): from the next
  // learn(), the published set holds it as class kFieldClassName (in place of a configured
  // class of that name, whose look and min_area_px it keeps; else with min_area_px 0.5% of the
  // image; left out when the set is full). A move of a level or more on any bound is a change
  // to publish; a move of over a third of the published range's half width on a channel (the
  // tracker's copy is losing the floor's outer pixels: fast light changes) goes out at once,
  // without waiting for the publish period. nullptr: no field class (a configured one stays;
  // a field class published before is taken out with the next set, which goes out for it).
  void setFieldColour(const ColorClass* field);

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
  std::vector<ColorClass> withField(std::vector<ColorClass> classes) const;

  bool has_field_ = false;
  bool field_urgent_ = false;    // the field moved too far for the publish period to wait
  size_t image_area_px_ = 0;     // of the last frame learned from
  ColorClass field_;             // the field class to publish (has_field_)
  ColorClass published_field_;   // ... as it went out last (name empty: not published)
  std::mutex resume_mutex_;
  std::unique_ptr<std::vector<ColorClass>> pending_resume_;
};

}  // namespace rle_vision

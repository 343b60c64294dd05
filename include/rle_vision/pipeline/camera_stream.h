// One camera stream through the pipeline's core, frame after frame, as the nodelets run it
// without ROS: the Tracker's ColorTracker with the current colour table, the
// Landmark's LandmarkDetector (on the 5x5 Sobel the EdgeDetector computes), the field stage
// (FieldDetector: field colour and boundary) and its ColorLearningLoop; blobs of classes
// with a verifier are screened by it (CandidateScreen), as the Tracker does; ranges the loop publishes replace the table from the next frame on, as
// color_ranges does in the pipeline. Used by rle_vision_detect --sequence and make eval.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/field/field_detector.h"
#include "rle_vision/learning/color_learning_loop.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/tracking/color_tracker.h"
#include "rle_vision/landmark/landmark_detector.h"
#include "rle_vision/verify/candidate_screen.h"

namespace rle_vision {

struct CameraStreamOptions {
  LandmarkOptions landmark;
  LearningOptions learning;
  LearningLoopOptions loop;  // loop.enabled: learn (false: the configured ranges throughout)
  FieldOptions field;
  uint32_t verifier_max_candidates_per_frame = 50;  // as the Tracker's setting of that name
};

class CameraStream {
 public:
  // Throws std::invalid_argument for unusable classes, std::runtime_error for a class's
  // verifier_file that cannot be read. Classes with a verifier have their blobs screened.
  CameraStream(const std::vector<ColorClass>& classes, const CameraStreamOptions& options);

  struct Frame {
    std::vector<TrackedBlob> blobs;
    ScreeningCounts screening;  // the verifier's work on this frame's blobs
    LandmarkResult landmarks;
    FieldResult field;
    std::shared_ptr<const ColorTable> table;  // the ranges the blobs were found with
    std::string ignored_ranges;  // why learned ranges could not be used ("" when they could)
  };
  // One BGR frame (CV_8UC3) at `stamp_s` (the clock of tracking and of the publish period).
  // Throws std::invalid_argument for an unusable image.
  void process(const cv::Mat& bgr, double stamp_s, Frame* frame);

 private:
  std::shared_ptr<const ColorTable> table_;
  CameraStreamOptions options_;
  ColorLearningLoop loop_;
  ColorTracker tracker_;
  CandidateScreen screen_;
  LandmarkDetector detector_;
  FieldDetector field_;
};

}  // namespace rle_vision

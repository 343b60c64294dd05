// make eval (balls): how blobs of a ball class score against labelled ball boxes, and the
// methods compared on one frame (ours, ours on the field side only, OpenCV's inRange
// pipeline). Shared by rle_vision_eval_balls (one folder calibrates) and
// rle_vision_eval_balls_by_date (each date calibrates in turn).
//
// A ball counts as found when a blob of the class (area >= 20 px) has its centroid inside the
// ball's labelled box; blob precision is the share of such blobs whose centroid lies inside
// some ball box. Balls on the field side (their box's bottom centre at most the tracker's
// margin above the frame's field boundary) are counted apart: a ball in a spectator's hands or
// in the stands is not one a robot plays.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "eval/opencv_pipeline.h"
#include "rle_vision/color/color_table.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/segment/segmenter.h"

namespace rle_vision {
namespace bench {

constexpr uint32_t kMinBallBlobArea = 20;
constexpr double kOnFieldMarginPx = 10;  // the tracker's on_field_margin_px default

struct BallScore {
  int frames = 0, balls = 0, found = 0, blobs = 0, on_ball = 0;
  int field_balls = 0, field_found = 0;  // balls on the field side, and those found
  double ms = 0;
  void add(const BallScore& o) {
    frames += o.frames, balls += o.balls, found += o.found, blobs += o.blobs, on_ball += o.on_ball, ms += o.ms;
    field_balls += o.field_balls, field_found += o.field_found;
  }
  double recall() const { return balls ? 100.0 * found / balls : 0; }
  double fieldRecall() const { return field_balls ? 100.0 * field_found / field_balls : 0; }
  double precision() const { return blobs ? 100.0 * on_ball / blobs : 100; }
  double msPerFrame() const { return frames ? ms / frames : 0; }
};

// A frame's labelled balls and, per ball, whether it lies on the field side.
struct BallTruth {
  std::vector<cv::Rect> balls;
  std::vector<bool> on_field;
};

// The balls of a frame against its field boundary (none found: every ball counts as on it).
BallTruth ballTruth(std::vector<cv::Rect> balls, const FieldBoundaryEstimate& boundary);

void scoreBlobs(const std::vector<cv::Point2d>& blobs, const BallTruth& truth, double ms, BallScore* s);

inline double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The methods on one frame.
class BallMethods {
 public:
  explicit BallMethods(const ColorClass& ball) : table_({ball}), opencv_({ball}) {}

  // Ours, and (`on_field`) the same blobs less those whose lowest point (below the centroid)
  // lies more than the margin above `field`'s boundary (its time counted too).
  void ours(const cv::Mat& bgr, const BallTruth& truth, const FieldResult& field, BallScore* s, BallScore* on_field);
  void opencv(const cv::Mat& bgr, const BallTruth& truth, BallScore* s);

 private:
  ColorTable table_;
  Segmenter segmenter_;
  std::vector<Region> regions_;
  OpenCvPipeline opencv_;  // cvtColor + inRange + connectedComponentsWithStats, 8-connected
  std::vector<OpenCvBlob> opencv_blobs_;
};

std::string ballScoreJson(const BallScore& s);
// The score's figures as make eval's flat JSON values, under `key` ("KEY.balls", ...).
void addBallScoreValues(const std::string& key, const BallScore& s, std::vector<std::pair<std::string, double>>* values);

// A data set's recording date (one hall and its light): its name and every image below it.
struct LabelledDate {
  std::string name;
  std::vector<std::string> images;
};
// The folders of `root`, each a date, in name order (none when `root` is not a folder).
std::vector<LabelledDate> labelledDates(const std::string& root);
// The ball class calibrated (rle_vision_calibrate's core) on every labelled ball of `dates`.
// Throws std::runtime_error when they hold none.
ColorClass calibrateBall(const std::vector<const LabelledDate*>& dates, int label_class);

}  // namespace bench
}  // namespace rle_vision

#include "ball_scoring.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "rle_vision/io/yolo_labels.h"
#include "rle_vision/learning/color_calibration.h"

namespace rle_vision {
namespace bench {
namespace {

bool inside(const cv::Point2d& p, const cv::Rect& box) {
  return p.x >= box.x && p.x <= box.br().x - 1 && p.y >= box.y && p.y <= box.br().y - 1;
}

}  // namespace

BallTruth ballTruth(std::vector<cv::Rect> balls, const FieldBoundaryEstimate& boundary) {
  BallTruth truth;
  truth.balls = std::move(balls);
  for (const cv::Rect& b : truth.balls) {
    const double x = b.x + 0.5 * b.width, y = b.y + b.height - 0.5;
    truth.on_field.push_back(!boundary.found || boundary.heightAbove(x, y) <= kOnFieldMarginPx);
  }
  return truth;
}

void scoreBlobs(const std::vector<cv::Point2d>& blobs, const BallTruth& truth, double ms, BallScore* s) {
  ++s->frames;
  s->ms += ms;
  s->balls += static_cast<int>(truth.balls.size());
  s->blobs += static_cast<int>(blobs.size());
  for (size_t i = 0; i < truth.balls.size(); ++i) {
    bool found = false;
    for (const cv::Point2d& b : blobs) found = found || inside(b, truth.balls[i]);
    s->found += found;
    s->field_balls += truth.on_field[i];
    s->field_found += truth.on_field[i] && found;
  }
  for (const cv::Point2d& b : blobs) {
    bool on_ball = false;
    for (const cv::Rect& ball : truth.balls) on_ball = on_ball || inside(b, ball);
    s->on_ball += on_ball;
  }
}

void BallMethods::ours(const cv::Mat& bgr, const BallTruth& truth, const FieldResult& field, BallScore* s,
                       BallScore* on_field) {
  const auto start = std::chrono::steady_clock::now();
  segmenter_.segment(bgr, PixelFormat::BGR8, table_, &regions_);
  const double ms = msSince(start);
  std::vector<cv::Point2d> blobs, kept;
  for (const Region& r : regions_) {
    if (r.area < kMinBallBlobArea) continue;
    blobs.emplace_back(r.cx, r.cy);
    if (!field.boundary.found || field.boundary.heightAbove(r.cx, r.bottom_at_cx) <= kOnFieldMarginPx) {
      kept.emplace_back(r.cx, r.cy);
    }
  }
  scoreBlobs(blobs, truth, ms, s);
  scoreBlobs(kept, truth, ms + field.ms, on_field);
}

void BallMethods::opencv(const cv::Mat& bgr, const BallTruth& truth, BallScore* s) {
  const auto start = std::chrono::steady_clock::now();
  opencv_.run(bgr, &opencv_blobs_);
  const double ms = msSince(start);
  std::vector<cv::Point2d> blobs;
  for (const OpenCvBlob& b : opencv_blobs_) {
    if (b.area >= static_cast<int>(kMinBallBlobArea)) blobs.emplace_back(b.cx, b.cy);
  }
  scoreBlobs(blobs, truth, ms, s);
}

std::string ballScoreJson(const BallScore& s) {
  std::ostringstream out;
  out << "{\"frames\": " << s.frames << ", \"balls\": " << s.balls << ", \"found\": " << s.found
      << ", \"recall_pct\": " << s.recall() << ", \"balls_on_field\": " << s.field_balls
      << ", \"found_on_field\": " << s.field_found << ", \"recall_on_field_pct\": " << s.fieldRecall()
      << ", \"blobs\": " << s.blobs << ", \"blobs_on_ball\": " << s.on_ball << ", \"precision_pct\": " << s.precision()
      << ", \"ms_per_frame\": " << s.msPerFrame() << "}";
  return out.str();
}

void addBallScoreValues(const std::string& key, const BallScore& s, std::vector<std::pair<std::string, double>>* values) {
  values->emplace_back(key + ".balls", s.balls);
  values->emplace_back(key + ".recall_pct", s.recall());
  values->emplace_back(key + ".recall_on_field_pct", s.fieldRecall());
  values->emplace_back(key + ".blobs", s.blobs);
  values->emplace_back(key + ".precision_pct", s.precision());
}

std::vector<LabelledDate> labelledDates(const std::string& root) {
  std::vector<LabelledDate> dates;
  if (root.empty() || !std::filesystem::is_directory(root)) return dates;
  for (const auto& entry : std::filesystem::directory_iterator(root)) {
    if (entry.is_directory()) dates.push_back({entry.path().filename().string(), imagesUnderFolder(entry.path().string())});
  }
  std::sort(dates.begin(), dates.end(), [](const LabelledDate& a, const LabelledDate& b) { return a.name < b.name; });
  return dates;
}

ColorClass calibrateBall(const std::vector<const LabelledDate*>& dates, int label_class) {
  std::vector<CalibrationExample> examples;
  std::string names;
  for (const LabelledDate* d : dates) {
    names += (names.empty() ? "" : ", ") + d->name;
    for (const std::string& path : d->images) {
      CalibrationExample e = readYoloExample(path, label_class);
      if (!e.boxes.empty()) examples.push_back(std::move(e));
    }
  }
  if (examples.empty()) throw std::runtime_error(names + ": no labelled balls to calibrate from");
  return calibrateColorClass(examples, "ball").color_class;
}

}  // namespace bench
}  // namespace rle_vision

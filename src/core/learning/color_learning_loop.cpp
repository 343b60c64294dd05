#include "rle_vision/learning/color_learning_loop.h"

#include <algorithm>
#include <cstdlib>

#include "rle_vision/landmark/param_range.h"

namespace rle_vision {

std::string validateLearningLoopOptions(const LearningLoopOptions& o) {
  std::string problem;
#define RLE_LEARNING_LOOP_PARAM(key, member, type, default_value, min, max, description) \
  if (problem.empty()) problem = outOfRange(#key, o.member, min, max);
#include "rle_vision/params/landmark_params.def"
  return problem;
}

ColorLearningLoop::ColorLearningLoop(std::vector<ColorClass> configured)
    : configured_(std::move(configured)), learner_(std::make_unique<ColorLearner>(configured_, LearningOptions())) {}

void ColorLearningLoop::offerResume(std::vector<ColorClass> learned) {
  std::lock_guard<std::mutex> lock(resume_mutex_);
  pending_resume_ = std::make_unique<std::vector<ColorClass>>(std::move(learned));
}

ColorLearningLoop::Step ColorLearningLoop::learn(const cv::Mat& bgr, const LandmarkResult& landmarks,
                                                 const EdgeObjectFinder& objects, double stamp_s, double now_s,
                                                 const LearningOptions& learning, double publish_period_s) {
  Step step;
  learner_->setOptions(learning);
  std::unique_ptr<std::vector<ColorClass>> resume;
  {
    std::lock_guard<std::mutex> lock(resume_mutex_);
    resume.swap(pending_resume_);
  }
  if (resume && !published_learned_) {
    step.resumed = learner_->resume(*resume, stamp_s);
    published_learned_ = step.resumed > 0;
  }
  image_area_px_ = bgr.total();
  changes_pending_ = learner_->update(bgr, landmarks, objects, stamp_s) || changes_pending_;
  if (changes_pending_ && (!published_once_ || field_urgent_ || now_s - last_publish_s_ >= publish_period_s)) {
    step.publish = true;
    step.classes = withField(learner_->classes());
    const bool field_sent = std::any_of(step.classes.begin(), step.classes.end(),
                                        [](const ColorClass& c) { return c.name == kFieldClassName; });
    published_field_ = has_field_ && field_sent ? field_ : ColorClass();  // a full set leaves it out
    field_urgent_ = false;
    last_publish_s_ = now_s;
    published_once_ = published_learned_ = true;
    changes_pending_ = false;
  }
  return step;
}

void ColorLearningLoop::setFieldColour(const ColorClass* field) {
  has_field_ = field != nullptr;
  if (!has_field_) {
    // Switched off: the next set goes out without it (once).
    changes_pending_ = changes_pending_ || !published_field_.name.empty();
    return;
  }
  field_ = *field;
  field_.name = kFieldClassName;
  field_.source = "learned";
  const bool first = published_field_.name.empty();
  bool moved = first;
  for (int c = 0; c < 3; ++c) {
    const int shift_min = std::abs(field_.min[c] - published_field_.min[c]);
    const int shift_max = std::abs(field_.max[c] - published_field_.max[c]);
    moved = moved || shift_min > 0 || shift_max > 0;
    // The tracker's copy is losing the floor's outer pixels: a bound moved by over a third of
    // the published half width (the floor's spread) goes out without waiting for the period.
    const double half_width = 0.5 * (published_field_.max[c] - published_field_.min[c]);
    field_urgent_ = field_urgent_ || (!first && std::max(shift_min, shift_max) > half_width / 3.0);
  }
  changes_pending_ = changes_pending_ || moved;
}

std::vector<ColorClass> ColorLearningLoop::withField(std::vector<ColorClass> classes) const {
  if (!has_field_) return classes;
  for (ColorClass& c : classes) {
    if (c.name == kFieldClassName) {
      // The configured class's look and size limit, the followed range.
      const ColorClass configured = c;
      c = field_;
      c.display_rgb = configured.display_rgb;
      c.min_area_px = configured.min_area_px;
      return classes;
    }
  }
  if (static_cast<int>(classes.size()) >= kMaxColorClasses) return classes;
  // Before the first class with a verifier (its range is permissive: without the floor taking
  // its own pixels first, a candidate could run over the floor and swallow what lies on it, and
  // the verifier was trained on candidates made that way), else last.
  const auto at = std::find_if(classes.begin(), classes.end(), [](const ColorClass& c) { return !c.verifier_file.empty(); });
  ColorClass& field = *classes.insert(at, field_);
  // Floor patches under 0.5% of the view are specks of the floor's colour elsewhere, not the
  // floor: the tracker need not track them.
  field.min_area_px = std::max<uint32_t>(1, static_cast<uint32_t>(0.005 * image_area_px_));
  return classes;
}

ColorLearningLoop::Step ColorLearningLoop::stop(const LearningOptions& learning) {
  Step step;
  if (!published_learned_) return step;
  learner_ = std::make_unique<ColorLearner>(configured_, learning);
  step.publish = true;
  step.classes = configured_;
  published_learned_ = changes_pending_ = false;
  published_field_ = ColorClass();
  field_urgent_ = false;
  return step;
}

}  // namespace rle_vision

#include "rle_vision/learning/color_learning_loop.h"

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
  changes_pending_ = learner_->update(bgr, landmarks, objects, stamp_s) || changes_pending_;
  if (changes_pending_ && (!published_once_ || now_s - last_publish_s_ >= publish_period_s)) {
    step.publish = true;
    step.classes = learner_->classes();
    last_publish_s_ = now_s;
    published_once_ = published_learned_ = true;
    changes_pending_ = false;
  }
  return step;
}

ColorLearningLoop::Step ColorLearningLoop::stop(const LearningOptions& learning) {
  Step step;
  if (!published_learned_) return step;
  learner_ = std::make_unique<ColorLearner>(configured_, learning);
  step.publish = true;
  step.classes = configured_;
  published_learned_ = changes_pending_ = false;
  return step;
}

}  // namespace rle_vision

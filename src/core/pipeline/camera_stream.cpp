#include "rle_vision/pipeline/camera_stream.h"

#include <stdexcept>

namespace rle_vision {

CameraStream::CameraStream(const std::vector<ColorClass>& classes, const CameraStreamOptions& options)
    : options_(options), loop_(classes),
      screen_(loadClassVerifiers(classes), options.verifier_max_candidates_per_frame), field_(options.field) {
  table_ = std::make_shared<const ColorTable>(withFloorGuard(classes, screen_.verifiers()));
  for (const ColorClass& c : classes) {
    if (c.name == kFieldClassName) field_.setConfiguredColour(c);  // the floor's colour seeds from it
  }
}

void CameraStream::process(const cv::Mat& bgr, double stamp_s, Frame* frame) {
  frame->table = table_;
  frame->ignored_ranges.clear();
  tracker_.process(bgr, PixelFormat::BGR8, *table_, stamp_s, &frame->blobs);
  frame->screening = screen_.apply(bgr, *table_, &frame->blobs);
  detector_.detectInImage(bgr, options_.landmark, &frame->landmarks);
  field_.detect(bgr, &frame->field);
  // As the Landmark node does: the floor's colour goes out with the learned ranges.
  if (!options_.loop.field_class) loop_.setFieldColour(nullptr);
  if (options_.loop.field_class && frame->field.colour.found) loop_.setFieldColour(&frame->field.colour.range);
  const ColorLearningLoop::Step step =
      options_.loop.enabled ? loop_.learn(bgr, frame->landmarks, detector_.edgeObjects(), stamp_s, stamp_s,
                                          options_.learning, options_.loop.publish_period_s)
                            : loop_.stop(options_.learning);
  if (!step.publish) return;
  // As the tracker does with color_ranges: a set it cannot use is reported, the table kept.
  try {
    table_ = std::make_shared<const ColorTable>(withFloorGuard(step.classes, screen_.verifiers()));
  } catch (const std::invalid_argument& e) {
    frame->ignored_ranges = e.what();
  }
}

}  // namespace rle_vision

#include "landmark_conversions.h"

#include <limits>

namespace rle_vision {

Line lineToMsg(const ImageLine& line, double x1, double y1, double x2, double y2, uint32_t votes, uint32_t support) {
  Line l;
  l.theta = static_cast<float>(line.theta);
  l.intercept = static_cast<float>(line.intercept);
  l.x1 = static_cast<float>(x1);
  l.y1 = static_cast<float>(y1);
  l.x2 = static_cast<float>(x2);
  l.y2 = static_cast<float>(y2);
  l.votes = votes;
  l.support = support;
  return l;
}

Line lineToMsg(const DetectedLine& l) { return lineToMsg(l.line, l.x1, l.y1, l.x2, l.y2, l.votes, l.support); }

Horizon horizonToMsg(const std_msgs::Header& header, const HorizonEstimate& h, double roll, double pitch) {
  Horizon msg;
  msg.header = header;
  msg.found = h.found;
  msg.roll = msg.pitch = std::numeric_limits<float>::quiet_NaN();
  msg.confidence = static_cast<float>(h.confidence);  // also the best candidate's when not found: for tuning
  if (!h.found) return msg;
  msg.line = lineToMsg(h.line, h.x1, h.y1, h.x2, h.y2, h.votes, h.support);
  msg.roll = static_cast<float>(roll);
  msg.pitch = static_cast<float>(pitch);
  return msg;
}

LandmarkOptions optionsFromConfig(const LandmarkConfig& c) {
  LandmarkOptions o;
#define RLE_OBJECTS_PARAM(key, member, type, default_value, min, max, description) o.objects.member = static_cast<type>(c.key);
#define RLE_HOUGH_PARAM(key, member, type, default_value, min, max, description) o.hough.member = static_cast<type>(c.key);
#define RLE_HORIZON_PARAM(key, member, type, default_value, min, max, description) o.horizon.member = static_cast<type>(c.key);
#include "rle_vision/params/landmark_params.def"
  return o;
}

LearningOptions learningFromConfig(const LandmarkConfig& c) {
  LearningOptions o;
#define RLE_LEARNING_PARAM(key, member, type, default_value, min, max, description) o.member = static_cast<type>(c.key);
#include "rle_vision/params/landmark_params.def"
  return o;
}

LearningLoopOptions learningLoopFromConfig(const LandmarkConfig& c) {
  LearningLoopOptions o;
#define RLE_LEARNING_LOOP_PARAM(key, member, type, default_value, min, max, description) o.member = static_cast<type>(c.key);
#include "rle_vision/params/landmark_params.def"
  return o;
}

FieldOptions fieldFromConfig(const LandmarkConfig& c) {
  FieldOptions o;
#define RLE_FIELD_COLOR_PARAM(key, member, type, default_value, min, max, description) o.colour.member = static_cast<type>(c.key);
#define RLE_FIELD_BOUNDARY_PARAM(key, member, type, default_value, min, max, description) o.boundary.member = static_cast<type>(c.key);
#include "rle_vision/params/landmark_params.def"
  return o;
}

}  // namespace rle_vision

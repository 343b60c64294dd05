#include "tracker_conversions.h"

#include <cmath>
#include <type_traits>

namespace rle_vision {

void optionsFromConfig(const TrackerConfig& c, SegmenterOptions* segmenter, TrackerOptions* tracker) {
#define RLE_SEGMENTER_PARAM(key, member, type, default_value, min, max, description) \
  segmenter->member = static_cast<type>(c.key);
#define RLE_TRACKER_PARAM(key, member, type, default_value, min, max, description) \
  tracker->member = static_cast<type>(c.key);
#define RLE_REGION_LIMITS_PARAM(key, member, type, default_value, min, max, description) \
  tracker->limits.member = static_cast<type>(c.key);
#include "rle_vision/params/tracker_params.def"
}

void configFromOptions(const SegmenterOptions& segmenter, const TrackerOptions& tracker, TrackerConfig* c) {
#define RLE_SEGMENTER_PARAM(key, member, type, default_value, min, max, description) \
  c->key = static_cast<decltype(c->key)>(segmenter.member);
#define RLE_TRACKER_PARAM(key, member, type, default_value, min, max, description) \
  c->key = static_cast<decltype(c->key)>(tracker.member);
#define RLE_REGION_LIMITS_PARAM(key, member, type, default_value, min, max, description) \
  c->key = static_cast<decltype(c->key)>(tracker.limits.member);
#include "rle_vision/params/tracker_params.def"
}

std::string nonFiniteTrackerParam(const TrackerConfig& c) {
#define RLE_CHECK_FINITE(key, member, type, default_value, min, max, description) \
  if (std::is_floating_point<type>::value && !std::isfinite(static_cast<double>(c.key))) return #key;
#define RLE_SEGMENTER_PARAM RLE_CHECK_FINITE
#define RLE_REGION_LIMITS_PARAM RLE_CHECK_FINITE
#define RLE_TRACKER_PARAM RLE_CHECK_FINITE
#include "rle_vision/params/tracker_params.def"
#undef RLE_CHECK_FINITE
  return "";
}

}  // namespace rle_vision

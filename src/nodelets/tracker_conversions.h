// The Tracker's dynamic parameters as core options and back, generated from its parameter
// table (include/rle_vision/params/tracker_params.def): a parameter added there arrives here.
#pragma once

#include <string>

#include "rle_vision/TrackerConfig.h"
#include "rle_vision/segment/segmenter.h"
#include "rle_vision/tracking/blob_tracker.h"

namespace rle_vision {

// The options `config` holds (the region limits inside `tracker`).
void optionsFromConfig(const TrackerConfig& config, SegmenterOptions* segmenter, TrackerOptions* tracker);

// `config` holding these options (what is in effect, shown in rqt_reconfigure).
void configFromOptions(const SegmenterOptions& segmenter, const TrackerOptions& tracker, TrackerConfig* config);

// The name of the first real-valued parameter that is not a finite number ("" when none is):
// NaN passes dynamic_reconfigure's clamping.
std::string nonFiniteTrackerParam(const TrackerConfig& config);

}  // namespace rle_vision

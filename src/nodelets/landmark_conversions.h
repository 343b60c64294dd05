// The landmark path's lines and horizon as messages, and its nodelets' parameters as core options.
#pragma once

#include "rle_vision/Horizon.h"
#include "rle_vision/LandmarkConfig.h"
#include "rle_vision/Line.h"
#include "rle_vision/field/field_detector.h"
#include "rle_vision/learning/color_learning.h"
#include "rle_vision/learning/color_learning_loop.h"
#include "rle_vision/landmark/detected_line.h"
#include "rle_vision/landmark/horizon_finder.h"
#include "rle_vision/landmark/landmark_detector.h"

namespace rle_vision {

Line lineToMsg(const ImageLine& line, double x1, double y1, double x2, double y2, uint32_t votes, uint32_t support);
Line lineToMsg(const DetectedLine& line);

// The horizon (roll and pitch as horizonAttitude gives them; NaN when not found).
Horizon horizonToMsg(const std_msgs::Header& header, const HorizonEstimate& horizon, double roll, double pitch);

// The Landmark nodelet's dynamic parameters as core options (landmark_params.def; edge_gain
// belongs to the EdgeDetector and keeps its default).
LandmarkOptions optionsFromConfig(const LandmarkConfig& config);
LearningOptions learningFromConfig(const LandmarkConfig& config);
LearningLoopOptions learningLoopFromConfig(const LandmarkConfig& config);
FieldOptions fieldFromConfig(const LandmarkConfig& config);

}  // namespace rle_vision

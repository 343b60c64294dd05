// The field boundary as a message and back (FieldBoundary.msg: image points, left to right).
#pragma once

#include "rle_vision/FieldBoundary.h"
#include "rle_vision/field/field_boundary.h"

namespace rle_vision {

FieldBoundary fieldBoundaryToMsg(const std_msgs::Header& header, const FieldBoundaryEstimate& boundary);

FieldBoundaryEstimate fieldBoundaryFromMsg(const FieldBoundary& msg);

}  // namespace rle_vision

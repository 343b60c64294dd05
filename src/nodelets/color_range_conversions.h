// rle_vision/ColorRange messages to and from the core's colour classes.
#pragma once

#include <string>
#include <vector>

#include "rle_vision/ColorRangeArray.h"
#include "rle_vision/color/color_class.h"

namespace rle_vision {

// Colour classes from a ColorRangeArray; false (with the reason) if any entry is invalid.
bool colorClassesFromMsg(const ColorRangeArray& msg, std::vector<ColorClass>* classes, std::string* error);
ColorRange colorRangeToMsg(const ColorClass& c);

// The whole class set as one message.
ColorRangeArrayPtr colorRangesMsg(const std_msgs::Header& header, const std::vector<ColorClass>& classes);

}  // namespace rle_vision

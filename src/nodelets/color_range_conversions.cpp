#include "color_range_conversions.h"

#include <algorithm>

#include <boost/make_shared.hpp>

namespace rle_vision {

bool colorClassesFromMsg(const ColorRangeArray& msg, std::vector<ColorClass>* classes, std::string* error) {
  classes->clear();
  for (const ColorRange& r : msg.ranges) {
    ColorClass c;
    c.name = r.name;
    if (!parseColorSpace(r.space, &c.space)) {
      *error = "colour range '" + r.name + "' has unknown space '" + r.space + "' (use YUV, RGB or HSV)";
      return false;
    }
    for (int ch = 0; ch < 3; ++ch) {
      c.min[ch] = r.min[ch];
      c.max[ch] = r.max[ch];
      c.display_rgb[ch] = r.display_rgb[ch];
    }
    c.min_area_px = std::max<uint32_t>(1, r.min_area);
    c.source = r.source.empty() ? "config" : r.source;
    classes->push_back(c);
  }
  *error = validateColorClasses(*classes);
  return error->empty();
}

ColorRange colorRangeToMsg(const ColorClass& c) {
  ColorRange r;
  r.name = c.name;
  r.space = toString(c.space);
  for (int ch = 0; ch < 3; ++ch) {
    r.min[ch] = c.min[ch];
    r.max[ch] = c.max[ch];
    r.display_rgb[ch] = c.display_rgb[ch];
  }
  r.min_area = c.min_area_px;
  r.source = c.source;
  return r;
}

ColorRangeArrayPtr colorRangesMsg(const std_msgs::Header& header, const std::vector<ColorClass>& classes) {
  auto msg = boost::make_shared<ColorRangeArray>();
  msg->header = header;
  for (const ColorClass& c : classes) msg->ranges.push_back(colorRangeToMsg(c));
  return msg;
}

}  // namespace rle_vision

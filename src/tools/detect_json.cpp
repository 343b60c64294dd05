#include "detect_json.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace rle_vision {
namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", v);
  return buffer;
}

void blobsJson(std::ostringstream& json, const std::vector<TrackedBlob>& blobs, const ColorTable& table,
               const FieldBoundaryEstimate& field) {
  for (size_t i = 0; i < blobs.size(); ++i) {
    const Region& r = blobs[i].region;
    // How far the blob's lowest point (below its centroid) lies above the field boundary.
    const double above = field.found ? field.heightAbove(r.cx, r.bottom_at_cx) : NAN;
    json << (i ? "," : "") << "{\"id\":" << blobs[i].id << ",\"color\":" << jsonString(table.classes()[r.label - 1].name)
         << ",\"area\":" << r.area << ",\"cx\":" << number(r.cx) << ",\"cy\":" << number(r.cy) << ",\"left\":" << r.left
         << ",\"top\":" << r.top << ",\"right\":" << r.right << ",\"bottom\":" << r.bottom << ",\"bottom_at_cx\":" << r.bottom_at_cx
         << ",\"angle\":" << number(r.angle) << ",\"above_field_px\":" << number(above)
         << ",\"score\":" << number(blobs[i].score) << "}";
  }
}

void fieldJson(std::ostringstream& json, const FieldResult& field) {
  const FieldBoundaryEstimate& b = field.boundary;
  json << "{\"found\":" << (b.found ? "true" : "false") << ",\"confidence\":" << number(b.confidence) << ",\"points\":[";
  for (size_t i = 0; i < b.polyline.size(); ++i) {
    json << (i ? "," : "") << "[" << number(b.polyline[i].x) << "," << number(b.polyline[i].y) << "]";
  }
  json << "]}";
}

void linesJson(std::ostringstream& json, const std::vector<DetectedLine>& lines) {
  for (size_t i = 0; i < lines.size(); ++i) {
    const DetectedLine& l = lines[i];
    json << (i ? "," : "") << "{\"theta\":" << number(l.line.theta) << ",\"intercept\":" << number(l.line.intercept)
         << ",\"x1\":" << number(l.x1) << ",\"y1\":" << number(l.y1) << ",\"x2\":" << number(l.x2) << ",\"y2\":" << number(l.y2)
         << ",\"votes\":" << l.votes << ",\"support\":" << l.support << "}";
  }
}

void horizonJson(std::ostringstream& json, const HorizonEstimate& h) {
  // The confidence also when not found (the best candidate's), as on the horizon topic.
  json << "{\"found\":" << (h.found ? "true" : "false") << ",\"confidence\":" << number(h.confidence);
  if (h.found) {
    double roll = 0, pitch = 0;
    horizonAttitude(h.line, nullptr, &roll, &pitch);
    json << ",\"theta\":" << number(h.line.theta) << ",\"intercept\":" << number(h.line.intercept) << ",\"x1\":" << number(h.x1)
         << ",\"y1\":" << number(h.y1) << ",\"x2\":" << number(h.x2) << ",\"y2\":" << number(h.y2)
         << ",\"roll\":" << number(roll);
  }
  json << "}";
}

void rangesJson(std::ostringstream& json, const std::vector<ColorClass>& classes) {
  auto channels = [](const Channels& c) {
    return "[" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + "]";
  };
  for (size_t i = 0; i < classes.size(); ++i) {
    const ColorClass& c = classes[i];
    json << (i ? "," : "") << "{\"name\":" << jsonString(c.name) << ",\"space\":\"" << toString(c.space)
         << "\",\"min\":" << channels(c.min) << ",\"max\":" << channels(c.max) << ",\"source\":" << jsonString(c.source)
         << "}";
  }
}

}  // namespace

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string detectionJson(const std::string& file, int width, int height, const std::vector<TrackedBlob>& blobs,
                          const ColorTable& table, const LandmarkResult& result, const FieldResult& field,
                          bool ranges_in_use) {
  std::ostringstream json;
  json << "{\"file\":" << jsonString(file) << ",\"width\":" << width << ",\"height\":" << height << ",\"blobs\":[";
  blobsJson(json, blobs, table, field.boundary);
  json << "],\"lines\":[";
  linesJson(json, result.lines);
  json << "],\"line_budget_exhausted\":" << (result.hough.budget_exhausted ? "true" : "false")
       << ",\"edge_objects_skipped\":" << result.hough.objects_skipped << ",\"horizon\":";
  horizonJson(json, result.horizon);
  json << ",\"field_boundary\":";
  fieldJson(json, field);
  if (ranges_in_use) {
    json << ",\"ranges\":[";
    rangesJson(json, table.classes());
    json << "]";
  }
  json << "}";
  return json.str();
}

std::string errorJson(const std::string& file, const std::string& error) {
  return "{\"file\":" + jsonString(file) + ",\"error\":" + jsonString(error) + "}";
}

}  // namespace rle_vision

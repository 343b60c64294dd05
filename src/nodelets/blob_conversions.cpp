#include "blob_conversions.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace rle_vision {

Blob blobToMsg(const TrackedBlob& blob, const std::string& color_name) {
  Blob b;
  const Region& r = blob.region;
  b.id = blob.id;
  b.color = color_name;
  b.area = r.area;
  b.cx = static_cast<float>(r.cx);
  b.cy = static_cast<float>(r.cy);
  b.left = static_cast<uint32_t>(r.left);
  b.top = static_cast<uint32_t>(r.top);
  b.right = static_cast<uint32_t>(r.right);
  b.bottom = static_cast<uint32_t>(r.bottom);
  b.bottom_at_cx = static_cast<uint32_t>(r.bottom_at_cx);
  b.vx = static_cast<float>(blob.vx);
  b.vy = static_cast<float>(blob.vy);
  b.angle = static_cast<float>(r.angle);
  b.age = blob.age;
  b.above_field_px = std::nanf("");  // unknown until the tracker measures it against a boundary
  b.score = blob.score;
  return b;
}

CmvisionBlobs cmvisionBlobsMsg(const BlobArray& blobs, const ColorTable& table) {
  CmvisionBlobs out;
  out.header = blobs.header;
  out.image_width = blobs.image_width;
  out.image_height = blobs.image_height;
  std::vector<std::pair<int, const Blob*>> ordered;
  for (const Blob& b : blobs.blobs) ordered.emplace_back(table.indexOf(b.color), &b);
  std::stable_sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second->area > b.second->area;
  });
  for (const auto& entry : ordered) {
    const Blob& b = *entry.second;
    CmvisionBlob c;
    c.name = b.color;
    if (entry.first >= 0) {
      const Channels& rgb = table.classes()[entry.first].display_rgb;
      c.red = rgb[0];
      c.green = rgb[1];
      c.blue = rgb[2];
    }
    c.area = b.area;
    c.x = static_cast<uint32_t>(std::rint(b.cx + 0.5));  // cmvision's rounding, kept for drop-in use
    c.y = static_cast<uint32_t>(std::rint(b.cy + 0.5));
    c.left = b.left;
    c.right = b.right + 1;  // CMVision's x2 = x + run length: one past the last column
    c.top = b.top;
    c.bottom = b.bottom;  // its y2 is the row of the last run: inclusive
    out.blobs.push_back(c);
  }
  out.blob_count = static_cast<uint32_t>(out.blobs.size());
  return out;
}

}  // namespace rle_vision

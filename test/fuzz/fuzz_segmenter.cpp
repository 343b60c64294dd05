// libFuzzer target: image bytes to blobs. The first bytes choose the size (1..96 x 1..96), the
// pixel format, the connectivity and up to four colour classes; the rest are pixels. Every
// region must lie inside the image and the areas must add up to at most the pixel count.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <opencv2/core.hpp>

#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/segment/segmenter.h"

using namespace rle_vision;

namespace {

struct Reader {
  const uint8_t* data;
  size_t size;
  uint8_t next() {
    if (size == 0) return 0;
    --size;
    return *data++;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Reader in{data, size};
  const int width = 1 + in.next() % 96, height = 1 + in.next() % 96;
  const PixelFormat formats[] = {PixelFormat::BGR8, PixelFormat::RGB8, PixelFormat::MONO8, PixelFormat::UYVY,
                                 PixelFormat::YUYV};
  const PixelFormat format = formats[in.next() % 5];
  SegmenterOptions options;
  options.connectivity = in.next() % 2 ? Connectivity::Four : Connectivity::Eight;
  options.min_area_px = 1 + in.next() % 4;
  std::vector<ColorClass> classes;
  const int count = 1 + in.next() % 4;
  for (int k = 0; k < count; ++k) {
    ColorClass c;
    c.name = "c" + std::to_string(k);
    c.space = static_cast<ColorSpace>(in.next() % 3);
    for (int ch = 0; ch < 3; ++ch) {
      c.min[ch] = in.next();
      c.max[ch] = in.next();
    }
    c.min_area_px = 1 + in.next() % 3;
    classes.push_back(c);
  }
  std::unique_ptr<ColorTable> table;
  try {
    table = std::make_unique<ColorTable>(classes);
  } catch (const std::invalid_argument&) {
    return 0;  // e.g. a wrapped range in a space that does not allow it
  }
  const int channels = format == PixelFormat::MONO8 ? 1 : (format == PixelFormat::UYVY || format == PixelFormat::YUYV ? 2 : 3);
  const int even_width = channels == 2 ? (width + 1) / 2 * 2 : width;  // 4:2:2 needs pixel pairs
  cv::Mat image(height, even_width, CV_8UC(channels));
  for (int y = 0; y < image.rows; ++y) {
    uint8_t* row = image.ptr<uint8_t>(y);
    for (int i = 0; i < even_width * channels; ++i) row[i] = in.next();
  }
  Segmenter segmenter(options);
  std::vector<Region> regions;
  try {
    segmenter.segment(image, format, *table, &regions);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  uint64_t total = 0;
  for (const Region& r : regions) {
    if (r.left < 0 || r.top < 0 || r.right >= image.cols || r.bottom >= image.rows || r.left > r.right ||
        r.top > r.bottom || r.bottom_at_cx < r.top || r.bottom_at_cx > r.bottom || r.label < 1 ||
        r.label > table->size()) {
      abort();
    }
    total += r.area;
  }
  if (total > static_cast<uint64_t>(image.total())) abort();
  BlobTracker tracker;
  std::vector<TrackedBlob> blobs;
  tracker.update(regions, 0.0, &blobs);
  tracker.update(regions, 1.0 / 30, &blobs);
  return 0;
}

// Camera frames as robots record them, made into images the pipeline reads, with OpenCV alone:
// JPEG or PNG frames (sensor_msgs/CompressedImage, image_transport's "compressed" transport)
// decoded, and Bayer mosaics (raw industrial cameras) demosaiced. No image_transport plugin
// and no image_proc nodelet is needed, so it works the same on Debian (which packages neither
// compressed_image_transport nor image_proc's nodelet description) and on Noetic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace rle_vision {

// An image and its sensor_msgs encoding ("bgr8", "mono8", "bayer_rggb8", ...).
struct EncodedImage {
  cv::Mat image;
  std::string encoding;
};

// Decodes one CompressedImage. `format` is the message's format field: "jpeg" or "png" (old
// drivers), or image_transport's "ENCODING; jpeg compressed TARGET" / "ENCODING; png compressed
// TARGET". Colour comes out as bgr8 (what the codec gives), one channel as mono8 or, for a PNG
// of a Bayer mosaic, that Bayer encoding; 16-bit and depth images are refused. On failure
// returns false with a sentence in `error` that says what to do.
bool decodeCompressedImage(const std::string& format, const uint8_t* data, size_t size, EncodedImage* out,
                           std::string* error);

// "bayer_rggb8", "bayer_bggr8", "bayer_gbrg8", "bayer_grbg8" (and their 16-bit names).
bool isBayerEncoding(const std::string& encoding);

// A bgr8 image from an 8-bit Bayer mosaic (OpenCV's edge-aware demosaicing). False, with the
// reason, for other encodings, 16-bit mosaics, or a mosaic of odd width or height.
bool demosaicBayer(const cv::Mat& mosaic, const std::string& encoding, cv::Mat* bgr, std::string* error);

// Which input the image-input stage reads, decided from what the ROS master shows.
enum class InputChoice {
  kUndecided,  // nothing published yet: look again later
  kRaw,  // sensor_msgs/Image frames on the raw topic
  kCompressed,  // sensor_msgs/CompressedImage frames on RAW/compressed
  kWrongType,  // the raw topic itself carries CompressedImage: nothing can read it as an image
};

// `mode`: "auto", "raw" or "compressed" (anything else is kUndecided, reported by
// inputModeError). `raw_topic_type`: the type published on the raw topic ("" when nobody
// publishes it); `compressed_published`: someone publishes RAW/compressed. Raw frames win in
// "auto" when both exist (a live driver offers both; decoding would only cost time).
InputChoice chooseInput(const std::string& mode, const std::string& raw_topic_type, bool compressed_published);

// "" when `mode` is one chooseInput knows, else a sentence naming the valid ones.
std::string inputModeError(const std::string& mode);

// What to tell the user about a choice: which input is read from which topic and, for
// kWrongType, how to fix it.
std::string describeInputChoice(InputChoice choice, const std::string& raw_topic, bool debayer);

}  // namespace rle_vision

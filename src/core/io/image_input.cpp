#include "rle_vision/io/image_input.h"

#include <algorithm>
#include <cctype>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/pixel_format.h"

namespace rle_vision {
namespace {

std::string lowerTrimmed(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  const size_t first = s.find_first_not_of(" \t");
  const size_t last = s.find_last_not_of(" \t");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// OpenCV names a Bayer pattern by the second row's second and third pixels, ROS by the first
// row's first two: ROS rggb is OpenCV BG (as cv_bridge maps them).
int demosaicCode(const std::string& encoding) {
  if (encoding == "bayer_rggb8") return cv::COLOR_BayerBG2BGR;
  if (encoding == "bayer_bggr8") return cv::COLOR_BayerRG2BGR;
  if (encoding == "bayer_gbrg8") return cv::COLOR_BayerGR2BGR;
  if (encoding == "bayer_grbg8") return cv::COLOR_BayerGB2BGR;
  return -1;
}

}  // namespace

bool decodeCompressedImage(const std::string& format, const uint8_t* data, size_t size, EncodedImage* out,
                           std::string* error) {
  const std::string lower = lowerTrimmed(format);
  if (lower.find("compresseddepth") != std::string::npos) {
    *error = "'" + format + "' is a compressed depth image, not a camera image: point the pipeline at the colour camera";
    return false;
  }
  if (size == 0 || data == nullptr) {
    *error = "the compressed frame is empty (0 bytes)";
    return false;
  }
  // IMREAD_UNCHANGED keeps 16-bit and alpha so that they can be refused or dropped knowingly.
  const cv::Mat bytes(1, static_cast<int>(std::min<size_t>(size, INT32_MAX)), CV_8UC1, const_cast<uint8_t*>(data));
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {  // a corrupt frame: reported below
    image.release();
  }
  if (image.empty()) {
    *error = "could not decode the " + std::to_string(size) + "-byte frame (format '" + format +
             "'): it is not a valid JPEG or PNG image";
    return false;
  }
  *error = checkImageSize(image.cols, image.rows);
  if (!error->empty()) return false;
  if (image.depth() != CV_8U) {
    *error = "the decoded frame is " + std::to_string(8 * image.elemSize1()) +
             "-bit; colour tracking needs 8-bit images (publish bgr8, rgb8 or mono8)";
    return false;
  }
  // The encoding the driver compressed: "bayer_rggb8; png compressed mono8" keeps its mosaic.
  const std::string original = lowerTrimmed(lower.substr(0, lower.find(';')));
  switch (image.channels()) {
    case 1:
      out->encoding = isBayerEncoding(original) ? original : "mono8";
      break;
    case 3:
      out->encoding = "bgr8";  // what the codecs give, whatever the driver's channel order was
      break;
    case 4:
      cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
      out->encoding = "bgr8";
      break;
    default:
      *error = "the decoded frame has " + std::to_string(image.channels()) + " channels (expected 1, 3 or 4)";
      return false;
  }
  out->image = image;
  return true;
}

bool isBayerEncoding(const std::string& encoding) { return encoding.rfind("bayer_", 0) == 0; }

bool demosaicBayer(const cv::Mat& mosaic, const std::string& encoding, cv::Mat* bgr, std::string* error) {
  const int code = demosaicCode(encoding);
  if (code < 0) {
    *error = isBayerEncoding(encoding)
                 ? "16-bit Bayer images ('" + encoding + "') are not supported: set the camera to an 8-bit Bayer mode"
                 : "'" + encoding + "' is not a Bayer encoding";
    return false;
  }
  if (mosaic.empty() || mosaic.type() != CV_8UC1 || mosaic.cols % 2 || mosaic.rows % 2) {
    *error = "a Bayer mosaic must be one 8-bit channel of even width and height (got " + std::to_string(mosaic.cols) +
             "x" + std::to_string(mosaic.rows) + ", " + std::to_string(mosaic.channels()) + " channel(s))";
    return false;
  }
  // Bilinear, like image_proc's default: the fastest, and the tracker averages over blobs anyway.
  cv::cvtColor(mosaic, *bgr, code);
  return true;
}

InputChoice chooseInput(const std::string& mode, const std::string& raw_topic_type, bool compressed_published) {
  if (raw_topic_type == "sensor_msgs/CompressedImage") return InputChoice::kWrongType;
  if (mode == "raw") return InputChoice::kRaw;
  if (mode == "compressed") return InputChoice::kCompressed;
  if (mode != "auto") return InputChoice::kUndecided;
  if (raw_topic_type == "sensor_msgs/Image") return InputChoice::kRaw;
  if (compressed_published) return InputChoice::kCompressed;
  return InputChoice::kUndecided;
}

std::string inputModeError(const std::string& mode) {
  if (mode == "auto" || mode == "raw" || mode == "compressed") return "";
  return "input mode '" + mode + "' is not one of auto, raw, compressed";
}

std::string describeInputChoice(InputChoice choice, const std::string& raw_topic, bool debayer) {
  const std::string debayering = debayer ? ", demosaicing Bayer frames" : "";
  switch (choice) {
    case InputChoice::kRaw:
      return debayer ? "reading raw frames on " + raw_topic + debayering
                     : "raw frames on " + raw_topic + ": the pipeline reads them directly, nothing to decode";
    case InputChoice::kCompressed:
      return "reading compressed frames on " + raw_topic + "/compressed (JPEG/PNG, decoded once for the whole pipeline" +
             debayering + ")";
    case InputChoice::kWrongType:
      return raw_topic + " carries sensor_msgs/CompressedImage, which no image subscriber can read: remap the "
             "compressed topic to " + raw_topic + "/compressed instead (image_transport's name for it; play.launch "
             "does this by itself)";
    case InputChoice::kUndecided:
      break;
  }
  return "waiting for frames on " + raw_topic + " or " + raw_topic + "/compressed";
}

}  // namespace rle_vision

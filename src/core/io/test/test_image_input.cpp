// Compressed and Bayer camera frames into images the pipeline reads, and the choice of input.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rle_vision/io/image_input.h"

namespace rle_vision {
namespace {

std::vector<uint8_t> encode(const std::string& extension, const cv::Mat& image) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes));
  return bytes;
}

// A scene with known colours: left half orange, right half blue (BGR).
cv::Mat twoColours() {
  cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(30, 120, 230));
  bgr(cv::Rect(32, 0, 32, 48)).setTo(cv::Scalar(200, 90, 20));
  return bgr;
}

// The RGGB mosaic a Bayer camera would give of `bgr`.
cv::Mat mosaicOf(const cv::Mat& bgr, const std::string& pattern) {
  cv::Mat mosaic(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const char c = pattern[(y % 2) * 2 + (x % 2)];
      const int channel = c == 'b' ? 0 : c == 'g' ? 1 : 2;
      mosaic.at<uint8_t>(y, x) = bgr.at<cv::Vec3b>(y, x)[channel];
    }
  }
  return mosaic;
}

TEST(ImageInput, JpegDecodesToBgrWithTheColoursKept) {
  const cv::Mat scene = twoColours();
  const std::vector<uint8_t> jpeg = encode(".jpg", scene);
  EncodedImage out;
  std::string error;
  ASSERT_TRUE(decodeCompressedImage("rgb8; jpeg compressed bgr8", jpeg.data(), jpeg.size(), &out, &error)) << error;
  EXPECT_EQ(out.encoding, "bgr8");
  ASSERT_EQ(out.image.size(), scene.size());
  ASSERT_EQ(out.image.type(), CV_8UC3);
  // Away from the colour edge, JPEG keeps each colour within a few levels.
  const cv::Scalar left = cv::mean(out.image(cv::Rect(4, 4, 20, 40)));
  const cv::Scalar right = cv::mean(out.image(cv::Rect(40, 4, 20, 40)));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(left[c], scene.at<cv::Vec3b>(0, 0)[c], 4.0) << "channel " << c;
    EXPECT_NEAR(right[c], scene.at<cv::Vec3b>(0, 63)[c], 4.0) << "channel " << c;
  }
}

TEST(ImageInput, PngIsLosslessAndKeepsMonoAndBayerEncodings) {
  cv::Mat gray(30, 40, CV_8UC1);
  cv::randu(gray, 0, 256);
  const std::vector<uint8_t> png = encode(".png", gray);
  EncodedImage out;
  std::string error;
  ASSERT_TRUE(decodeCompressedImage("png", png.data(), png.size(), &out, &error)) << error;
  EXPECT_EQ(out.encoding, "mono8");
  EXPECT_EQ(cv::norm(out.image, gray, cv::NORM_INF), 0);
  ASSERT_TRUE(decodeCompressedImage("bayer_rggb8; png compressed mono8", png.data(), png.size(), &out, &error)) << error;
  EXPECT_EQ(out.encoding, "bayer_rggb8");
  EXPECT_EQ(cv::norm(out.image, gray, cv::NORM_INF), 0);
}

TEST(ImageInput, AlphaIsDroppedAndSixteenBitRefused) {
  cv::Mat bgra(10, 12, CV_8UC4, cv::Scalar(10, 20, 30, 255));
  std::vector<uint8_t> png = encode(".png", bgra);
  EncodedImage out;
  std::string error;
  ASSERT_TRUE(decodeCompressedImage("bgra8; png compressed bgra8", png.data(), png.size(), &out, &error)) << error;
  EXPECT_EQ(out.encoding, "bgr8");
  EXPECT_EQ(out.image.at<cv::Vec3b>(5, 5), cv::Vec3b(10, 20, 30));

  png = encode(".png", cv::Mat(10, 12, CV_16UC1, cv::Scalar(1000)));
  EXPECT_FALSE(decodeCompressedImage("mono16; png compressed mono16", png.data(), png.size(), &out, &error));
  EXPECT_NE(error.find("8-bit"), std::string::npos) << error;
}

TEST(ImageInput, BadFramesAreRefusedWithTheReason) {
  EncodedImage out;
  std::string error;
  const std::vector<uint8_t> garbage(500, 0x5a);
  EXPECT_FALSE(decodeCompressedImage("jpeg", garbage.data(), garbage.size(), &out, &error));
  EXPECT_NE(error.find("not a valid JPEG or PNG"), std::string::npos) << error;
  EXPECT_FALSE(decodeCompressedImage("jpeg", nullptr, 0, &out, &error));
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
  const std::vector<uint8_t> png = encode(".png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)));
  EXPECT_FALSE(decodeCompressedImage("16UC1; compressedDepth", png.data(), png.size(), &out, &error));
  EXPECT_NE(error.find("depth"), std::string::npos) << error;
  // A truncated JPEG (a frame cut by a dropped packet) is refused, not half-decoded into a crash.
  std::vector<uint8_t> jpeg = encode(".jpg", twoColours());
  jpeg.resize(20);
  EXPECT_FALSE(decodeCompressedImage("jpeg", jpeg.data(), jpeg.size(), &out, &error));
}

TEST(ImageInput, EveryBayerPatternDemosaicsToTheSceneColours) {
  const cv::Mat scene = twoColours();
  for (const std::string pattern : {"rggb", "bggr", "gbrg", "grbg"}) {
    cv::Mat bgr;
    std::string error;
    ASSERT_TRUE(demosaicBayer(mosaicOf(scene, pattern), "bayer_" + pattern + "8", &bgr, &error)) << error;
    ASSERT_EQ(bgr.size(), scene.size());
    // Inside each half (two pixels from the edges) the colour is exact.
    for (const cv::Point p : {cv::Point(10, 20), cv::Point(50, 20)}) {
      EXPECT_EQ(bgr.at<cv::Vec3b>(p), scene.at<cv::Vec3b>(p)) << pattern << " at " << p;
    }
  }
}

TEST(ImageInput, DemosaicRefusesWhatItCannotDo) {
  cv::Mat bgr;
  std::string error;
  EXPECT_FALSE(demosaicBayer(cv::Mat(4, 4, CV_8UC1), "mono8", &bgr, &error));
  EXPECT_FALSE(demosaicBayer(cv::Mat(4, 4, CV_16UC1), "bayer_rggb16", &bgr, &error));
  EXPECT_NE(error.find("8-bit Bayer mode"), std::string::npos) << error;
  EXPECT_FALSE(demosaicBayer(cv::Mat(5, 4, CV_8UC1), "bayer_rggb8", &bgr, &error));
  EXPECT_NE(error.find("even width and height"), std::string::npos) << error;
  EXPECT_TRUE(isBayerEncoding("bayer_gbrg8"));
  EXPECT_FALSE(isBayerEncoding("bgr8"));
}

TEST(ImageInput, AutoPrefersRawFramesAndNamesTheFixForAMisroutedTopic) {
  EXPECT_EQ(chooseInput("auto", "", false), InputChoice::kUndecided);
  EXPECT_EQ(chooseInput("auto", "", true), InputChoice::kCompressed);
  EXPECT_EQ(chooseInput("auto", "sensor_msgs/Image", true), InputChoice::kRaw);
  EXPECT_EQ(chooseInput("auto", "sensor_msgs/Image", false), InputChoice::kRaw);
  EXPECT_EQ(chooseInput("compressed", "", false), InputChoice::kCompressed);
  EXPECT_EQ(chooseInput("raw", "", true), InputChoice::kRaw);
  EXPECT_EQ(chooseInput("auto", "sensor_msgs/CompressedImage", false), InputChoice::kWrongType);
  EXPECT_EQ(chooseInput("raw", "sensor_msgs/CompressedImage", false), InputChoice::kWrongType);
  EXPECT_EQ(chooseInput("jpeg", "", true), InputChoice::kUndecided);
  EXPECT_NE(inputModeError("jpeg").find("auto, raw, compressed"), std::string::npos);
  EXPECT_EQ(inputModeError("auto"), "");
  const std::string fix = describeInputChoice(InputChoice::kWrongType, "/camera/image_raw", false);
  EXPECT_NE(fix.find("/camera/image_raw/compressed"), std::string::npos) << fix;
  EXPECT_NE(fix.find("remap"), std::string::npos) << fix;
}

}  // namespace
}  // namespace rle_vision

// Colour conversion, the per-channel bit tables and the vectorised classifier.
#include <algorithm>
#include <cstdlib>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "rle_vision/color/classifier.h"
#include "rle_vision/color/color_convert.h"
#include "rle_vision/color/color_table.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

using test::makeClass;

TEST(ColorConvert, YuvIsBitExactWithOpenCvForAllColours) {
  cv::Mat bgr(4096, 4096, CV_8UC3);
  for (int i = 0; i < (1 << 24); ++i) {
    uint8_t* p = bgr.ptr<uint8_t>() + 3 * i;
    p[0] = i & 255;
    p[1] = (i >> 8) & 255;
    p[2] = (i >> 16) & 255;
  }
  cv::Mat expected;
  cv::cvtColor(bgr, expected, cv::COLOR_BGR2YUV);
  std::vector<uint8_t> y(4096), u(4096), v(4096);
  long mismatches = 0;
  for (int row = 0; row < 4096; ++row) {
    bgrRowToYuvPlanes(bgr.ptr<uint8_t>(row), 4096, false, y.data(), u.data(), v.data());
    const uint8_t* e = expected.ptr<uint8_t>(row);
    for (int x = 0; x < 4096; ++x) {
      mismatches += (y[x] != e[3 * x]) + (u[x] != e[3 * x + 1]) + (v[x] != e[3 * x + 2]);
    }
  }
  EXPECT_EQ(mismatches, 0);
  // The scalar helper agrees too (spot check).
  const Channels s = yuvFromRgb(12, 200, 99);
  const int index = (12 << 16) | (200 << 8) | 99;  // pixel i holds b = i & 255, g, r = i >> 16
  const cv::Vec3b e = expected.at<cv::Vec3b>(index / 4096, index % 4096);
  EXPECT_EQ(s[0], e[0]);
  EXPECT_EQ(s[1], e[1]);
  EXPECT_EQ(s[2], e[2]);
}

TEST(ColorConvert, PackedYuvFramesReadAsTheCamerasOwnYuv) {
  // Random colours, each on a pixel pair (which shares its chroma in 4:2:2): every colour
  // a camera could send for it, none clipped on the way back.
  cv::Mat pairs(60, 40, CV_8UC3), bgr;
  cv::RNG(13).fill(pairs, cv::RNG::UNIFORM, 0, 256);
  cv::resize(pairs, bgr, cv::Size(80, 60), 0, 0, cv::INTER_NEAREST);
  const cv::Mat uyvy = bgrToUyvy(bgr);
  const cv::Mat back = convertBgrImage(yuv422ToBgr(uyvy, /*is_uyvy=*/true), ColorSpace::YUV);
  int worst = 0;
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const uint8_t* pair = uyvy.ptr<uint8_t>(y) + 4 * (x / 2);
      const int camera[3] = {pair[x % 2 == 0 ? 1 : 3], pair[0], pair[2]};
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(back.at<cv::Vec3b>(y, x)[c] - camera[c]));
    }
  }
  EXPECT_LE(worst, 2) << "the camera's Y, U, V within rounding";
  cv::Mat opencv_bgr;
  cv::cvtColor(uyvy, opencv_bgr, cv::COLOR_YUV2BGR_UYVY);
  const cv::Mat opencv_yuv = convertBgrImage(opencv_bgr, ColorSpace::YUV);
  EXPECT_GT(cv::norm(opencv_yuv, back, cv::NORM_INF), 10) << "OpenCV's video-range decode would shift ranges";
  EXPECT_THROW(yuv422ToBgr(cv::Mat(4, 3, CV_8UC2), true), std::invalid_argument);
}

TEST(ColorClass, WrappedRangeContainsBothEnds) {
  const ColorClass red = makeClass("red", ColorSpace::HSV, {{170, 100, 50}}, {{10, 255, 255}});
  EXPECT_TRUE(red.channelContains(0, 175));
  EXPECT_TRUE(red.channelContains(0, 0));
  EXPECT_TRUE(red.channelContains(0, 10));
  EXPECT_FALSE(red.channelContains(0, 11));
  EXPECT_FALSE(red.channelContains(0, 90));
  EXPECT_FALSE(red.channelContains(1, 99));
}

TEST(ColorClass, ValidationNamesTheProblem) {
  EXPECT_NE(validateColorClasses({}).find("no colour classes"), std::string::npos);
  std::vector<ColorClass> many(33, makeClass("x", ColorSpace::YUV, {{0, 0, 0}}, {{1, 1, 1}}));
  for (size_t i = 0; i < many.size(); ++i) many[i].name = "c" + std::to_string(i);
  EXPECT_NE(validateColorClasses(many).find("at most 32"), std::string::npos);
  many.resize(32);
  EXPECT_EQ(validateColorClasses(many), "");
  many[5].name = "c1";
  EXPECT_NE(validateColorClasses(many).find("'c1' is used twice"), std::string::npos);
  EXPECT_THROW(ColorTable({}), std::invalid_argument);
}

TEST(ColorClasses, OnlyTheHsvHueMayWrap) {
  EXPECT_EQ(validateColorClasses({makeClass("red", ColorSpace::HSV, {{170, 100, 50}}, {{10, 255, 255}})}), "");
  EXPECT_EQ(validateColorClasses({makeClass("y", ColorSpace::YUV, {{200, 0, 0}}, {{40, 255, 255}})}),
            "colour class 'y': min 200 > max 40 on YUV Y (only the HSV hue may wrap around)");
  EXPECT_EQ(validateColorClasses({makeClass("s", ColorSpace::HSV, {{0, 200, 0}}, {{179, 100, 255}})}),
            "colour class 's': min 200 > max 100 on HSV S (only the HSV hue may wrap around)");
  EXPECT_EQ(validateColorClasses({makeClass("h", ColorSpace::HSV, {{0, 0, 0}}, {{200, 255, 255}})}),
            "colour class 'h': HSV hue bounds must be 0..179 (OpenCV's 8-bit hue), got 0..200");
}

// Random classes of every space (some hues wrapped) and random pixels: the bit tables, the class
// boxes and the vectorised row classifier must give the same label everywhere.
TEST(PixelClassifier, AgreesWithBitTablesOnRandomImagesInEveryFormat) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<ColorClass> classes;
    const int count = 1 + trial % 32;
    for (int k = 0; k < count; ++k) {
      Channels lo, hi;
      for (int ch = 0; ch < 3; ++ch) {
        lo[ch] = static_cast<uint8_t>(byte(rng));
        hi[ch] = static_cast<uint8_t>(byte(rng));
        const bool hue = k % 3 == 2 && ch == 0;
        if (hue) {  // OpenCV's hue is 0..179; some hue ranges wrap around
          lo[ch] = static_cast<uint8_t>(lo[ch] % 180);
          hi[ch] = static_cast<uint8_t>(hi[ch] % 180);
        }
        if (!(hue && k % 2 == 0) && lo[ch] > hi[ch]) std::swap(lo[ch], hi[ch]);
      }
      classes.push_back(makeClass("c" + std::to_string(k), static_cast<ColorSpace>(k % 3), lo, hi));
    }
    const ColorTable table(classes);
    cv::Mat bgr(7 + trial, 33 + 2 * trial, CV_8UC3);
    cv::RNG(trial).fill(bgr, cv::RNG::UNIFORM, 0, 256);
    PixelClassifier classifier;
    const cv::Mat labels = classifier.classify(bgr, PixelFormat::BGR8, table);
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    const cv::Mat rgb_labels = classifier.classify(rgb, PixelFormat::RGB8, table);
    for (int y = 0; y < bgr.rows; ++y) {
      for (int x = 0; x < bgr.cols; ++x) {
        const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
        const int expected = table.classifyBgr(p[0], p[1], p[2]);
        int by_box = 0;
        for (int k = count - 1; k >= 0; --k) {
          if (classes[k].contains(convertBgrPixel(p[0], p[1], p[2], classes[k].space))) by_box = k + 1;
        }
        ASSERT_EQ(labels.at<uint8_t>(y, x), expected) << "trial " << trial << " at " << x << "," << y;
        ASSERT_EQ(rgb_labels.at<uint8_t>(y, x), expected);
        ASSERT_EQ(by_box, expected);
      }
    }
  }
}

// All-YUV tables take the fused AVX2 kernel where the CPU has it: check it on every colour.
TEST(PixelClassifier, YuvOnlyTablesAgreeWithBitTablesOnAllColours) {
  cv::Mat bgr(4096, 4096, CV_8UC3);
  for (int i = 0; i < (1 << 24); ++i) {
    uint8_t* p = bgr.ptr<uint8_t>() + 3 * i;
    p[0] = i & 255;
    p[1] = (i >> 8) & 255;
    p[2] = (i >> 16) & 255;
  }
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int count : {1, 4, 32}) {
    std::vector<ColorClass> classes;
    for (int k = 0; k < count; ++k) {
      Channels lo, hi;
      for (int ch = 0; ch < 3; ++ch) {
        lo[ch] = static_cast<uint8_t>(byte(rng));
        hi[ch] = static_cast<uint8_t>(byte(rng));
        if (lo[ch] > hi[ch]) std::swap(lo[ch], hi[ch]);
      }
      classes.push_back(makeClass("c" + std::to_string(k), ColorSpace::YUV, lo, hi));
    }
    const ColorTable table(classes);
    PixelClassifier classifier;
    // Row widths 4096 (no tail) and, through a narrower view, 4093 (a 29-pixel scalar tail).
    for (int width : {4096, 4093}) {
      const cv::Mat view = bgr.colRange(0, width);
      const cv::Mat labels = classifier.classify(view, PixelFormat::BGR8, table);
      cv::Mat rgb;
      cv::cvtColor(view, rgb, cv::COLOR_BGR2RGB);
      const cv::Mat rgb_labels = classifier.classify(rgb, PixelFormat::RGB8, table);
      long mismatches = 0;
      for (int y = 0; y < view.rows; ++y) {
        const uint8_t* p = view.ptr<uint8_t>(y);
        const uint8_t* l = labels.ptr<uint8_t>(y);
        const uint8_t* lr = rgb_labels.ptr<uint8_t>(y);
        for (int x = 0; x < width; ++x) {
          const int expected = firstClassLabel(table.mask(ColorSpace::YUV, yuvFromRgb(p[3 * x + 2], p[3 * x + 1], p[3 * x])));
          mismatches += (l[x] != expected) + (lr[x] != expected);
        }
      }
      EXPECT_EQ(mismatches, 0) << count << " classes, width " << width;
    }
  }
}

TEST(PixelClassifier, FirstListedClassWinsWhereClassesOverlap) {
  const ColorTable table({makeClass("wide", ColorSpace::RGB, {{100, 0, 0}}, {{255, 255, 255}}),
                          makeClass("narrow", ColorSpace::RGB, {{200, 0, 0}}, {{255, 50, 50}})});
  EXPECT_EQ(table.classifyBgr(10, 10, 220), 1);
  const ColorTable reversed({table.classes()[1], table.classes()[0]});
  EXPECT_EQ(reversed.classifyBgr(10, 10, 220), 1);  // now "narrow" is first
  EXPECT_EQ(reversed.classifyBgr(10, 10, 150), 2);
  cv::Mat image(1, 2, CV_8UC3);
  image.at<cv::Vec3b>(0, 0) = cv::Vec3b(10, 10, 220);
  image.at<cv::Vec3b>(0, 1) = cv::Vec3b(10, 10, 150);
  PixelClassifier classifier;
  const cv::Mat labels = classifier.classify(image, PixelFormat::BGR8, reversed);
  EXPECT_EQ(labels.at<uint8_t>(0, 0), 1);
  EXPECT_EQ(labels.at<uint8_t>(0, 1), 2);
}

// bgr_pair_chroma: each pixel pair's YUV classes see the pair's mean U and V ((a + b + 1) / 2),
// Y its own; a last odd pixel keeps its own chroma. The fused kernel (all-YUV table) and the
// plane path (a table with an RGB class too) both, vector bodies and scalar tails.
TEST(PixelClassifier, PairChromaClassifiesEachPairOnItsMeanChroma) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<ColorClass> yuv_classes;
  for (int k = 0; k < 4; ++k) {
    Channels lo, hi;
    for (int ch = 0; ch < 3; ++ch) {
      lo[ch] = static_cast<uint8_t>(byte(rng) / 2);
      hi[ch] = static_cast<uint8_t>(std::min(255, lo[ch] + 40 + byte(rng) / 2));
    }
    yuv_classes.push_back(makeClass("y" + std::to_string(k), ColorSpace::YUV, lo, hi));
  }
  std::vector<ColorClass> mixed = yuv_classes;
  mixed.push_back(makeClass("r", ColorSpace::RGB, {{200, 0, 0}}, {{255, 60, 60}}));
  for (const std::vector<ColorClass>& classes : {yuv_classes, mixed}) {
    const ColorTable table(classes);
    for (int width : {64, 70, 33, 1}) {
      cv::Mat bgr(9, width, CV_8UC3);
      cv::RNG(width).fill(bgr, cv::RNG::UNIFORM, 0, 256);
      PixelClassifier classifier;
      classifier.setBgrPairChroma(true);
      const cv::Mat labels = classifier.classify(bgr, PixelFormat::BGR8, table);
      long mismatches = 0, changed = 0;
      for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < width; ++x) {
          const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
          Channels yuv = yuvFromRgb(p[2], p[1], p[0]);
          const int mate = x % 2 == 0 ? x + 1 : x - 1;
          if (mate < width) {
            const cv::Vec3b q = bgr.at<cv::Vec3b>(y, mate);
            const Channels other = yuvFromRgb(q[2], q[1], q[0]);
            for (int ch = 1; ch < 3; ++ch) yuv[ch] = static_cast<uint8_t>((yuv[ch] + other[ch] + 1) / 2);
          }
          int expected = 0;
          for (int k = static_cast<int>(classes.size()) - 1; k >= 0; --k) {
            const Channels seen = classes[k].space == ColorSpace::YUV ? yuv : convertBgrPixel(p[0], p[1], p[2], classes[k].space);
            if (classes[k].contains(seen)) expected = k + 1;
          }
          mismatches += labels.at<uint8_t>(y, x) != expected;
          changed += table.classifyBgr(p[0], p[1], p[2]) != expected;
        }
      }
      EXPECT_EQ(mismatches, 0) << classes.size() << " classes, width " << width;
      cv::Mat rgb;
      cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
      EXPECT_EQ(cv::countNonZero(labels != classifier.classify(rgb, PixelFormat::RGB8, table)), 0) << "rgb8, width " << width;
      if (width > 1) EXPECT_GT(changed, 0) << "the option changed no label: the test would not see it off";
      // YUV classes alone (an RGB class reads UYVY through a lossy BGR decode): the labels of
      // the same frame sent as UYVY, pixel for pixel.
      if (width % 2 == 0 && classes.size() == yuv_classes.size()) {
        EXPECT_EQ(cv::countNonZero(labels != classifier.classify(bgrToUyvy(bgr), PixelFormat::UYVY, table)), 0);
      }
    }
  }
}

TEST(PixelClassifier, Yuv422UsesTheCamerasOwnYuv) {
  const ColorTable table({makeClass("a", ColorSpace::YUV, {{0, 100, 100}}, {{255, 140, 140}}),
                          makeClass("b", ColorSpace::YUV, {{50, 0, 150}}, {{200, 120, 255}}),
                          makeClass("w", ColorSpace::YUV, {{40, 10, 0}}, {{200, 250, 255}})});
  PixelClassifier classifier;
  for (int width : {64, 70, 2, 640}) {  // vector body only, with a scalar tail, tail only
    cv::Mat uyvy(5, width, CV_8UC2);
    cv::RNG(width).fill(uyvy, cv::RNG::UNIFORM, 0, 256);
    cv::Mat yuyv(uyvy.size(), CV_8UC2);
    for (int y = 0; y < uyvy.rows; ++y) {
      const uint8_t* s = uyvy.ptr<uint8_t>(y);
      uint8_t* d = yuyv.ptr<uint8_t>(y);
      for (int i = 0; i < uyvy.cols * 2; i += 2) {
        d[i] = s[i + 1];
        d[i + 1] = s[i];
      }
    }
    const cv::Mat from_uyvy = classifier.classify(uyvy, PixelFormat::UYVY, table);
    const cv::Mat from_yuyv = classifier.classify(yuyv, PixelFormat::YUYV, table);
    for (int y = 0; y < uyvy.rows; ++y) {
      const uint8_t* p = uyvy.ptr<uint8_t>(y);
      for (int x = 0; x < uyvy.cols; ++x) {
        const int pair = x / 2;
        const Channels yuv{{p[4 * pair + 1 + 2 * (x % 2)], p[4 * pair], p[4 * pair + 2]}};
        const int expected = firstClassLabel(table.mask(ColorSpace::YUV, yuv));
        ASSERT_EQ(from_uyvy.at<uint8_t>(y, x), expected) << "width " << width << " x " << x;
        ASSERT_EQ(from_yuyv.at<uint8_t>(y, x), expected) << "width " << width << " x " << x;
      }
    }
  }
}

TEST(PixelClassifier, MonoOnlyUsesClassesThatIgnoreChroma) {
  const ColorTable table({makeClass("orange", ColorSpace::YUV, {{0, 0, 150}}, {{255, 110, 255}}),
                          makeClass("white", ColorSpace::YUV, {{200, 0, 0}}, {{255, 255, 255}}),
                          makeClass("dark", ColorSpace::HSV, {{0, 0, 0}}, {{179, 255, 40}})});
  EXPECT_EQ(table.chromaClasses(), 1u);
  cv::Mat mono(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) mono.at<uint8_t>(0, i) = static_cast<uint8_t>(i);
  PixelClassifier classifier;
  const cv::Mat labels = classifier.classify(mono, PixelFormat::MONO8, table);
  for (int i = 0; i < 256; ++i) {
    const int expected = i >= 200 ? 2 : (i <= 40 ? 3 : 0);
    EXPECT_EQ(labels.at<uint8_t>(0, i), expected) << "gray " << i;
  }
}

TEST(PixelClassifier, RejectsImagesThatDoNotFitTheFormat) {
  const ColorTable table({makeClass("a", ColorSpace::YUV, {{0, 0, 0}}, {{255, 255, 255}})});
  PixelClassifier classifier;
  try {
    classifier.classify(cv::Mat(), PixelFormat::BGR8, table);
    FAIL() << "empty image accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
  try {
    // 4097 x 4096 mono8 (16 MB, one row over the limit); a header-only view is enough.
    static uint8_t pixel = 0;
    classifier.classify(cv::Mat(4096, 4097, CV_8UC1, &pixel, 0), PixelFormat::MONO8, table);
    FAIL() << "an image over kMaxImagePixels accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4097x4096 pixels, more than the 16777216"), std::string::npos) << e.what();
  }
  EXPECT_EQ(checkImageSize(4096, 4096), "");
  EXPECT_EQ(checkImageSize(8192, 2048), "");  // the limit is on pixels, not on either side
  EXPECT_NE(checkImageSize(8000, 8000), "");
  EXPECT_NE(checkImageSize(0, 480).find("empty (0x480"), std::string::npos);
  try {
    classifier.classify(cv::Mat(4, 4, CV_8UC1), PixelFormat::BGR8, table);
    FAIL() << "mono image accepted as bgr8";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs 3 bytes per pixel"), std::string::npos);
  }
  try {
    classifier.classify(cv::Mat(4, 5, CV_8UC2), PixelFormat::UYVY, table);
    FAIL() << "odd-width 4:2:2 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("even width"), std::string::npos);
  }
  EXPECT_THROW(classifier.classify(cv::Mat(4, 4, CV_16UC3), PixelFormat::BGR8, table), std::invalid_argument);
}

TEST(PixelFormat, MapsRosEncodings) {
  PixelFormat f;
  ASSERT_TRUE(pixelFormatFromEncoding("bgr8", &f));
  EXPECT_EQ(f, PixelFormat::BGR8);
  ASSERT_TRUE(pixelFormatFromEncoding("yuv422", &f));
  EXPECT_EQ(f, PixelFormat::UYVY);
  ASSERT_TRUE(pixelFormatFromEncoding("yuv422_yuy2", &f));
  EXPECT_EQ(f, PixelFormat::YUYV);
  EXPECT_FALSE(pixelFormatFromEncoding("bayer_rggb8", &f));
  EXPECT_FALSE(pixelFormatFromEncoding("16UC1", &f));
  EXPECT_FALSE(pixelFormatFromEncoding("", &f));
}

}  // namespace
}  // namespace rle_vision

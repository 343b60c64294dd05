// colors.yaml, CMVision colors.txt and scene files: good files load, broken ones fail loudly
// with the file, the line and the reason.
#include <array>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "rle_vision/io/color_config.h"
#include "rle_vision/sim/scene_file.h"
#include "testing/test_helpers.h"

namespace rle_vision {
namespace {

using test::sourcePath;

// The message of the ConfigError `f` throws ("" when it does not throw).
template <typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ColorConfig, ShippedColorsYamlLoads) {
  const std::vector<ColorClass> classes = loadColorClasses(sourcePath("config/colors.yaml"));
  ASSERT_EQ(classes.size(), 4u);
  EXPECT_EQ(classes[0].name, "red");
  EXPECT_EQ(classes[0].space, ColorSpace::YUV);
  EXPECT_EQ(classes[0].min[2], 184);
  EXPECT_EQ(classes[0].min_area_px, 30u);
  EXPECT_EQ(classes[0].source, "config");
}

TEST(ColorConfig, YamlRoundTrips) {
  std::vector<ColorClass> classes = loadColorClasses(sourcePath("config/colors.yaml"));
  classes[1].space = ColorSpace::HSV;
  classes[1].min[0] = 170;  // wrapped hue
  classes[1].max[0] = 10;
  const std::vector<ColorClass> back = parseColorClassesYaml(colorClassesToYaml(classes), "text");
  ASSERT_EQ(back.size(), classes.size());
  for (size_t i = 0; i < classes.size(); ++i) {
    EXPECT_EQ(back[i].name, classes[i].name);
    EXPECT_EQ(back[i].space, classes[i].space);
    EXPECT_EQ(back[i].min, classes[i].min);
    EXPECT_EQ(back[i].max, classes[i].max);
    EXPECT_EQ(back[i].display_rgb, classes[i].display_rgb);
    EXPECT_EQ(back[i].min_area_px, classes[i].min_area_px);
  }
}

TEST(ColorConfig, BrokenYamlNamesFileLineAndReason) {
  const std::string head = "classes:\n  - name: red\n";
  EXPECT_EQ(errorOf([&] { parseColorClassesYaml(head + "    min: [0, 300, 1]\n    max: [1, 1, 1]\n", "c.yaml"); }),
            "c.yaml:3: 'min' must be a list of 3 integers 0..255");
  EXPECT_EQ(errorOf([&] { parseColorClassesYaml(head + "    min: [0, 1]\n    max: [1, 1, 1]\n", "c.yaml"); }),
            "c.yaml:3: 'min' must be a list of 3 integers 0..255");
  EXPECT_EQ(errorOf([&] { parseColorClassesYaml(head + "    min: [0, 0, 0]\n", "c.yaml"); }),
            "c.yaml:2: class 'red' needs 'min' and 'max' (or a 'verifier_file' to take them from)");
  EXPECT_NE(errorOf([&] { parseColorClassesYaml(head + "    mni: [0, 0, 0]\n", "c.yaml"); })
                .find("c.yaml:3: unknown key 'mni'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              parseColorClassesYaml(head + "    space: LAB\n    min: [0, 0, 0]\n    max: [1, 1, 1]\n", "c.yaml");
            }).find("c.yaml:3: unknown colour space 'LAB'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { parseColorClassesYaml("classes:\n  - name: [unclosed\n", "c.yaml"); })
                .find("YAML syntax error"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              parseColorClassesYaml(head + "    min: [0, 0, 0]\n    max: [1, 1, 1]\n" + head.substr(9) +
                                        "    min: [0, 0, 0]\n    max: [1, 1, 1]\n", "c.yaml");
            }).find("'red' is used twice"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { parseColorClassesYaml(head + "    min: [0, 0, 0]\n    max: [1, 1, 1]\n    min_area_px: .nan\n", "c.yaml"); })
                .find("c.yaml:5: 'min_area_px'"),
            std::string::npos);
  // Found by fuzz_color_config: a list or mapping as a key ("? [a]") once escaped as a yaml-cpp
  // conversion error instead of a ConfigError naming the line.
  EXPECT_EQ(errorOf([&] { parseColorClassesYaml(head + "    ? [min]\n    : [0, 0, 0]\n", "c.yaml"); }),
            "c.yaml:3: a key must be a plain name, not a list or mapping");
  EXPECT_EQ(errorOf([] { loadColorClasses("/nonexistent/colors.yaml"); }),
            "/nonexistent/colors.yaml: cannot open the file (check the path and permissions)");
}

TEST(ColorConfig, CmvisionClassicAndCommentedFilesLoad) {
  const std::vector<ColorClass> classic = loadColorClasses(sourcePath("test/data/colors_classic.txt"));
  ASSERT_EQ(classic.size(), 3u);
  EXPECT_EQ(classic[0].name, "Ball");
  EXPECT_EQ(classic[0].display_rgb, (Channels{{255, 128, 0}}));
  EXPECT_EQ(classic[0].min, (Channels{{12, 99, 143}}));
  EXPECT_EQ(classic[0].max, (Channels{{153, 127, 168}}));
  EXPECT_EQ(classic[2].space, ColorSpace::YUV);
  const std::vector<ColorClass> commented = loadColorClasses(sourcePath("test/data/colors_commented.txt"));
  ASSERT_EQ(commented.size(), 2u);
  EXPECT_EQ(commented[0].min, classic[0].min);
  EXPECT_EQ(commented[1].name, "Yellow_Team");
  EXPECT_EQ(commented[1].max, classic[1].max);
}

TEST(ColorConfig, ShippedColorsTxtHoldsTheShippedYamlClasses) {
  const std::vector<ColorClass> yaml = loadColorClasses(sourcePath("config/colors.yaml"));
  const std::vector<ColorClass> txt = loadColorClasses(sourcePath("config/colors.txt"));
  ASSERT_EQ(txt.size(), yaml.size());
  for (size_t i = 0; i < yaml.size(); ++i) {
    EXPECT_EQ(txt[i].name, yaml[i].name);
    EXPECT_EQ(txt[i].space, yaml[i].space);
    EXPECT_EQ(txt[i].min, yaml[i].min) << yaml[i].name;
    EXPECT_EQ(txt[i].max, yaml[i].max) << yaml[i].name;
    EXPECT_EQ(txt[i].display_rgb, yaml[i].display_rgb) << yaml[i].name;
  }
}

// What CMVision's own loadOptions() reads from a colors.txt, by its rules: a section header
// line starts "[", an entry is what its sscanf pattern matches (anything after it ignored),
// and a line matching nothing at all (sscanf returns 0: a comment, a blank line, the next
// header, which is then lost) ends the section.
struct CmvisionReading {
  std::vector<std::string> names;
  std::vector<std::array<int, 6>> thresholds;
};
CmvisionReading readLikeCmvision(const std::string& path) {
  enum { kScan, kColors, kThresholds } state = kScan;
  CmvisionReading out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    line += '\n';  // as fgets() leaves it: a blank line matches nothing and ends a section
    char header[256] = {0}, name[256] = {0};
    int r, g, b, expected;
    double merge;
    std::array<int, 6> t{};
    if (state == kScan) {
      if (std::sscanf(line.c_str(), "[%255s", header) == 1) {
        if (std::string(header) == "Colors]") state = kColors;
        if (std::string(header) == "Thresholds]") state = kThresholds;
      }
    } else if (state == kColors) {
      const int n = std::sscanf(line.c_str(), "(%d,%d,%d) %lf %d %255s", &r, &g, &b, &merge, &expected, name);
      if (n == 6) out.names.push_back(name);
      if (n == 0) state = kScan;
    } else {
      const int n = std::sscanf(line.c_str(), "(%d:%d,%d:%d,%d:%d)", &t[0], &t[1], &t[2], &t[3], &t[4], &t[5]);
      if (n == 6) out.thresholds.push_back(t);
      if (n == 0) state = kScan;
    }
  }
  return out;
}

TEST(ColorConfig, CmvisionReadsTheShippedColorsTxtAsWeDo) {
  const std::vector<ColorClass> ours = loadColorClasses(sourcePath("config/colors.txt"));
  const CmvisionReading cmvision = readLikeCmvision(sourcePath("config/colors.txt"));
  ASSERT_EQ(cmvision.names.size(), ours.size());
  ASSERT_EQ(cmvision.thresholds.size(), ours.size());
  for (size_t i = 0; i < ours.size(); ++i) {
    EXPECT_EQ(cmvision.names[i], ours[i].name);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_EQ(cmvision.thresholds[i][2 * ch], ours[i].min[ch]) << ours[i].name;
      EXPECT_EQ(cmvision.thresholds[i][2 * ch + 1], ours[i].max[ch]) << ours[i].name;
    }
  }
  // The rule this guards: a comment line inside a section hides the entries below it from
  // CMVision (we read all of them).
  const CmvisionReading commented = readLikeCmvision(sourcePath("test/data/colors_commented.txt"));
  EXPECT_TRUE(commented.names.empty());
  EXPECT_TRUE(commented.thresholds.empty());
  EXPECT_EQ(loadColorClasses(sourcePath("test/data/colors_commented.txt")).size(), 2u);
}

TEST(ColorConfig, BrokenCmvisionFilesNameTheLine) {
  // Found by fuzz_color_config: a number too long for a long made std::stol throw out_of_range.
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\n(255,0,99999999999999999999999) 0.5 2 red\n", "c.txt"); }),
            "c.txt:2: value 99999999999999999999999 is larger than 255");
  EXPECT_EQ(parseCmvisionColors("[Colors]\n(0255,000,0) 0.5 2 red\n[Thresholds]\n(0:0,00:10,1:2)\n", "c.txt")[0].display_rgb,
            (Channels{{255, 0, 0}}));
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\n(255,0,0) 0.5 2 red\n(0,255,0) 0.5 2 green\n[Thresholds]\n(1:2,3:4,5:6)\n", "c.txt"); }),
            "c.txt:3: colour 'green' has no line in [Thresholds]");
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\n(255,0,0) 0.5 2 red\n[Thresholds]\n(1:2,3:4)\n", "c.txt"); }),
            "c.txt:4: expected '(y0:y1,u0:u1,v0:v1)', got '(1:2,3:4)'");
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\n(255,0,0) 0.5 2 red\n[Thresholds]\n(1:2,3:4,5:600)\n", "c.txt"); }),
            "c.txt:4: value 600 is larger than 255");
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\n(255,0,0) 0.5 2 red\n[Thresholds]\n(9:2,3:4,5:6)\n", "c.txt"); }),
            "c.txt:4: range 9:2 has its low end above its high end");
  EXPECT_EQ(errorOf([] { parseCmvisionColors("[Colors]\nred\n", "c.txt"); }),
            "c.txt:2: expected '(r,g,b) merge expected name', got 'red'");
}

TEST(SceneConfig, ShippedSceneLoadsAndBrokenOnesFail) {
  const SceneConfig scene = loadSceneConfig(sourcePath("config/scene_default.yaml"));
  EXPECT_EQ(scene.width, 640);
  EXPECT_EQ(scene.boxes.size(), 10u);
  EXPECT_EQ(scene.boxes[2].name, "blue_1");
  EXPECT_DOUBLE_EQ(scene.boxes[2].sway_period_s, 6.0);
  EXPECT_EQ(errorOf([] { parseSceneConfig("camera: {height_m: -2}\n", "s.yaml"); }),
            "s.yaml:1: 'height_m' = -2 is out of range [0.030000, 100.000000]");
  EXPECT_NE(errorOf([] { parseSceneConfig("boxes:\n  - {name: a, hieght_m: 1}\n", "s.yaml"); })
                .find("s.yaml:2: unknown key 'hieght_m'"),
            std::string::npos);
  EXPECT_NE(errorOf([] { parseSceneConfig("camera: {hfov_deg: .nan}\n", "s.yaml"); }).find("s.yaml:1: 'hfov_deg'"),
            std::string::npos);
  // Found by fuzz_params: a flow mapping with a list as a key.
  EXPECT_EQ(errorOf([] { parseSceneConfig("lighting: {gain_start: 1.0, [1, 1, 1]}\n", "s.yaml"); }),
            "s.yaml:1: a key must be a plain name, not a list or mapping");
  EXPECT_NE(errorOf([] { parseSceneConfig("boxes: 3\n", "s.yaml"); }).find("'boxes' must be a list"),
            std::string::npos);
}

}  // namespace
}  // namespace rle_vision

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "rle_vision/io/color_config.h"
#include "io/yaml_reader.h"
#include "rle_vision/verify/blob_verifier.h"

namespace rle_vision {
namespace {

std::string stripComment(const std::string& line) {
  const size_t hash = line.find('#');
  return hash == std::string::npos ? line : line.substr(0, hash);
}

bool isBlank(const std::string& s) { return s.find_first_not_of(" \t\r") == std::string::npos; }

// True when the text is a CMVision colors.txt: it has a [Colors] section header.
bool looksLikeCmvision(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::string s = stripComment(line);
    if (s.find("[Colors]") != std::string::npos) return true;
    if (!isBlank(s)) return false;
  }
  return false;
}

// A class's verifier_file (relative to the colours file's folder) and min_score. Without min and
// max, the class's range is the one the verifier was trained on (kept in its file).
void parseVerifier(const std::string& origin, const YAML::Node& node, ColorClass* c) {
  using namespace yaml_reader;
  c->verifier_file = stringValue(origin, node, "verifier_file", "");
  c->min_score = number(origin, node, "min_score", 0.5, 0.0, 1.0);
  if (node["verifier_file"] && c->verifier_file.empty()) {
    fail(origin, node["verifier_file"], "class '" + c->name + "': verifier_file is empty (name a file, or leave the key out)");
  }
  if (c->verifier_file.empty()) {
    if (node["min_score"]) fail(origin, node["min_score"], "class '" + c->name + "' has min_score but no verifier_file");
    return;
  }
  const std::filesystem::path file(c->verifier_file);
  c->verifier_path = file.is_relative()
                         ? (std::filesystem::path(origin).parent_path() / file).lexically_normal().string()
                         : c->verifier_file;
  if (node["min"] || node["max"]) return;
  try {
    const ColorClass range = BlobVerifier::load(c->verifier_path).candidateRange();
    c->space = range.space;
    c->min = range.min;
    c->max = range.max;
  } catch (const std::exception& e) {
    fail(origin, node["verifier_file"], std::string("class '") + c->name + "' takes its range from its verifier: " + e.what());
  }
}

}  // namespace

std::vector<ColorClass> parseColorClassesYaml(const std::string& text, const std::string& origin) {
  using namespace yaml_reader;
  const YAML::Node root = parse(text, origin);
  if (!root.IsMap() || !root["classes"]) fail(origin, root, "expected a top-level 'classes:' list");
  checkKeys(origin, root, {"classes"});
  const YAML::Node list = root["classes"];
  if (!list.IsSequence()) fail(origin, list, "'classes' must be a list");
  std::vector<ColorClass> classes;
  for (const YAML::Node& node : list) {
    checkKeys(origin, node, {"name", "space", "min", "max", "display_rgb", "min_area_px", "verifier_file", "min_score"});
    ColorClass c;
    c.name = stringValue(origin, node, "name", "");
    if (c.name.empty()) fail(origin, node, "every class needs a non-empty 'name'");
    const std::string space = stringValue(origin, node, "space", "YUV");
    if (!parseColorSpace(space, &c.space)) {
      fail(origin, node["space"], "unknown colour space '" + space + "' (use YUV, RGB or HSV)");
    }
    if ((!node["min"] || !node["max"]) && !node["verifier_file"]) {
      fail(origin, node, "class '" + c.name + "' needs 'min' and 'max' (or a 'verifier_file' to take them from)");
    }
    if (!node["min"] != !node["max"]) fail(origin, node, "class '" + c.name + "' needs both 'min' and 'max' or neither");
    c.min = triple<uint8_t>(origin, node, "min", c.min, 0, 255, "integers 0..255");
    c.max = triple<uint8_t>(origin, node, "max", c.max, 0, 255, "integers 0..255");
    parseVerifier(origin, node, &c);
    c.display_rgb = triple<uint8_t>(origin, node, "display_rgb", c.display_rgb, 0, 255, "integers 0..255");
    c.min_area_px = static_cast<uint32_t>(number(origin, node, "min_area_px", 1, 1, 1e9));
    c.source = "config";
    classes.push_back(c);
  }
  const std::string problem = validateColorClasses(classes);
  if (!problem.empty()) fail(origin, list, problem);
  return classes;
}

std::vector<ColorClass> parseCmvisionColors(const std::string& text, const std::string& origin) {
  static const std::regex color_line(
      R"(^\s*\(\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*\)\s+([-+0-9.eE]+)\s+(\d+)\s+(\S+)\s*$)");
  static const std::regex threshold_line(
      R"(^\s*\(\s*(\d+)\s*:\s*(\d+)\s*,\s*(\d+)\s*:\s*(\d+)\s*,\s*(\d+)\s*:\s*(\d+)\s*\)\s*$)");
  enum class Section { None, Colors, Thresholds } section = Section::None;
  std::vector<ColorClass> classes;
  std::vector<int> class_lines;
  size_t thresholds = 0;
  std::istringstream in(text);
  std::string raw;
  int line_number = 0;
  auto byte = [&](const std::string& s) {  // s is all digits (the regexes say so), maybe very many
    const size_t first = std::min(s.find_first_not_of('0'), s.size());
    if (s.size() - first > 3 || (s.size() > first && std::stoi(s.substr(first)) > 255)) {
      yaml_reader::fail(origin, line_number, "value " + s + " is larger than 255");
    }
    return static_cast<uint8_t>(s.size() > first ? std::stoi(s.substr(first)) : 0);
  };
  while (std::getline(in, raw)) {
    ++line_number;
    const std::string line = stripComment(raw);
    if (isBlank(line)) continue;
    if (line.find("[Colors]") != std::string::npos) {
      section = Section::Colors;
      continue;
    }
    if (line.find("[Thresholds]") != std::string::npos) {
      section = Section::Thresholds;
      continue;
    }
    std::smatch m;
    if (section == Section::Colors) {
      if (!std::regex_match(line, m, color_line)) {
        yaml_reader::fail(origin, line_number, "expected '(r,g,b) merge expected name', got '" + line + "'");
      }
      ColorClass c;
      c.display_rgb = Channels{{byte(m[1]), byte(m[2]), byte(m[3])}};
      c.name = m[6];
      c.space = ColorSpace::YUV;
      classes.push_back(c);
      class_lines.push_back(line_number);
    } else if (section == Section::Thresholds) {
      if (!std::regex_match(line, m, threshold_line)) {
        yaml_reader::fail(origin, line_number, "expected '(y0:y1,u0:u1,v0:v1)', got '" + line + "'");
      }
      if (thresholds >= classes.size()) {
        yaml_reader::fail(origin, line_number, "more [Thresholds] lines than [Colors] lines");
      }
      ColorClass& c = classes[thresholds++];
      for (int ch = 0; ch < 3; ++ch) {
        c.min[ch] = byte(m[1 + 2 * ch]);
        c.max[ch] = byte(m[2 + 2 * ch]);
        if (c.min[ch] > c.max[ch]) {
          yaml_reader::fail(origin, line_number, "range " + std::string(m[1 + 2 * ch]) + ":" +
                                                     std::string(m[2 + 2 * ch]) + " has its low end above its high end");
        }
      }
    } else {
      yaml_reader::fail(origin, line_number, "text before the [Colors] section: '" + line + "'");
    }
  }
  if (classes.empty()) yaml_reader::fail(origin, line_number, "no colours in the [Colors] section");
  if (thresholds < classes.size()) {
    yaml_reader::fail(origin, class_lines[thresholds],
                      "colour '" + classes[thresholds].name + "' has no line in [Thresholds]");
  }
  const std::string problem = validateColorClasses(classes);
  if (!problem.empty()) yaml_reader::fail(origin, class_lines.front(), problem);
  return classes;
}

std::vector<ColorClass> loadColorClasses(const std::string& path) {
  const std::string text = yaml_reader::readFile(path);
  return looksLikeCmvision(text) ? parseCmvisionColors(text, path) : parseColorClassesYaml(text, path);
}

std::string colorClassesToYaml(const std::vector<ColorClass>& classes) {
  std::ostringstream out;
  auto list = [&](const Channels& c) {
    out << "[" << int(c[0]) << ", " << int(c[1]) << ", " << int(c[2]) << "]";
  };
  out << "classes:\n";
  for (const ColorClass& c : classes) {
    out << "  - name: " << c.name << "\n    space: " << toString(c.space) << "\n    min: ";
    list(c.min);
    out << "\n    max: ";
    list(c.max);
    out << "\n    display_rgb: ";
    list(c.display_rgb);
    out << "\n    min_area_px: " << c.min_area_px << "\n";
    if (!c.verifier_file.empty()) out << "    verifier_file: " << c.verifier_file << "\n    min_score: " << c.min_score << "\n";
  }
  return out.str();
}

std::string cmvisionColorsText(const std::vector<ColorClass>& classes) {
  std::ostringstream colors, thresholds;
  colors << "[Colors]\n";
  thresholds << "[Thresholds]\n";
  for (const ColorClass& c : classes) {
    if (c.space != ColorSpace::YUV) {
      throw std::invalid_argument("class '" + c.name + "' is in " + toString(c.space) +
                                  ": CMVision's colors.txt holds YUV ranges only");
    }
    colors << "(" << int(c.display_rgb[0]) << "," << int(c.display_rgb[1]) << "," << int(c.display_rgb[2])
           << ") 0.5000 1 " << c.name << "\n";
    thresholds << "(" << int(c.min[0]) << ":" << int(c.max[0]) << "," << int(c.min[1]) << ":" << int(c.max[1]) << ","
               << int(c.min[2]) << ":" << int(c.max[2]) << ")\n";
  }
  return colors.str() + "\n" + thresholds.str();
}

namespace {

std::vector<ColorClass> fileClassesWith(const std::string& path, const ColorClass& c) {
  std::vector<ColorClass> classes;
  if (std::ifstream(path).good()) classes = loadColorClasses(path);
  return mergeColorClass(std::move(classes), c);
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!(out << text)) throw std::invalid_argument("cannot write " + path);
}

}  // namespace

std::vector<ColorClass> mergeColorClass(std::vector<ColorClass> classes, const ColorClass& c) {
  auto same = std::find_if(classes.begin(), classes.end(), [&](const ColorClass& k) { return k.name == c.name; });
  if (same == classes.end()) {
    classes.push_back(c);
    return classes;
  }
  // The new range replaces the old; a verifier the class had stays with it.
  ColorClass replaced = c;
  replaced.verifier_file = same->verifier_file;
  replaced.verifier_path = same->verifier_path;
  replaced.min_score = same->min_score;
  *same = replaced;
  return classes;
}

void saveColorClassInto(const ColorClass& c, const std::string& yaml_path, const std::string& cmvision_path) {
  const std::string yaml = yaml_path.empty() ? "" : colorClassesToYaml(fileClassesWith(yaml_path, c));
  const std::string cmvision = cmvision_path.empty() ? "" : cmvisionColorsText(fileClassesWith(cmvision_path, c));
  if (!yaml_path.empty()) writeText(yaml_path, yaml);
  if (!cmvision_path.empty()) writeText(cmvision_path, cmvision);
}

}  // namespace rle_vision

// Small helpers over yaml-cpp that turn every problem into "origin:line: reason".
#pragma once

#include <array>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include <yaml-cpp/yaml.h>

#include "rle_vision/io/config_error.h"

namespace rle_vision {
namespace yaml_reader {

[[noreturn]] inline void fail(const std::string& origin, int line, const std::string& reason) {
  throw ConfigError(origin + ":" + std::to_string(line) + ": " + reason);
}

[[noreturn]] inline void fail(const std::string& origin, const YAML::Node& node, const std::string& reason) {
  fail(origin, node.Mark().line + 1, reason);
}

// The whole file, or a ConfigError that names it.
inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open the file (check the path and permissions)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline YAML::Node parse(const std::string& text, const std::string& origin) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    fail(origin, e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
}

// Rejects keys other than `allowed`: a misspelt parameter must not be silently ignored.
template <typename Names>
void checkKeys(const std::string& origin, const YAML::Node& map, const Names& allowed) {
  if (!map.IsMap()) fail(origin, map, "expected a mapping of key: value");
  for (const auto& entry : map) {
    // YAML allows lists and maps as keys ("? [a, b]: 1"); no parameter is named like that.
    if (!entry.first.IsScalar()) fail(origin, entry.first, "a key must be a plain name, not a list or mapping");
    const std::string key = entry.first.as<std::string>();
    bool known = false;
    for (const auto& a : allowed) known = known || key == a;
    if (!known) {
      std::string list;
      for (const auto& a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(origin, entry.first, "unknown key '" + key + "' (known keys: " + list + ")");
    }
  }
}
inline void checkKeys(const std::string& origin, const YAML::Node& map, std::initializer_list<const char*> allowed) {
  checkKeys<std::initializer_list<const char*>>(origin, map, allowed);
}

inline double number(const std::string& origin, const YAML::Node& map, const char* key,
                     double fallback, double lo = -INFINITY, double hi = INFINITY) {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  double value = 0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(origin, node, std::string("'") + key + "' must be a number");
  }
  if (!std::isfinite(value) || value < lo || value > hi) {
    fail(origin, node, std::string("'") + key + "' = " + node.as<std::string>() +
                           " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return value;
}

inline std::string stringValue(const std::string& origin, const YAML::Node& map, const char* key,
                        const std::string& fallback) {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  if (!node.IsScalar()) fail(origin, node, std::string("'") + key + "' must be a string");
  return node.as<std::string>();
}

template <typename T>
std::array<T, 3> triple(const std::string& origin, const YAML::Node& map, const char* key,
                        const std::array<T, 3>& fallback, double lo, double hi,
                        const char* what) {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  if (!node.IsSequence() || node.size() != 3) {
    fail(origin, node, std::string("'") + key + "' must be a list of 3 " + what);
  }
  std::array<T, 3> out{};
  for (size_t i = 0; i < 3; ++i) {
    double v = 0;
    try {
      v = node[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(origin, node, std::string("'") + key + "' must be a list of 3 " + what);
    }
    if (!std::isfinite(v) || v < lo || v > hi || (std::is_integral<T>::value && v != std::floor(v))) {
      fail(origin, node, std::string("'") + key + "' must be a list of 3 " + what);
    }
    out[i] = static_cast<T>(v);
  }
  return out;
}

}  // namespace yaml_reader
}  // namespace rle_vision

// A nodelet's start-up settings, the RLE_<NODE>_SETTING lines of its parameter table
// (include/rle_vision/params/): each read once from the private namespace with its type and
// limits checked. A problem is reported in `problems` (the node logs it: "NAME must be of type
// int, got 'many': using the default 1") and the default, or the nearest limit, is used.
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace rle_vision {
namespace node_settings {

inline std::string given(XmlRpc::XmlRpcValue& value) {
  // A launch file's "nan" or "many" arrives as a string; show it as the user wrote it.
  return value.getType() == XmlRpc::XmlRpcValue::TypeString ? static_cast<std::string>(value) : value.toXml();
}

template <typename T>
std::string text(const T& value) {
  std::ostringstream out;
  out << std::boolalpha << value;
  return out.str();
}

// The value given for `key`, or false when none is (the default stays).
inline bool lookUp(const ros::NodeHandle& pnh, const std::string& key, XmlRpc::XmlRpcValue* value) {
  return pnh.getParam(key, *value);
}

template <typename T>
void wrongType(const ros::NodeHandle& pnh, const std::string& key, const char* type, XmlRpc::XmlRpcValue& value,
               const T& fallback, std::vector<std::string>* problems) {
  problems->push_back(pnh.resolveName(key) + " must be of type " + type + ", got '" + given(value) +
                      "': using the default " + text(fallback));
}

}  // namespace node_settings

inline void readSetting(const ros::NodeHandle& pnh, const std::string& key, bool* value, double, double,
                        std::vector<std::string>* problems) {
  XmlRpc::XmlRpcValue v;
  if (!node_settings::lookUp(pnh, key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return node_settings::wrongType(pnh, key, "bool", v, *value, problems);
  *value = static_cast<bool>(v);
}

inline void readSetting(const ros::NodeHandle& pnh, const std::string& key, std::string* value, double, double,
                        std::vector<std::string>* problems) {
  XmlRpc::XmlRpcValue v;
  if (!node_settings::lookUp(pnh, key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return node_settings::wrongType(pnh, key, "string", v, *value, problems);
  *value = static_cast<std::string>(v);
}

inline void readSetting(const ros::NodeHandle& pnh, const std::string& key, int* value, double lo, double hi,
                        std::vector<std::string>* problems) {
  XmlRpc::XmlRpcValue v;
  if (!node_settings::lookUp(pnh, key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) return node_settings::wrongType(pnh, key, "int", v, *value, problems);
  const int x = static_cast<int>(v);
  *value = std::min(std::max(x, static_cast<int>(lo)), static_cast<int>(hi));
  if (*value != x) {
    problems->push_back(pnh.resolveName(key) + " = " + std::to_string(x) + " is outside [" + node_settings::text(lo) + ", " +
                        node_settings::text(hi) + "]: using " + std::to_string(*value));
  }
}

inline void readSetting(const ros::NodeHandle& pnh, const std::string& key, double* value, double lo, double hi,
                        std::vector<std::string>* problems) {
  XmlRpc::XmlRpcValue v;
  if (!node_settings::lookUp(pnh, key, &v)) return;
  double x = 0;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    x = static_cast<double>(v);
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    x = static_cast<int>(v);
  } else {
    return node_settings::wrongType(pnh, key, "double", v, *value, problems);
  }
  if (!std::isfinite(x)) {
    problems->push_back(pnh.resolveName(key) + " is not a finite number: using the default " + node_settings::text(*value));
    return;
  }
  *value = std::min(std::max(x, lo), hi);
  if (*value != x) {
    problems->push_back(pnh.resolveName(key) + " = " + node_settings::text(x) + " is outside [" + node_settings::text(lo) +
                        ", " + node_settings::text(hi) + "]: using " + node_settings::text(*value));
  }
}

}  // namespace rle_vision

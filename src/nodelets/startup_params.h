// Checks a nodelet's start-up parameters (launch file, rosparam) against its dynamic_reconfigure
// description before the server silently clamps them, so the user learns that "-5" became "1"
// and that a misspelt type was ignored.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <boost/any.hpp>
#include <ros/node_handle.h>

namespace rle_vision {

template <class Config>
std::vector<std::string> startupParamProblems(const ros::NodeHandle& pnh) {
  std::vector<std::string> problems;
  Config raw = Config::__getDefault__();
  const Config& min = Config::__getMin__();
  const Config& max = Config::__getMax__();
  for (const auto& description : Config::__getParamDescriptions__()) {
    const std::string& name = description->name;
    XmlRpc::XmlRpcValue value;
    if (!pnh.getParam(name, value)) continue;
    const std::string where = pnh.resolveName(name);
    const std::string& type = description->type;
    const bool type_ok = (type == "double" && (value.getType() == XmlRpc::XmlRpcValue::TypeDouble ||
                                               value.getType() == XmlRpc::XmlRpcValue::TypeInt)) ||
                         (type == "int" && value.getType() == XmlRpc::XmlRpcValue::TypeInt) ||
                         (type == "bool" && value.getType() == XmlRpc::XmlRpcValue::TypeBoolean) ||
                         (type == "str" && value.getType() == XmlRpc::XmlRpcValue::TypeString);
    if (!type_ok) {
      // A launch file's "nan" or "1e" arrives as a string; show it as the user wrote it.
      const std::string given = value.getType() == XmlRpc::XmlRpcValue::TypeString
                                    ? static_cast<std::string>(value)
                                    : value.toXml();
      problems.push_back(where + " must be of type " + type + ", got '" + given + "': using the default");
      continue;
    }
    description->fromServer(pnh, raw);
    boost::any v, lo, hi;
    description->getValue(raw, v);
    description->getValue(min, lo);
    description->getValue(max, hi);
    std::ostringstream text;
    if (type == "double") {
      const double x = boost::any_cast<double>(v), a = boost::any_cast<double>(lo), b = boost::any_cast<double>(hi);
      if (!std::isfinite(x)) {
        text << where << " is not a finite number (" << x << "): the node keeps its default";
      } else if (x < a || x > b) {
        text << where << " = " << x << " is outside [" << a << ", " << b << "]: using " << (x < a ? a : b);
      }
    } else if (type == "int") {
      const int x = boost::any_cast<int>(v), a = boost::any_cast<int>(lo), b = boost::any_cast<int>(hi);
      if (x < a || x > b) text << where << " = " << x << " is outside [" << a << ", " << b << "]: using " << (x < a ? a : b);
    }
    if (!text.str().empty()) problems.push_back(text.str());
  }
  return problems;
}

}  // namespace rle_vision

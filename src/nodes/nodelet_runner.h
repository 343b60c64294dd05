// Runs one nodelet in a process of its own, so each part of the graph can also run as a plain
// node (e.g. on another machine). Command-line remappings and private parameters apply.
#pragma once

#include <string>

#include <nodelet/loader.h>
#include <ros/ros.h>

namespace rle_vision {

inline int runNodelet(int argc, char** argv, const std::string& default_name, const std::string& type) {
  ros::init(argc, argv, default_name);
  nodelet::Loader loader(false);
  const nodelet::M_string remappings(ros::names::getRemappings());
  const nodelet::V_string my_argv(argv + 1, argv + argc);
  if (!loader.load(ros::this_node::getName(), type, remappings, my_argv)) {
    ROS_FATAL("could not start %s (see the error above)", type.c_str());
    return 1;
  }
  ros::spin();
  return 0;
}

}  // namespace rle_vision

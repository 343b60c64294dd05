# Included by find_package(catkin COMPONENTS rle_vision) in packages that build against
# rle_vision (catkin_package CFG_EXTRAS): its public headers need C++17 (std::optional, inline
# variables), which GCC 9 (Ubuntu 20.04, ROS Noetic) does not use by default (gnu++14). A
# package asking for an older standard gets C++17; one asking for a newer keeps it.
if(NOT CMAKE_CXX_STANDARD OR CMAKE_CXX_STANDARD EQUAL 98 OR CMAKE_CXX_STANDARD LESS 17)
  set(CMAKE_CXX_STANDARD 17)
  set(CMAKE_CXX_STANDARD_REQUIRED ON)
endif()

#!/usr/bin/env bash
# The ROS-free core on its own: configures src/core with plain CMake (no catkin) in a
# throw-away build folder, builds it with -Werror, runs its unit tests with CTest, installs it
# into a throw-away prefix and builds a small program against the installed package, and
# checks that nothing in the build came from ROS: no header of a ROS package was compiled in
# (the compiler's dependency lists) and no ROS library is linked. Prints "N passed, M failed".
set -uo pipefail
source "$(dirname "$0")/env.sh"
build=$(mktemp -d /tmp/rle_vision_core.XXXXXX)
trap 'rm -rf "$build"' EXIT
CHECK_SUITE=core_without_ros
CHECK_LOG_DIR="$build/logs" && mkdir -p "$CHECK_LOG_DIR"
source "$(dirname "$0")/checks.sh"
check configure cmake -S "$ROOT/src/core" -B "$build/core" -DCMAKE_BUILD_TYPE=Release -DRLE_VISION_WERROR=ON
check build cmake --build "$build/core" -j"${JOBS:-2}"
check ctest sh -c "cd '$build/core' && ctest --output-on-failure"  # CMake 3.16 (Ubuntu 20.04): no --test-dir
# Every header compiled into the core, from the compiler's dependency files: none may belong
# to a ROS package (Debian installs ROS headers under /usr/include, so an include of one would
# compile here and fail on a machine without ROS).
ros_headers() {
  local headers
  headers=$(find "$build/core" -name "*.d" -o -name "compiler_depend.make" -o -name "depend.make" |
            xargs cat 2>/dev/null | tr ' \\' '\n\n' | grep -E '^/usr/include/[^ ]+\.h(pp)?$' | sort -u)
  [[ -n "$headers" ]] || { echo "no dependency lists found"; return 1; }
  local owners
  owners=$(echo "$headers" | xargs dpkg -S 2>/dev/null | cut -d: -f1 | tr ',' '\n' | sed 's/^ *//' | sort -u)
  local ros
  ros=$(echo "$owners" | grep -E '^(ros-|libros|python3-ros|catkin|lib(cv-bridge|image-transport|nodelet|pluginlib|tf2|message-filters|dynamic-reconfigure|diagnostic|class-loader|xmlrpcpp|rosconsole|actionlib|std-msgs|sensor-msgs|geometry-msgs)|.*-msgs-dev)' || true)
  echo "header packages: $(echo $owners)"
  [[ -z "$ros" ]] || { echo "ROS headers in the core's build: $ros"; return 1; }
}
check no_ros_headers ros_headers
no_ros_libraries() {
  ! ldd "$build/core/test_core" "$build/core/rle_vision_detect" | grep -E 'libros|roscpp|rosconsole|cv_bridge|tf2|xmlrpc'
}
check no_ros_libraries no_ros_libraries
check install cmake --install "$build/core" --prefix "$build/prefix"
# A dependant finds the installed package, with OpenCV and Eigen, and the CLI its colours.
mkdir -p "$build/user"
cat >"$build/user/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.10)
project(user CXX)
set(CMAKE_CXX_STANDARD 14)  # GCC 9's default: the core's targets must raise it to C++17
find_package(rle_vision_core REQUIRED)
add_executable(user user.cpp)
target_link_libraries(user rle_vision::config rle_vision::core)
CMAKE
cat >"$build/user/user.cpp" <<'CPP'
#include <Eigen/Core>
#include "rle_vision/io/color_config.h"
#include "rle_vision/io/data_files.h"
#include "rle_vision/common/latest_mailbox.h"
#include "rle_vision/landmark/landmark_detector.h"
int main() {
  rle_vision::LatestMailbox<int> mailbox;  // std::optional inside: C++17
  mailbox.put(1);
  rle_vision::LandmarkDetector detector;
  const Eigen::Vector2d unused(0, 0);
  return rle_vision::loadColorClasses(rle_vision::packageDataFile("config/colors.yaml")).empty() ? 1 : 0;
}
CPP
check dependant_builds sh -c "cmake -S '$build/user' -B '$build/user/build' -DCMAKE_PREFIX_PATH='$build/prefix' && cmake --build '$build/user/build'"
check installed_cli_finds_its_colours sh -c "cd / && '$build/prefix/bin/rle_vision_detect' --help |
  grep -qx 'Default colours file: $build/prefix/bin/../share/rle_vision/config/colors.yaml' &&
  '$build/prefix/bin/rle_vision_detect' '$ROOT/docs/rviz_screenshot.png' | grep -q '\"blobs\"'"
finish_checks

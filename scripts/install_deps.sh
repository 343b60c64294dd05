#!/usr/bin/env bash
# Installs the Debian packages rle_vision needs that are not installed yet (non-interactive,
# through sudo when not root). Debian bookworm ships ROS 1 under /usr.
set -euo pipefail

packages=(
  build-essential cmake catkin ros-core-dev
  libroscpp-dev libnodelet-dev libnodeletlib-dev libnodeletlib-tools pluginlib-dev
  libcv-bridge-dev libimage-transport-dev libmessage-filters-dev libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev libtf2-dev
  libopencv-dev libopencv-contrib-dev libeigen3-dev libyaml-cpp-dev python3-opencv python3-numpy
  ros-sensor-msgs ros-geometry-msgs ros-visualization-msgs ros-std-msgs
  python3-sensor-msgs python3-geometry-msgs python3-std-msgs python3-visualization-msgs
  python3-rospy python3-yaml python3-rostest python3-nose librostest-dev python3-roslaunch python3-rostopic python3-rosnode
  rosbash python3-roslib
  librosbag-dev python3-rosbag python3-std-srvs ros-message-generation ros-message-runtime
  libdiagnostic-updater-dev python3-diagnostic-msgs libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libbenchmark-dev libgtest-dev
  rviz xvfb x11-apps
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "[deps] all ${#packages[@]} Debian packages present"
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "[deps] installing ${#missing[@]} missing Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"

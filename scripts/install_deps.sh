#!/usr/bin/env bash
# Installs what rle_vision needs that is not installed yet (non-interactive, through sudo when
# not root).
# - Debian bookworm ships ROS 1 under /usr: the Debian packages below.
# - Ubuntu 20.04 with ROS Noetic (/opt/ros/$ROS_DISTRO present): rosdep installs what package.xml
#   declares, and apt the non-ROS tools by their Ubuntu names (scripts/dependencies.tsv, "tool");
#   no Debian ROS package is mixed in (Debian's catkin conflicts with ROS's python3-catkin-pkg).
#
#   scripts/install_deps.sh [--dry-run] [--distro NAME]
#   --dry-run      print the commands instead of running them
#   --distro NAME  take the /opt/ros/NAME branch (default: $ROS_DISTRO when /opt/ros/$ROS_DISTRO
#                  exists, else the only /opt/ros/*; none: Debian)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
dry_run=0
distro="${ROS_DISTRO:-}"
while (( $# > 0 )); do
  case "$1" in
    --dry-run) dry_run=1 ;;
    --distro) distro="${2:?--distro needs a name}"; shift ;;
    *) echo "usage: scripts/install_deps.sh [--dry-run] [--distro NAME]" >&2; exit 2 ;;
  esac
  shift
done
if [[ -z "$distro" ]]; then
  found=(/opt/ros/*/setup.bash)
  [[ ${#found[@]} -eq 1 && -f "${found[0]}" ]] && distro=$(basename "$(dirname "${found[0]}")")
fi
[[ -n "$distro" && ! -d "/opt/ros/$distro" && $dry_run -eq 0 ]] && distro=""

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
run() {
  if (( dry_run )); then echo "+ $*"; else "$@"; fi
}

if [[ -n "$distro" ]]; then
  # ROS from /opt/ros (Ubuntu 20.04 + Noetic): rosdep for package.xml, apt for the tools.
  tools=$(python3 "$ROOT/scripts/check_dependencies.py" --tools)
  echo "[deps] ROS $distro from /opt/ros/$distro: rosdep installs package.xml's dependencies; apt the tools: $tools"
  export DEBIAN_FRONTEND=noninteractive
  run $sudo apt-get update -q
  # shellcheck disable=SC2086
  run $sudo apt-get install -y -q --no-install-recommends python3-rosdep $tools
  [[ -f /etc/ros/rosdep/sources.list.d/20-default.list ]] || run $sudo rosdep init
  run rosdep update --rosdistro "$distro"
  run rosdep install --from-paths "$ROOT" --ignore-src --rosdistro "$distro" -y
  exit 0
fi

debian_packages=(
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
  rviz xvfb x11-apps xdotool
)

missing=()
for p in "${debian_packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "[deps] all ${#debian_packages[@]} Debian packages present"
  exit 0
fi

echo "[deps] installing ${#missing[@]} missing Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
run $sudo apt-get update -q
run $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"

#!/usr/bin/env bash
# The set-up itself: package.xml declares every package scripts/install_deps.sh installs
# (scripts/dependencies.tsv), and the Ubuntu 20.04 + Noetic branch, as a dry run (this machine
# has no /opt/ros): it sources nothing Debian-only, installs with rosdep from package.xml and
# the tools by name, and names no Debian ROS package. Prints "N passed, M failed".
set -uo pipefail
source "$(dirname "$0")/env.sh"
CHECK_SUITE=setup
CHECK_LOG_DIR="$WS/setup_logs" && mkdir -p "$CHECK_LOG_DIR"
source "$(dirname "$0")/checks.sh"
check package_xml_declares_the_set_up python3 "$ROOT/scripts/check_dependencies.py"
noetic_dry_run() {
  local out
  out=$(ROS_DISTRO= "$ROOT/scripts/install_deps.sh" --dry-run --distro noetic) || return 1
  echo "$out"
  grep -q "^+ .*rosdep install --from-paths $ROOT --ignore-src --rosdistro noetic -y$" <<<"$out" || {
    echo "no rosdep install from package.xml"; return 1; }
  grep -q "^+ .*apt-get install .* python3-rosdep .*xvfb" <<<"$out" || { echo "the tools are not installed by name"; return 1; }
  # Debian's own ROS packages must not be installed next to /opt/ros.
  if grep -E "^\+ .*apt-get install" <<<"$out" | grep -qwE "catkin|ros-core-dev|libroscpp-dev|rviz|python3-rospy"; then
    echo "a Debian ROS package in the Noetic branch"; return 1
  fi
}
check noetic_dry_run noetic_dry_run
finish_checks

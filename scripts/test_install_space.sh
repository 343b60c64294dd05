#!/usr/bin/env bash
# The package as installed: `catkin_make install` into the workspace's install space, then, in
# a fresh shell that sources only install/setup.bash (no devel space, no source tree on the
# path), `roslaunch rle_vision demo.launch` for a few seconds; passes when the demo's summary
# shows blobs, lines and a horizon. Prints "N passed, M failed".
set -uo pipefail
source "$(dirname "$0")/env.sh"
CHECK_SUITE=install_space
CHECK_LOG_DIR="$WS/install_space_logs" && mkdir -p "$CHECK_LOG_DIR"
source "$(dirname "$0")/checks.sh"
check catkin_make_install sh -c "cd '$WS' && catkin_make install -j'${JOBS:-2}'"
demo_from_install_space() {
  env -i HOME="$HOME" PATH=/usr/bin:/bin ROS_HOME="$ROS_HOME" bash --noprofile --norc -c "
    set -e
    source '$WS/install/setup.bash'
    cd /
    case \"\$(rospack find rle_vision)\" in '$WS/install/'*) ;; *) echo 'rle_vision is not found in the install space'; exit 1;; esac
    timeout 60 roslaunch --no-summary rle_vision demo.launch duration_s:=8 rviz:=false realtime_priority:=0
  " 2>&1 | tee "$CHECK_LOG_DIR/demo_output.log"
  local summary
  summary=$(grep -E 't= *[5-8]s' "$CHECK_LOG_DIR/demo_output.log" | tail -1)
  echo "summary: $summary"
  echo "$summary" | grep -qE 'blobs: [a-z]' && echo "$summary" | grep -qE ' [1-9][0-9.]* lines/frame' &&
    echo "$summary" | grep -qE 'horizon [1-9][0-9]*%'
}
check demo_launch_from_install_space demo_from_install_space
finish_checks

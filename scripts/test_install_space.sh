#!/usr/bin/env bash
# The package as installed: `catkin_make install` into the workspace's install space, then, in
# a fresh shell that sources only install/setup.bash (no devel space, no source tree on the
# path), `roslaunch rle_vision demo.launch` until its summary shows blobs, lines and a horizon
# in one second (passes; at most 3 minutes). Prints "N passed, M failed".
set -uo pipefail
source "$(dirname "$0")/env.sh"
CHECK_SUITE=install_space
CHECK_LOG_DIR="$WS/install_space_logs" && mkdir -p "$CHECK_LOG_DIR"
source "$(dirname "$0")/checks.sh"
check catkin_make_install sh -c "cd '$WS' && catkin_make install -j'${JOBS:-2}'"
# Waits for the summary line rather than a fixed run: a slow machine may take many seconds to
# start the demo, a fast one shows all three in its first seconds.
demo_from_install_space() {
  local log="$CHECK_LOG_DIR/demo_output.log"
  setsid env -i HOME="$HOME" PATH=/usr/bin:/bin ROS_HOME="$ROS_HOME" bash --noprofile --norc -c "
    set -e
    source '$WS/install/setup.bash'
    cd /
    case \"\$(rospack find rle_vision)\" in '$WS/install/'*) ;; *) echo 'rle_vision is not found in the install space'; exit 1;; esac
    exec roslaunch --no-summary rle_vision demo.launch duration_s:=180 rviz:=false realtime_priority:=0
  " >"$log" 2>&1 &
  local demo=$! summary="" seconds
  for ((seconds = 0; seconds < 180; seconds++)); do
    # A summary second with blobs, lines and a horizon.
    summary=$(grep -E 't= *[0-9]+s' "$log" | grep -E 'blobs: [a-z]' | grep -E ' [1-9][0-9.]* lines/frame' |
              grep -E 'horizon [1-9][0-9]*%' | head -1)
    [[ -n "$summary" ]] || ! kill -0 "$demo" 2>/dev/null && break
    sleep 1
  done
  kill -INT -- -"$demo" 2>/dev/null
  wait "$demo" 2>/dev/null
  cat "$log"
  echo "summary: ${summary:-none with blobs, lines and a horizon in ${seconds} s}"
  [[ -n "$summary" ]]
}
check demo_launch_from_install_space demo_from_install_space
finish_checks

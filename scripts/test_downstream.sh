#!/usr/bin/env bash
# A user's package built against rle_vision, as catkin finds it: test/downstream (C++14 asked,
# public headers that need C++17, the core linked) in a workspace of its own chained onto the
# devel space (`devel`) or the install space (`install`, after `catkin_make install`); then run.
# Prints "N passed, M failed".
#
#   scripts/test_downstream.sh devel|install
set -uo pipefail
source "$(dirname "$0")/env.sh"
space=${1:-devel}
CHECK_SUITE=downstream_$space
CHECK_LOG_DIR="$WS/downstream_logs_$space" && mkdir -p "$CHECK_LOG_DIR"
source "$(dirname "$0")/checks.sh"
ws=$(mktemp -d /tmp/rle_vision_downstream.XXXXXX)
trap 'rm -rf "$ws"' EXIT
mkdir -p "$ws/src" && cp -r "$ROOT/test/downstream" "$ws/src/"
# A fresh shell that sees only that space: what a user's terminal would.
in_space() {
  env -i HOME="$HOME" PATH=/usr/bin:/bin ROS_HOME="$ROS_HOME" bash --noprofile --norc -c "
    set -e
    source '$WS/$space/setup.bash'
    cd '$ws'
    $1"
}
if [[ "$space" == install ]]; then
  check catkin_make_install sh -c "cd '$WS' && catkin_make install -j'${JOBS:-2}'"
fi
check builds_against_the_${space}_space in_space "catkin_make -j'${JOBS:-2}'"
check finds_a_blob in_space "source devel/setup.bash && devel/lib/rle_vision_downstream_test/downstream_blobs \"\$(rospack find rle_vision)/config/colors.yaml\""
finish_checks

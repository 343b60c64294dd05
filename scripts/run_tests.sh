#!/usr/bin/env bash
# Builds and runs every test (gtest for the core, rostest for nodelets and launch files), then
# prints "N passed, M failed" as the last line; exits non-zero on any failure.
set -uo pipefail
source "$(dirname "$0")/env.sh"
source_workspace
results="$WS/build/test_results"
rm -rf "$results"
extra=()
cd "$WS"
if ! catkin_make run_tests -j"${JOBS:-2}"; then
  extra+=("catkin_make run_tests exited with an error (see above)")
fi
exec python3 "$ROOT/scripts/summarize_tests.py" "$results" "${extra[@]}"

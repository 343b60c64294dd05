#!/usr/bin/env bash
# Builds and runs every test (gtest for the core, rostest for nodelets and launch files, the code
# shape check, the core built without ROS, the install space, the docs' commands), then prints "N passed,
# M failed" as the last line; exits non-zero on any failure.
set -uo pipefail
source "$(dirname "$0")/env.sh"
source_workspace
results="$WS/build/test_results"
rm -rf "$results"
extra=()
cd "$WS"
# The test binaries are built first with all jobs; the tests then run one at a time, since the
# rostests run 30-Hz pipelines that must not compete for the 2 cores with each other.
if ! catkin_make tests -j"${JOBS:-2}"; then
  extra+=("building the tests failed (see above)")
fi
if ! catkin_make run_tests -j1; then
  extra+=("catkin_make run_tests exited with an error (see above)")
fi
# The calibration window, driven with the mouse and keys under a virtual X server.
JUNIT_DIR="$results/checks" "$ROOT/test/gui/test_calibrate_gui.sh" || true
# The core built on its own with plain CMake (no ROS in it), and the package's install space.
JUNIT_DIR="$results/checks" "$ROOT/scripts/test_core_plain.sh" || true
JUNIT_DIR="$results/checks" "$ROOT/scripts/test_install_space.sh" || true
# The set-up: package.xml declares what it installs; its Noetic branch, as a dry run.
JUNIT_DIR="$results/checks" "$ROOT/scripts/test_setup.sh" || true
# A user's package built against the devel space and against the install space.
JUNIT_DIR="$results/checks" "$ROOT/scripts/test_downstream.sh" devel || true
JUNIT_DIR="$results/checks" "$ROOT/scripts/test_downstream.sh" install || true
# Every shell command block of README.md and docs/*.md, as a new user would run it, and the
# generated tables of docs/ (figures, parameters).
"$ROOT/scripts/test_readme.sh" --junit "$results/checks/readme.xml" || true
exec python3 "$ROOT/scripts/summarize_tests.py" "$results" "${extra[@]}"

#!/usr/bin/env bash
# Runs the benchmarks (one thread pinned to one CPU, against OpenCV and memcpy on the same
# frames, in one run), writes their JSON results to bench/measured/ and prints them beside the
# committed figures; RECORD=1 writes bench/results/ and the docs' tables instead.
set -euo pipefail
source "$(dirname "$0")/env.sh"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_bench_tracker rle_vision_bench_landmark >/dev/null
# A real robot frame for the tracker timing: the first folder of make eval's ball frames.
ball_folder=$(find "${EVAL_BALLS_DIR:-$ROOT/../shared/data/robocup_msl/20220716}" -mindepth 1 -maxdepth 1 -type d 2>/dev/null | sort | head -1 || true)
"$WS/devel/lib/rle_vision/rle_vision_bench_tracker" "$ROOT" "$RESULTS_DIR/tracker.json" ${ball_folder:+"$ball_folder"}
echo
# Real frames for the landmark timing: make eval's UAV folder and, the robot's own kind of frame,
# its indoor MSL frames, when they are there.
real_dir="${EVAL_DIR:-$ROOT/../shared/data/uav_horizon}"
robot_dir="${EVAL_NEGATIVES_DIR:-$ROOT/../shared/data/robocup_msl}"
real_frames=("")
[[ -f "$real_dir/label.csv" ]] && real_frames=("$real_dir")
[[ -d "$robot_dir" ]] && real_frames+=("$robot_dir")
"$WS/devel/lib/rle_vision/rle_vision_bench_landmark" "$ROOT" "$RESULTS_DIR/landmark.json" "${real_frames[@]}"
echo
report_results tracker landmark

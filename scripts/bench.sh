#!/usr/bin/env bash
# Runs the benchmarks (one thread pinned to one CPU, against OpenCV and memcpy on the same
# frames, in one run) and writes their JSON results to bench/results/.
set -euo pipefail
source "$(dirname "$0")/env.sh"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_bench_tracker rle_vision_bench_landmark >/dev/null
mkdir -p "$ROOT/bench/results"
# A real robot frame for the tracker timing: the first folder of make eval's ball frames.
ball_folder=$(find "${EVAL_BALLS_DIR:-$ROOT/../shared/data/robocup_msl/20220716}" -mindepth 1 -maxdepth 1 -type d 2>/dev/null | sort | head -1 || true)
"$WS/devel/lib/rle_vision/rle_vision_bench_tracker" "$ROOT" "$ROOT/bench/results/tracker.json" ${ball_folder:+"$ball_folder"}
echo
# Real frames for the landmark timing: make eval's folder, when it is there.
real_dir="${EVAL_DIR:-$ROOT/../shared/data/uav_horizon}"
real_frames=()
[[ -f "$real_dir/label.csv" ]] && real_frames=("$real_dir")
"$WS/devel/lib/rle_vision/rle_vision_bench_landmark" "$ROOT" "$ROOT/bench/results/landmark.json" "${real_frames[@]}"

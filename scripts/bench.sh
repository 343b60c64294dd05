#!/usr/bin/env bash
# Runs the benchmarks (one thread pinned to one CPU, against OpenCV and memcpy on the same
# frames, in one run) and writes their JSON results to bench/results/.
set -euo pipefail
source "$(dirname "$0")/env.sh"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_bench_tracker rle_vision_bench_landmark >/dev/null
mkdir -p "$ROOT/bench/results"
"$WS/devel/lib/rle_vision/rle_vision_bench_tracker" "$ROOT" "$ROOT/bench/results/tracker.json"
echo
"$WS/devel/lib/rle_vision/rle_vision_bench_landmark" "$ROOT" "$ROOT/bench/results/landmark.json"

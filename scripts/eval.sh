#!/usr/bin/env bash
# make eval: accuracy on real labelled frames (EVAL_DIR, default ../shared/data/uav_horizon when
# it exists), ours against OpenCV line detectors in one run, one thread. Writes
# bench/results/eval_horizon.json, then checks it against bench/eval_floor.json (the best
# figures landed so far: a regression fails; see scripts/check_eval_floor.py).
set -euo pipefail
source "$(dirname "$0")/env.sh"
dir="${EVAL_DIR:-$ROOT/../shared/data/uav_horizon}"
if [[ ! -f "$dir/label.csv" ]]; then
  echo "[eval] no labelled frames at $dir (label.csv): nothing evaluated (EVAL_DIR=... for another folder)"
  exit 0
fi
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_eval_horizon >/dev/null
mkdir -p "$ROOT/bench/results"
"$WS/devel/lib/rle_vision/rle_vision_eval_horizon" "$dir" --json "$ROOT/bench/results/eval_horizon.json"
if [[ -z "${EVAL_DIR:-}" ]]; then
  python3 "$ROOT/scripts/check_eval_floor.py" "$ROOT/bench/results/eval_horizon.json" "$ROOT/bench/eval_floor.json"
fi

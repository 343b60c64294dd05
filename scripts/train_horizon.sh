#!/usr/bin/env bash
# make train-horizon: fits the horizon model on every labelled frame make eval scores (the UAV
# folders, the indoor robot frames without a horizon, the simulator's scenes) and writes it to
# config/horizon_model.yaml, which the package ships (commit it). make eval then reports what
# the same fitting gives on frames it did not see (each flight, date or scene held out).
set -euo pipefail
source "$(dirname "$0")/env.sh"
data="${EVAL_DATA_DIR:-$ROOT/../shared/data}"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_eval_horizon >/dev/null
dirs=()
for dir in "$data/uav_horizon" "$data/uav_horizon_clouds"; do [[ -f "$dir/label.csv" ]] && dirs+=("$dir"); done
if (( ${#dirs[@]} == 0 )); then
  echo "[train-horizon] no labelled horizon frames under $data (EVAL_DATA_DIR=...)"
  exit 1
fi
"$WS/devel/lib/rle_vision/rle_vision_eval_horizon" "${dirs[@]}" --negatives "$data/robocup_msl" --sim-frames 40 \
  --train-output "$ROOT/config/horizon_model.yaml"

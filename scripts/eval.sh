#!/usr/bin/env bash
# make eval: accuracy on real labelled frames, ours against OpenCV in one run, one thread.
#  - Horizon: EVAL_DIR (default ../shared/data/uav_horizon when it exists), label.csv; writes
#    eval_horizon.json.
#  - Balls: EVAL_BALLS_DIR (default ../shared/data/robocup_msl/20220716 when it exists), folders
#    of images with YOLO labels (ball class EVAL_BALL_CLASS, default 0): the class is calibrated
#    on the first folder (sorted) and scored on the others; writes eval_balls.json.
# The JSON goes to bench/measured/ (RECORD=1: bench/results/, and the docs' tables rewritten).
# On the default data both are checked against bench/eval_floor.json (the best figures landed
# so far: a regression fails; see scripts/check_eval_floor.py).
set -euo pipefail
source "$(dirname "$0")/env.sh"
horizon_dir="${EVAL_DIR:-$ROOT/../shared/data/uav_horizon}"
balls_dir="${EVAL_BALLS_DIR:-$ROOT/../shared/data/robocup_msl/20220716}"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_eval_horizon rle_vision_eval_balls >/dev/null
checked=()
if [[ -f "$horizon_dir/label.csv" ]]; then
  "$WS/devel/lib/rle_vision/rle_vision_eval_horizon" "$horizon_dir" --json "$RESULTS_DIR/eval_horizon.json"
  if [[ -z "${EVAL_DIR:-}" ]]; then checked+=(--horizon "$RESULTS_DIR/eval_horizon.json"); fi
else
  echo "[eval] no labelled horizon frames at $horizon_dir (label.csv): horizon not evaluated (EVAL_DIR=... for another folder)"
fi
mapfile -t folders < <(find "$balls_dir" -mindepth 1 -maxdepth 1 -type d 2>/dev/null | sort)
if (( ${#folders[@]} >= 2 )); then
  "$WS/devel/lib/rle_vision/rle_vision_eval_balls" --calibrate "${folders[0]}" --label-class "${EVAL_BALL_CLASS:-0}" \
    --json "$RESULTS_DIR/eval_balls.json" "${folders[@]:1}"
  if [[ -z "${EVAL_BALLS_DIR:-}" ]]; then checked+=(--balls "$RESULTS_DIR/eval_balls.json"); fi
else
  echo "[eval] no folders of YOLO-labelled frames under $balls_dir (two or more: one to calibrate, the others to score): balls not evaluated (EVAL_BALLS_DIR=...)"
fi
if (( ${#checked[@]} )); then
  python3 "$ROOT/scripts/check_eval_floor.py" "${checked[@]}" --floor "$ROOT/bench/eval_floor.json"
fi
report_results eval_horizon eval_balls

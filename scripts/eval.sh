#!/usr/bin/env bash
# make eval: accuracy on real labelled frames, ours against OpenCV in one run, one thread.
#  - Horizon: the labelled UAV folders (EVAL_DIR, default ../shared/data/uav_horizon and
#    ../shared/data/uav_horizon_clouds where they exist), frames without a horizon
#    (EVAL_NEGATIVES_DIR, default ../shared/data/robocup_msl) and the simulator's scenes; every
#    flight, date or scene scored with the horizon model fitted without it (leave one group out);
#    the robustness suite; writes eval_horizon.json.
#  - Balls: EVAL_BALLS_DIR (default ../shared/data/robocup_msl/20220716 when it exists), folders
#    of images with YOLO labels (ball class EVAL_BALL_CLASS, default 0): the class is calibrated
#    on the first folder (sorted) and scored on the others; writes eval_balls.json.
#  - Balls by date: the robot frames' dates (EVAL_NEGATIVES_DIR), the class calibrated on each
#    date in turn and scored on every other one, with and without the field side filter; writes
#    eval_balls_by_date.json. And the ball verifier: each date held out, the class calibrated
#    and the verifier trained on the others; writes eval_verifier.json.
#  - Field boundary: the same robot frames, per date, each frame alone: how often a boundary is
#    found and the share of labelled balls, robots and people it puts on the field side; writes
#    eval_field.json.
# The JSON goes to bench/measured/ (RECORD=1: bench/results/, and the docs' tables rewritten).
# On the default data all three are checked against bench/eval_floor.json (the best figures landed
# so far: a regression fails; see scripts/check_eval_floor.py).
set -euo pipefail
source "$(dirname "$0")/env.sh"
horizon_dirs=()
for dir in ${EVAL_DIR:-$ROOT/../shared/data/uav_horizon $ROOT/../shared/data/uav_horizon_clouds}; do
  [[ -f "$dir/label.csv" ]] && horizon_dirs+=("$dir")
done
negatives_dir="${EVAL_NEGATIVES_DIR:-$ROOT/../shared/data/robocup_msl}"
balls_dir="${EVAL_BALLS_DIR:-$ROOT/../shared/data/robocup_msl/20220716}"
cd "$WS" && catkin_make -DRLE_VISION_BUILD_BENCHMARKS=ON -j"${JOBS:-2}" rle_vision_eval_horizon rle_vision_eval_balls \
  rle_vision_eval_balls_by_date rle_vision_eval_verifier rle_vision_eval_field >/dev/null
checked=()
if (( ${#horizon_dirs[@]} )); then
  negatives=()
  [[ -d "$negatives_dir" ]] && negatives=(--negatives "$negatives_dir")
  "$WS/devel/lib/rle_vision/rle_vision_eval_horizon" "${horizon_dirs[@]}" "${negatives[@]}" --sim-frames 40 \
    --json "$RESULTS_DIR/eval_horizon.json"
  if [[ -z "${EVAL_DIR:-}" ]]; then checked+=(--horizon "$RESULTS_DIR/eval_horizon.json"); fi
else
  echo "[eval] no labelled horizon frames (label.csv) in ${EVAL_DIR:-../shared/data/uav_horizon*}: horizon not evaluated (EVAL_DIR=... for other folders)"
fi
mapfile -t folders < <(find "$balls_dir" -mindepth 1 -maxdepth 1 -type d 2>/dev/null | sort)
if (( ${#folders[@]} >= 2 )); then
  "$WS/devel/lib/rle_vision/rle_vision_eval_balls" --calibrate "${folders[0]}" --label-class "${EVAL_BALL_CLASS:-0}" \
    --json "$RESULTS_DIR/eval_balls.json" "${folders[@]:1}"
  if [[ -z "${EVAL_BALLS_DIR:-}" ]]; then checked+=(--balls "$RESULTS_DIR/eval_balls.json"); fi
else
  echo "[eval] no folders of YOLO-labelled frames under $balls_dir (two or more: one to calibrate, the others to score): balls not evaluated (EVAL_BALLS_DIR=...)"
fi
# The ball class calibrated on one date and scored on each other one, every date in turn, with
# and without the field side filter (grouped cross-validation).
if [[ -d "$negatives_dir" ]]; then
  "$WS/devel/lib/rle_vision/rle_vision_eval_balls_by_date" --label-class "${EVAL_BALL_CLASS:-0}" \
    --json "$RESULTS_DIR/eval_balls_by_date.json" "$negatives_dir"
  if [[ -z "${EVAL_NEGATIVES_DIR:-}" ]]; then checked+=(--balls-by-date "$RESULTS_DIR/eval_balls_by_date.json"); fi
  # The ball verifier (issue 30): each date held out, calibrated and trained on the others; JOBS
  # dates at a time (the same figures as one at a time).
  "$WS/devel/lib/rle_vision/rle_vision_eval_verifier" --label-class "${EVAL_BALL_CLASS:-0}" --jobs "${JOBS:-2}" \
    --json "$RESULTS_DIR/eval_verifier.json" "$negatives_dir"
  if [[ -z "${EVAL_NEGATIVES_DIR:-}" ]]; then checked+=(--verifier "$RESULTS_DIR/eval_verifier.json"); fi
fi
# The field boundary on the same robot frames, every date on its own.
if [[ -d "$negatives_dir" ]]; then
  "$WS/devel/lib/rle_vision/rle_vision_eval_field" --json "$RESULTS_DIR/eval_field.json" "$negatives_dir"
  if [[ -z "${EVAL_NEGATIVES_DIR:-}" ]]; then checked+=(--field "$RESULTS_DIR/eval_field.json"); fi
fi
if (( ${#checked[@]} )); then
  python3 "$ROOT/scripts/check_eval_floor.py" "${checked[@]}" --floor "$ROOT/bench/eval_floor.json"
fi
report_results eval_horizon eval_balls eval_balls_by_date eval_verifier eval_field

#!/usr/bin/env bash
# make train: rebuilds the shipped ball verifier, config/ball_verifier.yml.gz, from the labelled
# RoboCup MSL frames (each date a group: rle_vision_train prints each date held out, a model
# trained on the other dates scoring it). Deterministic: the same frames give the same file.
# Commit the file; it loads on a robot without the data (colors.yaml: verifier_file).
set -euo pipefail
source "$(dirname "$0")/env.sh"
data="${EVAL_DATA_DIR:-$ROOT/../shared/data}/robocup_msl"
output="${VERIFIER_OUTPUT:-$ROOT/config/ball_verifier.yml.gz}"
dates=()
for dir in "$data"/*/; do [[ -d "$dir" ]] && dates+=("${dir%/}"); done
if (( ${#dates[@]} == 0 )); then
  echo "[train] no labelled MSL frames under $data (EVAL_DATA_DIR=...)"
  exit 1
fi
ball_class=$(tr -d '\r' < "$data/obj.names" 2>/dev/null | grep -nx 'ball' | cut -d: -f1 || true)
if [[ -z "$ball_class" ]]; then
  echo "[train] no 'ball' line in $data/obj.names (the YOLO class names)"
  exit 1
fi
"$WS/devel/lib/rle_vision/rle_vision_train" --class ball --label-class $((ball_class - 1)) --output "$output" "${dates[@]}"
echo "[train] wrote $output ($(du -k "$output" | cut -f1) KB)"

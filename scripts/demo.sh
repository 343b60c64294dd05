#!/usr/bin/env bash
# Runs the pipeline on the built-in simulated biped view and prints a summary per second.
# Usage: scripts/demo.sh [DURATION_S [NAME:=VALUE ...]]   (0 or empty: until Ctrl-C; the rest
# are demo.launch arguments). roslaunch starts a roscore when none runs.
set -euo pipefail
source "$(dirname "$0")/env.sh"
source_workspace
duration="${1:-0}"
shift || true
args=(duration_s:="$duration" "$@")
echo "[demo] roslaunch rle_vision demo.launch ${args[*]}"
exec roslaunch --no-summary rle_vision demo.launch "${args[@]}"

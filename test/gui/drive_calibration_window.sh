#!/usr/bin/env bash
# Runs inside xvfb-run: opens the calibration window on IMAGE, drags over the box of DIR/box.txt
# ("label left top right bottom") grown by a quarter of its size, presses s (save into
# DIR/colors.yaml and DIR/colors.txt, class CLASS_NAME, default target) and q (quit). With
# SCREENSHOT (an .xwd path), the screen is dumped after the save and the window's geometry
# written beside it (SCREENSHOT.geometry: WIDTH HEIGHT X Y), for `make screenshot`.
# Usage: drive_calibration_window.sh CALIBRATE_BIN DIR IMAGE [SCREENSHOT]
set -uo pipefail
source "$(dirname "$0")/window_driving.sh"
tool_bin=$1 dir=$2 image=$3 screenshot=${4:-}
read -r _label left top right bottom <"$dir/box.txt"
cd "$dir" || exit 1  # the window's notice names the files as given: colors.yaml, colors.txt
"$tool_bin" --gui --name "${CLASS_NAME:-target}" --output colors.yaml --cmvision colors.txt \
  "$image" >stdout.txt 2>&1 &
tool=$!
window=$(find_window "rle_vision calibrate") || { kill "$tool"; exit 1; }
wait_for_width "$window" "$(python3 -c 'import sys, cv2; print(cv2.imread(sys.argv[1]).shape[1])' "$image")" ||
  { kill "$tool"; exit 1; }
drag_grown_box "$window" "$left" "$top" "$right" "$bottom"
xdotool key --window "$window" s
wait_until test -s colors.yaml || { kill "$tool"; exit 1; }
if [[ -n "$screenshot" ]]; then
  sleep 1  # the saved notice drawn
  xwd -root -silent >"$screenshot"
  eval "$(xdotool getwindowgeometry --shell "$window")"
  echo "$WIDTH $HEIGHT $X $Y" >"$screenshot.geometry"
fi
xdotool key --window "$window" q
wait_for_exit "$tool"

#!/usr/bin/env bash
# Runs inside xvfb-run: opens the calibration window on IMAGE, drags over the box of DIR/box.txt
# ("label left top right bottom") grown by a quarter of its size (after a box on the ground taken
# back with u), goes round the colour spaces with c, presses s (save into
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
read -r width height < <(python3 -c 'import sys, cv2; print(*cv2.imread(sys.argv[1]).shape[1::-1])' "$image")
wait_for_width "$window" "$width" || { kill "$tool"; exit 1; }
# The class as the tool reports it after each change (its last line on the terminal).
status_says() { tail -1 stdout.txt | grep -q -- "$1"; }
# A box on the ground first, taken back with u.
drag_grown_box "$window" 20 "$((height - 70))" 60 "$((height - 30))"
wait_until status_says "1 boxes\|no class" || { kill "$tool"; exit 1; }
xdotool key --window "$window" u
wait_until status_says "drag a box around the object" || { kill "$tool"; exit 1; }
drag_grown_box "$window" "$left" "$top" "$right" "$bottom"
wait_until status_says "(YUV) \[.*, 1 boxes" || { kill "$tool"; exit 1; }
# Round the colour spaces and back to YUV, the class measured in each.
for space in RGB HSV YUV; do
  xdotool key --window "$window" c
  wait_until status_says "($space)" || { kill "$tool"; exit 1; }
done
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

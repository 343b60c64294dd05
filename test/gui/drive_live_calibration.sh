#!/usr/bin/env bash
# Runs inside xvfb-run for test_calibrate_gui.sh, with a running demo graph (simulator + tracker):
# starts calibrate_gui on camera/image_raw, drags over the box of DIR/box.txt ("label left top
# right bottom") grown by a quarter of its size, presses s (save into DIR/live_colors.yaml), t
# (send to the tracker) and q (quit).
# Usage: drive_live_calibration.sh CALIBRATE_GUI_BIN DIR
set -uo pipefail
source "$(dirname "$0")/window_driving.sh"
gui_bin=$1 dir=$2
read -r _label left top right bottom <"$dir/box.txt"
ROS_NAMESPACE=camera "$gui_bin" image:=image_raw _name:=target _output:="$dir/live_colors.yaml" >"$dir/live.log" 2>&1 &
tool=$!
window=$(find_window "rle_vision calibrate") || { kill "$tool"; exit 1; }
# A live frame drawn (a box needs a frame to start on): the window takes the camera's width.
wait_for_width "$window" "$(timeout 30 rostopic echo -n1 /camera/camera_info/width | head -1)" ||
  { kill "$tool"; exit 1; }
drag_grown_box "$window" "$left" "$top" "$right" "$bottom"
xdotool key --window "$window" s
wait_until test -s "$dir/live_colors.yaml" || { kill "$tool"; exit 1; }
xdotool key --window "$window" t
tracker_has_target() {
  timeout 5 rostopic echo -n1 /camera/tracker/active_color_ranges 2>/dev/null | grep -q 'name: "target"'
}
wait_until tracker_has_target || { kill "$tool"; exit 1; }
xdotool key --window "$window" q
wait_for_exit "$tool"

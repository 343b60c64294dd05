#!/usr/bin/env bash
# The calibration window used as a person would (make test): under a virtual X server, xdotool
# drags a box over a simulator frame's object, presses s (save) and q (quit); the saved class
# must then take >= 95% of that object's pixels and no region elsewhere in the frame, in both
# files written (colors.yaml, CMVision colors.txt). Also: without a display, one line names the
# fix. On a live camera (the demo graph): a box dragged over the object and t sent to the tracker
# make the tracker use the class and report the object as it. Prints "N passed, M failed" (JUnit report when JUNIT_DIR is set).
set -uo pipefail
source "$(dirname "$0")/../../scripts/env.sh"
CHECK_SUITE=calibrate_gui
CHECK_LOG_DIR="$WS/calibrate_gui_logs" && mkdir -p "$CHECK_LOG_DIR"
source "$ROOT/scripts/checks.sh"
bin="$WS/devel/lib/rle_vision"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

drag_save_and_quit() {
  "$bin/calibration_scene" write "$ROOT/config/scene_default.yaml" "$dir" || return 1
  xvfb-run -a -s "-screen 0 1280x1024x24" "$ROOT/test/gui/drive_calibration_window.sh" \
    "$bin/rle_vision_calibrate" "$dir" "$dir/frame.png" || return 1
  cat "$dir/stdout.txt"
  [[ -s "$dir/colors.yaml" && -s "$dir/colors.txt" ]] || { echo "s did not save both files"; return 1; }
}

check drag_save_and_quit drag_save_and_quit
check saved_yaml_class_finds_the_object "$bin/calibration_scene" check "$dir" "$dir/colors.yaml" target
check saved_cmvision_class_finds_the_object "$bin/calibration_scene" check "$dir" "$dir/colors.txt" target
no_display_names_the_fix() {
  local out
  out=$(env -u DISPLAY -u WAYLAND_DISPLAY "$bin/rle_vision_calibrate" --gui --name target "$ROOT/README.md" 2>&1)
  local status=$?
  echo "$out"
  [[ $status -eq 2 && $(wc -l <<<"$out") -eq 1 ]] && grep -q "xvfb-run" <<<"$out" && grep -q -- "--box" <<<"$out"
}
check no_display_names_the_fix no_display_names_the_fix

# The demo graph (simulator, tracker; no rviz, no colour learning) on a master of its own, its
# tracker without the blue class: the blue object is what the user calibrates. The camera stands
# still (no gait), so the box of the scene's first frame is where the object is on the live one.
export ROS_MASTER_URI=http://localhost:11397
demo_pid=""
stop_demo() {
  # TERM: a background job of a script ignores INT; roslaunch stops its nodes on TERM too.
  [[ -n "$demo_pid" ]] && kill -TERM "$demo_pid" 2>/dev/null && wait "$demo_pid" 2>/dev/null
  demo_pid=""
}
trap 'stop_demo; rm -rf "$dir"' EXIT
live_send_to_tracker() {
  source_workspace
  python3 -c 'import sys, yaml
classes = yaml.safe_load(open(sys.argv[1]))["classes"]
yaml.safe_dump({"classes": [c for c in classes if c["name"] != "blue"]}, open(sys.argv[2], "w"))' \
    "$ROOT/config/colors.yaml" "$dir/no_blue.yaml" || return 1
  sed 's/^gait: .*/gait: {frequency_hz: 1.0, roll_amplitude_deg: 0, pitch_amplitude_deg: 0, yaw_amplitude_deg: 0, bob_amplitude_m: 0}/' \
    "$ROOT/config/scene_default.yaml" >"$dir/still_scene.yaml"
  grep -q "roll_amplitude_deg: 0," "$dir/still_scene.yaml" || { echo "no gait line in the scene file"; return 1; }
  mkdir -p "$dir/live" && "$bin/calibration_scene" write "$dir/still_scene.yaml" "$dir/live" || return 1
  roslaunch -p 11397 rle_vision demo.launch rviz:=false learning:=false colors_file:="$dir/no_blue.yaml" \
    scene_file:="$dir/still_scene.yaml" >"$dir/demo.log" 2>&1 &
  demo_pid=$!
  for _ in $(seq 60); do
    rostopic list >/dev/null 2>&1 && break
    sleep 1
  done
  timeout 60 rostopic echo -n1 /camera/tracker/active_color_ranges >"$dir/before.txt" || { echo "no tracker"; return 1; }
  grep -q 'name: "\(target\|blue\)"' "$dir/before.txt" && { echo "the tracker has a blue class already"; return 1; }
  xvfb-run -a -s "-screen 0 1280x1024x24" "$ROOT/test/gui/drive_live_calibration.sh" "$bin/calibrate_gui" "$dir/live"
  local status=$?
  cat "$dir/live/live.log"
  [[ $status -eq 0 ]] || return 1
  for _ in $(seq 20); do  # the tracker takes the class up on its next frame
    timeout 10 rostopic echo -n1 /camera/tracker/active_color_ranges >"$dir/after.txt"
    grep -q 'name: "target"' "$dir/after.txt" && break
    sleep 0.5
  done
  # The tracker uses the class saved, and that class finds the object on the scene's first frame.
  python3 -c 'import sys, yaml
active = {c["name"]: c for c in yaml.safe_load(open(sys.argv[1]).read().split("---")[0])["ranges"]}
saved = yaml.safe_load(open(sys.argv[2]))["classes"][0]
sent = active.get("target")
print("tracker:", sent and (list(sent["min"]), list(sent["max"])), "saved:", saved["min"], saved["max"])
sys.exit(0 if sent and list(sent["min"]) == saved["min"] and list(sent["max"]) == saved["max"] else 1)' \
    "$dir/after.txt" "$dir/live/live_colors.yaml" || { echo "the tracker did not take up the class"; return 1; }
  "$bin/calibration_scene" check "$dir/live" "$dir/live/live_colors.yaml" target || return 1
  # The object (still in view) is reported as the new class within 30 frames.
  timeout 10 rostopic echo -n30 /camera/blobs >"$dir/blobs.txt"
  grep -q 'color: "target"' "$dir/blobs.txt" || { echo "no blob of class target"; return 1; }
}
check live_send_to_tracker live_send_to_tracker
stop_demo
finish_checks

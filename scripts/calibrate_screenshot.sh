#!/usr/bin/env bash
# Regenerates docs/calibrate_gui.png (make screenshot): the calibration window
# (rle_vision_calibrate --gui) on a real RoboCup MSL frame, a box dragged over its ball with
# xdotool under Xvfb, as test/gui/test_calibrate_gui.sh drives it. The frame: the first one of
# BALL_DIR (default ../shared/data/robocup_msl/20220716/r2) whose YOLO ball box is >= 60 px wide
# and whole in the frame.
set -euo pipefail
source "$(dirname "$0")/env.sh"
ball_dir="${BALL_DIR:-$ROOT/../shared/data/robocup_msl/20220716/r2}"
out="$ROOT/docs/calibrate_gui.png"
[[ -d "$ball_dir" ]] || { echo "[screenshot] no $ball_dir: calibration window screenshot not retaken"; exit 0; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
image=$(python3 - "$ball_dir" "$dir/box.txt" <<'PY'
import glob, os, sys
import cv2
folder, box_file = sys.argv[1:3]
for image in sorted(glob.glob(os.path.join(folder, '*.jpg')) + glob.glob(os.path.join(folder, '*.png'))):
    label = os.path.splitext(image)[0] + '.txt'
    if not os.path.exists(label):
        continue
    height, width = cv2.imread(image).shape[:2]
    for line in open(label):
        fields = line.split()
        if len(fields) != 5 or fields[0] != '0':
            continue
        cx, cy, w, h = (float(v) for v in fields[1:])
        if w * width >= 60 and min(cx - w / 2, cy - h / 2) > 0.02 and max(cx + w / 2, cy + h / 2) < 0.98:
            box = [int((cx - w / 2) * width), int((cy - h / 2) * height), int((cx + w / 2) * width), int((cy + h / 2) * height)]
            open(box_file, 'w').write('0 %d %d %d %d\n' % tuple(box))
            print(image)
            sys.exit(0)
sys.exit('no ball box of 60 px or more in ' + folder)
PY
)
CLASS_NAME=ball xvfb-run -a -s "-screen 0 1280x1024x24" "$ROOT/test/gui/drive_calibration_window.sh" \
  "$WS/devel/lib/rle_vision/rle_vision_calibrate" "$dir" "$image" "$dir/screen.xwd"
python3 - "$dir/screen.xwd" "$out" "$ROOT/test/ros" <<'PY'
import sys
import cv2
dump, out, helpers = sys.argv[1:4]
sys.path.insert(0, helpers)
import screenshot
width, height, x, y = (int(v) for v in open(dump + '.geometry').read().split())
rgb = screenshot.read_xwd(open(dump, 'rb').read())[y:y + height, x:x + width]
cv2.imwrite(out, cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_PNG_COMPRESSION, 9])
PY
echo "[screenshot] wrote $out ($(basename "$image"))"

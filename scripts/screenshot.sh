#!/usr/bin/env bash
# Regenerates docs/rviz_screenshot.png (the README's picture) with the rviz screenshot test:
# rviz with config/rle_vision.rviz on the demo graph, under Xvfb.
set -euo pipefail
source "$(dirname "$0")/env.sh"
source_workspace
mkdir -p "$ROOT/docs"
export RLE_VISION_SCREENSHOT="$ROOT/docs/rviz_screenshot.png"
rostest rle_vision rviz_screenshot.test
echo "[screenshot] wrote $RLE_VISION_SCREENSHOT"
scripts/calibrate_screenshot.sh

#!/usr/bin/env bash
# Builds rle_vision in a git-ignored catkin workspace inside the checkout (.ws/).
set -euo pipefail
source "$(dirname "$0")/env.sh"
mkdir -p "$WS/src"
# .ws/src/rle_vision -> the checkout (relative, so the checkout can move).
[[ -L "$WS/src/rle_vision" ]] || ln -s ../.. "$WS/src/rle_vision"
cd "$WS"
# RLE_VISION_WERROR=ON (CI) turns warnings into errors.
catkin_make -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON -DRLE_VISION_WERROR="${RLE_VISION_WERROR:-OFF}" \
  -j"${JOBS:-2}" "$@"

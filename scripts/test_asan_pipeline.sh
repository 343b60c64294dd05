#!/usr/bin/env bash
# The running pipeline under AddressSanitizer: builds the package (nodelets included) with ASan
# in a git-ignored catkin workspace (.ws-asan-ros), runs demo.launch (simulator, tracker, edge
# detector, landmark with learning, ground projector, all in one manager) for ASAN_PIPELINE_S
# seconds (default 60) with both cores kept busy by two spinning processes after the start, and
# fails on any sanitizer report or a process that died. The load matters: the landmark worker
# runs at idle priority, so only a busy machine makes it lag its colour-image cache, and that is
# when a frame's pixels can be freed under it (the use-after-free this found).
# Writes a JUnit result to $JUNIT_DIR/asan_pipeline.xml when JUNIT_DIR is set.
set -uo pipefail
source "$(dirname "$0")/env.sh"
ASAN_WS="${ASAN_WS:-$ROOT/.ws-asan-ros}"
seconds="${ASAN_PIPELINE_S:-60}"
libasan=$(g++ -print-file-name=libasan.so)
mkdir -p "$ASAN_WS/src"
ln -sfn "$ROOT" "$ASAN_WS/src/rle_vision"
logs="$ASAN_WS/logs"
rm -rf "$logs" && mkdir -p "$logs"

failure=""
if ! (cd "$ASAN_WS" && catkin_make -j"${JOBS:-2}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS="-fsanitize=address -fno-omit-frame-pointer" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address" -DRLE_VISION_BUILD_BENCHMARKS=OFF -DCATKIN_ENABLE_TESTING=OFF) \
      >"$logs/build.log" 2>&1; then
  tail -40 "$logs/build.log"
  failure="building the package with AddressSanitizer failed (log: $logs/build.log)"
fi

if [[ -z "$failure" ]]; then
  (
    set +u
    source "$ASAN_WS/devel/setup.bash"
    set -u
    export ROS_HOME="$logs/ros_home"
    # Leaks are not checked: the Python tools (roslaunch) get the runtime preloaded too.
    export ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:log_path=$logs/asan"
    # The manager (/usr/lib/nodelet/nodelet) is not instrumented: the runtime must come first.
    LD_PRELOAD="$libasan" exec roslaunch --no-summary rle_vision demo.launch rviz:=false realtime_priority:=0 \
      duration_s:=$((seconds + 15))
  ) >"$logs/demo.log" 2>&1 &
  demo=$!
  sleep 10
  busy=()
  for _ in 1 2; do
    (while :; do :; done) &
    busy+=($!)
  done
  sleep "$seconds"
  kill "${busy[@]}" 2>/dev/null
  wait "$demo" 2>/dev/null
  reports=$(ls "$logs"/asan.* 2>/dev/null || true)
  if [[ -n "$reports" ]]; then
    for report in $reports; do head -30 "$report"; done
    failure="AddressSanitizer reported an error in the running pipeline ($reports)"
  elif grep -q "process has died" "$logs/demo.log"; then
    grep "process has died" "$logs/demo.log"
    failure="a process died in the running pipeline (log: $logs/demo.log)"
  elif ! grep -q "blobs: " "$logs/demo.log"; then
    tail -20 "$logs/demo.log"
    failure="the pipeline under AddressSanitizer gave no blobs (log: $logs/demo.log)"
  fi
fi

if [[ -n "${JUNIT_DIR:-}" ]]; then
  mkdir -p "$JUNIT_DIR"
  python3 - "$JUNIT_DIR/asan_pipeline.xml" "$failure" <<'EOF'
import sys
from xml.sax.saxutils import quoteattr
path, failure = sys.argv[1], sys.argv[2]
inner = '<failure message=%s/>' % quoteattr(failure) if failure else ''
with open(path, 'w') as f:
    f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="asan_pipeline" tests="1" failures="%d">'
            '<testcase classname="asan" name="demo_pipeline_under_load">%s</testcase></testsuite>\n'
            % (1 if failure else 0, inner))
EOF
fi
if [[ -n "$failure" ]]; then
  echo "[asan-pipeline] FAILED: $failure"
  exit 1
fi
echo "[asan-pipeline] the demo pipeline ran ${seconds} s under load with no sanitizer report"

#!/usr/bin/env bash
# The running pipeline under AddressSanitizer: builds the package (nodelets included) with ASan
# in a git-ignored catkin workspace (.ws-asan-ros), runs demo.launch (simulator, tracker, edge
# detector, landmark with learning, ground projector, all in one manager) for ASAN_PIPELINE_S
# seconds (default 60) with both cores kept busy by two spinning processes once it runs, and
# fails on any sanitizer report or a process that died. The load matters: the landmark worker
# runs at idle priority, so only a busy machine makes it lag its colour-image cache, and that is
# when a frame's pixels can be freed under it (the use-after-free this found).
# One test case (scripts/checks.sh): a JUnit result in $JUNIT_DIR/asan_pipeline.xml when JUNIT_DIR is set.
set -uo pipefail
source "$(dirname "$0")/env.sh"
ASAN_WS="${ASAN_WS:-$ROOT/.ws-asan-ros}"
seconds="${ASAN_PIPELINE_S:-60}"
libasan=$(g++ -print-file-name=libasan.so)
mkdir -p "$ASAN_WS/src"
ln -sfn "$ROOT" "$ASAN_WS/src/rle_vision"
logs="$ASAN_WS/logs"
rm -rf "$logs" && mkdir -p "$logs"

# One test case: build, run under load, read the logs. Prints why it failed.
demo_pipeline_under_load() {
  if ! (cd "$ASAN_WS" && catkin_make -j"${JOBS:-2}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS="-fsanitize=address -fno-omit-frame-pointer" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address" \
        -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address" -DRLE_VISION_BUILD_BENCHMARKS=OFF -DCATKIN_ENABLE_TESTING=OFF) \
        >"$logs/build.log" 2>&1; then
    tail -40 "$logs/build.log"
    echo "building the package with AddressSanitizer failed (log: $logs/build.log)"
    return 1
  fi
  (
    set +u
    source "$ASAN_WS/devel/setup.bash"
    set -u
    export ROS_HOME="$logs/ros_home"
    # Leaks are not checked: the Python tools (roslaunch) get the runtime preloaded too.
    export ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:log_path=$logs/asan"
    # The manager (/usr/lib/nodelet/nodelet) is not instrumented: the runtime must come first.
    LD_PRELOAD="$libasan" exec roslaunch --no-summary rle_vision demo.launch rviz:=false realtime_priority:=0 \
      duration_s:=$((seconds + 200))
  ) >"$logs/demo.log" 2>&1 &
  local demo=$!
  # The load starts once the pipeline runs (its first summary line), however long an
  # instrumented start-up takes on a slow machine.
  local waited
  for ((waited = 0; waited < 180; waited++)); do
    grep -q "blobs: " "$logs/demo.log" 2>/dev/null || ! kill -0 "$demo" 2>/dev/null && break
    sleep 1
  done
  local busy=()
  for _ in 1 2; do
    (while :; do :; done) &
    busy+=($!)
  done
  sleep "$seconds"
  kill "${busy[@]}" 2>/dev/null
  kill -INT "$demo" 2>/dev/null  # Ctrl-C: roslaunch stops every node
  wait "$demo" 2>/dev/null
  local reports
  reports=$(ls "$logs"/asan.* 2>/dev/null || true)
  if [[ -n "$reports" ]]; then
    for report in $reports; do head -30 "$report"; done
    echo "AddressSanitizer reported an error in the running pipeline ($reports)"
    return 1
  elif grep -q "process has died" "$logs/demo.log"; then
    grep "process has died" "$logs/demo.log"
    echo "a process died in the running pipeline (log: $logs/demo.log)"
    return 1
  elif ! grep -q "blobs: " "$logs/demo.log"; then
    tail -20 "$logs/demo.log"
    echo "the pipeline under AddressSanitizer gave no blobs (log: $logs/demo.log)"
    return 1
  fi
  echo "the demo pipeline ran ${seconds} s under load with no sanitizer report"
}

CHECK_SUITE=asan_pipeline
CHECK_LOG_DIR="$logs"
source "$(dirname "$0")/checks.sh"
check demo_pipeline_under_load demo_pipeline_under_load
finish_checks

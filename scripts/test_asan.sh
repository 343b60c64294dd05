#!/usr/bin/env bash
# Builds the core and its unit tests (and the offline CLI they run) with AddressSanitizer and
# UndefinedBehaviorSanitizer in a second git-ignored workspace (.ws-asan), runs them, and
# prints "N passed, M failed". Any sanitizer report fails the run.
set -uo pipefail
source "$(dirname "$0")/env.sh"
WS_ASAN="$ROOT/.ws-asan"
mkdir -p "$WS_ASAN/src"
ln -sfn "$ROOT" "$WS_ASAN/src/rle_vision"
cd "$WS_ASAN"
if ! catkin_make -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRLE_VISION_SANITIZE=address,undefined \
    -j"${JOBS:-2}" test_core >"$WS_ASAN/build.log" 2>&1; then
  tail -40 "$WS_ASAN/build.log"
  echo "0 passed, 1 failed"
  exit 1
fi
results="$WS_ASAN/test_results"
rm -rf "$results" && mkdir -p "$results"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
extra=()
if ! "$WS_ASAN/devel/lib/rle_vision/test_core" --gtest_output="xml:$results/test_core_asan.xml"; then
  extra+=("test_core under ASan/UBSan exited with an error (see the report above)")
fi
exec python3 "$ROOT/scripts/summarize_tests.py" "$results" "${extra[@]}"

#!/usr/bin/env bash
# Builds the ROS-free core (src/core, plain CMake) and its unit tests with AddressSanitizer and
# UndefinedBehaviorSanitizer in a git-ignored build folder (.ws-asan), runs them, then runs the
# whole demo pipeline built with ASan (scripts/test_asan_pipeline.sh), and prints
# "N passed, M failed". Any sanitizer report fails the run.
set -uo pipefail
source "$(dirname "$0")/env.sh"
BUILD="$ROOT/.ws-asan"
mkdir -p "$BUILD"
if ! { cmake -S "$ROOT/src/core" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRLE_VISION_SANITIZE=address,undefined &&
       cmake --build "$BUILD" -j"${JOBS:-2}" --target test_core; } >"$BUILD/build.log" 2>&1; then
  tail -40 "$BUILD/build.log"
  echo "0 passed, 1 failed"
  exit 1
fi
results="$BUILD/test_results"
rm -rf "$results" && mkdir -p "$results"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
extra=()
if ! "$BUILD/test_core" --gtest_output="xml:$results/test_core_asan.xml"; then
  extra+=("test_core under ASan/UBSan exited with an error (see the report above)")
fi
# The running pipeline (every nodelet) under ASan, on a busy machine.
JUNIT_DIR="$results" "$ROOT/scripts/test_asan_pipeline.sh" || true
exec python3 "$ROOT/scripts/summarize_tests.py" "$results" "${extra[@]}"

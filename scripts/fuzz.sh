#!/usr/bin/env bash
# Builds the libFuzzer targets in test/fuzz (clang, with AddressSanitizer and
# UndefinedBehaviorSanitizer) and runs each for FUZZ_SECONDS (default 60) from the seeds in
# test/fuzz/corpus, then prints executions and coverage per target. A crash leaves its input in
# .ws-fuzz/artifacts/ and fails the run (turn it into a regression test).
set -euo pipefail
source "$(dirname "$0")/env.sh"
seconds="${FUZZ_SECONDS:-60}"
out="$ROOT/.ws-fuzz"
mkdir -p "$out/obj" "$out/artifacts"
flags=(-std=c++17 -O1 -g -fno-omit-frame-pointer -DRLE_VISION_NO_MULTIVERSION -DRLE_VISION_SOURCE_DIR="\"$ROOT\"" -I"$ROOT/include"
       -I/usr/include/opencv4 -I/usr/include/eigen3 -fsanitize=address,undefined -fno-sanitize-recover=all)
libs=(-lopencv_core -lopencv_imgproc -lopencv_calib3d -lyaml-cpp -lpthread)

# The core, its file readers and the simulator (every stage folder of src/core, not the tests),
# compiled once (instrumented for coverage).
objects=()
newest_header=$(ls -t "$ROOT"/include/rle_vision/*/*.h "$ROOT"/src/core/*/*.h | head -1)
for src in "$ROOT"/src/core/*/*.cpp; do
  obj="$out/obj/$(basename "${src%.cpp}").o"
  if [[ ! -f "$obj" || "$src" -nt "$obj" || "$newest_header" -nt "$obj" ]]; then
    clang++ "${flags[@]}" -fsanitize=fuzzer-no-link -I"$ROOT/src/core" -c "$src" -o "$obj"
  fi
  objects+=("$obj")
done

status=0
printf '%-20s %12s %10s %10s %s\n' target executions coverage features result
for target in color_config params segmenter landmark; do
  bin="$out/fuzz_$target"
  clang++ "${flags[@]}" -fsanitize=fuzzer "$ROOT/test/fuzz/fuzz_$target.cpp" "${objects[@]}" "${libs[@]}" -o "$bin"
  corpus="$out/corpus/$target"
  mkdir -p "$corpus"
  log="$out/fuzz_$target.log"
  result=clean
  if ! "$bin" "$corpus" "$ROOT/test/fuzz/corpus/$target" -max_total_time="$seconds" -rss_limit_mb=2048 \
       -artifact_prefix="$out/artifacts/${target}-" -print_final_stats=1 >"$log" 2>&1; then
    result="CRASH (see $log and $out/artifacts)"
    status=1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  printf '%-20s %12s %10s %10s %s\n' "$target" "$execs" "$cov" "$ft" "$result"
done
exit $status

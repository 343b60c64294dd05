#!/usr/bin/env bash
# Latency under load: runs the demo pipeline (simulator -> tracker, edge detector, landmark,
# ground projector, monitor, all at 30 Hz) for BENCH_SECONDS (default 60) at 640x480 and at
# 1280x720, and writes tracker latency, drops, landmark skips and CPU per node to
# latency.json. Both sizes run at both priorities, each twice (the spread is in
# the file): as launched by default (the tracker's frame thread at SCHED_FIFO priority 50,
# where the system allows it) and with realtime_priority:=0 (normal priority, what a user
# without CAP_SYS_NICE or an rtprio limit gets). A fifth configuration, 640x480@overload, is
# the bounded-frame case: sensor noise sigma 60 and CMVision's colors.txt (thousands of regions a
# frame), the tracker alone, as launched; its rows give the slowest frame's wall-clock and CPU
# time. BENCH_REPEATS (2) sets the repeats. The JSON goes to bench/measured/ (RECORD=1:
# bench/results/, and the docs' tables rewritten).
set -euo pipefail
source "$(dirname "$0")/env.sh"
source_workspace
seconds="${BENCH_SECONDS:-60}"
out="$RESULTS_DIR/latency.json"
rm -f "$out"
runs=()
for config in 640x480 640x480@normal 1280x720 1280x720@normal 640x480@overload; do
  for repeat in $(seq 1 "${BENCH_REPEATS:-2}"); do runs+=("$config#$repeat"); done
done
for run in "${runs[@]}"; do
  config=${run%#*}
  size=${config%@*}
  priority=50
  [[ "$config" == *@normal ]] && priority=0
  width=${size%x*}
  height=${size#*x}
  scene="$WS/bench_scene_$config.yaml"
  sed "s/^image: .*/image: {width: $width, height: $height}/" "$ROOT/config/scene_default.yaml" >"$scene"
  extra=()
  if [[ "$config" == *@overload ]]; then
    sed -i "s/noise_sigma: [0-9.]*/noise_sigma: 60/" "$scene"
    extra=(colors_file:="$ROOT/config/colors.txt" landmarks:=false)
  fi
  echo "[bench-latency] $config at 30 Hz for $seconds s (plus start-up), tracker realtime_priority $priority"
  roslaunch --no-summary rle_vision demo.launch rviz:=false scene_file:="$scene" realtime_priority:=$priority \
    duration_s:=$((seconds + 30)) "${extra[@]}" >"$WS/bench_latency_$run.log" 2>&1 &
  launch_pid=$!
  probe_flags=()
  [[ "$config" == *@overload ]] && probe_flags=(--no-landmark)
  python3 "$ROOT/bench/latency_probe.py" "$run" "$seconds" "$out" "${probe_flags[@]}" || status=$?
  kill -INT "$launch_pid" 2>/dev/null || true
  wait "$launch_pid" 2>/dev/null || true
  if [[ -n "${status:-}" ]]; then
    echo "[bench-latency] the probe failed; the launch log is $WS/bench_latency_$run.log"
    exit 1
  fi
done
echo "[bench-latency] wrote $out"
report_results latency

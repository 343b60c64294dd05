# Sourced by the calibration window's drivers (run under xvfb-run): find the window, wait for it
# to show a frame, drag a box as a hand would, wait for the program to quit. Each prints why it
# failed and returns non-zero.

# The id of the first window whose title contains TITLE, within 15 s: find_window TITLE
find_window() {
  local window
  for _ in $(seq 150); do
    window=$(xdotool search --name "$1" 2>/dev/null | head -1)
    [[ -n "$window" ]] && { echo "$window"; return 0; }
    sleep 0.1
  done
  echo "no window '$1' appeared" >&2
  return 1
}

# Waits (30 s at most) until WINDOW is WIDTH px wide: the window takes the width of the frame it
# shows, so a frame is drawn and mouse events land on it. wait_for_width WINDOW WIDTH
wait_for_width() {
  local WIDTH=0 HEIGHT X Y SCREEN WINDOW
  for _ in $(seq 300); do
    eval "$(xdotool getwindowgeometry --shell "$1")"
    [[ "$WIDTH" == "$2" ]] && return 0
    sleep 0.1
  done
  echo "the window is $WIDTH px wide, not the frame's $2" >&2
  return 1
}

# Drags with the left button over the box grown by a quarter of its size on each side (a hand
# does not draw it pixel-exact): drag_grown_box WINDOW LEFT TOP RIGHT BOTTOM
drag_grown_box() {
  local window=$1 left=$2 top=$3 right=$4 bottom=$5
  local grow_x=$(((right - left) / 4 + 2)) grow_y=$(((bottom - top) / 4 + 2))
  xdotool mousemove --window "$window" $((left - grow_x)) $((top - grow_y)) mousedown 1 \
    mousemove --window "$window" $(((left + right) / 2)) $(((top + bottom) / 2)) \
    mousemove --window "$window" $((right + grow_x)) $((bottom + grow_y)) mouseup 1
}

# Waits (10 s at most) until COMMAND... succeeds: what a key did, before the next key goes (highgui
# reads one key per wait, so keys sent together can overwrite each other). wait_until COMMAND...
wait_until() {
  for _ in $(seq 100); do
    "$@" && return 0
    sleep 0.1
  done
  echo "waited 10 s for: $*" >&2
  return 1
}

# Waits (10 s at most) for PID to exit and returns its status: wait_for_exit PID
wait_for_exit() {
  for _ in $(seq 100); do
    kill -0 "$1" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$1" 2>/dev/null; then
    echo "the window did not quit on q" >&2
    kill "$1"
    return 1
  fi
  wait "$1"
}

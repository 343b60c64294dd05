# Sourced by the other scripts: paths and an environment where catkin, roslaunch and rostest
# find Debian's Python (a pyenv python3 earlier on PATH lacks catkin_pkg).
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="$ROOT/.ws"
export PATH="/usr/bin:/bin:$PATH"
# ROS from /opt/ros (Ubuntu 20.04 + Noetic); Debian's ROS lives under /usr and needs nothing.
for ros_setup in /opt/ros/"${ROS_DISTRO:-*}"/setup.bash; do
  if [[ -f "$ros_setup" ]]; then
    case $- in *u*) set +u; source "$ros_setup"; set -u ;; *) source "$ros_setup" ;; esac
    break
  fi
done
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
export ROSCONSOLE_FORMAT='[${severity}] [${node}]: ${message}'
source_workspace() {
  # setup.bash reads unset variables; relax -u while sourcing it.
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
}
# Where make bench, make eval and make bench-latency write their JSON: bench/measured/
# (git-ignored: measuring a machine leaves the checkout clean), or with RECORD=1 bench/results/,
# the committed figures that the docs' tables are written from (scripts/readme_figures.py).
if [[ "${RECORD:-0}" == 1 ]]; then
  RESULTS_DIR="$ROOT/bench/results"
else
  RESULTS_DIR="$ROOT/bench/measured"
fi
mkdir -p "$RESULTS_DIR"
# After a run: the measured figures beside the committed ones, or (RECORD=1) the docs' tables
# rewritten from the new ones.
report_results() {
  if [[ "${RECORD:-0}" == 1 ]]; then
    python3 "$ROOT/scripts/readme_figures.py" --write
  else
    python3 "$ROOT/scripts/compare_results.py" "$@"
  fi
}

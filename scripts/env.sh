# Sourced by the other scripts: paths and an environment where catkin, roslaunch and rostest
# find Debian's Python (a pyenv python3 earlier on PATH lacks catkin_pkg).
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="$ROOT/.ws"
export PATH="/usr/bin:/bin:$PATH"
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
export ROSCONSOLE_FORMAT='[${severity}] [${node}]: ${message}'
source_workspace() {
  # setup.bash reads unset variables; relax -u while sourcing it.
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
}

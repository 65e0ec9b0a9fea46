# Sourced by the scripts: Debian's ROS lives in /usr, and its Python modules are only
# visible to /usr/bin/python3, so /usr/bin goes first on PATH.
export PATH="/usr/bin:/bin:$PATH"
export BEARING_SIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export BEARING_SIM_BUILD="${BEARING_SIM_BUILD:-$BEARING_SIM_ROOT/build}"
export ROS_HOME="${ROS_HOME:-$BEARING_SIM_BUILD/ros_home}"
export ROS_LOG_DIR="${ROS_LOG_DIR:-$ROS_HOME/log}"

#!/usr/bin/env bash
# The main job: install what is missing, build, and run the CT gantry bearing in real time.
# Extra arguments go to roslaunch (e.g. rviz:=true).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$here/../dev/install_deps.sh"
"$here/../dev/build.sh"
source "$here/env.sh"
set +u  # catkin's setup hooks read unset variables
source "$BEARING_SIM_BUILD/devel/setup.bash"
set -u
exec roslaunch bearing_sim ct_gantry.launch "$@"

#!/usr/bin/env bash
# Screenshot of the ball-load display: starts Xvfb, the CT gantry launch file with rviz
# (real bearing_sim_node, or the test fake with --fake), waits for the picture to settle
# and saves docs/images/ct_gantry_rviz.png.
#   dev/capture_rviz_screenshot.sh [--fake] [output.png]
# Needs a built package ($BEARING_SIM_BUILD, default build/) and xvfb, x11-apps, imagemagick.
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../scripts/env.sh"
source "$BEARING_SIM_BUILD/devel/setup.bash"  # (not under set -u: ROS setup scripts read unset variables)
set -u

use_fake=false
if [[ "${1:-}" == "--fake" ]]; then use_fake=true; shift; fi
out="${1:-$BEARING_SIM_ROOT/docs/images/ct_gantry_rviz.png}"
settle_s="${SETTLE_S:-25}"       # rviz under software GL needs a while for its first frames
display_num="${DISPLAY_NUM:-99}"
port="${ROS_PORT:-11399}"

export ROS_MASTER_URI="http://localhost:$port"
export DISPLAY=":$display_num"
export LIBGL_ALWAYS_SOFTWARE=1   # Xvfb has no GPU: Mesa's software rasteriser
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -INT -- "-$p" 2>/dev/null || kill "$p" 2>/dev/null || true; done
  sleep 2
  for p in "${pids[@]}"; do kill -KILL -- "-$p" 2>/dev/null || true; done
}
trap cleanup EXIT

setsid Xvfb "$DISPLAY" -screen 0 1280x960x24 -nolisten tcp >/dev/null 2>&1 &
pids+=($!)
sleep 2

if $use_fake; then
  # Stand-in for bearing_sim_node: static solution of the launch file's load case.
  setsid roslaunch -p "$port" bearing_sim fake_ct_gantry.launch rviz:=true >/dev/null 2>&1 &
  pids+=($!)
elif grep -q "bearing_viz.launch" "$BEARING_SIM_ROOT/launch/ct_gantry.launch"; then
  setsid roslaunch -p "$port" bearing_sim ct_gantry.launch rviz:=true >/dev/null 2>&1 &
  pids+=($!)
else
  # ct_gantry.launch does not include the display yet: start it beside, in /bearing.
  setsid roslaunch -p "$port" bearing_sim ct_gantry.launch >/dev/null 2>&1 &
  pids+=($!)
  sleep 5
  ROS_NAMESPACE=bearing setsid roslaunch bearing_sim bearing_viz.launch rviz:=true \
    initial_speed_rad_s:=18.84955592153876 >/dev/null 2>&1 &
  pids+=($!)
fi
sleep 8
# Command the CT case of the paper on the inputs, as a user would: the display then also
# shows the applied-load arrow and the speed (the simulation starts with these values too).
setsid rostopic pub -l /bearing/load geometry_msgs/WrenchStamped \
  "{header: {frame_id: bearing}, wrench: {force: {x: 6800.0, y: 0.0, z: 0.0}, torque: {x: 0.0, y: 2100.0, z: 0.0}}}" \
  >/dev/null 2>&1 &
pids+=($!)
setsid rostopic pub -l /bearing/speed std_msgs/Float64 "data: 18.84955592153876" >/dev/null 2>&1 &
pids+=($!)
sleep "$settle_s"

mkdir -p "$(dirname "$out")"
xwd -root -display "$DISPLAY" | convert xwd:- png:"$out"
echo "saved $out"

#!/usr/bin/env bash
# Soak of both ROS nodes: 10 000 synthetic frames with 1 % malformed messages.
#
#   scripts/soak.sh [--no-build] [--frames N] [--render-frames N] [--scene S] [--period S]
#
# Renders a periodic synthetic sequence once (ply_slam_synth --loop, default office, 300
# frames, kept in build/soak/<scene>_loop_<N>/), starts its own roscore (a free port),
# tracking.launch and mapping.launch with the sequence's camera.yaml plus loop closure (dense
# maps and grid on, as shipped), and scripts/soak_publisher.py, which loops the frames to
# --frames good ones with increasing stamps, paced by the tracker, every 100th slot a malformed
# message (scripts/soak_publisher.py lists the kinds). scripts/soak_monitor.py samples both
# nodes' RSS and the map size every --period s (5). At the end: both nodes alive?
# save_trajectory and save_map answered? Then the nodes are stopped and
# scripts/soak_report.py checks every frame and fault against what the nodes report, computes
# ATE, writes build/soak/run/{soak.csv,soak.png,report.json} and the table between
# <!-- soak:begin --> and <!-- soak:end --> in docs/RESULTS.md. Exit 1 when a check failed.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

COMMAND="scripts/soak.sh"
for arg in "$@"; do COMMAND+=" $(printf '%q' "$arg")"; done

BUILD=1
FRAMES=10000
RENDER=300
SCENE=office
PERIOD=5
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) BUILD=0 ;;
    --frames) FRAMES="$2"; shift ;;
    --render-frames) RENDER="$2"; shift ;;
    --scene) SCENE="$2"; shift ;;
    --period) PERIOD="$2"; shift ;;
    -h | --help)
      sed -n '2,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *)
      echo "soak: unknown argument $1" >&2
      exit 2
      ;;
  esac
  shift
done
for n in "$FRAMES" "$RENDER"; do
  [[ "$n" =~ ^[0-9]+$ ]] && [ "$n" -ge 100 ] || { echo "soak: frame counts must be >= 100" >&2; exit 2; }
done

if [ "$BUILD" -eq 1 ]; then
  PLY_SLAM_PACKAGES+=(python3-matplotlib)  # the plot
  ply_slam_install_packages
  echo "[soak] building (log: ${PLY_SLAM_WS}/build.log)"
  ply_slam_build
fi
for tool in ply_slam_synth ply_slam_eval tracking_node mapping_node; do
  [ -x "${PLY_SLAM_BIN}/${tool}" ] || { echo "soak: ${PLY_SLAM_BIN}/${tool} not built" >&2; exit 1; }
done
/usr/bin/python3 -c 'import matplotlib' 2>/dev/null ||
  { echo "soak: needs python3-matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }

ROOT="${PLY_SLAM_ROOT}/build/soak"
SEQ="${ROOT}/${SCENE}_loop_${RENDER}"
ply_slam_render_once "$SEQ" "$SCENE" "$RENDER" "${ROOT}/render.log" --loop || exit 1
RUN="${ROOT}/run"
rm -rf "$RUN"
mkdir -p "$RUN/ros"
# As shipped configs run it: loop closure on (the synthetic camera.yaml leaves it off).
CONFIG="${RUN}/soak.yaml"
{ cat "${SEQ}/camera.yaml"; printf 'loop:\n  enabled: true\n'; } >"$CONFIG"

# A roscore of our own on a free port: other ROS work on the machine is not disturbed.
PORT=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://localhost:${PORT}" ROS_HOME="${RUN}/ros" ROS_LOG_DIR="${RUN}/ros"
set +u
source "${PLY_SLAM_WS}/devel/setup.bash"
set -u
PIDS=()
stop_all() {  # our processes only, newest first, by their id
  local i
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do kill -INT "${PIDS[i]}" 2>/dev/null || true; done
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do
    timeout 30 tail --pid="${PIDS[i]}" -f /dev/null || kill -KILL "${PIDS[i]}" 2>/dev/null || true
  done
  PIDS=()
}
trap stop_all EXIT
roscore -p "$PORT" >"${RUN}/roscore.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do rosparam list >/dev/null 2>&1 && break; sleep 0.2; done

# The node among roslaunch's children (it also runs a short-lived disk-usage check).
node_pid() {  # ROSLAUNCH_PID NODE_BINARY
  local pid
  for _ in $(seq 150); do
    pid=$(ps -o pid=,args= --ppid "$1" | awk -v b="/$2" 'index($2, b) {print $1; exit}')
    [ -n "$pid" ] && { echo "$pid"; return 0; }
    sleep 0.2
  done
  return 1
}
echo "[soak] roscore on port ${PORT}; nodes (logs: ${RUN}/tracker.log, ${RUN}/mapper.log)"
roslaunch ply_slam tracking.launch config:="$CONFIG" rgb_topic:=/camera/rgb/image_color \
  depth_topic:=/camera/depth/image camera_info_topic:=/camera/rgb/camera_info \
  world_frame:=ply_slam_world >"${RUN}/tracker.log" 2>&1 &
PIDS+=($!)
TRACKER=$(node_pid "${PIDS[-1]}" tracking_node)
# As tum_bag.launch: the optical-frame world upright under map.
roslaunch ply_slam mapping.launch config:="$CONFIG" world_frame:=ply_slam_world \
  world_in_map:="[0, 0, 0, -1.5707963, 0, -1.5707963]" camera_frame:=openni_rgb_optical_frame >"${RUN}/mapper.log" 2>&1 &
PIDS+=($!)
MAPPER=$(node_pid "${PIDS[-1]}" mapping_node)

/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/soak_monitor.py" "${RUN}/soak.csv" "$TRACKER" "$MAPPER" \
  --period "$PERIOD" --stop-file "${RUN}/stop" >"${RUN}/monitor.log" 2>&1 &
MONITOR=$!
echo "[soak] publishing ${FRAMES} frames (tracking_node ${TRACKER}, mapping_node ${MAPPER})"
STATUS=0
/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/soak_publisher.py" "$SEQ" "$RUN" --frames "$FRAMES" \
  2>&1 | tee "${RUN}/publisher.log" || STATUS=1
touch "${RUN}/stop"
wait "$MONITOR" || STATUS=1

# Alive at the end, and the services answer (their replies are checked by the report).
{
  for pid in "$TRACKER" "$MAPPER"; do
    if kill -0 "$pid" 2>/dev/null; then echo "alive $pid"; else echo "dead $pid"; fi
  done
} >"${RUN}/alive.txt"
rosservice call /ply_slam/mapping_node/save_trajectory "path: '${RUN}/CameraTrajectory.txt'" \
  >"${RUN}/save_trajectory.txt" 2>&1 || true
rosservice call /ply_slam/mapping_node/save_map "path: '${RUN}/map'" >"${RUN}/save_map.txt" 2>&1 || true
stop_all
trap - EXIT

/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/soak_report.py" "$RUN" "${PLY_SLAM_BIN}/ply_slam_eval" \
  "${PLY_SLAM_ROOT}/docs/RESULTS.md" "$COMMAND" "$SCENE" "$RENDER" || STATUS=1
exit $STATUS

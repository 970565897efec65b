#!/usr/bin/env bash
# Runs ply_slam on a TUM RGB-D folder and shows the result:
#   scripts/demo.sh [TUM_FOLDER]
# Installs what is missing, builds into build/ws, runs ply_slam_tum, prints accuracy and
# timing and where the outputs are. Without a folder it uses the shared fr1_rpy excerpt.
# The config follows the folder name (freiburg1/2/3); PLY_SLAM_CONFIG overrides it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

sequence="${1:-${PLY_SLAM_SHARED}/data/tum/rgbd_dataset_freiburg1_rpy_150_349}"
if [ ! -f "${sequence}/rgb.txt" ]; then
  echo "demo: ${sequence} is not a TUM RGB-D folder (no rgb.txt)." >&2
  echo "usage: scripts/demo.sh [TUM_FOLDER]" >&2
  exit 1
fi
config="${PLY_SLAM_CONFIG:-$(ply_slam_config_for "$sequence")}"

ply_slam_install_packages
echo "[demo] building (log: ${PLY_SLAM_WS}/build.log)"
ply_slam_build

out="${PLY_SLAM_ROOT}/build/demo/$(basename "$sequence")"
echo "[demo] running on ${sequence} with $(basename "$config")"
"${PLY_SLAM_BIN}/ply_slam_tum" --sequence "$sequence" --config "$config" --out "$out"
echo "[demo] trajectory plot: ${out}/trajectory.png"
echo "[demo] trajectories, timing.csv and summary.json: ${out}/"

#!/usr/bin/env bash
# Runs ply_slam on an RGB-D sequence and shows the result:
#   scripts/demo.sh [TUM_FOLDER]
# Installs what is missing, builds into build/ws, runs ply_slam_tum and prints accuracy,
# timing and where the outputs are. Without a folder it renders the synthetic office with two
# people walking through it (300 frames, cached in build/synth) and runs on that.
# For a TUM folder the config follows its name (freiburg1/2/3); PLY_SLAM_CONFIG overrides it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

sequence="${1:-}"
if [ -n "$sequence" ] && [ ! -f "${sequence}/rgb.txt" ]; then
  echo "demo: ${sequence} is not a TUM RGB-D folder (no rgb.txt)." >&2
  echo "usage: scripts/demo.sh [TUM_FOLDER]" >&2
  exit 1
fi

ply_slam_install_packages
echo "[demo] building (log: ${PLY_SLAM_WS}/build.log)"
ply_slam_build
ply_slam_vocabularies
SECONDS=0

if [ -z "$sequence" ]; then
  sequence="${PLY_SLAM_ROOT}/build/synth/office_walkers2_300"
  if [ ! -f "${sequence}/.complete" ]; then
    echo "[demo] rendering the synthetic office with two walkers into ${sequence}"
    rm -rf "$sequence"
    "${PLY_SLAM_BIN}/ply_slam_synth" --out "$sequence" --scene office --walkers 2 --frames 300
    touch "${sequence}/.complete"
  fi
fi
if [ -n "${PLY_SLAM_CONFIG:-}" ]; then
  config="$PLY_SLAM_CONFIG"
elif [ -f "${sequence}/camera.yaml" ]; then
  config="${sequence}/camera.yaml"
else
  config="$(ply_slam_config_for "$sequence")"
fi

# The best segmenter at hand: the folder's own instance masks (ground truth in the synthetic and
# the shared walkers sequences), else YOLOv8n-seg from the shared models, else none.
segmenter_args=(--segmenter none)
model="${PLY_SLAM_SHARED}/models/yolov8n-seg-480x640.onnx"  # file names are HxW, --input WxH
if [ -d "${sequence}/masks" ] && [ -f "${sequence}/instances.txt" ]; then
  segmenter_args=(--segmenter masks)
  echo "[demo] segmenter: the folder's instance masks"
elif [ -f "$model" ]; then
  segmenter_args=(--segmenter yolo --model "$model" --input 640x480)
  echo "[demo] segmenter: YOLOv8n-seg ${model}"
else
  echo "[demo] segmenter: none (no instance masks in the folder, no model at ${model})"
fi

out="${PLY_SLAM_ROOT}/build/demo/$(basename "$sequence")"
echo "[demo] running on ${sequence} with $(basename "$config")"
"${PLY_SLAM_BIN}/ply_slam_tum" --sequence "$sequence" --config "$config" --out "$out" \
  "${segmenter_args[@]}"
echo "[demo] trajectory plot: ${out}/trajectory.png"
echo "[demo] trajectories, timing.csv and summary.json: ${out}/"
if [[ -f "${out}/grid.png" ]]; then
  echo "[demo] semantic octree from above: ${out}/map_top.png; occupancy grid: ${out}/grid.png" \
    "(map.pgm + map.yaml for map_server)"
fi
echo "[demo] done in ${SECONDS} s after the build"

#!/usr/bin/env bash
# Live through both nodes (issue #51): the shared Bonn crowd window and fr1_rpy_150_349 as bags
# (scripts/tum_to_bag.py) through tum_bag.launch at the recorded rate and at 1.5x, with YOLOv8-seg
# 480x640, 320x320 and without a segmenter; each beside the offline run of the same settings
# (ply_slam_tum). Writes the table into docs/RESULTS.md ("live" section) and the runs into
# build/live_benchmark/.
#   scripts/live_benchmark.sh [--no-build] [--rates "1.0 1.5"] [--models "480x640 320x320 none"]
#                             [--launch tum_bag|turtlebot3]
# --launch turtlebot3: turtlebot3_d435i.launch (camera:=false) with its defaults, the bags written
#   with realsense2_camera's topics and encodings (tum_to_bag.py --d435i) and played beside it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

build=true rates="1.0 1.5" models="480x640 320x320 none" launch=tum_bag
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=false ;;
    --rates) rates=$2; shift ;;
    --models) models=$2; shift ;;
    --launch) launch=$2; shift ;;
    *) echo "usage: scripts/live_benchmark.sh [--no-build] [--rates R] [--models M] [--launch L]" >&2
       exit 2 ;;
  esac
  shift
done
if $build; then ply_slam_install_packages; ply_slam_build; ply_slam_vocabularies; fi
set +u
source "${PLY_SLAM_WS}/devel/setup.bash"
set -u

OUT="${PLY_SLAM_ROOT}/build/live_benchmark"
mkdir -p "$OUT"
SEQUENCES=(bonn/rgbd_bonn_crowd_150_449 tum/rgbd_dataset_freiburg1_rpy_150_349)
ROWS="${OUT}/rows.jsonl"
: >"$ROWS"

model_path() {  # 480x640 | 320x320 | none
  [ "$1" = none ] && return 0
  echo "${PLY_SLAM_SHARED}/models/yolov8n-seg-$1.onnx"
}

for seq in "${SEQUENCES[@]}"; do
  dir="${PLY_SLAM_SHARED}/data/${seq}" name=$(basename "$seq")
  [ -d "$dir" ] || { echo "live_benchmark: ${dir} missing" >&2; exit 1; }
  config=$(ply_slam_config_for "$dir")
  frames=$(grep -vc '^#' "${dir}/associations.txt" 2>/dev/null || grep -vc '^#' "${dir}/rgb.txt")
  bag="${OUT}/${name}.bag" bag_options=(--config "$config") robot=()
  if [ "$launch" = turtlebot3 ]; then
    bag="${OUT}/${name}_d435i.bag" bag_options+=(--d435i) robot=(--robot)
  fi
  if [ ! -f "$bag" ] || [ "$bag" -ot "$dir" ]; then
    echo "[live] writing ${bag}"
    /usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/tum_to_bag.py" "$dir" "${bag}.part" "${bag_options[@]}" \
      >"${bag}.log" 2>&1 && mv -f "${bag}.part" "$bag"
  fi
  for model in $models; do
    tag="${name}_${model}"
    segmenter=(--segmenter none)
    [ "$model" != none ] && segmenter=(--segmenter yolo --model "$(model_path "$model")")
    echo "[live] offline ${tag}"
    "${PLY_SLAM_BIN}/ply_slam_tum" --sequence "$dir" --config "$config" --out "${OUT}/offline_${tag}" \
      "${segmenter[@]}" >"${OUT}/offline_${tag}.log" 2>&1 || true
    for rate in $rates; do
      echo "[live] ${launch} ${tag} rate ${rate}"
      /usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/live_run.py" --bag "$bag" --config "$config" \
        --frames "$frames" --groundtruth "${dir}/groundtruth.txt" --eval "${PLY_SLAM_BIN}/ply_slam_eval" \
        --out "${OUT}/live_${launch}_${tag}_${rate}" --model "$(model_path "$model")" --rate "$rate" \
        "${robot[@]}" >"${OUT}/live_${launch}_${tag}_${rate}.json" || {
        echo "[live] run failed: ${OUT}/live_${launch}_${tag}_${rate}/" >&2; continue; }
      /usr/bin/python3 - "$tag" "$name" "${OUT}/offline_${tag}/summary.json" \
        "${OUT}/live_${launch}_${tag}_${rate}.json" >>"$ROWS" <<'EOF'
import json, sys
tag, seq, offline, live = sys.argv[1:5]
row = json.load(open(live))
row["sequence"] = seq
try:
    s = json.load(open(offline))
    row["offline_ate"] = s.get("ate", {}).get("rmse")
    row["offline_peak_rss_mb"] = s.get("peak_rss_mb")
    row["offline_tracked"] = s.get("tracked")
except (OSError, ValueError):
    row["offline_ate"] = None
print(json.dumps(row))
EOF
    done
  done
done
/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/live_table.py" "$ROWS" "$launch" >"${OUT}/section_${launch}.md"
/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/results_section.py" "live_${launch}" \
  "${PLY_SLAM_ROOT}/docs/RESULTS.md" "${OUT}/section_${launch}.md"
cat "${OUT}/section_${launch}.md"

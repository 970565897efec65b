#!/usr/bin/env bash
# Dynamic-feature rejection on the shared walkers sequence and its static twin: ATE for every
# --dynamic mode with YOLO and with the ground-truth masks, the feature-level classification
# against the ground-truth masks, tracking and segmentation ms; and on the real Bonn crowd
# window (config/bonn.yaml): off, geometric, YOLO 480x640 full offline and live.
#
#   scripts/dynamic_benchmark.sh [--no-build] [--models "640x640 320x320"]
#
# Runs go to build/dynamic_benchmark/<run>/; the table replaces the section between
# <!-- dynamic:begin --> and <!-- dynamic:end --> in docs/RESULTS.md.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

COMMAND="scripts/dynamic_benchmark.sh $*"
BUILD=1
MODELS="640x640 320x320"
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) BUILD=0 ;;
    --models) MODELS="$2"; shift ;;
    *) echo "dynamic_benchmark: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

WALKERS="${PLY_SLAM_SHARED}/data/dynamic/fr1_rpy_150_349_walkers"
STATIC="${PLY_SLAM_SHARED}/data/tum/rgbd_dataset_freiburg1_rpy_150_349"
BONN="${PLY_SLAM_SHARED}/data/bonn/rgbd_bonn_crowd_150_449"
for d in "$WALKERS" "$STATIC" "$BONN"; do
  [ -d "$d" ] || { echo "dynamic_benchmark: missing $d" >&2; exit 1; }
done
if [ "$BUILD" -eq 1 ]; then
  ply_slam_install_packages
  ply_slam_build
fi

OUT="${PLY_SLAM_ROOT}/build/dynamic_benchmark"
mkdir -p "$OUT"
CONFIG="${PLY_SLAM_ROOT}/config/tum_fr1.yaml"
ROWS="$OUT/rows.tsv"
: >"$ROWS"

run() {  # name sequence segmenter mode [model size HxW] [more ply_slam_tum options]
  local name=$1 seq=$2 seg=$3 mode=$4 args=()
  if [ "$seg" = yolo ]; then
    # Model files are named HxW; --input takes WxH.
    args=(--model "${PLY_SLAM_SHARED}/models/yolov8n-seg-$5.onnx" --input "${5#*x}x${5%x*}")
  fi
  args+=("${@:6}")
  echo "[dynamic] $name"
  rm -rf "${OUT:?}/$name"  # a failed run must not leave an old summary behind
  "${PLY_SLAM_BIN}/ply_slam_tum" --sequence "$seq" --config "${RUN_CONFIG:-$CONFIG}" \
    --out "$OUT/$name" --segmenter "$seg" --dynamic "$mode" "${args[@]}" \
    >"$OUT/$name.log" 2>&1 </dev/null ||
    echo "[dynamic] $name failed: $OUT/$name.log" >&2
  printf '%s\t%s\n' "$name" "$OUT/$name/summary.json" >>"$ROWS"
}

run static_off "$STATIC" none off
run static_full "$STATIC" none full
for mode in off geometric semantic full; do run "walkers_masks_$mode" "$WALKERS" masks "$mode"; done
for size in $MODELS; do
  run "static_yolo${size}_full" "$STATIC" yolo full "$size"
  for mode in off geometric semantic full; do
    run "walkers_yolo${size}_$mode" "$WALKERS" yolo "$mode" "$size"
  done
done
export RUN_CONFIG="${PLY_SLAM_ROOT}/config/bonn.yaml"
run bonn_off "$BONN" none off
run bonn_geometric "$BONN" none geometric
run bonn_yolo480x640_full "$BONN" yolo full 480x640
run bonn_yolo480x640_full_live "$BONN" yolo full 480x640 --live
unset RUN_CONFIG

/usr/bin/python3 - "$ROWS" "$OUT/section.md" "$COMMAND" <<'PY'
import json, sys
rows, section, command = sys.argv[1], sys.argv[2], sys.argv[3]
lines = ["Command: `%s` (config/tum_fr1.yaml; walkers = fr1_rpy_150_349_walkers, static = its twin "
         "rgbd_dataset_freiburg1_rpy_150_349; bonn = rgbd_bonn_crowd_150_449 with config/bonn.yaml, "
         "live = --live). Walker features: keypoints on a ground-truth walker mask; "
         "static: farther than 5 px from one. *Kept*: not dropped by the rejection; *used*: inlier of the "
         "pose optimisation. Dense ghosts: share of the dense map's points, and of the octree's occupied "
         "voxels, that mostly come from ground-truth walker pixels (section \"Dense and semantic "
         "octree maps\")." % command, "",
         "| run | segmenter | --dynamic | ATE RMSE (m) | lost | walker features kept | walker features used | static dropped | dense points from walkers | octree voxels from walkers | tracking ms median | segmentation ms median |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for line in open(rows):
    name, path = line.rstrip("\n").split("\t")
    try:
        s = json.load(open(path))
    except Exception:
        lines.append("| %s | failed | | | | | | | | | | |" % name)
        continue
    c = s.get("feature_classification")
    pct = lambda k: "%.1f %%" % (100 * c[k]) if c else "–"
    seg = s["segmenter"]
    w = s.get("dense", {}).get("walkers")
    ghost = lambda k: "%.2f %%" % (100 * w[k]) if w else "–"
    lines.append("| %s | %s | %s | %.4f | %d | %s | %s | %s | %s | %s | %.1f | %s |" % (
        name, seg, s["dynamic_mode"], s["ate"]["rmse"] if "ate" in s else float("nan"), s["lost"],
        pct("walker_kept_share"), pct("walker_inlier_share"), pct("static_dropped_share"),
        ghost("points_share"), ghost("voxels_majority_share"),
        s["tracking_ms_median"], "%.0f" % s["segmentation_ms_median"] if seg != "none" else "–"))
with open(section, "w") as f:
    f.write("<!-- dynamic:begin -->\n" + "\n".join(lines) + "\n<!-- dynamic:end -->\n")
print("\n".join(lines))
PY
/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/results_section.py" dynamic "${PLY_SLAM_ROOT}/docs/RESULTS.md" \
  "$OUT/section.md"

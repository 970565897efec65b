#!/usr/bin/env bash
# Relocalisation after a kidnap (30 frames skipped, ten cut positions) and after a covered lens
# (10 black frames, five positions) on fr1_rpy_150_349, the Bonn crowd window and the synthetic
# office, low-texture room and corridor (600 frames, --loop); scripts/kidnap_benchmark.py runs
# them and writes the table between <!-- kidnap:begin --> and <!-- kidnap:end --> in
# docs/RESULTS.md.
#
#   scripts/kidnap_benchmark.sh [--no-build]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

COMMAND="scripts/kidnap_benchmark.sh $*"
BUILD=1
for arg in "$@"; do
  case "$arg" in
    --no-build) BUILD=0 ;;
    *) echo "kidnap_benchmark: unknown option $arg" >&2; exit 2 ;;
  esac
done
if [ "$BUILD" -eq 1 ]; then
  ply_slam_install_packages
  ply_slam_build
fi

OUT="${PLY_SLAM_ROOT}/build/kidnap_benchmark"
mkdir -p "$OUT"
SPECS=(
  "${PLY_SLAM_SHARED}/data/tum/rgbd_dataset_freiburg1_rpy_150_349:${PLY_SLAM_ROOT}/config/tum_fr1.yaml"
  "${PLY_SLAM_SHARED}/data/bonn/rgbd_bonn_crowd_150_449:${PLY_SLAM_ROOT}/config/bonn.yaml"
)
for scene in office lowtexture corridor; do
  dir="${OUT}/${scene}_loop600"
  ply_slam_render_once "$dir" "$scene" 600 "${OUT}/render_${scene}.log" --loop
  # Without the dense maps, which take no part in relocalisation (a third of the run's time).
  { cat "${dir}/camera.yaml"; printf 'dense:\n  enabled: false\n'; } >"${OUT}/${scene}.yaml"
  SPECS+=("${dir}:${OUT}/${scene}.yaml")
done
/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/kidnap_benchmark.py" "$PLY_SLAM_BIN" "$OUT" \
  "${PLY_SLAM_ROOT}/docs/RESULTS.md" "$COMMAND" "${SPECS[@]}"

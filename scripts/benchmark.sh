#!/usr/bin/env bash
# Side-by-side benchmark: ply_slam (ply_slam_tum) against OpenCV's dense RgbdOdometry
# (ply_slam_rgbd_odometry, default parameters, frame to frame) on TUM RGB-D folders.
#
#   scripts/benchmark.sh [--no-build] [SEQUENCE_DIR...]
#
# Default sequences: the two shared TUM excerpts under $PLY_SLAM_SHARED/data/tum. The config
# is chosen from the folder name ("freiburgN" or "frN" -> config/tum_frN.yaml). Results go to
# build/benchmark/<sequence>/{ply_slam,rgbd_odometry}/ and one table replaces the section
# between <!-- benchmark:begin --> and <!-- benchmark:end --> in docs/RESULTS.md.
# --no-build reuses the binaries of the last build. Exit code 1 when any run or evaluation
# failed (the table is written anyway and marks it).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

# The exact invocation, recorded in the results so they can be reproduced.
COMMAND="scripts/benchmark.sh"
for arg in "$@"; do COMMAND+=" $(printf '%q' "$arg")"; done

BUILD=1
SEQUENCES=()
for arg in "$@"; do
  case "$arg" in
    --no-build) BUILD=0 ;;
    -h | --help)
      sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    -*)
      echo "benchmark: unknown option $arg" >&2
      exit 2
      ;;
    *) SEQUENCES+=("${arg%/}") ;;
  esac
done
if [ ${#SEQUENCES[@]} -eq 0 ]; then
  SEQUENCES=(
    "${PLY_SLAM_SHARED}/data/tum/rgbd_dataset_freiburg1_xyz_37"
    "${PLY_SLAM_SHARED}/data/tum/rgbd_dataset_freiburg1_rpy_150_349"
    "${PLY_SLAM_SHARED}/data/bonn/rgbd_bonn_crowd_150_449"
  )
fi

# Fail early, before a long build, on a folder or config that cannot work.
for seq in "${SEQUENCES[@]}"; do
  [ -d "$seq" ] || { echo "benchmark: sequence folder missing: $seq" >&2; exit 1; }
done

for seq in "${SEQUENCES[@]}"; do ply_slam_config_for "$seq" >/dev/null; done

if [ "$BUILD" -eq 1 ]; then
  ply_slam_install_packages
  echo "[benchmark] building (log: ${PLY_SLAM_WS}/build.log)"
  ply_slam_build
fi
for tool in ply_slam_tum ply_slam_rgbd_odometry ply_slam_eval; do
  [ -x "${PLY_SLAM_BIN}/${tool}" ] || { echo "benchmark: ${PLY_SLAM_BIN}/${tool} not built" >&2; exit 1; }
done

PY=/usr/bin/python3  # the system interpreter: only the standard library is needed
OUT_ROOT="${PLY_SLAM_ROOT}/build/benchmark"
RESULTS="${PLY_SLAM_ROOT}/docs/RESULTS.md"
ROWS="$(mktemp)"
trap 'rm -f "$ROWS"' EXIT
STATUS=0

# json_value FILE KEY FORMAT: the formatted number at top-level KEY, or "n/a".
json_value() {
  "$PY" - "$1" "$2" "$3" <<'EOF' 2>/dev/null || echo "n/a"
import json, sys
path, key, fmt = sys.argv[1:4]
with open(path) as f:
    print(format(float(json.load(f)[key]), fmt))
EOF
}

# evaluate GT EST DIR: writes DIR/ate.json, DIR/rpe.json (consecutive frames) and
# DIR/rpe_1s.json; returns 1 when any fails.
evaluate() {
  local gt="$1" est="$2" dir="$3" ok=0
  rm -f "$dir/ate.json" "$dir/rpe.json" "$dir/rpe_1s.json"
  "${PLY_SLAM_BIN}/ply_slam_eval" ate "$gt" "$est" --json >"$dir/ate.json.tmp" &&
    mv "$dir/ate.json.tmp" "$dir/ate.json" || ok=1
  "${PLY_SLAM_BIN}/ply_slam_eval" rpe "$gt" "$est" --delta 1 --json >"$dir/rpe.json.tmp" &&
    mv "$dir/rpe.json.tmp" "$dir/rpe.json" || ok=1
  "${PLY_SLAM_BIN}/ply_slam_eval" rpe "$gt" "$est" --delta-seconds 1 --json >"$dir/rpe_1s.json.tmp" &&
    mv "$dir/rpe_1s.json.tmp" "$dir/rpe_1s.json" || ok=1
  rm -f "$dir/ate.json.tmp" "$dir/rpe.json.tmp" "$dir/rpe_1s.json.tmp"
  return $ok
}

# add_row SEQUENCE METHOD DIR TIMING_JSON RUN_OK: one markdown table row from DIR's results.
add_row() {
  local name="$1" method="$2" dir="$3" timing="$4" run_ok="$5"
  if [ "$run_ok" -ne 0 ]; then
    echo "| $name | $method | failed | failed | failed | failed | failed | failed | failed | failed | failed |" >>"$ROWS"
    return
  fi
  echo "| $name | $method | $(json_value "$dir/ate.json" rmse .4f)" \
    "| $(json_value "$dir/ate.json" sim3_rmse .4f)" \
    "| $(json_value "$dir/ate.json" sim3_scale .3f)" \
    "| $(json_value "$dir/rpe.json" trans_rmse .4f)" \
    "| $(json_value "$dir/rpe.json" rot_rmse_deg .3f)" \
    "| $(json_value "$dir/rpe_1s.json" trans_rmse .4f)" \
    "| $(json_value "$dir/rpe.json" trans_max .4f)" \
    "| $(json_value "$timing" lost .0f)" \
    "| $(json_value "$timing" tracking_ms_median .1f) |" >>"$ROWS"
}

for seq in "${SEQUENCES[@]}"; do
  name="$(basename "$seq")"
  config="$(ply_slam_config_for "$seq")"
  gt="$seq/groundtruth.txt"
  slam_dir="${OUT_ROOT}/${name}/ply_slam"
  odo_dir="${OUT_ROOT}/${name}/rgbd_odometry"
  mkdir -p "$slam_dir" "$odo_dir"
  echo "[benchmark] ${name} ($(basename "$config"))"

  slam_ok=0
  echo "[benchmark]   ply_slam_tum (log: ${slam_dir}/run.log)"
  "${PLY_SLAM_BIN}/ply_slam_tum" --sequence "$seq" --config "$config" --out "$slam_dir" \
    >"${slam_dir}/run.log" 2>&1 || { slam_ok=1; tail -n 20 "${slam_dir}/run.log"; }

  odo_ok=0
  echo "[benchmark]   ply_slam_rgbd_odometry (log: ${odo_dir}/run.log)"
  "${PLY_SLAM_BIN}/ply_slam_rgbd_odometry" --sequence "$seq" --config "$config" \
    --out "${odo_dir}/CameraTrajectory.txt" --timing-json "${odo_dir}/timing.json" \
    >"${odo_dir}/run.log" 2>&1 || { odo_ok=1; tail -n 20 "${odo_dir}/run.log"; }

  if [ -f "$gt" ]; then
    if [ "$slam_ok" -eq 0 ]; then
      evaluate "$gt" "${slam_dir}/CameraTrajectory.txt" "$slam_dir" || STATUS=1
    fi
    if [ "$odo_ok" -eq 0 ]; then
      evaluate "$gt" "${odo_dir}/CameraTrajectory.txt" "$odo_dir" || STATUS=1
    fi
  else
    echo "[benchmark]   no groundtruth.txt: accuracy columns stay n/a"
  fi
  [ "$slam_ok" -eq 0 ] && [ "$odo_ok" -eq 0 ] || STATUS=1

  add_row "$name" "ply_slam" "$slam_dir" "${slam_dir}/summary.json" "$slam_ok"
  add_row "$name" "OpenCV RgbdOdometry" "$odo_dir" "${odo_dir}/timing.json" "$odo_ok"
done

# The generated section, then spliced into docs/RESULTS.md between the markers.
SECTION="$(mktemp)"
trap 'rm -f "$ROWS" "$SECTION"' EXIT
{
  echo "<!-- benchmark:begin -->"
  echo "<!-- generated by scripts/benchmark.sh; edits between these markers are overwritten -->"
  echo "## Benchmark: ply_slam vs. OpenCV RgbdOdometry"
  echo
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- machine: $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'))"
  echo "- command: \`${COMMAND}\`"
  echo "- ply_slam: \`ply_slam_tum\`, the whole system; ms per frame = median time of a whole"
  echo "  frame (features + tracking)."
  echo "- OpenCV RgbdOdometry: \`ply_slam_rgbd_odometry\`, opencv_contrib \`rgbd::RgbdOdometry\`"
  echo "  with default parameters, frame to frame, no map; ms per frame = median odometry time."
  echo "- ATE: RMSE after rigid alignment (no scale); beside it with scale (Sim(3)) and the scale"
  echo "  fitted (> 1: the estimate is smaller than the truth); RPE: RMSE over consecutive frames and"
  echo "  over 1 s; largest jump: the largest translation error between consecutive frames;"
  echo "  lost: frames ply_slam could not track (RgbdOdometry reports none)."
  echo
  echo "| sequence | method | ATE RMSE (m) | ATE Sim(3) (m) | scale | RPE trans (m/frame) | RPE rot (deg/frame) | RPE trans (m/s) | largest jump (m) | lost | ms per frame |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  cat "$ROWS"
  echo "<!-- benchmark:end -->"
} >"$SECTION"

mkdir -p "$(dirname "$RESULTS")"
"$PY" "${PLY_SLAM_ROOT}/scripts/results_section.py" benchmark "$RESULTS" "$SECTION"

cat "$ROWS"
echo "[benchmark] table written to ${RESULTS}"
exit $STATUS

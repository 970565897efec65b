#!/usr/bin/env bash
# Bad input as a hostile user gives it: broken configs, a ground truth that does not
# fit, outputs that cannot be written, swapped model sizes, unknown options, duplicate and huge
# poses for ply_slam_eval. Prints one line per case: name, exit code, the last words on stderr
# (the "Bad input" table of docs/RESULTS.md). Runs the binaries of the last build
# ($PLY_SLAM_BIN), on the shared fr1_xyz_37 ($PLY_SLAM_SHARED, default ../shared).
#
#   scripts/bad_input.sh [OUT_DIR]   (default build/bad_input; emptied first)
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${PLY_SLAM_BIN:-${ROOT}/build/ws/devel/lib/ply_slam}"
SHARED="${PLY_SLAM_SHARED:-$(cd "${ROOT}/.." && pwd)/shared}"
SEQ="${SHARED}/data/tum/rgbd_dataset_freiburg1_xyz_37"
CONFIG="${ROOT}/config/tum_fr1.yaml"
OUT="${1:-${ROOT}/build/bad_input}"
rm -rf "$OUT" && mkdir -p "$OUT/configs" || exit 1
cd "$OUT" || exit 1

# One line of the config changed (sed expression) into configs/NAME.yaml.
variant() { sed "$2" "$CONFIG" >"configs/$1.yaml"; }
variant fx_tiny 's/^  fx: 517.3/  fx: 1e-300/'
variant fy_inf 's/^  fy: 516.5/  fy: .inf/'
variant distortion_nan 's/^  distortion: \[0.2624/  distortion: [.nan/'
variant readout_nan 's/^  rolling_shutter_readout: 0.02/  rolling_shutter_readout: .nan/'
variant alpha_nan 's/^    alpha: 2.5e-5/    alpha: .nan/'
variant fx_twice 's/^  fy: 516.5/  fy: 516.5\n  fx: 600/'

# The sequence's images with its ground truth 1000 s later.
mkdir -p late_gt
for f in rgb depth rgb.txt depth.txt associations.txt; do ln -sfn "$SEQ/$f" "late_gt/$f"; done
awk '/^#/ {next} {printf "%.4f", $1 + 1000; for (i = 2; i <= NF; i++) printf " %s", $i; print ""}' \
  "$SEQ/groundtruth.txt" >late_gt/groundtruth.txt

report() {  # NAME EXIT: the last two lines the tool said on stderr
  printf '%s\t%s\t%s\n' "$1" "$2" "$(grep '^ply_slam' "$1.err" | tail -n 2 | tr '\n' ' ' | cut -c1-240)"
}
tum() {
  local name=$1
  shift
  timeout 600 "$BIN/ply_slam_tum" "$@" >"$name.out" 2>"$name.err"
  report "$name" $?
}
for cfg in fx_tiny fy_inf distortion_nan readout_nan alpha_nan fx_twice; do
  tum "$cfg" --sequence "$SEQ" --config "configs/$cfg.yaml" --out "out_$cfg"
done
tum config_dir --sequence "$SEQ" --config configs --out out_config_dir
tum late_gt --sequence late_gt --config "$CONFIG" --out out_late_gt
mkdir -p out_summary_dir/summary.json
tum summary_dir --sequence "$SEQ" --config "$CONFIG" --out out_summary_dir
mkdir -p out_devfull
ln -sf /dev/full out_devfull/timing.csv
ln -sf /dev/full out_devfull/dense_map.ply
tum devfull --sequence "$SEQ" --config "$CONFIG" --out out_devfull
tum help --help
tum no_line --no-line --sequence "$SEQ" --config "$CONFIG" --out out_no_line
tum model_no_yolo --sequence "$SEQ" --config "$CONFIG" --out out_model_no_yolo \
  --model "$SHARED/models/yolov8n-seg-320x320.onnx"
tum two_frames --sequence "$SEQ" --config "$CONFIG" --out out_two_frames --max-frames 2
tum input_swapped --sequence "$SEQ" --config "$CONFIG" --out out_input_swapped --segmenter yolo \
  --model "$SHARED/models/yolov8n-seg-480x640.onnx" --input 480x640 --max-frames 3

printf '1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.20 2 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n' >gt.txt
printf '1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.10 1.5 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n' >est_dup.txt
printf '1.00 1e308 0 0 0 0 0 1\n1.10 -1e308 0 0 0 0 0 1\n1.20 1e308 0 0 0 0 0 1\n1.30 -1e308 0 0 0 0 0 1\n' \
  >est_huge.txt
for est in dup huge; do
  "$BIN/ply_slam_eval" ate gt.txt "est_$est.txt" --json >"eval_$est.out" 2>"eval_$est.err"
  rc=$?
  cat "eval_$est.out" >>"eval_$est.err"
  report "eval_$est" $rc
done
for tool in ply_slam_eval ply_slam_lines ply_slam_loops ply_slam_map_compare \
  ply_slam_rgbd_odometry ply_slam_segment ply_slam_synth ply_slam_tum ply_slam_vocabulary; do
  "$BIN/$tool" --help >/dev/null 2>&1
  help=$?
  "$BIN/$tool" --bogus >/dev/null 2>"$tool.err"
  printf '%s\t--help %s, --bogus %s\t%s\n' "$tool" "$help" $? "$(head -n 1 "$tool.err" | cut -c1-100)"
done

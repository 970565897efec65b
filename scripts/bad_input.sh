#!/usr/bin/env bash
# Bad input as a hostile user gives it, to every tool: broken, cyclic and huge configs, sequences
# with missing, special, truncated or wrong images, damaged maps and vocabularies, outputs that
# cannot be written (a full disk, /dev/full, a FIFO), bad options. Each case runs under a 10 s
# timeout (issue #53's hang bound) and prints one Markdown row: case, what is tried, exit code,
# what the tool said (its last words on stderr) and the verdict: "ok" when it ended as it should
# (the expected exit code, the file or key named, a kept file unchanged, no partial output),
# else CRASH (exit >= 128), HANG (timed out) or WRONG. The "Bad input" table of
# docs/RESULTS.md. Runs the binaries of the last build ($PLY_SLAM_BIN) on the shared fr1_xyz_37
# ($PLY_SLAM_SHARED, default ../shared). The full-disk cases mount a 200 kB tmpfs (root only;
# otherwise they say "skipped").
#
#   scripts/bad_input.sh [OUT_DIR]   (default build/bad_input; emptied first)
#
# Exit code: the number of rows that did not end as they should (0: all did).
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${PLY_SLAM_BIN:-${ROOT}/build/ws/devel/lib/ply_slam}"
SHARED="${PLY_SLAM_SHARED:-$(cd "${ROOT}/.." && pwd)/shared}"
SEQ="${SHARED}/data/tum/rgbd_dataset_freiburg1_xyz_37"
CONFIG="${ROOT}/config/tum_fr1.yaml"
OUT="${1:-${ROOT}/build/bad_input}"
HANG_S=10
FULL="" # the tmpfs, once mounted
[ -d "$OUT/full" ] && umount "$OUT/full" 2>/dev/null
rm -rf "$OUT" && mkdir -p "$OUT"/{configs,logs,o} || exit 1
OUT="$(cd "$OUT" && pwd)"
cd "$OUT" || exit 1
trap '[ -n "$FULL" ] && umount "$FULL" 2>/dev/null' EXIT
ROWS=0 WRONG=0 CHECK=""

# ---- how a case is run and judged --------------------------------------------------------------

said() {  # FILE: what the tool said last (its own lines when it names itself), one line
  local lines  # (without its notes on outputs removed and on an empty dense cloud)
  lines="$(grep -aE '^ply_slam[a-z_]*:' "$1" | grep -avE '^ply_slam[a-z_]*: removed |dense cloud is empty' |
    tail -n 2)"
  [ -n "$lines" ] || lines="$(grep -av '^\s*$' "$1" | grep -av '^usage:' | tail -n 1)"
  printf '%s' "$lines" | tr '\n\t' '  ' | LC_ALL=C tr -c '[:print:]' '?' | sed 's/|/\\|/g; s/`/'"'"'/g' | cut -c1-220
}

# NAME EXPECT PATTERN WHAT -- COMMAND...: EXPECT is the exit code it should end with (0, 1, 2, 3),
# "fail" (any of 1..127) or "any" (no crash nor hang; $CHECK judges); PATTERN (may be empty) must appear in what it says on stderr (the
# file or key at fault). $CHECK, when set, is run after it and prints what is wrong, if anything.
case_() {
  local name=$1 expect=$2 pattern=$3 what=$4
  shift 5
  timeout -k 2 "$HANG_S" "$@" >"logs/$name.out" 2>"logs/$name.err" </dev/null
  local rc=$? verdict=ok
  if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    verdict="HANG (killed after ${HANG_S} s)"
  elif [ $rc -ge 128 ]; then
    verdict="CRASH"
  elif [ "$expect" = fail ] && { [ $rc -eq 0 ] || [ $rc -gt 127 ]; }; then
    verdict="WRONG: exit $rc"
  elif [ "$expect" != fail ] && [ "$expect" != any ] && [ $rc -ne "$expect" ]; then
    verdict="WRONG: exit $rc, not $expect"
  elif [ "$expect" = any ]; then
    :
  elif [ -n "$pattern" ] && ! grep -aqF -- "$pattern" "logs/$name.err"; then
    verdict="WRONG: does not name '$pattern'"
  fi
  if [ -n "$CHECK" ]; then
    local problem
    problem="$($CHECK)"
    [ -n "$problem" ] && verdict="${verdict/#ok/WRONG:} ${problem}"
  fi
  CHECK=""
  ROWS=$((ROWS + 1))
  [ "$verdict" = ok ] || WRONG=$((WRONG + 1))
  printf '| %d | %s | %s | %s | %s | %s |\n' "$ROWS" "$name" "$what" "$rc" \
    "$(said "logs/$name.err")" "$verdict"
}

# ---- what the cases are made of ----------------------------------------------------------------

variant() { sed "$2" "$CONFIG" >"configs/$1.yaml"; }  # NAME SED: one line of the config changed
appended() { { cat "$CONFIG"; printf '%b' "$2"; } >"configs/$1.yaml"; }  # NAME TEXT: config + TEXT

farm() {  # DIR: a copy of the sequence, lists copied, images linked one by one
  mkdir -p "$1" && cp "$SEQ"/*.txt "$1"/ && cp -as "$SEQ/rgb" "$1/rgb" && cp -as "$SEQ/depth" "$1/depth"
}
nth() {  # DIR KIND K: the K-th (from 1) associated rgb or depth image of the folder
  local column=2
  [ "$2" = depth ] && column=4
  awk -v k="$3" -v c=$column '!/^#/ && ++n == k {print $c}' "$1/associations.txt"
}
broken_image() {  # NAME KIND HOW: a farm whose 3rd rgb or depth image is replaced as HOW says
  local dir="seq_$1" file
  farm "$dir"
  file="$dir/$(nth "$dir" "$2" 3)"
  local source
  source="$(readlink -f "$file")"
  rm -f "$file"
  case $3 in
    missing) ;;
    dir) mkdir "$file" ;;
    fifo) mkfifo "$file" ;;
    empty) : >"$file" ;;
    truncated) head -c 2000 "$source" >"$file" ;;
    garbage) head -c 5000 /dev/urandom >"$file" ;;
    loop) ln -s "$(basename "$file")" "$file" ;;
    small) py "import cv2; cv2.imwrite('$file', cv2.resize(cv2.imread('$source', -1), (320, 240)))" ;;
    gray) py "import cv2; cv2.imwrite('$file', cv2.imread('$source', 0))" ;;
    colour) cp "$(readlink -f "$dir/$(nth "$dir" rgb 3)")" "$file" ;;  # an rgb image as depth
    float) py "import cv2, numpy as n; cv2.imwrite('$file'.replace('.png', '.exr'), n.ones((480, 640), n.float32))"
      [ -f "${file%.png}.exr" ] && mv "${file%.png}.exr" "$file" ;;
  esac
}
py() { /usr/bin/python3 -c "$1"; }

T="$BIN/ply_slam_tum"  # the main tool
BASE=(--config "$CONFIG" --max-frames 8)

unchanged() {  # FILE REFERENCE: prints a complaint when FILE is no longer the same as REFERENCE
  cmp -s "$1" "$2" || echo "$(basename "$1") changed"
}
finite_poses() {  # DIR: prints a complaint when DIR's CameraTrajectory.txt holds a NaN or inf
  ! grep -qiE 'nan|inf' "$1/CameraTrajectory.txt" 2>/dev/null || echo "non-finite poses"
}
no_partial() {  # DIR: no temporary, empty or half-named output left in DIR
  local leftovers
  leftovers="$(find "$1" -name '*.tmp-*' -o -type f -size 0 | sed "s|$1/||" | tr '\n' ' ')"
  [ -z "$leftovers" ] || echo "left: $leftovers"
}

# ---- the inputs the cases share ----------------------------------------------------------------

mkdir -p maps vocs lists
echo "[bad_input] making a map and a vocabulary to spoil" >&2
"$BIN/ply_slam_tum" --sequence "$SEQ" --config "$CONFIG" --max-frames 15 --out o/map_run \
  --save-map maps/good >/dev/null 2>&1 || echo "[bad_input] saving the map failed" >&2
"$BIN/ply_slam_vocabulary" --images "$SEQ/rgb" --kind orb --k 4 --levels 2 --out vocs/good.voc \
  >/dev/null 2>&1 || echo "[bad_input] training the vocabulary failed" >&2
for how in truncated checksum forged dir fifo empty garbage; do mkdir -p "maps/$how"; done
GOOD_MAP=maps/good/map.plymap
head -c "$(($(stat -c %s $GOOD_MAP) / 2))" $GOOD_MAP >maps/truncated/map.plymap
# One byte flipped in the middle; "forged": eight bytes there set to a NaN and the checksum
# (FNV-1a 64 of all but the last 8 bytes, little-endian) made to fit again.
py "
import struct, sys
b = bytearray(open('$GOOD_MAP', 'rb').read()); m = len(b) // 2
c = bytearray(b); c[m] ^= 0xff; open('maps/checksum/map.plymap', 'wb').write(c)
b[m:m + 8] = struct.pack('<d', float('nan'))
h = 0xcbf29ce484222325
for x in b[:-8]: h = ((h ^ x) * 0x100000001b3) & 0xffffffffffffffff
b[-8:] = struct.pack('<Q', h); open('maps/forged/map.plymap', 'wb').write(b)"
rmdir maps/dir && mkdir -p maps/dir/map.plymap
mkfifo maps/fifo/map.plymap
: >maps/empty/map.plymap
head -c 3000 /dev/urandom >maps/garbage/map.plymap
head -c 200 vocs/good.voc >vocs/truncated.voc
mkdir -p vocs/dir.voc
mkfifo vocs/fifo.voc

# ---- configs -------------------------------------------------------------------------------------

variant fx_tiny 's/^  fx: 517.3/  fx: 1e-300/'
variant fy_inf 's/^  fy: 516.5/  fy: .inf/'
variant fx_overflow 's/^  fx: 517.3/  fx: 1e400/'
variant distortion_nan 's/^  distortion: \[0.2624/  distortion: [.nan/'
variant readout_nan 's/^  rolling_shutter_readout: 0.02/  rolling_shutter_readout: .nan/'
variant alpha_nan 's/^    alpha: 2.5e-5/    alpha: .nan/'
variant fx_twice 's/^  fy: 516.5/  fy: 516.5\n  fx: 600/'
variant fx_alias_self 's/^  fx: 517.3/  fx: \&x [*x]/'
variant fx_string 's/^  fx: 517.3/  fx: abc/'
variant fx_list 's/^  fx: 517.3/  fx: [517.3, 1]/'
variant fx_map 's/^  fx: 517.3/  fx: {a: 1}/'
variant fx_null 's/^  fx: 517.3/  fx: ~/'
variant fx_negative 's/^  fx: 517.3/  fx: -517.3/'
variant fx_missing '/^  fx: 517.3/d'
variant width_zero 's/^  width: 640/  width: 0/'
variant width_huge 's/^  width: 640/  width: 1000000000/'
variant width_fraction 's/^  width: 640/  width: 640.5/'
variant width_hex 's/^  width: 640/  width: 0x280junk/'
variant depth_factor_zero 's/^  depth_factor: 5000.0/  depth_factor: 0/'
variant depth_range_inverted 's/^  max_depth: 6.0/  max_depth: 0.1/'
variant distortion_short 's/^  distortion: \[0.2624, -0.9531,/  distortion: [0.2624,/'
variant distortion_three 's/^  distortion: \[.*/  distortion: [0.26, -0.95, -0.005]/'
variant camera_unknown_key 's/^  fx: 517.3/  fx: 517.3\n  fxx: 1/'
variant orb_features_huge 's/^  num_features: 1000 /  num_features: 1000000000 /'
variant orb_levels_zero 's/^  num_levels: 8 /  num_levels: 0 /'
variant orb_scale_one 's/^  scale_factor: 1.2 /  scale_factor: 1.0 /'
variant orb_edge_huge 's/^  edge_threshold: 19 /  edge_threshold: 100000 /'
variant lines_enabled_int 's/^  enabled: false/  enabled: 2/'
variant dynamic_mode_bogus 's/^  mode: full/  mode: bogus/'
variant dense_stride_huge 's/^  stride: 2 /  stride: 1000000000 /'
variant octree_resolution_tiny 's/^  octree_resolution: 0.05 /  octree_resolution: 1e-300 /'
variant orb_vocabulary_truncated "s|^  orb_vocabulary: \"\"|  orb_vocabulary: $OUT/vocs/truncated.voc|"
variant orb_vocabulary_dir "s|^  orb_vocabulary: \"\"|  orb_vocabulary: $OUT/vocs/dir.voc|"
variant orb_vocabulary_fifo "s|^  orb_vocabulary: \"\"|  orb_vocabulary: $OUT/vocs/fifo.voc|"
variant orb_vocabulary_missing "s|^  orb_vocabulary: \"\"|  orb_vocabulary: $OUT/vocs/none.voc|"
variant model_missing 's|^  model: ""|  model: /nonexistent/yolo.onnx|'
variant fx_other_camera 's/^  fx: 517.3/  fx: 517.4/'
sed '/^camera:/,/^orb:/{/^orb:/!d}' "$CONFIG" >configs/camera_missing.yaml
appended unknown_section 'bogus_section:\n  a: 1\n'
appended camera_twice 'camera:\n  fx: 1\n'
appended section_alias 'extra: &e {fx: 1}\n'
appended section_merge 'tracking2: &t\n  a: 1\nlines2:\n  <<: *t\n'
appended map_key '? {a: b}\n: c\n'
appended second_document '---\ncamera: {fx: 1}\n'
appended nul_byte 'dense:\0 x\n'
{ cat "$CONFIG"; echo 'l0: &l0 [x, x, x, x, x, x, x, x, x, x]'
  for i in $(seq 1 9); do
    printf 'l%d: &l%d [' "$i" "$i"
    for _ in $(seq 1 9); do printf '*l%d, ' $((i - 1)); done
    printf '*l%d]\n' $((i - 1))
  done; } >configs/billion_laughs.yaml
printf 'a: &x [*x]\n' >configs/alias_self.yaml
{ printf 'deep: '; for _ in $(seq 1 200); do printf '['; done; for _ in $(seq 1 200); do printf ']'; done
  echo; } >configs/deep.yaml
{ cat "$CONFIG"; printf 'big: ['; seq -s, 1 200000 | tr -d '\n'; echo ']'; } >configs/many_nodes.yaml
{ cat "$CONFIG"; printf 'long: "'; head -c 20000000 /dev/zero | tr '\0' a; echo '"'; } >configs/huge_value.yaml
printf -- '- a\n- b\n' >configs/top_list.yaml
echo 'just a scalar' >configs/top_scalar.yaml
: >configs/empty.yaml
printf 'camera: [\n  fx: 1\n' >configs/unclosed.yaml
head -c 3000 "$(readlink -f "$SEQ/rgb/$(ls "$SEQ/rgb" | head -n 1)")" >configs/binary.yaml
mkfifo configs/fifo.yaml
ln -s loop.yaml configs/loop.yaml

config_case() {  # NAME EXPECT PATTERN WHAT: ply_slam_tum with configs/NAME.yaml
  case_ "config_$1" "$2" "$3" "$4" -- "$T" --sequence "$SEQ" --config "configs/$1.yaml" \
    --max-frames 8 --out "o/$1"
}
config_case fx_tiny 1 camera.fx '`camera.fx: 1e-300`'
config_case fy_inf 1 camera.fy '`camera.fy: .inf`'
config_case fx_overflow 1 camera.fx '`camera.fx: 1e400` (beyond a double)'
config_case distortion_nan 1 camera.distortion '`camera.distortion: [.nan, …]`'
config_case readout_nan 1 rolling_shutter_readout '`camera.rolling_shutter_readout: .nan`'
config_case alpha_nan 1 camera.depth_noise.alpha '`camera.depth_noise.alpha: .nan`'
config_case fx_twice 1 camera.fx '`fx` given twice in `camera`'
config_case camera_twice 1 camera '`camera:` given twice'
config_case alias_self 1 alias_self.yaml 'a YAML alias inside its own anchor, `a: &x [*x]`'
config_case fx_alias_self 1 fx_alias_self.yaml '`fx: &x [*x]` in the real config'
config_case billion_laughs 1 billion_laughs.yaml '"billion laughs": 10 levels of aliases of aliases (10^10 nodes)'
config_case deep 1 deep.yaml '200 nested lists'
config_case many_nodes 1 many_nodes.yaml 'the config plus a list of 200 000 numbers'
config_case huge_value 1 long 'the config plus a 20 MB string value'
config_case section_alias 1 extra 'an extra top-level key holding an anchor'
config_case section_merge 1 tracking2 'a YAML merge key (`<<: *t`) in an unknown section'
config_case map_key 1 map_key.yaml 'a map as a key (`? {a: b}`)'
config_case second_document 1 second_document.yaml 'a second YAML document (`---`) after the config'
config_case nul_byte 1 nul_byte.yaml 'a NUL byte inside the config'
config_case fx_string 1 camera.fx '`camera.fx: abc`'
config_case fx_list 1 camera.fx '`camera.fx: [517.3, 1]`'
config_case fx_map 1 camera.fx '`camera.fx: {a: 1}`'
config_case fx_null 1 camera.fx '`camera.fx: ~`'
config_case fx_negative 1 camera.fx '`camera.fx: -517.3`'
config_case fx_missing 1 camera.fx '`camera.fx` left out'
config_case camera_missing 1 camera 'the `camera:` section left out'
config_case width_zero 1 camera.width '`camera.width: 0`'
config_case width_huge 1 camera.width '`camera.width: 1000000000`'
config_case width_fraction 1 camera.width '`camera.width: 640.5`'
config_case width_hex 1 camera.width '`camera.width: 0x280junk`'
config_case depth_factor_zero 1 camera.depth_factor '`camera.depth_factor: 0`'
config_case depth_range_inverted 1 max_depth '`camera.max_depth: 0.1` (below min_depth 0.3)'
config_case distortion_short 1 camera.distortion '`camera.distortion` with fr1'"'"'s k2 left out (4 values: p2 = 1.16)'
config_case distortion_three 1 camera.distortion '`camera.distortion: [0.26, -0.95, -0.005]`'
config_case camera_unknown_key 1 camera.fxx 'an unknown key `camera.fxx`'
config_case unknown_section 1 bogus_section 'an unknown section `bogus_section:`'
config_case orb_features_huge 0 '' '`orb.num_features: 1000000000` (a target: as many as the image has, runs)'
config_case orb_levels_zero 1 orb.num_levels '`orb.num_levels: 0`'
config_case orb_scale_one 1 orb.scale_factor '`orb.scale_factor: 1.0`'
config_case orb_edge_huge 1 orb.edge_threshold '`orb.edge_threshold: 100000` (no pixel left)'
config_case lines_enabled_int 1 lines.enabled '`lines.enabled: 2`'
config_case dynamic_mode_bogus 1 dynamic.mode '`dynamic.mode: bogus`'
config_case dense_stride_huge 1 dense.stride '`dense.stride: 1000000000`'
config_case octree_resolution_tiny 1 dense.octree_resolution '`dense.octree_resolution: 1e-300`'
config_case top_list 1 top_list.yaml 'a YAML list, not a map'
config_case top_scalar 1 top_scalar.yaml 'a YAML scalar'
config_case empty 1 empty.yaml 'an empty file'
config_case unclosed 1 unclosed.yaml 'a `[` never closed'
config_case binary 1 binary.yaml 'the first 3 kB of a PNG as config'
config_case fifo 1 fifo.yaml 'a named pipe as config'
config_case loop 1 loop.yaml 'a symbolic link to itself as config'
case_ config_dir 1 configs 'a folder as `--config`' -- "$T" --sequence "$SEQ" --config configs \
  --max-frames 8 --out o/config_dir
case_ config_missing 1 none.yaml 'a config that does not exist' -- "$T" --sequence "$SEQ" \
  --config configs/none.yaml --max-frames 8 --out o/config_missing

# ---- sequences ---------------------------------------------------------------------------------

seq_case() {  # NAME EXPECT PATTERN WHAT DIR [more options]
  local name=$1 expect=$2 pattern=$3 what=$4 dir=$5
  shift 5
  case_ "seq_$name" "$expect" "$pattern" "$what" -- "$T" --sequence "$dir" "${BASE[@]}" \
    --out "o/seq_$name" "$@"
}
mkdir -p seq_empty
farm seq_no_rgb_txt && rm seq_no_rgb_txt/{rgb.txt,associations.txt}
farm seq_empty_lists && : >seq_empty_lists/rgb.txt && : >seq_empty_lists/associations.txt
farm seq_rgb_txt_dir && rm seq_rgb_txt_dir/{rgb.txt,associations.txt} && mkdir seq_rgb_txt_dir/rgb.txt
farm seq_rgb_txt_fifo && rm seq_rgb_txt_fifo/{rgb.txt,associations.txt} && mkfifo seq_rgb_txt_fifo/rgb.txt
farm seq_assoc_fifo && rm seq_assoc_fifo/associations.txt && mkfifo seq_assoc_fifo/associations.txt
farm seq_assoc_garbage && sed -i '5s/.*/1305031102.2 rgb.png garbage/' seq_assoc_garbage/associations.txt
farm seq_assoc_unknown_image && sed -i '5s| rgb/[^ ]*| rgb/none.png|' seq_assoc_unknown_image/associations.txt
farm seq_assoc_nan_stamp && sed -i '5s/^[0-9.]*/nan/' seq_assoc_nan_stamp/associations.txt
farm seq_assoc_binary && head -c 4000 /dev/urandom >seq_assoc_binary/associations.txt
farm seq_assoc_backwards && { grep '^#' "$SEQ/associations.txt"; grep -v '^#' "$SEQ/associations.txt" |
  tac; } >seq_assoc_backwards/associations.txt
for how in missing dir fifo empty truncated garbage loop small gray; do broken_image "rgb_$how" rgb "$how"; done
for how in missing fifo truncated small colour float; do broken_image "depth_$how" depth "$how"; done
farm seq_gt_empty && : >seq_gt_empty/groundtruth.txt
farm seq_gt_dir && rm seq_gt_dir/groundtruth.txt && mkdir seq_gt_dir/groundtruth.txt
farm seq_gt_fifo && rm seq_gt_fifo/groundtruth.txt && mkfifo seq_gt_fifo/groundtruth.txt
farm seq_gt_nan && sed -i '10s/^\([0-9.]*\) [^ ]*/\1 nan/' seq_gt_nan/groundtruth.txt
farm seq_gt_late && awk '/^#/ {next} {printf "%.4f", $1 + 1000; for (i = 2; i <= NF; i++)
  printf " %s", $i; print ""}' "$SEQ/groundtruth.txt" >seq_gt_late/groundtruth.txt
: >file.txt

seq_case missing 1 none 'a `--sequence` that does not exist' none
seq_case is_file 1 file.txt 'a file as `--sequence`' file.txt
seq_case empty_dir 1 seq_empty 'an empty folder' seq_empty
seq_case no_rgb_txt 1 rgb.txt 'no rgb.txt nor associations.txt' seq_no_rgb_txt
seq_case empty_lists 1 seq_empty_lists 'empty rgb.txt and associations.txt' seq_empty_lists
seq_case rgb_txt_dir 1 rgb.txt 'a folder as rgb.txt' seq_rgb_txt_dir
seq_case rgb_txt_fifo 1 rgb.txt 'a named pipe as rgb.txt' seq_rgb_txt_fifo
seq_case assoc_fifo 1 associations.txt 'a named pipe as associations.txt' seq_assoc_fifo
seq_case assoc_garbage 1 associations.txt 'associations.txt line 5: 3 fields, one not a stamp' seq_assoc_garbage
seq_case assoc_unknown_image 1 none.png 'associations.txt naming an rgb image that is not there' seq_assoc_unknown_image
seq_case assoc_nan_stamp 1 associations.txt 'associations.txt line 5 stamped `nan`' seq_assoc_nan_stamp
seq_case assoc_binary 1 associations.txt '4 kB of random bytes as associations.txt' seq_assoc_binary
seq_case assoc_backwards 0 '' 'associations.txt in reverse order (sorted by stamp: runs)' seq_assoc_backwards
for how in missing dir fifo empty truncated garbage loop small; do
  seq_case "rgb_$how" 1 "$(nth "seq_rgb_$how" rgb 3)" "the 3rd rgb image: $how" "seq_rgb_$how"
done
seq_case rgb_gray 1 "$(nth seq_rgb_gray rgb 3)" 'the 3rd rgb image: 8-bit grey' seq_rgb_gray
for how in missing fifo truncated small colour float; do
  seq_case "depth_$how" 1 "$(nth "seq_depth_$how" depth 3)" "the 3rd depth image: $how" "seq_depth_$how"
done
seq_case gt_empty 3 groundtruth.txt 'an empty groundtruth.txt (evaluation_error, exit 3)' seq_gt_empty
seq_case gt_dir 3 groundtruth.txt 'a folder as groundtruth.txt' seq_gt_dir
seq_case gt_fifo 3 groundtruth.txt 'a named pipe as groundtruth.txt' seq_gt_fifo
seq_case gt_nan 1 'groundtruth.txt'"'"' line 10' 'groundtruth.txt line 10 with x `nan` (refused before the run)' seq_gt_nan
seq_case gt_late 3 groundtruth.txt 'groundtruth.txt 1000 s after the run' seq_gt_late
case_ seq_twice 2 --sequence '`--sequence` given twice' -- "$T" --sequence seq_empty --sequence "$SEQ" \
  "${BASE[@]}" --out o/seq_twice

# ---- options -----------------------------------------------------------------------------------

case_ tum_no_line 2 --no-line '`--no-line` (for `--no-lines`)' -- "$T" --no-line --sequence "$SEQ" \
  "${BASE[@]}" --out o/no_line
case_ tum_max_frames_zero 2 --max-frames '`--max-frames 0`' -- "$T" --sequence "$SEQ" \
  --config "$CONFIG" --max-frames 0 --out o/max0
case_ tum_max_frames_text 2 --max-frames '`--max-frames ten`' -- "$T" --sequence "$SEQ" \
  --config "$CONFIG" --max-frames ten --out o/max_text
case_ tum_max_frames_huge 2 --max-frames '`--max-frames 99999999999999999999`' -- "$T" \
  --sequence "$SEQ" --config "$CONFIG" --max-frames 99999999999999999999 --out o/max_huge
case_ tum_segmenter_bogus 2 --segmenter '`--segmenter bogus`' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out o/seg_bogus --segmenter bogus
case_ tum_dynamic_bogus 2 --dynamic '`--dynamic bogus`' -- "$T" --sequence "$SEQ" "${BASE[@]}" \
  --out o/dyn_bogus --dynamic bogus
case_ tum_value_missing 2 --out '`--out` as the last word, without its value' -- "$T" \
  --sequence "$SEQ" "${BASE[@]}" --out
case_ tum_model_no_yolo 2 --segmenter '`--model` without `--segmenter yolo`' -- "$T" \
  --sequence "$SEQ" "${BASE[@]}" --out o/model_no_yolo --model "$SHARED/models/yolov8n-seg-320x320.onnx"
case_ tum_model_missing 1 yolo.onnx 'the config'"'"'s YOLO model not there (`--segmenter yolo`)' -- \
  "$T" --sequence "$SEQ" --config configs/model_missing.yaml --max-frames 8 --out o/model_missing \
  --segmenter yolo
case_ tum_model_text 1 coco.names 'a text file as `--model`' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out o/model_text --segmenter yolo --model "$SHARED/models/coco.names" --input 320x320
case_ tum_input_swapped 1 640x480 '`--input 480x640` with the 640-wide export' -- "$T" \
  --sequence "$SEQ" "${BASE[@]}" --out o/input_swapped --segmenter yolo \
  --model "$SHARED/models/yolov8n-seg-480x640.onnx" --input 480x640
case_ tum_input_text 2 --input '`--input big`' -- "$T" --sequence "$SEQ" "${BASE[@]}" \
  --out o/input_text --segmenter yolo --model "$SHARED/models/yolov8n-seg-320x320.onnx" --input big
case_ tum_two_frames 3 '' '2 frames (1 keyframe: no dense cloud, nothing to evaluate)' -- "$T" \
  --sequence "$SEQ" --config "$CONFIG" --max-frames 2 --out o/two_frames

# ---- maps --------------------------------------------------------------------------------------

CHECK="finite_poses o/map_forged"
case_ map_forged any '' '`map.plymap`: 8 bytes in the middle made a NaN, checksum made to fit (refused, or a run with finite poses)' -- \
  "$T" --sequence "$SEQ" "${BASE[@]}" --out o/map_forged --map maps/forged
for how in truncated checksum dir fifo empty garbage; do
  case_ "map_$how" 1 map.plymap "\`map.plymap\`: $how" -- "$T" --sequence "$SEQ" "${BASE[@]}" \
    --out "o/map_$how" --map "maps/$how"
done
case_ map_missing 1 maps/none '`--map` a folder that does not exist' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out o/map_missing --map maps/none
case_ map_other_camera 1 517.4 'a map loaded with `camera.fx` 517.4 (saved with 517.3)' -- "$T" \
  --sequence "$SEQ" --config configs/fx_other_camera.yaml --max-frames 8 --out o/map_other --map maps/good
case_ map_localisation_bogus 2 --localisation-only '`--localisation-only maybe`' -- "$T" \
  --sequence "$SEQ" "${BASE[@]}" --out o/map_loc --map maps/good --localisation-only maybe

# ---- outputs -----------------------------------------------------------------------------------

mkdir -p o/summary_dir/summary.json o/devfull o/fifo
ln -sf /dev/full o/devfull/timing.csv
ln -sf /dev/full o/devfull/dense_map.ply
mkfifo o/fifo/timing.csv
case_ out_summary_dir 1 summary.json '`summary.json` is a folder' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out o/summary_dir
case_ out_devfull 1 dense_map.ply '`timing.csv`, `dense_map.ply` linked to /dev/full' -- "$T" \
  --sequence "$SEQ" "${BASE[@]}" --out o/devfull
case_ out_fifo 1 timing.csv 'a named pipe as `timing.csv`' -- "$T" --sequence "$SEQ" "${BASE[@]}" \
  --out o/fifo
case_ out_is_file 1 file.txt 'a file as `--out`' -- "$T" --sequence "$SEQ" "${BASE[@]}" --out file.txt
case_ out_under_file 1 file.txt '`--out file.txt/sub`' -- "$T" --sequence "$SEQ" "${BASE[@]}" \
  --out file.txt/sub
case_ out_proc 1 /proc '`--out /proc/ply_slam` (cannot be made)' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out /proc/ply_slam
case_ save_map_under_file 1 file.txt '`--save-map file.txt/m`' -- "$T" --sequence "$SEQ" \
  "${BASE[@]}" --out o/save_map_file --save-map file.txt/m

# A 200 kB tmpfs: fills part-way through the outputs. Each file is whole or absent, and every
# absent one is named.
full_disk_check() {
  local dir=$FULL/run said_missing missing="" f
  said_missing="$(grep 'output(s) not written' logs/out_full_tmpfs.err)"
  for f in CameraTrajectory.txt KeyFrameTrajectory.txt timing.csv summary.json trajectory.png \
    dense_map.pcd dense_map.ply semantic_octree.ot octree.bt map_legend.txt map_top.png map.pgm \
    map.yaml grid.png map/map.plymap; do
    [ -s "$dir/$f" ] || grep -qF "$(basename "$f")" <<<"$said_missing" || missing+="$f "
  done
  [ -z "$missing" ] || echo "absent but not named: $missing"
  no_partial "$dir"
  local ply="$dir/dense_map.ply"
  if [ -f "$ply" ]; then  # whole: as many vertices as the header announces
    local n
    n="$(grep -a -m1 '^element vertex' "$ply" | awk '{print $3}')"
    [ "$(stat -c %s "$ply")" -gt $((n * 12)) ] || echo "dense_map.ply shorter than its $n points"
  fi
}
mkdir -p full
if mount -t tmpfs -o size=200k tmpfs full 2>/dev/null; then
  FULL="$OUT/full"
  CHECK=full_disk_check
  case_ out_full_tmpfs 1 'not written' '`--out` and `--save-map` on a 200 kB tmpfs, 20 frames' -- \
    "$T" --sequence "$SEQ" --config "$CONFIG" --max-frames 20 --out "$FULL/run" --save-map "$FULL/run/map"
  rm -rf "${FULL:?}"/*
  CHECK="no_partial $FULL"
  case_ synth_full_tmpfs 1 "$FULL" '`ply_slam_synth --out` on a 200 kB tmpfs' -- \
    "$BIN/ply_slam_synth" --out "$FULL/synth" --frames 5
  rm -rf "${FULL:?}"/*
  cp vocs/good.voc "$FULL/good.voc"
  head -c 300000 /dev/zero >"$FULL/filler" 2>/dev/null  # fills the rest
  CHECK="unchanged $FULL/good.voc vocs/good.voc"
  case_ voc_full_tmpfs 1 good.voc 'a vocabulary over a good one on a full tmpfs' -- \
    "$BIN/ply_slam_vocabulary" --images "$SEQ/rgb" --kind orb --k 4 --levels 2 --out "$FULL/good.voc"
  umount "$FULL" && FULL=""
else
  for c in out_full_tmpfs synth_full_tmpfs voc_full_tmpfs; do
    ROWS=$((ROWS + 1))
    printf '| %d | %s | (needs root to mount a tmpfs) | - | - | skipped |\n' "$ROWS" "$c"
  done
fi

# ---- vocabularies ------------------------------------------------------------------------------

echo nonexistent.png >lists/missing.txt
mkdir -p junk && for i in 1 2 3; do head -c 500 /dev/urandom >"junk/$i.png"; done
mkfifo lists/fifo.txt
voc() {  # NAME EXPECT PATTERN WHAT [options]: over a copy of the good vocabulary
  local name=$1 expect=$2 pattern=$3 what=$4 option
  shift 4
  local args=("$@")
  for option in "--kind orb" "--k 4" "--levels 2"; do  # the defaults the case does not set
    [[ " $* " == *" ${option% *} "* ]] || args+=($option)
  done
  cp vocs/good.voc "vocs/$name.voc"
  CHECK="unchanged vocs/$name.voc vocs/good.voc"
  case_ "voc_$name" "$expect" "$pattern" "$what" -- "$BIN/ply_slam_vocabulary" \
    --out "vocs/$name.voc" "${args[@]}"
}
voc missing_images 1 nonexistent.png 'a list of one image that is not there' --images lists/missing.txt
voc junk_png 1 junk 'a folder of 3 random-byte .png' --images junk
voc images_none 1 none '`--images` that does not exist' --images none
voc images_fifo 1 fifo.txt 'a named pipe as `--images`' --images lists/fifo.txt
voc kind_bogus 2 --kind '`--kind sift`' --images "$SEQ/rgb" --kind sift
voc k_one 2 --k '`--k 1`' --images "$SEQ/rgb" --k 1
voc levels_huge 2 --levels '`--levels 100`' --images "$SEQ/rgb" --levels 100
voc config_cycle 1 alias_self.yaml '`--config` with an alias cycle' --images "$SEQ/rgb" \
  --config configs/alias_self.yaml
case_ voc_out_dir 1 vocs/dir.voc 'a folder as `--out`' -- "$BIN/ply_slam_vocabulary" \
  --images "$SEQ/rgb" --kind orb --k 4 --levels 2 --out vocs/dir.voc
case_ voc_out_devfull 1 /dev/full '`--out /dev/full`' -- "$BIN/ply_slam_vocabulary" \
  --images "$SEQ/rgb" --kind orb --k 4 --levels 2 --out /dev/full
case_ voc_out_fifo 1 fifo.voc 'a named pipe as `--out`' -- "$BIN/ply_slam_vocabulary" \
  --images "$SEQ/rgb" --kind orb --k 4 --levels 2 --out vocs/fifo.voc
case_ voc_benchmark_truncated 1 truncated.voc '`--benchmark` with a truncated vocabulary' -- \
  "$BIN/ply_slam_vocabulary" --benchmark --orb-vocabulary vocs/truncated.voc \
  --lbd-vocabulary vocs/good.voc --images "$SEQ/rgb"
for v in truncated dir fifo; do
  config_case "orb_vocabulary_$v" 1 "$v.voc" "\`loop.orb_vocabulary\`: $v"
done
config_case orb_vocabulary_missing 1 none.voc '`loop.orb_vocabulary`: a file that is not there'

# ---- the other tools ---------------------------------------------------------------------------

printf '1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.20 2 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n' >gt.txt
printf '1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.10 1.5 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n' >est_dup.txt
printf '1.00 1e308 0 0 0 0 0 1\n1.10 -1e308 0 0 0 0 0 1\n1.20 1e308 0 0 0 0 0 1\n1.30 -1e308 0 0 0 0 0 1\n' \
  >est_huge.txt
printf '1.00 0 0 0 0 0 0 1\n1.10 nan 0 0 0 0 0 1\n1.20 2 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n' >est_nan.txt
printf '1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n' >est_two.txt
printf '1.00 0 0 0\n' >est_short.txt
: >est_empty.txt
mkfifo est_fifo.txt
E="$BIN/ply_slam_eval"
case_ eval_dup 1 est_dup.txt 'an estimate stamp given twice' -- "$E" ate gt.txt est_dup.txt --json
case_ eval_huge 1 est_huge.txt 'coordinates of 1e308' -- "$E" ate gt.txt est_huge.txt --json
case_ eval_nan 1 est_nan.txt 'a `nan` coordinate' -- "$E" ate gt.txt est_nan.txt --json
case_ eval_two 1 '' '2 poses (ATE needs 3 pairs)' -- "$E" ate gt.txt est_two.txt
case_ eval_short 1 est_short.txt 'a line of 4 fields' -- "$E" ate gt.txt est_short.txt
case_ eval_empty 1 est_empty.txt 'an empty estimate' -- "$E" ate gt.txt est_empty.txt
case_ eval_fifo 1 est_fifo.txt 'a named pipe as the estimate' -- "$E" ate gt.txt est_fifo.txt
case_ eval_dir 1 configs 'a folder as ground truth' -- "$E" rpe configs gt.txt
case_ eval_missing 1 none.txt 'a ground truth that is not there' -- "$E" ate none.txt gt.txt
case_ eval_plot_devfull 1 /dev/full '`--plot /dev/full`' -- "$E" ate gt.txt gt.txt --plot /dev/full
case_ eval_delta_zero 2 --delta '`rpe --delta 0`' -- "$E" rpe gt.txt gt.txt --delta 0
case_ eval_max_dt_nan 2 --max-dt '`--max-dt nan`' -- "$E" ate gt.txt gt.txt --max-dt nan
case_ eval_no_command 2 '' 'no subcommand' -- "$E"
case_ eval_bogus_command 2 bogus '`ply_slam_eval bogus a b`' -- "$E" bogus gt.txt gt.txt

L="$BIN/ply_slam_lines"
case_ lines_alias_self 1 alias_self.yaml 'ply_slam_lines, config `a: &x [*x]`' -- "$L" --sequence "$SEQ" \
  --config configs/alias_self.yaml --max-frames 4
case_ lines_laughs 1 billion_laughs.yaml 'ply_slam_lines, billion laughs' -- "$L" --sequence "$SEQ" \
  --config configs/billion_laughs.yaml --max-frames 4
case_ lines_rgb_truncated 1 "$(nth seq_rgb_truncated rgb 3)" 'ply_slam_lines, a truncated rgb image' \
  -- "$L" --sequence seq_rgb_truncated --config "$CONFIG" --max-frames 4
case_ lines_offset_text 2 --offset 'ply_slam_lines `--offset x`' -- "$L" --sequence "$SEQ" \
  --config "$CONFIG" --offset x

P="$BIN/ply_slam_loops"
case_ loops_alias_self 1 alias_self.yaml 'ply_slam_loops, config `a: &x [*x]`' -- "$P" --sequence "$SEQ" \
  --config configs/alias_self.yaml --out o/loops_alias --max-frames 4
case_ loops_vocabulary_dir 1 dir.voc 'ply_slam_loops, a folder as `loop.orb_vocabulary`' -- "$P" \
  --sequence "$SEQ" --config configs/orb_vocabulary_dir.yaml --out o/loops_voc --max-frames 4
case_ loops_out_file 1 file.txt 'ply_slam_loops `--out file.txt`' -- "$P" --sequence "$SEQ" \
  --config "$CONFIG" --out file.txt --max-frames 4
case_ loops_min_gap_nan 2 --min-gap-s 'ply_slam_loops `--min-gap-s nan`' -- "$P" --sequence "$SEQ" \
  --config "$CONFIG" --out o/loops_gap --min-gap-s nan

R="$BIN/ply_slam_rgbd_odometry"
case_ odometry_alias_self 1 alias_self.yaml 'ply_slam_rgbd_odometry, config `a: &x [*x]`' -- "$R" \
  --sequence "$SEQ" --config configs/alias_self.yaml --out o/odo.txt
case_ odometry_devfull 1 /dev/full 'ply_slam_rgbd_odometry `--out /dev/full`' -- "$R" \
  --sequence "$SEQ" --config "$CONFIG" --out /dev/full
case_ odometry_depth_colour 1 "$(nth seq_depth_colour depth 3)" \
  'ply_slam_rgbd_odometry, an rgb image as depth' -- "$R" --sequence seq_depth_colour \
  --config "$CONFIG" --out o/odo_colour.txt
case_ odometry_fifo_config 1 fifo.yaml 'ply_slam_rgbd_odometry, a named pipe as config' -- "$R" \
  --sequence "$SEQ" --config configs/fifo.yaml --out o/odo_fifo.txt

G="$BIN/ply_slam_segment"
case_ segment_model_missing 1 none.onnx 'ply_slam_segment, a model that is not there' -- "$G" \
  --sequence "$SEQ" --model none.onnx --input 320x320
case_ segment_model_dir 1 configs 'ply_slam_segment, a folder as model' -- "$G" --sequence "$SEQ" \
  --model configs --input 320x320
case_ segment_input_text 2 --input 'ply_slam_segment `--input 0x0`' -- "$G" --sequence "$SEQ" \
  --model "$SHARED/models/yolov8n-seg-320x320.onnx" --input 0x0
case_ segment_every_zero 2 --every 'ply_slam_segment `--every 0`' -- "$G" --sequence "$SEQ" \
  --model "$SHARED/models/yolov8n-seg-320x320.onnx" --input 320x320 --every 0
case_ segment_classes_fifo 1 fifo.txt 'ply_slam_segment, a named pipe as `--classes`' -- "$G" \
  --sequence "$SEQ" --model "$SHARED/models/yolov8n-seg-320x320.onnx" --input 320x320 \
  --classes lists/fifo.txt

S="$BIN/ply_slam_synth"
case_ synth_out_file 1 file.txt 'ply_slam_synth `--out file.txt`' -- "$S" --out file.txt --frames 2
case_ synth_frames_zero 2 --frames 'ply_slam_synth `--frames 0`' -- "$S" --out o/synth0 --frames 0
case_ synth_frames_huge 2 --frames 'ply_slam_synth `--frames 10000000000`' -- "$S" --out o/synth1 \
  --frames 10000000000
case_ synth_walkers_huge 2 --walkers 'ply_slam_synth `--walkers 1000000`' -- "$S" --out o/synth2 \
  --walkers 1000000 --frames 2
case_ synth_scene_bogus 2 --scene 'ply_slam_synth `--scene moon`' -- "$S" --out o/synth3 --scene moon
case_ synth_textures_missing 1 none 'ply_slam_synth `--textures none`' -- "$S" --out o/synth4 \
  --textures none --frames 2

M="$BIN/ply_slam_map_compare"
printf '1305031102.2 0 0 0 0 0 0 1\n' >kf_one.txt
case_ compare_keyframes_missing 1 none.txt 'ply_slam_map_compare, keyframes not there' -- "$M" \
  --sequence "$SEQ" --config "$CONFIG" --keyframes none.txt
case_ compare_keyframes_binary 1 associations.txt 'ply_slam_map_compare, random bytes as keyframes' \
  -- "$M" --sequence "$SEQ" --config "$CONFIG" --keyframes seq_assoc_binary/associations.txt
case_ compare_keyframes_one 1 kf_one.txt 'ply_slam_map_compare, one keyframe' -- "$M" \
  --sequence "$SEQ" --config "$CONFIG" --keyframes kf_one.txt
case_ compare_offset_nan 2 --clock-offset 'ply_slam_map_compare `--clock-offset nan`' -- "$M" \
  --sequence "$SEQ" --config "$CONFIG" --keyframes kf_one.txt --clock-offset nan
case_ compare_laughs 1 billion_laughs.yaml 'ply_slam_map_compare, billion laughs' -- "$M" \
  --sequence "$SEQ" --config configs/billion_laughs.yaml --keyframes kf_one.txt

for tool in ply_slam_eval ply_slam_lines ply_slam_loops ply_slam_map_compare \
  ply_slam_rgbd_odometry ply_slam_segment ply_slam_synth ply_slam_tum ply_slam_vocabulary; do
  case_ "${tool#ply_slam_}_help" 0 '' "\`$tool --help\`" -- "$BIN/$tool" --help
  case_ "${tool#ply_slam_}_bogus" 2 'unknown option --bogus' "\`$tool --bogus\`" -- "$BIN/$tool" --bogus
done

echo "[bad_input] ${ROWS} cases, ${WRONG} not as they should be" >&2
exit "$WRONG"

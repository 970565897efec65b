#!/usr/bin/env bash
# Shared set-up, sourced by demo.sh, test.sh and benchmark.sh: installs the Debian
# packages that are missing (silent when all are there), then creates or refreshes the
# catkin workspace build/ws with this repository as its package and builds it (Release, -j2).
set -euo pipefail

PLY_SLAM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PLY_SLAM_WS="${PLY_SLAM_ROOT}/build/ws"
PLY_SLAM_BIN="${PLY_SLAM_BIN:-${PLY_SLAM_WS}/devel/lib/ply_slam}"  # preset: use other binaries

PLY_SLAM_PACKAGES=(
  build-essential cmake catkin python3-catkin-pkg
  libopencv-dev libopencv-contrib-dev libceres-dev libeigen3-dev libyaml-cpp-dev
  libgtest-dev googletest opencv-doc
  # ROS 1 layer (nodes, messages, rostest) and scripts/tum_to_bag.py, rviz
  ros-base-dev libroscpp-dev librosbag-dev python3-rosbag rosbash topic-tools ros-message-generation
  ros-message-runtime librostest-dev python3-rostest ros-std-msgs ros-std-srvs ros-sensor-msgs
  ros-geometry-msgs ros-nav-msgs ros-visualization-msgs libstd-msgs-dev libstd-srvs-dev
  libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libvisualization-msgs-dev
  libcv-bridge-dev libmessage-filters-dev libtf2-dev libtf2-ros-dev tf2-tools python3-sensor-msgs
  python3-geometry-msgs python3-tf2-ros python3-std-msgs python3-std-srvs python3-nav-msgs
  python3-opencv python3-numpy python3-yaml rviz
  libpcl-dev liboctomap-dev nlohmann-json3-dev
  # scripts/yolo_onnx_for_opencv46.py and its test (test/python)
  python3-onnx
)

ply_slam_install_packages() {
  local missing=()
  for p in "${PLY_SLAM_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "[setup] installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

ply_slam_build() {
  # The source space is the hidden folder .src: roslaunch, rosrun and rostest search a
  # package's whole tree (following links, skipping dot-folders) and would otherwise follow
  # build/ws/src/ply_slam back into this repository for ever.
  if [ -L "${PLY_SLAM_WS}/src/ply_slam" ]; then  # a workspace made before: move it over
    rm -f "${PLY_SLAM_WS}/src/ply_slam" "${PLY_SLAM_WS}/src/CMakeLists.txt"
    rmdir "${PLY_SLAM_WS}/src" 2>/dev/null || true
    rm -rf "${PLY_SLAM_WS}/build"
  fi
  mkdir -p "${PLY_SLAM_WS}/.src"
  ln -sfn "${PLY_SLAM_ROOT}" "${PLY_SLAM_WS}/.src/ply_slam"
  (cd "${PLY_SLAM_WS}" &&
     catkin_make --source .src -j2 -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 "$@" \
       >"${PLY_SLAM_WS}/build.log" 2>&1) || {
    tail -n 60 "${PLY_SLAM_WS}/build.log"
    echo "[setup] build failed; full log: ${PLY_SLAM_WS}/build.log" >&2
    return 1
  }
}

# The default place-recognition vocabularies (loop.orb_vocabulary / loop.lbd_vocabulary ""):
# build/vocabulary/{orb,lbd}_k10_l5.voc, trained by ply_slam_vocabulary from the opencv-doc
# example images, which are in no evaluation sequence (k 10, 5 levels, seed 1; ~18 s on two
# cores). Retrained when missing or older than the tool, so a changed extractor or trainer
# never leaves a stale vocabulary behind.
PLY_SLAM_VOCABULARY_IMAGES="${PLY_SLAM_VOCABULARY_IMAGES:-/usr/share/doc/opencv-doc/examples/data}"

ply_slam_vocabularies() {
  local tool="${PLY_SLAM_BIN}/ply_slam_vocabulary" dir="${PLY_SLAM_ROOT}/build/vocabulary"
  mkdir -p "$dir"
  local kind out
  for kind in orb lbd; do
    out="${dir}/${kind}_k10_l5.voc"
    [ -f "$out" ] && [ "$out" -nt "$tool" ] && continue
    echo "[setup] training the ${kind} vocabulary (log: ${dir}/${kind}_k10_l5.log)"
    # Written beside and moved into place: an interrupted run leaves no truncated file.
    "$tool" --images "$PLY_SLAM_VOCABULARY_IMAGES" --kind "$kind" --k 10 --levels 5 --seed 1 \
      --out "${out}.part" >"${dir}/${kind}_k10_l5.log" 2>&1 || {
      tail -n 20 "${dir}/${kind}_k10_l5.log"
      echo "[setup] training the ${kind} vocabulary failed" >&2
      return 1
    }
    mv -f "${out}.part" "$out"
  done
}

# The shared data and models live beside the repository (never inside it).
PLY_SLAM_SHARED="${PLY_SLAM_SHARED:-$(cd "${PLY_SLAM_ROOT}/.." && pwd)/shared}"
export PLY_SLAM_SHARED

# The config for a TUM folder, from "freiburgN" or "frN" in its name.
ply_slam_config_for() {
  local name
  name="$(basename "$1")"
  if [[ "$name" =~ (freiburg|fr)([123]) ]]; then
    echo "${PLY_SLAM_ROOT}/config/tum_fr${BASH_REMATCH[2]}.yaml"
  elif [[ "$name" =~ bonn ]]; then
    echo "${PLY_SLAM_ROOT}/config/bonn.yaml"
  else
    echo "cannot choose a config for '$name' (expected freiburg1/2/3 or bonn in the folder name;" \
      "set PLY_SLAM_CONFIG to a config file)" >&2
    return 1
  fi
}

# A synthetic sequence rendered once and kept: DIR SCENE FRAMES LOG [more ply_slam_synth
# options]. A finished rendering lists all its frames; anything else is rendered again.
ply_slam_render_once() {
  local dir=$1 scene=$2 frames=$3 log=$4
  shift 4
  [ -f "${dir}/rgb.txt" ] && [ "$(grep -vc '^#' "${dir}/rgb.txt")" -eq "$frames" ] && return 0
  echo "[setup] rendering ${scene}, ${frames} frames $* (log: ${log})"
  mkdir -p "$(dirname "$log")"
  rm -rf "$dir"
  "${PLY_SLAM_BIN}/ply_slam_synth" --out "$dir" --scene "$scene" --frames "$frames" "$@" \
    >"$log" 2>&1 || { tail -n 20 "$log"; return 1; }
}

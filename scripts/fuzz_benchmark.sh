#!/usr/bin/env bash
# Fuzzes the input parsers and decoders with libFuzzer (clang, ASan + UBSan) for a fixed time
# each and writes a table into docs/RESULTS.md between <!-- fuzz:begin --> and <!-- fuzz:end -->.
#
#   scripts/fuzz_benchmark.sh [--seconds N] [--no-build] [TARGET...]
#
# Targets: the fuzz/fuzz_*.cpp harnesses (default: all), built into build/fuzz with clang.
# Seeds: the repo's configs and, from $PLY_SLAM_SHARED/data, list heads and thumbnails made into
# ROS messages (build/fuzz/seeds, never committed), plus test/fuzz_regressions/<target> and the
# committed corpus fuzz/corpus/<target> (fuzz_config's: our own inputs only, minimised with
# -merge=1). The corpus grows across runs in build/fuzz/corpus/<target>. A finding (crash, UB,
# leak, timeout, out-of-memory) is written to build/fuzz/findings/<target>/ and the target
# restarted until its time is up. Exit code 1 when anything was found.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

COMMAND="scripts/fuzz_benchmark.sh"
for arg in "$@"; do COMMAND+=" $(printf '%q' "$arg")"; done
SECONDS_PER_TARGET=120 BUILD=1 TARGETS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) SECONDS_PER_TARGET="${2:?--seconds needs a value}"; shift ;;
    --no-build) BUILD=0 ;;
    -h | --help) sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz_benchmark: unknown option $1" >&2; exit 2 ;;
    *) TARGETS+=("$1") ;;
  esac
  shift
done

FUZZ="${PLY_SLAM_ROOT}/build/fuzz"
RESULTS="${PLY_SLAM_ROOT}/docs/RESULTS.md"
CXX_FUZZ="$(command -v clang++-14 || command -v clang++)" || {
  echo "fuzz_benchmark: clang++ (with libFuzzer) is needed" >&2
  exit 1
}

# The harnesses need the generated message headers (C++) and the seeds their Python classes:
# from a workspace that has them, else generated in build/ws (messages only, ~1 min).
msg_ws=""
for ws in "${PLY_SLAM_ROOT}/build/ws" "${PLY_SLAM_ROOT}/build/ws_sanitize"; do
  if [ -f "${ws}/devel/include/ply_slam/KeyFrameMsg.h" ] &&
     [ -d "${ws}/devel/lib/python3/dist-packages/ply_slam/msg" ]; then msg_ws="$ws"; break; fi
done
if [ -z "$msg_ws" ]; then
  echo "[fuzz] generating the message headers in ${PLY_SLAM_WS}"
  ply_slam_build ply_slam_generate_messages_cpp ply_slam_generate_messages_py
  msg_ws="$PLY_SLAM_WS"
fi

if [ "$BUILD" = 1 ]; then
  echo "[fuzz] building the harnesses with $(basename "$CXX_FUZZ") (log: ${FUZZ}/build.log)"
  mkdir -p "$FUZZ"
  (cd "$FUZZ" && CXX="$CXX_FUZZ" cmake "${PLY_SLAM_ROOT}/fuzz" -DCMAKE_BUILD_TYPE=None \
     -DPLY_SLAM_MSG_INCLUDE="${msg_ws}/devel/include" && make -j2) >"${FUZZ}/build.log" 2>&1 || {
    tail -n 40 "${FUZZ}/build.log"
    echo "[fuzz] build failed" >&2
    exit 1
  }
fi
[ ${#TARGETS[@]} -gt 0 ] || for src in "${PLY_SLAM_ROOT}"/fuzz/fuzz_*.cpp; do
  TARGETS+=("$(basename "$src" .cpp)")
done

rm -rf "${FUZZ}/seeds"
PYTHONPATH="${msg_ws}/devel/lib/python3/dist-packages:${PYTHONPATH:-}" \
  /usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/fuzz_seeds.py" "${PLY_SLAM_SHARED}/data" \
  "$PLY_SLAM_ROOT" "${FUZZ}/seeds"

ROWS="$(mktemp)" SECTION="$(mktemp)"
trap 'rm -f "$ROWS" "$SECTION"' EXIT
STATUS=0
for target in "${TARGETS[@]}"; do
  corpus="${FUZZ}/corpus/${target}" findings="${FUZZ}/findings/${target}"
  regressions="${PLY_SLAM_ROOT}/test/fuzz_regressions/${target}"
  mkdir -p "$corpus" "$findings" "${FUZZ}/seeds/${target}"
  inputs=("$corpus" "${FUZZ}/seeds/${target}")
  [ -d "$regressions" ] && inputs+=("$regressions")
  [ -d "${PLY_SLAM_ROOT}/fuzz/corpus/${target}" ] && inputs+=("${PLY_SLAM_ROOT}/fuzz/corpus/${target}")
  before=$(ls "$findings" | wc -l)
  executions=0 cov=0 left=$SECONDS_PER_TARGET restarts=0
  echo "[fuzz] ${target}: ${SECONDS_PER_TARGET} s"
  # libFuzzer stops at a finding: restarted on the grown corpus until the time is used (at
  # most 5 findings per target: more are usually the same bug again).
  while [ "$left" -gt 0 ] && [ $(( $(ls "$findings" | wc -l) - before )) -lt 5 ]; do
    start=$(date +%s)
    log="${FUZZ}/${target}.log"
    "${FUZZ}/${target}" -max_total_time="$left" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="${findings}/" "${inputs[@]}" >"$log" 2>&1 || true
    n=$(grep -oP 'stat::number_of_executed_units:\s*\K[0-9]+' "$log" | tail -1 || true)
    [ -n "$n" ] || n=$(grep -oP '^#\K[0-9]+' "$log" | tail -1 || echo 0)
    executions=$((executions + n))
    c=$(grep -oP 'cov: \K[0-9]+' "$log" | tail -1 || true)
    [ -n "$c" ] && [ "$c" -gt "$cov" ] && cov=$c
    left=$((left - ($(date +%s) - start) ))
    restarts=$((restarts + 1))
  done
  found=$(( $(ls "$findings" | wc -l) - before ))
  [ "$found" -gt 0 ] && STATUS=1
  # (head -n 0 would close the pipe on ls: with pipefail a target without new findings but with
  # old ones stopped the script)
  names=""
  [ "$found" -gt 0 ] && names=$(ls -t "$findings" | head -n "$found" | tr '\n' ' ')
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$target" "$SECONDS_PER_TARGET" "$executions" \
    "$((executions / SECONDS_PER_TARGET))" "$(ls "$corpus" | wc -l)" "$cov" \
    "$([ "$found" -gt 0 ] && echo "${found}: ${names}" || echo 0)" | tee -a "$ROWS"
done

{
  echo "<!-- fuzz:begin -->"
  echo "<!-- generated by scripts/fuzz_benchmark.sh; edits between these markers are overwritten -->"
  echo "### Fuzzing: executions and findings"
  echo
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- machine: $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')), shared with other builds"
  echo "- command: \`${COMMAND}\`"
  echo "- harnesses: \`fuzz/fuzz_*.cpp\`, libFuzzer with ASan + UBSan ($(basename "$CXX_FUZZ")); corpus: files"
  echo "  kept in \`build/fuzz/corpus/\` (grows across runs); coverage: edges (libFuzzer \`cov\`);"
  echo "  findings: inputs written to \`build/fuzz/findings/\` in this run."
  echo
  echo "| target | seconds | executions | exec/s | corpus | coverage | findings |"
  echo "|---|---:|---:|---:|---:|---:|---|"
  cat "$ROWS"
  echo "<!-- fuzz:end -->"
} >"$SECTION"

/usr/bin/python3 "${PLY_SLAM_ROOT}/scripts/results_section.py" fuzz "$RESULTS" "$SECTION"
echo "[fuzz] table written to ${RESULTS}"
exit $STATUS

#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, -DHI_FUZZ=ON) and runs each for a
# bounded time; exits non-zero when any harness finds a crash, a sanitizer
# report, a leak, an uncaught exception, a hang or an input that needs more
# than 2 GiB. See docs/reliability.md.
#
# usage: tests/fuzz/run-fuzz.sh [harness ...]      (default: all of them)
# environment:
#   FUZZ_SECONDS   time per harness (default 20)
#   FUZZ_RUNS      stop each harness after this many executions instead (e.g. 10000000)
#   FUZZ_CPU_SECONDS  stop each harness after the executions it runs in this
#                  many CPU seconds at its measured rate (docs/reliability.md,
#                  "Runs and rates"): a count, so with FUZZ_SEED the run is the
#                  same on a fast and a slow machine (CI: 5)
#   FUZZ_JOBS      parallel fuzzing processes per harness (default 1)
#   FUZZ_SEED      libFuzzer's random seed (default: a new one each run). With
#                  a fixed seed, a count of executions (FUZZ_RUNS or
#                  FUZZ_CPU_SECONDS), one job and a fresh FUZZ_BUILD corpus, a
#                  run executes the same inputs on any machine (CI sets 1)
#   FUZZ_BUILD     build folder (default build-fuzz)
#   FUZZ_NO_BUILD  set to 1 to use the harnesses already built
# Findings go to $FUZZ_BUILD/fuzz-artifacts/<harness>/; the corpus grown by a
# run stays in $FUZZ_BUILD/fuzz-corpus/<harness>/ (the checked-in seeds in
# tests/fuzz/corpus are read, never written).
set -euo pipefail
cd "$(dirname "$0")/../.."
src=tests/fuzz
build=${FUZZ_BUILD:-build-fuzz}
seconds=${FUZZ_SECONDS:-20}
jobs=${FUZZ_JOBS:-1}

all=(survey_json survey_nav survey_odometry survey_dvl survey_features survey_landmarks survey_truth
     sonar_json sonar_controls sonar_measurements
     mesh_stl mesh_ply mesh_obj mesh_off mesh_gz mesh_gltf mesh_step image json project)
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=("${all[@]}")

if [ "${FUZZ_NO_BUILD:-0}" != 1 ]; then
  # -O1 with line tables: quick to build, and reports still name file and line.
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DHI_FUZZ=ON -DHI_BUILD_GUI=OFF -DHI_BUILD_TESTS=OFF -DHI_BUILD_BENCH=OFF \
    -DHI_BUILD_GLTF_PLUGIN=OFF -DHI_WERROR=ON >/dev/null
  targets=()
  for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
  cmake --build "$build" -- -l"$(nproc)" "${targets[@]}"
fi

# Largest input per harness: a few times the seeds, far below what would let
# a reader spend seconds legitimately.
max_len() {
  case $1 in
    json) echo 4096 ;;
    image) echo 8192 ;;
    mesh_*) echo 16384 ;;
    *) echo 8192 ;;
  esac
}
dict() {
  case $1 in
    json | survey_json | sonar_json) echo "-dict=$src/dict/json.dict" ;;
    survey_* | sonar_*) echo "-dict=$src/dict/csv.dict" ;;
    mesh_stl | mesh_ply | mesh_obj | mesh_off) echo "-dict=$src/dict/mesh.dict" ;;
    project) echo "-dict=$src/dict/project.dict" ;;
  esac
}

# The harnesses write each input to a file (the readers take paths): keep
# those in memory, not on disk (several times more executions per second).
if [ -z "${TMPDIR:-}" ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/$src/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Executions per CPU second of each harness (docs/reliability.md, "Runs and
# rates", 30 s runs; rounded down).
rate() {
  case $1 in
    survey_json) echo 365 ;;
    survey_nav | survey_odometry | survey_features) echo 170 ;;
    survey_dvl) echo 220 ;;
    survey_landmarks | survey_truth) echo 150 ;;
    sonar_json) echo 900 ;;
    sonar_controls | sonar_measurements) echo 400 ;;
    mesh_stl | mesh_ply | mesh_obj | mesh_off | mesh_gz | project) echo 4000 ;;
    mesh_gltf) echo 130 ;;
    mesh_step) echo 95 ;;
    image) echo 11000 ;;
    json) echo 8800 ;;
    *) echo 100 ;;
  esac
}
limit_for() {
  if [ -n "${FUZZ_CPU_SECONDS:-}" ]; then
    echo "-runs=$(($(rate "$1") * FUZZ_CPU_SECONDS))"
  elif [ -n "${FUZZ_RUNS:-}" ]; then
    echo "-runs=$FUZZ_RUNS"
  else
    echo "-max_total_time=$seconds"
  fi
  [ -z "${FUZZ_SEED:-}" ] || echo "-seed=$FUZZ_SEED"
}
fork=()
[ "$jobs" -le 1 ] || fork=(-fork="$jobs")
failed=()
for h in "${harnesses[@]}"; do
  exe="$build/fuzz/fuzz_$h"
  [ -x "$exe" ] || { echo "no harness $exe" >&2; failed+=("$h (not built)"); continue; }
  work="$build/fuzz-corpus/$h"
  art="$build/fuzz-artifacts/$h"
  mkdir -p "$work" "$art"
  log="$build/fuzz-artifacts/$h.log"
  mapfile -t limit < <(limit_for "$h")
  echo "== fuzz_$h (${limit[*]})"
  # shellcheck disable=SC2046
  if "$exe" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len="$(max_len "$h")" \
    -print_final_stats=1 -artifact_prefix="$art/" $(dict "$h") \
    "${fork[@]}" \
    "$work" "$src/corpus/$h" >"$log" 2>&1; then
    grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec|^stat::peak_rss_mb' "$log" | tr '\n' ' '
    echo
  else
    tail -n 60 "$log"
    echo "fuzz_$h FAILED: input in $art, log $log" >&2
    failed+=("$h")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzing found problems in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzzing: ${#harnesses[@]} harnesses, no findings"

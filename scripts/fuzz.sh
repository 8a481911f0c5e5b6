#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a
# bounded time. See docs/robustness.md.
#
# Usage: scripts/fuzz.sh [run|build|seeds|repro TARGET FILE...]
#   run    (default) build, then fuzz every target for FUZZ_SECONDS each
#   build  configure and build only
#   seeds  rebuild fuzz/corpus/ from our own inputs (fuzz/make_seeds.sh)
#   repro  run TARGET on the given files once (crash reproduction), with
#          DELTAMESH_FUZZ_VERBOSE=1 so fuzz_mesh prints its input as a .poly
#
# Environment:
#   FUZZ_SECONDS  time per target (default 60)
#   FUZZ_TARGETS  space-separated subset (default: every built target)
#   FUZZ_JOBS     targets fuzzed at the same time (default 1)
#   FUZZ_BUILD    build directory (default build-fuzz)
#   FUZZ_FLAGS    extra libFuzzer flags
#   JOBS          build parallelism (default 2)
#
# The committed seeds (fuzz/corpus/TARGET) are read, never written: inputs
# the fuzzer finds go to FUZZ_BUILD/corpus/TARGET and are reused by the next
# run. A crash is saved to FUZZ_BUILD/crashes/TARGET/ and makes the script
# exit 1; turn it into a test under tests/regress/ (docs/robustness.md).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${FUZZ_BUILD:-build-fuzz}
seconds=${FUZZ_SECONDS:-60}
jobs=${JOBS:-2}
fuzz_jobs=${FUZZ_JOBS:-1}
cmd=${1:-run}

configure_and_build() {
  scripts/install-deps.sh core fuzz
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDELTAMESH_FUZZ=ON \
    -DDELTAMESH_TESTS=OFF -DDELTAMESH_SANITIZE=address,undefined >/dev/null
  # Everything in one pass (DELTAMESH_TESTS=OFF: the library, the CLI,
  # deltamesh-gen and the fuzz targets).
  cmake --build "$build" -j "$jobs"
}

targets() {
  if [ -n "${FUZZ_TARGETS:-}" ]; then echo "$FUZZ_TARGETS"; else cat "$build/fuzz/targets.txt"; fi
}

# Per-target input size limit: text formats need room for a few dozen
# lines; fuzz_mesh (and the other PSLG-from-bytes targets) read at most ~1 KB.
max_len() {
  case "$1" in
    fuzz_mesh | fuzz_insert_segments | fuzz_adapt) echo 1024 ;;
    fuzz_geojson) echo 8192 ;;
    *) echo 4096 ;;
  esac
}

fuzz_one() {
  local t=$1
  local corpus=$build/corpus/$t crashes=$build/crashes/$t log=$build/logs/$t.log
  mkdir -p "$corpus" "$crashes" "$(dirname "$log")"
  local dict=()
  case "$t" in
    fuzz_node | fuzz_poly | fuzz_ele | fuzz_area) dict=(-dict=fuzz/triangle_formats.dict) ;;
    *) [ -f "fuzz/$t.dict" ] && dict=(-dict="fuzz/$t.dict") ;;
  esac
  local seeds=()
  [ -d "fuzz/corpus/$t" ] && seeds=("fuzz/corpus/$t")
  local rc=0
  # -timeout: one input may take at most 10 s (refinement has a 2 s limit);
  # -rss_limit_mb/-malloc_limit_mb: an allocation an absurd header asks for
  # is a crash, not a slow swap.
  # shellcheck disable=SC2086
  "$build/fuzz/$t" "$corpus" "${seeds[@]}" "${dict[@]}" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len="$(max_len "$t")" -print_final_stats=1 \
    -artifact_prefix="$crashes/" ${FUZZ_FLAGS:-} >"$log" 2>&1 || rc=$?
  local execs rate cov
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  printf '%-14s %4s  %12s execs  %8s exec/s  %s  corpus %s files\n' "$t" \
    "$([ $rc -eq 0 ] && echo ok || echo FAIL)" "${execs:-?}" "${rate:-?}" "${cov:-}" "$(ls "$corpus" | wc -l)"
  if [ $rc -ne 0 ]; then
    echo "  $t failed (exit $rc); log: $log" >&2
    grep -E "ERROR|invariant violated|SUMMARY|Test unit written" "$log" | head -5 | sed 's/^/  /' >&2
  fi
  return $rc
}

case "$cmd" in
  build) configure_and_build ;;
  seeds)
    configure_and_build
    fuzz/make_seeds.sh "$build"
    ;;
  repro)
    shift
    t=${1:?usage: scripts/fuzz.sh repro TARGET FILE...}
    shift
    [ -x "$build/fuzz/$t" ] || configure_and_build
    DELTAMESH_FUZZ_VERBOSE=1 "$build/fuzz/$t" "$@"
    ;;
  run)
    configure_and_build
    echo "fuzz: $seconds s per target, $fuzz_jobs at a time (logs in $build/logs)"
    status=0
    pids=()
    for t in $(targets); do
      if [ "$fuzz_jobs" -le 1 ]; then
        fuzz_one "$t" || status=1
      else
        fuzz_one "$t" &
        pids+=($!)
        if [ ${#pids[@]} -ge "$fuzz_jobs" ]; then
          wait "${pids[0]}" || status=1
          pids=("${pids[@]:1}")
        fi
      fi
    done
    for p in "${pids[@]}"; do wait "$p" || status=1; done
    if [ $status -ne 0 ]; then
      echo "fuzz: FAILED; crashes are in $root/$build/crashes/ (reproduce: scripts/fuzz.sh repro TARGET FILE)" >&2
    fi
    exit $status
    ;;
  *) echo "usage: scripts/fuzz.sh [run|build|seeds|repro TARGET FILE...]" >&2; exit 2 ;;
esac

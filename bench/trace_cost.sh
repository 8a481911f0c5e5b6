#!/usr/bin/env bash
# What the trace hooks cost when no observer is attached: the working tree's
# CLI against the same tree with the hooks compiled out (Mesh::trace()
# returning nullptr, so the compiler drops every hook call), counted with
# callgrind. Instruction counts are deterministic, so one run per case is
# enough and a busy machine does not change them. docs/trace.md quotes the
# table this prints.
#
# usage: bench/trace_cost.sh [--keep]
#   --keep   keep the work directory (builds, inputs, callgrind files)
# Needs valgrind (scripts/install-deps.sh bench).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
keep=0
[ "${1:-}" = "--keep" ] && keep=1
command -v valgrind >/dev/null || { echo "trace_cost.sh: valgrind is missing (scripts/install-deps.sh bench)" >&2; exit 2; }
jobs=${JOBS:-2}
work=$(mktemp -d "${TMPDIR:-/tmp}/deltamesh-trace-cost.XXXXXX")
cleanup() {
  git -C "$repo" worktree remove --force "$work/notrace" >/dev/null 2>&1 || true
  [ $keep = 1 ] && echo "work directory kept: $work" >&2 || rm -rf "$work"
}
trap cleanup EXIT

build() {  # SRC BUILD
  cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$2" -j"$jobs" --target deltamesh_cli deltamesh-gen >"$2.log" 2>&1 ||
    { tail -30 "$2.log" >&2; echo "trace_cost.sh: build of $1 failed" >&2; exit 1; }
}

# The working tree as it is (uncommitted changes included) ...
mkdir -p "$work/with"
build "$repo" "$work/with/build"
# ... and a copy of it with the hooks compiled out.
git -C "$repo" worktree add --detach --quiet "$work/notrace" HEAD
(cd "$repo" && git diff HEAD) | (cd "$work/notrace" && git apply --allow-empty 2>/dev/null || true)
hdr=$work/notrace/include/deltamesh/mesh.hpp
grep -q 'TraceObserver\* trace() const { return trace_.ptr; }' "$hdr" ||
  { echo "trace_cost.sh: Mesh::trace() in $hdr no longer has the expected form" >&2; exit 1; }
sed -i 's|TraceObserver\* trace() const { return trace_.ptr; }|TraceObserver* trace() const { return nullptr; }|' "$hdr"
build "$work/notrace" "$work/notrace/build"

gen=$work/with/build/bin/deltamesh-gen
mkdir -p "$work/in"
"$gen" uniform 300000 --seed 42 -o "$work/in/u300k.node"
"$gen" smooth 20000 -o "$work/in/smooth20k.poly"
"$gen" square-hole 8 -o "$work/in/square-hole.poly"
"$gen" star 100000 -o "$work/in/star100k.poly"
cases=("u300k.node -NEQ" "smooth20k.poly -pq30Q" "smooth20k.poly -pq33Q"
       "square-hole.poly -pq30a0.00002Q" "star100k.poly -pQ" "smooth20k.poly -pQ --cdt=lawson")
corpus=${CORPUS:-$repo/../shared/corpus}
if [ -f "$corpus/ne50m_land.poly" ]; then
  cp "$corpus/ne50m_land.poly" "$work/in/"
  cases+=("ne50m_land.poly -pq30Q")
else
  echo "trace_cost.sh: $corpus/ne50m_land.poly absent, corpus case skipped" >&2
fi

instructions() {  # BIN INPUT SWITCHES...
  local bin=$1 in=$2; shift 2
  local d; d=$(mktemp -d "$work/run.XXXXXX")
  cp "$work/in/$in" "$d/"
  (cd "$d" && valgrind --tool=callgrind --callgrind-out-file="$d/cg.out" "$bin" "$@" "$in" 2>&1 >/dev/null) |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
  rm -rf "$d"
}

printf '| input | switches | hooks compiled in (Ir) | hooks compiled out (Ir) | ratio |\n|---|---|---:|---:|---:|\n'
for c in "${cases[@]}"; do
  read -r in sw <<<"$c"
  a=$(instructions "$work/with/build/bin/deltamesh" "$in" $sw)
  b=$(instructions "$work/notrace/build/bin/deltamesh" "$in" $sw)
  awk -v i="$in" -v s="$sw" -v a="$a" -v b="$b" \
    'BEGIN { printf "| %s | `%s` | %.1f M | %.1f M | %.4f |\n", i, s, a/1e6, b/1e6, a/b }'
done

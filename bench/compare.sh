#!/usr/bin/env bash
# Whole-process comparison of the working tree against a baseline commit:
# builds both (Release, only deltamesh and deltamesh-gen), generates fixed
# seeded inputs, runs the two binaries alternately RUNS times per case and
# switch string, and prints medians of wall time, CPU time (user + sys) and
# peak RSS, their ratios, triangle counts, bytes per triangle and whether
# the two wrote the same bytes. See bench/README.md and docs/benchmarks.md.
#
# usage: bench/compare.sh [options] [CASE...]
#   --base REV        baseline commit (default ee56553)
#   --base-bin FILE   use this deltamesh as the baseline (no build)
#   --new-bin FILE    use this deltamesh as the new side (no build)
#   --runs N          timed runs per binary and row (default 3)
#   --switches LIST   comma-separated switch strings for every case
#                     (default: per case, see CASES below)
#   --peer FILE|none  CGAL whole-process peer (default: build-bench/bin/
#                     cgal_triangulate_node when built); rows -NEQ and -NQ
#                     on .node cases only
#   --cache DIR       baseline builds (default ${XDG_CACHE_HOME:-~/.cache}/deltamesh-compare)
#   --markdown        print the table as Markdown (for docs/benchmarks.md)
#   --keep            keep the work directory (inputs and last outputs)
# CASES (default: all; corpus cases skipped when ../shared/corpus is absent):
#   u1m           10^6 uniform points, seed 42 (.node)       -NEQ -NQ -Q
#   smooth100k    deltamesh-gen smooth 100000 (.poly)        -pQ -pq30Q
#   square-hole   deltamesh-gen square-hole 8 (.poly)        -pq30a0.000004Q
#   ne50m_land, ne10m_lakes_north_america, ne50m_lakes_all   -pQ -pq30Q
# Environment: JOBS (build parallelism, default 2), CORPUS (corpus dir).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
base_rev=ee56553
base_bin="" new_bin="" runs=3 switches_all="" peer=auto markdown=0 keep=0
cache=${XDG_CACHE_HOME:-$HOME/.cache}/deltamesh-compare
jobs=${JOBS:-2}
corpus=${CORPUS:-$repo/../shared/corpus}
if [ -z "${CORPUS:-}" ] && [ ! -d "$corpus" ]; then
  # In a linked worktree, ../shared is next to the main checkout.
  common=$(cd "$repo" && realpath "$(git rev-parse --git-common-dir)" 2>/dev/null) || common=
  [ -n "$common" ] && corpus=$(dirname "$common")/../shared/corpus
fi
cases=()

die() { echo "compare.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case $1 in
    --base) base_rev=${2:?}; shift 2 ;;
    --base-bin) base_bin=$(realpath "${2:?}"); shift 2 ;;
    --new-bin) new_bin=$(realpath "${2:?}"); shift 2 ;;
    --runs) runs=${2:?}; shift 2 ;;
    --switches) switches_all=${2:?}; shift 2 ;;
    --peer) peer=${2:?}; shift 2 ;;
    --cache) cache=${2:?}; shift 2 ;;
    --markdown) markdown=1; shift ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (try --help)" ;;
    *) cases+=("$1"); shift ;;
  esac
done
[[ $runs =~ ^[1-9][0-9]*$ ]] || die "--runs needs a positive integer"
[ -x /usr/bin/time ] || die "/usr/bin/time (GNU time) is needed for the peak RSS"
[ ${#cases[@]} -gt 0 ] || cases=(u1m smooth100k square-hole ne50m_land ne10m_lakes_north_america ne50m_lakes_all)

log() { echo "$*" >&2; }

# ---- builds -------------------------------------------------------------------
# build SRC_DIR BUILD_DIR: Release, the CLI and the generator only.
build() {
  mkdir -p "$2"
  local log=$2/compare-build.log
  cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_TESTS=OFF -DDELTAMESH_PYTHON=OFF \
    -DDELTAMESH_BENCH=OFF >"$log" 2>&1 || { cat "$log" >&2; die "configuring $1 failed"; }
  cmake --build "$2" -j"$jobs" --target deltamesh_cli deltamesh-gen >>"$log" 2>&1 ||
    { tail -30 "$log" >&2; die "building $1 failed (log: $log)"; }
}

if [ -z "$base_bin" ]; then
  sha=$(git -C "$repo" rev-parse --verify "$base_rev^{commit}") || die "no commit $base_rev"
  bdir=$cache/base-$sha
  base_bin=$bdir/build/bin/deltamesh
  if [ ! -x "$base_bin" ]; then
    log "building baseline $base_rev ($sha) in $bdir"
    mkdir -p "$bdir"
    rm -rf "$bdir/src"
    git -C "$repo" worktree prune
    git -C "$repo" worktree add --detach --quiet "$bdir/src" "$sha"
    build "$bdir/src" "$bdir/build"
    # The binaries are all we keep: the checkout goes.
    git -C "$repo" worktree remove --force "$bdir/src"
  fi
fi
if [ -z "$new_bin" ]; then
  log "building the working tree in $repo/build-compare"
  build "$repo" "$repo/build-compare"
  new_bin=$repo/build-compare/bin/deltamesh
fi
gen=$(dirname "$new_bin")/deltamesh-gen
[ -x "$gen" ] || die "no deltamesh-gen next to $new_bin"
if [ "$peer" = auto ]; then
  peer=none
  [ -x "$repo/build-bench/bin/cgal_triangulate_node" ] && peer=$repo/build-bench/bin/cgal_triangulate_node
fi
[ "$peer" = none ] || [ -x "$peer" ] || die "peer $peer is not executable"

# ---- inputs -------------------------------------------------------------------
work=$(mktemp -d "${TMPDIR:-/tmp}/deltamesh-compare.XXXXXX")
if [ $keep = 1 ]; then log "work directory: $work"; else trap 'rm -rf "$work"' EXIT; fi
mkdir -p "$work/in"

# input CASE: prints the input file of CASE (made once), or nothing to skip it.
input() {
  local f
  case $1 in
    u1m) f=$work/in/u1m.node; [ -f "$f" ] || "$gen" uniform 1000000 --seed 42 -o "$f" ;;
    smooth100k) f=$work/in/smooth100k.poly; [ -f "$f" ] || "$gen" smooth 100000 -o "$f" ;;
    square-hole) f=$work/in/square-hole.poly; [ -f "$f" ] || "$gen" square-hole 8 -o "$f" ;;
    *)
      [ -f "$corpus/$1.poly" ] || { log "compare.sh: $1: not in $corpus, skipped"; return 0; }
      f=$work/in/$1.poly; cp "$corpus/$1.poly" "$f" ;;
  esac
  echo "$f"
}
default_switches() {
  case $1 in
    u1m) echo "-NEQ,-NQ,-Q" ;;
    square-hole) echo "-pq30a0.000004Q" ;;
    *) echo "-pQ,-pq30Q" ;;
  esac
}

# ---- timing -------------------------------------------------------------------
# timed DIR CMD...: runs CMD in DIR, appends "wall cpu rss_kb" to DIR/.times.
timed() {
  local dir=$1 t
  shift
  local TIMEFORMAT='%3R %3U %3S'
  if ! t=$( { time (cd "$dir" && /usr/bin/time -f '%M' -o .rss "$@" >.out 2>.err); } 2>&1); then
    log "compare.sh: failed in $dir: $*"
    cat "$dir/.err" >&2
    exit 1
  fi
  awk -v rss="$(tail -n 1 "$dir/.rss")" '{ printf "%.3f %.3f %s\n", $1, $2 + $3, rss }' <<<"$t" >>"$dir/.times"
}
# Median of column $1 of file $2.
median() {
  awk -v c="$1" '{ print $c }' "$2" | sort -g |
    awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
# Triangles in the mesh deltamesh makes with these switches (an untimed run
# with --stats=json, which also warms the page cache), or "-".
triangles() {
  local bin=$1 dir=$2 sw=$3 file=$4 n
  n=$(cd "$dir" && "$bin" "$sw" --stats=json "$(basename "$file")" 2>/dev/null |
    sed -n 's/.*"triangles":\([0-9]*\).*/\1/p' | head -n 1)
  echo "${n:--}"
}
# Whether the two sides wrote the same files, byte for byte (the version
# line "# generated by deltamesh ..." aside): same / DIFF / none.
same_outputs() {
  local a=$1 b=$2 f any=0
  for f in "$a"/*; do
    [ "$(basename "$f")" = "$(basename "$3")" ] && continue
    any=1
    [ -f "$b/$(basename "$f")" ] || { echo DIFF; return; }
    cmp -s "$f" "$b/$(basename "$f")" && continue
    cmp -s <(grep -v '^# generated by deltamesh' "$f") <(grep -v '^# generated by deltamesh' "$b/$(basename "$f")") ||
      { echo DIFF; return; }
  done
  [ "$(ls "$b" | wc -l)" = "$(ls "$a" | wc -l)" ] || { echo DIFF; return; }
  [ $any = 1 ] && echo same || echo none
}

read -r load_start _ </proc/loadavg 2>/dev/null || load_start=?
log "baseline: $base_bin"
log "new:      $new_bin"
log "peer:     $peer"
log "runs: $runs each, alternating; load average $load_start on $(nproc) cores"

rows=()  # one TSV line per row, formatted at the end
for c in "${cases[@]}"; do
  file=$(input "$c")
  [ -n "$file" ] || continue
  IFS=, read -r -a sws <<<"${switches_all:-$(default_switches "$c")}"
  for sw in "${sws[@]}"; do
    sides=(base new)
    peer_args=()
    if [ "$peer" != none ] && [[ $file == *.node ]]; then
      case $sw in
        -NEQ) peer_args=(--no-output) ;;
        -NQ) peer_args=(-o peer.ele) ;;
      esac
      [ ${#peer_args[@]} -gt 0 ] && sides+=(peer)
    fi
    for s in "${sides[@]}"; do
      rm -rf "$work/$s"
      mkdir -p "$work/$s"
      cp "$file" "$work/$s/"
    done
    log "$c $sw"
    tb=$(triangles "$base_bin" "$work/base" "$sw" "$file")
    tn=$(triangles "$new_bin" "$work/new" "$sw" "$file")
    tp=-
    if [ ${#peer_args[@]} -gt 0 ]; then
      tp=$(cd "$work/peer" && "$peer" -v --no-output "$(basename "$file")" 2>&1 | sed -n 's/.* \([0-9]*\) triangles.*/\1/p')
    fi
    for s in "${sides[@]}"; do rm -f "$work/$s"/*.1.* "$work/$s/.times"; done
    for ((i = 0; i < runs; ++i)); do
      # Rotate who goes first, so neither side always follows the other.
      order=("${sides[@]:i % ${#sides[@]}}" "${sides[@]:0:i % ${#sides[@]}}")
      for s in "${order[@]}"; do
        case $s in
          base) timed "$work/base" "$base_bin" "$sw" "$(basename "$file")" ;;
          new) timed "$work/new" "$new_bin" "$sw" "$(basename "$file")" ;;
          peer) timed "$work/peer" "$peer" "${peer_args[@]}" "$(basename "$file")" ;;
        esac
      done
    done
    same=$(same_outputs "$work/base" "$work/new" "$file")
    row="$c	$sw	$tb	$tn"
    for s in base new; do
      row+="	$(median 1 "$work/$s/.times")	$(median 2 "$work/$s/.times")	$(median 3 "$work/$s/.times")"
    done
    if [ ${#peer_args[@]} -gt 0 ]; then
      row+="	$(median 1 "$work/peer/.times")	$(median 2 "$work/peer/.times")	$(median 3 "$work/peer/.times")	$tp"
    else
      row+="	-	-	-	-"
    fi
    rows+=("$row	$same")
  done
done
read -r load_end _ </proc/loadavg 2>/dev/null || load_end=?

# ---- table --------------------------------------------------------------------
printf '%s\n' "${rows[@]}" | awk -F'\t' -v md=$markdown -v runs="$runs" -v l0="$load_start" -v l1="$load_end" '
  function ratio(a, b) { return (a == "-" || b == "-" || b + 0 == 0) ? "-" : sprintf("%.2f", a / b) }
  function mb(kb) { return kb == "-" ? "-" : sprintf("%.0f", kb / 1024) }
  function bpt(kb, t) { return (kb == "-" || t == "-" || t + 0 == 0) ? "-" : sprintf("%.1f", kb * 1024 / t) }
  BEGIN {
    n = split("case|switches|triangles|base s|new s|new/base|base cpu|new cpu|cpu new/base|base MB|new MB|RSS new/base|new B/tri|peer s|new/peer|peer cpu|cpu new/peer|peer B/tri|outputs", h, "|")
  }
  {
    tri = ($3 == $4) ? $4 : $4 " (base " $3 ")"
    v[NR, 1] = $1; v[NR, 2] = $2; v[NR, 3] = tri
    v[NR, 4] = sprintf("%.3f", $5); v[NR, 5] = sprintf("%.3f", $8); v[NR, 6] = ratio($8, $5)
    v[NR, 7] = sprintf("%.3f", $6); v[NR, 8] = sprintf("%.3f", $9); v[NR, 9] = ratio($9, $6)
    v[NR, 10] = mb($7); v[NR, 11] = mb($10); v[NR, 12] = ratio($10, $7); v[NR, 13] = bpt($10, $4)
    v[NR, 14] = ($11 == "-") ? "-" : sprintf("%.3f", $11); v[NR, 15] = ratio($8, $11)
    v[NR, 16] = ($12 == "-") ? "-" : sprintf("%.3f", $12); v[NR, 17] = ratio($9, $12); v[NR, 18] = bpt($13, $14)
    v[NR, 19] = $15
    if ($5 > 1.15 * $6 || $8 > 1.15 * $9) busy = 1
    rowsn = NR
  }
  END {
    for (j = 1; j <= n; ++j) { w[j] = length(h[j]); for (i = 1; i <= rowsn; ++i) if (length(v[i, j]) > w[j]) w[j] = length(v[i, j]) }
    if (md) {
      line = "|"; sep = "|"
      for (j = 1; j <= n; ++j) { line = line " " h[j] " |"; sep = sep (j <= 3 || j == n ? " --- |" : " ---: |") }
      print line; print sep
      for (i = 1; i <= rowsn; ++i) { line = "|"; for (j = 1; j <= n; ++j) line = line " " v[i, j] " |"; print line }
    } else {
      for (j = 1; j <= n; ++j) printf (j <= 2 ? "%-*s  " : "%*s  "), w[j], h[j]; printf "\n"
      for (i = 1; i <= rowsn; ++i) { for (j = 1; j <= n; ++j) printf (j <= 2 ? "%-*s  " : "%*s  "), w[j], v[i, j]; printf "\n" }
    }
    printf "\nmedians of %d alternated runs; s = wall seconds, cpu = user + sys seconds, MB = peak RSS;\n", runs
    printf "ratios new/base and new/peer (below 1: the new binary is faster or smaller); B/tri = peak RSS / triangles;\n"
    printf "outputs: same = identical bytes (version line aside), DIFF = they differ, none = nothing written.\n"
    printf "load average %s at the start, %s at the end\n", l0, l1
    if (busy) printf "warning: wall time exceeds CPU time by over 15%% in some row: the machine was busy\n"
  }'

#!/usr/bin/env bash
# Runs the benchmarks of a build made with -DDELTAMESH_BENCH=ON and prints a
# summary. See docs/benchmarks.md.
#
# usage: bench/run.sh BUILD_DIR [bench_delaunay options, e.g. --benchmark_filter=1e5]
#
# 1. bench_delaunay (library calls, deltamesh and CGAL in one binary):
#    console output, and JSON in BUILD_DIR/bench_delaunay.json.
# 2. Whole process on 10^6 uniform points: `deltamesh -NQ` (writes .ele)
#    against cgal_triangulate_node (writes .ele), and `deltamesh -NEQ`
#    (writes nothing) against cgal_triangulate_node --no-output; RUNS runs
#    each (default 5), alternating, medians reported.
# 3. A summary table of the medians.
set -euo pipefail

build=${1:?usage: bench/run.sh BUILD_DIR [bench_delaunay options]}
shift
bin=$build/bin
json=$build/bench_delaunay.json
runs=${RUNS:-5}

if [ ! -x "$bin/bench_delaunay" ]; then
  echo "run.sh: $bin/bench_delaunay not found; configure with -DDELTAMESH_BENCH=ON and build" >&2
  exit 1
fi

read -r load1 _ </proc/loadavg 2>/dev/null || load1=0
echo "== bench_delaunay: library calls (medians of the repetitions); load average $load1 on $(nproc) cores"
"$bin/bench_delaunay" --benchmark_format=console --benchmark_out="$json" \
  --benchmark_out_format=json "$@"
echo "JSON written to $json"

# ---- whole process -------------------------------------------------------------
# Median of column $1 of stdin.
median() { awk -v c="$1" '{ print $c }' | sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# "wall cpu" seconds of one run of "$@" (cpu = user + sys; output discarded,
# failure fatal).
timed() {
  local TIMEFORMAT='%3R %3U %3S' t
  if ! t=$( { time "$@" >/dev/null 2>"$tmp/stderr"; } 2>&1); then
    echo "run.sh: failed: $*" >&2
    cat "$tmp/stderr" >&2
    exit 1
  fi
  awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' <<<"$t"
}

whole=()  # "name|dm wall|dm cpu|cgal wall|cgal cpu|label" for the summary
if [ ! -x "$bin/deltamesh" ] || [ ! -x "$bin/deltamesh-gen" ]; then
  echo "run.sh: deltamesh or deltamesh-gen not built; whole-process comparison skipped" >&2
else
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  "$bin/deltamesh-gen" uniform 1000000 --seed 42 -o "$tmp/u1m.node"
  have_cgal=0
  if [ -x "$bin/cgal_triangulate_node" ]; then
    have_cgal=1
  else
    echo "run.sh: cgal_triangulate_node not built (CGAL not found); deltamesh timed alone"
  fi
  echo
  echo "== whole process, 10^6 uniform points, $runs runs each, alternating (median seconds, wall / cpu)"
  for mode in ele none; do
    : >"$tmp/dm" && : >"$tmp/cg"
    for ((i = 0; i < runs; ++i)); do
      if [ $mode = ele ]; then
        timed "$bin/deltamesh" -NQ "$tmp/u1m.node" >>"$tmp/dm"
        if [ $have_cgal = 1 ]; then timed "$bin/cgal_triangulate_node" -o "$tmp/cgal.ele" "$tmp/u1m.node" >>"$tmp/cg"; fi
      else
        timed "$bin/deltamesh" -NEQ "$tmp/u1m.node" >>"$tmp/dm"
        if [ $have_cgal = 1 ]; then timed "$bin/cgal_triangulate_node" --no-output "$tmp/u1m.node" >>"$tmp/cg"; fi
      fi
    done
    dmw=$(median 1 <"$tmp/dm") dmc=$(median 2 <"$tmp/dm")
    cgw=nan cgc=nan
    if [ $have_cgal = 1 ]; then cgw=$(median 1 <"$tmp/cg") cgc=$(median 2 <"$tmp/cg"); fi
    if [ $mode = ele ]; then
      label="read+triangulate+write .ele"
      cmds="deltamesh -NQ | cgal_triangulate_node"
    else
      label="read+triangulate"
      cmds="deltamesh -NEQ | cgal_triangulate_node --no-output"
    fi
    if [ $have_cgal = 1 ]; then cgs=$(printf '%7.3f / %7.3f' "$cgw" "$cgc"); else cgs="-"; fi
    printf '%-28s deltamesh %7.3f / %7.3f   CGAL %s   (%s)\n' "$label" "$dmw" "$dmc" "$cgs" "$cmds"
    whole+=("process_$mode|$dmw|$dmc|$cgw|$cgc|$label")
  done
fi

# ---- refinement ----------------------------------------------------------------
# bench_refine: square with a square hole at -q30 with an area bound (~4e6
# triangles), each configuration in its own process (peak RSS per triangle);
# CGAL's refine_Delaunay_mesh_2 when built with CGAL; the 100k star at -q20.
# Then the triangle counts against Triangle 1.6's on the corpus, when present.
refine_lines=()
if [ -x "$bin/bench_refine" ] && [ -z "${SKIP_REFINE:-}" ]; then
  echo
  echo "== refinement (bench_refine; medians)"
  for cfg in "--runs 3" "--runs 3 --offcenter" "--runs 1 --peer cgal" "--star 100000 --q 20 --runs 3"; do
    # shellcheck disable=SC2086
    if out=$("$bin/bench_refine" $cfg 2>&1); then
      line=$(tail -n 1 <<<"$out")
      echo "bench_refine $cfg: $line"
      refine_lines+=("bench_refine $cfg: $line")
    else
      echo "bench_refine $cfg: skipped ($(tail -n 1 <<<"$out"))"
    fi
  done
  corpus=${CORPUS:-$(cd "$(dirname "$0")/.." && pwd)/../shared/corpus}
  if [ -d "$corpus" ] && [ -x "$bin/deltamesh" ]; then
    echo
    echo "== triangle counts against Triangle 1.6 on $corpus (bench/quality_vs_triangle.sh)"
    qfile=$(mktemp)
    CORPUS=$corpus "$(dirname "$0")/quality_vs_triangle.sh" "$bin/deltamesh" | grep '^TOTAL' | tee "$qfile" || true
    while read -r l; do refine_lines+=("$l"); done <"$qfile"
    rm -f "$qfile"
  else
    echo "run.sh: corpus not found at $corpus; triangle-count comparison skipped"
  fi
fi

# ---- adaptation ------------------------------------------------------------------
# Whole process: a fine mesh of the unit square with the square hole
# [0.4,0.6]^2 (-pq30a5e-6: ~306k triangles) adapted to h = 0.005 + 0.095 x
# (sizes at its vertices in box.1.mtr): read, coarsen, refine, write.
# No peer: neither CGAL's Mesh_2 nor Triangle coarsens.
if [ -x "$bin/deltamesh" ] && [ -z "${SKIP_ADAPT:-}" ]; then
  echo
  echo "== adaptation (deltamesh -rpq30 --adapt box.1; medians of 3)"
  tmp=${tmp:-$(mktemp -d)}
  trap 'rm -rf "$tmp"' EXIT
  printf '8 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n5 0.4 0.4 2\n6 0.6 0.4 2\n7 0.6 0.6 2\n8 0.4 0.6 2\n8 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n5 5 6 2\n6 6 7 2\n7 7 8 2\n8 8 5 2\n1\n1 0.5 0.5\n' >"$tmp/box.poly"
  "$bin/deltamesh" -pq30a0.000005Q "$tmp/box"
  awk 'NR==1{print $1, 1; next} /^#/||NF==0{next} {print 0.005 + 0.095 * $2}' "$tmp/box.1.node" >"$tmp/box.1.mtr"
  for _ in 1 2 3; do timed "$bin/deltamesh" -rpq30Q --adapt "$tmp/box.1"; done >"$tmp/adapt_times"
  before=$(awk 'NR==1{print $1; exit}' "$tmp/box.1.ele")
  after=$(awk 'NR==1{print $1; exit}' "$tmp/box.2.ele")
  line=$(printf 'adapt box: %s -> %s triangles, wall %.3f s, cpu %.3f s' "$before" "$after" \
    "$(median 1 <"$tmp/adapt_times")" "$(median 2 <"$tmp/adapt_times")")
  echo "$line"
  refine_lines+=("$line")
fi

# ---- summary ----------------------------------------------------------------------
echo
echo "== summary (medians; ratio = CGAL wall time / deltamesh wall time, > 1: deltamesh faster;"
echo "   cpu ratio: the same with CPU times, steadier on a busy machine)"
{
  # Google Benchmark writes one "key": value per line.
  awk '
    /"run_name":/       { split($0, q, "\""); run = q[4] }
    /"aggregate_name":/ { split($0, q, "\""); agg = q[4] }
    /"error_occurred":/ { err = 1 }
    /"real_time":/      { gsub(/[ ,]/, "", $2); t = $2 }
    /"cpu_time":/       { gsub(/[ ,]/, "", $2); cpu = $2 }
    /"us_per_pt":/      { gsub(/[ ,]/, "", $2); us = $2 }
    /"B_per_tri":/      { gsub(/[ ,]/, "", $2); bt = $2 }
    /^ *}/ {
      if (agg == "median" && !err) {
        split(run, p, "/"); c = p[3]
        if (!(c in seen)) { seen[c] = 1; order[++n] = c }
        T[c, p[2]] = t; CPU[c, p[2]] = cpu; US[c, p[2]] = us; BT[c, p[2]] = bt
        if (t + 0 > 1.15 * cpu) busy = 1
      }
      run = agg = t = us = bt = cpu = ""; err = 0
    }
    function f(x, fmt) { return x == "" ? "-" : sprintf(fmt, x) }
    END {
      printf "%-16s %12s %12s %7s %9s %10s %10s %9s %9s\n", "case", "deltamesh", "CGAL", "ratio", "cpu ratio", "us/pt dm", "us/pt CGAL", "B/tri dm", "B/tri CGAL"
      for (i = 1; i <= n; ++i) {
        c = order[i]; d = T[c, "deltamesh"]; g = T[c, "cgal"]; dc = CPU[c, "deltamesh"]; gc = CPU[c, "cgal"]
        r = (d != "" && g != "" && d + 0 > 0) ? sprintf("%.2f", g / d) : "-"
        rc = (dc != "" && gc != "" && dc + 0 > 0) ? sprintf("%.2f", gc / dc) : "-"
        printf "%-16s %12s %12s %7s %9s %10s %10s %9s %9s\n", c, f(d, "%.1f ms"), f(g, "%.1f ms"), r, rc,
          f(US[c, "deltamesh"], "%.3f"), f(US[c, "cgal"], "%.3f"), f(BT[c, "deltamesh"], "%.1f"), f(BT[c, "cgal"], "%.1f")
      }
      if (busy) print "warning: wall time exceeds CPU time by over 15% in some case: the machine was busy, figures are inflated"
    }' "$json"
  for w in "${whole[@]}"; do
    IFS='|' read -r name dw dc gw gc label <<<"$w"
    awk -v c="$name" -v l="$label" -v dw="$dw" -v dc="$dc" -v gw="$gw" -v gc="$gc" 'BEGIN {
      have = gw != "nan"
      r = (have && dw + 0 > 0) ? sprintf("%.2f", gw / dw) : "-"
      rc = (have && dc + 0 > 0) ? sprintf("%.2f", gc / dc) : "-"
      printf "%-16s %12s %12s %7s %9s   (whole process, 10^6 uniform: %s)\n", c, sprintf("%.3f s", dw),
        (have ? sprintf("%.3f s", gw) : "-"), r, rc, l }'
  done
}
for l in "${refine_lines[@]}"; do echo "$l"; done

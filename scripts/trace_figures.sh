#!/usr/bin/env bash
# Remakes the trace figures of docs/trace.md (docs/img/trace-*.png) with the
# command line's --trace and scripts/trace_player.py; rsvg-convert (Debian's
# librsvg2-bin, installed by scripts/install-deps.sh) turns them into PNGs.
# usage: scripts/trace_figures.sh [BUILD_DIR]   (default: build)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cli=$repo/${1:-build}/bin/deltamesh
player=$repo/scripts/trace_player.py
src=$repo/docs/examples/trace
img=$repo/docs/img
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[ -x "$cli" ] || { echo "trace_figures.sh: no $cli (make build first)" >&2; exit 2; }
command -v rsvg-convert >/dev/null || { echo "trace_figures.sh: rsvg-convert missing (scripts/install-deps.sh)" >&2; exit 2; }

png() { rsvg-convert "$1" -o "$2"; echo "wrote ${2#$repo/}"; }
flips() { python3 "$player" count "$1" | awk '$2 == "flip" && $3 != "delaunay" {n += $1} END {print n + 0}'; }

# 1. A segment recovered by a queue of flips (Ct, seed §1.2.2).
cp "$src/recover.poly" "$work/"
"$cli" -pcQ --cdt=ct -N -E -P --trace "$work/recover.jsonl" "$work/recover.poly"
python3 "$player" sheet "$work/recover.jsonl" -o "$work/recover.svg" --select flip:recovery --max 8 --cols 3 --panel 300 \
  --final --title "Segment 0-1 recovered by {count} flips of crossing edges (--cdt=ct)"
png "$work/recover.svg" "$img/trace-recover.png"

# 2. The same input by Lawson flips and by lifting-map order.
cp "$src/lawson_vs_lifting.poly" "$work/"
for m in lawson lifting; do
  "$cli" -pQ --cdt=$m -N -E -P --trace "$work/$m.jsonl" "$work/lawson_vs_lifting.poly"
  n=$(flips "$work/$m.jsonl")
  python3 "$player" sheet "$work/$m.jsonl" -o "$work/$m.svg" --phase segments --select flip:recovery,flip:lawson,flip:lifting --max 7 --cols 4 \
    --panel 230 --final --title "--cdt=$m: $n flips to insert the three segments"
  png "$work/$m.svg" "$img/trace-cdt-$m.png"
done

# 3. Ruppert's refinement of a small domain, step by step (R1 and R2).
cp "$repo/examples/plate.poly" "$work/"
"$cli" -pq30Q -N -E -P --trace "$work/plate.jsonl" "$work/plate.poly"
python3 "$player" sheet "$work/plate.jsonl" -o "$work/refine.svg" --select split_segment,split_triangle --cols 4 \
  --panel 230 --final --title "Ruppert refinement of examples/plate.poly to 30 degrees: {count} Steiner points"
png "$work/refine.svg" "$img/trace-refine.png"

# The player itself, on the refinement.
python3 "$player" html "$work/plate.jsonl" -o "$repo/docs/examples/trace/plate-player.html"

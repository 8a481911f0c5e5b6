#!/usr/bin/env bash
# Anisotropic against isotropic adaptation (bench_aniso.cpp; docs/adapt.md):
# error-vs-triangles CSV, the table and plots, mesh pictures, and Gmsh's
# BAMG on the same metric when gmsh is installed. Not part of `make test`.
#
# usage: bench/aniso.sh BUILD_DIR [OUT_DIR]   (BUILD_DIR configured with -DDELTAMESH_BENCH=ON)
#
# Writes OUT_DIR/aniso.csv (bench_aniso's rows), OUT_DIR/aniso_table.md,
# OUT_DIR/aniso_FUNCTION_l2.svg/.png (error plots) and
# OUT_DIR/FUNCTION_{iso,aniso}.svg/.png (meshes at N = 2000).
# Environment: N (complexities, default 250,500,1000,2000,4000,8000),
# ISO_EXTRA (isotropic-only complexities to bracket the anisotropic errors,
# default 16000,32000), ITERATIONS (default 5), NO_GMSH=1 to skip Gmsh.
set -euo pipefail
build=${1:?usage: bench/aniso.sh BUILD_DIR [OUT_DIR]}
out=${2:-$build/aniso}
bin=$build/bin/bench_aniso
[ -x "$bin" ] || { echo "aniso.sh: $bin not found; configure with -DDELTAMESH_BENCH=ON and build bench_aniso" >&2; exit 1; }
mkdir -p "$out/gmsh"
here=$(cd "$(dirname "$0")" && pwd)
gmsh_args=()
if [ -z "${NO_GMSH:-}" ] && command -v gmsh >/dev/null; then gmsh_args=(--gmsh "$out/gmsh"); fi
read -r load1 _ </proc/loadavg 2>/dev/null || load1=0
echo "aniso.sh: load average $load1 on $(nproc) cores" >&2
"$bin" --n "${N:-250,500,1000,2000,4000,8000}" --iterations "${ITERATIONS:-5}" --svg "$out" "${gmsh_args[@]}" \
  > "$out/aniso.csv"
"$bin" --n "${ISO_EXTRA:-16000,32000}" --methods iso --iterations "${ITERATIONS:-5}" | tail -n +2 >> "$out/aniso.csv"
python3 "$here/aniso_plot.py" "$out/aniso.csv" "$out" > "$out/aniso_table.md"
python3 "$here/aniso_plot.py" "$out/aniso.csv" "$out" --error linf > "$out/aniso_table_linf.md"
if command -v rsvg-convert >/dev/null; then
  for f in "$out"/*.svg; do rsvg-convert -w 560 "$f" -o "${f%.svg}.png"; done
fi
cat "$out/aniso_table.md"

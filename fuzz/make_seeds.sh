#!/usr/bin/env bash
# Regenerates the seed corpora fuzz/corpus/<target>/ from our own inputs:
# examples/, deltamesh-gen output, files the deltamesh CLI writes from
# them, and the hand-written snippets below (every syntax the readers
# accept, and near misses). Only our own inputs: nothing is copied from
# elsewhere.
#
# Usage: fuzz/make_seeds.sh BUILD_DIR   (BUILD_DIR/bin holds deltamesh and
# deltamesh-gen; scripts/fuzz.sh seeds calls it with build-fuzz)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: fuzz/make_seeds.sh BUILD_DIR}
gen=$build/bin/deltamesh-gen
cli=$build/bin/deltamesh
for b in "$gen" "$cli"; do
  [ -x "$b" ] || { echo "make_seeds: $b not built" >&2; exit 1; }
done
out=fuzz/corpus
rm -rf "$out"
mkdir -p "$out"/{fuzz_node,fuzz_poly,fuzz_ele,fuzz_area,fuzz_geojson,fuzz_mesh,fuzz_insert_segments,fuzz_adapt,fuzz_hubs}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

seed() {  # seed TARGET NAME  (content on stdin)
  cat > "$out/$1/$2"
}

# random_seeds TARGET BASH_SEED COUNT MIN_LEN LEN_SPAN: COUNT pseudo-random
# byte strings random_1.bin ... of MIN_LEN + (0..LEN_SPAN-1) bytes.
random_seeds() {
  local target=$1 count=$3 min=$4 span=$5 i len s b
  RANDOM=$2
  for i in $(seq 1 "$count"); do
    len=$((min + RANDOM % span))
    s=""
    # RANDOM read here, not inside $(...): bash reseeds it in subshells,
    # which made the strings differ from run to run.
    for _ in $(seq 1 "$len"); do
      b=$((RANDOM % 256))
      s+=$(printf '\\x%02x' "$b")
    done
    printf "$s" | seed "$target" "random_$i.bin"
  done
}

# --- .node: generated point sets (small: the fuzzer mutates, it needs no bulk)
for spec in "uniform 12" "gaussian 12" "grid 16" "collinear 8" "cocircular 10" "duplicates 12"; do
  set -- $spec
  "$gen" "$1" "$2" --seed 3 -o "$out/fuzz_node/gen_$1.node" 2>/dev/null
done
"$gen" uniform 6 --seed 5 --scale 1e-9 -o "$out/fuzz_node/gen_uniform_tiny.node"
"$gen" uniform 6 --seed 5 --scale 1e9 -o "$out/fuzz_node/gen_uniform_huge.node"
seed fuzz_node attributes_markers_1based.node <<'EOF'
# vertices numbered from 1, two attributes and a marker each
4 2 2 1
1 0 0 0.5 -1 1
2 1 0 1.5 2e3 2
3 1 1 +2.5 3 0   # trailing comment
4 0 1 3.5 .4 1
EOF
printf '3 2 0 0\r\n0 0 0\r\n1 1.0e0 0\r\n2 0 1' | seed fuzz_node crlf_no_final_newline.node
printf '\xEF\xBB\xBF3\n0 0 0\n1 1 0\n2 0 1\n' | seed fuzz_node bom_header_count_only.node
printf '3 2 0 0\n0 0 0\n1 1 0\n2 0 1 extra fields\n\n# end\n' | seed fuzz_node trailing_fields.node
printf '2 2 0 0\n0 nan 0\n1 inf -1e400\n' | seed fuzz_node nonfinite.node
printf '1000000000000 2 0 0\n0 0 0\n' | seed fuzz_node absurd_count.node
printf -- '-3 2 0 0\n' | seed fuzz_node negative_count.node
printf '3 2 0 0\n0 0 0\n0 1 0\n2 0 1\n' | seed fuzz_node duplicate_id.node
printf '3 2 0 0\n0 4.9e-324 -0\n1 1e200 0x1p3\n2 3.0 1e-310\n' | seed fuzz_node denormal_hex.node

# --- .poly
cp examples/*.poly "$out/fuzz_poly/"
"$gen" star 8 --seed 2 -o "$out/fuzz_poly/gen_star.poly"
"$gen" square-hole 8 --seed 2 -o "$out/fuzz_poly/gen_square_hole.poly"
seed fuzz_poly square_hole_regions.poly <<'EOF'
8 2 1 1
1 0 0 0 1
2 4 0 0 1
3 4 4 0 1
4 0 4 0 1
5 1 1 1 2
6 3 1 1 2
7 3 3 1 2
8 1 3 1 2
8 1
1 1 2 1
2 2 3 1
3 3 4 1
4 4 1 1
5 5 6 2
6 6 7 2
7 7 8 2
8 8 5 2
1
1 2 2
2
1 0.5 0.5 10 0.1
2 3.5 3.5 20
EOF
printf '0 2 0 0\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n---\n3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n' | seed fuzz_poly vertices_from_node.poly
printf '4 2 0 0\n0 0 0\n1 2 0\n2 0 2\n3 2 2\n2 0\n0 0 3\n1 1 2\n0\n' | seed fuzz_poly crossing_segments.poly
printf '3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n1 0\n0 0 7\n1\n0 9 9\n1\n0 5 5 1\n' | seed fuzz_poly bad_ref_hole_outside.poly

# --- .ele and .area: what the CLI writes for the inputs above. The first
# byte of an .ele seed is the numbering of its vertices (0 or 1).
cp examples/plate.poly "$work/plate.poly"
"$cli" -pQ "$work/plate.poly"
cp "$out/fuzz_node/gen_grid.node" "$work/grid.node"
"$cli" -Q "$work/grid.node"
{ printf '\001'; cat "$work/plate.1.ele"; } | seed fuzz_ele plate.ele
{ printf '\000'; cat "$work/grid.1.ele"; } | seed fuzz_ele grid.ele
printf '\001 2 6 1\n1 1 2 3 4 5 6 0.5\n2 2 3 1 7 8 9 -1\n' | seed fuzz_ele six_nodes_attribute.ele
printf '\000 2 3 0\n0 0 1 2\n1 0 0 3\n' | seed fuzz_ele vertex_twice.ele
printf '\000 1 3 0\n0 0 1 4294967296\n' | seed fuzz_ele huge_vertex.ele
printf '3\n1 0.5\n2 -1\n3 1e-3\n' | seed fuzz_area three.area
awk 'NR==1 && !/^#/ {print $1; next} !/^#/ && NF {print $1, 0.01 * NR}' "$work/plate.1.ele" | seed fuzz_area plate.area
printf '2\n0 nan\n1 1e999\n' | seed fuzz_area nonfinite.area

# --- GeoJSON (first byte: which property options are set; see fuzz_geojson.cpp)
{ printf '\007'; cat <<'EOF'
{"type": "FeatureCollection", "features": [
 {"type": "Feature", "properties": {"a": "lake", "area": 0.5, "m": 3},
  "geometry": {"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,4],[0,4],[0,0]], [[1,1],[1,2],[2,2],[2,1],[1,1]]]}},
 {"type": "Feature", "properties": {"a": 2, "area": null},
  "geometry": {"type": "MultiPolygon", "coordinates": [[[[4,0],[6,0],[6,4],[4,4],[4,0]]], [[[7,7],[8,7],[8,8.5e0]]]]}},
 {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [1, 2]}}
]}
EOF
} | seed fuzz_geojson features.geojson
{ printf '\000'; printf '{"type":"Polygon","coordinates":[[[0,0,1],[1,0,1],[0,1,1],[0,0,1]]]}'; } | seed fuzz_geojson bare_polygon.geojson
{ printf '\001'; printf '{"type":"GeometryCollection","geometries":[{"type":"Polygon","coordinates":[[[-1e-3,2E2],[1,0],[0,1]]]}, null]}\n'; } | seed fuzz_geojson collection_unclosed.geojson
{ printf '\000'; printf '{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], "x"]], "\\u00e9\\ud83d\\ude00": [true, false, null]}'; } | seed fuzz_geojson bad_position.geojson

# --- fuzz_mesh: bytes, read by FuzzedDataProvider from the end backwards
# (options, then counts, then coordinates). A few fixed patterns and
# seeded pseudo-random strings.
printf '\x01\x00\x02\x03\x04\x05\x06\x07\x08\x09\x0a\x0b\x0c\x0d\x0e\x0f\x10\x11\x12\x13\x14\x15\x16\x17\x18\x19\x1a\x1b\x1c\x1d\x1e\x1f\x00\x05\x03\x08\x21\x01' | seed fuzz_mesh counting.bin
random_seeds fuzz_mesh 7 24 16 200
# --- fuzz_insert_segments: byte values in the order the target consumes
# them (FuzzedDataProvider reads from the end, so they are written
# reversed): f1 f2 coord-mode grid [scale shift bool bool] n-3 m k-1,
# points, PSLG segments (a b marker; only a marker for the ring f1&1
# makes), a hole point if f1&2, then the new segments (a b marker).
seed_bytes_to() {  # seed_bytes_to TARGET NAME BYTE...
  local target=$1 name=$2 s="" i
  shift 2
  local a=("$@")
  for ((i = ${#a[@]} - 1; i >= 0; i--)); do s+=$(printf '\\x%02x' "${a[i]}"); done
  printf "$s" | seed "$target" "$name"
}
seed_bytes() { seed_bytes_to fuzz_insert_segments "$@"; }
# square 0..4 carved by its ring, both diagonals (they cross: a new vertex)
seed_bytes square_diagonals.bin 1 0 0 3 1 4 1  0 0 4 0 4 4 0 4  1 1 1 1  0 2 2 1 3 3
# the same under strict: IntersectingSegments, the mesh unchanged
seed_bytes square_diagonals_strict.bin 1 4 0 3 1 4 1  0 0 4 0 4 4 0 4  1 1 1 1  0 2 2 1 3 3
# square with a square hole; the last new segment passes through the hole
seed_bytes hole_through.bin 2 0 0 5 5 8 2  0 0 6 0 6 6 0 6 2 2 4 2 4 4 2 4 \
  0 1 1 1 2 1 2 3 1 3 0 1 4 5 2 5 6 2 6 7 2 7 4 2  3 3  0 4 1 1 5 1 0 2 0
# the same, new segments from the outer to the inner corners (Lawson, no final flips)
seed_bytes hole_corners.bin 2 10 0 5 5 8 2  0 0 6 0 6 6 0 6 2 2 4 2 4 4 2 4 \
  0 1 1 1 2 1 2 3 1 3 0 1 4 5 2 5 6 2 6 7 2 7 4 2  3 3  0 4 1 1 5 1 2 6 0
# convex hull, points moved by an ulp near a diagonal; refined afterwards
seed_bytes ulp_near_diagonal.bin 28 3 2 7 60 0 0 0 3 0 2 \
  0 3 0 3  8 3 0 3  8 3 8 3  0 3 8 3  4 4 4 3  2 3 2 3  0 2 1 1 3 2 5 2 0
# collinear vertices on a new segment, a zero-length one, a crossing (Ct)
seed_bytes collinear_chain.bin 4 9 0 3 3 0 2  0 0 1 1 2 2 3 3 3 0 0 3  0 3 1 0 0 0 4 5 2
# an endpoint out of range: SegmentError
seed_bytes out_of_range.bin 4 0 0 3 0 0 1  0 0 4 0 0 4  0 2 0 3 1 1
random_seeds fuzz_insert_segments 11 12 24 120
# --- fuzz_adapt: the same convention (values reduced modulo their range):
# f1 f2 f3 coord-mode grid [scale shift bool bool] n-3 ns, points (x y,
# each followed by an ulp shift 0..6 -> -3..3 in mode 2), segments (a b
# marker; a marker for ring ones), a hole point if f1&2; then per step the
# coarsen byte (ratio, max_spoke, renumber, protect), [protect id],
# max_removals 0..3 [count], [field kind on the second step], the field's
# parameters (see fuzz_adapt.cpp).
# 8x8 square ring and its centre, refined to 30 degrees; coarsen to a huge field
seed_bytes_to fuzz_adapt square_refined_huge.bin 161 5 4 0 8 2 4  0 0 8 0 8 8 0 8 4 4  1 1 1 1  0 0 2
# the same, adapt to a ramp, input vertices protected
seed_bytes_to fuzz_adapt square_adapt_ramp.bin 161 53 13 0 8 2 4  0 0 8 0 8 8 0 8 4 4  1 1 1 1  64 0 5 16
# square with a square hole; coarsen to a wavy field, then adapt (no renumbering)
# to sizes at the mesh's vertices
seed_bytes_to fuzz_adapt hole_wavy_then_background.bin 98 10 18 0 12 5 8 \
  0 0 12 0 12 12 0 12 4 4 8 4 8 8 4 8  0 1 1 1 2 1 2 3 1 3 0 1 4 5 2 5 6 2 6 7 2 7 4 2  6 6 \
  0 0 2 1 2  32 0 6
# ulp-perturbed rectangle with collinear boundary vertices; a NaN disk in the field
seed_bytes_to fuzz_adapt ulp_chain_nan_disk.bin 37 0 20 2 8 60 20 1 0 3 6 \
  0 3 0 3 4 5 0 3 8 3 0 3 8 3 8 3 4 1 8 6 0 3 8 3  1 1 1 1 1 1  0 0 1 3 4 3 4 3 3
# point set with two segments (Lawson); adapt to sizes on a background point
# set, a random protected prefix, at most 3 removals
seed_bytes_to fuzz_adapt points_background_adapt.bin 44 18 29 0 10 5 2 \
  0 0 10 0 10 10 0 10 2 3 7 8 5 1 3 9  0 5 2 1 6 3  130 4 2  1 0 0 10 0 0 10 10 10 8 10 6 12 0
# square with markers changing at the corners, fine mesh; coarsen to a tiny
# field, then to a huge one with no spoke limit
seed_bytes_to fuzz_adapt markers_tiny_then_huge.bin 161 11 11 0 15 1 4  0 0 16 0 16 16 0 16  1 2 1 2  0 0 10  24 0 1 3
# sizes at the vertices with a zero among them: InputError
seed_bytes_to fuzz_adapt background_bad_size.bin 33 0 24 0 4 2 4  0 0 4 0 4 4 0 4 2 2  0 0 0 0  0 0  5 5 5 5 5 1
random_seeds fuzz_adapt 13 12 24 160
# --- fuzz_hubs: bytes read from the end (options, degree, seed, scale),
# the spoke directions from the front, two bytes each; seeded strings of
# 20-600 bytes give hubs of every size (the degree falls back to the seed's
# directions when the bytes run out).
random_seeds fuzz_hubs 17 16 20 580
echo "make_seeds: $(find "$out" -type f | wc -l) seeds, $(du -sk "$out" | cut -f1) KiB in $out"

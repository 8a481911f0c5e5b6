// The command line's --help text.
#include "deltamesh/switches.hpp"

namespace deltamesh {

std::string help_text() {
  return R"(deltamesh - two-dimensional Delaunay triangulation and mesh generation

Usage: deltamesh [-switches] [--long-options] FILE

Reads FILE.node (or FILE.poly with -p, or FILE.node + FILE.ele with -r, or
FILE.geojson / FILE.json: GeoJSON polygons, meshed even-odd like -p) and
writes FILE.1.node and FILE.1.ele, plus FILE.1.poly with -p (Triangle's formats
and naming: an input FILE.1.node gives FILE.2.*). With --output, only the
named files are written (and those of -e -n -v -g).

Every switch has a long option (shown on the right); see docs/cli.md.

Switches (Triangle's, combinable as one string, e.g. -pczV):
Input:
  -p  read FILE.poly: segments, holes, regional attributes; constrained
      Delaunay triangulation of the domain the segments enclose  --poly
  -r  (--refine) read a mesh (FILE.node, FILE.ele; with -p also FILE.poly: its
      segments are inserted where they are not edges yet, its holes carved)
      and refine it (with -q/-a; -a without a number reads the per-triangle
      bounds of FILE.area) into the next iteration
  --adapt  (implies -r) adapt the mesh to the target edge lengths of FILE.mtr
      (TetGen's format: '<#nodes> 1', then one size per node): coarsen where
      edges are shorter than the size, refine where longer (with -q: quality),
      then smooth (2 passes; --smooth=N sets them, --smooth=0 none)
  --smooth[=N]  N passes (default 3) of vertex smoothing after meshing or
      refinement: free interior vertices move towards the centroid of their
      neighbours when the smallest angle around them does not drop (nor -a's
      area or --adapt's sizes get worse), then Delaunay flips; input
      vertices, segments and the boundary stay
Quality meshing:
  -q[ANGLE]  (--quality, --min-angle=ANGLE) quality mesh: no angle below ANGLE degrees (default 20), except
      in input angles under 60 degrees; up to ~34 in practice
  -a[AREA]   (--max-area=AREA, --regional-area) maximum triangle area; -a without a number: the .poly regions'
      bounds (with -r: FILE.area)
  -S[N]      (--steiner-budget=N) at most N Steiner points (exit code 3 if the bound is not reached)
  -Y  no Steiner points on boundary segments; -YY none on any segment
      --no-boundary-steiner (twice: -YY)
  -D  conforming Delaunay: segments split until every edge is locally Delaunay
      --conforming-delaunay
Domain:
  -c  keep the whole convex hull and make its edges segments  --convex-hull
  -A  regional attribute per triangle from the .poly regions  --regional-attributes
  -O  ignore the holes of the .poly file                      --ignore-holes
Output files:
  -P  do not write the .poly file                             --no-poly
  -z  number vertices and triangles from zero                 --zero-based
  -e  also write FILE.1.edge (edges with boundary markers)    --edges
  -n  also write FILE.1.neigh (triangle neighbours)           --neighbors
  -N  do not write the .node file                             --no-node
  -E  do not write the .ele file                              --no-ele
  -I  no iteration number: write FILE.node, FILE.ele           --no-iteration
      (an output that would replace an input is refused)       --overwrite allows it
  -j  drop duplicate and unused vertices from the output      --jettison
  -B  no boundary markers in the output                       --no-markers
  -v  also write the Voronoi diagram (dual graph): FILE.1.v.node, FILE.1.v.edge
      --voronoi
  -g  also write FILE.1.off (Geomview's OFF format)           --off
Messages and checks:
  -C  check the mesh (topology, orientation, Delaunay)        --check
  -Q  quiet: print nothing unless there is an error           --quiet
  -V  verbose: counts and timings per phase                   --verbose
  -h  this help                                               --help
Triangle's algorithm choices, accepted and mapped to deltamesh's (-V prints a note):
  -i (--incremental), -F (--sweepline): the Delaunay triangulation is the same
      (deltamesh always inserts incrementally in Hilbert order)
  -l (--vertical-cuts): no effect (no divide-and-conquer)
  -X (--no-exact): no effect (predicates are always exact)
  -s (--split-segments): segments are always recovered in a constrained
      triangulation; add -D for a conforming Delaunay mesh
  -o2 (--second-order): six-node triangles: a node at the midpoint of every
      edge, in FILE.1.node and the 6-node FILE.1.ele, and in .msh/.vtu/.vtk outputs;
      -r on a 6-node mesh refines its corner mesh (old midpoints dropped)
Not available (parsed, then refused): -u (--user-area: a size function
compiled in; in the C++ API it is RefineOptions::max_area_at, thread-safe).

Long options:
  --cdt=METHOD     segment insertion: fast (default), ct (flips, not always
                   Delaunay), lawson (ct + Lawson flips), lifting (flips ordered
                   by the lifting map)
  --fill=RULE      holes (default: Triangle's hole points and exterior) or
                   evenodd (keep odd nesting depth; no hole points needed)
  --strict         crossing segments are an error instead of being split
  --steiner=RULE   refinement's Steiner points: best (default, fewest
                   triangles), grid (the same search scored on the mesh,
                   slower), offcenter (quickest) or circumcenter (the
                   seed's algorithm)
  --encroachment=RULE  lens (default) or circle (the seed's R1): when a
                   vertex near a segment makes it split
  --order=ORDER    shortest (default: shortest edge first) or worst (worst
                   angle first); circumcenter + circle + worst is exactly
                   Ruppert's algorithm
  --time-limit=S   stop refining after S seconds (exit code 3)
  --stats=json     print the mesh quality report as one JSON object
  --svg PATH       also write an SVG picture of the mesh
Output formats:
  --output PATH    write the mesh to PATH, in the format its extension names:
                   .msh (Gmsh) .vtu .vtk (VTK) .svg .geojson .off, or a
                   Triangle format (repeatable); when given, FILE.1.node/.ele/
                   .poly are not written
  --msh-version=V  2.2 or 4.1 (default) for .msh outputs
  --vtu-binary     .vtu data arrays as base64 binary
  --geojson-segments  .geojson outputs also carry boundary/segment lines
  --voronoi-overlay   bounded Voronoi cells in .svg and .geojson outputs
GeoJSON input (FILE.geojson, FILE.json):
  --region-property=NAME  a feature property as the regional attribute of
                   its polygons (strings numbered 1, 2, ... in order)
  --area-property=NAME    a numeric feature property as the maximum
                   triangle area of its polygons (refines to meet them)
  --version        print the version

Examples:
  deltamesh points.node              Delaunay triangulation -> points.1.node, points.1.ele
  deltamesh -pV plate.poly           mesh a PSLG with holes, verbose -> plate.1.{node,ele,poly}
  deltamesh -pcA plate               whole convex hull, regional attributes
  deltamesh -rpe plate.1             rebuild plate.1 with its segments -> plate.2.*, with edges
  deltamesh -p --fill=evenodd map    polygons with nested rings and no hole points
  deltamesh -pq30a0.01V plate        quality mesh, angles >= 30, areas <= 0.01
  deltamesh -pq --output plate.msh --msh-version=2.2 plate   only plate.msh (Gmsh 2.2)
  deltamesh -q --region-property=name --output map.vtu map.geojson
  deltamesh -pq --voronoi-overlay --output plate.svg plate   picture with Voronoi cells

Exit codes:
  0 success (an empty domain is a success), 1 usage error or a switch not
  available yet, 2 input error (file missing or malformed, or no triangle
  possible), 3 budget reached before the requested quality, 4 output file could
  not be written, 5 -C found the mesh invalid, 70 internal error (a bug).
)";
}

}  // namespace deltamesh

// Command-line options: Triangle's switch string (-pq30a0.1) and long options.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "deltamesh/cdt.hpp"
#include "deltamesh/domain.hpp"
#include "deltamesh/refine.hpp"

namespace deltamesh::cli {

// Documented exit codes.
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,        // bad switches or arguments, or a switch not available yet
  kExitInput = 2,        // input file missing, unreadable or malformed; input not meshable
  kExitBudget = 3,       // a budget stopped refinement before the requested quality, or triangles are left too large
  kExitOutput = 4,       // an output file could not be written
  kExitCheckFailed = 5,  // -C found the mesh invalid
  kExitInternal = 70,    // a bug: please report it
};

struct Options {
  // Triangle switches that work.
  bool poly = false;                 // -p  read FILE.poly (segments, holes, regions)
  bool refine = false;               // -r  read a mesh: FILE.node + FILE.ele (rebuilt, not refined yet)
  bool adapt = false;                // --adapt (implies -r): coarsen and refine to FILE.mtr's per-vertex sizes
  int smooth = -1;                   // --smooth[=N]: N smoothing passes after refinement (-1: not given)
  bool convex_hull = false;          // -c
  bool regional_attributes = false;  // -A
  bool ignore_holes = false;         // -O
  bool no_poly = false;              // -P
  bool zero_based = false;           // -z
  bool quiet = false;                // -Q
  int verbose = 0;                   // -V (repeatable)
  bool check = false;                // -C
  bool no_node = false;              // -N
  bool no_ele = false;               // -E
  bool no_iteration = false;         // -I
  bool jettison = false;             // -j
  bool edges = false;                // -e
  bool neighbors = false;            // -n
  bool no_markers = false;           // -B
  bool voronoi = false;              // -v  FILE.1.v.node, FILE.1.v.edge
  bool geomview = false;             // -g  FILE.1.off
  bool help = false;                 // -h / --help

  // Triangle switches that are parsed (numbers included) but whose feature
  // is not built yet; `unavailable` names each one given, and the run stops
  // with a usage error while it is not empty.
  bool quality = false;                       // -q[angle]
  std::optional<double> min_angle;            //   the angle after q
  bool area = false;                          // -a[area]
  std::optional<double> max_area;             //   the area after a (without: per-region / .area bounds)
  bool area_from_regions = false;             //   -a given without a number
  bool user_area = false;                     // -u
  std::optional<unsigned long long> steiner_budget;  // -S[n]
  int order = 1;                              // -o2
  int no_boundary_steiner = 0;                // -Y, -YY
  bool conforming_delaunay = false;           // -D
  bool split_segments = false;                // -s
  std::vector<std::string> unavailable;       // e.g. "-q30 (quality mesh generation with a minimum angle)"
  // Accepted for compatibility, no effect: -i -F (Triangle's algorithm
  // choices), -l (divide-and-conquer cuts), -X (exact arithmetic is always on).

  // Long options.
  // Refinement (with -q, -a, -S, -D): where Steiner points go, when a
  // vertex encroaches a segment, which bad triangle goes first, a time limit,
  // and the quality report as JSON on standard output.
  SteinerRule steiner = SteinerRule::Best;                          // --steiner=best|offcenter|circumcenter
  EncroachmentRule encroachment = EncroachmentRule::DiametralLens;  // --encroachment=lens|circle
  RefineOrder refine_order = RefineOrder::ShortestEdgeFirst;        // --order=shortest|worst
  double time_limit = 0.0;                                          // --time-limit=SECONDS
  bool stats_json = false;                                          // --stats=json
  CdtMethod cdt_method = CdtMethod::Fast;     // --cdt=fast|ct|lawson|lifting
  FillRule fill = FillRule::Holes;            // --fill=holes|evenodd
  bool strict = false;                        // --strict
  bool version = false;
  std::optional<std::string> svg_path;
  std::vector<std::string> outputs;  // --output PATH (format from the extension); when given, only these
                                     // (and -e -n -v -g files) are written, not FILE.1.node/.ele/.poly
  bool msh_v22 = false;              // --msh-version=2.2 (default 4.1)
  bool vtu_binary = false;           // --vtu-binary
  bool geojson_segments = false;     // --geojson-segments
  bool voronoi_overlay = false;      // --voronoi-overlay (bounded Voronoi cells in .svg/.geojson)
  std::string region_property;       // --region-property NAME (GeoJSON input)
  std::string area_property;         // --area-property NAME (GeoJSON input)
  std::vector<char> compat_notes;    // -i -F -l -X -s given: explained with -V
  std::string input;  // the FILE argument as given
};

// Parses argv. Throws UsageError with a message naming the offending switch.
Options parse_arguments(const std::vector<std::string>& args);

struct UsageError {
  std::string message;
};

std::string help_text();

// The refinement the switches ask for (-q -a -S -Y -D, --steiner, ...).
// -a without a number (area_from_regions) turns on the mesh's own bounds;
// callers with other sources of bounds (GeoJSON's --area-property) add them.
RefineOptions refine_options(const Options& o);

}  // namespace deltamesh::cli

#include "deltamesh/switches.hpp"

#include "deltamesh/formats.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <charconv>
#include <cmath>
#include <string_view>

namespace deltamesh::cli {

namespace {

// A switch string is Triangle's: letters, each optionally followed by a
// number with no space (-pq30.5a0.01zQ). Numbers are digits and '.' only, so
// a letter that follows a number (like the 'e' in -a0.1e) is the next switch.
class SwitchString {
 public:
  SwitchString(std::string_view s, Options& o) : s_(s), o_(o) {}

  void parse() {
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      switch (c) {
        case 'p': o_.poly = true; break;
        case 'r': o_.refine = true; break;
        case 'c': o_.convex_hull = true; break;
        case 'A': o_.regional_attributes = true; break;
        case 'O': o_.ignore_holes = true; break;
        case 'P': o_.no_poly = true; break;
        case 'z': o_.zero_based = true; break;
        case 'Q': o_.quiet = true; break;
        case 'V': ++o_.verbose; break;
        case 'C': o_.check = true; break;
        case 'N': o_.no_node = true; break;
        case 'E': o_.no_ele = true; break;
        case 'I': o_.no_iteration = true; break;
        case 'j': o_.jettison = true; break;
        case 'e': o_.edges = true; break;
        case 'n': o_.neighbors = true; break;
        case 'B': o_.no_markers = true; break;
        case 'h': o_.help = true; break;
        case 'i': case 'F': case 'l': case 'X': case 's':  // accepted: mapped to ours, a note with -V
          if (std::find(o_.compat_notes.begin(), o_.compat_notes.end(), c) == o_.compat_notes.end())
            o_.compat_notes.push_back(c);
          break;
        case 'q': {
          o_.quality = true;
          const std::string_view num = number();
          if (!num.empty()) o_.min_angle = to_double(c, num);
          break;
        }
        case 'a': {
          o_.area = true;
          const std::string_view num = number();
          if (num.empty()) {
            o_.area_from_regions = true;
          } else {
            o_.max_area = to_double(c, num);
            if (!(*o_.max_area > 0))
              throw UsageError{"-a" + std::string(num) + ": the maximum area must be positive"};
          }
          break;
        }
        case 'S': {
          const std::string_view num = digits();
          unsigned long long n = 0;
          if (!num.empty()) {
            const auto r = std::from_chars(num.data(), num.data() + num.size(), n);
            if (r.ec != std::errc() || r.ptr != num.data() + num.size())
              throw UsageError{"-S" + std::string(num) + ": the Steiner point budget is too large"};
          }
          o_.steiner_budget = n;
          break;
        }
        case 'o': {
          if (i_ >= s_.size() || s_[i_] != '2')
            throw UsageError{"switch -o must be followed by 2 (-o2: second-order, six-node triangles)"};
          ++i_;
          o_.order = 2;
          break;
        }
        case 'Y':
          ++o_.no_boundary_steiner;
          break;
        // -u: Triangle calls a function compiled into it; here that is the
        // API's RefineOptions::max_area_at / max_edge_at callback.
        case 'u': o_.user_area = true; planned(c, {}, "user size function: the C++ API's RefineOptions::max_area_at"); break;
        case 'D': o_.conforming_delaunay = true; break;
        case 'v': o_.voronoi = true; break;
        case 'g': o_.geomview = true; break;
        default:
          if (std::isdigit(static_cast<unsigned char>(c)) || c == '.')
            throw UsageError{std::string("number '") + c + "' in '-" + std::string(s_) +
                             "' does not follow a switch that takes one (q, a, S)"};
          throw UsageError{std::string("unknown switch -") + c + " in '-" + std::string(s_) +
                           "' (see deltamesh --help)"};
      }
    }
  }

 private:
  // The run of digits and '.' at the current position (possibly empty).
  std::string_view number() {
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) ++i_;
    return s_.substr(start, i_ - start);
  }
  std::string_view digits() {
    const std::size_t start = i_;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
    return s_.substr(start, i_ - start);
  }
  static double to_double(char c, std::string_view num) {
    double v = 0;
    const auto r = std::from_chars(num.data(), num.data() + num.size(), v);
    if (r.ec != std::errc() || r.ptr != num.data() + num.size() || !std::isfinite(v))
      throw UsageError{std::string("-") + c + std::string(num) + ": '" + std::string(num) + "' is not a number"};
    return v;
  }
  void planned(char c, std::string_view num, const char* what) {
    o_.unavailable.push_back(std::string("-") + c + std::string(num) + " (" + what + ")");
  }

  std::string_view s_;
  Options& o_;
  std::size_t i_ = 0;
};

}  // namespace

Options parse_arguments(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const std::string& name) -> std::string {
      const auto eq = a.find('=');
      if (eq != std::string::npos) return a.substr(eq + 1);
      if (i + 1 >= args.size()) throw UsageError{"option " + name + " needs a value"};
      return args[++i];
    };
    auto no_value = [&](const std::string& name) {
      if (a.find('=') != std::string::npos) throw UsageError{"option " + name + " takes no value"};
    };
    if (a.rfind("--", 0) == 0) {
      const std::string name = a.substr(0, a.find('='));
      if (name == "--svg") {
        o.svg_path = value(name);
      } else if (name == "--output") {
        const std::string v = value(name);
        if (!output_format_for(v))
          throw UsageError{"--output " + v +
                           ": cannot tell the format from the extension (known: .msh .vtu .vtk .svg .geojson .json "
                           ".off .node .ele .edge .neigh .poly)"};
        o.outputs.push_back(v);
      } else if (name == "--msh-version") {
        const std::string v = value(name);
        if (v == "2.2") o.msh_v22 = true;
        else if (v == "4.1" || v == "4") o.msh_v22 = false;
        else throw UsageError{"--msh-version=" + v + ": the version must be 2.2 or 4.1"};
      } else if (name == "--region-property") {
        o.region_property = value(name);
      } else if (name == "--area-property") {
        o.area_property = value(name);
      } else if (name == "--min-angle") {
        o.quality = true;
        const std::string v = value(name);
        char* end = nullptr;
        const double t = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !std::isfinite(t)) throw UsageError{"--min-angle=" + v + ": degrees, a number"};
        o.min_angle = t;
      } else if (name == "--max-area") {
        o.area = true;
        const std::string v = value(name);
        char* end = nullptr;
        const double t = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !(t > 0) || !std::isfinite(t))
          throw UsageError{"--max-area=" + v + ": the maximum area must be a positive number"};
        o.max_area = t;
      } else if (name == "--smooth") {
        // The count is optional: --smooth alone is 3 passes.
        o.smooth = 3;
        if (a.find('=') != std::string::npos) {
          const std::string v = a.substr(a.find('=') + 1);
          int n = 0;
          const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
          if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size() || n < 0 || n > 1000)
            throw UsageError{"--smooth=" + v + ": a number of passes from 0 to 1000"};
          o.smooth = n;
        }
      } else if (name == "--steiner-budget") {
        const std::string v = value(name);
        unsigned long long n = 0;
        const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
        if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size())
          throw UsageError{"--steiner-budget=" + v + ": a count of Steiner points"};
        o.steiner_budget = n;
      } else if (name == "--cdt") {
        const std::string v = value(name);
        const std::optional<CdtMethod> m = v == "fast"     ? std::optional(CdtMethod::Fast)
                                           : v == "ct"      ? std::optional(CdtMethod::Ct)
                                           : v == "lawson"  ? std::optional(CdtMethod::Lawson)
                                           : v == "lifting" ? std::optional(CdtMethod::Lifting)
                                                            : std::nullopt;
        if (!m) throw UsageError{"--cdt=" + v + ": the method must be fast, ct, lawson or lifting"};
        o.cdt_method = *m;
      } else if (name == "--steiner") {
        const std::string v = value(name);
        const auto r = parse_steiner_rule(v);
        if (!r) throw UsageError{"--steiner=" + v + ": the rule must be best, offcenter or circumcenter"};
        o.steiner = *r;
      } else if (name == "--encroachment") {
        const std::string v = value(name);
        const auto r = parse_encroachment_rule(v);
        if (!r) throw UsageError{"--encroachment=" + v + ": the rule must be lens or circle"};
        o.encroachment = *r;
      } else if (name == "--order") {
        const std::string v = value(name);
        if (v == "shortest") o.refine_order = RefineOrder::ShortestEdgeFirst;
        else if (v == "worst") o.refine_order = RefineOrder::WorstFirst;
        else throw UsageError{"--order=" + v + ": the order must be shortest or worst"};
      } else if (name == "--time-limit") {
        const std::string v = value(name);
        char* end = nullptr;
        const double t = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !(t > 0)) throw UsageError{"--time-limit=" + v + ": seconds, a positive number"};
        o.time_limit = t;
      } else if (name == "--stats") {
        const std::string v = value(name);
        if (v != "json") throw UsageError{"--stats=" + v + ": the only format is json"};
        o.stats_json = true;
      } else if (name == "--fill") {
        const std::string v = value(name);
        if (v == "holes") o.fill = FillRule::Holes;
        else if (v == "evenodd" || v == "even-odd") o.fill = FillRule::EvenOdd;
        else throw UsageError{"--fill=" + v + ": the rule must be holes or evenodd"};
      } else {
        no_value(name);
        if (name == "--help") o.help = true;
        else if (name == "--version") o.version = true;
        else if (name == "--strict") o.strict = true;
        else if (name == "--quiet") o.quiet = true;
        else if (name == "--verbose") ++o.verbose;
        else if (name == "--check") o.check = true;
        else if (name == "--zero-based") o.zero_based = true;
        else if (name == "--jettison") o.jettison = true;
        else if (name == "--edges") o.edges = true;
        else if (name == "--neighbors") o.neighbors = true;
        else if (name == "--no-node") o.no_node = true;
        else if (name == "--no-ele") o.no_ele = true;
        else if (name == "--no-poly") o.no_poly = true;
        else if (name == "--no-iteration") o.no_iteration = true;
        else if (name == "--no-markers") o.no_markers = true;
        else if (name == "--convex-hull") o.convex_hull = true;
        else if (name == "--regional-attributes") o.regional_attributes = true;
        else if (name == "--ignore-holes") o.ignore_holes = true;
        else if (name == "--vtu-binary") o.vtu_binary = true;
        else if (name == "--geojson-segments") o.geojson_segments = true;
        else if (name == "--voronoi-overlay") o.voronoi_overlay = true;
        else if (name == "--poly") o.poly = true;
        else if (name == "--refine") o.refine = true;
        else if (name == "--adapt") { o.adapt = true; o.refine = true; }
        else if (name == "--quality") o.quality = true;
        else if (name == "--regional-area") { o.area = true; o.area_from_regions = true; }
        else if (name == "--user-area") { o.user_area = true; o.unavailable.push_back("--user-area (-u: user size function: the C++ API's RefineOptions::max_area_at)"); }
        else if (name == "--conforming-delaunay") o.conforming_delaunay = true;
        else if (name == "--voronoi") o.voronoi = true;
        else if (name == "--off") o.geomview = true;
        else if (name == "--second-order") o.order = 2;
        else if (name == "--no-boundary-steiner") ++o.no_boundary_steiner;
        else if (name == "--incremental" || name == "--sweepline" || name == "--vertical-cuts" ||
                 name == "--no-exact" || name == "--split-segments") {
          const char c = name == "--incremental" ? 'i' : name == "--sweepline" ? 'F' : name == "--vertical-cuts" ? 'l'
                       : name == "--no-exact" ? 'X' : 's';
          if (std::find(o.compat_notes.begin(), o.compat_notes.end(), c) == o.compat_notes.end()) o.compat_notes.push_back(c);
        }
        else throw UsageError{"unknown option " + name + " (see deltamesh --help)"};
      }
    } else if (a.size() > 1 && a[0] == '-') {
      SwitchString(std::string_view(a).substr(1), o).parse();
    } else {
      if (!o.input.empty()) throw UsageError{"more than one input file: '" + o.input + "' and '" + a + "'"};
      o.input = a;
    }
  }
  if (o.smooth > 0 && o.conforming_delaunay)
    throw UsageError{"--smooth cannot be combined with -D: moved vertices may encroach segments"};
  return o;
}

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
                   triangles), offcenter (quickest) or circumcenter (the
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

RefineOptions refine_options(const Options& o) {
  RefineOptions r;
  r.min_angle_deg = o.quality ? o.min_angle.value_or(20.0) : 0.0;
  r.max_area = o.max_area.value_or(-1.0);
  r.use_triangle_area_bounds = o.area_from_regions;
  r.steiner = o.steiner;
  r.encroachment = o.encroachment;
  r.order = o.refine_order;
  r.segment_splitting = o.no_boundary_steiner == 0   ? SegmentSplitting::All
                        : o.no_boundary_steiner == 1 ? SegmentSplitting::InteriorOnly
                                                     : SegmentSplitting::None;
  r.conforming_delaunay = o.conforming_delaunay;
  if (o.steiner_budget) r.max_steiner = static_cast<std::size_t>(*o.steiner_budget);
  r.time_limit_seconds = o.time_limit;
  return r;
}

}  // namespace deltamesh::cli

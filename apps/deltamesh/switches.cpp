#include "deltamesh/switches.hpp"

#include <cctype>
#include <string_view>

namespace deltamesh::cli {

namespace {

// Triangle switches that exist but are not built yet, with what they do.
std::string_view planned_switch(char c) {
  switch (c) {
    case 'r': return "refine a previously generated mesh";
    case 'q': return "quality mesh generation (minimum angle)";
    case 'a': return "maximum triangle area constraints";
    case 'u': return "user-defined area constraint";
    case 'A': return "regional attributes";
    case 'c': return "enclose the convex hull with segments";
    case 'D': return "conforming Delaunay";
    case 'v': return "Voronoi diagram output";
    case 'g': return "OFF (Geomview) output";
    case 'P': return "no .poly output";
    case 'O': return "ignore holes";
    case 'X': return "no exact arithmetic";
    case 'o': return "second-order (six-node) triangles";
    case 'Y': return "no Steiner points on the boundary";
    case 'S': return "Steiner point budget";
    case 'i': return "incremental algorithm selection";
    case 'F': return "Fortune's sweepline selection";
    case 'l': return "vertical cuts only";
    case 's': return "segment splitting";
    default: return {};
  }
}

void parse_switch_string(std::string_view s, Options& o) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    switch (c) {
      case 'p': o.poly = true; break;
      case 'z': o.zero_based = true; break;
      case 'Q': o.quiet = true; break;
      case 'V': ++o.verbose; break;
      case 'C': o.check = true; break;
      case 'N': o.no_node = true; break;
      case 'E': o.no_ele = true; break;
      case 'I': o.no_iteration = true; break;
      case 'j': o.jettison = true; break;
      case 'e': o.edges = true; break;
      case 'n': o.neighbors = true; break;
      case 'B': o.no_markers = true; break;
      case 'h': o.help = true; break;
      default: {
        const std::string_view planned = planned_switch(c);
        if (!planned.empty())
          throw UsageError{std::string("switch -") + c + " (" + std::string(planned) +
                           ") is not available in this version of deltamesh"};
        throw UsageError{std::string("unknown switch -") + c + " in '-" + std::string(s) +
                         "' (see deltamesh --help)"};
      }
    }
  }
}

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
    if (a.rfind("--", 0) == 0) {
      const std::string name = a.substr(0, a.find('='));
      if (name == "--help") o.help = true;
      else if (name == "--version") o.version = true;
      else if (name == "--svg") o.svg_path = value(name);
      else if (name == "--quiet") o.quiet = true;
      else if (name == "--verbose") ++o.verbose;
      else if (name == "--check") o.check = true;
      else if (name == "--zero-based") o.zero_based = true;
      else if (name == "--jettison") o.jettison = true;
      else if (name == "--edges") o.edges = true;
      else if (name == "--neighbors") o.neighbors = true;
      else if (name == "--no-node") o.no_node = true;
      else if (name == "--no-ele") o.no_ele = true;
      else if (name == "--no-iteration") o.no_iteration = true;
      else if (name == "--no-markers") o.no_markers = true;
      else throw UsageError{"unknown option " + name + " (see deltamesh --help)"};
    } else if (a.size() > 1 && a[0] == '-') {
      parse_switch_string(std::string_view(a).substr(1), o);
    } else {
      if (!o.input.empty()) throw UsageError{"more than one input file: '" + o.input + "' and '" + a + "'"};
      o.input = a;
    }
  }
  return o;
}

std::string help_text() {
  return R"(deltamesh - two-dimensional Delaunay triangulation and mesh generation

Usage: deltamesh [-switches] [--long-options] FILE[.node]

Reads FILE.node and writes FILE.1.node and FILE.1.ele (Triangle's formats and
naming: an input FILE.1.node gives FILE.2.*).

Switches (Triangle's, combinable as one string, e.g. -zQVC):
  -z  number vertices and triangles from zero          --zero-based
  -e  also write FILE.1.edge (edges with boundary markers) --edges
  -n  also write FILE.1.neigh (triangle neighbours)     --neighbors
  -N  do not write the .node file                      --no-node
  -E  do not write the .ele file                       --no-ele
  -I  no iteration number: write FILE.node, FILE.ele    --no-iteration
  -j  drop duplicate and unused vertices from the output --jettison
  -B  no boundary markers in the output                --no-markers
  -C  check the mesh (topology, orientation, Delaunay)  --check
  -Q  quiet: print nothing unless there is an error     --quiet
  -V  verbose: statistics and timings per phase        --verbose
  -h  this help                                        --help
Long options:
  --svg PATH    write an SVG picture of the mesh
  --version     print the version

Examples:
  deltamesh points.node                 Delaunay triangulation -> points.1.node, points.1.ele
  deltamesh -zenV points.node           zero-based, with .edge and .neigh, verbose
  deltamesh -QC --svg mesh.svg pts.node quiet, self-check, and a picture

Exit codes:
  0 success, 1 usage error, 2 input error (file missing or malformed, or no
  triangle possible), 3 budget reached before the requested quality,
  4 output file could not be written, 5 -C found the mesh invalid,
  70 internal error (a bug; please report it).
)";
}

}  // namespace deltamesh::cli

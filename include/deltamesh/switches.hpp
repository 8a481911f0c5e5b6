// Triangle's switch string (-pq30a0.1) and deltamesh's long options, parsed
// into a Plan (pipeline.hpp) plus what only a command line needs: the input
// file, which output files and formats, messages. The command line and the
// Python bindings use this one parser, so a switch means the same in both.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/formats.hpp"
#include "deltamesh/pipeline.hpp"

namespace deltamesh {

// The command line's documented exit codes (docs/cli.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,        // bad switches or arguments, or a switch not available yet
  kExitInput = 2,        // input file missing, unreadable or malformed; input not meshable
  kExitBudget = 3,       // bounds not met: a budget stopped refinement, or triangles are left too large or below the angle bound outside small input angles
  kExitOutput = 4,       // an output file could not be written
  kExitCheckFailed = 5,  // -C found the mesh invalid
  kExitInternal = 70,    // a bug: please report it
};

// A switch or option that cannot be parsed; the message names it.
class UsageError : public Error {
 public:
  using Error::Error;
};

struct CommandLine {
  Plan plan;

  std::string input;  // the FILE argument as given
  // Output files.
  bool no_poly = false;       // -P
  bool no_node = false;       // -N
  bool no_ele = false;        // -E
  bool no_iteration = false;  // -I
  bool overwrite = false;     // --overwrite: an output may replace an input file
  bool voronoi = false;       // -v  FILE.1.v.node, FILE.1.v.edge
  bool geomview = false;      // -g  FILE.1.off
  std::optional<std::string> svg_path;  // --svg PATH
  std::optional<std::string> trace_path;  // --trace PATH: every step as JSON Lines (docs/trace.md)
  std::vector<std::string> outputs;     // --output PATH (format from the extension); when given, only these
                                        // (and -e -n -v -g files) are written, not FILE.1.node/.ele/.poly
  bool msh_v22 = false;                 // --msh-version=2.2 (default 4.1)
  bool msh_version_given = false;       // --msh-version (either value)
  bool vtu_binary = false;              // --vtu-binary
  bool geojson_segments = false;        // --geojson-segments
  bool voronoi_overlay = false;         // --voronoi-overlay (bounded Voronoi cells in .svg/.geojson)
  // --stats, --stats=json: the quality report as JSON alone on stdout (the
  // summary lines go to stderr); --stats=json:FILE: to FILE instead.
  bool stats_json = false;
  std::string stats_path;
  // GeoJSON input.
  std::string region_property;  // --region-property NAME
  std::string area_property;    // --area-property NAME
  // Messages.
  bool help = false;     // -h / --help
  bool version = false;  // --version
  // Triangle's algorithm choices accepted for compatibility (-i -F -l -X
  // -s), explained with -V.
  std::vector<char> compat_notes;
  // Switches parsed but not available (-u): each given one named, e.g.
  // "-u (user size function: ...)"; the command line refuses to run.
  std::vector<std::string> unavailable;

  // The switches as written, before a front end changes the plan (GeoJSON
  // input is meshed like -p): -p, -r, --adapt (which implies -r).
  bool poly = false;
  bool refine = false;
  bool adapt = false;
};

// Parses argv (switch strings, long options, one FILE). Throws UsageError
// with a message naming the offending switch.
CommandLine parse_arguments(const std::vector<std::string>& args);

// Sets what one long option that takes a value (--cdt, --min-angle, ...;
// `name` with its dashes) says, with the command line's checks and messages.
void apply_long_option(CommandLine& cl, std::string_view name, std::string_view value);

// "unknown option --cdtt (did you mean --cdt?)": the message for a long
// option that is not among `known` (the nearest within a third of its
// length suggested). The command line passes every option it knows.
std::string unknown_option_message(std::string_view name, const std::vector<std::string_view>& known);
// The command line's long options, with and without a value.
std::vector<std::string_view> long_option_names();

// (parse_cdt_method, parse_steiner_rule, parse_encroachment_rule: cdt.hpp, refine.hpp)
std::optional<FillRule> parse_fill_rule(std::string_view name);    // "holes", "evenodd" ("even-odd")
std::optional<RefineOrder> parse_refine_order(std::string_view name);  // "shortest", "worst"

// Options and switches that change nothing in this run, one message each
// ("--vtu-binary has no effect: no .vtu output (--output FILE.vtu)"); the
// command line prints them once as warnings. `geojson_input`: FILE is
// GeoJSON; `geojson` its reader's counts (the property checks), or null
// before reading. Settings of the Plan alone are run()'s (unused_settings).
std::vector<std::string> unused_options(const CommandLine& cl, bool geojson_input, const GeoJsonInfo* geojson);

// The command line's --help.
std::string help_text();

}  // namespace deltamesh

// Command-line options: Triangle's switch string (-pq30a0.1) and long options.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace deltamesh::cli {

// Documented exit codes.
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,        // bad switches or arguments
  kExitInput = 2,        // input file missing, unreadable or malformed; input not meshable
  kExitBudget = 3,       // a budget stopped refinement before the requested quality
  kExitOutput = 4,       // an output file could not be written
  kExitCheckFailed = 5,  // -C found the mesh invalid
  kExitInternal = 70,    // a bug: please report it
};

struct Options {
  // Triangle switches.
  bool poly = false;          // -p
  bool zero_based = false;    // -z
  bool quiet = false;         // -Q
  int verbose = 0;            // -V (repeatable)
  bool check = false;         // -C
  bool no_node = false;       // -N
  bool no_ele = false;        // -E
  bool no_iteration = false;  // -I
  bool jettison = false;      // -j
  bool edges = false;         // -e
  bool neighbors = false;     // -n
  bool no_markers = false;    // -B
  bool help = false;          // -h / --help
  // Long options.
  bool version = false;
  std::optional<std::string> svg_path;
  std::string input;  // the FILE argument as given
};

// Parses argv. Throws UsageError with a message naming the offending switch.
Options parse_arguments(const std::vector<std::string>& args);

struct UsageError {
  std::string message;
};

std::string help_text();

}  // namespace deltamesh::cli

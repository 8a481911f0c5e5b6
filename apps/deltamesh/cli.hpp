// The command line's parts: reading FILE.* into the pipeline's input,
// writing the result, reporting it. main.cpp puts them in order.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "deltamesh/deltamesh.hpp"

namespace deltamesh::cli {

using Clock = std::chrono::steady_clock;

// FILE.node -> FILE; FILE.3.node -> FILE with iteration 3.
struct InputName {
  std::string base;
  int iteration = 0;
  std::string with_iteration() const { return base + (iteration ? "." + std::to_string(iteration) : ""); }
};
InputName split_input_name(std::string path);

// An input named FILE.geojson or FILE.json is read as GeoJSON.
bool is_geojson_input(const std::string& path);

// An input that is not there is reported before anything is read.
class MissingInput {
 public:
  explicit MissingInput(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// One run of the command line: what was asked, read and written.
struct Session {
  explicit Session(const CommandLine& c);

  const CommandLine& cl;
  Plan plan;              // the command line's; GeoJSON input is meshed as -p, even-odd
  bool geojson = false;   // the input is GeoJSON
  InputName name;
  std::string input_path;  // the file being read, named by input errors
  std::string ele_path;  // -r: the .ele read, named when its triangles overlap
  std::vector<std::string> inputs_read;  // every file read: outputs may not replace them
  void reading(const std::string& path) {
    input_path = path;
    inputs_read.push_back(path);
  }
  bool writing = false;    // an IoError from here on is an output error
  int first_index = 0;     // the input's numbering, kept in the output (unless -z)
  std::vector<Point> holes;          // the input's, written into the output .poly
  std::vector<RegionSeed> regions;
  GeoJsonInfo geojson_info;
  std::vector<PhaseTime> phases;  // -V timings: reading, the pipeline's, writing
  TerminalProgress progress{stderr};
};

// Reads the input files for the plan (FILE.node / .poly / .geojson, or with
// -r FILE.node + .ele (+ .poly, .area, .mtr)). Prints the 6-node warning of -r.
RunInput read_input(Session& s);

// The 1-based line of segment `index` in a .poly file (0 when not found).
std::size_t poly_segment_line(const std::string& path, std::size_t index);
// Where vertex `index` (0-based in the input) is written: "FILE.node:LINE"
// (or the .poly that lists it), for messages about one vertex.
std::string vertex_place(const Session& s, std::size_t index);
// The 1-based line of triangle `index` (0-based) in a .ele file (0 when not found).
std::size_t ele_triangle_line(const std::string& path, std::size_t index);

// Writes FILE.1.* and the --output / --svg files (-o2 nodes included);
// returns the paths written.
std::vector<std::string> write_outputs(Session& s, const RunResult& r);

// -C's summary when it passed ("..., N segments present" with -p).
std::string check_summary(const Session& s, const RunResult& r);

// The quality report for --stats=json and -V.
QualityReport quality(const Session& s, const RunResult& r);

// What -Q silences: the summary lines, -V's statistics and timings, on
// `out` (stderr when stdout carries --stats=json).
void report(const Session& s, const RunResult& r, const std::vector<std::string>& written, std::FILE* out);

// --stats=json: the quality report alone on stdout, or in --stats=json:FILE
// (an IoError when it cannot be written).
void write_stats(const Session& s, const RunResult& r);

}  // namespace deltamesh::cli

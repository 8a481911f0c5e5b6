// deltamesh command line: Triangle's conventions for inputs, outputs and
// switches. parse -> read -> run (the library's pipeline) -> write -> report.
#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "cli.hpp"

namespace dm = deltamesh;
using namespace deltamesh::cli;

namespace {

void add_phase(Session& s, const char* name, Clock::time_point t0) {
  s.phases.push_back({name, std::chrono::duration<double>(Clock::now() - t0).count()});
}

// Runs the pipeline; a -r -p segment error names the .poly (and its line).
dm::RunResult run_pipeline(Session& s, dm::RunInput input) {
  const std::string poly_path = s.name.with_iteration() + ".poly";
  try {
    return dm::run(s.plan, std::move(input));
  } catch (const dm::SegmentError& e) {
    if (s.plan.mesh_input()) {
      const std::size_t line = poly_segment_line(poly_path, e.segment());
      s.input_path = poly_path + (line ? ":" + std::to_string(line) : "");
    }
    throw;
  } catch (const dm::IntersectingSegments&) {
    if (s.plan.mesh_input()) s.input_path = poly_path;
    throw;
  }
}

int execute(Session& s) {
  const auto t_total = Clock::now();
  dm::RunInput input = read_input(s);
  if (!s.plan.quiet)
    for (const std::string& w : dm::unused_options(s.cl, s.geojson, s.geojson ? &s.geojson_info : nullptr))
      std::fprintf(stderr, "deltamesh: warning: %s\n", w.c_str());
  std::unique_ptr<dm::TraceFile> trace;  // --trace: opened before the run, committed with the outputs
  if (s.cl.trace_path) {
    s.writing = true;  // a trace file that cannot be created is an output error
    trace = std::make_unique<dm::TraceFile>(*s.cl.trace_path);
    s.writing = false;
    s.plan.trace = &trace->observer();
  }
  dm::RunResult r = run_pipeline(s, std::move(input));
  s.progress.clear();
  s.phases.insert(s.phases.end(), r.phases.begin(), r.phases.end());
  if (!s.plan.quiet)
    for (const std::string& w : r.warnings()) std::fprintf(stderr, "deltamesh: warning: %s\n", w.c_str());

  int status = dm::kExitOk;
  if (!r.complete()) status = dm::kExitBudget;
  if (r.check && !r.check->ok()) {
    std::fprintf(stderr, "deltamesh: -C: %s\n", r.check->summary().c_str());
    status = dm::kExitCheckFailed;
  }

  const auto t = Clock::now();
  s.writing = true;
  std::vector<std::string> written = write_outputs(s, r);
  if (trace) {
    trace->commit();
    written.push_back(*s.cl.trace_path);
  }
  add_phase(s, "write", t);
  add_phase(s, "total", t_total);

  std::vector<std::string> reported = written;
  if (s.cl.stats_json && !s.cl.stats_path.empty()) {
    write_stats(s, r);
    reported.push_back(s.cl.stats_path);
  }
  // stdout carries the JSON alone when it goes there.
  const bool json_on_stdout = s.cl.stats_json && s.cl.stats_path.empty();
  if (!s.plan.quiet) report(s, r, reported, json_on_stdout ? stderr : stdout);
  if (json_on_stdout) write_stats(s, r);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  dm::CommandLine cl;
  try {
    cl = dm::parse_arguments(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const dm::UsageError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return dm::kExitUsage;
  }
  if (cl.help) {
    std::fputs(dm::help_text().c_str(), stdout);
    return dm::kExitOk;
  }
  if (cl.version) {
    std::printf("deltamesh %s\n", dm::kVersion);
    return dm::kExitOk;
  }
  if (!cl.unavailable.empty()) {
    for (const std::string& s : cl.unavailable)
      std::fprintf(stderr, "deltamesh: switch %s is not available in this version of deltamesh\n", s.c_str());
    return dm::kExitUsage;
  }
  if (cl.refine && is_geojson_input(cl.input)) {
    std::fprintf(stderr, "deltamesh: -r reads a Triangle mesh (FILE.node, FILE.ele), not GeoJSON\n");
    return dm::kExitUsage;
  }
  if (cl.input.empty()) {
    std::fprintf(stderr, "deltamesh: no input file (usage: deltamesh [-switches] FILE; see --help)\n");
    return dm::kExitUsage;
  }
  Session s(cl);
  try {
    return execute(s);
  } catch (const MissingInput& e) {
    std::fprintf(stderr, "deltamesh: cannot open input file '%s': no such file\n", e.path().c_str());
    return dm::kExitInput;
  } catch (const dm::ParseError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return dm::kExitInput;
  } catch (const dm::IntersectingSegments& e) {
    std::fprintf(stderr,
                 "deltamesh: %s: segments %zu and %zu cross (--strict; without it they are split where they cross)\n",
                 s.input_path.c_str(), e.first() + static_cast<std::size_t>(s.first_index),
                 e.second() + static_cast<std::size_t>(s.first_index));
    return dm::kExitInput;
  } catch (const dm::SegmentError& e) {
    const std::size_t base = static_cast<std::size_t>(s.first_index);
    std::fprintf(stderr, "deltamesh: %s: segment %zu (vertices %zu-%zu) %s\n", s.input_path.c_str(),
                 e.segment() + base, e.a() + base, e.b() + base, e.problem().c_str());
    return dm::kExitInput;
  } catch (const dm::OverlappingTriangles& e) {
    // Ids and lines as in the user's .ele file.
    const std::size_t base = static_cast<std::size_t>(s.first_index);
    const std::string& ele = s.ele_path.empty() ? s.input_path : s.ele_path;
    std::fprintf(stderr, "deltamesh: %s:%zu: triangles %zu and %zu (line %zu) %s; the mesh is refused\n", ele.c_str(),
                 ele_triangle_line(ele, e.first()), e.first() + base, e.second() + base,
                 ele_triangle_line(ele, e.second()), e.how().c_str());
    return dm::kExitInput;
  } catch (const dm::VertexError& e) {
    // As numbered in the user's file, with its line (GeoJSON has no numbers).
    if (s.geojson) {
      std::fprintf(stderr, "deltamesh: %s: %s\n", cl.input.c_str(), e.what());
    } else {
      std::fprintf(stderr, "deltamesh: %s: vertex %zu: %s\n", vertex_place(s, e.index()).c_str(),
                   e.index() + static_cast<std::size_t>(s.first_index), e.problem().c_str());
    }
    return dm::kExitInput;
  } catch (const dm::InputError& e) {
    std::fprintf(stderr, "deltamesh: %s: %s\n", s.input_path.empty() ? cl.input.c_str() : s.input_path.c_str(),
                 e.what());
    return dm::kExitInput;
  } catch (const dm::IoError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return s.writing ? dm::kExitOutput : dm::kExitInput;
  } catch (const dm::InternalError& e) {
    std::fprintf(stderr, "deltamesh: internal error: %s (please report this)\n", e.what());
    return dm::kExitInternal;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "deltamesh: out of memory\n");
    return dm::kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deltamesh: internal error: %s (please report this)\n", e.what());
    return dm::kExitInternal;
  }
}

// deltamesh command line: Triangle's conventions for inputs, outputs and switches.
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "deltamesh/deltamesh.hpp"
#include "deltamesh/switches.hpp"

namespace dm = deltamesh;
using namespace deltamesh::cli;

namespace {

using Clock = std::chrono::steady_clock;

struct Phase {
  const char* name;
  double seconds;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// FILE.node -> FILE; FILE.3.node -> FILE with iteration 3.
struct InputName {
  std::string base;
  int iteration = 0;
};

InputName split_input_name(std::string path) {
  for (const char* ext : {".node", ".poly", ".ele"})
    if (ends_with(path, ext)) {
      path.resize(path.size() - std::string(ext).size());
      break;
    }
  InputName name{path, 0};
  const auto dot = path.rfind('.');
  if (dot != std::string::npos && dot + 1 < path.size() && path.find('/', dot) == std::string::npos) {
    const std::string digits = path.substr(dot + 1);
    if (digits.find_first_not_of("0123456789") == std::string::npos && digits.size() < 9) {
      name.base = path.substr(0, dot);
      name.iteration = std::stoi(digits);
    }
  }
  return name;
}

class Run {
 public:
  explicit Run(const Options& o) : opt_(o) {}

  int execute() {
    const InputName name = split_input_name(opt_.input);
    const std::string in_path = name.base + (name.iteration ? "." + std::to_string(name.iteration) : "") +
                                (opt_.poly ? ".poly" : ".node");
    if (!std::filesystem::exists(in_path)) {
      std::fprintf(stderr, "deltamesh: cannot open input file '%s': no such file\n", in_path.c_str());
      return kExitInput;
    }
    if (opt_.poly) {
      std::fprintf(stderr, "deltamesh: -p (segments, holes and regions from a .poly file) is not available in this version\n");
      return kExitUsage;
    }
    auto t = Clock::now();
    dm::Pslg input = dm::read_node(in_path);
    phase("read", t);

    t = Clock::now();
    dm::DelaunayStats stats;
    dm::Mesh mesh = dm::delaunay(input.points, {}, &stats);
    phases_.push_back({"sort", stats.sort_seconds});
    phases_.push_back({"insert", stats.insert_seconds});
    phase("triangulate (total)", t);
    mesh.vertex_markers() = std::move(input.point_markers);
    mesh.set_num_vertex_attributes(input.num_point_attributes);
    mesh.vertex_attributes() = std::move(input.point_attributes);

    if (opt_.jettison) mesh.remove_unused_vertices();

    int status = kExitOk;
    if (opt_.check) {
      t = Clock::now();
      const dm::CheckReport report = dm::check(mesh);
      phase("check", t);
      if (!report.ok()) {
        std::fprintf(stderr, "deltamesh: -C: %s\n", report.summary().c_str());
        status = kExitCheckFailed;
      } else if (!opt_.quiet) {
        std::printf("Check: %s\n", report.summary().c_str());
      }
    }

    t = Clock::now();
    const std::string out_base =
        name.base + (opt_.no_iteration ? "" : "." + std::to_string(name.iteration + 1));
    dm::TriangleWriteOptions wopt;
    wopt.first_index = opt_.zero_based ? 0 : input.first_index;
    wopt.write_markers = !opt_.no_markers;
    std::vector<std::string> written;
    auto emit = [&](bool enabled, const char* ext, auto writer) {
      if (!enabled) return;
      const std::string path = out_base + ext;
      writer(mesh, path, wopt);
      written.push_back(path);
    };
    emit(!opt_.no_node, ".node", [](auto& m, auto& p, auto& w) { dm::write_node(m, p, w); });
    emit(!opt_.no_ele, ".ele", [](auto& m, auto& p, auto& w) { dm::write_ele(m, p, w); });
    emit(opt_.edges, ".edge", [](auto& m, auto& p, auto& w) { dm::write_edge(m, p, w); });
    emit(opt_.neighbors, ".neigh", [](auto& m, auto& p, auto& w) { dm::write_neigh(m, p, w); });
    if (opt_.svg_path) {
      dm::SvgOptions sopt;
      sopt.title = opt_.input;
      dm::write_svg(mesh, *opt_.svg_path, sopt);
      written.push_back(*opt_.svg_path);
    }
    phase("write", t);

    if (!opt_.quiet) report(input.points.size(), stats, mesh, written);
    return status;
  }

 private:
  void phase(const char* name, Clock::time_point t0) {
    phases_.push_back({name, std::chrono::duration<double>(Clock::now() - t0).count()});
  }

  void report(std::size_t input_points, const dm::DelaunayStats& stats, const dm::Mesh& mesh,
              const std::vector<std::string>& written) const {
    std::size_t hull = 0;
    for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
      if (mesh.twin(e) == dm::kNone) ++hull;
    std::printf("Delaunay triangulation: %zu input vertices", input_points);
    if (stats.duplicates) std::printf(" (%zu duplicates merged)", stats.duplicates);
    std::printf(", %zu triangles, %zu hull edges\n", mesh.num_triangles(), hull);
    for (const std::string& w : written) std::printf("  wrote %s\n", w.c_str());
    if (opt_.verbose > 0) {
      std::printf("Statistics:\n");
      std::printf("  vertices in output: %zu\n", mesh.num_vertices());
      std::printf("  edges: %zu\n", (3 * mesh.num_triangles() + hull) / 2);
      std::printf("  mesh memory: %.1f MB (%.1f bytes per triangle)\n", mesh.memory_bytes() / 1e6,
                  mesh.num_triangles() ? double(mesh.memory_bytes()) / double(mesh.num_triangles()) : 0.0);
      std::printf("Timings:\n");
      for (const Phase& p : phases_) std::printf("  %-22s %9.3f ms\n", p.name, p.seconds * 1e3);
    }
  }

  const Options& opt_;
  std::vector<Phase> phases_;
};

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parse_arguments(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.message.c_str());
    return kExitUsage;
  }
  if (opt.help) {
    std::fputs(help_text().c_str(), stdout);
    return kExitOk;
  }
  if (opt.version) {
    std::printf("deltamesh %s\n", dm::kVersion);
    return kExitOk;
  }
  if (opt.input.empty()) {
    std::fprintf(stderr, "deltamesh: no input file (usage: deltamesh [-switches] FILE.node; see --help)\n");
    return kExitUsage;
  }
  try {
    return Run(opt).execute();
  } catch (const dm::ParseError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return kExitInput;
  } catch (const dm::InputError& e) {
    std::fprintf(stderr, "deltamesh: %s: %s\n", opt.input.c_str(), e.what());
    return kExitInput;
  } catch (const dm::IoError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return kExitOutput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "deltamesh: out of memory\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deltamesh: internal error: %s (please report this)\n", e.what());
    return kExitInternal;
  }
}

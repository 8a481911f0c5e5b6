// deltamesh command line: Triangle's conventions for inputs, outputs and switches.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/deltamesh.hpp"
#include "deltamesh/formats.hpp"
#include "deltamesh/insert_segments.hpp"
#include "deltamesh/quality.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/switches.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/voronoi.hpp"

namespace dm = deltamesh;
using namespace deltamesh::cli;

namespace {

using Clock = std::chrono::steady_clock;

struct Phase {
  std::string name;
  double seconds;
};

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// An input named FILE.geojson or FILE.json is read as GeoJSON.
bool is_geojson_input(const std::string& path) { return ends_with(path, ".geojson") || ends_with(path, ".json"); }

// FILE.node -> FILE; FILE.3.node -> FILE with iteration 3.
struct InputName {
  std::string base;
  int iteration = 0;
  std::string with_iteration() const { return base + (iteration ? "." + std::to_string(iteration) : ""); }
};

InputName split_input_name(std::string path) {
  for (const char* ext : {".node", ".poly", ".ele", ".area", ".geojson", ".json"})
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

// An input that is not there is reported before anything is read.
class MissingInput {
 public:
  explicit MissingInput(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void require_file(const std::string& path) {
  if (!std::filesystem::exists(path)) throw MissingInput(path);
}

class Run {
 public:
  explicit Run(const Options& o) : opt_(o), geojson_(is_geojson_input(o.input)), poly_(o.poly || geojson_) {}

  int execute() {
    const InputName name = split_input_name(opt_.input);
    const std::string in = name.with_iteration();
    const auto t_total = Clock::now();

    dm::Mesh mesh;
    dm::TriangulateStats stats;
    if (opt_.refine) {
      mesh = read_mesh(in, stats);
      read_vertices_ = mesh.num_vertices();
      read_triangles_ = mesh.num_triangles();
      if (!opt_.quiet)
        for (const std::string& w : stats.warnings) std::fprintf(stderr, "deltamesh: warning: %s\n", w.c_str());
      if (opt_.adapt) {
        // Sizes at the vertices of the mesh as read (vertices added by -p's
        // segment insertion take the mean of their neighbours'), then the
        // CDT flips refinement needs, coarsening and refinement to them.
        auto t = Clock::now();
        const dm::SizeField h = dm::size_field_from_vertices(mesh, vertex_sizes(mesh));
        delaunay_flips_ = dm::make_constrained_delaunay(mesh);
        dm::AdaptOptions aopt;
        aopt.refine = refine_options();
        aopt.refine.progress = progress_callback();
        if (opt_.smooth >= 0) aopt.smooth_passes = opt_.smooth;
        adapt_stats_ = dm::adapt(mesh, h, aopt);
        progress_.clear();
        refine_stats_ = adapt_stats_.refine;
        dm::finish_vertex_markers(mesh);
        refined_ = adapted_ = true;
        phase("adapt (coarsen + refine)", t);
      } else if (refining()) {
        // Refinement needs a constrained Delaunay triangulation; a mesh from
        // another tool need not be one (on a CDT this flips nothing).
        auto t = Clock::now();
        delaunay_flips_ = dm::make_constrained_delaunay(mesh);
        phase("constrained Delaunay flips", t);
        t = Clock::now();
        dm::RefineOptions ropt = refine_options();
        ropt.progress = progress_callback();
        refine_stats_ = dm::refine(mesh, ropt);
        progress_.clear();
        dm::finish_vertex_markers(mesh);
        refined_ = true;
        phase("refine", t);
      } else if (opt_.smooth > 0) {
        // Smoothing keeps a constrained Delaunay triangulation: start from one.
        auto t = Clock::now();
        delaunay_flips_ = dm::make_constrained_delaunay(mesh);
        phase("constrained Delaunay flips", t);
      }
      if (!opt_.adapt) smooth_mesh(mesh, 0);
    } else {
      const std::string in_path = geojson_ ? opt_.input : in + (poly_ ? ".poly" : ".node");
      require_file(in_path);
      input_path_ = in_path;
      auto t = Clock::now();
      dm::Pslg input;
      if (geojson_) {
        dm::GeoJsonReadOptions gopt;
        gopt.attribute_property = opt_.region_property;
        gopt.area_property = opt_.area_property;
        input = dm::read_geojson(in_path, gopt, &geojson_info_);
      } else {
        input = poly_ ? dm::read_poly(in_path) : dm::read_node(in_path);
      }
      phase("read", t);
      first_index_ = input.first_index;
      holes_ = input.holes;
      regions_ = input.regions;

      dm::TriangulateOptions topt;
      topt.use_segments = poly_;
      topt.method = opt_.cdt_method;
      topt.strict = opt_.strict;
      topt.domain.fill = geojson_ ? dm::FillRule::EvenOdd : opt_.fill;
      topt.domain.keep_convex_hull = opt_.convex_hull;
      topt.domain.ignore_holes = opt_.ignore_holes;
      topt.domain.regional_attributes = (opt_.regional_attributes && poly_) || (geojson_ && !opt_.region_property.empty());
      topt.check_segments = opt_.check && poly_;
      topt.domain.regional_area_bounds = (opt_.area_from_regions && poly_) || (geojson_ && !opt_.area_property.empty());
      if (refining()) topt.refine = refine_options();
      topt.progress = progress_callback();
      mesh = dm::triangulate(input, topt, &stats);
      progress_.clear();
      if (topt.refine) {
        refine_stats_ = stats.refine;
        refined_ = true;
      }
      if (poly_) {
        phase(std::string("constrained triangulation (") + std::string(dm::to_string(opt_.cdt_method)) + ")",
              stats.triangulate_seconds, true);
        phases_.push_back({"  of which segments", stats.cdt.segments_seconds});
        if (topt.check_segments) phase("check segments", stats.check_seconds, true);
        phase("domain (holes, regions)", stats.domain_seconds, true);
      } else {
        phase("Delaunay triangulation", stats.triangulate_seconds, true);
        if (opt_.convex_hull) phase("hull segments", stats.domain_seconds, true);
      }
      if (refined_) phase("refine", stats.refine_seconds, true);
      phase("markers and attributes", stats.finish_seconds, true);
      smooth_mesh(mesh, input.points.size());  // the input's vertices stay
      if (!opt_.quiet)
        for (const std::string& w : stats.warnings) std::fprintf(stderr, "deltamesh: warning: %s\n", w.c_str());
    }

    if (opt_.jettison) mesh.remove_unused_vertices();

    int status = kExitOk;
    if (refined_ && !refine_stats_.complete) status = kExitBudget;
    if (opt_.check) {
      auto t = Clock::now();
      dm::CheckOptions copt;
      // A point set's Delaunay triangulation covers its convex hull; a
      // carved domain need not be convex; a mesh read with -r need not be
      // Delaunay.
      copt.convex_hull = !poly_ && !opt_.refine && !refined_;  // split hull edges bend by rounding
      // -r refines a CDT (flipped to one first); without refinement the
      // mesh is written as read, Delaunay or not.
      copt.delaunay = opt_.refine ? refined_ || smoothed_ : opt_.cdt_method != dm::CdtMethod::Ct || smoothed_;
      dm::CheckReport report = dm::check(mesh, copt);
      // With -r -p: every .poly segment was a chain of constrained edges
      // after insertion (checked before holes were carved).
      if (opt_.refine)
        for (const std::string& p : stats.segment_check.problems) report.problems.push_back("before carving: " + p);
      // With -p: every segment was a chain of constrained edges before
      // carving (checked in the pipeline), and carving left a boundary made
      // of segments only.
      if (poly_ && !opt_.refine) {
        for (const std::string& p : stats.segment_check.problems) report.problems.push_back("before carving: " + p);
        for (const std::string& p : dm::check_domain_boundary(mesh)) report.problems.push_back(p);
      }
      phase("check", t);
      if (!report.ok()) {
        std::fprintf(stderr, "deltamesh: -C: %s\n", report.summary().c_str());
        status = kExitCheckFailed;
      } else {
        check_summary_ = report.summary();
        if (stats.segment_check.segments_checked)
          check_summary_ += ", " + plural(stats.segment_check.segments_checked, "segment", "segments") + " present";
      }
    }

    auto t = Clock::now();
    writing_ = true;
    const std::string out_base = name.base + (opt_.no_iteration ? "" : "." + std::to_string(name.iteration + 1));
    dm::TriangleWriteOptions wopt;
    wopt.first_index = opt_.zero_based ? 0 : first_index_;
    wopt.write_markers = !opt_.no_markers;
    wopt.holes = holes_;      // the output .poly describes the same domain
    wopt.regions = regions_;
    // -o2: a node at the midpoint of every edge, appended to the vertices
    // (after -j and -C, which see the linear mesh).
    std::vector<dm::VertexId> midside;
    if (opt_.order == 2) {
      midside = dm::add_midpoint_nodes(mesh);
      wopt.midside = midside;
    }
    std::vector<std::string> written;
    auto emit = [&](bool enabled, const char* ext, auto writer) {
      if (!enabled) return;
      const std::string path = out_base + ext;
      writer(mesh, path, wopt);
      written.push_back(path);
    };
    // Triangle writes a .poly when it read one, and for a point set with -c.
    // With --output, only the named files (and those of -e -n -v -g) are written.
    const bool only_named = !opt_.outputs.empty();
    const bool write_poly = !only_named && !opt_.no_poly && (poly_ || opt_.convex_hull);
    emit(!only_named && !opt_.no_node, ".node", [](auto& m, auto& p, auto& w) { dm::write_node(m, p, w); });
    emit(!only_named && !opt_.no_ele, ".ele", [](auto& m, auto& p, auto& w) { dm::write_ele(m, p, w); });
    emit(write_poly, ".poly", [](auto& m, auto& p, auto& w) { dm::write_poly(m, p, w); });
    emit(opt_.edges, ".edge", [](auto& m, auto& p, auto& w) { dm::write_edge(m, p, w); });
    emit(opt_.neighbors, ".neigh", [](auto& m, auto& p, auto& w) { dm::write_neigh(m, p, w); });
    emit(opt_.geomview, ".off", [](auto& m, auto& p, auto&) { dm::write_off(m, p); });
    if (opt_.voronoi) {
      const dm::VoronoiDiagram vd = dm::voronoi_diagram(mesh);
      dm::write_voronoi_node(vd, out_base + ".v.node", wopt.first_index);
      written.push_back(out_base + ".v.node");
      dm::write_voronoi_edge(vd, out_base + ".v.edge", wopt.first_index);
      written.push_back(out_base + ".v.edge");
    }
    std::optional<dm::BoundedVoronoi> cells;
    if (opt_.voronoi_overlay && !opt_.outputs.empty()) cells = dm::bounded_voronoi(mesh);
    for (const std::string& path : opt_.outputs) {
      dm::OutputOptions oopt;
      oopt.first_index = wopt.first_index;
      oopt.write_markers = wopt.write_markers;
      oopt.svg.title = opt_.input;
      oopt.msh.version = opt_.msh_v22 ? dm::MshVersion::V22 : dm::MshVersion::V41;
      oopt.vtk.binary = opt_.vtu_binary;
      oopt.geojson.segments = opt_.geojson_segments;
      oopt.msh.second_order.midside = midside;
      oopt.vtk.second_order.midside = midside;
      if (cells) oopt.voronoi = &*cells;
      dm::write_output(mesh, path, oopt);
      written.push_back(path);
    }
    if (opt_.svg_path) {
      dm::SvgOptions sopt;
      sopt.title = opt_.input;
      dm::write_svg(mesh, *opt_.svg_path, sopt);
      written.push_back(*opt_.svg_path);
    }
    phase("write", t);
    phase("total", t_total);

    if (!opt_.quiet) report(stats, mesh, written);
    if (opt_.stats_json) std::printf("%s\n", quality(mesh).json().c_str());
    return status;
  }

  int first_index() const { return first_index_; }
  const std::string& input_path() const { return input_path_; }
  bool writing() const { return writing_; }

 private:
  // -r: FILE.node + FILE.ele (+ FILE.poly with -p: its segments inserted
  // where they are not edges yet, its holes carved), -ra: FILE.area.
  dm::Mesh read_mesh(const std::string& in, dm::TriangulateStats& stats) {
    const std::string node_path = in + ".node", ele_path = in + ".ele", poly_path = in + ".poly";
    const std::string area_path = in + ".area";
    require_file(node_path);
    require_file(ele_path);
    if (opt_.poly) require_file(poly_path);
    if (opt_.area_from_regions) require_file(area_path);
    input_path_ = node_path;
    auto t = Clock::now();
    dm::Pslg nodes = dm::read_node(node_path);
    first_index_ = nodes.first_index;
    if (opt_.poly) {
      input_path_ = poly_path;
      dm::Pslg poly = dm::read_poly(poly_path);
      if (poly.points.size() != nodes.points.size())
        throw dm::InputError(poly_path + " lists " + std::to_string(poly.points.size()) + " vertices but " +
                             node_path + " has " + std::to_string(nodes.points.size()));
      nodes.segments = std::move(poly.segments);
      holes_ = std::move(poly.holes);
      regions_ = std::move(poly.regions);
    }
    input_path_ = ele_path;
    dm::EleData ele = dm::read_ele(ele_path, nodes.first_index);
    if (opt_.adapt) {
      const std::string mtr_path = in + ".mtr";
      require_file(mtr_path);
      input_path_ = mtr_path;
      sizes_ = dm::read_mtr(mtr_path);
      if (sizes_.size() != nodes.points.size())
        throw dm::InputError("has " + std::to_string(sizes_.size()) + " sizes but " + node_path + " has " +
                             std::to_string(nodes.points.size()) + " nodes");
      if (!ele.midside.empty())
        throw dm::InputError("--adapt needs a 3-node mesh; " + ele_path + " has 6-node triangles");
    }
    // -ra: per-triangle bounds (one per triangle of FILE.ele, <= 0: none),
    // set before segments are inserted so they stay with their triangles.
    std::vector<double> bounds;
    if (opt_.area_from_regions) {
      input_path_ = area_path;
      bounds = dm::read_area(area_path);
      if (bounds.size() != ele.triangles.size() / 3)
        throw dm::InputError("has " + std::to_string(bounds.size()) + " bounds for " +
                             std::to_string(ele.triangles.size() / 3) + " triangles");
    }
    phase("read", t);
    if (!ele.midside.empty()) {
      // A 6-node (-o2) mesh: refined as the corner mesh; its midpoint nodes
      // would be vertices in no triangle, so they go (-o2 writes new ones).
      const std::size_t dropped = dm::drop_midpoint_nodes(nodes, ele.triangles, ele.midside);
      if (!opt_.quiet)
        std::fprintf(stderr,
                     "deltamesh: warning: %s has 6-node triangles; %zu midpoint nodes dropped, the other "
                     "vertices renumbered in order%s\n",
                     ele_path.c_str(), dropped, opt_.order == 2 ? " (-o2 writes new ones)" : " (add -o2 for new ones)");
    }
    input_path_ = node_path;
    t = Clock::now();
    dm::RebuildOptions ropt;
    ropt.area_bounds = bounds;
    ropt.method = opt_.cdt_method;
    ropt.strict = opt_.strict;
    dm::Mesh mesh;
    try {
      mesh = dm::mesh_from_triangles(nodes, ele.triangles, ele.num_attributes, ele.attributes, ropt, &inserted_);
    } catch (const dm::SegmentError& e) {
      const std::size_t line = poly_segment_line(poly_path, e.segment());
      input_path_ = poly_path + (line ? ":" + std::to_string(line) : "");
      throw;
    } catch (const dm::IntersectingSegments&) {
      input_path_ = poly_path;
      throw;
    }
    phase("rebuild mesh", t);
    if (opt_.poly) {
      if (inserted_.inserted) phase("  of which segment insertion", inserted_.seconds, true);
      if (opt_.check) {
        t = Clock::now();
        dm::CheckOptions co;
        co.delaunay = false;
        co.convex_hull = false;
        co.pslg = &nodes;
        stats.segment_check = dm::check(mesh, co);
        phase("check segments", t);
      }
      // Holes (in the mesh: carved; outside it, as in a .poly written with
      // the mesh: nothing to do) and, with -A, regional attributes. Area
      // bounds come from FILE.area with -r, as in Triangle.
      t = Clock::now();
      dm::DomainOptions dopt;
      dopt.ignore_holes = opt_.ignore_holes;
      dopt.regional_attributes = opt_.regional_attributes;
      dm::Pslg seeds;
      seeds.holes = holes_;
      seeds.regions = regions_;
      dm::carve_mesh(mesh, seeds, dopt, &stats.domain);
      if (stats.domain.triangles_removed) dm::finish_vertex_markers(mesh);
      phase("holes, regions", t);
      for (std::string& w : dm::domain_warnings(stats.domain, mesh.num_triangles(), true))
        stats.warnings.push_back(std::move(w));
    }
    if (opt_.convex_hull) {
      // With -r, -c makes the mesh boundary (holes included) into segments.
      for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
        if (mesh.twin(e) == dm::kNone && !mesh.is_constrained(e)) mesh.constrain_edge(e, 0);
    }
    return mesh;
  }

  // One size per mesh vertex: the .mtr's, and for vertices appended since
  // (segment crossings of -r -p) the mean of their neighbours' sizes.
  std::vector<double> vertex_sizes(const dm::Mesh& mesh) const {
    std::vector<double> sizes = sizes_;
    const std::size_t n = sizes.size();
    double mean = 0;
    for (double h : sizes_) mean += h / double(std::max<std::size_t>(n, 1));
    for (dm::VertexId v = static_cast<dm::VertexId>(n); v < mesh.num_vertices(); ++v) {
      double sum = 0;
      std::size_t k = 0;
      mesh.for_each_out_edge(v, [&](dm::HalfEdgeId e) {
        if (mesh.dest(e) < n) {
          sum += sizes_[mesh.dest(e)];
          ++k;
        }
        return true;
      });
      sizes.push_back(k ? sum / double(k) : mean);
    }
    return sizes;
  }

  // The 1-based line of segment `index` in a .poly file (0 when it cannot be
  // found): data lines are those with something before any '#'.
  static std::size_t poly_segment_line(const std::string& path, std::size_t index) {
    std::FILE* f = std::fopen(path.c_str(), "r");
    if (!f) return 0;
    std::size_t line = 0, data = 0, target = 0;
    long long vertices = -1;
    std::string text;
    for (int c = 0; c != EOF;) {
      text.clear();
      while ((c = std::fgetc(f)) != EOF && c != '\n') text.push_back(static_cast<char>(c));
      ++line;
      text = text.substr(0, text.find('#'));
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      if (data++ == 0) {
        vertices = std::atoll(text.c_str());
        target = static_cast<std::size_t>(std::max(0LL, vertices)) + 3 + index;  // header, vertices, segment header
      }
      if (data == target) {
        std::fclose(f);
        return line;
      }
    }
    std::fclose(f);
    return 0;
  }

  void phase(const std::string& name, Clock::time_point t0) {
    phases_.push_back({name, std::chrono::duration<double>(Clock::now() - t0).count()});
  }
  void phase(const std::string& name, double seconds, bool) { phases_.push_back({name, seconds}); }

  void report(const dm::TriangulateStats& st, const dm::Mesh& mesh, const std::vector<std::string>& written) const {
    std::size_t boundary = 0;
    for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
      if (mesh.twin(e) == dm::kNone) ++boundary;
    if (opt_.verbose > 0) {
      static const char* const notes[][2] = {
          {"i", "incremental insertion: deltamesh inserts incrementally in Hilbert order; the Delaunay triangulation is the same"},
          {"F", "Fortune's sweepline: deltamesh inserts incrementally in Hilbert order; the Delaunay triangulation is the same"},
          {"l", "vertical cuts only: deltamesh does not use divide-and-conquer; no effect"},
          {"X", "no exact arithmetic: deltamesh's predicates are always exact (adaptive); no effect"},
          {"s", "segments forced in by splitting: deltamesh recovers segments in a constrained triangulation; "
                "add -D for a conforming Delaunay mesh"},
      };
      for (char c : opt_.compat_notes)
        for (const auto& n : notes)
          if (n[0][0] == c) std::printf("Note: -%c: %s\n", c, n[1]);
      if (geojson_) {
        const dm::GeoJsonInfo& g = geojson_info_;
        std::printf("GeoJSON: %s, %s, %s (%s), %s skipped, %zu unclosed closed, %zu degenerate ignored, "
                    "%s merged, %s kept once, %s (%zu not placed)",
                    plural(g.features, "feature", "features").c_str(), plural(g.polygons, "polygon", "polygons").c_str(),
                    plural(g.rings, "ring", "rings").c_str(), plural(g.holes, "hole", "holes").c_str(),
                    plural(g.skipped_geometries, "other geometry", "other geometries").c_str(), g.unclosed_rings,
                    g.degenerate_rings, plural(g.duplicate_points, "duplicate point", "duplicate points").c_str(),
                    plural(g.duplicate_segments, "shared segment", "shared segments").c_str(),
                    plural(g.seeds, "region seed", "region seeds").c_str(), g.seeds_failed);
        if (!g.categories.empty()) {
          std::printf("; categories:");
          for (std::size_t i = 0; i < g.categories.size(); ++i) std::printf(" %zu=%s", i + 1, g.categories[i].c_str());
        }
        std::printf("\n");
      }
    }
    if (opt_.refine) {
      std::printf("Mesh read: %zu vertices, %zu triangles", read_vertices_, read_triangles_);
      if (opt_.poly) {
        std::printf("; %s (%zu already edges, %zu inserted, %s added)",
                    plural(inserted_.segments, "segment", "segments").c_str(), inserted_.already_present,
                    inserted_.inserted, plural(inserted_.vertices_added, "vertex", "vertices").c_str());
        if (st.domain.holes_used) std::printf(", %s carved", plural(st.domain.holes_used, "hole", "holes").c_str());
      }
      std::printf("\n");
    } else if (poly_) {
      std::printf("Constrained Delaunay triangulation: %s, %s", plural(st.input_vertices, "input vertex", "input vertices").c_str(),
                  plural(st.input_segments, "segment", "segments").c_str());
      if (st.input_holes) std::printf(", %s", plural(st.input_holes, "hole", "holes").c_str());
      std::printf(" -> %s\n", plural(mesh.num_triangles(), "triangle", "triangles").c_str());
    } else {
      std::printf("Delaunay triangulation: %zu input vertices", st.input_vertices);
      if (st.duplicate_vertices) std::printf(" (%zu duplicates merged)", st.duplicate_vertices);
      std::printf(", %zu triangles, %zu hull edges\n", mesh.num_triangles(), boundary);
    }
    if (adapted_) std::printf("Coarsened: %s\n", adapt_stats_.coarsen.summary().c_str());
    if (refined_) {
      std::printf("Quality mesh: %s\n", refine_stats_.summary().c_str());
      if (refine_stats_.budget_exhausted || refine_stats_.time_exhausted)
        std::fprintf(stderr, "deltamesh: warning: refinement stopped by its budget before reaching the requested quality\n");
      else if (!refine_stats_.complete)
        std::fprintf(stderr, "deltamesh: warning: refinement left %zu triangles above their size bound%s\n",
                     refine_stats_.too_large,
                     refine_stats_.too_large_precision == 0
                         ? ""
                         : (" (" + std::to_string(refine_stats_.too_large_precision) + " at the precision of doubles)")
                               .c_str());
    }
    if (adapted_) std::printf("Adapted: %s\n", adapt_stats_.summary().c_str());
    if (adapted_ && adapt_stats_.smooth.passes) std::printf("Smoothed: %s\n", adapt_stats_.smooth.summary().c_str());
    if (smoothed_) {
      std::printf("Smoothed: %s", smooth_stats_.summary().c_str());
      if (resplit_) std::printf(" (then %zu points to restore the refinement bounds)", resplit_);
      std::printf("\n");
    }
    for (const std::string& w : written) std::printf("  wrote %s\n", w.c_str());
    if (!check_summary_.empty()) std::printf("Check: %s\n", check_summary_.c_str());
    if (opt_.verbose > 0) {
      std::printf("Statistics:\n");
      if (!opt_.refine) {
        std::printf("  input vertices:            %zu\n", st.input_vertices);
        std::printf("  duplicate vertices merged: %zu\n", st.duplicate_vertices);
      }
      if (poly_ && !opt_.refine) {
        std::printf("  input segments:            %zu\n", st.input_segments);
        std::printf("  segments already edges:    %zu (of the Delaunay triangulation)\n",
                    st.cdt.segments_already_present);
        std::printf("  segments recovered:        %zu (%zu flips)\n",
                    st.cdt.segments_inserted - std::min(st.cdt.segments_inserted, st.cdt.segments_already_present),
                    st.cdt.flips);
        std::printf("  intersections resolved:    %zu (%zu vertices added)\n", st.cdt.intersections,
                    st.steiner_vertices);
        std::printf("  vertices on segments:      %zu\n", st.cdt.vertices_on_segments);
        std::printf("  overlapping segments:      %zu merged\n", st.cdt.overlaps_merged);
        std::printf("  zero-length segments:      %zu ignored\n", st.cdt.zero_length_segments);
        std::printf("  holes:                     %zu (%zu used, %zu ignored)%s\n", st.input_holes,
                    st.domain.holes_used, st.domain.holes_ignored, opt_.ignore_holes ? " -O: not applied" : "");
        if (opt_.regional_attributes || (geojson_ && !opt_.region_property.empty()))
          std::printf("  regions:                   %zu (%zu used, %zu ignored)\n", st.input_regions,
                      st.domain.regions_used, st.domain.regions_ignored);
        else
          std::printf("  regions:                   %zu (not used without -A)\n", st.input_regions);
        std::printf("  triangles removed:         %zu\n", st.domain.triangles_removed);
        if (opt_.convex_hull) std::printf("  hull segments added:       %zu\n", st.domain.hull_segments_added);
      }
      if (opt_.refine && opt_.poly) {
        std::printf("  segments:                  %zu (%zu already edges, %zu inserted, %zu zero-length ignored)\n",
                    inserted_.segments, inserted_.already_present, inserted_.inserted, inserted_.zero_length);
        std::printf("  intersections resolved:    %zu (%zu vertices added)\n", inserted_.cdt.intersections,
                    inserted_.vertices_added);
        std::printf("  vertices on segments:      %zu\n", inserted_.cdt.vertices_on_segments);
        std::printf("  holes:                     %zu (%zu carved, %zu outside the mesh, %zu ignored)%s\n",
                    holes_.size(), st.domain.holes_used, st.domain.holes_outside, st.domain.holes_ignored,
                    opt_.ignore_holes ? " -O: not applied" : "");
        std::printf("  triangles removed:         %zu\n", st.domain.triangles_removed);
      }
      if (opt_.refine && refined_) std::printf("  Delaunay flips:            %zu (before refinement)\n", delaunay_flips_);
      std::printf("  vertices in output:        %zu\n", mesh.num_vertices());
      std::printf("  triangles:                 %zu\n", mesh.num_triangles());
      std::printf("  edges:                     %zu (%zu on the boundary)\n", (3 * mesh.num_triangles() + boundary) / 2,
                  boundary);
      if (!opt_.refine) std::printf("  segments in output:        %zu\n", st.segments);
      std::printf("  mesh memory:               %.1f MB (%.1f bytes per triangle)\n", mesh.memory_bytes() / 1e6,
                  mesh.num_triangles() ? double(mesh.memory_bytes()) / double(mesh.num_triangles()) : 0.0);
      if (refined_) std::fputs(quality(mesh).text().c_str(), stdout);
      std::printf("Timings:\n");
      for (const Phase& p : phases_) std::printf("  %-38s %9.3f ms\n", p.name.c_str(), p.seconds * 1e3);
    }
  }

  // --smooth=N after meshing or refinement (not --adapt: adapt() smooths).
  // Vertices below `protect` stay. Refinement runs again for the triangles
  // left outside its bounds: a flip may lengthen an edge, and a move keeps
  // its star's smallest angle, which may already be below -q's bound, so
  // another triangle of the star may drop below it too (seldom: a few points).
  void smooth_mesh(dm::Mesh& mesh, std::size_t protect) {
    if (opt_.smooth <= 0 || mesh.num_triangles() == 0) return;
    auto t = Clock::now();
    dm::SmoothOptions so;
    so.passes = opt_.smooth;
    so.protect_first = protect;
    if (refined_) so.max_area = refine_options().max_area;
    if (refined_) {
      // Then what smoothing left outside the refinement's bounds is refined,
      // within what is left of its budgets.
      dm::RefineOptions ropt = refine_options();
      ropt.progress = progress_callback();
      smooth_stats_ = dm::smooth_refined(mesh, so, ropt, refine_stats_, &resplit_);
      progress_.clear();
      if (resplit_) dm::finish_vertex_markers(mesh);
    } else {
      smooth_stats_ = dm::smooth(mesh, so);
    }
    smoothed_ = true;
    phase("smooth", t);
  }

  // Refinement is asked for by -q, -a, -S or -D.
  // A GeoJSON --area-property asks for its bounds, so it refines too.
  bool refining() const {
    return opt_.quality || opt_.area || opt_.steiner_budget || opt_.conforming_delaunay ||
           (geojson_ && !opt_.area_property.empty());
  }

  dm::RefineOptions refine_options() const {
    dm::RefineOptions r = dm::cli::refine_options(opt_);
    r.use_triangle_area_bounds = r.use_triangle_area_bounds || (geojson_ && !opt_.area_property.empty());
    return r;
  }

  dm::QualityReport quality(const dm::Mesh& mesh) const {
    dm::QualityOptions q;
    q.min_angle_deg = opt_.quality ? opt_.min_angle.value_or(20.0) : 0.0;
    q.max_area = opt_.max_area.value_or(-1.0);
    if (refined_) q.input_vertices = refine_stats_.input_vertices;
    return dm::quality_report(mesh, q, refined_ ? &refine_stats_ : nullptr);
  }

  // A live progress line on stderr when it is a terminal (not with -Q).
  dm::ProgressCallback progress_callback() {
    if (opt_.quiet || !progress_.enabled()) return {};
    return progress_.callback();
  }

  const Options& opt_;
  dm::TerminalProgress progress_{stderr};
  bool geojson_ = false;  // the input is GeoJSON (meshed even-odd, like -p)
  bool poly_ = false;     // segments are meshed: -p or a GeoJSON input
  dm::GeoJsonInfo geojson_info_;
  bool refined_ = false;
  bool adapted_ = false;           // --adapt
  std::size_t read_vertices_ = 0, read_triangles_ = 0;  // -r: the mesh as read
  dm::AdaptStats adapt_stats_;
  bool smoothed_ = false;          // --smooth (not with --adapt)
  dm::SmoothStats smooth_stats_;
  std::size_t resplit_ = 0;        // points the refinement after smoothing added
  std::vector<double> sizes_;      // --adapt: FILE.mtr
  dm::RefineStats refine_stats_;
  std::vector<Phase> phases_;
  int first_index_ = 0;
  std::string check_summary_;  // -C passed: what was checked
  bool writing_ = false;  // an IoError before this is an input error
  std::string input_path_;
  std::vector<dm::Point> holes_;
  std::vector<dm::RegionSeed> regions_;
  dm::InsertSegmentsStats inserted_;  // -r -p: the .poly segments
  std::size_t delaunay_flips_ = 0;    // -r: flips before refinement
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
  if (!opt.unavailable.empty()) {
    for (const std::string& s : opt.unavailable)
      std::fprintf(stderr, "deltamesh: switch %s is not available in this version of deltamesh\n", s.c_str());
    return kExitUsage;
  }
  if (opt.refine && is_geojson_input(opt.input)) {
    std::fprintf(stderr, "deltamesh: -r reads a Triangle mesh (FILE.node, FILE.ele), not GeoJSON\n");
    return kExitUsage;
  }
  if (opt.input.empty()) {
    std::fprintf(stderr, "deltamesh: no input file (usage: deltamesh [-switches] FILE; see --help)\n");
    return kExitUsage;
  }
  Run run(opt);
  try {
    return run.execute();
  } catch (const MissingInput& e) {
    std::fprintf(stderr, "deltamesh: cannot open input file '%s': no such file\n", e.path().c_str());
    return kExitInput;
  } catch (const dm::ParseError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return kExitInput;
  } catch (const dm::IntersectingSegments& e) {
    std::fprintf(stderr,
                 "deltamesh: %s: segments %zu and %zu cross (--strict; without it they are split where they cross)\n",
                 run.input_path().c_str(), e.first() + static_cast<std::size_t>(run.first_index()),
                 e.second() + static_cast<std::size_t>(run.first_index()));
    return kExitInput;
  } catch (const dm::SegmentError& e) {
    const std::size_t base = static_cast<std::size_t>(run.first_index());
    std::fprintf(stderr, "deltamesh: %s: segment %zu (vertices %zu-%zu) %s\n", run.input_path().c_str(),
                 e.segment() + base, e.a() + base, e.b() + base, e.problem().c_str());
    return kExitInput;
  } catch (const dm::InputError& e) {
    std::fprintf(stderr, "deltamesh: %s: %s\n", run.input_path().empty() ? opt.input.c_str() : run.input_path().c_str(),
                 e.what());
    return kExitInput;
  } catch (const dm::IoError& e) {
    std::fprintf(stderr, "deltamesh: %s\n", e.what());
    return run.writing() ? kExitOutput : kExitInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "deltamesh: out of memory\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deltamesh: internal error: %s (please report this)\n", e.what());
    return kExitInternal;
  }
}

// Constrained Delaunay triangulation benchmarks.
//
// 1. cdt/<impl>/star100k: the CDT of a 100k-vertex star-shaped polygon
//    (deltamesh-gen's `star`), deltamesh's default method against CGAL's
//    Constrained_Delaunay_triangulation_2<Epick, Exact_predicates_tag> (when
//    CGAL is found at configure time), CGAL two ways: points inserted first
//    (range insert, spatially sorted) then the constraints between their
//    handles, and insert_constraint over the closed polygon.
// 2. methods/<method>/<input>/<n>: the seed's methods on the same inputs at
//    growing sizes, to see §1.2.3 and §2.3.3 on real numbers:
//      star   - star-shaped polygon (few edges crossed per segment);
//      chain  - x-monotone polyline through n random points, consecutive in x
//               (no two segments cross, each crosses ~sqrt(n) Delaunay edges);
//      random - n/2 random short segments between random points (some cross:
//               their crossings become vertices, the same for every method).
//
// Counters (per run): us_per_seg wall microseconds per input segment, flips
// (edge flips while recovering segments), crossed (edges crossed by the
// pieces that had to be recovered), cavity (triangles Fast retriangulated),
// steiner (crossing vertices added), fallbacks (pieces a method handed to
// another), tris.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/cdt.hpp"

#ifdef DELTAMESH_HAVE_CGAL
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

namespace {

using namespace deltamesh;
using Clock = std::chrono::steady_clock;

// ---- inputs ---------------------------------------------------------------------

Pslg chain_input(std::size_t n, std::uint64_t seed) {
  Pslg g;
  g.points = gen::uniform_points(n, seed);
  std::vector<VertexId> order(n);
  for (VertexId i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](VertexId a, VertexId b) { return g.points[a].x < g.points[b].x; });
  for (std::size_t i = 0; i + 1 < n; ++i) g.segments.push_back({order[i], order[i + 1], 1});
  return g;
}

Pslg random_input(std::size_t n, std::uint64_t seed) {
  Pslg g;
  g.points = gen::uniform_points(n, seed);
  gen::Rng rng(seed + 1000);
  std::vector<VertexId> order(n);
  for (VertexId i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](VertexId a, VertexId b) { return g.points[a].x < g.points[b].x; });
  // Short segments: to one of the next ~sqrt(n) points in x order.
  const auto reach = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  for (std::size_t s = 0; s < n / 2; ++s) {
    const std::size_t i = rng.below(n);
    const std::size_t j = std::min(n - 1, i + 1 + rng.below(reach));
    if (i != j) g.segments.push_back({order[i], order[j], 1});
  }
  return g;
}

const Pslg& input(const std::string& kind, std::size_t n) {
  static std::map<std::string, Pslg> cache;
  const std::string key = kind + std::to_string(n);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Pslg g = kind == "star" ? gen::star_polygon(n, 1) : kind == "chain" ? chain_input(n, 1) : random_input(n, 1);
    it = cache.emplace(key, std::move(g)).first;
  }
  return it->second;
}

// ---- deltamesh --------------------------------------------------------------------

void run_deltamesh(benchmark::State& state, const Pslg& g, CdtMethod method) {
  double total_us = 0.0;
  CdtStats st;
  std::size_t tris = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    try {
      CdtOptions opt;
      opt.method = method;
      Mesh m = constrained_triangulation(g, opt, &st);
      tris = m.num_triangles();
      benchmark::DoNotOptimize(m);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return;
    }
    total_us += std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  }
  const double segs = static_cast<double>(std::max<std::size_t>(1, g.segments.size()));
  state.counters["us_per_seg"] = benchmark::Counter(total_us / segs, benchmark::Counter::kAvgIterations);
  state.counters["flips"] = static_cast<double>(st.flips);
  state.counters["crossed"] = static_cast<double>(st.edges_crossed);
  state.counters["cavity"] = static_cast<double>(st.cavity_triangles);
  state.counters["steiner"] = static_cast<double>(st.intersections);
  state.counters["fallbacks"] = static_cast<double>(st.method_fallbacks);
  state.counters["tris"] = static_cast<double>(tris);
  state.counters["segs_ms"] = st.segments_seconds * 1e3;  // segment phase alone (last run)
}

// ---- CGAL -------------------------------------------------------------------------

#ifdef DELTAMESH_HAVE_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

void cgal_points_then_constraints(benchmark::State& state, const Pslg& g) {
  std::vector<std::pair<K::Point_2, std::uint32_t>> pts;
  for (std::uint32_t i = 0; i < g.points.size(); ++i) pts.emplace_back(K::Point_2(g.points[i].x, g.points[i].y), i);
  double total_us = 0.0;
  std::size_t faces = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    Cdt cdt;
    cdt.insert(pts.begin(), pts.end());  // spatially sorted range insert
    std::vector<Cdt::Vertex_handle> vh(g.points.size());
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) vh[v->info()] = v;
    for (const Segment& s : g.segments) cdt.insert_constraint(vh[s.a], vh[s.b]);
    faces = cdt.number_of_faces();
    benchmark::DoNotOptimize(cdt);
    total_us += std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  }
  state.counters["us_per_seg"] =
      benchmark::Counter(total_us / static_cast<double>(g.segments.size()), benchmark::Counter::kAvgIterations);
  state.counters["tris"] = static_cast<double>(faces);
}

void cgal_polygon(benchmark::State& state, const Pslg& g) {
  std::vector<K::Point_2> pts;
  for (const Point& p : g.points) pts.emplace_back(p.x, p.y);
  double total_us = 0.0;
  std::size_t faces = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    Cdt cdt;
    cdt.insert_constraint(pts.begin(), pts.end(), true);  // the closed polygon
    faces = cdt.number_of_faces();
    benchmark::DoNotOptimize(cdt);
    total_us += std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  }
  state.counters["us_per_seg"] =
      benchmark::Counter(total_us / static_cast<double>(g.segments.size()), benchmark::Counter::kAvgIterations);
  state.counters["tris"] = static_cast<double>(faces);
}
#endif

// ---- registration -------------------------------------------------------------------

void register_all() {
  auto setup = [](benchmark::internal::Benchmark* b, int reps) {
    b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(reps)->ReportAggregatesOnly(true);
  };
  const Pslg* star = &input("star", 100000);
  setup(benchmark::RegisterBenchmark("cdt/deltamesh/star100k",
                                     [star](benchmark::State& s) { run_deltamesh(s, *star, CdtMethod::Fast); }),
        5);
#ifdef DELTAMESH_HAVE_CGAL
  setup(benchmark::RegisterBenchmark("cdt/cgal_points_then_constraints/star100k",
                                     [star](benchmark::State& s) { cgal_points_then_constraints(s, *star); }),
        5);
  setup(benchmark::RegisterBenchmark("cdt/cgal_polygon/star100k",
                                     [star](benchmark::State& s) { cgal_polygon(s, *star); }),
        5);
#endif
  for (const char* kind : {"star", "chain", "random"}) {
    for (std::size_t n : {1000u, 4000u, 16000u, 64000u}) {
      for (CdtMethod m : {CdtMethod::Fast, CdtMethod::Ct, CdtMethod::Lawson, CdtMethod::Lifting}) {
        const std::string name =
            std::string("methods/") + std::string(to_string(m)) + "/" + kind + "/" + std::to_string(n);
        const std::string k = kind;
        setup(benchmark::RegisterBenchmark(name.c_str(),
                                           [k, n, m](benchmark::State& s) { run_deltamesh(s, input(k, n), m); }),
              1);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
#ifdef DELTAMESH_HAVE_CGAL
  benchmark::AddCustomContext("cgal", "CGAL " CGAL_VERSION_STR
                                      " Constrained_Delaunay_triangulation_2<Epick, Exact_predicates_tag>");
#else
  benchmark::AddCustomContext("cgal", "not built (CGAL not found at configure time)");
#endif
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

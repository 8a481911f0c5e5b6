// Thread safety: the library keeps no global mutable state, so independent
// calls in different threads must not interfere. Many inputs are meshed
// concurrently (Delaunay, every CDT method, domains with holes, refinement
// with sizing callbacks, reading and writing files) and each result must
// equal the single-threaded one, bit for bit. Run under ThreadSanitizer by
// `make test-sanitize` (build-tsan), which also catches races that happen
// not to change a result.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "algo/delaunay_parallel.hpp"
#include "algo/refine_parallel.hpp"
#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"

namespace dm = deltamesh;
namespace fs = std::filesystem;

namespace {

// Everything a run produced, compared exactly.
struct Outcome {
  std::vector<double> coords;
  std::vector<dm::VertexId> triangles;
  std::vector<std::uint8_t> flags;
  std::vector<int> markers;
  std::vector<double> numbers;  // statistics, attributes
  std::string text;             // error message or file contents
  bool valid = true;

  friend bool operator==(const Outcome&, const Outcome&) = default;
};

// convex: a point set's triangulation (convex hull); delaunay: false for
// --cdt=ct, which is a constrained triangulation but not always Delaunay.
Outcome outcome_of(const dm::Mesh& m, bool convex, bool delaunay = true) {
  Outcome o;
  for (const dm::Point& p : m.points()) o.coords.insert(o.coords.end(), {p.x, p.y});
  o.triangles.assign(m.triangle_vertices().begin(), m.triangle_vertices().end());
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    o.flags.push_back(m.edge_flags(e));
    o.markers.push_back(m.edge_marker(e));
  }
  o.markers.insert(o.markers.end(), m.vertex_markers().begin(), m.vertex_markers().end());
  o.numbers.assign(m.triangle_attributes().begin(), m.triangle_attributes().end());
  dm::CheckOptions co;
  co.convex_hull = convex;
  co.delaunay = delaunay;
  o.valid = dm::check(m, co).ok();
  return o;
}

struct Job {
  std::string name;
  std::function<Outcome(int thread)> run;
};

std::size_t scaled(std::size_t n) { return dm::test::quick_tests() ? n / 4 : n; }

// A square with random crossing segments inside and two hole points.
dm::Pslg crossing_segments(std::uint64_t seed, std::size_t count) {
  dm::gen::Rng rng(seed);
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 1});
  for (std::size_t i = 0; i < count; ++i) {
    const auto a = static_cast<dm::VertexId>(g.points.size());
    g.points.push_back({rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95)});
    g.points.push_back({rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95)});
    g.segments.push_back({a, a + 1, static_cast<int>(2 + i % 3)});
  }
  g.holes.push_back({0.5, 0.5});
  g.regions.push_back({{0.01, 0.01}, 3.0, 0.01});
  return g;
}

std::vector<Job> jobs(const fs::path& dir) {
  std::vector<Job> js;
  for (const dm::gen::Kind kind : {dm::gen::Kind::Uniform, dm::gen::Kind::Gaussian, dm::gen::Kind::Grid,
                                   dm::gen::Kind::Cocircular, dm::gen::Kind::Duplicates}) {
    js.push_back({"delaunay " + std::string(dm::gen::kKinds[static_cast<int>(kind)].name), [kind](int) {
                    const dm::Pslg g = dm::gen::generate(kind, scaled(4000), 11);
                    dm::DelaunayStats st;
                    Outcome o = outcome_of(dm::delaunay(g.points, {}, &st), true);
                    o.numbers.push_back(static_cast<double>(st.duplicates));
                    return o;
                  }});
  }
  for (const dm::CdtMethod method : {dm::CdtMethod::Fast, dm::CdtMethod::Ct, dm::CdtMethod::Lawson,
                                     dm::CdtMethod::Lifting}) {
    js.push_back({"cdt star " + std::string(dm::to_string(method)), [method](int) {
                    dm::TriangulateOptions opt;
                    opt.method = method;
                    return outcome_of(dm::triangulate(dm::gen::star_polygon(scaled(400), 5), opt), false,
                                      method != dm::CdtMethod::Ct);
                  }});
    js.push_back({"cdt crossings " + std::string(dm::to_string(method)), [method](int) {
                    dm::TriangulateOptions opt;
                    opt.method = method;
                    opt.domain.regional_attributes = true;
                    dm::TriangulateStats st;
                    Outcome o = outcome_of(dm::triangulate(crossing_segments(7, scaled(60)), opt, &st), false,
                                           method != dm::CdtMethod::Ct);
                    o.numbers.push_back(static_cast<double>(st.cdt.intersections));
                    return o;
                  }});
  }
  js.push_back({"refine square-hole", [](int) {
                  dm::Mesh m = dm::triangulate(dm::gen::square_with_hole(64));
                  dm::RefineOptions ro;
                  ro.min_angle_deg = 30;
                  ro.max_area = dm::test::quick_tests() ? 1e-3 : 2e-4;
                  const dm::RefineStats st = dm::refine(m, ro);
                  Outcome o = outcome_of(m, false);
                  o.numbers.push_back(static_cast<double>(st.steiner_points));
                  o.numbers.push_back(st.complete);
                  return o;
                }});
  js.push_back({"refine star with sizing callback and budget", [](int thread) {
                  dm::Mesh m = dm::triangulate(dm::gen::star_polygon(50, 9));
                  dm::RefineOptions ro;
                  ro.min_angle_deg = 25;
                  // A callback with per-call state of its own thread.
                  std::size_t calls = 0;
                  ro.max_area_at = [&calls, thread](double x, double y) {
                    ++calls;
                    (void)thread;
                    return 1e-4 + 0.01 * (x * x + y * y);
                  };
                  ro.max_steiner = scaled(4000);
                  const dm::RefineStats st = dm::refine(m, ro);
                  Outcome o = outcome_of(m, false);
                  o.numbers.push_back(static_cast<double>(st.steiner_points));
                  o.numbers.push_back(st.budget_exhausted);
                  o.numbers.push_back(calls > 0);
                  return o;
                }});
  js.push_back({"input error", [](int) {
                  Outcome o;
                  try {
                    dm::delaunay(dm::gen::collinear_points(scaled(1000), 3));
                  } catch (const dm::InputError& e) {
                    o.text = e.what();
                  }
                  return o;
                }});
  js.push_back({"read, mesh, write", [dir](int thread) {
                  const fs::path in = fs::path(DELTAMESH_SOURCE_DIR) / "examples" / "plate.poly";
                  const dm::Pslg g = dm::read_poly(in.string());
                  const dm::Mesh m = dm::triangulate(g);
                  const std::string out = (dir / ("plate_" + std::to_string(thread) + ".node")).string();
                  dm::write_node(m, out);
                  dm::write_ele(m, (dir / ("plate_" + std::to_string(thread) + ".ele")).string());
                  Outcome o = outcome_of(m, false);
                  o.text = dm::test::slurp(out);
                  return o;
                }});
  return js;
}

class Threads : public dm::test::TempDirTest {};

}  // namespace

TEST_F(Threads, ConcurrentMeshingEqualsSingleThreaded) {
  const std::vector<Job> js = jobs(dir_);
  std::vector<Outcome> reference;
  for (const Job& j : js) {
    reference.push_back(j.run(-1));
    EXPECT_TRUE(reference.back().valid) << j.name;
  }
  constexpr int kThreads = 4;
  const int rounds = dm::test::quick_tests() ? 1 : 2;
  std::vector<std::vector<Outcome>> got(kThreads, std::vector<Outcome>(js.size()));
  std::vector<std::string> errors(kThreads);
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      // Start together, each thread walking the jobs in its own order.
      ready.fetch_add(1);
      while (ready.load() < kThreads) std::this_thread::yield();
      try {
        for (int r = 0; r < rounds; ++r)
          for (std::size_t k = 0; k < js.size(); ++k) {
            const std::size_t i = (k * (2 * t + 1) + static_cast<std::size_t>(t)) % js.size();
            got[t][i] = js[i].run(t);
          }
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) {
    EXPECT_EQ(errors[t], "") << "thread " << t;
    for (std::size_t i = 0; i < js.size(); ++i) EXPECT_TRUE(got[t][i] == reference[i]) << js[i].name << ", thread " << t;
  }
}

TEST_F(Threads, ConcurrentWritersOfOneFileLeaveAWholeFile) {
  // Several threads write the same output path: each write is atomic, so
  // whichever lands last, the file is whole, and no temporary is left.
  const dm::Mesh m = dm::delaunay(dm::gen::uniform_points(scaled(2000), 3));
  const std::string target = path("same.node");
  dm::write_node(m, target);
  const std::string expected = dm::test::slurp(target);
  constexpr int kThreads = 4;
  std::vector<std::string> errors(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      try {
        for (int r = 0; r < 10; ++r) dm::write_node(m, target);
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(errors[t], "") << "thread " << t;
  EXPECT_EQ(dm::test::slurp(target), expected);
  EXPECT_EQ(listing(), (std::vector<std::string>{"same.node"}));
}

// The library's own threads (-t): the parallel Delaunay triangulation run
// again and again with more slabs than threads and more threads than
// cores, each result the same as the first and valid. Under ThreadSanitizer
// this is the stress test of the slab tasks and the merge.
TEST_F(Threads, ParallelDelaunayRepeatedGivesOneResult) {
  const auto pts = dm::gen::uniform_points(scaled(20000), 17);
  const int runs = dm::test::quick_tests() ? 6 : 20;
  for (unsigned threads : {2u, 4u}) {
    std::optional<dm::Mesh> first = dm::detail::parallel_delaunay(pts, 2 * threads, threads, nullptr);
    ASSERT_TRUE(first.has_value());
    const Outcome expected = outcome_of(*first, true);
    EXPECT_TRUE(expected.valid);
    for (int r = 0; r < runs; ++r) {
      std::optional<dm::Mesh> again = dm::detail::parallel_delaunay(pts, 2 * threads, threads, nullptr);
      ASSERT_TRUE(again.has_value());
      EXPECT_TRUE(outcome_of(*again, true) == expected) << threads << " threads, run " << r;
    }
  }
}

// Parallel refinement (refine_in_parts: parts refined on their threads, the
// stitch and the last pass's scans shared) run again and again: under
// ThreadSanitizer this is the stress test of its threads, and every run must
// give the first run's mesh, bit for bit, and a valid one.
TEST_F(Threads, ParallelRefinementRepeatedGivesOneResult) {
  const dm::Pslg g = dm::gen::square_with_hole(dm::test::quick_tests() ? 32 : 64);
  dm::TriangulateOptions to;
  to.threads = 1;
  dm::RefineOptions o;
  o.min_angle_deg = 30;
  o.max_area = dm::test::quick_tests() ? 8e-4 : 2e-4;
  const int runs = dm::test::quick_tests() ? 4 : 12;
  for (unsigned parts : {2u, 4u}) {
    o.threads = parts;
    dm::Mesh first = dm::triangulate(g, to);
    ASSERT_TRUE(dm::detail::refine_in_parts(first, o, parts).has_value());
    const Outcome expected = outcome_of(first, false);
    EXPECT_TRUE(expected.valid);
    for (int r = 0; r < runs; ++r) {
      dm::Mesh again = dm::triangulate(g, to);
      ASSERT_TRUE(dm::detail::refine_in_parts(again, o, parts).has_value());
      EXPECT_TRUE(outcome_of(again, false) == expected) << parts << " parts, run " << r;
    }
  }
}

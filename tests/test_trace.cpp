// The trace (include/deltamesh/trace.hpp, docs/trace.md): a run's JSON Lines
// replayed by the rules of docs/trace.md alone rebuild exactly the run's
// final mesh (the same coordinates bit for bit, the same triangles as a
// set), for every method and phase that reports events; and the CLI's
// --trace writes the file whole or not at all.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "deltamesh/deltamesh.hpp"

using namespace deltamesh;
using Tri = std::array<long long, 3>;
namespace fs = std::filesystem;

namespace {

Tri canonical(Tri t) {
  const int i = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return {t[i], t[(i + 1) % 3], t[(i + 2) % 3]};
}

// The mesh a trace describes, by docs/trace.md's replay rules only.
struct Replayed {
  std::vector<Point> points;
  std::multiset<Tri> tris;
  std::map<std::string, std::map<std::string, int>> counts;  // ev -> why -> events
  long long end_vertices = -1, end_triangles = -1;
  std::size_t recover_flips = 0;  // the sum of `flips` of the recover events
};

Point point_of(const nlohmann::json& p) { return {p[0].get<double>(), p[1].get<double>()}; }

Tri tri_of(const nlohmann::json& t) { return canonical({t[0].get<long long>(), t[1].get<long long>(), t[2].get<long long>()}); }

Replayed replay(const std::string& jsonl) {
  Replayed r;
  std::istringstream in(jsonl);
  std::string line;
  std::getline(in, line);
  const auto head = nlohmann::json::parse(line);
  EXPECT_EQ(head.at("trace"), "deltamesh");
  EXPECT_EQ(head.at("version"), 1);
  while (std::getline(in, line)) {
    const auto ev = nlohmann::json::parse(line);
    const std::string kind = ev.at("ev");
    ++r.counts[kind][ev.value("why", "")];
    if (kind == "points") {
      const std::size_t first = ev.at("first");
      const auto& pts = ev.at("points");
      if (r.points.size() < first + pts.size()) r.points.resize(first + pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) r.points[first + i] = point_of(pts[i]);
    }
    if (ev.contains("v") && ev.contains("p")) {
      const std::size_t v = ev.at("v");
      if (r.points.size() <= v) r.points.resize(v + 1);
      r.points[v] = point_of(ev.at("p"));
    }
    if (kind == "renumber") {
      const auto& map = ev.at("map");
      const std::size_t n = ev.at("vertices");
      std::vector<Point> next(n);
      std::vector<bool> set(n, false);
      for (std::size_t j = 0; j < n && j < r.points.size(); ++j) next[j] = r.points[j];
      for (std::size_t i = 0; i < map.size(); ++i) {
        const long long to = map[i];
        if (to < 0 || set[to]) continue;
        next[to] = r.points[i];
        set[to] = true;
      }
      r.points = next;
      std::multiset<Tri> tris;
      for (Tri t : r.tris) tris.insert(canonical({map[t[0]], map[t[1]], map[t[2]]}));
      r.tris = tris;
    }
    if (kind == "recover") r.recover_flips += ev.at("flips").get<std::size_t>();
    if (ev.contains("del"))
      for (const auto& t : ev.at("del")) {
        const auto it = r.tris.find(tri_of(t));
        EXPECT_NE(it, r.tris.end()) << "removes a triangle that is not there: " << line;
        if (it != r.tris.end()) r.tris.erase(it);
      }
    if (ev.contains("add"))
      for (const auto& t : ev.at("add")) r.tris.insert(tri_of(t));
    if (kind == "end") {
      r.end_vertices = ev.at("vertices");
      r.end_triangles = ev.at("triangles");
    }
  }
  return r;
}

void expect_valid(const Mesh& m) {
  CheckOptions co;
  co.convex_hull = false;
  co.delaunay = false;  // Ct is not Delaunay; the other runs are checked by their own tests
  const CheckReport rep = check(m, co);
  EXPECT_TRUE(rep.ok()) << rep.summary();
}

// Runs `switches` on `input` with a trace and compares its replay with the result.
std::vector<std::string> args_of(const std::string& switches) {
  std::vector<std::string> args;
  std::istringstream in(switches);
  for (std::string a; in >> a;) args.push_back(a);
  args.push_back("x");
  return args;
}

Replayed run_and_replay(const std::string& switches, RunInput input) {
  Plan plan = parse_arguments(args_of(switches)).plan;
  std::ostringstream out;
  JsonLinesTrace trace(out);
  plan.trace = &trace;
  const RunResult res = run(plan, std::move(input));
  trace.finish();
  expect_valid(res.mesh);
  const Replayed r = replay(out.str());
  // Vertices: the same coordinates, bit for bit.
  EXPECT_EQ(r.points.size(), res.mesh.num_vertices()) << switches;
  for (std::size_t v = 0; v < std::min(r.points.size(), res.mesh.num_vertices()); ++v) {
    const Point& a = r.points[v];
    const Point& b = res.mesh.point(static_cast<VertexId>(v));
    EXPECT_TRUE(std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
                std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y))
        << switches << ": vertex " << v;
  }
  // Triangles: the same set.
  std::multiset<Tri> mesh_tris;
  for (TriId t = 0; t < res.mesh.num_triangle_slots(); ++t) {
    if (!res.mesh.is_real(t)) continue;
    const auto tv = res.mesh.triangle(t);
    mesh_tris.insert(canonical({tv[0], tv[1], tv[2]}));
  }
  EXPECT_EQ(r.tris.size(), mesh_tris.size()) << switches;
  EXPECT_TRUE(r.tris == mesh_tris) << switches << ": the replayed triangles differ from the mesh's";
  EXPECT_EQ(r.end_vertices, static_cast<long long>(res.mesh.num_vertices()));
  EXPECT_EQ(r.end_triangles, static_cast<long long>(res.mesh.num_triangles()));
  return r;
}

// A unit square with a square hole.
Pslg square_with_hole() {
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 5});
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({4 + i, 4 + (i + 1) % 4, 7});
  p.holes = {{0.5, 0.5}};
  return p;
}

// Random points in a box, a closed boundary and random chords that cross
// each other: every recovery method has work to do.
Pslg crossing_chords(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (VertexId i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1});
  for (int i = 0; i < 60; ++i) p.points.push_back({u(rng), u(rng)});
  for (VertexId i = 0; i < 6; ++i) p.segments.push_back({4 + 2 * i, 5 + 2 * i, 0});
  p.points.push_back(p.points[7]);  // a duplicate
  return p;
}

RunInput input_of(Pslg p) {
  RunInput in;
  in.pslg = std::move(p);
  return in;
}

TEST(TraceReplay, DelaunayOfPoints) {
  Pslg p = crossing_chords(1);
  p.segments.clear();
  const Replayed r = run_and_replay("-Q", input_of(p));
  EXPECT_GT(r.counts.at("flip").at("delaunay"), 0);
  EXPECT_GT(r.counts.at("renumber").at(""), 0);
}

TEST(TraceReplay, EveryCdtMethod) {
  for (const char* method : {"fast", "ct", "lawson", "lifting"}) {
    SCOPED_TRACE(method);
    const Replayed r = run_and_replay(std::string("-pQ --cdt=") + method, input_of(crossing_chords(2)));
    EXPECT_GT(r.counts.at("insert").at("crossing"), 0);
    EXPECT_GT(r.counts.at("recover").size(), 0u);
    const std::string m = method;
    if (m == "ct") {
      EXPECT_GT(r.counts.at("flip").at("recovery"), 0);
    }
    if (m == "lifting") {
      EXPECT_GT(r.counts.at("flip").at("lifting"), 0);
    }
    if (m == "fast") {
      EXPECT_GT(r.counts.at("retriangulate").at("fast"), 0);
    }
    if (m == "ct" || m == "lifting") {
      // `flips` of the recover events counts exactly the method's flip events.
      const auto& flips = r.counts.at("flip");
      const std::size_t method_flips = (flips.count("recovery") ? flips.at("recovery") : 0) +
                                       (flips.count("lifting") ? flips.at("lifting") : 0) +
                                       (flips.count("lawson") ? flips.at("lawson") : 0);
      EXPECT_EQ(r.recover_flips, method_flips);
    }
  }
}

TEST(TraceReplay, RefinementWithHoles) {
  const Replayed r = run_and_replay("-pq30a0.01Q", input_of(square_with_hole()));
  EXPECT_GT(r.counts.at("carve").at(""), 0);
  EXPECT_GT(r.counts.at("split_segment").size(), 0u);
  EXPECT_GT(r.counts.at("split_triangle").size(), 0u);
}

TEST(TraceReplay, RefinementRules) {
  for (const char* rule : {"circumcenter", "offcenter", "best"}) {
    SCOPED_TRACE(rule);
    const Replayed r = run_and_replay(std::string("-pq33Q --steiner=") + rule, input_of(crossing_chords(3)));
    EXPECT_GT(r.counts.at("split_triangle").size(), 0u);
  }
  // Above 34 degrees: refinement may be undone back to the 34-degree mesh.
  run_and_replay("-pq40Q", input_of(crossing_chords(4)));
}

TEST(TraceReplay, SmoothingAndJettison) {
  const Replayed r = run_and_replay("-pq25a0.02jQ --smooth=2", input_of(crossing_chords(5)));
  EXPECT_GT(r.counts.at("move").size(), 0u);
}

TEST(TraceReplay, MeshInputRefinedAndAdapted) {
  // A mesh (-r): refined, then adapted to a size field.
  Plan first = parse_arguments({"-pQ", "x"}).plan;
  const RunResult base = run(first, input_of(crossing_chords(6)));
  RunInput in;
  in.pslg.points.assign(base.mesh.points().begin(), base.mesh.points().end());
  for (TriId t = 0; t < base.mesh.num_triangle_slots(); ++t)
    if (base.mesh.is_real(t))
      for (VertexId v : base.mesh.triangle(t)) in.triangles.push_back(v);
  run_and_replay("-rq30Q", in);
  RunInput adapt_in = in;
  adapt_in.size = [](double x, double) { return 0.02 + 0.2 * x; };
  const Replayed r = run_and_replay("-rQ --adapt", adapt_in);
  EXPECT_GT(r.counts.at("remove").size() + r.counts.at("split_triangle").size(), 0u);
  // Sizes per vertex: a background mesh is copied from the traced one (the
  // copy reports nothing).
  RunInput per_vertex = in;
  for (const Point& p : in.pslg.points) per_vertex.vertex_sizes.push_back(0.03 + 0.1 * p.x);
  run_and_replay("-rQ --adapt", per_vertex);
}

TEST(TraceReplay, CorpusFiles) {
  const fs::path corpus = fs::path(DELTAMESH_SOURCE_DIR) / ".." / "shared" / "corpus";
  if (!fs::exists(corpus)) GTEST_SKIP() << "no shared corpus beside the repository";
  for (const char* name : {"cdt_crossing_edges.poly", "cdt_hanging.poly", "poly2tri_star.poly",
                           "cdt_overlapping_constraints.poly", "earcut_hourglass.poly", "triangle_box.poly"}) {
    SCOPED_TRACE(name);
    const fs::path path = corpus / name;
    if (!fs::exists(path)) continue;
    run_and_replay("-pq25Q", input_of(read_poly(path.string())));
    run_and_replay("-pQ --cdt=lifting", input_of(read_poly(path.string())));
  }
}

// A run beyond the predicates' range reports the user's coordinates through
// a power-of-two frame; when it fails (here a size callback throws) the
// observer must not stay in that frame for the next run it watches.
TEST(TraceFrame, AFailedFramedRunLeavesTheObserverInTheUsersFrame) {
  struct PointsSeen : TraceObserver {
    std::vector<Point> points;
    void on_event(const TraceEvent& ev) override {
      if (ev.kind == TraceKind::Points) points.assign(ev.points.begin(), ev.points.end());
    }
  } seen;
  const std::vector<Point> in{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.25, 0.5}};
  Pslg far;
  for (const Point& p : in) far.points.push_back({std::ldexp(p.x, 300), std::ldexp(p.y, 300)});
  far.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (const bool refine_alone : {false, true}) {
    SCOPED_TRACE(refine_alone ? "refine()" : "triangulate()");
    TriangulateOptions opt;
    opt.trace = &seen;
    opt.refine.emplace();
    opt.refine->max_area_at = [](double, double) -> double { throw std::runtime_error("no size here"); };
    if (refine_alone) {
      TriangulateOptions plain;
      Mesh mesh = triangulate(far, plain);
      mesh.set_trace(&seen);
      const Mesh before = mesh;
      EXPECT_THROW(refine(mesh, *opt.refine), std::runtime_error);
      // The mesh came back in the user's frame as well.
      EXPECT_TRUE(std::equal(before.points().begin(), before.points().end(), mesh.points().begin()));
    } else {
      EXPECT_THROW(triangulate(far, opt), std::runtime_error);
    }

    DelaunayOptions dopt;
    dopt.trace = &seen;
    const Mesh again = delaunay(in, dopt);
    const CheckReport rep = check(again);
    EXPECT_TRUE(rep.ok()) << rep.summary();
    // Reported in insertion order: compare as sets.
    const auto less = [](const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    std::vector<Point> want = in, got = seen.points;
    std::sort(want.begin(), want.end(), less);
    std::sort(got.begin(), got.end(), less);
    EXPECT_EQ(got, want);
  }
}

// The command line: --trace PATH writes the file, and a trace that cannot
// be written is an output error that leaves no file behind.
TEST(TraceCli, WritesTheFileWholeOrNotAtAll) {
  const fs::path dir = fs::temp_directory_path() / ("dm_trace_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(fs::path(DELTAMESH_SOURCE_DIR) / "examples" / "plate.poly", dir / "plate.poly",
                fs::copy_options::overwrite_existing);
  const std::string cli = std::string(DELTAMESH_CLI);
  int status = std::system(("cd '" + dir.string() + "' && '" + cli + "' -pq30Q --trace t.jsonl plate.poly").c_str());
  ASSERT_EQ(WEXITSTATUS(status), 0);
  std::ifstream f(dir / "t.jsonl");
  std::stringstream ss;
  ss << f.rdbuf();
  const Replayed r = replay(ss.str());
  EXPECT_GT(r.end_triangles, 0);
  const Mesh m = [&] {
    Plan plan = parse_arguments({"-pq30Q", "x"}).plan;
    return run(plan, input_of(read_poly((dir / "plate.poly").string()))).mesh;
  }();
  EXPECT_EQ(r.end_triangles, static_cast<long long>(m.num_triangles()));
  status = std::system(("cd '" + dir.string() + "' && '" + cli + "' -pQ --trace no/such/dir/t.jsonl plate.poly 2>/dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), kExitOutput);
  EXPECT_FALSE(fs::exists(dir / "no"));
  fs::remove_all(dir);
}

}  // namespace

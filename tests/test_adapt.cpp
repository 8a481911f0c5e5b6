// Mesh adaptation (adapt.hpp): coarsening to a size field keeps a valid
// constrained Delaunay triangulation of the same domain, adapt() grades the
// mesh to the field, the background size field interpolates, and the CLI's
// --adapt reads TetGen .mtr sizes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"
#include "test_refine_util.hpp"

namespace dm = deltamesh;
namespace fs = std::filesystem;

namespace {

// The unit square (marker 1) with the square hole [0.4,0.6]^2 (marker 2) and
// an interior segment from (0.1,0.2) to (0.3,0.8) (marker 3): 10 vertices.
dm::Pslg domain() {
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}, {0.1, 0.2}, {0.3, 0.8}};
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 1});
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  g.segments.push_back({8, 9, 3});
  g.holes.push_back({0.5, 0.5});
  return g;
}

dm::RefineOptions quality(double angle, double max_area) {
  dm::RefineOptions r;
  r.min_angle_deg = angle;
  r.max_area = max_area;
  return r;
}
dm::AdaptOptions adapt_options(double angle) {
  dm::AdaptOptions a;
  a.refine.min_angle_deg = angle;
  return a;
}
dm::CoarsenOptions protect(std::size_t n) {
  dm::CoarsenOptions c;
  c.protect_first = n;
  return c;
}

dm::Mesh mesh_of(const dm::Pslg& g, std::optional<dm::RefineOptions> r) {
  dm::TriangulateOptions o;
  o.refine = std::move(r);
  return dm::triangulate(g, o);
}

// (Input vertices keep their ids 0..9: they are never removed and come first.)

std::size_t used_vertices(const dm::Mesh& m) {
  std::vector<char> used(m.num_vertices(), 0);
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t))
      for (dm::VertexId v : m.triangle(t)) used[v] = 1;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

// Area covered, and whether any triangle lies in the hole.
double area(const dm::Mesh& m, bool* in_hole = nullptr) {
  double a = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &p = m.point(v[0]), &q = m.point(v[1]), &r = m.point(v[2]);
    a += 0.5 * ((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
    const double cx = (p.x + q.x + r.x) / 3, cy = (p.y + q.y + r.y) / 3;
    if (in_hole && cx > 0.4 && cx < 0.6 && cy > 0.4 && cy < 0.6) *in_hole = true;
  }
  return a;
}

dm::SizeField ramp() {
  return [](double x, double) { return 0.01 + 0.19 * std::clamp(x, 0.0, 1.0); };
}

TEST(Adapt, GradesAFineMeshToARamp) {
  const dm::Pslg g = domain();
  dm::Mesh m = mesh_of(g, quality(30, 5e-5));
  dm::test::expect_valid_with_pslg(m, g);
  const std::size_t before = used_vertices(m);
  ASSERT_GT(before, 8000u);
  const dm::SizeField h = ramp();
  const dm::AdaptStats st = dm::adapt(m, h, adapt_options(30));
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_TRUE(st.complete) << st.refine.summary();
  const std::size_t after = used_vertices(m);
  EXPECT_GT(st.removed, before / 2);
  // ~600 vertices are right for this field (density 1/h^2): a large drop.
  EXPECT_LT(after * 6, before) << before << " -> " << after;
  EXPECT_GT(after, 200u);
  EXPECT_GE(dm::test::min_angle_deg(m), 30.0 - 1e-9);
  EXPECT_NEAR(area(m), 1.0 - 0.04, 1e-12);
  // Edges near each side have about the length h asks for there.
  std::size_t left = 0, right = 0;
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    const dm::Point &a = m.point(m.origin(e)), &b = m.point(m.dest(e));
    const double mx = (a.x + b.x) / 2, my = (a.y + b.y) / 2;
    const double len = std::hypot(a.x - b.x, a.y - b.y), want = h(mx, my);
    if (mx < 0.05) {
      ++left;
      EXPECT_GT(len, 0.3 * want) << mx << "," << my;
      EXPECT_LT(len, 3 * want) << mx << "," << my;
    } else if (mx > 0.95) {
      ++right;
      EXPECT_GT(len, 0.3 * want) << mx << "," << my;
      EXPECT_LT(len, 3 * want) << mx << "," << my;
    }
  }
  EXPECT_GT(left, 100u);
  EXPECT_GT(right, 10u);
}

TEST(Coarsen, KeepsCornersSegmentsAndHoles) {
  const dm::Pslg g = domain();
  dm::Mesh m = mesh_of(g, quality(25, 2e-4));
  const std::size_t before = used_vertices(m);
  const dm::CoarsenStats st = dm::coarsen(m, [](double, double) { return 0.15; });
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_EQ(st.removed + used_vertices(m), before);
  EXPECT_GT(st.removed, before / 2);
  EXPECT_GT(st.removed_on_segments, 20u);
  // Corners and segment ends keep their ids and coordinates.
  for (dm::VertexId v = 0; v < g.points.size(); ++v) {
    EXPECT_NE(m.out_edge(v), dm::kNone);
    EXPECT_EQ(m.point(v), g.points[v]);
  }
  bool in_hole = false;
  EXPECT_NEAR(area(m, &in_hole), 0.96, 1e-12);
  EXPECT_FALSE(in_hole);
  // Every constrained edge lies on an input segment with its marker.
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    if (!m.is_constrained(e)) continue;
    const dm::Point &a = m.point(m.origin(e)), &b = m.point(m.dest(e));
    // (exactly on it, or by the rounding of split points on the slanted one)
    auto near = [](const dm::Point& p, const dm::Point& q, const dm::Point& r) {
      const double o = dm::orient2d(p, q, r), l2 = (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y);
      return o == 0 || std::fabs(o) <= 1e-9 * l2;
    };
    bool on = false;
    for (const dm::Segment& s : g.segments)
      if (near(g.points[s.a], g.points[s.b], a) && near(g.points[s.a], g.points[s.b], b))
        on = on || m.edge_marker(e) == s.marker;
    EXPECT_TRUE(on) << a.x << "," << a.y << " - " << b.x << "," << b.y;
  }
}

TEST(Coarsen, AFieldLargerThanTheDomainGivesBackTheInputCdt) {
  const dm::Pslg g = domain();
  const dm::Mesh cdt = mesh_of(g, std::nullopt);
  dm::Mesh m = mesh_of(g, quality(30, 1e-3));
  ASSERT_GT(used_vertices(m), 300u);
  const dm::CoarsenStats st = dm::coarsen(m, [](double, double) { return 100.0; });
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_EQ(st.refused, 0u);
  EXPECT_EQ(used_vertices(m), g.points.size());
  EXPECT_EQ(m.num_triangles(), cdt.num_triangles());
}

TEST(Coarsen, ProtectedVerticesAndNoFieldStay) {
  const dm::Pslg g = domain();
  dm::Mesh m = mesh_of(g, quality(30, 1e-3));
  const std::size_t before = used_vertices(m);
  dm::coarsen(m, [](double, double) { return -1.0; });  // no target anywhere
  EXPECT_EQ(used_vertices(m), before);
  dm::coarsen(m, [](double, double) { return 100.0; }, protect(before));
  EXPECT_EQ(used_vertices(m), before);
  dm::test::expect_valid_with_pslg(m, g);
}

// A vertex marker of its own (one the vertex would not get from its segments)
// marks a point the user cares about: it stays, with its marker.
TEST(Coarsen, VerticesWithTheirOwnMarkersStay) {
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0}, {0.3, 0.3}, {0.7, 0.7}, {0.3, 0.7}};
  // On the bottom edge (segments marked 1): 7; interior points: 9, 0 (none), 1.
  g.point_markers = {0, 0, 0, 0, 7, 9, 0, 1};
  g.segments = {{0, 4, 1}, {4, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}};
  dm::Mesh m = mesh_of(g, quality(30, 2e-3));
  ASSERT_GT(used_vertices(m), 200u);
  const dm::CoarsenStats st = dm::coarsen(m, [](double, double) { return 100.0; });
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_GT(st.removed, 150u);
  auto find = [&](dm::Point p) {
    for (dm::VertexId v = 0; v < m.num_vertices(); ++v)
      if (m.point(v) == p) return v;
    return dm::kNone;
  };
  ASSERT_EQ(m.vertex_markers().size(), m.num_vertices());
  for (const auto& [p, marker] : {std::pair{dm::Point{0.5, 0}, 7}, {dm::Point{0.3, 0.3}, 9}, {dm::Point{0.3, 0.7}, 1}}) {
    const dm::VertexId v = find(p);
    ASSERT_NE(v, dm::kNone) << p.x << "," << p.y;
    EXPECT_NE(m.out_edge(v), dm::kNone);
    EXPECT_EQ(m.vertex_markers()[v], marker);
  }
  EXPECT_EQ(find({0.7, 0.7}), dm::kNone);  // no marker of its own: removed
  // Everything else that is left is a corner or a marked point.
  EXPECT_EQ(used_vertices(m), 4u + 3u);

  // A mesh read without its segments (-r without -p): the boundary's marker
  // (5) is only on its vertices; they go, the 7 between them stays.
  g.point_markers = {0, 0, 0, 0, 7, 0, 0, 0};
  g.points.resize(5);
  for (dm::Segment& sg : g.segments) sg.marker = 5;
  const dm::Mesh fine = mesh_of(g, quality(30, 2e-3));
  dm::Pslg nodes;
  nodes.points.assign(fine.points().begin(), fine.points().end());
  nodes.point_markers = fine.vertex_markers();
  std::vector<dm::VertexId> tris;
  for (dm::TriId t = 0; t < fine.num_triangle_slots(); ++t)
    if (fine.is_real(t))
      for (dm::VertexId v : fine.triangle(t)) tris.push_back(v);
  m = dm::mesh_from_triangles(nodes, tris);
  ASSERT_GT(used_vertices(m), 200u);
  dm::coarsen(m, [](double, double) { return 100.0; });
  g.segments.clear();  // (the boundary is checked as the mesh's own)
  dm::test::expect_valid_with_pslg(m, g);
  const dm::VertexId v = find({0.5, 0});
  ASSERT_NE(v, dm::kNone);
  EXPECT_EQ(m.vertex_markers()[v], 7);
  EXPECT_EQ(used_vertices(m), 5u);
}

// A fan: n points on the bottom side, every triangle at the top vertex
// (degree n + 1). Coarsening merges the bottom side into one segment; each
// removal next to the hub must not cost O(n) (it took 15 s at n = 40000,
// quadratic in n, when the Lawson pass started from every edge around the
// touched vertices; now about 0.1 s).
TEST(Coarsen, AHubOfHugeDegreeDoesNotMakeItQuadratic) {
  const std::size_t n = 40000;
  dm::Pslg nodes;
  for (std::size_t i = 0; i < n; ++i) nodes.points.push_back({double(i) / double(n - 1), 0.0});
  nodes.points.push_back({0.5, 1.0});
  std::vector<dm::VertexId> tris;
  for (dm::VertexId i = 0; i + 1 < n; ++i) tris.insert(tris.end(), {i, i + 1, static_cast<dm::VertexId>(n)});
  dm::Mesh m = dm::mesh_from_triangles(nodes, tris);
  // (Speed is not asserted here: 13 s before the fix, 0.1 s after, in Release;
  // see docs/adapt.md. The test keeps the case valid and in the suite.)
  const dm::CoarsenStats st = dm::coarsen(m, [](double, double) { return 1.0; });
  EXPECT_EQ(st.removed, n - 2);
  EXPECT_EQ(used_vertices(m), 3u);
  dm::Pslg outline;
  outline.points = {m.point(0), m.point(1), m.point(2)};
  dm::test::expect_valid_with_pslg(m, outline);
}

// A grid's Delaunay triangulation (all cocircular) has vertices of degree 4
// at the crossing of their link's diagonals: no spoke can be flipped, but
// the vertex goes by merging its four triangles into two.
TEST(Coarsen, GridVerticesOnTheirLinksDiagonalsGo) {
  dm::Pslg g;
  const int k = 30;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) g.points.push_back({double(i), double(j)});
  dm::TriangulateOptions points_only;
  points_only.use_segments = false;
  dm::Mesh m = dm::triangulate(g, points_only);
  std::size_t degree4 = 0;
  for (dm::VertexId v = 0; v < m.num_vertices(); ++v) {
    std::size_t d = 0;
    bool boundary = false;
    m.for_each_out_edge(v, [&](dm::HalfEdgeId e) {
      ++d;
      boundary = boundary || m.twin(e) == dm::kNone;
      return true;
    });
    if (d == 4 && !boundary && m.twin(dm::prev_edge(m.out_edge(v))) != dm::kNone) ++degree4;
  }
  ASSERT_GT(degree4, 20u);  // the case this is about
  const dm::CoarsenStats st = dm::coarsen(m, [](double, double) { return 1000.0; });
  EXPECT_EQ(st.refused, 0u) << st.summary();
  EXPECT_EQ(used_vertices(m), 4u);
  EXPECT_EQ(m.num_triangles(), 2u);
  dm::Pslg corners;
  dm::test::expect_valid_with_pslg(m, corners);
  // Graded: a field of 5 to 10 grid steps leaves about (k / 7)^2 vertices, not a third of them.
  dm::Mesh f = dm::triangulate(g, points_only);
  const dm::AdaptStats as = dm::adapt(f, [](double x, double) { return 5 * (1 + x / k); }, adapt_options(25));
  dm::test::expect_valid_with_pslg(f, corners);
  EXPECT_EQ(as.coarsen.refused, 0u);
  EXPECT_LT(as.coarsen.vertices_after, std::size_t{k * k / 8});
}

// fuzz_adapt: with an empty SizeField coarsen() skipped its counting and
// reported "0 -> 0 vertices", so adapt() without a field had stats that did
// not describe the mesh (vertices_after != the vertices refinement started from).
TEST(Coarsen, NoFieldStillCountsVertices) {
  const dm::Pslg g = domain();
  dm::Mesh m = mesh_of(g, quality(30, 1e-2));
  const std::size_t before = used_vertices(m);
  ASSERT_GT(before, g.points.size());
  const dm::CoarsenStats st = dm::coarsen(m, dm::SizeField{});
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_EQ(st.removed, 0u);
  EXPECT_EQ(st.vertices_before, before);
  EXPECT_EQ(st.vertices_after, before);
  EXPECT_EQ(used_vertices(m), before);
  const dm::AdaptStats as = dm::adapt(m, dm::SizeField{});  // nothing to refine either
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_EQ(as.coarsen.vertices_before, before);
  EXPECT_EQ(as.coarsen.vertices_after, as.refine.input_vertices);
}

TEST(Adapt, RefineCoarsenRefineRoundTrip) {
  const dm::Pslg g = domain();
  dm::Mesh m = mesh_of(g, quality(30, 2e-4));
  dm::test::expect_valid_with_pslg(m, g);
  const std::size_t fine = used_vertices(m);
  const dm::SizeField coarse = [](double x, double y) { return 0.05 + 0.1 * (x + y); };
  dm::coarsen(m, coarse);
  dm::test::expect_valid_with_pslg(m, g);
  const std::size_t coarsened = used_vertices(m);
  EXPECT_LT(coarsened * 2, fine);
  dm::RefineOptions r = quality(30, -1);
  r.max_edge_at = coarse;
  const dm::RefineStats rs = dm::refine(m, r);
  EXPECT_TRUE(rs.complete);
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_GE(dm::test::min_angle_deg(m), 30.0 - 1e-9);
  // Adapting again to the same field changes little.
  const std::size_t once = used_vertices(m);
  dm::adapt(m, coarse, adapt_options(30));
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_LT(used_vertices(m), once * 3 / 2);
  EXPECT_GT(used_vertices(m) * 3 / 2, once);
}

TEST(SizeField, InterpolatesVertexSizesLinearly) {
  const dm::Pslg g = domain();
  const dm::Mesh bg = mesh_of(g, quality(20, 1e-2));
  auto lin = [](double x, double y) { return 1 + 2 * x + 3 * y; };
  std::vector<double> sizes;
  for (const dm::Point& p : bg.points()) sizes.push_back(lin(p.x, p.y));
  const dm::SizeField h = dm::size_field_from_vertices(bg, sizes);
  for (double x = 0.05; x < 1; x += 0.1)
    for (double y = 0.03; y < 1; y += 0.07) {
      if (x > 0.4 && x < 0.6 && y > 0.4 && y < 0.6) continue;
      EXPECT_NEAR(h(x, y), lin(x, y), 1e-9) << x << "," << y;
    }
  // Inside the hole and outside the mesh: the nearest vertex's size.
  EXPECT_NEAR(h(0.5, 0.41), lin(0.5, 0.4), 0.3);
  EXPECT_DOUBLE_EQ(h(2, 2), lin(1, 1));
  EXPECT_DOUBLE_EQ(h(-5, -1), lin(0, 0));
  sizes.pop_back();
  EXPECT_THROW(dm::size_field_from_vertices(bg, sizes), dm::InputError);
  sizes.push_back(0.0);
  EXPECT_THROW(dm::size_field_from_vertices(bg, sizes), dm::InputError);
}

// The two topology primitives coarsening uses undo split_triangle and
// split_edge exactly: the same triangles, twins, flags and markers.
std::vector<std::array<dm::VertexId, 3>> triangles_of(const dm::Mesh& m) {
  std::vector<std::array<dm::VertexId, 3>> t;
  for (dm::TriId i = 0; i < m.num_triangle_slots(); ++i) {
    if (!m.is_real(i)) continue;
    auto v = m.triangle(i);
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    t.push_back(v);
  }
  std::sort(t.begin(), t.end());
  return t;
}
std::vector<std::array<int, 3>> constrained_of(const dm::Mesh& m) {
  std::vector<std::array<int, 3>> c;
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.is_real(dm::tri_of(e)) && m.is_constrained(e))
      c.push_back({int(m.origin(e)), int(m.dest(e)), m.edge_marker(e)});
  std::sort(c.begin(), c.end());
  return c;
}
void expect_topology(const dm::Mesh& m) {
  dm::CheckOptions co;
  co.delaunay = false;
  const dm::CheckReport rep = dm::check(m, co);
  EXPECT_TRUE(rep.ok()) << rep.summary();
}

TEST(MeshPrimitives, RemoveDegree3VertexAndUnsplitEdgeUndoSplits) {
  dm::Mesh m = dm::test::convex_domain({{0, 0}, {4, 0}, {4, 3}, {0, 3}, {1.5, 1.2}, {2.6, 1.9}}, 7);
  const auto tris = triangles_of(m);
  const auto cons = constrained_of(m);
  ASSERT_EQ(cons.size(), 4u);
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    dm::Mesh s = m;
    const auto v = s.triangle(t);
    const dm::Point c{(s.point(v[0]).x + s.point(v[1]).x + s.point(v[2]).x) / 3,
                      (s.point(v[0]).y + s.point(v[1]).y + s.point(v[2]).y) / 3};
    const dm::VertexId p = s.add_vertex(c);
    s.split_triangle(t, p);
    expect_topology(s);
    s.remove_degree3_vertex(p);
    expect_topology(s);
    EXPECT_EQ(triangles_of(s), tris);
    EXPECT_EQ(constrained_of(s), cons);
    EXPECT_EQ(s.out_edge(p), dm::kNone);
  }
  // Every edge, boundary (one side) and interior (two sides), at its midpoint.
  for (dm::HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) {
    dm::Mesh s = m;
    const dm::Point &a = s.point(s.origin(e)), &b = s.point(s.dest(e));
    const dm::VertexId p = s.add_vertex({(a.x + b.x) / 2, (a.y + b.y) / 2});
    const dm::HalfEdgeId g = s.split_edge(e, p);  // p -> dest(e)
    expect_topology(s);
    s.unsplit_edge(g);
    expect_topology(s);
    EXPECT_EQ(triangles_of(s), tris) << e;
    EXPECT_EQ(constrained_of(s), cons) << e;
    EXPECT_EQ(s.out_edge(p), dm::kNone);
  }
}

// ---- the command line: deltamesh -rq30 --adapt FILE.1 with FILE.1.mtr ----

class AdaptCli : public dm::test::TempDirTest {
 protected:
  // A fine mesh box.1.* of the unit square with a hole, and its vertices.
  dm::Pslg fine_mesh() const {
    write("box.poly",
          "8 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n5 0.4 0.4 2\n6 0.6 0.4 2\n7 0.6 0.6 2\n8 0.4 0.6 2\n"
          "8 1\n1 1 2 1\n2 2 3 1\n3 3 4 1\n4 4 1 1\n5 5 6 2\n6 6 7 2\n7 7 8 2\n8 8 5 2\n1\n1 0.5 0.5\n");
    const dm::test::CliResult r = run("-pq30a0.0002 -Q box");
    EXPECT_EQ(r.code, 0) << r.err;
    return dm::read_node(path("box.1.node"));
  }
};

TEST_F(AdaptCli, AdaptsToMtrSizes) {
  const dm::Pslg nodes = fine_mesh();
  ASSERT_GT(nodes.points.size(), 2000u);
  std::string mtr = std::to_string(nodes.points.size()) + " 1\n# sizes: 0.01 at x = 0 to 0.2 at x = 1\n";
  for (const dm::Point& p : nodes.points) mtr += std::to_string(0.01 + 0.19 * p.x) + "\n";
  write("box.1.mtr", mtr);
  const dm::test::CliResult r = run("-rpq30C --adapt box.1");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Coarsened:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Check:"), std::string::npos) << r.out;
  // The output is valid with the .poly's segments, and much coarser.
  dm::Pslg out = dm::read_node(path("box.2.node"));
  EXPECT_LT(out.points.size() * 2, nodes.points.size()) << nodes.points.size() << " -> " << out.points.size();
  const dm::EleData ele = dm::read_ele(path("box.2.ele"), out.first_index);
  // The corners keep their numbers (never removed, and first).
  const dm::Pslg g = dm::read_poly(path("box.poly"));
  out.segments = g.segments;
  const dm::Mesh m = dm::mesh_from_triangles(out, ele.triangles, ele.num_attributes, ele.attributes);
  dm::test::expect_valid_with_pslg(m, g);
  EXPECT_GE(dm::test::min_angle_deg(m), 30.0 - 1e-9);
  EXPECT_NEAR(area(m), 0.96, 1e-12);
}

TEST_F(AdaptCli, BadMtrFilesAreInputErrors) {
  const dm::Pslg nodes = fine_mesh();
  const std::size_t n = nodes.points.size();
  auto sizes = [&](std::size_t count, const std::string& bad_line, std::size_t at) {
    std::string s = std::to_string(count) + " 1\n";
    for (std::size_t i = 0; i < count; ++i) s += i == at ? bad_line + "\n" : "0.05\n";
    return s;
  };
  struct Case {
    std::string text, message;
  };
  const Case cases[] = {
      {sizes(n - 1, "", n), "box.1.mtr: has " + std::to_string(n - 1) + " sizes but"},
      {sizes(n, "-0.5", 3), "box.1.mtr:5: size 4 of " + std::to_string(n) + " is -0.5; sizes must be positive"},
      {sizes(n, "0", 0), "box.1.mtr:2: size 1 of"},
      {sizes(n, "abc", 6), "box.1.mtr:8:"},
      {sizes(n, "0.1 0.2", 6), "box.1.mtr:8: expected one size per line"},
      {std::to_string(n) + " 2\n", "box.1.mtr:1: the number of values per node is 2; 1 (an isotropic size) and 3"},
      {std::to_string(n) + " 3\n", "box.1.mtr:1: header announces"},
      {sizes(n, "", n) + "0.1\n", "box.1.mtr:" + std::to_string(n + 2) + ": unexpected data after"},
  };
  for (const Case& c : cases) {
    write("box.1.mtr", c.text);
    const dm::test::CliResult r = run("-rq30 --adapt box.1");
    EXPECT_EQ(r.code, 2) << c.message << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_FALSE(exists("box.2.node"));
  }
  fs::remove(path("box.1.mtr"));
  const dm::test::CliResult r = run("-rq30 --adapt box.1");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("box.1.mtr"), std::string::npos) << r.err;
}

}  // namespace

// A 135-degree corner beside an edge of length 1.4e-11 lies within 1e-11 of
// the line through its neighbours (relative to their distance) but is a
// corner: it stays. (Found by fuzz_adapt.)
TEST(Coarsen, ACornerBesideATinyEdgeStays) {
  dm::Pslg g;
  g.points = {{-1e-11, 1e-11}, {0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (dm::VertexId i = 0; i < 5; ++i) g.segments.push_back({i, (i + 1) % 5, 1});
  dm::Mesh m = dm::triangulate(g);
  const double before = dm::test::covered_area(m);
  dm::coarsen(m, [](double, double) { return 1e6; });
  bool corner = false;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t))
      for (dm::VertexId v : m.triangle(t)) corner = corner || (m.point(v).x == 0 && m.point(v).y == 0);
  EXPECT_TRUE(corner);
  EXPECT_EQ(dm::test::covered_area(m), before);
  dm::test::expect_valid(m, false);
}

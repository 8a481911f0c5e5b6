// Voronoi output: the dual graph (Triangle's .v.node/.v.edge) and bounded
// cells clipped to the domain.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "deltamesh/voronoi.hpp"

using namespace deltamesh;
namespace fs = std::filesystem;

namespace {

Mesh random_mesh(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  std::vector<Point> pts;
  for (int i = 0; i < n; ++i) pts.push_back({u(rng), u(rng)});
  return delaunay(pts);
}

std::vector<Point> grid_points(int n, double h) {
  std::vector<Point> pts;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) pts.push_back({i * h, j * h});
  return pts;
}

std::size_t edge_count(const Mesh& m) {
  std::size_t half = 0, hull = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      ++half;
      hull += m.twin(e) == kNone;
    }
  }
  return (half + hull) / 2;
}

double dist(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

double hull_area(const Mesh& m) {
  double a = 0.0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const Point p = m.point(v[0]), q = m.point(v[1]), r = m.point(v[2]);
    a += 0.5 * ((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
  }
  return a;
}

// Strictly inside a counter-clockwise ring (not necessarily convex)?
bool inside_ring(const std::vector<Point>& ring, const Point& p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point &a = ring[j], &b = ring[i];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x > p.x) in = !in;
    }
  }
  return in;
}

TEST(Voronoi, DualGraphCountsAndGeometry) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Mesh m = random_mesh(400, seed);
    ASSERT_TRUE(check(m).ok());
    const VoronoiDiagram d = voronoi_diagram(m);
    // One vertex per triangle, one edge per Delaunay edge.
    ASSERT_EQ(d.vertices.size(), m.num_triangles());
    ASSERT_EQ(d.edges.size(), edge_count(m));
    std::size_t k = 0, rays = 0;
    for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
      if (!m.is_real(t)) continue;
      // Equidistant from the triangle's corners.
      const auto v = m.triangle(t);
      const Point c = d.vertices[k++];
      const double r0 = dist(c, m.point(v[0])), r1 = dist(c, m.point(v[1])), r2 = dist(c, m.point(v[2]));
      EXPECT_NEAR(r1, r0, 1e-9 * r0);
      EXPECT_NEAR(r2, r0, 1e-9 * r0);
    }
    for (const VoronoiDiagram::Edge& e : d.edges) {
      const Point p = m.point(m.origin(e.delaunay_edge)), q = m.point(m.dest(e.delaunay_edge));
      const double dx = q.x - p.x, dy = q.y - p.y;
      ASSERT_LT(e.a, d.vertices.size());
      if (e.is_ray()) {
        ++rays;
        EXPECT_EQ(m.twin(e.delaunay_edge), kNone);
        // Perpendicular, outward (to the right of p -> q, away from the triangle).
        EXPECT_EQ(e.direction.x * dx + e.direction.y * dy, 0.0);
        EXPECT_LT(orient2d(p, q, {p.x + e.direction.x, p.y + e.direction.y}), 0.0);
        continue;
      }
      ASSERT_LT(e.b, d.vertices.size());
      const Point a = d.vertices[e.a], b = d.vertices[e.b];
      // Perpendicular to its Delaunay edge (both ends on the bisector).
      const double len = dist(a, b) * std::hypot(dx, dy);
      if (len > 0.0) {
        EXPECT_LE(std::fabs((b.x - a.x) * dx + (b.y - a.y) * dy), 1e-7 * len);
      }
      EXPECT_NEAR(dist(a, p), dist(a, q), 1e-9 * dist(a, p));
      EXPECT_NEAR(dist(b, p), dist(b, q), 1e-9 * dist(b, p));
    }
    std::size_t hull = 0;
    for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e) hull += m.twin(e) == kNone;
    EXPECT_EQ(rays, hull);
  }
}

// Vertex attributes are interpolated linearly at the circumcentres: an
// attribute that is a linear function of position is reproduced exactly.
TEST(Voronoi, AttributesInterpolatedAtCircumcentres) {
  Mesh m = random_mesh(80, 11);
  m.set_num_vertex_attributes(2);
  for (VertexId v = 0; v < m.num_vertices(); ++v) {
    const Point p = m.point(v);
    m.vertex_attributes().push_back(2.0 * p.x - 3.0 * p.y + 1.0);
    m.vertex_attributes().push_back(7.0);
  }
  const VoronoiDiagram d = voronoi_diagram(m);
  ASSERT_EQ(d.num_attributes, 2u);
  ASSERT_EQ(d.attributes.size(), 2 * d.vertices.size());
  for (std::size_t i = 0; i < d.vertices.size(); ++i) {
    const Point c = d.vertices[i];
    const double expect = 2.0 * c.x - 3.0 * c.y + 1.0;
    EXPECT_NEAR(d.attributes[2 * i], expect, 1e-6 * (1.0 + std::fabs(c.x) + std::fabs(c.y)));
    EXPECT_NEAR(d.attributes[2 * i + 1], 7.0, 1e-6 * (1.0 + std::fabs(c.x) + std::fabs(c.y)));
  }
}

TEST(Voronoi, TriangleVNodeAndVEdgeFiles) {
  const Mesh m = random_mesh(60, 9);
  const VoronoiDiagram d = voronoi_diagram(m);
  const fs::path dir = fs::temp_directory_path() / ("deltamesh_voronoi_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string vnode = (dir / "a.1.v.node").string(), vedge = (dir / "a.1.v.edge").string();
  write_voronoi_node(d, vnode, 1);
  write_voronoi_edge(d, vedge, 1);
  {
    std::ifstream in(vnode);
    std::size_t n, dim, attrs, markers;
    in >> n >> dim >> attrs >> markers;
    EXPECT_EQ(n, d.vertices.size());
    EXPECT_EQ(dim, 2u);
    EXPECT_EQ(attrs, 0u);
    EXPECT_EQ(markers, 0u);
    for (std::size_t i = 0; i < n; ++i) {
      long long id;
      double x, y;
      in >> id >> x >> y;
      EXPECT_EQ(id, static_cast<long long>(i) + 1);
      EXPECT_EQ(x, d.vertices[i].x);  // shortest round-trip output: exact
      EXPECT_EQ(y, d.vertices[i].y);
    }
  }
  {
    std::ifstream in(vedge);
    std::size_t n, markers;
    in >> n >> markers;
    EXPECT_EQ(n, d.edges.size());
    EXPECT_EQ(markers, 0u);
    std::string line;
    std::getline(in, line);
    std::size_t rays = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(std::getline(in, line));
      std::istringstream ls(line);
      long long id, a, b;
      ls >> id >> a >> b;
      EXPECT_EQ(id, static_cast<long long>(i) + 1);
      EXPECT_EQ(a, static_cast<long long>(d.edges[i].a) + 1);
      if (b == -1) {
        ++rays;
        double dx, dy;
        ASSERT_TRUE(ls >> dx >> dy) << line;
        EXPECT_EQ(dx, d.edges[i].direction.x);
        EXPECT_EQ(dy, d.edges[i].direction.y);
        EXPECT_TRUE(d.edges[i].is_ray());
      } else {
        EXPECT_EQ(b, static_cast<long long>(d.edges[i].b) + 1);
      }
    }
    EXPECT_GT(rays, 2u);
  }
  fs::remove_all(dir);
}

// Cells of a Delaunay triangulation (a convex domain) tile the hull.
TEST(Voronoi, BoundedCellsTileConvexDomain) {
  for (unsigned seed : {4u, 5u}) {
    const Mesh m = random_mesh(500, seed);
    const BoundedVoronoi b = bounded_voronoi(m);
    std::size_t used = 0;
    for (VertexId v = 0; v < m.num_vertices(); ++v) used += m.out_edge(v) != kNone;
    ASSERT_EQ(b.cells.size(), used);
    double total = 0.0;
    for (const VoronoiCell& c : b.cells) {
      EXPECT_GT(c.area, 0.0);
      total += c.area;
      // The site is inside (or, at a hull corner, on the boundary of) its cell.
      const Point s = m.point(c.site);
      bool on_ring = false;
      for (const Point& p : c.ring) on_ring = on_ring || dist(p, s) < 1e-12;
      EXPECT_TRUE(on_ring || inside_ring(c.ring, s)) << c.site;
      // Every cell corner is as close to the site as to any other vertex
      // (checked against the triangle neighbours of the site).
      m.for_each_out_edge(c.site, [&](HalfEdgeId e) {
        const Point u = m.point(m.dest(e));
        for (const Point& p : c.ring) EXPECT_LE(dist(p, s), dist(p, u) * (1 + 1e-9) + 1e-12);
        return true;
      });
    }
    EXPECT_NEAR(total, hull_area(m), 1e-9 * hull_area(m));
  }
}

TEST(Voronoi, GridCellsAreSquares) {
  const int n = 6;
  const double h = 0.5;
  const Mesh m = delaunay(grid_points(n, h));
  const BoundedVoronoi b = bounded_voronoi(m);
  ASSERT_EQ(b.cells.size(), static_cast<std::size_t>((n + 1) * (n + 1)));
  for (const VoronoiCell& c : b.cells) {
    const Point s = m.point(c.site);
    const bool bx = s.x == 0.0 || s.x == n * h, by = s.y == 0.0 || s.y == n * h;
    const double expect = h * h / ((bx ? 2 : 1) * (by ? 2 : 1));
    EXPECT_NEAR(c.area, expect, 1e-12) << s.x << " " << s.y;
  }
}

// An L-shaped domain (a grid with the upper right quarter removed): cells
// stay inside, the reflex corner's cell loses its outside quadrant, and on
// this Delaunay-conforming mesh the cells tile the domain.
TEST(Voronoi, BoundedCellsOnNonConvexDomain) {
  const int n = 8;
  const double h = 0.5;
  Mesh m = delaunay(grid_points(n, h));
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const double cx = (m.point(v[0]).x + m.point(v[1]).x + m.point(v[2]).x) / 3;
    const double cy = (m.point(v[0]).y + m.point(v[1]).y + m.point(v[2]).y) / 3;
    if (cx > 2.0 && cy > 2.0) m.remove_triangle(t);
  }
  m.compact();
  CheckOptions copt;
  copt.convex_hull = false;
  ASSERT_TRUE(check(m, copt).ok()) << check(m, copt).summary();
  const BoundedVoronoi b = bounded_voronoi(m);
  double total = 0.0;
  bool saw_corner = false;
  for (const VoronoiCell& c : b.cells) {
    total += c.area;
    const Point s = m.point(c.site);
    for (const Point& p : c.ring) {
      EXPECT_FALSE(p.x > 2.0 + 1e-12 && p.y > 2.0 + 1e-12) << "cell of " << s.x << "," << s.y << " leaves the L";
      EXPECT_TRUE(p.x >= -1e-12 && p.y >= -1e-12 && p.x <= 4 + 1e-12 && p.y <= 4 + 1e-12);
    }
    if (s.x == 2.0 && s.y == 2.0) {
      saw_corner = true;
      EXPECT_NEAR(c.area, 0.75 * h * h, 1e-12);
      EXPECT_EQ(c.ring.size(), 6u);  // a square less one quadrant
    }
  }
  EXPECT_TRUE(saw_corner);
  EXPECT_NEAR(total, 12.0, 1e-9);
}

// A notch: the cell of a vertex across a narrow gap must not spill over it.
TEST(Voronoi, CellsDoNotCrossANarrowGap) {
  // Two fingers x in [0,1] and [1.2,2.2], joined at the bottom (y < 0.2).
  std::vector<Point> pts;
  for (double x : {0.0, 0.5, 1.0, 1.2, 1.7, 2.2})
    for (double y : {0.0, 0.2, 1.0, 2.0, 3.0}) pts.push_back({x, y});
  Mesh m = delaunay(pts);
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const double cx = (m.point(v[0]).x + m.point(v[1]).x + m.point(v[2]).x) / 3;
    const double cy = (m.point(v[0]).y + m.point(v[1]).y + m.point(v[2]).y) / 3;
    if (cx > 1.0 && cx < 1.2 && cy > 0.2) m.remove_triangle(t);
  }
  m.compact();
  const BoundedVoronoi b = bounded_voronoi(m);
  for (const VoronoiCell& c : b.cells) {
    const Point s = m.point(c.site);
    for (const Point& p : c.ring) {
      if (p.y <= 0.2 + 1e-12) continue;
      if (s.x <= 1.0) {
        EXPECT_LE(p.x, 1.0 + 1e-12) << s.x << "," << s.y;
      }
      if (s.x >= 1.2) {
        EXPECT_GE(p.x, 1.2 - 1e-12) << s.x << "," << s.y;
      }
    }
  }
}

// A quality conforming Delaunay mesh of a plate with two holes (a square and
// an octagon) and an interior segment: the cells tile the non-convex domain
// and stay in it; with a constrained (not conforming) mesh they overlap a
// little across the interior segment, as documented.
TEST(Voronoi, CellsTileAConformingMeshWithHoles) {
  const Pslg g = read_poly(std::string(DELTAMESH_SOURCE_DIR) + "/examples/plate.poly");
  for (const bool conforming : {true, false}) {
    TriangulateOptions opt;
    RefineOptions r;
    r.min_angle_deg = 25;
    r.max_area = 0.1;
    r.conforming_delaunay = conforming;
    opt.refine = r;
    const Mesh m = triangulate(g, opt);
    double area = 0.0;
    for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
      if (!m.is_real(t)) continue;
      const auto v = m.triangle(t);
      const Point a = m.point(v[0]), b = m.point(v[1]), c = m.point(v[2]);
      area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    }
    const BoundedVoronoi cells = bounded_voronoi(m);
    double total = 0.0;
    for (const VoronoiCell& c : cells.cells) total += c.area;
    if (conforming) {
      EXPECT_NEAR(total, area, 1e-9 * area);
    } else {
      EXPECT_NEAR(total, area, 1e-3 * area);
    }
  }
}

}  // namespace

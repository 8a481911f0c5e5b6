// Property tests of Delaunay triangulation over seeded inputs, every result
// through the validator.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <string>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/validate.hpp"

using namespace deltamesh;

namespace {

std::size_t hull_edges(const Mesh& m) {
  std::size_t h = 0;
  for (HalfEdgeId e = 0; e < m.triangle_vertices().size(); ++e)
    if (m.is_real(tri_of(e)) && (m.twin(e) == kNone || m.is_ghost(tri_of(m.twin(e))))) ++h;
  return h;
}

void expect_valid(const Mesh& m, const std::string& what) {
  const CheckReport r = check(m);
  EXPECT_TRUE(r.ok()) << what << ": " << r.summary();
  // Euler on a triangulated convex polygon with B boundary vertices and V
  // vertices in all: T = 2V - 2 - B.
  EXPECT_EQ(m.num_triangles(), 2 * r.vertices_used - 2 - hull_edges(m)) << what;
}

// Triangles as sorted vertex triples, for comparing triangulations.
std::set<std::array<VertexId, 3>> triangle_set(const Mesh& m, const std::vector<VertexId>* relabel = nullptr) {
  std::set<std::array<VertexId, 3>> s;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    auto v = m.triangle(t);
    if (relabel)
      for (auto& x : v) x = (*relabel)[x];
    std::sort(v.begin(), v.end());
    s.insert(v);
  }
  return s;
}

std::vector<Point> scaled(std::vector<Point> p, double s) {
  for (Point& q : p) q = {q.x * s, q.y * s};
  return p;
}

constexpr double kScales[] = {1e-9, 1e-3, 1.0, 1e3, 1e9};

}  // namespace

TEST(Delaunay, UniformAtManyScales) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
    for (double s : kScales) {
      const auto pts = scaled(gen::uniform_points(2000, seed), s);
      DelaunayStats st;
      const Mesh m = delaunay(pts, {}, &st);
      EXPECT_EQ(st.duplicates, 0u);
      expect_valid(m, "uniform seed " + std::to_string(seed) + " scale " + std::to_string(s));
    }
}

TEST(Delaunay, GaussianClusters) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    for (double s : kScales) expect_valid(delaunay(scaled(gen::gaussian_points(3000, seed), s)), "gaussian");
}

TEST(Delaunay, CocircularGrid) {
  for (double s : kScales) {
    const auto pts = scaled(gen::grid_points(40 * 40), s);
    const Mesh m = delaunay(pts);
    expect_valid(m, "grid scale " + std::to_string(s));
    EXPECT_EQ(m.num_triangles(), 2u * 39 * 39);
  }
}

TEST(Delaunay, CocircularRing) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    auto pts = gen::cocircular_points(500, seed);
    pts.push_back({0.0, 0.0});  // centre: every ring point is on one circle around it
    expect_valid(delaunay(pts), "cocircular");
  }
}

TEST(Delaunay, CollinearPlusOneOffLine) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    auto pts = gen::collinear_points(300, seed);
    pts.push_back({0.5, 0.0});
    const Mesh m = delaunay(pts);
    expect_valid(m, "collinear+1");
  }
}

TEST(Delaunay, AllCollinearIsAClearError) {
  const auto pts = gen::collinear_points(100, 3);
  try {
    (void)delaunay(pts);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("collinear"), std::string::npos) << e.what();
  }
}

TEST(Delaunay, TooFewDistinctPoints) {
  const std::vector<Point> same(10, Point{1, 2});
  EXPECT_THROW((void)delaunay(same), InputError);
  EXPECT_THROW((void)delaunay(std::vector<Point>{}), InputError);
  EXPECT_THROW((void)delaunay(std::vector<Point>{{0, 0}, {1, 1}}), InputError);
}

TEST(Delaunay, NonFiniteRejected) {
  std::vector<Point> pts = gen::uniform_points(10, 1);
  pts[4].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)delaunay(pts), InputError);
  pts[4].y = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)delaunay(pts), InputError);
}

TEST(Delaunay, DuplicatesMergedAndMapped) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto pts = gen::duplicate_points(4000, seed);
    DelaunayStats st;
    const Mesh m = delaunay(pts, {}, &st);
    expect_valid(m, "duplicates");
    std::set<std::pair<double, double>> distinct;
    for (const Point& p : pts) distinct.insert({p.x, p.y});
    EXPECT_EQ(st.duplicates, pts.size() - distinct.size());
    ASSERT_EQ(st.duplicate_of.size(), pts.size());
    std::size_t mapped = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const VertexId d = st.duplicate_of[i];
      if (d == kNone) {
        EXPECT_NE(m.out_edge(static_cast<VertexId>(i)), kNone) << "kept vertex " << i << " is in no triangle";
        continue;
      }
      ++mapped;
      EXPECT_EQ(pts[d], pts[i]);
      EXPECT_LT(d, i) << "of equal points the first in input order is kept";
      EXPECT_EQ(st.duplicate_of[d], kNone) << "a duplicate maps to another duplicate";
      EXPECT_EQ(m.out_edge(static_cast<VertexId>(i)), kNone);
    }
    EXPECT_EQ(mapped, st.duplicates);
  }
}

TEST(Delaunay, RemoveUnusedVerticesRenumbers) {
  const auto pts = gen::duplicate_points(500, 9);
  DelaunayStats st;
  Mesh m = delaunay(pts, {}, &st);
  const auto map = m.remove_unused_vertices();
  EXPECT_EQ(m.num_vertices(), pts.size() - st.duplicates);
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (map[i] != kNone) {
      EXPECT_EQ(m.point(map[i]), pts[i]);
    }
  expect_valid(m, "after remove_unused_vertices");
}

TEST(Delaunay, InsertionOrderDoesNotMatter) {
  // Random points are in general position with probability 1: the
  // triangulation is unique, so a shuffled input must give the same one.
  for (std::uint64_t seed = 11; seed <= 14; ++seed) {
    const auto pts = gen::uniform_points(3000, seed);
    std::vector<VertexId> perm(pts.size());
    for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<VertexId>(i);
    gen::Rng rng(seed);
    gen::shuffle(perm, rng);
    std::vector<Point> shuffled(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) shuffled[i] = pts[perm[i]];
    const Mesh a = delaunay(pts);
    const Mesh b = delaunay(shuffled);
    expect_valid(b, "shuffled");
    EXPECT_EQ(triangle_set(a), triangle_set(b, &perm));
  }
}

TEST(Delaunay, MatchesBruteForceEmptyCircleOnSmallSets) {
  // Independent of the validator's local test: every triangle's circumcircle
  // is empty of all other points (global Delaunay property, O(n^2)).
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto pts = gen::uniform_points(60, seed);
    const Mesh m = delaunay(pts);
    for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
      if (!m.is_real(t)) continue;
      const auto v = m.triangle(t);
      for (std::size_t i = 0; i < pts.size(); ++i)
        EXPECT_LE(incircle(pts[v[0]], pts[v[1]], pts[v[2]], pts[i]), 0.0) << "seed " << seed;
    }
  }
}

TEST(Delaunay, KeepGhostsGivesClosedTriangulation) {
  const auto pts = gen::uniform_points(500, 3);
  DelaunayOptions opt;
  opt.keep_ghosts = true;
  Mesh m = delaunay(pts, opt);
  expect_valid(m, "with ghosts");
  // Insert more points into it, then compact and validate.
  const auto more = gen::uniform_points(300, 4);
  for (const Point& p : more) insert_delaunay_vertex(m, p);
  EXPECT_EQ(m.num_vertices(), 800u);
  EXPECT_TRUE(check(m).ok()) << check(m).summary();
  m.compact();
  expect_valid(m, "after inserting and compacting");
}

TEST(Delaunay, PointsOutsideAndOnHullInsertedLater) {
  // Inserting vertices onto hull edges and collinear with hull edges.
  std::vector<Point> pts = {{0, 0}, {4, 0}, {0, 4}, {2, 0}, {6, 0}, {-2, 0}, {2, 2}, {0, 2}, {0, 8}, {1, 1}};
  const Mesh m = delaunay(pts);
  expect_valid(m, "hull cases");
}

// Helpers shared by the refinement and adaptation tests.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/validate.hpp"

namespace deltamesh::test {

// A carved convex domain: the Delaunay triangulation of `points` with its
// hull edges as segments (marker 1), compacted.
inline Mesh convex_domain(const std::vector<Point>& points, int marker = 1) {
  Mesh mesh = delaunay(points, {.keep_ghosts = true});
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    if (mesh.is_dead(tri_of(e)) || mesh.is_ghost(tri_of(e))) continue;
    const HalfEdgeId f = mesh.twin(e);
    if (f != kNone && mesh.is_ghost(tri_of(f))) mesh.constrain_edge(e, marker);
  }
  mesh.compact();
  return mesh;
}

// The constrained edges of a mesh as vertex pairs (each once).
inline std::vector<std::pair<VertexId, VertexId>> boundary_segments(const Mesh& mesh) {
  std::vector<std::pair<VertexId, VertexId>> s;
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    if (!mesh.is_real(tri_of(e)) || !mesh.is_constrained(e)) continue;
    const HalfEdgeId f = mesh.twin(e);
    if (f != kNone && f < e) continue;
    s.push_back({mesh.origin(e), mesh.dest(e)});
  }
  return s;
}

inline double min_angle_deg(const Mesh& mesh) {
  double lo = 180;
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const Point& a = mesh.point(v[i]);
      const Point& b = mesh.point(v[(i + 1) % 3]);
      const Point& c = mesh.point(v[(i + 2) % 3]);
      const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
      lo = std::min(lo, std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy) * 180 / std::numbers::pi);
    }
  }
  return lo;
}

// Valid (topology, orientation, constrained Delaunay) and every segment of g
// a chain of constrained edges between its vertices (ids unchanged).
inline void expect_valid_with_pslg(const Mesh& mesh, const Pslg& g) {
  CheckOptions co;
  co.convex_hull = false;
  co.pslg = &g;
  const CheckReport rep = check(mesh, co);
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_EQ(rep.segments_checked, g.segments.size());
}

// The area the live triangles cover.
inline double covered_area(const Mesh& mesh) {
  double a = 0;
  for (TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const Point &p = mesh.point(v[0]), &q = mesh.point(v[1]), &r = mesh.point(v[2]);
    a += 0.5 * ((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
  }
  return a;
}

inline void expect_valid(const Mesh& mesh, bool convex) {
  CheckOptions co;
  co.convex_hull = convex;
  const CheckReport rep = check(mesh, co);
  EXPECT_TRUE(rep.ok()) << rep.summary();
}

// Every input segment (a, b) is still a chain of constrained edges from a to
// b whose vertices lie on the segment (up to rounding of split points).
inline bool segments_conform(const Mesh& mesh, const std::vector<std::pair<VertexId, VertexId>>& segs) {
  // Constrained neighbours of every vertex, from all half-edges (a vertex
  // where holes touch has two fans; a rotation would see only one).
  std::vector<std::vector<VertexId>> adj(mesh.num_vertices());
  for (HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e) {
    if (!mesh.is_real(tri_of(e)) || !mesh.is_constrained(e)) continue;
    adj[mesh.origin(e)].push_back(mesh.dest(e));
    adj[mesh.dest(e)].push_back(mesh.origin(e));
  }
  for (const auto& [a, b] : segs) {
    const Point& pa = mesh.point(a);
    const Point& pb = mesh.point(b);
    const double dx = pb.x - pa.x, dy = pb.y - pa.y, len2 = dx * dx + dy * dy;
    VertexId v = a;
    double progress = 0;
    for (std::size_t steps = 0; v != b; ++steps) {
      if (steps > mesh.num_vertices()) return false;
      VertexId next = kNone;
      double best = 2, best_dist = INFINITY;
      for (VertexId w_id : adj[v]) {
        const Point& w = mesh.point(w_id);
        const double t = ((w.x - pa.x) * dx + (w.y - pa.y) * dy) / len2;
        // Distance from the line, against rounding at the coordinates' magnitude.
        const double dist = std::fabs((w.x - pa.x) * dy - (w.y - pa.y) * dx) / std::sqrt(len2);
        const double tol = 1e-9 * std::sqrt(len2) + 1e-13 * (std::fabs(w.x) + std::fabs(w.y) + 1e-300);
        // Of the constrained neighbours ahead on the line, the one nearest
        // to it (near a small input angle another segment runs close by).
        if (t > progress && dist < tol && dist < best_dist) {
          best = t;
          best_dist = dist;
          next = w_id;
        }
      }
      if (next == kNone) return false;
      progress = best;
      v = next;
    }
  }
  return true;
}

}  // namespace deltamesh::test

namespace deltamesh::test {

// A carved domain for a PSLG whose segments are all Delaunay edges of its
// vertices (no CDT needed): Delaunay triangulation, segments constrained,
// triangles reachable from the hole points without crossing a segment
// removed, compacted. Returns false when a segment is not a Delaunay edge.
inline bool delaunay_domain(const std::vector<Point>& points,
                            const std::vector<std::pair<VertexId, VertexId>>& segments,
                            const std::vector<Point>& holes, Mesh& out, int marker = 1) {
  Mesh mesh = delaunay(points, {.keep_ghosts = true});
  for (const auto& [a, b] : segments) {
    const HalfEdgeId e = mesh.find_edge(a, b);
    if (e == kNone) return false;
    mesh.constrain_edge(e, marker);
  }
  std::vector<TriId> stack;
  for (const Point& h : holes) {
    const Location loc = mesh.locate(h);
    if (loc.tri != kNone && loc.kind == Location::Kind::InTriangle) stack.push_back(loc.tri);
  }
  std::vector<char> gone(mesh.num_triangle_slots(), 0);
  while (!stack.empty()) {
    const TriId t = stack.back();
    stack.pop_back();
    if (gone[t] || mesh.is_ghost(t)) continue;
    gone[t] = 1;
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      if (!mesh.is_constrained(e) && mesh.twin(e) != kNone) stack.push_back(tri_of(mesh.twin(e)));
    }
  }
  for (TriId t = 0; t < gone.size(); ++t)
    if (gone[t]) mesh.remove_triangle(t);
  mesh.compact();
  out = std::move(mesh);
  return true;
}

}  // namespace deltamesh::test

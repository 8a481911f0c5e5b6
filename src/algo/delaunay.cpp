// Incremental Delaunay triangulation: Hilbert order, walking location from
// the previous insertion, split + Lawson flips, ghost triangles for the hull.
#include "deltamesh/delaunay.hpp"

#include <chrono>
#include <string>

#include "algo/insertion.hpp"
#include "core/spatial_sort.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Real triangle (a, b, c) counter-clockwise plus its three ghosts, linked.
void make_first_triangle(Mesh& mesh, VertexId a, VertexId b, VertexId c) {
  const TriId t = mesh.add_triangle(a, b, c);
  const VertexId v[3] = {a, b, c};
  TriId g[3];
  for (int i = 0; i < 3; ++i) g[i] = mesh.add_triangle(v[(i + 1) % 3], v[i], kInfinite);
  for (int i = 0; i < 3; ++i) {
    mesh.link(3 * t + i, 3 * g[i]);
    // Ghost g[i] = (v[i+1], v[i], inf): its edge v[i] -> inf meets ghost
    // g[i-1] = (v[i], v[i-1], inf) at its edge inf -> v[i].
    mesh.link(3 * g[i] + 1, 3 * g[(i + 2) % 3] + 2);
    mesh.set_out_edge(v[i], 3 * t + i);
  }
}

}  // namespace

Mesh delaunay(std::span<const Point> points, const DelaunayOptions& options, DelaunayStats* stats) {
  check_coordinates(points);
  const std::size_t n = points.size();
  if (n >= kNone - 2) throw InputError("too many points: at most 4294967292 are supported");
  auto t0 = Clock::now();
  std::vector<VertexId> order = detail::hilbert_order(points);

  // Build on a copy in insertion order, so the walk touches nearby memory.
  Mesh mesh;
  {
    std::vector<Point>& pts = mesh.points_mut();
    pts.resize(n);
    for (std::size_t k = 0; k < n; ++k) pts[k] = points[order[k]];
    mesh.vert_edge_mut().assign(n, kNone);
  }
  if (stats) stats->sort_seconds = seconds_since(t0);
  t0 = Clock::now();

  // First triangle: the first point, the next distinct one, the next one off their line.
  const std::span<const Point> pts = mesh.points();
  std::size_t i1 = 1;
  while (i1 < n && pts[i1] == pts[0]) ++i1;
  std::size_t i2 = i1 + 1;
  while (i2 < n && orient2d(pts[0], pts[i1], pts[i2]) == 0) ++i2;
  if (i2 >= n) {
    const std::size_t distinct = i1 < n ? 2 : (n == 0 ? 0 : 1);
    if (distinct < 2)
      throw InputError("no triangle can be made: the input has " + std::to_string(n) +
                       " points but fewer than 3 distinct ones");
    throw InputError("no triangle can be made: all " + std::to_string(n) + " points are collinear");
  }
  mesh.reserve(n, 2 * n + 2);
  if (orient2d(pts[0], pts[i1], pts[i2]) > 0)
    make_first_triangle(mesh, 0, static_cast<VertexId>(i1), static_cast<VertexId>(i2));
  else
    make_first_triangle(mesh, 0, static_cast<VertexId>(i2), static_cast<VertexId>(i1));

  std::vector<VertexId> dup_of;  // in insertion order, only when asked for
  if (stats) dup_of.assign(n, kNone);
  std::size_t duplicates = 0;
  detail::DelaunayInserter inserter(mesh);
  TriId hint = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (k == i1 || k == i2) continue;
    const VertexId v = static_cast<VertexId>(k);
    const auto r = inserter.insert_existing(v, hint);
    if (r.vertex != v) {
      ++duplicates;
      if (stats) dup_of[k] = r.vertex;
      continue;
    }
    hint = r.tri;
  }
  if (stats) stats->insert_seconds = seconds_since(t0);

  if (!options.keep_ghosts) mesh.compact();

  // Back to input numbering: vertex ids become input indices.
  for (VertexId& v : mesh.tri_v_mut())
    if (v < n) v = order[v];
  {
    std::vector<HalfEdgeId>& ve = mesh.vert_edge_mut();
    std::vector<HalfEdgeId> moved(n);
    for (std::size_t k = 0; k < n; ++k) moved[order[k]] = ve[k];
    ve.swap(moved);
  }
  mesh.points_mut().assign(points.begin(), points.end());
  if (stats) {
    stats->duplicates = duplicates;
    stats->duplicate_of.assign(n, kNone);
    for (std::size_t k = 0; k < n; ++k)
      if (dup_of[k] != kNone) stats->duplicate_of[order[k]] = order[dup_of[k]];
  }
  return mesh;
}

VertexId insert_delaunay_vertex(Mesh& mesh, const Point& p, TriId hint) {
  check_coordinates(std::span<const Point>(&p, 1));
  detail::DelaunayInserter inserter(mesh);
  return inserter.insert_point(p, hint).vertex;
}

}  // namespace deltamesh

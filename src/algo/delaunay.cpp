// Incremental Delaunay triangulation: Hilbert order, walking location from
// the previous insertion, split + Lawson flips, ghost triangles for the hull.
#include "deltamesh/delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "algo/insertion.hpp"
#include "core/spatial_sort.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/legalize.hpp"
#include "mesh/locate.hpp"

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


// The bulk builder: split + Lawson flips (mesh/legalize.hpp) on raw arrays
// sized once, without per-vertex out-edges (compact() rebuilds them), because
// this loop is where a 10^6-point triangulation spends its time.
class BulkBuilder {
 public:
  BulkBuilder(Mesh& mesh, std::size_t max_triangles)
      : mesh_(mesh), used_(mesh.tri_v_mut().size()), p_(mesh.points().data()) {
    mesh.tri_v_mut().resize(3 * max_triangles);
    mesh.twin_mut().resize(3 * max_triangles);
    v_ = mesh.tri_v_mut().data();
    tw_ = mesh.twin_mut().data();
    stack_.reserve(64);
  }
  ~BulkBuilder() {
    mesh_.tri_v_mut().resize(used_);
    mesh_.twin_mut().resize(used_);
  }
  BulkBuilder(const BulkBuilder&) = delete;
  BulkBuilder& operator=(const BulkBuilder&) = delete;

  // Inserts vertex v; returns v, or the vertex it coincides with. `hint`
  // (a real triangle) is updated to a triangle near v for the next walk.
  VertexId insert(VertexId v, TriId& hint) {
    // In a Delaunay triangulation the walk cannot cycle, so the edges are
    // tried in a fixed order.
    const Location loc = detail::visibility_walk(v_, tw_, p_, p_[v], hint, detail::FixedEdgeOrder{}).loc;
    switch (loc.kind) {
      case Location::Kind::OnVertex:
        hint = loc.tri;
        return loc.vertex;
      case Location::Kind::OnEdge:
        split_edge(loc.edge, v);
        break;
      case Location::Kind::InTriangle:
      case Location::Kind::Outside:  // the ghost beyond the hull edge p sees takes p
        split(loc.tri, v);
        break;
    }
    detail::MeshArrays arrays;
    arrays.tv = v_;
    arrays.tw = tw_;
    arrays.pts = p_;
    detail::RawTopology<detail::kCarryTopologyOnly> topo(arrays);
    const HalfEdgeId last = detail::legalize_around_vertex(topo, v, stack_).last;
    hint = detail::real_triangle_near(v_, tw_, tri_of(last));
    return v;
  }

 private:
  void push(HalfEdgeId e) { stack_.push_back(e); }

  // Triangle t = (a, b, c) becomes (a, b, v) + new (b, c, v) + new (c, a, v).
  void split(TriId t, VertexId v) {
    const HalfEdgeId e0 = 3 * t, e1 = e0 + 1, e2 = e0 + 2;
    const VertexId a = v_[e0], b = v_[e1], c = v_[e2];
    const HalfEdgeId tw_bc = tw_[e1], tw_ca = tw_[e2];
    const HalfEdgeId g0 = static_cast<HalfEdgeId>(used_), h0 = g0 + 3;
    used_ += 6;
    v_[g0] = b;
    v_[g0 + 1] = c;
    v_[g0 + 2] = v;
    v_[h0] = c;
    v_[h0 + 1] = a;
    v_[h0 + 2] = v;
    tw_[g0] = tw_bc;
    tw_[g0 + 1] = h0 + 2;
    tw_[g0 + 2] = e1;
    tw_[h0] = tw_ca;
    tw_[h0 + 1] = e2;
    tw_[h0 + 2] = g0 + 1;
    tw_[tw_bc] = g0;
    tw_[tw_ca] = h0;
    v_[e2] = v;
    tw_[e1] = g0 + 2;
    tw_[e2] = h0 + 1;
    push(e0);
    push(g0);
    push(h0);
  }

  // Edge e = (a, b) between (a, b, c) and (b, a, d) is split at v into
  // (a, v, c), new (v, b, c), (b, v, d), new (v, a, d).
  void split_edge(HalfEdgeId e, VertexId v) {
    const unsigned ie = e % 3;
    const HalfEdgeId e1 = e - ie + detail::kNextIndex[ie], e2 = e - ie + detail::kPrevIndex[ie];
    const HalfEdgeId f = tw_[e];
    const unsigned jf = f % 3;
    const HalfEdgeId f1 = f - jf + detail::kNextIndex[jf], f2 = f - jf + detail::kPrevIndex[jf];
    const VertexId a = v_[e], b = v_[e1], c = v_[e2], d = v_[f2];
    const HalfEdgeId tw_bc = tw_[e1], tw_ad = tw_[f1];
    const HalfEdgeId g0 = static_cast<HalfEdgeId>(used_), h0 = g0 + 3;
    used_ += 6;
    v_[g0] = v;
    v_[g0 + 1] = b;
    v_[g0 + 2] = c;
    v_[h0] = v;
    v_[h0 + 1] = a;
    v_[h0 + 2] = d;
    v_[e1] = v;
    v_[f1] = v;
    tw_[g0] = f;
    tw_[f] = g0;
    tw_[g0 + 1] = tw_bc;
    tw_[tw_bc] = g0 + 1;
    tw_[g0 + 2] = e1;
    tw_[e1] = g0 + 2;
    tw_[h0] = e;
    tw_[e] = h0;
    tw_[h0 + 1] = tw_ad;
    tw_[tw_ad] = h0 + 1;
    tw_[h0 + 2] = f1;
    tw_[f1] = h0 + 2;
    push(e2);
    push(g0 + 1);
    push(f2);
    push(h0 + 1);
  }

  Mesh& mesh_;
  std::size_t used_;  // half-edge slots in use
  VertexId* v_ = nullptr;
  HalfEdgeId* tw_ = nullptr;
  const Point* p_;
  std::vector<HalfEdgeId> stack_;
};

}  // namespace

Mesh delaunay(std::span<const Point> points, const DelaunayOptions& options, DelaunayStats* stats) {
  check_coordinates(points);
  const std::size_t n = points.size();
  if (n >= kNone - 2) throw InputError("too many points: at most 4294967292 are supported");
  auto t0 = Clock::now();
  // Build on a copy in insertion order, so the walk touches nearby memory.
  Mesh mesh;
  std::vector<VertexId> order = detail::hilbert_order(points, &mesh.points_mut());

  mesh.vert_edge_mut().assign(n, kNone);
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

  // (duplicate, the vertex it met) in insertion order.
  std::vector<std::pair<VertexId, VertexId>> dups;
  {
    // A closed triangulation of k vertices plus the vertex at infinity has
    // 2k - 2 triangles; the builder's arrays are sized for that once.
    BulkBuilder builder(mesh, 2 * n + 2);
    TriId hint = 0;
    for (std::size_t k = 1; k < n; ++k) {
      if (k == i1 || k == i2) continue;
      const VertexId v = static_cast<VertexId>(k);
      const VertexId got = builder.insert(v, hint);
      if (got != v) dups.emplace_back(v, got);
    }
  }
  mesh.recount();
  if (stats) stats->insert_seconds = seconds_since(t0);

  if (options.keep_ghosts) {
    std::vector<HalfEdgeId>& ve = mesh.vert_edge_mut();
    const std::vector<VertexId>& tv = mesh.tri_v_mut();
    for (HalfEdgeId e = 0; e < tv.size(); ++e)
      if (tv[e] < n) ve[tv[e]] = e;
  } else {
    mesh.compact();
  }

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
    stats->duplicates = dups.size();
    stats->duplicate_of.assign(n, kNone);
  }
  if (!dups.empty()) {
    // Of equal points the first in input order is the one kept (as the CDT
    // and DelaunayStats promise, and the CLI's ids, markers and attributes
    // assume); the insertion order may have met a later copy first.
    std::vector<VertexId> first(n);
    for (VertexId v = 0; v < n; ++v) first[v] = v;
    for (const auto& [d, kept] : dups) first[order[kept]] = std::min(first[order[kept]], order[d]);
    for (VertexId& v : mesh.tri_v_mut())
      if (v < n) v = first[v];
    std::vector<HalfEdgeId>& ve = mesh.vert_edge_mut();
    for (const auto& [d, kept] : dups) {
      const VertexId k = order[kept];
      if (first[k] != k && ve[k] != kNone) {
        ve[first[k]] = ve[k];
        ve[k] = kNone;
      }
    }
    if (stats)
      for (const auto& [d, kept] : dups) {
        const VertexId k = order[kept], f = first[k];
        stats->duplicate_of[order[d]] = f;
        if (f != k) stats->duplicate_of[k] = f;
        stats->duplicate_of[f] = kNone;
      }
  }
  return mesh;
}

VertexId insert_delaunay_vertex(Mesh& mesh, const Point& p, TriId hint) {
  check_coordinates(std::span<const Point>(&p, 1));
  detail::DelaunayInserter inserter(mesh);
  return inserter.insert_point(p, hint).vertex;
}

}  // namespace deltamesh

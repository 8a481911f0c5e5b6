// Incremental Delaunay triangulation: Hilbert order, walking location from
// the previous insertion, split + Lawson flips, ghost triangles for the hull.
#include "deltamesh/delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "algo/delaunay_parallel.hpp"
#include "algo/insertion.hpp"
#include "core/parallel.hpp"
#include "algo/normalize.hpp"
#include "core/spatial_sort.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/legalize.hpp"
#include "mesh/locate.hpp"
#include "mesh/split.hpp"
#include "mesh/editor.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The bulk builder: split + Lawson flips (mesh/legalize.hpp) on raw arrays
// allocated once, without per-vertex out-edges (compact() rebuilds them),
// because this loop is where a 10^6-point triangulation spends its time.
// The arrays grow within their capacity as triangles are added (no
// reallocation, so the raw pointers stay valid): resizing them whole at the
// start would zero-fill every page once before the build writes it again.
class BulkBuilder {
 public:
  BulkBuilder(Mesh& mesh, std::size_t max_triangles)
      : used_(detail::MeshEditor(mesh).triangle_vertices().size()), p_(mesh.points().data()), trace_(mesh.trace()),
        tv_vec_(detail::MeshEditor(mesh).triangle_vertices()), tw_vec_(detail::MeshEditor(mesh).twins()) {
    tv_vec_.reserve(3 * max_triangles);
    tw_vec_.reserve(3 * max_triangles);
    v_ = tv_vec_.data();
    tw_ = tw_vec_.data();
    stack_.reserve(64);
  }
  ~BulkBuilder() {
    tv_vec_.resize(used_);
    tw_vec_.resize(used_);
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
    detail::RawTopology<detail::kCarryTopologyOnly> topo(arrays());
    const HalfEdgeId last = detail::legalize_around_vertex(topo, v, stack_).last;
    hint = detail::real_triangle_near(v_, tw_, tri_of(last));
    return v;
  }

 private:
  void push(HalfEdgeId e) { stack_.push_back(e); }

  detail::MeshArrays arrays() const {
    detail::MeshArrays a;
    a.tv = v_;
    a.tw = tw_;
    a.pts = p_;
    a.trace = trace_;
    return a;
  }

  // Triangle t = (a, b, c) becomes (a, b, v) + new (b, c, v) + new (c, a, v);
  // the edges opposite v go on the stack.
  // Two more triangle slots, within the capacity reserved. The arrays grow
  // by chunks that stay in cache until the build writes them.
  void grow() {
    used_ += 6;
    if (used_ <= tv_vec_.size()) [[likely]]
      return;
    if (used_ > tv_vec_.capacity()) throw InternalError("delaunay", "more triangles than Euler's bound allows");
    const std::size_t size = std::min(tv_vec_.capacity(), used_ + 3 * 4096);
    tv_vec_.resize(size);
    tw_vec_.resize(size);
  }

  void split(TriId t, VertexId v) {
    const TriId t1 = static_cast<TriId>(used_ / 3);
    grow();
    detail::split_triangle_arrays<detail::kCarryTopologyOnly>(arrays(), t, v, t1, t1 + 1);
    if (trace_) [[unlikely]]
      detail::TraceAccess::slots(*trace_, detail::trace_insert(v, p_[v]), v_, {t, t1, t1 + 1});
    push(3 * t);
    push(3 * t1);
    push(3 * t1 + 3);
  }

  // Edge e = (a, b) between (a, b, c) and (b, a, d) is split at v into
  // (a, v, c), new (v, b, c), (b, v, d), new (v, a, d).
  void split_edge(HalfEdgeId e, VertexId v) {
    const HalfEdgeId f = tw_[e];
    const TriId t3 = static_cast<TriId>(used_ / 3);
    grow();
    const HalfEdgeId g0 = detail::split_edge_arrays<detail::kCarryTopologyOnly>(arrays(), e, v, t3, t3 + 1);
    if (trace_) [[unlikely]]
      detail::TraceAccess::slots(*trace_, detail::trace_insert(v, p_[v]), v_, {tri_of(e), tri_of(f), t3, t3 + 1});
    push(prev_edge(e));
    push(g0 + 1);
    push(prev_edge(f));
    push(g0 + 4);
  }

  std::size_t used_;  // half-edge slots in use
  VertexId* v_ = nullptr;
  HalfEdgeId* tw_ = nullptr;
  const Point* p_;
  TraceObserver* trace_;
  std::vector<VertexId>& tv_vec_;
  std::vector<HalfEdgeId>& tw_vec_;
  std::vector<HalfEdgeId> stack_;
};

}  // namespace

namespace detail {

InsertionOrderDelaunay delaunay_in_insertion_order(std::span<const Point> points, TraceObserver* trace,
                                                   DelaunayStats* stats, std::chrono::steady_clock::time_point& t0,
                                                   std::size_t reserve_triangles, std::size_t reserve_points,
                                                   const std::function<void()>& after_sort, bool finish,
                                                   std::span<const VertexId> subset) {
  const std::size_t n = subset.empty() ? points.size() : subset.size();
  InsertionOrderDelaunay out;
  // Build on a copy in insertion order, so the walk touches nearby memory.
  Mesh& mesh = out.mesh;
  mesh.set_trace(trace);
  MeshEditor(mesh).points().reserve(std::max(n, reserve_points));
  out.order = subset.empty() ? hilbert_order(points, &MeshEditor(mesh).points())
                             : hilbert_order(points, subset, &MeshEditor(mesh).points());
  if (after_sort) after_sort();  // `points` is not read again
  if (trace) {  // vertices in insertion order until the caller renumbers them
    TraceAccess::phase(*trace, "delaunay");
    TraceAccess::points(*trace, 0, mesh.points());
  }

  if (finish) MeshEditor(mesh).out_edges().assign(n, kNone);
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
  mesh.reserve(n, std::max(2 * n + 2, reserve_triangles));
  // Unfinished (a slab): out-edges only for the first triangle's corners,
  // which it sets; the n-entry fill would be freed unread.
  if (!finish) MeshEditor(mesh).out_edges().assign(std::max(i1, i2) + 1, kNone);
  if (orient2d(pts[0], pts[i1], pts[i2]) > 0)
    make_first_triangle(mesh, 0, static_cast<VertexId>(i1), static_cast<VertexId>(i2));
  else
    make_first_triangle(mesh, 0, static_cast<VertexId>(i2), static_cast<VertexId>(i1));

  {
    // A closed triangulation of k vertices plus the vertex at infinity has
    // 2k - 2 triangles; the builder's arrays are sized for that once.
    BulkBuilder builder(mesh, 2 * n + 2);
    TriId hint = 0;
    for (std::size_t k = 1; k < n; ++k) {
      if (k == i1 || k == i2) continue;
      const VertexId v = static_cast<VertexId>(k);
      const VertexId got = builder.insert(v, hint);
      if (got != v) out.dups.emplace_back(v, got);
    }
  }
  if (finish) MeshEditor(mesh).recount();
  return out;
}

}  // namespace detail

Mesh delaunay(std::span<const Point> points, const DelaunayOptions& options, DelaunayStats* stats) {
  // Beyond the predicates' range: in an exact power-of-two frame. In range
  // this costs one branch-free scan (in chunks on the threads).
  const unsigned threads = detail::resolve_threads(options.threads);
  bool framed_run = false;
  if (!detail::in_predicate_range(points, threads)) {
    try {
      check_coordinates(points);
    } catch (const VertexError&) {
      if (!detail::needs_frame(points)) throw;
      framed_run = true;
    }
  }
  if (framed_run) {
    const detail::Frame f = detail::frame_for(points);
    std::vector<Point> framed(points.begin(), points.end());
    detail::scale_vertices(f, framed);
    Mesh mesh = [&] {
      const detail::TraceFrameScope in_frame(options.trace, f.k);
      return delaunay(framed, options, stats);
    }();
    detail::restore(f, mesh);
    return mesh;
  }
  const std::size_t n = points.size();
  if (n >= kNone - 2) throw InputError("too many points: at most 4294967292 are supported");
  if (!options.keep_ghosts && !options.trace) {  // a traced run is the sequential one, step by step
    const auto parts = static_cast<unsigned>(std::min<std::size_t>(threads, n / detail::kMinPointsPerPart));
    if (parts >= 2)
      if (std::optional<Mesh> m = detail::parallel_delaunay(points, parts, threads, stats)) return std::move(*m);
  }
  auto t0 = Clock::now();
  detail::InsertionOrderDelaunay built = detail::delaunay_in_insertion_order(points, options.trace, stats, t0);
  Mesh& mesh = built.mesh;
  const std::vector<VertexId>& order = built.order;
  const std::vector<std::pair<VertexId, VertexId>>& dups = built.dups;
  if (stats) stats->insert_seconds = seconds_since(t0);

  if (options.keep_ghosts) {
    std::vector<HalfEdgeId>& ve = detail::MeshEditor(mesh).out_edges();
    const std::vector<VertexId>& tv = detail::MeshEditor(mesh).triangle_vertices();
    for (HalfEdgeId e = 0; e < tv.size(); ++e)
      if (tv[e] < n) ve[tv[e]] = e;
  } else {
    mesh.compact();
  }

  // Back to input numbering: vertex ids become input indices.
  for (VertexId& v : detail::MeshEditor(mesh).triangle_vertices())
    if (v < n) v = order[v];
  if (options.trace) detail::TraceAccess::renumber(*options.trace, order, n);
  {
    std::vector<HalfEdgeId>& ve = detail::MeshEditor(mesh).out_edges();
    std::vector<HalfEdgeId> moved(n);
    for (std::size_t k = 0; k < n; ++k) moved[order[k]] = ve[k];
    ve.swap(moved);
  }
  detail::MeshEditor(mesh).points().assign(points.begin(), points.end());
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
    for (VertexId& v : detail::MeshEditor(mesh).triangle_vertices())
      if (v < n) v = first[v];
    if (options.trace) detail::TraceAccess::renumber(*options.trace, first, n);
    std::vector<HalfEdgeId>& ve = detail::MeshEditor(mesh).out_edges();
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
  return std::move(built.mesh);
}

VertexId insert_delaunay_vertex(Mesh& mesh, const Point& p, TriId hint) {
  check_coordinates(std::span<const Point>(&p, 1));
  detail::DelaunayInserter inserter(mesh);
  return inserter.insert_point(p, hint).vertex;
}

}  // namespace deltamesh

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


// The bulk builder: the same split + Lawson flips as detail::DelaunayInserter,
// on the raw arrays and without per-vertex out-edges (compact() rebuilds
// them), because this loop is where a 10^6-point triangulation spends its time.
class BulkBuilder {
 public:
  explicit BulkBuilder(Mesh& mesh)
      : mesh_(mesh), v_(mesh.tri_v_mut()), tw_(mesh.twin_mut()), p_(mesh.points().data()) {
    stack_.reserve(64);
  }

  // Inserts vertex v; returns v, or the vertex it coincides with. `hint`
  // is updated to a triangle near v for the next walk.
  VertexId insert(VertexId v, TriId& hint) {
    const Point& p = p_[v];
    TriId t = hint;
    HalfEdgeId from = kNone;  // the half-edge we entered t through
    for (;;) {
      const HalfEdgeId base = 3 * t;
      // Start after the entry edge: it cannot be an exit.
      const HalfEdgeId first = from == kNone ? base : next_edge(from);
      HalfEdgeId exit = kNone, zero = kNone;
      int zeros = 0;
      HalfEdgeId e = first;
      for (int k = 0; k < 3; ++k, e = next_edge(e)) {
        if (e == from) continue;
        const double o = orient2d(p_[v_[e]], p_[v_[next_edge(e)]], p);
        if (o < 0) {
          exit = e;
          break;
        }
        if (o == 0) {
          ++zeros;
          zero = e;
        }
      }
      if (exit == kNone) {
        if (zeros == 2) {  // on a vertex: the one both zero edges share
          for (int i = 0; i < 3; ++i)
            if (p_[v_[base + i]] == p) {
              hint = t;
              return v_[base + i];
            }
        }
        if (zeros >= 1) {
          const HalfEdgeId f = tw_[zero];
          const HalfEdgeId g0 = mesh_.split_edge(zero, v);
          push(prev_edge(zero));
          push(g0 + 1);
          push(prev_edge(f));
          push(next_edge(tw_[zero]));
        } else {
          split(t, v);
        }
        break;
      }
      from = tw_[exit];
      t = tri_of(from);
      if (is_ghost(t)) {
        split(t, v);
        break;
      }
    }
    legalize(v);
    hint = real_near(last_);
    return v;
  }

 private:
  bool is_ghost(TriId t) const {
    return v_[3 * t] == kInfinite || v_[3 * t + 1] == kInfinite || v_[3 * t + 2] == kInfinite;
  }
  void push(HalfEdgeId e) { stack_.push_back(e); }
  // t itself, or the real triangle across a ghost's hull edge.
  TriId real_near(TriId t) const {
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i;
      if (v_[e] == kInfinite) return tri_of(tw_[next_edge(e)]);
    }
    return t;
  }

  // Triangle t = (a, b, c) becomes (a, b, v) + new (b, c, v) + new (c, a, v).
  void split(TriId t, VertexId v) {
    const HalfEdgeId e0 = 3 * t, e1 = e0 + 1, e2 = e0 + 2;
    const VertexId a = v_[e0], b = v_[e1], c = v_[e2];
    const HalfEdgeId tw_bc = tw_[e1], tw_ca = tw_[e2];
    const HalfEdgeId g0 = static_cast<HalfEdgeId>(v_.size()), h0 = g0 + 3;
    v_.insert(v_.end(), {b, c, v, c, a, v});
    tw_.insert(tw_.end(), {tw_bc, h0 + 2, e1, tw_ca, e2, g0 + 1});
    tw_[tw_bc] = g0;
    tw_[tw_ca] = h0;
    v_[e2] = v;
    tw_[e1] = g0 + 2;
    tw_[e2] = h0 + 1;
    push(e0);
    push(g0);
    push(h0);
  }

  void flip(HalfEdgeId e, HalfEdgeId f) {
    const HalfEdgeId e1 = next_edge(e), e2 = prev_edge(e);
    const HalfEdgeId f1 = next_edge(f), f2 = prev_edge(f);
    const VertexId a = v_[e], b = v_[e1], c = v_[e2], d = v_[f2];
    const HalfEdgeId tw_bc = tw_[e1], tw_ca = tw_[e2], tw_ad = tw_[f1], tw_db = tw_[f2];
    v_[e] = c;
    v_[e1] = a;
    v_[e2] = d;
    v_[f] = d;
    v_[f1] = b;
    v_[f2] = c;
    tw_[e] = tw_ca;
    tw_[tw_ca] = e;
    tw_[e1] = tw_ad;
    tw_[tw_ad] = e1;
    tw_[f] = tw_db;
    tw_[tw_db] = f;
    tw_[f1] = tw_bc;
    tw_[tw_bc] = f1;
    tw_[e2] = f2;
    tw_[f2] = e2;
  }

  void legalize(VertexId v) {
    const Point& p = p_[v];
    while (!stack_.empty()) {
      const HalfEdgeId e = stack_.back();
      stack_.pop_back();
      last_ = tri_of(e);
      const HalfEdgeId f = tw_[e];
      const VertexId a = v_[e], b = v_[next_edge(e)], d = v_[prev_edge(f)];
      bool flip_it;
      if (d == kInfinite)
        flip_it = false;
      else if (b == kInfinite)
        flip_it = orient2d(p_[a], p_[d], p) > 0;
      else if (a == kInfinite)
        flip_it = orient2d(p_[d], p_[b], p) > 0;
      else
        flip_it = incircle(p_[a], p_[b], p, p_[d]) > 0;
      if (!flip_it) continue;
      flip(e, f);
      push(next_edge(e));
      push(f);
    }
  }

  Mesh& mesh_;
  std::vector<VertexId>& v_;
  std::vector<HalfEdgeId>& tw_;
  const Point* p_;
  std::vector<HalfEdgeId> stack_;
  TriId last_ = 0;
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

  std::vector<VertexId> dup_of;  // in insertion order, only when asked for
  if (stats) dup_of.assign(n, kNone);
  BulkBuilder builder(mesh);
  std::size_t duplicates = 0;
  TriId hint = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (k == i1 || k == i2) continue;
    const VertexId v = static_cast<VertexId>(k);
    const VertexId got = builder.insert(v, hint);
    if (got != v) {
      ++duplicates;
      if (stats) dup_of[k] = got;
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

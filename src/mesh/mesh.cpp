#include "deltamesh/mesh.hpp"

#include <algorithm>
#include <cassert>

#include "deltamesh/predicates.hpp"
#include "mesh/flip.hpp"
#include "mesh/locate.hpp"
#include "mesh/split.hpp"

namespace deltamesh {

namespace {
// x's twin becomes y, and y's x when y exists.
void relink(std::vector<HalfEdgeId>& twin, HalfEdgeId x, HalfEdgeId y) {
  twin[x] = y;
  if (y != kNone) twin[y] = x;
}
}  // namespace

HalfEdgeId Mesh::find_edge(VertexId a, VertexId b) const {
  HalfEdgeId found = kNone;
  for_each_out_edge(a, [&](HalfEdgeId e) {
    if (dest(e) == b) {
      found = e;
      return false;
    }
    return true;
  });
  return found;
}

void Mesh::reserve(std::size_t vertices, std::size_t triangles) {
  points_.reserve(vertices);
  vert_edge_.reserve(vertices);
  tri_v_.reserve(3 * triangles);
  twin_.reserve(3 * triangles);
}

TriId Mesh::add_triangle(VertexId a, VertexId b, VertexId c) {
  TriId t;
  if (!free_.empty()) {
    t = free_.back();
    free_.pop_back();
  } else {
    t = static_cast<TriId>(tri_v_.size() / 3);
    tri_v_.resize(tri_v_.size() + 3);
    twin_.resize(twin_.size() + 3);
    if (!edge_flags_.empty()) edge_flags_.resize(tri_v_.size(), 0);
    if (!edge_markers_.empty()) edge_markers_.resize(tri_v_.size(), 0);
    if (num_triangle_attributes_ > 0)
      triangle_attributes_.resize((t + 1) * num_triangle_attributes_, 0.0);
    if (!triangle_area_bounds_.empty()) triangle_area_bounds_.resize(t + 1, -1.0);
  }
  const HalfEdgeId e = 3 * t;
  tri_v_[e] = a;
  tri_v_[e + 1] = b;
  tri_v_[e + 2] = c;
  twin_[e] = twin_[e + 1] = twin_[e + 2] = kNone;
  if (!edge_flags_.empty()) edge_flags_[e] = edge_flags_[e + 1] = edge_flags_[e + 2] = 0;
  if (!edge_markers_.empty()) edge_markers_[e] = edge_markers_[e + 1] = edge_markers_[e + 2] = 0;
  note_added(t);
  compacted_ = false;
  return t;
}

void Mesh::remove_triangle(TriId t) {
  note_removed(t);
  for (int i = 0; i < 3; ++i) {
    const HalfEdgeId e = 3 * t + i;
    if (twin_[e] != kNone && twin_[twin_[e]] == e) twin_[twin_[e]] = kNone;
    twin_[e] = kNone;
    tri_v_[e] = kNone;
  }
  free_.push_back(t);
}

void Mesh::set_edge_flags(HalfEdgeId e, std::uint8_t flags) {
  if (edge_flags_.empty()) {
    if (flags == 0) return;
    edge_flags_.assign(tri_v_.size(), 0);
  }
  edge_flags_[e] = flags;
}

void Mesh::copy_triangle_data(TriId from, TriId to) {
  const std::size_t na = num_triangle_attributes_;
  for (std::size_t k = 0; k < na; ++k) triangle_attributes_[to * na + k] = triangle_attributes_[from * na + k];
  if (!triangle_area_bounds_.empty()) triangle_area_bounds_[to] = triangle_area_bounds_[from];
}

void Mesh::set_triangle_area_bound(TriId t, double max_area) {
  if (triangle_area_bounds_.empty()) {
    if (max_area <= 0) return;
    triangle_area_bounds_.assign(num_triangle_slots(), -1.0);
  }
  triangle_area_bounds_[t] = max_area;
}

void Mesh::set_edge_marker(HalfEdgeId e, int marker) {
  if (edge_markers_.empty()) {
    if (marker == 0) return;
    edge_markers_.assign(tri_v_.size(), 0);
  }
  edge_markers_[e] = marker;
}

HalfEdgeId Mesh::flip(HalfEdgeId e) {
  assert(twin_[e] != kNone);
  const TriId t1 = tri_of(e), t2 = tri_of(twin_[e]);
  note_removed(t1);
  note_removed(t2);
  const HalfEdgeId cd = detail::flip_arrays<detail::kCarryAll>(detail::MeshArrays::of(*this), e);
  note_added(t1);
  note_added(t2);
  return cd;
}

HalfEdgeId Mesh::split_triangle(TriId t, VertexId p) {
  const VertexId a = tri_v_[3 * t], b = tri_v_[3 * t + 1], c = tri_v_[3 * t + 2];
  note_removed(t);
  const TriId t1 = add_triangle(b, c, p);  // (counted with their final corners)
  const TriId t2 = add_triangle(c, a, p);
  const HalfEdgeId r = detail::split_triangle_arrays<detail::kCarryAll>(detail::MeshArrays::of(*this), t, p, t1, t2);
  note_added(t);
  copy_triangle_data(t, t1);
  copy_triangle_data(t, t2);
  return r;
}

HalfEdgeId Mesh::split_edge(HalfEdgeId e, VertexId p) {
  const HalfEdgeId f = twin_[e];
  const TriId t1 = tri_of(e);
  const VertexId a = tri_v_[e], b = tri_v_[next_edge(e)], c = tri_v_[prev_edge(e)];
  note_removed(t1);
  const TriId t3 = add_triangle(p, b, c);
  TriId t2 = kNone, t4 = kNone;
  if (f != kNone) {
    t2 = tri_of(f);
    note_removed(t2);
    t4 = add_triangle(p, a, tri_v_[prev_edge(f)]);
  }
  const HalfEdgeId g0 = detail::split_edge_arrays<detail::kCarryAll>(detail::MeshArrays::of(*this), e, p, t3, t4);
  note_added(t1);
  copy_triangle_data(t1, t3);
  if (f != kNone) {
    note_added(t2);
    copy_triangle_data(t2, t4);
  }
  return g0;
}

void Mesh::remove_degree3_vertex(VertexId v) {
  // e = v->a in (v,a,b); g = v->b in (v,b,c); h = v->c in (v,c,a).
  const HalfEdgeId e0 = vert_edge_[v], e1 = next_edge(e0), e2 = prev_edge(e0);
  const HalfEdgeId g0 = twin_[e2], g1 = next_edge(g0), g2 = prev_edge(g0);
  const HalfEdgeId h0 = twin_[g2], h1 = next_edge(h0);
  assert(g0 != kNone && h0 != kNone && twin_[prev_edge(h0)] == e0);
  const VertexId a = tri_v_[e1], b = tri_v_[e2], c = tri_v_[g2];
  const HalfEdgeId h2 = prev_edge(h0);
  const HalfEdgeId tw_ca = twin_[h1], tw_bc = twin_[g1];
  const std::uint8_t fl_ca = edge_flags(h1), fl_bc = edge_flags(g1);
  const int m_ca = edge_marker(h1), m_bc = edge_marker(g1);
  const TriId t0 = tri_of(e0);
  remove_triangle(tri_of(g0));
  remove_triangle(tri_of(h0));
  note_removed(t0);
  tri_v_[e0] = c;  // (c, a, b)
  note_added(t0);
  relink(twin_, e0, tw_ca);
  relink(twin_, e2, tw_bc);
  if (!edge_flags_.empty()) {
    edge_flags_[e0] = fl_ca;
    edge_flags_[e2] = fl_bc;
  }
  if (!edge_markers_.empty()) {
    edge_markers_[e0] = m_ca;
    edge_markers_[e2] = m_bc;
  }
  vert_edge_[v] = kNone;
  if (a != kInfinite && vert_edge_[a] == h2) vert_edge_[a] = e1;
  if (b != kInfinite && vert_edge_[b] == g1) vert_edge_[b] = e2;
  if (c != kInfinite && (vert_edge_[c] == g2 || vert_edge_[c] == h1)) vert_edge_[c] = e0;
  compacted_ = false;
}

void Mesh::unsplit_edge(HalfEdgeId g) {
  // g = v->b in (v,b,c); h = v->c in (v,c,a) becomes (b,c,a).
  const HalfEdgeId g1 = next_edge(g), g2 = prev_edge(g);
  const HalfEdgeId h0 = twin_[g2], h1 = next_edge(h0), h2 = prev_edge(h0);
  assert(h0 != kNone);
  const VertexId v = tri_v_[g], b = tri_v_[g1], c = tri_v_[g2], a = tri_v_[h2];
  const HalfEdgeId tw_bc = twin_[g1];
  const std::uint8_t fl_bc = edge_flags(g1);
  const int m_bc = edge_marker(g1);
  // Other side: f = b->v in (b,v,d) becomes (b,a,d); k = d->v in (d,v,a) goes.
  const HalfEdgeId f = twin_[g];
  HalfEdgeId f1 = kNone, f2 = kNone, k0 = kNone, k2 = kNone, tw_ad = kNone;
  std::uint8_t fl_ad = 0;
  int m_ad = 0;
  VertexId d = kNone;
  if (f != kNone) {
    f1 = next_edge(f);
    f2 = prev_edge(f);
    k0 = twin_[f1];
    assert(k0 != kNone);
    k2 = prev_edge(k0);
    d = tri_v_[f2];
    tw_ad = twin_[k2];
    fl_ad = edge_flags(k2);
    m_ad = edge_marker(k2);
  }
  remove_triangle(tri_of(g));
  if (f != kNone) remove_triangle(tri_of(k0));
  const TriId t1 = tri_of(h0);
  note_removed(t1);
  tri_v_[h0] = b;  // (b, c, a)
  note_added(t1);
  relink(twin_, h0, tw_bc);
  if (!edge_flags_.empty()) edge_flags_[h0] = fl_bc;
  if (!edge_markers_.empty()) edge_markers_[h0] = m_bc;
  twin_[h2] = kNone;
  if (f != kNone) {
    const TriId t3 = tri_of(f);
    note_removed(t3);
    tri_v_[f1] = a;  // (b, a, d)
    note_added(t3);
    relink(twin_, f1, tw_ad);
    if (!edge_flags_.empty()) edge_flags_[f1] = fl_ad;
    if (!edge_markers_.empty()) edge_markers_[f1] = m_ad;
    link(h2, f);
  }
  vert_edge_[v] = kNone;
  if (b != kInfinite && vert_edge_[b] == g1) vert_edge_[b] = h0;
  if (c != kInfinite && vert_edge_[c] == g2) vert_edge_[c] = h1;
  if (f != kNone) {
    if (a != kInfinite && vert_edge_[a] == k2) vert_edge_[a] = f1;
    if (d != kInfinite && vert_edge_[d] == k0) vert_edge_[d] = f2;
  }
  compacted_ = false;
}

Location Mesh::locate(const Point& p, TriId start) const {
  const std::size_t slots = num_triangle_slots();
  if (start == kNone || start >= slots || is_dead(start)) {
    start = kNone;
    for (TriId t = 0; t < slots; ++t)
      if (!is_dead(t)) {
        start = t;
        break;
      }
    if (start == kNone) return Location{};
  }
  const TriId t = detail::real_triangle_near(tri_v_.data(), twin_.data(), start);
  // A visibility walk visits at most every triangle once per pass when it
  // cannot cycle; the bound only guards against a corrupt mesh.
  detail::RandomRotationOrder order{0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(t)};
  return detail::visibility_walk(tri_v_.data(), twin_.data(), points_.data(), p, t, order, 4 * slots + 16).loc;
}

void Mesh::compact() {
  // Ghost and dead triangles are few (a hull's worth), so rather than
  // renumbering everything, move the last live triangles into their slots.
  const std::size_t na = num_triangle_attributes_;
  std::vector<TriId> holes;
  std::size_t slots = num_triangle_slots();
  for (TriId t = 0; t < slots; ++t) {
    if (is_dead(t)) {
      holes.push_back(t);
    } else if (is_ghost(t)) {
      holes.push_back(t);
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId tw = twin_[3 * t + i];
        if (tw != kNone && !is_ghost(tri_of(tw))) twin_[tw] = kNone;
      }
    }
  }
  auto live = [&](TriId t) { return !is_dead(t) && !is_ghost(t); };
  std::size_t h = 0;
  while (h < holes.size()) {
    while (slots > 0 && !live(static_cast<TriId>(slots - 1))) --slots;
    const TriId hole = holes[h++];
    if (hole >= slots) break;
    const TriId from = static_cast<TriId>(slots - 1);
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId o = 3 * from + i, m = 3 * hole + i;
      tri_v_[m] = tri_v_[o];
      twin_[m] = twin_[o];
      if (twin_[m] != kNone) twin_[twin_[m]] = m;
      if (!edge_flags_.empty()) edge_flags_[m] = edge_flags_[o];
      if (!edge_markers_.empty()) edge_markers_[m] = edge_markers_[o];
    }
    copy_triangle_data(from, hole);
    tri_v_[3 * from] = kNone;  // now dead
    --slots;
  }
  while (slots > 0 && !live(static_cast<TriId>(slots - 1))) --slots;
  tri_v_.resize(3 * slots);
  twin_.resize(3 * slots);
  if (!edge_flags_.empty()) edge_flags_.resize(3 * slots);
  if (!edge_markers_.empty()) edge_markers_.resize(3 * slots);
  triangle_attributes_.resize(slots * na);
  if (!triangle_area_bounds_.empty()) triangle_area_bounds_.resize(slots);
  // No shrink_to_fit: reallocating would double the peak memory here.
  free_.clear();
  std::fill(vert_edge_.begin(), vert_edge_.end(), kNone);
  for (HalfEdgeId e = 0; e < tri_v_.size(); ++e) vert_edge_[tri_v_[e]] = e;
  // A boundary vertex starts its fan at its boundary edge (most clockwise).
  for (HalfEdgeId e = 0; e < twin_.size(); ++e)
    if (twin_[e] == kNone) vert_edge_[tri_v_[e]] = e;
  live_real_ = slots;
  compacted_ = true;
}

void Mesh::recount() {
  live_real_ = 0;
  for ([[maybe_unused]] TriId t : triangles()) ++live_real_;
}

std::size_t Mesh::memory_bytes() const {
  return points_.capacity() * sizeof(Point) + tri_v_.capacity() * sizeof(VertexId) +
         twin_.capacity() * sizeof(HalfEdgeId) + vert_edge_.capacity() * sizeof(HalfEdgeId) +
         edge_flags_.capacity() + edge_markers_.capacity() * sizeof(int) + free_.capacity() * sizeof(TriId) +
         vertex_markers_.capacity() * sizeof(int) +
         (vertex_attributes_.capacity() + triangle_attributes_.capacity() + triangle_area_bounds_.capacity()) *
             sizeof(double);
}

std::vector<VertexId> Mesh::remove_unused_vertices() {
  const std::size_t n = points_.size();
  std::vector<VertexId> map(n, kNone);
  for (VertexId v : tri_v_)
    if (v < n) map[v] = 0;
  VertexId next = 0;
  const std::size_t na = num_vertex_attributes_;
  for (std::size_t v = 0; v < n; ++v) {
    if (map[v] == kNone) continue;
    map[v] = next;
    points_[next] = points_[v];
    vert_edge_[next] = vert_edge_[v];
    if (!vertex_markers_.empty()) vertex_markers_[next] = vertex_markers_[v];
    for (std::size_t k = 0; k < na; ++k) vertex_attributes_[next * na + k] = vertex_attributes_[v * na + k];
    ++next;
  }
  points_.resize(next);
  vert_edge_.resize(next);
  if (!vertex_markers_.empty()) vertex_markers_.resize(next);
  vertex_attributes_.resize(std::size_t{next} * na);
  for (VertexId& v : tri_v_)
    if (v < n) v = map[v];
  return map;
}

}  // namespace deltamesh

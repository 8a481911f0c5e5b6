// The Fast method's first attempt: vertices inserted along the segment chains
// (a polygon's vertices in polygon order), each segment inserted as soon as
// both its endpoints are in.
//
// Inserted this way, a segment usually joins two vertices the triangulation
// has only just reached, and is an edge already or crosses few edges: on a
// star-shaped polygon the classic order (Delaunay of all vertices, then the
// segments) recovers ten times more crossed edges. The order has a bad case
// of its own: points along a convex curve, each inserted next to the last,
// make Lawson flips sweep the whole triangulation (quadratic), and chains that
// jump around make point location walk far. So the attempt runs on a budget
// of flips and walk steps proportional to the vertices inserted, and gives up
// (the caller starts over the classic way) when it is exceeded.
#include <algorithm>
#include <limits>
#include <span>
#include <string>

#include "algo/cdt_builder.hpp"
#include "core/spatial_sort.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/legalize.hpp"
#include "mesh/locate.hpp"
#include "mesh/split.hpp"
#include "mesh/editor.hpp"

namespace deltamesh::detail {

namespace {

// The vertices of `pslg` in insertion order: depth-first along the segments
// (a chain in chain order, a polygon in polygon order), components ordered
// along a Hilbert curve by their first vertex, then the vertices on no
// segment along the Hilbert curve.
std::vector<VertexId> chain_order(const Pslg& pslg, const std::vector<std::uint32_t>& start,
                                  const std::vector<std::uint32_t>& inc) {
  const std::size_t n = pslg.points.size();
  auto other = [&](std::uint32_t k, VertexId u) {
    const Segment& s = pslg.segments[inc[k]];
    return s.a == u ? s.b : s.a;
  };
  std::vector<VertexId> order;
  order.reserve(n);
  // One polygon through every vertex: its order, read off directly.
  bool single = n > 0;
  for (std::size_t v = 0; v < n && single; ++v) single = start[v + 1] - start[v] == 2;
  if (single) {
    VertexId prev = 0, cur = other(start[0], 0);
    order.push_back(0);
    while (cur != 0 && order.size() < n) {
      order.push_back(cur);
      const VertexId a = other(start[cur], cur), b = other(start[cur] + 1, cur);
      const VertexId next = a == prev ? b : a;
      prev = cur;
      cur = next;
    }
    if (cur == 0 && order.size() == n) return order;
    order.clear();
  }
  // Otherwise components go along a Hilbert curve (by the first vertex met),
  // each from a chain's end (degree 1) when there is one, depth first; then
  // the vertices on no segment, along the curve.
  const std::vector<VertexId> hilbert = hilbert_order(pslg.points);
  std::vector<char> seen(n, 0);
  std::vector<VertexId> roots;
  {
    std::vector<char> in_comp(n, 0);
    std::vector<VertexId> stack;
    for (VertexId s : hilbert) {
      if (in_comp[s] || start[s] == start[s + 1]) continue;
      VertexId root = s;
      stack.push_back(s);
      in_comp[s] = 1;
      while (!stack.empty()) {
        const VertexId u = stack.back();
        stack.pop_back();
        if (start[u + 1] - start[u] == 1 && (start[root + 1] - start[root] != 1)) root = u;
        for (std::uint32_t k = start[u]; k < start[u + 1]; ++k) {
          const VertexId w = other(k, u);
          if (!in_comp[w]) {
            in_comp[w] = 1;
            stack.push_back(w);
          }
        }
      }
      roots.push_back(root);
    }
  }
  std::vector<std::pair<VertexId, std::uint32_t>> dfs;  // vertex, next adjacency slot
  for (VertexId root : roots) {
    seen[root] = 1;
    order.push_back(root);
    dfs.push_back({root, start[root]});
    while (!dfs.empty()) {
      auto& [u, k] = dfs.back();
      while (k < start[u + 1] && seen[other(k, u)]) ++k;
      if (k == start[u + 1]) {
        dfs.pop_back();
        continue;
      }
      const VertexId w = other(k++, u);
      seen[w] = 1;
      order.push_back(w);
      dfs.push_back({w, start[w]});
    }
  }
  for (VertexId v : hilbert)
    if (!seen[v]) order.push_back(v);
  return order;
}

}  // namespace

VertexId CdtBuilder::insert_vertex(VertexId v, HalfEdgeId near) {
  const TriId t = real_triangle_near(tv_.data(), tw_.data(), tri_of(near));
  // Visibility walk; the edges are tried in random order, which cannot cycle.
  const WalkResult w =
      visibility_walk(tv_.data(), tw_.data(), pts_.data(), pts_[v], t, RandomPairOrder{rng_}, tv_.size() + 16);
  walk_steps_ += w.steps;
  const Location& loc = w.loc;
  if (loc.tri == kNone) throw InternalError("CdtBuilder::insert_vertex", "point location does not end");
  if (loc.kind == Location::Kind::OnEdge && (flags_[loc.edge] & kConstrained))
    ++st_.vertices_on_segments;  // a vertex exactly on a segment inserted already splits it
  if ((loc.kind == Location::Kind::InTriangle || loc.kind == Location::Kind::Outside) &&
      next_slot_ + 2 <= reserved_slots_) {
    split_and_legalize(loc.tri, v);
    return v;
  }
  return inserter_.insert_located(loc, v).vertex;
}

void CdtBuilder::reserve_slots(std::size_t slots) {
  next_slot_ = mesh_.num_triangle_slots();
  reserved_slots_ = next_slot_ + slots;
  tv_.resize(3 * reserved_slots_, kNone);  // dead until used
  tw_.resize(3 * reserved_slots_, kNone);
  flags_.resize(3 * reserved_slots_, 0);
  if (ids_) seg_of_.resize(3 * reserved_slots_, 0);
}

void CdtBuilder::release_slots() {
  // Unused reserved slots go when nothing was added after them (else they
  // stay, dead).
  if (tv_.size() / 3 == reserved_slots_) {
    tv_.resize(3 * next_slot_);
    tw_.resize(3 * next_slot_);
    flags_.resize(3 * next_slot_);
    if (ids_) seg_of_.resize(3 * next_slot_);
  }
  reserved_slots_ = next_slot_ = 0;
  detail::MeshEditor(mesh_).recount();
}

// Triangle t = (a, b, c), or a ghost, split at v into (a, b, v) in t and
// (b, c, v), (c, a, v) in two reserved slots; then Lawson flips that keep
// constrained edges. The mesh kernels DelaunayInserter uses, inlined on the
// raw arrays without the Mesh's bookkeeping (this loop is the chain order's
// cost; release_slots() recounts).
void CdtBuilder::split_and_legalize(TriId t, VertexId v) {
  // Raw pointers: nothing here reallocates the arrays.
  MeshArrays arrays;
  arrays.tv = tv_.data();
  arrays.tw = tw_.data();
  arrays.flags = flags_.data();
  arrays.markers = ids_ ? seg_of_.data() : nullptr;
  arrays.out = ve_.data();
  arrays.pts = pts_.data();
  constexpr unsigned kCarry = kCarryFlags | kCarryMarkers | kCarryOutEdges;
  const TriId t1 = static_cast<TriId>(next_slot_), t2 = t1 + 1;
  next_slot_ += 2;
  split_triangle_arrays<kCarry>(arrays, t, v, t1, t2);
  // Lawson flips that keep constrained edges, with the static incircle filter.
  const auto in_circle = [this](const Point& pa, const Point& pb, const Point& pc, const Point& pd) {
    return incircle_fast(pa, pb, pc, pd);
  };
  RawTopology<kCarry, decltype(in_circle)> topo(arrays, in_circle);
  legal_.clear();
  legal_.push_back(3 * t);
  legal_.push_back(3 * t1);
  legal_.push_back(3 * t2);
  lean_flips_ += legalize_around_vertex(topo, v, legal_).flips;
}

bool chain_order_cdt(Mesh& mesh, const Pslg& pslg, const CdtOptions& options, CdtStats& st,
                     std::vector<VertexId>& first_copy) {
  const std::size_t n = pslg.points.size();
  check_coordinates(pslg.points);
  // Segments by vertex (zero-length ones left out and counted).
  std::vector<std::uint32_t> start(n + 1, 0);
  for (const Segment& s : pslg.segments)
    if (s.a != s.b) {
      ++start[s.a + 1];
      ++start[s.b + 1];
    } else {
      ++st.zero_length_segments;
    }
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> inc(start[n]);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < pslg.segments.size(); ++i) {
      const Segment& s = pslg.segments[i];
      if (s.a == s.b) continue;
      inc[fill[s.a]++] = i;
      inc[fill[s.b]++] = i;
    }
  }
  const std::vector<VertexId> order = chain_order(pslg, start, inc);
  const std::vector<Point>& pts = pslg.points;
  // The first triangle: the first vertex, the next distinct one, the next one off their line.
  std::size_t i1 = 1;
  while (i1 < n && pts[order[i1]] == pts[order[0]]) ++i1;
  std::size_t i2 = i1 + 1;
  while (i2 < n && orient2d(pts[order[0]], pts[order[i1]], pts[order[i2]]) == 0) ++i2;
  if (i2 >= n) return false;  // the classic path reports it

  mesh = Mesh();
  detail::MeshEditor(mesh).points().assign(pts.begin(), pts.end());
  detail::MeshEditor(mesh).out_edges().assign(n, kNone);
  mesh.reserve(n, 2 * n + 2);
  detail::MeshEditor(mesh).edge_flags().reserve(6 * n + 6);
  VertexId v0 = order[0], v1 = order[i1], v2 = order[i2];
  if (orient2d(pts[v0], pts[v1], pts[v2]) < 0) std::swap(v1, v2);
  make_first_triangle(mesh, v0, v1, v2);
  detail::MeshEditor(mesh).recount();

  first_copy.assign(n, kNone);
  CdtBuilder builder(mesh, pslg, options, st);
  builder.reserve_slots(2 * n);  // a triangulation of n vertices with ghosts has 2n - 4 triangles
  // Inserts the segments of v whose other end is in already.
  auto ready = [&](VertexId v) {
    for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
      const Segment& s = pslg.segments[inc[k]];
      const VertexId w = s.a == v ? s.b : s.a;
      if (first_copy[w] == kNone) continue;
      const VertexId a = first_copy[v], b = first_copy[w];
      if (a == b) {
        ++st.zero_length_segments;
        continue;
      }
      ++st.segments_inserted;
      builder.insert_segment(a, b, inc[k]);
    }
  };
  for (VertexId v : {v0, v1, v2}) {
    first_copy[v] = v;
    ready(v);
  }
  // The walk starts at the nearest of the last few vertices inserted: along
  // a chain the next vertex is near one of them, not always the last (a
  // star's vertices alternate between long and short radii).
  constexpr int kRecent = 4;
  VertexId recent[kRecent] = {v0, v1, v2, v2};
  int next_recent = 0;
  std::size_t inserted = 3;
  for (std::size_t k = 1; k < n; ++k) {
    const VertexId v = order[k];
    if (first_copy[v] != kNone) continue;  // v1, v2
    const Point p = pts[v];
    VertexId from = recent[0];
    double best = std::numeric_limits<double>::infinity();
    for (VertexId r : recent) {  // (r may be a vertex added at a crossing: read the mesh's points)
      const Point& q = mesh.point(r);
      const double dx = q.x - p.x, dy = q.y - p.y, d2 = dx * dx + dy * dy;
      if (d2 < best) {
        best = d2;
        from = r;
      }
    }
    const VertexId got = builder.insert_vertex(v, mesh.out_edge(from));
    first_copy[v] = got;
    if (got >= n)
      ++st.vertices_on_segments;  // exactly where segments inserted already cross: it takes that vertex's place
    else if (got != v)
      ++st.duplicate_vertices;
    recent[next_recent] = got;
    next_recent = (next_recent + 1) % kRecent;
    ready(v);
    ++inserted;
    if (builder.vertex_flips() > 12 * inserted + 4096 || builder.walk_steps() > 24 * inserted + 4096) return false;
  }
  builder.release_slots();
  builder.finish();
  return true;
}

}  // namespace deltamesh::detail

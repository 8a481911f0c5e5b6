// Segments inserted into a finished mesh (see insert_segments.hpp).
//
// The CDT builder (cdt.cpp, cdt_recover.cpp) works on a closed
// triangulation: ghost triangles around a convex hull. A finished mesh is
// not one (a non-convex boundary, holes), so it is closed for the time of
// the insertion: the constrained triangulation of its vertices with its
// boundary edges as segments covers the hull; the regions of it outside the
// mesh (told apart by which side of each boundary edge the mesh lies on) are
// added to the mesh's own triangles as filler, ghosts around. The boundary
// edges are constrained meanwhile, so nothing the builder does (cavities,
// flips) reaches the filler, and each segment is first walked through the
// closed triangulation to make sure it stays in the mesh's triangles. The
// filler and ghosts are then removed and the boundary edges released.
#include "deltamesh/insert_segments.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "algo/cdt_builder.hpp"
#include "algo/vertex_data.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/triangulate.hpp"
#include "mesh/edge_rules.hpp"
#include "mesh/locate.hpp"
#include "mesh/editor.hpp"

namespace deltamesh {

namespace {

// The half-edges of a straight chain of edges of the compacted mesh from a
// to b (appended to `chain`), or false when the segment is not one.
bool find_chain(const Mesh& mesh, VertexId a, VertexId b, std::vector<HalfEdgeId>& chain) {
  const Point& pa = mesh.point(a);
  const Point& pb = mesh.point(b);
  const bool use_x = std::abs(pb.x - pa.x) >= std::abs(pb.y - pa.y);
  auto along = [&](const Point& p) { return use_x ? (pb.x >= pa.x ? p.x : -p.x) : (pb.y >= pa.y ? p.y : -p.y); };
  const std::size_t start = chain.size();
  VertexId cur = a;
  for (std::size_t guard = 0; cur != b; ++guard) {
    if (guard > mesh.num_vertices()) break;
    // Neighbours of cur: the dest and the third vertex of each triangle
    // around it (the latter reaches the last edge of a boundary fan).
    HalfEdgeId step = kNone;
    VertexId next = kNone;
    mesh.for_each_out_edge(cur, [&](HalfEdgeId g) {
      for (const HalfEdgeId c : {g, prev_edge(g)}) {  // cur->w, and w->cur
        const VertexId w = c == g ? mesh.dest(c) : mesh.origin(c);
        const Point& pw = mesh.point(w);
        if (w == b || (orient2d(pa, pb, pw) == 0 && along(pw) > along(mesh.point(cur)) && along(pw) < along(pb))) {
          if (next == kNone || along(pw) < along(mesh.point(next))) {
            next = w;
            step = c;
          }
        }
      }
      return true;
    });
    if (step == kNone) break;
    chain.push_back(step);
    cur = next;
  }
  if (cur == b) return true;
  chain.resize(start);
  return false;
}

// The mesh closed with filler and ghost triangles; slots below `inside_slots`
// are the mesh's own triangles (same ids), the rest outside it.
struct Closed {
  Mesh mesh;
  std::size_t inside_slots = 0;
  std::vector<std::array<VertexId, 3>> filler;  // the outside triangles as built, to check they stay
  std::vector<HalfEdgeId> boundary;             // the mesh's boundary half-edges (same ids in `mesh`)
};

Closed close_mesh(const Mesh& m) {
  const std::size_t n = m.num_vertices();
  const std::size_t nt = m.num_triangle_slots();
  Closed c;
  c.inside_slots = nt;

  // The constrained triangulation of the used vertices and the boundary edges.
  std::vector<VertexId> local(n, kNone), global;
  for (VertexId v : m.triangle_vertices())
    if (local[v] == kNone) {
      local[v] = static_cast<VertexId>(global.size());
      global.push_back(v);
    }
  Pslg fill;
  fill.points.reserve(global.size());
  for (VertexId v : global) fill.points.push_back(m.point(v));
  for (HalfEdgeId e = 0; e < 3 * nt; ++e)
    if (m.twin(e) == kNone) {
      c.boundary.push_back(e);
      fill.segments.push_back({local[m.origin(e)], local[m.dest(e)], 0});
    }
  CdtOptions copt;
  copt.strict = true;
  CdtStats cst;
  Mesh cdt;
  try {
    cdt = constrained_triangulation(fill, copt, &cst);
  } catch (const IntersectingSegments& e) {
    const Segment& s = fill.segments[e.first()];
    throw InputError("the mesh's boundary crosses itself (at boundary edge " + std::to_string(global[s.a]) + "-" +
                     std::to_string(global[s.b]) + "): its triangles overlap");
  }
  if (cst.duplicate_vertices > 0) throw InputError("two vertices of the mesh's triangles are at the same point");
  if (cst.vertices_on_segments > 0 || cst.overlaps_merged > 0 || cdt.num_vertices() != global.size())
    throw InputError("a vertex of the mesh lies on one of its boundary edges: its triangles overlap or do not meet edge to edge");

  // Regions of the triangulation (pieces between boundary edges), each
  // inside the mesh or outside it, told by the sides of the boundary edges.
  const std::size_t cslots = cdt.num_triangle_slots();
  std::vector<std::uint32_t> region(cslots, kNone);
  std::uint32_t regions = 0;
  std::vector<TriId> stack;
  for (TriId s = 0; s < cslots; ++s) {
    if (region[s] != kNone || cdt.is_dead(s)) continue;
    region[s] = regions;
    stack.push_back(s);
    while (!stack.empty()) {
      const TriId t = stack.back();
      stack.pop_back();
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        const HalfEdgeId f = cdt.twin(e);
        if (cdt.is_constrained(e) || f == kNone || region[tri_of(f)] != kNone) continue;
        region[tri_of(f)] = regions;
        stack.push_back(tri_of(f));
      }
    }
    ++regions;
  }
  std::vector<std::int8_t> side(regions, -1);  // 1 inside, 0 outside
  auto vote = [&](TriId t, std::int8_t s) {
    std::int8_t& r = side[region[t]];
    if (r != -1 && r != s) throw InputError("the mesh's triangles overlap (its boundary encloses itself)");
    r = s;
  };
  for (HalfEdgeId e : c.boundary) {
    const HalfEdgeId h = cdt.find_edge(local[m.origin(e)], local[m.dest(e)]);
    if (h == kNone || cdt.is_ghost(tri_of(h)))
      throw InputError("the mesh's triangles overlap (boundary edge " + std::to_string(m.origin(e)) + "-" +
                       std::to_string(m.dest(e)) + " has triangles on both sides)");
    vote(tri_of(h), 1);
    vote(tri_of(cdt.twin(h)), 0);
  }
  std::size_t inside = 0;
  for (TriId t = 0; t < cslots; ++t)
    if (cdt.is_real(t) && side[region[t]] == 1) ++inside;
  if (inside != m.num_triangles())
    throw InputError("the mesh's triangles overlap: " + std::to_string(m.num_triangles()) +
                     " triangles cover what " + std::to_string(inside) + " do when they meet edge to edge");

  // The closed mesh: the mesh's triangles (same slots), filler, ghosts.
  Mesh& out = c.mesh;
  out.reserve(n, cslots + nt);
  for (const Point& p : m.points()) out.add_vertex(p);
  const std::size_t na = m.num_triangle_attributes();
  out.set_num_triangle_attributes(na);
  for (TriId t = 0; t < nt; ++t) {
    const auto v = m.triangle(t);
    out.add_triangle(v[0], v[1], v[2]);
  }
  std::copy_n(m.triangle_attributes().begin(), std::min(m.triangle_attributes().size(), nt * na),
              out.triangle_attributes().begin());
  if (m.has_triangle_area_bounds())
    for (TriId t = 0; t < nt; ++t) out.set_triangle_area_bound(t, m.triangle_area_bound(t));
  auto to_global = [&](VertexId v) { return v == kInfinite ? kInfinite : global[v]; };
  for (int pass = 0; pass < 2; ++pass)  // filler first, then ghosts
    for (TriId t = 0; t < cslots; ++t) {
      if (cdt.is_dead(t) || cdt.is_ghost(t) != (pass == 1) || side[region[t]] == 1) continue;
      const auto v = cdt.triangle(t);
      const std::array<VertexId, 3> g = {to_global(v[0]), to_global(v[1]), to_global(v[2])};
      out.add_triangle(g[0], g[1], g[2]);
      if (pass == 0) c.filler.push_back(g);
    }
  // Twins: the mesh's own; the rest matched by their undirected edge.
  std::vector<HalfEdgeId>& tw = detail::MeshEditor(out).twins();
  for (HalfEdgeId e = 0; e < 3 * nt; ++e) tw[e] = m.twin(e);
  struct Key {
    std::uint64_t edge;
    HalfEdgeId half;
  };
  std::vector<Key> keys;
  for (HalfEdgeId e = 0; e < tw.size(); ++e)
    if (tw[e] == kNone) keys.push_back({edge_key(out.origin(e), out.dest(e)), e});
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) { return x.edge < y.edge; });
  for (std::size_t i = 0; i < keys.size(); i += 2) {
    if (i + 1 >= keys.size() || keys[i].edge != keys[i + 1].edge ||
        out.origin(keys[i].half) != out.dest(keys[i + 1].half))
      throw InternalError("close_mesh", "the filled mesh does not close");
    out.link(keys[i].half, keys[i + 1].half);
  }
  for (HalfEdgeId e = 0; e < tw.size(); ++e)
    if (out.origin(e) != kInfinite) out.set_out_edge(out.origin(e), e);
  return c;
}

// Does the segment from a to b stay in the mesh's own triangles (slots below
// `inside`) of the closed mesh? A walk along it (as CdtBuilder::trace does):
// around each vertex reached, the triangle it enters or the edge it runs
// along, then through the triangles it crosses to the next vertex on it.
bool stays_inside(Mesh& c, std::size_t inside, VertexId a, VertexId b) {
  const Point pa = c.point(a), pb = c.point(b);
  auto in = [&](HalfEdgeId e) { return tri_of(e) < inside; };
  const VertexId* tv = detail::MeshEditor(c).triangle_vertices().data();
  const HalfEdgeId* tw = detail::MeshEditor(c).twins().data();
  const Point* pts = c.points().data();
  const std::size_t limit = c.triangle_vertices().size() + 3;
  VertexId cur = a;
  for (std::size_t guard = 0; cur != b; ++guard) {
    if (guard > c.num_vertices()) throw InternalError("stays_inside", "the walk along a segment does not end");
    const detail::SegmentExit ex = detail::segment_exit(tv, tw, pts, c.out_edge(cur), c.point(cur), pa, pb, limit);
    if (ex.kind == detail::SegmentExit::Kind::Along) {
      if (!in(ex.edge) && !in(c.twin(ex.edge))) return false;
      cur = ex.vertex;
      continue;
    }
    if (ex.kind == detail::SegmentExit::Kind::None)
      throw InternalError("stays_inside", "no triangle around a vertex meets the segment");
    const detail::SegmentWalk w = detail::walk_segment(
        tv, tw, pts, pa, pb, b, ex.edge, [&](HalfEdgeId h) { return in(h) && in(tw[h]); }, limit);
    switch (w.kind) {
      case detail::SegmentWalk::Kind::Reached: cur = b; break;
      case detail::SegmentWalk::Kind::OnVertex: cur = w.vertex; break;
      case detail::SegmentWalk::Kind::Stopped: return false;
      case detail::SegmentWalk::Kind::LeftHull:
      case detail::SegmentWalk::Kind::Overrun: throw InternalError("stays_inside", "the walk along a segment does not end");
    }
  }
  return true;
}

using Clock = std::chrono::steady_clock;

}  // namespace

std::size_t make_constrained_delaunay(Mesh& mesh) {
  if (!mesh.compacted()) mesh.compact();
  return detail::constrained_lawson_flips(mesh);
}

void insert_segments(Mesh& mesh, std::span<const Segment> segments, const InsertSegmentsOptions& options,
                     InsertSegmentsStats* stats) {
  const auto t0 = Clock::now();
  InsertSegmentsStats local;
  InsertSegmentsStats& st = stats ? *stats : local;
  st = InsertSegmentsStats{};
  st.segments = segments.size();
  if (!mesh.compacted()) mesh.compact();
  const std::size_t n = mesh.num_vertices();
  if (segments.size() >= (std::size_t{1} << 30)) throw InputError("too many segments");

  // Every endpoint a vertex of some triangle; each segment a chain already?
  std::vector<HalfEdgeId> chains;
  std::vector<std::size_t> chain_end(segments.size(), 0);  // chains[chain_end[i-1] .. chain_end[i])
  std::size_t missing = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    if (s.a >= n || s.b >= n)
      throw SegmentError(i, s.a, s.b, "refers to a vertex that does not exist (there are " + std::to_string(n) + ")");
    if (s.a != s.b) {
      if (mesh.out_edge(s.a) == kNone || mesh.out_edge(s.b) == kNone)
        throw SegmentError(i, s.a, s.b, "has an endpoint that is in no triangle of the mesh");
      if (find_chain(mesh, s.a, s.b, chains))
        ++st.already_present;
      else
        ++missing;
    } else {
      ++st.zero_length;
    }
    chain_end[i] = chains.size();
  }

  if (missing == 0) {
    // Constrain the chains; in reverse order with nonzero markers
    // overwriting, so the lowest-numbered nonzero marker stays.
    for (std::size_t i = segments.size(); i-- > 0;) {
      const int marker = segments[i].marker;
      for (std::size_t k = i ? chain_end[i - 1] : 0; k < chain_end[i]; ++k)
        if (marker != 0 || !mesh.is_constrained(chains[k])) mesh.constrain_edge(chains[k], marker);
    }
  } else {
    // Work list of segments for the builder, whose segment ids are indices
    // into it: the given segments, the mesh's constrained edges, then the
    // boundary edges that are not (constrained only while filler is there).
    const std::size_t k = segments.size();
    Closed c = close_mesh(mesh);
    Mesh& cm = c.mesh;
    Pslg work;
    work.points.assign(mesh.points().begin(), mesh.points().end());
    work.segments.assign(segments.begin(), segments.end());
    std::vector<std::uint8_t>& flags = detail::MeshEditor(cm).edge_flags();
    std::vector<int> ids(cm.triangle_vertices().size(), 0);  // the builder's, per half-edge
    flags.assign(cm.triangle_vertices().size(), 0);
    auto constrain = [&](HalfEdgeId e, std::size_t index) {
      for (const HalfEdgeId h : {e, cm.twin(e)}) {
        flags[h] |= kConstrained;
        ids[h] = static_cast<int>(index);
      }
    };
    const std::size_t halves = 3 * c.inside_slots;
    for (HalfEdgeId e = 0; e < halves; ++e)
      if (mesh.is_constrained(e) && (mesh.twin(e) == kNone || e < mesh.twin(e))) {
        constrain(e, work.segments.size());
        work.segments.push_back({mesh.origin(e), mesh.dest(e), mesh.edge_marker(e)});
      }
    const std::size_t fill_base = work.segments.size();
    for (const HalfEdgeId e : c.boundary)
      if (!mesh.is_constrained(e)) {
        constrain(e, work.segments.size());
        work.segments.push_back({mesh.origin(e), mesh.dest(e), 0});
      }

    // Nothing leaves the mesh: checked for all before anything changes.
    for (std::size_t i = 0; i < k; ++i) {
      const Segment& s = segments[i];
      if (s.a != s.b && !stays_inside(cm, c.inside_slots, s.a, s.b))
        throw SegmentError(i, s.a, s.b,
                           "leaves the mesh: part of it is outside the triangles (beyond the boundary or in a hole)");
    }

    CdtOptions copt;
    copt.method = options.method;
    copt.strict = options.strict;
    {
      detail::CdtBuilder builder(cm, work, copt, st.cdt, std::move(ids));
      for (std::size_t i = 0; i < k; ++i) {
        const Segment& s = segments[i];
        if (s.a == s.b) continue;
        try {
          builder.insert_segment(s.a, s.b, static_cast<std::uint32_t>(i));
        } catch (const IntersectingSegments& e) {
          if (e.second() < k) throw;
          throw SegmentError(i, s.a, s.b,
                             "crosses a segment of the mesh (--strict; without it they are split where they cross)");
        }
      }
      // The filler must be as it was (a rounded crossing point outside the
      // mesh would have been inserted into it).
      for (std::size_t i = 0; i < c.filler.size(); ++i)
        if (cm.triangle(static_cast<TriId>(c.inside_slots + i)) != c.filler[i])
          throw InputError("a segment crossing could not be placed inside the mesh (numerically hopeless input?)");
      // Boundary edges no given segment runs along are released (read
      // before finish() turns indices into markers).
      std::vector<HalfEdgeId> release;
      for (HalfEdgeId e = 0; e < flags.size(); ++e)
        if ((flags[e] & kConstrained) && builder.segment_of(e) >= fill_base) release.push_back(e);
      builder.finish();
      for (HalfEdgeId e : release) {
        detail::MeshEditor(cm).edge_flags()[e] &= static_cast<std::uint8_t>(~kConstrained);
        if (cm.has_edge_markers()) detail::MeshEditor(cm).edge_markers()[e] = 0;
      }
    }
    const std::size_t slots = cm.num_triangle_slots();
    for (TriId t = static_cast<TriId>(c.inside_slots); t < c.inside_slots + c.filler.size(); ++t) cm.remove_triangle(t);
    for (TriId t = 0; t < slots; ++t)
      if (!cm.is_dead(t) && cm.is_ghost(t)) cm.remove_triangle(t);
    cm.compact();
    if (!cm.has_edge_markers() && cm.has_edge_flags()) {
      bool any = false;
      for (std::uint8_t f : detail::MeshEditor(cm).edge_flags()) any = any || f != 0;
      if (!any) detail::MeshEditor(cm).edge_flags().clear();
    }
    // The vertex data goes along; added vertices get theirs below.
    cm.vertex_markers() = std::move(mesh.vertex_markers());
    cm.set_num_vertex_attributes(mesh.num_vertex_attributes());
    cm.vertex_attributes() = std::move(mesh.vertex_attributes());
    mesh = std::move(cm);
    st.inserted = segments.size() - st.zero_length - st.already_present;
    st.vertices_added = mesh.num_vertices() - n;
  }

  if (options.delaunay) st.flips = make_constrained_delaunay(mesh);
  const std::size_t na = mesh.num_vertex_attributes();
  mesh.vertex_attributes().resize(mesh.num_vertices() * na, 0.0);
  if (na > 0)
    for (std::size_t v = n; v < mesh.num_vertices(); ++v)
      detail::interpolate_vertex_attributes(mesh, static_cast<VertexId>(v), n);
  finish_vertex_markers(mesh);
  st.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace deltamesh

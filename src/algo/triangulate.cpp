// The one-call pipeline (see triangulate.hpp) and the -r mesh rebuild.
#include "deltamesh/triangulate.hpp"
#include "core/plural.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "algo/normalize.hpp"
#include "algo/validate_overlap.hpp"
#include "algo/vertex_data.hpp"
#include "core/parallel.hpp"
#include "mesh/editor.hpp"
#include "mesh/edge_rules.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Walks from Steiner vertex `from` along half-edge e (constrained, from ->
// w) straight on through further added vertices until an input vertex
// (id < n) is reached. Returns it, or kNone when the chain bends or ends.
VertexId walk_to_input_vertex(const Mesh& mesh, HalfEdgeId e, std::size_t n) {
  VertexId prev = mesh.origin(e);
  VertexId cur = mesh.dest(e);
  for (std::size_t guard = 0; guard < mesh.num_vertices() && cur != kInfinite && cur >= n; ++guard) {
    VertexId next = kNone;
    mesh.for_each_out_edge(cur, [&](HalfEdgeId g) {
      const VertexId w = mesh.dest(g);
      if (w == kInfinite || w == prev || !mesh.is_constrained(g)) return true;
      const Point& a = mesh.point(prev);
      const Point& b = mesh.point(cur);
      const Point& c = mesh.point(w);
      if (orient2d(a, b, c) != 0) return true;
      if ((b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) <= 0) return true;
      next = w;
      return false;
    });
    if (next == kNone) return kNone;
    prev = cur;
    cur = next;
  }
  return cur == kInfinite || cur >= n ? kNone : cur;
}

// Attributes of an added vertex v: linear interpolation between the input
// endpoints of a straight chain of constrained edges through v.
void interpolate_attributes(Mesh& mesh, VertexId v, std::size_t n) {
  const std::size_t na = mesh.num_vertex_attributes();
  std::vector<double>& attrs = mesh.vertex_attributes();
  std::vector<HalfEdgeId> constrained;
  mesh.for_each_out_edge(v, [&](HalfEdgeId g) {
    if (mesh.dest(g) != kInfinite && mesh.is_constrained(g)) constrained.push_back(g);
    return true;
  });
  const Point& p = mesh.point(v);
  for (std::size_t i = 0; i < constrained.size(); ++i) {
    for (std::size_t j = i + 1; j < constrained.size(); ++j) {
      const Point& a = mesh.point(mesh.dest(constrained[i]));
      const Point& b = mesh.point(mesh.dest(constrained[j]));
      // Opposite directions through v: one straight chain.
      if (orient2d(a, p, b) != 0 || (a.x - p.x) * (b.x - p.x) + (a.y - p.y) * (b.y - p.y) >= 0) continue;
      const VertexId va = walk_to_input_vertex(mesh, constrained[i], n);
      const VertexId vb = walk_to_input_vertex(mesh, constrained[j], n);
      if (va == kNone || vb == kNone) continue;
      const double da = std::hypot(p.x - mesh.point(va).x, p.y - mesh.point(va).y);
      const double db = std::hypot(p.x - mesh.point(vb).x, p.y - mesh.point(vb).y);
      const double t = da + db > 0 ? da / (da + db) : 0.5;
      for (std::size_t k = 0; k < na; ++k)
        attrs[v * na + k] = (1 - t) * attrs[std::size_t{va} * na + k] + t * attrs[std::size_t{vb} * na + k];
      return;
    }
  }
}

// Input markers and attributes onto the mesh's vertices, then the segment
// part of Triangle's marker rule. Runs on the mesh before carving, while every
// segment is still present.
void carry_vertex_data(Mesh& mesh, const Pslg& pslg, bool use_segments) {
  const std::size_t n = pslg.points.size();
  const std::size_t nv = mesh.num_vertices();
  std::vector<int>& markers = mesh.vertex_markers();
  markers.assign(nv, 0);
  for (std::size_t v = 0; v < n && v < pslg.point_markers.size(); ++v) markers[v] = pslg.point_markers[v];

  const std::size_t na = pslg.num_point_attributes;
  mesh.set_num_vertex_attributes(na);
  std::vector<double>& attrs = mesh.vertex_attributes();
  attrs.assign(nv * na, 0.0);
  std::copy_n(pslg.point_attributes.begin(), std::min(pslg.point_attributes.size(), n * na), attrs.begin());
  if (na > 0)
    for (std::size_t v = n; v < nv; ++v) interpolate_attributes(mesh, static_cast<VertexId>(v), n);

  if (!use_segments) return;
  // A vertex on a segment with a nonzero marker takes that marker: segment
  // endpoints first, in input order, then vertices inside segments.
  for (const Segment& s : pslg.segments) {
    if (s.marker == 0) continue;
    if (s.a < nv && markers[s.a] == 0) markers[s.a] = s.marker;
    if (s.b < nv && markers[s.b] == 0) markers[s.b] = s.marker;
  }
  if (!mesh.has_edge_markers()) return;
  const std::size_t slots = mesh.num_triangle_slots();
  for (TriId t = 0; t < slots; ++t) {
    if (mesh.is_dead(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const int m = mesh.edge_marker(e);
      const VertexId o = mesh.origin(e);
      if (m != 0 && o != kInfinite && mesh.is_constrained(e) && markers[o] == 0) markers[o] = m;
    }
  }
}

std::size_t count_constrained_edges(const Mesh& mesh) {
  std::size_t count = 0;
  if (!mesh.has_edge_flags()) return 0;
  if (mesh.compacted()) {  // every slot real, every twin real or none: one scan of the flags
    const std::size_t ne = 3 * std::size_t{mesh.num_triangle_slots()};
    for (HalfEdgeId e = 0; e < ne; ++e)
      if (mesh.edge_flags(e) & kConstrained) count += mesh.twin(e) == kNone || e < mesh.twin(e);
    return count;
  }
  for (TriId t : mesh.triangles()) {
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (!mesh.is_constrained(e)) continue;
      const HalfEdgeId f = real_twin(mesh, e);
      if (f == kNone || e < f) ++count;
    }
  }
  return count;
}

}  // namespace

void detail::interpolate_vertex_attributes(Mesh& mesh, VertexId v, std::size_t n) { interpolate_attributes(mesh, v, n); }

void finish_vertex_markers(Mesh& mesh) { detail::finish_vertex_markers(mesh, 1); }

void detail::finish_vertex_markers(Mesh& mesh, unsigned threads) {
  std::vector<int>& markers = mesh.vertex_markers();
  markers.resize(mesh.num_vertices(), 0);
  const std::size_t na = mesh.num_vertex_attributes();
  mesh.vertex_attributes().resize(mesh.num_vertices() * na, 0.0);
  // A compacted mesh has only real triangles, so its half-edges are scanned
  // as one array, in chunks on the threads: each chunk lists the half-edges
  // it finds, and the markers are then set in half-edge order, as one pass
  // over the triangles sets them.
  const bool compacted = mesh.compacted();
  const std::size_t half_edges = 3 * std::size_t{mesh.num_triangle_slots()};
  const auto found = [&](auto&& wanted) {
    constexpr std::size_t kMinChunk = std::size_t{1} << 18;
    const std::size_t chunks = std::max<std::size_t>(1, std::min<std::size_t>(threads, half_edges / kMinChunk));
    std::vector<std::vector<HalfEdgeId>> lists(chunks);
    detail::run_tasks(chunks, threads, [&](std::size_t j) {
      auto pick = wanted;  // a copy of its own: kept in registers, not reread after each push_back
      std::vector<HalfEdgeId>& list = lists[j];
      const std::size_t end = half_edges * (j + 1) / chunks;
      for (std::size_t e = half_edges * j / chunks; e < end; ++e)
        if (pick(static_cast<HalfEdgeId>(e))) list.push_back(static_cast<HalfEdgeId>(e));
    });
    return lists;
  };
  // A vertex on a segment with a nonzero marker (one added on a segment
  // after carry_vertex_data, say) takes it ...
  if (mesh.has_edge_markers()) {
    const auto take = [&](HalfEdgeId e) {
      const int m = mesh.edge_marker(e);
      if (markers[mesh.origin(e)] == 0) markers[mesh.origin(e)] = m;
      if (markers[mesh.dest(e)] == 0) markers[mesh.dest(e)] = m;
    };
    const auto marked = [&](HalfEdgeId e) {
      return mesh.edge_marker(e) != 0 && mesh.is_constrained(e) && mesh.is_real(tri_of(e));
    };
    if (compacted) {
      for (const std::vector<HalfEdgeId>& list : found(marked))
        for (const HalfEdgeId e : list) take(e);
    } else {
      for (TriId t : mesh.triangles())
        for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e)
          if (marked(e)) take(e);
    }
  }
  // ... and a vertex still at 0 on the boundary gets 1. A compacted mesh's
  // boundary is where twins are kNone (a few instructions per half-edge).
  if (compacted) {
    const std::span<const VertexId> tv = mesh.triangle_vertices();
    const std::span<const HalfEdgeId> tw = detail::MeshEditor(mesh).twins();
    const std::size_t n = mesh.num_vertices();
    const HalfEdgeId* const twins = tw.data();
    for (const std::vector<HalfEdgeId>& list : found([twins](HalfEdgeId e) { return twins[e] == kNone; }))
      for (const HalfEdgeId e : list) {
        if (tv[e] >= n || tv[next_edge(e)] >= n) continue;  // (a removed slot)
        if (markers[tv[e]] == 0) markers[tv[e]] = 1;
        if (markers[tv[next_edge(e)]] == 0) markers[tv[next_edge(e)]] = 1;
      }
    return;
  }
  for (TriId t : mesh.triangles()) {
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (real_twin(mesh, e) != kNone) continue;
      if (markers[mesh.origin(e)] == 0) markers[mesh.origin(e)] = 1;
      if (markers[mesh.dest(e)] == 0) markers[mesh.dest(e)] = 1;
    }
  }
}

namespace {

// triangulate() on coordinates in the predicates' range (else a VertexError
// from the coordinate check, before any work).
Mesh triangulate_in_range(const Pslg& pslg, const TriangulateOptions& options, TriangulateStats* stats) {
  const auto t_start = Clock::now();
  TriangulateStats local;
  TriangulateStats& st = stats ? *stats : local;
  st = TriangulateStats{};
  st.input_vertices = pslg.points.size();
  st.input_segments = options.use_segments ? pslg.segments.size() : 0;
  st.input_holes = options.use_segments ? pslg.holes.size() : 0;
  st.input_regions = options.use_segments ? pslg.regions.size() : 0;

  Mesh mesh;
  auto t = Clock::now();
  if (!options.use_segments) {
    DelaunayOptions dopt;
    dopt.keep_ghosts = options.domain.keep_convex_hull;  // the hull edges are constrained below
    dopt.trace = options.trace;
    dopt.threads = options.threads;
    DelaunayStats ds;
    {
      ProgressReporter rep(options.progress, "insert points", "points", pslg.points.size());
      mesh = delaunay(pslg.points, dopt, &ds);
      rep.set(pslg.points.size());
    }
    st.duplicate_vertices = ds.duplicates;
    st.triangulate_seconds = seconds_since(t);
    carry_vertex_data(mesh, pslg, false);
    if (options.domain.keep_convex_hull) {
      t = Clock::now();
      DomainOptions hull;
      hull.keep_convex_hull = true;
      if (options.trace) detail::TraceAccess::phase(*options.trace, "carve");
      carve_domain(mesh, Pslg{}, hull, &st.domain);
      st.domain_seconds = seconds_since(t);
    }
  } else {
    CdtOptions copt;
    copt.method = options.method;
    copt.strict = options.strict;
    copt.trace = options.trace;
    {
      ProgressReporter rep(options.progress, "insert points, recover segments", "segments", pslg.segments.size());
      mesh = constrained_triangulation(pslg, copt, &st.cdt);
      rep.set(pslg.segments.size());
    }
    st.triangulate_seconds = seconds_since(t);
    st.duplicate_vertices = st.cdt.duplicate_vertices;
    st.steiner_vertices = mesh.num_vertices() - std::min(mesh.num_vertices(), pslg.points.size());
    if (options.check_segments) {
      t = Clock::now();
      CheckOptions co;
      co.delaunay = options.method != CdtMethod::Ct;
      co.pslg = &pslg;
      st.segment_check = check(mesh, co);
      st.check_seconds = seconds_since(t);
    }
    carry_vertex_data(mesh, pslg, true);

    t = Clock::now();
    if (options.trace) detail::TraceAccess::phase(*options.trace, "carve");
    {
      ProgressReporter rep(options.progress, "carve domain", "triangles", mesh.num_triangles());
      carve_domain(mesh, pslg, options.domain, &st.domain);
    }
    st.domain_seconds = seconds_since(t);

    if (st.cdt.zero_length_segments)
      st.warnings.push_back(count_of(st.cdt.zero_length_segments, "zero-length segment", "zero-length segments") +
                            " ignored (both ends at the same point)");
    for (std::string& w : domain_warnings(st.domain, mesh.num_triangles(), false, &pslg)) st.warnings.push_back(std::move(w));
  }

  st.triangulated = mesh.num_triangles();
  // Refinement works on the carved mesh; vertices it adds get their markers
  // from finish_vertex_markers below.
  if (options.refine && mesh.num_triangles() > 0) {
    t = Clock::now();
    if (options.trace) detail::TraceAccess::phase(*options.trace, "refine");
    if (options.progress && !options.refine->progress) {
      RefineOptions ropt = *options.refine;
      ropt.progress = options.progress;
      st.refine = refine(mesh, ropt);
    } else {
      st.refine = refine(mesh, *options.refine);
    }
    st.refine_seconds = seconds_since(t);
  }

  t = Clock::now();
  if (!mesh.compacted()) mesh.compact();
  detail::finish_vertex_markers(mesh, detail::resolve_threads(options.threads));
  st.finish_seconds = seconds_since(t);
  st.vertices = mesh.num_vertices();
  st.triangles = mesh.num_triangles();
  st.segments = count_constrained_edges(mesh);
  st.total_seconds = seconds_since(t_start);
  return mesh;
}

}  // namespace

Mesh triangulate(const Pslg& pslg, const TriangulateOptions& options, TriangulateStats* stats) {
  // Beyond the predicates' range: in an exact power-of-two frame. In range
  // this costs nothing: the triangulation's own coordinate check finds it
  // out (a VertexError before any work).
  try {
    return triangulate_in_range(pslg, options, stats);
  } catch (const VertexError&) {
    if (!detail::needs_frame(pslg.points)) throw;
  }
  {
    const detail::Frame f = detail::frame_for(pslg.points);
    TriangulateOptions framed = options;
    if (framed.refine) detail::scale_options(f, *framed.refine);
    Mesh mesh = [&] {
      const detail::TraceFrameScope in_frame(options.trace, f.k);
      return triangulate(detail::scaled_pslg(f, pslg), framed, stats);
    }();
    detail::restore(f, mesh);
    if (stats) detail::restore(f, stats->refine);
    return mesh;
  }
}

Mesh mesh_from_triangles(const Pslg& nodes, std::span<const VertexId> triangles, std::size_t num_attributes,
                         std::span<const double> attributes, const RebuildOptions& options, InsertSegmentsStats* stats) {
  const std::size_t n = nodes.points.size();
  const std::size_t nt = triangles.size() / 3;
  if (triangles.size() % 3 != 0) throw InputError("the triangle list length is not a multiple of 3");
  Mesh mesh;
  mesh.reserve(n, nt);
  for (const Point& p : nodes.points) mesh.add_vertex(p);
  mesh.set_num_triangle_attributes(num_attributes);
  for (std::size_t i = 0; i < nt; ++i) {
    VertexId v[3] = {triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]};
    for (VertexId x : v)
      if (x >= n)
        throw InputError("triangle " + std::to_string(i) + " refers to vertex " + std::to_string(x) + " of " +
                         std::to_string(n),
                         i);
    const double o = orient2d(nodes.points[v[0]], nodes.points[v[1]], nodes.points[v[2]]);
    if (o == 0) throw InputError("triangle " + std::to_string(i) + " is degenerate (its vertices are collinear)", i);
    if (o < 0) std::swap(v[1], v[2]);
    const TriId t = mesh.add_triangle(v[0], v[1], v[2]);
    for (std::size_t k = 0; k < num_attributes; ++k) {
      const std::size_t src = i * num_attributes + k;
      mesh.triangle_attributes()[std::size_t{t} * num_attributes + k] = src < attributes.size() ? attributes[src] : 0.0;
    }
  }
  // Twins: sort half-edges by their undirected edge.
  struct Key {
    std::uint64_t edge;
    HalfEdgeId half;
  };
  std::vector<Key> keys;
  keys.reserve(3 * nt);
  for (HalfEdgeId e = 0; e < 3 * nt; ++e) {
    const VertexId a = mesh.origin(e), b = mesh.dest(e);
    keys.push_back({edge_key(a, b), e});
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return x.edge != y.edge ? x.edge < y.edge : x.half < y.half;
  });
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].edge == keys[i].edge) ++j;
    const VertexId a = static_cast<VertexId>(keys[i].edge >> 32), b = static_cast<VertexId>(keys[i].edge);
    const std::string name = "edge " + std::to_string(a) + "-" + std::to_string(b);
    if (j - i > 2) throw InputError(name + " is shared by " + std::to_string(j - i) + " triangles");
    if (j - i == 2) {
      const HalfEdgeId e = keys[i].half, f = keys[i + 1].half;
      if (mesh.origin(e) == mesh.origin(f))
        throw OverlappingTriangles(tri_of(e), tri_of(f), "overlap (both on the same side of their common edge)");
      mesh.link(e, f);
    }
    i = j;
  }
  if (!options.area_bounds.empty()) {
    if (options.area_bounds.size() != nt)
      throw InputError(std::to_string(options.area_bounds.size()) + " area bounds for " + std::to_string(nt) +
                       " triangles");
    for (TriId t = 0; t < nt; ++t) mesh.set_triangle_area_bound(t, options.area_bounds[t]);
  }
  mesh.compact();
  // Triangles that overlap without sharing an edge (separate components, a
  // triangle inside another, crossing boundaries): the validator's sweep.
  // Slots are still the list's indices here (nothing was deleted).
  if (const auto found = options.refuse_overlaps ? detail::find_overlap(mesh) : std::nullopt) {
    const TriangleConflict& c = found->conflict;
    throw OverlappingTriangles(c.first, c.second,
                               c.kind == TriangleConflict::Kind::Overlap
                                   ? "overlap"
                                   : "meet other than edge to edge (a vertex on the other's edge, or an edge "
                                     "given twice without being shared)");
  }

  // Segments: constrained where they are chains of edges, inserted where not.
  InsertSegmentsOptions iopt;
  iopt.method = options.method;
  iopt.strict = options.strict;
  iopt.delaunay = false;
  insert_segments(mesh, nodes.segments, iopt, stats);
  carry_vertex_data(mesh, nodes, true);
  finish_vertex_markers(mesh);
  return mesh;
}

}  // namespace deltamesh

// Constrained triangulation of a PSLG: Delaunay triangulation of the
// vertices, then segments inserted one by one. This file holds the public
// entry point and the front end shared by every method: tracing a segment
// from one endpoint (rotary traversal, then a walk along it, §1.2.1), and
// splitting it where it meets a vertex or crosses an earlier segment.
#include "deltamesh/cdt.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "algo/cdt_builder.hpp"
#include "algo/normalize.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "core/expansion.hpp"
#include "mesh/locate.hpp"
#include "mesh/editor.hpp"

namespace deltamesh {

std::string_view to_string(CdtMethod m) {
  switch (m) {
    case CdtMethod::Fast: return "fast";
    case CdtMethod::Ct: return "ct";
    case CdtMethod::Lawson: return "lawson";
    case CdtMethod::Lifting: return "lifting";
  }
  return "unknown";
}

std::optional<CdtMethod> parse_cdt_method(std::string_view name) {
  for (CdtMethod m : {CdtMethod::Fast, CdtMethod::Ct, CdtMethod::Lawson, CdtMethod::Lifting})
    if (name == to_string(m)) return m;
  return std::nullopt;
}

namespace detail {

namespace {

// The bounding box of a non-empty point list.
struct Box {
  double x0, x1, y0, y1;
};
Box bounding_box(const std::vector<Point>& pts) {
  Box b{pts[0].x, pts[0].x, pts[0].y, pts[0].y};
  for (const Point& q : pts) {
    b.x0 = std::min(b.x0, q.x);
    b.x1 = std::max(b.x1, q.x);
    b.y0 = std::min(b.y0, q.y);
    b.y1 = std::max(b.y1, q.y);
  }
  return b;
}

std::uint64_t saturating_pairs(std::uint64_t s) {
  if (s > (std::uint64_t{1} << 31)) return std::uint64_t{1} << 62;
  return s * (s > 0 ? s - 1 : 0) / 2;
}

}  // namespace

CdtBuilder::CdtBuilder(Mesh& mesh, const Pslg& pslg, const CdtOptions& options, CdtStats& stats,
                       std::vector<int> segment_ids)
    : mesh_(mesh),
      pslg_(pslg),
      opt_(options),
      st_(stats),
      pts_(detail::MeshEditor(mesh).points()),
      tv_(detail::MeshEditor(mesh).triangle_vertices()),
      tw_(detail::MeshEditor(mesh).twins()),
      flags_(detail::MeshEditor(mesh).edge_flags()),
      seg_of_(std::move(segment_ids)),
      ve_(detail::MeshEditor(mesh).out_edges()),
      inserter_(mesh) {
  // Both per-half-edge arrays exist from now on, so the mesh's topological
  // operations keep them in step.
  if (flags_.size() != tv_.size()) flags_.assign(tv_.size(), 0);
  // Segment indices are only needed to name crossing segments (strict) and
  // to give edges their markers; without either none are kept and every
  // constrained edge counts as segment 0.
  for (const Segment& s : pslg.segments) ids_ = ids_ || s.marker != 0;
  ids_ = ids_ || options.strict || !seg_of_.empty();
  if (ids_) {
    if (seg_of_.size() != tv_.size()) seg_of_.assign(tv_.size(), 0);
    inserter_.carry(&seg_of_);
    // finish() writes the markers; until then the mesh carries none.
    detail::MeshEditor(mesh).edge_markers().clear();
  }
  max_steiner_ = static_cast<std::size_t>(saturating_pairs(pslg.segments.size())) + 16;
  // The static incircle filter's bound (incircle_fast): differences of
  // coordinates within the bounding box (crossing vertices lie inside it).
  if (!pslg.points.empty()) {
    const Box bb = bounding_box(pslg.points);
    const double box = std::max(bb.x1 - bb.x0, bb.y1 - bb.y0) * (1.0 + 1e-12);
    const double box2 = box * box;
    // Beyond the range where a fourth power stays finite and normal, the
    // bound is useless: leave it infinite, so incircle() always decides.
    static_err_ = box2 > 0x1p-450 && box2 < 0x1p450 ? kIncircleErrA * 12.0 * box2 * box2 * (1.0 + 1e-6)
                                                     : std::numeric_limits<double>::infinity();
  }
  crossings_.reserve(64);
}

void CdtBuilder::insert_segment(VertexId a, VertexId b, std::uint32_t index) {
  pieces_.clear();
  pieces_.push_back({a, b, index});
  const std::size_t steiner_start = steiner_;
  std::size_t processed = 0;
  bool whole = true;
  while (!pieces_.empty()) {
    const Piece p = pieces_.back();
    pieces_.pop_back();
    if (p.a == p.b) continue;  // a crossing snapped onto an endpoint
    // Each piece either ends, or moves on past a vertex on the segment, or
    // adds a crossing vertex: bounded by the vertices there are.
    if (++processed > 16 + 4 * pts_.size() + 8 * (steiner_ - steiner_start))
      throw InputError("segment " + std::to_string(index) +
                       " could not be inserted: too many pieces (numerically hopeless input?)");
    process(p, whole);
    whole = false;
  }
}

void CdtBuilder::process(const Piece& p, bool whole) {
  const Trace tr = trace(p.a, p.b);
  switch (tr.kind) {
    case TraceKind::Present:
      if (flags_[tr.edge] & kConstrained)
        ++st_.overlaps_merged;
      else if (whole)
        ++st_.segments_already_present;
      mark(tr.edge, p.seg);
      trace_present(p.a, p.b);
      break;
    case TraceKind::OnVertex:
      ++st_.vertices_on_segments;
      if (crossings_.empty()) {
        if (flags_[tr.edge] & kConstrained) ++st_.overlaps_merged;
        mark(tr.edge, p.seg);
        trace_present(p.a, tr.vertex);
      } else {
        recover(p.a, tr.vertex, p.seg);
      }
      pieces_.push_back({tr.vertex, p.b, p.seg});
      break;
    case TraceKind::Constrained:
      resolve_crossing(p, tr.edge);
      break;
    case TraceKind::Clean:
      recover(p.a, p.b, p.seg);
      break;
  }
}

CdtBuilder::Trace CdtBuilder::trace(VertexId a, VertexId b) {
  crossings_.clear();
  const HalfEdgeId start = ve_[a];
  const std::size_t limit = tv_.size() + 3;
  // Rotary traversal around a (§1.2.1): first, is ab an edge already? Only
  // integer comparisons, so segments present in the Delaunay triangulation
  // cost no predicate at all.
  HalfEdgeId e = start;
  std::size_t guard = 0;
  do {
    if (tv_[next_edge(e)] == b) return {TraceKind::Present, e};
    e = tw_[prev_edge(e)];
  } while (e != start && ++guard < limit);

  // Then the triangle around a that the segment leaves through (its far edge
  // crosses ab), or a neighbour exactly on the segment; then the walk along
  // ab through the triangles it crosses, up to a constrained edge.
  const Point pa = pt(a), pb = pt(b);
  const SegmentExit ex = segment_exit(tv_.data(), tw_.data(), pts_.data(), start, pa, pa, pb, limit);
  if (ex.kind == SegmentExit::Kind::Along) return {TraceKind::OnVertex, ex.edge, ex.vertex};
  if (ex.kind == SegmentExit::Kind::None)
    throw InternalError("CdtBuilder::trace", "no triangle around vertex " + std::to_string(a) +
                                                 " meets the segment to " + std::to_string(b));
  const SegmentWalk w = walk_segment(
      tv_.data(), tw_.data(), pts_.data(), pa, pb, b, ex.edge,
      [&](HalfEdgeId h) {
        if (flags_[h] & kConstrained) return false;
        crossings_.push_back(h);
        return true;
      },
      limit);
  switch (w.kind) {
    case SegmentWalk::Kind::Reached: return {TraceKind::Clean};
    case SegmentWalk::Kind::OnVertex: return {TraceKind::OnVertex, kNone, w.vertex};
    case SegmentWalk::Kind::Stopped: return {TraceKind::Constrained, w.edge};
    case SegmentWalk::Kind::LeftHull:
      throw InternalError("CdtBuilder::trace", "the segment from " + std::to_string(a) + " to " + std::to_string(b) +
                                                   " leaves the convex hull");
    case SegmentWalk::Kind::Overrun: break;
  }
  throw InternalError("CdtBuilder::trace", "the walk along a segment does not end");
}

void CdtBuilder::mark(HalfEdgeId e, std::uint32_t seg) {
  const HalfEdgeId f = tw_[e];
  if (ids_) {
    int keep = static_cast<int>(seg);
    if (flags_[e] & kConstrained) {
      // An edge of overlapping segments keeps the marker of the lowest-numbered
      // one with a nonzero marker (whatever the order they were inserted in).
      const int old = seg_of_[e];
      const bool old_nz = pslg_.segments[static_cast<std::size_t>(old)].marker != 0;
      const bool new_nz = pslg_.segments[seg].marker != 0;
      if (old_nz != new_nz ? old_nz : old < keep) keep = old;
    }
    seg_of_[e] = keep;
    seg_of_[f] = keep;
  }
  flags_[e] |= kConstrained;
  flags_[f] |= kConstrained;
}

bool CdtBuilder::split_fits(HalfEdgeId cd, const Point& p) const {
  const VertexId c = tv_[cd], d = tv_[next_edge(cd)];
  const VertexId x = tv_[prev_edge(cd)], y = tv_[prev_edge(tw_[cd])];
  if (x == kInfinite || y == kInfinite) return false;
  return orient2d(pt(c), p, pt(x)) > 0 && orient2d(p, pt(d), pt(x)) > 0 && orient2d(pt(d), p, pt(y)) > 0 &&
         orient2d(p, pt(c), pt(y)) > 0;
}

void CdtBuilder::resolve_crossing(const Piece& p, HalfEdgeId cd) {
  const std::uint32_t other = seg_id(cd);
  if (opt_.strict) throw IntersectingSegments(std::min(other, p.seg), std::max(other, p.seg));
  if (++steiner_ > max_steiner_)
    throw InputError("more vertices added at segment crossings than there are segment pairs (" +
                     std::to_string(max_steiner_) + "): numerically hopeless input?");
  const VertexId c = tv_[cd], d = tv_[next_edge(cd)];
  const Point pa = pt(p.a), pb = pt(p.b), pc = pt(c), pd = pt(d);
  // The intersection point in parametric form along each segment; the exact
  // orientations give the parameters' signs, so both lie in [0, 1].
  const double oc = orient2d(pa, pb, pc), od = orient2d(pa, pb, pd);  // oc < 0 < od
  const double oa = orient2d(pc, pd, pa), ob = orient2d(pc, pd, pb);  // opposite signs
  const double t = oc / (oc - od), s = oa / (oa - ob);
  Point cand[3];
  cand[0] = {pc.x + t * (pd.x - pc.x), pc.y + t * (pd.y - pc.y)};
  cand[1] = {pa.x + s * (pb.x - pa.x), pa.y + s * (pb.y - pa.y)};
  cand[2] = {0.5 * (cand[0].x + cand[1].x), 0.5 * (cand[0].y + cand[1].y)};
  const double lox = std::max(std::min(pa.x, pb.x), std::min(pc.x, pd.x));
  const double hix = std::min(std::max(pa.x, pb.x), std::max(pc.x, pd.x));
  const double loy = std::max(std::min(pa.y, pb.y), std::min(pc.y, pd.y));
  const double hiy = std::min(std::max(pa.y, pb.y), std::max(pc.y, pd.y));
  for (Point& q : cand) {
    if (!(q.x >= lox)) q.x = lox;  // also catches NaN
    if (q.x > hix) q.x = hix;
    if (!(q.y >= loy)) q.y = loy;
    if (q.y > hiy) q.y = hiy;
    // Keep coordinates in the predicates' exact range.
    if (std::fabs(q.x) < kMinCoordinate) q.x = 0.0;
    if (std::fabs(q.y) < kMinCoordinate) q.y = 0.0;
  }
  // A crossing within a few rounding errors of an endpoint is taken to be at
  // that endpoint: otherwise nearly concurrent segments can keep crossing
  // each other's rounded pieces an ulp further along, without end.
  {
    const double scale = std::max({std::fabs(pa.x), std::fabs(pa.y), std::fabs(pb.x), std::fabs(pb.y),
                                   std::fabs(pc.x), std::fabs(pc.y), std::fabs(pd.x), std::fabs(pd.y)});
    const double tol = 64.0 * kEpsilon * scale;
    auto near = [&](const Point& q) { return std::fabs(q.x - cand[0].x) <= tol && std::fabs(q.y - cand[0].y) <= tol; };
    for (const VertexId x : {c, d}) {
      if (!near(pt(x))) continue;
      // The piece passes (within rounding) through an end of cd: split it there.
      ++st_.crossings_snapped;
      pieces_.push_back({x, p.b, p.seg});
      pieces_.push_back({p.a, x, p.seg});
      return;
    }
    for (const VertexId x : {p.a, p.b}) {
      if (!near(pt(x))) continue;
      // cd passes (within rounding) through an end of the piece: cd is split there.
      ++st_.crossings_snapped;
      release(cd);
      pieces_.push_back({x, d, other});
      pieces_.push_back({c, x, other});
      pieces_.push_back({p.a, p.b, p.seg});
      return;
    }
    // Nearly collinear pieces (an overlapping segment whose chain is bent
    // at rounded crossing vertices, a segment given twice): their crossing
    // point is ill-conditioned, lands anywhere along them, and the next
    // copy crosses the bent chain again, without end. When both ends of one
    // lie within rounding distance of the other's line, strictly between its
    // ends, the longer one is routed through them instead.
    auto along = [&](const Point& u, const Point& v, const Point& q) {  // q's offset from line uv is within tol
      const double ux = v.x - u.x, uy = v.y - u.y;
      const double len = std::sqrt(ux * ux + uy * uy);
      const double dot = (q.x - u.x) * ux + (q.y - u.y) * uy;
      return len > 0 && std::fabs(orient2d(u, v, q)) <= tol * len && dot > 0 && dot < len * len;
    };
    auto first_from = [](const Point& u, const Point& v, const Point& q1, const Point& q2) {
      const double ux = v.x - u.x, uy = v.y - u.y;
      return (q1.x - u.x) * ux + (q1.y - u.y) * uy <= (q2.x - u.x) * ux + (q2.y - u.y) * uy;
    };
    if (along(pa, pb, pc) && along(pa, pb, pd)) {
      ++st_.crossings_snapped;
      const bool c_first = first_from(pa, pb, pc, pd);
      const VertexId x = c_first ? c : d, y = c_first ? d : c;
      pieces_.push_back({y, p.b, p.seg});
      pieces_.push_back({x, y, p.seg});
      pieces_.push_back({p.a, x, p.seg});
      return;
    }
    if (along(pc, pd, pa) && along(pc, pd, pb)) {
      ++st_.crossings_snapped;
      release(cd);
      const bool a_first = first_from(pc, pd, pa, pb);
      const VertexId x = a_first ? p.a : p.b, y = a_first ? p.b : p.a;
      pieces_.push_back({y, d, other});
      pieces_.push_back({x, y, other});
      pieces_.push_back({c, x, other});
      pieces_.push_back({p.a, p.b, p.seg});
      return;
    }
  }
  for (const Point& q : cand) {
    if (!split_fits(cd, q)) continue;
    const VertexId v = mesh_.add_vertex(q);
    inserter_.insert_splitting_edge(cd, v);  // both halves stay constrained with cd's segment
    ++st_.intersections;
    pieces_.push_back({v, p.b, p.seg});
    pieces_.push_back({p.a, v, p.seg});
    return;
  }
  // The rounded point is not inside the two triangles of cd (a vertex lies
  // within rounding distance of cd). Release cd, insert the point as a free
  // vertex (or use the vertex it coincides with), and insert both segments
  // again through it.
  ++st_.intersection_fallbacks;
  const TriId hint = tri_of(cd);
  release(cd);
  const std::size_t before = pts_.size();
  const VertexId v = inserter_.insert_point(cand[0], hint).vertex;
  if (v == kNone) throw InternalError("CdtBuilder::resolve_crossing", "a segment crossing could not be located");
  if (pts_.size() > before) ++st_.intersections;
  pieces_.push_back({v, d, other});
  pieces_.push_back({c, v, other});
  pieces_.push_back({v, p.b, p.seg});
  pieces_.push_back({p.a, v, p.seg});
}

// Unconstrains edge cd (its segment goes back in as pieces). cd was locally
// Delaunay only as a segment: flip where needed, so that the triangulation is
// the CDT of what is constrained now.
void CdtBuilder::release(HalfEdgeId cd) {
  const HalfEdgeId dc = tw_[cd];
  flags_[cd] &= static_cast<std::uint8_t>(~kConstrained);
  flags_[dc] &= static_cast<std::uint8_t>(~kConstrained);
  if (ids_) seg_of_[cd] = seg_of_[dc] = 0;
  lawson_stack_.clear();
  lawson_stack_.push_back(cd);
  lawson_flips(lawson_stack_);
}

void CdtBuilder::finish() {
  bool markers = false;
  for (const Segment& s : pslg_.segments) markers = markers || s.marker != 0;
  std::vector<int>& out = detail::MeshEditor(mesh_).edge_markers();
  if (!markers) {  // every constrained edge gets marker 0: no marker array
    out.clear();
    return;
  }
  // (markers imply ids_: seg_of_ holds segment indices.) Indices -> markers
  // in place, then the array becomes the mesh's: no second array to fill.
  seg_of_.resize(tv_.size(), 0);
  int* const ids = seg_of_.data();
  const VertexId* const tv = tv_.data();
  const std::uint8_t* const flags = flags_.data();
  const Segment* const segments = pslg_.segments.data();
  bool any_marker = false, any_constrained = false;
  for (HalfEdgeId e = 0, end = static_cast<HalfEdgeId>(tv_.size()); e < end; ++e) {
    if (tv[e - e % 3] != kNone && (flags[e] & kConstrained)) {
      ids[e] = segments[ids[e]].marker;
      any_marker = any_marker || ids[e] != 0;
      any_constrained = true;
    } else {
      ids[e] = 0;
    }
  }
  out.clear();
  if (any_marker) out.swap(seg_of_);
  ids_ = false;  // no indices are left
  inserter_.carry(nullptr);
  if (!any_constrained) flags_.clear();
}

}  // namespace detail

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Are the segments long against the spacing of the vertices (their mean
// length over twice sqrt(bounding box area / vertices)), and chained? Then,
// in the classic order, each crosses many Delaunay edges and the chain order
// pays (a star-shaped polygon: 26; coastlines and lakes: 0.05 to 0.6, where
// the classic order is up to three times faster).
bool long_segments(const Pslg& pslg) {
  if (pslg.segments.empty() || pslg.points.size() < 3) return false;
  const detail::Box bb = detail::bounding_box(pslg.points);
  const double area = (bb.x1 - bb.x0) * (bb.y1 - bb.y0);
  if (!(area > 0) || !std::isfinite(area)) return false;
  // The mean length over a sample of (at most about 4096) segments.
  const std::size_t stride = pslg.segments.size() / 4096 + 1;
  double length = 0;
  std::size_t sampled = 0;
  for (std::size_t i = 0; i < pslg.segments.size(); i += stride, ++sampled) {
    const Point& a = pslg.points[pslg.segments[i].a];
    const Point& b = pslg.points[pslg.segments[i].b];
    length += std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y));
  }
  const double spacing = std::sqrt(area / static_cast<double>(pslg.points.size()));
  if (!(length / static_cast<double>(sampled) > 2.0 * spacing)) return false;
  // ... and do they form chains (most segment vertices shared by exactly
  // two)? Isolated segments gain nothing from the order: each one's far end
  // is a long walk away.
  std::vector<std::uint8_t> degree(pslg.points.size(), 0);
  for (const Segment& s : pslg.segments) {
    if (degree[s.a] < 3) ++degree[s.a];
    if (degree[s.b] < 3) ++degree[s.b];
  }
  std::size_t used = 0, inner = 0;
  for (std::uint8_t d : degree) {
    used += d > 0;
    inner += d == 2;
  }
  return 2 * inner >= used;
}

// Relabels vertex `from` as `to` around its fan.
void relabel(Mesh& mesh, VertexId from, VertexId to) {
  std::vector<VertexId>& tv = detail::MeshEditor(mesh).triangle_vertices();
  std::vector<HalfEdgeId>& ve = detail::MeshEditor(mesh).out_edges();
  const std::vector<HalfEdgeId>& tw = detail::MeshEditor(mesh).twins();
  const HalfEdgeId start = ve[from];
  HalfEdgeId e = start;
  do {
    tv[e] = to;
    e = tw[prev_edge(e)];
  } while (e != start);
  ve[to] = start;
  ve[from] = kNone;
}

// In the chain order an input vertex may arrive exactly where two segments
// inserted before it cross (first_copy[v] >= n, a vertex added there). The
// input vertex takes that vertex's place, and the added vertices left in no
// triangle are dropped, the last ones moved into their ids.
void claim_crossing_vertices(Mesh& mesh, std::vector<VertexId>& first_copy) {
  const std::size_t n = first_copy.size();
  const std::size_t total = mesh.num_vertices();
  std::vector<VertexId> claimant(total - n, kNone);
  bool any = false;
  for (VertexId v = 0; v < n; ++v) {
    const VertexId s = first_copy[v];
    if (s < n) continue;
    if (claimant[s - n] == kNone) {
      claimant[s - n] = v;
      relabel(mesh, s, v);
      any = true;
    }
    first_copy[v] = claimant[s - n];
  }
  if (!any) return;
  std::vector<Point>& pts = detail::MeshEditor(mesh).points();
  std::vector<HalfEdgeId>& ve = detail::MeshEditor(mesh).out_edges();
  std::size_t end = total;
  for (std::size_t h = n; h < end; ++h) {
    if (ve[h] != kNone) continue;  // still used
    while (end > h + 1 && ve[end - 1] == kNone) --end;
    if (end > h + 1) {  // move the last used added vertex into the hole
      pts[h] = pts[end - 1];
      relabel(mesh, static_cast<VertexId>(end - 1), static_cast<VertexId>(h));
    }
    --end;
  }
  pts.resize(end);
  ve.resize(end);
}

// Of equal points the triangulation keeps the one it inserted first; keep
// the first in input order instead (deterministic, and what a user
// numbering vertices expects). On entry kept[v] is the copy of v's point in
// the mesh; on return it is the lowest index of v's point.
void keep_lowest_copies(Mesh& mesh, std::vector<VertexId>& kept) {
  const std::size_t n = kept.size();
  std::vector<VertexId> low(n);
  for (VertexId v = 0; v < n; ++v) low[v] = v;
  for (VertexId v = 0; v < n; ++v)
    if (v < low[kept[v]]) low[kept[v]] = v;
  for (VertexId k = 0; k < n; ++k)
    if (kept[k] == k && low[k] != k) relabel(mesh, k, low[k]);
  for (VertexId v = 0; v < n; ++v) kept[v] = low[kept[v]];
}
}  // namespace

Mesh constrained_triangulation(const Pslg& pslg, const CdtOptions& options, CdtStats* stats) {
  CdtStats local;
  CdtStats& st = stats ? *stats : local;
  st = CdtStats{};
  const std::size_t n = pslg.points.size();
  if (pslg.segments.size() >= (std::size_t{1} << 31))
    throw InputError("too many segments: at most 2147483647 are supported");
  for (std::size_t i = 0; i < pslg.segments.size(); ++i) {
    const Segment& s = pslg.segments[i];
    if (s.a >= n || s.b >= n)
      throw InputError("segment " + std::to_string(i) + " refers to vertex " + std::to_string(std::max(s.a, s.b)) +
                           " but there are " + std::to_string(n) + " vertices",
                       i);
  }
  auto t0 = Clock::now();
  if (options.method == CdtMethod::Fast && !pslg.segments.empty() && !options.trace &&
      (options.chain_order == ChainOrder::Always || (options.chain_order == ChainOrder::Auto && long_segments(pslg)))) {
    Mesh mesh;
    std::vector<VertexId> first_copy;
    if (detail::chain_order_cdt(mesh, pslg, options, st, first_copy)) {
      if (mesh.num_vertices() > n) claim_crossing_vertices(mesh, first_copy);
      if (st.duplicate_vertices > 0) keep_lowest_copies(mesh, first_copy);
      // Rounded crossing vertices converging on one point can leave an edge
      // that is not locally Delaunay (tests/regress/
      // cdt_ring_crossings_converge_not_delaunay.poly); inputs without
      // crossings skip this.
      if (mesh.num_vertices() > n) detail::constrained_lawson_flips(mesh);
      st.chain_order = true;
      st.triangulate_seconds = seconds_since(t0);
      return mesh;
    }
    st = CdtStats{};  // over budget: start over the classic way
    st.chain_order_abandoned = true;
  }
  // Beyond the predicates' range a VertexError, as on the chain-order path
  // (triangulate() then meshes in a frame): delaunay() would frame the points
  // on its own and leave segments and holes to coordinates the predicates
  // cannot handle (subnormal ones underflow: a "degenerate" triangle).
  if (!detail::in_predicate_range(pslg.points, 1)) check_coordinates(pslg.points);
  DelaunayStats ds;
  DelaunayOptions dopt;
  dopt.keep_ghosts = true;
  dopt.trace = options.trace;
  Mesh mesh = delaunay(pslg.points, dopt, &ds);
  st.duplicate_vertices = ds.duplicates;
  std::vector<VertexId> canonical;  // delaunay() keeps the first copy of equal points
  if (ds.duplicates > 0) {
    canonical.resize(n);
    for (VertexId v = 0; v < n; ++v) canonical[v] = ds.duplicate_of[v] == kNone ? v : ds.duplicate_of[v];
  }
  st.triangulate_seconds = seconds_since(t0);
  if (pslg.segments.empty()) return mesh;

  t0 = Clock::now();
  if (options.trace) detail::TraceAccess::phase(*options.trace, "segments");
  {
    detail::CdtBuilder builder(mesh, pslg, options, st);
    auto canon = [&](VertexId v) { return canonical.empty() ? v : canonical[v]; };  // first copy
    for (std::size_t i = 0; i < pslg.segments.size(); ++i) {
      const VertexId a = canon(pslg.segments[i].a), b = canon(pslg.segments[i].b);
      if (a == b) {
        ++st.zero_length_segments;
        continue;
      }
      ++st.segments_inserted;
      builder.insert_segment(a, b, static_cast<std::uint32_t>(i));
    }
    builder.finish();
  }
  if (options.method == CdtMethod::Fast && st.intersections > 0) detail::constrained_lawson_flips(mesh);  // as above
  st.segments_seconds = seconds_since(t0);
  return mesh;
}

}  // namespace deltamesh

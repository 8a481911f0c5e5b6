// Recovery of a clean segment piece ab (every edge it crosses is
// unconstrained, no vertex lies on it) by the seed's methods:
//   Fast    - remove the crossed triangles, retriangulate both pseudo-polygons
//             (constrained Delaunay, recursive empty-circle choice), reusing slots;
//   Ct      - §1.2.2: queue of crossing edges, flip strictly convex ones that do
//             not re-create an edge flipped before;
//   Lawson  - §2.2: Ct, then constrained Lawson flips over the changed region;
//   Lifting - §2.3: flips in the order of the lifting-map event times.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "algo/cdt_builder.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/edge_rules.hpp"
#include "mesh/legalize.hpp"

namespace deltamesh::detail {

namespace {

[[noreturn]] void internal(const char* where, const std::string& what) { throw InternalError(where, what); }

TraceReason method_reason(CdtMethod m) {
  switch (m) {
    case CdtMethod::Fast: return TraceReason::Fast;
    case CdtMethod::Ct: return TraceReason::Ct;
    case CdtMethod::Lawson: return TraceReason::LawsonMethod;
    case CdtMethod::Lifting: return TraceReason::LiftingMethod;
  }
  return TraceReason::None;
}

// A segment a-b is an edge now, after `flips` flips (or none: `why` Present).
void trace_recovered(TraceObserver& o, VertexId a, VertexId b, TraceReason why, std::size_t flips) {
  TraceEvent ev = trace_event(deltamesh::TraceKind::Recover, why);
  ev.edge = {a, b, kNone, kNone};
  ev.count = flips;
  TraceAccess::plain(o, ev);
}

}  // namespace

bool CdtBuilder::crosses(VertexId a, VertexId b, VertexId c, VertexId d) const {
  if (c == kInfinite || d == kInfinite) return false;
  const double oc = orient2d(pt(a), pt(b), pt(c));
  const double od = orient2d(pt(a), pt(b), pt(d));
  return (oc < 0 && od > 0) || (oc > 0 && od < 0);
}

void CdtBuilder::recover(VertexId a, VertexId b, std::uint32_t seg) {
  st_.edges_crossed += crossings_.size();
  const std::size_t flips_before = st_.flips;
  switch (opt_.method) {
    case CdtMethod::Fast: recover_fast(a, b, seg); break;
    case CdtMethod::Ct: recover_flips(a, b, seg, false); break;
    case CdtMethod::Lawson: recover_flips(a, b, seg, true); break;
    case CdtMethod::Lifting: recover_lifting(a, b, seg); break;
  }
  if (TraceObserver* o = mesh_.trace()) [[unlikely]]
    trace_recovered(*o, a, b, method_reason(opt_.method), st_.flips - flips_before);
}

void CdtBuilder::trace_present(VertexId a, VertexId b) {
  if (TraceObserver* o = mesh_.trace()) [[unlikely]]
    trace_recovered(*o, a, b, TraceReason::Present, 0);
}

void CdtBuilder::trace_cavity(VertexId a, VertexId b) {
  TraceEvent ev = trace_event(deltamesh::TraceKind::Retriangulate, TraceReason::Fast);
  ev.edge = {a, b, kNone, kNone};
  TraceAccess::slots(*mesh_.trace(), ev, tv_.data(), slots_);
}

// ---------------------------------------------------------------------------
// Fast: cavity retriangulation.
//
// The k crossed edges h_i run from the right of ab to its left; the k + 1
// triangles they separate form the cavity. Its boundary is ab's left chain
// a = L0, L1, ..., b and right chain a = R0, R1, ..., b. Each side is an
// edge-visible pseudo-polygon whose constrained Delaunay triangulation is
// built recursively: for base uv and the chain between, the chain vertex c
// whose circle with uv contains no other chain vertex (one linear incircle
// scan: circles through u, v are nested on one side of uv) gives triangle
// uvc, then the chains u..c and c..v are done the same way (Anglada 1997).
// Both sides together need exactly k + 1 triangles: the cavity's slots.
//
// The cavity may enclose vertices (seed §1.2.2, Figure 4): every triangle
// around them is crossed, and a chain walks out to them and back along the
// same edges (L = ..., 607, 604, 607, ...). Such excursions are cut out of
// the chain, the sides triangulated without them, the spare slots freed,
// and the enclosed vertices inserted again by Delaunay insertion (which
// respects ab, constrained by then); a segment edge among the cut ones is
// inserted again as a segment piece.
//
// The cavity may even enclose triangles it does not contain: a chain then
// loops around them (R = ..., 1592, 1857, 1998, 1592, ...; the triangle
// 1592-1857-1998 is not crossed, its three neighbours are, wrapping around
// it from far vertex 1592). The side is then no longer an edge-visible
// polygon, and such pieces are handed to the Lifting method, whose flips
// work on any cavity (counted in method_fallbacks).

bool CdtBuilder::cut_excursions(std::vector<VertexId>& chain, std::vector<HalfEdgeId>& out) {
  const std::uint32_t live = new_vertex_stamp();
  std::size_t top = 0;  // chain[0..top] is the reduced chain, out[0..top) its edges
  vstamp_[chain[0]] = live;
  vpos_[chain[0]] = 0;
  for (std::size_t i = 1; i < chain.size(); ++i) {
    const VertexId v = chain[i];
    const HalfEdgeId o = out[i - 1];
    if (vstamp_[v] == live && vpos_[v] <= top && chain[vpos_[v]] == v) {
      // Back at v: everything after it was an excursion into the cavity.
      cut_edges_.push_back(o);
      while (chain[top] != v) {
        cut_vertices_.push_back(chain[top]);
        vstamp_[chain[top]] = 0;
        cut_edges_.push_back(out[top - 1]);
        --top;
      }
      continue;
    }
    if (vstamp_[v] == live) return false;  // not a walk out and back: give up
    ++top;
    chain[top] = v;
    out[top - 1] = o;
    vstamp_[v] = live;
    vpos_[v] = static_cast<std::uint32_t>(top);
  }
  chain.resize(top + 1);
  out.resize(top);
  return true;
}

void CdtBuilder::fast_gave_up(VertexId a, VertexId b, std::uint32_t seg) {
  ++st_.method_fallbacks;
  recover_lifting(a, b, seg);
}

void CdtBuilder::recover_fast(VertexId a, [[maybe_unused]] VertexId b, std::uint32_t seg) {
  const std::size_t k = crossings_.size();
  slots_.clear();
  left_.clear();
  right_.clear();
  left_out_.clear();
  right_out_.clear();
  // out[j] is the half-edge outside the cavity running from chain[j] to
  // chain[j + 1] (the cavity lies on its right).
  const HalfEdgeId h0 = crossings_[0];  // in triangle (a, R1, L1)
  slots_.push_back(tri_of(h0));
  left_.push_back(a);
  left_.push_back(tv_[next_edge(h0)]);
  left_out_.push_back(tw_[next_edge(h0)]);
  right_.push_back(a);
  right_.push_back(tv_[h0]);
  right_out_.push_back(tw_[prev_edge(h0)]);  // outside R1 -> a: reversed below
  for (std::size_t i = 0; i < k; ++i) {
    const HalfEdgeId g = tw_[crossings_[i]];  // w -> u in triangle (w, u, z)
    slots_.push_back(tri_of(g));
    const VertexId z = tv_[prev_edge(g)];
    const bool last = i + 1 == k;
    if (last || crossings_[i + 1] == prev_edge(g)) {  // z is right of ab (or b)
      right_.push_back(z);
      right_out_.push_back(tw_[next_edge(g)]);
    }
    if (last || crossings_[i + 1] == next_edge(g)) {  // z is left of ab (or b)
      left_.push_back(z);
      left_out_.push_back(tw_[prev_edge(g)]);
    }
  }
  // The right side is triangulated on base b -> a, its chain from b to a.
  std::reverse(right_.begin(), right_.end());
  std::reverse(right_out_.begin(), right_out_.end());

  // An enclosed vertex or triangle shows as a vertex met twice on a chain.
  bool repeats = false;
  for (const std::vector<VertexId>* chain : {&left_, &right_}) {
    const std::uint32_t now = new_vertex_stamp();
    for (VertexId v : *chain) {
      repeats = repeats || vstamp_[v] == now;
      vstamp_[v] = now;
    }
  }
  cut_vertices_.clear();
  cut_edges_.clear();
  if (repeats) {
    if (!cut_excursions(left_, left_out_) || !cut_excursions(right_, right_out_)) {
      fast_gave_up(a, b, seg);  // a chain that is no walk out and back: a cavity with holes
      return;
    }
    new_cavity_stamp();
    for (TriId t : slots_) cavity_stamp_[t] = stamp_;
    for (HalfEdgeId o : cut_edges_) {
      if (cavity_stamp_[tri_of(o)] != stamp_) {  // an edge cut out with the outside behind it
        fast_gave_up(a, b, seg);
        return;
      }
    }
  }

  std::size_t next_slot = 0;
  auto triangulate = [&](const std::vector<VertexId>& chain, const std::vector<HalfEdgeId>& out) -> HalfEdgeId {
    HalfEdgeId top = kNone;
    jobs_.clear();
    jobs_.push_back({0, static_cast<std::uint32_t>(chain.size() - 1), kNone});
    while (!jobs_.empty()) {
      const Job j = jobs_.back();
      jobs_.pop_back();
      const VertexId u = chain[j.lo], v = chain[j.hi];
      const Point& pu = pt(u);
      const Point& pv = pt(v);
      std::uint32_t c = j.lo + 1;
      for (std::uint32_t m = j.lo + 2; m < j.hi; ++m)
        if (incircle(pu, pv, pt(chain[c]), pt(chain[m])) > 0) c = m;
      const VertexId vc = chain[c];
      if (next_slot >= slots_.size()) internal("CdtBuilder::recover_fast", "cavity retriangulation needs more triangles than it removed");
      const TriId t = slots_[next_slot++];
      const HalfEdgeId e = 3 * t;
      tv_[e] = u;
      tv_[e + 1] = v;
      tv_[e + 2] = vc;
      flags_[e] = flags_[e + 1] = flags_[e + 2] = 0;
      if (ids_) seg_of_[e] = seg_of_[e + 1] = seg_of_[e + 2] = 0;
      if (j.parent == kNone) {
        top = e;
      } else {
        tw_[e] = j.parent;
        tw_[j.parent] = e;
      }
      auto link_out = [&](HalfEdgeId inner, HalfEdgeId o) {
        tw_[inner] = o;
        tw_[o] = inner;
        flags_[inner] = flags_[o];
        if (ids_) seg_of_[inner] = seg_of_[o];
      };
      if (c + 1 == j.hi)
        link_out(e + 1, out[c]);  // v -> c is the boundary edge c -> v
      else
        jobs_.push_back({c, j.hi, e + 1});
      if (c == j.lo + 1)
        link_out(e + 2, out[j.lo]);  // c -> u is the boundary edge u -> c
      else
        jobs_.push_back({j.lo, c, e + 2});
      ve_[u] = e;
      ve_[v] = e + 1;
      ve_[vc] = e + 2;
    }
    return top;
  };
  if (!cut_vertices_.empty()) {
    // Segment edges among the cut ones go back in as pieces (read their
    // flags before the slots are rewritten).
    for (HalfEdgeId o : cut_edges_)
      if ((flags_[o] & kConstrained) && tv_[o] < tv_[next_edge(o)])  // each edge once
        pieces_.push_back({tv_[o], tv_[next_edge(o)], seg_id(o)});
  }
  const HalfEdgeId top_left = triangulate(left_, left_out_);
  const HalfEdgeId top_right = triangulate(right_, right_out_);
  tw_[top_left] = top_right;
  tw_[top_right] = top_left;
  st_.cavity_triangles += slots_.size();
  mark(top_left, seg);
  if (cut_vertices_.empty()) {
    if (next_slot != slots_.size()) internal("CdtBuilder::recover_fast", "cavity retriangulation left triangles over");
    if (mesh_.trace()) [[unlikely]] trace_cavity(a, b);
    return;
  }
  for (std::size_t i = next_slot; i < slots_.size(); ++i) mesh_.remove_triangle(slots_[i]);
  if (mesh_.trace()) [[unlikely]] trace_cavity(a, b);
  for (VertexId v : cut_vertices_) ve_[v] = kNone;
  for (VertexId v : cut_vertices_) {
    if (inserter_.insert_existing(v, tri_of(top_left)).vertex != v)
      internal("CdtBuilder::recover_fast", "a vertex enclosed by a segment's cavity could not be inserted again");
  }
}

// ---------------------------------------------------------------------------
// Ct and Lawson.

void CdtBuilder::fallback_fast(VertexId a, VertexId b, std::uint32_t seg) {
  if (in_fallback_) internal("CdtBuilder::fallback_fast", "no recovery method could insert a segment piece");
  ++st_.method_fallbacks;
  struct Guard {
    bool& flag;
    explicit Guard(bool& f) : flag(f) { flag = true; }
    ~Guard() { flag = false; }
  } guard(in_fallback_);
  const Trace tr = trace(a, b);
  if (tr.kind == TraceKind::Present) {
    mark(tr.edge, seg);
    return;
  }
  if (tr.kind != TraceKind::Clean) internal("CdtBuilder::fallback_fast", "a segment piece changed while it was recovered");
  recover_fast(a, b, seg);
}

void CdtBuilder::recover_flips(VertexId a, VertexId b, std::uint32_t seg, bool lawson) {
  const std::size_t k = crossings_.size();
  // Flips keep triangle slots, so the cavity stays these k + 1 slots (and so
  // does a Fast fallback); Lawson starts from all their edges.
  lawson_stack_.clear();
  if (lawson) {
    auto add_tri = [&](TriId t) {
      for (int i = 0; i < 3; ++i) lawson_stack_.push_back(3 * t + i);
    };
    add_tri(tri_of(crossings_[0]));
    for (HalfEdgeId h : crossings_) add_tri(tri_of(tw_[h]));
  }
  queue_.clear();
  flipped_.clear();
  for (HalfEdgeId h : crossings_) queue_.emplace_back(tv_[h], tv_[next_edge(h)]);
  // Lemma 1.1 says a flippable, never flipped crossing edge always exists;
  // a whole pass over the queue without a flip means it does not (degenerate
  // input), and the flips are bounded by the cavity's vertex pairs.
  const std::size_t cap = (k + 2) * (k + 2) + 16;
  std::size_t failures = 0, flips = 0;
  bool done = true;
  while (!queue_.empty()) {
    const auto [u, v] = queue_.front();
    queue_.pop_front();
    const HalfEdgeId e = mesh_.find_edge(u, v);
    if (e == kNone) continue;  // cannot happen: only popped edges are flipped
    const HalfEdgeId f = tw_[e];
    const VertexId c = tv_[prev_edge(e)], d = tv_[prev_edge(f)];
    bool flippable = false;
    if (c != kInfinite && d != kInfinite && !flipped_.count(edge_key(c, d))) {
      const double ou = orient2d(pt(c), pt(d), pt(u)), ov = orient2d(pt(c), pt(d), pt(v));
      flippable = (ou < 0 && ov > 0) || (ou > 0 && ov < 0);
    }
    if (!flippable) {
      queue_.emplace_back(u, v);
      if (++failures > queue_.size()) {
        done = false;
        break;
      }
      continue;
    }
    failures = 0;
    flip(e);
    if (TraceObserver* o = mesh_.trace()) [[unlikely]] TraceAccess::flip_at(*o, TraceReason::Recovery, tv_.data(), e, f);
    ++st_.flips;
    flipped_.insert(edge_key(u, v));
    if (crosses(a, b, c, d)) queue_.emplace_back(c, d);
    if (++flips > cap) {
      done = false;
      break;
    }
  }
  if (done) {
    const HalfEdgeId ab = mesh_.find_edge(a, b);
    if (ab == kNone) internal("CdtBuilder::recover_flips", "no crossing edge is left but the segment is not an edge");
    mark(ab, seg);
  } else {
    fallback_fast(a, b, seg);
  }
  if (lawson) lawson_flips(lawson_stack_);
}

// Constrained Lawson flips from the half-edges on `stack` until every edge
// pushed is locally Delaunay. A flip pushes the four edges around it, so
// an edge that changes neighbours is always looked at again.
void CdtBuilder::lawson_flips(std::vector<HalfEdgeId>& stack) {
  MeshArrays arrays = MeshArrays::of(mesh_);
  arrays.markers = ids_ ? seg_of_.data() : nullptr;
  RawTopology<kCarryAll> topo(arrays);
  st_.flips += constrained_lawson(topo, stack);
}

// ---------------------------------------------------------------------------
// Lifting: flips ordered by a motion of the lifted points (cdt_lifting.hpp).
//
// The vertices right of ab rise at a rate proportional to their distance from
// the line ab. Inside the cavity (its boundary held fixed) the triangulation
// follows the lower hull of the moving lifted points: an edge flips when its
// quadrilateral's four lifted points become coplanar. Events sit in a
// priority queue keyed by their exact times; an event whose edge is gone or
// has other apexes by now is stale and skipped. Each flip makes new events
// for the new edge and the four around it.

void CdtBuilder::recover_lifting(VertexId a, VertexId b, std::uint32_t seg) {
  const Point pa = pt(a), pb = pt(b);
  // The cavity: the triangles crossed by ab (flips keep slots).
  new_cavity_stamp();
  lawson_stack_.clear();
  auto add_slot = [&](TriId t) {
    cavity_stamp_[t] = stamp_;
    for (int i = 0; i < 3; ++i) lawson_stack_.push_back(3 * t + i);
  };
  add_slot(tri_of(crossings_[0]));
  for (HalfEdgeId h : crossings_) add_slot(tri_of(tw_[h]));

  // Exact comparisons of event times multiply degree-4 expansions
  // (compare_kinetic_times scales the points by a power of two first): they
  // stay exact when the nonzero coordinates of the cavity span at most a
  // factor 2^80. Flips add no vertices, so checking the cavity's vertices
  // suffices; beyond that range the piece is done by Lawson's flips (a
  // fallback). Not by Fast: Fast gives up on a cavity with holes by calling
  // this function, which would call it again without end.
  {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    auto note = [&](const Point& q) {
      for (const double c : {std::fabs(q.x), std::fabs(q.y)}) {
        if (c == 0.0) continue;
        lo = std::min(lo, c);
        hi = std::max(hi, c);
      }
    };
    note(pa);
    note(pb);
    for (HalfEdgeId h : crossings_) {
      note(pt(tv_[h]));
      note(pt(tv_[next_edge(h)]));
    }
    if (hi > 0.0 && hi > lo * 0x1p80) {
      ++st_.method_fallbacks;
      recover_flips(a, b, seg, true);
      return;
    }
  }

  // Side of ab of each vertex, computed once per piece.
  const std::uint32_t sides = new_vertex_stamp();
  auto side = [&](VertexId v) -> int {
    if (vstamp_[v] != sides) {
      const double o = orient2d(pa, pb, pt(v));
      vstamp_[v] = sides;
      vpos_[v] = o > 0 ? 2 : (o < 0 ? 0 : 1);
    }
    return static_cast<int>(vpos_[v]) - 1;
  };
  // The heap holds small entries (time interval, index into events_).
  auto later = [&](const HeapEntry& hp, const HeapEntry& hq) {
    int s = compare_times(hp.time, hq.time);
    if (s != 0) return s > 0;
    const Event& p = events_[hp.index];
    const Event& q = events_[hq.index];
    s = compare_kinetic_times(pa, pb, p.quad, q.quad);
    if (s != 0) return s > 0;
    if (edge_key(p.x, p.y) != edge_key(q.x, q.y)) return edge_key(p.x, p.y) > edge_key(q.x, q.y);
    return edge_key(p.p, p.q) > edge_key(q.p, q.q);
  };
  events_.clear();
  heap_.clear();
  // An event for the edge of half-edge e, if it is inside the cavity and its
  // quadrilateral's lifted points will become coplanar.
  auto consider = [&](HalfEdgeId e) {
    const HalfEdgeId f = tw_[e];
    if (cavity_stamp_[tri_of(e)] != stamp_ || cavity_stamp_[tri_of(f)] != stamp_) return;
    Event ev;
    ev.x = tv_[e];
    ev.y = tv_[next_edge(e)];
    ev.p = tv_[prev_edge(e)];
    ev.q = tv_[prev_edge(f)];
    const VertexId ids[4] = {ev.x, ev.y, ev.p, ev.q};
    bool right[4];
    bool any_left = false, any_right = false;
    for (int i = 0; i < 4; ++i) {
      const int o = side(ids[i]);
      right[i] = o < 0;
      any_right = any_right || o < 0;
      any_left = any_left || o > 0;
    }
    // A quadrilateral on one (closed) side of ab moves by an affine function
    // of the position: its edge never flips (R1 = 0).
    if (!any_left || !any_right) return;
    ev.quad = Quad{pt(ev.x), pt(ev.y), pt(ev.p), pt(ev.q), right[0], right[1], right[2], right[3]};
    const KineticEvent k = kinetic_event(pa, pb, ev.quad);
    if (!k.happens) return;
    ev.time = k.time;
    heap_.push_back({k.time, static_cast<std::uint32_t>(events_.size())});
    events_.push_back(ev);
    std::push_heap(heap_.begin(), heap_.end(), later);
  };
  for (HalfEdgeId h : crossings_) consider(h);

  bool ok = true;
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const Event ev = events_[heap_.back().index];
    heap_.pop_back();
    const HalfEdgeId e = mesh_.find_edge(ev.x, ev.y);
    if (e == kNone) continue;
    const HalfEdgeId f = tw_[e];
    if (tv_[prev_edge(e)] != ev.p || tv_[prev_edge(f)] != ev.q) continue;  // stale
    const double ox = orient2d(pt(ev.p), pt(ev.q), pt(ev.x)), oy = orient2d(pt(ev.p), pt(ev.q), pt(ev.y));
    if (!((ox < 0 && oy > 0) || (ox > 0 && oy < 0))) {  // cannot happen (convex lift); guard
      ok = false;
      break;
    }
    flip(e);  // e's slot becomes (p, x, q), f's (q, y, p)
    if (TraceObserver* o = mesh_.trace()) [[unlikely]] TraceAccess::flip_at(*o, TraceReason::Lifting, tv_.data(), e, f);
    ++st_.flips;
    consider(prev_edge(e));  // the new edge q -> p
    consider(e);
    consider(next_edge(e));
    consider(f);
    consider(next_edge(f));
  }
  const HalfEdgeId ab = ok ? mesh_.find_edge(a, b) : kNone;
  if (ab != kNone) {
    mark(ab, seg);
    return;
  }
  // Degenerate input defeated the simulation: finish with Fast, then make
  // the cavity constrained Delaunay again.
  fallback_fast(a, b, seg);
  lawson_flips(lawson_stack_);
}

}  // namespace deltamesh::detail

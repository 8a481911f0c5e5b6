// Coarsening: vertices removed where the mesh is finer than a size field,
// keeping a constrained Delaunay triangulation. A vertex goes by flipping its
// degree down (the ear of least power first, after O. Devillers, "On
// deletion in Delaunay triangulations", IJCGA 2002) and removing it; then
// constrained Lawson flips restore the Delaunay property around its old star.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <queue>

#include "algo/adapt/common.hpp"
#include "core/plural.hpp"
#include "deltamesh/adapt.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/legalize.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

namespace {

using adaptation::Clock;
using adaptation::dist;
using adaptation::kMaxDegree;
using adaptation::seconds_since;

constexpr double kAltitudeScale = 1.1547005383792515;  // 2 / sqrt(3)
// Split points on a slanted segment are rounded off its line: a chain vertex
// this close to the line through its neighbours (relative to their
// distance) counts as on it. Far below the validator's 1e-9.
constexpr double kCollinearTolerance = 1e-11;
// ... and the chain turns there by less than this (sine of the angle).
constexpr double kMaxTurnSine = 1e-6;

// One coarsening: candidates in a heap by shortest edge / h (stale entries
// recognised by a stamp), removed one at a time.
class Coarsener {
 public:
  Coarsener(Mesh& mesh, const SizeField& h, const CoarsenOptions& opt, CoarsenStats& st)
      : m_(mesh), h_(h), opt_(opt), st_(st) {}

  void run() {
    if (!m_.compacted()) m_.compact();
    // Boundary edges are segments (as refine() treats them).
    for (HalfEdgeId e = 0; e < m_.triangle_vertices().size(); ++e)
      if (m_.twin(e) == kNone && !m_.is_constrained(e)) m_.constrain_edge(e, m_.edge_marker(e));
    const std::size_t n = m_.num_vertices();
    stamp_.assign(n, 0);
    mark_.assign(n, 0);
    refused_.assign(n, 0);
    h_at_.assign(n, NAN);
    for (VertexId v = 0; v < n; ++v)
      if (m_.out_edge(v) != kNone) ++st_.vertices_before;
    // A vertex where the boundary touches itself has several fans (one
    // boundary out-edge each); a rotation sees one, so it stays. Removals
    // keep the domain, so no new such vertex appears.
    std::vector<std::uint8_t> fans(n, 0);
    for (HalfEdgeId e = 0; e < m_.triangle_vertices().size(); ++e)
      if (m_.twin(e) == kNone && fans[m_.origin(e)] < 2) ++fans[m_.origin(e)];
    for (VertexId v = 0; v < n; ++v)
      if (fans[v] > 1) refused_[v] = 1;
    for (VertexId v = 0; v < n; ++v) consider(v);
    while (!heap_.empty()) {
      if (opt_.max_removals && st_.removed >= opt_.max_removals) break;
      const Entry top = heap_.top();
      heap_.pop();
      if (top.stamp != stamp_[top.v] || refused_[top.v]) continue;
      remove(top.v);
    }
    st_.vertices_after = st_.vertices_before - st_.removed;
  }

 private:
  enum class Kind { None, Interior, Segment };
  struct Star {
    Kind kind = Kind::None;
    bool boundary = false;
    bool huge = false;  // degree above kMaxDegree: left alone
    std::vector<HalfEdgeId> out;  // out-edges, counter-clockwise
    std::vector<VertexId> nbr;    // neighbours (out-edge ends, then the last in-edge's origin on the boundary)
    VertexId a = kNone, b = kNone;  // Segment: the two constrained neighbours
  };
  struct Entry {
    double key;
    VertexId v;
    std::uint32_t stamp;
    bool operator<(const Entry& o) const { return key > o.key; }  // min-heap
  };

  const Point& pt(VertexId v) const { return m_.point(v); }

  Star star(VertexId v) const {
    Star s;
    const HalfEdgeId start = m_.out_edge(v);
    if (start == kNone) return s;
    HalfEdgeId e = start;
    do {
      s.out.push_back(e);
      s.nbr.push_back(m_.dest(e));
      e = m_.rotate_ccw(e);
    } while (e != kNone && e != start && s.out.size() <= kMaxDegree);
    if (e == kNone) {
      s.boundary = true;
      s.nbr.push_back(m_.origin(prev_edge(s.out.back())));
    } else if (e != start) {
      s.huge = true;  // absurd degree: leave alone
      return s;
    }
    if (v < opt_.protect_first) return s;
    // Constrained neighbours and their edges' markers.
    std::vector<VertexId> cn;
    std::vector<int> cm;
    for (HalfEdgeId o : s.out)
      if (m_.is_constrained(o)) {
        cn.push_back(m_.dest(o));
        cm.push_back(m_.edge_marker(o));
      }
    if (s.boundary) {
      const HalfEdgeId in = prev_edge(s.out.back());
      if (m_.is_constrained(in)) {
        cn.push_back(m_.origin(in));
        cm.push_back(m_.edge_marker(in));
      }
    }
    // A vertex marker of its own marks a point that matters: it stays. Not
    // its own: 0, the one its segments give it (theirs, 1 on the boundary),
    // or, on segments without a marker (a boundary read without its .poly),
    // a neighbour's along the chain.
    const auto marker = [&](VertexId w) { return w < m_.vertex_markers().size() ? m_.vertex_markers()[w] : 0; };
    const int own = marker(v);
    if (cn.empty() && !s.boundary) {
      if (own == 0) s.kind = Kind::Interior;
    } else if (cn.size() == 2 && cm[0] == cm[1] &&
               (own == 0 || own == (cm[0] != 0 ? cm[0] : s.boundary ? 1 : 0) ||
                (cm[0] == 0 && (own == marker(cn[0]) || own == marker(cn[1]))))) {
      const Point &pa = pt(cn[0]), &pv = pt(v), &pb = pt(cn[1]);
      const double dot = (pa.x - pv.x) * (pb.x - pv.x) + (pa.y - pv.y) * (pb.y - pv.y);
      const double o = orient2d(pa, pv, pb);
      const double ab2 = (pa.x - pb.x) * (pa.x - pb.x) + (pa.y - pb.y) * (pa.y - pb.y);
      // Also the turn itself must be tiny: beside a very short edge, a
      // sharp corner is close to the line through its neighbours.
      const double turn_bound = kMaxTurnSine * dist(pa, pv) * dist(pv, pb);
      if ((o == 0 || (std::fabs(o) <= kCollinearTolerance * ab2 && std::fabs(o) <= turn_bound)) && dot < 0) {
        s.kind = Kind::Segment;
        s.a = cn[0];
        s.b = cn[1];
      }
    }
    return s;
  }

  // Pushes v when it is removable and finer than the field wants.
  void consider(VertexId v) {
    ++stamp_[v];
    if (refused_[v]) return;
    const Star s = star(v);
    // For good: each removal next to it would walk kMaxDegree spokes again.
    if (s.huge) refused_[v] = 1;
    if (s.kind == Kind::None) return;
    const Point& p = pt(v);
    if (std::isnan(h_at_[v])) h_at_[v] = h_(p.x, p.y);  // vertices do not move: one call each
    const double h = h_at_[v];
    if (!(h > 0) || !std::isfinite(h)) return;
    double lo = INFINITY, hi = 0;
    for (VertexId w : s.nbr) {
      const double d = dist(p, pt(w));
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    // A vertex close to an edge of its link (a flat triangle, often beside a
    // segment whose vertices went) counts as that close: its altitude over
    // the edge, scaled so that equilateral triangles change nothing.
    for (HalfEdgeId e : s.out) {
      const Point &q = pt(m_.dest(e)), &r = pt(m_.origin(prev_edge(e)));
      const double len = dist(q, r);
      if (len > 0) lo = std::min(lo, std::fabs((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)) / len * kAltitudeScale);
    }
    if (!(lo < opt_.ratio * h) || !(hi < opt_.max_spoke * h)) return;
    heap_.push({lo / h, v, stamp_[v]});
  }

  // Spoke e = v->w can be flipped when its quadrilateral is strictly convex;
  // then returns the power of v with respect to the circle of the ear
  // (y, w, x) the flip cuts off the star, else NaN.
  double ear_power(HalfEdgeId e) const {
    const HalfEdgeId f = m_.twin(e);
    if (f == kNone || m_.is_constrained(e)) return NAN;
    const VertexId v = m_.origin(e), w = m_.dest(e);
    const VertexId x = m_.origin(prev_edge(e)), y = m_.origin(prev_edge(f));
    const Point &pv = pt(v), &pw = pt(w), &px = pt(x), &py = pt(y);
    if (!(orient2d(px, pv, py) > 0) || !(orient2d(py, pw, px) > 0)) return NAN;
    // Circumcentre of (y, w, x) relative to w.
    const double bx = py.x - pw.x, by = py.y - pw.y, cx = px.x - pw.x, cy = px.y - pw.y;
    const double d = 2 * (bx * cy - by * cx);
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
    const double vx = pv.x - pw.x - ux, vy = pv.y - pw.y - uy;
    return vx * vx + vy * vy - (ux * ux + uy * uy);
  }

  // Flips spokes of v away (Devillers' ear of least power first) until
  // `keep` remain: all of v's spokes when from == kNone, else those strictly
  // between v->from and v->until counter-clockwise. False when none of them
  // can be flipped. Spokes are found again after every flip, which moves
  // edges between slots.
  bool reduce(VertexId v, VertexId from, VertexId until, std::size_t keep) {
    std::vector<HalfEdgeId>& spokes = spokes_;
    for (;;) {
      spokes.clear();
      if (from == kNone) {
        m_.for_each_out_edge(v, [&](HalfEdgeId e) {
          spokes.push_back(e);
          return true;
        });
      } else {
        const HalfEdgeId f = m_.find_edge(v, from);
        if (f == kNone) return false;
        HalfEdgeId e = m_.rotate_ccw(f);
        while (e != kNone && e != f && m_.dest(e) != until) {
          spokes.push_back(e);
          e = m_.rotate_ccw(e);
        }
      }
      if (spokes.size() <= keep) return true;
      HalfEdgeId best = kNone;
      double best_power = INFINITY;
      for (HalfEdgeId s : spokes) {
        const double p = ear_power(s);
        if (!std::isnan(p) && (best == kNone || p < best_power)) {
          best = s;
          best_power = p;
        }
      }
      if (best == kNone) return false;
      note_flip(best);
      changed_.push_back(tri_of(best));
      changed_.push_back(tri_of(m_.twin(best)));
      const HalfEdgeId best_twin = m_.twin(best);
      m_.flip(best);
      if (TraceObserver* o = m_.trace()) [[unlikely]]
        detail::TraceAccess::flip_at(*o, TraceReason::Coarsen, m_.triangle_vertices().data(), best, best_twin);
      ++st_.flips;
    }
  }

  // Flips get stuck at degree 4 when v lies on a diagonal of its link
  // (every vertex of a grid's Delaunay triangulation with that link): no
  // quadrilateral of a spoke is strictly convex. v is then the split point
  // of that diagonal, and unsplit_edge merges its four triangles into two.
  template <class NoteStar>
  bool unsplit_degree4(VertexId v, NoteStar&& note_star) {
    HalfEdgeId out[4];
    std::size_t d = 0;
    m_.for_each_out_edge(v, [&](HalfEdgeId e) {
      if (d < 4) out[d] = e;
      return ++d <= 4;
    });
    if (d != 4 || m_.twin(prev_edge(out[3])) != out[0]) return false;
    for (std::size_t k = 0; k < 2; ++k) {
      // g = v->b; a opposite; c and d the other two.
      const VertexId b = m_.dest(out[k]), c = m_.dest(out[k + 1]), a = m_.dest(out[k + 2]), e = m_.dest(out[(k + 3) % 4]);
      if (orient2d(pt(a), pt(v), pt(b)) != 0 || !(orient2d(pt(a), pt(b), pt(c)) > 0) ||
          !(orient2d(pt(b), pt(a), pt(e)) > 0))
        continue;
      note_star();
      m_.unsplit_edge(out[k]);
      return true;
    }
    return false;
  }

  void note_flip(HalfEdgeId e) {
    touch(m_.origin(e));
    touch(m_.dest(e));
    touch(m_.origin(prev_edge(e)));
    if (m_.twin(e) != kNone) touch(m_.origin(prev_edge(m_.twin(e))));
  }
  void touch(VertexId v) {
    if (!mark_[v]) {
      mark_[v] = 1;
      touched_.push_back(v);
    }
  }

  void remove(VertexId v) {
    const Star s = star(v);
    if (s.kind == Kind::None) return;
    // On the boundary, out_edge(v) is the most clockwise spoke (compact()
    // sets it; flips and the removals keep it).
    if (s.boundary && m_.twin(m_.out_edge(v)) != kNone) {
      refused_[v] = 1;
      ++st_.refused;
      return;
    }
    touched_.clear();
    changed_.clear();
    for (VertexId w : s.nbr) touch(w);
    bool ok = false;
    // The star's triangles left after the flips: the slots the removal keeps.
    const auto note_star = [&] {
      m_.for_each_out_edge(v, [&](HalfEdgeId e) {
        changed_.push_back(tri_of(e));
        return true;
      });
    };
    if (s.kind == Kind::Interior) {
      ok = reduce(v, kNone, kNone, 3);
      if (ok) {
        note_star();
        m_.remove_degree3_vertex(v);
      } else {
        ok = unsplit_degree4(v, note_star);
      }
    } else {
      // g = v->b; on the boundary b is the most clockwise neighbour.
      VertexId a = s.a, b = s.b;
      if (s.boundary) {
        b = m_.dest(m_.out_edge(v));
        a = b == s.a ? s.b : s.a;
      }
      ok = reduce(v, b, a, 1) && (s.boundary || reduce(v, a, b, 1));
      HalfEdgeId g = ok ? m_.find_edge(v, b) : kNone;
      // The merged triangles (a,b,c) and (b,a,d) must turn left exactly (v
      // may lie a rounding error off the line ab).
      if (g != kNone && !(orient2d(pt(a), pt(b), pt(m_.origin(prev_edge(g)))) > 0)) g = kNone;
      if (g != kNone && m_.twin(g) != kNone &&
          !(orient2d(pt(b), pt(a), pt(m_.origin(prev_edge(m_.twin(g))))) > 0))
        g = kNone;
      if (g != kNone) {
        note_star();
        m_.unsplit_edge(g);
        ++st_.removed_on_segments;
      }
      ok = g != kNone;
    }
    if (ok) {
      ++st_.removed;
      if (TraceObserver* o = m_.trace()) [[unlikely]] trace_removed(*o, v);
    } else {
      refused_[v] = 1;
      ++st_.refused;
    }
    lawson();
    for (VertexId w : touched_) {
      mark_[w] = 0;
      consider(w);
    }
  }

  // Vertex v is gone: its old star's slots (changed_) hold the triangles
  // that replace it.
  void trace_removed(TraceObserver& o, VertexId v) {
    TraceEvent ev = detail::trace_event(TraceKind::Remove, TraceReason::Coarsen);
    ev.vertex = v;
    ev.point = pt(v);
    detail::TraceAccess::slots(o, ev, m_.triangle_vertices().data(), changed_);
  }

  // The mesh for the kernel's constrained Lawson flips, with the
  // coarsener's bookkeeping: a flip touches its four vertices (each is
  // looked at again after the removal).
  class Topology : public detail::MeshTopology {
   public:
    explicit Topology(Coarsener& c) : MeshTopology(c.m_), c_(c) {}
    void flip(const detail::FlipQuad& q, TraceReason why) {
      c_.note_flip(q.e);
      MeshTopology::flip(q, why);
    }

   private:
    Coarsener& c_;
  };

  // Constrained Lawson flips from the edges of the triangles the removal and
  // its flips changed (the old star's area: only there, or on its outline,
  // can an edge have stopped being Delaunay). Not from every edge around the
  // touched vertices: next to a vertex of degree D that costs O(D) per
  // removal, O(D^2) to coarsen its fan.
  // (The kernel passes over the edges of dead slots: they have no twins.)
  void lawson() {
    std::vector<HalfEdgeId>& stack = stack_;
    stack.clear();
    for (TriId t : changed_)
      if (!m_.is_dead(t))
        for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) stack.push_back(e);
    Topology topo(*this);
    st_.flips += detail::constrained_lawson(topo, stack);
  }

  Mesh& m_;
  const SizeField& h_;
  const CoarsenOptions& opt_;
  CoarsenStats& st_;
  std::priority_queue<Entry> heap_;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::uint8_t> mark_, refused_;
  std::vector<double> h_at_;
  std::vector<VertexId> touched_;
  std::vector<TriId> changed_;  // triangle slots changed by the current removal
  std::vector<HalfEdgeId> stack_, spokes_;
};

}  // namespace

std::string CoarsenStats::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu -> %s (%zu removed, %zu of them on segments; %zu kept: star not emptied), %s, %.3f s",
                vertices_before, count_of(vertices_after, "vertex", "vertices").c_str(), removed, removed_on_segments,
                refused, count_of(flips, "flip", "flips").c_str(), seconds);
  return buf;
}

CoarsenStats coarsen(Mesh& mesh, const SizeField& h, const CoarsenOptions& options) {
  const auto t0 = Clock::now();
  CoarsenStats st;
  if (h) {
    Coarsener(mesh, h, options, st).run();
    mesh.compact();
  } else {
    // No field: nothing to remove, but the counts still describe the mesh.
    mesh.compact();
    for (VertexId v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.out_edge(v) != kNone) ++st.vertices_before;
    st.vertices_after = st.vertices_before;
  }
  if (options.renumber) st.new_id = mesh.remove_unused_vertices();
  st.seconds = seconds_since(t0);
  return st;
}

}  // namespace deltamesh

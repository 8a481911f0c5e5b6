// Adaptation to a metric field: split long edges, collapse short ones, swap
// for anisotropic quality, smooth in the metric (the loop of metric-based
// remeshers such as MMG2D; Dobrzynski & Frey, "Anisotropic Delaunay mesh
// adaptation for unsteady simulations", IMR 2008). Every decision that
// changes the topology or moves a vertex is guarded by exact orient2d.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <utility>

#include "algo/adapt/common.hpp"
#include "algo/adapt/metric_math.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/metric.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/editor.hpp"

namespace deltamesh {

std::string MetricAdaptStats::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu splits, %zu collapses, %zu swaps, %zu moves in %zu iterations, %zu triangles%s, %.3f s",
                splits, collapses, swaps, moves, iterations, triangles,
                vertex_budget_hit ? " (vertex budget reached)" : "", seconds);
  return buf;
}

namespace {

using adaptation::Clock;
using adaptation::dist;
using adaptation::kMaxDegree;
using adaptation::seconds_since;

constexpr double kLongEdge = M_SQRT2;
constexpr double kShortEdge = M_SQRT1_2;
// As coarsen(): a chain vertex this close to the line through its
// neighbours (relative to their distance) counts as on it, with a turn of
// sine below kMaxTurnSine.
constexpr double kCollinearTolerance = 1e-11;
constexpr double kMaxTurnSine = 1e-6;
// A swap or move must raise the worst quality by this factor (no cycles).
constexpr double kGain = 1.01;
constexpr double kCollapseFloor = 0.3;

enum class Kind { Fixed, Interior, Segment };

class MetricAdapter {
 public:
  MetricAdapter(Mesh& mesh, const MetricField& field, const MetricAdaptOptions& opt, MetricAdaptStats& st)
      : m_(mesh), field_(field), opt_(opt), st_(st) {}

  void run() {
    if (!m_.compacted()) m_.compact();
    // Boundary edges are segments (as coarsen() and refine() treat them).
    for (HalfEdgeId e = 0; e < m_.triangle_vertices().size(); ++e)
      if (m_.twin(e) == kNone && !m_.is_constrained(e)) m_.constrain_edge(e, m_.edge_marker(e));
    const std::size_t n = m_.num_vertices();
    pinned_.assign(n, 0);
    // A vertex where the boundary touches itself has several fans: it stays.
    std::vector<std::uint8_t> fans(n, 0);
    for (HalfEdgeId e = 0; e < m_.triangle_vertices().size(); ++e)
      if (m_.twin(e) == kNone && fans[m_.origin(e)] < 2) ++fans[m_.origin(e)];
    for (VertexId v = 0; v < n; ++v) pinned_[v] = v < opt_.protect_first || fans[v] > 1;
    met_.resize(n);
    lg_.resize(n);
    for (VertexId v = 0; v < n; ++v)
      if (m_.out_edge(v) != kNone) set_metric(v);
    for (int it = 0; it < opt_.iterations; ++it) {
      const std::size_t before = st_.splits + st_.collapses;
      const std::size_t swaps_before = st_.swaps;
      split_pass();
      after("split");
      collapse_pass();
      after("collapse");
      for (int k = 0; k < 4; ++k) {
        const bool swapped = swap_pass();
        after("swap");
        if (!swapped) break;
      }
      for (int k = 0; k < opt_.smooth_passes; ++k) {
        const bool moved = smooth_pass();
        after("smooth");
        if (!moved) break;
        swap_pass();
        after("swap");
      }
      ++st_.iterations;
      const std::size_t changed = st_.splits + st_.collapses - before;
      if (changed <= live_vertices_ / 200 && (it > 0 || changed == 0) && st_.swaps - swaps_before <= live_vertices_ / 100)
        break;
    }
    m_.compact();
    m_.remove_unused_vertices();
    st_.triangles = m_.num_triangles();
  }

 private:
  const Point& pt(VertexId v) const { return m_.point(v); }

  // Compacting between passes is safe (each pass sweeps the slots anew), and
  // done with or without a callback so that it sees the same run.
  void after(const char* pass) {
    m_.compact();
    if (opt_.after_pass) opt_.after_pass(m_, pass);
  }

  Metric eval(const Point& p) const {
    const Metric mt = field_(p.x, p.y);
    const std::string why = metric_problem(mt);
    if (!why.empty()) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "the metric field at (%.17g, %.17g) ", p.x, p.y);
      throw InputError(buf + why);
    }
    return mt;
  }
  void set_metric(VertexId v) {
    met_[v] = eval(pt(v));
    lg_[v] = adaptation::log_metric(met_[v]);
    ++live_vertices_;
  }

  // The metric length of ab by Simpson's rule, with the field at the
  // midpoint: the length the split at that midpoint will see. The
  // endpoints alone (edge_length_in_metrics) miss how the field varies
  // between them: across a graded layer, splits made halves that the
  // collapse pass took back, pass after pass, until the iteration limit.
  double length(VertexId a, VertexId b) {
    const Point &p = pt(a), &q = pt(b);
    const double dx = q.x - p.x, dy = q.y - p.y;
    const Point mp{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
    return (metric_length(met_[a], dx, dy) + 4 * metric_length(midpoint_metric(a, b, mp), dx, dy) +
            metric_length(met_[b], dx, dy)) /
           6;
  }
  // The field at an edge's midpoint, cached per vertex pair (valid while
  // the midpoint stays: smoothing moves vertices, ids are never reused).
  const Metric& midpoint_metric(VertexId a, VertexId b, const Point& mp) {
    const std::uint64_t key = std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
    const auto it = mid_.find(key);
    if (it != mid_.end() && it->second.first.x == mp.x && it->second.first.y == mp.y) return it->second.second;
    const Metric m = eval(mp);  // may throw: nothing is cached then
    return (mid_[key] = {mp, m}).second;
  }
  Metric tri_metric(const Metric& la, const Metric& lb, const Metric& lc) const {
    return adaptation::exp_sym(adaptation::mean3(la, lb, lc));
  }
  double quality(VertexId a, VertexId b, VertexId c) const {
    return metric_quality(pt(a), pt(b), pt(c), tri_metric(lg_[a], lg_[b], lg_[c]));
  }

  // ---- classification (the rules of coarsen()) ----------------------------

  struct Star {
    bool boundary = false;
    std::vector<HalfEdgeId> out;  // counter-clockwise
    std::vector<VertexId> cn;     // constrained neighbours
    std::vector<int> cm;          // ... their edges' markers
  };

  Kind classify(VertexId v, Star& s) const {
    s.boundary = adaptation::star_of(m_, v, s.out, kMaxDegree);
    s.cn.clear();
    s.cm.clear();
    if (s.out.empty() || s.out.size() > kMaxDegree || pinned_[v]) return Kind::Fixed;
    for (HalfEdgeId o : s.out)
      if (m_.is_constrained(o)) {
        s.cn.push_back(m_.dest(o));
        s.cm.push_back(m_.edge_marker(o));
      }
    if (s.boundary) {
      const HalfEdgeId in = prev_edge(s.out.back());
      if (m_.is_constrained(in)) {
        s.cn.push_back(m_.origin(in));
        s.cm.push_back(m_.edge_marker(in));
      }
    }
    const auto marker = [&](VertexId w) { return w < m_.vertex_markers().size() ? m_.vertex_markers()[w] : 0; };
    const int own = marker(v);
    if (s.cn.empty() && !s.boundary) return own == 0 ? Kind::Interior : Kind::Fixed;
    if (s.cn.size() == 2 && s.cm[0] == s.cm[1] &&
        (own == 0 || own == (s.cm[0] != 0 ? s.cm[0] : s.boundary ? 1 : 0) ||
         (s.cm[0] == 0 && (own == marker(s.cn[0]) || own == marker(s.cn[1]))))) {
      const Point &pa = pt(s.cn[0]), &pv = pt(v), &pb = pt(s.cn[1]);
      const double dot = (pa.x - pv.x) * (pb.x - pv.x) + (pa.y - pv.y) * (pb.y - pv.y);
      const double o = orient2d(pa, pv, pb);
      const double ab2 = (pa.x - pb.x) * (pa.x - pb.x) + (pa.y - pb.y) * (pa.y - pb.y);
      const double turn_bound = kMaxTurnSine * dist(pa, pv) * dist(pv, pb);
      if ((o == 0 || (std::fabs(o) <= kCollinearTolerance * ab2 && std::fabs(o) <= turn_bound)) && dot < 0)
        return Kind::Segment;
    }
    return Kind::Fixed;
  }

  // ---- split ----------------------------------------------------------------

  // Edges (as vertex pairs) whose metric length is above `above` or below
  // `below`, longest (shortest) first. Splits and collapses rewrite
  // triangle slots, so a sweep over slots would skip edges that moved.
  struct Candidate {
    double length;
    VertexId a, b;
  };
  std::vector<Candidate> candidates(bool longest) {
    std::vector<Candidate> c;
    for (HalfEdgeId e = 0; e < m_.triangle_vertices().size(); ++e) {
      if (!m_.is_real(tri_of(e))) continue;
      const HalfEdgeId tw = m_.twin(e);
      if (tw != kNone && tw < e) continue;
      const VertexId a = m_.origin(e), b = m_.dest(e);
      const double l = length(a, b);
      if (longest ? l > kLongEdge : l < kShortEdge) c.push_back({l, a, b});
    }
    std::sort(c.begin(), c.end(), [&](const Candidate& x, const Candidate& y) {
      return longest ? x.length > y.length : x.length < y.length;
    });
    return c;
  }

  // The half-edge a -> b, or b -> a on the boundary, or kNone.
  HalfEdgeId find(VertexId a, VertexId b) {
    const bool boundary = adaptation::star_of(m_, a, scratch2_, kMaxDegree);
    for (HalfEdgeId o : scratch2_)
      if (m_.dest(o) == b) return o;
    if (boundary && !scratch2_.empty() && m_.origin(prev_edge(scratch2_.back())) == b) return prev_edge(scratch2_.back());
    return kNone;
  }

  // Each edge longer than sqrt 2 (at the pass's start, longest first) is
  // split at its midpoint when the halves of each side stay
  // counter-clockwise (exact).
  void split_pass() {
    for (const Candidate& cand : candidates(true)) {
      if (opt_.max_vertices && live_vertices_ >= opt_.max_vertices) {
        st_.vertex_budget_hit = true;
        return;
      }
      const HalfEdgeId e = find(cand.a, cand.b);
      if (e == kNone) continue;
      const HalfEdgeId tw = m_.twin(e);
      const bool constrained = m_.is_constrained(e);
      if (constrained && !opt_.split_segments) continue;
      const VertexId a = m_.origin(e), b = m_.dest(e);
      if (length(a, b) <= kLongEdge) continue;
      const Point mp{0.5 * (pt(a).x + pt(b).x), 0.5 * (pt(a).y + pt(b).y)};
      const VertexId c = m_.origin(prev_edge(e));
      // On the boundary the rounded midpoint must not leave the domain (it
      // could land on another part of the boundary across a slit).
      if (tw == kNone && orient2d(pt(a), pt(b), mp) < 0) continue;
      if (!(orient2d(pt(a), mp, pt(c)) > 0 && orient2d(mp, pt(b), pt(c)) > 0)) continue;
      if (tw != kNone) {
        const VertexId d = m_.origin(prev_edge(tw));
        if (!(orient2d(pt(b), mp, pt(d)) > 0 && orient2d(mp, pt(a), pt(d)) > 0)) continue;
      }
      const Metric mm = eval(mp);
      const VertexId v = m_.add_vertex(mp);
      met_.push_back(mm);
      lg_.push_back(adaptation::log_metric(mm));
      pinned_.push_back(0);
      ++live_vertices_;
      if (!m_.vertex_markers().empty()) {
        const int mk = m_.edge_marker(e);
        m_.vertex_markers().push_back(constrained ? (mk != 0 ? mk : tw == kNone ? 1 : 0) : 0);
      }
      const std::size_t na = m_.num_vertex_attributes();
      if (na > 0) {
        std::vector<double>& at = m_.vertex_attributes();
        at.resize(at.size() + na);
        for (std::size_t k = 0; k < na; ++k) at[v * na + k] = 0.5 * (at[a * na + k] + at[b * na + k]);
      }
      m_.split_edge(e, v);
      ++st_.splits;
    }
  }

  // ---- collapse ---------------------------------------------------------------

  void collapse_pass() {
    for (const Candidate& cand : candidates(false)) {
      if (m_.out_edge(cand.a) == kNone || m_.out_edge(cand.b) == kNone) continue;
      if (find(cand.a, cand.b) == kNone || length(cand.a, cand.b) >= kShortEdge) continue;
      if (!try_collapse(cand.a, cand.b)) try_collapse(cand.b, cand.a);
    }
  }

  // Collapses v onto its neighbour w when v may go (free, or along its
  // straight chain towards w), the link condition holds, every triangle
  // that takes w for v stays counter-clockwise (exact), no new edge is
  // longer than sqrt 2 and the worst quality does not halve.
  bool try_collapse(VertexId v, VertexId w) {
    const Kind kind = classify(v, star_);
    if (kind == Kind::Fixed) return false;
    if (kind == Kind::Segment && w != star_.cn[0] && w != star_.cn[1]) return false;
    if (kind == Kind::Interior && star_.boundary) return false;
    if (kind == Kind::Segment && star_.boundary) {
      // The boundary runs u -> v -> x (the domain on its left). Where v is a
      // reflex vertex by rounding (left of u -> x), the new edge u-x would
      // leave the domain and might cross another part of its boundary.
      const VertexId u = m_.origin(prev_edge(star_.out.back())), x = m_.dest(star_.out.front());
      if (orient2d(pt(u), pt(x), pt(v)) > 0) return false;
    }
    const std::vector<HalfEdgeId>& out = star_.out;
    // Triangles of v: (v, dest(o), dest(rotate_ccw(o))) = (v, x, y).
    std::size_t with_w = 0;
    double old_q = INFINITY, new_q = INFINITY;
    ++stamp_;
    if (mark_.size() < m_.num_vertices()) mark_.resize(m_.num_vertices(), 0);
    adaptation::neighbors_of(m_, w, scratch_, nbr_);
    for (VertexId u : nbr_) mark_[u] = stamp_;
    std::size_t common = 0;
    adaptation::neighbors_of(m_, v, scratch_, nbr_);
    for (VertexId u : nbr_)
      if (u != w && mark_[u] == stamp_) ++common;
    for (HalfEdgeId o : out) {
      const VertexId x = m_.dest(o), y = m_.origin(prev_edge(o));
      old_q = std::min(old_q, quality(v, x, y));
      if (x == w || y == w) {
        ++with_w;
        // v's edge to the third vertex must have a twin (it merges with w's),
        // and two segments must not merge (in a sliver whose third vertex is
        // v's chain neighbour, v's edge to it is a segment).
        const HalfEdgeId vedge = x == w ? prev_edge(o) : o;  // y->v or v->x
        if (m_.twin(vedge) == kNone) return false;
        if (m_.is_constrained(vedge) && m_.is_constrained(next_edge(o))) return false;
        continue;
      }
      if (!(orient2d(pt(w), pt(x), pt(y)) > 0)) return false;
      new_q = std::min(new_q, quality(w, x, y));
    }
    if (with_w == 0 || with_w == out.size() || common != with_w) return false;  // link condition
    for (VertexId u : nbr_)
      if (u != w && length(w, u) > kLongEdge) return false;
    // No new triangle worse than kCollapseFloor, or than the old worst
    // when that was already below it: repeated collapses cannot wear the
    // quality down.
    if (new_q < std::min(old_q, kCollapseFloor)) return false;
    collapse(v, w, out);
    ++st_.collapses;
    --live_vertices_;
    return true;
  }

  struct Dead {
    TriId t;
    HalfEdgeId tv, tw_, hw;  // twin of v's edge to x, twin of w's edge to x, w's edge to x
    VertexId x;
  };
  // v's edge to x inside the dead triangle (the twin of tv).
  HalfEdgeId twin_of_vedge(const Dead& d) const { return m_.twin(d.tv); }

  void collapse(VertexId v, VertexId w, const std::vector<HalfEdgeId>& out) {
    Dead dead[2];
    int nd = 0;
    std::vector<HalfEdgeId>& live = scratch2_;
    live.clear();
    for (HalfEdgeId o : out) {
      const VertexId x = m_.dest(o), y = m_.origin(prev_edge(o));
      if (x == w) {  // (v, w, y): v's edge y->v, w's edge w->y
        const HalfEdgeId hw = next_edge(o);
        dead[nd++] = {tri_of(o), m_.twin(prev_edge(o)), m_.twin(hw), hw, y};
      } else if (y == w) {  // (v, x, w): v's edge v->x, w's edge x->w
        const HalfEdgeId hw = next_edge(o);
        dead[nd++] = {tri_of(o), m_.twin(o), m_.twin(hw), hw, x};
      } else {
        live.push_back(o);
      }
    }
    // The merged edge is a segment when either part was (w's edge, or v's
    // edge to a chain neighbour that closes a sliver).
    std::uint8_t flags[2];
    int markers[2];
    for (int i = 0; i < nd; ++i) {
      const HalfEdgeId ve = twin_of_vedge(dead[i]);
      const bool v_seg = m_.is_constrained(ve);
      flags[i] = m_.edge_flags(dead[i].hw) | m_.edge_flags(ve);
      markers[i] = v_seg ? m_.edge_marker(ve) : m_.edge_marker(dead[i].hw);
    }
    detail::MeshEditor ed(m_);
    std::vector<VertexId>& tv = ed.triangle_vertices();
    for (HalfEdgeId o : live) tv[o] = w;
    for (int i = 0; i < nd; ++i) m_.remove_triangle(dead[i].t);
    for (int i = 0; i < nd; ++i) {
      const Dead& d = dead[i];
      if (d.tw_ != kNone) {
        m_.link(d.tv, d.tw_);
      } else {
        ed.twins()[d.tv] = kNone;
      }
      m_.set_edge_flags(d.tv, flags[i]);
      m_.set_edge_marker(d.tv, markers[i]);
      if (d.tw_ != kNone) {
        m_.set_edge_flags(d.tw_, flags[i]);
        m_.set_edge_marker(d.tw_, markers[i]);
      }
      // x's out-edge may have been in the dead triangle: tv's triangle has
      // one from x. tv runs w->x or x->w.
      const HalfEdgeId from_x = m_.origin(d.tv) == d.x ? d.tv : next_edge(d.tv);
      m_.set_out_edge(d.x, from_x);
    }
    m_.set_out_edge(w, live.front());
    m_.set_out_edge(v, kNone);
  }

  // ---- swap ---------------------------------------------------------------

  bool swap_pass() {
    std::size_t swaps = 0;
    const HalfEdgeId end = static_cast<HalfEdgeId>(m_.triangle_vertices().size());
    for (HalfEdgeId e = 0; e < end; ++e) {
      if (!m_.is_real(tri_of(e))) continue;
      const HalfEdgeId tw = m_.twin(e);
      if (tw == kNone || tw < e || m_.is_constrained(e)) continue;
      const VertexId a = m_.origin(e), b = m_.dest(e), c = m_.origin(prev_edge(e)), d = m_.origin(prev_edge(tw));
      // (a,b,c) and (b,a,d) become (a,d,c) and (d,b,c): strictly convex quad.
      if (!(orient2d(pt(a), pt(d), pt(c)) > 0 && orient2d(pt(d), pt(b), pt(c)) > 0)) continue;
      const double before = std::min(quality(a, b, c), quality(b, a, d));
      const double after = std::min(quality(a, d, c), quality(d, b, c));
      if (!(after > kGain * before)) continue;
      m_.flip(e);
      ++swaps;
    }
    st_.swaps += swaps;
    return swaps > 0;
  }

  // ---- smooth ---------------------------------------------------------------

  // Each free interior vertex moves towards the mean of the points at unit
  // metric length from its neighbours on the edges towards it; the full,
  // then the half step is taken when every triangle of its star stays
  // counter-clockwise (exact) and the star's worst quality rises.
  bool smooth_pass() {
    std::size_t moves = 0;
    for (VertexId v = 0; v < m_.num_vertices(); ++v) {
      if (classify(v, star_) != Kind::Interior) continue;
      const std::vector<HalfEdgeId>& out = star_.out;
      const Point p = pt(v);
      double sx = 0, sy = 0;
      double old_q = INFINITY, old_sum = 0;
      bool degenerate = false;
      for (HalfEdgeId o : out) {
        const VertexId x = m_.dest(o);
        const double l = length(v, x);
        if (!(l > 0)) {
          degenerate = true;
          break;
        }
        const Point& q = pt(x);
        sx += q.x + (p.x - q.x) / l;
        sy += q.y + (p.y - q.y) / l;
        const double q0 = quality(v, x, m_.origin(prev_edge(o)));
        old_q = std::min(old_q, q0);
        old_sum += q0;
      }
      if (degenerate) continue;
      const Point target{sx / double(out.size()), sy / double(out.size())};
      for (double step : {1.0, 0.5}) {
        const Point np{p.x + step * (target.x - p.x), p.y + step * (target.y - p.y)};
        if (np.x == p.x && np.y == p.y) break;
        bool ok = true;
        for (HalfEdgeId o : out)
          if (!(orient2d(np, pt(m_.dest(o)), pt(m_.origin(prev_edge(o)))) > 0)) {
            ok = false;
            break;
          }
        if (!ok) continue;
        const Metric nm = eval(np);
        const Metric nl = adaptation::log_metric(nm);
        double new_q = INFINITY, new_sum = 0;
        for (HalfEdgeId o : out) {
          const VertexId x = m_.dest(o), y = m_.origin(prev_edge(o));
          const double q1 = metric_quality(np, pt(x), pt(y), tri_metric(nl, lg_[x], lg_[y]));
          new_q = std::min(new_q, q1);
          new_sum += q1;
        }
        // The worst never drops; the worst or the mean must rise.
        if (!(new_q >= old_q && (new_q > kGain * old_q || new_sum > kGain * old_sum))) continue;
        detail::MeshEditor(m_).points()[v] = np;
        met_[v] = nm;
        lg_[v] = nl;
        ++moves;
        break;
      }
    }
    st_.moves += moves;
    return moves > 0;
  }

  Mesh& m_;
  const MetricField& field_;
  const MetricAdaptOptions& opt_;
  MetricAdaptStats& st_;
  std::vector<Metric> met_, lg_;
  std::unordered_map<std::uint64_t, std::pair<Point, Metric>> mid_;
  std::vector<std::uint8_t> pinned_;
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
  std::size_t live_vertices_ = 0;
  Star star_;
  std::vector<HalfEdgeId> scratch_, scratch2_;
  std::vector<VertexId> nbr_;
};

}  // namespace

MetricAdaptStats adapt_to_metric(Mesh& mesh, const MetricField& metric, const MetricAdaptOptions& options) {
  const auto t0 = Clock::now();
  MetricAdaptStats st;
  if (!metric) throw InputError("adapt_to_metric needs a metric field");
  if (mesh.num_triangles() == 0) return st;
  MetricAdapter(mesh, metric, options, st).run();
  st.seconds = seconds_since(t0);
  return st;
}

}  // namespace deltamesh

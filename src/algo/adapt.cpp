// Mesh adaptation (seed §4): coarsening by vertex removal, then refinement.
#include "deltamesh/adapt.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <queue>

#include "algo/cdt_builder.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"

namespace deltamesh {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double dist(const Point& a, const Point& b) { return std::hypot(a.x - b.x, a.y - b.y); }

constexpr double kAltitudeScale = 1.1547005383792515;  // 2 / sqrt(3)
// Split points on a slanted segment are rounded off its line: a chain vertex
// this close to the line through its neighbours (relative to their
// distance) counts as on it. Far below the validator's 1e-9.
constexpr double kCollinearTolerance = 1e-11;
// ... and the chain turns there by less than this (sine of the angle).
constexpr double kMaxTurnSine = 1e-6;
// Vertices of higher degree are never removed (reducing one costs O(degree^2)).
constexpr std::size_t kMaxDegree = 4096;

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
      m_.flip(best);
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

  // Constrained Lawson flips from the edges of the triangles the removal and
  // its flips changed (the old star's area: only there, or on its outline,
  // can an edge have stopped being Delaunay). Not from every edge around the
  // touched vertices: next to a vertex of degree D that costs O(D) per
  // removal, O(D^2) to coarsen its fan.
  void lawson() {
    std::vector<HalfEdgeId>& stack = stack_;
    stack.clear();
    for (TriId t : changed_)
      if (!m_.is_dead(t))
        for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) stack.push_back(e);
    while (!stack.empty()) {
      const HalfEdgeId e = stack.back();
      stack.pop_back();
      const HalfEdgeId f = m_.twin(e);
      if (f == kNone || m_.is_constrained(e) || m_.is_dead(tri_of(e))) continue;
      const Point& a = pt(m_.origin(e));
      const Point& b = pt(m_.dest(e));
      const Point& c = pt(m_.origin(prev_edge(e)));
      const Point& d = pt(m_.origin(prev_edge(f)));
      if (!(incircle(a, b, c, d) > 0)) continue;  // d inside also makes the quad strictly convex
      note_flip(e);
      m_.flip(e);
      ++st_.flips;
      stack.push_back(e);
      stack.push_back(next_edge(e));
      stack.push_back(f);
      stack.push_back(next_edge(f));
    }
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

// Smallest angle of triangle (a, b, c) in degrees.
double min_angle_of(const Point& a, const Point& b, const Point& c) {
  const auto at = [](const Point& p, const Point& q, const Point& r) {
    const double ux = q.x - p.x, uy = q.y - p.y, wx = r.x - p.x, wy = r.y - p.y;
    return std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
  };
  return std::min({at(a, b, c), at(b, c, a), at(c, a, b)}) * (180.0 / std::numbers::pi);
}

// Smallest and mean smallest angle over the live real triangles.
void angle_stats(const Mesh& m, double& lo, double& mean) {
  lo = 180.0;
  double sum = 0;
  std::size_t n = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const double a = min_angle_of(m.point(v[0]), m.point(v[1]), m.point(v[2]));
    lo = std::min(lo, a);
    sum += a;
    ++n;
  }
  mean = n ? sum / double(n) : 0.0;
  if (!n) lo = 0.0;
}

class Smoother {
 public:
  Smoother(Mesh& mesh, const SmoothOptions& opt, SmoothStats& st) : m_(mesh), opt_(opt), st_(st) {}

  void run() {
    if (!m_.compacted()) m_.compact();
    const std::size_t n = m_.num_vertices();
    std::vector<VertexId> movable;
    for (VertexId v = 0; v < n; ++v)
      if (is_free(v)) movable.push_back(v);
    // Flips neither create nor remove constrained or boundary edges, so the
    // free vertices stay free.
    for (int pass = 0; pass < opt_.passes; ++pass) {
      std::size_t moved = 0;
      for (VertexId v : movable) moved += try_move(v);
      st_.moved += moved;
      ++st_.passes;
      // A move keeps every star triangle counter-clockwise, so the mesh stays
      // a valid triangulation, but edges may stop being locally Delaunay.
      // Each Lawson flip replaces two triangles by the two on the other
      // diagonal, and when the edge is not locally Delaunay the other
      // diagonal's pair has the larger smallest angle (Delaunay maximises the
      // smallest angle over the two triangulations of a convex
      // quadrilateral). So the flips never lower the mesh's smallest angle:
      // with the move guard, it never decreases.
      st_.flips += detail::constrained_lawson_flips(m_);
      if (moved == 0) break;
    }
  }

 private:
  bool is_free(VertexId v) const {
    if (v < opt_.protect_first || m_.out_edge(v) == kNone) return false;
    const auto& mk = m_.vertex_markers();
    if (v < mk.size() && mk[v] != 0) return false;  // a point with a marker of its own matters
    const HalfEdgeId start = m_.out_edge(v);
    HalfEdgeId e = start;
    std::size_t degree = 0;
    do {
      if (m_.is_constrained(e) || ++degree > kMaxDegree) return false;
      e = m_.rotate_ccw(e);
    } while (e != kNone && e != start);
    return e == start;  // kNone: on the boundary
  }

  double h_at(double x, double y) const {
    if (!opt_.h) return -1.0;
    const double v = opt_.h(x, y);
    return v > 0 && std::isfinite(v) ? v : -1.0;
  }

  // The star of v with v at q: smallest angle, worst longest-edge / h and
  // worst area / max_area (0 without a bound). False when a triangle does
  // not turn left (exact).
  struct Quality {
    double angle = 180.0, size = 0.0, area = 0.0;
  };
  bool quality(const Point& q, Quality& out) const {
    const std::size_t k = link_.size();
    for (std::size_t i = 0; i < k; ++i) {
      const Point &a = m_.point(link_[i]), &b = m_.point(link_[(i + 1) % k]);
      if (!(orient2d(q, a, b) > 0)) return false;
      out.angle = std::min(out.angle, min_angle_of(q, a, b));
      if (opt_.h) {
        const double h = h_at((q.x + a.x + b.x) / 3, (q.y + a.y + b.y) / 3);
        if (h > 0) out.size = std::max(out.size, std::max({dist(q, a), dist(a, b), dist(b, q)}) / h);
      }
      if (opt_.max_area > 0)
        out.area = std::max(out.area, 0.5 * ((a.x - q.x) * (b.y - q.y) - (a.y - q.y) * (b.x - q.x)) / opt_.max_area);
    }
    return true;
  }

  bool target(const Point& p, Point& t) const {
    const std::size_t k = link_.size();
    double sx = 0, sy = 0, sw = 0;
    for (std::size_t i = 0; i < k; ++i) {
      const Point &a = m_.point(link_[i]), &b = m_.point(link_[(i + 1) % k]);
      if (opt_.target == SmoothTarget::Laplacian) {
        sx += a.x;
        sy += a.y;
        sw += 1;
        continue;
      }
      // Circumcentre of (p, a, b) relative to p, weighted by the area.
      const double bx = a.x - p.x, by = a.y - p.y, cx = b.x - p.x, cy = b.y - p.y;
      const double d = 2 * (bx * cy - by * cx);
      if (!(d > 0)) return false;
      const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
      const double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
      double w = d / 4;  // area
      const double h = h_at(p.x + (bx + cx) / 3, p.y + (by + cy) / 3);
      if (h > 0) w /= (h * h) * (h * h);  // density h^-4: optimal 2D meshes have edges ~ density^(-1/4)
      sx += w * (p.x + ux);
      sy += w * (p.y + uy);
      sw += w;
    }
    if (!(sw > 0)) return false;
    t = {sx / sw, sy / sw};
    return std::isfinite(t.x) && std::isfinite(t.y);
  }

  // 1 when v moved.
  std::size_t try_move(VertexId v) {
    link_.clear();
    m_.for_each_out_edge(v, [&](HalfEdgeId e) {
      link_.push_back(m_.dest(e));
      return true;
    });
    const Point p = m_.point(v);
    Point t;
    if (!target(p, t) || (t.x == p.x && t.y == p.y)) return 0;
    Quality before;
    quality(p, before);
    const double angle_floor = opt_.min_angle_deg < 0 ? before.angle : std::min(before.angle, opt_.min_angle_deg);
    for (const double step : {1.0, 0.5}) {
      const Point q{p.x + step * (t.x - p.x), p.y + step * (t.y - p.y)};
      Quality after;
      if (!quality(q, after) || !(after.angle >= angle_floor) || !(after.size <= std::max(1.0, before.size)) ||
          !(after.area <= std::max(1.0, before.area)))
        continue;
      m_.points_mut()[v] = q;
      return 1;
    }
    ++st_.rejected;
    return 0;
  }

  Mesh& m_;
  const SmoothOptions& opt_;
  SmoothStats& st_;
  std::vector<VertexId> link_;
};

// Sizes at the vertices of a copy of a background mesh.
class BackgroundField {
 public:
  BackgroundField(const Mesh& bg, std::span<const double> sizes) : m_(bg), sizes_(sizes.begin(), sizes.end()) {
    if (sizes_.size() != m_.num_vertices())
      throw InputError(std::to_string(sizes_.size()) + " sizes for a mesh of " + std::to_string(m_.num_vertices()) +
                       " vertices");
    for (std::size_t i = 0; i < sizes_.size(); ++i)
      if (!(sizes_[i] > 0) || !std::isfinite(sizes_[i]))
        throw InputError("the size of vertex " + std::to_string(i) + " is not a positive number", i);
    if (!m_.compacted()) m_.compact();
    build_grid();
  }

  double operator()(double x, double y) const {
    const Point p{x, y};
    // The walk starts beside the nearest vertex (a grid look-up), so it is
    // a few steps whatever the order of the queries.
    const VertexId v = nearest(p);
    if (v == kNone) return -1.0;
    if (m_.num_triangles() == 0) return sizes_[v];
    // A walk may stop at a hole between its start and p: start from each
    // triangle around v in turn. Outside the mesh (or behind a hole from all
    // of them): the nearest vertex's size.
    Location loc;
    m_.for_each_out_edge(v, [&](HalfEdgeId e) {
      loc = m_.locate(p, tri_of(e));
      return loc.kind == Location::Kind::Outside || loc.tri == kNone;
    });
    if (loc.kind == Location::Kind::Outside || loc.tri == kNone) return sizes_[v];
    const auto t = m_.triangle(loc.tri);
    const Point &a = m_.point(t[0]), &b = m_.point(t[1]), &c = m_.point(t[2]);
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / area;
    double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / area;
    wa = std::clamp(wa, 0.0, 1.0);
    wb = std::clamp(wb, 0.0, 1.0 - wa);
    const double wc = 1.0 - wa - wb;
    return wa * sizes_[t[0]] + wb * sizes_[t[1]] + wc * sizes_[t[2]];
  }

 private:
  void build_grid() {
    std::vector<VertexId> used;
    for (VertexId v = 0; v < m_.num_vertices(); ++v)
      if (m_.out_edge(v) != kNone) used.push_back(v);
    if (used.empty()) return;
    lo_ = hi_ = m_.point(used[0]);
    for (VertexId v : used) {
      const Point& q = m_.point(v);
      lo_ = {std::min(lo_.x, q.x), std::min(lo_.y, q.y)};
      hi_ = {std::max(hi_.x, q.x), std::max(hi_.y, q.y)};
    }
    const double w = hi_.x - lo_.x, h = hi_.y - lo_.y;
    cell_ = std::sqrt(std::max(w * h, std::max(w, h) * std::max(w, h) * 1e-6) / double(used.size()));
    if (!(cell_ > 0)) cell_ = 1.0;
    nx_ = std::min<std::size_t>(4096, static_cast<std::size_t>(w / cell_) + 1);
    ny_ = std::min<std::size_t>(4096, static_cast<std::size_t>(h / cell_) + 1);
    cell_ = std::max({cell_, w / double(nx_), h / double(ny_)});
    start_.assign(nx_ * ny_ + 1, 0);
    for (VertexId v : used) ++start_[cell_of(m_.point(v)) + 1];
    for (std::size_t i = 0; i < nx_ * ny_; ++i) start_[i + 1] += start_[i];
    items_.resize(used.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (VertexId v : used) items_[fill[cell_of(m_.point(v))]++] = v;
  }
  std::size_t ix(double x) const {
    const double f = std::floor((x - lo_.x) / cell_);
    return f <= 0 ? 0 : std::min(nx_ - 1, static_cast<std::size_t>(std::min(f, 1e9)));
  }
  std::size_t iy(double y) const {
    const double f = std::floor((y - lo_.y) / cell_);
    return f <= 0 ? 0 : std::min(ny_ - 1, static_cast<std::size_t>(std::min(f, 1e9)));
  }
  std::size_t cell_of(const Point& p) const { return iy(p.y) * nx_ + ix(p.x); }

  VertexId nearest(const Point& p) const {
    if (items_.empty()) return kNone;
    const long cx = static_cast<long>(ix(p.x)), cy = static_cast<long>(iy(p.y));
    VertexId best = kNone;
    double best_d2 = INFINITY;
    const long rmax = static_cast<long>(std::max(nx_, ny_));
    for (long r = 0; r <= rmax; ++r) {
      // Every vertex in ring r is at least (r - 1) cells away.
      if (best != kNone && r >= 1 && (double(r - 1) * cell_) * (double(r - 1) * cell_) > best_d2) break;
      for (long j = cy - r; j <= cy + r; ++j) {
        if (j < 0 || j >= static_cast<long>(ny_)) continue;
        const bool edge_row = j == cy - r || j == cy + r;
        for (long i = cx - r; i <= cx + r; i += (edge_row ? 1 : 2 * r)) {
          if (i >= 0 && i < static_cast<long>(nx_)) {
            const std::size_t c = static_cast<std::size_t>(j) * nx_ + static_cast<std::size_t>(i);
            for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
              const Point& q = m_.point(items_[k]);
              const double d2 = (q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y);
              if (d2 < best_d2) {
                best_d2 = d2;
                best = items_[k];
              }
            }
          }
          if (r == 0) break;
        }
      }
    }
    return best;
  }

  Mesh m_;
  std::vector<double> sizes_;
  Point lo_{0, 0}, hi_{0, 0};
  double cell_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;
  std::vector<VertexId> items_;
};

}  // namespace

SizeField size_field_from_vertices(const Mesh& background, std::span<const double> sizes) {
  auto field = std::make_shared<BackgroundField>(background, sizes);
  return [field](double x, double y) { return (*field)(x, y); };
}

std::string CoarsenStats::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu -> %zu vertices (%zu removed, %zu of them on segments; %zu kept: star not emptied), %zu flips, %.3f s",
                vertices_before, vertices_after, removed, removed_on_segments, refused, flips, seconds);
  return buf;
}

std::string SmoothStats::summary() const {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%zu moves in %zu passes (%zu refused), %zu flips; smallest angle %.2f -> %.2f deg, mean smallest "
                "angle %.2f -> %.2f deg, %.3f s",
                moved, passes, rejected, flips, min_angle_before, min_angle_after, mean_min_angle_before,
                mean_min_angle_after, seconds);
  return buf;
}

SmoothStats smooth(Mesh& mesh, const SmoothOptions& options) {
  const auto t0 = Clock::now();
  SmoothStats st;
  if (!mesh.compacted()) mesh.compact();
  angle_stats(mesh, st.min_angle_before, st.mean_min_angle_before);
  Smoother(mesh, options, st).run();
  angle_stats(mesh, st.min_angle_after, st.mean_min_angle_after);
  st.seconds = seconds_since(t0);
  return st;
}

std::string AdaptStats::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu vertices removed, %zu inserted, %zu triangles%s, %.3f s", removed, inserted,
                triangles, complete ? "" : " (incomplete: see the refinement report)", seconds);
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

SmoothStats smooth_refined(Mesh& mesh, const SmoothOptions& options, const RefineOptions& refine_options,
                           RefineStats& refined, std::size_t* resplit) {
  const SmoothStats s = smooth(mesh, options);
  if (resplit) *resplit = 0;
  if (!refined.complete) return s;  // a budget stopped it: nothing is owed
  // The budgets are the whole run's (the second refinement could otherwise
  // add max_steiner points again, and take the time limit again).
  RefineOptions r = refine_options;
  if (r.max_steiner != kUnlimited && r.max_steiner != kAutomaticBudget)
    r.max_steiner -= std::min(r.max_steiner, refined.steiner_points);
  if (r.time_limit_seconds > 0)
    r.time_limit_seconds = std::max(1e-9, r.time_limit_seconds - refined.seconds);  // (<= 0 is none)
  const RefineStats again = refine(mesh, r);
  if (resplit) *resplit = again.steiner_points;
  refined.steiner_points += again.steiner_points;
  refined.segment_splits += again.segment_splits;
  refined.interior_points += again.interior_points;
  refined.offcenters += again.offcenters;
  refined.complete = again.complete;
  refined.budget_exhausted = again.budget_exhausted;
  refined.time_exhausted = again.time_exhausted;
  // What is left below the bound is the final mesh's, as the second
  // refinement classified it.
  refined.below_bound = again.below_bound;
  refined.below_small_input_angle = again.below_small_input_angle;
  refined.below_segment_protected = again.below_segment_protected;
  refined.below_budget = again.below_budget;
  refined.below_precision = again.below_precision;
  refined.too_large = again.too_large;
  refined.too_large_precision = again.too_large_precision;
  refined.seconds += again.seconds;
  return s;
}

AdaptStats adapt(Mesh& mesh, const SizeField& h, const AdaptOptions& options) {
  const auto t0 = Clock::now();
  AdaptStats st;
  st.coarsen = coarsen(mesh, h, options.coarsen);
  RefineOptions r = options.refine;
  if (h) {
    const SizeField user = r.max_edge_at;
    r.max_edge_at = [h, user](double x, double y) {
      double v = h(x, y);
      if (!(v > 0) || !std::isfinite(v)) v = -1.0;
      if (user) {
        const double u = user(x, y);
        if (u > 0 && (v <= 0 || u < v)) v = u;
      }
      return v;
    };
  }
  st.refine = refine(mesh, r);
  // A moved vertex may encroach a segment: no smoothing of conforming meshes.
  if (options.smooth_passes > 0 && mesh.num_triangles() > 0 && !options.refine.conforming_delaunay) {
    SmoothOptions so;
    so.passes = options.smooth_passes;
    so.h = h;
    so.max_area = options.refine.max_area;
    so.protect_first = options.coarsen.protect_first;
    st.smooth = smooth_refined(mesh, so, r, st.refine, &st.resplit);
  }
  st.removed = st.coarsen.removed;
  st.inserted = st.refine.steiner_points;
  st.triangles = mesh.num_triangles();
  st.complete = st.refine.complete;
  st.seconds = seconds_since(t0);
  return st;
}

}  // namespace deltamesh

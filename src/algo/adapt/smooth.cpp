// Smoothing: free vertices moved towards the centroid of their neighbours
// (Laplacian) or the area-weighted mean of their triangles' circumcentres
// (L. Chen, J. Xu, "Optimal Delaunay triangulations", J. Comput. Math. 2004),
// a move taken only when its star stays valid and its smallest angle and
// size guards do not get worse; then constrained Lawson flips.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "algo/adapt/common.hpp"
#include "algo/cdt_builder.hpp"
#include "core/angles.hpp"
#include "deltamesh/adapt.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/editor.hpp"

namespace deltamesh {

namespace {

using adaptation::Clock;
using adaptation::dist;
using adaptation::kMaxDegree;
using adaptation::seconds_since;

// Smallest and mean smallest angle over the live real triangles.
void angle_stats(const Mesh& m, double& lo, double& mean) {
  lo = 180.0;
  double sum = 0;
  std::size_t n = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const double a = min_angle_deg(m.point(v[0]), m.point(v[1]), m.point(v[2]));
    lo = std::min(lo, a);
    sum += a;
    ++n;
  }
  mean = n ? sum / double(n) : 0.0;
  if (!n) lo = 0.0;
}

// One smoothing: passes over the free vertices, each followed by flips.
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
      out.angle = std::min(out.angle, min_angle_deg(q, a, b));
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
      detail::MeshEditor(m_).points()[v] = q;
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

}  // namespace

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

}  // namespace deltamesh

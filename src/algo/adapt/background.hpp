// A copy of a background mesh that finds, for any point, the vertices and
// barycentric weights to interpolate vertex data with: the triangle
// containing it (a walk from the nearest vertex, found by a bucket grid), or
// outside the mesh (or behind a hole from every start) the nearest vertex
// alone. Immutable after construction: safe to share between threads.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh::adaptation {

struct Weights {
  std::array<VertexId, 3> v{kNone, kNone, kNone};
  std::array<double, 3> w{0, 0, 0};
  int n = 0;  // 0: empty mesh; 1: nearest vertex; 3: a triangle
};

class BackgroundMesh {
 public:
  explicit BackgroundMesh(const Mesh& bg) : m_(bg) {
    if (!m_.compacted()) m_.compact();
    build_grid();
  }
  const Mesh& mesh() const { return m_; }

  Weights weights(const Point& p) const {
    Weights r;
    // The walk starts beside the nearest vertex (a grid look-up), so it is
    // a few steps whatever the order of the queries.
    const VertexId v = nearest(p);
    if (v == kNone) return r;
    r.n = 1;
    r.v[0] = v;
    r.w[0] = 1;
    if (m_.num_triangles() == 0) return r;
    // A walk may stop at a hole between its start and p: start from each
    // triangle around v in turn.
    Location loc;
    m_.for_each_out_edge(v, [&](HalfEdgeId e) {
      loc = m_.locate(p, tri_of(e));
      return loc.kind == Location::Kind::Outside || loc.tri == kNone;
    });
    if (loc.kind == Location::Kind::Outside || loc.tri == kNone) return r;
    const auto t = m_.triangle(loc.tri);
    const Point &a = m_.point(t[0]), &b = m_.point(t[1]), &c = m_.point(t[2]);
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / area;
    double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / area;
    wa = std::clamp(wa, 0.0, 1.0);
    wb = std::clamp(wb, 0.0, 1.0 - wa);
    r.n = 3;
    r.v = {t[0], t[1], t[2]};
    r.w = {wa, wb, 1.0 - wa - wb};
    return r;
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
  Point lo_{0, 0}, hi_{0, 0};
  double cell_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;
  std::vector<VertexId> items_;
};

}  // namespace deltamesh::adaptation

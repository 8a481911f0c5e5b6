// Shared pieces of the exchange-format writers (msh, vtk, geojson, off):
// a buffered number writer over an AtomicFile, the output numbering of
// triangles, per-triangle quantities and the boundary/segment edge list.
#pragma once
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "io/atomic_file.hpp"

namespace deltamesh::io {

// Buffered writer into an AtomicFile: numbers go straight into the buffer
// with std::to_chars (shortest round-trip form for doubles); the buffer is
// flushed whenever it passes kChunk.
class OutBuffer {
 public:
  explicit OutBuffer(AtomicFile& file) : file_(file), buf_(kChunk + kSlack) {}

  void put(char c) {
    room();
    buf_[n_++] = c;
  }
  void put(std::string_view s) {
    if (n_ + s.size() > buf_.size()) {
      flush();
      if (s.size() > buf_.size()) {
        file_.write(s);
        return;
      }
    }
    s.copy(buf_.data() + n_, s.size());
    n_ += s.size();
  }
  void put_int(long long v) {
    room();
    n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  void put_uint(unsigned long long v) {
    room();
    n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  void put_double(double v) {
    room();
    n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  // A double that JSON/VTK readers accept: finite values as put_double,
  // with "-0" written as "0".
  void put_number(double v) { put_double(v == 0.0 ? 0.0 : v); }
  void field_int(long long v) {
    put(' ');
    put_int(v);
  }
  void field_double(double v) {
    put(' ');
    put_double(v);
  }
  // Flushes and renames the file onto its target.
  void commit() {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;
  static constexpr std::size_t kSlack = 256;  // > any single numeric put
  void room() {
    if (n_ >= kChunk) flush();
  }
  void flush() {
    file_.write(std::string_view(buf_.data(), n_));
    n_ = 0;
  }
  AtomicFile& file_;
  std::vector<char> buf_;
  std::size_t n_ = 0;
};

// Output numbering of live real triangles (dead and ghost slots skipped).
struct TriangleOrder {
  std::vector<TriId> slots;  // output index -> triangle slot
  std::size_t size() const { return slots.size(); }
};

inline TriangleOrder live_triangles(const Mesh& m) {
  TriangleOrder order;
  order.slots.reserve(m.num_triangles());
  const std::size_t n = m.num_triangle_slots();
  for (TriId t = 0; t < n; ++t)
    if (m.is_real(t)) order.slots.push_back(t);
  return order;
}

// The twin of e if it lies in a live real triangle, else kNone (a boundary).
inline HalfEdgeId real_twin(const Mesh& m, HalfEdgeId e) {
  const HalfEdgeId f = m.twin(e);
  return f == kNone || !m.is_real(tri_of(f)) ? kNone : f;
}

// Triangle attribute 0 rounded, 0 without attributes.
inline long long triangle_region(const Mesh& m, TriId t) {
  if (m.num_triangle_attributes() == 0) return 0;
  const std::size_t i = std::size_t{t} * m.num_triangle_attributes();
  const std::vector<double>& a = m.triangle_attributes();
  if (i >= a.size() || !std::isfinite(a[i])) return 0;
  return std::llround(std::clamp(a[i], -9.0e15, 9.0e15));
}

constexpr double kPi = 3.14159265358979323846;

// Smallest interior angle in degrees (the one opposite the shortest edge,
// computed with atan2 for accuracy near 0). 0 for a degenerate triangle.
inline double smallest_angle_deg(const Point& a, const Point& b, const Point& c) {
  const double ab = std::hypot(b.x - a.x, b.y - a.y);
  const double bc = std::hypot(c.x - b.x, c.y - b.y);
  const double ca = std::hypot(a.x - c.x, a.y - c.y);
  const Point *apex, *p, *q;
  if (ab <= bc && ab <= ca) {
    apex = &c, p = &a, q = &b;
  } else if (bc <= ca) {
    apex = &a, p = &b, q = &c;
  } else {
    apex = &b, p = &c, q = &a;
  }
  const double ux = p->x - apex->x, uy = p->y - apex->y;
  const double vx = q->x - apex->x, vy = q->y - apex->y;
  const double cross = std::fabs(ux * vy - uy * vx);
  const double dot = ux * vx + uy * vy;
  if (cross == 0.0 && dot == 0.0) return 0.0;
  return std::atan2(cross, dot) * 180.0 / kPi;
}

inline double triangle_area(const Point& a, const Point& b, const Point& c) {
  return 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// A boundary or segment edge, written as a line element.
struct LineEdge {
  HalfEdgeId e;  // the half-edge in a live real triangle (origin -> dest)
  int marker;
};

// Every edge that is on the mesh boundary or constrained, once, with its
// output marker: the segment's marker when nonzero, otherwise 1 on the mesh
// boundary and 0 inside (Triangle's rule, as write_edge applies it).
inline std::vector<LineEdge> boundary_and_segment_edges(const Mesh& m) {
  std::vector<LineEdge> out;
  const std::size_t n = m.num_triangle_slots();
  for (TriId t = 0; t < n; ++t) {
    if (!m.is_real(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const HalfEdgeId tw = real_twin(m, e);
      if (tw != kNone && tw < e) continue;
      const bool segment = m.is_constrained(e) || (tw != kNone && m.is_constrained(tw));
      if (tw != kNone && !segment) continue;
      int marker = m.edge_marker(e);
      if (marker == 0 && tw != kNone) marker = m.edge_marker(tw);
      out.push_back({e, marker != 0 ? marker : (tw == kNone ? 1 : 0)});
    }
  }
  return out;
}

// Per vertex: its marker from the input when the mesh has markers, otherwise
// 1 on the boundary and 0 elsewhere (what write_node does).
inline std::vector<int> vertex_output_markers(const Mesh& m) {
  const std::size_t nv = m.num_vertices();
  const std::vector<int>& given = m.vertex_markers();
  if (given.size() >= nv) return std::vector<int>(given.begin(), given.begin() + static_cast<std::ptrdiff_t>(nv));
  std::vector<int> on(nv, 0);
  const std::size_t n = m.num_triangle_slots();
  for (TriId t = 0; t < n; ++t) {
    if (!m.is_real(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e)
      if (real_twin(m, e) == kNone) on[m.origin(e)] = on[m.dest(e)] = 1;
  }
  return on;
}

}  // namespace deltamesh::io

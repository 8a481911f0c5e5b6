// Shared pieces of the writers (Triangle's files and the exchange formats
// msh, vtk, geojson, off): a buffered number writer over an AtomicFile, the output numbering of
// triangles, per-triangle quantities and the boundary/segment edge list.
#pragma once
#include <algorithm>
#include <charconv>

#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/angles.hpp"
#include "core/float_chars.hpp"
#include "deltamesh/mesh.hpp"
#include "io/atomic_file.hpp"
#include "mesh/edge_rules.hpp"

namespace deltamesh::io {

// Decimal digits of v at p, as std::to_chars writes them; returns the end.
// Two digits per step from a table: the writers' lines are mostly integers.
inline char* write_decimal(char* p, long long v) {
  static constexpr char kPairs[] =
      "0001020304050607080910111213141516171819202122232425262728293031323334353637383940414243444546474849"
      "5051525354555657585960616263646566676869707172737475767778798081828384858687888990919293949596979899";
  unsigned long long u = static_cast<unsigned long long>(v);
  if (v < 0) {
    *p++ = '-';
    u = 0 - u;
  }
  char tmp[20];  // backwards: 2^64 has 20 digits
  char* q = tmp + sizeof tmp;
  while (u >= 100) {
    const auto i = static_cast<std::size_t>(u % 100) * 2;
    u /= 100;
    *--q = kPairs[i + 1];
    *--q = kPairs[i];
  }
  if (u >= 10) {
    const auto i = static_cast<std::size_t>(u) * 2;
    *--q = kPairs[i + 1];
    *--q = kPairs[i];
  } else {
    *--q = static_cast<char>('0' + u);
  }
  while (q != tmp + sizeof tmp) *p++ = *q++;
  return p;
}

// Buffered writer into an AtomicFile: numbers go straight into the buffer
// (integers by write_decimal, doubles in the shortest round-trip form); the
// buffer is flushed whenever it passes kChunk.
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
    raw_int(v);
  }
  void put_uint(unsigned long long v) {
    room();
    n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  void put_double(double v) {
    room();
    n_ = static_cast<std::size_t>(chars::shortest(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
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
  // The unchecked forms, for a line of a few fields after one line_room()
  // (kSlack holds any such line), so that each field skips the check.
  void line_room() { room(); }
  void raw(char c) { buf_[n_++] = c; }
  void raw_field_int(long long v) {
    buf_[n_++] = ' ';
    raw_int(v);
  }
  void raw_int(long long v) { n_ = static_cast<std::size_t>(write_decimal(buf_.data() + n_, v) - buf_.data()); }
  void raw_field_double(double v) {
    buf_[n_++] = ' ';
    n_ = static_cast<std::size_t>(chars::shortest(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  // Flushes and renames the file onto its target.
  void commit() {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;
  static constexpr std::size_t kSlack = 256;  // > any single numeric put, or a raw line of a few fields
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

using ::deltamesh::real_twin;
using ::deltamesh::smallest_angle_deg;

// Triangle attribute 0 rounded, 0 without attributes.
inline long long triangle_region(const Mesh& m, TriId t) {
  if (m.num_triangle_attributes() == 0) return 0;
  const std::size_t i = std::size_t{t} * m.num_triangle_attributes();
  const std::vector<double>& a = m.triangle_attributes();
  if (i >= a.size() || !std::isfinite(a[i])) return 0;
  return std::llround(std::clamp(a[i], -9.0e15, 9.0e15));
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
  for_each_edge(m, [&](HalfEdgeId e, bool boundary) {
    if (!boundary && !is_segment_edge(m, e)) return;
    out.push_back({e, edge_output_marker(m, e, boundary ? kNone : m.twin(e))});
  });
  return out;
}

// Per vertex the marker write_node writes (vertex_output_marker).
inline std::vector<int> vertex_output_markers(const Mesh& m) {
  const std::size_t nv = m.num_vertices();
  std::vector<std::uint8_t> on_boundary;
  if (m.vertex_markers().size() < nv) on_boundary = boundary_vertices(m);
  std::vector<int> out(nv);
  for (VertexId v = 0; v < nv; ++v) out[v] = vertex_output_marker(m, v, on_boundary);
  return out;
}

}  // namespace deltamesh::io

// VTK writers: XML UnstructuredGrid (.vtu; ASCII or base64 binary) and the
// legacy ASCII format (.vtk, file version 3.0), after the "VTK File Formats"
// document. Cells are the live real triangles (VTK_TRIANGLE = 5, or
// VTK_QUADRATIC_TRIANGLE = 22 with midside nodes), points are all vertices.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "deltamesh/formats.hpp"
#include "deltamesh/version.hpp"
#include "io/export_util.hpp"

namespace deltamesh {

namespace {

using io::OutBuffer;

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkQuadraticTriangle = 22;

// Everything the two writers share, computed once.
struct VtkData {
  std::vector<double> points;           // 3 per vertex
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets;    // end of each cell in connectivity
  std::uint8_t cell_type = kVtkTriangle;
  std::vector<std::int32_t> region;
  std::vector<double> min_angle;
  std::vector<double> area;
  std::vector<std::vector<double>> cell_attributes;   // per attribute, per cell
  std::vector<std::int32_t> marker;
  std::vector<std::vector<double>> point_attributes;  // per attribute, per vertex
};

VtkData gather(const Mesh& mesh, const SecondOrderNodes& second_order) {
  VtkData d;
  const io::TriangleOrder order = io::live_triangles(mesh);
  const std::size_t nt = order.size();
  const std::size_t nv = mesh.num_vertices();
  const std::span<const VertexId> mid = second_order.midside;
  const bool quadratic = !mid.empty();
  if (quadratic && mid.size() != 3 * nt)
    throw Error("VTK writer: " + std::to_string(mid.size()) + " midside nodes given for " + std::to_string(nt) +
                " triangles (3 per triangle expected)");
  for (const VertexId v : mid)
    if (v >= nv) throw Error("VTK writer: midside node " + std::to_string(v) + " is not a vertex");
  d.cell_type = quadratic ? kVtkQuadraticTriangle : kVtkTriangle;

  d.points.reserve(3 * nv);
  for (const Point& p : mesh.points()) {
    d.points.push_back(p.x);
    d.points.push_back(p.y);
    d.points.push_back(0.0);
  }
  const std::size_t per = quadratic ? 6 : 3;
  d.connectivity.reserve(per * nt);
  d.offsets.reserve(nt);
  d.region.reserve(nt);
  d.min_angle.reserve(nt);
  d.area.reserve(nt);
  const std::size_t nta = mesh.num_triangle_attributes();
  d.cell_attributes.assign(nta, {});
  const std::vector<double>& tattr = mesh.triangle_attributes();
  for (std::size_t k = 0; k < nt; ++k) {
    const TriId t = order.slots[k];
    const auto tri = mesh.triangle(t);
    for (const VertexId v : tri) d.connectivity.push_back(v);
    if (quadratic) {
      // VTK wants the midpoints of edges 01, 12, 20; Triangle's order lists
      // them opposite corners 2, 0, 1.
      d.connectivity.push_back(mid[3 * k + 2]);
      d.connectivity.push_back(mid[3 * k + 0]);
      d.connectivity.push_back(mid[3 * k + 1]);
    }
    d.offsets.push_back(static_cast<std::int64_t>(d.connectivity.size()));
    const Point &a = mesh.point(tri[0]), &b = mesh.point(tri[1]), &c = mesh.point(tri[2]);
    d.region.push_back(static_cast<std::int32_t>(
        std::clamp<long long>(io::triangle_region(mesh, t), INT32_MIN, INT32_MAX)));
    d.min_angle.push_back(io::smallest_angle_deg(a, b, c));
    d.area.push_back(io::triangle_area(a, b, c));
    for (std::size_t j = 0; j < nta; ++j) {
      const std::size_t i = std::size_t{t} * nta + j;
      d.cell_attributes[j].push_back(i < tattr.size() ? tattr[i] : 0.0);
    }
  }
  for (const int m : io::vertex_output_markers(mesh)) d.marker.push_back(m);
  const std::size_t nva = mesh.num_vertex_attributes();
  const std::vector<double>& vattr = mesh.vertex_attributes();
  d.point_attributes.assign(nva, {});
  for (std::size_t j = 0; j < nva; ++j) {
    d.point_attributes[j].reserve(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      const std::size_t i = v * nva + j;
      d.point_attributes[j].push_back(i < vattr.size() ? vattr[i] : 0.0);
    }
  }
  return d;
}

void put_value(OutBuffer& out, double v) { out.put_number(v); }
void put_value(OutBuffer& out, std::int64_t v) { out.put_int(v); }
void put_value(OutBuffer& out, std::int32_t v) { out.put_int(v); }
void put_value(OutBuffer& out, std::uint8_t v) { out.put_int(v); }

template <class T>
void put_ascii_values(OutBuffer& out, const std::vector<T>& values, std::size_t per_line) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    put_value(out, values[i]);
    out.put((i + 1) % per_line == 0 || i + 1 == values.size() ? '\n' : ' ');
  }
}

// Base64 (RFC 4648) of a byte stream, fed in pieces; output goes to the
// OutBuffer in blocks.
class Base64 {
 public:
  explicit Base64(OutBuffer& out) : out_(out) {}
  ~Base64() { flush(); }
  void feed(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    if (have_ != 0) {  // complete a pending triple
      while (have_ < 3 && i < n) carry_[have_++] = p[i++];
      if (have_ < 3) return;
      encode(carry_);
      have_ = 0;
    }
    for (; i + 3 <= n; i += 3) encode(p + i);
    for (; i < n && have_ < 3; ++i) carry_[have_++] = p[i];
  }
  // Pads and emits what is pending (ends one base64 block).
  void finish() {
    if (have_ != 0) {
      const std::size_t had = have_;
      for (std::size_t i = have_; i < 3; ++i) carry_[i] = 0;
      encode(carry_);
      for (std::size_t i = had + 1; i < 4; ++i) buf_[n_ - 4 + i] = '=';
      have_ = 0;
    }
    flush();
  }

 private:
  void encode(const unsigned char* t) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned v = (unsigned{t[0]} << 16) | (unsigned{t[1]} << 8) | unsigned{t[2]};
    buf_[n_] = kAlphabet[(v >> 18) & 63];
    buf_[n_ + 1] = kAlphabet[(v >> 12) & 63];
    buf_[n_ + 2] = kAlphabet[(v >> 6) & 63];
    buf_[n_ + 3] = kAlphabet[v & 63];
    n_ += 4;
    if (n_ == sizeof buf_) flush();
  }
  void flush() {
    out_.put(std::string_view(buf_, n_));
    n_ = 0;
  }
  OutBuffer& out_;
  unsigned char carry_[3] = {0, 0, 0};
  std::size_t have_ = 0;
  char buf_[4096];
  std::size_t n_ = 0;
};

bool little_endian() {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

template <class T>
void vtu_array(OutBuffer& out, const char* type, const std::string& name, int components, const std::vector<T>& values,
               bool binary, std::size_t per_line) {
  out.put("<DataArray type=\"");
  out.put(type);
  out.put('"');
  if (!name.empty()) {
    out.put(" Name=\"");
    out.put(name);
    out.put('"');
  }
  if (components != 1) {
    out.put(" NumberOfComponents=\"");
    out.put_int(components);
    out.put('"');
  }
  out.put(binary ? " format=\"binary\">\n" : " format=\"ascii\">\n");
  if (binary) {
    // A UInt64 byte count, then the raw values, each base64-encoded on its
    // own (the header's padding ends its block), which VTK and meshio read.
    Base64 b64(out);
    const std::uint64_t bytes = values.size() * sizeof(T);
    b64.feed(&bytes, sizeof bytes);
    b64.finish();
    if (!values.empty()) b64.feed(values.data(), bytes);
    b64.finish();
    out.put('\n');
  } else {
    put_ascii_values(out, values, per_line);
  }
  out.put("</DataArray>\n");
}

void vtk_scalars(OutBuffer& out, const char* name, const char* type, const auto& values) {
  out.put("SCALARS ");
  out.put(name);
  out.put(' ');
  out.put(type);
  out.put(" 1\nLOOKUP_TABLE default\n");
  put_ascii_values(out, values, 10);
}

}  // namespace

void write_vtu(const Mesh& mesh, const std::string& path, const VtkOptions& options) {
  const VtkData d = gather(mesh, options.second_order);
  const bool binary = options.binary;
  const std::size_t nv = mesh.num_vertices();
  const std::size_t nt = d.offsets.size();
  const std::vector<std::uint8_t> types(nt, d.cell_type);

  io::AtomicFile file(path);
  OutBuffer out(file);
  out.put("<?xml version=\"1.0\"?>\n");
  out.put("<!-- generated by deltamesh ");
  out.put(kVersion);
  out.put(" -->\n");
  out.put("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"");
  out.put(little_endian() ? "LittleEndian" : "BigEndian");
  out.put("\" header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"");
  out.put_uint(nv);
  out.put("\" NumberOfCells=\"");
  out.put_uint(nt);
  out.put("\">\n");

  out.put("<PointData Scalars=\"marker\">\n");
  vtu_array(out, "Int32", "marker", 1, d.marker, binary, 20);
  for (std::size_t j = 0; j < d.point_attributes.size(); ++j)
    vtu_array(out, "Float64", "attribute_" + std::to_string(j), 1, d.point_attributes[j], binary, 6);
  out.put("</PointData>\n");

  out.put("<CellData Scalars=\"region\">\n");
  vtu_array(out, "Int32", "region", 1, d.region, binary, 20);
  vtu_array(out, "Float64", "min_angle", 1, d.min_angle, binary, 6);
  vtu_array(out, "Float64", "area", 1, d.area, binary, 6);
  for (std::size_t j = 0; j < d.cell_attributes.size(); ++j)
    vtu_array(out, "Float64", "attribute_" + std::to_string(j), 1, d.cell_attributes[j], binary, 6);
  out.put("</CellData>\n");

  out.put("<Points>\n");
  vtu_array(out, "Float64", "", 3, d.points, binary, 3);
  out.put("</Points>\n<Cells>\n");
  vtu_array(out, "Int64", "connectivity", 1, d.connectivity, binary, d.cell_type == kVtkTriangle ? 3 : 6);
  vtu_array(out, "Int64", "offsets", 1, d.offsets, binary, 10);
  vtu_array(out, "UInt8", "types", 1, types, binary, 20);
  out.put("</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  out.commit();
}

void write_vtk(const Mesh& mesh, const std::string& path, const VtkOptions& options) {
  const VtkData d = gather(mesh, options.second_order);
  const std::size_t nv = mesh.num_vertices();
  const std::size_t nt = d.offsets.size();
  const std::size_t per = d.cell_type == kVtkTriangle ? 3 : 6;

  io::AtomicFile file(path);
  OutBuffer out(file);
  out.put("# vtk DataFile Version 3.0\ndeltamesh ");
  out.put(kVersion);
  out.put(" mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ");
  out.put_uint(nv);
  out.put(" double\n");
  put_ascii_values(out, d.points, 3);
  out.put("CELLS ");
  out.put_uint(nt);
  out.put(' ');
  out.put_uint(nt * (per + 1));
  out.put('\n');
  for (std::size_t k = 0; k < nt; ++k) {
    out.put_uint(per);
    for (std::size_t i = 0; i < per; ++i) out.field_int(d.connectivity[k * per + i]);
    out.put('\n');
  }
  out.put("CELL_TYPES ");
  out.put_uint(nt);
  out.put('\n');
  for (std::size_t k = 0; k < nt; ++k) {
    out.put_int(d.cell_type);
    out.put('\n');
  }
  if (nt > 0) {
    out.put("CELL_DATA ");
    out.put_uint(nt);
    out.put('\n');
    vtk_scalars(out, "region", "int", d.region);
    vtk_scalars(out, "min_angle", "double", d.min_angle);
    vtk_scalars(out, "area", "double", d.area);
    for (std::size_t j = 0; j < d.cell_attributes.size(); ++j)
      vtk_scalars(out, ("attribute_" + std::to_string(j)).c_str(), "double", d.cell_attributes[j]);
  }
  if (nv > 0) {
    out.put("POINT_DATA ");
    out.put_uint(nv);
    out.put('\n');
    vtk_scalars(out, "marker", "int", d.marker);
    for (std::size_t j = 0; j < d.point_attributes.size(); ++j)
      vtk_scalars(out, ("attribute_" + std::to_string(j)).c_str(), "double", d.point_attributes[j]);
  }
  out.commit();
}

}  // namespace deltamesh

// Triangle's file formats, read (the writers are in triangle_write.cpp).
//
// Readers follow the format descriptions in Triangle's documentation: every
// section starts with a count line, entries are numbered consecutively from
// 0 or 1 (the first entry decides), `#` starts a comment. Missing trailing
// header fields take Triangle's defaults (dimension 2, no attributes, no
// markers); extra trailing fields on an entry line are ignored, as Triangle
// does. Everything else that is wrong is a ParseError naming the line.
#include "deltamesh/triangle_io.hpp"

#include <array>
#include <charconv>

#include <climits>
#include <cmath>
#include <string_view>
#include <utility>
#include <vector>

#include "core/float_chars.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/version.hpp"
#include "core/parallel.hpp"
#include "io/atomic_file.hpp"
#include "io/text_reader.hpp"
#include "mesh/edge_rules.hpp"

namespace deltamesh {

namespace {

using io::plural;
using io::TextReader;

std::string str(long long v) { return std::to_string(v); }

// ---------------------------------------------------------------------------
// Reading helpers

// A non-negative count in token i of the current (header) line.
long long read_count(const TextReader& r, std::size_t i, const char* what) {
  const long long n = r.integer(i, [&] { return std::string(what); });
  if (n < 0) r.fail(std::string(what) + " " + str(n) + " is negative");
  return n;
}

// Optional header field i (default when absent).
long long read_optional_count(const TextReader& r, std::size_t i, const char* what, long long dflt) {
  return i < r.size() ? read_count(r, i, what) : dflt;
}

// 0 or 1 boundary markers per entry.
bool read_marker_flag(const TextReader& r, std::size_t i) {
  const long long m = read_optional_count(r, i, "boundary marker count", 0);
  if (m > 1) r.fail("boundary marker count " + str(m) + " must be 0 or 1");
  return m == 1;
}

// Called on a header line announcing `count` entries of at least `tokens`
// fields each. Rejects counts the rest of the file cannot hold, so an absurd
// header never makes the reader allocate for it. The cheap test (each field
// takes at least one character and one separator) settles almost every file;
// only when it fails are the remaining data lines counted. Afterwards count
// is at most the number of lines left, hence bounded by the file size.
void check_count_fits(const TextReader& r, long long count, std::size_t tokens, const char* nouns) {
  if (count <= 0) return;
  const std::size_t room = (r.bytes_left() + 1) / 2;  // fields the rest could hold
  if (static_cast<unsigned long long>(count) <= room / tokens) return;
  const std::size_t lines = r.count_data_lines_left();
  if (static_cast<unsigned long long>(count) > lines)
    r.fail("header announces " + str(count) + " " + nouns + " but the file has only " +
           plural(static_cast<long long>(lines), "line", "lines") + " left");
}

// A capacity to reserve for count * per values: never more than the rest of
// the file could hold, whatever the header says.
std::size_t safe_capacity(const TextReader& r, std::size_t count, std::size_t per) {
  const std::size_t cap = r.bytes_left() / 2 + 1;
  if (per == 0) return 0;
  return count > cap / per ? cap : count * per;
}

// Moves to entry `index` (0-based) of a section announced on `header_line`.
void next_entry(TextReader& r, long long index, long long count, std::size_t header_line, const char* nouns) {
  if (!r.next_line())
    r.fail_at(header_line, "header announces " + str(count) + " " + nouns + " but the file ends after " +
                               str(index));
}

// Entry ids: consecutive, from 0 or 1 (the section's first id decides).
// Returns the id.
long long check_id(const TextReader& r, long long index, long long& base, const char* noun, const char* nouns) {
  const long long id = r.integer(0, [&] {
    return index == 0 ? "the number of the first " + std::string(noun)
                      : "the number of " + std::string(noun) + " " + str(base + index);
  });
  if (index == 0) {
    if (id != 0 && id != 1)
      r.fail("the first " + std::string(noun) + " is numbered " + str(id) + ", but " + nouns +
             " must be numbered from 0 or 1");
    base = id;
    return id;
  }
  const long long expected = base + index;
  if (id == expected) return id;
  if (id >= base && id < expected)
    r.fail("duplicate " + std::string(noun) + " number " + str(id) + ": " + nouns +
           " must be numbered consecutively, expected " + str(expected));
  r.fail(std::string(noun) + " number " + str(id) + " is out of order: " + nouns +
         " must be numbered consecutively, expected " + str(expected));
}

int read_marker(const TextReader& r, std::size_t i, const char* noun, long long id) {
  const long long m = r.integer(i, [&] { return "the boundary marker of " + std::string(noun) + " " + str(id); });
  if (m < INT_MIN || m > INT_MAX)
    r.fail("boundary marker " + str(m) + " of " + noun + " " + str(id) + " does not fit in an int");
  return static_cast<int>(m);
}

// Reads coordinates x, y from tokens 1 and 2 (the caller checked they exist).
Point read_point(const TextReader& r, const char* noun, long long id) {
  const double x = r.finite_number(1, [&] { return "the x coordinate of " + std::string(noun) + " " + str(id); });
  const double y = r.finite_number(2, [&] { return "the y coordinate of " + std::string(noun) + " " + str(id); });
  return {x, y};
}

void require_coordinates(const TextReader& r, const char* noun, long long id) {
  if (r.size() < 3)
    r.fail("expected 2 coordinates for " + std::string(noun) + " " + str(id) + ", found " +
           str(static_cast<long long>(r.size()) - 1));
}

struct NodeHeader {
  long long count = 0;
  long long attributes = 0;
  bool markers = false;
  std::size_t line = 0;
};

// The `<#vertices> <dimension> <#attributes> <#markers>` line (current line).
NodeHeader parse_node_header(const TextReader& r) {
  NodeHeader h;
  h.line = r.line();
  h.count = read_count(r, 0, "vertex count");
  const long long dim = read_optional_count(r, 1, "dimension", 2);
  if (dim != 2) r.fail("dimension is " + str(dim) + ", but only 2 is supported");
  h.attributes = read_optional_count(r, 2, "attribute count", 0);
  h.markers = read_marker_flag(r, 3);
  return h;
}

// Vertex lists from this long are parsed on several threads.
constexpr long long kParallelParseVertices = 100000;

void read_vertices(TextReader& r, const NodeHeader& h, Pslg& g, unsigned threads) {
  const std::size_t na = static_cast<std::size_t>(h.attributes);
  const std::size_t fields = 3 + na + (h.markers ? 1 : 0);
  // Attribute counts too large for any line are caught here as well.
  if (na > r.bytes_left()) r.fail("attribute count " + str(h.attributes) + " is larger than the file");
  check_count_fits(r, h.count, fields, "vertices");
  if (h.count >= static_cast<long long>(kInfinite)) r.fail("vertex count " + str(h.count) + " is too large");
  const std::size_t n = static_cast<std::size_t>(h.count);
  g.points.reserve(n);
  g.num_point_attributes = na;
  g.point_attributes.reserve(safe_capacity(r, n, na));
  if (h.markers) g.point_markers.reserve(n);
  long long base = 0;
  for (long long i = 0; i < h.count; ++i) {
    if (i == 1 && na == 0 && threads > 1 && h.count >= kParallelParseVertices) {
      if (r.try_point_lines(base + 1, n - 1, h.markers, threads, g.points, g.point_markers)) break;
    }
    if (i > 0 && na == 0) {
      double x, y;
      long long marker = 0;
      if (r.try_point_line(base + i, h.markers, x, y, marker) && marker == static_cast<int>(marker)) {
        g.points.push_back({x, y});
        if (h.markers) g.point_markers.push_back(static_cast<int>(marker));
        continue;
      }
    }
    next_entry(r, i, h.count, h.line, "vertices");
    const long long id = check_id(r, i, base, "vertex", "vertices");
    require_coordinates(r, "vertex", id);
    if (r.size() < 3 + na)
      r.fail("expected " + plural(h.attributes, "attribute", "attributes") + " for vertex " + str(id) +
             ", found " + str(static_cast<long long>(r.size()) - 3));
    if (r.size() < fields)
      r.fail("expected a boundary marker for vertex " + str(id) + " after its " +
             plural(h.attributes, "attribute", "attributes") + ", found none");
    g.points.push_back(read_point(r, "vertex", id));
    for (std::size_t k = 0; k < na; ++k)
      g.point_attributes.push_back(r.finite_number(
          3 + k, [&] { return "attribute " + str(static_cast<long long>(k) + 1) + " of vertex " + str(id); }));
    if (h.markers) g.point_markers.push_back(read_marker(r, 3 + na, "vertex", id));
  }
  g.first_index = static_cast<int>(base);
}

void reject_trailing_data(TextReader& r, const std::string& after) {
  if (!r.has_more_data()) return;
  r.next_line();
  r.fail("unexpected data after " + after);
}

// Vertex reference in token i, re-based to 0 and checked against [0, n).
VertexId read_vertex_ref(const TextReader& r, std::size_t i, const Pslg& g, const char* noun, long long id) {
  const long long v = r.integer(i, [&] { return "an endpoint of " + std::string(noun) + " " + str(id); });
  const long long n = static_cast<long long>(g.points.size());
  const long long first = g.first_index;
  if (v < first || v - first >= n) {
    if (n == 0) r.fail(std::string(noun) + " " + str(id) + " refers to vertex " + str(v) + ", but there are no vertices");
    r.fail(std::string(noun) + " " + str(id) + " refers to vertex " + str(v) + ", but vertices are numbered " +
           str(first) + ".." + str(first + n - 1));
  }
  return static_cast<VertexId>(v - first);
}

std::string sibling_node_path(const std::string& poly_path) {
  const std::size_t slash = poly_path.find_last_of('/');
  const std::size_t dot = poly_path.find_last_of('.');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? poly_path.substr(0, dot) : poly_path) + ".node";
}

double area_bound(double a) { return a > 0.0 ? a : -1.0; }

}  // namespace

// ---------------------------------------------------------------------------
// Readers

Pslg read_node(const std::string& path, unsigned threads) {
  TextReader r = TextReader::open(path);
  if (!r.next_line())
    r.fail_at(r.last_line(), "expected the header line '<#vertices> 2 <#attributes> <#boundary markers>', "
                             "but the file holds no data");
  const NodeHeader h = parse_node_header(r);
  Pslg g;
  read_vertices(r, h, g, detail::resolve_threads(threads));
  reject_trailing_data(r, "the " + plural(h.count, "vertex", "vertices") + " announced on line " +
                              std::to_string(h.line));
  return g;
}

Pslg read_poly(const std::string& path, unsigned threads) {
  TextReader r = TextReader::open(path);
  if (!r.next_line())
    r.fail_at(r.last_line(), "expected the header line '<#vertices> 2 <#attributes> <#boundary markers>', "
                             "but the file holds no data");
  const NodeHeader h = parse_node_header(r);
  Pslg g;
  if (h.count > 0) {
    read_vertices(r, h, g, detail::resolve_threads(threads));
  } else {
    const std::string node = sibling_node_path(path);
    try {
      g = read_node(node, threads);
    } catch (const IoError& e) {
      r.fail_at(h.line, "the .poly file lists no vertices, so they must come from '" + node +
                            "', which cannot be read (" + e.what() + ")");
    }
  }

  // Segments.
  if (!r.next_line())
    r.fail_at(r.last_line(), "the file ends before the segment count line '<#segments> <#boundary markers>'");
  const std::size_t seg_line = r.line();
  const long long ns = read_count(r, 0, "segment count");
  const bool seg_markers = read_marker_flag(r, 1);
  check_count_fits(r, ns, 3 + (seg_markers ? 1 : 0), "segments");
  g.segments.reserve(static_cast<std::size_t>(ns));
  long long base = 0;
  for (long long i = 0; i < ns; ++i) {
    next_entry(r, i, ns, seg_line, "segments");
    const long long id = check_id(r, i, base, "segment", "segments");
    if (r.size() < 3)
      r.fail("expected 2 endpoints for segment " + str(id) + ", found " + str(static_cast<long long>(r.size()) - 1));
    if (seg_markers && r.size() < 4) r.fail("expected a boundary marker for segment " + str(id) + ", found none");
    Segment s;
    s.a = read_vertex_ref(r, 1, g, "segment", id);
    s.b = read_vertex_ref(r, 2, g, "segment", id);
    // A segment with the same vertex at both ends is kept: meshing ignores
    // and counts zero-length segments (with a warning), as real files have them.
    if (seg_markers) s.marker = read_marker(r, 3, "segment", id);
    g.segments.push_back(s);
  }

  // Holes.
  if (!r.next_line()) r.fail_at(r.last_line(), "the file ends before the hole count line '<#holes>'");
  const std::size_t hole_line = r.line();
  const long long nh = read_count(r, 0, "hole count");
  check_count_fits(r, nh, 3, "holes");
  g.holes.reserve(static_cast<std::size_t>(nh));
  base = 0;
  for (long long i = 0; i < nh; ++i) {
    next_entry(r, i, nh, hole_line, "holes");
    const long long id = check_id(r, i, base, "hole", "holes");
    require_coordinates(r, "hole", id);
    g.holes.push_back(read_point(r, "hole", id));
  }

  // Optional regional attributes and area constraints.
  if (r.next_line()) {
    const std::size_t region_line = r.line();
    const long long nr = read_count(r, 0, "region count");
    check_count_fits(r, nr, 4, "regions");
    g.regions.reserve(static_cast<std::size_t>(nr));
    base = 0;
    for (long long i = 0; i < nr; ++i) {
      next_entry(r, i, nr, region_line, "regions");
      const long long id = check_id(r, i, base, "region", "regions");
      require_coordinates(r, "region", id);
      if (r.size() < 4) r.fail("expected a regional attribute for region " + str(id) + ", found none");
      RegionSeed seed;
      seed.p = read_point(r, "region", id);
      seed.attribute = r.finite_number(3, [&] { return "the attribute of region " + str(id); });
      if (r.size() >= 5)
        seed.max_area = area_bound(r.finite_number(4, [&] { return "the maximum area of region " + str(id); }));
      g.regions.push_back(seed);
    }
    reject_trailing_data(r, "the " + plural(nr, "region", "regions") + " announced on line " +
                                std::to_string(region_line));
  }
  return g;
}

EleData read_ele(const std::string& path, int first_index) {
  TextReader r = TextReader::open(path);
  if (!r.next_line())
    r.fail_at(r.last_line(), "expected the header line '<#triangles> <nodes per triangle> <#attributes>', "
                             "but the file holds no data");
  const std::size_t header_line = r.line();
  const long long nt = read_count(r, 0, "triangle count");
  const long long nodes = read_optional_count(r, 1, "nodes per triangle", 3);
  if (nodes != 3 && nodes != 6) r.fail("nodes per triangle is " + str(nodes) + ", but only 3 or 6 are supported");
  const long long nattr = read_optional_count(r, 2, "attribute count", 0);
  if (static_cast<unsigned long long>(nattr) > r.bytes_left())
    r.fail("attribute count " + str(nattr) + " is larger than the file");
  const std::size_t na = static_cast<std::size_t>(nattr);
  const std::size_t fields = 1 + static_cast<std::size_t>(nodes) + na;
  check_count_fits(r, nt, fields, "triangles");
  if (nt >= static_cast<long long>(kNone / 3)) r.fail("triangle count " + str(nt) + " is too large");

  EleData d;
  d.num_attributes = na;
  d.triangles.reserve(3 * static_cast<std::size_t>(nt));
  d.attributes.reserve(safe_capacity(r, static_cast<std::size_t>(nt), na));
  long long base = 0;
  for (long long i = 0; i < nt; ++i) {
    next_entry(r, i, nt, header_line, "triangles");
    const long long id = check_id(r, i, base, "triangle", "triangles");
    if (r.size() < 1 + static_cast<std::size_t>(nodes))
      r.fail("expected " + str(nodes) + " vertices for triangle " + str(id) + ", found " +
             str(static_cast<long long>(r.size()) - 1));
    if (r.size() < fields)
      r.fail("expected " + plural(nattr, "attribute", "attributes") + " for triangle " + str(id) + ", found " +
             str(static_cast<long long>(r.size()) - 1 - nodes));
    std::array<VertexId, 3> v{};
    for (std::size_t k = 0; k < static_cast<std::size_t>(nodes); ++k) {
      const long long x = r.integer(1 + k, [&] { return "a vertex of triangle " + str(id); });
      if (x < first_index)
        r.fail("triangle " + str(id) + " refers to vertex " + str(x) + ", but vertices are numbered from " +
               str(first_index));
      if (x - first_index >= static_cast<long long>(kInfinite))
        r.fail("triangle " + str(id) + " refers to vertex " + str(x) + ", which is too large");
      if (k < 3) v[k] = static_cast<VertexId>(x - first_index);
      else d.midside.push_back(static_cast<VertexId>(x - first_index));
    }
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      r.fail("triangle " + str(id) + " uses vertex " + std::string(r.token(v[0] == v[1] || v[0] == v[2] ? 1 : 2)) +
             " twice");
    d.triangles.insert(d.triangles.end(), v.begin(), v.end());
    for (std::size_t k = 0; k < na; ++k)
      d.attributes.push_back(r.finite_number(1 + static_cast<std::size_t>(nodes) + k, [&] {
        return "attribute " + str(static_cast<long long>(k) + 1) + " of triangle " + str(id);
      }));
  }
  reject_trailing_data(r, "the " + plural(nt, "triangle", "triangles") + " announced on line " +
                              std::to_string(header_line));
  return d;
}

std::vector<double> read_area(const std::string& path) {
  TextReader r = TextReader::open(path);
  if (!r.next_line())
    r.fail_at(r.last_line(), "expected the header line '<#triangles>', but the file holds no data");
  const std::size_t header_line = r.line();
  const long long nt = read_count(r, 0, "triangle count");
  check_count_fits(r, nt, 2, "triangles");
  std::vector<double> areas;
  areas.reserve(static_cast<std::size_t>(nt));
  long long base = 0;
  for (long long i = 0; i < nt; ++i) {
    next_entry(r, i, nt, header_line, "triangles");
    const long long id = check_id(r, i, base, "triangle", "triangles");
    if (r.size() < 2) r.fail("expected a maximum area for triangle " + str(id) + ", found none");
    areas.push_back(area_bound(r.finite_number(1, [&] { return "the maximum area of triangle " + str(id); })));
  }
  reject_trailing_data(r, "the " + plural(nt, "triangle", "triangles") + " announced on line " +
                              std::to_string(header_line));
  return areas;
}

MtrData read_mtr_data(const std::string& path) {
  TextReader r = TextReader::open(path);
  if (!r.next_line())
    r.fail_at(r.last_line(), "expected the header line '<#nodes> <1 or 3>', but the file holds no data");
  const std::size_t header_line = r.line();
  const long long nv = read_count(r, 0, "node count");
  MtrData d;
  if (r.size() > 1) {
    const long long k = r.integer(1, [] { return std::string("the number of values per node"); });
    if (k != 1 && k != 3)
      r.fail("the number of values per node is " + str(k) +
             "; 1 (an isotropic size) and 3 (a metric tensor m11 m12 m22) are supported");
    d.per_node = static_cast<int>(k);
  }
  check_count_fits(r, nv, d.per_node, "nodes");
  d.values.reserve(static_cast<std::size_t>(nv) * static_cast<std::size_t>(d.per_node));
  for (long long i = 0; i < nv; ++i) {
    next_entry(r, i, nv, header_line, d.per_node == 1 ? "node sizes" : "node metrics");
    if (d.per_node == 1) {
      const std::string which = "size " + str(i + 1) + " of " + str(nv);
      if (r.size() != 1)
        r.fail("expected one size per line (" + which + "), found " + str(static_cast<long long>(r.size())) +
               " fields");
      const double h = r.finite_number(0, [&] { return which; });
      if (!(h > 0)) r.fail(which + " is " + std::string(r.token(0)) + "; sizes must be positive");
      d.values.push_back(h);
      continue;
    }
    const std::string which = "metric " + str(i + 1) + " of " + str(nv);
    if (r.size() != 3)
      r.fail("expected three values m11 m12 m22 per line (" + which + "), found " +
             str(static_cast<long long>(r.size())) + " fields");
    Metric m;
    m.m11 = r.finite_number(0, [&] { return "m11 of " + which; });
    m.m12 = r.finite_number(1, [&] { return "m12 of " + which; });
    m.m22 = r.finite_number(2, [&] { return "m22 of " + which; });
    const std::string why = metric_problem(m);
    if (!why.empty()) r.fail(which + " (" + std::string(r.token(0)) + " " + std::string(r.token(1)) + " " +
                             std::string(r.token(2)) + ") " + why);
    d.values.insert(d.values.end(), {m.m11, m.m12, m.m22});
  }
  reject_trailing_data(r, "the " + plural(nv, d.per_node == 1 ? "node size" : "node metric",
                                          d.per_node == 1 ? "node sizes" : "node metrics") +
                              " announced on line " + std::to_string(header_line));
  return d;
}

std::vector<double> read_mtr(const std::string& path) {
  MtrData d = read_mtr_data(path);
  if (d.per_node != 1)
    throw InputError(path + ": holds metric tensors (3 values per node), not sizes: read it with read_mtr_data");
  return std::move(d.values);
}

}  // namespace deltamesh

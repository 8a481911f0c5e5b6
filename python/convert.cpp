// numpy <-> library: the arrays of Triangle's dict layout read into the
// pipeline's input (every array checked, errors naming it), and meshes,
// statistics and PSLGs written back as dicts of arrays.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <tuple>

#include "bindings.hpp"

namespace deltamesh::python {

[[noreturn]] void bad(const std::string& name, const std::string& problem) {
  throw py::value_error(name + ": " + problem);
}

// Any array-like as an ndarray (np.asarray), or a ValueError naming it.
py::array as_array(py::handle obj, const std::string& name) {
  py::array a = py::array::ensure(obj);
  if (!a) bad(name, "cannot be converted to a numpy array (ragged or non-numeric?)");
  return a;
}

std::string dtype_name(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// Shape check: (rows, cols) with cols == want (0: any); a 1-D array is one
// column when want == 1 (markers) or when any width is allowed (attributes);
// an empty list or a (0, k) array is zero rows.
std::pair<std::size_t, std::size_t> rows_cols(const py::array& a, const std::string& name, std::size_t want,
                                              std::size_t rows_expected = static_cast<std::size_t>(-1)) {
  std::size_t rows = 0, cols = want;
  if ((a.ndim() == 1 && a.shape(0) == 0) || (a.ndim() == 2 && a.shape(0) == 0)) {
    rows = 0;
  } else if (a.ndim() == 2 && (want == 0 || static_cast<std::size_t>(a.shape(1)) == want)) {
    rows = static_cast<std::size_t>(a.shape(0));
    cols = static_cast<std::size_t>(a.shape(1));
  } else if (a.ndim() == 1 && (want == 1 || want == 0)) {
    rows = static_cast<std::size_t>(a.shape(0));
    cols = 1;
  } else {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
    shape += a.ndim() == 1 ? ",)" : ")";
    const std::string expected = want == 0   ? "(n, k)"
                                 : want == 1 ? "(n,) or (n, 1)"
                                             : "(n, " + std::to_string(want) + ")";
    bad(name, "expected an array of shape " + expected + ", got shape " + shape);
  }
  if (rows_expected != static_cast<std::size_t>(-1) && rows != rows_expected)
    bad(name, "has " + std::to_string(rows) + " rows, expected " + std::to_string(rows_expected) + " (one per " +
                  (name.find("triangle") != std::string::npos  ? "triangle"
                   : name.find("segment") != std::string::npos ? "segment"
                                                               : "vertex") +
                  ")");
  return {rows, cols};
}


Doubles to_doubles(py::handle obj, const std::string& name, std::size_t want_cols, std::size_t rows_expected) {
  py::array a = as_array(obj, name);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    bad(name, "expected numbers (float or int), got dtype " + dtype_name(a));
  Doubles d;
  std::tie(d.rows, d.cols) = rows_cols(a, name, want_cols, rows_expected);
  auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!c) throw py::error_already_set();
  d.v.assign(c.data(), c.data() + d.rows * d.cols);
  for (std::size_t i = 0; i < d.v.size(); ++i)
    if (!std::isfinite(d.v[i]))
      bad(name, "row " + std::to_string(i / std::max<std::size_t>(d.cols, 1)) + " holds " +
                    (std::isnan(d.v[i]) ? "nan" : "inf") + " (values must be finite)");
  return d;
}

struct Ints {
  std::vector<std::int64_t> v;
  std::size_t rows = 0, cols = 0;
};

Ints to_ints(py::handle obj, const std::string& name, std::size_t want_cols,
             std::size_t rows_expected = static_cast<std::size_t>(-1)) {
  py::array a = as_array(obj, name);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f')
    bad(name, "expected integers, got dtype " + dtype_name(a));
  Ints r;
  std::tie(r.rows, r.cols) = rows_cols(a, name, want_cols, rows_expected);
  if (kind == 'f') {
    // Triangle's package casts float indices; a whole number is taken as
    // it is, a fraction is an error rather than a silent truncation.
    const Doubles d = to_doubles(obj, name, want_cols, rows_expected);
    r.v.resize(d.v.size());
    for (std::size_t i = 0; i < d.v.size(); ++i) {
      const double x = d.v[i];
      if (std::floor(x) != x || std::abs(x) > 9.0e15)
        bad(name, "value " + number_text(x) + " in row " + std::to_string(i / std::max<std::size_t>(d.cols, 1)) +
                      " is not a whole number");
      r.v[i] = static_cast<std::int64_t>(x);
    }
    return r;
  }
  auto c = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!c) throw py::error_already_set();
  r.v.assign(c.data(), c.data() + r.rows * r.cols);
  return r;
}

// Vertex indices (0-based) into n vertices.
std::vector<VertexId> to_indices(py::handle obj, const std::string& name, std::size_t cols, std::size_t n,
                                     std::size_t* rows) {
  Ints r = to_ints(obj, name, cols);
  std::vector<VertexId> out(r.v.size());
  for (std::size_t i = 0; i < r.v.size(); ++i) {
    if (r.v[i] < 0 || static_cast<std::uint64_t>(r.v[i]) >= n)
      bad(name, "index " + std::to_string(r.v[i]) + " in row " + std::to_string(i / cols) + " is out of range for " +
                    std::to_string(n) + " vertices (indices are 0-based)");
    out[i] = static_cast<VertexId>(r.v[i]);
  }
  *rows = r.rows;
  return out;
}

std::vector<int> to_markers(py::handle obj, const std::string& name, std::size_t rows) {
  Ints r = to_ints(obj, name, 1, rows);
  std::vector<int> out(r.v.size());
  for (std::size_t i = 0; i < r.v.size(); ++i) {
    if (r.v[i] < INT32_MIN || r.v[i] > INT32_MAX)
      bad(name, "marker " + std::to_string(r.v[i]) + " does not fit 32 bits");
    out[i] = static_cast<int>(r.v[i]);
  }
  return out;
}

std::string number_text(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool given(py::handle h) { return h && !h.is_none(); }

// All points on one line (exact orient2d): Triangle's package returns the
// vertices and no triangles, where the library refuses the input.
bool all_collinear(const std::vector<Point>& given) {
  if (given.size() < 3) return false;  // too few points: the library's error, as Triangle's
  // At a power-of-two scale near 1 (exact), so that the predicate's products
  // neither underflow nor overflow whatever the input's scale.
  double big = 0;
  for (const Point& q : given) big = std::max({big, std::fabs(q.x), std::fabs(q.y)});
  if (!(big > 0) || !std::isfinite(big)) return false;  // the library says why
  const int k = -std::ilogb(big);
  std::vector<Point> p(given.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = {std::ldexp(given[i].x, k), std::ldexp(given[i].y, k)};
  std::size_t b = 1;
  while (b < p.size() && p[b].x == p[0].x && p[b].y == p[0].y) ++b;
  if (b == p.size()) return true;
  for (std::size_t c = b + 1; c < p.size(); ++c)
    if (orient2d(p[0], p[b], p[c]) != 0) return false;
  return true;
}


Input read_input(const InputArrays& a) {
  Input in;
  if (!given(a.vertices)) throw py::value_error("vertices: required (an (n, 2) array of coordinates)");
  const Doubles v = to_doubles(a.vertices, "vertices", 2);
  const std::size_t n = v.rows;
  in.run.pslg.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) in.run.pslg.points[i] = {v.at(i, 0), v.at(i, 1)};
  if (given(a.vertex_markers)) in.run.pslg.point_markers = to_markers(a.vertex_markers, "vertex_markers", n);
  if (given(a.vertex_attributes)) {
    Doubles at = to_doubles(a.vertex_attributes, "vertex_attributes", 0, n);
    in.run.pslg.num_point_attributes = at.v.empty() ? 0 : at.cols;
    in.run.pslg.point_attributes = std::move(at.v);
  }
  if (given(a.segments)) {
    in.has_segments = true;
    std::size_t rows = 0;
    const std::vector<VertexId> s = to_indices(a.segments, "segments", 2, n, &rows);
    std::vector<int> markers;
    if (given(a.segment_markers)) markers = to_markers(a.segment_markers, "segment_markers", rows);
    in.run.pslg.segments.resize(rows);
    for (std::size_t i = 0; i < rows; ++i)
      in.run.pslg.segments[i] = {s[2 * i], s[2 * i + 1], markers.empty() ? 0 : markers[i]};
  } else if (given(a.segment_markers)) {
    throw py::value_error("segment_markers: given without segments");
  }
  if (given(a.holes)) {
    const Doubles h = to_doubles(a.holes, "holes", 2);
    for (std::size_t i = 0; i < h.rows; ++i) in.run.pslg.holes.push_back({h.at(i, 0), h.at(i, 1)});
  }
  if (given(a.regions)) {
    // Triangle's layout: x, y, attribute, maximum area (negative: none).
    py::array r = as_array(a.regions, "regions");
    const bool three = r.ndim() == 2 && r.shape(1) == 3;
    const Doubles d = to_doubles(a.regions, "regions", three ? 3 : 4);
    for (std::size_t i = 0; i < d.rows; ++i) {
      const double area = three ? -1.0 : d.at(i, 3);
      in.run.pslg.regions.push_back({{d.at(i, 0), d.at(i, 1)}, d.at(i, 2), area > 0 ? area : -1.0});
    }
  }
  if (given(a.triangles)) {
    in.has_triangles = true;
    py::array t = as_array(a.triangles, "triangles");
    const std::size_t corners = t.ndim() == 2 && t.shape(1) == 6 ? 6 : 3;
    std::size_t rows = 0;
    const std::vector<VertexId> tv = to_indices(a.triangles, "triangles", corners, n, &rows);
    for (std::size_t i = 0; i < rows; ++i) {
      for (std::size_t k = 0; k < 3; ++k) in.run.triangles.push_back(tv[i * corners + k]);
      if (corners == 6)
        for (std::size_t k = 3; k < 6; ++k) in.run.midside.push_back(tv[i * corners + k]);
    }
    if (given(a.triangle_attributes)) {
      Doubles at = to_doubles(a.triangle_attributes, "triangle_attributes", 0, rows);
      in.run.num_triangle_attributes = at.v.empty() ? 0 : at.cols;
      in.run.triangle_attributes = std::move(at.v);
    }
    if (given(a.triangle_max_area))
      in.run.triangle_area_bounds = to_doubles(a.triangle_max_area, "triangle_max_area", 1, rows).v;
  } else if (given(a.triangle_attributes) || given(a.triangle_max_area)) {
    throw py::value_error(std::string(given(a.triangle_attributes) ? "triangle_attributes" : "triangle_max_area") +
                          ": given without triangles");
  }
  return in;
}

// Keys triangulate() reads from a dict, and keys of its own output that it
// ignores (so a result can be passed back in, as with Triangle's 'r').
constexpr std::string_view kInputKeys[] = {
    "vertices", "vertex_markers", "vertex_attributes",   "segments",         "segment_markers", "holes",
    "regions",  "triangles",      "triangle_attributes", "triangle_max_area"};
constexpr std::string_view kIgnoredKeys[] = {"edges", "edge_markers", "neighbors", "stats", "voronoi"};

InputArrays arrays_from_dict(const py::dict& d) {
  for (auto item : d) {
    if (!py::isinstance<py::str>(item.first)) throw py::value_error("dict keys must be strings");
    const std::string key = item.first.cast<std::string>();
    const auto known = [&](const auto& list) {
      return std::find(std::begin(list), std::end(list), key) != std::end(list);
    };
    if (!known(kInputKeys) && !known(kIgnoredKeys))
      throw py::value_error("unknown key '" + key +
                            "' (known: vertices, vertex_markers, vertex_attributes, segments, segment_markers, holes, "
                            "regions, triangles, triangle_attributes, triangle_max_area)");
  }
  auto get = [&](const char* k) -> py::handle { return d.contains(k) ? py::handle(d[k]) : py::handle(); };
  return {get("vertices"),         get("vertex_markers"),  get("vertex_attributes"),
          get("segments"),         get("segment_markers"), get("holes"),
          get("regions"),          get("triangles"),       get("triangle_attributes"),
          get("triangle_max_area")};
}


py::dict refine_stats_dict(const RefineStats& s) {
  py::dict d;
  d["complete"] = s.complete;
  d["budget_exhausted"] = s.budget_exhausted;
  d["time_exhausted"] = s.time_exhausted;
  d["stalled"] = s.stalled;
  d["reached_angle"] = s.reached_angle_deg;
  d["below_out_of_reach"] = s.below_out_of_reach;
  if (s.stalled) {
    d["stall_center"] = py::make_tuple(s.stall_x, s.stall_y);
    d["stall_radius"] = s.stall_radius;
    d["kept_angle"] = s.kept_angle_deg;
    d["discarded_steiner"] = s.discarded_steiner;
  }
  d["input_vertices"] = s.input_vertices;
  d["steiner_points"] = s.steiner_points;
  d["segment_splits"] = s.segment_splits;
  d["interior_points"] = s.interior_points;
  d["offcenters"] = s.offcenters;
  d["rejected_points"] = s.rejected_points;
  d["small_angle_skips"] = s.small_angle_skips;
  d["failed_splits"] = s.failed_splits;
  d["below_bound"] = s.below_bound;
  d["below_small_input_angle"] = s.below_small_input_angle;
  d["below_segment_protected"] = s.below_segment_protected;
  d["below_budget"] = s.below_budget;
  d["below_precision"] = s.below_precision;
  d["too_large"] = s.too_large;
  d["too_large_precision"] = s.too_large_precision;
  d["min_angle_bound"] = s.min_angle_deg;
  d["seconds"] = s.seconds;
  d["summary"] = s.summary();
  // Why the run is incomplete (the CLI's exit-3 message); "" when complete.
  d["unmet"] = s.unmet();
  if (s.below_precision || s.too_large_precision) {
    d["precision_center"] = py::make_tuple(s.precision_x, s.precision_y);
    d["precision_edge"] = s.precision_edge;
    d["precision_magnitude"] = s.precision_magnitude;
  }
  return d;
}

// A Python size function called from the refining thread: it takes the GIL
// for each call; the first exception (or a non-finite value) stops the
// calls and is re-raised when refinement returns.

namespace {

// Output ordering only (nothing in the mesh depends on it): how far `w`
// lies along the way from `from` to `to`, as a cosine and a length ratio.
bool continues_towards(const Point& from, const Point& w, const Point& to, double* cos_out) {
  const double ux = w.x - from.x, uy = w.y - from.y, vx = to.x - from.x, vy = to.y - from.y;
  const double lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
  if (!(lu > 0) || !(lv > 0) || lu > lv * (1 + 1e-9)) return false;
  *cos_out = (ux * vx + uy * vy) / (lu * lv);
  return *cos_out > 1 - 1e-9;
}

}  // namespace

std::vector<OutEdge> triangle_boundary_order(const Mesh& mesh, std::vector<OutEdge> ccw) {
  std::vector<OutEdge> out;
  out.reserve(ccw.size());
  std::vector<std::vector<std::size_t>> from(mesh.num_vertices());
  for (std::size_t i = 0; i < ccw.size(); ++i) from[static_cast<std::size_t>(ccw[i].a)].push_back(i);
  std::vector<bool> used(ccw.size(), false);
  // Cycle by cycle, each from its lowest-leftmost vertex (x, then y).
  std::vector<std::size_t> by_origin(ccw.size());
  for (std::size_t i = 0; i < ccw.size(); ++i) by_origin[i] = i;
  std::stable_sort(by_origin.begin(), by_origin.end(), [&](std::size_t i, std::size_t j) {
    const Point& p = mesh.point(static_cast<VertexId>(ccw[i].a));
    const Point& q = mesh.point(static_cast<VertexId>(ccw[j].a));
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  for (const std::size_t first : by_origin) {
    std::size_t e = first;
    while (!used[e]) {
      used[e] = true;
      out.push_back({ccw[e].b, ccw[e].a, ccw[e].marker, true});  // reversed: the interior on the right
      std::size_t next = ccw.size();
      for (const std::size_t k : from[static_cast<std::size_t>(ccw[e].b)])
        if (!used[k]) {
          next = k;
          break;
        }
      if (next == ccw.size()) break;
      e = next;
    }
  }
  return out;
}

namespace {

// Segments in the order of the input: each input segment's pieces from its
// first end to its second, then what no input segment explains (hull edges
// of 'c', pieces of segments split where they crossed) as Triangle lists a
// boundary, then the rest in triangle order.
std::vector<OutEdge> input_order(const Mesh& mesh, const std::vector<OutEdge>& found,
                                 const std::vector<Segment>& input) {
  std::vector<std::vector<std::size_t>> at(mesh.num_vertices());
  for (std::size_t i = 0; i < found.size(); ++i) {
    at[static_cast<std::size_t>(found[i].a)].push_back(i);
    at[static_cast<std::size_t>(found[i].b)].push_back(i);
  }
  std::vector<bool> used(found.size(), false);
  std::vector<OutEdge> out;
  out.reserve(found.size());
  for (const Segment& s : input) {
    if (s.a == s.b || s.a >= mesh.num_vertices() || s.b >= mesh.num_vertices()) continue;
    const Point& to = mesh.point(s.b);
    std::size_t cur = s.a;
    for (std::size_t steps = 0; cur != s.b && steps < found.size(); ++steps) {
      std::size_t best = found.size();
      double best_cos = -2;
      for (const std::size_t k : at[cur]) {
        if (used[k]) continue;
        const std::size_t w = static_cast<std::size_t>(found[k].a) == cur ? found[k].b : found[k].a;
        double c = 0;
        if (w == s.b || continues_towards(mesh.point(static_cast<VertexId>(cur)), mesh.point(static_cast<VertexId>(w)),
                                          to, &c)) {
          if (w == s.b) c = 2;
          if (c > best_cos) best_cos = c, best = k;
        }
      }
      if (best == found.size()) break;
      used[best] = true;
      const std::size_t w = static_cast<std::size_t>(found[best].a) == cur ? found[best].b : found[best].a;
      out.push_back({static_cast<std::int32_t>(cur), static_cast<std::int32_t>(w), found[best].marker,
                     found[best].boundary});
      cur = w;
    }
  }
  std::vector<OutEdge> boundary, interior;
  for (std::size_t i = 0; i < found.size(); ++i)
    if (!used[i]) (found[i].boundary ? boundary : interior).push_back(found[i]);
  for (const OutEdge& e : triangle_boundary_order(mesh, std::move(boundary))) out.push_back(e);
  out.insert(out.end(), interior.begin(), interior.end());
  return out;
}

// Triangle's package leaves out every array with no rows.
void put(py::dict& out, const char* key, py::array a) {
  if (a.ndim() >= 1 && a.shape(0) > 0) out[key] = std::move(a);
}

}  // namespace

py::dict mesh_dict(const RunResult& res, const Plan& o, const Pslg& seeds, const OutputSwitches& sw) {
  const Mesh& mesh = res.mesh;
  py::dict out;
  const std::size_t nv = mesh.num_vertices();
  if (!sw.no_node) {
    std::vector<double> xy(2 * nv);
    for (std::size_t i = 0; i < nv; ++i) {
      xy[2 * i] = mesh.point(static_cast<VertexId>(i)).x;
      xy[2 * i + 1] = mesh.point(static_cast<VertexId>(i)).y;
    }
    put(out, "vertices", array_2d(xy, 2));
    if (o.markers) {
      std::vector<std::int32_t> vm(nv, 0);
      const auto& mk = mesh.vertex_markers();
      for (std::size_t i = 0; i < std::min(nv, mk.size()); ++i) vm[i] = mk[i];
      put(out, "vertex_markers", array_2d(vm, 1));
    }
    if (mesh.num_vertex_attributes() > 0) {
      std::vector<double> va(mesh.vertex_attributes().begin(), mesh.vertex_attributes().end());
      va.resize(nv * mesh.num_vertex_attributes(), 0.0);
      put(out, "vertex_attributes", array_2d(va, mesh.num_vertex_attributes()));
    }
  }

  // Triangles in slot order (the mesh is compacted: every slot is real).
  const std::size_t slots = mesh.num_triangle_slots();
  std::vector<TriId> index(slots, kNone);
  std::size_t nt = 0;
  for (TriId t = 0; t < slots; ++t)
    if (mesh.is_real(t)) index[t] = static_cast<TriId>(nt++);
  const std::size_t corners = res.midside.empty() ? 3 : 6;
  const std::size_t na = mesh.num_triangle_attributes();
  // -A appends a column; with no regions Triangle's package has none.
  const std::size_t na_out = o.domain.regional_attributes && seeds.regions.empty() && na > 0 ? na - 1 : na;
  std::vector<std::int32_t> tris;
  std::vector<double> tattr;
  std::vector<std::int32_t> neigh;
  tris.reserve(corners * nt);
  for (TriId t = 0; t < slots; ++t) {
    if (index[t] == kNone) continue;
    for (const VertexId v : mesh.triangle(t)) tris.push_back(static_cast<std::int32_t>(v));
    if (corners == 6)
      for (std::size_t k = 0; k < 3; ++k)
        tris.push_back(static_cast<std::int32_t>(res.midside[3 * std::size_t{t} + k]));
    for (std::size_t k = 0; k < na_out; ++k) tattr.push_back(mesh.triangle_attributes()[t * na + k]);
    if (o.neighbors)
      for (HalfEdgeId i = 0; i < 3; ++i) {
        // Neighbour i is opposite vertex i, across half-edge 3t + (i+1)%3.
        const HalfEdgeId tw = real_twin(mesh, 3 * t + (i + 1) % 3);
        neigh.push_back(tw == kNone ? -1 : static_cast<std::int32_t>(index[tri_of(tw)]));
      }
  }
  if (!sw.no_ele) {
    put(out, "triangles", array_2d(tris, corners));
    if (na_out > 0) put(out, "triangle_attributes", array_2d(tattr, na_out));
  }
  if (o.neighbors) put(out, "neighbors", array_2d(neigh, 3));

  // Edges once each; segments are the constrained ones.
  const bool want_segments = (o.uses_segments() || o.domain.convex_hull) && !sw.no_poly;
  std::vector<OutEdge> found;
  std::vector<std::int32_t> edges, edge_mk;
  for (TriId t = 0; t < slots; ++t) {
    if (index[t] == kNone) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const HalfEdgeId tw = real_twin(mesh, e);
      if (tw != kNone && tw < e) continue;
      const std::int32_t a = static_cast<std::int32_t>(mesh.origin(e)), b = static_cast<std::int32_t>(mesh.dest(e));
      const int marker = edge_output_marker(mesh, e, tw);
      if (o.edges) {
        edges.insert(edges.end(), {a, b});
        edge_mk.push_back(marker);
      }
      if (want_segments && (mesh.is_constrained(e) || (tw != kNone && mesh.is_constrained(tw))))
        found.push_back({a, b, marker, tw == kNone});
    }
  }
  if (want_segments) {
    std::vector<std::int32_t> seg, seg_mk;
    for (const OutEdge& e : input_order(mesh, found, seeds.segments)) {
      seg.insert(seg.end(), {e.a, e.b});
      seg_mk.push_back(e.marker);
    }
    put(out, "segments", array_2d(seg, 2));
    if (o.markers) put(out, "segment_markers", array_2d(seg_mk, 1));
  }
  if (o.edges) {
    put(out, "edges", array_2d(edges, 2));
    if (o.markers) put(out, "edge_markers", array_2d(edge_mk, 1));
  }
  if (o.uses_segments() && !sw.no_poly) {
    std::vector<double> h;
    for (const Point& p : seeds.holes) h.insert(h.end(), {p.x, p.y});
    put(out, "holes", array_2d(h, 2));
    std::vector<double> r;
    for (const RegionSeed& s : seeds.regions) r.insert(r.end(), {s.p.x, s.p.y, s.attribute, s.max_area});
    put(out, "regions", array_2d(r, 4));
  }
  if (sw.voronoi) out["voronoi"] = voronoi_arrays(mesh);
  return out;
}

// Triangle's -v output as the package's voronoi() gives it: the Voronoi
// vertices, the finite edges, and each ray's origin and direction.
py::dict voronoi_arrays(const Mesh& mesh) {
  VoronoiDiagram vd;
  {
    py::gil_scoped_release nogil;
    vd = voronoi_diagram(mesh);
  }
  std::vector<double> xy, dir;
  std::vector<std::int32_t> edges, origins;
  for (const Point& p : vd.vertices) xy.insert(xy.end(), {p.x, p.y});
  for (const auto& e : vd.edges) {
    if (e.is_ray()) {
      origins.push_back(static_cast<std::int32_t>(e.a));
      dir.insert(dir.end(), {e.direction.x + 0.0, e.direction.y + 0.0});  // no -0.0
    } else {
      edges.insert(edges.end(), {static_cast<std::int32_t>(e.a), static_cast<std::int32_t>(e.b)});
    }
  }
  py::dict d;
  d["vertices"] = array_2d(xy, 2);
  d["edges"] = array_2d(edges, 2);
  py::array_t<std::int32_t> o(static_cast<py::ssize_t>(origins.size()));
  std::copy(origins.begin(), origins.end(), o.mutable_data());
  d["ray_origins"] = o;
  d["ray_directions"] = array_2d(dir, 2);
  return d;
}

// The smallest and largest angle of the mesh in degrees. quality_report()
// computes far more and costs as much as a Delaunay triangulation, so this
// ranks triangles by a monotone proxy and takes atan2 for the two winners
// only: the smallest angle sits between the two longer edges b, c and is
// at most 60 degrees, where cross^2 / (b^2 c^2) = sin^2 grows with the angle;
// the largest sits between the two shorter edges, where the signed square of
// dot / (|b| |c|) = cos falls as the angle grows.
namespace {

std::pair<double, double> extreme_angles(const Mesh& mesh) {
  double best_min = 2.0, best_max = 2.0;
  double min_deg = 0.0, max_deg = 0.0;
  const std::size_t slots = mesh.num_triangle_slots();
  auto angle_at = [&](const Point& apex, const Point& p, const Point& q) {
    const double ux = p.x - apex.x, uy = p.y - apex.y, vx = q.x - apex.x, vy = q.y - apex.y;
    return std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * (180.0 / 3.14159265358979323846);
  };
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const Point* p[3] = {&mesh.point(v[0]), &mesh.point(v[1]), &mesh.point(v[2])};
    double len2[3];  // len2[k]: edge opposite corner k
    for (int k = 0; k < 3; ++k) {
      const Point& a = *p[(k + 1) % 3];
      const Point& b = *p[(k + 2) % 3];
      len2[k] = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
    }
    const int shortest = len2[0] <= len2[1] ? (len2[0] <= len2[2] ? 0 : 2) : (len2[1] <= len2[2] ? 1 : 2);
    const int longest = len2[0] >= len2[1] ? (len2[0] >= len2[2] ? 0 : 2) : (len2[1] >= len2[2] ? 1 : 2);
    const double ux = p[1]->x - p[0]->x, uy = p[1]->y - p[0]->y, wx = p[2]->x - p[0]->x, wy = p[2]->y - p[0]->y;
    const double cross = ux * wy - uy * wx;
    auto corner_terms = [&](int k, double& bc2, double& dot) {
      const Point& a = *p[k];
      const Point& b = *p[(k + 1) % 3];
      const Point& c = *p[(k + 2) % 3];
      bc2 = len2[(k + 1) % 3] * len2[(k + 2) % 3];
      dot = (b.x - a.x) * (c.x - a.x) + (b.y - a.y) * (c.y - a.y);
    };
    double bc2 = 0, dot = 0;
    corner_terms(shortest, bc2, dot);
    const double sin2 = bc2 > 0 ? cross * cross / bc2 : 0.0;
    if (sin2 < best_min) {
      best_min = sin2;
      min_deg = angle_at(*p[shortest], *p[(shortest + 1) % 3], *p[(shortest + 2) % 3]);
    }
    corner_terms(longest, bc2, dot);
    const double cos2 = bc2 > 0 ? dot * std::abs(dot) / bc2 : -1.0;
    if (cos2 < best_max) {
      best_max = cos2;
      max_deg = angle_at(*p[longest], *p[(longest + 1) % 3], *p[(longest + 2) % 3]);
    }
  }
  return {min_deg, max_deg};
}

}  // namespace

py::dict stats_dict(const RunResult& res) {
  const Mesh& mesh = res.mesh;
  const TriangulateStats& s = res.stats;
  py::dict d;
  d["input_vertices"] = s.input_vertices;
  d["input_segments"] = s.input_segments;
  d["duplicate_vertices"] = s.duplicate_vertices;
  d["crossing_vertices"] = s.steiner_vertices;
  d["vertices"] = mesh.num_vertices();
  d["triangles"] = mesh.num_triangles();
  d["holes_used"] = s.domain.holes_used;
  d["holes_ignored"] = s.domain.holes_ignored;
  d["regions_used"] = s.domain.regions_used;
  d["regions_ignored"] = s.domain.regions_ignored;
  const auto [min_angle, max_angle] = extreme_angles(mesh);
  d["min_angle"] = mesh.num_triangles() ? py::object(py::float_(min_angle)) : py::object(py::none());
  d["max_angle"] = mesh.num_triangles() ? py::object(py::float_(max_angle)) : py::object(py::none());
  d["refined"] = res.refined;
  d["complete"] = !res.refined || s.refine.complete;
  d["steiner_points"] = res.refined ? s.refine.steiner_points : 0;
  d["refine"] = res.refined ? py::object(refine_stats_dict(s.refine)) : py::object(py::none());
  py::list w;
  for (const std::string& x : s.warnings) w.append(x);
  d["warnings"] = w;
  d["check"] = res.check ? py::object(py::str(res.check->summary())) : py::object(py::none());
  d["seconds"] = res.seconds;
  return d;
}


py::dict pslg_dict(const Pslg& p) {
  py::dict d;
  std::vector<double> xy;
  for (const Point& q : p.points) xy.insert(xy.end(), {q.x, q.y});
  d["vertices"] = array_2d(xy, 2);
  if (!p.point_markers.empty())
    d["vertex_markers"] = array_2d(std::vector<std::int32_t>(p.point_markers.begin(), p.point_markers.end()), 1);
  if (p.num_point_attributes) d["vertex_attributes"] = array_2d(p.point_attributes, p.num_point_attributes);
  if (!p.segments.empty()) {
    std::vector<std::int32_t> s, m;
    for (const Segment& g : p.segments) {
      s.insert(s.end(), {static_cast<std::int32_t>(g.a), static_cast<std::int32_t>(g.b)});
      m.push_back(g.marker);
    }
    d["segments"] = array_2d(s, 2);
    d["segment_markers"] = array_2d(m, 1);
  }
  if (!p.holes.empty()) {
    std::vector<double> h;
    for (const Point& q : p.holes) h.insert(h.end(), {q.x, q.y});
    d["holes"] = array_2d(h, 2);
  }
  if (!p.regions.empty()) {
    std::vector<double> r;
    for (const RegionSeed& s : p.regions) r.insert(r.end(), {s.p.x, s.p.y, s.attribute, s.max_area});
    d["regions"] = array_2d(r, 4);
  }
  return d;
}

}  // namespace deltamesh::python

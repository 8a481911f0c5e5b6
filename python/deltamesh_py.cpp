// Python bindings (pybind11 + numpy): Triangle-style triangulate() on a dict
// of arrays and a switch string, a keyword form of the same, the validator,
// the quality report and file reading/writing. See docs/python.md.
//
// Both forms of triangulate() end up as the CLI's Options (the switch string
// and the keywords go through cli::parse_arguments), so they mean the same
// thing as the command line does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "deltamesh/deltamesh.hpp"
#include "deltamesh/switches.hpp"

namespace py = pybind11;
namespace dm = deltamesh;
using deltamesh::cli::Options;
using deltamesh::cli::UsageError;

namespace {

// ---------------------------------------------------------------------------
// Exceptions: deltamesh.Error and subclasses, created in the module init.

struct ExceptionTypes {
  PyObject* error = nullptr;         // deltamesh.Error(Exception)
  PyObject* input = nullptr;         // deltamesh.InputError(Error, ValueError)
  PyObject* parse = nullptr;         // deltamesh.ParseError(InputError)
  PyObject* intersecting = nullptr;  // deltamesh.IntersectingSegments(InputError)
  PyObject* segment = nullptr;       // deltamesh.SegmentError(InputError)
  PyObject* io = nullptr;            // deltamesh.IoError(Error, OSError)
  PyObject* check = nullptr;         // deltamesh.CheckError(Error)
};
ExceptionTypes g_exc;  // references owned by the module (never freed: the module lives until exit)

PyObject* new_exception(py::module_& m, const char* name, std::initializer_list<PyObject*> bases, const char* doc) {
  py::tuple b(bases.size());
  std::size_t i = 0;
  for (PyObject* p : bases) b[i++] = py::reinterpret_borrow<py::object>(p);
  const std::string full = std::string("deltamesh.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(full.c_str(), doc, b.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(type));
  return type;  // the new reference from PyErr_NewException is kept for g_exc
}

// Raises `type(message)` with extra attributes set on the instance.
void raise_with(PyObject* type, const std::string& message,
                std::initializer_list<std::pair<const char*, py::object>> attrs = {}) {
  py::object inst = py::reinterpret_borrow<py::object>(type)(message);
  for (const auto& [k, v] : attrs) inst.attr(k) = v;
  PyErr_SetObject(type, inst.ptr());
}

void translate_exception(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const dm::ParseError& e) {
    raise_with(g_exc.parse, e.what(), {{"file", py::str(e.file())}, {"line", py::int_(e.line())}});
  } catch (const dm::IntersectingSegments& e) {
    raise_with(g_exc.intersecting, e.what(), {{"first", py::int_(e.first())}, {"second", py::int_(e.second())}});
  } catch (const dm::SegmentError& e) {
    raise_with(g_exc.segment, e.what(), {{"segment", py::int_(e.segment())}});
  } catch (const dm::InputError& e) {
    py::object index =
        e.index() == static_cast<std::size_t>(-1) ? py::object(py::none()) : py::object(py::int_(e.index()));
    raise_with(g_exc.input, e.what(), {{"index", index}});
  } catch (const dm::IoError& e) {
    raise_with(g_exc.io, e.what());
  } catch (const dm::Error& e) {
    raise_with(g_exc.error, e.what());
  }
}

// ---------------------------------------------------------------------------
// numpy arrays in

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

struct Doubles {
  std::vector<double> v;  // row-major
  std::size_t rows = 0, cols = 0;
  double at(std::size_t r, std::size_t c) const { return v[r * cols + c]; }
};

// Floating-point rows (integers are converted); every value finite.
Doubles to_doubles(py::handle obj, const std::string& name, std::size_t want_cols,
                   std::size_t rows_expected = static_cast<std::size_t>(-1)) {
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
  if (kind != 'i' && kind != 'u' && !(kind == 'f' && a.size() == 0))  // [] is float64 to numpy
    bad(name, "expected integers, got dtype " + dtype_name(a));
  Ints r;
  std::tie(r.rows, r.cols) = rows_cols(a, name, want_cols, rows_expected);
  auto c = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!c) throw py::error_already_set();
  r.v.assign(c.data(), c.data() + r.rows * r.cols);
  return r;
}

// Vertex indices (0-based) into n vertices.
std::vector<dm::VertexId> to_indices(py::handle obj, const std::string& name, std::size_t cols, std::size_t n,
                                     std::size_t* rows) {
  Ints r = to_ints(obj, name, cols);
  std::vector<dm::VertexId> out(r.v.size());
  for (std::size_t i = 0; i < r.v.size(); ++i) {
    if (r.v[i] < 0 || static_cast<std::uint64_t>(r.v[i]) >= n)
      bad(name, "index " + std::to_string(r.v[i]) + " in row " + std::to_string(i / cols) + " is out of range for " +
                    std::to_string(n) + " vertices (indices are 0-based)");
    out[i] = static_cast<dm::VertexId>(r.v[i]);
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

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool given(py::handle h) { return h && !h.is_none(); }

// What triangulate() meshes: a PSLG and, for 'r', a mesh's triangles.
struct Input {
  dm::Pslg pslg;
  bool has_segments = false;
  bool has_triangles = false;
  std::vector<dm::VertexId> triangles;  // 3 per triangle (corners)
  std::vector<dm::VertexId> midside;    // 3 per triangle when 6-node triangles were given
  std::size_t num_triangle_attributes = 0;
  std::vector<double> triangle_attributes;
  std::vector<double> triangle_max_area;  // one per triangle, or empty
};

struct InputArrays {
  py::handle vertices, vertex_markers, vertex_attributes, segments, segment_markers, holes, regions, triangles,
      triangle_attributes, triangle_max_area;
};

Input read_input(const InputArrays& a) {
  Input in;
  if (!given(a.vertices)) throw py::value_error("vertices: required (an (n, 2) array of coordinates)");
  const Doubles v = to_doubles(a.vertices, "vertices", 2);
  const std::size_t n = v.rows;
  in.pslg.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) in.pslg.points[i] = {v.at(i, 0), v.at(i, 1)};
  if (given(a.vertex_markers)) in.pslg.point_markers = to_markers(a.vertex_markers, "vertex_markers", n);
  if (given(a.vertex_attributes)) {
    Doubles at = to_doubles(a.vertex_attributes, "vertex_attributes", 0, n);
    in.pslg.num_point_attributes = at.v.empty() ? 0 : at.cols;
    in.pslg.point_attributes = std::move(at.v);
  }
  if (given(a.segments)) {
    in.has_segments = true;
    std::size_t rows = 0;
    const std::vector<dm::VertexId> s = to_indices(a.segments, "segments", 2, n, &rows);
    std::vector<int> markers;
    if (given(a.segment_markers)) markers = to_markers(a.segment_markers, "segment_markers", rows);
    in.pslg.segments.resize(rows);
    for (std::size_t i = 0; i < rows; ++i)
      in.pslg.segments[i] = {s[2 * i], s[2 * i + 1], markers.empty() ? 0 : markers[i]};
  } else if (given(a.segment_markers)) {
    throw py::value_error("segment_markers: given without segments");
  }
  if (given(a.holes)) {
    const Doubles h = to_doubles(a.holes, "holes", 2);
    for (std::size_t i = 0; i < h.rows; ++i) in.pslg.holes.push_back({h.at(i, 0), h.at(i, 1)});
  }
  if (given(a.regions)) {
    // Triangle's layout: x, y, attribute, maximum area (negative: none).
    py::array r = as_array(a.regions, "regions");
    const bool three = r.ndim() == 2 && r.shape(1) == 3;
    const Doubles d = to_doubles(a.regions, "regions", three ? 3 : 4);
    for (std::size_t i = 0; i < d.rows; ++i) {
      const double area = three ? -1.0 : d.at(i, 3);
      in.pslg.regions.push_back({{d.at(i, 0), d.at(i, 1)}, d.at(i, 2), area > 0 ? area : -1.0});
    }
  }
  if (given(a.triangles)) {
    in.has_triangles = true;
    py::array t = as_array(a.triangles, "triangles");
    const std::size_t corners = t.ndim() == 2 && t.shape(1) == 6 ? 6 : 3;
    std::size_t rows = 0;
    const std::vector<dm::VertexId> tv = to_indices(a.triangles, "triangles", corners, n, &rows);
    for (std::size_t i = 0; i < rows; ++i) {
      for (std::size_t k = 0; k < 3; ++k) in.triangles.push_back(tv[i * corners + k]);
      if (corners == 6)
        for (std::size_t k = 3; k < 6; ++k) in.midside.push_back(tv[i * corners + k]);
    }
    if (given(a.triangle_attributes)) {
      Doubles at = to_doubles(a.triangle_attributes, "triangle_attributes", 0, rows);
      in.num_triangle_attributes = at.v.empty() ? 0 : at.cols;
      in.triangle_attributes = std::move(at.v);
    }
    if (given(a.triangle_max_area))
      in.triangle_max_area = to_doubles(a.triangle_max_area, "triangle_max_area", 1, rows).v;
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
constexpr std::string_view kIgnoredKeys[] = {"edges", "edge_markers", "neighbors", "stats"};

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

// ---------------------------------------------------------------------------
// Options

// Long options that make sense without files (the rest name outputs).
constexpr std::string_view kLongOptions[] = {"--cdt",
                                             "--fill",
                                             "--strict",
                                             "--steiner",
                                             "--encroachment",
                                             "--order",
                                             "--time-limit",
                                             "--min-angle",
                                             "--max-area",
                                             "--steiner-budget",
                                             "--quality",
                                             "--regional-area",
                                             "--conforming-delaunay",
                                             "--no-boundary-steiner",
                                             "--second-order",
                                             "--convex-hull",
                                             "--regional-attributes",
                                             "--ignore-holes",
                                             "--jettison",
                                             "--edges",
                                             "--neighbors",
                                             "--check",
                                             "--quiet",
                                             "--verbose",
                                             "--zero-based",
                                             "--poly",
                                             "--refine",
                                             "--no-markers",
                                             "--no-poly",
                                             "--no-iteration",
                                             "--incremental",
                                             "--sweepline",
                                             "--vertical-cuts",
                                             "--no-exact",
                                             "--split-segments"};

// Triangle switches that are about files or need a compiled-in function.
std::optional<std::string> refused_switch(char c) {
  switch (c) {
    case 'N':
      return "-N (no .node file) would drop the vertices; there are no files here";
    case 'E':
      return "-E (no .ele file) would drop the triangles; there are no files here";
    case 'g':
      return "-g writes an .off file: use deltamesh.write(mesh, 'out.off')";
    case 'v':
      return "-v (Voronoi diagram): use deltamesh.voronoi(vertices)";
    case 'h':
      return "-h prints the command line help: see help(deltamesh.triangulate)";
    case 'u':
      return "-u (user size function): pass max_area_fn=f(x, y) to the keyword form of deltamesh.triangulate";
    default:
      return std::nullopt;
  }
}

// Parses a Triangle switch string ("pq30a0.1", a leading '-' optional) with
// the CLI's parser; whitespace separates it from long options given as
// --name=value. Throws ValueError for anything the parser rejects.
Options parse_switches(const std::string& opts) {
  std::vector<std::string> args;
  std::size_t i = 0;
  while (i < opts.size()) {
    while (i < opts.size() && std::isspace(static_cast<unsigned char>(opts[i]))) ++i;
    std::size_t j = i;
    while (j < opts.size() && !std::isspace(static_cast<unsigned char>(opts[j]))) ++j;
    if (j > i) {
      std::string tok = opts.substr(i, j - i);
      if (tok.rfind("--", 0) == 0) {
        const std::string name = tok.substr(0, tok.find('='));
        if (name == "--adapt" || name == "--smooth")
          throw py::value_error("option " + name + " in '" + opts +
                                "': use deltamesh.adapt(mesh, size, opts, smooth=N) (smooth=0 for none)");
        if (std::find(std::begin(kLongOptions), std::end(kLongOptions), name) == std::end(kLongOptions))
          throw py::value_error(
              "option " + name + " in '" + opts +
              "' is not available in deltamesh.triangulate (it names an output file or does not exist)");
      } else {
        if (tok[0] == '-') tok.erase(0, 1);
        if (tok.empty()) {
          i = j;
          continue;
        }
        // Numbers are digits and '.', so every letter is a switch.
        for (const char c : tok)
          if (auto why = refused_switch(c)) throw py::value_error("switch " + *why);
        tok = "-" + tok;
      }
      args.push_back(std::move(tok));
    }
    i = j;
  }
  try {
    // One at a time first, so that "--cdt" without "=value" cannot take the next token as its value.
    for (const std::string& a : args) (void)dm::cli::parse_arguments({a});
    Options o = dm::cli::parse_arguments(args);
    if (!o.unavailable.empty()) throw py::value_error("switch " + o.unavailable.front() + " is not available");
    return o;
  } catch (const UsageError& e) {
    std::string msg = e.message;
    const std::string_view cli_hint = " (see deltamesh --help)";
    if (ends_with(msg, cli_hint)) msg.resize(msg.size() - cli_hint.size());
    throw py::value_error("bad switches '" + opts + "': " + msg);
  }
}

// The keyword form, as long options for the same parser: each keyword is
// checked on its own so that the error names it.
std::string number_text(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest text that reads back as x
  return std::string(buf, r.ptr);
}

struct KeywordOptions {
  std::vector<std::pair<std::string, std::string>> args;  // keyword name, long option
  void flag(const char* kw, bool on, const char* opt) {
    if (on) args.emplace_back(kw, opt);
  }
  void value(const char* kw, py::handle v, const char* opt) {
    if (!given(v)) return;
    std::string text;
    if (py::isinstance<py::str>(v))
      text = v.cast<std::string>();
    else if (py::isinstance<py::bool_>(v))
      throw py::value_error(std::string(kw) + ": expected a number or a string, got a bool");
    else if (py::isinstance<py::int_>(v))
      text = py::str(v).cast<std::string>();
    else {
      try {
        text = number_text(v.cast<double>());
      } catch (const py::cast_error&) {
        throw py::value_error(std::string(kw) + ": expected a number or a string, got " +
                              py::str(py::type::of(v)).cast<std::string>());
      }
    }
    args.emplace_back(kw, std::string(opt) + "=" + text);
  }
  Options parse() const {
    std::vector<std::string> all;
    for (const auto& [kw, a] : args) {
      try {
        (void)dm::cli::parse_arguments({a});
      } catch (const UsageError& e) {
        throw py::value_error(kw + ": " + e.message);
      }
      all.push_back(a);
    }
    return dm::cli::parse_arguments(all);
  }
};

// ---------------------------------------------------------------------------
// The pipeline

// Triangle's output marker of an edge: its segment's marker when nonzero,
// else 1 on the boundary, else 0.
int edge_marker(const dm::Mesh& m, dm::HalfEdgeId e, dm::HalfEdgeId twin) {
  int marker = m.edge_marker(e);
  if (marker == 0 && twin != dm::kNone) marker = m.edge_marker(twin);
  if (marker != 0) return marker;
  return twin == dm::kNone ? 1 : 0;
}

dm::HalfEdgeId real_twin(const dm::Mesh& m, dm::HalfEdgeId e) {
  const dm::HalfEdgeId f = m.twin(e);
  return f == dm::kNone || !m.is_real(dm::tri_of(f)) ? dm::kNone : f;
}

template <class T>
py::array_t<T> array_2d(const std::vector<T>& v, std::size_t cols) {
  const std::size_t rows = cols ? v.size() / cols : 0;
  py::array_t<T> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict refine_stats_dict(const dm::RefineStats& s) {
  py::dict d;
  d["complete"] = s.complete;
  d["budget_exhausted"] = s.budget_exhausted;
  d["time_exhausted"] = s.time_exhausted;
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
  return d;
}

// A Python size function called from the refining thread: it takes the GIL
// for each call; the first exception (or a non-finite value) stops the
// calls and is re-raised when refinement returns.
struct SizeCallback {
  py::object fn;
  const char* name = "";
  std::exception_ptr error;
  std::string bad_value;
  std::function<double(double, double)> make() {
    if (!given(fn)) return {};
    return [this](double x, double y) -> double {
      if (error || !bad_value.empty()) return -1.0;
      py::gil_scoped_acquire gil;
      try {
        const py::object r = fn(x, y);
        const double v = PyFloat_AsDouble(r.ptr());  // TypeError for a non-number
        if (v == -1.0 && PyErr_Occurred()) throw py::error_already_set();
        if (!std::isfinite(v)) {
          bad_value = std::string(name) + " returned " + number_text(v) + " at (" + number_text(x) + ", " +
                      number_text(y) + "); it must return a finite area or length (<= 0: no bound)";
          return -1.0;
        }
        return v;
      } catch (...) {
        error = std::current_exception();
        return -1.0;
      }
    };
  }
  void rethrow() const {
    if (error) std::rethrow_exception(error);
    if (!bad_value.empty()) throw py::value_error(bad_value);
  }
};

struct RunResult {
  dm::Mesh mesh;
  dm::TriangulateStats stats;
  bool refined = false;
  bool poly = false;
  std::vector<dm::VertexId> midside;
  std::string check_summary;
  std::vector<std::string> check_problems;
  double seconds = 0.0;
};

bool wants_refinement(const Options& o, bool size_fn) {
  return o.quality || o.area || o.steiner_budget || o.conforming_delaunay || size_fn;
}

// Meshes `in` as the CLI would with the same switches; called without the GIL.
void run_pipeline(Input& in, const Options& o, dm::RefineOptions* ropt, RunResult& res) {
  const auto t0 = std::chrono::steady_clock::now();
  res.poly = o.poly;
  if (o.refine) {
    // 'r': rebuild the given triangles (segments of 'p' inserted where they
    // are not edges, holes carved), then refine.
    dm::Pslg nodes = in.pslg;
    if (!o.poly) nodes.segments.clear();
    if (!in.midside.empty()) dm::drop_midpoint_nodes(nodes, in.triangles, in.midside);
    dm::RebuildOptions rb;
    if (o.area_from_regions) rb.area_bounds = in.triangle_max_area;
    rb.method = o.cdt_method;
    rb.strict = o.strict;
    dm::InsertSegmentsStats ins;
    res.mesh =
        dm::mesh_from_triangles(nodes, in.triangles, in.num_triangle_attributes, in.triangle_attributes, rb, &ins);
    res.stats.input_vertices = nodes.points.size();
    res.stats.input_segments = nodes.segments.size();
    if (o.poly) {
      if (o.check) {
        dm::CheckOptions co;
        co.delaunay = false;
        co.convex_hull = false;
        co.pslg = &nodes;
        res.stats.segment_check = dm::check(res.mesh, co);
      }
      dm::DomainOptions dopt;
      dopt.ignore_holes = o.ignore_holes;
      dopt.regional_attributes = o.regional_attributes;
      dm::Pslg seeds;
      seeds.holes = in.pslg.holes;
      seeds.regions = in.pslg.regions;
      dm::carve_mesh(res.mesh, seeds, dopt, &res.stats.domain);
      if (res.stats.domain.triangles_removed) dm::finish_vertex_markers(res.mesh);
      // The command line's warnings for -r -p (region points ignored, mesh emptied too).
      for (std::string& w : dm::domain_warnings(res.stats.domain, res.mesh.num_triangles(), true))
        res.stats.warnings.push_back(std::move(w));
    }
    if (o.convex_hull)
      for (dm::HalfEdgeId e = 0; e < res.mesh.triangle_vertices().size(); ++e)
        if (res.mesh.twin(e) == dm::kNone && !res.mesh.is_constrained(e)) res.mesh.constrain_edge(e, 0);
    if (ropt) {
      dm::make_constrained_delaunay(res.mesh);
      res.stats.refine = dm::refine(res.mesh, *ropt);
      dm::finish_vertex_markers(res.mesh);
      res.refined = true;
    }
  } else {
    dm::TriangulateOptions topt;
    topt.use_segments = o.poly;
    topt.method = o.cdt_method;
    topt.strict = o.strict;
    topt.domain.fill = o.fill;
    topt.domain.keep_convex_hull = o.convex_hull;
    topt.domain.ignore_holes = o.ignore_holes;
    topt.domain.regional_attributes = o.regional_attributes && o.poly;
    topt.domain.regional_area_bounds = o.area_from_regions && o.poly;
    topt.check_segments = o.check && o.poly;
    if (ropt) topt.refine = *ropt;
    res.mesh = dm::triangulate(in.pslg, topt, &res.stats);
    res.refined = ropt != nullptr;
  }
  if (o.jettison) res.mesh.remove_unused_vertices();
  if (o.check) {
    dm::CheckOptions copt;
    copt.convex_hull = !o.poly && !o.refine && !res.refined;
    copt.delaunay = o.refine ? res.refined : o.cdt_method != dm::CdtMethod::Ct;
    dm::CheckReport report = dm::check(res.mesh, copt);
    for (const std::string& p : res.stats.segment_check.problems) report.problems.push_back("before carving: " + p);
    if (o.poly && !o.refine)
      for (const std::string& p : dm::check_domain_boundary(res.mesh)) report.problems.push_back(p);
    res.check_summary = report.summary();
    res.check_problems = report.problems;
  }
  if (o.order == 2) res.midside = dm::add_midpoint_nodes(res.mesh);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The result dict, Triangle's keys and layout (markers as (n, 1) int32).
py::dict mesh_dict(const dm::Mesh& mesh, const Options& o, const Input& in, const RunResult& res) {
  py::dict out;
  const std::size_t nv = mesh.num_vertices();
  std::vector<double> xy(2 * nv);
  for (std::size_t i = 0; i < nv; ++i) {
    xy[2 * i] = mesh.point(static_cast<dm::VertexId>(i)).x;
    xy[2 * i + 1] = mesh.point(static_cast<dm::VertexId>(i)).y;
  }
  out["vertices"] = array_2d(xy, 2);
  if (!o.no_markers) {
    std::vector<std::int32_t> vm(nv, 0);
    const auto& mk = mesh.vertex_markers();
    for (std::size_t i = 0; i < std::min(nv, mk.size()); ++i) vm[i] = mk[i];
    out["vertex_markers"] = array_2d(vm, 1);
  }
  if (mesh.num_vertex_attributes() > 0) {
    std::vector<double> va(mesh.vertex_attributes().begin(), mesh.vertex_attributes().end());
    va.resize(nv * mesh.num_vertex_attributes(), 0.0);
    out["vertex_attributes"] = array_2d(va, mesh.num_vertex_attributes());
  }

  // Triangles in slot order (the mesh is compacted: every slot is real).
  const std::size_t slots = mesh.num_triangle_slots();
  std::vector<dm::TriId> index(slots, dm::kNone);
  std::size_t nt = 0;
  for (dm::TriId t = 0; t < slots; ++t)
    if (mesh.is_real(t)) index[t] = static_cast<dm::TriId>(nt++);
  const std::size_t corners = res.midside.empty() ? 3 : 6;
  const std::size_t na = mesh.num_triangle_attributes();
  std::vector<std::int32_t> tris;
  std::vector<double> tattr;
  std::vector<std::int32_t> neigh;
  tris.reserve(corners * nt);
  for (dm::TriId t = 0; t < slots; ++t) {
    if (index[t] == dm::kNone) continue;
    for (const dm::VertexId v : mesh.triangle(t)) tris.push_back(static_cast<std::int32_t>(v));
    if (corners == 6)
      for (std::size_t k = 0; k < 3; ++k)
        tris.push_back(static_cast<std::int32_t>(res.midside[3 * std::size_t{t} + k]));
    for (std::size_t k = 0; k < na; ++k) tattr.push_back(mesh.triangle_attributes()[t * na + k]);
    if (o.neighbors)
      for (dm::HalfEdgeId i = 0; i < 3; ++i) {
        // Neighbour i is opposite vertex i, across half-edge 3t + (i+1)%3.
        const dm::HalfEdgeId tw = real_twin(mesh, 3 * t + (i + 1) % 3);
        neigh.push_back(tw == dm::kNone ? -1 : static_cast<std::int32_t>(index[dm::tri_of(tw)]));
      }
  }
  out["triangles"] = array_2d(tris, corners);
  if (na > 0) out["triangle_attributes"] = array_2d(tattr, na);
  if (o.neighbors) out["neighbors"] = array_2d(neigh, 3);

  // Edges once each; segments are the constrained ones.
  const bool want_segments = o.poly || o.convex_hull;
  std::vector<std::int32_t> seg, seg_mk, edges, edge_mk;
  for (dm::TriId t = 0; t < slots; ++t) {
    if (index[t] == dm::kNone) continue;
    for (dm::HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const dm::HalfEdgeId tw = real_twin(mesh, e);
      if (tw != dm::kNone && tw < e) continue;
      const std::int32_t a = static_cast<std::int32_t>(mesh.origin(e)), b = static_cast<std::int32_t>(mesh.dest(e));
      const int marker = edge_marker(mesh, e, tw);
      if (o.edges) {
        edges.insert(edges.end(), {a, b});
        edge_mk.push_back(marker);
      }
      if (want_segments && (mesh.is_constrained(e) || (tw != dm::kNone && mesh.is_constrained(tw)))) {
        seg.insert(seg.end(), {a, b});
        seg_mk.push_back(marker);
      }
    }
  }
  if (want_segments) {
    out["segments"] = array_2d(seg, 2);
    if (!o.no_markers) out["segment_markers"] = array_2d(seg_mk, 1);
  }
  if (o.edges) {
    out["edges"] = array_2d(edges, 2);
    if (!o.no_markers) out["edge_markers"] = array_2d(edge_mk, 1);
  }
  if (o.poly && !in.pslg.holes.empty()) {
    std::vector<double> h;
    for (const dm::Point& p : in.pslg.holes) h.insert(h.end(), {p.x, p.y});
    out["holes"] = array_2d(h, 2);
  }
  if (o.poly && !in.pslg.regions.empty()) {
    std::vector<double> r;
    for (const dm::RegionSeed& s : in.pslg.regions) r.insert(r.end(), {s.p.x, s.p.y, s.attribute, s.max_area});
    out["regions"] = array_2d(r, 4);
  }
  return out;
}

// The smallest and largest angle of the mesh in degrees. quality_report()
// computes far more and costs as much as a Delaunay triangulation, so this
// ranks triangles by a monotone proxy and takes atan2 for the two winners
// only: the smallest angle sits between the two longer edges b, c and is
// at most 60 degrees, where cross^2 / (b^2 c^2) = sin^2 grows with the angle;
// the largest sits between the two shorter edges, where the signed square of
// dot / (|b| |c|) = cos falls as the angle grows.
std::pair<double, double> extreme_angles(const dm::Mesh& mesh) {
  double best_min = 2.0, best_max = 2.0;
  double min_deg = 0.0, max_deg = 0.0;
  const std::size_t slots = mesh.num_triangle_slots();
  auto angle_at = [&](const dm::Point& apex, const dm::Point& p, const dm::Point& q) {
    const double ux = p.x - apex.x, uy = p.y - apex.y, vx = q.x - apex.x, vy = q.y - apex.y;
    return std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * (180.0 / 3.14159265358979323846);
  };
  for (dm::TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    const auto v = mesh.triangle(t);
    const dm::Point* p[3] = {&mesh.point(v[0]), &mesh.point(v[1]), &mesh.point(v[2])};
    double len2[3];  // len2[k]: edge opposite corner k
    for (int k = 0; k < 3; ++k) {
      const dm::Point& a = *p[(k + 1) % 3];
      const dm::Point& b = *p[(k + 2) % 3];
      len2[k] = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
    }
    const int shortest = len2[0] <= len2[1] ? (len2[0] <= len2[2] ? 0 : 2) : (len2[1] <= len2[2] ? 1 : 2);
    const int longest = len2[0] >= len2[1] ? (len2[0] >= len2[2] ? 0 : 2) : (len2[1] >= len2[2] ? 1 : 2);
    const double ux = p[1]->x - p[0]->x, uy = p[1]->y - p[0]->y, wx = p[2]->x - p[0]->x, wy = p[2]->y - p[0]->y;
    const double cross = ux * wy - uy * wx;
    auto corner_terms = [&](int k, double& bc2, double& dot) {
      const dm::Point& a = *p[k];
      const dm::Point& b = *p[(k + 1) % 3];
      const dm::Point& c = *p[(k + 2) % 3];
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

py::dict stats_dict(const dm::Mesh& mesh, const Options& o, const RunResult& res) {
  const dm::TriangulateStats& s = res.stats;
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
  d["check"] = o.check ? py::object(py::str(res.check_summary)) : py::object(py::none());
  d["seconds"] = res.seconds;
  return d;
}

py::dict run(Input in, const Options& o, py::object max_area_fn, py::object max_edge_fn) {
  SizeCallback area{std::move(max_area_fn), "max_area_fn", {}, {}};
  SizeCallback edge{std::move(max_edge_fn), "max_edge_fn", {}, {}};
  if (o.refine && !in.has_triangles)
    throw py::value_error("switch -r refines a mesh: the input needs 'triangles' (and 'vertices')");
  if (o.refine && o.area_from_regions && in.triangle_max_area.empty())
    throw py::value_error(
        "switches -r with -a and no number read per-triangle bounds: the input needs 'triangle_max_area'");
  std::optional<dm::RefineOptions> ropt;
  if (wants_refinement(o, given(area.fn) || given(edge.fn))) {
    ropt = dm::cli::refine_options(o);
    ropt->max_area_at = area.make();
    ropt->max_edge_at = edge.make();
  }
  RunResult res;
  {
    py::gil_scoped_release nogil;
    run_pipeline(in, o, ropt ? &*ropt : nullptr, res);
  }
  area.rethrow();
  edge.rethrow();
  if (!res.check_problems.empty()) {
    py::list problems;
    for (const std::string& p : res.check_problems) problems.append(p);
    raise_with(g_exc.check, "-C: " + res.check_summary, {{"problems", problems}});
    throw py::error_already_set();
  }
  py::dict out = mesh_dict(res.mesh, o, in, res);
  py::dict stats = stats_dict(res.mesh, o, res);
  out["stats"] = stats;
  if (!o.quiet) {
    for (const std::string& w : res.stats.warnings)
      if (PyErr_WarnEx(PyExc_UserWarning, ("deltamesh: " + w).c_str(), 2) < 0) throw py::error_already_set();
    if (res.refined && !res.stats.refine.complete) {
      const std::string msg =
          "deltamesh: refinement stopped before the requested quality: " + res.stats.refine.summary();
      if (PyErr_WarnEx(PyExc_UserWarning, msg.c_str(), 2) < 0) throw py::error_already_set();
    }
  }
  if (o.verbose) {
    py::print("deltamesh:", res.mesh.num_vertices(), "vertices,", res.mesh.num_triangles(), "triangles in",
              res.seconds * 1e3, "ms", py::arg("file") = py::module_::import("sys").attr("stderr"));
    if (res.refined)
      py::print("deltamesh: refine:", res.stats.refine.summary(),
                py::arg("file") = py::module_::import("sys").attr("stderr"));
  }
  return out;
}

// ---------------------------------------------------------------------------
// Python entry points

py::dict triangulate_dict(const py::dict& tri, const std::string& opts, py::object max_area_fn,
                          py::object max_edge_fn) {
  const Options o = parse_switches(opts);
  return run(read_input(arrays_from_dict(tri)), o, std::move(max_area_fn), std::move(max_edge_fn));
}

// adapt(mesh, size, opts): the mesh rebuilt as for 'r' (with 'p' when it has
// segments), then coarsened and refined to the size field (and smoothed).
py::dict adapt_dict(const py::dict& tri, py::object size, const std::string& opts, int smooth) {
  Input in = read_input(arrays_from_dict(tri));
  if (!in.has_triangles) throw py::value_error("adapt: the mesh needs 'triangles' (and 'vertices')");
  Options o = parse_switches(opts);
  if (o.refine || o.order == 2 || o.conforming_delaunay)
    throw py::value_error("adapt: switches r, o2 and D do not apply (the mesh is always rebuilt and refined)");
  if (smooth < 0) throw py::value_error("adapt: smooth must be >= 0 passes");
  o.refine = true;
  o.poly = o.poly || in.has_segments;
  const bool check = o.check;
  o.check = false;
  // The size field: a function of (x, y), or one size per given vertex.
  SizeCallback fn{py::none(), "size", {}, {}};
  std::vector<double> sizes;
  if (PyCallable_Check(size.ptr())) {
    fn.fn = size;
  } else {
    const Doubles d = to_doubles(size, "size", 1);
    if (d.rows != in.pslg.points.size())
      throw py::value_error("size: has " + std::to_string(d.rows) + " values, expected one per vertex (" +
                            std::to_string(in.pslg.points.size()) + ")");
    sizes = d.v;
  }
  dm::AdaptOptions aopt;
  aopt.refine = dm::cli::refine_options(o);
  aopt.smooth_passes = smooth;
  RunResult res;
  dm::AdaptStats st;
  std::string size_error;
  {
    py::gil_scoped_release nogil;
    run_pipeline(in, o, nullptr, res);
    dm::SizeField h = fn.make();
    if (!h) {
      if (res.mesh.num_vertices() != sizes.size())
        size_error = "size: per-vertex sizes need the mesh's segments to be edges of its triangles already (" +
                     std::to_string(res.mesh.num_vertices() - sizes.size()) + " vertices were added inserting them)";
      else
        h = dm::size_field_from_vertices(res.mesh, sizes);
    }
    if (h) {
      dm::make_constrained_delaunay(res.mesh);
      st = dm::adapt(res.mesh, h, aopt);
      dm::finish_vertex_markers(res.mesh);
    }
  }
  fn.rethrow();
  if (!size_error.empty()) throw py::value_error(size_error);
  res.stats.refine = st.refine;
  res.refined = true;
  if (check) {
    dm::CheckOptions co;
    co.convex_hull = false;
    const dm::CheckReport report = dm::check(res.mesh, co);
    res.check_summary = report.summary();
    if (!report.ok()) {
      py::list problems;
      for (const std::string& p : report.problems) problems.append(p);
      raise_with(g_exc.check, "-C: " + res.check_summary, {{"problems", problems}});
      throw py::error_already_set();
    }
  }
  o.check = check;
  py::dict out = mesh_dict(res.mesh, o, in, res);
  py::dict stats = stats_dict(res.mesh, o, res);
  py::dict a;
  a["removed"] = st.removed;
  a["inserted"] = st.inserted;
  a["smoothed"] = st.smooth.moved;
  a["resplit"] = st.resplit;
  a["triangles"] = st.triangles;
  a["complete"] = st.complete;
  a["seconds"] = st.seconds;
  a["summary"] = st.summary();
  stats["adapt"] = a;
  out["stats"] = stats;
  if (!o.quiet && !st.complete) {
    const std::string msg = "deltamesh: adaptation stopped before the requested quality: " + st.refine.summary();
    if (PyErr_WarnEx(PyExc_UserWarning, msg.c_str(), 2) < 0) throw py::error_already_set();
  }
  return out;
}

py::dict triangulate_kw(py::object vertices, py::object segments, py::object holes, py::object regions,
                        py::object vertex_markers, py::object vertex_attributes, py::object segment_markers,
                        py::object triangles, py::object triangle_attributes, py::object triangle_max_area,
                        py::object min_angle, py::object max_area, bool regional_area, py::object max_steiner,
                        py::object max_area_fn, py::object max_edge_fn, bool conforming_delaunay,
                        const std::string& segment_splitting, bool convex_hull, bool regional_attributes,
                        bool ignore_holes, const std::string& fill, const std::string& cdt, bool strict,
                        const std::string& steiner, const std::string& encroachment, const std::string& order,
                        py::object time_limit, bool jettison, bool second_order, bool edges, bool neighbors, bool check,
                        bool markers, bool quiet) {
  if (py::isinstance<py::dict>(vertices))
    throw py::value_error("vertices: got a dict; for Triangle's form call triangulate(dict, 'switches')");
  KeywordOptions k;
  k.flag("segments", given(segments) || given(triangles), "--poly");
  k.flag("triangles", given(triangles), "--refine");
  k.value("min_angle", min_angle, "--min-angle");
  k.value("max_area", max_area, "--max-area");
  k.flag("regional_area", regional_area, "--regional-area");
  k.value("max_steiner", max_steiner, "--steiner-budget");
  k.flag("conforming_delaunay", conforming_delaunay, "--conforming-delaunay");
  if (segment_splitting == "interior" || segment_splitting == "none")
    k.flag("segment_splitting", true, "--no-boundary-steiner");
  if (segment_splitting == "none") k.flag("segment_splitting", true, "--no-boundary-steiner");
  if (segment_splitting != "all" && segment_splitting != "interior" && segment_splitting != "none")
    throw py::value_error("segment_splitting: '" + segment_splitting +
                          "' must be 'all', 'interior' (Triangle's -Y) or 'none' (-YY)");
  k.flag("convex_hull", convex_hull, "--convex-hull");
  k.flag("regional_attributes", regional_attributes, "--regional-attributes");
  k.flag("ignore_holes", ignore_holes, "--ignore-holes");
  k.value("fill", py::str(fill), "--fill");
  k.value("cdt", py::str(cdt), "--cdt");
  k.flag("strict", strict, "--strict");
  k.value("steiner", py::str(steiner), "--steiner");
  k.value("encroachment", py::str(encroachment), "--encroachment");
  k.value("order", py::str(order), "--order");
  k.value("time_limit", time_limit, "--time-limit");
  k.flag("jettison", jettison, "--jettison");
  k.flag("second_order", second_order, "--second-order");
  k.flag("edges", edges, "--edges");
  k.flag("neighbors", neighbors, "--neighbors");
  k.flag("check", check, "--check");
  k.flag("markers", !markers, "--no-markers");
  k.flag("quiet", quiet, "--quiet");
  const Options o = k.parse();
  const InputArrays a{vertices, vertex_markers, vertex_attributes,   segments,         segment_markers, holes,
                      regions,  triangles,      triangle_attributes, triangle_max_area};
  return run(read_input(a), o, std::move(max_area_fn), std::move(max_edge_fn));
}

// A mesh rebuilt from arrays (vertices, triangles, optional markers,
// attributes and segments), for check(), quality() and write().
struct Rebuilt {
  dm::Pslg nodes;
  dm::Mesh mesh;
  dm::InsertSegmentsStats inserted;
  std::vector<std::string> orientation_problems;
};

Rebuilt rebuild(const py::dict& tri, bool with_segments) {
  InputArrays a = arrays_from_dict(tri);
  if (!given(a.triangles)) throw py::value_error("triangles: required (an (m, 3) array of 0-based vertex indices)");
  if (!with_segments) a.segments = a.segment_markers = py::handle();
  Input in = read_input(a);
  Rebuilt r;
  r.nodes = std::move(in.pslg);
  for (std::size_t t = 0; 3 * t < in.triangles.size(); ++t) {
    const dm::Point& p = r.nodes.points[in.triangles[3 * t]];
    const dm::Point& q = r.nodes.points[in.triangles[3 * t + 1]];
    const dm::Point& s = r.nodes.points[in.triangles[3 * t + 2]];
    const double o = dm::orient2d(p, q, s);
    if (o <= 0 && r.orientation_problems.size() < 20)
      r.orientation_problems.push_back("triangle " + std::to_string(t) + " (" + std::to_string(in.triangles[3 * t]) +
                                       ", " + std::to_string(in.triangles[3 * t + 1]) + ", " +
                                       std::to_string(in.triangles[3 * t + 2]) +
                                       (o < 0 ? ") is clockwise" : ") is degenerate"));
  }
  if (!in.midside.empty()) dm::drop_midpoint_nodes(r.nodes, in.triangles, in.midside);
  py::gil_scoped_release nogil;
  r.mesh = dm::mesh_from_triangles(r.nodes, in.triangles, in.num_triangle_attributes, in.triangle_attributes, {},
                                   &r.inserted);
  return r;
}

py::dict check_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments) {
  Rebuilt r;
  std::vector<std::string> problems;
  try {
    r = rebuild(tri, segments);
  } catch (const dm::InputError& e) {
    problems.push_back(std::string("not a triangulation: ") + e.what());
  }
  problems.insert(problems.begin(), r.orientation_problems.begin(), r.orientation_problems.end());
  dm::CheckReport rep;
  if (problems.empty()) {
    if (r.inserted.inserted || r.inserted.vertices_added)
      problems.push_back(std::to_string(r.inserted.inserted) +
                         " segment(s) are not edges or chains of edges of the triangles");
    dm::CheckOptions co;
    co.delaunay = delaunay;
    co.convex_hull = convex_hull;
    if (segments && !r.nodes.segments.empty()) co.pslg = &r.nodes;
    {
      py::gil_scoped_release nogil;
      rep = dm::check(r.mesh, co);
    }
    problems.insert(problems.end(), rep.problems.begin(), rep.problems.end());
  }
  py::dict d;
  d["ok"] = problems.empty();
  py::list pl;
  for (const std::string& p : problems) pl.append(p);
  d["problems"] = pl;
  d["triangles"] = rep.triangles;
  d["edges"] = rep.edges;
  d["vertices_used"] = rep.vertices_used;
  d["segments_checked"] = rep.segments_checked;
  d["summary"] =
      problems.empty() ? rep.summary() : std::to_string(problems.size()) + " problem(s): " + problems.front();
  return d;
}

py::dict validate_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments) {
  py::dict d = check_dict(tri, delaunay, convex_hull, segments);
  if (!d["ok"].cast<bool>()) {
    raise_with(g_exc.check, "invalid mesh: " + d["summary"].cast<std::string>(), {{"problems", d["problems"]}});
    throw py::error_already_set();
  }
  return d;
}

py::dict quality_dict(const py::dict& tri, double min_angle, double max_area) {
  Rebuilt r = rebuild(tri, false);
  dm::QualityOptions q;
  q.min_angle_deg = min_angle;
  q.max_area = max_area;
  const dm::QualityReport qr = dm::quality_report(r.mesh, q);
  py::dict d;
  d["triangles"] = qr.triangles;
  d["vertices"] = qr.vertices;
  d["min_angle"] = qr.min_angle_deg;
  d["max_angle"] = qr.max_angle_deg;
  d["min_area"] = qr.min_area;
  d["max_area"] = qr.max_area;
  d["shortest_edge"] = qr.shortest_edge;
  d["longest_edge"] = qr.longest_edge;
  d["max_aspect_ratio"] = qr.max_aspect_ratio;
  d["max_radius_edge"] = qr.max_radius_edge;
  py::list hist;
  for (const std::size_t c : qr.angle_histogram) hist.append(c);
  d["angle_histogram"] = hist;
  d["below_angle"] = qr.below_angle;
  d["above_area"] = qr.above_area;
  return d;
}

py::dict pslg_dict(const dm::Pslg& p) {
  py::dict d;
  std::vector<double> xy;
  for (const dm::Point& q : p.points) xy.insert(xy.end(), {q.x, q.y});
  d["vertices"] = array_2d(xy, 2);
  if (!p.point_markers.empty())
    d["vertex_markers"] = array_2d(std::vector<std::int32_t>(p.point_markers.begin(), p.point_markers.end()), 1);
  if (p.num_point_attributes) d["vertex_attributes"] = array_2d(p.point_attributes, p.num_point_attributes);
  if (!p.segments.empty()) {
    std::vector<std::int32_t> s, m;
    for (const dm::Segment& g : p.segments) {
      s.insert(s.end(), {static_cast<std::int32_t>(g.a), static_cast<std::int32_t>(g.b)});
      m.push_back(g.marker);
    }
    d["segments"] = array_2d(s, 2);
    d["segment_markers"] = array_2d(m, 1);
  }
  if (!p.holes.empty()) {
    std::vector<double> h;
    for (const dm::Point& q : p.holes) h.insert(h.end(), {q.x, q.y});
    d["holes"] = array_2d(h, 2);
  }
  if (!p.regions.empty()) {
    std::vector<double> r;
    for (const dm::RegionSeed& s : p.regions) r.insert(r.end(), {s.p.x, s.p.y, s.attribute, s.max_area});
    d["regions"] = array_2d(r, 4);
  }
  return d;
}

py::dict read_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::string base = path;
  for (const char* ext : {".node", ".ele", ".poly"})
    if (ends_with(path, ext)) base = path.substr(0, path.size() - std::string(ext).size());
  if (ends_with(path, ".geojson") || ends_with(path, ".json")) {
    dm::Pslg p;
    {
      py::gil_scoped_release nogil;
      p = dm::read_geojson(path);
    }
    return pslg_dict(p);
  }
  if (ends_with(path, ".poly")) {
    dm::Pslg p;
    {
      py::gil_scoped_release nogil;
      p = dm::read_poly(path);
    }
    return pslg_dict(p);
  }
  // FILE.node (or FILE.ele, or FILE): the vertices, with FILE.ele's
  // triangles and FILE.poly's segments, holes and regions when present.
  const std::string node = base + ".node", ele = base + ".ele", poly = base + ".poly";
  if (!fs::exists(node)) {
    if (base == path && fs::exists(poly)) return read_file(poly);
    throw dm::IoError("cannot open '" + node + "'" +
                      (base == path ? " (read takes FILE.node, FILE.poly, FILE.ele, FILE or FILE.geojson)" : ""));
  }
  dm::Pslg p;
  dm::EleData e;
  bool has_ele = fs::exists(ele), has_poly = fs::exists(poly);
  {
    py::gil_scoped_release nogil;
    p = dm::read_node(node);
    if (has_poly) {
      dm::Pslg q = dm::read_poly(poly);
      if (q.points.size() != p.points.size())
        throw dm::InputError(poly + " lists " + std::to_string(q.points.size()) + " vertices but " + node + " has " +
                             std::to_string(p.points.size()));
      p.segments = std::move(q.segments);
      p.holes = std::move(q.holes);
      p.regions = std::move(q.regions);
    }
    if (has_ele) e = dm::read_ele(ele, p.first_index);
  }
  py::dict d = pslg_dict(p);
  if (has_ele) {
    const std::size_t nt = e.triangles.size() / 3;
    std::vector<std::int32_t> t;
    for (std::size_t i = 0; i < nt; ++i) {
      for (std::size_t k = 0; k < 3; ++k) t.push_back(static_cast<std::int32_t>(e.triangles[3 * i + k]));
      if (!e.midside.empty())
        for (std::size_t k = 0; k < 3; ++k) t.push_back(static_cast<std::int32_t>(e.midside[3 * i + k]));
    }
    d["triangles"] = array_2d(t, e.midside.empty() ? 3 : 6);
    if (e.num_attributes) d["triangle_attributes"] = array_2d(e.attributes, e.num_attributes);
  }
  return d;
}

void write_file(const py::dict& tri, const std::string& path, int first_index, bool markers) {
  if (first_index != 0 && first_index != 1) throw py::value_error("first_index: must be 0 or 1");
  if (!dm::output_format_for(path)) throw py::value_error(dm::UnknownOutputFormat(path).what());
  Rebuilt r = rebuild(tri, true);
  // Inserting a segment changes the triangles: the file would not hold the mesh given.
  if (r.inserted.inserted || r.inserted.vertices_added)
    throw py::value_error("segments: " + std::to_string(r.inserted.inserted) +
                          " segment(s) not an edge or a chain of edges of the triangles (deltamesh.check() "
                          "lists the problems); mesh them in with triangulate(mesh, 'rp') first");
  py::gil_scoped_release nogil;
  if (*dm::output_format_for(path) == dm::OutputFormat::Poly) {
    dm::TriangleWriteOptions w;
    w.first_index = first_index;
    w.write_markers = markers;
    w.holes = r.nodes.holes;
    w.regions = r.nodes.regions;
    dm::write_poly(r.mesh, path, w);
    return;
  }
  dm::OutputOptions oo;
  oo.first_index = first_index;
  oo.write_markers = markers;
  dm::write_output(r.mesh, path, oo);
}

// The Delaunay triangulation of points (no segments), for delaunay(),
// convex_hull() and voronoi().
dm::Mesh delaunay_mesh(py::handle vertices) {
  InputArrays a{};
  a.vertices = vertices;
  Input in = read_input(a);
  dm::TriangulateOptions topt;
  topt.use_segments = false;
  py::gil_scoped_release nogil;
  return dm::triangulate(in.pslg, topt);
}

py::array_t<std::int32_t> delaunay_triangles(py::handle vertices) {
  const dm::Mesh mesh = delaunay_mesh(vertices);
  std::vector<std::int32_t> t;
  for (dm::TriId i = 0; i < mesh.num_triangle_slots(); ++i)
    if (mesh.is_real(i))
      for (const dm::VertexId v : mesh.triangle(i)) t.push_back(static_cast<std::int32_t>(v));
  return array_2d(t, 3);
}

py::array_t<std::int32_t> hull_segments(py::handle vertices) {
  const dm::Mesh mesh = delaunay_mesh(vertices);
  std::vector<std::int32_t> s;
  for (dm::HalfEdgeId e = 0; e < mesh.triangle_vertices().size(); ++e)
    if (mesh.is_real(dm::tri_of(e)) && real_twin(mesh, e) == dm::kNone)
      s.insert(s.end(), {static_cast<std::int32_t>(mesh.origin(e)), static_cast<std::int32_t>(mesh.dest(e))});
  return array_2d(s, 2);
}

py::dict voronoi_dict(py::handle vertices) {
  const dm::Mesh mesh = delaunay_mesh(vertices);
  dm::VoronoiDiagram vd;
  {
    py::gil_scoped_release nogil;
    vd = dm::voronoi_diagram(mesh);
  }
  std::vector<double> xy, dir;
  std::vector<std::int32_t> edges;
  for (const dm::Point& p : vd.vertices) xy.insert(xy.end(), {p.x, p.y});
  for (const auto& e : vd.edges) {
    edges.insert(edges.end(), {static_cast<std::int32_t>(e.a), e.is_ray() ? -1 : static_cast<std::int32_t>(e.b)});
    dir.insert(dir.end(), {e.is_ray() ? e.direction.x : 0.0, e.is_ray() ? e.direction.y : 0.0});
  }
  py::dict d;
  d["vertices"] = array_2d(xy, 2);
  d["edges"] = array_2d(edges, 2);
  d["ray_directions"] = array_2d(dir, 2);
  return d;
}

}  // namespace

PYBIND11_MODULE(deltamesh, m) {
  m.doc() = R"(deltamesh: 2-D constrained Delaunay triangulation and quality meshing.

triangulate(dict, 'pq30a0.1') takes and returns Triangle's dict of numpy
arrays (the `triangle` package's layout); triangulate(vertices, segments=...,
min_angle=...) is the keyword form. check()/validate() run the library's
exact validator on arrays, quality() reports angles and sizes, read()/write()
handle Triangle's files and the other formats. See docs/python.md.)";
  m.attr("__version__") = dm::kVersion;

  g_exc.error = new_exception(m, "Error", {PyExc_Exception}, "Base of the errors deltamesh raises on purpose.");
  g_exc.input = new_exception(m, "InputError", {g_exc.error, PyExc_ValueError},
                              "Input that cannot be meshed (attribute `index`: the offending item, or None).");
  g_exc.parse = new_exception(m, "ParseError", {g_exc.input}, "A malformed input file (attributes `file`, `line`).");
  g_exc.intersecting = new_exception(m, "IntersectingSegments", {g_exc.input},
                                     "Two segments cross under --strict (attributes `first`, `second`).");
  g_exc.segment = new_exception(m, "SegmentError", {g_exc.input},
                                "A segment that cannot be inserted into a mesh (attribute `segment`).");
  g_exc.io = new_exception(m, "IoError", {g_exc.error, PyExc_OSError}, "An output file could not be written.");
  g_exc.check = new_exception(m, "CheckError", {g_exc.error},
                              "The validator found the mesh invalid (attribute `problems`: a list of str).");
  py::register_exception_translator(&translate_exception);

  m.def("triangulate", &triangulate_dict, py::arg("tri"), py::arg("opts") = "", py::kw_only(),
        py::arg("max_area_fn") = py::none(), py::arg("max_edge_fn") = py::none(),
        R"(Triangle's form: triangulate(tri: dict, opts: str = '') -> dict.

tri holds numpy arrays (or lists): vertices (n, 2) float, and optionally
vertex_markers (n,) or (n, 1), vertex_attributes (n, k), segments (s, 2) int
(0-based), segment_markers, holes (h, 2), regions (r, 4): x, y, attribute,
maximum area; for 'r' also triangles (m, 3), triangle_attributes,
triangle_max_area. opts is Triangle's switch string, e.g. 'pq30a0.1'
(p: use segments/holes, q[angle], a[area], c, A, O, D, Y, S[n], j, e, n, o2,
r, C, Q, V, B; long options such as '--cdt=lawson' may follow after a
space). Unknown switches raise ValueError.

Returns a dict: vertices (N, 2) float64, vertex_markers (N, 1) int32,
triangles (M, 3) int32 (M, 6 with o2), triangle_attributes (M, k) with A,
segments/segment_markers with p or c, edges/edge_markers with e, neighbors
(M, 3) with n (-1: none), holes/regions with p, and stats (a dict:
complete, steiner_points, min_angle, refine details, warnings...).)");

  m.def("triangulate", &triangulate_kw, py::arg("vertices"), py::arg("segments") = py::none(),
        py::arg("holes") = py::none(), py::arg("regions") = py::none(), py::kw_only(),
        py::arg("vertex_markers") = py::none(), py::arg("vertex_attributes") = py::none(),
        py::arg("segment_markers") = py::none(), py::arg("triangles") = py::none(),
        py::arg("triangle_attributes") = py::none(), py::arg("triangle_max_area") = py::none(),
        py::arg("min_angle") = py::none(), py::arg("max_area") = py::none(), py::arg("regional_area") = false,
        py::arg("max_steiner") = py::none(), py::arg("max_area_fn") = py::none(), py::arg("max_edge_fn") = py::none(),
        py::arg("conforming_delaunay") = false, py::arg("segment_splitting") = "all", py::arg("convex_hull") = false,
        py::arg("regional_attributes") = false, py::arg("ignore_holes") = false, py::arg("fill") = "holes",
        py::arg("cdt") = "fast", py::arg("strict") = false, py::arg("steiner") = "best",
        py::arg("encroachment") = "lens", py::arg("order") = "shortest", py::arg("time_limit") = py::none(),
        py::arg("jettison") = false, py::arg("second_order") = false, py::arg("edges") = false,
        py::arg("neighbors") = false, py::arg("check") = false, py::arg("markers") = true, py::arg("quiet") = false,
        R"(Keyword form: triangulate(vertices, segments=None, holes=None, regions=None, *, ...) -> dict.

Same result as Triangle's form. Segments (or triangles) switch on 'p'
(constrained triangulation of the domain; without them: Delaunay of the
points). min_angle=30 is 'q30', max_area=0.1 'a0.1', regional_area=True 'a',
max_steiner 'S', conforming_delaunay 'D', segment_splitting='interior'|'none'
'Y'|'YY', convex_hull 'c', regional_attributes 'A', ignore_holes 'O',
jettison 'j', second_order 'o2', edges 'e', neighbors 'n', check 'C',
markers=False 'B', quiet 'Q'; triangles=... is 'r'. fill, cdt, steiner,
encroachment, order, time_limit are the command line's long options.
max_area_fn(x, y) / max_edge_fn(x, y): size functions evaluated at triangle
centroids (<= 0: no bound there); they refine like max_area.)");

  m.def("adapt", &adapt_dict, py::arg("mesh"), py::arg("size"), py::arg("opts") = "q", py::kw_only(),
        py::arg("smooth") = 2,
        R"(adapt(mesh: dict, size, opts: str = 'q', *, smooth: int = 2) -> dict.

Mesh adaptation (docs/adapt.md): coarsens where the mesh is finer than the
target edge length and refines where it is coarser, then smooths `smooth`
passes. mesh is a result of triangulate() (or the same keys: vertices,
triangles, and optionally segments, markers, attributes, holes); size is a
function h(x, y) -> target edge length (<= 0: no target there) or an array
of one size per vertex (interpolated linearly over the mesh, as a TetGen
.mtr file). opts: refinement switches as for triangulate ('q30', 'a0.01',
'S1000', 'C'...). The result has triangulate()'s keys; stats['adapt'] holds
removed, inserted, smoothed, triangles, complete.)");
  m.def("delaunay", &delaunay_triangles, py::arg("vertices"),
        "Delaunay triangulation of points: the (M, 3) int32 triangles (counter-clockwise) of triangulate({'vertices': "
        "v}).");
  m.def("convex_hull", &hull_segments, py::arg("vertices"),
        "Convex hull edges of points as (H, 2) int32 vertex pairs, counter-clockwise around the hull (points on "
        "a hull edge split it).");
  m.def("voronoi", &voronoi_dict, py::arg("vertices"),
        R"(Voronoi diagram of points (the dual of their Delaunay triangulation):
vertices (V, 2) float64, one circumcentre per Delaunay triangle (in
delaunay()'s order); edges (E, 2) int32, one per Delaunay edge, the second
end -1 for an infinite ray; ray_directions (E, 2) float64, the outward
direction of each ray (0, 0 for finite edges).)");

  m.def("check", &check_dict, py::arg("mesh"), py::kw_only(), py::arg("delaunay") = true,
        py::arg("convex_hull") = false, py::arg("segments") = true,
        R"(Runs the library's exact validator on a mesh dict (vertices, triangles and
optionally segments): counter-clockwise non-degenerate triangles, a valid
triangulation (no overlap, manifold edges), every unconstrained edge locally
Delaunay (delaunay=True; segments are constrained edges), a convex union
(convex_hull=True), every segment a chain of edges (segments=True).
Returns a dict: ok, problems (list of str), triangles, edges, vertices_used,
segments_checked, summary.)");
  m.def("validate", &validate_dict, py::arg("mesh"), py::kw_only(), py::arg("delaunay") = true,
        py::arg("convex_hull") = false, py::arg("segments") = true,
        "Like check(), but raises deltamesh.CheckError when the mesh is invalid; returns the report otherwise.");
  m.def("quality", &quality_dict, py::arg("mesh"), py::kw_only(), py::arg("min_angle") = 0.0,
        py::arg("max_area") = -1.0,
        "Quality report of a mesh dict: min/max angle (degrees), areas, edge lengths, aspect and radius-edge "
        "ratios, the angle histogram (10-degree bins), triangles below min_angle and above max_area.");
  m.def("read", &read_file, py::arg("path"),
        R"(Reads FILE.poly, FILE.node (with FILE.ele's triangles and FILE.poly's
segments, holes and regions when those files exist), FILE.ele, FILE (base
name) or FILE.geojson into a dict of arrays with 0-based indices.)");
  m.def("write", &write_file, py::arg("mesh"), py::arg("path"), py::kw_only(), py::arg("first_index") = 0,
        py::arg("markers") = true,
        R"(Writes a mesh dict (vertices, triangles, optional markers, attributes,
segments, holes, regions) to path in the format its extension names: .node
.ele .poly .edge .neigh (Triangle's, numbered from first_index), .msh .vtu
.vtk .svg .geojson .off.)");
}

// The Python module's parts (internal): numpy <-> library conversion
// (convert.cpp), switch strings and keywords -> Plan (options.cpp),
// triangulate() and adapt() over the library's pipeline (triangulate.cpp),
// the other functions (tools.cpp), the module definition (module.cpp).
#pragma once
#include "mesh/edge_rules.hpp"  // real_twin, edge_output_marker: one home with the io layer
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/deltamesh.hpp"

namespace deltamesh::python {

namespace py = pybind11;

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
  PyObject* internal = nullptr;      // deltamesh.InternalError(Error)
};
extern ExceptionTypes g_exc;  // references owned by the module (never freed: the module lives until exit)

// Raises `type(message)` with extra attributes set on the instance.
void raise_with(PyObject* type, const std::string& message,
                std::initializer_list<std::pair<const char*, py::object>> attrs = {});

// ---------------------------------------------------------------------------
// numpy arrays in (convert.cpp)

bool given(py::handle h);
// At least three points, all on one line (exact orient2d; duplicates count
// as on it): Triangle's package returns the vertices and no triangles.
bool all_collinear(const std::vector<Point>& p);
bool ends_with(const std::string& s, std::string_view suffix);
// The shortest text that reads back as x.
std::string number_text(double x);

// Floating-point rows (integers are converted); every value finite.
struct Doubles {
  std::vector<double> v;  // row-major
  std::size_t rows = 0, cols = 0;
  double at(std::size_t r, std::size_t c) const { return v[r * cols + c]; }
};
Doubles to_doubles(py::handle obj, const std::string& name, std::size_t want_cols,
                   std::size_t rows_expected = static_cast<std::size_t>(-1));

// What triangulate() meshes: the pipeline's input and which arrays were given.
struct Input {
  RunInput run;  // pslg (vertices, segments, holes, regions) and, for 'r', the triangles
  bool has_segments = false;
  bool has_triangles = false;
};

struct InputArrays {
  py::handle vertices, vertex_markers, vertex_attributes, segments, segment_markers, holes, regions, triangles,
      triangle_attributes, triangle_max_area;
};

Input read_input(const InputArrays& a);
// The arrays of a Triangle-style dict; unknown keys are a ValueError.
InputArrays arrays_from_dict(const py::dict& d);

// ---------------------------------------------------------------------------
// numpy arrays out (convert.cpp)

template <class T>
py::array_t<T> array_2d(const std::vector<T>& v, std::size_t cols) {
  const std::size_t rows = cols ? v.size() / cols : 0;
  py::array_t<T> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}


// Triangle's output switches that a Plan does not hold (they name files on
// the command line): -N, -E, -P drop arrays, -v adds the Voronoi diagram.
struct OutputSwitches {
  bool no_node = false, no_ele = false, no_poly = false, voronoi = false;
};

// An output edge: its ends, marker, and whether it is on the boundary.
struct OutEdge {
  std::int32_t a = 0, b = 0;
  int marker = 0;
  bool boundary = false;
};
// Boundary edges given counter-clockwise (interior on the left) in
// Triangle's hull order: cycle by cycle from the lowest-leftmost vertex,
// each edge reversed (the interior on its right), as convex_hull() returns.
std::vector<OutEdge> triangle_boundary_order(const Mesh& mesh, std::vector<OutEdge> ccw);

// The result dict, Triangle's keys and layout (markers as (n, 1) int32);
// `seeds` holds the input's segments (their order is kept), holes and
// regions (written back with 'p'). Arrays with no rows are left out.
py::dict mesh_dict(const RunResult& res, const Plan& plan, const Pslg& seeds, const OutputSwitches& sw = {});
// {vertices, edges (finite), ray_origins, ray_directions}: the voronoi() tuple as a dict.
py::dict voronoi_arrays(const Mesh& mesh);
// stats: counts, extreme angles, refinement, warnings, -C's summary.
py::dict stats_dict(const RunResult& res);
py::dict pslg_dict(const Pslg& p);

// ---------------------------------------------------------------------------
// Options (options.cpp)

// A Triangle switch string ("pq30a0.1", a leading '-' optional), with long
// options after whitespace, by the command line's parser. ValueError for
// anything it rejects and for switches about files.
CommandLine parse_switches(const std::string& opts);

// The keyword form of triangulate(): the plan its keywords describe.
struct Keywords {
  py::object min_angle, max_area, max_steiner, time_limit;
  bool segments = false, triangles = false, regional_area = false, conforming_delaunay = false;
  std::string segment_splitting, fill, cdt, steiner, encroachment, order;
  bool convex_hull = false, regional_attributes = false, ignore_holes = false, strict = false;
  bool jettison = false, second_order = false, edges = false, neighbors = false, check = false, markers = true,
       quiet = false;
};
Plan keyword_plan(const Keywords& k);

// ---------------------------------------------------------------------------
// Entry points (triangulate.cpp, tools.cpp)

// Both return the result dict, or (dict, stats) with stats=True.
py::object triangulate_dict(const py::dict& tri, const std::string& opts, py::object max_area_fn,
                            py::object max_edge_fn, bool stats, py::object trace, py::object threads);
py::object triangulate_kw(py::object vertices, py::object segments, py::object holes, py::object regions,
                        py::object vertex_markers, py::object vertex_attributes, py::object segment_markers,
                        py::object triangles, py::object triangle_attributes, py::object triangle_max_area,
                        py::object min_angle, py::object max_area, bool regional_area, py::object max_steiner,
                        py::object max_area_fn, py::object max_edge_fn, bool conforming_delaunay,
                        const std::string& segment_splitting, bool convex_hull, bool regional_attributes,
                        bool ignore_holes, const std::string& fill, const std::string& cdt, bool strict,
                        const std::string& steiner, const std::string& encroachment, const std::string& order,
                        py::object time_limit, bool jettison, bool second_order, bool edges, bool neighbors, bool check,
                        bool markers, bool quiet, bool stats, py::object trace, py::object threads);
// threads= of both forms: None leaves the plan's (the switches' -t, else 0).
void apply_threads(Plan& plan, const py::object& threads);
py::dict adapt_dict(const py::dict& tri, py::object size, const std::string& opts, int smooth, py::object metric);
py::dict adapt_metric_dict(const py::dict& tri, py::object metric, const std::string& opts, int smooth);  // metric.cpp
py::dict check_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments);
py::dict validate_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments);
py::dict quality_dict(const py::dict& tri, double min_angle, double max_area);
py::dict read_file(const std::string& path);
void write_file(const py::dict& tri, const std::string& path, int first_index, bool markers);
py::array_t<std::int32_t> delaunay_triangles(py::handle vertices);
py::array_t<std::int32_t> hull_segments(py::handle vertices);
py::tuple voronoi_tuple(py::handle vertices);

}  // namespace deltamesh::python

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


// The result dict, Triangle's keys and layout (markers as (n, 1) int32);
// holes and regions are the input's (written back with 'p').
py::dict mesh_dict(const RunResult& res, const Plan& plan, const Pslg& seeds);
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

py::dict triangulate_dict(const py::dict& tri, const std::string& opts, py::object max_area_fn,
                          py::object max_edge_fn);
py::dict triangulate_kw(py::object vertices, py::object segments, py::object holes, py::object regions,
                        py::object vertex_markers, py::object vertex_attributes, py::object segment_markers,
                        py::object triangles, py::object triangle_attributes, py::object triangle_max_area,
                        py::object min_angle, py::object max_area, bool regional_area, py::object max_steiner,
                        py::object max_area_fn, py::object max_edge_fn, bool conforming_delaunay,
                        const std::string& segment_splitting, bool convex_hull, bool regional_attributes,
                        bool ignore_holes, const std::string& fill, const std::string& cdt, bool strict,
                        const std::string& steiner, const std::string& encroachment, const std::string& order,
                        py::object time_limit, bool jettison, bool second_order, bool edges, bool neighbors, bool check,
                        bool markers, bool quiet);
py::dict adapt_dict(const py::dict& tri, py::object size, const std::string& opts, int smooth, py::object metric);
py::dict adapt_metric_dict(const py::dict& tri, py::object metric, const std::string& opts, int smooth);  // metric.cpp
py::dict check_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments);
py::dict validate_dict(const py::dict& tri, bool delaunay, bool convex_hull, bool segments);
py::dict quality_dict(const py::dict& tri, double min_angle, double max_area);
py::dict read_file(const std::string& path);
void write_file(const py::dict& tri, const std::string& path, int first_index, bool markers);
py::array_t<std::int32_t> delaunay_triangles(py::handle vertices);
py::array_t<std::int32_t> hull_segments(py::handle vertices);
py::dict voronoi_dict(py::handle vertices);

}  // namespace deltamesh::python

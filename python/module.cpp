// The Python module `deltamesh`: its exceptions and functions. See
// docs/python.md; the functions are in triangulate.cpp and tools.cpp.
#include <exception>

#include "bindings.hpp"

namespace deltamesh::python {

ExceptionTypes g_exc;

void raise_with(PyObject* type, const std::string& message,
                std::initializer_list<std::pair<const char*, py::object>> attrs) {
  py::object inst = py::reinterpret_borrow<py::object>(type)(message);
  for (const auto& [k, v] : attrs) inst.attr(k) = v;
  PyErr_SetObject(type, inst.ptr());
}

namespace {

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

void translate_exception(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const ParseError& e) {
    raise_with(g_exc.parse, e.what(), {{"file", py::str(e.file())}, {"line", py::int_(e.line())}});
  } catch (const IntersectingSegments& e) {
    raise_with(g_exc.intersecting, e.what(), {{"first", py::int_(e.first())}, {"second", py::int_(e.second())}});
  } catch (const SegmentError& e) {
    raise_with(g_exc.segment, e.what(), {{"segment", py::int_(e.segment())}});
  } catch (const InputError& e) {
    py::object index =
        e.index() == static_cast<std::size_t>(-1) ? py::object(py::none()) : py::object(py::int_(e.index()));
    raise_with(g_exc.input, e.what(), {{"index", index}});
  } catch (const IoError& e) {
    raise_with(g_exc.io, e.what());
  } catch (const InternalError& e) {
    raise_with(g_exc.internal, e.what(), {{"where", py::str(e.where())}});
  } catch (const Error& e) {
    raise_with(g_exc.error, e.what());
  }
}

}  // namespace
}  // namespace deltamesh::python

using namespace deltamesh::python;
namespace dm = deltamesh;

PYBIND11_MODULE(_deltamesh, m) {
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
  g_exc.internal = new_exception(m, "InternalError", {g_exc.error},
                                 "A broken invariant: a bug in deltamesh, please report it (attribute `where`).");
  py::register_exception_translator(&translate_exception);

  m.def("triangulate", &triangulate_dict, py::arg("tri"), py::arg("opts") = "", py::kw_only(),
        py::arg("max_area_fn") = py::none(), py::arg("max_edge_fn") = py::none(), py::arg("stats") = false, py::arg("trace") = py::none(),
        py::arg("threads") = py::none(),
        R"(Triangle's form: triangulate(tri: dict, opts: str = '') -> dict.

tri holds numpy arrays (or lists): vertices (n, 2) float, and optionally
vertex_markers (n,) or (n, 1), vertex_attributes (n, k), segments (s, 2) int
(0-based), segment_markers, holes (h, 2), regions (r, 4): x, y, attribute,
maximum area; for 'r' also triangles (m, 3), triangle_attributes,
triangle_max_area. opts is Triangle's switch string, e.g. 'pq30a0.1'
(p r q a c A O D Y S j e n o2 C Q V B z, and the output switches v N E P;
i F l X s u g I are accepted with a warning that they change nothing;
long options such as '--cdt=lawson' may follow after a space). Unknown
switches raise ValueError. threads=N (or 't4' in opts):
threads for Delaunay and refinement, 0 (default) every hardware thread, 1
the sequential code.

Returns the `triangle` package's dict: vertices (N, 2) float64,
vertex_markers (N, 1) int32, triangles (M, 3) int32 (M, 6 with o2),
triangle_attributes (M, k) with A and regions, segments/segment_markers
with p or c (input segments first, in their order), edges/edge_markers
with e, neighbors (M, 3) with n (-1: none), holes/regions with p, and
voronoi (a dict: vertices, edges, ray_origins, ray_directions) with v.
Arrays with no rows are left out. stats=True returns (dict, stats), stats
being the run's report (complete, steiner_points, min_angle, refine
details, warnings...).)");

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
        py::arg("stats") = false, py::arg("trace") = py::none(), py::arg("threads") = py::none(),
        R"(Keyword form: triangulate(vertices, segments=None, holes=None, regions=None, *, ...) -> dict.

Same result as Triangle's form. Segments (or triangles) switch on 'p'
(constrained triangulation of the domain; without them: Delaunay of the
points). min_angle=30 is 'q30', max_area=0.1 'a0.1', regional_area=True 'a',
max_steiner 'S', conforming_delaunay 'D', segment_splitting='interior'|'none'
'Y'|'YY', convex_hull 'c', regional_attributes 'A', ignore_holes 'O',
jettison 'j', second_order 'o2', edges 'e', neighbors 'n', check 'C',
markers=False 'B', quiet 'Q'; triangles=... is 'r'. fill, cdt, steiner,
encroachment, order, time_limit are the command line's long options;
threads=N is -tN (0, the default: every hardware thread; 1: sequential).
max_area_fn(x, y) / max_edge_fn(x, y): size functions evaluated at triangle
centroids (<= 0: no bound there); they refine like max_area.
stats=True returns (dict, stats). trace=PATH writes every step of the run as
JSON Lines (docs/trace.md).)");

  m.def("adapt", &adapt_dict, py::arg("mesh"), py::arg("size") = py::none(), py::arg("opts") = "q", py::kw_only(),
        py::arg("smooth") = 2, py::arg("metric") = py::none(),
        R"(adapt(mesh: dict, size, opts: str = 'q', *, smooth: int = 2, metric=None) -> dict.

Mesh adaptation (docs/adapt.md): coarsens where the mesh is finer than the
target edge length and refines where it is coarser, then smooths `smooth`
passes. mesh is a result of triangulate() (or the same keys: vertices,
triangles, and optionally segments, markers, attributes, holes); size is a
function h(x, y) -> target edge length (<= 0: no target there) or an array
of one size per vertex (interpolated linearly over the mesh, as a TetGen
.mtr file). opts: refinement switches as for triangulate ('q30', 'a0.01',
'S1000', 'C'...). The result has triangulate()'s keys; stats['adapt'] holds
removed, inserted, smoothed, triangles, complete.

metric=...: adapt to a metric tensor field instead of a size (anisotropic;
docs/adapt.md): an (n, 3) array of m11, m12, m22 per vertex (log-Euclidean
interpolation) or a function (x, y) -> (m11, m12, m22). Edges get metric
length near 1 (split above sqrt 2, collapse below 1/sqrt 2, swaps and
smoothing in the metric); refinement switches of opts other than Y, C, Q do
not apply. stats['adapt'] then holds splits, collapses, swaps, moves,
edges_within (share of edges of metric length in [1/sqrt 2, sqrt 2]),
mean_quality, min_quality.)");
  m.def("delaunay", &delaunay_triangles, py::arg("vertices"),
        "Delaunay triangulation of points: the (M, 3) int32 triangles (counter-clockwise) of triangulate({'vertices': "
        "v}).");
  m.def("convex_hull", &hull_segments, py::arg("vertices"),
        "Convex hull edges of points as (H, 2) int32 vertex pairs in Triangle's order: the hull walked from its "
        "lowest-leftmost vertex, each edge with the interior on its right (points on a hull edge split it).");
  m.def("voronoi", &voronoi_tuple, py::arg("vertices"),
        R"(Voronoi diagram of points (the dual of their Delaunay triangulation), as
the `triangle` package returns it: (points, edges, ray_origins,
ray_directions). points (V, 2) float64, one circumcentre per Delaunay
triangle (in delaunay()'s order); edges (E, 2) int32, the finite edges;
ray_origins (R,) int32, the Voronoi vertex each infinite ray starts at;
ray_directions (R, 2) float64, its outward direction (the hull edge's
normal, as long as that edge).)");

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


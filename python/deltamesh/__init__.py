"""deltamesh: 2-D constrained Delaunay triangulation and quality meshing.

A drop-in for the `triangle` package (``import deltamesh as triangle``):
triangulate(dict, 'pq30a0.1'), delaunay, convex_hull, voronoi, get_data,
load, loads, show_data, plot, compare, comparev, with the same arguments,
keys and return conventions; docs/python.md lists the deliberate
differences. deltamesh's own functions: the keyword form of triangulate,
adapt, check/validate (the library's exact validator), quality, read and
write, and typed exceptions.
"""
from ._deltamesh import (  # noqa: F401
    CheckError,
    Error,
    InputError,
    InternalError,
    IntersectingSegments,
    IoError,
    ParseError,
    SegmentError,
    __version__,
    adapt,
    check,
    convex_hull,
    delaunay,
    quality,
    read,
    triangulate,
    validate,
    voronoi,
    write,
)
from . import plot as _plot_module
from .data import data_names, get_data, get_data_dir, load, loads, show_data  # noqa: F401
from .plot import compare, comparev, plot  # noqa: F401

# Code written for `triangle` calls both triangle.plot(ax, **d) and, from
# older releases, triangle.plot.plot(ax, **d) / triangle.plot.vertices(...):
# the function carries the module's drawing functions as attributes.
for _name in ("plot", "compare", "comparev", "vertices", "triangles", "segments", "edges", "holes", "regions",
              "triangle_attributes"):
    setattr(plot, _name, getattr(_plot_module, _name))
del _name

__all__ = [
    "triangulate", "delaunay", "convex_hull", "voronoi", "get_data", "get_data_dir", "data_names", "load", "loads",
    "show_data", "plot", "compare", "comparev", "adapt", "check", "validate", "quality", "read", "write", "Error",
    "InputError", "ParseError", "IntersectingSegments", "SegmentError", "IoError", "CheckError", "InternalError",
    "__version__",
]

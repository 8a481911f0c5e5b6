"""Triangle's files as dicts of arrays: get_data, load, loads, show_data.

The `triangle` package's data functions, on deltamesh's readers: .node,
.ele and .poly go through the library's parsers (deltamesh.read, the same
ones as the command line, with their messages naming file and line); the
small .area, .edge and .neigh formats are read here. The example data sets
in deltamesh/data were written for deltamesh (see data/README).
"""
import os
import tempfile

import numpy as np

from . import _deltamesh as _core

EXTENSIONS = ("node", "ele", "poly", "area", "edge", "neigh")


def get_data_dir():
    """The directory of the example data sets shipped with the package."""
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def data_names(directory=None):
    """Names get_data() can load from `directory` (default: the package's data sets)."""
    directory = directory or get_data_dir()
    names = set()
    for f in os.listdir(directory):
        base, dot, ext = f.rpartition(".")
        if dot and ext in EXTENSIONS:
            names.add(base)
    return sorted(names)


def get_data(name, directory=None):
    """The data set `name` as a dict of arrays: one of the examples shipped
    with deltamesh (data_names() lists them), or NAME.node/.ele/.poly/... in
    `directory` when given. Raises FileNotFoundError naming the choices when
    no file of that name exists."""
    return load(directory or get_data_dir(), name)


def load(directory, name):
    """Reads DIRECTORY/NAME.node, .ele, .poly, .area, .edge and .neigh (those
    that exist) into one dict: vertices, vertex_markers, vertex_attributes,
    triangles, triangle_attributes, segments, segment_markers, holes,
    regions, triangle_max_area, edges (edge_markers, or ray_origins and
    ray_directions for a Voronoi .v.edge file), neighbors. Indices are
    0-based whatever the files' numbering."""
    paths = {ext: os.path.join(directory, name + "." + ext) for ext in EXTENSIONS}
    present = {ext for ext, p in paths.items() if os.path.isfile(p)}
    if not present:
        try:
            known = ", ".join(data_names(directory)) or "none"
        except OSError:
            known = "none (the directory cannot be listed)"
        raise FileNotFoundError(f"no file {name}.{{{','.join(EXTENSIONS)}}} in {directory} (data sets there: {known})")
    first = 0
    if "node" in present:
        data = _core.read(paths["node"])  # with NAME.ele's triangles and NAME.poly's segments, holes, regions
        first = _first_index(paths["node"])
    elif "poly" in present:
        data = _core.read(paths["poly"])
        first = _first_index(paths["poly"])
        if "ele" in present:  # a mesh whose vertices are listed in the .poly file
            with tempfile.TemporaryDirectory() as tmp:
                node = os.path.join(tmp, "m.node")
                _copy_vertices(paths["poly"], node)
                os.symlink(os.path.abspath(paths["ele"]), os.path.join(tmp, "m.ele"))
                mesh = _core.read(node)
            for key in ("triangles", "triangle_attributes"):
                if key in mesh:
                    data[key] = mesh[key]
    else:
        raise ValueError(f"{name}: .{'/.'.join(sorted(present))} without a .node or .poly file to number vertices")
    if "area" in present:
        data["triangle_max_area"] = _read_area(paths["area"])
    if "edge" in present:
        data.update(_read_edge(paths["edge"], first))
    if "neigh" in present:
        data["neighbors"] = _read_neigh(paths["neigh"], first)
    return data


def loads(node=None, ele=None, poly=None, area=None, edge=None, neigh=None):
    """Like load(), from the files' contents given as strings."""
    given = {ext: text for ext, text in zip(EXTENSIONS, (node, ele, poly, area, edge, neigh)) if text is not None}
    if not given:
        return {}
    with tempfile.TemporaryDirectory() as tmp:
        for ext, text in given.items():
            with open(os.path.join(tmp, "data." + ext), "w") as f:
                f.write(text)
        try:
            return load(tmp, "data")
        except (_core.ParseError, ValueError) as e:
            # Name the argument rather than the temporary file.
            msg = str(e)
            for ext in EXTENSIONS:
                msg = msg.replace(os.path.join(tmp, "data." + ext), f"<{ext} string>")
            err = type(e)(msg)
            for attr in ("file", "line", "index"):
                if hasattr(e, attr):
                    setattr(err, attr, getattr(e, attr))
            raise err from None


def show_data(name, directory=None):
    """Draws get_data(name) with plot() in a new figure and shows it (matplotlib needed)."""
    from .plot import _pyplot, plot
    plt = _pyplot()
    plt.figure()
    plot(plt.axes(), **get_data(name, directory))
    plt.show()


# -- the small formats ------------------------------------------------------

def _rows(path):
    """(line number, fields) of each non-empty line, '#' comments removed."""
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split("#", 1)[0].split()
            if fields:
                yield number, fields


def _parse_error(path, line, problem):
    err = _core.ParseError(f"{path}:{line}: {problem}")
    err.file, err.line, err.index = path, line, None
    return err


def _numbers(path, line, fields, kind):
    try:
        return [kind(x) for x in fields]
    except ValueError:
        raise _parse_error(path, line, f"expected numbers, got '{' '.join(fields)}'") from None


def _first_index(path):
    """0 or 1: the number of the first vertex listed in a .node or .poly file."""
    rows = _rows(path)
    for number, fields in rows:
        count = _numbers(path, number, fields[:1], int)[0]
        if count == 0:
            return 0  # vertices in the .node file of a .poly: numbered as that file
        for number2, fields2 in rows:
            return _numbers(path, number2, fields2[:1], int)[0]
    return 0


def _copy_vertices(poly, node):
    """Writes the vertex section of a .poly file as a .node file."""
    lines = []
    rows = _rows(poly)
    for number, fields in rows:
        count = _numbers(poly, number, fields[:1], int)[0]
        lines.append(" ".join(fields))
        for _ in range(count):
            lines.append(" ".join(next(rows)[1]))
        break
    with open(node, "w") as f:
        f.write("\n".join(lines) + "\n")


def _header(path):
    rows = _rows(path)
    try:
        number, fields = next(rows)
    except StopIteration:
        raise _parse_error(path, 1, "the file is empty (expected a header line)") from None
    return rows, number, fields


def _read_area(path):
    rows, number, fields = _header(path)
    n = _numbers(path, number, fields[:1], int)[0]
    areas = []
    for number, fields in rows:
        if len(fields) < 2:
            raise _parse_error(path, number, "expected '<triangle> <maximum area>'")
        areas.append(_numbers(path, number, fields[1:2], float)[0])
    if len(areas) != n:
        raise _parse_error(path, number, f"the header says {n} triangles, the file lists {len(areas)}")
    return np.array(areas, dtype=np.float64).reshape(-1, 1)


def _read_edge(path, first):
    rows, number, fields = _header(path)
    head = _numbers(path, number, fields[:2], int)
    n, has_markers = head[0], len(head) > 1 and head[1] > 0
    edges, markers, origins, directions = [], [], [], []
    for number, fields in rows:
        values = _numbers(path, number, fields, float)
        if len(values) >= 5 and values[2] == -1:  # a Voronoi ray: id, origin, -1, dx, dy
            origins.append(int(values[1]) - first)
            directions.append(values[3:5])
        elif len(values) >= 3:
            edges.append([int(values[1]) - first, int(values[2]) - first])
            if has_markers:
                markers.append(int(values[3]) if len(values) > 3 else 0)
        else:
            raise _parse_error(path, number, "expected '<edge> <first end> <second end> [marker]'")
    if len(edges) + len(origins) != n:
        raise _parse_error(path, number, f"the header says {n} edges, the file lists {len(edges) + len(origins)}")
    out = {"edges": np.array(edges, dtype=np.int32).reshape(-1, 2)}
    if has_markers:
        out["edge_markers"] = np.array(markers, dtype=np.int32).reshape(-1, 1)
    if origins:
        out["ray_origins"] = np.array(origins, dtype=np.int32)
        out["ray_directions"] = np.array(directions, dtype=np.float64).reshape(-1, 2)
    return out


def _read_neigh(path, first):
    rows, number, fields = _header(path)
    n = _numbers(path, number, fields[:1], int)[0]
    out = []
    for number, fields in rows:
        values = _numbers(path, number, fields, int)
        if len(values) != 4:
            raise _parse_error(path, number, "expected '<triangle> <neighbour> <neighbour> <neighbour>'")
        out.append([v - first if v >= 0 else -1 for v in values[1:]])
    if len(out) != n:
        raise _parse_error(path, number, f"the header says {n} triangles, the file lists {len(out)}")
    return np.array(out, dtype=np.int32).reshape(-1, 3)

"""The `triangle` package's interface on deltamesh (`import deltamesh as triangle`):
every function, switch, key and return convention, on our own data.

Every mesh made here goes through deltamesh.validate (the library's exact
validator). Drawing tests run with matplotlib's Agg backend and are skipped
when matplotlib is missing (the clear error then is tested instead).
"""
import inspect
import os
import subprocess
import sys
import tempfile
import unittest
import warnings

import numpy as np

import deltamesh as triangle  # the point of the exercise

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None

DTYPES = {"vertices": np.float64, "vertex_markers": np.int32, "vertex_attributes": np.float64,
          "triangles": np.int32, "triangle_attributes": np.float64, "segments": np.int32,
          "segment_markers": np.int32, "edges": np.int32, "edge_markers": np.int32, "neighbors": np.int32,
          "holes": np.float64, "regions": np.float64}


def mesh_of(tri, opts=""):
    """triangulate() with warnings as errors (none is expected) and the result validated."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = triangle.triangulate(tri, opts)
    if "triangles" in out and "vertices" in out:
        triangle.validate(out, delaunay="D" in opts or "p" not in opts and "r" not in opts,
                          segments="segments" in out)
    return out


def undirected(pairs):
    return sorted(tuple(sorted(map(int, p))) for p in pairs)


class Interface(unittest.TestCase):
    def test_every_function_of_the_package_exists_with_its_arguments(self):
        expected = {"triangulate": ["tri", "opts"], "delaunay": ["vertices"], "convex_hull": ["vertices"],
                    "voronoi": ["vertices"], "get_data": ["name"], "load": ["directory", "name"],
                    "loads": ["node", "ele", "poly", "area", "edge", "neigh"], "show_data": ["name"],
                    "plot": ["ax"], "compare": ["plt", "A", "B", "figsize"], "comparev": ["plt", "A", "B", "figsize"]}
        for name, args in expected.items():
            fn = getattr(triangle, name)
            self.assertTrue(callable(fn), name)
            if name in ("triangulate", "delaunay", "convex_hull", "voronoi"):
                self.assertIn(args[0], fn.__doc__, name)  # pybind11 functions: the signature is in the docstring
            else:
                params = list(inspect.signature(fn).parameters)
                self.assertEqual(params[:len(args)], args, name)
        # triangle.plot.plot(...) of older code and triangle.plot(...) of newer both work
        self.assertIs(triangle.plot.plot, triangle.plot)
        for part in ("vertices", "triangles", "segments", "edges", "holes", "regions", "triangle_attributes"):
            self.assertTrue(callable(getattr(triangle.plot, part)))
        self.assertRegex(triangle.__version__, r"^\d+\.\d+\.\d+")

    def test_positional_and_keyword_opts(self):
        sq = triangle.get_data("square_hole")
        a = mesh_of(sq, "pq")
        b = triangle.triangulate(tri=sq, opts="pq")
        for k in a:
            np.testing.assert_array_equal(a[k], b[k])


class Keys(unittest.TestCase):
    """Exactly the keys `triangle` returns for each switch; no `stats`."""

    def setUp(self):
        self.sq = triangle.get_data("square_hole")
        self.two = triangle.get_data("two_regions")
        self.dots = {"vertices": triangle.get_data("dots")["vertices"]}

    def check_layout(self, out):
        for key, value in out.items():
            if key == "voronoi":
                continue
            self.assertIsInstance(value, np.ndarray, key)
            self.assertEqual(value.dtype, DTYPES[key], key)
            self.assertEqual(value.ndim, 2, key)
            self.assertGreater(len(value), 0, f"{key}: an empty array is left out")

    def test_keys_per_switch(self):
        base = {"vertices", "vertex_markers", "triangles"}
        poly = base | {"segments", "segment_markers"}
        cases = [
            (self.dots, "", base),
            (self.dots, "c", base | {"segments", "segment_markers"}),
            (self.dots, "q", base),
            (self.dots, "e", base | {"edges", "edge_markers"}),
            (self.dots, "n", base | {"neighbors"}),
            (self.dots, "B", {"vertices", "triangles"}),
            (self.dots, "eB", {"vertices", "triangles", "edges"}),
            (self.sq, "p", poly | {"holes"}),
            (self.sq, "pq30a0.01", poly | {"holes"}),
            (self.sq, "pA", poly | {"holes"}),  # A without regions: no triangle_attributes
            (self.two, "pA", poly | {"triangle_attributes", "regions"}),
            (self.two, "pqaA", poly | {"triangle_attributes", "regions"}),
            (self.two, "p", poly | {"regions"}),
            (self.sq, "pP", base),
            (self.two, "pAP", base | {"triangle_attributes"}),
            (self.sq, "pN", {"triangles", "segments", "segment_markers", "holes"}),
            (self.sq, "pE", {"vertices", "vertex_markers", "segments", "segment_markers", "holes"}),
            (self.sq, "pEn", {"vertices", "vertex_markers", "segments", "segment_markers", "holes", "neighbors"}),
            (self.sq, "pv", poly | {"holes", "voronoi"}),
            (self.sq, "po2", poly | {"holes"}),
            (self.sq, "pzQVCj", poly | {"holes"}),
            (self.sq, "pDY", poly | {"holes"}),
            (self.sq, "pqYYS10", poly | {"holes"}),
            (self.sq, "pO", poly | {"holes"}),
            (self.sq, "-pq", poly | {"holes"}),
        ]
        for tri, opts, keys in cases:
            with self.subTest(opts=opts):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # V's report, S10's budget
                    out = triangle.triangulate(tri, opts)
                self.assertEqual(set(out), keys)
                self.check_layout(out)
                if "triangles" in out and "vertices" in out:
                    triangle.validate(out, delaunay=False)

    def test_no_effect_switches_warn_and_change_nothing(self):
        plain = mesh_of(self.sq, "pq")
        for c in "iFlXsugI":
            with self.subTest(switch=c):
                with self.assertWarnsRegex(UserWarning, f"switch -{c} has no effect"):
                    out = triangle.triangulate(self.sq, "pq" + c)
                self.assertEqual(set(out), set(plain))
                for k in plain:
                    np.testing.assert_array_equal(out[k], plain[k], err_msg=k)

    def test_P_N_E_drop_what_triangle_drops(self):
        full = mesh_of(self.two, "pqA")
        for opts, gone in (("pqAP", ("segments", "segment_markers", "regions")),
                           ("pqAN", ("vertices", "vertex_markers")),
                           ("pqAE", ("triangles", "triangle_attributes"))):
            out = triangle.triangulate(self.two, opts)
            for k in gone:
                self.assertNotIn(k, out)
            for k in out:
                np.testing.assert_array_equal(out[k], full[k], err_msg=f"{opts}: {k}")

    def test_v_returns_the_voronoi_diagram_beside_the_mesh(self):
        out = mesh_of(self.dots, "v")
        vor = out["voronoi"]
        self.assertEqual(set(vor), {"vertices", "edges", "ray_origins", "ray_directions"})
        t, v = out["triangles"], out["vertices"]
        self.assertEqual(len(vor["vertices"]), len(t))  # one circumcentre per triangle, in triangle order
        d = np.linalg.norm(v[t] - vor["vertices"][:, None, :], axis=2)
        np.testing.assert_allclose(d, d[:, :1].repeat(3, axis=1), rtol=1e-9)
        hull = triangle.convex_hull(self.dots["vertices"])
        self.assertEqual(len(vor["ray_origins"]), len(hull))
        n_edges = len(set(undirected(np.vstack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]))))
        self.assertEqual(len(vor["edges"]) + len(vor["ray_origins"]), n_edges)
        # the same diagram as voronoi() (as sets: triangle order is the pipeline's)
        points, edges, origins, directions = triangle.voronoi(self.dots["vertices"])
        np.testing.assert_allclose(np.sort(points, axis=0), np.sort(vor["vertices"], axis=0), rtol=1e-12)
        # and the output can be fed back in (the voronoi key is ignored)
        again = mesh_of(out, "r")
        np.testing.assert_array_equal(again["vertices"], out["vertices"])

    def test_stats_only_when_asked(self):
        out, st = triangle.triangulate(self.sq, "pq30", stats=True)
        self.assertNotIn("stats", out)
        self.assertTrue(st["complete"])
        self.assertGreaterEqual(st["min_angle"], 30 - 1e-9)
        self.assertEqual(st["triangles"], len(out["triangles"]))
        kw, st2 = triangle.triangulate(self.sq["vertices"], self.sq["segments"], self.sq["holes"], min_angle=30,
                                       segment_markers=self.sq["segment_markers"], stats=True)
        np.testing.assert_array_equal(kw["triangles"], out["triangles"])
        self.assertNotIn("stats", triangle.triangulate(self.sq["vertices"], self.sq["segments"]))


class Inputs(unittest.TestCase):
    def test_float_indices_are_cast(self):
        sq = triangle.get_data("square_hole")
        a = mesh_of(sq, "pq")
        b = mesh_of(dict(sq, segments=sq["segments"].astype(float), segment_markers=sq["segment_markers"] * 1.0),
                    "pq")
        for k in a:
            np.testing.assert_array_equal(a[k], b[k], err_msg=k)
        c = mesh_of(dict(a, triangles=a["triangles"].astype(np.float64)), "r")
        np.testing.assert_array_equal(c["triangles"], a["triangles"])
        with self.assertRaisesRegex(ValueError, "segments: value 0.5 in row 0 is not a whole number"):
            triangle.triangulate(dict(sq, segments=sq["segments"] + 0.5), "p")

    def test_collinear_points_give_the_vertices_and_no_triangles(self):
        line = [[0, 0], [1, 1], [3, 3], [2, 2]]
        with self.assertWarnsRegex(UserWarning, "collinear"):
            out = triangle.triangulate({"vertices": line})
        self.assertEqual(set(out), {"vertices", "vertex_markers"})
        np.testing.assert_array_equal(out["vertices"], np.array(line, float))
        out = triangle.triangulate({"vertices": line, "vertex_markers": [1, 2, 3, 4]}, "Q")
        np.testing.assert_array_equal(out["vertex_markers"][:, 0], [1, 2, 3, 4])
        self.assertEqual(triangle.delaunay(line).shape, (0, 3))
        self.assertEqual(triangle.convex_hull(line).shape, (0, 2))
        points, edges, origins, directions = triangle.voronoi(line)
        self.assertEqual((len(points), len(edges), len(origins), len(directions)), (0, 0, 0, 0))
        same = [[1, 1]] * 4  # duplicates of one point count as collinear
        self.assertEqual(set(triangle.triangulate({"vertices": same}, "Q")), {"vertices", "vertex_markers"})

    def test_too_few_points_and_empty_input_raise(self):
        for pts in ([], [[0, 0]], [[0, 0], [1, 0]]):
            with self.subTest(pts=pts), self.assertRaises(triangle.InputError):
                triangle.triangulate({"vertices": np.array(pts, float).reshape(-1, 2)})

    def test_empty_results_leave_keys_out(self):
        sq = triangle.get_data("square_hole")
        # a hole point outside the inner square eats the whole domain
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = triangle.triangulate(dict(sq, holes=[[.1, .1], [.5, .5]]), "p")
        self.assertNotIn("triangles", out)
        self.assertNotIn("segments", out)
        self.assertIn("vertices", out)
        # p with no segments: nothing encloses a domain
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = triangle.triangulate({"vertices": sq["vertices"]}, "p")
        self.assertNotIn("segments", out)
        self.assertNotIn("holes", out)
        for value in out.values():
            self.assertGreater(len(value), 0)


class Order(unittest.TestCase):
    """Order fixed by the input comes in Triangle's order."""

    def test_convex_hull_in_triangles_order(self):
        # the package's documented example: the unit square
        np.testing.assert_array_equal(triangle.convex_hull([[0, 0], [0, 1], [1, 1], [1, 0]]),
                                      [[3, 0], [2, 3], [1, 2], [0, 1]])
        pts = triangle.get_data("dots")["vertices"]
        hull = triangle.convex_hull(pts)
        # one cycle from the lowest-leftmost point, each edge with the interior on its right
        start = min(range(len(pts)), key=lambda i: (pts[i, 0], pts[i, 1]))
        self.assertEqual(hull[0, 1], start)
        for (a, b), (c, d) in zip(hull, np.roll(hull, -1, axis=0)):
            self.assertEqual(a, d)  # each edge starts where the next one ends
        p, q = pts[hull[:, 0]], pts[hull[:, 1]]
        for x in pts:
            self.assertTrue((((q[:, 0] - p[:, 0]) * (x[1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (x[0] - p[:, 0]))
                             <= 0).all())
        # 'c' gives the same segments
        np.testing.assert_array_equal(mesh_of({"vertices": pts}, "c")["segments"], hull)

    def test_segments_in_input_order_and_direction(self):
        sq = triangle.get_data("square_hole")
        out = mesh_of(sq, "p")
        np.testing.assert_array_equal(out["segments"], sq["segments"])
        np.testing.assert_array_equal(out["segment_markers"], sq["segment_markers"])
        # reversed and shuffled input: the output follows it
        perm = [5, 2, 7, 0, 3, 6, 1, 4]
        shuffled = dict(sq, segments=sq["segments"][perm][:, ::-1], segment_markers=sq["segment_markers"][perm])
        out = mesh_of(shuffled, "p")
        np.testing.assert_array_equal(out["segments"], shuffled["segments"])
        # split segments: each input segment's pieces in order from its first end to its second
        out = mesh_of(sq, "pq30a0.005")
        s, v = out["segments"], out["vertices"]
        k = 0
        for (a, b), m in zip(sq["segments"], sq["segment_markers"][:, 0]):
            self.assertEqual(s[k, 0], a)
            while s[k, 1] != b:
                self.assertEqual(s[k + 1, 0], s[k, 1])
                self.assertEqual(out["segment_markers"][k, 0], m)
                k += 1
            k += 1
        self.assertEqual(k, len(s))
        # input vertices keep their ids and markers
        np.testing.assert_array_equal(v[:8], sq["vertices"])

    def test_hull_segments_of_pc_follow_the_input_segments(self):
        pts = triangle.get_data("dots")["vertices"]
        tri = {"vertices": pts, "segments": [[0, 1], [2, 3]]}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = triangle.triangulate(tri, "pc")
        triangle.validate(out)
        s = out["segments"]
        # the input segments (possibly split where they cross) come first, then the hull
        hull = triangle.convex_hull(pts)
        self.assertEqual(undirected(s[-len(hull):]), undirected(hull))


class RoundTrips(unittest.TestCase):
    def test_result_fed_back_with_r(self):
        sq = triangle.get_data("square_hole")
        first = mesh_of(sq, "pq30")
        same = mesh_of(first, "rp")  # nothing to do: the same mesh
        for k in ("vertices", "segments"):
            np.testing.assert_array_equal(same[k], first[k], err_msg=k)
        as_set = lambda m: sorted(tuple(sorted(t)) for t in m["triangles"].tolist())
        self.assertEqual(as_set(same), as_set(first))
        finer = mesh_of(first, "rpq30a0.002")
        self.assertGreater(len(finer["triangles"]), len(first["triangles"]))
        np.testing.assert_array_equal(finer["vertices"][:len(first["vertices"])], first["vertices"])
        # with every output switch on, the result still goes back in
        loaded = mesh_of(first, "rpenv")
        mesh_of(loaded, "rp")

    def test_r_with_area_file(self):
        ell = triangle.get_data("ell.1")
        out = mesh_of(ell, "rpa")
        v, t = out["vertices"], out["triangles"]
        area = 0.5 * np.abs(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]))
        self.assertLessEqual(area.max(), ell["triangle_max_area"].max() * (1 + 1e-12))
        self.assertGreater(len(t), len(ell["triangles"]))

    def test_triangle_attributes_carried_by_r(self):
        two = mesh_of(triangle.get_data("two_regions"), "pqA")
        again = mesh_of(two, "rpq30a0.01")
        self.assertIn("triangle_attributes", again)
        self.assertEqual(set(np.unique(again["triangle_attributes"])), {1.0, 2.0})


class Data(unittest.TestCase):
    def test_every_data_set_loads_and_meshes(self):
        names = triangle.data_names()
        self.assertGreaterEqual(len(names), 6)
        for name in names:
            with self.subTest(name=name):
                d = triangle.get_data(name)
                self.assertIn("vertices", d)
                opts = "rp" if "triangles" in d else "pq" if "segments" in d else "q"
                mesh_of(d, opts)

    def test_mesh_files_numbered_from_one(self):
        ell = triangle.get_data("ell.1")
        self.assertEqual(set(ell), {"vertices", "vertex_markers", "triangles", "segments", "segment_markers",
                                    "triangle_max_area", "edges", "edge_markers", "neighbors"})
        n, m = len(ell["vertices"]), len(ell["triangles"])
        self.assertEqual(ell["triangles"].min(), 0)
        self.assertEqual(ell["triangles"].max(), n - 1)
        self.assertEqual(ell["triangle_max_area"].shape, (m, 1))
        self.assertEqual(ell["neighbors"].shape, (m, 3))
        self.assertEqual(ell["neighbors"].min(), -1)
        triangle.validate(ell)
        # the .edge and .neigh files are what triangulate gives for that mesh
        again = mesh_of(ell, "rpen")
        self.assertEqual(undirected(again["edges"]), undirected(ell["edges"]))
        pairs = lambda m: sorted(tuple(sorted(r)) for r in m["neighbors"].tolist())
        self.assertEqual(len(pairs(again)), len(pairs(ell)))

    def test_get_data_from_a_directory_and_errors(self):
        with tempfile.TemporaryDirectory() as tmp:
            mesh = mesh_of(triangle.get_data("two_regions"), "pqA")
            triangle.write(mesh, os.path.join(tmp, "plate.node"), first_index=1)
            triangle.write(mesh, os.path.join(tmp, "plate.ele"), first_index=1)
            d = triangle.get_data("plate", tmp)
            np.testing.assert_array_equal(d["triangles"], mesh["triangles"])
            np.testing.assert_array_equal(d["vertices"], mesh["vertices"])
            same = triangle.load(tmp, "plate")
            np.testing.assert_array_equal(same["triangle_attributes"], mesh["triangle_attributes"])
            with self.assertRaisesRegex(FileNotFoundError, "no file nothing.*data sets there: plate"):
                triangle.get_data("nothing", tmp)
        with self.assertRaisesRegex(FileNotFoundError, "square_hole"):
            triangle.get_data("no_such_set")

    def test_loads_from_strings(self):
        node = "# a square\n4 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n"
        ele = "2 3 0\n1 1 2 3\n2 1 3 4\n"
        area = "2\n1 0.1\n2 -1\n"
        neigh = "2 3\n1 -1 2 -1\n2 -1 -1 1\n"
        edge = "5 1\n1 1 2 1\n2 2 3 1\n3 3 1 0\n4 3 4 1\n5 4 1 1\n"
        d = triangle.loads(node=node, ele=ele, area=area, neigh=neigh, edge=edge)
        np.testing.assert_array_equal(d["triangles"], [[0, 1, 2], [0, 2, 3]])
        np.testing.assert_array_equal(d["neighbors"], [[-1, 1, -1], [-1, -1, 0]])
        np.testing.assert_array_equal(d["triangle_max_area"][:, 0], [0.1, -1])
        np.testing.assert_array_equal(d["edges"][2], [2, 0])
        np.testing.assert_array_equal(d["edge_markers"][:, 0], [1, 1, 0, 1, 1])
        triangle.validate(d)
        out = mesh_of(d, "ra")
        self.assertGreater(len(out["triangles"]), 2)
        poly = "4 2 0 0\n0 0 0\n1 2 0\n2 2 2\n3 0 2\n4 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n0\n1\n0 1 1 7 0.5\n"
        d = triangle.loads(poly=poly)
        np.testing.assert_array_equal(d["regions"], [[1, 1, 7, 0.5]])
        out = mesh_of(d, "pqaA")
        self.assertEqual(set(out["triangle_attributes"][:, 0]), {7.0})
        # a Voronoi .v.edge file: finite edges and rays
        vedge = "3 0\n0 0 1\n1 0 -1 1.0 0.0\n2 1 -1 0.0 -2.0\n"
        d = triangle.loads(node="2 2 0 0\n0 0 0\n1 1 1\n", edge=vedge)
        np.testing.assert_array_equal(d["edges"], [[0, 1]])
        np.testing.assert_array_equal(d["ray_origins"], [0, 1])
        np.testing.assert_array_equal(d["ray_directions"], [[1, 0], [0, -2]])
        self.assertEqual(triangle.loads(), {})

    def test_loads_errors_name_the_argument_and_line(self):
        with self.assertRaisesRegex(triangle.ParseError, "<node string>") as cm:
            triangle.loads(node="3 2 0 0\n0 0 0\n1 1 x\n2 0 1\n")
        self.assertEqual(cm.exception.line, 3)
        with self.assertRaisesRegex(triangle.ParseError, "<neigh string>:2"):
            triangle.loads(node="3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", neigh="1 3\n0 1 2\n")


@unittest.skipIf(plt is None, "matplotlib is not installed")
class Drawing(unittest.TestCase):
    def tearDown(self):
        plt.close("all")

    def test_plot_draws_every_key(self):
        mesh = mesh_of(triangle.get_data("two_regions"), "pqAe")
        ax = plt.figure().add_subplot()
        self.assertIs(triangle.plot(ax, **mesh, labels=True, markers=True), ax)
        # triangles, edges and segments as line collections; labels as texts
        sizes = sorted(len(c.get_segments()) for c in ax.collections)
        self.assertEqual(sizes, sorted([3 * len(mesh["triangles"]), len(mesh["edges"]), len(mesh["segments"])]))
        self.assertGreaterEqual(len(ax.texts), 2 * len(mesh["vertices"]) + len(mesh["triangles"]))
        self.assertEqual(ax.get_aspect(), 1.0)

    def test_compare_and_comparev(self):
        a = triangle.get_data("square_hole")
        b = mesh_of(a, "pq")
        fig = triangle.compare(plt, a, b)
        self.assertEqual(len(fig.axes), 2)
        (x0, y0), (x1, y1) = (ax.get_position().p0 for ax in fig.axes)
        self.assertLess(x0, x1)  # side by side
        fig = triangle.comparev(plt, a, b, figsize=(3, 6))
        (x0, y0), (x1, y1) = (ax.get_position().p0 for ax in fig.axes)
        self.assertGreater(y0, y1)  # one above the other
        self.assertEqual(tuple(fig.get_size_inches()), (3, 6))

    def test_voronoi_drawing_and_show_data(self):
        pts = triangle.get_data("dots")["vertices"]
        points, edges, origins, directions = triangle.voronoi(pts)
        fig = triangle.compare(plt, {"vertices": pts},
                               dict(vertices=points, edges=edges, ray_origins=origins, ray_directions=directions))
        segs = sum(len(c.get_segments()) for c in fig.axes[1].collections)
        self.assertEqual(segs, len(edges) + len(origins))
        triangle.show_data("ell.1")  # Agg: show() draws nothing on screen, returns
        self.assertEqual(len(plt.get_fignums()), 2)


class MissingMatplotlib(unittest.TestCase):
    def test_a_clear_error_without_matplotlib(self):
        code = ("import sys; sys.modules['matplotlib'] = None; sys.modules['matplotlib.pyplot'] = None\n"
                "import deltamesh\n"
                "try:\n    deltamesh.show_data('dots')\nexcept ImportError as e:\n    print(e)\n")
        env = dict(os.environ)
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("need matplotlib, an optional dependency", out.stdout)


if __name__ == "__main__":
    unittest.main()

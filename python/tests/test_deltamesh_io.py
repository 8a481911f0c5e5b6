"""Tests of the Python bindings, part two: garbage in, dicts and keywords,
adaptation, the GIL, errors, files and the docs' examples (part one:
test_deltamesh.py). Every mesh produced here goes through deltamesh.validate.
"""
import contextlib
import io
import math
import os
import re
import tempfile
import threading
import time
import unittest
import warnings

import numpy as np

import deltamesh


from binding_support import areas, centroids, edge_set, min_angles, quiet_triangulate, square_with_hole, two_regions


class Garbage(unittest.TestCase):
    def test_random_malformed_inputs_raise_or_validate(self):
        """Seeded random shapes, dtypes and values (NaN, huge, negative indices,
        ragged lists, strings): each call returns a valid mesh or raises a
        ValueError / deltamesh.Error; none crashes."""
        rng = np.random.default_rng(5)

        def junk():
            kind = rng.integers(0, 9)
            n = int(rng.integers(0, 6))
            if kind == 0:
                return rng.random((n, int(rng.integers(0, 4))))
            if kind == 1:
                return rng.integers(-3, 8, size=(n, int(rng.integers(1, 4))))
            if kind == 2:
                return [[1, 2], [3]]
            if kind == 3:
                return "abc"
            if kind == 4:
                return np.array([[np.nan, 1.0], [1e308, -1e308]])
            if kind == 5:
                return rng.integers(0, 4, size=n).astype(np.uint8)
            if kind == 6:
                return None
            if kind == 7:
                return np.zeros((2, 2, 2))
            return rng.random((n, 2)) * 10.0 ** rng.integers(-300, 300)

        keys = ["vertices", "vertex_markers", "vertex_attributes", "segments", "segment_markers", "holes",
                "regions", "triangles", "triangle_attributes", "triangle_max_area"]
        outcomes = {"ok": 0, "error": 0}
        for _ in range(300):
            tri = {"vertices": rng.integers(0, 5, size=(int(rng.integers(0, 8)), 2)).astype(float)}
            for k in rng.choice(keys, size=int(rng.integers(0, 4)), replace=False):
                value = junk()
                if value is not None:
                    tri[str(k)] = value
            opts = str(rng.choice(["", "p", "pq", "pc", "pA", "r", "rp", "pqa0.5", "pcj", "pYYq"]))
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    mesh = deltamesh.triangulate(tri, opts)
            except (ValueError, deltamesh.Error):
                outcomes["error"] += 1
                continue
            outcomes["ok"] += 1
            if "triangles" not in mesh:  # collinear points, or all eaten: no rows, no key
                self.assertIn("vertices", mesh)
                continue
            deltamesh.validate(mesh, delaunay=False)
            for fn in (deltamesh.check, deltamesh.quality):
                try:
                    fn(dict(tri, triangles=tri.get("triangles", mesh["triangles"])))
                except (ValueError, deltamesh.Error):
                    pass
        self.assertGreater(outcomes["ok"], 20)
        self.assertGreater(outcomes["error"], 20)


class DictAndKeywords(unittest.TestCase):
    def assert_same(self, a, b):
        self.assertEqual(set(a) - {"stats"}, set(b) - {"stats"})
        for key in a:
            if key != "stats":
                np.testing.assert_array_equal(a[key], b[key], err_msg=key)

    def test_forms_agree(self):
        sq = square_with_hole()
        self.assert_same(quiet_triangulate(sq, "pq30a0.01"),
                         quiet_triangulate(sq["vertices"], sq["segments"], sq["holes"],
                                           segment_markers=sq["segment_markers"], min_angle=30, max_area=0.01))
        self.assert_same(quiet_triangulate({"vertices": sq["vertices"]}, "en"),
                         quiet_triangulate(sq["vertices"], edges=True, neighbors=True))
        r = two_regions()
        self.assert_same(quiet_triangulate(r, "pq28aA --cdt=lawson --steiner=offcenter"),
                         quiet_triangulate(r["vertices"], r["segments"], regions=r["regions"], min_angle=28,
                                           regional_area=True, regional_attributes=True,
                                           steiner="offcenter", cdt="lawson"))
        # -YY: no Steiner points on segments, so the 28 degree bound is not reached (a result, not an error)
        yy = deltamesh.triangulate(r, "pq28YYQ")
        self.assert_same(yy, deltamesh.triangulate(r["vertices"], r["segments"], regions=r["regions"], min_angle=28,
                                                   segment_splitting="none", quiet=True))
        deltamesh.validate(yy)
        self.assertEqual(edge_set(yy["segments"]), edge_set(r["segments"]))
        # a leading '-' is allowed, and the result can be passed back in (stats etc. ignored)
        self.assert_same(quiet_triangulate(sq, "-pc"), quiet_triangulate(sq, "pc"))
        self.assert_same(quiet_triangulate(quiet_triangulate(sq, "pen"), "p"), quiet_triangulate(sq, "p"))

    def test_regional_attributes_and_area_bounds(self):
        r = two_regions()
        mesh = quiet_triangulate(r, "pqaA")
        deltamesh.validate(mesh)
        attr, c, a = mesh["triangle_attributes"][:, 0], centroids(mesh), areas(mesh)
        np.testing.assert_array_equal(attr, np.where(c[:, 0] < 0.5, 1.0, 2.0))
        self.assertLessEqual(a[attr == 1].max(), 0.01 * (1 + 1e-12))
        self.assertLessEqual(a[attr == 2].max(), 0.05 * (1 + 1e-12))
        self.assertAlmostEqual(a[attr == 1].sum(), 0.5, places=12)
        self.assertAlmostEqual(a[attr == 2].sum(), 0.5, places=12)
        self.assertGreater((attr == 1).sum(), (attr == 2).sum())
        # O ignores the hole; without p there are no regions or holes
        sq = square_with_hole()
        self.assertAlmostEqual(areas(quiet_triangulate(sq, "pO")).sum(), 1.0, places=12)
        with self.assertWarnsRegex(UserWarning, "-A has no effect"):  # said, not silent
            self.assertNotIn("triangle_attributes", deltamesh.triangulate(r, "A"))

    def test_threads_give_the_same_mesh(self):
        sq = square_with_hole()
        expected = quiet_triangulate(sq, "pq30a0.001")
        results = [None] * 4

        def work(i):
            results[i] = deltamesh.triangulate(sq, "pq30a0.001")
        threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        for r in results:
            deltamesh.validate(r)
            self.assert_same(r, expected)


class Adapt(unittest.TestCase):
    def setUp(self):
        self.fine = deltamesh.triangulate(square_with_hole(), "pq30a0.0002Q")

    def test_grades_a_fine_mesh_to_a_ramp(self):
        ramp = lambda x, y: 0.01 + 0.19 * x
        r = deltamesh.adapt(self.fine, ramp, "q30")
        deltamesh.validate(r, convex_hull=False)
        a = r["stats"]["adapt"]
        self.assertTrue(a["complete"])
        self.assertGreater(a["removed"], 0)
        self.assertLess(len(r["triangles"]), len(self.fine["triangles"]) / 2)
        self.assertGreaterEqual(min_angles(r).min(), 30 - 1e-9)
        self.assertAlmostEqual(areas(r).sum(), 0.96, places=12)
        # Finer on the left than on the right: mean area per strip grows with x.
        c = centroids(r)
        left, right = areas(r)[c[:, 0] < 0.2].mean(), areas(r)[c[:, 0] > 0.8].mean()
        self.assertGreater(right, 10 * left)
        # Segment markers of the input stay on its pieces.
        self.assertEqual(set(r["segment_markers"][:, 0]), {5, 7})

    def test_sizes_per_vertex_equal_the_function_at_the_vertices(self):
        v = self.fine["vertices"]
        by_array = deltamesh.adapt(self.fine, 0.01 + 0.19 * v[:, 0], "q30")
        by_function = deltamesh.adapt(self.fine, lambda x, y: 0.01 + 0.19 * x, "q30")
        deltamesh.validate(by_array, convex_hull=False)
        # Linear in x: interpolation over the triangles is exact (to rounding).
        self.assertLess(abs(len(by_array["triangles"]) - len(by_function["triangles"])),
                        0.02 * len(by_function["triangles"]))

    def test_smoothing_raises_the_mean_angle(self):
        h = lambda x, y: 0.05
        rough = deltamesh.adapt(self.fine, h, "q30", smooth=0)
        smooth = deltamesh.adapt(self.fine, h, "q30", smooth=3)
        deltamesh.validate(smooth, convex_hull=False)
        self.assertEqual(rough["stats"]["adapt"]["smoothed"], 0)
        self.assertGreater(smooth["stats"]["adapt"]["smoothed"], 0)
        self.assertGreater(min_angles(smooth).mean(), min_angles(rough).mean())
        self.assertGreaterEqual(min_angles(smooth).min(), 30 - 1e-9)

    def test_sizes_per_vertex_when_segments_add_vertices(self):
        """Vertices that inserting the mesh's segments adds (here where the
        two diagonals cross) take their neighbours' mean size, as with the
        command line's --adapt; before, per-vertex sizes were refused."""
        square = dict(vertices=[[0, 0], [1, 0], [1, 1], [0, 1]], triangles=[[0, 1, 2], [0, 2, 3]],
                      segments=[[0, 2], [1, 3]], segment_markers=[3, 4])
        by_array = deltamesh.adapt(square, [0.1] * 4, "q30")
        by_function = deltamesh.adapt(square, lambda x, y: 0.1, "q30")
        deltamesh.validate(by_array, convex_hull=False)
        self.assertTrue(np.array_equal(by_array["vertices"], by_function["vertices"]))
        self.assertTrue(np.array_equal(by_array["triangles"], by_function["triangles"]))
        self.assertTrue((np.abs(by_array["vertices"] - [0.5, 0.5]).max(axis=1) == 0).any())

    def test_bad_sizes_and_switches(self):
        v = self.fine["vertices"]
        with self.assertRaisesRegex(ValueError, "size: has 3 values, expected one per vertex"):
            deltamesh.adapt(self.fine, [1.0, 2.0, 3.0])
        with self.assertRaisesRegex(deltamesh.InputError, "not a positive number"):
            deltamesh.adapt(self.fine, -np.ones(len(v)))
        with self.assertRaisesRegex(ValueError, "size returned nan"):
            deltamesh.adapt(self.fine, lambda x, y: math.nan)
        with self.assertRaisesRegex(ZeroDivisionError, "division"):
            deltamesh.adapt(self.fine, lambda x, y: 1 / 0)
        with self.assertRaisesRegex(ValueError, "switches r, o2 and D"):
            deltamesh.adapt(self.fine, lambda x, y: 0.1, "rq30")
        with self.assertRaisesRegex(ValueError, "needs 'triangles'"):
            deltamesh.adapt(square_with_hole(), lambda x, y: 0.1)
        with self.assertRaisesRegex(ValueError, "use deltamesh.adapt"):
            deltamesh.triangulate(square_with_hole(), "pq30 --smooth=2")


class Gil(unittest.TestCase):
    def test_gil_is_released_while_meshing(self):
        """The main thread runs Python while another thread meshes (~0.3 s): with
        the GIL held it could not return from wait() before the meshing ended."""
        started = threading.Event()
        times = {}

        def mesh():
            pslg = square_with_hole()
            times["start"] = time.perf_counter()
            started.set()
            m = deltamesh.triangulate(pslg, "pq30a0.000004Q")
            times["end"] = time.perf_counter()
            times["triangles"] = len(m["triangles"])
        th = threading.Thread(target=mesh)
        th.start()
        started.wait()
        times["main"] = time.perf_counter()
        th.join()
        self.assertGreater(times["triangles"], 200000)
        # Held GIL: main resumes only as the call returns (measured: at 99.7%
        # of it); released: at once. 0.9 leaves room for a loaded machine.
        self.assertLess(times["main"] - times["start"], 0.9 * (times["end"] - times["start"]))


class Errors(unittest.TestCase):
    def test_bad_arrays_name_the_argument(self):
        cases = [
            (dict(vertices=np.zeros((4, 3))), "vertices: expected an array of shape \\(n, 2\\)"),
            (dict(vertices=[[0, 0], [1, math.nan], [0, 1]]), "vertices: row 1 holds nan"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], segments=[[0, 3]]), "segments: index 3 .* out of range"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], segments=[[0, -1]]), "segments: index -1"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], segments=[[0, 1.5]]), "segments: value 1.5 in row 0 is not a whole"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], segments=[["a", "b"]]), "segments: expected integers"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], vertex_markers=[1, 2]), "vertex_markers: has 2 rows, expected 3"),
            (dict(vertices=[["a", "b"]]), "vertices: expected numbers"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], holes=[[math.inf, 0]]), "holes: row 0 holds inf"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], vertice=[]), "unknown key 'vertice'"),
            (dict(segments=[[0, 1]]), "vertices: required"),
            (dict(vertices=np.zeros((5, 0))), "vertices: expected an array of shape \\(n, 2\\), got shape \\(5, 0\\)"),
            (dict(vertices=np.float64(1)), "vertices: expected an array of shape"),
            (dict(vertices=[[0, 0], [1, 0], [0, 1]], vertex_attributes=[]), "vertex_attributes: has 0 rows, expected 3"),
        ]
        for tri, message in cases:
            with self.subTest(message=message), self.assertRaisesRegex(ValueError, message):
                deltamesh.triangulate(tri, "p")

    def test_switches(self):
        sq = square_with_hole()
        for opts, message in [("pk", "unknown switch -k"), ("pq30x", "unknown switch -x"),
                              ("pa-1", "unknown switch --"), ("p1", "does not follow a switch"),
                              ("ph", "-h"), ("p --svg=x.svg", "--svg"),
                              ("p --cdt", "needs a value"), ("p --cdt=x", "fast, ct, lawson or lifting")]:
            with self.subTest(opts=opts), self.assertRaisesRegex(ValueError, message):
                deltamesh.triangulate(sq, opts)
        for kw, message in [(dict(min_angle="x"), "min_angle"), (dict(max_area=-1), "max_area: .*positive"),
                            (dict(cdt="foo"), "cdt: "), (dict(segment_splitting="some"), "segment_splitting")]:
            with self.subTest(kw=kw), self.assertRaisesRegex(ValueError, message):
                deltamesh.triangulate(sq["vertices"], sq["segments"], **kw)

    def test_library_errors_are_typed(self):
        with self.assertRaisesRegex(deltamesh.InputError, "point") as cm:
            deltamesh.triangulate(dict(vertices=[[0, 0], [1, 0]]))
        self.assertIsInstance(cm.exception, ValueError)
        self.assertIsInstance(cm.exception, deltamesh.Error)
        # A bug (a broken invariant) is not the input's fault: its own class.
        self.assertTrue(issubclass(deltamesh.InternalError, deltamesh.Error))
        self.assertFalse(issubclass(deltamesh.InternalError, deltamesh.InputError))
        with self.assertRaises(deltamesh.InputError):
            deltamesh.triangulate(dict(vertices=np.zeros((0, 2))))
        # zero attribute columns are fine
        mesh = quiet_triangulate(dict(vertices=[[0, 0], [1, 0], [0, 1]], vertex_attributes=np.zeros((3, 0))))
        self.assertNotIn("vertex_attributes", mesh)
        deltamesh.validate(mesh)
        crossing = dict(vertices=[[0, 0], [2, 2], [0, 2], [2, 0]], segments=[[0, 1], [2, 3]])
        with self.assertRaises(deltamesh.IntersectingSegments) as cm:
            deltamesh.triangulate(crossing, "p --strict")
        self.assertEqual((cm.exception.first, cm.exception.second), (0, 1))
        # without --strict the crossing gets a vertex
        mesh = quiet_triangulate(crossing, "pc")
        deltamesh.validate(mesh)
        self.assertTrue((np.abs(mesh["vertices"] - [1, 1]).max(axis=1) < 1e-15).any())

    def test_check_finds_broken_meshes(self):
        good = quiet_triangulate(dict(vertices=[[0, 0], [1, 0], [1, 1], [0, 1.2]]))
        self.assertTrue(deltamesh.check(good)["ok"])
        flipped = dict(good, triangles=good["triangles"][:, ::-1].copy())
        report = deltamesh.check(flipped)
        self.assertFalse(report["ok"])
        self.assertRegex(report["problems"][0], "clockwise")
        # The other diagonal of a quadrilateral whose Delaunay diagonal is unique.
        t = good["triangles"]
        d = set(t[0]) & set(t[1])
        other = sorted(set(range(4)) - d)
        a, b = sorted(d)
        bad = dict(vertices=good["vertices"],
                   triangles=np.array([[other[0], other[1], a], [other[1], other[0], b]]))
        for tri in bad["triangles"]:  # orient counter-clockwise
            p = good["vertices"][tri]
            if (p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) - (p[1, 1] - p[0, 1]) * (p[2, 0] - p[0, 0]) < 0:
                tri[[1, 2]] = tri[[2, 1]]
        report = deltamesh.check(bad)
        self.assertFalse(report["ok"])
        self.assertTrue(any("Delaunay" in p for p in report["problems"]), report["problems"])
        self.assertTrue(deltamesh.check(bad, delaunay=False)["ok"])
        with self.assertRaises(deltamesh.CheckError) as cm:
            deltamesh.validate(bad)
        self.assertTrue(cm.exception.problems)
        # overlapping triangles are reported, not a crash
        overlap = dict(vertices=[[0, 0], [1, 0], [0, 1], [1, 1]], triangles=[[0, 1, 2], [0, 1, 3]])
        self.assertFalse(deltamesh.check(overlap)["ok"])
        # a segment that is not an edge
        seg = dict(good, segments=[[other[0], other[1]]])
        self.assertFalse(deltamesh.check(seg)["ok"])


class Files(unittest.TestCase):
    def test_triangle_files_round_trip(self):
        mesh = quiet_triangulate(two_regions(), "pq30a0.02A")
        deltamesh.validate(mesh)
        with tempfile.TemporaryDirectory() as d:
            base = os.path.join(d, "m")
            for ext in (".node", ".ele", ".poly"):
                deltamesh.write(mesh, base + ext)
            back = deltamesh.read(base + ".node")
            deltamesh.validate(back)
            np.testing.assert_array_equal(back["vertices"], mesh["vertices"])  # exact: written round-trip precise
            np.testing.assert_array_equal(back["triangles"], mesh["triangles"])
            np.testing.assert_array_equal(back["vertex_markers"], mesh["vertex_markers"])
            np.testing.assert_array_equal(back["triangle_attributes"], mesh["triangle_attributes"])
            self.assertEqual(edge_set(back["segments"]), edge_set(mesh["segments"]))
            np.testing.assert_array_equal(back["regions"], mesh["regions"])
            # one-based files read back the same
            deltamesh.write(mesh, base + "1.node", first_index=1)
            deltamesh.write(mesh, base + "1.ele", first_index=1)
            np.testing.assert_array_equal(deltamesh.read(base + "1.ele")["triangles"], mesh["triangles"])
            # the .poly as a PSLG meshes again to the same triangles
            again = quiet_triangulate(deltamesh.read(base), "pq30a0.02A")
            deltamesh.validate(again)
            for ext in (".msh", ".vtu", ".svg", ".off"):
                deltamesh.write(mesh, base + ext)
                self.assertGreater(os.path.getsize(base + ext), 100)
            with self.assertRaisesRegex(ValueError, "cannot tell the output format"):
                deltamesh.write(mesh, base + ".xyz")
        with self.assertRaises(deltamesh.IoError):
            deltamesh.write(mesh, os.path.join(d, "gone", "m.node"))

    def test_write_refuses_segments_that_are_not_edges(self):
        """Inserting such a segment would change the triangles: the file would not hold the mesh given."""
        square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
        mesh = dict(vertices=square, triangles=[[0, 1, 2], [0, 2, 3]], segments=[[1, 3]])
        self.assertFalse(deltamesh.check(mesh)["ok"])
        with tempfile.TemporaryDirectory() as d:
            for ext in (".ele", ".poly", ".vtu"):
                path = os.path.join(d, "m" + ext)
                with self.assertRaisesRegex(ValueError, "segments: .*not an edge"):
                    deltamesh.write(mesh, path)
                self.assertFalse(os.path.exists(path))
            # segments that are chains of edges are written as they are
            good = dict(vertices=square, triangles=[[0, 1, 2], [0, 2, 3]], segments=[[0, 2]])
            deltamesh.validate(good)
            for ext in (".node", ".ele"):
                deltamesh.write(good, os.path.join(d, "g" + ext))
            np.testing.assert_array_equal(deltamesh.read(os.path.join(d, "g.ele"))["triangles"], good["triangles"])

    def test_read_errors(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bad.poly")
            with open(path, "w") as f:
                f.write("3 2 0 0\n1 0 0\n2 1 zero\n3 0 1\n0 0\n0\n")
            with self.assertRaises(deltamesh.ParseError) as cm:
                deltamesh.read(path)
            self.assertEqual(cm.exception.line, 3)
            self.assertIn("bad.poly:3", str(cm.exception))
            for missing in ("missing.poly", "missing.node", "missing"):
                with self.assertRaisesRegex(deltamesh.IoError, "missing"):
                    deltamesh.read(os.path.join(d, missing))


class Docs(unittest.TestCase):
    def test_docs_example_runs(self):
        """The example in docs/python.md runs and prints what the text says it checks."""
        doc = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "python.md")
        with open(doc) as f:
            code = re.search(r"```python\n(.*?)```", f.read(), re.S).group(1)
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(code, doc, "exec"), {})
        lines = out.getvalue().splitlines()
        self.assertEqual(len(lines), 4)
        self.assertTrue(lines[1].startswith("True "))  # complete
        self.assertGreaterEqual(float(lines[1].split()[2]), 30)  # smallest angle
        self.assertTrue(lines[2].startswith("mesh is valid"))
        self.assertEqual(lines[3], "True")  # dict and keyword forms agree

    def test_check_switch_reports(self):
        mesh, st = quiet_triangulate(square_with_hole(), "pq30C", stats=True)
        self.assertRegex(st["check"], "^mesh is valid")
        deltamesh.validate(mesh)


if __name__ == "__main__":
    unittest.main()

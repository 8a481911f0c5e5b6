"""Tests of the Python bindings (stdlib unittest; ctest runs them with the
interpreter the module was built for and PYTHONPATH=<build>/python).

Every mesh produced here goes through deltamesh.validate (the library's exact
validator, on the arrays returned), and properties are asserted as bounds.
"""
import math
import os
import tempfile
import unittest
import warnings

import numpy as np

import deltamesh


from binding_support import ARRAY_DTYPES, areas, centroids, edge_set, min_angles, quiet_triangulate, square_with_hole, two_regions


class Shapes(unittest.TestCase):
    def assert_layout(self, mesh):
        for key, value in mesh.items():
            if key == "stats":
                self.assertIsInstance(value, dict)
                continue
            self.assertIsInstance(value, np.ndarray, key)
            self.assertEqual(value.dtype, ARRAY_DTYPES[key], key)
            self.assertEqual(value.ndim, 2, key)
        n, m = len(mesh["vertices"]), len(mesh["triangles"])
        self.assertEqual(mesh["vertices"].shape, (n, 2))
        self.assertEqual(mesh["vertex_markers"].shape, (n, 1))
        self.assertIn(mesh["triangles"].shape[1], (3, 6))
        self.assertTrue(((mesh["triangles"] >= 0) & (mesh["triangles"] < n)).all())
        if "triangle_attributes" in mesh:
            self.assertEqual(len(mesh["triangle_attributes"]), m)
        if "segments" in mesh:
            self.assertEqual(mesh["segment_markers"].shape, (len(mesh["segments"]), 1))

    def test_every_switch_output_has_triangle_layout(self):
        mesh = quiet_triangulate(square_with_hole(), "pq25enA")
        deltamesh.validate(mesh)
        self.assert_layout(mesh)
        for key in ("segments", "edges", "edge_markers", "neighbors", "holes"):
            self.assertIn(key, mesh)
        self.assertEqual(mesh["neighbors"].shape, mesh["triangles"].shape)

    def test_delaunay_of_points_has_no_segments_and_euler_count(self):
        rng = np.random.default_rng(7)
        pts = rng.random((300, 2))
        mesh = quiet_triangulate({"vertices": pts}, "n")
        self.assert_layout(mesh)
        self.assertNotIn("segments", mesh)
        deltamesh.validate(mesh, convex_hull=True)
        # Triangles of a Delaunay triangulation: 2n - 2 - h (h hull edges = -1 neighbours).
        h = int((mesh["neighbors"] == -1).sum())
        self.assertEqual(len(mesh["triangles"]), 2 * len(pts) - 2 - h)
        np.testing.assert_array_equal(mesh["vertices"], pts)  # input vertices keep their ids

    def test_threads_give_the_same_triangles_and_bad_counts_raise(self):
        # 120000 points: two slabs with threads=2 (50000 points per thread at least).
        rng = np.random.default_rng(11)
        pts = rng.random((120000, 2))
        one = quiet_triangulate({"vertices": pts}, "", threads=1)
        two = quiet_triangulate({"vertices": pts}, "", threads=2)
        deltamesh.validate(two, convex_hull=True)
        canon = lambda t: sorted(map(tuple, np.sort(t, axis=1).tolist()))
        self.assertEqual(canon(one["triangles"]), canon(two["triangles"]))
        again = quiet_triangulate({"vertices": pts}, "t2")
        np.testing.assert_array_equal(again["triangles"], two["triangles"])
        kw = deltamesh.triangulate(pts[:100], threads=3, quiet=True)
        deltamesh.validate(kw, convex_hull=True)
        with self.assertRaises(ValueError):
            deltamesh.triangulate({"vertices": pts[:10]}, "", threads=-1)
        with self.assertRaises(TypeError):
            deltamesh.triangulate({"vertices": pts[:10]}, "", threads="2")

    def test_neighbors_are_symmetric_and_edges_match_triangles(self):
        mesh = quiet_triangulate(square_with_hole(), "pq30a0.02en")
        deltamesh.validate(mesh)
        t, nb = mesh["triangles"], mesh["neighbors"]
        for i in range(len(t)):
            for k in range(3):
                j = nb[i, k]
                if j < 0:
                    continue
                self.assertIn(i, nb[j])
                # neighbour k lies across the edge opposite vertex k
                shared = set(t[i]) - {t[i, k]}
                self.assertEqual(shared, set(t[i]) & set(t[j]))
        tri_edges = edge_set(np.vstack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]))
        self.assertEqual(edge_set(mesh["edges"]), tri_edges)
        self.assertEqual(len(tri_edges), len(mesh["edges"]))  # each edge once
        # The square with a hole is an annulus: V - E + F = 0 on the vertices used.
        used = len(np.unique(t))
        self.assertEqual(used - len(mesh["edges"]) + len(t), 0)
        # Boundary edges (one triangle) are exactly the segments here.
        self.assertEqual(int((nb == -1).sum()), len(mesh["segments"]))


class Quality(unittest.TestCase):
    def test_square_with_hole_q30_a(self):
        mesh, st = quiet_triangulate(square_with_hole(), "pq30a0.01", stats=True)
        self.assertNotIn("stats", mesh)
        report = deltamesh.validate(mesh)
        self.assertTrue(report["ok"])
        self.assertEqual(report["segments_checked"], len(mesh["segments"]))
        self.assertTrue(st["complete"])
        self.assertEqual(st["steiner_points"], len(mesh["vertices"]) - 8)
        self.assertGreater(st["steiner_points"], 20)
        # Angles: no input angle below 60 degrees here, so every triangle meets the bound.
        self.assertGreaterEqual(min_angles(mesh).min(), 30 - 1e-9)
        self.assertAlmostEqual(st["min_angle"], min_angles(mesh).min(), places=9)
        a = areas(mesh)
        self.assertTrue((a > 0).all())
        self.assertLessEqual(a.max(), 0.01 * (1 + 1e-12))
        self.assertAlmostEqual(a.sum(), 1 - 0.04, places=12)
        # Nothing inside the hole; markers carried to every subsegment.
        c = centroids(mesh)
        self.assertFalse((np.abs(c - 0.5) < 0.1).all(axis=1).any())
        s, sm = mesh["segments"], mesh["segment_markers"][:, 0]
        v = mesh["vertices"]
        on_outer = np.isin(v[s], [0.0, 1.0]).any(axis=2).all(axis=1)
        self.assertEqual(set(sm[on_outer]), {5})
        self.assertEqual(set(sm[~on_outer]), {7})
        q = deltamesh.quality(mesh, min_angle=30, max_area=0.01)
        self.assertEqual((q["below_angle"], q["above_area"]), (0, 0))
        self.assertEqual(sum(q["angle_histogram"]), 3 * len(mesh["triangles"]))
        # stats' angles (a cheaper pass) are the quality report's
        self.assertAlmostEqual(st["min_angle"], q["min_angle"], places=12)
        self.assertAlmostEqual(st["max_angle"], q["max_angle"], places=12)

    def test_budget_stops_with_a_warning_and_a_valid_mesh(self):
        with self.assertWarnsRegex(UserWarning, "Steiner budget"):
            mesh, st = deltamesh.triangulate(square_with_hole(), "pq30S5", stats=True)
        deltamesh.validate(mesh)
        self.assertFalse(st["complete"])
        self.assertTrue(st["refine"]["budget_exhausted"])
        self.assertLessEqual(st["steiner_points"], 5)
        # Q silences it.
        quiet_triangulate(square_with_hole(), "pq30S5Q")

    def test_bound_out_of_reach_stops_early_and_says_where(self):
        # Above 34 degrees refinement watches its progress; at 45 on this
        # domain it stalls, keeps the mesh refined to 34 and reports it.
        with self.assertWarnsRegex(UserWarning, "45° out of reach"):
            mesh, st = deltamesh.triangulate(square_with_hole(), "pq45", stats=True)
        deltamesh.validate(mesh)
        r = st["refine"]
        self.assertFalse(st["complete"])
        self.assertTrue(r["stalled"])
        self.assertGreater(r["below_out_of_reach"], 0)
        self.assertGreaterEqual(r["reached_angle"], 34.0)
        self.assertLess(r["reached_angle"], 45.0)
        self.assertEqual(len(r["stall_center"]), 2)
        self.assertGreater(r["stall_radius"], 0.0)
        self.assertGreaterEqual(min(min_angles(mesh)), 34.0 - 1e-9)

    def test_size_function(self):
        def f(x, y):
            return 0.001 if x < 0.3 else 0.05
        mesh = quiet_triangulate(square_with_hole(), "pq20", max_area_fn=f)
        deltamesh.validate(mesh)
        a, c = areas(mesh), centroids(mesh)
        bound = np.where(c[:, 0] < 0.3, 0.001, 0.05)
        self.assertTrue((a <= bound * (1 + 1e-9)).all())
        self.assertGreater((c[:, 0] < 0.3).sum(), 300)  # about 0.3 / 0.001 triangles there
        with self.assertRaises(ZeroDivisionError):  # the callback's own exception comes through
            deltamesh.triangulate(square_with_hole(), "pq", max_area_fn=lambda x, y: 1 / 0)
        with self.assertRaises(TypeError):
            deltamesh.triangulate(square_with_hole(), "pq", max_area_fn=lambda x, y: "small")
        with self.assertRaisesRegex(ValueError, "max_area_fn returned nan"):
            deltamesh.triangulate(square_with_hole(), "pq", max_area_fn=lambda x, y: math.nan)

    def test_refine_a_mesh_with_r(self):
        coarse = quiet_triangulate(square_with_hole(), "pq30")
        fine = quiet_triangulate(coarse, "rpq30a0.002")
        deltamesh.validate(fine)
        self.assertLessEqual(areas(fine).max(), 0.002 * (1 + 1e-12))
        self.assertAlmostEqual(areas(fine).sum(), 0.96, places=12)
        self.assertGreater(len(fine["triangles"]), 0.96 / 0.002)
        # the coarse vertices keep their ids
        np.testing.assert_array_equal(fine["vertices"][:len(coarse["vertices"])], coarse["vertices"])
        with self.assertRaisesRegex(ValueError, "triangles"):
            deltamesh.triangulate(square_with_hole(), "rq")

    def test_refine_with_p_warns_as_the_command_line_does(self):
        """'rp' reports region points it could not use and a mesh emptied by a hole (the CLI's warnings)."""
        coarse = quiet_triangulate(two_regions(), "pq30")
        outside = dict(coarse, regions=[[.25, .5, 1, -1], [3, 3, 2, -1]])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh, st = deltamesh.triangulate(outside, "rpA", stats=True)
        deltamesh.validate(mesh)
        self.assertEqual(st["regions_ignored"], 1)
        self.assertIn("region point 1 at (3, 3) ignored", st["warnings"][0])  # 0-based, as given
        self.assertTrue(any("region point 1 at (3, 3) ignored" in str(w.message) for w in caught))
        # a hole point in a closed region with no segment left around it eats the mesh
        emptied = dict(coarse, segments=np.zeros((0, 2), int), holes=[[.25, .5]])
        emptied.pop("segment_markers")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh = deltamesh.triangulate(emptied, "rp")
        self.assertNotIn("triangles", mesh)  # no rows: left out, as Triangle's package does
        self.assertTrue(any("every triangle was removed" in str(w.message) for w in caught))

    def test_second_order_midpoints(self):
        mesh = quiet_triangulate(square_with_hole(), "pq30o2")
        self.assertEqual(mesh["triangles"].shape[1], 6)
        deltamesh.validate(mesh)
        v, t = mesh["vertices"], mesh["triangles"]
        for k in range(3):  # node 3 + k is the midpoint of the edge opposite corner k
            mid = (v[t[:, (k + 1) % 3]] + v[t[:, (k + 2) % 3]]) / 2
            np.testing.assert_allclose(v[t[:, 3 + k]], mid, rtol=0, atol=1e-15)

    def test_conforming_delaunay_and_jettison(self):
        pslg = square_with_hole()
        pslg["vertices"] = np.vstack([pslg["vertices"], [[.45, .5], [.45, .5]]])  # a point in the hole, twice
        mesh = quiet_triangulate(pslg, "pDj")
        deltamesh.validate(mesh)
        # -j drops the vertices in no triangle
        self.assertEqual(len(np.unique(mesh["triangles"])), len(mesh["vertices"]))
        # -D: Delaunay even across segments
        deltamesh.validate({k: mesh[k] for k in ("vertices", "triangles")})


class PointSets(unittest.TestCase):
    """delaunay(), convex_hull() and voronoi(), the `triangle` package's helpers."""

    def setUp(self):
        # integer coordinates: the numpy orientation tests below are exact
        self.pts = np.random.default_rng(11).integers(0, 1000, size=(200, 2)).astype(float)

    def test_delaunay_is_triangulate_without_switches(self):
        tris = deltamesh.delaunay(self.pts)
        self.assertEqual((tris.dtype, tris.shape[1]), (np.int32, 3))
        np.testing.assert_array_equal(tris, quiet_triangulate({"vertices": self.pts})["triangles"])
        deltamesh.validate(dict(vertices=self.pts, triangles=tris), convex_hull=True)

    def test_convex_hull_edges_enclose_every_point(self):
        hull = deltamesh.convex_hull(self.pts)
        p, q = self.pts[hull[:, 0]], self.pts[hull[:, 1]]
        for x in self.pts:  # every point on the right of or on every hull edge (Triangle's orientation)
            side = (q[:, 0] - p[:, 0]) * (x[1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (x[0] - p[:, 0])
            self.assertTrue((side <= 0).all())
        # one closed cycle: each hull vertex starts one edge and ends one
        self.assertEqual(sorted(hull[:, 0]), sorted(hull[:, 1]))
        nxt = dict(hull)
        v, steps = hull[0, 0], 0
        while True:
            v, steps = nxt[v], steps + 1
            if v == hull[0, 0]:
                break
        self.assertEqual(steps, len(hull))

    def test_voronoi_is_the_dual(self):
        tris = deltamesh.delaunay(self.pts)
        points, edges, ray_origins, ray_directions = deltamesh.voronoi(self.pts)
        self.assertEqual(len(points), len(tris))
        # each Voronoi vertex is equidistant from its triangle's corners
        d = np.linalg.norm(self.pts[tris] - points[:, None, :], axis=2)
        np.testing.assert_allclose(d, d[:, :1].repeat(3, axis=1), rtol=1e-9)
        n_edges = len(edge_set(np.vstack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])))
        self.assertEqual(len(edges) + len(ray_origins), n_edges)
        self.assertTrue(((edges >= 0) & (edges < len(points))).all())
        hull = deltamesh.convex_hull(self.pts)
        self.assertEqual(len(ray_origins), len(hull))
        self.assertEqual(ray_directions.shape, (len(hull), 2))
        # a ray is as long as its hull edge (Triangle's convention)
        lengths = np.sort(np.linalg.norm(self.pts[hull[:, 0]] - self.pts[hull[:, 1]], axis=1))
        np.testing.assert_allclose(np.sort(np.linalg.norm(ray_directions, axis=1)), lengths, rtol=1e-12)


class UnmetBounds(unittest.TestCase):
    """One rule (docs/robustness.md, exit codes): an unmet angle or size bound
    makes the result incomplete, with the counts and reasons, as the CLI's exit 3."""

    def test_y_forbidding_splits_is_incomplete_with_the_reason(self):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh, st = deltamesh.triangulate(square_with_hole(), "pq33Y", stats=True)
        deltamesh.validate(mesh)
        r = st["refine"]
        below = (min_angles(mesh) < 33).sum()
        if below == 0:
            self.skipTest("-Y met the bound here")
        self.assertFalse(st["complete"])
        self.assertGreater(r["below_segment_protected"], 0)
        self.assertIn("-Y/-YY forbids", r["unmet"])
        self.assertTrue(any("refinement stopped" in str(w.message) for w in caught))
        _, ok = quiet_triangulate(square_with_hole(), "pq33", stats=True)
        self.assertTrue(ok["complete"])
        self.assertEqual(ok["refine"]["unmet"], "")

    def test_any_scale_gives_the_same_mesh(self):
        base, base_st = quiet_triangulate(square_with_hole(), "pq30", stats=True)
        for k in (-1000, -60, 60, 1000):
            shape = square_with_hole()
            s = math.ldexp(1.0, k)
            shape["vertices"] = np.asarray(shape["vertices"], dtype=float) * s
            shape["holes"] = np.asarray(shape["holes"], dtype=float) * s
            mesh, st = quiet_triangulate(shape, "pq30", stats=True)
            np.testing.assert_array_equal(mesh["vertices"], base["vertices"] * s)
            np.testing.assert_array_equal(mesh["triangles"], base["triangles"])
            self.assertTrue(st["complete"])
            self.assertEqual(st["refine"]["below_bound"], base_st["refine"]["below_bound"])


class RandomInputs(unittest.TestCase):
    def test_seeded_random_pslgs(self):
        """Random points with random (crossing) segments on a coarse grid, so that
        collinear and duplicate points and segments through vertices occur; every
        result validates, covers the hull and keeps the bounds."""
        for seed in range(25):
            with self.subTest(seed=seed):
                rng = np.random.default_rng(seed)
                n = int(rng.integers(3, 40))
                pts = rng.integers(0, 8, size=(n, 2)).astype(float) * (10.0 ** rng.integers(-6, 7))
                if len(np.unique(pts, axis=0)) < 3:
                    continue
                segs = rng.integers(0, n, size=(int(rng.integers(0, 15)), 2))
                segs = segs[segs[:, 0] != segs[:, 1]]
                try:
                    mesh, st = deltamesh.triangulate(dict(vertices=pts, segments=segs), "pcq25Q", stats=True)
                except deltamesh.InputError as e:
                    self.fail(str(e))
                if "triangles" not in mesh:  # all points collinear: the vertices only
                    self.assertEqual(st["triangles"], 0)
                    np.testing.assert_array_equal(mesh["vertices"], pts)
                    continue
                deltamesh.validate(mesh)
                self.assertGreater(len(mesh["triangles"]), 0)
                a = areas(mesh)
                self.assertTrue((a > 0).all())
                # with -c the domain is the convex hull of the input points
                lo, hi = pts.min(0), pts.max(0)
                self.assertTrue(((mesh["vertices"] >= lo) & (mesh["vertices"] <= hi)).all())
                np.testing.assert_array_equal(mesh["vertices"][:n], pts)
                # the refiner's count of triangles below the bound is what the arrays show,
                # and each of them has a reason (small input angle, precision, ...)
                r, ma = st["refine"], min_angles(mesh)
                # complete, or only triangles at the precision of doubles left (an unmet bound)
                self.assertTrue(st["complete"] or (r["below_precision"] > 0 and not r["budget_exhausted"]))
                self.assertLessEqual((ma < 25 - 1e-9).sum(), r["below_bound"])
                self.assertLessEqual(r["below_bound"], (ma < 25 + 1e-9).sum())
                self.assertEqual(r["below_bound"], r["below_small_input_angle"] + r["below_segment_protected"] +
                                 r["below_budget"] + r["below_precision"])



class Trace(unittest.TestCase):
    """trace=PATH writes the run's steps (docs/trace.md); replayed by its
    rules alone they give the returned mesh."""

    @staticmethod
    def replay(path):
        import json
        points, tris = {}, set()
        with open(path) as f:
            head = json.loads(f.readline())
            assert head == {"trace": "deltamesh", "version": 1}, head
            for line in f:
                ev = json.loads(line)
                if ev["ev"] == "points":
                    for i, p in enumerate(ev["points"]):
                        points[ev["first"] + i] = tuple(p)
                if "v" in ev and "p" in ev:
                    points[ev["v"]] = tuple(ev["p"])
                if ev["ev"] == "renumber":
                    new = {j: points[j] for j in range(ev["vertices"]) if j in points}
                    done = set()
                    for i, to in enumerate(ev["map"]):
                        if to >= 0 and to not in done:
                            new[to] = points[i]
                            done.add(to)
                    points = new
                    tris = {tuple(ev["map"][v] for v in t) for t in tris}
                    tris = {Trace.canon(t) for t in tris}
                for t in ev.get("del", []):
                    tris.remove(Trace.canon(t))
                for t in ev.get("add", []):
                    tris.add(Trace.canon(t))
        return points, tris

    @staticmethod
    def canon(t):
        i = min(range(3), key=lambda k: t[k])
        return (t[i], t[(i + 1) % 3], t[(i + 2) % 3])

    def test_trace_replays_to_the_mesh(self):
        with tempfile.TemporaryDirectory() as d:
            for form in ("dict", "keywords"):
                path = os.path.join(d, form + ".jsonl")
                if form == "dict":
                    mesh = deltamesh.triangulate(square_with_hole(), "pq30a0.01Q", trace=path)
                else:
                    mesh = deltamesh.triangulate(**square_with_hole(), min_angle=30, max_area=0.01, quiet=True,
                                                 trace=path)
                deltamesh.validate(mesh)
                points, tris = self.replay(path)
                self.assertEqual(len(points), len(mesh["vertices"]))
                for v, p in enumerate(mesh["vertices"]):
                    self.assertEqual(points[v], (p[0], p[1]))
                self.assertEqual(tris, {self.canon(tuple(int(x) for x in t)) for t in mesh["triangles"]})

    def test_unwritable_trace_is_an_io_error_and_leaves_nothing(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "no", "such", "t.jsonl")
            with self.assertRaises(deltamesh.IoError):
                deltamesh.triangulate(square_with_hole(), "pQ", trace=path)
            self.assertFalse(os.path.exists(os.path.join(d, "no")))

if __name__ == "__main__":
    unittest.main()

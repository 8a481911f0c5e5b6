"""Tests of the Python bindings (stdlib unittest; ctest runs them with the
interpreter the module was built for and PYTHONPATH=<build>/python).

Every mesh produced here goes through deltamesh.validate (the library's exact
validator, on the arrays returned), and properties are asserted as bounds.
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

ARRAY_DTYPES = {
    "vertices": np.float64, "vertex_markers": np.int32, "vertex_attributes": np.float64,
    "triangles": np.int32, "triangle_attributes": np.float64, "segments": np.int32,
    "segment_markers": np.int32, "edges": np.int32, "edge_markers": np.int32, "neighbors": np.int32,
    "holes": np.float64, "regions": np.float64,
}


def square_with_hole():
    """Unit square with a 0.2 x 0.2 square hole in the middle; outer marker 5, hole marker 7."""
    return dict(
        vertices=np.array([[0, 0], [1, 0], [1, 1], [0, 1], [.4, .4], [.6, .4], [.6, .6], [.4, .6]], float),
        segments=np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]]),
        segment_markers=np.array([5, 5, 5, 5, 7, 7, 7, 7]),
        holes=np.array([[.5, .5]]),
    )


def two_regions():
    """Unit square split at x = 0.5 by an interior segment; region seeds with attributes 1 and 2
    and area bounds 0.01 and 0.05."""
    return dict(
        vertices=[[0, 0], [.5, 0], [1, 0], [1, 1], [.5, 1], [0, 1]],
        segments=[[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]],
        regions=[[.25, .5, 1, .01], [.75, .5, 2, .05]],
    )


def areas(mesh):
    v, t = mesh["vertices"], mesh["triangles"][:, :3]
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def min_angles(mesh):
    """Smallest angle of each triangle in degrees (law of cosines on edge vectors)."""
    v, t = mesh["vertices"], mesh["triangles"][:, :3]
    p = [v[t[:, k]] for k in range(3)]
    out = np.full(len(t), 180.0)
    for k in range(3):
        u, w = p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]
        cos = (u * w).sum(1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1))
        out = np.minimum(out, np.degrees(np.arccos(np.clip(cos, -1, 1))))
    return out


def centroids(mesh):
    v, t = mesh["vertices"], mesh["triangles"][:, :3]
    return (v[t[:, 0]] + v[t[:, 1]] + v[t[:, 2]]) / 3


def edge_set(pairs):
    return {tuple(sorted(map(int, e))) for e in pairs}


def quiet_triangulate(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an unexpected warning fails the test
        return deltamesh.triangulate(*args, **kwargs)


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

"""deltamesh.adapt(mesh, metric=...): anisotropic adaptation from Python
(docs/adapt.md). Every mesh produced here goes through deltamesh.validate."""
import math
import unittest

import numpy as np

import deltamesh


def layer(x, y):
    """A boundary layer along x = 0: size 0.003 + 0.1 x across it, 0.06 along it."""
    return (1 / (0.003 + 0.1 * x) ** 2, 0.0, 1 / 0.06 ** 2)


class MetricAdapt(unittest.TestCase):
    def setUp(self):
        square = dict(vertices=[[0, 0], [.5, 0], [1, 0], [1, 1], [.5, 1], [0, 1]],
                      segments=[[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]],
                      segment_markers=[1, 1, 2, 3, 3, 4, 5],
                      regions=[[.25, .5, 1, 0], [.75, .5, 2, 0]])
        self.mesh = deltamesh.triangulate(square, "pq25a0.01AQ")

    def check_result(self, r):
        deltamesh.validate(r, delaunay=False)
        a = r["stats"]["adapt"]
        self.assertGreaterEqual(a["edges_within"], 0.9, a["fit"])
        # Regions keep their attributes (the segment x = 0.5 separates them).
        c = r["vertices"][r["triangles"]].mean(axis=1)
        attr = r["triangle_attributes"][:, 0]
        self.assertTrue(np.all(attr[c[:, 0] < 0.5] == 1))
        self.assertTrue(np.all(attr[c[:, 0] > 0.5] == 2))
        # Input vertices are kept.
        for p in ([0, 0], [.5, 0], [1, 0], [1, 1], [.5, 1], [0, 1]):
            self.assertTrue(np.any(np.all(r["vertices"] == p, axis=1)), p)

    def test_array_and_function_give_anisotropic_meshes(self):
        v = self.mesh["vertices"]
        m = np.array([layer(x, y) for x, y in v])
        by_array = deltamesh.adapt(self.mesh, metric=m, opts="Q")
        by_function = deltamesh.adapt(self.mesh, metric=layer, opts="Q")
        for r in (by_array, by_function):
            self.check_result(r)
            self.assertGreater(len(r["triangles"]), 500)
        # Segment markers survive on the split boundary.
        self.assertEqual(set(np.unique(by_array["segment_markers"])), {1, 2, 3, 4, 5})

    def test_bad_metrics_are_errors(self):
        v = self.mesh["vertices"]
        m = np.array([layer(x, y) for x, y in v])
        m[3] = [1, 2, 1]
        with self.assertRaisesRegex(deltamesh.InputError, "vertex 3 is not positive definite"):
            deltamesh.adapt(self.mesh, metric=m)
        with self.assertRaises(ValueError):
            deltamesh.adapt(self.mesh, metric=m[:-1])
        with self.assertRaises(ZeroDivisionError):
            deltamesh.adapt(self.mesh, metric=lambda x, y: 1 / 0)
        with self.assertRaisesRegex(deltamesh.InputError, "degenerate|positive definite"):
            deltamesh.adapt(self.mesh, metric=lambda x, y: (1.0, 1.0, 1.0))
        with self.assertRaises(ValueError):
            deltamesh.adapt(self.mesh, metric=lambda x, y: (1.0, 0.0))
        with self.assertRaises(ValueError):
            deltamesh.adapt(self.mesh, lambda x, y: 0.1, metric=layer)


if __name__ == "__main__":
    unittest.main()

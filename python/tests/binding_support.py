"""Helpers shared by the binding tests (test_deltamesh, test_deltamesh_io)."""
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

"""Writes the example data sets of deltamesh.get_data() (python/deltamesh/data).

Every set is made here from a formula or by deltamesh itself: nothing is
copied from elsewhere. Run from the checkout with the module on PYTHONPATH:
    PYTHONPATH=build/python /usr/bin/python3 scripts/make-python-data.py
"""
import math
import os

import numpy as np

import deltamesh

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "deltamesh", "data")


def write_node(path, xy, markers=None, comment=""):
    with open(path, "w") as f:
        f.write(f"# {comment}\n" if comment else "")
        f.write(f"{len(xy)} 2 0 {1 if markers is not None else 0}\n")
        for i, (x, y) in enumerate(xy):
            f.write(f"{i} {float(x)!r} {float(y)!r}" + (f" {markers[i]}" if markers is not None else "") + "\n")


# dots: 60 points of the Halton sequence (bases 2 and 3) in the unit square.
def halton(i, b):
    r, f = 0.0, 1.0
    while i:
        f /= b
        r += f * (i % b)
        i //= b
    return r


write_node(os.path.join(here, "dots.node"), [(halton(i, 2), halton(i, 3)) for i in range(1, 61)],
           comment="dots: the first 60 points of the Halton sequence in bases 2 and 3")

# spiral: 80 points on an Archimedean spiral r = 0.1 * t.
write_node(os.path.join(here, "spiral.node"),
           [(0.1 * t * math.cos(t), 0.1 * t * math.sin(t)) for t in (0.3 * k + 0.5 for k in range(80))],
           comment="spiral: 80 points on r = 0.1 t, t = 0.5, 0.8, ...")

# square_hole: the unit square with a square hole, outer marker 5, hole marker 7.
square_hole = dict(
    vertices=np.array([[0, 0], [1, 0], [1, 1], [0, 1], [.4, .4], [.6, .4], [.6, .6], [.4, .6]], float),
    segments=np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]]),
    segment_markers=np.array([5, 5, 5, 5, 7, 7, 7, 7]),
    holes=np.array([[.5, .5]]),
)
# two_regions: a 2 x 1 rectangle split in two by a segment; region seeds with
# attributes 1 and 2 and area bounds 0.02 and 0.1 (mesh with 'pqAa').
two_regions = dict(
    vertices=np.array([[0, 0], [1, 0], [2, 0], [2, 1], [1, 1], [0, 1]], float),
    segments=np.array([[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]]),
    segment_markers=np.array([1, 1, 1, 1, 1, 1, 0]),
    regions=np.array([[.5, .5, 1, .02], [1.5, .5, 2, .1]]),
)
# ell: an L-shaped domain; ell.1.* is its mesh by 'pq30a0.05' (node, ele,
# poly, edge, neigh) with ell.1.area asking for half of each triangle's area.
ell = dict(
    vertices=np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float),
    segments=np.array([[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0]]),
    segment_markers=np.array([1, 2, 3, 3, 4, 5]),
)
def write_poly(path, pslg, comment):
    v, s = pslg["vertices"], pslg["segments"]
    with open(path, "w") as f:
        f.write(f"# {comment}\n{len(v)} 2 0 0\n")
        f.write("".join(f"{i} {float(x)!r} {float(y)!r}\n" for i, (x, y) in enumerate(v)))
        f.write(f"{len(s)} 1\n")
        f.write("".join(f"{i} {a} {b} {m}\n" for i, ((a, b), m) in enumerate(zip(s, pslg["segment_markers"]))))
        h = pslg.get("holes", np.zeros((0, 2)))
        f.write(f"{len(h)}\n" + "".join(f"{i} {float(x)!r} {float(y)!r}\n" for i, (x, y) in enumerate(h)))
        r = pslg.get("regions", np.zeros((0, 4)))
        f.write(f"{len(r)}\n" + "".join(f"{i} {float(x)!r} {float(y)!r} {float(a)!r} {float(m)!r}\n"
                                         for i, (x, y, a, m) in enumerate(r)))


write_poly(os.path.join(here, "square_hole.poly"), square_hole,
           "square_hole: the unit square with a square hole; outer segments marker 5, hole marker 7")
write_poly(os.path.join(here, "two_regions.poly"), two_regions,
           "two_regions: two unit squares side by side, region attributes 1 and 2, area bounds 0.02 and 0.1")
write_poly(os.path.join(here, "ell.poly"), ell, "ell: an L-shaped domain, one marker per side (1 to 5)")
mesh = deltamesh.triangulate(ell, "pq30a0.05eQ")
for ext in ("node", "ele", "poly", "edge", "neigh"):
    deltamesh.write(mesh, os.path.join(here, "ell.1." + ext), first_index=1)
v, t = mesh["vertices"], mesh["triangles"]
area = 0.5 * np.abs(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]))
with open(os.path.join(here, "ell.1.area"), "w") as f:
    f.write(f"{len(t)}\n" + "".join(f"{i + 1} {float(a) / 2!r}\n" for i, a in enumerate(area)))
print("wrote", sorted(os.listdir(here)))

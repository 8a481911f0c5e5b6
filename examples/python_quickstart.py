"""deltamesh from Python: mesh examples/plate.poly with angles >= 30 degrees,
check the result, print statistics and write an SVG picture.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_quickstart.py [out.svg]

(ctest runs it as python_quickstart_example.)
"""
import os
import sys

import numpy as np

import deltamesh

here = os.path.dirname(os.path.abspath(__file__))
out_svg = sys.argv[1] if len(sys.argv) > 1 else "plate.svg"

# Triangle's dict: vertices, segments (0-based), holes, regions, markers.
plate = deltamesh.read(os.path.join(here, "plate.poly"))
print({k: v.shape for k, v in plate.items()})

# Triangle's switches: p (segments, holes), q30 (min angle), a0.05 (max
# area), A (regional attribute per triangle). stats=True adds the run's
# report: (mesh, stats) instead of the `triangle` package's mesh dict alone.
mesh, stats = deltamesh.triangulate(plate, "pq30a0.05A", stats=True)
print(f"{len(mesh['vertices'])} vertices, {len(mesh['triangles'])} triangles, "
      f"{stats['steiner_points']} Steiner points, smallest angle {stats['min_angle']:.2f} degrees, "
      f"complete: {stats['complete']}")

# The same with keywords.
same = deltamesh.triangulate(plate["vertices"], plate["segments"], plate["holes"], plate["regions"],
                             segment_markers=plate["segment_markers"], min_angle=30, max_area=0.05,
                             regional_attributes=True)
assert np.array_equal(same["triangles"], mesh["triangles"])

# The library's exact validator (raises deltamesh.CheckError if invalid).
report = deltamesh.validate(mesh)
print(report["summary"])

# Area per material region (triangle attribute 0).
v, t = mesh["vertices"], mesh["triangles"]
a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
for region in np.unique(mesh["triangle_attributes"][:, 0]):
    sel = mesh["triangle_attributes"][:, 0] == region
    print(f"region {region:g}: {sel.sum()} triangles, area {area[sel].sum():.4f}")

deltamesh.write(mesh, out_svg)
print("wrote", out_svg)

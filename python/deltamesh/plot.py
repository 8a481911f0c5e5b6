"""Drawing mesh dicts with matplotlib (an optional dependency).

plot(ax, **mesh) draws what the dict holds: vertices, triangles, segments,
edges (with Voronoi rays: ray_origins, ray_directions), holes, regions,
triangle attributes; labels=True numbers the vertices, markers=True writes
their markers. compare() and comparev() draw two dicts side by side or one
above the other. These are the `triangle` package's drawing functions;
matplotlib is imported only when one is called.
"""
import numpy as np


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            "deltamesh's drawing functions (plot, compare, comparev, show_data) need matplotlib, an optional "
            "dependency: install it (Debian: apt install python3-matplotlib; pip: pip install 'deltamesh[plot]')"
        ) from e
    return plt


def _lines(ax, starts, ends, **style):
    from matplotlib.collections import LineCollection
    if len(starts):
        ax.add_collection(LineCollection(np.stack([starts, ends], axis=1), **style))


def vertices(ax, **kw):
    v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
    ax.plot(v[:, 0], v[:, 1], "k.", markersize=3, zorder=3)
    if kw.get("labels"):
        for i, (x, y) in enumerate(v):
            ax.annotate(str(i), (x, y), fontsize=7, xytext=(2, 2), textcoords="offset points")
    if kw.get("markers") and "vertex_markers" in kw:
        for (x, y), m in zip(v, np.asarray(kw["vertex_markers"]).reshape(-1)):
            ax.annotate(str(m), (x, y), fontsize=7, color="g", xytext=(2, -8), textcoords="offset points")


def triangles(ax, **kw):
    v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
    t = np.asarray(kw["triangles"]).reshape(len(kw["triangles"]), -1)[:, :3]
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    _lines(ax, np.concatenate([a, b, c]), np.concatenate([b, c, a]), colors="0.35", linewidths=0.6, zorder=1)


def segments(ax, **kw):
    v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
    s = np.asarray(kw["segments"]).astype(np.int64).reshape(-1, 2)
    _lines(ax, v[s[:, 0]], v[s[:, 1]], colors="tab:red", linewidths=2.0, zorder=2)


def edges(ax, **kw):
    """Edges, and Voronoi rays when ray_origins and ray_directions are given."""
    v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
    e = np.asarray(kw["edges"]).astype(np.int64).reshape(-1, 2)
    finite = e[(e[:, 0] >= 0) & (e[:, 1] >= 0)]
    _lines(ax, v[finite[:, 0]], v[finite[:, 1]], colors="tab:blue", linewidths=0.8, zorder=1)
    if "ray_origins" in kw and "ray_directions" in kw:
        o = np.asarray(kw["ray_origins"]).astype(np.int64).reshape(-1)
        d = np.asarray(kw["ray_directions"], dtype=float).reshape(-1, 2)
        if len(o):
            # Long enough to leave the picture: the span of the vertices.
            span = max(float(np.ptp(v[:, 0])) if len(v) else 1.0, float(np.ptp(v[:, 1])) if len(v) else 1.0, 1e-12)
            norm = np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
            _lines(ax, v[o], v[o] + 10 * span * d / norm, colors="tab:blue", linewidths=0.8, linestyles="dashed")


def holes(ax, **kw):
    h = np.asarray(kw["holes"], dtype=float).reshape(-1, 2)
    ax.plot(h[:, 0], h[:, 1], "rx", zorder=4)


def regions(ax, **kw):
    r = np.asarray(kw["regions"], dtype=float)
    r = r.reshape(len(r), -1)
    ax.plot(r[:, 0], r[:, 1], "b*", zorder=4)
    for row in r:
        ax.annotate(f"{row[2]:g}", (row[0], row[1]), color="b", fontsize=7, xytext=(3, 0), textcoords="offset points")


def triangle_attributes(ax, **kw):
    v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
    t = np.asarray(kw["triangles"]).reshape(len(kw["triangles"]), -1)[:, :3]
    att = np.asarray(kw["triangle_attributes"], dtype=float).reshape(len(t), -1)
    for (x, y), a in zip(v[t].mean(axis=1), att[:, 0]):
        ax.annotate(f"{a:g}", (x, y), color="m", fontsize=6, ha="center", va="center")


def plot(ax, **kw):
    """Draws a mesh dict (the `triangle` package's keys) on matplotlib axes `ax`;
    keys it does not know (stats, voronoi, ...) are ignored. Returns ax."""
    _pyplot()
    ax.set_aspect("equal")
    drawn = [(k, f) for k, f in (("triangles", triangles), ("edges", edges), ("segments", segments),
                                 ("holes", holes), ("regions", regions),
                                 ("triangle_attributes", triangle_attributes)) if k in kw]
    if "vertices" in kw:
        vertices(ax, **kw)
    for _, draw in drawn:
        draw(ax, **kw)
    if "edges" in kw and "ray_origins" in kw and "vertices" in kw and len(kw["vertices"]):
        v = np.asarray(kw["vertices"], dtype=float).reshape(-1, 2)
        pad = 0.05 * max(float(np.ptp(v[:, 0])), float(np.ptp(v[:, 1])), 1e-12)
        ax.set_xlim(v[:, 0].min() - pad, v[:, 0].max() + pad)  # rays stay out of the limits
        ax.set_ylim(v[:, 1].min() - pad, v[:, 1].max() + pad)
    else:
        ax.autoscale_view()
    ax.get_xaxis().set_visible(False)
    ax.get_yaxis().set_visible(False)
    return ax


def compare(plt, A, B, figsize=(6, 3)):
    """Draws mesh dicts A and B side by side in a new figure (plt: matplotlib.pyplot). Returns the figure."""
    _pyplot()
    fig = plt.figure(figsize=figsize)
    left = fig.add_subplot(1, 2, 1)
    plot(left, **A)
    right = fig.add_subplot(1, 2, 2, sharex=left, sharey=left)
    plot(right, **B)
    fig.tight_layout()
    return fig


def comparev(plt, A, B, figsize=(3, 6)):
    """Draws mesh dict A above B in a new figure. Returns the figure."""
    _pyplot()
    fig = plt.figure(figsize=figsize)
    top = fig.add_subplot(2, 1, 1)
    plot(top, **A)
    bottom = fig.add_subplot(2, 1, 2, sharex=top, sharey=top)
    plot(bottom, **B)
    fig.tight_layout()
    return fig

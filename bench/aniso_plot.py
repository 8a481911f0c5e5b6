#!/usr/bin/env python3
"""Plots bench_aniso's CSV: interpolation error against triangle count per
function (log-log SVG, one curve per method), and prints a Markdown table
with, for each anisotropic run, the triangles the isotropic curve needs for
the same error (log-log interpolation between its runs) and the ratio; where
even the largest isotropic run has a larger error, the log-log extrapolation
of its last two runs, marked, with the measured lower bound.

    bench/aniso_plot.py results.csv OUTDIR [--error l2|linf]
"""
import csv
import math
import sys
from collections import defaultdict

COLORS = {"iso": "#d62728", "aniso": "#1f77b4", "gmsh-bamg": "#2ca02c"}


def read(path):
    rows = list(csv.DictReader(open(path)))
    for r in rows:
        for k in ("N", "triangles", "vertices"):
            r[k] = int(r[k])
        for k in ("l2", "linf", "within", "mean_length", "mean_quality", "min_quality", "seconds"):
            r[k] = float(r[k])
    return rows


def iso_triangles_at(iso, err, key):
    """Triangles the isotropic curve (sorted by triangles) needs for error `err`."""
    pts = sorted((r["triangles"], r[key]) for r in iso)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if (e0 - err) * (e1 - err) <= 0 and e0 != e1:
            s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0))), False
    # Beyond the curve: extrapolate from the last two points (marked).
    (t0, e0), (t1, e1) = pts[-2], pts[-1]
    if e0 == e1:
        return float("nan"), True
    s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
    return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0))), True


def svg_plot(fn, by_method, key, path):
    w, h, ml, mr, mt, mb = 560, 400, 70, 20, 30, 50
    pts = [(r["triangles"], r[key]) for rs in by_method.values() for r in rs]
    x0, x1 = math.log10(min(p[0] for p in pts)), math.log10(max(p[0] for p in pts))
    y0, y1 = math.log10(min(p[1] for p in pts)), math.log10(max(p[1] for p in pts))
    x0, x1 = math.floor(x0 * 2) / 2, math.ceil(x1 * 2) / 2
    y0, y1 = math.floor(y0), math.ceil(y1)
    X = lambda t: ml + (math.log10(t) - x0) / (x1 - x0) * (w - ml - mr)
    Y = lambda e: h - mb - (math.log10(e) - y0) / (y1 - y0) * (h - mt - mb)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w / 2}" y="18" text-anchor="middle" font-size="14">{fn}: {key} error of the P1 interpolant</text>']
    for k in range(int(y0), int(y1) + 1):
        y = Y(10 ** k)
        out.append(f'<line x1="{ml}" y1="{y}" x2="{w - mr}" y2="{y}" stroke="#ddd"/>')
        out.append(f'<text x="{ml - 6}" y="{y + 4}" text-anchor="end">1e{k}</text>')
    k = x0
    while k <= x1 + 1e-9:
        x = X(10 ** k)
        out.append(f'<line x1="{x}" y1="{mt}" x2="{x}" y2="{h - mb}" stroke="#ddd"/>')
        if abs(k - round(k)) < 1e-9:
            out.append(f'<text x="{x}" y="{h - mb + 16}" text-anchor="middle">{10 ** k:.0f}</text>')
        k += 0.5
    out.append(f'<text x="{w / 2}" y="{h - 10}" text-anchor="middle">triangles</text>')
    out.append(f'<rect x="{ml}" y="{mt}" width="{w - ml - mr}" height="{h - mt - mb}" fill="none" stroke="black"/>')
    for i, (method, rs) in enumerate(sorted(by_method.items())):
        rs = sorted(rs, key=lambda r: r["triangles"])
        c = COLORS.get(method, "black")
        d = " ".join(f'{X(r["triangles"]):.1f},{Y(r[key]):.1f}' for r in rs)
        out.append(f'<polyline points="{d}" fill="none" stroke="{c}" stroke-width="2"/>')
        for r in rs:
            out.append(f'<circle cx="{X(r["triangles"]):.1f}" cy="{Y(r[key]):.1f}" r="3" fill="{c}"/>')
        ly = mt + 16 + 16 * i
        out.append(f'<line x1="{w - mr - 110}" y1="{ly - 4}" x2="{w - mr - 90}" y2="{ly - 4}" stroke="{c}" stroke-width="2"/>')
        out.append(f'<text x="{w - mr - 85}" y="{ly}">{method}</text>')
    out.append("</svg>")
    open(path, "w").write("\n".join(out) + "\n")


def main():
    path, outdir = sys.argv[1], sys.argv[2]
    key = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--error" else "l2"
    rows = read(path)
    by_fn = defaultdict(lambda: defaultdict(list))
    for r in rows:
        by_fn[r["function"]][r["method"]].append(r)
    print(f"| function | N | aniso triangles | {key} error | iso triangles at that error | ratio | "
          "aniso edges within [1/√2, √2] | mean quality |")
    print("|---|---|---|---|---|---|---|---|")
    for fn, by_method in by_fn.items():
        svg_plot(fn, by_method, key, f"{outdir}/aniso_{fn}_{key}.svg")
        iso = by_method["iso"]
        for r in sorted(by_method["aniso"], key=lambda r: r["N"]):
            t, extrapolated = iso_triangles_at(iso, r[key], key)
            if extrapolated:
                # Beyond the isotropic runs: the log-log extrapolation of
                # its last two, and the measured lower bound (the largest
                # isotropic run still has a larger error).
                big = max(iso, key=lambda x: x["triangles"])
                need = f'≈{t:.0f} extrapolated; measured > {big["triangles"]}'
                ratio = f'≈{t / r["triangles"]:.1f} (> {big["triangles"] / r["triangles"]:.1f})'
            else:
                need, ratio = f"{t:.0f}", f'{t / r["triangles"]:.1f}'
            print(f'| {fn} | {r["N"]} | {r["triangles"]} | {r[key]:.3g} | {need} | {ratio} | '
                  f'{100 * r["within"]:.1f}% | {r["mean_quality"]:.3f} |')


if __name__ == "__main__":
    main()

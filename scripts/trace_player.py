#!/usr/bin/env python3
"""Render a deltamesh trace (deltamesh --trace FILE, docs/trace.md).

  trace_player.py html   TRACE -o player.html          one self-contained page:
                                                        play, pause, step, speed, phases
  trace_player.py frames TRACE -o DIR [--only KINDS]    numbered SVG frames, one per event
  trace_player.py sheet  TRACE -o FIG.svg --select KIND[:WHY] [--max N] [--cols C]
                                                        small multiples of chosen events
  trace_player.py count  TRACE                          events per kind and reason

The replay follows docs/trace.md: a table of points and a set of triangles;
each event removes its `del` triangles and adds its `add` ones. Only the
Python standard library is used; PNGs are made with rsvg-convert.
"""
import argparse
import html
import json
import os
import sys
from collections import Counter

# One sentence per event: what the player shows under the mesh.
REASONS = {
    ("insert", "delaunay"): "vertex {v} inserted: its triangle is split, then Lawson flips restore the empty-circle property",
    ("insert", "crossing"): "two segments cross: vertex {v} inserted at their intersection",
    ("insert", ""): "the triangles of the mesh read",
    ("flip", "delaunay"): "edge {edge} flipped to {to}: the new vertex lies inside the circumcircle across it (Lawson)",
    ("flip", "lawson"): "edge {edge} flipped to {to}: it is not locally Delaunay (constrained Lawson flip)",
    ("flip", "recovery"): "edge {edge} crosses the segment being inserted and its quadrilateral is convex: flipped to {to}",
    ("flip", "lifting"): "edge {edge} flipped to {to}: its four lifted points become coplanar first (lifting-map order)",
    ("flip", "coarsen"): "edge {edge} flipped to {to} to empty the star of the vertex to remove",
    ("recover", "present"): "segment {seg} is an edge already",
    ("recover", ""): "segment {seg} recovered ({why}, {flips} flips)",
    ("retriangulate", "fast"): "the triangles segment {seg} crossed are replaced (cavity retriangulation)",
    ("split_segment", "encroached"): "R1: vertex {by} encroaches subsegment {seg}: split at vertex {v}",
    ("split_segment", "rejected_point"): "R1: the Steiner point of a bad triangle would encroach subsegment {seg}: split at vertex {v}",
    ("split_segment", ""): "subsegment {seg} split at vertex {v}",
    ("split_triangle", "circumcentre"): "R2: bad triangle {tri} split at its circumcentre, vertex {v}",
    ("split_triangle", "offcentre"): "R2: bad triangle {tri} split at its off-centre, vertex {v}",
    ("split_triangle", "best_point"): "R2: bad triangle {tri} split at the best point of its petal, vertex {v}",
    ("split_triangle", "area"): "R2: triangle {tri} is too large: split at vertex {v}",
    ("reject", "encroaches"): "R2: the Steiner point of {tri} encroaches a subsegment: rejected",
    ("remove", "coarsen"): "coarsening: vertex {v} removed (the mesh is finer than the size field here)",
    ("move", ""): "smoothing: vertex {v} moved ({why})",
    ("carve", ""): "{ndel} triangles outside the domain removed",
    ("renumber", ""): "vertices renumbered",
    ("undo", ""): "refinement beyond 34 degrees stalled: back to the 34-degree mesh",
    ("phase", ""): "phase: {name}",
    ("points", ""): "{npoints} input vertices",
    ("end", ""): "done: {vertices} vertices, {triangles} triangles",
}


def explain(ev):
    kind, why = ev["ev"], ev.get("why", "")
    text = REASONS.get((kind, why)) or REASONS.get((kind, ""), kind + " " + why)
    fields = dict(ev)
    fields.setdefault("why", "")
    for k in ("edge", "to", "seg", "tri"):
        if k in ev:
            fields[k] = "-".join("inf" if x < 0 else str(x) for x in ev[k])
    fields["ndel"] = len(ev.get("del", []))
    fields["npoints"] = len(ev.get("points", []))
    try:
        return text.format(**fields)
    except (KeyError, IndexError):
        return text


def canon(t):
    i = min(range(3), key=lambda k: t[k])
    return (t[i], t[(i + 1) % 3], t[(i + 2) % 3])


def read_trace(path):
    with open(path) as f:
        head = json.loads(f.readline())
        if head.get("trace") != "deltamesh":
            sys.exit(f"{path}:1: not a deltamesh trace")
        if head.get("version") != 1:
            sys.exit(f"{path}:1: trace version {head.get('version')}, this player reads version 1")
        events = []
        for n, line in enumerate(f, start=2):
            try:
                events.append(json.loads(line))
            except json.JSONDecodeError as e:
                sys.exit(f"{path}:{n}: {e}")
    return events


class Replay:
    """docs/trace.md's replay: points by id, a set of triangles."""

    def __init__(self):
        self.points = {}
        self.tris = set()
        self.segs = set()  # segments known so far (recover events, split by R1)

    def apply(self, ev):
        kind = ev["ev"]
        if kind == "points":
            for i, p in enumerate(ev["points"]):
                self.points[ev["first"] + i] = tuple(p)
        if "v" in ev and "p" in ev:
            self.points[ev["v"]] = tuple(ev["p"])
        if kind == "renumber":
            new = {j: self.points[j] for j in range(ev["vertices"]) if j in self.points}
            done = set()
            for i, to in enumerate(ev["map"]):
                if to >= 0 and to not in done and i in self.points:
                    new[to] = self.points[i]
                    done.add(to)
            self.points = new
            self.tris = {canon(tuple(ev["map"][v] for v in t)) for t in self.tris}
            self.segs = {tuple(sorted((ev["map"][a], ev["map"][b]))) for a, b in self.segs}
        if kind == "recover":
            self.segs.add(tuple(sorted(ev["seg"])))
        if kind == "split_segment":
            a, b = ev["seg"]
            self.segs.discard(tuple(sorted((a, b))))
            self.segs.update({tuple(sorted((a, ev["v"]))), tuple(sorted((ev["v"], b)))})
        for t in ev.get("del", []):
            self.tris.discard(canon(t))
        for t in ev.get("add", []):
            self.tris.add(canon(t))


def bounds(events):
    xs, ys = [], []
    for ev in events:
        for p in ev.get("points", []):
            xs.append(p[0])
            ys.append(p[1])
        if "p" in ev:
            xs.append(ev["p"][0])
            ys.append(ev["p"][1])
    if not xs:
        return 0, 0, 1, 1
    return min(xs), min(ys), max(xs), max(ys)


def panel(state, ev, box, x0, y0, w, h, caption=None):
    """SVG of the state after `ev` in a w x h panel at (x0, y0); ev's triangles highlighted."""
    bx0, by0, bx1, by1 = box
    dx, dy = (bx1 - bx0) or 1.0, (by1 - by0) or 1.0
    s = 0.94 * min(w / dx, (h - 34) / dy)
    ox = x0 + (w - s * dx) / 2
    oy = y0 + 6 + (h - 34 - s * dy) / 2 + s * dy

    def xy(v):
        p = state.points.get(v)
        return (ox + s * (p[0] - bx0), oy - s * (p[1] - by0)) if p else None

    def poly(t):
        pts = [xy(v) for v in t]
        if None in pts:
            return ""
        return " ".join(f"{a:.2f},{b:.2f}" for a, b in pts)

    added = {canon(t) for t in ev.get("add", [])}
    out = [f'<rect x="{x0}" y="{y0}" width="{w}" height="{h}" fill="white"/>']
    for t in state.tris:
        fill = "#ffb347" if t in added else "#eef3fb"
        out.append(f'<polygon points="{poly(t)}" fill="{fill}" stroke="#4a6fa5" stroke-width="0.7"/>')
    for a, b in state.segs:
        pa, pb = xy(a), xy(b)
        if pa and pb:
            out.append(f'<line x1="{pa[0]:.2f}" y1="{pa[1]:.2f}" x2="{pb[0]:.2f}" y2="{pb[1]:.2f}" '
                       f'stroke="#222" stroke-width="1.8"/>')
    for t in ev.get("del", []):
        out.append(f'<polygon points="{poly(t)}" fill="none" stroke="#d62728" stroke-width="1.2" stroke-dasharray="3,2"/>')
    for key, colour in (("seg", "#1f77b4"), ("to", "#2ca02c")):
        if key in ev and all(x >= 0 for x in ev[key]):
            a, b = xy(ev[key][0]), xy(ev[key][1])
            if a and b:
                out.append(f'<line x1="{a[0]:.2f}" y1="{a[1]:.2f}" x2="{b[0]:.2f}" y2="{b[1]:.2f}" '
                           f'stroke="{colour}" stroke-width="2.4"/>')
    if "v" in ev and xy(ev["v"]):
        a = xy(ev["v"])
        out.append(f'<circle cx="{a[0]:.2f}" cy="{a[1]:.2f}" r="3.2" fill="#d62728"/>')
    if "at" in ev:
        p = ev["at"]
        a = (ox + s * (p[0] - bx0), oy - s * (p[1] - by0))
        out.append(f'<path d="M{a[0]-4:.1f},{a[1]-4:.1f}l8,8m0,-8l-8,8" stroke="#9467bd" stroke-width="2"/>')
    text = caption if caption is not None else explain(ev)
    out.append(f'<text x="{x0 + w / 2}" y="{y0 + h - 10}" font-family="sans-serif" font-size="11" '
               f'text-anchor="middle">{html.escape(text)}</text>')
    return "\n".join(out)


def svg_document(w, h, body):
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">\n'
            f'<rect width="{w}" height="{h}" fill="white"/>\n{body}\n</svg>\n')


def matches(ev, selectors):
    for sel in selectors:
        kind, _, why = sel.partition(":")
        if ev["ev"] == kind and (not why or ev.get("why", "") == why):
            return True
    return False


def cmd_frames(args):
    events = read_trace(args.trace)
    box = bounds(events)
    os.makedirs(args.output, exist_ok=True)
    only = args.only.split(",") if args.only else None
    state, n = Replay(), 0
    for i, ev in enumerate(events):
        state.apply(ev)
        if only and not matches(ev, only):
            continue
        n += 1
        with open(os.path.join(args.output, f"frame{n:05d}.svg"), "w") as f:
            f.write(svg_document(640, 560, panel(state, ev, box, 0, 0, 640, 560, f"{i + 1}. {explain(ev)}")))
    print(f"{n} frames in {args.output}")


def cmd_sheet(args):
    events = read_trace(args.trace)
    box = bounds(events)
    selectors = args.select.split(",")
    chosen = []
    state = Replay()
    phase_ok = args.phase is None
    for i, ev in enumerate(events):
        state.apply(ev)
        if ev["ev"] == "phase":
            phase_ok = args.phase is None or ev["name"] == args.phase
        if phase_ok and matches(ev, selectors):
            chosen.append((i, ev, Replay.__new__(Replay)))
            snap = chosen[-1][2]
            snap.points, snap.tris, snap.segs = dict(state.points), set(state.tris), set(state.segs)
    total = len(chosen)
    if args.max and len(chosen) > args.max:  # evenly spaced, always the last one
        step = (len(chosen) - 1) / (args.max - 1) if args.max > 1 else 0
        chosen = [chosen[round(k * step)] for k in range(args.max)]
    if args.final:
        final = Replay.__new__(Replay)
        final.points, final.tris, final.segs = dict(state.points), set(state.tris), set(state.segs)
        chosen.append((len(events) - 1, {"ev": "end"}, final))
    cols = max(1, min(args.cols, len(chosen)))
    rows = (len(chosen) + cols - 1) // cols
    aspect = ((box[3] - box[1]) or 1.0) / ((box[2] - box[0]) or 1.0)
    pw = args.panel
    ph = int(pw * min(max(aspect, 0.2), 1.5)) + 40
    title_h = 30 if args.title else 0
    body = []
    if args.title:
        body.append(f'<text x="{cols * pw / 2}" y="20" font-family="sans-serif" font-size="15" font-weight="bold" '
                    f'text-anchor="middle">{html.escape(args.title.format(count=total))}</text>')
    for k, (i, ev, snap) in enumerate(chosen):
        x, y = (k % cols) * pw, title_h + (k // cols) * ph
        caption = "final mesh" if ev["ev"] == "end" else f"step {i + 1}: {short(ev)}"
        body.append(panel(snap, ev, box, x, y, pw, ph, caption))
    with open(args.output, "w") as f:
        f.write(svg_document(cols * pw, title_h + rows * ph, "\n".join(body)))
    print(f"{len(chosen)} panels ({total} matching events) in {args.output}")


def short(ev):
    """A panel caption: the event in a few words."""
    kind, why = ev["ev"], ev.get("why", "")
    if kind == "flip":
        return f"flip {'-'.join(map(str, ev['edge']))} -> {'-'.join(map(str, ev['to']))}"
    if kind in ("split_segment", "split_triangle"):
        return f"{'R1' if kind == 'split_segment' else 'R2'} {why.replace('_', ' ')}"
    return f"{kind} {why}".strip()


def cmd_count(args):
    c = Counter((ev["ev"], ev.get("why", "")) for ev in read_trace(args.trace))
    for (kind, why), n in sorted(c.items()):
        print(f"{n:8d}  {kind} {why}")


def cmd_html(args):
    events = read_trace(args.trace)
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "trace_player.html")) as f:
        page = f.read()
    reasons = {f"{k}|{w}": t for (k, w), t in REASONS.items()}
    data = json.dumps({"title": os.path.basename(args.trace), "events": events, "reasons": reasons},
                      separators=(",", ":"))
    page = page.replace("/*TRACE_DATA*/null", data.replace("</", "<\\/"))
    with open(args.output, "w") as f:
        f.write(page)
    print(f"{len(events)} events in {args.output}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("html")
    p.add_argument("trace")
    p.add_argument("-o", "--output", required=True)
    p.set_defaults(fn=cmd_html)
    p = sub.add_parser("frames")
    p.add_argument("trace")
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--only", help="comma-separated KIND[:WHY]: frames for these events only")
    p.set_defaults(fn=cmd_frames)
    p = sub.add_parser("sheet")
    p.add_argument("trace")
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--select", required=True, help="comma-separated KIND[:WHY]")
    p.add_argument("--phase", help="only events in this phase")
    p.add_argument("--max", type=int, default=0, help="at most N panels, evenly spaced")
    p.add_argument("--cols", type=int, default=4)
    p.add_argument("--panel", type=int, default=220, help="panel width in pixels")
    p.add_argument("--final", action="store_true", help="add a panel with the final mesh")
    p.add_argument("--title", help="title; {count} is the number of matching events")
    p.set_defaults(fn=cmd_sheet)
    p = sub.add_parser("count")
    p.add_argument("trace")
    p.set_defaults(fn=cmd_count)
    args = ap.parse_args()
    args.fn(args)


if __name__ == "__main__":
    main()

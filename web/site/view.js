// The picture: a mesh shaded by smallest angle, the state of a trace being
// stepped through, and the PSLG being drawn, with pan (drag) and zoom (wheel).
// Paths are built once per mesh in world coordinates (one Path2D per colour
// bucket), so redrawing 10^5 triangles on pan/zoom is a few fills.
'use strict';

// Smallest angle (degrees) -> colour: red at 0°, yellow at 30°, green from 60°.
function angleColour(deg) {
  const t = Math.max(0, Math.min(1, deg / 60));
  return `hsl(${Math.round(t * 120)}, 70%, ${Math.round(62 + 10 * t)}%)`;
}
const kBuckets = 24;  // 2.5° colour steps

class MeshView {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.scale = 40;
    this.ox = 20;  // screen position of world (0, 0)
    this.oy = 300;
    this.mesh = null;       // {fills: [Path2D], edges: Path2D, segments: Path2D, bounds}
    this.trace = null;      // {all: Path2D, del: Path2D, add: Path2D, mark: [x, y] | null, edge: [..] | null}
    this.drawing = null;    // Drawing (app.js)
    this.showMesh = true;
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  resize() {
    const r = this.canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    this.canvas.width = Math.max(1, Math.round(r.width * dpr));
    this.canvas.height = Math.max(1, Math.round(r.height * dpr));
    this.dpr = dpr;
    this.draw();
  }

  toWorld(sx, sy) { return [(sx - this.ox) / this.scale, (this.oy - sy) / this.scale]; }
  toScreen(x, y) { return [this.ox + x * this.scale, this.oy - y * this.scale]; }

  fit(b) {
    if (!b || !(b.maxx >= b.minx)) return;
    const r = this.canvas.getBoundingClientRect();
    const w = Math.max(b.maxx - b.minx, 1e-12), h = Math.max(b.maxy - b.miny, 1e-12);
    this.scale = 0.9 * Math.min(r.width / w, r.height / h);
    this.ox = r.width / 2 - this.scale * (b.minx + b.maxx) / 2;
    this.oy = r.height / 2 + this.scale * (b.miny + b.maxy) / 2;
    this.draw();
  }

  zoomAt(sx, sy, factor) {
    this.ox = sx - (sx - this.ox) * factor;
    this.oy = sy - (sy - this.oy) * factor;
    this.scale *= factor;
    this.draw();
  }

  pan(dx, dy) { this.ox += dx; this.oy += dy; this.draw(); }

  // Builds the paths in slices of a few milliseconds, drawing as it goes,
  // so that the page stays responsive while 10^5 triangles are turned into
  // paths (each path call costs about a microsecond).
  setMesh(v) {
    if (this.building) cancelAnimationFrame(this.building);
    this.building = 0;
    if (!v) { this.mesh = null; this.draw(); return; }
    const { xy, tri, angle, seg } = v;
    // Paths of at most kChunk triangles: Skia's fill and stroke slow down
    // badly on single paths of 10^5 subpaths.
    const kChunk = 2048;
    const withEdges = angle.length <= 50000;
    const segments = [];
    for (let s = 0; s < seg.length; s += 2) {
      if (s % (2 * kChunk) === 0) segments.push(new Path2D());
      const a = 2 * seg[s], b = 2 * seg[s + 1], p = segments[segments.length - 1];
      p.moveTo(xy[a], xy[a + 1]); p.lineTo(xy[b], xy[b + 1]);
    }
    const m = { fills: [], edges: [], segments, withEdges, bounds: bounds(xy), triangles: Math.max(1, angle.length), count: angle.length, done: 0 };
    this.mesh = m;
    const open = new Array(kBuckets).fill(null);
    let edgePath = null;
    const slice = () => {
      const stop = performance.now() + 12;
      let t = m.done;
      for (; t < angle.length && (t % 256 !== 0 || performance.now() < stop); ++t) {
        const a = 2 * tri[3 * t], b = 2 * tri[3 * t + 1], c = 2 * tri[3 * t + 2];
        const k = Math.min(kBuckets - 1, Math.floor(angle[t] / 60 * kBuckets));
        if (!open[k] || open[k].n === kChunk) { open[k] = { k, path: new Path2D(), n: 0 }; m.fills.push(open[k]); }
        const p = open[k].path;
        ++open[k].n;
        p.moveTo(xy[a], xy[a + 1]); p.lineTo(xy[b], xy[b + 1]); p.lineTo(xy[c], xy[c + 1]); p.closePath();
        if (withEdges) {
          if (t % kChunk === 0) { edgePath = new Path2D(); m.edges.push(edgePath); }
          edgePath.moveTo(xy[a], xy[a + 1]); edgePath.lineTo(xy[b], xy[b + 1]); edgePath.lineTo(xy[c], xy[c + 1]); edgePath.closePath();
        }
      }
      m.done = t;
      this.building = t < angle.length && this.mesh === m ? requestAnimationFrame(slice) : 0;
      this.draw();
    };
    slice();
  }

  // All the triangles of the mesh are in the picture.
  complete() { return !this.mesh || this.mesh.done >= this.mesh.count; }

  // state: {points: [[x, y]], tris: Map key -> [a, b, c]}, ev: the event just applied.
  setTrace(state, ev, prevPoints) {
    if (!state) { this.trace = null; this.draw(); return; }
    const pt = (i, pts) => (pts || state.points)[i];
    const tri = (p, t, pts) => {
      const a = pt(t[0], pts), b = pt(t[1], pts), c = pt(t[2], pts);
      if (!a || !b || !c) return;
      p.moveTo(a[0], a[1]); p.lineTo(b[0], b[1]); p.lineTo(c[0], c[1]); p.closePath();
    };
    const all = new Path2D();
    for (const t of state.tris.values()) tri(all, t);
    const del = new Path2D(), add = new Path2D();
    let mark = null, edge = null, seg = null, at = null;
    if (ev) {
      for (const t of ev.del || []) tri(del, t, prevPoints);
      for (const t of ev.add || []) tri(add, t);
      if (ev.p) mark = ev.p;
      if (ev.at) at = ev.at;
      if (ev.to) edge = [pt(ev.to[0]), pt(ev.to[1])];
      if (ev.seg) seg = [pt(ev.seg[0]), pt(ev.seg[1])];
    }
    this.trace = { all, del, add, mark, edge, seg, at, points: state.points };
    this.draw();
  }

  draw() {
    const ctx = this.ctx, s = this.scale;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    ctx.setTransform(this.dpr * s, 0, 0, -this.dpr * s, this.dpr * this.ox, this.dpr * this.oy);
    const px = 1 / s;  // one CSS pixel in world units
    if (this.trace) this.drawTrace(px);
    else if (this.mesh && this.showMesh) this.drawMesh(px);
    if (this.drawing) this.drawing.draw(ctx, px);
  }

  drawMesh(px) {
    const ctx = this.ctx, m = this.mesh;
    for (const f of m.fills) { ctx.fillStyle = angleColour((f.k + 0.5) * 60 / kBuckets); ctx.fill(f.path); }
    // Edges only where triangles are a few pixels or more on screen: below
    // that they are a grey blur, and stroking 10^5 of them is slow.
    const b = m.bounds, pixels = (b.maxx - b.minx) * (b.maxy - b.miny) / m.triangles / (px * px);
    if (m.withEdges && pixels > 60) {
      ctx.strokeStyle = 'rgba(30,30,30,0.55)'; ctx.lineWidth = 0.6 * px;
      for (const e of m.edges) ctx.stroke(e);
    }
    ctx.strokeStyle = '#111'; ctx.lineWidth = 2 * px;
    for (const p of m.segments) ctx.stroke(p);
  }

  drawTrace(px) {
    const ctx = this.ctx, t = this.trace;
    ctx.fillStyle = '#eceff1'; ctx.fill(t.all);
    ctx.strokeStyle = '#78909c'; ctx.lineWidth = 0.8 * px; ctx.stroke(t.all);
    ctx.fillStyle = 'rgba(102,187,106,0.55)'; ctx.fill(t.add);
    ctx.strokeStyle = '#e53935'; ctx.lineWidth = 1.5 * px; ctx.setLineDash([4 * px, 3 * px]); ctx.stroke(t.del);
    ctx.setLineDash([]);
    if (t.seg && t.seg[0] && t.seg[1]) {
      ctx.strokeStyle = '#1e88e5'; ctx.lineWidth = 3 * px;
      ctx.beginPath(); ctx.moveTo(t.seg[0][0], t.seg[0][1]); ctx.lineTo(t.seg[1][0], t.seg[1][1]); ctx.stroke();
    }
    if (t.edge && t.edge[0] && t.edge[1]) {
      ctx.strokeStyle = '#2e7d32'; ctx.lineWidth = 3 * px;
      ctx.beginPath(); ctx.moveTo(t.edge[0][0], t.edge[0][1]); ctx.lineTo(t.edge[1][0], t.edge[1][1]); ctx.stroke();
    }
    ctx.fillStyle = '#37474f';
    for (const p of t.points) if (p) { ctx.beginPath(); ctx.arc(p[0], p[1], 1.5 * px, 0, 7); ctx.fill(); }
    for (const [p, colour] of [[t.mark, '#1565c0'], [t.at, '#e53935']]) {
      if (!p) continue;
      ctx.fillStyle = colour; ctx.beginPath(); ctx.arc(p[0], p[1], 5 * px, 0, 7); ctx.fill();
    }
  }
}

function bounds(xy) {
  const b = { minx: Infinity, miny: Infinity, maxx: -Infinity, maxy: -Infinity };
  for (let i = 0; i < xy.length; i += 2) {
    const x = xy[i], y = xy[i + 1];
    if (x < b.minx) b.minx = x; if (x > b.maxx) b.maxx = x;
    if (y < b.miny) b.miny = y; if (y > b.maxy) b.maxy = y;
  }
  return b;
}

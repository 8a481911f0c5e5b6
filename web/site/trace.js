// Replaying a trace (JSON Lines, docs/trace.md, schema version 1): a table
// of points and a set of triangles, updated event by event with the schema's
// rules (points, v + p, renumber, del then add). Stepping back replays from
// the nearest snapshot, taken every few events.
'use strict';

// What each event's `why` means, as the player says it.
const kWhy = {
  insert: {
    delaunay: 'Delaunay insertion: the vertex splits its triangle, then Lawson flips restore the empty-circle property',
    crossing: 'two segments cross: a vertex at their intersection',
  },
  flip: {
    delaunay: 'Lawson flip after an insertion: the new vertex is inside the circumcircle across this edge',
    lawson: 'constrained Lawson flip: the edge is not locally Delaunay',
    recovery: 'edge recovery: the edge crosses the segment being inserted and its quadrilateral is convex',
    lifting: 'lifting-map order: the next edge whose four lifted points become coplanar first',
    coarsen: 'coarsening: an edge at the vertex to be removed is flipped away',
  },
  recover: { present: 'the segment was an edge already' },
  retriangulate: { fast: 'the triangles the segment crosses are replaced: the cavity on each side is retriangulated' },
  split_segment: {
    encroached: 'R1: a vertex lies inside the subsegment\'s diametral circle (or lens): split at its midpoint',
    rejected_point: 'R1 instead of R2: the Steiner point would have encroached this subsegment',
    conforming: '-D: the subsegment is split until it is Delaunay',
  },
  split_triangle: {
    circumcentre: 'R2: a skinny triangle split at its circumcentre (Ruppert 1995)',
    offcentre: 'R2: a skinny triangle split at an off-centre (Üngör 2004)',
    best_point: 'R2: a skinny triangle split at the best point (Erten and Üngör 2009)',
    area: 'R2: the triangle is too large (-a), split at its circumcentre',
  },
  reject: {
    encroaches: 'the Steiner point encroaches a subsegment, which is split instead',
    outside: 'the Steiner point is outside the domain',
    precision: 'the Steiner point is too close to existing vertices',
    budget: 'the Steiner budget is spent',
  },
  remove: { coarsen: 'coarsening: the mesh is finer than the size field here' },
  move: { laplacian: 'smoothing: moved towards its neighbours\' centroid', odt: 'smoothing: optimal Delaunay triangulation target' },
  carve: { holes: 'triangles in a hole removed', exterior: 'triangles outside the segments removed' },
};

function explainEvent(ev) {
  if (!ev) return '';
  const why = (kWhy[ev.ev] || {})[ev.why];
  switch (ev.ev) {
    case 'phase': return `phase "${ev.name}" starts`;
    case 'points': return `${(ev.points || []).length} input vertices from ${ev.first}`;
    case 'recover':
      return `segment ${ev.seg} recovered by the ${ev.why} method` + (ev.flips !== undefined ? ` (${ev.flips} flips)` : '') +
        (why ? ': ' + why : '');
    case 'renumber': return 'vertices renumbered';
    case 'carve': return 'triangles outside the domain (in holes, outside the segments) removed';
    case 'undo': return 'refinement above 34° made no progress: back to the mesh refined to 34°';
    case 'insert': if (ev.v === undefined) return 'the triangles of the mesh read, all at once';
    // falls through
    case 'end': return `the end: ${ev.vertices} vertices, ${ev.triangles} triangles`;
    default: {
      const head = ev.ev.replace('_', ' ') + (ev.v !== undefined ? ` vertex ${ev.v}` : '') + (ev.edge ? ` edge ${ev.edge} → ${ev.to}` : '');
      return head + (why ? ': ' + why : ev.why ? ` (${ev.why})` : '');
    }
  }
}

function triKey(t) {
  // The triple rotated to start at its smallest id.
  const [a, b, c] = t;
  if (a <= b && a <= c) return a + ',' + b + ',' + c;
  if (b <= a && b <= c) return b + ',' + c + ',' + a;
  return c + ',' + a + ',' + b;
}

class TraceReplay {
  // text: the JSON Lines file. Throws Error with the line number on a bad line.
  constructor(text) {
    this.events = [];
    const lines = text.split('\n');
    lines.forEach((line, i) => {
      if (!line.trim()) return;
      let obj;
      try { obj = JSON.parse(line); } catch (e) { throw new Error(`trace line ${i + 1}: ${e.message}`); }
      if (i === 0 || obj.trace) {
        if (obj.trace !== 'deltamesh') throw new Error('trace line 1: not a deltamesh trace');
        if (obj.version !== 1) throw new Error(`trace line 1: schema version ${obj.version}, this page reads version 1`);
        this.header = obj;
        return;
      }
      this.events.push(obj);
    });
    this.phases = [];
    this.events.forEach((ev, i) => { if (ev.ev === 'phase') this.phases.push({ name: ev.name, index: i }); });
    this.every = Math.max(64, Math.ceil(this.events.length / 200));
    this.snapshots = [{ index: 0, state: { points: [], tris: new Map() } }];
    this.state = this.copy(this.snapshots[0].state);
    this.index = 0;  // events applied
    this.prevPoints = null;
  }

  copy(s) { return { points: s.points.slice(), tris: new Map(s.tris) }; }

  apply(ev) {
    const s = this.state;
    if (ev.ev === 'points') ev.points.forEach((p, i) => { s.points[ev.first + i] = p; });
    if (ev.v !== undefined && ev.p) s.points[ev.v] = ev.p;
    if (ev.ev === 'renumber') {
      // Entry map[i] takes the point of vertex i (the smallest such i), an
      // entry nothing maps to keeps its point; `vertices` entries in all.
      const n = ev.vertices !== undefined ? ev.vertices : Math.max(-1, ...ev.map) + 1;
      const points = s.points.slice(0, n);
      const taken = new Set();
      ev.map.forEach((to, from) => {
        if (to >= 0 && !taken.has(to)) { points[to] = s.points[from]; taken.add(to); }
      });
      points.length = n;
      const tris = new Map();
      for (const t of s.tris.values()) {
        const r = t.map((i) => ev.map[i]);
        tris.set(triKey(r), r);
      }
      s.points = points;
      s.tris = tris;
    }
    for (const t of ev.del || []) s.tris.delete(triKey(t));
    for (const t of ev.add || []) s.tris.set(triKey(t), t);
  }

  // Moves to the state after `n` events.
  seek(n) {
    n = Math.max(0, Math.min(this.events.length, n));
    if (n < this.index) {
      let snap = this.snapshots[0];
      for (const sn of this.snapshots) if (sn.index <= n) snap = sn;
      this.state = this.copy(snap.state);
      this.index = snap.index;
    }
    this.prevPoints = null;
    while (this.index < n) {
      if (this.index === n - 1) this.prevPoints = this.state.points.slice();
      this.apply(this.events[this.index]);
      ++this.index;
      if (this.index % this.every === 0 && this.snapshots[this.snapshots.length - 1].index < this.index)
        this.snapshots.push({ index: this.index, state: this.copy(this.state) });
    }
    return this.state;
  }

  current() { return this.index > 0 ? this.events[this.index - 1] : null; }

  // Does the state equal the mesh (xy, tri arrays from the written files)?
  // Same triangles (as vertex triples) and the same coordinates for their vertices.
  matches(view) {
    const s = this.state;
    const nt = view.tri.length / 3;
    if (s.tris.size !== nt) return { ok: false, why: `${s.tris.size} triangles replayed, the mesh has ${nt}` };
    for (let t = 0; t < nt; ++t) {
      const tri = [view.tri[3 * t], view.tri[3 * t + 1], view.tri[3 * t + 2]];
      if (!s.tris.has(triKey(tri))) return { ok: false, why: `triangle ${tri} of the mesh is not in the replay` };
      for (const v of tri) {
        const p = s.points[v];
        if (!p || p[0] !== view.xy[2 * v] || p[1] !== view.xy[2 * v + 1])
          return { ok: false, why: `vertex ${v} is at a different place in the replay` };
      }
    }
    return { ok: true, why: `${nt} triangles, the same vertices and coordinates` };
  }
}

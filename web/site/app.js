// The page: input (example, file, drop, drawing), switches, a run in the
// worker, and the result (picture, statistics, histogram, downloads, trace).
// Everything about meshing happens in the WebAssembly command line; this
// file only builds its arguments and shows what it wrote.
'use strict';

const $ = (id) => document.getElementById(id);
const view = new MeshView($('view'));
const worker = new Worker('worker.js');
let ready = false;
let traceSupported = false;
let input = null;      // {name, text}
let runCounter = 0;
let replay = null;
let lastView = null;
let playing = null;

// ---------------------------------------------------------------------------
// Drawing a PSLG

class Drawing {
  constructor() { this.vertices = []; this.segments = []; this.holes = []; this.chain = null; this.history = []; }
  empty() { return this.vertices.length === 0 && this.holes.length === 0; }
  snap(x, y, px) {
    let best = -1, bestD = 8 * px;
    this.vertices.forEach((v, i) => { const d = Math.hypot(v[0] - x, v[1] - y); if (d < bestD) { best = i; bestD = d; } });
    return best;
  }
  vertexAt(x, y, px) {
    const i = this.snap(x, y, px);
    if (i >= 0) return i;
    this.vertices.push([x, y]);
    this.history.push(() => this.vertices.pop());
    return this.vertices.length - 1;
  }
  click(tool, x, y, px) {
    if (tool === 'point') { this.vertexAt(x, y, px); this.chain = null; }
    if (tool === 'hole') { this.holes.push([x, y]); this.history.push(() => this.holes.pop()); }
    if (tool === 'segment') {
      const first = this.chain ? this.chain.first : null;
      const i = this.vertexAt(x, y, px);
      if (this.chain && i !== this.chain.last) {
        this.segments.push([this.chain.last, i]);
        this.history.push(() => this.segments.pop());
      }
      this.chain = i === first && this.chain ? null : { first: first === null ? i : first, last: i };
    }
  }
  endChain() { this.chain = null; }
  undo() { const u = this.history.pop(); if (u) u(); this.chain = null; }
  // A .poly file (1-based): the vertices, segments and hole points drawn.
  toPoly() {
    const fmt = (v) => String(Math.round(v * 1e6) / 1e6);
    const lines = ['# drawn in the deltamesh web app', `${this.vertices.length} 2 0 0`];
    this.vertices.forEach((v, i) => lines.push(`${i + 1} ${fmt(v[0])} ${fmt(v[1])}`));
    lines.push(`${this.segments.length} 0`);
    this.segments.forEach((s, i) => lines.push(`${i + 1} ${s[0] + 1} ${s[1] + 1}`));
    lines.push(`${this.holes.length}`);
    this.holes.forEach((h, i) => lines.push(`${i + 1} ${fmt(h[0])} ${fmt(h[1])}`));
    return lines.join('\n') + '\n';
  }
  draw(ctx, px) {
    ctx.strokeStyle = '#0d47a1'; ctx.lineWidth = 2 * px;
    ctx.beginPath();
    for (const [a, b] of this.segments) {
      ctx.moveTo(this.vertices[a][0], this.vertices[a][1]); ctx.lineTo(this.vertices[b][0], this.vertices[b][1]);
    }
    ctx.stroke();
    ctx.fillStyle = '#0d47a1';
    for (const v of this.vertices) { ctx.beginPath(); ctx.arc(v[0], v[1], 3 * px, 0, 7); ctx.fill(); }
    ctx.strokeStyle = '#c62828'; ctx.lineWidth = 2 * px;
    for (const h of this.holes) {
      ctx.beginPath(); ctx.moveTo(h[0] - 5 * px, h[1] - 5 * px); ctx.lineTo(h[0] + 5 * px, h[1] + 5 * px);
      ctx.moveTo(h[0] - 5 * px, h[1] + 5 * px); ctx.lineTo(h[0] + 5 * px, h[1] - 5 * px); ctx.stroke();
    }
  }
}
let drawing = null;

function tool() { return document.querySelector('input[name=tool]:checked').value; }

// ---------------------------------------------------------------------------
// Input

function setInput(name, text, autoRun) {
  input = { name, text };
  $('input-name').textContent = `${name} (${text.length} bytes)`;
  if (drawing && name !== 'drawing.poly') { drawing = null; view.drawing = null; }
  updateCommand();
  if (autoRun && ready) runMesh();
}

function readFile(file) {
  const r = new FileReader();
  r.onload = () => setInput(file.name, String(r.result), true);
  r.onerror = () => showError(`${file.name}: could not be read (${r.error})`);
  r.readAsText(file);
}

$('file').addEventListener('change', (e) => { if (e.target.files[0]) readFile(e.target.files[0]); e.target.value = ''; });
$('load-example').addEventListener('click', () => {
  fetch('plate.poly').then((r) => r.text()).then((t) => setInput('plate.poly', t, true))
    .catch((e) => showError('plate.poly: ' + e));
});
const wrap = $('view-wrap');
wrap.addEventListener('dragover', (e) => { e.preventDefault(); wrap.classList.add('dragging'); });
wrap.addEventListener('dragleave', () => wrap.classList.remove('dragging'));
wrap.addEventListener('drop', (e) => {
  e.preventDefault();
  wrap.classList.remove('dragging');
  const f = e.dataTransfer.files[0];
  if (f) readFile(f);
});

$('draw-new').addEventListener('click', () => {
  drawing = new Drawing();
  view.drawing = drawing;
  view.setMesh(null);
  view.setTrace(null);
  $('trace-panel').hidden = true;
  input = null;
  $('input-name').textContent = 'drawing (empty)';
  document.querySelector('input[name=tool][value=segment]').checked = true;
  view.fit({ minx: 0, miny: 0, maxx: 10, maxy: 10 });
  updateCommand();
});
$('draw-undo').addEventListener('click', () => { if (drawing) { drawing.undo(); drawingChanged(); } });

function drawingChanged() {
  view.draw();
  if (drawing && !drawing.empty()) setInput('drawing.poly', drawing.toPoly(), false);
}

// Pointer: pan with a drag (any tool), draw with a click.
let drag = null;
const canvas = $('view');
canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, moved: false }; canvas.setPointerCapture(e.pointerId); });
canvas.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  if (drag.moved || Math.hypot(dx, dy) > 4) {
    drag.moved = true;
    view.pan(dx, dy);
    drag.x = e.clientX; drag.y = e.clientY;
  }
});
canvas.addEventListener('pointerup', (e) => {
  const d = drag;
  drag = null;
  if (!d || d.moved || tool() === 'pan') return;
  if (!drawing) {
    drawing = new Drawing();
    view.drawing = drawing;
    view.setMesh(null);
    view.setTrace(null);
  }
  const r = canvas.getBoundingClientRect();
  const [x, y] = view.toWorld(e.clientX - r.left, e.clientY - r.top);
  drawing.click(tool(), x, y, 1 / view.scale);
  drawingChanged();
});
canvas.addEventListener('dblclick', () => { if (drawing) drawing.endChain(); });
window.addEventListener('keydown', (e) => { if (e.key === 'Escape' && drawing) drawing.endChain(); });
canvas.addEventListener('wheel', (e) => {
  e.preventDefault();
  const r = canvas.getBoundingClientRect();
  view.zoomAt(e.clientX - r.left, e.clientY - r.top, Math.exp(-e.deltaY * 0.0015));
}, { passive: false });

// ---------------------------------------------------------------------------
// Switches -> the command line's arguments

function inputKind(name) {
  const n = name.toLowerCase();
  if (n.endsWith('.poly')) return 'poly';
  if (n.endsWith('.node')) return 'node';
  if (n.endsWith('.geojson') || n.endsWith('.json')) return 'geojson';
  return 'unknown';
}

function baseName(name) { return name.replace(/\.(poly|node|geojson|json)$/i, ''); }

function switches(kind) {
  let s = '-';
  if (kind === 'poly') s += 'p';
  if ($('quality').checked) s += 'q' + ($('angle').value.trim() || '');
  const area = $('area').value.trim();
  if (area) s += 'a' + area;
  if ($('conforming').checked) s += 'D';
  s += 'Y'.repeat(Number($('noboundary').value));
  const budget = $('steiner').value.trim();
  if (budget) s += 'S' + budget;
  return s + 'V';
}

function commandArgs() {
  if (!input) return null;
  const kind = inputKind(input.name);
  const base = baseName(input.name) + '.1';
  const args = [switches(kind), '--cdt=' + $('cdt').value];
  const extra = $('extra').value.trim();
  if (extra) args.push(...extra.split(/\s+/));
  args.push('--stats=json');
  const outputs = [base + '.node', base + '.ele', base + '.poly', base + '.msh', base + '.vtu', base + '.svg'];
  for (const f of outputs) args.push('--output', '/out/' + f);
  let trace = null;
  if ($('trace').checked && traceSupported) {
    trace = base + '.trace.jsonl';
    args.push('--trace', '/out/' + trace);
  }
  args.push('/in/' + input.name);
  return { args, outputs, base, trace };
}

function updateCommand() {
  const c = commandArgs();
  if (!c) { $('command').textContent = ''; return; }
  const shown = c.args.filter((a, i) => !(a.startsWith('/out/') || c.args[i + 1]?.startsWith('/out/') ||
    a === '--stats=json')).map((a) => a.replace('/in/', ''));
  $('command').textContent = 'deltamesh ' + shown.join(' ');
}
for (const id of ['cdt', 'quality', 'angle', 'area', 'conforming', 'noboundary', 'steiner', 'trace', 'extra'])
  $(id).addEventListener('input', updateCommand);

// ---------------------------------------------------------------------------
// Running

function setStatus(text) { $('status').textContent = text; }
function showError(text) { const e = $('error'); e.textContent = text; e.hidden = !text; }

function runMesh() {
  if (!ready) return;
  if (!input) { showError('nothing to mesh: load the example, open or drop a file, or draw'); return; }
  const c = commandArgs();
  const id = ++runCounter;
  showError('');
  setStatus('meshing…');
  $('mesh').disabled = true;
  worker.postMessage({ type: 'run', id, name: input.name, text: input.text, args: c.args, outputs: c.outputs,
    base: c.base, trace: c.trace });
}
$('mesh').addEventListener('click', runMesh);

worker.onmessage = (e) => {
  const m = e.data;
  if (m.type === 'ready') {
    ready = true;
    traceSupported = m.traceSupported;
    if (!traceSupported) { $('trace').checked = false; $('trace').disabled = true; $('trace').parentElement.title = 'this build has no --trace'; }
    $('mesh').disabled = false;
    setStatus(`ready (${m.version})`);
    updateCommand();
    if (input) runMesh();
  } else if (m.type === 'progress') {
    if (m.id === runCounter && m.line.trim()) setStatus(m.line.trim());
  } else if (m.type === 'result') {
    if (m.id !== runCounter) return;
    $('mesh').disabled = false;
    showResult(m);
  }
};
worker.onerror = (e) => { setStatus('the mesher failed to load'); showError('web worker: ' + (e.message || e)); };

function showResult(m) {
  const lines = m.stdout.split('\n');
  const json = lines.filter((l) => l.startsWith('{')).pop();
  // The files live in the worker's /in and /out: the names are what the user knows.
  $('log').textContent = (lines.filter((l) => !l.startsWith('{')).join('\n') + (m.stderr ? '\n' + m.stderr : ''))
    .replace(/\/(in|out)\//g, '');
  const failed = !(m.code === 0 || m.code === 3) || !m.view || m.view.error;
  if (failed) {
    const msg = m.stderr || (m.view && m.view.error) || `exit code ${m.code}`;
    showError(msg.replace(/\/in\//g, ''));
    setStatus(`error (exit code ${m.code})`);
    window.dmApp.last = { code: m.code, error: msg };
    return;
  }
  showError(m.code === 3 ? m.stderr.replace(/\/in\//g, '') : '');
  const q = json ? JSON.parse(json) : null;
  lastView = m.view;
  view.drawing = null;
  view.setTrace(null);
  view.setMesh(m.view);
  view.fit(view.mesh.bounds);
  const nt = m.view.angle.length;
  $('triangle-count').textContent = String(q ? q.triangles : nt);
  $('vertex-count').textContent = String(m.view.xy.length / 2);
  $('min-angle').textContent = q && q.min_angle_deg !== null ? q.min_angle_deg.toFixed(4) + '°' : '–';
  $('max-angle').textContent = q && q.max_angle_deg !== null ? q.max_angle_deg.toFixed(4) + '°' : '–';
  $('run-time').textContent = m.ms.toFixed(0) + ' ms';
  if (q) histogram(q.angle_histogram_deg10);
  downloads(m.files);
  setStatus(`done: ${nt} triangles` + (m.code === 3 ? ' (budget reached)' : ''));
  window.dmApp.last = { code: m.code, stats: q, triangles: nt, stdout: m.stdout, stderr: m.stderr };
  setupTrace(m.trace);
}

function histogram(h) {
  const svg = $('histogram');
  const max = Math.max(1, ...h);
  let s = '';
  h.forEach((n, i) => {
    const hgt = 64 * n / max;
    s += `<rect x="${i * 10 + 0.5}" y="${68 - hgt}" width="9" height="${hgt}" fill="${angleColour(Math.min(60, i * 10 + 5))}" stroke="#555" stroke-width="0.2"><title>${i * 10}°–${i * 10 + 10}°: ${n} angles</title></rect>`;
  });
  svg.innerHTML = s + '<line x1="0" y1="68.5" x2="180" y2="68.5" stroke="#555" stroke-width="0.3"/>';
}

let urls = [];
function downloads(files) {
  for (const u of urls) URL.revokeObjectURL(u);
  urls = [];
  const box = $('downloads');
  box.textContent = '';
  for (const [name, data] of Object.entries(files)) {
    const u = URL.createObjectURL(new Blob([data], { type: 'application/octet-stream' }));
    urls.push(u);
    const a = document.createElement('a');
    a.href = u; a.download = name; a.textContent = name.replace(/^.*\./, '.');
    a.title = `${name} (${data.length} bytes)`;
    box.appendChild(a);
  }
}

// ---------------------------------------------------------------------------
// Trace stepping

function setupTrace(text) {
  stopPlay();
  replay = null;
  $('trace-panel').hidden = !text;
  if (!text) return;
  try {
    replay = new TraceReplay(text);
  } catch (ex) {
    $('trace-panel').hidden = false;
    $('trace-explain').textContent = String(ex.message || ex);
    return;
  }
  $('tr-slider').max = String(replay.events.length);
  const sel = $('tr-phase');
  sel.innerHTML = '';
  for (const p of replay.phases) {
    const o = document.createElement('option');
    o.value = String(p.index + 1); o.textContent = `${p.name} (event ${p.index + 1})`;
    sel.appendChild(o);
  }
  showStep(0);
}

function showStep(n) {
  if (!replay) return;
  const state = replay.seek(n);
  const ev = replay.current();
  $('tr-slider').value = String(replay.index);
  $('trace-step').textContent = `${replay.index} / ${replay.events.length}`;
  $('trace-tris').textContent = `${state.tris.size} triangles`;
  $('trace-explain').textContent = explainEvent(ev);
  if (replay.index === 0 || replay.index === replay.events.length) {
    if (replay.index === 0) { view.setTrace(null); $('trace-match').textContent = ''; return; }
    const r = replay.matches(lastView);
    $('trace-match').textContent = (r.ok ? 'the replay reaches the final mesh: ' : 'the replay differs from the mesh: ') + r.why;
    $('trace-match').dataset.ok = String(r.ok);
  } else {
    $('trace-match').textContent = '';
  }
  view.setTrace(state, ev, replay.prevPoints);
}

function stopPlay() { if (playing) clearInterval(playing); playing = null; $('tr-play').textContent = '▶'; }
$('tr-first').addEventListener('click', () => { stopPlay(); showStep(0); });
$('tr-last').addEventListener('click', () => { stopPlay(); showStep(replay ? replay.events.length : 0); });
$('tr-back').addEventListener('click', () => { stopPlay(); if (replay) showStep(replay.index - 1); });
$('tr-fwd').addEventListener('click', () => { stopPlay(); if (replay) showStep(replay.index + 1); });
$('tr-slider').addEventListener('input', (e) => { stopPlay(); showStep(Number(e.target.value)); });
$('tr-phase').addEventListener('change', (e) => { stopPlay(); showStep(Number(e.target.value)); });
$('tr-play').addEventListener('click', () => {
  if (playing) { stopPlay(); return; }
  if (!replay) return;
  if (replay.index >= replay.events.length) showStep(0);
  $('tr-play').textContent = '❚❚';
  playing = setInterval(() => {
    // Speed: events per second; several per tick when fast.
    const perTick = Math.max(1, Math.round(Number($('tr-speed').value) / 25));
    showStep(replay.index + perTick);
    if (replay.index >= replay.events.length) stopPlay();
  }, 40);
});

// Legend
(() => {
  const c = $('legend').getContext('2d');
  for (let x = 0; x < 180; ++x) { c.fillStyle = angleColour(x / 3); c.fillRect(x, 0, 1, 12); }
})();

// For the browser tests (tests/web) and the curious: the last run's numbers.
window.dmApp = { last: null, runMesh, setInput, view, input: () => input };
updateCommand();

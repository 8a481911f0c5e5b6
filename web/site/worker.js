// The mesher's thread: loads the WebAssembly build of the command line
// (deltamesh.js, built by `make web`) and runs it on one input file in the
// in-memory file system, so the page stays responsive on large meshes.
//
// Messages in:  {type: 'run', id, name, text, args, outputs, trace}
// Messages out: {type: 'ready', traceSupported, version}
//               {type: 'progress', id, line}
//               {type: 'result', id, code, stdout, stderr, ms, view, files, trace}
'use strict';
importScripts('deltamesh.js');

let mod = null;
let out = [];
let err = [];
let runId = null;

function capture(isErr) {
  return (line) => {
    // Emscripten hands over whole lines: a progress line of the command line
    // ("\r" + text, erased by "\r   \r") arrives glued to the next line.
    const parts = line.split('\r');
    if (isErr && runId !== null && parts.length > 1) postMessage({ type: 'progress', id: runId, line: parts[parts.length - 2] });
    const text = parts[parts.length - 1];
    if (parts.length === 1 || text.trim()) (isErr ? err : out).push(text);
  };
}

function cli(args) {
  out = [];
  err = [];
  const code = mod.ccall('dm_run', 'number', ['string'], [args.join('\n')]);
  return { code, stdout: out.join('\n'), stderr: err.join('\n') };
}

function clearDir(dir) {
  const FS = mod.FS;
  try { FS.mkdir(dir); } catch (e) { /* exists */ }
  for (const f of FS.readdir(dir)) if (f !== '.' && f !== '..') FS.unlink(dir + '/' + f);
}

function loadView(base) {
  if (mod.ccall('dm_view_load', 'number', ['string'], [base]) !== 0)
    return { error: mod.ccall('dm_view_error', 'string', [], []) };
  const nv = mod._dm_view_vertices(), nt = mod._dm_view_triangles(), ns = mod._dm_view_segments();
  const f64 = (ptr, n) => mod.HEAPF64.slice(ptr >> 3, (ptr >> 3) + n);
  const i32 = (ptr, n) => mod.HEAP32.slice(ptr >> 2, (ptr >> 2) + n);
  return {
    xy: f64(mod._dm_view_xy(), 2 * nv),
    tri: i32(mod._dm_view_corners(), 3 * nt),
    angle: f64(mod._dm_view_min_angle(), nt),
    seg: i32(mod._dm_view_segment_ends(), 2 * ns),
  };
}

function run(msg) {
  const FS = mod.FS;
  clearDir('/in');
  clearDir('/out');
  FS.writeFile('/in/' + msg.name, msg.text);
  const t0 = performance.now();
  runId = msg.id;
  const r = cli(msg.args);
  runId = null;
  const ms = performance.now() - t0;
  const result = { type: 'result', id: msg.id, code: r.code, stdout: r.stdout, stderr: r.stderr, ms, files: {} };
  const transfer = [];
  if (r.code === 0 || r.code === 3) {
    result.view = loadView('/out/' + msg.base);
    for (const [k, v] of Object.entries(result.view)) if (v && v.buffer) transfer.push(v.buffer);
    for (const f of msg.outputs) {
      try {
        const data = FS.readFile('/out/' + f);
        result.files[f] = data;
        transfer.push(data.buffer);
      } catch (e) { /* not written */ }
    }
    if (msg.trace) {
      try { result.trace = FS.readFile('/out/' + msg.trace, { encoding: 'utf8' }); } catch (e) { result.trace = null; }
    }
  }
  postMessage(result, transfer);
}

createDeltamesh({ print: capture(false), printErr: capture(true) }).then((m) => {
  mod = m;
  const help = cli(['--help']).stdout;
  const version = cli(['--version']).stdout.trim();
  postMessage({ type: 'ready', traceSupported: /--trace/.test(help), version });
});

onmessage = (e) => {
  if (e.data.type === 'run') {
    try {
      run(e.data);
    } catch (ex) {
      postMessage({ type: 'result', id: e.data.id, code: -1, stdout: '', stderr: 'web worker: ' + ex, ms: 0, files: {} });
    }
  }
};

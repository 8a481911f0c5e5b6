// Browser tests of the web app (web/): the page built by `make web`, served
// by a static file server started here, driven in headless Debian chromium
// through puppeteer-core. The numbers the page shows are compared with the
// native command line's on the same input and switches.
//
//   node tests/web/run.mjs --site build-web/site --cli build/bin/deltamesh \
//        --example examples/plate.poly [--screenshot docs/img/web-app.png]
//
// Exit code 0 when every check passed; each check prints "ok" or "FAIL".
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const opt = { site: 'build-web/site', cli: 'build/bin/deltamesh', example: 'examples/plate.poly', screenshot: null,
  chromium: process.env.CHROMIUM || '/usr/bin/chromium' };
for (let i = 2; i < process.argv.length; i += 2) opt[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];

let failures = 0;
function check(ok, what, detail = '') {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}${detail ? ' -- ' + detail : ''}`);
  if (!ok) ++failures;
}

// A static file server: what any static server does, nothing more.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.css': 'text/css',
  '.poly': 'text/plain' };
const server = http.createServer((req, res) => {
  const rel = decodeURIComponent(new URL(req.url, 'http://x').pathname).replace(/^\/+/, '') || 'index.html';
  const file = path.join(opt.site, path.normalize(rel));
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end('not found'); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const url = `http://127.0.0.1:${server.address().port}/index.html`;

const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'deltamesh-web-'));

// The native command line on the same input: its --stats=json numbers.
function cliStats(inputPath, sw, cdt) {
  const base = path.join(tmp, path.basename(inputPath).replace(/\.[^.]*$/, ''));
  if (path.resolve(inputPath) !== path.resolve(base + path.extname(inputPath)))
    fs.copyFileSync(inputPath, base + path.extname(inputPath));
  const r = spawnSync(opt.cli, [sw, '--cdt=' + cdt, '--stats=json', '--output', base + '.1.node',
    base + path.extname(inputPath)], { encoding: 'utf8' });
  const json = r.stdout.split('\n').filter((l) => l.startsWith('{')).pop();
  return { code: r.status, stats: json ? JSON.parse(json) : null, stderr: r.stderr };
}

const browser = await puppeteer.launch({ executablePath: opt.chromium, headless: true, protocolTimeout: 600000,
  args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'] });
const page = await browser.newPage();
await page.setViewport({ width: 1400, height: 860 });
const pageErrors = [];
page.on('pageerror', (e) => pageErrors.push(String(e)));
page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });

async function setSwitches(s) {
  await page.evaluate((s) => {
    const $ = (id) => document.getElementById(id);
    $('cdt').value = s.cdt;
    $('quality').checked = s.angle !== undefined;
    $('angle').value = s.angle ?? '';
    $('area').value = s.area ?? '';
    $('conforming').checked = !!s.D;
    $('noboundary').value = String(s.Y ?? 0);
    $('steiner').value = s.S ?? '';
    $('trace').checked = !!s.trace;
    $('extra').value = '';
    $('cdt').dispatchEvent(new Event('input'));
  }, s);
}

// Starts a run (by `start`) and waits for its result.
async function meshAndWait(start) {
  await page.evaluate(() => { window.dmApp.last = null; });
  await start();
  await page.waitForFunction(() => window.dmApp.last !== null, { timeout: 300000 });
  return page.evaluate(() => window.dmApp.last);
}

try {
  await page.goto(url);
  await page.waitForFunction(() => /^ready/.test(document.getElementById('status').textContent), { timeout: 120000 });
  check(true, 'the page loads and the WebAssembly mesher starts');
  const traceSupported = await page.evaluate(() => !document.getElementById('trace').disabled);

  // 1. The bundled example, several methods and switches: the page's triangle
  //    count and smallest angle are the command line's.
  const cases = [
    { cdt: 'fast', angle: '30', area: '0.05', sw: '-pq30a0.05V' },
    { cdt: 'lifting', angle: '25', Y: 1, sw: '-pq25YV' },
    { cdt: 'lawson', sw: '-pV' },
    { cdt: 'ct', angle: '20', D: true, S: '40', sw: '-pq20DS40V' },
  ];
  for (const c of cases) {
    await setSwitches(c);
    const last = await meshAndWait(() => page.click('#load-example'));
    const shown = await page.evaluate(() => ({ tris: document.getElementById('triangle-count').textContent,
      angle: document.getElementById('min-angle').textContent, command: document.getElementById('command').textContent }));
    const cli = cliStats(opt.example, c.sw, c.cdt);
    const what = `plate.poly ${c.sw} --cdt=${c.cdt}`;
    check(shown.command.startsWith(`deltamesh ${c.sw} --cdt=${c.cdt}`), `${what}: the page shows the command`, shown.command);
    check(last.code === cli.code && last.stats && cli.stats, `${what}: exit code ${last.code} (CLI ${cli.code})`);
    if (last.stats && cli.stats) {
      check(last.stats.triangles === cli.stats.triangles && shown.tris === String(cli.stats.triangles),
        `${what}: triangles in the page = CLI`, `${shown.tris} / ${cli.stats.triangles}`);
      check(last.stats.min_angle_deg === cli.stats.min_angle_deg &&
        shown.angle === cli.stats.min_angle_deg.toFixed(4) + '°',
        `${what}: smallest angle in the page = CLI`, `${shown.angle} / ${cli.stats.min_angle_deg}`);
    }
  }

  // 2. The trace of a run, stepped through to its end, is the final mesh.
  //    (Whenever the tree has --trace, the page must have it too.)
  const cliTrace = /--trace/.test(spawnSync(opt.cli, ['--help'], { encoding: 'utf8' }).stdout);
  if (cliTrace || traceSupported)
    check(traceSupported && cliTrace, 'the WebAssembly build and the CLI both have --trace', `${traceSupported} / ${cliTrace}`);
  else
    console.log('skip this tree has no --trace: the trace checks are skipped');
  if (traceSupported) {
    await setSwitches({ cdt: 'lifting', angle: '28', trace: true });
    await meshAndWait(() => page.click('#load-example'));
    const steps = await page.evaluate(() => document.getElementById('trace-step').textContent);
    check(/^0 \/ [1-9]\d*$/.test(steps), 'the trace is loaded, at its start', steps);
    await page.click('#tr-fwd');
    await page.click('#tr-fwd');
    const second = await page.evaluate(() => ({ step: document.getElementById('trace-step').textContent,
      why: document.getElementById('trace-explain').textContent }));
    check(second.step.startsWith('2 /') && second.why.length > 0, 'stepping forward explains each event', second.why);
    await page.select('#tr-phase', await page.evaluate(() => document.querySelector('#tr-phase option:last-child').value));
    await page.click('#tr-last');
    const end = await page.evaluate(() => ({ ok: document.getElementById('trace-match').dataset.ok,
      text: document.getElementById('trace-match').textContent }));
    check(end.ok === 'true', 'stepping to the end of the trace reaches the final mesh', end.text);
    await page.click('#tr-back');
    await page.click('#tr-fwd');
  }

  // 3. A dropped .poly with a syntax error: the file:line message, as the CLI words it.
  const broken = '# a broken file\n4 2 0 0\n1 0 0\n2 1 0\n3 1 x1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n';
  const brokenPath = path.join(tmp, 'broken.poly');
  fs.writeFileSync(brokenPath, broken);
  await setSwitches({ cdt: 'fast', angle: '30' });
  const bad = await meshAndWait(() => page.evaluate((text) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], 'broken.poly'));
    document.getElementById('view-wrap').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, broken));
  const err = await page.evaluate(() => ({ hidden: document.getElementById('error').hidden,
    text: document.getElementById('error').textContent }));
  const cliBad = spawnSync(opt.cli, ['-pq30', brokenPath], { encoding: 'utf8' });
  const cliMsg = cliBad.stderr.trim().replace(brokenPath, 'broken.poly');
  check(bad.code === 2 && cliBad.status === 2, 'the broken .poly: exit code 2 in the page and the CLI', `${bad.code} / ${cliBad.status}`);
  check(!err.hidden && /broken\.poly:5:/.test(err.text), 'the broken .poly: the page shows file:line', err.text);
  check(err.text.trim() === cliMsg, 'the broken .poly: the same message as the CLI', cliMsg);

  // 3b. Dropped GeoJSON (a polygon with a hole, meshed even-odd) and .node
  //     (a point set) files: the command line's numbers too.
  const dropped = [
    ['ring.geojson', '{"type":"Polygon","coordinates":[[[0,0],[4,0],[4,3],[0,3],[0,0]],[[1,1],[2,1],[2,2],[1,2],[1,1]]]}\n', '-q30V'],
    ['points.node', '6 2 0 0\n1 0 0\n2 3 0\n3 3 2\n4 0 2\n5 1.5 0.7\n6 0.4 1.6\n', '-q30V'],
  ];
  for (const [name, text, sw] of dropped) {
    await setSwitches({ cdt: 'fast', angle: '30' });
    const r = await meshAndWait(() => page.evaluate((name, text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], name));
      document.getElementById('view-wrap').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, name, text));
    const file = path.join(tmp, name);
    fs.writeFileSync(file, text);
    const cli = cliStats(file, sw, 'fast');
    // The same mesh; its smallest angle in degrees comes from each
    // platform's asin (musl's in WebAssembly, glibc's natively), which may
    // differ in the last bit.
    check(r.code === 0 && r.stats && cli.stats && r.stats.triangles === cli.stats.triangles &&
      r.stats.vertices === cli.stats.vertices &&
      Math.abs(r.stats.min_angle_deg - cli.stats.min_angle_deg) <= 1e-12 * cli.stats.min_angle_deg,
      `dropped ${name}: the CLI's triangles and smallest angle`,
      `${r.stats && r.stats.triangles} / ${cli.stats && cli.stats.triangles}, ` +
      `${r.stats && r.stats.min_angle_deg}° / ${cli.stats && cli.stats.min_angle_deg}°`);
  }

  // 4. A PSLG drawn with the mouse: a square with a square hole.
  await page.click('#draw-new');
  await setSwitches({ cdt: 'fast', angle: '30', area: '1' });
  const click = async (wx, wy) => {
    const [sx, sy] = await page.evaluate((wx, wy) => {
      const v = document.getElementById('view').getBoundingClientRect();
      const [x, y] = window.dmApp.view.toScreen(wx, wy);  // the page's world -> CSS pixels in the canvas
      return [v.left + x, v.top + y];
    }, wx, wy);
    await page.mouse.click(sx, sy);
  };
  for (const [x, y] of [[1, 1], [9, 1], [9, 9], [1, 9], [1, 1], [4, 4], [6, 4], [6, 6], [4, 6], [4, 4]]) await click(x, y);
  await page.click('input[name=tool][value=hole]');
  await click(5, 5);
  const drawn = await meshAndWait(() => page.click('#mesh'));
  const cliDrawnPath = path.join(tmp, 'drawing.poly');
  fs.writeFileSync(cliDrawnPath, await page.evaluate(() => window.dmApp.input().text));
  const cliDrawn = cliStats(cliDrawnPath, '-pq30a1V', 'fast');
  check(drawn.code === 0 && drawn.stats && cliDrawn.stats && drawn.stats.triangles === cliDrawn.stats.triangles &&
    drawn.stats.min_angle_deg === cliDrawn.stats.min_angle_deg,
    'a square with a square hole drawn with the mouse meshes as the CLI meshes its .poly',
    `${drawn.stats && drawn.stats.triangles} triangles`);
  check(drawn.stats && drawn.stats.triangles > 0 && (await page.evaluate(() => window.dmApp.input().text)).includes('\n1\n1 5 5'),
    'the drawing has its hole point');

  // 5. About 10^5 triangles: the page answers while the worker meshes.
  await setSwitches({ cdt: 'fast', angle: '30', area: '0.0006' });
  await page.evaluate(() => { window.dmApp.last = null; });
  await page.click('#load-example');
  const t0 = Date.now();
  let answered = 0, maxGap = 0;
  while (!(await page.evaluate(() => window.dmApp.last !== null))) {
    const t = Date.now();
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
    maxGap = Math.max(maxGap, Date.now() - t);
    ++answered;
    if (Date.now() - t0 > 300000) break;
  }
  // ... and while the page turns the result into paths, slice by slice.
  while (!(await page.evaluate(() => window.dmApp.view.complete()))) {
    const t = Date.now();
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
    maxGap = Math.max(maxGap, Date.now() - t);
    ++answered;
    if (Date.now() - t0 > 600000) break;
  }
  const big = await page.evaluate(() => window.dmApp.last);
  const bigCli = cliStats(opt.example, '-pq30a0.0006V', 'fast');
  check(big && big.stats && bigCli.stats && big.stats.triangles === bigCli.stats.triangles && big.stats.triangles > 80000,
    'plate.poly -pq30a0.0006: about 10^5 triangles, as many as the CLI', `${big && big.stats && big.stats.triangles}`);
  check(answered >= 2, 'the page kept drawing frames while the worker meshed',
    `${answered} frames, longest wait ${maxGap} ms, ${Date.now() - t0} ms in all`);

  // 6. The screenshot for the docs: the example meshed, its trace ready to step through.
  if (opt.screenshot) {
    await page.click('input[name=tool][value=pan]');
    await setSwitches({ cdt: 'fast', angle: '30', area: '0.05', trace: traceSupported });
    await meshAndWait(() => page.click('#load-example'));
    await page.waitForFunction(() => window.dmApp.view.complete(), { timeout: 120000 });
    fs.mkdirSync(path.dirname(opt.screenshot), { recursive: true });
    await page.screenshot({ path: opt.screenshot });
    check(fs.statSync(opt.screenshot).size > 10000, `screenshot written to ${opt.screenshot}`);
  }
  check(pageErrors.length === 0, 'no errors in the page\'s console', pageErrors.join(' | '));
} catch (e) {
  check(false, 'the browser test ran to its end', String(e && e.stack || e));
} finally {
  await browser.close();
  server.close();
  fs.rmSync(tmp, { recursive: true, force: true });
}
console.log(failures ? `${failures} browser check(s) failed` : 'all browser checks passed');
process.exit(failures ? 1 : 0);

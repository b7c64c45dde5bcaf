// Frame time of GeolensView (web/src/view.js) in chromium against the floor (issue 31, "How it
// is measured", second item): a scripted 300-frame drag of one circle lens at 1280 x 1024
// (through the view's own pointer handlers: PointerEvents dispatched on its canvas, one move per
// animation frame), against the same picture drawn as one textured quad per frame; both read
// back one pixel per frame so that SwiftShader's GPU work is counted. Then the same at the demo
// page's default canvas size (its geolens canvas at the tests' 1280 x 760 viewport, its picture
// examples/demo.png and its lens). Per run: the rAF-to-rAF interval and the frame's work (input
// + the view's animation frame: solve, upload, draw, outlines, readback), medians and 90th
// percentiles, the CPU time chromium's processes spent per frame (renderer, GPU process: less
// sensitive to a loaded machine than wall time), drafts and full frames, the moves shown in the
// next frame; then where the lens frame goes (timers around the view's steps, the GPU's draws
// alone in variants, and a CDP Profiler run, self time by function). Debian's chromium headless
// with SwiftShader's WebGL2, as the browser tests launch it (web/browser-test/browser.mjs), the
// repository served by their static server. About 4 minutes on 2 busy cores.
//
//   node bench/web/view_bench.mjs [--runs 2] [--frames 300] [--no-demo] [--no-profile]
//                                 [--unthrottled] [--draft-mesh N] [--only 1280|demo]
//                                 [--worker] [--floor-mip nearest] [--json out.json]
//
// --unthrottled launches chromium with --disable-gpu-vsync --disable-frame-rate-limit, so that
// frames follow as fast as they are made instead of at 60 Hz; --draft-mesh sets the view's
// draftMesh option (its drafts' grid, 30 by default) in the lens runs; --worker adds runs of the
// view's opt-in worker mode (the solve in a Web Worker) beside the default, page-thread one;
// --floor-mip nearest draws the floor with the drafts' sampling (the nearest mipmap level).

import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import { CHROMIUM, CHROMIUM_ARGS } from '../../web/browser-test/browser.mjs';
import { serve } from '../../web/browser-test/server.mjs';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : fallback;
};
const runs = Number(option('--runs', 2));
const frameCount = Number(option('--frames', 300));
const unthrottled = args.includes('--unthrottled');
const jsonOut = option('--json', null);
const draftMesh = option('--draft-mesh', null);
const floorMip = option('--floor-mip', null); // 'nearest': the floor samples as drafts do
const only = option('--only', null); // '1280' or 'demo': one of the two configurations
const withWorker = args.includes('--worker');

// ---------------------------------------------------------------------------------------------
// Statistics

function quantile(values, q) {
  const sorted = values.filter((v) => Number.isFinite(v)).sort((a, b) => a - b);
  if (sorted.length === 0) return NaN;
  const at = (sorted.length - 1) * q, lo = Math.floor(at), hi = Math.ceil(at);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * (at - lo);
}
const median = (values) => quantile(values, 0.5);
const p90 = (values) => quantile(values, 0.9);
const mean = (values) => values.reduce((a, b) => a + b, 0) / Math.max(1, values.length);
const fixed = (v, digits = 2) => (Number.isFinite(v) ? v.toFixed(digits) : '—');
const load = () => os.loadavg().map((v) => v.toFixed(2)).join(' ');

// The figures of one floor run: frames[0] starts it, frames 1..n are measured.
function floorFigures(result) {
  const f = result.frames;
  const intervals = [], work = [], sync = [];
  for (let i = 1; i < f.length; ++i) {
    intervals.push(f[i].timestamp - f[i - 1].timestamp);
    work.push(f[i].workMs);
    sync.push(f[i].syncMs);
  }
  return { intervals, work, sync };
}

const STEPS = ['input', 'update', 'solveJs', 'forward', 'upload', 'meshDraw', 'outlines',
  'cursor', 'sync', 'other'];

// The figures of one lens run: frames[0] presses the pointer, frames 1..n should show moves
// 1..n (the drag), frame n + 1 follows the release.
function lensFigures(result) {
  const f = result.frames;
  const n = result.lags.length;
  const intervals = [], work = [], steps = Object.fromEntries(STEPS.map((k) => [k, []]));
  let missing = 0;
  for (let i = 1; i <= n; ++i) {
    const x = f[i], r = x.record;
    intervals.push(x.timestamp - f[i - 1].timestamp);
    if (!r) {
      ++missing;
      work.push(x.inputMs);
      continue;
    }
    work.push(x.inputMs + r.viewMs);
    const get = (k) => r[k] || 0;
    const values = {
      input: x.inputMs, update: get('updateMs'),
      solveJs: get('showMs') - get('uploadMs') - get('forwardMs'), forward: get('forwardMs'),
      upload: get('uploadMs'), meshDraw: get('drawMs') - get('outlinesMs'),
      outlines: get('outlinesMs'), cursor: get('cursorMs'), sync: get('syncMs'),
      other: r.viewMs - get('updateMs') - get('showMs') - get('drawMs') - get('cursorMs') -
        get('syncMs'),
    };
    for (const k of STEPS) steps[k].push(values[k]);
  }
  const lags = result.lags.filter((x) => x !== null);
  return {
    intervals, work, steps, drafts: result.drafts, full: result.full, moves: n, missing,
    shown: result.lags.filter((x) => x === 0).length, shownEver: lags.length,
    lagMedian: median(lags), lagMax: Math.max(...lags),
    outsideShowMs: (result.outside.showMs || 0) / n,
    vertices: result.draftVertices, triangles: result.draftTriangles,
    rest: result.rest,
  };
}

// ---------------------------------------------------------------------------------------------
// CPU time of this bench's chromium (the processes under this node process), by kind: the
// renderer (the page's main thread: JS, wasm, WebGL calls) and the GPU process (SwiftShader's
// rasterizer, the compositor); Linux /proc, in ms. On a loaded machine the wall time of a frame
// depends on what else runs; the CPU time it costs much less.

const TICK_MS = 10; // USER_HZ = 100 on Linux

function chromiumCpu() {
  const procs = new Map();
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    try {
      const stat = readFileSync(`/proc/${name}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      procs.set(Number(name), {
        ppid: Number(fields[1]),
        ms: (Number(fields[11]) + Number(fields[12])) * TICK_MS,
      });
    } catch {
      // gone meanwhile
    }
  }
  const ours = new Set([process.pid]);
  for (let grew = true; grew;) {
    grew = false;
    for (const [pid, p] of procs) {
      if (!ours.has(pid) && ours.has(p.ppid)) ours.add(pid), (grew = true);
    }
  }
  const out = new Map();
  for (const pid of ours) {
    if (pid === process.pid) continue;
    let kind = 'other';
    try {
      const cmdline = readFileSync(`/proc/${pid}/cmdline`, 'utf8');
      if (cmdline.includes('--type=gpu-process')) kind = 'gpu';
      else if (cmdline.includes('--type=renderer')) kind = 'renderer';
    } catch {
      continue;
    }
    out.set(pid, { kind, ms: procs.get(pid).ms });
  }
  return out;
}

// CPU ms by kind spent between two chromiumCpu() snapshots.
function cpuSpent(before, after) {
  const spent = { renderer: 0, gpu: 0, other: 0 };
  for (const [pid, p] of after) spent[p.kind] += p.ms - (before.get(pid)?.ms ?? 0);
  return spent;
}

// ---------------------------------------------------------------------------------------------
// The browser

async function launch() {
  const extra = unthrottled ? ['--disable-gpu-vsync', '--disable-frame-rate-limit'] : [];
  return chromium.launch({ executablePath: CHROMIUM, args: [...CHROMIUM_ARGS, ...extra] });
}

// The demo page's geolens canvas (device pixels) at the browser tests' viewport.
async function demoCanvas(browser, url) {
  const context = await browser.newContext({
    viewport: { width: 1280, height: 760 }, deviceScaleFactor: 1,
  });
  try {
    const page = await context.newPage();
    await page.goto(`${url}/web/demo/`);
    await page.waitForFunction(() => document.body.dataset.ready === '1', null,
      { timeout: 60000 });
    return await page.evaluate(() => {
      const c = window.__geolensView.canvas;
      return { width: c.width, height: c.height, lens: window.__geolensView.lenses[0] };
    });
  } finally {
    await context.close();
  }
}

// One run of the bench page: {info, result, load: [before, after]} (and the profile if asked).
async function runPage(browser, url, query,
  { profile = false, gpu = false, frames = frameCount } = {}) {
  const [w, h] = /size=(\d+)x(\d+)/.exec(query).slice(1).map(Number);
  const context = await browser.newContext({
    viewport: { width: Math.max(w, 640), height: Math.max(h, 480) }, deviceScaleFactor: 1,
  });
  try {
    const page = await context.newPage();
    const problems = [];
    page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
    page.on('pageerror', (e) => problems.push(e.message));
    await page.goto(`${url}/bench/web/view_bench.html?${query}&frames=${frames}`);
    await page.waitForFunction(() => window.__bench !== undefined, null, { timeout: 60000 });
    await page.evaluate(() => window.__bench.warm());
    let cdp = null;
    if (profile) {
      cdp = await context.newCDPSession(page);
      await cdp.send('Profiler.enable');
      await cdp.send('Profiler.setSamplingInterval', { interval: 200 });
      await cdp.send('Profiler.start');
    }
    const before = load(), cpuBefore = chromiumCpu();
    const result = await page.evaluate(() => window.__bench.run());
    const cpu = cpuSpent(cpuBefore, chromiumCpu());
    const after = load();
    let cpuProfile = null;
    if (cdp) cpuProfile = (await cdp.send('Profiler.stop')).profile;
    const info = await page.evaluate(() => window.__bench.info());
    const gpuTimes = gpu ? await gpuAlone(page) : null;
    if (problems.length) throw new Error('the bench page: ' + problems.join('; '));
    return { info, result, load: [before, after], cpuProfile, gpu: gpuTimes, cpu };
  } finally {
    await context.close();
  }
}

// The GPU alone (mode=lens pages): each draw variant of the page's gpuVariants, drawn for 1.5 s
// (at least 11 times), synced; its median wall time and the chromium CPU time per draw (renderer
// + GPU process), for the draft mesh and the full one.
async function gpuAlone(page) {
  const out = {};
  const names = await page.evaluate(() => window.__bench.gpuNames());
  for (const which of ['draft', 'full']) {
    const mesh = await page.evaluate((w) => window.__bench.gpuMesh(w), which);
    const ms = {}, cpu = {};
    for (const name of names) {
      const before = chromiumCpu();
      const timed = await page.evaluate((n) => window.__bench.gpuTime(n), name);
      if (!timed) continue;
      const spent = cpuSpent(before, chromiumCpu());
      ms[name] = timed.ms;
      cpu[name] = (spent.renderer + spent.gpu) / timed.count;
    }
    out[which] = { ...mesh, ms, cpu };
  }
  return out;
}

// Self time (ms) by function in a CDP CPU profile; wasm functions together, by module.
function selfTimes(profile) {
  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const total = new Map();
  for (let i = 0; i < profile.samples.length; ++i) {
    const node = byId.get(profile.samples[i]);
    const dt = (profile.timeDeltas[i + 1] ?? 0) / 1000;
    const { functionName, url, lineNumber } = node.callFrame;
    let key;
    if (url.endsWith('.wasm') || url.startsWith('wasm://') || /^(wasm-|js-to-wasm)/.test(
      functionName)) key = 'wasm (the engine), all functions';
    else if (!url) key = functionName || '(anonymous)';
    else key = `${functionName || '(anonymous)'} ${url.split('/').pop()}:${lineNumber + 1}`;
    total.set(key, (total.get(key) || 0) + dt);
  }
  return [...total.entries()].sort((a, b) => b[1] - a[1]);
}

// ---------------------------------------------------------------------------------------------

const server = await serve();
const browser = await launch();
const chromiumVersion = browser.version();
const rows = [], breakdowns = [], raw = [];
let profileRows = null, renderer = '', demo = null;
const kinds = [{ key: 'lens', label: 'lens', query: 'mode=lens' }];
if (withWorker) kinds.push({ key: 'worker', label: 'lens, worker', query: 'mode=lens&worker=1' });
const perFrame = (cpu) => Object.fromEntries(Object.entries(cpu).map(([k, v]) =>
  [k, v / frameCount]));
const cpuTotal = (c) => c.renderer + c.gpu + c.other;
try {
  const configs = [{
    name: '1280 x 1024',
    query: 'size=1280x1024',
    about: '1280 x 1024 canvas, generated 1280 x 1024 picture, circle r 150 zoom 2 at its centre',
  }];
  if (!args.includes('--no-demo')) {
    demo = await demoCanvas(browser, server.url);
    const l = demo.lens;
    if (demo.width !== 1280 || demo.height !== 1024) {
      configs.push({
        name: `demo ${demo.width} x ${demo.height}`,
        query: `size=${demo.width}x${demo.height}&image=/examples/demo.png` +
          `&lens=${l.cx},${l.cy},${l.r},${l.zoom}`,
        about: `the demo's canvas at a 1280 x 760 viewport (${demo.width} x ${demo.height}), ` +
          `examples/demo.png (1024 x 1024), its circle (${l.cx}, ${l.cy}) r ${l.r} zoom ${l.zoom}`,
      });
    }
  }
  for (const config of configs) {
    if (only && !config.name.startsWith(only)) continue;
    const floors = [], lenses = Object.fromEntries(kinds.map((k) => [k.key, []])), gpus = [];
    const loads = [];
    for (let run = 0; run < runs; ++run) {
      // A floor run, then each lens kind's: adjacent in time, they share the machine's load.
      const floor = await runPage(browser, server.url, `mode=floor&${config.query}` +
        (floorMip ? `&floormip=${floorMip}` : ''));
      floors.push({ ...floorFigures(floor.result), cpu: perFrame(floor.cpu) });
      loads.push(floor.load);
      for (const kind of kinds) {
        const query = `${kind.query}&${config.query}` +
          (draftMesh ? `&draftmesh=${draftMesh}` : '');
        const lens = await runPage(browser, server.url, query,
          { gpu: run === 0 && kind.key === 'lens' });
        if (lens.gpu) gpus.push(lens.gpu);
        renderer = lens.info.renderer;
        lenses[kind.key].push({ ...lensFigures(lens.result), cpu: perFrame(lens.cpu) });
        loads.push(lens.load);
        raw.push({ config: config.name, run, kind: kind.key, lens: lens.result });
      }
      raw.push({ config: config.name, run, kind: 'floor', floor: floor.result });
      process.stderr.write(`${config.name}: run ${run + 1}/${runs} done (load ${load()})\n`);
    }
    // All runs' frames together; CPU per frame, the median of the runs'.
    const all = (list, key) => list.flatMap((x) => x[key]);
    const summary = (list) => ({
      interval: [median(all(list, 'intervals')), p90(all(list, 'intervals'))],
      work: [median(all(list, 'work')), p90(all(list, 'work'))],
      cpu: ['renderer', 'gpu', 'other'].map((k) => median(list.map((x) => x.cpu[k]))),
      cpuTotal: median(list.map((x) => cpuTotal(x.cpu))),
    });
    const row = { config, loads, floor: summary(floors), kinds: {} };
    row.floor.sync = median(all(floors, 'sync'));
    for (const kind of kinds) {
      const list = lenses[kind.key];
      const sum = (key) => list.reduce((a, x) => a + x[key], 0);
      row.kinds[kind.key] = {
        ...summary(list), drafts: sum('drafts'), full: sum('full'), shown: sum('shown'),
        shownEver: sum('shownEver'), moves: sum('moves'), missing: sum('missing'),
        lagMax: Math.max(...list.map((x) => x.lagMax)), vertices: list[0].vertices,
        triangles: list[0].triangles, rest: list.map((x) => x.rest),
        outsideShowMs: median(list.map((x) => x.outsideShowMs)),
        pairs: floors.map((f, k) => ({
          interval: median(list[k].intervals) / median(f.intervals),
          work: median(list[k].work) / median(f.work),
          cpu: cpuTotal(list[k].cpu) / cpuTotal(f.cpu),
        })),
      };
    }
    rows.push(row);
    const steps = Object.fromEntries(STEPS.map((k) => [k,
      lenses.lens.flatMap((x) => x.steps[k])]));
    breakdowns.push({ config, steps, gpus });
  }
  if (!args.includes('--no-profile')) {
    const config = configs.find((c) => !only || c.name.startsWith(only));
    const profiled = await runPage(browser, server.url, `mode=lens&${config.query}`,
      { profile: true, frames: Math.min(frameCount, 100) });
    const figures = lensFigures(profiled.result);
    const span = profiled.result.frames.at(-1).timestamp - profiled.result.frames[0].timestamp;
    profileRows = { config, figures, span, self: selfTimes(profiled.cpuProfile) };
  }
} finally {
  await browser.close();
  await server.close();
}

// ---------------------------------------------------------------------------------------------
// The report

const cpus = os.cpus();
console.log(`\nGeolensView frame time against the floor (issue 31), ${frameCount}-frame drags, ` +
  `${runs} run(s) each, ${unthrottled ? 'unthrottled (no vsync)' : '60 Hz (headless default)'}`);
console.log('');
console.log('| machine | |');
console.log('|---|---|');
console.log(`| os.cpus().length | ${cpus.length} (${cpus[0]?.model.trim()}) |`);
console.log(`| node | ${process.version} |`);
console.log(`| chromium | ${chromiumVersion} (headless, ${renderer}) |`);
console.log(`| load average (1, 5, 15 min) at the end | ${load()} |`);
for (const row of rows) {
  console.log(`\n${row.config.about}; load average (1 min) before each run: ` +
    row.loads.map((l) => l[0].split(' ')[0]).join(', '));
  console.log('');
  const head = ['per frame (ms)', 'floor'];
  for (const kind of kinds) head.push(kind.label, `${kind.label} / floor`);
  console.log(`| ${head.join(' | ')} |`);
  console.log(`|---|${head.slice(1).map(() => '---:').join('|')}|`);
  const line = (label, floorCell, cell, ratio) => {
    const cells = [label, floorCell];
    for (const kind of kinds) cells.push(cell(row.kinds[kind.key]), ratio(row.kinds[kind.key]));
    console.log(`| ${cells.join(' | ')} |`);
  };
  const f = row.floor;
  line('rAF-to-rAF interval, median', fixed(f.interval[0]), (k) => fixed(k.interval[0]),
    (k) => fixed(k.interval[0] / f.interval[0]));
  line('rAF-to-rAF interval, p90', fixed(f.interval[1]), (k) => fixed(k.interval[1]),
    (k) => fixed(k.interval[1] / f.interval[1]));
  line('work in the frame (input + rAF + 1 px readback), median', fixed(f.work[0]),
    (k) => fixed(k.work[0]), (k) => fixed(k.work[0] / f.work[0]));
  line('work in the frame, p90', fixed(f.work[1]), (k) => fixed(k.work[1]),
    (k) => fixed(k.work[1] / f.work[1]));
  const cpuCell = (c) => `${fixed(c[0], 1)} / ${fixed(c[1], 1)} / ${fixed(c[2], 1)}`;
  line('chromium CPU: renderer / GPU process / other', cpuCell(f.cpu), (k) => cpuCell(k.cpu),
    () => '');
  line('chromium CPU, total', fixed(f.cpuTotal, 1), (k) => fixed(k.cpuTotal, 1),
    (k) => fixed(k.cpuTotal / f.cpuTotal));
  line('lens / floor per run pair: interval; work; CPU', '', () => '', (k) => k.pairs.map((p) =>
    `${fixed(p.interval)}; ${fixed(p.work)}; ${fixed(p.cpu)}`).join(' · '));
  line('moves shown in the next frame', '', (k) => `${k.shown} / ${k.moves}`,
    (k) => `${fixed((100 * k.shown) / k.moves, 1)} %`);
  line('frames shown: drafts / full mesh', '', (k) => `${k.drafts} / ${k.full}`, () => '');
  console.log('');
  console.log(`floor: 1 px readback median ${fixed(f.sync)} ms.`);
  for (const kind of kinds) {
    const k = row.kinds[kind.key];
    console.log(`${kind.label}: draft mesh ${k.vertices} vertices, ${k.triangles} triangles; ` +
      `${k.missing} drag frames without a view callback; moves ever shown ${k.shownEver} / ` +
      `${k.moves}, the latest ${k.lagMax} frame(s) late; page work outside animation frames ` +
      `(worker replies) ${fixed(k.outsideShowMs)} ms a frame; the full mesh after the release ` +
      `in ${k.rest.map((r) => (r ? `${fixed(r.ms, 0)} ms (${r.vertexCount} vertices)` : '—'))
        .join(', ')}.`);
  }
}
for (const { config, steps, gpus } of breakdowns) {
  console.log(`\nwhere a lens drag frame goes, ${config.name} (ms; all runs):`);
  console.log('');
  console.log('| step | mean | median | p90 |');
  console.log('|---|---:|---:|---:|');
  const names = {
    input: 'input: the pointermove handler',
    update: 'solve in wasm (session.update, draft)',
    solveJs: 'solve in JS: shape distortion, gpuMesh, boundary points',
    forward: 'outline points (session.forward)',
    upload: 'mesh upload (bufferData)',
    meshDraw: 'mesh draw calls',
    outlines: 'outlines (strokeQuads, upload, draw)',
    cursor: 'cursor (pick: session.inverse)',
    sync: 'GPU: 1 px readback (draw finished)',
    other: 'other',
  };
  let total = 0;
  for (const k of STEPS) {
    total += mean(steps[k]);
    console.log(`| ${names[k]} | ${fixed(mean(steps[k]))} | ${fixed(median(steps[k]))} | ` +
      `${fixed(p90(steps[k]))} |`);
  }
  console.log(`| total | ${fixed(total)} | | |`);
  const g = gpus[0];
  console.log(`\nthe GPU alone, ${config.name}: one draw synced by a 1 px readback, repeated for ` +
    '1.5 s in one task (no animation frames, no compositing); median wall ms, and chromium CPU ' +
    'ms per draw (renderer + GPU process)');
  console.log('');
  console.log('| draw | draft: wall | draft: CPU | full: wall | full: CPU |');
  console.log('|---|---:|---:|---:|---:|');
  console.log(`| (vertices drawn, 3 a triangle; in warped triangles) | ${g.draft.vertices}; ` +
    `${g.draft.warped ?? '—'} | | ${g.full.vertices}; ${g.full.warped} | |`);
  for (const name of Object.keys(g.full.ms)) {
    console.log(`| ${name} | ${fixed(g.draft.ms[name], 1)} | ${fixed(g.draft.cpu[name], 1)} | ` +
      `${fixed(g.full.ms[name], 1)} | ${fixed(g.full.cpu[name], 1)} |`);
  }
}
if (profileRows) {
  const { config, figures, span, self } = profileRows;
  console.log(`\nCDP Profiler (200 us sampling), one lens run, ${config.name}, over ` +
    `${fixed(span, 0)} ms (${figures.moves} frames; median work ` +
    `${fixed(median(figures.work))} ms with the profiler on): main-thread self time, ms per frame`);
  console.log('');
  console.log('| function | ms / frame | share of busy |');
  console.log('|---|---:|---:|');
  const busy = self.filter(([k]) => k !== '(idle)').reduce((a, [, v]) => a + v, 0);
  for (const [key, ms] of self.slice(0, 24)) {
    const share = key === '(idle)' ? '' : `${fixed((100 * ms) / busy, 1)} %`;
    console.log(`| ${key} | ${fixed(ms / figures.moves)} | ${share} |`);
  }
}
if (jsonOut) writeFileSync(jsonOut, JSON.stringify({ rows, raw }, null, 1));

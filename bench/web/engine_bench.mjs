// Benchmark of the lens engine in WebAssembly (web/dist/geolens.mjs, issue 31) on the scenes of
// the native Google Benchmark (bench/lens_bench.cpp): a 1024 x 1024 image, mesh 100, the focus
// model; a circle (r = 150 px, zoom 2) and a 5-pointed star (R = 120 px, zoom 2.5) placed at
// first, and dragged 3 px a frame from x = 400 to 620 and back (full frames and drafts). Medians
// of 10 runs (a run: one first placement, or the mean frame of one whole drag of 74 frames),
// after 2 runs of warm-up. With --native BIN it runs the native equivalents (BM_UpdateFirst/100/1,
// BM_UpdateMoved/100/3/1 and /2, BM_UpdateMovedStar/100/1 and /2; 10 repetitions, medians) and
// prints both; --pin runs them on one core (taskset -c 0), as the wasm build has one thread.
//
//   node bench/web/engine_bench.mjs [--runs 10] [--size 1024x1024]
//                                   [--native build/bench/geolens_bench [--pin]]
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import os from 'node:os';
import createGeolens from '../../web/dist/geolens.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : fallback;
};
const runs = Number(option('--runs', 10));
const [width, height] = option('--size', '1024x1024').split('x').map(Number);
const nativeBench = option('--native', null);
const pin = args.includes('--pin');
const WARMUP = 2, MESH = 100, DRAG_FRAMES = 74;

const wasmBinary = readFileSync(new URL('../../web/dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

const cy = height / 2;
const circle = (x) => ({ kind: 'circle', cx: x, cy, r: 150, zoom: 2 });
// bench/lens_bench.cpp's star: 10 vertices, R = 120 px, inner 0.382 R, a tip straight up.
const star = (x) => {
  const points = [];
  for (let k = 0; k < 10; ++k) {
    const r = k % 2 === 0 ? 120 : 0.382 * 120, a = Math.PI / 2 + (k * Math.PI) / 5;
    points.push(x + r * Math.cos(a), cy - r * Math.sin(a));
  }
  return { kind: 'polygon', points, zoom: 2.5 };
};
const session = () => engine.session({ width, height, mesh: MESH, model: 'focus' });

// Wall and CPU time (this process's, ms) of f() over `count`.
function timed(f, count = 1) {
  const cpu = process.cpuUsage(), start = performance.now();
  f();
  const wall = performance.now() - start, { user, system } = process.cpuUsage(cpu);
  return { wall: wall / count, cpu: (user + system) / 1000 / count };
}

// One first placement: a new session, its first update and its dispose (as BM_UpdateFirst
// times a LensSession made, updated and destroyed).
function firstPlacement(lens, x) {
  let zoom;
  const t = timed(() => {
    const s = session();
    zoom = s.update([lens(x)]).lenses[0].zoomGot;
    s.dispose();
  });
  if (!(Math.abs(zoom - lens(x).zoom) < 0.05)) throw new Error(`zoom got ${zoom}`);
  return t;
}

// One drag (BM_UpdateMoved's frames): placed at x = 400, then 74 frames 3 px apart, from 403 to
// 619 and back to 400 in one jump; the mean frame.
function drag(lens, draft) {
  const s = session();
  try {
    let x = 400;
    s.update([lens(x)], draft);
    return timed(() => {
      for (let frame = 0; frame < DRAG_FRAMES; ++frame) {
        x = x + 3 > 620 ? 400 : x + 3;
        s.update([lens(x)], draft);
      }
    }, DRAG_FRAMES);
  } finally {
    s.dispose();
  }
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b), n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
};

const cases = [
  { name: 'circle: first placement', run: () => firstPlacement(circle, width / 2),
    native: 'BM_UpdateFirst/100/1' },
  { name: 'circle: drag, full frames', run: () => drag(circle, false),
    native: 'BM_UpdateMoved/100/3/1/iterations:222' },
  { name: 'circle: drag, drafts', run: () => drag(circle, true),
    native: 'BM_UpdateMoved/100/3/2/iterations:222' },
  { name: 'star: first placement', run: () => firstPlacement(star, width / 2), native: null },
  { name: 'star: drag, full frames', run: () => drag(star, false),
    native: 'BM_UpdateMovedStar/100/1/iterations:222' },
  { name: 'star: drag, drafts', run: () => drag(star, true),
    native: 'BM_UpdateMovedStar/100/2/iterations:222' },
];

// The native figures first (a bad --native fails fast): Google Benchmark's medians of 10
// repetitions, wall and CPU time (of the benchmark's thread: the pool's other thread is not
// counted), ms.
const native = new Map();
if (nativeBench) {
  if (width !== 1024 || height !== 1024) throw new Error('the native scenes are 1024x1024');
  const filter = cases.filter((c) => c.native).map((c) => `^${c.native}$`).join('|');
  const command = [nativeBench, `--benchmark_filter=${filter}`, '--benchmark_repetitions=10',
                   '--benchmark_report_aggregates_only=true', '--benchmark_format=json'];
  // Pinned: one core and the library's pool of one thread (GEOLENS_BENCH_THREADS=1), as the
  // wasm build runs; a pool of two on one core would add their switching to the wall time.
  const output = pin
    ? execFileSync('taskset', ['-c', '0', ...command],
      { encoding: 'utf8', env: { ...process.env, GEOLENS_BENCH_THREADS: '1' } })
    : execFileSync(command[0], command.slice(1), { encoding: 'utf8' });
  // Google Benchmark writes a counter's undefined spread as a bare NaN, which is not JSON.
  const json = output.replace(/:\s*-?(?:NaN|nan|inf|Infinity)\b/g, ': null');
  for (const b of JSON.parse(json).benchmarks) {
    if (b.aggregate_name !== 'median') continue;
    const scale = { ns: 1e-6, us: 1e-3, ms: 1, s: 1e3 }[b.time_unit];
    native.set(b.run_name, { wall: b.real_time * scale, cpu: b.cpu_time * scale });
  }
}

// The engine's figures.
for (const c of cases) {
  for (let i = 0; i < WARMUP; ++i) c.run();
  const times = Array.from({ length: runs }, () => c.run());
  c.wall = times.map((t) => t.wall);
  c.cpu = median(times.map((t) => t.cpu));
  process.stderr.write(`${c.name}: ${median(c.wall).toFixed(2)} ms\n`);
}

const load = os.loadavg().map((l) => l.toFixed(2)).join(' ');
console.log(`geolens engine (wasm) on node ${process.version}, ${os.cpus().length} cores ` +
            `(${os.cpus()[0].model.trim()}), load average ${load}`);
console.log(`${width}x${height} image, mesh ${MESH}, focus model; medians of ${runs} runs ` +
            `(ms, wall time unless cpu; a drag's figure is its mean frame)` +
            (nativeBench ? `; native: ${nativeBench}${pin ? ' on one core (taskset -c 0)' : ''}`
                         : ''));
const rows = [['case', 'wasm', 'min', 'max', 'wasm cpu',
               ...(nativeBench ? ['native', 'native cpu', 'wasm/native'] : [])]];
for (const c of cases) {
  const row = [c.name, median(c.wall), Math.min(...c.wall), Math.max(...c.wall), c.cpu];
  if (nativeBench) {
    const n = c.native && native.get(c.native);
    row.push(n ? n.wall : '-', n ? n.cpu : '-', n ? median(c.wall) / n.wall : '-');
  }
  rows.push(row.map((v) => (typeof v === 'number' ? v.toFixed(2) : v)));
}
const widths = rows[0].map((_, i) => Math.max(...rows.map((r) => r[i].length)));
const cell = (v, i) => (i ? v.padStart(widths[i]) : v.padEnd(widths[i]));
for (const r of rows) console.log(`| ${r.map(cell).join(' | ')} |`);

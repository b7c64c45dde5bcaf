// The WASM engine against the native CLI (issue 31): for 50 seeded lens setups (image size,
// circles and polygons, 1-3 lenses, zoom 1.2-4, the focus / lift / field / auto models and some
// of their options, mesh size) the engine's warp equals `geolens map`'s within 1e-6 px, forward
// and inverse, and its zoom got, zoom fit, reasons, model and mesh size equal `magnify --stats`;
// forward then inverse returns within 1e-6 px (where the warp neither folds nor squeezes a
// triangle to a sliver: there inverse then forward, within 1e-4 px); its errors carry the CLI's
// messages. `subdivide` is left out: the engine's session ignores it (LensSession keeps its grid).
// Needs the native CLI: GEOLENS_CLI, else <repo>/build/geolens (a missing one FAILS the tests).
// Run: node --test web/test/native.test.mjs   (about 15 s on 2 cores)
import { encodePng } from '../browser-test/png.mjs';
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { accessSync, constants, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { promisify } from 'node:util';
import createGeolens from '../dist/geolens.mjs';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

const CLI =
  process.env.GEOLENS_CLI || fileURLToPath(new URL('../../build/geolens', import.meta.url));
const TOLERANCE = 1e-6; // px
const FOLD_TOLERANCE = 1e-4; // px: inverse then forward where a triangle folds or is a sliver
const SETUPS = 50;
const SEED = 31;

// Fails (never skips) when the native CLI is not there: these checks are the point of the file.
function requireCli() {
  try {
    accessSync(CLI, constants.X_OK);
  } catch {
    assert.fail(`the native CLI '${CLI}' does not exist or is not executable: build it ` +
                '(cmake --build build) or point GEOLENS_CLI at it');
  }
}

const dir = mkdtempSync(join(tmpdir(), 'geolens-native-'));
after(() => rmSync(dir, { recursive: true, force: true }));
let fileCount = 0;
const scratch = (name) => join(dir, `${++fileCount}_${name}`);

const execFileAsync = promisify(execFile);
// Runs the CLI; resolves {stdout, stderr}, or rejects with the error line it printed.
async function cli(args) {
  try {
    return await execFileAsync(CLI, args, { maxBuffer: 64 << 20 });
  } catch (e) {
    if (e.code === 'ENOENT') requireCli();
    const line = (e.stderr || '').split('\n').find((l) => l.startsWith('geolens: error: '));
    throw new Error(line ? line.slice('geolens: error: '.length) : `${CLI} failed: ${e.message}`);
  }
}

// mulberry32: a small seeded PRNG, so every run draws the same setups.
function prng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// A grey RGB PNG of width x height (browser-test/png.mjs's writer; magnify needs an image of
// the lenses' size for --stats).
const pngs = new Map();
function greyPng(width, height) {
  const key = `${width}x${height}`;
  if (!pngs.has(key)) {
    const path = scratch(`${key}.png`);
    writeFileSync(path, encodePng(width, height, 3, Buffer.alloc(width * height * 3, 128)));
    pngs.set(key, path);
  }
  return pngs.get(key);
}

// --- The setups -----------------------------------------------------------------------------

function insidePolygon(xy, x, y) {
  let inside = false;
  for (let i = 0, j = xy.length - 2; i < xy.length; j = i, i += 2) {
    const [xi, yi, xj, yj] = [xy[i], xy[i + 1], xy[j], xy[j + 1]];
    if (yi > y !== yj > y && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

// Distance from (px, py) to the line through (ax, ay) and (bx, by).
function lineDistance(px, py, ax, ay, bx, by) {
  return Math.abs((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / Math.hypot(bx - ax, by - ay);
}

// A star (alternating radii) or a star-shaped polygon about (cx, cy) of reach `size`, every
// vertex at least 2 px off its neighbours' chord (the CLI simplifies a polygon file to 0.1 px).
function polygon(random, cx, cy, size) {
  for (;;) {
    const xy = [];
    if (random() < 0.5) {
      const n = 3 + Math.floor(random() * 5), inner = 0.35 + 0.3 * random();
      const turn = random() * 2 * Math.PI;
      for (let k = 0; k < 2 * n; ++k) {
        const a = turn + (k * Math.PI) / n, r = size * (k % 2 === 0 ? 1 : inner);
        xy.push(cx + r * Math.cos(a), cy + r * Math.sin(a));
      }
    } else {
      const n = 3 + Math.floor(random() * 6);
      const angles = Array.from({ length: n }, () => random() * 2 * Math.PI).sort((a, b) => a - b);
      for (const a of angles) {
        const r = size * (0.55 + 0.45 * random());
        xy.push(cx + r * Math.cos(a), cy + r * Math.sin(a));
      }
    }
    const m = xy.length / 2;
    let ok = true;
    for (let k = 0; k < m && ok; ++k) {
      const p = (k + m - 1) % m, q = (k + 1) % m;
      ok = lineDistance(xy[2 * k], xy[2 * k + 1], xy[2 * p], xy[2 * p + 1], xy[2 * q],
                        xy[2 * q + 1]) > 2;
    }
    // Simple (its vertices in order of angle about the centre), with the centre inside.
    if (ok && insidePolygon(xy, cx, cy)) return xy;
  }
}

const pick = (random, items) => items[Math.floor(random() * items.length)];

function makeSetup(index, random) {
  const width = 160 + Math.floor(random() * 1440);
  const height = Math.max(120, Math.min(1200, Math.round(width * (0.5 + random()))));
  const model = pick(random, ['focus', 'focus', 'focus', 'focus', 'lift', 'lift', 'field',
                              'field', 'auto']);
  const options = { mesh: 12 + Math.floor(random() * 89), model };
  const count = 1 + Math.floor(random() * 3);
  const side = Math.min(width, height);
  const lenses = [];
  for (let tries = 0; lenses.length < count && tries < 200; ++tries) {
    const size = side * (0.04 + 0.14 * random());
    const cx = size + 2 + random() * (width - 2 * size - 4);
    const cy = size + 2 + random() * (height - 2 * size - 4);
    if (lenses.some((l) => Math.hypot(l.at[0] - cx, l.at[1] - cy) < l.size + size + 4)) continue;
    const zoom = 1.2 + 2.8 * random();
    const spec = random() < 0.6 ? { kind: 'circle', cx, cy, r: size, zoom }
                                : { kind: 'polygon', points: polygon(random, cx, cy, size), zoom };
    lenses.push({ spec, at: [cx, cy], size });
  }
  // The CLI's --profile and --footprint are the same for every lens.
  let profile, footprint;
  if (model === 'focus') {
    const zoomMax = Math.max(...lenses.map((l) => l.spec.zoom));
    if (random() < 0.3) footprint = zoomMax + 0.3 + 3 * random();
    if (random() < 0.4) options.mesh_tolerance = pick(random, [0, 0.05, 0.5, 1]);
  } else {
    if (random() < 0.6) profile = pick(random, ['gaussian', 'sphere', 'mesa']);
    // No `subdivide`: a session (LensSession, what the engine runs) keeps the base grid and
    // ignores it, where the CLI's GeometricLens::solve subdivides.
    if (model === 'lift' && random() < 0.4) options.texture = pick(random, ['cotan+', 'mvc']);
    if (random() < 0.2) options.boundary = pick(random, ['fixed', 'free']);
    if (random() < 0.2) {
      options.extent = 'local';
      options.extent_factor = 1.5 + 2 * random();
    }
    if (random() < 0.15) Object.assign(options, { metric: 'spectrum', alpha: 0.5 * random() });
  }
  for (const l of lenses) {
    if (profile) l.spec.profile = profile;
    if (footprint) l.spec.footprint = footprint;
  }
  return { index, width, height, options, profile, footprint, lenses };
}

function describe(s) {
  const kinds = s.lenses.map((l) => l.spec.kind[0] + l.spec.zoom.toFixed(2)).join(' ');
  const extra = Object.entries(s.options).filter(([k]) => k !== 'mesh' && k !== 'model')
    .map(([k, v]) => `${k}=${typeof v === 'number' ? +v.toFixed(3) : v}`);
  if (s.profile) extra.push(`profile=${s.profile}`);
  if (s.footprint) extra.push(`footprint=${s.footprint.toFixed(2)}`);
  return `${s.width}x${s.height} ${s.options.model} mesh ${s.options.mesh} [${kinds}]` +
         (extra.length ? ` ${extra.join(' ')}` : '');
}

// The points: a 13 x 11 grid over the image (its border included), a few just outside, each
// lens's centre and 30 points inside it.
function sourcePoints(s, random) {
  const xy = [];
  for (let i = 0; i <= 12; ++i)
    for (let j = 0; j <= 10; ++j) xy.push((i * s.width) / 12, (j * s.height) / 10);
  xy.push(-1, s.height / 2, s.width + 0.5, 3, 7, -0.25, s.width / 3, s.height + 2);
  for (const { spec, at, size } of s.lenses) {
    xy.push(at[0], at[1]);
    for (let n = 0; n < 30;) {
      const x = at[0] + (2 * random() - 1) * size, y = at[1] + (2 * random() - 1) * size;
      const inside = spec.kind === 'circle' ? Math.hypot(x - spec.cx, y - spec.cy) < spec.r
                                            : insidePolygon(spec.points, x, y);
      if (inside) xy.push(x, y), ++n;
    }
  }
  return new Float64Array(xy);
}

// --- The CLI's side --------------------------------------------------------------------------

function cliLensArgs(s, lenses = s.lenses.map((l) => l.spec)) {
  const args = [];
  for (const spec of lenses) {
    if (spec.kind === 'circle') {
      args.push('--lens', `circle:${spec.cx},${spec.cy},${spec.r}:${spec.zoom}`);
    } else {
      const path = scratch('polygon.txt');
      let text = '';
      for (let i = 0; i < spec.points.length; i += 2)
        text += `${spec.points[i]} ${spec.points[i + 1]}\n`;
      writeFileSync(path, text);
      args.push('--lens', `polygon:${path}:${spec.zoom}`);
    }
  }
  for (const [name, value] of Object.entries(s.options))
    args.push(`--${name.replaceAll('_', '-')}`, String(value));
  if (s.profile) args.push('--profile', s.profile);
  if (s.footprint) args.push('--footprint', String(s.footprint));
  return args;
}

// `geolens map` of the points (x, y pairs): an array of [x, y] or null where the CLI dropped the
// point (outside the image, or the output frame with --inverse), and its warnings.
async function cliMap(s, points, { inverse = false, lenses } = {}) {
  const input = scratch('points.csv');
  let text = 'x,y,id\n';
  for (let i = 0; i < points.length / 2; ++i)
    text += `${points[2 * i]},${points[2 * i + 1]},${i}\n`;
  writeFileSync(input, text);
  const args = ['map', input, '--size', `${s.width}x${s.height}`, ...cliLensArgs(s, lenses)];
  if (inverse) args.push('--inverse');
  const { stdout, stderr } = await cli(args);
  const mapped = new Array(points.length / 2).fill(null);
  const lines = stdout.trim().split('\n');
  assert.equal(lines[0], 'x,y,id');
  for (const line of lines.slice(1)) {
    const [x, y, id] = line.split(',');
    mapped[Number(id)] = [Number(x), Number(y)];
  }
  return { mapped, warnings: warningLines(stderr) };
}

const warningLines = (stderr) => stderr.split('\n')
  .filter((l) => l.startsWith('geolens: warning: '))
  .map((l) => l.slice('geolens: warning: '.length));

async function cliStats(s) {
  const stats = scratch('stats.json');
  await cli(['magnify', greyPng(s.width, s.height), '-o', scratch('out.png'), '--stats', stats,
             ...cliLensArgs(s)]);
  return JSON.parse(readFileSync(stats, 'utf8'));
}

// The largest difference between the engine's points (NaN where off the warp) and the CLI's
// (null where dropped); a point one side maps and the other does not fails. A point where they
// differ but `otherPreimage(i)` holds is counted apart.
function compare(ours, theirs, what, otherPreimage = () => false) {
  let worst = 0, mapped = 0, otherPreimages = 0;
  for (let i = 0; i < theirs.length; ++i) {
    const x = ours[2 * i], y = ours[2 * i + 1];
    if (theirs[i] === null) {
      assert.ok(Number.isNaN(x) && Number.isNaN(y),
                `${what}: point ${i}: the CLI drops it, the engine maps it to ${x}, ${y}`);
      continue;
    }
    assert.ok(Number.isFinite(x) && Number.isFinite(y),
              `${what}: point ${i}: the engine gives ${x}, ${y}, the CLI ${theirs[i]}`);
    const d = Math.max(Math.abs(x - theirs[i][0]), Math.abs(y - theirs[i][1]));
    if (d > TOLERANCE && otherPreimage(i)) ++otherPreimages;
    else worst = Math.max(worst, d), ++mapped;
  }
  return { worst, mapped, otherPreimages };
}

// How many triangles fold the warp or squeeze it: turned over (or of no source area), as
// measure_triangles counts them, or squeezed to under 1e-3 across (the smaller singular value
// of their Jacobian; the flattener's flip-safe steps can leave a sliver of 1e-14 of its area,
// which measure_triangles does not count). Over a fold a screen point has several source points
// and inverse() gives one of them; over a squeezed triangle the inverse magnifies the 1e-10 px
// by which the engine's and the CLI's screen points may differ a thousandfold and more.
function foldingTriangles(frame) {
  const { positions: p, texcoords: t, triangles: f } = frame;
  let folds = 0;
  for (let k = 0; k < f.length; k += 3) {
    const [a, b, c] = [2 * f[k], 2 * f[k + 1], 2 * f[k + 2]];
    const s00 = t[b] - t[a], s01 = t[c] - t[a];
    const s10 = t[b + 1] - t[a + 1], s11 = t[c + 1] - t[a + 1];
    const ds = s00 * s11 - s01 * s10;
    if (Math.abs(ds) <= 1e-12) {
      ++folds;
      continue;
    }
    const q00 = p[b] - p[a], q01 = p[c] - p[a];
    const q10 = p[b + 1] - p[a + 1], q11 = p[c + 1] - p[a + 1];
    // J = Q S^-1
    const j00 = (q00 * s11 - q01 * s10) / ds, j01 = (q01 * s00 - q00 * s01) / ds;
    const j10 = (q10 * s11 - q11 * s10) / ds, j11 = (q11 * s00 - q10 * s01) / ds;
    const det = j00 * j11 - j01 * j10, half = (j00 ** 2 + j01 ** 2 + j10 ** 2 + j11 ** 2) / 2;
    const largest = Math.sqrt(half + Math.sqrt(Math.max(0, half * half - det * det)));
    if (det <= 0 || det / largest < 1e-3) ++folds;
  }
  return folds;
}

// --- The tests -------------------------------------------------------------------------------

const random = prng(SEED);
const setups = Array.from({ length: SETUPS }, (_, i) => makeSetup(i, random));
const worst = { forward: 0, inverse: 0, roundTrip: 0, foldedTrip: 0, zoom: 0, points: 0 };
const folded = []; // setups whose warp folds, its folding triangles and ambiguous points

for (const s of setups) {
  test(`setup ${s.index}: ${describe(s)}`, async () => {
    requireCli();
    const points = sourcePoints(s, prng(SEED + 1000 + s.index));
    const session = engine.session({ width: s.width, height: s.height, ...s.options });
    try {
      const frame = session.update(s.lenses.map((l) => l.spec));
      const screen = session.forward(points);
      // The screen side: where the source points landed, a grid over the output, two outside.
      const screenPoints = [...screen.filter(Number.isFinite)];
      for (let i = 0; i <= 8; ++i)
        for (let j = 0; j <= 6; ++j) screenPoints.push((i * s.width) / 8, (j * s.height) / 6);
      screenPoints.push(-2, 5, s.width / 2, s.height + 1);
      const back = session.inverse(new Float64Array(screenPoints));

      const [forward, inverse, stats] = await Promise.all([
        cliMap(s, points), cliMap(s, screenPoints, { inverse: true }), cliStats(s)]);

      const f = compare(screen, forward.mapped, 'forward');
      assert.ok(f.worst <= TOLERANCE, `forward differs from the CLI's by ${f.worst} px`);
      assert.ok(f.mapped > 100, `only ${f.mapped} points mapped`);

      // Where the warp folds, a screen point has several source points: the engine's and the
      // CLI's inverse may give different ones, each mapping forward to the point (within 1e-4
      // px over a sliver, whose barycentric coordinates are ill-conditioned). Elsewhere the
      // inverse is the CLI's, and forward then inverse comes back where it started.
      const folds = foldingTriangles(frame) + stats.flipped;
      const residual = folds > 0 ? FOLD_TOLERANCE : TOLERANCE;
      const theirs = new Float64Array(inverse.mapped.flatMap((q) => q ?? [NaN, NaN]));
      const theirsThere = session.forward(theirs), there = session.forward(back);
      const bothPreimages = (i) => [there, theirsThere].every((xy) =>
        Math.hypot(xy[2 * i] - screenPoints[2 * i], xy[2 * i + 1] - screenPoints[2 * i + 1]) <=
        residual);
      const b = compare(back, inverse.mapped, 'inverse', folds > 0 ? bothPreimages : undefined);
      assert.ok(b.worst <= TOLERANCE, `inverse differs from the CLI's by ${b.worst} px`);
      let trip = 0;
      if (folds === 0) {
        const again = session.inverse(screen);
        for (let i = 0; i < points.length; ++i)
          if (Number.isFinite(screen[i])) trip = Math.max(trip, Math.abs(again[i] - points[i]));
        assert.ok(trip <= TOLERANCE, `forward then inverse off by ${trip} px`);
      } else {
        folded.push(`${s.index} (${folds} triangles, ${stats.flipped} flipped by --stats; ` +
                    `${b.otherPreimages} points inverted elsewhere)`);
      }
      let tripBack = 0;
      for (let i = 0; i < screenPoints.length; ++i)
        if (Number.isFinite(back[i]))
          tripBack = Math.max(tripBack, Math.abs(there[i] - screenPoints[i]));
      assert.ok(tripBack <= residual, `inverse then forward off by ${tripBack} px`);
      if (folds === 0) trip = Math.max(trip, tripBack);
      else worst.foldedTrip = Math.max(worst.foldedTrip, tripBack);

      // What magnify --stats says of the same lenses.
      assert.equal(frame.model, stats.model);
      assert.equal(frame.vertexCount, stats.vertices);
      assert.equal(frame.triangleCount, stats.triangles);
      assert.equal(frame.lenses.length, stats.lenses.length);
      let zoom = 0;
      frame.lenses.forEach((got, k) => {
        const theirs = stats.lenses[k];
        assert.equal(got.zoomAsked, theirs.zoom_requested);
        zoom = Math.max(zoom, Math.abs(got.zoomGot - theirs.zoom_measured));
        if (theirs.zoom_fit === undefined) assert.equal(got.zoomFit, null, `lens ${k + 1} zoomFit`);
        else assert.ok(Math.abs(got.zoomFit - theirs.zoom_fit) <= 1e-12, `lens ${k + 1} zoomFit`);
        assert.equal(got.reason, theirs.zoom_fit_reason ?? '');
      });
      assert.ok(zoom <= 1e-9, `zoom got differs from the CLI's by ${zoom}`);
      // The engine's warnings are the CLI's zoom warnings.
      for (const w of frame.warnings) assert.ok(forward.warnings.includes(w), `warning '${w}'`);

      worst.forward = Math.max(worst.forward, f.worst);
      worst.inverse = Math.max(worst.inverse, b.worst);
      worst.roundTrip = Math.max(worst.roundTrip, trip);
      worst.zoom = Math.max(worst.zoom, zoom);
      worst.points += f.mapped + b.mapped;
    } finally {
      session.dispose();
    }
  });
}

test('the setups cover the models, kinds, lens counts and zooms asked for', (t) => {
  const models = new Set(setups.map((s) => s.options.model));
  assert.deepEqual([...models].sort(), ['auto', 'field', 'focus', 'lift']);
  const specs = setups.flatMap((s) => s.lenses.map((l) => l.spec));
  assert.ok(specs.some((l) => l.kind === 'polygon') && specs.some((l) => l.kind === 'circle'));
  for (const n of [1, 2, 3]) assert.ok(setups.some((s) => s.lenses.length === n), `${n} lenses`);
  for (const l of specs) assert.ok(l.zoom >= 1.2 && l.zoom <= 4);
  t.diagnostic(`largest differences from the CLI over ${worst.points} points: forward ` +
               `${worst.forward} px, inverse ${worst.inverse} px, zoom got ${worst.zoom}; ` +
               `round trips ${worst.roundTrip} px; folded warps (inverse then forward only, ` +
               `${worst.foldedTrip} px at most): setups ${folded.join(', ') || 'none'}`);
});

// The comparison can fail: the same setup with one zoom off by 1e-3 is far outside 1e-6 px.
test('a zoom off by 1e-3 fails the comparison', async () => {
  requireCli();
  const s = { width: 800, height: 600, options: { mesh: 60, model: 'focus' } };
  const spec = { kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2 };
  const points = new Float64Array([400, 300, 430, 310, 450, 300, 200, 100, 560, 420]);
  const { mapped } = await cliMap(s, points, { lenses: [spec] });
  for (const [dz, off] of [[0, false], [1e-3, true]]) {
    const session = engine.session({ width: 800, height: 600, ...s.options });
    try {
      session.update([{ ...spec, zoom: spec.zoom + dz }]);
      const { worst: diff } = compare(session.forward(points), mapped, 'forward');
      assert.equal(diff > 1e-3, off, `zoom + ${dz}: ${diff} px from the CLI's`);
      assert.equal(diff <= TOLERANCE, !off);
    } finally {
      session.dispose();
    }
  }
});

// The engine's errors for lenses and options the CLI takes too: the same text, but for where it
// was found (the engine's function, the CLI's flag or polygon file).
test("the engine's errors carry the CLI's messages", async () => {
  requireCli();
  const s = { width: 800, height: 600, options: {} };
  const circle = (o) => ({ kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2, ...o });
  const engineError = (lenses, options = {}) => {
    try {
      const session = engine.session({ width: 800, height: 600, mesh: 20, ...options });
      try {
        session.update(lenses);
      } finally {
        session.dispose();
      }
    } catch (e) {
      assert.ok(e instanceof Error);
      return e;
    }
    assert.fail(`no error for ${JSON.stringify(lenses)} ${JSON.stringify(options)}`);
  };
  const cliError = async (lenses, flags = []) => {
    const points = scratch('p.csv');
    writeFileSync(points, 'x,y\n1,1\n');
    try {
      await cli(['map', points, '--size', '800x600', ...cliLensArgs(s, lenses), ...flags]);
    } catch (e) {
      return e.message;
    }
    assert.fail(`the CLI takes ${JSON.stringify(lenses)} ${flags.join(' ')}`);
  };
  // The same message, word for word.
  for (const zoom of [9, 0, 0.5]) {
    const e = engineError([circle({ zoom })]);
    assert.equal(e.name, 'InvalidInput');
    assert.equal(e.message, await cliError([circle({ zoom })]));
  }
  const outside = engineError([circle({ cx: 900 })]);
  assert.equal(outside.message, await cliError([circle({ cx: 900 })]));
  assert.equal(engineError([circle({ profile: 'cone' })]).message,
               await cliError([circle({})], ['--profile', 'cone']));
  // The same text after the place: the engine's 'Region::polygon: ' is the CLI's
  // "polygon 'FILE': ".
  const rest = (message) => message.slice(message.indexOf(': ') + 2);
  const two = { kind: 'polygon', points: [100, 100, 200, 200], zoom: 2 };
  const e2 = engineError([two]);
  assert.equal(e2.message, 'Region::polygon: a polygon needs at least 3 vertices, got 2');
  assert.equal(rest(e2.message), rest(await cliError([two])));
  // A vertex outside: both name it and the image, in their own words.
  const out = { kind: 'polygon', points: [10, 10, 900, 10, 100, 100], zoom: 2 };
  const e3 = engineError([out]), cli3 = await cliError([out]);
  for (const m of [e3.message, cli3]) assert.match(m, /\(900, 10\) is outside the 800x600 image/);
  // A negative radius: the CLI refuses the spec's text, the engine the region.
  const e4 = engineError([circle({ r: -1 })]), cli4 = await cliError([circle({ r: -1 })]);
  for (const m of [e4.message, cli4]) assert.match(m, /radius must be a positive number, got '?-1/);
  // Options: the engine's 'validate: NAME REST' (or 'LensOptions: NAME REST') is the CLI's
  // '--FLAG: REST'. The footprint is a lens's in the engine and a flag of the CLI.
  const bad = [['mesh', 2], ['mesh', '2.5'], ['model', 'x'], ['mesh_tolerance', 0.001],
               ['subdivide', 9], ['alpha', 1], ['metric', 'm'], ['weights', 'w'], ['texture', 't'],
               ['boundary', 'b'], ['extent', 'e'], ['extent_factor', 1], ['tolerance', 0],
               ['max_iterations', 0]];
  for (const [name, value] of bad) {
    const e = engineError([circle({})], { [name]: value });
    assert.equal(e.name, 'InvalidOption', `${name}: ${e.message}`);
    const m = /^(validate|LensOptions): (\w+) (.*)$/.exec(e.message);
    assert.ok(m, `${name}: ${e.message}`);
    assert.equal(m[2], name);
    const flag = `--${name.replaceAll('_', '-')}`;
    assert.equal(`${flag}: ${m[3]}`, await cliError([circle({})], [flag, String(value)]));
  }
  const e5 = engineError([circle({ footprint: 1.5 })]);
  assert.equal(e5.name, 'InvalidOption');
  assert.equal(e5.message.replace('validate_lens: footprint ', '--footprint: '),
               await cliError([circle({})], ['--footprint', '1.5']));
});

// Tests of the browser build (web/dist/geolens.mjs + geolens.wasm, scripts/web_build.sh) under
// node's own test runner: node --test web/test/
// The module is built for the web (-sENVIRONMENT=web,worker: emscripten 3.1.6's node code uses
// require and __dirname, which an ES module does not have), so node hands it the .wasm bytes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import createGeolens from '../dist/geolens.mjs';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

const circle = (cx, cy, r, zoom) => ({ kind: 'circle', cx, cy, r, zoom });

test('a circle lens at zoom 2 on 800x600 gets zoom 2', () => {
  const lens = new engine.Session(800, 600, 100);
  try {
    const frame = lens.update([circle(400, 300, 80, 2)], false);
    assert.equal(frame.lenses.length, 1);
    const [got] = frame.lenses;
    assert.equal(got.zoomAsked, 2);
    assert.ok(Math.abs(got.zoomGot - 2) < 0.02, `zoomGot ${got.zoomGot}`);
    assert.equal(got.zoomFit, 2);
    assert.equal(got.reason, '');
    assert.equal(frame.model, 'focus');
    assert.equal(frame.draft, false);
    assert.equal(frame.screenWidth, 800);
    assert.equal(frame.screenHeight, 600);
  } finally {
    lens.dispose();
  }
});

test('the warp: as many positions as texcoords, triangles index them', () => {
  const lens = engine.session({ width: 800, height: 600, mesh: 100 });
  try {
    const frame = lens.update([circle(400, 300, 80, 2)]);
    const { positions, texcoords, triangles } = frame;
    assert.ok(positions instanceof Float64Array);
    assert.ok(texcoords instanceof Float64Array);
    assert.ok(triangles instanceof Uint32Array);
    assert.ok(frame.vertexCount > 100);
    assert.equal(positions.length, 2 * frame.vertexCount);
    assert.equal(texcoords.length, positions.length);
    assert.equal(triangles.length, 3 * frame.triangleCount);
    assert.ok(triangles.every((i) => i < frame.vertexCount));
    // Views into the wasm heap, not copies.
    assert.equal(positions.buffer, engine.HEAPF64.buffer);
    // Source coordinates cover the image; far from the lens the warp is the identity.
    const xs = texcoords.filter((_, i) => i % 2 === 0), ys = texcoords.filter((_, i) => i % 2 === 1);
    assert.equal(Math.min(...xs), 0);
    assert.equal(Math.max(...xs), 800);
    assert.equal(Math.min(...ys), 0);
    assert.equal(Math.max(...ys), 600);
  } finally {
    lens.dispose();
  }
});

test('a polygon lens', () => {
  const lens = new engine.Session(800, 600, 60);
  try {
    const frame = lens.update([
      { kind: 'polygon', points: [300, 250, 500, 250, 500, 350, 300, 350], zoom: 2 },
    ]);
    assert.ok(Math.abs(frame.lenses[0].zoomGot - 2) < 0.05, `zoomGot ${frame.lenses[0].zoomGot}`);
    assert.equal(frame.positions.length, frame.texcoords.length);
  } finally {
    lens.dispose();
  }
});

test('forward then inverse round-trips within 1e-6 px; NaN outside', () => {
  const lens = new engine.Session(800, 600, 100);
  try {
    const frame = lens.update([circle(400, 300, 80, 2), circle(150, 450, 50, 3)]);
    // Two lenses this close fit less than asked, and say why.
    assert.ok(frame.lenses[0].zoomFit < 2 && frame.lenses[1].zoomFit < 3);
    assert.match(frame.lenses[1].reason, /lens 1 beside it/);
    assert.equal(frame.warnings.length, 2);
    const points = new Float64Array([400, 300, 430, 310, 480, 300, 150, 450, 165, 440, 10, 10,
                                     799, 599, 0, 0, 620.25, 123.5, 400, 390]);
    const screen = lens.forward(points);
    assert.ok(screen instanceof Float64Array);
    assert.equal(screen.length, points.length);
    assert.ok(screen.every(Number.isFinite));
    // The focus model magnifies the region as a whole: a point 30, 10 px from the centre lands
    // zoomFit times as far from where the centre lands.
    assert.ok(Math.abs(Math.hypot(screen[2] - screen[0], screen[3] - screen[1]) -
                       frame.lenses[0].zoomFit * Math.hypot(30, 10)) < 1e-6);
    const back = lens.inverse(screen);
    let worst = 0;
    for (let i = 0; i < points.length; ++i) worst = Math.max(worst, Math.abs(back[i] - points[i]));
    assert.ok(worst < 1e-6, `round trip off by ${worst} px`);
    const outside = lens.forward([-5, 10, 900, 100]);
    assert.ok(outside.every(Number.isNaN));
    assert.throws(() => lens.forward([1, 2, 3]), /Session.forward: points must be x, y pairs/);
    assert.throws(() => lens.inverse(7), /Session.inverse: points must be an array/);
  } finally {
    lens.dispose();
  }
});

test("an invalid lens throws an Error with the library's message; the session goes on", () => {
  const lens = new engine.Session(800, 600, 40);
  try {
    assert.throws(() => lens.update([circle(400, 300, 80, 9)]), (e) => {
      assert.ok(e instanceof Error);
      assert.equal(e.name, 'InvalidInput');
      assert.equal(e.message, 'validate_lens: zoom must be in [1, 8], got 9');
      return true;
    });
    assert.throws(() => lens.update([circle(900, 300, 80, 2)]), {
      name: 'InvalidInput',
      message: 'validate_lens: lens centre (900, 300) is outside the 800x600 image',
    });
    assert.throws(() => lens.update([circle(400, 300, -1, 2)]), {
      message: 'Region::circle: radius must be a positive number, got -1',
    });
    assert.throws(() => lens.update([{ kind: 'square' }]), {
      message: "Session.update: lens 1: kind must be 'circle' or 'polygon', got 'square'",
    });
    assert.throws(() => lens.update([{ kind: 'circle', cx: 1, cy: 2 }]), {
      message: "Session.update: lens 1: 'r' must be a number, got undefined",
    });
    assert.throws(() => lens.update([{ kind: 'polygon', points: [0, 0, 10, 10, 10, 0, 0, 10] }]),
                  { message: 'Region::polygon: the polygon has zero area' });
    assert.throws(() => lens.update([{ kind: 'polygon' }]), {
      message: 'Session.update: lens 1: points must be an array or a typed array of numbers, ' +
               'got undefined',
    });
    assert.throws(() => lens.update('circle'), { message: 'Session.update: lenses must be an array' });
    // Still usable after the errors.
    assert.ok(Math.abs(lens.update([circle(400, 300, 80, 2)]).lenses[0].zoomGot - 2) < 0.05);
  } finally {
    lens.dispose();
  }
  assert.throws(() => new engine.Session(800, 600, 2), {
    name: 'InvalidOption',
    message: 'validate: mesh must be in [4, 1000] vertices per side, got 2',
  });
  assert.throws(() => engine.session({ width: 800, height: 600, meshes: 3 }), /meshes/);
});

test('views go away with update() and dispose(); dispose twice is fine', () => {
  const lens = new engine.Session(800, 600, 30);
  const first = lens.update([circle(400, 300, 80, 2)]);
  assert.ok(first.positions.length > 0);
  const second = lens.update([circle(410, 300, 80, 2)], true);
  assert.throws(() => first.positions, /view is gone/);
  assert.ok(second.positions.length > 0);
  lens.dispose();
  assert.throws(() => second.texcoords, /view is gone/);
  assert.throws(() => lens.update([]), /disposed/);
  lens.dispose();
});

test('1000 sessions created and disposed do not grow the wasm heap', () => {
  const lenses = [circle(400, 300, 80, 2)];
  const run = (n) => {
    for (let i = 0; i < n; ++i) {
      const lens = new engine.Session(800, 600, 20);
      lens.update(lenses, i % 2 === 1);
      lens.forward([400, 300, 10, 10]);
      if (i % 10 === 0) assert.throws(() => lens.update([circle(400, 300, 80, 9)]));
      lens.dispose();
    }
  };
  run(5);
  const heapBytes = engine.HEAP8.length, inUse = engine.heapInUse();
  run(1000);
  assert.equal(engine.HEAP8.length, heapBytes);
  assert.equal(engine.heapInUse(), inUse, 'malloc bytes in use after 1000 sessions');
  // And with the default mesh, fewer of them.
  const big = () => {
    const lens = new engine.Session(800, 600, 100);
    lens.update(lenses);
    lens.dispose();
  };
  for (let i = 0; i < 3; ++i) big();
  const heapBig = engine.HEAP8.length, inUseBig = engine.heapInUse();
  for (let i = 0; i < 30; ++i) big();
  assert.equal(engine.HEAP8.length, heapBig);
  assert.equal(engine.heapInUse(), inUseBig);
});

test("number_text gives std::to_chars's text without it (emscripten's libc++ has none)", () => {
  assert.equal(engine.numberText(0.1 + 0.2), '0.30000000000000004');
  assert.equal(engine.numberText(1e21), '1e+21');
  assert.equal(engine.numberText(1e-9), '1e-09');
  assert.equal(engine.numberText(180.00000000000014), '180.00000000000014');
  assert.equal(engine.numberText(100), '100');
  assert.equal(engine.numberText(-0.5), '-0.5');
});

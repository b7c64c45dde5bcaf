// Tests of MeshLocator (web/src/mesh_locator.js), the JS point location GeolensView's worker mode
// answers pick() and project() with: on real frames of the engine (web/dist/geolens.mjs) it maps
// points as session.forward() and session.inverse() do, within 1e-9 px, NaN where they give NaN.
// node --test web/test/
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import createGeolens from '../dist/geolens.mjs';
import { MeshLocator } from '../src/mesh_locator.js';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

// A seeded generator in [0, 1).
function random(seed) {
  return () => (seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) / 2 ** 32;
}

// Points to map on a side of `V` (flat): random ones over the frame and a margin beyond it, the
// vertices, the edges' midpoints and points a hair outside the frame's corners.
function probes(V, triangles, width, height, next) {
  const out = [];
  for (let k = 0; k < 3000; ++k)
    out.push(-20 + next() * (width + 40), -20 + next() * (height + 40));
  for (let i = 0; i < V.length; i += 7 * 2) out.push(V[i], V[i + 1]);
  for (let t = 0; t < triangles.length; t += 3 * 11) {
    const a = 2 * triangles[t], b = 2 * triangles[t + 1];
    out.push((V[a] + V[b]) / 2, (V[a + 1] + V[b + 1]) / 2);
  }
  out.push(0, 0, width, height, -1e-6, 0, width + 1e-6, height, 0.5, -0.01);
  return new Float64Array(out);
}

function compare(name, got, want) {
  let max = 0, nan = 0;
  assert.equal(got.length, want.length);
  for (let i = 0; i < got.length; ++i) {
    if (Number.isNaN(want[i]) || Number.isNaN(got[i])) {
      assert.ok(Number.isNaN(want[i]) && Number.isNaN(got[i]),
        `${name}: point ${i >> 1}: the engine gives ${want[i]}, the locator ${got[i]}`);
      ++nan;
      continue;
    }
    max = Math.max(max, Math.abs(got[i] - want[i]));
  }
  assert.ok(max <= 1e-9, `${name}: differs from the engine by up to ${max} px`);
  return { max, nan: nan / 2 };
}

const setups = [
  { size: [800, 600], options: { mesh: 100 }, draft: false,
    lenses: [{ kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2 }] },
  { size: [640, 480], options: { mesh: 60, model: 'lift' }, draft: false,
    lenses: [{ kind: 'polygon', points: [100, 100, 300, 120, 220, 260], zoom: 2.5 },
      { kind: 'circle', cx: 480, cy: 330, r: 50, zoom: 1.7 }] },
  { size: [500, 500], options: { mesh: 40, model: 'field' }, draft: false,
    lenses: [{ kind: 'circle', cx: 250, cy: 240, r: 60, zoom: 3 }] },
  { size: [1024, 768], options: { mesh: 100, draft_mesh: 30 }, draft: true,
    lenses: [{ kind: 'circle', cx: 10, cy: 700, r: 120, zoom: 4 }] },
];

for (const [index, setup] of setups.entries()) {
  test(`MeshLocator equals session.forward / inverse: setup ${index} ` +
    `(${setup.options.model || 'focus'}, mesh ${setup.options.mesh}` +
    `${setup.draft ? ', draft' : ''})`, () => {
    const [width, height] = setup.size;
    const session = engine.session({ width, height, ...setup.options });
    try {
      const frame = session.update(setup.lenses, setup.draft);
      // Copies, as the worker sends them.
      const positions = frame.positions.slice(), texcoords = frame.texcoords.slice();
      const triangles = frame.triangles.slice();
      const map = new MeshLocator(positions, texcoords, triangles);
      const next = random(1000 + index);
      const screen = probes(positions, triangles, width, height, next);
      const source = probes(texcoords, triangles, width, height, next);
      const inverse = compare('inverse', map.inverse(screen), session.inverse(screen));
      const forward = compare('forward', map.forward(source), session.forward(source));
      // Round trips through the locator alone.
      const back = map.forward(map.inverse(screen));
      for (let i = 0; i < screen.length; ++i)
        if (!Number.isNaN(back[i])) assert.ok(Math.abs(back[i] - screen[i]) < 1e-6);
      assert.ok(inverse.nan > 0 && forward.nan > 0, 'some probes are off the mesh');
      assert.ok(inverse.nan < screen.length / 4, `${inverse.nan} of the screen probes off`);
    } finally {
      session.dispose();
    }
  });
}

test('MeshLocator: NaN for non-finite points and an empty mesh; refuses bad indices', () => {
  const map = new MeshLocator([0, 0, 10, 0, 0, 10], [0, 0, 20, 0, 0, 20], [0, 1, 2]);
  assert.deepEqual(Array.from(map.inverse([5, 2])), [10, 4]);
  assert.deepEqual(Array.from(map.forward([10, 4])), [5, 2]);
  const off = map.inverse([NaN, NaN, Infinity, 1, 9, 9]);
  assert.ok(Array.from(off).every(Number.isNaN));
  const flat = new MeshLocator([0, 0, 1, 1, 2, 2], [0, 0, 1, 1, 2, 2], [0, 1, 2]);
  assert.ok(Number.isNaN(flat.inverse([1, 1])[0]));
  assert.throws(() => new MeshLocator([0, 0], [0, 0], [0, 1, 2]), RangeError);
});

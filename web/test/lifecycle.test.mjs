// Memory and lifetimes of the engine's sessions beyond engine.test.mjs's 1000 plain sessions
// (issue 31, item 5): 1000 create / update / drag / dispose cycles through every path (the three
// models, circles and polygons, drafts, inverse, reset, refused lenses and refused options) leave
// the wasm heap, malloc's bytes in use and embind's JS handles where they were after warm-up;
// a frame's views follow the heap when it grows.
// Run: node --test web/test/lifecycle.test.mjs
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import createGeolens from '../dist/geolens.mjs';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

const circle = (cx, cy, r, zoom) => ({ kind: 'circle', cx, cy, r, zoom });
const star = (cx, cy, r, zoom) => {
  const points = new Float64Array(20);
  for (let k = 0; k < 10; ++k) {
    const reach = k % 2 === 0 ? r : 0.4 * r, a = Math.PI / 2 + (k * Math.PI) / 5;
    points[2 * k] = cx + reach * Math.cos(a);
    points[2 * k + 1] = cy - reach * Math.sin(a);
  }
  return { kind: 'polygon', points, zoom };
};

// What is held: the heap's size, malloc's bytes in use, embind's live JS handles.
const held = () => ({
  heapBytes: engine.HEAP8.buffer.byteLength,
  mallocBytes: engine.heapInUse(),
  handles: engine.count_emval_handles(),
});

// One cycle: a session, its first placement, a move (every other cycle a draft first), both
// mappings, a reset and a refused lens; the model turns focus, lift, field; every 20th cycle
// places a star too, every tenth tries two refused sessions.
function cycle(i) {
  const model = ['focus', 'lift', 'field'][i % 3];
  const lens = engine.session({ width: 320, height: 240, mesh: 12, model, draft_mesh: 8,
                                mesh_tolerance: 0 });
  try {
    const first = lens.update(i % 20 === 0 ? [circle(100, 120, 30, 2), star(220, 120, 40, 1.5)]
                                           : [circle(100, 120, 30, 2)]);
    assert.ok(first.lenses.length >= 1);
    if (i % 2 === 1) lens.update([circle(102, 120, 30, 2)], true);
    const frame = lens.update([circle(104, 120, 30, 2)]);
    const screen = lens.forward(frame.texcoords.subarray(0, 40));
    lens.inverse(screen);
    lens.reset();
    assert.throws(() => lens.update([circle(106, 120, 30, 0)]), Error);
  } finally {
    lens.dispose();
  }
  if (i % 10 === 0) {
    assert.throws(() => engine.session({ width: 320, height: 240, mesh: 2 }), Error);
    assert.throws(() => engine.session({ width: 320, height: 240, nonsense: 1 }), Error);
  }
}

test('1000 cycles through every path hold no more memory or handles than after warm-up', () => {
  for (let i = 0; i < 30; ++i) cycle(i);
  const before = held();
  const start = performance.now();
  for (let i = 0; i < 1000; ++i) cycle(i);
  const after = held();
  assert.deepEqual(after, before,
                   `after 1000 cycles (${((performance.now() - start) / 1000).toFixed(1)} s)`);
});

// Grows the wasm heap: forward() of as many zeros as the heap has bytes / 8 copies them four
// times over (the input, two matrices, the output) before it lets them go.
function growHeap() {
  const bytes = engine.HEAP8.buffer.byteLength;
  const lens = engine.session({ width: 100, height: 100, mesh: 8 });
  try {
    lens.update([]);
    lens.forward(new Float64Array(bytes / 8));
  } finally {
    lens.dispose();
  }
  assert.ok(engine.HEAP8.buffer.byteLength > bytes, 'the heap did not grow');
}

test("when the heap grows, a frame's views follow it; a view taken before is detached", () => {
  const lens = engine.session({ width: 800, height: 600, mesh: 40 });
  try {
    const frame = lens.update([circle(400, 300, 80, 2)]);
    const positions = frame.positions.slice(), triangles = frame.triangles.slice();
    const old = frame.texcoords;
    assert.ok(old.length > 0);
    growHeap();
    // Each access is a view of the heap as it is now.
    assert.equal(frame.positions.buffer, engine.HEAP8.buffer);
    assert.deepEqual(frame.positions, positions);
    assert.deepEqual(frame.triangles, triangles);
    // The old ArrayBuffer is detached by memory.grow: its views read as empty, not stale.
    assert.equal(old.length, 0);
    assert.equal(old.buffer.byteLength, 0);
  } finally {
    lens.dispose();
  }
});

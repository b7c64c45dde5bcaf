// Browser tests of GeolensView's worker mode (web/src/view.js with {worker: true}, the engine in
// web/src/solver_worker.js) on the demo page opened with ?worker=1, in Debian's chromium driven
// by playwright-core, under node's own test runner:
//   cd web && npm install && node --test browser-test/worker.test.mjs
// A drag moves the lens (drafts, then the full mesh); pick() answers on the page's thread; the
// focus is drawn as without the worker. How long the page waits during a solve is a timing, not
// a test: it failed on a loaded CI machine (103.6 ms with the worker, 93.7 without); see
// docs/design.md for the figures measured by hand.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  start, openDemo, readCanvas, pagePoint, firstLens, dragFirstLens, knownPicture,
} from './browser.mjs';
import { encodePng } from './png.mjs';

const scratch = mkdtempSync(join(tmpdir(), 'geolens-worker-'));
let env;

before(async () => {
  env = await start({ '/__scratch/': scratch });
});

after(async () => {
  if (env) await env.close();
  rmSync(scratch, { recursive: true, force: true });
});

test('worker mode: the demo loads, solved in the worker, with no console error', async () => {
  const { page, context, problems } = await openDemo(env, '?worker=1');
  try {
    const state = await page.evaluate(() => {
      const view = window.__geolensView;
      return { engine: view.engine, frame: view.frame, workers: view._solver !== null };
    });
    assert.equal(state.engine, null, 'no engine on the page');
    assert.ok(state.workers, 'a solver worker');
    assert.equal(state.frame.draft, false);
    assert.ok(Math.abs(state.frame.lenses[0].zoomGot - 2.5) < 0.01);
    const row = await page.locator('#lens-table tbody tr').first().innerText();
    assert.match(row, /circle\s+2\.50×\s+2\.50×/);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('worker mode: a drag moves the lens: drafts, then the full mesh at rest', async () => {
  const { page, context, problems } = await openDemo(env, '?worker=1');
  try {
    // Two frames a move: the worker's answer comes a frame late at least.
    const { lens, frames } = await dragFirstLens(page, 2);
    assert.equal(frames.at(-1).lenses[0].zoomAsked, lens.zoom);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test("worker mode: pick at the lens's centre gives its source point within 0.5 px; null off",
  async () => {
    const { page, context, problems } = await openDemo(env, '?worker=1');
    try {
      const lens = await firstLens(page);
      const result = await page.evaluate(([cx, cy]) => {
        const view = window.__geolensView;
        const at = view.project(cx, cy);
        const inside = view.project(cx + 30, cy - 20);
        return {
          centre: view.pick(at.x, at.y),
          inside: view.pick(inside.x, inside.y),
          off: view.pick(2, 2),
        };
      }, [lens.cx, lens.cy]);
      assert.ok(Math.hypot(result.centre.x - lens.cx, result.centre.y - lens.cy) < 0.5,
        JSON.stringify(result.centre));
      assert.ok(Math.hypot(result.inside.x - lens.cx - 30, result.inside.y - lens.cy + 20) < 0.5);
      assert.equal(result.off, null);
      // The page's readout under the mouse (pick on each move).
      const c = await pagePoint(page, lens.cx, lens.cy);
      await page.mouse.move(Math.round(c.x), Math.round(c.y));
      const readout = await page.locator('#pick').innerText();
      const [, x, y] = /source \(([\d.]+), ([\d.]+)\)/.exec(readout).map(Number);
      assert.ok(Math.hypot(x - lens.cx, y - lens.cy) < 0.5, readout);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

test('worker mode: the focus equals the page-thread mode within 1 grey level', async () => {
  const [width, height] = [400, 300];
  writeFileSync(join(scratch, 'known.png'), encodePng(width, height, 3,
    knownPicture(width, height)));
  const [cx, cy, r, zoom] = [173.3, 151.7, 40.5, 2.7];
  const query = `?image=/__scratch/known.png&size=${width}x${height}&compare=0&outlines=0` +
    `&lens=circle:${cx},${cy},${r}:${zoom}`;
  const drawn = {};
  for (const [name, extra] of [['page', ''], ['worker', '&worker=1']]) {
    const { page, context, problems } = await openDemo(env, query + extra);
    try {
      drawn[name] = { pixels: await readCanvas(page),
        got: await page.evaluate(() => window.__geolensView.frame.lenses[0].zoomGot) };
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  }
  assert.equal(drawn.worker.got, drawn.page.got);
  const a = drawn.page.pixels.data, b = drawn.worker.pixels.data;
  assert.equal(a.length, b.length);
  let focusMax = 0, allMax = 0;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      const inFocus = Math.hypot(x + 0.5 - cx, y + 0.5 - cy) <= r * drawn.page.got - 3;
      for (let c = 0; c < 4; ++c) {
        const i = 4 * (y * width + x) + c;
        const d = Math.abs(a[i] - b[i]);
        allMax = Math.max(allMax, d);
        if (inFocus) focusMax = Math.max(focusMax, d);
      }
    }
  }
  console.log(`worker vs page thread: focus max ${focusMax}, whole canvas max ${allMax}`);
  assert.ok(focusMax <= 1, `the focus differs by up to ${focusMax}`);
});

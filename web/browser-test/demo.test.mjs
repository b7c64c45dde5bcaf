// Browser tests of the WebGL lens (web/src/view.js) on the demo page (web/demo/), in Debian's
// chromium driven by playwright-core, under node's own test runner:
//   cd web && npm install && node --test browser-test/
// The focus is compared with the native CLI's `magnify` (GEOLENS_CLI, default build/geolens).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  start, openDemo, nextFrame, viewIdle, readCanvas, pagePoint, repoRoot, firstLens, recordFrames,
  dragFirstLens, knownPicture,
} from './browser.mjs';
import { encodePng, decodePng } from './png.mjs';

const CLI = process.env.GEOLENS_CLI || join(repoRoot, 'build', 'geolens');
const scratch = mkdtempSync(join(tmpdir(), 'geolens-browser-'));
let env;

before(async () => {
  env = await start({ '/__scratch/': scratch });
});

after(async () => {
  if (env) await env.close();
  rmSync(scratch, { recursive: true, force: true });
});

test('(a) the demo page loads with no console error and draws both panes', async () => {
  const { page, context, problems } = await openDemo(env);
  try {
    const frame = await page.evaluate(() => window.__geolensView.frame);
    assert.equal(frame.draft, false);
    assert.equal(frame.lenses.length, 1);
    const got = frame.lenses[0].zoomGot;
    assert.ok(Math.abs(got - 2.5) < 0.01, `zoom got ${got}`);
    const pixels = await readCanvas(page);
    const colours = new Set();
    for (let i = 0; i < pixels.data.length; i += 4 * 7)
      colours.add((pixels.data[i] << 16) | (pixels.data[i + 1] << 8) | pixels.data[i + 2]);
    assert.ok(colours.size > 1000, `the geolens canvas has ${colours.size} colours: blank?`);
    const classicColours = await page.evaluate(() => {
      const c = document.getElementById('classic');
      const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const seen = new Set();
      for (let i = 0; i < data.length; i += 4 * 7)
        seen.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
      return seen.size;
    });
    assert.ok(classicColours > 1000, `the classic canvas has ${classicColours} colours: blank?`);
    // The figures are shown.
    const row = await page.locator('#lens-table tbody tr').first().innerText();
    assert.match(row, /circle\s+2\.50×\s+2\.50×/);
    await page.screenshot({ path: join(scratch, 'page.png') });
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('(b) a scripted drag moves the lens: drafts, then the full mesh at rest', async () => {
  const { page, context, problems } = await openDemo(env);
  try {
    const before = await readCanvas(page);
    await dragFirstLens(page, 1);
    const after = await readCanvas(page);
    let changed = 0;
    for (let i = 0; i < after.data.length; i += 4)
      if (Math.abs(after.data[i] - before.data[i]) > 8) ++changed;
    assert.ok(changed > 0.02 * (after.data.length / 4), `${changed} pixels changed`);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

// Two RGBA pictures' difference over a focus: the disc about (cx, cy) of the radius given, shrunk
// by 3 px to leave out its edge; the largest and mean over the colour channels' values.
function focusStats(image, native, width, height, cx, cy, radius) {
  let max = 0, sum = 0, values = 0;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      if (Math.hypot(x + 0.5 - cx, y + 0.5 - cy) > radius - 3) continue;
      for (let c = 0; c < 3; ++c) {
        const i = 4 * (y * width + x) + c;
        const d = Math.abs(image[i] - native[i]);
        max = Math.max(max, d);
        sum += d;
        values += 1;
      }
    }
  }
  return { max, mean: sum / values, values };
}

test("(c) the focus equals the native CLI's magnify output within 2 levels", async () => {
  assert.ok(existsSync(CLI), `no native CLI at ${CLI}: build it (bash scripts/test.sh or cmake ` +
    '--build build --target geolens_cli) or set GEOLENS_CLI');
  const [width, height] = [400, 300];
  const picture = join(scratch, 'known.png');
  writeFileSync(picture, encodePng(width, height, 3, knownPicture(width, height)));
  const report = [];
  // Two setups: a centre on a pixel corner at zoom 2 (the source points fall on quarter texels)
  // and an arbitrary one.
  for (const [cx, cy, r, zoom] of [[200, 150, 50, 2], [173.3, 151.7, 40.5, 2.7]]) {
    const spec = `circle:${cx},${cy},${r}:${zoom}`;
    const output = join(scratch, `cli_${report.length}.png`);
    // The view's engine options are the CLI's defaults (model focus, mesh 100, tolerance 0.2).
    execFileSync(CLI, ['magnify', picture, '--lens', spec, '-o', output], { stdio: 'pipe' });
    const native = decodePng(readFileSync(output));
    const query = `?image=/__scratch/known.png&size=${width}x${height}&compare=0&outlines=0` +
      `&lens=${spec}`;
    const { page, context, problems } = await openDemo(env, query);
    try {
      const frame = await page.evaluate(() => window.__geolensView.frame);
      const got = frame.lenses[0].zoomGot;
      assert.ok(Math.abs(got - zoom) < 1e-6, `zoom got ${got} of ${zoom}`);
      const screenshot = decodePng(await page.locator('#geolens').screenshot());
      const drawn = await readCanvas(page);
      assert.equal(screenshot.width, width);
      assert.equal(screenshot.height, height);
      // The focus on screen: the disc about the centre (which stays put) of radius r * zoom,
      // shrunk by 3 px to leave out the edge.
      for (const [name, image] of [['screenshot', screenshot.data], ['readPixels', drawn.data]]) {
        const { max, mean, values } = focusStats(image, native.data, width, height, cx, cy,
          r * got);
        report.push({ lens: spec, from: name, max, mean, values });
        assert.ok(max <= 2, `${spec} ${name}: the focus differs from the CLI's by up to ${max}`);
      }
      // A draft of the same lens (as while it moves): the coarse mesh drawn with interpolated
      // texture coordinates, which the rasterizer's vertex snapping shifts by up to 1/32 texel
      // here: measured 4 levels at most (the per-pixel noise), 0.26-0.30 on average.
      const draft = await page.evaluate(([x, y]) => {
        const view = window.__geolensView;
        view.setLens(0, { cx: x, cy: y }, { moving: true });
        const { data } = view.readPixels();
        return { draft: view.frame.draft, data: Array.from(data) };
      }, [cx, cy]);
      assert.equal(draft.draft, true);
      const focusDifference = focusStats(draft.data, native.data, width, height, cx, cy, r * got);
      report.push({ lens: spec, from: 'draft', ...focusDifference });
      assert.ok(focusDifference.max <= 8 && focusDifference.mean <= 0.5,
        `${spec} draft: the focus differs from the CLI's by up to ${focusDifference.max}, ` +
        `${focusDifference.mean} on average`);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  }
  for (const r of report)
    console.log(`${r.lens} ${r.from}: max ${r.max}, mean ${r.mean.toFixed(4)} over ${r.values}` +
      ' channel values');
});

// Touches through the DevTools protocol (Input.dispatchTouchEvent): chromium turns them into
// pointer events of pointerType 'touch'.
async function touch(cdp, type, points) {
  await cdp.send('Input.dispatchTouchEvent', {
    type,
    touchPoints: points.map(([x, y], id) => ({ x, y, id })),
  });
}

test('(d) a tap then a two-finger pinch on a lens changes its zoom', async () => {
  const { page, context, problems } = await openDemo(env, '', { hasTouch: true });
  try {
    const cdp = await context.newCDPSession(page);
    const lens = await firstLens(page);
    await page.evaluate(() => (window.__geolensView.selectedIndex = -1));
    const c = await pagePoint(page, lens.cx, lens.cy);
    // A tap on the lens selects it.
    await touch(cdp, 'touchStart', [[c.x, c.y]]);
    await touch(cdp, 'touchEnd', []);
    assert.equal(await page.evaluate(() => window.__geolensView.selectedIndex), 0);
    await recordFrames(page);
    // Two fingers 50 px apart, spread to 80 px: the zoom times 1.6.
    const pointerTypes = await page.evaluate(() => {
      window.__pointerTypes = [];
      window.__geolensView.canvas.addEventListener('pointerdown',
        (e) => window.__pointerTypes.push(e.pointerType));
    });
    void pointerTypes;
    await touch(cdp, 'touchStart', [[c.x - 25, c.y], [c.x + 25, c.y]]);
    for (let k = 1; k <= 6; ++k) {
      const half = 25 + (15 * k) / 6;
      await touch(cdp, 'touchMove', [[c.x - half, c.y], [c.x + half, c.y]]);
      await nextFrame(page);
    }
    await touch(cdp, 'touchEnd', []);
    await viewIdle(page);
    const zoomed = await firstLens(page);
    assert.ok(Math.abs(zoomed.zoom - lens.zoom * 1.6) < 1e-6, `${lens.zoom} -> ${zoomed.zoom}`);
    assert.equal(zoomed.cx, lens.cx, 'a pinch does not move the lens');
    const types = await page.evaluate(() => window.__pointerTypes);
    assert.deepEqual(types, ['touch', 'touch']);
    const frames = await page.evaluate(() => window.__frames);
    assert.ok(frames.some((f) => f.draft), 'drafts while pinching');
    assert.equal(frames.at(-1).draft, false);
    assert.equal(frames.at(-1).lenses[0].zoomAsked, zoomed.zoom);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test("(e) pick at the lens's centre returns its source point within 0.5 px; null off the picture",
  async () => {
    const { page, context, problems } = await openDemo(env);
    try {
      const lens = await firstLens(page);
      const result = await page.evaluate(([cx, cy]) => {
        const view = window.__geolensView;
        const at = view.project(cx, cy);
        const inside = view.project(cx + 30, cy - 20); // in the focus (r 90)
        return {
          centre: view.pick(at.x, at.y),
          inside: view.pick(inside.x, inside.y),
          // The letterbox above the picture (the canvas is wider than tall).
          off: view.pick(2, 2),
          size: [view.canvas.clientWidth, view.canvas.clientHeight],
        };
      }, [lens.cx, lens.cy]);
      assert.ok(Math.hypot(result.centre.x - lens.cx, result.centre.y - lens.cy) < 0.5,
        JSON.stringify(result.centre));
      assert.ok(Math.hypot(result.inside.x - lens.cx - 30, result.inside.y - lens.cy + 20) < 0.5);
      assert.equal(result.off, null, `canvas ${result.size}`);
      // The pointer's own way: the mouse over the centre, read back by the page's readout.
      const c = await pagePoint(page, lens.cx, lens.cy);
      await page.mouse.move(Math.round(c.x), Math.round(c.y));
      const readout = await page.locator('#pick').innerText();
      const [, x, y] = /source \(([\d.]+), ([\d.]+)\)/.exec(readout).map(Number);
      // A whole CSS pixel from the centre is under 1 / (zoom * scale) source pixels from it.
      assert.ok(Math.hypot(x - lens.cx, y - lens.cy) < 0.5, readout);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

test('wheel over a lens zooms it; a polygon drawn by clicks; Delete removes the selected lens',
  async () => {
    const { page, context, problems } = await openDemo(env);
    try {
      const lens = await firstLens(page);
      const c = await pagePoint(page, lens.cx, lens.cy);
      await page.mouse.move(c.x, c.y);
      await page.mouse.wheel(0, -200);
      await viewIdle(page);
      const wheeled = await firstLens(page);
      assert.ok(Math.abs(wheeled.zoom - lens.zoom * Math.exp(0.3)) < 1e-9, `${wheeled.zoom}`);
      // A polygon: the button, three clicks, a double-click on the last.
      await page.click('#draw-polygon');
      const corners = [[700, 200], [850, 220], [780, 330]];
      for (const [x, y] of corners) {
        const p = await pagePoint(page, x, y);
        await page.mouse.click(p.x, p.y);
      }
      const last = await pagePoint(page, ...corners[2]);
      await page.mouse.dblclick(last.x, last.y);
      await viewIdle(page);
      const lenses = await page.evaluate(() => window.__geolensView.lenses);
      assert.equal(lenses.length, 2);
      assert.equal(lenses[1].kind, 'polygon');
      assert.equal(lenses[1].points.length, 6);
      corners.flat().forEach((v, i) => assert.ok(Math.abs(lenses[1].points[i] - v) < 1.5));
      assert.equal(await page.evaluate(() => window.__geolensView.mode), 'idle');
      // Selected (the newest lens): Delete removes it.
      await page.keyboard.press('Delete');
      await viewIdle(page);
      assert.equal((await page.evaluate(() => window.__geolensView.lenses)).length, 1);
      assert.equal(await page.locator('#lens-table tbody tr').count(), 1);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

test('nothing is drawn while nothing changes; a playing <video> is drawn frame by frame',
  async () => {
    const { page, context, problems } = await openDemo(env);
    try {
      const counts = await page.evaluate(async () => {
        const view = window.__geolensView;
        const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
        // Count the GL draws (the mesh and the outlines).
        const gl = view.canvas.getContext('webgl2');
        let draws = 0;
        const drawArrays = gl.drawArrays.bind(gl);
        gl.drawArrays = (...args) => {
          draws += 1;
          return drawArrays(...args);
        };
        await sleep(400);
        const idle = draws;
        // A video of a canvas whose colour changes every 30 ms.
        const canvas = document.createElement('canvas');
        Object.assign(canvas, { width: 320, height: 240 });
        const g = canvas.getContext('2d');
        let t = 0;
        const paint = () => {
          g.fillStyle = `hsl(${(t++ * 40) % 360} 80% 50%)`;
          g.fillRect(0, 0, 320, 240);
        };
        paint();
        const timer = setInterval(paint, 30);
        const video = document.createElement('video');
        video.muted = true;
        video.srcObject = canvas.captureStream(30);
        await video.play();
        await view.setImage(video);
        view.addCircle(160, 120, 30, 2);
        await view.idle();
        // The canvas's middle pixel (the picture is one colour: whatever the lens does there).
        const middle = () => {
          const { width, height, data } = view.readPixels();
          const i = 4 * (width * Math.floor(height / 2) + Math.floor(width / 2));
          return Array.from(data.slice(i, i + 3)).join(',');
        };
        const seen = new Set();
        for (let k = 0; k < 6; ++k) {
          seen.add(middle());
          await sleep(120);
        }
        video.pause();
        clearInterval(timer);
        await sleep(200);
        const paused = [middle()];
        await sleep(300);
        paused.push(middle());
        return { idle, playing: seen.size, paused, lenses: view.lenses.length };
      });
      assert.equal(counts.idle, 0, 'draws while nothing changed');
      assert.ok(counts.playing >= 3, `${counts.playing} different pictures while playing`);
      assert.equal(counts.paused[0], counts.paused[1], 'the picture stays once paused');
      assert.equal(counts.lenses, 1, 'a picture of another size starts without lenses');
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

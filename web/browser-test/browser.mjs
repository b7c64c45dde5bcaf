// What the browser tests share: Debian's chromium launched headless through playwright-core with
// WebGL2 on SwiftShader, the static server over the repository, the demo page opened with its
// console watched, and the steps of a drag of its lens.

import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { chromium } from 'playwright-core';
import { serve, repoRoot } from './server.mjs';

export { repoRoot };

export const CHROMIUM = process.env.GEOLENS_CHROMIUM || '/usr/bin/chromium';

// WebGL2 through ANGLE on SwiftShader (Vulkan), the software GPU; --enable-unsafe-swiftshader
// keeps chromium from warning that it falls back to it.
export const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--use-gl=angle',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

/**
 * Starts the server (the repository at '/', plus `mounts`) and chromium.
 * @returns {Promise<{browser, server, close: () => Promise<void>}>}
 */
export async function start(mounts = {}) {
  if (!existsSync(CHROMIUM))
    throw new Error(`no chromium at ${CHROMIUM}: install it or set GEOLENS_CHROMIUM`);
  const server = await serve({ mounts });
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
  return {
    browser,
    server,
    close: async () => {
      await browser.close();
      await server.close();
    },
  };
}

/**
 * Opens the demo page with `query` (the page's URL parameters) and waits for its first full
 * frame. `problems` collects console errors and page errors.
 */
export async function openDemo(env, query = '', contextOptions = {}) {
  const context = await env.browser.newContext({
    viewport: { width: 1280, height: 760 },
    deviceScaleFactor: 1,
    ...contextOptions,
  });
  const page = await context.newPage();
  const problems = [];
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`pageerror: ${error.message}`));
  await page.goto(`${env.server.url}/web/demo/${query}`);
  await page.waitForFunction(() => document.body.dataset.ready === '1', null, { timeout: 30000 });
  return { page, context, problems };
}

/** Resolves after the page's next animation frame. */
export function nextFrame(page) {
  return page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => resolve())));
}

/** Waits until the view has solved and drawn everything asked (the full mesh shown). */
export function viewIdle(page) {
  return page.evaluate(() => window.__geolensView.idle());
}

/** The geolens canvas's pixels as the view draws them: {width, height, data: number[]}. */
export function readCanvas(page) {
  return page.evaluate(() => {
    const { width, height, data } = window.__geolensView.readPixels();
    return { width, height, data: Array.from(data) };
  });
}

/** Where source point (x, y) is shown, in page CSS pixels (null where the warp does not reach). */
export function pagePoint(page, x, y) {
  return page.evaluate(([sx, sy]) => {
    const view = window.__geolensView;
    const at = view.project(sx, sy);
    if (!at) return null;
    const rect = view.canvas.getBoundingClientRect();
    return { x: rect.left + at.x, y: rect.top + at.y };
  }, [x, y]);
}

/** The demo's first lens, in the engine's form ({kind, cx, cy, r, zoom, ...}). */
export function firstLens(page) {
  return page.evaluate(() => window.__geolensView.lenses[0]);
}

/** Records the view's frames (draft or full, per-lens figures) from now on in window.__frames. */
export function recordFrames(page) {
  return page.evaluate(() => {
    window.__frames = [];
    window.__geolensView.addEventListener('frame', (e) => window.__frames.push(e.detail));
  });
}

/**
 * Drags the demo's first lens by its centre 80 px right and 60 px up (CSS pixels) in 8 mouse
 * moves, `framesPerMove` animation frames apart, and checks what a drag does: drafts while the
 * button is down (at least 2: a step slower than the rest delay may show the full mesh between),
 * the full mesh once the lens rests, the lens moved by the drag in source pixels (within 1e-6)
 * and shown where the pointer left it (within 0.01 px).
 * @returns {Promise<{lens: object, moved: object, frames: object[]}>} before, after, the frames
 */
export async function dragFirstLens(page, framesPerMove) {
  const lens = await firstLens(page);
  await recordFrames(page);
  const from = await pagePoint(page, lens.cx, lens.cy);
  const by = { x: 80, y: -60 };
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let k = 1; k <= 8; ++k) {
    await page.mouse.move(from.x + (by.x * k) / 8, from.y + (by.y * k) / 8);
    for (let f = 0; f < framesPerMove; ++f) await nextFrame(page);
  }
  const whileDown = await page.evaluate(() => window.__frames.map((f) => f.draft));
  await page.mouse.up();
  await viewIdle(page);
  const moved = await firstLens(page);
  // The drag in source pixels: CSS pixels over the picture's scale on the canvas.
  const expected = await page.evaluate(([dx, dy]) => {
    const view = window.__geolensView;
    const a = view.toFrame(0, 0), b = view.toFrame(dx, dy);
    return { x: b.x - a.x, y: b.y - a.y };
  }, [by.x, by.y]);
  assert.ok(Math.abs(moved.cx - lens.cx - expected.x) < 1e-6, `cx ${lens.cx} -> ${moved.cx}`);
  assert.ok(Math.abs(moved.cy - lens.cy - expected.y) < 1e-6, `cy ${lens.cy} -> ${moved.cy}`);
  assert.ok(whileDown.filter((d) => d).length >= 2, `frames while down (draft?): ${whileDown}`);
  const frames = await page.evaluate(() => window.__frames);
  assert.equal(frames.at(-1).draft, false, 'the full mesh once the lens rests');
  const at = await pagePoint(page, moved.cx, moved.cy);
  assert.ok(Math.hypot(at.x - from.x - by.x, at.y - from.y - by.y) < 0.01);
  return { lens, moved, frames };
}

/**
 * An RGB picture (width x height x 3 bytes) with detail at every scale: a smooth wave, 8 px
 * checks and per-pixel noise (a different channel each), so that any difference in sampling shows.
 */
export function knownPicture(width, height) {
  const pixels = new Uint8Array(width * height * 3);
  let seed = 12345;
  const random = () => (seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) / 2 ** 32;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      const i = 3 * (y * width + x);
      pixels[i] = Math.round(128 + 100 * Math.sin(x / 7 + y / 11));
      pixels[i + 1] = ((x >> 3) + (y >> 3)) % 2 ? 200 : 40;
      pixels[i + 2] = Math.floor(random() * 256);
    }
  }
  return pixels;
}

// What the browser tests share: Debian's chromium launched headless through playwright-core with
// WebGL2 on SwiftShader, the static server over the repository, and the demo page opened with its
// console watched.

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

// Browser tests of the map page (web/demo/map.html): a geolens lens over a Leaflet map of local
// XYZ tiles, GeoJSON points clicked through it; in Debian's chromium through playwright-core,
// under node's own test runner:
//   cd web && npm install && node --test browser-test/map.test.mjs
// The tiles (zooms 0-3) are made first by the project's generator, make_xyz_tiles, from the
// native build (GEOLENS_TILES_TOOL, default make_xyz_tiles beside GEOLENS_CLI, default
// build/geolens), into a scratch folder the test server mounts at /__tiles/.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { start, openDemo, repoRoot } from './browser.mjs';

const CLI = process.env.GEOLENS_CLI || join(repoRoot, 'build', 'geolens');
const TILES_TOOL = process.env.GEOLENS_TILES_TOOL || join(dirname(CLI), 'make_xyz_tiles');
const MAX_ZOOM = 3;
const scratch = mkdtempSync(join(tmpdir(), 'geolens-map-'));
const QUERY = 'map.html?tiles=' + encodeURIComponent('/__tiles/{z}/{x}/{y}.png') +
  `&maxzoom=${MAX_ZOOM}`;
let env;

before(async () => {
  if (!existsSync(TILES_TOOL))
    throw new Error(`no tile generator at ${TILES_TOOL}: build it (cmake --build build --target ` +
      'make_xyz_tiles) or set GEOLENS_TILES_TOOL (or GEOLENS_CLI, the folder it is in)');
  execFileSync(TILES_TOOL, [scratch, String(MAX_ZOOM)], { stdio: 'pipe' });
  env = await start({ '/__tiles/': scratch });
});

after(async () => {
  if (env) await env.close();
  rmSync(scratch, { recursive: true, force: true });
});

async function openMap() {
  const opened = await openDemo(env, QUERY);
  await opened.page.evaluate(() => {
    window.__picks = [];
    window.addEventListener('geolens-pick', (e) => window.__picks.push(e.detail));
  });
  return opened;
}

/** Waits until the map rests, its tiles are in, and the lens is solved and drawn. */
function settled(page) {
  return page.evaluate(() => window.__mapDemo.settled());
}

/** A GeoJSON point's unmagnified place: container CSS pixels (= source pixels at DPR 1). */
function pointAt(page, name) {
  return page.evaluate((wanted) => {
    const point = window.__mapDemo.points().find((p) => p.name === wanted);
    const at = window.__map.latLngToContainerPoint(point.latlng);
    return { x: at.x, y: at.y };
  }, name);
}

/** Where the lens shows source point (x, y), in page CSS pixels. */
function shownAt(page, x, y) {
  return page.evaluate(([sx, sy]) => {
    const view = window.__geolensView;
    const at = view.project(sx, sy);
    const box = view.canvas.getBoundingClientRect();
    return at && { x: box.left + at.x, y: box.top + at.y, local: at };
  }, [x, y]);
}

/** A container point in page CSS pixels. */
function onPage(page, x, y) {
  return page.evaluate(([cx, cy]) => {
    const box = window.__map.getContainer().getBoundingClientRect();
    return { x: box.left + cx, y: box.top + cy };
  }, [x, y]);
}

async function clickAt(page, at) {
  await page.evaluate(() => delete document.body.dataset.clicked);
  await page.mouse.click(at.x, at.y);
  return page.evaluate(() => ({
    clicked: document.body.dataset.clicked,
    pick: window.__picks.at(-1),
    panel: document.getElementById('clicked').innerText,
  }));
}

async function drag(page, from, by, steps = 10) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let k = 1; k <= steps; ++k)
    await page.mouse.move(from.x + (by.x * k) / steps, from.y + (by.y * k) / steps);
  await page.mouse.up();
}

/**
 * Figures of the lens's canvas, computed in the page (its pixels are too many to send): the
 * colours (every 5th pixel), the share of the tiles' land colour (242, 239, 233), and the share
 * of pixels whose red differs by more than 8 from the last call's.
 */
function canvasFigures(page) {
  return page.evaluate(() => {
    const { data } = window.__geolensView.readPixels();
    const last = window.__lastPixels;
    window.__lastPixels = data;
    const colours = new Set();
    let land = 0, changed = 0;
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      if (i % 20 === 0) colours.add((r << 16) | (g << 8) | b);
      if (Math.abs(r - 242) + Math.abs(g - 239) + Math.abs(b - 233) < 12) ++land;
      if (last && Math.abs(r - last[i]) > 8) ++changed;
    }
    const count = data.length / 4;
    return { colours: colours.size, land: land / count, changed: changed / count };
  });
}

function state(page) {
  return page.evaluate(() => ({
    center: window.__map.getCenter(),
    zoom: window.__map.getZoom(),
    lens: window.__geolensView.lenses[0],
  }));
}

test('(a) the map page loads with no console error and shows the tiles through the lens',
  async () => {
    const { page, context, problems } = await openMap();
    try {
      const loaded = await page.locator('.leaflet-tile-loaded').count();
      assert.ok(loaded >= 4, `${loaded} tiles loaded`);
      const frame = await page.evaluate(() => window.__geolensView.frame);
      assert.equal(frame.draft, false);
      assert.equal(frame.lenses.length, 1);
      const got = frame.lenses[0].zoomGot;
      assert.ok(Math.abs(got - 3) < 0.01, `zoom got ${got}`);
      // The lens's canvas shows the map: many colours, mostly the tiles' land colour, not the
      // background beyond the world's edge.
      const figures = await canvasFigures(page);
      assert.ok(figures.colours > 300, `the lens canvas has ${figures.colours} colours: blank?`);
      assert.ok(figures.land > 0.3, `${figures.land} of the pixels are land`);
      const listed = await page.locator('#points li').count();
      assert.equal(listed, 12);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

test('(b) a click where the lens shows a point magnified names it; outside the lens too',
  async () => {
    const { page, context, problems } = await openMap();
    try {
      // The lens's centre 26 px (source) from Dordor: the lens shows Dordor about 3 x 26 px
      // from its centre, far from where the map has it.
      const dordor = await pointAt(page, 'Dordor');
      await page.evaluate(([cx, cy]) => window.__geolensView.setLens(0, { cx, cy }),
        [dordor.x - 22, dordor.y + 14]);
      await settled(page);
      const shown = await shownAt(page, dordor.x, dordor.y);
      const plain = await onPage(page, dordor.x, dordor.y);
      const apart = Math.hypot(shown.x - plain.x, shown.y - plain.y);
      assert.ok(apart > 30, `shown ${apart.toFixed(1)} px from its unmagnified place`);
      assert.equal(await page.evaluate(([x, y]) => window.__mapDemo.lensAt(x, y),
        [shown.local.x, shown.local.y]), 0, 'the magnified point is in the lens');
      let got = await clickAt(page, shown);
      assert.equal(got.clicked, 'Dordor');
      assert.equal(got.pick.lens, 0, 'picked through the lens');
      assert.ok(Math.hypot(got.pick.source.x - dordor.x, got.pick.source.y - dordor.y) < 1,
        `picked source ${JSON.stringify(got.pick.source)}, Dordor at ${JSON.stringify(dordor)}`);
      assert.match(got.panel, /Dordor/);
      assert.match(got.panel, /through lens 1/);
      // Where the map has it unmagnified, the lens shows something else.
      got = await clickAt(page, plain);
      assert.notEqual(got.clicked, 'Dordor');
      // A second point, outside the lens (where the lens leaves the map as it is).
      const senbra = await pointAt(page, 'Senbra');
      const there = await shownAt(page, senbra.x, senbra.y);
      const senbraPlain = await onPage(page, senbra.x, senbra.y);
      assert.ok(Math.hypot(there.x - senbraPlain.x, there.y - senbraPlain.y) < 1);
      got = await clickAt(page, there);
      assert.equal(got.clicked, 'Senbra');
      assert.equal(got.pick.lens, -1, 'outside the lens');
      assert.match(got.panel, /Senbra/);
      await page.screenshot({ path: join(scratch, 'clicked.png') });
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

test('(c) a drag outside the lens pans the map; the lens stays on the screen', async () => {
  const { page, context, problems } = await openMap();
  try {
    const before = await state(page);
    await canvasFigures(page);
    // Far from the lens (which is in the middle).
    await drag(page, await onPage(page, 150, 550), { x: 140, y: -110 });
    await settled(page);
    const after = await state(page);
    const moved = Math.hypot(after.center.lat - before.center.lat,
      after.center.lng - before.center.lng);
    assert.ok(moved > 1, `the centre moved ${moved.toFixed(3)} degrees`);
    assert.deepEqual(after.lens, before.lens, 'the lens stays where it was');
    assert.equal(await page.evaluate(() => document.body.dataset.clicked), undefined,
      'a drag is no click');
    // The lens shows the panned map.
    const { changed } = await canvasFigures(page);
    assert.ok(changed > 0.05, `${(100 * changed).toFixed(1)} % of the pixels changed`);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('(d) a drag or a wheel on the lens moves or zooms the lens, not the map', async () => {
  const { page, context, problems } = await openMap();
  try {
    const before = await state(page);
    await drag(page, await onPage(page, before.lens.cx, before.lens.cy), { x: 60, y: 40 });
    await settled(page);
    const after = await state(page);
    assert.deepEqual(after.center, before.center, 'the map did not move');
    assert.ok(Math.abs(after.lens.cx - before.lens.cx - 60) < 1e-6, `cx ${after.lens.cx}`);
    assert.ok(Math.abs(after.lens.cy - before.lens.cy - 40) < 1e-6, `cy ${after.lens.cy}`);
    await page.mouse.move(...Object.values(await onPage(page, after.lens.cx, after.lens.cy)));
    await page.mouse.wheel(0, -200);
    await settled(page);
    const zoomed = await state(page);
    assert.ok(zoomed.lens.zoom > after.lens.zoom + 0.2, `lens zoom ${zoomed.lens.zoom}`);
    assert.equal(zoomed.zoom, before.zoom, 'the map kept its zoom');
    // A wheel off the lens zooms the map.
    await page.mouse.move(...Object.values(await onPage(page, 120, 120)));
    await page.mouse.wheel(0, -200);
    await page.waitForFunction((z) => window.__map.getZoom() > z, before.zoom);
    await settled(page);
    const mapZoomed = await state(page);
    assert.equal(mapZoomed.lens.zoom, zoomed.lens.zoom, 'the lens kept its zoom');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

// Touches through the DevTools protocol (Input.dispatchTouchEvent): chromium turns them into
// pointer events of pointerType 'touch' and into touch events, which Leaflet uses.
async function touchDrag(cdp, from, by, steps = 8) {
  const send = (type, points) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: points.map(([x, y], id) => ({ x, y, id })),
  });
  await send('touchStart', [[from.x, from.y]]);
  for (let k = 1; k <= steps; ++k)
    await send('touchMove', [[from.x + (by.x * k) / steps, from.y + (by.y * k) / steps]]);
  await send('touchEnd', []);
}

test('(e) touch: a drag pans the map off the lens and moves the lens on it; a tap names a point',
  async () => {
    const { page, context, problems } = await openDemo(env, QUERY, { hasTouch: true });
    try {
      const cdp = await context.newCDPSession(page);
      const before = await state(page);
      await touchDrag(cdp, await onPage(page, 150, 550), { x: 100, y: -80 });
      await settled(page);
      const panned = await state(page);
      assert.notDeepEqual(panned.center, before.center, 'the map moved');
      assert.deepEqual(panned.lens, before.lens, 'the lens stayed');
      await touchDrag(cdp, await onPage(page, before.lens.cx, before.lens.cy), { x: 40, y: 30 });
      await settled(page);
      const moved = await state(page);
      assert.deepEqual(moved.center, panned.center, 'the map stayed');
      assert.ok(Math.abs(moved.lens.cx - before.lens.cx - 40) < 1e-6, `cx ${moved.lens.cx}`);
      // A tap on Garbra (bottom left, far from the lens).
      const garbra = await pointAt(page, 'Garbra');
      const at = await shownAt(page, garbra.x, garbra.y);
      await cdp.send('Input.dispatchTouchEvent', {
        type: 'touchStart', touchPoints: [{ x: at.x, y: at.y, id: 0 }],
      });
      await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
      await page.waitForFunction(() => document.body.dataset.clicked !== undefined);
      assert.equal(await page.evaluate(() => document.body.dataset.clicked), 'Garbra');
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  });

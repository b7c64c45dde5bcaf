// The browser pages' pictures in the docs, taken by the pages themselves in headless chromium
// (web/browser-test/browser.mjs): docs/web_demo.jpg (web/demo/index.html, its default picture and
// lens, beside the classic magnifier) and docs/web_map.jpg (web/demo/map.html over tiles from
// build/make_xyz_tiles, zooms 0-3). Needs web/dist (scripts/web_build.sh) and web/node_modules
// (cd web && npm ci).
//   node scripts/web_pictures.mjs
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { start, openDemo, repoRoot, viewIdle } from '../web/browser-test/browser.mjs';

const tiles = mkdtempSync(join(tmpdir(), 'geolens-pictures-'));
execFileSync(join(repoRoot, 'build', 'make_xyz_tiles'), [tiles, '3'], { stdio: 'pipe' });
const env = await start({ '/__tiles/': tiles });
try {
  const shots = [
    ['', 'web_demo.jpg', viewIdle],
    [
      'map.html?tiles=' + encodeURIComponent('/__tiles/{z}/{x}/{y}.png') + '&maxzoom=3',
      'web_map.jpg',
      (page) => page.evaluate(() => window.__mapDemo.settled()),
    ],
  ];
  for (const [query, name, settled] of shots) {
    const { page, context, problems } = await openDemo(env, query);
    await settled(page);
    if (problems.length) throw new Error(`${name}: ${problems.join('; ')}`);
    await page.screenshot({ path: join(repoRoot, 'docs', name), type: 'jpeg', quality: 70 });
    await context.close();
    console.log(`docs/${name}`);
  }
} finally {
  await env.close();
  rmSync(tiles, { recursive: true, force: true });
}

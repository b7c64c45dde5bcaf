// The npm package (web/package.json): `npm pack` makes a tarball of at most 1 MB holding the
// engine, the view and their declarations, and web/example installs it and runs in node.
// node --test web/test/   (needs npm, and web/dist built: scripts/web_build.sh)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { cpSync, mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const web = fileURLToPath(new URL('..', import.meta.url));

test('npm pack makes the package web/example installs and runs', () => {
  const folder = mkdtempSync(join(tmpdir(), 'geolens-pack-'));
  try {
    const npm = (args, cwd) =>
      execFileSync('npm', [...args, '--no-audit', '--no-fund', '--loglevel=error'], {
        cwd,
        encoding: 'utf8',
      });
    const [packed] = JSON.parse(npm(['pack', '--json', '--pack-destination', folder], web));
    const files = packed.files.map((f) => f.path).sort();
    assert.deepEqual(files, [
      'README.md',
      'dist/geolens.mjs',
      'dist/geolens.wasm',
      'geolens.d.ts',
      'package.json',
      'src/mesh_locator.js',
      'src/solver_worker.js',
      'src/view.d.ts',
      'src/view.js',
    ]);
    const tarball = join(folder, packed.filename);
    const size = statSync(tarball).size;
    assert.ok(size <= 1024 * 1024, `the package is ${size} bytes gzipped, over 1 MB`);
    const pkg = JSON.parse(readFileSync(join(web, 'package.json'), 'utf8'));
    assert.equal(pkg.dependencies, undefined, 'the package has no runtime dependencies');

    const example = join(folder, 'example');
    cpSync(join(web, 'example'), example, { recursive: true });
    const manifest = JSON.parse(readFileSync(join(example, 'package.json'), 'utf8'));
    manifest.dependencies.geolens = `file:${tarball}`;
    writeFileSync(join(example, 'package.json'), JSON.stringify(manifest));
    npm(['install', '--offline'], example);
    const out = execFileSync(process.execPath, ['magnify.mjs'], { cwd: example, encoding: 'utf8' });
    assert.match(out, /^zoom asked 2, got 2\.00; \d+ triangles$/m);
    assert.match(out, /\(430, 300\) is shown at \(460\.00, 300\.00\); back: \(430\.00, 300\.00\)/);
  } finally {
    rmSync(folder, { recursive: true, force: true });
  }
});

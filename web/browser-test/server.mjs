// A small static file server for the browser tests (and for trying the demo page by hand):
// serves a folder (by default the repository's root, so that /web/demo/ finds
// ../../examples/demo.png) plus any extra URL prefixes mapped to folders, on a free port.
//
//   node web/browser-test/server.mjs [port]     # then open http://127.0.0.1:PORT/web/demo/

import { createServer } from 'node:http';
import { createReadStream, statSync } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

export const repoRoot = resolve(fileURLToPath(new URL('../..', import.meta.url)));

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.geojson': 'application/geo+json',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
  '.svg': 'image/svg+xml',
  '.txt': 'text/plain; charset=utf-8',
};

// The file a URL path names under `folder`, or null if it would leave the folder.
function inside(folder, path) {
  const file = normalize(join(folder, path));
  return file === folder || file.startsWith(folder + sep) ? file : null;
}

/**
 * Starts serving. `root`: the folder served at '/'; `mounts`: {'/prefix/': folder, ...}.
 * @returns {Promise<{url: string, port: number, close: () => Promise<void>}>}
 */
export function serve({ root = repoRoot, mounts = {}, port = 0 } = {}) {
  const server = createServer((request, response) => {
    let path;
    try {
      path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    } catch {
      response.writeHead(400).end();
      return;
    }
    let folder = resolve(root), rest = path;
    for (const [prefix, target] of Object.entries(mounts)) {
      if (path.startsWith(prefix)) {
        folder = resolve(target);
        rest = path.slice(prefix.length);
        break;
      }
    }
    let file = inside(folder, rest);
    try {
      if (file && statSync(file).isDirectory()) file = join(file, 'index.html');
      if (!file || !statSync(file).isFile()) throw new Error('not a file');
    } catch {
      response.writeHead(404, { 'content-type': 'text/plain' }).end('not found: ' + path);
      return;
    }
    response.writeHead(200, {
      'content-type': TYPES[extname(file).toLowerCase()] || 'application/octet-stream',
      'cache-control': 'no-store',
    });
    createReadStream(file).pipe(response);
  });
  return new Promise((resolveStart, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', () => {
      const actual = server.address().port;
      resolveStart({
        url: `http://127.0.0.1:${actual}`,
        port: actual,
        close: () => new Promise((done) => {
          server.closeAllConnections();
          server.close(() => done());
        }),
      });
    });
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const { url } = await serve({ port: Number(process.argv[2] || 8000) });
  console.log(`serving ${repoRoot} at ${url}/ (the demo: ${url}/web/demo/)`);
}

// The solver of GeolensView's worker mode (view.js, `{worker: true}`): a module Worker that makes
// the engine (../dist/geolens.mjs, next to this file as the npm package ships it) and a session,
// and solves there, off the page's thread.
//
// Messages in (one at a time, in order):
//   {type: 'session', id, width, height, options}  a new session (the old one stays if refused)
//   {type: 'update', id, lenses, draft, outlines}   a solve; outlines: per lens, source points of
//                                                   its boundary (flat) to map by session.forward
//   {type: 'dispose'}                               frees the session and closes the worker
// Messages out:
//   {type: 'session', id}                          the session is made
//   {type: 'frame', id, positions, texcoords (Float64Array), triangles (Uint32Array), lenses,
//    warnings, draft, model, vertexCount, triangleCount, solveMs, outlines (Float64Array each),
//    mesh: {vertices: Float32Array, count[, indices: Uint32Array]} (the GPU's copy, view.js's
//    gpuMesh), shape: {mean, max, flipped} (shapeDistortion)}: copies of the frame, their buffers
//    transferred, and what the page would otherwise compute from them on its own thread
//   {type: 'error', id, request: 'session' | 'update', error: {name, message}}: the engine
//    refused; the session keeps its last frame

import createGeolens from '../dist/geolens.mjs';
import { gpuMesh, shapeDistortion } from './view.js';

let engine = null;
let session = null;
let queue = Promise.resolve();

function fail(id, request, error) {
  const name = (error && error.name) || 'Error';
  const message = (error && error.message) || String(error);
  self.postMessage({ type: 'error', id, request, error: { name, message } });
}

async function handle(message) {
  if (message.type === 'dispose') {
    if (session) session.dispose();
    session = null;
    self.close();
    return;
  }
  try {
    if (!engine) engine = await createGeolens();
  } catch (error) {
    fail(message.id, message.type, error);
    return;
  }
  if (message.type === 'session') {
    try {
      const next = engine.session({
        width: message.width, height: message.height, ...message.options,
      });
      if (session) session.dispose();
      session = next;
      self.postMessage({ type: 'session', id: message.id });
    } catch (error) {
      fail(message.id, 'session', error);
    }
    return;
  }
  if (message.type === 'update') {
    if (!session) {
      fail(message.id, 'update', new Error('GeolensView worker: no session'));
      return;
    }
    try {
      const start = performance.now();
      const frame = session.update(message.lenses, message.draft);
      const solveMs = performance.now() - start;
      // The views die with the next update: copies, whose buffers go to the page.
      const positions = frame.positions.slice();
      const texcoords = frame.texcoords.slice();
      const triangles = frame.triangles.slice();
      const outlines = (message.outlines || []).map((points) => session.forward(points));
      const mesh = gpuMesh({ positions, texcoords, triangles, draft: frame.draft });
      const shape = shapeDistortion(texcoords, positions, triangles);
      const reply = {
        type: 'frame',
        id: message.id,
        positions,
        texcoords,
        triangles,
        lenses: frame.lenses,
        warnings: frame.warnings,
        draft: frame.draft,
        model: frame.model,
        vertexCount: frame.vertexCount,
        triangleCount: frame.triangleCount,
        solveMs,
        outlines,
        mesh,
        shape,
      };
      const transfer = [positions.buffer, texcoords.buffer, triangles.buffer, mesh.vertices.buffer,
        ...(mesh.indices ? [mesh.indices.buffer] : []),
        ...outlines.map((o) => o.buffer)];
      self.postMessage(reply, transfer);
    } catch (error) {
      fail(message.id, 'update', error);
    }
  }
}

self.onmessage = (event) => {
  const message = event.data;
  queue = queue.then(() => handle(message));
};

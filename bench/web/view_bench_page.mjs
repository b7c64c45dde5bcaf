// The page side of the GeolensView frame-time bench (bench/web/view_bench.html, driven by
// view_bench.mjs): on one canvas of size=WxH CSS pixels (devicePixelRatio 1 in the bench), either
//
//   mode=lens   a GeolensView (web/src/view.js) with one circle lens, dragged for `frames` frames
//               through the view's own pointer handlers: a PointerEvent dispatched on the canvas
//               in each animation frame, after the view's own callback of that frame, so that the
//               view's next callback (the next frame) solves and draws it;
//   mode=floor  the same picture drawn as one textured quad (mipmapped, as the view's texture)
//               in each animation frame, with its own tiny WebGL2 program.
//
// Both read back one pixel (gl.readPixels) after each frame's draw, so that the GPU's work
// (SwiftShader, in the GPU process) is finished and counted in the frame's work in both.
//
// Parameters: mode=lens|floor, size=WxH (the canvas, CSS pixels; 1280x1024), image=URL (else a
// generated picture of picture=WxH, by default the canvas's size), lens=CX,CY,R,ZOOM (source
// pixels; the picture's centre, r 150, zoom 2), frames=300, warmup=30 (a first drag, not
// recorded), mesh=100 (the view's full mesh), draftmesh=N (the view's draftMesh, else its
// default, 30), pointer=mouse, worker=1 (the view's opt-in worker mode: the solve in a Worker),
// floormip=nearest (the floor samples the nearest mipmap level, as the view's drafts do, instead
// of blending two, as its frames at rest do).
// window.__bench: {ready: Promise, info(), warm() (the warm-up: a first drag, or floor frames),
// run(): Promise<result> (the measured frames; result: per frame figures), and in mode=lens
// gpuNames(), gpuMesh('draft'|'full'), gpuTime(name, budget, least): the draws alone, synced,
// without animation frames (see gpuVariants).

import createGeolens from '../../web/dist/geolens.mjs';
import { GeolensView } from '../../web/src/view.js';

const params = new URLSearchParams(location.search);
const pair = (text) => text.split('x').map(Number);
const mode = params.get('mode') || 'lens';
const [cssWidth, cssHeight] = pair(params.get('size') || '1280x1024');
const imageUrl = params.get('image');
const [pictureWidth, pictureHeight] = pair(params.get('picture') || `${cssWidth}x${cssHeight}`);
const frames = Number(params.get('frames') || 300);
const warmup = Number(params.get('warmup') || 30);
const mesh = Number(params.get('mesh') || 100);
const draftMesh = params.has('draftmesh') ? Number(params.get('draftmesh')) : undefined;
const pointerType = params.get('pointer') || 'mouse';
const useWorker = params.get('worker') === '1';
const floorMinFilter = params.get('floormip') === 'nearest' ? 'LINEAR_MIPMAP_NEAREST'
  : 'LINEAR_MIPMAP_LINEAR';

const canvas = document.getElementById('bench');
const dpr = window.devicePixelRatio || 1;
canvas.style.width = cssWidth + 'px';
canvas.style.height = cssHeight + 'px';
canvas.width = Math.round(cssWidth * dpr);
canvas.height = Math.round(cssHeight * dpr);

const now = () => performance.now();

// A seeded generator (mulberry32), so that the generated picture is the same in every run.
function random(seed) {
  return () => {
    seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// A detailed picture: a gradient, 600 translucent discs and boxes, a 16 px grid of 1 px lines,
// labels every 64 px and fine diagonal hatching (every mip level has detail).
function makePicture(width, height) {
  const c = document.createElement('canvas');
  c.width = width;
  c.height = height;
  const g = c.getContext('2d');
  const rand = random(31);
  const gradient = g.createLinearGradient(0, 0, width, height);
  gradient.addColorStop(0, '#203a5c');
  gradient.addColorStop(0.5, '#d9c9a3');
  gradient.addColorStop(1, '#5c2033');
  g.fillStyle = gradient;
  g.fillRect(0, 0, width, height);
  for (let k = 0; k < 600; ++k) {
    g.fillStyle = `hsla(${Math.floor(rand() * 360)}, 70%, 55%, 0.45)`;
    const x = rand() * width, y = rand() * height, s = 4 + rand() * 60;
    if (k % 2 === 0) {
      g.beginPath();
      g.arc(x, y, s, 0, 2 * Math.PI);
      g.fill();
    } else {
      g.fillRect(x, y, s, s * (0.3 + rand()));
    }
  }
  g.strokeStyle = 'rgba(0, 0, 0, 0.35)';
  g.lineWidth = 1;
  g.beginPath();
  for (let x = 0.5; x < width; x += 16) g.moveTo(x, 0), g.lineTo(x, height);
  for (let y = 0.5; y < height; y += 16) g.moveTo(0, y), g.lineTo(width, y);
  g.stroke();
  g.strokeStyle = 'rgba(255, 255, 255, 0.25)';
  g.beginPath();
  for (let d = -height; d < width; d += 5) g.moveTo(d, 0), g.lineTo(d + height, height);
  g.stroke();
  g.fillStyle = '#111';
  g.font = '10px sans-serif';
  for (let x = 0; x < width; x += 64)
    for (let y = 0; y < height; y += 64) g.fillText(`${x / 64},${y / 64}`, x + 3, y + 12);
  return c;
}

async function loadPicture() {
  if (!imageUrl) return makePicture(pictureWidth, pictureHeight);
  const image = new Image();
  image.src = imageUrl;
  await image.decode();
  return image;
}

// The picture's place on the canvas, as the view computes it (view.js _placement): letterboxed,
// frame point p at device pixel (ox, oy) + p * scale.
function placement(width, height) {
  const W = canvas.width, H = canvas.height;
  const scale = Math.min(W / width, H / height);
  return {
    scale,
    ox: Math.round((W - width * scale) / 2),
    oy: Math.round((H - height * scale) / 2),
  };
}

const readback = new Uint8Array(4);
let floorGl = null;

// ---------------------------------------------------------------------------------------------
// The floor: the picture as one textured quad per frame.

const QUAD_VERTEX = `#version 300 es
in vec2 a_corner;
uniform vec4 u_rect;
out vec2 v_uv;
void main() {
  v_uv = a_corner;
  gl_Position = vec4(mix(u_rect.xy, u_rect.zw, a_corner), 0.0, 1.0);
}`;

const QUAD_FRAGMENT = `#version 300 es
precision highp float;
uniform sampler2D u_picture;
in vec2 v_uv;
out vec4 color;
void main() {
  color = texture(u_picture, v_uv);
}`;

function program(gl, vertexText, fragmentText) {
  const p = gl.createProgram();
  for (const [type, text] of [[gl.VERTEX_SHADER, vertexText], [gl.FRAGMENT_SHADER, fragmentText]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, text);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
      throw new Error('shader: ' + gl.getShaderInfoLog(shader));
    gl.attachShader(p, shader);
  }
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return p;
}

// The unit square's two triangles as program p's a_corner, in a vertex array of their own (bound
// on return).
function quadVao(gl, p) {
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 1]),
    gl.STATIC_DRAW);
  const corner = gl.getAttribLocation(p, 'a_corner');
  gl.enableVertexAttribArray(corner);
  gl.vertexAttribPointer(corner, 2, gl.FLOAT, false, 0, 0);
  return vao;
}

// The floor's drawing state, with the same context attributes and texture as the view's.
function floorSetup(picture) {
  const gl = (floorGl = canvas.getContext('webgl2', {
    alpha: true, premultipliedAlpha: true, antialias: false, depth: false, stencil: false,
  }));
  const p = program(gl, QUAD_VERTEX, QUAD_FRAGMENT);
  const vao = quadVao(gl, p);
  const texture = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl[floorMinFilter]);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, true);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, picture);
  gl.generateMipmap(gl.TEXTURE_2D);
  const width = picture.naturalWidth || picture.width, height = picture.naturalHeight ||
    picture.height;
  const { scale, ox, oy } = placement(width, height);
  const W = canvas.width, H = canvas.height;
  const rect = [(2 * ox) / W - 1, 1 - (2 * oy) / H, (2 * (ox + width * scale)) / W - 1,
    1 - (2 * (oy + height * scale)) / H];
  const location = {
    rect: gl.getUniformLocation(p, 'u_rect'),
    picture: gl.getUniformLocation(p, 'u_picture'),
  };
  return () => {
    gl.viewport(0, 0, W, H);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.useProgram(p);
    gl.uniform4fv(location.rect, rect);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.uniform1i(location.picture, 0);
    gl.bindVertexArray(vao);
    gl.drawArrays(gl.TRIANGLES, 0, 6);
    gl.bindVertexArray(null);
    const t = now();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, readback);
    return now() - t;
  };
}

// `count` frames of the floor: per frame the rAF timestamp, the work (draw + readback) and the
// readback alone.
function floorFrames(draw, count) {
  return new Promise((resolve) => {
    const out = [];
    const step = (timestamp) => {
      const start = now();
      const syncMs = draw();
      out.push({ timestamp, workMs: now() - start, syncMs });
      if (out.length < count + 1) requestAnimationFrame(step);
      else resolve(out);
    };
    requestAnimationFrame(step);
  });
}

let floorDraw = null;

async function warmFloor(picture) {
  floorDraw = floorSetup(picture);
  await floorFrames(floorDraw, warmup);
}

async function runFloor() {
  const out = await floorFrames(floorDraw, frames);
  return { mode, frames: out };
}

// ---------------------------------------------------------------------------------------------
// The lens: a GeolensView, instrumented.

// Timers around the view's steps (its private methods, wrapped on this instance only; view.js is
// unchanged): per animation frame of the view, a record of the time in each (ms), when it drew
// and which lens the mesh it drew shows; and every frame shown (_showFrame: solved on the page,
// or received from the worker in worker mode) with its lens and whether it is a draft.
function instrument(view) {
  const gl = view._gl;
  const probe = { record: null, records: [], outside: {}, shows: [], shown: null };
  const add = (key, ms) => {
    const into = probe.record || probe.outside;
    into[key] = (into[key] || 0) + ms;
  };
  const wrap = (object, name, key, after) => {
    const original = object[name];
    if (typeof original !== 'function') return;
    object[name] = function (...args) {
      const start = now();
      try {
        return original.apply(this, args);
      } finally {
        add(key, now() - start);
        if (after) after(probe.record, args);
      }
    };
  };
  const session = view._session;
  wrap(session, 'update', 'updateMs');
  wrap(session, 'forward', 'forwardMs');
  wrap(session, 'inverse', 'inverseMs');
  wrap(view, '_solve', 'solveMs');
  wrap(view, '_showFrame', 'showMs', (record, [lenses, frame]) => {
    probe.shown = { cx: lenses[0].cx, cy: lenses[0].cy, draft: Boolean(frame.draft), at: now(),
      vertexCount: frame.vertexCount, triangleCount: frame.triangleCount };
    probe.shows.push(probe.shown);
  });
  wrap(view, '_uploadMesh', 'uploadMs');
  wrap(view, '_draw', 'drawMs', (record) => {
    if (!record) return;
    record.drawnAt = now();
    record.drawn = probe.shown;
  });
  wrap(view, '_drawOutlines', 'outlinesMs');
  wrap(view, '_updateCursor', 'cursorMs');
  const animationFrame = view._animationFrame;
  view._animationFrame = function () {
    const record = { start: now() };
    probe.record = record;
    try {
      animationFrame.call(this);
      if (record.drawnAt !== undefined) {
        const t = now();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, readback);
        record.syncMs = now() - t;
      }
    } finally {
      record.viewMs = now() - record.start;
      probe.record = null;
      probe.records.push(record);
    }
  };
  return probe;
}

// A drag of `count` frames by the pointer: pressed on the lens's centre, then a figure of eight
// (A = a quarter of the picture's shown width across, B = an eighth of its height up and down)
// back to where it started, one pointermove per animation frame, then released. Each move is
// dispatched in the bench's callback, which runs after the view's in the same frame; the view's
// callback in the next frame should solve and draw it. Per frame: the rAF timestamp, the input
// dispatched in the frame before (the move this frame should show), the view's record of this
// frame (if its callback ran). Per move: its lag, how many frames after the next one the view
// first drew a mesh of the lens at the move's target (0: in the next frame; null: never, a later
// move's came first).
function drag(view, probe, count) {
  const lens = view.lenses[0];
  const start = view.project(lens.cx, lens.cy);
  const from = view.toFrame(start.x, start.y);
  const { scale } = placement(view.imageSize.width, view.imageSize.height);
  const A = (0.25 * view.imageSize.width * scale) / dpr;
  const B = (0.125 * view.imageSize.height * scale) / dpr;
  const point = (k) => ({
    x: start.x + A * Math.sin((2 * Math.PI * k) / count),
    y: start.y + B * Math.sin((4 * Math.PI * k) / count),
  });
  const clamp = (v, hi) => Math.min(hi, Math.max(0, v));
  const target = (k) => {
    const f = view.toFrame(point(k).x, point(k).y);
    return {
      cx: clamp(lens.cx + f.x - from.x, view.imageSize.width),
      cy: clamp(lens.cy + f.y - from.y, view.imageSize.height),
    };
  };
  const rect = canvas.getBoundingClientRect();
  const pointer = (type, p) => {
    canvas.dispatchEvent(new PointerEvent(type, {
      pointerId: 1, pointerType, isPrimary: true, bubbles: true, cancelable: true,
      composed: true, button: type === 'pointermove' ? -1 : 0,
      buttons: type === 'pointerup' ? 0 : 1, clientX: rect.left + p.x, clientY: rect.top + p.y,
      pressure: type === 'pointerup' ? 0 : 0.5,
    }));
  };
  const firstShow = probe.shows.length;
  return new Promise((resolve) => {
    const out = [];
    let i = 0, inputMs = 0, releasedAt = 0;
    const step = (timestamp) => {
      // The view's callback of this frame, if it ran (it was asked for before this one).
      const last = probe.records[probe.records.length - 1];
      const record = last && last.start >= timestamp ? last : null;
      out.push({ timestamp, inputMs, record, rest: i > count });
      const t = now();
      if (i === 0) {
        pointer('pointerdown', point(0));
        pointer('pointermove', point(1));
      } else if (i < count) {
        pointer('pointermove', point(i + 1));
      } else if (i === count) {
        pointer('pointerup', point(count));
        releasedAt = t;
      }
      inputMs = now() - t;
      if (i <= count) {
        ++i;
        requestAnimationFrame(step);
        return;
      }
      const same = (a, b) => a && Math.abs(a.cx - b.cx) < 1e-6 && Math.abs(a.cy - b.cy) < 1e-6;
      const lags = [];
      for (let k = 1; k <= count; ++k) {
        const want = target(k);
        let lag = null;
        for (let j = k; j <= count && lag === null; ++j) {
          const r = out[j].record;
          if (r && r.drawnAt !== undefined && same(r.drawn, want)) lag = j - k;
        }
        lags.push(lag);
      }
      resolve({ frames: out, lags, releasedAt, shows: probe.shows.slice(firstShow) });
    };
    requestAnimationFrame(step);
  });
}

let lensView = null;

async function setupLens(picture) {
  const options = { mesh };
  if (draftMesh) options.draftMesh = draftMesh;
  if (useWorker) options.worker = true;
  const view = new GeolensView(canvas, useWorker ? null : await createGeolens(), options);
  await view.setImage(picture);
  const width = view.imageSize.width, height = view.imageSize.height;
  const [cx, cy, r, zoom] = params.has('lens')
    ? params.get('lens').split(',').map(Number)
    : [width / 2, height / 2, 150, 2];
  view.addCircle(cx, cy, r, zoom);
  await view.idle();
  lensView = view;
  return view;
}

let probe = null;

async function warmLens(view) {
  probe = instrument(view);
  await drag(view, probe, warmup);
  await view.idle();
}

async function runLens(view) {
  probe.records.length = 0;
  probe.outside = {};
  const result = await drag(view, probe, frames);
  await view.idle();
  const full = probe.shows.find((x) => x.at > result.releasedAt && !x.draft);
  const during = result.shows.filter((x) => x.at <= result.releasedAt);
  return {
    mode, frames: result.frames, lags: result.lags, outside: probe.outside, worker: useWorker,
    rest: full ? { ms: full.at - result.releasedAt, vertexCount: full.vertexCount } : null,
    drafts: during.filter((x) => x.draft).length, full: during.filter((x) => !x.draft).length,
    draftVertices: during.length ? during[0].vertexCount : 0,
    draftTriangles: during.length ? during[0].triangleCount : 0,
  };
}

// ---------------------------------------------------------------------------------------------
// The GPU alone: draws synced by a 1 px readback, back to back in one task (no animation frames,
// so no compositing between them), on the view's context: the view's own draw (its mesh with the
// per-pixel affine map and textureLod, and its outlines), the mesh alone, the same mesh with
// texture coordinates interpolated between its vertices (a plain texture() lookup), the floor's
// quad, the quad with only the triangles that move something drawn over it, and a clear. For the
// draft mesh (a drag's) and the full one (at rest). The view draws a draft with interpolated
// texture coordinates already (its own indexed vertices, view.js's draftVertices): the two
// variants made from the exact mesh's vertices (EXACT_ONLY) are not drawn for it.
const EXACT_ONLY = new Set(['mesh, interpolated texcoords',
  'floor quad + warped triangles (view shader)']);

const INTERPOLATED_VERTEX = `#version 300 es
in vec2 a_position;
in vec2 a_origin;
in vec2 a_source;
in vec4 a_jacobian;
uniform vec2 u_scale;
uniform vec2 u_offset;
uniform vec2 u_size;
out vec2 v_uv;
void main() {
  vec2 d = a_position - a_origin;
  v_uv = (a_source + vec2(dot(a_jacobian.xy, d), dot(a_jacobian.zw, d))) / u_size;
  gl_Position = vec4(a_position * u_scale + u_offset, 0.0, 1.0);
}`;

function gpuVariants(view) {
  const gl = view._gl;
  const W = canvas.width, H = canvas.height;
  const { width, height } = view.imageSize;
  const { scale, ox, oy } = placement(width, height);
  // The mesh through the view's buffer, with interpolated texture coordinates.
  const interpolated = program(gl, INTERPOLATED_VERTEX, QUAD_FRAGMENT);
  const meshVao = gl.createVertexArray();
  gl.bindVertexArray(meshVao);
  gl.bindBuffer(gl.ARRAY_BUFFER, view._meshBuffer);
  for (const [name, size, offset] of [['a_position', 2, 0], ['a_origin', 2, 2],
    ['a_source', 2, 4], ['a_jacobian', 4, 6]]) {
    const at = gl.getAttribLocation(interpolated, name);
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, gl.FLOAT, false, 44, 4 * offset);
  }
  // The floor's quad.
  const quad = program(gl, QUAD_VERTEX, QUAD_FRAGMENT);
  const quadArray = quadVao(gl, quad);
  gl.bindVertexArray(null);
  const rect = [(2 * ox) / W - 1, 1 - (2 * oy) / H, (2 * (ox + width * scale)) / W - 1,
    1 - (2 * (oy + height * scale)) / H];
  // The triangles that move something by 0.01 px or more (the lens and the ring around it),
  // drawn with the view's own program over the floor's quad: the rest of the warp is the picture
  // as it is. Rebuilt when the view's mesh changes (draft, full).
  const warpedBuffer = gl.createBuffer();
  const warpedVao = gl.createVertexArray();
  gl.bindVertexArray(warpedVao);
  gl.bindBuffer(gl.ARRAY_BUFFER, warpedBuffer);
  for (const [name, size, offset] of [['a_position', 2, 0], ['a_origin', 2, 2],
    ['a_source', 2, 4], ['a_jacobian', 4, 6], ['a_sigma', 1, 10]]) {
    const at = gl.getAttribLocation(view._meshProgram, name);
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, gl.FLOAT, false, 44, 4 * offset);
  }
  gl.bindVertexArray(null);
  let warpedFor = null;
  const warped = { count: 0, of: 0 };
  const buildWarped = () => {
    if (warpedFor === view._mesh || view._mesh.indices) return;
    warpedFor = view._mesh;
    const v = view._mesh.vertices, F = 11, keep = [];
    for (let t = 0; t < view._mesh.count; t += 3) {
      let moved = 0;
      for (let k = 0; k < 3; ++k) {
        const o = (t + k) * F, dx = v[o] - v[o + 2], dy = v[o + 1] - v[o + 3];
        const sx = v[o + 4] + v[o + 6] * dx + v[o + 7] * dy;
        const sy = v[o + 5] + v[o + 8] * dx + v[o + 9] * dy;
        moved = Math.max(moved, Math.hypot(sx - v[o], sy - v[o + 1]));
      }
      if (moved >= 0.01) keep.push(v.subarray(t * F, (t + 3) * F));
    }
    const data = new Float32Array(keep.length * 3 * F);
    keep.forEach((tri, i) => data.set(tri, i * 3 * F));
    gl.bindBuffer(gl.ARRAY_BUFFER, warpedBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    warped.count = keep.length * 3;
    warped.of = view._mesh.count;
  };
  const clear = () => {
    gl.viewport(0, 0, W, H);
    gl.disable(gl.BLEND);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
  };
  const texture = () => {
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, view._texture);
  };
  const variants = {
    'view: mesh + outlines': () => view._draw(),
    'view: mesh, no outlines': () => {
      view._view.outlines = false;
      view._draw();
      view._view.outlines = true;
    },
    'mesh, interpolated texcoords': () => {
      clear();
      gl.useProgram(interpolated);
      gl.uniform2f(gl.getUniformLocation(interpolated, 'u_scale'), (2 * scale) / W,
        (-2 * scale) / H);
      gl.uniform2f(gl.getUniformLocation(interpolated, 'u_offset'), (2 * ox) / W - 1,
        1 - (2 * oy) / H);
      gl.uniform2f(gl.getUniformLocation(interpolated, 'u_size'), width, height);
      texture();
      gl.uniform1i(gl.getUniformLocation(interpolated, 'u_picture'), 0);
      gl.bindVertexArray(meshVao);
      gl.drawArrays(gl.TRIANGLES, 0, view._mesh.count);
      gl.bindVertexArray(null);
    },
    'floor quad': () => {
      clear();
      gl.useProgram(quad);
      gl.uniform4fv(gl.getUniformLocation(quad, 'u_rect'), rect);
      texture();
      gl.uniform1i(gl.getUniformLocation(quad, 'u_picture'), 0);
      gl.bindVertexArray(quadArray);
      gl.drawArrays(gl.TRIANGLES, 0, 6);
      gl.bindVertexArray(null);
    },
    'floor quad + warped triangles (view shader)': () => {
      buildWarped();
      variants['floor quad']();
      const loc = view._loc;
      gl.useProgram(view._meshProgram);
      gl.uniform2f(loc.scale, (2 * scale) / W, (-2 * scale) / H);
      gl.uniform2f(loc.offset, (2 * ox) / W - 1, 1 - (2 * oy) / H);
      gl.uniform2f(loc.size, width, height);
      gl.uniform1f(loc.placeScale, scale);
      gl.uniform2f(loc.placeOffset, ox, oy);
      gl.uniform1f(loc.height, H);
      texture();
      gl.uniform1i(loc.picture, 0);
      gl.bindVertexArray(warpedVao);
      gl.drawArrays(gl.TRIANGLES, 0, warped.count);
      gl.bindVertexArray(null);
    },
    'clear only': clear,
  };
  Object.defineProperty(variants, 'warped', { value: warped, enumerable: false });
  return variants;
}

let variants = null;
let restDelay = null; // the view's, while a draft is held for gpuTime

// Puts the draft mesh (a drag's) or the full one (at rest) on the view: for a draft the lens is
// "moved" where it is (setLens with moving: true) and solved in the next animation frame, with
// the rest put off until the full mesh is asked for again.
async function gpuMesh(view, which) {
  if (!variants) variants = gpuVariants(view);
  if (which === 'draft') {
    if (restDelay === null) restDelay = view.options.restDelay;
    view.setOptions({ restDelay: 600000 });
    view.setLens(0, { cx: view.lenses[0].cx }, { moving: true });
    await new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));
  } else {
    if (restDelay !== null) view.setOptions({ restDelay });
    restDelay = null;
    view.setLens(0, { cx: view.lenses[0].cx });
    await view.idle();
  }
  if (!view._mesh.indices) variants['floor quad + warped triangles (view shader)']();
  return { vertices: view._mesh.count, warped: view._mesh.indices ? null : variants.warped.count,
    draft: view.frame.draft };
}

// Variant `name` drawn once, then again until `budget` ms have passed (at least `least` times),
// each synced by a 1 px readback: {ms: the median of those after the first, count: all draws};
// null for a variant not drawn for the view's mesh (EXACT_ONLY on a draft).
function gpuTime(view, name, budget, least) {
  if (view._mesh.indices && EXACT_ONLY.has(name)) return null;
  const gl = view._gl, times = [], begin = now();
  for (let k = 0; k <= least || now() - begin < budget; ++k) {
    const start = now();
    variants[name]();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, readback);
    if (k > 0) times.push(now() - start);
  }
  return { ms: times.sort((a, b) => a - b)[Math.floor(times.length / 2)], count: times.length + 1 };
}

// ---------------------------------------------------------------------------------------------

let picture = null;

function info() {
  const gl = lensView ? lensView._gl : floorGl;
  if (!gl) return null;
  const debug = gl.getExtension('WEBGL_debug_renderer_info');
  return {
    mode,
    canvas: [canvas.width, canvas.height],
    css: [cssWidth, cssHeight],
    dpr,
    picture: [picture.naturalWidth || picture.width, picture.naturalHeight || picture.height],
    image: imageUrl || 'generated',
    renderer: debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
    lens: lensView ? lensView.lenses[0] : null,
    mesh,
    userAgent: navigator.userAgent,
  };
}

const ready = (async () => {
  picture = await loadPicture();
  if (mode === 'lens') await setupLens(picture);
})();

window.__bench = {
  ready,
  info,
  warm: async () => {
    await ready;
    return mode === 'floor' ? warmFloor(picture) : warmLens(lensView);
  },
  run: async () => (mode === 'floor' ? runFloor() : runLens(lensView)),
  gpuNames: () => Object.keys((variants = variants || gpuVariants(lensView))),
  gpuMesh: (which) => gpuMesh(lensView, which),
  gpuTime: (name, budget = 1500, least = 10) => gpuTime(lensView, name, budget, least),
};

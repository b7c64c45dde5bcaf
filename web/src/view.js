// GeolensView: a geolens lens on a <canvas>, drawn with WebGL2 (issue 31, item 2).
//
//   import createGeolens from 'geolens';
//   import { GeolensView } from 'geolens/view';
//   const view = new GeolensView(canvas, await createGeolens());
//   await view.setImage(imageElement);
//   view.addCircle(300, 500, 90, 2.5);
//   view.addEventListener('frame', (e) => console.log(e.detail.lenses));  // zoom asked / got
//
// The canvas shows the whole picture, letterboxed; the picture is drawn through the lens's warp
// mesh (positions: where, in the picture's frame; texture coordinates: which source point),
// textured with mipmaps. Pointer events (mouse, pen, touch): drag a lens by its inside, wheel over
// it or pinch it for its zoom; Delete or Backspace removes the selected lens; drawPolygon() makes
// clicks add a polygon's vertices (a double-click, Enter or a click on its first vertex closes
// it, Escape cancels).
//
// Off the pointer's critical path: the handlers only record the newest lens state and ask for an
// animation frame; the solve runs there (a draft, on the coarse mesh, while a lens moves), then
// the full mesh once the lens rests (restDelay after the last move, or on release). Nothing is
// drawn unless the warp, the picture, the outlines or the canvas size changed.
//
// Coordinates: "frame" points are pixels of the picture's frame where the warp puts things (the
// warp's positions); "source" points are pixels of the picture itself (texture coordinates, the
// lenses' coordinates); "CSS" points are CSS pixels from the canvas's top-left corner.
//
// Worker mode (opt-in): the engine runs in a module Worker (solver_worker.js), off the page's
// thread, so that a first placement or a drag's solve does not freeze the page:
//
//   const view = new GeolensView(canvas, null, { worker: true });  // or a URL of the worker
//   const view = await GeolensView.create(canvas, createGeolens, { worker: true });  // the same
//
// The engine argument is not used then (the worker makes its own engine from ../dist/geolens.mjs
// next to it; create() does not call the factory). Only the newest request waits: while a solve
// is in flight, later lens states replace the waiting one. pick() and project() stay synchronous:
// they are answered on the page's thread from the last frame's copied mesh (mesh_locator.js, the
// engine's rules). What differs: readPixels() draws what was solved last (it cannot wait for the
// worker: await idle() first); an engine option or picture size the engine refuses is not thrown
// by setOptions() or setImage() but dispatched as an 'error' event, and the options go back to
// the last ones the engine took.

import { MeshLocator } from './mesh_locator.js';

const ZOOM_MIN = 1;
const ZOOM_MAX = 8;

// Options the view reads itself; every other option of setOptions() goes to the engine's session.
const VIEW_DEFAULTS = {
  restDelay: 150, // ms after the last move before the full mesh is solved
  outlines: true, // draw the lens outlines
  background: [0, 0, 0, 0], // the letterbox, RGBA in [0, 1] (premultiplied by the canvas)
  autoResize: true, // keep the canvas's pixels in step with its CSS size and devicePixelRatio
  interactive: true, // pointer, wheel and key handling
  onFrame: null, // called with each frame's figures, as the 'frame' event's detail
};
const ENGINE_DEFAULTS = { mesh: 100, draft_mesh: 30 };

// The warp is drawn triangle by triangle with each triangle's own affine map from frame to source
// (flat: the same for all its pixels), evaluated at each pixel's centre, rather than texture
// coordinates interpolated between its vertices: the rasterizer snaps vertices to its sub-pixel
// grid (1/16 px under SwiftShader), which moves interpolated coordinates by up to 1/64 texel at
// zoom 2 and changes the picture by up to 4 levels where it is busy. So each pixel samples the
// source point the warp gives it, as geolens's own renderer (src/render/render.cpp) does, and at
// its level of detail: log2 of the map's largest singular value in source texels per device
// pixel, trilinear between levels.
const MESH_VERTEX = `#version 300 es
in vec2 a_position;
in vec2 a_origin;
in vec2 a_source;
in vec4 a_jacobian;
in float a_sigma;
uniform vec2 u_scale;
uniform vec2 u_offset;
flat out vec2 v_origin;
flat out vec2 v_source;
flat out vec4 v_jacobian;
flat out float v_sigma;
void main() {
  v_origin = a_origin;
  v_source = a_source;
  v_jacobian = a_jacobian;
  v_sigma = a_sigma;
  gl_Position = vec4(a_position * u_scale + u_offset, 0.0, 1.0);
}`;

const MESH_FRAGMENT = `#version 300 es
precision highp float;
uniform sampler2D u_picture;
uniform vec2 u_size;
uniform float u_placeScale;
uniform vec2 u_placeOffset;
uniform float u_height;
flat in vec2 v_origin;
flat in vec2 v_source;
flat in vec4 v_jacobian;
flat in float v_sigma;
out vec4 color;
void main() {
  vec2 device = vec2(gl_FragCoord.x, u_height - gl_FragCoord.y);
  vec2 d = (device - u_placeOffset) / u_placeScale - v_origin;
  vec2 source = v_source + vec2(dot(v_jacobian.xy, d), dot(v_jacobian.zw, d));
  float lod = log2(max(v_sigma / u_placeScale, 1.0));
  color = textureLod(u_picture, source / u_size, lod);
}`;
const MESH_FLOATS = 11; // per vertex: position 2, origin 2, source 2, jacobian 4, sigma 1

// Drafts (while a lens moves) are drawn the plain way: the engine's vertices, indexed, their
// texture coordinates interpolated, the nearest mipmap level of the GPU's level of detail (a
// sampler of their own). Under SwiftShader a draft on the 30 grid then costs about what the
// picture drawn as one quad does, less than half the per-pixel map on the 50 grid
// (bench/web/README.md); the frame at rest keeps the exact sampling.
const DRAFT_VERTEX = `#version 300 es
in vec2 a_position;
in vec2 a_source;
uniform vec2 u_scale;
uniform vec2 u_offset;
uniform vec2 u_size;
out vec2 v_texcoord;
void main() {
  v_texcoord = a_source / u_size;
  gl_Position = vec4(a_position * u_scale + u_offset, 0.0, 1.0);
}`;

const DRAFT_FRAGMENT = `#version 300 es
precision highp float;
uniform sampler2D u_picture;
in vec2 v_texcoord;
out vec4 color;
void main() {
  color = texture(u_picture, v_texcoord);
}`;
const DRAFT_FLOATS = 4; // per vertex: position 2, source 2

// Strokes: quads around each segment, in device pixels, their edges smoothed by the distance
// across the line (v_across, pixels from its middle).
const STROKE_VERTEX = `#version 300 es
in vec2 a_position;
in float a_across;
uniform vec2 u_viewport;
out float v_across;
void main() {
  v_across = a_across;
  vec2 clip = a_position / u_viewport * 2.0 - 1.0;
  gl_Position = vec4(clip.x, -clip.y, 0.0, 1.0);
}`;

const STROKE_FRAGMENT = `#version 300 es
precision highp float;
uniform vec4 u_color;
uniform float u_half;
in float v_across;
out vec4 color;
void main() {
  float alpha = clamp(u_half + 0.5 - abs(v_across), 0.0, 1.0) * u_color.a;
  color = vec4(u_color.rgb * alpha, alpha);
}`;

function snakeCase(name) {
  return name.replace(/[A-Z]/g, (c) => '_' + c.toLowerCase());
}

function clampZoom(zoom) {
  return Math.min(ZOOM_MAX, Math.max(ZOOM_MIN, zoom));
}

function finite(value, what) {
  if (typeof value !== 'number' || !Number.isFinite(value))
    throw new TypeError(`GeolensView: ${what} must be a finite number, got ${value}`);
  return value;
}

// A polygon's vertices as a flat array [x0, y0, x1, y1, ...] from [[x, y], ...], [{x, y}, ...] or
// a flat array (or typed array) of numbers.
function flatPoints(points) {
  const list = Array.from(points);
  if (list.length > 0 && typeof list[0] === 'object')
    return list.flatMap((p) => (Array.isArray(p) ? [p[0], p[1]] : [p.x, p.y]));
  return list;
}

function copyLens(lens) {
  return lens.kind === 'polygon' ? { ...lens, points: lens.points.slice() } : { ...lens };
}

function polygonArea(flat) {
  let twice = 0;
  for (let i = 0, n = flat.length; i < n; i += 2) {
    const j = (i + 2) % n;
    twice += flat[i] * flat[j + 1] - flat[j] * flat[i + 1];
  }
  return Math.abs(twice) / 2;
}

function insidePolygon(flat, x, y) {
  let inside = false;
  for (let i = 0, n = flat.length, j = n - 2; i < n; j = i, i += 2) {
    const xi = flat[i], yi = flat[i + 1], xj = flat[j], yj = flat[j + 1];
    if (yi > y !== yj > y && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

function lensArea(lens) {
  return lens.kind === 'circle' ? Math.PI * lens.r * lens.r : polygonArea(lens.points);
}

function lensContains(lens, x, y) {
  if (lens.kind === 'circle') return Math.hypot(x - lens.cx, y - lens.cy) <= lens.r;
  return insidePolygon(lens.points, x, y);
}

// Source points along a lens's boundary, flat: a circle every ~4 px (at least 48), a polygon's
// edges every ~8 px (the lift and field models do not keep a polygon's edges straight).
function boundaryPoints(lens) {
  const out = [];
  if (lens.kind === 'circle') {
    const n = Math.max(48, Math.min(720, Math.ceil((2 * Math.PI * lens.r) / 4)));
    for (let k = 0; k < n; ++k) {
      const a = (2 * Math.PI * k) / n;
      out.push(lens.cx + lens.r * Math.cos(a), lens.cy + lens.r * Math.sin(a));
    }
    return out;
  }
  const p = lens.points, n = p.length;
  for (let i = 0; i < n; i += 2) {
    const j = (i + 2) % n;
    const steps = Math.max(1, Math.ceil(Math.hypot(p[j] - p[i], p[j + 1] - p[i + 1]) / 8));
    for (let s = 0; s < steps; ++s) {
      const t = s / steps;
      out.push(p[i] + t * (p[j] - p[i]), p[i + 1] + t * (p[j + 1] - p[i + 1]));
    }
  }
  return out;
}

function pictureSize(source) {
  if (typeof HTMLImageElement !== 'undefined' && source instanceof HTMLImageElement)
    return [source.naturalWidth, source.naturalHeight];
  if (typeof HTMLVideoElement !== 'undefined' && source instanceof HTMLVideoElement)
    return [source.videoWidth, source.videoHeight];
  if (typeof VideoFrame !== 'undefined' && source instanceof VideoFrame)
    return [source.displayWidth, source.displayHeight];
  return [source.width, source.height];
}

function compileProgram(gl, vertexText, fragmentText) {
  const program = gl.createProgram();
  for (const [type, text] of [
    [gl.VERTEX_SHADER, vertexText],
    [gl.FRAGMENT_SHADER, fragmentText],
  ]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, text);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS) && !gl.isContextLost())
      throw new Error('GeolensView: shader: ' + gl.getShaderInfoLog(shader));
    gl.attachShader(program, shader);
    gl.deleteShader(shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS) && !gl.isContextLost())
    throw new Error('GeolensView: program: ' + gl.getProgramInfoLog(program));
  return program;
}

/**
 * A geolens lens on a canvas: the picture drawn through the warp with WebGL2, lenses moved with
 * the pointer, the solve done in animation frames (drafts while a lens moves, the full mesh once
 * it rests).
 *
 * Events (an EventTarget): 'frame' (CustomEvent, detail: the frame's figures, see `frame`),
 * 'change' (detail: {reason}: the lenses, the selection or the mode changed), 'error' (detail:
 * {error}: a solve failed; the lenses went back to the last ones solved).
 */
export class GeolensView extends EventTarget {
  /**
   * @param {HTMLCanvasElement} canvas the canvas to draw on (it gets touch-action: none and a
   *   tabIndex so that it takes keys)
   * @param {object|null} engine what createGeolens() resolves to; not used (may be null) in
   *   worker mode
   * @param {object} [options] view options (restDelay, outlines, background, autoResize,
   *   interactive, onFrame), engine options (model, mesh, draftMesh, meshTolerance, ... in
   *   camelCase or as the library names them; see setOptions()) and `worker`: true (the
   *   solver_worker.js next to this file) or the URL of a solver worker script to solve in a
   *   module Worker; set here only
   */
  constructor(canvas, engine, options = {}) {
    super();
    if (!canvas || typeof canvas.getContext !== 'function')
      throw new TypeError('GeolensView: canvas must be a <canvas> element');
    const { worker = false, ...rest } = options;
    if (!worker && (!engine || typeof engine.session !== 'function'))
      throw new TypeError('GeolensView: engine must be what createGeolens() resolves to');
    this.canvas = canvas;
    this.engine = engine && typeof engine.session === 'function' ? engine : null;
    this._solver = null; // worker mode: {worker, nextId, generation, inFlight, waiting, ...}
    this._view = { ...VIEW_DEFAULTS };
    this._engineOptions = { ...ENGINE_DEFAULTS };
    this._lenses = [];
    this._good = []; // the lenses of the last frame solved
    this._selected = -1;
    this._source = null;
    this._width = 0; // the picture's size, source pixels
    this._height = 0;
    this._session = null;
    this._frame = null; // the last frame's figures
    this._mesh = null; // its warp as the GPU draws it: {vertices, count[, indices]} (gpuMesh)
    this._outlines = []; // per lens: frame points of its boundary (NaN breaks the line)
    this._solveWanted = false;
    this._moving = false; // a lens is being moved: solve drafts
    this._restTimer = 0;
    this._textureDirty = false;
    this._needsDraw = true;
    this._raf = 0;
    this._idleWaiters = [];
    this._pointers = new Map(); // pointerId -> {x, y} (CSS pixels)
    this._drag = null; // {index, fromX, fromY (frame), lens (as it was)}
    this._pinch = null; // {index, distance, zoom}
    this._drawing = null; // {points: source points (flat), pointer: frame point or null}
    this._hover = null; // the mouse's last place, for the cursor
    this._closedAt = null; // where and when a click closed a polygon (the rest of a double-click)
    this._videoLoop = null;
    this._resizeObserver = null;
    this._disposed = false;
    this._initGL();
    this._listen();
    if (worker) this._startWorker(worker);
    this.setOptions(rest);
  }

  /**
   * Makes a view, creating the engine first when given createGeolens itself (not in worker
   * mode, `options.worker`: the worker makes its own).
   * @param {HTMLCanvasElement} canvas
   * @param {object|Function|null} engineOrFactory an engine, or createGeolens
   * @param {object} [options] as the constructor's
   * @returns {Promise<GeolensView>}
   */
  static async create(canvas, engineOrFactory, options = {}) {
    if (options.worker) return new GeolensView(canvas, engineOrFactory, options);
    const engine =
      typeof engineOrFactory === 'function' ? await engineOrFactory() : engineOrFactory;
    return new GeolensView(canvas, engine, options);
  }

  // ---------------------------------------------------------------------------------------------
  // The picture

  /**
   * Shows a picture: an HTMLImageElement (waited for if still loading), ImageBitmap,
   * HTMLCanvasElement, OffscreenCanvas, VideoFrame or HTMLVideoElement (re-uploaded each frame
   * while it plays). A picture of another size starts a new session and removes the lenses.
   * @param {TexImageSource} source
   * @returns {Promise<void>} resolved once the picture is uploaded
   */
  async setImage(source) {
    this._checkAlive('setImage');
    const isImage = typeof HTMLImageElement !== 'undefined' && source instanceof HTMLImageElement;
    const isVideo = typeof HTMLVideoElement !== 'undefined' && source instanceof HTMLVideoElement;
    if (isImage && !(source.complete && source.naturalWidth > 0)) await source.decode();
    if (isVideo && source.readyState < 2)
      await new Promise((resolve, reject) => {
        source.addEventListener('loadeddata', resolve, { once: true });
        source.addEventListener('error', () => reject(new Error('GeolensView: video error')), {
          once: true,
        });
      });
    if (this._disposed) return;
    const [width, height] = pictureSize(source);
    if (!(width > 0 && height > 0)) throw new Error('GeolensView.setImage: the picture is empty');
    const resized = width !== this._width || height !== this._height || !this._session;
    if (resized) this._newSession(width, height, this._engineOptions);
    this._stopVideo();
    this._source = source;
    this._textureSize = null;
    this._upload();
    if (resized) {
      this._lenses = [];
      this._good = [];
      this._selected = -1;
      this._drawing = null;
      this._drag = this._pinch = null;
      this._changed('image');
    }
    if (isVideo) this._startVideo(source);
    this._needsDraw = true;
    this._schedule();
  }

  /** The picture's size in source pixels, {width, height} (0 x 0 before setImage). */
  get imageSize() {
    return { width: this._width, height: this._height };
  }

  // ---------------------------------------------------------------------------------------------
  // Lenses

  /**
   * The lenses, copies in the engine's form: {kind: 'circle', cx, cy, r, zoom, footprint?} or
   * {kind: 'polygon', points: [x0, y0, ...], zoom, footprint?} (source pixels).
   * @returns {object[]}
   */
  get lenses() {
    return this._lenses.map(copyLens);
  }

  /**
   * Adds a circle lens (source pixels) and selects it.
   * @param {number} cx @param {number} cy centre, inside the picture
   * @param {number} r radius, > 0
   * @param {number} [zoom=2] in [1, 8]
   * @returns {number} its index
   */
  addCircle(cx, cy, r, zoom = 2) {
    this._needPicture('addCircle');
    finite(cx, 'cx'), finite(cy, 'cy'), finite(r, 'r'), finite(zoom, 'zoom');
    if (!(r > 0)) throw new RangeError(`GeolensView.addCircle: r must be > 0, got ${r}`);
    this._checkZoom(zoom, 'addCircle');
    this._checkInside([cx, cy], 'addCircle: the centre');
    return this._add({ kind: 'circle', cx, cy, r, zoom });
  }

  /**
   * Adds a polygon lens (source pixels) and selects it.
   * @param {Array} points its vertices: [[x, y], ...], [{x, y}, ...] or [x0, y0, x1, y1, ...],
   *   at least 3, inside the picture
   * @param {number} [zoom=2] in [1, 8]
   * @returns {number} its index
   */
  addPolygon(points, zoom = 2) {
    this._needPicture('addPolygon');
    const flat = flatPoints(points);
    flat.forEach((v, i) => finite(v, `points[${i}]`));
    finite(zoom, 'zoom');
    if (flat.length % 2 !== 0 || flat.length < 6)
      throw new RangeError('GeolensView.addPolygon: a polygon needs at least 3 vertices');
    this._checkZoom(zoom, 'addPolygon');
    this._checkInside(flat, 'addPolygon: a vertex');
    return this._add({ kind: 'polygon', points: flat, zoom });
  }

  /**
   * Changes lens `index`: any of zoom, footprint (0: the default), profile, cx, cy, r, points.
   * @param {number} index
   * @param {object} changes
   * @param {{moving?: boolean}} [how] moving: one of a stream of changes (a slider dragged):
   *   drafts, then the full mesh once the changes rest, as a drag does
   */
  setLens(index, changes, how = {}) {
    this._checkIndex(index, 'setLens');
    const lens = { ...copyLens(this._lenses[index]), ...changes };
    if (changes.points) lens.points = flatPoints(changes.points);
    if ('zoom' in changes) this._checkZoom(finite(changes.zoom, 'zoom'), 'setLens');
    if (lens.kind === 'circle') this._checkInside([lens.cx, lens.cy], 'setLens: the centre');
    else this._checkInside(lens.points, 'setLens: a vertex');
    this._lenses[index] = lens;
    this._wantSolve(Boolean(how.moving));
    this._changed('lens');
  }

  /**
   * Removes lens `index` (the selection is cleared).
   * @param {number} index
   */
  removeLens(index) {
    this._checkIndex(index, 'removeLens');
    this._lenses.splice(index, 1);
    this._drag = this._pinch = null;
    this._selected = -1;
    this._wantSolve(false);
    this._changed('remove');
  }

  /** The selected lens's index, -1 for none; settable. */
  get selectedIndex() {
    return this._selected;
  }

  set selectedIndex(index) {
    const next = Number.isInteger(index) && index >= 0 && index < this._lenses.length ? index : -1;
    if (next === this._selected) return;
    this._selected = next;
    this._needsDraw = true;
    this._schedule();
    this._changed('select');
  }

  /**
   * Starts drawing a polygon: each click (or tap) adds a vertex where it points in the source; a
   * double-click, Enter or a click on the first vertex closes it (a lens of `zoom`), Escape
   * cancels.
   * @param {number} [zoom=2]
   */
  drawPolygon(zoom = 2) {
    this._needPicture('drawPolygon');
    this._checkZoom(finite(zoom, 'zoom'), 'drawPolygon');
    this._drawing = { points: [], pointer: null, zoom, lastAt: 0 };
    this._drag = this._pinch = null;
    this._needsDraw = true;
    this._schedule();
    this._changed('mode');
  }

  /**
   * Closes the polygon being drawn (a lens if it has 3 vertices or more).
   * @returns {number} the new lens's index, or -1
   */
  finishPolygon() {
    const drawing = this._drawing;
    if (!drawing) return -1;
    this._drawing = null;
    this._needsDraw = true;
    this._schedule();
    let index = -1;
    if (drawing.points.length >= 6 && polygonArea(drawing.points) > 1)
      index = this._add({ kind: 'polygon', points: drawing.points, zoom: drawing.zoom });
    this._changed('mode');
    return index;
  }

  /** Stops drawing a polygon without adding it. */
  cancelPolygon() {
    if (!this._drawing) return;
    this._drawing = null;
    this._needsDraw = true;
    this._schedule();
    this._changed('mode');
  }

  /** 'polygon' while a polygon is being drawn, else 'idle'. */
  get mode() {
    return this._drawing ? 'polygon' : 'idle';
  }

  // ---------------------------------------------------------------------------------------------
  // Options, frames, picking

  /**
   * Sets options. The view's: restDelay (ms, 150), outlines (true), background ([r, g, b, a] in
   * [0, 1]), autoResize (true), interactive (true), onFrame (a callback). Every other is the
   * engine's, camelCase or as the library names it: model ('focus', 'lift', 'field', 'auto'),
   * mesh (100), draftMesh (30), meshTolerance, ...; changing them starts a new session (the
   * lenses stay).
   * @param {object} options
   */
  setOptions(options = {}) {
    this._checkAlive('setOptions');
    let engineChanged = false;
    const engineOptions = { ...this._engineOptions };
    for (const [key, value] of Object.entries(options)) {
      if (key === 'worker') {
        if (Boolean(value) !== Boolean(this._solver))
          throw new TypeError('GeolensView.setOptions: worker is set by the constructor only');
      } else if (key in VIEW_DEFAULTS) {
        this._view[key] = value;
      } else {
        const name = snakeCase(key);
        if (engineOptions[name] !== value) engineChanged = true;
        if (value === undefined || value === null) delete engineOptions[name];
        else engineOptions[name] = value;
      }
    }
    this._listenResize();
    if (engineChanged && this._width > 0) {
      // Throws the engine's error (InvalidOption) and keeps the session when they are refused.
      this._newSession(this._width, this._height, engineOptions);
      this._changed('options');
    }
    this._engineOptions = engineOptions;
    this._needsDraw = true;
    this._schedule();
  }

  /** The options as set: the view's and the engine's (as the library names them). */
  get options() {
    return { ...this._view, ...this._engineOptions };
  }

  /**
   * The last frame's figures, null before the first: {lenses: [{zoomAsked, zoomGot, zoomFit,
   * reason}], warnings: [text], draft, model, solveMs, shapeMean, shapeMax, flipped,
   * vertexCount, triangleCount}. shapeMean and shapeMax: the warp's shape distortion as the
   * library measures it (s1 / s2 - 1 of each triangle's map from source to frame: 0 where shape
   * is kept; the mean weighted by source area), flipped: triangles turned over.
   */
  get frame() {
    return this._frame;
  }

  /**
   * The source point shown under a point of the canvas.
   * @param {number} x @param {number} y CSS pixels from the canvas's top-left corner
   * @returns {{x: number, y: number}|null} source pixels, or null off the picture
   */
  pick(x, y) {
    if (!this._session || !this._frame) return null;
    const at = this.toFrame(x, y);
    const out = this._session.inverse(new Float64Array([at.x, at.y]));
    return Number.isNaN(out[0]) || Number.isNaN(out[1]) ? null : { x: out[0], y: out[1] };
  }

  /**
   * Where the warp shows a source point, in CSS pixels of the canvas.
   * @param {number} x @param {number} y source pixels
   * @returns {{x: number, y: number}|null} null where the warp does not reach
   */
  project(x, y) {
    if (!this._session || !this._frame) return null;
    const out = this._session.forward(new Float64Array([x, y]));
    if (Number.isNaN(out[0]) || Number.isNaN(out[1])) return null;
    const { scale, ox, oy, cssPerDevice } = this._placement();
    return { x: (ox + out[0] * scale) * cssPerDevice, y: (oy + out[1] * scale) * cssPerDevice };
  }

  /**
   * A canvas point (CSS pixels) in frame pixels (the picture's frame, where the warp puts
   * things); no lens involved.
   * @returns {{x: number, y: number}}
   */
  toFrame(x, y) {
    const { scale, ox, oy, cssPerDevice } = this._placement();
    return { x: (x / cssPerDevice - ox) / scale, y: (y / cssPerDevice - oy) / scale };
  }

  /**
   * Resolves once no solve is waiting (the full mesh shown, not a draft) and the canvas is drawn.
   * @returns {Promise<void>}
   */
  idle() {
    if (this._isIdle()) return Promise.resolve();
    return new Promise((resolve) => {
      this._idleWaiters.push(resolve);
      this._schedule();
    });
  }

  /**
   * Solves what waits and draws now, then reads the canvas back: device pixels, RGBA, top row
   * first (premultiplied by alpha where the picture has any). In worker mode it draws the last
   * frame solved (the solve it asks for comes later): await idle() first.
   * @returns {{width: number, height: number, data: Uint8Array}}
   */
  readPixels() {
    this._checkAlive('readPixels');
    if (this._solveWanted) this._solve();
    this._draw();
    const gl = this._gl, width = gl.drawingBufferWidth, height = gl.drawingBufferHeight;
    const raw = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, raw);
    const data = new Uint8Array(raw.length), row = width * 4;
    for (let y = 0; y < height; ++y)
      data.set(raw.subarray((height - 1 - y) * row, (height - y) * row), y * row);
    return { width, height, data };
  }

  /** Frees the session, the GL resources and the listeners; the view is unusable after. */
  dispose() {
    if (this._disposed) return;
    this._disposed = true;
    if (this._raf) cancelAnimationFrame(this._raf);
    clearTimeout(this._restTimer);
    this._stopVideo();
    for (const [target, type, handler] of this._handlers) target.removeEventListener(type, handler);
    this._handlers = [];
    if (this._resizeObserver) this._resizeObserver.disconnect();
    if (this._session) this._session.dispose();
    this._session = null;
    if (this._solver) {
      this._solver.worker.terminate();
      this._solver.inFlight = this._solver.waiting = null;
    }
    const gl = this._gl;
    if (!gl.isContextLost()) {
      gl.deleteTexture(this._texture);
      gl.deleteBuffer(this._meshBuffer);
      gl.deleteBuffer(this._strokeBuffer);
      gl.deleteVertexArray(this._meshVao);
      gl.deleteVertexArray(this._strokeVao);
      gl.deleteProgram(this._meshProgram);
      gl.deleteProgram(this._strokeProgram);
    }
    for (const resolve of this._idleWaiters) resolve();
    this._idleWaiters = [];
  }

  // ---------------------------------------------------------------------------------------------
  // Checks and bookkeeping

  _checkAlive(what) {
    if (this._disposed) throw new Error(`GeolensView.${what}: the view is disposed`);
  }

  _needPicture(what) {
    this._checkAlive(what);
    if (!this._session) throw new Error(`GeolensView.${what}: no picture yet (setImage first)`);
  }

  _checkIndex(index, what) {
    this._checkAlive(what);
    if (!Number.isInteger(index) || index < 0 || index >= this._lenses.length)
      throw new RangeError(
        `GeolensView.${what}: no lens ${index} (there are ${this._lenses.length})`,
      );
  }

  _checkZoom(zoom, what) {
    if (!(zoom >= ZOOM_MIN && zoom <= ZOOM_MAX))
      throw new RangeError(`GeolensView.${what}: zoom must be in [1, 8], got ${zoom}`);
  }

  _checkInside(flat, what) {
    for (let i = 0; i < flat.length; i += 2) {
      const x = flat[i], y = flat[i + 1];
      if (!(x >= 0 && x <= this._width && y >= 0 && y <= this._height))
        throw new RangeError(
          `GeolensView.${what} (${x}, ${y}) is outside the ${this._width}x${this._height} picture`,
        );
    }
  }

  _add(lens) {
    this._lenses.push(lens);
    this._selected = this._lenses.length - 1;
    this._wantSolve(false);
    this._changed('add');
    return this._selected;
  }

  _changed(reason) {
    this.dispatchEvent(new CustomEvent('change', { detail: { reason } }));
  }

  // A session on a width x height picture with `engineOptions`; if the engine refuses them, it
  // throws and the view keeps the session it had.
  _newSession(width, height, engineOptions) {
    const session = this._solver
      ? this._askSession(width, height, engineOptions)
      : this.engine.session({ width, height, ...engineOptions });
    if (this._session) this._session.dispose();
    this._session = session;
    this._width = width;
    this._height = height;
    this._frame = null;
    this._wantSolve(false);
  }

  // A solve is wanted: a draft when `moving` (then the full mesh once the lens rests).
  _wantSolve(moving) {
    this._solveWanted = true;
    clearTimeout(this._restTimer);
    this._moving = moving;
    if (moving) this._restTimer = setTimeout(() => this._rest(), this._view.restDelay);
    this._schedule();
  }

  // The lens rests: the full mesh, unless the last frame was already one.
  _rest() {
    clearTimeout(this._restTimer);
    this._restTimer = 0;
    if (!this._moving) return;
    this._moving = false;
    if (this._solveWanted || (this._frame && this._frame.draft)) this._solveWanted = true;
    this._schedule();
  }

  _isIdle() {
    if (this._disposed || !this._session) return true;
    const draftShown = this._frame !== null && this._frame.draft;
    const solving = this._solver !== null &&
      (this._solver.inFlight !== null || this._solver.waiting !== null);
    return !this._solveWanted && !this._moving && !this._needsDraw && !this._textureDirty &&
      !draftShown && !solving;
  }

  _schedule() {
    if (this._raf || this._disposed) return;
    this._raf = requestAnimationFrame(() => this._animationFrame());
  }

  _animationFrame() {
    this._raf = 0;
    if (this._disposed) return;
    if (this._solveWanted) this._solve();
    if (this._textureDirty) this._upload();
    if (this._needsDraw) this._draw();
    if (this._hover) this._updateCursor();
    if (this._isIdle()) {
      const waiters = this._idleWaiters;
      this._idleWaiters = [];
      for (const resolve of waiters) resolve();
    }
  }

  // ---------------------------------------------------------------------------------------------
  // The solve

  _solve() {
    this._solveWanted = false;
    if (!this._session) return;
    const draft = this._moving;
    const lenses = this._lenses.map(copyLens);
    if (this._solver) {
      this._solveInWorker(lenses, draft);
      return;
    }
    const start = performance.now();
    let frame;
    try {
      frame = this._session.update(lenses, draft);
    } catch (error) {
      this._solveFailed(error);
      return;
    }
    const solveMs = performance.now() - start;
    this._showFrame(lenses, frame, solveMs,
      () => lenses.map((lens) => this._session.forward(boundaryPoints(lens))));
  }

  // A solve failed: back to the lenses of the frame shown; the session keeps that frame.
  _solveFailed(error) {
    this._lenses = this._good.map(copyLens);
    if (this._selected >= this._lenses.length) this._selected = -1;
    this._drag = this._pinch = null;
    this._moving = false;
    if (this._frame && this._frame.draft) this._solveWanted = true;
    this.dispatchEvent(new CustomEvent('error', { detail: { error } }));
    this._changed('error');
  }

  // A solved frame of `lenses` shown: the GPU's mesh, the outlines (frame points, by
  // outlines()), the figures, the 'frame' event.
  _showFrame(lenses, frame, solveMs, outlines) {
    // (The worker sends both made.)
    const shape = frame.shape || shapeDistortion(frame.texcoords, frame.positions,
      frame.triangles);
    // The views die with the next update: the GPU's copy is made now (and kept for a lost
    // context).
    this._mesh = frame.mesh || gpuMesh(frame);
    this._uploadMesh();
    this._good = lenses;
    this._outlines = outlines();
    this._frame = {
      lenses: frame.lenses,
      warnings: frame.warnings,
      draft: frame.draft,
      model: frame.model,
      solveMs,
      shapeMean: shape.mean,
      shapeMax: shape.max,
      flipped: shape.flipped,
      vertexCount: frame.vertexCount,
      triangleCount: frame.triangleCount,
    };
    this._needsDraw = true;
    const detail = this._frame;
    if (typeof this._view.onFrame === 'function') this._view.onFrame(detail);
    this.dispatchEvent(new CustomEvent('frame', { detail }));
  }

  // ---------------------------------------------------------------------------------------------
  // Worker mode: the solve in solver_worker.js

  _startWorker(url) {
    const script = url === true ? new URL('./solver_worker.js', import.meta.url) : url;
    const worker = new Worker(script, { type: 'module' });
    this._solver = {
      worker,
      nextId: 0,
      generation: 0, // one per session asked for; replies of an older one are not shown
      inFlight: null, // the update the worker is solving: {id, lenses, draft, generation}
      waiting: null, // the newest lens state asked for meanwhile (it replaces older ones)
      sessionOptions: null, // the engine options of the last session the worker made
    };
    worker.addEventListener('message', (e) => this._onWorkerMessage(e.data));
    worker.addEventListener('error', (e) => {
      e.preventDefault();
      this._onWorkerMessage({
        type: 'error',
        id: this._solver.inFlight ? this._solver.inFlight.id : -1,
        request: 'update',
        error: { name: 'Error', message: `GeolensView: the solver worker failed: ${e.message}` },
      });
    });
  }

  // Asks the worker for a session; returns the page's stand-in for it (pick and project from the
  // last frame's mesh).
  _askSession(width, height, engineOptions) {
    const s = this._solver;
    s.generation += 1;
    s.waiting = null;
    s.sessionOptions = s.sessionOptions || { ...engineOptions };
    const id = ++s.nextId;
    s.sessionAsked = { id, options: { ...engineOptions } };
    s.worker.postMessage({ type: 'session', id, width, height, options: engineOptions });
    return new LocatedSession();
  }

  _solveInWorker(lenses, draft) {
    const s = this._solver;
    const request = { lenses, draft, generation: s.generation };
    if (s.inFlight) s.waiting = request;
    else this._postUpdate(request);
  }

  _postUpdate(request) {
    const s = this._solver;
    request.id = ++s.nextId;
    s.inFlight = request;
    s.worker.postMessage({
      type: 'update',
      id: request.id,
      lenses: request.lenses,
      draft: request.draft,
      outlines: request.lenses.map(boundaryPoints),
    });
  }

  _onWorkerMessage(message) {
    const s = this._solver;
    if (this._disposed || !s) return;
    const error = () => Object.assign(new Error(message.error.message), {
      name: message.error.name,
    });
    if (message.type === 'session') {
      if (s.sessionAsked && s.sessionAsked.id === message.id)
        s.sessionOptions = s.sessionAsked.options;
      return;
    }
    if (message.type === 'error' && message.request === 'session') {
      // The worker keeps the session it had: so do the options.
      if (s.sessionOptions) this._engineOptions = { ...s.sessionOptions };
      this.dispatchEvent(new CustomEvent('error', { detail: { error: error() } }));
      this._changed('error');
      return;
    }
    const request = s.inFlight;
    if (!request || request.id !== message.id) return;
    s.inFlight = null;
    const current = request.generation === s.generation;
    if (message.type === 'error') {
      if (current) {
        s.waiting = null;
        this._solveFailed(error());
      }
    } else if (message.type === 'frame' && current) {
      this._session.locator = new MeshLocator(message.positions, message.texcoords,
        message.triangles);
      this._showFrame(request.lenses, message, message.solveMs, () => message.outlines);
    }
    if (s.waiting) {
      const next = s.waiting;
      s.waiting = null;
      if (next.generation === s.generation) this._postUpdate(next);
    }
    // A draft shown once the lens rests, nothing more asked: the full mesh.
    if (!s.inFlight && !this._moving && this._frame && this._frame.draft) this._solveWanted = true;
    this._schedule();
  }

  // ---------------------------------------------------------------------------------------------
  // WebGL

  _initGL() {
    const gl = this.canvas.getContext('webgl2', {
      alpha: true,
      premultipliedAlpha: true,
      antialias: false,
      depth: false,
      stencil: false,
    });
    if (!gl) throw new Error('GeolensView: this browser has no WebGL2');
    this._gl = gl;
    this._meshProgram = compileProgram(gl, MESH_VERTEX, MESH_FRAGMENT);
    this._draftProgram = compileProgram(gl, DRAFT_VERTEX, DRAFT_FRAGMENT);
    this._strokeProgram = compileProgram(gl, STROKE_VERTEX, STROKE_FRAGMENT);
    const mp = this._meshProgram, dp = this._draftProgram, sp = this._strokeProgram;
    this._loc = {
      scale: gl.getUniformLocation(mp, 'u_scale'),
      offset: gl.getUniformLocation(mp, 'u_offset'),
      picture: gl.getUniformLocation(mp, 'u_picture'),
      size: gl.getUniformLocation(mp, 'u_size'),
      placeScale: gl.getUniformLocation(mp, 'u_placeScale'),
      placeOffset: gl.getUniformLocation(mp, 'u_placeOffset'),
      height: gl.getUniformLocation(mp, 'u_height'),
      draftScale: gl.getUniformLocation(dp, 'u_scale'),
      draftOffset: gl.getUniformLocation(dp, 'u_offset'),
      draftSize: gl.getUniformLocation(dp, 'u_size'),
      draftPicture: gl.getUniformLocation(dp, 'u_picture'),
      strokePosition: gl.getAttribLocation(sp, 'a_position'),
      strokeAcross: gl.getAttribLocation(sp, 'a_across'),
      viewport: gl.getUniformLocation(sp, 'u_viewport'),
      color: gl.getUniformLocation(sp, 'u_color'),
      half: gl.getUniformLocation(sp, 'u_half'),
    };
    this._meshBuffer = gl.createBuffer();
    this._strokeBuffer = gl.createBuffer();
    this._meshVao = gl.createVertexArray();
    gl.bindVertexArray(this._meshVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this._meshBuffer);
    let offset = 0;
    for (const [name, size] of [
      ['a_position', 2], ['a_origin', 2], ['a_source', 2], ['a_jacobian', 4], ['a_sigma', 1],
    ]) {
      const location = gl.getAttribLocation(mp, name);
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, size, gl.FLOAT, false, 4 * MESH_FLOATS, 4 * offset);
      offset += size;
    }
    this._draftBuffer = gl.createBuffer();
    this._draftIndexBuffer = gl.createBuffer();
    this._draftVao = gl.createVertexArray();
    gl.bindVertexArray(this._draftVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this._draftBuffer);
    for (const [name, offset] of [['a_position', 0], ['a_source', 2]]) {
      const location = gl.getAttribLocation(dp, name);
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, 2, gl.FLOAT, false, 4 * DRAFT_FLOATS, 4 * offset);
    }
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this._draftIndexBuffer);
    // Drafts sample the nearest mipmap level, not a blend of two (where the ring compresses).
    this._draftSampler = gl.createSampler();
    gl.samplerParameteri(this._draftSampler, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_NEAREST);
    gl.samplerParameteri(this._draftSampler, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.samplerParameteri(this._draftSampler, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.samplerParameteri(this._draftSampler, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    this._strokeVao = gl.createVertexArray();
    gl.bindVertexArray(this._strokeVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this._strokeBuffer);
    gl.enableVertexAttribArray(this._loc.strokePosition);
    gl.vertexAttribPointer(this._loc.strokePosition, 2, gl.FLOAT, false, 12, 0);
    gl.enableVertexAttribArray(this._loc.strokeAcross);
    gl.vertexAttribPointer(this._loc.strokeAcross, 1, gl.FLOAT, false, 12, 8);
    gl.bindVertexArray(null);
    this._texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this._texture);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    this._textureSize = null;
  }

  // The picture into the texture, with its mipmaps.
  _upload() {
    this._textureDirty = false;
    const gl = this._gl, source = this._source;
    if (!source || gl.isContextLost()) return;
    const [width, height] = pictureSize(source);
    gl.bindTexture(gl.TEXTURE_2D, this._texture);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, true);
    const size = this._textureSize;
    if (size && size[0] === width && size[1] === height) {
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, gl.RGBA, gl.UNSIGNED_BYTE, source);
    } else {
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, source);
      this._textureSize = [width, height];
    }
    gl.generateMipmap(gl.TEXTURE_2D);
    this._needsDraw = true;
  }

  _uploadMesh() {
    const gl = this._gl, mesh = this._mesh;
    if (!mesh || gl.isContextLost()) return;
    if (mesh.indices) {
      gl.bindVertexArray(this._draftVao);
      gl.bindBuffer(gl.ARRAY_BUFFER, this._draftBuffer);
      gl.bufferData(gl.ARRAY_BUFFER, mesh.vertices, gl.DYNAMIC_DRAW);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, mesh.indices, gl.DYNAMIC_DRAW);
      gl.bindVertexArray(null);
      return;
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, this._meshBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, mesh.vertices, gl.DYNAMIC_DRAW);
  }

  // The picture's place on the canvas: frame point p at device pixel (ox, oy) + p * scale.
  _placement() {
    const canvas = this.canvas;
    const deviceWidth = canvas.width, deviceHeight = canvas.height;
    const cssWidth = canvas.clientWidth || deviceWidth;
    const cssPerDevice = cssWidth / deviceWidth;
    if (!(this._width > 0))
      return { scale: 1, ox: 0, oy: 0, cssPerDevice, deviceWidth, deviceHeight };
    const scale = Math.min(deviceWidth / this._width, deviceHeight / this._height);
    const ox = Math.round((deviceWidth - this._width * scale) / 2);
    const oy = Math.round((deviceHeight - this._height * scale) / 2);
    return { scale, ox, oy, cssPerDevice, deviceWidth, deviceHeight };
  }

  _draw() {
    this._needsDraw = false;
    const gl = this._gl;
    if (gl.isContextLost()) return;
    const { scale, ox, oy, deviceWidth: W, deviceHeight: H } = this._placement();
    gl.viewport(0, 0, W, H);
    const [r, g, b, a] = this._view.background;
    gl.disable(gl.BLEND);
    gl.clearColor(r * a, g * a, b * a, a);
    gl.clear(gl.COLOR_BUFFER_BIT);
    if (!this._mesh || !this._source) return;
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this._texture);
    const mesh = this._mesh, loc = this._loc;
    if (mesh.indices) {
      gl.useProgram(this._draftProgram);
      gl.uniform2f(loc.draftScale, (2 * scale) / W, (-2 * scale) / H);
      gl.uniform2f(loc.draftOffset, (2 * ox) / W - 1, 1 - (2 * oy) / H);
      gl.uniform2f(loc.draftSize, this._width, this._height);
      gl.uniform1i(loc.draftPicture, 0);
      gl.bindSampler(0, this._draftSampler);
      gl.bindVertexArray(this._draftVao);
      gl.drawElements(gl.TRIANGLES, mesh.count, gl.UNSIGNED_INT, 0);
      gl.bindVertexArray(null);
      gl.bindSampler(0, null);
      this._drawOutlines(scale, ox, oy, W, H);
      return;
    }
    gl.useProgram(this._meshProgram);
    gl.uniform2f(this._loc.scale, (2 * scale) / W, (-2 * scale) / H);
    gl.uniform2f(this._loc.offset, (2 * ox) / W - 1, 1 - (2 * oy) / H);
    gl.uniform2f(this._loc.size, this._width, this._height);
    gl.uniform1f(this._loc.placeScale, scale);
    gl.uniform2f(this._loc.placeOffset, ox, oy);
    gl.uniform1f(this._loc.height, H);
    gl.uniform1i(this._loc.picture, 0);
    gl.bindVertexArray(this._meshVao);
    gl.drawArrays(gl.TRIANGLES, 0, this._mesh.count);
    gl.bindVertexArray(null);
    this._drawOutlines(scale, ox, oy, W, H);
  }

  _drawOutlines(scale, ox, oy, W, H) {
    const dpr = (this.canvas.width / (this.canvas.clientWidth || this.canvas.width)) || 1;
    const toDevice = (flat) => {
      const out = new Float64Array(flat.length);
      for (let i = 0; i < flat.length; ++i) out[i] = (i % 2 === 0 ? ox : oy) + flat[i] * scale;
      return out;
    };
    const strokes = []; // [points (device, flat), closed, halfWidth, color]
    // Opaque colours: the quads overlap at the joins, where a translucent stroke would darken.
    const halo = [0.08, 0.08, 0.08, 1], cyan = [0.2, 0.9, 1, 1];
    if (this._view.outlines) {
      this._outlines.forEach((frame, i) => {
        const selected = i === this._selected;
        const points = toDevice(frame);
        strokes.push([points, true, (selected ? 2.75 : 2) * dpr, halo]);
        strokes.push([points, true, (selected ? 1.75 : 1.2) * dpr,
          selected ? [1, 0.7, 0.1, 1] : [1, 1, 1, 1]]);
      });
    }
    if (this._drawing && this._session) {
      const d = this._drawing;
      let frame = d.points.length > 0 ? Array.from(this._session.forward(d.points)) : [];
      if (d.pointer) frame = frame.concat([d.pointer.x, d.pointer.y]);
      const points = toDevice(frame);
      strokes.push([points, false, 2 * dpr, halo]);
      strokes.push([points, false, 1 * dpr, cyan]);
      for (let i = 0; i < d.points.length; i += 2) {
        const dot = [points[i], points[i + 1], points[i] + 0.01, points[i + 1]];
        strokes.push([dot, false, 4 * dpr, halo]);
        strokes.push([dot, false, 2.5 * dpr, cyan]);
      }
    }
    if (strokes.length === 0) return;
    const gl = this._gl;
    gl.useProgram(this._strokeProgram);
    gl.uniform2f(this._loc.viewport, W, H);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
    gl.bindVertexArray(this._strokeVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this._strokeBuffer);
    for (const [points, closed, half, color] of strokes) {
      const data = strokeQuads(points, closed, half);
      if (data.length === 0) continue;
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STREAM_DRAW);
      gl.uniform4fv(this._loc.color, color);
      gl.uniform1f(this._loc.half, half);
      gl.drawArrays(gl.TRIANGLES, 0, data.length / 3);
    }
    gl.bindVertexArray(null);
    gl.disable(gl.BLEND);
  }

  _onContextRestored() {
    this._initGL();
    this._textureSize = null;
    this._upload();
    this._uploadMesh();
    this._needsDraw = true;
    this._schedule();
  }

  // ---------------------------------------------------------------------------------------------
  // Video

  _startVideo(video) {
    const loop = { video, handle: 0, stopped: false };
    const frameReady = () => {
      if (loop.stopped) return;
      loop.handle = 0;
      this._textureDirty = true;
      this._schedule();
      if (!video.paused && !video.ended) request();
    };
    const request = () => {
      if (loop.stopped || loop.handle) return;
      loop.handle =
        typeof video.requestVideoFrameCallback === 'function'
          ? video.requestVideoFrameCallback(frameReady)
          : requestAnimationFrame(frameReady);
    };
    loop.events = ['play', 'seeked', 'loadeddata'].map((type) => {
      const handler = () => frameReady();
      video.addEventListener(type, handler);
      return [type, handler];
    });
    loop.request = request;
    this._videoLoop = loop;
    if (!video.paused) request();
  }

  _stopVideo() {
    const loop = this._videoLoop;
    if (!loop) return;
    loop.stopped = true;
    for (const [type, handler] of loop.events) loop.video.removeEventListener(type, handler);
    this._videoLoop = null;
  }

  // ---------------------------------------------------------------------------------------------
  // Input

  _on(target, type, handler, options) {
    target.addEventListener(type, handler, options);
    this._handlers.push([target, type, handler]);
  }

  _listen() {
    this._handlers = [];
    const canvas = this.canvas;
    canvas.style.touchAction = 'none';
    canvas.style.userSelect = 'none';
    if (!canvas.hasAttribute('tabindex')) canvas.tabIndex = 0;
    this._on(canvas, 'webglcontextlost', (e) => e.preventDefault());
    this._on(canvas, 'webglcontextrestored', () => this._onContextRestored());
    this._on(canvas, 'pointerdown', (e) => this._interactive() && this._pointerDown(e));
    this._on(canvas, 'pointermove', (e) => this._interactive() && this._pointerMove(e));
    this._on(canvas, 'pointerup', (e) => this._pointerUp(e));
    this._on(canvas, 'pointercancel', (e) => this._pointerUp(e));
    this._on(canvas, 'dblclick', (e) => {
      if (this._interactive() && this._drawing) e.preventDefault(), this.finishPolygon();
    });
    this._on(canvas, 'wheel', (e) => this._interactive() && this._wheel(e), { passive: false });
    this._on(canvas, 'keydown', (e) => this._interactive() && this._key(e));
  }

  _listenResize() {
    const want = Boolean(this._view.autoResize) && typeof ResizeObserver !== 'undefined';
    if (want && !this._resizeObserver) {
      this._resizeObserver = new ResizeObserver(() => this._resize());
      this._resizeObserver.observe(this.canvas);
      this._resize();
    } else if (!want && this._resizeObserver) {
      this._resizeObserver.disconnect();
      this._resizeObserver = null;
    }
  }

  _resize() {
    const canvas = this.canvas, dpr = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(canvas.clientWidth * dpr));
    const height = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.clientWidth === 0 || (canvas.width === width && canvas.height === height)) return;
    canvas.width = width;
    canvas.height = height;
    this._needsDraw = true;
    this._schedule();
  }

  _interactive() {
    return this._view.interactive && !this._disposed && this._session !== null;
  }

  _cssPoint(e) {
    const rect = this.canvas.getBoundingClientRect();
    return { x: e.clientX - rect.left, y: e.clientY - rect.top };
  }

  // The lens under a canvas point: the smallest whose region holds the source point shown there.
  _lensAt(x, y) {
    const p = this.pick(x, y);
    if (!p) return -1;
    let best = -1;
    this._lenses.forEach((lens, i) => {
      const smaller = best < 0 || lensArea(lens) < lensArea(this._lenses[best]);
      if (smaller && lensContains(lens, p.x, p.y)) best = i;
    });
    return best;
  }

  _pointerDown(e) {
    if (e.pointerType === 'mouse' && e.button !== 0) return;
    const at = this._cssPoint(e);
    this._pointers.set(e.pointerId, at);
    this.canvas.focus({ preventScroll: true });
    try {
      this.canvas.setPointerCapture(e.pointerId);
    } catch {
      // a synthetic pointer has no capture; the view works without
    }
    e.preventDefault();
    if (this._drawing) {
      if (this._pointers.size === 1) this._polygonClick(at);
      return;
    }
    const closed = this._closedAt;
    this._closedAt = null;
    if (closed && performance.now() - closed.time < 600 &&
        Math.hypot(at.x - closed.x, at.y - closed.y) <= 6) return;
    if (this._pointers.size === 2) {
      this._startPinch();
      return;
    }
    if (this._pointers.size > 2) return;
    const index = this._lensAt(at.x, at.y);
    this.selectedIndex = index;
    if (index >= 0) {
      const from = this.toFrame(at.x, at.y);
      this._drag = { index, fromX: from.x, fromY: from.y, lens: copyLens(this._lenses[index]) };
    }
  }

  _startPinch() {
    this._drag = null;
    const [a, b] = [...this._pointers.values()];
    let index = this._lensAt((a.x + b.x) / 2, (a.y + b.y) / 2);
    if (index < 0) index = this._selected;
    if (index < 0) index = this._lensAt(a.x, a.y);
    if (index < 0) return;
    this.selectedIndex = index;
    this._pinch = {
      index,
      distance: Math.max(1, Math.hypot(a.x - b.x, a.y - b.y)),
      zoom: this._lenses[index].zoom,
    };
  }

  // The cursor for the pointer's last place (hovering), set in the animation frame.
  _updateCursor() {
    const at = this._hover;
    this._hover = null;
    let cursor = '';
    if (this._drawing) cursor = 'crosshair';
    else if (this._drag) cursor = 'grabbing';
    else if (this._lensAt(at.x, at.y) >= 0) cursor = 'grab';
    if (this.canvas.style.cursor !== cursor) this.canvas.style.cursor = cursor;
  }

  _pointerMove(e) {
    const at = this._cssPoint(e);
    if (this._pointers.has(e.pointerId)) this._pointers.set(e.pointerId, at);
    if (e.pointerType === 'mouse') {
      this._hover = at;
      this._schedule();
    }
    if (this._drawing) {
      this._drawing.pointer = this.toFrame(at.x, at.y);
      this._needsDraw = true;
      this._schedule();
      return;
    }
    if (this._pinch && this._pointers.size >= 2) {
      const [a, b] = [...this._pointers.values()];
      const zoom = clampZoom(this._pinch.zoom * (Math.hypot(a.x - b.x, a.y - b.y) /
        this._pinch.distance));
      const lens = this._lenses[this._pinch.index];
      if (lens && lens.zoom !== zoom) {
        lens.zoom = zoom;
        this._wantSolve(true);
        this._changed('zoom');
      }
      return;
    }
    if (!this._drag) return;
    const now = this.toFrame(at.x, at.y);
    const moved = this._translated(this._drag.lens, now.x - this._drag.fromX,
      now.y - this._drag.fromY);
    this._lenses[this._drag.index] = moved;
    this._wantSolve(true);
    this._changed('move');
  }

  // `lens` moved by (dx, dy) source pixels, its centre or vertices kept in the picture.
  _translated(lens, dx, dy) {
    const xs = [], ys = [];
    if (lens.kind === 'circle') {
      xs.push(lens.cx);
      ys.push(lens.cy);
    } else {
      lens.points.forEach((v, i) => (i % 2 === 0 ? xs : ys).push(v));
    }
    dx = Math.min(this._width - Math.max(...xs), Math.max(-Math.min(...xs), dx));
    dy = Math.min(this._height - Math.max(...ys), Math.max(-Math.min(...ys), dy));
    if (lens.kind === 'circle') return { ...lens, cx: lens.cx + dx, cy: lens.cy + dy };
    return { ...lens, points: lens.points.map((v, i) => v + (i % 2 === 0 ? dx : dy)) };
  }

  _pointerUp(e) {
    if (!this._pointers.delete(e.pointerId)) return;
    if (this._pinch && this._pointers.size < 2) this._pinch = null;
    if (this._pointers.size === 0) this._drag = null;
    else if (this._drag) this._drag = null;
    if (this._pointers.size === 0 && this._moving) this._rest();
  }

  _polygonClick(at) {
    const d = this._drawing;
    const p = this.pick(at.x, at.y);
    if (!p) return;
    const now = performance.now();
    const n = d.points.length;
    if (n >= 2) {
      // A second click on the last vertex (a double-click) or a click on the first closes it.
      const shown = this._session.forward(new Float64Array([d.points[0], d.points[1],
        d.points[n - 2], d.points[n - 1]]));
      const frame = this.toFrame(at.x, at.y);
      const near = (x, y) => Math.hypot(x - frame.x, y - frame.y) * this._placement().scale *
        this._placement().cssPerDevice <= 6;
      if ((n >= 6 && near(shown[0], shown[1])) || (near(shown[2], shown[3]) &&
          now - d.lastAt < 600)) {
        // The rest of a double-click is not a click on the picture.
        this._closedAt = { time: now, x: at.x, y: at.y };
        this.finishPolygon();
        return;
      }
    }
    d.points.push(p.x, p.y);
    d.lastAt = now;
    this._needsDraw = true;
    this._schedule();
    this._changed('vertex');
  }

  _wheel(e) {
    const at = this._cssPoint(e);
    const index = this._lensAt(at.x, at.y);
    if (index < 0) return;
    e.preventDefault();
    const pixels = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
    const lens = this._lenses[index];
    const zoom = clampZoom(lens.zoom * Math.exp(-pixels * 0.0015));
    this.selectedIndex = index;
    if (zoom === lens.zoom) return;
    lens.zoom = zoom;
    this._wantSolve(true);
    this._changed('zoom');
  }

  _key(e) {
    if (this._drawing) {
      if (e.key === 'Enter') e.preventDefault(), this.finishPolygon();
      else if (e.key === 'Escape') e.preventDefault(), this.cancelPolygon();
      else if (e.key === 'Backspace' && this._drawing.points.length > 0) {
        e.preventDefault();
        this._drawing.points.length -= 2;
        this._needsDraw = true;
        this._schedule();
      }
      return;
    }
    if ((e.key === 'Delete' || e.key === 'Backspace') && this._selected >= 0) {
      e.preventDefault();
      this.removeLens(this._selected);
    }
  }
}

// gpuMesh and shapeDistortion are exported for solver_worker.js (which makes both off the
// page's thread), not as the package's API.

// The page's stand-in for the worker's session (worker mode): forward and inverse from the last
// frame's mesh (NaN before the first).
class LocatedSession {
  constructor() {
    this.locator = null;
  }

  forward(points) {
    return this.locator ? this.locator.forward(points) : new Float64Array(points.length).fill(NaN);
  }

  inverse(points) {
    return this.locator ? this.locator.inverse(points) : new Float64Array(points.length).fill(NaN);
  }

  dispose() {
    this.locator = null;
  }
}

// The GPU's copy of a frame's warp: a draft's (draftVertices), else the exact one (meshVertices).
export function gpuMesh(frame) {
  const { positions, texcoords, triangles } = frame;
  return frame.draft ? draftVertices(positions, texcoords, triangles)
    : meshVertices(positions, texcoords, triangles);
}

// A draft's copy for the GPU: per vertex its frame position and source point (4 floats), and the
// triangles' vertex indices, drawn with interpolated texture coordinates.
export function draftVertices(positions, texcoords, triangles) {
  const n = positions.length / 2;
  const vertices = new Float32Array(n * DRAFT_FLOATS);
  for (let i = 0, k = 0; i < 2 * n; i += 2, k += DRAFT_FLOATS) {
    vertices[k] = positions[i];
    vertices[k + 1] = positions[i + 1];
    vertices[k + 2] = texcoords[i];
    vertices[k + 3] = texcoords[i + 1];
  }
  return { vertices, indices: new Uint32Array(triangles), count: triangles.length };
}

// The GPU's copy of a warp: three vertices per triangle (positions: frame pixels), each with the
// triangle's affine map from frame to source pixels (its first vertex, the source point there and
// the Jacobian J, source per frame pixel) and J's largest singular value; triangles of (nearly)
// no area in the frame are left out, as geolens's renderer leaves them.
export function meshVertices(positions, texcoords, triangles) {
  const out = new Float32Array((triangles.length / 3) * 3 * MESH_FLOATS);
  let n = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = 2 * triangles[t], b = 2 * triangles[t + 1], c = 2 * triangles[t + 2];
    const x0 = positions[a], y0 = positions[a + 1];
    const e1x = positions[b] - x0, e1y = positions[b + 1] - y0;
    const e2x = positions[c] - x0, e2y = positions[c + 1] - y0;
    const det = e1x * e2y - e1y * e2x;
    if (!(Math.abs(det) > 1e-10)) continue;
    const u0 = texcoords[a], v0 = texcoords[a + 1];
    const s1x = texcoords[b] - u0, s1y = texcoords[b + 1] - v0;
    const s2x = texcoords[c] - u0, s2y = texcoords[c + 1] - v0;
    // J = [source edges] [frame edges]^-1
    const j00 = (s1x * e2y - s2x * e1y) / det, j01 = (s2x * e1x - s1x * e2x) / det;
    const j10 = (s1y * e2y - s2y * e1y) / det, j11 = (s2y * e1x - s1y * e2x) / det;
    const sigma = 0.5 * (Math.hypot(j00 + j11, j10 - j01) + Math.hypot(j00 - j11, j10 + j01));
    for (const v of [a, b, c]) {
      out[n] = positions[v];
      out[n + 1] = positions[v + 1];
      out[n + 2] = x0;
      out[n + 3] = y0;
      out[n + 4] = u0;
      out[n + 5] = v0;
      out[n + 6] = j00;
      out[n + 7] = j01;
      out[n + 8] = j10;
      out[n + 9] = j11;
      out[n + 10] = sigma;
      n += MESH_FLOATS;
    }
  }
  return { vertices: out.subarray(0, n), count: n / MESH_FLOATS };
}

// The shape distortion of a warp: per triangle s1 / s2 - 1, s1 >= s2 the singular values of its
// affine map from source to frame (0 for a similarity), as geolens's measure/distortion.h
// defines it: the mean weighted by source area and the largest over the triangles not flipped,
// and the triangles flipped (det J <= 0, degenerate ones included).
export function shapeDistortion(source, frame, triangles) {
  let sum = 0, area = 0, max = 0, flipped = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = 2 * triangles[t], b = 2 * triangles[t + 1], c = 2 * triangles[t + 2];
    const s1x = source[b] - source[a], s1y = source[b + 1] - source[a + 1];
    const s2x = source[c] - source[a], s2y = source[c + 1] - source[a + 1];
    const f1x = frame[b] - frame[a], f1y = frame[b + 1] - frame[a + 1];
    const f2x = frame[c] - frame[a], f2y = frame[c + 1] - frame[a + 1];
    const det = s1x * s2y - s2x * s1y;
    if (det === 0) {
      ++flipped;
      continue;
    }
    // J = [frame edges] [source edges]^-1
    const j00 = (f1x * s2y - f2x * s1y) / det, j01 = (f2x * s1x - f1x * s2x) / det;
    const j10 = (f1y * s2y - f2y * s1y) / det, j11 = (f2y * s1x - f1y * s2x) / det;
    if (!(j00 * j11 - j01 * j10 > 0)) {
      ++flipped;
      continue;
    }
    const p = Math.hypot(j00 + j11, j10 - j01), q = Math.hypot(j00 - j11, j10 + j01);
    const shape = (p + q) / (p - q) - 1; // s1 / s2 - 1; p > q as det J > 0
    const weight = Math.abs(det) / 2;
    sum += shape * weight;
    area += weight;
    if (shape > max) max = shape;
  }
  return { mean: area > 0 ? sum / area : 0, max, flipped };
}

// Triangles (x, y, across per vertex) of a thick polyline through device points `flat`: a quad
// per segment, widened by a pixel for the smoothed edge and lengthened by the half width so that
// the joins overlap. NaN points break the line.
function strokeQuads(flat, closed, half) {
  const out = [];
  const n = flat.length / 2;
  const e = half + 1;
  const segments = closed ? n : n - 1;
  for (let s = 0; s < segments; ++s) {
    const i = 2 * s, j = 2 * ((s + 1) % n);
    const x0 = flat[i], y0 = flat[i + 1], x1 = flat[j], y1 = flat[j + 1];
    if (!Number.isFinite(x0 + y0 + x1 + y1)) continue;
    const length = Math.hypot(x1 - x0, y1 - y0);
    if (length === 0) continue;
    const dx = (x1 - x0) / length, dy = (y1 - y0) / length;
    const nx = -dy * e, ny = dx * e;
    const ax = x0 - dx * half, ay = y0 - dy * half, bx = x1 + dx * half, by = y1 + dy * half;
    out.push(
      ax + nx, ay + ny, e, ax - nx, ay - ny, -e, bx + nx, by + ny, e,
      bx + nx, by + ny, e, ax - nx, ay - ny, -e, bx - nx, by - ny, -e,
    );
  }
  return new Float32Array(out);
}

// MeshLocator: points mapped through a warp mesh in JS, forward (source -> screen) and inverse
// (screen -> source), as the engine's WarpMap (include/geolens/warp/warp_map.h) maps them.
//
//   import { MeshLocator } from './mesh_locator.js';
//   const map = new MeshLocator(frame.positions, frame.texcoords, frame.triangles);
//   map.inverse(new Float64Array([410, 300]));  // the source point under a screen point
//   map.forward([x0, y0, x1, y1]);               // where source points are shown
//
// GeolensView's worker mode answers pick() and project() with it on the page's thread, from the
// copy of the last frame the worker sent. The rules are WarpMap's, so that the answers equal the
// engine's (to rounding): per side a uniform grid of square buckets over the usable triangles'
// bounding boxes (widened by the edge tolerance), each bucket listing the triangles whose box
// meets it in ascending order; a point belongs to the first of its bucket's triangles whose
// barycentric coordinates are all >= -1e-9, and is interpolated there; no triangle: NaN.
// Triangles of (nearly) no area (|det| <= 2e-12 x longest edge^2) are never used. Each side's
// grid is built on its first query (O(#triangles)), as the engine builds its map on a frame's
// first pick.

const EDGE_TOLERANCE = 1e-9;
const BUCKET_SCALE = 1.0;

// One side's triangles (vertices `V`, flat x, y) bucketed on a uniform grid.
function buildSide(V, F) {
  const m = F.length / 3;
  // Per triangle: its first vertex and the inverse of [b - a, c - a] (row-major), or NaN.
  const locators = new Float64Array(6 * m).fill(NaN);
  const boxes = new Float64Array(4 * m); // minX, minY, maxX, maxY; usable[] says which are set
  const usable = new Uint8Array(m);
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  let area = 0, count = 0;
  for (let f = 0; f < m; ++f) {
    const a = 2 * F[3 * f], b = 2 * F[3 * f + 1], c = 2 * F[3 * f + 2];
    const ax = V[a], ay = V[a + 1], bx = V[b], by = V[b + 1], cx = V[c], cy = V[c + 1];
    const e1x = bx - ax, e1y = by - ay, e2x = cx - ax, e2y = cy - ay;
    const det = e1x * e2y - e1y * e2x;
    const longest2 = Math.max(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y,
      (cx - bx) * (cx - bx) + (cy - by) * (cy - by));
    if (!(Math.abs(det) > 2e-12 * longest2)) continue;
    const k = 6 * f;
    locators[k] = ax;
    locators[k + 1] = ay;
    locators[k + 2] = e2y / det;
    locators[k + 3] = -e2x / det;
    locators[k + 4] = -e1y / det;
    locators[k + 5] = e1x / det;
    const pad = 2 * EDGE_TOLERANCE * Math.sqrt(longest2);
    const x0 = Math.min(ax, bx, cx) - pad, y0 = Math.min(ay, by, cy) - pad;
    const x1 = Math.max(ax, bx, cx) + pad, y1 = Math.max(ay, by, cy) + pad;
    boxes[4 * f] = x0;
    boxes[4 * f + 1] = y0;
    boxes[4 * f + 2] = x1;
    boxes[4 * f + 3] = y1;
    usable[f] = 1;
    if (x0 < minX) minX = x0;
    if (y0 < minY) minY = y0;
    if (x1 > maxX) maxX = x1;
    if (y1 > maxY) maxY = y1;
    area += Math.abs(det) / 2;
    ++count;
  }
  const side = { locators, columns: 0, rows: 0, originX: 0, originY: 0, inverseSide: 0 };
  if (count === 0) return side;
  const width = maxX - minX, height = maxY - minY;
  const size = Math.max(BUCKET_SCALE * Math.sqrt(area / count),
    Math.sqrt((width * height) / (4 * count)), Math.max(width, height) / (4 * count));
  const inverseSide = 1 / size;
  const columns = Math.trunc(width * inverseSide) + 1;
  const rows = Math.trunc(height * inverseSide) + 1;
  const clamp = (v, hi) => Math.min(hi, Math.max(0, v));
  const ranges = new Int32Array(4 * m);
  const start = new Int32Array(columns * rows + 1);
  for (let f = 0; f < m; ++f) {
    if (!usable[f]) continue;
    const r = 4 * f;
    const c0 = clamp(Math.trunc((boxes[r] - minX) * inverseSide), columns - 1);
    const c1 = clamp(Math.trunc((boxes[r + 2] - minX) * inverseSide), columns - 1);
    const r0 = clamp(Math.trunc((boxes[r + 1] - minY) * inverseSide), rows - 1);
    const r1 = clamp(Math.trunc((boxes[r + 3] - minY) * inverseSide), rows - 1);
    ranges[r] = c0, ranges[r + 1] = c1, ranges[r + 2] = r0, ranges[r + 3] = r1;
    for (let y = r0; y <= r1; ++y) for (let x = c0; x <= c1; ++x) ++start[y * columns + x + 1];
  }
  for (let k = 1; k < start.length; ++k) start[k] += start[k - 1];
  const triangles = new Int32Array(start[start.length - 1]);
  const next = start.slice(0, start.length - 1);
  for (let f = 0; f < m; ++f) {
    if (!usable[f]) continue;
    const r = 4 * f;
    for (let y = ranges[r + 2]; y <= ranges[r + 3]; ++y)
      for (let x = ranges[r]; x <= ranges[r + 1]; ++x) triangles[next[y * columns + x]++] = f;
  }
  return { locators, columns, rows, originX: minX, originY: minY, inverseSide, start, triangles };
}

/**
 * The piecewise-linear map of a warp mesh and its inverse, located on uniform grids of buckets
 * (one per side, built on first use), as the engine's WarpMap: equal to session.forward() and
 * session.inverse() on the same frame to rounding.
 */
export class MeshLocator {
  /**
   * @param {ArrayLike<number>} positions screen x, y per vertex (pixels), flat
   * @param {ArrayLike<number>} texcoords source x, y per vertex (pixels), flat
   * @param {ArrayLike<number>} triangles three vertex indices per triangle
   */
  constructor(positions, texcoords, triangles) {
    if (positions.length !== texcoords.length || positions.length % 2 !== 0)
      throw new RangeError('MeshLocator: positions and texcoords must be x, y pairs, as many');
    if (triangles.length % 3 !== 0)
      throw new RangeError('MeshLocator: triangles must be index triples');
    const vertices = positions.length / 2;
    for (let i = 0; i < triangles.length; ++i)
      if (!(triangles[i] >= 0 && triangles[i] < vertices))
        throw new RangeError(`MeshLocator: triangles[${i}] = ${triangles[i]} is not a vertex`);
    this.positions = positions;
    this.texcoords = texcoords;
    this.triangles = triangles;
    this._screen = null; // built on the first inverse()
    this._source = null; // built on the first forward()
  }

  /**
   * Source -> screen pixels of the points [x0, y0, x1, y1, ...]: a new Float64Array of the same
   * length, NaN where a point is in no source triangle (or is not finite).
   * @param {ArrayLike<number>} points
   * @returns {Float64Array}
   */
  forward(points) {
    if (!this._source) this._source = buildSide(this.texcoords, this.triangles);
    return this._map(this._source, this.positions, points);
  }

  /**
   * Screen -> source pixels of the points [x0, y0, x1, y1, ...], as forward().
   * @param {ArrayLike<number>} points
   * @returns {Float64Array}
   */
  inverse(points) {
    if (!this._screen) this._screen = buildSide(this.positions, this.triangles);
    return this._map(this._screen, this.texcoords, points);
  }

  _map(side, V, points) {
    const out = new Float64Array(points.length).fill(NaN);
    const F = this.triangles, L = side.locators;
    for (let i = 0; i + 1 < points.length; i += 2) {
      const px = points[i], py = points[i + 1];
      if (!Number.isFinite(px) || !Number.isFinite(py) || side.columns === 0) continue;
      const x = (px - side.originX) * side.inverseSide, y = (py - side.originY) * side.inverseSide;
      if (!(x >= 0 && y >= 0 && x < side.columns && y < side.rows)) continue;
      const bucket = Math.trunc(y) * side.columns + Math.trunc(x);
      for (let k = side.start[bucket], end = side.start[bucket + 1]; k < end; ++k) {
        const f = side.triangles[k], t = 6 * f;
        const dx = px - L[t], dy = py - L[t + 1];
        const l1 = L[t + 2] * dx + L[t + 3] * dy, l2 = L[t + 4] * dx + L[t + 5] * dy;
        if (Math.min(l1, l2, 1 - l1 - l2) < -EDGE_TOLERANCE) continue;
        const a = 2 * F[3 * f], b = 2 * F[3 * f + 1], c = 2 * F[3 * f + 2];
        out[i] = V[a] + l1 * (V[b] - V[a]) + l2 * (V[c] - V[a]);
        out[i + 1] = V[a + 1] + l1 * (V[b + 1] - V[a + 1]) + l2 * (V[c + 1] - V[a + 1]);
        break;
      }
    }
    return out;
  }
}

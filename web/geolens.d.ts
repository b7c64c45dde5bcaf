// TypeScript declarations of the geolens lens engine in WebAssembly (issue 31): the ES module
// web/dist/geolens.mjs (+ geolens.wasm) that scripts/web_build.sh builds from web/src/bindings.cpp
// (embind) and web/src/post.js (its JS face). web/test/types.test.mjs checks that its names are
// the module's; it compiles under `tsc --strict` (TypeScript 5.9 and 7.0) with a usage file:
//   npm install --no-save typescript @types/node   (in a scratch folder, not in the repo)
//   npx tsc --strict --noEmit --module nodenext --target es2022 --types node usage.mts
//
// Coordinates: "source" pixels are the image's (x right, y down, 0..width and 0..height, what a
// texture is sampled at); "screen" pixels are the magnified output's, framed at the same
// width x height. A lens is placed in source pixels.

/** A typed array of numbers (what `Array.isArray` or `ArrayBuffer.isView` accepts). */
export type TypedNumberArray =
  | Float64Array
  | Float32Array
  | Int32Array
  | Uint32Array
  | Int16Array
  | Uint16Array
  | Int8Array
  | Uint8Array
  | Uint8ClampedArray;

/** Numbers as the engine reads them: a plain array or a typed array. */
export type NumberArray = readonly number[] | TypedNumberArray;

/** A number, or its text (options are read from their text, as the CLI reads its flags). */
export type Numeric = number | `${number}`;

// --- Lenses ------------------------------------------------------------------------------------

/** The shape of a lens's 3D lift (read by the `lift` and `field` models only). */
export type Profile = 'gaussian' | 'sphere' | 'mesa';

/** What every kind of lens may give besides its region. */
export interface LensCommon {
  /**
   * The magnification asked for at the region's peak, in [1, 8]; default 2. A lens that does
   * not fit gets the largest zoom that does ({@link LensFigures.zoomFit}, with a reason).
   */
  zoom?: number;
  /** The lift's bump shape (`lift` and `field` models); default `'gaussian'`. */
  profile?: Profile;
  /**
   * `focus` model: how far the context gives way, as the ratio of the footprint's reach to the
   * region's from its peak: 0 (the default: 2 x zoom) or in (zoom, 100].
   */
  footprint?: number;
}

/** A circle lens: centre and radius in source pixels; the centre must be inside the image. */
export interface CircleLens extends LensCommon {
  kind: 'circle';
  /** Centre x, source pixels, in [0, width]. */
  cx: number;
  /** Centre y, source pixels, in [0, height]. */
  cy: number;
  /** Radius, source pixels, > 0 (and at least half a pixel). */
  r: number;
}

/** A polygon lens: its outline in source pixels, every vertex inside the image. */
export interface PolygonLens extends LensCommon {
  kind: 'polygon';
  /**
   * The vertices as x, y pairs: `[x0, y0, x1, y1, ...]`, source pixels; at least 3 vertices, a
   * simple outline of non-zero area (either orientation), not closed by repeating the first.
   */
  points: NumberArray;
}

/** One lens of {@link Session.update}'s list: a circle or a polygon. */
export type LensSpec = CircleLens | PolygonLens;

// --- Options -----------------------------------------------------------------------------------

/**
 * How the lenses are solved: `focus` (the default; the region magnified as a whole, the
 * context giving way within the footprint), `lift` (the paper's: lifted triangles, harmonic
 * texture), `field` (the lift as a zoom field) or `auto` (lift for circles only, else field).
 */
export type LensModel = 'focus' | 'lift' | 'field' | 'auto';

/**
 * The library's lens options (`lens_option_fields()` in include/geolens/lens/lens_options.h),
 * named as it names them. Each value is read from its text (`String(value)`), with the library's
 * checks: a bad one throws an `InvalidOption` Error naming it, an unknown name an
 * `InvalidInput` Error listing the names.
 */
export interface LensOptions {
  /** How the lenses are solved; default `'focus'`. */
  model?: LensModel;
  /** Grid vertices along the solved area's long side, an integer in [4, 1000]; default 100. */
  mesh?: Numeric;
  /**
   * `focus` model: the grid is refined where the lens's start strays from linear over a
   * triangle by more than this many screen pixels (or 1/400 of the smallest lens's reach);
   * 0 (not refined) or >= 0.01; default 0.2. Drafts are not refined.
   */
  mesh_tolerance?: Numeric;
  /**
   * Drafts ({@link Session.update} with `draft`) on a grid of this many vertices along the long
   * side: 0 (the default: `mesh`) or an integer in [4, 1000]. Where it cannot hold a lens's zoom,
   * the draft is solved on a grid twice as fine (while coarser than `mesh`), then in full.
   */
  draft_mesh?: Numeric;
  /**
   * Bisection rounds refining triangles the lift stretches: only 0 (the default) is taken. A
   * session keeps its mesh from frame to frame (LensSession), so any other value is refused
   * (`InvalidOption`); the CLI's `--subdivide` does subdivide.
   */
  subdivide?: Numeric;
  /** The flattening's metric: `'paper'` (Eq. 6 alpha blend, default) or `'spectrum'`. */
  metric?: 'paper' | 'spectrum';
  /** Metric blend: [0, 1) for `'paper'`, [0, 1] for `'spectrum'`; default 0. */
  alpha?: Numeric;
  /** Flattening weights of the lift model: `'paper'` (default) or `'cotan'`. */
  weights?: 'paper' | 'cotan';
  /** Texture map weights of the lift model: `'cotan'` (default), `'cotan+'` or `'mvc'`. */
  texture?: 'cotan' | 'cotan+' | 'mvc';
  /** The image border: `'sliding'` (default), `'fixed'` or `'free'`. */
  boundary?: 'sliding' | 'fixed' | 'free';
  /** `'global'` (default: the whole image gives way) or `'local'` (a patch around the lenses). */
  extent?: 'global' | 'local';
  /** Local extent: the patch's half-side over the lens radius, in (1, 100]; default 2.5. */
  extent_factor?: Numeric;
  /** Relative energy change that stops the flattening, in (0, 1); default 0.001. */
  tolerance?: Numeric;
  /** Cap on flattening iterations, an integer in [1, 100000]; default 100. */
  max_iterations?: Numeric;
  /**
   * Threads of the solve, an integer in [0, 1024]; the engine sets 1. The module is built
   * without threads, so every value runs on the calling thread; results do not depend on it.
   */
  threads?: Numeric;
}

/** The names of {@link LensOptions}, in the library's order. */
export type LensOptionName = keyof LensOptions;

/** {@link GeolensEngine.session}'s argument: the image's size and the lens options. */
export interface SessionOptions extends LensOptions {
  /** The image's width, source pixels: a whole number in [1, 1048576]. */
  width: number;
  /** The image's height, source pixels: a whole number in [1, 1048576]. */
  height: number;
}

// --- Results -----------------------------------------------------------------------------------

/** Per lens, in the order given: what was asked and what was got. */
export interface LensFigures {
  /** The zoom asked for (the lens's `zoom`, or 2). */
  zoomAsked: number;
  /** The magnification measured at the region's peak, on the warp as solved. */
  zoomGot: number;
  /**
   * `focus` model: the zoom the lens was solved with, the largest that fits where it is (equal
   * to `zoomAsked` when it fits); `null` for the lift and field models.
   */
  zoomFit: number | null;
  /** Why `zoomFit` is below `zoomAsked` (e.g. "lens 2 beside it ..."); `''` when it is not. */
  reason: string;
}

/**
 * One solved frame: the warp as a triangle mesh (each vertex has a screen position and the
 * source point drawn there) and the figures per lens.
 *
 * Lifetime: `positions`, `texcoords` and `triangles` are views into the wasm heap, made anew at
 * each access (so they follow the heap when it grows). They are valid until the session's next
 * successful {@link Session.update} or its {@link Session.dispose}; after that an access throws
 * an Error. A view kept across a heap growth is detached (length 0). Copy (`.slice()`) to keep
 * one longer. The other fields are plain values, valid for ever.
 */
export interface Frame {
  /** The mesh's vertices. */
  readonly vertexCount: number;
  /** The mesh's triangles. */
  readonly triangleCount: number;
  /** The screen frame's width, pixels (the session's width). */
  readonly screenWidth: number;
  /** The screen frame's height, pixels (the session's height). */
  readonly screenHeight: number;
  /** Whether this frame is a draft (asked as one and solved on the draft mesh). */
  readonly draft: boolean;
  /** The model that solved it (`'auto'` resolved). */
  readonly model: Exclude<LensModel, 'auto'>;
  /** Per lens of the update, in its order. */
  readonly lenses: readonly LensFigures[];
  /** One line per lens that got less zoom than asked, as the CLI prints them. */
  readonly warnings: readonly string[];
  /** Screen x, y per vertex (screen pixels): 2 x vertexCount numbers. A heap view: see above. */
  readonly positions: Float64Array;
  /**
   * Source x, y per vertex (source pixels, what to sample the image at; divide by width and
   * height for texture coordinates in [0, 1]): 2 x vertexCount numbers. A heap view.
   */
  readonly texcoords: Float64Array;
  /** Three vertex indices per triangle: 3 x triangleCount numbers. A heap view. */
  readonly triangles: Uint32Array;
}

// --- Sessions ----------------------------------------------------------------------------------

/**
 * A lens session on one image (the library's LensSession): updated with the lenses of each
 * frame, it reuses what did not change since the last update (so a drag is fast, and a frame's
 * result may differ slightly from a first placement of the same lenses: the lift and field
 * models start from the last flattening). Holds wasm memory until {@link Session.dispose}.
 */
export declare class Session {
  /**
   * A session on a width x height image (source pixels).
   * @param meshOrOptions the grid's vertices along the long side (a number, not its text), or
   *   lens options.
   * @throws Error (`InvalidInput`, `InvalidOption`) for a size that is not positive or a bad
   *   option.
   */
  constructor(width: number, height: number, meshOrOptions?: number | LensOptions);
  /**
   * Solves the lenses of this frame. `draft`: a drag's frame, solved on the draft mesh (coarser,
   * not refined), for speed; the frame at rest should be a full one.
   * @returns the frame; the previous frame's views are gone.
   * @throws Error named after the library's exception (`InvalidInput` for a bad lens,
   *   `InvalidOption`, `SolverError`) with its message; the session and its last frame are
   *   then unchanged. Also when the session is disposed.
   */
  update(lenses: readonly LensSpec[], draft?: boolean): Frame;
  /**
   * Maps source points to screen points through the last frame's warp.
   * @param points x, y pairs, source pixels.
   * @returns a new Float64Array (its own memory, valid for ever) of the same length: screen
   *   pixels, NaN for a point outside the image.
   * @throws Error before the first update, after dispose, or for an odd count or not numbers.
   */
  forward(points: NumberArray): Float64Array;
  /**
   * Maps screen points back to the source points shown there (picking).
   * @param points x, y pairs, screen pixels.
   * @returns a new Float64Array: source pixels, NaN for a point outside the frame. Where the warp
   *   folds, one of the source points under it.
   * @throws as {@link Session.forward}.
   */
  inverse(points: NumberArray): Float64Array;
  /** Forgets every frame: the next update starts as a first placement (the warp stays). */
  reset(): void;
  /** Frees the session's wasm memory and its frame's views; calling it again does nothing. */
  dispose(): void;
}

/** The names the engine's errors carry (`error.name`): the library's exception types. */
export type GeolensErrorName =
  | 'InvalidInput'
  | 'InvalidOption'
  | 'SolverError'
  | 'Cancelled'
  | 'RangeError'
  | 'Error';

/** What the engine throws: an `Error` with the library's message, named after its type. */
export interface GeolensError extends Error {
  name: GeolensErrorName;
}

/** The engine: an instance of the module, with its own wasm memory. */
export interface GeolensEngine {
  /**
   * A session: `engine.session({width, height, mesh, ...options})`, the same as
   * `new engine.Session(width, height, options)`.
   */
  session(options: SessionOptions): Session;
  /** The Session class of this instance. */
  Session: typeof Session;
  /** The library's number_text: the shortest text that reads back to `value` (for tests). */
  numberText(value: number): string;
  /** Bytes of the wasm heap malloc has handed out and not had back (for leak tests). */
  heapInUse(): number;
  /** embind's live JS handles (for leak tests). */
  count_emval_handles(): number;
  /**
   * Views of the whole wasm heap as it is now; replaced when it grows (read them again, do not
   * keep them).
   */
  readonly HEAP8: Int8Array;
  readonly HEAPU8: Uint8Array;
  readonly HEAP16: Int16Array;
  readonly HEAPU16: Uint16Array;
  readonly HEAP32: Int32Array;
  readonly HEAPU32: Uint32Array;
  readonly HEAPF32: Float32Array;
  readonly HEAPF64: Float64Array;
}

/** What {@link createGeolens} takes: Emscripten's module settings that apply to this build. */
export interface GeolensModuleOptions {
  /**
   * The bytes of geolens.wasm. Needed under node (the module is built for the web and workers:
   * it cannot read files); in a browser it is fetched next to geolens.mjs unless given.
   */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where to fetch a file the module needs (geolens.wasm) from, given its name. */
  locateFile?: (path: string, scriptDirectory: string) => string;
  /**
   * Instantiates the wasm module yourself (e.g. from a cached WebAssembly.Module): call
   * `receiveInstance` with the instance, return `{}` (asynchronous) or its exports.
   */
  instantiateWasm?: (
    imports: object,
    receiveInstance: (instance: object, module?: object) => void,
  ) => object;
  /** Where the module's standard output goes (default console.log). */
  print?: (text: string) => void;
  /** Where its standard error goes (default console.warn). */
  printErr?: (text: string) => void;
  /** Called if the module aborts (then the promise rejects). */
  onAbort?: (what: unknown) => void;
}

/**
 * Loads and instantiates the engine; each call is an instance of its own (its own memory).
 * Under node: `createGeolens({wasmBinary: readFileSync('geolens.wasm')})`.
 */
declare function createGeolens(options?: GeolensModuleOptions): Promise<GeolensEngine>;
export default createGeolens;

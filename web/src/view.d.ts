// TypeScript declarations of GeolensView (src/view.js): a geolens lens on a canvas, drawn with
// WebGL2, moved with the pointer. The engine's own types are in geolens.d.ts; the few this file
// needs are restated structurally here so that it stands alone.

/** A circle lens (source pixels). */
export interface CircleLens {
  kind: 'circle';
  cx: number;
  cy: number;
  r: number;
  /** In [1, 8]. */
  zoom: number;
  /** How far the context gives way: 0 (default: 2 x zoom) or in (zoom, 100]. */
  footprint?: number;
  /** 'gaussian' (default), 'sphere' or 'mesa'. */
  profile?: string;
}

/** A polygon lens (source pixels). */
export interface PolygonLens {
  kind: 'polygon';
  /** Vertices, flat: [x0, y0, x1, y1, ...], at least 3. */
  points: number[];
  zoom: number;
  footprint?: number;
  profile?: string;
}

export type Lens = CircleLens | PolygonLens;

/** What the engine says of one lens in a frame. */
export interface LensFigures {
  zoomAsked: number;
  /** The zoom measured over the region. */
  zoomGot: number;
  /** The largest zoom that fits where the lens is (focus model), null otherwise. */
  zoomFit: number | null;
  /** What limits the zoom where it gets less than asked; '' otherwise. */
  reason: string;
}

/** The figures of a solved frame: the 'frame' event's detail and GeolensView.frame. */
export interface FrameFigures {
  lenses: LensFigures[];
  /** One line per lens that gets less than asked. */
  warnings: string[];
  /** Solved on the coarse mesh while a lens moves. */
  draft: boolean;
  /** The model that solved it: 'focus', 'lift' or 'field'. */
  model: string;
  /** Wall-clock time of the solve, milliseconds. */
  solveMs: number;
  /** Shape distortion s1 / s2 - 1 of the warp's triangles: mean (by source area) and largest. */
  shapeMean: number;
  shapeMax: number;
  /** Triangles turned over (det J <= 0). */
  flipped: number;
  vertexCount: number;
  triangleCount: number;
}

/** A point in pixels. */
export interface Point {
  x: number;
  y: number;
}

/** The engine as createGeolens() resolves it (see geolens.d.ts); only session() is used. */
export interface GeolensEngineLike {
  session(options: { width: number; height: number; [option: string]: unknown }): unknown;
}

/** What a view shows. */
export type PictureSource =
  | HTMLImageElement
  | HTMLCanvasElement
  | HTMLVideoElement
  | ImageBitmap
  | OffscreenCanvas
  | VideoFrame;

export interface GeolensViewOptions {
  /** Milliseconds after the last move before the full mesh is solved (150). */
  restDelay?: number;
  /** Draw the lens outlines (true). */
  outlines?: boolean;
  /** The letterbox, [r, g, b, a] in [0, 1] ([0, 0, 0, 0]: transparent). */
  background?: [number, number, number, number];
  /** Keep the canvas's pixels in step with its CSS size and devicePixelRatio (true). */
  autoResize?: boolean;
  /** Pointer, wheel and key handling (true). */
  interactive?: boolean;
  /** Called with each frame's figures. */
  onFrame?: ((frame: FrameFigures) => void) | null;
  /**
   * Constructor only: solve in a module Worker, off the page's thread. true: the
   * solver_worker.js next to view.js (it imports ../dist/geolens.mjs); a URL or string: another
   * copy of it. The engine argument is then not used (null is fine; create() does not call the
   * factory). pick() and project() stay synchronous (answered from the last frame's mesh on the
   * page's thread); readPixels() draws the last frame solved (await idle() first); options or
   * sizes the engine refuses come as 'error' events rather than thrown, and the options go back.
   */
  worker?: boolean | string | URL;
  /** Engine: 'focus' (default), 'lift', 'field' or 'auto'. */
  model?: string;
  /** Engine: grid vertices along the long side (100). */
  mesh?: number;
  /** Engine: the drafts' grid (30; 60 where that cannot hold a lens's zoom). */
  draftMesh?: number;
  /** Engine: the focus model's refinement tolerance, output pixels (0.2). */
  meshTolerance?: number;
  /** Any other engine option, camelCase or as the library names it (mesh_tolerance, ...). */
  [engineOption: string]: unknown;
}

export interface GeolensViewEventMap {
  frame: CustomEvent<FrameFigures>;
  change: CustomEvent<{ reason: string }>;
  error: CustomEvent<{ error: Error }>;
}

export class GeolensView extends EventTarget {
  /** `engine`: what createGeolens() resolves to; not used (may be null) with options.worker. */
  constructor(
    canvas: HTMLCanvasElement,
    engine: GeolensEngineLike | null,
    options?: GeolensViewOptions,
  );

  /**
   * Makes a view, creating the engine first when given createGeolens itself (not with
   * options.worker: the worker makes its own).
   */
  static create(
    canvas: HTMLCanvasElement,
    engineOrFactory: GeolensEngineLike | (() => Promise<GeolensEngineLike>) | null,
    options?: GeolensViewOptions,
  ): Promise<GeolensView>;

  readonly canvas: HTMLCanvasElement;
  /** The engine given; null in worker mode unless one was given. */
  readonly engine: GeolensEngineLike | null;

  /** Shows a picture; a picture of another size starts a new session and removes the lenses. */
  setImage(source: PictureSource): Promise<void>;
  /** The picture's size in source pixels (0 x 0 before setImage). */
  readonly imageSize: { width: number; height: number };

  /** The lenses (copies). */
  readonly lenses: Lens[];
  /** Adds a circle lens and selects it; returns its index. */
  addCircle(cx: number, cy: number, r: number, zoom?: number): number;
  /** Adds a polygon lens and selects it; returns its index. */
  addPolygon(points: number[] | [number, number][] | Point[], zoom?: number): number;
  /** Changes a lens; `moving`: one of a stream of changes (drafts, then the full mesh). */
  setLens(
    index: number,
    changes: Partial<Omit<CircleLens, 'kind'>> | Partial<Omit<PolygonLens, 'kind'>>,
    how?: { moving?: boolean },
  ): void;
  removeLens(index: number): void;
  /** The selected lens, -1 for none. */
  selectedIndex: number;

  /** Clicks add a polygon's vertices; a double-click, Enter or its first vertex closes it. */
  drawPolygon(zoom?: number): void;
  /** Closes the polygon being drawn; the new lens's index or -1. */
  finishPolygon(): number;
  cancelPolygon(): void;
  readonly mode: 'idle' | 'polygon';

  /** Sets view and engine options (engine options start a new session; the lenses stay). */
  setOptions(options: GeolensViewOptions): void;
  readonly options: Record<string, unknown>;

  /** The last frame's figures, null before the first. */
  readonly frame: FrameFigures | null;
  /** The source point under a canvas point (CSS pixels), null off the picture. */
  pick(x: number, y: number): Point | null;
  /** Where a source point is shown, in canvas CSS pixels; null where the warp does not reach. */
  project(x: number, y: number): Point | null;
  /** A canvas point (CSS pixels) in the picture's frame pixels, no lens involved. */
  toFrame(x: number, y: number): Point;
  /**
   * Resolves once everything asked is solved (the full mesh) and drawn; in worker mode once the
   * worker has answered and its frame is drawn.
   */
  idle(): Promise<void>;
  /**
   * Solves and draws now, then reads the canvas back: RGBA, top row first. In worker mode it
   * draws the last frame solved (await idle() first).
   */
  readPixels(): { width: number; height: number; data: Uint8Array };
  dispose(): void;

  addEventListener<K extends keyof GeolensViewEventMap>(
    type: K,
    listener: (this: GeolensView, event: GeolensViewEventMap[K]) => void,
    options?: boolean | AddEventListenerOptions,
  ): void;
  addEventListener(
    type: string,
    listener: EventListenerOrEventListenerObject | null,
    options?: boolean | AddEventListenerOptions,
  ): void;
  removeEventListener<K extends keyof GeolensViewEventMap>(
    type: K,
    listener: (this: GeolensView, event: GeolensViewEventMap[K]) => void,
    options?: boolean | EventListenerOptions,
  ): void;
  removeEventListener(
    type: string,
    listener: EventListenerOrEventListenerObject | null,
    options?: boolean | EventListenerOptions,
  ): void;
}

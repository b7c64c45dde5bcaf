// The JS face of the geolens bindings (bindings.cpp's SessionCore), linked into geolens.mjs with
// --post-js: it runs inside createGeolens(), so Module, HEAPF64 and HEAPU32 are the instance's.
//
//   const engine = await createGeolens();
//   const lens = new engine.Session(800, 600, 100);        // or engine.session({width, height, mesh})
//   const frame = lens.update([{kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2}], false);
//   frame.positions  // Float64Array view: screen x, y per vertex
//   frame.texcoords  // Float64Array view: source x, y per vertex (pixels)
//   frame.triangles  // Uint32Array view: 3 vertex indices per triangle
//   frame.lenses     // [{zoomAsked, zoomGot, zoomFit, reason}]
//   lens.forward(new Float64Array([x0, y0, ...]))  // source -> screen, NaN outside
//   lens.inverse(...)                              // screen -> source
//   lens.dispose();
//
// The views look into the wasm heap: each access makes a view of the heap as it is now (so it
// survives the heap growing), and they are valid until the session's next update() or its
// dispose(); after that an access throws. Copy (frame.positions.slice()) to keep one longer.
// Errors of the library (geolens::InvalidInput, ...) are thrown as Error objects with its message,
// named after its exception type (error.name: 'InvalidInput', 'InvalidOption', 'SolverError').

(function () {
  function check(result) {
    if (result instanceof Error) throw result;
    return result;
  }

  class Frame {
    constructor(session, generation, core) {
      this._session = session;
      this._generation = generation;
      this._core = core;
      this.vertexCount = core.vertexCount;
      this.triangleCount = core.triangleCount;
      this.screenWidth = core.screenWidth;
      this.screenHeight = core.screenHeight;
      this.draft = core.draft;
      this.model = core.model;
      this.lenses = core.lenses;
      this.warnings = core.warnings;
    }
    _live(what) {
      if (this._session._core === null || this._session._generation !== this._generation)
        throw new Error('Session frame: the ' + what + ' view is gone (a later update() or ' +
                        'dispose() freed it); copy the arrays to keep them');
    }
    get positions() {
      this._live('positions');
      return new Float64Array(HEAPF64.buffer, this._core.positionsPtr, 2 * this.vertexCount);
    }
    get texcoords() {
      this._live('texcoords');
      return new Float64Array(HEAPF64.buffer, this._core.texcoordsPtr, 2 * this.vertexCount);
    }
    get triangles() {
      this._live('triangles');
      return new Uint32Array(HEAPU32.buffer, this._core.trianglesPtr, 3 * this.triangleCount);
    }
  }

  class Session {
    // A session on a width x height image; meshOrOptions: the grid's vertices along the long
    // side (a number), or an object of lens options named as the library names them (mesh,
    // model, mesh_tolerance, draft_mesh, ...).
    constructor(width, height, meshOrOptions) {
      const core = new Module['SessionCore']();
      const result = core['init'](width, height, meshOrOptions);
      if (result instanceof Error) {
        core.delete();
        throw result;
      }
      this._core = core;
      this._generation = 0;
    }
    _alive(name) {
      if (this._core === null) throw new Error('Session.' + name + ': the session is disposed');
      return this._core;
    }
    // Solves the lenses of this frame (draft: a drag's frame, LensSession::update).
    update(lenses, draft) {
      const result = check(this._alive('update')['update'](lenses, Boolean(draft)));
      this._generation += 1;
      return new Frame(this, this._generation, result);
    }
    forward(points) {
      return check(this._alive('forward')['forward'](points));
    }
    inverse(points) {
      return check(this._alive('inverse')['inverse'](points));
    }
    // Forgets every frame: the next update() starts as a first placement.
    reset() {
      check(this._alive('reset')['reset']());
    }
    // Frees the session's wasm memory; calling it again does nothing.
    dispose() {
      if (this._core !== null) {
        this._core.delete();
        this._core = null;
        this._generation += 1;
      }
    }
  }

  Module['Session'] = Session;
  // engine.session({width, height, mesh, ...options})
  Module['session'] = function (options) {
    const o = options || {};
    return new Session(o.width, o.height, o);
  };
})();

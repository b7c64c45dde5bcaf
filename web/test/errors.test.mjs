// The engine's errors beyond engine.test.mjs's (issue 31, item 5): bad zooms, radii, polygons,
// lens objects, options and image sizes each throw an Error whose message is the library's and
// whose name is its exception type, naming the lens or option; a refused update leaves the
// session's last frame as it was. (native.test.mjs checks these messages against the CLI's.)
// Run: node --test web/test/errors.test.mjs
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import createGeolens from '../dist/geolens.mjs';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });

const circle = (o) => ({ kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2, ...o });
const polygon = (points, o) => ({ kind: 'polygon', points, zoom: 2, ...o });

// Asserts that fn throws an Error named `name` with exactly `message` (or matching a RegExp).
function throwsLibrary(fn, name, message) {
  assert.throws(fn, (e) => {
    assert.ok(e instanceof Error, `not an Error: ${e}`);
    assert.equal(e.name, name, e.message);
    if (message instanceof RegExp) assert.match(e.message, message);
    else assert.equal(e.message, message);
    return true;
  });
}

function withSession(fn, options = { mesh: 20 }) {
  const lens = engine.session({ width: 800, height: 600, ...options });
  try {
    return fn(lens);
  } finally {
    lens.dispose();
  }
}

test('zooms outside [1, 8], NaN or not numbers are refused; 1 and 8 are taken', () => {
  withSession((lens) => {
    const zoom = (value) => `validate_lens: zoom must be in [1, 8], got ${value}`;
    for (const [value, text] of [[NaN, 'nan'], [Infinity, 'inf'], [-Infinity, '-inf'], [0, '0'],
                                 [0.5, '0.5'], [-2, '-2'], [8.000001, '8.000001'],
                                 [1 - 1e-12, '0.999999999999']])
      throwsLibrary(() => lens.update([circle({ zoom: value })]), 'InvalidInput', zoom(text));
    for (const [value, type] of [['2', 'string'], [null, 'object'], [true, 'boolean']])
      throwsLibrary(() => lens.update([circle({ zoom: value })]), 'InvalidInput',
                    `Session.update: lens 1: 'zoom' must be a number, got ${type}`);
    assert.equal(lens.update([circle({ zoom: 1 })]).lenses[0].zoomGot, 1);
    assert.ok(Math.abs(lens.update([circle({ r: 20, zoom: 8 })]).lenses[0].zoomAsked - 8) < 1e-12);
    // A zoom left out is the library's default, 2.
    assert.equal(lens.update([{ kind: 'circle', cx: 400, cy: 300, r: 80 }]).lenses[0].zoomAsked, 2);
  });
});

test('circles: a radius that is not positive, a centre not finite or off the image', () => {
  withSession((lens) => {
    const radius = (text) => `Region::circle: radius must be a positive number, got ${text}`;
    throwsLibrary(() => lens.update([circle({ r: 0 })]), 'InvalidInput', radius('0'));
    throwsLibrary(() => lens.update([circle({ r: NaN })]), 'InvalidInput', radius('nan'));
    throwsLibrary(() => lens.update([circle({ r: Infinity })]), 'InvalidInput', radius('inf'));
    throwsLibrary(() => lens.update([circle({ r: 1e-9 })]), 'InvalidInput',
                  'validate_lens: the circle reaches 1e-09 px from its centre, less than half a ' +
                  'pixel');
    throwsLibrary(() => lens.update([circle({ cx: NaN })]), 'InvalidInput',
                  'Region::circle: centre is not finite');
    throwsLibrary(() => lens.update([circle({ cy: -Infinity })]), 'InvalidInput',
                  'Region::circle: centre is not finite');
    throwsLibrary(() => lens.update([circle({ cx: -0.5 })]), 'InvalidInput',
                  'validate_lens: lens centre (-0.5, 300) is outside the 800x600 image');
    throwsLibrary(() => lens.update([circle({ cy: 600.25 })]), 'InvalidInput',
                  'validate_lens: lens centre (400, 600.25) is outside the 800x600 image');
    throwsLibrary(() => lens.update([circle({ cx: '400' })]), 'InvalidInput',
                  "Session.update: lens 1: 'cx' must be a number, got string");
  });
});

test('polygons: fewer than 3 vertices, odd or bad coordinates, a vertex off the image', () => {
  withSession((lens) => {
    throwsLibrary(() => lens.update([polygon([100, 100, 200, 200])]), 'InvalidInput',
                  'Region::polygon: a polygon needs at least 3 vertices, got 2');
    throwsLibrary(() => lens.update([polygon([])]), 'InvalidInput',
                  'Region::polygon: a polygon needs at least 3 vertices, got 0');
    throwsLibrary(() => lens.update([polygon([100, 100, 200, 100, 150])]), 'InvalidInput',
                  'Session.update: lens 1: points must be x, y pairs, got 5 numbers');
    throwsLibrary(() => lens.update([polygon([100, 100, NaN, 100, 150, 200])]), 'InvalidInput',
                  'Region::polygon: vertex 1 (nan, 100) is not finite');
    throwsLibrary(() => lens.update([polygon([10, 10, 900, 10, 100, 100])]), 'InvalidInput',
                  'validate_lens: polygon vertex (900, 10) is outside the 800x600 image');
    throwsLibrary(() => lens.update([polygon('100,100,200,100,150,200')]), 'InvalidInput',
                  'Session.update: lens 1: points must be an array or a typed array of numbers, ' +
                  'got string');
  });
  // Any array of numbers is taken, typed or not (each placed first on its own session: a
  // session's next update starts from its last frame).
  const points = [300, 250, 500, 250, 500, 350, 300, 350];
  const plain = withSession((lens) => lens.update([polygon(points)]).positions.slice());
  for (const typed of [new Float64Array(points), new Float32Array(points), new Int32Array(points)])
    assert.deepEqual(withSession((lens) => lens.update([polygon(typed)]).positions.slice()), plain);
});

test('lens objects: not an object, no kind, an unknown profile; the lens is named by place', () => {
  withSession((lens) => {
    for (const bad of [null, 5, 'circle', undefined])
      throwsLibrary(() => lens.update([bad]), 'InvalidInput',
                    'Session.update: lens 1 must be an object');
    throwsLibrary(() => lens.update([{ cx: 1 }]), 'InvalidInput',
                  "Session.update: lens 1: kind must be 'circle' or 'polygon', got '(none)'");
    throwsLibrary(() => lens.update([circle({}), { kind: 'mask' }]), 'InvalidInput',
                  "Session.update: lens 2: kind must be 'circle' or 'polygon', got 'mask'");
    throwsLibrary(() => lens.update([circle({}), circle({ cx: 100, cy: 100, r: 30, zoom: 0 })]),
                  'InvalidInput', 'validate_lens: zoom must be in [1, 8], got 0');
    throwsLibrary(() => lens.update([circle({ profile: 'cone' })]), 'InvalidInput',
                  "parse_profile: unknown profile 'cone' (expected gaussian, sphere or mesa)");
    // Not the library's message (embind's own), but still an Error.
    assert.throws(() => lens.update([circle({ profile: 3 })]), Error);
    const footprint = (text) =>
      `validate_lens: footprint must be 0 (default) or in (zoom, 100] = (2, 100], got ${text}`;
    throwsLibrary(() => lens.update([circle({ footprint: 1.5 })]), 'InvalidOption',
                  footprint('1.5'));
    throwsLibrary(() => lens.update([circle({ footprint: NaN })]), 'InvalidOption',
                  footprint('nan'));
    throwsLibrary(() => lens.update([circle({ footprint: 101 })]), 'InvalidOption',
                  footprint('101'));
    // An empty list is no error: the identity.
    const frame = lens.update([]);
    assert.deepEqual(frame.lenses, []);
    assert.deepEqual([...lens.forward([123.5, 456.25])], [123.5, 456.25]);
  });
});

test('options: unknown names, text that does not read, values out of range', () => {
  const session = (options) => engine.session({ width: 800, height: 600, ...options });
  throwsLibrary(() => session({ meshes: 3 }), 'InvalidInput',
                "lens_option_field: unknown option 'meshes' (expected model, mesh, " +
                'mesh_tolerance, draft_mesh, subdivide, metric, alpha, weights, texture, ' +
                'boundary, extent, extent_factor, tolerance, max_iterations, threads)');
  const cases = [
    [{ mesh: NaN }, "LensOptions: mesh must be an integer, got 'NaN'"],
    [{ mesh: null }, "LensOptions: mesh must be an integer, got 'null'"],
    [{ mesh: 1001 }, 'validate: mesh must be in [4, 1000] vertices per side, got 1001'],
    [{ draft_mesh: 2 }, 'validate: draft_mesh must be in [4, 1000] vertices per side, got 2'],
    [{ threads: -1 }, 'validate: threads must be in [0, 1024], got -1'],
    [{ alpha: 'x' }, "LensOptions: alpha must be a number, got 'x'"],
    [{ metric: 'spectrum', alpha: 1.5 }, 'validate: alpha must be in [0, 1] for metric ' +
                                         'spectrum, got 1.5'],
    [{ model: 'Focus' }, "LensOptions: model must be focus, lift, field or auto, got 'Focus'"],
  ];
  for (const [options, message] of cases) throwsLibrary(() => session(options), 'InvalidOption',
                                                        message);
  // A mesh as the third argument of the constructor, checked alike.
  throwsLibrary(() => new engine.Session(800, 600, 2.5), 'InvalidOption',
                "LensOptions: mesh must be an integer, got '2.5'");
  // Options that read are taken as text, numbers or not.
  const lens = session({ mesh: '24', mesh_tolerance: '0', model: 'focus', draft_mesh: 12 });
  try {
    assert.equal(lens.update([circle({})]).model, 'focus');
    assert.ok(lens.update([circle({ cx: 402 })], true).vertexCount <
              lens.update([circle({ cx: 404 })]).vertexCount, 'the draft mesh is coarser');
  } finally {
    lens.dispose();
  }
});

test('image sizes that are not whole numbers of pixels in [1, 2^20] are refused', () => {
  const size = (name, text) => `Session: ${name} must be a whole number of pixels in ` +
    `[1, 1048576], got ${text}`;
  const cases = [[0, 600, size('width', '0')], [-1, 600, size('width', '-1')],
    [NaN, 600, size('width', 'nan')], [800, Infinity, size('height', 'inf')],
    [800.5, 600, size('width', '800.5')], [3e9, 600, size('width', '3e+09')],
    [800, 2 ** 20 + 1, size('height', '1048577')]];
  for (const [width, height, message] of cases)
    throwsLibrary(() => engine.session({ width, height }), 'InvalidInput', message);
  throwsLibrary(() => engine.session({ height: 600 }), 'InvalidInput', size('width', 'nan'));
  engine.session({ width: 1, height: 2 ** 20 }).dispose();
});

test('subdivide is refused: a session keeps its mesh', () => {
  throwsLibrary(() => engine.session({ width: 800, height: 600, subdivide: 2 }), 'InvalidOption',
                'Session: subdivide must be 0: a session keeps its mesh from frame to frame ' +
                'and does not subdivide it');
  engine.session({ width: 800, height: 600, subdivide: 0 }).dispose();
});

test('a refused update leaves the last frame, its views and its map as they were', () => {
  withSession((lens) => {
    const frame = lens.update([circle({})]);
    const positions = frame.positions.slice();
    const probe = [410, 305, 700, 50];
    const before = lens.forward(probe);
    for (const bad of [[circle({ zoom: 9 })], [circle({}), { kind: 'x' }], 'nothing'])
      assert.throws(() => lens.update(bad), Error);
    assert.deepEqual(frame.positions, positions);
    assert.deepEqual(lens.forward(probe), before);
    assert.ok(Math.abs(lens.inverse(before)[0] - 410) < 1e-9);
  });
});

test('every error is an Error with a library name, and none is a bare number', () => {
  const names = new Set();
  const lens = engine.session({ width: 300, height: 200, mesh: 12 });
  const attempts = [
    () => lens.update([circle({})]), // centre off this image
    () => lens.update([polygon([1, 1])]),
    () => lens.update({ length: 1, 0: circle({}) }),
    () => lens.forward({}),
    () => lens.inverse([1, 2, 3]),
    () => engine.session({ width: 300, height: 200, weights: 'x' }),
    () => engine.session({ width: 300, height: 200, extent_factor: 200 }),
  ];
  try {
    lens.update([circle({ cx: 150, cy: 100, r: 30 })]);
    for (const attempt of attempts) {
      assert.throws(attempt, (e) => {
        assert.ok(e instanceof Error, `${typeof e} ${e}`);
        assert.ok(e.message.length > 10, e.message);
        names.add(e.name);
        return true;
      });
    }
  } finally {
    lens.dispose();
  }
  assert.deepEqual([...names].sort(), ['InvalidInput', 'InvalidOption']);
  assert.throws(() => lens.update([]), { message: 'Session.update: the session is disposed' });
  assert.throws(() => lens.forward([1, 2]),
                { message: 'Session.forward: the session is disposed' });
});

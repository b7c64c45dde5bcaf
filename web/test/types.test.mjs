// web/geolens.d.ts against the module it declares (issue 31): the option names are the library's
// (in its order), the choices of each choice option are the ones it takes, and the members of
// the engine, Session and Frame declared are the ones the module has. (Whether the .d.ts
// compiles is tsc's to say: its header has the command.)
// Run: node --test web/test/types.test.mjs
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import createGeolens from '../dist/geolens.mjs';

const wasmBinary = readFileSync(new URL('../dist/geolens.wasm', import.meta.url));
const engine = await createGeolens({ wasmBinary });
const declarations = readFileSync(new URL('../geolens.d.ts', import.meta.url), 'utf8');

// The body of `export interface NAME ... {` or `export declare class NAME {`, comments removed.
function body(name) {
  const start =
    new RegExp(`export (?:interface|declare class) ${name}\\b[^{]*\\{`).exec(declarations);
  assert.ok(start, `no ${name} in geolens.d.ts`);
  let depth = 1, i = start.index + start[0].length;
  const from = i;
  for (; depth > 0; ++i) depth += declarations[i] === '{' ? 1 : declarations[i] === '}' ? -1 : 0;
  return declarations.slice(from, i - 1).replace(/\/\*\*[\s\S]*?\*\//g, '').replace(/\/\/.*/g, '');
}
// The members declared at the top level of a body: `name?:`, `readonly name:`, `name(`.
const members = (text) => [...text.matchAll(/^ {2}(?:readonly )?(\w+)\??[:(]/gm)].map((m) => m[1]);

test("LensOptions names the library's options, in its order", () => {
  let listed;
  try {
    engine.session({ width: 10, height: 10, no_such_option: 1 });
  } catch (e) {
    listed = /\(expected (.*)\)$/.exec(e.message)[1].split(', ');
  }
  assert.ok(listed && listed.length >= 15, 'the library lists its options');
  assert.deepEqual(members(body('LensOptions')), listed);
});

test('each choice option declares exactly the choices the library takes', () => {
  const options = body('LensOptions');
  for (const name of ['model', 'metric', 'weights', 'texture', 'boundary', 'extent']) {
    const declared = /^ {2}\w+\?: (.*);$/m.exec(options.split('\n').find((l) =>
      l.startsWith(`  ${name}?:`)))[1];
    const union = name === 'model' ? /export type LensModel = ([^;]*);/.exec(declarations)[1]
                                   : declared;
    const choices = [...union.matchAll(/'([^']+)'/g)].map((m) => m[1]);
    let message;
    try {
      engine.session({ width: 10, height: 10, [name]: 'no-such-choice' });
    } catch (e) {
      message = e.message;
    }
    // "LensOptions: NAME must be A, B or C, got '...'"
    const taken = /must be (.*), got/.exec(message)[1].split(/, | or /);
    assert.deepEqual(choices, taken, name);
    for (const choice of choices)
      engine.session({ width: 10, height: 10, [name]: choice }).dispose();
  }
  // The profiles a lens takes.
  const profiles = [.../export type Profile = ([^;]*);/.exec(declarations)[1]
    .matchAll(/'([^']+)'/g)].map((m) => m[1]);
  const lens = engine.session({ width: 100, height: 100, mesh: 8, model: 'lift' });
  try {
    for (const profile of profiles)
      lens.update([{ kind: 'circle', cx: 50, cy: 50, r: 10, profile }]);
    assert.throws(() => lens.update([{ kind: 'circle', cx: 50, cy: 50, r: 10, profile: 'x' }]),
                  { message: `parse_profile: unknown profile 'x' (expected ${profiles.slice(0, -1)
                    .join(', ')} or ${profiles.at(-1)})` });
  } finally {
    lens.dispose();
  }
});

test('the engine has the members declared; Session and Frame those and no others', () => {
  for (const name of members(body('GeolensEngine'))) assert.ok(name in engine, `engine.${name}`);
  assert.equal(typeof engine.session, 'function');
  const methods = Object.getOwnPropertyNames(engine.Session.prototype)
    .filter((k) => !k.startsWith('_'));
  assert.deepEqual(methods.sort(), members(body('Session')).sort());
  const lens = engine.session({ width: 100, height: 100, mesh: 8 });
  try {
    const frame = lens.update([{ kind: 'circle', cx: 50, cy: 50, r: 10 }]);
    const declared = members(body('Frame')).sort();
    const own = Object.keys(frame).filter((k) => !k.startsWith('_'));
    const getters = Object.getOwnPropertyNames(Object.getPrototypeOf(frame))
      .filter((k) => k !== 'constructor' && !k.startsWith('_'));
    assert.deepEqual([...own, ...getters].sort(), declared);
    assert.deepEqual(Object.keys(frame.lenses[0]).sort(), members(body('LensFigures')).sort());
  } finally {
    lens.dispose();
  }
});

test('the kinds of lens declared are the ones the engine takes', () => {
  const kinds = [...declarations.matchAll(/^ {2}kind: '(\w+)';$/gm)].map((m) => m[1]);
  assert.deepEqual(kinds, ['circle', 'polygon']);
  const lens = engine.session({ width: 100, height: 100, mesh: 8 });
  try {
    assert.throws(() => lens.update([{ kind: 'ellipse' }]),
                  { message: `Session.update: lens 1: kind must be '${kinds.join("' or '")}', ` +
                             "got 'ellipse'" });
  } finally {
    lens.dispose();
  }
});

// geolens from its npm package, in node: a circle magnified 2x on an 800 x 600 picture, its zoom
// measured, and a point mapped to the screen and back. In a page, createGeolens() needs no
// argument (the browser fetches geolens.wasm beside geolens.mjs); node hands it the bytes.
//   cd web && npm pack && cd example && npm install && node magnify.mjs
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import createGeolens from 'geolens';

const wasmBinary = readFileSync(createRequire(import.meta.url).resolve('geolens/geolens.wasm'));
const engine = await createGeolens({ wasmBinary });
const lens = engine.session({ width: 800, height: 600, mesh: 100 });
const frame = lens.update([{ kind: 'circle', cx: 400, cy: 300, r: 80, zoom: 2 }]);
const { zoomAsked, zoomGot } = frame.lenses[0];
console.log(`zoom asked ${zoomAsked}, got ${zoomGot.toFixed(2)}; ${frame.triangleCount} triangles`);
const screen = lens.forward(new Float64Array([430, 300]));
const source = lens.inverse(screen);
console.log(`(430, 300) is shown at (${screen[0].toFixed(2)}, ${screen[1].toFixed(2)}); ` +
  `back: (${source[0].toFixed(2)}, ${source[1].toFixed(2)})`);
lens.dispose();

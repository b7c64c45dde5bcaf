// The geolens map page (web/demo/map.html): a GeolensView over a Leaflet map of local XYZ tiles,
// with GeoJSON points drawn through the lens and clickable through it.
//
// How: a canvas the size of the map's container, above Leaflet's panes (under its controls),
// shows the map's current view through the lens. The view is composed into an offscreen canvas
// of the container's size: the tile layer's loaded <img> tiles where they are on the screen (the
// tiles are same-origin, so the canvas stays readable), then the points as markers. It is
// composed again, and handed to the view, whenever the map moves, zooms (every frame while
// Leaflet animates) or a tile loads. The lenses are in the container's pixels (times
// devicePixelRatio), so they stay where they are on the screen while the map moves under them.
//
// Pointers: a press on a lens goes to the view (drag it, wheel or pinch its zoom); a press
// elsewhere is kept from the view so that Leaflet gets it (pan, wheel zoom, double-click). A
// click anywhere is picked through the lens: view.pick gives the source point, that is the
// unmagnified container point, whose nearest GeoJSON point (within the marker's reach) is named.
//
// URL parameters: tiles=URL template (default tiles/{z}/{x}/{y}.png, made with
// `./build/make_xyz_tiles web/demo/tiles 4`), maxzoom=the folder's deepest zoom (4),
// points=GeoJSON URL (points.geojson), view=LAT,LNG,ZOOM (0,0,2), lens=circle:CX,CY,R[:ZOOM]
// (container pixels, repeatable; default one of radius 50 at zoom 3 in the middle), lens=none.
// Test hooks: window.__geolensView, window.__map, window.__mapDemo ({ready, settled, points,
// lensAt, compose}); a click sets document.body.dataset.clicked to the point's name ('' for
// none) and dispatches a 'geolens-pick' CustomEvent on window (detail: {name, feature, latlng,
// source, lens}).

import createGeolens from '../dist/geolens.mjs';
import { GeolensView } from '../src/view.js';

const params = new URLSearchParams(location.search);
const TILES = params.get('tiles') || 'tiles/{z}/{x}/{y}.png';
const MAX_NATIVE_ZOOM = Number(params.get('maxzoom') || 4);
const POINTS_URL = params.get('points') || 'points.geojson';
const BACKGROUND = '#0d0e10'; // beyond the world's edge
const MARKER_RADIUS = 4.5; // CSS pixels, unmagnified
const HIT_RADIUS = MARKER_RADIUS + 4; // a click this near a point (unmagnified) names it
const CLICK_SLOP = 5; // CSS pixels a press may move and still be a click

const $ = (id) => document.getElementById(id);
const ui = {
  map: $('map'),
  addLens: $('add-lens'),
  removeLens: $('remove-lens'),
  zoom: $('zoom'),
  zoomValue: $('zoom-value'),
  radius: $('radius'),
  radiusValue: $('radius-value'),
  clicked: $('clicked'),
  status: $('status'),
  error: $('error'),
  points: $('points'),
};

function showError(error) {
  ui.error.textContent = error ? String(error.message || error) : '';
}

const L = window.L;
if (!L) {
  const message = 'Leaflet is missing: run `npm install` in web/ (it loads ' +
    '../node_modules/leaflet/dist/leaflet.js).';
  showError(message);
  throw new Error(message);
}

// ---------------------------------------------------------------------------------------------
// The map

const [lat0, lng0, zoom0] = (params.get('view') || '0,0,2').split(',').map(Number);
const map = L.map(ui.map, {
  center: [lat0, lng0],
  zoom: zoom0,
  minZoom: 1,
  maxZoom: MAX_NATIVE_ZOOM + 2,
  maxBounds: [[-85.06, -180], [85.06, 180]],
});
const tiles = L.tileLayer(TILES, {
  maxNativeZoom: MAX_NATIVE_ZOOM,
  maxZoom: MAX_NATIVE_ZOOM + 2,
  noWrap: true,
  bounds: [[-85.0511, -180], [85.0511, 180]], // no requests beyond the world's edge
  attribution: 'tiles: geolens <code>make_xyz_tiles</code> (an imaginary country)',
});
const tilesLoaded = new Promise((resolve) => tiles.once('load', resolve));
const tileCoords = new WeakMap(); // <img> -> its {x, y, z}
tiles.on('tileload', (e) => tileCoords.set(e.tile, e.coords));
tiles.on('tileerror', (e) => {
  const url = L.Util.template(TILES, e.coords);
  showError(`no tile at ${url}: generate the tiles (./build/make_xyz_tiles web/demo/tiles ` +
    `${MAX_NATIVE_ZOOM}) or pass tiles=URL template and maxzoom=`);
});
tiles.addTo(map);
window.__map = map;

const container = map.getContainer();
const overlay = document.createElement('canvas');
overlay.id = 'lens-overlay';
container.append(overlay);

// ---------------------------------------------------------------------------------------------
// The points

let points = []; // {name, feature, latlng}
let clickedPoint = null;

async function loadPoints() {
  const response = await fetch(POINTS_URL);
  if (!response.ok) throw new Error(`cannot load ${POINTS_URL}: ${response.status}`);
  const collection = await response.json();
  points = (collection.features || [])
    .filter((f) => f.geometry && f.geometry.type === 'Point')
    .map((feature, i) => ({
      name: String((feature.properties && feature.properties.name) ?? `point ${i + 1}`),
      feature,
      latlng: L.latLng(feature.geometry.coordinates[1], feature.geometry.coordinates[0]),
    }));
  ui.points.replaceChildren(...points.map((point) => {
    const item = document.createElement('li');
    const button = document.createElement('button');
    button.type = 'button';
    button.textContent = point.name;
    button.addEventListener('click', () => map.panTo(point.latlng));
    item.append(button);
    point.item = item;
    return item;
  }));
}

// ---------------------------------------------------------------------------------------------
// The picture: the map's view composed, handed to the lens

const picture = document.createElement('canvas');
const paint = picture.getContext('2d', { alpha: false });
let view = null;
let lensMemory = []; // the lenses, kept across a new picture size (which removes them)
let firstLenses = null; // the lenses to start with, added by the next compose()
let composeFrame = 0;
let animating = false; // Leaflet's zoom animation (CSS transitions: no events while they run)
let moving = false; // between 'movestart' and 'moveend'
let fading = false; // tiles fading in (Leaflet changes their opacity every frame, no events)
let tilesDrawn = 0;

function scheduleCompose() {
  if (!composeFrame) composeFrame = requestAnimationFrame(compose);
}

// The picture's pixels per CSS pixel (the view's canvas has as many pixels as the picture).
function pictureScale() {
  return window.devicePixelRatio || 1;
}

// The loaded tiles, the lowest level first (Leaflet stacks the current zoom's level on top), each
// with its place on the screen relative to the container.
function visibleTiles() {
  const box = container.getBoundingClientRect();
  const images = [...container.querySelectorAll('.leaflet-tile-pane img.leaflet-tile-loaded')];
  const level = (img) => Number(img.parentElement.style.zIndex) || 0;
  return images
    .map((img) => ({ img, level: level(img), rect: img.getBoundingClientRect() }))
    .sort((a, b) => a.level - b.level)
    .map(({ img, level, rect }) => ({
      img, level, x: rect.left - box.left, y: rect.top - box.top, width: rect.width,
      height: rect.height, opacity: img.style.opacity === '' ? 1 : Number(img.style.opacity),
    }));
}

// Where a latlng is on the screen (container CSS pixels) as the tiles are drawn: through a tile
// of the top level, so that the markers follow the tiles through Leaflet's zoom animation.
function placer(drawn) {
  const top = drawn.filter((t) => tileCoords.has(t.img)).at(-1);
  if (!top) return (latlng) => map.latLngToContainerPoint(latlng);
  const c = tileCoords.get(top.img), size = tiles.getTileSize();
  const kx = top.width / size.x, ky = top.height / size.y;
  return (latlng) => {
    const p = map.project(latlng, c.z);
    return L.point(top.x + (p.x - c.x * size.x) * kx, top.y + (p.y - c.y * size.y) * ky);
  };
}

function drawMarker(x, y, clicked) {
  const r = clicked ? MARKER_RADIUS + 1.5 : MARKER_RADIUS;
  paint.beginPath();
  paint.arc(x, y, r, 0, 2 * Math.PI);
  paint.lineWidth = 4;
  paint.strokeStyle = 'rgb(20 20 24 / 0.75)';
  paint.stroke();
  paint.lineWidth = 2;
  paint.strokeStyle = '#ffffff';
  paint.stroke();
  paint.fillStyle = clicked ? '#ffb31a' : '#e4572e';
  paint.fill();
}

function compose() {
  composeFrame = 0;
  if (!view) return;
  const scale = pictureScale();
  // As the view sizes its canvas (round(CSS size x devicePixelRatio)).
  const width = Math.max(1, Math.round(overlay.clientWidth * scale));
  const height = Math.max(1, Math.round(overlay.clientHeight * scale));
  if (picture.width !== width || picture.height !== height)
    Object.assign(picture, { width, height });
  paint.setTransform(1, 0, 0, 1, 0, 0);
  paint.fillStyle = BACKGROUND;
  paint.fillRect(0, 0, width, height);
  paint.setTransform(scale, 0, 0, scale, 0, 0);
  paint.imageSmoothingQuality = 'high';
  const drawn = visibleTiles();
  for (const t of drawn) {
    paint.globalAlpha = t.opacity; // Leaflet fades new tiles in over the old ones
    paint.drawImage(t.img, t.x, t.y, t.width, t.height);
  }
  paint.globalAlpha = 1;
  fading = drawn.some((t) => t.opacity < 1);
  const place = placer(drawn);
  for (const point of points) {
    if (point === clickedPoint) continue;
    const p = place(point.latlng);
    drawMarker(p.x, p.y, false);
  }
  if (clickedPoint) {
    const p = place(clickedPoint.latlng);
    drawMarker(p.x, p.y, true);
  }
  const size = view.imageSize;
  const resized = size.width !== width || size.height !== height;
  const lenses = firstLenses || lensMemory;
  view.setImage(picture).catch(showError);
  // A picture of another size starts a new session without lenses: put them back.
  if (resized || firstLenses) restoreLenses(lenses, width, height);
  firstLenses = null;
  tilesDrawn = drawn.length;
  updateStatus();
  if (animating || fading || transitionsRunning()) scheduleCompose();
}

// Leaflet's zoom transitions (CSS) may outlast its 'zoomend' where frames are slow: a running
// transition keeps going after Leaflet takes its class away.
function transitionsRunning() {
  const pane = map.getPane('mapPane');
  return typeof pane.getAnimations === 'function' &&
    pane.getAnimations({ subtree: true }).length > 0;
}

function restoreLenses(lenses, width, height) {
  for (const lens of lenses) {
    const r = Math.min(lens.r, Math.max(4, Math.min(width, height) / 3));
    const cx = Math.min(width, Math.max(0, lens.cx)), cy = Math.min(height, Math.max(0, lens.cy));
    try {
      view.addCircle(cx, cy, r, lens.zoom);
    } catch (error) {
      showError(error);
    }
  }
  lensMemory = view.lenses;
}

map.on('move zoom viewreset resize', scheduleCompose);
map.on('movestart', () => (moving = true));
map.on('moveend', () => {
  moving = false;
  scheduleCompose();
});
map.on('zoomanim', () => {
  animating = true;
  scheduleCompose();
});
map.on('zoomend', () => {
  animating = false;
  scheduleCompose();
});
tiles.on('tileload tileunload load', scheduleCompose);
new ResizeObserver(() => {
  map.invalidateSize({ pan: false });
  scheduleCompose();
}).observe(container);

// ---------------------------------------------------------------------------------------------
// Pointers: the lens's presses to the view, the others to Leaflet

function local(e) {
  const box = overlay.getBoundingClientRect();
  return { x: e.clientX - box.left, y: e.clientY - box.top };
}

// The lens under a canvas point (CSS pixels): the smallest holding the source point shown there.
function lensAt(x, y) {
  if (!view) return -1;
  const p = view.pick(x, y);
  if (!p) return -1;
  let best = -1, bestR = Infinity;
  view.lenses.forEach((lens, i) => {
    if (lens.kind === 'circle' && lens.r < bestR && Math.hypot(p.x - lens.cx, p.y - lens.cy) <=
      lens.r) {
      best = i;
      bestR = lens.r;
    }
  });
  return best;
}

const lensPointers = new Set(); // pointers pressed on a lens (the view's)
let press = null; // the last press's place, for telling clicks from drags

container.addEventListener('pointerdown', (e) => {
  if (e.target !== overlay) return; // Leaflet's controls
  press = { x: e.clientX, y: e.clientY };
  const at = local(e);
  if (lensPointers.size > 0 || lensAt(at.x, at.y) >= 0) {
    lensPointers.add(e.pointerId);
    return;
  }
  // Not on a lens: the view does not see it, so it does not cancel the press and Leaflet gets
  // its mousedown or touchstart (bubbling from the canvas to the container).
  e.stopPropagation();
}, true);
for (const type of ['pointerup', 'pointercancel'])
  window.addEventListener(type, (e) => lensPointers.delete(e.pointerId), true);
// What reaches the container from a press on a lens is not Leaflet's.
overlay.addEventListener('touchstart', (e) => {
  if (lensPointers.size > 0) e.stopPropagation();
}, { passive: true });
overlay.addEventListener('mousedown', (e) => {
  if (lensPointers.size > 0) e.stopPropagation();
});
overlay.addEventListener('dblclick', (e) => {
  const at = local(e);
  if (lensAt(at.x, at.y) >= 0) e.stopPropagation();
});

// A click, through the lens or not.
overlay.addEventListener('click', (e) => {
  if (!press || Math.hypot(e.clientX - press.x, e.clientY - press.y) > CLICK_SLOP) return;
  const at = local(e);
  report(at, lensAt(at.x, at.y));
});

function report(at, lens) {
  if (!view) return;
  const source = view.pick(at.x, at.y);
  if (!source) return;
  const scale = pictureScale();
  const shown = L.point(source.x / scale, source.y / scale); // the unmagnified container point
  const latlng = map.containerPointToLatLng(shown);
  let best = null, bestDistance = HIT_RADIUS;
  for (const point of points) {
    const d = map.latLngToContainerPoint(point.latlng).distanceTo(shown);
    if (d <= bestDistance) {
      best = point;
      bestDistance = d;
    }
  }
  clickedPoint = best;
  const where = `${latlng.lat.toFixed(3)}°, ${latlng.lng.toFixed(3)}°`;
  const through = lens >= 0 ? `through lens ${lens + 1} (${view.lenses[lens].zoom.toFixed(2)}×)`
    : 'outside the lenses';
  ui.clicked.classList.toggle('hit', Boolean(best));
  const title = document.createElement('strong');
  title.textContent = best ? best.name : 'no point here';
  const line = document.createElement('span');
  line.textContent = `${where}, ${through}`;
  ui.clicked.replaceChildren(title, line);
  for (const point of points)
    if (point.item) point.item.classList.toggle('clicked', point === best);
  document.body.dataset.clicked = best ? best.name : '';
  window.dispatchEvent(new CustomEvent('geolens-pick', {
    detail: {
      name: best ? best.name : null,
      feature: best ? best.feature : null,
      latlng,
      source: { x: shown.x, y: shown.y },
      lens,
    },
  }));
  scheduleCompose();
}

// ---------------------------------------------------------------------------------------------
// The panel

const fixed = (v, digits = 2) => (Number.isFinite(v) ? v.toFixed(digits) : '–');

function selectedLens() {
  if (!view) return -1;
  const lenses = view.lenses;
  return view.selectedIndex >= 0 ? view.selectedIndex : lenses.length > 0 ? 0 : -1;
}

function updateControls() {
  const i = selectedLens();
  const lens = i >= 0 ? view.lenses[i] : null;
  ui.zoom.disabled = ui.radius.disabled = ui.removeLens.disabled = !lens;
  if (lens) {
    ui.zoom.value = lens.zoom;
    ui.radius.value = lens.r;
  }
  ui.zoomValue.textContent = lens ? fixed(lens.zoom) + '×' : '–';
  ui.radiusValue.textContent = lens ? `${Math.round(lens.r)} px` : '–';
}

function updateStatus() {
  const frame = view && view.frame;
  const got = frame && frame.lenses.length > 0
    ? frame.lenses.map((l) => `${fixed(l.zoomAsked)}× asked, ${fixed(l.zoomGot)}× got`)
      .join('; ')
    : 'no lens';
  ui.status.textContent = `map zoom ${map.getZoom()}, ${tilesDrawn} tiles shown; ${got}.`;
}

function setLens(changes, moving) {
  const i = selectedLens();
  if (i < 0) return;
  try {
    view.setLens(i, changes, { moving });
  } catch (error) {
    showError(error);
  }
}

for (const type of ['input', 'change']) {
  ui.zoom.addEventListener(type, () => setLens({ zoom: Number(ui.zoom.value) }, type === 'input'));
  ui.radius.addEventListener(type, () => setLens({ r: Number(ui.radius.value) }, type === 'input'));
}

ui.addLens.addEventListener('click', () => {
  const { width, height } = view.imageSize;
  if (!width) return;
  // Round the middle, a little apart from the lenses before it.
  const k = view.lenses.length, scale = pictureScale();
  const reach = k === 0 ? 0 : Math.min(width, height) * 0.25;
  view.addCircle(width / 2 + reach * Math.cos(k * 2.4), height / 2 + reach * Math.sin(k * 2.4),
    50 * scale, 3);
});
ui.removeLens.addEventListener('click', () => {
  const i = selectedLens();
  if (i >= 0) view.removeLens(i);
});

// ---------------------------------------------------------------------------------------------
// Start

// circle:CX,CY,R[:ZOOM], container CSS pixels.
function parseLens(text) {
  const match = /^circle:([^,]+),([^,]+),([^:]+)(?::(.+))?$/.exec(text);
  const numbers = match ? match.slice(1).map((v) => (v === undefined ? 3 : Number(v))) : [];
  if (numbers.length !== 4 || !numbers.every(Number.isFinite))
    throw new Error(`lens '${text}': circle:CX,CY,R[:ZOOM] in the map's pixels, or none`);
  const [cx, cy, r, zoom] = numbers, scale = pictureScale();
  return { kind: 'circle', cx: cx * scale, cy: cy * scale, r: r * scale, zoom };
}

function lensesAsked() {
  const texts = params.getAll('lens');
  if (texts.includes('none')) return [];
  if (texts.length > 0) return texts.map(parseLens);
  const scale = pictureScale();
  return [{ kind: 'circle', cx: (overlay.clientWidth * scale) / 2,
    cy: (overlay.clientHeight * scale) / 2, r: 50 * scale, zoom: 3 }];
}

// Resolves once nothing is pending: the map at rest, its tiles loaded, the picture composed and
// the lens solved and drawn.
async function settled() {
  for (;;) {
    await new Promise((resolve) => requestAnimationFrame(resolve));
    if (animating || moving || fading || composeFrame || tiles.isLoading() || transitionsRunning())
      continue;
    await view.idle();
    if (!composeFrame) return;
  }
}

async function start() {
  const engine = await createGeolens();
  view = new GeolensView(overlay, engine);
  window.__geolensView = view;
  view.addEventListener('frame', () => {
    updateStatus();
    updateControls();
  });
  view.addEventListener('change', (e) => {
    // A new picture size removes the lenses; compose() puts them back.
    if (e.detail.reason !== 'image') lensMemory = view.lenses;
    updateControls();
  });
  view.addEventListener('error', (e) => showError(e.detail.error));
  // Wheel over a lens zooms the lens (the view cancels the event), not the map.
  overlay.addEventListener('wheel', (e) => {
    if (e.defaultPrevented) e.stopPropagation();
  }, { passive: false });
  try {
    await loadPoints();
  } catch (error) {
    showError(error);
  }
  await tilesLoaded;
  firstLenses = lensesAsked();
  compose();
  updateControls();
  await settled();
  document.body.dataset.ready = '1';
}

const ready = start().catch((error) => {
  showError(error);
  throw error;
});
window.__mapDemo = { ready, settled, compose, lensAt, points: () => points, map, tiles };

// The geolens demo page (web/demo/index.html): a GeolensView on the left, a classic magnifier
// (the same region and zoom pasted over the picture, hiding the ring around it) on the right,
// the controls, and the per-lens figures the view reports.
//
// URL parameters (for links and the browser tests): image=URL (default: the repository's
// examples/demo.png), size=WxH (fixed canvas size in CSS pixels), lens=circle:CX,CY,R[:ZOOM] or
// lens=polygon:X,Y;X,Y;...[:ZOOM] (repeatable; source pixels, as the CLI's --lens), model=,
// mesh=, compare=0 (no classic pane), outlines=0, worker=1 (the view solves in a module Worker).
// Test hooks: window.__geolensView (the view), window.__demo ({ready, classic, drawClassic}).

import createGeolens from '../dist/geolens.mjs';
import { GeolensView } from '../src/view.js';

const DEFAULT_IMAGE = new URL('../../examples/demo.png', import.meta.url).href;
const DEFAULT_LENSES = ['circle:300,500,90:2.5'];

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const canvas = $('geolens');
const classic = $('classic');
const ui = {
  file: $('file'),
  addCircle: $('add-circle'),
  drawPolygon: $('draw-polygon'),
  remove: $('remove'),
  model: $('model'),
  mesh: $('mesh'),
  compare: $('compare'),
  zoom: $('zoom'),
  zoomValue: $('zoom-value'),
  footprint: $('footprint'),
  footprintValue: $('footprint-value'),
  table: document.querySelector('#lens-table tbody'),
  status: $('status'),
  pick: $('pick'),
  error: $('error'),
  dropHint: $('drop-hint'),
};

let picture = null; // what the view shows, drawn again by the classic pane

// ---------------------------------------------------------------------------------------------
// Setup from the URL

const size = /^(\d+)x(\d+)$/.exec(params.get('size') || '');
if (size) {
  document.body.classList.add('fixed');
  for (const c of [canvas, classic]) {
    c.style.width = size[1] + 'px';
    c.style.height = size[2] + 'px';
  }
}
if (params.get('compare') === '0') ui.compare.checked = false;
if (params.has('model')) ui.model.value = params.get('model');
if (params.has('mesh')) {
  const mesh = params.get('mesh');
  if (![...ui.mesh.options].some((o) => o.value === mesh)) ui.mesh.add(new Option(mesh, mesh));
  ui.mesh.value = mesh;
}

// circle:CX,CY,R[:ZOOM] or polygon:X,Y;X,Y;...[:ZOOM]
function parseLens(text) {
  const [kind, body, zoom = '2'] = text.split(':');
  const numbers = body.split(/[,;]/).map(Number);
  if (kind === 'circle' && numbers.length === 3)
    return { kind, cx: numbers[0], cy: numbers[1], r: numbers[2], zoom: Number(zoom) };
  if (kind === 'polygon' && numbers.length >= 6)
    return { kind, points: numbers, zoom: Number(zoom) };
  throw new Error(`lens '${text}': circle:CX,CY,R[:ZOOM] or polygon:X,Y;X,Y;...[:ZOOM]`);
}

function addLens(lens) {
  if (lens.kind === 'circle') view.addCircle(lens.cx, lens.cy, lens.r, lens.zoom);
  else view.addPolygon(lens.points, lens.zoom);
}

const useWorker = params.get('worker') === '1';
const engine = useWorker ? null : await createGeolens();
const view = new GeolensView(canvas, engine, {
  model: ui.model.value,
  mesh: Number(ui.mesh.value),
  outlines: params.get('outlines') !== '0',
  ...(useWorker ? { worker: true } : {}),
});
window.__geolensView = view;

// ---------------------------------------------------------------------------------------------
// The picture

function loadImage(url) {
  return new Promise((resolve, reject) => {
    const image = new Image();
    image.onload = () => resolve(image);
    image.onerror = () => reject(new Error(`cannot load ${url}`));
    image.src = url;
  });
}

// A stand-in picture when the default one cannot be loaded (the page served without the
// repository around it): a grid with labels, which shows what the lens does.
function fallbackPicture() {
  const c = document.createElement('canvas');
  c.width = 800;
  c.height = 600;
  const g = c.getContext('2d');
  g.fillStyle = '#f4f1ea';
  g.fillRect(0, 0, c.width, c.height);
  g.strokeStyle = '#b9b2a3';
  g.fillStyle = '#444';
  g.font = '9px sans-serif';
  for (let x = 0; x <= c.width; x += 40) {
    for (let y = 0; y <= c.height; y += 40) {
      g.strokeRect(x + 0.5, y + 0.5, 40, 40);
      g.fillText(`${x / 40},${y / 40}`, x + 4, y + 14);
    }
  }
  return c;
}

async function show(source, lenses) {
  picture = source;
  await view.setImage(source);
  for (const lens of lenses) {
    try {
      addLens(lens);
    } catch (error) {
      showError(error);
    }
  }
  drawClassic();
}

async function openFile(file) {
  if (!file) return;
  const url = URL.createObjectURL(file);
  try {
    let source;
    if (file.type.startsWith('video/')) {
      source = document.createElement('video');
      Object.assign(source, { src: url, muted: true, loop: true, playsInline: true });
      await source.play();
    } else {
      source = await loadImage(url);
    }
    const [w, h] = source.videoWidth ? [source.videoWidth, source.videoHeight]
      : [source.naturalWidth, source.naturalHeight];
    await show(source, [{ kind: 'circle', cx: w / 2, cy: h / 2, r: defaultRadius(w, h), zoom: 2 }]);
  } catch (error) {
    showError(error);
  }
}

function defaultRadius(w, h) {
  return Math.max(8, Math.round(0.08 * Math.min(w, h)));
}

// ---------------------------------------------------------------------------------------------
// The classic magnifier: the picture, then each lens's region magnified about its centre by the
// zoom geolens got for it and pasted over it (clipped to the magnified region), as insets do.

function regionCentre(lens) {
  if (lens.kind === 'circle') return [lens.cx, lens.cy];
  const p = lens.points;
  let a = 0, cx = 0, cy = 0;
  for (let i = 0; i < p.length; i += 2) {
    const j = (i + 2) % p.length;
    const cross = p[i] * p[j + 1] - p[j] * p[i + 1];
    a += cross;
    cx += (p[i] + p[j]) * cross;
    cy += (p[i + 1] + p[j + 1]) * cross;
  }
  return [cx / (3 * a), cy / (3 * a)];
}

function regionPath(g, lens) {
  g.beginPath();
  if (lens.kind === 'circle') {
    g.arc(lens.cx, lens.cy, lens.r, 0, 2 * Math.PI);
  } else {
    for (let i = 0; i < lens.points.length; i += 2) g.lineTo(lens.points[i], lens.points[i + 1]);
    g.closePath();
  }
}

let classicPending = 0;
function drawClassic() {
  if (classicPending) return;
  classicPending = requestAnimationFrame(() => {
    classicPending = 0;
    paintClassic();
  });
}

function paintClassic() {
  if (!ui.compare.checked || !picture) return;
  const dpr = window.devicePixelRatio || 1;
  const W = Math.max(1, Math.round(classic.clientWidth * dpr));
  const H = Math.max(1, Math.round(classic.clientHeight * dpr));
  if (classic.width !== W || classic.height !== H) Object.assign(classic, { width: W, height: H });
  const { width: iw, height: ih } = view.imageSize;
  const g = classic.getContext('2d');
  g.setTransform(1, 0, 0, 1, 0, 0);
  g.clearRect(0, 0, W, H);
  if (!iw) return;
  const s = Math.min(W / iw, H / ih);
  const ox = Math.round((W - iw * s) / 2), oy = Math.round((H - ih * s) / 2);
  g.imageSmoothingQuality = 'high';
  g.setTransform(s, 0, 0, s, ox, oy);
  g.drawImage(picture, 0, 0, iw, ih);
  const figures = view.frame ? view.frame.lenses : [];
  view.lenses.forEach((lens, i) => {
    const [cx, cy] = regionCentre(lens);
    // The zoom geolens got (what the left pane shows), so that both show the same focus.
    const got = figures[i] ? figures[i].zoomGot : NaN;
    const z = Number.isFinite(got) && got >= 1 ? got : lens.zoom;
    // Source point p shown at c + z (p - c), clipped to the region magnified.
    g.save();
    g.setTransform(s * z, 0, 0, s * z, ox + s * cx * (1 - z), oy + s * cy * (1 - z));
    regionPath(g, lens);
    g.clip();
    g.drawImage(picture, 0, 0, iw, ih);
    g.restore();
    g.save();
    g.setTransform(s * z, 0, 0, s * z, ox + s * cx * (1 - z), oy + s * cy * (1 - z));
    regionPath(g, lens); // the path keeps the transform it was made with
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.lineWidth = 5 * dpr;
    g.strokeStyle = 'rgb(0 0 0 / 0.55)';
    g.stroke();
    g.lineWidth = (i === view.selectedIndex ? 3 : 1.8) * dpr;
    g.strokeStyle = i === view.selectedIndex ? '#ffb31a' : 'white';
    g.stroke();
    g.restore();
  });
}

new ResizeObserver(drawClassic).observe(classic);

// ---------------------------------------------------------------------------------------------
// The panel

const fixed = (v, digits = 2) => (Number.isFinite(v) ? v.toFixed(digits) : '–');

function showError(error) {
  ui.error.textContent = error ? String(error.message || error) : '';
}

function updateControls() {
  const i = view.selectedIndex;
  const lens = i >= 0 ? view.lenses[i] : null;
  ui.zoom.disabled = ui.footprint.disabled = ui.remove.disabled = !lens;
  if (lens) {
    ui.zoom.value = lens.zoom;
    ui.zoomValue.textContent = fixed(lens.zoom) + '×';
    const ratio = lens.footprint > 0 ? lens.footprint / lens.zoom : 1;
    ui.footprint.value = ratio;
    ui.footprintValue.textContent = lens.footprint > 0 ? fixed(ratio) + '×' : 'auto';
  } else {
    ui.zoomValue.textContent = ui.footprintValue.textContent = '–';
  }
  const drawing = view.mode === 'polygon';
  ui.drawPolygon.classList.toggle('active', drawing);
  ui.drawPolygon.textContent = drawing ? 'Finish polygon' : 'Draw polygon';
  document.querySelectorAll('#lens-table tbody tr').forEach((row, k) => {
    row.classList.toggle('selected', k === i);
  });
}

function updateTable(frame) {
  const lenses = view.lenses;
  ui.table.replaceChildren(
    ...frame.lenses.map((figures, k) => {
      const row = document.createElement('tr');
      const lens = lenses[k];
      const note = figures.reason
        ? `fits ${fixed(figures.zoomFit)}×: ${figures.reason}`
        : '';
      for (const [text, cls] of [
        [String(k + 1)],
        [lens ? lens.kind : ''],
        [fixed(figures.zoomAsked) + '×'],
        [fixed(figures.zoomGot) + '×'],
        [note, 'note'],
      ]) {
        const cell = document.createElement('td');
        cell.textContent = text;
        if (cls) cell.className = cls;
        row.append(cell);
      }
      row.classList.toggle('selected', k === view.selectedIndex);
      row.addEventListener('click', () => (view.selectedIndex = k));
      return row;
    }),
  );
  ui.status.textContent =
    `${frame.draft ? 'draft' : 'full'} mesh (${frame.model}), ${frame.vertexCount} vertices, ` +
    `solved in ${fixed(frame.solveMs, 1)} ms. Shape distortion (s1/s2 − 1): mean ` +
    `${fixed(frame.shapeMean, 3)}, max ${fixed(frame.shapeMax, 2)}; ${frame.flipped} flipped.`;
}

view.addEventListener('frame', (e) => {
  updateTable(e.detail);
  updateControls();
  drawClassic();
  if (!e.detail.draft) showError(null);
});
view.addEventListener('change', () => {
  updateControls();
  drawClassic();
});
view.addEventListener('error', (e) => showError(e.detail.error));

canvas.addEventListener('pointermove', (e) => {
  const rect = canvas.getBoundingClientRect();
  const p = view.pick(e.clientX - rect.left, e.clientY - rect.top);
  ui.pick.textContent = p ? `under the pointer: source (${fixed(p.x, 1)}, ${fixed(p.y, 1)})` : '';
});

ui.file.addEventListener('change', () => openFile(ui.file.files[0]));
ui.addCircle.addEventListener('click', () => {
  const { width: w, height: h } = view.imageSize;
  if (!w) return;
  const k = view.lenses.length;
  const r = defaultRadius(w, h);
  // Round the centre, a little apart from the lenses before it.
  const angle = k * 2.4;
  const reach = k === 0 ? 0 : Math.min(w, h) * 0.25;
  const cx = Math.min(w - r, Math.max(r, w / 2 + reach * Math.cos(angle)));
  const cy = Math.min(h - r, Math.max(r, h / 2 + reach * Math.sin(angle)));
  view.addCircle(Math.round(cx), Math.round(cy), r, 2);
  canvas.focus(); // so that Delete reaches the view
});
ui.drawPolygon.addEventListener('click', () => {
  if (view.mode === 'polygon') view.finishPolygon();
  else view.drawPolygon(2);
  canvas.focus();
});
ui.remove.addEventListener('click', () => {
  if (view.selectedIndex >= 0) view.removeLens(view.selectedIndex);
});
const CAPTIONS = {
  focus: 'geolens: the region magnified as a whole, the context giving way around it',
  lift: "geolens, the paper's lift: the region lifted into a bump, its zoom at the peak",
  field: 'geolens, field: the lift as a zoom field, its zoom at the peak',
};
function showModel() {
  $('geolens-caption').textContent = CAPTIONS[ui.model.value] || CAPTIONS.focus;
}
showModel();
ui.model.addEventListener('change', () => {
  view.setOptions({ model: ui.model.value });
  showModel();
});
ui.mesh.addEventListener('change', () => view.setOptions({ mesh: Number(ui.mesh.value) }));
ui.compare.addEventListener('change', () => {
  $('classic-pane').hidden = !ui.compare.checked;
  drawClassic();
});
$('classic-pane').hidden = !ui.compare.checked;

function footprintFor(ratio, zoom) {
  return ratio <= 1 ? 0 : Math.min(100, ratio * zoom);
}

function setSelected(changes, moving) {
  const i = view.selectedIndex;
  if (i < 0) return;
  try {
    view.setLens(i, changes, { moving });
  } catch (error) {
    showError(error);
  }
}

for (const type of ['input', 'change']) {
  ui.zoom.addEventListener(type, () => {
    const lens = view.lenses[view.selectedIndex];
    if (!lens) return;
    const zoom = Number(ui.zoom.value);
    const ratio = lens.footprint > 0 ? lens.footprint / lens.zoom : 1;
    setSelected({ zoom, footprint: footprintFor(ratio, zoom) }, type === 'input');
  });
  ui.footprint.addEventListener(type, () => {
    const lens = view.lenses[view.selectedIndex];
    if (!lens) return;
    setSelected({ footprint: footprintFor(Number(ui.footprint.value), lens.zoom) },
      type === 'input');
  });
}

// Drop an image anywhere on the page.
let dragDepth = 0;
window.addEventListener('dragenter', (e) => {
  e.preventDefault();
  dragDepth += 1;
  ui.dropHint.hidden = false;
});
window.addEventListener('dragleave', () => {
  dragDepth = Math.max(0, dragDepth - 1);
  if (dragDepth === 0) ui.dropHint.hidden = true;
});
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  ui.dropHint.hidden = true;
  openFile(e.dataTransfer.files[0]);
});

// ---------------------------------------------------------------------------------------------
// Start

async function start() {
  const lensTexts = params.getAll('lens');
  const lenses = (lensTexts.length > 0 || params.has('image') ? lensTexts : DEFAULT_LENSES)
    .map(parseLens);
  let source;
  try {
    source = await loadImage(params.get('image') || DEFAULT_IMAGE);
  } catch (error) {
    showError(error);
    source = fallbackPicture();
  }
  await show(source, lenses);
  await view.idle();
  document.body.dataset.ready = '1';
}

const ready = start();
window.__demo = { ready, classic, drawClassic, paintClassic };

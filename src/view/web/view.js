// pathlab view's page: polls /api/status, fetches the tone-mapped images when
// a pass finishes or the display changes, and draws them with nearest-
// neighbour magnification (docs/view.md).
'use strict';

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const ctx = canvas.getContext('2d');
const state = {
  status: null, images: { a: null, b: null }, shown: '', loading: false,
  zoom: 0, panX: 0, panY: 0, split: 0.5, swapped: false, drag: null,
  updates: 0,  // images drawn, for tests
};
window.pathlabView = state;

async function api(path, body) {
  const init = body === undefined ? {} :
    { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) };
  const res = await fetch(path, init);
  if (res.status === 204) return null;  // nothing yet: the first pass has not landed
  const json = await res.json();
  if (!res.ok) throw new Error(json.error || res.statusText);
  return json;
}

function format(n) {
  if (n >= 1e9) return (n / 1e9).toFixed(2) + ' G';
  if (n >= 1e6) return (n / 1e6).toFixed(2) + ' M';
  if (n >= 1e3) return (n / 1e3).toFixed(1) + ' k';
  return n.toFixed(0) + ' ';
}

function showStatus(s) {
  // At equal time A and B have counts of their own.
  const b = !s.compare ? '' : s.equal === 'time' ? ` (${s.spp} spp) vs ${s.compare} (${s.spp_b} spp)` :
    ` vs ${s.compare}`;
  const spp = s.compare && s.equal === 'time' ? 'equal time' : `${s.spp} spp`;
  $('stats').textContent = `${s.sampler}${b} · ${spp} · ${format(s.paths_per_second)}paths/s` +
    ` · ${s.elapsed.toFixed(1)} s · ${s.width}×${s.height}` + (s.paused ? ' · paused' :
    s.running ? '' : ' · done');
  $('error').textContent = s.error || '';
  $('pause').textContent = s.paused ? 'Resume' : 'Pause';
  for (const key of ['scene', 'seed', 'max_depth', 'equal', 'exposure', 'tone_map']) {
    const el = $(key);
    if (document.activeElement !== el) el.value = s[key];
  }
  $('sampler').value = s.sampler;
  $('compare').value = s.compare || '';
  $('russian_roulette').checked = s.russian_roulette;
  $('light_sampler').value = s.light_sampler || '';
  $('spectral').checked = s.spectral;
  $('exposure_value').textContent = Number(s.exposure).toFixed(2);
  for (const id of ['relse', 'flip']) $('map').querySelector(`[value=${id}]`).disabled = !s.reference;
  showReference(s);
  const which = $('points_which');
  if (s.compare && which.options.length === 1) which.add(new Option('B', 'b'));
  if (!s.compare && which.options.length === 2) which.remove(1);
  which.options[0].textContent = `A ${s.sampler}`;
  if (s.compare) which.options[1].textContent = `B ${s.compare}`;
}

// The reference the error is measured against: a file, the study's cache, or
// one the page asked for (POST /api/reference), with the progress of a build.
function showReference(s) {
  const building = s.reference_progress !== null && s.reference_progress !== undefined;
  const bar = $('reference_progress');
  bar.hidden = !building;
  if (building) bar.value = s.reference_progress;
  const spp = s.reference_spp ? `${s.reference_spp} spp, ` : '';
  $('reference_info').textContent = s.reference_error ? `build failed: ${s.reference_error}` :
    building ? `building: ${Math.round(100 * s.reference_progress)}%` :
    s.reference ? `${spp}from ${s.reference_source === 'page' ? 'this page' : 'the ' + s.reference_source}` :
    'none for these settings';
}

// The display: the image, or its error against the reference (GET
// /api/image's map).
function mapShown(s) { return s.reference ? $('map').value : 'image'; }

async function fetchImage(which, map) {
  const res = await fetch(`/api/image?which=${which}&format=png&map=${map}&t=${Date.now()}`);
  if (!res.ok || res.status === 204) return null;  // 204: no pass yet
  return createImageBitmap(await res.blob());
}

async function refreshImages(s) {
  const map = mapShown(s);
  const key = [s.generation, s.spp, s.spp_b, s.exposure, s.tone_map, map].join('/');
  if (state.loading || key === state.shown || s.spp === 0) return;
  state.loading = true;
  try {
    // At equal time B's first pass may not have landed yet.
    const [a, b] = await Promise.all([fetchImage('a', map),
      s.compare && s.spp_b > 0 ? fetchImage('b', map) : null]);
    if (a) {
      state.images = { a, b };
      state.shown = key;
      state.updates++;
      if (state.zoom === 0) fit();
      draw();
      if (!$('points_count').value) refreshPoints(points.pixel);  // the count follows spp
    }
  } finally {
    state.loading = false;
  }
}

// The log-log plot of /api/error: each curve scaled to the plot's decades,
// with a line of slope −1 (error ∝ 1/spp, plain Monte Carlo) through A's
// first MSE for comparison.
function plotError(e) {
  const c = $('error_plot'), g = c.getContext('2d'), W = c.width, H = c.height, m = 18;
  g.clearRect(0, 0, W, H);
  // B's own counts: at equal time they differ from A's.
  const sppB = e.b.spp && e.b.spp.length ? e.b.spp : e.spp;
  const series = [[e.spp, e.a.mse, '#4af', []], [sppB, e.b.mse, '#fa4', []],
    [e.spp, e.a.flip, '#4af', [4, 3]], [sppB, e.b.flip, '#fa4', [4, 3]]]
    .filter(([x, v]) => v.length === x.length && v.length > 0);
  const values = series.flatMap(([, v]) => v).filter((v) => v > 0);
  if (!values.length) return;
  const lx = (spp) => Math.log2(spp), ly = (v) => Math.log10(v);
  const last = Math.max(...series.map(([x]) => x[x.length - 1]));
  const x0 = 0, x1 = Math.max(1, lx(last));
  const y0 = Math.floor(ly(Math.min(...values))), y1 = Math.ceil(ly(Math.max(...values)));
  const px = (spp) => m + (lx(spp) - x0) / (x1 - x0) * (W - 2 * m);
  const py = (v) => H - m - (ly(v) - y0) / Math.max(1, y1 - y0) * (H - 2 * m);
  g.strokeStyle = '#555';
  g.strokeRect(m, m, W - 2 * m, H - 2 * m);
  g.fillStyle = '#999';
  g.font = '10px system-ui';
  g.fillText(`1e${y1}`, 0, m - 4);
  g.fillText(`1e${y0}`, 0, H - 4);
  g.fillText(`${last} spp`, W - m - 40, H - 4);
  const first = e.a.mse[0];
  g.strokeStyle = '#888';
  g.setLineDash([]);
  g.beginPath();
  g.moveTo(px(1), py(first));
  g.lineTo(px(last), py(first / last));
  g.stroke();
  for (const [x, v, colour, dash] of series) {
    g.strokeStyle = colour;
    g.setLineDash(dash);
    g.beginPath();
    v.forEach((y, i) => (i ? g.lineTo : g.moveTo).call(g, px(x[i]), py(Math.max(y, 1e-30))));
    g.stroke();
  }
  g.setLineDash([]);
}

async function refreshError(s) {
  $('error_panel').hidden = !s.reference;
  if (!s.reference) return;
  const key = `${s.generation}/${s.spp}/${s.spp_b}`;
  if (key === state.errorShown) return;
  state.errorShown = key;
  const e = await api('/api/error');
  state.errorPoints = e.spp.length;
  plotError(e);
}

async function poll() {
  try {
    const s = await api('/api/status');
    state.status = s;
    showStatus(s);
    await refreshImages(s);
    await refreshError(s);
  } catch (e) {
    $('stats').textContent = 'disconnected';
  }
  setTimeout(poll, 200);
}

function sideBySide() { return $('layout').value === 'side' && state.images.b; }

function fit() {
  const a = state.images.a;
  if (!a) return;
  const w = canvas.clientWidth, h = canvas.clientHeight;
  const across = sideBySide() ? 2 * a.width + 8 : a.width;
  state.zoom = Math.min(w / across, h / a.height);
  if (state.zoom >= 1) state.zoom = Math.floor(state.zoom);
  state.panX = (w - across * state.zoom) / 2;
  state.panY = (h - a.height * state.zoom) / 2;
}

function draw() {
  const dpr = window.devicePixelRatio || 1;
  canvas.width = canvas.clientWidth * dpr;
  canvas.height = canvas.clientHeight * dpr;
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.imageSmoothingEnabled = false;  // pixel-exact magnification
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  let { a, b } = state.images;
  if (!a) return;
  if (state.swapped && b) [a, b] = [b, a];
  const z = state.zoom, w = a.width * z, h = a.height * z;
  if (sideBySide()) {
    ctx.drawImage(a, state.panX, state.panY, w, h);
    ctx.drawImage(b, state.panX + w + 8 * z, state.panY, w, h);
    return;
  }
  ctx.drawImage(a, state.panX, state.panY, w, h);
  if (!b) return;
  const sx = state.panX + state.split * w;
  ctx.save();
  ctx.beginPath();
  ctx.rect(sx, 0, canvas.clientWidth, canvas.clientHeight);
  ctx.clip();
  ctx.drawImage(b, state.panX, state.panY, w, h);
  ctx.restore();
  ctx.fillStyle = '#fff';
  ctx.fillRect(sx - 1, state.panY, 2, h);
  const s = state.status;
  const label = (name, spp) => s.equal === 'time' ? `${name} · ${spp} spp` : name;
  const names = [label(s.sampler, s.spp), label(s.compare, s.spp_b)];
  if (state.swapped) names.reverse();
  ctx.font = '12px system-ui';
  ctx.fillText(names[0], state.panX + 4, state.panY + 14);
  ctx.fillText(names[1], sx + 4, state.panY + 14);
}

// The image pixel under a canvas position, or null.
function pixelAt(cx, cy) {
  const a = state.images.a;
  if (!a) return null;
  let x = Math.floor((cx - state.panX) / state.zoom), y = Math.floor((cy - state.panY) / state.zoom);
  if (sideBySide() && x >= a.width + 8) x -= a.width + 8;
  return x >= 0 && y >= 0 && x < a.width && y < a.height ? { x, y } : null;
}

let pixelRequest = 0;
async function showPixel(p) {
  if (!p) return;
  const id = ++pixelRequest;
  try {
    const v = await api(`/api/pixel?x=${p.x}&y=${p.y}`);
    if (id !== pixelRequest || !v) return;
    const rgb = (c) => c ? c.map((x) => x.toPrecision(5)).join(' ') : '—';
    const s = state.status;
    const sppB = v.b && v.spp_b !== v.spp ? ` (${v.spp_b} spp)` : '';
    $('pixel').textContent = `(${v.x}, ${v.y}) at ${v.spp} spp\nA ${s.sampler}: ${rgb(v.a)}` +
      (v.b ? `\nB ${s.compare}${sppB}: ${rgb(v.b)}` : '');
  } catch (e) { /* the image is between generations */ }
}

// The points panel: GET /api/points for the pixel under the cursor (or the
// one pinned by a click), drawn as a scatter in [0,1)² and as the
// periodogram of the points (log power, grey: white noise; dark: less power,
// the hole of blue noise round the centre) with its radial average (yellow;
// dashed: white noise, 1). One request at a time; the latest pixel wins.
const points = { pixel: null, pinned: false, busy: false, pending: false, key: '' };
state.pointsDrawn = 0;  // for tests

function pointsQuery(p) {
  const count = $('points_count').value;
  return `/api/points?pixel=${p.x},${p.y}&dims=${$('points_x').value},${$('points_y').value}` +
    `&which=${$('points_which').value}` + (count ? `&count=${count}` : '');
}

async function refreshPoints(p) {
  if (!p) return;
  points.pixel = p;
  if (points.busy) { points.pending = true; return; }
  const query = pointsQuery(p), key = `${query}/${state.shown}`;
  if (key === points.key) return;
  points.busy = true;
  try {
    const r = await api(query);
    if (r) {  // null before the first image
      points.key = key;
      drawPoints(r);
    }
  } catch (e) {
    $('points_caption').textContent = e.message;
  } finally {
    points.busy = false;
    if (points.pending) { points.pending = false; refreshPoints(points.pixel); }
  }
}

function drawPoints(r) {
  const c = $('points_plot'), g = c.getContext('2d'), W = c.width, H = c.height;
  g.fillStyle = '#111';
  g.fillRect(0, 0, W, H);
  g.strokeStyle = '#555';
  g.strokeRect(0.5, 0.5, W - 1, H - 1);
  g.fillStyle = '#9cf';
  const size = Math.max(1, Math.min(4, W / Math.sqrt(r.count) / 4));
  for (const [x, y] of r.points) g.fillRect(x * W - size / 2, (1 - y) * H - size / 2, size, size);
  drawSpectrum(r.spectrum_image, r.spectrum.radial);
  $('points_caption').textContent = `${r.sampler} at (${r.pixel}), dims ${r.dims.join(', ')}: ` +
    `${r.count} points${points.pinned ? ' (pinned; click to follow the cursor)' : ''}`;
  state.pointsDrawn++;
}

function drawSpectrum(image, radial) {
  const c = $('points_spectrum'), g = c.getContext('2d'), W = c.width, H = c.height;
  const n = image.size, pixels = new ImageData(n, n);
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) {
      // log10 power −1 … 1 as black … white, frequency y upwards.
      const v = image.log10_power[(n - 1 - y) * n + x];
      const grey = Math.max(0, Math.min(255, Math.round((v + 1) * 127.5))), i = 4 * (y * n + x);
      pixels.data[i] = pixels.data[i + 1] = pixels.data[i + 2] = grey;
      pixels.data[i + 3] = 255;
    }
  }
  const tile = document.createElement('canvas');
  tile.width = tile.height = n;
  tile.getContext('2d').putImageData(pixels, 0, 0);
  g.imageSmoothingEnabled = false;
  g.drawImage(tile, 0, 0, W, H);
  // The radial average up to the image's frequency, power 0 … 2.
  const f = image.max_frequency, py = (v) => H - Math.min(v, 2) / 2 * H;
  g.strokeStyle = '#ccc';
  g.setLineDash([4, 3]);
  g.beginPath();
  g.moveTo(0, py(1));
  g.lineTo(W, py(1));
  g.stroke();
  g.setLineDash([]);
  g.strokeStyle = '#fd4';
  g.beginPath();
  for (let r = 1; r <= f && r < radial.length; r++) {
    (r === 1 ? g.moveTo : g.lineTo).call(g, r / f * W, py(radial[r]));
  }
  g.stroke();
}

function onSplitLine(cx) {
  const a = state.images.a;
  return a && state.images.b && !sideBySide() &&
    Math.abs(cx - (state.panX + state.split * a.width * state.zoom)) < 6;
}

canvas.addEventListener('mousedown', (e) => {
  state.drag = { split: onSplitLine(e.offsetX), x: e.offsetX, y: e.offsetY, moved: false };
});
window.addEventListener('mouseup', () => { state.dragged = state.drag && state.drag.moved; state.drag = null; });
canvas.addEventListener('click', (e) => {
  if (state.dragged) return;
  const p = pixelAt(e.offsetX, e.offsetY);
  points.pinned = !points.pinned && p !== null;
  if (p) refreshPoints(p);
});
canvas.addEventListener('mousemove', (e) => {
  const d = state.drag;
  if (d) d.moved = true;
  if (d && d.split) {
    const w = state.images.a.width * state.zoom;
    state.split = Math.min(1, Math.max(0, (e.offsetX - state.panX) / w));
    draw();
  } else if (d) {
    state.panX += e.offsetX - d.x, state.panY += e.offsetY - d.y;
    d.x = e.offsetX, d.y = e.offsetY;
    draw();
  }
  canvas.style.cursor = onSplitLine(e.offsetX) ? 'ew-resize' : 'crosshair';
  const p = pixelAt(e.offsetX, e.offsetY);
  showPixel(p);
  if (!points.pinned && !d) refreshPoints(p);
});
canvas.addEventListener('wheel', (e) => {
  e.preventDefault();
  const factor = e.deltaY < 0 ? 2 : 0.5, z = state.zoom * factor;
  if (z < 1 / 16 || z > 256) return;
  state.panX = e.offsetX - (e.offsetX - state.panX) * factor;
  state.panY = e.offsetY - (e.offsetY - state.panY) * factor;
  state.zoom = z;
  draw();
}, { passive: false });
window.addEventListener('keydown', (e) => {
  if (e.target.tagName === 'INPUT' || e.target.tagName === 'SELECT') return;
  if (e.key === 's') { state.swapped = !state.swapped; draw(); }
  if (e.key === '0') { fit(); draw(); }
});
window.addEventListener('resize', () => { fit(); draw(); });

async function change(settings) {
  try {
    const s = await api('/api/settings', settings);
    $('error').textContent = '';
    state.status = s;
    showStatus(s);
  } catch (e) {
    $('error').textContent = e.message;
  }
}

function wireControls() {
  const number = (id) => $(id).addEventListener('change', () => change({ [id]: Number($(id).value) }));
  number('max_depth');
  $('seed').addEventListener('change', () => change({ seed: $('seed').value }));
  $('scene').addEventListener('change', () => change({ scene: $('scene').value }));
  $('sampler').addEventListener('change', () => change({ sampler: $('sampler').value }));
  $('compare').addEventListener('change', () => change({ compare: $('compare').value || null }));
  $('equal').addEventListener('change', () => change({ equal: $('equal').value }));
  $('russian_roulette').addEventListener('change',
    () => change({ russian_roulette: $('russian_roulette').checked }));
  $('light_sampler').addEventListener('change',
    () => change({ light_sampler: $('light_sampler').value || null }));
  $('spectral').addEventListener('change', () => change({ spectral: $('spectral').checked }));
  $('exposure').addEventListener('input', () => change({ exposure: Number($('exposure').value) }));
  $('tone_map').addEventListener('change', () => change({ tone_map: $('tone_map').value }));
  $('pause').addEventListener('click', () => change({ paused: !state.status.paused }));
  $('reset').addEventListener('click', () => api('/api/reset', {}));
  $('reference_build').addEventListener('click', () =>
    api('/api/reference', { spp: Number($('reference_spp').value) })
      .then(showStatus).catch((e) => { $('error').textContent = e.message; }));
  $('layout').addEventListener('change', () => { fit(); draw(); });
  $('map').addEventListener('change', () => state.status && refreshImages(state.status));
  for (const id of ['points_which', 'points_x', 'points_y', 'points_count'])
    $(id).addEventListener('change', () => refreshPoints(points.pixel));
}

async function start() {
  const options = await api('/api/options');
  for (const s of options.samplers) {
    for (const id of ['sampler', 'compare']) {
      const o = document.createElement('option');
      o.value = o.textContent = s.name;
      o.title = s.description;
      $(id).appendChild(o);
    }
  }
  for (const name of options.scenes) {
    const o = document.createElement('option');
    o.value = name;
    $('scenes').appendChild(o);
  }
  wireControls();
  poll();
}
start();

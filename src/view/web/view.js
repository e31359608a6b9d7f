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
  const b = s.compare ? ` vs ${s.compare}` : '';
  $('stats').textContent = `${s.sampler}${b} · ${s.spp} spp · ${format(s.paths_per_second)}paths/s` +
    ` · ${s.elapsed.toFixed(1)} s · ${s.width}×${s.height}` + (s.paused ? ' · paused' :
    s.running ? '' : ' · done');
  $('error').textContent = s.error || '';
  $('pause').textContent = s.paused ? 'Resume' : 'Pause';
  for (const key of ['scene', 'seed', 'max_depth', 'exposure', 'tone_map']) {
    const el = $(key);
    if (document.activeElement !== el) el.value = s[key];
  }
  $('sampler').value = s.sampler;
  $('compare').value = s.compare || '';
  $('russian_roulette').checked = s.russian_roulette;
  $('exposure_value').textContent = Number(s.exposure).toFixed(2);
}

async function fetchImage(which) {
  const res = await fetch(`/api/image?which=${which}&format=png&t=${Date.now()}`);
  if (!res.ok) return null;
  return createImageBitmap(await res.blob());
}

async function refreshImages(s) {
  const key = [s.generation, s.spp, s.exposure, s.tone_map].join('/');
  if (state.loading || key === state.shown || s.spp === 0) return;
  state.loading = true;
  try {
    const [a, b] = await Promise.all([fetchImage('a'), s.compare ? fetchImage('b') : null]);
    if (a) {
      state.images = { a, b };
      state.shown = key;
      state.updates++;
      if (state.zoom === 0) fit();
      draw();
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
  const series = [[e.a.mse, '#4af', []], [e.b.mse, '#fa4', []], [e.a.flip, '#4af', [4, 3]],
    [e.b.flip, '#fa4', [4, 3]]].filter(([v]) => v.length === e.spp.length && v.length > 0);
  const values = series.flatMap(([v]) => v).filter((v) => v > 0);
  if (!values.length) return;
  const lx = (spp) => Math.log2(spp), ly = (v) => Math.log10(v);
  const x0 = 0, x1 = Math.max(1, lx(e.spp[e.spp.length - 1]));
  const y0 = Math.floor(ly(Math.min(...values))), y1 = Math.ceil(ly(Math.max(...values)));
  const px = (spp) => m + (lx(spp) - x0) / (x1 - x0) * (W - 2 * m);
  const py = (v) => H - m - (ly(v) - y0) / Math.max(1, y1 - y0) * (H - 2 * m);
  g.strokeStyle = '#555';
  g.strokeRect(m, m, W - 2 * m, H - 2 * m);
  g.fillStyle = '#999';
  g.font = '10px system-ui';
  g.fillText(`1e${y1}`, 0, m - 4);
  g.fillText(`1e${y0}`, 0, H - 4);
  g.fillText(`${e.spp[e.spp.length - 1]} spp`, W - m - 40, H - 4);
  const first = e.a.mse[0], last = e.spp[e.spp.length - 1];
  g.strokeStyle = '#888';
  g.setLineDash([]);
  g.beginPath();
  g.moveTo(px(1), py(first));
  g.lineTo(px(last), py(first / last));
  g.stroke();
  for (const [v, colour, dash] of series) {
    g.strokeStyle = colour;
    g.setLineDash(dash);
    g.beginPath();
    v.forEach((y, i) => (i ? g.lineTo : g.moveTo).call(g, px(e.spp[i]), py(Math.max(y, 1e-30))));
    g.stroke();
  }
  g.setLineDash([]);
}

async function refreshError(s) {
  $('error_panel').hidden = !s.reference;
  if (!s.reference) return;
  const key = `${s.generation}/${s.spp}`;
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
  const names = state.swapped ? [s.compare, s.sampler] : [s.sampler, s.compare];
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
    if (id !== pixelRequest) return;
    const rgb = (c) => c ? c.map((x) => x.toPrecision(5)).join(' ') : '—';
    const s = state.status;
    $('pixel').textContent = `(${v.x}, ${v.y}) at ${v.spp} spp\nA ${s.sampler}: ${rgb(v.a)}` +
      (v.b ? `\nB ${s.compare}: ${rgb(v.b)}` : '');
  } catch (e) { /* the image is between generations */ }
}

function onSplitLine(cx) {
  const a = state.images.a;
  return a && state.images.b && !sideBySide() &&
    Math.abs(cx - (state.panX + state.split * a.width * state.zoom)) < 6;
}

canvas.addEventListener('mousedown', (e) => {
  state.drag = { split: onSplitLine(e.offsetX), x: e.offsetX, y: e.offsetY };
});
window.addEventListener('mouseup', () => { state.drag = null; });
canvas.addEventListener('mousemove', (e) => {
  const d = state.drag;
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
  showPixel(pixelAt(e.offsetX, e.offsetY));
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
  $('russian_roulette').addEventListener('change',
    () => change({ russian_roulette: $('russian_roulette').checked }));
  $('exposure').addEventListener('input', () => change({ exposure: Number($('exposure').value) }));
  $('tone_map').addEventListener('change', () => change({ tone_map: $('tone_map').value }));
  $('pause').addEventListener('click', () => change({ paused: !state.status.paused }));
  $('reset').addEventListener('click', () => api('/api/reset', {}));
  $('layout').addEventListener('change', () => { fit(); draw(); });
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

// tirpol live view: polls the server for the latest S0 frame and Stokes cycle (binary, see
// live/src/display_frame.h), draws them with colour bars, histogram and FPA plot,
// reads pixels under the cursor, averages a dragged region, zooms, and drives capture plans.
'use strict';

const params = new URLSearchParams(location.search);
const token = params.get('token');
const $ = (id) => document.getElementById(id);
function api(path) {
  if (!token) return path;
  return path + (path.includes('?') ? '&' : '?') + 'token=' + encodeURIComponent(token);
}
// Still mode (screenshots with chromium --screenshot --virtual-time-budget): stop polling once there
// is something to show. Chromium's virtual time stands still while a request is pending, and the
// page always has a long poll pending, so without this the budget never runs out. On by default in
// headless Chromium (the only browser that shoots this way), unless the address asks for a live
// page (observe=ID, the tests' pages, or live=1); ?still=1 asks for it in any browser.
const still = params.has('still') ||
  (/HeadlessChrome/.test(navigator.userAgent) && !params.has('observe') && !params.has('live'));
const enough = () => state.framesShown >= 3 && state.status && (!(state.describe.stage || state.describe.microgrid) || state.stokesShown >= 1);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const nextPaint = () => new Promise((r) => requestAnimationFrame(r));

// ---- wire format ----------------------------------------------------------------------------
const CODE_NONE = 0, CODE_DEAD = 1, CODE_SATURATED = 65535, CODE_FIRST = 2, CODE_SPAN = 65532;
function decode(buffer) {
  const view = new DataView(buffer);
  const magic = new TextDecoder().decode(new Uint8Array(buffer, 0, 4));
  if (magic !== 'TPLV') throw new Error('not a tirpol live image');
  const n = view.getUint32(4, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 8, n)));
  const pixels = header.width * header.height;
  let offset = 8 + n;
  for (const c of header.channels || []) {
    c.codes = new Uint16Array(buffer, offset, pixels);
    offset += 2 * pixels;
  }
  return header;
}
function codeValue(c, code) {
  if (code === CODE_NONE || code === CODE_DEAD || code === CODE_SATURATED) return NaN;
  return c.min + (code - CODE_FIRST) * (c.max - c.min) / CODE_SPAN;
}
function codeText(c, code) {
  if (code === CODE_DEAD) return 'dead';
  if (code === CODE_SATURATED) return 'saturated';
  if (code === CODE_NONE) return '—';
  return fmt(codeValue(c, code)) + (c.units ? ' ' + c.units : '');
}
function fmt(v) {
  if (!isFinite(v)) return '—';
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-2 || a >= 1e5) ? v.toExponential(3) : v.toPrecision(5);
}

// ---- colour maps ----------------------------------------------------------------------------
// Each palette is a lookup table of LUT_STEPS + 1 = 257 colours (an odd count: a range symmetric
// about 0 puts 0 exactly on the middle entry, the diverging palettes' centre colour).
const LUT_STEPS = 256;
function lerpStops(stops, t) {
  t = Math.min(1, Math.max(0, t));
  const x = t * (stops.length - 1), i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
  return [0, 1, 2].map((k) => Math.round(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
}
function makeLut(stops) {
  const lut = new Uint8Array((LUT_STEPS + 1) * 3);
  for (let i = 0; i <= LUT_STEPS; i++) lut.set(lerpStops(stops, i / LUT_STEPS), 3 * i);
  return lut;
}
// Sequential (S0, DoLP): inferno and viridis (matplotlib), grey.
const INFERNO = [[0, 0, 4], [40, 11, 84], [101, 21, 110], [159, 42, 99], [212, 72, 66], [245, 125, 21],
  [250, 193, 39], [252, 255, 164]];
const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
const GREY = [[0, 0, 0], [255, 255, 255]];
// Diverging (S1, S2; symmetric about 0): ColorBrewer RdBu (5 classes, reversed: negative blue),
// centre #f7f7f7; Moreland's cool-warm (SAND2009-0000, 2009), centre (221, 221, 221).
const RDBU = [[5, 113, 176], [146, 197, 222], [247, 247, 247], [244, 165, 130], [202, 0, 32]];
const COOLWARM = [[59, 76, 192], [141, 176, 254], [221, 221, 221], [244, 154, 123], [180, 4, 38]];
// Cyclic (AoP, 0° = 180°): a hue wheel and matplotlib's twilight; first stop = last stop.
const HUE_WHEEL = [[230, 60, 60], [230, 200, 40], [60, 200, 90], [50, 120, 230], [200, 60, 200], [230, 60, 60]];
const TWILIGHT = [[226, 217, 226], [155, 179, 196], [95, 119, 182], [94, 56, 144], [47, 20, 54],
  [114, 41, 83], [171, 86, 77], [207, 158, 135], [226, 217, 226]];
const PALETTES = { inferno: makeLut(INFERNO), grey: makeLut(GREY) };
const SIGNED_PALETTES = { rdbu: makeLut(RDBU), coolwarm: makeLut(COOLWARM) };
const CYCLIC_PALETTES = { 'hue-wheel': makeLut(HUE_WHEEL), twilight: makeLut(TWILIGHT) };
const DOLP_LUT = makeLut(VIRIDIS);
// AoP pixels whose DoLP is below the threshold: the angle of noise, drawn in this grey.
const MASKED = [64, 64, 64];
// The palette chosen on the page for a channel of the Stokes cycle (S0 shares the live S0's).
function lutFor(name) {
  if (name === 'S1' || name === 'S2') return SIGNED_PALETTES[$('palette-signed').value];
  if (name === 'AoP') return CYCLIC_PALETTES[$('palette-aop').value];
  if (name === 'DoLP') return DOLP_LUT;
  return PALETTES[$('palette').value];
}

// The display range of a channel: S0 stretched between the 0.5 % and 99.5 % points of its histogram
// (a hot spot does not flatten the scene), S1/S2 symmetric about 0, DoLP from 0, AoP 0–180°.
function displayRange(c, name) {
  if (name === 'AoP') return [0, 180];
  if (name === 'S0' && $('span-mode').value === 'lock') {
    const lo = Number($('span-lo').value), hi = Number($('span-hi').value);
    if (isFinite(lo) && isFinite(hi) && hi > lo) return [lo, hi];
  }
  const bins = new Uint32Array(1024);
  let n = 0;
  for (const code of c.codes) if (code >= CODE_FIRST && code !== CODE_SATURATED) { bins[(code - CODE_FIRST) >> 6]++; n++; }
  if (n === 0) return [c.min, c.max];
  const at = (q) => { let s = 0; for (let i = 0; i < 1024; i++) { s += bins[i]; if (s >= q * n) return codeValue(c, CODE_FIRST + (i << 6) + 32); } return c.max; };
  let lo = at(0.005), hi = at(0.995);
  if (name === 'S1' || name === 'S2') { const m = Math.max(Math.abs(lo), Math.abs(hi)) || 1; return [-m, m]; }
  if (name === 'DoLP') return [0, Math.max(hi, 1e-3)];
  if (!(hi > lo)) { lo = c.min; hi = c.max > c.min ? c.max : c.min + 1; }
  return [lo, hi];
}

// ---- shared view: zoom and region apply to every image --------------------------------------
const state = { s0: null, stokes: null, view: { x: 0, y: 0, scale: 1 }, region: null, cursor: null,
  framesShown: 0, stokesShown: 0, describe: null, status: null, focus: [], regionReadout: null };

// `masked(i)`: pixel i is drawn in the MASKED grey (AoP where DoLP is below the threshold).
function paint(canvas, header, channel, range, lut, masked) {
  const w = header.width, h = header.height;
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const off = paint.off || (paint.off = document.createElement('canvas'));
  off.width = w; off.height = h;
  const ctx = off.getContext('2d');
  const img = ctx.createImageData(w, h);
  const [lo, hi] = range, k = hi > lo ? LUT_STEPS / (hi - lo) : 0;
  const codes = channel.codes, px = img.data;
  for (let i = 0; i < codes.length; i++) {
    const code = codes[i], o = 4 * i;
    px[o + 3] = 255;
    if (code === CODE_SATURATED) { px[o + 1] = 255; continue; }
    if (code === CODE_DEAD) { px[o + 1] = 128; px[o + 2] = 255; continue; }
    if (code === CODE_NONE) continue;
    if (masked && masked(i)) { px[o] = MASKED[0]; px[o + 1] = MASKED[1]; px[o + 2] = MASKED[2]; continue; }
    const j = 3 * Math.min(LUT_STEPS, Math.max(0, Math.round((codeValue(channel, code) - lo) * k)));
    px[o] = lut[j]; px[o + 1] = lut[j + 1]; px[o + 2] = lut[j + 2];
  }
  ctx.putImageData(img, 0, 0);
  const out = canvas.getContext('2d');
  out.imageSmoothingEnabled = false;
  out.fillStyle = '#000';
  out.fillRect(0, 0, w, h);
  const v = state.view;
  out.drawImage(off, v.x, v.y, w / v.scale, h / v.scale, 0, 0, w, h);
  const r = state.region;
  if (r) {
    out.strokeStyle = '#0ff';
    out.lineWidth = 1;
    out.strokeRect((r.x0 - v.x) * v.scale + 0.5, (r.y0 - v.y) * v.scale + 0.5, (r.x1 - r.x0 + 1) * v.scale,
      (r.y1 - r.y0 + 1) * v.scale);
  }
}

function drawColorbar(canvas, range, units, lut) {
  const ctx = canvas.getContext('2d');
  ctx.fillStyle = '#111'; ctx.fillRect(0, 0, canvas.width, canvas.height);
  for (let x = 0; x < canvas.width; x++) {
    const j = 3 * Math.round(LUT_STEPS * x / (canvas.width - 1));
    ctx.fillStyle = `rgb(${lut[j]},${lut[j + 1]},${lut[j + 2]})`;
    ctx.fillRect(x, 0, 1, 20);
  }
  ctx.fillStyle = '#ddd'; ctx.font = '12px system-ui';
  const ticks = canvas.width < 400 ? 2 : 4;  // the Stokes thumbnails' bars have room for three labels
  for (let i = 0; i <= ticks; i++) {
    const x = i * (canvas.width - 1) / ticks, v = range[0] + i * (range[1] - range[0]) / ticks;
    ctx.fillRect(x, 20, 1, 5);
    ctx.textAlign = i === 0 ? 'left' : i === ticks ? 'right' : 'center';
    ctx.fillText(fmt(v) + (i === ticks && units ? ' ' + units : ''), x, 38);
  }
  canvas.dataset.range = JSON.stringify(range);
  canvas.dataset.units = units;
}

function drawHistogram(channel, range) {
  const canvas = $('histogram'), ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height;
  const bins = new Float64Array(W);
  let saturated = 0, dead = 0;
  for (const code of channel.codes) {
    if (code === CODE_SATURATED) { saturated++; continue; }
    if (code === CODE_DEAD) { dead++; continue; }
    if (code === CODE_NONE) continue;
    const b = Math.floor((codeValue(channel, code) - range[0]) / (range[1] - range[0]) * (W - 1));
    bins[Math.min(W - 1, Math.max(0, b))]++;
  }
  $('n-saturated').textContent = saturated;
  $('n-dead').textContent = dead;
  const top = Math.log10(1 + Math.max(...bins));
  ctx.fillStyle = '#000'; ctx.fillRect(0, 0, W, H);
  ctx.fillStyle = '#fa3';
  for (let x = 0; x < W; x++) { const h = top > 0 ? (H - 14) * Math.log10(1 + bins[x]) / top : 0; ctx.fillRect(x, H - 14 - h, 1, h); }
  ctx.fillStyle = '#aaa'; ctx.font = '11px system-ui';
  ctx.textAlign = 'left'; ctx.fillText(fmt(range[0]), 0, H - 2);
  ctx.textAlign = 'right'; ctx.fillText(fmt(range[1]) + ' ' + channel.units + ' (log count)', W, H - 2);
}

function drawFpa(samples) {
  const canvas = $('fpa-plot'), ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height;
  ctx.fillStyle = '#000'; ctx.fillRect(0, 0, W, H);
  ctx.fillStyle = '#aaa'; ctx.font = '11px system-ui';
  if (!samples.length) { ctx.fillText('the camera reports no temperature', 8, 20); return; }
  const t0 = samples[0][0], t1 = Math.max(samples[samples.length - 1][0], t0 + 1);
  let lo = Math.min(...samples.map((s) => s[1])), hi = Math.max(...samples.map((s) => s[1]));
  if (hi - lo < 0.1) { lo -= 0.05; hi += 0.05; }
  ctx.strokeStyle = '#6cf'; ctx.beginPath();
  samples.forEach(([t, k], i) => {
    const x = (t - t0) / (t1 - t0) * (W - 1), y = 4 + (hi - k) / (hi - lo) * (H - 22);
    if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y);
  });
  ctx.stroke();
  ctx.textAlign = 'left'; ctx.fillText(`${hi.toFixed(2)} K`, 2, 12); ctx.fillText(`${lo.toFixed(2)} K`, 2, H - 2);
  ctx.textAlign = 'right'; ctx.fillText(`last ${(t1 - t0).toFixed(0)} s`, W - 2, H - 2);
}

function redraw() {
  if (state.s0 && state.s0.channels && state.s0.channels.length) {
    const c = state.s0.channels[0], range = displayRange(c, 'S0'), lut = PALETTES[$('palette').value];
    paint($('s0'), state.s0, c, range, lut);
    drawColorbar($('colorbar'), range, c.units, lut);
    drawHistogram(c, range);
  }
  if (state.stokes) {
    const dolp = state.stokes.channels.find((c) => c.name === 'DoLP'), dolpMin = Number($('dolp-min').value) || 0;
    const masked = (i) => !(codeValue(dolp, dolp.codes[i]) >= dolpMin);
    for (const c of state.stokes.channels) {
      const range = displayRange(c, c.name);
      const lut = lutFor(c.name);
      paint($('st-' + c.name), state.stokes, c, range, lut, c.name === 'AoP' && dolp ? masked : null);
      drawColorbar($('cb-' + c.name), range, c.name === 'DoLP' ? 'fraction' : c.units, lut);
      $('r-' + c.name).textContent = `${fmt(range[0])} … ${fmt(range[1])} ${c.units}`;
    }
  }
  updateReadouts();
}

// ---- cursor, region, zoom -------------------------------------------------------------------
function pixelAt(canvas, event) {
  const rect = canvas.getBoundingClientRect(), v = state.view;
  const cx = (event.clientX - rect.left) / rect.width * canvas.width, cy = (event.clientY - rect.top) / rect.height * canvas.height;
  return { x: Math.floor(v.x + cx / v.scale), y: Math.floor(v.y + cy / v.scale), cx, cy };
}
function valuesAt(x, y) {
  const lines = [];
  const one = (img) => {
    if (!img || x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    for (const c of img.channels) lines.push(`${(img === state.stokes ? 'cycle ' : 'live  ') + c.name.padEnd(5)} ${codeText(c, c.codes[y * img.width + x])}`);
  };
  one(state.s0); one(state.stokes);
  return lines;
}
// The region readout is computed by the server (GET /api/region, live/src/region_statistics.cpp):
// AoP with circular statistics over the pixels with DoLP ≥ the threshold, and the focus metric.
function focusRegion() {
  if (state.region) return state.region;
  const w = state.s0.width, h = state.s0.height;
  return { x0: w >> 2, y0: h >> 2, x1: (3 * w >> 2) - 1, y1: (3 * h >> 2) - 1 };
}
async function fetchRegion() {
  if (!state.s0 || fetchRegion.busy) return;
  fetchRegion.busy = true;
  try {
    const r = focusRegion(), q = `x0=${r.x0}&y0=${r.y0}&x1=${r.x1}&y1=${r.y1}&dolp_min=${Number($('dolp-min').value) || 0}`;
    const j = await (await fetch(api('/api/region?' + q), { cache: 'no-store' })).json();
    if (j.error) { $('error').textContent = j.error; return; }
    state.regionReadout = j;
    if (j.focus && j.focus.value != null) {
      state.focus.push(j.focus.value);
      if (state.focus.length > 300) state.focus.shift();
      drawFocus(j.focus.units);
    }
    updateReadouts();
  } catch (e) { $('error').textContent = String(e); } finally { fetchRegion.busy = false; }
}
function regionLines(j) {
  const [x0, y0, x1, y1] = j.region, lines = [`x ${x0}–${x1}, y ${y0}–${y1} (${(x1 - x0 + 1) * (y1 - y0 + 1)} px)`];
  const one = (group, label) => {
    for (const [name, s] of Object.entries(group || {})) {
      const extra = s.circular ? ` circular, ${s.masked} px with DoLP < ${j.dolp_min} left out` : '';
      lines.push(`${label}${name.padEnd(5)} mean ${fmt(s.mean)} ± ${fmt(s.std)} ${s.units} (${s.count} px${extra})`);
    }
  };
  one(j.live, 'live  '); one(j.cycle, 'cycle ');
  if (j.focus) lines.push(`focus ${fmt(j.focus.value)} ${j.focus.units}`);
  return lines;
}
function drawFocus(units) {
  const canvas = $('focus-plot'), ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height, f = state.focus;
  ctx.fillStyle = '#000'; ctx.fillRect(0, 0, W, H);
  const lo = Math.min(...f), hi = Math.max(...f), span = hi > lo ? hi - lo : 1;
  ctx.strokeStyle = '#fc6'; ctx.beginPath();
  f.forEach((v, i) => { const x = i / 299 * (W - 1), y = 4 + (hi - v) / span * (H - 22); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
  ctx.stroke();
  ctx.fillStyle = '#aaa'; ctx.font = '11px system-ui'; ctx.textAlign = 'left';
  ctx.fillText(`now ${fmt(f[f.length - 1])}  max ${fmt(hi)} ${units}`, 2, H - 2);
}
function updateReadouts() {
  if (state.cursor) $('readout').textContent = `x ${state.cursor.x}, y ${state.cursor.y}\n` + valuesAt(state.cursor.x, state.cursor.y).join('\n');
  if (state.region && state.regionReadout) $('region').textContent = regionLines(state.regionReadout).join('\n');
}
function attachInteraction(canvas) {
  let drag = null;
  canvas.addEventListener('mousemove', (e) => {
    state.cursor = pixelAt(canvas, e);
    if (drag) {
      const p = state.cursor;
      state.region = { x0: Math.min(drag.x, p.x), y0: Math.min(drag.y, p.y), x1: Math.max(drag.x, p.x), y1: Math.max(drag.y, p.y) };
      state.focus = [];
      redraw();
      fetchRegion();
    } else updateReadouts();
  });
  canvas.addEventListener('mousedown', (e) => { drag = pixelAt(canvas, e); });
  window.addEventListener('mouseup', () => { drag = null; });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const p = pixelAt(canvas, e), v = state.view;
    const scale = Math.min(32, Math.max(1, v.scale * (e.deltaY < 0 ? 1.25 : 0.8)));
    v.x = p.x - p.cx / scale; v.y = p.y - p.cy / scale; v.scale = scale;
    if (scale === 1) { v.x = 0; v.y = 0; }
    redraw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { state.view = { x: 0, y: 0, scale: 1 }; state.region = null; state.focus = []; $('region').textContent = 'drag over an image'; redraw(); });
}

// ---- polling loops: each asks for the next image after drawing the last (display pace) -------
async function imageLoop(path, onImage) {
  let after = 0;
  while (!(still && enough())) {
    try {
      const r = await fetch(api(`${path}?after=${after}`), { cache: 'no-store' });
      if (r.status === 200) {
        after = Number(r.headers.get('X-Sequence'));
        onImage(decode(await r.arrayBuffer()));
        await nextPaint();
      } else if (r.status !== 204) { await sleep(1000); }
    } catch (e) {
      $('error').textContent = String(e);
      await sleep(1000);
    }
  }
}

function showStatus(s) {
  state.status = s;
  const c = s.camera;
  $('fps').textContent = c.frame_rate_hz == null ? '–' : c.frame_rate_hz.toFixed(1);
  $('delivered').textContent = c.delivered;
  $('dropped').textContent = c.dropped;
  $('error').textContent = c.error || (state.s0 && state.s0.error) || '';
  const fpa = s.fpa_temperature_k;
  $('fpa').textContent = fpa.length ? `${fpa[fpa.length - 1][1].toFixed(2)} K` : 'n/a';
  drawFpa(fpa);
  if (s.stage) {
    $('stage-state').textContent = s.stage.state + (s.stage.error ? ` (${s.stage.error})` : '');
    $('stage-angle').textContent = s.stage.angle_deg == null ? '–' : `${s.stage.angle_deg.toFixed(2)}°`;
    $('cycles').textContent = s.stage.cycles;
  }
  if (s.capture) {
    const k = s.capture;
    $('capture-progress').max = Math.max(1, k.steps_total);
    $('capture-progress').value = k.steps_recorded;
    $('capture-state').textContent = `${k.phase}: ${k.steps_recorded}/${k.steps_total} steps` + (k.output ? ` → ${k.output}` : '');
    $('capture-message').textContent = k.message;
  }
}
async function statusLoop() {
  while (!(still && enough())) {
    try { showStatus(await (await fetch(api('/api/status'), { cache: 'no-store' })).json()); } catch (e) { $('error').textContent = String(e); }
    await sleep(500);
  }
}

async function post(path, body) {
  const r = await fetch(api(path), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body || {}) });
  const j = await r.json();
  if (j.error) $('capture-message').textContent = j.error; else showStatus(j);
  return j;
}

// Snapshot: the server writes the latest frame (and cycle) as EXR + PNG into --snapshot-dir.
async function snapshot() {
  const r = await fetch(api('/api/snapshot'), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: '{}' });
  const j = await r.json();
  state.snapshot = j;
  $('snapshot-result').textContent = j.error ? j.error : `${j.files.length} files in ${j.folder}: ${j.files[0]}`;
  return j;
}

// ---- test mode (?observe=ID): report what this page shows, drive the capture buttons --------
function paintedFraction(canvas) {
  if (!canvas.width) return 0;
  const d = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let lit = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] || d[i + 1] || d[i + 2]) lit++;
  return lit / (d.length / 4);
}
// The share of a canvas's pixels drawn in colour `rgb`, and whether every pixel is grey (r = g = b).
function colourShare(canvas, rgb) {
  const d = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] === rgb[0] && d[i + 1] === rgb[1] && d[i + 2] === rgb[2]) n++;
  return n / (d.length / 4);
}
// Saturated (green) and dead (blue) pixels keep their flag colours on every palette: not counted.
function allGrey(canvas) {
  const d = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  for (let i = 0; i < d.length; i += 4) {
    const flag = d[i] === 0 && ((d[i + 1] === 255 && d[i + 2] === 0) || (d[i + 1] === 128 && d[i + 2] === 255));
    if (!flag && (d[i] !== d[i + 1] || d[i + 1] !== d[i + 2])) return false;
  }
  return true;
}
function colourBars() {
  const out = {};
  for (const c of document.querySelectorAll('canvas#colorbar, canvas.bar'))
    if (c.dataset.range) out[c.id] = { range: JSON.parse(c.dataset.range), units: c.dataset.units };
  return out;
}

// The S1 pixel closest to 0 (within half a palette step of the symmetric range, or null), its
// value and the colour the page painted there; and the colours at both ends of AoP's colour bar.
function paletteProbe() {
  if (!state.stokes || state.view.scale !== 1) return null;
  const s1 = state.stokes.channels.find((c) => c.name === 'S1');
  const range = JSON.parse($('cb-S1').dataset.range || 'null');
  if (!s1 || !range) return null;
  let best = -1, bestValue = Infinity;
  s1.codes.forEach((code, i) => {
    const v = codeValue(s1, code);
    if (Math.abs(v) < Math.abs(bestValue)) { bestValue = v; best = i; }
  });
  const rgbAt = (canvas, x, y) => Array.from(canvas.getContext('2d').getImageData(x, y, 1, 1).data.slice(0, 3));
  const w = state.stokes.width, bar = $('cb-AoP');
  return {
    s1_palette: $('palette-signed').value, aop_palette: $('palette-aop').value, s1_range: range,
    s1_zero: best < 0 ? null : { value: bestValue, x: best % w, y: Math.floor(best / w), rgb: rgbAt($('st-S1'), best % w, Math.floor(best / w)) },
    aop_bar_ends: [rgbAt(bar, 0, 5), rgbAt(bar, bar.width - 1, 5)],
  };
}

// Drags a region over pixels (100, 80)–(139, 119) of the S0 image and zooms once at its centre with
// synthetic mouse events, as an operator's mouse would.
function exerciseMouse() {
  const canvas = $('s0'), rect = canvas.getBoundingClientRect();
  // Mouse events carry whole CSS pixels: the first whole position inside the image pixel.
  const at = (x, y) => ({ clientX: Math.ceil(rect.left + x * rect.width / canvas.width - 1e-6),
    clientY: Math.ceil(rect.top + y * rect.height / canvas.height - 1e-6), bubbles: true });
  canvas.dispatchEvent(new MouseEvent('mousedown', at(100, 80)));
  canvas.dispatchEvent(new MouseEvent('mousemove', at(139, 119)));
  window.dispatchEvent(new MouseEvent('mouseup', at(139, 119)));
  canvas.dispatchEvent(new WheelEvent('wheel', { ...at(canvas.width / 2, canvas.height / 2), deltaY: -100, cancelable: true }));
  return { region: $('region').textContent.split('\n'), cursor: $('readout').textContent.split('\n'), zoom: state.view.scale };
}

async function observeLoop(client) {
  let clickedStart = false, clickedStop = false, clickedSnapshot = false, mouse = null;
  const stopAfter = params.has('capture_stop_after') ? Number(params.get('capture_stop_after')) : null;
  for (;;) {
    await sleep(400);
    const k = state.status && state.status.capture;
    if (params.has('capture_plan') && state.framesShown > 0 && !clickedStart) {
      $('plan').value = params.get('capture_plan');
      $('output').value = params.get('capture_output');
      $('resume').checked = params.get('capture_resume') === '1';
      $('start').click();
      clickedStart = true;
    }
    if (stopAfter !== null && k && k.phase === 'running' && k.steps_recorded >= stopAfter && !clickedStop) {
      $('stop').click();
      clickedStop = true;
    }
    if (!mouse && state.framesShown > 0 && params.has('mouse')) mouse = exerciseMouse();
    if (params.has('snapshot') && !clickedSnapshot && state.framesShown > 0 && (!(state.describe.stage || state.describe.microgrid) || state.stokesShown > 0)) {
      $('snapshot').click();
      clickedSnapshot = true;
    }
    if (mouse) mouse.region = $('region').textContent.split('\n');
    const cx = Math.floor($('s0').width / 2), cy = Math.floor($('s0').height / 2);
    const dolp = state.stokes && state.stokes.channels.find((c) => c.name === 'DoLP');
    const obs = {
      frames_shown: state.framesShown, last_frame_id: state.s0 ? state.s0.frame_id : null,
      s0_painted: paintedFraction($('s0')), colorbar_units: state.s0 && state.s0.channels[0] ? state.s0.channels[0].units : null,
      stokes_shown: state.stokesShown, dolp_painted: state.stokes ? paintedFraction($('st-DoLP')) : 0,
      dolp_range: dolp ? [dolp.min, dolp.max] : null, center_readout: valuesAt(cx, cy),
      stage: state.status && state.status.stage, capture: k || null, clicked_start: clickedStart, clicked_stop: clickedStop,
      capture_message: $('capture-message').textContent, mouse,
      focus: { n: state.focus.length, last: state.focus.length ? state.focus[state.focus.length - 1] : null },
      s0_grey: state.framesShown > 0 && allGrey($('s0')), colorbars: colourBars(), region_readout: state.regionReadout,
      aop_masked: state.stokes ? colourShare($('st-AoP'), MASKED) : null, palettes: paletteProbe(),
      snapshot: state.snapshot || null,
    };
    try { await fetch(api(`/api/observations?client=${encodeURIComponent(client)}`), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(obs) }); } catch (e) { /* next round */ }
  }
}

async function main() {
  // The controls can be preset from the address (also what the tests use): palette=grey,
  // span=LO,HI (locks the S0 span), dolp_min=X (the AoP mask threshold).
  if (params.has('palette')) $('palette').value = params.get('palette');
  if (params.has('span')) { const [lo, hi] = params.get('span').split(','); $('span-mode').value = 'lock'; $('span-lo').value = lo; $('span-hi').value = hi; }
  if (params.has('dolp_min')) $('dolp-min').value = params.get('dolp_min');
  if (params.has('palette_signed')) $('palette-signed').value = params.get('palette_signed');
  if (params.has('palette_aop')) $('palette-aop').value = params.get('palette_aop');
  // Lock keeps the span shown when it was chosen, ready to edit.
  $('span-mode').addEventListener('change', () => {
    const r = JSON.parse($('colorbar').dataset.range || 'null');
    if ($('span-mode').value === 'lock' && r && !$('span-lo').value) { $('span-lo').value = fmt(r[0]); $('span-hi').value = fmt(r[1]); }
    redraw();
  });
  for (const id of ['palette', 'palette-signed', 'palette-aop', 'span-lo', 'span-hi', 'dolp-min']) $(id).addEventListener('change', () => { redraw(); fetchRegion(); });
  const d = await (await fetch(api('/api/describe'))).json();
  state.describe = d;
  $('camera').textContent = `${d.camera.vendor} ${d.camera.model} ${d.camera.width}×${d.camera.height} ${d.camera.pixel_format}`;
  $('s0-units').textContent = `(${d.units})`;
  $('plan').value = d.default_plan; $('output').value = d.default_output;
  attachInteraction($('s0'));
  $('snapshot').disabled = !d.snapshot_dir;
  $('snapshot').title = d.snapshot_dir ? `writes EXR + PNG into ${d.snapshot_dir}` : 'start tirpol live with --snapshot-dir FOLDER';
  $('snapshot').addEventListener('click', () => snapshot().catch((e) => { $('snapshot-result').textContent = String(e); }));
  if (d.microgrid) {  // a microgrid camera: Stokes of every frame, no stage, no capture plan
    $('stokes').hidden = false;
    $('stokes-title').textContent = `Stokes of the latest frame (microgrid ${d.microgrid.pattern}, ${d.microgrid.demosaic})`;
    $('capture-section').hidden = true;
    $('stage-line').hidden = true;
    for (const n of ['S0', 'S1', 'S2', 'DoLP', 'AoP']) attachInteraction($('st-' + n));
    imageLoop('/api/stokes', (img) => { state.stokes = img; state.stokesShown++; redraw(); });
  }
  if (d.stage) {
    $('stokes').hidden = false;
    $('stage-uri').textContent = d.stage;
    for (const n of ['S0', 'S1', 'S2', 'DoLP', 'AoP']) attachInteraction($('st-' + n));
    $('start').addEventListener('click', () => post('/api/capture/start', { plan: $('plan').value, output: $('output').value, resume: $('resume').checked }));
    $('stop').addEventListener('click', () => post('/api/capture/stop'));
    imageLoop('/api/stokes', (img) => { state.stokes = img; state.stokesShown++; redraw(); });
  }
  imageLoop('/api/frame', (img) => {
    state.s0 = img;
    state.framesShown++;
    $('frame-id').textContent = img.frame_id;
    $('shown').textContent = state.framesShown;
    redraw();
    fetchRegion();
  });
  statusLoop();
  if (params.has('observe')) observeLoop(params.get('observe'));
}
main();

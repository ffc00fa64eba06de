// vilslam report: builds the page from the JSON in #report-data (src/report/report_json.cpp writes it) with
// Chart.js (2D plots) and three.js (the map). When every plot exists it writes "report-status: ok" into
// #report-status; the browser test (tests/report/test_report_browser.cpp) reads that marker.
'use strict';

const COLORS = { gt: '#7a8294', VIO: '#1f77b4', 'LiDAR odometry': '#ff7f0e', 'LiDAR loop-closed': '#2ca02c' };
const LOOP_COLOR = '#9c27b0';
const DEGENERATE_COLOR = '#d62728';
const plots = [];  // every Chart created, checked at the end

Chart.defaults.animation = false;
Chart.defaults.font.size = 12;

// A base64 little-endian float32 array (report/base64.h) as a Float32Array.
function f32(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

function el(tag, attrs, parent) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
  }
  if (parent) parent.appendChild(e);
  return e;
}

function fmt(x, digits) { return x === null || x === undefined ? '–' : Number(x).toFixed(digits); }

// Points {x, y} of an interleaved xyz array, axes a and b (0 = x, 1 = y, 2 = z).
function projected(xyz, a, b) {
  const pts = [];
  for (let i = 0; i + 2 < xyz.length; i += 3) pts.push({ x: xyz[i + a], y: xyz[i + b] });
  return pts;
}

function section(parent, title, caption) {
  const s = el('section', {}, parent);
  el('h2', { text: title }, s);
  if (caption) el('p', { class: 'caption', text: caption }, s);
  return s;
}

function plotBox(parent, title, height) {
  const box = el('div', { class: 'plot' }, parent);
  if (title) el('h3', { text: title }, box);
  const holder = el('div', { style: 'position: relative; height: ' + height + 'px' }, box);
  return el('canvas', {}, holder);
}

function chart(canvas, config) {
  config.options = Object.assign({ responsive: true, maintainAspectRatio: false }, config.options);
  const c = new Chart(canvas, config);
  plots.push(c);
  return c;
}

function axis(title, extra) {
  return Object.assign({ type: 'linear', title: { display: true, text: title } }, extra || {});
}

// Axis limits giving x and y the same metres per pixel on a plot of the given size.
function equalScale(datasets, widthPx, heightPx) {
  let xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
  for (const d of datasets) {
    for (const p of d.data) {
      xmin = Math.min(xmin, p.x); xmax = Math.max(xmax, p.x); ymin = Math.min(ymin, p.y); ymax = Math.max(ymax, p.y);
    }
  }
  const perPx = 1.08 * Math.max((xmax - xmin) / widthPx, (ymax - ymin) / heightPx, 1e-3 / widthPx);
  const cx = (xmin + xmax) / 2, cy = (ymin + ymax) / 2;
  return { x: { min: cx - perPx * widthPx / 2, max: cx + perPx * widthPx / 2 },
           y: { min: cy - perPx * heightPx / 2, max: cy + perPx * heightPx / 2 } };
}

function pathDatasets(data, a, b) {
  const sets = [];
  if (data.ground_truth)
    sets.push({ label: 'ground truth (' + data.ground_truth.frame + ')',
                data: projected(f32(data.ground_truth.xyz), a, b), borderColor: COLORS.gt,
                borderDash: [6, 4], borderWidth: 2, pointRadius: 0, showLine: true, order: 5 });
  for (const t of data.trajectories)
    sets.push({ label: t.name, data: projected(f32(t.xyz), a, b), borderColor: COLORS[t.name], borderWidth: 1.6,
                pointRadius: 0, showLine: true, order: 3 });
  const ev = data.events;
  if (ev.degenerate_xyz !== undefined && ev.degenerate > 0)
    sets.push({ label: 'degenerate sweep (' + ev.degenerate + ')', data: projected(f32(ev.degenerate_xyz), a, b),
                backgroundColor: DEGENERATE_COLOR, borderColor: DEGENERATE_COLOR, pointStyle: 'crossRot',
                pointRadius: 5, pointBorderWidth: 2, showLine: false, order: 1 });
  (ev.loops || []).forEach((l, i) => {
    sets.push({ label: i === 0 ? 'loop closure (' + ev.loops.length + ')' : '', data: [
                  { x: l.from[a], y: l.from[b] }, { x: l.to[a], y: l.to[b] }],
                borderColor: LOOP_COLOR, backgroundColor: LOOP_COLOR, borderWidth: 2, pointRadius: 4,
                showLine: true, order: 0 });
  });
  return sets;
}

const legendWithoutBlanks = { labels: { filter: (item) => item.text !== '' } };

function pathsSection(root, data) {
  const frame = data.ground_truth ? 'in the ground truth\'s world (each estimate aligned as `vilslam eval` does; ' +
                                    'VIO poses are of the IMU, LiDAR poses of the LiDAR)' : 'in the estimator\'s world';
  const s = section(root, 'Trajectory', 'Top and side views ' + frame + ', both at equal scale. Degenerate sweeps ' +
                    'and loop closures are drawn on the ' + (data.events.on || '–') + ' path; a loop joins the two ' +
                    'poses it relates.');
  const views = [['Top view (x–y)', 1, 'y [m]', 560], ['Side view (x–z)', 2, 'z [m]', 250]];
  for (const [title, b, yl, h] of views) {
    const canvas = plotBox(el('div', { class: 'row' }, s), title, h);
    const sets = pathDatasets(data, 0, b);
    const width = canvas.parentElement.clientWidth || 1300;
    const lim = equalScale(sets, width - 70, h - 80);
    const ticks = { includeBounds: false };
    chart(canvas, { type: 'scatter', data: { datasets: sets },
                    options: { scales: { x: axis('x [m]', Object.assign({ ticks: ticks }, lim.x)),
                                         y: axis(yl, Object.assign({ ticks: ticks }, lim.y)) },
                               plugins: { legend: legendWithoutBlanks } } });
  }
}

function errorsSection(root, data) {
  const withErrors = data.trajectories.filter((t) => t.errors);
  if (withErrors.length === 0) return;
  const s = section(root, 'Absolute error', 'Translation error of each matched pose after alignment (VIO: position ' +
                    'and yaw; LiDAR: SE(3)), over time since the first estimated pose and over the distance travelled.');
  const row = el('div', { class: 'row' }, s);
  for (const [title, key, xl] of [['Over time', 't_s', 'time [s]'], ['Over distance', 'travelled_m', 'distance travelled [m]']]) {
    const sets = withErrors.map((t) => {
      const x = f32(t.errors[key]), y = f32(t.errors.ape_m);
      const pts = Array.from(x, (v, i) => ({ x: v, y: y[i] }));
      return { label: t.name + ' (' + t.errors.align + ', RMSE ' + fmt(t.errors.rmse_m, 3) + ' m)', data: pts,
               borderColor: COLORS[t.name], borderWidth: 1.5, pointRadius: 0, showLine: true };
    });
    chart(plotBox(row, title, 300), { type: 'scatter', data: { datasets: sets },
                                     options: { scales: { x: axis(xl), y: axis('APE [m]', { min: 0 }) } } });
  }
}

function timingSection(root, data) {
  const t = data.timings;
  const s = section(root, 'Timing', 'Per-event wall time of each module (and, with --realtime, the latency of each ' +
                    'output from its measurement\'s time to its publication), from timing_samples.csv.');
  const grid = el('div', { class: 'histograms' }, s);
  for (const h of t.histograms) {
    const labels = h.counts.map((_, i) => fmt(h.lower_ms + (i + 0.5) * h.bin_width_ms, h.bin_width_ms < 1 ? 2 : 1));
    const canvas = plotBox(grid, h.series.replace(/_/g, ' ') + ' (' + h.counts.reduce((a, b) => a + b, 0) + ')', 160);
    chart(canvas, { type: 'bar', data: { labels: labels, datasets: [{ data: h.counts, backgroundColor: '#4e79a7',
                                                                     barPercentage: 1.0, categoryPercentage: 1.0 }] },
                    options: { plugins: { legend: { display: false } },
                               scales: { x: { title: { display: true, text: 'ms' },
                                              ticks: { maxTicksLimit: 6, maxRotation: 0 } },
                                         y: { title: { display: true, text: 'count' } } } } });
  }
  const table = el('table', {}, s);
  const head = el('tr', {}, table);
  for (const c of ['series', 'events', 'median ms', 'p95 ms', 'max ms']) el('th', { text: c }, head);
  for (const r of t.summaries.filter((row) => row.frames > 0)) {
    const tr = el('tr', {}, table);
    for (const v of [r.series, r.frames, fmt(r.median_ms, 2), fmt(r.p95_ms, 2), fmt(r.max_ms, 2)])
      el('td', { text: String(v) }, tr);
  }
}

// Viridis, sampled at 9 stops; v in [0, 1].
const VIRIDIS = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141], [39, 173, 129],
                 [92, 200, 99], [170, 220, 50], [253, 231, 37]];
function viridis(v) {
  const x = Math.min(1, Math.max(0, v)) * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(x)), f = x - i;
  return VIRIDIS[i].map((c, k) => (c + f * (VIRIDIS[i + 1][k] - c)) / 255);
}

function percentile(values, q) {
  const sorted = Float32Array.from(values).sort();
  return sorted[Math.min(sorted.length - 1, Math.floor(q * (sorted.length - 1)))];
}

function mapSection(root, data) {
  const m = data.map;
  const byMre = m.value_name === 'mre_m';
  const caption = m.shown_points + ' of ' + m.total_points + ' points of ' + m.file + ', coloured by ' +
      (byMre ? 'the distance to the reference model (MRE; mean ' + fmt(m.mre_mean_m, 3) + ' m, median ' +
               fmt(m.mre_median_m, 3) + ' m, p95 ' + fmt(m.mre_p95_m, 3) + ' m)' : 'height') +
      ', with the LiDAR path it was built with (white). Drag to turn, scroll to zoom, right-drag to pan.';
  const s = section(root, 'Map', caption);
  const holder = el('div', { id: 'map3d' }, s);
  const xyz = f32(m.xyz), value = f32(m.value);
  const lo = byMre ? 0 : percentile(value, 0.02), hi = byMre ? percentile(value, 0.95) : percentile(value, 0.98);
  const colors = new Float32Array(xyz.length);
  for (let i = 0; i < value.length; ++i) colors.set(viridis((value[i] - lo) / Math.max(hi - lo, 1e-6)), 3 * i);

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(holder.clientWidth, holder.clientHeight);
  holder.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x11151c);
  const cloud = new THREE.BufferGeometry();
  cloud.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
  cloud.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  cloud.computeBoundingSphere();
  // three.js r111 takes THREE.VertexColors here (later releases: true).
  const material = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: THREE.VertexColors });
  scene.add(new THREE.Points(cloud, material));
  const path = new THREE.BufferGeometry();
  path.setAttribute('position', new THREE.BufferAttribute(f32(m.path.xyz), 3));
  scene.add(new THREE.Line(path, new THREE.LineBasicMaterial({ color: 0xffffff })));

  const sphere = cloud.boundingSphere;
  const camera = new THREE.PerspectiveCamera(50, holder.clientWidth / holder.clientHeight, sphere.radius / 100, sphere.radius * 20);
  camera.up.set(0, 0, 1);  // z is up in the map's world
  camera.position.set(sphere.center.x - 0.9 * sphere.radius, sphere.center.y - 1.3 * sphere.radius,
                      sphere.center.z + 1.1 * sphere.radius);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(sphere.center);
  controls.update();
  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);
  render();

  const legend = el('div', { class: 'legend' }, s);
  el('span', { text: (byMre ? 'MRE ' : 'height ') + fmt(lo, 2) + ' m' }, legend);
  const stops = VIRIDIS.map((c, i) => 'rgb(' + c.join(',') + ') ' + (100 * i / (VIRIDIS.length - 1)).toFixed(0) + '%');
  el('div', { class: 'bar', style: 'background: linear-gradient(to right, ' + stops.join(', ') + ')' }, legend);
  el('span', { text: fmt(hi, 2) + ' m' + (byMre ? ' and more' : '') }, legend);
  return { renderer: renderer, points: value.length, drawn: cloud.getAttribute('position').count };
}

function header(root, data) {
  el('h1', { text: 'vilslam report' }, root);
  el('div', { class: 'subtitle', text: 'run ' + data.run + (data.gt ? ' · ground truth ' + data.gt : '') +
                                       ' · Chart.js ' + Chart.version + ', three.js r' + THREE.REVISION }, root);
  const cards = el('div', { class: 'cards' }, root);
  const card = (label, value) => {
    const c = el('div', { class: 'card' }, cards);
    el('div', { class: 'label', text: label }, c);
    el('div', { class: 'value', text: value }, c);
  };
  card('mode', data.mode + (data.realtime_speed ? ' (real time ×' + data.realtime_speed + ')' : ''));
  card('data / wall time', fmt(data.data_s, 1) + ' s / ' + fmt(data.run_wall_s, 1) + ' s');
  for (const t of data.trajectories) if (t.errors) card(t.name + ' ATE RMSE', fmt(t.errors.rmse_m, 3) + ' m');
  if (data.events.loops) card('loop closures', String(data.events.loops.length));
  if (data.events.sweeps !== undefined) card('degenerate sweeps', data.events.degenerate + ' of ' + data.events.sweeps);
  if (data.lidar_lost_s.length > 0) {
    card('LiDAR mapping lost at', data.lidar_lost_s.map((t) => fmt(t, 1) + ' s').join(', '));
  }
  if (data.map && data.map.value_name === 'mre_m') card('map MRE (mean)', fmt(data.map.mre_mean_m, 3) + ' m');
  if (data.notes.length > 0) {
    const notes = el('div', { class: 'notes' }, root);
    el('strong', { text: 'Left out' }, notes);
    const ul = el('ul', {}, notes);
    for (const n of data.notes) el('li', { text: n }, ul);
  }
}

// The page's own check: every plot exists, has a size, and the 3D view drew every point.
function check(data, map) {
  const problems = [];
  for (const c of plots) {
    if (!Chart.getChart(c.canvas) || c.canvas.width === 0 || c.canvas.height === 0) problems.push('a plot has no canvas');
  }
  const expected = 2 + (data.trajectories.some((t) => t.errors) ? 2 : 0) + data.timings.histograms.length;
  if (plots.length !== expected) problems.push(plots.length + ' plots, expected ' + expected);
  if (data.map) {
    if (!map || !map.renderer.getContext()) problems.push('no WebGL context for the map');
    else if (map.drawn !== map.points || map.points !== data.map.shown_points) problems.push('map points missing');
  }
  if (problems.length > 0) throw new Error(problems.join('; '));
  return plots.length + ' plots' + (map ? ', map of ' + map.points + ' points' : '');
}

(function main() {
  const status = document.getElementById('report-status');
  try {
    const data = JSON.parse(document.getElementById('report-data').textContent);
    const root = document.getElementById('report');
    header(root, data);
    pathsSection(root, data);
    errorsSection(root, data);
    timingSection(root, data);
    const map = data.map ? mapSection(root, data) : null;
    const summary = check(data, map);
    if (window.reportErrors.length === 0) {
      status.textContent = 'report-status: ok: ' + summary;
      status.className = 'ok';
    }
  } catch (e) {
    status.textContent = 'report-status: error: ' + e.message;
    status.className = 'error';
    throw e;
  }
})();

// The report page's interactive figures (issue 34; docs/rk-run.md "The report page"): time series that zoom and
// pan at full resolution (uPlot), and a 3-D view of a trajectory (three.js), linked by one time cursor.
// Bundled with uPlot and three.js into one script by esbuild at build time (apps/CMakeLists.txt) and inlined into
// each page by scripts/rk-report: the page fetches nothing.
//
// The page carries its data once, in <script type="application/json" id="rk-data">:
//   {"tables": {ID: {"n": rows, "t": SERIES, "cols": {name: SERIES}, "sigma": {name: SERIES (1σ of that column)},
//                    "status": {"names": [...], "codes": SERIES}, "bad": [[t0, t1], ...]}}}
// SERIES: {"q", "k0", "z"} (zlib int32 deltas, scripts/rk_interactive.py encode) or {"f64"}.
// and says where the figures go:
//   <div class="rk-chart" data-table=ID data-cols='["az_deg",...]' data-group=UNIT data-title=...>
//     one panel per column against t_s, its ±1σ band, the lost / invalid / predicted spans shaded; drag to zoom,
//     double-click to reset; the panels of one group (a unit) share their time window and cursor; the read-out
//     under each panel gives every series' value and 1σ at the cursor. data-wrap='["az_deg"]': columns that are
//     angles that wrap, whose line is not drawn across a wrap (more than half a turn between neighbouring rows).
//   <div class="rk-3d" data-table=ID data-x=e_m data-y=n_m data-z=u_m data-colour=time|status
//        data-stations='[{"name", "e", "n", "u"}]' data-group=UNIT>
//     the path coloured by time (or status), the stations, the ground plane, and at the cursor's time the
//     target and every station's line of sight to it; drag to orbit, wheel to zoom, right-drag to pan.
import uPlot from "uplot";
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

let data = null;  // parsed after the page's first paint (boot, at the end)
const decoded = new Map();

function bytes(b64) {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out;
}

async function inflate(b64) {
  const stream = new Blob([bytes(b64)]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Response(stream).arrayBuffer();
}

// One series (scripts/rk_interactive.py encode): int32 deltas of the value in units of q from k0, INT32_MIN a
// gap; or plain float64. A gap is null (uPlot draws none).
const NULL_DELTA = -2147483648;
async function decodeSeries(s) {
  if (s.f64) return Array.from(new Float64Array(await inflate(s.f64)), (v) => (Number.isFinite(v) ? v : null));
  const d = new Int32Array(await inflate(s.z));
  const out = new Array(d.length);
  let k = s.k0;
  for (let i = 0; i < d.length; ++i) {
    const x = d[i];
    if (x === NULL_DELTA) { out[i] = null; continue; }
    k += x;
    out[i] = k * s.q;
  }
  return out;
}

async function decodeTable(id) {
  const src = data.tables[id];
  const tab = { n: src.n, t: await decodeSeries(src.t), cols: {}, sigma: {}, bad: src.bad || [], status: null };
  for (const [k, v] of Object.entries(src.cols)) tab.cols[k] = await decodeSeries(v);
  for (const [k, v] of Object.entries(src.sigma || {})) tab.sigma[k] = await decodeSeries(v);
  if (src.status) tab.status = (await decodeSeries(src.status.codes)).map((c) => src.status.names[c]);
  decoded.set(id, tab);
}

function table(id) { return decoded.get(id); }

// Index of the row nearest t (t sorted ascending, gaps allowed).
function nearest(ts, t) {
  let lo = 0, hi = ts.length - 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (ts[mid] === null || ts[mid] < t) lo = mid + 1; else hi = mid;
  }
  if (lo > 0 && ts[lo - 1] !== null && Math.abs(ts[lo - 1] - t) <= Math.abs(ts[lo] - t)) return lo - 1;
  return lo;
}

function fmt(v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return "—";
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e7)) return v.toExponential(6);
  return Number(v.toPrecision(9)).toString();
}

// ---------------------------------------------------------------------------------------- the time cursor
const listeners = [];
function onTime(f) { listeners.push(f); }
function timeChanged(t, group) { for (const f of listeners) f(t, group); }

// ---------------------------------------------------------------------------------------------- charts
const groups = new Map();  // group → {charts: [uPlot], x: [min, max] | null, busy}
window.rkCharts = [];      // every chart made, for the browser test and the console

function group(name) {
  if (!groups.has(name)) groups.set(name, { charts: [], x: null, busy: false });
  return groups.get(name);
}

const COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"];

// An angle that wraps (data-wrap, scripts/rk_html.py angle_wraps): the rows [i, j] of each pair of neighbouring
// values more than half a turn apart (359.9° → 0.1°), where the line is the wrap, not a motion.
const HALF_TURN_DEG = 180;
function wrapBreaks(t, y) {
  const out = [];
  let last = -1;
  for (let i = 0; i < y.length; ++i) {
    if (y[i] === null || t[i] === null) { last = -1; continue; }
    if (last >= 0 && Math.abs(y[i] - y[last]) > HALF_TURN_DEG) out.push([last, i]);
    last = i;
  }
  return out;
}

// The first of the breaks that does not end before what is in view (endsBefore(row): that row is before it).
function firstBreakInView(breaks, endsBefore) {
  let lo = 0, hi = breaks.length;
  while (lo < hi) { const m = (lo + hi) >> 1; if (endsBefore(breaks[m][1])) lo = m + 1; else hi = m; }
  return lo;
}

// uPlot's series.gaps: the spans (canvas pixels) its line is clipped over — its own null gaps and, for an angle
// that wraps, each wrap's span (at least a pixel wide, so a wrap between rows drawn on one pixel column is not
// drawn either). Sorted and merged, as uPlot's clip expects.
function wrapGaps(t, breaks) {
  return (u, sidx, i0, i1, nullGaps) => {
    if (!breaks.length) return nullGaps;
    const out = nullGaps.map((g) => g.slice());
    for (let b = firstBreakInView(breaks, (j) => j < i0); b < breaks.length && breaks[b][0] <= i1; ++b) {
      const p0 = Math.round(u.valToPos(t[breaks[b][0]], "x", true));
      const p1 = Math.round(u.valToPos(t[breaks[b][1]], "x", true));
      out.push([p0, Math.max(p1, p0 + 1)]);
    }
    out.sort((p, q) => p[0] - q[0]);
    const merged = [];
    for (const g of out) {
      const m = merged[merged.length - 1];
      if (m && g[0] <= m[1]) m[1] = Math.max(m[1], g[1]); else merged.push(g);
    }
    return merged;
  };
}

// The rows on either side of each wrap, drawn as points: a target that sits on north and jitters across it wraps
// between every pair of rows, and its line, cut at each wrap, would show nothing at all.
function wrapPoints(t, breaks) {
  if (!breaks.length) return null;
  return (u) => {
    const { min, max } = u.scales.x;
    const out = [];
    for (let b = firstBreakInView(breaks, (j) => t[j] < min); b < breaks.length && t[breaks[b][0]] <= max; ++b) {
      for (const i of breaks[b]) if (out[out.length - 1] !== i && t[i] >= min && t[i] <= max) out.push(i);
    }
    return out;
  };
}

function makePanel(el, tab, col, k, g, groupName, wraps) {
  const sigma = tab.sigma[col] || null;
  const y = tab.cols[col];
  const colour = COLOURS[k % COLOURS.length];
  const breaks = wraps ? wrapBreaks(tab.t, y) : [];
  const gaps = wrapGaps(tab.t, breaks);
  const series = [{ label: "t_s" }, { label: col, stroke: colour, width: 1, spanGaps: false, gaps,
                                      points: { show: false, size: 3, fill: colour,
                                                filter: wrapPoints(tab.t, breaks) } }];
  const rows = [tab.t, y];
  const bands = [];
  if (sigma) {
    const lo = y.map((v, i) => (v === null || sigma[i] === null ? null : v - sigma[i]));
    const hi = y.map((v, i) => (v === null || sigma[i] === null ? null : v + sigma[i]));
    rows.push(hi, lo);
    series.push({ label: col + " +1σ", stroke: "transparent", spanGaps: false, gaps, points: { show: false } },
                { label: col + " −1σ", stroke: "transparent", spanGaps: false, gaps, points: { show: false } });
    bands.push({ series: [2, 3], fill: colour + "40" });
  }
  const readout = document.createElement("div");
  readout.className = "rk-readout";
  const box = document.createElement("div");
  el.appendChild(box);
  el.appendChild(readout);
  const width = Math.max(300, el.clientWidth || 800);
  const opts = {
    width, height: 170, series, bands,
    legend: { show: false },
    scales: { x: { time: false } },
    axes: [{ label: k === 0 ? "" : "", size: 36 }, { label: col, size: 70 }],
    cursor: { sync: { key: groupName }, drag: { x: true, y: false, setScale: true } },
    hooks: {
      // The lost / invalid / predicted spans, under the lines.
      drawClear: [(u) => {
        if (!tab.bad.length) return;
        const ctx = u.ctx;
        ctx.save();
        ctx.fillStyle = "rgba(217,83,79,0.15)";
        const { left, top, width: w, height: h } = u.bbox;
        for (const [a, b] of tab.bad) {
          const x0 = Math.max(left, u.valToPos(a, "x", true));
          const x1 = Math.min(left + w, u.valToPos(b, "x", true));
          if (x1 > x0) ctx.fillRect(x0, top, Math.max(1, x1 - x0), h);
        }
        ctx.restore();
      }],
      setCursor: [(u) => {
        const i = u.cursor.idx;
        if (i === null || i === undefined) return;
        const t = tab.t[i];
        readout.textContent = "t_s " + fmt(t) + " · " + col + " " + fmt(y[i]) +
          (sigma ? " ± " + fmt(sigma[i]) + " (1σ)" : "") + (tab.status ? " · " + tab.status[i] : "");
        readout.dataset.t = String(t);
        readout.dataset.value = String(y[i]);
        readout.dataset.sigma = sigma ? String(sigma[i]) : "";
        if (!g.busy) timeChanged(t, groupName);
      }],
      // One time window for every panel of the group (drag to zoom, double-click to reset).
      setScale: [(u, key) => {
        if (key !== "x" || g.busy) return;
        g.busy = true;
        const { min, max } = u.scales.x;
        g.x = [min, max];
        for (const other of g.charts) if (other !== u) other.setScale("x", { min, max });
        g.busy = false;
      }],
    },
  };
  const u = new uPlot(opts, rows, box);
  u.rkColumn = col;
  u.rkWrapBreaks = breaks;
  u.rkReadout = readout;
  u.rkGroup = groupName;
  g.charts.push(u);
  window.rkCharts.push(u);
  if (g.x) {
    g.busy = true;
    u.setScale("x", { min: g.x[0], max: g.x[1] });
    g.busy = false;
  }
  return u;
}

function makeChart(el) {
  const tab = table(el.dataset.table);
  const cols = JSON.parse(el.dataset.cols);
  const wrap = new Set(JSON.parse(el.dataset.wrap || "[]"));
  const g = group(el.dataset.group || el.dataset.table);
  cols.forEach((c, k) => {
    if (tab.cols[c]) makePanel(el, tab, c, k, g, el.dataset.group || el.dataset.table, wrap.has(c));
  });
}

// --------------------------------------------------------------------------------------------- 3-D view
function viridis(f) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const x = Math.min(1, Math.max(0, f)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const r = x - i;
  return stops[i].map((c, k) => (c + r * (stops[i + 1][k] - c)) / 255);
}
const STATUS_RGB = { ok: [0.17, 0.63, 0.17], reacquired: [0.12, 0.47, 0.71], predicted: [1.0, 0.5, 0.05],
                     lost: [0.5, 0.5, 0.5], invalid: [0.84, 0.15, 0.16] };

function make3d(el) {
  const tab = table(el.dataset.table);
  const X = tab.cols[el.dataset.x], Y = tab.cols[el.dataset.y], Z = tab.cols[el.dataset.z];
  const stations = JSON.parse(el.dataset.stations || "[]");
  const canvasBox = document.createElement("div");
  const info = document.createElement("div");
  info.className = "rk-readout";
  el.appendChild(canvasBox);
  el.appendChild(info);
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    info.textContent = "The 3-D view needs WebGL, which this browser does not offer (" + e.message + ").";
    el.dataset.ready = "no-webgl";
    return;
  }
  const width = Math.max(300, el.clientWidth || 800), height = 480;
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(width, height);
  canvasBox.appendChild(renderer.domElement);
  // Scene axes: x east, y up, z south (three.js is y-up): ENU (e, n, u) → (e, u, −n), about the path's centre.
  const pts = [];
  for (let i = 0; i < tab.n; ++i) if (X[i] !== null && Y[i] !== null && Z[i] !== null) pts.push(i);
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  const grow = (e, n, u) => { [e, n, u].forEach((v, k) => { lo[k] = Math.min(lo[k], v); hi[k] = Math.max(hi[k], v); }); };
  for (const i of pts) grow(X[i], Y[i], Z[i]);
  for (const s of stations) grow(s.e, s.n, s.u);
  if (!pts.length) { info.textContent = "no position to show"; return; }
  const c = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 0];
  const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1);
  const v3 = (e, n, u) => new THREE.Vector3(e - c[0], u - c[2], -(n - c[1]));
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  // Framed on the bounding sphere of the path, the stations and the ground under them, seen from the south-west
  // and above.
  const centre = v3(c[0], c[1], (Math.min(lo[2], 0) + hi[2]) / 2);
  const radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - Math.min(lo[2], 0)) || 1;
  const fov = 45;
  const camera = new THREE.PerspectiveCamera(fov, width / height, radius / 1000, radius * 40);
  const distance = 1.15 * radius / Math.sin((fov / 2) * Math.PI / 180);
  const look = new THREE.Vector3(-0.55, 0.45, 0.7).normalize();  // from the south-west, 27° above the horizon
  camera.position.copy(centre.clone().addScaledVector(look, distance));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.update();
  // The path: every row, coloured by time (or status).
  const pos = new Float32Array(pts.length * 3), col = new Float32Array(pts.length * 3);
  const t0 = tab.t[pts[0]], t1 = tab.t[pts[pts.length - 1]];
  const paint = (by) => {
    pts.forEach((i, k) => {
      const rgb = by === "status" && tab.status ? (STATUS_RGB[tab.status[i]] || [0, 0, 0])
        : viridis((tab.t[i] - t0) / Math.max(t1 - t0, 1e-9));
      col.set(rgb, 3 * k);
    });
  };
  pts.forEach((i, k) => {
    const p = v3(X[i], Y[i], Z[i]);
    pos.set([p.x, p.y, p.z], 3 * k);
  });
  paint(el.dataset.colour);
  const geo = new THREE.BufferGeometry();
  geo.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  geo.setAttribute("color", new THREE.BufferAttribute(col, 3));
  // Colour by time (viridis: dark at the start, yellow at the end) or by status (green ok, blue reacquired,
  // orange predicted, grey lost, red invalid).
  if (tab.status) {
    const pick = document.createElement("select");
    pick.className = "rk-colour";
    for (const [v, label] of [["time", "colour by time"], ["status", "colour by status"]]) {
      const o = document.createElement("option");
      o.value = v;
      o.textContent = label;
      o.selected = v === el.dataset.colour;
      pick.appendChild(o);
    }
    pick.addEventListener("change", () => {
      paint(pick.value);
      geo.attributes.color.needsUpdate = true;
      render();
    });
    el.insertBefore(pick, canvasBox);
  }
  scene.add(new THREE.Line(geo, new THREE.LineBasicMaterial({ vertexColors: true })));
  // The ground plane (u = 0 of the frame) as a grid.
  const grid = new THREE.GridHelper(span * 1.4, 14, 0x999999, 0xdddddd);
  grid.position.copy(v3(c[0], c[1], 0));
  scene.add(grid);
  // The stations.
  const marker = (colour, size) => new THREE.Mesh(new THREE.SphereGeometry(size, 16, 12),
                                                 new THREE.MeshBasicMaterial({ color: colour }));
  for (const s of stations) {
    const m = marker(0x000000, span / 120);
    m.position.copy(v3(s.e, s.n, s.u));
    scene.add(m);
  }
  // At the cursor's time: the target and each station's line of sight to it.
  const target = marker(0xd62728, span / 150);
  target.visible = false;
  scene.add(target);
  const sight = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xd62728 }));
  sight.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(Math.max(1, stations.length) * 6), 3));
  sight.visible = false;
  scene.add(sight);
  const render = () => renderer.render(scene, camera);
  controls.addEventListener("change", render);
  onTime((t) => {
    const i = nearest(tab.t, t);
    if (X[i] === null || Y[i] === null || Z[i] === null) return;
    const p = v3(X[i], Y[i], Z[i]);
    target.position.copy(p);
    target.visible = true;
    const a = sight.geometry.attributes.position;
    stations.forEach((s, k) => {
      const q = v3(s.e, s.n, s.u);
      a.setXYZ(2 * k, q.x, q.y, q.z);
      a.setXYZ(2 * k + 1, p.x, p.y, p.z);
    });
    a.needsUpdate = true;
    sight.geometry.setDrawRange(0, 2 * stations.length);
    sight.visible = stations.length > 0;
    info.textContent = "t_s " + fmt(tab.t[i]) + " · " + el.dataset.x + " " + fmt(X[i]) + " · " + el.dataset.y + " " +
      fmt(Y[i]) + " · " + el.dataset.z + " " + fmt(Z[i]) + (tab.status ? " · " + tab.status[i] : "");
    info.dataset.t = String(tab.t[i]);
    render();
  });
  render();
  el.dataset.ready = "yes";
  window.rkViews = (window.rkViews || []).concat([{ el, scene, camera, controls, render }]);
}

// -------------------------------------------------------------------------------------------- start-up
// Figures are made when they come near the screen, so a long page paints at once.
function start() {
  const made = new WeakSet();
  const make = (el) => {
    if (made.has(el)) return;
    made.add(el);
    try {
      if (el.classList.contains("rk-chart")) makeChart(el); else make3d(el);
    } catch (e) {
      el.textContent = "figure not drawn: " + e.message;
      el.dataset.ready = "error";
      throw e;
    }
  };
  const els = document.querySelectorAll(".rk-chart, .rk-3d");
  window.rkMakeAll = () => els.forEach(make);
  if ("IntersectionObserver" in window) {
    const io = new IntersectionObserver((entries) => {
      for (const e of entries) if (e.isIntersecting) { make(e.target); io.unobserve(e.target); }
    }, { rootMargin: "400px" });
    els.forEach((el) => io.observe(el));
  } else {
    window.rkMakeAll();
  }
}
// The data (megabytes for a long trial) are read after the page has painted its text and tables: a frame, then
// a task.
function boot() {
  data = JSON.parse(document.getElementById("rk-data").textContent);
  Promise.all(Object.keys(data.tables).map(decodeTable)).then(() => {
    start();
    window.rkReady = true;
  }, (e) => {
    document.querySelectorAll(".rk-chart, .rk-3d").forEach((el) => { el.textContent = "figure not drawn: " + e.message; });
    throw e;
  });
}
requestAnimationFrame(() => setTimeout(boot, 0));

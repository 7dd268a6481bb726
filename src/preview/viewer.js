// lmdc's plan viewer: a canvas 2-D renderer of the plan's moves, projected
// orthographically. Deposits are drawn in colour buckets (one stroke per
// colour, so a frame is a few dozen strokes however many moves), travel
// moves faint and grey. Reads the JSON in <script id="data">, written by
// src/preview/encode.rs; needs nothing from the network.
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("data").textContent);
  const M = D.meta;
  const $ = (id) => document.getElementById(id);

  // --- the data -----------------------------------------------------------
  function bytes(b64) {
    const s = atob(b64);
    const a = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) a[i] = s.charCodeAt(i);
    return a;
  }
  // A column of 16-bit fractions of its range, back to numbers.
  function column(name, k) {
    const b = bytes(D[name]);
    const [lo, hi] = D.ranges[k];
    const step = (hi - lo) / 65535;
    const out = new Float32Array(b.length / 2);
    for (let i = 0; i < out.length; i++) out[i] = lo + (b[2 * i] | (b[2 * i + 1] << 8)) * step;
    return out;
  }
  const N = M.kept;
  const X = column("x", 0), Y = column("y", 1), Z = column("z", 2);
  const VALUES = { speed: column("speed", 3), height: column("height", 4), power: column("power", 5) };
  const STYLE = bytes(D.style), FLAGS = bytes(D.flags);
  const DEPOSIT = 1, GAP = 2;
  const STARTS = M.starts; // [layer number, first move] of each layer on the page
  const LAYER = new Uint32Array(N); // index into STARTS of each move
  for (let k = 0; k < STARTS.length; k++) {
    const end = k + 1 < STARTS.length ? STARTS[k + 1][1] : N;
    LAYER.fill(k, STARTS[k][1], end);
  }
  const LAYER_NUMBER = new Float32Array(N);
  for (let i = 0; i < N; i++) LAYER_NUMBER[i] = STARTS.length ? STARTS[LAYER[i]][0] : 0;
  VALUES.layer = LAYER_NUMBER;
  const UNITS = { speed: "mm/s", height: "mm", power: "W", layer: "" };

  // --- colours ------------------------------------------------------------
  const RAMP = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
                [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];
  function ramp(t) {
    const x = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
    const i = Math.min(Math.floor(x), RAMP.length - 2), f = x - i;
    const c = RAMP[i].map((v, k) => Math.round(v + (RAMP[i + 1][k] - v) * f));
    return `rgb(${c[0]},${c[1]},${c[2]})`;
  }
  const BUCKETS = 32;
  const PALETTE = ["#4c78a8", "#f58518", "#54a24b", "#e45756", "#72b7b2", "#b279a2", "#ff9da6", "#9d755d"];
  function styleColour(id) {
    const s = M.styles.find((s) => s.id === id);
    return s ? s.colour : PALETTE[id % PALETTE.length];
  }
  function styleName(id) {
    const s = M.styles.find((s) => s.id === id);
    return s ? s.name : id === 0 ? "process" : `style ${id}`;
  }

  // Deposits sorted into colour buckets by the chosen quantity (a counting
  // sort), travel moves on a list of their own.
  let buckets = [], colours = [], travel = new Uint32Array(0), legend = null;
  function bucketise(q) {
    const bucket = new Int32Array(N).fill(-1);
    if (q === "style") {
      const ids = [...new Set(Array.from(STYLE))].sort((a, b) => a - b);
      const at = new Map(ids.map((id, k) => [id, k]));
      for (let i = 0; i < N; i++) if (FLAGS[i] & DEPOSIT) bucket[i] = at.get(STYLE[i]);
      colours = ids.map(styleColour);
      legend = { styles: ids };
    } else {
      const v = VALUES[q];
      let lo = Infinity, hi = -Infinity;
      for (let i = 0; i < N; i++) if (FLAGS[i] & DEPOSIT) { lo = Math.min(lo, v[i]); hi = Math.max(hi, v[i]); }
      if (!(hi >= lo)) { lo = 0; hi = 0; }
      const span = hi > lo ? hi - lo : 1;
      for (let i = 0; i < N; i++)
        if (FLAGS[i] & DEPOSIT) bucket[i] = Math.round(((v[i] - lo) / span) * (BUCKETS - 1));
      colours = Array.from({ length: BUCKETS }, (_, b) => ramp(b / (BUCKETS - 1)));
      legend = { lo, hi, unit: UNITS[q] };
    }
    const count = new Uint32Array(colours.length + 1);
    let travelCount = 0;
    for (let i = 0; i < N; i++) bucket[i] >= 0 ? count[bucket[i] + 1]++ : travelCount++;
    for (let b = 1; b <= colours.length; b++) count[b] += count[b - 1];
    const order = new Uint32Array(count[colours.length]);
    const fill = count.slice();
    travel = new Uint32Array(travelCount);
    let t = 0;
    for (let i = 0; i < N; i++) bucket[i] >= 0 ? (order[fill[bucket[i]]++] = i) : (travel[t++] = i);
    buckets = colours.map((_, b) => order.subarray(count[b], count[b + 1]));
    drawLegend(q);
  }

  function fmt(x) {
    return Math.abs(x) >= 100 ? x.toFixed(0) : Math.abs(x) >= 10 ? x.toFixed(1) : x.toFixed(2);
  }
  function drawLegend(q) {
    const el = $("legend");
    el.textContent = "";
    const title = document.createElement("div");
    title.textContent = { speed: "speed", height: "layer height", power: "laser power", style: "style", layer: "layer" }[q];
    el.appendChild(title);
    if (legend.styles) {
      for (const id of legend.styles) {
        const row = document.createElement("div");
        const sw = document.createElement("span");
        sw.className = "swatch";
        sw.style.background = styleColour(id);
        row.appendChild(sw);
        row.appendChild(document.createTextNode(styleName(id)));
        el.appendChild(row);
      }
    } else {
      const bar = document.createElement("div");
      bar.className = "bar";
      bar.style.background = `linear-gradient(to right, ${RAMP.map((_, k) => ramp(k / (RAMP.length - 1))).join(",")})`;
      el.appendChild(bar);
      const row = document.createElement("div");
      row.className = "row";
      for (const v of [legend.lo, legend.hi]) {
        const s = document.createElement("span");
        s.textContent = `${fmt(v)} ${legend.unit}`;
        row.appendChild(s);
      }
      el.appendChild(row);
    }
    const t = document.createElement("div");
    t.style.color = "#777";
    t.textContent = "grey: travel (laser off)";
    el.appendChild(t);
  }

  // --- the view -----------------------------------------------------------
  const canvas = $("view"), ctx = canvas.getContext("2d");
  const bounds = D.ranges.slice(0, 3);
  const centre = bounds.map(([lo, hi]) => (lo + hi) / 2);
  const size = Math.hypot(...bounds.map(([lo, hi]) => hi - lo)) || 1;
  const HOME = { yaw: -0.6, pitch: 0.5, zoom: 0.9, panX: 0, panY: 0 };
  const view = Object.assign({}, HOME);
  const PX = new Float32Array(N), PY = new Float32Array(N);
  let range = [0, Math.max(STARTS.length - 1, 0)];
  let showTravel = true;

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    for (const c of [canvas, $("plot")]) {
      c.width = Math.max(1, Math.round(c.clientWidth * dpr));
      c.height = Math.max(1, Math.round(c.clientHeight * dpr));
    }
  }

  // Orthographic: turn about z (yaw), then tilt toward the viewer (pitch).
  function project() {
    const W = canvas.width, H = canvas.height;
    const scale = (view.zoom * Math.min(W, H)) / size;
    const cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
    const cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
    const ox = W / 2 + view.panX * W, oy = H / 2 + view.panY * H;
    for (let i = 0; i < N; i++) {
      const dx = X[i] - centre[0], dy = Y[i] - centre[1], dz = Z[i] - centre[2];
      const x1 = cy * dx - sy * dy, y1 = sy * dx + cy * dy;
      PX[i] = ox + scale * x1;
      PY[i] = oy - scale * (cp * dz + sp * y1);
    }
  }

  function strokeList(list) {
    const [a, b] = range;
    ctx.beginPath();
    for (let k = 0; k < list.length; k++) {
      const i = list[k];
      if (i === 0 || FLAGS[i] & GAP) continue;
      const l = LAYER[i];
      if (l < a || l > b) continue;
      ctx.moveTo(PX[i - 1], PY[i - 1]);
      ctx.lineTo(PX[i], PY[i]);
    }
    ctx.stroke();
  }

  function draw() {
    const dpr = window.devicePixelRatio || 1;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    project();
    ctx.lineCap = "round";
    if (showTravel) {
      ctx.lineWidth = dpr;
      ctx.strokeStyle = "rgba(110,110,110,0.3)";
      strokeList(travel);
    }
    ctx.lineWidth = 1.6 * dpr;
    for (let b = 0; b < buckets.length; b++) {
      ctx.strokeStyle = colours[b];
      strokeList(buckets[b]);
    }
  }

  let queued = false;
  function redraw() {
    if (queued) return;
    queued = true;
    requestAnimationFrame(() => { queued = false; draw(); });
  }

  // --- per-layer plots: speed and height along the deposit path ----------
  function plot() {
    const c = $("plot"), g = c.getContext("2d");
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    g.fillStyle = "#fff";
    g.fillRect(0, 0, W, H);
    const k = range[1];
    if (!STARTS.length) return;
    const first = STARTS[k][1], end = k + 1 < STARTS.length ? STARTS[k + 1][1] : N;
    const s = [], v = [], h = [];
    let along = 0;
    for (let i = Math.max(first, 1); i < end; i++) {
      if (!(FLAGS[i] & DEPOSIT) || FLAGS[i] & GAP) continue;
      along += Math.hypot(X[i] - X[i - 1], Y[i] - Y[i - 1], Z[i] - Z[i - 1]);
      s.push(along); v.push(VALUES.speed[i]); h.push(VALUES.height[i]);
    }
    $("plot-title").textContent =
      `layer ${STARTS[k][0]}: speed and layer height along the deposit path (${fmt(along)} mm)`;
    const panel = (ys, top, height, label, colour) => {
      const left = 70 * dpr, right = W - 16 * dpr;
      let lo = Infinity, hi = -Infinity;
      for (const y of ys) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
      if (!(hi > lo)) { lo -= 0.5; hi += 0.5; }
      g.strokeStyle = "#bbb"; g.lineWidth = dpr;
      g.strokeRect(left, top, right - left, height);
      g.fillStyle = "#333"; g.font = `${11 * dpr}px sans-serif`;
      g.fillText(fmt(hi), 6 * dpr, top + 10 * dpr);
      g.fillText(fmt(lo), 6 * dpr, top + height);
      g.fillText(label, left + 6 * dpr, top + 13 * dpr);
      if (!ys.length) return;
      g.strokeStyle = colour; g.lineWidth = 1.5 * dpr;
      g.beginPath();
      for (let j = 0; j < ys.length; j++) {
        const x = left + ((right - left) * s[j]) / (along || 1);
        const y = top + height - (height * (ys[j] - lo)) / (hi - lo);
        j ? g.lineTo(x, y) : g.moveTo(x, y);
      }
      g.stroke();
    };
    const gap = 10 * dpr, ph = (H - 3 * gap) / 2;
    panel(v, gap, ph, "speed, mm/s", "#1f77b4");
    panel(h, 2 * gap + ph, ph, "layer height, mm", "#d62728");
  }

  // --- controls -----------------------------------------------------------
  function showRange() {
    if (!STARTS.length) return;
    $("range").textContent = `${STARTS[range[0]][0]} – ${STARTS[range[1]][0]} of ${M.layers}`;
  }
  const from = $("from"), to = $("to");
  from.max = to.max = String(Math.max(STARTS.length - 1, 0));
  to.value = String(range[1]);
  from.addEventListener("input", () => {
    range[0] = +from.value;
    if (range[0] > range[1]) { range[1] = range[0]; to.value = from.value; plot(); }
    showRange(); redraw();
  });
  to.addEventListener("input", () => {
    range[1] = +to.value;
    if (range[1] < range[0]) { range[0] = range[1]; from.value = to.value; }
    showRange(); plot(); redraw();
  });
  $("quantity").addEventListener("change", (e) => { bucketise(e.target.value); redraw(); });
  $("travel").addEventListener("change", (e) => { showTravel = e.target.checked; redraw(); });
  const reset = () => { Object.assign(view, HOME); redraw(); };
  $("reset").addEventListener("click", reset);
  canvas.addEventListener("dblclick", reset);
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      view.panX += dx / canvas.clientWidth;
      view.panY += dy / canvas.clientHeight;
    } else {
      view.yaw += dx * 0.01;
      view.pitch = Math.min(Math.PI / 2, Math.max(-Math.PI / 2, view.pitch + dy * 0.01));
    }
    redraw();
  });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    view.zoom *= Math.exp(-e.deltaY * 0.001);
    redraw();
  }, { passive: false });
  window.addEventListener("resize", () => { resize(); plot(); redraw(); });

  // --- the page's own account of what it shows (tests read it) ------------
  $("heading").textContent = `${M.part} on ${M.machine}`;
  document.title = `lmdc preview: ${M.part} on ${M.machine}: ${M.layers} layers`;
  const summary = $("summary");
  summary.textContent = `${M.layers} layers, ${M.points} points, ${M.moves} moves of the motion plan ` +
    `(tool tip at the laser focus; ${M.generator})`;
  summary.dataset.layers = M.layers;
  summary.dataset.shownLayers = STARTS.length;
  summary.dataset.moves = M.moves;
  summary.dataset.shownMoves = N;
  const [everyLayer, everyMove] = M.decimation;
  if (everyLayer > 1 || everyMove > 1)
    $("note").textContent = `Decimated for the browser: every ${everyLayer}th layer (and the last) and every ` +
      `${everyMove}th deposit move of each path (and its last) are shown, ${N} of ${M.moves} moves; ` +
      `the programs have every one.`;

  resize();
  bucketise("speed");
  showRange();
  const t0 = performance.now();
  draw();
  // What one frame of the whole plan costs here: orbiting redraws it.
  canvas.dataset.frameMs = Math.round(performance.now() - t0);
  plot();
  // How much of the view the first frame painted: a blank page says 0.
  const px = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  let painted = 0;
  for (let i = 0; i < px.length; i += 4) if (px[i] < 245 || px[i + 1] < 245 || px[i + 2] < 245) painted++;
  canvas.dataset.painted = painted;
})();

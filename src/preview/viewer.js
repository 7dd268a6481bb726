// lmdc's plan viewer: a canvas 2-D renderer of the plan's moves, projected
// orthographically. Deposits are drawn in colour buckets (one stroke per
// colour, so a frame is a few dozen strokes however many moves), travel
// moves faint and grey, over the substrate (a grid at z = 0) with the part's
// axes and a scale bar; a slider over the moves draws the head's solids and
// a robot's links at the chosen one over the part laid by then. Reads the
// JSON in <script id="data">, written by src/preview/encode.rs; needs
// nothing from the network.
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
  const VALUES = {
    speed: column("speed", 3), height: column("height", 4), power: column("power", 5),
    error: column("error", 6),
  };
  const STYLE = bytes(D.style), FLAGS = bytes(D.flags);
  // The flag bits (encode.rs): laser on, no line leads here, error predicted;
  // the path kind (an index into M.kinds) from bit 3 up.
  const DEPOSIT = 1, GAP = 2, PREDICTED = 4, KIND_SHIFT = 3;
  const KIND = new Uint8Array(N);
  for (let i = 0; i < N; i++) KIND[i] = FLAGS[i] >> KIND_SHIFT;
  const TRAVEL_KIND = M.kinds.indexOf("travel");
  const STARTS = M.starts; // [layer number, first move] of each layer on the page
  const LAYER = new Uint32Array(N); // index into STARTS of each move
  for (let k = 0; k < STARTS.length; k++) {
    const end = k + 1 < STARTS.length ? STARTS[k + 1][1] : N;
    LAYER.fill(k, STARTS[k][1], end);
  }
  const LAYER_NUMBER = new Float32Array(N);
  for (let i = 0; i < N; i++) LAYER_NUMBER[i] = STARTS.length ? STARTS[LAYER[i]][0] : 0;
  VALUES.layer = LAYER_NUMBER;
  // With a thermal prediction (docs/thermal.md): each move coloured by its
  // layer's interpass temperature.
  if (M.thermal) {
    const t = M.thermal.interpass;
    VALUES.interpass = LAYER_NUMBER.map((l) => t[Math.min(Math.max(l - 1, 0), t.length - 1)] || 0);
  }
  // Where each move is (encode.rs, Poses): a tag byte and what changed
  // since the move before, in LEB128 varints. Decoded once into columns: its
  // target's kind (0 a point, 1 a clearance move, 2 the end), layer, path and
  // point (from 0), the plan's move index, the plan's deposit moves up to it
  // (its own included), and the unit vector up its beam.
  const P_KIND = new Uint8Array(N), P_LAYER = new Uint32Array(N), P_PATH = new Uint32Array(N);
  const P_POINT = new Uint32Array(N), P_INDEX = new Float64Array(N), P_LAID = new Float64Array(N);
  const BEAM = new Float32Array(3 * N);
  (function () {
    const b = bytes(D.poses || "");
    let at = 0, layer = 0, path = 0, point = 0, index = -1, laid = 0, beam = [0, 0, 1];
    const varint = () => {
      let v = 0, scale = 1, x;
      do { x = b[at++]; v += (x & 127) * scale; scale *= 128; } while (x & 128 && at < b.length);
      return v;
    };
    for (let i = 0; i < N && at < b.length; i++) {
      const tag = b[at++];
      if (tag & 4) layer = varint();
      if (tag & 8) { path = varint(); point = 0; }
      let skipped = 0, skippedLaid = 0;
      if (tag & 16) { skipped = varint(); skippedLaid = varint(); }
      const kind = tag & 3;
      if (kind === 0) { const z = varint(); point += z % 2 ? -(z + 1) / 2 : z / 2; }
      if (tag & 32) {
        beam = [0, 1, 2].map((k) => {
          const v = b[at + 2 * k] | (b[at + 2 * k + 1] << 8);
          return (v >= 32768 ? v - 65536 : v) / 32767;
        });
        at += 6;
        const len = Math.hypot(...beam) || 1;
        beam = beam.map((v) => v / len);
      }
      index += 1 + skipped;
      laid += skippedLaid + (FLAGS[i] & DEPOSIT ? 1 : 0);
      P_KIND[i] = kind; P_LAYER[i] = layer; P_PATH[i] = path; P_POINT[i] = point;
      P_INDEX[i] = index; P_LAID[i] = laid;
      BEAM.set(beam, 3 * i);
    }
  })();
  // The page's deposit moves up to each move, its own included.
  const LAID = new Uint32Array(N);
  for (let i = 0, n = 0; i < N; i++) { if (FLAGS[i] & DEPOSIT) n++; LAID[i] = n; }
  const DEPOSITS = N ? LAID[N - 1] : 0;
  const PLAN_DEPOSITS = N ? P_LAID[N - 1] : 0;
  const UNITS = { speed: "mm/s", height: "mm", power: "W", layer: "", interpass: "°C" };
  const TITLES = {
    speed: "speed", height: "layer height", power: "laser power", style: "style", layer: "layer",
    interpass: "interpass temperature: the layer's start, predicted",
    error: "height error: predicted rise / layer height − 1", kind: "path kind",
  };

  // --- colours ------------------------------------------------------------
  const RAMP = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
                [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];
  const rgb = (c) => `rgb(${c[0]},${c[1]},${c[2]})`;
  // Piecewise linear through `stops` ([t, [r, g, b]], t rising).
  function through(stops, t) {
    let k = 0;
    while (k + 2 < stops.length && t > stops[k + 1][0]) k++;
    const [t0, a] = stops[k], [t1, b] = stops[k + 1];
    const f = Math.min(Math.max((t - t0) / (t1 - t0), 0), 1);
    return rgb(a.map((v, j) => Math.round(v + (b[j] - v) * f)));
  }
  function ramp(t) {
    return through(RAMP.map((c, k) => [k / (RAMP.length - 1), c]), Math.min(Math.max(t, 0), 1));
  }
  // The height error's diverging scale over t in [-1, 1]: blue lays too
  // little, red too much. Its centre is a dark neutral grey, not the white
  // of the usual diverging maps, which would vanish on the white view; and
  // it stays nearly neutral to |t| = 0.25 (±1 % on the least range of ±5 %
  // reads as on plan), then turns blue or red, more saturated the further.
  const DIVERGE = [[-1, [25, 95, 235]], [-0.55, [60, 110, 195]], [-0.25, [76, 84, 108]],
                   [0, [72, 72, 72]], [0.25, [108, 78, 72]], [0.55, [200, 65, 50]], [1, [235, 35, 25]]];
  const diverge = (t) => through(DIVERGE, Math.min(Math.max(t, -1), 1));
  const UNPREDICTED = "rgb(190,190,190)";
  const BUCKETS = 32;
  const ERROR_BUCKETS = 33; // odd: the middle one is 0
  const PALETTE = ["#4c78a8", "#f58518", "#54a24b", "#e45756", "#72b7b2", "#b279a2", "#ff9da6", "#9d755d"];
  // Path kinds by name (M.kinds says which number is which).
  const KIND_COLOURS = { wall: "#4e79a7", contour: "#f28e2b", infill: "#59a14f", link: "#e15759", travel: "#9467bd" };
  const TRAVEL_GREY = "rgba(110,110,110,0.3)", TRAVEL_KIND_COLOUR = "rgba(148,103,189,0.6)";
  function styleColour(id) {
    const s = M.styles.find((s) => s.id === id);
    return s ? s.colour : PALETTE[id % PALETTE.length];
  }
  function styleName(id) {
    const s = M.styles.find((s) => s.id === id);
    return s ? s.name : id === 0 ? "process" : `style ${id}`;
  }
  // A round length (1, 2 or 5 times a power of ten) at or above x, or below.
  function niceUp(x) {
    const p = Math.pow(10, Math.floor(Math.log10(x)));
    for (const m of [1, 2, 5, 10]) if (m * p >= x * (1 - 1e-9)) return m * p;
    return 10 * p;
  }
  function niceDown(x) {
    const p = Math.pow(10, Math.floor(Math.log10(x)));
    for (const m of [5, 2, 1]) if (m * p <= x * (1 + 1e-9)) return m * p;
    return p;
  }

  // Deposits sorted into colour buckets by the chosen quantity (a counting
  // sort), travel moves on a list of their own.
  let buckets = [], colours = [], order = [], travel = new Uint32Array(0), legend = null;
  let mode = "speed";
  // The least range the height error's scale spans, per cent.
  const ERROR_SPAN = 5;
  let errorSpan = ERROR_SPAN;
  function bucketise(q) {
    mode = q;
    const bucket = new Int32Array(N).fill(-1);
    order = null;
    if (q === "style") {
      const ids = [...new Set(Array.from(STYLE))].sort((a, b) => a - b);
      const at = new Map(ids.map((id, k) => [id, k]));
      for (let i = 0; i < N; i++) if (FLAGS[i] & DEPOSIT) bucket[i] = at.get(STYLE[i]);
      colours = ids.map(styleColour);
      legend = { styles: ids };
    } else if (q === "kind") {
      const count = M.kinds.map(() => 0);
      for (let i = 0; i < N; i++) count[KIND[i]]++;
      const shown = M.kinds.map((_, k) => k).filter((k) => k !== TRAVEL_KIND && count[k] > 0);
      const at = new Map(shown.map((k, b) => [k, b]));
      for (let i = 0; i < N; i++) if (FLAGS[i] & DEPOSIT && at.has(KIND[i])) bucket[i] = at.get(KIND[i]);
      colours = shown.map((k) => KIND_COLOURS[M.kinds[k]] || "#000");
      legend = { kinds: shown.map((k) => [M.kinds[k], count[k]]), travel: count[TRAVEL_KIND] || 0 };
    } else if (q === "error") {
      const v = VALUES.error;
      let lo = Infinity, hi = -Infinity, unpredicted = 0;
      for (let i = 0; i < N; i++) {
        if (!(FLAGS[i] & DEPOSIT)) continue;
        if (FLAGS[i] & PREDICTED) { lo = Math.min(lo, v[i]); hi = Math.max(hi, v[i]); } else unpredicted++;
      }
      // Symmetric about 0, at least ±5 %, a round number.
      const worst = hi >= lo ? Math.max(Math.abs(lo), Math.abs(hi)) : 0;
      errorSpan = Math.max(ERROR_SPAN, niceUp(worst || 1));
      const mid = (ERROR_BUCKETS - 1) / 2;
      for (let i = 0; i < N; i++) {
        if (!(FLAGS[i] & DEPOSIT)) continue;
        bucket[i] = FLAGS[i] & PREDICTED
          ? Math.min(Math.max(Math.round(mid + (v[i] / errorSpan) * mid), 0), ERROR_BUCKETS - 1)
          : ERROR_BUCKETS;
      }
      colours = Array.from({ length: ERROR_BUCKETS }, (_, b) => diverge((b - mid) / mid));
      colours.push(UNPREDICTED);
      // The unpredicted first, then outwards from 0: the worst on top.
      order = [ERROR_BUCKETS, ...Array.from({ length: ERROR_BUCKETS }, (_, b) => b)
        .sort((a, b) => Math.abs(a - mid) - Math.abs(b - mid) || a - b)];
      legend = { span: errorSpan, lo, hi, unpredicted, predicted: hi >= lo };
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
    if (!order) order = colours.map((_, b) => b);
    const count = new Uint32Array(colours.length + 1);
    let travelCount = 0;
    for (let i = 0; i < N; i++) bucket[i] >= 0 ? count[bucket[i] + 1]++ : travelCount++;
    for (let b = 1; b <= colours.length; b++) count[b] += count[b - 1];
    const sorted = new Uint32Array(count[colours.length]);
    const fill = count.slice();
    travel = new Uint32Array(travelCount);
    let t = 0;
    for (let i = 0; i < N; i++) bucket[i] >= 0 ? (sorted[fill[bucket[i]]++] = i) : (travel[t++] = i);
    buckets = colours.map((_, b) => sorted.subarray(count[b], count[b + 1]));
    drawLegend(q);
  }

  function fmt(x) {
    return Math.abs(x) >= 100 ? x.toFixed(0) : Math.abs(x) >= 10 ? x.toFixed(1) : x.toFixed(2);
  }
  // With its sign (a typographic minus), none where it rounds to 0.
  function signed(x, d) {
    const r = +x.toFixed(d);
    return (r > 0 ? "+" : r < 0 ? "−" : "") + Math.abs(r).toFixed(d);
  }
  function el(tag, text, cls) {
    const e = document.createElement(tag);
    if (text !== undefined) e.textContent = text;
    if (cls) e.className = cls;
    return e;
  }
  function swatchRow(colour, text) {
    const row = el("div");
    const sw = el("span", undefined, "swatch");
    sw.style.background = colour;
    row.appendChild(sw);
    row.appendChild(document.createTextNode(text));
    return row;
  }
  function scaleRow(labels) {
    const row = el("div", undefined, "row");
    for (const s of labels) row.appendChild(el("span", s));
    return row;
  }
  function drawLegend(q) {
    const box = $("legend");
    box.textContent = "";
    box.dataset.mode = q;
    box.appendChild(el("div", TITLES[q], "title"));
    let travelText = "thin grey: travel (laser off)";
    if (legend.styles) {
      for (const id of legend.styles) box.appendChild(swatchRow(styleColour(id), styleName(id)));
    } else if (legend.kinds) {
      for (const [name, n] of legend.kinds) box.appendChild(swatchRow(KIND_COLOURS[name], `${name} (${n} moves)`));
      box.appendChild(swatchRow(TRAVEL_KIND_COLOUR, `travel, laser off (${legend.travel} moves)`));
      travelText = null;
    } else if (legend.span) {
      const bar = el("div", undefined, "bar");
      const stops = Array.from({ length: 21 }, (_, k) => diverge(k / 10 - 1));
      bar.style.background = `linear-gradient(to right, ${stops.join(",")})`;
      box.appendChild(bar);
      box.appendChild(scaleRow([`−${legend.span} %`, "0", `+${legend.span} %`]));
      box.appendChild(el("div", "blue: lays too little · red: too much · dark grey: within about ±1 %", "note"));
      if (legend.predicted)
        box.appendChild(el("div", `these moves: ${signed(legend.lo, 2)} % .. ${signed(legend.hi, 2)} %; ` +
          `lmd::deposit allows ±${fmt(M.tolerance)} %`, "note"));
      if (legend.unpredicted)
        box.appendChild(swatchRow(UNPREDICTED,
          `no prediction (${legend.unpredicted} moves): no bead model predicts the rise here, e.g. a ring`));
    } else {
      const bar = el("div", undefined, "bar");
      bar.style.background = `linear-gradient(to right, ${RAMP.map((_, k) => ramp(k / (RAMP.length - 1))).join(",")})`;
      box.appendChild(bar);
      box.appendChild(scaleRow([legend.lo, legend.hi].map((v) => `${fmt(v)} ${legend.unit}`)));
    }
    if (travelText) box.appendChild(el("div", travelText, "note"));
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
  // The move the bodies stand at (an index into the page's moves) and how
  // far along the move to it (1: its end); the part is drawn as laid by then.
  const pose = { cur: Math.max(N - 1, 0), way: 1 };
  let showBodies = true, showRest = true;

  // The substrate: the deposits' footprint on z = 0 and a margin, out to
  // whole steps of its grid (a round length, about an eighth of it).
  const substrate = (function () {
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < N; i++) {
      if (!(FLAGS[i] & DEPOSIT)) continue;
      x0 = Math.min(x0, X[i]); x1 = Math.max(x1, X[i]);
      y0 = Math.min(y0, Y[i]); y1 = Math.max(y1, Y[i]);
    }
    if (!(x1 >= x0)) [[x0, x1], [y0, y1]] = [bounds[0], bounds[1]];
    const side = Math.max(x1 - x0, y1 - y0, 1);
    const margin = Math.max(0.1 * side, 2);
    const step = niceUp(side / 8);
    const out = (v, dir) => (dir < 0 ? Math.floor(v / step) : Math.ceil(v / step)) * step;
    return { x: [out(x0 - margin, -1), out(x1 + margin, 1)], y: [out(y0 - margin, -1), out(y1 + margin, 1)], step };
  })();
  // Axes from the part's origin: a round length about a fifth of the part.
  const AXIS = niceDown(0.2 * size);

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    for (const c of [canvas, $("plot"), $("errplot")].concat(ARM ? [$("joints")] : [], ROT ? [$("rotary")] : [], HEAT ? [$("thermal")] : [])) {
      c.width = Math.max(1, Math.round(c.clientWidth * dpr));
      c.height = Math.max(1, Math.round(c.clientHeight * dpr));
    }
  }

  // Orthographic: turn about z (yaw), then tilt toward the viewer (pitch).
  function camera() {
    const W = canvas.width, H = canvas.height;
    return {
      scale: (view.zoom * Math.min(W, H)) / size,
      cy: Math.cos(view.yaw), sy: Math.sin(view.yaw), cp: Math.cos(view.pitch), sp: Math.sin(view.pitch),
      ox: W / 2 + view.panX * W, oy: H / 2 + view.panY * H,
    };
  }
  function at(c, x, y, z) {
    const dx = x - centre[0], dy = y - centre[1], dz = z - centre[2];
    const x1 = c.cy * dx - c.sy * dy, y1 = c.sy * dx + c.cy * dy;
    return [c.ox + c.scale * x1, c.oy - c.scale * (c.cp * dz + c.sp * y1)];
  }
  function project(c) {
    // Locals: the loop runs over every move on the page each frame.
    const { scale, cy, sy, cp, sp, ox, oy } = c;
    const [x0, y0, z0] = centre;
    for (let i = 0; i < N; i++) {
      const dx = X[i] - x0, dy = Y[i] - y0, dz = Z[i] - z0;
      const x1 = cy * dx - sy * dy, y1 = sy * dx + cy * dy;
      PX[i] = ox + scale * x1;
      PY[i] = oy - scale * (cp * dz + sp * y1);
    }
  }

  // Strokes the moves of `list`, a path of at most CHUNK lines at a time:
  // one colour may hold every move (a plan at its height, one path kind),
  // and one path of 300 000 lines strokes slower than twenty of 16 000.
  const CHUNK = 16384;
  function strokeList(list, upto) {
    const [a, b] = range;
    let n = 0;
    ctx.beginPath();
    for (let k = 0; k < list.length; k++) {
      const i = list[k];
      if (i === 0 || i > upto || FLAGS[i] & GAP) continue;
      const l = LAYER[i];
      if (l < a || l > b) continue;
      ctx.moveTo(PX[i - 1], PY[i - 1]);
      ctx.lineTo(PX[i], PY[i]);
      if (++n === CHUNK) { ctx.stroke(); ctx.beginPath(); n = 0; }
    }
    ctx.stroke();
  }

  function drawSubstrate(c, dpr) {
    const { x: [x0, x1], y: [y0, y1], step } = substrate;
    ctx.beginPath();
    [[x0, y0], [x1, y0], [x1, y1], [x0, y1]].forEach(([x, y], k) => {
      const [u, v] = at(c, x, y, 0);
      k ? ctx.lineTo(u, v) : ctx.moveTo(u, v);
    });
    ctx.closePath();
    ctx.fillStyle = "rgba(95,110,135,0.10)";
    ctx.fill();
    ctx.lineWidth = dpr;
    ctx.strokeStyle = "rgba(95,110,135,0.45)";
    ctx.stroke();
    ctx.beginPath();
    const line = (a, b) => {
      const [u0, v0] = at(c, ...a), [u1, v1] = at(c, ...b);
      ctx.moveTo(u0, v0);
      ctx.lineTo(u1, v1);
    };
    for (let x = x0 + step; x < x1 - step / 2; x += step) line([x, y0, 0], [x, y1, 0]);
    for (let y = y0 + step; y < y1 - step / 2; y += step) line([x0, y, 0], [x1, y, 0]);
    ctx.strokeStyle = "rgba(95,110,135,0.18)";
    ctx.stroke();
  }

  function drawAxes(c, dpr) {
    const [u0, v0] = at(c, 0, 0, 0);
    ctx.font = `bold ${12 * dpr}px sans-serif`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    for (const [name, d, colour] of [["X", [1, 0, 0], "#c0392b"], ["Y", [0, 1, 0], "#27864a"], ["Z", [0, 0, 1], "#2b5fad"]]) {
      const [u1, v1] = at(c, d[0] * AXIS, d[1] * AXIS, d[2] * AXIS);
      const len = Math.hypot(u1 - u0, v1 - v0);
      ctx.strokeStyle = ctx.fillStyle = colour;
      ctx.lineWidth = 2 * dpr;
      ctx.beginPath();
      ctx.moveTo(u0, v0);
      ctx.lineTo(u1, v1);
      ctx.stroke();
      // An axis pointing at the viewer has no direction on screen to draw
      // a head along: its label sits on the origin.
      const ex = len > 1 ? (u1 - u0) / len : 0, ey = len > 1 ? (v1 - v0) / len : 0;
      if (len > 8 * dpr) {
        const h = 8 * dpr, w = 4 * dpr;
        ctx.beginPath();
        ctx.moveTo(u1 + ex * h * 0.5, v1 + ey * h * 0.5);
        ctx.lineTo(u1 - ex * h * 0.5 - ey * w, v1 - ey * h * 0.5 + ex * w);
        ctx.lineTo(u1 - ex * h * 0.5 + ey * w, v1 - ey * h * 0.5 - ex * w);
        ctx.closePath();
        ctx.fill();
      }
      ctx.fillText(name, u1 + ex * 14 * dpr, v1 + ey * 14 * dpr);
    }
  }

  // A bar of a round length whose pixels are that many millimetres at the
  // view's scale (orthographic: true for every length parallel to the
  // screen), redrawn with every frame so it follows the zoom.
  function drawScaleBar(c, dpr) {
    const perMm = c.scale / dpr; // CSS pixels a millimetre
    const mm = niceDown(120 / perMm);
    const px = mm * perMm * dpr;
    const x = 16 * dpr, y = canvas.height - 16 * dpr, tick = 5 * dpr;
    ctx.fillStyle = "rgba(255,255,255,0.85)";
    ctx.fillRect(x - 6 * dpr, y - 30 * dpr, px + 12 * dpr, 38 * dpr);
    ctx.strokeStyle = ctx.fillStyle = "#222";
    ctx.lineWidth = 2 * dpr;
    ctx.beginPath();
    ctx.moveTo(x, y - tick); ctx.lineTo(x, y); ctx.lineTo(x + px, y); ctx.lineTo(x + px, y - tick);
    ctx.stroke();
    ctx.font = `${12 * dpr}px sans-serif`;
    ctx.textAlign = "center";
    ctx.textBaseline = "alphabetic";
    ctx.fillText(`${mm} mm`, x + px / 2, y - 8 * dpr);
    canvas.dataset.scaleMm = mm;
    canvas.dataset.scalePx = (px / dpr).toFixed(1);
    canvas.dataset.pxPerMm = perMm.toFixed(4);
  }

  // One frame; `movesOnly` leaves out the substrate, axes and scale bar.
  function draw(movesOnly) {
    const dpr = window.devicePixelRatio || 1;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    const c = camera();
    if (!movesOnly) drawSubstrate(c, dpr);
    project(c);
    ctx.lineCap = "round";
    // The part laid up to the shown move; what comes after it faint.
    const upto = pose.cur;
    if (showRest && upto < N - 1) {
      ctx.lineWidth = 1.2 * dpr;
      ctx.strokeStyle = REST_GREY;
      strokeRest(upto);
    }
    if (showTravel) {
      ctx.lineWidth = dpr;
      ctx.strokeStyle = mode === "kind" ? TRAVEL_KIND_COLOUR : TRAVEL_GREY;
      strokeList(travel, upto);
    }
    ctx.lineWidth = 1.6 * dpr;
    for (const b of order) {
      ctx.strokeStyle = colours[b];
      strokeList(buckets[b], upto);
    }
    if (movesOnly) return;
    drawAxes(c, dpr);
    drawScaleBar(c, dpr);
    drawRepair(c, dpr);
    drawFixtures(c, dpr);
    drawMoving(c, dpr);
    drawFaceplate(c, dpr);
    if (showBodies) drawBodies(c, dpr);
    drawApproaches(c, dpr);
  }

  // The deposits after move `upto`, in the layers shown.
  function strokeRest(upto) {
    const [a, b] = range;
    let n = 0;
    ctx.beginPath();
    for (let i = upto + 1; i < N; i++) {
      if (!(FLAGS[i] & DEPOSIT) || FLAGS[i] & GAP || LAYER[i] < a || LAYER[i] > b) continue;
      ctx.moveTo(PX[i - 1], PY[i - 1]);
      ctx.lineTo(PX[i], PY[i]);
      if (++n === CHUNK) { ctx.stroke(); ctx.beginPath(); n = 0; }
    }
    ctx.stroke();
  }

  // --- a repair's scan and finish ------------------------------------------
  // The scanned surface as grey dots; the finished face's places (the
  // report's finish, docs/repair.md) at the top asked for, blue where the
  // bead model's face lies below it and red where above, full colour at the
  // larger of the two extremes; the legend names them. The canvas's
  // data-scan, data-finish and data-finish-range say what is drawn.
  const REPAIR = M.repair || null;
  function drawRepair(c, dpr) {
    if (!REPAIR) return;
    const s = 1.6 * dpr;
    ctx.fillStyle = "rgba(120,120,120,0.35)";
    for (const [x, y, z] of REPAIR.scan) {
      const [u, v] = at(c, x, y, z);
      ctx.fillRect(u - s / 2, v - s / 2, s, s);
    }
    const worst = Math.max(REPAIR.below, REPAIR.above, 1e-9);
    for (const [x, y, top, off] of REPAIR.finish) {
      const k = Math.min(1, Math.abs(off) / worst);
      const fade = Math.round(235 * (1 - k));
      ctx.fillStyle = off < 0 ? `rgb(${fade},${fade},255)` : `rgb(255,${fade},${fade})`;
      const [u, v] = at(c, x, y, top);
      ctx.fillRect(u - s, v - s, 2 * s, 2 * s);
    }
    if (REPAIR.finish.length) {
      ctx.fillStyle = "#333";
      ctx.font = `${11 * dpr}px sans-serif`;
      ctx.textAlign = "left";
      ctx.fillText(
        `finished face vs top: ${REPAIR.below.toFixed(3)} mm below (blue) .. ${REPAIR.above.toFixed(3)} mm above (red)`,
        16 * dpr, canvas.height - 36 * dpr);
    }
    canvas.dataset.scan = REPAIR.scan.length;
    canvas.dataset.finish = REPAIR.finish.length;
    canvas.dataset.finishRange = `${REPAIR.below},${REPAIR.above}`;
  }

  // --- the fixtures --------------------------------------------------------
  // In the part's coordinates, as the collision checks take them (docs/
  // collision.md): a box's twelve edges, an upright cylinder's rims and
  // four sides, a mesh's box dashed; the name over the top's centre, where
  // the canvas's data-fixture-tops says it is drawn (CSS px, for the tests).
  const FIXTURES = M.fixtures || [];
  const FIXTURE_EDGE = "rgba(170,90,20,0.95)";
  // One fixture's edges, each point brought into the part's coordinates by
  // `map`, and its name over its top's centre; returns where that is drawn.
  function strokeFixture(c, dpr, f, map) {
    const [x0, y0, z0] = f.lo, [x1, y1, z1] = f.hi;
    const seg = (a, b) => {
      const [u0, v0] = at(c, ...map(a)), [u1, v1] = at(c, ...map(b));
      ctx.moveTo(u0, v0);
      ctx.lineTo(u1, v1);
    };
    ctx.beginPath();
    if (f.kind === "cylinder") {
      const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2, r = (x1 - x0) / 2;
      const rim = (a) => [cx + r * Math.cos(a), cy + r * Math.sin(a)];
      for (const z of [z0, z1]) {
        for (let k = 0; k < 48; k++) {
          seg([...rim(2 * Math.PI * k / 48), z], [...rim(2 * Math.PI * (k + 1) / 48), z]);
        }
      }
      for (let k = 0; k < 4; k++) {
        const p = rim(Math.PI * k / 2);
        seg([...p, z0], [...p, z1]);
      }
    } else {
      const xs = [x0, x1], ys = [y0, y1], zs = [z0, z1];
      for (const y of ys) for (const z of zs) seg([x0, y, z], [x1, y, z]);
      for (const x of xs) for (const z of zs) seg([x, y0, z], [x, y1, z]);
      for (const x of xs) for (const y of ys) seg([x, y, z0], [x, y, z1]);
    }
    ctx.setLineDash(f.kind === "mesh" ? [5 * dpr, 4 * dpr] : []);
    ctx.lineWidth = 1.5 * dpr;
    ctx.strokeStyle = FIXTURE_EDGE;
    ctx.stroke();
    ctx.setLineDash([]);
    const [u, v] = at(c, ...map([(x0 + x1) / 2, (y0 + y1) / 2, z1]));
    ctx.fillStyle = FIXTURE_EDGE;
    ctx.font = `${11 * dpr}px sans-serif`;
    ctx.textAlign = "center";
    ctx.fillText(f.name, u, v - 6 * dpr);
    return [u, v];
  }
  function drawFixtures(c, dpr) {
    const tops = [];
    for (const f of FIXTURES) {
      const [u, v] = strokeFixture(c, dpr, f, (p) => p);
      tops.push(`${(u / dpr).toFixed(1)},${(v / dpr).toFixed(1)}`);
    }
    canvas.dataset.fixtures = FIXTURES.length;
    canvas.dataset.fixtureTops = tops.join(";");
  }

  // Fixtures fixed to a machine whose table or positioner turns the part
  // (docs/collision.md): each as declared, in the machine's coordinates or
  // its tilt axis's body's, brought into the part's by the frame at the
  // last posed move at or before the slider's — part = then⁻¹ · C⁻¹ · T⁻¹
  // · x, the tilt's turn left out on the tilt axis's body. The canvas's
  // data-moving says the axes used and the first one's least corner in the
  // part's coordinates (for the tests).
  const MOVING = M.moving;
  // `p` turned about turn `t` by its axis at `deg` (Rodrigues' formula).
  function turnBy(t, deg, p) {
    const a = t.sign * deg * Math.PI / 180, c = Math.cos(a), s = Math.sin(a);
    const k = t.dir, v = [p[0] - t.point[0], p[1] - t.point[1], p[2] - t.point[2]];
    const kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const x = [k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]];
    return [0, 1, 2].map((i) => v[i] * c + x[i] * s + k[i] * kv * (1 - c) + t.point[i]);
  }
  function movingMove(i) {
    const m = MOVING.moves;
    let lo = 0, hi = m.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (m[mid] <= i) lo = mid + 1; else hi = mid; }
    return lo - 1;
  }
  function drawMoving(c, dpr) {
    if (!MOVING || !N) return;
    const k = Math.max(movingMove(pose.cur), 0);
    if (!MOVING.axes.length) return;
    const [tilt, rot] = MOVING.axes[k], R = MOVING.then;
    const unthen = (p) => {
      const d = [p[0] - R[0][3], p[1] - R[1][3], p[2] - R[2][3]];
      return [0, 1, 2].map((j) => R[0][j] * d[0] + R[1][j] * d[1] + R[2][j] * d[2]);
    };
    const said = [];
    MOVING.fixtures.forEach((f, n) => {
      const toPart = (p) => {
        const q = MOVING.tilts[n] ? p : turnBy(MOVING.turns[0], -tilt, p);
        return unthen(turnBy(MOVING.turns[1], -rot, q));
      };
      strokeFixture(c, dpr, f, toPart);
      if (!n) said.push(...toPart(f.lo).map((v) => v.toFixed(4)));
    });
    canvas.dataset.moving = `${tilt},${rot}|${said.join(",")}`;
  }

  // A positioner's faceplate: its face's rim and the rim `thickness` behind
  // it, joined at four points, in the part's coordinates (it turns with the
  // part), faint blue-grey; the plate's grid lies on its face when the base
  // puts the part there.
  const FACEPLATE = M.faceplate;
  function drawFaceplate(c, dpr) {
    if (!FACEPLATE) return;
    const { diameter, thickness, centre, normal, u, v } = FACEPLATE;
    const r = diameter / 2;
    const p = (a, depth) => [0, 1, 2].map((k) =>
      centre[k] + r * (Math.cos(a) * u[k] + Math.sin(a) * v[k]) - depth * normal[k]);
    ctx.beginPath();
    for (const depth of [0, thickness]) {
      for (let k = 0; k <= 96; k++) {
        const [x, y] = at(c, ...p(2 * Math.PI * k / 96, depth));
        k ? ctx.lineTo(x, y) : ctx.moveTo(x, y);
      }
    }
    for (let k = 0; k < 4; k++) {
      const [x0, y0] = at(c, ...p(Math.PI * k / 2, 0)), [x1, y1] = at(c, ...p(Math.PI * k / 2, thickness));
      ctx.moveTo(x0, y0);
      ctx.lineTo(x1, y1);
    }
    ctx.lineWidth = 1.2 * dpr;
    ctx.strokeStyle = "rgba(70,90,130,0.55)";
    ctx.stroke();
    canvas.dataset.faceplate = diameter;
  }

  // --- the bodies at a move -------------------------------------------------
  // The head's solids about the beam at the shown move's focus (docs/
  // collision.md): each a frustum from `s0` to `s1` up the beam, its radii
  // `r0` and `r1`, the nozzle's tip `standoff` above the focus. Orthographic,
  // so a solid's outline is the convex hull of its two rims' projections.
  const HEAD = M.head || { standoff: 0, bodies: [], gap: 0 };
  const SOLIDS = (function () {
    let s = HEAD.standoff;
    return HEAD.bodies.map((b) => {
      const f = { name: b.name, s: [s, s + b.length], r: [b.diameters[0] / 2, b.diameters[1] / 2] };
      s += b.length;
      return f;
    });
  })();
  const ARM_LINKS = M.arm && M.arm.links;
  const LINK_POINTS = ARM_LINKS ? (function () {
    const b = bytes(ARM_LINKS.points), out = new Float64Array(b.length / 2);
    for (let i = 0; i < out.length; i++) {
      const [lo, hi] = ARM_LINKS.ranges[i % 3];
      out[i] = lo + (b[2 * i] | (b[2 * i + 1] << 8)) * ((hi - lo) / 65535);
    }
    return out;
  })() : null;
  const BODY_FILL = "rgba(70,78,92,0.16)", BODY_EDGE = "rgba(55,60,72,0.85)", RIM = "rgba(55,60,72,0.45)";
  const REST_GREY = "rgba(160,160,160,0.22)";

  // The shown pose: its focus and the unit vector up its beam, `way` along
  // the move to it (1: at its end; an approach may lie within a move).
  function posed() {
    const i = pose.cur, t = i > 0 ? pose.way : 1;
    const a = i > 0 ? i - 1 : i;
    const lerp = (A) => A[a] + t * (A[i] - A[a]);
    const f = [lerp(X), lerp(Y), lerp(Z)];
    let u = [0, 1, 2].map((k) => BEAM[3 * a + k] + t * (BEAM[3 * i + k] - BEAM[3 * a + k]));
    const len = Math.hypot(...u) || 1;
    u = u.map((v) => v / len);
    return { focus: f, up: u };
  }
  // Two unit vectors square to `u` and to each other.
  function across(u) {
    const h = Math.abs(u[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    const cross = (p, q) => [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
    let e1 = cross(u, h);
    const l = Math.hypot(...e1);
    e1 = e1.map((v) => v / l);
    return [e1, cross(u, e1)];
  }
  // The convex hull of screen points (monotone chain), counter-clockwise.
  function hull(pts) {
    pts = pts.slice().sort((p, q) => p[0] - q[0] || p[1] - q[1]);
    const turn = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const half = (list) => {
      const h = [];
      for (const p of list) {
        while (h.length >= 2 && turn(h[h.length - 2], h[h.length - 1], p) <= 0) h.pop();
        h.push(p);
      }
      h.pop();
      return h;
    };
    return half(pts).concat(half(pts.slice().reverse()));
  }
  const RIM_STEPS = 36;
  function drawHead(c, dpr) {
    const { focus: f, up: u } = posed();
    const [e1, e2] = across(u);
    const point = (s, r, a) => at(c, ...[0, 1, 2].map((k) =>
      f[k] + s * u[k] + r * (Math.cos(a) * e1[k] + Math.sin(a) * e2[k])));
    // The beam from the focus up to the nozzle's tip, dashed.
    const [fu, fv] = at(c, ...f), [tu, tv] = point(HEAD.standoff, 0, 0);
    ctx.setLineDash([3 * dpr, 3 * dpr]);
    ctx.strokeStyle = BODY_EDGE; ctx.lineWidth = dpr;
    ctx.beginPath(); ctx.moveTo(fu, fv); ctx.lineTo(tu, tv); ctx.stroke();
    ctx.setLineDash([]);
    for (const b of SOLIDS) {
      const rims = [0, 1].map((e) => Array.from({ length: RIM_STEPS }, (_, k) =>
        point(b.s[e], b.r[e], (2 * Math.PI * k) / RIM_STEPS)));
      const h = hull(rims[0].concat(rims[1]));
      ctx.beginPath();
      h.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      ctx.closePath();
      ctx.fillStyle = BODY_FILL; ctx.fill();
      ctx.strokeStyle = BODY_EDGE; ctx.lineWidth = 1.2 * dpr; ctx.stroke();
      ctx.strokeStyle = RIM; ctx.lineWidth = dpr;
      for (const rim of rims) {
        ctx.beginPath();
        rim.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
        ctx.closePath(); ctx.stroke();
      }
    }
    const tip = [0, 1, 2].map((k) => f[k] + HEAD.standoff * u[k]);
    return { focus: f, up: u, tip };
  }
  // The posed move of the arm at or before move `i` (-1: none).
  function armMove(i) {
    if (!ARM_LINKS) return -1;
    const m = ARM_LINKS.moves;
    let lo = 0, hi = m.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (m[mid] <= i) lo = mid + 1; else hi = mid; }
    return lo - 1;
  }
  // A robot's links as capsules (a segment and a radius: orthographically a
  // stroke as wide as the capsule with round caps), on the frames the
  // collision check hangs them on: the upper arm A2–A3, the forearm A3 past
  // its offset to the wrist centre, the wrist to the flange; the column
  // from A1's height to A2 a line.
  const CAPSULES = [[1, 2, 0], [2, 3, 1], [3, 4, 1], [4, 5, 2]];
  function drawArm(c, dpr, k) {
    const p = (j) => at(c, ...[0, 1, 2].map((a) => LINK_POINTS[18 * k + 3 * j + a]));
    const radii = ARM_LINKS.radii;
    ctx.lineCap = "round";
    for (const [a, b, link] of CAPSULES) {
      const [u0, v0] = p(a), [u1, v1] = p(b);
      ctx.beginPath(); ctx.moveTo(u0, v0); ctx.lineTo(u1, v1);
      if (radii) {
        ctx.lineWidth = Math.max(2 * radii[link] * c.scale, dpr);
        ctx.strokeStyle = "rgba(85,95,115,0.2)"; ctx.stroke();
      }
      ctx.lineWidth = 1.5 * dpr; ctx.strokeStyle = BODY_EDGE; ctx.stroke();
    }
    const [u0, v0] = p(0), [u1, v1] = p(1);
    ctx.setLineDash([4 * dpr, 4 * dpr]);
    ctx.beginPath(); ctx.moveTo(u0, v0); ctx.lineTo(u1, v1); ctx.stroke();
    ctx.setLineDash([]);
  }
  function drawBodies(c, dpr) {
    if (!N) return;
    const k = armMove(pose.cur);
    if (k >= 0) drawArm(c, dpr, k);
    const h = drawHead(c, dpr);
    const s = $("pose");
    s.dataset.tip = h.tip.map((v) => v.toFixed(4)).join(",");
    s.dataset.armMove = k >= 0 ? ARM_LINKS.moves[k] : -1;
  }

  // The closest approach of each body to each thing of the cell, marked at
  // the focus where it happens: the tightest (least room over its gap) a
  // ring, red where it is within its gap, orange else; the others a dot.
  const APPROACHES = M.approaches || [];
  const tightest = APPROACHES.reduce((best, a, i) =>
    best < 0 || a.distance_mm - a.gap_mm < APPROACHES[best].distance_mm - APPROACHES[best].gap_mm ? i : best, -1);
  function drawApproaches(c, dpr) {
    APPROACHES.forEach((a, i) => {
      const [u, v] = at(c, a.focus[0], a.focus[1], a.focus[2]);
      const top = i === tightest;
      ctx.beginPath();
      ctx.arc(u, v, (top ? 7 : 3) * dpr, 0, 2 * Math.PI);
      ctx.lineWidth = 2 * dpr;
      ctx.strokeStyle = !top ? "#666" : a.distance_mm < a.gap_mm ? "#c0392b" : "#e08a00";
      ctx.stroke();
      if (top) {
        ctx.fillStyle = ctx.strokeStyle;
        ctx.font = `${12 * dpr}px system-ui, sans-serif`;
        ctx.fillText(`${a.body} – ${a.with}: ${fmt(a.distance_mm)} mm`, u + 10 * dpr, v - 8 * dpr);
      }
    });
  }

  let queued = false;
  function redraw() {
    if (queued) return;
    queued = true;
    requestAnimationFrame(() => { queued = false; draw(); });
  }

  // --- plots --------------------------------------------------------------
  // A framed panel of lines over x in [x0, x1]: `series` are [ys, colour,
  // width] with NaN for a gap; `marks` [y, colour, dashed] horizontal lines;
  // `band` [lows, highs, colour] filled between.
  function panel(g, box, xs, x0, x1, spec) {
    const dpr = window.devicePixelRatio || 1;
    const { left, right, top, height } = box;
    let [lo, hi] = spec.range || [Infinity, -Infinity];
    if (!spec.range) {
      for (const [ys] of spec.series) for (const y of ys) if (y === y) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
      if (!(hi > lo)) { lo = (lo === lo && lo !== Infinity ? lo : 0) - 0.5; hi = lo + 1; }
    }
    const X_ = (x) => left + ((right - left) * (x - x0)) / (x1 - x0 || 1);
    const Y_ = (y) => top + height - (height * (Math.min(Math.max(y, lo), hi) - lo)) / (hi - lo);
    g.strokeStyle = "#bbb"; g.lineWidth = dpr;
    g.strokeRect(left, top, right - left, height);
    if (spec.shade) {
      g.fillStyle = "rgba(255,200,80,0.18)";
      g.fillRect(X_(spec.shade[0]), top, Math.max(X_(spec.shade[1]) - X_(spec.shade[0]), dpr), height);
    }
    g.fillStyle = "#333"; g.font = `${11 * dpr}px sans-serif`;
    g.textAlign = "left"; g.textBaseline = "alphabetic";
    g.fillText(spec.fmt(hi), 6 * dpr, top + 10 * dpr);
    g.fillText(spec.fmt(lo), 6 * dpr, top + height);
    g.fillText(spec.label, left + 6 * dpr, top + 13 * dpr);
    for (const [y, colour, dashed] of spec.marks || []) {
      if (y < lo || y > hi) continue;
      g.strokeStyle = colour; g.lineWidth = dpr;
      g.setLineDash(dashed ? [4 * dpr, 4 * dpr] : []);
      g.beginPath(); g.moveTo(left, Y_(y)); g.lineTo(right, Y_(y)); g.stroke();
    }
    g.setLineDash([]);
    if (spec.band) {
      const [ls, hs, colour] = spec.band;
      g.fillStyle = colour;
      let open = false;
      const close = (j) => {
        for (let k = j; k >= 0 && hs[k] === hs[k]; k--) g.lineTo(X_(xs[k]), Y_(hs[k]));
        g.closePath(); g.fill(); open = false;
      };
      for (let j = 0; j < xs.length; j++) {
        if (ls[j] !== ls[j]) { if (open) close(j - 1); continue; }
        if (!open) { g.beginPath(); g.moveTo(X_(xs[j]), Y_(ls[j])); open = true; } else g.lineTo(X_(xs[j]), Y_(ls[j]));
      }
      if (open) close(xs.length - 1);
    }
    for (const [ys, colour, width] of spec.series) {
      g.strokeStyle = colour; g.lineWidth = (width || 1.5) * dpr;
      g.beginPath();
      let pen = false;
      for (let j = 0; j < ys.length; j++) {
        if (ys[j] !== ys[j]) { pen = false; continue; }
        pen ? g.lineTo(X_(xs[j]), Y_(ys[j])) : g.moveTo(X_(xs[j]), Y_(ys[j]));
        pen = true;
      }
      g.stroke();
    }
    return [lo, hi];
  }
  function clear(c) {
    const g = c.getContext("2d");
    g.fillStyle = "#fff";
    g.fillRect(0, 0, c.width, c.height);
    return g;
  }
  // A symmetric range about 0 for per cents: at least ±5, a round number.
  const symmetric = (ys) => {
    let m = 0;
    for (const y of ys) if (y === y) m = Math.max(m, Math.abs(y));
    const s = Math.max(ERROR_SPAN, niceUp(m || 1));
    return [-s, s];
  };
  const pct = (x) => `${signed(x, Math.abs(x) >= 10 ? 0 : 1)} %`;

  // Speed, layer height and height error along the top layer's deposit path.
  function plot() {
    const c = $("plot"), g = clear(c);
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    const k = range[1];
    if (!STARTS.length) return;
    const first = STARTS[k][1], end = k + 1 < STARTS.length ? STARTS[k + 1][1] : N;
    const s = [], v = [], h = [], e = [];
    let along = 0;
    for (let i = Math.max(first, 1); i < end; i++) {
      if (!(FLAGS[i] & DEPOSIT) || FLAGS[i] & GAP) continue;
      along += Math.hypot(X[i] - X[i - 1], Y[i] - Y[i - 1], Z[i] - Z[i - 1]);
      s.push(along); v.push(VALUES.speed[i]); h.push(VALUES.height[i]);
      e.push(FLAGS[i] & PREDICTED ? VALUES.error[i] : NaN);
    }
    $("plot-title").textContent =
      `layer ${STARTS[k][0]}: speed, layer height and height error along the deposit path (${fmt(along)} mm)`;
    const gap = 8 * dpr, ph = (H - 4 * gap) / 3;
    const box = (n) => ({ left: 70 * dpr, right: W - 16 * dpr, top: gap + n * (ph + gap), height: ph });
    panel(g, box(0), s, 0, along, { series: [[v, "#1f77b4"]], label: "speed, mm/s", fmt });
    panel(g, box(1), s, 0, along, { series: [[h, "#555"]], label: "layer height, mm", fmt });
    const known = e.some((y) => y === y);
    panel(g, box(2), s, 0, along, {
      series: [[e, "#b03a2e"]], range: symmetric(e), fmt: pct,
      marks: [[0, "#888"], [M.tolerance, "#e08a00", true], [-M.tolerance, "#e08a00", true]],
      label: known ? `height error, % (dashed: lmd::deposit's ±${fmt(M.tolerance)} %)` : "height error: no prediction on this layer",
    });
  }

  // The height error layer by layer, from every move of the plan (the page
  // may leave layers out; these numbers do not): each layer's mean over its
  // deposited length with its lowest and highest move, and the layers' mean
  // rise − height added up (how far the top drifts from the plan).
  const LE = M.layer_error;
  function plotLayers() {
    const c = $("errplot"), g = clear(c);
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    const xs = LE.map((_, k) => k + 1);
    const pick = (j) => LE.map((r) => (r ? r[j] : NaN));
    const mean = pick(0), lo = pick(1), hi = pick(2), drift = pick(3);
    const known = LE.some((r) => r);
    $("errplot-title").textContent = known
      ? `height error by layer: mean (black), highest (red) and lowest (blue) move of each`
      : "height error by layer: no rise predicted on this plan (no bead model predicts it, e.g. a ring)";
    if (!known) return;
    // The layers the view shows, when that is not all of them.
    const all = range[0] === 0 && range[1] === STARTS.length - 1;
    const shade = STARTS.length && !all ? [STARTS[range[0]][0] - 0.5, STARTS[range[1]][0] + 0.5] : null;
    const gap = 8 * dpr, ph = (H - 3 * gap) / 2;
    const box = (n) => ({ left: 70 * dpr, right: W - 16 * dpr, top: gap + n * (ph + gap), height: ph });
    const x0 = 0.5, x1 = LE.length + 0.5;
    panel(g, box(0), xs, x0, x1, {
      series: [[hi, "#c0392b", 1], [lo, "#2166ac", 1], [mean, "#111", 1.5]], band: [lo, hi, "rgba(120,120,120,0.22)"],
      range: symmetric(lo.concat(hi)), fmt: pct, shade,
      marks: [[0, "#888"], [M.tolerance, "#e08a00", true], [-M.tolerance, "#e08a00", true]],
      label: `per layer, % (dashed: lmd::deposit's ±${fmt(M.tolerance)} %)`,
    });
    let m = 0, last = 0;
    for (const y of drift) if (y === y) { m = Math.max(m, Math.abs(y)); last = y; }
    const span = Math.max(2 * M.max_drift, niceUp(m || 0.01));
    panel(g, box(1), xs, x0, x1, {
      series: [[drift, "#111"]], range: [-span, span], fmt: (x) => `${signed(x, 2)} mm`, shade,
      marks: [[0, "#888"], [M.max_drift, "#e08a00", true], [-M.max_drift, "#e08a00", true]],
      label: `mean rise − height added up over the layers: the top ends ${signed(last, 2)} mm off ` +
        `(dashed: max_drift ±${fmt(M.max_drift)} mm)`,
    });
    g.fillStyle = "#333"; g.font = `${11 * dpr}px sans-serif`;
    g.textBaseline = "alphabetic";
    g.textAlign = "left"; g.fillText("layer 1", 70 * dpr, H - 1 * dpr);
    g.textAlign = "right"; g.fillText(`layer ${LE.length}`, W - 16 * dpr, H - 1 * dpr);
  }

  // A robot arm's six axes layer by layer, solved as the verifier solves
  // them (every move, whatever the view keeps): each layer's lowest to
  // highest angle as a band, against the axis's limits (red) and the margin
  // lmd::joint-limit keeps inside them (dashed). A layer whose band comes
  // within NEAR degrees of the margin is ticked red below its panel; on A5
  // and A3 the zone lmd::singular-lin keeps LINs out of is shaded.
  const ARM = M.arm;
  const NEAR = 10;
  function plotJoints() {
    if (!ARM) return;
    const c = $("joints"), g = clear(c);
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    const L = ARM.layers, xs = L.map((_, k) => k + 1);
    const x0 = 0.5, x1 = L.length + 0.5;
    const gap = 8 * dpr, ph = (H - 7 * gap) / 6;
    const all = range[0] === 0 && range[1] === STARTS.length - 1;
    const shade = STARTS.length && !all ? [STARTS[range[0]][0] - 0.5, STARTS[range[1]][0] + 0.5] : null;
    let near = 0, past = 0;
    for (let a = 0; a < 6; a++) {
      const lo = L.map((r) => (r ? r[a][0] : NaN)), hi = L.map((r) => (r ? r[a][1] : NaN));
      const [l0, l1] = ARM.limits[a], m0 = l0 + ARM.margin, m1 = l1 - ARM.margin;
      const box = { left: 70 * dpr, right: W - 16 * dpr, top: gap + a * (ph + gap), height: ph - 4 * dpr };
      const pad = 0.05 * (l1 - l0);
      const marks = [[l0, "#c0392b"], [l1, "#c0392b"]];
      if (ARM.margin > 0) marks.push([m0, "#c0392b", true], [m1, "#c0392b", true]);
      const zone = a === 4 ? 0 : a === 2 ? ARM.stretch : null;
      if (zone !== null) marks.push([zone - ARM.singularity, "#888", true], [zone + ARM.singularity, "#888", true]);
      panel(g, box, xs, x0, x1, {
        series: [[lo, "#1f4e79", 1], [hi, "#1f4e79", 1]], band: [lo, hi, "rgba(31,78,121,0.28)"],
        range: [l0 - pad, l1 + pad], fmt: (x) => `${signed(x, 0)}°`, shade, marks,
        label: `A${a + 1}, deg (limits ${fmt(l0)}° to ${fmt(l1)}°${ARM.margin > 0 ? `, margin ${fmt(ARM.margin)}°` : ""})`,
      });
      // Layers near a limit: a red tick under the panel.
      const X_ = (x) => box.left + ((box.right - box.left) * (x - x0)) / (x1 - x0);
      g.fillStyle = "#c0392b";
      // Past the margin (a refused plan: lmd::joint-limit fails there): a
      // tick three times as tall.
      for (let k = 0; k < L.length; k++) {
        if (!L[k] || !(L[k][a][0] < m0 + NEAR || L[k][a][1] > m1 - NEAR)) continue;
        const over = L[k][a][0] < m0 || L[k][a][1] > m1;
        if (over) past++; else near++;
        g.fillRect(X_(k + 1) - dpr, box.top + box.height + dpr, 2 * dpr, (over ? 9 : 3) * dpr);
      }
    }
    $("joints-title").textContent = `${ARM.name}: axes A1–A6 layer by layer, lowest to highest angle of each ` +
      `layer's moves (blue), limits (red; dashed: lmd::joint-limit's margin)`;
    $("joints-note").textContent = (past
      ? `${past} layer-axis pairs go past the margin (tall red ticks: lmd::joint-limit fails there). ` : "") +
      (near
      ? `${near} layer-axis pairs come within ${NEAR}° of the margin (red ticks). `
      : past ? "" : `Every axis stays more than ${NEAR}° inside its margin. `) +
      `Grey dashed on A3 and A5: lmd::singular-lin's ±${fmt(ARM.singularity)}° about the stretched elbow and A5 = 0. ` +
      (ARM.unreachable ? `${ARM.unreachable} moves out of reach.` : "");
    c.dataset.joints = 6;
    c.dataset.nearLimit = near;
    c.dataset.pastLimit = past;
  }

  // A 5-axis CNC's tilt axis and C layer by layer: each layer's lowest to
  // highest angle as a band against the axis's travel (red). On a tilting
  // table these are the angles the table turns the part to.
  const ROT = M.rotary;
  function plotRotary() {
    if (!ROT) return;
    const c = $("rotary"), g = clear(c);
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    const L = ROT.layers, xs = L.map((_, k) => k + 1);
    const x0 = 0.5, x1 = L.length + 0.5;
    const gap = 8 * dpr, ph = (H - 3 * gap) / 2;
    for (let a = 0; a < 2; a++) {
      const lo = L.map((r) => (r ? r[a][0] : NaN)), hi = L.map((r) => (r ? r[a][1] : NaN));
      const [l0, l1] = ROT.limits[a];
      let [v0, v1] = [Infinity, -Infinity];
      for (let k = 0; k < L.length; k++) if (L[k]) { v0 = Math.min(v0, lo[k]); v1 = Math.max(v1, hi[k]); }
      // The travel can be many turns of C: scale to the angles used, the
      // limits drawn where they fall within.
      const span = v1 > v0 ? v1 - v0 : 1, r0 = Math.max(l0, v0 - 0.1 * span), r1 = Math.min(l1, v1 + 0.1 * span);
      const box = { left: 70 * dpr, right: W - 16 * dpr, top: gap + a * (ph + gap), height: ph - 4 * dpr };
      panel(g, box, xs, x0, x1, {
        series: [[lo, "#1f4e79", 1], [hi, "#1f4e79", 1]], band: [lo, hi, "rgba(31,78,121,0.28)"],
        range: [Math.min(r0, v0), Math.max(r1, v1)].map((v, i) => (v === v && Math.abs(v) !== Infinity ? v : i ? 1 : -1)),
        fmt: (x) => `${signed(x, 0)}°`, marks: [[l0, "#c0392b"], [l1, "#c0392b"]],
        label: `${ROT.axes[a]}, deg (travel ${fmt(l0)}° to ${fmt(l1)}°)`,
      });
    }
    const table = ROT.kinematics.startsWith("table"), dkp = ROT.kinematics === "positioner";
    $("rotary-title").textContent = `${ROT.kinematics}: ${ROT.axes[0]} and ${ROT.axes[1]} layer by layer, lowest to ` +
      `highest angle of each layer's moves (blue), travel (red)`;
    $("rotary-note").textContent = dkp
      ? "The positioner turns the part (E1 tilts, E2 rotates) to the angles lmdc chose for each layer; they change only between layers."
      : table
      ? "The table turns the part so each layer's normal points up the vertical nozzle; C unwinds only between layers."
      : "The head tilts the nozzle along each layer's normal.";
    c.dataset.layers = L.length;
  }

  // The thermal model's prediction layer by layer (docs/thermal.md): each
  // layer's interpass temperature against the limit (red), and its own
  // temperature when laid; below, the wait before each layer.
  const HEAT = M.thermal;
  function plotHeat() {
    if (!HEAT) return;
    const c = $("thermal"), g = clear(c);
    const W = c.width, H = c.height, dpr = window.devicePixelRatio || 1;
    const n = HEAT.interpass.length, xs = HEAT.interpass.map((_, k) => k + 1);
    const gap = 8 * dpr, ph = (H - 3 * gap) / 2;
    const box = (a) => ({ left: 70 * dpr, right: W - 16 * dpr, top: gap + a * (ph + gap), height: ph - 4 * dpr });
    const marks = HEAT.limit == null ? [] : [[HEAT.limit, "#c0392b"]];
    panel(g, box(0), xs, 0.5, n + 0.5, {
      series: [[HEAT.peak, "#e67e22", 1], [HEAT.interpass, "#1f4e79", 2]], marks,
      fmt: (x) => `${fmt(x)} °C`, label: "°C: interpass (blue), the layer as laid (orange)",
    });
    panel(g, box(1), xs, 0.5, n + 0.5, {
      series: [[HEAT.wait, "#555", 1]], fmt: (x) => `${fmt(x)} s`, label: "wait before the layer, s",
    });
    $("thermal-title").textContent = `${HEAT.material}: each layer's predicted temperatures` +
      (HEAT.limit == null ? "" : `, the interpass limit ${fmt(HEAT.limit)} °C (red)`);
    $("thermal-note").textContent = "The interpass temperature is the part's where and when the nozzle starts the layer; " +
      "the layer as laid is its mean, not the melt pool's.";
    c.dataset.layers = n;
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
    showRange(); plotLayers(); plotJoints(); plotRotary(); redraw();
  });
  to.addEventListener("input", () => {
    range[1] = +to.value;
    if (range[1] < range[0]) { range[0] = range[1]; from.value = to.value; }
    showRange(); plot(); plotLayers(); plotJoints(); plotRotary(); redraw();
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
  window.addEventListener("resize", () => { resize(); plot(); plotLayers(); plotJoints(); plotRotary(); redraw(); });

  // --- the move slider: the bodies at any move ------------------------------
  const moveInput = $("move");
  moveInput.max = String(Math.max(N - 1, 0));
  moveInput.value = String(pose.cur);
  const KIND_WORDS = M.kinds;
  // Where move `i` is, in the messages' words (layers, paths, points from 1).
  function where(i) {
    if (P_KIND[i] === 2) return "the retract after the last path";
    if (P_KIND[i] === 1) return `the clearance move before layer ${P_LAYER[i] + 1}, path ${P_PATH[i] + 1}`;
    return `layer ${P_LAYER[i] + 1}, path ${P_PATH[i] + 1}, point ${P_POINT[i] + 1}`;
  }
  function showPose() {
    const i = pose.cur, s = $("pose");
    if (!N) return;
    const laser = FLAGS[i] & DEPOSIT ? `laser on (${KIND_WORDS[KIND[i]]})` : "laser off";
    const thinned = P_INDEX[N - 1] + 1 > N;
    const along = pose.way < 1 ? `${Math.round(pose.way * 100)} % of the way along ` : "";
    s.textContent = `move ${i + 1} of ${N}` + (thinned ? ` (the plan's move ${P_INDEX[i] + 1} of ${M.moves})` : "") +
      `: ${along}the move to ${where(i)}, ${laser}; laid so far: ${LAID[i]} of ${DEPOSITS} deposit moves` +
      (thinned ? ` (the plan's ${P_LAID[i]} of ${PLAN_DEPOSITS})` : "");
    const k = armMove(i);
    if (ARM_LINKS && k >= 0 && ARM_LINKS.moves[k] !== i)
      s.textContent += `; the arm as at move ${ARM_LINKS.moves[k] + 1} (the page carries it at ` +
        `${ARM_LINKS.moves.length} of its ${N} moves)`;
    const d = s.dataset;
    d.move = i; d.planMove = P_INDEX[i]; d.way = pose.way;
    d.kind = ["point", "clearance", "end"][P_KIND[i]];
    d.layer = P_LAYER[i] + 1; d.path = P_PATH[i] + 1; d.point = P_KIND[i] === 0 ? P_POINT[i] + 1 : "";
    d.focus = [X[i], Y[i], Z[i]].map((v) => v.toFixed(4)).join(",");
    d.beam = [0, 1, 2].map((k) => BEAM[3 * i + k].toFixed(5)).join(",");
    d.laid = LAID[i]; d.laidPlan = P_LAID[i];
    moveInput.value = String(i);
  }
  function goTo(i, way) {
    pose.cur = Math.min(Math.max(Math.round(i), 0), Math.max(N - 1, 0));
    pose.way = way === undefined ? 1 : way;
    showPose(); redraw();
  }
  // The first move of the layer before (or of this one, from inside it), or
  // of the layer after.
  function layerStep(dir) {
    if (!STARTS.length) return pose.cur;
    const k = LAYER[pose.cur];
    if (dir < 0) return pose.cur > STARTS[k][1] ? STARTS[k][1] : STARTS[Math.max(k - 1, 0)][1];
    return k + 1 < STARTS.length ? STARTS[k + 1][1] : N - 1;
  }
  moveInput.addEventListener("input", () => goTo(+moveInput.value));
  $("prev").addEventListener("click", () => goTo(pose.cur - 1));
  $("next").addEventListener("click", () => goTo(pose.cur + 1));
  $("prevlayer").addEventListener("click", () => goTo(layerStep(-1)));
  $("nextlayer").addEventListener("click", () => goTo(layerStep(1)));
  $("first").addEventListener("click", () => goTo(0));
  $("last").addEventListener("click", () => goTo(N - 1));
  $("bodies").addEventListener("change", (e) => { showBodies = e.target.checked; redraw(); });
  $("rest").addEventListener("change", (e) => { showRest = e.target.checked; redraw(); });
  // Arrows step a move (with shift, a layer), Home and End go to the ends,
  // `c` to the closest approach; not while a control that takes keys has
  // the focus.
  document.addEventListener("keydown", (e) => {
    if (/^(INPUT|SELECT|TEXTAREA)$/.test(e.target.tagName || "")) return;
    const go = {
      ArrowLeft: () => goTo(e.shiftKey ? layerStep(-1) : pose.cur - 1),
      ArrowRight: () => goTo(e.shiftKey ? layerStep(1) : pose.cur + 1),
      Home: () => goTo(0), End: () => goTo(N - 1), c: () => $("jump").click(),
    }[e.key];
    if (go) { e.preventDefault(); go(); }
  });

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

  // The address may ask for a view: #colour=error&view=top&zoom=2 (a link to
  // what one saw; the tests render each colouring this way).
  const ask = new URLSearchParams(location.hash.slice(1));
  const select = $("quantity");
  if (M.thermal) select.add(new Option("interpass temperature", "interpass"));
  if ([...select.options].some((o) => o.value === ask.get("colour"))) select.value = ask.get("colour");
  if (ask.get("view") === "top") Object.assign(view, { yaw: 0, pitch: Math.PI / 2 });
  if (+ask.get("zoom") > 0) view.zoom *= +ask.get("zoom");

  // A plan refused for its arm: the errors head the page, each with its
  // place and its fix; everything below is the plan the other rules passed.
  if (M.refused) {
    const box = $("refused");
    box.appendChild(el("strong", `Refused: this plan does not build. ${M.refused.length} error` +
      `${M.refused.length === 1 ? "" : "s"} of the arm's rules (the other rules passed; the plan is drawn ` +
      `as they checked it, and lmdc build writes no program for it):`));
    const list = document.createElement("ul");
    for (const f of M.refused) {
      const item = el("li", `${f.code}: ${f.message}`);
      if (f.help) item.appendChild(el("div", `help: ${f.help}`, "help"));
      list.appendChild(item);
    }
    box.appendChild(list);
    box.hidden = false;
    box.dataset.errors = M.refused.length;
  }
  if (tightest >= 0) {
    const a = APPROACHES[tightest], p = $("approach");
    const hit = a.distance_mm < a.gap_mm;
    p.textContent = `${hit ? "Collision" : "Closest approach"}: ${a.body} – ${a.with}, ` +
      `${fmt(a.distance_mm)} mm (it keeps ${fmt(a.gap_mm)} mm) at ${a.at}; marked in the view.`;
    p.classList.toggle("hit", hit);
    p.hidden = false;
    p.dataset.approaches = APPROACHES.length;
    p.dataset.distance = a.distance_mm;
    // The button takes the slider to the move the approach happened on (at
    // the pose along it, where that move is on the page).
    const m = (M.approach_moves || [])[tightest], jump = $("jump");
    if (m) {
      jump.hidden = false;
      jump.textContent = hit ? "go to the collision" : "go to the closest approach";
      jump.dataset.target = m.kept;
      // The pose along the move needs the move before it on the page too.
      const whole = m.kept === 0 || P_INDEX[m.kept - 1] === P_INDEX[m.kept] - 1;
      jump.addEventListener("click", () => goTo(m.kept, m.exact && whole ? a.way : 1));
    }
  }
  // The address may ask for a move (#move=K, from 0), a step from it
  // (#step=-3: as many presses of ← or →), the closest approach
  // (#jump=closest: the button's click), or no bodies (#bodies=0).
  if (ask.get("bodies") === "0") { $("bodies").checked = false; showBodies = false; }
  if (ask.has("move")) { moveInput.value = ask.get("move"); moveInput.dispatchEvent(new Event("input")); }
  for (let n = Math.abs(+ask.get("step") || 0); n > 0; n--)
    document.dispatchEvent(new KeyboardEvent("keydown", { key: +ask.get("step") < 0 ? "ArrowLeft" : "ArrowRight" }));
  if (ask.get("jump") === "closest") $("jump").click();
  showPose();
  if (ARM) $("armplots").hidden = false;
  if (ROT) $("rotaryplots").hidden = false;
  if (HEAT) $("thermalplots").hidden = false;
  resize();
  // Where the view is on the page, CSS pixels (a test measures its screenshot).
  canvas.dataset.viewTop = Math.round(canvas.getBoundingClientRect().top + window.scrollY);
  bucketise(select.value);
  showRange();
  const t0 = performance.now();
  draw();
  // What one frame of the whole plan costs here: orbiting redraws it.
  canvas.dataset.frameMs = Math.round(performance.now() - t0);
  // How much of the view the plan's moves paint: a blank page says 0 (the
  // substrate, axes and scale bar would paint a page without moves). A frame
  // of the moves alone, counted, then the whole frame again.
  draw(true);
  const px = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  let painted = 0;
  for (let i = 0; i < px.length; i += 4) if (px[i] < 245 || px[i + 1] < 245 || px[i + 2] < 245) painted++;
  canvas.dataset.painted = painted;
  draw();
  plot();
  plotLayers();
  plotJoints();
  plotRotary();
  plotHeat();
  document.documentElement.dataset.ready = select.value;
})();

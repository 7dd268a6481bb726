//! Seed 003's variable-thickness layers, checked against the formulas and the
//! paper's numbers, written out here again rather than taken from the
//! library: the bead map `H = −0.135·v + 1.82 mm` (4 … 8.7 mm/s), the layer
//! count `⌈H_max/h_max⌉ ≤ N ≤ ⌊H_min/h_min⌋`, the segment error
//! `E(m) = (1/L)∫|H − H_seg|` (a plane's `ΔH/(4m)`), the overlap balance
//! `C_k·(h_k + h_{k+1}) = A_k + A_{k+1}` with the circular segment's area in
//! its `acos` form, and the deposit: a track that fills a strip `p` wide
//! (the bead's width alone, else the mean of its spacings to its
//! neighbours) raises its layer by `A(v)/p` — mass conservation, so the
//! paper's single-track map read as a layer height would stack about 3/4 of
//! a one-bead wall.

use lmdc::ir::{Point, Program};
use lmdc::pipeline::compile;
use proptest::prelude::*;
use std::collections::BTreeMap;

/// The paper's map: bead height at horizontal speed `v`.
fn paper_map(v: f64) -> f64 {
    -0.135 * v + 1.82
}

const H_MIN: f64 = 0.6455; // paper_map(8.7)
const H_MAX: f64 = 1.28; // paper_map(4)
const W: f64 = 2.4;

/// The layer heights a plan can have: a wall one bead wide rises `A/W`
/// (the bead's own heights spread over its width), balanced tracks by
/// their beads' heights.
fn heights(path: &str) -> [f64; 2] {
    if path.contains("ramp_wall") {
        [segment_area(W, H_MIN) / W, segment_area(W, H_MAX) / W]
    } else {
        [H_MIN, H_MAX]
    }
}

/// The strip each path of `layer` fills: its line's mean spacing to the
/// lines either side (across the scan axis, `across` the coordinate), the
/// bead's width `w` on a lone line.
fn pitches(layer: &lmdc::ir::Layer, across: usize, w: f64) -> Vec<f64> {
    let mut lines: Vec<f64> = layer
        .paths
        .iter()
        .map(|p| p.points[0].pos[across])
        .collect();
    lines.sort_by(f64::total_cmp);
    lines.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let pitch = |c: f64| {
        let k = lines.iter().position(|&l| (l - c).abs() < 1e-9).unwrap();
        let before = (k > 0).then(|| lines[k] - lines[k - 1]);
        let after = (k + 1 < lines.len()).then(|| lines[k + 1] - lines[k]);
        match (before, after) {
            (Some(a), Some(b)) => (a + b) / 2.0,
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => w,
        }
    };
    layer
        .paths
        .iter()
        .map(|p| pitch(p.points[0].pos[across]))
        .collect()
}

/// A circular segment of chord `w` and height `h`: `R²·acos((R−h)/R) −
/// (R−h)·√(2Rh − h²)`, `R = (w²/4 + h²)/(2h)`.
fn segment_area(w: f64, h: f64) -> f64 {
    let r = (w * w / 4.0 + h * h) / (2.0 * h);
    r * r * ((r - h) / r).acos() - (r - h) * (2.0 * r * h - h * h).sqrt()
}

/// The tops of the three examples, as their files state them.
fn ramp_wall_top(p: [f64; 2]) -> f64 {
    20.0 + 0.16 * (p[0] + 50.0)
}
fn wedge_top(p: [f64; 2]) -> f64 {
    8.0 + 5.0 * (p[1] + 7.5) / 15.0
}
fn ramp_cuboid_top(p: [f64; 2]) -> f64 {
    14.0 + 8.0 * (p[0] + 30.0) / 60.0 + 3.0 * (p[1] + 7.5) / 15.0
}

type Top = fn([f64; 2]) -> f64;

const EXAMPLES: [(&str, Top); 3] = [
    ("examples/ramp_wall.lmd", ramp_wall_top),
    ("examples/wedge.lmd", wedge_top),
    ("examples/ramp_cuboid.lmd", ramp_cuboid_top),
];

fn ir(path: &str) -> Program {
    let src = std::fs::read_to_string(path).unwrap();
    let c = compile(&src, &mut ());
    c.program
        .unwrap_or_else(|| panic!("{path}: {:#?}", c.diagnostics))
        .into_ir()
}

fn xy(p: &Point) -> [f64; 2] {
    [p.pos[0], p.pos[1]]
}

/// The speed over the ground of the move from `a` to `b` at `a`'s speed.
fn ground_speed(a: &Point, b: &Point) -> f64 {
    let run = (b.pos[0] - a.pos[0]).hypot(b.pos[1] - a.pos[1]);
    let path = (run * run + (b.pos[2] - a.pos[2]).powi(2)).sqrt();
    a.speed as f64 * run / path
}

#[test]
fn the_layer_count_is_the_fewest_the_bounds_allow() {
    for (path, top) in EXAMPLES {
        let p = ir(path);
        let n = p.layers.len() as f64;
        let heights: Vec<f64> = p.layers[0]
            .paths
            .iter()
            .flat_map(|pa| &pa.points)
            .map(|q| top(xy(q)))
            .collect();
        let hi = heights.iter().cloned().fold(f64::MIN, f64::max);
        let lo = heights.iter().cloned().fold(f64::MAX, f64::min);
        let [h_min, h_max] = self::heights(path);
        assert_eq!(n, (hi / h_max).ceil(), "{path}: H_max {hi}");
        assert!(n <= (lo / h_min).floor(), "{path}: H_min {lo}, {n} layers");
        // One layer fewer lays more than h_max at the highest point.
        assert!(hi / (n - 1.0) > h_max, "{path}");
    }
}

#[test]
fn the_layers_add_up_to_the_top_and_lie_on_each_other() {
    for (path, top) in EXAMPLES {
        let p = ir(path);
        let n = p.layers.len();
        // Σ of the layer heights at each (x, y), over every layer.
        let mut sums: BTreeMap<(i64, i64), (f64, usize, f64)> = BTreeMap::new();
        for (i, l) in p.layers.iter().enumerate() {
            for q in l.paths.iter().flat_map(|pa| &pa.points) {
                let h = top(xy(q));
                assert!(
                    (q.pos[2] - i as f64 * h / n as f64).abs() <= 1e-9 * h,
                    "{path}: layer {i} at {:?} is not on the planned top of the one below",
                    q.pos
                );
                assert!(((q.layer_height as f64) - h / n as f64).abs() <= 1e-6 * h);
                if q.laser_on {
                    let lh = q.layer_height as f64;
                    let [h_min, h_max] = heights(path);
                    assert!(
                        (h_min * (1.0 - 1e-6)..=h_max * (1.0 + 1e-6)).contains(&lh),
                        "{path}: {lh}"
                    );
                }
                let key = (
                    (q.pos[0] * 1e6).round() as i64,
                    (q.pos[1] * 1e6).round() as i64,
                );
                let e = sums.entry(key).or_insert((0.0, 0, h));
                e.0 += q.layer_height as f64;
                e.1 += 1;
            }
        }
        for ((x, y), (sum, count, h)) in sums {
            assert_eq!(count, n, "{path}: ({x}, {y}) µm is not on every layer");
            assert!((sum - h).abs() <= 1e-6 * h, "{path}: Σ {sum} ≠ top {h}");
        }
    }
}

#[test]
fn every_speed_lays_the_layer_by_the_paper_map() {
    // Each move of a plane top is a whole segment: at the move's speed over
    // the ground the map gives a bead whose segment, spread over the strip
    // the track fills, is the layer height at the move's middle.
    for (path, top) in EXAMPLES {
        let p = ir(path);
        let n = p.layers.len() as f64;
        let mut moves = 0;
        for l in &p.layers {
            // Every example scans along x: the lines lie across y.
            for (pa, pitch) in l.paths.iter().zip(pitches(l, 1, W)) {
                for w in pa.points.windows(2).filter(|w| w[0].laser_on) {
                    let v = ground_speed(&w[0], &w[1]);
                    assert!((4.0 - 1e-5..=8.7 + 1e-5).contains(&v), "{path}: {v}");
                    let mid = [
                        (w[0].pos[0] + w[1].pos[0]) / 2.0,
                        (w[0].pos[1] + w[1].pos[1]) / 2.0,
                    ];
                    let want = top(mid) / n;
                    let rise = segment_area(W, paper_map(v)) / pitch;
                    assert!(
                        (rise - want).abs() < 2e-6,
                        "{path}: {v} mm/s over {pitch} mm raises {rise}, the segment needs {want}",
                    );
                    // The IR says the same.
                    assert!((w[0].pitch as f64 - pitch).abs() < 1e-5);
                    assert!((w[0].rise as f64 - want).abs() < 1e-5);
                    moves += 1;
                }
            }
        }
        assert!(moves > 0);
    }
}

/// The segments of each track of layer 0: (length, rise of the top along
/// it, segment count).
fn tracks(p: &Program, top: Top) -> Vec<(f64, f64, usize)> {
    p.layers[0]
        .paths
        .iter()
        .map(|pa| {
            let (a, b) = (&pa.points[0], &pa.points[pa.points.len() - 1]);
            let len = (b.pos[0] - a.pos[0]).hypot(b.pos[1] - a.pos[1]);
            let rise = (top(xy(b)) - top(xy(a))).abs();
            (len, rise, pa.points.len() - 1)
        })
        .collect()
}

/// `E` of `m` equal segments, each at its midpoint height, on the straight
/// top `top(t)` over `0..len`, by dense integration.
fn mean_error(len: f64, m: usize, top: impl Fn(f64) -> f64) -> f64 {
    let k = 20_000;
    let dt = len / k as f64;
    (0..k)
        .map(|i| {
            let t = (i as f64 + 0.5) * dt;
            let j = ((t / len * m as f64) as usize).min(m - 1);
            let mid = (j as f64 + 0.5) * len / m as f64;
            (top(t) - top(mid)).abs() * dt
        })
        .sum::<f64>()
        / len
}

#[test]
fn the_segment_count_is_the_smallest_that_meets_the_tolerance() {
    for (path, top, tol) in [
        ("examples/ramp_wall.lmd", ramp_wall_top as Top, 0.1),
        ("examples/ramp_cuboid.lmd", ramp_cuboid_top as Top, 0.1),
    ] {
        let p = ir(path);
        for (len, rise, m) in tracks(&p, top) {
            // A plane: E(m) = ΔH/(4m); m = ⌈ΔH/(4·E_H)⌉.
            assert_eq!(m as f64, (rise / (4.0 * tol)).ceil(), "{path}");
            let line = |t: f64| rise * t / len;
            assert!(mean_error(len, m, line) <= tol * (1.0 + 1e-3), "{path}");
            assert!(
                mean_error(len, m - 1, line) > tol,
                "{path}: {} would do",
                m - 1
            );
            // And no segment is shorter than the minimum (the bead width).
            assert!(len / m as f64 >= W, "{path}");
        }
    }
    // The ramp wall: 97.6 mm between the track's ends half a bead inside
    // the wall's, rising 16 % of that: 40 segments of 2.44 mm.
    let p = ir("examples/ramp_wall.lmd");
    assert_eq!(tracks(&p, ramp_wall_top)[0].2, 40);
}

/// `σ_k = C_k·(h_k + h_{k+1}) / (A_k + A_{k+1})` of each pair of tracks of
/// layer 0 (centres across at `y`, heights at mid-length `x = 0`).
fn balance(p: &Program, top: Top) -> (Vec<f64>, Vec<f64>) {
    let n = p.layers.len() as f64;
    let ys: Vec<f64> = p.layers[0]
        .paths
        .iter()
        .map(|pa| pa.points[0].pos[1])
        .collect();
    let h: Vec<f64> = ys.iter().map(|&y| top([0.0, y]) / n).collect();
    let sigma = (0..ys.len() - 1)
        .map(|k| {
            (ys[k + 1] - ys[k]) * (h[k] + h[k + 1])
                / (segment_area(W, h[k]) + segment_area(W, h[k + 1]))
        })
        .collect();
    (ys, sigma)
}

#[test]
fn unequal_tracks_meet_level_in_one_balance() {
    for (path, top) in [
        ("examples/wedge.lmd", wedge_top as Top),
        ("examples/ramp_cuboid.lmd", ramp_cuboid_top as Top),
    ] {
        let p = ir(path);
        let (ys, sigma) = balance(&p, top);
        // Every pair in the same balance, stretched by one σ to close.
        for s in &sigma {
            assert!((s - sigma[0]).abs() <= 1e-6 * sigma[0], "{path}: {sigma:?}");
        }
        assert!((sigma[0] - 1.0).abs() < 0.05, "{path}: σ = {}", sigma[0]);
        // From half a bead inside one face to half a bead inside the other.
        assert!((ys[0] - (-7.5 + W / 2.0)).abs() < 1e-9, "{path}");
        assert!((ys[ys.len() - 1] - (7.5 - W / 2.0)).abs() < 1e-9, "{path}");
        // Taller beads are fuller: the spacing grows up the slope.
        assert!(ys.windows(3).all(|w| w[2] - w[1] > w[1] - w[0]), "{path}");
        // The unstretched balance, stepped across: the track count is one of
        // the two around where it reaches the far face.
        let n = p.layers.len() as f64;
        let h = |y: f64| top([0.0, y]) / n;
        let (mut y, mut steps) = (ys[0], 0usize);
        let target = ys[ys.len() - 1];
        while y <= target {
            let gap =
                |c: f64| c * (h(y) + h(y + c)) - segment_area(W, h(y)) - segment_area(W, h(y + c));
            let (mut lo, mut hi) = (0.0, 2.0 * W);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if gap(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            y += lo;
            steps += 1;
        }
        let gaps = ys.len() - 1;
        assert!(
            gaps == steps || gaps + 1 == steps,
            "{path}: {gaps} gaps, {steps} steps"
        );
    }
}

#[test]
fn the_paper_map_is_the_reference_bead() {
    // H = −0.135·v + 1.82 over 4 … 8.7 mm/s: 0.6455 … 1.28 mm, ratio 1.983.
    // A wall one bead wide rises by those beads' segments over the width.
    let p = ir("examples/ramp_wall.lmd");
    let [lo, hi] = heights("examples/ramp_wall.lmd");
    // (The library's segment takes its angle from atan2, this one's acos.)
    assert!((p.limits.layer_height[0] - lo).abs() < 1e-7);
    assert!((p.limits.layer_height[1] - hi).abs() < 1e-7);
    // The balanced tracks of a wedge rise by what their beads lay over the
    // strips they fill, from the widest strip to the narrowest.
    let p = ir("examples/wedge.lmd");
    let ps = pitches(&p.layers[0], 1, W);
    let wide = ps.iter().cloned().fold(f64::MIN, f64::max);
    let narrow = ps.iter().cloned().fold(f64::MAX, f64::min);
    assert!((p.limits.layer_height[0] - segment_area(W, H_MIN) / wide).abs() < 1e-7);
    assert!((p.limits.layer_height[1] - segment_area(W, H_MAX) / narrow).abs() < 1e-7);
    assert_eq!(p.limits.speed, [4.0, 8.7]);
    assert!((H_MAX / H_MIN - 1.983).abs() < 5e-4);
    assert!((paper_map(4.0) - H_MAX).abs() < 1e-12 && (paper_map(8.7) - H_MIN).abs() < 1e-12);
}

/// A rectangle `lx × ly` (outer face, centred) under a plane top
/// `h0 + sx·x + sy·y`, built with a linear bead of heights `h_lo … h_hi`
/// over `v0 … v1`, sliced along x with tolerance `tol`.
#[derive(Clone, Debug)]
struct Case {
    lx: f64,
    ly: f64,
    w: f64,
    h0: f64,
    sx: f64,
    sy: f64,
    v0: f64,
    v1: f64,
    h_lo: f64,
    h_hi: f64,
    tol: f64,
}

impl Case {
    fn slope(&self) -> f64 {
        (self.h_lo - self.h_hi) / (self.v1 - self.v0)
    }

    fn source(&self) -> String {
        let k = self.slope();
        let c = self.h_lo - k * self.v1;
        format!(
            "part p
bead b {{
  width = {w} mm
  speed = {v0} mm/s .. {v1} mm/s
  model = linear(slope = {k} mm / (1 mm/s), intercept = {c} mm)
}}
extrude e {{
  profile = rectangle(width = {lx} mm, height = {ly} mm)
  size = outer
  bead = b
  top = plane(at = [0 mm, 0 mm], height = {h0} mm, slope_x = {sx}, slope_y = {sy})
}}
slicing variable {{
  scan = x
  segments {{ tolerance = {tol} mm }}
}}
process {{
  power = 1000 W
  powder = 12 g/min
  defocus = 0 mm
}}
machine m {{
  kind = cnc
  head {{ standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }}
  axes = 3
  dialect = linuxcnc
  max_speed = 100 mm/s
  clearance = 5 mm
  limits {{
    x = -100 mm .. 100 mm
    y = -100 mm .. 100 mm
    z = -10 mm .. 200 mm
  }}
}}
",
            w = self.w,
            v0 = self.v0,
            v1 = self.v1,
            lx = self.lx,
            ly = self.ly,
            h0 = self.h0,
            sx = self.sx,
            sy = self.sy,
            tol = self.tol,
        )
    }

    fn top(&self, p: [f64; 2]) -> f64 {
        self.h0 + self.sx * p[0] + self.sy * p[1]
    }
}

fn cases() -> impl Strategy<Value = Case> {
    (
        (10.0..60.0f64, 1.0..5.0f64, 1.0..4.0f64),
        (3.0..30.0f64, -0.15..0.15f64, -0.15..0.15f64),
        (2.0..6.0f64, 1.3..3.0f64, 0.3..1.0f64, 1.2..2.5f64),
        0.03..0.3f64,
    )
        .prop_map(|((lx, ly, w), (h0, sx, sy), (v0, vr, h_lo, hr), tol)| {
            // A bead lower than half its width (a minor circular segment),
            // as DED beads are.
            let w = w.max(2.2 * h_lo * hr);
            Case {
                lx: lx.max(2.0 * w),
                ly: ly * w,
                w,
                h0,
                sx,
                sy,
                v0,
                v1: v0 * vr,
                h_lo,
                h_hi: h_lo * hr,
                tol,
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random plane tops and bead maps: the compiler either builds the part
    /// — the layers summing to the top, the fewest segments, every move's
    /// speed within the bead's range and raising its layer by the height it
    /// plans (`A(v)/pitch`, mass conservation), with the fewest layers the
    /// bounds allow for a wall one bead wide — or says why not, and for a
    /// wall the formulas agree there is no way. (Balanced tracks are spaced
    /// to close on the far edge, which moves their pitches with the count:
    /// there the plan's own physics is the oracle.)
    #[test]
    fn random_tops_and_beads(case in cases()) {
        let c = compile(&case.source(), &mut ());
        // What the layers are is asked here; whether a nozzle 15 mm above
        // the focus clears random layers (tracks squeezed to 12 mm a layer)
        // is tests/collision.rs's.
        let codes: Vec<&str> = c
            .diagnostics
            .iter()
            .filter(|d| d.is_error() && d.code != lmdc::diag::Code::Collision)
            .map(|d| d.code.as_str())
            .collect();
        // Where tracks run: half a bead inside the outer face, both ways.
        let (ax, ay) = (case.lx / 2.0 - case.w / 2.0, case.ly / 2.0 - case.w / 2.0);
        let corners = [[-ax, -ay], [-ax, ay], [ax, -ay], [ax, ay]].map(|p| case.top(p));
        let lo = corners.iter().cloned().fold(f64::MAX, f64::min);
        let hi = corners.iter().cloned().fold(f64::MIN, f64::max);
        if lo <= 0.0 {
            prop_assert_eq!(codes, vec!["lmd::top-height"]);
            return Ok(());
        }
        // One track fills the footprint: a wall, rising A/w.
        let single = case.ly <= case.w * (1.0 + 1e-9);
        let (h_lo, h_hi) = if single {
            (segment_area(case.w, case.h_lo) / case.w, segment_area(case.w, case.h_hi) / case.w)
        } else {
            (case.h_lo, case.h_hi)
        };
        let fits = |n: f64| hi / n <= h_hi * (1.0 + 1e-6) && lo / n >= h_lo * (1.0 - 1e-6);
        let n = (1..=2000).map(|n| n as f64).find(|&n| fits(n));
        // The count's first bounds: a wall's rises, balanced tracks' beads.
        if n.is_none() {
            prop_assert_eq!(codes, vec!["lmd::no-layer-count"]);
            return Ok(());
        }
        // A plane's segments: m = ⌈ΔH/(4·E_H)⌉ on a track 2·ax long, each
        // at least a bead long.
        let len = 2.0 * ax;
        let m_for = |rise: f64| (1..).find(|&m| rise / (4.0 * m as f64) <= case.tol * (1.0 + 1e-9)).unwrap();
        let m = m_for(case.sx.abs() * len);
        let allowed = ((len / case.w) * (1.0 + 1e-9)).floor().max(1.0) as usize;
        if m > allowed {
            prop_assert_eq!(codes, vec!["lmd::segments-too-short"]);
            return Ok(());
        }
        if !single && !codes.is_empty() {
            prop_assert_eq!(codes, vec!["lmd::no-layer-count"]);
            return Ok(());
        }
        prop_assert!(codes.is_empty(), "{:#?}", c.diagnostics);
        let Some(p) = c.program else {
            // Refused for a collision only.
            return Ok(());
        };
        let p = p.into_ir();
        if single {
            prop_assert_eq!(Some(p.layers.len() as f64), n);
        }
        let n = p.layers.len() as f64;
        let map = |v: f64| case.slope() * (v - case.v1) + case.h_lo;
        for (i, l) in p.layers.iter().enumerate() {
            for pa in &l.paths {
                prop_assert_eq!(pa.points.len() - 1, m);
                for q in &pa.points {
                    let h = case.top(xy(q));
                    prop_assert!((q.pos[2] - i as f64 * h / n).abs() <= 1e-9 * h);
                    prop_assert!(((q.layer_height as f64) - h / n).abs() <= 1e-6 * h);
                    if q.laser_on && single {
                        let lh = q.layer_height as f64;
                        prop_assert!((h_lo * (1.0 - 1e-6)..=h_hi * (1.0 + 1e-6)).contains(&lh));
                    }
                }
            }
            for (pa, pitch) in l.paths.iter().zip(pitches(l, 1, case.w)) {
                for w in pa.points.windows(2).filter(|w| w[0].laser_on) {
                    let mid = [(w[0].pos[0] + w[1].pos[0]) / 2.0, (w[0].pos[1] + w[1].pos[1]) / 2.0];
                    let v = ground_speed(&w[0], &w[1]);
                    prop_assert!(v >= case.v0 * (1.0 - 1e-5) && v <= case.v1 * (1.0 + 1e-5), "{} mm/s", v);
                    let rise = segment_area(case.w, map(v)) / pitch;
                    prop_assert!((rise - case.top(mid) / n).abs() <= 1e-5 * case.h_hi, "{} vs {}", rise, case.top(mid) / n);
                }
            }
        }
    }
}

/// A top higher in the middle than at the tracks' ends (found by trying one):
/// each layer ends at one end and the next starts at the other, and the
/// straight rapid between their clearance points ran up to 10 mm inside the
/// ridge built before. Every rapid of the plan now passes `clearance` above
/// everything deposited so far, or goes straight up or down.
#[test]
fn no_rapid_cuts_through_a_ridge_laid_before() {
    use lmdc::plan::{Move, Speed, Visit};
    let src = r#"part ridge
bead b316 {
  width = 2.4 mm
  speed = 4 mm/s .. 8.7 mm/s
  model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)
}
extrude blk {
  profile = rectangle(width = 60 mm, height = 12 mm)
  size = outer
  bead = b316
  top = 30 mm - (x * x) / (60 mm)
}
slicing variable {
  layers = auto
  scan = y
  offset = balanced
}
process {
  power = 1000 W
  powder = 12 g/min
  defocus = 0 mm
}
machine mill3 {
  kind = cnc
  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }
  axes = 3
  max_speed = 50 mm/s
  clearance = 2 mm
}
"#;
    struct Rapids {
        at: Option<[f64; 3]>,
        top: f64,
        /// Rapids that cross ground, with how far they pass below
        /// `clearance` above the top at their lower end.
        low: Vec<f64>,
        crossings: usize,
    }
    impl Visit for Rapids {
        fn motion(&mut self, m: &Move) {
            let from = self.at.unwrap_or(m.to);
            if m.deposits() {
                self.top = self.top.max(from[2]).max(m.to[2]);
            } else if m.speed == Speed::Rapid && (from[0] - m.to[0]).hypot(from[1] - m.to[1]) > 1e-6
            {
                self.crossings += 1;
                let lowest = from[2].min(m.to[2]);
                if lowest < self.top + 2.0 - 1e-6 {
                    self.low.push(self.top + 2.0 - lowest);
                }
            }
            self.at = Some(m.to);
        }
    }
    let c = compile(src, &mut ());
    let p = c.program.expect("the ridge builds");
    let m = p.machines().next().unwrap();
    let mut r = Rapids {
        at: None,
        top: f64::NEG_INFINITY,
        low: Vec::new(),
        crossings: 0,
    };
    m.plan().walk(&mut r);
    assert!(r.crossings > 100, "{} rapids", r.crossings);
    assert!(
        r.low.is_empty(),
        "{} rapids pass low: {:?}",
        r.low.len(),
        r.low
    );
}

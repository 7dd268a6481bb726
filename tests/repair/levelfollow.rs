//! `level = …` with `follow = surface` (docs/repair.md, *Levelling* and
//! *Following the surface*): the worn pad levelled to its scan's highest
//! point with the nozzle along the scan's normal, then built up in regular
//! layers (tests/repair/worn_pad_level_follow.lmd), and a steeper wear of
//! the same pad. Pass `k` of the `n` a place takes lies on
//! `B + (k/n)·(z_L − B)`: its nozzle is along that surface's normal, the
//! scan's slope fitted over a bead's width either way scaled by `1 − k/n`,
//! computed here from the wear's formula. A pass `t` thick (vertically)
//! laid along a normal tilted `θ` on a surface sloping `α` along the tracks
//! is `t·cos θ` thick along the nozzle and fills a strip `p·cos α / cos θ`
//! of the track spacing `p`: it lays `A(v)/strip` at a speed `v`, so its
//! thickness along the nozzle must lie between `A(8.7 mm/s)/strip` and
//! `A(4 mm/s)/strip`, `A` the circular segment of the bead's width and the
//! linear model's height, computed here too.

use super::{compile, example_z, messages, ply, scan, Wear};
use lmdc::ir::Program;
use std::collections::BTreeMap;

const SRC: &str = include_str!("worn_pad_level_follow.lmd");

/// The bead's width and its linear model (the file's b316).
const WIDTH: f64 = 2.4;

fn bead_height(v: f64) -> f64 {
    1.82 - 0.135 * v
}

/// The cross-section of a bead of chord `w` and height `h`: a circular
/// segment.
fn segment_area(w: f64, h: f64) -> f64 {
    let half = w / 2.0;
    let r = (half * half + h * h) / (2.0 * h);
    let theta = 2.0 * half.atan2(r - h);
    0.5 * r * r * theta - half * (r - h)
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot: f64 = (0..3).map(|i| a[i] * b[i]).sum();
    dot.clamp(-1.0, 1.0).acos().to_degrees()
}

/// A laser-on point of a pass: where, its unit normal, its layer height
/// (along the normal) and the strip it is written to fill.
#[derive(Clone, Copy, Debug)]
struct Deposit {
    pos: [f64; 3],
    normal: [f64; 3],
    height: f64,
    pitch: f64,
}

impl Deposit {
    /// Its thickness read vertically: along the normal over `cos θ`.
    fn vertical(&self) -> f64 {
        self.height / self.normal[2]
    }
}

/// The points of `l`: its laser-on ones, or with `ends` every one (a
/// path's last point, laser off, is where its stretch ends).
fn deposits(l: &lmdc::ir::Layer, ends: bool) -> Vec<Deposit> {
    l.paths
        .iter()
        .flat_map(|p| &p.points)
        .filter(|q| ends || q.laser_on)
        .map(|q| {
            let n = q.normal.map(f64::from);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            Deposit {
                pos: q.pos,
                normal: n.map(|v| v / len),
                height: f64::from(q.layer_height),
                pitch: f64::from(q.pitch),
            }
        })
        .collect()
}

/// What a levelled plan followed along the normal must hold on a scan of
/// `z` up to `top` (the tracks along x): the passes, then regular layers
/// from the level (the first of them on `on_plate`, flat at `z_L`, their
/// nozzle vertical). Each place's passes: the first on the surface within
/// `tol`, each next one on the one before (read vertically), one vertical
/// thickness for all, the last ending on the level (up to half a pass
/// proud, where the gap is thinner than the thinnest pass); pass `k` of `n`
/// along the fitted normal scaled by `1 − k/n` within `deg`; every pass's
/// thickness along its nozzle within the bead's heights over its own strip.
/// Returns the level, the passes and the largest tilt of the first pass.
fn check(
    p: &Program,
    z: impl Fn(f64, f64) -> f64,
    top: f64,
    tol: f64,
    deg: f64,
) -> (f64, usize, f64) {
    let passes = p
        .layers
        .iter()
        .position(|l| l.on_plate)
        .expect("levelling passes, then the regular layers");
    assert!(passes >= 1);
    let level = deposits(&p.layers[passes], false)[0].pos[2];
    // The regular layers: flat, vertical, of one height, the last at the top.
    let regular = &p.layers[passes..];
    let t = (top - level) / regular.len() as f64;
    for (i, l) in regular.iter().enumerate() {
        for d in deposits(l, false) {
            assert_eq!(d.normal, [0.0, 0.0, 1.0], "regular layer {i}");
            assert!((d.pos[2] - level - i as f64 * t).abs() < 1e-4, "{d:?}");
            assert!((d.height - t).abs() < 1e-4, "{d:?}");
        }
    }
    // The strip of each line: the regular layers' (vertical) pitch there.
    let strips: Vec<(f64, f64)> = deposits(&regular[0], false)
        .iter()
        .map(|d| (d.pos[1], d.pitch))
        .collect();
    let spacing = |y: f64| {
        strips
            .iter()
            .find(|s| (s.0 - y).abs() < 1e-6)
            .map(|s| s.1)
            .unwrap_or_else(|| panic!("no regular track at y = {y}"))
    };
    let [a_min, a_max] = [8.7, 4.0].map(|v| segment_area(WIDTH, bead_height(v)));
    // Each place's stack: its passes in order, by place and vertical
    // thickness (where the count changes two stacks meet at one place).
    let mut at: BTreeMap<(i64, i64, i64), Vec<Deposit>> = BTreeMap::new();
    for l in &p.layers[..passes] {
        for d in deposits(l, true) {
            assert!(d.pos[2] < level + 1e-6, "{d:?} above the level {level}");
            let key = (
                (d.pos[0] * 1e4).round() as i64,
                (d.pos[1] * 1e4).round() as i64,
                (d.vertical() * 1e3).round() as i64,
            );
            at.entry(key).or_default().push(d);
        }
    }
    let mut steepest: f64 = 0.0;
    for stack in at.values() {
        let [x, y, b] = stack[0].pos;
        let n = stack.len();
        let t = stack[0].vertical();
        assert!(
            (b - z(x, y)).abs() <= tol,
            "first pass at ({x}, {y}): {b} on {}",
            z(x, y)
        );
        let g = super::fitted_slope(&z, x, y);
        for (k, d) in stack.iter().enumerate() {
            assert!(
                (d.vertical() - t).abs() < 1e-4,
                "({x}, {y}) pass {k}: {d:?}"
            );
            assert!(
                (d.pos[2] - b - k as f64 * t).abs() < 1e-4,
                "({x}, {y}) pass {k}: {d:?}"
            );
            // Along the normal of the pass's surface: the slope `1 − k/n` of
            // the scan's.
            let w = 1.0 - k as f64 / n as f64;
            let want = [-w * g[0], -w * g[1], 1.0];
            let off = angle(d.normal, want);
            assert!(
                off < deg,
                "({x}, {y}) pass {k} of {n}: {off}° off {want:?}: {d:?}"
            );
            if k == 0 {
                steepest = steepest.max(angle(d.normal, [0.0, 0.0, 1.0]));
            }
            // Its thickness along the nozzle, within the bead's heights over
            // the strip it fills: `p·cos α / cos θ`.
            let [nx, _, nz] = d.normal;
            let cos_alpha = 1.0 / (nx / nz).hypot(1.0);
            let strip = spacing(y) * cos_alpha / nz;
            let [lo, hi] = [a_min / strip, a_max / strip];
            assert!(
                d.height >= lo * (1.0 - 1e-5) && d.height <= hi * (1.0 + 1e-5),
                "({x}, {y}) pass {k} of {n}: {} mm along the nozzle, the bead lays {lo} .. {hi} over {strip} mm",
                d.height
            );
        }
        // The last pass ends on the level: half a pass proud at most, where
        // a gap under the thinnest pass takes one of it; none thinner than
        // half a pass.
        let last = stack[n - 1];
        let reached = last.pos[2] + last.vertical() - level;
        assert!(
            (-1e-4..=n as f64 * t / 2.0 + 1e-4).contains(&reached),
            "({x}, {y}): {n} passes of {t} end {reached} off the level"
        );
        if n > 1 {
            assert!(
                reached.abs() < 1e-4,
                "({x}, {y}): {n} passes end {reached} off the level"
            );
        }
        assert!(
            level - z(x, y) >= n as f64 * t / 2.0 - tol,
            "({x}, {y}): {n} × {t}"
        );
    }
    (level, passes, steepest)
}

/// The worn pad: its trough 1.5 mm deep, the level the scan's highest
/// point under the tracks (10 mm and its noise), two passes where the
/// trough is deeper than a pass (1.229 mm on 2 mm strips), the first
/// along the scan's normal (up to 5°: the trough's flanks), the second
/// half as tilted; then 3 regular layers to 13 mm. Its programs pass every
/// rule (lmd::deposit among them: each stretch at one speed lays the mean
/// of what it plans along the nozzle).
#[test]
fn the_worn_pad_levelled_along_its_normal_then_built_up() {
    let bytes = std::fs::read("examples/repair/worn_pad.ply").unwrap();
    let files = BTreeMap::from([("repair/worn_pad.ply".to_string(), bytes)]);
    let c = compile(SRC, files);
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    let p = p.ir();
    // The scan's noise is 0.03 mm RMS: its normal fitted over a bead within
    // 0.5°, its surface within 0.06 mm.
    let (level, passes, steepest) = check(p, example_z, 13.0, 0.06, 0.5);
    assert!((level - 10.0).abs() < 0.1, "{level}");
    assert_eq!((passes, p.layers.len()), (2, 5));
    // The trough slopes up to 1.5·√2·e^(−½)/15 = 0.0858 along x (4.9°) and
    // 1.5·2·8.8/14² = 0.135 across at its bottom under the outer tracks
    // (y = ±8.8 mm): 7.7°.
    assert!((6.5..8.5).contains(&steepest), "{steepest}°");
}

/// The steeper wear of the tests below, 2.5 mm deep and 7 mm wide along
/// the tracks, and its scan. No noise: the surface estimate on its 1 mm
/// cells rounds the trough's bottom (curving 2·2.5/7² = 0.1 /mm) by up to
/// 0.06 mm.
fn steep_wear() -> (Wear, Vec<[f64; 3]>) {
    let wear = Wear {
        face: 10.0,
        depth: 2.5,
        c: [0.0, 0.0],
        s: [7.0, 14.0],
    };
    let pts = scan(|x, y| wear.z(x, y), 0.0, 1);
    (wear, pts)
}

/// A steeper wear (2.5 mm deep, 7 mm wide along the tracks): its flanks
/// slope up to 17° along them, so the thinnest pass laid along the
/// normal there is the bead's over cos 17°, thicker than a vertical one. A pass carries the gap's whole slope: the segments'
/// tolerance is 0.3 mm (at 0.1 mm the flanks need segments shorter than
/// a bead, `lmd::segments-too-short`, followed or not).
#[test]
fn a_steep_wear_levelled_along_its_normal_keeps_the_beads_heights() {
    let (wear, pts) = steep_wear();
    let src = SRC.replace("repair/worn_pad.ply", "s.ply").replace(
        "  follow = surface\n",
        "  follow = surface\n  segments {\n    tolerance = 0.3 mm\n  }\n",
    );
    let c = compile(&src, BTreeMap::from([("s.ply".to_string(), ply(&pts))]));
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    let (level, passes, steepest) = check(p.ir(), |x, y| wear.z(x, y), 13.0, 0.08, 0.5);
    assert!((level - 10.0).abs() < 0.01, "{level}");
    // 2.44 mm at the bottom as scanned: 2 passes of up to 1.229 mm.
    assert!(passes >= 2, "{passes}");
    // The plane fitted over ±3 mm flattens the steepest flank a little.
    assert!(steepest > 12.0, "{steepest}°");
}

/// The steep wear with a bead of a narrow range (8.6 to 8.7 mm/s): the
/// thinnest pass along the normal, the bead's lowest over `cos α`, is more
/// than its tallest where the wear slopes more than `acos(lo/hi)` along
/// the tracks (12.2°, from the bead's areas here), so no pass can be laid
/// there: refused before planning, at `follow`, with the tilt that would
/// do. (The top 12.75 mm and the pad 20.4 mm across keep the regular
/// layers' count and spacing within the narrow bead.)
#[test]
fn a_pass_no_thickness_lays_along_the_normal_is_refused() {
    let (_, pts) = steep_wear();
    let src = SRC
        .replace("repair/worn_pad.ply", "s.ply")
        .replace("speed = 4 mm/s .. 8.7 mm/s", "speed = 8.6 mm/s .. 8.7 mm/s")
        .replace("top = 13 mm", "top = 12.75 mm")
        .replace("height = 20 mm)", "height = 20.4 mm)")
        .replace(
            "  follow = surface\n",
            "  follow = surface\n  segments {\n    tolerance = 0.3 mm\n  }\n",
        );
    let c = compile(&src, BTreeMap::from([("s.ply".to_string(), ply(&pts))]));
    let m = messages(&c);
    assert!(c.program.is_none(), "{m}");
    assert!(
        m.starts_with(
            "lmd::follow-surface: the levelling passes cannot be laid along the scan's normal at ("
        ),
        "{m}"
    );
    let most = (segment_area(WIDTH, bead_height(8.7)) / segment_area(WIDTH, bead_height(8.6)))
        .acos()
        .to_degrees();
    assert!((12.0..12.5).contains(&most), "{most}");
    let help = c
        .diagnostics
        .iter()
        .next()
        .unwrap()
        .help
        .as_deref()
        .unwrap();
    assert!(
        help.starts_with(&format!("let the nozzle tilt at most {}°", most.floor())),
        "{help}"
    );
}

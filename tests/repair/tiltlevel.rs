//! Levelling and `follow = surface` along a tilted build direction
//! (`direction = auto`, docs/repair.md, *Undercuts* and *Levelling*): a
//! block whose face slopes 30° down toward +x, worn, and on it a boss to
//! build square to the face, 12 mm along its axis (30° from vertical
//! toward +x). Its +x flank overhangs the face, so it is built along its
//! axis; the level is a plane square to the axis, at its height along it.
//! All checks are against the formulas here, not lmdc's mesh or scan.

use super::{compile, messages};
use lmdc::ir::Program;
use std::collections::BTreeMap;

/// The boss's lean from vertical toward +x, deg.
const LEAN: f64 = 30.0;

/// The boss's half width across its lean (along `e`), mm.
const HALF: f64 = 12.0;

/// The block's face as designed along the lean, the boss's end, mm.
const FACE: f64 = 10.0;
const TOP: f64 = 22.0;

/// The face as scanned lies this far under the design along the lean
/// outside the wear, mm: under the boss's overhang a line along a lesser
/// tilt leaves the boss and enters the block again above the scan.
const SKIN: f64 = 0.3;

/// The build direction `d` and the direction across it in x–z, `e`.
fn axes() -> ([f64; 3], [f64; 3]) {
    let (s, c) = LEAN.to_radians().sin_cos();
    ([s, 0.0, c], [c, 0.0, -s])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| a[k] * b[k]).sum()
}

/// A point's coordinates across the lean, along y and along the lean.
fn boss(q: [f64; 3]) -> [f64; 3] {
    let (d, e) = axes();
    [dot(q, e), q[1], dot(q, d)]
}

/// The part's point at `a` across the lean and `u` along it, in x–z.
fn at(a: f64, u: f64) -> [f64; 2] {
    let (d, e) = axes();
    [a * e[0] + u * d[0], a * e[2] + u * d[2]]
}

/// The face's wear along the lean, mm.
fn wear(a: f64, y: f64) -> f64 {
    1.5 * (-(a / 6.0).powi(2)).exp() * (1.0 - (y / 14.0).powi(2))
}

/// The worn face along the lean at `a`, `y`.
fn worn(a: f64, y: f64) -> f64 {
    FACE - SKIN - wear(a, y)
}

/// The worn face's slope across the lean and along y as the nozzle
/// follows it (docs/repair.md, *Following the surface*): the
/// least-squares plane through the face every cell (1 mm) over a bead's
/// width (2.4 mm, so 3 cells) either way, about `(a, y)`. On a full
/// symmetric window its slopes are `Σ i·w / Σ i²` each way.
fn fitted_slope(a: f64, y: f64) -> [f64; 2] {
    super::fitted_slope(&worn, a, y)
}

/// The part as designed in x–z (counter-clockwise): the block to its
/// face, and on it the boss to its end, both square to the lean.
fn section() -> Vec<[f64; 2]> {
    [
        (-40.0, -10.0),
        (40.0, -10.0),
        (40.0, FACE),
        (HALF, FACE),
        (HALF, TOP),
        (-HALF, TOP),
        (-HALF, FACE),
        (-40.0, FACE),
    ]
    .into_iter()
    .map(|(a, u)| at(a, u))
    .collect()
}

/// Whether `q` is in the part as designed, within `tol` mm.
fn in_target(q: [f64; 3], tol: f64) -> bool {
    let [a, y, u] = boss(q);
    let block = a.abs() <= 40.0 && (-10.0..=FACE + tol).contains(&u);
    let lean = a.abs() <= HALF + tol && u <= TOP + tol && u >= FACE - tol;
    (block || lean) && y.abs() <= 20.0
}

/// The worn face's height at `(x, y)`, seen from above.
fn scanned(x: f64, y: f64) -> f64 {
    let (s, c) = LEAN.to_radians().sin_cos();
    // u = worn(a), a and u both of z (a few rounds).
    let mut z = (FACE - s * x) / c;
    for _ in 0..30 {
        z = (worn(c * x - s * z, y) - s * x) / c;
    }
    z
}

/// The scan as a binary PLY, every 0.25 mm over x −15..40, y −12..12.
fn ply() -> Vec<u8> {
    let mut pts = Vec::new();
    for i in 0..=220 {
        for j in 0..=96 {
            let (x, y) = (-15.0 + i as f64 * 0.25, -12.0 + j as f64 * 0.25);
            pts.push([x, y, scanned(x, y)]);
        }
    }
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
        pts.len()
    )
    .into_bytes();
    for p in pts {
        for v in p {
            out.extend((v as f32).to_le_bytes());
        }
    }
    out
}

/// The boss on the leaning slab's 5-axis head (A ±35°, the bead measured
/// to 35°), its profile its end seen from above, 16 mm across y; `extra`
/// added to the slicing.
fn compile_boss(extra: &str) -> lmdc::pipeline::Compiled {
    let src = include_str!("../../examples/leaning_slab.lmd");
    let src = &src[..src.find("machine kr30").unwrap()];
    let x = [-HALF, HALF].map(|a| at(a, TOP)[0]);
    let src = src
        .replace(
            "place(rectangle(width = 24 mm, height = 20 mm), at = [2.0207 mm, 0 mm])",
            &format!(
                "place(rectangle(width = {} mm, height = 16 mm), at = [{} mm, 0 mm])",
                x[1] - x[0],
                (x[0] + x[1]) / 2.0
            ),
        )
        .replace("repair/worn_pad.ply", "boss.ply")
        .replace("repair/leaning_slab.stl", "boss.stl")
        .replace(
            "direction = auto  //",
            &format!("{extra}\n  direction = auto  //"),
        );
    let files = BTreeMap::from([
        ("boss.ply".to_string(), ply()),
        (
            "boss.stl".to_string(),
            super::target::extruded_stl(&section(), [-20.0, 20.0]),
        ),
    ]);
    compile(&src, files)
}

fn program(extra: &str) -> Program {
    let c = compile_boss(extra);
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    p.ir().clone()
}

/// Levelled along the lean (`level = auto`): the level is the scan's
/// highest point along the lean under the tracks; every layer above it a
/// plane square to the lean, the last ending on the target's end at 22 mm
/// along it; the levelling passes' thicknesses the bead's; every bead's
/// middle in the target and above the worn face; the volume laid the fill
/// between the worn face and the target's, integrated here, within 3 %.
#[test]
fn a_worn_leaning_boss_is_levelled_square_to_its_lean() {
    let p = program("level = auto");
    let (d, _) = axes();
    for l in &p.layers {
        assert!(
            l.frame.z.iter().zip(d).all(|(a, b)| (a - b).abs() < 1e-6),
            "{:?}",
            l.frame
        );
    }
    let first = p
        .layers
        .iter()
        .position(|l| l.on_plate)
        .expect("levelling passes, then the regular layers");
    assert!(first >= 1, "{first}");
    let on = |l: &lmdc::ir::Layer| -> Vec<([f64; 3], f64, f64)> {
        l.paths
            .iter()
            .flat_map(|p| &p.points)
            .filter(|q| q.laser_on)
            .map(|q| (q.pos, f64::from(q.layer_height), f64::from(q.pitch)))
            .collect()
    };
    // The regular layers: each at one height along the lean.
    let mut level = None;
    for (i, l) in p.layers[first..].iter().enumerate() {
        let along: Vec<f64> = on(l).iter().map(|(q, _, _)| dot(*q, d)).collect();
        let lo = along.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = along.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            hi - lo < 1e-3,
            "layer {i} above the level: {lo}..{hi} along the lean"
        );
        level.get_or_insert(lo);
        if i + first == p.layers.len() - 1 {
            for (q, h, _) in on(l) {
                assert!((dot(q, d) + h - TOP).abs() < 1e-3, "{q:?} + {h}");
            }
        }
    }
    // The level: the worn face's highest point under the tracks along the
    // lean, at most the unworn face's.
    let level = level.unwrap();
    let mut highest = f64::NEG_INFINITY;
    for (q, _, pitch) in on(&p.layers[first]) {
        let [a, y, _] = boss(q);
        for k in [-0.5, 0.0, 0.5] {
            highest = highest.max(worn(a, y + k * pitch));
        }
    }
    assert!(
        level <= FACE - SKIN && (level - highest).abs() < 0.05,
        "{level} {highest}"
    );
    // The levelling passes: the bead's heights over the strips its tracks
    // fill, 0.545 to 1.229 mm on 2 mm strips (docs/repair.md,
    // *Levelling*: the same bead), a little more on narrower ones.
    for l in &p.layers[..first] {
        for (q, h, pitch) in on(l) {
            assert!(
                (0.5..=1.3).contains(&h),
                "levelling {h} mm at {q:?} (pitch {pitch})"
            );
        }
    }
    let moves = super::moves(&p);
    assert!(moves.len() > 100);
    for (a, b, h, _) in &moves {
        let mid = [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0 + d[k] * h / 2.0);
        let [x, y, u] = boss(mid);
        assert!(in_target(mid, 0.02), "{mid:?} is not in the target");
        assert!(u > worn(x, y), "{mid:?} is under the worn face");
    }
    let planned: f64 = moves
        .iter()
        .map(|(a, b, h, pitch)| {
            let m = [0, 1, 2].map(|k| b[k] - a[k]);
            let along = dot(m, d);
            let run = (0..3)
                .map(|k| (m[k] - along * d[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            run * h * pitch
        })
        .sum();
    let fill = fill(&p.layers[first]);
    assert!(
        (planned / fill - 1.0).abs() < 0.03,
        "planned {planned} mm³ against the fill's {fill} mm³"
    );
}

/// The footprint is the boss's end seen from above (20.78 by 16 mm, its
/// end square to the lean): seen along the lean, the lines through it are
/// the boss's whole section, 24 by 16 mm. Every regular layer's tracks end
/// half a bead inside its flanks across the lean, and the outermost lie
/// at ±6.8 mm, 2 mm apart from the middle of a 16 mm stretch of it.
#[test]
fn the_end_seen_from_above_is_the_boss_s_section_along_its_lean() {
    let p = program("level = auto");
    let half_bead = 1.2;
    let first = p
        .layers
        .iter()
        .position(|l| l.on_plate)
        .expect("levelling passes, then the regular layers");
    assert!(p.layers.len() - first >= 2, "{} layers", p.layers.len());
    for l in &p.layers[first..] {
        let [a, y] = extent(l, |_| 0.0);
        for (end, want) in a.into_iter().zip([-HALF + half_bead, HALF - half_bead]) {
            assert!(
                (end - want).abs() < 0.01,
                "tracks end at {a:?} across the lean"
            );
        }
        // Tracks 2 mm apart over 16 mm less a bead: ±6.8 mm.
        assert!(
            (y[0] + 6.8).abs() < 1e-6 && (y[1] - 6.8).abs() < 1e-6,
            "outermost tracks at {y:?}"
        );
    }
}

/// The extent of `layer`'s laser-on points across the lean and along y,
/// each point's `y` widened by `half(point)` either way.
fn extent(layer: &lmdc::ir::Layer, half: impl Fn(&lmdc::ir::Point) -> f64) -> [[f64; 2]; 2] {
    let (mut a, mut y) = (
        [f64::INFINITY, f64::NEG_INFINITY],
        [f64::INFINITY, f64::NEG_INFINITY],
    );
    for q in layer
        .paths
        .iter()
        .flat_map(|p| &p.points)
        .filter(|q| q.laser_on)
    {
        let [qa, qy, _] = boss(q.pos);
        let h = half(q);
        a = [a[0].min(qa), a[1].max(qa)];
        y = [y[0].min(qy - h), y[1].max(qy + h)];
    }
    [a, y]
}

/// The fill over the tracks of `layer`: across the lean from the tracks'
/// first to last point, along y over their strips, from the worn face to
/// the target's (on a 0.05 mm grid).
fn fill(layer: &lmdc::ir::Layer) -> f64 {
    let [a, y] = extent(layer, |q| f64::from(q.pitch) / 2.0);
    let cell = 0.05;
    let (na, ny) = (
        ((a[1] - a[0]) / cell) as usize,
        ((y[1] - y[0]) / cell) as usize,
    );
    let (ca, cy) = ((a[1] - a[0]) / na as f64, (y[1] - y[0]) / ny as f64);
    let mut v = 0.0;
    for i in 0..na {
        for j in 0..ny {
            let (qa, qy) = (a[0] + (i as f64 + 0.5) * ca, y[0] + (j as f64 + 0.5) * cy);
            v += (TOP - worn(qa, qy)) * ca * cy;
        }
    }
    v
}

/// A level declared below the worn face's unworn skin: refused, the point
/// named in the part (on the worn face, found here from its formula) and
/// the heights along the lean.
#[test]
fn a_level_under_the_worn_end_is_refused_at_a_point_of_the_part() {
    let c = compile_boss("level = 9 mm");
    assert!(c.program.is_none());
    let (m, point) = super::refused_at(&c, "lmd::repair-level", "the scanned surface at (");
    assert!(
        m.contains("planned along the build direction tilted 30° toward 0° from +x")
            && m.contains("above the level 9 mm"),
        "{m}"
    );
    let [a, y, u] = boss([point[0], point[1], point[2]]);
    assert!(a.abs() <= HALF && y.abs() <= 8.0, "{point:?}");
    assert!(
        (u - worn(a, y)).abs() < 0.1,
        "{point:?} is {u} along the lean, the worn face {}",
        worn(a, y)
    );
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let n = |v: [f64; 3]| dot(v, v).sqrt();
    (dot(a, b) / n(a) / n(b))
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// `follow = surface` along the lean: the first layer's nozzle tilts from
/// the lean as the worn face's normal does (its slope from the formula),
/// toward the same side, wherever the whole tilt from vertical is within
/// the head's 35°; where the end slopes farther toward +x the nozzle is
/// held at 35° from vertical, never beyond.
#[test]
fn following_the_worn_end_along_the_lean_keeps_to_the_head_s_tilt() {
    let p = program("follow = surface");
    let (d, e) = axes();
    let (mut free, mut held, mut most) = (0, 0, 0.0f64);
    for q in p.layers[0].paths.iter().flat_map(|p| &p.points) {
        if !q.laser_on {
            continue;
        }
        let n = q.normal.map(f64::from);
        let whole = angle(n, [0.0, 0.0, 1.0]);
        assert!(whole <= 35.0 + 1e-3, "{whole}° at {:?}", q.pos);
        let [a, y, _] = boss(q.pos);
        // The face u = worn(a, y): its normal (−∂u/∂a, −∂u/∂y, 1).
        let g = fitted_slope(a, y);
        let normal = [0, 1, 2].map(|k| -g[0] * e[k] + d[k] - if k == 1 { g[1] } else { 0.0 });
        if angle(normal, [0.0, 0.0, 1.0]) < 34.0 {
            free += 1;
            // 0.7° at worst each way: the scan rastered, turned and
            // rastered again.
            let off = [angle(n, normal), (angle(n, d) - angle(normal, d)).abs()];
            assert!(
                off[0] < 1.0 && off[1] < 0.75,
                "{n:?} at {:?}: the face's normal {normal:?}",
                q.pos
            );
        } else if angle(normal, [0.0, 0.0, 1.0]) > 36.0 {
            // The slope fitted over a bead is a little less than the
            // formula's at a point: near the limit, held at it.
            held += 1;
            assert!(whole > 34.0, "{whole}° at {:?}", q.pos);
            most = most.max(whole);
        }
    }
    assert!(free > 20 && held > 20, "{free} followed, {held} held");
    assert!(most > 35.0 - 1e-3, "the steepest {most}°");
}

/// A track that a refusal names is named where its line along the lean
/// enters the boss: on the end, its middle across the lean (not at the
/// height of the end's highest point, 6 mm higher there).
#[test]
fn a_refused_track_is_named_on_the_boss_s_sloping_end() {
    let c = compile_boss("segments {\n    tolerance = 0.0001 mm\n    min_length = 20 mm\n  }");
    let (m, q) = super::refused_at(&c, "lmd::segments-too-short", "mm track through (");
    let [a, _, u] = boss([q[0], q[1], q[2]]);
    assert!((u - TOP).abs() < 1e-3 && a.abs() < 0.05, "{q:?}: {m}");
}

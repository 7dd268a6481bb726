//! `follow = surface` on a wall on a scan (docs/repair.md, *A wall on a
//! scan*): a rib on the shaft of examples/shaft_pad.lmd (radius 40 mm,
//! along x), along the shaft at y = 10 mm and then across its crown, each
//! layer `i` of `N` laid with the nozzle along the normal of `z = B +
//! (i/N)·(43 mm − B)`, the shaft's slope scaled by `1 − i/N`, computed
//! here from the formula: across the bead on the first leg, along it on
//! the second.

use super::{compile, messages};
use lmdc::ir::{PathKind, Program};
use std::collections::BTreeMap;

const RADIUS: f64 = 40.0;

/// examples/shaft_pad.lmd with its pad replaced by a one-bead rib, with
/// or without `follow = surface`.
fn rib(follow: bool) -> String {
    let src = include_str!("../../examples/shaft_pad.lmd");
    let from = src.find("extrude pad {").unwrap();
    let to = src.find("process {").unwrap();
    let rib = format!(
        "wall rib {{
  along = polyline(points = [[-15 mm, 10 mm], [0 mm, 10 mm], [0 mm, -11 mm]])
  bead = b316
  ends = lead(length = 3 mm)
  on = scan(file = \"repair/shaft_pad.ply\", units = mm, cell = 1 mm)
  top = 43 mm
}}

slicing variable {{
  layers = auto
  {}
}}

",
        if follow { "follow = surface" } else { "" }
    );
    let mut out = src.to_string();
    out.replace_range(from..to, &rib);
    out
}

fn plan(src: &str) -> Program {
    let bytes = std::fs::read("examples/repair/shaft_pad.ply").unwrap();
    let files = BTreeMap::from([("repair/shaft_pad.ply".to_string(), bytes)]);
    let c = compile(src, files);
    let m = messages(&c);
    c.program.unwrap_or_else(|| panic!("{m}")).into_ir()
}

/// The shaft's normal at `y` with its slope scaled by `weight`.
fn analytic(y: f64, weight: f64) -> [f64; 3] {
    let g = weight * y / (RADIUS * RADIUS - y * y).sqrt();
    let len = (1.0 + g * g).sqrt();
    [0.0, g / len, 1.0 / len]
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot: f64 = (0..3).map(|i| a[i] * b[i]).sum();
    dot.clamp(-1.0, 1.0).acos().to_degrees()
}

/// Every laser-on point of the beads: (layer, position, unit normal,
/// layer height).
fn deposits(p: &Program) -> Vec<(usize, [f64; 3], [f64; 3], f64)> {
    let mut out = Vec::new();
    for (i, l) in p.layers.iter().enumerate() {
        for path in l.paths.iter().filter(|p| p.kind == PathKind::Wall) {
            for q in path.points.iter().filter(|q| q.laser_on) {
                let n = q.normal.map(f64::from);
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                out.push((i, q.pos, n.map(|v| v / len), f64::from(q.layer_height)));
            }
        }
    }
    out
}

/// Every bead point's nozzle is the shaft's normal scaled by `1 − i/N`
/// within 0.25° (the scan's noise through a plane fitted over a bead's
/// width), turned across the shaft on both legs; the first layer's tilt
/// reaches the shaft's slope at y = 10 mm (14.5°); the last layer's
/// height along its normal, read vertically, ends at 43 mm; each lead
/// keeps its bead end's nozzle; and both machines' programs pass every
/// rule. Without `follow`, every nozzle is vertical.
#[test]
fn a_rib_on_the_shaft_follows_its_normal_back_to_vertical() {
    let p = plan(&rib(true));
    let n = p.layers.len();
    assert!(n >= 3, "{n} layers");
    let mut worst = 0.0f64;
    let mut first_most = 0.0f64;
    for (i, pos, normal, h) in deposits(&p) {
        let want = analytic(pos[1], 1.0 - i as f64 / n as f64);
        worst = worst.max(angle(normal, want));
        assert!(normal[0].abs() < 0.005, "{pos:?}: {normal:?}");
        if i == 0 {
            first_most = first_most.max(angle(normal, [0.0, 0.0, 1.0]));
        }
        if i + 1 == n {
            let top = pos[2] + h / normal[2];
            assert!((top - 43.0).abs() < 1e-3, "{pos:?}: {top}");
        }
    }
    assert!(worst < 0.25, "{worst}° off the shaft's normal");
    let edge = (10.0 / (RADIUS * RADIUS - 100.0).sqrt())
        .atan()
        .to_degrees();
    assert!((first_most - edge).abs() < 0.25, "{first_most} vs {edge}");
    for l in &p.layers {
        for w in l.paths.windows(2) {
            if w[0].kind == PathKind::Lead && w[1].kind == PathKind::Wall {
                assert_eq!(w[0].points[1].normal, w[1].points[0].normal);
            }
        }
    }
    let plain = plan(&rib(false));
    assert!(deposits(&plain).iter().all(|d| d.2 == [0.0, 0.0, 1.0]));
}

/// Levelled first (`level = 40.5 mm`, half a millimetre over the crown):
/// the first pass lies on the scan with
/// the nozzle along the shaft's own normal within 0.25°, and the regular
/// layers above the level are laid vertical.
#[test]
fn a_levelled_rib_on_the_shaft_tilts_its_passes_only() {
    // The crown's flanks fall 1.2 mm over a 4.6 mm two-pass stretch:
    // segments a bead long hold it within 0.3 mm, not 0.1.
    let src = rib(true).replace(
        "layers = auto",
        "level = 40.5 mm\n  segments { tolerance = 0.3 mm }",
    );
    let p = plan(&src);
    let first = p.layers.iter().position(|l| l.on_plate).unwrap();
    assert!(first >= 1, "no pass");
    let mut tilted = 0;
    for (i, pos, normal, _) in deposits(&p) {
        if i == 0 {
            let a = angle(normal, analytic(pos[1], 1.0));
            assert!(a < 0.25, "{pos:?}: {a}°");
            tilted += usize::from(normal[2] < 0.999);
        } else if i >= first {
            assert_eq!(normal, [0.0, 0.0, 1.0], "layer {i} at {pos:?}");
        }
    }
    assert!(tilted > 10, "{tilted} tilted points on the first pass");
}

/// Levelled along the normal with a bead whose heights span 2 % (0.8201
/// .. 0.8334 mm at the wall's pitch): where the rib turns across the
/// shaft at (0, 10) mm the scan slopes 14.48° along it, and the thinnest
/// pass along the normal, `0.8201 / cos 14.48°`, stands taller than the
/// bead lays: refused there (`lmd::follow-surface`), with no `scan` to
/// turn the tracks in the help (a wall's tracks follow its path).
#[test]
fn a_levelled_rib_too_steep_for_its_bead_along_the_normal_is_refused_where() {
    let src = rib(true)
        .replace(
            "layers = auto",
            "level = 40.5 mm\n  segments { tolerance = 0.3 mm }",
        )
        .replace(
            "model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)",
            "model = linear(slope = -0.003 mm / (1 mm/s), intercept = 1.1 mm)",
        );
    let bytes = std::fs::read("examples/repair/shaft_pad.ply").unwrap();
    let files = BTreeMap::from([("repair/shaft_pad.ply".to_string(), bytes)]);
    let c = compile(&src, files);
    let d = super::diagnostic(&c, "lmd::follow-surface");
    let m = &d.message;
    assert!(m.contains("along the scan's normal at (0, 10) mm"), "{m}");
    // The slope fitted to the scan, within 0.25° of the shaft's 14.48°.
    let alpha = (10.0 / (RADIUS * RADIUS - 100.0).sqrt()).atan();
    let slope = super::number_after(m, "the scan slopes ", '°');
    assert!((slope - alpha.to_degrees()).abs() < 0.25, "{m}");
    let thinnest = super::number_after(m, "the thinnest pass is ", ' ');
    assert!((thinnest - 0.8201 / alpha.cos()).abs() < 0.002, "{m}");
    assert!(thinnest > super::number_after(m, "more than the ", ' '));
    assert!(!d.help.as_deref().unwrap().contains("`scan`"));
}

/// Levelled at 40.5 mm with a bead of 0.7636 .. 0.807 mm a layer: the
/// 2.5 mm from the level to the top takes neither 3 layers nor 4. The
/// error speaks of the rise from the level (not of the scan), and its
/// help names the flat tops a count reaches from it, not `level = auto`:
/// each of them builds in that many regular layers.
#[test]
fn a_levelled_rib_whose_rise_no_count_reaches_is_told_from_its_level() {
    let src = |top: &str| {
        rib(false)
            .replace("layers = auto", "level = 40.5 mm")
            .replace("top = 43 mm", &format!("top = {top}"))
            .replace(
                "model = linear(slope = -0.135 mm / (1 mm/s), intercept = 1.82 mm)",
                "model = linear(slope = -0.01 mm / (1 mm/s), intercept = 1.1 mm)",
            )
    };
    let files = || {
        let bytes = std::fs::read("examples/repair/shaft_pad.ply").unwrap();
        BTreeMap::from([("repair/shaft_pad.ply".to_string(), bytes)])
    };
    let c = compile(&src("43 mm"), files());
    let d = super::diagnostic(&c, "lmd::no-layer-count");
    assert!(
        d.message
            .starts_with("from the level 40.5 mm the wall's regular layers rise 2.5 mm .. 2.5 mm"),
        "{}",
        d.message
    );
    let help = d.help.clone().unwrap();
    assert!(!help.contains("level = auto"), "{help}");
    let lo = super::number_after(&help, "a top from ", ' ');
    let hi = super::number_after(&help, &format!("a top from {lo} to "), ' ');
    let count = super::number_after(&help, "mm (", ' ');
    for top in [lo, hi] {
        let p = plan(&src(&format!("{top} mm")));
        let first = p.layers.iter().position(|l| l.on_plate).unwrap();
        assert_eq!((p.layers.len() - first) as f64, count, "top {top}: {help}");
    }
}

//! The blade-tip repair (examples/blade_tip.lmd): the profile is the
//! scanned blade's section below the wear, the wear is levelled up to the
//! tip's highest point and the blade built past its designed tip, on a
//! robot with a positioner. The blade's shape and wear are the formulas of
//! examples/repair/make_blade_tip.py, written out again here.

use super::{check_levelled, compile, messages};
use lmdc::geometry::mesh::Placement;
use lmdc::geometry::scan::{self, section};
use std::collections::BTreeMap;

fn camber(x: f64) -> f64 {
    3.0 * (1.0 - (x / 20.0).powi(2))
}

fn half(x: f64) -> f64 {
    let s = (x + 20.0) / 40.0;
    0.9 + 2.1 * (4.0 * s * (1.0 - s)).powf(0.75)
}

/// The worn tip's height over `x` (the edges' half circles take their
/// end's).
fn worn(x: f64) -> f64 {
    let s = (x.clamp(-20.0, 20.0) + 20.0) / 40.0;
    40.0 - 0.4 - 1.2 * ((s - 0.45) / 0.55).powi(2)
}

/// The blade's outline, finely: its sides every 0.05 mm of chord and its
/// edges' half circles every 5°.
fn outline() -> Vec<[f64; 2]> {
    let xs: Vec<f64> = (0..=800).map(|i| -20.0 + 0.05 * f64::from(i)).collect();
    let mut out: Vec<[f64; 2]> = xs.iter().rev().map(|&x| [x, camber(x) + half(x)]).collect();
    let arc = |c: f64, from: f64| {
        (1..36).map(move |k| {
            let a = from + std::f64::consts::PI * f64::from(k) / 36.0;
            [c + 0.9 * a.cos(), camber(c) + 0.9 * a.sin()]
        })
    };
    out.extend(arc(-20.0, std::f64::consts::FRAC_PI_2));
    out.extend(xs.iter().map(|&x| [x, camber(x) - half(x)]));
    out.extend(arc(20.0, -std::f64::consts::FRAC_PI_2));
    out
}

fn area(l: &[[f64; 2]]) -> f64 {
    (0..l.len())
        .map(|i| {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// How far `p` is from the loop `l`.
fn distance(l: &[[f64; 2]], p: [f64; 2]) -> f64 {
    (0..l.len())
        .map(|i| {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let t = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]))
                .clamp(0.0, 1.0);
            (a[0] + t * d[0] - p[0]).hypot(a[1] + t * d[1] - p[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether `p` is inside `l` (even-odd).
fn inside(l: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut odd = false;
    for i in 0..l.len() {
        let (a, b) = (l[i], l[(i + 1) % l.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) > p[0]
        {
            odd = !odd;
        }
    }
    odd
}

/// The example's scan of the blade, read, and placed where it was
/// scanned.
fn scanned() -> (scan::Raw, scan::Pose) {
    let bytes = std::fs::read("examples/repair/blade_tip.ply").unwrap();
    let raw = scan::ply::read(&bytes).unwrap();
    let pose = scan::Pose::from(Placement {
        scale: 1.0,
        turn: [0.0; 3],
        at: [0.0; 3],
    });
    (raw, pose)
}

/// The scan's section 36 mm up is the blade's outline: one island, no
/// holes, every point within the scan's noise (0.02 mm a coordinate) and
/// the sides' polygon (0.5 mm chords) of the outline, the same area
/// within 0.5 %.
#[test]
fn the_scanned_blades_section_is_its_outline() {
    let (raw, pose) = scanned();
    let cut = section::cut(&raw, &pose, 36.0).unwrap();
    assert_eq!(cut.len(), 1);
    assert!(cut[0].holes.is_empty());
    let want = outline();
    for &p in &cut[0].outline {
        assert!(distance(&want, p) < 0.1, "{p:?}: {}", distance(&want, p));
    }
    let (got, want) = (cut[0].area(), area(&want));
    assert!((got / want - 1.0).abs() < 0.005, "{got} vs {want} mm²");
}

/// The plan: every track's centre inside the blade at least half a bead
/// from its side (`size = outer`); the wear levelled from the scanned tip
/// up to the highest point under the tracks, then flat layers to 40.5 mm
/// ([`check_levelled`]).
#[test]
fn the_blade_tip_is_levelled_then_built_past_its_tip() {
    let bytes = std::fs::read("examples/repair/blade_tip.ply").unwrap();
    let files = BTreeMap::from([("repair/blade_tip.ply".to_string(), bytes)]);
    let c = compile(include_str!("../../examples/blade_tip.lmd"), files);
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    let p = p.ir();
    let blade = outline();
    let mut highest = f64::NEG_INFINITY;
    for q in p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
    {
        let xy = [q.pos[0], q.pos[1]];
        assert!(inside(&blade, xy), "{xy:?} outside the blade");
        // Half the 1.2 mm bead, less the scan's noise in the section.
        assert!(distance(&blade, xy) >= 0.6 - 0.06, "{xy:?}");
        highest = highest.max(worn(xy[0]));
    }
    // The regular layers are flat: the level is the first of them.
    let flat = |l: &lmdc::ir::Layer| {
        let z0 = l.paths[0].points[0].pos[2];
        l.paths
            .iter()
            .flat_map(|p| &p.points)
            .all(|q| (q.pos[2] - z0).abs() < 1e-6)
    };
    let first_flat = (0..p.layers.len())
        .find(|&i| p.layers[i..].iter().all(flat))
        .unwrap();
    let level = p.layers[first_flat].paths[0].points[0].pos[2];
    // `auto`: the scanned tip's highest point under the tracks (noise
    // 0.02 mm, a few of them high).
    assert!((level - highest).abs() < 0.08, "level {level} vs {highest}");
    let (passes, laid) = check_levelled(p, |x, _| worn(x), level, 40.5, 0.08);
    assert_eq!(passes, first_flat);
    // The wear under the tracks is up to 1.2 mm deep against beads of at
    // most 0.6 mm: two passes and more.
    assert!(passes >= 2, "{passes}");
    assert!(laid > 0.0);
}

/// The blade tip's finish held (`finish_tolerance`, docs/repair.md, *The
/// finish held*): its trailing edge, 1.17 mm short, is refused at
/// 0.5 mm with the report's own worst place and the stock that would
/// keep the face above the design; at 1.2 mm the plan is the one without
/// a tolerance. Without one, it is a warning with the same place.
#[test]
fn the_blade_tips_short_trailing_edge_breaks_a_finish_tolerance() {
    let files = super::example_files(&["blade_tip.ply"]);
    let src = include_str!("../../examples/blade_tip.lmd");
    let held = |t: &str| {
        src.replace(
            "level = auto  // fill the wear up to the tip's highest point first\n",
            &format!("level = auto\n  finish_tolerance = {t}\n"),
        )
    };
    let (free, model) = crate::support::data::compile_with_files_and_model(src, files.clone());
    let m = messages(&free);
    let plan = free.program.unwrap_or_else(|| panic!("{m}"));
    let report = lmdc::report::Report::new(plan.machines().next().unwrap(), &model.unwrap(), None);
    let f = report.finish.as_ref().unwrap();
    assert!(f.below_mm > 1.1 && f.below_mm < 1.2, "{f:?}");
    // Without a tolerance, a warning gives the same place, short by more
    // than the bead's thinnest layer.
    let short = lmdc::units::short;
    let warned = free
        .diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::finish")
        .unwrap_or_else(|| panic!("{m}"));
    assert_eq!(warned.severity, lmdc::diag::Severity::Warning);
    let thinnest = plan.ir().limits.layer_height[0];
    assert!(f.below_mm > thinnest);
    assert!(
        warned.message.contains(&format!(
            "fall {} mm below the top at ({}, {}) mm, more than the thinnest layer the bead lays ({} mm)",
            short(f.below_mm),
            short(f.below_at[0]),
            short(f.below_at[1]),
            short(thinnest)
        )),
        "{}",
        warned.message
    );
    let tight = compile(&held("0.5 mm"), files.clone());
    assert!(tight.program.is_none());
    let d = tight
        .diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::finish")
        .unwrap_or_else(|| panic!("{}", messages(&tight)));
    let expected = format!(
        "falls {} mm below the top at ({}, {}) mm, more than the `finish_tolerance` of 0.5 mm",
        short(f.below_mm),
        short(f.below_at[0]),
        short(f.below_at[1])
    );
    assert!(d.message.contains(&expected), "{}\n{expected}", d.message);
    // The worst place is at the trailing edge, past 19 mm of the chord.
    assert!(f.below_at[0] > 19.0, "{f:?}");
    let stock = format!(
        "build to a `top` at least {} mm above the designed face",
        short(f.below_mm)
    );
    assert!(d.help.as_deref().unwrap().contains(&stock), "{:?}", d.help);
    let loose = compile(&held("1.2 mm"), files);
    let m = messages(&loose);
    let loose = loose.program.unwrap_or_else(|| panic!("{m}"));
    assert_eq!(
        serde_json::to_string(loose.ir()).unwrap(),
        serde_json::to_string(plan.ir()).unwrap()
    );
}

/// A section cut through the wear is warned of: at 39 mm the worn tip
/// (down to 38.4 mm at the trailing edge) leaves a section smaller than
/// the one 1 mm lower by more than 5 %, and the warning gives both areas
/// as the scan's own sections measure them; the example's cut at 36 mm,
/// below the wear, is not warned of.
#[test]
fn a_section_cut_through_the_wear_is_warned_of() {
    let (raw, pose) = scanned();
    let area = |z: f64| -> f64 {
        let cut = section::cut(&raw, &pose, z).unwrap();
        cut.iter().map(|s| s.area()).sum()
    };
    let (here, below) = (area(39.0), area(38.0));
    assert!(here < 0.95 * below, "{here} vs {below}");
    let files = || super::example_files(&["blade_tip.ply"]);
    let src = include_str!("../../examples/blade_tip.lmd");
    let warned = |c: &lmdc::pipeline::Compiled| {
        c.diagnostics
            .iter()
            .find(|d| d.message.contains("the cut may pass through the worn part"))
            .map(|d| d.message.clone())
    };
    assert_eq!(warned(&compile(src, files())), None);
    let at39 = src.replace("scan_section(z = 36 mm)", "scan_section(z = 39 mm)");
    let m = warned(&compile(&at39, files())).expect("warned");
    let short = |v: f64| format!("{}", (v * 10.0).round() / 10.0);
    assert!(
        m.contains(&format!("({} against {} mm²)", short(here), short(below))),
        "{m}"
    );
}

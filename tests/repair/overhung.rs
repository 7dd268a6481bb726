//! A scanned part that overhangs itself (docs/repair.md, *Undercuts*): a
//! boss leaning 30° toward +x, its end worn down to 10 mm, scanned with
//! the plate it stands on, to be built up along its lean to 13.5 mm. Seen
//! from above the scan is a height field: past the end's +x edge it drops
//! to the plate, and under that edge it shows the end's height where the
//! boss leans away and there is air. A line along a lesser tilt that
//! leaves the boss through its leaning face and passes under that edge
//! meets only the cliff the height field draws there: it must not count
//! as standing on the scan. Checked against the sections here, not
//! lmdc's mesh or scan.

use super::tilted::{shift, slab_input};
use super::{compile, messages};

/// The boss's lean from vertical toward +x, deg.
const LEAN: f64 = 30.0;

/// Its worn end and its finished end, mm.
const WORN: f64 = 10.0;
const TOP: f64 = 13.5;

/// How far its faces lean along x over `z`, mm.
fn lean(z: f64) -> f64 {
    z * LEAN.to_radians().tan()
}

/// The boss's x–z section up to `top` on a plate whose face is at
/// `plate` (counter-clockwise), its base 24 mm wide at z = 0.
fn section(top: f64, plate: f64) -> Vec<[f64; 2]> {
    vec![
        [-40.0, -1.0],
        [40.0, -1.0],
        [40.0, plate],
        [12.0 + lean(plate), plate],
        [12.0 + lean(top), top],
        [-12.0 + lean(top), top],
        [-12.0 + lean(plate), plate],
        [-40.0, plate],
    ]
}

/// The boss as scanned, a closed mesh (its faces show where it is): the
/// plate, and on it the boss up to its worn end.
fn scanned_boss() -> Vec<u8> {
    let plate = vec![[-40.0, -1.0], [40.0, -1.0], [40.0, 0.0], [-40.0, 0.0]];
    let boss = vec![
        [-12.0, 0.0],
        [12.0, 0.0],
        [12.0 + lean(WORN), WORN],
        [-12.0 + lean(WORN), WORN],
    ];
    super::target::prisms_stl(&[plate, boss], [-20.0, 20.0])
}

/// The file of [`super::tilted`]'s slab with the boss's scan and target:
/// a head whose A axis turns `a` either way, `direction` as given, the
/// footprint the finished end seen from above. The part as designed
/// stands on a flange 0.5 mm proud of the plate's scanned face, so that
/// vertical lines past the worn end leave the boss and meet the flange
/// again: an overhang.
fn boss(a: f64) -> lmdc::pipeline::Compiled {
    boss_on(a, "direction = auto", 0.5)
}

/// [`boss`] with `direction` as given, the plate as designed at `plate`.
fn boss_on(a: f64, direction: &str, plate: f64) -> lmdc::pipeline::Compiled {
    let src = include_str!("../../examples/worn_pad.lmd").replace(
        "scan(file = \"repair/worn_pad.ply\", units = mm, cell = 1 mm)",
        "scan(file = \"boss.stl\", units = mm, cell = 0.5 mm)",
    );
    let (src, mut files) = slab_input(a, direction, &src);
    let src = src.replace(
        &format!("at = [{} mm, 0 mm]", shift()),
        &format!("at = [{} mm, 0 mm]", lean(TOP)),
    );
    let stl = super::target::extruded_stl;
    files.insert("boss.stl".into(), scanned_boss());
    files.insert(
        "target.stl".into(),
        stl(&section(TOP, plate), [-20.0, 20.0]),
    );
    compile(&src, files)
}

/// Along a tilt short of the lean the lines past the worn end's edge pass
/// under it: the fill goes along the lean, every first-layer point stands
/// on the worn end, and every bead lies in the boss as designed above it.
/// (Counting the cliff as the scan, the search took 7°, and the first
/// layer ran over the air beside the boss.)
#[test]
fn a_boss_that_overhangs_its_own_scan_is_filled_along_its_lean() {
    check_along_the_lean(boss(35.0));
}

/// What [`a_boss_that_overhangs_its_own_scan_is_filled_along_its_lean`]
/// holds of `c`.
fn check_along_the_lean(c: lmdc::pipeline::Compiled) {
    let m = messages(&c);
    let v = c.program.unwrap_or_else(|| panic!("{m}"));
    let p = v.ir();
    let z = p.layers[0].frame.z;
    let (tilt, azimuth) = (z[2].acos().to_degrees(), z[1].atan2(z[0]).to_degrees());
    // Its lean to the hundredth: the scan's faces show that the lines
    // along it meet the worn end (a height field alone left 29°).
    assert!((tilt - 30.0).abs() < 1e-6, "{tilt}° toward {azimuth}°");
    assert!(azimuth.abs() < 1e-6, "{tilt}° toward {azimuth}°");
    let edge = 12.0 + lean(WORN);
    let first: Vec<_> = p.layers[0].paths.iter().flat_map(|p| &p.points).collect();
    assert!(first.len() > 50, "{}", first.len());
    for q in first {
        assert!(
            (q.pos[2] - WORN).abs() < 0.05,
            "{:?} is off the worn end",
            q.pos
        );
        // A twentieth of a bead (2.4 mm) is the outermost lines' slack.
        assert!(q.pos[0] < edge + 0.12, "{:?} is past the end's edge", q.pos);
    }
    for (a, b, h, _) in super::moves(p) {
        let mid = [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0 + z[k] * h / 2.0);
        let x = mid[0] - lean(mid[2]);
        assert!(
            mid[2] < TOP + 1e-6 && x.abs() <= 12.0,
            "{mid:?} is off the boss"
        );
        // Under the worn end the boss as designed is the boss as scanned.
        assert!(mid[2] > WORN, "{mid:?} is under the worn end");
    }
}

/// On a head that tilts 20°, the lean is out of reach: refused at a line
/// that passes under the worn end's edge, with the tilt that builds it.
/// The scan is a mesh: its faces show no step where the line comes under
/// the height field's cliff, only the boss over it (the lean itself
/// builds to the hundredth: 30°).
#[test]
fn under_the_edge_of_its_own_scan_is_no_ground_to_build_on() {
    let c = boss(20.0);
    assert!(c.program.is_none());
    let (m, at) = super::refused_at(&c, "lmd::top-height", "the line through (");
    assert!(
        m.contains("no build direction within 20° of vertical builds the target's overhangs")
            && m.contains("the scan's faces show no step there that the line meets in the open, so the part leans out over the line")
            && m.contains("the least tilt that builds every point is 30° toward 0°"),
        "{m}"
    );
    // Under the end's edge, in the air beside the boss.
    assert!(at[2] < WORN && at[0] > 12.0 + lean(at[2]), "{at:?}");
    assert!(at[0] < 12.0 + lean(WORN) + 0.5, "{at:?}");
}

/// With the part as designed on the plate as scanned, a vertical line past
/// the worn end leaves the boss and meets the plate 12 mm lower: the
/// target holds the scanned boss, so that gap is air beside it, not wear
/// under added metal. Laid from above, refused as an overhang, the point
/// past the end's edge and the underside on the boss's leaning face
/// named (before, the layers stood on the plate beside the boss); along
/// the lean, built as over the flange.
#[test]
fn air_under_the_boss_as_designed_is_no_wear_to_fill() {
    let c = boss_on(35.0, "", 0.0);
    assert!(c.program.is_none());
    let m = messages(&c);
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.message.contains("has an overhang over ("))
        .unwrap_or_else(|| panic!("{m}"));
    let number = |after: &str, until: char| super::number_after(&d.message, after, until);
    let x = number("overhang over (", ',');
    let under = number("a face of it runs at", 'm');
    assert!(x > 12.0 + lean(WORN), "{m}");
    // The boss's leaning face over x, to the target's sampling.
    assert!((under - (x - 12.0) / lean(1.0)).abs() < 0.05, "{m}");
    check_along_the_lean(boss_on(35.0, "direction = auto", 0.0));
}

//! Inclined walls: a cone's nozzle following its lean (`nozzle = wall`),
//! and the overhang rule (`lmd::overhang`) refusing a lean the bead cannot
//! carry, with the angle.

use lmdc::pipeline::{compile, Compiled};

const CONE: &str = include_str!("../examples/cone.lmd");

/// The half-angle of examples/cone.lmd: radius 40 → 20 mm over 40 mm.
fn half_angle() -> f64 {
    (20.0f64 / 40.0).atan()
}

fn messages(c: &Compiled) -> String {
    c.diagnostics
        .iter()
        .map(|d| d.message.clone())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first number before `°` after `after` in `m`.
fn degrees_after(m: &str, after: &str) -> f64 {
    let rest = &m[m.find(after).unwrap_or_else(|| panic!("{after:?} in {m}")) + after.len()..];
    rest[..rest.find('°').unwrap()].trim().parse().unwrap()
}

#[test]
fn the_cone_nozzle_tilts_by_its_half_angle() {
    let c = compile(CONE, &mut ());
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    let alpha = half_angle();
    let dz = 40.0 / ir.layers.len() as f64;
    let mut n = 0;
    for l in &ir.layers {
        for p in l.paths.iter().flat_map(|p| &p.points) {
            let [x, y, z] = p.normal.map(f64::from);
            // Tilted from the spine (z) by the half-angle, inward: toward
            // the axis, as the wall leans in.
            let tilt = z.acos();
            assert!(
                (tilt - alpha).abs() < 1e-4,
                "{} vs {}",
                tilt.to_degrees(),
                alpha.to_degrees()
            );
            let radial = x * p.pos[0] + y * p.pos[1];
            assert!(radial < 0.0, "the nozzle leans out, not in");
            // What the bead stacks along the tilted nozzle: Δz / cos α.
            assert!((p.layer_height as f64 - dz / alpha.cos()).abs() < 1e-4);
            n += 1;
        }
    }
    assert!(n > 1000);
}

#[test]
fn a_vertical_nozzle_on_the_cone_overhangs_by_its_half_angle() {
    let src = CONE.replace("  nozzle = wall", "  // nozzle = wall");
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let m = messages(&c);
    let lean = degrees_after(&m, "the wall leans out");
    // Measured to the chords of the layer below (0.05 mm chord error).
    assert!((lean - half_angle().to_degrees()).abs() < 0.2, "{m}");
    assert!(m.contains("more than the 10° `max_overhang` allows"), "{m}");
    let help = c
        .diagnostics
        .iter()
        .filter_map(|d| d.help.clone())
        .collect::<String>();
    assert!(
        help.contains("`nozzle = wall`") && help.contains("turn the part"),
        "{help}"
    );
}

#[test]
fn without_max_overhang_a_lean_that_lands_builds() {
    // 26.6° with a vertical nozzle: each 0.89 mm layer steps 0.44 mm, well
    // within the ¾ bead (3 mm) lmd::stacking holds it to; nothing else
    // limits the lean.
    let vertical = CONE
        .replace("  nozzle = wall", "")
        .replace("  max_overhang = 10 deg", "");
    let c = compile(&vertical, &mut ());
    assert!(c.program.is_some(), "{}", messages(&c));
    // The same cone with a limit under its lean is refused, naming both.
    let limited = CONE
        .replace("  nozzle = wall", "")
        .replace("max_overhang = 10 deg", "max_overhang = 26 deg");
    let c = compile(&limited, &mut ());
    let m = messages(&c);
    assert!(
        (degrees_after(&m, "the wall leans out") - half_angle().to_degrees()).abs() < 0.2,
        "{m}"
    );
    assert!(m.contains("more than the 26° `max_overhang` allows"), "{m}");
}

#[test]
fn auto_layers_on_the_cone_count_along_the_nozzle() {
    assert!(CONE.contains("layers = auto"));
    let c = compile(CONE, &mut ());
    let m = messages(&c);
    let ir = c.program.unwrap_or_else(|| panic!("{m}")).into_ir();
    // The slant from the loft's radii (40 → 20 mm) and height (40 mm).
    let slant = (40.0f64).hypot(40.0 - 20.0);
    // The most the bead lays one bead wide: the mass balance at its slowest
    // speed, A = feed·efficiency/(density·v), over the 4 mm width.
    let h_max = (20.0 / 60.0) * 0.5 / (7.9e-3 * 5.0) / 4.0;
    let n = (slant / h_max).ceil() as usize;
    assert_eq!(ir.layers.len(), n, "{slant} / {h_max}");
    // Each point lays the slant's share along the nozzle (the last layer's
    // height is the step from the one below, the same on a cone).
    for l in &ir.layers {
        for p in l.paths.iter().flat_map(|p| &p.points) {
            let h = f64::from(p.layer_height);
            assert!(
                (h - slant / n as f64).abs() < 2e-3,
                "layer {}: {h}",
                l.index
            );
        }
    }
}

/// examples/cone.lmd with a vertical nozzle and no `max_overhang`, widened
/// to a 120 mm base over a 20 mm spine so that its wall leans `deg` from
/// the vertical: its top radius is `60 − 20·tan(deg)` mm.
fn vertical_cone(deg: f64) -> String {
    let top = 2.0 * (60.0 - 20.0 * deg.to_radians().tan());
    CONE.replace("circle(diameter = 80 mm)", "circle(diameter = 120 mm)")
        .replace(
            "circle(diameter = 40 mm)",
            &format!("circle(diameter = {top:.4} mm)"),
        )
        .replace("line(length = 40 mm)", "line(length = 20 mm)")
        .replace("  nozzle = wall ", "  // nozzle = wall ")
        .replace("  max_overhang = 10 deg", "  // max_overhang = 10 deg")
}

fn warnings(c: &Compiled) -> Vec<&lmdc::diag::Diagnostic> {
    c.diagnostics
        .iter()
        .filter(|d| d.code == lmdc::diag::Code::Overhang)
        .collect()
}

/// Issue 33: cones leaning 45°, 50° and 63.4° (a rise of 2 a run) with a
/// vertical nozzle built without a word unless the file set
/// `max_overhang`. Now each is warned with its lean (measured to the chords
/// of the layer below, so up to the 0.05 mm chord error over the layer's
/// height more), and still builds.
#[test]
fn a_vertical_nozzle_on_a_cone_leaning_past_45_degrees_is_warned() {
    for deg in [45.0, 50.0, 2f64.atan().to_degrees()] {
        let c = compile(&vertical_cone(deg), &mut ());
        let m = messages(&c);
        assert!(c.program.is_some(), "{deg}°: {m}");
        let w = warnings(&c);
        assert_eq!(w.len(), 1, "{deg}°: {m}");
        assert_eq!(w[0].severity, lmdc::diag::Severity::Warning);
        let lean = degrees_after(&w[0].message, "the wall leans out");
        // 19 layers of 20/19 mm: the chord error adds at most 0.05 mm.
        let h = 20.0 / 19.0;
        let most = (h * deg.to_radians().tan() + 0.05).atan2(h).to_degrees();
        assert!(lean >= deg - 0.1 && lean <= most + 0.1, "{deg}°: {lean}");
        assert!(
            w[0].message
                .contains("more than the 45° a layer may lean without `max_overhang`"),
            "{}",
            w[0].message
        );
        let help = w[0].help.clone().unwrap_or_default();
        assert!(
            help.contains("`nozzle = wall`")
                && help.contains("`mill5` tilts")
                && help.contains(&format!("`max_overhang = {} deg`", lean.ceil())),
            "{help}"
        );
    }
    // Under 45° nothing is said.
    let c = compile(&vertical_cone(40.0), &mut ());
    assert!(
        c.program.is_some() && warnings(&c).is_empty(),
        "{}",
        messages(&c)
    );
}

/// The overhang warning's helps, followed: the nozzle along the wall lays
/// the 50° cone without a lean (at 63.4° the tilted head meets the plate,
/// lmd::collision); `max_overhang` at the lean it names accepts it in
/// silence, and under it makes it an error.
#[test]
fn the_overhang_warnings_helps_build() {
    let src = vertical_cone(50.0);
    let c = compile(&src, &mut ());
    let help = warnings(&c)[0].help.clone().unwrap_or_default();
    let at = help.find("`max_overhang = ").unwrap() + "`".len();
    let written = &help[at..at + help[at..].find('`').unwrap()];
    let wall = src.replace("  // nozzle = wall ", "  nozzle = wall ");
    let c = compile(&wall, &mut ());
    assert!(
        c.program.is_some() && warnings(&c).is_empty(),
        "{}",
        messages(&c)
    );
    let allowed = src.replace("  // max_overhang = 10 deg", &format!("  {written}"));
    let c = compile(&allowed, &mut ());
    assert!(
        c.program.is_some() && warnings(&c).is_empty(),
        "{}",
        messages(&c)
    );
    let refused = src.replace("  // max_overhang = 10 deg", "  max_overhang = 48 deg");
    let c = compile(&refused, &mut ());
    assert!(c.program.is_none(), "{}", messages(&c));
    assert!(messages(&c).contains("more than the 48° `max_overhang` allows"));
}

/// Without `max_overhang`, a step of more than half a bead is warned on a
/// layer thick enough that it leans less than 45°: the 40 mm cone of
/// examples/cone.lmd (26.6°) with a 2 mm bead whose layers are about
/// 2.1 mm, so each steps about 1.05 mm, past the 1 mm half bead and short
/// of the 1.5 mm lmd::stacking refuses.
#[test]
fn a_step_of_more_than_half_a_bead_is_warned() {
    let src = CONE
        .replace("width = 4 mm", "width = 2 mm")
        .replace("  nozzle = wall ", "  // nozzle = wall ")
        .replace("  max_overhang = 10 deg", "  // max_overhang = 10 deg");
    let c = compile(&src, &mut ());
    let m = messages(&c);
    assert!(c.program.is_some(), "{m}");
    let w = warnings(&c);
    assert_eq!(w.len(), 1, "{m}");
    let (step, h) = (
        number_after(&w[0].message, "a step of "),
        number_after(&w[0].message, " mm on a "),
    );
    assert!(step > 1.0 && step < 1.5, "{m}");
    // The limit there: half the bead over the layer's height.
    let limit = degrees_after(&w[0].message, "more than the");
    let expect = (1.0f64).atan2(h).to_degrees();
    assert!(
        (limit - expect).abs() < 0.06 && limit < 45.0,
        "{limit} vs {expect}: {m}"
    );
    assert!(w[0].message.contains("a step of half the 2 mm bead"), "{m}");
}

/// The first number after `after` in `m`.
fn number_after(m: &str, after: &str) -> f64 {
    let rest = &m[m.find(after).unwrap_or_else(|| panic!("{after:?} in {m}")) + after.len()..];
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(rest.len());
    rest[..end].parse().unwrap()
}

/// examples/cone.lmd's nozzle follows its wall, 26.6° from vertical on the
/// 5-axis head and the robot alike. Without the bead's `tilt` (a bead
/// measured vertical) each machine is warned with that tilt; the help's
/// `tilt` covers it and builds in silence; a table machine keeps the
/// nozzle vertical and is not warned.
#[test]
fn a_bead_measured_vertical_is_warned_on_the_tilted_cone() {
    let tilt = |c: &Compiled| -> Vec<lmdc::diag::Diagnostic> {
        c.diagnostics
            .iter()
            .filter(|d| d.code == lmdc::diag::Code::BeadTilt)
            .cloned()
            .collect()
    };
    assert!(CONE.contains("  tilt = 0 deg .. 30 deg\n"));
    let c = compile(CONE, &mut ());
    assert!(
        c.program.is_some() && tilt(&c).is_empty(),
        "{}",
        messages(&c)
    );
    let vertical = CONE.replace("  tilt = 0 deg .. 30 deg\n", "");
    let c = compile(&vertical, &mut ());
    assert!(c.program.is_some(), "{}", messages(&c));
    let w = tilt(&c);
    assert_eq!(w.len(), 2, "{}", messages(&c));
    for (d, machine) in w.iter().zip(["mill5", "kr30"]) {
        assert_eq!(d.severity, lmdc::diag::Severity::Warning);
        assert!(
            d.message.contains(&format!("machine `{machine}` tilts")),
            "{}",
            d.message
        );
        let deg = number_after(&d.message, "tilts the nozzle ");
        assert!(
            (deg - half_angle().to_degrees()).abs() < 0.06,
            "{}",
            d.message
        );
        let help = d.help.clone().unwrap_or_default();
        assert!(help.contains("`tilt = 0 deg .. 27 deg`"), "{help}");
    }
    let followed = CONE.replace("  tilt = 0 deg .. 30 deg\n", "  tilt = 0 deg .. 27 deg\n");
    let c = compile(&followed, &mut ());
    assert!(
        c.program.is_some() && tilt(&c).is_empty(),
        "{}",
        messages(&c)
    );
    // Up to 5° beyond what was measured passes: 22° covers 26.6°.
    let near = CONE.replace("  tilt = 0 deg .. 30 deg\n", "  tilt = 0 deg .. 22 deg\n");
    assert!(tilt(&compile(&near, &mut ())).is_empty());
    let far = CONE.replace("  tilt = 0 deg .. 30 deg\n", "  tilt = 0 deg .. 21 deg\n");
    assert_eq!(tilt(&compile(&far, &mut ())).len(), 2);
}

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

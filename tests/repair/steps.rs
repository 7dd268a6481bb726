//! A repair in steps (docs/repair.md, *Repairs in steps*): a cap that
//! flares 30° out on both sides of a post 16 mm wide, worn off down to the
//! post's top at z = 20 mm, to be built up to z = 30 mm. Each lip
//! overhangs the other way, so no one direction builds the cap. In steps:
//! the middle from above, then each lip along its flare on a scan of the
//! part as the steps before left it. The scans are meshes: their faces
//! show that the middle's side is a step of the part, where a height
//! field alone shows a cliff that may hide an overhang. The geometry is
//! tests/cases/repair/cap_lip's; the checks here are against the sections
//! written below, not lmdc's mesh or scan.

use super::{compile, messages};
use lmdc::ir::Program;
use std::collections::BTreeMap;

/// The post's half width, its worn top (where the flare starts) and the
/// cap's top, mm.
const HALF: f64 = 8.0;
const WORN: f64 = 20.0;
const TOP: f64 = 30.0;

/// The scans' cell, mm: a height field places a step to within half of it.
const CELL: f64 = 0.5;

/// How far the flare leans out from vertical, deg.
const FLARE: f64 = 30.0;

/// The cap's half width at `z` (mm) over the flare.
fn rim(z: f64) -> f64 {
    HALF + (z - WORN).max(0.0) * FLARE.to_radians().tan()
}

/// The part as designed in x–z, counter-clockwise: a plate to z = 0, the
/// post, and the cap flaring out of it to its top.
fn designed() -> Vec<[f64; 2]> {
    vec![
        [-40.0, -10.0],
        [40.0, -10.0],
        [40.0, 0.0],
        [HALF, 0.0],
        [HALF, WORN],
        [rim(TOP), TOP],
        [-rim(TOP), TOP],
        [-HALF, WORN],
        [-HALF, 0.0],
        [-40.0, 0.0],
    ]
}

/// The part as scanned: the plate and the post up to `top`, and the lips
/// already built (`-1`: the -x lip).
fn scanned(top: f64, lips: &[i32]) -> Vec<[f64; 2]> {
    let mut s = vec![[-40.0, -10.0], [40.0, -10.0], [40.0, 0.0], [HALF, 0.0]];
    if lips.contains(&1) {
        s.extend([[HALF, WORN], [rim(TOP), TOP]]);
    } else {
        s.push([HALF, top]);
    }
    if lips.contains(&-1) {
        s.extend([[-rim(TOP), TOP], [-HALF, WORN]]);
    } else {
        s.push([-HALF, top]);
    }
    s.extend([[-HALF, 0.0], [-40.0, 0.0]]);
    s
}

/// [`scanned`] as convex pieces: the plate, the post up to `top`, the
/// lips already built.
fn scanned_pieces(top: f64, lips: &[i32]) -> Vec<Vec<[f64; 2]>> {
    let mut p = vec![
        vec![[-40.0, -10.0], [40.0, -10.0], [40.0, 0.0], [-40.0, 0.0]],
        vec![[-HALF, 0.0], [HALF, 0.0], [HALF, top], [-HALF, top]],
    ];
    for &side in lips {
        let s = f64::from(side);
        // A thousandth into the post: two closed pieces that overlap, as
        // one solid (sharing the post's corner, its edge would have four
        // faces).
        let inner = HALF - 1e-3;
        let lip = vec![[s * inner, WORN], [s * rim(TOP), TOP], [s * inner, TOP]];
        // Counter-clockwise in x–z, as every piece.
        p.push(if side > 0 {
            lip
        } else {
            lip.into_iter().rev().collect()
        });
    }
    p
}

/// The scan of the part after the steps that built up to `top` and
/// `lips`: a closed mesh, as a scan whose faces show a step must be.
fn scan_stl(top: f64, lips: &[i32]) -> Vec<u8> {
    super::target::prisms_stl(&scanned_pieces(top, lips), [-20.0, 20.0])
}

/// The case's file with its footprint from `x0` to `x1` (the top seen
/// from above), on `scan` (its bytes), the part as designed as its target.
fn step(x0: f64, x1: f64, scan: Vec<u8>, file: &str) -> lmdc::pipeline::Compiled {
    let src = include_str!("../cases/repair/cap_lip/input.lmd")
        .replace(
            "place(rectangle(width = 5.7735 mm, height = 20 mm), at = [-10.88675 mm, 0 mm])",
            &format!(
                "place(rectangle(width = {} mm, height = 20 mm), at = [{} mm, 0 mm])",
                x1 - x0,
                (x0 + x1) / 2.0
            ),
        )
        .replace("\"middle_built.stl\"", &format!("\"{file}\""));
    let stl = super::target::extruded_stl;
    let files = BTreeMap::from([
        (file.to_string(), scan),
        ("cap.stl".to_string(), stl(&designed(), [-20.0, 20.0])),
    ]);
    compile(&src, files)
}

/// The layers' build direction: its tilt and azimuth, deg.
fn direction(p: &Program) -> [f64; 2] {
    let z = p.layers[0].frame.z;
    [z[2].acos().to_degrees(), z[1].atan2(z[0]).to_degrees()]
}

/// Whether `(x, z)` is in the section `s` (crossings of a ray along +x).
fn inside(s: &[[f64; 2]], x: f64, z: f64) -> bool {
    let mut inside = false;
    for (k, a) in s.iter().enumerate() {
        let b = s[(k + 1) % s.len()];
        if (a[1] > z) != (b[1] > z) && x < a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    inside
}

/// Every bead's middle (half a layer along the build direction over the
/// middle of each move) in the part as designed, above what was scanned
/// (to within `tol` mm of it), and its x on the `side` of the post it is
/// built on (`0`: over it).
fn check_beads(p: &Program, scan: &[[f64; 2]], side: i32, tol: f64) {
    let z = p.layers[0].frame.z;
    let moves = super::moves(p);
    assert!(moves.len() > 5, "{}", moves.len());
    for (a, b, h, _) in moves {
        let m = [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0 + z[k] * h / 2.0);
        assert!(inside(&designed(), m[0], m[2]), "{m:?} is off the cap");
        let clear = [-tol, tol]
            .iter()
            .all(|dx| !inside(scan, m[0] + dx, m[2]) || !inside(scan, m[0] - dx, m[2]));
        assert!(clear, "{m:?} is in the part as scanned");
        match side {
            0 => assert!(m[0].abs() <= HALF + tol, "{m:?}"),
            s => assert!(m[0] * f64::from(s) >= HALF - tol, "{m:?}"),
        }
    }
}

/// `c`'s refusal for the target's overhangs (`lmd::top-height`): it must
/// be refused, and for that.
fn untilted(c: &lmdc::pipeline::Compiled) -> &lmdc::diag::Diagnostic {
    assert!(c.program.is_none());
    c.diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::top-height")
        .unwrap_or_else(|| panic!("{}", messages(c)))
}

/// Laid whole on the worn post, no direction builds the cap: the help
/// says to build it in steps, on a scan of what the steps before left.
#[test]
fn a_cap_flaring_both_ways_is_refused_whole_with_the_steps_help() {
    let c = step(-rim(TOP), rim(TOP), scan_stl(WORN, &[]), "worn.stl");
    let d = untilted(&c);
    assert!(
        d.message
            .contains("no direction within 85° of vertical builds every point"),
        "{}",
        d.message
    );
    let help = d.help.as_deref().unwrap_or_default();
    assert!(
        help.contains("build the part in steps")
            && help.contains("on a scan of the part as the steps before left it")
            && !help.contains("close no solid"),
        "{help}"
    );
}

/// The middle from above on the worn post; then each lip along its flare,
/// 30° toward it, on a mesh scan of the part as the steps before left it:
/// every bead in the cap as designed, out of the part as scanned, on its
/// own side of the post; each lip's first layer on the middle's side.
#[test]
fn the_middle_then_each_lip_on_a_scan_of_what_the_steps_before_left() {
    let worn = scanned(WORN, &[]);
    let c = step(-HALF, HALF, scan_stl(WORN, &[]), "worn.stl");
    let m = messages(&c);
    let middle = c.program.unwrap_or_else(|| panic!("{m}"));
    assert_eq!(direction(middle.ir())[0], 0.0);
    check_beads(middle.ir(), &worn, 0, 1e-6);
    for (side, lips, azimuth) in [(-1, vec![], 180.0), (1, vec![-1], 0.0)] {
        let scan = scanned(TOP, &lips);
        let (x0, x1) = if side < 0 {
            (-rim(TOP), -HALF)
        } else {
            (HALF, rim(TOP))
        };
        let c = step(x0, x1, scan_stl(TOP, &lips), "built.stl");
        let m = messages(&c);
        let lip = c.program.unwrap_or_else(|| panic!("lip {side}: {m}"));
        let [tilt, az] = direction(lip.ir());
        assert!(
            (tilt - FLARE).abs() < 1e-6,
            "lip {side}: {tilt}° toward {az}°"
        );
        assert!(
            (az.abs() - azimuth).abs() < 1e-6,
            "lip {side}: {tilt}° toward {az}°"
        );
        // The height field stands the middle's side within half a cell.
        check_beads(lip.ir(), &scan, side, CELL / 2.0);
        let first: Vec<_> = lip.ir().layers[0]
            .paths
            .iter()
            .flat_map(|p| &p.points)
            .collect();
        assert!(!first.is_empty());
        for q in first {
            assert!(
                (q.pos[0].abs() - HALF).abs() <= CELL / 2.0 && (WORN..=TOP).contains(&q.pos[2]),
                "lip {side}: {:?} is off the middle's side",
                q.pos
            );
        }
    }
}

/// The same scan as points only: seen from above, the middle's side is a
/// cliff that may hide an overhang, so no direction builds the lip, and
/// the help says a closed mesh would show the step.
#[test]
fn a_scan_of_points_cannot_show_the_step() {
    let mut points = Vec::new();
    for i in 0..=160 {
        for j in 0..=80 {
            let (x, y) = (-40.0 + f64::from(i) * 0.5, -20.0 + f64::from(j) * 0.5);
            points.push([x, y, if x.abs() <= HALF { TOP } else { 0.0 }]);
        }
    }
    let c = step(-rim(TOP), -HALF, super::ply(&points), "built.ply");
    let d = untilted(&c);
    let help = d.help.as_deref().unwrap_or_default();
    assert!(
        help.contains("this scan's faces close no solid (or it has none)")
            && help.contains(
                "a closed mesh of the part (a watertight STL, 3MF or PLY with faces) shows a step"
            ),
        "{help}"
    );
}

/// The rescan as an open surface, as a scanner sees the part from one
/// side (its faces the section's outline drawn along y, no ends): where
/// its faces close no solid they may join an overhang's edge to the floor
/// through air, so they are not asked, and the lip is refused as from
/// points.
#[test]
fn an_open_mesh_scan_cannot_show_the_step() {
    let open = super::target::extruded_stl(&scanned(TOP, &[]), [-20.0, 20.0]);
    let c = step(-rim(TOP), -HALF, open, "built.stl");
    let help = untilted(&c).help.as_deref().unwrap_or_default();
    assert!(help.contains("this scan's faces close no solid"), "{help}");
}

/// The rescan as a 3MF (in millimetres, its unit its own) plans the lip as
/// the STL of the same faces does.
#[test]
fn a_3mf_scan_plans_as_its_stl() {
    let (mut vertices, mut tris) = (Vec::new(), Vec::new());
    for t in super::target::prisms(&scanned_pieces(TOP, &[]), [-20.0, 20.0]) {
        let n = vertices.len();
        vertices.extend(t.map(|c| c.map(f64::from)));
        tris.push([n, n + 1, n + 2]);
    }
    let three_mf = crate::support::three_mf::package(&vertices, &tris, "millimeter", &[None]);
    let stl = scan_stl(TOP, &[]);
    let ir = |bytes: Vec<u8>, file: &str| {
        let c = step(-rim(TOP), -HALF, bytes, file);
        let m = messages(&c);
        let mut ir = c
            .program
            .unwrap_or_else(|| panic!("{file}: {m}"))
            .ir()
            .clone();
        for f in &mut ir.fixtures {
            if let lmdc::ir::FixtureShape::Mesh { file, .. } = &mut f.shape {
                *file = "scan".into();
            }
        }
        serde_json::to_string(&ir).unwrap()
    };
    assert!(ir(three_mf, "built.3mf") == ir(stl, "built.stl"));
}

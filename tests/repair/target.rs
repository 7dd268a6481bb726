//! A target given as a mesh (`top = mesh(…)`, docs/repair.md, *A target
//! mesh*): the part as designed, its highest face over each point the
//! finished surface. A box's flat top and a wedge's sloped one plan exactly
//! what the same top written as a height or a plane plans; a target that
//! does not cover the footprint is refused with where.

use super::{compile, messages};
use lmdc::ir::Program;
use std::collections::BTreeMap;

/// A binary STL of the block `lo`..`hi` whose top corners stand at
/// `top(x, y)` (a plane when `top` is linear).
pub(super) fn solid_stl(lo: [f64; 3], hi: [f64; 3], top: impl Fn(f64, f64) -> f64) -> Vec<u8> {
    let c = |i: usize| {
        let (x, y) = (
            if i & 1 == 1 { hi[0] } else { lo[0] },
            if i & 2 == 2 { hi[1] } else { lo[1] },
        );
        let z = if i & 4 == 4 { top(x, y) } else { lo[2] };
        [x as f32, y as f32, z as f32]
    };
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut b = vec![b' '; 80];
    b.extend(12u32.to_le_bytes());
    for q in quads {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            b.extend([0u8; 12]);
            for i in t {
                for v in c(i) {
                    b.extend(v.to_le_bytes());
                }
            }
            b.extend([0u8; 2]);
        }
    }
    b
}

/// examples/worn_pad.lmd with `top = …` as given, its scan and `target.stl`.
fn pad(top: &str, target: Vec<u8>) -> lmdc::pipeline::Compiled {
    let src = include_str!("../../examples/worn_pad.lmd").replace("top = 13 mm", top);
    let files = BTreeMap::from([
        (
            "repair/worn_pad.ply".to_string(),
            std::fs::read("examples/repair/worn_pad.ply").unwrap(),
        ),
        ("target.stl".to_string(), target),
    ]);
    compile(&src, files)
}

/// Every point's place, height and speed, layer by layer.
fn points(p: &Program) -> Vec<[f64; 5]> {
    p.layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
        .map(|q| {
            [
                q.pos[0],
                q.pos[1],
                q.pos[2],
                f64::from(q.layer_height),
                f64::from(q.speed),
            ]
        })
        .collect()
}

fn same(a: &Program, b: &Program) {
    let (a, b) = (points(a), points(b));
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(&b) {
        for k in 0..5 {
            // f32 corners: 13 mm and 0.5 % of 40 mm are exact in f32, the
            // plane's heights within a micrometre.
            assert!((p[k] - q[k]).abs() < 2e-4, "{p:?} vs {q:?}");
        }
    }
}

#[test]
fn a_boxs_flat_top_plans_what_the_height_plans() {
    let target = solid_stl([-40.0, -20.0, 0.0], [40.0, 20.0, 13.0], |_, _| 13.0);
    let by_mesh = pad("top = mesh(file = \"target.stl\")", target.clone());
    let by_height = pad("top = 13 mm", target);
    let (m, h) = (messages(&by_mesh), messages(&by_height));
    let (m, h) = (
        by_mesh.program.unwrap_or_else(|| panic!("{m}")),
        by_height.program.unwrap_or_else(|| panic!("{h}")),
    );
    same(m.ir(), h.ir());
}

#[test]
fn a_wedges_sloped_top_plans_what_the_plane_plans() {
    // 13 mm at x = 0, rising 0.5 % along x.
    let z = |x: f64, _: f64| 13.0 + 0.005 * x;
    let target = solid_stl([-40.0, -20.0, 0.0], [40.0, 20.0, 0.0], z);
    let by_mesh = pad("top = mesh(file = \"target.stl\")", target.clone());
    let plane = "top = plane(at = [0 mm, 0 mm], height = 13 mm, slope_x = 0.5 %, slope_y = 0)";
    let by_plane = pad(plane, target);
    let (m, p) = (messages(&by_mesh), messages(&by_plane));
    let (m, p) = (
        by_mesh.program.unwrap_or_else(|| panic!("{m}")),
        by_plane.program.unwrap_or_else(|| panic!("{p}")),
    );
    same(m.ir(), p.ir());
}

/// A target of the added metal alone, a slab from the pad's nominal face
/// (10 mm) to 13 mm: its underside stands over the wear, which it does
/// not hold, so the gap is filled down to the scan, and it plans exactly
/// what `top = 13 mm` plans. (A target that holds the scanned part is the
/// part as designed, and a gap under it is air: `repair::overhung`.)
#[test]
fn a_target_of_the_added_metal_alone_is_filled_down_over_the_wear() {
    let slab = solid_stl([-40.0, -20.0, 10.0], [40.0, 20.0, 13.0], |_, _| 13.0);
    let by_mesh = pad("top = mesh(file = \"target.stl\")", slab.clone());
    let by_height = pad("top = 13 mm", slab);
    let (m, h) = (messages(&by_mesh), messages(&by_height));
    let (m, h) = (
        by_mesh.program.unwrap_or_else(|| panic!("{m}")),
        by_height.program.unwrap_or_else(|| panic!("{h}")),
    );
    same(m.ir(), h.ir());
}

#[test]
fn a_target_that_misses_part_of_the_footprint_is_refused_with_where() {
    // The pad is 60 mm long; the target stops at x = 20 mm.
    let target = solid_stl([-40.0, -20.0, 0.0], [20.0, 20.0, 13.0], |_, _| 13.0);
    let c = pad("top = mesh(file = \"target.stl\")", target);
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains("lmd::top-height: the target mesh has no face over (2"),
        "{m}"
    );
}

/// A target with an overhang over the pad: a ledge sticking out at
/// 11..12 mm over x 10..20 mm (above the worn face, under the 13 mm top)
/// on a block standing on the part. Laid from above, the layers would
/// fill under the ledge: refused, naming the ledge's underside.
#[test]
fn a_target_with_an_overhang_is_refused_where_it_is() {
    let mut stl = solid_stl([-40.0, -20.0, 0.0], [40.0, 20.0, 10.5], |_, _| 10.5);
    let ledge = solid_stl([10.0, -20.0, 11.0], [20.0, 20.0, 13.0], |_, _| 13.0);
    // Two blocks in one file: 24 triangles.
    stl.extend_from_slice(&ledge[84..]);
    stl[80..84].copy_from_slice(&24u32.to_le_bytes());
    let c = pad("top = mesh(file = \"target.stl\")", stl);
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains("lmd::top-height: the target has an overhang over (1")
            && m.contains("a face of it runs at 11 mm"),
        "{m}"
    );
    // Under the ledge is a gap over the block: whichever way the layers
    // are laid, the ledge's underside stands on nothing.
    assert!(
        m.contains(
            "no build direction within 85° of vertical puts the underside here on metal below it"
        ),
        "{m}"
    );
}

/// A target whose overhang leans: a block to 10.5 mm with a wall on it,
/// 10 mm thick, leaning 40.5° toward +x up to 13 mm (the pad along y, its
/// faces extruded from the section in x–z). Over x 0..2.13 mm the wall
/// overhangs the block; the layers stand under it when their direction
/// tilts toward +x by more than its 40.5°, found to the degree above.
#[test]
fn a_leaning_overhang_is_refused_with_the_tilt_that_builds_it() {
    let lean = 40.5f64.to_radians().tan() * 2.5;
    let section = [
        [-40.0, 0.0],
        [40.0, 0.0],
        [40.0, 10.5],
        [0.0, 10.5],
        [lean, 13.0],
        [lean - 10.0, 13.0],
        [-10.0, 10.5],
        [-40.0, 10.5],
    ];
    let c = pad(
        "top = mesh(file = \"target.stl\")",
        extruded_stl(&section, [-20.0, 20.0]),
    );
    assert!(c.program.is_none());
    let m = messages(&c);
    let number = |after: &str, until: char| super::number_after(&m, after, until);
    let x = number("overhang over (", ',');
    assert!(x > 0.0 && x < lean, "{m}");
    assert_eq!(number("tilted ", '°'), 41.0, "{m}");
    assert_eq!(number("from vertical toward ", '°'), 0.0, "{m}");
    // What would plan it: the fill along a tilted direction, asked for.
    let help = c.diagnostics.iter().find_map(|d| d.help.clone()).unwrap();
    assert!(
        help.contains("`direction = auto` in `slicing variable`"),
        "{help}"
    );
}

/// The sides of a section in x–z (a closed polygon) extruded along y over
/// `y`, as triangles.
fn sides(section: &[[f64; 2]], y: [f64; 2]) -> Vec<[[f32; 3]; 3]> {
    let c = |p: [f64; 2], y: f64| [p[0] as f32, y as f32, p[1] as f32];
    let mut tris = Vec::new();
    for (k, a) in section.iter().enumerate() {
        let b = section[(k + 1) % section.len()];
        let q = [c(*a, y[0]), c(b, y[0]), c(b, y[1]), c(*a, y[1])];
        tris.push([q[0], q[1], q[2]]);
        tris.push([q[0], q[2], q[3]]);
    }
    tris
}

/// Triangles as a binary STL.
pub(super) fn stl_bytes(tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![b' '; 80];
    out.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        out.extend([0u8; 12]);
        for v in t.iter().flatten() {
            out.extend(v.to_le_bytes());
        }
        out.extend([0u8; 2]);
    }
    out
}

/// The faces of a section in x–z (a closed polygon) extruded along y over
/// `y`: a binary STL of its sides (the end caps, seen edge-on from above,
/// are left out: a target mesh need not be closed).
pub(super) fn extruded_stl(section: &[[f64; 2]], y: [f64; 2]) -> Vec<u8> {
    stl_bytes(&sides(section, y))
}

/// The triangles of convex x–z `pieces` (counter-clockwise) extruded
/// along `y` and closed at both ends: a solid, every edge shared by two
/// faces running it opposite ways (what a scan's faces must be to show a
/// step).
pub(super) fn prisms(pieces: &[Vec<[f64; 2]>], y: [f64; 2]) -> Vec<[[f32; 3]; 3]> {
    let c = |p: [f64; 2], y: f64| [p[0] as f32, y as f32, p[1] as f32];
    let mut tris = Vec::new();
    for section in pieces {
        tris.extend(sides(section, y));
        // The ends, fanned (the pieces are convex).
        for k in 1..section.len() - 1 {
            let [a, b, d] = [section[0], section[k], section[k + 1]];
            tris.push([c(a, y[0]), c(d, y[0]), c(b, y[0])]);
            tris.push([c(a, y[1]), c(b, y[1]), c(d, y[1])]);
        }
    }
    tris
}

/// [`prisms`] as a binary STL.
pub(super) fn prisms_stl(pieces: &[Vec<[f64; 2]>], y: [f64; 2]) -> Vec<u8> {
    stl_bytes(&prisms(pieces, y))
}

// A target given as a solid of the file (`top = NAME`, docs/repair.md, *A
// target solid*): the solid is not built, its highest surface over each
// point is the finished surface.

/// examples/worn_pad.lmd with `top = nominal` and `nominal`, the block
/// given (the part as designed), declared before the pad.
fn pad_on(nominal: &str) -> lmdc::pipeline::Compiled {
    let src = include_str!("../../examples/worn_pad.lmd")
        .replace("top = 13 mm", "top = nominal")
        .replace("extrude pad {", &format!("{nominal}\n\nextrude pad {{"));
    let files = BTreeMap::from([
        (
            "repair/worn_pad.ply".to_string(),
            std::fs::read("examples/repair/worn_pad.ply").unwrap(),
        ),
        (
            "target.stl".to_string(),
            solid_stl([-40.0, -20.0, 0.0], [40.0, 20.0, 13.0], |_, _| 13.0),
        ),
    ]);
    compile(&src, files)
}

/// Every program the plan's machines are written, less the line naming
/// the source and its hash.
fn programs(p: &lmdc::verify::Verified) -> BTreeMap<String, String> {
    let mut sink = lmdc::back::MemorySink::default();
    let templates = lmdc::back::Templates::builtin().unwrap();
    lmdc::pipeline::emit(p, &templates, &mut sink, &mut ()).unwrap();
    sink.files
        .into_iter()
        .map(|(n, b)| {
            let text = String::from_utf8(b).unwrap();
            let kept: Vec<&str> = text.lines().filter(|l| !l.contains("sha256")).collect();
            (n, kept.join("\n"))
        })
        .collect()
}

fn built(c: lmdc::pipeline::Compiled) -> lmdc::verify::Verified {
    let m = messages(&c);
    c.program.unwrap_or_else(|| panic!("{m}"))
}

/// A box declared as an extrusion of a rectangle to 13 mm or lofted
/// straight up 13 mm plans exactly what `top = 13 mm` plans: the same IR,
/// point for point, and the same programs; an extrusion of a box's mesh,
/// within float noise.
#[test]
fn a_box_solids_flat_top_plans_exactly_what_the_height_plans() {
    let by_height = built(pad("top = 13 mm", Vec::new()));
    let extruded = "extrude nominal {\n  profile = rectangle(width = 80 mm, height = 40 mm)\n  height = 13 mm\n}";
    let lofted = "loft nominal {\n  from = rectangle(width = 80 mm, height = 40 mm)\n  to = rectangle(width = 80 mm, height = 40 mm)\n  spine = line(length = 13 mm)\n}";
    for nominal in [extruded, lofted] {
        let by_solid = built(pad_on(nominal));
        assert_eq!(points(by_solid.ir()), points(by_height.ir()), "{nominal}");
        assert_eq!(programs(&by_solid), programs(&by_height), "{nominal}");
    }
    // A mesh's face is read within float noise, as `top = mesh(…)` is.
    let meshed = "extrude nominal {\n  profile = mesh(file = \"target.stl\")\n}";
    same(built(pad_on(meshed)).ir(), by_height.ir());
}

/// A box bent along an arc of 2 m through 0.5° stands on the plate and
/// leans toward +x: over the pad its top is its end section, tilted 0.5°.
/// It plans what that plane plans, within the programs' 0.001 mm.
#[test]
fn a_bent_lofts_tilted_end_plans_what_its_plane_plans() {
    let (r, a) = (2000.0_f64, 0.5_f64.to_radians());
    let (xc, zc) = (r - r * a.cos(), r * a.sin());
    let nominal = "loft nominal {\n  from = rectangle(width = 80 mm, height = 40 mm)\n  to = rectangle(width = 80 mm, height = 40 mm)\n  spine = arc(radius = 2000 mm, angle = 0.5 deg)\n}";
    let by_loft = built(pad_on(nominal));
    let plane = format!(
        "top = plane(at = [{xc:.12} mm, 0 mm], height = {zc:.12} mm, slope_x = {:.15}, slope_y = 0)",
        -a.tan()
    );
    let by_plane = built(pad(&plane, Vec::new()));
    let (l, p) = (points(by_loft.ir()), points(by_plane.ir()));
    assert_eq!(l.len(), p.len());
    for (a, b) in l.iter().zip(&p) {
        for k in 0..5 {
            assert!((a[k] - b[k]).abs() < 1e-4, "{a:?} vs {b:?}");
        }
    }
}

/// A target solid that stops short of the footprint is refused with where.
#[test]
fn a_target_solid_short_of_the_footprint_is_refused_with_where() {
    let nominal = "extrude nominal {\n  profile = place(rectangle(width = 60 mm, height = 40 mm), at = [-10 mm, 0 mm])\n  height = 13 mm\n}";
    let c = pad_on(nominal);
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains("lmd::top-height: the target solid `nominal` has no part over (2"),
        "{m}"
    );
}

/// A bar twisted half a turn over 13 mm: over the pad's ends a vertical
/// line is in it near the bottom and the top and out of it between (the
/// bar turned across), so the solid overhangs the scan there: refused,
/// naming its underside, 13·(1 − asin(1/3)/π) = 11.59 mm at x = 28.8 mm.
#[test]
fn a_target_solid_with_an_overhang_is_refused_where_it_is() {
    let nominal = "loft nominal {\n  from = rectangle(width = 80 mm, height = 20 mm)\n  to = rectangle(width = 80 mm, height = 20 mm)\n  spine = line(length = 13 mm)\n  twist = 180 deg\n}";
    let c = pad_on(nominal);
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains("lmd::top-height: the target solid `nominal` has an overhang over (")
            && m.contains("its underside runs at 1"),
        "{m}"
    );
}

/// Names that are no target: the extrusion itself, a bead, a wall, and a
/// typo (with the solid it is closest to, which is then not built).
#[test]
fn names_that_are_no_target_are_refused_with_what_works() {
    let itself = pad("top = pad", Vec::new());
    assert!(
        messages(&itself)
            .contains("lmd::target-solid: `top = pad` names the extrusion it is written in"),
        "{}",
        messages(&itself)
    );
    let bead = pad("top = b316", Vec::new());
    assert!(
        messages(&bead).contains("lmd::target-solid: `top = b316` names a bead, not a solid"),
        "{}",
        messages(&bead)
    );
    let src = include_str!("../../examples/worn_pad.lmd").replace("top = 13 mm", "top = nominl");
    let src = src.replace(
        "slicing variable {",
        "extrude nominal {\n  profile = rectangle(width = 80 mm, height = 40 mm)\n  height = 13 mm\n}\n\nslicing variable {",
    );
    let files = BTreeMap::from([(
        "repair/worn_pad.ply".to_string(),
        std::fs::read("examples/repair/worn_pad.ply").unwrap(),
    )]);
    let m = messages(&compile(&src, files));
    // `nominl` names no solid; `nominal`, the solid it is closest to, is
    // taken for the target and kept out of the build: the typo is the one
    // error, not a second part to build.
    assert_eq!(
        m.trim(),
        "lmd::unknown-name: there is no solid called `nominl`",
        "{m}"
    );
}

/// A top written with `sin` (docs/language.md, *Values, units and
/// expressions*): the worn pad built up to
/// `13 mm + 0.3 mm · sin(x / 30 mm · 180°)`, its last
/// layer ending on that formula (computed here) at every point; `sin` of
/// a plain number is refused for its units, where it is written.
#[test]
fn a_top_written_with_sin_ends_on_its_formula() {
    let src = |top: &str| {
        include_str!("../../examples/worn_pad.lmd").replace(
            "top = 13 mm                                         // the finished face",
            &format!("top = {top}  // the finished face"),
        )
    };
    let files = || super::example_files(&["worn_pad.ply"]);
    let c = compile(&src("13 mm + 0.3 mm * sin(x / 30 mm * 180 deg)"), files());
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    let last = p.ir().layers.last().unwrap();
    let mut n = 0;
    for q in last.paths.iter().flat_map(|p| &p.points) {
        let end = q.pos[2] + f64::from(q.layer_height);
        let f = 13.0 + 0.3 * (q.pos[0] / 30.0 * std::f64::consts::PI).sin();
        assert!((end - f).abs() < 1e-4, "{:?} ends at {end}, not {f}", q.pos);
        n += 1;
    }
    assert!(n > 20, "{n}");
    let c = compile(&src("13 mm + 0.3 mm * sin(x / 30 mm)"), files());
    let m = messages(&c);
    assert!(
        m.contains("lmd::unit-mismatch: `sin` takes an angle (deg), not a plain number"),
        "{m}"
    );
}

//! Registration to a solid of the file (`scan(register = NAME)`,
//! docs/repair.md, *Registration*): a worn block scanned on a fixture
//! that moved it, fitted to the block as designed — a loft the file
//! describes, not built — plans what the scan placed where it belongs
//! plans, with the fit an STL of the same block gives.

use super::{check_plan, compile, messages, ply};
use lmdc::ir::Registration;
use lmdc::pipeline::Compiled;
use nalgebra::{Rotation3, Vector3};
use std::collections::BTreeMap;

/// The block as designed: 44 × 28 mm at the plate, 40 × 24 mm at its top
/// 12 mm up (its sides lean in 1 in 6).
const DESIGN: &str = "loft design {
  from = rectangle(width = 44 mm, height = 28 mm)
  to = rectangle(width = 40 mm, height = 24 mm)
  spine = line(length = 12 mm)
}";

/// The half sides of the design at height `z`.
fn half(z: f64) -> [f64; 2] {
    [22.0 - z / 6.0, 14.0 - z / 6.0]
}

/// The worn top: the design's 12 mm, but for a trough 0.8 mm deep across
/// the block, 24 mm long about x = 2 mm (`(1 − u²)²`, flat to the design
/// beyond it).
fn worn(x: f64, _y: f64) -> f64 {
    let u = ((x - 2.0) / 12.0).clamp(-1.0, 1.0);
    12.0 - 0.8 * (1.0 - u * u).powi(2)
}

/// The fixture's move: 1° about z after 0.4° about x, then (0.9, −0.6,
/// 0.25) mm.
fn fixture() -> (Rotation3<f64>, Vector3<f64>) {
    let r = Rotation3::from_euler_angles(0.4f64.to_radians(), 0.0, 1f64.to_radians());
    (r, Vector3::new(0.9, -0.6, 0.25))
}

/// The worn block's scan every 0.5 mm, 0.02 mm of deterministic noise
/// along each face's normal: its top (40 × 24 mm: the repair's footprint,
/// 36 × 20 mm, and 2 mm round it) and its four leaning sides up to
/// 11.5 mm; moved by the fixture when `moved`.
fn scan(moved: bool) -> Vec<[f64; 3]> {
    let mut state = 0x5eed_u64;
    let mut noise = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.07
    };
    let mut pts = Vec::new();
    for j in 0..=48 {
        for i in 0..=80 {
            let (x, y) = (-20.0 + 0.5 * i as f64, -12.0 + 0.5 * j as f64);
            pts.push([x, y, worn(x, y) + noise()]);
        }
    }
    // A side's outward normal leans up by 1 in 6: (±6, 0, 1)/√37.
    let lean = 1.0 / 37f64.sqrt();
    for k in 1..=23 {
        let z = 0.5 * k as f64;
        let [a, b] = half(z);
        let (na, nb) = ((2.0 * a / 0.5) as usize, (2.0 * b / 0.5) as usize);
        for i in 0..=na {
            let x = -a + 0.5 * i as f64;
            for s in [-1.0, 1.0] {
                let e = noise();
                pts.push([x, s * (b + 6.0 * lean * e), z + lean * e]);
            }
        }
        for j in 0..=nb {
            let y = -b + 0.5 * j as f64;
            for s in [-1.0, 1.0] {
                let e = noise();
                pts.push([s * (a + 6.0 * lean * e), y, z + lean * e]);
            }
        }
    }
    if moved {
        let (r, t) = fixture();
        for p in &mut pts {
            let q = r * Vector3::from(*p) + t;
            *p = [q.x, q.y, q.z];
        }
    }
    pts
}

/// The design as a binary STL: its six faces, twelve triangles.
fn design_stl() -> Vec<u8> {
    let c = |i: usize| {
        let z = if i & 4 == 0 { 0.0 } else { 12.0 };
        let [a, b] = half(z);
        let x = if i & 1 == 0 { -a } else { a };
        let y = if i & 2 == 0 { -b } else { b };
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
    let tris: Vec<[[f32; 3]; 3]> = quads
        .iter()
        .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
        .collect();
    super::target::stl_bytes(&tris)
}

/// The repair: the worn block's top built up to `top` from the scan `on`,
/// with `design` declared beside it when `on` or `top` names it (it is
/// then not built: it has no bead).
fn source(on: &str, top: &str) -> String {
    let mut s = include_str!("../../examples/worn_pad.lmd")
        .replace(
            "rectangle(width = 60 mm, height = 20 mm)",
            "rectangle(width = 36 mm, height = 20 mm)",
        )
        .replace("top = 13 mm", &format!("top = {top}"));
    let from = s.find("on = scan(").unwrap();
    let to = from + s[from..].find(")\n").unwrap() + 1;
    s.replace_range(from..to, on);
    if on.contains("register = design") || top == "design" {
        s = s.replace("extrude pad {", &format!("{DESIGN}\n\nextrude pad {{"));
    }
    s
}

fn build(on: &str, top: &str, moved: bool) -> Compiled {
    let files = BTreeMap::from([
        ("worn.ply".to_string(), ply(&scan(moved))),
        ("design.stl".to_string(), design_stl()),
    ]);
    compile(&source(on, top), files)
}

const PLAIN: &str = r#"on = scan(file = "worn.ply", cell = 1 mm)"#;
const TO_SOLID: &str =
    r#"on = scan(file = "worn.ply", cell = 1 mm, register = design, fit_tolerance = 0.05 mm)"#;
const TO_STL: &str = r#"on = scan(file = "worn.ply", cell = 1 mm, register = mesh(file = "design.stl"), fit_tolerance = 0.05 mm)"#;

/// The scan's fit, from an accepted plan.
fn fit(c: &Compiled) -> Registration {
    let p = c
        .program
        .as_ref()
        .unwrap_or_else(|| panic!("{}", messages(c)));
    let scan = p.ir().fixtures.iter().find(|f| f.is_scan()).unwrap();
    scan.registration.clone().expect("registered")
}

/// The moved scan fitted to the loft `design` undoes the fixture's move
/// within 0.02 mm and 0.01°, leaves the scanner's noise (0.02 mm RMS) as
/// its residual, and plans the layers of the scan left where it was:
/// as many, the first on the worn top, the last ending at the top
/// (14.3 mm). `design` is not built (it has no bead). The same block as an
/// STL gives the same fit within a micrometre and 0.002°.
#[test]
fn a_scan_registered_to_a_loft_of_the_file_plans_as_placed() {
    let plain = build(PLAIN, "14.3 mm", false);
    let placed = plain
        .program
        .as_ref()
        .unwrap_or_else(|| panic!("{}", messages(&plain)));
    let reg = build(TO_SOLID, "14.3 mm", true);
    let r = fit(&reg);
    let (rot, shift) = fixture();
    let back = rot.inverse();
    let (x, y, z) = back.euler_angles();
    let undo = -(back * shift);
    for k in 0..3 {
        let turned = [x, y, z][k].to_degrees();
        assert!((r.turned[k] - turned).abs() < 0.01, "{r:?}");
        assert!((r.moved[k] - undo[k]).abs() < 0.02, "{r:?}");
    }
    assert!(r.rms > 0.015 && r.rms < 0.03, "{r:?}");
    assert_eq!(r.nominal, "design");
    let p = reg.program.as_ref().unwrap();
    assert_eq!(placed.ir().layers.len(), p.ir().layers.len());
    check_plan(p.ir(), worn, 14.3, 36.0, 20.0, [0.06; 2]);
    let stl = fit(&build(TO_STL, "14.3 mm", true));
    // Its triangles differ: a point nearest an edge takes the normal of
    // the face the search meets first.
    for k in 0..3 {
        assert!((stl.moved[k] - r.moved[k]).abs() < 1e-3, "{stl:?} {r:?}");
        assert!((stl.turned[k] - r.turned[k]).abs() < 2e-3, "{stl:?} {r:?}");
    }
    assert!((stl.rms - r.rms).abs() < 1e-3, "{stl:?} {r:?}");
    let report = lmdc::report::Report::of_plan(p.machines().next().unwrap());
    let text = lmdc::report::text::render(&report);
    assert!(
        text.contains("scan fit    the scan moved onto its nominal `design`"),
        "{text}"
    );
}

/// What `register = NAME` cannot name, each said with what would work:
/// the extrusion the scan is in, a bead, a name no solid has (with the
/// solid it may mean), a number, and a solid that builds on something of
/// its own (once, when both `top` and `register` name it), and a region
/// whose hole lies outside its outline.
#[test]
fn a_nominal_that_is_no_solid_of_the_part_is_refused() {
    let with = |name: &str| TO_SOLID.replace("register = design", &format!("register = {name}"));
    let own = build(&with("pad"), "design", true);
    let m = messages(&own);
    assert!(own.program.is_none());
    assert!(
        m.contains(
            "lmd::target-solid: `register = pad` names the extrusion its scan is written in"
        ),
        "{m}"
    );
    let bead = build(&with("b316"), "design", true);
    let m = messages(&bead);
    assert!(
        m.contains("lmd::target-solid: `register = b316` names a bead, not a solid"),
        "{m}"
    );
    let typo = build(&with("desgin"), "design", true);
    let m = messages(&typo);
    let d: Vec<_> = typo.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{m}");
    assert_eq!(d[0].message, "there is no solid called `desgin`");
    assert!(
        d[0].help.as_deref().unwrap_or("").contains("`design`"),
        "{:?}",
        d[0].help
    );
    let number = build(&with("5 mm"), "design", true);
    let m = messages(&number);
    assert!(
        m.contains("lmd::target-solid: `register` must be the part as designed: a `mesh(…)` or the name of a solid of the file"),
        "{m}"
    );
    let src = source(TO_SOLID, "14.3 mm").replace(
        "spine = line(length = 12 mm)\n}",
        "spine = line(length = 12 mm)\n  size = centre\n}",
    );
    let files = BTreeMap::from([("worn.ply".to_string(), ply(&scan(true)))]);
    let centre = compile(&src, files);
    let m = messages(&centre);
    assert!(
        m.contains("lmd::target-solid: the nominal `design` says `size = centre`"),
        "{m}"
    );
    // Named by `top` and by `register` both, it is read once: its
    // mistake is reported once, for the first field that names it.
    let src = source(TO_SOLID, "design").replace(
        "spine = line(length = 12 mm)\n}",
        "spine = line(length = 12 mm)\n  size = centre\n}",
    );
    let files = BTreeMap::from([("worn.ply".to_string(), ply(&scan(true)))]);
    let both = compile(&src, files);
    let m = messages(&both);
    assert_eq!(m.matches("says `size = centre`").count(), 1, "{m}");
    // A region whose hole lies outside its outline is refused as a built
    // extrusion's is: its faces would not be the part.
    let src = source(TO_SOLID, "14.3 mm").replace(
        DESIGN,
        "extrude design {\n  profile = region(outline = rectangle(width = 44 mm, height = 28 mm), holes = [place(circle(diameter = 4 mm), at = [60 mm, 0 mm])])\n  height = 12 mm\n}",
    );
    let files = BTreeMap::from([("worn.ply".to_string(), ply(&scan(true)))]);
    let holed = compile(&src, files);
    let m = messages(&holed);
    assert!(holed.program.is_none(), "{m}");
    assert!(
        m.contains("lmd::hole: hole 1 lies outside the outline"),
        "{m}"
    );
}

/// Two extrusions that name each other as the part as designed (`register
/// = NAME` both ways) leave nothing to build, and the error says so, with
/// both names, rather than that the file has no solid.
#[test]
fn solids_that_name_each_other_as_designed_are_named_in_the_error() {
    let src = r#"part p
bead b { width = 2 mm  speed = 4 mm/s .. 8 mm/s  model = linear(slope = -0.1 mm / (1 mm/s), intercept = 1.8 mm) }
extrude a { profile = rectangle(width = 10 mm, height = 10 mm)  bead = b  on = scan(file = "s.xyz", register = c)  top = 5 mm }
extrude c { profile = rectangle(width = 10 mm, height = 10 mm)  bead = b  on = scan(file = "s.xyz", register = a)  top = 5 mm }
slicing variable { layers = auto }
"#;
    let c = compile(src, BTreeMap::new());
    let m = messages(&c);
    assert!(
        m.contains("lmd::missing-solid: every solid of the file is named by another as the part as designed (`a`, `c`), so none is left to build"),
        "{m}"
    );
    assert!(!m.contains("does not describe a solid"), "{m}");
}

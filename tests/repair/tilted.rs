//! A target that overhangs the scan, filled along a tilted build
//! direction (`direction = auto`, docs/repair.md, *Undercuts*): a slab
//! leaning 30° toward +x on the worn pad. Seen from above, its leaning
//! face overhangs the block it stands on; along the least tilt that
//! builds it every line over the footprint meets it in one piece.

use super::{compile, messages};
use lmdc::ir::Program;
use std::collections::BTreeMap;

/// The slab's lean from vertical, deg.
pub(super) const LEAN: f64 = 30.0;

/// Its height over the block, mm (from z = 10 to 13.5).
pub(super) const HEIGHT: f64 = 3.5;

/// Its base's x, mm.
pub(super) const BASE: [f64; 2] = [-12.0, 12.0];

/// How far its top is shifted along x from its base, mm.
pub(super) fn shift() -> f64 {
    HEIGHT * LEAN.to_radians().tan()
}

/// The part as designed, in x–z (counter-clockwise): the block to 10 mm
/// and on it the slab leaning toward +x up to 13.5 mm.
fn section() -> Vec<[f64; 2]> {
    let s = shift();
    vec![
        [-40.0, 0.0],
        [40.0, 0.0],
        [40.0, 10.0],
        [BASE[1], 10.0],
        [BASE[1] + s, 10.0 + HEIGHT],
        [BASE[0] + s, 10.0 + HEIGHT],
        [BASE[0], 10.0],
        [-40.0, 10.0],
    ]
}

/// Whether `q` is in the part as designed (y within ±20 mm): the section
/// tested on its own, not through lmdc's mesh.
fn in_target(q: [f64; 3]) -> bool {
    let s = section();
    let (x, z) = (q[0], q[2]);
    let mut inside = false;
    for k in 0..s.len() {
        let (a, b) = (s[k], s[(k + 1) % s.len()]);
        if (a[1] > z) != (b[1] > z) && x < a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    inside && q[1].abs() <= 20.0
}

/// The worn pad's surface (examples/repair/make_worn_pad.py), without its
/// noise.
pub(super) fn worn(x: f64, y: f64) -> f64 {
    10.0 - 1.5 * (-((x - 5.0) / 15.0).powi(2)).exp() * (1.0 - (y / 14.0).powi(2))
}

/// The worn pad toward the leaning slab, its profile the slab's top seen
/// from above, on a 5-axis head whose A axis turns `a` either way and a
/// bead measured up to 35°; `direction` as given.
fn slab(a: f64, direction: &str) -> lmdc::pipeline::Compiled {
    slab_with(a, direction, include_str!("../../examples/worn_pad.lmd"))
}

/// [`slab`] from `src`, the worn pad's file as edited by the test.
fn slab_with(a: f64, direction: &str, src: &str) -> lmdc::pipeline::Compiled {
    let (src, files) = slab_input(a, direction, src);
    compile(&src, files)
}

/// The file and the files it reads of [`slab_with`].
pub(super) fn slab_input(
    a: f64,
    direction: &str,
    src: &str,
) -> (String, BTreeMap<String, Vec<u8>>) {
    let machines = src.find("machine mill3").unwrap();
    let head = format!(
        "machine mill5 {{
  kind = cnc
  head {{
    standoff = 15 mm
    nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm)
    body = cylinder(length = 100 mm, diameter = 60 mm)
  }}
  axes = 5
  kinematics = head_ac
  dialect = linuxcnc
  max_speed = 50 mm/s
  clearance = 5 mm
  limits {{
    a = -{a} deg .. {a} deg
    c = -30000 deg .. 30000 deg
  }}
}}
"
    );
    let width = BASE[1] - BASE[0];
    let src = format!("{}{head}", &src[..machines])
        .replace(
            "rectangle(width = 60 mm, height = 20 mm)",
            &format!(
                "place(rectangle(width = {width} mm, height = 20 mm), at = [{} mm, 0 mm])",
                shift()
            ),
        )
        .replace("top = 13 mm", "top = mesh(file = \"target.stl\")")
        .replace(
            "model = linear(",
            "tilt = 0 deg .. 35 deg\n  model = linear(",
        )
        .replace("offset = 2 mm", &format!("offset = 2 mm\n  {direction}"));
    let files = BTreeMap::from([
        (
            "repair/worn_pad.ply".to_string(),
            std::fs::read("examples/repair/worn_pad.ply").unwrap(),
        ),
        (
            "target.stl".to_string(),
            super::target::extruded_stl(&section(), [-20.0, 20.0]),
        ),
    ]);
    (src, files)
}

/// The slab on a head that turns 35° either way, `direction = auto`,
/// planned, with its checked model (for the report).
pub(super) fn slab_and_model() -> (lmdc::verify::Verified, lmdc::sema::model::Model) {
    let (src, files) = slab_input(
        35.0,
        "direction = auto",
        include_str!("../../examples/worn_pad.lmd"),
    );
    let (c, model) = crate::support::data::compile_with_files_and_model(&src, files);
    let m = messages(&c);
    let p = c.program.unwrap_or_else(|| panic!("{m}"));
    (p, model.unwrap())
}

/// Planned along the least tilt that builds it: 30° toward +x (the slab's
/// lean, to the degree; its faces leave the lines at the footprint's edge
/// less tilted); every point's nozzle and every layer's frame along it;
/// every bead's middle in the part as designed and above the scan; and
/// the volume laid is the fill's, integrated independently over the
/// lines along the direction through the tracks' extent, within 3 %.
#[test]
fn a_leaning_slab_is_filled_along_its_lean_on_a_tilting_head() {
    let vertical = slab(35.0, "");
    assert!(vertical.program.is_none());
    let m = messages(&vertical);
    assert!(
        m.contains("lmd::top-height") && m.contains("overhang"),
        "{m}"
    );
    let c = slab(35.0, "direction = auto");
    let m = messages(&c);
    let v = c.program.unwrap_or_else(|| panic!("{m}"));
    let p = v.ir();
    let tilt = LEAN.to_radians();
    let d = [tilt.sin(), 0.0, tilt.cos()];
    for l in &p.layers {
        assert!(
            l.frame.z.iter().zip(d).all(|(a, b)| (a - b).abs() < 1e-9),
            "{:?}",
            l.frame
        );
        for q in l.paths.iter().flat_map(|p| &p.points) {
            let along: f64 = q.normal.iter().zip(d).map(|(&a, b)| f64::from(a) * b).sum();
            assert!(along > 1.0 - 1e-6, "{:?}", q.normal);
        }
    }
    assert!(p.layers.len() >= 4, "{}", p.layers.len());
    let moves = super::moves(p);
    assert!(moves.len() > 100);
    for (a, b, h, _) in &moves {
        let mid = [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0 + d[k] * h / 2.0);
        assert!(in_target(mid), "{mid:?} is not in the target");
        assert!(mid[2] > worn(mid[0], mid[1]), "{mid:?} is under the scan");
    }
    let planned: f64 = moves
        .iter()
        .map(|(a, b, h, pitch)| {
            // A layer height along d over the ground its move covers
            // across d (a move on a layer sloped against d runs longer).
            let m = [0, 1, 2].map(|k| b[k] - a[k]);
            let along: f64 = (0..3).map(|k| m[k] * d[k]).sum();
            let run = (0..3)
                .map(|k| (m[k] - along * d[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            run * h * pitch
        })
        .sum();
    // The fill: points of the target above the scan whose line along d
    // meets the finished face (13.5 mm) where the tracks run: half a bead
    // in from the footprint's ends along x (measured across d), across y
    // as far as the tracks' strips reach.
    let half = 1.2 / tilt.cos();
    let x_face = [BASE[0] + shift() + half, BASE[1] + shift() - half];
    let fill = fill_along(x_face, tracks_across(p));
    assert!(
        (planned / fill - 1.0).abs() < 0.03,
        "planned {planned} mm³ against the fill's {fill} mm³"
    );
}

/// The fill along the lean, mm³: the points of the part as designed above
/// the worn surface's formula (on a 0.1 mm grid) whose line along the
/// lean meets the slab's face (13.5 mm) within `face` along x, across y
/// over `across` (the section is the same along y: the scan's depth is
/// integrated).
fn fill_along(face: [f64; 2], across: [f64; 2]) -> f64 {
    let tilt = LEAN.to_radians();
    let cell = 0.1;
    let mut fill = 0.0;
    for i in 0..700 {
        let x = -20.0 + (i as f64 + 0.5) * cell;
        for k in 0..70 {
            let z = 7.0 + (k as f64 + 0.5) * cell;
            let on_face = x + (10.0 + HEIGHT - z) * tilt.tan();
            if on_face < face[0] || on_face > face[1] || !in_target([x, 0.0, z]) {
                continue;
            }
            for j in 0..((across[1] - across[0]) / cell).round() as usize {
                let y = across[0] + (j as f64 + 0.5) * cell;
                if z > worn(x, y) {
                    fill += cell * cell * cell;
                }
            }
        }
    }
    fill
}

/// The y the tracks' strips cover: their outer centres and half their
/// pitch beyond.
fn tracks_across(p: &Program) -> [f64; 2] {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for q in p.layers[0].paths.iter().flat_map(|p| &p.points) {
        let half = f64::from(q.pitch) / 2.0;
        lo = lo.min(q.pos[1] - half);
        hi = hi.max(q.pos[1] + half);
    }
    [lo, hi]
}

/// A head whose A axis turns 20° either way cannot tilt the 30° the slab
/// needs: refused, with how far it tilts, what holds it there and the
/// least tilt that would build it.
#[test]
fn a_head_that_tilts_too_little_is_refused_with_the_tilt_needed() {
    let c = slab(20.0, "direction = auto");
    assert!(c.program.is_none());
    let m = messages(&c);
    assert!(
        m.contains(
            "lmd::top-height: no build direction within 20° of vertical builds the target's overhangs"
        ) && m.contains("the least tilt that builds every point is 30° toward 0° (")
            && m.contains("10° more than allowed"),
        "{m}"
    );
    let help = c.diagnostics.iter().find_map(|d| d.help.clone()).unwrap();
    assert!(help.contains("machine `mill5`'s tilt axis"), "{help}");
}

/// Levelled along the lean, the level is a plane square to it (the worn
/// pad's highest point along the lean): the slab's face, level in the
/// part, stands under it toward −x. Refused at `level`, the point named
/// on the slab's face (13.5 mm high) in the part, the heights along the
/// lean.
#[test]
fn levelling_the_slab_square_to_its_lean_is_refused_where_its_face_is_below() {
    let c = slab(35.0, "direction = auto\n  level = auto");
    assert!(c.program.is_none());
    let (m, point) = super::refused_at(&c, "lmd::repair-level", " at (");
    assert!(
        m.contains("planned along the build direction tilted 30° toward 0° from +x"),
        "{m}"
    );
    assert!((point[2] - (10.0 + HEIGHT)).abs() < 0.01, "{point:?}");
    assert!(point[0] < shift(), "{point:?}");
}

/// Where vertical builds the target, `direction = auto` plans exactly
/// what the file without it plans: a box's mesh on the worn pad, the IR
/// the same point for point.
#[test]
fn a_target_vertical_builds_is_planned_as_without_direction() {
    let plan = |direction: &str| {
        let src = include_str!("../../examples/worn_pad.lmd")
            .replace("top = 13 mm", "top = mesh(file = \"target.stl\")")
            .replace("offset = 2 mm", &format!("offset = 2 mm\n  {direction}"));
        let files = BTreeMap::from([
            (
                "repair/worn_pad.ply".to_string(),
                std::fs::read("examples/repair/worn_pad.ply").unwrap(),
            ),
            (
                "target.stl".to_string(),
                super::target::solid_stl([-40.0, -20.0, 0.0], [40.0, 20.0, 13.0], |_, _| 13.0),
            ),
        ]);
        let c = compile(&src, files);
        let m = messages(&c);
        c.program.unwrap_or_else(|| panic!("{m}"))
    };
    let (auto, vertical) = (plan("direction = auto"), plan(""));
    assert_eq!(auto.ir().layers, vertical.ir().layers);
}

/// A bead that lays only 0.84 .. 0.91 mm (6 to 6.5 mm/s, its tracks 2 mm
/// apart) cannot lay the slab's fill along its lean, 4.4 to 5.8 mm deep
/// along it: no whole number of layers fits both ends. The refusal comes from the planner in the
/// frame turned so the lean is up, and names where the fill is deepest and
/// shallowest as points of the part: each on the slab's face (13.5 mm
/// high) within its outline seen from above, and the depth it prints
/// there is the depth along the lean down to the worn surface, found here
/// from the surface's formula.
#[test]
fn a_refusal_of_the_tilted_plan_names_its_points_in_the_part() {
    let src = include_str!("../../examples/worn_pad.lmd")
        .replace("speed = 4 mm/s .. 8.7 mm/s", "speed = 6 mm/s .. 6.5 mm/s");
    let c = slab_with(35.0, "direction = auto", &src);
    assert!(c.program.is_none());
    let m = messages(&c);
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::no-layer-count")
        .unwrap_or_else(|| panic!("{m}"));
    assert!(
        d.message
            .contains("planned along the build direction tilted 30° toward 0° from +x"),
        "{}",
        d.message
    );
    let label = d
        .labels
        .iter()
        .find_map(|l| l.text.strip_prefix("where the tracks run: "))
        .unwrap_or_else(|| panic!("{:?}", d.labels));
    let named = depths_at(label);
    assert_eq!(named.len(), 2, "{label}");
    let tilt = LEAN.to_radians();
    let s = shift();
    for (depth, p) in &named {
        assert!((p[2] - (10.0 + HEIGHT)).abs() < 1e-3, "{label}");
        assert!(
            (BASE[0] + s..=BASE[1] + s).contains(&p[0]) && p[1].abs() <= 10.0,
            "{label}"
        );
        // Down the lean from p to the worn surface, bisected.
        let below = |t: f64| p[2] - t * tilt.cos() < worn(p[0] - t * tilt.sin(), p[1]);
        let (mut lo, mut hi) = (0.0, 20.0);
        for _ in 0..60 {
            let mid = (lo + hi) / 2.0;
            if below(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        assert!(
            (depth - lo).abs() < 0.06,
            "{label}: {depth} mm printed at {p:?}, {lo} mm down the lean to the surface"
        );
    }
    assert!(named[0].0 > named[1].0 + 1.0, "{label}");
}

/// The depths and points of "5.7 mm at (x, y, z) mm, 4 mm at (x, y, z) mm".
fn depths_at(label: &str) -> Vec<(f64, [f64; 3])> {
    let number = |s: &str| s.trim().trim_end_matches("mm").trim().parse::<f64>();
    label
        .split(") mm")
        .filter_map(|part| {
            let (depth, point) = part.split_once(" at (")?;
            let depth = number(depth.trim_start_matches(',')).ok()?;
            let xyz: Vec<f64> = point
                .split(", ")
                .map(number)
                .collect::<Result<_, _>>()
                .ok()?;
            Some((depth, xyz.try_into().ok()?))
        })
        .collect()
}

/// The report's design volume of the slab filled along its lean is the
/// fill over the whole footprint seen along the lean: the points of the
/// part as designed above the worn surface's formula whose line along the
/// lean meets the slab's face (13.5 mm) within its outline seen from
/// above, counted here on a 0.1 mm grid, within 0.6 % (0.2 % apart).
/// Integrated from above (the face less the surface over the outline),
/// the trough's depth is paired with other places: 1.3 % more.
#[test]
fn the_report_integrates_the_design_volume_along_the_lean() {
    let (p, model) = slab_and_model();
    let r = lmdc::report::Report::new(p.machines().next().unwrap(), &model, None);
    let v = r.design_volume().expect("the design volume along the lean");
    let face = [BASE[0] + shift(), BASE[1] + shift()];
    let fill = fill_along(face, [-10.0, 10.0]);
    let cell = 0.1;
    // From above: the top (13.5 mm) less the surface over the outline.
    let mut above = 0.0;
    for i in 0..240 {
        let x = face[0] + (i as f64 + 0.5) * cell;
        for j in 0..200 {
            let y = -10.0 + (j as f64 + 0.5) * cell;
            above += (10.0 + HEIGHT - worn(x, y)) * cell * cell;
        }
    }
    assert!(
        (v / fill - 1.0).abs() < 0.006,
        "the report's {v} mm³ against the fill's {fill} mm³"
    );
    // The check tells the two apart.
    assert!((above / fill - 1.0).abs() > 0.01, "{above} {fill}");
}

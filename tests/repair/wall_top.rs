//! A wall on a scan whose top is not one height (docs/repair.md, *A wall
//! on a scan*): a rib on the worn pad's scan up to a sloped plane, written
//! three ways, each layer `i` of `N` at `B + i·(T − B)/N` under the top `T`
//! at that point; up to the pad as designed, a solid of the file; and the
//! tops that have no height over the path, refused with where.

use super::wall::{band_integral_to, bead_points, built, rib_to, stacked, STRAIGHT};
use super::{compile, example_files, example_z, messages};
use lmdc::ir::Program;

/// The sloped top `13 + 0.02·x` mm over the straight rib (x −25..20 mm:
/// 12.5 .. 13.4 mm), as a plane.
const PLANE: &str = "plane(at = [0 mm, 0 mm], height = 13 mm, slope_x = 0.02, slope_y = 0)";

fn sloped(x: f64) -> f64 {
    13.0 + 0.02 * x
}

/// Every point of `a` and `b`, position and layer height, within `tol`.
fn same_plan(a: &Program, b: &Program, tol: f64) {
    assert_eq!(a.layers.len(), b.layers.len());
    for (la, lb) in a.layers.iter().zip(&b.layers) {
        let pa = la.paths.iter().flat_map(|p| &p.points);
        let pb: Vec<_> = lb.paths.iter().flat_map(|p| &p.points).collect();
        assert_eq!(pa.clone().count(), pb.len());
        for (qa, qb) in pa.zip(pb) {
            for k in 0..3 {
                assert!((qa.pos[k] - qb.pos[k]).abs() < tol, "{qa:?} vs {qb:?}");
            }
            assert!((qa.layer_height - qb.layer_height).abs() < tol as f32);
        }
    }
}

/// A straight rib two beads wide up to the sloped plane: `plane(…)`, the
/// expression `13 mm + 0.02 * x` and `edges(along = x, …)` from 12.5 to
/// 13.4 mm over the path's extent give the same plan. Its first layer lies
/// on the scan within 0.1 mm; every layer `i` of `N` (from 0) is laid at
/// `T − (N − i)·h`, `h` its local height, so the last ends on the plane; and the
/// layers stack `∫ (T − z)` over the band within 2 %.
#[test]
fn a_rib_up_to_a_sloped_plane_ends_on_it_however_its_top_is_written() {
    let p = built(&rib_to(STRAIGHT, PLANE, 2));
    let expr = built(&rib_to(STRAIGHT, "13 mm + 0.02 * x", 2));
    let edges = built(&rib_to(
        STRAIGHT,
        "edges(along = x, from = 12.5 mm, to = 13.4 mm)",
        2,
    ));
    same_plan(&p, &expr, 1e-9);
    same_plan(&p, &edges, 1e-9);
    let n = p.layers.len();
    for q in bead_points(&p, 0) {
        let [x, y, z] = q.pos;
        assert!((z - example_z(x, y)).abs() < 0.1, "({x}, {y}): {z}");
    }
    for i in 0..n {
        for q in bead_points(&p, i) {
            let [x, _, z] = q.pos;
            let want = sloped(x) - (n - i) as f64 * f64::from(q.layer_height);
            assert!((z - want).abs() < 1e-4, "layer {i}: {q:?}, want {want}");
        }
    }
    let pitch = f64::from(bead_points(&p, 0)[0].pitch);
    let integral = band_integral_to(pitch, sloped);
    let stacked = stacked(&p);
    assert!(
        (stacked / integral - 1.0).abs() < 0.02,
        "stacked {stacked} mm³ vs ∫ {integral} mm³"
    );
    // The report measures against the plane: the finish at every move's
    // middle, the design over the band face to face (the two pitches and
    // a bead's width less a pitch), both against the top there.
    let src = rib_to(STRAIGHT, PLANE, 2);
    let files = example_files(&["worn_pad.ply"]);
    let (_, model) = crate::support::data::compile_with_files_and_model(&src, files);
    let model = model.unwrap();
    let (_, samples) = lmdc::report::finish::sampled(&p, &model).unwrap();
    assert!(samples.len() > 40);
    for s in &samples {
        assert!((s.top - sloped(s.at[0])).abs() < 1e-9, "{}", s.top);
    }
    let mean = samples.iter().map(|s| s.off.abs()).sum::<f64>() / samples.len() as f64;
    assert!(mean <= 0.1 + 0.03 * 1.12, "mean departure {mean}");
    let lmdc::report::design::Design::Known {
        volume_mm3: volume, ..
    } = lmdc::report::design::volume(&model, None)
    else {
        panic!("no design volume");
    };
    let share = 2.0 * pitch / (pitch + 2.4);
    assert!(
        (stacked / volume / share - 1.0).abs() < 0.02,
        "{stacked} of {volume} mm³, not {share}"
    );
}

/// The pad as designed, a box 13 mm high written as a solid of the file
/// and named by the rib's `top`: it is not built, and the rib is the one
/// up to `top = 13 mm`. A design that does not reach over the whole path
/// is refused with the first place and how many more, the path named.
#[test]
fn a_rib_up_to_the_pad_as_designed_is_the_rib_up_to_its_height() {
    let design = |width: f64| {
        format!(
            "extrude nominal {{\n  profile = rectangle(width = {width} mm, height = 26 mm)\n  height = 13 mm\n}}\n\nwall rib {{"
        )
    };
    let with = |width: f64| rib_to(STRAIGHT, "nominal", 2).replace("wall rib {", &design(width));
    let flat = built(&rib_to(STRAIGHT, "13 mm", 2));
    let named = built(&with(66.0));
    same_plan(&flat, &named, 1e-6);
    let short = compile(&with(30.0), example_files(&["worn_pad.ply"]));
    assert!(short.program.is_none());
    let m = messages(&short);
    assert!(
        m.contains("top-height: the target solid `nominal` has no part over (-25, "),
        "{m}"
    );
    let d = short
        .diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::top-height")
        .unwrap();
    assert!(
        d.help.as_deref().unwrap().contains("cover the path"),
        "{d:?}"
    );
}

/// A top that is not a positive height where the path runs is refused
/// there, with how many other places: an expression negative for x < 0.
/// A sloped top no layer count reaches gets no flat top in its help.
#[test]
fn a_top_without_a_height_over_the_path_is_refused_with_where() {
    let c = compile(
        &rib_to(STRAIGHT, "0.5 mm * x / 1 mm", 1),
        example_files(&["worn_pad.ply"]),
    );
    let m = messages(&c);
    assert!(c.program.is_none());
    assert!(
        m.contains("top-height: the top is -12.5 mm at (-25, 0) mm, where a track runs (and at "),
        "{m}"
    );
    // 0.3 .. 2.1 mm to add along the sloped top 10.3 mm + 0.004·(x + 25):
    // no whole count with a bead of ratio 2.
    let c = compile(
        &rib_to(STRAIGHT, "10.3 mm + 0.004 * (x + 25 mm)", 1),
        example_files(&["worn_pad.ply"]),
    );
    let d = super::diagnostic(&c, "lmd::no-layer-count");
    let help = d.help.clone().unwrap();
    assert!(!help.contains("top"), "{help}");
    assert!(help.contains("level = auto"), "{help}");
}

/// Levelled first, then up to the sloped plane: the regular layers rise
/// from the level to the plane, the last laid one local height under it.
#[test]
fn a_levelled_rib_rises_from_its_level_to_a_sloped_top() {
    let src = rib_to(STRAIGHT, PLANE, 2).replace("layers = auto", "level = auto");
    let p = built(&src);
    let n = p.layers.len();
    let top: Vec<_> = bead_points(&p, n - 1);
    assert!(!top.is_empty());
    for q in top {
        let [x, _, z] = q.pos;
        let h = f64::from(q.layer_height);
        assert!((z + h - sloped(x)).abs() < 1e-4, "{q:?}");
    }
}

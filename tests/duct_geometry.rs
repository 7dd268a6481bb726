//! The seed 000 duct's IR against its design: bend and twist angles, local layer
//! heights ρ·Δδ, start and end sections, unit orthogonal directions, and the
//! paper's displacement-compensation identity (eq. 9–10).

use crate::support::duct;

use duct::Duct;
use lmdc::ir::Program;
use lmdc::pipeline::compile;
use proptest::prelude::*;

fn ir(src: &str) -> Program {
    let c = compile(src, &mut ());
    match c.program {
        Some(p) => p.into_ir(),
        None => panic!(
            "does not compile:\n{}",
            lmdc::diag::render(&c.diagnostics, "duct.lmd", src, false)
        ),
    }
}

type V = [f64; 3];
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn f(v: [f32; 3]) -> V {
    [v[0] as f64, v[1] as f64, v[2] as f64]
}

/// Bend angle of a layer plane: the angle of its normal from +Z, in the XZ plane.
fn bend_of(z: V) -> f64 {
    z[0].atan2(z[2])
}

/// Twist of a layer frame: the angle of its x axis from the untwisted
/// reference (toward the bend centre, `Y × z`), about z.
fn twist_of(x: V, z: V) -> f64 {
    let y = [0.0, 1.0, 0.0];
    let inward = cross(y, z);
    dot(x, y).atan2(dot(x, inward))
}

/// Checks every invariant of a compiled duct against its parameters.
fn check_duct(d: &Duct, p: &Program) {
    let n = p.layers.len();
    let bend = d.bend_deg.to_radians();
    let dd = bend / n as f64;
    let [h_min, h_max] = p.limits.layer_height;
    for (i, l) in p.layers.iter().enumerate() {
        // Stations are i/n; the plane's bend and the frame's twist follow them.
        assert!((l.station - i as f64 / n as f64).abs() < 1e-12);
        assert!(
            (bend_of(l.frame.z) - bend * l.station).abs() < 1e-9,
            "bend at layer {i}"
        );
        let tw = twist_of(l.frame.x, l.frame.z);
        assert!(
            (tw - d.twist_deg.to_radians() * l.station).abs() < 1e-9,
            "twist at layer {i}"
        );
        for pt in l.paths.iter().flat_map(|p| &p.points) {
            // ρ: distance from the bend axis (through (R, 0, 0), along Y).
            let rho = ((pt.pos[0] - d.radius).powi(2) + pt.pos[2].powi(2)).sqrt();
            let h = pt.layer_height as f64;
            assert!((h - rho * dd).abs() < 1e-5 * h, "h {h} vs ρΔδ {}", rho * dd);
            assert!(h >= h_min * (1.0 - 1e-5) && h <= h_max * (1.0 + 1e-5));
            let (nn, t) = (f(pt.normal), f(pt.tangent));
            assert!((dot(nn, nn) - 1.0).abs() < 1e-6 && (dot(t, t) - 1.0).abs() < 1e-6);
            assert!(dot(nn, t).abs() < 1e-6);
            // The point lies in its layer's plane.
            let rel = [
                pt.pos[0] - l.frame.origin[0],
                pt.pos[1] - l.frame.origin[1],
                pt.pos[2] - l.frame.origin[2],
            ];
            assert!(dot(rel, l.frame.z).abs() < 1e-9);
        }
    }
}

#[test]
fn seed_duct_matches_its_design() {
    let d = Duct::seed();
    let p = ir(&d.source());
    check_duct(&d, &p);
    let n = p.layers.len() as f64;
    let last = p.layers.last().unwrap();
    // Between the first and the last layer: 45°·(n−1)/n of bend and of twist.
    let bend = bend_of(last.frame.z) - bend_of(p.layers[0].frame.z);
    assert!((bend.to_degrees() - 45.0 * (n - 1.0) / n).abs() < 1e-9);
    let twist =
        twist_of(last.frame.x, last.frame.z) - twist_of(p.layers[0].frame.x, p.layers[0].frame.z);
    assert!((twist.to_degrees() - 45.0 * (n - 1.0) / n).abs() < 1e-9);
}

#[test]
fn auto_layer_count_is_the_smallest_feasible() {
    let d = Duct::seed();
    let p = ir(&d.source());
    let n = p.layers.len();
    let max_h = p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
        .map(|p| p.layer_height as f64)
        .fold(0.0, f64::max);
    // One layer fewer would make the thickest point too high.
    let h_max = p.limits.layer_height[1];
    assert!(
        max_h * n as f64 / (n as f64 - 1.0) > h_max,
        "n = {n} is not the smallest"
    );
}

#[test]
fn first_layer_is_the_circle_and_the_end_section_the_square() {
    let d = Duct::seed();
    let p = ir(&d.source());
    // size = outer: the bead's centre line runs half a bead width (3 mm) inside.
    let r = d.diameter / 2.0 - 3.0;
    for pt in &p.layers[0].paths[0].points {
        assert!(pt.pos[2].abs() < 1e-12);
        assert!((pt.pos[0].hypot(pt.pos[1]) - r).abs() < 1e-9);
    }
    // The end section at station 1 from the same geometry the slicer uses.
    let src = d.source();
    let ast = lmdc::syntax::parse(&src).unwrap();
    let model = lmdc::sema::check(&ast).0.unwrap();
    let lmdc::sema::model::Build::Duct { loft, .. } = &model.build else {
        panic!("the duct is a loft")
    };
    let geo = loft.geometry();
    let frame = geo.frame(1.0);
    let half = d.side / 2.0 - 3.0;
    let mut corners = 0;
    for j in 0..64 {
        let th = j as f64 * std::f64::consts::TAU / 64.0;
        let (_, uv) = geo.point(&frame, 1.0, th);
        let inf_norm = uv[0].abs().max(uv[1].abs());
        assert!(
            (inf_norm - half).abs() < 1e-9,
            "not on the square at θ = {th}"
        );
        if (uv[0].abs() - half).abs() < 1e-9 && (uv[1].abs() - half).abs() < 1e-9 {
            corners += 1;
        }
    }
    assert_eq!(corners, 4);
}

#[test]
fn displacement_compensation_identity() {
    // Seed 000 eq. 9–10: tilting the nozzle from α to α+β about the deposit
    // point moves the focus, Δd away along the nozzle, by
    // Δ(horizontal) = 2Δd·sin(β/2)·cos(α+β/2), Δ(vertical) = 2Δd·sin(β/2)·sin(α+β/2).
    let d = Duct::seed();
    let p = ir(&d.source());
    let dd = -p.layers[0].paths[0].points[0].defocus as f64; // 8.57 mm
    for (i, j) in [(0, 1), (0, p.layers.len() - 1), (10, 57)] {
        let a = p.layers[i].paths[0].points[0];
        let b = p.layers[j].paths[0].points[0];
        let alpha = bend_of(f(a.normal));
        let beta = bend_of(f(b.normal)) - alpha;
        // The same deposit point seen with layer j's nozzle: its focus moves by
        // focus_b − focus_a.
        let mut moved = a;
        moved.normal = b.normal;
        let (fa, fb) = (a.focus(), moved.focus());
        let dx = fb[0] - fa[0];
        let dz = fb[2] - fa[2];
        let s = 2.0 * dd * (beta / 2.0).sin();
        assert!(
            (dx.abs() - (s * (alpha + beta / 2.0).cos()).abs()).abs() < 1e-5,
            "Δ horizontal"
        );
        assert!(
            (dz.abs() - (s * (alpha + beta / 2.0).sin()).abs()).abs() < 1e-5,
            "Δ vertical"
        );
    }
}

#[test]
fn speeds_lay_the_local_height() {
    // Mass conservation: a wall one bead wide rises by the metal caught per
    // mm over its width, η·ṁ/(ρ·v·w), at every point — not by the height of
    // a single bead (which would stack only about 2/3 of it).
    // Each move lays the mean of its ends' heights, along which the layer
    // height varies linearly.
    let d = Duct::seed();
    let p = ir(&d.source());
    let feed = 45.9 / 60.0; // g/s
    let density = 7.9e-3; // g/mm³
    let moves = p
        .layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| p.points.windows(2).filter(|w| w[0].laser_on));
    for w in moves.step_by(97) {
        let (pt, next) = (&w[0], &w[1]);
        let rise = 0.35 * feed / (density * pt.speed as f64 * 6.0);
        let planned = 0.5 * (pt.layer_height as f64 + next.layer_height as f64);
        assert!((rise / planned - 1.0).abs() < 1e-5, "{rise} vs {planned}");
        assert!(pt.speed >= 7.0 * 0.99999 && pt.speed <= 10.0 * 1.00001);
        // The IR says so itself: the strip it fills and what it lays there.
        assert_eq!(pt.pitch, 6.0);
        assert!((pt.rise as f64 / planned - 1.0).abs() < 1e-5);
    }
}

#[test]
fn power_ramps_down_over_twenty_layers_then_holds() {
    let p = ir(&Duct::seed().source());
    let power = |i: usize| p.layers[i].paths[0].points[0].power as f64;
    assert_eq!(power(0), 4000.0);
    assert!((power(10) - (4000.0 - 1900.0 * 0.5)).abs() < 1e-3);
    assert_eq!(power(20), 2100.0);
    assert_eq!(power(p.layers.len() - 1), 2100.0);
}

#[test]
fn seam_at_the_inside_of_the_bend_warns() {
    let mut d = Duct::seed();
    d.seam_deg = 0.0; // the section's x axis points at the bend centre on layer 0
    let c = compile(&d.source(), &mut ());
    assert!(c.program.is_some());
    assert!(c
        .diagnostics
        .iter()
        .any(|d| d.code == "lmd::seam-at-bend-extreme"));
    let c = compile(&Duct::seed().source(), &mut ());
    assert!(c.diagnostics.is_empty(), "{:?}", c.diagnostics);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Random ducts whose bend is wide enough for the bead model keep every
    /// invariant. Feasible needs more than R ≥ reach·(q+1)/(q−1) ≈ 5.9× the
    /// reach (height ratio q = 1.41): a whole number N of layers must fit
    /// L_out/h_max ≤ N ≤ L_in/h_min, L = (R ± reach)·δ. With R ≥ 8× the reach
    /// that window is ≥ 0.091·R·δ/mm wide (h 0.8345..1.175 mm), and R·δ ≥ 80 mm ·
    /// 10° = 14 mm makes it wider than one layer.
    #[test]
    fn random_feasible_ducts(
        diameter in 20.0f64..80.0,
        side in 20.0f64..80.0,
        factor in 8.0f64..12.0,
        bend in 10.0f64..120.0,
        twist in -90.0f64..90.0,
        points in 16usize..96,
        outer in any::<bool>(),
        seam in 60.0f64..120.0,
    ) {
        let reach = (diameter / 2.0).max(side / 2.0 * 2f64.sqrt());
        let d = Duct {
            diameter, side, radius: (reach * factor).round(), bend_deg: bend.round(),
            twist_deg: twist.round(), points, outer, seam_deg: seam.round(),
        };
        let p = ir(&d.source());
        check_duct(&d, &p);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// A bend too tight for the bead model is refused, and the radius the
    /// diagnostic suggests does build.
    #[test]
    fn suggested_radius_builds(
        diameter in 20.0f64..80.0,
        side in 20.0f64..80.0,
        factor in 1.5f64..4.5,
        bend in 10.0f64..90.0,
        twist in -60.0f64..60.0,
    ) {
        // Both end sections reach at least min(D, side)/2 into the bend plane,
        // so R below 5.88× that makes some layer's height ratio exceed 1.41.
        let inner = diameter.min(side) / 2.0;
        let mut d = Duct {
            diameter, side, radius: (inner * factor).round(), bend_deg: bend.round(),
            twist_deg: twist.round(), points: 32, outer: false, seam_deg: 90.0,
        };
        let c = compile(&d.source(), &mut ());
        prop_assert!(c.program.is_none());
        let help = c.diagnostics.iter().find(|d| d.code == "lmd::bend-too-tight")
            .and_then(|d| d.help.clone()).expect("a bend-too-tight diagnostic");
        let after = help.split("at least ").nth(1).unwrap();
        let radius: f64 = after.split(" mm").next().unwrap().parse().unwrap();
        d.radius = radius;
        let p = ir(&d.source());
        check_duct(&d, &p);
    }
}

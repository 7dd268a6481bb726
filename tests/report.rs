//! The plan report against hand computations: one straight track, and a
//! rectangle laid as one contour on two layers; and the command's text and
//! JSON agreeing with each other and with the program headers.

use lmdc::bead::segment_area;
use lmdc::deposit::Basis;
use lmdc::ir::{Bead, BeadModel, Path, PathKind, Point};
use lmdc::pipeline::compile_with_model;
use lmdc::report::{Design, Report};
use lmdc::verify::{verify, Select};
use std::process::Command;

/// A 20 × 10 mm rectangle (the tracks' centre line), one contour a layer, two
/// layers, 5 mm/s, 1000 W, 6 g/min, on a robot with 100 mm/s rapids and a
/// 10 mm clearance.
const BOX: &str = "part box
bead b {
  width = 2 mm
  model = measured(height = 0.6 mm, speed = 5 mm/s)
}
extrude block {
  profile = rectangle(width = 20 mm, height = 10 mm)
  size = centre
  bead = b
}
slicing planar {
  layers = 2
  contours = 1
}
process {
  speed = 5 mm/s
  power = 1000 W
  powder = 6 g/min
  defocus = 0 mm
}
machine r {
  kind = robot
  head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) }
  load = load(mass = 18 kg, cog = [0 mm, 0 mm, 160 mm])
  tool = 1
  base = 1
  laser = 1
  power_output = 1
  full_scale = 2000 W
  max_speed = 100 mm/s
  clearance = 10 mm
}
";

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-6 * b.abs().max(1.0),
        "{what}: {a} != {b}"
    );
}

#[test]
fn a_rectangle_contour_on_two_layers() {
    let (c, model) = compile_with_model(BOX, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let m = p.machines().next().unwrap();
    let r = Report::new(m, &model, Some(8.0));
    // A single track rises by A/w (seed 001): A = seg(2, 0.6).
    let a = segment_area(2.0, 0.6);
    let lift = a / 2.0;
    close(p.ir().layers[1].paths[0].points[0].pos[2], lift, "lift");
    let (l1, l2) = (&r.layers[0].tally, &r.layers[1].tally);
    close(l1.deposit_mm, 60.0, "perimeter");
    // Layer 1: the first move starts wherever the robot stands (no length);
    // the approach comes down 10 mm at the path's speed.
    close(l1.travel_mm, 10.0, "travel 1");
    close(l1.motion_s, 10.0 / 5.0 + 60.0 / 5.0, "time 1");
    // Layer 2: retract 10 (rapid), across and up by the lift (rapid), down
    // 10 at 5 mm/s; after it the last retract (rapid).
    close(l2.travel_mm, 30.0 + lift, "travel 2");
    close(l2.motion_s, 12.0 + 2.0 + (20.0 + lift) / 100.0, "time 2");
    close(r.total.laser_on_s, 24.0, "laser on");
    close(r.total.energy_j, 24_000.0, "energy");
    close(r.total.powder_g, 6.0 / 60.0 * 24.0, "powder");
    // The bead model lays its segment; one track a layer stacks h·w.
    close(r.total.bead_volume_mm3, a * 120.0, "bead volume");
    close(r.total.stacked_volume_mm3, lift * 2.0 * 120.0, "stacked");
    close(r.bead_mass_g.unwrap(), 8e-3 * a * 120.0, "mass");
    close(
        r.bead_efficiency.unwrap(),
        8e-3 * a * 120.0 / 2.4,
        "efficiency",
    );
    // The design solid: the centre line widened by a bead's half, 22 × 12
    // with corners rounded by 1 mm, two lifts high.
    let design = (200.0 + 60.0 + std::f64::consts::PI) * 2.0 * lift;
    close(r.design_volume().unwrap(), design, "design");
    close(
        r.design_efficiency.unwrap(),
        8e-3 * design / 2.4,
        "design efficiency",
    );
}

#[test]
fn one_straight_track_with_a_mass_balance_bead() {
    let (c, _) = compile_with_model(BOX, &Default::default(), &mut ()).unwrap();
    let mut ir = c.program.unwrap().into_ir();
    // 10 mm along x at 5 mm/s, 1000 W, 6 g/min, one track 2 mm wide: by
    // the mass balance it lays A = η·ṁ/(ρ·v) = 0.4 · 0.1 g/s / (0.008 g/mm³
    // · 5 mm/s) = 1 mm², and rises A/w = 0.5 mm, the height planned.
    ir.bead = Some(Bead {
        width: 2.0,
        model: BeadModel::MassBalance {
            feed: 6.0,
            efficiency: 0.4,
            density: 8.0,
        },
        basis: Basis::Track,
        speed: [1.0, 10.0],
        widths: None,
        measured: None,
        fit: None,
        tilt: None,
        powers: None,
        powders: None,
    });
    let at = |x: f64, on: bool| Point {
        pos: [x, 0.0, 0.0],
        normal: [0.0, 0.0, 1.0],
        tangent: [1.0, 0.0, 0.0],
        layer_height: 0.5,
        speed: 5.0,
        power: 1000.0,
        powder: 6.0,
        defocus: 0.0,
        laser_on: on,
        style: 0,
        pitch: 2.0,
        rise: if on { 0.5 } else { 0.0 },
    };
    ir.layers.truncate(1);
    ir.layers[0].paths = vec![Path {
        kind: PathKind::Contour,
        points: vec![at(0.0, true), at(10.0, false)],
    }];
    let v = verify(ir, Select::All).expect("verifies");
    let design = Design::Unknown { why: "test".into() };
    let r = Report::from_parts(v.machines().next().unwrap(), design, None);
    let t = &r.total;
    close(t.deposit_mm, 10.0, "length");
    close(t.laser_on_s, 2.0, "laser");
    close(t.powder_g, 0.2, "powder");
    close(t.energy_j, 2000.0, "energy");
    close(t.bead_volume_mm3, 10.0, "volume");
    close(r.bead_mass_g.unwrap(), 0.08, "mass");
    // The mass balance's own efficiency comes back.
    close(r.bead_efficiency.unwrap(), 0.4, "efficiency");
    close(t.stacked_volume_mm3, 0.5 * 2.0 * 10.0, "stacked");
    assert_eq!(r.density_g_cm3, Some(8.0));
    assert!(r.design_mass_g.is_none());
}

#[test]
fn a_tilted_defocused_cone_catches_the_powder_its_model_declares() {
    // examples/cone.lmd leans its nozzle 26.6° along the wall and focuses
    // 4 mm below the working plane: the program moves the focus on a larger
    // circle than the deposit point the metal lands at. By the mass balance
    // the bead holds exactly η of the powder the program feeds while the
    // laser is on, layer by layer (it said 47.2 % of the declared 50 %).
    let src = std::fs::read_to_string("examples/cone.lmd").unwrap();
    let (c, model) = compile_with_model(&src, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    for m in p.machines() {
        let r = Report::new(m, &model, None);
        close(r.bead_efficiency.unwrap(), 0.5, "efficiency");
        for row in &r.layers {
            let t = &row.tally;
            let mass = 7.9e-3 * t.bead_volume_mm3;
            assert!(
                (mass / t.powder_g - 0.5).abs() < 1e-4,
                "layer {}: {mass} g of {} g",
                row.layer,
                t.powder_g
            );
        }
    }
}

fn lmdc(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

#[test]
fn the_command_prints_text_and_json_that_agree() {
    let o = lmdc(&["report", "examples/sprocket_tooth.lmd", "--machine", "kr30"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.starts_with("sprocket_tooth on kr30: 35 layers"),
        "{text}"
    );
    assert!(text.contains("give one with --density"), "{text}");
    let o = lmdc(&[
        "report",
        "examples/sprocket_tooth.lmd",
        "--json",
        "--density",
        "7.9",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let lines: Vec<serde_json::Value> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object a line"))
        .collect();
    assert_eq!(lines.len(), 2, "one report a machine");
    for r in &lines {
        assert_eq!(r["type"], "report");
        assert_eq!(r["layers"].as_array().unwrap().len(), 35);
        let sum: f64 = r["layers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l["deposit_mm"].as_f64().unwrap())
            .sum();
        close(
            sum,
            r["total"]["deposit_mm"].as_f64().unwrap(),
            "layers add up",
        );
        assert_eq!(r["density_g_cm3"], 7.9);
        assert!(r["design"]["known"]["volume_mm3"].as_f64().unwrap() > 0.0);
    }
    // The text's totals are the JSON's, rounded.
    let m = (lines[0]["total"]["deposit_mm"].as_f64().unwrap() / 1000.0 * 100.0).round() / 100.0;
    assert!(text.contains(&format!("{m:.2} m deposited")), "{text}");
}

#[test]
fn a_file_with_errors_reports_nothing() {
    let o = lmdc(&["report", "examples/errors/bend_too_tight.lmd"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    let o = lmdc(&["report", "examples/twisted_duct.lmd", "--density", "-1"]);
    assert_eq!(o.status.code(), Some(2));
}

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

/// A small generator of points, so the sampling below is the same every run.
struct Lcg(u64);

impl Lcg {
    /// Uniform in [0, 1).
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The squared distance from `p` to the segment `a b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (d, q) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 {
        ((q[0] * d[0] + q[1] * d[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q[0] - t * d[0]).powi(2) + (q[1] - t * d[1]).powi(2)
}

/// Whether `p` lies within half its pitch of a deposit move of `layer`.
fn in_a_strip(layer: &lmdc::ir::Layer, p: [f64; 2]) -> bool {
    layer
        .paths
        .iter()
        .flat_map(|q| q.points.windows(2))
        .any(|m| {
            let r = m[0].pitch as f64 / 2.0;
            m[0].laser_on
                && r > 0.0
                && to_segment(p, [m[0].pos[0], m[0].pos[1]], [m[1].pos[0], m[1].pos[1]]) <= r * r
        })
}

#[test]
fn the_flange_says_how_much_of_its_design_is_the_band_at_its_faces() {
    // Issue 33 item 5: the design line said "2.0 % outside every strip,
    // where the outermost beads round off", where the band between the
    // faces and the contours' strips alone is more. Sampled here at random
    // over the flange's own circles (not lmdc's grid): a point of the
    // design no deposit's strip covers is the band at the faces within
    // half a bead (1.5 mm) of the outline or a hole, else missing for
    // other reasons (raster ends short of the contours).
    let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
    let (c, model) = compile_with_model(&src, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let m = p.machines().next().unwrap();
    let r = Report::new(m, &model, Some(7.9));
    let got = r.design_missing.expect("a breakdown for flat layers");
    let bolts: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let a = (30.0 + 60.0 * k as f64).to_radians();
            [30.0 * a.cos(), 30.0 * a.sin()]
        })
        .collect();
    let face = |q: [f64; 2]| {
        let r = q[0].hypot(q[1]);
        let hole = bolts
            .iter()
            .map(|c| (q[0] - c[0]).hypot(q[1] - c[1]) - 4.5)
            .fold(f64::INFINITY, f64::min);
        (40.0 - r).min(r - 15.0).min(hole)
    };
    let (mut rng, mut n, mut counts) = (Lcg(33), 0usize, [0usize; 3]);
    let layers = &p.ir().layers;
    for _ in 0..120_000 {
        let q = [80.0 * rng.next() - 40.0, 80.0 * rng.next() - 40.0];
        let layer = &layers[(rng.next() * layers.len() as f64) as usize];
        let d = face(q);
        if d < 0.0 {
            continue;
        }
        n += 1;
        if in_a_strip(layer, q) {
            counts[0] += 1;
        } else if d < 1.5 {
            counts[1] += 1;
        } else {
            counts[2] += 1;
        }
    }
    let share = |k: usize| counts[k] as f64 / n as f64;
    // 1.3 · √(p(1 − p)/n) is below 0.1 % here; the grid's cell adds a little.
    let near = |a: f64, b: f64, what: &str| {
        assert!((a - b).abs() < 0.004, "{what}: lmdc {a}, sampled {b}")
    };
    near(got.covered.share, share(0), "covered");
    near(got.faces.share, share(1), "the band at the faces");
    near(got.other.share, share(2), "missing otherwise");
    assert_eq!(got.hollows.share, 0.0, "the flange is filled");
    // The band if every contour filled half the offset on its face side
    // (d = A/h = seg(3 mm, 1 mm)/1 mm), as the issue measured it: 5.5 %.
    // Between a bolt hole and the outline the layer is two contours
    // across, and each fills its full half bead towards its face
    // (fill::pitch), so the band is less.
    let d = segment_area(3.0, 1.0);
    let b = 1.5 - d / 2.0;
    let pi = std::f64::consts::PI;
    let band = pi * (40f64.powi(2) - (40.0 - b).powi(2))
        + pi * ((15.0 + b).powi(2) - 225.0)
        + 6.0 * pi * ((4.5 + b).powi(2) - 4.5f64.powi(2));
    let area = pi * (1600.0 - 225.0 - 6.0 * 4.5 * 4.5);
    assert!((band / area - 0.0552).abs() < 5e-4, "{}", band / area);
    assert!(
        got.faces.share > 0.6 * band / area && got.faces.share < band / area,
        "{:?}",
        got.faces
    );
    // The figures add up to the design, and are given in grams too.
    let sum = got.covered.share + got.faces.share + got.hollows.share + got.other.share;
    close(sum, 1.0, "the design's parts");
    let v = r.design_volume().unwrap();
    close(
        got.faces.volume_mm3,
        got.faces.share * v,
        "the band's volume",
    );
    close(
        got.faces.mass_g.unwrap(),
        7.9e-3 * got.faces.volume_mm3,
        "its mass",
    );
    let text = lmdc::report::text::render(&r);
    let faces = format!("{:.1} %", got.faces.share * 100.0);
    assert!(
        text.contains(&format!("{faces} (")) && text.contains("is the band at the faces"),
        "{text}"
    );
}

#[test]
fn a_contour_only_part_reports_its_inside_as_a_hollow_on_purpose() {
    // A 30 × 20 mm block's faces, one contour of a 2 mm bead and no
    // infill: the contour fills the 2 mm at the faces (a wall one bead
    // wide), and the 26 × 16 mm inside is the hollow the plan leaves on
    // purpose; it was "the outermost beads round off" (82.5 % on the
    // issue's part).
    let src = BOX
        .replace(
            "width = 20 mm, height = 10 mm",
            "width = 30 mm, height = 20 mm",
        )
        .replace("size = centre", "size = outer");
    let (c, model) = compile_with_model(&src, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let r = Report::new(p.machines().next().unwrap(), &model, None);
    let got = r.design_missing.expect("a breakdown");
    let hollow = 26.0 * 16.0 / 600.0;
    assert!((got.hollows.share - hollow).abs() < 0.004, "{got:?}");
    // The faces: only the four corners' squares outside the contour's
    // round strip, 4·(1 − π/4) mm² of 600.
    let corners = 4.0 * (1.0 - std::f64::consts::FRAC_PI_4) / 600.0;
    assert!((got.faces.share - corners).abs() < 0.002, "{got:?}");
    assert!(got.other.share < 0.002, "{got:?}");
    let text = lmdc::report::text::render(&r);
    let line = text.lines().find(|l| l.starts_with("unfilled")).unwrap();
    assert!(
        line.contains(&format!("{:.1} % (", hollow * 100.0))
            && line.contains("is hollow on purpose"),
        "{line}"
    );
    // Drawn as the tracks' centre line (the box above, 20 × 10): the
    // design is widened by half a bead, the contour's strip is the whole
    // of it, and the inside 18 × 8 is hollow.
    let (c, model) = compile_with_model(BOX, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let r = Report::new(p.machines().next().unwrap(), &model, None);
    let got = r.design_missing.expect("a breakdown");
    let design = 200.0 + 60.0 + std::f64::consts::PI;
    assert!(
        (got.hollows.share - 144.0 / design).abs() < 0.004,
        "{got:?}"
    );
    assert!(
        got.faces.share < 0.003 && got.other.share < 0.003,
        "{got:?}"
    );
}

/// The flange's layers, sampled at random over its own circles (not lmdc's
/// grid): the share of the design some deposit's strip covers, and what
/// the layers stack over the design (`Σ pitch·length` over each layer's
/// laser-on moves, from the IR alone, times the layer's lift, over the
/// design's area times the lift).
fn flange_strips(src: &str) -> (Report, f64, f64) {
    let (c, model) = compile_with_model(src, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let m = p.machines().next().unwrap();
    let r = Report::new(m, &model, None);
    let bolts: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let a = (30.0 + 60.0 * k as f64).to_radians();
            [30.0 * a.cos(), 30.0 * a.sin()]
        })
        .collect();
    let inside = |q: [f64; 2]| {
        let r = q[0].hypot(q[1]);
        (15.0..=40.0).contains(&r)
            && bolts
                .iter()
                .all(|c| (q[0] - c[0]).hypot(q[1] - c[1]) >= 4.5)
    };
    let pi = std::f64::consts::PI;
    let area = pi * (1600.0 - 225.0 - 6.0 * 4.5 * 4.5);
    let layers = &p.ir().layers;
    // Every layer is as thick (a flat flange): the shares weigh them alike.
    let credited: f64 = layers
        .iter()
        .flat_map(|l| l.paths.iter().flat_map(|q| q.points.windows(2)))
        .filter(|m| m[0].laser_on)
        .map(|m| {
            let d = (m[1].pos[0] - m[0].pos[0]).hypot(m[1].pos[1] - m[0].pos[1]);
            m[0].pitch as f64 * d
        })
        .sum::<f64>()
        / (area * layers.len() as f64);
    let (mut rng, mut n, mut hit) = (Lcg(7), 0usize, 0usize);
    for _ in 0..120_000 {
        let q = [80.0 * rng.next() - 40.0, 80.0 * rng.next() - 40.0];
        let layer = &layers[(rng.next() * layers.len() as f64) as usize];
        if inside(q) {
            n += 1;
            hit += usize::from(in_a_strip(layer, q));
        }
    }
    (r, hit as f64 / n as f64, credited)
}

#[test]
fn the_flange_s_laser_on_turns_lay_no_strip_twice() {
    // Issue 33: the flange's laser-on links ran along the contours, each
    // credited a strip of its own on top of the raster ends' (8.1 % of
    // the design counted twice, the layers stacking 101.4 %). Its turns
    // are half circles across the tracks' spacing now, the raster ends
    // trimmed beside them: what the layers stack is what the strips cover,
    // counted independently here (`Σ pitch·length` against the sampled
    // union of the strips), with the laser on and off through the links.
    let on = std::fs::read_to_string("examples/flange.lmd").unwrap();
    assert!(on.contains("link = laser_on"));
    let off = on.replace("link = laser_on", "link = laser_off");
    let mut stacks = Vec::new();
    for src in [&on, &off] {
        let (r, covered, credited) = flange_strips(src);
        let got = r.design_missing.expect("a breakdown for flat layers");
        let filled = r.design_filled.expect("a design volume");
        // The sampled union: 1.3 · √(p(1 − p)/n) is below 0.2 %.
        assert!(
            (got.covered.share - covered).abs() < 0.004,
            "covered: lmdc {}, sampled {covered}",
            got.covered.share
        );
        assert!(
            (filled - credited).abs() < 2e-3,
            "stacked: lmdc {filled}, from the IR {credited}"
        );
        // Nothing counted twice: the stack is at most what the strips
        // cover (the union of round-ended strips is a little more than
        // their rectangles where a track ends short of the next).
        assert!(
            credited <= covered + 0.004,
            "the layers stack {credited} of the design where strips cover {covered}"
        );
        assert!(credited > 0.85 && credited < 0.95, "{credited}");
        // The report agrees: its text says nothing of strips counted twice.
        let text = lmdc::report::text::render(&r);
        assert!(!text.contains("counted twice"), "{text}");
        let stacked = r.deposit.as_ref().expect("a deposit check");
        assert!(
            (stacked.bead_over_stacked - 1.0).abs() < 0.005,
            "{stacked:?}"
        );
        stacks.push(credited);
    }
    // The turns lay what the trimmed ends leave: the laser-on flange
    // stacks as much of its design as the unlinked one, within 1 %.
    assert!((stacks[0] - stacks[1]).abs() < 0.01, "{stacks:?}");
}

/// A variable top's finish (docs/repair.md, *The report*): the ramp wall's
/// one track is laid in `m` equal stretches of constant speed, each at the
/// height of its middle (the top is a plane, seed 003), so the finished top
/// is a sawtooth `16 %·L/(2m)` either way of the design, its RMS that over
/// √3. The bead model lays what each stretch plans, so that is what the
/// report predicts; the first layer is the top at the track's ends over the
/// layer count.
#[test]
fn a_ramp_walls_finish_is_its_segments_sawtooth() {
    let src = std::fs::read_to_string("examples/ramp_wall.lmd").unwrap();
    let (c, model) = compile_with_model(&src, &Default::default(), &mut ()).unwrap();
    let (p, model) = (c.program.expect("compiles"), model.unwrap());
    let r = Report::new(p.machines().next().unwrap(), &model, None);
    let f = r.finish.expect("a variable top's finish");
    let layers = &p.ir().layers;
    let track = &layers.last().unwrap().paths[0].points;
    let xs = track.iter().map(|q| q.pos[0]);
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let mut m = 1;
    for w in track.windows(2).filter(|w| w[0].laser_on && w[1].laser_on) {
        m += usize::from(w[0].speed != w[1].speed);
    }
    let amplitude = 0.16 * (x1 - x0) / (2.0 * m as f64);
    // Sampled every 0.3 mm: the tooth's tip is found within 0.16 × 0.15.
    for (got, what) in [(f.below_mm, "below"), (f.above_mm, "above")] {
        assert!(
            (got - amplitude).abs() <= 0.16 * 0.15 + 1e-6,
            "{what}: {got} vs {amplitude} ({m} stretches)"
        );
    }
    // About eight samples a tooth: the sampled RMS within 1 %.
    let rms = amplitude / 3f64.sqrt();
    assert!(
        (f.rms_mm - rms).abs() <= 0.01 * rms,
        "RMS {} vs {rms}",
        f.rms_mm
    );
    let n = layers.len() as f64;
    let top = |x: f64| 20.0 + 0.16 * (x + 50.0);
    close(f.first_layer_mm[0], top(x0) / n, "first layer, thinnest");
    close(f.first_layer_mm[1], top(x1) / n, "first layer, thickest");
}

//! The KRL controller of seed 004 executed: the robot program lmdc writes for
//! `examples/segmented_ring.lmd` runs in a small KRL interpreter
//! (tests/support/krl_run.rs) that models the advance run, with `$ANIN`
//! scripted. Fed the heights `lmdc simulate` computes (the library call it
//! prints; tests/ring.rs holds its CSV to the same numbers), the update routine
//! sets the same speeds, layer by layer and segment by segment, and the
//! working planes rise by the same heights; every update lands before its
//! segment is laid again, without stopping the advance run.

use crate::support::krl_parser;
use crate::support::krl_run;
use crate::support::ring;
use crate::support::skip;

use krl_run::{Config, Motion, Read, Run};
use lmdc::ir::{Machine, RingRun};

struct Setup {
    files: krl_run::Files,
    laser: u16,
    power: u16,
    scale: f64,
    input: u16,
    segments: usize,
    per: usize,
    flat: usize,
    defocus: Vec<f64>,
    arc: f64,
    rows: Vec<Vec<ring::Row>>,
}

fn setup() -> Setup {
    let src = std::fs::read_to_string(ring::EXAMPLE).unwrap();
    let p = ring::compile(ring::EXAMPLE, &src);
    let r = p.ir().ring.clone().expect("a ring");
    assert!(matches!(r.run, RingRun::OnMachine(_)));
    let Some(Machine::Robot(robot)) = p.ir().machines.iter().find(|m| m.name() == "kr60") else {
        panic!("kr60 is a robot")
    };
    let sensor = robot.height_sensor.expect("a sensor");
    let rows = ring::simulation(&src);
    Setup {
        files: ring::files(&p, "kr60"),
        laser: robot.laser_out.number().unwrap(),
        power: robot.power_out.number().unwrap(),
        scale: sensor.full_scale,
        input: sensor.input,
        segments: r.segments.len(),
        per: r.flat_moves + r.transition_moves,
        flat: r.flat_moves,
        defocus: r.segments.iter().map(|s| s.defocus).collect(),
        arc: r.radius * r.transition.to_radians(),
        rows,
    }
}

/// Runs the program with the sensor reading `height(layer, segment)` (both
/// from 0) when segment `segment`'s update asks for its `layer`-th reading.
fn run(s: &Setup, delay_motions: usize, height: impl Fn(usize, usize) -> f64) -> Run {
    let mut reads = vec![0usize; s.segments];
    let mut sensor = |r: &Read| -> Result<f64, String> {
        if r.input != s.input as i64 || r.routine != "SEG_UPD" || r.args.len() != 1 {
            return Err(format!("unexpected read {r:?}"));
        }
        let j = r.args[0] as usize - 1;
        let layer = reads[j];
        reads[j] += 1;
        Ok(height(layer, j) / s.scale)
    };
    krl_run::run(
        &s.files,
        "segmented_ring_kr60",
        s.laser,
        s.power,
        Config { delay_motions },
        &mut sensor,
    )
    .unwrap_or_else(|e| panic!("the program fails: {e}"))
}

/// The laser-on motions, layer by layer.
fn layers(s: &Setup, run: &Run) -> Vec<Vec<Motion>> {
    let on: Vec<Motion> = run.motions.iter().filter(|m| m.laser).cloned().collect();
    let per_layer = s.segments * s.per;
    assert_eq!(on.len(), per_layer * s.rows.len(), "one motion per point");
    on.chunks(per_layer).map(|c| c.to_vec()).collect()
}

/// The speeds and heights the program ran, against the simulation.
fn assert_runs_the_simulation(s: &Setup, got: &[Vec<Motion>]) {
    for (l, layer) in got.iter().enumerate() {
        for j in 0..s.segments {
            let row = s.rows[l][j];
            // Where the segment's working plane is: what it laid so far.
            let plane = if l == 0 { 0.0 } else { s.rows[l - 1][j].total };
            let moves = &layer[j * s.per..(j + 1) * s.per];
            for (k, m) in moves.iter().enumerate() {
                let at = format!("layer {} segment {} move {k}: {m:?}", l + 1, j + 1);
                if k < s.flat {
                    assert!((m.speed - row.speed).abs() < 1e-9, "{at}: want {row:?}");
                    assert!(
                        (m.pos[2] - (plane + s.defocus[j])).abs() < 1e-9,
                        "{at}: want the working plane {plane}"
                    );
                } else {
                    // v / cos γ over the transition to the next segment's height.
                    let (zf, zt) = (
                        layer[j * s.per + s.flat - 1].pos[2],
                        moves[s.per - 1].pos[2],
                    );
                    let want = row.speed * (1.0 + ((zt - zf) / s.arc).powi(2)).sqrt();
                    // ARC is written with 6 decimals: 2e-7 of it.
                    assert!((m.speed - want).abs() < 1e-6 * want, "{at}: want {want}");
                }
            }
        }
    }
}

#[test]
fn the_update_routine_sets_the_speeds_lmdc_simulate_computes() {
    let s = setup();
    let run = run(&s, 12, |l, j| s.rows[l][j].height);
    let got = layers(&s, &run);
    assert_runs_the_simulation(&s, &got);
    // Every segment updated after every layer, in the main run.
    let updates: Vec<_> = run.triggered.iter().filter(|t| t.0 == "SEG_UPD").collect();
    assert_eq!(updates.len(), s.segments * s.rows.len());
    let module_stops: Vec<&String> = run
        .stops
        .iter()
        .filter(|w| w.starts_with("SEGMENTED_RING_KR60_M"))
        .collect();
    assert!(
        module_stops.is_empty(),
        "advance-run stops: {module_stops:?}"
    );
    // The last segment of the last layer ends where the simulation's total
    // puts it: the working plane rose by every measured height.
    let last = got.last().unwrap().last().unwrap();
    let total = s.rows.last().unwrap()[s.segments - 1].total
        - s.rows.last().unwrap()[s.segments - 1].height;
    assert!((last.pos[2] - (total + s.defocus[s.segments - 1])).abs() < 1e-9);
    // Home, the PTP from home to above the first point, home.
    assert!(!run.laser_at_end && run.ptps == 3);
}

/// The interpreter's advance-run model has teeth: an update that landed a
/// whole layer late would leave every segment a layer behind the law.
#[test]
fn an_update_that_lands_too_late_is_caught() {
    let s = setup();
    let late = run(&s, s.segments * s.per + 1, |l, j| s.rows[l][j].height);
    let got = layers(&s, &late);
    let r = std::panic::catch_unwind(|| assert_runs_the_simulation(&s, &got));
    assert!(r.is_err(), "a late update went unnoticed");
}

/// A sensor that reads the target every layer leaves the nominal plan: the
/// table's speeds, layers `h_r` apart.
#[test]
fn on_target_the_program_lays_the_table() {
    let s = setup();
    let h = s.rows[0][0].target;
    let run = run(&s, 12, |_, _| h);
    let got = layers(&s, &run);
    for (l, layer) in got.iter().enumerate() {
        for j in 0..s.segments {
            let m = &layer[j * s.per];
            let v = s.rows[0][j].speed;
            assert!((m.speed - v).abs() < 1e-9, "layer {l} segment {j}: {m:?}");
            assert!((m.pos[2] - (l as f64 * h + s.defocus[j])).abs() < 1e-9);
        }
    }
}

/// Rings of every shape — two segments or many, one layer or a few, any
/// beam axis — run in the interpreter with the sensor on target lay their IR:
/// every deposit at its focus, speed and power, the laser off at the end.
mod shapes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(16))]
        #[test]
        fn every_ring_lays_its_ir_on_target(
            segments in prop_oneof![2..5usize, Just(10)],
            layers in 1..4usize,
            transition in prop_oneof![Just(2.0f64), Just(5.0)],
            step in prop_oneof![Just(1.0f64), Just(3.0)],
            beam in prop_oneof![Just("z"), Just("-x"), Just("y")],
        ) {
            let src = ring::variant(segments, layers, transition, step, beam, false);
            let p = ring::compile("variant", &src);
            let ir = p.ir();
            let Some(Machine::Robot(robot)) = ir.machines.iter().find(|m| m.name() == "kr60") else {
                panic!("kr60")
            };
            let files = ring::files(&p, "kr60");
            let main = files
                .keys()
                .find(|k| k.ends_with(".src") && !k.contains("_m0"))
                .unwrap()
                .trim_end_matches(".src")
                .to_string();
            let run = krl_run::run_steady(&files, &main, robot.laser_out.number().unwrap(), robot.power_out.number().unwrap(), ring::on_target_reading(&p, "kr60"))
                .unwrap_or_else(|e| panic!("{e}\n{src}"));
            let want: Vec<_> = ir
                .layers
                .iter()
                .flat_map(|l| &l.paths)
                .flat_map(|p| p.points.windows(2))
                .filter(|w| w[0].laser_on)
                .map(|w| (w[0], w[1]))
                .collect();
            let got: Vec<&Motion> = run.motions.iter().filter(|m| m.laser).collect();
            prop_assert_eq!(got.len(), want.len());
            for ((from, to), m) in want.iter().zip(&got) {
                let f = to.focus();
                for i in 0..3 {
                    prop_assert!((m.pos[i] - f[i]).abs() < 1e-3, "{:?} vs {:?}", m, f);
                }
                prop_assert!((m.speed - from.speed as f64).abs() < 1e-3 * from.speed as f64, "{:?} vs {}", m, from.speed);
                prop_assert!((m.anout - from.power as f64 / robot.full_scale_power).abs() < 1e-4);
            }
            prop_assert!(!run.laser_at_end);
            prop_assert!(run.stops.iter().all(|w| !w.contains("_M0")), "{:?}", run.stops);
        }
    }
}

/// One segment cannot run the loop on a robot: it starts again where it
/// ends, before its update lands; the verifier says so.
#[test]
fn one_segment_is_refused_on_a_robot() {
    let src = ring::variant(2, 2, 2.0, 1.0, "z", false)
        .replace("segments = 2", "segments = 1")
        .replace("defocus = [-8 mm, -7 mm]", "defocus = [-8 mm]")
        .replace("power = [900 W, 950 W]", "power = [900 W]")
        .replace("width = [3 mm, 3.5 mm]", "width = [3 mm]")
        .replace("speed = [4 mm/s, 5 mm/s]", "speed = [4 mm/s]");
    let c = lmdc::pipeline::compile(&src, &mut ());
    let text = lmdc::diag::render(&c.diagnostics, "one.lmd", &src, false);
    assert!(c.program.is_none(), "{text}");
    assert!(text.contains("lmd::loop-timing"), "{text}");
    assert!(
        text.contains("a ring of one segment cannot run its loop"),
        "{text}"
    );
}

/// The KRL of rings of other shapes (two segments, one layer, another beam
/// axis) parses with the KRL grammar too (the example's is checked with
/// every example's in krl_parser.rs).
#[test]
fn other_rings_krl_parses() {
    if krl_parser::find_krl_parser().is_none() {
        skip::skip(
            "other_rings_krl_parses",
            "a KRL parser",
            "run `sh ../shared/tools/krlcheck/install.sh` and export LMDC_KRL_PARSER",
        );
        return;
    }
    for (n, layers, beam) in [(2, 3, "z"), (3, 1, "-x"), (10, 2, "y")] {
        let src = ring::variant(n, layers, 2.0, 3.0, beam, false);
        let p = ring::compile("variant", &src);
        let files = ring::files(&p, "kr60");
        let list: Vec<(&str, &str)> = files
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect();
        krl_parser::parse_sources(&list).unwrap_or_else(|e| panic!("{e}"));
    }
}

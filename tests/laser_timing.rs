//! One laser-timing rule for every back end (docs/ir.md): the KRL and G-code
//! programs of every example, read back by independent readers, switch the
//! laser on and off at the same places — and those are the IR points where a
//! run of laser-on points starts and where it ends.

use crate::support::krl_check as krl;
use crate::support::krl_run;
use crate::support::m66;
use crate::support::rapid_check as rapid;
use crate::support::rs274;
use crate::support::skip;

use lmdc::back::{MemorySink, Templates};
use lmdc::ir::{Dialect, Machine, Program};

/// A laser switch: on or off, at a tool-tip position (µm, as printed).
type Switch = (bool, [i64; 3]);

fn micrometres(p: [f64; 3]) -> [i64; 3] {
    p.map(|v| (v * 1000.0).round() as i64)
}

/// Where the IR says the laser switches, found without the motion plan: on at
/// the first point of each run of laser-on points, off at the point after its
/// last one. A run goes on into the next path only when that path, in the same
/// layer (or the next one of a continuous program), starts where the last one
/// ended.
fn from_ir(p: &Program) -> Vec<Switch> {
    let mut out = Vec::new();
    let mut on = false;
    let mut last: Option<[f64; 3]> = None;
    for layer in &p.layers {
        let mut first_in_layer = true;
        for path in layer.paths.iter().filter(|p| !p.points.is_empty()) {
            let start = path.points[0].focus();
            // A continuous program's layer goes on from the last one's end.
            let joined = (!first_in_layer || p.continuous)
                && last.is_some_and(|l| (0..3).all(|i| (l[i] - start[i]).abs() < 1e-3));
            if on && !(joined && path.points.len() > 1 && path.points[0].laser_on) {
                out.push((false, micrometres(last.unwrap())));
                on = false;
            }
            for w in path.points.windows(2) {
                if w[0].laser_on != on {
                    on = w[0].laser_on;
                    // On at a run's first point; off at the point after its last.
                    out.push((on, micrometres(w[0].focus())));
                }
            }
            last = Some(path.points[path.points.len() - 1].focus());
            first_in_layer = false;
        }
        if on && !p.continuous {
            out.push((false, micrometres(last.unwrap())));
            on = false;
        }
    }
    if on {
        out.push((false, micrometres(last.unwrap())));
    }
    out
}

/// The switches of a G-code program: M-words of the dialect, at the position
/// the moves before them reached.
fn from_gcode(text: &str, d: &Dialect) -> Vec<Switch> {
    let mut out = Vec::new();
    let mut pos = [0.0f64; 3];
    let mut on = false;
    for line in text.lines() {
        let l = line.trim();
        if l == d.laser_on || l == d.laser_off {
            let now = l == d.laser_on;
            if now != on {
                on = now;
                out.push((on, micrometres(pos)));
            }
            continue;
        }
        let mut words = l.split_whitespace();
        if !matches!(words.next(), Some("G0" | "G1" | "G00" | "G01")) {
            continue;
        }
        for w in words {
            let (letter, value) = w.split_at(1);
            let axis = match letter {
                "X" => 0,
                "Y" => 1,
                "Z" => 2,
                _ => continue,
            };
            pos[axis] = value.parse().unwrap_or_else(|_| panic!("{w} in {l}"));
        }
    }
    out
}

/// The switches of a LinuxCNC program as rs274 ran it: M3/M5 at the
/// position the moves before them reached.
fn from_canon(calls: &[rs274::CanonCall]) -> Vec<Switch> {
    use rs274::CanonCall::*;
    let mut out = Vec::new();
    let mut pos = [0.0f64; 3];
    let mut on = false;
    for c in rs274::program_body(calls) {
        match *c {
            Traverse { x, y, z, .. } | Feed { x, y, z, .. } => pos = [x, y, z],
            SpindleOn | SpindleOff => {
                let now = matches!(c, SpindleOn);
                if now != on {
                    on = now;
                    out.push((on, micrometres(pos)));
                }
            }
            _ => {}
        }
    }
    out
}

/// The switches of a KRL program, run by the test interpreter: where the laser
/// state of one LIN differs from the one before, it switched at that LIN's start.
fn from_krl(trace: &krl::Trace) -> Vec<Switch> {
    from_motions(
        trace.lins.iter().map(|l| (l.laser, l.pos)),
        trace.laser_at_end,
    )
}

/// The switches of motions run with these laser states, ending with the
/// laser `at_end`.
fn from_motions(motions: impl Iterator<Item = (bool, [f64; 3])>, at_end: bool) -> Vec<Switch> {
    let mut out = Vec::new();
    let mut on = false;
    let mut pos = [f64::NAN; 3];
    for (laser, at) in motions {
        if laser != on {
            on = laser;
            out.push((on, micrometres(pos)));
        }
        pos = at;
    }
    if at_end != on {
        out.push((at_end, micrometres(pos)));
    }
    out
}

fn main_program(files: &krl::Files) -> String {
    let srcs: Vec<&String> = files.keys().filter(|n| n.ends_with(".src")).collect();
    srcs.iter()
        .map(|n| n.trim_end_matches(".src").to_string())
        .find(|stem| {
            srcs.iter()
                .all(|o| o.trim_end_matches(".src") == stem || o.starts_with(&format!("{stem}_m")))
        })
        .expect("a main program")
}

#[test]
fn every_example_switches_the_laser_at_the_same_ir_points_in_krl_and_gcode() {
    let templates = Templates::builtin().unwrap();
    let mut sources: Vec<_> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lmd"))
        .collect();
    sources.push("tests/cases/duct/small_duct/input.lmd".into());
    sources.sort();
    let mut compared = 0;
    for path in sources {
        let src = std::fs::read_to_string(&path).unwrap();
        let p = crate::support::example::compile_file(&path, &src)
            .program
            .unwrap_or_else(|| panic!("{} compiles", path.display()));
        let want = from_ir(p.ir());
        assert!(
            !want.is_empty(),
            "{}: the laser never switches",
            path.display()
        );
        let (mut robots, mut cncs) = (0, 0);
        for m in p.machines() {
            let mut sink = MemorySink::default();
            lmdc::back::emit(m, &templates, &mut sink).unwrap();
            let got = match m.machine() {
                // A table written in machine coordinates puts its switches
                // where the table brings the part: tests/table.rs turns
                // them back to the part and checks them there.
                Machine::Cnc(c) if lmdc::plan::table::machine_output(c).is_some() => continue,
                Machine::Cnc(c) => {
                    let (_, bytes) = &sink.files[0];
                    let text = std::str::from_utf8(bytes).unwrap();
                    match (p.ir().loop_on_machine(), c.height_sensor) {
                        // A ring's loop computes its heights: rs274 runs it
                        // with the sensor on target.
                        (Some((_, law)), Some(s)) => {
                            if rs274::find_rs274().is_none() {
                                skip::skip(
                                    "every_example_switches_the_laser…",
                                    "rs274",
                                    "run `bash .ci/install-rs274.sh` or set LMDC_RS274",
                                );
                                continue;
                            }
                            let segments = p.ir().ring.as_ref().map_or(0, |r| r.segments.len());
                            let steady = vec![
                                vec![law.target / s.full_scale; segments];
                                p.ir().layers.len()
                            ];
                            let text = m66::scripted(text, s.input, &steady);
                            cncs += 1;
                            from_canon(&rs274::interpret_source(&text).unwrap())
                        }
                        _ => {
                            cncs += 1;
                            from_gcode(text, &c.dialect)
                        }
                    }
                }
                Machine::Robot(r) if r.controller == lmdc::ir::Controller::Abb => {
                    robots += 1;
                    let files: rapid::Files = sink
                        .files
                        .into_iter()
                        .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
                        .collect();
                    let main = files
                        .keys()
                        .filter_map(|n| n.strip_suffix(".mod"))
                        .min_by_key(|n| n.len())
                        .expect("a main module")
                        .to_string();
                    let trace =
                        rapid::run(&files, &main, &rapid::signals(r).0, &rapid::signals(r).1)
                            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                    from_motions(
                        trace
                            .motions
                            .iter()
                            .filter_map(|m| m.pose().map(|t| (m.laser, t.pos))),
                        trace.laser_at_end,
                    )
                }
                Machine::Robot(r) => {
                    robots += 1;
                    let files: krl::Files = sink
                        .files
                        .into_iter()
                        .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
                        .collect();
                    let main = main_program(&files);
                    match (p.ir().loop_on_machine(), r.height_sensor) {
                        // A ring's loop, run with the sensor on target.
                        (Some((_, law)), Some(s)) => {
                            let run = krl_run::run_steady(
                                &files,
                                &main,
                                r.laser_out.number().unwrap(),
                                r.power_out.number().unwrap(),
                                law.target / s.full_scale,
                            )
                            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                            from_motions(
                                run.motions.iter().map(|m| (m.laser, m.pos)),
                                run.laser_at_end,
                            )
                        }
                        _ => {
                            let trace = krl::run(
                                &files,
                                &main,
                                r.laser_out.number().unwrap(),
                                r.power_out.number().unwrap(),
                            )
                            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                            from_krl(&trace)
                        }
                    }
                }
            };
            assert_eq!(
                got.len(),
                want.len(),
                "{} on {}: {} switches, the IR has {}",
                path.display(),
                m.machine().name(),
                got.len(),
                want.len()
            );
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert_eq!(
                    g,
                    w,
                    "{} on {}: switch {k} differs",
                    path.display(),
                    m.machine().name()
                );
            }
        }
        assert!(
            robots > 0 && (cncs > 0 || !skip::in_ci() && rs274::find_rs274().is_none()),
            "{}: needs a robot and a CNC",
            path.display()
        );
        compared += 1;
    }
    assert!(compared >= 4);
}

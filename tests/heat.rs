//! Cooling between layers: with `min_layer_time` every layer, read back from the
//! programs (G-code by its moves and G4 dwells, KRL by the test interpreter's
//! LINs and WAIT SECs), takes at least the minimum; with `dwell` every layer
//! but the last is followed by at least that wait, at the retracted position
//! with the laser off.

use crate::support::krl_check as krl;
use crate::support::krl_parser;

use lmdc::back::{MemorySink, Templates};
use lmdc::ir::Machine;
use lmdc::pipeline::compile;

fn tooth(process: &str) -> lmdc::verify::Verified {
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace(
            "  defocus = -3 mm\n",
            &format!("  defocus = -3 mm\n  {process}\n"),
        );
    let c = compile(&src, &mut ());
    c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics))
}

/// Per layer of a G-code program: (time of its G1 moves at their F, dwell after it).
fn gcode_layers(text: &str) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let (mut pos, mut f) = ([0.0f64; 3], 0.0f64);
    for l in text.lines() {
        if l.starts_with("(layer ") {
            out.push((0.0, 0.0));
            continue;
        }
        let mut w = l.split_whitespace();
        match w.next() {
            Some("G4") => {
                let s: f64 = w
                    .next()
                    .unwrap()
                    .strip_prefix('P')
                    .unwrap()
                    .parse()
                    .unwrap();
                out.last_mut().unwrap().1 += s;
            }
            Some(g @ ("G0" | "G1")) => {
                let mut to = pos;
                for word in w {
                    let (k, v) = word.split_at(1);
                    let v: f64 = v.parse().unwrap();
                    match k {
                        "X" => to[0] = v,
                        "Y" => to[1] = v,
                        "Z" => to[2] = v,
                        "F" => f = v / 60.0,
                        _ => {}
                    }
                }
                if g == "G1" {
                    let d = (0..3).map(|i| (to[i] - pos[i]).powi(2)).sum::<f64>().sqrt();
                    if let Some(last) = out.last_mut() {
                        last.0 += d / f;
                    }
                }
                pos = to;
            }
            _ => {}
        }
    }
    out
}

fn emit_all(p: &lmdc::verify::Verified) -> Vec<(Machine, Vec<(String, String)>)> {
    p.machines()
        .map(|m| {
            let mut sink = MemorySink::default();
            lmdc::back::emit(m, &Templates::builtin().unwrap(), &mut sink).unwrap();
            let files = sink
                .files
                .into_iter()
                .map(|(n, b)| (n, String::from_utf8(b).unwrap()))
                .collect();
            (m.machine().clone(), files)
        })
        .collect()
}

fn krl_trace(files: Vec<(String, String)>, r: &lmdc::ir::Robot) -> krl::Trace {
    let files: krl::Files = files.into_iter().collect();
    krl::run(&files, "sprocket_tooth_kr30", r.laser_out, r.power_out).unwrap()
}

#[test]
fn every_layer_takes_at_least_the_minimum_layer_time() {
    // A layer of the tooth lays 15 tracks of ≤ 40 mm at 6 mm/s: about 100 s.
    let p = tooth("min_layer_time = 200 s");
    let layers = p.ir().layers.len();
    for (m, files) in emit_all(&p) {
        match m {
            Machine::Cnc(_) => {
                let per = gcode_layers(&files[0].1);
                assert_eq!(per.len(), layers);
                for (i, (t, dwell)) in per[..layers - 1].iter().enumerate() {
                    assert!(
                        t + dwell >= 200.0 - 0.01,
                        "layer {}: {t} s + {dwell} s",
                        i + 1
                    );
                    assert!(
                        *dwell > 0.0 && *t > 50.0,
                        "layer {}: {t} s + {dwell} s",
                        i + 1
                    );
                }
                assert_eq!(per[layers - 1].1, 0.0, "no dwell after the last layer");
            }
            Machine::Robot(r) => {
                let trace = krl_trace(files, &r);
                assert_eq!(trace.waits.len(), layers - 1);
                let mut from = 0;
                for &(upto, wait) in &trace.waits {
                    let t: f64 = trace.lins[from.max(1)..upto]
                        .iter()
                        .enumerate()
                        .map(|(k, l)| {
                            let prev = &trace.lins[from.max(1) + k - 1];
                            let d = (0..3)
                                .map(|i| (l.pos[i] - prev.pos[i]).powi(2))
                                .sum::<f64>()
                                .sqrt();
                            d / l.speed
                        })
                        .sum();
                    assert!(t + wait >= 200.0 - 0.01, "{t} s + {wait} s");
                    from = upto;
                }
            }
        }
    }
}

#[test]
fn a_declared_dwell_follows_every_layer_but_the_last() {
    let p = tooth("dwell = 4.5 s");
    let layers = p.ir().layers.len();
    for (m, files) in emit_all(&p) {
        match m {
            Machine::Cnc(_) => {
                let text = &files[0].1;
                assert_eq!(text.matches("\nG4 P4.5\n").count(), layers - 1, "{text}");
                // Laser off and retracted first: M5, then G0 up, then the dwell.
                let before: Vec<&str> = text
                    .split("\nG4 P4.5\n")
                    .next()
                    .unwrap()
                    .lines()
                    .rev()
                    .take(2)
                    .collect();
                assert!(
                    before[0].starts_with("G0 ") && before[1] == "M5",
                    "{before:?}"
                );
            }
            Machine::Robot(r) => {
                // The public KRL grammar reads WAIT SEC in a motion module.
                if krl_parser::find_krl_parser().is_some() {
                    let srcs: Vec<(&str, &str)> = files
                        .iter()
                        .map(|(n, t)| (n.as_str(), t.as_str()))
                        .collect();
                    krl_parser::parse_sources(&srcs).unwrap();
                } else {
                    assert!(
                        std::env::var_os("CI").is_none(),
                        "CI is set but the KRL oracle is missing"
                    );
                }
                let trace = krl_trace(files, &r);
                assert_eq!(trace.waits.len(), layers - 1);
                assert!(trace.waits.iter().all(|&(_, s)| s == 4.5));
            }
        }
    }
}

#[test]
fn no_cooling_asked_no_dwell_written() {
    let p = tooth("");
    for (_, files) in emit_all(&p) {
        for (name, text) in files {
            assert!(
                !text.contains("WAIT SEC 4") && !text.contains("\nG4 "),
                "{name}"
            );
        }
    }
}

#[test]
fn cooling_times_are_checked() {
    let src = std::fs::read_to_string("examples/sprocket_tooth.lmd")
        .unwrap()
        .replace(
            "  defocus = -3 mm\n",
            "  defocus = -3 mm\n  min_layer_time = -5 s\n  dwell = 2 mm\n",
        );
    let c = compile(&src, &mut ());
    assert!(c.program.is_none());
    let msgs: Vec<String> = c.diagnostics.iter().map(|d| d.message.clone()).collect();
    assert_eq!(c.diagnostics.error_count(), 2, "{msgs:?}");
}

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
    krl::run(
        &files,
        "sprocket_tooth_kr30",
        r.laser_out.number().unwrap(),
        r.power_out.number().unwrap(),
    )
    .unwrap()
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

/// Whether every deposit move of every machine's plan of `p` runs from its
/// IR point to the next: the laser lays nothing on a move the IR does not
/// have (down from where the nozzle waited, across a gap). Returns how
/// many deposits were checked, or the first that does not.
fn deposits_start_at_their_points(p: &lmdc::ir::Program) -> Result<usize, String> {
    use lmdc::plan::{Move, MoveKind, Plan, Visit, Where};
    struct Check<'a> {
        p: &'a lmdc::ir::Program,
        last: Option<[f64; 3]>,
        n: usize,
        bad: Option<String>,
    }
    impl Visit for Check<'_> {
        fn motion(&mut self, m: &Move) {
            if m.kind == MoveKind::Deposit && self.bad.is_none() {
                let Where::Point { layer, path, point } = m.at else {
                    self.bad = Some(format!("a deposit at {}", m.at));
                    return;
                };
                let pts = &self.p.layers[layer].paths[path].points;
                let (from, to) = (pts[point - 1].focus(), pts[point].focus());
                let off = |a: [f64; 3], b: [f64; 3]| {
                    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
                };
                match self.last {
                    Some(l) if off(l, from) < 1e-9 && off(m.to, to) < 1e-9 => self.n += 1,
                    l => {
                        self.bad = Some(format!(
                            "the deposit to {} starts at {l:?}, its IR point is at {from:?}",
                            m.at
                        ))
                    }
                }
            }
            self.last = Some(m.to);
        }
    }
    let mut n = 0;
    for m in &p.machines {
        let mut c = Check {
            p,
            last: None,
            n: 0,
            bad: None,
        };
        Plan::new(p, m).walk(&mut c);
        if let Some(b) = c.bad {
            return Err(format!("{}: {b}", m.name()));
        }
        n += c.n;
    }
    Ok(n)
}

/// Every example, and every example cooled by a dwell between layers (the
/// nozzle backs off to wait): each deposit move runs between its IR
/// points. A spiral wall, one run of deposits from layer to layer, once
/// switched its laser on where it waited, 10 mm up, and laid the next
/// layer's first bead on the way down.
#[test]
fn every_deposit_runs_between_its_ir_points_cooled_or_not() {
    let mut files = crate::support::example::files();
    // The planar one-bead wall climbing in a spiral, as its golden case.
    files.push("tests/cases/planar/spiral_wall/input.lmd".into());
    let mut cooled = 0;
    for f in &files {
        let src = std::fs::read_to_string(f).unwrap();
        let mut variants = vec![("as written", src.clone())];
        // A ring is laid in one run and refuses a dwell; a spiral wall
        // stops for it.
        let ring = src.contains("slicing continuous");
        if !ring && !src.contains("dwell") && src.contains("\nprocess {\n") {
            variants.push((
                "with a dwell",
                src.replacen("\nprocess {\n", "\nprocess {\n  dwell = 5 s\n", 1),
            ));
        }
        for (how, src) in variants {
            let c = crate::support::example::compile_file(f, &src);
            let Some(v) = c.program else {
                panic!(
                    "{} ({how}) does not build: {:?}",
                    f.display(),
                    c.diagnostics
                );
            };
            let p = v.ir();
            if how != "as written" && p.continuous {
                cooled += 1;
            }
            match deposits_start_at_their_points(p) {
                Ok(n) => assert!(n > 0, "{} ({how}): no deposits", f.display()),
                Err(e) => panic!("{} ({how}): {e}", f.display()),
            }
        }
    }
    // The two spiral walls (normal-sliced and planar), cooled.
    assert!(cooled >= 2, "{cooled} continuous programs cooled");
}

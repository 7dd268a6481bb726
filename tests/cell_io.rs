//! Gas and powder, read back from both programs: every laser start has the gas
//! flowing for at least its `pre_flow` and the powder running for at least its
//! `arrival` time (since the feeder started or changed rate), the feeder is off
//! through long cooling dwells, and at the end the laser goes off first, then
//! the powder, then, `post_flow` later, the gas. Time is counted from the
//! programs as a control runs them: feed moves at their speed (KRL: every LIN
//! at its `$VEL.CP`), dwells and waits; G0 moves count as instant.
//! Also: what a wrong declaration gets.

use crate::support::example;
use crate::support::krl_check as krl;
use crate::support::krl_parser;
use crate::support::rs274;
use crate::support::skip;

use lmdc::back::{MemorySink, Templates};
use lmdc::diag::Code;
use lmdc::ir::Machine;
use lmdc::pipeline::compile;

const PRE_FLOW: f64 = 2.0;
const POST_FLOW: f64 = 5.0;
const ARRIVAL: f64 = 2.5;

/// The sprocket tooth on its robot and its mill, with gas and powder
/// declared on both, and `process` added to its process block.
fn tooth(process: &str) -> String {
    let io = |gas: u16, powder: u16, rate: u16| {
        format!(
            "  gas {{\n    output = {gas}\n    pre_flow = {PRE_FLOW} s\n    post_flow = {POST_FLOW} s\n  }}\n  \
             powder {{\n    output = {powder}\n    arrival = {ARRIVAL} s\n    rate_output = {rate}\n    full_scale = 60 g/min\n  }}\n"
        )
    };
    example::tooth(&[
        (
            "  defocus = -3 mm\n",
            &format!("  defocus = -3 mm\n  {process}\n"),
        ),
        (
            "  clearance = 5 mm\n}\n\nmachine mill3",
            &format!("  clearance = 5 mm\n{}}}\n\nmachine mill3", io(2, 3, 2)),
        ),
        (
            "    z = -20 mm .. 100 mm\n  }\n",
            &format!("    z = -20 mm .. 100 mm\n  }}\n{}", io(0, 1, 0)),
        ),
    ])
}

fn build(src: &str) -> MemorySink {
    let c = compile(src, &mut ());
    let program = c.program.unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    let mut sink = MemorySink::default();
    lmdc::pipeline::emit(&program, &Templates::builtin().unwrap(), &mut sink, &mut ()).unwrap();
    sink
}

/// What a timeline saw: laser starts, each with the gas and powder times
/// before it; the feeder's state at each start; the end's order.
#[derive(Default, Debug)]
struct Timeline {
    t: f64,
    laser: bool,
    gas: Option<f64>,
    powder: Option<f64>,
    /// (gas time, powder time) at every laser start.
    starts: Vec<(f64, f64)>,
    last_laser_off: f64,
    /// Time from the last laser stop to the gas closing.
    gas_after: Option<f64>,
    /// Cooling waits the feeder was off through.
    powder_off_waits: usize,
    /// Rates set on the feed-rate output, fractions of full scale.
    rates: Vec<f64>,
}

impl Timeline {
    fn laser(&mut self, on: bool) {
        if on && !self.laser {
            let since = |s: Option<f64>| s.map_or(f64::NEG_INFINITY, |s| self.t - s);
            self.starts.push((since(self.gas), since(self.powder)));
        }
        if !on && self.laser {
            self.last_laser_off = self.t;
        }
        self.laser = on;
    }

    fn out(&mut self, gas: bool, on: bool) {
        assert!(!self.laser, "gas or powder switched with the laser on");
        match (gas, on) {
            (true, true) => self.gas = Some(self.t),
            (true, false) => {
                self.gas = None;
                self.gas_after = Some(self.t - self.last_laser_off);
            }
            (false, true) => self.powder = Some(self.t),
            (false, false) => self.powder = None,
        }
    }

    fn wait(&mut self, s: f64) {
        if self.powder.is_none() && self.gas.is_some() && s > 0.0 {
            self.powder_off_waits += 1;
        }
        self.t += s;
    }

    fn check(&self, layers: usize) {
        assert!(!self.starts.is_empty());
        for (i, &(gas, powder)) in self.starts.iter().enumerate() {
            assert!(gas >= PRE_FLOW - 1e-9, "start {i}: gas for {gas} s");
            assert!(powder >= ARRIVAL - 1e-9, "start {i}: powder for {powder} s");
        }
        assert!(self.gas.is_none() && self.powder.is_none(), "left on");
        let after = self.gas_after.expect("the gas never closes");
        assert!(
            after >= POST_FLOW - 1e-9,
            "gas closes {after} s after the laser"
        );
        // `dwell = 10 s` between layers, longer than the arrival: the feeder
        // stops through every one (and the gas's post-flow at the end).
        assert_eq!(self.powder_off_waits, layers - 1 + 1);
        // 8 g/min of 60 g/min full scale, as the output writes it.
        assert!(self.rates.iter().all(|&x| (x - 8.0 / 60.0).abs() < 1e-4));
        assert_eq!(self.rates.len(), layers, "set at every start of the feeder");
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

#[test]
fn the_krl_program_has_gas_and_powder_ready_at_every_laser_start() {
    let sink = build(&tooth("dwell = 10 s"));
    let files: krl::Files = sink
        .files
        .iter()
        .filter(|(n, _)| n.ends_with(".src") || n.ends_with(".dat"))
        .map(|(n, b)| (n.clone(), String::from_utf8(b.clone()).unwrap()))
        .collect();
    let trace = krl::run(&files, "sprocket_tooth_kr30", 1, 1).unwrap();
    let mut tl = Timeline::default();
    let mut at: Option<[f64; 3]> = None;
    for e in &trace.events {
        match *e {
            krl::Event::Lin(i) => {
                let l = &trace.lins[i];
                // A TRIGGER at DISTANCE=0 switches at the motion's start.
                tl.laser(l.laser);
                if let Some(a) = at {
                    tl.t += dist(a, l.pos) / l.speed;
                }
                at = Some(l.pos);
            }
            krl::Event::Wait(s) => tl.wait(s),
            krl::Event::Out(2, on) => tl.out(true, on),
            krl::Event::Out(3, on) => tl.out(false, on),
            krl::Event::Anout(2, x) => tl.rates.push(x),
            ref e => panic!("unexpected {e:?}"),
        }
    }
    tl.laser(false);
    tl.check(35);
    // And the KRL grammar reads the outputs' lines.
    if krl_parser::find_krl_parser().is_none() {
        skip::skip(
            "the_krl_program_has_gas_and_powder_ready_at_every_laser_start",
            "krlcheck",
            "sh ../shared/tools/krlcheck/install.sh",
        );
        return;
    }
    let texts: Vec<(&str, &str)> = files
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    krl_parser::parse_sources(&texts).unwrap();
}

#[test]
fn the_gcode_program_has_gas_and_powder_ready_at_every_laser_start() {
    if rs274::find_rs274().is_none() {
        skip::skip(
            "the_gcode_program_has_gas_and_powder_ready_at_every_laser_start",
            "rs274",
            "bash .ci/install-rs274.sh",
        );
        return;
    }
    let sink = build(&tooth("dwell = 10 s"));
    let text = sink.text("sprocket_tooth_mill3.ngc").unwrap();
    let calls = rs274::interpret_source(&text).unwrap();
    let mut tl = Timeline::default();
    let (mut at, mut feed) = (None::<[f64; 3]>, 0.0);
    for c in rs274::program_body(&calls) {
        use rs274::CanonCall as C;
        match *c {
            C::Feed { x, y, z, .. } => {
                if let Some(a) = at {
                    tl.t += dist(a, [x, y, z]) / (feed / 60.0);
                }
                at = Some([x, y, z]);
            }
            C::Traverse { x, y, z, .. } => at = Some([x, y, z]),
            C::FeedRate(f) if f > 0.0 => feed = f,
            C::SpindleOn => tl.laser(true),
            C::SpindleOff => tl.laser(false),
            C::Dwell(s) => tl.wait(s),
            C::DigitalOut { index, on, synced } => {
                assert!(!synced, "M64/M65: they wait for the motion before them");
                tl.out(index == 0, on);
            }
            C::AnalogOut {
                index: 0, value, ..
            } => tl.rates.push(value),
            _ => {}
        }
    }
    tl.check(35);
}

#[test]
fn a_machine_without_gas_or_powder_writes_the_same_program_as_before() {
    // The IR of a plan with a bead model is version 4 with or without cell
    // I/O, and without it nothing switches.
    let c = compile(&example::tooth(&[]), &mut ());
    let p = c.program.unwrap();
    assert_eq!(p.ir().version, lmdc::ir::VERSION);
    let c = compile(&tooth(""), &mut ());
    assert_eq!(c.program.unwrap().ir().version, lmdc::ir::VERSION);
    let sink = build(&example::tooth(&[]));
    let text = sink.text("sprocket_tooth_mill3.ngc").unwrap();
    assert!(!text.contains("M64") && !text.contains("M68"));
}

fn codes(src: &str) -> Vec<(Code, String)> {
    let c = compile(src, &mut ());
    assert!(c.program.is_none(), "compiled");
    c.diagnostics
        .iter()
        .filter(|d| d.severity == lmdc::diag::Severity::Error)
        .map(|d| (d.code, d.message.clone()))
        .collect()
}

#[test]
fn wrong_declarations_are_reported_together() {
    let src = tooth("").replace(
        "  gas {\n    output = 2\n",
        // The robot's laser is on $OUT[1].
        "  gas {\n    output = 1\n",
    );
    let src = src.replacen("    arrival = 2.5 s\n", "", 1).replacen(
        "dialect = linuxcnc",
        "dialect = fagor8070",
        1,
    );
    let got = codes(&src);
    let has = |code: Code, text: &str| {
        assert!(
            got.iter().any(|(c, m)| *c == code && m.contains(text)),
            "{code:?} `{text}` not in {got:#?}"
        )
    };
    has(
        Code::OutputClash,
        "the gas valve and the laser are both on digital output 1",
    );
    has(Code::MissingField, "`powder` needs `arrival`");
    has(Code::IoDialect, "no built-in `output_on`");
    has(Code::IoDialect, "no built-in `analog_output`");
}

#[test]
fn own_output_lines_serve_another_dialect() {
    let src = tooth("").replacen(
        "dialect = linuxcnc",
        "dialect = fagor8070\n  output_on = \"M10 P{n}\"\n  output_off = \"M11 P{n}\"\n  analog_output = \"M12 E{n} Q{v}\"",
        1,
    );
    let sink = build(&src);
    let text = sink.text("sprocket_tooth_mill3.nc").unwrap();
    assert!(
        text.contains("M10 P0 ;gas on") || text.contains("M10 P0 ; gas on"),
        "{}",
        &text[..800]
    );
    assert!(text.contains("M12 E0 Q0.1333"));
    // A line without its `{n}` is refused.
    let bad = src.replacen("\"M10 P{n}\"", "\"M10\"", 1);
    assert!(codes(&bad)
        .iter()
        .any(|(c, m)| *c == Code::ProgramText && m.contains("`output_on` must hold `{n}` once")));
}

#[test]
fn a_feed_beyond_the_rate_outputs_full_scale_is_an_error() {
    let src = tooth("").replace("full_scale = 60 g/min", "full_scale = 5 g/min");
    let got = codes(&src);
    assert!(
        got.iter().any(|(c, m)| *c == Code::PowderRate
            && m.contains(
                "would feed 8 g/min, beyond its feed-rate output's full_scale of 5 g/min"
            )),
        "{got:#?}"
    );
    // Both machines.
    assert_eq!(
        got.iter().filter(|(c, _)| *c == Code::PowderRate).count(),
        2
    );
}

#[test]
fn machine_is_plain_data_in_the_ir() {
    let c = compile(&tooth(""), &mut ());
    let p = c.program.unwrap();
    let Machine::Robot(r) = &p.ir().machines[0] else {
        panic!()
    };
    let f = r.cell.powder.clone().unwrap();
    assert_eq!(
        (&f.output, f.arrival),
        (&lmdc::ir::Signal::Number(3), ARRIVAL)
    );
    assert_eq!(f.rate.unwrap().full_scale, 60.0);
    let json = serde_json::to_value(p.ir()).unwrap();
    assert_eq!(json["machines"][0]["cell"]["gas"]["pre_flow"], PRE_FLOW);
    assert_eq!(json["machines"][1]["cell"]["output_on"], "M64 P{n}");
}

/// The segmented ring with gas and powder on its robot and its mill.
fn ring_with_cell() -> String {
    let io = |g: u16, p: u16, r: u16| {
        format!(
            "  gas {{\n    output = {g}\n    pre_flow = {PRE_FLOW} s\n    post_flow = {POST_FLOW} s\n  }}\n  \
             powder {{\n    output = {p}\n    arrival = {ARRIVAL} s\n    rate_output = {r}\n    full_scale = 20 g/min\n  }}\n"
        )
    };
    // The robot's block ends after its `height_delay` line, however the
    // formatter aligns that line's comment.
    let src = example::edited(
        "segmented_ring.lmd",
        &[(
            "    z = -20 mm .. 60 mm\n  }\n}",
            &format!("    z = -20 mm .. 60 mm\n  }}\n{}}}", io(0, 1, 0)),
        )],
    );
    let at = src
        .find("  height_delay = 150 ms")
        .expect("the robot's height_delay");
    let end = at + src[at..].find('\n').unwrap() + 1;
    assert!(src[end..].starts_with('}'), "the robot's block ends there");
    format!("{}{}{}", &src[..end], io(2, 3, 2), &src[end..])
}

#[test]
fn a_ring_whose_loop_runs_on_the_machine_switches_gas_and_powder_too() {
    // The looping programs are written by their own writers (src/back/ring.rs):
    // gas and powder come before the first laser start and after the last stop.
    let sink = build(&ring_with_cell());
    let krl = sink.text("segmented_ring_kr60_m001.src").unwrap();
    let at = |text: &str, what: &str| {
        text.find(what)
            .unwrap_or_else(|| panic!("no `{what}` in the program"))
    };
    let laser_on = at(&krl, "DO $OUT[1]=TRUE");
    let prepare = at(&krl, "WAIT SEC 0 ; advance-run stop: the outputs switch here\n$OUT[2]=TRUE ; gas on\n$ANOUT[2]=0.3000 ; powder 6 g/min\n$OUT[3]=TRUE ; powder on\nWAIT SEC 2.50\n");
    assert!(prepare < laser_on);
    let laser_off = at(&krl, "DO $OUT[1]=FALSE");
    let finish = at(
        &krl,
        "$OUT[3]=FALSE ; powder off\nWAIT SEC 5.00\n$OUT[2]=FALSE ; gas off\n",
    );
    assert!(finish > laser_off);

    if rs274::find_rs274().is_none() {
        skip::skip(
            "a_ring_whose_loop_runs_on_the_machine_switches_gas_and_powder_too",
            "rs274",
            "bash .ci/install-rs274.sh",
        );
        return;
    }
    let ngc = sink.text("segmented_ring_mill3.ngc").unwrap();
    let calls = rs274::interpret_source(&ngc).unwrap();
    use rs274::CanonCall as C;
    let body = rs274::program_body(&calls);
    let first_on = body.iter().position(|c| *c == C::SpindleOn).unwrap();
    let last_off = body.iter().rposition(|c| *c == C::SpindleOff).unwrap();
    let outs = |range: &[C]| -> Vec<C> {
        range
            .iter()
            .filter(|c| matches!(c, C::DigitalOut { .. } | C::AnalogOut { .. } | C::Dwell(_)))
            .cloned()
            .collect()
    };
    let dout = |index, on| C::DigitalOut {
        index,
        on,
        synced: false,
    };
    let before = outs(&body[..first_on]);
    assert_eq!(
        before,
        [
            dout(0, true),
            C::AnalogOut {
                index: 0,
                value: 0.3,
                synced: false
            },
            dout(1, true),
            C::Dwell(ARRIVAL),
        ]
    );
    // After the last stop (M2 also stops the spindle): the powder, the
    // post-flow, the gas.
    let after: Vec<C> = outs(&body[..=last_off]).into_iter().rev().take(3).collect();
    assert_eq!(after, [dout(0, false), C::Dwell(POST_FLOW), dout(1, false)]);
}

//! The motion plan as JSON lines (`lmdc build --emit plan`, docs/plan.md):
//! one object a line, in the order the machine does things, for users'
//! checks of what the machine will do. Each object has a `type`: `layer`,
//! `move`, `laser`, `dwell`, `io`, `segment_end`. A `move` carries the
//! laser and the cell's state during it.

use super::{Io, Move, MoveKind, Plan, SegmentEnd, Speed, Visit, Where};
use crate::ir::{Layer, Machine};
use serde_json::{json, Value};
use std::io::Write;

/// Writes `plan` (of `machine`) as JSON lines into `out`.
pub fn write(plan: &Plan<'_>, machine: &Machine, out: &mut dyn Write) -> std::io::Result<()> {
    let axes = match machine {
        Machine::Cnc(c) => match c.effective_kinematics().tilt_letter() {
            None => None,
            Some('B') => Some("B"),
            Some(_) => Some("A"),
        },
        Machine::Robot(_) => None,
    };
    let mut w = Lines {
        out,
        axes,
        laser: false,
        gas: false,
        powder: None,
        error: None,
    };
    plan.walk(&mut w);
    match w.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct Lines<'o> {
    out: &'o mut dyn Write,
    /// The tilt axis's letter on a tilting head (`None`: no rotary axes).
    axes: Option<&'static str>,
    laser: bool,
    gas: bool,
    /// The powder feed, g/min, while the feeder runs.
    powder: Option<f32>,
    error: Option<std::io::Error>,
}

impl Lines<'_> {
    fn line(&mut self, v: Value) {
        if self.error.is_none() {
            if let Err(e) = writeln!(self.out, "{v}") {
                self.error = Some(e);
            }
        }
    }
}

fn kind(k: MoveKind) -> &'static str {
    match k {
        MoveKind::Deposit => "deposit",
        MoveKind::Approach => "approach",
        MoveKind::Retract => "retract",
        MoveKind::Travel => "travel",
        MoveKind::LeadIn => "lead_in",
        MoveKind::LeadOut => "lead_out",
        MoveKind::Lift => "lift",
        MoveKind::FromHome => "from_home",
        MoveKind::Home => "home",
    }
}

fn place(at: Where) -> Value {
    match at {
        Where::Point { layer, path, point } => {
            json!({"layer": layer, "path": path, "point": point})
        }
        Where::Clearance { layer, path } => json!({"layer": layer, "path": path}),
        Where::End => json!("end"),
    }
}

impl Visit for Lines<'_> {
    fn layer(&mut self, index: usize, _layer: &Layer) {
        self.line(json!({"type": "layer", "index": index}));
    }
    fn laser_on(&mut self, _next: &Move) {
        self.laser = true;
        self.line(json!({"type": "laser", "on": true}));
    }
    fn laser_off(&mut self) {
        self.laser = false;
        self.line(json!({"type": "laser", "on": false}));
    }
    fn motion(&mut self, m: &Move) {
        let speed = match m.speed {
            Speed::Rapid => json!("rapid"),
            Speed::Feed(v) => json!(v),
        };
        let axes = self
            .axes
            .map(|t| json!({ t: m.axes.tilt, "C": m.axes.c }))
            .unwrap_or(Value::Null);
        self.line(json!({
            "type": "move",
            "kind": kind(m.kind),
            "to": m.to,
            "normal": m.normal,
            "axes": axes,
            "speed": speed,
            "power": if self.laser { m.power } else { 0.0 },
            "laser": self.laser,
            "gas": self.gas,
            "powder": self.powder,
            "from": place(m.at),
        }));
    }
    fn dwell(&mut self, seconds: f64) {
        self.line(json!({"type": "dwell", "seconds": seconds}));
    }
    fn io(&mut self, event: Io) {
        let (name, rate) = match event {
            Io::GasOn => {
                self.gas = true;
                ("gas_on", None)
            }
            Io::GasOff => {
                self.gas = false;
                ("gas_off", None)
            }
            Io::PowderOn(r) => {
                self.powder = Some(r);
                ("powder_on", Some(r))
            }
            Io::PowderRate(r) => {
                self.powder = Some(r);
                ("powder_rate", Some(r))
            }
            Io::PowderOff => {
                self.powder = None;
                ("powder_off", None)
            }
        };
        self.line(json!({"type": "io", "event": name, "rate": rate}));
    }
    fn segment_end(&mut self, end: SegmentEnd) {
        self.line(json!({"type": "segment_end", "layer": end.layer, "segment": end.segment, "last": end.last}));
    }
}

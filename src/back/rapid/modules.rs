//! The streaming module writer of RAPID: motion instructions go into the
//! routine of the current motion module; when it holds `max_lines` of them
//! the module is closed (rendered through `rapid/module.mod.tera`, written
//! to the sink) and the next begins, so memory is bounded by a module.
//!
//! A motion is held back until the next one says how it ends (`fine` where
//! the plan stops or the next motion switches the laser at its start, the
//! zone `lmd_z` otherwise) and whether the laser switches at its end, which
//! turns it from a `MoveL` into a `TriggL`.

use crate::back::{EmitError, Sink, Templates};
use crate::numbers::{push_fixed, push_trimmed, push_u64};
use crate::target::names::KrlNames;
use crate::target::rapid::{AO_DECIMALS, POS_DECIMALS, QUAT_DECIMALS};
use std::io::Write;

/// Marker the module template's `body` variable is rendered as.
const BODY: &str = "\u{1}lmdc-body\u{1}";

/// Where a trigger fires on its motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum At {
    /// Where the motion starts (`\Start`).
    Start,
    /// Where it ends.
    End,
}

/// What a trigger sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Set {
    /// The laser's digital output on or off.
    Laser(bool),
    /// The power's analog output, a fraction of full scale.
    Power(f64),
}

impl Set {
    /// The `triggdata` a trigger of this kind at `at` uses: one variable
    /// per kind and place, so one motion's triggers never share one.
    fn var(self, at: At) -> &'static str {
        match (self, at) {
            (Set::Laser(true), At::Start) => "lmd_on",
            (Set::Laser(false), At::Start) => "lmd_off",
            (Set::Power(_), At::Start) => "lmd_power",
            (Set::Laser(true), At::End) => "lmd_on_end",
            (Set::Laser(false), At::End) => "lmd_off_end",
            (Set::Power(_), At::End) => "lmd_power_end",
        }
    }
}

/// Every `triggdata` the motion modules may use, declared in the main
/// module.
pub const TRIGGERS: [&str; 6] = [
    "lmd_on",
    "lmd_off",
    "lmd_power",
    "lmd_on_end",
    "lmd_off_end",
    "lmd_power_end",
];

/// A position as a `robtarget` writes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// x, y, z in the work object, mm.
    pub pos: [f64; 3],
    /// The orientation, `[q1, q2, q3, q4]` (`q1` the scalar part).
    pub quat: [f64; 4],
    /// `[cf1, cf4, cf6, cfx]`.
    pub conf: [i32; 4],
    /// A positioner's two axes, deg.
    pub ext: Option<[f64; 2]>,
}

/// Counts of what was written, for the main module's comments.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Motion instructions in all modules.
    pub moves: u64,
    /// Those with the laser on.
    pub deposits: u64,
    /// Laser switch-ons.
    pub laser_ons: u64,
}

/// A motion waiting for how it ends.
struct Pending {
    /// `MoveL ` / `MoveJ ` and the target, then `, <speed>`.
    head: Vec<u8>,
    /// Its triggers, start ones first.
    triggers: Vec<(Set, At)>,
    /// `MoveJ` (from home): always `fine`.
    joint: bool,
}

/// Writes the motion modules of one robot program.
pub struct Modules<'a> {
    sink: &'a mut dyn Sink,
    t: &'a Templates,
    base: tera::Context,
    names: KrlNames,
    max_lines: usize,
    /// The laser's digital signal and its power's analog one
    /// ([`crate::target::rapid::signal`]).
    laser_out: String,
    power_out: String,
    body: Vec<u8>,
    lines: usize,
    pending: Option<Pending>,
    /// Layer comment lines waiting for the layer's first motion.
    pre: Vec<u8>,
    pre_layer: Option<usize>,
    layers: Option<(usize, usize)>,
    current: usize,
    continues: usize,
    /// The robot stands still after the last instruction (`WaitRob \InPos`
    /// or `WaitTime \InPos`).
    at_rest: bool,
    modules: Vec<String>,
    error: Option<EmitError>,
    /// What has been written.
    pub stats: Stats,
}

impl<'a> Modules<'a> {
    /// A writer naming modules by `names`, switching the laser on the
    /// signal `laser_out` (`do1`, `doLaserOn`) and its power on
    /// `power_out` (`ao2`, `aoLaserPower`).
    pub fn new(
        sink: &'a mut dyn Sink,
        t: &'a Templates,
        base: tera::Context,
        names: KrlNames,
        max_lines: usize,
        [laser_out, power_out]: [String; 2],
    ) -> Self {
        Modules {
            sink,
            t,
            base,
            names,
            max_lines: max_lines.max(1),
            laser_out,
            power_out,
            body: Vec::with_capacity(1 << 16),
            lines: 0,
            pending: None,
            pre: Vec::new(),
            pre_layer: None,
            layers: None,
            current: 0,
            continues: 0,
            at_rest: false,
            modules: Vec::new(),
            error: None,
            stats: Stats::default(),
        }
    }

    /// A layer's comment lines (`! …`), placed before its first motion.
    pub fn layer(&mut self, number: usize, text: &str) {
        for l in text.lines().filter(|l| !l.trim().is_empty()) {
            self.pre.extend_from_slice(b"    ");
            self.pre.extend_from_slice(l.trim_end().as_bytes());
            self.pre.push(b'\n');
        }
        self.pre_layer = Some(number);
    }

    fn place_pre(&mut self) {
        if let Some(number) = self.pre_layer.take() {
            self.body.extend_from_slice(&self.pre);
            self.pre.clear();
            self.layers = Some(match self.layers {
                Some((first, _)) => (first, number),
                None => (number, number),
            });
            self.current = number;
        }
    }

    /// Opens a motion instruction: the module rolls over when full, the
    /// motion before ends (`fine` when `stop`), the layer's comments go
    /// first.
    fn open(&mut self, stop: bool) {
        self.end_pending(!stop);
        self.at_rest = false;
        if self.lines >= self.max_lines {
            self.roll();
        }
        self.place_pre();
    }

    /// A linear motion to `to` at the speed `speed` (a `speeddata`'s
    /// name), with the triggers `start` fires where it starts (the motion
    /// before then ends `fine` when one switches the laser).
    pub fn line(&mut self, to: &Target, speed: &str, start: &[Set], deposit: bool) {
        let stop = start.iter().any(|s| matches!(s, Set::Laser(_)));
        if start.contains(&Set::Laser(true)) {
            self.stats.laser_ons += 1;
        }
        let triggers = start.iter().map(|s| (*s, At::Start)).collect();
        self.motion(b"MoveL ", to, speed, triggers, stop);
        if deposit {
            self.stats.deposits += 1;
        }
    }

    /// The move from home to the first position: a `MoveJ` at `speed`,
    /// ending `fine`, with the configuration the verifier checked.
    pub fn joint(&mut self, to: &Target, speed: &str) {
        self.motion(b"MoveJ ", to, speed, Vec::new(), true);
    }

    /// Holds back the motion `word` (`MoveL `, `MoveJ `) to `to` at
    /// `speed` with its `triggers`, after ending the one before (`fine`
    /// when `stop`).
    fn motion(
        &mut self,
        word: &[u8],
        to: &Target,
        speed: &str,
        triggers: Vec<(Set, At)>,
        stop: bool,
    ) {
        self.open(stop);
        let mut head = Vec::with_capacity(160);
        head.extend_from_slice(word);
        robtarget(&mut head, to);
        head.extend_from_slice(b", ");
        head.extend_from_slice(speed.as_bytes());
        self.pending = Some(Pending {
            head,
            triggers,
            joint: word == b"MoveJ ",
        });
        self.lines += 1;
        self.stats.moves += 1;
    }

    /// Sets `what` where the motion written last ends, the robot going on:
    /// that motion becomes a `TriggL`.
    pub fn at_end(&mut self, what: &[Set]) {
        let Some(p) = self.pending.as_mut() else {
            return;
        };
        for s in what {
            if *s == Set::Laser(true) {
                self.stats.laser_ons += 1;
            }
            p.triggers.push((*s, At::End));
        }
    }

    /// `WaitTime \InPos, seconds`: the robot stands still there.
    pub fn wait(&mut self, seconds: f64) {
        self.end_pending(false);
        self.at_rest = true;
        self.body.extend_from_slice(b"    WaitTime \\InPos, ");
        push_trimmed(&mut self.body, seconds, 2);
        self.body.extend_from_slice(b";\n");
    }

    /// Output instructions (`SetDO do3, 1; ! gas on`) where the robot
    /// stands: after `WaitRob \InPos`, so they switch when the motion
    /// before has ended rather than when the program pointer reads them.
    pub fn io(&mut self, lines: &[String]) {
        self.end_pending(false);
        if !self.at_rest {
            self.body.extend_from_slice(b"    WaitRob \\InPos;\n");
            self.at_rest = true;
        }
        for l in lines {
            self.body.extend_from_slice(b"    ");
            self.body.extend_from_slice(l.as_bytes());
            self.body.push(b'\n');
        }
    }

    /// Closes the last module; returns the module names in call order.
    pub fn finish(mut self) -> Result<(Vec<String>, Stats), EmitError> {
        self.end_pending(false);
        self.place_pre();
        if self.lines > 0 || !self.body.is_empty() {
            self.roll();
        }
        match self.error {
            Some(e) => Err(e),
            None => Ok((self.modules, self.stats)),
        }
    }

    /// Writes the motion held back: its `TriggIO`s, then the instruction
    /// with its zone (`lmd_z` when `blend`, else `fine`).
    fn end_pending(&mut self, blend: bool) {
        let Some(p) = self.pending.take() else {
            return;
        };
        let b = &mut self.body;
        for (s, at) in &p.triggers {
            b.extend_from_slice(b"    TriggIO ");
            b.extend_from_slice(s.var(*at).as_bytes());
            b.extend_from_slice(if *at == At::Start {
                b", 0 \\Start"
            } else {
                b", 0"
            });
            match s {
                Set::Laser(on) => {
                    b.extend_from_slice(b" \\DOp:=");
                    b.extend_from_slice(self.laser_out.as_bytes());
                    b.extend_from_slice(if *on { b", 1;\n" } else { b", 0;\n" });
                }
                Set::Power(x) => {
                    b.extend_from_slice(b" \\AOp:=");
                    b.extend_from_slice(self.power_out.as_bytes());
                    b.extend_from_slice(b", ");
                    push_fixed(b, *x, AO_DECIMALS);
                    b.extend_from_slice(b";\n");
                }
            }
        }
        b.extend_from_slice(b"    ");
        let rest = if p.triggers.is_empty() {
            b.extend_from_slice(&p.head);
            &[][..]
        } else {
            // `MoveL ` → `TriggL `, the triggers after the speed.
            b.extend_from_slice(b"TriggL ");
            &p.head[6..]
        };
        b.extend_from_slice(rest);
        for (i, (s, at)) in p.triggers.iter().enumerate() {
            match i {
                0 => b.extend_from_slice(b", "),
                _ => {
                    b.extend_from_slice(b" \\T");
                    push_u64(b, i as u64 + 1);
                    b.extend_from_slice(b":=");
                }
            }
            b.extend_from_slice(s.var(*at).as_bytes());
        }
        b.extend_from_slice(if blend && !p.joint {
            b", lmd_z, lmd_tool \\WObj:=lmd_wobj;\n".as_slice()
        } else {
            b", fine, lmd_tool \\WObj:=lmd_wobj;\n".as_slice()
        });
    }

    /// Writes the current module and starts the next.
    fn roll(&mut self) {
        self.end_pending(true);
        let name = self.names.module(self.modules.len());
        if self.error.is_none() {
            if let Err(e) = self.write(&name) {
                self.error = Some(e);
            }
        }
        self.modules.push(name);
        self.body.clear();
        self.lines = 0;
        self.layers = None;
        self.continues = if self.pre_layer.is_some() {
            0
        } else {
            self.current
        };
    }

    fn write(&mut self, name: &str) -> Result<(), EmitError> {
        let mut ctx = self.base.clone();
        ctx.insert("name", name);
        ctx.insert("module", &(self.modules.len() + 1));
        ctx.insert("lines", &self.lines);
        let (first, last) = self.layers.unwrap_or((0, 0));
        ctx.insert("first_layer", &first);
        ctx.insert("last_layer", &last);
        ctx.insert("continues", &self.continues);
        ctx.insert("body", BODY);
        let text = self
            .t
            .render("rapid/module.mod.tera", &ctx)
            .map_err(EmitError::Template)?;
        let (head, tail) = text.split_once(BODY).ok_or_else(|| {
            EmitError::Template("template rapid/module.mod.tera: it must contain {{ body }}".into())
        })?;
        let mut out = self.sink.create(&format!("{name}.mod"))?;
        out.write_all(head.as_bytes())?;
        out.write_all(&self.body)?;
        out.write_all(tail.as_bytes())?;
        out.flush()?;
        Ok(())
    }
}

/// ABB's "no axis" in a position's external axes.
pub const NO_AXIS: &str = "9E+09";

/// Appends `t` as a `robtarget` aggregate.
pub fn robtarget(b: &mut Vec<u8>, t: &Target) {
    b.extend_from_slice(b"[[");
    for (i, c) in t.pos.iter().enumerate() {
        if i > 0 {
            b.push(b',');
        }
        push_trimmed(b, *c, POS_DECIMALS);
    }
    b.extend_from_slice(b"],[");
    for (i, q) in t.quat.iter().enumerate() {
        if i > 0 {
            b.push(b',');
        }
        push_trimmed(b, *q, QUAT_DECIMALS);
    }
    b.extend_from_slice(b"],[");
    for (i, c) in t.conf.iter().enumerate() {
        if i > 0 {
            b.push(b',');
        }
        if *c < 0 {
            b.push(b'-');
        }
        push_u64(b, c.unsigned_abs() as u64);
    }
    b.extend_from_slice(b"],");
    extax(b, t.ext);
    b.push(b']');
}

/// Appends the external axes `[eax_a, …, eax_f]`: a positioner's two,
/// `9E+09` for the rest.
pub fn extax(b: &mut Vec<u8>, ext: Option<[f64; 2]>) {
    b.push(b'[');
    for i in 0..6 {
        if i > 0 {
            b.push(b',');
        }
        match ext {
            Some(e) if i < 2 => push_trimmed(b, e[i], POS_DECIMALS),
            _ => b.extend_from_slice(NO_AXIS.as_bytes()),
        }
    }
    b.push(b']');
}

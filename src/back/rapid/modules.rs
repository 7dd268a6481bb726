//! The streaming module writer of RAPID: motion instructions go into the
//! routine of the current motion module; when it holds `max_lines` of them
//! the module is closed (rendered through `rapid/module.mod.tera`, written
//! to the sink) and the next begins ([`ModuleStream`]).
//!
//! A motion is held back until the next one says how it ends (`fine` where
//! the plan stops or the next motion switches the laser at its start, the
//! zone `lmd_z` otherwise) and whether the laser switches at its end, which
//! turns it from a `MoveL` into a `TriggL`.

use crate::back::module_stream::{ModuleFiles, ModuleStream};
use crate::back::{EmitError, Sink, Templates};
use crate::numbers::{push_fixed, push_trimmed, push_u64};
use crate::target::names::KrlNames;
use crate::target::rapid::{AO_DECIMALS, POS_DECIMALS, QUAT_DECIMALS};

/// A RAPID motion module is one file.
const FILES: ModuleFiles = ModuleFiles {
    body: ("rapid/module.mod.tera", "mod"),
    beside: None,
};

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
    stream: ModuleStream<'a>,
    /// The laser's digital signal and its power's analog one
    /// ([`crate::target::rapid::signal`]).
    laser_out: String,
    power_out: String,
    pending: Option<Pending>,
    /// The robot stands still after the last instruction (`WaitRob \InPos`
    /// or `WaitTime \InPos`).
    at_rest: bool,
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
            stream: ModuleStream::new(sink, t, base, names, FILES, max_lines),
            laser_out,
            power_out,
            pending: None,
            at_rest: false,
            stats: Stats::default(),
        }
    }

    /// A layer's comment lines (`! …`), placed before its first motion.
    pub fn layer(&mut self, number: usize, text: &str) {
        let pre = self.stream.layer(number);
        for l in text.lines().filter(|l| !l.trim().is_empty()) {
            pre.extend_from_slice(b"    ");
            pre.extend_from_slice(l.trim_end().as_bytes());
            pre.push(b'\n');
        }
    }

    /// Opens a motion instruction: the module rolls over when full, the
    /// motion before ends (`fine` when `stop`), the layer's comments go
    /// first.
    fn open(&mut self, stop: bool) {
        self.end_pending(!stop);
        self.at_rest = false;
        if self.stream.full() {
            self.roll();
        }
        self.stream.place_pre();
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
        self.stream.lines += 1;
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
        self.stream
            .body
            .extend_from_slice(b"    WaitTime \\InPos, ");
        push_trimmed(&mut self.stream.body, seconds, 2);
        self.stream.body.extend_from_slice(b";\n");
    }

    /// Output instructions (`SetDO do3, 1; ! gas on`) where the robot
    /// stands: after `WaitRob \InPos`, so they switch when the motion
    /// before has ended rather than when the program pointer reads them.
    pub fn io(&mut self, lines: &[String]) {
        self.end_pending(false);
        if !self.at_rest {
            self.stream
                .body
                .extend_from_slice(b"    WaitRob \\InPos;\n");
            self.at_rest = true;
        }
        for l in lines {
            self.stream.body.extend_from_slice(b"    ");
            self.stream.body.extend_from_slice(l.as_bytes());
            self.stream.body.push(b'\n');
        }
    }

    /// Closes the last module; returns the module names in call order.
    pub fn finish(mut self) -> Result<(Vec<String>, Stats), EmitError> {
        self.end_pending(false);
        Ok((self.stream.finish()?, self.stats))
    }

    /// Writes the motion held back: its `TriggIO`s, then the instruction
    /// with its zone (`lmd_z` when `blend`, else `fine`).
    fn end_pending(&mut self, blend: bool) {
        let Some(p) = self.pending.take() else {
            return;
        };
        let b = &mut self.stream.body;
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
        self.stream.close();
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

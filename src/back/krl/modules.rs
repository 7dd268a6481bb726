//! The streaming module writer: motion lines go into the body of the current
//! module; when it holds `max_lines` LIN lines it is closed (rendered through
//! `krl/module.src.tera` and `krl/module.dat.tera`, written to the sink) and the
//! next one begins ([`ModuleStream`]).
//!
//! Per-point hot path: numbers are appended with [`push_fixed`], no `format!` and
//! no tera per line.

use super::orient::Abc;
use crate::back::fmt::{key, put_fixed, put_trimmed, MAX_NUMBER};
use crate::back::module_stream::{ModuleFiles, ModuleStream};
use crate::back::{EmitError, Sink, Templates};
use crate::numbers::{push_fixed, push_u64};
use crate::target::names::KrlNames;

pub use crate::target::kuka::{ANOUT_DECIMALS, POS_DECIMALS, VEL_DECIMALS};
/// Room for `,A …,B …,C …,E1 …,E2 …}`.
const ABC_BYTES: usize = 1 + 3 * (3 + MAX_NUMBER) + 2 * (4 + MAX_NUMBER);
/// Room for one LIN line: its words, X Y Z and the orientation.
const LINE: usize = 8 + 3 * (3 + MAX_NUMBER) + ABC_BYTES;
/// A KRL module's files: its program and its data list.
const FILES: ModuleFiles = ModuleFiles {
    body: ("krl/module.src.tera", "src"),
    beside: Some(("krl/module.dat.tera", "dat")),
};

/// A laser output switch attached to the start of a motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Switch {
    /// `$OUT[n]=TRUE`
    On,
    /// `$OUT[n]=FALSE`
    Off,
}

/// Counts of what was written, for the main program's comments.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// LIN lines in all modules.
    pub lin: u64,
    /// LIN lines with the laser on.
    pub deposits: u64,
    /// Laser switch-ons.
    pub laser_ons: u64,
}

/// Writes the motion modules of one robot program.
pub struct Modules<'a> {
    stream: ModuleStream<'a>,
    laser_out: u16,
    power_out: u16,
    /// The last LIN line awaits its approximation word.
    pending: bool,
    /// Where that LIN line starts in `body`.
    lin_at: usize,
    /// The advance run stopped after the last motion (a `WAIT SEC`).
    at_rest: bool,
    /// `$VEL.CP` written in this module, as a [`key`].
    vel: Option<i64>,
    /// The orientation and external axes of the last LIN and its text
    /// `,A …,B …,C …}` (`,A …,B …,C …,E1 …,E2 …}` with a positioner).
    abc_last: Option<(Abc, Option<[f64; 2]>)>,
    abc_text: [u8; ABC_BYTES],
    abc_len: usize,
    /// What has been written.
    pub stats: Stats,
}

impl<'a> Modules<'a> {
    /// A writer naming modules by `names`.
    pub fn new(
        sink: &'a mut dyn Sink,
        t: &'a Templates,
        base: tera::Context,
        names: KrlNames,
        max_lines: usize,
        laser_out: u16,
        power_out: u16,
    ) -> Self {
        Modules {
            stream: ModuleStream::new(sink, t, base, names, FILES, max_lines),
            laser_out,
            power_out,
            pending: false,
            lin_at: 0,
            at_rest: false,
            vel: None,
            abc_last: None,
            abc_text: [0; ABC_BYTES],
            abc_len: 0,
            stats: Stats::default(),
        }
    }

    /// A layer's comment block: it goes before the layer's first motion, in the
    /// module that motion goes to.
    pub fn layer(&mut self, number: usize, text: &str) {
        let pre = self.stream.layer(number);
        pre.extend_from_slice(text.as_bytes());
        if !text.is_empty() && !text.ends_with('\n') {
            pre.push(b'\n');
        }
    }

    /// One motion: `LIN` to `pos` with orientation `abc` at `speed` mm/s, after
    /// setting the power (`anout`, a fraction of full scale) and switching the
    /// laser at the motion's start when asked. The previous LIN is approximated
    /// (`C_DIS`) unless this motion switches the laser, so switches happen at the
    /// programmed points.
    #[allow(clippy::too_many_arguments)]
    pub fn lin(
        &mut self,
        pos: [f64; 3],
        abc: Abc,
        ext: Option<[f64; 2]>,
        speed: f64,
        anout: Option<f64>,
        switch: Option<Switch>,
        deposit: bool,
    ) {
        self.end_pending(switch.is_none());
        self.at_rest = false;
        if self.stream.full() {
            self.roll();
        }
        self.stream.place_pre();
        // The same printed speed is the same key; both are m/s at VEL_DECIMALS.
        let v = speed / 1000.0;
        let key = key(v, VEL_DECIMALS);
        if self.vel != Some(key) {
            self.vel = Some(key);
            let mut line = [0u8; 16 + MAX_NUMBER];
            line[..10].copy_from_slice(b"$VEL.CP = ");
            let at = put_trimmed(&mut line, 10, v, VEL_DECIMALS);
            line[at] = b'\n';
            self.stream.body.extend_from_slice(&line[..at + 1]);
        }
        let b = &mut self.stream.body;
        if let Some(x) = anout {
            b.extend_from_slice(b"TRIGGER WHEN DISTANCE=0 DELAY=0 DO $ANOUT[");
            push_u64(b, self.power_out as u64);
            b.extend_from_slice(b"]=");
            push_fixed(b, x, ANOUT_DECIMALS);
            b.push(b'\n');
        }
        if let Some(s) = switch {
            b.extend_from_slice(b"TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[");
            push_u64(b, self.laser_out as u64);
            b.extend_from_slice(match s {
                Switch::On => b"]=TRUE\n",
                Switch::Off => b"]=FALSE\n",
            });
            if s == Switch::On {
                self.stats.laser_ons += 1;
            }
        }
        // Most lines repeat the orientation of the line before: keep its text.
        if self.abc_last != Some((abc, ext)) {
            self.abc_last = Some((abc, ext));
            let t = &mut self.abc_text;
            t[..3].copy_from_slice(b",A ");
            let at = put_fixed(t, 3, angle_value(abc.a), POS_DECIMALS);
            t[at..at + 3].copy_from_slice(b",B ");
            let at = put_fixed(t, at + 3, abc.b, POS_DECIMALS);
            t[at..at + 3].copy_from_slice(b",C ");
            let mut at = put_fixed(t, at + 3, angle_value(abc.c), POS_DECIMALS);
            if let Some([e1, e2]) = ext {
                t[at..at + 4].copy_from_slice(b",E1 ");
                at = put_fixed(t, at + 4, e1, POS_DECIMALS);
                t[at..at + 4].copy_from_slice(b",E2 ");
                at = put_fixed(t, at + 4, e2, POS_DECIMALS);
            }
            t[at] = b'}';
            self.abc_len = at + 1;
        }
        // One line, formatted in place on the stack and appended with one copy.
        self.lin_at = self.stream.body.len();
        let mut line = [0u8; LINE];
        line[..7].copy_from_slice(b"LIN {X ");
        let mut at = put_fixed(&mut line, 7, pos[0], POS_DECIMALS);
        line[at..at + 3].copy_from_slice(b",Y ");
        at = put_fixed(&mut line, at + 3, pos[1], POS_DECIMALS);
        line[at..at + 3].copy_from_slice(b",Z ");
        at = put_fixed(&mut line, at + 3, pos[2], POS_DECIMALS);
        line[at..at + self.abc_len].copy_from_slice(&self.abc_text[..self.abc_len]);
        at += self.abc_len;
        self.stream.body.extend_from_slice(&line[..at]);
        self.pending = true;
        self.stream.lines += 1;
        self.stats.lin += 1;
        if deposit {
            self.stats.deposits += 1;
        }
    }

    /// The move from home to the first pose: a `PTP`, with KUKA's Status
    /// and Turn and the axis angles they stand for (as a comment) where
    /// the arm is known (`config`), so the controller takes the
    /// configuration the verifier checked; not approximated.
    pub fn ptp(
        &mut self,
        pos: [f64; 3],
        abc: Abc,
        ext: Option<[f64; 2]>,
        config: Option<(u8, u8, [f64; 6])>,
    ) {
        self.end_pending(false);
        self.at_rest = false;
        if self.stream.full() {
            self.roll();
        }
        self.stream.place_pre();
        let b = &mut self.stream.body;
        b.extend_from_slice(b"PTP {X ");
        push_fixed(b, pos[0], POS_DECIMALS);
        b.extend_from_slice(b",Y ");
        push_fixed(b, pos[1], POS_DECIMALS);
        b.extend_from_slice(b",Z ");
        push_fixed(b, pos[2], POS_DECIMALS);
        b.extend_from_slice(b",A ");
        push_fixed(b, angle_value(abc.a), POS_DECIMALS);
        b.extend_from_slice(b",B ");
        push_fixed(b, abc.b, POS_DECIMALS);
        b.extend_from_slice(b",C ");
        push_fixed(b, angle_value(abc.c), POS_DECIMALS);
        if let Some([e1, e2]) = ext {
            b.extend_from_slice(b",E1 ");
            push_fixed(b, e1, POS_DECIMALS);
            b.extend_from_slice(b",E2 ");
            push_fixed(b, e2, POS_DECIMALS);
        }
        match config {
            Some((s, t, j)) => {
                b.extend_from_slice(b",S ");
                push_u64(b, s as u64);
                b.extend_from_slice(b",T ");
                push_u64(b, t as u64);
                b.extend_from_slice(b"} ; from home, axes");
                for (i, a) in j.iter().enumerate() {
                    b.extend_from_slice(format!(" A{} ", i + 1).as_bytes());
                    push_fixed(b, *a, POS_DECIMALS);
                }
                b.push(b'\n');
            }
            None => b.extend_from_slice(b"} ; from home\n"),
        }
        self.stream.lines += 1;
    }

    /// Switches the laser (after setting the power `anout`, when given) at
    /// the end point of the LIN written last, while the robot moves on: a
    /// `TRIGGER WHEN PATH=0` before that LIN, which stays approximated. A
    /// path trigger refers to the motion's end point, or where it is
    /// approximated to the point of the approximation contour closest to
    /// it: on a lead, which goes on straight, the end point itself.
    pub fn switch_at_end(&mut self, anout: Option<f64>, switch: Switch) {
        if !self.pending {
            return;
        }
        let mut t = Vec::with_capacity(128);
        if let Some(x) = anout {
            t.extend_from_slice(b"TRIGGER WHEN PATH=0 DELAY=0 DO $ANOUT[");
            push_u64(&mut t, self.power_out as u64);
            t.extend_from_slice(b"]=");
            push_fixed(&mut t, x, ANOUT_DECIMALS);
            t.push(b'\n');
        }
        t.extend_from_slice(b"TRIGGER WHEN PATH=0 DELAY=0 DO $OUT[");
        push_u64(&mut t, self.laser_out as u64);
        t.extend_from_slice(match switch {
            Switch::On => b"]=TRUE\n",
            Switch::Off => b"]=FALSE\n",
        });
        if switch == Switch::On {
            self.stats.laser_ons += 1;
        }
        let at = self.lin_at.min(self.stream.body.len());
        self.stream.body.splice(at..at, t);
    }

    /// `WAIT SEC seconds`: the robot stands still (the advance run stops there,
    /// which between layers costs nothing). The LIN before it ends exactly.
    pub fn wait(&mut self, seconds: f64) {
        self.end_pending(false);
        self.at_rest = true;
        self.stream.body.extend_from_slice(b"WAIT SEC ");
        push_fixed(&mut self.stream.body, seconds, 2);
        self.stream.body.push(b'\n');
    }

    /// Output assignments (`$OUT[n]=TRUE`, …) where the robot stands: after an
    /// advance-run stop, so they switch when the motion before them has ended
    /// rather than when the advance run reads them, motions earlier.
    pub fn io(&mut self, lines: &[String]) {
        self.end_pending(false);
        if !self.at_rest {
            self.stream
                .body
                .extend_from_slice(b"WAIT SEC 0 ; advance-run stop: the outputs switch here\n");
            self.at_rest = true;
        }
        for l in lines {
            self.stream.body.extend_from_slice(l.as_bytes());
            self.stream.body.push(b'\n');
        }
    }

    /// Closes the last module; returns the module names in call order.
    pub fn finish(mut self) -> Result<(Vec<String>, Stats), EmitError> {
        self.end_pending(false);
        Ok((self.stream.finish()?, self.stats))
    }

    fn end_pending(&mut self, approximate: bool) {
        if self.pending {
            self.stream
                .body
                .extend_from_slice(if approximate { b" C_DIS\n" } else { b"\n" });
            self.pending = false;
        }
    }

    /// Writes the current module and starts the next.
    fn roll(&mut self) {
        self.end_pending(true);
        self.stream.close();
        self.vel = None;
    }
}

/// An angle as written: +180 rather than −180 when it rounds there (the same
/// orientation; KUKA's range is (−180, 180]).
pub(super) fn angle_value(deg: f64) -> f64 {
    if deg < -179.9995 {
        deg + 360.0
    } else {
        deg
    }
}

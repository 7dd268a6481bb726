//! The streaming module writer: motion lines go into the body of the current
//! module; when it holds `max_lines` LIN lines it is closed (rendered through
//! `krl/module.src.tera` and `krl/module.dat.tera`, written to the sink) and the
//! next one begins. Holding one module in memory bounds memory by the module
//! size, whatever the part's size.
//!
//! Per-point hot path: numbers are appended with [`push_fixed`], no `format!` and
//! no tera per line.

use super::orient::Abc;
use crate::back::fmt::{key, put_fixed, put_trimmed, MAX_NUMBER};
use crate::back::{EmitError, Sink, Templates};
use crate::numbers::{push_fixed, push_u64};
use crate::target::names::KrlNames;
use std::io::Write;

pub use crate::target::kuka::{ANOUT_DECIMALS, POS_DECIMALS, VEL_DECIMALS};
/// Room for `,A …,B …,C …,E1 …,E2 …}`.
const ABC_BYTES: usize = 1 + 3 * (3 + MAX_NUMBER) + 2 * (4 + MAX_NUMBER);
/// Room for one LIN line: its words, X Y Z and the orientation.
const LINE: usize = 8 + 3 * (3 + MAX_NUMBER) + ABC_BYTES;
/// Marker the module template's `body` variable is rendered as, where the motion
/// lines go.
const BODY: &str = "\u{1}lmdc-body\u{1}";

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
    sink: &'a mut dyn Sink,
    t: &'a Templates,
    base: tera::Context,
    names: KrlNames,
    max_lines: usize,
    laser_out: u16,
    power_out: u16,
    body: Vec<u8>,
    lines: usize,
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
    /// Layer numbers (1-based) whose comment blocks are in this module.
    layers: Option<(usize, usize)>,
    /// A layer comment block waiting for the layer's first motion, and its number.
    pre: Vec<u8>,
    pre_layer: Option<usize>,
    /// The last layer whose comment block was placed (1-based; 0: none yet).
    current: usize,
    /// The layer already under way when this module starts (0: it starts
    /// with a layer's comment block, or before any).
    continues: usize,
    /// The modules written so far.
    modules: Vec<String>,
    error: Option<EmitError>,
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
            sink,
            t,
            base,
            names,
            max_lines: max_lines.max(1),
            laser_out,
            power_out,
            body: Vec::with_capacity(1 << 16),
            lines: 0,
            pending: false,
            lin_at: 0,
            at_rest: false,
            vel: None,
            abc_last: None,
            abc_text: [0; ABC_BYTES],
            abc_len: 0,
            layers: None,
            pre: Vec::new(),
            pre_layer: None,
            current: 0,
            continues: 0,
            modules: Vec::new(),
            error: None,
            stats: Stats::default(),
        }
    }

    /// A layer's comment block: it goes before the layer's first motion, in the
    /// module that motion goes to.
    pub fn layer(&mut self, number: usize, text: &str) {
        self.pre.extend_from_slice(text.as_bytes());
        if !text.is_empty() && !text.ends_with('\n') {
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
        if self.lines >= self.max_lines {
            self.roll();
        }
        self.place_pre();
        // The same printed speed is the same key; both are m/s at VEL_DECIMALS.
        let v = speed / 1000.0;
        let key = key(v, VEL_DECIMALS);
        if self.vel != Some(key) {
            self.vel = Some(key);
            let mut line = [0u8; 16 + MAX_NUMBER];
            line[..10].copy_from_slice(b"$VEL.CP = ");
            let at = put_trimmed(&mut line, 10, v, VEL_DECIMALS);
            line[at] = b'\n';
            self.body.extend_from_slice(&line[..at + 1]);
        }
        let b = &mut self.body;
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
        self.lin_at = self.body.len();
        let mut line = [0u8; LINE];
        line[..7].copy_from_slice(b"LIN {X ");
        let mut at = put_fixed(&mut line, 7, pos[0], POS_DECIMALS);
        line[at..at + 3].copy_from_slice(b",Y ");
        at = put_fixed(&mut line, at + 3, pos[1], POS_DECIMALS);
        line[at..at + 3].copy_from_slice(b",Z ");
        at = put_fixed(&mut line, at + 3, pos[2], POS_DECIMALS);
        line[at..at + self.abc_len].copy_from_slice(&self.abc_text[..self.abc_len]);
        at += self.abc_len;
        self.body.extend_from_slice(&line[..at]);
        self.pending = true;
        self.lines += 1;
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
        if self.lines >= self.max_lines {
            self.roll();
        }
        self.place_pre();
        let b = &mut self.body;
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
        self.lines += 1;
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
        let at = self.lin_at.min(self.body.len());
        self.body.splice(at..at, t);
    }

    /// `WAIT SEC seconds`: the robot stands still (the advance run stops there,
    /// which between layers costs nothing). The LIN before it ends exactly.
    pub fn wait(&mut self, seconds: f64) {
        self.end_pending(false);
        self.at_rest = true;
        self.body.extend_from_slice(b"WAIT SEC ");
        push_fixed(&mut self.body, seconds, 2);
        self.body.push(b'\n');
    }

    /// Output assignments (`$OUT[n]=TRUE`, …) where the robot stands: after an
    /// advance-run stop, so they switch when the motion before them has ended
    /// rather than when the advance run reads them, motions earlier.
    pub fn io(&mut self, lines: &[String]) {
        self.end_pending(false);
        if !self.at_rest {
            self.body
                .extend_from_slice(b"WAIT SEC 0 ; advance-run stop: the outputs switch here\n");
            self.at_rest = true;
        }
        for l in lines {
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

    fn end_pending(&mut self, approximate: bool) {
        if self.pending {
            self.body
                .extend_from_slice(if approximate { b" C_DIS\n" } else { b"\n" });
            self.pending = false;
        }
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
        self.vel = None;
        self.layers = None;
        // Mid-layer unless the next motion opens a layer with its block.
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
        let src = self
            .t
            .render("krl/module.src.tera", &ctx)
            .map_err(EmitError::Template)?;
        let (head, tail) = src.split_once(BODY).ok_or_else(|| {
            EmitError::Template("template krl/module.src.tera: it must contain {{ body }}".into())
        })?;
        let dat = self
            .t
            .render("krl/module.dat.tera", &ctx)
            .map_err(EmitError::Template)?;
        let mut out = self.sink.create(&format!("{name}.src"))?;
        out.write_all(head.as_bytes())?;
        out.write_all(&self.body)?;
        out.write_all(tail.as_bytes())?;
        out.flush()?;
        drop(out);
        if !dat.is_empty() {
            let mut out = self.sink.create(&format!("{name}.dat"))?;
            out.write_all(dat.as_bytes())?;
            out.flush()?;
        }
        Ok(())
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

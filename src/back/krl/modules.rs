//! The streaming module writer: motion lines go into the body of the current
//! module; when it holds `max_lines` LIN lines it is closed (rendered through
//! `krl/module.src.tera` and `krl/module.dat.tera`, written to the sink) and the
//! next one begins. Holding one module in memory bounds memory by the module
//! size, whatever the part's size.
//!
//! Per-point hot path: numbers are appended with [`push_fixed`], no `format!` and
//! no tera per line.

use super::orient::Abc;
use crate::back::fixed::{push_fixed, push_trimmed, push_u64};
use crate::back::fmt::{put_fixed, MAX_NUMBER};
use crate::back::{EmitError, Sink, Templates};
use std::io::Write;

/// Decimals of X Y Z (mm) and A B C (deg).
pub const POS_DECIMALS: usize = 3;
/// Decimals of `$VEL.CP` (m/s): 0.001 mm/s.
pub const VEL_DECIMALS: usize = 6;
/// Decimals of `$ANOUT` (fraction of full scale).
pub const ANOUT_DECIMALS: usize = 4;
/// Room for one LIN line: its words and six numbers.
const LINE: usize = 32 + 6 * (3 + MAX_NUMBER);
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
    stem: String,
    digits: usize,
    max_lines: usize,
    laser_out: u16,
    power_out: u16,
    body: Vec<u8>,
    lines: usize,
    /// The last LIN line awaits its approximation word.
    pending: bool,
    /// `$VEL.CP` written in this module, in µm/s.
    vel: Option<i64>,
    /// Layer numbers (1-based) whose comment blocks are in this module.
    layers: Option<(usize, usize)>,
    /// A layer comment block waiting for the layer's first motion, and its number.
    pre: Vec<u8>,
    pre_layer: Option<usize>,
    names: Vec<String>,
    error: Option<EmitError>,
    /// What has been written.
    pub stats: Stats,
}

impl<'a> Modules<'a> {
    /// A writer naming modules `<stem>_m<NNN>` with `digits` digits.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        sink: &'a mut dyn Sink,
        t: &'a Templates,
        base: tera::Context,
        stem: String,
        digits: usize,
        max_lines: usize,
        laser_out: u16,
        power_out: u16,
    ) -> Self {
        Modules {
            sink,
            t,
            base,
            stem,
            digits,
            max_lines: max_lines.max(1),
            laser_out,
            power_out,
            body: Vec::with_capacity(1 << 16),
            lines: 0,
            pending: false,
            vel: None,
            layers: None,
            pre: Vec::new(),
            pre_layer: None,
            names: Vec::new(),
            error: None,
            stats: Stats::default(),
        }
    }

    /// The name of module number `i` (0-based).
    pub fn name(stem: &str, digits: usize, i: usize) -> String {
        format!("{stem}_m{:0digits$}", i + 1)
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
        }
    }

    /// One motion: `LIN` to `pos` with orientation `abc` at `speed` mm/s, after
    /// setting the power (`anout`, a fraction of full scale) and switching the
    /// laser at the motion's start when asked. The previous LIN is approximated
    /// (`C_DIS`) unless this motion switches the laser, so switches happen at the
    /// programmed points.
    pub fn lin(
        &mut self,
        pos: [f64; 3],
        abc: Abc,
        speed: f64,
        anout: Option<f64>,
        switch: Option<Switch>,
        deposit: bool,
    ) {
        self.end_pending(switch.is_none());
        if self.lines >= self.max_lines {
            self.roll();
        }
        self.place_pre();
        let b = &mut self.body;
        let key = (speed * 1000.0).round() as i64;
        if self.vel != Some(key) {
            self.vel = Some(key);
            b.extend_from_slice(b"$VEL.CP = ");
            push_trimmed(b, key as f64 / 1e6, VEL_DECIMALS);
            b.push(b'\n');
        }
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
        // One line, formatted in place on the stack and appended with one copy.
        let mut line = [0u8; LINE];
        line[..7].copy_from_slice(b"LIN {X ");
        let mut at = put_fixed(&mut line, 7, pos[0], POS_DECIMALS);
        for (word, v, angle) in [
            (b",Y ", pos[1], false),
            (b",Z ", pos[2], false),
            (b",A ", abc.a, true),
            (b",B ", abc.b, false),
            (b",C ", abc.c, true),
        ] {
            line[at..at + 3].copy_from_slice(word);
            at = put_fixed(
                &mut line,
                at + 3,
                if angle { angle_value(v) } else { v },
                POS_DECIMALS,
            );
        }
        line[at] = b'}';
        b.extend_from_slice(&line[..at + 1]);
        self.pending = true;
        self.lines += 1;
        self.stats.lin += 1;
        if deposit {
            self.stats.deposits += 1;
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
            None => Ok((self.names, self.stats)),
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
        let name = Self::name(&self.stem, self.digits, self.names.len());
        if self.error.is_none() {
            if let Err(e) = self.write(&name) {
                self.error = Some(e);
            }
        }
        self.names.push(name);
        self.body.clear();
        self.lines = 0;
        self.vel = None;
        self.layers = None;
    }

    fn write(&mut self, name: &str) -> Result<(), EmitError> {
        let mut ctx = self.base.clone();
        ctx.insert("name", name);
        ctx.insert("module", &(self.names.len() + 1));
        ctx.insert("lines", &self.lines);
        let (first, last) = self.layers.unwrap_or((0, 0));
        ctx.insert("first_layer", &first);
        ctx.insert("last_layer", &last);
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
fn angle_value(deg: f64) -> f64 {
    if deg < -179.9995 {
        deg + 360.0
    } else {
        deg
    }
}

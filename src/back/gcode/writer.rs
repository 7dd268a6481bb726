//! The streaming motion writer: formats G-code lines in place into one reused
//! buffer and hands it to the output in large chunks. It owns the modal state (F,
//! S, laser), so a word is written only when the value a reader would see changes.
//!
//! This is the per-point hot path (millions of lines): no `format!`, no tera, no
//! allocation and no `memcpy` call per line (see [`super::fmt`]).

use super::dialect::Words;
use crate::back::fmt::{key, put_fixed, put_trimmed, MAX_NUMBER};
use crate::plan::kinematics::Rotary;
use std::io::{self, Write};

/// Bytes handed to the output at a time.
const CHUNK: usize = 1 << 20;
/// Room kept free past [`CHUNK`]: more than any motion line needs.
const ROOM: usize = 1024;
use crate::target::gcode::POS_DECIMALS;
/// Scratch size of one number (≥ MAX_NUMBER; copied whole, a fixed length).
const NUM: usize = 32;
/// Room for the rotary words ` A<n> C<n>`.
const ROT_BYTES: usize = 2 * (2 + MAX_NUMBER);

/// Lines written, by kind, for the footer template.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Stats {
    /// G0 lines.
    pub rapids: u64,
    /// G1 lines with the laser on.
    pub deposits: u64,
    /// G1 lines with the laser off (approaches).
    pub approaches: u64,
    /// Laser-on lines (= laser-off lines).
    pub laser_switches: u64,
}

/// A G-code writer over one output file.
pub(crate) struct Writer<'w> {
    out: Box<dyn Write + 'w>,
    /// `buf[..len]` is written and not yet handed on; `buf` is `CHUNK + ROOM` long.
    buf: Box<[u8]>,
    len: usize,
    /// `G0 `/`G00 ` and `G1 `/`G01 `, padded to 4 bytes so they copy with a fixed
    /// length, with their real lengths.
    rapid: ([u8; 4], usize),
    feed: ([u8; 4], usize),
    laser_on_text: Vec<u8>,
    laser_off_text: Vec<u8>,
    s_per_watt: f64,
    s_decimals: usize,
    f_per_mm_s: f64,
    f_decimals: usize,
    /// `b'A'`/`b'B'` on a tilting head; `None` writes X Y Z only.
    tilt_letter: Option<u8>,
    /// Printed F and S as [`key`]s; `None` before the first.
    f: Option<i64>,
    s: Option<i64>,
    /// The bits of the speed and power whose F and S were last settled, so an
    /// unchanged value skips the key computation.
    f_raw: u32,
    s_raw: u32,
    laser: bool,
    /// The rotary words of the last line, kept because most lines repeat them.
    rot_last: Option<Rotary>,
    rot_text: [u8; ROT_BYTES],
    rot_len: usize,
    /// Set once nothing more should be written (a problem was found or the output
    /// failed); the modal state is then no longer kept.
    quiet: bool,
    error: Option<io::Error>,
    /// What has been written.
    pub stats: Stats,
}

fn padded(g: &[u8]) -> ([u8; 4], usize) {
    let mut a = [b' '; 4];
    a[..g.len()].copy_from_slice(g);
    (a, g.len())
}

impl<'w> Writer<'w> {
    /// A writer appending to `out`; `tilt_letter` selects 5-axis words.
    pub fn new(out: Box<dyn Write + 'w>, words: Words, tilt_letter: Option<u8>) -> Self {
        Writer {
            out,
            buf: vec![0u8; CHUNK + ROOM].into_boxed_slice(),
            len: 0,
            rapid: padded(words.rapid),
            feed: padded(words.feed),
            laser_on_text: words.laser_on,
            laser_off_text: words.laser_off,
            s_per_watt: words.s_per_watt,
            s_decimals: words.s_decimals,
            f_per_mm_s: words.f_per_mm_s,
            f_decimals: words.f_decimals,
            tilt_letter,
            f: None,
            s: None,
            // NaN bits: no f32 the IR can hold (checks refuse NaN) matches them.
            f_raw: u32::MAX,
            s_raw: u32::MAX,
            laser: false,
            rot_last: None,
            rot_text: [0; ROT_BYTES],
            rot_len: 0,
            quiet: false,
            error: None,
            stats: Stats::default(),
        }
    }

    /// Stops writing; later calls do nothing. Used once the program is known to
    /// fail (a template error), so no time goes into text nobody will read.
    pub fn silence(&mut self) {
        self.quiet = true;
    }

    /// Appends text as it is (template output, dialect lines), of any length.
    pub fn raw(&mut self, text: &[u8]) {
        if self.quiet {
            return;
        }
        if self.len + text.len() > self.buf.len() {
            self.flush_chunk();
            if text.len() > self.buf.len() {
                if let Err(e) = self.out.write_all(text) {
                    self.fail(e);
                }
                return;
            }
        }
        self.buf[self.len..self.len + text.len()].copy_from_slice(text);
        self.len += text.len();
    }

    /// Switches the laser on unless it is, first setting S to `power` so the
    /// laser never fires at the previous power.
    #[inline]
    pub fn laser_on(&mut self, power: f32) {
        if self.laser || self.quiet {
            return;
        }
        let (v, k) = self.s_value(power);
        if self.s != Some(k) {
            self.room();
            let b = &mut self.buf[..];
            b[self.len] = b'S';
            let at = put_fixed(b, self.len + 1, v, self.s_decimals);
            b[at] = b'\n';
            self.len = at + 1;
            self.s = Some(k);
        }
        self.s_raw = power.to_bits();
        let text = std::mem::take(&mut self.laser_on_text);
        self.raw(&text);
        self.laser_on_text = text;
        self.laser = true;
        self.stats.laser_switches += 1;
    }

    /// Switches the laser off unless it is.
    #[inline]
    pub fn laser_off(&mut self) {
        if !self.laser || self.quiet {
            return;
        }
        let text = std::mem::take(&mut self.laser_off_text);
        self.raw(&text);
        self.laser_off_text = text;
        self.laser = false;
    }

    /// A `G0` to tool-tip position `p` with the head at `r`.
    #[inline]
    pub fn rapid(&mut self, p: [f64; 3], r: Rotary) {
        if self.quiet {
            return;
        }
        self.room();
        let at = self.position(self.rapid, p, r);
        self.buf[at] = b'\n';
        self.len = at + 1;
        self.stats.rapids += 1;
    }

    /// A rapid move of Z alone to `z`: the other axes stay where they are
    /// (the safe lift, [`crate::plan::MoveKind::Lift`]).
    pub fn lift(&mut self, z: f64) {
        if self.quiet {
            return;
        }
        self.room();
        let (g, g_len) = self.rapid;
        let at = self.len;
        self.buf[at..at + 4].copy_from_slice(&g);
        let at = at + g_len;
        self.buf[at] = b'Z';
        let at = put_fixed(&mut self.buf, at + 1, z, POS_DECIMALS);
        self.buf[at] = b'\n';
        self.len = at + 1;
        self.stats.rapids += 1;
    }

    /// A `G1` to `p`/`r` at `speed` (mm/s) and `power` (W), each word written only
    /// if its printed value changes.
    #[inline]
    pub fn feed(&mut self, p: [f64; 3], r: Rotary, speed: f32, power: f32) {
        if self.quiet {
            return;
        }
        self.room();
        let mut at = self.position(self.feed, p, r);
        let b = &mut self.buf[..];
        // Most lines repeat the previous speed and power exactly: skip the keys.
        if speed.to_bits() != self.f_raw {
            self.f_raw = speed.to_bits();
            let f = speed as f64 * self.f_per_mm_s;
            let f_key = key(f, self.f_decimals);
            if self.f != Some(f_key) {
                b[at..at + 2].copy_from_slice(b" F");
                at = put_trimmed(b, at + 2, f, self.f_decimals);
                self.f = Some(f_key);
            }
        }
        if power.to_bits() != self.s_raw {
            let s = power as f64 * self.s_per_watt;
            let s_key = key(s, self.s_decimals);
            if self.s != Some(s_key) {
                b[at..at + 2].copy_from_slice(b" S");
                at = put_fixed(b, at + 2, s, self.s_decimals);
                self.s = Some(s_key);
            }
            self.s_raw = power.to_bits();
        }
        b[at] = b'\n';
        self.len = at + 1;
        if self.laser {
            self.stats.deposits += 1;
        } else {
            self.stats.approaches += 1;
        }
    }

    /// Hands everything to the output; the first I/O error, if any.
    pub fn finish(mut self) -> io::Result<()> {
        if self.error.is_none() && self.len > 0 {
            if let Err(e) = self.out.write_all(&self.buf[..self.len]) {
                self.fail(e);
            }
        }
        if self.error.is_none() {
            if let Err(e) = self.out.flush() {
                self.fail(e);
            }
        }
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// The S value for `power` and its key.
    #[inline]
    fn s_value(&self, power: f32) -> (f64, i64) {
        let v = power as f64 * self.s_per_watt;
        (v, key(v, self.s_decimals))
    }

    /// Makes sure a whole motion line fits after `len`.
    #[inline(always)]
    fn room(&mut self) {
        if self.len >= CHUNK {
            self.flush_chunk();
        }
    }

    /// Writes `G.. X.. Y.. Z..` and the rotary words at `len`; returns the end.
    #[inline(always)]
    fn position(&mut self, (g, g_len): ([u8; 4], usize), p: [f64; 3], r: Rotary) -> usize {
        if let Some(letter) = self.tilt_letter {
            if self.rot_last != Some(r) {
                let t = &mut self.rot_text;
                t[0] = b' ';
                t[1] = letter;
                let at = put_fixed(t, 2, r.tilt, POS_DECIMALS);
                t[at..at + 2].copy_from_slice(b" C");
                self.rot_len = put_fixed(t, at + 2, r.c, POS_DECIMALS);
                self.rot_last = Some(r);
            }
        }
        // Each number into its own scratch first: the three are then independent
        // and the CPU formats them side by side; written in place one after the
        // other, each would wait for the previous one's length.
        let mut num = [[0u8; NUM]; 3];
        let mut lens = [0usize; 3];
        for k in 0..3 {
            lens[k] = put_fixed(&mut num[k], 0, p[k], POS_DECIMALS);
        }
        let b = &mut self.buf[..];
        let mut at = self.len;
        b[at..at + 4].copy_from_slice(&g);
        at += g_len;
        for (k, letter) in [b'X', b'Y', b'Z'].into_iter().enumerate() {
            if k > 0 {
                b[at] = b' ';
                at += 1;
            }
            b[at] = letter;
            b[at + 1..at + 1 + NUM].copy_from_slice(&num[k]);
            at += 1 + lens[k];
        }
        if self.tilt_letter.is_some() {
            // A fixed-length copy (no memcpy call); only rot_len bytes count.
            b[at..at + ROT_BYTES].copy_from_slice(&self.rot_text);
            at += self.rot_len;
        }
        at
    }

    #[cold]
    fn flush_chunk(&mut self) {
        if self.len > 0 && self.error.is_none() {
            if let Err(e) = self.out.write_all(&self.buf[..self.len]) {
                self.fail(e);
            }
        }
        self.len = 0;
    }

    #[cold]
    fn fail(&mut self, e: io::Error) {
        self.error = Some(e);
        self.quiet = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{CommentStyle, Dialect, FeedUnit};

    fn dialect() -> Dialect {
        Dialect {
            profile: "test".into(),
            laser_on: "M3".into(),
            laser_off: "M5".into(),
            s_per_watt: 0.25,
            s_decimals: 1,
            preamble: vec![],
            postamble: vec![],
            dwell: "G4 P{s}".into(),
            tcp_on: String::new(),
            tcp_off: String::new(),
            comment: CommentStyle::Parens,
            padded_g: true,
            extension: "nc".into(),
            feed: FeedUnit::MmPerMin,
        }
    }

    struct Shared(std::rc::Rc<std::cell::RefCell<Vec<u8>>>);
    impl Write for Shared {
        fn write(&mut self, b: &[u8]) -> io::Result<usize> {
            self.0.borrow_mut().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn modal_words_and_laser() {
        let out = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
        let mut w = Writer::new(
            Box::new(Shared(out.clone())),
            Words::new(&dialect()),
            Some(b'A'),
        );
        let r = Rotary {
            tilt: 10.0,
            c: -0.0,
        };
        w.rapid([1.0, 2.0, 3.0], r);
        w.feed([1.0, 2.0, 2.0], r, 10.0, 1000.0);
        w.laser_on(1000.0);
        w.feed([2.0, 2.0, 2.0], r, 10.0001, 1000.1);
        w.feed([3.0, 2.0, 2.0], r, 10.5, 1002.0);
        w.laser_off();
        w.laser_off();
        w.rapid([3.0, 2.0, 12.0], Rotary { tilt: 0.0, c: 90.0 });
        let stats = w.stats;
        w.finish().unwrap();
        let text = String::from_utf8(out.borrow().clone()).unwrap();
        assert_eq!(
            text,
            "G00 X1.000 Y2.000 Z3.000 A10.000 C0.000\n\
             G01 X1.000 Y2.000 Z2.000 A10.000 C0.000 F600 S250.0\n\
             M3\n\
             G01 X2.000 Y2.000 Z2.000 A10.000 C0.000\n\
             G01 X3.000 Y2.000 Z2.000 A10.000 C0.000 F630 S250.5\n\
             M5\n\
             G00 X3.000 Y2.000 Z12.000 A0.000 C90.000\n"
        );
        assert_eq!(stats.deposits, 2);
        assert_eq!(stats.approaches, 1);
        assert_eq!(stats.rapids, 2);
    }
}

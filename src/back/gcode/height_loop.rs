//! A segmented ring's height loop in LinuxCNC G-code. The header and footer
//! templates frame a program that loops over one layer:
//!
//! - named global parameters per segment `j`: the speed `#<_lmd_v{j}>`
//!   (mm/s), the error sum `#<_lmd_s{j}>` and the working plane
//!   `#<_lmd_z{j}>`; the gains, target, clamp and sensor scale;
//! - the law ([`crate::control::LAW`], step by step) in `o<lmd_pi> sub`,
//!   called with a segment's measured height and its three values and
//!   returning them in `#<_lmd_v>`, `#<_lmd_s>`, `#<_lmd_z>`;
//! - `o<lmd_layers> repeat [layers − 1]` over the first layer's moves, then
//!   the last layer (its last transition stays level): every move's Z is
//!   `#<_lmd_z{j}>` plus the segment's defocus, its F `#<_lmd_v{j}>·60`
//!   (times `√(1 + (Δz/arc)²)` over a transition: `v / cos γ`).
//!
//! **Where the sensor is read, and what it costs.** `M66 E… L0` reads an
//! analog input into `#5399`, and like every read of the machine's state
//! it stops the interpreter's look-ahead: the motion queue runs empty and
//! the machine stops there, with the laser still on, laying extra metal
//! where it stands. So the program reads once a layer: all segments' inputs
//! (`height_input + j`) back to back, one stop, at the seam after the layer
//! change, where segment 1 — the slowest (it stops soonest) and widest
//! bead of Table 1 — starts, and its own loop sees the bump in its mean
//! and trims it. Every segment is updated before it is laid again, as the
//! law needs. A declared `height_delay` is waited out (`G4`) before the
//! reads, when the last segment's mean arrives. Because segment 1 is read
//! only at the seam, the layer-change transition climbs to where segment 1
//! would be had it laid the target height; the first move of the next
//! layer takes up the difference. A controller without the stop would run
//! the law in HAL (on `motion.adaptive-feed`), which lmdc does not write.

use super::dialect::{comment_safe, delimiters};
use super::{base_context, footer_context, header_context, EmitError, Sink, Templates};
use crate::back::height_loop::{constants, prepare, CellStep, LayerMove, LoopPlan, Part, Prepared};
use crate::control::{Step, LAW};
use crate::ir::{Cnc, HeightLoop, HeightSensor, Kinematics, Ring};
use crate::numbers::{fixed, trimmed};
use crate::plan::{Move, MoveKind, Speed};
use crate::target::gcode::POS_DECIMALS;
use crate::target::names::gcode_file;
use crate::verify::VerifiedMachine;
use std::io::Write;

/// Decimals of the loop's constants.
const CONST_DECIMALS: usize = 6;

/// Writes the LinuxCNC program of a CNC that runs the ring's loop.
pub fn emit(
    m: VerifiedMachine<'_>,
    cnc: &Cnc,
    t: &Templates,
    sink: &mut dyn Sink,
) -> Result<(), EmitError> {
    let prog = m.ir();
    let Prepared {
        ring,
        law,
        sensor,
        plan,
    } = prepare(m, cnc.height_sensor, "G-code")?;
    let kin = cnc.effective_kinematics();
    let five = kin != Kinematics::Xyz;
    let file = gcode_file(&prog.part, cnc);
    let base = base_context(m, cnc, kin, &file);
    let mut ctx = base.clone();
    header_context(&mut ctx, prog, cnc, five);
    let header = t
        .render("gcode/header.tera", &ctx)
        .map_err(EmitError::Template)?;

    let mut w = Text {
        out: String::new(),
        cnc,
        tilt: kin.tilt_letter(),
        stats: Default::default(),
    };
    w.constants(&plan, ring, law, sensor);
    w.subroutine();
    w.head(&plan);
    w.layers(&plan, ring, sensor);
    w.tail(&plan);

    let mut ctx = base.clone();
    footer_context(&mut ctx, prog, cnc, five, w.stats);
    let footer = t
        .render("gcode/footer.tera", &ctx)
        .map_err(EmitError::Template)?;
    let mut out = sink.create(&file)?;
    out.write_all(header.as_bytes())?;
    out.write_all(w.out.as_bytes())?;
    out.write_all(footer.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// The program's text being written.
struct Text<'a> {
    out: String,
    cnc: &'a Cnc,
    /// The tilt axis's letter on a 5-axis head.
    tilt: Option<char>,
    stats: super::writer::Stats,
}

/// `[a + b]` written with the sign of `b`: `[#<x> - 8.000]`.
fn plus(a: &str, b: f64) -> String {
    let sign = if b < 0.0 { '-' } else { '+' };
    format!("[{a} {sign} {}]", fixed(b.abs(), POS_DECIMALS))
}

impl Text<'_> {
    fn line(&mut self, indent: usize, text: &str) {
        for _ in 0..indent {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn comment(&mut self, indent: usize, text: &str) {
        let style = self.cnc.dialect.comment;
        let (open, close) = delimiters(style);
        let text = format!("{open}{}{close}", comment_safe(text, style));
        self.line(indent, &text);
    }

    /// ` A… C…` on a tilting head, else nothing.
    fn rotary(&self, m: &Move) -> String {
        match self.tilt {
            Some(letter) => format!(
                " {letter}{} C{}",
                fixed(m.axes.tilt, POS_DECIMALS),
                fixed(m.axes.c, POS_DECIMALS)
            ),
            None => String::new(),
        }
    }

    fn f(&self, v: f64) -> String {
        trimmed(
            v * self.cnc.dialect.feed.per_mm_s(),
            crate::target::gcode::f_decimals(self.cnc.dialect.feed),
        )
    }

    fn s(&self, power: f32) -> String {
        fixed(
            power as f64 * self.cnc.dialect.s_per_watt,
            self.cnc.dialect.s_decimals,
        )
    }

    /// The loop's constants and each segment's start values.
    fn constants(&mut self, plan: &LoopPlan, ring: &Ring, law: &HeightLoop, sensor: HeightSensor) {
        self.comment(
            0,
            "the height loop (control::law): after each layer every segment's measured height sets its speed and working plane",
        );
        let c = |v: f64| trimmed(v, CONST_DECIMALS);
        for (name, v, what) in constants(ring, law, &sensor) {
            let style = self.cnc.dialect.comment;
            let (open, close) = delimiters(style);
            let what = comment_safe(what, style);
            self.line(0, &format!("#<_lmd_{name}> = {} {open}{what}{close}", c(v)));
        }
        self.comment(
            0,
            "per segment: speed mm/s, sum of height errors mm, working plane mm",
        );
        for (j, s) in ring.segments.iter().enumerate() {
            let z0 = plan.first_plane(j, s.defocus);
            let k = j + 1;
            self.line(0, &format!("#<_lmd_v{k}> = {}", c(s.speed)));
            self.line(0, &format!("#<_lmd_s{k}> = 0"));
            self.line(0, &format!("#<_lmd_z{k}> = {}", fixed(z0, POS_DECIMALS)));
        }
    }

    /// `o<lmd_pi>`: the law's steps on one segment's values.
    fn subroutine(&mut self) {
        self.comment(
            0,
            "o<lmd_pi> call [measured height mm] [speed] [error sum] [working plane]: sets #<_lmd_v> #<_lmd_s> #<_lmd_z>",
        );
        self.line(0, "o<lmd_pi> sub");
        for step in LAW {
            match step {
                Step::Error => self.line(1, "#<e> = [#<_lmd_hr> - #1]"),
                Step::Sum => self.line(1, "#3 = [#3 + #<e>]"),
                Step::Speed => self.line(1, "#2 = [#2 + #<_lmd_kp> * #<e> + #<_lmd_ki> * #3]"),
                Step::ClampLow => {
                    self.line(1, "o<lmd_pi_low> if [#2 LT #<_lmd_vmin>]");
                    self.line(2, "#2 = #<_lmd_vmin>");
                    self.line(1, "o<lmd_pi_low> endif");
                }
                Step::ClampHigh => {
                    self.line(1, "o<lmd_pi_high> if [#2 GT #<_lmd_vmax>]");
                    self.line(2, "#2 = #<_lmd_vmax>");
                    self.line(1, "o<lmd_pi_high> endif");
                }
                Step::Plane => self.line(1, "#4 = [#4 + #1]"),
            }
        }
        self.line(1, "#<_lmd_v> = #2");
        self.line(1, "#<_lmd_s> = #3");
        self.line(1, "#<_lmd_z> = #4");
        self.line(0, "o<lmd_pi> endsub");
    }

    /// The moves before the first deposit, then the laser on.
    fn head(&mut self, plan: &LoopPlan) {
        self.comment(0, "to the ring's first point");
        let n = plan.head.len();
        for (i, m) in plan.head.iter().enumerate() {
            if i + 1 == n {
                self.cell(&plan.prepare);
            }
            let rot = self.rotary(m);
            let [x, y, z] = m.to.map(|v| fixed(v, POS_DECIMALS));
            if m.kind == MoveKind::Lift {
                // Z alone first, from wherever the machine stands.
                self.line(0, &format!("G0 Z{z}"));
                self.stats.rapids += 1;
                continue;
            }
            match m.speed {
                Speed::Rapid => {
                    self.line(0, &format!("G0 X{x} Y{y} Z{z}{rot}"));
                    self.stats.rapids += 1;
                }
                Speed::Feed(v) => {
                    let (f, s) = (self.f(v as f64), self.s(m.power));
                    self.line(0, &format!("G1 X{x} Y{y} Z{z}{rot} F{f} S{s}"));
                    self.stats.approaches += 1;
                }
            }
        }
        if let Some(first) = plan.body.first() {
            // S before the laser fires, unless the approach set it.
            let approached = plan.head.last().is_some_and(|m| {
                matches!(m.speed, Speed::Feed(_)) && m.power == first.planned.power
            });
            if !approached {
                let s = self.s(first.planned.power);
                self.line(0, &format!("S{s}"));
            }
            let on = self.cnc.dialect.laser_on.clone();
            self.line(0, on.trim_end());
            self.stats.laser_switches += 1;
        }
    }

    fn layers(&mut self, plan: &LoopPlan, ring: &Ring, sensor: HeightSensor) {
        if plan.layers <= 1 {
            self.comment(0, "the only layer");
            self.layer(&plan.body, ring, 0, true);
            self.stats.deposits = plan.body.len() as u64;
            return;
        }
        self.comment(
            0,
            &format!(
                "layers 1 .. {}: the same {} moves, each segment at its speed and working plane",
                plan.layers - 1,
                plan.body.len()
            ),
        );
        self.line(0, &format!("o<lmd_layers> repeat [{}]", plan.layers - 1));
        self.layer(&plan.body, ring, 1, false);
        self.reads(ring, sensor);
        self.line(0, "o<lmd_layers> endrepeat");
        self.comment(
            0,
            &format!(
                "layer {}: the last; its last transition stays level and the build ends there",
                plan.layers
            ),
        );
        self.layer(&plan.last, ring, 0, true);
        // The footer counts the moves the machine makes, not the lines.
        self.stats.deposits = (plan.body.len() * (plan.layers - 1) + plan.last.len()) as u64;
    }

    /// The seam: every segment's mean height, and the law on each.
    fn reads(&mut self, ring: &Ring, sensor: HeightSensor) {
        self.comment(
            1,
            "the seam: M66 stops the motion here, laser on, to read every segment's mean height",
        );
        if sensor.delay > 0.0 {
            self.comment(1, "until the last segment's mean is on its input");
            self.line(1, &format!("G4 P{}", trimmed(sensor.delay, 3)));
        }
        for j in 0..ring.segments.len() {
            let k = j + 1;
            let input = sensor.input as usize + j;
            self.line(1, &format!("M66 E{input} L0"));
            self.line(
                1,
                &format!(
                    "o<lmd_pi> call [#5399 * #<_lmd_hscale>] [#<_lmd_v{k}>] [#<_lmd_s{k}>] [#<_lmd_z{k}>]"
                ),
            );
            self.line(1, &format!("#<_lmd_v{k}> = #<_lmd_v>"));
            self.line(1, &format!("#<_lmd_s{k}> = #<_lmd_s>"));
            self.line(1, &format!("#<_lmd_z{k}> = #<_lmd_z>"));
        }
    }

    /// One layer's moves.
    fn layer(&mut self, moves: &[LayerMove], ring: &Ring, ind: usize, last: bool) {
        let n = ring.segments.len();
        for m in moves {
            let j = m.segment;
            let k = j + 1;
            if m.first {
                self.segment(j, ring, ind, last && j + 1 == n);
            }
            let z = match m.part {
                Part::Flat => "#<zf>".to_string(),
                Part::Transition { step, of } if step == of => "#<zt>".to_string(),
                Part::Transition { step, of } => format!(
                    "[#<zf> + [#<zt> - #<zf>] * {}]",
                    trimmed(step as f64 / of as f64, 6)
                ),
            };
            let [x, y] = [m.planned.to[0], m.planned.to[1]].map(|v| fixed(v, POS_DECIMALS));
            let rot = self.rotary(&m.planned);
            let per = self.cnc.dialect.feed.per_mm_s();
            let words = if m.first {
                format!(
                    " F[#<_lmd_v{k}> * {}] S{}",
                    trimmed(per, 3),
                    self.s(m.planned.power)
                )
            } else if matches!(m.part, Part::Transition { step: 1, .. }) {
                format!(
                    " F[#<_lmd_v{k}> * {} * SQRT[1 + [[#<zt> - #<zf>] / #<_lmd_arc>] ** 2]]",
                    trimmed(per, 3)
                )
            } else {
                String::new()
            };
            self.line(ind, &format!("G1 X{x} Y{y} Z{z}{rot}{words}"));
            self.stats.deposits += 1;
        }
    }

    /// A segment's heights, set before its first move: its own (`zf`) and
    /// where its transition leads (`zt`).
    fn segment(&mut self, j: usize, ring: &Ring, ind: usize, level: bool) {
        let s = &ring.segments[j];
        let n = ring.segments.len();
        self.comment(ind, &crate::back::height_loop::segment_title(ring, j));
        let zf = plus(&format!("#<_lmd_z{}>", j + 1), s.defocus);
        self.line(ind, &format!("#<zf> = {zf}"));
        let zt = if level {
            "#<zf>".to_string()
        } else if j + 1 == n {
            // Segment 1 is read at the seam, after this transition: climb to
            // where it will be if it laid the target height.
            plus("#<_lmd_z1> + #<_lmd_hr>", ring.segments[0].defocus)
        } else {
            plus(&format!("#<_lmd_z{}>", j + 2), ring.segments[j + 1].defocus)
        };
        self.line(ind, &format!("#<zt> = {zt}"));
    }

    /// The laser off, then the retract, relative to where the build ended.
    fn tail(&mut self, plan: &LoopPlan) {
        self.comment(0, "the build is done: back off from where it ended");
        let off = self.cnc.dialect.laser_off.clone();
        self.line(0, off.trim_end());
        let end = plan.last.last().or(plan.body.last()).map(|m| m.planned.to);
        for m in &plan.tail {
            let rot = self.rotary(m);
            let [x, y] = [m.to[0], m.to[1]].map(|v| fixed(v, POS_DECIMALS));
            let z = match end {
                Some(e) => plus("#<zt>", m.to[2] - e[2]),
                None => fixed(m.to[2], POS_DECIMALS),
            };
            self.line(0, &format!("G0 X{x} Y{y} Z{z}{rot}"));
            self.stats.rapids += 1;
        }
        self.cell(&plan.finish);
        // Then Z alone up to the safe height, over where the build ended.
        for m in &plan.park {
            let z = match end {
                Some(e) => plus("#<zt>", m.to[2] - e[2]),
                None => fixed(m.to[2], POS_DECIMALS),
            };
            self.line(0, &format!("G0 Z{z}"));
            self.stats.rapids += 1;
        }
    }

    /// Gas and powder, in the dialect's output and dwell lines.
    fn cell(&mut self, steps: &[CellStep]) {
        let comment = delimiters(self.cnc.dialect.comment);
        for step in steps {
            match *step {
                CellStep::Io(e) => {
                    for l in super::io_lines(&self.cnc.cell, comment, e) {
                        self.line(0, &l);
                    }
                }
                CellStep::Dwell(t) => {
                    let l = super::dwell_line(&self.cnc.dialect.dwell, t);
                    self.line(0, &l);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::plus;

    #[test]
    fn sums_keep_their_sign_outside_the_number() {
        assert_eq!(plus("#<a>", -8.0), "[#<a> - 8.000]");
        assert_eq!(plus("#<a>", 0.23), "[#<a> + 0.230]");
    }
}

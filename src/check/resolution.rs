//! Values as the program writes them. A power, speed or position is written only
//! when the machine's settings let the program say it: within
//! [`WRITE_TOLERANCE`] of the plan, never rounded to 0, never too large to print
//! (the formatters would otherwise have to write *something*). Each rule names
//! the setting that would fix it.

use super::worst::{plural, Worst};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::{Cnc, Machine, MachineOrigin, Robot};
use crate::plan::{Move, Speed};
use crate::target::{gcode, kuka, quantised, written, MAX_WRITTEN, WRITE_TOLERANCE};
use crate::units::short;

/// Powers and speeds one machine cannot write, and positions too large to.
pub(super) struct Resolution {
    /// Planned value and how it would be written (0 if it could not be).
    speed: Option<Worst>,
    power: Option<Worst>,
    /// The smallest positive power and speed planned (what the help sizes
    /// the settings for).
    least_power: f64,
    least_speed: f64,
    position: Option<Worst>,
    /// The last speed and power (f32 bits) found writable: most moves repeat them.
    speed_ok: u32,
    power_ok: u32,
}

impl Resolution {
    pub fn new() -> Self {
        Resolution {
            speed: None,
            power: None,
            least_power: f64::INFINITY,
            least_speed: f64::INFINITY,
            position: None,
            // NaN bits: no planned value (all finite) matches them.
            speed_ok: u32::MAX,
            power_ok: u32::MAX,
        }
    }

    #[inline]
    pub fn motion(&mut self, m: &Move, machine: &Machine) {
        if !m.to.iter().all(|v| v.abs() < MAX_WRITTEN)
            || m.axes.tilt.abs() >= MAX_WRITTEN
            || m.axes.c.abs() >= MAX_WRITTEN
        {
            let worst = m.to.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            Worst::hit(&mut self.position, worst, MAX_WRITTEN, m.at);
        }
        let v = match (m.speed, machine) {
            (Speed::Feed(v), _) if v.to_bits() == self.speed_ok => None,
            (Speed::Feed(v), _) => Some((v as f64, v.to_bits())),
            (Speed::Rapid, Machine::Robot(r)) => Some((r.max_speed, u32::MAX)),
            (Speed::Rapid, Machine::Cnc(_)) => None, // G0 has no F
        };
        if let Some((v, bits)) = v {
            let (scale, decimals) = speed_word(machine);
            if quantised(v * scale, decimals).is_some() {
                self.speed_ok = bits;
            } else {
                self.least_speed = self.least_speed.min(v);
                let w = written(v * scale, decimals) / scale;
                Worst::hit(&mut self.speed, v, w, m.source());
            }
        }
        if m.deposits() && m.power > 0.0 && m.power.to_bits() != self.power_ok {
            let p = m.power as f64;
            let (scale, decimals) = power_word(machine);
            if quantised(p * scale, decimals).is_some() {
                self.power_ok = m.power.to_bits();
            } else {
                self.least_power = self.least_power.min(p);
                let w = written(p * scale, decimals) / scale;
                Worst::hit(&mut self.power, p, w, m.source());
            }
        }
    }

    pub fn report(
        self,
        machine: &Machine,
        o: &MachineOrigin,
        speeds: Option<crate::span::Span>,
        out: &mut Diagnostics,
    ) {
        let name = machine.name();
        let tol = short(WRITE_TOLERANCE * 100.0);
        if let Some(w) = self.position {
            out.push(
                Diagnostic::error(
                    Code::Resolution,
                    format!(
                        "machine `{name}` would have to write a position {} mm from the origin at {} ({} move{}): too large to write",
                        short(w.value),
                        w.at,
                        w.count,
                        plural(w.count)
                    ),
                )
                .label(o.at("name"), "machine")
                .help("check the part's dimensions and units"),
            );
        }
        if let Some(w) = self.speed {
            let (text, help, field, what) = match machine {
                Machine::Cnc(c) => {
                    let unit = c.dialect.feed.text();
                    let per = c.dialect.feed.per_mm_s();
                    (
                        format!("F{}", short(w.limit * per)),
                        format!(
                            "F is written in {unit} with {} decimals: speeds below {} mm/s do not come out within {tol} %; \
                             {}raise the speed",
                            gcode::f_decimals(c.dialect.feed),
                            short(0.5 * 10f64.powi(-(gcode::f_decimals(c.dialect.feed) as i32)) / (WRITE_TOLERANCE * per)),
                            if per < 60.0 { "`feed_units = mm_per_min` writes them 60 times finer, or " } else { "" }
                        ),
                        if o.fields.iter().any(|(n, _)| n == "feed_units") {
                            "feed_units"
                        } else {
                            "name"
                        },
                        format!("writes F in {unit} with {} decimals", gcode::f_decimals(c.dialect.feed)),
                    )
                }
                Machine::Robot(_) => (
                    format!("$VEL.CP = {}", short(w.limit / 1000.0)),
                    format!(
                        "$VEL.CP is written in m/s with {} decimals: speeds below {} mm/s do not come out within {tol} % (or at all); raise the speed",
                        kuka::VEL_DECIMALS,
                        short(0.0005 / WRITE_TOLERANCE)
                    ),
                    "name",
                    "writes $VEL.CP in m/s with 6 decimals".to_string(),
                ),
            };
            out.push(
                Diagnostic::error(
                    Code::Resolution,
                    format!(
                        "machine `{name}` cannot write the speed {} mm/s: it would come out as {text}, at {} ({} move{}, the slowest {} mm/s)",
                        short(w.value),
                        w.at,
                        w.count,
                        plural(w.count),
                        short(self.least_speed)
                    ),
                )
                .label(o.at(field), what)
                .label_opt(speeds, "the speeds come from here")
                .help(help),
            );
        }
        if let Some(w) = self.power {
            let d = match machine {
                Machine::Cnc(c) => cnc_power(c, w, self.least_power, o, &tol),
                Machine::Robot(r) => robot_power(r, w, o, &tol),
            };
            out.push(d);
        }
    }
}

/// The speed word's scale (per mm/s) and decimals.
fn speed_word(m: &Machine) -> (f64, usize) {
    match m {
        Machine::Cnc(c) => (c.dialect.feed.per_mm_s(), gcode::f_decimals(c.dialect.feed)),
        Machine::Robot(_) => (1e-3, kuka::VEL_DECIMALS),
    }
}

/// The power word's scale (per W) and decimals.
fn power_word(m: &Machine) -> (f64, usize) {
    match m {
        Machine::Cnc(c) => (c.dialect.s_per_watt, c.dialect.s_decimals),
        Machine::Robot(r) => (1.0 / r.full_scale_power, kuka::ANOUT_DECIMALS),
    }
}

fn cnc_power(c: &Cnc, w: Worst, least: f64, o: &MachineOrigin, tol: &str) -> Diagnostic {
    let spw = c.dialect.s_per_watt;
    let s = w.value * spw;
    let help = if s >= MAX_WRITTEN {
        format!(
            "S = power × s_per_watt = {}: lower `s_per_watt` (S units per watt)",
            short(s)
        )
    } else {
        // The fewest decimals that write the smallest power within the tolerance.
        let need = (0.5 / (WRITE_TOLERANCE * least * spw))
            .log10()
            .ceil()
            .max(0.0) as usize;
        if need <= 4 {
            format!(
                "S = power × s_per_watt is written with s_decimals = {} decimals: set `s_decimals = {need}` \
                 (or a larger `s_per_watt` if the control reads S that way)",
                c.dialect.s_decimals
            )
        } else {
            format!(
                "S = power × s_per_watt = {} for {} W: even 4 decimals cannot write it within {tol} %; \
                 check `s_per_watt` (S units per watt)",
                short(least * spw),
                short(least)
            )
        }
    };
    Diagnostic::error(
        Code::Resolution,
        format!(
            "machine `{}` cannot write the laser power {} W: S would be {} (i.e. {} W), at {} ({} move{})",
            c.name,
            short(w.value),
            short(w.limit * spw),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(
        o.at(if o.fields.iter().any(|(n, _)| n == "s_decimals") {
            "s_decimals"
        } else {
            "s_per_watt"
        }),
        "the S word's scale and decimals come from here",
    )
    .help(help)
}

fn robot_power(r: &Robot, w: Worst, o: &MachineOrigin, tol: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Resolution,
        format!(
            "robot `{}` cannot write the laser power {} W: $ANOUT[{}] = {} would give {} W, at {} ({} move{})",
            r.name,
            short(w.value),
            r.power_out,
            short(w.limit / r.full_scale_power),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(o.at("full_scale"), "the analog output's scale")
    .help(format!(
        "$ANOUT is written with {} decimals of full_scale = {} W: powers below {} W do not come out within {tol} %; \
         declare the full scale the laser really has",
        kuka::ANOUT_DECIMALS,
        short(r.full_scale_power),
        short(r.full_scale_power * 5e-5 / WRITE_TOLERANCE)
    ))
}

//! Rules a machine's motion plan must keep: its speed limit, its axes' travel,
//! a vertical nozzle on a 3-axis CNC, the robot's analog power output. Each rule
//! follows the plan ([`Visit`]) and reports every kind of violation once, with
//! the worst case, at the field of the machine that declares the limit.
//!
//! Limits are compared with the value as the program writes it, exactly (no
//! slack): what the control reads must lie within what was declared.

use super::rule::{MachineCx, PlanRule, Worst};
use crate::diag::message::{self, verify::machine::AnalogOverrun, verify::machine::AxisOverrun};
use crate::diag::Diagnostics;
use crate::ir::MachineField;
use crate::ir::{AxisLimits, Kinematics, Machine, RotaryTable};
use crate::plan::kinematics::tilt_of;
use crate::plan::{table, Move, MoveKind, Speed, Visit, Where};
use crate::target::{gcode, kuka, written as rounded};

/// A normal tilted more than this (deg) cannot be followed by a vertical nozzle.
pub const NEEDS_TILT_DEG: f64 = 0.01;

/// `lmd::machine-speed`: feed moves faster than the machine's `max_speed`.
pub(super) struct SpeedLimit<'p> {
    machine: &'p Machine,
    max: f64,
    /// The speed as written, mm/s, from the planned one.
    written: fn(f64, &Machine) -> f64,
    found: Option<Worst>,
}

impl<'p> PlanRule<'p> for SpeedLimit<'p> {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let (max, written): (f64, fn(f64, &Machine) -> f64) = match cx.machine {
            Machine::Robot(r) => (r.max_speed, robot_speed),
            Machine::Cnc(c) => (c.max_speed, cnc_speed),
        };
        Some(SpeedLimit {
            machine: cx.machine,
            max,
            written,
            found: None,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(message::verify::machine::machine_speed(
            cx.machine.name(),
            &w,
            cx.origin.at(MachineField::MaxSpeed),
            cx.program.origins.bead_speed,
        ));
    }
}

impl Visit for SpeedLimit<'_> {
    #[inline]
    fn motion(&mut self, m: &Move) {
        if let Speed::Feed(v) = m.speed {
            // Well below the limit no rounding can reach it: skip the rounding.
            if (v as f64) < self.max * (1.0 - 1e-6) {
                return;
            }
            let w = (self.written)(v as f64, self.machine);
            if w > self.max {
                Worst::hit(&mut self.found, w, self.max, m.source());
            }
        }
    }
}

fn cnc_speed(v: f64, m: &Machine) -> f64 {
    match m {
        Machine::Cnc(c) => {
            let per = c.dialect.feed.per_mm_s();
            rounded(v * per, gcode::f_decimals(c.dialect.feed)) / per
        }
        Machine::Robot(_) => v,
    }
}

fn robot_speed(v: f64, _: &Machine) -> f64 {
    rounded(v / 1000.0, kuka::VEL_DECIMALS) * 1000.0
}

/// `lmd::axis-limit`: positions and rotary angles beyond a CNC's travel.
/// Positions are the program's plus the placement's origin: what the
/// machine's axes reach.
pub(super) struct Travel {
    lim: AxisLimits,
    origin: [f64; 3],
    /// A tilting table: positions are checked where its inverse
    /// kinematics puts the machine's axes.
    table: Option<(Kinematics, RotaryTable)>,
    /// Whether the rotary axes exist (and are checked).
    five: bool,
    /// X Y Z tilt C.
    axes: [Option<Worst>; 5],
    /// The program positions' extent, for the placement that would fit.
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Visit for Travel {
    #[inline]
    fn motion(&mut self, m: &Move) {
        let l = &self.lim;
        let o = self.origin;
        let to = match &self.table {
            Some((kin, t)) => table::written(*kin, t, o, m.to, m.axes),
            None => m.to,
        };
        for (i, &v) in to.iter().enumerate() {
            self.lo[i] = self.lo[i].min(v);
            self.hi[i] = self.hi[i].max(v);
        }
        // A value a printed digit inside its range is inside however it is
        // rounded; only values at the edge are rounded as written (in `miss`).
        const EDGE: f64 = 1e-3;
        let inside = |v: f64, r: [f64; 2]| v >= r[0] + EDGE && v <= r[1] - EDGE;
        let ok = inside(to[0] + o[0], l.x)
            && inside(to[1] + o[1], l.y)
            && inside(to[2] + o[2], l.z)
            && (!self.five || (inside(m.axes.tilt, l.tilt) && inside(m.axes.c, l.rotary)));
        if !ok {
            self.miss(m, to);
        }
    }
}

impl Travel {
    /// `m` leaves the travel somewhere; `to` is its position under the
    /// origin (a table's: in machine coordinates).
    #[cold]
    fn miss(&mut self, m: &Move, to: [f64; 3]) {
        let l = self.lim;
        let o = self.origin;
        let vals = [
            (to[0] + o[0], l.x),
            (to[1] + o[1], l.y),
            (to[2] + o[2], l.z),
            (m.axes.tilt, l.tilt),
            (m.axes.c, l.rotary),
        ];
        let n = if self.five { 5 } else { 3 };
        for (i, &(v, r)) in vals.iter().enumerate().take(n) {
            // As the program writes it: the position (or angle) rounded, plus
            // the origin for positions.
            let v = if i < 3 {
                rounded(v - o[i], gcode::POS_DECIMALS) + o[i]
            } else {
                rounded(v, gcode::POS_DECIMALS)
            };
            if v < r[0] {
                Worst::hit(&mut self.axes[i], v, r[0], m.at);
            } else if v > r[1] {
                Worst::hit(&mut self.axes[i], v, r[1], m.at);
            }
        }
    }
}

impl<'p> PlanRule<'p> for Travel {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Cnc(c) = cx.machine else {
            return None;
        };
        let kin = c.effective_kinematics();
        Some(Travel {
            lim: c.limits,
            origin: c.placement.origin,
            table: c.table.filter(|_| kin.is_table()).map(|t| (kin, t)),
            five: kin != Kinematics::Xyz,
            axes: [None; 5],
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let Machine::Cnc(cnc) = cx.machine else {
            return;
        };
        let tilt_name = if cnc.effective_kinematics().tilt_letter() == Some('B') {
            "B"
        } else {
            "A"
        };
        let tilt = if tilt_name == "B" {
            MachineField::Limit('B')
        } else {
            MachineField::Limit('A')
        };
        let fields = [
            MachineField::Limit('X'),
            MachineField::Limit('Y'),
            MachineField::Limit('Z'),
            tilt,
            MachineField::Limit('C'),
        ];
        let lim = self.lim;
        let ranges = [lim.x, lim.y, lim.z, lim.tilt, lim.rotary];
        for (i, w) in self.axes.iter().enumerate() {
            let Some(w) = w else { continue };
            let linear = i < 3;
            out.push(message::verify::machine::axis_limit(&AxisOverrun {
                machine: &cnc.name,
                axis: i,
                tilt_name,
                worst: *w,
                range: ranges[i],
                extent: if linear {
                    [self.lo[i], self.hi[i]]
                } else {
                    [0.0; 2]
                },
                origin: if linear { cnc.placement.origin[i] } else { 0.0 },
                clearance: (!matches!(w.at, Where::Point { .. })).then_some(cnc.clearance),
                declared: cx.origin.at(fields[i]),
            }));
        }
    }
}

/// `lmd::needs-tilt`: normals a vertical nozzle cannot follow (3-axis CNCs).
pub(super) struct Tilt {
    tan2: f64,
    found: Option<Worst>,
}

impl Visit for Tilt {
    #[inline]
    fn motion(&mut self, m: &Move) {
        // Only the IR's points: the clearance moves repeat their normals.
        if !matches!(m.at, Where::Point { .. }) {
            return;
        }
        let n = m.normal;
        let (x, y, z) = (n[0] as f64, n[1] as f64, n[2] as f64);
        if z <= 0.0 || x * x + y * y > self.tan2 * z * z {
            Worst::hit(&mut self.found, tilt_of([x, y, z]), NEEDS_TILT_DEG, m.at);
        }
    }
}

impl<'p> PlanRule<'p> for Tilt {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Cnc(c) = cx.machine else {
            return None;
        };
        (c.effective_kinematics() == Kinematics::Xyz).then(|| Tilt {
            tan2: NEEDS_TILT_DEG.to_radians().tan().powi(2),
            found: None,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(message::verify::machine::needs_tilt(
            cx.machine.name(),
            &w,
            cx.origin.at(MachineField::Axes),
        ));
    }
}

/// `lmd::analog-range`: laser powers beyond the robot's analog output
/// (`$ANOUT` above 1.0).
pub(super) struct Analog {
    full_scale: f64,
    found: Option<Worst>,
}

impl Visit for Analog {
    #[inline]
    fn motion(&mut self, m: &Move) {
        // Below full scale no rounding reaches 1.0: round only near it.
        if m.deposits() && m.power as f64 >= self.full_scale * (1.0 - 1e-4) {
            let x = rounded(m.power as f64 / self.full_scale, kuka::ANOUT_DECIMALS);
            if x > 1.0 {
                Worst::hit(&mut self.found, m.power as f64, self.full_scale, m.source());
            }
        }
    }
}

impl<'p> PlanRule<'p> for Analog {
    fn new(cx: &MachineCx<'p>) -> Option<Self> {
        let Machine::Robot(r) = cx.machine else {
            return None;
        };
        Some(Analog {
            full_scale: r.full_scale_power,
            found: None,
        })
    }

    fn report(self, cx: &MachineCx<'p>, out: &mut Diagnostics) {
        let (Some(w), Machine::Robot(r)) = (self.found, cx.machine) else {
            return;
        };
        out.push(message::verify::machine::analog_range(&AnalogOverrun {
            robot: &r.name,
            output: &r.power_out,
            words: crate::diag::message::words::Words::of(r.controller),
            full_scale: r.full_scale_power,
            needed: rounded(w.value / r.full_scale_power, kuka::ANOUT_DECIMALS),
            worst: w,
            declared: cx.origin.at(MachineField::FullScale),
            power: cx.program.origins.power,
        }));
    }
}

/// `lmd::safe-height`: a CNC's declared `safe_height` that does not clear
/// the part: below its highest point plus the clearance (what the default
/// is), or below a move of the plan (the lifts to it aside). The program's
/// first move goes across at the safe height and it ends there; the plan
/// would quietly start higher and end lower than declared.
pub(super) struct SafeHeight {
    declared: f64,
    clearance: f64,
    /// The highest deposit (the part's top) and the highest move, each
    /// with where it is.
    top: Option<(f64, Where)>,
    highest: Option<(f64, Where)>,
}

impl PlanRule<'_> for SafeHeight {
    fn new(cx: &MachineCx<'_>) -> Option<Self> {
        let Machine::Cnc(c) = cx.machine else {
            return None;
        };
        Some(SafeHeight {
            declared: c.safe_height?,
            clearance: c.clearance,
            top: None,
            highest: None,
        })
    }

    fn report(self, cx: &MachineCx<'_>, out: &mut Diagnostics) {
        let (Some(top), Some(highest)) = (self.top, self.highest) else {
            return;
        };
        let need = (top.0 + self.clearance).max(highest.0);
        // A written Z is rounded to a micrometre: no finer slack is needed.
        if self.declared + 1e-6 >= need {
            return;
        }
        let at = cx
            .origin
            .written(MachineField::SafeHeight)
            .unwrap_or(cx.origin.block);
        out.push(message::verify::machine::safe_height(
            &message::verify::machine::LowSafeHeight {
                machine: cx.machine.name(),
                declared: self.declared,
                top,
                clearance: self.clearance,
                highest,
            },
            at,
        ));
    }
}

impl Visit for SafeHeight {
    #[inline]
    fn motion(&mut self, m: &Move) {
        let z = m.to[2];
        let higher = |slot: &Option<(f64, Where)>| slot.is_none_or(|(h, _)| z > h);
        if m.kind == MoveKind::Deposit && higher(&self.top) {
            self.top = Some((z, m.source()));
        }
        if m.kind != MoveKind::Lift && higher(&self.highest) {
            self.highest = Some((z, m.source()));
        }
    }
}

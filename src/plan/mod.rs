//! The motion plan: the moves one machine makes to build the IR, and when its
//! laser switches. One stage, one set of rules, for every back end: the
//! verifier checks the plan against the machine's limits, and the back ends only
//! write it (KRL, G-code, and any later one).
//!
//! The plan is not stored: [`Plan::walk`] generates it from the IR on demand, in
//! one pass, so a 3.6 M-point part costs no second copy of its points. The same
//! IR and machine always give the same moves, so what the verifier saw is what
//! the writer writes.
//!
//! # The moves
//! Every position is the tool tip: the laser focus ([`Point::focus`]). A path
//! that does not join the one before (and every layer's first path) is reached
//! through a transition:
//! 1. [`MoveKind::Retract`]: `clearance` back up the nozzle from where the last
//!    path ended (not before the first path);
//! 2. [`MoveKind::Travel`]: to `clearance` above the path's first point —
//!    over the top: up to `clearance` above the highest point deposited so
//!    far and every fixture on the way, across, and down, whenever either
//!    end lies lower (a straight line could cut a ridge laid before, a
//!    taller island, a clamp); with a tilted nozzle by what its retract
//!    rises, `clearance·cos θ`, and what its head hangs below the focus;
//! 3. [`MoveKind::Approach`]: down to the first point, at the path's first speed
//!    when the path deposits from its first point, else at the machine's rapid.
//!
//! Then one move per point: [`MoveKind::Deposit`] from a point whose laser is on
//! (at its speed and power), [`MoveKind::Travel`] at rapid from one whose laser
//! is off. A path joins the one before when it starts where that one ended,
//! with the same nozzle direction ([`joins`]): the motion goes straight on.
//!
//! # Start and end
//! One rule for every machine, checked by the verifier like any move. A CNC's
//! first move is a [`MoveKind::Lift`] of Z alone to its safe height
//! ([`safe_height`]) from wherever the machine stands, then a travel across
//! at that height (the rotary axes turning there), then down to above the
//! first path. A robot's first move is a [`MoveKind::FromHome`]: a PTP from
//! its home axes (and its positioner's home angles) to above the first
//! path, which the controller interpolates in the axes (a LIN from KUKA's
//! home, at A5 = 0, would start in the wrist singularity). After the last
//! path every machine ends the same way: the laser off (after its
//! lead-out), a last retract, the feeder off, the gas's post-flow and the
//! gas off; then a CNC lifts Z alone to its safe height (in the part's
//! frame, whatever its table's output mode: [`Plan::lift_at_end`]) and a
//! robot goes back home by PTP ([`MoveKind::Home`]).
//!
//! "Up the nozzle" is the point's normal on a robot and a tilting head; on a
//! 3-axis CNC, whose nozzle always points down, it is +Z.
//!
//! # Continuous layers
//! A continuous program (`Program::continuous`, a segmented ring or a
//! spiral wall) is one run of deposit moves: a layer's first path joins the
//! last layer's like any path that starts where the one before ended, so
//! the laser stays on from the first deposit of the build to the last, by
//! the same rule as below. Where the program cools between layers (a
//! `dwell` or `min_layer_time`), the nozzle backs off to wait, and the next
//! layer is reached through the transition as any other: a path joins only
//! where the nozzle still is. Every other program starts each layer with the
//! moves above.
//!
//! # Segment ends
//! On a ring, [`Visit::segment_end`] comes right before the move that ends a
//! segment (its transition's last): where a closed loop measures the segment
//! it has just laid and updates its speed. One event, for every back end: the
//! KRL writer triggers its update routine on that move, the LinuxCNC writer
//! reads its sensors after the last segment's.
//!
//! # Cooling
//! Before each layer but the first the plan dwells, retracted, for the
//! program's interlayer `dwell`, or longer if the layer before took less than
//! its `min_layer_time` (counting its feed moves at their speeds; rapid moves
//! count as instant, so the real time is at least the minimum).
//!
//! # The laser
//! One rule for every back end: **the laser is on exactly during deposit moves.**
//! It switches on ([`Visit::laser_on`]) at the start point of a run of deposit
//! moves, after the move that reached it, and off ([`Visit::laser_off`]) at the
//! end point of the run, before the next move or layer begins. A deposit move's
//! power applies from its start. Paths that join keep the laser on when both
//! sides deposit: the last point's own flag (off: nothing follows it in its
//! path) switches nothing, since no move starts there.
//!
//! # Leads
//! A machine with `ramp = lead` (and an `acceleration` `a`) starts every run
//! of deposits on a lead-in and ends it with a lead-out, so the nozzle is at
//! speed wherever the laser switches ([`profile`] says why): the
//! [`MoveKind::LeadIn`] runs, laser off, at the run's first speed `v` onto
//! its first point along its first move's direction, `v²/2a` long plus the
//! machine's corner blending (the control may round the corner onto it over
//! that much), and the laser switches on where it ends; the [`MoveKind::LeadOut`] goes on from
//! the run's last point along its last move at its speed, `v²/2a` long,
//! after the laser switched off there. The approach comes down onto the
//! lead-in's start; a gap inside a path (a linked raster's laser-off link
//! among them) travels straight from the lead-out's end to it, not along
//! the gap's points; where a run's start is reached along a separate path
//! that joins, the nozzle first backs up to it. The retract, travel or
//! cooling after a run start where its lead-out ends. The blending is the
//! machine's, else what its program sets ([`crate::target::blending`]). A
//! ring whose loop runs on the machine gets no leads (its programs write
//! their own moves).
//!
//! A path of the IR's kind [`Lead`](crate::ir::PathKind::Lead) (a wall
//! along an open path with `ends = lead(…)`) is a lead of its own: its
//! moves run at its points' speed with the laser off, as a
//! [`MoveKind::LeadOut`] where it goes on from a run under way, else as a
//! [`MoveKind::LeadIn`] onto the run that joins its end; the machine's own
//! lead-in and lead-out are then left out.

pub mod arm;
pub mod kinematics;
pub mod lines;
pub mod orient;
pub mod part_frame;
pub mod positioner;
pub mod profile;
pub mod spin;
pub mod table;

use crate::ir::{AxisLimits, Cell, Kinematics, Layer, Machine, Point, Program, Ramp, Ring};
use crate::target::{self, POSITION_STEP};
use kinematics::Rotary;

/// A path joins the previous one when it starts within this distance (mm) of
/// where the previous one ended ...
pub const JOIN_MM: f64 = 1e-3;

/// ... with a normal whose components differ by at most this (about 0.0006°).
pub const JOIN_NORMAL: f32 = 1e-5;

/// What a move is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MoveKind {
    /// Laser on, laying a bead.
    Deposit,
    /// Laser off, down to a path's first point.
    Approach,
    /// Laser off, back up the nozzle by the clearance.
    Retract,
    /// Laser off, between clearance positions or over a gap inside a path.
    Travel,
    /// Laser off, along the path onto a run's first point at the run's
    /// first speed, `v²/2a` long: the nozzle is up to speed where the laser
    /// switches on (`ramp = lead`).
    LeadIn,
    /// Laser off, on along a run's last direction from its end at its last
    /// speed, `v²/2a` long: the nozzle brakes after the laser is off.
    LeadOut,
    /// Laser off, a CNC's Z alone up to its safe height, every other axis
    /// where it stands: the program's first move (from wherever the machine
    /// is) and its last. Its `to` is the safe height over the next (or
    /// last) position; a writer moves only Z. On a table written in machine
    /// coordinates, the last one goes up the machine's Z to where the tip
    /// is at the safe height of the part ([`Plan::lift_at_end`]).
    Lift,
    /// Laser off, a robot's first move: a PTP from its home axes (and its
    /// positioner's home angles) to above the first path. The controller
    /// interpolates the axes, not a line, so no wrist singularity lies on
    /// its way (a LIN from KUKA's home, at A5 = 0, would start in one).
    FromHome,
    /// Laser off, a robot's last move: a PTP back to its home axes (and its
    /// positioner's home angles), after the last retract and the cell's end
    /// sequence. Home is given by axis angles, not a position: its `to` is
    /// where the robot stands when it starts (no line is travelled), its
    /// `axes` the positioner's home angles.
    Home,
}

impl MoveKind {
    /// Whether the controller interpolates the move in its axes (a robot's
    /// PTP), not along a straight line.
    pub fn ptp(self) -> bool {
        matches!(self, MoveKind::FromHome | MoveKind::Home)
    }
}

/// How fast a move goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Speed {
    /// As fast as the machine moves with the laser off (G0; KRL: `max_speed`).
    Rapid,
    /// This path speed, mm/s.
    Feed(f32),
}

/// Where a move's target comes from, for diagnostics (0-based indices).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Where {
    /// The IR point itself.
    Point {
        /// Layer index.
        layer: usize,
        /// Path index in the layer.
        path: usize,
        /// Point index in the path.
        point: usize,
    },
    /// The retract and travel before a path.
    Clearance {
        /// Layer index.
        layer: usize,
        /// Path index in the layer.
        path: usize,
    },
    /// The retract after the last path.
    End,
}

impl Where {
    /// The IR point this is, if it is one.
    pub fn point<'p>(&self, program: &'p Program) -> Option<&'p Point> {
        match *self {
            Where::Point { layer, path, point } => program
                .layers
                .get(layer)?
                .paths
                .get(path)?
                .points
                .get(point),
            _ => None,
        }
    }
}

impl std::fmt::Display for Where {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Where::Point { layer, path, point } => write!(
                f,
                "layer {}, path {}, point {}",
                layer + 1,
                path + 1,
                point + 1
            ),
            Where::Clearance { layer, path } => write!(
                f,
                "the clearance move before layer {}, path {}",
                layer + 1,
                path + 1
            ),
            Where::End => f.write_str("the retract after the last path"),
        }
    }
}

/// One move of the machine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Move {
    /// What it is for.
    pub kind: MoveKind,
    /// The tool tip's target, mm.
    pub to: [f64; 3],
    /// The nozzle direction at the target (the IR normal: up the nozzle).
    pub normal: [f32; 3],
    /// The rotary axes at the target on a tilting head or table; a robot's
    /// positioner's E1 (`tilt`) and E2 (`c`); zero elsewhere.
    pub axes: Rotary,
    /// How fast.
    pub speed: Speed,
    /// Laser power during the move, W (the path's power on an approach, so a
    /// writer can preset it; only deposits fire the laser).
    pub power: f32,
    /// Where the target comes from.
    pub at: Where,
}

impl Move {
    /// Whether the laser is on during this move.
    pub fn deposits(&self) -> bool {
        self.kind == MoveKind::Deposit
    }

    /// The IR point whose speed and power the move carries: the point it
    /// starts from inside a path (the IR gives a point's values "from this
    /// point to the next"), else where its target comes from.
    pub fn source(&self) -> Where {
        match (self.kind, self.at) {
            (MoveKind::Deposit | MoveKind::Travel, Where::Point { layer, path, point })
                if point > 0 =>
            {
                Where::Point {
                    layer,
                    path,
                    point: point - 1,
                }
            }
            (_, at) => at,
        }
    }
}

/// A switching event of the cell's gas or powder (`Machine::cell`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Io {
    /// Open the shielding gas.
    GasOn,
    /// Close it.
    GasOff,
    /// Start the powder feeder; with a rate output, at this rate (g/min),
    /// set first.
    PowderOn(f32),
    /// Set the feeder's rate output to this rate (g/min) while it runs.
    PowderRate(f32),
    /// Stop the feeder.
    PowderOff,
}

/// A ring's segment ends with the next move ([`Visit::segment_end`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentEnd {
    /// The layer, from 0.
    pub layer: usize,
    /// The segment, from 0.
    pub segment: usize,
    /// Whether it is the layer's last segment: the move ends the layer, and
    /// the next layer (if any) starts where it ends.
    pub last: bool,
}

/// What follows the plan: a verifier rule or a back end's writer.
pub trait Visit {
    /// Layer `number` (0-based) begins; its moves follow.
    fn layer(&mut self, _index: usize, _layer: &Layer) {}
    /// The laser switches on here, before `next` (a deposit) starts.
    fn laser_on(&mut self, _next: &Move) {}
    /// The laser switches off here, after the last deposit move.
    fn laser_off(&mut self) {}
    /// A move.
    fn motion(&mut self, m: &Move);
    /// Wait here for `seconds`, standing still with the laser off: a layer
    /// cools, or gas and powder settle.
    fn dwell(&mut self, _seconds: f64) {}
    /// Switch the cell's gas or powder here, with the laser off.
    fn io(&mut self, _event: Io) {}
    /// A ring's segment ends with the next move.
    fn segment_end(&mut self, _end: SegmentEnd) {}
    /// Whether it has seen what it needs (a help's probe that has met what
    /// refuses it): the walk then stops before the next path, without the
    /// plan's end.
    fn done(&self) -> bool {
        false
    }
}

/// A closure told every move (and nothing else): the shortest walker.
impl<F: FnMut(&Move)> Visit for F {
    fn motion(&mut self, m: &Move) {
        self(m)
    }
}

/// Two visitors following one plan side by side (the verifier's rules and
/// its summary), each told everything in turn.
impl<A: Visit, B: Visit> Visit for (A, B) {
    fn layer(&mut self, index: usize, layer: &Layer) {
        self.0.layer(index, layer);
        self.1.layer(index, layer);
    }
    fn laser_on(&mut self, next: &Move) {
        self.0.laser_on(next);
        self.1.laser_on(next);
    }
    fn laser_off(&mut self) {
        self.0.laser_off();
        self.1.laser_off();
    }
    #[inline]
    fn motion(&mut self, m: &Move) {
        self.0.motion(m);
        self.1.motion(m);
    }
    fn dwell(&mut self, seconds: f64) {
        self.0.dwell(seconds);
        self.1.dwell(seconds);
    }
    fn io(&mut self, event: Io) {
        self.0.io(event);
        self.1.io(event);
    }
    fn segment_end(&mut self, end: SegmentEnd) {
        self.0.segment_end(end);
        self.1.segment_end(end);
    }
    fn done(&self) -> bool {
        self.0.done() && self.1.done()
    }
}

/// How a machine moves, as far as the plan is concerned.
#[derive(Clone, Copy, Debug)]
enum Head {
    /// Nozzle along the normal, oriented by the back end (robots).
    Free,
    /// A CNC that keeps the nozzle vertical.
    Vertical,
    /// A CNC with a tilting head: the plan solves its rotary axes.
    Tilting(Kinematics, AxisLimits),
}

/// The motion plan of one machine for one IR.
#[derive(Clone, Copy, Debug)]
pub struct Plan<'a> {
    program: &'a Program,
    head: Head,
    /// What the machine carries along the beam: how low and how wide it
    /// hangs about the focus, for the travels over what is there.
    tool: &'a crate::ir::Head,
    clearance: f64,
    cell: &'a Cell,
    /// The acceleration leads are sized by, and the corner blending a
    /// lead-in adds, when the machine has leads.
    lead: Option<(f64, f64)>,
    /// A CNC's safe height: declared, else the highest focus plus the
    /// clearance (none on a robot, which starts and ends at home).
    safe: Option<f64>,
    /// The machine planned for.
    machine: &'a Machine,
    /// A robot's positioner's angles, each layer's E1 and E2 (deg): a
    /// move's `axes` (tilt E1, C E2), the part's base turning with them.
    held: Option<&'a [[f64; 2]]>,
    /// A robot's home: its positioner's home angles (zero without one). A
    /// robot starts and ends there by PTP; a CNC has none.
    home: Option<Rotary>,
    /// A table written in machine coordinates: its last lift goes up the
    /// machine's Z, which the tilted table does not turn.
    machine_table: Option<(Kinematics, crate::ir::RotaryTable)>,
    /// A robot's positioner's top speeds (E1, E2, deg/s) and the robot's
    /// rapid (mm/s): a laser-off line that turns the positioner is slowed
    /// so that neither axis goes faster ([`Plan::held_to_axes`]).
    turns: Option<([f64; 2], f64)>,
}

/// A line whose axes turn by `turn` (deg, each axis) over `d` mm at `speed`:
/// the speed slowed so no axis turns faster than its top speed `tops`
/// (deg/s). A line of no length keeps its speed: the controller turns axes
/// alone at their own speeds. The one rule a plan's laser-off lines and
/// the verifier's check of them share.
pub fn held_to_axes(speed: f64, d: f64, turn: [f64; 2], tops: [f64; 2]) -> f64 {
    let need = (0..2)
        .map(|i| turn[i].abs() / tops[i])
        .fold(0.0f64, f64::max);
    if d <= JOIN_MM || need <= 0.0 || d / speed >= need {
        speed
    } else {
        d / need
    }
}

/// The height a CNC lifts to first and ends at: `declared`, else
/// `clearance` above the highest focus of the program or the highest
/// fixture's top, whichever is higher (what no retract, travel or approach
/// rises above).
pub fn safe_height(
    program: &Program,
    fixtures: &[part_frame::Placed<'_>],
    declared: Option<f64>,
    clearance: f64,
) -> f64 {
    declared.unwrap_or_else(|| {
        let top = program
            .layers
            .iter()
            .flat_map(|l| &l.paths)
            .flat_map(|p| &p.points)
            .map(|p| p.focus()[2])
            .chain(fixtures.iter().map(|f| f.bounds.1[2]))
            .fold(f64::NEG_INFINITY, f64::max);
        if top.is_finite() {
            top + clearance
        } else {
            clearance
        }
    })
}

impl<'a> Plan<'a> {
    /// The plan of `machine` for `program`.
    pub fn new(program: &'a Program, machine: &'a Machine) -> Self {
        let head = match machine {
            Machine::Robot(_) => Head::Free,
            Machine::Cnc(c) => match c.effective_kinematics() {
                Kinematics::Xyz => Head::Vertical,
                k => Head::Tilting(k, c.limits),
            },
        };
        let common = machine.common();
        let lead = match (common.ramp, common.acceleration) {
            (Ramp::Lead, Some(a)) if a > 0.0 && program.loop_on_machine().is_none() => {
                Some((a, crate::target::blending(machine).0))
            }
            _ => None,
        };
        let boxes = part_frame::fixture_boxes(program, machine);
        let safe = match machine {
            Machine::Cnc(c) => Some(safe_height(
                program,
                &boxes,
                c.safe_height,
                common.clearance,
            )),
            Machine::Robot(_) => None,
        };
        let held = match machine {
            Machine::Robot(r) => r.positioner.as_ref().map(|p| p.angles.as_slice()),
            Machine::Cnc(_) => None,
        };
        let home =
            match machine {
                Machine::Robot(r) => Some(r.positioner.as_ref().map_or_else(
                    Rotary::default,
                    |p| Rotary {
                        tilt: p.home[0],
                        c: p.home[1],
                    },
                )),
                Machine::Cnc(_) => None,
            };
        let machine_table = match machine {
            Machine::Cnc(c) => table::machine_output(c).map(|t| (c.effective_kinematics(), t)),
            Machine::Robot(_) => None,
        };
        let turns = match machine {
            Machine::Robot(r) => r
                .positioner
                .as_ref()
                .map(|p| ([p.tilt.speed, p.rotate.speed], r.max_speed)),
            Machine::Cnc(_) => None,
        };
        Plan {
            program,
            head,
            tool: &common.head,
            clearance: common.clearance,
            cell: machine.cell(),
            lead,
            safe,
            machine,
            held,
            home,
            machine_table,
            turns,
        }
    }

    /// Where a CNC's last lift from `last` (part coordinates, the rotary
    /// axes at `axes`) ends: Z alone up to the safe height `safe`. A table
    /// written in machine coordinates moves its Z up the machine's axis,
    /// which a tilted table sees at an angle: the lift goes along it until
    /// the tip is at the safe height of the part, so the program ends
    /// there in either output mode. (Past a tilt of about 87° the machine's
    /// Z barely rises in the part: the lift then goes up the machine's Z by
    /// as much as the safe height is above the tip, at least the clearance.)
    pub fn lift_at_end(&self, last: [f64; 3], axes: Rotary, safe: f64) -> [f64; 3] {
        let rise = safe - last[2];
        let up = match self.machine_table {
            Some((kin, t)) => {
                let o = table::part_point(kin, &t, [0.0; 3], axes);
                let z = table::part_point(kin, &t, [0.0, 0.0, 1.0], axes);
                [z[0] - o[0], z[1] - o[1], z[2] - o[2]]
            }
            None => [0.0, 0.0, 1.0],
        };
        if up[2] < 0.05 {
            return along(last, up, rise.abs().max(self.clearance));
        }
        along(last, up, rise / up[2])
    }

    /// A robot's positioner's angles for layer `li` (its last layer's
    /// beyond them, zero where it has none), as the moves' `axes`.
    fn held(&self, li: usize) -> Option<Rotary> {
        let a = self.held?;
        let e = a.get(li).or(a.last()).copied().unwrap_or_default();
        Some(Rotary {
            tilt: e[0],
            c: e[1],
        })
    }

    /// Whether runs of deposits start on a lead-in and end with a lead-out.
    pub fn leads(&self) -> bool {
        self.lead.is_some()
    }

    /// The IR the plan is made from.
    pub fn program(&self) -> &'a Program {
        self.program
    }

    /// Generates every step of the plan, in order, into `v`.
    pub fn walk(&self, v: &mut impl Visit) {
        let mut w = Walker {
            plan: self,
            v,
            cursor: None,
            retracted: false,
            laser: false,
            layer_time: 0.0,
            timed: self.program.cools(),
            gas: false,
            powder: None,
            ends: None,
            end_next: None,
            last: None,
            last_axes: None,
            last_normal: None,
            run_end: None,
            lead_path: false,
            last_kind: None,
            top: f64::NEG_INFINITY,
            boxes: part_frame::fixture_boxes(self.program, self.machine),
        };
        let continuous = self.program.continuous;
        for (li, layer) in self.program.layers.iter().enumerate() {
            if !continuous {
                w.end_run();
            }
            if li > 0 {
                w.cool(li);
            }
            w.layer_time = 0.0;
            w.v.layer(li, layer);
            // A ring's segment ends in its layer's (first) path.
            w.ends = self
                .program
                .ring
                .as_ref()
                .and_then(|r| SegmentEnds::new(r, li));
            let mut first = !continuous;
            for (pi, path) in layer.paths.iter().enumerate() {
                if path.points.is_empty() {
                    continue;
                }
                if w.v.done() {
                    return;
                }
                // The path after it in the layer, where a gap may end.
                let after = layer.paths[pi + 1..]
                    .iter()
                    .map(|p| p.points.as_slice())
                    .find(|p| !p.is_empty());
                w.lead_path = path.kind == crate::ir::PathKind::Lead;
                w.path(li, pi, (&path.points, after), first);
                first = false;
                w.ends = None;
            }
        }
        w.end();
    }
}

/// Where the segments of one layer of a ring end: every `per` points.
#[derive(Clone, Copy, Debug)]
struct SegmentEnds {
    layer: usize,
    per: usize,
    segments: usize,
}

impl SegmentEnds {
    fn new(r: &Ring, layer: usize) -> Option<Self> {
        let per = r.flat_moves + r.transition_moves;
        (per > 0).then_some(SegmentEnds {
            layer,
            per,
            segments: r.segments.len(),
        })
    }

    /// The segment end reached by the move to point `to` of the layer's path.
    #[inline]
    fn at(&self, to: usize) -> Option<SegmentEnd> {
        if to == 0 || !to.is_multiple_of(self.per) {
            return None;
        }
        let segment = to / self.per - 1;
        (segment < self.segments).then_some(SegmentEnd {
            layer: self.layer,
            segment,
            last: segment + 1 == self.segments,
        })
    }
}

/// Whether a path starting at `next` joins one that ended with its tool tip at
/// `focus` and normal `normal`: same place, same nozzle direction.
pub fn joins(focus: [f64; 3], normal: [f32; 3], next: &Point) -> bool {
    let f = next.focus();
    let d2 = (0..3).map(|i| (f[i] - focus[i]).powi(2)).sum::<f64>();
    d2 <= JOIN_MM * JOIN_MM && (0..3).all(|i| (next.normal[i] - normal[i]).abs() <= JOIN_NORMAL)
}

/// Where the nozzle is between paths.
#[derive(Clone, Copy, Debug)]
struct Cursor {
    focus: [f64; 3],
    normal: [f32; 3],
    axes: Rotary,
}

struct Walker<'p, 'a, V> {
    plan: &'p Plan<'a>,
    v: &'p mut V,
    cursor: Option<Cursor>,
    /// Whether the nozzle already backed off from the cursor's point.
    retracted: bool,
    laser: bool,
    /// Time of the current layer's feed moves, s.
    layer_time: f64,
    /// Whether layers are timed (only for cooling).
    timed: bool,
    /// Whether the gas flows.
    gas: bool,
    /// The powder feeder's rate while it runs (g/min).
    powder: Option<f32>,
    /// Where a ring's segments end in the path being walked.
    ends: Option<SegmentEnds>,
    /// The segment end the next move reaches.
    end_next: Option<SegmentEnd>,
    /// Where the last move ended.
    last: Option<[f64; 3]>,
    /// The rotary axes (a positioner's) the last move ended at.
    last_axes: Option<Rotary>,
    /// The nozzle's direction the last move ended at.
    last_normal: Option<[f32; 3]>,
    /// With leads: where the last deposit started, and the move itself.
    run_end: Option<([f64; 3], Move)>,
    /// Whether the path being walked is a lead of its own
    /// ([`PathKind::Lead`](crate::ir::PathKind::Lead)).
    lead_path: bool,
    /// What the last move sent was.
    last_kind: Option<MoveKind>,
    /// The highest focus deposited so far (Z, mm): travels pass at least
    /// `clearance` above it ([`Walker::travel_height`]).
    top: f64,
    /// The boxes of the fixtures the travels rise over, in the part's
    /// coordinates ([`part_frame::fixture_boxes`]).
    boxes: Vec<part_frame::Placed<'p>>,
}

/// Powder rates that print the same (they come from the same declaration).
fn same_rate(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-4 * a.abs().max(b.abs())
}

fn f64s(n: [f32; 3]) -> [f64; 3] {
    [n[0] as f64, n[1] as f64, n[2] as f64]
}

fn along(p: [f64; 3], dir: [f64; 3], d: f64) -> [f64; 3] {
    [p[0] + d * dir[0], p[1] + d * dir[1], p[2] + d * dir[2]]
}

/// The unit vector from `a` to `b`, if they are apart.
fn unit(a: [f64; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    (len > JOIN_MM).then(|| d.map(|c| c / len))
}

/// Whether the segment from `a` to `b`, seen from above, passes within
/// `margin` of the box from `lo` to `hi` (its X and Y; by the box grown by
/// `margin`, a slab test).
fn crosses_box(a: [f64; 3], b: [f64; 3], lo: [f64; 3], hi: [f64; 3], margin: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for i in 0..2 {
        let (l, h, d) = (lo[i] - margin, hi[i] + margin, b[i] - a[i]);
        if d.abs() < 1e-12 {
            if a[i] < l || a[i] > h {
                return false;
            }
            continue;
        }
        let (u, v) = ((l - a[i]) / d, (h - a[i]) / d);
        t0 = t0.max(u.min(v));
        t1 = t1.min(u.max(v));
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// How long a lead at `v` mm/s is with acceleration `a`: `v²/2a`, mm.
fn lead_length(v: f32, a: f64) -> f64 {
    let v = v as f64;
    v * v / (2.0 * a)
}

impl<'a, V: Visit> Walker<'_, 'a, V> {
    fn switch_off(&mut self) {
        if self.laser {
            self.laser = false;
            self.v.laser_off();
        }
    }

    /// Sends `m`, switching the laser first when the move needs it changed.
    #[inline]
    fn send(&mut self, mut m: Move) {
        if let (Some((tops, rapid)), Some(from), Some(was)) =
            (self.plan.turns, self.last, self.last_axes)
        {
            if m.speed == Speed::Rapid && !m.kind.ptp() && m.axes != was {
                // The positioner turns on a laser-off line: slowed to its axes.
                let d = (0..3)
                    .map(|i| (m.to[i] - from[i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let turn = [m.axes.tilt - was.tilt, m.axes.c - was.c];
                // Rounded down to what a program prints, so it stays held.
                let v = (held_to_axes(rapid, d, turn, tops) * 1000.0).floor() / 1000.0;
                if v < rapid && v > 0.0 {
                    m.speed = Speed::Feed(v as f32);
                }
            }
        }
        self.last_axes = Some(m.axes);
        self.last_normal = Some(m.normal);
        self.last_kind = Some(m.kind);
        if self.timed {
            if let (Speed::Feed(v), Some(from)) = (m.speed, self.last) {
                let d = (0..3)
                    .map(|i| (m.to[i] - from[i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                self.layer_time += d / v as f64;
            }
        }
        let on = m.deposits();
        if on {
            let from = self.last.map_or(m.to[2], |p| p[2]);
            self.top = self.top.max(m.to[2]).max(from);
            if self.plan.lead.is_some() {
                self.run_end = self.last.map(|p| (p, m));
            }
        }
        self.last = Some(m.to);
        if on != self.laser {
            self.laser = on;
            if on {
                self.v.laser_on(&m);
            } else {
                self.v.laser_off();
            }
        }
        if let Some(e) = self.end_next.take() {
            self.v.segment_end(e);
        }
        self.v.motion(&m);
    }

    /// Unit vector up the nozzle at a point with `normal`.
    fn up(&self, normal: [f32; 3]) -> [f64; 3] {
        if let Head::Vertical = self.plan.head {
            return [0.0, 0.0, 1.0];
        }
        let n = f64s(normal);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        [n[0] / len, n[1] / len, n[2] / len]
    }

    /// The path `pts` (layer `li`, path `pi`), `after` the next one in its
    /// layer.
    fn path(
        &mut self,
        li: usize,
        pi: usize,
        (pts, after): (&[Point], Option<&[Point]>),
        first_in_layer: bool,
    ) {
        let first = &pts[0];
        let mut cur = match self.cursor {
            // A nozzle backed off (to cool between layers) must come back
            // down: a path joins only where the nozzle still is.
            Some(c) if !first_in_layer && !self.retracted && joins(c.focus, c.normal, first) => c,
            _ => {
                // The powder of the path's first deposit, for the cell (a
                // lead's: of the deposit it leads onto, so the powder is
                // ready before the nozzle runs up to speed).
                let deposits = |pts: &[Point]| {
                    pts[..pts.len().saturating_sub(1)]
                        .iter()
                        .find(|p| p.laser_on)
                        .map(|p| p.powder)
                };
                let powder =
                    deposits(pts).or_else(|| after.filter(|_| self.lead_path).and_then(deposits));
                let feed_in = pts.get(1).filter(|_| first.laser_on);
                self.transition((li, pi, first_in_layer), first, feed_in, powder)
            }
        };
        if let Some(r) = self.plan.held(li) {
            // A path that joins across layers turns the positioner on.
            cur.axes = r;
        }
        self.retracted = false;
        // A lead of its own that goes on from a run under way is its
        // lead-out; any other, a lead-in onto the run that joins its end.
        let lead = self.lead_path.then_some(if self.laser {
            MoveKind::LeadOut
        } else {
            MoveKind::LeadIn
        });
        for (k, seg) in pts.windows(2).enumerate() {
            let (from, to) = (&seg[0], &seg[1]);
            if to.normal != cur.normal {
                // Most parts keep one normal over many points: solve only on a change.
                cur.normal = to.normal;
                if let Head::Tilting(kin, _) = self.plan.head {
                    cur.axes = kinematics::follow(kin, f64s(to.normal), cur.axes);
                }
            }
            if from.laser_on && !self.ready(from.powder) {
                // A start after a gap inside a path, or a rate change there.
                self.prepare(from.powder);
            }
            let at = Where::Point {
                layer: li,
                path: pi,
                point: k + 1,
            };
            let (kind, speed, target) = if from.laser_on {
                if !self.laser {
                    self.lead_in((li, pi, k), from, to, cur);
                }
                (MoveKind::Deposit, Speed::Feed(from.speed), to.focus())
            } else if let Some(kind) = lead {
                // At the deposit's speed, laser off: the laser switches
                // off before a lead-out, on after a lead-in.
                (kind, Speed::Feed(from.speed), to.focus())
            } else {
                self.end_run();
                // A gap ends where the next run's lead-in starts: in this
                // path, or in the next where it joins this one's end.
                let start = match pts.get(k + 2) {
                    Some(n) if to.laser_on => self.lead_start(to, n),
                    Some(_) => None,
                    None => after
                        .filter(|a| a.len() > 1 && a[0].laser_on)
                        .filter(|a| joins(to.focus(), to.normal, &a[0]))
                        .and_then(|a| self.lead_start(&a[0], &a[1])),
                };
                (MoveKind::Travel, Speed::Rapid, start.unwrap_or(to.focus()))
            };
            if let Some(ends) = self.ends {
                self.end_next = ends.at(k + 1);
            }
            self.send(Move {
                kind,
                to: target,
                normal: to.normal,
                axes: cur.axes,
                speed,
                power: from.power,
                at,
            });
        }
        cur.focus = pts[pts.len() - 1].focus();
        self.cursor = Some(cur);
    }

    /// Retract, travel above `first`, get gas and powder ready for a path
    /// that deposits at `powder` g/min, approach. A path that deposits from
    /// `first` on to `second` is approached at its speed, onto its lead-in's
    /// start where it has one. Returns the cursor at `first`.
    fn transition(
        &mut self,
        (li, pi, layer_start): (usize, usize, bool),
        first: &Point,
        second: Option<&Point>,
        powder: Option<f32>,
    ) -> Cursor {
        self.end_run();
        let feed_in = second.is_some();
        let clearance = Where::Clearance {
            layer: li,
            path: pi,
        };
        let prev = self
            .cursor
            .map(|c| c.axes)
            .or(self.plan.home)
            .unwrap_or_default();
        if let Some(c) = self.cursor.filter(|_| !self.retracted) {
            self.retract(c, clearance);
        }
        let axes = self.start_axes((li, pi), prev, layer_start);
        let f0 = first.focus();
        let entry = second.and_then(|n| self.lead_start(first, n)).unwrap_or(f0);
        let above = along(entry, self.up(first.normal), self.plan.clearance);
        if let (Some(safe), None) = (self.plan.safe, self.last) {
            // The first move: Z alone up to the safe height, then X, Y and
            // the rotary axes across at that height.
            let high = [above[0], above[1], safe.max(above[2])];
            let lift = |kind, axes| Move {
                kind,
                to: high,
                normal: first.normal,
                axes,
                speed: Speed::Rapid,
                power: first.power,
                at: clearance,
            };
            self.send(lift(MoveKind::Lift, prev));
            if high[2] > above[2] {
                self.send(lift(MoveKind::Travel, axes));
            }
        }
        self.over_the_top(first, above, (prev, axes), clearance);
        // A robot comes from home by PTP; every later travel is a line.
        let kind = match (self.plan.home, self.last) {
            (Some(_), None) => MoveKind::FromHome,
            _ => MoveKind::Travel,
        };
        if !self.stands_at(above, first.normal, axes) {
            self.send(Move {
                kind,
                to: above,
                normal: first.normal,
                axes,
                speed: Speed::Rapid,
                power: first.power,
                at: clearance,
            });
        }
        if let Some(rate) = powder.filter(|&r| !self.ready(r)) {
            self.prepare(rate);
        }
        self.send(Move {
            kind: MoveKind::Approach,
            to: entry,
            normal: first.normal,
            axes,
            speed: if feed_in {
                Speed::Feed(first.speed)
            } else {
                Speed::Rapid
            },
            power: first.power,
            at: Where::Point {
                layer: li,
                path: pi,
                point: 0,
            },
        });
        let c = Cursor {
            focus: f0,
            normal: first.normal,
            axes,
        };
        self.cursor = Some(c);
        c
    }

    /// The rotary axes at the first point of path `pi` of layer `li`,
    /// reached from `prev`, the nozzle retracted and the laser off: where
    /// C unwinds. A head unwinds on any transition, to where it can follow
    /// the paths up to the next one (its run, [`Walker::run`]) within its
    /// stops ([`kinematics::run_start`]). A table turns the part itself: it
    /// unwinds only before a layer's first path, to where the whole layer
    /// can be followed, and follows the normals on every other transition.
    /// A table keeps the branch (the tilt's side) it is on unless the run
    /// needs the other; a head takes the start of least axis travel.
    fn start_axes(&self, (li, pi): (usize, usize), prev: Rotary, layer_start: bool) -> Rotary {
        if let Some(r) = self.plan.held(li) {
            return r;
        }
        let Head::Tilting(kin, lim) = self.plan.head else {
            return Rotary::default();
        };
        let ranges = [lim.tilt, lim.rotary];
        if !kin.is_table() {
            let run = self.run(li, pi);
            let normals = run.iter().flat_map(|p| p.iter()).map(|p| f64s(p.normal));
            return kinematics::run_start(kin, normals, prev, ranges);
        }
        let layer = &self.plan.program.layers[li];
        if !layer_start {
            let n = f64s(layer.paths[pi].points[0].normal);
            return kinematics::follow(kin, n, prev);
        }
        let normals = layer
            .paths
            .iter()
            .flat_map(|p| &p.points)
            .map(|p| f64s(p.normal));
        kinematics::run_start(kin, normals, prev, ranges)
    }

    /// The paths the nozzle follows from path `pi` of layer `li` up to the
    /// next transition: that path, and every later one that starts where
    /// the one before ends, in its layer, and in a continuous program
    /// (which does not cool between layers) in the next layers too.
    fn run(&self, li: usize, pi: usize) -> Vec<&'a [Point]> {
        let program = self.plan.program;
        let across = program.continuous && !program.cools();
        let mut out: Vec<&'a [Point]> = vec![&program.layers[li].paths[pi].points];
        let rest = program.layers[li].paths[pi + 1..].iter().chain(
            program.layers[li + 1..]
                .iter()
                .take_while(|_| across)
                .flat_map(|l| &l.paths),
        );
        for path in rest.map(|p| p.points.as_slice()).filter(|p| !p.is_empty()) {
            let end = out.last().and_then(|p| p.last());
            if !end.is_some_and(|e| joins(e.focus(), e.normal, &path[0])) {
                break;
            }
            out.push(path);
        }
        out
    }

    /// The travel to `above` (the clearance point over the next path's
    /// `first` point) passes over everything it could meet by the
    /// clearance ([`Walker::travel_height`]): a straight line between the
    /// two clearance points could cut through a ridge of an earlier layer
    /// (a top that is higher in the middle than at the tracks' ends), a
    /// taller island built before, or a fixture on the way. Rises there and
    /// crosses, with the head at `axes` (before, after), wherever either
    /// end lies lower; a nozzle that points sideways or down (its beam
    /// within 3° of level or below) is left to the collision check.
    fn over_the_top(
        &mut self,
        first: &Point,
        above: [f64; 3],
        (prev, axes): (Rotary, Rotary),
        clearance: Where,
    ) {
        let (Some(from), Some(c)) = (self.last, self.cursor) else {
            return;
        };
        let ups = [self.up(c.normal)[2], self.up(first.normal)[2]];
        if ups.iter().any(|&u| u < 0.05) {
            return;
        }
        let safe = self.travel_height(from, above, ups);
        if from[2].min(above[2]) >= safe - 1e-6 {
            return;
        }
        // A rise shorter than a printed step would print as none, or as a
        // step of one digit: the travel across starts where it is.
        if safe - from[2] >= POSITION_STEP {
            self.send(Move {
                kind: MoveKind::Travel,
                to: [from[0], from[1], safe],
                normal: c.normal,
                axes: prev,
                speed: Speed::Rapid,
                power: first.power,
                at: clearance,
            });
        }
        if above[2] >= safe {
            // The travel on to `above` goes no lower than `safe`.
            return;
        }
        // Straight up and down (the next path starts under where the last
        // ended, a layer change of a wall): nothing to cross.
        let across = [above[0], above[1], safe];
        if self.stands_at(across, first.normal, axes) {
            return;
        }
        self.send(Move {
            kind: MoveKind::Travel,
            to: [above[0], above[1], safe],
            normal: first.normal,
            axes,
            speed: Speed::Rapid,
            power: first.power,
            at: clearance,
        });
    }

    /// Whether the nozzle already stands at `to`, turned to `normal` and
    /// `axes`, within the step a program prints ([`POSITION_STEP`]): a
    /// travel there would print as no move, or as a step of one digit
    /// (`lmd::short-move`). After a lift or home, where the nozzle stands
    /// is not the last move's `to`.
    fn stands_at(&self, to: [f64; 3], normal: [f32; 3], axes: Rotary) -> bool {
        let (Some(at), Some(n), Some(a)) = (self.last, self.last_normal, self.last_axes) else {
            return false;
        };
        let d2: f64 = (0..3).map(|i| (to[i] - at[i]).powi(2)).sum();
        !matches!(self.last_kind, Some(MoveKind::Lift | MoveKind::Home))
            && d2 < POSITION_STEP * POSITION_STEP
            && (axes.tilt - a.tilt).abs() < POSITION_STEP
            && (axes.c - a.c).abs() < POSITION_STEP
            && target::same_direction(n, normal)
    }

    /// The least height (Z) of the focus on a travel from `from` to `to`
    /// with the beam's Z component `ups` at its ends: above the highest
    /// focus deposited so far (the part, every island of it) and the top
    /// of every fixture the head passes within its gap of (by its box), by
    /// as much as a retract along the beam rises (the clearance, times the
    /// lesser `up_z`: no lower over anything than its ends stand over their
    /// own paths), and as much more as a tilted head hangs below its
    /// focus.
    fn travel_height(&self, from: [f64; 3], to: [f64; 3], ups: [f64; 2]) -> f64 {
        let tool = self.plan.tool;
        let hang = ups
            .iter()
            .map(|&u| -tool.lowest_above_focus(u))
            .fold(0.0, f64::max);
        let reach = ups.iter().map(|&u| tool.spread(u)).fold(0.0, f64::max) + tool.gap;
        let mut top = self.top;
        for &part_frame::Placed {
            bounds: (lo, hi), ..
        } in &self.boxes
        {
            if hi[2] > top && crosses_box(from, to, lo, hi, reach) {
                top = hi[2];
            }
        }
        let rise = ups.iter().fold(1.0f64, |a, &u| a.min(u));
        top + self.plan.clearance * rise + hang
    }

    /// Before layer `next`: dwell, retracted, for the declared interlayer
    /// dwell, what the last layer fell short of the minimum layer time, or
    /// the wait the thermal budget chose (docs/thermal.md).
    /// Rapid moves count as instant, so the real layer time is at least the
    /// minimum whatever the machine's rapid speed.
    fn cool(&mut self, next: usize) {
        let heat = self.plan.program.heat;
        let wait = heat
            .dwell
            .max(heat.min_layer_time - self.layer_time)
            .max(self.plan.program.thermal_wait(next));
        if wait <= 0.0 {
            return;
        }
        self.end_run();
        if let Some(c) = self.cursor.filter(|_| !self.retracted) {
            self.retract(
                c,
                Where::Clearance {
                    layer: next,
                    path: 0,
                },
            );
            self.retracted = true;
        }
        // A feeder that would run longer than its arrival time for nothing
        // stops; the next path's preparation waits the arrival time again,
        // so the pause is as long as asked.
        match (&self.plan.cell.powder, self.powder) {
            (Some(f), Some(_)) if wait > f.arrival => {
                self.v.io(Io::PowderOff);
                self.powder = None;
                self.v.dwell(wait - f.arrival);
            }
            _ => self.v.dwell(wait),
        }
    }

    /// Whether gas and powder are as a deposit at `powder` g/min needs them:
    /// flowing, and at that rate where the feeder's rate is programmed.
    fn ready(&self, powder: f32) -> bool {
        let cell = self.plan.cell;
        let gas = cell.gas.is_none() || self.gas;
        let feed = match (&cell.powder, self.powder) {
            (None, _) => true,
            (Some(_), None) => false,
            (Some(f), Some(r)) => f.rate.is_none() || same_rate(r, powder),
        };
        gas && feed
    }

    /// Switches gas and powder on (or the powder to `powder` g/min) and
    /// waits, standing, until both have arrived at the nozzle.
    fn prepare(&mut self, powder: f32) {
        let cell = self.plan.cell;
        let mut wait = 0.0f64;
        if let (Some(g), false) = (&cell.gas, self.gas) {
            self.v.io(Io::GasOn);
            self.gas = true;
            wait = wait.max(g.pre_flow);
        }
        if let Some(f) = &cell.powder {
            match self.powder {
                None => {
                    self.v.io(Io::PowderOn(powder));
                    wait = wait.max(f.arrival);
                }
                Some(r) if f.rate.is_some() && !same_rate(r, powder) => {
                    self.v.io(Io::PowderRate(powder));
                    wait = wait.max(f.arrival);
                }
                Some(_) => {}
            }
            self.powder = Some(powder);
        }
        if wait > 0.0 {
            self.v.dwell(wait);
        }
    }

    /// Where the lead-in of a run from `p` on to `next` starts, with leads:
    /// `v²/2a` and the blending back along the run's first move.
    fn lead_start(&self, p: &Point, next: &Point) -> Option<[f64; 3]> {
        let (a, blend) = self.plan.lead?;
        let (f, dir) = (p.focus(), unit(p.focus(), next.focus())?);
        // The control may round the corner onto the lead-in (the approach,
        // a back-up) over up to `blend` of it: the ramp comes after that.
        Some(along(f, dir, -(lead_length(p.speed, a) + blend)))
    }

    /// Before the run that deposits from `from` (layer, path and point
    /// `(layer, path, point)`) on to `to`, with leads: the lead-in onto
    /// `from`, backing up to its start first where the nozzle is not there
    /// (a run reached along a path that joins).
    fn lead_in(
        &mut self,
        (layer, path, point): (usize, usize, usize),
        from: &Point,
        to: &Point,
        cur: Cursor,
    ) {
        if self.last_kind == Some(MoveKind::LeadIn) {
            // The path's own lead-in brought the nozzle up to speed.
            return;
        }
        let Some(start) = self.lead_start(from, to) else {
            return;
        };
        let at = Where::Point { layer, path, point };
        let lead = |kind, to, speed| Move {
            kind,
            to,
            normal: from.normal,
            axes: cur.axes,
            speed,
            power: from.power,
            at,
        };
        let away = self.last.map_or(f64::INFINITY, |l| {
            (0..3).map(|i| (l[i] - start[i]).powi(2)).sum::<f64>()
        });
        if away > JOIN_MM * JOIN_MM {
            self.send(lead(MoveKind::Travel, start, Speed::Rapid));
        }
        self.send(lead(
            MoveKind::LeadIn,
            from.focus(),
            Speed::Feed(from.speed),
        ));
    }

    /// Ends the run of deposits under way, if any: with leads by its
    /// lead-out (the laser switches off where it starts), else by switching
    /// the laser off where the nozzle stands.
    fn end_run(&mut self) {
        if !self.laser {
            return;
        }
        let lead = self.plan.lead.zip(self.run_end.take());
        let Some(((a, _), (from, m))) = lead else {
            self.switch_off();
            return;
        };
        let (Speed::Feed(v), Some(dir)) = (m.speed, unit(from, m.to)) else {
            self.switch_off();
            return;
        };
        let to = along(m.to, dir, lead_length(v, a));
        self.send(Move {
            kind: MoveKind::LeadOut,
            to,
            ..m
        });
        if let Some(c) = self.cursor.as_mut() {
            c.focus = to;
        }
    }

    fn retract(&mut self, c: Cursor, at: Where) {
        let to = along(c.focus, self.up(c.normal), self.plan.clearance);
        self.send(Move {
            kind: MoveKind::Retract,
            to,
            normal: c.normal,
            axes: c.axes,
            speed: Speed::Rapid,
            power: 0.0,
            at,
        });
    }

    /// After the last path, one sequence on every machine: laser off,
    /// retract, feeder off, post-flow, gas off; then a CNC lifts Z alone to
    /// its safe height, a robot goes home by PTP.
    fn end(&mut self) {
        self.end_run();
        if let Some(c) = self.cursor.filter(|_| !self.retracted) {
            self.retract(c, Where::End);
        }
        if self.powder.take().is_some() {
            self.v.io(Io::PowderOff);
        }
        if let (Some(g), true) = (&self.plan.cell.gas, self.gas) {
            if g.post_flow > 0.0 {
                self.v.dwell(g.post_flow);
            }
            self.v.io(Io::GasOff);
            self.gas = false;
        }
        let (Some(last), Some(c)) = (self.last, self.cursor) else {
            return;
        };
        let park = |kind, to, axes| Move {
            kind,
            to,
            normal: c.normal,
            axes,
            speed: Speed::Rapid,
            power: 0.0,
            at: Where::End,
        };
        if let Some(safe) = self.plan.safe.filter(|&s| last[2] < s) {
            let to = self.plan.lift_at_end(last, c.axes, safe);
            // A lift within the printed digit would be written as a line
            // that moves nowhere: the retract ended there.
            let printed = |x| crate::target::written(x, crate::target::gcode::POS_DECIMALS);
            if (0..3).any(|i| printed(to[i]) != printed(last[i])) {
                self.send(park(MoveKind::Lift, to, c.axes));
            }
        }
        if let Some(home) = self.plan.home {
            self.send(park(MoveKind::Home, last, home));
        }
    }
}

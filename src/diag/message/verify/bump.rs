//! What the verifier says where a machine's acceleration makes the bead
//! grow: at the starts and ends of runs and at corners (`lmd::deposit-bump`).

use crate::diag::{plural, Code, Diagnostic};
use crate::numbers::trimmed;
use crate::plan::Where;
use crate::span::Span;

/// Where a bump lies in its run of deposits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lies {
    /// Where the run starts.
    Start,
    /// Where it ends.
    End,
    /// A run shorter than the melt pool's window: start and end at once.
    Whole,
    /// Inside it: a corner, or a step up of the programmed speed.
    Inside,
}

/// A corner a bump has in it: the slowest there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerPass {
    /// How far the path turns, deg.
    pub turn_deg: f64,
    /// Half the shorter move there: the most blending the control can use, mm.
    pub room: f64,
    /// The speed the nozzle passes it at, and the programmed one, mm/s.
    pub reached: f64,
    /// The programmed speed.
    pub speed: f64,
    /// The blending that would hold the speed that lays the tolerance
    /// there, mm (more than `room`: none can).
    pub needs: f64,
    /// The speed the corner holds with all of `room` blended, mm/s.
    pub best: f64,
}

/// One place where the bead grows past the tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    /// The point whose move lays most of it.
    pub at: Where,
    /// Where it lies in its run.
    pub lies: Lies,
    /// How much higher the layer comes out there, over a bead width, as a
    /// fraction of what the plan lays, and in mm.
    pub share: f64,
    /// The same in mm.
    pub mm: f64,
    /// What the plan lays there, mm.
    pub planned: f64,
    /// The programmed speed there, mm/s.
    pub speed: f64,
    /// How long the nozzle runs slower than [`Self::slow`] in it, mm.
    pub length: f64,
    /// The speed below which a point lays more than the tolerance above the
    /// plan, mm/s.
    pub slow: f64,
    /// The slowest corner in it, if it has one.
    pub corner: Option<CornerPass>,
}

/// The model the rule predicted with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Model {
    /// The machine's acceleration, mm/s².
    pub accel: f64,
    /// Its blending, mm, and where that comes from.
    pub blending: f64,
    /// Where the blending comes from.
    pub blending_from: &'static str,
    /// The melt pool's window: a bead width, mm.
    pub window: f64,
    /// `rise_tolerance`.
    pub tolerance: f64,
    /// `ramp = lead`.
    pub lead: bool,
    /// Whether the laser switches on the fly (else leads do not help).
    pub fly: bool,
    /// A robot (else a CNC).
    pub robot: bool,
}

/// What the rule found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bumps {
    /// Places past the tolerance.
    pub count: u64,
    /// Of which at a run's start, at its end, whole short runs, inside.
    pub starts: u64,
    /// At a run's end.
    pub ends: u64,
    /// Whole short runs.
    pub whole: u64,
    /// Inside runs: corners and speed steps.
    pub inside: u64,
    /// The worst of all.
    pub worst: Bump,
    /// The worst at a run's start or end.
    pub worst_end: Option<Bump>,
    /// The worst on a run shorter than a bead width.
    pub worst_short: Option<Bump>,
    /// The worst inside a run.
    pub worst_inside: Option<Bump>,
    /// The model.
    pub model: Model,
}

fn mm(x: f64) -> String {
    format!("{} mm", trimmed(x, 3))
}

fn speed(x: f64) -> String {
    format!("{} mm/s", trimmed(x, 2))
}

fn lies(l: Lies) -> &'static str {
    match l {
        Lies::Start => "where a run of deposits starts",
        Lies::End => "where a run of deposits ends",
        Lies::Whole => "a run shorter than a bead width",
        Lies::Inside => "inside a run",
    }
}

/// The bead grows past the tolerance where the machine slows down.
pub fn deposit_bump(
    machine: &str,
    b: &Bumps,
    acceleration: Option<Span>,
    blending: Option<Span>,
    ramp: Option<Span>,
) -> Diagnostic {
    let m = &b.model;
    let w = &b.worst;
    let places: Vec<String> = [
        (b.starts, "where runs start"),
        (b.ends, "where runs end"),
        (b.whole, "on runs shorter than a bead width"),
        (b.inside, "inside runs, at corners or speed steps"),
    ]
    .iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, what)| format!("{n} {what}"))
    .collect();
    let places = places.join(", ");
    let msg = format!(
        "at the speeds `{machine}` reaches (acceleration {} mm/s², blending {}), the bead grows more than {} % above its layer at {} place{}: {places}; the worst, at {} ({}), lays {} ({} %) more than the planned {} over a bead width ({}), where the nozzle runs below {} for {}",
        trimmed(m.accel, 1),
        mm(m.blending),
        trimmed(m.tolerance * 100.0, 1),
        b.count,
        plural(b.count),
        w.at,
        lies(w.lies),
        mm(w.mm),
        trimmed(w.share * 100.0, 1),
        mm(w.planned),
        mm(m.window),
        speed(w.slow),
        mm(w.length)
    );
    let d = Diagnostic::error(Code::DepositBump, msg)
        .label_opt(acceleration, "the path acceleration")
        .label_opt(blending, "the corner blending")
        .label_opt(ramp, "how runs start and stop");
    let mut help = Vec::new();
    // The worst corner's dip: the speed it is programmed at and reached.
    let corner = b
        .worst_inside
        .and_then(|i| i.corner)
        .map(|c| (c.speed, c.reached));
    if let Some(e) = &b.worst_end {
        help.push(ends_help(m, e, corner));
    }
    if let Some(e) = &b.worst_short {
        help.push(short_help(m, e, b.worst_end.is_none()));
    }
    if let Some(c) = b
        .worst_inside
        .as_ref()
        .and_then(|i| i.corner.map(|c| (i, c)))
    {
        help.push(corner_help(m, c.0, &c.1));
    } else if let Some(i) = &b.worst_inside {
        help.push(format!(
            "inside runs the programmed speed steps up (at {}): the nozzle takes (Δv)²/2a to follow, laying more meanwhile; smaller steps, or a higher acceleration",
            i.at
        ));
    }
    d.help(help.join("; "))
}

/// The fixes for the bumps where runs start and end; `corner` the worst
/// corner inside a run, its programmed and reached speeds, mm/s.
///
/// A ramp from rest to `v` at `a` lays `v²/2a` more bead than the plan
/// (the integral of `v/u − 1` over it); a corner passed at `u` costs two
/// ramps, `(v − u)²/a`. So the ends pass at `a ≥ v²/(2·tol·w)` or
/// `v ≤ √(2·a·tol·w)`, and a corner the nozzle stops at needs twice the
/// acceleration (`u` only grows with it, so the figure holds).
fn ends_help(m: &Model, e: &Bump, corner: Option<(f64, f64)>) -> String {
    let tw = m.tolerance * m.window;
    let ramp = e.speed * e.speed / (2.0 * m.accel);
    let (mut most, mut least) = ((2.0 * m.accel * tw).sqrt(), e.speed * e.speed / (2.0 * tw));
    if let Some((v, u)) = corner {
        most = most.min(u + (m.accel * tw).sqrt());
        // Another corner may be programmed as fast as the ends' run.
        least = least.max((v.max(e.speed) - u).max(0.0).powi(2) / tw);
    }
    // Rounded the safe way: the figures are printed to 0.01 mm/s and
    // 1 mm/s².
    let (most, least) = ((most * 100.0).floor() / 100.0, least.ceil());
    let mut s = format!(
        "from rest the nozzle needs v²/2a = {} to reach {} at {} mm/s²: ",
        mm(ramp),
        speed(e.speed),
        trimmed(m.accel, 1)
    );
    if !m.lead {
        s.push_str("`ramp = lead` starts the laser at the end of a laser-off lead-in that long, and stops it before a lead-out as long");
    } else if !m.fly {
        s.push_str("`ramp = lead` writes the lead-ins, but the machine stops where its laser lines switch, so they do not help: on LinuxCNC switch the laser with the motion, `laser_on = \"M62 P0\"` and `laser_off = \"M63 P0\"` (the laser's enable on `motion.digital-out-00`)");
    } else {
        s.push_str(
            "the leads keep the nozzle at speed where the laser switches, yet a bump remains",
        );
    }
    if most < e.speed {
        s.push_str(&format!(
            "; or scan at most {} (a ramp then lays no more than the tolerance over a bead width{}), or give the machine an acceleration of at least {} mm/s²",
            speed(most),
            if corner.is_some() {
                ", and the two ramps of the corner inside the run no more either"
            } else {
                ""
            },
            trimmed(least, 0)
        ));
    } else if let Some(c) = &e.corner {
        // The ramp alone stays within the tolerance: a corner next to it adds.
        s.push_str(&format!(
            "; the ramp alone lays {} %, the corner next to it the rest: {}",
            trimmed(ramp / m.window * 100.0, 1),
            corner_help(m, e, c)
        ));
    }
    s
}

/// The fixes for runs shorter than a bead width; `lead` when the help says
/// nothing of leads otherwise.
fn short_help(m: &Model, e: &Bump, lead: bool) -> String {
    let mut s = format!(
        "a run shorter than a bead width (at {}) speeds up and slows down over most of its length and lays {} % more than planned",
        e.at,
        trimmed(e.share * 100.0, 1)
    );
    if lead && !m.lead {
        s.push_str(": `ramp = lead` runs it at speed from end to end");
    } else if lead && !m.fly {
        s.push_str(": leads only help where the laser lines switch on the fly (on LinuxCNC `laser_on = \"M62 P0\"`, `laser_off = \"M63 P0\"`)");
    }
    s.push_str("; or leave such slivers out of the profile (`lmd::short-track` names them)");
    s
}

/// The fixes for the bump at the worst corner.
fn corner_help(m: &Model, at: &Bump, c: &CornerPass) -> String {
    let mut s = format!(
        "through the corner at {} (turning {}°) the nozzle slows from {} to {} with a blending of {} ({})",
        at.at,
        trimmed(c.turn_deg, 1),
        speed(c.speed),
        speed(c.reached),
        mm(m.blending.min(c.room)),
        m.blending_from
    );
    if c.needs <= c.room {
        s.push_str(&format!(
            ": a blending of at least {} holds {} there",
            mm(c.needs),
            speed(at.slow)
        ));
    } else {
        s.push_str(&format!(
            ": its moves are too short to round it faster than {} (half of each), so scan at most {} there",
            speed(c.best),
            speed(c.best * (1.0 + m.tolerance))
        ));
    }
    s
}

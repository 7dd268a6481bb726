//! What the verifier says about a robot's arm (`lmd::reach`,
//! `lmd::joint-limit`, `lmd::singular-lin`, `lmd::configuration-flip`,
//! `lmd::joint-speed`): where in the file, by how much, and what would fix
//! it — the base, the tool's angle on the flange, the speed.

use crate::diag::message::words::Words;
use crate::diag::{plural, Worst};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;
use std::fmt::Display;

/// The robot and the spans a message about its arm points at.
pub struct ArmAt<'a> {
    /// The machine's name.
    pub machine: &'a str,
    /// The arm's name (`KR 16-2`, or `the opw(…) arm`).
    pub arm: &'a str,
    /// `arm = …`.
    pub declared: Span,
    /// `base = …`.
    pub base: Span,
    /// `tool = …`.
    pub tool: Span,
    /// Its controller's words for axes, moves and configurations.
    pub words: Words,
}

/// What would bring a plan the arm cannot reach within its reach.
pub enum ReachFix<'a> {
    /// A base, as written, that stands the part on or above the robot's
    /// foot, in front of it, from where the arm follows a sample of the
    /// plan's moves.
    Base(&'a str),
    /// No base can: two of the part's points lie `across` mm apart, no two
    /// foci the arm reaches more than `most`.
    TooLarge {
        /// The part's extent, mm.
        across: f64,
        /// The most two reachable foci lie apart, mm.
        most: f64,
    },
    /// No base lmdc tried lets the arm follow the plan, the part `across`
    /// mm along one axis (0: not known).
    Unfound {
        /// The part's extent, mm.
        across: f64,
    },
    /// The part rides a positioner: its place in the cell is the
    /// positioner's.
    Positioner,
}

/// Poses the arm cannot reach: the worst's wrist centre `value` mm from A2,
/// against the arm's `span` of reach; `quick`: found from the part's points
/// before any pose was solved (at least that many poses, the wrist centre
/// at least that far, whatever the tool's turn).
pub fn reach(
    a: &ArmAt<'_>,
    w: &Worst<impl Display>,
    span: [f64; 2],
    quick: bool,
    fix: ReachFix<'_>,
) -> Diagnostic {
    let least = if quick { "at least " } else { "" };
    let a2 = match a.words {
        Words::Kuka => "the A2 axis",
        Words::Abb => "axis 2",
    };
    let d = Diagnostic::error(
        Code::Reach,
        format!(
            "robot `{}` cannot reach {least}{} pose{} of the plan: at {} its wrist centre would have to be {least}{} mm from {a2}, and the {} reaches {} to {} mm",
            a.machine,
            w.count,
            plural(w.count),
            w.at,
            short(w.value),
            a.arm,
            short(span[0]),
            short(span[1])
        ),
    );
    let d = match fix {
        ReachFix::Positioner => d.label(a.base, "the part's place on the positioner's flange"),
        _ => d.label(a.base, "the part is placed here"),
    }
    .label(a.declared, "the arm declared here");
    match fix {
        ReachFix::Base(base) => d.help(format!(
            "move the base so the part stands in front of the robot, on or above the plane of its foot: e.g. `base = {base}`, from where the arm follows a sample of the plan's moves within its limits (then check again)"
        )),
        ReachFix::TooLarge { across, most } => d.help(format!(
            "no base brings the whole part within reach: two of its points lie {} mm apart, and no two poses the {} reaches with this tool lie more than {} mm apart; check the part's lengths and their units, or use a larger arm",
            short(across),
            a.arm,
            short(most)
        )),
        ReachFix::Unfound { across } => {
            let size = if across > 0.0 {
                format!(" (the part is {} mm across)", short(across))
            } else {
                String::new()
            };
            d.help(format!(
                "no base lmdc tried (the part in front of the robot, on or above the plane of its foot) lets the arm follow the plan{size}: a larger arm, a positioner, a shorter tool or one tilted on the flange; or check the part's lengths and their units"
            ))
        }
        ReachFix::Positioner => d
            .help("the part rides the positioner: bring the positioner nearer the robot (`tilt_point` and `rotate_point` are in the robot's frame), or the part nearer the rotate axis on its flange (`base`), then check again"),
    }
}

/// Axis `axis` (0-based) beyond its limit less the margin: `w.value` against
/// `w.limit`, the margin `margin` deg.
pub fn joint_limit(a: &ArmAt<'_>, axis: usize, w: &Worst<impl Display>, margin: f64) -> Diagnostic {
    let by = (w.value - w.limit).abs();
    let fix = match axis {
        0 => format!("turn the base (`base = frame(…, a = …)`) or move it so the part lies in front of {}'s middle", a.words.axis(0)),
        1 | 2 => "move the base so the part lies at a comfortable distance and height from the robot".to_string(),
        _ => "tilt the nozzle on the flange (`tool = frame(…, b = …)`) or the base so the wrist turns less, or turn the tool about the beam (`spin = auto` lets lmdc choose the turn; a pinned `spin = … deg` is used as written)".to_string(),
    };
    Diagnostic::error(
        Code::JointLimit,
        format!(
            "{} of robot `{}` would turn to {}°, {}° past {}° (its limit less the {}° margin), at {} ({} pose{})",
            a.words.an_axis(axis),
            a.machine,
            short(w.value),
            short(by),
            short(w.limit),
            short(margin),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(a.declared, format!("the {}'s limits", a.arm))
    .label(a.base, "the part is placed here")
    .help(format!("{fix}; or lower `joint_margin` if the cell really runs that close"))
}

/// `home` outside the arm's limits: axis `axis` (0-based) at `value` deg;
/// the help suggests the arm's upright pose `up` (its convention's: KUKA's
/// home, ABB's zero) with axis 5 bent 30°, and names the home as the
/// controller does.
pub fn home_limit(
    a: &ArmAt<'_>,
    home: Span,
    axis: usize,
    value: f64,
    range: [f64; 2],
    up: [f64; 6],
) -> Diagnostic {
    let mut h = up;
    h[4] = 30.0;
    // `+ 0.0`: KUKA's A1 of 0° is −0° through its sign.
    let h: Vec<String> = h.iter().map(|x| format!("{} deg", x + 0.0)).collect();
    let theirs = a.words.home();
    Diagnostic::error(
        Code::JointLimit,
        format!(
            "robot `{}`'s home puts {} at {}°, outside the {}'s {}° to {}°",
            a.machine,
            a.words.axis(axis),
            short(value),
            a.arm,
            short(range[0]),
            short(range[1])
        ),
    )
    .label(home, "home declared here")
    .label(a.declared, "the arm declared here")
    .help(format!(
        "declare the home the robot has on its controller ({theirs}), within its limits: e.g. `home = [{}]`",
        h.join(", ")
    ))
}

/// A LIN within `w.limit` deg of a singularity: the wrist (`wrist`: A5 at
/// `w.value`) or the stretched arm (A3 `w.value` from its stretch angle).
pub fn singular_lin(
    a: &ArmAt<'_>,
    kind: Singular,
    w: &Worst<impl Display>,
    at: Option<Span>,
) -> Diagnostic {
    let x = |i| a.words.axis(i);
    let (a46, a1_line, on_it) = match a.words {
        Words::Kuka => ("A4 and A6", "A1's axis", "on that axis A1"),
        Words::Abb => ("axes 4 and 6", "the line of axis 1", "on that line axis 1"),
    };
    let (what, fix) = match kind {
        Singular::Wrist => (
            format!("{} at {}°, within {}° of the wrist singularity ({} = 0, where {a46} spin)", x(4), short(w.value), short(w.limit), x(4)),
            format!("tilt the nozzle on the flange (`tool = frame(…, b = 20 deg)`) or tilt the base so {} stays bent", x(4)),
        ),
        Singular::Elbow => (
            format!("{} {}° from the stretched arm, within {}° (the arm straight, the wrist at the edge of its reach)", x(2), short(w.value), short(w.limit)),
            "move the base closer to the part so the arm stays bent".to_string(),
        ),
        Singular::Overhead => (
            format!("near the overhead singularity: the wrist centre {}° from {a1_line} (seen from the shoulder), within {}° of it ({on_it} turns freely and spins)", short(w.value), short(w.limit)),
            "move the base so the part lies in front of the robot, not above or below its foot".to_string(),
        ),
    };
    Diagnostic::error(
        Code::SingularLin,
        format!(
            "a {} of robot `{}` passes {what}, at {} ({} pose{})",
            a.words.lin(),
            a.machine,
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(
        if kind == Singular::Overhead {
            a.base
        } else {
            a.tool
        },
        if kind == Singular::Overhead {
            "the part is placed here"
        } else {
            "the tool's angle on the flange"
        },
    )
    .label_opt(at, "the distance asked for")
    .help(format!(
        "{fix}; or lower `singularity` if the cell runs there safely"
    ))
}

/// Which singular configuration a LIN comes near.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Singular {
    /// A5 near 0: A4 and A6 line up.
    Wrist,
    /// A3 near its stretch angle: the arm straight.
    Elbow,
    /// The wrist centre near A1's axis.
    Overhead,
}

impl Singular {
    /// Every kind, in the order [`crate::plan::arm::Solver::singular`]
    /// gives their distances.
    pub const ALL: [Singular; 3] = [Singular::Wrist, Singular::Elbow, Singular::Overhead];
}

/// A configuration change on a LIN: the solutions' KUKA Status and ABB
/// `confdata` before and after it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Flip {
    /// KUKA's Status, from and to.
    pub status: [u8; 2],
    /// ABB's `[cf1, cf4, cf6, cfx]`, from and to.
    pub confdata: [[i32; 4]; 2],
}

/// A LIN whose solution changes configuration: KUKA's Status (ABB's
/// `confdata`, whose `cfx` a Status change changes) from one to the other.
pub fn configuration_flip(a: &ArmAt<'_>, w: &Worst<impl Display>, flip: &Flip) -> Diagnostic {
    let [from, to] = flip.status;
    let change = from ^ to;
    let what = if change & 4 != 0 {
        format!("the wrist flips ({} changes sign)", a.words.axis(4))
    } else if change & 2 != 0 {
        "the elbow passes the stretched arm".to_string()
    } else {
        format!("the wrist centre passes over {}", a.words.axis(0))
    };
    let conf = match a.words {
        Words::Kuka => format!("Status {from:03b} to {to:03b}"),
        Words::Abb => {
            let cf = flip
                .confdata
                .map(|c| format!("[{},{},{},{}]", c[0], c[1], c[2], c[3]));
            format!(
                "`confdata` {} to {}, cfx {} to {}",
                cf[0], cf[1], flip.confdata[0][3], flip.confdata[1][3]
            )
        }
    };
    let lin = a.words.lin();
    Diagnostic::error(
        Code::ConfigurationFlip,
        format!(
            "a {lin} of robot `{}` changes configuration ({conf}: {what}) at {}; the controller stops there ({} pose{})",
            a.machine,
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(a.tool, "the tool's angle on the flange")
    .label(a.base, "the part is placed here")
    .help(format!("a {lin} keeps one configuration: tilt the nozzle on the flange (`tool = frame(…, b = …)`) or move the base so the path stays on one side"))
}

/// Axis `axis` (0-based) would turn at `w.value` deg/s against its top
/// speed `w.limit` to follow a path at `speed` mm/s.
pub fn joint_speed(a: &ArmAt<'_>, axis: usize, w: &Worst<impl Display>, speed: f64) -> Diagnostic {
    let fits = speed * w.limit / w.value;
    Diagnostic::error(
        Code::JointSpeed,
        format!(
            "{} of robot `{}` would have to turn at {}°/s, beyond its {}°/s, to follow the path at {} mm/s at {} ({} pose{})",
            a.words.an_axis(axis),
            a.machine,
            short(w.value),
            short(w.limit),
            short(speed),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(a.declared, format!("the {}'s axis speeds", a.arm))
    .help(format!(
        "lower the path speed there to {} mm/s or less, or keep the path away from the wrist singularity (tilt the nozzle on the flange) where a short move turns the wrist far",
        short(fits)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The home a limit error suggests is the arm's own upright pose in its
    /// convention, with its controller's name for the home.
    #[test]
    fn home_limit_suggests_the_makers_home() {
        let help = |words, up| {
            let a = ArmAt {
                machine: "r",
                arm: "IRB 4600-60/2.05",
                declared: Span::new(0, 0),
                base: Span::new(0, 0),
                tool: Span::new(0, 0),
                words,
            };
            home_limit(&a, Span::new(0, 0), 1, -90.0, [-90.0, 150.0], up)
                .help
                .unwrap()
        };
        let abb = help(Words::Abb, [0.0; 6]);
        assert!(abb.contains("(its home `jointtarget`)"), "{abb}");
        assert!(
            abb.contains("`home = [0 deg, 0 deg, 0 deg, 0 deg, 30 deg, 0 deg]`"),
            "{abb}"
        );
        let kuka = help(Words::Kuka, [-0.0, -90.0, 90.0, 0.0, 0.0, 0.0]);
        assert!(kuka.contains("(`$H_POS`)"), "{kuka}");
        assert!(
            kuka.contains("`home = [0 deg, -90 deg, 90 deg, 0 deg, 30 deg, 0 deg]`"),
            "{kuka}"
        );
    }
}

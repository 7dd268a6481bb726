//! What the verifier says about a machine's limits: its speed, its axes'
//! travel, a vertical nozzle, the robot's analog output, and the values its
//! programs could not write within the tolerance.

use crate::diag::{plural, Worst};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::target::{kuka, MAX_WRITTEN, WRITE_TOLERANCE};
use crate::units::{short, short_up};
use std::fmt::Display;

/// Feed moves faster than machine `name`'s `max_speed`.
pub fn machine_speed(
    name: &str,
    w: &Worst<impl Display>,
    declared: Span,
    bead_speed: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::MachineSpeed,
        format!(
            "machine `{name}` would have to move at {} mm/s, beyond its max_speed of {} mm/s, at {} ({} move{} too fast)",
            short(w.value),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(declared, "limit declared here")
    .label_opt(bead_speed, "the scan speeds come from here")
    .help("lower the scan speeds, or raise the machine's max_speed if it really can go faster")
}

/// An axis of a CNC that the plan drives beyond its travel (at an `At`).
pub struct AxisOverrun<'a, At> {
    /// The machine's name.
    pub machine: &'a str,
    /// 0–2 for X Y Z, 3 for the tilt axis, 4 for C.
    pub axis: usize,
    /// The tilt axis's letter, `A` or `B`.
    pub tilt_name: &'static str,
    /// The worst position and how many pass the limit.
    pub worst: Worst<At>,
    /// The axis's declared range.
    pub range: [f64; 2],
    /// For X Y Z: the program's extent along the axis (with clearance moves).
    pub extent: [f64; 2],
    /// For X Y Z: the placement's origin along the axis now.
    pub origin: f64,
    /// The machine's clearance, when the worst position is on a clearance move.
    pub clearance: Option<f64>,
    /// The field that declares the limit.
    pub declared: Span,
}

/// An axis driven beyond its travel, with the placement (or machine) that fits.
pub fn axis_limit(a: &AxisOverrun<'_, impl Display>) -> Diagnostic {
    let i = a.axis;
    let (name, tilt_name, w) = (a.machine, a.tilt_name, &a.worst);
    let axis = ["X", "Y", "Z", tilt_name, "C"][i];
    let (unit, sep) = if i < 3 { ("mm", " ") } else { ("°", "") };
    let mut help = match i {
        0..=2 => placement_help(a),
        3 => format!(
            "the layers tilt the nozzle further than the {tilt_name} axis of `{name}` \
             can go: use a machine whose head tilts further, or build the part in an \
             orientation whose layers tilt less"
        ),
        _ => "the C axis turns past its stop while following the normals around the \
              part: widen the C limits if the axis turns endlessly, or orient the part \
              so the paths wind less"
            .to_string(),
    };
    if let (0..=2, Some(c)) = (i, a.clearance) {
        help.push_str(&format!(
            "; the clearance moves go {} mm beyond the path along the nozzle, a \
             smaller clearance may do",
            short(c)
        ));
    }
    Diagnostic::error(
        Code::AxisLimit,
        format!(
            "axis {axis} of machine `{name}` would have to reach {}{sep}{unit}, beyond its \
             limit of {}{sep}{unit}, at {} ({} position{} outside [{}, {}]{sep}{unit})",
            short(w.value),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count),
            short(a.range[0]),
            short(a.range[1]),
        ),
    )
    .label(a.declared, "axis limit declared here")
    .help(help)
}

/// What placement of the part would keep a linear axis inside its travel.
fn placement_help<At>(a: &AxisOverrun<'_, At>) -> String {
    let axis = ["X", "Y", "Z"][a.axis];
    let key = ["x", "y", "z"][a.axis];
    let (r, [lo, hi], o) = (a.range, a.extent, a.origin);
    let (from, to) = (r[0] - lo, r[1] - hi);
    let span = format!(
        "the program spans {axis} {} .. {} mm (with the clearance moves), the machine {} .. {} mm",
        short(lo),
        short(hi),
        short(r[0]),
        short(r[1])
    );
    if from <= to {
        let best = if (from..=to).contains(&0.0) {
            0.0
        } else {
            (from + to) / 2.0
        };
        format!(
            "{span}: place the part with its origin at {axis} {} .. {} mm in machine coordinates \
             (now {}), e.g. {key} = {} mm in `origin = [x, y, z]` with `work_offset` set to it, or correct the machine's limits",
            short(from),
            short(to),
            short(o),
            short(best)
        )
    } else {
        format!(
            "{span}: the part is {} mm across {axis}, more than the {} mm the axis travels; \
             build it on a larger machine or in another orientation",
            short(hi - lo),
            short(r[1] - r[0])
        )
    }
}

/// Normals that a 3-axis machine's vertical nozzle cannot follow.
pub fn needs_tilt(name: &str, w: &Worst<impl Display>, axes: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NeedsTilt,
        format!(
            "the part's layers tilt the nozzle up to {}° from vertical ({} point{}, the worst at {}), \
             but machine `{name}` moves X Y Z only and keeps the nozzle vertical",
            short(w.value),
            w.count,
            plural(w.count),
            w.at
        ),
    )
    .label(axes, "this machine has no tilting axes")
    .help(
        "compile for a 5-axis machine (axes 5, kinematics head_ac or head_bc), \
         or slice the part in planar (horizontal) layers",
    )
}

/// A robot's analog output that would have to pass 1.0 for the power asked
/// (at an `At`).
pub struct AnalogOverrun<'a, At> {
    /// The robot's name.
    pub robot: &'a str,
    /// Its power output.
    pub output: &'a crate::ir::Signal,
    /// Its controller's words for the output.
    pub words: crate::diag::message::words::Words,
    /// The power at $ANOUT = 1.0, W.
    pub full_scale: f64,
    /// The output the worst power needs, as written.
    pub needed: f64,
    /// The worst power and how many moves ask for too much.
    pub worst: Worst<At>,
    /// The `full_scale` field.
    pub declared: Span,
    /// What sets the power.
    pub power: Option<Span>,
}

/// Laser power beyond the robot's analog output.
pub fn analog_range(a: &AnalogOverrun<'_, impl Display>) -> Diagnostic {
    let w = &a.worst;
    Diagnostic::error(
        Code::AnalogRange,
        format!(
            "laser power {} W needs {} = {} on robot `{}`, beyond the analog output's 1.0 ({} move{}, the worst at {})",
            short(w.value),
            a.words.analog_out(a.output),
            short(a.needed),
            a.robot,
            w.count,
            plural(w.count),
            w.at
        ),
    )
    .label(
        a.declared,
        format!(
            "full_scale = {} W is the power at {} = 1.0",
            short(a.full_scale),
            a.words.analog_outs(a.output)
        ),
    )
    .label_opt(a.power, "the power comes from here")
    .help(format!(
        "set `full_scale` to the power the laser source gives at full analog input \
         (at least {} W), or lower the power",
        short(w.value)
    ))
}

/// A position too large for machine `name` to write.
pub fn position_too_large(name: &str, w: &Worst<impl Display>, machine: Span) -> Diagnostic {
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
    .label(machine, "machine")
    .help("check the part's dimensions and units")
}

/// Moves of machine `name`'s plan shorter than the printed step (`w`: the
/// shortest, mm, against the step).
pub fn short_moves(name: &str, w: &Worst<impl Display>, machine: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::ShortMove,
        format!(
            "machine `{name}` would write {} move{} shorter than the {} mm its positions are \
             written at, the shortest {} mm at {}: each prints as no move, or as a step of one \
             digit the part does not make",
            w.count,
            plural(w.count),
            short(w.limit),
            short(w.value),
            w.at,
        ),
    )
    .label(machine, "machine")
    .help(
        "lmdc merges such points inside a path; a path whose points all lie in one place is \
         left as it is: look at the profile there (arcs or lines that meet in a sliver)",
    )
}

/// How a machine writes its speeds.
#[derive(Clone, Copy, Debug)]
pub enum SpeedWord {
    /// A CNC's F word.
    F {
        /// Its unit as written (`mm/min`).
        unit: &'static str,
        /// F per mm/s.
        per_mm_s: f64,
        /// Its decimals.
        decimals: usize,
    },
    /// A robot's `$VEL.CP`, in m/s with [`kuka::VEL_DECIMALS`] decimals.
    VelCp,
}

/// A speed machine `name`'s speed word cannot write within the tolerance;
/// `w` holds the planned speed and (as its limit) how it would come out;
/// `setting` is the field that decides how the speed is written.
pub fn speed_unwritable(
    name: &str,
    word: SpeedWord,
    w: &Worst<impl Display>,
    least_speed: f64,
    setting: Span,
    speeds: Option<Span>,
) -> Diagnostic {
    let tol = short(WRITE_TOLERANCE * 100.0);
    let (text, help, what) = match word {
        SpeedWord::F {
            unit,
            per_mm_s: per,
            decimals,
        } => {
            (
                format!("F{}", short(w.limit * per)),
                format!(
                    "F is written in {unit} with {decimals} decimals: speeds below {} mm/s do not come out within {tol} %; \
                     {}raise the speed",
                    short(0.5 * 10f64.powi(-(decimals as i32)) / (WRITE_TOLERANCE * per)),
                    if per < 60.0 { "`feed_units = mm_per_min` writes them 60 times finer, or " } else { "" }
                ),
                format!("writes F in {unit} with {decimals} decimals"),
            )
        }
        SpeedWord::VelCp => (
            format!("$VEL.CP = {}", short(w.limit / 1000.0)),
            format!(
                "$VEL.CP is written in m/s with {} decimals: speeds below {} mm/s do not come out within {tol} % (or at all); raise the speed",
                kuka::VEL_DECIMALS,
                short(0.0005 / WRITE_TOLERANCE)
            ),
            "writes $VEL.CP in m/s with 6 decimals".to_string(),
        ),
    };
    Diagnostic::error(
        Code::Resolution,
        format!(
            "machine `{name}` cannot write the speed {} mm/s: it would come out as {text}, at {} ({} move{}, the slowest {} mm/s)",
            short(w.value),
            w.at,
            w.count,
            plural(w.count),
            short(least_speed)
        ),
    )
    .label(setting, what)
    .label_opt(speeds, "the speeds come from here")
    .help(help)
}

/// A laser power the S word of CNC `name` (S = power × `s_per_watt`, with
/// `s_decimals` decimals) cannot write within the tolerance; `w` holds the
/// planned power and (as its limit) what S would give, `least` the smallest
/// power planned; `setting` is the field that sets the S word's scale and
/// decimals.
pub fn cnc_power_unwritable(
    name: &str,
    s_per_watt: f64,
    s_decimals: usize,
    w: &Worst<impl Display>,
    least: f64,
    setting: Span,
) -> Diagnostic {
    let tol = short(WRITE_TOLERANCE * 100.0);
    let spw = s_per_watt;
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
                s_decimals
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
            "machine `{name}` cannot write the laser power {} W: S would be {} (i.e. {} W), at {} ({} move{})",
            short(w.value),
            short(w.limit * spw),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(setting, "the S word's scale and decimals come from here")
    .help(help)
}

/// A laser power the analog output `$ANOUT[output]` of robot `name` (full
/// scale `full_scale_power` W) cannot write within the tolerance; `w` holds
/// the planned power and (as its limit) what would be given.
pub fn robot_power_unwritable(
    (name, words): (&str, crate::diag::message::words::Words),
    output: &crate::ir::Signal,
    full_scale_power: f64,
    w: &Worst<impl Display>,
    full_scale: Span,
) -> Diagnostic {
    let tol = short(WRITE_TOLERANCE * 100.0);
    Diagnostic::error(
        Code::Resolution,
        format!(
            "robot `{name}` cannot write the laser power {} W: {} = {} would give {} W, at {} ({} move{})",
            short(w.value),
            words.analog_out(output),
            short(w.limit / full_scale_power),
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label(full_scale, "the analog output's scale")
    .help(format!(
        "{} is written with {} decimals of full_scale = {} W: powers below {} W do not come out within {tol} %; \
         declare the full scale the laser really has",
        words.analog_outs(output),
        kuka::ANOUT_DECIMALS,
        short(full_scale_power),
        short(full_scale_power * 5e-5 / WRITE_TOLERANCE)
    ))
}

/// A CNC's declared `safe_height` that does not clear its part.
pub struct LowSafeHeight<'a, At> {
    /// The machine's name.
    pub machine: &'a str,
    /// The declared safe height, mm.
    pub declared: f64,
    /// The part's highest point (Z, mm) and where.
    pub top: (f64, At),
    /// The machine's clearance, mm.
    pub clearance: f64,
    /// The plan's highest move (the lifts aside) and where.
    pub highest: (f64, At),
}

/// `lmd::safe-height`.
pub fn safe_height(s: &LowSafeHeight<'_, impl Display>, declared: Span) -> Diagnostic {
    let over = s.top.0 + s.clearance;
    let need = over.max(s.highest.0);
    let higher = if s.highest.0 > over {
        format!(
            "; its program goes up to Z {} mm, at {}",
            short(s.highest.0),
            s.highest.1
        )
    } else {
        String::new()
    };
    Diagnostic::error(
        Code::SafeHeight,
        format!(
            "machine `{}`'s safe_height of {} mm does not clear the part: its highest point is at Z {} mm ({}), and the clearance is {} mm{higher}",
            s.machine,
            short(s.declared),
            short(s.top.0),
            s.top.1,
            short(s.clearance)
        ),
    )
    .label(declared, "declared here")
    .help(format!(
        "the program's first move goes across at the safe height and its last ends there: raise it to at least {} mm, or leave it out for the default (the highest point plus the clearance)",
        short_up(need)
    ))
}

//! What lmdc says about a `machine` block: its kind, frames, axes, dialect,
//! program texts, height sensor, and the gas and powder of its cell.

use crate::diag::message::words::Words;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;

/// A machine block (`span`) without `kind`.
pub fn missing_kind(name: &str, span: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, format!("machine `{name}` needs `kind`"))
        .label(span, "is it a robot or a CNC?")
        .help("add `kind = robot` (KUKA, KRL) or `kind = cnc` (G-code)")
}

/// The frame's `key` is `shown` (deg when `angle`, else mm), beyond the
/// bounds of any cell (±`max_mm`, ±`max_deg`).
pub fn frame_out_of_range(
    key: &str,
    shown: f64,
    angle: bool,
    at: Span,
    max_mm: f64,
    max_deg: f64,
) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "`{key}` of the frame is {}",
            if angle {
                format!("{}°", short(shown))
            } else {
                format!("{} mm", short(shown))
            }
        ),
    )
    .label(at, "beyond any cell")
    .help(format!(
        "frame offsets lie within ±{} m and angles within ±{max_deg}°",
        max_mm / 1000.0
    ))
}

/// A robot's `max_speed` (mm/s) is beyond `cap`, the KUKA $VEL.CP limit.
pub fn robot_speed_too_high(speed: f64, at: Span, cap: f64) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "`max_speed` {} mm/s is beyond what a KUKA controller takes for $VEL.CP",
            speed
        ),
    )
    .label(at, "lmdc moves at this speed between paths")
    .help(format!(
        "$VEL.CP is capped by the controller's $VEL_MA.CP, at most {} mm/s (3 m/s); \
         declare the robot's real path speed limit",
        cap
    ))
}

/// Axis `axis` (0-based) of `home` is at `deg`, beyond ±`max_deg`.
pub fn home_axis_out_of_range(
    (axis, words): (usize, Words),
    deg: f64,
    at: Span,
    max_deg: f64,
) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "home {} at {}° is beyond any robot axis",
            words.an_axis(axis),
            short(deg)
        ),
    )
    .label(at, "axis angle")
    .help(format!(
        "axis angles lie within ±{max_deg}°: give the angles of the home position the robot really has"
    ))
}

/// `home` is not a list of six angles (`got` describes what it is); the
/// example is the controller's usual home.
pub fn home_not_six_angles(at: Span, got: &str, words: Words) -> Diagnostic {
    Diagnostic::error(Code::Type, "`home` is the list of the six axis angles")
        .label(at, format!("this is {got}"))
        .help(match words {
            Words::Kuka => "e.g. `home = [0 deg, -90 deg, 90 deg, 0 deg, 0 deg, 0 deg]`",
            Words::Abb => "e.g. `home = [0 deg, 0 deg, 0 deg, 0 deg, 90 deg, 0 deg]`",
        })
}

/// A CNC declared with `axes = 4`.
pub fn four_axes(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        "a CNC has 3 axes (X Y Z) or 5 (X Y Z and a tilting head)",
    )
    .label(at, "4 axes")
    .help("write `axes = 3` or `axes = 5`")
}

/// The kinematics `kin` does not fit a machine of `axes` axes.
pub fn kinematics_mismatch(
    kin: &str,
    axes: u8,
    kin_at: Option<Span>,
    axes_at: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        format!("kinematics `{kin}` does not fit a {axes}-axis machine"),
    )
    .label_opt(kin_at, "kinematics")
    .label_opt(axes_at, "axes")
    .help("3 axes take `kinematics = xyz`; 5 axes take `head_ac`, `head_bc`, `table_ac` or `table_bc`")
}

/// A CNC's `postamble` has no program end (`M2`/`M30`).
pub fn postamble_without_end(at: Span) -> Diagnostic {
    Diagnostic::error(Code::ProgramText, "the postamble does not end the program")
        .label(at, "no `M2` or `M30` here")
        .help("end it with the control's program end, e.g. `postamble = [\"M5\", \"M30\"]`: without one the control runs on past the last line (LinuxCNC refuses the file)")
}

/// `preamble` or `postamble` (`key`) is not a list of texts.
pub fn lines_not_texts(key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Type, format!("`{key}` is a list of lines in quotes"))
        .label(at, "expected texts")
        .help(format!("e.g. `{key} = [\"G21 G90\", \"G94\"]`"))
}

/// `limits` bounds the tilt axis `other` that this head does not have
/// (its tilt axis is `tilt`).
pub fn no_such_head_axis(other: &str, tilt: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::UnknownField,
        format!("this machine's head has no {} axis", other.to_uppercase()),
    )
    .label(at, "not an axis of this machine")
    .help(format!(
        "the tilt axis of this kinematics is {}",
        tilt.to_uppercase()
    ))
}

/// A limit for rotary axis `axis` on a machine that moves X Y Z only.
pub fn no_rotary_axes(axis: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::UnknownField,
        format!(
            "this machine moves X Y Z only: it has no {} axis",
            axis.to_uppercase()
        ),
    )
    .label(at, "not an axis of this machine")
    .help(
        "drop the limit, or declare the head: `axes = 5` with `kinematics = head_ac` or `head_bc`",
    )
}

/// `origin` is not a point `[x, y, z]` (`got` describes what it is).
pub fn origin_not_a_point(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedPoint,
        "`origin` is where the part's origin is in machine coordinates: `[x, y, z]`",
    )
    .label(at, format!("this is {got}"))
    .help("e.g. `origin = [250 mm, 150 mm, 40 mm]`")
}

/// A height sensor field `key` is given without `height_input`.
pub fn sensor_without_input(key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        format!("`{key}` describes a height sensor, but the machine declares no `height_input`"),
    )
    .label(at, "for which input?")
    .help("add `height_input = N`, the analog input the sensor's height arrives on")
}

/// A height sensor's input is declared without `height_full_scale`.
pub fn sensor_without_full_scale(input: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        "a height sensor needs `height_full_scale`: the height at an input of 1.0",
    )
    .label_opt(input, "the sensor's input")
    .help("add `height_full_scale = 2 mm` (the height the sensor reports as full scale)")
}

/// A machine's name is declared a second time.
pub fn duplicate_machine(name: &str, second: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        Code::DuplicateName,
        format!("machine `{name}` is declared twice"),
    )
    .label(second, "second declaration")
    .label(first, "first declaration")
}

/// The file declares no machine at all.
pub fn no_machine() -> Diagnostic {
    Diagnostic::error(
        Code::MissingMachine,
        "the file declares no machine to write a program for",
    )
    .label(Span::new(0, 0), "no `machine` here")
    .help("add `machine NAME { kind = robot … }` or `machine NAME { kind = cnc … }`")
}

/// `what` and `other` (an earlier claim, at `first`) are both on the same
/// (analog or digital) output `n`.
pub fn output_clash(
    what: &str,
    other: &str,
    (analog, on): (bool, &crate::ir::Signal),
    at: Span,
    first: Option<Span>,
) -> Diagnostic {
    let (on, fix) = match on {
        crate::ir::Signal::Number(n) => (
            format!("{} output {n}", if analog { "analog" } else { "digital" }),
            "give each its own output number",
        ),
        crate::ir::Signal::Name(name) => (
            format!("signal `{name}`"),
            "give each its own signal (RAPID's names are the same in upper and lower case)",
        ),
    };
    Diagnostic::error(
        Code::OutputClash,
        format!("{what} and {other} are both on {on}"),
    )
    .label(at, what.to_string())
    .label_opt(first, other.to_string())
    .help(format!("every output switches one thing: {fix}"))
}

/// An output `key` given a signal's name (`at`) on a machine whose outputs
/// are numbered: a KUKA robot's (`robot`) or a CNC's.
pub fn signal_name_numbered(key: &str, at: Span, robot: bool) -> Diagnostic {
    let (who, numbered, example) = if robot {
        (
            "a KUKA robot",
            "KRL switches `$OUT[n]` and sets `$ANOUT[n]`",
            if key == "power_output" || key == "rate_output" {
                "2"
            } else {
                "1"
            },
        )
    } else {
        ("a CNC", "its output lines take the number as `{n}`", "2")
    };
    Diagnostic::error(
        Code::SignalName,
        format!("`{key}` names a signal, and this machine is {who}, whose outputs are numbered: {numbered}"),
    )
    .label(at, "a signal's name")
    .help(format!(
        "give the output's number, e.g. `{key} = {example}`; signals are named on an ABB robot (`controller = abb`, docs/rapid.md)"
    ))
}

/// A signal's name `name` for output `key` that RAPID cannot take or that
/// the program uses itself: `why` says which.
pub fn signal_name_invalid(key: &str, name: &str, at: Span, why: &str) -> Diagnostic {
    Diagnostic::error(
        Code::SignalName,
        format!("`{key} = \"{name}\"` is not a signal's name the program can use: {why}"),
    )
    .label(at, "the signal's name")
    .help("name the signal as the controller's I/O configuration does: a RAPID name, a letter then letters, digits and `_`, at most 32 characters (e.g. `\"doLaserOn\"`, `\"aoLaserPower\"`), not a RAPID reserved word nor one of lmdc's own names (`lmd_…`, `main`, `v200`, `fine`)")
}

/// A `powder` block (`at`) without `arrival`.
pub fn powder_without_arrival(at: Span) -> Diagnostic {
    Diagnostic::error(Code::MissingField, "`powder` needs `arrival`")
        .label(at, "how long until the powder reaches the nozzle?")
        .help(
            "add `arrival = 2 s`: the time from starting the feeder until the \
             powder comes out of the nozzle (measure it: seconds on most cells); \
             lmdc waits that long before the laser starts",
        )
}

/// `powder` has one of `rate_output` and `full_scale` (`has`) but not the
/// other (`lacks`).
pub fn powder_rate_half(has: &str, lacks: &str, at: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        format!("`powder` has `{has}` but no `{lacks}`"),
    )
    .label_opt(at, "the feed rate's analog output")
    .help(
        "give both: `rate_output = 2` (the analog output) and \
         `full_scale = 60 g/min` (the rate at 1.0), or neither when \
         the feeder's rate is set on the feeder",
    )
}

/// Gas or powder needs the output line `key`, which the CNC's dialect
/// `profile` does not have built in. The example is in that control's
/// language where lmdc knows it (Sinumerik's `$A_OUT`/`$A_OUTA` system
/// variables), never another control's M-code.
pub fn no_output_line(
    key: &str,
    profile: &str,
    cell: Option<Span>,
    dialect: Option<Span>,
) -> Diagnostic {
    let analog = key == "analog_output";
    let holes = if analog {
        "`{n}` for the output number and `{v}` for the value (a fraction of full scale)"
    } else {
        "`{n}` for the output number"
    };
    let example = match (profile, key) {
        ("sinumerik840d", "output_on") => Some("$A_OUT[{n}]=1"),
        ("sinumerik840d", "output_off") => Some("$A_OUT[{n}]=0"),
        ("sinumerik840d", _) => Some("$A_OUTA[{n}]={v}"),
        _ => None,
    };
    let help =
        match example {
            Some(e) => format!(
                "give the control's command in the machine block, with {holes}: on a {profile} \
             e.g. `{key} = \"{e}\"` (check how the machine's integrator wired the output)"
            ),
            None => {
                format!(
            "give the control's command in the machine block, with {holes}: `{key} = \"…\"` — \
             the M-function or system variable the {profile} control's integrator assigned to \
             the {} (its manual or PLC program names it)",
            if analog { "analog output" } else { "digital output" }
        )
            }
        };
    Diagnostic::error(
        Code::IoDialect,
        format!("the {profile} dialect has no built-in `{key}` line"),
    )
    .label_opt(cell, "gas and powder need outputs switched")
    .label_opt(dialect, "dialect")
    .help(help)
}

/// The output line `key` does not hold the hole `hole` exactly once;
/// `example` is LinuxCNC's line for it.
pub fn output_line_hole(key: &str, hole: &str, at: Span, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ProgramText,
        format!("`{key}` must hold `{hole}` once"),
    )
    .label(at, "output line")
    .help(format!(
        "`{{n}}` is where the output number goes{}: e.g. `{key} = \"{}\"`",
        if key == "analog_output" {
            ", `{v}` the value (a fraction of full scale)"
        } else {
            ""
        },
        example
    ))
}

/// `blending` is `mm`, below zero or beyond `max` mm.
pub fn blending_out_of_range(mm: f64, at: Span, max: f64) -> Diagnostic {
    let (code, what) = if mm < 0.0 {
        (Code::NotPositive, "a rounding distance cannot be negative")
    } else {
        (Code::OutOfRange, "far beyond a control's corner rounding")
    };
    Diagnostic::error(code, format!("`blending` is {} mm: {what}", short(mm)))
        .label(at, "the corner blending")
        .help(format!(
            "how far before a corner the control may leave the path to round it, from 0 mm (an exact stop) to {} mm, e.g. `blending = 0.5 mm`",
            short(max)
        ))
}

/// `ramp = lead` without an `acceleration` to size the lead by.
pub fn lead_without_acceleration(ramp: Option<Span>, block: Span) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        "`ramp = lead` needs the machine's `acceleration`: a lead-in is as long as the nozzle takes to reach its speed, v²/2a",
    )
    .label(ramp.unwrap_or(block), "a lead-in and a lead-out")
    .help("add the path acceleration the control plans with, e.g. `acceleration = 1000 mm/s^2`")
}

/// A robot declares an `arm` but its `what` (`base` or `tool`) is only an
/// index into the controller's table: the poses cannot be solved.
pub fn arm_unchecked(what: &str, at: Span, arm: Span) -> Diagnostic {
    let example = if what == "base" {
        "`base = frame(1, x = 1200 mm, y = 0 mm, z = 400 mm)`: where the part's origin sits from the robot's foot ($ROBROOT)"
    } else {
        "`tool = frame(1, z = 350 mm)`: the laser focus from the flange"
    };
    Diagnostic::warning(
        Code::ArmUnchecked,
        format!(
            "the arm cannot be checked: `{what}` is only an index into the controller's table, so lmdc does not know where the poses are"
        ),
    )
    .label(at, format!("the {what}'s value is on the controller"))
    .label(arm, "the arm declared here")
    .help(format!(
        "reach, axis limits, singularities and axis speeds are not checked; declare the value the program sets: {example}"
    ))
}

/// An ABB robot whose `what` (`tool`, `base`, `load`) is not declared in
/// full: its RAPID program declares it, so lmdc must know it.
pub fn abb_needs(what: &str, at: Span, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        format!("an ABB robot's program declares its {what}: its value is needed"),
    )
    .label(at, format!("the {what}'s value is not declared"))
    .help(format!("declare it: {example}"))
}

/// A catalogue arm (`name`) of another maker than the robot's controller
/// (`abb`: the controller is ABB's, the arm KUKA's; else the other way).
pub fn arm_of_other_maker(
    name: &str,
    abb: bool,
    arm: Span,
    controller: Option<Span>,
) -> Diagnostic {
    let (arm_maker, ctl, fix) = if abb {
        ("a KUKA", "an ABB controller (RAPID)", "an ABB arm (`irb2600_12_165`, `irb4600_60_205`, `irb4600_40_255`, `irb6700_200_260`), or `controller = kuka`")
    } else {
        ("an ABB", "a KUKA controller (KRL)", "`controller = abb` for RAPID, or a KUKA arm (`kr6_r900_2`, `kr16_2`, `kr60ha`, `kr150_r3100_2`)")
    };
    let d = Diagnostic::error(
        Code::ConflictingFields,
        format!("the {name} is {arm_maker} arm, and this robot has {ctl}: its axis angles and program would not be the arm's"),
    )
    .label(arm, format!("{arm_maker} arm"));
    let d = match controller {
        Some(at) => d.label(at, "the controller"),
        None => d,
    };
    d.help(format!("declare {fix}"))
}

/// An item of `opw(…)`'s `key` list that is not what it takes.
pub fn arm_list_item((key, words): (&str, Words), at: Span, got: &str, wanted: &str) -> Diagnostic {
    Diagnostic::error(Code::Type, format!("each item of `{key}` is {wanted}"))
        .label(at, format!("this is {got}"))
        .help(format!("one item per axis, {}: {wanted}", words.six_axes()))
}

/// `opw(…)`'s `key` is not a list of six.
pub fn arm_list_not_six((key, words): (&str, Words), at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("`{key}` is a list of six, one per axis {}", words.six_axes()),
    )
    .label(at, format!("this is {got}"))
    .help(if key == "limits" {
        "e.g. `limits = [-185 deg .. 185 deg, -155 deg .. 35 deg, -130 deg .. 154 deg, -350 deg .. 350 deg, -130 deg .. 130 deg, -350 deg .. 350 deg]`"
    } else {
        "e.g. `speeds = [156 deg/s, 156 deg/s, 156 deg/s, 330 deg/s, 330 deg/s, 615 deg/s]`"
    })
}

/// A field of a tilting table (`key`) on a machine whose kinematics (`kin`)
/// has no table, or of rotary axes on one without them.
pub fn not_a_table(key: &str, kin: &str, at: Span) -> Diagnostic {
    let what = if key == "rotary_speed" {
        "the rotary axes"
    } else {
        "a tilting table"
    };
    Diagnostic::error(
        Code::UnknownField,
        format!("`{key}` describes {what}, and this machine's kinematics is `{kin}`"),
    )
    .label(at, "no such axis on this machine")
    .help("drop it, or declare the table: `axes = 5` with `kinematics = table_ac` or `table_bc`")
}

/// A table axis's point (`key`) is not a point `[x, y, z]` (`got` says
/// what it is).
pub fn axis_point_not_a_point(key: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedPoint,
        format!("`{key}` is a point of the axis in machine coordinates: `[x, y, z]`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("e.g. `{key} = [0 mm, 120 mm, -80 mm]`"))
}

/// A tilting table (`kin`) without `key`, one of its axes' points.
pub fn table_axis_missing(key: &str, kin: &str, kinematics: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        format!("a `{kin}` machine needs `{key}`: where that axis is decides where every point of the part goes"),
    )
    .label_opt(kinematics, "a tilting table")
    .help(format!(
        "give a point of the axis in machine coordinates with every rotary axis at 0, e.g. `{key} = [250 mm, 200 mm, 100 mm]` (LinuxCNC: `x/y/z-rot-point` is `c_axis`, `x/y/z-offset` is `tilt_axis` − `c_axis`)"
    ))
}

//! `machine NAME { kind = robot | cnc, … }`: a KUKA robot's and a CNC's
//! fields, the CNC's `limits { … }`, and the `gas { … }` and `powder { … }`
//! blocks and height sensor either kind takes. The fields both kinds share
//! are one entry each, listed in both tables: the common part of a machine
//! ([`crate::ir::MachineCommon`]).

use super::Bound::{Any, Magnitude, Positive, ZeroUpTo};
use super::DefaultValue::{
    Count as DefaultCount, Described, Quantity as DefaultQuantity, Word as DefaultWord,
};
use super::Kind::{
    self, Block as Nested, Call, Count, Either, Io, Lines, List, Quantity, Text, Word,
};
use super::Need::{Default, Optional, Required};
use super::{Block, Field, Io as Signal, Len};
use crate::target::gcode::PROFILES;
use crate::units::Dim;

/// Largest angle a robot axis or frame is declared with, deg.
pub const MAX_ANGLE_DEG: f64 = 360.0;
/// Largest frame offset, mm: beyond any cell.
pub const MAX_FRAME_MM: f64 = 100_000.0;
/// Longest delay of a height reading lmdc plans, s.
pub const MAX_SENSOR_DELAY_S: f64 = 10.0;
/// Longest gas or powder time, s: far beyond any cell's, short of a typo's.
pub const MAX_CELL_TIME_S: f64 = 600.0;

/// The machine's name, `machine NAME { … }`: not a field, but what a check
/// points at when no field declares what it is about.
pub static NAME: Field = Field::new(
    "name",
    Kind::Name("machine"),
    Required("kr60"),
    "the machine's name: `--machine NAME` selects it, its programs are named after it",
);

/// `kind = robot | cnc`.
pub static KIND: Field = Field::new(
    "kind",
    Word(&["robot", "cnc"]),
    Required("robot"),
    "which controller the programs are for: a robot (KRL for KUKA, RAPID for ABB: `controller`) or a CNC (G-code)",
);

/// The highest speed, either kind.
pub static MAX_SPEED: Field = Field::new(
    "max_speed",
    Quantity(Dim::SPEED, Positive),
    Required("250 mm/s"),
    "the highest path speed, which rapid moves run at (a robot's within what KUKA's $VEL.CP takes, 3000 mm/s; an ABB robot's up to v7000)",
);

/// The back-off between paths, either kind.
pub static CLEARANCE: Field = Field::new(
    "clearance",
    Quantity(Dim::LENGTH, Positive),
    Default(DefaultQuantity(10.0)),
    "how far the nozzle backs off along the normal between paths that do not join",
);

/// Largest corner blending lmdc plans, mm: far beyond any control's
/// rounding at a bead's scale, short of a typo's.
pub const MAX_BLENDING_MM: f64 = 50.0;

/// The path acceleration, either kind.
pub static ACCELERATION: Field = Field::new(
    "acceleration",
    Quantity(Dim::ACCELERATION, Positive),
    Optional,
    "the path acceleration (and deceleration) the control plans with: the verifier then predicts where the nozzle runs slower than programmed and the bead grows (`lmd::deposit-bump`); none: the programmed speeds are taken as reached",
);

/// The corner blending, either kind.
pub static BLENDING: Field = Field::new(
    "blending",
    Quantity(Dim::LENGTH, ZeroUpTo(MAX_BLENDING_MM)),
    Default(Described(
        "a robot's 0.2 mm; a CNC's `G64 P…` or `ADIS=…` of its preamble (LinuxCNC's built-in `G64 P0.02`), else 0 mm",
    )),
    "how far before a corner the control may leave the path to round it, written into the program (KUKA `$APO.CDIS`, LinuxCNC `G64 P`, Sinumerik `G641 ADIS`); 0 mm: an exact stop at every corner",
);

/// How a bead starts and stops, either kind.
pub static RAMP: Field = Field::new(
    "ramp",
    Word(&["none", "lead"]),
    Default(DefaultWord("none")),
    "`lead`: a laser-off lead-in brings the nozzle up to speed where the laser starts, and a lead-out lets it slow down after the laser stops (needs `acceleration`); `none`: the laser switches where the nozzle stands",
);

/// The height sensor's input, either kind.
pub static HEIGHT_INPUT: Field = Field::new(
    "height_input",
    Io(Signal::AnalogIn),
    Optional,
    "the analog input a segment's mean layer height arrives on (a ring's height loop)",
);

/// The height at an input of 1.0.
pub static HEIGHT_FULL_SCALE: Field = Field::new(
    "height_full_scale",
    Quantity(Dim::LENGTH, Positive),
    Optional,
    "the height at an input of 1.0; needed with `height_input`",
);

/// When a segment's mean is on the input.
pub static HEIGHT_DELAY: Field = Field::new(
    "height_delay",
    Quantity(Dim::TIME, ZeroUpTo(MAX_SENSOR_DELAY_S)),
    Default(DefaultQuantity(0.0)),
    "how long after a segment's end its mean is on the input",
);

/// `gas { … }`, either kind.
pub static GAS_BLOCK: Field = Field::new(
    "gas",
    Nested(&GAS),
    Optional,
    "the shielding gas valve the program opens and closes",
);

/// `powder { … }`, either kind.
pub static POWDER_BLOCK: Field = Field::new(
    "powder",
    Nested(&POWDER),
    Optional,
    "the powder feeder the program starts and stops",
);

/// A robot's frame: an index, or `frame(…)` with a value.
const FRAME_REF: Kind = Either(&[Count(1, 32), Call(&[&FRAME])]);

/// `tool = …`.
pub static TOOL: Field = Field::new(
    "tool",
    FRAME_REF,
    Default(DefaultCount(1)),
    "the tool (TCP at the laser focus): `TOOL_DATA[n]`, or `frame(n, …)` to set it",
);

/// `base = …`.
pub static BASE: Field = Field::new(
    "base",
    FRAME_REF,
    Default(DefaultCount(1)),
    "the base the part is programmed in: `BASE_DATA[n]`, or `frame(n, …)` to set it",
);

/// `controller = kuka`.
pub static CONTROLLER: Field = Field::new(
    "controller",
    Word(&["kuka", "abb"]),
    Default(DefaultWord("kuka")),
    "the robot's controller: `kuka` (KRL) or `abb` (RAPID, docs/rapid.md)",
);

/// `beam = z`.
pub static BEAM: Field = Field::new(
    "beam",
    Word(&["x", "-x", "y", "-y", "z", "-z"]),
    Default(DefaultWord("z")),
    "the tool axis the beam leaves along",
);

/// `laser = 1`.
pub static LASER: Field = Field::new(
    "laser",
    Either(&[Count(1, 4096), Text]),
    Required("1"),
    "the digital output `$OUT[n]` (ABB: `do<n>`, or the signal's name, `\"doLaserOn\"`) that switches the laser",
);

/// `power_output = 1`.
pub static POWER_OUTPUT: Field = Field::new(
    "power_output",
    Either(&[Count(1, 32), Text]),
    Required("1"),
    "the analog output `$ANOUT[n]` (ABB: `ao<n>`, or the signal's name, `\"aoLaserPower\"`) that sets the power",
);

/// `full_scale = 4000 W`.
pub static FULL_SCALE: Field = Field::new(
    "full_scale",
    Quantity(Dim::POWER, Positive),
    Required("4000 W"),
    "the power at `$ANOUT = 1.0`",
);

/// `home = […]`.
pub static HOME: Field = Field::new(
    "home",
    List(
        &Quantity(
            Dim::ANGLE,
            Magnitude(crate::sema::schema::deg(MAX_ANGLE_DEG)),
        ),
        Len::Exactly(6),
    ),
    Default(Described("`[0 deg, -90 deg, 90 deg, 0 deg, 0 deg, 0 deg]` on KUKA, `[0 deg, 0 deg, 0 deg, 0 deg, 90 deg, 0 deg]` on ABB (the flange facing down)")),
    "the axis angles of the home position, moved to (PTP, `MoveAbsJ`) at the start and the end",
);

/// `arm = kr16_2 | opw(…)`.
pub static ARM: Field = Field::new(
    "arm",
    Either(&[Word(crate::target::arm::KEYS), Call(&[&OPW])]),
    Optional,
    "the arm: a KUKA model lmdc knows (docs/robots.md) or `opw(…)` with its own parameters; every move is then solved to axis angles and checked for reach, axis limits, singular LINs, configuration changes and axis speeds (needs `base` and `tool` as `frame(…)`)",
);

/// Largest margin or singularity distance, deg.
pub const MAX_ARM_ANGLE_DEG: f64 = 90.0;

/// `joint_margin = 2 deg`.
pub static JOINT_MARGIN: Field = Field::new(
    "joint_margin",
    Quantity(
        Dim::ANGLE,
        ZeroUpTo(crate::sema::schema::deg(MAX_ARM_ANGLE_DEG)),
    ),
    Default(DefaultQuantity(crate::sema::schema::deg(2.0))),
    "how far inside its limits every axis of the `arm` must stay",
);

/// `arm_links = [190 mm, 140 mm, 100 mm]`.
pub static ARM_LINKS: Field = Field::new(
    "arm_links",
    List(&Quantity(Dim::LENGTH, Positive), Len::Exactly(3)),
    Optional,
    "the radii of the arm's links as the collision checks take them, each a capsule: the upper arm, the forearm, the wrist (docs/collision.md, *The arm*); none: the catalogue's, for an arm from it (an `opw(…)` arm's links are then not checked)",
);

/// `singularity = 5 deg`.
pub static SINGULARITY: Field = Field::new(
    "singularity",
    Quantity(
        Dim::ANGLE,
        ZeroUpTo(crate::sema::schema::deg(MAX_ARM_ANGLE_DEG)),
    ),
    Default(DefaultQuantity(crate::sema::schema::deg(5.0))),
    "how far a LIN must stay from the wrist singularity (A5 = 0), the stretched arm (A3 at its stretch angle) and A1's axis (the wrist centre overhead, seen from the shoulder)",
);

/// `spin = auto | 30 deg`.
pub static SPIN: Field = Field::new(
    "spin",
    Either(&[
        Word(&["auto"]),
        Quantity(Dim::ANGLE, Magnitude(crate::sema::schema::deg(180.0))),
    ]),
    Default(DefaultWord("auto")),
    "the tool's turn about the beam, free for a coaxial nozzle; `auto`: 0° unless the `arm`'s rules fail there, then the turn that keeps the axes farthest from their limits and singularities (docs/robots.md)",
);

/// `load = load(…)`.
pub static LOAD: Field = Field::new(
    "load",
    Call(&[&LOAD_DATA]),
    Optional,
    "the tool's load — its mass, centre of gravity and, optionally, inertia — which the program sets as `$LOAD` (KUKA's load data of the tool's number); none: the controller's `LOAD_DATA[n]` is used, unchecked (`lmd::load-unchecked`)",
);

/// Heaviest tool load lmdc takes, kg: above any KUKA arm's rated payload
/// (the KR 1000 titan's 1300 kg), short of a typo's.
pub const MAX_LOAD_KG: f64 = 1500.0;
/// Farthest a load's centre of gravity may lie from the flange along each
/// axis, mm: beyond any nozzle's, short of a typo's.
pub const MAX_COG_MM: f64 = 2000.0;
/// Largest principal moment of inertia of a load, kg·m²: more than the
/// heaviest load at a metre, short of a typo's.
pub const MAX_INERTIA_KG_M2: f64 = 2000.0;

/// `load(mass, cog, inertia, inertia_axes)`: a robot tool's load, as
/// KUKA's `LOAD_DATA` holds it.
pub static LOAD_DATA: Block = Block::new(
    "load",
    "load(mass = 12 kg, cog = [0 mm, 0 mm, 150 mm])",
    "the tool's load as KUKA's `$LOAD` takes it: its mass, and where its centre of gravity and principal axes of inertia are in the flange's frame (`$FLANGE`)",
    &[
        &load::MASS,
        &load::COG,
        &load::INERTIA,
        &load::INERTIA_AXES,
    ],
);

/// The arguments of `load(…)`.
pub mod load {
    use super::super::Bound::{Magnitude, PositiveUpTo, ZeroUpTo};
    use super::super::DefaultValue::Described;
    use super::super::Field;
    use super::super::Kind::{List, Quantity};
    use super::super::Len;
    use super::super::Need::{Default, Required};
    use super::{MAX_ANGLE_DEG, MAX_COG_MM, MAX_INERTIA_KG_M2, MAX_LOAD_KG};
    use crate::units::Dim;

    /// `mass = 12 kg`.
    pub static MASS: Field = Field::new(
        "mass",
        Quantity(Dim::MASS, PositiveUpTo(MAX_LOAD_KG * 1000.0)),
        Required("12 kg"),
        "the tool's mass with everything it carries (nozzle, hoses and fibre as far as they hang on the flange): KUKA's `M`",
    );
    /// `cog = [x, y, z]`.
    pub static COG: Field = Field::new(
        "cog",
        List(
            &Quantity(Dim::LENGTH, Magnitude(MAX_COG_MM)),
            Len::Exactly(3),
        ),
        Required("[0 mm, 0 mm, 150 mm]"),
        "its centre of gravity in the flange's frame (Z out of the flange): KUKA's `CM` X, Y, Z",
    );
    /// `inertia = [jx, jy, jz]`.
    pub static INERTIA: Field = Field::new(
        "inertia",
        List(
            &Quantity(Dim::INERTIA, ZeroUpTo(MAX_INERTIA_KG_M2 * 1e9)),
            Len::Exactly(3),
        ),
        Default(Described("`[0 kg*m^2, 0 kg*m^2, 0 kg*m^2]`: a point mass")),
        "its principal moments of inertia about its centre of gravity: KUKA's `J` X, Y, Z",
    );
    /// `inertia_axes = [a, b, c]`.
    pub static INERTIA_AXES: Field = Field::new(
        "inertia_axes",
        List(
            &Quantity(
                Dim::ANGLE,
                Magnitude(crate::sema::schema::deg(MAX_ANGLE_DEG)),
            ),
            Len::Exactly(3),
        ),
        Default(Described("`[0 deg, 0 deg, 0 deg]`: along the flange's axes")),
        "how its principal axes of inertia are turned from the flange's, KUKA A, B, C: KUKA's `CM` A, B, C",
    );
}

/// `opw(a1, a2, b, c1, c2, c3, c4, limits, speeds)`: an arm by its parameters.
pub static OPW: Block = Block::new(
    "opw",
    "opw(a1 = …, a2 = …, b = …, c1 = …, c2 = …, c3 = …, c4 = …, limits = […], speeds = […])",
    "an arm with an ortho-parallel base and a spherical wrist, by its OPW parameters, in KUKA's axis angles",
    &[
        &opw::A1,
        &opw::A2,
        &opw::B,
        &opw::C1,
        &opw::C2,
        &opw::C3,
        &opw::C4,
        &opw::LIMITS,
        &opw::SPEEDS,
    ],
);

/// The arguments of `opw(…)`.
pub mod opw {
    use super::super::Bound::{Magnitude, Positive};
    use super::super::DefaultValue::Quantity as DefaultQuantity;
    use super::super::Field;
    use super::super::Kind::{List, Quantity, Range};
    use super::super::Len;
    use super::super::Need::{Default, Required};
    use super::MAX_FRAME_MM;
    use crate::units::Dim;

    const LINK: super::Kind = Quantity(Dim::LENGTH, Magnitude(MAX_FRAME_MM));

    /// `a1`.
    pub static A1: Field = Field::new(
        "a1",
        LINK,
        Required("260 mm"),
        "A1 axis to A2 axis, along the arm",
    );
    /// `a2`.
    pub static A2: Field = Field::new(
        "a2",
        LINK,
        Default(DefaultQuantity(0.0)),
        "the forearm's offset from the A3 axis",
    );
    /// `b`.
    pub static B: Field = Field::new(
        "b",
        LINK,
        Default(DefaultQuantity(0.0)),
        "the sideways offset",
    );
    /// `c1`.
    pub static C1: Field = Field::new(
        "c1",
        LINK,
        Required("675 mm"),
        "the base's floor to the A2 axis",
    );
    /// `c2`.
    pub static C2: Field = Field::new(
        "c2",
        LINK,
        Required("680 mm"),
        "A2 axis to A3 axis (the upper arm)",
    );
    /// `c3`.
    pub static C3: Field = Field::new(
        "c3",
        LINK,
        Required("670 mm"),
        "A3 axis to the wrist centre (the forearm)",
    );
    /// `c4`.
    pub static C4: Field = Field::new(
        "c4",
        LINK,
        Required("158 mm"),
        "the wrist centre to the flange",
    );
    /// `limits`.
    pub static LIMITS: Field = Field::new(
        "limits",
        List(&Range(Dim::ANGLE), Len::Exactly(6)),
        Required("[-185 deg .. 185 deg, -155 deg .. 35 deg, -130 deg .. 154 deg, -350 deg .. 350 deg, -130 deg .. 130 deg, -350 deg .. 350 deg]"),
        "A1–A6's software limits",
    );
    /// `speeds`.
    pub static SPEEDS: Field = Field::new(
        "speeds",
        List(&Quantity(Dim::ANGULAR_SPEED, Positive), Len::Exactly(6)),
        Required("[156 deg/s, 156 deg/s, 156 deg/s, 330 deg/s, 330 deg/s, 615 deg/s]"),
        "A1–A6's top speeds",
    );
}

/// `module_lines = 2000`.
pub static MODULE_LINES: Field = Field::new(
    "module_lines",
    Count(10, 100_000),
    Default(DefaultCount(2000)),
    "the most motion lines in one sub-program module",
);

/// A KUKA robot (KRL).
pub static ROBOT: Block = Block::new(
    "robot",
    "machine NAME { kind = robot … }",
    "a KUKA robot programmed in KRL, or an ABB robot in RAPID",
    &[
        &KIND,
        &CONTROLLER,
        &TOOL,
        &LOAD,
        &BASE,
        &BEAM,
        &LASER,
        &POWER_OUTPUT,
        &FULL_SCALE,
        &MAX_SPEED,
        &HOME,
        &ARM,
        &JOINT_MARGIN,
        &SINGULARITY,
        &ARM_LINKS,
        &SPIN,
        &CLEARANCE,
        &ACCELERATION,
        &BLENDING,
        &RAMP,
        &MODULE_LINES,
        &HEIGHT_INPUT,
        &HEIGHT_FULL_SCALE,
        &HEIGHT_DELAY,
        &GAS_BLOCK,
        &POWDER_BLOCK,
        &super::collision::HEAD_BLOCK,
        &POSITIONER_BLOCK,
    ],
);

/// `frame(index, x, y, z, a, b, c)`: a robot's tool or base with its value.
pub static FRAME: Block = Block::new(
    "frame",
    "frame(index, x, y, z, a, b, c)",
    "a robot's tool or base, with the value the program sets",
    &[
        &frame::INDEX,
        &frame::X,
        &frame::Y,
        &frame::Z,
        &frame::A,
        &frame::B,
        &frame::C,
    ],
)
.positional(1);

/// The arguments of `frame(…)`.
pub mod frame {
    use super::super::Bound::Magnitude;
    use super::super::DefaultValue::Quantity as DefaultQuantity;
    use super::super::Field;
    use super::super::Kind::{Count, Quantity};
    use super::super::Need::{Default, Required};
    use super::{MAX_ANGLE_DEG, MAX_FRAME_MM};
    use crate::units::Dim;

    const OFFSET: super::Kind = Quantity(Dim::LENGTH, Magnitude(MAX_FRAME_MM));
    const TURN: super::Kind = Quantity(
        Dim::ANGLE,
        Magnitude(crate::sema::schema::deg(MAX_ANGLE_DEG)),
    );

    /// `index`.
    pub static INDEX: Field = Field::new(
        "index",
        Count(1, 32),
        Required("1"),
        "the frame's number: `TOOL_DATA[n]`, `BASE_DATA[n]`",
    );
    /// `x`.
    pub static X: Field = Field::new(
        "x",
        OFFSET,
        Default(DefaultQuantity(0.0)),
        "the offset along X",
    );
    /// `y`.
    pub static Y: Field = Field::new(
        "y",
        OFFSET,
        Default(DefaultQuantity(0.0)),
        "the offset along Y",
    );
    /// `z`.
    pub static Z: Field = Field::new(
        "z",
        OFFSET,
        Default(DefaultQuantity(0.0)),
        "the offset along Z",
    );
    /// `a`.
    pub static A: Field = Field::new(
        "a",
        TURN,
        Default(DefaultQuantity(0.0)),
        "KUKA A: the turn about Z",
    );
    /// `b`.
    pub static B: Field = Field::new(
        "b",
        TURN,
        Default(DefaultQuantity(0.0)),
        "KUKA B: then about the new Y",
    );
    /// `c`.
    pub static C: Field = Field::new(
        "c",
        TURN,
        Default(DefaultQuantity(0.0)),
        "KUKA C: then about the new X",
    );
}

/// The dialect's value of a line or number.
const DIALECTS: super::Need = Default(Described("the dialect's"));

/// `axes = 3 | 5`.
pub static AXES: Field = Field::new(
    "axes",
    Count(3, 5),
    Required("5"),
    "3 (X Y Z) or 5 (a tilting head or table); 4 is refused",
);

/// `kinematics = …`.
pub static KINEMATICS: Field = Field::new(
    "kinematics",
    Word(&["xyz", "head_ac", "head_bc", "table_ac", "table_bc"]),
    Default(Described("`xyz` for 3 axes, `head_ac` for 5")),
    "how the axes move the nozzle: X Y Z only, a head tilting about A or B, then C, or a table turning the part on C, tilted about A or B",
);

/// `c_axis = [x, y, z]`.
pub static C_AXIS: Field = Field::new(
    "c_axis",
    List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
    Default(Described("required with `table_ac` and `table_bc`")),
    "a tilting table's C axis: a point of it in machine coordinates, the tilt at 0 (LinuxCNC's `x/y/z-rot-point`)",
);

/// `tilt_axis = [x, y, z]`.
pub static TILT_AXIS: Field = Field::new(
    "tilt_axis",
    List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
    Default(Described("required with `table_ac` and `table_bc`")),
    "a tilting table's A or B axis: a point of it in machine coordinates (its offset from `c_axis` is LinuxCNC's `x/y/z-offset`)",
);

/// `table_output = tcp | machine`.
pub static TABLE_OUTPUT: Field = Field::new(
    "table_output",
    Word(&["tcp", "machine"]),
    Default(DefaultWord("tcp")),
    "a tilting table's program: part coordinates under the control's transform (`tcp`: trt kinematics, TRAORI, #RTCP), or machine coordinates lmdc computes (`machine`)",
);

/// `rotary_speed = 90 deg/s`.
pub static ROTARY_SPEED: Field = Field::new(
    "rotary_speed",
    Quantity(Dim::ANGULAR_SPEED, Positive),
    Optional,
    "the rotary axes' top speed; the plan's feed moves are checked against it (none: not checked)",
);

/// `dialect = linuxcnc`.
pub static DIALECT: Field = Field::new(
    "dialect",
    Word(PROFILES),
    Default(DefaultWord("linuxcnc")),
    "the control's G-code dialect",
);

/// `laser_on = "M3"`.
pub static LASER_ON: Field = Field::new(
    "laser_on",
    Text,
    DIALECTS,
    "the line that switches the laser on",
);
/// `laser_off = "M5"`.
pub static LASER_OFF: Field = Field::new(
    "laser_off",
    Text,
    DIALECTS,
    "the line that switches the laser off",
);

/// `s_per_watt = 1`.
pub static S_PER_WATT: Field = Field::new(
    "s_per_watt",
    Quantity(Dim::NONE, Positive),
    DIALECTS,
    "how many S units one watt is (1 when S is programmed in W)",
);

/// `s_decimals = 0`.
pub static S_DECIMALS: Field = Field::new(
    "s_decimals",
    Count(0, 4),
    DIALECTS,
    "the decimals of the S word",
);

/// `preamble = […]`.
pub static PREAMBLE: Field = Field::new(
    "preamble",
    Lines,
    DIALECTS,
    "the lines at the start of the program, after the header comment",
);

/// `postamble = […]`.
pub static POSTAMBLE: Field = Field::new(
    "postamble",
    Lines,
    DIALECTS,
    "the lines at the end of the program; they must end it (`M2` or `M30`)",
);

/// `tcp_on = "TRAORI"`.
pub static TCP_ON: Field = Field::new(
    "tcp_on",
    Text,
    DIALECTS,
    "the line that switches tool-tip control on for 5-axis moves",
);

/// `tcp_off = "TRAFOOF"`.
pub static TCP_OFF: Field = Field::new("tcp_off", Text, DIALECTS, "the line that switches it off");

/// `dwell = "G4 P{s}"`.
pub static DWELL: Field = Field::new(
    "dwell",
    Text,
    DIALECTS,
    "a dwell: the line, with `{s}` where the seconds go",
);

/// `work_offset = 1`.
pub static WORK_OFFSET: Field = Field::new(
    "work_offset",
    Count(1, 6),
    Optional,
    "the work offset the program selects, 1 (G54) to 6 (G59); none: the control's active one",
);

/// `origin = [x, y, z]`.
pub static ORIGIN: Field = Field::new(
    "origin",
    List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
    Default(Described("`[0 mm, 0 mm, 0 mm]`")),
    "where the part's origin is in machine coordinates (the work offset's value)",
);

/// `feed_units = mm_per_min`.
pub static FEED_UNITS: Field = Field::new(
    "feed_units",
    Word(&["mm_per_min", "mm_per_s"]),
    DIALECTS,
    "what the F word measures",
);

/// `output_on = "…"`.
pub static OUTPUT_ON: Field = Field::new(
    "output_on",
    Text,
    Default(Described("LinuxCNC's `M64 P{n}`, else none")),
    "the line that switches digital output `{n}` on (gas, powder)",
);

/// `output_off = "…"`.
pub static OUTPUT_OFF: Field = Field::new(
    "output_off",
    Text,
    Default(Described("LinuxCNC's `M65 P{n}`, else none")),
    "the line that switches digital output `{n}` off",
);

/// `analog_output = "…"`.
pub static ANALOG_OUTPUT: Field = Field::new(
    "analog_output",
    Text,
    Default(Described("LinuxCNC's `M68 E{n} Q{v}`, else none")),
    "the line that sets analog output `{n}` to `{v}`, a fraction of its full scale (the powder rate)",
);

/// `safe_height = 150 mm`.
pub static SAFE_HEIGHT: Field = Field::new(
    "safe_height",
    Quantity(Dim::LENGTH, Any),
    Default(Described("the part's highest point (or the highest fixture's top) plus the clearance")),
    "the height (Z, part coordinates) the program's first move lifts the nozzle to before X, Y and the rotary axes move, and its last move ends at; at least the default (`lmd::safe-height`)",
);

/// `limits { … }`.
pub static LIMITS_BLOCK: Field = Field::new(
    "limits",
    Nested(&LIMITS),
    Default(Described("±1000 mm, the tilt ±110°, C ±360°")),
    "the axes' travel in machine coordinates",
);

/// A CNC (G-code).
pub static CNC: Block = Block::new(
    "cnc",
    "machine NAME { kind = cnc … }",
    "a CNC, programmed in G-code",
    &[
        &KIND,
        &AXES,
        &KINEMATICS,
        &DIALECT,
        &LASER_ON,
        &LASER_OFF,
        &S_PER_WATT,
        &S_DECIMALS,
        &PREAMBLE,
        &POSTAMBLE,
        &TCP_ON,
        &TCP_OFF,
        &DWELL,
        &WORK_OFFSET,
        &ORIGIN,
        &FEED_UNITS,
        &MAX_SPEED,
        &CLEARANCE,
        &SAFE_HEIGHT,
        &C_AXIS,
        &TILT_AXIS,
        &TABLE_OUTPUT,
        &ROTARY_SPEED,
        &ACCELERATION,
        &BLENDING,
        &RAMP,
        &OUTPUT_ON,
        &OUTPUT_OFF,
        &ANALOG_OUTPUT,
        &HEIGHT_INPUT,
        &HEIGHT_FULL_SCALE,
        &HEIGHT_DELAY,
        &LIMITS_BLOCK,
        &GAS_BLOCK,
        &POWDER_BLOCK,
        &super::collision::HEAD_BLOCK,
    ],
)
.with_examples(&[(&MAX_SPEED, "100 mm/s")]);

/// A machine whose `kind` is missing or wrong: what either kind takes, so a
/// misspelt field shows in the same run as the kind.
pub static MACHINE: Block = Block::new(
    "machine",
    "machine NAME { kind = robot | cnc … }",
    "a machine whose kind is missing or wrong",
    &[
        &KIND,
        &CONTROLLER,
        &TOOL,
        &LOAD,
        &BASE,
        &BEAM,
        &LASER,
        &POWER_OUTPUT,
        &FULL_SCALE,
        &MAX_SPEED,
        &HOME,
        &ARM,
        &JOINT_MARGIN,
        &SINGULARITY,
        &ARM_LINKS,
        &SPIN,
        &CLEARANCE,
        &ACCELERATION,
        &BLENDING,
        &RAMP,
        &MODULE_LINES,
        &HEIGHT_INPUT,
        &HEIGHT_FULL_SCALE,
        &HEIGHT_DELAY,
        &AXES,
        &KINEMATICS,
        &DIALECT,
        &LASER_ON,
        &LASER_OFF,
        &S_PER_WATT,
        &S_DECIMALS,
        &PREAMBLE,
        &POSTAMBLE,
        &TCP_ON,
        &TCP_OFF,
        &DWELL,
        &WORK_OFFSET,
        &ORIGIN,
        &FEED_UNITS,
        &SAFE_HEIGHT,
        &C_AXIS,
        &TILT_AXIS,
        &TABLE_OUTPUT,
        &ROTARY_SPEED,
        &OUTPUT_ON,
        &OUTPUT_OFF,
        &ANALOG_OUTPUT,
        &LIMITS_BLOCK,
        &GAS_BLOCK,
        &POWDER_BLOCK,
        &super::collision::HEAD_BLOCK,
        &POSITIONER_BLOCK,
    ],
);

/// The fields of `limits { … }`.
pub mod limits {
    use super::super::Kind::Range;
    use super::super::Need::Default;
    use super::super::{DefaultValue::Described, Field};
    use crate::units::Dim;

    /// `x = lo .. hi`.
    pub static X: Field = Field::new(
        "x",
        Range(Dim::LENGTH),
        Default(Described("`-1000 mm .. 1000 mm`")),
        "the X axis' travel",
    );
    /// `y = lo .. hi`.
    pub static Y: Field = Field::new(
        "y",
        Range(Dim::LENGTH),
        Default(Described("`-1000 mm .. 1000 mm`")),
        "the Y axis' travel",
    );
    /// `z = lo .. hi`.
    pub static Z: Field = Field::new(
        "z",
        Range(Dim::LENGTH),
        Default(Described("`-1000 mm .. 1000 mm`")),
        "the Z axis' travel",
    );
    /// `a = lo .. hi`.
    pub static A: Field = Field::new(
        "a",
        Range(Dim::ANGLE),
        Default(Described("`-110 deg .. 110 deg`")),
        "the tilt axis of `head_ac` and `table_ac`",
    );
    /// `b = lo .. hi`.
    pub static B: Field = Field::new(
        "b",
        Range(Dim::ANGLE),
        Default(Described("`-110 deg .. 110 deg`")),
        "the tilt axis of `head_bc` and `table_bc`",
    );
    /// `c = lo .. hi`.
    pub static C: Field = Field::new(
        "c",
        Range(Dim::ANGLE),
        Default(Described("`-360 deg .. 360 deg`")),
        "the rotary axis C",
    );
}

/// A CNC's `limits { … }`.
pub static LIMITS: Block = Block::new(
    "limits",
    "limits { … }",
    "a CNC's travel limits, in machine coordinates",
    &[
        &limits::X,
        &limits::Y,
        &limits::Z,
        &limits::A,
        &limits::B,
        &limits::C,
    ],
);

/// The fields of `gas { … }`.
pub mod gas {
    use super::super::Bound::ZeroUpTo;
    use super::super::DefaultValue::Quantity as DefaultQuantity;
    use super::super::Kind::{Either, Io, Quantity, Text};
    use super::super::Need::{Default, Required};
    use super::super::{Field, Io as Signal};
    use super::MAX_CELL_TIME_S;
    use crate::units::Dim;

    /// `output = 2`.
    pub static OUTPUT: Field = Field::new(
        "output",
        Either(&[Io(Signal::DigitalOut), Text]),
        Required("2"),
        "the digital output that opens the valve (ABB: or the signal's name, `\"doGas\"`)",
    );
    /// `pre_flow = 2 s`.
    pub static PRE_FLOW: Field = Field::new(
        "pre_flow",
        Quantity(Dim::TIME, ZeroUpTo(MAX_CELL_TIME_S)),
        Default(DefaultQuantity(0.0)),
        "how long the gas flows before the laser first starts",
    );
    /// `post_flow = 5 s`.
    pub static POST_FLOW: Field = Field::new(
        "post_flow",
        Quantity(Dim::TIME, ZeroUpTo(MAX_CELL_TIME_S)),
        Default(DefaultQuantity(0.0)),
        "how long it flows on after the laser last stops",
    );
}

/// `gas { … }`.
pub static GAS: Block = Block::new(
    "gas",
    "gas { … }",
    "the shielding gas valve, on a digital output",
    &[&gas::OUTPUT, &gas::PRE_FLOW, &gas::POST_FLOW],
);

/// The fields of `powder { … }`.
pub mod powder {
    use super::super::Bound::{Positive, ZeroUpTo};
    use super::super::Kind::{Either, Io, Quantity, Text};
    use super::super::Need::{Optional, Required};
    use super::super::{Field, Io as Signal};
    use super::MAX_CELL_TIME_S;
    use crate::units::Dim;

    /// `output = 3`.
    pub static OUTPUT: Field = Field::new(
        "output",
        Either(&[Io(Signal::DigitalOut), Text]),
        Required("3"),
        "the digital output that starts the feeder (ABB: or the signal's name, `\"doPowder\"`)",
    );
    /// `arrival = 2.5 s`.
    pub static ARRIVAL: Field = Field::new(
        "arrival",
        Quantity(Dim::TIME, ZeroUpTo(MAX_CELL_TIME_S)),
        Required("2.5 s"),
        "the time from starting the feeder (or changing its rate) until powder leaves the nozzle",
    );
    /// `rate_output = 2`.
    pub static RATE_OUTPUT: Field = Field::new(
        "rate_output",
        Either(&[Io(Signal::AnalogOut), Text]),
        Optional,
        "the analog output that sets the feed rate, with `full_scale` (ABB: or the signal's name, `\"aoPowderRate\"`)",
    );
    /// `full_scale = 60 g/min`.
    pub static FULL_SCALE: Field = Field::new(
        "full_scale",
        Quantity(Dim::MASS_FLOW, Positive),
        Optional,
        "the feed rate at 1.0 on the rate output (with `rate_output`)",
    );
}

/// `powder { … }`.
pub static POWDER: Block = Block::new(
    "powder",
    "powder { … }",
    "the powder feeder, on a digital output, its rate on an analog one where the cell has it",
    &[
        &powder::OUTPUT,
        &powder::ARRIVAL,
        &powder::RATE_OUTPUT,
        &powder::FULL_SCALE,
    ],
);

/// `positioner { … }`, a robot's.
pub static POSITIONER_BLOCK: Field = Field::new(
    "positioner",
    Nested(&POSITIONER),
    Optional,
    "a two-axis positioner turning the part (KUKA external axes E1 tilt, E2 rotate, mathematically coupled): `base` is then where the part's base sits on its flange (docs/robots.md)",
);

/// `positioner { … }`: a robot's tilt-and-rotate positioner.
pub static POSITIONER: Block = Block::new(
    "positioner",
    "positioner { tilt_axis = [1, 0, 0] … }",
    "a robot's two-axis positioner: E1 tilts, E2 rotates the part on its flange; axes given in the robot's frame at E1 = E2 = 0",
    &[
        &positioner::TILT_AXIS,
        &positioner::TILT_POINT,
        &positioner::TILT_LIMITS,
        &positioner::TILT_SPEED,
        &positioner::ROTATE_AXIS,
        &positioner::ROTATE_POINT,
        &positioner::ROTATE_LIMITS,
        &positioner::ROTATE_SPEED,
        &positioner::HOME,
        &positioner::KEEP,
        &positioner::FACEPLATE,
    ],
);

/// `cone(angle)`: a positioner that turns only when the layer leaves the cone.
pub static CONE: Block = Block::new(
    "cone",
    "cone(15 deg)",
    "keep each layer's mean normal within this angle of straight up, turning only when it leaves",
    &[&positioner::CONE_ANGLE],
)
.positional(1);

/// `fixed(e1, e2)`: a positioner standing still.
pub static FIXED: Block = Block::new(
    "fixed",
    "fixed(e1 = 30 deg, e2 = 0 deg)",
    "the positioner at these angles for every layer",
    &[&positioner::E1, &positioner::E2],
);

/// The fields of `positioner { … }` and its `keep`'s calls.
pub mod positioner {
    use super::super::Bound::{Any, Magnitude, Positive, ZeroUpTo};
    use super::super::DefaultValue::{Quantity as DefaultQuantity, Word as DefaultWord};
    use super::super::Kind::{self, Call, Either, List, Quantity, Range, Word};
    use super::super::Need::{Default, Optional, Required};
    use super::super::{Field, Len};
    use super::MAX_ANGLE_DEG;
    use crate::units::Dim;

    const DIRECTION: Kind = List(&Quantity(Dim::NONE, Any), Len::Exactly(3));
    const POINT: Kind = List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3));
    const ANGLE: Kind = Quantity(
        Dim::ANGLE,
        Magnitude(crate::sema::schema::deg(MAX_ANGLE_DEG)),
    );

    /// `tilt_axis = [1, 0, 0]`.
    pub static TILT_AXIS: Field = Field::new(
        "tilt_axis",
        DIRECTION,
        Required("[1, 0, 0]"),
        "E1's direction in the robot's frame (`$ROBROOT`); a positive E1 turns right-handed about it",
    );
    /// `tilt_point = [x, y, z]`.
    pub static TILT_POINT: Field = Field::new(
        "tilt_point",
        POINT,
        Required("[1500 mm, 0 mm, 600 mm]"),
        "a point of E1's axis in the robot's frame",
    );
    /// `tilt_limits = lo .. hi`.
    pub static TILT_LIMITS: Field = Field::new(
        "tilt_limits",
        Range(Dim::ANGLE),
        Required("-90 deg .. 90 deg"),
        "E1's software limits",
    );
    /// `tilt_speed = 60 deg/s`.
    pub static TILT_SPEED: Field = Field::new(
        "tilt_speed",
        Quantity(Dim::ANGULAR_SPEED, Positive),
        Required("60 deg/s"),
        "E1's top speed",
    );
    /// `rotate_axis = [0, 0, 1]`.
    pub static ROTATE_AXIS: Field = Field::new(
        "rotate_axis",
        DIRECTION,
        Required("[0, 0, 1]"),
        "E2's direction in the robot's frame at E1 = 0: the flange's Z (not along `tilt_axis`)",
    );
    /// `rotate_point = [x, y, z]`.
    pub static ROTATE_POINT: Field = Field::new(
        "rotate_point",
        POINT,
        Required("[1500 mm, 0 mm, 700 mm]"),
        "the flange's centre, on E2's axis, in the robot's frame at E1 = 0",
    );
    /// `rotate_limits = lo .. hi`.
    pub static ROTATE_LIMITS: Field = Field::new(
        "rotate_limits",
        Range(Dim::ANGLE),
        Required("-360 deg .. 360 deg"),
        "E2's software limits",
    );
    /// `rotate_speed = 90 deg/s`.
    pub static ROTATE_SPEED: Field = Field::new(
        "rotate_speed",
        Quantity(Dim::ANGULAR_SPEED, Positive),
        Required("90 deg/s"),
        "E2's top speed",
    );
    /// `home = [e1, e2]`.
    pub static HOME: Field = Field::new(
        "home",
        List(&ANGLE, Len::Exactly(2)),
        Default(super::super::DefaultValue::Described("`[0 deg, 0 deg]`")),
        "E1 and E2 at home: the program starts from them (the PTP from home) and ends at them (the PTP back), with the arm at its `home`",
    );
    /// `faceplate = 600 mm`.
    pub static FACEPLATE: Field = Field::new(
        "faceplate",
        Quantity(Dim::LENGTH, Positive),
        Optional,
        "the faceplate's diameter: a disc on E2's flange, its face where the part's base sits, 40 mm thick behind it, which the arm's links keep their gap from (docs/collision.md); none: not checked",
    );
    /// `keep = vertical | cone(…) | fixed(…)`.
    pub static KEEP: Field = Field::new(
        "keep",
        Either(&[Word(&["vertical"]), Call(&[&super::CONE, &super::FIXED])]),
        Default(DefaultWord("vertical")),
        "how each layer's E1 and E2 are chosen: `vertical` turns the layer's mean normal straight up (the nozzle vertical), `cone(15 deg)` turns only when it is further than that from up, `fixed(e1 = …, e2 = …)` stands still",
    );
    /// `cone(angle)`.
    pub static CONE_ANGLE: Field = Field::new(
        "angle",
        Quantity(Dim::ANGLE, ZeroUpTo(crate::sema::schema::deg(90.0))),
        Required("15 deg"),
        "how far from straight up a layer's mean normal may lean before the positioner turns",
    );
    /// `e1`.
    pub static E1: Field = Field::new("e1", ANGLE, Default(DefaultQuantity(0.0)), "E1, the tilt");
    /// `e2`.
    pub static E2: Field = Field::new(
        "e2",
        ANGLE,
        Default(DefaultQuantity(0.0)),
        "E2, the rotation",
    );
}

//! What the collision checks know of the cell (docs/collision.md): a
//! machine's `head { … }` — the solids it carries along the beam — and the
//! `fixture NAME { … }` statements, the clamps on the plate.

use super::Bound::{Any, PositiveUpTo};
use super::DefaultValue::{Described, Quantity as DefaultQuantity};
use super::Kind::{Block as Nested, Call, List, Quantity};
use super::Need::{Default, Optional, Required};
use super::{Block, Field, Len};
use crate::units::Dim;

/// The largest solid or fixture lmdc takes, mm: a cell's, short of a typo's.
pub const MAX_SIZE_MM: f64 = 10_000.0;

const LENGTH_KIND: super::Kind = Quantity(Dim::LENGTH, PositiveUpTo(MAX_SIZE_MM));

/// `head { … }`, either kind of machine.
pub static HEAD_BLOCK: Field = Field::new(
    "head",
    Nested(&HEAD),
    Optional,
    "what the machine carries along the beam — its nozzle and body as solids of revolution, its tip's standoff from the focus — kept `gap` from the plate, the fixtures and the part as it grows (docs/collision.md); none: a typical coaxial nozzle is checked, and `lmd::head-unchecked` says so",
);

/// `head { standoff, nozzle, body, housing, gap }`.
pub static HEAD: Block = Block::new(
    "head",
    "head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm) … }",
    "the solids a machine carries along the beam, from the nozzle's tip up",
    &[&STANDOFF, &NOZZLE, &BODY, &HOUSING, &GAP],
);

/// `standoff = 15 mm`.
pub static STANDOFF: Field = Field::new(
    "standoff",
    LENGTH_KIND,
    Required("15 mm"),
    "the nozzle tip's distance from the laser focus (the tool's TCP), up the beam: with a defocus below the surface the tip comes that much nearer the part",
);

/// `nozzle = frustum(…)`.
pub static NOZZLE: Field = Field::new(
    "nozzle",
    Call(&[&FRUSTUM, &CYLINDER]),
    Required("frustum(length = 45 mm, tip = 12 mm, top = 40 mm)"),
    "the nozzle, from its tip up",
);

/// `body = cylinder(…)`.
pub static BODY: Field = Field::new(
    "body",
    Call(&[&CYLINDER, &FRUSTUM]),
    Optional,
    "what sits on the nozzle: the powder distributor, the optics' tube",
);

/// `housing = cylinder(…)`.
pub static HOUSING: Field = Field::new(
    "housing",
    Call(&[&CYLINDER, &FRUSTUM]),
    Optional,
    "what sits on the body: the optics' housing, the head's mount",
);

/// `gap = 2 mm`.
pub static GAP: Field = Field::new(
    "gap",
    Quantity(Dim::LENGTH, PositiveUpTo(1000.0)),
    Default(DefaultQuantity(2.0)),
    "the least distance the head keeps from the plate, the fixtures and the part laid so far",
);

/// `frustum(length, tip, top)`.
pub static FRUSTUM: Block = Block::new(
    "frustum",
    "frustum(length = 45 mm, tip = 12 mm, top = 40 mm)",
    "a solid tapering along the beam: its length, and its diameters at its lower end (`tip`) and its upper end (`top`)",
    &[&LENGTH, &TIP, &TOP],
);

/// `cylinder(length, diameter)`.
pub static CYLINDER: Block = Block::new(
    "cylinder",
    "cylinder(length = 100 mm, diameter = 60 mm)",
    "a cylinder: along the beam in a head, upright as a fixture",
    &[&LENGTH, &DIAMETER],
);

/// `box(size)`.
pub static BOX: Block = Block::new(
    "box",
    "box(size = [40 mm, 20 mm, 30 mm])",
    "a box, its sides along the part's X, Y and Z",
    &[&SIZE],
);

/// `length = …`.
pub static LENGTH: Field = Field::new(
    "length",
    LENGTH_KIND,
    Required("45 mm"),
    "its length along the beam (a fixture's: its height)",
);

/// `tip = …`.
pub static TIP: Field = Field::new(
    "tip",
    LENGTH_KIND,
    Required("12 mm"),
    "its diameter at its lower end",
);

/// `top = …`.
pub static TOP: Field = Field::new(
    "top",
    LENGTH_KIND,
    Required("40 mm"),
    "its diameter at its upper end",
);

/// `diameter = …`.
pub static DIAMETER: Field = Field::new("diameter", LENGTH_KIND, Required("60 mm"), "its diameter");

/// `size = [x, y, z]`.
pub static SIZE: Field = Field::new(
    "size",
    List(&LENGTH_KIND, Len::Exactly(3)),
    Required("[40 mm, 20 mm, 30 mm]"),
    "its size along X, Y and Z",
);

/// `fixture NAME { shape, at, machine }`.
pub static FIXTURE: Block = Block::new(
    "fixture",
    "fixture clamp { shape = box(size = [40 mm, 20 mm, 30 mm])  at = [60 mm, 0 mm, 0 mm] }",
    "a fixture or clamp on the plate, in the part's coordinates, which every machine's head keeps its gap from; or, with `machine`, fixed to that machine in its own coordinates",
    &[&SHAPE, &AT, &MACHINE, &TURNS_WITH],
);

/// `turns_with = nothing | tilt`.
pub static TURNS_WITH: Field = Field::new(
    "turns_with",
    super::Kind::Word(&["nothing", "tilt"]),
    Default(super::DefaultValue::Word("nothing")),
    "with `machine`, what of the machine it stands on: `nothing`, its base, which no axis turns; `tilt`, the tilt axis's body — a tilting table's cradle or trunnion (turning with A or B, not with C), a positioner's tilting arm (with E1, not E2) — `at` then where it stands with every rotary axis at 0",
);

/// `machine = NAME`.
pub static MACHINE: Field = Field::new(
    "machine",
    super::Kind::Name("machine"),
    Optional,
    "the machine it is fixed to, not turning with the part (a tailstock, a probe, a column): `at` is then in that machine's coordinates — a CNC's with every rotary axis at 0, a robot's own frame (its foot) — and only that machine is checked against it; none: on the plate, in the part's coordinates",
);

/// `shape = box(…) | cylinder(…)`.
pub static SHAPE: Field = Field::new(
    "shape",
    Call(&[&BOX, &CYLINDER, &super::solid::MESH]),
    Required("box(size = [40 mm, 20 mm, 30 mm])"),
    "its shape: a box, an upright cylinder, or a mesh file (`mesh(file = \"clamp.stl\", units = mm, turn = [0 deg, 0 deg, 30 deg])`, its own origin at `at`)",
);

/// `at = [x, y, z]`.
pub static AT: Field = Field::new(
    "at",
    List(&Quantity(Dim::LENGTH, Any), Len::Exactly(3)),
    Default(Described("`[0 mm, 0 mm, 0 mm]`")),
    "the centre of its bottom face (a mesh's: where its file's origin goes), in the part's coordinates (with `machine`, in that machine's)",
);

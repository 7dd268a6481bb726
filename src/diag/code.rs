//! Every diagnostic code lmdc can emit, in one table: its stable text, the
//! group `docs/diagnostics.md` lists it under and what it means there. The
//! documentation's tables are generated from this list (`tests/docs.rs`
//! checks them, `LMDC_UPDATE_DOCS=1 cargo test --test docs` rewrites them).

use std::fmt;

/// The section of `docs/diagnostics.md` a code is listed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Group {
    /// The command line or the files it names, before the .lmd text is read.
    Usage,
    /// The text does not parse.
    Syntax,
    /// Names, units and values of the declarations.
    Values,
    /// Style tables and inheritance.
    Styles,
    /// Whether the part can be built with the bead and process.
    Feasibility,
    /// Whether the plan fits each machine and can be written for it.
    Machines,
    /// Things to look at that do not stop the build.
    Warnings,
}

impl Group {
    /// Every group, in the order of the documentation.
    pub const ALL: [Group; 7] = [
        Group::Usage,
        Group::Syntax,
        Group::Values,
        Group::Styles,
        Group::Feasibility,
        Group::Machines,
        Group::Warnings,
    ];

    /// The heading of the group's section.
    pub fn title(self) -> &'static str {
        match self {
            Group::Usage => "Command line and files",
            Group::Syntax => "Syntax",
            Group::Values => "Names, units and values",
            Group::Styles => "Styles",
            Group::Feasibility => "Feasibility",
            Group::Machines => "Machines",
            Group::Warnings => "Warnings",
        }
    }
}

macro_rules! codes {
    ($($(#[$doc:meta])* $variant:ident = $text:literal, $group:ident, $meaning:literal;)*) => {
        /// A diagnostic's stable code (written `lmd::<text>`).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code {
            $($(#[$doc])* #[doc = $meaning] $variant,)*
        }

        impl Code {
            /// Every code, in the order of the documentation.
            pub const ALL: &'static [Code] = &[$(Code::$variant),*];

            /// The code as users see it, e.g. `lmd::unit-mismatch`.
            pub fn as_str(self) -> &'static str {
                match self {
                    $(Code::$variant => concat!("lmd::", $text),)*
                }
            }

            /// The documentation section the code is listed in.
            pub fn group(self) -> Group {
                match self {
                    $(Code::$variant => Group::$group,)*
                }
            }

            /// What the code means, as `docs/diagnostics.md` says it.
            pub fn meaning(self) -> &'static str {
                match self {
                    $(Code::$variant => $meaning,)*
                }
            }
        }
    };
}

codes! {
    Usage = "usage", Usage,
        "the command line is not one lmdc understands: an unknown command or option, a missing argument, an option value it cannot use (`--message-format xml`, `--density -1`), a command that does not apply to the file (`simulate` without a ring loop); exit status 2";
    Unreadable = "unreadable", Usage,
        "the .lmd file cannot be read: missing, a directory, not UTF-8 text, larger than 16 MB; exit status 2";
    NoSuchMachine = "no-such-machine", Usage,
        "`--machine NAME` names no machine the file declares (the message lists those it does); exit status 2";
    BadSet = "bad-set", Usage,
        "a `--set NAME=VALUE` the file cannot take: no top-level `let NAME`, a value of another kind than the file's (an angle for a length), text that is not one value, a name set twice; exit status 2";
    Output = "output", Usage,
        "the outputs cannot be written: the output directory, a `--templates` folder or template, the disk; exit status 2";
    DeniedWarnings = "denied-warnings", Usage,
        "`--deny-warnings` and the file has warnings: they are reported as usual, this error counts them, nothing is written and the exit status is 1";

    Syntax = "syntax", Syntax,
        "the text does not follow the grammar: an unclosed or mismatched bracket, a statement in the wrong shape (`let` without `=`, a field without a value, …)";
    TooDeep = "too-deep", Syntax,
        "brackets nested more than 64 deep";
    DeepExpression = "deep-expression", Syntax,
        "an expression nests more than 256 operators and brackets into one another (a very long chain of `+`, `..` or `^`, thousands of signs); compute it in steps with `let`";
    Number = "number", Syntax,
        "a number too large to represent";

    Allow = "allow", Values,
        "an `allow \"lmd::CODE\" = \"why\"` that names no warning code or gives no reason";
    UnknownStatement = "unknown-statement", Values,
        "a top-level word that starts no statement (`part let section profile bead loft extrude slicing process style inheritance machine`)";
    UnknownField = "unknown-field", Values,
        "a field the block does not have (with a \"did you mean\")";
    UnknownName = "unknown-name", Values,
        "a section or bead model that is not declared";
    UnknownUnit = "unknown-unit", Values,
        "a unit lmdc does not know";
    Argument = "argument", Values,
        "an argument a shape or model does not take, too many unnamed ones, or none where one is needed (`max()`)";
    DuplicateName = "duplicate-name", Values,
        "a name declared twice: a constant, a section or profile, a bead model, a machine, a style";
    DuplicateField = "duplicate-field", Values,
        "a field given twice in one block, or an argument given twice to one call";
    DuplicateStatement = "duplicate-statement", Values,
        "a statement a file has once given twice: `part`, `slicing`, `process`, `inheritance`";
    SecondSolid = "second-solid", Values,
        "a second `loft` or `extrude`: lmdc builds one solid per file";
    ConflictingFields = "conflicting-fields", Values,
        "two fields that say one thing twice: `layers` (slicing) and `height` (extrude), an extrusion's `height` and `top`, `points` and `chord_error`, a circle's `diameter` and `radius`, a polygon's `circumradius` and `side`; and fields that cannot go together: `layer_change = spiral` with a seam that moves, or on planar layers that are not one loop the same on every layer (more contours, an infill, a hole or an island, a profile that changes)";
    MissingStatement = "missing-statement", Values,
        "a statement the file needs is not there (`part`, `slicing`, `process`); the help shows an example";
    MissingField = "missing-field", Values,
        "a field the block needs is not there (the help shows an example); a style without a `when { … }` block, or an empty `when` block (it would pick every track)";
    MissingSolid = "missing-solid", Values,
        "the file has no `loft` or `extrude` to build";
    MissingMachine = "missing-machine", Values,
        "the file declares no machine to write a program for";
    Cycle = "cycle", Values,
        "constants defined in terms of each other";
    ConstantChain = "constant-chain", Values,
        "constants recomputed for each layer (they follow `layer`) through a chain of more than 128 constants, each using the next, or more than 512 nested steps of constants and operators together (other constants are computed in the order they use each other, however long the chain)";
    UnitMismatch = "unit-mismatch", Values,
        "operands or a field with the wrong kind of unit: a length plus an angle, a power in mm/s";
    ExpectedNumber = "expected-number", Values,
        "a name, text, list or shape where a number with a unit belongs, in a field or as an operand (`+ - * / ^`, a minus sign, `min`/`max`)";
    ExpectedWholeNumber = "expected-whole-number", Values,
        "a count that is not a whole number (`layers`, `contours`, `sides`, `id`, `laser`, …)";
    ExpectedRange = "expected-range", Values,
        "a single value where a range `low .. high` belongs (a bead's `speed` and `height`, `power_range`, a style's `layers`)";
    ExpectedText = "expected-text", Values,
        "a value where a text in quotes belongs (`colour`, `laser_on`, …)";
    ExpectedShape = "expected-shape", Values,
        "a value that is not a shape where one belongs: a section, a profile, a loft's `from`/`to`, a `spine`";
    TargetSolid = "target-solid", Values,
        "a `top = NAME` or `scan(register = NAME)` whose solid cannot be a repair's target or a scan's nominal: the extrusion itself, a `ring` or a `wall`, a bead, section or profile where a solid belongs, or a target that is no part standing on the plate (a `top` or `on` of its own, a profile that follows `layer` or cuts a scan, a `size = centre`, no `height`, a loft bent round its own sections)";
    ExpectedPoint = "expected-point", Values,
        "an outline piece that is not a point `[x, y]` or `arc(…)`, or a point that is not two lengths";
    ExpectedName = "expected-name", Values,
        "a value where the name of a declared bead model belongs (`wall = my_bead`, `bead = my_bead`)";
    Type = "type", Values,
        "a value of the wrong kind in a machine block: a `home` that is not six angles, a `preamble` or `postamble` that is not texts, a `load` that is not `load(…)` or whose `cog` is not three lengths";
    BadChoice = "bad-choice", Values,
        "a word that is not one of the field's choices (`kind = robott`); a `colour` that is not `#rrggbb`, a `paths` that is not `outer_contour`, `inner_contour`, `contour` or `infill`";
    EmptyRange = "empty-range", Values,
        "a range written high to low";
    Degenerate = "degenerate", Values,
        "an outline piece of no length, an arc whose radius is less than half its chord, an outline with fewer than three corners";
    ProfileLayer = "profile-layer", Values,
        "a profile whose numbers use `layer` is not a valid shape on some layer; the error below it says why";
    DivisionByZero = "division-by-zero", Values,
        "arithmetic that divides by zero";
    BadExponent = "bad-exponent", Values,
        "a power whose exponent is not a plain number, or that has no real answer";
    Domain = "domain", Values,
        "a function's value outside its domain: `sqrt` of a negative value, `asin` or `acos` of a number outside -1 .. 1, `tan` of a right angle";
    Overflow = "overflow", Values,
        "arithmetic whose result is too large to represent";
    NotPositive = "not-positive", Values,
        "a value that must be greater than zero is not (a size, a speed, a power, a powder feed, a bead's lowest scan speed), or an `extend` below zero";
    TooLarge = "too-large", Values,
        "a length or speed beyond what lmdc plans (100 m, 100 m/s): usually a wrong unit";
    CountRange = "count-range", Values,
        "a whole number outside its field's range (`sides` 3–1000, `points` 8–100 000, a style's `id` 1–65 535, …); the message gives the range";
    BeadSlope = "bead-slope", Values,
        "a linear bead model whose height does not fall as the scan speed rises (slope ≥ 0), a `power(…)` whose exponent is not negative, or coupons whose fitted line or power law rises with the speed";
    Sheet = "sheet", Values,
        "a measurement sheet (`lmdc fit`, `model = fit(…, data = …)`) lmdc cannot read: a cell that is not a number greater than zero (with its line and column), a row with more cells than the header, a measured row without a speed, a header without a `speed` column";
    Mesh = "mesh", Values,
        "a `mesh(…)` lmdc cannot build: a file that cannot be read or is no STL or 3MF lmdc reads (with where it goes wrong: an STL's line or triangle; a 3MF's build item, object, triangle and vertex index), a 3MF whose `unit` disagrees with `units`, a mesh that is open, non-manifold or has triangles facing both ways (with the triangles' numbers in the file and where), a mesh not standing on the plate, or a layer whose section is empty, does not close, has a hole in no outline, or has loops of two shells that overlap, cross or touch (with the layer, counted from 1, the height of its cut and a point)";
    Scan = "scan", Values,
        "a `scan(…)` lmdc cannot build on: a file that cannot be read or is no PLY, XYZ/CSV, STL or 3MF it reads (with the line, face or point), more points than it reads, a grid of more cells than it keeps (with the `cell` that fits), a mesh with no face seen from above, `on` without `top`, or `fit_tolerance` without `register`; as a warning, a `scan_section(z)` more than 5 % smaller than the section 1 mm lower (a cut through the wear: both areas)";
    SheetUnits = "sheet-units", Values,
        "a measurement sheet's header names a column lmdc reads (`speed`, `height`, `width`, `area`, `mass`, `feed`, `length`, `power`) without its unit in brackets, in a unit lmdc does not convert, or twice";
    TooFewPoints = "too-few-points", Values,
        "a measurement sheet with too few coupons for the model asked (a line or a power law needs two speeds, a mass balance one coupon with area or mass and feed), or without the column it fits";
    CouponsPlate = "coupons-plate", Values,
        "a `calibration` block whose coupons do not fit on its `plate`: the message gives the room they need and the plate's size";
    BeadTable = "bead-table", Values,
        "a bead `table(…)` (or measured data) that is no table: fewer than two speeds, lists of unequal length, speeds that do not increase, or heights that do not fall as the speed rises (names the entries that break it)";
    EfficiencyRange = "efficiency-range", Values,
        "a mass-balance bead model's catch efficiency above 1 (100 %), or one fitted from coupons outside 0–1";
    CornerRadius = "corner-radius", Values,
        "a rounded rectangle's corner radius below zero or above half its shorter side";
    BendAngle = "bend-angle", Values,
        "a spine arc that bends more than 270°: the part would collide with itself";
    PowerSchedule = "power-schedule", Values,
        "the process power, or a power ramp, reaches outside `power_range`";
    NothingDeposited = "nothing-deposited", Values,
        "planar slicing with `contours = 0` and no infill: the layers lay no track";
    OutOfRange = "out-of-range", Values,
        "a value outside what its field allows where no code above says more: a robot's `max_speed` beyond what a KUKA controller takes, `axes = 4`; from the IR checks: points whose height, speed or power leave the bead model's or the machine's range";
    PositionerAxes = "positioner-axes", Values,
        "a robot's positioner whose axes cannot turn a part: a direction of no length, the tilt and rotate axes parallel, limits whose low end is not below the high, or no `base = frame(…)` to put the part on its flange";
    LayerOutsideProfile = "layer-outside-profile", Values,
        "a field, a `section` or an extrusion's `top` uses `layer` or `layer_z`: only a profile is evaluated per layer (a power schedule is `ramp(…)`)";
    PositionOutsideTop = "position-outside-top", Values,
        "`x` or `y` used as a number outside an extrusion's `top`: only the top is a function of the position";
    SpeedFromBead = "speed-from-bead", Values,
        "a process `speed` with `slicing variable`: each segment's speed comes from the bead model (the speed that lays its height)";
    BeadMapNeeded = "bead-map-needed", Values,
        "`slicing variable` with a `measured` bead: variable layers change the height through the speed, which needs a `linear` or `mass_balance` model over a speed range";
    GainUnit = "gain-unit", Values,
        "a height-loop gain (`kp`, `ki`) without a unit, written per second (`Hz`, `s^-1`) or in another unit than a speed per length: (mm/s)/mm and (m/s)/mm are both 1/s but 1000 apart (the paper's \"s⁻¹\" is right only as (m/s)/mm), so a gain names both (`-3 mm/s/mm`, `-0.003 m/s/mm`)";
    TableLength = "table-length", Values,
        "a ring's `table` list, or a plant's `factors`, with another length than the ring has segments";
    Unsupported = "unsupported", Values,
        "a combination lmdc does not build: styles on a loft's wall or on variable-thickness layers, a `top` over a profile that follows `layer`";

    StyleName = "style-name", Styles,
        "a style's name that is not a word of letters, digits and `_` (it goes into the programs' comments)";
    DuplicateId = "duplicate-id", Styles,
        "two styles with one `id`";
    TooManyStyles = "too-many-styles", Styles,
        "more styles than ids 1–65 535";
    StyleSpeed = "style-speed", Styles,
        "a style's speed outside the bead model's speeds, or one at which the bead's height leaves its allowed heights";
    StylePower = "style-power", Styles,
        "a style's power outside the laser's `power_range` (the process power when no range is declared)";
    CornerAngle = "corner-angle", Styles,
        "a `when` block's `corner_angle` that is not more than 0° and at most 180°";
    LayersRange = "layers-range", Styles,
        "a `when` block's `layers` that is not a range of layer numbers counted from 1 (`1 .. 3`)";
    HitRange = "hit-range", Styles,
        "inheritance's `hit` that is not more than 0 % and at most 100 %";

    ScanSpeed = "scan-speed", Feasibility,
        "the process `speed` of planar layers outside the bead model's speeds, or not the speed a measured bead was measured at";
    SectionTooSmall = "section-too-small", Feasibility,
        "a loft's end measured at its outer face (`size = outer`) with nothing left inside half a bead width";
    Extrapolation = "extrapolation", Feasibility,
        "a bead's `speed` range reaching beyond the speeds its model was measured at (a `table(…)`'s): an error naming the measured range, or with `extrapolate = allow` a warning saying how far outside";
    InfeasibleBead = "infeasible-bead", Feasibility,
        "the bead model gives no positive height over its speed range, or its heights miss the declared `height` range";
    RingTooSmall = "ring-too-small", Feasibility,
        "a ring whose `radius` is at most half its widest bead: the wall's inner face would cross the centre";
    BendTooTight = "bend-too-tight", Feasibility,
        "normal slicing of this bend needs layers whose outer/inner height ratio exceeds what the bead model can lay; names the radius, speed range and section size that would work";
    FillGap = "fill-gap", Feasibility,
        "planar tracks further apart than the bead is wide would leave gaps (names the flat-top offset `A/h`); two neighbouring tracks that run parallel farther apart than the bead (names the layer, where, how far apart and the strip left); or a raster fill leaves a spot more than a bead width from every track — a part of the profile narrower than the offset that no line crosses (names the layer, the point and its distance)";
    Overlap = "overlap", Feasibility,
        "planar tracks closer than 30 % of the bead width: the layer would pile up instead of levelling (as a warning: a contour pass that is a sliver, its sides closer than 30 % of the bead width)";
    SelfIntersecting = "self-intersecting", Feasibility,
        "a profile's edges cross on some layer";
    PathBend = "path-bend", Feasibility,
        "a wall along an open path cannot follow it: an arc bends tighter than the wall reaches to its inside, or the wall's face runs into itself (a sharp bend whose inside eats a whole piece, two stretches of the path closer than the wall is wide); names the radius or the place, and what would fit";
    Hole = "hole", Feasibility,
        "a hole of a `region(…)` crosses, touches or lies outside the outline, or crosses, touches or lies inside another hole (on some layer)";
    FillEmpty = "fill-empty", Feasibility,
        "no track fits in a layer's profile (narrower than the bead and its contours)";
    Fill = "fill", Feasibility,
        "the fill of a layer failed for another reason (too many raster lines, non-finite geometry); the message says which";
    NoLayerCount = "no-layer-count", Feasibility,
        "no whole number of layers keeps every height within `h_min..h_max`; for a variable top, names the top's heights, the bead's, and the top or bead map that would work";
    LayerHeight = "layer-height", Feasibility,
        "the declared `layers` gives heights outside `h_min..h_max`; names the counts that work";
    ScanCoverage = "scan-coverage", Feasibility,
        "a repair's footprint reaches where the scan has no point (with the first such place and how many), or its top lies below the scanned surface somewhere in it (with where and by how much): nothing to build on, or nothing to add";
    Finish = "finish", Feasibility,
        "a repair's finished face, as the plan's own bead model predicts it (`lmdc report`'s finish), departing from the top by more than `finish_tolerance` (`slicing variable`, docs/repair.md): names the worst place below or above the top, by how much, and what would hold it; or a plan whose finish cannot be predicted, which no tolerance holds; as a warning, without `finish_tolerance`, a repair on a scan whose face falls short of its top by more than the bead's thinnest layer (the worst place)";
    RepairLevel = "repair-level", Feasibility,
        "a levelled repair's `level` (`slicing variable`, docs/repair.md) lies below the scanned surface by more than a levelling pass may leave (with where, and the level that works), or the top stands less than a regular layer's lowest bead above it";
    ScanRegistration = "scan-registration", Feasibility,
        "a scan's best fit to its nominal (`scan(register = …)`, docs/repair.md) that leaves the points it keeps farther from the nominal than `fit_tolerance` (RMS), keeps fewer than 100 points, does not settle in 50 iterations, or leaves the scan free to slide or turn (a nominal whose faces under the scan do not fix it); names the RMS, the tolerance, the share of the points kept and the move found; as a warning, a fit that turns the scan more than 10° from its declared placement (with the `turn` it found)";
    FollowSurface = "follow-surface", Feasibility,
        "`follow = surface` (`slicing variable`, docs/repair.md) where the nozzle cannot follow the scanned surface: a part not built on a scan, a bead measured with the nozzle vertical only (no `tilt`), or a machine whose nozzle stays vertical (a 3-axis CNC, named)";
    TopHeight = "top-height", Feasibility,
        "an extrusion's `top` is zero, negative or cannot be computed at a point where a track runs (named, with the inner error); or a target mesh or solid overhangs the scan where the layers would fill under it: laid from above (named, with the least tilt that builds it there and `direction = auto`), or along no direction the bead's `tilt` and the machines' tilt axes allow (the line that fails, the tilt needed)";
    SegmentsTooShort = "segments-too-short", Feasibility,
        "meeting the `segments` height tolerance along a track needs constant-speed segments shorter than `min_length`; names the tolerance that works";
    GainSign = "gain-sign", Feasibility,
        "a height-loop gain that is not negative: a layer's height falls as its speed rises (h ∝ 1/v), so a layer that comes out low must slow its segment down";
    UnstableLoop = "unstable-loop", Feasibility,
        "the height loop, linearised at a segment's speed, is unstable (spectral radius ≥ 1): names the worst segment and the gains that are stable at every segment; as a warning, stable at the segments' speeds but not at the clamp's low speed";
    SlowLoop = "slow-loop", Feasibility,
        "the height loop settles in more layers than the build has: an error when less than half of an error is corrected by the last layer (naming the (m/s)/mm reading when 1000 times the gains would do), else a warning with the gains that settle in time";
    TooManyPoints = "too-many-points", Feasibility,
        "the plan would exceed 20 M points (or 100 000 a layer, or 100 000 layers), found before slicing from cheap bounds: for a wall, from its layer count (with the bead height that would fit); for a mesh, from its size (with the size in mm and a `units` in which it would fit)";
    NonFinite = "non-finite", Feasibility,
        "a computed value is not finite: a bug in lmdc, please report it";
    BadDirection = "bad-direction", Feasibility,
        "a computed direction is not a unit vector: a bug in lmdc, please report it";
    Overhang = "overhang", Feasibility,
        "a wall's layer, or a planar layer's outline or hole, leans out over the one below, from the nozzle's axis, by more than the slicing's `max_overhang` (an error), or without one by more than 45° or a step of half the bead (a warning; beyond ¾ bead `lmd::stacking` refuses it); names the angle, the limit and where, and the fixes (the nozzle following the wall, the part turned, `max_overhang`)";
    Stacking = "stacking", Feasibility,
        "a deposit lands more than ¾ of a bead width (across the nozzle) from every bead of the layer below: the layers do not lie on each other (a twist or section that jumps between layers)";
    PointHeight = "point-height", Feasibility,
        "planned points whose layer height leaves the bead model's `h_min..h_max` (counted, the worst named)";
    PointSpeed = "point-speed", Feasibility,
        "planned laser-on points whose scan speed leaves the bead model's speed range";
    PointPower = "point-power", Feasibility,
        "planned laser-on points whose power leaves the laser's `power_range`";
    Deposit = "deposit", Feasibility,
        "the plan's own bead model does not lay the layers it plans: a point's predicted rise (`A/pitch` at its speed) off its layer height by more than `rise_tolerance`, or the layers' error adding up past `max_drift`; says where, how much, after how many layers, and the speed, offset or layer height that would lay it";
    Interpass = "interpass", Feasibility,
        "no cooling `thermal { cooling }` allows keeps a layer within `max_interpass`: names the layer (and, in a layer of several islands, the island and where it starts), its predicted interpass temperature after the most cooling allowed (the longest wait, the least power, the best order of its islands), and what would keep it (a wait, a higher limit, another `cooling`)";

    MachineSpeed = "machine-speed", Machines,
        "the plan moves faster than a machine's `max_speed` (named, with the worst move)";
    Resolution = "resolution", Machines,
        "a power, speed or position a machine's program cannot write within 0.5 % (or at all) at the resolution its settings give (`s_decimals`, `s_per_watt`, `feed_units`, `full_scale`); names the setting to change";
    ProgramText = "program-text", Machines,
        "a text written into a program as it is (`laser_on`, `laser_off`, `tcp_on`, `tcp_off`, `preamble`, `postamble`) that is not one line of printable ASCII, a laser switch that is empty, or a postamble without a program end (`M2`, `M30`)";
    NeedsTilt = "needs-tilt", Machines,
        "the part's layers tilt but the CNC has 3 axes";
    AxisLimit = "axis-limit", Machines,
        "a programmed position or rotary angle is outside the CNC's declared travel";
    SafeHeight = "safe-height", Machines,
        "a CNC's declared `safe_height` lies below where its program goes (the part's highest point plus the clearance): the first move across and the program's end would not clear the part";
    AxisSpeed = "axis-speed", Machines,
        "a feed move whose machine axes would move faster than declared: a tilting table's X Y Z (the part turning under the nozzle) beyond `max_speed`, or a rotary axis beyond `rotary_speed`";
    Collision = "collision", Machines,
        "a body of a machine's head (its nozzle, body, housing) would come within its `gap` of the plate, a fixture or the part as laid so far, at some pose of the plan; names the body, what it meets, where and how close, and what keeps the gap";
    CUnwind = "c-unwind", Machines,
        "a C axis would turn through more than its travel where it cannot unwind: a tilting table's within one layer (lmdc unwinds it only between layers), a tilting head's between two retracts (lmdc unwinds it at every retract, the laser off)";
    NameClash = "name-clash", Machines,
        "two machines whose names differ only in characters a file name drops (`m 1`, `m_1`) would write the same file";
    TransitionSpeed = "transition-speed", Machines,
        "a ring's transition, run at the loop's top speed, moves faster than a machine's `max_speed` (`v / cos γ`, γ its climb); names the clamp, transition angle or `max_speed` that would fit";
    LoopDialect = "loop-dialect", Machines,
        "a height loop to run on a machine whose programs cannot (a G-code dialect other than LinuxCNC, an ABB robot); `run = schedule` writes an open-loop speed schedule instead";
    LoopTiming = "loop-timing", Machines,
        "on a robot, a ring segment's update (a trigger `height_delay` after its end) could land after the advance run has read the values it sets: too few segments or moves between them";
    HeightSensor = "height-sensor", Machines,
        "a height loop to run on a machine that declares no `height_input`, or a LinuxCNC input past `M66 E63` (one input per segment)";
    AnalogRange = "analog-range", Machines,
        "the laser power would need `$ANOUT` outside −1…1 for the robot's `full_scale`";
    OutputClash = "output-clash", Machines,
        "two things a machine switches (laser, gas valve, powder feeder, power or feed-rate analog output) declared on the same output, or on an ABB robot on the same signal";
    SignalName = "signal-name", Machines,
        "an output given a signal's name (`laser = \"doLaserOn\"`) where outputs are numbered (a KUKA robot, a CNC), or a name an ABB robot's program cannot use: not a RAPID name of at most 32 characters, a RAPID reserved word, or one of lmdc's own (`lmd_…`, `main`, `v200`, `fine`)";
    IoDialect = "io-dialect", Machines,
        "gas or powder declared on a CNC whose dialect has no built-in output line (only LinuxCNC's `M64`/`M65`/`M68` are): give `output_on`, `output_off` (and `analog_output`)";
    PowderArrival = "powder-arrival", Machines,
        "the laser would start before the gas has flowed its `pre_flow` or the powder has had its `arrival` time since the feeder started or changed rate";
    DepositBump = "deposit-bump", Machines,
        "where a machine with a declared `acceleration` slows down — a run of deposits starting from rest or stopping, a corner its blending cannot round at speed — the powder keeps flowing and the bead grows as 1/v: over a bead width it rises above its layer by more than `rise_tolerance`; says how many places, the worst, by how much and over what length, and the lead, speed, acceleration or blending that would keep it";
    PowderRate = "powder-rate", Machines,
        "a powder feed the feeder's analog rate output cannot write: beyond its `full_scale`, or changing inside a path where the rate cannot follow; or a style's own powder feed on a machine whose feeder has no rate output (its tracks would get the rate the feeder is set to)";
    Reach = "reach", Machines,
        "a robot's move its declared `arm` cannot reach from where `base` puts the part (or only on the far side of a singularity): says where, how far the wrist centre would have to be from A2 against what the arm reaches (\"at least\" where the part's points were found beyond reach before any pose was solved), and a base, in front of the robot and above its foot, from where the arm reaches the part, or that none can";
    JointLimit = "joint-limit", Machines,
        "a robot's axis (A1–A6) beyond its limit less the `joint_margin` on a move of the plan, or its `home` outside its limits; names the axis, the worst move, by how much, and what would turn it less (the base, the tool's angle)";
    SingularLin = "singular-lin", Machines,
        "a robot's LIN passes within `singularity` of a singular configuration: A5 near 0 (the wrist: A4 and A6 spin), A3 near its stretch angle (the arm straight), or the wrist centre near A1's axis (overhead: A1 spins), as an angle seen from the shoulder; names where and the tool or base change that keeps clear of it";
    ConfigurationFlip = "configuration-flip", Machines,
        "a robot's LIN whose axis solution changes configuration (KUKA's Status: overhead, elbow, wrist flip): the controller stops there; names the move and the bit";
    JointSpeed = "joint-speed", Machines,
        "an axis of a robot's arm would have to turn faster than its top speed to follow a feed move at its path speed (near a singularity a small move turns the wrist far); names the axis, the worst move and the path speed that would keep it within";
    PositionerLimit = "positioner-limit", Machines,
        "a robot's positioner axis (E1 tilt, E2 rotate) would stand outside its declared limits for a layer: the angles `keep` asks for cannot be reached; names the axis, the worst layer and the angle";
    PositionerSpeed = "positioner-speed", Machines,
        "a robot's positioner axis (E1, E2) would have to turn faster than its declared speed on a feed move (layers that join without a travel between them); names the axis and the worst move";

    ArmUnchecked = "arm-unchecked", Warnings,
        "a robot declares an `arm` but its `base` or `tool` is only an index into the controller's table (`base = 1`): lmdc cannot solve the poses, so reach, axis limits and singularities are not checked; says how to declare the value";
    HeadUnchecked = "head-unchecked", Warnings,
        "a machine declares no `head`: its collisions were checked with a typical coaxial nozzle, not its own; says how to declare it";
    LoadUnchecked = "load-unchecked", Warnings,
        "a robot declares no tool `load`: its program sets `$LOAD = LOAD_DATA[n]` (n the tool's number), whatever the controller holds there, which lmdc cannot check; says how to declare the mass and centre of gravity the program then sets";
    ShortMove = "short-move", Warnings,
        "a machine's move shorter than the 0.001 mm its program writes positions at, the nozzle standing as it was: it prints as no move, or as a step of one digit the part does not make; lmdc merges such points of a path, so one that remains is a path of one place or a plan's own move; counts them and names the shortest";
    ShortTrack = "short-track", Warnings,
        "planar tracks shorter than the bead width (they overheat and pile up); counts them and names the first layer";
    LiftMismatch = "lift-mismatch", Warnings,
        "a declared planar `layer_height` more than 2 % from what the tracks lay (A/d overlapped, A/w one track): the standoff drifts by the difference every layer";
    HeightRounded = "height-rounded", Warnings,
        "an extrusion's `height` is not a whole number of layers: it is rounded up, and the warning says to what";
    ThinGap = "thin-gap", Warnings,
        "a raster layer has spots more than ¾ of a bead width from every track centre line (not a bead wide, but a quarter bead unreached); names the farthest";
    FewContours = "few-contours", Warnings,
        "fewer contour passes fit inside the profile than `contours` asks for (named: the first such layer)";
    TallBead = "tall-bead", Warnings,
        "a mass-balance bead model that lays more than a square of its width in cross-section at its slowest speed (a one-bead wall would rise more than its width a layer): no nozzle lays that; a density, feed or efficiency in the wrong unit most often";
    PooledFit = "pooled-fit", Warnings,
        "a `fit(…)` over coupons laid at several powers or powder feeds that one model pooled over them misfits: each group fitted apart explains the coupons better for the numbers it takes (lower AICc); names each group's mean residual and the `power` / `powder` that fits one";
    BeadTilt = "bead-tilt", Warnings,
        "a deposit whose nozzle tilts from vertical more than 5° beyond the tilts its bead was measured at (the bead's `tilt`, vertical unless written): its heights there are not the ones measured";
    PowderMismatch = "powder-mismatch", Warnings,
        "a mass-balance bead model fitted at another powder feed than the process feeds";
    Unused = "unused", Warnings,
        "something that has no effect: `inheritance` without styles, `corner_angle` without `near_corner`, a style's `powder` on a machine whose feeder has no rate output (recorded in the IR, not programmed there), a style that sets no value, a `when` block no track can meet (`shorter_than` ≤ `longer_than`, layers past the last), a style that picks no track on any layer, inheritance with a raster that turns between layers";
    OverlapStretch = "overlap-stretch", Warnings,
        "the balanced spacing of unequal-height tracks had to be stretched (or squeezed) by more than 5 % to land the last track half a bead inside the far edge: the tracks are scanned about that much slower (faster) to fill their strips, and the help names the footprint width that needs no stretch";
    SeamAtBendExtreme = "seam-at-bend-extreme", Warnings,
        "the seam (laser on/off) sits at the innermost or outermost point of the bend, where the layer height is extreme";
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for Code {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl PartialEq<str> for Code {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_kebab_case() {
        let mut seen = std::collections::BTreeSet::new();
        for c in Code::ALL {
            let s = c.as_str();
            assert!(seen.insert(s), "{s} twice");
            let tail = s.strip_prefix("lmd::").unwrap();
            assert!(
                tail.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
                "{s}"
            );
            assert!(!c.meaning().is_empty());
        }
    }
}

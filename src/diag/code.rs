//! Every diagnostic code lmdc can emit, in one table: its stable text, the
//! group `docs/diagnostics.md` lists it under and what it means there. The
//! documentation's tables are generated from this list (`tests/docs.rs`
//! checks them, `LMDC_UPDATE_DOCS=1 cargo test --test docs` rewrites them).

use std::fmt;

/// The section of `docs/diagnostics.md` a code is listed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Group {
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
    pub const ALL: [Group; 6] = [
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
    Syntax = "syntax", Syntax,
        "the text does not follow the grammar: an unclosed or mismatched bracket, a statement in the wrong shape (`let` without `=`, a field without a value, …)";
    TooDeep = "too-deep", Syntax,
        "brackets nested more than 64 deep";
    DeepExpression = "deep-expression", Syntax,
        "an expression nests more than 256 operators and brackets into one another (a very long chain of `+`, `..` or `^`, thousands of signs); compute it in steps with `let`";
    Number = "number", Syntax,
        "a number too large to represent";

    UnknownStatement = "unknown-statement", Values,
        "a top-level word that starts no statement (`part let section profile bead loft extrude slicing process style inheritance machine`)";
    UnknownField = "unknown-field", Values,
        "a field the block does not have (with a \"did you mean\")";
    UnknownName = "unknown-name", Values,
        "a section or bead model that is not declared";
    UnknownUnit = "unknown-unit", Values,
        "a unit lmdc does not know";
    Argument = "argument", Values,
        "an argument a shape or model does not take, or too many unnamed ones";
    Duplicate = "duplicate", Values,
        "something given twice: a field, a constant, a section, a machine, a second solid; two styles with one name or one id";
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
    Type = "type", Values,
        "a value of the wrong kind: a name where a number belongs, a list where a shape belongs";
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
    Overflow = "overflow", Values,
        "arithmetic whose result is too large to represent";
    OutOfRange = "out-of-range", Values,
        "a value outside what the field allows (a negative diameter, an efficiency above 100 %, a power schedule outside `power_range`); a style's speed outside the bead model's speeds, or one where the bead height leaves the allowed heights; a style's power outside `power_range`; `hit` not within 0–100 %; `layers` not a range of layer numbers from 1; from the IR checks: points whose height, speed or power leave the bead model's or the machine's range";
    LayerOutsideProfile = "layer-outside-profile", Values,
        "a field or a `section` uses `layer` or `layer_z`: only a profile is evaluated per layer (a power schedule is `ramp(…)`)";
    Unsupported = "unsupported", Values,
        "a combination lmdc does not build: styles on a loft's wall";

    InfeasibleBead = "infeasible-bead", Feasibility,
        "the bead model gives no positive height over its speed range, or its heights miss the declared `height` range";
    BendTooTight = "bend-too-tight", Feasibility,
        "normal slicing of this bend needs layers whose outer/inner height ratio exceeds what the bead model can lay; names the radius, speed range and section size that would work";
    FillGap = "fill-gap", Feasibility,
        "planar tracks further apart than the bead is wide would leave gaps (names the flat-top offset `A/h`); or a raster fill leaves a spot more than a bead width from every track — a part of the profile narrower than the offset that no line crosses (names the layer, the point and its distance)";
    Overlap = "overlap", Feasibility,
        "planar tracks closer than 30 % of the bead width: the layer would pile up instead of levelling (as a warning: a contour pass that is a sliver, its sides closer than 30 % of the bead width)";
    SelfIntersecting = "self-intersecting", Feasibility,
        "a profile's edges cross on some layer";
    FillEmpty = "fill-empty", Feasibility,
        "no track fits in a layer's profile (narrower than the bead and its contours)";
    Fill = "fill", Feasibility,
        "the fill of a layer failed for another reason (too many raster lines, non-finite geometry); the message says which";
    NoLayerCount = "no-layer-count", Feasibility,
        "no whole number of layers keeps every height within `h_min..h_max`";
    LayerHeight = "layer-height", Feasibility,
        "the declared `layers` gives heights outside `h_min..h_max`; names the counts that work";
    TooManyPoints = "too-many-points", Feasibility,
        "the plan would exceed 20 M points (or 100 000 a layer)";
    NonFinite = "non-finite", Feasibility,
        "a computed value is not finite: a bug in lmdc, please report it";

    NeedsTilt = "needs-tilt", Machines,
        "the part's layers tilt but the CNC has 3 axes";
    AxisLimit = "axis-limit", Machines,
        "a programmed position or rotary angle is outside the CNC's declared travel";
    NameClash = "name-clash", Machines,
        "two machines whose names differ only in characters a file name drops (`m 1`, `m_1`) would write the same file";
    AnalogRange = "analog-range", Machines,
        "the laser power would need `$ANOUT` outside −1…1 for the robot's `full_scale`";

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
    PowderMismatch = "powder-mismatch", Warnings,
        "a mass-balance bead model fitted at another powder feed than the process feeds";
    Unused = "unused", Warnings,
        "something that has no effect: `inheritance` without styles, `corner_angle` without `near_corner`, a style's `powder` (recorded in the IR, not programmed), a style that sets no value, a `when` block no track can meet (`shorter_than` ≤ `longer_than`, layers past the last), a style that picks no track on any layer, inheritance with a raster that turns between layers";
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

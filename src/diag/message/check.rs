//! What the verifier says about a plan: its points' values, the file names
//! machines would write, how the layers stack. What it says about each
//! machine's limits is in [`machine`], about the cell's gas and powder in
//! [`cell`], about a ring's loop in [`ring`].

pub mod cell;
pub mod deposit;
pub mod machine;
pub mod ring;

use crate::diag::{plural, Worst};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;

/// Two machines would write a file of the same name (`file`).
pub fn name_clash(
    first: &str,
    second: &str,
    file: &str,
    first_block: Option<Span>,
    second_block: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::NameClash,
        format!("machines `{first}` and `{second}` would both write {file}"),
    )
    .label_opt(second_block, "second machine")
    .label_opt(first_block, "first machine")
    .help("file names keep letters, digits and `_` of the part's and the machine's names: give the machines names that differ there")
}

/// Points carry a value that is not a finite number (a bug in lmdc).
pub fn non_finite_points(w: &Worst) -> Diagnostic {
    Diagnostic::error(
        Code::NonFinite,
        format!(
            "{} point{} carry a value that is not a finite number (first at {})",
            w.count,
            plural(w.count),
            w.at
        ),
    )
    .help("this is a bug in lmdc's geometry for this input; please report it with the .lmd file")
}

/// Normals or tangents that are not unit vectors (a bug in lmdc).
pub fn bad_directions(w: &Worst) -> Diagnostic {
    Diagnostic::error(
        Code::BadDirection,
        format!(
            "{} direction{} that are not unit vectors: the worst has length {} at {}",
            w.count,
            plural(w.count),
            short(w.value),
            w.at
        ),
    )
    .help("this is a bug in lmdc's geometry; please report it with the .lmd file")
}

/// A quantity every laser-on point must keep within a declared range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointQuantity {
    /// The layer height, within the bead's h_min ..= h_max; how the layers
    /// were made decides what would fix it.
    Height(Layering),
    /// The speed across the nozzle, within the bead model's range.
    Speed,
    /// The power, within the laser's range.
    Power,
}

/// How a plan's layers get their height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layering {
    /// Flat layers lifted by what their tracks lay.
    Planar,
    /// Layers along a bent spine.
    Bent,
    /// Layers following a variable top (H/N each).
    Variable,
}

/// Which end of a range a value passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Below the low end.
    Below,
    /// Above the high end.
    Above,
}

/// Laser-on points whose `q` passes one end of its range; `spans` label first
/// what declared the limit, then what produces the value.
pub fn point_out_of_range(
    q: PointQuantity,
    side: Side,
    w: &Worst,
    spans: &[Option<Span>],
) -> Diagnostic {
    use PointQuantity::*;
    use Side::*;
    let (code, unit) = match q {
        Height(_) => (Code::PointHeight, "mm"),
        Speed => (Code::PointSpeed, "mm/s"),
        Power => (Code::PointPower, "W"),
    };
    let what = match (q, side) {
        (Height(_), Below) => "layer height below h_min",
        (Height(_), Above) => "layer height above h_max",
        (Speed, Below) => "speed (across the nozzle) below the bead model's range",
        (Speed, Above) => "speed (across the nozzle) above the bead model's range",
        (Power, Below) => "power below the laser's range",
        (Power, Above) => "power above the laser's range",
    };
    let help = match (q, side) {
        (Height(Layering::Planar), _) => "a flat layer rises by what its tracks lay (A/w for one track, A/d for tracks d apart): `layer_height = auto` derives it, or declare one within the bead's heights",
        (Height(Layering::Variable), _) => "a variable layer lays H/N where the top is H: `layers = auto` picks the fewest layers that keep it within the bead's heights",
        (Height(Layering::Bent), Below) => "use more layers' worth of height per layer (fewer layers), a larger bend radius, or a bead model that reaches lower heights",
        (Height(Layering::Bent), Above) => "use more layers, a larger bend radius, or a bead model that reaches higher beads",
        (Speed, Below) => "the bead model is not valid this slow: widen its speed range if the process allows",
        (Speed, Above) => "the bead model is not valid this fast: widen its speed range if the process allows",
        (Power, Below) => "raise the power schedule into the laser's range",
        (Power, Above) => "lower the power schedule into the laser's range",
    };
    let mut d = Diagnostic::error(
        code,
        format!(
            "{} point{} with a {what}: the worst is {} {unit} (limit {} {unit}) at {}",
            w.count,
            plural(w.count),
            short(w.value),
            short(w.limit),
            w.at
        ),
    )
    .help(help);
    for (i, s) in spans.iter().enumerate() {
        d = d.label_opt(
            *s,
            if i == 0 {
                "limit declared here"
            } else {
                "this produces it"
            },
        );
    }
    d
}

/// Deposits that land beside the layer below rather than on it; `w.value` is
/// how far across the nozzle the nearest bead lies (`reach` when none was
/// found that near), `half` the limit.
pub fn stacking(
    w: &Worst,
    reach: f64,
    half: f64,
    slicing: Option<Span>,
    spine: Option<Span>,
) -> Diagnostic {
    Diagnostic::error(
        Code::Stacking,
        format!(
            "a deposit lands {} mm across the nozzle from the nearest bead of the layer below, more than ¾ of the bead width ({} mm), at {} ({} place{} so far off, checked at most every eighth of a bead)",
            if w.value >= reach { format!("more than {}", short(reach)) } else { short(w.value) },
            short(half),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label_opt(slicing, "the layers come from here")
    .label_opt(spine, "the part's shape")
    .help(if spine.is_some() {
        // A loft: its shape moves the layers.
        "each layer must lie on the one below: check the twist, the bend and the section sizes for jumps between layers, or use more layers"
    } else {
        // Flat or variable layers: the profile or the fill moves them.
        "each layer must lie on the one below: check a profile that changes with `layer` for jumps, and spots the fill leaves unfilled (they move as the raster turns): more contour passes or a smaller offset close them"
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::Where;

    #[test]
    fn the_stacking_help_names_what_moves_the_layers() {
        let w = Worst {
            count: 1,
            value: 3.0,
            limit: 2.0,
            at: Where::End,
        };
        let at = Some(Span::new(0, 1));
        let help = |spine| stacking(&w, 5.0, 2.0, at, spine).help.unwrap();
        // A loft: its twist, bend and sections.
        assert!(help(at).contains("the twist, the bend"));
        // Flat layers have none of those: their profile and fill.
        let flat = help(None);
        assert!(!flat.contains("twist"), "{flat}");
        assert!(flat.contains("spots the fill leaves unfilled"), "{flat}");
    }
}

//! What the verifier says about a plan: its points' values, the file names
//! machines would write, how the layers stack. What it says about each
//! machine's limits is in [`machine`], about the cell's gas and powder in
//! [`cell`], about a ring's loop in [`ring`].

pub mod arm;
pub mod bump;
pub mod cell;
pub mod deposit;
pub mod height_loop;
pub mod machine;
pub mod table;

use crate::diag::{plural, Worst};
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;
use std::fmt::Display;

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
pub fn non_finite_points(w: &Worst<impl Display>) -> Diagnostic {
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
pub fn bad_directions(w: &Worst<impl Display>) -> Diagnostic {
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
    /// A wall climbing in a spiral (`layer_change = spiral`): its first
    /// layer's climb lays up to two layer heights, rising off the plate.
    Spiral,
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
    w: &Worst<impl Display>,
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
        (Height(Layering::Spiral), Below) => "a spiral wall lays one layer height at every point (on a bent spine, the thin side's): fewer layers, a larger bend radius, a bead model that reaches lower heights, or `layer_change = lift`",
        (Height(Layering::Spiral), Above) => "a spiral wall's first layer climbs off the plate and lays up to two layer heights where its climb ends (more, on a bent spine's thick side): a bead model that reaches twice the layer height, more layers, or `layer_change = lift`, which lays one on every layer",
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

/// The help of a planar contour laid too slow because it is laid as a lone
/// bead (it fills a strip the bead's `width` wide): no raster track lies
/// within a bead of it there; `speed` is what it needs, mm/s.
pub fn lone_contour(d: Diagnostic, width: f64, speed: f64) -> Diagnostic {
    d.help(format!(
        "there the contour is laid as a lone bead (it fills a strip {} mm wide, the bead's width): \
         no raster track lies within a bead of it. This happens where a curved edge (a round \
         hole's or a rounded tongue's crest or flank, a rounded inner corner) runs with the \
         raster lines and the nearest line stops up to an offset short of it. One contour more \
         than the slicing's `contours` usually closes that strip; so does a bead speed range \
         down to {} mm/s, if the process allows",
        short(width),
        // Rounded down: a range down to the printed speed reaches it.
        short((speed * 1e3).floor() / 1e3)
    ))
}

/// What would land the worst deposit of a stacking error on the layer
/// below.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackingFix {
    /// The layer height there, mm.
    pub height: f64,
    /// How far across the nozzle it lands from the layer below, mm, if
    /// found (else farther than the search went).
    pub step: Option<f64>,
    /// The farthest it may land, mm (¾ of the bead width).
    pub half: f64,
    /// A layer count whose thinner layers step little enough and that the
    /// bead lays (a loft's), if there is one.
    pub layers: Option<usize>,
    /// Whether the worst deposit is a raster track's.
    pub raster: bool,
}

/// Deposits that land beside the layer below rather than on it; `w.value` is
/// how far across the nozzle the nearest bead lies (`far` when none was
/// found within the search, `fix.step` `None`), `w.limit` the limit.
pub fn stacking(
    w: &Worst<impl Display>,
    fix: &StackingFix,
    slicing: Option<Span>,
    spine: Option<Span>,
) -> Diagnostic {
    let h = fix.height;
    let deg = |d: f64| (d / h).atan().to_degrees();
    // The lean that passes, printed rounded down so it does pass.
    let lean_max = (deg(fix.half) * 10.0).floor() / 10.0;
    let here = match fix.step {
        Some(d) if h > 0.0 => format!(
            "here the layer steps {} mm out on a {} mm layer, a lean of {}° from the build direction; ",
            short(d),
            short(h),
            short((deg(d) * 10.0).round() / 10.0)
        ),
        _ => String::new(),
    };
    let lands = if h > 0.0 {
        format!(
            "a wall leaning at most {}° at these layers (a step of at most {} mm, contours' chords and raster ends included) lands on the layer below",
            short(lean_max),
            short(fix.half)
        )
    } else {
        "each layer must lie on the one below".to_string()
    };
    let help = if spine.is_some() {
        // A loft: its shape moves the layers, and its count thins them.
        let count = match fix.layers {
            Some(n) => format!("`layers = {n}` (thinner layers, each stepping less) or "),
            None => String::new(),
        };
        format!("{here}{count}{lands}: check the twist, the bend and the section sizes for jumps between layers; a wall that leans all along (a cone) steps by nothing with the nozzle tilted along it (`nozzle = wall` in `slicing normal`, on a robot or a 5-axis head)")
    } else {
        // Flat or variable layers: the profile or the fill moves them.
        let raster = if fix.raster {
            "; a raster track's end steps out faster than the outline where it curves: a contour pass (`contours = 1`) lays the edge"
        } else {
            ""
        };
        format!("{here}{lands}: check a profile that changes with `layer` or `layer_z` for jumps, and spots the fill leaves unfilled (they move as the raster turns){raster}")
    };
    Diagnostic::error(
        Code::Stacking,
        format!(
            "a deposit lands {} mm across the nozzle from the nearest bead of the layer below, more than ¾ of the bead width ({} mm), at {} ({} place{} so far off, checked at most every eighth of a bead)",
            match fix.step {
                Some(d) => short(d),
                None => format!("more than {}", short(w.value)),
            },
            short(w.limit),
            w.at,
            w.count,
            plural(w.count)
        ),
    )
    .label_opt(slicing, "the layers come from here")
    .label_opt(spine, "the part's shape")
    .help(help)
}

/// The worst overhang's numbers: the step across the nozzle to the layer
/// below and the layer's height there.
pub struct OverhangFix {
    /// The step across the nozzle, mm.
    pub step: f64,
    /// The layer's height there, mm.
    pub height: f64,
    /// Whether it is a planar layer's contour (a filled part's outline or
    /// hole), not a wall sliced normal to its spine.
    pub planar: bool,
    /// Whether the limit is the file's `max_overhang` (an error); else the
    /// default's, 45° or a step of half the bead (a warning).
    pub declared: bool,
    /// The bead's width, mm.
    pub bead: f64,
    /// A machine of the file that tilts its nozzle (a robot, a tilting
    /// head), if one does.
    pub tilting: Option<String>,
}

/// A wall's layers lean out over the layer below by more than the declared
/// `max_overhang` (an error) or, without one, by more than 45° or half a
/// bead a layer (a warning); `w.value` is the worst lean (rad), `w.limit`
/// the limit there.
pub fn overhang(w: &Worst<impl Display>, fix: &OverhangFix, slicing: Option<Span>) -> Diagnostic {
    let deg = |a: f64| short((a.to_degrees() * 10.0).round() / 10.0);
    let what = if fix.planar {
        "the part's outline"
    } else {
        "the wall"
    };
    // The lean that passes, rounded up so that it does.
    let accept = (w.value.to_degrees()).ceil();
    let allow = if fix.declared {
        "or allow more, if the bead carries it (`max_overhang`; more, thinner layers do not change a lean)".to_string()
    } else {
        format!("or, if the bead carries it, say how far a layer may lean: `max_overhang = {accept} deg` in the slicing accepts this lean and makes any layer leaning farther an error (more, thinner layers do not change a lean)")
    };
    let tilt = match &fix.tilting {
        Some(m) => format!("`{m}` tilts"),
        None => "on a robot or a 5-axis head; none of this file's machines tilts".to_string(),
    };
    let help = if fix.planar {
        format!("turn the part (`turn` of its mesh) so the outline leans less over the layer below; build it on a machine that tilts and slice it as a wall (`slicing normal`, `nozzle = wall`); {allow}")
    } else {
        format!("tilt the nozzle with the wall (`nozzle = wall` in `slicing normal`; {tilt}); turn the part so the wall leans less; {allow}")
    };
    let head = format!(
        "{what} leans out {}° from the nozzle's axis over the layer below (a step of {} mm on a {} mm layer)",
        deg(w.value),
        short(fix.step),
        short(fix.height),
    );
    let count = format!("{} place{} so far over", w.count, plural(w.count));
    let d = if fix.declared {
        Diagnostic::error(
            Code::Overhang,
            format!(
                "{head}, more than the {}° `max_overhang` allows, at {} ({count})",
                deg(w.limit),
                w.at
            ),
        )
    } else {
        Diagnostic::warning(
            Code::Overhang,
            format!(
                "{head}, more than the {}° a layer may lean without `max_overhang` (45°, or a step of half the {} mm bead), at {} ({count})",
                deg(w.limit),
                short(fix.bead),
                w.at
            ),
        )
    };
    d.label_opt(slicing, "the layers come from here").help(help)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stacking_help_names_what_moves_the_layers() {
        let w = Worst {
            count: 1,
            value: 3.0,
            limit: 2.0,
            at: "the retract after the last path",
        };
        let at = Some(Span::new(0, 1));
        let fix = StackingFix {
            height: 1.0,
            step: Some(3.0),
            half: 2.0,
            layers: Some(7),
            raster: true,
        };
        let help = |spine| stacking(&w, &fix, at, spine).help.unwrap();
        // A loft: its twist, bend and sections, and a count.
        let loft = help(at);
        assert!(loft.contains("the twist, the bend"), "{loft}");
        assert!(loft.contains("`layers = 7`"), "{loft}");
        // atan(3) = 71.57°; atan(2) = 63.43°, printed down.
        assert!(loft.contains("a lean of 71.6°"), "{loft}");
        assert!(loft.contains("at most 63.4°"), "{loft}");
        // Flat layers have none of those: their profile and fill.
        let flat = help(None);
        assert!(!flat.contains("twist"), "{flat}");
        assert!(flat.contains("spots the fill leaves unfilled"), "{flat}");
        assert!(flat.contains("`contours = 1`"), "{flat}");
    }
}

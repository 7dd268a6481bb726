//! What lmdc says about a scan a repair is built on (`on = scan(…)`,
//! docs/repair.md): a file it cannot read, a grid too fine, a footprint
//! the scan does not cover, a top below the scanned surface, a best fit to
//! its nominal refused.

use crate::diag::{Code, Diagnostic};
use crate::geometry::mesh::SectionFault;
use crate::geometry::scan::section::{CutFault, MAX_LOOPS};
use crate::geometry::scan::{FitFault, Freedom, GridFault, ScanError, MAX_CELLS};
use crate::geometry::target::TurnedFrame;
use crate::span::Span;
use crate::units::short;

fn p2(p: [f64; 2]) -> String {
    format!("({}, {}) mm", short(p[0]), short(p[1]))
}

/// " and at N other points", or nothing.
fn others(more: usize) -> String {
    match more {
        0 => String::new(),
        1 => " and at 1 other point".to_string(),
        n => format!(" and at {n} other points"),
    }
}

/// The scan file `path` cannot be read (`why`).
pub fn unreadable(path: &str, why: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Scan, format!("cannot read the scan `{path}`: {why}"))
        .label(at, "this file")
        .help("the path is relative to the folder of the .lmd file")
}

/// A program names a scan where no file can be read.
pub fn no_reader(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        "this program is compiled from a text, not a file: there is no folder to read the scan from",
    )
    .label(at, "scan file")
    .help("compile the .lmd file (`lmdc build FILE.lmd`)")
}

/// The scan `path` is no file of its format lmdc reads.
pub fn bad(path: &str, format: &str, e: &ScanError, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        format!("cannot read the scan `{path}` as {format}: {e}"),
    )
    .label(at, "this file")
    .help("export the scan as PLY (ASCII or binary, points or faces), as text with a point `x y z` a line, or as STL or 3MF")
}

/// The scan's grid cannot be built.
pub fn grid(path: &str, fault: &GridFault, cell: f64, at: Span) -> Diagnostic {
    match fault {
        GridFault::TooManyCells { cells, cell: fits } => Diagnostic::error(
            Code::Scan,
            format!(
                "the scan `{path}` spans {cells} cells of {} mm, more than the {MAX_CELLS} lmdc keeps",
                short(cell)
            ),
        )
        .label(at, "this scan")
        .help(format!(
            "a coarser grid fits (`cell = {} mm`), or crop the scan to the part (is it in the `units` it says?)",
            short(*fits)
        )),
        GridFault::NoSurface => Diagnostic::error(
            Code::Scan,
            format!("the scan `{path}` has no face seen from above: every face stands upright"),
        )
        .label(at, "this scan")
        .help("turn the scan so that its surface faces up (`turn = [90 deg, 0 deg, 0 deg]` for a scan whose up is its y)"),
    }
}

/// `on = scan(…)` on an extrusion without `top`.
pub fn needs_top(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        "`on = scan(…)` needs a `top`: a repair is built up to a finished surface, in layers that follow the scan (`slicing variable`)",
    )
    .label(at, "built on a scan")
    .help("write `top = 25 mm` (the finished surface's height above the part's z = 0), or a `plane(…)` or expression of `x` and `y`")
}

/// The footprint reaches `at_point` where the scan has no point.
pub fn uncovered(
    at_point: [f64; 2],
    more: usize,
    surface: &crate::geometry::scan::HeightField,
    at: Span,
    scan: Span,
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let others = others(more);
    let extent = surface.extent();
    let inside = (0..2).all(|k| (extent.0[k]..=extent.1[k]).contains(&at_point[k]));
    // Turned, the extent is the turned scan's: no place in the part.
    let help = match (turned, surface.sparse()) {
        (None, Some((share, spacing))) if inside => {
            let span = format!(
                "the scan spans x {} .. {} mm, y {} .. {} mm",
                short(extent.0[0]),
                short(extent.1[0]),
                short(extent.0[1]),
                short(extent.1[1])
            );
            let cell = short((spacing * 1.5 * 10.0).ceil() / 10.0);
            // Points far apart against the cell: more likely read in the
            // wrong units than scanned that coarsely.
            let fix = if spacing > 4.0 * surface.cell() {
                format!("check its `units` first: {span}, is that the part's size? If it is, take a `cell` of at least {cell} mm in `scan(…)`")
            } else {
                format!("take a `cell` of at least {cell} mm in `scan(…)`, or check its `units` ({span})")
            };
            format!(
                "the scan's points fill only {} % of its {} mm cells: they lie about {} mm apart, so most cells hold none: {fix}",
                short(share * 100.0),
                short(surface.cell()),
                short(spacing),
            )
        }
        (Some(_), _) => "scan the part there too, or keep the footprint within what the scan covers seen along the build direction (what a steep flank hides from its side is not covered); a coarser `cell` bridges small gaps".to_string(),
        (None, _) => format!(
            "scan the part there too, or keep the footprint within what the scan covers (it spans x {} .. {} mm, y {} .. {} mm, with gaps where it has no point); a coarser `cell` bridges small gaps",
            short(extent.0[0]),
            short(extent.1[0]),
            short(extent.0[1]),
            short(extent.1[1])
        ),
    };
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the scan has no point under {}{others} where a track runs: there is nothing measured to build on",
            super::top::spot(turned, at_point)
        ),
    )
    .label(at, "the footprint")
    .label(scan, "the scan")
    .help(help)
}

/// The top lies `by` mm below (or on) the scanned surface at `at_point`.
pub fn top_below(
    at_point: [f64; 2],
    top: f64,
    surface: f64,
    more: usize,
    [at, scan]: [Span; 2],
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    use super::top::{height, spot};
    let others = others(more);
    let help = match turned {
        Some(_) => "raise the target above the scanned surface there along the build direction, or keep the footprint to where the part is worn below it".to_string(),
        None => format!(
            "raise the top above {} mm there, or keep the footprint to where the part is worn below the top",
            short(surface)
        ),
    };
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the top ({}) is not above the scanned surface ({}) at {}{others} where a track runs: there is nothing to add there",
            height(turned, at_point, top),
            height(turned, at_point, surface),
            spot(turned, at_point)
        ),
    )
    .label(at, "the top")
    .label(scan, "the scan")
    .help(help)
}

/// `level = …` on a variable slicing whose part is not built on a scan.
pub fn level_without_scan(at: Span, solid: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        "`level` levels a scanned part's wear before the regular layers, and this part is not built on a scan",
    )
    .label(at, "levelling")
    .label(solid, "built on the plate")
    .help("build on the scan with `on = scan(file = …)` in the extrusion, or leave `level` out")
}

/// The scan rises above the level by more than a levelling pass may leave
/// (`slack`) at `at_point`.
///
/// Planned `turned` (along a tilted build direction), the point is the
/// part's on the scan and the heights are along the direction.
pub fn above_level(
    at_point: [f64; 2],
    surface: f64,
    level: f64,
    slack: f64,
    [at, scan]: [Span; 2],
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let place = match turned {
        None => p2(at_point),
        Some(_) => super::top::height(turned, at_point, surface),
    };
    Diagnostic::error(
        Code::RepairLevel,
        format!(
            "the scanned surface at {place} is at {} mm, {} mm above the level {} mm: the regular layers would run into the part there",
            short(surface),
            short(surface - level),
            short(level),
        ),
    )
    .label(at, "the level")
    .label(scan, "the scan")
    .help(format!(
        "raise the level to at least {} mm (the scan may stand at most {} mm, half the lowest bead, above it), or write `level = auto` (the scan's highest point under the tracks)",
        short(surface - slack),
        short(slack)
    ))
}

/// The top is `gap` mm above the level at `at_point`, less than one
/// regular layer of `h_min`.
///
/// Planned `turned`, the point is the part's on the top and the heights
/// are along the build direction.
pub fn top_near_level(
    at_point: [f64; 2],
    top: f64,
    level: f64,
    h_min: f64,
    at: Span,
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let place = match turned {
        None => p2(at_point),
        Some(_) => super::top::height(turned, at_point, top),
    };
    Diagnostic::error(
        Code::RepairLevel,
        format!(
            "the top ({} mm) at {place} is {} mm above the level {} mm: a regular layer lays at least {} mm",
            short(top),
            short(top - level),
            short(level),
            short(h_min)
        ),
    )
    .label(at, "the level")
    .help(format!(
        "lower the level to {} mm or below, or raise the top; `level = none` lays every layer as a fraction of the top less the scan",
        short(top - h_min)
    ))
}

/// `(x, y, z)` rounded for people.
fn p3(p: [f64; 3]) -> String {
    format!("({}, {}, {})", short(p[0]), short(p[1]), short(p[2]))
}

/// A direction: an axis's name when it lies along one, else its numbers.
fn direction(d: [f64; 3]) -> String {
    let axis = (0..3).find(|&k| d[k].abs() > 0.995);
    match axis {
        Some(k) => ["x", "y", "z"][k].to_string(),
        None => format!("({:.2}, {:.2}, {:.2})", d[0], d[1], d[2]),
    }
}

/// What the scan `scan` and its nominal `nominal` are called in a message.
pub struct Registering<'a> {
    /// The scan's file.
    pub scan: &'a str,
    /// The nominal's file.
    pub nominal: &'a str,
    /// `scan(…)`.
    pub at: Span,
    /// `register = mesh(…)`.
    pub register: Span,
}

/// A best fit that turned the scan `turned`° from its declared placement,
/// to the whole `turn` (deg, about x, y, z).
pub fn fit_turned_far(n: &Registering<'_>, turned: f64, turn: [f64; 3]) -> Diagnostic {
    let t = turn.map(short);
    Diagnostic::warning(
        Code::ScanRegistration,
        format!(
            "the best fit turned the scan `{}` {}° from its declared placement onto `{}`: more than a placement is usually off, and a part that looks alike turned (a symmetric pad, a blade's two sides) may have been fitted the wrong way round",
            n.scan,
            short(turned),
            n.nominal
        ),
    )
    .label(n.at, "the scan")
    .label(n.register, "the nominal")
    .help(format!(
        "check the plan's place against the part; declare the turn the fit found, `turn = [{}, {}, {}] deg`, if it is right, or the right one nearer the part's if not",
        t[0], t[1], t[2]
    ))
}

/// What every refused fit's help says the fit needs.
const FIT_NEEDS: &str = "the best fit starts from the scan's `turn` and `at` and finds the nominal only from within a few mm and degrees of it: place the scan nearer";

/// The best fit leaves an RMS of `fit.rms` over `tolerance`.
pub fn fit_too_loose(
    r: &Registering<'_>,
    fit: &crate::ir::Registration,
    tolerance_at: Option<Span>,
) -> Diagnostic {
    let d = Diagnostic::error(
        Code::ScanRegistration,
        format!(
            "the scan `{}` fits its nominal `{}` to {} mm RMS, more than the `fit_tolerance` of {} mm (the best fit keeps {:.1} % of its points, moved {} mm and turned {}° after the declared placement)",
            r.scan,
            r.nominal,
            short(fit.rms),
            short(fit.tolerance),
            fit.inliers * 100.0,
            p3(fit.moved),
            p3(fit.turned)
        ),
    )
    .label(r.at, "this scan")
    .label(r.register, "the nominal");
    let d = match tolerance_at {
        Some(t) => d.label(t, "the tolerance"),
        None => d,
    };
    d.help(format!(
        "{FIT_NEEDS}; or the nominal is not this part, or not in the part's coordinates; or, if the part differs from its nominal this much where it is not worn, raise `fit_tolerance` (to {} mm)",
        crate::units::short_up(fit.rms)
    ))
}

/// The best fit cannot be made (`fault`).
pub fn fit_refused(r: &Registering<'_>, fault: &FitFault) -> Diagnostic {
    let (message, help) = match fault {
        FitFault::NoNominal => (
            format!("the nominal `{}` has no triangle with an area", r.nominal),
            "export the part as designed as a mesh of its faces (STL or 3MF)".to_string(),
        ),
        FitFault::NoneNear => (
            format!(
                "no face of the nominal `{}` lies near the scan `{}` as placed: the fit looks within half the scan's size round it (at least {} mm)",
                r.nominal,
                r.scan,
                short(crate::geometry::scan::register::NEAR_LEAST)
            ),
            "place the scan near the part as designed with `turn` and `at` (the fit starts there), or check that the nominal is in the part's coordinates".to_string(),
        ),
        FitFault::TooFewInliers {
            inliers,
            points,
            limit,
        } => (
            format!(
                "the best fit of the scan `{}` to its nominal `{}` keeps only {inliers} of its {points} points (within {} mm of the nominal): too few to place it",
                r.scan,
                r.nominal,
                short(*limit)
            ),
            format!("{FIT_NEEDS}; or the scan holds too few points, or the nominal is not this part"),
        ),
        FitFault::NotSettled { iterations, step } => (
            format!(
                "the best fit of the scan `{}` to its nominal `{}` does not settle: after {iterations} iterations it still moves points by {} mm",
                r.scan,
                r.nominal,
                short(*step)
            ),
            format!("{FIT_NEEDS}; or the nominal is not this part"),
        ),
        FitFault::Undetermined { free, .. } => (
            format!(
                "the nominal `{}` does not fix where the scan `{}` goes: under the points the fit keeps, its faces leave the scan free to {}",
                r.nominal,
                r.scan,
                freedoms(free)
            ),
            "scan more of the part than a face that fixes only some of its place (a flat face fixes its height and tilt, not where along it): its sides, an edge, a hole; or leave `register` out and place the scan by `turn` and `at`".to_string(),
        ),
    };
    Diagnostic::error(
        match fault {
            FitFault::NoNominal => Code::Scan,
            _ => Code::ScanRegistration,
        },
        message,
    )
    .label(r.at, "this scan")
    .label(r.register, "the nominal")
    .help(help)
}

/// "slide along x and y and turn about z".
fn freedoms(free: &[Freedom]) -> String {
    let mut slides = Vec::new();
    let mut turns = Vec::new();
    for f in free {
        match f {
            Freedom::Slide(d) => slides.push(direction(*d)),
            Freedom::Turn(d) => turns.push(direction(*d)),
        }
    }
    let and = |v: &[String]| match v {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    };
    match (slides.is_empty(), turns.is_empty()) {
        (false, false) => format!(
            "slide along {} and turn about {}",
            and(&slides),
            and(&turns)
        ),
        (false, true) => format!("slide along {}", and(&slides)),
        (true, false) => format!("turn about {}", and(&turns)),
        (true, true) => "move".to_string(),
    }
}

/// `fit_tolerance` without `register`: nothing to fit to.
pub fn tolerance_without_nominal(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        "`fit_tolerance` bounds a best fit to a nominal, and this scan has none (`register`)",
    )
    .label(at, "a tolerance for no fit")
    .help("add `register = mesh(file = \"nominal.stl\")` or `register = NAME` (an `extrude` or `loft` of the file: the part as designed), or leave `fit_tolerance` out")
}

/// `profile = scan_section(…)` on an extrusion without `on = scan(…)`.
pub fn section_without_scan(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Scan,
        "`scan_section(…)` is the section of the part scanned in `on = scan(…)`, and this extrusion is built on no scan",
    )
    .label(at, "a section of which scan?")
    .help("add `on = scan(file = \"part.ply\")` (a scan with faces), or draw the profile")
}

/// The section of the scan `path` at `z` is no profile.
pub fn section(path: &str, z: f64, fault: &CutFault, at: Span, scan: Span) -> Diagnostic {
    let z = short(z);
    let (what, help) = match fault {
        CutFault::NoFaces => (
            format!("the scan `{path}` has points only, and a section is cut through faces"),
            "mesh the scan (the scanner's software, or Open3D's or MeshLab's surface reconstruction) and export it as PLY with faces, STL or 3MF; or draw the profile".to_string(),
        ),
        CutFault::Empty { span: Some([lo, hi]) } => (
            format!(
                "the scan `{path}` has nothing to cut at z = {z} mm: its faces reach from z = {} to {} mm",
                short(*lo),
                short(*hi)
            ),
            "cut it where the scan shows the part whole, below the worn or missing part".to_string(),
        ),
        CutFault::Empty { span: None } => (
            format!("the scan `{path}` has no faces with an area to cut at z = {z} mm"),
            "check the scan's faces and `units`".to_string(),
        ),
        CutFault::Open { at } => (
            format!(
                "the scan `{path}`'s faces do not close round the part at z = {z} mm: the cut runs out at {}",
                p2(*at)
            ),
            "the scan has a hole there (a shadow, a reflection): cut a little higher or lower, or fill the hole in the scan".to_string(),
        ),
        CutFault::TooMany { loops } => (
            format!("the scan `{path}`'s section at z = {z} mm falls into {loops} loops"),
            format!("at most {MAX_LOOPS} are taken for a part; a scan this broken needs cleaning first"),
        ),
        CutFault::Islands(f) => (
            format!("the scan `{path}`'s section at z = {z} mm is no region: {}", islands(f)),
            "the scan has faces crossing there (two overlapping passes?): clean it or cut at another height".to_string(),
        ),
    };
    Diagnostic::error(Code::Scan, what)
        .label(at, "this section")
        .label(scan, "this scan")
        .help(help)
}

/// The section at `z` is much smaller than the one `below` mm lower
/// (`[here, there]` mm²): the cut may pass through the wear.
pub fn section_worn(
    path: &str,
    z: f64,
    [here, there]: [f64; 2],
    below: f64,
    scan: Span,
) -> Diagnostic {
    Diagnostic::warning(
        Code::Scan,
        format!(
            "the section of `{path}` at z = {} mm is {} % smaller than {} mm lower ({} against {} mm²): the cut may pass through the worn part, and the footprint leave out what wore away",
            short(z),
            short((1.0 - here / there) * 100.0),
            short(below),
            short(here),
            short(there)
        ),
    )
    .label(scan, "this scan")
    .help("cut where the part is whole, below the wear (a lower `scan_section(z = …)`); a part that narrows this fast upward by design may stay as it is")
}

fn islands(f: &SectionFault) -> String {
    match f {
        SectionFault::Empty => "it is empty".to_string(),
        SectionFault::Open { at, .. } => format!("a chain ends at {}", p2(*at)),
        SectionFault::StrayHole { at } => format!("a hole at {} lies in no outline", p2(*at)),
        SectionFault::Overlap { at } => format!("two loops meet at {}", p2(*at)),
    }
}

/// `follow = surface` on a part built on the plate: there is no scanned
/// surface to follow.
pub fn follow_without_scan(at: Span, solid: Span) -> Diagnostic {
    Diagnostic::error(
        Code::FollowSurface,
        "`follow = surface` tilts the nozzle to a scanned part's surface, and this part is not built on a scan",
    )
    .label(at, "the nozzle along the scan's normal")
    .label(solid, "built on the plate")
    .help("build on the scan with `on = scan(file = …)` in the extrusion, or leave `follow` out (the nozzle vertical)")
}

/// `follow = surface` with a bead measured with the nozzle vertical only.
pub fn follow_untilted_bead(bead: &str, at: Span, bead_at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::FollowSurface,
        format!(
            "`follow = surface` tilts the nozzle to the scanned surface's normal, but bead `{bead}` was measured with the nozzle vertical only (it has no `tilt`): a tilted melt pool runs downhill, and the heights it lays at each speed are not the ones measured"
        ),
    )
    .label(at, "the nozzle along the scan's normal")
    .label(bead_at, "measured vertical")
    .help(format!(
        "lay the bead's coupons with the nozzle tilted too and write the tilts they cover in bead `{bead}`, e.g. `tilt = 0 deg .. 20 deg`: the nozzle then follows the surface up to the upper one; or leave `follow` out"
    ))
}

/// `follow = surface` and a machine whose nozzle stays vertical.
pub fn follow_on_vertical_machine(machine: &str, at: Span, axes: Span) -> Diagnostic {
    Diagnostic::error(
        Code::FollowSurface,
        format!(
            "`follow = surface` tilts the nozzle to the scanned surface's normal, but machine `{machine}` moves X Y Z only and keeps the nozzle vertical"
        ),
    )
    .label(at, "the nozzle along the scan's normal")
    .label(axes, "no tilting axis")
    .help(format!(
        "build it on a machine that tilts the nozzle or the part (a 5-axis CNC: `axes = 5` with `kinematics = head_ac`, `head_bc`, `table_ac` or `table_bc`; a robot), take machine `{machine}` out of this file, or leave `follow` out (the nozzle vertical on every machine)"
    ))
}

/// Where a levelling pass followed along the scan's normal cannot be laid:
/// the place, the scan's height there, the slope along the tracks (rad),
/// and the bead's lowest and highest heights over the track's strip (mm).
pub struct SteepPass {
    /// The place, in the frame the layers are planned in.
    pub at: [f64; 2],
    /// The scan's height there.
    pub surface: f64,
    /// The first pass's slope along the tracks, rad.
    pub alpha: f64,
    /// The bead's lowest height over the strip, mm.
    pub lo: f64,
    /// Its highest, mm.
    pub hi: f64,
    /// Whether the tracks' direction is the slicing's to choose (`scan`):
    /// an extrusion's, not a wall's (its tracks follow its path).
    pub turnable: bool,
}

/// `level = …` with `follow = surface`: where the first pass's surface
/// slopes `α` along the tracks, a pass laid along its normal is at least
/// `lo / cos α` thick (vertically), more than the `hi` the bead lays.
///
/// Planned `turned`, the point is the part's on the scan and the heights
/// are along the build direction.
pub fn level_follow_too_steep(
    s: SteepPass,
    [follow, bead]: [Span; 2],
    turned: Option<&TurnedFrame>,
) -> Diagnostic {
    let place = match turned {
        None => p2(s.at),
        Some(_) => super::top::height(turned, s.at, s.surface),
    };
    let deg = s.alpha.to_degrees();
    // The tilt along the tracks at which the thinnest pass is the tallest.
    let most = (s.lo / s.hi).clamp(-1.0, 1.0).acos().to_degrees();
    Diagnostic::error(
        Code::FollowSurface,
        format!(
            "the levelling passes cannot be laid along the scan's normal at {place}: the scan slopes {}° along the tracks there, and a bead laid along the normal is at least {} mm thick along it, so the thinnest pass is {} mm high ({} mm / cos {}°), more than the {} mm the bead lays at most",
            short(deg),
            short(s.lo),
            short(s.lo / s.alpha.cos()),
            short(s.lo),
            short(deg),
            short(s.hi)
        ),
    )
    .label(follow, "the nozzle along the scan's normal")
    .label(bead, "the bead")
    .help(format!(
        "let the nozzle tilt at most {}° (the upper end of the bead's `tilt`, or the machine's tilt axis), {}give a bead measured over a wider range of heights, or leave `follow` out to level with the nozzle vertical",
        short(most.floor().max(0.0)),
        if s.turnable { "lay the tracks across the slope (`scan`), " } else { "" }
    ))
}

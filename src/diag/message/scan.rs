//! What lmdc says about a scan a repair is built on (`on = scan(…)`,
//! docs/repair.md): a file it cannot read, a grid too fine, a footprint
//! the scan does not cover, a top below the scanned surface.

use crate::diag::{Code, Diagnostic};
use crate::geometry::scan::{GridFault, ScanError, MAX_CELLS};
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
    extent: ([f64; 2], [f64; 2]),
    at: Span,
    scan: Span,
) -> Diagnostic {
    let others = others(more);
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the scan has no point under {}{others} where a track runs: there is nothing measured to build on",
            p2(at_point)
        ),
    )
    .label(at, "the footprint")
    .label(scan, "the scan")
    .help(format!(
        "scan the part there too, or keep the footprint within what the scan covers (it spans x {} .. {} mm, y {} .. {} mm, with gaps where it has no point); a coarser `cell` bridges small gaps",
        short(extent.0[0]),
        short(extent.1[0]),
        short(extent.0[1]),
        short(extent.1[1])
    ))
}

/// The top lies `by` mm below (or on) the scanned surface at `at_point`.
pub fn top_below(
    at_point: [f64; 2],
    top: f64,
    surface: f64,
    more: usize,
    at: Span,
    scan: Span,
) -> Diagnostic {
    let others = others(more);
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the top ({} mm) is not above the scanned surface ({} mm) at {}{others} where a track runs: there is nothing to add there",
            short(top),
            short(surface),
            p2(at_point)
        ),
    )
    .label(at, "the top")
    .label(scan, "the scan")
    .help(format!(
        "raise the top above {} mm there, or keep the footprint to where the part is worn below the top",
        short(surface)
    ))
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
pub fn above_level(
    at_point: [f64; 2],
    surface: f64,
    level: f64,
    slack: f64,
    at: Span,
    scan: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the scanned surface at {} is at {} mm, {} mm above the level {} mm: the regular layers would run into the part there",
            p2(at_point),
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
pub fn top_near_level(
    at_point: [f64; 2],
    top: f64,
    level: f64,
    h_min: f64,
    at: Span,
) -> Diagnostic {
    Diagnostic::error(
        Code::ScanCoverage,
        format!(
            "the top ({} mm) at {} is {} mm above the level {} mm: a regular layer lays at least {} mm",
            short(top),
            p2(at_point),
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

//! `top = NAME`: a repair's target given as a solid of the file
//! (docs/repair.md, *A target solid*), and the names and solids that
//! cannot be one.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;

/// What a target solid needs, said once for every refusal.
const WHAT_WORKS: &str = "a target is the part as designed, standing on the plate: an `extrude` of a shape up to a `height`, an `extrude` of a `mesh(…)`, or a `loft`; it is not built";

/// Why a solid of the file cannot be a target.
#[derive(Clone, Copy, Debug)]
pub enum Fault<'a> {
    /// `top` names the extrusion it is written in.
    Itself,
    /// A solid of a kind that cannot be one (`ring`, `wall`).
    Kind(&'a str),
    /// The target has a field that builds on something else (`top`, `on`).
    Field(&'a str),
    /// Its profile follows `layer`: there are no layers to follow.
    FollowsLayer,
    /// Its profile is a section of a scan: it has none.
    ScanSection,
    /// Its sizes are the tracks' centre line (`size = centre`).
    Centre,
    /// An extrusion of a shape without a `height`.
    NoHeight,
    /// An extrusion of a mesh with a `height`: the mesh is the target.
    MeshHeight,
    /// A loft whose sections reach the bend's axis: the bend's radius and
    /// the sections' reach, mm.
    Tight(f64, f64),
}

/// `top = NAME` naming the solid `name` (declared at `decl`, or the field
/// refused there), which cannot be a target, for `fault`.
pub fn cannot(name: &str, fault: Fault<'_>, at: Span, decl: Span) -> Diagnostic {
    let (message, help) = match fault {
        Fault::Itself => (
            format!("`top = {name}` names the extrusion it is written in"),
            format!("the top is the finished surface of what `{name}` builds: name another solid of the file, the part as designed, or give the top as a height, a `plane(…)` or a `mesh(…)`"),
        ),
        Fault::Kind(kind) => (
            format!("the {kind} `{name}` cannot be a repair's target"),
            WHAT_WORKS.to_string(),
        ),
        Fault::Field(key) => (
            format!("the target `{name}` has its own `{key}`"),
            format!("{WHAT_WORKS}: write its height, or give the repair's top as a `plane(…)` or an expression"),
        ),
        Fault::FollowsLayer => (
            format!("the target `{name}`'s profile follows `layer`"),
            "a target is not built, so it has no layers to follow: give it one shape".to_string(),
        ),
        Fault::ScanSection => (
            format!("the target `{name}`'s profile is a section of a scan"),
            "a target is the part as designed and is built on no scan: give its shape as a section, an outline or a region".to_string(),
        ),
        Fault::Centre => (
            format!("the target `{name}` says `size = centre`"),
            "a target is not built, so it has no tracks: its shapes are its faces; write `size = outer` or leave `size` out".to_string(),
        ),
        Fault::NoHeight => (
            format!("the target `{name}` has no `height`"),
            format!("{WHAT_WORKS}: write `height = …`, the height its top stands at above the part's z = 0"),
        ),
        Fault::MeshHeight => (
            format!("the target `{name}` is a mesh with a `height`"),
            "a mesh target is the whole mesh, its highest faces the finished surface: leave `height` out".to_string(),
        ),
        Fault::Tight(radius, reach) => (
            format!(
                "the target `{name}` bends on a radius of {} mm, but its sections reach {} mm from its spine",
                short(radius),
                short(reach)
            ),
            "a loft's stations are planes through the bend's axis: sections that reach it overlap themselves; bend it on a radius larger than its sections reach".to_string(),
        ),
    };
    // A field refused is pointed at; else the target's name.
    let what = match fault {
        Fault::Field(key) => format!("its `{key}`"),
        Fault::Centre => "its `size`".to_string(),
        _ => "the target".to_string(),
    };
    Diagnostic::error(Code::TargetSolid, message)
        .label(at, "the top")
        .label(decl, what)
        .help(help)
}

/// `top = NAME` naming a bead, section or profile (`kind`, declared at
/// `decl`); `solids` the solids a top may name.
pub fn not_a_solid(name: &str, kind: &str, at: Span, decl: Span, solids: &[&str]) -> Diagnostic {
    let known = if solids.is_empty() {
        "declare it as an `extrude` or a `loft` (it is not built)".to_string()
    } else {
        format!("the solids a top may name: {}", solids.join(", "))
    };
    Diagnostic::error(
        Code::TargetSolid,
        format!("`top = {name}` names a {kind}, not a solid"),
    )
    .label(at, "the top")
    .label(decl, format!("the {kind}"))
    .help(format!(
        "a top given by a name is a solid of the file, the part as designed: {known}"
    ))
}

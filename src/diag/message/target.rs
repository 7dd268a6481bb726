//! `top = NAME`: a repair's target given as a solid of the file
//! (docs/repair.md, *A target solid*), and `scan(register = NAME)`: a
//! scan's nominal given so (*Registration*); the names and solids that
//! cannot be one.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::short;

/// What names a solid of the file as the part as designed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// `top = NAME`: a repair's target, its highest surface the finish.
    Top,
    /// `scan(register = NAME)`: the nominal a scan is fitted to.
    Nominal,
}

impl Role {
    /// The field that names the solid.
    pub fn key(self) -> &'static str {
        match self {
            Role::Top => "top",
            Role::Nominal => "register",
        }
    }

    /// What the solid is, in a message.
    fn noun(self) -> &'static str {
        match self {
            Role::Top => "target",
            Role::Nominal => "nominal",
        }
    }

    /// The label on the field.
    fn label(self) -> &'static str {
        match self {
            Role::Top => "the top",
            Role::Nominal => "the nominal",
        }
    }

    /// What such a solid needs, said once for every refusal.
    fn what_works(self) -> String {
        format!("a {} is the part as designed, standing on the plate: an `extrude` of a shape up to a `height`, an `extrude` of a `mesh(…)`, or a `loft`; it is not built", self.noun())
    }

    /// What else the field may be.
    fn instead(self) -> &'static str {
        match self {
            Role::Top => "give the repair's top as a `plane(…)` or an expression",
            Role::Nominal => "give the nominal as `mesh(file = …)`",
        }
    }
}

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

/// `top = NAME` or `register = NAME` (`role`) naming the solid `name`
/// (declared at `decl`, or the field refused there), which cannot be the
/// part as designed, for `fault`.
pub fn cannot(name: &str, fault: Fault<'_>, role: Role, at: Span, decl: Span) -> Diagnostic {
    let noun = role.noun();
    let (message, help) = match fault {
        Fault::Itself => match role {
            Role::Top => (
                format!("`top = {name}` names the extrusion it is written in"),
                format!("the top is the finished surface of what `{name}` builds: name another solid of the file, the part as designed, or give the top as a height, a `plane(…)` or a `mesh(…)`"),
            ),
            Role::Nominal => (
                format!("`register = {name}` names the extrusion its scan is written in"),
                format!("the nominal is the part as designed, which the scan is fitted to, not what `{name}` builds on it: name another solid of the file (it is then not built) or give it as `mesh(file = …)`"),
            ),
        },
        Fault::Kind(kind) => (
            format!("the {kind} `{name}` cannot be a {}", match role {
                Role::Top => "repair's target",
                Role::Nominal => "scan's nominal",
            }),
            role.what_works(),
        ),
        Fault::Field(field) => (
            format!("the {noun} `{name}` has its own `{field}`"),
            match field {
                "on" => format!("{}: leave its `on` out, or {}", role.what_works(), role.instead()),
                _ => format!("{}: write its height, or {}", role.what_works(), role.instead()),
            },
        ),
        Fault::FollowsLayer => (
            format!("the {noun} `{name}`'s profile follows `layer`"),
            format!("a {noun} is not built, so it has no layers to follow: give it one shape"),
        ),
        Fault::ScanSection => (
            format!("the {noun} `{name}`'s profile is a section of a scan"),
            format!("a {noun} is the part as designed and is built on no scan: give its shape as a section, an outline or a region"),
        ),
        Fault::Centre => (
            format!("the {noun} `{name}` says `size = centre`"),
            format!("a {noun} is not built, so it has no tracks: its shapes are its faces; write `size = outer` or leave `size` out"),
        ),
        Fault::NoHeight => (
            format!("the {noun} `{name}` has no `height`"),
            format!("{}: write `height = …`, the height its top stands at above the part's z = 0", role.what_works()),
        ),
        Fault::MeshHeight => (
            format!("the {noun} `{name}` is a mesh with a `height`"),
            format!("a mesh {noun} is the whole mesh{}: leave `height` out", match role {
                Role::Top => ", its highest faces the finished surface",
                Role::Nominal => "",
            }),
        ),
        Fault::Tight(radius, reach) => (
            format!(
                "the {noun} `{name}` bends on a radius of {} mm, but its sections reach {} mm from its spine",
                short(radius),
                short(reach)
            ),
            "a loft's stations are planes through the bend's axis: sections that reach it overlap themselves; bend it on a radius larger than its sections reach".to_string(),
        ),
    };
    // A field refused is pointed at; else the solid's name.
    let what = match fault {
        Fault::Field(field) => format!("its `{field}`"),
        Fault::Centre => "its `size`".to_string(),
        _ => format!("the {noun}"),
    };
    Diagnostic::error(Code::TargetSolid, message)
        .label(at, role.label())
        .label(decl, what)
        .help(help)
}

/// `top = NAME` or `register = NAME` (`role`) naming a bead, section or
/// profile (`kind`, declared at `decl`); `solids` the solids it may name.
pub fn not_a_solid(
    name: &str,
    kind: &str,
    role: Role,
    at: Span,
    decl: Span,
    solids: &[&str],
) -> Diagnostic {
    let key = role.key();
    let who = match role {
        Role::Top => "a top",
        Role::Nominal => "a nominal",
    };
    let known = if solids.is_empty() {
        "declare it as an `extrude` or a `loft` (it is not built)".to_string()
    } else {
        format!("the solids {who} may name: {}", solids.join(", "))
    };
    Diagnostic::error(
        Code::TargetSolid,
        format!("`{key} = {name}` names a {kind}, not a solid"),
    )
    .label(at, role.label())
    .label(decl, format!("the {kind}"))
    .help(format!(
        "{who} given by a name is a solid of the file, the part as designed: {known}"
    ))
}

/// `register = …` given what is neither a mesh nor a name (a number, a
/// text, a constant's value).
pub fn not_a_nominal(got: crate::diag::message::value::Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TargetSolid,
        "`register` must be the part as designed: a `mesh(…)` or the name of a solid of the file",
    )
    .label(at, format!("this is {}", got.describe()))
    .help("write `register = mesh(file = \"nominal.stl\")`, or `register = NAME` for an `extrude` or `loft` of the file (it is then not built)")
}

/// Every solid of the file is named by another as the part as designed
/// (`top = NAME`, `register = NAME`), so none is left to build: the
/// solids, each with its name's span.
pub fn every_solid_named(solids: &[(&str, Span)]) -> Diagnostic {
    let names: Vec<String> = solids.iter().map(|(n, _)| format!("`{n}`")).collect();
    let mut d = Diagnostic::error(
        Code::MissingSolid,
        format!(
            "every solid of the file is named by another as the part as designed ({}), so none is left to build",
            names.join(", ")
        ),
    );
    for (_, at) in solids {
        d = d.label(*at, "named as the part as designed");
    }
    d.help("a solid that `top = NAME` or `register = NAME` names is the part as designed and is not built: the part to build names it, and no solid names the part to build")
}

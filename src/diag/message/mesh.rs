//! What lmdc says about a solid given as a mesh (`mesh(file = "…")`): a
//! file it cannot read, a surface that encloses no solid, a placement off
//! the plate, a layer whose section is no region. Triangles are numbered
//! from 0 in the order of the file, as mesh tools number them.

use crate::diag::{Code, Diagnostic};
use crate::geometry::mesh::stl::{StlError, MAX_TRIANGLES};
use crate::geometry::mesh::three_mf::{
    ThreeMfError, MAX_DEPTH, MAX_MODEL_BYTES, MAX_RATIO, RATIO_FREE,
};
use crate::geometry::mesh::{MeshFault, SectionFault, ON_PLATE};
use crate::span::Span;
use crate::units::short;

const REPAIR: &str = "repair the mesh (e.g. MeshLab's or PrusaSlicer's repair, or Blender's 3D-Print toolbox) or export it again from CAD as a closed solid";

fn p3(p: [f64; 3]) -> String {
    format!("({}, {}, {}) mm", short(p[0]), short(p[1]), short(p[2]))
}

fn p2(p: [f64; 2]) -> String {
    format!("({}, {}) mm", short(p[0]), short(p[1]))
}

fn list(ts: &[usize]) -> String {
    ts.iter()
        .map(|t| t.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The mesh file `path` (named at `at`) cannot be read (`why`).
pub fn unreadable(path: &str, why: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        format!("cannot read the mesh file `{path}`: {why}"),
    )
    .label(at, "this file")
    .help("the path is relative to the folder of the .lmd file")
}

/// A program names a mesh file where no file can be read (compiled from a
/// text, not a file).
pub fn no_reader(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        "this program is compiled from a text, not a file: there is no folder to read the mesh from",
    )
    .label(at, "mesh file")
    .help("compile the .lmd file (`lmdc build FILE.lmd`)")
}

/// The file `path` is no STL lmdc reads.
pub fn not_stl(path: &str, e: &StlError, at: Span) -> Diagnostic {
    let what = match e {
        StlError::NotStl { len } => format!(
            "it is neither a binary STL (84 bytes of header and count, then 50 a triangle) nor an ASCII one (starting `solid`): {len} bytes"
        ),
        StlError::Truncated { count, expected, got } => format!(
            "its header counts {count} triangles, which take {expected} bytes; the file has {got}: it is cut short or no STL"
        ),
        StlError::Ascii { line, expected } => format!("line {line}: expected {expected}"),
        StlError::NotFinite { triangle } => {
            format!("triangle {triangle} has a corner that is not a finite number")
        }
        StlError::Empty => "it holds no triangle".to_string(),
        StlError::TooMany { count } => format!(
            "it holds {count} triangles; lmdc reads at most {MAX_TRIANGLES}"
        ),
    };
    Diagnostic::error(
        Code::Mesh,
        format!("the mesh file `{path}` is no STL lmdc can read: {what}"),
    )
    .label(at, "this file")
    .help("export the part as STL (binary or ASCII) or 3MF; OBJ and STEP are not read")
}

/// The file `path` is no 3MF lmdc can read.
pub fn not_3mf(path: &str, e: &ThreeMfError, at: Span) -> Diagnostic {
    let what = match e {
        ThreeMfError::NotZip { why } => {
            format!("a 3MF is a ZIP package, and this is none ({why})")
        }
        ThreeMfError::NoModel => {
            "the package holds no model part (`3D/3dmodel.model`)".to_string()
        }
        ThreeMfError::TooLarge { bytes } => format!(
            "its model parts inflate to {bytes} bytes; lmdc reads at most {MAX_MODEL_BYTES}"
        ),
        ThreeMfError::Inflates { bytes, compressed } => format!(
            "its model part inflates {compressed} bytes to {bytes}, {} times over; lmdc reads a model part past {} MB that inflates at most {MAX_RATIO} times (a mesh's XML inflates 5 to 10 times; this is mostly blank or repeated)",
            bytes / (*compressed).max(1),
            RATIO_FREE >> 20
        ),
        ThreeMfError::SeveralModels { count } => format!(
            "its objects lie in {count} model parts (the production extension); lmdc reads a package of one model part"
        ),
        ThreeMfError::Xml { why } => format!("its model is no 3MF model lmdc reads: {why}"),
        ThreeMfError::NoItem => "its build has no item: it makes nothing".to_string(),
        ThreeMfError::NoObject { id, item } => {
            format!("build item {item} needs object {id}, which the model does not hold")
        }
        ThreeMfError::Index { object, triangle, index, vertices } => format!(
            "triangle {triangle} of object {object} names vertex {index}, but the object has {vertices} vertices (counted from 0)"
        ),
        ThreeMfError::NotFinite { object, item } => format!(
            "object {object} in build item {item} has a vertex or transform that is not a finite number"
        ),
        ThreeMfError::TooDeep { object, item } => format!(
            "the components of build item {item} nest deeper than {MAX_DEPTH} at object {object} (or contain themselves)"
        ),
        ThreeMfError::Empty => "its build items hold no triangle".to_string(),
        ThreeMfError::TooMany => {
            format!("its build items hold more than {MAX_TRIANGLES} triangles")
        }
    };
    Diagnostic::error(
        Code::Mesh,
        format!("the mesh file `{path}` is no 3MF lmdc can read: {what}"),
    )
    .label(at, "this file")
    .help("export the part again as 3MF (one model part, meshes only) or as STL")
}

/// A 3MF whose model says its unit is `unit` where the program writes
/// `units = written`, another.
pub fn units_disagree(path: &str, unit: &str, written: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        format!(
            "the 3MF `{path}` says its unit is the {unit} (`unit=\"{unit}\"`), and `units = {written}` says otherwise"
        ),
    )
    .label(at, "not the file's unit")
    .help("leave out `units`: a 3MF says its unit itself, and lmdc reads it")
}

/// The mesh of `path` encloses no solid (`f`).
pub fn fault(path: &str, f: &MeshFault, at: Span) -> Diagnostic {
    let msg = match f {
        MeshFault::Open { edges, triangles, at: [a, b] } => format!(
            "the mesh `{path}` is open: {edges} edge(s) belong to one triangle only, so it encloses no solid; triangles {} (counted from 0 in the file) border the gap, the first edge from {} to {}",
            list(triangles),
            p3(*a),
            p3(*b)
        ),
        MeshFault::NonManifold { edges, triangles, at: [a, b] } => format!(
            "the mesh `{path}` is not manifold: {edges} edge(s) are shared by more than two triangles; triangles {} (counted from 0 in the file) meet on the edge from {} to {}",
            list(triangles),
            p3(*a),
            p3(*b)
        ),
        MeshFault::Flipped { edges, triangles: [t, u], at: [a, b] } => format!(
            "the mesh `{path}` has triangles facing both ways: triangles {t} and {u} (counted from 0 in the file) share the edge from {} to {} and disagree on which side is outside ({edges} such edge(s))",
            p3(*a),
            p3(*b)
        ),
        MeshFault::Flat => format!("the mesh `{path}` encloses no volume"),
    };
    Diagnostic::error(Code::Mesh, msg)
        .label(at, "this mesh")
        .help(REPAIR)
}

/// The placed mesh's lowest point is at `z` (mm), not on the plate at 0:
/// `at[2]` would be `fix` (a decimal chosen so that writing it builds,
/// shown in full).
pub fn not_on_plate(path: &str, z: f64, fix: f64, at: Span) -> Diagnostic {
    let place = if z > 0.0 { "above" } else { "below" };
    Diagnostic::error(
        Code::Mesh,
        format!(
            "the mesh `{path}`, placed, has its lowest point at z = {} mm, {place} the plate: the layers start on the plate at z = 0",
            short(z)
        ),
    )
    .label(at, "placed here")
    .help(format!(
        "set the third number of `at` to {fix} mm, so the part stands on the plate (its lowest point may be up to {ON_PLATE} mm off it)"
    ))
}

/// Which of a plan's limits a mesh would pass, and by how much.
#[derive(Clone, Copy, Debug)]
pub enum Over {
    /// Its layers.
    Layers {
        /// How many layers build it.
        n: f64,
        /// The most a plan may have.
        max: usize,
    },
    /// The pieces of outline its sections have over all layers.
    Pieces {
        /// How many.
        n: f64,
        /// The most a plan's profiles may have.
        max: usize,
    },
    /// The points its fill lays.
    Points {
        /// The fewest it can lay.
        least: f64,
        /// The most a plan may hold.
        max: usize,
    },
}

/// What [`too_big`] says: the placed mesh's size and what slicing it
/// would need.
pub struct TooBig {
    /// Its size along x, y and z (mm, placed).
    pub size: [f64; 3],
    /// The file's unit, when it is one `units` names.
    pub unit: Option<&'static str>,
    /// The unit a 3MF names for itself (`foot`), which `units` cannot
    /// change; `None` for an STL.
    pub file_unit: Option<&'static str>,
    /// How many layers build it.
    pub layers: usize,
    /// The lift (mm).
    pub lift: f64,
    /// The track offset (mm).
    pub pitch: f64,
    /// The limit it passes.
    pub over: Over,
    /// A unit in which it would fit, and its size then (mm).
    pub other: Option<(&'static str, [f64; 3])>,
}

/// `× `-joined sizes, in mm.
fn size3(s: [f64; 3]) -> String {
    format!("{} × {} × {} mm", short(s[0]), short(s[1]), short(s[2]))
}

/// A unit `mesh(units = …)` takes, as a 3MF's `unit` names it.
fn three_mf_unit(u: &str) -> &str {
    match u {
        "mm" => "millimeter",
        "cm" => "centimeter",
        "m" => "meter",
        "in" => "inch",
        other => other,
    }
}

/// The mesh `path` is too big to slice within a plan's limits, which it
/// would find only after minutes of slicing: most likely a file read in
/// the wrong unit.
pub fn too_big(path: &str, t: TooBig, at: Span) -> Diagnostic {
    let read = read_in(t.file_unit, t.unit);
    let help = match t.other {
        Some(other) => in_other_unit(other, t.file_unit),
        None => "a smaller part, or fewer layers (`height` or `layers`); check the file's `units`"
            .to_string(),
    };
    let layers = format!("{} layers of {} mm", t.layers, short(t.lift));
    let need = match t.over {
        Over::Layers { n, max } => format!(
            "it needs {n:.0} layers of {} mm, more than the {max} a plan may have",
            short(t.lift)
        ),
        Over::Pieces { n, max } => format!(
            "its {layers} cut its faces into {n:.0} pieces of outline, more than the {max} a plan's profiles may have"
        ),
        Over::Points { least, max } => format!(
            "its {layers}, filled with tracks {} mm apart, need at least {least:.0} points, more than the {max} a plan may hold",
            short(t.pitch)
        ),
    };
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "the mesh `{path}`{read} is {} as placed: {need}",
            size3(t.size)
        ),
    )
    .label(at, "this mesh")
    .help(help)
}

/// What the mesh would be in the unit `u`, at size `s` (mm), and how to read
/// it so: `units = u` for an STL, exported again for a 3MF naming
/// `file_unit` itself.
fn in_other_unit((u, s): (&str, [f64; 3]), file_unit: Option<&str>) -> String {
    let said = spoken(u);
    match file_unit {
        Some(f) => format!(
            "in {said} it would be {}: if the file's numbers are {said}, not the `{f}` it names, export it again with `unit=\"{}\"` (a 3MF names its unit itself)",
            size3(s),
            three_mf_unit(u)
        ),
        None => format!(
            "in {said} it would be {}: if the file's numbers are {said}, write `units = {u}` in `mesh(…)`{}",
            size3(s),
            if u == "mm" { " or leave `units` out" } else { "" }
        ),
    }
}

/// How a mesh's numbers were read: ` (its unit `foot`)` for a 3MF, ` (read
/// in `units = m`)` for an STL read in a unit `units` names.
fn read_in(file_unit: Option<&str>, unit: Option<&str>) -> String {
    match (file_unit, unit) {
        (Some(f), _) => format!(" (its unit `{f}`)"),
        (None, Some(u)) => format!(" (read in `units = {u}`)"),
        (None, None) => String::new(),
    }
}

/// A unit as a sentence says it: `in` is inches.
fn spoken(u: &str) -> &str {
    match u {
        "in" => "inches",
        other => other,
    }
}

/// A mesh too narrow for any track, and what it would be in another unit.
#[derive(Clone, Debug)]
pub struct TooSmall {
    /// Its size along x, y and z (mm, placed).
    pub size: [f64; 3],
    /// The file's unit, when it is one `units` names.
    pub unit: Option<&'static str>,
    /// The unit a 3MF names for itself; `None` for an STL.
    pub file_unit: Option<&'static str>,
    /// The bead's width (mm).
    pub width: f64,
    /// The larger units in which a few beads fit across it, and its size
    /// then, the likeliest first.
    pub others: Vec<(&'static str, [f64; 3])>,
}

/// The mesh `path` is narrower than the band its outer contour takes:
/// no track fits on any layer. Most likely a file drawn in a larger unit
/// (inches) read in a smaller one.
pub fn too_small(path: &str, t: TooSmall, at: Span) -> Diagnostic {
    let read = read_in(t.file_unit, t.unit);
    let help = match t.others.split_first() {
        Some((&first, rest)) => {
            let also: Vec<String> = rest
                .iter()
                .map(|&(u, s)| format!("; in {}, {}", spoken(u), size3(s)))
                .collect();
            format!("{}{}", in_other_unit(first, t.file_unit), also.concat())
        }
        None => format!(
            "a part at least {} mm across, or a narrower bead; check the file's `units`",
            short(t.width)
        ),
    };
    Diagnostic::error(
        Code::FillEmpty,
        format!(
            "the mesh `{path}`{read} is {} as placed: narrower than the {} mm bead, no track fits in it",
            size3(t.size),
            short(t.width)
        ),
    )
    .label(at, "this mesh")
    .help(help)
}

/// Layer `k`'s section of the mesh, at height `z` (mm), is no region.
pub fn section(f: &SectionFault, k: usize, z: f64, at: Span) -> Diagnostic {
    let on = format!("layer {} (cut at z = {} mm)", k + 1, short(z));
    let (msg, help) = match f {
        SectionFault::Empty => (
            format!("the mesh has no section on {on}: nothing to build there"),
            "build no higher than the mesh: leave out `height` and `layers`, and lmdc builds the mesh's height".to_string(),
        ),
        SectionFault::Open { at: p, triangles } => (
            format!(
                "the section of {on} does not close: it stops at {} after triangles {} (counted from 0 in the file)",
                p2(*p),
                list(triangles)
            ),
            REPAIR.to_string(),
        ),
        SectionFault::StrayHole { at: p } => (
            format!(
                "the section of {on} has a hole at {} that lies in no outline: the mesh's faces there run the wrong way round",
                p2(*p)
            ),
            REPAIR.to_string(),
        ),
        SectionFault::Overlap { at: p } => (
            format!(
                "the sections of two shells of the mesh overlap on {on}, at {}: each shell would be traced and filled in full, crossing the other's contours and laying metal twice where they share",
                p2(*p)
            ),
            "unite the shells into one solid in CAD (a boolean union) and export that one solid, or move the shells apart with a gap between them".to_string(),
        ),
    };
    Diagnostic::error(Code::Mesh, msg)
        .label(at, "this mesh")
        .help(help)
}

/// `mesh(key = …)` is not a list of three numbers (`got`).
pub fn not_three(key: &str, got: &str, at: Span) -> Diagnostic {
    let (what, e) = if key == "turn" {
        ("turns about x, y and z", "[0 deg, 0 deg, 90 deg]")
    } else {
        ("where the file's origin goes", "[0 mm, 0 mm, 5 mm]")
    };
    Diagnostic::error(
        Code::ExpectedPoint,
        format!("`{key}` of a mesh is {what}: a list of three, `[x, y, z]`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("e.g. `{key} = {e}`"))
}

/// A mesh with a `top`: its top is its own.
pub fn mesh_with_top(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        "a mesh has its own top: it is sliced in flat layers, not built up to a `top`",
    )
    .label(at, "this mesh")
    .help("leave out `top` and slice it with `slicing planar { … }`")
}

/// `top = mesh(…)` whose faces are all upright: no surface seen from above.
pub fn no_upper_face(path: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        format!("the target `{path}` has no face seen from above: every face stands upright"),
    )
    .label(at, "the finished part")
    .help("a target mesh is the part as designed, its upper faces the finished surface: check its `turn` (a part lying on its side?)")
}

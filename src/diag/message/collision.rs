//! The head against the cell (docs/collision.md): a body of the head that
//! comes within its gap of the plate, a fixture or the part laid so far
//! (`lmd::collision`), and a machine that declares no head
//! (`lmd::head-unchecked`).

use crate::diag::message::words::Words;
use crate::diag::{plural, Code, Diagnostic, Worst};
use crate::span::Span;
use crate::units::{short, short_up};
use std::fmt::Display;

/// What a body came too close to.
#[derive(Clone, Copy, Debug)]
pub enum With<'a> {
    /// The plate (the part's `z = 0`).
    Plate,
    /// The fixture of this name.
    Fixture(&'a str),
    /// The scanned part a repair builds on (docs/repair.md).
    Scan,
    /// The part as laid so far, at its layer (from 1).
    Part(usize),
}

/// One kind of collision, the worst of it and what fixes it.
pub struct Hit<'a, At> {
    /// The machine.
    pub machine: &'a str,
    /// The head's body (`nozzle`, `body`, …).
    pub body: &'a str,
    /// What it comes too close to.
    pub with: With<'a>,
    /// The closest approach (its value the distance, its limit the gap).
    pub worst: &'a Worst<At>,
    /// The standoff that keeps the gap at every pose found too close,
    /// where raising the head along its beam does (mm).
    pub standoff: Option<f64>,
    /// The declared head, if any.
    pub declared: Option<Span>,
    /// Where the fixture it meets is placed (its `at`, else its name).
    pub placed: Option<Span>,
    /// Where that fixture keeps the gap, checked by making the plan again
    /// with it there.
    pub moved: Option<Moved>,
    /// The body made narrower so that it keeps the gap from the part at
    /// every pose found too close (where raising the head does not help).
    pub narrower: Option<Narrower>,
}

/// A head's body as declared, narrowed.
#[derive(Clone, Debug, PartialEq)]
pub struct Narrower {
    /// Its length, mm.
    pub length: f64,
    /// Its diameters at its lower and upper ends, mm (equal: a cylinder).
    pub diameters: [f64; 2],
}

/// A fixture moved along X or Y.
#[derive(Clone, Debug, PartialEq)]
pub struct Moved {
    /// The direction, as printed (`−x`).
    pub axis: &'static str,
    /// How far, mm.
    pub by: f64,
    /// Its `at` there, mm.
    pub at: [f64; 3],
}

/// A body of the head closer than its gap to something.
pub fn collision<At: Display>(h: &Hit<'_, At>) -> Diagnostic {
    let w = h.worst;
    let what = match h.with {
        With::Plate => "the plate".to_string(),
        With::Scan => "the scanned part".to_string(),
        With::Fixture(name) => format!("fixture `{name}`"),
        With::Part(layer) => format!("the part laid so far (layer {layer})"),
    };
    let who = format!("the {} of machine `{}`", h.body, h.machine);
    let message = too_close(&who, &what, w, false);
    let fix = match (h.with, h.standoff, &h.moved) {
        (With::Scan, Some(s), _) => format!(
            "the head comes down onto the part it builds on (its scanned surface, docs/repair.md): a `standoff` of {} mm (the nozzle's tip that far from the focus) keeps the gap at every such pose; or tilt the nozzle less there",
            short_up(s)
        ),
        (With::Scan, None, _) => "the head comes down onto the part it builds on (its scanned surface, docs/repair.md): a `standoff` that holds the nozzle farther from it, a higher travel `clearance`, or the nozzle tilted less there".to_string(),
        (With::Fixture(name), _, Some(m)) => format!(
            "move fixture `{name}` {} mm in {} (`at = [{} mm, {} mm, {} mm]`): the plan made again with it there, its travels over it included, keeps the gap at every pose; or lower it, or build the part where the head passes farther from it",
            short(m.by),
            m.axis,
            short(m.at[0]),
            short(m.at[1]),
            short(m.at[2])
        ),
        (With::Fixture(name), _, None) => format!(
            "move fixture `{name}` clear of the head's way (or lower it), or build the part where the head passes farther from it"
        ),
        (_, Some(s), _) => format!(
            "a `standoff` of {} mm (the nozzle's tip that far from the focus) keeps the gap at every such pose; or tilt the nozzle less there, or bring the focus nearer the surface (a smaller defocus below it) by as much",
            short_up(s)
        ),
        (With::Part(_), None, _) if h.narrower.is_some() => {
            let n = h.narrower.as_ref().expect("matched");
            let [d0, d1] = n.diameters.map(short);
            let shape = if n.diameters[0] == n.diameters[1] {
                format!("cylinder(length = {} mm, diameter = {d0} mm)", short(n.length))
            } else {
                format!("frustum(length = {} mm, tip = {d0} mm, top = {d1} mm)", short(n.length))
            };
            format!(
                "the part leans over the head's side here, and raising the head does not take its {} off it: a {} at most {d1} mm across (`{} = {shape}`) would keep the gap at every such pose — a slimmer head; else tilt the nozzle less there, turn the part (a positioner's `keep`, the layers' `nozzle`), or build it in another order",
                h.body, h.body, h.body
            )
        }
        (_, None, _) => "the head passes beside what it comes near: tilt the nozzle less there, turn the part (a positioner's `keep`, the layers' `nozzle`), or build it in another order".to_string(),
    };
    let d = Diagnostic::error(Code::Collision, message).help(format!(
        "{fix}; `head {{ … }}` says what the machine carries (docs/collision.md)"
    ));
    let d = match (h.with, h.placed) {
        (With::Scan, Some(at)) => d.label(at, "the part built on, as scanned"),
        (With::Fixture(name), Some(at)) => d.label(at, format!("fixture `{name}` stands here")),
        _ => d,
    };
    match h.declared {
        Some(at) => d.label(at, "the head as declared"),
        None => d,
    }
}

/// `who` (a head's body, an arm's link) closer than its gap to `what` at
/// worst `w`: how close (how deep, with `depth`, where it runs into it),
/// where, the gap and how many poses.
fn too_close<At: Display>(who: &str, what: &str, w: &Worst<At>, depth: bool) -> String {
    let how = match (w.value <= 0.0, depth) {
        (true, true) => format!("runs {} mm into {what}", short(-w.value)),
        (true, false) => format!("runs into {what}"),
        (false, _) => format!("comes within {} mm of {what}", short(w.value)),
    };
    format!(
        "{who} {how} at {}, where it must keep {} mm ({} pose{} too close)",
        w.at,
        short(w.limit),
        w.count,
        plural(w.count)
    )
}

/// A machine that declares no head: a typical coaxial nozzle was checked.
pub fn head_unchecked(machine: &str, at: Span) -> Diagnostic {
    Diagnostic::warning(
        Code::HeadUnchecked,
        format!(
            "machine `{machine}` declares no head: collisions were checked with a typical coaxial nozzle (a 45 mm cone from a 12 mm tip to 40 mm on a body 60 mm across, its tip 15 mm above the focus), not the machine's own"
        ),
    )
    .label(at, "no `head { … }` here")
    .help(
        "declare what the machine carries, e.g. `head { standoff = 15 mm  nozzle = frustum(length = 45 mm, tip = 12 mm, top = 40 mm)  body = cylinder(length = 100 mm, diameter = 60 mm) }` (docs/collision.md)",
    )
}

/// A robot's `arm_links` that is not three lengths above zero.
pub fn not_three_links(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        "`arm_links` is three lengths above zero: the radii of the upper arm, the forearm and the wrist",
    )
    .label(at, format!("this is {got}"))
    .help("e.g. `arm_links = [190 mm, 140 mm, 100 mm]` (a KR 60 HA's, docs/collision.md)")
}

/// A head's solid (`key`) written as something other than a solid.
pub fn not_a_solid(key: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("a head's `{key}` is a solid about the beam: `frustum(…)` or `cylinder(…)`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!(
        "e.g. `{key} = frustum(length = 45 mm, tip = 12 mm, top = 40 mm)` (tapering from its lower end up) or `{key} = cylinder(length = 100 mm, diameter = 60 mm)`"
    ))
}

/// A fixture's `shape` that is no shape.
pub fn not_a_shape(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        "a fixture's `shape` is `box(size = [x, y, z])`, an upright `cylinder(length = …, diameter = …)` or `mesh(file = \"…\")`",
    )
    .label(at, format!("this is {got}"))
    .help("e.g. `shape = box(size = [40 mm, 20 mm, 30 mm])`, standing on its bottom face at `at`")
}

/// A fixture's `key` (`size`, `at`) that is not three lengths.
pub fn not_three(key: &str, at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Type,
        format!("a fixture's `{key}` is three lengths `[x, y, z]`"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("e.g. `{key} = [40 mm, 20 mm, 30 mm]`"))
}

/// A fixture's size `mm` not above zero or beyond `max`.
pub fn bad_size(at: Span, mm: f64, max: f64) -> Diagnostic {
    Diagnostic::error(
        Code::OutOfRange,
        format!(
            "a fixture {} mm in size is no fixture lmdc checks: each side is above 0 and at most {} m",
            short(mm),
            short(max / 1000.0)
        ),
    )
    .label(at, "here")
    .help("write the fixture's real size, in its units")
}

/// A fixture's `machine = …` that is not a bare name.
pub fn fixture_machine_not_a_name(at: Span, got: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedName,
        "`machine` names the machine the fixture is fixed to",
    )
    .label(at, format!("this is {got}"))
    .help("write the name of a `machine NAME { … }` of this file: `machine = mill5`")
}

/// `turns_with = tilt` on a fixture on the plate.
pub fn tilts_without_machine(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        "`turns_with = tilt` says which axis of its machine a fixture turns with, but this one is on the plate (no `machine`)",
    )
    .label(at, "turns with the tilt axis of no machine")
    .help("name the machine whose tilt axis carries it (`machine = trt`), or leave `turns_with` out: a fixture on the plate turns with the part")
}

/// `turns_with = tilt` on a fixture fixed to machine `machine`, which has
/// no tilting table or positioner.
pub fn nothing_tilts(machine: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        format!("machine `{machine}` has no tilt axis for the fixture to turn with: no tilting table (`kinematics = table_ac` or `table_bc` on 5 axes) and no positioner"),
    )
    .label(at, "turns with the tilt axis")
    .help("leave `turns_with` out (the fixture stands on the machine's base), or fix it to a machine with a tilting table or a positioner")
}

/// Fixture `name` is fixed to robot `robot`, whose base has no value.
pub fn fixture_unplaced(name: &str, robot: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::MissingField,
        format!(
            "fixture `{name}` is fixed to robot `{robot}`, whose `base` is an index without values: where the part stands in the robot's frame is not known, so where the fixture stands from the part is not either"
        ),
    )
    .label(at, "fixed to this robot")
    .help("give the base its values (`base = 1 [x, y, z, a, b, c]`), or place the fixture in the part's coordinates (without `machine`)")
}

/// A fixture's `mesh(at = …)`: the fixture's own `at` places it.
pub fn mesh_fixture_at(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        "a fixture's mesh is placed by the fixture's `at` (where the file's origin goes), not by `mesh(at = …)`",
    )
    .label(at, "here")
    .help("move this `at` out of `mesh(…)` into the fixture's block: `fixture NAME { shape = mesh(file = \"…\")  at = [x, y, z] }`")
}

/// A fixture's mesh `path` with `n` triangles, more than `max`.
pub fn mesh_fixture_too_big(path: &str, n: usize, max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!(
            "the fixture's mesh `{path}` has {n} triangles, more than the {max} a fixture's mesh may have"
        ),
    )
    .label(at, "this mesh")
    .help("export the fixture more coarsely or decimate it (MeshLab's quadric edge collapse, Blender's Decimate): the check samples its faces every 2 mm and needs no finer triangles")
}

/// A fixture's mesh `path` whose box is `size` (mm, as read), past `max`.
pub fn mesh_fixture_size(path: &str, size: [f64; 3], max: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Mesh,
        format!(
            "the fixture's mesh `{path}` is {} × {} × {} mm as read: a fixture lmdc checks is at most {} m along each side",
            short(size[0]),
            short(size[1]),
            short(size[2]),
            short(max / 1000.0)
        ),
    )
    .label(at, "this mesh")
    .help("check its `units` (an STL does not say its own: `units = mm` unless written)")
}

/// A second fixture named `name`.
pub fn duplicate_fixture(name: &str, at: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        Code::DuplicateName,
        format!("there are two fixtures called `{name}`"),
    )
    .label(at, "this one")
    .label(first, "and this one")
    .help("give each fixture a name of its own: the messages name them")
}

/// What an arm's link came too close to.
#[derive(Clone, Copy, Debug)]
pub enum Against<'a> {
    /// The positioner's faceplate, and the diameter at most it may have
    /// to keep the gap at every pose found too close, where a smaller one
    /// does (mm).
    Faceplate(Option<f64>),
    /// The fixture of this name.
    Fixture(&'a str),
    /// The scanned part a repair builds on (docs/repair.md).
    Scan,
    /// The plate (the part's `z = 0`), without a positioner.
    Plate,
    /// Another link of the same arm (`upper arm`, `column`).
    Own(&'a str),
    /// The part, finished (on the PTP back home).
    Part,
}

/// How a `home` the help proposes was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HomeFrom {
    /// The first pose's A1 and wrist, the upper arm as at home and the
    /// forearm raised this many degrees above home's.
    Raised(u8),
    /// The first pose's own axes.
    First,
}

/// A change to the file that keeps an arm's link clear, found by making
/// the plan again with it and following the arm along it.
#[derive(Clone, Debug, PartialEq)]
pub enum LinkFix {
    /// The fixture in the link's way, moved.
    Moved(Moved),
    /// The part's base stood `by` mm farther from the arm's foot, along the
    /// horizontal line from the foot to it: `base = frame(index, …)` with
    /// `pose` (x, y, z mm, a, b, c deg).
    Base {
        /// How far, mm.
        by: f64,
        /// `BASE_DATA[index]`.
        index: u16,
        /// The base there.
        pose: [f64; 6],
    },
    /// The tool turned about the beam to `deg` (`spin = deg`) from `from`.
    Spin {
        /// The turn, deg.
        deg: f64,
        /// The turn used, deg.
        from: f64,
    },
}

/// One kind of an arm's collision: its link, the worst and what fixes it.
pub struct LinkHit<'a, At> {
    /// The robot.
    pub machine: &'a str,
    /// The link (`upper arm`, `forearm`, `wrist`, `column`, `tool`) or the
    /// head's body (`nozzle`, …) it carries.
    pub link: &'a str,
    /// What it comes too close to.
    pub with: Against<'a>,
    /// The closest approach (its value the distance, its limit the gap).
    pub worst: &'a Worst<At>,
    /// Where the arm is declared.
    pub arm: Span,
    /// Where the faceplate is declared or the fixture placed.
    pub placed: Option<Span>,
    /// Where the worst lies on a PTP from or back to home: the axis angles
    /// of a `home` whose PTPs keep the gap, where one was found (`None`
    /// inside: none was).
    pub ptp: Option<Option<([f64; 6], HomeFrom)>>,
    /// Where `home` is declared, if it is.
    pub home: Option<Span>,
    /// A change checked to keep the link clear, where one was found.
    pub fix: Option<LinkFix>,
    /// The robot's controller's words for its axes and moves.
    pub words: Words,
}

/// A link of a robot's arm (or the head it carries, on a PTP) closer than
/// its gap to the positioner's faceplate, a fixture, the plate, another
/// link or the part.
pub fn link_collision<At: Display>(h: &LinkHit<'_, At>) -> Diagnostic {
    let w = h.worst;
    let what = match h.with {
        Against::Faceplate(_) => "the positioner's faceplate".to_string(),
        Against::Scan => "the scanned part".to_string(),
        Against::Fixture(name) => format!("fixture `{name}`"),
        Against::Plate => "the plate".to_string(),
        Against::Own(link) => format!("its own {link}"),
        Against::Part => "the part".to_string(),
    };
    let who = format!("the {} of robot `{}`", h.link, h.machine);
    let message = too_close(&who, &what, w, true);
    let a1 = h.words.axis(0);
    let fix = match (h.ptp, h.with, &h.fix) {
        (None, _, Some(f)) => link_fix(h.with, f, h.words),
        (Some(Some((home, from))), _, _) => format!(
            "the axes' straight path from `home` passes through it: `home = [{}]` ({}) keeps the gap on {}; or a home of your own, checked the same way",
            home.iter().map(|a| format!("{} deg", short(*a))).collect::<Vec<_>>().join(", "),
            match from {
                HomeFrom::Raised(0) => format!("the first pose's {a1} and wrist, the arm as at home"),
                HomeFrom::Raised(up) => format!("the first pose's {a1} and wrist, the upper arm as at home and the forearm raised {up}° above it"),
                HomeFrom::First => "the first pose's own axes, above the first path".to_string(),
            },
            h.words.home_moves()
        ),
        (Some(None), _, _) => "the axes' straight path from `home` passes through it: a `home` with the arm raised above the cell and turned towards the part, or the part placed where the arm comes down onto it from above".to_string(),
        (None, Against::Faceplate(Some(d)), _) => format!(
            "a faceplate at most {} mm across (`faceplate = {} mm`) keeps the gap at every such pose; or tilt the part less there (the positioner's `tilt_limits` or `keep`), or stand the positioner farther from the arm",
            short(d),
            short(d)
        ),
        (None, Against::Faceplate(None), _) => "the link passes over the faceplate's middle: tilt the part less there (the positioner's `tilt_limits` or `keep`), stand the positioner farther from the arm, or raise the part off the faceplate".to_string(),
        (None, Against::Scan, _) => "the arm reaches down past the part it builds on (its scanned surface, docs/repair.md): tilt the nozzle less there, or stand the part where the arm comes onto it from above".to_string(),
        (None, Against::Fixture(name), _) => format!(
            "move fixture `{name}` out of the arm's way, or build the part where the arm passes farther from it"
        ),
        (None, Against::Plate, _) => "the link hangs down to the part's plane there: tilt the nozzle less there (the wrist hangs lower the more it leans), or a tool that holds the flange farther from the focus".to_string(),
        (None, Against::Own(_), _) => "the arm folds back onto itself there: stand the part farther from the arm's foot (the robot's `base`), or tilt the nozzle less there".to_string(),
        (None, Against::Part, _) => "the head passes through the finished part on its way home: a `home` above the part".to_string(),
    };
    let d = Diagnostic::error(Code::Collision, message)
        .help(format!(
            "{fix}; the arm's links are capsules sized from its catalogue entry (docs/collision.md, *The arm*)"
        ))
        .label(h.arm, "the arm");
    let d = match (h.ptp, h.home) {
        (Some(_), Some(at)) => d.label(at, "home"),
        _ => d,
    };
    match (h.with, h.placed) {
        (Against::Faceplate(_), Some(at)) => d.label(at, "the faceplate"),
        (Against::Scan, Some(at)) => d.label(at, "the part built on, as scanned"),
        (Against::Fixture(name), Some(at)) => d.label(at, format!("fixture `{name}` stands here")),
        _ => d,
    }
}

/// The help's change for a link too close to `with` (docs/collision.md,
/// *What is said*).
fn link_fix(with: Against<'_>, f: &LinkFix, words: Words) -> String {
    let lin = words.lin();
    let mm = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{} mm", short(*x)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match (f, with) {
        (LinkFix::Moved(m), Against::Fixture(name)) => format!(
            "move fixture `{name}` {} mm in {} (`at = [{}]`): the plan made again with it there, its travels over it included, keeps the arm's links and the head clear of it at every pose; or build the part where the arm passes farther from it",
            short(m.by),
            m.axis,
            mm(&m.at)
        ),
        (LinkFix::Base { by, index, pose }, _) => format!(
            "the arm folds back onto itself there: the part stood {} mm farther from the arm's foot, along the level line from the foot through the base (`base = frame({index}, x = {}, y = {}, z = {}, a = {} deg, b = {} deg, c = {} deg)`), keeps the arm unfolded enough — the plan followed from there reaches every pose within the axes' limits, no {lin} singular or changing configuration, and the links keep their gap at every pose; or tilt the nozzle less there",
            short(*by),
            mm(&pose[0..1]),
            mm(&pose[1..2]),
            mm(&pose[2..3]),
            short(pose[3]),
            short(pose[4]),
            short(pose[5])
        ),
        (LinkFix::Spin { deg, from }, _) => format!(
            "the tool is angled on its flange, and turned as it is about the beam ({} deg) it holds the flange down at the part's plane there: turned to `spin = {} deg` it holds it higher — the plan followed with that turn reaches every pose within the axes' limits, no {lin} singular or changing configuration, and the links keep their gap at every pose; or tilt the nozzle less there",
            short(*from),
            short(*deg)
        ),
        (LinkFix::Moved(m), _) => format!(
            "move it {} mm in {} (`at = [{}]`)",
            short(m.by),
            m.axis,
            mm(&m.at)
        ),
    }
}

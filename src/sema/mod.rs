//! The checker: typed AST → [`Model`]. Resolves names, evaluates constants with
//! units, checks every block's fields and ranges, and reports every problem it
//! finds (pest stops at the first syntax error; this stage never stops early).
//!
//! Each statement kind has its reader; a value that fails is reported once
//! and becomes "nothing", and every check that does not need it still runs
//! (a wrong power does not hide a style's wrong speed).

pub mod allow;
pub mod data;
mod declare;
pub mod eval;
mod fields;
mod machine;
mod math;
pub mod model;
pub mod named_shape;
mod process;
mod program_text;
pub mod schema;
pub mod slicing;
mod solid;
mod statement;
mod suggest;
pub mod value;

pub use solid::profile::LayerShapes;
pub use solid::top::TopHeights;

use crate::diag::{message, Diagnostics};
use crate::syntax::ast::File;
use eval::Env;
use machine::{fixture, statements as machines};
use model::{Model, PowerSchedule};
use process::{bead, calibration, control, style};
use statement::Statements;

/// Checks a parsed file. Returns every diagnostic (errors and warnings) found,
/// and the model when every part of it could be read — even if some other
/// statement had errors (an unused constant, a machine that is dropped), so the
/// later stages can report their own problems in the same run. A model that
/// comes with errors is never built into a program.
pub fn check(file: &File) -> (Option<Model>, Diagnostics) {
    check_reading(file, None)
}

/// Reads the data files a program names (`fit(…, data = "coupons.csv")`,
/// `mesh(file = "part.stl")`): the bytes of the file at a path as the
/// program writes it (relative to the program's file), or why it cannot;
/// read as the kind of data it is ([`data::Data`]: a reader stops at its
/// cap, with [`data::read_capped`]). The caller decides where files are;
/// sema opens none itself.
pub type DataReader = std::rc::Rc<dyn Fn(&str, data::Data) -> Result<Vec<u8>, String>>;

/// [`check`], reading the data files the program names with `data` (none:
/// a program that names one is refused, there being no file to read it
/// beside).
pub fn check_reading(file: &File, data: Option<DataReader>) -> (Option<Model>, Diagnostics) {
    let mut diags = Diagnostics::new();
    let model = check_into(file, data, &mut diags);
    (model, diags)
}

fn check_into(file: &File, data: Option<DataReader>, diags: &mut Diagnostics) -> Option<Model> {
    // Shapes named inside shapes, written out first: everything after reads
    // one self-contained expression per shape.
    let file = &named_shape::expand(file, diags);
    let st = Statements::group(file, diags);
    allow::read(&st, diags);
    let mut env = Env::new();
    env.data = data;
    // Constants first: everything else may use them, in any order.
    if !st.get("calibration").is_empty() {
        // A calibration file lays coupons, not a part: no solid, no slicing.
        declare::constants(&mut env, &st, diags);
        let part = statement::part(&st, diags);
        return calibration::check(&mut env, &st, part, diags);
    }
    let decl = declare::read(&mut env, &st, diags);
    let part = statement::part(&st, diags);
    let solid = solid::read(&mut env, &st, &decl, diags);
    let slicing = slicing::statement(&mut env, &st, diags);
    let ring = solid.kind == Some(solid::Kind::Ring);
    let process = process::statement(&mut env, &st, ring.then(|| solid.ring_powers()), diags);
    let control = control::statement(&mut env, &st, &decl.constants, diags);
    if let (false, Some((_, at))) = (ring, &control) {
        diags.push(message::statement::control_without_ring(*at));
    }
    let machines = machines::read(&mut env, &st, diags);
    let mut fixtures = fixture::read(&mut env, &st, &machines, diags);
    // The part built on is there before the first bead: an obstacle to
    // every body, as a fixture is (docs/repair.md).
    fixtures.extend(solid.scan().map(|s| (fixture::scanned(s), s.span)));
    let styles = style::read(&mut env, st.get("style"), diags);
    let inheritance = style::inheritance_statement(&mut env, &st, diags);

    let solid_kind = solid.kind;
    let tolerance = slicing
        .spec
        .as_ref()
        .map(|s| s.tolerance())
        .unwrap_or_default();
    let planar = match &slicing.spec {
        Some(slicing::Spec::Planar(p)) => Some(p.clone()),
        _ => None,
    };
    let variable =
        solid_kind == Some(solid::Kind::TopExtrude) || slicing.strategy == Some("variable");
    let ring_cx = solid::RingContext {
        control: match control {
            None => Some(None),
            Some((spec, _)) => spec.map(Some),
        },
        powder: process.powder.map(|p| p.0),
    };
    let (build, bead) = solid::build(
        &mut env,
        solid,
        slicing,
        process.speed,
        &decl,
        ring_cx,
        diags,
    );
    let styles = style::assemble(
        styles,
        &inheritance,
        &style::Context {
            loft: solid_kind == Some(solid::Kind::Loft),
            wall: matches!(solid_kind, Some(solid::Kind::Wall | solid::Kind::ScanWall)),
            variable,
            ring,
            planar: planar.as_ref(),
            bead: bead.as_ref(),
            laser: process.laser.as_ref(),
        },
        diags,
    );
    if let (Some(b), Some((powder, at))) = (&bead, process.powder) {
        bead::check_feed(b, powder, at, diags);
    }
    if let (Some(b), Some(p), false) = (&bead, &process.process, ring) {
        measured_at(b, p, styles.as_ref(), diags);
    }
    // The slicers lay the feed the process runs.
    let bead = bead.map(|mut b| {
        b.feed = process.powder.map(|(p, _)| p);
        b
    });
    let build = build.map(without_unasked_faces);
    Some(Model {
        part: part?,
        build: build?,
        bead: if ring { None } else { Some(bead?) },
        process: process.process?,
        machines,
        fixtures,
        styles: styles?,
        tolerance,
    })
}

/// `b` without its scan's faces unless `direction = auto` may ask them
/// (what a line meets at a flank): a mesh scan's faces are let go here,
/// not held through the slicing.
fn without_unasked_faces(mut b: model::Build) -> model::Build {
    match &mut b {
        model::Build::Variable { extrusion, slicing } => {
            if let (Some(base), None) = (&mut extrusion.base, slicing.direction) {
                base.faces = None;
            }
        }
        model::Build::ScanWall { on, .. } => on.base.faces = None,
        _ => {}
    }
    b
}

/// Warns where the process or a style runs `b` at a power or feed it was
/// not measured at ([`bead::check_measured_at`]): the process's power (a
/// ramp's last) and feed, and each style's that sets one.
fn measured_at(
    b: &model::Bead,
    p: &model::Process,
    styles: Option<&model::Styles>,
    diags: &mut Diagnostics,
) {
    let power = match p.power {
        PowerSchedule::Constant(w) => w,
        PowerSchedule::Ramp { to, .. } => to,
    };
    let mut powers = vec![(power, p.power_span, None)];
    let mut powders = vec![(p.powder, p.powder_span, None)];
    // A style's power or feed lays its tracks with the same bead.
    for s in styles.iter().flat_map(|s| &s.table) {
        if let Some(w) = s.power {
            powers.push((w, s.span, Some(s.name.as_str())));
        }
        if let Some(f) = s.powder {
            powders.push((f, s.span, Some(s.name.as_str())));
        }
    }
    bead::check_measured_at(b, &powers, &powders, diags);
}

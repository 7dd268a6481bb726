//! `scan(file, units, turn, at, cell, outlier, register, fit_tolerance)`:
//! the measured surface a repair is built on, read through the program's
//! data reader in any of the formats [`crate::geometry::scan`] reads,
//! placed in the part's coordinates — as declared, or moved from there
//! onto its nominal (a mesh, or a solid of the file cut into triangles)
//! by a best fit ([`crate::geometry::scan::register`]) —
//! and estimated on a grid (docs/repair.md).

use crate::diag::{message, Diagnostics};
use crate::geometry::mesh::{Placement, Section};
use crate::geometry::scan::register::{near_box, register, Nominal};
use crate::geometry::scan::section::{self, CutFault};
use crate::geometry::scan::{self, Estimate, Format, HeightField, Pose, Raw};
use crate::geometry::target::Target;
use crate::sema::data::Data;
use crate::sema::fields::Fields;
use crate::sema::model::ScanBase;
use crate::sema::schema::solid::{mesh, scan as field, SCAN};
use crate::sema::solid::mesh::{decode, triple};
use crate::sema::value::{Call, Value};
use crate::sema::DataReader;
use crate::span::Span;
use crate::units::mm_per;
use crate::units::Dim;
use std::sync::Arc;

/// The section of a scan a profile asks for (`scan_section(z)`), when
/// asked: the islands or why there are none.
pub type Cut = Option<Result<Vec<Section>, CutFault>>;

/// How `register = NAME` finds the solid `NAME` of the file (written at
/// the span): the part as designed, or `None` after reporting why it
/// cannot be.
pub type SolidNamed<'s> = &'s mut dyn FnMut(&str, Span, &mut Diagnostics) -> Option<Arc<Target>>;

/// Reads `scan(…)` (the call `c` at `at`), its file through `data`, and
/// its section at `z` when a profile asks for one (cut where the scan is
/// placed, after any best fit); a nominal named as a solid through
/// `solid`.
pub fn read(
    c: &Call,
    at: Span,
    (data, solid): (Option<&DataReader>, SolidNamed<'_>),
    z: Option<f64>,
    diags: &mut Diagnostics,
) -> Option<(ScanBase, Cut)> {
    let f = Fields::call(c, &SCAN, diags);
    let file = f.text(&field::FILE, diags);
    let units = f.word_or_default(&field::UNITS, diags);
    let turn = triple(&f, &mesh::TURN, Dim::ANGLE, diags);
    let place = triple(&f, &field::AT, Dim::LENGTH, diags);
    let cell = f.quantity_or_default(&field::CELL, diags);
    let outlier = f.quantity_or_default(&field::OUTLIER, diags);
    let nominal = nominal(&f, data, solid, diags);
    let tolerance = f.quantity_or_default(&field::FIT_TOLERANCE, diags);
    let ((path, file_at), units, turn, place, cell, outlier, nominal, tolerance) = (
        file?, units?, turn?, place?, cell?, outlier?, nominal?, tolerance?,
    );
    if let (None, Some(t)) = (&nominal, f.span(&field::FIT_TOLERANCE)) {
        diags.push(message::scan::tolerance_without_nominal(t));
        return None;
    }
    let Some(read) = data else {
        diags.push(message::scan::no_reader(file_at));
        return None;
    };
    let bytes = read(&path, Data::Scan)
        .and_then(|b| Data::Scan.too_long(&b).map_or(Ok(b), Err))
        .map_err(|why| diags.push(message::scan::unreadable(&path, &why, file_at)))
        .ok()?;
    let (raw, scale) = raw(&f, (&path, file_at), &bytes, units, diags)?;
    drop(bytes);
    let declared = Pose::from(Placement {
        scale,
        turn: turn.0,
        at: place.0,
    });
    let (pose, registration) = match &nominal {
        None => (declared, None),
        Some(n) => {
            let ask = Fit {
                raw: &raw,
                declared,
                tolerance,
                scan: (&path, at),
                tolerance_at: f.span(&field::FIT_TOLERANCE),
            };
            let (pose, r) = fit(&ask, n, diags)?;
            (pose, Some(Box::new(r)))
        }
    };
    let est = Estimate { cell, outlier };
    let surface = HeightField::new(&raw, pose, est)
        .map_err(|e| diags.push(message::scan::grid(&path, &e, cell, at)))
        .ok()?;
    let cut = z.map(|z| section::cut(&raw, &pose, z));
    if let (Some(z), Some(Ok(sections))) = (z, &cut) {
        if let Some(d) = worn_at(&raw, &pose, z, sections, (&path, at)) {
            diags.push(d);
        }
    }
    let base = ScanBase {
        path,
        surface: std::sync::Arc::new(surface),
        registration,
        faces: scan::Faces::new(raw, pose).map(std::sync::Arc::new),
        span: at,
    };
    Some((base, cut))
}

/// The turn (deg) past which a best fit's correction of the declared
/// placement is warned of: a scan's placement is known to a few degrees.
const FAR_TURN: f64 = 10.0;

/// How far below a section the part is cut again to see whether the
/// section is whole, mm.
const BELOW: f64 = 1.0;

/// A warning when the section at `z` is much smaller than the one
/// [`BELOW`] lower: a cut through the worn part (a blade's tip worn
/// aslant), whose footprint would leave out what wore away. A part that
/// narrows upward by design a few per cent a millimetre is no warning.
fn worn_at(
    raw: &Raw,
    pose: &Pose,
    z: f64,
    sections: &[Section],
    (path, at): (&str, Span),
) -> Option<crate::diag::Diagnostic> {
    let area = |s: &[Section]| s.iter().map(Section::area).sum::<f64>();
    let below = section::cut(raw, pose, z - BELOW).ok()?;
    let (here, there) = (area(sections), area(&below));
    (here < 0.95 * there).then(|| message::scan::section_worn(path, z, [here, there], BELOW, at))
}

/// The scan's points and faces as its format reads them, with the mm per
/// unit of its numbers (`units`, or a 3MF's own).
fn raw(
    f: &Fields<'_>,
    (path, file_at): (&str, Span),
    bytes: &[u8],
    units: &str,
    diags: &mut Diagnostics,
) -> Option<(Raw, f64)> {
    let (raw, scale) = match Format::of(path, bytes) {
        Format::Ply => (
            scan::ply::read(bytes).map_err(|e| ("PLY", e)),
            mm_per(units),
        ),
        Format::E57 => (scan::e57::read(bytes).map_err(|e| ("E57", e)), 1.0),
        Format::Xyz => (
            scan::xyz::read(bytes).map_err(|e| ("XYZ text", e)),
            mm_per(units),
        ),
        // The mesh solid's reader: the same errors, and a 3MF's own unit.
        Format::Stl | Format::ThreeMf => {
            let (tris, scale, _) = decode(f, (path, file_at), bytes, diags)?;
            (Ok(Raw::from_triangles(&tris)), scale)
        }
    };
    let raw = raw
        .map_err(|(what, e)| diags.push(message::scan::bad(path, what, &e, file_at)))
        .ok()?;
    Some((raw, scale))
}

/// The nominal of `register = mesh(…)`, placed, or of `register = NAME`,
/// a solid of the file cut into triangles, with its file or name and
/// where it is written: `Some(None)` when not written, `None` when
/// written wrong (reported).
fn nominal(
    f: &Fields<'_>,
    data: Option<&DataReader>,
    solid: SolidNamed<'_>,
    diags: &mut Diagnostics,
) -> Option<Option<(Named, String, Span)>> {
    let Some(v) = f.value(&field::REGISTER, diags) else {
        return (!f.has(&field::REGISTER)).then_some(None);
    };
    match &v.value {
        Value::Call(c) => {
            let (placed, path) = crate::sema::solid::mesh::placed(c, data, diags)?;
            Some(Some((Named::Mesh(Nominal::new(&placed)), path, v.span)))
        }
        Value::Symbol(name) => {
            let target = solid(name, v.span, diags)?;
            Some(Some((Named::Solid(target), name.clone(), v.span)))
        }
        other => {
            diags.push(message::target::not_a_nominal(other.got(), v.span));
            None
        }
    }
}

/// The part as designed a scan is registered to: a mesh's triangles, or a
/// solid of the file, cut into triangles near the scan when it is fitted.
enum Named {
    Mesh(Nominal),
    Solid(Arc<Target>),
}

/// What a best fit is asked: the scan's points, their declared placement,
/// the tolerance, and where the scan and the tolerance are written.
struct Fit<'a> {
    raw: &'a Raw,
    declared: Pose,
    tolerance: f64,
    scan: (&'a str, Span),
    tolerance_at: Option<Span>,
}

/// The scan's best fit to `nominal`: its whole pose and the record of the
/// fit; `None` when refused (reported).
fn fit(
    ask: &Fit<'_>,
    (nominal, nominal_path, register_at): &(Named, String, Span),
    diags: &mut Diagnostics,
) -> Option<(Pose, crate::ir::Registration)> {
    let cut;
    let nominal = match nominal {
        Named::Mesh(n) => n,
        Named::Solid(target) => {
            let placed: Vec<[f64; 3]> = ask
                .raw
                .vertices
                .iter()
                .map(|v| ask.declared.apply(v))
                .collect();
            let near = near_box(&placed).map(|(lo, hi, _)| [[lo[0], lo[1]], [hi[0], hi[1]]]);
            cut = Nominal::new(&target.triangles_near(near));
            &cut
        }
    };
    let names = message::scan::Registering {
        scan: ask.scan.0,
        nominal: nominal_path,
        at: ask.scan.1,
        register: *register_at,
    };
    let found = register(ask.raw, &ask.declared, nominal)
        .map_err(|e| diags.push(message::scan::fit_refused(&names, &e)))
        .ok()?;
    let pose = ask.declared.then(&found.moved);
    let (x, y, z) = pose.rot.euler_angles();
    let record = crate::ir::Registration {
        nominal: nominal_path.clone(),
        moved: [
            found.moved.shift.x,
            found.moved.shift.y,
            found.moved.shift.z,
        ],
        turned: found.moved.angles().map(f64::to_degrees),
        turn: [x, y, z].map(f64::to_degrees),
        at: [pose.at.x, pose.at.y, pose.at.z],
        rms: found.rms,
        max: found.max,
        inliers: found.share(),
        points: found.points,
        iterations: found.iterations,
        tolerance: ask.tolerance,
    };
    // A fit that turned the scan far from where it was declared may have
    // found a part that looks alike turned (a symmetric pad).
    let turned = found.moved.rot.angle().to_degrees();
    if turned > FAR_TURN && found.rms <= ask.tolerance {
        diags.push(message::scan::fit_turned_far(&names, turned, record.turn));
    }
    if found.rms > ask.tolerance {
        diags.push(message::scan::fit_too_loose(
            &names,
            &record,
            ask.tolerance_at,
        ));
        return None;
    }
    Some((pose, record))
}

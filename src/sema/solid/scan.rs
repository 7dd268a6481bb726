//! `scan(file, units, turn, at, cell, outlier)`: the measured surface a
//! repair is built on, read through the program's data reader in any of
//! the formats [`crate::geometry::scan`] reads, placed in the part's
//! coordinates and estimated on a grid (docs/repair.md).

use crate::diag::{message, Diagnostics};
use crate::geometry::mesh::Placement;
use crate::geometry::scan::{self, Estimate, Format, HeightField, Raw};
use crate::sema::data::Data;
use crate::sema::fields::Fields;
use crate::sema::model::ScanBase;
use crate::sema::schema::solid::{mesh, scan as field, SCAN};
use crate::sema::solid::mesh::{decode, triple};
use crate::sema::value::Call;
use crate::sema::DataReader;
use crate::span::Span;
use crate::units::mm_per;
use crate::units::Dim;

/// Reads `scan(…)` (the call `c` at `at`), its file through `data`.
pub fn read(
    c: &Call,
    at: Span,
    data: Option<&DataReader>,
    diags: &mut Diagnostics,
) -> Option<ScanBase> {
    let f = Fields::call(c, &SCAN, diags);
    let file = f.text(&field::FILE, diags);
    let units = f.word_or_default(&field::UNITS, diags);
    let turn = triple(&f, &mesh::TURN, Dim::ANGLE, diags);
    let place = triple(&f, &field::AT, Dim::LENGTH, diags);
    let cell = f.quantity_or_default(&field::CELL, diags);
    let outlier = f.quantity_or_default(&field::OUTLIER, diags);
    let ((path, file_at), units, turn, place, cell, outlier) =
        (file?, units?, turn?, place?, cell?, outlier?);
    let Some(read) = data else {
        diags.push(message::scan::no_reader(file_at));
        return None;
    };
    let bytes = read(&path, Data::Scan)
        .and_then(|b| Data::Scan.too_long(&b).map_or(Ok(b), Err))
        .map_err(|why| diags.push(message::scan::unreadable(&path, &why, file_at)))
        .ok()?;
    let format = Format::of(&path, &bytes);
    let (raw, scale) = match format {
        Format::Ply => (
            scan::ply::read(&bytes).map_err(|e| ("PLY", e)),
            mm_per(units),
        ),
        Format::Xyz => (
            scan::xyz::read(&bytes).map_err(|e| ("XYZ text", e)),
            mm_per(units),
        ),
        // The mesh solid's reader: the same errors, and a 3MF's own unit.
        Format::Stl | Format::ThreeMf => {
            let (tris, scale, _) = decode(&f, (&path, file_at), &bytes, diags)?;
            (Ok(Raw::from_triangles(&tris)), scale)
        }
    };
    drop(bytes);
    let raw = raw
        .map_err(|(what, e)| diags.push(message::scan::bad(&path, what, &e, file_at)))
        .ok()?;
    let placement = Placement {
        scale,
        turn: turn.0,
        at: place.0,
    };
    let est = Estimate { cell, outlier };
    let surface = HeightField::new(&raw, placement, est)
        .map_err(|e| diags.push(message::scan::grid(&path, &e, cell, at)))
        .ok()?;
    Some(ScanBase {
        path,
        surface: std::sync::Arc::new(surface),
        span: at,
    })
}

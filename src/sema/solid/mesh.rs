//! `mesh(file, units, turn, at)`: a solid given as an STL or 3MF mesh, read
//! through the program's data reader, checked a closed surface and placed
//! with its lowest point on the plate ([`crate::geometry::mesh`]).

use crate::diag::{message, Diagnostics};
use crate::geometry::mesh::{plate_z, stl, three_mf, Mesh, Placement, ON_PLATE};
use crate::sema::data::Data;
use crate::sema::fields::{self, Fields};
use crate::sema::model::MeshSolid;
use crate::sema::schema::solid::{mesh, MESH};
use crate::sema::value::{Call, Value};
use crate::sema::DataReader;
use crate::span::Span;
use crate::units::{Dim, Length};

/// Reads `mesh(…)` (the call `c` at `at`), its file through `data`.
pub fn read(
    c: &Call,
    at: Span,
    data: Option<&DataReader>,
    diags: &mut Diagnostics,
) -> Option<MeshSolid> {
    let f = Fields::call(c, &MESH, diags);
    let file = f.text(&mesh::FILE, diags);
    let units = f.word_or_default(&mesh::UNITS, diags);
    let turn = triple(&f, &mesh::TURN, Dim::ANGLE, diags);
    let place = triple(&f, &mesh::AT, Dim::LENGTH, diags);
    let ((path, file_at), _, turn, place) = (file?, units?, turn?, place?);
    let (tris, scale, file_unit) = load(&f, (&path, file_at), data, diags)?;
    let placement = Placement {
        scale,
        turn: turn.0,
        at: place.0,
    };
    let m = Mesh::new(&tris, placement)
        .map_err(|e| diags.push(message::mesh::fault(&path, &e, at)))
        .ok()?;
    let (lo, hi) = m.bounds();
    if lo[2].abs() > ON_PLATE {
        let where_ = place.1.unwrap_or(at);
        diags.push(message::mesh::not_on_plate(
            &path,
            lo[2],
            plate_z(place.0[2] - lo[2]),
            where_,
        ));
        return None;
    }
    Some(MeshSolid {
        path,
        mesh: std::sync::Arc::new(m),
        top: Length(hi[2]),
        scale,
        file_unit,
        span: at,
    })
}

/// The triangles of the mesh file `path` (named at `file_at`) that the call
/// `f` reads — through `data`, an STL or a 3MF — with the mm per unit of
/// its numbers and, for a 3MF, the unit it names: what the part's and a
/// fixture's `mesh(…)` share.
pub fn load(
    f: &Fields<'_>,
    (path, file_at): (&str, Span),
    data: Option<&DataReader>,
    diags: &mut Diagnostics,
) -> Option<(Vec<stl::Triangle>, f64, Option<&'static str>)> {
    let Some(read) = data else {
        diags.push(message::mesh::no_reader(file_at));
        return None;
    };
    let bytes = read(path, Data::Mesh)
        .and_then(|b| Data::Mesh.too_long(&b).map_or(Ok(b), Err))
        .map_err(|why| diags.push(message::mesh::unreadable(path, &why, file_at)))
        .ok()?;
    decode(f, (path, file_at), &bytes, diags)
}

/// The triangles of an STL's or a 3MF's `bytes` (read from `path`), with
/// the mm per unit of its numbers (`f`'s `units`, which a 3MF's own unit
/// must agree with) and, for a 3MF, the unit it names: what a mesh's and
/// a scan's readers share.
pub fn decode(
    f: &Fields<'_>,
    (path, file_at): (&str, Span),
    bytes: &[u8],
    diags: &mut Diagnostics,
) -> Option<(Vec<stl::Triangle>, f64, Option<&'static str>)> {
    let units = f.word_or_default(&mesh::UNITS, diags)?;
    let scale = crate::units::mm_per(units);
    if is_3mf(path, bytes) {
        let m = three_mf::read(bytes)
            .map_err(|e| diags.push(message::mesh::not_3mf(path, &e, file_at)))
            .ok()?;
        if let Some((w, w_at)) = f
            .has(&mesh::UNITS)
            .then(|| f.word(&mesh::UNITS, diags))
            .flatten()
        {
            if scale != m.scale {
                diags.push(message::mesh::units_disagree(path, m.unit, w, w_at));
                return None;
            }
        }
        Some((m.triangles, m.scale, Some(m.unit)))
    } else {
        let tris = stl::read(bytes)
            .map_err(|e| diags.push(message::mesh::not_stl(path, &e, file_at)))
            .ok()?;
        Some((tris, scale, None))
    }
}

/// Whether the mesh file is a 3MF: named `….3mf`, or a ZIP package (a
/// binary STL's 80-byte header could start so only by chance; ASCII never).
fn is_3mf(path: &str, bytes: &[u8]) -> bool {
    path.to_ascii_lowercase().ends_with(".3mf") || bytes.starts_with(b"PK\x03\x04")
}

/// A list of three quantities of `dim` (zeros when not written), and where
/// it is written.
pub fn triple(
    f: &Fields<'_>,
    field: &crate::sema::schema::Field,
    dim: Dim,
    diags: &mut Diagnostics,
) -> Option<([f64; 3], Option<Span>)> {
    let Some(v) = f.value(field, diags) else {
        return (!f.has(field)).then_some(([0.0; 3], None));
    };
    match &v.value {
        Value::List(items) if items.len() == 3 => {
            let c: Vec<_> = ["x", "y", "z"]
                .iter()
                .zip(items)
                .map(|(k, it)| fields::quantity(it, dim, k, diags))
                .collect();
            match c[..] {
                [Some(x), Some(y), Some(z)] => Some(([x, y, z], Some(v.span))),
                _ => None,
            }
        }
        other => {
            diags.push(message::mesh::not_three(
                field.key,
                &other.describe(),
                v.span,
            ));
            None
        }
    }
}

/// The triangles of `mesh(file, units, turn, at)` (the call `c`), placed
/// in the part's coordinates as written (mm), with the file's path: a
/// nominal or a target, which need not be a closed solid nor stand on the
/// plate.
pub fn placed(
    c: &Call,
    data: Option<&DataReader>,
    diags: &mut Diagnostics,
) -> Option<(Vec<[[f64; 3]; 3]>, String)> {
    let g = Fields::call(c, &MESH, diags);
    let file = g.text(&mesh::FILE, diags);
    let turn = triple(&g, &mesh::TURN, Dim::ANGLE, diags);
    let place = triple(&g, &mesh::AT, Dim::LENGTH, diags);
    let ((path, file_at), turn, place) = (file?, turn?, place?);
    let (tris, scale, _) = load(&g, (&path, file_at), data, diags)?;
    let [rx, ry, rz] = turn.0;
    let rot = nalgebra::Rotation3::from_euler_angles(rx, ry, rz);
    let at = nalgebra::Vector3::from(place.0);
    let placed = tris
        .iter()
        .map(|t| {
            t.map(|c| {
                let p = nalgebra::Vector3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
                let q = rot * (p * scale) + at;
                [q.x, q.y, q.z]
            })
        })
        .collect();
    Some((placed, path))
}

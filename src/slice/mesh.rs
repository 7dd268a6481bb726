//! A mesh's layers: each layer's section, cut halfway up the part of the
//! layer the mesh reaches (so the top layer, rounded up past the mesh, is
//! cut within it), as an outline and its holes of straight pieces — the
//! mesh's own polygons, nothing smoothed. A layer cut into separate
//! islands is [`Shape::Islands`].

use crate::diag::{message, Diagnostics};
use crate::geometry::mesh::{self, Loop};
use crate::sema::model::{Hole, MeshSolid, Outline, PlanarSlicing, RegionShape, Segment, Shape};
use crate::slice::MAX_TOTAL_POINTS;
use crate::units::Length;

/// A lower bound of the points a raster fill of the mesh `m`, scaled by
/// `k`, lays in the layers `lift` apart that build its height, with tracks
/// `offset` apart inside `contours` contours. The raster fills the layers'
/// sections less a band along their outlines `(contours + 1)·offset` wide
/// (contours, and half a track's room, with half as much again to spare),
/// whose volume over all layers is at most the mesh's surface area times
/// that width. A layer of raster area `A` no wider than the mesh's
/// diagonal `D` in plan spans at least `A/D` across any direction, so it
/// is crossed by at least `A/(D·offset) − 1` raster lines of two ends
/// each; the layers' areas times the lift add up to the volume. `None` for
/// a fill without raster, for which no such bound holds.
fn least_fill_points(m: &MeshSolid, k: f64, lift: f64, slicing: &PlanarSlicing) -> Option<f64> {
    slicing.infill.as_ref()?;
    let (lo, hi) = m.mesh.bounds();
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]) * k;
    let n = ((hi[2] - lo[2]) * k / lift).ceil();
    let band = (slicing.contours as f64 + 1.0) * slicing.offset.0;
    let raster = m.mesh.volume() * k.powi(3) - m.mesh.surface() * k * k * band;
    let lines = raster / (lift * diagonal * slicing.offset.0) - n;
    Some(2.0 * lines.max(0.0))
}

/// Refuses, before any layer is cut, a mesh whose fill would need more
/// points than a plan may hold ([`MAX_TOTAL_POINTS`]) by a lower bound
/// ([`least_fill_points`]): a part in the wrong `units` (metres for
/// millimetres) would otherwise be sliced for minutes and gigabytes before
/// the fill's own check stops it. The hint names a unit in which it fits.
pub fn plausible(
    m: &MeshSolid,
    n: usize,
    lift: Length,
    slicing: &PlanarSlicing,
    diags: &mut Diagnostics,
) -> Option<()> {
    // A `height` or `layers` below the mesh's top builds part of it: its
    // volume says nothing then.
    let whole = n as f64 >= crate::units::whole_count(m.top.0 / lift.0);
    let Some(least) = least_fill_points(m, 1.0, lift.0, slicing).filter(|_| whole) else {
        return Some(());
    };
    if least <= MAX_TOTAL_POINTS as f64 {
        return Some(());
    }
    let (lo, hi) = m.mesh.bounds();
    let size = [0, 1, 2].map(|i| hi[i] - lo[i]);
    // The units `mesh(units = …)` takes, with mm per unit: the ones a hint
    // may suggest.
    let units: Vec<(&str, f64)> = crate::sema::schema::solid::mesh::UNITS
        .kind
        .words()
        .unwrap_or(&[])
        .iter()
        .map(|&u| (u, crate::units::mm_per(u)))
        .collect();
    let unit = units.iter().find(|u| u.1 == m.scale).map(|u| u.0);
    let fits = units.iter().find(|&&(_, s)| {
        let k = s / m.scale;
        s != m.scale
            && least_fill_points(m, k, lift.0, slicing)
                .is_some_and(|p| p <= MAX_TOTAL_POINTS as f64)
    });
    let other = fits.map(|&(name, s)| (name, size.map(|x| x * s / m.scale)));
    diags.push(message::mesh::too_big(
        &m.path,
        message::mesh::TooBig {
            size,
            unit,
            layers: n,
            lift: lift.0,
            pitch: slicing.offset.0,
            least,
            max: MAX_TOTAL_POINTS,
            other,
        },
        m.span,
    ));
    None
}

/// The shape of each of `n` layers `lift` apart; `None` after reporting a
/// layer whose section is no region.
pub fn shapes(
    m: &MeshSolid,
    n: usize,
    lift: Length,
    diags: &mut Diagnostics,
) -> Option<Vec<Shape>> {
    let mut sections = m.mesh.sections();
    let mut out = Vec::with_capacity(n.min(1 << 16));
    for k in 0..n {
        let base = k as f64 * lift.0;
        let z = (base + ((k + 1) as f64 * lift.0).min(m.top.0)) / 2.0;
        let section = sections
            .loops(z)
            .and_then(mesh::islands)
            .map_err(|f| diags.push(message::mesh::section(&f, k, z, m.span)))
            .ok()?;
        out.push(layer_shape(section, m));
    }
    Some(out)
}

/// A layer's islands as its shape: the one island's shape, or
/// [`Shape::Islands`].
fn layer_shape(mut islands: Vec<mesh::Section>, m: &MeshSolid) -> Shape {
    if islands.len() == 1 {
        return shape(islands.remove(0), m);
    }
    Shape::Islands(islands.into_iter().map(|s| shape(s, m)).collect())
}

/// An island as a shape: a region when it has holes.
fn shape(s: mesh::Section, m: &MeshSolid) -> Shape {
    let outer = Shape::Outline(outline(&s.outline));
    if s.holes.is_empty() {
        return outer;
    }
    Shape::Region(Box::new(RegionShape {
        outline: outer,
        outline_span: m.span,
        holes: s
            .holes
            .iter()
            .map(|h| Hole {
                shape: Shape::Outline(outline(h)),
                span: m.span,
            })
            .collect(),
    }))
}

/// A loop as an outline of lines, back to its start.
fn outline(l: &Loop) -> Outline {
    let mm = |p: [f64; 2]| [Length(p[0]), Length(p[1])];
    Outline {
        start: mm(l[0]),
        segments: l[1..]
            .iter()
            .chain(std::iter::once(&l[0]))
            .map(|&p| Segment::Line { to: mm(p) })
            .collect(),
    }
}

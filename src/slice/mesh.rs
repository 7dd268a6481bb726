//! A mesh's layers: each layer's section, cut halfway up the part of the
//! layer the mesh reaches (so the top layer, rounded up past the mesh, is
//! cut within it), as an outline and its holes of straight pieces — the
//! mesh's own polygons, nothing smoothed. A layer cut into separate
//! islands is [`Shape::Islands`].

use crate::diag::message::mesh::Over;
use crate::diag::{message, Diagnostics};
use crate::geometry::mesh;
use crate::sema::model::MAX_LAYERS;
use crate::sema::model::{MeshSolid, PlanarSlicing, Shape};
use crate::slice::budget::{least_raster_points, Island, MAX_PROFILE_WORK};
use crate::slice::MAX_TOTAL_POINTS;
use crate::units::Length;

/// A lower bound of the points a raster fill of the mesh `m`, scaled by
/// `k`, lays in the layers `lift` apart that build its height, with tracks
/// `offset` apart inside `contours` contours. The raster fills the layers'
/// sections less a [`band`] along their outlines, whose volume over all
/// layers is at most the mesh's surface area times that width. A layer of
/// raster area `A` no wider than the mesh's diagonal `D` in plan spans at
/// least `A/D` across any direction, so it is crossed by at least
/// `A/(D·offset) − 1` raster lines of two ends each; the layers' areas
/// times the lift add up to the volume. `None` for a fill without raster,
/// for which no such bound holds.
fn least_fill_points(
    m: &MeshSolid,
    k: f64,
    lift: f64,
    (slicing, band): (&PlanarSlicing, f64),
) -> Option<f64> {
    slicing.infill.as_ref()?;
    let (lo, hi) = m.mesh.bounds();
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]) * k;
    let n = ((hi[2] - lo[2]) * k / lift).ceil();
    let raster = m.mesh.volume() * k.powi(3) - m.mesh.surface() * k * k * band;
    let lines = raster / (lift * diagonal * slicing.offset.0) - n;
    Some(2.0 * lines.max(0.0))
}

/// [`least_raster_points`] of one layer's section, with its raster lines
/// at `angle` (rad), island by island (so a tall narrow boss on a wide
/// plate counts its own lines, not the plate's).
fn least_section_points(
    islands: &[mesh::Section],
    angle: f64,
    (slicing, band): (&PlanarSlicing, f64),
) -> f64 {
    if slicing.infill.is_none() {
        return 0.0;
    }
    let (u, n) = ([angle.cos(), angle.sin()], [-angle.sin(), angle.cos()]);
    let extent = |l: &mesh::Loop, d: [f64; 2]| {
        let (lo, hi) = l
            .iter()
            .map(|p| p[0] * d[0] + p[1] * d[1])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        hi - lo
    };
    islands
        .iter()
        .map(|s| {
            let island = Island {
                area: s.area(),
                perimeter: s.perimeter(),
                along: extent(&s.outline, u),
                convex_width: (s.holes.is_empty() && convex(&s.outline))
                    .then(|| extent(&s.outline, n)),
            };
            least_raster_points(&island, band, slicing.offset.0)
        })
        .sum()
}

/// Whether the loop turns one way only at every corner.
fn convex(l: &mesh::Loop) -> bool {
    let k = l.len();
    let turn = |i: usize| {
        let (a, b, c) = (l[i], l[(i + 1) % k], l[(i + 2) % k]);
        (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
    };
    let (mut left, mut right) = (false, false);
    for i in 0..k {
        let t = turn(i);
        left |= t > 0.0;
        right |= t < 0.0;
    }
    !(left && right)
}

/// What slicing the mesh scaled by `k` into `layers` layers `lift` apart
/// costs, by bounds that take microseconds: the layers, the pieces of
/// outline their sections have ([`Mesh::crossings`]), and the fewest
/// points a raster fill lays ([`least_fill_points`], when the layers build
/// the whole mesh).
///
/// [`Mesh::crossings`]: crate::geometry::mesh::Mesh::crossings
fn cost(
    m: &MeshSolid,
    k: f64,
    (lift, layers): (f64, f64),
    fill: (&PlanarSlicing, f64),
) -> Option<Over> {
    let pieces = m
        .mesh
        .crossings(k, lift, layers.min(MAX_LAYERS as f64 + 1.0));
    // A `height` or `layers` below the mesh's top builds part of it: its
    // volume says nothing then.
    // Float noise (a mesh's f32 coordinates in inches) is no extra layer.
    let whole = layers >= crate::units::whole_count(m.top.0 * k / lift);
    let points = least_fill_points(m, k, lift, fill).filter(|_| whole);
    if layers > MAX_LAYERS as f64 {
        Some(Over::Layers {
            n: layers,
            max: MAX_LAYERS,
        })
    } else if pieces > MAX_PROFILE_WORK as f64 {
        Some(Over::Pieces {
            n: pieces,
            max: MAX_PROFILE_WORK,
        })
    } else {
        points
            .filter(|&p| p > MAX_TOTAL_POINTS as f64)
            .map(|least| Over::Points {
                least,
                max: MAX_TOTAL_POINTS,
            })
    }
}

/// Refuses, before any layer is cut, a mesh that would slice into more
/// layers, pieces of outline or points than a plan may have, by the
/// bounds of [`cost`] for `layers` layers `lift` apart: a part in the
/// wrong `units` (metres for millimetres, a 3MF in feet) would otherwise
/// be cut and filled for minutes and gigabytes before a limit stops it.
/// The hint names a unit in which it fits.
pub fn plausible(
    m: &MeshSolid,
    (layers, lift): (f64, Length),
    (slicing, band): (&PlanarSlicing, f64),
    diags: &mut Diagnostics,
) -> Option<()> {
    let fill = (slicing, band);
    let Some(over) = cost(m, 1.0, (lift.0, layers), fill) else {
        return Some(());
    };
    let whole = layers >= crate::units::whole_count(m.top.0 / lift.0);
    let fits = |k: f64| {
        let n = if whole {
            crate::units::whole_count(m.top.0 * k / lift.0).max(1.0)
        } else {
            layers
        };
        cost(m, k, (lift.0, n), fill).is_none()
    };
    diags.push(too_big(m, layers as usize, lift, slicing, over, fits));
    None
}

/// Whether the mesh is wide enough for a track: narrower than `2·inset`
/// (the band an outer contour keeps from the faces) nothing fits on any
/// layer, which fill would find only as `lmd::fill-empty` with a help to
/// make it larger. Refused here instead, with the size it would have in a
/// larger unit where a few beads `width` wide fit across it (a part drawn
/// in inches read in mm).
pub fn wide_enough(
    m: &MeshSolid,
    inset: f64,
    width: Length,
    diags: &mut Diagnostics,
) -> Option<()> {
    let (lo, hi) = m.mesh.bounds();
    let size = [0, 1, 2].map(|i| hi[i] - lo[i]);
    if inset <= 0.0 || size[0].min(size[1]) > 2.0 * inset {
        return Some(());
    }
    let (units, unit) = mesh_units(m);
    // Every larger unit in which it is a part a cell builds: a few beads
    // across, at most 2 m.
    let mut others: Vec<(&str, [f64; 3])> = units
        .iter()
        .filter(|&&(_, s)| s > m.scale)
        .map(|&(name, s)| (name, size.map(|x| x * s / m.scale)))
        .filter(|(_, big)| big[0].min(big[1]) >= 4.0 * width.0 && big[0].max(big[1]) <= 2000.0)
        .collect();
    // Inches first: the unit a drawing read as mm most often is in.
    others.sort_by_key(|&(name, _)| name != "in");
    diags.push(message::mesh::too_small(
        &m.path,
        message::mesh::TooSmall {
            size,
            unit,
            file_unit: m.file_unit,
            width: width.0,
            others,
        },
        m.span,
    ));
    None
}

/// The units `mesh(units = …)` takes, with mm per unit: the ones a hint may
/// suggest; and the one `m` is read in, if it is one of them.
fn mesh_units(m: &MeshSolid) -> (Vec<(&'static str, f64)>, Option<&'static str>) {
    let units: Vec<(&'static str, f64)> = crate::geometry::mesh::UNITS
        .iter()
        .map(|&u| (u, crate::units::mm_per(u)))
        .collect();
    let unit = units.iter().find(|u| u.1 == m.scale).map(|u| u.0);
    (units, unit)
}

/// The message for a mesh that is `over` a limit, with a unit in which
/// it `fits` (the scale from its own unit to that one).
fn too_big(
    m: &MeshSolid,
    layers: usize,
    lift: Length,
    slicing: &PlanarSlicing,
    over: Over,
    fits: impl Fn(f64) -> bool,
) -> crate::diag::Diagnostic {
    let (lo, hi) = m.mesh.bounds();
    let size = [0, 1, 2].map(|i| hi[i] - lo[i]);
    let (units, unit) = mesh_units(m);
    let other = units
        .iter()
        .find(|&&(_, s)| s != m.scale && fits(s / m.scale))
        .map(|&(name, s)| (name, size.map(|x| x * s / m.scale)));
    message::mesh::too_big(
        &m.path,
        message::mesh::TooBig {
            size,
            unit,
            file_unit: m.file_unit,
            layers,
            lift: lift.0,
            pitch: slicing.offset.0,
            over,
            other,
        },
        m.span,
    )
}

/// The shape of each of `n` layers `lift` apart; `None` after reporting a
/// layer whose section is no region, or sections whose fill would need
/// more points than a plan may hold (by [`least_section_points`], counted
/// as they are cut, so the cutting stops there) or pieces of outline past
/// the profile's budget.
pub fn shapes(
    m: &MeshSolid,
    (n, lift): (usize, Length),
    (slicing, band): (&PlanarSlicing, f64),
    diags: &mut Diagnostics,
) -> Option<Vec<Shape>> {
    let mut sections = m.mesh.sections();
    let mut out = Vec::with_capacity(n.min(1 << 16));
    let (mut least, mut pieces) = (0.0, 0usize);
    for k in 0..n {
        let base = k as f64 * lift.0;
        let z = (base + ((k + 1) as f64 * lift.0).min(m.top.0)) / 2.0;
        let section = sections
            .loops(z)
            .and_then(mesh::islands)
            .map_err(|f| diags.push(message::mesh::section(&f, k, z, m.span)))
            .ok()?;
        let angle = slicing
            .infill
            .map_or(0.0, |r| r.angle.0 + r.rotate.0 * k as f64);
        least += least_section_points(&section, angle, (slicing, band));
        pieces += section
            .iter()
            .flat_map(|s| std::iter::once(&s.outline).chain(&s.holes))
            .map(Vec::len)
            .sum::<usize>();
        let over = if least > MAX_TOTAL_POINTS as f64 {
            Some(Over::Points {
                least,
                max: MAX_TOTAL_POINTS,
            })
        } else {
            (pieces > MAX_PROFILE_WORK).then_some(Over::Pieces {
                n: pieces as f64,
                max: MAX_PROFILE_WORK,
            })
        };
        if let Some(over) = over {
            // The count so far scales with the lines a layer has and the
            // layers, each in proportion to the unit: a hint, not a bound.
            let fits = |s: f64| least * s * s <= MAX_TOTAL_POINTS as f64;
            diags.push(too_big(m, n, lift, slicing, over, fits));
            return None;
        }
        out.push(mesh::shape_of(section, m.span));
    }
    Some(out)
}

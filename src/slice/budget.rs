//! The points a planar plan's raster and contours lay, bounded from below
//! before any layer is filled: the raster from each layer's shape at its
//! raster angle, in the time it takes to turn the shape once (a fixed
//! profile once per angle); a fixed profile's contours from its first
//! layer's, filled once.
//! A plan the bound puts past the points a plan may hold
//! ([`super::MAX_TOTAL_POINTS`]) is refused before the fill, which would
//! otherwise lay, check and hold every layer until its count passed the
//! limit (a 2 m plate in 10 000 layers: minutes and gigabytes; the flange
//! with one contour in 100 000 layers: 100 s and 2.6 GB). A mesh's
//! sections are bounded the same way as they are cut ([`super::mesh`]).

use super::MAX_TOTAL_POINTS;
use crate::diag::{message, Diagnostics};
use crate::fill::{self, FillSpec, Seam};
use crate::geometry::outline;
use crate::geometry::region::Region;
use crate::sema::model::{Extrusion, LayerProfile, PlanarSlicing, Shape};
use std::collections::HashMap;

/// The band along a layer's outlines a raster leaves out: `(contours +
/// 1)·offset` wide (contours, and half a track's room, with half as much
/// again to spare), or as deep as the raster starts, `inset +
/// contours·offset` (the first contour's `inset` from the outline), when
/// that is deeper (tracks overlapping by more than half a width).
pub fn band(slicing: &PlanarSlicing, inset: f64) -> f64 {
    let (c, d) = (slicing.contours as f64, slicing.offset.0);
    ((c + 1.0) * d).max(inset + c * d)
}

/// What bounds an island's raster lines: its area and the length of its
/// loops, its extent along the lines and, when it is convex and has no
/// hole, its width across them.
pub struct Island {
    /// mm².
    pub area: f64,
    /// mm.
    pub perimeter: f64,
    /// Its extent along the raster lines, mm.
    pub along: f64,
    /// Its width across them, for a convex island without holes, mm.
    pub convex_width: Option<f64>,
}

/// The fewest points a raster of lines `offset` apart lays in `island`
/// less a `band` along its loops: a line meets the island along at most
/// its extent `L` that way, so at least `A/(L·offset) − 1` lines cross the
/// raster area `A` (the area less the perimeter times the band); a convex
/// island without holes keeps a convex raster area exactly the band
/// narrower on each side, crossed by at least `(W − 2·band)/offset − 1`
/// lines for its width `W`. Each line lays two ends at least.
pub fn least_raster_points(island: &Island, band: f64, offset: f64) -> f64 {
    let raster = island.area - island.perimeter * band;
    let by_area = raster / (island.along * offset) - 1.0;
    let by_width = island
        .convex_width
        .map_or(0.0, |w| (w - 2.0 * band) / offset - 1.0);
    let lines = by_area.max(by_width);
    if lines.is_finite() {
        2.0 * lines.max(0.0)
    } else {
        0.0
    }
}

/// A drawn layer's islands, measured for [`least_raster_points`] with its
/// lines at `angle` (rad).
fn islands(shape: &Shape, angle: f64, chord: f64) -> Vec<Island> {
    let parts = match shape {
        Shape::Islands(parts) => parts.iter().collect(),
        one => vec![one],
    };
    parts
        .into_iter()
        .map(|s| {
            // Turned so that the lines run along x.
            let r: Region = outline::region(s, chord).placed(-angle, [0.0, 0.0]);
            let b = r.bounds().unwrap_or([[0.0; 2]; 2]);
            let perimeter = r
                .polylines(chord)
                .iter()
                .map(|l| {
                    // Each loop closed, whether or not it repeats its start.
                    let closing = match (l.first(), l.last()) {
                        (Some(&a), Some(&b)) => dist(b, a),
                        _ => 0.0,
                    };
                    l.windows(2).map(|w| dist(w[0], w[1])).sum::<f64>() + closing
                })
                .sum();
            Island {
                area: r.area(),
                perimeter,
                along: b[1][0] - b[0][0],
                convex_width: None,
            }
        })
        .collect()
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// Most outline pieces over all layers: every piece of every layer is offset,
/// clipped and checked, so the work (and the profiles kept) grows with it.
pub const MAX_PROFILE_WORK: usize = 20_000_000;

/// The points one layer's contour passes lay, for a plan whose layers are
/// all `shape`: its passes filled once, as the slicer keeps them (points
/// closer than [`super::DISTINCT`] are one, [`super::dedup_points`]), one a pass less (a
/// pass that starts at another seam may split an edge).
fn contour_points(shape: &Shape, slicing: &PlanarSlicing, inset: f64) -> f64 {
    if slicing.contours == 0 {
        return 0.0;
    }
    let chord = slicing.chord_error.0;
    let parts = match shape {
        Shape::Islands(parts) => parts.iter().collect(),
        one => vec![one],
    };
    let spec = FillSpec {
        inset,
        contours: slicing.contours,
        offset: slicing.offset.0,
        raster: None,
        seam: Seam::Lowest,
    };
    parts
        .into_iter()
        .map(
            |s| match fill::fill_region(&outline::region(s, chord), &spec, chord) {
                Ok(tracks) => tracks
                    .into_iter()
                    .map(|mut t| {
                        super::dedup_points(&mut t.points);
                        t.points.len().saturating_sub(1)
                    })
                    .sum::<usize>() as f64,
                Err(_) => 0.0,
            },
        )
        .sum()
}

/// Refuses, before any layer is filled, a drawn profile's plan (the
/// layers' `shapes`, `fixed` where they are all one) whose raster and
/// contours lay more points than a plan may hold: the raster by
/// [`least_raster_points`] on every layer (a fixed profile measured once
/// per raster angle), the contours of a fixed profile as its first
/// layer's ([`contour_points`]; a profile that changes from layer to
/// layer is bounded by its raster alone). A mesh's layers were bounded as
/// they were cut.
pub fn planar(
    (shapes, fixed): (&[Shape], bool),
    extrusion: &Extrusion,
    slicing: &PlanarSlicing,
    [band, inset]: [f64; 2],
    diags: &mut Diagnostics,
) -> Option<()> {
    if matches!(extrusion.profile, LayerProfile::Mesh(_)) {
        return Some(());
    }
    let contours = match (fixed, shapes.first()) {
        (true, Some(shape)) => shapes.len() as f64 * contour_points(shape, slicing, inset),
        _ => 0.0,
    };
    let raster = slicing.infill.map_or(0.0, |r| {
        least_raster(shapes, fixed, slicing, [r.angle.0, r.rotate.0, band])
    });
    let least = raster + contours;
    if least <= MAX_TOTAL_POINTS as f64 {
        return Some(());
    }
    diags.push(message::slicing::too_many_planned_points(
        message::slicing::PointBudget {
            layers: shapes.len(),
            offset: slicing.offset,
            least,
            contours,
            max: MAX_TOTAL_POINTS,
        },
        slicing.span,
    ));
    None
}

/// [`least_raster_points`] over every layer, its lines at `angle` turned
/// by `rotate` a layer (rad), leaving `band` along the outlines.
fn least_raster(
    shapes: &[Shape],
    fixed: bool,
    slicing: &PlanarSlicing,
    [angle, rotate, band]: [f64; 3],
) -> f64 {
    let chord = slicing.chord_error.0;
    let mut by_angle: HashMap<u64, f64> = HashMap::new();
    let mut least = 0.0;
    for (k, shape) in shapes.iter().enumerate() {
        let angle = (angle + rotate * k as f64).rem_euclid(std::f64::consts::PI);
        let measure = || {
            islands(shape, angle, chord)
                .iter()
                .map(|i| least_raster_points(i, band, slicing.offset.0))
                .sum::<f64>()
        };
        least += match fixed {
            true => *by_angle.entry(angle.to_bits()).or_insert_with(measure),
            false => measure(),
        };
    }
    least
}

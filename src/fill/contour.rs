//! Contour passes: the region offset inward, pass by pass. Each loop of a
//! pass is one closed track, outer loops counter-clockwise and hole loops
//! clockwise (the part on the left, as the nozzle goes), starting at the
//! seam the [`Seam`] rule puts it.

use super::{spend, FillError, FillSpec, Seam, Track, TrackKind};
use crate::geometry::profile::Profile;
use crate::geometry::region::Region;
use std::cmp::Ordering;

/// The contour tracks, outermost pass first; `points_left` is the layer's
/// point budget, spent here.
pub(super) fn passes(
    region: &Region,
    spec: &FillSpec,
    chord_error: f64,
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let mut tracks = Vec::new();
    for index in 0..spec.contours {
        // Each pass offsets the outline itself, not the pass before it, so
        // that rounding does not accumulate from pass to pass.
        let loops = region.offset_inward(spec.inset + index as f64 * spec.offset);
        if loops.is_empty() {
            // Offsets nest: every pass further in is empty too.
            break;
        }
        let mut pass: Vec<Vec<[f64; 2]>> = Vec::new();
        for (l, hole) in loops.loops() {
            let points = closed_loop(l, hole, spec.seam, chord_error);
            spend(points_left, points.len())?;
            pass.push(points);
        }
        pass.sort_by(|a, b| by_yx(a[0], b[0]));
        tracks.extend(pass.into_iter().map(|points| Track {
            kind: TrackKind::Contour { index },
            points,
            link: None,
        }));
    }
    Ok(tracks)
}

/// The open loop `points` started `d` (mm) further along it, wrapping
/// round: the point there is added (unless it is one already) and the loop
/// runs on from it through the same points.
fn along(points: Vec<[f64; 2]>, d: f64) -> Vec<[f64; 2]> {
    let n = points.len();
    let len = |i: usize| {
        let (a, b) = (points[i], points[(i + 1) % n]);
        (b[0] - a[0]).hypot(b[1] - a[1])
    };
    let perimeter: f64 = (0..n).map(len).sum();
    if n < 2 || perimeter.is_nan() || perimeter <= 0.0 {
        return points;
    }
    let mut left = d.rem_euclid(perimeter);
    for i in 0..n {
        let l = len(i);
        if left < l {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let t = left / l;
            let start = if t > 1e-9 {
                [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
            } else {
                a
            };
            let mut out = Vec::with_capacity(n + 1);
            out.push(start);
            out.extend((1..=n).map(|j| points[(i + j) % n]).filter(|&p| p != start));
            return out;
        }
        left -= l;
    }
    points
}

/// Orders points by y, then x.
fn by_yx(a: [f64; 2], b: [f64; 2]) -> Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// The loop flattened, clockwise for a hole, starting at its seam and closed
/// by repeating that point.
fn closed_loop(l: &Profile, hole: bool, seam: Seam, chord_error: f64) -> Vec<[f64; 2]> {
    let start = match seam {
        Seam::Lowest | Seam::Along(_) => None,
        Seam::Toward(angle) => l.support(angle),
        Seam::SharpestCorner => l.sharpest_corner(),
    };
    let mut points = match start {
        Some((piece, at)) => {
            let mut points = l.starting_at(piece, at).polyline(chord_error);
            if hole && points.len() > 1 {
                points[1..].reverse();
            }
            points
        }
        None => {
            let mut points = l.polyline(chord_error);
            if hole {
                points.reverse();
            }
            let first = (0..points.len())
                .min_by(|&i, &j| by_yx(points[i], points[j]))
                .unwrap_or(0);
            points.rotate_left(first);
            match seam {
                Seam::Along(d) => along(points, d),
                _ => points,
            }
        }
    };
    if let Some(&first) = points.first() {
        points.push(first);
    }
    points
}

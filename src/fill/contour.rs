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

/// Orders points by y, then x.
fn by_yx(a: [f64; 2], b: [f64; 2]) -> Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// The loop flattened, clockwise for a hole, starting at its seam and closed
/// by repeating that point.
fn closed_loop(l: &Profile, hole: bool, seam: Seam, chord_error: f64) -> Vec<[f64; 2]> {
    let start = match seam {
        Seam::Lowest => None,
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
            points
        }
    };
    if let Some(&first) = points.first() {
        points.push(first);
    }
    points
}

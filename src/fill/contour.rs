//! Contour passes: the outline offset inward, pass by pass.

use super::{spend, FillError, FillSpec, Track, TrackKind};
use crate::geometry::profile::Profile;
use std::cmp::Ordering;

/// The contour tracks, outermost pass first; `points_left` is the layer's
/// point budget, spent here.
pub(super) fn passes(
    profile: &Profile,
    spec: &FillSpec,
    chord_error: f64,
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let mut tracks = Vec::new();
    for index in 0..spec.contours {
        // Each pass offsets the outline itself, not the pass before it, so
        // that rounding does not accumulate from pass to pass.
        let loops = profile.offset_inward(spec.inset + index as f64 * spec.offset);
        if loops.is_empty() {
            // Offsets nest: every pass further in is empty too.
            break;
        }
        let mut pass: Vec<Vec<[f64; 2]>> = Vec::with_capacity(loops.len());
        for l in &loops {
            let points = closed_loop(l, chord_error);
            spend(points_left, points.len())?;
            pass.push(points);
        }
        pass.sort_by(|a, b| by_yx(a[0], b[0]));
        tracks.extend(pass.into_iter().map(|points| Track {
            kind: TrackKind::Contour { index },
            points,
        }));
    }
    Ok(tracks)
}

/// Orders points by y, then x.
fn by_yx(a: [f64; 2], b: [f64; 2]) -> Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// The loop flattened, starting at its point with the smallest `(y, x)` and
/// closed by repeating that point.
fn closed_loop(l: &Profile, chord_error: f64) -> Vec<[f64; 2]> {
    let mut points = l.polyline(chord_error);
    let start = (0..points.len())
        .min_by(|&i, &j| by_yx(points[i], points[j]))
        .unwrap_or(0);
    points.rotate_left(start);
    if let Some(&first) = points.first() {
        points.push(first);
    }
    points
}

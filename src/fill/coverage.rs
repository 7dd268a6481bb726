//! Gaps a fill leaves: points where a track's centre line may run (the
//! profile inset by the fill's inset) that lie farther than a bead width
//! from every track, so the spot left there is at least a bead wide.
//!
//! The region is sampled on a square grid (pitch `reach / 2`, coarser on
//! huge layers: at most `max_samples`, and never more than [`MAX_SAMPLES`],
//! points a layer) and each sample asks
//! a uniform grid of the tracks' segments for a segment within `reach`; the
//! cost is linear in samples plus track points.

use super::{raster, Track};
use crate::geometry::profile::Profile;
use std::collections::HashMap;

/// Most points sampled on a layer.
pub const MAX_SAMPLES: usize = 40_000;

/// A spot the tracks do not reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// The sampled point, mm.
    pub at: [f64; 2],
    /// Its distance to the nearest track's centre line, mm.
    pub distance: f64,
}

/// The sampled point of `profile` inset by `inset` farthest from every track,
/// if any lies farther than `reach` (of many such points, the farthest of a
/// spread of 256; ties go to the first in rows of increasing y, then
/// x).
pub fn gap(
    profile: &Profile,
    inset: f64,
    tracks: &[Track],
    reach: f64,
    max_samples: usize,
) -> Option<Gap> {
    if !(reach.is_finite() && reach > 0.0) {
        return None;
    }
    let region = profile.offset_inward(inset);
    let samples = raster::samples(&region, reach / 2.0, max_samples.min(MAX_SAMPLES));
    let segments: Vec<[[f64; 2]; 2]> = tracks
        .iter()
        .flat_map(|t| match t.points.as_slice() {
            [p] => vec![[*p, *p]],
            pts => pts.windows(2).map(|w| [w[0], w[1]]).collect(),
        })
        .filter(|s| s.iter().flatten().all(|v| v.is_finite()))
        .collect();
    let grid = Grid::new(&segments, reach);
    let uncovered: Vec<[f64; 2]> = samples
        .into_iter()
        .filter(|&p| !grid.any_within(&segments, p, reach))
        .collect();
    // The farthest of at most MEASURED of them, spread over all: the exact
    // distance is a search over every segment.
    let stride = uncovered.len().div_ceil(MEASURED).max(1);
    uncovered
        .iter()
        .step_by(stride)
        .map(|&at| Gap {
            at,
            distance: segments
                .iter()
                .map(|s| distance(at, s))
                .fold(f64::INFINITY, f64::min),
        })
        .fold(None, |worst: Option<Gap>, g| match worst {
            Some(w) if w.distance >= g.distance => Some(w),
            _ => Some(g),
        })
}

/// Most uncovered samples whose distance is measured exactly.
const MEASURED: usize = 256;

/// Distance from `p` to the segment `s`.
fn distance(p: [f64; 2], s: &[[f64; 2]; 2]) -> f64 {
    let [a, b] = *s;
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = ux * ux + uy * uy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a[0] + t * ux - p[0]).hypot(a[1] + t * uy - p[1])
}

/// Segments by the cells of side `cell` they pass through.
struct Grid {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<u32>>,
}

impl Grid {
    fn new(segments: &[[[f64; 2]; 2]], cell: f64) -> Grid {
        let mut cells: HashMap<(i64, i64), Vec<u32>> = HashMap::new();
        for (i, s) in segments.iter().enumerate() {
            // Points every half cell: each point of the segment is within a
            // quarter cell of one, so a query two cells round finds it.
            let len = (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]);
            let steps = ((len / (cell / 2.0)).ceil() as usize).clamp(1, 1 << 20);
            let mut last = None;
            for k in 0..=steps {
                let f = k as f64 / steps as f64;
                let p = [
                    s[0][0] + f * (s[1][0] - s[0][0]),
                    s[0][1] + f * (s[1][1] - s[0][1]),
                ];
                let key = key(p, cell);
                if last != Some(key) {
                    let v = cells.entry(key).or_default();
                    if v.last() != Some(&(i as u32)) {
                        v.push(i as u32);
                    }
                    last = Some(key);
                }
            }
        }
        Grid { cell, cells }
    }

    fn any_within(&self, segments: &[[[f64; 2]; 2]], p: [f64; 2], reach: f64) -> bool {
        let (cx, cy) = key(p, self.cell);
        (-2..=2).any(|dx| {
            (-2..=2).any(|dy| {
                self.cells.get(&(cx + dx, cy + dy)).is_some_and(|v| {
                    v.iter()
                        .any(|&i| distance(p, &segments[i as usize]) <= reach)
                })
            })
        })
    }
}

fn key(p: [f64; 2], cell: f64) -> (i64, i64) {
    // `as` saturates: far-off points share the edge cells, which is only slower.
    ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fill::TrackKind;

    fn line(a: [f64; 2], b: [f64; 2]) -> Track {
        Track {
            kind: TrackKind::Infill,
            points: vec![a, b],
        }
    }

    #[test]
    fn a_rectangle_raster_a_bead_apart_has_no_gap() {
        let p = Profile::rectangle(20.0, 10.0);
        let tracks: Vec<Track> = (0..=5)
            .map(|n| line([0.0, 2.0 * n as f64], [20.0, 2.0 * n as f64]))
            .collect();
        assert_eq!(gap(&p, 0.0, &tracks, 2.2, MAX_SAMPLES), None);
    }

    #[test]
    fn a_missing_line_leaves_a_gap_where_it_should_be() {
        let p = Profile::rectangle(20.0, 10.0);
        // Lines at y = 0, 2, 8, 10: the band 2 < y < 8 is 6 mm wide, so its
        // middle is 3 mm from the nearest track.
        let tracks: Vec<Track> = [0.0, 2.0, 8.0, 10.0]
            .iter()
            .map(|&y| line([0.0, y], [20.0, y]))
            .collect();
        let g = gap(&p, 0.0, &tracks, 2.2, MAX_SAMPLES).expect("a gap");
        assert!(g.at[1] > 4.2 && g.at[1] < 5.8, "{g:?}");
        assert!(g.distance > 2.2 && g.distance <= 3.0, "{g:?}");
    }

    #[test]
    fn long_diagonal_tracks_are_found_from_any_sample() {
        // Lines y = x + c, 2 mm apart in c (1.41 mm apart), each one segment
        // across the whole square: every sample is within reach of one.
        let p = Profile::rectangle(100.0, 100.0);
        let tracks: Vec<Track> = (-50..=50)
            .map(|n| {
                let c = 2.0 * n as f64;
                line([-10.0, -10.0 + c], [110.0, 110.0 + c])
            })
            .collect();
        assert_eq!(gap(&p, 0.0, &tracks, 1.0, MAX_SAMPLES), None);
        // Without every other line the spacing is 2.83 mm: gaps 1.41 mm from both.
        let half: Vec<Track> = tracks.into_iter().step_by(2).collect();
        let g = gap(&p, 0.0, &half, 1.0, MAX_SAMPLES).expect("a gap");
        assert!(
            g.distance > 1.0 && g.distance <= 2f64.sqrt() + 1e-9,
            "{g:?}"
        );
    }
}

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
use crate::geometry::region::Region;

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
/// x): [`gap_in`] of the profile alone.
pub fn gap(
    profile: &Profile,
    inset: f64,
    tracks: &[Track],
    reach: f64,
    max_samples: usize,
) -> Option<Gap> {
    gap_in(
        &Region::from(profile.clone()),
        inset,
        tracks,
        reach,
        max_samples,
    )
}

/// [`gap`] over a region with holes: samples inside a hole are not the
/// part's. A link that deposits (laser on) covers as its tracks do.
pub fn gap_in(
    region: &Region,
    inset: f64,
    tracks: &[Track],
    reach: f64,
    max_samples: usize,
) -> Option<Gap> {
    if !(reach.is_finite() && reach > 0.0) {
        return None;
    }
    let region = region.offset_inward(inset);
    let samples = raster::samples(&region, reach / 2.0, max_samples.min(MAX_SAMPLES));
    let segments: Vec<[[f64; 2]; 2]> = deposited(tracks)
        .filter(|s| s.iter().flatten().all(|v| v.is_finite()))
        .collect();
    let grid = Grid::new(&segments, &samples, reach);
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

/// Every segment laid with the laser on: the tracks', and the links' that
/// deposit (from a track's end through the link to the next one's start).
fn deposited(tracks: &[Track]) -> impl Iterator<Item = [[f64; 2]; 2]> + '_ {
    tracks.iter().enumerate().flat_map(move |(i, t)| {
        let mut segs: Vec<[[f64; 2]; 2]> = match t.points.as_slice() {
            [p] => vec![[*p, *p]],
            pts => pts.windows(2).map(|w| [w[0], w[1]]).collect(),
        };
        let next = tracks.get(i + 1).and_then(|n| n.points.first());
        if let (Some(l), Some(&last), Some(&next)) = (&t.link, t.points.last(), next) {
            if l.laser {
                let path: Vec<[f64; 2]> = std::iter::once(last)
                    .chain(l.via.iter().copied())
                    .chain(std::iter::once(next))
                    .collect();
                segs.extend(path.windows(2).map(|w| [w[0], w[1]]));
            }
        }
        segs
    })
}

/// Most uncovered samples whose distance is measured exactly.
const MEASURED: usize = 256;

/// Distance from `p` to the segment `s`.
fn distance(p: [f64; 2], s: &[[f64; 2]; 2]) -> f64 {
    distance2(p, s).sqrt()
}

/// Segments by the cells of side `cell` they pass through, in a dense grid
/// over the samples' bounding box (segments outside it are clamped to its
/// edge cells, which only costs time).
struct Grid {
    cell: f64,
    origin: [f64; 2],
    nx: usize,
    ny: usize,
    /// Segment indices of cell `iy * nx + ix`, as ranges into `items`.
    starts: Vec<u32>,
    items: Vec<u32>,
}

/// Most (cell, segment) pairs the grid may hold; coarser cells beyond.
const MAX_PAIRS: f64 = 8_000_000.0;

/// Most cells the grid may have; coarser cells beyond.
const MAX_CELLS: f64 = 4_000_000.0;

impl Grid {
    fn new(segments: &[[[f64; 2]; 2]], samples: &[[f64; 2]], reach: f64) -> Grid {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in samples {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !(lo[0].is_finite() && hi[0].is_finite() && lo[1].is_finite() && hi[1].is_finite()) {
            lo = [0.0; 2];
            hi = [0.0; 2];
        }
        // Cells at least `reach` wide, so a query two cells round suffices;
        // wider when the cells or the (cell, segment) pairs would be too many
        // (a plate tens of metres wide), which only makes queries slower.
        let area = (hi[0] - lo[0] + 4.0 * reach) * (hi[1] - lo[1] + 4.0 * reach);
        let length: f64 = segments
            .iter()
            .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
            .sum();
        let cell = reach
            .max((area / MAX_CELLS).sqrt())
            .max(2.0 * length / MAX_PAIRS);
        let origin = [lo[0] - 2.0 * cell, lo[1] - 2.0 * cell];
        let nx = (((hi[0] - origin[0]) / cell).floor() as usize + 3).max(1);
        let ny = (((hi[1] - origin[1]) / cell).floor() as usize + 3).max(1);
        let mut grid = Grid {
            cell,
            origin,
            nx,
            ny,
            starts: Vec::new(),
            items: Vec::new(),
        };
        // Two passes, counting then filling, keep it to two flat vectors.
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, s) in segments.iter().enumerate() {
            // Points every half cell: each point of the segment is within a
            // quarter cell of one, so a query two cells round finds it.
            let len = (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]);
            let steps = ((len / (cell / 2.0)).ceil() as usize).clamp(1, 1 << 20);
            let mut last = u32::MAX;
            for k in 0..=steps {
                let f = k as f64 / steps as f64;
                let p = [
                    s[0][0] + f * (s[1][0] - s[0][0]),
                    s[0][1] + f * (s[1][1] - s[0][1]),
                ];
                let c = grid.index(grid.key(p));
                if c != last {
                    pairs.push((c, i as u32));
                    last = c;
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        grid.starts = vec![0; nx * ny + 1];
        for &(c, _) in &pairs {
            grid.starts[c as usize + 1] += 1;
        }
        for k in 1..grid.starts.len() {
            grid.starts[k] += grid.starts[k - 1];
        }
        grid.items = pairs.into_iter().map(|(_, i)| i).collect();
        grid
    }

    fn key(&self, p: [f64; 2]) -> (usize, usize) {
        // `as` saturates (and sends NaN to 0): far-off points land on the
        // edge cells.
        let ix = ((p[0] - self.origin[0]) / self.cell).floor() as usize;
        let iy = ((p[1] - self.origin[1]) / self.cell).floor() as usize;
        (ix.min(self.nx - 1), iy.min(self.ny - 1))
    }

    fn index(&self, (ix, iy): (usize, usize)) -> u32 {
        (iy * self.nx + ix) as u32
    }

    fn any_within(&self, segments: &[[[f64; 2]; 2]], p: [f64; 2], reach: f64) -> bool {
        let (cx, cy) = self.key(p);
        let r2 = reach * reach;
        // The own cell first: most samples find their track there.
        let near = |ix: usize, iy: usize| {
            let c = self.index((ix, iy)) as usize;
            self.items[self.starts[c] as usize..self.starts[c + 1] as usize]
                .iter()
                .any(|&i| distance2(p, &segments[i as usize]) <= r2)
        };
        if near(cx, cy) {
            return true;
        }
        let (x0, x1) = (cx.saturating_sub(2), (cx + 2).min(self.nx - 1));
        let (y0, y1) = (cy.saturating_sub(2), (cy + 2).min(self.ny - 1));
        (y0..=y1).any(|iy| (x0..=x1).any(|ix| (ix, iy) != (cx, cy) && near(ix, iy)))
    }
}

/// Squared distance from `p` to the segment `s`.
fn distance2(p: [f64; 2], s: &[[f64; 2]; 2]) -> f64 {
    let [a, b] = *s;
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = ux * ux + uy * uy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (dx, dy) = (a[0] + t * ux - p[0], a[1] + t * uy - p[1]);
    dx * dx + dy * dy
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fill::TrackKind;

    fn line(a: [f64; 2], b: [f64; 2]) -> Track {
        Track {
            kind: TrackKind::Infill,
            points: vec![a, b],
            link: None,
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

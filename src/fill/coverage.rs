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

/// Segments by the cells they pass through, in a grid over the samples'
/// bounding box laid out along the longest segment (a raster's lines,
/// which then each lie in a row or two): cells at least `reach` high and
/// wide, and at most [`COLUMNS`] across, so a raster line enters a few
/// dozen cells however long it is, and the grid costs time in proportion
/// to the segments and samples, not the length of track (segments
/// outside the box are clamped to its edge cells, which only costs time).
/// A 2 m plate's layer once cost a quarter of a second here.
struct Grid {
    /// The grid's x direction, and its y direction.
    axes: [[f64; 2]; 2],
    /// A cell's width and height.
    cell: [f64; 2],
    /// The corner of cell (0, 0), in the grid's frame.
    origin: [f64; 2],
    nx: usize,
    ny: usize,
    /// Segment indices of cell `iy * nx + ix`, as ranges into `items`.
    starts: Vec<u32>,
    items: Vec<u32>,
}

/// Most columns across the grid.
const COLUMNS: f64 = 64.0;

/// Most rows up the grid; lower cells beyond.
const MAX_ROWS: f64 = 65_536.0;

/// Most (cell, segment) pairs the grid may hold; larger cells beyond.
const MAX_PAIRS: f64 = 8_000_000.0;

impl Grid {
    fn new(segments: &[[[f64; 2]; 2]], samples: &[[f64; 2]], reach: f64) -> Grid {
        let longest = segments
            .iter()
            .map(|s| [s[1][0] - s[0][0], s[1][1] - s[0][1]])
            .max_by(|a, b| a[0].hypot(a[1]).total_cmp(&b[0].hypot(b[1])))
            .filter(|d| d[0].hypot(d[1]) > 0.0)
            .map_or([1.0, 0.0], |d| {
                let l = d[0].hypot(d[1]);
                [d[0] / l, d[1] / l]
            });
        let axes = [longest, [-longest[1], longest[0]]];
        let turn = |p: [f64; 2]| [0, 1].map(|k| p[0] * axes[k][0] + p[1] * axes[k][1]);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in samples.iter().map(|&p| turn(p)) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !(lo.iter().chain(&hi).all(|v| v.is_finite())) {
            (lo, hi) = ([0.0; 2], [0.0; 2]);
        }
        let turned: Vec<[[f64; 2]; 2]> = segments.iter().map(|s| s.map(turn)).collect();
        let span = [0, 1].map(|k| hi[k] - lo[k] + 4.0 * reach);
        let mut cell = [reach.max(span[0] / COLUMNS), reach.max(span[1] / MAX_ROWS)];
        // Cells twice as large while the pairs would be too many (a plate
        // tens of metres wide with a fine outline): queries only slower.
        let mut grid = loop {
            let origin = [0, 1].map(|k| lo[k] - 2.0 * cell[k]);
            let n = [0, 1].map(|k| (((hi[k] - origin[k]) / cell[k]).floor() as usize + 3).max(1));
            let grid = Grid {
                axes,
                cell,
                origin,
                nx: n[0],
                ny: n[1],
                starts: Vec::new(),
                items: Vec::new(),
            };
            let pairs: f64 = turned.iter().map(|s| grid.span_cells(s) as f64).sum();
            // Each segment is in a cell or two at least, however large.
            let least = 2.0 * turned.len() as f64;
            if pairs <= MAX_PAIRS.max(least) || (grid.nx <= 3 && grid.ny <= 3) {
                break grid;
            }
            cell = cell.map(|c| c * 2.0);
        };
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, s) in turned.iter().enumerate() {
            grid.cells_of(s, |c| pairs.push((c, i as u32)));
        }
        pairs.sort_unstable();
        pairs.dedup();
        grid.starts = vec![0; grid.nx * grid.ny + 1];
        for &(c, _) in &pairs {
            grid.starts[c as usize + 1] += 1;
        }
        for k in 1..grid.starts.len() {
            grid.starts[k] += grid.starts[k - 1];
        }
        grid.items = pairs.into_iter().map(|(_, i)| i).collect();
        grid
    }

    /// The rows (`k = 1`) or columns (`k = 0`) the coordinates `a ..= b`
    /// of the grid's frame fall in, clamped to the grid.
    fn keys(&self, k: usize, a: f64, b: f64) -> (usize, usize) {
        let n = [self.nx, self.ny][k];
        // `as` saturates (and sends NaN to 0): far-off points land on the
        // edge cells.
        let key = |v: f64| (((v - self.origin[k]) / self.cell[k]).floor() as usize).min(n - 1);
        (key(a.min(b)), key(a.max(b)))
    }

    /// Calls `f` with every cell the turned segment `s` passes through:
    /// row by row, the columns of the piece of it within the row.
    fn cells_of(&self, s: &[[f64; 2]; 2], mut f: impl FnMut(u32)) {
        let [a, b] = *s;
        let (r0, r1) = self.keys(1, a[1], b[1]);
        for iy in r0..=r1 {
            // The piece within the row's band (the edge rows reach out to
            // every segment clamped into them).
            let y0 = if iy == 0 {
                f64::NEG_INFINITY
            } else {
                self.origin[1] + iy as f64 * self.cell[1]
            };
            let y1 = if iy + 1 == self.ny {
                f64::INFINITY
            } else {
                y0.max(self.origin[1]) + self.cell[1]
            };
            let (x0, x1) = if a[1] == b[1] {
                (a[0], b[0])
            } else {
                let t = |y: f64| ((y - a[1]) / (b[1] - a[1])).clamp(0.0, 1.0);
                let (ta, tb) = (t(y0), t(y1));
                (a[0] + ta * (b[0] - a[0]), a[0] + tb * (b[0] - a[0]))
            };
            let (c0, c1) = self.keys(0, x0, x1);
            for ix in c0..=c1 {
                f((iy * self.nx + ix) as u32);
            }
        }
    }

    /// How many cells [`Grid::cells_of`] gives for `s`.
    fn span_cells(&self, s: &[[f64; 2]; 2]) -> usize {
        let mut n = 0;
        self.cells_of(s, |_| n += 1);
        n
    }

    fn any_within(&self, segments: &[[[f64; 2]; 2]], p: [f64; 2], reach: f64) -> bool {
        let q = [0, 1].map(|k| p[0] * self.axes[k][0] + p[1] * self.axes[k][1]);
        let (cx, _) = self.keys(0, q[0], q[0]);
        let (cy, _) = self.keys(1, q[1], q[1]);
        let r2 = reach * reach;
        let near = |ix: usize, iy: usize| {
            let c = iy * self.nx + ix;
            self.items[self.starts[c] as usize..self.starts[c + 1] as usize]
                .iter()
                .any(|&i| distance2(p, &segments[i as usize]) <= r2)
        };
        // The own cell first: most samples find their track there. Cells
        // two round make up for the turn's rounding.
        if near(cx, cy) {
            return true;
        }
        let (x0, x1) = (cx.saturating_sub(2), (cx + 2).min(self.nx - 1));
        let (y0, y1) = (cy.saturating_sub(2), (cy + 2).min(self.ny - 1));
        (y0..=y1).any(|iy| (x0..=x1).any(|ix| (ix, iy) != (cx, cy) && near(ix, iy)))
    }
}

/// Squared distance from `p` to the segment `s`.
pub(crate) fn distance2(p: [f64; 2], s: &[[f64; 2]; 2]) -> f64 {
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

    /// A 2 m plate's raster lines once entered a cell every 1.1 mm each
    /// (2.3 M cells a layer, a quarter of a second): laid out along them,
    /// the grid holds each in a few dozen cells, and finds the same gap.
    #[test]
    fn long_lines_enter_few_cells_at_any_angle() {
        for deg in [0.0f64, 30.0, 90.0, 137.5] {
            let (c, s) = (deg.to_radians().cos(), deg.to_radians().sin());
            let turn = |p: [f64; 2]| [p[0] * c - p[1] * s, p[0] * s + p[1] * c];
            // Lines 1.6 mm apart across a 2 m square, but one left out.
            let segments: Vec<[[f64; 2]; 2]> = (0..1250)
                .filter(|&n| n != 600)
                .map(|n| {
                    let y = n as f64 * 1.6;
                    [turn([0.0, y]), turn([2000.0, y])]
                })
                .collect();
            let samples: Vec<[f64; 2]> = (0..2000)
                .map(|k| turn([(k % 50) as f64 * 40.0 + 3.0, (k / 50) as f64 * 48.0]))
                .collect();
            let g = Grid::new(&segments, &samples, 1.1);
            assert!(
                g.items.len() <= segments.len() * 70,
                "{deg}: {}",
                g.items.len()
            );
            let uncovered: Vec<_> = samples
                .iter()
                .filter(|&&p| !g.any_within(&segments, p, 1.1))
                .collect();
            let slow: Vec<_> = samples
                .iter()
                .filter(|&&p| !segments.iter().any(|s| distance2(p, s) <= 1.1 * 1.1))
                .collect();
            assert_eq!(uncovered, slow, "{deg}");
            assert!(!slow.is_empty());
        }
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

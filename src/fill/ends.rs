//! The nearest of many track ends to a point, through a grid of buckets:
//! a raster's closing tracks each follow the nearest run end
//! ([`super::raster`]), which a scan over every track made quadratic in
//! the tracks of a layer.
//!
//! The grid has about one end a bucket. A query searches rings of buckets
//! outward from the point's own and stops once every bucket left lies
//! farther than the nearest end found; ties go to the lowest number, as a
//! scan in order would give.

/// Track ends by bucket.
pub struct Ends {
    origin: [f64; 2],
    cell: f64,
    n: [i64; 2],
    /// Each bucket's ends: (number, place).
    buckets: Vec<Vec<(usize, [f64; 2])>>,
}

impl Ends {
    /// The grid of `ends` (number, place); non-finite places are left out.
    pub fn new(ends: impl IntoIterator<Item = (usize, [f64; 2])>) -> Ends {
        let ends: Vec<(usize, [f64; 2])> = ends
            .into_iter()
            .filter(|(_, p)| p[0].is_finite() && p[1].is_finite())
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (_, p) in &ends {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if ends.is_empty() {
            return Ends {
                origin: [0.0; 2],
                cell: 1.0,
                n: [0, 0],
                buckets: Vec::new(),
            };
        }
        let span = [(hi[0] - lo[0]).max(1e-9), (hi[1] - lo[1]).max(1e-9)];
        // About one end a bucket, and no more buckets than ends (a line of
        // ends has a span of nothing across).
        let per = (span[0] * span[1] / ends.len() as f64).sqrt();
        let cell = per.max(span[0].max(span[1]) / ends.len() as f64).max(1e-9);
        let n = [
            (span[0] / cell).floor() as i64 + 1,
            (span[1] / cell).floor() as i64 + 1,
        ];
        let mut grid = Ends {
            origin: lo,
            cell,
            n,
            buckets: vec![Vec::new(); (n[0] * n[1]) as usize],
        };
        for (i, p) in ends {
            let [x, y] = grid.bucket(p);
            let b = (y * n[0] + x) as usize;
            grid.buckets[b].push((i, p));
        }
        grid
    }

    /// The bucket `p` falls in, which may lie off the grid.
    fn bucket(&self, p: [f64; 2]) -> [i64; 2] {
        let at = |k: usize| {
            let c = ((p[k] - self.origin[k]) / self.cell).floor();
            c.clamp(-1e15, 1e15) as i64
        };
        [at(0), at(1)]
    }

    /// The end nearest `p`: its number, distance and place; the lowest
    /// number among those equally near. `None` when there are none.
    pub fn nearest(&self, p: [f64; 2]) -> Option<(usize, f64, [f64; 2])> {
        if self.buckets.is_empty() {
            return None;
        }
        let [cx, cy] = self.bucket(p);
        let [nx, ny] = self.n;
        // The first ring that meets the grid, and the last.
        let first = [-cx, cx - (nx - 1), -cy, cy - (ny - 1)]
            .into_iter()
            .fold(0, i64::max);
        let last = [cx, nx - 1 - cx, cy, ny - 1 - cy]
            .into_iter()
            .map(i64::abs)
            .fold(0, i64::max);
        let mut best: Option<(usize, f64, [f64; 2])> = None;
        for k in first..=last {
            // Ring k lies k − 1 whole buckets or more from p's.
            if best.is_some_and(|(_, d, _)| d < (k - 1) as f64 * self.cell) {
                break;
            }
            for (x, y) in self.ring([cx, cy], k) {
                for &(i, q) in &self.buckets[(y * nx + x) as usize] {
                    let d = (q[0] - p[0]).hypot(q[1] - p[1]);
                    let better = match best {
                        None => true,
                        Some((j, e, _)) => d < e || (d == e && i < j),
                    };
                    if better {
                        best = Some((i, d, q));
                    }
                }
            }
        }
        best
    }

    /// The grid's buckets `k` rings round `c` (Chebyshev distance `k`),
    /// each once.
    fn ring(&self, [cx, cy]: [i64; 2], k: i64) -> Vec<(i64, i64)> {
        let [nx, ny] = self.n;
        let mut out = Vec::new();
        let xs = (cx - k).max(0)..=(cx + k).min(nx - 1);
        for y in [cy - k, cy + k] {
            if (0..ny).contains(&y) && (k > 0 || y == cy - k) {
                out.extend(xs.clone().map(|x| (x, y)));
            }
            if k == 0 {
                break;
            }
        }
        let ys = (cy - k + 1).max(0)..=(cy + k - 1).min(ny - 1);
        for x in [cx - k, cx + k] {
            if k > 0 && (0..nx).contains(&x) {
                out.extend(ys.clone().map(|y| (x, y)));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against a scan in order over scattered ends, ties included.
    #[test]
    fn the_nearest_end_is_the_scans() {
        let mut state = 7u64;
        let mut r = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 * 40.0).round() / 2.0 - 10.0
        };
        for count in [1, 2, 5, 50, 400] {
            let ends: Vec<(usize, [f64; 2])> = (0..count).map(|i| (i, [r(), r() * 0.3])).collect();
            let grid = Ends::new(ends.iter().copied());
            for _ in 0..200 {
                let p = [r() * 1.7, r()];
                let scan = ends
                    .iter()
                    .map(|&(i, q)| (i, (q[0] - p[0]).hypot(q[1] - p[1]), q))
                    .min_by(|a, b| a.1.total_cmp(&b.1));
                assert_eq!(grid.nearest(p), scan, "{count} ends, {p:?}");
            }
        }
        assert_eq!(Ends::new([]).nearest([0.0, 0.0]), None);
    }

    /// Each bucket of a ring once, those off the grid left out.
    #[test]
    fn a_ring_is_its_border_on_the_grid() {
        let ends = (0..100).map(|i| (i, [(i % 10) as f64, (i / 10) as f64]));
        let grid = Ends::new(ends);
        assert!(grid.n[0] >= 8 && grid.n[1] >= 8, "{:?}", grid.n);
        assert_eq!(grid.ring([4, 4], 0), vec![(4, 4)]);
        for k in 1..4 {
            let mut cells = grid.ring([4, 4], k);
            let n = cells.len();
            cells.sort_unstable();
            cells.dedup();
            assert_eq!((cells.len(), n), (8 * k as usize, 8 * k as usize));
        }
        // From a corner, only the quarter on the grid.
        assert_eq!(grid.ring([0, 0], 2).len(), 5);
        // From far off, the grid's nearest column.
        assert_eq!(grid.ring([-20, 5], 20).len(), grid.n[1] as usize);
    }
}

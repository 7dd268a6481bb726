//! The highest face of a triangle soup over each point, seen from above:
//! a target surface given as a mesh (`top = mesh(…)`, docs/repair.md) — the
//! part as designed, its upper faces the finished surface a repair builds
//! up to. Exact (a vertical ray against the faces), found through a
//! uniform grid of buckets, so a query costs the few faces near the point.

/// Most bucket entries per face, on average, before the buckets grow.
const ENTRIES_PER_FACE: usize = 8;

/// A face's corners, mm.
type Face = [[f64; 3]; 3];

/// A triangle soup's upper surface.
#[derive(Debug)]
pub struct Highest {
    /// The faces that are not upright (mm, placed).
    faces: Vec<[[f64; 3]; 3]>,
    /// The upright faces, not asked from above but kept for the whole
    /// mesh ([`Highest::faces`]): a best fit's nominal needs its sides.
    upright: Vec<[[f64; 3]; 3]>,
    origin: [f64; 2],
    cell: f64,
    n: [usize; 2],
    /// Each bucket's first entry in `entries` (one more than buckets).
    start: Vec<u32>,
    /// Face numbers, bucket by bucket.
    entries: Vec<u32>,
}

impl Highest {
    /// The upper surface of `faces` (placed, mm); faces seen edge-on from
    /// above are left out. `None` when none is left.
    pub fn new(faces: Vec<[[f64; 3]; 3]>) -> Option<Highest> {
        let (faces, upright): (Vec<Face>, Vec<Face>) = faces
            .into_iter()
            .filter(|t| t.iter().flatten().all(|v| v.is_finite()))
            .partition(|t| det(t).abs() > 1e-12);
        if faces.is_empty() {
            return None;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in faces.iter().flatten() {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let span = [(hi[0] - lo[0]).max(1e-9), (hi[1] - lo[1]).max(1e-9)];
        // About a face a bucket to start; coarser while large faces would
        // fill too many buckets.
        let mut cell = (span[0] * span[1] / faces.len() as f64).sqrt().max(1e-6);
        loop {
            let n = [
                (span[0] / cell).floor() as usize + 1,
                (span[1] / cell).floor() as usize + 1,
            ];
            let h = Highest {
                faces: Vec::new(),
                upright: Vec::new(),
                origin: lo,
                cell,
                n,
                start: Vec::new(),
                entries: Vec::new(),
            };
            let count: usize = faces.iter().map(|t| h.cells(t).count()).sum();
            let buckets = n[0].saturating_mul(n[1]);
            if count <= ENTRIES_PER_FACE * faces.len() + 1024 && buckets <= 4 * faces.len() + 1024 {
                return Some(Highest {
                    upright,
                    ..h.fill(faces)
                });
            }
            cell *= 2.0;
        }
    }

    /// The buckets face `t`'s box covers.
    fn cells(&self, t: &[[f64; 3]; 3]) -> impl Iterator<Item = usize> + '_ {
        let idx = |v: f64, k: usize| {
            (((v - self.origin[k]) / self.cell).floor().max(0.0) as usize).min(self.n[k] - 1)
        };
        let lo = |k: usize| t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        let (i0, i1, j0, j1) = (idx(lo(0), 0), idx(hi(0), 0), idx(lo(1), 1), idx(hi(1), 1));
        let nx = self.n[0];
        (j0..=j1).flat_map(move |j| (i0..=i1).map(move |i| j * nx + i))
    }

    /// The buckets filled with `faces` (counting sort by bucket).
    fn fill(mut self, faces: Vec<[[f64; 3]; 3]>) -> Highest {
        let buckets = self.n[0] * self.n[1];
        let mut count = vec![0u32; buckets + 1];
        for t in &faces {
            for c in self.cells(t) {
                count[c + 1] += 1;
            }
        }
        for c in 0..buckets {
            count[c + 1] += count[c];
        }
        let mut next = count.clone();
        let mut entries = vec![0u32; count[buckets] as usize];
        for (f, t) in faces.iter().enumerate() {
            for c in self.cells(t).collect::<Vec<_>>() {
                entries[next[c] as usize] = f as u32;
                next[c] += 1;
            }
        }
        self.start = count;
        self.entries = entries;
        self.faces = faces;
        self
    }

    /// Every finite face of the mesh, the upright ones after the others.
    pub fn faces(&self) -> impl Iterator<Item = &[[f64; 3]; 3]> + '_ {
        self.faces.iter().chain(&self.upright)
    }

    /// The box its faces lie within (mm): lowest corner, highest.
    pub fn bounds(&self) -> [[f64; 3]; 2] {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in self.faces.iter().flatten() {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        [lo, hi]
    }

    /// The heights of the faces over `p` higher than `z` (mm), highest
    /// first, faces meeting at an edge or corner the ray passes through
    /// counted once. From the top down they enter and leave the part in
    /// turn: three or more mean the part leaves and enters again above
    /// `z` (an overhang, a cavity).
    pub fn crossings_above(&self, p: [f64; 2], z: f64) -> Vec<f64> {
        let mut hs: Vec<f64> = self
            .near(p)
            .iter()
            .filter_map(|&f| height(&self.faces[f as usize], p))
            .filter(|&h| h > z)
            .collect();
        hs.sort_by(|a, b| b.total_cmp(a));
        hs.dedup_by(|a, b| (*a - *b).abs() <= 1e-6);
        hs
    }

    /// The faces of `p`'s bucket (none off the grid).
    fn near(&self, p: [f64; 2]) -> &[u32] {
        let (fx, fy) = (
            (p[0] - self.origin[0]) / self.cell,
            (p[1] - self.origin[1]) / self.cell,
        );
        if !(fx >= 0.0 && fy >= 0.0) {
            return &[];
        }
        let (i, j) = (fx.floor() as usize, fy.floor() as usize);
        if i >= self.n[0] || j >= self.n[1] {
            return &[];
        }
        let c = j * self.n[0] + i;
        &self.entries[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The height of the highest face over `p` (mm), if any face is over
    /// it.
    pub fn at(&self, p: [f64; 2]) -> Option<f64> {
        let mut best: Option<f64> = None;
        for &f in self.near(p) {
            if let Some(z) = height(&self.faces[f as usize], p) {
                best = Some(best.map_or(z, |b: f64| b.max(z)));
            }
        }
        best
    }
}

/// Twice the signed area of `t` seen from above.
fn det(t: &[[f64; 3]; 3]) -> f64 {
    let [a, b, c] = t;
    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
}

/// The height of face `t` over `p`, if `p` is over it (its edges
/// included).
fn height(t: &[[f64; 3]; 3], p: [f64; 2]) -> Option<f64> {
    let [a, b, c] = t;
    let d = det(t);
    let l1 = ((b[0] - p[0]) * (c[1] - p[1]) - (c[0] - p[0]) * (b[1] - p[1])) / d;
    let l2 = ((c[0] - p[0]) * (a[1] - p[1]) - (a[0] - p[0]) * (c[1] - p[1])) / d;
    let l3 = 1.0 - l1 - l2;
    let eps = -1e-9;
    (l1 >= eps && l2 >= eps && l3 >= eps).then(|| l1 * a[2] + l2 * b[2] + l3 * c[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box's faces: the highest over a point inside is its top.
    #[test]
    fn a_boxs_highest_face_is_its_top_and_nothing_is_beside_it() {
        let (lo, hi) = ([-5.0, -3.0, 0.0], [5.0, 3.0, 12.5]);
        let c = |i: usize| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        };
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let faces: Vec<[[f64; 3]; 3]> = quads
            .iter()
            .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
            .collect();
        let h = Highest::new(faces).unwrap();
        for p in [[0.0, 0.0], [4.9, -2.9], [-5.0, 3.0], [1.234, 2.5]] {
            assert_eq!(h.at(p), Some(12.5), "{p:?}");
        }
        assert_eq!(h.at([5.1, 0.0]), None);
        assert_eq!(h.at([0.0, -30.0]), None);
        // Above its floor the ray meets the top alone, on an edge of two
        // of its triangles too; above -1 mm the floor as well.
        assert_eq!(h.crossings_above([1.0, 1.0], 0.5), vec![12.5]);
        assert_eq!(h.crossings_above([0.0, 0.0], 0.5), vec![12.5]);
        assert_eq!(h.crossings_above([1.0, 1.0], -1.0), vec![12.5, 0.0]);
    }

    /// Many small faces of a dome `z = 10 − (x² + y²)/20`: the height
    /// between the corners is the faces' plane, within the dome's sag over
    /// a face.
    #[test]
    fn a_fine_domes_heights_are_read_through_its_buckets() {
        let z = |x: f64, y: f64| 10.0 - (x * x + y * y) / 20.0;
        let mut faces = Vec::new();
        for j in 0..40 {
            for i in 0..40 {
                let (x, y) = (-10.0 + 0.5 * i as f64, -10.0 + 0.5 * j as f64);
                let p = |dx: f64, dy: f64| [x + dx, y + dy, z(x + dx, y + dy)];
                faces.push([p(0.0, 0.0), p(0.5, 0.0), p(0.5, 0.5)]);
                faces.push([p(0.0, 0.0), p(0.5, 0.5), p(0.0, 0.5)]);
            }
        }
        let h = Highest::new(faces).unwrap();
        for (x, y) in [(0.1, 0.2), (-7.33, 4.1), (9.9, -9.9)] {
            let got = h.at([x, y]).unwrap();
            // A plane through a face's corners is within a/20·0.5² of it.
            assert!((got - z(x, y)).abs() <= 0.25 / 10.0, "({x}, {y}): {got}");
        }
    }
}

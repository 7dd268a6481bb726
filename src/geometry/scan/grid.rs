//! The scanned surface seen from above, on a square grid: each cell holds
//! the surface's height at its centre, or nothing where the scan has none.
//!
//! **Points** (a cloud): a cell's height is a plane fitted through the
//! points of its 3 × 3 cells, read at its centre, with stray returns far
//! from the plane left out by a robust rule ([`fit`]): a local fit, whose
//! noise is the scan's over the root of the points it holds (36 at 0.5 mm
//! points and 1 mm cells: a sixth). **Faces** (a mesh): the highest face
//! over the cell's centre (the surface a nozzle meets coming down); a
//! cell at the part's rim, which faces cover only in part, the height of
//! the faces' point nearest its centre.
//! Then **spikes**: a cell whose height departs from the median of its
//! filled neighbours (at least three of the eight) by more than
//! [`Estimate::outlier`] takes that median instead — a burr of stray
//! returns a cell wide is gone, a real step (a row of cells) stays.
//!
//! Between cell centres the surface is bilinear (and extrapolated so in the
//! grid's outer half cell); where some of the four centres around a point
//! are empty, the filled ones are averaged with the same weights, and a point whose own cell is empty has no surface
//! ([`HeightField::at`] is `None`): the scan does not cover it.

use super::{Pose, Raw};
#[cfg(test)]
use crate::geometry::mesh::Placement;

/// Most cells of a height field: 64 MB of heights.
pub const MAX_CELLS: usize = 16_000_000;

/// How a surface is estimated from a scan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The cells' side, mm.
    pub cell: f64,
    /// How far a cell may stand out of its neighbours before it is taken
    /// for a spike, mm.
    pub outlier: f64,
}

/// Why a scan gives no height field.
#[derive(Clone, Debug, PartialEq)]
pub enum GridFault {
    /// The scan's extent over the cell's side needs too many cells.
    TooManyCells {
        /// The cells it would need.
        cells: u64,
        /// The smallest cell side that fits (mm, rounded up to 0.01).
        cell: f64,
    },
    /// A mesh whose faces are all upright: nothing seen from above.
    NoSurface,
}

/// A surface `z(x, y)` on a grid, in the part's coordinates (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    origin: [f64; 2],
    cell: f64,
    nx: usize,
    ny: usize,
    /// Row-major (x fastest); NaN where the scan has nothing.
    z: Vec<f32>,
    /// What the estimate found.
    pub stats: Stats,
}

/// What the estimate found, for the report and the tests.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// The scan's points (vertices).
    pub points: usize,
    /// Cells with a height.
    pub filled: usize,
    /// Cells taken for spikes and replaced.
    pub spikes: usize,
    /// RMS of the points' heights about their cell's median, mm: the scan's
    /// noise as the grid sees it (0 for a mesh).
    pub noise: f64,
    /// The lowest and highest height of the surface, mm.
    pub z_range: [f64; 2],
    /// The scan's lowest and highest x and y, placed (mm).
    pub xy_range: ([f64; 2], [f64; 2]),
    /// Whether it was read from faces (a mesh), not points.
    pub faces: bool,
}

impl HeightField {
    /// The height field of `raw`, placed by `place` (a declared
    /// [`crate::geometry::mesh::Placement`], or a [`Pose`] a best fit
    /// moved), estimated by `est`.
    pub fn new(raw: &Raw, place: impl Into<Pose>, est: Estimate) -> Result<HeightField, GridFault> {
        let pose: Pose = place.into();
        let placed = |v: &[f32; 3]| pose.apply(v);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in &raw.vertices {
            let p = placed(v);
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let cell = est.cell;
        let n = |k: usize| ((hi[k] - lo[k]) / cell).floor() as u64 + 1;
        let cells = n(0).saturating_mul(n(1));
        if cells > MAX_CELLS as u64 {
            let side = ((hi[0] - lo[0] + cell) * (hi[1] - lo[1] + cell) / MAX_CELLS as f64).sqrt();
            return Err(GridFault::TooManyCells {
                cells,
                cell: (side.max(cell) * 100.0).ceil() / 100.0 + 0.01,
            });
        }
        let mut g = HeightField {
            origin: lo,
            cell,
            nx: n(0) as usize,
            ny: n(1) as usize,
            z: vec![f32::NAN; cells as usize],
            stats: Stats {
                points: raw.vertices.len(),
                xy_range: (lo, hi),
                faces: !raw.triangles.is_empty(),
                ..Stats::default()
            },
        };
        if raw.triangles.is_empty() {
            g.fit_points(raw.vertices.iter().map(placed));
        } else {
            let v: Vec<[f64; 3]> = raw.vertices.iter().map(placed).collect();
            let mut rim = vec![f32::NAN; g.z.len()];
            for t in &raw.triangles {
                g.raster(
                    [v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]],
                    &mut rim,
                );
            }
            // A cell no face covers at its centre but one covers in part
            // (at the part's rim) takes that face's height nearest its
            // centre: a track's bead reaches to the rim.
            for (z, r) in g.z.iter_mut().zip(rim) {
                if z.is_nan() {
                    *z = r;
                }
            }
        }
        g.despike(est.outlier);
        g.finish()
    }

    /// The cell of `(x, y)`, if on the grid.
    fn cell_of(&self, x: f64, y: f64) -> Option<usize> {
        let i = ((x - self.origin[0]) / self.cell).floor();
        let j = ((y - self.origin[1]) / self.cell).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.nx && (j as usize) < self.ny)
            .then(|| j as usize * self.nx + i as usize)
    }

    /// Each cell's height from the points of its 3 × 3 cells ([`fit`]);
    /// a cell without points of its own stays empty. The noise about it.
    fn fit_points(&mut self, points: impl Iterator<Item = [f64; 3]>) {
        // The point's offset from its cell's centre, and its height.
        let mut pairs: Vec<(u32, [f32; 3])> = points
            .filter_map(|p| {
                let c = self.cell_of(p[0], p[1])?;
                let (cx, cy) = self.centre(c % self.nx, c / self.nx);
                Some((
                    c as u32,
                    [(p[0] - cx) as f32, (p[1] - cy) as f32, p[2] as f32],
                ))
            })
            .collect();
        pairs.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1[2].total_cmp(&b.1[2])));
        // Where each cell's points start in `pairs`.
        let mut start = vec![0u32; self.z.len() + 1];
        for p in &pairs {
            start[p.0 as usize + 1] += 1;
        }
        for k in 0..self.z.len() {
            start[k + 1] += start[k];
        }
        let (mut sq, mut count) = (0.0f64, 0usize);
        let mut pts = Vec::new();
        for j in 0..self.ny {
            for i in 0..self.nx {
                let k = j * self.nx + i;
                if start[k] == start[k + 1] {
                    continue;
                }
                pts.clear();
                for (di, dj) in std::iter::once((0, 0)).chain(NEIGHBOURS) {
                    let (ii, jj) = (i as isize + di, j as isize + dj);
                    if ii < 0 || jj < 0 || ii as usize >= self.nx || jj as usize >= self.ny {
                        continue;
                    }
                    let c = jj as usize * self.nx + ii as usize;
                    let (ox, oy) = (di as f64 * self.cell, dj as f64 * self.cell);
                    pts.extend(
                        pairs[start[c] as usize..start[c + 1] as usize]
                            .iter()
                            .map(|p| {
                                [
                                    f64::from(p.1[0]) + ox,
                                    f64::from(p.1[1]) + oy,
                                    f64::from(p.1[2]),
                                ]
                            }),
                    );
                }
                let (z, residual, kept) = fit(&pts, self.cell);
                self.z[k] = z as f32;
                sq += residual;
                count += kept;
            }
        }
        self.stats.noise = if count > 0 {
            (sq / count as f64).sqrt()
        } else {
            0.0
        };
    }

    /// The triangle `t` over the cells whose centres it covers, seen from
    /// above; each cell keeps the highest. A cell it covers only in part
    /// gets in `rim` the height of its point nearest the cell's centre
    /// (the highest of those).
    fn raster(&mut self, t: [[f64; 3]; 3], rim: &mut [f32]) {
        let [a, b, c] = t;
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        if det.abs() < 1e-12 {
            return; // upright: nothing seen from above
        }
        let idx = |v: f64, k: usize, n: usize| {
            (((v - self.origin[k]) / self.cell - 0.5).clamp(-1.0, n as f64)) as isize
        };
        let (xs, ys) = ([a[0], b[0], c[0]], [a[1], b[1], c[1]]);
        let fmin = |v: [f64; 3]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let fmax = |v: [f64; 3]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (i0, i1) = (idx(fmin(xs), 0, self.nx), idx(fmax(xs), 0, self.nx) + 1);
        let (j0, j1) = (idx(fmin(ys), 1, self.ny), idx(fmax(ys), 1, self.ny) + 1);
        for j in j0.max(0)..=j1.min(self.ny as isize - 1) {
            for i in i0.max(0)..=i1.min(self.nx as isize - 1) {
                let (x, y) = self.centre(i as usize, j as usize);
                let l1 = ((b[0] - x) * (c[1] - y) - (c[0] - x) * (b[1] - y)) / det;
                let l2 = ((c[0] - x) * (a[1] - y) - (a[0] - x) * (c[1] - y)) / det;
                let l3 = 1.0 - l1 - l2;
                let eps = -1e-9;
                let k = j as usize * self.nx + i as usize;
                if l1 >= eps && l2 >= eps && l3 >= eps {
                    let z = (l1 * a[2] + l2 * b[2] + l3 * c[2]) as f32;
                    if self.z[k].is_nan() || z > self.z[k] {
                        self.z[k] = z;
                    }
                } else if let Some(z) = nearest_in_cell(t, [x, y], self.cell / 2.0) {
                    let z = z as f32;
                    if rim[k].is_nan() || z > rim[k] {
                        rim[k] = z;
                    }
                }
            }
        }
    }

    /// Cell `(i, j)`'s centre.
    fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.origin[0] + (i as f64 + 0.5) * self.cell,
            self.origin[1] + (j as f64 + 0.5) * self.cell,
        )
    }

    /// Cells standing out of their neighbours' median by more than `limit`
    /// take that median (decided on the heights before any is replaced).
    fn despike(&mut self, limit: f64) {
        let before = self.z.clone();
        let mut around = Vec::with_capacity(8);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let k = j * self.nx + i;
                if before[k].is_nan() {
                    continue;
                }
                around.clear();
                for (di, dj) in NEIGHBOURS {
                    let (ii, jj) = (i as isize + di, j as isize + dj);
                    if ii >= 0 && jj >= 0 && (ii as usize) < self.nx && (jj as usize) < self.ny {
                        let z = before[jj as usize * self.nx + ii as usize];
                        if !z.is_nan() {
                            around.push(z);
                        }
                    }
                }
                if around.len() < 3 {
                    continue;
                }
                around.sort_unstable_by(f32::total_cmp);
                let m = around.len();
                let med = if m % 2 == 1 {
                    around[m / 2]
                } else {
                    (around[m / 2 - 1] + around[m / 2]) / 2.0
                };
                if f64::from((before[k] - med).abs()) > limit {
                    self.z[k] = med;
                    self.stats.spikes += 1;
                }
            }
        }
    }

    fn finish(mut self) -> Result<HeightField, GridFault> {
        let (mut lo, mut hi, mut filled) = (f64::INFINITY, f64::NEG_INFINITY, 0);
        for z in self.z.iter().filter(|z| !z.is_nan()) {
            lo = lo.min(f64::from(*z));
            hi = hi.max(f64::from(*z));
            filled += 1;
        }
        if filled == 0 {
            return Err(GridFault::NoSurface);
        }
        self.stats.filled = filled;
        self.stats.z_range = [lo, hi];
        Ok(self)
    }

    /// The surface's height at `p` (mm), or `None` where the scan has no
    /// point in `p`'s cell.
    pub fn at(&self, p: [f64; 2]) -> Option<f64> {
        let own = self.cell_of(p[0], p[1])?;
        if self.z[own].is_nan() {
            return None;
        }
        let fx = (p[0] - self.origin[0]) / self.cell - 0.5;
        let fy = (p[1] - self.origin[1]) / self.cell - 0.5;
        // The four centres around p; in the outer half cell, the last two,
        // extrapolated (a sloped surface stays a plane to the scan's edge).
        let base = |f: f64, n: usize| (f.floor().max(0.0) as usize).min(n.saturating_sub(2));
        let (i0, j0) = (base(fx, self.nx), base(fy, self.ny));
        let corner = |di: usize, dj: usize| {
            let (i, j) = ((i0 + di).min(self.nx - 1), (j0 + dj).min(self.ny - 1));
            f64::from(self.z[j * self.nx + i])
        };
        let (tx, ty) = (fx - i0 as f64, fy - j0 as f64);
        let (tx, ty) = (
            if self.nx > 1 { tx } else { 0.0 },
            if self.ny > 1 { ty } else { 0.0 },
        );
        let zs = [corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)];
        if zs.iter().all(|z| !z.is_nan()) {
            let w = [
                (1.0 - tx) * (1.0 - ty),
                tx * (1.0 - ty),
                (1.0 - tx) * ty,
                tx * ty,
            ];
            return Some(zs.iter().zip(w).map(|(z, w)| z * w).sum());
        }
        // Some empty: the filled ones, weighted as far as they are near.
        let (cx, cy) = (tx.clamp(0.0, 1.0), ty.clamp(0.0, 1.0));
        let w = [
            (1.0 - cx) * (1.0 - cy),
            cx * (1.0 - cy),
            (1.0 - cx) * cy,
            cx * cy,
        ];
        let (mut sum, mut wsum) = (0.0, 0.0);
        for (z, w) in zs.iter().zip(w) {
            if !z.is_nan() && w > 0.0 {
                sum += w * z;
                wsum += w;
            }
        }
        Some(if wsum > 0.0 {
            sum / wsum
        } else {
            f64::from(self.z[own])
        })
    }

    /// The surface turned by `rot` (about the part's origin) and seen
    /// from above again, on cells of the same side: what a build direction
    /// `rot⁻¹·z` sees of it (docs/repair.md, *Undercuts*). The surface
    /// between cell centres (two triangles a square of four filled
    /// centres) is turned and rastered as a scan's faces are: each cell
    /// takes the highest face over its centre, the one a nozzle along the
    /// direction meets first, so what the surface hides from that side
    /// (behind a steep flank) is hidden, and a cell no face covers is no
    /// surface (`lmd::scan-coverage` where a track runs). The outer half
    /// cell, which the centres do not span, is left out.
    pub fn turned(
        &self,
        rot: &nalgebra::Rotation3<f64>,
        outlier: f64,
    ) -> Result<HeightField, GridFault> {
        let (nx, ny) = (self.nx, self.ny);
        let mut index = vec![u32::MAX; self.z.len()];
        let mut vertices = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let z = self.z[j * nx + i];
                if z.is_nan() {
                    continue;
                }
                index[j * nx + i] = vertices.len() as u32;
                // About the grid's origin, so f32 keeps its precision.
                let (x, y) = ((i as f64 + 0.5) * self.cell, (j as f64 + 0.5) * self.cell);
                vertices.push([x as f32, y as f32, z]);
            }
        }
        let mut triangles = Vec::new();
        for j in 0..ny.saturating_sub(1) {
            for i in 0..nx.saturating_sub(1) {
                let c = [
                    index[j * nx + i],
                    index[j * nx + i + 1],
                    index[(j + 1) * nx + i],
                    index[(j + 1) * nx + i + 1],
                ];
                if c.contains(&u32::MAX) {
                    continue;
                }
                triangles.push([c[0], c[1], c[3]]);
                triangles.push([c[0], c[3], c[2]]);
            }
        }
        if triangles.is_empty() {
            return Err(GridFault::NoSurface);
        }
        let raw = Raw {
            vertices,
            triangles,
        };
        let origin = nalgebra::Vector3::new(self.origin[0], self.origin[1], 0.0);
        let pose = Pose {
            scale: 1.0,
            rot: *rot,
            at: rot * origin,
        };
        let mut g = HeightField::new(
            &raw,
            pose,
            Estimate {
                cell: self.cell,
                outlier,
            },
        )?;
        // The points are the estimate's, not the scan's.
        g.stats.points = self.stats.points;
        g.stats.noise = self.stats.noise;
        Ok(g)
    }

    /// The scan's extent in x and y (mm): its lowest corner and highest.
    pub fn extent(&self) -> ([f64; 2], [f64; 2]) {
        self.stats.xy_range
    }

    /// The cells' side, mm.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// When a cloud of points leaves most cells of its box empty: the
    /// share filled and the points' mean spacing over the box, mm (an
    /// upper bound where the scan does not fill its box). Why a place
    /// inside the scan's span has no surface: a `cell` finer than the
    /// points' spacing, or `units` that spread the points apart.
    pub fn sparse(&self) -> Option<(f64, f64)> {
        let cells = (self.nx * self.ny) as f64;
        let share = self.stats.filled as f64 / cells.max(1.0);
        let (lo, hi) = self.stats.xy_range;
        let area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
        let spacing = (area / self.stats.points.max(1) as f64).sqrt();
        (!self.stats.faces && share < 0.5 && spacing.is_finite()).then_some((share, spacing))
    }

    /// The surface as spheres `[x, y, z, radius]` (mm) that hold it, for
    /// the collision checks: one a block of `k × k` cells, `k` the least
    /// that keeps them within `max` (1 below a million cells). A block's
    /// sphere is centred over it, halfway between the lowest and highest
    /// height of its cells and their neighbours (the surface between
    /// centres runs to them), and reaches its corners at both: the
    /// surface over the block lies inside it.
    pub fn samples(&self, max: usize) -> Vec<[f64; 4]> {
        let mut k = 1;
        while self.stats.filled.div_ceil(k * k) > max.max(1) {
            k += 1;
        }
        let height = |i: usize, j: usize| f64::from(self.z[j * self.nx + i]);
        let mut out = Vec::new();
        for bj in (0..self.ny).step_by(k) {
            for bi in (0..self.nx).step_by(k) {
                let (i1, j1) = ((bi + k).min(self.nx), (bj + k).min(self.ny));
                let filled = (bj..j1).any(|j| (bi..i1).any(|i| !height(i, j).is_nan()));
                if !filled {
                    continue;
                }
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for j in bj.saturating_sub(1)..(j1 + 1).min(self.ny) {
                    for i in bi.saturating_sub(1)..(i1 + 1).min(self.nx) {
                        let z = height(i, j);
                        if !z.is_nan() {
                            lo = lo.min(z);
                            hi = hi.max(z);
                        }
                    }
                }
                let (w, d) = ((i1 - bi) as f64 * self.cell, (j1 - bj) as f64 * self.cell);
                let x = self.origin[0] + bi as f64 * self.cell + w / 2.0;
                let y = self.origin[1] + bj as f64 * self.cell + d / 2.0;
                let r = ((w / 2.0).powi(2) + (d / 2.0).powi(2) + ((hi - lo) / 2.0).powi(2)).sqrt();
                out.push([x, y, (lo + hi) / 2.0, r]);
            }
        }
        out
    }
}

/// A cell's height at its centre from the points around it (offsets from
/// the centre, and heights): the points within three robust standard
/// deviations (1.4826 × the median absolute deviation) of the heights'
/// median, a least-squares plane through them, then again through those
/// within three robust deviations of the plane, up to three times — a
/// stray return left in tilts a plane a little and is left out of the next.
/// The height of the point of triangle `t`'s edges nearest `c`, when it
/// lies in the square of half side `h` round `c` (the cell): the triangle
/// covers part of the cell, not its centre.
fn nearest_in_cell(t: [[f64; 3]; 3], c: [f64; 2], h: f64) -> Option<f64> {
    let mut best: Option<(f64, [f64; 3])> = None;
    for s in 0..3 {
        let (a, b) = (t[s], t[(s + 1) % 3]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let u = if len2 > 0.0 {
            (((c[0] - a[0]) * d[0] + (c[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [a[0] + u * d[0], a[1] + u * d[1], a[2] + u * (b[2] - a[2])];
        let dist = (q[0] - c[0]).hypot(q[1] - c[1]);
        if best.is_none_or(|(bd, _)| dist < bd) {
            best = Some((dist, q));
        }
    }
    let (_, q) = best?;
    ((q[0] - c[0]).abs() <= h && (q[1] - c[1]).abs() <= h).then_some(q[2])
}

/// The plane is read at the centre (on a sloped surface the points' mean
/// need not lie there). With fewer than 3 points, or too little spread to
/// tilt a plane, the median. Returns the height, the kept points' sum of
/// squared residuals, and how many.
fn fit(pts: &[[f64; 3]], cell: f64) -> (f64, f64, usize) {
    // First the points within three robust deviations of the heights'
    // median (on a slope the heights spread, so this only drops the wild).
    let mut zs: Vec<f64> = pts.iter().map(|p| p[2]).collect();
    zs.sort_unstable_by(f64::total_cmp);
    let med = median(&zs);
    let mut dev: Vec<f64> = zs.iter().map(|z| (z - med).abs()).collect();
    dev.sort_unstable_by(f64::total_cmp);
    let wild = (3.0 * 1.4826 * median(&dev)).max(1e-6);
    let mut kept: Vec<[f64; 3]> = pts
        .iter()
        .copied()
        .filter(|p| (p[2] - med).abs() <= wild)
        .collect();
    let mut plane = Plane::through(&kept, cell);
    for _ in 0..3 {
        let mut dev: Vec<f64> = kept.iter().map(|p| (p[2] - plane.at(p)).abs()).collect();
        dev.sort_unstable_by(f64::total_cmp);
        let limit = (3.0 * 1.4826 * median(&dev)).max(1e-6);
        let next: Vec<[f64; 3]> = kept
            .iter()
            .copied()
            .filter(|p| (p[2] - plane.at(p)).abs() <= limit)
            .collect();
        if next.len() == kept.len() || next.is_empty() {
            break;
        }
        kept = next;
        plane = Plane::through(&kept, cell);
    }
    let residual = kept.iter().map(|p| (p[2] - plane.at(p)).powi(2)).sum();
    let (lo, hi) = kept
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[2]), hi.max(p[2]))
        });
    (plane.at(&[0.0; 3]).clamp(lo, hi), residual, kept.len())
}

/// The median of sorted values.
fn median(v: &[f64]) -> f64 {
    let m = v.len();
    if m == 0 {
        0.0
    } else if m % 2 == 1 {
        v[m / 2]
    } else {
        (v[m / 2 - 1] + v[m / 2]) / 2.0
    }
}

/// `z = mz + a·(x − mx) + b·(y − my)`, or a constant.
struct Plane {
    m: [f64; 3],
    slope: [f64; 2],
}

impl Plane {
    /// The least-squares plane through `pts`; flat at their median where
    /// they are fewer than 3 or spread less than a quarter cell either way.
    fn through(pts: &[[f64; 3]], cell: f64) -> Plane {
        let n = pts.len() as f64;
        let mean = |k: usize| pts.iter().map(|p| p[k]).sum::<f64>() / n;
        let m = [mean(0), mean(1), mean(2)];
        let (mut sxx, mut sxy, mut syy, mut sxz, mut syz) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for p in pts {
            let (x, y, z) = (p[0] - m[0], p[1] - m[1], p[2] - m[2]);
            sxx += x * x;
            sxy += x * y;
            syy += y * y;
            sxz += x * z;
            syz += y * z;
        }
        let det = sxx * syy - sxy * sxy;
        let spread = n * (cell / 4.0).powi(2) / 12.0;
        if pts.len() >= 3 && sxx >= spread && syy >= spread && det > spread * spread * 1e-3 {
            return Plane {
                m,
                slope: [(sxz * syy - syz * sxy) / det, (syz * sxx - sxz * sxy) / det],
            };
        }
        let mut zs: Vec<f64> = pts.iter().map(|p| p[2]).collect();
        zs.sort_unstable_by(f64::total_cmp);
        Plane {
            m: [0.0, 0.0, median(&zs)],
            slope: [0.0; 2],
        }
    }

    fn at(&self, p: &[f64; 3]) -> f64 {
        self.m[2] + self.slope[0] * (p[0] - self.m[0]) + self.slope[1] * (p[1] - self.m[1])
    }
}

const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

#[cfg(test)]
mod tests {
    use super::*;

    const PLACE: Placement = Placement {
        scale: 1.0,
        turn: [0.0; 3],
        at: [0.0; 3],
    };
    const EST: Estimate = Estimate {
        cell: 1.0,
        outlier: 0.5,
    };

    /// A cloud over `[0, n) × [0, n)` at `per` points a mm, heights `f`.
    fn cloud(n: f64, per: usize, f: impl Fn(f64, f64) -> f64) -> Raw {
        let step = 1.0 / per as f64;
        let m = (n / step) as usize;
        let mut vertices = Vec::new();
        for j in 0..m {
            for i in 0..m {
                let (x, y) = ((i as f64 + 0.5) * step, (j as f64 + 0.5) * step);
                vertices.push([x as f32, y as f32, f(x, y) as f32]);
            }
        }
        Raw {
            vertices,
            triangles: Vec::new(),
        }
    }

    #[test]
    fn a_plane_is_read_back_between_the_points() {
        let f = |x: f64, y: f64| 2.0 + 0.1 * x - 0.05 * y;
        let g = HeightField::new(&cloud(20.0, 4, f), PLACE, EST).unwrap();
        for p in [[3.3, 7.9], [10.0, 10.0], [0.6, 19.4], [15.25, 2.75]] {
            let z = g.at(p).unwrap();
            assert!((z - f(p[0], p[1])).abs() < 1e-5, "{p:?}: {z}");
        }
        assert_eq!(g.at([-1.0, 5.0]), None);
        assert_eq!(g.stats.spikes, 0);
    }

    /// A flat surface turned 30° about y reads back as the plane it
    /// turns into, within float noise of the turned points; a step
    /// facing away from the direction hides what is behind it.
    #[test]
    fn a_turned_plane_is_the_plane_turned_and_a_step_hides_its_back() {
        let g = HeightField::new(&cloud(20.0, 4, |_, _| 5.0), PLACE, EST).unwrap();
        let a = 30.0f64.to_radians();
        let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::y_axis(), -a);
        let t = g.turned(&rot, f64::INFINITY).unwrap();
        // z = 5 turned by −30° about y: z' = x'·tan 30° + 5 / cos 30°.
        for p in [[5.0, 5.0], [10.0, 12.0], [12.0, 3.0]] {
            let want = p[0] * a.tan() + 5.0 / a.cos();
            let got = t.at(p).unwrap();
            assert!((got - want).abs() < 1e-3, "{p:?}: {got} vs {want}");
        }
        assert!(t.at([-20.0, 5.0]).is_none());
        // A 10 mm step up at x = 10, seen along a direction tilted 60°
        // toward +x: its face hides the foot before it.
        let g = HeightField::new(
            &cloud(20.0, 4, |x, _| if x < 10.0 { 0.0 } else { 10.0 }),
            PLACE,
            EST,
        )
        .unwrap();
        let b = 60.0f64.to_radians();
        let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::y_axis(), -b);
        let t = g.turned(&rot, f64::INFINITY).unwrap();
        // The foot at x = 6 (z = 0): up along the direction the line meets
        // the step's face about 4 mm on, so the surface seen there is the
        // face's, that much higher.
        let foot = rot * nalgebra::Vector3::new(6.0, 5.0, 0.0);
        let seen = t.at([foot.x, foot.y]).unwrap();
        assert!(seen > foot.z + 3.0, "{seen} vs {}", foot.z);
    }

    #[test]
    fn noise_and_a_burr_are_seen_through() {
        // ±0.05 mm of deterministic noise, and a burr of stray returns 3 mm
        // high in one cell: the median and the spike rule keep the surface.
        let mut raw = cloud(20.0, 5, |x, y| 1.0 + 0.05 * ((x * 7.3 + y * 3.1).sin()));
        for v in raw.vertices.iter_mut() {
            if v[0] > 10.0 && v[0] < 11.0 && v[1] > 10.0 && v[1] < 11.0 {
                v[2] += 3.0;
            }
        }
        let g = HeightField::new(&raw, PLACE, EST).unwrap();
        // The burr's 25 points are a ninth of its window's: left out.
        for p in [[10.5, 10.5], [11.5, 10.5], [9.5, 11.5]] {
            assert!((g.at(p).unwrap() - 1.0).abs() < 0.06, "{p:?}");
        }
        assert!(
            g.stats.noise > 0.01 && g.stats.noise < 0.05,
            "{}",
            g.stats.noise
        );
    }

    #[test]
    fn a_hole_in_the_scan_is_no_surface() {
        let mut raw = cloud(20.0, 2, |_, _| 5.0);
        raw.vertices
            .retain(|v| !(v[0] > 8.0 && v[0] < 12.0 && v[1] > 8.0 && v[1] < 12.0));
        let g = HeightField::new(&raw, PLACE, EST).unwrap();
        assert_eq!(g.at([10.0, 10.0]), None);
        assert_eq!(g.at([7.5, 10.0]), Some(5.0));
    }

    #[test]
    fn a_mesh_is_its_top_face() {
        // Two triangles of a tilted square, and one below them (the part's
        // underside): the top is what the grid keeps.
        let raw = Raw {
            vertices: vec![
                [0.0, 0.0, 1.0],
                [10.0, 0.0, 2.0],
                [10.0, 10.0, 2.0],
                [0.0, 10.0, 1.0],
                [0.0, 0.0, -5.0],
                [10.0, 0.0, -5.0],
                [10.0, 10.0, -5.0],
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]],
        };
        let g = HeightField::new(&raw, PLACE, EST).unwrap();
        let z = g.at([4.5, 6.5]).unwrap();
        assert!((z - 1.45).abs() < 1e-6, "{z}");
    }

    #[test]
    fn a_cell_a_face_covers_in_part_takes_its_nearest_height() {
        // A right triangle over x + y <= 10 and a point at (10, 10) that
        // stretches the grid over the square: cell (9, 1)'s centre
        // (9.5, 1.5) is off the face but its corner (9, 1) is on it; cell
        // (9, 2)'s square misses the face.
        let raw = Raw {
            vertices: vec![
                [0.0, 0.0, 5.0],
                [10.0, 0.0, 5.0],
                [0.0, 10.0, 5.0],
                [10.0, 10.0, 0.0],
            ],
            triangles: vec![[0, 1, 2]],
        };
        let g = HeightField::new(&raw, PLACE, EST).unwrap();
        assert_eq!(g.at([9.7, 1.3]), Some(5.0));
        assert_eq!(g.at([9.7, 2.3]), None);
    }

    #[test]
    fn placement_scales_turns_and_moves() {
        let place = Placement {
            scale: 25.4,
            turn: [0.0, 0.0, std::f64::consts::FRAC_PI_2],
            at: [100.0, 0.0, 10.0],
        };
        // 1 in square at z = 0.1 in, turned a quarter about z, moved.
        let raw = cloud(1.0, 40, |x, _| 0.1 + 0.0 * x);
        let g = HeightField::new(&raw, place, EST).unwrap();
        assert!((g.at([90.0, 12.7]).unwrap() - 12.54).abs() < 1e-4);
        assert_eq!(g.at([110.0, 12.7]), None);
    }

    #[test]
    fn too_fine_a_grid_is_refused_with_one_that_fits() {
        let raw = Raw {
            vertices: vec![[0.0, 0.0, 0.0], [10_000.0, 10_000.0, 0.0]],
            triangles: vec![],
        };
        let Err(GridFault::TooManyCells { cell, .. }) = HeightField::new(&raw, PLACE, EST) else {
            panic!("expected too many cells");
        };
        let est = Estimate { cell, ..EST };
        assert!(HeightField::new(&raw, PLACE, est).is_ok(), "{cell}");
    }
}

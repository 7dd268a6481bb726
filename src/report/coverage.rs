//! Where the design solid and the plan's strips part: which of the design
//! the deposits' strips cover, and what of the rest is the band at the
//! faces, a hollow the plan leaves unfilled on purpose, or missing for
//! other reasons. For an extrusion built in flat layers, whose design each
//! layer's region says exactly.
//!
//! Each layer is laid on a grid of square cells (about
//! [`CELLS`] over the part, at most [`LAYER_CELLS`] a layer), each cell
//! standing for its centre:
//!
//! - **design**: inside the layer's region (parity over its loops), or for
//!   a profile drawn as the tracks' centre line (`size = centre`), within
//!   half a bead of it;
//! - **covered**: within half its pitch of a deposit move's centre line (a
//!   capsule round the move, `pitch` as the IR carries it): the strip the
//!   layer's rise `A/pitch` is credited over;
//! - **faces**: not covered, and nearer the design's faces (outline or a
//!   hole's edge) than half a bead: the band between the faces and the
//!   outermost beads' strips, which the deposit model leaves to the report
//!   (the outermost track of a filled layer fills its offset like one
//!   inside, `fill::pitch`): where real beads round off;
//! - **hollow**: not covered, on a layer the slicing fills with contours
//!   only (no infill), and deeper inside than the innermost contour's
//!   centre line: the inside the plan leaves unfilled on purpose;
//! - **other**: the rest not covered: gaps between tracks, ends of tracks
//!   short of a contour.
//!
//! The distances to the faces are the grid's exact Euclidean distance
//! transform (Felzenszwalb and Huttenlocher), a cell from the nearest cell
//! outside.

use crate::geometry::outline::region;
use crate::ir::{Layer, Program};
use crate::sema::model::{Build, Measure, Model};
use serde::Serialize;

/// Cells over the whole part, all layers together.
pub const CELLS: usize = 4_000_000;

/// Most cells a layer gets.
pub const LAYER_CELLS: usize = 400_000;

/// A share of the design and its volume.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Figure {
    /// Volume, mm³.
    pub volume_mm3: f64,
    /// Share of the design volume, 0–1.
    pub share: f64,
    /// Mass, g, when the density is known.
    pub mass_g: Option<f64>,
}

/// What of the design the deposits' strips cover, and what they leave.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[cfg_attr(feature = "json-schema", derive(schemars::JsonSchema))]
pub struct Missing {
    /// The design inside some deposit's strip.
    pub covered: Figure,
    /// The band between the design's faces and the outermost beads'
    /// strips: where the beads round off at the faces.
    pub faces: Figure,
    /// Hollows the design has that the plan leaves unfilled on purpose:
    /// the inside of a layer filled with contours only.
    pub hollows: Figure,
    /// The rest no strip covers: gaps between tracks, track ends short of
    /// a contour.
    pub other: Figure,
    /// The grid's cell, mm.
    pub cell_mm: f64,
}

impl Missing {
    /// The figures as volumes of a design `volume_mm3`, with masses at
    /// `density` (g/cm³).
    pub fn scaled(mut self, volume_mm3: f64, density: Option<f64>) -> Missing {
        for f in [
            &mut self.covered,
            &mut self.faces,
            &mut self.hollows,
            &mut self.other,
        ] {
            f.volume_mm3 = f.share * volume_mm3;
            f.mass_g = density.map(|d| d / 1000.0 * f.volume_mm3);
        }
        self
    }
}

/// Cell counts of one layer, or of all.
#[derive(Clone, Copy, Debug, Default)]
struct Counts {
    design: f64,
    covered: f64,
    faces: f64,
    hollows: f64,
    other: f64,
}

/// What of `model`'s design the strips of `program` cover and leave,
/// as shares (volumes 0: see [`Missing::scaled`]); `None` where the design
/// is not an extrusion in flat layers, or its layers are not the IR's.
pub fn missing(model: &Model, program: &Program) -> Option<Missing> {
    let Build::Block {
        extrusion, slicing, ..
    } = &model.build
    else {
        return None;
    };
    let w = model.bead.as_ref()?.width.0;
    let mut scratch = crate::diag::Diagnostics::new();
    let bead = model.bead.as_ref()?;
    let layers = crate::slice::layers::plan(bead, extrusion, slicing, &mut scratch)?;
    if layers.shapes.len() != program.layers.len() || w.is_nan() || w <= 0.0 {
        return None;
    }
    let per_layer = (CELLS / layers.shapes.len().max(1)).clamp(1, LAYER_CELLS);
    let mut sum = Counts::default();
    let mut cell_mm = 0.0f64;
    for (shape, layer) in layers.shapes.iter().zip(&program.layers) {
        let r = region(shape, 0.005);
        let Some(grid) = Grid::new(&r, extrusion.measure, w, per_layer) else {
            continue;
        };
        cell_mm = cell_mm.max(grid.h);
        let c = grid.classify(&r, extrusion.measure, w, layer, slicing.infill.is_none());
        sum.design += c.design;
        sum.covered += c.covered;
        sum.faces += c.faces;
        sum.hollows += c.hollows;
        sum.other += c.other;
    }
    if sum.design <= 0.0 {
        return None;
    }
    let share = |n: f64| Figure {
        share: n / sum.design,
        ..Figure::default()
    };
    Some(Missing {
        covered: share(sum.covered),
        faces: share(sum.faces),
        hollows: share(sum.hollows),
        other: share(sum.other),
        cell_mm,
    })
}

/// A layer's grid: `nx × ny` cells `h` wide from `origin`.
struct Grid {
    origin: [f64; 2],
    h: f64,
    nx: usize,
    ny: usize,
}

impl Grid {
    /// The grid over `r` and half a bead round it, about `cells` cells.
    fn new(
        r: &crate::geometry::region::Region,
        measure: Measure,
        w: f64,
        cells: usize,
    ) -> Option<Grid> {
        let [lo, hi] = r.bounds()?;
        let margin = match measure {
            Measure::Outer => 0.0,
            Measure::Centre => w / 2.0,
        };
        let size = [hi[0] - lo[0] + 2.0 * margin, hi[1] - lo[1] + 2.0 * margin];
        let h = (size[0] * size[1] / cells as f64).sqrt();
        if !(h.is_finite() && h > 0.0) {
            return None;
        }
        // Two cells of outside all round: the faces' distances start there.
        let nx = (size[0] / h).ceil() as usize + 4;
        let ny = (size[1] / h).ceil() as usize + 4;
        let origin = [lo[0] - margin - 2.0 * h, lo[1] - margin - 2.0 * h];
        Some(Grid { origin, h, nx, ny })
    }

    fn centre(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + (i as f64 + 0.5) * self.h,
            self.origin[1] + (j as f64 + 0.5) * self.h,
        ]
    }

    /// Each cell's design membership, coverage and class, counted.
    fn classify(
        &self,
        r: &crate::geometry::region::Region,
        measure: Measure,
        w: f64,
        layer: &Layer,
        contours_only: bool,
    ) -> Counts {
        let inside = self.parity(r);
        let design = match measure {
            Measure::Outer => inside,
            Measure::Centre => {
                let d = edt(&inside, self.nx, self.ny, true);
                let reach = (w / 2.0 / self.h).powi(2);
                d.iter().map(|&d| d <= reach).collect()
            }
        };
        // Squared distance (cells²) of every cell to the nearest outside.
        let face = edt(&design, self.nx, self.ny, false);
        let covered = self.strips(layer);
        let depth = if contours_only {
            self.deepest(layer, &face)
        } else {
            f64::INFINITY
        };
        let band = (w / 2.0 / self.h).powi(2);
        let mut c = Counts::default();
        for k in (0..design.len()).filter(|&k| design[k]) {
            c.design += 1.0;
            if covered[k] {
                c.covered += 1.0;
            } else if face[k] < band {
                c.faces += 1.0;
            } else if face[k] > depth {
                c.hollows += 1.0;
            } else {
                c.other += 1.0;
            }
        }
        c
    }

    /// Cells inside `r` by parity over its loops, row by row.
    fn parity(&self, r: &crate::geometry::region::Region) -> Vec<bool> {
        let mut inside = vec![false; self.nx * self.ny];
        let loops = r.polylines((self.h / 4.0).min(0.01));
        let mut xs = Vec::new();
        for j in 0..self.ny {
            let y = self.centre(0, j)[1];
            xs.clear();
            for l in &loops {
                for k in 0..l.len() {
                    let (a, b) = (l[k], l[(k + 1) % l.len()]);
                    if (a[1] <= y) != (b[1] <= y) {
                        xs.push(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                    }
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                let from = ((pair[0] - self.origin[0]) / self.h - 0.5).ceil().max(0.0) as usize;
                let to = ((pair[1] - self.origin[0]) / self.h - 0.5).floor();
                if to < 0.0 {
                    continue;
                }
                for i in from..=(to as usize).min(self.nx - 1) {
                    inside[j * self.nx + i] = true;
                }
            }
        }
        inside
    }

    /// Cells within half its pitch of a deposit move of `layer`.
    fn strips(&self, layer: &Layer) -> Vec<bool> {
        let mut covered = vec![false; self.nx * self.ny];
        let moves = layer.paths.iter().flat_map(|p| p.points.windows(2));
        for m in moves.filter(|m| m[0].laser_on && m[0].pitch > 0.0) {
            let (a, b) = ([m[0].pos[0], m[0].pos[1]], [m[1].pos[0], m[1].pos[1]]);
            let r = m[0].pitch as f64 / 2.0;
            let cell = |x: f64, o: f64| ((x - o) / self.h).floor().max(0.0) as usize;
            let (i0, j0) = (
                cell(a[0].min(b[0]) - r, self.origin[0]),
                cell(a[1].min(b[1]) - r, self.origin[1]),
            );
            let i1 = cell(a[0].max(b[0]) + r, self.origin[0]).min(self.nx - 1);
            let j1 = cell(a[1].max(b[1]) + r, self.origin[1]).min(self.ny - 1);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    if segment_distance2(self.centre(i, j), a, b) <= r * r {
                        covered[j * self.nx + i] = true;
                    }
                }
            }
        }
        covered
    }

    /// The largest squared distance (cells²) from the faces of a deposit
    /// point of `layer`: the innermost contour's centre line.
    fn deepest(&self, layer: &Layer, face: &[f64]) -> f64 {
        let points = layer.paths.iter().flat_map(|p| &p.points);
        points
            .filter(|q| q.laser_on)
            .filter_map(|q| {
                let i = ((q.pos[0] - self.origin[0]) / self.h).floor();
                let j = ((q.pos[1] - self.origin[1]) / self.h).floor();
                let inside = i >= 0.0 && j >= 0.0;
                let (i, j) = (i as usize, j as usize);
                (inside && i < self.nx && j < self.ny).then(|| face[j * self.nx + i])
            })
            .fold(0.0, f64::max)
    }
}

/// The squared distance from `p` to the segment `a b`.
fn segment_distance2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (d, q) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 {
        ((q[0] * d[0] + q[1] * d[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (q[0] - t * d[0], q[1] - t * d[1]);
    x * x + y * y
}

/// The squared Euclidean distance (in cells²) of every cell of an
/// `nx × ny` grid to the nearest cell whose `set` equals `source`.
fn edt(set: &[bool], nx: usize, ny: usize, source: bool) -> Vec<f64> {
    const FAR: f64 = 1e20;
    let mut d: Vec<f64> = set
        .iter()
        .map(|&s| if s == source { 0.0 } else { FAR })
        .collect();
    let mut line = Vec::new();
    for j in 0..ny {
        line.clear();
        line.extend_from_slice(&d[j * nx..(j + 1) * nx]);
        let out = edt_1d(&line);
        d[j * nx..(j + 1) * nx].copy_from_slice(&out);
    }
    for i in 0..nx {
        line.clear();
        line.extend((0..ny).map(|j| d[j * nx + i]));
        for (j, v) in edt_1d(&line).into_iter().enumerate() {
            d[j * nx + i] = v;
        }
    }
    d
}

/// The 1-D squared distance transform of `f`: `min_q (p − q)² + f(q)`, by
/// the lower envelope of parabolas.
fn edt_1d(f: &[f64]) -> Vec<f64> {
    let n = f.len();
    let mut out = vec![0.0; n];
    if n == 0 {
        return out;
    }
    let (mut v, mut z) = (vec![0usize; n], vec![0.0f64; n + 1]);
    let mut k = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    let meet = |q: usize, p: usize| {
        ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64))
    };
    for q in 1..n {
        let mut s = meet(q, v[k]);
        while s <= z[k] {
            k -= 1;
            s = meet(q, v[k]);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as f64 - v[k] as f64;
        *o = d * d + f[v[k]];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_transform_of_a_point_is_its_squared_distance() {
        let (nx, ny) = (7, 5);
        let mut set = vec![false; nx * ny];
        set[2 * nx + 3] = true;
        let d = edt(&set, nx, ny, true);
        for j in 0..ny {
            for i in 0..nx {
                let e = (i as f64 - 3.0).powi(2) + (j as f64 - 2.0).powi(2);
                assert_eq!(d[j * nx + i], e, "{i} {j}");
            }
        }
    }

    #[test]
    fn a_segment_is_as_far_as_its_nearest_point() {
        assert_eq!(segment_distance2([1.0, 2.0], [0.0, 0.0], [3.0, 0.0]), 4.0);
        assert_eq!(segment_distance2([5.0, 0.0], [0.0, 0.0], [3.0, 0.0]), 4.0);
    }
}

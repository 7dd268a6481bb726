//! A planar region: outer loops with holes, each loop a [`Profile`] of lines
//! and arcs. A layer with bolt holes is one outline and a hole loop per hole;
//! its offsets may split into several outer loops and merge holes with each
//! other or with the outline.
//!
//! Offsets go through `cavalier_contours`' `Shape`, which offsets the outer
//! loops inward and the holes outward at once and stitches where they meet,
//! arcs kept as arcs. Without holes a region offsets exactly as its
//! [`Profile`] does. Every loop is stored counter-clockwise; which ones are
//! holes is kept beside them.

mod check;

pub use check::{Fault, MAX_FAULTS};

use super::profile::{Profile, MIN_LOOP_AREA, TOLERANCE};
use cavalier_contours::polyline::{PlineSource, PlineSourceMut};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};

/// Outer loops and the holes inside them.
#[derive(Clone, Debug)]
pub struct Region {
    outer: Vec<Profile>,
    holes: Vec<Profile>,
}

impl From<Profile> for Region {
    fn from(p: Profile) -> Region {
        Region {
            outer: vec![p],
            holes: Vec::new(),
        }
    }
}

impl Region {
    /// The region inside `outer` and outside every hole. The loops are not
    /// checked here: see [`Region::check`].
    pub fn new(outer: Profile, holes: Vec<Profile>) -> Region {
        Region {
            outer: vec![outer],
            holes,
        }
    }

    /// The separate regions `parts` as one: all their outer loops and all
    /// their holes (a layer of islands, for what looks at the whole layer:
    /// its area, the distance to its edges).
    pub fn islands(parts: impl IntoIterator<Item = Region>) -> Region {
        let mut out = Region {
            outer: Vec::new(),
            holes: Vec::new(),
        };
        for p in parts {
            out.outer.extend(p.outer);
            out.holes.extend(p.holes);
        }
        out
    }

    /// The outer loops, counter-clockwise.
    pub fn outer(&self) -> &[Profile] {
        &self.outer
    }

    /// The holes, each stored counter-clockwise.
    pub fn holes(&self) -> &[Profile] {
        &self.holes
    }

    /// Every loop, the outer ones first, each with whether it is a hole.
    pub fn loops(&self) -> impl Iterator<Item = (&Profile, bool)> + '_ {
        self.outer
            .iter()
            .map(|p| (p, false))
            .chain(self.holes.iter().map(|p| (p, true)))
    }

    /// Whether nothing is left (no outer loop).
    pub fn is_empty(&self) -> bool {
        self.outer.is_empty()
    }

    /// Whether every number of every loop is finite.
    pub fn is_finite(&self) -> bool {
        self.loops().all(|(p, _)| p.is_finite())
    }

    /// The vertices of all loops together: the work an offset or a clip does.
    pub fn pieces(&self) -> usize {
        self.loops().map(|(p, _)| p.vertices().len()).sum()
    }

    /// The area: the outer loops' less the holes'.
    pub fn area(&self) -> f64 {
        self.outer.iter().map(Profile::area).sum::<f64>()
            - self.holes.iter().map(Profile::area).sum::<f64>()
    }

    /// Exact bounding box of the outer loops; `None` when there are none.
    pub fn bounds(&self) -> Option<[[f64; 2]; 2]> {
        self.outer
            .iter()
            .filter_map(Profile::bounds)
            .reduce(|a, b| {
                [
                    [a[0][0].min(b[0][0]), a[0][1].min(b[0][1])],
                    [a[1][0].max(b[1][0]), a[1][1].max(b[1][1])],
                ]
            })
    }

    /// Whether `p` lies in the closed region: inside or on an outer loop and
    /// not strictly inside a hole (a hole's edge belongs to the region).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        self.outer.iter().any(|o| o.contains(p))
            && !self
                .holes
                .iter()
                .any(|h| h.contains(p) && h.distance_to_boundary(p) > TOLERANCE)
    }

    /// Exact distance from `p` to the nearest loop, holes included.
    pub fn distance_to_boundary(&self, p: [f64; 2]) -> f64 {
        self.loops()
            .map(|(l, _)| l.distance_to_boundary(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The region turned by `angle` (rad, counter-clockwise) about the
    /// origin, then moved by `by`: every loop placed alike.
    pub fn placed(&self, angle: f64, by: [f64; 2]) -> Region {
        Region {
            outer: self.outer.iter().map(|p| p.placed(angle, by)).collect(),
            holes: self.holes.iter().map(|p| p.placed(angle, by)).collect(),
        }
    }

    /// The region without the holes whose indices are in `drop`.
    pub fn without_holes(&self, drop: &[usize]) -> Region {
        Region {
            outer: self.outer.clone(),
            holes: self
                .holes
                .iter()
                .enumerate()
                .filter(|(i, _)| !drop.contains(i))
                .map(|(_, h)| h.clone())
                .collect(),
        }
    }

    /// Every loop flattened within `chord_error` (see [`Profile::polyline`]).
    pub fn polylines(&self, chord_error: f64) -> Vec<Vec<[f64; 2]>> {
        self.loops().map(|(l, _)| l.polyline(chord_error)).collect()
    }

    /// The region at distance `d` inside this one (outside for negative `d`):
    /// outer loops shrink, holes grow, and where they meet they merge. Loops
    /// smaller than 1e-9 mm² are dropped; `d = 0` gives a clone. A region
    /// whose loops are not finite, or whose holes cross (see
    /// [`Region::check`]), gives no meaningful result.
    pub fn offset_inward(&self, d: f64) -> Region {
        if self.holes.is_empty() {
            // One engine for a plain profile, so that a part without holes
            // fills exactly as it always has.
            return Region {
                outer: self.outer.iter().flat_map(|o| o.offset_inward(d)).collect(),
                holes: Vec::new(),
            };
        }
        if d == 0.0 {
            return self.clone();
        }
        if !d.is_finite() || !self.loops().all(|(l, _)| l.engine_safe()) {
            return Region {
                outer: Vec::new(),
                holes: Vec::new(),
            };
        }
        // The engine tells holes by their orientation: clockwise.
        let plines = self.loops().map(|(l, hole)| {
            let mut pl = l.to_pline();
            if hole {
                pl.invert_direction_mut();
            }
            pl
        });
        let shape = Shape::from_plines(plines).parallel_offset(d, &ShapeOffsetOptions::default());
        let keep = |ip: &cavalier_contours::shape_algorithms::IndexedPolyline<f64>| {
            let p = Profile::from_pline(&ip.polyline);
            (ip.polyline.is_closed() && p.area() > MIN_LOOP_AREA).then_some(p)
        };
        Region {
            outer: shape.ccw_plines.iter().filter_map(keep).collect(),
            holes: shape.cw_plines.iter().filter_map(keep).collect(),
        }
    }
}

#[cfg(test)]
mod tests;

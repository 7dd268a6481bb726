//! Whether a region as the user wrote it is one: a simple outline, simple
//! holes strictly inside it, no two holes crossing, touching or nested.
//!
//! Each hole is tested against the outline through the outline's segment
//! index, and only pairs of holes whose bounding boxes overlap are tested
//! against each other (a sweep over the boxes sorted by x): `O(P log P)` for
//! `P` pieces in all, plus the pairs that overlap.

use super::Region;
use crate::geometry::profile::{Profile, TOLERANCE};
use cavalier_contours::polyline::PlineSource;
use cavalier_contours::static_aabb2d_index::StaticAABB2DIndex;

/// Most faults [`Region::faults`] lists: a thousand holes piled on one
/// spot would otherwise make half a million errors, and as much work.
pub const MAX_FAULTS: usize = 50;

/// Why a region is not one. Hole numbers count from 0 in the order given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fault {
    /// The outline crosses or touches itself near `at`.
    Outline {
        /// A point where it does.
        at: [f64; 2],
    },
    /// A hole's own edges cross or touch.
    HoleItself {
        /// The hole.
        hole: usize,
        /// A point where they do.
        at: [f64; 2],
    },
    /// A hole crosses or touches the outline.
    HoleOutline {
        /// The hole.
        hole: usize,
        /// A point where they meet.
        at: [f64; 2],
    },
    /// A hole lies outside the outline.
    HoleOutside {
        /// The hole.
        hole: usize,
    },
    /// Two holes cross or touch.
    Holes {
        /// The first of the two.
        hole: usize,
        /// The other, later one.
        other: usize,
        /// A point where they meet.
        at: [f64; 2],
    },
    /// A hole lies inside another.
    HoleInHole {
        /// The inner hole.
        hole: usize,
        /// The hole around it.
        other: usize,
    },
}

impl Region {
    /// The first fault of a region made by [`Region::new`], in the order of
    /// [`Region::faults`].
    pub fn check(&self) -> Result<(), Fault> {
        self.faults().first().map_or(Ok(()), |&f| Err(f))
    }

    /// Every fault of a region made by [`Region::new`] (at most
    /// [`MAX_FAULTS`]), in the order: the outline, each hole by itself, each
    /// hole against the outline, the pairs of holes (by their lower number,
    /// then the other). Loops that are not finite or beyond
    /// [`crate::geometry::profile::MAX_COORDINATE`] are not tested: check
    /// those first.
    pub fn faults(&self) -> Vec<Fault> {
        let mut out = Vec::new();
        let Some(outline) = self.outer.first() else {
            return out;
        };
        if !self.loops().all(|(l, _)| l.engine_safe()) {
            return out;
        }
        if let Some(at) = outline.self_intersection() {
            out.push(Fault::Outline { at });
        }
        for (hole, h) in self.holes.iter().enumerate() {
            if let Some(at) = h.self_intersection() {
                out.push(Fault::HoleItself { hole, at });
            }
        }
        let outer = outline.to_pline();
        let index = outer.create_approx_aabb_index();
        for (hole, h) in self.holes.iter().enumerate() {
            if let Some(at) = meet(&outer, Some(&index), h) {
                out.push(Fault::HoleOutline { hole, at });
                continue;
            }
            // Not crossing: wholly inside or wholly outside.
            let v = h.vertices()[0];
            if !outline.contains([v.x, v.y]) {
                out.push(Fault::HoleOutside { hole });
            }
        }
        out.truncate(MAX_FAULTS);
        let left = MAX_FAULTS - out.len();
        out.extend(holes_apart(&self.holes, left));
        out
    }
}

/// A point where `p` meets the loop `other`, if they cross or touch.
fn meet(
    p: &cavalier_contours::polyline::Polyline<f64>,
    index: Option<&StaticAABB2DIndex<f64>>,
    other: &Profile,
) -> Option<[f64; 2]> {
    crate::geometry::profile::meet(p, index, &other.to_pline())
}

/// Every pair of holes whose boxes overlap, tested for crossing and nesting:
/// the faults, at most `most` of them (the first the sweep finds), ordered
/// by the pair's numbers.
fn holes_apart(holes: &[Profile], most: usize) -> Vec<Fault> {
    let boxes: Vec<[[f64; 2]; 2]> = holes
        .iter()
        .map(|h| h.bounds().unwrap_or([[0.0; 2]; 2]))
        .collect();
    let mut order: Vec<usize> = (0..holes.len()).collect();
    order.sort_by(|&a, &b| boxes[a][0][0].total_cmp(&boxes[b][0][0]));
    let mut found: Vec<Fault> = Vec::new();
    'sweep: for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if found.len() >= most {
                break 'sweep;
            }
            if boxes[b][0][0] > boxes[a][1][0] + TOLERANCE {
                break;
            }
            if boxes[b][0][1] > boxes[a][1][1] + TOLERANCE
                || boxes[a][0][1] > boxes[b][1][1] + TOLERANCE
            {
                continue;
            }
            let (hole, other) = (a.min(b), a.max(b));
            if let Some(at) = meet(&holes[hole].to_pline(), None, &holes[other]) {
                found.push(Fault::Holes { hole, other, at });
            } else if inside(&holes[hole], &holes[other]) {
                found.push(Fault::HoleInHole { hole, other });
            } else if inside(&holes[other], &holes[hole]) {
                found.push(Fault::HoleInHole {
                    hole: other,
                    other: hole,
                });
            }
        }
    }
    found.sort_by_key(|&f| key(f));
    found
}

/// Whether `a` lies inside `b`, given that they do not meet.
fn inside(a: &Profile, b: &Profile) -> bool {
    let v = a.vertices()[0];
    b.contains([v.x, v.y])
}

/// The pair a fault between holes names, lowest first, for a stable choice.
fn key(f: Fault) -> (usize, usize) {
    match f {
        Fault::Holes { hole, other, .. } | Fault::HoleInHole { hole, other } => {
            (hole.min(other), hole.max(other))
        }
        _ => (usize::MAX, usize::MAX),
    }
}

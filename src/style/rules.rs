//! Explicit style rules: conditions on a track (its class, length, layer, and
//! where it lies relative to the layer's boundary and sharp corners) that pin a
//! style. The paper assigns styles by hand per scan line; with ~3000 layers that
//! is impossible, so rules state once what a user would otherwise click.

use super::band::Bands;
use super::{Layout, PathClass, StyleId, TrackFacts};

/// Absolute allowance (mm) on the distance conditions: contours are offsets of
/// the boundary by exact amounts, so a track lies *at* the threshold by
/// construction and rounding must not decide which side it falls on.
const DISTANCE_SLACK_MM: f64 = 1e-9;
/// Relative allowance on the distance conditions (see [`DISTANCE_SLACK_MM`]).
const DISTANCE_SLACK_REL: f64 = 1e-9;
/// Largest uncovered share of a track that still counts as "the whole track
/// lies within" (rounding in the interval ends, not geometry).
const WHOLE_TOLERANCE: f64 = 1e-9;

/// One condition of a [`Rule`]. Numbers are mm; NaN or negative distances and NaN
/// lengths make the condition false rather than panicking.
#[derive(Clone, Debug, PartialEq)]
pub enum Condition {
    /// The track is of this class.
    Class(PathClass),
    /// The track is a contour, outer or inner.
    Contour,
    /// The track is shorter than this (mm), per [`TrackFacts::length`].
    LengthBelow(f64),
    /// The track is at least this long (mm), per [`TrackFacts::length`].
    LengthAtLeast(f64),
    /// The whole track lies within this distance (mm) of the layer's boundary.
    BoundaryWithin(f64),
    /// Some point of the track comes within this distance (mm) of a sharp corner.
    CornerWithin(f64),
    /// The track's layer is in `first..=last` (0-based layer numbers).
    Layers {
        /// First layer, inclusive.
        first: usize,
        /// Last layer, inclusive.
        last: usize,
    },
}

/// A rule: when every condition holds, the track gets `style`. A rule with no
/// conditions matches every track (a catch-all). A rule may name style 0: it
/// then pins the default style, which also stops inheritance for those tracks.
#[derive(Clone, Debug)]
pub struct Rule {
    /// Conditions that must all hold.
    pub when: Vec<Condition>,
    /// The style the rule assigns.
    pub style: StyleId,
}

/// A distance condition's threshold with the rounding allowance, or `None` when
/// the distance is NaN or negative (no point is at such a distance).
fn threshold(d: f64) -> Option<f64> {
    (d >= 0.0).then_some(d + DISTANCE_SLACK_MM + d * DISTANCE_SLACK_REL)
}

impl Condition {
    /// Whether the condition holds for `track` (a polyline in mm) with `facts`
    /// in the layer described by `layout`.
    ///
    /// Length conditions read `facts.length` (the caller's measure, usually
    /// [`length`](super::length) of the track). `BoundaryWithin` is exact (capsule
    /// intervals around the boundary's closed loops) and, for a zero-length track,
    /// tests its point; both distance conditions are false for an empty track or
    /// layout. Cost: `BoundaryWithin` O(boundary + track points), `CornerWithin`
    /// O(track points + corners), each with a grid built per call.
    pub fn holds(&self, track: &[[f64; 2]], facts: &TrackFacts, layout: &Layout) -> bool {
        match *self {
            Condition::Class(c) => facts.class == c,
            Condition::Contour => matches!(
                facts.class,
                PathClass::OuterContour | PathClass::InnerContour
            ),
            Condition::LengthBelow(l) => facts.length < l,
            Condition::LengthAtLeast(l) => facts.length >= l,
            Condition::BoundaryWithin(d) => {
                BoundaryBand::new(layout.boundary, d).is_some_and(|b| b.holds(track))
            }
            Condition::CornerWithin(d) => threshold(d).is_some_and(|d| {
                // A corner is within d of the track iff it lies in the track's band.
                let bands = Bands::new([(track, 0)], false, d);
                layout.corners.iter().any(|&c| bands.contains(c))
            }),
            Condition::Layers { first, last } => (first..=last).contains(&facts.layer),
        }
    }
}

/// The band of one half-width along a layer's boundary, built once and asked
/// about many tracks: [`Condition::BoundaryWithin`] without rebuilding the
/// boundary's index for every track.
pub struct BoundaryBand {
    bands: Bands,
}

impl BoundaryBand {
    /// The band within `d` (mm) of the closed loops `boundary`; `None` for a
    /// NaN or negative `d` (no point is that close).
    pub fn new(boundary: &[Vec<[f64; 2]>], d: f64) -> Option<Self> {
        let d = threshold(d)?;
        let loops = boundary.iter().map(|l| (l.as_slice(), 0));
        Some(BoundaryBand {
            bands: Bands::new(loops, true, d),
        })
    }

    /// Whether the whole `track` lies in the band (a track of no length: its
    /// point, if it has a finite one).
    pub fn holds(&self, track: &[[f64; 2]]) -> bool {
        let cov = self.bands.coverage(track);
        if cov.total > 0.0 {
            cov.fraction(0) >= 1.0 - WHOLE_TOLERANCE
        } else {
            let point = track.iter().find(|p| p[0].is_finite() && p[1].is_finite());
            point.is_some_and(|&p| self.bands.contains(p))
        }
    }
}

/// The style of the first rule whose conditions all hold for the track, or `None`
/// when no rule matches.
pub fn apply_rules(
    rules: &[Rule],
    track: &[[f64; 2]],
    facts: &TrackFacts,
    layout: &Layout,
) -> Option<StyleId> {
    rules
        .iter()
        .find(|r| r.when.iter().all(|c| c.holds(track, facts, layout)))
        .map(|r| r.style)
}

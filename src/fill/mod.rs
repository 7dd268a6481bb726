//! Filling a planar layer (seed 001): contour passes that follow the outline,
//! then raster tracks across what is left.
//!
//! # What [`fill`] makes
//!
//! The [`Profile`] is the outline of the layer, in mm.
//!
//! - **Contours.** Pass `i` (`i = 0 .. contours`, 0 outermost) is the outline
//!   offset inward by `inset + i·offset`. Each loop of it (an offset may split
//!   a narrow waist into several loops) is one closed [`Track`]: arcs
//!   flattened within `chord_error`, counter-clockwise, starting at its point
//!   with the smallest `(y, x)` and ending with that point again. Loops of
//!   one pass come in order of those start points. Once a pass vanishes the
//!   passes inside it are skipped.
//! - **Raster region.** The outline offset inward by
//!   `inset + contours·offset` (just `inset` without contours).
//! - **Raster lines** run in direction `angle_deg` (from +x, counter-
//!   clockwise). With `s` the coordinate across them, lines sit at
//!   `s_min + n·offset` for `n = 0, 1, …` while `≤ s_max` (with 1e-9 of an
//!   offset of slack, so that a region exactly `k` offsets wide gets its
//!   last line, placed exactly on `s_max`); `s` is measured along the
//!   direction's left normal (+y for 0°), and `s_min`, `s_max` are the
//!   region's extremes (arcs included). Line 0 thus touches
//!   the region's extreme point, and over a circular edge of radius `R` line
//!   `n` meets the circle `sqrt(R² − (R − n·d)²)` from the circle's centre
//!   line — seed 001's `X_n`. When more than half an offset
//!   ([`CLOSING`]) is left between the last such line and `s_max`, a closing
//!   line sits on `s_max`, so the far edge is not short by up to an offset.
//! - **Clipping** is exact, against the region's lines and true arcs (not a
//!   flattened polygon), and the region is closed: a line lying along a
//!   straight edge yields that edge, a line touching an arc yields the touch
//!   point (which the extension then grows). A concave region gives several
//!   intervals on one line.
//! - **Extension** (seed 001, `ΔX ≤ d`): each end of each interval moves
//!   outward along its line by `min(extend, reach)`, where `reach` is how much
//!   further an interval of a neighbouring line (`n − 1` or `n + 1`, the
//!   larger reach counts) goes past that end. Only a neighbour interval that
//!   overlaps this interval counts, at this interval's +end only if no later
//!   interval of this line overlaps it too, at the −end only if no earlier
//!   one does: under a notch the wide
//!   interval below reaches past the inner ends of the two intervals above,
//!   but that reach belongs to the notch's floor, not to those ends. So a
//!   curved or slanted edge's staircase is filled, a straight edge across the
//!   tracks gets nothing, and no end moves more than `extend`. Reaches are
//!   measured on the clipped intervals, before any extension. Two intervals
//!   of one line that would grow into each other stop at the middle of the
//!   gap between them. Intervals shorter than 1e-9 mm after extension (a
//!   touch point with nothing to grow it) are dropped.
//! - **Order.** Contours first, outermost first; then the raster lines in
//!   increasing `s`. [`Pattern::OneWay`] runs every interval in the +direction
//!   of the line; [`Pattern::Serpentine`] alternates direction from one line
//!   that carries tracks to the next (the first one runs in the +direction),
//!   and on a line run backwards its intervals come in that backward order.
//!   Each raster interval is one two-point [`Track`].
//!
//! The output depends only on the inputs. If nothing at all results, `fill`
//! returns [`FillError::Empty`]: a layer without tracks cannot be built.
//!
//! # Limits
//!
//! Every number must be finite ([`FillError::NonFinite`]); offsets and chord
//! error must be positive, inset and extension not negative, and every
//! length (coordinates included) within [`MAX_LENGTH`]
//! ([`FillError::OutOfRange`]). At most [`MAX_LINES`] raster lines, a
//! bounded number of contour passes ([`MAX_CONTOURS`], fewer for outlines of
//! many pieces) and [`MAX_POINTS`] points a layer, so that no input can hang
//! the compiler or exhaust its memory. A self-intersecting outline is
//! rejected with a point where it crosses itself.
//!
//! The cost is `O(V log V)` per offset (`V` the outline's pieces) plus the
//! output: the clip walks each line only past the pieces that span it.

mod contour;
mod coverage;
mod error;
mod extend;
mod raster;

pub use coverage::{gap, Gap, MAX_SAMPLES};
pub use error::{Count, FillError, Invalid};
pub use raster::{intervals_at, CLOSING};

use crate::geometry::profile::Profile;

/// Largest length accepted anywhere (mm): coordinates, offsets, inset,
/// extension, chord error. A kilometre is far beyond any deposition cell and
/// keeps every squared distance exact to well below a micron.
pub const MAX_LENGTH: f64 = 1e6;

/// Most raster lines in one layer.
pub const MAX_LINES: u64 = 100_000;

/// Most contour passes in one layer.
pub const MAX_CONTOURS: u64 = 10_000;

/// Most points (contour points plus raster track ends) in one layer.
pub const MAX_POINTS: u64 = 2_000_000;

/// Most pieces an outline may have.
pub const MAX_PIECES: usize = 100_000;

/// Bound on contour passes × outline pieces: the offsets' work.
const CONTOUR_WORK: u64 = 2_000_000;

/// How raster tracks follow each other.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pattern {
    /// Back and forth: every other line runs the other way.
    Serpentine,
    /// Every line in the same direction.
    OneWay,
}

/// The raster part of a fill.
#[derive(Clone, Copy, Debug)]
pub struct RasterSpec {
    /// Direction of the lines, degrees from +x, counter-clockwise.
    pub angle_deg: f64,
    /// Distance between lines, mm (the bead offset `d`).
    pub offset: f64,
    /// Back and forth, or one way.
    pub pattern: Pattern,
    /// Most an interval's end may be extended past the clipped line, mm
    /// (seed 001: `d`; 0 turns extension off).
    pub extend: f64,
}

/// How a layer is filled.
#[derive(Clone, Copy, Debug)]
pub struct FillSpec {
    /// Distance from the outline to the first contour (or to the raster
    /// region without contours), mm.
    pub inset: f64,
    /// Number of contour passes.
    pub contours: usize,
    /// Distance between contour passes, and from the last one to the raster
    /// region, mm. Must be positive when there are contours.
    pub offset: f64,
    /// The raster inside the contours, if any.
    pub raster: Option<RasterSpec>,
}

/// What a track is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrackKind {
    /// A closed contour pass; 0 is the outermost.
    Contour {
        /// The pass.
        index: usize,
    },
    /// A raster interval.
    Infill,
}

/// One deposited track: a polyline the nozzle follows with the laser on.
#[derive(Clone, Debug)]
pub struct Track {
    /// Contour or raster.
    pub kind: TrackKind,
    /// The points, in mm, in travel order; a contour repeats its first point
    /// at the end.
    pub points: Vec<[f64; 2]>,
}

/// The tracks that fill `profile` as `spec` says, arcs flattened within
/// `chord_error` mm. See the [module documentation](self) for what exactly
/// is produced and in which order.
pub fn fill(profile: &Profile, spec: &FillSpec, chord_error: f64) -> Result<Vec<Track>, FillError> {
    validate(profile, spec, chord_error)?;
    let mut points_left = MAX_POINTS;
    let mut tracks = contour::passes(profile, spec, chord_error, &mut points_left)?;
    if let Some(raster) = &spec.raster {
        let depth = spec.inset + spec.contours as f64 * spec.offset;
        let region = profile.offset_inward(depth);
        tracks.extend(raster::tracks(&region, raster, &mut points_left)?);
    }
    if tracks.is_empty() {
        return Err(FillError::Empty);
    }
    Ok(tracks)
}

/// Takes `n` points from the layer's budget, or fails once it is spent.
fn spend(points_left: &mut u64, n: usize) -> Result<(), FillError> {
    let n = n as u64;
    if n > *points_left {
        return Err(too_many_points(*points_left, n));
    }
    *points_left -= n;
    Ok(())
}

/// The error for needing `n` more points with `left` of the budget left.
fn too_many_points(left: u64, n: u64) -> FillError {
    FillError::TooManyPoints(Count {
        wanted: (MAX_POINTS - left).saturating_add(n),
        max: MAX_POINTS,
    })
}

fn validate(profile: &Profile, spec: &FillSpec, chord_error: f64) -> Result<(), FillError> {
    let mut numbers = vec![spec.inset, spec.offset, chord_error];
    if let Some(r) = &spec.raster {
        numbers.extend([r.angle_deg, r.offset, r.extend]);
    }
    if !profile.is_finite() || numbers.iter().any(|v| !v.is_finite()) {
        return Err(FillError::NonFinite);
    }
    let positive = "more than 0 mm and at most 1e6 mm";
    let not_negative = "at least 0 mm and at most 1e6 mm";
    length("the chord error", chord_error, positive, false)?;
    length("the inset", spec.inset, not_negative, true)?;
    if spec.contours > 0 {
        length("the contour offset", spec.offset, positive, false)?;
    }
    if let Some(r) = &spec.raster {
        length("the raster offset", r.offset, positive, false)?;
        length("the raster extension", r.extend, not_negative, true)?;
    }
    let pieces = profile.vertices().len();
    if pieces > MAX_PIECES {
        return Err(FillError::OutOfRange(Invalid {
            what: "the number of pieces of the outline",
            value: pieces as f64,
            unit: "",
            expected: "at most 100000",
        }));
    }
    let Some([lo, hi]) = profile.bounds() else {
        return Err(FillError::Empty);
    };
    let coords = [lo[0], lo[1], hi[0], hi[1]];
    // An arc whose numbers overflow leaves NaN in the bounds: out of range too.
    if coords.iter().any(|v| v.is_nan() || v.abs() > MAX_LENGTH) {
        let reach = coords.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        return Err(FillError::OutOfRange(Invalid {
            what: "the farthest point of the outline",
            value: if coords.iter().any(|v| v.is_nan()) {
                f64::INFINITY
            } else {
                reach
            },
            unit: " mm from the origin",
            expected: "at most 1e6 mm from the origin",
        }));
    }
    if let Some(at) = profile.self_intersection() {
        return Err(FillError::SelfIntersecting { at });
    }
    let max_contours = (CONTOUR_WORK / pieces.max(1) as u64).min(MAX_CONTOURS);
    if spec.contours as u64 > max_contours {
        return Err(FillError::TooManyContours(Count {
            wanted: spec.contours as u64,
            max: max_contours,
        }));
    }
    Ok(())
}

/// Checks one length: `(0, MAX_LENGTH]`, or `[0, MAX_LENGTH]` with `zero_ok`.
fn length(
    what: &'static str,
    value: f64,
    expected: &'static str,
    zero_ok: bool,
) -> Result<(), FillError> {
    let low_ok = if zero_ok { value >= 0.0 } else { value > 0.0 };
    if low_ok && value <= MAX_LENGTH {
        Ok(())
    } else {
        Err(FillError::OutOfRange(Invalid {
            what,
            value,
            unit: " mm",
            expected,
        }))
    }
}

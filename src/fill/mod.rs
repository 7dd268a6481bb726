//! Filling a planar layer: contour passes that follow the outline
//! and its holes, then raster tracks across what is left.
//!
//! # What [`fill_region`] makes
//!
//! The [`Region`] is the layer: an outline and any holes, in mm ([`fill`]
//! takes a [`Profile`] without holes).
//!
//! - **Contours.** Pass `i` (`i = 0 .. contours`, 0 outermost) is the region
//!   offset inward by `inset + i·offset`: the outline shrinks and every hole
//!   grows, so each hole gets passes of its own, and where they meet the
//!   loops merge. Each loop of it (an offset may also split a narrow waist
//!   into several loops) is one closed [`Track`]: arcs flattened within
//!   `chord_error`, counter-clockwise round the outline and clockwise round a
//!   hole (the part on the left), starting at its seam ([`Seam`]; by default
//!   its point with the smallest `(y, x)`) and ending with that point again.
//!   Loops of one pass come in order of those start points. Once a pass
//!   vanishes the passes inside it are skipped.
//! - **Raster region.** The region offset inward by
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
//!   ([`CLOSING`]; less where [`RasterSpec::closing`] says) is left between
//!   the last such line and `s_max`, a closing line sits on `s_max`, so the
//!   far edge is not short by up to an offset. A straight edge between the
//!   extremes that runs within [`PARALLEL_DEG`] of the lines (a notch's
//!   side, a step of the outline, an edge a hair off the lines' direction)
//!   gets a closing track on it by the same rule, where the nearest line
//!   beside it is farther than that threshold: module `edge`, laid after
//!   the raster track (or linked run) whose end is nearest it. With
//!   contours, where the innermost one would be left with no raster track
//!   within its reach (the offset and that threshold) over at least that
//!   length — beside a curved edge that runs through the lines' direction,
//!   which the lines run past — a closing track runs along the raster
//!   region's margin there: module `margin`, laid the same way.
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
//!   gap between them. No end is extended into a hole grown by the inset
//!   (where its bead would lay metal into the hole): it stops there. Intervals
//!   shorter than 1e-9 mm after extension (a touch point with nothing to grow
//!   it) are dropped.
//! - **Order.** Contours first, outermost first; then the raster lines in
//!   increasing `s`. [`Pattern::OneWay`] runs every interval in the +direction
//!   of the line; [`Pattern::Serpentine`] alternates direction from one line
//!   that carries tracks to the next (the first one runs in the +direction),
//!   and on a line run backwards its intervals come in that backward order.
//!   Each raster interval is one two-point [`Track`].
//! - **Links** ([`Linking`], serpentine only): neighbouring tracks are joined
//!   at their ends when the link stays where track centre lines may run
//!   (the region less the inset): with the laser off along the edge, with
//!   it on by a half circle across their spacing, the two ends trimmed
//!   level to meet it (where the edge slants, that link is laid with the
//!   laser off); the tracks then come in chains, each track carrying its
//!   [`Link`] to the next. The rule is in [`link`].
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
//! rejected with a point where it crosses itself; holes that cross, touch or
//! nest, or lie outside the outline, with which ([`FillError::Region`]).
//!
//! The cost is `O(V log V)` per offset and for the region's check (`V` the
//! pieces of all loops) plus the output: the clip walks each line only past
//! the pieces that span it.

mod clamp;
mod clip;
mod contour;
pub(crate) mod coverage;
mod edge;
mod ends;
mod error;
mod extend;
mod inside;
pub mod link;
mod margin;
pub mod pitch;
mod raster;

pub use coverage::{gap, gap_in, Gap, MAX_SAMPLES};
pub use edge::PARALLEL_DEG;
pub use error::{BadValue, Count, FillError};
pub use raster::{intervals_at, CLOSING};

use crate::geometry::profile::Profile;
use crate::geometry::region::{Fault, Region};

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

/// Whether neighbouring raster tracks are linked at their ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Linking {
    /// Every track its own: the laser stops at each end.
    None,
    /// Linked, the laser on through the link: a serpentine turning along
    /// the edge.
    LaserOn,
    /// Linked, the laser off through the link: the nozzle moves on without
    /// lifting.
    LaserOff,
}

/// Where a contour loop starts and ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seam {
    /// At its point with the smallest `(y, x)` after flattening.
    Lowest,
    /// At its point farthest in this direction (rad from +x,
    /// counter-clockwise), exact on arcs; of a straight edge across the
    /// direction, at the edge's first point.
    Toward(f64),
    /// At its sharpest corner; a loop without corners (a circle) as
    /// [`Seam::Lowest`].
    SharpestCorner,
    /// This far (mm) along the loop, the way it runs, from its point with the
    /// smallest `(y, x)`, wrapping round.
    Along(f64),
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
    /// (the track offset `d`, as `ΔX ≤ d` has it; 0 turns extension off).
    pub extend: f64,
    /// Whether neighbouring tracks are linked (serpentine only: one-way
    /// tracks are never linked).
    pub link: Linking,
    /// More than this left (mm) between the last whole-offset line and the
    /// region's far extreme gets a closing line on the extreme: at most
    /// [`CLOSING`] offsets; less where a contour runs an offset beyond the
    /// region, so that no line lies farther than a bead from it.
    pub closing: f64,
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
    /// Where contour loops start.
    pub seam: Seam,
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

/// How the nozzle goes on from a track's end to the next track's start
/// without stopping.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The points strictly between the two (none: straight on), mm.
    pub via: Vec<[f64; 2]>,
    /// Whether the laser stays on through the link.
    pub laser: bool,
}

/// One deposited track: a polyline the nozzle follows with the laser on.
#[derive(Clone, Debug)]
pub struct Track {
    /// Contour or raster.
    pub kind: TrackKind,
    /// The points, in mm, in travel order; a contour repeats its first point
    /// at the end.
    pub points: Vec<[f64; 2]>,
    /// How it goes on into the next track of the fill, if it is linked.
    pub link: Option<Link>,
}

/// The tracks that fill `profile` (no holes) as `spec` says, arcs flattened
/// within `chord_error` mm: [`fill_region`] of the profile alone.
pub fn fill(profile: &Profile, spec: &FillSpec, chord_error: f64) -> Result<Vec<Track>, FillError> {
    fill_region(&Region::from(profile.clone()), spec, chord_error)
}

/// The tracks that fill `region` as `spec` says, arcs flattened within
/// `chord_error` mm. See the [module documentation](self) for what exactly
/// is produced and in which order.
pub fn fill_region(
    region: &Region,
    spec: &FillSpec,
    chord_error: f64,
) -> Result<Vec<Track>, FillError> {
    validate(region, spec, chord_error)?;
    let mut points_left = MAX_POINTS;
    let mut tracks = contour::passes(region, spec, chord_error, &mut points_left)?;
    if let Some(raster) = &spec.raster {
        let depth = spec.inset + spec.contours as f64 * spec.offset;
        let inner = region.offset_inward(depth);
        // Holes grown by the inset: a bead centred closer lays metal inside.
        let keep_out: Vec<Profile> = region
            .holes()
            .iter()
            .flat_map(|h| h.offset_inward(-spec.inset))
            .collect();
        let centres;
        let link = match raster.link {
            Linking::None => None,
            _ if raster.pattern == Pattern::OneWay => None,
            l => {
                centres = region.offset_inward(spec.inset);
                Some((&centres, l == Linking::LaserOn))
            }
        };
        let cx = raster::Context {
            keep_out: &keep_out,
            link,
            chord_error,
        };
        tracks.extend(raster::tracks(&inner, raster, &cx, &mut points_left)?);
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

fn validate(region: &Region, spec: &FillSpec, chord_error: f64) -> Result<(), FillError> {
    let mut numbers = vec![spec.inset, spec.offset, chord_error];
    if let Some(r) = &spec.raster {
        numbers.extend([r.angle_deg, r.offset, r.extend]);
    }
    if let Seam::Toward(a) | Seam::Along(a) = spec.seam {
        numbers.push(a);
    }
    if !region.is_finite() || numbers.iter().any(|v| !v.is_finite()) {
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
    let pieces = region.pieces();
    if pieces > MAX_PIECES {
        return Err(FillError::OutOfRange(BadValue {
            what: "the number of pieces of the outline",
            value: pieces as f64,
            unit: "",
            expected: "at most 100000",
        }));
    }
    let Some([lo, hi]) = region.bounds() else {
        return Err(FillError::Empty);
    };
    // Holes inside the outline lie within its bounds; one outside is found
    // by the check below, but its numbers must be in range for that.
    let holes = region.holes().iter().filter_map(Profile::bounds);
    let coords: Vec<f64> = [lo[0], lo[1], hi[0], hi[1]]
        .into_iter()
        .chain(holes.flat_map(|[a, b]| [a[0], a[1], b[0], b[1]]))
        .collect();
    // An arc whose numbers overflow leaves NaN in the bounds: out of range too.
    if coords.iter().any(|v| v.is_nan() || v.abs() > MAX_LENGTH) {
        let reach = coords.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        return Err(FillError::OutOfRange(BadValue {
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
    match region.check() {
        Ok(()) => {}
        Err(Fault::Outline { at }) => return Err(FillError::SelfIntersecting { at }),
        Err(fault) => return Err(FillError::Region(fault)),
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
        Err(FillError::OutOfRange(BadValue {
            what,
            value,
            unit: " mm",
            expected,
        }))
    }
}

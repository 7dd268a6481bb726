//! Where the speed may change along a track (seed 003 eq. 7). A controller
//! changes speed only so often, so a track is laid in `m` segments of
//! constant speed — constant layer height — and the top they build departs
//! from the target `H(x)`. The error is the area between the two per unit of
//! track length,
//!
//! `E(m) = (1/L) ∫₀ᴸ |H(x) − H_seg(x)| dx`,
//!
//! with the absolute value the paper drops (without it a rising top's
//! over- and undershoots cancel and the bound never binds). The plan takes
//! the smallest `m` with `E(m) ≤ E_H`.
//!
//! **Equal segments, each at its best height.** Segment `j` spans
//! `[jL/m, (j+1)L/m]` (the paper's `L_s/m`) at the height that minimises its
//! own area, the length-weighted median of `H` over it — on a straight piece
//! the midpoint value (the paper samples the segment's end, which doubles
//! the error of a ramp). Why equal lengths rather than free boundaries:
//! - on a plane top (the paper's parts, and the examples) they *are* optimal:
//!   a segment of length `ℓ` on slope `k` leaves `|k|ℓ²/4`, and `Σℓ²` over a
//!   fixed `L` is least when all `ℓ` are equal — so `E(m) = ΔH/(4m)` and
//!   `m = ⌈ΔH/(4·E_H)⌉`, with `ΔH` the rise along the track;
//! - "smallest m" is then checked, not assumed: every `m` from 1 up is
//!   tried, so every count below the one returned fails (on a curved top
//!   `E(m)` need not fall with every added segment, and exhaustion is the
//!   only proof);
//! - one segment length `L/m` makes the minimum-length rule exact: the
//!   counts allowed are `m ≤ ⌊L/ℓ_min⌋`, and the tolerance that would work is
//!   the least `E(m)` among them.
//!
//! Free boundaries would save segments only on curved tops, at the price of
//! a search over breakpoints whose minimality is only as good as its
//! discretisation.
//!
//! Every layer uses the same segments (it lays the same fraction of `H`), so
//! the layers' errors add up; the tolerance is therefore on the finished top,
//! as the paper writes it, and each layer departs from `H/N` by `E/N`.

use super::floor_slack;
use super::input::Positive;
use super::profile::TrackProfile;
use super::SLACK;
use crate::units::Length;
use std::num::NonZeroUsize;

/// Most segments a track may have: a speed change every 0.1 mm on a 100 mm
/// track. Bounds the search for any input.
pub const MAX_SEGMENTS: usize = 1000;

/// What the file asks of the segmentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentSpec {
    /// `E_H`: the largest mean |height error| of the top along a track.
    pub tolerance: Positive,
    /// The shortest segment the controller can lay (default: the bead width).
    pub min_length: Positive,
}

/// One constant-speed stretch of a track.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Where it starts along the track.
    pub start: Length,
    /// Where it ends.
    pub end: Length,
    /// The top height it builds (each layer lays `height / N`).
    pub height: Length,
}

/// A track cut into segments.
#[derive(Clone, Debug, PartialEq)]
pub struct Segmentation {
    /// In order along the track; they tile it.
    pub segments: Vec<Segment>,
    /// `E(m)`: area between target and segmented top per unit length.
    pub error: Length,
}

/// Why no segmentation meets the tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegmentError {
    /// Meeting the tolerance needs segments shorter than the minimum length.
    TooShort(TooShort),
    /// Not even [`MAX_SEGMENTS`] segments meet the tolerance.
    TooMany {
        /// The tolerance asked for.
        tolerance: Length,
        /// The least error any allowed count reaches: a tolerance that works.
        workable: Length,
    },
}

/// The tolerance needs segments shorter than allowed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TooShort {
    /// The tolerance asked for.
    pub tolerance: Length,
    /// The minimum segment length.
    pub min_length: Length,
    /// The most segments at least that long: `⌊L / min_length⌋` (at least 1).
    pub allowed: NonZeroUsize,
    /// The least error those counts reach: the tightest tolerance that works.
    pub workable: Length,
    /// The count the tolerance needs and its segment length, if at most
    /// [`MAX_SEGMENTS`] do.
    pub needed: Option<(NonZeroUsize, Length)>,
}

/// The track in `m` equal segments, each at its best height, and its error.
pub fn equal_segments(profile: &TrackProfile, m: NonZeroUsize) -> Segmentation {
    let (x0, l) = (profile.start().0, profile.length().0);
    let m = m.get();
    let at = |j: usize| {
        if j == m {
            x0 + l
        } else {
            x0 + l * j as f64 / m as f64
        }
    };
    let mut area = 0.0;
    let segments = (0..m)
        .map(|j| {
            let (start, end) = (Length(at(j)), Length(at(j + 1)));
            let (height, a) = profile.best_constant(start, end);
            area += a;
            Segment { start, end, height }
        })
        .collect();
    Segmentation {
        segments,
        error: Length(area / l),
    }
}

/// The fewest equal segments whose error is within the tolerance, none
/// shorter than the minimum length. One segment is always allowed: a track
/// shorter than the minimum has no speed change to make (tracks shorter than
/// a bead are reported on their own, as `lmd::short-track`).
pub fn segment(profile: &TrackProfile, spec: SegmentSpec) -> Result<Segmentation, SegmentError> {
    let l = profile.length().0;
    let tol = spec.tolerance.mm();
    let meets = |s: &Segmentation| s.error.0 <= tol * (1.0 + SLACK);
    let by_length = floor_slack(l / spec.min_length.mm()).max(1.0);
    let allowed = by_length.min(MAX_SEGMENTS as f64) as usize;
    let mut workable = f64::INFINITY;
    for m in (1..=allowed).filter_map(NonZeroUsize::new) {
        let s = equal_segments(profile, m);
        if meets(&s) {
            return Ok(s);
        }
        workable = workable.min(s.error.0);
    }
    let workable = Length(workable);
    match NonZeroUsize::new(allowed) {
        Some(allowed) if by_length <= MAX_SEGMENTS as f64 => {
            let needed = (allowed.get() + 1..=MAX_SEGMENTS)
                .filter_map(NonZeroUsize::new)
                .find(|&m| meets(&equal_segments(profile, m)))
                .map(|m| (m, Length(l / m.get() as f64)));
            Err(SegmentError::TooShort(TooShort {
                tolerance: spec.tolerance.get(),
                min_length: spec.min_length.get(),
                allowed,
                workable,
                needed,
            }))
        }
        _ => Err(SegmentError::TooMany {
            tolerance: spec.tolerance.get(),
            workable,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(tol: f64, min: f64) -> SegmentSpec {
        SegmentSpec {
            tolerance: Positive::new("tolerance", Length(tol)).unwrap(),
            min_length: Positive::new("min length", Length(min)).unwrap(),
        }
    }

    fn ramp(l: f64, h0: f64, h1: f64) -> TrackProfile {
        TrackProfile::new([(Length(0.0), Length(h0)), (Length(l), Length(h1))]).unwrap()
    }

    #[test]
    fn a_ramp_needs_a_quarter_of_its_rise_per_tolerance() {
        // 100 mm rising 20 → 36 mm, E_H = 0.1 mm: m = ⌈16/(4·0.1)⌉ = 40
        // segments of 2.5 mm (≥ a 2.4 mm bead), E(40) = 16/160 = 0.1 exactly.
        let s = segment(&ramp(100.0, 20.0, 36.0), spec(0.1, 2.4)).unwrap();
        assert_eq!(s.segments.len(), 40);
        assert!((s.error.0 - 0.1).abs() < 1e-12);
        // Each segment sits at its midpoint height.
        let first = s.segments[0];
        assert!((first.height.0 - 20.2).abs() < 1e-12);
        assert_eq!((first.start.0, s.segments[39].end.0), (0.0, 100.0));
        // 39 would not do.
        let fewer = equal_segments(&ramp(100.0, 20.0, 36.0), NonZeroUsize::new(39).unwrap());
        assert!(fewer.error.0 > 0.1);
    }

    #[test]
    fn too_tight_a_tolerance_names_one_that_works() {
        // E_H = 0.05 mm needs 80 segments of 1.25 mm; a 2.4 mm minimum allows
        // ⌊100/2.4⌋ = 41, which reach 16/(4·41) = 0.0976 mm.
        let Err(SegmentError::TooShort(e)) = segment(&ramp(100.0, 20.0, 36.0), spec(0.05, 2.4))
        else {
            panic!("segments of 1.25 mm must be refused")
        };
        assert_eq!(e.allowed.get(), 41);
        assert!((e.workable.0 - 16.0 / 164.0).abs() < 1e-12);
        let (m, len) = e.needed.unwrap();
        assert_eq!((m.get(), len.0), (80, 1.25));
        // And that tolerance works.
        assert!(segment(&ramp(100.0, 20.0, 36.0), spec(e.workable.0, 2.4)).is_ok());
    }

    #[test]
    fn a_flat_track_is_one_segment_and_a_short_track_is_allowed_one() {
        let s = segment(&ramp(50.0, 10.0, 10.0), spec(0.01, 2.4)).unwrap();
        assert_eq!(s.segments.len(), 1);
        assert_eq!(s.error.0, 0.0);
        let s = segment(&ramp(1.0, 10.0, 10.1), spec(0.1, 2.4)).unwrap();
        assert_eq!(s.segments.len(), 1);
    }

    #[test]
    fn an_unreachable_tolerance_stops_at_the_cap() {
        let r = segment(&ramp(100.0, 20.0, 36.0), spec(1e-6, 1e-6));
        assert!(matches!(r, Err(SegmentError::TooMany { .. })));
    }
}

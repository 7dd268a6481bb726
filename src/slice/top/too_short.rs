//! The error when a track's height tolerance needs constant-speed segments
//! shorter than the controller's minimum (`lmd::segments-too-short`), with
//! the tolerance that works on every track.

use super::footprint::Footprint;
use super::tracks::Failure;
use crate::diag::message::{self, top::TooShortSegments};
use crate::diag::Diagnostic;
use crate::sema::model::{Axis, Bead, TopExtrusion, VariableSlicing};
use crate::slice::variable::segments::{segment, SegmentError, SegmentSpec};
use crate::slice::variable::Positive;
use crate::units::Length;

/// `x` rounded up to two significant digits: a tolerance shown rounded
/// must still be one that works.
pub fn ceil_2(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let scale = 10f64.powf(x.log10().floor() - 1.0);
    let r = (x / scale).ceil() * scale;
    // `ceil` of a value a rounding above a whole step: keep the step.
    let down = (x / scale).round() * scale;
    if (down - x).abs() <= 1e-12 * x {
        down
    } else {
        r
    }
}

/// The diagnostic for `failures` (at least one) of the `tracks` laid with
/// segments at least `min` long.
pub fn report(
    failures: &[Failure],
    tracks: usize,
    scan: Axis,
    bead: &Bead,
    slicing: &VariableSlicing,
    ex: &TopExtrusion,
    min: Positive,
) -> Diagnostic {
    let locate = |worst: &Failure| {
        let place = (tracks > 1).then(|| (scan.across().name(), worst.c));
        let through = ex
            .turned
            .as_ref()
            .map(|f| f.footprint(Footprint::point(scan, worst.middle, worst.c)));
        (place, through)
    };
    let at = (tracks, ex.top_span);
    report_at(failures, at, bead, slicing, min, locate)
}

/// What places a failing track in the error: its line across and the
/// axis, or a point of the part it runs through.
pub type Place = (Option<(&'static str, f64)>, Option<[f64; 3]>);

/// The diagnostic for `failures` (at least one) of `tracks` laid with
/// segments at least `min` long, up to the top written at `top`; `locate`
/// places the worst.
pub fn report_at(
    failures: &[Failure],
    (tracks, top): (usize, crate::span::Span),
    bead: &Bead,
    slicing: &VariableSlicing,
    min: Positive,
    locate: impl Fn(&Failure) -> Place,
) -> Diagnostic {
    // The tolerance that works on every track: the largest of the least
    // errors the failing tracks can reach.
    let workable = |f: &Failure| match f.error {
        SegmentError::TooShort(e) => e.workable.0,
        SegmentError::TooMany { workable, .. } => workable.0,
    };
    let worst = failures
        .iter()
        .max_by(|a, b| workable(a).total_cmp(&workable(b)))
        .unwrap_or(&failures[0]);
    let fix = ceil_2(workable(worst));
    let length = Length(worst.length);
    let count = Positive::new("tolerance", Length(fix))
        .ok()
        .and_then(|tolerance| {
            segment(
                &worst.profile,
                SegmentSpec {
                    tolerance,
                    min_length: min,
                },
            )
            .ok()
            .map(|s| s.segments.len())
        });
    let (place, through) = locate(worst);
    message::top::segments_too_short(&TooShortSegments {
        tolerance: slicing.tolerance,
        min_length: slicing.min_length.unwrap_or(bead.width),
        min_declared: slicing.min_length.is_some(),
        length,
        place,
        through,
        failing: failures.len(),
        tracks,
        error: worst.error,
        fix,
        fix_segments: count,
        spans: [
            slicing.tolerance_span.unwrap_or(slicing.span),
            slicing.min_length_span.unwrap_or(bead.span),
            top,
        ],
    })
}

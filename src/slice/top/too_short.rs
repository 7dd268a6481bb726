//! The error when a track's height tolerance needs constant-speed segments
//! shorter than the controller's minimum (`lmd::segments-too-short`), with
//! the tolerance that works on every track.

use super::tracks::Failure;
use crate::diag::{Code, Diagnostic};
use crate::sema::model::{Axis, Bead, TopExtrusion, VariableSlicing};
use crate::slice::variable::segments::{segment, SegmentError, SegmentSpec, MAX_SEGMENTS};
use crate::slice::variable::Positive;
use crate::units::{short, Length};

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
    let tol = slicing.tolerance;
    let min_length = slicing.min_length.unwrap_or(bead.width);
    let place = if tracks > 1 {
        format!(" at {} = {} mm", scan.across().name(), short(worst.c))
    } else {
        String::new()
    };
    let length = Length(worst.length);
    let others = match failures.len() {
        1 => String::new(),
        n => format!(" ({n} of the {tracks} tracks need segments that short)"),
    };
    let message = match worst.error {
        SegmentError::TooShort(e) => match e.needed {
            Some((m, len)) => format!(
                "a height tolerance of {tol} needs {m} segments of {len} on the {length} track{place}, shorter than min_length {min_length}{others}"
            ),
            None => format!(
                "a height tolerance of {tol} needs more than {MAX_SEGMENTS} segments on the {length} track{place}, shorter than min_length {min_length}{others}"
            ),
        },
        SegmentError::TooMany { .. } => format!(
            "a height tolerance of {tol} needs more than {MAX_SEGMENTS} segments on the {length} track{place}{others}"
        ),
    };
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
    let works = match count {
        Some(m) => format!(
            "`tolerance = {} mm` works ({m} segments of {} on that track)",
            short(fix),
            Length(worst.length / m as f64)
        ),
        None => format!("`tolerance = {} mm` works", short(fix)),
    };
    Diagnostic::error(Code::SegmentsTooShort, message)
        .label(
            slicing.tolerance_span.unwrap_or(slicing.span),
            format!("tolerance {tol}"),
        )
        .label(
            slicing.min_length_span.unwrap_or(bead.span),
            match slicing.min_length {
                Some(_) => format!("min_length {min_length}"),
                None => format!("min_length: the bead width {min_length}"),
            },
        )
        .label(ex.top_span, "the top the segments follow")
        .help(format!(
            "{works}, or a lower `min_length` if the controller can change speed that often"
        ))
}

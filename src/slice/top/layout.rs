//! Where the tracks of a variable layer run across the scan axis: spaced so
//! that unequal beads meet level (seed 003 eq. 4 as corrected,
//! [`crate::slice::variable::overlap`]), or at a declared offset. Every layer
//! lays the same fraction of the top, so every layer has the same tracks.
//!
//! The balance needs the layer's thickness across the tracks, which the
//! overlap model takes linear from one edge to the other: it is read off the
//! top's mean along the first and the last track line and extended to the
//! outer faces — exact for a plane, which the tracks then follow with the
//! spacing each pair needs; on a curved top the spacing follows the top's
//! average slope across.

use super::footprint::{Footprint, Sampled};
use crate::diag::{message, Diagnostic};
use crate::fill::CLOSING;
use crate::sema::model::{Axis, Bead, TopExtrusion, VariableSlicing};
use crate::slice::variable::overlap::{lay_tracks, CrossSection, OverlapError, MAX_TRACKS};
use crate::slice::variable::Positive;
use crate::units::Length;
use std::num::NonZeroU32;

/// `|σ − 1|` above this is reported (`lmd::overlap-stretch`).
pub const STRETCH_WARNING: f64 = 0.05;

/// The track lines of one layer.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Each line's coordinate across the scan axis, in order, mm.
    pub centres: Vec<f64>,
    /// The strip each line's track fills, mm: the mean of its spacings to
    /// the lines either side (the one it has at an edge), the bead's width
    /// for a lone line. The layer rises `A/pitch` along it
    /// ([`crate::deposit`]).
    pub pitches: Vec<f64>,
    /// The closure's stretch of the balanced spacing (`None`: a declared
    /// offset).
    pub stretch: Option<f64>,
}

/// Lays the track lines of a layer `n` layers deep.
pub fn lay(
    fp: &Footprint,
    scan: Axis,
    sampled: &Sampled,
    n: NonZeroU32,
    bead: &Bead,
    slicing: &VariableSlicing,
    ex: &TopExtrusion,
) -> Result<Layout, Diagnostic> {
    let Some([c_lo, c_hi]) = fp.centres(scan) else {
        return Err(fp.too_narrow(ex, scan));
    };
    let w = bead.width.0;
    let layout = match slicing.offset {
        Some((d, _)) => {
            let centres = fixed(c_lo, c_hi, d.0);
            Layout {
                pitches: pitches(&centres, w),
                centres,
                stretch: None,
            }
        }
        None => balanced(fp, scan, sampled, n, w).map_err(|e| error(e, ex, fp, scan))?,
    };
    if layout.centres.len() > MAX_TRACKS {
        return Err(error(OverlapError::TooManyTracks, ex, fp, scan));
    }
    Ok(layout)
}

/// The strip each of the lines at `centres` fills: the mean of its spacings
/// to its neighbours, the one it has at an edge, `w` for a lone line.
fn pitches(centres: &[f64], w: f64) -> Vec<f64> {
    let n = centres.len();
    if n < 2 {
        return vec![w; n];
    }
    (0..n)
        .map(|k| {
            let before = (k > 0).then(|| centres[k] - centres[k - 1]);
            let after = (k + 1 < n).then(|| centres[k + 1] - centres[k]);
            match (before, after) {
                (Some(a), Some(b)) => 0.5 * (a + b),
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => w,
            }
        })
        .collect()
}

/// The pitch the layer count is chosen for, known before the tracks are
/// laid: the bead's width when one line fills the footprint (or a declared
/// offset leaves room for one only), the declared offset, or `None` for the
/// balanced layout, whose spacing makes each track rise by its bead's own
/// height (`h·C = A`).
pub fn count_pitch(fp: &Footprint, scan: Axis, w: f64, slicing: &VariableSlicing) -> Option<f64> {
    let [c_lo, c_hi] = fp.centres(scan)?;
    match slicing.offset {
        _ if c_hi - c_lo <= 0.0 => Some(w),
        Some((d, _)) if c_hi - c_lo <= CLOSING * d.0 => Some(w),
        Some((d, _)) => Some(d.0),
        None => None,
    }
}

/// Lines `d` apart from the first, and one on the last when more than
/// [`CLOSING`] of an offset is left (the planar raster's rule).
fn fixed(c_lo: f64, c_hi: f64, d: f64) -> Vec<f64> {
    let count = ((c_hi - c_lo) / d + 1e-9).floor().min(MAX_TRACKS as f64) as usize + 1;
    let mut out: Vec<f64> = (0..count).map(|k| c_lo + k as f64 * d).collect();
    if c_hi - out[out.len() - 1] > CLOSING * d {
        out.push(c_hi);
    }
    out
}

/// The balanced lines across the outer faces.
fn balanced(
    fp: &Footprint,
    scan: Axis,
    s: &Sampled,
    n: NonZeroU32,
    w: f64,
) -> Result<Layout, OverlapError> {
    let [o_lo, o_hi] = fp.outer_across(scan);
    let n = n.get() as f64;
    // The mean top along the first and last lines, extended to the faces.
    let (c0, m0) = s.lines[0];
    let (c1, m1) = s.lines[s.lines.len() - 1];
    let k = if c1 > c0 { (m1 - m0) / (c1 - c0) } else { 0.0 };
    // A top that falls to nothing within half a bead of a face keeps the
    // line's own value there instead.
    let first = Some(m0 - k * (c0 - o_lo))
        .filter(|&h| h > 0.0)
        .unwrap_or(m0);
    let far = Some(m1 + k * (o_hi - c1))
        .filter(|&h| h > 0.0)
        .unwrap_or(m1);
    let section = CrossSection::new(Length(o_hi - o_lo), Length(first / n), Length(far / n))
        .map_err(|_| OverlapError::NoClosure)?;
    let bead = Positive::new("bead width", Length(w)).map_err(|_| OverlapError::NoClosure)?;
    let t = lay_tracks(&section, bead)?;
    // Centres from the first face (a single one mid-way).
    let centres: Vec<f64> = t.centres.iter().map(|c| o_lo + c.0).collect();
    Ok(Layout {
        pitches: pitches(&centres, w),
        centres,
        stretch: Some(t.stretch),
    })
}

fn error(e: OverlapError, ex: &TopExtrusion, fp: &Footprint, scan: Axis) -> Diagnostic {
    match e {
        OverlapError::TooNarrow { .. } => fp.too_narrow(ex, scan),
        OverlapError::TooManyTracks => message::top::too_many_tracks(MAX_TRACKS, ex.shape_span),
        OverlapError::NoClosure => message::top::no_closure(ex.top_span),
    }
}

/// The warning when the closure stretches (or squeezes) the balanced spacing
/// by more than [`STRETCH_WARNING`].
pub fn stretch_warning(
    layout: &Layout,
    w: f64,
    slicing: &VariableSlicing,
    ex: &TopExtrusion,
) -> Option<Diagnostic> {
    let s = layout.stretch?;
    if (s - 1.0).abs() <= STRETCH_WARNING {
        return None;
    }
    // The balance unstretched spans its centres' distance over σ; the
    // footprint's faces lie half a bead outside the first and last centre.
    let (first, last) = (layout.centres[0], layout.centres[layout.centres.len() - 1]);
    let fits = (last - first) / s + w;
    Some(message::top::stretched(
        layout.centres.len(),
        s,
        fits,
        slicing.span,
        ex.shape_span,
    ))
}

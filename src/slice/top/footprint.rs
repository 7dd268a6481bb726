//! Where the tracks of a variable-top solid can run: straight lines along the
//! scan axis, clipped exactly against the footprint (lines and true arcs, the
//! raster's clip) offset half a bead inward when the footprint is the part's
//! outer face (`size = outer`), so that no bead passes a curved or slanted
//! edge either. Across the scan axis the first and last track centres sit
//! half a bead inside the outer face, as in a planar fill.
//!
//! Also the top sampled over that region, for the layer count: its lowest
//! and highest points, each line's mean, and how much it rises along a line.

use super::surface::{Bad, Surface};
use crate::diag::{message, Diagnostic};
use crate::fill::intervals_at;
use crate::geometry::{outline, profile::Profile};
use crate::sema::model::{Axis, Measure, TopExtrusion};

/// Arcs of a section footprint (an ellipse) are flattened within this, mm.
const CHORD_ERROR: f64 = 0.01;

/// A track shorter than this (mm) is a point: dropped.
pub const MIN_TRACK: f64 = 1e-6;

/// Most top evaluations when sampling the region (the pitch grows to fit).
const MAX_SAMPLES: f64 = 1e6;

/// The footprint of a variable-top solid, for one bead width.
pub struct Footprint {
    /// Where the track centre lines may run: the footprint, offset inward
    /// by the inset.
    region: Vec<Profile>,
    /// How much the clipped lines are shortened at both ends: the inset
    /// where the offset footprint is empty, else 0.
    shorten: f64,
    bounds: [[f64; 2]; 2],
    /// How far inside the written footprint the tracks' centre lines end
    /// (half a bead for `size = outer`, else 0).
    inset: f64,
    /// The bead width.
    width: f64,
}

impl Footprint {
    /// The footprint of `ex` built with beads `width` wide.
    pub fn new(ex: &TopExtrusion, width: f64) -> Result<Self, Diagnostic> {
        let profile = outline::profile(&ex.shape, CHORD_ERROR);
        if let Some(p) = profile.self_intersection() {
            return Err(message::top::footprint_crosses(
                p,
                ex.shape_span,
                ex.turned.as_ref(),
            ));
        }
        let bounds = profile
            .bounds()
            .filter(|b| b.iter().flatten().all(|v| v.is_finite()))
            .ok_or_else(|| message::top::footprint_empty(ex.shape_span))?;
        let inset = match ex.measure {
            Measure::Outer => width / 2.0,
            Measure::Centre => 0.0,
        };
        // A footprint exactly a bead wide offsets to nothing: its centre
        // line then runs along the written footprint, shortened by the
        // inset at its ends.
        let inner = (inset > 0.0)
            .then(|| profile.offset_inward(inset))
            .filter(|r| !r.is_empty());
        let shorten = if inner.is_some() { 0.0 } else { inset };
        Ok(Footprint {
            region: inner.unwrap_or_else(|| vec![profile]),
            shorten,
            bounds,
            inset,
            width,
        })
    }

    /// The written footprint's extent along `axis`, `[lo, hi]` mm: the
    /// extreme edges `edges(…)` gives its heights at.
    pub fn written_extent(&self, axis: Axis) -> [f64; 2] {
        let i = index(axis);
        [self.bounds[0][i], self.bounds[1][i]]
    }

    /// The part's outer face across `scan` (the footprint, or half a bead
    /// beyond the centre lines it gives), `[lo, hi]` mm.
    pub fn outer_across(&self, scan: Axis) -> [f64; 2] {
        let [lo, hi] = self.written_extent(scan.across());
        let grow = self.width / 2.0 - self.inset;
        [lo - grow, hi + grow]
    }

    /// The range of track centre lines across `scan`: half a bead inside
    /// the outer face; `None` when the footprint is narrower than a bead.
    pub fn centres(&self, scan: Axis) -> Option<[f64; 2]> {
        let [lo, hi] = self.outer_across(scan);
        let half = self.width / 2.0;
        let (a, b) = (lo + half, hi - half);
        let slack = 1e-9 * (hi - lo).abs().max(1.0);
        if b >= a {
            Some([a, b])
        } else if a - b <= slack {
            let mid = (a + b) / 2.0;
            Some([mid, mid])
        } else {
            None
        }
    }

    /// The intervals along `scan` where tracks run on the lines at cross
    /// coordinates `at`: the clip by the inset footprint (or by the written
    /// one, shortened), points dropped.
    pub fn intervals(&self, scan: Axis, at: &[f64]) -> Vec<Vec<[f64; 2]>> {
        // Along x the raster frame's cross coordinate is y; along y (90°)
        // it is −x.
        let (angle, sign) = match scan {
            Axis::X => (0.0, 1.0),
            Axis::Y => (90.0, -1.0),
        };
        let s: Vec<f64> = at.iter().map(|c| sign * c).collect();
        intervals_at(&self.region, angle, &s)
            .into_iter()
            .map(|line| {
                line.into_iter()
                    .map(|[a, b]| [a + self.shorten, b - self.shorten])
                    .filter(|[a, b]| b - a >= MIN_TRACK)
                    .collect()
            })
            .collect()
    }

    /// The world point at `t` along `scan` on the line at `c` across.
    pub fn point(scan: Axis, t: f64, c: f64) -> [f64; 2] {
        match scan {
            Axis::X => [t, c],
            Axis::Y => [c, t],
        }
    }

    /// The footprint's width across `scan` and the bead's, for "narrower
    /// than a bead" errors.
    pub fn too_narrow(&self, ex: &TopExtrusion, scan: Axis) -> Diagnostic {
        let [lo, hi] = self.outer_across(scan);
        message::top::footprint_too_narrow(hi - lo, scan.across().name(), self.width, ex.shape_span)
    }
}

fn index(axis: Axis) -> usize {
    match axis {
        Axis::X => 0,
        Axis::Y => 1,
    }
}

/// `n + 1` equally spaced values from `a` to `b` (just `a` when they meet),
/// `n` the fewest whose spacing is at most `pitch`.
pub fn spaced(a: f64, b: f64, pitch: f64) -> Vec<f64> {
    let n = ((b - a) / pitch).ceil();
    if !(n.is_finite() && n >= 1.0) {
        return vec![a];
    }
    let n = n as usize;
    (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            }
        })
        .collect()
}

/// The top sampled where tracks can run.
#[derive(Clone, Debug)]
pub struct Sampled {
    /// The lowest top and where, mm.
    pub low: (f64, [f64; 2]),
    /// The highest top and where, mm.
    pub high: (f64, [f64; 2]),
    /// Each line's cross coordinate and the mean top along it (lines with
    /// no track left out), in order across.
    pub lines: Vec<(f64, f64)>,
    /// The most the top rises along one line.
    pub rise: f64,
}

/// Samples the top over the lines tracks along `scan` can take, every
/// `pitch` (coarser for a huge footprint) across and along. `Ok(None)` when
/// no track fits at all.
pub fn sample(
    fp: &Footprint,
    scan: Axis,
    top: &mut Surface<'_>,
    pitch: f64,
) -> Result<Option<Sampled>, (Bad, usize)> {
    let Some([c_lo, c_hi]) = fp.centres(scan) else {
        return Ok(None);
    };
    let [t_lo, t_hi] = fp.written_extent(scan);
    let cells = (c_hi - c_lo + pitch) * (t_hi - t_lo + pitch) / (pitch * pitch);
    let most = top.most_samples(MAX_SAMPLES);
    let pitch = if cells > most {
        pitch * (cells / most).sqrt()
    } else {
        pitch
    };
    let at = spaced(c_lo, c_hi, pitch);
    let mut bad: Option<Bad> = None;
    let mut more = 0usize;
    let mut low = (f64::INFINITY, [0.0; 2]);
    let mut high = (f64::NEG_INFINITY, [0.0; 2]);
    let (mut lines, mut rise) = (Vec::new(), 0.0f64);
    for (c, intervals) in at.iter().zip(fp.intervals(scan, &at)) {
        let (mut sum, mut count) = (0.0, 0usize);
        for [a, b] in intervals {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for t in spaced(a, b, pitch) {
                let p = Footprint::point(scan, t, *c);
                match top.at(p) {
                    Ok(h) => {
                        (lo, hi) = (lo.min(h), hi.max(h));
                        if h < low.0 {
                            low = (h, p);
                        }
                        if h > high.0 {
                            high = (h, p);
                        }
                        sum += h;
                        count += 1;
                    }
                    Err(e) if bad.is_none() => bad = Some(e),
                    Err(_) => more += 1,
                }
            }
            if hi >= lo {
                rise = rise.max(hi - lo);
            }
        }
        if count > 0 {
            lines.push((*c, sum / count as f64));
        }
    }
    if let Some(b) = bad {
        return Err((b, more));
    }
    Ok((!lines.is_empty()).then_some(Sampled {
        low,
        high,
        lines,
        rise,
    }))
}

//! The tracks of a variable layer along the scan axis, and where each one's
//! speed changes (seed 003 eq. 7, [`crate::slice::variable::segments`]): the
//! top is sampled along the track, the samples a straight top passes through
//! are dropped (a plane keeps its two ends, so its segmentation is exact),
//! and the track is cut into the fewest equal constant-height segments that
//! meet the tolerance. A track's points are its kept samples and every
//! segment end; every layer has the same tracks and segments, since each
//! lays the same fraction of the top.

use super::count::TopRange;
use super::footprint::{spaced, Footprint};
use super::layout::Layout;
use super::surface::{Bad, Surface};
use crate::sema::model::Axis;
use crate::slice::variable::profile::TrackProfile;
use crate::slice::variable::segments::{segment, SegmentError, SegmentSpec};
use crate::slice::variable::{HeightRange, Invalid};
use crate::units::Length;

/// Most samples of the top over all tracks of a layer.
const MAX_SAMPLES: f64 = 1e6;

/// One track: the same on every layer.
#[derive(Clone, Debug)]
pub struct Track {
    /// Its line's coordinate across the scan axis, mm.
    pub c: f64,
    /// The strip of the layer it fills, mm ([`super::layout::Layout::pitches`]).
    pub pitch: f64,
    /// Point positions along the scan axis, increasing, mm.
    pub t: Vec<f64>,
    /// The top at each point, mm.
    pub h: Vec<f64>,
    /// For each move `t[j] → t[j+1]`, the segment it belongs to.
    pub seg: Vec<usize>,
    /// Each segment's top height (each layer lays `height / N`), mm.
    pub heights: Vec<f64>,
}

impl Track {
    /// Its length, mm.
    pub fn length(&self) -> f64 {
        self.t[self.t.len() - 1] - self.t[0]
    }
}

/// A track whose tolerance needs segments shorter than allowed.
#[derive(Clone, Debug)]
pub struct Failure {
    /// Its line across, mm.
    pub c: f64,
    /// Its length, mm.
    pub length: f64,
    /// Its middle along the scan axis, mm.
    pub middle: f64,
    /// Why.
    pub error: SegmentError,
    /// The top along it, to find a tolerance that works.
    pub profile: TrackProfile,
}

/// What stops the tracks.
#[derive(Debug)]
pub enum Problem {
    /// The top is not a positive height at a point (and at `usize` more).
    Top(Bad, usize),
    /// A track the segmentation cannot take (a bug, not a user's mistake).
    Invalid(Invalid),
}

/// Every track of a layer and the failures of those that cannot be
/// segmented; the top's range over every point.
pub struct Tracks {
    /// In order across, and along each line.
    pub tracks: Vec<Track>,
    /// Tracks whose tolerance cannot be met.
    pub failures: Vec<Failure>,
    /// The top's range over every point of every track.
    pub range: Option<TopRange>,
}

/// The tracks on `layout`'s lines, sampled every `pitch` along.
pub fn plan(
    fp: &Footprint,
    scan: Axis,
    layout: &Layout,
    top: &mut Surface<'_>,
    spec: SegmentSpec,
    pitch: f64,
) -> Result<Tracks, Problem> {
    let mut out = Tracks {
        tracks: Vec::new(),
        failures: Vec::new(),
        range: None,
    };
    let mut bad: Option<Bad> = None;
    let mut more = 0usize;
    let most = top.most_samples(MAX_SAMPLES);
    let mut eval = |p: [f64; 2]| match top.at(p) {
        Ok(h) => Some(h),
        Err(e) => {
            if bad.is_none() {
                bad = Some(e);
            } else {
                more += 1;
            }
            None
        }
    };
    let lines = fp.intervals(scan, &layout.centres);
    // A huge footprint is sampled more coarsely: a bounded number of points.
    let total: f64 = lines.iter().flatten().map(|[a, b]| b - a).sum();
    let pitch = pitch.max(total / most);
    for ((&c, &track_pitch), intervals) in layout.centres.iter().zip(&layout.pitches).zip(lines) {
        for [a, b] in intervals {
            let samples: Vec<(f64, f64)> = spaced(a, b, pitch)
                .into_iter()
                .filter_map(|t| eval(Footprint::point(scan, t, c)).map(|h| (t, h)))
                .collect();
            match segmented(c, track_pitch, &samples, spec, |t| {
                eval(Footprint::point(scan, t, c))
            })
            .map_err(Problem::Invalid)?
            {
                Some(Ok(track)) => out.tracks.push(track),
                Some(Err(failure)) => out.failures.push(failure),
                None => {}
            }
        }
    }
    if let Some(b) = bad {
        return Err(Problem::Top(b, more));
    }
    out.range = range(&out.tracks, scan);
    Ok(out)
}

/// The track on line `c` (filling a strip `pitch` wide) through `samples`
/// of its height `(t, h)`, in the fewest segments within `spec`; `h(t)`
/// gives the height at a segment's end. `None` for fewer than two samples
/// off a straight line; a [`Failure`] when the tolerance needs segments too
/// short.
pub(super) fn segmented(
    c: f64,
    pitch: f64,
    samples: &[(f64, f64)],
    spec: SegmentSpec,
    mut h: impl FnMut(f64) -> Option<f64>,
) -> Result<Option<Result<Track, Failure>>, Invalid> {
    let kept = straight_dropped(samples);
    let (Some(first), Some(last)) = (kept.first(), kept.last()) else {
        return Ok(None);
    };
    if kept.len() < 2 {
        return Ok(None);
    }
    let length = last.0 - first.0;
    let profile = TrackProfile::new(kept.iter().map(|&(t, h)| (Length(t), Length(h))))?;
    let s = match segment(&profile, spec) {
        Ok(s) => s,
        Err(error) => {
            return Ok(Some(Err(Failure {
                c,
                length,
                middle: (first.0 + last.0) / 2.0,
                error,
                profile,
            })))
        }
    };
    let mut t: Vec<f64> = kept.iter().map(|p| p.0).collect();
    t.extend(s.segments.iter().map(|g| g.start.0));
    t.sort_by(f64::total_cmp);
    t.dedup_by(|x, y| (*x - *y).abs() <= 1e-9 * y.abs().max(1.0));
    let heights_at: Vec<f64> = t.iter().map(|&t| h(t).unwrap_or(f64::NAN)).collect();
    let mut q = 0;
    let seg = t
        .windows(2)
        .map(|m| {
            let mid = 0.5 * (m[0] + m[1]);
            while q + 1 < s.segments.len() && mid >= s.segments[q].end.0 {
                q += 1;
            }
            q
        })
        .collect();
    let heights = s.segments.iter().map(|g| g.height.0).collect();
    Ok(Some(Ok(Track {
        c,
        pitch,
        t,
        h: heights_at,
        seg,
        heights,
    })))
}

/// The samples without those a straight line through their neighbours
/// passes (to 1e-9 of the top): a plane keeps its ends, a curve its bends.
fn straight_dropped(samples: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let Some((&first, rest)) = samples.split_first() else {
        return Vec::new();
    };
    let scale = samples.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
    let mut kept = vec![first];
    for (j, &p) in rest.iter().enumerate() {
        let Some(&next) = rest.get(j + 1) else {
            kept.push(p);
            break;
        };
        let last = kept[kept.len() - 1];
        let f = (p.0 - last.0) / (next.0 - last.0);
        let line = last.1 + f * (next.1 - last.1);
        if (p.1 - line).abs() > 1e-9 * scale {
            kept.push(p);
        }
    }
    kept
}

/// The top's range over every point of `tracks`.
fn range(tracks: &[Track], scan: Axis) -> Option<TopRange> {
    let mut low = (f64::INFINITY, [0.0; 2]);
    let mut high = (f64::NEG_INFINITY, [0.0; 2]);
    for tr in tracks {
        for (&t, &h) in tr.t.iter().zip(&tr.h) {
            let p = Footprint::point(scan, t, tr.c);
            if h < low.0 {
                low = (h, p);
            }
            if h > high.0 {
                high = (h, p);
            }
        }
    }
    let heights = HeightRange::new("top", Length(low.0), Length(high.0)).ok()?;
    Some(TopRange {
        heights,
        low_at: low.1,
        high_at: high.1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_top_keeps_its_ends_and_a_bent_one_its_bend() {
        let line: Vec<(f64, f64)> = (0..=10)
            .map(|i| (i as f64, 20.0 + 0.16 * i as f64))
            .collect();
        assert_eq!(straight_dropped(&line), vec![line[0], line[10]]);
        let bent: Vec<(f64, f64)> = (0..=10)
            .map(|i| (i as f64, 20.0 + (i as f64 - 4.0).abs()))
            .collect();
        assert_eq!(straight_dropped(&bent), vec![bent[0], bent[4], bent[10]]);
    }
}

use super::clamp;
use super::clip::{sweep, Frame, Pieces, Scratch};
use super::ends::Ends;
use super::extend::extend_kept;
use super::link::{self, Chains};
use super::margin;
use super::{
    spend, too_many_points, Count, FillError, Link, Pattern, RasterSpec, Track, TrackKind,
    MAX_LINES,
};
use crate::geometry::profile::{Profile, TOLERANCE};
use crate::geometry::region::Region;

/// Lines up to this fraction of an offset past the region's far extreme
/// still count, so that a region exactly `k` offsets wide gets `k + 1` lines
/// despite rounding.
const LINE_SLACK: f64 = 1e-9;

/// More than this many offsets left over past the last line gets a closing
/// line on the far extreme.
pub const CLOSING: f64 = 0.5;

/// What the raster needs to know besides its own region.
pub(super) struct Context<'a> {
    /// Loops no track end is extended into: the holes grown by the inset,
    /// where a bead would lay metal into the hole.
    pub keep_out: &'a [Profile],
    /// When neighbouring tracks are linked: the region a link must stay in
    /// (where track centre lines may run) and whether the laser stays on.
    pub link: Option<(&'a Region, bool)>,
    /// Arcs a link follows are flattened within this, mm.
    pub chord_error: f64,
}

/// The raster tracks over `region` (what is left inside the contours), in
/// travel order; `points_left` is the layer's point budget, spent here.
pub(super) fn tracks(
    region: &Region,
    spec: &RasterSpec,
    cx: &Context<'_>,
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let frame = Frame::new(spec.angle_deg);
    let pieces = Pieces::new(region.loops(), &frame);
    let Some(extent) = pieces.extent() else {
        return Ok(Vec::new());
    };
    let line_s = line_positions(extent, spec.offset, spec.closing)?;
    let (lines, ends) = clip_lines(&pieces, &line_s, extent.0, spec.offset, cx, points_left)?;

    let mut grown = extend_kept(&lines, spec.extend);
    if !cx.keep_out.is_empty() && spec.extend > 0.0 {
        let keep = Pieces::new(cx.keep_out.iter().map(|p| (p, true)), &frame);
        clamp::clamp(&mut grown, &lines, &line_s, &keep.items);
    }
    // Beside an edge, what the tracks lay: their intervals as extended.
    let threshold = spec.closing.min(CLOSING * spec.offset);
    let edges = super::edge::closings(
        region,
        (&pieces, &frame),
        (&line_s, &grown),
        [threshold, spec.offset, spec.extend],
    );
    let laid = margin::Tracks {
        line_s: &line_s,
        lines: &grown,
        edges: &edges,
    };
    // With contours, where the innermost would be left without a track
    // beside it (without, the raster's ends are the layer's edge).
    let margins = if spec.closing.is_finite() {
        margin::closings(&pieces, &laid, [threshold, spec.offset, cx.chord_error])
    } else {
        Vec::new()
    };
    // Both found in the raster's frame; laid in the world's.
    let closings: Vec<Vec<[f64; 2]>> = edges
        .iter()
        .map(|e| e.iter().map(|&q| frame.world(q)).collect())
        .chain(
            margins
                .into_iter()
                .map(|m| m.into_iter().map(|q| frame.world(q)).collect()),
        )
        .collect();

    if let Some((within, laser)) = cx.link {
        let chains = link::chains(
            &Chains {
                s: &line_s,
                clipped: &lines,
                ends: &ends,
                grown: &grown,
                pieces: &pieces,
                chord_error: cx.chord_error,
            },
            &Pieces::new(within.loops(), &frame),
            laser,
        );
        let mut out = link::tracks(&chains, &grown, &line_s, &frame, points_left)?;
        closing_tracks(closings, &mut out, points_left)?;
        return Ok(out);
    }

    let mut out = Vec::new();
    let mut forward = true;
    for (n, line) in grown.iter().enumerate() {
        if line.is_empty() {
            continue;
        }
        let s = line_s[n];
        spend(points_left, 2 * line.len())?;
        let track = |a: f64, b: f64| Track {
            kind: TrackKind::Infill,
            points: vec![frame.world([a, s]), frame.world([b, s])],
            link: None::<Link>,
        };
        if forward {
            out.extend(line.iter().map(|&(_, [a, b])| track(a, b)));
        } else {
            out.extend(line.iter().rev().map(|&(_, [a, b])| track(b, a)));
        }
        if spec.pattern == Pattern::Serpentine {
            forward = !forward;
        }
    }
    closing_tracks(closings, &mut out, points_left)?;
    Ok(out)
}

/// Adds the closing tracks (module `edge`'s along edges that run with the
/// lines, module `margin`'s where the contour has no track within reach)
/// to the raster's: each after the end of a run of tracks (a track not
/// linked on) nearest one of its ends, laid from that end, so the nozzle
/// lays it on its way rather than coming back for it.
fn closing_tracks(
    closings: Vec<Vec<[f64; 2]>>,
    out: &mut Vec<Track>,
    points_left: &mut u64,
) -> Result<(), FillError> {
    if closings.is_empty() {
        return Ok(());
    }
    spend(points_left, closings.iter().map(Vec::len).sum())?;
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    // For each closing track, the run end it follows and its way round:
    // the end nearest either of its own, the first of those equally near.
    let ends = Ends::new(
        out.iter()
            .enumerate()
            .filter(|(_, t)| t.link.is_none())
            .filter_map(|(i, t)| t.points.last().map(|&e| (i, e))),
    );
    let mut after: Vec<Vec<Track>> = vec![Vec::new(); out.len() + 1];
    for track in closings {
        let (Some(&a), Some(&b)) = (track.first(), track.last()) else {
            continue;
        };
        let best = match (ends.nearest(a), ends.nearest(b)) {
            (Some(x), Some(y)) => Some(if (y.1, y.0) < (x.1, x.0) { y } else { x }),
            (x, y) => x.or(y),
        };
        let mut points = track;
        let slot = match best {
            Some((i, _, e)) if dist(e, b) < dist(e, a) => {
                points.reverse();
                i + 1
            }
            Some((i, _, _)) => i + 1,
            None => out.len(),
        };
        after[slot].push(Track {
            kind: TrackKind::Infill,
            points,
            link: None,
        });
    }
    let tracks = std::mem::take(out);
    for (i, t) in tracks.into_iter().enumerate() {
        out.append(&mut after[i]);
        out.push(t);
    }
    out.extend(after.pop().into_iter().flatten());
    Ok(())
}

/// Each raster line's `s` over the extent `(s_min, s_max)`, `d` apart,
/// with a closing line on `s_max` where more than `closing` (at most
/// [`CLOSING`] offsets) is left.
fn line_positions((s_min, s_max): (f64, f64), d: f64, closing: f64) -> Result<Vec<f64>, FillError> {
    let count = ((s_max - s_min) / d + LINE_SLACK).floor() + 1.0;
    if count > MAX_LINES as f64 {
        return Err(FillError::TooManyLines(Count {
            // `as` saturates: a count beyond u64 reads as u64::MAX.
            wanted: count as u64,
            max: MAX_LINES,
        }));
    }
    let count = count as usize;
    // When more than half an offset is left beyond the last whole-offset
    // line, one more line on the far extreme keeps that edge from coming
    // up short by up to an offset (the last two lines are then closer).
    let closing = s_max - (s_min + (count - 1) as f64 * d) > closing.min(CLOSING * d);
    let count = count + usize::from(closing);
    // The last may sit a hair past `s_max`, so clamp it back onto the
    // extreme it is meant to touch.
    Ok((0..count)
        .map(|n| (s_min + n as f64 * d).min(s_max))
        .collect())
}

/// A raster line's intervals, and where each interval's ends meet the
/// boundary (for the links).
type Clipped = (Vec<Vec<[f64; 2]>>, Vec<Vec<[Option<u32>; 2]>>);

/// The region's intervals on each line at `line_s` (`d` apart from
/// `s_min`), sweeping the pieces that may touch each line.
fn clip_lines(
    pieces: &Pieces,
    line_s: &[f64],
    s_min: f64,
    d: f64,
    cx: &Context<'_>,
    points_left: &u64,
) -> Result<Clipped, FillError> {
    // The lines each piece may touch, one either side to spare rounding.
    let last = line_s.len() - 1;
    let range = |p: &super::clip::Piece| {
        let first = ((p.lo[1] - TOLERANCE - s_min) / d).ceil() - 1.0;
        let end = ((p.hi[1] + TOLERANCE - s_min) / d).floor() + 1.0;
        (first.max(0.0) as usize, (end.max(0.0) as usize).min(last))
    };
    let ranges: Vec<(usize, usize)> = pieces.items.iter().map(range).collect();
    let visits: u64 = ranges
        .iter()
        .map(|&(a, b)| (b + 1).saturating_sub(a) as u64)
        .sum();
    // Every visit may yield a track end: check the budget before the work.
    if visits > *points_left {
        return Err(too_many_points(*points_left, visits));
    }

    let mut order: Vec<usize> = (0..pieces.items.len()).collect();
    order.sort_by_key(|&i| ranges[i].0);
    let mut next = 0;
    let mut active: Vec<usize> = Vec::new();
    let mut lines: Vec<Vec<[f64; 2]>> = Vec::with_capacity(line_s.len());
    let mut ends: Vec<Vec<[Option<u32>; 2]>> = Vec::new();
    let mut scratch = Scratch::default();
    for (n, &s) in line_s.iter().enumerate() {
        while next < order.len() && ranges[order[next]].0 <= n {
            active.push(order[next]);
            next += 1;
        }
        active.retain(|&i| ranges[i].1 >= n);
        let line = scratch.clip(&pieces.items, active.iter().copied(), s);
        if cx.link.is_some() {
            ends.push(
                line.iter()
                    .map(|&[a, b]| [scratch.crossing_at(a), scratch.crossing_at(b)])
                    .collect(),
            );
        }
        lines.push(line);
    }
    Ok((lines, ends))
}

/// The closed region's intervals along lines of direction `angle_deg` placed
/// by the caller: for each `s` of `at` (the coordinate along the direction's
/// left normal: +y for 0°, −x for 90°), the intervals of the coordinate
/// along the line (x for 0°, y for 90°), sorted and disjoint. The same exact
/// clip as the raster's, for slicers that space their lines themselves
/// (variable layers' balanced tracks of unequal height). Linear in pieces ×
/// lines.
pub fn intervals_at(region: &[Profile], angle_deg: f64, at: &[f64]) -> Vec<Vec<[f64; 2]>> {
    let pieces = Pieces::new(region.iter().map(|p| (p, false)), &Frame::new(angle_deg));
    let mut scratch = Scratch::default();
    at.iter()
        .map(|&s| {
            let near = (0..pieces.items.len()).filter(|&i| {
                let p = &pieces.items[i];
                p.lo[1] - TOLERANCE <= s && s <= p.hi[1] + TOLERANCE
            });
            scratch.clip(&pieces.items, near, s)
        })
        .collect()
}

/// Points of `region` on a square grid of pitch `h` (rows along x), at most
/// `max` of them — the pitch grows until they fit. Used to look for gaps.
pub(super) fn samples(region: &Region, h: f64, max: usize) -> Vec<[f64; 2]> {
    let frame = Frame::new(0.0);
    let pieces = Pieces::new(region.loops(), &frame);
    let Some((lo, hi)) = pieces.extent() else {
        return Vec::new();
    };
    let (t_lo, t_hi) = pieces
        .items
        .iter()
        .flat_map(|p| [p.lo[0], p.hi[0]])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
            (a.min(t), b.max(t))
        });
    // Arcs bulge past their ends; one pitch of margin either way covers
    // the bounding box estimate for the budget only.
    let cells = ((hi - lo) / h + 1.0) * ((t_hi - t_lo) / h + 1.0);
    let h = if cells.is_finite() && cells > max as f64 {
        h * (cells / max as f64).sqrt()
    } else {
        h
    };
    if !(h.is_finite() && h > 0.0) {
        return Vec::new();
    }
    let rows = ((hi - lo) / h).floor() as usize + 1;
    // Rows sit half a pitch in, so a row never runs along an edge.
    let row_s: Vec<f64> = (0..rows.min(max))
        .map(|r| lo + (r as f64 + 0.5) * h)
        .take_while(|&s| s <= hi)
        .collect();
    let mut out = Vec::new();
    let mut scratch = Scratch::default();
    sweep(&pieces.items, &row_s, |r, active| {
        let s = row_s[r];
        for [a, b] in scratch.clip(&pieces.items, active.iter().copied(), s) {
            let n = ((b - a) / h).floor() as usize + 1;
            for k in 0..n {
                if out.len() >= max {
                    return;
                }
                let t = (a + (k as f64 + 0.5) * h).min(b);
                out.push(frame.world([t, s]));
            }
        }
    });
    out
}

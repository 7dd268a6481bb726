//! Levelling a scanned part's wear before regular layers (`level = …`,
//! docs/repair.md, *Levelling*).
//!
//! The gap `G = z_L − B` between the level `z_L` and the scanned surface
//! `B` is filled first, each point in the fewest passes that keep a bead's
//! height, `n = ⌈G/h_max⌉`, each laying `G/n` at the speed that thickness
//! needs; where `G/n` falls outside the bead's range (a bead whose
//! `h_max/h_min` is under 2 cannot lay every gap) the passes lay the
//! nearest height they can. Where the gap is thinner than half the lowest
//! bead nothing is laid ("too thin, none"): a bead there would stand up to
//! half a bead proud, and leaving it leaves at most as much. Pass `k` (from
//! 0) lays every stretch that needs more than `k` passes, so each pass lies
//! on the one before (`lmd::stacking` holds) and the last ones only fill the
//! deepest wear. A stretch of one pass count shorter than a bead is left
//! out: a laser switched on for less than a bead lays a blob, not a track.
//!
//! The regular layers then go on from the level to the top as any variable
//! solid's do ([`super::build`] over [`Base::Level`]), on the same track
//! lines; the first of them lies on the levelled part, partly on the scan,
//! so `lmd::stacking` does not look for the pass below it (`on_plate`).
//!
//! Along a tilted build direction (module `tilted`) all of this runs in
//! the part turned so the direction is up: the level is the plane square
//! to it at its height along it, and the messages name the part's points.

use super::emit::{self, Process};
use super::follow::Follow;
use super::footprint::{spaced, Footprint};
use super::layout::Layout;
use super::surface::{Base, Surface};
use super::tracks::{segmented, Failure, Track};
use super::{build, internal, too_short};
use crate::diag::{message, Diagnostics};
use crate::geometry::scan::HeightField;
use crate::ir::{Frame, Layer, Path, PathKind};
use crate::sema::model::{Axis, Bead, Level, Model, ScanBase, TopExtrusion, VariableSlicing};
use crate::slice::variable::segments::SegmentSpec;
use crate::slice::variable::speed::{BeadMap, HeightMap};
use crate::slice::variable::{ceil_slack, Positive, SLACK};
use crate::units::Length;

/// Most samples of the scan taken to find the level and check the top.
const MAX_SAMPLES: f64 = 1e6;

/// How many passes fill a gap `g` with beads of heights `lo..hi`, and the
/// height they lay together: none below half the lowest bead, else the
/// fewest passes, each `g/n` kept within the bead's range.
pub fn passes(g: f64, [lo, hi]: [f64; 2]) -> (u32, f64) {
    if !(g.is_finite() && g >= lo / 2.0 && hi >= lo && lo > 0.0) {
        return (0, 0.0);
    }
    let n = ceil_slack(g / hi).max(1.0);
    (n as u32, g.clamp(n * lo, n * hi))
}

/// A stretch of one line that takes `n` passes.
struct Piece {
    line: usize,
    n: u32,
    track: Track,
}

/// The levelling passes on `ex`'s scan, then the regular layers to the
/// top; their warnings.
pub(super) fn slice(
    model: &Model,
    bead: &Bead,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    scan: &ScanBase,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let w = bead.width.0;
    let own = BeadMap::new(bead, None).map_err(|e| internal(e.to_string()))?;
    let lowest = own.heights().low().0;
    let fp = Footprint::new(ex, w)?;
    let z = height(&fp, &scan.surface, slicing.level, lowest / 2.0, w)
        .map_err(|e| e.report(ex, slicing, scan))?;
    top_clear(&fp, ex, z, lowest, w, slicing)?;
    let regular = build(model, bead, ex, slicing, Base::Level(z))?;
    let spec = SegmentSpec {
        tolerance: positive("tolerance", slicing.tolerance)?,
        min_length: positive("min_length", slicing.min_length.unwrap_or(bead.width))?,
    };
    let tilt =
        super::follow::limit(model, bead, slicing).map(|t| (t, super::follow::part_vertical(ex)));
    let on = Line {
        fp: &fp,
        scan: regular.scan,
        surface: &scan.surface,
        z,
        bead,
        spec,
        follow: tilt.map(|(max, up)| Follow::new(&scan.surface, max, w).turned(up)),
    };
    if let Some(steep) = on.unlayable(&regular.lines)? {
        return Err(steep.report(bead, slicing, ex));
    }
    let (pieces, failures) = on.pieces(&regular.lines)?;
    if !failures.is_empty() {
        let min = spec.min_length;
        let all = pieces.len() + failures.len();
        return Err(too_short::report(&failures, all, regular.scan, bead, slicing, ex, min).into());
    }
    let passes = passes_laid(model, bead, &pieces, &regular.lines, &on, tilt)?;
    let layers = stacked(model, passes, regular.layers);
    Ok((layers, regular.warnings))
}

/// The levelling `passes`, then the `regular` layers: each regular layer
/// at the power of its place in the whole, the first of them marked as
/// lying on the levelled part (`on_plate`: partly on the scan, so
/// `lmd::stacking` does not look for the pass below it), every layer
/// numbered and placed by its station in the whole.
pub(in crate::slice) fn stacked(
    model: &Model,
    mut passes: Vec<Layer>,
    mut regular: Vec<Layer>,
) -> Vec<Layer> {
    let first = passes.len();
    for (i, layer) in regular.iter_mut().enumerate() {
        let power = model.process.power.at(first + i).watts() as f32;
        for p in layer.paths.iter_mut().flat_map(|p| &mut p.points) {
            p.power = power;
        }
        layer.on_plate = first > 0 && i == 0;
    }
    passes.extend(regular);
    let total = passes.len() as f64;
    for (i, layer) in passes.iter_mut().enumerate() {
        layer.index = i;
        layer.station = i as f64 / total;
    }
    passes
}

fn positive(what: &'static str, l: Length) -> Result<Positive, Diagnostics> {
    Positive::new(what, l).map_err(|e| internal(e.to_string()))
}

/// Why no level can be taken.
enum NoLevel {
    /// The scan has no point at this place of the footprint.
    Uncovered([f64; 2], usize),
    /// The scan stands above the level by more than `slack` here.
    Above {
        at: [f64; 2],
        surface: f64,
        level: f64,
        slack: f64,
    },
}

impl NoLevel {
    fn report(self, ex: &TopExtrusion, slicing: &VariableSlicing, scan: &ScanBase) -> Diagnostics {
        match self {
            NoLevel::Uncovered(at, more) => message::scan::uncovered(
                at,
                more,
                &scan.surface,
                ex.shape_span,
                scan.span,
                ex.turned.as_ref(),
            )
            .into(),
            NoLevel::Above {
                at,
                surface,
                level,
                slack,
            } => {
                let span = slicing.level.span().unwrap_or(slicing.span);
                let turned = ex.turned.as_ref();
                message::scan::above_level(at, surface, level, slack, [span, scan.span], turned)
                    .into()
            }
        }
    }
}

/// Points of the footprint where tracks can run, every `step` both ways
/// (coarser on a large footprint: at most [`MAX_SAMPLES`]).
fn grid_points(fp: &Footprint, w: f64) -> Vec<[f64; 2]> {
    let [x0, x1] = fp.written_extent(Axis::X);
    let [y0, y1] = fp.written_extent(Axis::Y);
    let area = ((x1 - x0) * (y1 - y0)).abs();
    let step = (w / 8.0).max((area / MAX_SAMPLES).sqrt());
    let across = spaced(y0, y1, step);
    fp.intervals(Axis::X, &across)
        .into_iter()
        .zip(&across)
        .flat_map(|(line, &c)| {
            line.into_iter()
                .flat_map(move |[a, b]| spaced(a, b, step).into_iter().map(move |t| [t, c]))
        })
        .collect()
}

/// The level: declared, or the scan's highest point under the tracks; the
/// scan may stand at most `slack` above a declared one.
fn height(
    fp: &Footprint,
    surface: &HeightField,
    level: Level,
    slack: f64,
    w: f64,
) -> Result<f64, NoLevel> {
    let mut highest: Option<([f64; 2], f64)> = None;
    let mut uncovered: Option<([f64; 2], usize)> = None;
    for p in grid_points(fp, w) {
        match surface.at(p) {
            Some(b) if highest.is_none_or(|(_, h)| b > h) => highest = Some((p, b)),
            Some(_) => {}
            None => match &mut uncovered {
                Some((_, more)) => *more += 1,
                None => uncovered = Some((p, 0)),
            },
        }
    }
    if let Some((at, more)) = uncovered {
        return Err(NoLevel::Uncovered(at, more));
    }
    let Some((at, b)) = highest else {
        return Err(NoLevel::Uncovered([0.0; 2], 0));
    };
    match level {
        Level::At(z, _) if b > z.0 + slack => Err(NoLevel::Above {
            at,
            surface: b,
            level: z.0,
            slack,
        }),
        Level::At(z, _) => Ok(z.0),
        _ => Ok(b),
    }
}

/// The top must stand a regular layer's lowest bead above the level
/// wherever the tracks run.
fn top_clear(
    fp: &Footprint,
    ex: &TopExtrusion,
    z: f64,
    lowest: f64,
    w: f64,
    slicing: &VariableSlicing,
) -> Result<(), Diagnostics> {
    let mut top = Surface::over(ex, |a| fp.written_extent(a), Base::Plate);
    let mut worst: Option<([f64; 2], f64)> = None;
    for p in grid_points(fp, w) {
        let h = top.at(p).map_err(|b| b.report(ex, 0))?;
        if worst.is_none_or(|(_, t)| h < t) {
            worst = Some((p, h));
        }
    }
    match worst {
        Some((p, h)) if h - z < lowest * (1.0 - crate::slice::variable::SLACK) => {
            let span = slicing.level.span().unwrap_or(slicing.span);
            let turned = ex.turned.as_ref();
            Err(message::scan::top_near_level(p, h, z, lowest, span, turned).into())
        }
        _ => Ok(()),
    }
}

/// What the pieces of a line are cut from.
struct Line<'a> {
    fp: &'a Footprint,
    scan: Axis,
    surface: &'a HeightField,
    z: f64,
    bead: &'a Bead,
    spec: SegmentSpec,
    /// `follow = surface`: the passes laid along the scan's normal.
    follow: Option<Follow<'a>>,
}

/// A place where no levelling pass can be laid along the scan's normal:
/// the first pass's surface slopes `alpha` rad along the tracks there, so
/// the thinnest pass the bead lays along it, `lo / cos α` mm thick
/// vertically, is more than its tallest `hi`.
struct Steep {
    at: [f64; 2],
    surface: f64,
    alpha: f64,
    lo: f64,
    hi: f64,
}

impl Steep {
    fn report(&self, bead: &Bead, slicing: &VariableSlicing, ex: &TopExtrusion) -> Diagnostics {
        let follow = slicing.follow.unwrap_or(slicing.span);
        message::scan::level_follow_too_steep(
            message::scan::SteepPass {
                at: self.at,
                surface: self.surface,
                alpha: self.alpha,
                lo: self.lo,
                hi: self.hi,
                turnable: true,
            },
            [follow, bead.span],
            ex.turned.as_ref(),
        )
        .into()
    }
}

impl Line<'_> {
    /// The gap at `t` along the line at `c`.
    fn gap(&self, t: f64, c: f64) -> Option<f64> {
        let b = self.surface.at(Footprint::point(self.scan, t, c))?;
        Some(self.z - b)
    }

    /// The heights a track filling a strip `pitch` wide lays.
    fn heights(&self, pitch: f64) -> Result<[f64; 2], Diagnostics> {
        let map =
            BeadMap::new(self.bead, Some(Length(pitch))).map_err(|e| internal(e.to_string()))?;
        let r = map.heights();
        Ok([r.low().0, r.high().0])
    }

    /// The heights a pass at `t` along the line at `c` may lay, measured
    /// vertically, for a track whose strip lays `range`: followed, a pass
    /// along the normal of a surface sloping `α` along the track lays
    /// `h·cos α` by the bead map at its pitch (module `follow`), so it is at
    /// least `lo / cos α` thick, the first pass's `α` (the scan's, the
    /// steepest) for them all.
    fn range_at(&self, t: f64, c: f64, [lo, hi]: [f64; 2]) -> [f64; 2] {
        match self.follow {
            Some(f) => {
                let tilt = f.at(Footprint::point(self.scan, t, c), 1.0, self.scan.unit());
                [lo / tilt.along_track, hi]
            }
            None => [lo, hi],
        }
    }

    /// The first place of the lines where the wear needs a pass but none
    /// can be laid along the scan's normal (see [`Steep`]).
    fn unlayable(&self, lines: &Layout) -> Result<Option<Steep>, Diagnostics> {
        if self.follow.is_none() {
            return Ok(None);
        }
        let step = self.bead.width.0 / 8.0;
        let intervals = self.fp.intervals(self.scan, &lines.centres);
        for ((&c, &pitch), intervals) in lines.centres.iter().zip(&lines.pitches).zip(intervals) {
            let range = self.heights(pitch)?;
            for t in intervals.into_iter().flat_map(|[a, b]| spaced(a, b, step)) {
                let Some(g) = self.gap(t, c) else { continue };
                let [lo, hi] = self.range_at(t, c, range);
                if lo > hi * (1.0 + SLACK) && g >= lo / 2.0 {
                    let at = Footprint::point(self.scan, t, c);
                    return Ok(Some(Steep {
                        at,
                        surface: self.z - g,
                        alpha: (range[0] / lo).clamp(-1.0, 1.0).acos(),
                        lo: range[0],
                        hi,
                    }));
                }
            }
        }
        Ok(None)
    }

    /// Every line's stretches of one pass count, as tracks; and those whose
    /// tolerance needs segments too short.
    fn pieces(&self, lines: &Layout) -> Result<(Vec<Piece>, Vec<Failure>), Diagnostics> {
        let step = self.bead.width.0 / 8.0;
        let mut pieces = Vec::new();
        let mut failures = Vec::new();
        let intervals = self.fp.intervals(self.scan, &lines.centres);
        for (line, ((&c, &pitch), intervals)) in lines
            .centres
            .iter()
            .zip(&lines.pitches)
            .zip(intervals)
            .enumerate()
        {
            let range = self.heights(pitch)?;
            for [a, b] in intervals {
                for (n, [t0, t1]) in self.runs(a, b, c, step, range) {
                    let h = |t: f64| {
                        let [lo, hi] = self.range_at(t, c, range);
                        self.gap(t, c)
                            .map(|g| g.clamp(n as f64 * lo, n as f64 * hi))
                    };
                    let samples: Vec<(f64, f64)> = spaced(t0, t1, step)
                        .into_iter()
                        .filter_map(|t| h(t).map(|h| (t, h)))
                        .collect();
                    match segmented(c, pitch, &samples, self.spec, h)
                        .map_err(|e| internal(e.to_string()))?
                    {
                        Some(Ok(mut track)) => {
                            mean_heights(&mut track);
                            pieces.push(Piece { line, n, track })
                        }
                        Some(Err(f)) => failures.push(f),
                        None => {}
                    }
                }
            }
        }
        Ok((pieces, failures))
    }

    /// The stretches of `[a, b]` on the line at `c` that take the same
    /// number of passes (at least one), each at least a bead long; where
    /// the count changes between two samples, the place is found by
    /// halving (to a millionth of the step) and both stretches end there,
    /// so a stretch holds no point more than that from its own count.
    fn runs(&self, a: f64, b: f64, c: f64, step: f64, range: [f64; 2]) -> Vec<(u32, [f64; 2])> {
        let count = |t: f64| {
            self.gap(t, c)
                .map_or(0, |g| passes(g, self.range_at(t, c, range)).0)
        };
        let ts = spaced(a, b, step);
        let counts: Vec<u32> = ts.iter().map(|&t| count(t)).collect();
        let mut out = Vec::new();
        let (mut start, mut from) = (0, a);
        for i in 1..=ts.len() {
            if i < ts.len() && counts[i] == counts[start] {
                continue;
            }
            let (to, next) = if i == ts.len() {
                (b, b)
            } else {
                let (mut lo, mut hi) = (ts[i - 1], ts[i]);
                for _ in 0..20 {
                    let mid = 0.5 * (lo + hi);
                    if count(mid) == counts[start] {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                // Both stretches meet at the bracket's middle: one point,
                // so the plan joins the two pieces without a gap.
                let mid = 0.5 * (lo + hi);
                (mid, mid)
            };
            if counts[start] > 0 && to - from >= self.bead.width.0 {
                out.push((counts[start], [from, to]));
            }
            (start, from) = (i, next);
        }
        out
    }
}

/// Each segment's height as the mean of the heights planned along it (its
/// moves' ends' mean, by length): the speed that lays it raises each pass
/// by what the pass plans there on average, which is what `lmd::deposit`
/// holds a stretch of one speed to. The best height for the finished
/// surface (the segmentation's) is not: one pass carries a gap's whole
/// slope, where a variable layer carries a share of it.
pub(in crate::slice) fn mean_heights(track: &mut Track) {
    let mut sums = vec![(0.0f64, 0.0f64); track.heights.len()];
    for (j, &q) in track.seg.iter().enumerate() {
        let len = track.t[j + 1] - track.t[j];
        sums[q].0 += len * 0.5 * (track.h[j] + track.h[j + 1]);
        sums[q].1 += len;
    }
    for (height, (area, len)) in track.heights.iter_mut().zip(sums) {
        if len > 0.0 {
            *height = area / len;
        }
    }
}

/// The levelling passes as layers: pass `k` lays every piece of more than
/// `k` passes, line after line, the lines alternating direction; the nozzle
/// along the scan's normal up to `tilt` rad when given (`follow = surface`;
/// planned turned, with the part's vertical its whole tilt is held from).
fn passes_laid(
    model: &Model,
    bead: &Bead,
    pieces: &[Piece],
    lines: &Layout,
    on: &Line<'_>,
    tilt: Option<(f64, Option<[f64; 3]>)>,
) -> Result<Vec<Layer>, Diagnostics> {
    let count = pieces.iter().map(|p| p.n).max().unwrap_or(0);
    let process = Process::of(model, bead, Base::Scan(on.surface))
        .following(tilt.map(|t| t.0), tilt.and_then(|t| t.1));
    let maps = lines
        .pitches
        .iter()
        .map(|&p| BeadMap::new(bead, Some(Length(p))))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| internal(e.to_string()))?;
    let layers = (0..count)
        .map(|k| {
            let power = model.process.power.at(k as usize).watts() as f32;
            let mut paths = Vec::new();
            let mut at = 0;
            while at < pieces.len() {
                let line = pieces[at].line;
                let end = at + pieces[at..].iter().take_while(|p| p.line == line).count();
                let reverse = (k as usize + line) % 2 == 1;
                let mut here: Vec<&Piece> = pieces[at..end].iter().filter(|p| p.n > k).collect();
                if reverse {
                    here.reverse();
                }
                paths.extend(here.into_iter().map(|p| Path {
                    kind: PathKind::Infill,
                    points: emit::track(
                        &p.track,
                        &maps[line],
                        &process,
                        on.scan,
                        k,
                        p.n as f64,
                        power,
                        reverse,
                    ),
                }));
                at = end;
            }
            Layer {
                index: k as usize,
                station: 0.0,
                frame: Frame::PART,
                paths,
                label: String::new(),
                on_plate: false,
            }
        })
        .collect();
    Ok(layers)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gap_takes_the_fewest_passes_and_none_below_half_a_bead() {
        let r = [0.6, 1.2];
        assert_eq!(passes(0.29, r), (0, 0.0));
        // Between half the lowest bead and the lowest: one pass of the lowest.
        assert_eq!(passes(0.4, r), (1, 0.6));
        assert_eq!(passes(1.0, r), (1, 1.0));
        assert_eq!(passes(1.2, r), (1, 1.2));
        assert_eq!(passes(1.5, r), (2, 1.5));
        assert_eq!(passes(3.7, r), (4, 3.7));
        // A bead whose range is under 2 to 1 cannot lay 1.3 in one or two.
        let narrow = [0.7, 1.2];
        assert_eq!(passes(1.3, narrow), (2, 1.4));
        assert_eq!(passes(f64::NAN, r), (0, 0.0));
        assert_eq!(passes(-1.0, r), (0, 0.0));
    }
}

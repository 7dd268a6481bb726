//! How many layers a variable top is built in (seed 003 eq. 2, through
//! [`crate::slice::variable::layers`]), and, when no count works, the error
//! that says why with the numbers a fix needs — in the voice of the bend's
//! (`lmd::bend-too-tight`): what the top needs, what the bead lays, and what
//! would work, in the file's own terms (the `to` or `from` of `edges(…)`,
//! the `height` or a slope of `plane(…)`). Every value the help prints is
//! read back from its printed form and run through the count's own steps
//! before it is named; a declared count's help names only counts whose
//! tracks the slicer can lay.

use super::count_input;
use super::footprint::{spaced, Footprint, Sampled};
use super::surface::{Form, Surface};
use crate::diag::message::{
    self,
    top::{CountBead, CountOutside, Decimal, TopFix},
};
use crate::diag::Diagnostic;
use crate::sema::model::{Axis, Bead, Top, TopExtrusion, VariableSlicing};
use crate::slice::variable::layers::{
    choose_layers, layer_range, LayerCount, LayerError, LayerRange, NoLayerCount, OutOfRange,
    MAX_LAYERS,
};
use crate::slice::variable::speed::HeightMap;
use crate::slice::variable::HeightRange;
use crate::units::{Length, Speed};
use std::num::NonZeroU32;

/// The heights the top needs where tracks run, and where its ends are.
#[derive(Clone, Copy, Debug)]
pub struct TopRange {
    /// `H_min .. H_max`.
    pub heights: HeightRange,
    /// Where the top is lowest, mm.
    pub low_at: [f64; 2],
    /// Where it is highest, mm.
    pub high_at: [f64; 2],
}

impl TopRange {
    /// The range of a sampling (whose heights are positive and finite).
    pub fn of(s: &Sampled) -> Option<Self> {
        let heights = HeightRange::new("top", Length(s.low.0), Length(s.high.0)).ok()?;
        Some(TopRange {
            heights,
            low_at: s.low.1,
            high_at: s.high.1,
        })
    }

    /// This range grown to hold `other` as well.
    pub fn union(self, other: TopRange) -> TopRange {
        let low = if other.heights.low().0 < self.heights.low().0 {
            (other.heights.low(), other.low_at)
        } else {
            (self.heights.low(), self.low_at)
        };
        let high = if other.heights.high().0 > self.heights.high().0 {
            (other.heights.high(), other.high_at)
        } else {
            (self.heights.high(), self.high_at)
        };
        TopRange {
            heights: HeightRange::new("top", low.0, high.0).unwrap_or(self.heights),
            low_at: low.1,
            high_at: high.1,
        }
    }

    /// Whether `other` lies within this range.
    pub fn holds(&self, other: &TopRange) -> bool {
        other.heights.low().0 >= self.heights.low().0
            && other.heights.high().0 <= self.heights.high().0
    }
}

/// What the count's errors check the fixes they name against.
pub struct Probe<'a> {
    /// The footprint.
    pub fp: &'a Footprint,
    /// The scan axis the top was sampled for.
    pub scan: Axis,
    /// The sampling pitch, mm.
    pub pitch: f64,
    /// Whether the tracks of a layer count can lay their layers (the
    /// layout, the tracks and their speeds, as the slicer lays them).
    pub builds: &'a mut dyn FnMut(NonZeroU32) -> bool,
    /// Whether `ex` with another top plans (its tracks laid as the slicer
    /// lays them); `None` while trying one, so that no help is looked for
    /// within a help.
    pub plans: Option<&'a dyn Fn(&Top) -> bool>,
}

/// The layer count: the fewest that lay every point of `top` within the
/// bead's heights, or the declared one if it does; else the error.
pub fn layers(
    top: &TopRange,
    bead: &Bead,
    map: &impl HeightMap,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    probe: Probe<'_>,
) -> Result<NonZeroU32, Diagnostic> {
    let beads = map.heights();
    let count = match slicing.layers {
        Some((n, _)) => LayerCount::Exactly(n),
        None => LayerCount::Auto,
    };
    choose_layers(top.heights, beads, count).map_err(|e| match e {
        LayerError::NoCount(e) => no_count(&e, top, bead, map, ex, slicing, &probe),
        LayerError::OutOfRange(e) => out_of_range(&e, bead, slicing, probe.builds),
        LayerError::TooMany { needed } => {
            message::top::too_many_layers(top.heights.high(), needed, beads.high(), ex.top_span)
        }
    })
}

/// No whole number of layers lays every point within the bead's heights:
/// the error with the fixes that work, each checked by the count's own test.
fn no_count(
    e: &NoLayerCount,
    top: &TopRange,
    bead: &Bead,
    map: &impl HeightMap,
    ex: &TopExtrusion,
    slicing: &VariableSlicing,
    probe: &Probe<'_>,
) -> Diagnostic {
    let beads = map.heights();
    let fixes: Vec<TopFix> = match &ex.top {
        Top::Edges { .. } => [Param::To, Param::From]
            .into_iter()
            .filter_map(|p| sugar_fix(p, ex, bead, slicing, probe, beads))
            .collect(),
        Top::Plane { slope, .. } => {
            let slopes = (0..2).filter(|&i| slope[i] != 0.0).map(Param::Slope);
            std::iter::once(Param::Height)
                .chain(slopes)
                .filter_map(|p| sugar_fix(p, ex, bead, slicing, probe, beads))
                .collect()
        }
        Top::Expr(_) | Top::Mesh(_) | Top::Solid(_) => expr_fixes(e, slicing),
    };
    // A flat top on a scan moves as one: its fixes are the flat tops a
    // count lays, not a reshaped top.
    let fixes = match flat_on_scan(ex, probe) {
        Some(t) => flat_fix(t, e, ex, bead, slicing, probe)
            .into_iter()
            .collect(),
        None => fixes,
    };
    let fit = |b: HeightRange| fits(e.top, b, slicing).is_some();
    // Millimetres to a tenth of a micrometre below 1 mm, as lengths print.
    let least = |h: f64| if h < 1.0 { 4 } else { 3 };
    // A bead reaching lower, or higher, printed within what fits.
    let low = e.bead_low_at_most().0;
    let low = candidates(low, [0.0, low], least(low))
        .find(|h| HeightRange::new("bead", Length(h.value), beads.high()).is_ok_and(fit));
    let high = e.bead_high_at_least().and_then(|h| {
        candidates(h.0, [h.0, f64::INFINITY], least(h.0))
            .find(|d| HeightRange::new("bead", beads.low(), Length(d.value)).is_ok_and(fit))
    });
    let speed = |h: Option<Decimal>, faster| {
        h.and_then(|h| bead_speed(Length(h.value), faster, ex, bead, slicing, probe, map))
    };
    let cb = CountBead {
        name: &bead.name,
        heights: bead.height_span,
        speeds: bead.speed_span,
        low,
        high,
        speed_for_low: speed(low, true),
        speed_for_high: speed(high, false),
    };
    let declared = slicing.layers.map(|l| l.0.get());
    message::top::no_count(
        e,
        [top.low_at, top.high_at],
        &fixes,
        &cb,
        declared,
        ex.top_span,
        ex.turned.as_ref(),
    )
}

/// The layer count `layer_range` gives for `top` over `beads` within a
/// declared count, if any: the fewest, or the declared one.
fn fits(top: HeightRange, beads: HeightRange, slicing: &VariableSlicing) -> Option<u32> {
    counted(layer_range(top, beads).ok()?, slicing)
}

/// The count a range of counts gives: the declared one if it holds it, else
/// the fewest (what `layers = auto` takes; the help then names the count to
/// declare).
fn counted(range: LayerRange, slicing: &VariableSlicing) -> Option<u32> {
    match slicing.layers {
        Some((n, _)) if range.contains(n) => Some(n.get()),
        _ => Some(range.fewest().get()),
    }
}

/// The speed (mm/s, a tenth) that lets the bead lay `h` as the tracks stack
/// it: faster than its range (`faster`) for a lower height, else slower;
/// checked by running the count with the bead's speeds extended to it.
fn bead_speed(
    h: Length,
    faster: bool,
    ex: &TopExtrusion,
    bead: &Bead,
    slicing: &VariableSlicing,
    probe: &Probe<'_>,
    map: &impl HeightMap,
) -> Option<f64> {
    let v = map.speed_within(h).0;
    if !(v.is_finite() && v > 0.0) {
        return None;
    }
    // Rounded away from the bead's range, then a tenth further each try.
    let first = if faster {
        (v * 10.0).ceil()
    } else {
        (v * 10.0).floor()
    };
    (0..20).find_map(|k| {
        let tenths = if faster {
            first + k as f64
        } else {
            first - k as f64
        };
        let v = tenths / 10.0;
        let mut b = bead.clone();
        b.speed[if faster { 1 } else { 0 }] = Speed(v);
        (v > 0.0
            && b.speed[0].0 <= b.speed[1].0
            && counts(ex, &ex.top, &b, slicing, probe).is_some())
        .then_some(v)
    })
}

/// Runs the count's steps (scan axis, sampling, the heights the bead stacks)
/// on `top` and `bead`: the count it gives, if one fits.
fn counts(
    ex: &TopExtrusion,
    top: &Top,
    bead: &Bead,
    slicing: &VariableSlicing,
    probe: &Probe<'_>,
) -> Option<u32> {
    let mut tried = ex.clone();
    tried.top = top.clone();
    let mut surface = Surface::new(&tried, |axis| probe.fp.written_extent(axis));
    let input = count_input(probe.fp, &mut surface, probe.pitch, &tried, bead, slicing).ok()?;
    counted(input.counts()?, slicing)
}

/// A number of a top written as `edges(…)` or `plane(…)` that a fix
/// changes, the others kept.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Param {
    /// `edges(…)`'s `from`.
    From,
    /// `edges(…)`'s `to`.
    To,
    /// `plane(…)`'s `height`.
    Height,
    /// `plane(…)`'s `slope_x` (0) or `slope_y` (1).
    Slope(usize),
}

impl Param {
    /// Its value in `top`, if `top` has it.
    fn get(self, top: &Top) -> Option<f64> {
        match (top, self) {
            (Top::Edges { from, .. }, Param::From) => Some(from.0),
            (Top::Edges { to, .. }, Param::To) => Some(to.0),
            (Top::Plane { height, .. }, Param::Height) => Some(height.0),
            (Top::Plane { slope, .. }, Param::Slope(i)) => Some(slope[i]),
            _ => None,
        }
    }

    /// `top` with it set to `v`.
    fn set(self, top: &Top, v: f64) -> Option<Top> {
        let mut t = top.clone();
        match (&mut t, self) {
            (Top::Edges { from, .. }, Param::From) => *from = Length(v),
            (Top::Edges { to, .. }, Param::To) => *to = Length(v),
            (Top::Plane { height, .. }, Param::Height) => *height = Length(v),
            (Top::Plane { slope, .. }, Param::Slope(i)) => slope[i] = v,
            _ => return None,
        }
        Some(t)
    }

    /// Printed in mm, a slope in % (×100).
    fn scale(self) -> f64 {
        match self {
            Param::Slope(_) => 100.0,
            _ => 1.0,
        }
    }

    /// The least value it may take: `edges(…)`'s heights are positive.
    fn least(self) -> f64 {
        match self {
            Param::From | Param::To => f64::MIN_POSITIVE,
            _ => f64::NEG_INFINITY,
        }
    }

    /// The fix it makes with the value printed.
    fn fix(self, value: Decimal, layers: u32) -> TopFix {
        match self {
            Param::From => TopFix::Edge {
                to: false,
                value,
                layers,
            },
            Param::To => TopFix::Edge {
                to: true,
                value,
                layers,
            },
            Param::Height => TopFix::Height { value, layers },
            Param::Slope(axis) => TopFix::Slope {
                axis,
                percent: value,
                layers,
            },
        }
    }
}

/// The value of `param` nearest the file's that lets a count lay the top,
/// printed and checked. The top is a plane, so at each point where a track
/// can run its height is `a + p·b` for the parameter `p`, and a count `N`
/// needs `N·h_min ≤ a + p·b ≤ N·h_max` there: linear in `p`, and binding at
/// the corners of the hull of those points. Each `N` gives an interval of
/// `p`; the nearest point of them all is rounded into its interval, and the
/// count's own steps are run on the top it gives.
fn sugar_fix(
    param: Param,
    ex: &TopExtrusion,
    bead: &Bead,
    slicing: &VariableSlicing,
    probe: &Probe<'_>,
    beads: HeightRange,
) -> Option<TopFix> {
    let p0 = param.get(&ex.top)?;
    let plane = |v: f64| {
        let mut tried = ex.clone();
        tried.top = param.set(&ex.top, v)?;
        match Surface::new(&tried, |axis| probe.fp.written_extent(axis)).form {
            Form::Plane { h0, slope } if ex.base.is_none() => Some((h0, slope)),
            _ => None,
        }
    };
    let ((h0, s0), (h1, s1)) = (plane(0.0)?, plane(1.0)?);
    let corners: Vec<(f64, f64)> = hull(track_ends(probe))
        .into_iter()
        .map(|[x, y]| {
            let a = h0 + s0[0] * x + s0[1] * y;
            (a, h1 + s1[0] * x + s1[1] * y - a)
        })
        .collect();
    let (lo, hi) = (beads.low().0, beads.high().0);
    // The value nearest the file's over the counts `ns`.
    let nearest = |ns: std::ops::RangeInclusive<u32>| {
        let mut best: Option<(f64, f64, [f64; 2])> = None;
        for n in ns {
            let (lo, hi) = (n as f64 * lo, n as f64 * hi);
            let Some([l, r]) = interval(&corners, lo, hi, param.least()) else {
                continue;
            };
            let p = p0.clamp(l, r);
            if best.is_none_or(|b| (p - p0).abs() < b.0) {
                best = Some(((p - p0).abs(), p, [l, r]));
            }
        }
        best
    };
    // The declared count if a value fits it, else any count.
    let declared = slicing.layers.map(|l| l.0.get());
    let best = declared
        .and_then(|n| nearest(n..=n))
        .or_else(|| nearest(1..=MAX_LAYERS));
    let (_, p, [l, r]) = best?;
    let scale = param.scale();
    candidates(p * scale, [l * scale, r * scale], 1).find_map(|d| {
        let top = param.set(&ex.top, d.value / scale)?;
        counts(ex, &top, bead, slicing, probe).map(|n| param.fix(d, n))
    })
}

/// The height of `ex`'s top when it is built on a scan and is flat: the
/// same at every track end and at the footprint's middle.
fn flat_on_scan(ex: &TopExtrusion, probe: &Probe<'_>) -> Option<f64> {
    ex.base.as_ref()?;
    let mut form = Form::of(&ex.top, |axis| probe.fp.written_extent(axis));
    let mut points = track_ends(probe);
    let n = points.len() as f64;
    let mid = points
        .iter()
        .fold([0.0; 2], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    points.push(mid);
    let mut heights = points.iter().map(|&p| form.at(p).ok());
    let first = heights.next()??;
    heights.all(|h| h == Some(first)).then_some(first)
}

/// The flat tops nearest `top` (mm) that a count lays over the scan, as
/// the count's own steps find them: with the gaps `g_lo .. g_hi` under
/// `top` and `N` layers of the bead's `h_lo .. h_hi`, `T` must lie within
/// `B_hi + N·h_lo .. B_lo + N·h_hi` (`B` the scan, `top − g`). That window
/// is the widest a count allows; the tracks' own strips may narrow it, so
/// the window is sampled and the run that plans nearest `top` (as the
/// slicer plans it, up to its tracks) is found and its ends halved. The
/// declared count only, if any.
fn flat_fix(
    top: f64,
    e: &NoLayerCount,
    ex: &TopExtrusion,
    bead: &Bead,
    slicing: &VariableSlicing,
    probe: &Probe<'_>,
) -> Option<TopFix> {
    let (b_lo, b_hi) = (top - e.top.high().0, top - e.top.low().0);
    let (h_lo, h_hi) = (e.bead.low().0, e.bead.high().0);
    let flat = |t: f64| Top::Plane {
        at: [Length(0.0); 2],
        height: Length(t),
        slope: [0.0; 2],
    };
    let plans = probe.plans?;
    // The count's steps first (cheap), then the plan's up to its tracks.
    let builds = |t: f64| {
        let top = flat(t);
        counts(ex, &top, bead, slicing, probe).filter(|_| plans(&top))
    };
    let windows = |n: u32| {
        let nf = n as f64;
        let (lo, hi) = (b_hi + nf * h_lo, b_lo + nf * h_hi);
        (lo <= hi && lo > b_hi).then_some((n, [lo, hi]))
    };
    let distance = |[lo, hi]: [f64; 2]| (lo - top).max(top - hi).max(0.0);
    let mut tried: Vec<(u32, [f64; 2])> = match slicing.layers {
        Some((n, _)) => windows(n.get()).into_iter().collect(),
        None => (1..=MAX_LAYERS.min(10_000)).filter_map(windows).collect(),
    };
    tried.sort_by(|a, b| distance(a.1).total_cmp(&distance(b.1)));
    // The few windows nearest the top: each costs the count's steps.
    tried.into_iter().take(4).find_map(|(_, [lo, hi])| {
        const SAMPLES: usize = 8;
        let at = |k: usize| lo + (hi - lo) * k as f64 / SAMPLES as f64;
        let good: Vec<usize> = (0..=SAMPLES).filter(|&k| builds(at(k)).is_some()).collect();
        let near = |k: &usize| (at(*k) - top).abs();
        let k = *good.iter().min_by(|a, b| near(a).total_cmp(&near(b)))?;
        // The run of samples that build around `k`, its ends halved out.
        let (mut a, mut b) = (k, k);
        while a > 0 && good.contains(&(a - 1)) {
            a -= 1;
        }
        while b < SAMPLES && good.contains(&(b + 1)) {
            b += 1;
        }
        let edge = |inside: f64, outside: f64| {
            let (mut i, mut o) = (inside, outside);
            for _ in 0..8 {
                let m = 0.5 * (i + o);
                if builds(m).is_some() {
                    i = m;
                } else {
                    o = m;
                }
            }
            i
        };
        let lo = if a > 0 { edge(at(a), at(a - 1)) } else { at(a) };
        let hi = if b < SAMPLES {
            edge(at(b), at(b + 1))
        } else {
            at(b)
        };
        // Printed to a hundredth, inward, and each end checked.
        let (lo, hi) = ((lo * 100.0).ceil() / 100.0, (hi * 100.0).floor() / 100.0);
        let n_lo = builds(lo)?;
        let n_hi = builds(hi)?;
        (lo <= hi && n_lo == n_hi).then_some(TopFix::Flat {
            from: Decimal {
                value: lo,
                decimals: 2,
            },
            to: Decimal {
                value: hi,
                decimals: 2,
            },
            layers: n_lo,
        })
    })
}

/// The fixes of a top written as an expression: its heights where the
/// tracks run, the highest lowered or the lowest raised, checked by the
/// count's own test.
fn expr_fixes(e: &NoLayerCount, slicing: &VariableSlicing) -> Vec<TopFix> {
    let (lo, hi) = (e.top.low().0, e.top.high().0);
    let mut out = Vec::new();
    if let Some(h) = e.top_high_at_most() {
        let ok = candidates(h.0, [lo, h.0], 3).find_map(|d| {
            let top = HeightRange::new("top", Length(lo), Length(d.value)).ok()?;
            fits(top, e.bead, slicing).map(|n| (d, n))
        });
        if let Some((at_most, layers)) = ok {
            out.push(TopFix::High { at_most, layers });
        }
    }
    if let Some(h) = e.top_low_at_least() {
        let ok = candidates(h.0, [h.0, hi], 3).find_map(|d| {
            let top = HeightRange::new("top", Length(d.value), Length(hi)).ok()?;
            fits(top, e.bead, slicing).map(|n| (d, n))
        });
        if let Some((at_least, layers)) = ok {
            out.push(TopFix::Low { at_least, layers });
        }
    }
    out
}

/// `v` rounded to `least`, then to each of three more decimals, each time
/// to the nearest value within `[l, r]` at that many (none when the
/// interval holds none).
fn candidates(v: f64, [l, r]: [f64; 2], least: usize) -> impl Iterator<Item = Decimal> {
    (least..least + 4).filter_map(move |decimals| {
        let step = 10f64.powi(-(decimals as i32));
        let mut q = (v / step).round() * step;
        if q < l {
            q = (l / step).ceil() * step;
        }
        if q > r {
            q = (r / step).floor() * step;
        }
        // The value read back from its printed form is the one checked.
        let q: f64 = format!("{q:.decimals$}").parse().ok()?;
        (l <= q && q <= r && q.is_finite()).then_some(Decimal { value: q, decimals })
    })
}

/// The values of `p` for which `lo ≤ a + p·b ≤ hi` at every corner `(a,
/// b)`, and `p ≥ least`.
fn interval(corners: &[(f64, f64)], lo: f64, hi: f64, least: f64) -> Option<[f64; 2]> {
    let (mut l, mut r) = (least, f64::INFINITY);
    for &(a, b) in corners {
        if b.abs() <= 1e-12 * a.abs().max(1.0) {
            if a < lo || a > hi {
                return None;
            }
            continue;
        }
        let (p, q) = ((lo - a) / b, (hi - a) / b);
        let (p, q) = if b > 0.0 { (p, q) } else { (q, p) };
        (l, r) = (l.max(p), r.min(q));
    }
    (l <= r).then_some([l, r])
}

/// The ends of every stretch a track can run along, on the lines the top
/// is sampled on (a plane's heights there are extreme at them).
fn track_ends(probe: &Probe<'_>) -> Vec<[f64; 2]> {
    let Some([lo, hi]) = probe.fp.centres(probe.scan) else {
        return Vec::new();
    };
    let at = spaced(lo, hi, probe.pitch);
    let mut out = Vec::new();
    for (c, intervals) in at.iter().zip(probe.fp.intervals(probe.scan, &at)) {
        for [a, b] in intervals {
            out.push(Footprint::point(probe.scan, a, *c));
            out.push(Footprint::point(probe.scan, b, *c));
        }
    }
    out
}

/// The corners of the convex hull of `points` (Andrew's monotone chain);
/// fewer than three points come back as they are.
pub(crate) fn hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for pass in [
        &points[..],
        &points.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let base = out.len();
        for &p in pass {
            while out.len() >= base + 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0 {
                out.pop();
            }
            out.push(p);
        }
        // Each chain's last point starts the other.
        out.pop();
    }
    out
}

/// Most layer counts a declared count's help tries (those nearest it).
const MAX_TRIED: usize = 64;

/// A declared count outside the counts that work: the help names those of
/// them whose tracks can lay their layers.
fn out_of_range(
    e: &OutOfRange,
    bead: &Bead,
    slicing: &VariableSlicing,
    builds: &mut dyn FnMut(NonZeroU32) -> bool,
) -> Diagnostic {
    let (fewest, most) = (e.range.fewest().get(), e.range.most().get());
    let n = e.layers.get();
    let mut tried: Vec<u32> = (fewest..=most).collect();
    tried.sort_by_key(|c| c.abs_diff(n));
    tried.truncate(MAX_TRIED);
    tried.sort_unstable();
    let mut runs: Vec<[u32; 2]> = Vec::new();
    for c in tried {
        if !NonZeroU32::new(c).is_some_and(&mut *builds) {
            continue;
        }
        match runs.last_mut() {
            Some(run) if run[1] + 1 == c => run[1] = c,
            _ => runs.push([c, c]),
        }
    }
    // `layers = auto` starts at the fewest and keeps it when it builds.
    let auto = runs.first().is_some_and(|r| r[0] == fewest);
    message::top::count_outside(&CountOutside {
        e,
        bead: &bead.name,
        runs: &runs,
        auto: auto.then_some(fewest),
        layers: slicing.layers.map(|l| l.1),
        heights: bead.height_span,
    })
}

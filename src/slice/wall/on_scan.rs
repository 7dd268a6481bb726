//! A wall along an open path built on a scanned part (`wall { on =
//! scan(…)  top = … }` with `slicing variable`, docs/repair.md, *A wall on
//! a scan*): a rib or a lip added along a worn edge.
//!
//! Each bead's centre line is sampled along its length at most a scan
//! cell apart, at every corner of the path too. Under each sample lies the
//! scanned surface `B`, and the gap to fill is `G = top − B`. The wall is
//! built as a variable solid is (seed 003, [`crate::slice::variable`]): in
//! `N` layers that each lay `G/N`, `N` the fewest (or the declared count)
//! that keeps every `G/N` within the heights the bead lays at the beads'
//! pitch. Each bead is cut into the fewest constant-speed segments within
//! the slicing's tolerance, and layer `i`'s points sit at `B + i·G/N`, at
//! the speed that lays its segment's height ([`crate::slice::top`]'s
//! emitter). The beads run as a flat wall's do: `direction`, `ends`.

use super::{beads, fault_at, layer, tracks, Track as Line};
use crate::diag::message::{self, top::CountOutside, top::TopAt};
use crate::diag::Diagnostics;
use crate::geometry::scan::HeightField;
use crate::ir::{Frame, Layer, Path, PathKind};
use crate::sema::model::{Axis, Bead, Level, Model, OpenWall, VariableSlicing, WallOnScan};
pub(super) use crate::slice::top::Failure;
use crate::slice::top::{along, segments_too_short, spaced, Base, Process, Track};
use crate::slice::top::{follow_check, follow_limit, TopFault, TopForm};
use crate::slice::variable::layers::{choose_layers, LayerCount, LayerError};
use crate::slice::variable::profile::TrackProfile;
use crate::slice::variable::segments::Segment;
use crate::slice::variable::segments::{segment, SegmentSpec};
use crate::slice::variable::speed::{BeadMap, HeightMap};
use crate::slice::variable::{HeightRange, Positive};
use crate::units::Length;
use std::cell::RefCell;
use std::num::NonZeroU32;

/// How closely the path's arcs are flattened, mm: planar slicing's default.
const CHORD: f64 = 0.05;

/// Most samples of the scan over all beads, and along one: a long wall is
/// sampled more coarsely rather than without bound (a bead's segmentation
/// tries up to a thousand counts over its samples).
const MAX_SAMPLES: f64 = 1e6;
const MAX_LINE_SAMPLES: f64 = 1e5;

/// One bead's centre line sampled: the length along it, the point and the
/// gap to fill there.
#[derive(Clone, Default)]
pub(super) struct Sampled {
    pub s: Vec<f64>,
    pub xy: Vec<[f64; 2]>,
    pub gap: Vec<f64>,
    /// The scanned surface there, mm.
    pub base: Vec<f64>,
    /// The top there, mm (NaN where it has none).
    pub top: Vec<f64>,
}

/// A place where the top is not above the scan: where, and the top and
/// the scan there (mm).
type Below = ([f64; 2], [f64; 2]);

/// The first place the scan cannot be built on, and how many more.
#[derive(Default)]
struct Unbuildable {
    uncovered: Option<([f64; 2], usize)>,
    /// Where the top is not above the scan: the place, the top and the
    /// scan there.
    below: Option<(Below, usize)>,
    /// Where the top itself has no height (an expression that fails, a
    /// target with nothing over the path).
    top: Option<(TopFault, usize)>,
}

/// The top of the wall `on`, ready to evaluate along `wall`'s path (whose
/// box is the extent `edges(…)` refers to).
pub fn top_form<'m>(wall: &OpenWall, on: &'m WallOnScan) -> TopForm<'m> {
    let points = wall.path.flatten(CHORD);
    let range = |k: usize| {
        points
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], p| {
                [lo.min(p[k]), hi.max(p[k])]
            })
    };
    let [x, y] = [range(0), range(1)];
    TopForm::of(&on.top, |a| match a {
        Axis::X => x,
        Axis::Y => y,
    })
}

/// Slices a wall on a scan into layers of variable thickness (levelling
/// its scan first when `level = …`, module `level`). Returns the layers
/// and any warnings, or every diagnostic found.
pub fn slice(
    model: &Model,
    bead: &Bead,
    wall: &OpenWall,
    on: &WallOnScan,
    slicing: &VariableSlicing,
    pitch: Length,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    follow_check(model, bead, slicing)?;
    let lines = tracks(wall, bead.width.0, pitch.0, CHORD).map_err(|f| fault_at(wall, f))?;
    let map = BeadMap::new(bead, Some(pitch)).map_err(|e| internal(&e.to_string()))?;
    let surface = &on.base.surface;
    let lengths: Vec<f64> = lines.iter().map(|l| polyline_length(&l.points)).collect();
    let longest = lengths.iter().fold(0.0f64, |a, &b| a.max(b));
    let step = surface
        .cell()
        .max(lengths.iter().sum::<f64>() / MAX_SAMPLES)
        .max(longest / MAX_LINE_SAMPLES);
    let mut bad = Unbuildable::default();
    let top = RefCell::new(top_form(wall, on));
    let sampled: Vec<Sampled> = lines
        .iter()
        .map(|l| sample(&l.points, step, &top, surface, &mut bad))
        .collect();
    let levelled = slicing.level != Level::None;
    unbuildable(bad, wall, on, !levelled)?;
    let spec = SegmentSpec {
        tolerance: Positive::new("tolerance", slicing.tolerance)
            .map_err(|e| internal(&e.to_string()))?,
        min_length: Positive::new("minimum segment", slicing.min_length.unwrap_or(bead.width))
            .map_err(|e| internal(&e.to_string()))?,
    };
    let top_at = |p: [f64; 2]| top.borrow_mut().at(p).ok();
    let cx = Cx {
        model,
        bead,
        wall,
        on,
        top: &top_at,
        tilt: follow_limit(model, bead, slicing),
        slicing,
        lines: &lines,
        map,
        spec,
        pitch: pitch.0,
    };
    if levelled {
        return super::level::slice(&cx, &sampled).map(|l| (l, Diagnostics::new()));
    }
    let gap = |p: [f64; 2]| {
        let t = top_at(p)?;
        surface.at(p).map(|b| t - b).filter(|&g| g > 0.0)
    };
    let layers = regular(&cx, &sampled, (Base::Scan(surface), 0), &gap)?;
    Ok((layers, Diagnostics::new()))
}

/// What a wall on a scan's layers are planned from.
pub(super) struct Cx<'a> {
    pub model: &'a Model,
    pub bead: &'a Bead,
    pub wall: &'a OpenWall,
    pub on: &'a WallOnScan,
    /// The top at a point, mm, where it has one.
    pub top: &'a dyn Fn([f64; 2]) -> Option<f64>,
    /// `follow = surface`: the largest tilt of the nozzle from vertical,
    /// rad (the layers on the scan laid along its normal).
    pub tilt: Option<f64>,
    pub slicing: &'a VariableSlicing,
    /// Each bead's centre line, across the wall.
    pub lines: &'a [Line],
    /// The bead's heights and speeds at the beads' pitch.
    pub map: BeadMap<'a>,
    pub spec: SegmentSpec,
    /// The beads' pitch, mm.
    pub pitch: f64,
}

/// The layers that each lay the same share of every sample's gap, on
/// `base`, after `below` layers (the levelling passes: the beads' order
/// and directions go on alternating from them); `gap(p)` is the gap
/// where a segment starts between samples.
pub(super) fn regular(
    cx: &Cx<'_>,
    sampled: &[Sampled],
    (base, below): (Base<'_>, usize),
    gap: &dyn Fn([f64; 2]) -> Option<f64>,
) -> Result<Vec<Layer>, Diagnostics> {
    let (model, bead, on, slicing) = (cx.model, cx.bead, cx.on, cx.slicing);
    let range = gap_range(sampled).ok_or_else(|| internal("the wall has no point"))?;
    let level = match base {
        Base::Level(z) => Some(z),
        _ => None,
    };
    let n = count(&range, (&cx.map, cx.pitch), bead, (on, level), slicing)?;
    let planned = match segmented(sampled, cx.spec)? {
        Ok(segments) => sampled
            .iter()
            .zip(&segments)
            .map(|(line, s)| on_samples(line, cx.pitch, s, gap))
            .collect::<Vec<_>>(),
        Err(failures) => {
            return Err(too_short(&failures, sampled, bead, on, slicing, cx.spec).into());
        }
    };
    let per_layer: usize = planned.iter().map(|(t, _)| t.t.len() + 4).sum();
    crate::slice::within_points(per_layer, n.get(), slicing.span)?;
    let process = Process::of(model, bead, base).following(cx.tilt, None);
    let layers = (0..n.get())
        .map(|i| {
            let power = model.process.power.at(i as usize).watts() as f32;
            let k = i as usize;
            let mut paths = beads(cx.wall, cx.lines, below + k, |j, forward, _: &Line| {
                let (track, xy) = &planned[j];
                let lay = (i, n.get() as f64);
                along(track, xy, &cx.map, &process, None, lay, power, !forward)
            });
            above_scan(&mut paths, &on.base.surface);
            layer(k, n.get() as usize, paths, Frame::PART)
        })
        .collect();
    Ok(layers)
}

/// Each lead of `paths` raised where the scan under its far end stands
/// higher than under the bead's end: a lead runs on at the bead's height
/// above the scan there, so on a rising scan it does not run into the
/// part (on the first layer the bead's end lies on the scan).
pub(super) fn above_scan(paths: &mut [Path], surface: &HeightField) {
    for i in 0..paths.len() {
        if paths[i].kind != PathKind::Lead {
            continue;
        }
        // The bead's end is the lead's last point before a bead, its first
        // after one.
        let into = paths.get(i + 1).is_some_and(|p| p.kind == PathKind::Wall);
        let (end, far) = if into { (1, 0) } else { (0, 1) };
        let lead = &mut paths[i].points;
        let (e, f) = (lead[end].pos, lead[far].pos);
        let (Some(be), Some(bf)) = (surface.at([e[0], e[1]]), surface.at([f[0], f[1]])) else {
            continue;
        };
        let z = e[2].max(bf + (e[2] - be));
        if z > f[2] {
            lead[far].pos[2] = z;
            let (a, b) = (lead[0].pos, lead[1].pos);
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let len = d[0].hypot(d[1]).hypot(d[2]).max(1e-12);
            let tangent = d.map(|v| (v / len) as f32);
            lead.iter_mut().for_each(|p| p.tangent = tangent);
        }
    }
}

/// The length of a polyline, mm.
fn polyline_length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

/// The line through `points` sampled at most `step` apart (at every point
/// of it too), the gap from the scan `surface` up to `top` at each; where
/// the scan has no surface, the top no height, or the top is not above the
/// scan is noted in `bad`.
fn sample(
    points: &[[f64; 2]],
    step: f64,
    top: &RefCell<TopForm<'_>>,
    surface: &HeightField,
    bad: &mut Unbuildable,
) -> Sampled {
    let mut out = Sampled::default();
    let mut at = 0.0;
    let mut push = |p: [f64; 2], s: f64, out: &mut Sampled| {
        if out.s.last().is_some_and(|&last| s <= last) {
            return;
        }
        let b = surface.at(p);
        let t = match top.borrow_mut().at(p) {
            Ok(t) => Some(t),
            Err(fault) => {
                note(&mut bad.top, fault);
                None
            }
        };
        let gap = match (b, t) {
            (None, _) => {
                note(&mut bad.uncovered, p);
                f64::NAN
            }
            (_, None) => f64::NAN,
            (Some(b), Some(t)) if t - b <= 0.0 => {
                note(&mut bad.below, (p, [t, b]));
                f64::NAN
            }
            (Some(b), Some(t)) => t - b,
        };
        out.s.push(s);
        out.xy.push(p);
        out.gap.push(gap);
        out.base.push(b.unwrap_or(f64::NAN));
        out.top.push(t.unwrap_or(f64::NAN));
    };
    for w in points.windows(2) {
        let [a, b] = [w[0], w[1]];
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let ts = spaced(0.0, len, step);
        for &t in &ts[..ts.len() - 1] {
            let f = if len > 0.0 { t / len } else { 0.0 };
            let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
            push(p, at + t, &mut out);
        }
        at += len;
    }
    if let Some(&last) = points.last() {
        push(last, at, &mut out);
    }
    out
}

/// Notes `what` in `first`: the first one found kept, the rest counted.
fn note<T>(first: &mut Option<(T, usize)>, what: T) {
    match first {
        Some((_, more)) => *more += 1,
        None => *first = Some((what, 0)),
    }
}

/// The error for where the wall cannot be built on the scan, if anywhere:
/// where the top has no height, where the scan has no surface, and
/// (`below`: not levelled first) where the top is not above it.
fn unbuildable(
    bad: Unbuildable,
    wall: &OpenWall,
    on: &WallOnScan,
    below: bool,
) -> Result<(), Diagnostics> {
    let mut diags = Diagnostics::new();
    let spans = [wall.along_span, on.base.span];
    if let Some((fault, more)) = bad.top {
        let at = TopAt {
            top: on.top_span,
            shape: wall.along_span,
            what: "path",
            turned: None,
        };
        diags.extend(fault.top_fault(more, &on.top, at).unwrap_or_default());
    }
    if let Some((p, more)) = bad.uncovered {
        let surface = &on.base.surface;
        diags.push(message::scan::uncovered(
            p, more, surface, spans[0], spans[1], None,
        ));
    }
    if let Some(((p, [t, b]), more)) = bad.below.filter(|_| below) {
        let at = [on.top_span, on.base.span];
        diags.push(message::scan::top_below(p, t, b, more, at, None));
    }
    if diags.has_errors() {
        return Err(diags);
    }
    Ok(())
}

/// The gaps' range over every sample, with where each end lies.
fn gap_range(sampled: &[Sampled]) -> Option<(HeightRange, [[f64; 2]; 2])> {
    let mut low = (f64::INFINITY, [0.0; 2]);
    let mut high = (f64::NEG_INFINITY, [0.0; 2]);
    for line in sampled {
        for (&g, &p) in line.gap.iter().zip(&line.xy) {
            if g < low.0 {
                low = (g, p);
            }
            if g > high.0 {
                high = (g, p);
            }
        }
    }
    let r = HeightRange::new("gap", Length(low.0), Length(high.0)).ok()?;
    Some((r, [low.1, high.1]))
}

/// The layer count: the fewest that lay every gap within the bead's
/// heights at the pitch, or the declared one if it does; else the error.
fn count(
    (range, at): &(HeightRange, [[f64; 2]; 2]),
    (map, pitch): (&BeadMap<'_>, f64),
    bead: &Bead,
    (on, level): (&WallOnScan, Option<f64>),
    slicing: &VariableSlicing,
) -> Result<NonZeroU32, Diagnostics> {
    let beads = map.heights();
    let declared = slicing.layers.map(|l| l.0);
    let count = match declared {
        Some(n) => LayerCount::Exactly(n),
        None => LayerCount::Auto,
    };
    choose_layers(*range, beads, count).map_err(|e| {
        let d = match e {
            LayerError::NoCount(e) => {
                let flat = on.top.flat();
                let fix = flat.and_then(|t| top_fix(t, &e, declared.map(|n| n.get())));
                message::wall::no_count_on_scan(&message::wall::NoCountOnScan {
                    e: &e,
                    at: *at,
                    top: flat,
                    level,
                    fix,
                    bead: (&bead.name, bead.height_span),
                    pitch,
                    spans: [on.top_span, on.base.span],
                })
            }
            LayerError::OutOfRange(e) => {
                let runs = [[e.range.fewest().get(), e.range.most().get()]];
                message::top::count_outside(&CountOutside {
                    e: &e,
                    bead: &bead.name,
                    runs: &runs,
                    auto: Some(e.range.fewest().get()),
                    layers: slicing.layers.map(|l| l.1),
                    heights: bead.height_span,
                })
            }
            LayerError::TooMany { needed } => {
                message::top::too_many_layers(range.high(), needed, beads.high(), on.top_span)
            }
        };
        d.into()
    })
}

/// The flat top nearest `top` that some count lays (the declared count,
/// when given): `[lowest, highest]` mm and the count. With the scan `B_lo
/// .. B_hi` under the wall and `N` layers of `h_lo .. h_hi`, a top `T`
/// works when `B_hi + N·h_lo ≤ T ≤ B_lo + N·h_hi`.
fn top_fix(
    top: f64,
    e: &crate::slice::variable::layers::NoLayerCount,
    declared: Option<u32>,
) -> Option<([f64; 2], u32)> {
    let (b_lo, b_hi) = (top - e.top.high().0, top - e.top.low().0);
    let (h_lo, h_hi) = (e.bead.low().0, e.bead.high().0);
    let within = |n: u32| {
        let nf = n as f64;
        let (lo, hi) = (b_hi + nf * h_lo, b_lo + nf * h_hi);
        // Shown to a hundredth, inward, so the printed ends still work.
        let (lo, hi) = ((lo * 100.0).ceil() / 100.0, (hi * 100.0).floor() / 100.0);
        (lo <= hi && lo > b_hi).then_some(([lo, hi], n))
    };
    let counts: Box<dyn Iterator<Item = u32>> = match declared {
        Some(n) => Box::new(std::iter::once(n)),
        None => Box::new(1..=crate::slice::variable::layers::MAX_LAYERS.min(10_000)),
    };
    let distance = |[lo, hi]: [f64; 2]| (lo - top).max(top - hi).max(0.0);
    counts
        .filter_map(within)
        .min_by(|a, b| distance(a.0).total_cmp(&distance(b.0)))
}

/// Each bead's fewest constant-speed segments within `spec` over its
/// samples; or the beads that cannot be segmented.
pub(super) fn segmented(
    sampled: &[Sampled],
    spec: SegmentSpec,
) -> Result<Result<Vec<Vec<Segment>>, Vec<Failure>>, Diagnostics> {
    let mut out = Vec::with_capacity(sampled.len());
    let mut failures = Vec::new();
    for (j, line) in sampled.iter().enumerate() {
        let points = line
            .s
            .iter()
            .zip(&line.gap)
            .map(|(&s, &g)| (Length(s), Length(g)));
        let profile = TrackProfile::new(points).map_err(|e| internal(&e.to_string()))?;
        let [first, last] = [line.s[0], line.s[line.s.len() - 1]];
        match segment(&profile, spec) {
            Ok(s) => out.push(s.segments),
            Err(error) => failures.push(Failure {
                c: j as f64,
                length: last - first,
                middle: (first + last) / 2.0,
                error,
                profile,
            }),
        }
    }
    Ok(if failures.is_empty() {
        Ok(out)
    } else {
        Err(failures)
    })
}

/// The track of `line` filling a strip `pitch` wide, through every sample
/// (a path's corners are among them) and a point where each segment
/// starts, so each speed holds over its own segment: between two samples
/// the path is straight, and `gap` gives the gap there.
/// Each move belongs to the segment its middle lies in. Also the points.
pub(super) fn on_samples(
    line: &Sampled,
    pitch: f64,
    segments: &[Segment],
    gap: &dyn Fn([f64; 2]) -> Option<f64>,
) -> (Track, Vec<[f64; 2]>) {
    let (mut t, mut h, mut xy) = (Vec::new(), Vec::new(), Vec::new());
    let mut starts = segments.iter().skip(1).map(|g| g.start.0).peekable();
    for k in 0..line.s.len() {
        if k > 0 {
            let (a, b) = (line.s[k - 1], line.s[k]);
            while let Some(&c) = starts.peek() {
                if c >= b {
                    break;
                }
                starts.next();
                let f = (c - a) / (b - a);
                let [p, q] = [line.xy[k - 1], line.xy[k]];
                let at = [p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1])];
                let inside = c - a > 1e-9 * b.abs().max(1.0);
                if let Some(g) = gap(at).filter(|_| inside) {
                    t.push(c);
                    h.push(g);
                    xy.push(at);
                }
            }
        }
        t.push(line.s[k]);
        h.push(line.gap[k]);
        xy.push(line.xy[k]);
    }
    let mut q = 0;
    let seg = t
        .windows(2)
        .map(|m| {
            let mid = 0.5 * (m[0] + m[1]);
            while q + 1 < segments.len() && mid >= segments[q].end.0 {
                q += 1;
            }
            q
        })
        .collect();
    let track = Track {
        c: 0.0,
        pitch,
        t,
        h,
        seg,
        heights: segments.iter().map(|g| g.height.0).collect(),
    };
    (track, xy)
}

/// The error for beads whose tolerance needs segments too short.
pub(super) fn too_short(
    failures: &[Failure],
    sampled: &[Sampled],
    bead: &Bead,
    on: &WallOnScan,
    slicing: &VariableSlicing,
    spec: SegmentSpec,
) -> crate::diag::Diagnostic {
    // The worst bead named by the point of the scan at its middle.
    let locate = |f: &Failure| {
        let line = &sampled[f.c as usize];
        let k = line
            .s
            .partition_point(|&s| s < f.middle)
            .min(line.s.len() - 1);
        let [x, y] = line.xy[k];
        (None, Some([x, y, line.base[k]]))
    };
    let at = (sampled.len(), on.top_span);
    segments_too_short(failures, at, bead, slicing, spec.min_length, locate)
}

/// An error that is lmdc's, not the file's.
pub(super) fn internal(what: &str) -> Diagnostics {
    message::top::internal(what)
}

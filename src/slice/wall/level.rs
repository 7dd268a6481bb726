//! A wall on a scan levelled first (`level = auto | HEIGHT` in `slicing
//! variable`, docs/repair.md, *A wall on a scan*), as an extrusion's wear
//! is (`crate::slice::top`'s levelling): the gap `G = z_L − B` between
//! the level `z_L` and the scanned surface under each bead is filled
//! first, each place in the fewest passes that keep a bead's height
//! (`n = ⌈G/h_max⌉`, each laying `G/n` kept within the bead's range at
//! the beads' pitch), nothing where the gap is thinner than half the
//! lowest bead. Pass `k` lays every stretch of a bead's line that needs
//! more than `k` passes, each stretch at least a bead long, so each pass
//! lies on the one before. The regular layers then rise from the level to
//! the top as the wall's layers do, flat; the first of them lies partly on
//! the scan, so `lmd::stacking` does not look for the pass below it.
//!
//! `level = auto` is the scan's highest point under the beads; a declared
//! level may stand below it by at most half the lowest bead (where the
//! scan stands above it, nothing is laid). The top must stand at least the
//! lowest bead above the level.

use super::on_scan::{
    above_scan, internal, on_samples, regular, segmented, too_short, Cx, Sampled,
};
use super::{layer, order, with_leads};
use crate::diag::{message, Diagnostics};
use crate::ir::{Frame, Layer};
use crate::sema::model::Level;
use crate::slice::top::{
    along, direction, mean_heights, passes, stacked, Base, Follow, Process, Track,
};
use crate::slice::variable::layers::MAX_LAYERS;
use crate::slice::variable::speed::HeightMap;
use crate::slice::variable::SLACK;
use crate::slice::MAX_TOTAL_POINTS;

/// A stretch of one bead's line that takes `n` passes: its samples.
struct Piece {
    line: usize,
    n: u32,
    track: Track,
    xy: Vec<[f64; 2]>,
}

/// The levelling passes, then the regular layers from the level to the
/// top.
pub(super) fn slice(cx: &Cx<'_>, sampled: &[Sampled]) -> Result<Vec<Layer>, Diagnostics> {
    let [lo, hi] = {
        let r = cx.map.heights();
        [r.low().0, r.high().0]
    };
    let z = height(cx, sampled, lo / 2.0)?;
    // The lowest top over the beads (the form gave each sample one: a
    // sample without was refused).
    let (p, top) = sampled.iter().flat_map(|l| l.xy.iter().zip(&l.top)).fold(
        ([0.0; 2], f64::INFINITY),
        |best, (&p, &t)| {
            if t < best.1 {
                (p, t)
            } else {
                best
            }
        },
    );
    if top - z < lo * (1.0 - SLACK) {
        let at = cx.slicing.level.span().unwrap_or(cx.slicing.span);
        let d = message::scan::top_near_level(p, top, z, lo, at, None);
        return Err(d.into());
    }
    let pieces = pieces(cx, sampled, z, [lo, hi])?;
    let points: usize = pieces
        .iter()
        .map(|p| (p.n as usize).saturating_mul(p.track.t.len()))
        .fold(0, usize::saturating_add);
    let count = pieces.iter().map(|p| p.n).max().unwrap_or(0);
    if points > MAX_TOTAL_POINTS || count > MAX_LAYERS {
        let per_layer = pieces.iter().map(|p| p.track.t.len()).sum();
        let at = cx.slicing.level.span().unwrap_or(cx.slicing.span);
        let d = message::top::too_many_points(count, per_layer, MAX_TOTAL_POINTS, at);
        return Err(d.into());
    }
    let passes = laid(cx, &pieces);
    let levelled: Vec<Sampled> = sampled
        .iter()
        .map(|l| Sampled {
            s: l.s.clone(),
            xy: l.xy.clone(),
            gap: l.top.iter().map(|t| t - z).collect(),
            base: vec![z; l.s.len()],
            top: l.top.clone(),
        })
        .collect();
    let above = |p: [f64; 2]| (cx.top)(p).map(|t| t - z);
    let rest = regular(cx, &levelled, (Base::Level(z), passes.len()), &above)?;
    Ok(stacked(cx.model, passes, rest))
}

/// The level: declared, or the scan's highest point under the beads; the
/// scan may stand at most `slack` above a declared one.
fn height(cx: &Cx<'_>, sampled: &[Sampled], slack: f64) -> Result<f64, Diagnostics> {
    let highest = sampled.iter().flat_map(|l| l.xy.iter().zip(&l.base)).fold(
        None,
        |best: Option<([f64; 2], f64)>, (&p, &b)| match best {
            Some((_, h)) if h >= b => best,
            _ => Some((p, b)),
        },
    );
    let Some((at, b)) = highest else {
        return Err(internal("the wall has no point"));
    };
    match cx.slicing.level {
        Level::At(z, span) if b > z.0 + slack => {
            Err(message::scan::above_level(at, b, z.0, slack, [span, cx.on.base.span], None).into())
        }
        Level::At(z, _) => Ok(z.0),
        _ => Ok(b),
    }
}

/// Every line's stretches of one pass count (at least one, at least a
/// bead long), each in the fewest constant-speed segments; or the error
/// of those whose tolerance needs segments too short.
fn pieces(
    cx: &Cx<'_>,
    sampled: &[Sampled],
    z: f64,
    range: [f64; 2],
) -> Result<Vec<Piece>, Diagnostics> {
    let surface = &cx.on.base.surface;
    let follow = cx.tilt.map(|t| Follow::new(surface, t, cx.bead.width.0));
    let range_at = |p: [f64; 2], along: [f64; 2]| match follow {
        Some(f) => [range[0] / f.at(p, 1.0, along).along_track, range[1]],
        None => range,
    };
    steep(cx, sampled, z, &range_at)?;
    let count = |p: [f64; 2], along: [f64; 2]| {
        surface
            .at(p)
            .map_or(0, |b| passes(z - b, range_at(p, along)).0)
    };
    let mut stretches: Vec<(usize, u32, Sampled)> = Vec::new();
    for (line, l) in sampled.iter().enumerate() {
        for (n, run) in runs(l, &count, cx.bead.width.0) {
            // Each point's scan and what the run's `n` passes lay there
            // together, the gap kept within their range (a point the
            // bisection found off the scan is left out).
            let mut piece = Sampled::default();
            for (k, (&s, &p)) in run.s.iter().zip(&run.xy).enumerate() {
                if let Some(b) = surface.at(p) {
                    piece.s.push(s);
                    piece.xy.push(p);
                    piece
                        .gap
                        .push(within(z - b, n, range_at(p, direction(&run.xy, k))));
                    piece.base.push(b);
                }
            }
            if piece.s.len() >= 2 {
                stretches.push((line, n, piece));
            }
        }
    }
    let samples: Vec<Sampled> = stretches.iter().map(|(.., s)| s.clone()).collect();
    let segments = match segmented(&samples, cx.spec)? {
        Ok(s) => s,
        Err(failures) => {
            let (bead, on, slicing) = (cx.bead, cx.on, cx.slicing);
            return Err(too_short(&failures, &samples, bead, on, slicing, cx.spec).into());
        }
    };
    Ok(stretches
        .into_iter()
        .zip(segments)
        .map(|((line, n, s), segs)| {
            // A segment's start lies on a straight piece of the line: the
            // nearest sample's direction is that piece's.
            let gap = |p: [f64; 2]| {
                let k = nearest(&s.xy, p);
                surface
                    .at(p)
                    .map(|b| within(z - b, n, range_at(p, direction(&s.xy, k))))
            };
            let (mut track, xy) = on_samples(&s, cx.pitch, &segs, &gap);
            mean_heights(&mut track);
            Piece { line, n, track, xy }
        })
        .collect())
}

/// What `n` passes of `lo .. hi` each lay of a gap `g` together: `g`,
/// kept within `n·lo .. n·hi`.
fn within(g: f64, n: u32, [lo, hi]: [f64; 2]) -> f64 {
    g.clamp(n as f64 * lo, n as f64 * hi)
}

/// The stretches of `l` that take the same number of passes (`count` at a
/// point), at least one and at least `least` long, as samples; where the
/// count changes between two samples, the place is found by halving along
/// the straight piece between them and both stretches end there.
fn runs(l: &Sampled, count: &dyn Fn([f64; 2], [f64; 2]) -> u32, least: f64) -> Vec<(u32, Sampled)> {
    let counts: Vec<u32> = (0..l.xy.len())
        .map(|k| count(l.xy[k], direction(&l.xy, k)))
        .collect();
    let mut out = Vec::new();
    let m = l.s.len();
    let mut start = 0;
    // The run's first point: a sample, or where the count changed.
    let mut from: ([f64; 2], f64) = (l.xy[0], l.s[0]);
    for i in 1..=m {
        if i < m && counts[i] == counts[start] {
            continue;
        }
        let to = if i == m {
            (l.xy[m - 1], l.s[m - 1])
        } else {
            let (a, b) = ((l.xy[i - 1], l.s[i - 1]), (l.xy[i], l.s[i]));
            let at = |f: f64| {
                let p = [
                    a.0[0] + f * (b.0[0] - a.0[0]),
                    a.0[1] + f * (b.0[1] - a.0[1]),
                ];
                (p, a.1 + f * (b.1 - a.1))
            };
            let along = direction(&[a.0, b.0], 0);
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..20 {
                let mid = 0.5 * (lo + hi);
                if count(at(mid).0, along) == counts[start] {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            at(0.5 * (lo + hi))
        };
        if counts[start] > 0 && to.1 - from.1 >= least {
            let mut run = Sampled {
                s: vec![from.1],
                xy: vec![from.0],
                ..Sampled::default()
            };
            for k in start..i {
                if l.s[k] > from.1 && l.s[k] < to.1 {
                    run.s.push(l.s[k]);
                    run.xy.push(l.xy[k]);
                }
            }
            run.s.push(to.1);
            run.xy.push(to.0);
            out.push((counts[start], run));
        }
        start = i;
        from = to;
    }
    out
}

/// The passes as layers: pass `k` lays the pieces of more than `k`
/// passes, bead by bead in the wall's order and direction for that layer,
/// each stretch with its leads as a bead's (a stretch starts and stops
/// where the laser does, mid-line too), raised over the scan.
fn laid(cx: &Cx<'_>, pieces: &[Piece]) -> Vec<Layer> {
    let count = pieces.iter().map(|p| p.n).max().unwrap_or(0) as usize;
    let process =
        Process::of(cx.model, cx.bead, Base::Scan(&cx.on.base.surface)).following(cx.tilt, None);
    (0..count)
        .map(|k| {
            let power = cx.model.process.power.at(k).watts() as f32;
            let mut paths = Vec::new();
            for (j, forward) in order(cx.wall, cx.lines.len(), k) {
                let mut here: Vec<&Piece> = pieces
                    .iter()
                    .filter(|p| p.line == j && p.n as usize > k)
                    .collect();
                if !forward {
                    here.reverse();
                }
                for p in here {
                    let lay = (k as u32, p.n as f64);
                    let points = along(
                        &p.track, &p.xy, &cx.map, &process, None, lay, power, !forward,
                    );
                    let xy: Vec<[f64; 2]> = points.iter().map(|q| [q.pos[0], q.pos[1]]).collect();
                    let ends = [
                        direction(&xy, 0),
                        direction(&xy, xy.len().saturating_sub(1)),
                    ];
                    with_leads(cx.wall.ends, points, ends, &mut paths);
                }
            }
            above_scan(&mut paths, &cx.on.base.surface);
            layer(k, count, paths, Frame::PART)
        })
        .collect()
}

/// The sample of `xy` nearest `p`.
fn nearest(xy: &[[f64; 2]], p: [f64; 2]) -> usize {
    let d = |q: &[f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]);
    (0..xy.len())
        .min_by(|&a, &b| d(&xy[a]).total_cmp(&d(&xy[b])))
        .unwrap_or(0)
}

/// With the nozzle along the scan's normal (`follow = surface`), the
/// first place where the wear needs a pass but none can be laid: the
/// scan slopes so steeply along the line that the thinnest pass laid
/// along its normal, `lo / cos α` high, is taller than the bead lays
/// (`range_at` gives a place's heights for a track along a direction).
fn steep(
    cx: &Cx<'_>,
    sampled: &[Sampled],
    z: f64,
    range_at: &dyn Fn([f64; 2], [f64; 2]) -> [f64; 2],
) -> Result<(), Diagnostics> {
    let Some(follow) = cx.slicing.follow.filter(|_| cx.tilt.is_some()) else {
        return Ok(());
    };
    let r = cx.map.heights();
    let (lo0, hi0) = (r.low().0, r.high().0);
    for l in sampled {
        for (k, (&p, &b)) in l.xy.iter().zip(&l.base).enumerate() {
            let [lo, hi] = range_at(p, direction(&l.xy, k));
            if b.is_finite() && lo > hi * (1.0 + SLACK) && z - b >= lo / 2.0 {
                let s = message::scan::SteepPass {
                    at: p,
                    surface: b,
                    alpha: (lo0 / lo).clamp(-1.0, 1.0).acos(),
                    lo: lo0,
                    hi: hi0,
                    turnable: false,
                };
                let d = message::scan::level_follow_too_steep(s, [follow, cx.bead.span], None);
                return Err(d.into());
            }
        }
    }
    Ok(())
}

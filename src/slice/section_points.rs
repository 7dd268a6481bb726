//! Where a normal layer puts its points round the section. `points = k`
//! places `k` at equal angles from the seam and adds the section's corners
//! that fall between them; `chord_error = e` starts from the seam, the
//! corners and eight equal angles and halves every gap whose chord strays
//! more than `e` from the outline (or, on a bent spine, whose ends' layer
//! heights differ by more than the rise tolerance, so one speed per move
//! can lay it). Either way no chord cuts a corner: a rectangle's corners are
//! points of every layer.

use crate::geometry::{LoftGeometry, SectionFrame};
use std::f64::consts::TAU;

/// How a layer's points are spaced.
#[derive(Clone, Copy, Debug)]
pub enum Spacing {
    /// `k` at equal angles, plus the corners between them.
    Count(usize),
    /// No chord further than `error` mm from the outline; no move whose
    /// ends' heights differ by more than `rise` of their mean.
    Chord {
        /// mm.
        error: f64,
        /// A share.
        rise: f64,
    },
}

/// One point's angle round the section.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// rad, from the section's x axis; increasing from the seam.
    pub theta: f64,
    /// Its index on the equal-angle grid of `points = k`, if it is on it.
    pub grid: Option<usize>,
}

/// Angles closer than this (rad; 0.1 µm on a 100 mm radius) are one point.
const SAME: f64 = 1e-6;
/// Gaps are halved at most this often (2⁻⁴⁰ of a turn).
const MAX_DEPTH: u32 = 40;

/// The angles of layer station `s`'s points, from the seam round once.
/// `Err(n)`: more than `max` points (`n` so far).
pub fn angles(
    geo: &LoftGeometry,
    f: &SectionFrame,
    s: f64,
    seam: f64,
    spacing: Spacing,
    max: usize,
) -> Result<Vec<Sample>, usize> {
    let rel = |th: f64| (th - seam).rem_euclid(TAU);
    let corners = geo.blend.corners(s).into_iter().map(rel);
    let mut seeds: Vec<Sample> = match spacing {
        Spacing::Count(k) => (0..k)
            .map(|j| Sample {
                theta: j as f64 * TAU / k as f64,
                grid: Some(j),
            })
            .collect(),
        Spacing::Chord { .. } => (0..8)
            .map(|j| Sample {
                theta: j as f64 * TAU / 8.0,
                grid: None,
            })
            .collect(),
    };
    // A corner is a point exactly: one that falls within `SAME` of a seed
    // moves that seed onto it (a grid point keeps its index). The seeds are
    // in order, so each corner finds its neighbours by bisection.
    let mut extra = Vec::new();
    for c in corners {
        let i = seeds.partition_point(|p| p.theta < c);
        let n = seeds.len();
        let (lo, hi) = ((i + n - 1) % n.max(1), i % n.max(1));
        let d = |p: &Sample| {
            let d = (p.theta - c).abs();
            d.min(TAU - d)
        };
        let near = [lo, hi]
            .into_iter()
            .filter(|&j| j < n)
            .find(|&j| d(&seeds[j]) < SAME);
        match near {
            // Past the last seed, a corner just short of a full turn is the
            // seam's neighbour from below.
            Some(j) => {
                seeds[j].theta = if c - seeds[j].theta > 0.5 * TAU {
                    c - TAU
                } else {
                    c
                }
            }
            None => extra.push(Sample {
                theta: c,
                grid: None,
            }),
        }
    }
    seeds.extend(extra);
    seeds.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    seeds.dedup_by(|later, kept| (later.theta - kept.theta).abs() < SAME);
    let turn = TAU + seeds.first().map_or(0.0, |f| f.theta);
    if seeds.len() > 1 && seeds.last().is_some_and(|l| turn - l.theta < SAME) {
        seeds.pop();
    }
    let mut out = match spacing {
        Spacing::Count(_) => seeds,
        Spacing::Chord { error, rise } => {
            let fits = |a: f64, b: f64| gap_fits(geo, f, s, seam + a, seam + b, error, rise);
            let mut out = Vec::with_capacity(seeds.len() * 4);
            for (i, a) in seeds.iter().enumerate() {
                let b = seeds.get(i + 1).map_or(turn, |n| n.theta);
                out.push(*a);
                refine(&mut out, a.theta, b, 0, &fits, max)?;
            }
            out
        }
    };
    if out.len() > max {
        return Err(out.len());
    }
    for p in &mut out {
        p.theta += seam;
    }
    Ok(out)
}

/// Pushes the points that split the gap `a ..< b` (relative angles) until
/// every part fits; `Err` once more than `max` points.
fn refine(
    out: &mut Vec<Sample>,
    a: f64,
    b: f64,
    depth: u32,
    fits: &impl Fn(f64, f64) -> bool,
    max: usize,
) -> Result<(), usize> {
    if out.len() > max {
        return Err(out.len());
    }
    if depth >= MAX_DEPTH || fits(a, b) {
        return Ok(());
    }
    let m = 0.5 * (a + b);
    refine(out, a, m, depth + 1, fits, max)?;
    out.push(Sample {
        theta: m,
        grid: None,
    });
    refine(out, m, b, depth + 1, fits, max)
}

/// Whether the chord from angle `a` to `b` (absolute) stays within `error`
/// of the outline, sampled at its quarters, and its ends' layer heights
/// (proportional to the distance from the bend axis) within `rise` of their
/// mean.
fn gap_fits(
    geo: &LoftGeometry,
    f: &SectionFrame,
    s: f64,
    a: f64,
    b: f64,
    error: f64,
    rise: f64,
) -> bool {
    let uv = |th: f64| {
        let r = geo.blend.radius(s, th);
        [r * th.cos(), r * th.sin()]
    };
    let (pa, pb) = (uv(a), uv(b));
    let d = [pb[0] - pa[0], pb[1] - pa[1]];
    let len = d[0].hypot(d[1]);
    for m in [0.25, 0.5, 0.75] {
        let pm = uv(a + m * (b - a));
        let e = [pm[0] - pa[0], pm[1] - pa[1]];
        let off = if len > 0.0 {
            (d[0] * e[1] - d[1] * e[0]).abs() / len
        } else {
            e[0].hypot(e[1])
        };
        if off > error {
            return false;
        }
    }
    match (geo.bend_distance(f, pa), geo.bend_distance(f, pb)) {
        (Some(ra), Some(rb)) => (ra - rb).abs() <= rise * 0.5 * (ra + rb).abs(),
        _ => true,
    }
}

/// Stations [`fewest`] samples a loft's layers at.
const ESTIMATE_STATIONS: usize = 9;

/// The fewest points a layer gets (its samples and the closing point) at
/// [`ESTIMATE_STATIONS`] stations spread over the loft: what a plan's
/// point budget is checked with before any layer is sliced (a few
/// sections' worth of work). `Err((s, n))`: station `s` (0 ..= 1) needs
/// more than `max`, `n` so far.
pub fn fewest(geo: &LoftGeometry, spacing: Spacing, max: usize) -> Result<usize, (f64, usize)> {
    let mut least = usize::MAX;
    for i in 0..ESTIMATE_STATIONS {
        let s = i as f64 / (ESTIMATE_STATIONS - 1) as f64;
        let f = geo.frame(s);
        let n = angles(geo, &f, s, std::f64::consts::FRAC_PI_2, spacing, max)
            .map_err(|n| (s, n))?
            .len();
        least = least.min(n + 1);
    }
    Ok(least)
}

//! Choosing the layer count of normal slicing, and explaining in the user's
//! terms why a part cannot be built with its bead model.

use crate::bead::HeightModel;
use crate::diag::message;
use crate::diag::message::bend::{Fewer, Heights, TooTight, WallLimit};
use crate::diag::Diagnostic;
use crate::geometry::LoftGeometry;
use crate::sema::model::{Bead, Loft, Measure, Resolution, Section, Slicing, Spine, MAX_LAYERS};
use crate::slice::MAX_TOTAL_POINTS;
use crate::units::{Length, Speed};

/// How far the outline reaches toward (`inward`) and away from (`outward`) the
/// bend centre, over all stations, mm.
#[derive(Clone, Copy, Debug)]
pub struct Reach {
    /// Largest offset toward the bend centre.
    pub inward: f64,
    /// Largest offset away from it.
    pub outward: f64,
}

/// Samples the loft's outline to find its reach. The exact points come later;
/// the margin in [`choose_layers`] covers the sampling error.
pub fn reach(geo: &LoftGeometry) -> Reach {
    const STATIONS: usize = 128;
    const ANGLES: usize = 720;
    let (mut inward, mut outward) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for i in 0..=STATIONS {
        let s = i as f64 / STATIONS as f64;
        let f = geo.frame(s);
        let (sin, cos) = f.twist.sin_cos();
        for j in 0..ANGLES {
            let th = j as f64 * std::f64::consts::TAU / ANGLES as f64;
            let r = geo.blend.radius(s, th);
            let (st, ct) = th.sin_cos();
            let a = r * ct * cos - r * st * sin;
            inward = inward.max(a);
            outward = outward.max(-a);
        }
    }
    Reach { inward, outward }
}

/// Relative margin on the sampled reach (see [`reach`]).
const MARGIN: f64 = 1e-5;

/// The number of layers and the step (Δδ in rad for an arc; the layer height
/// for a line), or the reasons it cannot be built. `per_layer`: the fewest
/// points a layer will have, so that `layers = auto` is held to the
/// layers and points a plan may have before anything is sliced.
pub fn choose_layers(
    loft: &Loft,
    geo: &LoftGeometry,
    bead: &Bead,
    slicing: &Slicing,
    per_layer: usize,
) -> Result<(usize, f64), Diagnostic> {
    // A wall one bead wide: the heights it stacks are its rises A/w.
    let [h_min, h_max] = bead.heights(bead.width).map(|h| h.0);
    let (total, rho_min, rho_max) = match loft.spine {
        Spine::Line { length } => (length.0, 1.0, 1.0),
        Spine::Arc { radius, angle } => {
            let r = reach(geo);
            let rho_min = (radius.0 - r.inward) * (1.0 - MARGIN);
            let rho_max = (radius.0 + r.outward) * (1.0 + MARGIN);
            if rho_min <= 0.0 {
                return Err(message::bend::section_past_centre(
                    r.inward,
                    radius,
                    suggest_radius(r, angle.0, [h_min, h_max], slicing.layers),
                    loft.spine_span,
                    loft.section_spans[0],
                ));
            }
            let q_need = rho_max / rho_min;
            let q_have = h_max / h_min;
            let (n_lo, n_hi) = layer_range(rho_min, rho_max, angle.0, h_min, h_max);
            if q_need > q_have || (slicing.layers.is_none() && n_lo > n_hi) {
                return Err(too_tight(
                    loft,
                    bead,
                    slicing.layers,
                    r,
                    angle.0,
                    q_need,
                    q_have,
                ));
            }
            (angle.0, rho_min, rho_max)
        }
    };
    // What each layer's height is a share of: the spine's length (or angle)
    // times the distance from the bend axis, or with the nozzle following
    // the wall the wall's own slant along the nozzle ([`along_nozzle`]).
    let (rho_min, rho_max, total, step) = match slicing.follow_wall {
        true => {
            let [lo, hi] = along_nozzle(geo);
            (lo, hi, 1.0, total)
        }
        false => (rho_min, rho_max, total, total),
    };
    let (n_lo, n_hi) = layer_range(rho_min, rho_max, total, h_min, h_max);
    let what = match loft.spine {
        Spine::Line { .. } => "layer height",
        Spine::Arc { .. } => "layer heights",
    };
    match slicing.layers {
        None => {
            // A spiral's first climb rises off the plate and lays up to
            // twice the layer height (`normal::Climb`): the fewest layers
            // whose thickest point the bead lays twice over, when the
            // thinnest still stays within the bead's range.
            let n_lo = match slicing.layer_change.is_spiral() {
                true => layer_range(rho_min, rho_max, total, h_min, h_max / 2.0)
                    .0
                    .min(n_hi.max(n_lo)),
                false => n_lo,
            };
            if n_lo > n_hi {
                return Err(message::bend::no_layer_count(
                    what,
                    heights(bead),
                    loft.spine_span,
                ));
            }
            // Refused here, from the count alone: every layer's seam and
            // points are allocated and computed after this.
            within_budget(n_lo, rho_max * total, (bead, slicing), per_layer)?;
            Ok((n_lo as usize, step / n_lo))
        }
        Some(n) => {
            let nf = n as f64;
            if nf < n_lo || nf > n_hi {
                return Err(message::bend::layer_count_outside(
                    n,
                    what,
                    [rho_min * total / nf, rho_max * total / nf],
                    (n_lo <= n_hi).then_some([n_lo, n_hi]),
                    heights(bead),
                    slicing.layers_span,
                ));
            }
            Ok((n, step / nf))
        }
    }
}

/// Refuses `n` layers of `per_layer` points, more than a plan may have,
/// for a wall whose thickest point stacks `reach` (mm) over all layers:
/// with the bead height, and a mass balance's efficiency, that would fit.
fn within_budget(
    n: f64,
    reach: f64,
    (bead, slicing): (&Bead, &Slicing),
    per_layer: usize,
) -> Result<(), Diagnostic> {
    let most = MAX_LAYERS.min(MAX_TOTAL_POINTS / per_layer.max(1)).max(1);
    if n <= most as f64 {
        return Ok(());
    }
    let fits = reach / most as f64;
    let h_max = bead.heights(bead.width)[1].0;
    Err(message::bend::too_many_wall_layers(
        n,
        WallLimit {
            layers: most,
            points: (most < MAX_LAYERS)
                .then(|| (per_layer, MAX_TOTAL_POINTS, fewer(slicing, per_layer, n))),
        },
        Length(fits),
        efficiency_for(bead, fits / h_max),
        heights(bead),
        slicing.layers_span.unwrap_or(slicing.span),
    ))
}

/// How `n` layers of `per_layer` points each would hold no more than a
/// plan may: a larger chord error, or `points = k` (the section's corners
/// and the closing point come on top of `k`), when 8 or more do.
fn fewer(slicing: &Slicing, per_layer: usize, n: f64) -> Option<Fewer> {
    match slicing.resolution {
        Resolution::ChordError(_) => Some(Fewer::ChordError),
        Resolution::Count(k) => {
            let extra = per_layer.saturating_sub(k) as f64;
            let fit = (MAX_TOTAL_POINTS as f64 / n).floor() - extra;
            (fit >= 8.0).then_some(Fewer::Points(fit as usize))
        }
    }
}

/// The catch efficiency (a share) at which a mass-balance bead lays `k`
/// times what it does: its heights grow with it in proportion.
fn efficiency_for(bead: &Bead, k: f64) -> Option<f64> {
    match bead.model {
        HeightModel::MassBalance { efficiency, .. } => {
            Some(efficiency * k).filter(|e| e.is_finite() && *e > 0.0)
        }
        _ => None,
    }
}

/// Stations and angles [`along_nozzle`] samples the wall at.
const SLANT_STATIONS: usize = 128;
/// See [`SLANT_STATIONS`].
const SLANT_ANGLES: usize = 360;

/// How fast the wall rises along the nozzle when it follows the wall
/// (`nozzle = wall`), least and most over the wall: the step from a point
/// to the same section angle a station on, less its part along the layer's
/// path (what `normal::follow_wall` makes each point's layer height), per
/// unit of station — a straight cone's slant length `√(L² + (R₀ − R₁)²)`
/// everywhere. With `n` layers the heights run from the least over `n` to
/// the most over `n`, so the count is taken along the nozzle as it is laid.
fn along_nozzle(geo: &LoftGeometry) -> [f64; 2] {
    use std::f64::consts::TAU;
    let ds = 1.0 / SLANT_STATIONS as f64;
    let dth = TAU / SLANT_ANGLES as f64;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..SLANT_STATIONS {
        let s = i as f64 * ds;
        let (f, g) = (geo.frame(s), geo.frame(s + ds));
        for j in 0..SLANT_ANGLES {
            let th = j as f64 * dth;
            let p = geo.point(&f, s, th).0;
            let t = geo.point(&f, s, th + 1e-4).0 - geo.point(&f, s, th - 1e-4).0;
            let mut d = geo.point(&g, s + ds, th).0 - p;
            if let Some(t) = t.try_normalize(1e-12) {
                d -= t * d.dot(&t);
            }
            let rate = d.norm() / ds;
            lo = lo.min(rate);
            hi = hi.max(rate);
        }
    }
    [lo * (1.0 - MARGIN), hi * (1.0 + MARGIN)]
}

/// The layer counts whose heights, from `rho_min·total/n` to
/// `rho_max·total/n`, fit within `h_min..h_max` (empty when `lo > hi`).
fn layer_range(rho_min: f64, rho_max: f64, total: f64, h_min: f64, h_max: f64) -> (f64, f64) {
    let lo = (rho_max * total / h_max).ceil().max(1.0);
    let hi = (rho_min * total / h_min).floor();
    (lo, hi)
}

/// Whether the layer counts of a bend of `radius` (the section reaching
/// `r`) over `angle` keep every height within `h` — the test
/// [`choose_layers`] applies, with its margin — and, when one does (the
/// declared one, if `declared`), how long the interval of counts is: once it
/// is a layer long it holds a whole count whatever its ends, and it grows
/// with the radius, the bead's span and a smaller section.
fn counts(r: Reach, radius: f64, angle: f64, h: [f64; 2], declared: Option<usize>) -> Option<f64> {
    let [h_min, h_max] = h;
    let rho_min = (radius - r.inward) * (1.0 - MARGIN);
    let rho_max = (radius + r.outward) * (1.0 + MARGIN);
    if !(rho_min > 0.0 && h_min > 0.0 && h_max.is_finite()) {
        return None;
    }
    let (lo, hi) = layer_range(rho_min, rho_max, angle, h_min, h_max);
    match declared {
        // A declared count fits a band of radii: no further claim.
        Some(n) => (lo <= n as f64 && n as f64 <= hi).then_some(0.0),
        None => (lo <= hi).then(|| (rho_min / h_min - rho_max / h_max) * angle),
    }
}

/// The first of `candidates` from which on every one passes `test` (which
/// gives the counts' interval length, [`counts`]): found when that length
/// reaches a layer, or at the first pass when `once`.
fn first_lasting(
    candidates: impl Iterator<Item = f64>,
    once: bool,
    mut test: impl FnMut(f64) -> Option<f64>,
) -> Option<f64> {
    let mut first = None;
    for c in candidates {
        match test(c) {
            Some(span) => {
                let f = *first.get_or_insert(c);
                if once || span >= 1.0 {
                    return Some(f);
                }
            }
            None => first = None,
        }
    }
    None
}

/// The smallest whole-mm bend radius from which on a layer count fits the
/// bead's heights (the declared count, if `declared`: then that radius
/// alone), by the same test [`choose_layers`] applies. The height ratio
/// alone gives `R ≥ (out + q·in)/(q − 1)`; a whole number of layers may need
/// a little more.
fn suggest_radius(r: Reach, angle: f64, h: [f64; 2], declared: Option<usize>) -> Option<f64> {
    let q = h[1] / h[0];
    if q <= 1.0 {
        return None;
    }
    let start = ((r.outward + q * r.inward) / (q - 1.0)).ceil().max(1.0);
    let radii = (0..100_000).map(|i| start + i as f64);
    first_lasting(radii, declared.is_some(), |radius| {
        counts(r, radius, angle, h, declared)
    })
}

/// The top speed (mm/s, a tenth) from which on a bead model with the
/// bead's speeds reaching it lays this bend, by the same test: the wall's
/// heights `A(v)/w` over the wider range, narrowed to a declared `height`.
fn suggest_speed(
    bead: &Bead,
    r: Reach,
    radius: f64,
    angle: f64,
    q_need: f64,
    declared: Option<usize>,
) -> Option<f64> {
    // Where the ratio alone would be met: the wall's rise at the slowest
    // speed over the ratio the bend needs.
    let deposit = bead.deposit();
    let h_max = bead.heights(bead.width)[1].0;
    let h_top = deposit.rise(bead.speed[0], bead.width, None).0.min(h_max);
    let v = deposit.speed_for(Length(h_top / q_need), bead.width).0;
    if !(v.is_finite() && v > 0.0) {
        return None;
    }
    let start = (v * 10.0).ceil().max((bead.speed[1].0 * 10.0).floor());
    let tops = (0..2000).map(|k| (start + k as f64) / 10.0);
    first_lasting(tops, declared.is_some(), |v| {
        let mut wider = bead.clone();
        wider.speed[1] = Speed(v);
        let h = wider.heights(wider.width).map(|h| h.0);
        counts(r, radius, angle, h, declared)
    })
}

/// The largest section, in tenths of a percent of the declared sizes, from
/// which down every smaller one lays this bend by the same test: the
/// sections scaled as written (outer faces, for `size = outer`) and their
/// reach sampled again.
fn suggest_scale(
    loft: &Loft,
    bead: &Bead,
    radius: f64,
    angle: f64,
    declared: Option<usize>,
) -> Option<f64> {
    let h = bead.heights(bead.width).map(|h| h.0);
    let reach_at = |s: f64| Some(reach(&scaled(loft, s, bead.width.0)?.geometry()));
    let ratio_fits = |s: f64| {
        reach_at(s).is_some_and(|r| {
            let q = (radius + r.outward) / (radius - r.inward);
            radius > r.inward && q <= h[1] / h[0]
        })
    };
    // The ratio shrinks with the section: halve toward the largest that
    // meets it, then step down by tenths of a percent for a whole count.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..14 {
        let mid = 0.5 * (lo + hi);
        if ratio_fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let start = (hi * 1000.0).floor();
    // A smaller section narrows the heights a bend needs, so the smallest
    // candidate passes if any does: tried first, it spares a thousand
    // samplings of the loft (seconds) when the bead is far off (a density
    // in kg/m^3 read as g/cm^3).
    let scales: Vec<f64> = (0..1000)
        .map(|k| (start - k as f64) / 10.0)
        .take_while(|&p| p > 0.0)
        .collect();
    let w = bead.width.0;
    if let Some(&p) = scales
        .iter()
        .rfind(|&&p| scaled(loft, p / 100.0, w).is_some())
    {
        let least = counts(reach_at(p / 100.0)?, radius, angle, h, declared)?;
        if declared.is_none() && least < 1.0 {
            return None;
        }
    }
    first_lasting(scales.into_iter(), declared.is_some(), |p| {
        counts(reach_at(p / 100.0)?, radius, angle, h, declared)
    })
}

/// `loft` with its sections scaled by `s` as declared: for `size = outer`
/// the outer faces scale, and the path runs half a bead inside them again.
fn scaled(loft: &Loft, s: f64, w: f64) -> Option<Loft> {
    let d = match loft.measure {
        Measure::Outer => w / 2.0,
        Measure::Centre => 0.0,
    };
    let grow = |x: Length, by: f64| Length((x.0 + by) * s);
    let declared = |sec: Section| match sec {
        Section::Circle { r } => Section::Circle { r: grow(r, d) },
        Section::Ellipse { a, b } => Section::Ellipse {
            a: grow(a, d),
            b: grow(b, d),
        },
        Section::Rectangle { a, b } => Section::Rectangle {
            a: grow(a, d),
            b: grow(b, d),
        },
        Section::RoundedRectangle { a, b, r } => Section::RoundedRectangle {
            a: grow(a, d),
            b: grow(b, d),
            r: grow(r, d),
        },
        Section::Polygon { n, r } => Section::Polygon {
            n,
            r: grow(r, d / (std::f64::consts::PI / n as f64).cos()),
        },
    };
    let mut out = loft.clone();
    out.from = declared(loft.from).inset(Length(d))?;
    out.to = declared(loft.to).inset(Length(d))?;
    Some(out)
}

fn too_tight(
    loft: &Loft,
    bead: &Bead,
    declared: Option<usize>,
    r: Reach,
    angle: f64,
    q_need: f64,
    q_have: f64,
) -> Diagnostic {
    let radius = match loft.spine {
        Spine::Arc { radius, .. } => radius.0,
        Spine::Line { .. } => f64::INFINITY,
    };
    let h = bead.heights(bead.width).map(|h| h.0);
    message::bend::too_tight(&TooTight {
        radius,
        inward: r.inward,
        outward: r.outward,
        q_need,
        q_have,
        heights: heights(bead),
        spine: loft.spine_span,
        speeds: bead.speed_span,
        radius_fits: suggest_radius(r, angle, h, declared),
        speed_fits: suggest_speed(bead, r, radius, angle, q_need, declared),
        scale_percent: suggest_scale(loft, bead, radius, angle, declared),
        at_least: declared.is_none(),
    })
}

/// The heights the bead stacks as a wall, for the messages.
fn heights(bead: &Bead) -> Heights {
    Heights {
        range: bead.heights(bead.width),
        span: bead.height_span,
    }
}

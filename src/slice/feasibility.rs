//! Choosing the layer count of normal slicing, and explaining in the user's
//! terms why a part cannot be built with its bead model.

use crate::diag::message::{self, bend::Heights, bend::TooTight};
use crate::diag::Diagnostic;
use crate::geometry::LoftGeometry;
use crate::sema::model::{Bead, Loft, Slicing, Spine};
use crate::units::Length;

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
/// for a line), or the reasons it cannot be built.
pub fn choose_layers(
    loft: &Loft,
    geo: &LoftGeometry,
    bead: &Bead,
    slicing: &Slicing,
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
                    suggest_radius(r, angle.0, h_min, h_max),
                    loft.spine_span,
                    loft.section_spans[0],
                ));
            }
            let q_need = rho_max / rho_min;
            let q_have = h_max / h_min;
            let (n_lo, n_hi) = layer_range(rho_min, rho_max, angle.0, h_min, h_max);
            if q_need > q_have || (slicing.layers.is_none() && n_lo > n_hi) {
                return Err(too_tight(loft, bead, radius.0, r, angle.0, q_need, q_have));
            }
            (angle.0, rho_min, rho_max)
        }
    };
    let (n_lo, n_hi) = layer_range(rho_min, rho_max, total, h_min, h_max);
    let what = match loft.spine {
        Spine::Line { .. } => "layer height",
        Spine::Arc { .. } => "layer heights",
    };
    match slicing.layers {
        None => {
            if n_lo > n_hi {
                return Err(message::bend::no_layer_count(
                    what,
                    heights(bead),
                    loft.spine_span,
                ));
            }
            Ok((n_lo as usize, total / n_lo))
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
            Ok((n, total / nf))
        }
    }
}

/// The layer counts whose heights, from `rho_min·total/n` to
/// `rho_max·total/n`, fit within `h_min..h_max` (empty when `lo > hi`).
fn layer_range(rho_min: f64, rho_max: f64, total: f64, h_min: f64, h_max: f64) -> (f64, f64) {
    let lo = (rho_max * total / h_max).ceil().max(1.0);
    let hi = (rho_min * total / h_min).floor();
    (lo, hi)
}

/// The smallest whole-mm bend radius for which some layer count fits the
/// bead's height range, by the same test [`choose_layers`] applies. The height
/// ratio alone gives `R ≥ (out + q·in)/(q − 1)`; a whole number of layers may
/// need a little more.
fn suggest_radius(r: Reach, angle: f64, h_min: f64, h_max: f64) -> Option<f64> {
    let q = h_max / h_min;
    if q <= 1.0 {
        return None;
    }
    let start = ((r.outward + q * r.inward) / (q - 1.0)).ceil().max(1.0);
    (0..100_000).map(|i| start + i as f64).find(|&radius| {
        let rho_min = (radius - r.inward) * (1.0 - MARGIN);
        let rho_max = (radius + r.outward) * (1.0 + MARGIN);
        let (lo, hi) = layer_range(rho_min, rho_max, angle, h_min, h_max);
        rho_min > 0.0 && lo <= hi
    })
}

fn too_tight(
    loft: &Loft,
    bead: &Bead,
    radius: f64,
    r: Reach,
    angle: f64,
    q_need: f64,
    q_have: f64,
) -> Diagnostic {
    let scale = radius * (q_have - 1.0) / (r.outward + q_have * r.inward);
    let [h_min, h_max] = bead.heights(bead.width);
    // The wall's rise at the slowest speed, and the speed that lays it over
    // the ratio the bend needs.
    let deposit = bead.deposit();
    let h_top = deposit.rise(bead.speed[0], bead.width, None).0.min(h_max.0);
    let v_fast = deposit.speed_for(Length(h_top / q_need), bead.width);
    let radius_fits = suggest_radius(r, angle, h_min.0, h_max.0);
    let speed_fits =
        (v_fast.0.is_finite() && v_fast.0 > 0.0).then(|| (v_fast.0 * 10.0).ceil() / 10.0);
    message::bend::too_tight(&TooTight {
        radius,
        inward: r.inward,
        outward: r.outward,
        q_need,
        q_have,
        heights: heights(bead),
        spine: loft.spine_span,
        speeds: bead.speed_span,
        radius_fits,
        speed_fits,
        scale_percent: (scale * 1000.0).floor() / 10.0,
    })
}

/// The heights the bead stacks as a wall, for the messages.
fn heights(bead: &Bead) -> Heights {
    Heights {
        range: bead.heights(bead.width),
        span: bead.height_span,
    }
}

//! Calibrating the thermal model to measured temperatures (`lmdc fit
//! --plan`, docs/thermal.md, *Calibration*): the absorptivity and the heat
//! transfer coefficient — the model's two least certain numbers — that make
//! its interpass temperatures nearest (least squares) to the ones measured
//! on a build of the same plan, with the residuals.
//!
//! The two are found by a log-spaced grid over their plausible ranges,
//! then refined from the best point by Levenberg–Marquardt in log space. A best value at the edge of its range means the data do not
//! settle it ([`Fitted::at_edge`]): the fit says so rather than
//! extrapolate.

use super::{predict_tree, Columns, Load, Material, Plate};

/// The absorptivities searched.
pub const ABSORPTIVITY: [f64; 2] = [0.05, 0.95];
/// The heat transfer coefficients searched, W/(m²·K).
pub const HEAT_TRANSFER: [f64; 2] = [1.0, 500.0];

/// One measurement: the temperature where and when layer `layer` (0-based)
/// starts, or one of its islands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// The layer, 0-based.
    pub layer: usize,
    /// The island, 0-based in the order the layer lays them (the report's
    /// order); `None`: the layer's start, on its first island.
    pub island: Option<usize>,
    /// Its interpass temperature, °C.
    pub interpass: f64,
}

/// A plan's layers as the model runs them for a fit.
#[derive(Clone, Copy, Debug)]
pub struct Plan<'a> {
    /// The columns each layer's islands are laid on.
    pub columns: &'a Columns,
    /// Each layer's islands' loads (a layer of one piece: one).
    pub layers: &'a [Vec<Load>],
    /// The order each layer lays its islands in.
    pub orders: &'a [Vec<usize>],
    /// The wait before each layer, s (the first's is not used).
    pub waits: &'a [f64],
}

/// What a fit found.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// The share of the laser's power the part takes up.
    pub absorptivity: f64,
    /// Heat transfer coefficient to the cell's gas, W/(m²·K).
    pub heat_transfer: f64,
    /// Each measurement's residual, predicted − measured, K.
    pub residuals: Vec<f64>,
    /// Root mean square of the residuals, K.
    pub rms: f64,
    /// Which of the two ended at the edge of the range searched
    /// (absorptivity, heat transfer): the data do not settle it.
    pub at_edge: [bool; 2],
}

/// Fits the absorptivity and heat transfer coefficient of `material` to
/// `measured`, the plan's layers laid as `plan` says (as [`predict_tree`]
/// runs them). A measurement is a layer's interpass temperature: where
/// the nozzle starts it (on its first island), or one of its islands.
/// `None` without a measurement, or with one of a layer or an island the
/// plan does not have.
pub fn fit(
    material: Material,
    plate: Plate,
    plan: Plan<'_>,
    measured: &[Measured],
) -> Option<Fitted> {
    let Plan {
        columns,
        layers,
        orders,
        waits,
    } = plan;
    let last = measured.iter().map(|m| m.layer).max()?;
    if last >= layers.len() || last >= orders.len() || last >= waits.len() {
        return None;
    }
    let islands = |m: &Measured| m.island.is_none_or(|g| g < layers[m.layer].len());
    if !measured.iter().all(islands) {
        return None;
    }
    let residuals = |eta: f64, h: f64| -> Vec<f64> {
        let m = Material {
            absorptivity: eta,
            heat_transfer: h,
            ..material
        };
        let p = predict_tree(
            m,
            plate,
            columns,
            &layers[..=last],
            &orders[..=last],
            |i| waits[i],
            None,
        )
        .unwrap_or_default();
        measured
            .iter()
            .map(|x| {
                let at = p.get(x.layer).and_then(|p| match x.island {
                    Some(g) => p.islands.get(g).map(|i| i.interpass),
                    None => Some(p.layer.interpass),
                });
                at.map_or(f64::INFINITY, |t| t - x.interpass)
            })
            .collect()
    };
    let cost = |eta: f64, h: f64| residuals(eta, h).iter().map(|r| r * r).sum::<f64>();
    let (le, lh) = (ABSORPTIVITY.map(f64::ln), HEAT_TRANSFER.map(f64::ln));
    let at = |t: f64, [a, b]: [f64; 2]| (a + t * (b - a)).exp();
    // The grid: 13 × 13, the best point its start.
    let n = 12;
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for i in 0..=n {
        for j in 0..=n {
            let (e, h) = (at(i as f64 / n as f64, le), at(j as f64 / n as f64, lh));
            let c = cost(e, h);
            if c < best.0 {
                best = (c, e.ln(), h.ln());
            }
        }
    }
    let (_, e, h) = best;
    let [e, h] = levenberg_marquardt(
        |[e, h]: [f64; 2]| residuals(e.exp(), h.exp()),
        [e, h],
        [le, lh],
    );
    let (eta, htc) = (e.exp(), h.exp());
    let r = residuals(eta, htc);
    let rms = (r.iter().map(|x| x * x).sum::<f64>() / r.len() as f64).sqrt();
    let edge = |x: f64, [a, b]: [f64; 2]| (x - a).abs() < 1e-3 * a || (b - x).abs() < 1e-3 * b;
    Some(Fitted {
        absorptivity: eta,
        heat_transfer: htc,
        residuals: r,
        rms,
        at_edge: [edge(eta, ABSORPTIVITY), edge(htc, HEAT_TRANSFER)],
    })
}

/// The least squares of `residuals` from `start` within `bounds` by
/// Levenberg–Marquardt: the two numbers trade against each other (more
/// heat in, more out), so the valley runs aslant and a search along each
/// in turn crawls down it; a Gauss–Newton step with a forward-difference
/// Jacobian goes along it.
fn levenberg_marquardt(
    residuals: impl Fn([f64; 2]) -> Vec<f64>,
    start: [f64; 2],
    bounds: [[f64; 2]; 2],
) -> [f64; 2] {
    let clamp = |x: [f64; 2]| [0, 1].map(|k| x[k].clamp(bounds[k][0], bounds[k][1]));
    let sq = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    let (mut x, mut lambda) = (start, 1e-3);
    let mut r = residuals(x);
    for _ in 0..50 {
        // The Jacobian's columns, by a step of 10⁻⁵ in log space (inwards
        // at an upper bound).
        let cols = [0, 1].map(|k| {
            let d = if x[k] + 1e-5 > bounds[k][1] {
                -1e-5
            } else {
                1e-5
            };
            let mut y = x;
            y[k] += d;
            let ry = residuals(y);
            r.iter()
                .zip(&ry)
                .map(|(a, b)| (b - a) / d)
                .collect::<Vec<f64>>()
        });
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let a = [
            [dot(&cols[0], &cols[0]), dot(&cols[0], &cols[1])],
            [0.0, dot(&cols[1], &cols[1])],
        ];
        let g = [dot(&cols[0], &r), dot(&cols[1], &r)];
        let mut moved = false;
        while lambda < 1e10 {
            let (p, q, s) = (a[0][0] * (1.0 + lambda), a[1][1] * (1.0 + lambda), a[0][1]);
            let det = p * q - s * s;
            if det == 0.0 || !det.is_finite() {
                lambda *= 4.0;
                continue;
            }
            let step = [-(q * g[0] - s * g[1]) / det, -(p * g[1] - s * g[0]) / det];
            let y = clamp([x[0] + step[0], x[1] + step[1]]);
            let ry = residuals(y);
            if sq(&ry) < sq(&r) {
                let small = (y[0] - x[0]).abs() < 1e-9 && (y[1] - x[1]).abs() < 1e-9;
                (x, r, lambda, moved) = (y, ry, (lambda / 3.0).max(1e-9), !small);
                break;
            }
            lambda *= 4.0;
        }
        if !moved {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::thermal::predict;

    /// Temperatures the model itself predicts with known values come back
    /// as those values, residuals nil.
    #[test]
    fn recovers_the_values_that_made_the_data() {
        let base = crate::thermal::alloy("ti64").unwrap().material;
        let truth = Material {
            absorptivity: 0.42,
            heat_transfer: 35.0,
            ..base
        };
        let plate = Plate {
            size: [0.1, 0.05, 0.01],
            temperature: 25.0,
            ambient: 25.0,
        };
        let load = Load {
            energy: 1500.0,
            time: 5.0,
            volume: 60e-9,
            height: 6e-4,
            perimeter: 0.1,
        };
        let loads = vec![load; 20];
        let waits: Vec<f64> = (0..20)
            .map(|i| if i % 2 == 0 { 5.0 } else { 40.0 })
            .collect();
        let p = predict(truth, plate, &loads, |i| waits[i], None).unwrap();
        let measured: Vec<Measured> = (1..20)
            .map(|layer| Measured {
                layer,
                island: None,
                interpass: p[layer].interpass,
            })
            .collect();
        let layers: Vec<Vec<Load>> = loads.iter().map(|l| vec![*l]).collect();
        let orders = vec![vec![0]; layers.len()];
        let columns = Columns::side_by_side(&layers);
        let plan = Plan {
            columns: &columns,
            layers: &layers,
            orders: &orders,
            waits: &waits,
        };
        let f = fit(base, plate, plan, &measured).unwrap();
        assert!((f.absorptivity - 0.42).abs() < 0.01, "{f:?}");
        assert!((f.heat_transfer - 35.0).abs() < 3.5, "{f:?}");
        assert!(f.rms < 0.5, "{f:?}");
        assert_eq!(f.at_edge, [false, false]);
    }
}

//! The height error the page shows: how far the rise the plan's bead model
//! predicts at a deposit's speed (`Point::rise`, [`crate::deposit`]) is from
//! the layer height the plan stacks there, move by move and layer by layer.
//! The verifier holds the plan to the same comparison (`lmd::deposit`); the
//! page shows where inside its tolerance a plan lies, and which way.

use crate::ir::Point;

/// The height error of a deposit starting at `p`, per cent:
/// `rise / layer_height − 1`. `None` where no rise is predicted (a ring, no
/// bead model, the laser off: `rise` is 0).
pub fn of(p: &Point) -> Option<f64> {
    (p.rise > 0.0 && p.layer_height > 0.0)
        .then(|| (p.rise as f64 / p.layer_height as f64 - 1.0) * 100.0)
}

/// One layer's height errors so far.
#[derive(Default)]
struct Layer {
    /// Ground covered by its predicted deposits, mm.
    len: f64,
    /// Their error, per cent, times the ground.
    pct: f64,
    /// Their rise minus the layer height, mm, times the ground.
    mm: f64,
    /// Lowest and highest error, per cent.
    lo: f64,
    hi: f64,
    /// Any predicted deposit.
    any: bool,
}

/// Every layer's height error, in plan order.
#[derive(Default)]
pub struct Layers {
    done: Vec<Option<[f64; 4]>>,
    open: Option<Layer>,
    /// The layers' mean errors (mm) added up so far.
    drift: f64,
}

impl Layers {
    /// A new layer begins (the one before is done).
    pub fn begin(&mut self) {
        self.end();
        self.open = Some(Layer {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            ..Layer::default()
        });
    }

    /// A deposit from `p` covering `ground` mm across the normal (what a
    /// layer's mean is weighted by, as `lmd::deposit` weighs it).
    pub fn deposit(&mut self, p: &Point, ground: f64) {
        let (Some(l), Some(e)) = (self.open.as_mut(), of(p)) else {
            return;
        };
        // A move of no length still counts: its point is on the path.
        let w = ground.max(1e-9);
        l.len += w;
        l.pct += w * e;
        l.mm += w * (p.rise - p.layer_height) as f64;
        l.lo = l.lo.min(e);
        l.hi = l.hi.max(e);
        l.any = true;
    }

    fn end(&mut self) {
        if let Some(l) = self.open.take() {
            self.done.push(l.any.then(|| {
                self.drift += l.mm / l.len;
                [
                    round(l.pct / l.len, 1e3),
                    round(l.lo, 1e3),
                    round(l.hi, 1e3),
                    round(self.drift, 1e4),
                ]
            }));
        }
    }

    /// Each layer's `[mean %, lowest %, highest %, drift mm]` — the mean
    /// over its deposited length, and the layers' mean rise minus height
    /// added up to this layer — or `None` where nothing is predicted.
    pub fn finish(mut self) -> Vec<Option<[f64; 4]>> {
        self.end();
        self.done
    }
}

/// `x` to `1/per` (short in the page's JSON; the page draws it, nobody
/// computes with it).
fn round(x: f64, per: f64) -> f64 {
    // + 0.0 turns −0 into 0: a page says 0, not -0.0.
    (x * per).round() / per + 0.0
}

/// The ground a move from `from` to `to` covers across the normal `n`, mm.
pub fn ground(from: [f64; 3], to: [f64; 3], n: [f32; 3]) -> f64 {
    let d = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
    let n = n.map(f64::from);
    let n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if n2 <= 0.0 {
        return len2.sqrt();
    }
    let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    (len2 - along * along / n2).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(rise: f32, height: f32) -> Point {
        Point {
            pos: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: height,
            speed: 10.0,
            power: 1000.0,
            powder: 10.0,
            defocus: 0.0,
            laser_on: true,
            style: 0,
            pitch: 2.0,
            rise,
        }
    }

    #[test]
    fn the_error_is_the_rise_over_the_height_and_none_unpredicted() {
        assert!((of(&point(1.02, 1.0)).unwrap() - 2.0).abs() < 1e-4);
        assert!((of(&point(0.45, 0.5)).unwrap() + 10.0).abs() < 1e-4);
        assert_eq!(of(&point(0.0, 1.0)), None);
        assert_eq!(of(&point(1.0, 0.0)), None);
    }

    #[test]
    fn layers_weigh_by_ground_and_add_their_means_up() {
        let mut l = Layers::default();
        l.begin();
        // 30 mm at +2 %, 10 mm at −2 %: mean +1 %, 0.01 mm over 1 mm.
        l.deposit(&point(1.02, 1.0), 30.0);
        l.deposit(&point(0.98, 1.0), 10.0);
        l.begin();
        l.deposit(&point(0.0, 1.0), 5.0);
        l.begin();
        l.deposit(&point(1.01, 1.0), 1.0);
        let out = l.finish();
        assert_eq!(out.len(), 3);
        let [mean, lo, hi, drift] = out[0].unwrap();
        assert!((mean - 1.0).abs() < 2e-3, "{mean}");
        assert!((lo + 2.0).abs() < 2e-3 && (hi - 2.0).abs() < 2e-3);
        assert!((drift - 0.01).abs() < 2e-4, "{drift}");
        assert_eq!(out[1], None, "nothing predicted on the second");
        assert!((out[2].unwrap()[3] - 0.02).abs() < 2e-4, "added up");
    }

    #[test]
    fn ground_leaves_out_the_climb_along_the_normal() {
        assert!((ground([0.0; 3], [3.0, 4.0, 5.0], [0.0, 0.0, 1.0]) - 5.0).abs() < 1e-12);
        assert!((ground([0.0; 3], [3.0, 4.0, 0.0], [0.0, 0.0, 2.0]) - 5.0).abs() < 1e-12);
    }
}

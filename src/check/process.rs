//! Rules every point of the IR must keep, whatever machine builds it: finite
//! numbers, unit directions, and — where the laser is on — the bead model's
//! layer heights and speeds and the laser's power range.

use super::rule::{ProgramCx, ProgramRule};
use crate::diag::message::{self, check::Layering, check::PointQuantity, check::Side};
use crate::diag::Diagnostics;
use crate::diag::Worst;
use crate::ir::{Point, Program};
use crate::plan::Where;
use crate::span::Span;
use crate::units::in_range;

/// Points with a value that is not a finite number.
#[derive(Default)]
pub(super) struct Finite {
    found: Option<Worst>,
}

impl Finite {
    /// Whether every value of `p` is finite (the other rules skip it if not).
    #[inline]
    pub fn point(&mut self, at: Where, p: &Point) -> bool {
        let vals = [
            p.pos[0],
            p.pos[1],
            p.pos[2],
            p.layer_height as f64,
            p.speed as f64,
            p.power as f64,
            p.powder as f64,
            p.defocus as f64,
        ];
        let ok = vals.iter().all(|v| v.is_finite())
            && p.normal.iter().chain(&p.tangent).all(|v| v.is_finite());
        if !ok {
            Worst::hit(&mut self.found, 0.0, 0.0, at);
        }
        ok
    }

    pub fn report(self, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(message::check::non_finite_points(&w));
    }
}

/// Directions (normal, tangent) that are not unit vectors.
#[derive(Default)]
pub(super) struct UnitDirections {
    found: Option<Worst>,
}

impl UnitDirections {
    #[inline]
    pub fn point(&mut self, at: Where, p: &Point) {
        for d in [p.normal, p.tangent] {
            let n2 = d.iter().map(|&c| (c as f64) * (c as f64)).sum::<f64>();
            // |n − 1| ≤ 1e-4 ⇔ |n² − 1| ≤ about 2e-4: no root unless it fails.
            if (n2 - 1.0).abs() > 2e-4 {
                Worst::hit(&mut self.found, n2.sqrt(), 1.0, at);
            }
        }
    }

    pub fn report(self, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(message::check::bad_directions(&w));
    }
}

/// A quantity of laser-on points that must stay in a declared range.
pub(super) struct Range {
    quantity: PointQuantity,
    range: [f64; 2],
    low: Option<Worst>,
    high: Option<Worst>,
}

impl Range {
    pub fn new(quantity: PointQuantity, range: [f64; 2]) -> Self {
        Range {
            quantity,
            range,
            low: None,
            high: None,
        }
    }

    #[inline]
    pub fn value(&mut self, v: f64, at: Where) {
        if !in_range(v, self.range) {
            self.miss(v, at);
        }
    }

    #[cold]
    fn miss(&mut self, v: f64, at: Where) {
        if v < self.range[0] {
            Worst::hit(&mut self.low, v, self.range[0], at);
        } else {
            Worst::hit(&mut self.high, v, self.range[1], at);
        }
    }

    /// One diagnostic per side that was passed, labelled at `spans` (the first
    /// declares the limit, the others produce the value).
    pub fn report(self, spans: &[Option<Span>], out: &mut Diagnostics) {
        for (w, side) in [(self.low, Side::Below), (self.high, Side::Above)] {
            if let Some(w) = w {
                out.push(message::check::point_out_of_range(
                    self.quantity,
                    side,
                    &w,
                    spans,
                ));
            }
        }
    }
}

/// The speed the bead model is checked at: the component of the point's
/// speed across its normal, `speed·|Δf − (Δf·n)n| / |Δf|` for the nozzle's
/// move `Δf` (focus to focus) to the next point. A bead map is measured on
/// flat tracks, and what sets a layer's thickness is the metal laid per
/// length across the build direction: a path that climbs along the normal
/// (seed 003's layers follow the planned top of the one below; seed 004's
/// nozzle climbs to the next segment's defocus over a transition) runs
/// `√(1 + s²)` faster than the ground it covers. For a move in the layer's
/// plane at one defocus — every planar and normal-sliced path — this is the
/// speed itself.
#[inline]
fn across_normal(pt: &Point, next: Option<&Point>) -> f64 {
    let v = pt.speed as f64;
    let Some(q) = next else { return v };
    let (a, b) = (pt.focus(), q.focus());
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let n = pt.normal.map(|c| c as f64);
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    // Along the normal's length squared: the rule for unit normals checks it.
    let n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if !(len2 > 0.0 && n2 > 0.0) {
        return v;
    }
    v * ((len2 - along * along / n2).max(0.0) / len2).sqrt()
}

/// How the plan's layers get their height, which decides what fixes a layer
/// height out of range.
fn layering(p: &Program) -> Layering {
    let o = &p.origins;
    if o.top.is_some() {
        Layering::Variable
    } else if o.spine.is_none() {
        // Planar layers have no spine: their height is the declared or derived lift.
        Layering::Planar
    } else {
        Layering::Bent
    }
}

/// `lmd::non-finite`, `lmd::bad-direction`, `lmd::point-height`,
/// `lmd::point-speed`, `lmd::point-power`: every rule over the IR's points,
/// run in one pass.
pub(super) struct ProcessRules {
    finite: Finite,
    units: UnitDirections,
    height: Range,
    speed: Range,
    power: Range,
}

impl ProgramRule for ProcessRules {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        let mut rules = ProcessRules::new(cx.program);
        rules.run(cx.program);
        rules.report(cx.program, out);
    }
}

impl ProcessRules {
    fn new(p: &Program) -> Self {
        let l = &p.limits;
        ProcessRules {
            finite: Finite::default(),
            units: UnitDirections::default(),
            // The height rule's layering is known once the origins are.
            height: Range::new(PointQuantity::Height(layering(p)), l.layer_height),
            speed: Range::new(PointQuantity::Speed, l.speed),
            power: Range::new(PointQuantity::Power, l.power),
        }
    }

    /// Checks every point of `p`.
    fn run(&mut self, p: &Program) {
        for (li, layer) in p.layers.iter().enumerate() {
            for (pi, path) in layer.paths.iter().enumerate() {
                let next = path.points.iter().skip(1).map(Some).chain([None]);
                for (k, (pt, next)) in path.points.iter().zip(next).enumerate() {
                    let at = Where::Point {
                        layer: li,
                        path: pi,
                        point: k,
                    };
                    if !self.finite.point(at, pt) {
                        continue;
                    }
                    self.units.point(at, pt);
                    if !pt.laser_on {
                        continue;
                    }
                    self.height.value(pt.layer_height as f64, at);
                    self.speed.value(across_normal(pt, next), at);
                    self.power.value(pt.power as f64, at);
                }
            }
        }
    }

    fn report(self, p: &Program, out: &mut Diagnostics) {
        let o = &p.origins;
        self.finite.report(out);
        self.units.report(out);
        self.height
            .report(&[o.bead_height, o.spine, o.top, o.slicing], out);
        self.speed.report(&[o.bead_speed], out);
        self.power.report(&[o.power], out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(pos: [f64; 3], speed: f32) -> Point {
        Point {
            pos,
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: 1.0,
            speed,
            power: 1000.0,
            powder: 12.0,
            defocus: 0.0,
            laser_on: true,
            style: 0,
        }
    }

    #[test]
    fn a_climbing_move_is_checked_at_the_speed_over_the_ground() {
        // A 3-4-5 climb: 5 mm of path per 4 mm of ground. At 10 mm/s along
        // the path the nozzle crosses the ground at 8 mm/s.
        let a = point([0.0, 0.0, 0.0], 10.0);
        let b = point([4.0, 0.0, 3.0], 10.0);
        assert!((across_normal(&a, Some(&b)) - 8.0).abs() < 1e-6);
        // In the layer's plane (every planar and normal-sliced move) it is
        // the speed itself; so is a last point, which has no move.
        let c = point([4.0, 3.0, 0.0], 10.0);
        assert_eq!(across_normal(&a, Some(&c)), 10.0);
        assert_eq!(across_normal(&a, None), 10.0);
        // A tilted normal: the move in the plane normal to it is unchanged.
        let mut t = point([0.0, 0.0, 0.0], 6.0);
        let s = std::f32::consts::FRAC_1_SQRT_2;
        t.normal = [s, 0.0, s];
        let u = point([-1.0, 2.0, 1.0], 6.0);
        assert!((across_normal(&t, Some(&u)) - 6.0).abs() < 1e-5);
    }
}

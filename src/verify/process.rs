//! Rules every point of the IR must keep, whatever machine builds it: finite
//! numbers, unit directions, and — where the laser is on — the bead model's
//! layer heights and speeds and the laser's power range.

use super::rule::{ProgramCx, ProgramRule, Worst};
use crate::diag::message::{self, verify::Layering, verify::PointQuantity, verify::Side};
use crate::diag::Diagnostic;
use crate::diag::Diagnostics;
use crate::ir::{PathKind, Point, Program};
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
        out.push(message::verify::non_finite_points(&w));
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
        out.push(message::verify::bad_directions(&w));
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
        self.report_with(spans, out, |_, _, d| d);
    }

    /// [`Range::report`], each diagnostic passed through `amend` with its
    /// side and worst point (to say more about why it is off).
    pub fn report_with(
        self,
        spans: &[Option<Span>],
        out: &mut Diagnostics,
        amend: impl Fn(Side, &Worst, Diagnostic) -> Diagnostic,
    ) {
        for (w, side) in [(self.low, Side::Below), (self.high, Side::Above)] {
            if let Some(w) = w {
                let d = message::verify::point_out_of_range(self.quantity, side, &w, spans);
                out.push(amend(side, &w, d));
            }
        }
    }
}

/// The bead's width, if the point at `at` is a contour's laid as a lone
/// bead: filling a strip the bead's width (to 1 %), no neighbour within a
/// bead on either side.
fn lone_contour(p: &Program, at: Where) -> Option<f64> {
    let Where::Point { layer, path, point } = at else {
        return None;
    };
    let width = p.bead.as_ref()?.width;
    let path = p.layers.get(layer)?.paths.get(path)?;
    let pitch = f64::from(path.points.get(point)?.pitch);
    (path.kind == PathKind::Contour && pitch >= 0.99 * width).then_some(width)
}

/// How the plan's layers get their height, which decides what fixes a layer
/// height out of range.
fn layering(p: &Program) -> Layering {
    let o = &p.origins;
    if p.continuous && p.ring.is_none() {
        // A program in one run that is no ring: a spiral wall.
        Layering::Spiral
    } else if o.top.is_some() {
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
                    self.speed.value(pt.speed_across(next), at);
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
        let planar = layering(p) == Layering::Planar;
        self.speed.report_with(&[o.bead_speed], out, |side, w, d| {
            match lone_contour(p, w.at) {
                Some(width) if planar && side == Side::Below => {
                    message::verify::lone_contour(d, width, w.value)
                }
                _ => d,
            }
        });
        self.power.report(&[o.power], out);
    }
}

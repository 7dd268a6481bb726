//! Rules every point of the IR must keep, whatever machine builds it: finite
//! numbers, unit directions, and — where the laser is on — the bead model's
//! layer heights and speeds and the laser's power range.

use super::worst::{plural, Worst};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::{Point, Program};
use crate::plan::Where;
use crate::span::Span;
use crate::units::{in_range, short};

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

    /// Whether any point failed.
    pub fn failed(&self) -> bool {
        self.found.is_some()
    }

    pub fn report(self, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(
            Diagnostic::error(
                Code::NonFinite,
                format!(
                    "{} point{} carry a value that is not a finite number (first at {})",
                    w.count,
                    plural(w.count),
                    w.at
                ),
            )
            .help(
                "this is a bug in lmdc's geometry for this input; please report it with the .lmd file",
            ),
        );
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
            let n = d
                .iter()
                .map(|&c| (c as f64) * (c as f64))
                .sum::<f64>()
                .sqrt();
            if (n - 1.0).abs() > 1e-4 {
                Worst::hit(&mut self.found, n, 1.0, at);
            }
        }
    }

    pub fn report(self, out: &mut Diagnostics) {
        let Some(w) = self.found else { return };
        out.push(
            Diagnostic::error(
                Code::BadDirection,
                format!(
                    "{} direction{} that are not unit vectors: the worst has length {} at {}",
                    w.count,
                    plural(w.count),
                    short(w.value),
                    w.at
                ),
            )
            .help("this is a bug in lmdc's geometry; please report it with the .lmd file"),
        );
    }
}

/// A quantity of laser-on points that must stay in a declared range.
pub(super) struct Range {
    code: Code,
    /// What the quantity is, for "a layer height below h_min".
    below: &'static str,
    above: &'static str,
    unit: &'static str,
    range: [f64; 2],
    low: Option<Worst>,
    high: Option<Worst>,
}

impl Range {
    pub fn new(
        code: Code,
        below: &'static str,
        above: &'static str,
        unit: &'static str,
        range: [f64; 2],
    ) -> Self {
        Range {
            code,
            below,
            above,
            unit,
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
    pub fn report(
        self,
        spans: &[Option<Span>],
        help_low: &str,
        help_high: &str,
        out: &mut Diagnostics,
    ) {
        for (w, what, help) in [
            (self.low, self.below, help_low),
            (self.high, self.above, help_high),
        ] {
            let Some(w) = w else { continue };
            let unit = self.unit;
            let mut d = Diagnostic::error(
                self.code,
                format!(
                    "{} point{} with a {what}: the worst is {} {unit} (limit {} {unit}) at {}",
                    w.count,
                    plural(w.count),
                    short(w.value),
                    short(w.limit),
                    w.at
                ),
            )
            .help(help.to_string());
            for (i, s) in spans.iter().enumerate() {
                d = d.label_opt(
                    *s,
                    if i == 0 {
                        "limit declared here"
                    } else {
                        "this produces it"
                    },
                );
            }
            out.push(d);
        }
    }
}

/// Every process rule, run over the IR's points in one pass.
pub(super) struct ProcessRules {
    pub finite: Finite,
    units: UnitDirections,
    height: Range,
    speed: Range,
    power: Range,
}

impl ProcessRules {
    pub fn new(p: &Program) -> Self {
        let l = &p.limits;
        ProcessRules {
            finite: Finite::default(),
            units: UnitDirections::default(),
            height: Range::new(
                Code::PointHeight,
                "layer height below h_min",
                "layer height above h_max",
                "mm",
                l.layer_height,
            ),
            speed: Range::new(
                Code::PointSpeed,
                "speed below the bead model's range",
                "speed above the bead model's range",
                "mm/s",
                l.speed,
            ),
            power: Range::new(
                Code::PointPower,
                "power below the laser's range",
                "power above the laser's range",
                "W",
                l.power,
            ),
        }
    }

    /// Checks every point of `p`.
    pub fn run(&mut self, p: &Program) {
        for (li, layer) in p.layers.iter().enumerate() {
            for (pi, path) in layer.paths.iter().enumerate() {
                for (k, pt) in path.points.iter().enumerate() {
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
                    self.speed.value(pt.speed as f64, at);
                    self.power.value(pt.power as f64, at);
                }
            }
        }
    }

    pub fn report(self, p: &Program, out: &mut Diagnostics) {
        let o = &p.origins;
        self.finite.report(out);
        self.units.report(out);
        let geom = [o.bead_height, o.spine, o.slicing];
        // Planar layers have no spine: their height is the declared or derived lift.
        let planar = "a flat layer rises by what its tracks lay (A/w for one track, A/d for tracks d apart): `layer_height = auto` derives it, or declare one within the bead's heights";
        let (low, high) = if o.spine.is_none() {
            (planar, planar)
        } else {
            (
                "use more layers' worth of height per layer (fewer layers), a larger bend radius, or a bead model that reaches lower heights",
                "use more layers, a larger bend radius, or a bead model that reaches higher beads",
            )
        };
        self.height.report(&geom, low, high, out);
        self.speed.report(
            &[o.bead_speed],
            "the bead model is not valid this slow: widen its speed range if the process allows",
            "the bead model is not valid this fast: widen its speed range if the process allows",
            out,
        );
        self.power.report(
            &[o.power],
            "raise the power schedule into the laser's range",
            "lower the power schedule into the laser's range",
            out,
        );
    }
}

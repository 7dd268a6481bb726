//! The top surface `H(x, y)` evaluated at points of the footprint: a plane
//! (`plane(…)`, `edges(…)`) in closed form, any other expression through the
//! checker's evaluator. A point where the top is not a positive length is
//! reported with the point, and with the inner error when there is one (a
//! division by zero there).
//!
//! On a scan (`on = scan(…)`, docs/repair.md) the layers stack the
//! thickness between the scanned surface `B(x, y)` and the top: [`Surface::at`]
//! gives `H − B` (the slicer's emitter adds `B` back to place the layers). A
//! point the scan does not cover, or where the top is not above it, is
//! reported as such (`lmd::scan-coverage`).

use crate::diag::message::{self, top::BadTop, top::TopAt};
use crate::diag::Diagnostics;
use crate::geometry::mesh::highest::Highest;
use crate::geometry::scan::HeightField;
use crate::geometry::target::Target;
use crate::sema::model::{Axis, Top, TopExtrusion};
use crate::sema::TopHeights;

/// The most inside tests of a target solid one pass over the footprint
/// makes ([`Surface::most_samples`]): some seconds.
pub const LINE_WORK: f64 = 1e7;

/// How far off a sampled point a gap under the target is tested, mm.
const NUDGE: f64 = 1e-4;

/// The top, ready to evaluate, over its base.
pub struct Surface<'m> {
    /// The top's form.
    pub form: Form<'m>,
    /// What the layers start on.
    base: Base<'m>,
    /// The extrusion, read for whether its target contains the scan.
    ex: &'m TopExtrusion,
    /// Whether its target contains the scan (the part as designed), once
    /// asked ([`super::underside::holds_scan`]).
    holds: Option<bool>,
}

/// What a variable solid's layers start on.
#[derive(Clone, Copy, Debug)]
pub enum Base<'m> {
    /// The plate, at z = 0.
    Plate,
    /// The scanned surface a repair builds on.
    Scan(&'m HeightField),
    /// A level the levelling passes left (`level = …`), mm.
    Level(f64),
}

impl<'m> Base<'m> {
    /// `ex`'s base: its scan, or the plate; or the level `z` when given.
    pub fn of(ex: &'m TopExtrusion, level: Option<f64>) -> Self {
        match (level, &ex.base) {
            (Some(z), _) => Base::Level(z),
            (None, Some(b)) => Base::Scan(&b.surface),
            (None, None) => Base::Plate,
        }
    }

    /// Its height at `p`, mm, where it has one.
    pub fn at(self, p: [f64; 2]) -> Option<f64> {
        match self {
            Base::Plate => Some(0.0),
            Base::Scan(s) => s.at(p),
            Base::Level(z) => Some(z),
        }
    }
}

/// How the top is written.
pub enum Form<'m> {
    /// `h0 + sx·x + sy·y`.
    Plane {
        /// Height at the origin, mm.
        h0: f64,
        /// Rise per unit of x and of y.
        slope: [f64; 2],
    },
    /// An expression of `x` and `y`.
    Expr(TopHeights<'m>),
    /// A target mesh's highest face.
    Mesh(&'m Highest),
    /// A target solid's highest surface.
    Solid(&'m Target),
}

impl<'m> Surface<'m> {
    /// The top of `ex` over a footprint whose written extent along an axis
    /// is `extent(axis)` (the extreme edges `edges(…)` refers to).
    pub fn new(ex: &'m TopExtrusion, extent: impl Fn(Axis) -> [f64; 2]) -> Self {
        Self::over(ex, extent, Base::of(ex, None))
    }

    /// The top of `ex` over `base`.
    pub fn over(ex: &'m TopExtrusion, extent: impl Fn(Axis) -> [f64; 2], base: Base<'m>) -> Self {
        Surface {
            form: Form::of(&ex.top, extent),
            base,
            ex,
            holds: None,
        }
    }

    /// How many points a pass over the footprint may evaluate, `most` for
    /// a top that is cheap at a point: fewer for a target solid walked
    /// down each line ([`Target::line_samples`]), so that a pass tests its
    /// inside at most [`LINE_WORK`] times (a tall loft over a large
    /// footprint is sampled more coarsely rather than for hours).
    pub fn most_samples(&self, most: f64) -> f64 {
        match self.form {
            Form::Solid(t) => most.min(LINE_WORK / t.line_samples()),
            _ => most,
        }
    }

    /// The thickness to lay at `p` (the top over the plate, or over the
    /// scan): a positive, finite height, or why not.
    pub fn at(&mut self, p: [f64; 2]) -> Result<f64, Bad> {
        let base = match self.base {
            Base::Plate => None,
            b => Some(b.at(p)),
        };
        // A solid's crossings above the base start with its top (one walk
        // down a loft, not two).
        let crossings = match (&self.form, base) {
            (Form::Mesh(m), Some(Some(b))) => m.crossings_above(p, b),
            (Form::Solid(t), Some(Some(b))) => t.crossings_above(p, b),
            _ => Vec::new(),
        };
        let h = match (&self.form, crossings.first()) {
            (Form::Solid(_), Some(&h)) if h > 0.0 && h.is_finite() => h,
            _ => self.form.at(p)?,
        };
        let Some(base) = base else {
            return Ok(h);
        };
        let Some(b) = base else {
            return Err(Bad::new(p, Why::Uncovered));
        };
        // Down from the top the ray leaves the part and enters it again
        // above the base: an overhang (or a cavity) the layers, laid from
        // above, would fill. Two crossings are a target whose underside
        // stands over the scan: over the wear, for a target of the added
        // metal alone, filled down to the scan as meant; over air beside
        // the part, for a target that contains the scanned part (module
        // `underside`), an overhang too.
        let overhang = match crossings[..] {
            [_, under, _, ..] => Some(under),
            [_, under] if self.holds() && self.air([p[0], p[1], (under + b) / 2.0]) => Some(under),
            _ => None,
        };
        if let Some(under) = overhang {
            return Err(Bad::new(
                p,
                Why::Undercut {
                    top: h,
                    under,
                    surface: b,
                },
            ));
        }
        if h - b > 0.0 && (h - b).is_finite() {
            Ok(h - b)
        } else {
            Err(Bad::new(p, Why::Below { top: h, surface: b }))
        }
    }
}

impl Surface<'_> {
    /// Whether `q` (mm), in a gap the crossings over it show, is outside
    /// the target, tested a hair off it: a line through the corner where
    /// one face of the target meets another (a wall on a block) counts the
    /// corner once, a gap that is not there.
    fn air(&self, q: [f64; 3]) -> bool {
        !self
            .ex
            .top
            .contains([q[0] + NUDGE, q[1] + NUDGE * 0.618, q[2]])
    }

    /// Whether the target contains the scanned part, read once.
    fn holds(&mut self) -> bool {
        let ex = self.ex;
        *self
            .holds
            .get_or_insert_with(|| super::underside::holds_scan(ex).is_some())
    }
}

impl<'m> Form<'m> {
    /// `top` ready to evaluate, over a footprint or path whose written
    /// extent along an axis is `extent(axis)` (the extreme edges
    /// `edges(…)` refers to).
    pub fn of(top: &'m Top, extent: impl Fn(Axis) -> [f64; 2]) -> Self {
        match top {
            Top::Plane { at, height, slope } => Form::Plane {
                h0: height.0 - slope[0] * at[0].0 - slope[1] * at[1].0,
                slope: *slope,
            },
            Top::Edges { along, from, to } => {
                let [lo, hi] = extent(*along);
                let k = if hi > lo {
                    (to.0 - from.0) / (hi - lo)
                } else {
                    0.0
                };
                let slope = match along {
                    Axis::X => [k, 0.0],
                    Axis::Y => [0.0, k],
                };
                Form::Plane {
                    h0: from.0 - k * lo,
                    slope,
                }
            }
            Top::Expr(e) => Form::Expr(e.evaluator()),
            Top::Mesh(m) => Form::Mesh(&m.surface),
            Top::Solid(t) => Form::Solid(&t.surface),
        }
    }

    /// The top at `p`: a positive, finite height, or why not.
    pub fn at(&mut self, p: [f64; 2]) -> Result<f64, Bad> {
        let (h, inner) = match self {
            Form::Plane { h0, slope } => (Some(*h0 + slope[0] * p[0] + slope[1] * p[1]), None),
            Form::Expr(e) => {
                let mut d = Diagnostics::new();
                let h = e.at(p[0], p[1], &mut d).map(|l| l.0);
                (h.filter(|_| !d.has_errors()), Some(d))
            }
            Form::Mesh(m) => {
                let Some(h) = m.at(p) else {
                    return Err(Bad::new(p, Why::OffTarget));
                };
                (Some(h), None)
            }
            Form::Solid(t) => {
                let Some(h) = t.at(p) else {
                    return Err(Bad::new(p, Why::OffTarget));
                };
                (Some(h), None)
            }
        };
        match h {
            Some(h) if h.is_finite() && h > 0.0 => Ok(h),
            _ => Err(Bad::new(
                p,
                Why::Top {
                    value: h,
                    inner: inner.unwrap_or_default(),
                },
            )),
        }
    }
}

/// A point of the footprint where there is no positive height to lay.
#[derive(Debug)]
pub struct Bad {
    /// Where, mm.
    pub at: [f64; 2],
    /// Why.
    pub why: Why,
}

/// Why a point has no height to lay.
#[derive(Debug)]
pub enum Why {
    /// The top is not a positive length there.
    Top {
        /// The value there, if it could be computed.
        value: Option<f64>,
        /// Why it could not be, if not.
        inner: Diagnostics,
    },
    /// The scan has no point there.
    Uncovered,
    /// The target mesh has no face over it.
    OffTarget,
    /// The target mesh has a face under its top and above the base there:
    /// an overhang the layers, laid from above, cannot leave open.
    Undercut {
        /// The top, mm.
        top: f64,
        /// The highest face under it, mm.
        under: f64,
        /// The base, mm.
        surface: f64,
    },
    /// The top is not above the scanned surface there.
    Below {
        /// The top, mm.
        top: f64,
        /// The scanned surface, mm.
        surface: f64,
    },
}

impl Bad {
    fn new(at: [f64; 2], why: Why) -> Self {
        Bad { at, why }
    }

    /// The diagnostics of the first bad point, `more` other points counted.
    pub fn report(self, ex: &TopExtrusion, more: usize) -> Diagnostics {
        let mut out = Diagnostics::new();
        let (value, inner) = match self.why {
            Why::Top { value, inner } => (value, Some(inner)),
            Why::Undercut {
                top,
                under,
                surface,
            } => {
                // Planned turned, the fill is along its direction already.
                let reach = match ex.turned {
                    Some(_) => None,
                    None => super::undercut::least_tilt(ex, self.at, under, top),
                };
                out.push(message::top::undercut(
                    self.at,
                    [top, under, surface],
                    more,
                    solid_name(&ex.top),
                    ex.top_span,
                    reach,
                    ex.turned.as_ref(),
                ));
                return out;
            }
            Why::OffTarget => (None, None),
            Why::Uncovered => {
                if let Some(b) = &ex.base {
                    out.push(message::scan::uncovered(
                        self.at,
                        more,
                        &b.surface,
                        ex.shape_span,
                        b.span,
                        ex.turned.as_ref(),
                    ));
                }
                return out;
            }
            Why::Below { top, surface } => {
                if let Some(b) = &ex.base {
                    out.push(message::scan::top_below(
                        self.at,
                        top,
                        surface,
                        more,
                        [ex.top_span, b.span],
                        ex.turned.as_ref(),
                    ));
                }
                return out;
            }
        };
        let at = TopAt {
            top: ex.top_span,
            shape: ex.shape_span,
            what: "footprint",
            turned: ex.turned.as_ref(),
        };
        out.extend(top_fault(
            self.at,
            (value, inner),
            more,
            solid_name(&ex.top),
            at,
        ));
        out
    }

    /// The diagnostics of a point where the top itself has no height (the
    /// faults of [`Form::at`]), `more` other points counted; `None` for a
    /// fault of the base.
    pub fn top_fault(self, more: usize, top: &Top, at: TopAt<'_>) -> Option<Diagnostics> {
        let (value, inner) = match self.why {
            Why::Top { value, inner } => (value, Some(inner)),
            Why::OffTarget => (None, None),
            _ => return None,
        };
        Some(top_fault(
            self.at,
            (value, inner),
            more,
            solid_name(top),
            at,
        ))
    }
}

/// The diagnostics of the top's value (or what failed) at `p`.
fn top_fault(
    p: [f64; 2],
    (value, inner): (Option<f64>, Option<Diagnostics>),
    more: usize,
    solid: Option<&str>,
    at: TopAt<'_>,
) -> Diagnostics {
    let bad = match (value, &inner) {
        (Some(h), _) if h.is_finite() => BadTop::NotPositive(h),
        (Some(_), _) => BadTop::NotFinite,
        (None, Some(_)) => BadTop::Failed,
        (None, None) => match solid {
            Some(name) => BadTop::OffSolid(name.to_string()),
            None => BadTop::OffTarget,
        },
    };
    let inner = inner.unwrap_or_default();
    let mut out = Diagnostics::new();
    out.push(message::top::bad_top(p, more, bad, inner.has_errors(), at));
    out.extend(inner);
    out
}

/// The target solid's name, when the top is one.
fn solid_name(top: &Top) -> Option<&str> {
    match top {
        Top::Solid(t) => Some(&t.name),
        _ => None,
    }
}

//! The top surface `H(x, y)` evaluated at points of the footprint: a plane
//! (`plane(…)`, `edges(…)`) in closed form, any other expression through the
//! checker's evaluator. A point where the top is not a positive length is
//! reported with the point, and with the inner error when there is one (a
//! division by zero there).

use crate::diag::message::{self, top::BadTop, top::TopAt};
use crate::diag::Diagnostics;
use crate::sema::model::{Axis, Top, TopExtrusion};
use crate::sema::TopHeights;

/// The top, ready to evaluate.
pub enum Surface<'m> {
    /// `h0 + sx·x + sy·y`.
    Plane {
        /// Height at the origin, mm.
        h0: f64,
        /// Rise per unit of x and of y.
        slope: [f64; 2],
    },
    /// An expression of `x` and `y`.
    Expr(TopHeights<'m>),
}

impl<'m> Surface<'m> {
    /// The top of `ex` over a footprint whose written extent along an axis
    /// is `extent(axis)` (the extreme edges `edges(…)` refers to).
    pub fn new(ex: &'m TopExtrusion, extent: impl Fn(Axis) -> [f64; 2]) -> Self {
        match &ex.top {
            Top::Plane { at, height, slope } => Surface::Plane {
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
                Surface::Plane {
                    h0: from.0 - k * lo,
                    slope,
                }
            }
            Top::Expr(e) => Surface::Expr(e.evaluator()),
        }
    }

    /// The top at `p`: a positive, finite height, or why not.
    pub fn at(&mut self, p: [f64; 2]) -> Result<f64, Bad> {
        let (h, inner) = match self {
            Surface::Plane { h0, slope } => (Some(*h0 + slope[0] * p[0] + slope[1] * p[1]), None),
            Surface::Expr(e) => {
                let mut d = Diagnostics::new();
                let h = e.at(p[0], p[1], &mut d).map(|l| l.0);
                (h.filter(|_| !d.has_errors()), Some(d))
            }
        };
        match h {
            Some(h) if h.is_finite() && h > 0.0 => Ok(h),
            _ => Err(Bad {
                at: p,
                value: h,
                inner: inner.unwrap_or_default(),
            }),
        }
    }
}

/// A point of the footprint where the top is not a positive height.
#[derive(Debug)]
pub struct Bad {
    /// Where, mm.
    pub at: [f64; 2],
    /// The value there, if it could be computed.
    pub value: Option<f64>,
    /// Why it could not be, if not.
    pub inner: Diagnostics,
}

impl Bad {
    /// The diagnostics of the first bad point, `more` other points counted.
    pub fn report(self, ex: &TopExtrusion, more: usize) -> Diagnostics {
        let bad = match self.value {
            Some(h) if h.is_finite() => BadTop::NotPositive(h),
            Some(_) => BadTop::NotFinite,
            None => BadTop::Failed,
        };
        let at = TopAt {
            top: ex.top_span,
            shape: ex.shape_span,
        };
        let mut out = Diagnostics::new();
        out.push(message::top::bad_top(
            self.at,
            more,
            bad,
            self.inner.has_errors(),
            at,
        ));
        out.extend(self.inner);
        out
    }
}

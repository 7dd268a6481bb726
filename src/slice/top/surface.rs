//! The top surface `H(x, y)` evaluated at points of the footprint: a plane
//! (`plane(…)`, `edges(…)`) in closed form, any other expression through the
//! checker's evaluator. A point where the top is not a positive length is
//! reported with the point, and with the inner error when there is one (a
//! division by zero there).

use super::footprint::Footprint;
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::sema::model::{Axis, Top, TopExtrusion};
use crate::sema::TopHeights;
use crate::units::{short, Length};

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
    /// The top of `ex` over `footprint` (whose extreme edges `edges(…)`
    /// refers to).
    pub fn new(ex: &'m TopExtrusion, footprint: &Footprint) -> Self {
        match &ex.top {
            Top::Plane { at, height, slope } => Surface::Plane {
                h0: height.0 - slope[0] * at[0].0 - slope[1] * at[1].0,
                slope: *slope,
            },
            Top::Edges { along, from, to } => {
                let [lo, hi] = footprint.written_extent(*along);
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
        let (x, y) = (short(self.at[0]), short(self.at[1]));
        let others = match more {
            0 => String::new(),
            1 => " (and at 1 other point sampled)".to_string(),
            n => format!(" (and at {n} other points sampled)"),
        };
        let message = match self.value {
            Some(h) if h.is_finite() => format!(
                "the top is {} at ({x}, {y}) mm, where a track runs{others}: every deposited point needs a height above the substrate",
                Length(h)
            ),
            Some(_) => format!("the top is not a finite number at ({x}, {y}) mm{others}"),
            None => format!("the top cannot be computed at ({x}, {y}) mm{others}"),
        };
        let help = if self.inner.has_errors() {
            "the top is the finished part's height above the substrate, computed at every point a track runs through: the error below says what failed there"
        } else {
            "the top is the finished part's height above the substrate: make it positive over the whole footprint"
        };
        let mut out = Diagnostics::new();
        out.push(
            Diagnostic::error(Code::TopHeight, message)
                .label(ex.top_span, "the top")
                .label(ex.shape_span, "the footprint")
                .help(help),
        );
        out.extend(self.inner);
        out
    }
}

//! Why a layer cannot be filled: the data of each reason. The words
//! ("layer 3 cannot be filled: …") are in [`crate::diag::message::fill`].

use crate::geometry::region::Fault;

/// Why [`fill`](super::fill) failed.
#[derive(Debug)]
pub enum FillError {
    /// The outline crosses or touches itself.
    SelfIntersecting {
        /// A point where it does.
        at: [f64; 2],
    },
    /// A hole crosses, touches or lies outside the outline, or another hole.
    Region(Fault),
    /// No track results at all.
    Empty,
    /// A coordinate or setting is NaN or infinite.
    NonFinite,
    /// A setting or the outline's size is outside what makes sense.
    OutOfRange(BadValue),
    /// The raster would need too many lines.
    TooManyLines(Count),
    /// Too many contour passes.
    TooManyContours(Count),
    /// The layer would have too many points.
    TooManyPoints(Count),
}

/// A value outside its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BadValue {
    /// What it is, e.g. "the raster offset".
    pub what: &'static str,
    /// Its value (infinite when it overflowed).
    pub value: f64,
    /// What follows the number, e.g. " mm".
    pub unit: &'static str,
    /// The rule, e.g. "more than 0 mm".
    pub expected: &'static str,
}

/// How many of something were needed, and the most allowed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    /// Needed (for points an estimate: they are counted only until the
    /// limit is passed).
    pub wanted: u64,
    /// Allowed.
    pub max: u64,
}

//! Why a layer cannot be filled, worded for the process engineer who reads
//! it as "layer 3 cannot be filled: …". All the wording is here.

use crate::geometry::region::Fault;
use std::fmt;

/// Why [`fill`](super::fill) failed.
#[derive(Debug, thiserror::Error)]
pub enum FillError {
    /// The outline crosses or touches itself.
    #[error(
        "the outline crosses or touches itself near x = {} mm, y = {} mm",
        num(at[0]),
        num(at[1])
    )]
    SelfIntersecting {
        /// A point where it does.
        at: [f64; 2],
    },
    /// A hole crosses, touches or lies outside the outline, or another hole.
    #[error("{}", region(.0))]
    Region(Fault),
    /// No track results at all.
    #[error(
        "nothing is left to fill: the outline encloses no room for a track once the inset and contour passes are taken off"
    )]
    Empty,
    /// A coordinate or setting is NaN or infinite.
    #[error("a coordinate of the outline or a fill setting is not a number (NaN or infinite)")]
    NonFinite,
    /// A setting or the outline's size is outside what makes sense.
    #[error("{0}")]
    OutOfRange(Invalid),
    /// The raster would need too many lines.
    #[error(
        "the raster needs {} lines, more than the {} a layer may have: use a larger raster offset",
        .0.wanted,
        .0.max
    )]
    TooManyLines(Count),
    /// Too many contour passes.
    #[error(
        "{} contour passes are more than the {} allowed for this outline (the more pieces an outline has, the fewer passes)",
        .0.wanted,
        .0.max
    )]
    TooManyContours(Count),
    /// The layer would have too many points.
    #[error(
        "the layer would need about {} points, more than the {} allowed: use a larger offset or chord error",
        .0.wanted,
        .0.max
    )]
    TooManyPoints(Count),
}

/// A region's fault in words; holes count from 1, as the user lists them.
fn region(f: &Fault) -> String {
    let at = |p: &[f64; 2]| format!("x = {} mm, y = {} mm", num(p[0]), num(p[1]));
    match f {
        Fault::Outline { at: p } => {
            format!("the outline crosses or touches itself near {}", at(p))
        }
        Fault::HoleItself { hole, at: p } => {
            format!("hole {} crosses or touches itself near {}", hole + 1, at(p))
        }
        Fault::HoleOutline { hole, at: p } => format!(
            "hole {} crosses or touches the outline near {}",
            hole + 1,
            at(p)
        ),
        Fault::HoleOutside { hole } => format!("hole {} lies outside the outline", hole + 1),
        Fault::Holes { hole, other, at: p } => format!(
            "holes {} and {} cross or touch near {}",
            hole + 1,
            other + 1,
            at(p)
        ),
        Fault::HoleInHole { hole, other } => {
            format!("hole {} lies inside hole {}", hole + 1, other + 1)
        }
    }
}

/// A value outside its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Invalid {
    /// What it is, e.g. "the raster offset".
    pub what: &'static str,
    /// Its value (infinite when it overflowed).
    pub value: f64,
    /// What follows the number, e.g. " mm".
    pub unit: &'static str,
    /// The rule, e.g. "more than 0 mm".
    pub expected: &'static str,
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.value.is_finite() {
            write!(f, "{} is {}{}", self.what, num(self.value), self.unit)?;
        } else {
            write!(f, "{} is too large", self.what)?;
        }
        write!(f, "; it must be {}", self.expected)
    }
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

/// A number as an engineer writes it: up to 4 decimals, or in exponent form
/// when very large or small (a plain `{}` would print 1e300 with 300 zeros).
fn num(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-4..1e7).contains(&a) {
        format!("{v:e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".to_string()
        } else {
            s.to_string()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_read_well() {
        let e = FillError::SelfIntersecting { at: [1.0, 2.5] };
        assert_eq!(
            e.to_string(),
            "the outline crosses or touches itself near x = 1 mm, y = 2.5 mm"
        );
        let e = FillError::OutOfRange(Invalid {
            what: "the raster offset",
            value: 0.0,
            unit: " mm",
            expected: "more than 0 mm",
        });
        assert_eq!(
            e.to_string(),
            "the raster offset is 0 mm; it must be more than 0 mm"
        );
        let e = FillError::OutOfRange(Invalid {
            what: "the inset",
            value: -1e300,
            unit: " mm",
            expected: "at least 0 mm",
        });
        assert_eq!(
            e.to_string(),
            "the inset is -1e300 mm; it must be at least 0 mm"
        );
        let e = FillError::TooManyLines(Count {
            wanted: 250_000,
            max: 100_000,
        });
        assert_eq!(
            e.to_string(),
            "the raster needs 250000 lines, more than the 100000 a layer may have: use a larger raster offset"
        );
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.23456789), "1.2346");
        assert_eq!(num(-0.00001), "-1e-5");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(1600.0), "1600");
    }
}

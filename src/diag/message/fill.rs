//! Why a layer cannot be filled, in words: the fill's errors as a process
//! engineer reads them after "layer 3 cannot be filled: ".

use crate::fill::{BadValue, FillError};
use crate::geometry::region::Fault;
use std::fmt;

impl fmt::Display for FillError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FillError::SelfIntersecting { at } => write!(
                f,
                "the outline crosses or touches itself near x = {} mm, y = {} mm",
                num(at[0]),
                num(at[1])
            ),
            FillError::Region(fault) => f.write_str(&region(fault)),
            FillError::Empty => f.write_str(
                "nothing is left to fill: the outline encloses no room for a track once the inset and contour passes are taken off",
            ),
            FillError::NonFinite => f.write_str(
                "a coordinate of the outline or a fill setting is not a number (NaN or infinite)",
            ),
            FillError::OutOfRange(e) => write!(f, "{e}"),
            FillError::TooManyLines(c) => write!(
                f,
                "the raster needs {} lines, more than the {} a layer may have: use a larger raster offset",
                c.wanted, c.max
            ),
            FillError::TooManyContours(c) => write!(
                f,
                "{} contour passes are more than the {} allowed for this outline (the more pieces an outline has, the fewer passes)",
                c.wanted, c.max
            ),
            FillError::TooManyPoints(c) => write!(
                f,
                "the layer would need about {} points, more than the {} allowed: use a larger offset or chord error",
                c.wanted, c.max
            ),
        }
    }
}

impl std::error::Error for FillError {}

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

impl fmt::Display for BadValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.value.is_finite() {
            write!(f, "{} is {}{}", self.what, num(self.value), self.unit)?;
        } else {
            write!(f, "{} is too large", self.what)?;
        }
        write!(f, "; it must be {}", self.expected)
    }
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
    use crate::fill::Count;

    #[test]
    fn messages_read_well() {
        let e = FillError::SelfIntersecting { at: [1.0, 2.5] };
        assert_eq!(
            e.to_string(),
            "the outline crosses or touches itself near x = 1 mm, y = 2.5 mm"
        );
        let e = FillError::OutOfRange(BadValue {
            what: "the raster offset",
            value: 0.0,
            unit: " mm",
            expected: "more than 0 mm",
        });
        assert_eq!(
            e.to_string(),
            "the raster offset is 0 mm; it must be more than 0 mm"
        );
        let e = FillError::OutOfRange(BadValue {
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

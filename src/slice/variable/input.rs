//! Checked inputs. A [`Positive`] length cannot be zero, negative or NaN; a
//! [`HeightRange`] cannot be empty or reversed. The functions of this module
//! take these, so the maths after the boundary needs no guards.

use super::SLACK;
pub(crate) use crate::invalid::finite;
pub use crate::invalid::Invalid;
use crate::units::Length;

/// A finite length greater than zero: a bead width, a footprint width, a
/// minimum segment length, a height tolerance.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Positive(Length);

impl Positive {
    /// Checks `v`; `what` names it in the error.
    pub fn new(what: &'static str, v: Length) -> Result<Self, Invalid> {
        let x = finite(what, v.0)?;
        if x > 0.0 {
            Ok(Positive(v))
        } else {
            Err(Invalid::NotPositive { what, value: x })
        }
    }

    /// The length.
    pub fn get(self) -> Length {
        self.0
    }

    /// In mm.
    pub fn mm(self) -> f64 {
        self.0 .0
    }
}

/// Heights from `low` to `high`, `0 < low ≤ high`, all finite: the heights a
/// bead map lays (`h_min .. h_max`) or the heights a top needs over every
/// deposited point (`H_min .. H_max`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightRange {
    low: Length,
    high: Length,
}

impl HeightRange {
    /// Checks the ends; `what` names the range in the error.
    pub fn new(what: &'static str, low: Length, high: Length) -> Result<Self, Invalid> {
        let lo = Positive::new(what, low)?.mm();
        let hi = Positive::new(what, high)?.mm();
        if lo > hi {
            return Err(Invalid::Reversed {
                what,
                low: lo,
                high: hi,
            });
        }
        Ok(HeightRange { low, high })
    }

    /// A range written in the source, such as the paper's bead map: the
    /// caller vouches for `0 < low ≤ high`.
    pub(super) const fn known(low: f64, high: f64) -> Self {
        HeightRange {
            low: Length(low),
            high: Length(high),
        }
    }

    /// The lowest and highest of `heights` (e.g. the top at every deposited
    /// point). An empty list, a NaN or a height ≤ 0 is [`Invalid`]: every
    /// deposited point needs some metal.
    pub fn of(
        what: &'static str,
        heights: impl IntoIterator<Item = Length>,
    ) -> Result<Self, Invalid> {
        let mut range: Option<(f64, f64)> = None;
        for h in heights {
            let h = Positive::new(what, h)?.mm();
            range = Some(match range {
                None => (h, h),
                Some((lo, hi)) => (lo.min(h), hi.max(h)),
            });
        }
        let (lo, hi) = range.ok_or(Invalid::Empty { what })?;
        Ok(HeightRange {
            low: Length(lo),
            high: Length(hi),
        })
    }

    /// The low end (`h_min`, `H_min`).
    pub fn low(self) -> Length {
        self.low
    }

    /// The high end (`h_max`, `H_max`).
    pub fn high(self) -> Length {
        self.high
    }

    /// `high / low` (≥ 1): the ratio of heights the range spans. A top can be
    /// built with a bead only if the bead's ratio is at least the top's.
    pub fn ratio(self) -> f64 {
        self.high.0 / self.low.0
    }

    /// Whether `h` lies in the range, with [`SLACK`].
    pub fn contains(self, h: Length) -> bool {
        h.0 >= self.low.0 * (1.0 - SLACK) && h.0 <= self.high.0 * (1.0 + SLACK)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_inputs_are_errors() {
        assert!(matches!(
            Positive::new("bead width", Length(0.0)),
            Err(Invalid::NotPositive { .. })
        ));
        assert!(matches!(
            Positive::new("bead width", Length(f64::NAN)),
            Err(Invalid::NotFinite { .. })
        ));
        assert!(matches!(
            HeightRange::new("bead heights", Length(2.0), Length(1.0)),
            Err(Invalid::Reversed { .. })
        ));
        assert!(matches!(
            HeightRange::of("top", []),
            Err(Invalid::Empty { .. })
        ));
        assert!(matches!(
            HeightRange::of("top", [Length(3.0), Length(-1.0)]),
            Err(Invalid::NotPositive { .. })
        ));
        let r = HeightRange::of("top", [Length(3.0), Length(1.5), Length(2.0)]).unwrap();
        assert_eq!(
            (r.low(), r.high(), r.ratio()),
            (Length(1.5), Length(3.0), 2.0)
        );
    }
}

//! A bead measured at several speeds: heights (and widths) joined by
//! straight lines between the speeds measured. No shape is assumed between
//! two measurements but a straight line, and none outside them: the plan
//! may use the table only over the speeds measured unless the file allows
//! more (`lmd::extrapolation`); where it does, the end pieces are extended.

use std::sync::Arc;

/// What makes a list of speeds and heights no table (each with the index
/// of the entry, from 0, where it shows).
#[derive(Clone, Debug, PartialEq)]
pub enum TableFault {
    /// Fewer than two speeds.
    TooFew(usize),
    /// The lists are not of one length.
    Lengths {
        /// How many speeds.
        speeds: usize,
        /// How many heights (or widths).
        other: usize,
    },
    /// A speed, height or width that is not a number greater than zero.
    NotPositive(usize),
    /// A speed not greater than the one before it.
    SpeedOrder(usize),
    /// A height not lower than the one at the speed before it: a faster
    /// scan must lay a lower bead, or no speed is the one for a height.
    NotFalling(usize),
}

/// Heights measured at increasing speeds, falling: a piecewise-linear map
/// with an inverse. Cheap to clone (the points are shared).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    speeds: Arc<[f64]>,
    heights: Arc<[f64]>,
}

impl Table {
    /// A table of `heights` (mm) at `speeds` (mm/s), or every fault of it.
    pub fn new(speeds: &[f64], heights: &[f64]) -> Result<Table, Vec<TableFault>> {
        let mut faults = shape(speeds, heights);
        for i in 1..speeds.len().min(heights.len()) {
            let ok = |k: usize| speeds[k] > 0.0 && heights[k] > 0.0;
            if ok(i) && ok(i - 1) && speeds[i] > speeds[i - 1] && heights[i] >= heights[i - 1] {
                faults.push(TableFault::NotFalling(i));
            }
        }
        if !faults.is_empty() {
            return Err(faults);
        }
        Ok(Table {
            speeds: speeds.into(),
            heights: heights.into(),
        })
    }

    /// The speeds measured, mm/s, increasing.
    pub fn speeds(&self) -> &[f64] {
        &self.speeds
    }

    /// The heights measured, mm, falling.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The slowest and the fastest speed measured.
    pub fn range(&self) -> [f64; 2] {
        [self.speeds[0], self.speeds[self.speeds.len() - 1]]
    }

    /// The height at `v` (mm/s), mm: on the straight line between the two
    /// speeds measured around it; outside them, on the end piece extended.
    pub fn height_at(&self, v: f64) -> f64 {
        interpolate(&self.speeds, &self.heights, v)
    }

    /// The speed that lays height `h` (mm), mm/s: the inverse of
    /// [`Table::height_at`], which falls strictly.
    pub fn speed_for(&self, h: f64) -> f64 {
        // Heights fall with the speed: the piece whose right end is the
        // first height at or below `h`, clamped to the end pieces.
        let (vs, hs) = (&self.speeds, &self.heights);
        let k = hs.partition_point(|&hk| hk > h).clamp(1, hs.len() - 1);
        let (v0, v1, h0, h1) = (vs[k - 1], vs[k], hs[k - 1], hs[k]);
        v0 + (v1 - v0) * (h - h0) / (h1 - h0)
    }
}

/// The faults of the lists' shape: length, count, positive values, order.
fn shape(speeds: &[f64], heights: &[f64]) -> Vec<TableFault> {
    let mut faults = Vec::new();
    if speeds.len() != heights.len() {
        faults.push(TableFault::Lengths {
            speeds: speeds.len(),
            other: heights.len(),
        });
    }
    if speeds.len() < 2 {
        faults.push(TableFault::TooFew(speeds.len()));
    }
    for (i, (&v, &h)) in speeds.iter().zip(heights).enumerate() {
        if !(v > 0.0 && v.is_finite() && h > 0.0 && h.is_finite()) {
            faults.push(TableFault::NotPositive(i));
        }
    }
    for i in 1..speeds.len() {
        if speeds[i] <= speeds[i - 1] {
            faults.push(TableFault::SpeedOrder(i));
        }
    }
    faults
}

/// Widths measured at increasing speeds, joined by straight lines and held
/// at the end values outside them (a bead does not narrow to nothing).
#[derive(Clone, Debug, PartialEq)]
pub struct Widths {
    speeds: Arc<[f64]>,
    widths: Arc<[f64]>,
}

impl Widths {
    /// `widths` (mm) at `speeds` (mm/s, increasing), or every fault.
    pub fn new(speeds: &[f64], widths: &[f64]) -> Result<Widths, Vec<TableFault>> {
        let mut faults = shape(speeds, widths);
        faults.retain(|f| !matches!(f, TableFault::TooFew(_)));
        if speeds.is_empty() {
            faults.push(TableFault::TooFew(0));
        }
        if !faults.is_empty() {
            return Err(faults);
        }
        Ok(Widths {
            speeds: speeds.into(),
            widths: widths.into(),
        })
    }

    /// The speeds measured, mm/s.
    pub fn speeds(&self) -> &[f64] {
        &self.speeds
    }

    /// The widths measured, mm.
    pub fn widths(&self) -> &[f64] {
        &self.widths
    }

    /// The width at `v`, mm.
    pub fn at(&self, v: f64) -> f64 {
        let n = self.speeds.len();
        if v <= self.speeds[0] {
            self.widths[0]
        } else if v >= self.speeds[n - 1] {
            self.widths[n - 1]
        } else {
            interpolate(&self.speeds, &self.widths, v)
        }
    }

    /// The narrowest and the widest width measured, mm.
    pub fn range(&self) -> [f64; 2] {
        self.widths
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &w| {
                [lo.min(w), hi.max(w)]
            })
    }
}

/// `y` at `x` on the polyline through `(xs, ys)` (`xs` increasing, at
/// least two points; one point: its `y`), the end pieces extended.
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    if n < 2 {
        return ys.first().copied().unwrap_or(f64::NAN);
    }
    // The piece whose right end is the first x above `x` (clamped to the
    // first and last pieces).
    let k = xs.partition_point(|&xi| xi <= x).clamp(1, n - 1);
    let (x0, x1, y0, y1) = (xs[k - 1], xs[k], ys[k - 1], ys[k]);
    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed_003() -> Table {
        // Seed 003's line at three speeds: a table of it is the line.
        let h = |v: f64| -0.135 * v + 1.82;
        Table::new(&[4.0, 6.0, 8.7], &[h(4.0), h(6.0), h(8.7)]).unwrap()
    }

    #[test]
    fn a_table_of_a_line_is_the_line_and_inverts() {
        let t = seed_003();
        for v in [4.0, 4.5, 6.0, 7.3, 8.7] {
            let h = -0.135 * v + 1.82;
            assert!((t.height_at(v) - h).abs() < 1e-12, "{v}");
            assert!((t.speed_for(h) - v).abs() < 1e-9, "{v}");
        }
        assert_eq!(t.range(), [4.0, 8.7]);
    }

    #[test]
    fn between_two_speeds_the_height_is_on_their_line() {
        let t = Table::new(&[4.0, 6.0, 8.0], &[1.3, 1.0, 0.9]).unwrap();
        // Halfway between 6 and 8: halfway between 1.0 and 0.9.
        assert!((t.height_at(7.0) - 0.95).abs() < 1e-12);
        assert!((t.speed_for(1.15) - 5.0).abs() < 1e-12);
        // Outside, the end pieces go on.
        assert!((t.height_at(3.0) - 1.45).abs() < 1e-12);
        assert!((t.height_at(9.0) - 0.85).abs() < 1e-12);
    }

    #[test]
    fn a_height_that_does_not_fall_is_refused_where_it_rises() {
        let faults = Table::new(&[4.0, 5.0, 6.0, 7.0], &[1.2, 1.25, 1.0, 1.0]).unwrap_err();
        assert_eq!(
            faults,
            vec![TableFault::NotFalling(1), TableFault::NotFalling(3)]
        );
        let faults = Table::new(&[4.0, 4.0], &[1.2, 1.0]).unwrap_err();
        assert_eq!(faults, vec![TableFault::SpeedOrder(1)]);
        let faults = Table::new(&[4.0], &[1.2]).unwrap_err();
        assert_eq!(faults, vec![TableFault::TooFew(1)]);
        let faults = Table::new(&[4.0, 5.0], &[1.2]).unwrap_err();
        assert!(faults.contains(&TableFault::Lengths {
            speeds: 2,
            other: 1
        }));
    }

    #[test]
    fn widths_hold_their_end_values_outside() {
        let w = Widths::new(&[4.0, 8.0], &[2.6, 2.2]).unwrap();
        assert!((w.at(6.0) - 2.4).abs() < 1e-12);
        assert_eq!(w.at(2.0), 2.6);
        assert_eq!(w.at(10.0), 2.2);
        assert_eq!(w.range(), [2.2, 2.6]);
        let one = Widths::new(&[6.0], &[2.4]).unwrap();
        assert_eq!(one.at(3.0), 2.4);
    }
}

//! Why a number cannot be planned, controlled or simulated at all: a
//! degenerate input (NaN, a zero speed, a reversed range, a table of the wrong
//! length), as opposed to a plan that does not fit the bead or a loop that is
//! unstable (those have diagnostics of their own, with the numbers a fix
//! needs). A leaf module, like [`crate::units`]: the slicer's and the control
//! module's maths check their inputs at the boundary with it.

/// A degenerate input. Every public function of the maths modules checks its
/// inputs at the boundary and returns one of these instead of panicking or
/// computing a NaN deep inside.
///
/// Its wording (`Display`) is in `crate::diag::message::segmented_ring`.
#[derive(Clone, Debug, PartialEq)]
pub enum Invalid {
    /// NaN or infinite.
    NotFinite {
        /// What the value is ("target height").
        what: &'static str,
    },
    /// Zero or negative where only a positive value makes sense.
    NotPositive {
        /// What the value is.
        what: &'static str,
        /// The value, in canonical units (mm, mm/s, rad, W·10⁹).
        value: f64,
    },
    /// A range whose low end lies above (or at) its high end.
    Reversed {
        /// What the range is.
        what: &'static str,
        /// Its low end.
        low: f64,
        /// Its high end.
        high: f64,
    },
    /// Nothing to work with: no segments, no speeds.
    Empty {
        /// What is empty.
        what: &'static str,
    },
    /// A segment asked for that does not exist.
    NoSegment {
        /// The segment asked for, from 0.
        segment: usize,
        /// How many there are.
        segments: usize,
    },
    /// A transition as long as its segment or longer: nothing of the segment
    /// would be left at its own height.
    TransitionTooLong {
        /// The transition, degrees.
        transition_deg: f64,
        /// The segment, degrees.
        segment_deg: f64,
    },
    /// A list with one entry per segment that has another length.
    Count {
        /// What the list is ("segment table").
        what: &'static str,
        /// Its length.
        found: usize,
        /// The number of segments.
        expected: usize,
    },
    /// A speed the loop starts from that the clamp would never allow.
    OutsideClamp {
        /// What the speed is ("start speed of segment 3").
        what: &'static str,
        /// The speed, mm/s.
        value: f64,
        /// The clamp's low end, mm/s.
        low: f64,
        /// The clamp's high end, mm/s.
        high: f64,
    },
    /// Positions along a track that do not strictly increase.
    NotIncreasing {
        /// What the positions are.
        what: &'static str,
        /// The first offending point (from 0).
        index: usize,
    },
    /// A value so large that the work it asks for is unbounded (a million
    /// points per degree).
    TooLarge {
        /// What the value is.
        what: &'static str,
        /// The value.
        value: f64,
        /// The largest accepted.
        max: f64,
    },
}

/// `v` if it is finite, else [`Invalid::NotFinite`].
pub(crate) fn finite(what: &'static str, v: f64) -> Result<f64, Invalid> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Invalid::NotFinite { what })
    }
}

/// `v` if it is finite and greater than zero.
pub(crate) fn positive(what: &'static str, v: f64) -> Result<f64, Invalid> {
    let x = finite(what, v)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(Invalid::NotPositive { what, value: x })
    }
}

/// `Ok` if a per-segment list has one entry per segment.
pub(crate) fn count(what: &'static str, found: usize, expected: usize) -> Result<(), Invalid> {
    if found == expected {
        Ok(())
    } else {
        Err(Invalid::Count {
            what,
            found,
            expected,
        })
    }
}

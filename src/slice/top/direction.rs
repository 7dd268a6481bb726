//! The build directions tried for a target that overhangs the scan
//! (docs/repair.md, *Overhangs* and *Undercuts*): tilts from vertical in
//! steps of [`TILT_STEP`] toward [`AZIMUTHS`] directions round the
//! vertical, least tilt first, up to [`MAX_TILT`]. The refusal's least
//! tilt (`undercut`) and `direction = auto`'s search (`tilted`) try the
//! same ones, so the tilt one names is the tilt the other finds.

/// Degrees between the tilts tried.
pub(super) const TILT_STEP: f64 = 1.0;

/// The directions round the vertical tried at each tilt.
pub(super) const AZIMUTHS: usize = 24;

/// The most tilt tried, deg: a line nearer horizontal runs along the part.
pub(super) const MAX_TILT: f64 = 85.0;

/// A build direction: its tilt from vertical and the direction it tilts
/// toward, deg from +x counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Direction {
    /// Its tilt from vertical, deg.
    pub tilt: f64,
    /// The direction it tilts toward, deg from +x counter-clockwise.
    pub azimuth: f64,
}

impl Direction {
    /// Straight up.
    pub const VERTICAL: Direction = Direction {
        tilt: 0.0,
        azimuth: 0.0,
    };

    /// The unit vector.
    pub fn vector(self) -> [f64; 3] {
        let (st, ct) = self.tilt.to_radians().sin_cos();
        let (sa, ca) = self.azimuth.to_radians().sin_cos();
        [st * ca, st * sa, ct]
    }

    /// Its tilt and azimuth, deg.
    pub fn pair(self) -> [f64; 2] {
        [self.tilt, self.azimuth]
    }

    /// Every direction tried with a tilt in `(from, to]` deg, least tilt
    /// first.
    pub fn tried(from: f64, to: f64) -> impl Iterator<Item = Direction> {
        let steps = (to.min(MAX_TILT) / TILT_STEP + 1e-9).floor() as usize;
        let first = (from / TILT_STEP + 1e-9).floor() as usize + 1;
        (first..=steps).flat_map(|k| {
            (0..AZIMUTHS).map(move |a| Direction {
                tilt: k as f64 * TILT_STEP,
                azimuth: a as f64 * 360.0 / AZIMUTHS as f64,
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_tried_least_tilt_first_within_the_limit() {
        let all: Vec<Direction> = Direction::tried(0.0, 2.5).collect();
        assert_eq!(all.len(), 2 * AZIMUTHS);
        assert_eq!(all[0].pair(), [1.0, 0.0]);
        assert_eq!(all[AZIMUTHS].pair(), [2.0, 0.0]);
        assert_eq!(Direction::tried(0.0, 0.0).count(), 0);
        assert_eq!(
            Direction::tried(30.0, 31.0).next().map(|d| d.tilt),
            Some(31.0)
        );
        let v = Direction {
            tilt: 30.0,
            azimuth: 90.0,
        }
        .vector();
        assert!((v[1] - 0.5).abs() < 1e-12 && v[0].abs() < 1e-12, "{v:?}");
    }
}

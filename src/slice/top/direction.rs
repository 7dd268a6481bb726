//! The build directions tried for a target that overhangs the scan
//! (docs/repair.md, *Overhangs* and *Undercuts*): tilts from vertical in
//! steps of [`TILT_STEP`] toward [`AZIMUTHS`] directions round the
//! vertical, least tilt first, up to [`MAX_TILT`], and for
//! `direction = auto`'s search (`tilted`) as many more at each tilt as
//! keep them a degree of arc apart. The refusal's least tilt (`undercut`)
//! tries the [`AZIMUTHS`] alone, at one point (a tilt it names along
//! them, `tilted` finds too).

/// Degrees between the tilts tried.
pub(super) const TILT_STEP: f64 = 1.0;

/// The directions round the vertical tried first at each tilt (every
/// 15°: the part's axes among them), and at least.
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
    /// first: at each tilt the [`AZIMUTHS`], then when `fine` as many
    /// more as [`Direction::azimuths`] says.
    pub fn tried(from: f64, to: f64, fine: bool) -> impl Iterator<Item = Direction> {
        let steps = (to.min(MAX_TILT) / TILT_STEP + 1e-9).floor() as usize;
        let first = (from / TILT_STEP + 1e-9).floor() as usize + 1;
        (first..=steps).flat_map(move |k| {
            let tilt = k as f64 * TILT_STEP;
            let n = if fine { Self::azimuths(tilt) } else { 0 };
            let coarse = (0..AZIMUTHS).map(|a| a as f64 * 360.0 / AZIMUTHS as f64);
            let fine = (0..n)
                .map(move |a| a as f64 * 360.0 / n as f64)
                .filter(|&az| Self::off_coarse(az));
            coarse
                .chain(fine)
                .map(move |azimuth| Direction { tilt, azimuth })
        })
    }

    /// How many directions round the vertical are tried at `tilt` deg: at
    /// least [`AZIMUTHS`], and enough that neighbours are at most
    /// [`TILT_STEP`] apart (a slab leaning 30° toward 37° is met within a
    /// degree, not 7°). The [`AZIMUTHS`] are tried first at each tilt, so
    /// that a lean along them is built along it, not along a neighbour
    /// within a hundredth.
    fn azimuths(tilt: f64) -> usize {
        let round = 360.0 * tilt.to_radians().sin() / TILT_STEP;
        AZIMUTHS.max(4 * (round / 4.0).ceil() as usize)
    }

    /// Whether `azimuth` deg is none of the [`AZIMUTHS`].
    fn off_coarse(azimuth: f64) -> bool {
        let k = azimuth * AZIMUTHS as f64 / 360.0;
        (k - k.round()).abs() > 1e-9
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_tried_least_tilt_first_within_the_limit() {
        let all: Vec<Direction> = Direction::tried(0.0, 2.5, true).collect();
        assert_eq!(all.len(), 2 * AZIMUTHS);
        // At 30°, 2° round the vertical is a degree of arc: the 24 first,
        // then the 168 of the 180 every 2° that are none of them.
        let at30: Vec<Direction> = Direction::tried(29.0, 30.0, true).collect();
        assert_eq!(at30.len(), AZIMUTHS + 168);
        assert_eq!(at30[1].azimuth, 15.0);
        assert_eq!(at30[AZIMUTHS].azimuth, 2.0);
        let mut az: Vec<f64> = at30.iter().map(|d| d.azimuth).collect();
        az.sort_by(f64::total_cmp);
        assert!(az
            .windows(2)
            .all(|w| w[1] - w[0] <= 2.0 + 1e-9 && w[1] > w[0]));
        assert_eq!(Direction::tried(29.0, 30.0, false).count(), AZIMUTHS);
        assert_eq!(all[0].pair(), [1.0, 0.0]);
        assert_eq!(all[AZIMUTHS].pair(), [2.0, 0.0]);
        assert_eq!(Direction::tried(0.0, 0.0, true).count(), 0);
        assert_eq!(
            Direction::tried(30.0, 31.0, true).next().map(|d| d.tilt),
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

//! How far apart tracks of unequal height sit (seed 003 eq. 4–6, the wedge).
//!
//! Across the tracks a layer's thickness is linear from one edge of the
//! footprint to the other. Beads `k` and `k+1`, of heights `h_k`, `h_{k+1}`
//! (the layer's thickness at their centres) and cross-sections `A_k`,
//! `A_{k+1}` (circular segments of chord `W`, [`crate::bead::segment_area`],
//! valid for every height), sit at the centre distance `C_k` where the
//! trapezoid between their centres holds half of each bead:
//!
//! `C_k · (h_k + h_{k+1}) = A_k + A_{k+1}`
//!
//! (the paper's eq. 4 has a spurious factor 2, which would put beads farther
//! apart than they are wide). From the first track's centre, `W/2` inside
//! the first edge, each `C_k` follows from the last centre; `h_{k+1}` is
//! the thickness at `y_k + C_k`, so each step solves one equation in `C_k`.
//!
//! **Closing on the far edge.** The recursion does not land the last centre
//! `W/2` inside the far edge; the paper does not say what to do. We keep
//! every pair in the *same* balance and stretch it uniformly: for a track
//! count `n`, find the one factor `σ` with
//!
//! `C_k · (h_k + h_{k+1}) = σ · (A_k + A_{k+1})` for every pair
//!
//! that puts the `n`-th centre exactly at `L₀ − W/2` (heights still read off
//! the planned line at the centres actually used). Of the two counts around
//! the unstretched recursion's fractional one, the one with `σ` nearer 1
//! wins. `σ > 1` spreads the tracks wider than the balance wants, so between
//! them the layer comes out about `1/σ` of its planned thickness; `σ < 1`
//! piles it up. [`TrackLayout::stretch`] returns `σ`, and the caller warns
//! when `|σ − 1|` is more than a few per cent. Stretching uniformly rather
//! than absorbing the remainder in the last gap spreads the error thinly, so
//! the top stays a plane instead of growing a ridge or groove at one edge.

use super::input::{Invalid, Positive};
use super::SLACK;
use crate::bead::segment_area;
use crate::units::Length;

/// Most tracks across one layer. Bounds the recursion for any input (a
/// 1 m wide footprint of 0.2 mm beads is 5000).
pub const MAX_TRACKS: usize = 10_000;

/// A layer's thickness across the tracks: linear from the footprint's first
/// edge (`y = 0`) to its far edge (`y = width`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossSection {
    width: Positive,
    first: Positive,
    far: Positive,
}

impl CrossSection {
    /// A footprint `width` across the tracks whose layer is `first` thick at
    /// the first edge and `far` at the far one (e.g. `H/N` at each edge).
    pub fn new(width: Length, first: Length, far: Length) -> Result<Self, Invalid> {
        Ok(CrossSection {
            width: Positive::new("footprint width across the tracks", width)?,
            first: Positive::new("layer thickness at the first edge", first)?,
            far: Positive::new("layer thickness at the far edge", far)?,
        })
    }

    /// The footprint's width across the tracks.
    pub fn width(&self) -> Length {
        self.width.get()
    }

    /// The thickness at `y` from the first edge (the edge value beyond it).
    pub fn at(&self, y: Length) -> Length {
        let t = (y.0 / self.width.mm()).clamp(0.0, 1.0);
        let (a, b) = (self.first.mm(), self.far.mm());
        Length(a + (b - a) * t)
    }

    fn thinnest(&self) -> f64 {
        self.first.mm().min(self.far.mm())
    }

    fn thickest(&self) -> f64 {
        self.first.mm().max(self.far.mm())
    }
}

/// The tracks of one layer across the footprint.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackLayout {
    /// Track centres from the first edge: `W/2` first, `L₀ − W/2` last.
    pub centres: Vec<Length>,
    /// The layer's thickness at each centre (the bead height there).
    pub heights: Vec<Length>,
    /// `σ`: every pair sits at `σ` times the balanced distance (1 = none).
    pub stretch: f64,
}

impl TrackLayout {
    /// The centre distances `C_k`.
    pub fn spacings(&self) -> Vec<Length> {
        self.centres
            .windows(2)
            .map(|c| Length(c[1].0 - c[0].0))
            .collect()
    }

    /// How much the closure stretches the spacing, in per cent (negative:
    /// squeezes).
    pub fn stretch_percent(&self) -> f64 {
        (self.stretch - 1.0) * 100.0
    }
}

/// Why the tracks cannot be laid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OverlapError {
    /// The footprint is narrower than one bead.
    TooNarrow {
        /// The footprint's width across the tracks.
        width: Length,
        /// The bead width.
        bead: Length,
    },
    /// More than [`MAX_TRACKS`] tracks.
    TooManyTracks,
    /// No uniform stretch lands the last track on the far edge (a balance
    /// whose spacing does not grow with the stretch: a thickness ratio far
    /// outside any bead map).
    NoClosure,
}

/// `C` such that `C·(h + h') = σ·(A(h) + A(h'))` for the bead at `y` and the
/// next, `h' = section.at(y + C)`, found by bisection: the left side minus
/// the right is negative at `C = 0` and not negative at
/// `σ·(A(h) + A_max)/(h + h_min)`.
pub fn balanced_spacing(section: &CrossSection, bead: Positive, y: Length, stretch: f64) -> Length {
    let w = bead.mm();
    let h = section.at(y).0;
    let a = segment_area(w, h);
    let gap = |c: f64| {
        let h1 = section.at(Length(y.0 + c)).0;
        c * (h + h1) - stretch * (a + segment_area(w, h1))
    };
    let (mut lo, mut hi) = (
        0.0,
        stretch * (a + segment_area(w, section.thickest())) / (h + section.thinnest()),
    );
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    Length(0.5 * (lo + hi))
}

/// The centre after `steps` balanced steps at stretch `σ` from the first.
fn reach(section: &CrossSection, bead: Positive, stretch: f64, steps: usize) -> f64 {
    (0..steps).fold(bead.mm() / 2.0, |y, _| {
        y + balanced_spacing(section, bead, Length(y), stretch).0
    })
}

/// The unstretched recursion (eq. 4 as corrected): centres from `W/2` while
/// they lie at or before `until`, and the first one beyond it. Never more
/// than [`MAX_TRACKS`] + 1 centres.
pub fn recursion(section: &CrossSection, bead: Positive, until: Length) -> Vec<Length> {
    let mut y = bead.mm() / 2.0;
    let mut out = vec![Length(y)];
    while y <= until.0 && out.len() <= MAX_TRACKS {
        y += balanced_spacing(section, bead, Length(y), 1.0).0;
        out.push(Length(y));
    }
    out
}

/// The stretch that puts the centre after `steps` steps at `target`, or
/// `None` if bisection cannot bracket it.
fn closing_stretch(
    section: &CrossSection,
    bead: Positive,
    steps: usize,
    target: f64,
) -> Option<f64> {
    let end = |s: f64| reach(section, bead, s, steps) - target;
    let (mut lo, mut hi) = (1.0, 1.0);
    for _ in 0..60 {
        if end(lo) <= 0.0 {
            break;
        }
        lo /= 2.0;
    }
    for _ in 0..60 {
        if end(hi) >= 0.0 {
            break;
        }
        hi *= 2.0;
    }
    if end(lo) > 0.0 || end(hi) < 0.0 {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if end(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-14 * hi {
            break;
        }
    }
    let s = 0.5 * (lo + hi);
    (end(s).abs() <= 1e-9 * target.max(1.0)).then_some(s)
}

/// The tracks of one layer: the first centre `W/2` inside the first edge,
/// the last `W/2` inside the far edge, every pair in the same balance
/// (see the module's closure rule).
pub fn lay_tracks(section: &CrossSection, bead: Positive) -> Result<TrackLayout, OverlapError> {
    let (l0, w) = (section.width().0, bead.mm());
    let span = l0 - w;
    if span < -SLACK * l0 {
        return Err(OverlapError::TooNarrow {
            width: section.width(),
            bead: bead.get(),
        });
    }
    if span <= SLACK * l0 {
        // One bead fills the footprint.
        let y = Length(l0 / 2.0);
        return Ok(TrackLayout {
            centres: vec![y],
            heights: vec![section.at(y)],
            stretch: 1.0,
        });
    }
    let target = l0 - w / 2.0;
    let raw = recursion(section, bead, Length(target));
    if raw.len() > MAX_TRACKS {
        return Err(OverlapError::TooManyTracks);
    }
    // `raw` ends with the first centre past the far edge: `short` steps fall
    // short of it, `short + 1` pass it.
    let short = raw.len() - 2;
    let (stretch, steps) = [short, short + 1]
        .into_iter()
        .filter(|&n| n >= 1)
        .filter_map(|n| closing_stretch(section, bead, n, target).map(|s| (s, n)))
        .min_by(|a, b| a.0.ln().abs().total_cmp(&b.0.ln().abs()))
        .ok_or(OverlapError::NoClosure)?;
    let mut centres = vec![Length(w / 2.0)];
    for _ in 0..steps {
        let y = centres[centres.len() - 1];
        centres.push(Length(y.0 + balanced_spacing(section, bead, y, stretch).0));
    }
    let heights = centres.iter().map(|&y| section.at(y)).collect();
    Ok(TrackLayout {
        centres,
        heights,
        stretch,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(v: f64) -> Positive {
        Positive::new("test", Length(v)).unwrap()
    }

    #[test]
    fn flat_layers_space_tracks_at_a_over_h() {
        // Seed 001: w 2.2, h 0.7 → d = A/h ≈ 1.58 mm.
        let s = CrossSection::new(Length(30.0), Length(0.7), Length(0.7)).unwrap();
        let c = balanced_spacing(&s, pos(2.2), Length(1.1), 1.0);
        assert!((c.0 - segment_area(2.2, 0.7) / 0.7).abs() < 1e-12);
        let t = lay_tracks(&s, pos(2.2)).unwrap();
        // 27.8 mm between the outer centres is 17.6 spacings of 1.58 mm: 18
        // tracks squeezed by 2.2 %.
        let raw = segment_area(2.2, 0.7) / 0.7;
        let gaps = t.centres.len() - 1;
        assert_eq!(gaps, (27.8 / raw).round() as usize);
        assert!((t.stretch - 27.8 / (gaps as f64 * raw)).abs() < 1e-9);
    }

    #[test]
    fn one_bead_wide_is_one_track() {
        let s = CrossSection::new(Length(2.4), Length(1.0), Length(1.0)).unwrap();
        let t = lay_tracks(&s, pos(2.4)).unwrap();
        assert_eq!((t.centres.clone(), t.stretch), (vec![Length(1.2)], 1.0));
        let s = CrossSection::new(Length(2.0), Length(1.0), Length(1.0)).unwrap();
        assert!(matches!(
            lay_tracks(&s, pos(2.4)),
            Err(OverlapError::TooNarrow { .. })
        ));
        assert!(CrossSection::new(Length(15.0), Length(0.0), Length(1.0)).is_err());
    }

    #[test]
    fn the_paper_wedge_closes_within_a_few_per_cent() {
        // 15 mm across (the paper's wedge), 9 layers of a top rising
        // 8 → 13 mm: 0.889 → 1.444 mm, with the 2.4 mm bead.
        let s = CrossSection::new(Length(15.0), Length(8.0 / 9.0), Length(13.0 / 9.0)).unwrap();
        let t = lay_tracks(&s, pos(2.4)).unwrap();
        assert!((t.centres[0].0 - 1.2).abs() < 1e-12);
        assert!((t.centres[t.centres.len() - 1].0 - 13.8).abs() < 1e-9);
        assert!(t.stretch_percent().abs() < 10.0, "{}", t.stretch_percent());
        // Taller beads are fuller (A/h grows from 2W/3 toward πW/4 at
        // h = W/2), so the spacing grows up the wedge.
        let c = t.spacings();
        assert!(c.windows(2).all(|p| p[1].0 > p[0].0));
    }
}

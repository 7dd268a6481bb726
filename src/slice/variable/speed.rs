//! Which speed lays the height a point needs (seed 003 eq. 1 and 8), and how
//! fast the nozzle must then move along a path that climbs.
//!
//! **The map gives the horizontal speed.** The bead map `H(v)` was measured on
//! flat single tracks, where path and horizontal speed are the same. What sets
//! a layer's *vertical* thickness is the metal caught per unit of *horizontal*
//! length, `η·ṁ / v_h`: a layer of vertical thickness `h` on a slope holds
//! `h` times its width per unit of horizontal length whatever the slope (a
//! shear keeps areas), and the layer heights the slicer stacks are vertical.
//! So the map is read at the horizontal speed, and the nozzle, which moves
//! along a path rising at slope `s = dz/dx`, runs at the path speed
//! `v_path = v_h · √(1 + s²)` — it covers `√(1+s²)` of path per unit of
//! horizontal length. This is the segmented ring's rule for its transition
//! arcs (keep the horizontal speed, path speed `v/cos γ`), so variable layers
//! and the ring agree. The alternative, programming the map's speed as the
//! path speed, crosses the ground `√(1+s²)` times slower and lays that much
//! too much metal on every slope: up to 1.3 % on the 16 % ramp proposed as
//! `examples/ramp_wall.lmd`, and the excess adds up layer on layer, as a lift
//! mismatch does.
//!
//! The slope is that of the *path*, i.e. of the surface the layer is laid on:
//! layer `i` (from 0) follows the planned top of layer `i − 1`, `i·H/N`, whose
//! slope is `i/N` of the top's ([`path_slope`]). The horizontal speeds are the
//! same on every layer; the path speeds grow with the layer.

use super::input::{finite, HeightRange, Invalid, Positive};
use crate::sema::model::Bead;
use crate::units::{Length, Speed, Time};
use std::num::NonZeroU32;

/// A bead's height ↔ speed map over the speeds it holds for.
pub trait HeightMap {
    /// The heights it lays over its speed range, `h_min .. h_max`.
    fn heights(&self) -> HeightRange;

    /// The horizontal scan speed that lays `h`, for `h` within
    /// [`heights`](Self::heights) (callers go through
    /// [`horizontal_speed`](Self::horizontal_speed)).
    fn speed_within(&self, h: Length) -> Speed;

    /// The horizontal scan speed that lays `h`, or why none does.
    fn horizontal_speed(&self, h: Length) -> Result<Speed, OutsideMap> {
        let heights = self.heights();
        if h.0.is_finite() && heights.contains(h) {
            Ok(self.speed_within(h))
        } else {
            Err(OutsideMap { height: h, heights })
        }
    }
}

/// A height the map cannot lay.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutsideMap {
    /// The height asked for.
    pub height: Length,
    /// What the map lays.
    pub heights: HeightRange,
}

/// `H = slope·v + intercept` over `speeds` (seed 003 eq. 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearMap {
    slope: Time,
    intercept: Length,
    speeds: [Speed; 2],
    heights: HeightRange,
}

impl LinearMap {
    /// Checks the map: a negative slope (a faster scan lays a lower bead), a
    /// speed range `0 < v_lo ≤ v_hi`, positive heights over all of it.
    pub fn new(slope: Time, intercept: Length, speeds: [Speed; 2]) -> Result<Self, Invalid> {
        let k = finite("slope of the bead map", slope.0)?;
        if k >= 0.0 {
            return Err(Invalid::NotPositive {
                what: "minus the slope of the bead map",
                value: -k,
            });
        }
        finite("intercept of the bead map", intercept.0)?;
        let lo = Positive::new("slowest speed of the bead map", Length(speeds[0].0))?.mm();
        let hi = Positive::new("fastest speed of the bead map", Length(speeds[1].0))?.mm();
        if lo > hi {
            return Err(Invalid::Reversed {
                what: "speed range of the bead map",
                low: lo,
                high: hi,
            });
        }
        let heights = HeightRange::new(
            "heights of the bead map",
            Length(k * hi + intercept.0),
            Length(k * lo + intercept.0),
        )?;
        Ok(LinearMap {
            slope,
            intercept,
            speeds,
            heights,
        })
    }

    /// The paper's fitted map: `H = −0.135·v + 1.82` mm for 4 ≤ v ≤ 8.7 mm/s,
    /// heights 0.6455 .. 1.28 mm (ratio 1.983).
    pub const fn seed_003() -> LinearMap {
        LinearMap {
            slope: Time(-0.135),
            intercept: Length(1.82),
            speeds: [Speed(4.0), Speed(8.7)],
            heights: HeightRange::known(-0.135 * 8.7 + 1.82, -0.135 * 4.0 + 1.82),
        }
    }

    /// The height laid at `v`.
    pub fn height_at(&self, v: Speed) -> Length {
        Length(self.slope.0 * v.0 + self.intercept.0)
    }

    /// The speeds it holds for.
    pub fn speeds(&self) -> [Speed; 2] {
        self.speeds
    }
}

impl HeightMap for LinearMap {
    fn heights(&self) -> HeightRange {
        self.heights
    }

    fn speed_within(&self, h: Length) -> Speed {
        Speed((h.0 - self.intercept.0) / self.slope.0)
    }
}

/// A checked bead model of the file (`bead NAME { … }`) as a height map for
/// tracks that each fill a strip `pitch` wide ([`crate::deposit`]): the
/// layer heights it stacks there and the speed that lays each. Without a
/// pitch (the balanced layout, whose spacing makes every track rise
/// by its bead's own height, `h·C = A`) the heights are the beads' own.
#[derive(Clone, Copy, Debug)]
pub struct BeadMap<'a> {
    bead: &'a Bead,
    pitch: Option<Length>,
    heights: HeightRange,
}

impl<'a> BeadMap<'a> {
    /// Wraps a bead whose heights at `pitch` form a valid range.
    pub fn new(bead: &'a Bead, pitch: Option<Length>) -> Result<Self, Invalid> {
        Positive::new("bead width", bead.width)?;
        let [lo, hi] = match pitch {
            Some(p) => bead.heights(Positive::new("track pitch", p)?.get()),
            None => bead.height,
        };
        let heights = HeightRange::new("allowed heights of the bead", lo, hi)?;
        Ok(BeadMap {
            bead,
            pitch,
            heights,
        })
    }
}

impl HeightMap for BeadMap<'_> {
    fn heights(&self) -> HeightRange {
        self.heights
    }

    fn speed_within(&self, h: Length) -> Speed {
        let d = self.bead.deposit();
        let w = self.bead.width;
        match self.pitch {
            Some(p) => d.speed_for(h, p),
            // A bead `h` high lays its segment: the speed for that area.
            None => d.speed_for(Length(crate::bead::segment_area(w.0, h.0) / w.0), w),
        }
    }
}

/// The slope of the path layer `layer` (from 0) of `layers` follows where the
/// top rises at `top_slope`: it is laid on the planned top of the layer
/// below, `layer/N` of the top (the first layer on the flat substrate).
pub fn path_slope(top_slope: f64, layer: u32, layers: NonZeroU32) -> f64 {
    top_slope * layer.min(layers.get()) as f64 / layers.get() as f64
}

/// The speed along a path rising at `slope` (dz per unit of horizontal
/// length) that keeps the horizontal speed `horizontal`: `v_h·√(1+s²)`.
/// Over a constant-speed segment of a curved path pass its chord slope
/// (rise over length): the nozzle then crosses the segment in the time the
/// horizontal speed gives, to second order in the curvature.
pub fn path_speed(horizontal: Speed, slope: f64) -> Result<Speed, Invalid> {
    let v = Positive::new("horizontal speed", Length(horizontal.0))?.mm();
    let s = finite("slope of the path", slope)?;
    Ok(Speed(v * s.hypot(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_map() {
        let m = LinearMap::seed_003();
        let h = m.heights();
        assert!((h.low().0 - 0.6455).abs() < 1e-12);
        assert!((h.high().0 - 1.28).abs() < 1e-12);
        assert!((h.ratio() - 1.983).abs() < 5e-4);
        // Its checked twin is the same map.
        let checked = LinearMap::new(Time(-0.135), Length(1.82), [Speed(4.0), Speed(8.7)]);
        assert_eq!(checked, Ok(m));
        // 1 mm needs (1.82 − 1)/0.135 = 6.074 mm/s.
        let v = m.horizontal_speed(Length(1.0)).unwrap();
        assert!((v.0 - 0.82 / 0.135).abs() < 1e-12);
        assert!((m.height_at(v).0 - 1.0).abs() < 1e-12);
        // The ends of the range lay the ends of the speed range.
        assert!((m.horizontal_speed(Length(1.28)).unwrap().0 - 4.0).abs() < 1e-9);
        assert!((m.horizontal_speed(Length(0.6455)).unwrap().0 - 8.7).abs() < 1e-9);
        assert!(m.horizontal_speed(Length(1.3)).is_err());
        assert!(m.horizontal_speed(Length(f64::NAN)).is_err());
    }

    #[test]
    fn bad_maps_are_refused() {
        let v = [Speed(4.0), Speed(8.7)];
        assert!(LinearMap::new(Time(0.1), Length(1.82), v).is_err());
        assert!(LinearMap::new(Time(-0.135), Length(1.0), v).is_err()); // < 0 at 8.7
        assert!(LinearMap::new(Time(-0.135), Length(1.82), [v[1], v[0]]).is_err());
        assert!(LinearMap::new(Time(f64::NAN), Length(1.82), v).is_err());
    }

    #[test]
    fn path_speed_keeps_the_horizontal_speed() {
        // A 3-4-5 slope: 5 mm of path per 4 mm of run.
        let v = path_speed(Speed(4.0), 0.75).unwrap();
        assert!((v.0 - 5.0).abs() < 1e-12);
        assert_eq!(path_speed(Speed(6.0), 0.0), Ok(Speed(6.0)));
        assert!(path_speed(Speed(0.0), 0.1).is_err());
        assert!(path_speed(Speed(6.0), f64::INFINITY).is_err());
        // The first layer lies on the flat substrate; layer i of N climbs i/N
        // of the top's slope.
        let n = NonZeroU32::new(4).unwrap();
        assert_eq!(path_slope(0.16, 0, n), 0.0);
        assert!((path_slope(0.16, 2, n) - 0.08).abs() < 1e-15);
    }
}

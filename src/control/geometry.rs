//! The ring's geometry: `n` segments of `μ = 360°/n` on a circle of radius
//! `R` about the origin, segment 0 starting on +x and running
//! counter-clockwise (seed 004 eq. 1). The last `θ_t` (2° in the paper) of
//! each segment is a transition: the nozzle moves linearly from this
//! segment's height to the next one's — its working plane and its defocus —
//! while the horizontal speed stays the segment's, so the path speed is
//! `v / cos γ`, `tan γ = Δz / (R·θ_t)` (eq. 7–8; eq. 9's garbled text reads
//! like `v·cos γ`, which would slow the nozzle where it climbs).
//!
//! The nozzle's height is that of the focus, `z + defocus`, with `z` the
//! working plane under it. Within a layer a transition rises by the defocus
//! step plus any difference in built height between the two segments; the last
//! transition of a layer also rises to the next layer (eq. 3: each segment's
//! next working plane is where this layer's measured height left it). The
//! laser stays on from the first point of the build to the last.

use super::invalid::{count, finite, positive, Invalid};
use super::table::SegmentTable;
use crate::units::{Angle, Length, Power, Speed};
use std::f64::consts::TAU;

/// The most moves lmdc will lay out for one layer.
pub const MAX_MOVES: f64 = 1e6;

/// The horizontal speed `v` kept up a slope of `rise` over `arc`: `v / cos γ`
/// with `tan γ = rise / arc`, written `v·√(1 + tan²γ)`.
pub fn path_speed(horizontal: Speed, rise: Length, arc: Length) -> Speed {
    let t = rise.0 / arc.0;
    Speed(horizontal.0 * t.hypot(1.0))
}

/// A ring split into equal segments with transitions at their ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    radius: Length,
    segments: usize,
    transition: Angle,
}

/// One transition of a layer, as the verifier checks it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transition {
    /// The segment it ends (from 0); the last one changes the layer.
    pub segment: usize,
    /// How far the nozzle rises over it (negative: falls).
    pub rise: Length,
    /// Its horizontal length `R·θ_t`.
    pub arc: Length,
}

impl Transition {
    /// `tan γ = Δz / arc`.
    pub fn tan_gamma(&self) -> f64 {
        self.rise.0 / self.arc.0
    }

    /// The path speed at a horizontal speed `v`: `v / cos γ`.
    pub fn path_speed(&self, horizontal: Speed) -> Speed {
        path_speed(horizontal, self.rise, self.arc)
    }
}

/// The moves of one segment on every layer ([`Ring::moves`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentMoves {
    /// Moves over the segment's constant part, at its own height.
    pub flat: usize,
    /// Moves over its transition to the next segment's height.
    pub transition: usize,
}

impl SegmentMoves {
    /// Both: the segment's moves.
    pub fn total(self) -> usize {
        self.flat + self.transition
    }
}

/// Where each segment's working plane lies on the layer being laid out.
#[derive(Clone, Copy, Debug)]
pub struct LayerSpec<'a> {
    /// The horizontal speed of each segment on this layer (the loop's).
    pub speeds: &'a [Speed],
    /// The working-plane height of each segment (0 on the substrate).
    pub base: &'a [Length],
    /// The working-plane height at which the next layer's first segment
    /// starts; `None` on the last layer, whose last transition runs flat (at
    /// the same angles as every other layer's, so that every layer has the
    /// same points in plan view and a program can loop over one).
    pub next_start: Option<Length>,
}

/// A point of a layer's path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingPoint {
    /// The point on the working plane, mm (as the IR's `pos`; the focus is
    /// `defocus` above it along +z).
    pub pos: [f64; 3],
    /// The defocus here.
    pub defocus: Length,
    /// The path speed of the move *from* this point.
    pub speed: Speed,
    /// The power of the move from this point.
    pub power: Power,
    /// The segment the point belongs to (from 0).
    pub segment: usize,
    /// Whether the move from this point is part of a transition.
    pub transition: bool,
    /// Always true: the laser is on from the first point of the build to the last.
    pub laser_on: bool,
}

impl RingPoint {
    /// The height of the focus (the nozzle's programmed height), `z + defocus`.
    pub fn focus_z(&self) -> f64 {
        self.pos[2] + self.defocus.0
    }
}

impl Ring {
    /// `radius > 0`, at least one segment, `0 < transition < 360°/segments`.
    pub fn new(radius: Length, segments: usize, transition: Angle) -> Result<Self, Invalid> {
        positive("ring radius", radius.0)?;
        if segments == 0 {
            return Err(Invalid::NotPositive {
                what: "number of segments",
                value: 0.0,
            });
        }
        if segments as f64 > MAX_MOVES {
            return Err(Invalid::TooLarge {
                what: "number of segments",
                value: segments as f64,
                max: MAX_MOVES,
            });
        }
        let t = positive("transition angle", transition.0)?;
        let mu = TAU / segments as f64;
        if t >= mu {
            return Err(Invalid::TransitionTooLong {
                transition_deg: t.to_degrees(),
                segment_deg: mu.to_degrees(),
            });
        }
        Ok(Ring {
            radius,
            segments,
            transition,
        })
    }

    /// `R`.
    pub fn radius(&self) -> Length {
        self.radius
    }

    /// `n`.
    pub fn segments(&self) -> usize {
        self.segments
    }

    /// `θ_t`.
    pub fn transition(&self) -> Angle {
        self.transition
    }

    /// `μ = 360°/n`.
    pub fn segment_angle(&self) -> Angle {
        Angle(TAU / self.segments as f64)
    }

    /// A transition's horizontal length, `R·θ_t`.
    pub fn transition_arc(&self) -> Length {
        Length(self.radius.0 * self.transition.0)
    }

    /// `Ok` when the table has one row per segment.
    pub fn check_table(&self, table: &SegmentTable) -> Result<(), Invalid> {
        count("segment table", table.len(), self.segments)
    }

    /// The planned transitions of a layer: each rises by the defocus step to
    /// the next segment; the last also by `layer_rise` (the target height: the
    /// built differences between segments are not known before the build).
    pub fn transitions(
        &self,
        table: &SegmentTable,
        layer_rise: Length,
    ) -> Result<Vec<Transition>, Invalid> {
        self.check_table(table)?;
        finite("layer rise", layer_rise.0)?;
        let rows = table.rows();
        let arc = self.transition_arc();
        Ok((0..self.segments)
            .map(|j| {
                let (next, extra) = match rows.get(j + 1) {
                    Some(r) => (r, 0.0),
                    None => (&rows[0], layer_rise.0),
                };
                Transition {
                    segment: j,
                    rise: Length(next.defocus.0 - rows[j].defocus.0 + extra),
                    arc,
                }
            })
            .collect())
    }

    /// The transition whose path speed is highest when its segment runs at
    /// `top` (the clamp's high speed), and that speed: what the verifier holds
    /// against the machine's `max_speed`.
    pub fn fastest_transition(
        &self,
        table: &SegmentTable,
        layer_rise: Length,
        top: Speed,
    ) -> Result<(Transition, Speed), Invalid> {
        positive("top speed", top.0)?;
        // The first of equals: segment 1 → 2 rather than 9 → 10 on Table 1.
        self.transitions(table, layer_rise)?
            .into_iter()
            .map(|t| (t, t.path_speed(top)))
            .fold(None, |best: Option<(Transition, Speed)>, c| match best {
                Some(b) if b.1 .0 >= c.1 .0 => Some(b),
                _ => Some(c),
            })
            .ok_or(Invalid::Empty {
                what: "segment table",
            })
    }

    /// How many moves each segment of every layer gets at most `step` apart:
    /// its constant part's and its transition's. Every segment and every layer
    /// has the same, so a layer's points are `segments × (flat + transition)`
    /// moves and segment `j`'s start at point `j·(flat + transition)`.
    pub fn moves(&self, step: Angle) -> Result<SegmentMoves, Invalid> {
        let step = positive("angular step", step.0)?;
        let mu = TAU / self.segments as f64;
        let per_layer = TAU / step + 2.0 * self.segments as f64;
        if per_layer > MAX_MOVES {
            return Err(Invalid::TooLarge {
                what: "moves per layer",
                value: per_layer.ceil(),
                max: MAX_MOVES,
            });
        }
        Ok(SegmentMoves {
            flat: moves_over(mu - self.transition.0, step),
            transition: moves_over(self.transition.0, step),
        })
    }

    /// The first layer: the table's speeds, on the substrate (z = 0), the next
    /// layer starting `layer_height` up.
    pub fn first_layer(
        &self,
        table: &SegmentTable,
        layer_height: Length,
        step: Angle,
    ) -> Result<Vec<RingPoint>, Invalid> {
        let speeds = table.speeds();
        let base = vec![Length(0.0); self.segments];
        let spec = LayerSpec {
            speeds: &speeds,
            base: &base,
            next_start: Some(layer_height),
        };
        self.layer(table, &spec, step)
    }

    /// The points of one layer, at most `step` apart in angle, from 0° to 360°.
    /// Each segment's constant part and its transition are split into equal
    /// moves; the ends of both are points. The last point is where the next
    /// layer begins: it has no move of its own (as in the IR), so a caller
    /// chaining layers drops it from every layer but the last.
    pub fn layer(
        &self,
        table: &SegmentTable,
        spec: &LayerSpec<'_>,
        step: Angle,
    ) -> Result<Vec<RingPoint>, Invalid> {
        self.check_table(table)?;
        count("layer speeds", spec.speeds.len(), self.segments)?;
        count("layer heights", spec.base.len(), self.segments)?;
        for v in spec.speeds {
            positive("segment speed", v.0)?;
        }
        for z in spec.base.iter().chain(spec.next_start.as_ref()) {
            finite("working-plane height", z.0)?;
        }
        let per = self.moves(step)?;
        let rows = table.rows();
        let (r, mu, t) = (self.radius.0, TAU / self.segments as f64, self.transition.0);
        let mut points = Vec::with_capacity(per.total() * self.segments + 1);
        let point =
            |theta: f64, z: f64, defocus: f64, speed: f64, j: usize, transition: bool| RingPoint {
                pos: [r * theta.cos(), r * theta.sin(), z],
                defocus: Length(defocus),
                speed: Speed(speed),
                power: rows[j].power,
                segment: j,
                transition,
                laser_on: true,
            };
        // Where each segment's last move ends; the last segment's is the
        // layer's last point (every other one is the next segment's first).
        let mut end = None;
        for j in 0..self.segments {
            let (z, d, v) = (spec.base[j].0, rows[j].defocus.0, spec.speeds[j].0);
            // Where the transition leads: the next segment, the next layer,
            // or — on the last layer — nowhere: its last transition stays at
            // the segment's own height.
            let (zn, dn) = match (spec.base.get(j + 1), spec.next_start) {
                (Some(zn), _) => (zn.0, rows[j + 1].defocus.0),
                (None, Some(zn)) => (zn.0, rows[0].defocus.0),
                (None, None) => (z, d),
            };
            let start = j as f64 * mu;
            let flat = mu - t;
            let k = per.flat;
            for m in 0..k {
                let theta = start + flat * m as f64 / k as f64;
                points.push(point(theta, z, d, v, j, false));
            }
            let rise = Length((zn + dn) - (z + d));
            let speed = path_speed(Speed(v), rise, self.transition_arc()).0;
            let k = per.transition;
            for m in 0..k {
                let f = m as f64 / k as f64;
                let theta = start + flat + t * f;
                points.push(point(
                    theta,
                    z + f * (zn - z),
                    d + f * (dn - d),
                    speed,
                    j,
                    true,
                ));
            }
            end = Some(point(start + mu, zn, dn, speed, j, true));
        }
        points.extend(end);
        Ok(points)
    }
}

/// Equal moves of at most `step` over `span` (both radians), at least one.
fn moves_over(span: f64, step: f64) -> usize {
    (span / step - 1e-9).ceil().max(1.0) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_speed_is_v_over_cos_gamma() {
        // A 1 mm rise over 2° of a 40 mm ring: arc 1.3963 mm, γ = 35.61°.
        let arc = Length(40.0 * 2f64.to_radians());
        assert!((arc.0 - 1.396_263).abs() < 1e-6);
        let gamma = (1.0 / arc.0).atan();
        let v = path_speed(Speed(20.0), Length(1.0), arc);
        assert!((v.0 - 20.0 / gamma.cos()).abs() < 1e-12);
        assert!((v.0 - 24.6).abs() < 0.01, "{v:?}");
        // Flat: unchanged; falling is as fast as rising.
        assert_eq!(path_speed(Speed(5.0), Length(0.0), arc), Speed(5.0));
        assert_eq!(
            path_speed(Speed(5.0), Length(-1.0), arc),
            path_speed(Speed(5.0), Length(1.0), arc)
        );
    }

    #[test]
    fn degenerate_rings_are_refused() {
        let two = Angle::from_deg(2.0);
        assert!(Ring::new(Length(0.0), 10, two).is_err());
        assert!(Ring::new(Length(40.0), 0, two).is_err());
        assert!(Ring::new(Length(40.0), 10, Angle(0.0)).is_err());
        assert_eq!(
            Ring::new(Length(40.0), 180, two),
            Err(Invalid::TransitionTooLong {
                transition_deg: 2.0,
                segment_deg: 2.0
            })
        );
        assert!(Ring::new(Length(40.0), usize::MAX, two).is_err());
        assert!(Ring::new(Length(40.0), 10, two).is_ok());
    }

    #[test]
    fn moves_split_spans_evenly() {
        assert_eq!(moves_over(34f64.to_radians(), 1f64.to_radians()), 34);
        assert_eq!(moves_over(2f64.to_radians(), 5f64.to_radians()), 1);
        assert_eq!(moves_over(2f64.to_radians(), 0.5f64.to_radians()), 4);
    }
}

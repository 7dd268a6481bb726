//! Section outlines in polar form: every section lmdc knows is convex and
//! centred, so it is fully described by its radius at each angle of its frame.
//! The morph between two sections works on that form too.

use crate::units::Length;
use std::f64::consts::PI;

/// A parametric section shape, sizes in mm, centred on its frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Section {
    /// `circle(diameter)`
    Circle {
        /// Radius.
        r: Length,
    },
    /// `ellipse(width, height)`: semi-axes along x and y.
    Ellipse {
        /// Semi-axis along x.
        a: Length,
        /// Semi-axis along y.
        b: Length,
    },
    /// `square(side)`, `rectangle(width, height)`: half sides.
    Rectangle {
        /// Half width (x).
        a: Length,
        /// Half height (y).
        b: Length,
    },
    /// `rounded_rectangle(width, height, radius)`.
    RoundedRectangle {
        /// Half width (x).
        a: Length,
        /// Half height (y).
        b: Length,
        /// Corner radius.
        r: Length,
    },
    /// `polygon(sides, circumradius | side)`: a vertex on +x.
    Polygon {
        /// Number of sides.
        n: u32,
        /// Circumradius.
        r: Length,
    },
}

/// How the section changes from the start to the end shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Morph {
    /// Superellipse whose exponent and semi-axes move linearly between the ends
    /// (circle/ellipse/square/rectangle ends only).
    Superellipse,
    /// Linear blend of the polar radius at each angle.
    Radial,
}

impl Section {
    /// The section offset inward by `d` (for sizes measured at the wall's outer
    /// face: the bead's centre line runs `w/2` inside). Exact for every shape but
    /// the ellipse, whose offset curve is not an ellipse (its semi-axes shrink by
    /// `d`). `None` if nothing is left.
    pub fn inset(self, d: Length) -> Option<Section> {
        let d = d.0;
        let pos = |x: f64| (x > 1e-9).then_some(Length(x));
        Some(match self {
            Section::Circle { r } => Section::Circle { r: pos(r.0 - d)? },
            Section::Ellipse { a, b } => Section::Ellipse {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
            },
            Section::Rectangle { a, b } => Section::Rectangle {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
            },
            Section::RoundedRectangle { a, b, r } => Section::RoundedRectangle {
                a: pos(a.0 - d)?,
                b: pos(b.0 - d)?,
                r: Length((r.0 - d).max(0.0)),
            },
            Section::Polygon { n, r } => {
                // Moving each side in by d moves the vertices in by d / cos(π/n).
                let dr = d / (std::f64::consts::PI / n as f64).cos();
                Section::Polygon {
                    n,
                    r: pos(r.0 - dr)?,
                }
            }
        })
    }
}

/// Distance from the centre to the outline of `s` in direction `theta` (rad,
/// from the section's x axis).
pub fn polar_radius(s: &Section, theta: f64) -> f64 {
    let (sin, cos) = theta.sin_cos();
    match *s {
        Section::Circle { r } => r.0,
        Section::Ellipse { a, b } => superellipse(a.0, b.0, 1.0, cos, sin),
        Section::Rectangle { a, b } => superellipse(a.0, b.0, 0.0, cos, sin),
        Section::RoundedRectangle { a, b, r } => rounded_rect(a.0, b.0, r.0, cos.abs(), sin.abs()),
        Section::Polygon { n, r } => {
            let sector = 2.0 * PI / n as f64;
            let local = theta.rem_euclid(sector) - sector / 2.0;
            r.0 * (sector / 2.0).cos() / local.cos()
        }
    }
}

/// Radius of the superellipse `(|x|/a)^(2/q) + (|y|/b)^(2/q) = 1` in direction
/// (cos, sin). `q = 1` is an ellipse, `q = 0` the rectangle `|x| ≤ a, |y| ≤ b`
/// (the limit of an ever larger exponent). Computed in log space so exponents in
/// the hundreds do not overflow.
pub fn superellipse(a: f64, b: f64, q: f64, cos: f64, sin: f64) -> f64 {
    let u = (cos.abs() / a).ln();
    let v = (sin.abs() / b).ln();
    let (hi, lo) = if u >= v { (u, v) } else { (v, u) };
    if q <= 1e-12 {
        return (-hi).exp();
    }
    let e = 2.0 / q;
    // ln r = -(1/e)·ln(exp(e·u) + exp(e·v)) = -hi - (1/e)·ln(1 + exp(e·(lo-hi)))
    (-hi - (e * (lo - hi)).exp().ln_1p() / e).exp()
}

fn rounded_rect(a: f64, b: f64, r: f64, c: f64, s: f64) -> f64 {
    // Ray from the centre, first quadrant by symmetry: hit the rectangle, then the
    // corner arc if the hit lies in the corner zone.
    let t = if c * b > s * a { a / c } else { b / s };
    let (x, y) = (t * c, t * s);
    let (cx, cy) = (a - r, b - r);
    if r > 0.0 && x > cx && y > cy {
        // |t·d − C|² = r², larger root.
        let bq = c * cx + s * cy;
        let cq = cx * cx + cy * cy - r * r;
        bq + (bq * bq - cq).max(0.0).sqrt()
    } else {
        t
    }
}

/// The superellipse parameters `(a, b, q)` of a section of the circle /
/// ellipse / rectangle family.
fn family(s: &Section) -> Option<(f64, f64, f64)> {
    match *s {
        Section::Circle { r } => Some((r.0, r.0, 1.0)),
        Section::Ellipse { a, b } => Some((a.0, b.0, 1.0)),
        Section::Rectangle { a, b } => Some((a.0, b.0, 0.0)),
        _ => None,
    }
}

/// The section outline at every station between two end sections.
#[derive(Clone, Copy, Debug)]
pub struct Blend {
    from: Section,
    to: Section,
    kind: Morph,
}

impl Blend {
    /// A blend from `from` (station 0) to `to` (station 1). A superellipse
    /// morph between sections outside its family falls back to radial.
    pub fn new(from: Section, to: Section, kind: Morph) -> Self {
        let kind = match (family(&from), family(&to)) {
            (Some(_), Some(_)) => kind,
            _ => Morph::Radial,
        };
        Blend { from, to, kind }
    }

    /// Radius at station `t` (0..1) in direction `theta`.
    pub fn radius(&self, t: f64, theta: f64) -> f64 {
        match (self.kind, family(&self.from), family(&self.to)) {
            (Morph::Superellipse, Some((a0, b0, q0)), Some((a1, b1, q1))) => {
                let (sin, cos) = theta.sin_cos();
                let lerp = |x: f64, y: f64| x + (y - x) * t;
                superellipse(lerp(a0, a1), lerp(b0, b1), lerp(q0, q1), cos, sin)
            }
            _ => {
                let r0 = polar_radius(&self.from, theta);
                let r1 = polar_radius(&self.to, theta);
                r0 + (r1 - r0) * t
            }
        }
    }

    /// The angles (rad, in 0 ..< 2π) where the outline at station `t` has
    /// a corner or, for a superellipse morph short of an ellipse, its
    /// sharpest bend: the points a layer must hold so a chord never cuts a
    /// corner. A radial morph keeps the kinks of both end sections at every
    /// station; a superellipse morph between rectangles has its corners on
    /// the diagonal of the station's own half-sides.
    pub fn corners(&self, t: f64) -> Vec<f64> {
        let diagonal = |a: f64, b: f64| {
            let c = b.atan2(a);
            vec![c, PI - c, PI + c, 2.0 * PI - c]
        };
        match (self.kind, family(&self.from), family(&self.to)) {
            (Morph::Superellipse, Some((a0, b0, q0)), Some((a1, b1, q1))) => {
                let lerp = |x: f64, y: f64| x + (y - x) * t;
                if lerp(q0, q1) < 1.0 - 1e-12 {
                    diagonal(lerp(a0, a1), lerp(b0, b1))
                } else {
                    Vec::new()
                }
            }
            _ => {
                let mut out = Vec::new();
                for s in [&self.from, &self.to] {
                    match *s {
                        Section::Rectangle { a, b } => out.extend(diagonal(a.0, b.0)),
                        Section::Polygon { n, .. } => {
                            out.extend((0..n).map(|j| 2.0 * PI * j as f64 / n as f64))
                        }
                        _ => {}
                    }
                }
                out
            }
        }
    }

    /// Whether every station is a rectangle: a superellipse morph between
    /// two rectangles (its corners move with the half-sides).
    pub fn rectangular(&self) -> bool {
        matches!(
            (self.kind, family(&self.from), family(&self.to)),
            (Morph::Superellipse, Some((_, _, q0)), Some((_, _, q1))) if q0 == 0.0 && q1 == 0.0
        )
    }

    /// The largest radius of either end section (a bound for every station,
    /// since both morphs interpolate between the ends).
    pub fn max_radius(&self) -> f64 {
        let end = |s: &Section| match *s {
            Section::Circle { r } => r.0,
            Section::Ellipse { a, b } => a.0.max(b.0),
            Section::Rectangle { a, b } | Section::RoundedRectangle { a, b, .. } => a.0.hypot(b.0),
            Section::Polygon { r, .. } => r.0,
        };
        end(&self.from).max(end(&self.to))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Length;

    #[test]
    fn square_corner_and_side() {
        let s = Section::Rectangle {
            a: Length(30.0),
            b: Length(30.0),
        };
        assert!((polar_radius(&s, 0.0) - 30.0).abs() < 1e-12);
        assert!((polar_radius(&s, PI / 4.0) - 30.0 * 2f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn superellipse_is_monotone_in_q() {
        // Between circle and square the radius at 45° grows steadily.
        let r = |q: f64| superellipse(30.0, 30.0, q, (PI / 4.0).cos(), (PI / 4.0).sin());
        assert!((r(1.0) - 30.0).abs() < 1e-9);
        assert!(r(0.5) > r(1.0) && r(0.01) > r(0.5) && r(0.0) >= r(0.01));
        assert!(r(1e-3).is_finite());
    }

    #[test]
    fn polygon_vertex_and_apothem() {
        let s = Section::Polygon {
            n: 6,
            r: Length(10.0),
        };
        assert!((polar_radius(&s, 0.0) - 10.0).abs() < 1e-9);
        assert!((polar_radius(&s, PI / 6.0) - 10.0 * (PI / 6.0).cos()).abs() < 1e-9);
    }

    #[test]
    fn rounded_rectangle_corner() {
        let s = Section::RoundedRectangle {
            a: Length(20.0),
            b: Length(20.0),
            r: Length(5.0),
        };
        let d = 15.0 * 2f64.sqrt() + 5.0;
        assert!((polar_radius(&s, PI / 4.0) - d).abs() < 1e-9);
        assert!((polar_radius(&s, 0.0) - 20.0).abs() < 1e-9);
    }
}

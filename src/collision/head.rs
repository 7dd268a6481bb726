//! A machine's head as the collision checks see it: solids of revolution
//! about the beam, each a frustum, stacked from the nozzle's tip up. A
//! point's distance to a solid of revolution is its distance, in the plane
//! through the axis, to the solid's outline there (a trapezoid): a few
//! operations, so a check can afford it for every point near the head.

use crate::ir::Head;

/// One solid of revolution about the beam: from `s[0]` to `s[1]` up the beam
/// from the focus, mm, its radii there `r[0]` and `r[1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Where it starts and ends up the beam from the focus, mm.
    pub s: [f64; 2],
    /// Its radii there, mm.
    pub r: [f64; 2],
}

impl Frustum {
    /// The distance from the point `(s, rho)` — `s` up the beam from the
    /// focus, `rho` from the beam — to the solid, mm (0 inside).
    pub fn distance(&self, s: f64, rho: f64) -> f64 {
        let ([s0, s1], [r0, r1]) = (self.s, self.r);
        if s >= s0 && s <= s1 {
            let t = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
            if rho <= r0 + (r1 - r0) * t {
                return 0.0;
            }
        }
        segment((s, rho), (s0, 0.0), (s0, r0))
            .min(segment((s, rho), (s1, 0.0), (s1, r1)))
            .min(segment((s, rho), (s0, r0), (s1, r1)))
    }
}

/// The distance from `p` to the segment `a`–`b` in the plane.
fn segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a.0 + t * dx - p.0, a.1 + t * dy - p.1);
    (x * x + y * y).sqrt()
}

/// A machine's head: its solids, the gap it keeps, and how far it reaches.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadShape {
    /// From the tip up.
    pub bodies: Vec<Frustum>,
    /// Their names (`nozzle`, `body`, …).
    pub names: Vec<String>,
    /// The least distance kept from anything else, mm.
    pub gap: f64,
    /// The farthest any of its points lies from the focus, mm.
    pub reach: f64,
}

/// A pose of the head: its focus and the unit vector up its beam.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The laser focus, mm.
    pub focus: [f64; 3],
    /// Up the beam, unit.
    pub up: [f64; 3],
}

impl Pose {
    /// How far any point of a head that reaches `reach` mm from its focus
    /// can have moved between this pose and `other`: the focus's move plus
    /// the turn's at that reach (a turn by θ moves a point `R` away by at
    /// most `R·θ`, and `θ ≤ (π/2)·|Δup|`).
    pub fn moved(&self, other: &Pose, reach: f64) -> f64 {
        let d = dist(self.focus, other.focus);
        d + std::f64::consts::FRAC_PI_2 * dist(self.up, other.up) * reach
    }
}

impl HeadShape {
    /// The shape of `head`: its bodies stacked from its tip, `standoff`
    /// up the beam from the focus.
    pub fn of(head: &Head) -> HeadShape {
        let mut s = head.standoff;
        let mut bodies = Vec::with_capacity(head.bodies.len());
        let mut reach: f64 = 0.0;
        for b in &head.bodies {
            let r = [b.diameters[0] / 2.0, b.diameters[1] / 2.0];
            let f = Frustum {
                s: [s, s + b.length],
                r,
            };
            reach = reach.max(f.s[1].hypot(r[0].max(r[1])));
            bodies.push(f);
            s += b.length;
        }
        HeadShape {
            bodies,
            names: head.bodies.iter().map(|b| b.name.clone()).collect(),
            gap: head.gap,
            reach,
        }
    }

    /// The distance from `p` to the head at `pose`, mm (0 inside a body),
    /// and the body nearest it; `None` for a head of no bodies (only a
    /// standoff: refused by the checker, but the verifier runs on to
    /// report every error together).
    pub fn distance(&self, pose: &Pose, p: [f64; 3]) -> Option<(f64, usize)> {
        let v = sub(p, pose.focus);
        let s = dot(v, pose.up);
        let rho = (dot(v, v) - s * s).max(0.0).sqrt();
        let mut best = None;
        for (i, b) in self.bodies.iter().enumerate() {
            let d = b.distance(s, rho);
            if best.is_none_or(|(low, _)| d < low) {
                best = Some((d, i));
            }
        }
        best
    }

    /// The lowest the head reaches along the unit direction `n` (the least
    /// `x·n` of its points) at `pose`, and the body that reaches it: on one
    /// of a body's end circles, the one whose centre is lowest, on the side
    /// the beam leans away from `n`. `None` for a head of no bodies.
    pub fn lowest(&self, pose: &Pose, n: [f64; 3]) -> Option<(f64, usize)> {
        let c = dot(pose.up, n);
        let across = (1.0 - c * c).max(0.0).sqrt();
        let base = dot(pose.focus, n);
        let mut best = None;
        for (i, b) in self.bodies.iter().enumerate() {
            for k in 0..2 {
                let low = base + b.s[k] * c - b.r[k] * across;
                if best.is_none_or(|(l, _)| low < l) {
                    best = Some((low, i));
                }
            }
        }
        best
    }

    /// The lowest the head reaches along `n` at `pose` ([`Self::lowest`]),
    /// mm; never, for a head of no bodies.
    pub fn lowest_along(&self, pose: &Pose, n: [f64; 3]) -> f64 {
        self.lowest(pose, n).map_or(f64::INFINITY, |l| l.0)
    }

    /// The distance from `p` to the head at `pose` ([`Self::distance`]),
    /// mm; none, for a head of no bodies.
    pub fn distance_to(&self, pose: &Pose, p: [f64; 3]) -> f64 {
        self.distance(pose, p).map_or(f64::INFINITY, |d| d.0)
    }

    /// A sphere round the head at `pose`: its centre and radius, mm.
    pub fn bound(&self, pose: &Pose) -> ([f64; 3], f64) {
        let top = self.bodies.last().map_or(0.0, |b| b.s[1]);
        let bottom = self.bodies.first().map_or(0.0, |b| b.s[0]);
        let mid = (top + bottom) / 2.0;
        let r = self
            .bodies
            .iter()
            .map(|b| b.r[0].max(b.r[1]))
            .fold(0.0, f64::max);
        let centre = add(pose.focus, scale(pose.up, mid));
        (centre, ((top - bottom) / 2.0).hypot(r))
    }
}

// Three-vector arithmetic, for the checks' own few lines (nalgebra's
// types would only be converted to and from).

/// `a − b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a + b`.
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `k·a`.
pub fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

/// `a·b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `|a − b|`.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn head() -> HeadShape {
        HeadShape::of(&Head::typical())
    }

    #[test]
    fn the_typical_head_stacks_from_its_standoff() {
        let h = head();
        assert_eq!(h.bodies[0].s, [15.0, 60.0]);
        assert_eq!(h.bodies[1].s, [60.0, 160.0]);
        assert_eq!(h.bodies[1].r, [30.0, 30.0]);
        assert!((h.reach - 160f64.hypot(30.0)).abs() < 1e-9);
    }

    /// The plan's own bounds of how low and how wide a tilted head hangs
    /// about its focus (`ir::Head::lowest_above_focus`, `spread`) against
    /// points sampled on the solids' rims here: the lowest exactly, the
    /// spread never short.
    #[test]
    fn the_plans_hang_and_spread_bound_the_sampled_rims() {
        let typical = Head::typical();
        let h = HeadShape::of(&typical);
        for deg in [0.0f64, 10.0, 30.0, 50.0, 70.0, 85.0] {
            let t = deg.to_radians();
            let up = [t.sin(), 0.0, t.cos()];
            let side = [t.cos(), 0.0, -t.sin()];
            let (mut low, mut wide) = (f64::INFINITY, 0.0f64);
            for b in &h.bodies {
                for k in 0..2 {
                    for j in 0..3600 {
                        let a = std::f64::consts::TAU * f64::from(j) / 3600.0;
                        let (sa, ca) = a.sin_cos();
                        let p = add(
                            scale(up, b.s[k]),
                            add(scale(side, b.r[k] * ca), [0.0, b.r[k] * sa, 0.0]),
                        );
                        low = low.min(p[2]);
                        wide = wide.max(p[0].hypot(p[1]));
                    }
                }
            }
            let plan_low = typical.lowest_above_focus(up[2]);
            assert!((plan_low - low).abs() < 1e-3, "{deg}°: {plan_low} vs {low}");
            let pose = Pose {
                focus: [0.0; 3],
                up,
            };
            assert!((h.lowest_along(&pose, [0.0, 0.0, 1.0]) - plan_low).abs() < 1e-9);
            let spread = typical.spread(up[2]);
            assert!(spread >= wide - 1e-9, "{deg}°: {spread} vs {wide}");
            assert!(spread <= wide + 31.0, "{deg}°: {spread} vs {wide}");
        }
    }

    #[test]
    fn points_below_beside_and_inside() {
        let h = head();
        let pose = Pose {
            focus: [0.0; 3],
            up: [0.0, 0.0, 1.0],
        };
        // Straight below the tip: the standoff less the point's height.
        assert!((h.distance_to(&pose, [0.0, 0.0, 5.0]) - 10.0).abs() < 1e-12);
        // Inside the body.
        assert_eq!(h.distance(&pose, [10.0, 0.0, 100.0]), Some((0.0, 1)));
        // Beside the body, 10 mm out from its side.
        assert!((h.distance_to(&pose, [40.0, 0.0, 100.0]) - 10.0).abs() < 1e-12);
        // The lowest point along +Z is the tip.
        assert!((h.lowest_along(&pose, [0.0, 0.0, 1.0]) - 15.0).abs() < 1e-12);
    }

    proptest! {
        /// A point pushed out from a body's slanted side along the
        /// outline's normal by `d` is `d` away (no farther, where the body
        /// above is nearer).
        #[test]
        fn the_outline_distance_is_euclidean(
            t in 0.0f64..1.0,
            d in 0.0f64..20.0,
            turn in 0.0f64..std::f64::consts::TAU,
            tilt in 0.0f64..1.2,
        ) {
            let h = head();
            let b = h.bodies[0];
            // On the slanted side, then outward along its normal in (s, ρ).
            let s = b.s[0] + t * (b.s[1] - b.s[0]);
            let r = b.r[0] + t * (b.r[1] - b.r[0]);
            let (ds, dr) = (b.s[1] - b.s[0], b.r[1] - b.r[0]);
            let len = ds.hypot(dr);
            let (ns, nr) = (-dr / len, ds / len);
            let (s, rho) = (s + d * ns, r + d * nr);
            let up = [tilt.sin(), 0.0, tilt.cos()];
            let side = [tilt.cos() * turn.cos(), turn.sin(), -tilt.sin() * turn.cos()];
            let pose = Pose { focus: [1.0, 2.0, 3.0], up };
            let p = add(add(pose.focus, scale(up, s)), scale(side, rho));
            let got = h.distance_to(&pose, p);
            // The body above may be nearer near the top edge.
            prop_assert!(got <= d + 1e-9, "{got} vs {d}");
            if t < 0.9 && d < 5.0 {
                prop_assert!((got - d).abs() < 1e-9, "{got} vs {d}");
            }
        }
    }
}

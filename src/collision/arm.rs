//! A robot's arm as the collision checks see it: its links as capsules
//! hung on the frames of its forward kinematics
//! ([`crate::plan::arm::Solver::joint_points`]), and the solids of the cell
//! they keep clear of — a positioner's faceplate (a disc), the fixtures (a
//! box, an upright cylinder) — each a closed-form point distance searched
//! along the capsule's axis ([`super::capsule`]); a mesh fixture by its
//! surface samples, in a tree of spheres ([`super::sample_tree`]).

use super::capsule::{box_point, cylinder_point, least_along, segment_point, Capsule};
use super::head::{dot, sub, Frustum, Pose};
use super::sample_tree::SampleTree;
use crate::ir::{Fixture, FixtureShape};
use nalgebra::{Isometry3, Point3};
use std::sync::Arc;

/// The links' names: the three whose radii a model gives
/// ([`crate::target::arm::Model::links`]) in that order, then the column
/// ([`crate::target::arm::Model::column`]) and the tool.
pub const LINKS: [&str; 5] = ["upper arm", "forearm", "wrist", "column", "tool"];

/// The index in [`LINKS`] of the upper arm.
pub const UPPER_ARM: usize = 0;
/// The index in [`LINKS`] of the wrist.
pub const WRIST: usize = 2;
/// The index in [`LINKS`] of the column.
pub const COLUMN: usize = 3;
/// The index in [`LINKS`] of the tool.
pub const TOOL: usize = 4;

/// The column's capsules at the frames' origins `p`: from the robot's
/// foot (its frame's origin) up A1's axis to the shoulder's height, then
/// on to the A2 axis, of radius `r`.
pub fn column(p: &[[f64; 3]; 6], r: f64) -> [Capsule; 2] {
    [
        Capsule {
            a: [0.0; 3],
            b: p[0],
            r,
        },
        Capsule {
            a: p[0],
            b: p[1],
            r,
        },
    ]
}

/// The least distance between two capsules (negative where they
/// overlap): the segments' distance, convex along either, less both radii.
pub fn capsule_capsule(c: &Capsule, d: &Capsule) -> f64 {
    least_along(c.a, c.b, |p| segment_point(d.a, d.b, p)).0 - c.r - d.r
}

/// The least distance from a head's body `b` at `pose` to the capsule `c`
/// (negative where the capsule's axis runs inside it, by the radius): a
/// point's distance to a solid of revolution is convex, so a search along
/// the capsule's axis finds it.
pub fn body_capsule(b: &Frustum, pose: &Pose, c: &Capsule) -> f64 {
    let at = |p: [f64; 3]| {
        let v = sub(p, pose.focus);
        let s = dot(v, pose.up);
        let rho = (dot(v, v) - s * s).max(0.0).sqrt();
        b.distance(s, rho)
    };
    least_along(c.a, c.b, at).0 - c.r
}

/// The arm's capsules at the frames' origins `p`
/// ([`crate::plan::arm::Solver::joint_points`]) with the links' radii
/// `radii`: each with the index of its link in [`LINKS`]. The upper arm
/// runs from the shoulder to the elbow, the forearm from the elbow past
/// its offset to the wrist centre (two capsules), the wrist from there to
/// the flange.
pub fn capsules(p: &[[f64; 3]; 6], radii: [f64; 3]) -> [(usize, Capsule); 4] {
    let cap = |a: usize, b: usize, link: usize| {
        (
            link,
            Capsule {
                a: p[a],
                b: p[b],
                r: radii[link],
            },
        )
    };
    [cap(1, 2, 0), cap(2, 3, 1), cap(3, 4, 1), cap(4, 5, 2)]
}

/// A solid of the cell in a frame of its own.
#[derive(Clone, Debug)]
pub enum Solid {
    /// A box, its sides along the frame's axes, mm.
    Box {
        /// Its least corner.
        lo: [f64; 3],
        /// Its greatest corner.
        hi: [f64; 3],
    },
    /// A cylinder about the frame's Z through `(x, y)`, from `z[0]` to
    /// `z[1]`, of radius `r`, mm. A faceplate is one: its face at `z = 0`,
    /// its thickness below.
    Cylinder {
        /// Its axis's X and Y.
        xy: [f64; 2],
        /// Its ends along Z.
        z: [f64; 2],
        /// Its radius.
        r: f64,
    },
    /// A mesh's surface as samples ([`super::surface`]), within its box.
    Mesh {
        /// Its box's least corner.
        lo: [f64; 3],
        /// Its box's greatest corner.
        hi: [f64; 3],
        /// The largest sample's radius: how far past the box a sample
        /// reaches, mm.
        tolerance: f64,
        /// The samples.
        tree: Arc<SampleTree>,
    },
}

impl Solid {
    /// A fixture's solid, in the part's coordinates: a mesh's is its
    /// surface samples, each a point and the radius it stands for (never
    /// farther from the link than the mesh is; nearer by at most the
    /// samples' `tolerance`, docs/collision.md).
    pub fn of(f: &Fixture) -> Solid {
        match &f.shape {
            FixtureShape::Box { .. } => {
                let (lo, hi) = f.bounds();
                Solid::Box { lo, hi }
            }
            FixtureShape::Mesh {
                samples, tolerance, ..
            } => {
                let (lo, hi) = f.bounds();
                Solid::Mesh {
                    lo,
                    hi,
                    tolerance: *tolerance,
                    tree: Arc::new(SampleTree::new(&samples.0, f.at)),
                }
            }
            &FixtureShape::Cylinder { diameter, length } => Solid::Cylinder {
                xy: [f.at[0], f.at[1]],
                z: [f.at[2], f.at[2] + length],
                r: diameter / 2.0,
            },
        }
    }

    /// A faceplate `diameter` across and `thickness` thick, its face on
    /// the frame's `z = 0`, round its Z axis.
    pub fn faceplate(diameter: f64, thickness: f64) -> Solid {
        Solid::Cylinder {
            xy: [0.0, 0.0],
            z: [-thickness, 0.0],
            r: diameter / 2.0,
        }
    }

    /// The distance from `p` to it, mm (0 inside; a mesh's, by its
    /// samples: negative inside one).
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        match self {
            Solid::Box { lo, hi } => box_point(*lo, *hi, p),
            &Solid::Cylinder { xy, z, r } => {
                let rho = (p[0] - xy[0]).hypot(p[1] - xy[1]);
                cylinder_point(p[2], rho, z, r)
            }
            Solid::Mesh { tree, .. } => tree
                .least_to_segment(p, p, f64::INFINITY)
                .unwrap_or(f64::INFINITY),
        }
    }

    /// A sphere round it: its centre and radius, mm.
    pub fn bound(&self) -> ([f64; 3], f64) {
        match *self {
            Solid::Box { lo, hi } => {
                let c = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
                let h = sub(hi, c);
                (c, dot(h, h).sqrt())
            }
            Solid::Mesh { ref tree, .. } => tree.bound(),
            Solid::Cylinder { xy, z, r } => (
                [xy[0], xy[1], (z[0] + z[1]) / 2.0],
                r.hypot((z[1] - z[0]) / 2.0),
            ),
        }
    }

    /// The distance from the capsule `c` (in the robot's frame) to it,
    /// its frame's pose being `frame` in the robot's: `None` where the
    /// spheres round both say it is farther than `beyond`.
    pub fn capsule(&self, frame_inv: &Isometry3<f64>, c: &Capsule, beyond: f64) -> Option<f64> {
        let local = |p: [f64; 3]| {
            let q = frame_inv * Point3::from(p);
            [q.x, q.y, q.z]
        };
        let (a, b) = (local(c.a), local(c.b));
        let (centre, r) = self.bound();
        if segment_point(a, b, centre) - r - c.r > beyond {
            return None;
        }
        if let Solid::Mesh {
            lo,
            hi,
            tolerance,
            tree,
        } = self
        {
            // Its box first (a sample's centre lies on the surface, or
            // merged within its radius of it: its sphere reaches past the
            // box by twice its radius at most), then the samples near the
            // axis.
            let boxed = least_along(a, b, |p| box_point(*lo, *hi, p)).0 - 2.0 * tolerance;
            if boxed - c.r > beyond {
                return None;
            }
            return Some(tree.least_to_segment(a, b, beyond + c.r)? - c.r);
        }
        Some(least_along(a, b, |p| self.distance(p)).0 - c.r)
    }

    /// The diameter, at most `diameter`, a faceplate of `thickness` (as
    /// [`Solid::faceplate`]) may have and keep `keep` from the capsule `c`
    /// (in its frame): found by halving, to 0.01 mm; `None` where not
    /// even its centre keeps it.
    pub fn faceplate_keeping(c: &Capsule, thickness: f64, diameter: f64, keep: f64) -> Option<f64> {
        let clear = |d: f64| {
            least_along(c.a, c.b, |p| Solid::faceplate(d, thickness).distance(p)).0 - c.r >= keep
        };
        if !clear(0.0) {
            return None;
        }
        if clear(diameter) {
            return Some(diameter);
        }
        Some(super::bisect(0.0, diameter, 0.01, clear))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::arm::Solver;
    use crate::target::arm::CATALOGUE;

    /// The links hang where the forward kinematics puts the wrist centre
    /// and the flange: the wrist's capsule ends `c4` from the wrist centre,
    /// at the flange the solver's own forward kinematics gives.
    #[test]
    fn links_end_at_the_flange() {
        for m in CATALOGUE {
            let s = Solver::with(
                m.arm(0.0, 5.0),
                Isometry3::identity(),
                Isometry3::identity(),
            );
            for j in [
                s.upright(),
                [30.0, -60.0, 70.0, 40.0, 50.0, -20.0],
                [-100.0, -120.0, 120.0, -90.0, -40.0, 180.0],
            ] {
                let p = s.joint_points(&j);
                let f = s.forward_flange(&j).translation.vector;
                assert!((p[5][0] - f.x).abs() < 1e-6 && (p[5][2] - f.z).abs() < 1e-6);
                let c4 = super::super::head::dist(p[4], p[5]);
                assert!((c4 - m.opw.c4).abs() < 1e-6, "{}", m.key);
                let upper = super::super::head::dist(p[1], p[2]);
                assert!((upper - m.opw.c2).abs() < 1e-6, "{}", m.key);
                let caps = capsules(&p, m.links);
                assert_eq!(caps[3].1.r, m.links[2]);
                // One pass of the forward kinematics gives the same.
                let (q, tcp) = s.joint_frames(&j);
                assert_eq!(q, p);
                let d = tcp.translation.vector - s.tcp(&j).translation.vector;
                assert!(d.norm() < 1e-9 && tcp.rotation.angle_to(&s.tcp(&j).rotation) < 1e-9);
            }
        }
    }

    /// A faceplate's distance to a capsule over its rim, and the diameter
    /// that keeps a gap from it.
    #[test]
    fn faceplate_distances() {
        let plate = Solid::faceplate(600.0, 40.0);
        // Level, 100 mm above the face, reaching 50 mm past the rim.
        let c = Capsule {
            a: [250.0, 0.0, 100.0],
            b: [350.0, 0.0, 100.0],
            r: 60.0,
        };
        let d = plate.capsule(&Isometry3::identity(), &c, 1e9).unwrap();
        assert!((d - 40.0).abs() < 1e-6, "{d}");
        // Upright beside the rim, 30 mm off it.
        let c = Capsule {
            a: [330.0 + 20.0, 0.0, -100.0],
            b: [350.0, 0.0, 100.0],
            r: 20.0,
        };
        let d = plate.capsule(&Isometry3::identity(), &c, 1e9).unwrap();
        assert!((d - 30.0).abs() < 1e-6, "{d}");
        // To keep 50 mm, the rim must draw back 20 mm: 560 mm across.
        let keep = Solid::faceplate_keeping(&c, 40.0, 600.0, 50.0).unwrap();
        assert!((keep - 560.0).abs() < 0.02, "{keep}");
        // Far away: culled.
        let far = Capsule {
            a: [5000.0, 0.0, 0.0],
            b: [5100.0, 0.0, 0.0],
            r: 10.0,
        };
        assert_eq!(plate.capsule(&Isometry3::identity(), &far, 100.0), None);
    }

    /// Points sampled every 1/2000 of a segment.
    fn sampled(a: [f64; 3], b: [f64; 3]) -> impl Iterator<Item = [f64; 3]> {
        (0..=2000).map(move |k| {
            let t = f64::from(k) / 2000.0;
            std::array::from_fn(|i| a[i] + t * (b[i] - a[i]))
        })
    }

    proptest::proptest! {
        /// Two capsules' distance against one axis sampled every 1/2000
        /// of it, each point's distance to the other axis by projection:
        /// never above it, below it by no more than the step.
        #[test]
        fn capsules_apart_as_sampled(
            a in proptest::array::uniform3(-500.0f64..500.0),
            b in proptest::array::uniform3(-500.0f64..500.0),
            c in proptest::array::uniform3(-500.0f64..500.0),
            d in proptest::array::uniform3(-500.0f64..500.0),
            r in 1.0f64..100.0,
        ) {
            let (p, q) = (Capsule { a, b, r }, Capsule { a: c, b: d, r: r / 2.0 });
            let got = capsule_capsule(&p, &q);
            let step = super::super::head::dist(a, b) / 2000.0;
            let want = sampled(a, b)
                .map(|x| segment_point(c, d, x))
                .fold(f64::INFINITY, f64::min)
                - 1.5 * r;
            proptest::prop_assert!(got <= want + 1e-6, "{} vs {}", got, want);
            proptest::prop_assert!(got >= want - step - 1e-6, "{} vs {}", got, want);
        }

        /// A head's nozzle (a frustum 12 mm across at its tip, 40 mm at
        /// its top, 45 mm long, 15 mm up the beam) against a capsule: its
        /// axis sampled every 1/2000, each point's distance to the cone
        /// by its (s, ρ) outline.
        #[test]
        fn a_body_and_a_capsule_apart_as_sampled(
            c in proptest::array::uniform3(-200.0f64..200.0),
            d in proptest::array::uniform3(-200.0f64..200.0),
            tilt in 0.0f64..3.0,
            r in 1.0f64..50.0,
        ) {
            let body = Frustum { s: [15.0, 60.0], r: [6.0, 20.0] };
            let pose = Pose { focus: [3.0, -2.0, 1.0], up: [tilt.sin(), 0.0, tilt.cos()] };
            let cap = Capsule { a: c, b: d, r };
            let got = body_capsule(&body, &pose, &cap);
            let step = super::super::head::dist(c, d) / 2000.0;
            let want = sampled(c, d)
                .map(|p| {
                    let v = sub(p, pose.focus);
                    let s = dot(v, pose.up);
                    body.distance(s, (dot(v, v) - s * s).max(0.0).sqrt())
                })
                .fold(f64::INFINITY, f64::min)
                - r;
            proptest::prop_assert!(got <= want + 1e-6, "{} vs {}", got, want);
            proptest::prop_assert!(got >= want - step - 1e-6, "{} vs {}", got, want);
        }
    }

    /// Every catalogue arm upright (KUKA's home, ABB's zero) keeps its wrist clear of its
    /// upper arm and its column (the non-adjacent pairs checked); folded
    /// (A3 at its upper limit, A5 bent back), the KR 60 HA's wrist comes
    /// within its radius and the upper arm's of the upper arm's axis,
    /// as the points' own distance says.
    #[test]
    fn home_is_clear_and_a_folded_arm_is_not() {
        for m in CATALOGUE {
            let s = Solver::with(
                m.arm(0.0, 5.0),
                Isometry3::identity(),
                Isometry3::identity(),
            );
            let p = s.joint_points(&s.upright());
            let caps = capsules(&p, m.links);
            let wrist = caps[3].1;
            assert!(capsule_capsule(&wrist, &caps[0].1) > 0.0, "{}", m.key);
            for col in column(&p, m.column) {
                assert!(capsule_capsule(&wrist, &col) > 0.0, "{}", m.key);
            }
        }
        let m = crate::target::arm::model("kr60ha").unwrap();
        let s = Solver::with(
            m.arm(0.0, 5.0),
            Isometry3::identity(),
            Isometry3::identity(),
        );
        let p = s.joint_points(&[0.0, -90.0, 158.0, 0.0, 110.0, 0.0]);
        let caps = capsules(&p, m.links);
        let d = capsule_capsule(&caps[3].1, &caps[0].1);
        let axes = segment_point(p[1], p[2], p[5]).min(segment_point(p[1], p[2], p[4]));
        assert!(d <= axes - 190.0 - 100.0 + 1e-9, "{d} vs {axes}");
        assert!(d < 0.0, "{d}");
    }
}

//! A mesh fixture's surface samples ([`super::surface`]: points, each with
//! the radius it stands for) in a tree of bounding spheres, so that the
//! least distance from a segment — a link's axis — to them costs a few
//! distance computations, not one per sample (docs/collision.md, *The
//! arm*).
//!
//! Each node holds a run of the samples, split at the median of its box's
//! longest side until a leaf holds at most 8; its sphere holds every
//! sample's own (its centre the run's box's, its radius the farthest
//! sample's distance plus that sample's radius). A sphere's distance to the
//! segment less its radius bounds every sample in it from below, so a
//! search walks the nearer child first and drops every node that bound puts
//! past the best so far (or past what the caller cares about). Built in
//! `O(n log n)`, searched in about `O(log n)` nodes near the segment.

use super::capsule::segment_point;

/// Most samples a leaf holds.
const LEAF: usize = 8;

/// One node: its sphere, its run of samples, its children.
#[derive(Clone, Copy, Debug)]
struct Node {
    centre: [f64; 3],
    radius: f64,
    /// The run of [`SampleTree::samples`] it holds.
    run: [u32; 2],
    /// Its two children's indices; 0 for a leaf (the root is no one's
    /// child).
    kids: [u32; 2],
}

/// Samples `[x, y, z, r]` in a tree of bounding spheres (module docs).
#[derive(Clone, Debug, Default)]
pub struct SampleTree {
    samples: Vec<[f64; 4]>,
    nodes: Vec<Node>,
}

impl SampleTree {
    /// The tree of `samples`, each moved by `at` (a fixture's place).
    pub fn new(samples: &[[f64; 4]], at: [f64; 3]) -> SampleTree {
        let mut t = SampleTree {
            samples: samples
                .iter()
                .map(|s| [s[0] + at[0], s[1] + at[1], s[2] + at[2], s[3]])
                .collect(),
            nodes: Vec::new(),
        };
        if !t.samples.is_empty() {
            t.split(0, t.samples.len());
        }
        t
    }

    /// How many samples it holds.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    /// The sphere round every sample's own: its centre and radius, mm
    /// (none: a point at the origin).
    pub fn bound(&self) -> ([f64; 3], f64) {
        self.nodes
            .first()
            .map_or(([0.0; 3], 0.0), |n| (n.centre, n.radius))
    }

    /// Whether it holds none.
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// Makes the node of the samples `from..to` (and its children's):
    /// its index.
    fn split(&mut self, from: usize, to: usize) -> u32 {
        let run = &mut self.samples[from..to];
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for s in run.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(s[k]);
                hi[k] = hi[k].max(s[k]);
            }
        }
        let centre: [f64; 3] = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
        let radius = run
            .iter()
            .map(|s| dist(centre, [s[0], s[1], s[2]]) + s[3])
            .fold(0.0, f64::max);
        let me = self.nodes.len();
        self.nodes.push(Node {
            centre,
            radius,
            run: [from as u32, to as u32],
            kids: [0, 0],
        });
        if to - from > LEAF {
            let axis = (0..3)
                .max_by(|a, b| (hi[*a] - lo[*a]).total_cmp(&(hi[*b] - lo[*b])))
                .unwrap_or(0);
            let half = (to - from) / 2;
            self.samples[from..to].select_nth_unstable_by(half, |a, b| a[axis].total_cmp(&b[axis]));
            let left = self.split(from, from + half);
            let right = self.split(from + half, to);
            self.nodes[me].kids = [left, right];
        }
        me as u32
    }

    /// The least over the samples of the segment `a`–`b`'s distance to
    /// each less its radius (never more than the segment's distance to the
    /// surface they stand for), where it is at most `beyond`; `None` where
    /// every sample lies farther (mm).
    pub fn least_to_segment(&self, a: [f64; 3], b: [f64; 3], beyond: f64) -> Option<f64> {
        self.search(a, b, beyond).0
    }

    /// [`SampleTree::least_to_segment`], and how many samples it measured.
    fn search(&self, a: [f64; 3], b: [f64; 3], beyond: f64) -> (Option<f64>, usize) {
        if self.nodes.is_empty() {
            return (None, 0);
        }
        let mut best = f64::INFINITY;
        let mut measured = 0;
        let mut stack = vec![0u32];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            let bound = segment_point(a, b, node.centre) - node.radius;
            if bound > beyond || bound >= best {
                continue;
            }
            if node.kids[0] == 0 {
                let run = &self.samples[node.run[0] as usize..node.run[1] as usize];
                measured += run.len();
                for s in run {
                    best = best.min(segment_point(a, b, [s[0], s[1], s[2]]) - s[3]);
                }
                continue;
            }
            // The nearer child is searched first (pushed last).
            let [l, r] = node.kids;
            let near = |k: u32| {
                let c = &self.nodes[k as usize];
                segment_point(a, b, c.centre) - c.radius
            };
            if near(l) <= near(r) {
                stack.extend([r, l]);
            } else {
                stack.extend([l, r]);
            }
        }
        ((best <= beyond).then_some(best), measured)
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::super::surface::{sample, Triangle};
    use super::*;

    /// The least distance from `p` to triangle `t` (its closest point by
    /// the regions of its corners and sides, Ericson's).
    fn point_triangle(p: [f64; 3], t: &Triangle) -> f64 {
        let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
        let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        let at = |u: f64, v: f64| {
            std::array::from_fn::<f64, 3, _>(|k| {
                t[0][k] + u * (t[1][k] - t[0][k]) + v * (t[2][k] - t[0][k])
            })
        };
        let (ab, ac, ap) = (sub(t[1], t[0]), sub(t[2], t[0]), sub(p, t[0]));
        let (d1, d2) = (dot(ab, ap), dot(ac, ap));
        if d1 <= 0.0 && d2 <= 0.0 {
            return dist(p, t[0]);
        }
        let bp = sub(p, t[1]);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            return dist(p, t[1]);
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            return dist(p, at(d1 / (d1 - d3), 0.0));
        }
        let cp = sub(p, t[2]);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        if d6 >= 0.0 && d5 <= d6 {
            return dist(p, t[2]);
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            return dist(p, at(0.0, d2 / (d2 - d6)));
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            return dist(p, at(1.0 - w, w));
        }
        let den = 1.0 / (va + vb + vc);
        dist(p, at(vb * den, vc * den))
    }

    /// An L of two plates 60 mm wide: a floor 100 mm long at z = 0 and a
    /// wall 80 mm tall at x = 0 — its box's far upper corner is empty.
    fn l_shape() -> Vec<Triangle> {
        let quad = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| [[a, b, c], [a, c, d]];
        let mut t = Vec::new();
        t.extend(quad(
            [0.0, 0.0, 0.0],
            [100.0, 0.0, 0.0],
            [100.0, 60.0, 0.0],
            [0.0, 60.0, 0.0],
        ));
        t.extend(quad(
            [0.0, 0.0, 0.0],
            [0.0, 60.0, 0.0],
            [0.0, 60.0, 80.0],
            [0.0, 0.0, 80.0],
        ));
        t
    }

    proptest::proptest! {
        /// A segment's least distance to the samples of an L, by the tree,
        /// against the triangles' own: the segment sampled every 1/4000 of
        /// it, each point's exact distance to each triangle. The tree is
        /// never farther than the surface, nearer by at most the samples'
        /// tolerance (and the sampling's step); and it is the same least a
        /// walk over every sample finds.
        #[test]
        fn the_trees_least_is_the_triangles_within_the_tolerance(
            a in proptest::array::uniform3(-150.0f64..250.0),
            b in proptest::array::uniform3(-150.0f64..250.0),
        ) {
            let tris = l_shape();
            let s = sample(&tris);
            let tree = SampleTree::new(&s.samples, [0.0; 3]);
            let got = tree.least_to_segment(a, b, f64::INFINITY).unwrap();
            let every = s
                .samples
                .iter()
                .map(|q| segment_point(a, b, [q[0], q[1], q[2]]) - q[3])
                .fold(f64::INFINITY, f64::min);
            proptest::prop_assert!((got - every).abs() < 1e-9, "{} vs {}", got, every);
            let n = 4000;
            let step = dist(a, b) / f64::from(n);
            let brute = (0..=n)
                .map(|k| {
                    let t = f64::from(k) / f64::from(n);
                    let p = std::array::from_fn(|i| a[i] + t * (b[i] - a[i]));
                    tris.iter().map(|tr| point_triangle(p, tr)).fold(f64::INFINITY, f64::min)
                })
                .fold(f64::INFINITY, f64::min);
            proptest::prop_assert!(got <= brute + 1e-9, "{} vs {}", got, brute);
            proptest::prop_assert!(
                got >= brute - s.tolerance - step - 1e-9,
                "{} vs {} (tolerance {})", got, brute, s.tolerance
            );
            // What lies farther than asked is not searched for.
            if got > 1.0 {
                proptest::prop_assert_eq!(tree.least_to_segment(a, b, got - 1.0), None);
            }
        }
    }

    /// Through the L's empty corner: 20 mm from the wall and the floor,
    /// though inside their box. The tree measures a few hundred of its
    /// thousands of samples (those along the segment's nearest lines on
    /// the two plates), and none for a segment far from it.
    #[test]
    fn a_segment_through_the_empty_corner_is_clear() {
        let s = sample(&l_shape());
        let tree = SampleTree::new(&s.samples, [10.0, 0.0, 0.0]);
        assert!(tree.len() > 4000, "{}", tree.len());
        let (got, measured) = tree.search([30.0, -50.0, 20.0], [30.0, 110.0, 20.0], 100.0);
        let got = got.unwrap();
        assert!(got <= 20.0 && got >= 20.0 - s.tolerance, "{got}");
        assert!(measured < tree.len() / 5, "{measured} of {}", tree.len());
        let (far, measured) = tree.search([500.0, 0.0, 0.0], [600.0, 0.0, 0.0], 100.0);
        assert_eq!((far, measured), (None, 0));
    }
}

//! The nearest point of a triangle mesh to a point: the triangles in a
//! tree of bounding boxes, searched nearer child first, dropping every box
//! farther than the best so far. What the registration of a scan to its
//! nominal asks for every point of every iteration ([`super::register`]).
//!
//! A crate of its own was weighed: parry3d (the geometric queries the
//! project guide names) works since 0.30 in glam, not in the nalgebra 0.34
//! lmdc uses, in `f32` unless its `f64` twin is taken, and brings its
//! spatial indexes and triangulator into a build this project keeps
//! short. This tree is the one query it needs.
//!
//! Each node holds a run of the triangles, split at the median of their
//! centres along its box's longest side until a leaf holds at most
//! four. Built in `O(n log n)`, deterministic (ties broken by the
//! corners themselves).

/// Most triangles a leaf holds.
const LEAF: usize = 4;

/// A triangle's corners, mm.
pub type Tri = [[f64; 3]; 3];

/// One node: its box, its run of triangles, its children (0 for a leaf:
/// the root is no one's child).
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    run: [u32; 2],
    kids: [u32; 2],
}

/// What [`TriangleTree::nearest`] finds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// The nearest point of the mesh, mm.
    pub point: [f64; 3],
    /// The unit normal of the triangle it lies on (by its corners' order).
    pub normal: [f64; 3],
    /// Its distance, mm.
    pub distance: f64,
}

/// Triangles in a tree of bounding boxes (module docs).
#[derive(Clone, Debug, Default)]
pub struct TriangleTree {
    tris: Vec<Tri>,
    normals: Vec<[f64; 3]>,
    nodes: Vec<Node>,
}

impl TriangleTree {
    /// The tree of `tris`, less those with no area (or not finite).
    pub fn new(tris: &[Tri]) -> TriangleTree {
        let mut kept: Vec<(Tri, [f64; 3])> = tris
            .iter()
            .filter_map(|t| {
                let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
                let len = dot(n, n).sqrt();
                (len.is_finite() && len > 1e-12).then(|| (*t, n.map(|c| c / len)))
            })
            .collect();
        let mut tree = TriangleTree::default();
        if kept.is_empty() {
            return tree;
        }
        let n = kept.len();
        tree.split(&mut kept, 0, n);
        (tree.tris, tree.normals) = kept.into_iter().unzip();
        tree
    }

    /// How many triangles it holds.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Whether it holds none.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Its box: the least and greatest x, y and z of its corners (zeros
    /// when empty).
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        self.nodes
            .first()
            .map_or(([0.0; 3], [0.0; 3]), |n| (n.lo, n.hi))
    }

    /// Builds the node of `tris[a..b]` (reordering them) and its children;
    /// returns its index.
    fn split(&mut self, tris: &mut [(Tri, [f64; 3])], a: usize, b: usize) -> u32 {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (t, _) in &tris[a..b] {
            for c in t {
                for k in 0..3 {
                    lo[k] = lo[k].min(c[k]);
                    hi[k] = hi[k].max(c[k]);
                }
            }
        }
        let me = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            run: [a as u32, b as u32],
            kids: [0, 0],
        });
        if b - a > LEAF {
            let axis = (0..3)
                .max_by(|&i, &j| (hi[i] - lo[i]).total_cmp(&(hi[j] - lo[j])))
                .unwrap_or(0);
            let centre = |t: &Tri| t[0][axis] + t[1][axis] + t[2][axis];
            let mid = (a + b) / 2;
            // Ties by the corners themselves: the same input, the same tree.
            tris[a..b].select_nth_unstable_by(mid - a, |x, y| {
                centre(&x.0).total_cmp(&centre(&y.0)).then_with(|| {
                    x.0.iter()
                        .flatten()
                        .zip(y.0.iter().flatten())
                        .fold(std::cmp::Ordering::Equal, |o, (p, q)| {
                            o.then(p.total_cmp(q))
                        })
                })
            });
            let left = self.split(tris, a, mid);
            let right = self.split(tris, mid, b);
            self.nodes[me].kids = [left, right];
        }
        me as u32
    }

    /// The nearest point of the mesh to `p`, if it has a triangle.
    pub fn nearest(&self, p: [f64; 3]) -> Option<Nearest> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: Option<(f64, [f64; 3], u32)> = None;
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let node = self.nodes[i as usize];
            let bound = box_sq(node.lo, node.hi, p);
            if best.is_some_and(|b| bound >= b.0) {
                continue;
            }
            if node.kids == [0, 0] {
                for k in node.run[0]..node.run[1] {
                    let q = closest(&self.tris[k as usize], p);
                    let d = dist_sq(p, q);
                    if best.is_none_or(|b| d < b.0) {
                        best = Some((d, q, k));
                    }
                }
                continue;
            }
            // The nearer child last, so that it is searched first.
            let [l, r] = node.kids;
            let dl = box_sq(self.nodes[l as usize].lo, self.nodes[l as usize].hi, p);
            let dr = box_sq(self.nodes[r as usize].lo, self.nodes[r as usize].hi, p);
            if dl <= dr {
                stack.extend([r, l]);
            } else {
                stack.extend([l, r]);
            }
        }
        best.map(|(d, point, k)| Nearest {
            point,
            normal: self.normals[k as usize],
            distance: d.sqrt(),
        })
    }
}

impl TriangleTree {
    /// How far along the segment from `from` along the unit vector `dir`,
    /// up to `len` mm, it first crosses a triangle (from either side), and
    /// that triangle's unit normal (by its corners' order), if it does.
    pub fn first_hit(&self, from: [f64; 3], dir: [f64; 3], len: f64) -> Option<(f64, [f64; 3])> {
        if self.nodes.is_empty() || len.is_nan() || len < 0.0 {
            return None;
        }
        let inv = dir.map(|c| 1.0 / c);
        let mut best: Option<(f64, u32)> = None;
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let node = self.nodes[i as usize];
            let reach = best.map_or(len, |b| b.0);
            if !slab(node.lo, node.hi, from, inv, reach) {
                continue;
            }
            if node.kids == [0, 0] {
                for k in node.run[0]..node.run[1] {
                    if let Some(t) = crossing(&self.tris[k as usize], from, dir) {
                        if t <= best.map_or(len, |b| b.0) {
                            best = Some((t, k));
                        }
                    }
                }
            } else {
                stack.extend(node.kids);
            }
        }
        best.map(|(t, k)| (t, self.normals[k as usize]))
    }
}

/// Whether the segment from `from` along the direction whose components'
/// inverses are `inv`, `0..=len` along it, meets the box `lo..hi`.
fn slab(lo: [f64; 3], hi: [f64; 3], from: [f64; 3], inv: [f64; 3], len: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, len);
    for k in 0..3 {
        let (a, b) = ((lo[k] - from[k]) * inv[k], (hi[k] - from[k]) * inv[k]);
        // A direction square to the axis gives ±inf (or NaN on a face):
        // inside the slab, any t; outside, none.
        let (a, b) = if a.is_nan() || b.is_nan() {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (a.min(b), a.max(b))
        };
        t0 = t0.max(a);
        t1 = t1.min(b);
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// Where the ray from `from` along `dir` crosses triangle `t`, `t ≥ 0`
/// along it (Möller–Trumbore); a ray in the triangle's plane crosses none.
fn crossing(t: &Tri, from: [f64; 3], dir: [f64; 3]) -> Option<f64> {
    let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let p = cross(dir, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-12 * dot(e1, e1).max(dot(e2, e2)) {
        return None;
    }
    let s = sub(from, t[0]);
    let u = dot(s, p) / det;
    if !(-1e-9..=1.0 + 1e-9).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(dir, q) / det;
    if v < -1e-9 || u + v > 1.0 + 1e-9 {
        return None;
    }
    let along = dot(e2, q) / det;
    (along >= 0.0).then_some(along)
}

/// The squared distance from `p` to the box `lo..hi`.
fn box_sq(lo: [f64; 3], hi: [f64; 3], p: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0).powi(2))
        .sum()
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dist_sq(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d)
}

/// `a + s·u + t·v`.
fn at(a: [f64; 3], u: [f64; 3], s: f64, v: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + s * u[k] + t * v[k])
}

/// The point of triangle `t` nearest `p`: by the region of the triangle's
/// plane `p` projects into (its corners', its edges' or its inside;
/// Ericson, *Real-Time Collision Detection*, 5.1.5).
pub(crate) fn closest(t: &Tri, p: [f64; 3]) -> [f64; 3] {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return at(a, ab, d1 / (d1 - d3), ac, 0.0);
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return at(a, ab, 0.0, ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return at(b, sub(c, b), w, ab, 0.0);
    }
    let denom = 1.0 / (va + vb + vc);
    at(a, ab, vb * denom, ac, vc * denom)
}

/// A closed box `lo..hi` as 12 triangles, faces out (for the tests).
#[cfg(test)]
pub(crate) fn block(lo: [f64; 3], hi: [f64; 3]) -> Vec<Tri> {
    let c = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    quads
        .iter()
        .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_point_of_a_block_by_region() {
        let tree = TriangleTree::new(&block([0.0; 3], [10.0, 4.0, 2.0]));
        assert_eq!(tree.len(), 12);
        // Over the top face: straight down, the top's normal up.
        let n = tree.nearest([3.0, 1.0, 5.0]).unwrap();
        assert_eq!(n.point, [3.0, 1.0, 2.0]);
        assert_eq!(n.normal, [0.0, 0.0, 1.0]);
        assert!((n.distance - 3.0).abs() < 1e-12);
        // Beyond an edge and a corner.
        let e = tree.nearest([12.0, 2.0, 4.0]).unwrap();
        assert!(dist_sq(e.point, [10.0, 2.0, 2.0]) < 1e-20, "{e:?}");
        let k = tree.nearest([-1.0, -1.0, -1.0]).unwrap();
        assert!(dist_sq(k.point, [0.0; 3]) < 1e-20, "{k:?}");
        // Inside: the nearest face.
        let i = tree.nearest([9.5, 2.0, 1.0]).unwrap();
        assert!(dist_sq(i.point, [10.0, 2.0, 1.0]) < 1e-20, "{i:?}");
        assert_eq!(i.normal, [1.0, 0.0, 0.0]);
    }

    #[test]
    fn a_tree_of_many_agrees_with_every_triangle_tried() {
        // A wavy sheet of 2 × 40 × 40 triangles; points around it.
        let z = |x: f64, y: f64| (x * 0.3).sin() + (y * 0.2).cos();
        let mut tris = Vec::new();
        for j in 0..40 {
            for i in 0..40 {
                let (x, y) = (i as f64, j as f64);
                let p = |dx: f64, dy: f64| [x + dx, y + dy, z(x + dx, y + dy)];
                tris.push([p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
                tris.push([p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
            }
        }
        tris.push([[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]); // no area
        let tree = TriangleTree::new(&tris);
        assert_eq!(tree.len(), 3200);
        for k in 0..200 {
            let f = k as f64;
            let p = [
                (f * 7.31) % 45.0 - 2.0,
                (f * 3.77) % 45.0 - 2.0,
                (f * 0.61) % 5.0 - 2.5,
            ];
            let brute = tris[..3200]
                .iter()
                .map(|t| dist_sq(p, closest(t, p)))
                .fold(f64::INFINITY, f64::min);
            let d = tree.nearest(p).unwrap().distance;
            assert!(
                (d * d - brute).abs() < 1e-9,
                "{p:?}: {d} vs {}",
                brute.sqrt()
            );
        }
        assert!(TriangleTree::new(&[]).nearest([0.0; 3]).is_none());
    }

    #[test]
    fn a_segment_first_crosses_the_nearest_face_along_it() {
        let tree = TriangleTree::new(&block([0.0; 3], [10.0, 4.0, 2.0]));
        // Down onto the top from 3 mm over it; not when 2 mm is all it goes.
        let down = [0.0, 0.0, -1.0];
        let (t, n) = tree.first_hit([3.0, 1.0, 5.0], down, 10.0).unwrap();
        assert!((t - 3.0).abs() < 1e-12, "{t}");
        assert_eq!(n, [0.0, 0.0, 1.0]);
        assert!(tree.first_hit([3.0, 1.0, 5.0], down, 2.0).is_none());
        // Slanting onto the +x side from beside it: 45° down toward -x.
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let (t, n) = tree
            .first_hit([12.0, 2.0, 3.5], [-s, 0.0, -s], 10.0)
            .unwrap();
        assert!((t - 2.0 / s).abs() < 1e-9, "{t}");
        assert_eq!(n, [1.0, 0.0, 0.0]);
        // From inside, the face it leaves by; along an axis past the block,
        // none (its direction's other components are zero).
        let (t, _) = tree
            .first_hit([5.0, 2.0, 1.0], [1.0, 0.0, 0.0], 100.0)
            .unwrap();
        assert!((t - 5.0).abs() < 1e-12, "{t}");
        assert!(tree
            .first_hit([5.0, 6.0, 1.0], [1.0, 0.0, 0.0], 100.0)
            .is_none());
        assert!(TriangleTree::new(&[])
            .first_hit([0.0; 3], down, 1.0)
            .is_none());
    }
}

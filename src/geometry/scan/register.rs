//! Registration: the scan moved onto its nominal (the part as designed, a
//! triangle mesh in the part's coordinates) by a best fit, the worn region
//! and the stray returns left out (docs/repair.md, *Registration*).
//!
//! **The fit** is point-to-plane ICP: each iteration takes every point's
//! nearest point on the nominal ([`TriangleTree`]) and the normal of the
//! triangle it lies on, and solves in closed form for the small turn `ω`
//! and shift `t` that bring the kept points nearest their planes in the
//! least-squares sense — the linearised 6 × 6 normal equations, the turn
//! about the kept points' centroid — then turns by `ω` exactly.
//!
//! **What is kept** (the inliers): the points within `limit` of the
//! nominal, where `limit` is the greater of
//! - three robust deviations `3σ̂`, `σ̂` the distance a quarter of the
//!   points kept by the last limit lie within, over 0.3186 — for scanner
//!   noise alone, the noise's standard deviation (the quarter quantile of
//!   a half-normal is 0.3186 σ); the worn points beyond the last limit do
//!   not widen it, and it holds while up to about half the points are
//!   worn or stray, as a median's would not past a half;
//! - a start that halves as the fit settles: at first the distance nine
//!   points in ten of the scan lie within (a placement a few mm off keeps
//!   its sides, which fix the scan along the nominal's faces, rather than
//!   only the points already near), then half of it, a quarter, …, each
//!   once a step moves no point more than a tenth of the limit (so the
//!   points kept are fitted before the limit shrinks past any of them:
//!   a limit shrunk faster keeps only the points that agree with the
//!   place reached, and they hold it there);
//! - [`FLOOR`], finer than scanners measure.
//!
//! **Bounded work**: at most [`MAX_FIT_POINTS`] points, every `k`-th of the
//! file's (the same ones every run), and [`MAX_ITERATIONS`] iterations.
//! The fit has **settled** when the halving start no longer sets the limit
//! and the last step moved no point by more than [`SETTLED`].
//!
//! A fit is refused ([`FitFault`]) when it does not settle, keeps fewer
//! than [`MIN_INLIERS`] points, or when the kept points leave a motion free
//! (a flat nominal lets the scan slide along it and turn about its normal).

use super::nearest::{cross, dot, sub, Tri, TriangleTree};
use super::{Pose, Raw};
use nalgebra::{Matrix6, Rotation3, SymmetricEigen, Vector3, Vector6};

/// Most points the fit uses.
pub const MAX_FIT_POINTS: usize = 50_000;

/// Most iterations.
pub const MAX_ITERATIONS: usize = 50;

/// Fewest points the fit must keep.
pub const MIN_INLIERS: usize = 100;

/// The least limit, mm: finer than scanners measure (a noiseless scan's
/// limit would shrink to nothing, each step keeping only the points that
/// agree with where it is).
pub const FLOOR: f64 = 0.01;

/// A step that moves no point farther than this has settled, mm.
pub const SETTLED: f64 = 0.001;

/// The quarter quantile of `|N(0, 1)|`: `Φ⁻¹(0.625)`.
const QUARTER: f64 = 0.318_639;

/// How many robust deviations a kept point may lie from the nominal.
const DEVIATIONS: f64 = 3.0;

/// The start halves once a step moves no point more than this share of
/// the limit.
const TIGHTEN: f64 = 0.1;

/// A motion whose stiffness is below this share of the stiffest is free.
const FREE: f64 = 1e-3;

/// A rigid move `p ↦ rot·p + shift` (mm), about the part's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rigid {
    /// The turn.
    pub rot: Rotation3<f64>,
    /// The shift after it, mm.
    pub shift: Vector3<f64>,
}

impl Rigid {
    /// No move.
    pub fn identity() -> Rigid {
        Rigid {
            rot: Rotation3::identity(),
            shift: Vector3::zeros(),
        }
    }

    /// `p` moved.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let q = self.rot * Vector3::from(p) + self.shift;
        [q.x, q.y, q.z]
    }

    /// This move, then `m`.
    pub fn then(&self, m: &Rigid) -> Rigid {
        Rigid {
            rot: m.rot * self.rot,
            shift: m.rot * self.shift + m.shift,
        }
    }

    /// The turn as angles about x, then y, then z (rad), as `turn` is
    /// written.
    pub fn angles(&self) -> [f64; 3] {
        let (x, y, z) = self.rot.euler_angles();
        [x, y, z]
    }
}

/// A best fit that settled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The move found, after the declared placement.
    pub moved: Rigid,
    /// RMS of the kept points' distances to the nominal, mm.
    pub rms: f64,
    /// The farthest kept point's distance, mm.
    pub max: f64,
    /// The points kept.
    pub inliers: usize,
    /// The points fitted (at most [`MAX_FIT_POINTS`]).
    pub points: usize,
    /// The iterations taken.
    pub iterations: usize,
    /// The limit the kept points lie within, mm.
    pub limit: f64,
}

impl Fit {
    /// The share of the fitted points kept, 0–1.
    pub fn share(&self) -> f64 {
        self.inliers as f64 / self.points.max(1) as f64
    }
}

/// A motion the kept points leave free: the nominal's surface under them
/// does not fix it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Freedom {
    /// Sliding along a direction (a unit vector).
    Slide([f64; 3]),
    /// Turning about a direction through the kept points' centroid.
    Turn([f64; 3]),
}

/// Why a scan cannot be registered.
#[derive(Clone, Debug, PartialEq)]
pub enum FitFault {
    /// The nominal has no triangle with an area.
    NoNominal,
    /// No face of the nominal lies near the scan as placed (within the
    /// reach [`Nominal::near`] looks).
    NoneNear,
    /// Fewer than [`MIN_INLIERS`] points lie within the limit.
    TooFewInliers {
        /// The points kept.
        inliers: usize,
        /// The points fitted.
        points: usize,
        /// The limit, mm.
        limit: f64,
    },
    /// Still moving after [`MAX_ITERATIONS`].
    NotSettled {
        /// The iterations taken.
        iterations: usize,
        /// How far the last step moved a point, mm.
        step: f64,
    },
    /// The kept points leave these motions free.
    Undetermined {
        /// The motions.
        free: Vec<Freedom>,
        /// The points kept.
        inliers: usize,
    },
}

/// The nominal's triangles, placed in the part's coordinates. The fit
/// asks its faces near the scan ([`Nominal::near`]).
#[derive(Clone, Debug, Default)]
pub struct Nominal {
    tris: Vec<Tri>,
}

/// How far round the scan's points the fit looks for the nominal's faces:
/// half the points' box's diagonal, and at least this, mm.
pub const NEAR_LEAST: f64 = 10.0;

/// Most faces the fit's tree holds once the nominal is cut near the scan:
/// past it the faces are kept as they are (a slower search, not more
/// memory).
pub const MAX_NEAR_FACES: usize = 1_000_000;

impl Nominal {
    /// The nominal of `tris` (mm, placed); triangles without area left out.
    pub fn new(tris: &[Tri]) -> Nominal {
        let tris = tris
            .iter()
            .filter(|t| {
                let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
                let len = dot(n, n).sqrt();
                len.is_finite() && len > 1e-12
            })
            .copied()
            .collect();
        Nominal { tris }
    }

    /// How many triangles it holds.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Whether it holds none.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Its faces near `pts`, in a tree: those whose box meets the points'
    /// box grown by its reach (half its diagonal, at least [`NEAR_LEAST`]),
    /// each cut in two across its longest edge until no edge is longer
    /// than half the reach or the piece leaves the box. A long thin face
    /// (a plate's cap cut by earcut between far holes) has a box that
    /// overlaps every other's and slows every search; cut and clipped,
    /// the faces about a point are the few that pass near it, and a
    /// nominal far larger than the scan costs what the part of it round
    /// the scan does. The fit moves the scan by far less than the reach,
    /// and a point farther than that from every face is no inlier.
    pub fn near(&self, pts: &[[f64; 3]]) -> TriangleTree {
        let Some((lo, hi, reach)) = near_box(pts) else {
            return TriangleTree::default();
        };
        let longest = reach / 2.0;
        let meets = |t: &Tri| {
            (0..3).all(|k| t.iter().any(|p| p[k] >= lo[k]) && t.iter().any(|p| p[k] <= hi[k]))
        };
        let mut todo: Vec<Tri> = self.tris.iter().filter(|t| meets(t)).copied().collect();
        let mut out = Vec::with_capacity(todo.len());
        while let Some(t) = todo.pop() {
            let (k, len) = longest_edge(&t);
            // Across its longest edge a sliver is narrower than an eighth of it.
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            let sliver = dot(n, n).sqrt() < len * len / 8.0;
            if !sliver || len <= longest || out.len() + todo.len() >= MAX_NEAR_FACES {
                out.push(t);
                continue;
            }
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let m = [0, 1, 2].map(|i| (a[i] + b[i]) / 2.0);
            todo.extend([[a, m, c], [m, b, c]].into_iter().filter(|t| meets(t)));
        }
        TriangleTree::new(&out)
    }
}

/// The box round `pts` the fit looks for the nominal's faces in: theirs
/// grown by half its diagonal (at least [`NEAR_LEAST`]), and that reach.
pub fn near_box(pts: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3], f64)> {
    let (lo, hi) = bounds(pts)?;
    let diagonal = dot(sub(hi, lo), sub(hi, lo)).sqrt();
    let reach = (diagonal / 2.0).max(NEAR_LEAST);
    Some((lo.map(|c| c - reach), hi.map(|c| c + reach), reach))
}

/// The box of `pts`, if any.
fn bounds(pts: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let first = *pts.first()?;
    Some(pts.iter().fold((first, first), |(lo, hi), p| {
        (
            [0, 1, 2].map(|k| lo[k].min(p[k])),
            [0, 1, 2].map(|k| hi[k].max(p[k])),
        )
    }))
}

/// The longest edge of `t`: the corner it starts at and its length.
fn longest_edge(t: &Tri) -> (usize, f64) {
    (0..3)
        .map(|k| {
            let d = sub(t[(k + 1) % 3], t[k]);
            (k, dot(d, d).sqrt())
        })
        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a })
}

/// Each point's distance to the nominal, its nearest point and normal.
type Matches = Vec<(f64, [f64; 3], [f64; 3])>;

/// The best fit of `raw`'s points, placed by `pose`, to `nominal`: the move
/// to apply after `pose` (module docs).
pub fn register(raw: &Raw, pose: &Pose, nominal: &Nominal) -> Result<Fit, FitFault> {
    register_within(raw, pose, nominal, MAX_ITERATIONS)
}

/// [`register`] in at most `most` iterations (the tests' way to a fit
/// that has not settled).
fn register_within(
    raw: &Raw,
    pose: &Pose,
    nominal: &Nominal,
    most: usize,
) -> Result<Fit, FitFault> {
    if nominal.is_empty() {
        return Err(FitFault::NoNominal);
    }
    let stride = raw.vertices.len().div_ceil(MAX_FIT_POINTS).max(1);
    let mut pts: Vec<[f64; 3]> = raw
        .vertices
        .iter()
        .step_by(stride)
        .map(|v| pose.apply(v))
        .collect();
    let tree = nominal.near(&pts);
    if tree.is_empty() {
        return Err(FitFault::NoneNear);
    }
    let mut moved = Rigid::identity();
    let mut m = matches(&pts, &tree);
    let mut start = quantile(&m, 0.9, f64::INFINITY);
    let mut limit = f64::INFINITY;
    let (mut settled, mut iterations, mut step) = (false, 0, f64::INFINITY);
    while iterations < most {
        let rule = robust_limit(&m, limit);
        limit = rule.max(start);
        iterations += 1;
        let Some(inc) = solve(&pts, &m, limit, false).ok() else {
            break;
        };
        step = displacement(&pts, &inc);
        for p in &mut pts {
            *p = inc.apply(*p);
        }
        moved = moved.then(&inc);
        m = matches(&pts, &tree);
        if step <= SETTLED && rule >= start {
            settled = true;
            break;
        }
        // Nearly settled at this limit (the points kept will hardly
        // change): half of it next.
        if step <= limit * TIGHTEN {
            start /= 2.0;
        }
    }
    let limit = robust_limit(&m, limit);
    let kept: Vec<f64> = m.iter().map(|x| x.0).filter(|d| *d <= limit).collect();
    if kept.len() < MIN_INLIERS {
        return Err(FitFault::TooFewInliers {
            inliers: kept.len(),
            points: pts.len(),
            limit,
        });
    }
    if !settled {
        return Err(FitFault::NotSettled { iterations, step });
    }
    if let Err(free) = solve(&pts, &m, limit, true) {
        return Err(FitFault::Undetermined {
            free,
            inliers: kept.len(),
        });
    }
    let rms = (kept.iter().map(|d| d * d).sum::<f64>() / kept.len() as f64).sqrt();
    Ok(Fit {
        moved,
        rms,
        max: kept.iter().copied().fold(0.0, f64::max),
        inliers: kept.len(),
        points: pts.len(),
        iterations,
        limit,
    })
}

/// Every point's match on the nominal (a point with none, an empty
/// nominal's, lies infinitely far).
fn matches(pts: &[[f64; 3]], tree: &TriangleTree) -> Matches {
    pts.iter()
        .map(|p| {
            tree.nearest(*p)
                .map_or((f64::INFINITY, *p, [0.0, 0.0, 1.0]), |n| {
                    (n.distance, n.point, n.normal)
                })
        })
        .collect()
}

/// The distance a share `q` of the points within `within` lie within.
fn quantile(m: &Matches, q: f64, within: f64) -> f64 {
    let mut d: Vec<f64> = m
        .iter()
        .map(|x| x.0)
        .filter(|d| d.is_finite() && *d <= within)
        .collect();
    if d.is_empty() {
        return 0.0;
    }
    let k = ((d.len() - 1) as f64 * q).round() as usize;
    let (_, v, _) = d.select_nth_unstable_by(k, f64::total_cmp);
    *v
}

/// Three robust deviations of the distances of the points kept by the
/// last limit (`last`), at least [`FLOOR`]: for noise alone, about three
/// of its standard deviations whatever `last` was (a limit too tight
/// grows back, one too wide shrinks), and the worn points beyond it do
/// not widen it.
fn robust_limit(m: &Matches, last: f64) -> f64 {
    (DEVIATIONS * quantile(m, 0.25, last) / QUARTER).max(FLOOR)
}

/// How far the move `inc` takes the farthest of `pts`, mm.
fn displacement(pts: &[[f64; 3]], inc: &Rigid) -> f64 {
    pts.iter()
        .map(|p| {
            let q = inc.apply(*p);
            (Vector3::from(q) - Vector3::from(*p)).norm()
        })
        .fold(0.0, f64::max)
}

/// The point-to-plane step of the points within `limit`: the least-squares
/// small turn (about their centroid) and shift, solved in the motions the
/// points fix (the others left still). With `check`, the motions they leave
/// free are returned as the error instead.
fn solve(pts: &[[f64; 3]], m: &Matches, limit: f64, check: bool) -> Result<Rigid, Vec<Freedom>> {
    let kept: Vec<usize> = (0..pts.len()).filter(|&i| m[i].0 <= limit).collect();
    if kept.len() < 6 {
        return Err(Vec::new());
    }
    let n = kept.len() as f64;
    let c = kept
        .iter()
        .fold(Vector3::zeros(), |s, &i| s + Vector3::from(pts[i]))
        / n;
    // The turn's columns scaled by the points' RMS radius: all six in mm.
    let radius = (kept
        .iter()
        .map(|&i| (Vector3::from(pts[i]) - c).norm_squared())
        .sum::<f64>()
        / n)
        .sqrt()
        .max(1e-9);
    let (mut a, mut b) = (Matrix6::<f64>::zeros(), Vector6::<f64>::zeros());
    for &i in &kept {
        let (p, q, nrm) = (
            Vector3::from(pts[i]),
            Vector3::from(m[i].1),
            Vector3::from(m[i].2),
        );
        let arm = (p - c).cross(&nrm) / radius;
        let row = Vector6::new(arm.x, arm.y, arm.z, nrm.x, nrm.y, nrm.z);
        a += row * row.transpose();
        b -= row * (p - q).dot(&nrm);
    }
    let eig = SymmetricEigen::new(a);
    let top = eig.eigenvalues.iter().copied().fold(0.0, f64::max);
    let mut u = Vector6::zeros();
    let mut free = Vec::new();
    for k in 0..6 {
        let (l, v) = (eig.eigenvalues[k], eig.eigenvectors.column(k).into_owned());
        if l.is_nan() || l <= FREE * top {
            free.push(freedom(&v));
            continue;
        }
        u += v * (v.dot(&b) / l);
    }
    if check && !free.is_empty() {
        return Err(free);
    }
    if !u.iter().all(|x| x.is_finite()) {
        return Err(free);
    }
    let w = Vector3::new(u[0], u[1], u[2]) / radius;
    let t = Vector3::new(u[3], u[4], u[5]);
    let rot = Rotation3::new(w);
    Ok(Rigid {
        rot,
        shift: c + t - rot * c,
    })
}

/// A free motion of the step's unknowns `v` (turn scaled, then shift): a
/// slide where its shift outweighs its turn, else a turn.
fn freedom(v: &Vector6<f64>) -> Freedom {
    let (turn, shift) = (
        Vector3::new(v[0], v[1], v[2]),
        Vector3::new(v[3], v[4], v[5]),
    );
    let unit = |x: Vector3<f64>| {
        let mut d = x.normalize();
        // One sign for a direction: its largest part positive.
        let k = d.iamax();
        if d[k] < 0.0 {
            d = -d;
        }
        [d.x, d.y, d.z]
    };
    if shift.norm() >= turn.norm() {
        Freedom::Slide(unit(shift))
    } else {
        Freedom::Turn(unit(turn))
    }
}

#[cfg(test)]
mod tests;

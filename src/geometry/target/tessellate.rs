//! A target solid as triangles: the faces a scan is fitted to when
//! `register` names a solid of the file (docs/repair.md,
//! *Registration*). The fit asks for the nearest point of a triangle mesh
//! ([`crate::geometry::scan::register`]), so the solid is cut into one:
//!
//! - **a prism** (an extrusion of a shape to a height): its loops
//!   flattened within [`CHORD`], a pair of triangles up each edge, and its
//!   top and bottom cut by earcut (its holes bridged in);
//! - **an extrusion of a mesh**: the mesh's own faces, upright ones too;
//! - **a loft**: its outline sampled at angles and stations, each pair of
//!   neighbours two triangles, and its end sections cut in rings toward
//!   the spine (every section lmdc knows is convex and centred). The
//!   angles are the end sections' corners and an even spread, each gap
//!   halved while its chord strays more than [`CHORD`] from the outline
//!   at one of 33 stations; the stations are doubled until the chord
//!   between two neighbours strays at most [`CHORD`] from the loft along
//!   it (a straight, untwisted loft's radial blend is straight between
//!   its ends: one interval). At most [`MAX_QUADS`] pieces: a loft so
//!   large that its faces need more is cut that finely and no finer.
//!
//! The faces close the solid and face out of it (a prism's holes and a
//! loft's ends too), so the volume they hold is the solid's: what the
//! tests check them by. The fit itself asks only for their planes.

use super::{Inner, Target, Turned};
use crate::geometry::region::Region;
use crate::geometry::scan::nearest::{closest, Tri};
use crate::geometry::{LoftGeometry, SectionFrame};
use nalgebra::Vector3;
use std::f64::consts::TAU;

/// How far (mm) a chord may stray from the solid's faces where the cut
/// is refined: the programs' resolution, a tenth of the fit's finest
/// limit (the triangles between chords stay within twice it).
pub const CHORD: f64 = 0.001;

/// Most quadrilaterals a loft's side is cut into (two triangles each,
/// 72 bytes a triangle: about 36 MB).
pub const MAX_QUADS: usize = 250_000;

/// The most rings an end section is cut into.
const CAP_RINGS: usize = 32;

/// The fewest angles round a loft's outline.
const MIN_ANGLES: usize = 64;

/// The most angles round a loft's outline.
const MAX_ANGLES: usize = 8192;

/// How many stations, evenly spread from end to end, a loft's outline is
/// checked at while its angles are chosen (a superellipse morph's bends
/// sharpen toward a rectangle's end).
const PROBES: usize = 33;

impl Target {
    /// The solid's faces as triangles (mm, in the target's frame), within
    /// 0.002 mm of them (module docs).
    pub fn triangles(&self) -> Vec<Tri> {
        self.triangles_near(None)
    }

    /// [`Target::triangles`], or, given a box seen from above (`[lo, hi]`,
    /// mm), a prism's without the loops whose own box lies outside it: a
    /// best fit looks for faces near the scan only, and a plate's
    /// thousand holes far from it would cost the cutting of its caps
    /// (earcut bridges every hole into the outline) for nothing. The caps
    /// within the box are the same: every loop that reaches into it is
    /// kept.
    pub fn triangles_near(&self, near: Option<[[f64; 2]; 2]>) -> Vec<Tri> {
        match self {
            Target::Prism { region, height } => prism(region, *height, near),
            Target::Mesh(m) => m.faces().copied().collect(),
            Target::Loft(l) => loft(&l.geometry),
            Target::Turned(t) => t.triangles(),
        }
    }
}

impl Turned {
    /// The inner target's triangles turned as the target is.
    fn triangles(&self) -> Vec<Tri> {
        let inner = match &self.inner {
            Inner::Mesh(m) => m.faces().copied().collect(),
            Inner::Solid(t) => t.triangles(),
        };
        let turn = |p: [f64; 3]| {
            let q = self.rot * Vector3::from(p);
            [q.x, q.y, q.z]
        };
        inner.into_iter().map(|t| t.map(turn)).collect()
    }
}

/// Whether the box of the polyline `pts` meets `near` (or there is none).
fn reaches(pts: &[[f64; 2]], near: Option<[[f64; 2]; 2]>) -> bool {
    let Some([lo, hi]) = near else {
        return true;
    };
    let (mut a, mut b) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pts {
        for k in 0..2 {
            a[k] = a[k].min(p[k]);
            b[k] = b[k].max(p[k]);
        }
    }
    (0..2).all(|k| a[k] <= hi[k] && b[k] >= lo[k])
}

/// A prism of `region` from z = 0 to `h`: its sides, top and bottom;
/// without the loops whose box lies outside `near` ([`Target::triangles_near`]).
fn prism(region: &Region, h: f64, near: Option<[[f64; 2]; 2]>) -> Vec<Tri> {
    let mut out = Vec::new();
    for (l, hole) in region.loops() {
        let mut pts = l.polyline(CHORD);
        if !reaches(&pts, near) {
            continue;
        }
        // Every loop is stored counter-clockwise: a hole's is turned so
        // its sides face into it, out of the solid.
        if hole {
            pts.reverse();
        }
        for (i, a) in pts.iter().enumerate() {
            let b = pts[(i + 1) % pts.len()];
            let (a0, b0) = ([a[0], a[1], 0.0], [b[0], b[1], 0.0]);
            let (a1, b1) = ([a[0], a[1], h], [b[0], b[1], h]);
            out.push([a0, b0, b1]);
            out.push([a0, b1, a1]);
        }
    }
    let mut cut = earcut::Earcut::<f64>::new();
    let mut idx: Vec<u32> = Vec::new();
    for outer in region.outer() {
        let mut pts = outer.polyline(CHORD);
        if !reaches(&pts, near) {
            continue;
        }
        let mut holes: Vec<u32> = Vec::new();
        // A hole is the outer loop's that holds it (an island in a hole
        // holds none of the hole's points).
        for hole in region.holes() {
            let hp = hole.polyline(CHORD);
            if !reaches(&hp, near) {
                continue;
            }
            if hp.first().is_some_and(|p| outer.contains(*p)) {
                holes.push(pts.len() as u32);
                pts.extend(hp);
            }
        }
        cut.earcut(pts.iter().copied(), &holes, &mut idx);
        let at = |i: u32, z: f64| {
            let p = pts[i as usize];
            [p[0], p[1], z]
        };
        for t in idx.chunks_exact(3) {
            // The top faces up, the bottom down, whichever way earcut wound.
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| pts[i as usize]);
            let ccw = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) >= 0.0;
            let (u, v) = if ccw { (t[1], t[2]) } else { (t[2], t[1]) };
            out.push([at(t[0], h), at(u, h), at(v, h)]);
            out.push([at(t[0], 0.0), at(v, 0.0), at(u, 0.0)]);
        }
    }
    out
}

/// A loft's side and end sections (module docs).
fn loft(g: &LoftGeometry) -> Vec<Tri> {
    // An untwisted loft whose stations are all rectangles is its corners,
    // wherever they move: its sides are ruled between them.
    let corners = g.twist == 0.0 && g.blend.rectangular();
    let angles = if corners { Vec::new() } else { angles(g) };
    let ring_at = |s: f64| {
        let f = g.frame(s);
        if corners {
            ring(g, &f, s, &g.blend.corners(s))
        } else {
            ring(g, &f, s, &angles)
        }
    };
    let stations = if corners {
        let mid_at = |s: f64| halves(&ring_at(s));
        stations(&ring_at, &mid_at, MAX_QUADS / 4)
    } else {
        let every = angles.len().div_ceil(512).max(1);
        let probe: Vec<f64> = angles.iter().step_by(every).copied().collect();
        let mids: Vec<f64> = (0..probe.len())
            .map(|j| 0.5 * (probe[j] + probe.get(j + 1).copied().unwrap_or(probe[0] + TAU)))
            .collect();
        let probe_at = |s: f64| ring(g, &g.frame(s), s, &probe);
        let mid_at = |s: f64| ring(g, &g.frame(s), s, &mids);
        stations(&probe_at, &mid_at, (MAX_QUADS / angles.len()).max(1))
    };
    let rings: Vec<Vec<Vector3<f64>>> = stations.iter().map(|&s| ring_at(s)).collect();
    // Between twisted stations a side's points are not on the plane of
    // its corners: a twisted loft keeps every angle.
    let rings = if g.twist == 0.0 && !corners {
        let mids: Vec<Vec<Vector3<f64>>> = stations
            .windows(2)
            .map(|w| ring_at(0.5 * (w[0] + w[1])))
            .collect();
        straightened(rings, &mids)
    } else {
        rings
    };
    let m = rings[0].len();
    let p = |v: &Vector3<f64>| [v.x, v.y, v.z];
    let mut out = Vec::with_capacity(2 * m * stations.len());
    for w in rings.windows(2) {
        let (lo, hi) = (&w[0], &w[1]);
        for j in 0..m {
            let k = (j + 1) % m;
            out.push([p(&lo[j]), p(&lo[k]), p(&hi[k])]);
            out.push([p(&lo[j]), p(&hi[k]), p(&hi[j])]);
        }
    }
    let last = rings.len() - 1;
    for (s, r, up) in [(0.0, &rings[0], false), (1.0, &rings[last], true)] {
        cap(g.frame(s).spine.origin.coords, r, up, &mut out);
    }
    out
}

/// The middle of each side of a closed polygon (from each point to the
/// next).
fn halves(r: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    (0..r.len())
        .map(|j| 0.5 * (r[j] + r[(j + 1) % r.len()]))
        .collect()
}

/// An end section: rings of its outline shrunk toward its centre `c`
/// (about as far apart as the outline's points, at most [`CAP_RINGS`]),
/// so the triangles are not the slivers a fan from the centre would be,
/// whose boxes all overlap there and slow every nearest-point search.
/// Facing along the spine at the far end (`up`), against it at the
/// start.
fn cap(c: Vector3<f64>, outline: &[Vector3<f64>], up: bool, out: &mut Vec<Tri>) {
    let m = outline.len();
    let p = |v: Vector3<f64>| [v.x, v.y, v.z];
    let reach = outline.iter().map(|q| (q - c).norm()).fold(0.0, f64::max);
    let edge = (0..m)
        .map(|j| (outline[(j + 1) % m] - outline[j]).norm())
        .sum::<f64>()
        / m as f64;
    // Within the side's budget too: m points round, rings of them.
    let most = (MAX_QUADS / (4 * m.max(1))).clamp(1, CAP_RINGS);
    let rings = ((reach / edge.max(1e-9)).ceil() as usize).clamp(1, most);
    let at = |k: usize, j: usize| {
        if k == rings {
            outline[j]
        } else {
            c + (outline[j] - c) * (k as f64 / rings as f64)
        }
    };
    let mut face = |t: [Vector3<f64>; 3]| {
        out.push(if up {
            [p(t[0]), p(t[1]), p(t[2])]
        } else {
            [p(t[0]), p(t[2]), p(t[1])]
        })
    };
    for j in 0..m {
        let n = (j + 1) % m;
        face([c, at(1, j), at(1, n)]);
        for k in 2..=rings {
            face([at(k - 1, j), at(k, j), at(k, n)]);
            face([at(k - 1, j), at(k, n), at(k - 1, n)]);
        }
    }
}

/// The rings of an untwisted loft without the points that lie on the
/// chord of their neighbours at every station and halfway between
/// stations (`mids`, within a nanometre): a polygon's sides need only
/// their corners, where they stay straight along the loft.
fn straightened(
    rings: Vec<Vec<Vector3<f64>>>,
    mids: &[Vec<Vector3<f64>>],
) -> Vec<Vec<Vector3<f64>>> {
    let m = rings[0].len();
    let mut keep: Vec<usize> = Vec::with_capacity(m);
    for j in 0..m {
        let prev = keep.last().copied().unwrap_or((m + j - 1) % m);
        let next = (j + 1) % m;
        let straight = rings
            .iter()
            .chain(mids)
            .all(|r| off_chord(r[j], r[prev], r[next]) <= 1e-9);
        if !straight {
            keep.push(j);
        }
    }
    if keep.len() < 3 {
        return rings;
    }
    rings
        .into_iter()
        .map(|r| keep.iter().map(|&j| r[j]).collect())
        .collect()
}

/// The outline at station `s` (frame `f`) at each of `angles`.
fn ring(g: &LoftGeometry, f: &SectionFrame, s: f64, angles: &[f64]) -> Vec<Vector3<f64>> {
    angles.iter().map(|&a| g.point(f, s, a).0.coords).collect()
}

/// The angles round the outline, sorted in `[0, 2π)`: the ends' corners
/// and [`MIN_ANGLES`] spread evenly, each gap halved while the chord
/// across it strays more than [`CHORD`] from the outline at one of the
/// [`PROBES`] stations (so a bend that sharpens is followed closely and
/// the rest stays coarse), up to [`MAX_ANGLES`].
fn angles(g: &LoftGeometry) -> Vec<f64> {
    // A superellipse morph's corners move between its ends' (where a
    // rectangle's is); the halving takes the rest.
    let mut corners = g.blend.corners(0.0);
    corners.extend(g.blend.corners(1.0));
    let frames: Vec<(f64, SectionFrame)> = (0..PROBES)
        .map(|k| k as f64 / (PROBES - 1) as f64)
        .map(|s| (s, g.frame(s)))
        .collect();
    let stray = |x: f64, y: f64| {
        frames
            .iter()
            .map(|(s, f)| {
                let at = |t: f64| g.point(f, *s, t).0.coords;
                off_chord(at(0.5 * (x + y)), at(x), at(y))
            })
            .fold(0.0, f64::max)
    };
    let mut a: Vec<f64> = (0..MIN_ANGLES)
        .map(|k| TAU * k as f64 / MIN_ANGLES as f64)
        .collect();
    a.extend(corners.iter().map(|c| c.rem_euclid(TAU)));
    loop {
        a.sort_by(f64::total_cmp);
        a.dedup_by(|x, y| (*x - *y).abs() < 1e-12);
        let mut added = Vec::new();
        for j in 0..a.len() {
            let (x, y) = (a[j], a.get(j + 1).copied().unwrap_or(a[0] + TAU));
            if a.len() + added.len() < MAX_ANGLES && y - x > 1e-9 && stray(x, y) > CHORD {
                added.push((0.5 * (x + y)).rem_euclid(TAU));
            }
        }
        if added.is_empty() {
            return a;
        }
        a.extend(added);
    }
}

/// The stations from 0 to 1, evenly spread: one interval, doubled until
/// between each two neighbours the loft strays at most [`CHORD`] from
/// the chord of each point of `ring_at` and from the two triangles of
/// each pair of neighbouring points (their true middle, `mid_at`), or
/// until `most` intervals would be passed.
fn stations(
    ring_at: &dyn Fn(f64) -> Vec<Vector3<f64>>,
    mid_at: &dyn Fn(f64) -> Vec<Vector3<f64>>,
    most: usize,
) -> Vec<f64> {
    let mut n = 1;
    loop {
        let stray = (0..n)
            .map(|i| {
                let (a, b) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                let m = 0.5 * (a + b);
                let (ra, rb, rm, mid) = (ring_at(a), ring_at(b), ring_at(m), mid_at(m));
                let k = ra.len();
                (0..k)
                    .map(|j| {
                        let l = (j + 1) % k;
                        let p = |v: Vector3<f64>| [v.x, v.y, v.z];
                        let q = p(mid[j]);
                        let off = [[ra[j], ra[l], rb[l]], [ra[j], rb[l], rb[j]]]
                            .map(|t| {
                                let c = closest(&t.map(p), q);
                                (Vector3::from(c) - mid[j]).norm()
                            })
                            .into_iter()
                            .fold(f64::INFINITY, f64::min);
                        off.max(off_chord(rm[j], ra[j], rb[j]))
                    })
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        if stray <= CHORD || 2 * n > most {
            return (0..=n).map(|i| i as f64 / n as f64).collect();
        }
        n *= 2;
    }
}

/// How far `p` lies from the chord `a`–`b`: a point of a straight piece
/// of outline lies on it, wherever along it.
fn off_chord(p: Vector3<f64>, a: Vector3<f64>, b: Vector3<f64>) -> f64 {
    let d = b - a;
    let t = if d.norm_squared() > 0.0 {
        ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * t)).norm()
}

#[cfg(test)]
mod tests;

//! A fixture given as a mesh (`shape = mesh(file = …)`), as the collision
//! checks see it: its triangles' surface as samples, each a point and the
//! radius within which it stands for every point of the surface near it
//! (docs/collision.md, *What it is checked against*).
//!
//! Each triangle is cut into `n²` triangles like it, `n` the fewest that
//! bring its longest side to at most [`STEP_MM`]; each piece's sample is its
//! centroid, its radius the centroid's distance to the piece's farthest
//! corner (a ball round the corners holds the whole piece, which is convex).
//! That radius is at most ⅔ of a piece's longest side, so at most
//! `⅔ · 2 mm ≈ 1.33 mm`: within the `√2 mm` a box's or a cylinder's samples
//! stand for.
//!
//! **Budget.** Past [`MAX_SAMPLES`] pieces (a mesh exported in millions of
//! triangles, or a large one), the pieces are merged into cubes of a grid —
//! one sample a cube, at its centre, its radius reaching the farthest piece
//! in it — whose side doubles from [`STEP_MM`] until at most
//! [`MAX_SAMPLES`] cubes hold a piece. The samples then stand for more
//! (their largest radius is the mesh's [`Surface::tolerance`]); memory stays
//! at the samples' 32 bytes each, time linear in the triangles.

use std::collections::HashMap;

/// The longest side a triangle's pieces may have, mm: the fixtures'
/// sampling step.
pub const STEP_MM: f64 = 2.0;

/// Most samples a mesh fixture has: past them, it is coarsened (module
/// docs).
pub const MAX_SAMPLES: usize = 1_000_000;

/// Most triangles a fixture's mesh may have: a clamp's, exported finely,
/// not a scan's (its samples are bounded anyway; this bounds the reading
/// and the time to sample).
pub const MAX_TRIANGLES: usize = 2_000_000;

/// A triangle's corners, mm.
pub type Triangle = [[f64; 3]; 3];

/// A mesh's surface as samples.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surface {
    /// Each sample's point and radius, mm: `[x, y, z, r]`.
    pub samples: Vec<[f64; 4]>,
    /// The largest radius: how far, at most, any point of the surface lies
    /// from the sample standing for it, mm.
    pub tolerance: f64,
}

/// The surface of `tris` as samples (module docs). Deterministic: the same
/// triangles give the same samples in the same order.
pub fn sample(tris: &[Triangle]) -> Surface {
    if pieces_at(tris, STEP_MM) <= MAX_SAMPLES as u64 {
        let mut samples = Vec::new();
        for t in tris {
            pieces(t, STEP_MM, |c, r| samples.push([c[0], c[1], c[2], r]));
        }
        let tolerance = samples.iter().map(|s| s[3]).fold(0.0, f64::max);
        return Surface { samples, tolerance };
    }
    let mut side = STEP_MM;
    loop {
        if let Some(s) = merged(tris, side) {
            return s;
        }
        side *= 2.0;
    }
}

/// How many pieces `tris` are cut into at `step` (saturating).
fn pieces_at(tris: &[Triangle], step: f64) -> u64 {
    tris.iter()
        .map(|t| cuts(t, step).pow(2))
        .fold(0u64, u64::saturating_add)
}

/// Into how many pieces along each side triangle `t` is cut at `step`.
fn cuts(t: &Triangle, step: f64) -> u64 {
    let longest = (0..3)
        .map(|k| dist(t[k], t[(k + 1) % 3]))
        .fold(0.0, f64::max);
    // Capped: a side of 10 m at 2 mm is 5000; more is a sliver's noise.
    (longest / step).ceil().clamp(1.0, 1e5) as u64
}

/// Calls `put` with each piece of `t` at `step`: its centroid and radius.
fn pieces(t: &Triangle, step: f64, mut put: impl FnMut([f64; 3], f64)) {
    let n = cuts(t, step);
    let nf = n as f64;
    let [a, b, c] = *t;
    let u = [0, 1, 2].map(|k| (b[k] - a[k]) / nf);
    let v = [0, 1, 2].map(|k| (c[k] - a[k]) / nf);
    let at = |i: f64, j: f64| [0, 1, 2].map(|k| a[k] + u[k] * i + v[k] * j);
    // Every piece is the triangle scaled by 1/n (the "down" ones turned a
    // half turn): one radius for all.
    let g = [0, 1, 2].map(|k| (u[k] + v[k]) / 3.0);
    let r = [[0.0; 3], u, v]
        .iter()
        .map(|p| dist(*p, g))
        .fold(0.0, f64::max);
    for i in 0..n {
        for j in 0..n - i {
            let (i, j) = (i as f64, j as f64);
            // Up: (i, j), (i+1, j), (i, j+1); its centroid at (i+⅓, j+⅓).
            put(at(i + 1.0 / 3.0, j + 1.0 / 3.0), r);
            if i + j + 2.0 <= nf {
                // Down: (i+1, j), (i, j+1), (i+1, j+1).
                put(at(i + 2.0 / 3.0, j + 2.0 / 3.0), r);
            }
        }
    }
}

/// The pieces of `tris` merged into cubes of `side` (cut at `side`, so a
/// cube holds a few): `None` when more than [`MAX_SAMPLES`] cubes hold one.
fn merged(tris: &[Triangle], side: f64) -> Option<Surface> {
    if pieces_at(tris, side) > 64 * MAX_SAMPLES as u64 {
        // Too many pieces to walk in good time: a coarser grid first.
        return None;
    }
    let mut cubes: HashMap<[i64; 3], f64> = HashMap::new();
    let mut full = false;
    for t in tris {
        pieces(t, side, |c, r| {
            if full {
                return;
            }
            let key = c.map(|x| (x / side).floor() as i64);
            let centre = key.map(|k| (k as f64 + 0.5) * side);
            let reach = dist(c, centre) + r;
            let e = cubes.entry(key).or_insert(0.0);
            *e = e.max(reach);
            full = cubes.len() > MAX_SAMPLES;
        });
        if full {
            return None;
        }
    }
    let mut keyed: Vec<_> = cubes.into_iter().collect();
    keyed.sort_unstable_by_key(|(k, _)| *k);
    let samples: Vec<[f64; 4]> = keyed
        .into_iter()
        .map(|(k, r)| {
            let c = k.map(|k| (k as f64 + 0.5) * side);
            [c[0], c[1], c[2], r]
        })
        .collect();
    let tolerance = samples.iter().map(|s| s[3]).fold(0.0, f64::max);
    Some(Surface { samples, tolerance })
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every point of a triangle lies within some sample's radius, and no
    /// radius is past ⅔ of the step.
    #[test]
    fn every_point_of_a_triangle_is_within_a_sample() {
        let t = [[0.0, 0.0, 0.0], [17.3, 1.0, 2.0], [3.0, 9.5, -4.0]];
        let s = sample(&[t]);
        assert!(s.tolerance <= STEP_MM * 2.0 / 3.0 + 1e-9, "{}", s.tolerance);
        let n = 60;
        for i in 0..=n {
            for j in 0..=n - i {
                let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
                let p =
                    [0, 1, 2].map(|k| t[0][k] + a * (t[1][k] - t[0][k]) + b * (t[2][k] - t[0][k]));
                let covered = s
                    .samples
                    .iter()
                    .any(|q| dist(p, [q[0], q[1], q[2]]) <= q[3] + 1e-9);
                assert!(covered, "{p:?}");
            }
        }
    }

    /// A mesh of many tiny triangles is merged under the budget, and still
    /// covers every corner.
    #[test]
    fn a_mesh_past_the_budget_is_merged_and_still_covers() {
        let mut tris = Vec::new();
        for i in 0..1100 {
            for j in 0..1000 {
                let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
                tris.push([[x, y, 0.0], [x + 0.1, y, 0.0], [x, y + 0.1, 0.0]]);
            }
        }
        let s = sample(&tris);
        assert!(s.samples.len() <= MAX_SAMPLES);
        assert!(s.tolerance > STEP_MM * 2.0 / 3.0 && s.tolerance < 3.0 * STEP_MM);
        for t in tris.iter().step_by(997) {
            for p in t {
                assert!(s
                    .samples
                    .iter()
                    .any(|q| dist(*p, [q[0], q[1], q[2]]) <= q[3] + 1e-9));
            }
        }
    }
}

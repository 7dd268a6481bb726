//! The section of a scanned part at a height: the outline a repair
//! continues upward ("the blade as it is at 36 mm, built up to its tip").
//!
//! A scan's faces are a triangle soup, not a solid: open below, maybe with
//! holes where the scanner saw nothing, its triangles facing either way.
//! So the cut joins the pieces by the edges they cross, not by the faces'
//! winding ([`crate::geometry::mesh::Sections`] does that for a closed
//! mesh), and turns the loops by how they nest
//! ([`crate::geometry::mesh::oriented`]). A chain that does not close
//! (a hole in the scan at that height) is refused with where it ends.

use super::{Pose, Raw};
use crate::geometry::mesh::{oriented, Loop, Section, SectionFault};
use std::collections::{HashMap, HashSet};

/// Most loops a section may have before it is taken for noise, not a part
/// (each is nested against the others).
pub const MAX_LOOPS: usize = 10_000;

/// Why a scan's section is no profile.
#[derive(Clone, Debug, PartialEq)]
pub enum CutFault {
    /// The scan has points only: a section needs its faces.
    NoFaces,
    /// The plane cuts no face, or only slivers with no area; the scan's
    /// faces span `z` (mm, placed; `None` without faces).
    Empty {
        /// The lowest and highest placed vertex of a face.
        span: Option<[f64; 2]>,
    },
    /// A chain of pieces ends at `at` (mm): the scan has a hole there, or
    /// an edge with more than two faces.
    Open {
        /// Where the chain ends.
        at: [f64; 2],
    },
    /// More than [`MAX_LOOPS`] loops.
    TooMany {
        /// How many.
        loops: usize,
    },
    /// The loops cross or a hole lies in no outline.
    Islands(SectionFault),
}

/// An edge of the welded soup: its two vertices, lower first.
type Edge = (u32, u32);

/// The section of the scan `raw`, placed by `pose`, at `z = h` (mm).
pub fn cut(raw: &Raw, pose: &Pose, h: f64) -> Result<Vec<Section>, CutFault> {
    if raw.triangles.is_empty() {
        return Err(CutFault::NoFaces);
    }
    let (placed, weld) = welded(raw, pose);
    // Each crossed edge's neighbours across the faces it bounds.
    let mut next: HashMap<Edge, [Option<Edge>; 2]> = HashMap::new();
    let mut span = [f64::INFINITY, f64::NEG_INFINITY];
    for t in &raw.triangles {
        let v = t.map(|i| weld[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
            continue;
        }
        let z = v.map(|i| placed[i as usize][2]);
        span = [
            span[0].min(z[0].min(z[1]).min(z[2])),
            span[1].max(z[0].max(z[1]).max(z[2])),
        ];
        // A corner on the plane counts as above it, so a crossed face has
        // exactly two crossed edges.
        let above = z.map(|z| z >= h);
        let crossed: Vec<Edge> = (0..3)
            .filter(|&s| above[s] != above[(s + 1) % 3])
            .map(|s| key(v[s], v[(s + 1) % 3]))
            .collect();
        if let [a, b] = crossed[..] {
            link(&mut next, a, b, &placed, h)?;
            link(&mut next, b, a, &placed, h)?;
        }
    }
    let mut loops = walk(&next, &placed, h)?;
    loops.retain(|l| crate::geometry::mesh::area(l).abs() > 0.0);
    if loops.is_empty() {
        return Err(CutFault::Empty {
            span: span[0].is_finite().then_some(span),
        });
    }
    if loops.len() > MAX_LOOPS {
        return Err(CutFault::TooMany { loops: loops.len() });
    }
    oriented(loops).map_err(|f| match f {
        SectionFault::Empty => CutFault::Empty { span: Some(span) },
        f => CutFault::Islands(f),
    })
}

/// The vertices placed, and each file vertex's welded number: corners
/// with the same coordinates are one (an STL repeats them per triangle).
fn welded(raw: &Raw, pose: &Pose) -> (Vec<[f64; 3]>, Vec<u32>) {
    let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(raw.vertices.len());
    let mut placed = Vec::with_capacity(raw.vertices.len());
    let weld = raw
        .vertices
        .iter()
        .map(|c| {
            // -0.0 and 0.0 are the same corner.
            let k = c.map(|x| (x + 0.0).to_bits());
            *index.entry(k).or_insert_with(|| {
                placed.push(pose.apply(c));
                (placed.len() - 1) as u32
            })
        })
        .collect();
    (placed, weld)
}

fn key(a: u32, b: u32) -> Edge {
    (a.min(b), a.max(b))
}

/// Records `b` as a neighbour of `a`; a third neighbour is a branch.
fn link(
    next: &mut HashMap<Edge, [Option<Edge>; 2]>,
    a: Edge,
    b: Edge,
    placed: &[[f64; 3]],
    h: f64,
) -> Result<(), CutFault> {
    let slot = next.entry(a).or_insert([None, None]);
    match slot {
        [None, _] => slot[0] = Some(b),
        [Some(_), None] => slot[1] = Some(b),
        _ => {
            return Err(CutFault::Open {
                at: point(a, placed, h),
            })
        }
    }
    Ok(())
}

/// Where edge `e` crosses `z = h` (from the edge alone, so both faces at
/// it agree to the bit).
fn point(e: Edge, placed: &[[f64; 3]], h: f64) -> [f64; 2] {
    let (a, b) = (placed[e.0 as usize], placed[e.1 as usize]);
    let t = ((h - a[2]) / (b[2] - a[2])).clamp(0.0, 1.0);
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// The pieces joined into loops, from the lowest-numbered edge of each, in
/// that order (the same loops whatever the hash map's order).
fn walk(
    next: &HashMap<Edge, [Option<Edge>; 2]>,
    placed: &[[f64; 3]],
    h: f64,
) -> Result<Vec<Loop>, CutFault> {
    let mut starts: Vec<Edge> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut seen: HashSet<Edge> = HashSet::with_capacity(next.len());
    let mut loops = Vec::new();
    for s in starts {
        if seen.contains(&s) {
            continue;
        }
        let mut pts = Vec::new();
        let (mut prev, mut e) = (None, s);
        loop {
            seen.insert(e);
            pts.push(point(e, placed, h));
            let [a, b] = next[&e];
            let (Some(a), Some(b)) = (a, b) else {
                return Err(CutFault::Open {
                    at: point(e, placed, h),
                });
            };
            // Onward: the neighbour we did not come from (the first one
            // at the start).
            let to = if prev == Some(a) { b } else { a };
            prev = Some(e);
            e = to;
            if e == s {
                break;
            }
        }
        pts.dedup();
        if pts.len() >= 3 {
            loops.push(pts);
        }
    }
    Ok(loops)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh::Placement;

    fn pose() -> Pose {
        Pose::from(Placement {
            scale: 1.0,
            turn: [0.0; 3],
            at: [0.0; 3],
        })
    }

    /// An open tube (no caps) round `n` corners of radius `r`, from z = 0
    /// to 10, its faces wound `flip`ped or not.
    fn tube(n: u32, r: f32, flip: bool) -> Raw {
        let mut vertices = Vec::new();
        for z in [0.0f32, 10.0] {
            for i in 0..n {
                let a = i as f32 * std::f32::consts::TAU / n as f32;
                vertices.push([r * a.cos(), r * a.sin(), z]);
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n {
            let j = (i + 1) % n;
            let (mut t, mut u) = ([i, j, n + j], [i, n + j, n + i]);
            if flip {
                t.swap(1, 2);
                u.swap(1, 2);
            }
            triangles.push(t);
            triangles.push(u);
        }
        Raw {
            vertices,
            triangles,
        }
    }

    #[test]
    fn a_tubes_section_is_its_ring_whichever_way_its_faces_face() {
        for flip in [false, true] {
            let s = cut(&tube(24, 5.0, flip), &pose(), 4.0).unwrap();
            assert_eq!(s.len(), 1);
            assert!(s[0].holes.is_empty());
            // A 24-gon of radius 5: area 12·r²·sin(15°).
            let want = 12.0 * 25.0 * (15f64).to_radians().sin();
            assert!((s[0].area() - want).abs() < 1e-3, "{}", s[0].area());
            assert!(crate::geometry::mesh::area(&s[0].outline) > 0.0);
        }
    }

    #[test]
    fn a_tube_in_a_tube_is_an_outline_and_its_hole() {
        let (outer, inner) = (tube(16, 8.0, false), tube(16, 3.0, false));
        let off = outer.vertices.len() as u32;
        let raw = Raw {
            vertices: [outer.vertices, inner.vertices].concat(),
            triangles: outer
                .triangles
                .into_iter()
                .chain(inner.triangles.into_iter().map(|t| t.map(|i| i + off)))
                .collect(),
        };
        let s = cut(&raw, &pose(), 5.0).unwrap();
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].holes.len(), 1);
        assert!(crate::geometry::mesh::area(&s[0].holes[0]) < 0.0);
    }

    #[test]
    fn a_gap_in_the_scan_is_refused_where_it_is() {
        let mut raw = tube(12, 5.0, false);
        raw.triangles.truncate(raw.triangles.len() - 2);
        match cut(&raw, &pose(), 5.0) {
            Err(CutFault::Open { at }) => assert!((at[0].hypot(at[1]) - 5.0).abs() < 0.5),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn above_the_scan_and_points_only_are_refused() {
        assert_eq!(
            cut(&tube(8, 5.0, false), &pose(), 20.0),
            Err(CutFault::Empty {
                span: Some([0.0, 10.0])
            })
        );
        let points = Raw {
            vertices: vec![[0.0; 3]],
            triangles: vec![],
        };
        assert_eq!(cut(&points, &pose(), 1.0), Err(CutFault::NoFaces));
    }
}

//! Linked raster: neighbouring tracks joined at their ends along the edge,
//! so the nozzle turns there instead of stopping, lifting and starting again.
//!
//! # The rule
//!
//! A track on line `n` ending at the boundary links to the track of line
//! `n + 1` that the boundary leads to: from the end's point on the boundary
//! the edge is followed upwards (towards line `n + 1`) while it keeps rising;
//! where it reaches line `n + 1` it meets the end of one interval there
//! (the same end, since the part stays on the same side of the edge), and
//! that interval is next — if no other chain has taken it. An edge that
//! turns back before the next line (the top of a hole, a notch) links
//! nothing: the tracks beyond it belong to another stretch of edge.
//!
//! The link is the straight move from one track end to the next if that
//! stays inside the part, else the edge itself (through the points between
//! the two ends; arcs flattened within the chord error, bulging into the part
//! where the edge is concave, so that no chord cuts the corner); if neither
//! stays inside, the tracks are not linked. Inside means within the region
//! where track centre lines may run (the profile less the inset: half a bead
//! for `size = outer`), every point and every segment (`inside::Inside`).
//!
//! Chains are grown greedily: the first unlinked track (lowest line, then
//! lowest along it) starts one, running forwards; each link turns it back,
//! so a chain is a serpentine over one stretch of the part, and a part with
//! holes splits into a few of them.
//!
//! Cost: each track end is walked once, along the edge between two lines,
//! and each link is checked against the pieces near its strip; linear in
//! tracks and pieces for a layer whose strips each meet a bounded part of
//! the boundary.

use super::clip::{Frame, Piece, Pieces};
use super::inside::Inside;
use super::{spend, FillError, Link, Track, TrackKind};
use crate::geometry::profile::MAX_ARC_CHORDS;
use std::f64::consts::PI;

/// The raster of one layer, as the links need it.
pub(super) struct Chains<'a> {
    /// Each line's position across the lines.
    pub s: &'a [f64],
    /// Each line's intervals as clipped (before extension).
    pub clipped: &'a [Vec<[f64; 2]>],
    /// The pieces each clipped interval's ends lie on, if a crossing.
    pub ends: &'a [Vec<[Option<u32>; 2]>],
    /// Each line's extended intervals, with their index into `clipped`.
    pub grown: &'a [Vec<(usize, [f64; 2])>],
    /// The raster region's boundary.
    pub pieces: &'a Pieces,
    /// Arcs of the edge are flattened within this, mm.
    pub chord_error: f64,
}

/// A track cut back to where it was clipped keeps at least this length, mm.
const MIN_TRACK: f64 = 1e-6;

/// One track of a chain: line `n`'s grown interval `g`, run forwards
/// (increasing `t`) or back, and the points (frame coordinates) between its
/// end and the next track's start, if linked. `from` and `to` replace the
/// interval's ends where a link that deposits takes over from an extension.
pub(super) struct Step {
    n: usize,
    g: usize,
    forward: bool,
    via: Option<Vec<[f64; 2]>>,
    from: Option<f64>,
    to: Option<f64>,
}

/// A link found by [`next`]: the next track (interval `g` of the next line),
/// the points between, and where the two tracks end and start when that is
/// not their grown ends.
struct Found {
    g: usize,
    via: Vec<[f64; 2]>,
    end: Option<f64>,
    start: Option<f64>,
}

/// The chains of the layer, in the order they are built; every grown
/// interval is in exactly one.
pub(super) fn chains(c: &Chains<'_>, within: &Pieces, laser: bool) -> Vec<Vec<Step>> {
    let mut inside = Inside::new(within, c.s, c.chord_error + 1e-6);
    let mut used: Vec<Vec<bool>> = c.grown.iter().map(|l| vec![false; l.len()]).collect();
    let mut out = Vec::new();
    for n0 in 0..c.grown.len() {
        for g0 in 0..c.grown[n0].len() {
            if used[n0][g0] {
                continue;
            }
            used[n0][g0] = true;
            let mut chain = vec![Step {
                n: n0,
                g: g0,
                forward: true,
                via: None,
                from: None,
                to: None,
            }];
            while let Some(inside) = inside.as_mut() {
                let Some(last) = chain.last_mut() else { break };
                let Some(f) = next(c, inside, last, laser, &used) else {
                    break;
                };
                let (n, forward) = (last.n + 1, !last.forward);
                last.via = Some(f.via);
                last.to = f.end;
                used[n][f.g] = true;
                chain.push(Step {
                    n,
                    g: f.g,
                    forward,
                    via: None,
                    from: f.start,
                    to: None,
                });
            }
            out.push(chain);
        }
    }
    out
}

/// The tracks of `chains` in world coordinates, each linked one carrying
/// its link; spends the layer's point budget.
pub(super) fn tracks(
    chains: &[Vec<Step>],
    grown: &[Vec<(usize, [f64; 2])>],
    s: &[f64],
    frame: &Frame,
    laser: bool,
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let mut out = Vec::new();
    for step in chains.iter().flatten() {
        let [a, b] = grown[step.n][step.g].1;
        let (from, to) = if step.forward { (a, b) } else { (b, a) };
        let (from, to) = (step.from.unwrap_or(from), step.to.unwrap_or(to));
        let link = step.via.as_ref().map(|via| Link {
            via: via.iter().map(|&p| frame.world(p)).collect(),
            laser,
        });
        spend(points_left, 2 + link.as_ref().map_or(0, |l| l.via.len()))?;
        out.push(Track {
            kind: TrackKind::Infill,
            points: vec![frame.world([from, s[step.n]]), frame.world([to, s[step.n]])],
            link,
        });
    }
    Ok(out)
}

/// The interval of line `n + 1` that the track `last` links to at its end
/// (the +t one when running forward), and the link.
///
/// Three links are tried, the first that stays inside wins: straight from
/// the track's end to the next one's start; along the edge between them;
/// along the edge from where the tracks were clipped. The last is for ends
/// that an extension moved past the region (a slanted or curved edge): with
/// the laser off the nozzle goes back along its own track to the edge, and
/// out along the next track to its start; with the laser on the link, which
/// deposits along the edge, takes the extensions' place and the tracks end
/// and start where they were clipped.
fn next(
    c: &Chains<'_>,
    inside: &mut Inside<'_>,
    last: &Step,
    laser: bool,
    used: &[Vec<bool>],
) -> Option<Found> {
    let (n, g, forward) = (last.n, last.g, last.forward);
    let (&s0, &s1) = (c.s.get(n)?, c.s.get(n + 1)?);
    let side = usize::from(forward);
    let (k, grown) = c.grown[n][g];
    let start = c.ends[n][k][side]?;
    let b = c.clipped[n][k][side];
    let (q, t1, edge) = walk(c.pieces, start as usize, b, s0, s1, c.chord_error)?;
    // The interval of line n + 1 whose same end is that crossing.
    let clipped = &c.clipped[n + 1];
    let k1 = clipped.partition_point(|iv| iv[side] < t1);
    if clipped.get(k1).is_none_or(|iv| iv[side] != t1) || c.ends[n + 1][k1][side] != Some(q) {
        return None;
    }
    let g1 = c.grown[n + 1].binary_search_by_key(&k1, |e| e.0).ok()?;
    if used[n + 1][g1] {
        return None;
    }
    let p = [grown[side], s0];
    let q = [c.grown[n + 1][g1].1[side], s1];
    let found = |via: Vec<[f64; 2]>, end, start| {
        Some(Found {
            g: g1,
            via: dedup(via, p, q),
            end,
            start,
        })
    };
    if inside.path(&[p, q], n) {
        return found(Vec::new(), None, None);
    }
    let mut along = Vec::with_capacity(edge.len() + 2);
    along.push(p);
    along.extend_from_slice(&edge);
    along.push(q);
    if inside.path(&along, n) {
        return found(edge, None, None);
    }
    let (b0, b1) = ([b, s0], [t1, s1]);
    let mut clipped_path = Vec::with_capacity(edge.len() + 2);
    clipped_path.push(b0);
    clipped_path.extend_from_slice(&edge);
    clipped_path.push(b1);
    if !inside.path(&clipped_path, n) {
        return None;
    }
    if laser {
        // The tracks now end at b0 and start at b1: the link's own points
        // are those strictly between. Neither track may shrink to nothing.
        let this_start = last.from.unwrap_or(grown[1 - side]);
        let next_end = c.grown[n + 1][g1].1[1 - side];
        if (b - this_start).abs() < MIN_TRACK || (t1 - next_end).abs() < MIN_TRACK {
            return None;
        }
        Some(Found {
            g: g1,
            via: dedup(edge, b0, b1),
            end: Some(b),
            start: Some(t1),
        })
    } else {
        found(clipped_path, None, None)
    }
}

/// The points without repeats (of each other or of the ends).
fn dedup(mut via: Vec<[f64; 2]>, p: [f64; 2], q: [f64; 2]) -> Vec<[f64; 2]> {
    let same = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9;
    via.dedup_by(|b, a| same(*a, *b));
    let mut prev = p;
    via.retain(|&x| {
        let keep = !same(x, prev) && !same(x, q);
        if keep {
            prev = x;
        }
        keep
    });
    via
}

/// Follows the boundary up from the crossing of piece `start` at `(t0, s0)`
/// to line `s1`: the piece it crosses there, the crossing's `t`, and the
/// points between (frame coordinates). `None` when the edge turns back first.
fn walk(
    pieces: &Pieces,
    start: usize,
    t0: f64,
    s0: f64,
    s1: f64,
    chord_error: f64,
) -> Option<(u32, f64, Vec<[f64; 2]>)> {
    let items = &pieces.items;
    let first = items.get(start)?;
    if !first.spans(s0) {
        return None;
    }
    // Along the loop in the direction that rises on the first piece.
    let forward = first.rising;
    let mut cur = start;
    let mut from = [t0, s0];
    let mut out = Vec::new();
    for _ in 0..items.len() {
        let p = &items[cur];
        if p.hi[1] > s1 {
            if p.lo[1] > s1 {
                return None;
            }
            let t1 = p.crossing(s1);
            flatten(p, from, [t1, s1], chord_error, &mut out);
            return Some((cur as u32, t1, out));
        }
        let exit = if forward == p.rising { p.hi } else { p.lo };
        flatten(p, from, exit, chord_error, &mut out);
        out.push(exit);
        from = exit;
        cur = pieces.neighbour(cur, forward);
        let np = &items[cur];
        // The edge must keep rising (or run level) to reach the next line.
        if np.lo[1] != np.hi[1] && np.rising != forward {
            return None;
        }
    }
    None
}

/// Appends the points strictly between `from` and `to` that follow piece
/// `p` (nothing for a line): on a convex arc points of the arc, on a concave
/// one the corners of the tangents, so the polyline never leaves the part.
fn flatten(p: &Piece, from: [f64; 2], to: [f64; 2], chord_error: f64, out: &mut Vec<[f64; 2]>) {
    let Some((c, r, _)) = p.arc else { return };
    let a0 = (from[1] - c[1]).atan2(from[0] - c[0]);
    let a1 = (to[1] - c[1]).atan2(to[0] - c[0]);
    let sweep = (a1 - a0 + PI).rem_euclid(2.0 * PI) - PI;
    let e = chord_error.max(1e-9);
    // Largest step: a chord within e of a convex arc; a tangent corner
    // within e of a concave one.
    let step = if p.convex {
        2.0 * (1.0 - (e / r).min(1.0)).acos()
    } else {
        2.0 * (r / (r + e)).acos()
    };
    let n = (sweep.abs() / step).ceil();
    let n = if n.is_finite() {
        (n as usize).clamp(1, MAX_ARC_CHORDS)
    } else {
        MAX_ARC_CHORDS
    };
    let delta = sweep / n as f64;
    let at = |phi: f64, radius: f64| [c[0] + radius * phi.cos(), c[1] + radius * phi.sin()];
    if p.convex {
        out.extend((1..n).map(|i| at(a0 + i as f64 * delta, r)));
    } else {
        let outer = r / (delta / 2.0).cos();
        out.extend((1..=n).map(|i| at(a0 + (i as f64 - 0.5) * delta, outer)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::profile::Profile;

    #[test]
    fn walking_up_a_hole_follows_its_edge_and_stops_at_its_top() {
        let hole = Profile::circle(5.0);
        let ps = Pieces::new([(&hole, true)], &Frame::new(0.0));
        // Start at the hole's left edge on u = 0, walk to u = 3.
        let start = (0..ps.items.len())
            .find(|&i| ps.items[i].spans(0.0) && ps.items[i].crossing(0.0) < 0.0)
            .unwrap();
        let (_, t1, pts) = walk(&ps, start, -5.0, 0.0, 3.0, 0.01).unwrap();
        assert!((t1 + 4.0).abs() < 1e-12);
        // A concave edge: every point on or outside the circle.
        assert!(!pts.is_empty());
        for p in &pts {
            assert!(p[0].hypot(p[1]) >= 5.0 - 1e-12 && p[0].hypot(p[1]) <= 5.0 + 0.011);
        }
        // Past the top (u = 5) the edge turns down: no link to u = 6.
        assert!(walk(&ps, start, -5.0, 0.0, 6.0, 0.01).is_none());
    }
}

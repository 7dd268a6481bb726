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
//! A link laid with the laser off is the straight move from one track end
//! to the next if that stays inside the part, else the edge itself (through
//! the points between the two ends; arcs flattened within the chord error,
//! bulging into the part where the edge is concave, so that no chord cuts
//! the corner); if neither stays inside, the tracks are not linked. Inside
//! means within the region where track centre lines may run (the profile
//! less the inset: half a bead for `size = outer`), every point and every
//! segment (`inside::Inside`).
//!
//! A link laid with the laser on deposits, so where it lies decides what
//! the layer stacks: a move along the edge from one track end to the next
//! would lay the inner half of its bead on the two tracks' ends, whose
//! strips already reach its centre line (issue 33: 8 % of the flange
//! counted twice). It is a half circle instead, its diameter the two
//! lines' spacing and its apex on the edge midway between the ends, and
//! both tracks end level half the spacing short of the ends' mean
//! (trimmed). A strip as wide as the spacing along such a half circle
//! covers the half disc round its centre once (its inner edge shrinks to
//! the centre), which is exactly what the trimmed ends leave: the turn
//! lays, at the tracks' speed, the metal its own strip holds. Where the two
//! ends are not level (to `LEVEL` of the radius: a slanted or curved
//! edge), the half circle would reach past the nearer end into the
//! contour's strip, and trimming them level would leave the staircase
//! between them bare: there, and where the turn would leave the region or a track
//! shrink to nothing, the link is laid with the laser off, as `laser_off`
//! lays it (the tracks keep their extensions, and the metal they lay is
//! theirs alone).
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
    /// Whether the laser stays on through the link (`via`).
    laser: bool,
    from: Option<f64>,
    to: Option<f64>,
}

/// A link found by [`next`]: the next track (interval `g` of the next line),
/// the points between, and where the two tracks end and start when that is
/// not their grown ends.
struct Found {
    g: usize,
    via: Vec<[f64; 2]>,
    laser: bool,
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
                laser: false,
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
                last.laser = f.laser;
                last.to = f.end;
                used[n][f.g] = true;
                chain.push(Step {
                    n,
                    g: f.g,
                    forward,
                    via: None,
                    laser: false,
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
    points_left: &mut u64,
) -> Result<Vec<Track>, FillError> {
    let mut out = Vec::new();
    for step in chains.iter().flatten() {
        let [a, b] = grown[step.n][step.g].1;
        let (from, to) = if step.forward { (a, b) } else { (b, a) };
        let (from, to) = (step.from.unwrap_or(from), step.to.unwrap_or(to));
        let link = step.via.as_ref().map(|via| Link {
            via: via.iter().map(|&p| frame.world(p)).collect(),
            laser: step.laser,
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
/// With the laser on, the link is a round turn where the ends allow one
/// ([`round_turn`]). Else, and with the laser off, the link is laid with
/// the laser off, and three are tried, the first that stays inside wins:
/// straight from the track's end to the next one's start; along the edge
/// between them; along the edge from where the tracks were clipped. The
/// last is for ends that an extension moved past the region (a slanted or
/// curved edge): the nozzle goes back along its own track to the edge, and
/// out along the next track to its start.
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
            laser: false,
            end,
            start,
        })
    };
    if laser {
        if let Some(turn) = round_turn(c, inside, last, g1, [b, t1], [s0, s1]) {
            return Some(turn);
        }
    }
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
    found(clipped_path, None, None)
}

/// How far apart along the lines (a share of the turn's radius) two ends
/// may lie and still be joined by a round turn.
const LEVEL: f64 = 0.01;

/// A link laid with the laser on between line `n`'s track `last`, which
/// meets the edge at `t = b` on `s0`, and interval `g1` of line `n + 1`,
/// which meets it at `t1` on `s1`: a half circle whose diameter is the
/// lines' spacing `s1 − s0`, its apex on the edge midway between the two
/// ends, and both tracks ending level where it starts and ends, half the
/// spacing short of the ends' mean (the raster ends beside a turn are
/// trimmed). A strip as wide as the spacing along a half circle of that
/// diameter covers the half disc round its centre exactly once (its inner
/// edge shrinks to the centre), so the turn's metal fills the strip the
/// trimmed ends leave and nothing the tracks already fill. `None` where the
/// ends are not level (within `LEVEL` of the radius: on a slanted edge
/// the turn would reach into the contour's strip, and trimming them level
/// would leave the staircase bare), the turn
/// leaves the region, or a track would shrink to nothing.
fn round_turn(
    c: &Chains<'_>,
    inside: &mut Inside<'_>,
    last: &Step,
    g1: usize,
    [b, t1]: [f64; 2],
    [s0, s1]: [f64; 2],
) -> Option<Found> {
    let (n, side) = (last.n, usize::from(last.forward));
    let out = if last.forward { 1.0 } else { -1.0 };
    let r = 0.5 * (s1 - s0);
    // Ends level to a hundredth of the radius: on a slanted edge the half
    // disc, centred between the ends, reaches past the nearer one's edge
    // into the contour's strip (1.4 % of a layer counted twice at 2°).
    if !(r.is_finite() && r > 0.0) || (t1 - b).abs() > LEVEL * r {
        return None;
    }
    let level = 0.5 * (b + t1) - out * r;
    let this_start = last.from.unwrap_or(c.grown[n].get(last.g)?.1[1 - side]);
    let next_end = c.grown[n + 1].get(g1)?.1[1 - side];
    if out * (level - this_start) < MIN_TRACK || out * (level - next_end) < MIN_TRACK {
        return None;
    }
    let e = c.chord_error.max(1e-9);
    let step = 2.0 * (1.0 - (e / r).min(1.0)).acos();
    let k = (PI / step).ceil();
    let k = if k.is_finite() {
        (k as usize).clamp(2, MAX_ARC_CHORDS)
    } else {
        MAX_ARC_CHORDS
    };
    let mid = 0.5 * (s0 + s1);
    let via: Vec<[f64; 2]> = (1..k)
        .map(|i| {
            let phi = -0.5 * PI + PI * i as f64 / k as f64;
            [level + out * r * phi.cos(), mid + r * phi.sin()]
        })
        .collect();
    let mut path = Vec::with_capacity(via.len() + 4);
    path.extend([[b, s0], [level, s0]]);
    path.extend_from_slice(&via);
    path.extend([[level, s1], [t1, s1]]);
    if !inside.path(&path, n) {
        return None;
    }
    Some(Found {
        g: g1,
        via,
        laser: true,
        end: Some(level),
        start: Some(level),
    })
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
    use crate::fill::{fill, FillSpec, Linking, Pattern, RasterSpec, Seam};
    use crate::geometry::profile::Profile;

    fn rectangle(link: Linking) -> Vec<Track> {
        // 30 × 14 mm from the origin, a bead 3 mm wide: one contour 2 mm
        // inside the outline's half-bead inset, raster lines 2 mm apart
        // from y = 3.5 mm to 9.5 mm between x = 3.5 and 26.5 mm (the
        // straight edges the turns come to).
        let spec = FillSpec {
            inset: 1.5,
            contours: 1,
            offset: 2.0,
            raster: Some(RasterSpec {
                angle_deg: 0.0,
                offset: 2.0,
                pattern: Pattern::Serpentine,
                extend: 2.0,
                link,
                closing: f64::INFINITY,
            }),
            seam: Seam::Lowest,
        };
        fill(&Profile::rectangle(30.0, 14.0), &spec, 0.01).unwrap()
    }

    #[test]
    fn a_laser_on_turn_is_a_half_circle_across_the_spacing() {
        let tracks = rectangle(Linking::LaserOn);
        let raster: Vec<&Track> = tracks
            .iter()
            .filter(|t| t.kind == TrackKind::Infill)
            .collect();
        let off = rectangle(Linking::LaserOff);
        let unlinked: Vec<&Track> = off.iter().filter(|t| t.kind == TrackKind::Infill).collect();
        assert_eq!(raster.len(), 4);
        let turns: Vec<_> = raster
            .windows(2)
            .filter_map(|p| {
                let l = p[0].link.as_ref()?;
                Some((p[0], l, p[1]))
            })
            .collect();
        assert_eq!(
            turns.len(),
            3,
            "every track linked with the laser on: {raster:?}"
        );
        for (a, l, b) in turns {
            assert!(l.laser);
            let (p, q) = (*a.points.last().unwrap(), b.points[0]);
            // Both ends level, half the 2 mm spacing short of the edge at
            // x = 3.5 or 26.5 mm (the laser-off raster's ends).
            assert!((p[0] - q[0]).abs() < 1e-9 && (q[1] - p[1] - 2.0).abs() < 1e-9);
            let inward = (p[0] - 15.0).abs();
            assert!((inward - 10.5).abs() < 1e-9, "{p:?}");
            let centre = [p[0], 0.5 * (p[1] + q[1])];
            for v in &l.via {
                let r = (v[0] - centre[0]).hypot(v[1] - centre[1]);
                assert!((r - 1.0).abs() < 1e-9, "{v:?} is {r} from {centre:?}");
                // On the outer side of the ends, up to the edge.
                let out = (v[0] - 15.0).abs();
                assert!(out > 10.5 && out <= 11.5 + 1e-9, "{v:?}");
            }
            // Flattened within the chord error: the half circle's apex
            // is a point of it or a chord's middle within 0.01 mm of it.
            let apex = l
                .via
                .iter()
                .map(|v| (v[0] - 15.0).abs())
                .fold(0.0, f64::max);
            assert!(apex > 11.49, "{apex}");
        }
        // The laser-off raster's tracks run to the edge, 1 mm further.
        for (t, u) in raster.iter().zip(&unlinked) {
            let len = |t: &Track| (t.points[1][0] - t.points[0][0]).abs();
            assert!((len(u) - 23.0).abs() < 1e-9, "{:?}", u.points);
            assert!(len(t) < len(u) - 1.0 + 1e-9, "{:?}", t.points);
        }
    }

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

//! Keeping the extension out of the holes. Seed 001's extension grows a track
//! end by up to `extend` where its neighbour reaches further; at the outline
//! that lays the staircase of a curved edge (machined off with the rest of
//! the stock), but at a hole it would lay metal into the hole, which then
//! has to be drilled out and closes up first on a small bore. So an end is
//! extended only as far as the hole grown by the inset: the line where a
//! bead's edge would touch the hole's face.

use super::clip::{sweep, Piece, Scratch};
use crate::geometry::profile::TOLERANCE;

/// Cuts each extended interval of `grown` (with its index into `clipped`,
/// the line's intervals before extension) back to where it would enter a
/// loop of `keep` (each loop by itself, so overlapping grown holes are
/// fine), never shorter than it was clipped; `s` are the lines' positions.
/// Intervals left without length are dropped.
pub(super) fn clamp(
    grown: &mut [Vec<(usize, [f64; 2])>],
    clipped: &[Vec<[f64; 2]>],
    s: &[f64],
    keep: &[Piece],
) {
    let mut scratch = Scratch::default();
    sweep(keep, s, |n, active| {
        if active.is_empty() || grown[n].is_empty() {
            return;
        }
        let forbidden = scratch.clip_each(keep, active.iter().copied(), s[n]);
        for (k, iv) in grown[n].iter_mut() {
            let [a, b] = clipped[n][*k];
            if iv[0] < a {
                // The last grown hole starting before the clipped end.
                let j = forbidden.partition_point(|f| f[0] < a);
                if let Some(f) = j.checked_sub(1).map(|j| forbidden[j]) {
                    if f[1] > iv[0] {
                        iv[0] = f[1].min(a);
                    }
                }
            }
            if iv[1] > b {
                // The first grown hole ending after the clipped end.
                let j = forbidden.partition_point(|f| f[1] <= b);
                if let Some(f) = forbidden.get(j) {
                    if f[0] < iv[1] {
                        iv[1] = f[0].max(b);
                    }
                }
            }
        }
    });
    for line in grown.iter_mut() {
        line.retain(|(_, i)| i[1] - i[0] > TOLERANCE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fill::clip::{Frame, Pieces};
    use crate::geometry::profile::Profile;

    #[test]
    fn an_end_stops_at_the_grown_hole_and_others_are_untouched() {
        // A grown hole of radius 2 at (10, 0); line 0 at u = 0.
        let hole = Profile::circle(2.0).placed(0.0, [10.0, 0.0]);
        let keep = Pieces::new([(&hole, true)], &Frame::new(0.0));
        let clipped = vec![vec![[0.0, 7.5], [12.5, 20.0]]];
        let mut grown = vec![vec![(0, [-1.0, 9.0]), (1, [11.0, 21.0])]];
        clamp(&mut grown, &clipped, &[0.0], &keep.items);
        assert_eq!(grown[0], vec![(0, [-1.0, 8.0]), (1, [12.0, 21.0])]);
    }
}

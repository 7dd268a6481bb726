//! Extending raster intervals into the staircase a curved edge leaves
//! (`ΔX ≤ d`). The rule is in the module docs of [`fill`](super).

use crate::geometry::profile::TOLERANCE;

/// One raster line's intervals as laid (extended), each with the index of
/// the clipped interval it grew from, sorted along the line and disjoint.
pub(super) type Laid = Vec<(usize, [f64; 2])>;

/// Each line's intervals with their ends extended by at most `limit`;
/// `lines[n]` are line `n`'s clipped intervals, sorted and disjoint.
#[cfg(test)]
pub(super) fn extend(lines: &[Vec<[f64; 2]>], limit: f64) -> Vec<Vec<[f64; 2]>> {
    extend_kept(lines, limit)
        .into_iter()
        .map(|l| l.into_iter().map(|(_, i)| i).collect())
        .collect()
}

/// [`extend`], each interval kept with its index among the line's clipped
/// ones (an interval that stays a point is dropped, so they may differ).
pub(super) fn extend_kept(lines: &[Vec<[f64; 2]>], limit: f64) -> Vec<Laid> {
    let grow = |reach: f64| {
        if reach > TOLERANCE {
            reach.min(limit)
        } else {
            0.0
        }
    };
    (0..lines.len())
        .map(|n| {
            let line = &lines[n];
            let neighbours = [n.checked_sub(1), Some(n + 1)];
            let mut grown: Vec<[f64; 2]> = (0..line.len())
                .map(|k| {
                    let (mut left, mut right) = (0.0f64, 0.0f64);
                    for nb in neighbours.iter().flatten().filter_map(|&m| lines.get(m)) {
                        let (l, r) = reach(line, k, nb);
                        left = left.max(l);
                        right = right.max(r);
                    }
                    [line[k][0] - grow(left), line[k][1] + grow(right)]
                })
                .collect();
            // Two intervals that would grow into each other share the gap.
            for k in 1..grown.len() {
                if grown[k - 1][1] > grown[k][0] {
                    let mid = (line[k - 1][1] + line[k][0]) / 2.0;
                    grown[k - 1][1] = grown[k - 1][1].min(mid);
                    grown[k][0] = grown[k][0].max(mid);
                }
            }
            grown
                .into_iter()
                .enumerate()
                .filter(|(_, i)| i[1] - i[0] > TOLERANCE)
                .collect()
        })
        .collect()
}

/// How much further than interval `k` of `line` the overlapping intervals of
/// the neighbouring line `nb` reach, `(at the start, at the end)`. A
/// neighbour interval counts at this interval's end only if no later
/// interval of `line` overlaps it too (and at the start only if no earlier
/// one does): the reach past a gap in `line` is the gap's, not this end's.
fn reach(line: &[[f64; 2]], k: usize, nb: &[[f64; 2]]) -> (f64, f64) {
    let [a, b] = line[k];
    let first = nb.partition_point(|j| j[1] < a - TOLERANCE);
    let (mut left, mut right) = (0.0f64, 0.0f64);
    for &[c, d] in nb[first..].iter().take_while(|j| j[0] <= b + TOLERANCE) {
        if line.get(k + 1).is_none_or(|next| next[0] > d + TOLERANCE) {
            right = right.max(d - b);
        }
        if k == 0 || line[k - 1][1] < c - TOLERANCE {
            left = left.max(a - c);
        }
    }
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_staircase_is_filled_up_to_the_limit() {
        // A lens: short, long, short.
        let lines = vec![vec![[4.0, 6.0]], vec![[1.0, 9.0]], vec![[3.5, 6.5]]];
        let out = extend(&lines, 2.0);
        assert_eq!(out[0], vec![[2.0, 8.0]]); // reach 3, limited to 2
        assert_eq!(out[1], vec![[1.0, 9.0]]); // nothing reaches past it
        assert_eq!(out[2], vec![[1.5, 8.5]]);
        assert_eq!(extend(&lines, 0.0), lines);
    }

    #[test]
    fn straight_ends_across_the_lines_stay() {
        let lines = vec![vec![[0.0, 5.0]]; 3];
        assert_eq!(extend(&lines, 10.0), lines);
    }

    #[test]
    fn a_notch_does_not_pull_the_inner_ends_in() {
        // Below the notch one interval, above it two.
        let lines = vec![vec![[0.0, 30.0]], vec![[0.0, 10.0], [20.0, 30.0]]];
        let out = extend(&lines, 5.0);
        assert_eq!(out, lines);
        // The same upside down.
        let flipped = vec![lines[1].clone(), lines[0].clone()];
        assert_eq!(extend(&flipped, 5.0), flipped);
    }

    #[test]
    fn neighbours_only_count_where_they_overlap() {
        // Far apart: no overlap, no reach.
        let lines = vec![vec![[0.0, 1.0]], vec![[5.0, 6.0]]];
        assert_eq!(extend(&lines, 3.0), lines);
    }

    #[test]
    fn intervals_growing_into_one_gap_meet_in_its_middle() {
        let lines = vec![
            vec![[0.0, 15.0]],
            vec![[0.0, 10.0], [20.0, 30.0]],
            vec![[12.0, 30.0]],
        ];
        let out = extend(&lines, 8.0);
        assert_eq!(out[1], vec![[0.0, 15.0], [15.0, 30.0]]);
    }

    #[test]
    fn a_touch_point_grows_or_goes() {
        let lines = vec![vec![[5.0, 5.0]], vec![[2.0, 8.0]]];
        assert_eq!(extend(&lines, 1.0)[0], vec![[4.0, 6.0]]);
        assert!(extend(&lines, 0.0)[0].is_empty());
    }
}

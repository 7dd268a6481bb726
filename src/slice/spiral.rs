//! `layer_change = spiral`, shared by the walls that take it (sliced normal
//! to their spine, and planar one-bead walls): the last `length` of each
//! layer's closed loop climbs to the next layer's first point with the
//! laser on. A point a share `t` of the way up the climb stands exactly one
//! layer height over the point of the climb below it, so it lays one layer
//! height — except on the first layer, whose climb rises off the plate and
//! so fills down to it: `(1 + t)` layer heights.

use crate::ir::Layer;
use nalgebra::Point3;

/// Each point's share of the way up the climb, for a closed loop through
/// `pos` (its last point its first again): 0 before the last `length` of
/// arc length, rising linearly with arc length to 1 at the last point.
/// `length` longer than the loop (or infinite) climbs over all of it.
pub fn shares(pos: &[Point3<f64>], length: f64) -> Vec<f64> {
    let mut along = Vec::with_capacity(pos.len());
    let mut total = 0.0;
    along.push(0.0);
    for w in pos.windows(2) {
        total += (w[1] - w[0]).norm();
        along.push(total);
    }
    let length = length.min(total);
    if length.is_nan() || length <= 0.0 {
        return vec![0.0; pos.len()];
    }
    along
        .iter()
        .map(|s| ((s - (total - length)) / length).clamp(0.0, 1.0))
        .collect()
}

/// Where the climb over the last `length` of the closed loop through `pos`
/// starts, when that falls inside a move rather than on a point: the move
/// (from point `j`) and the share `u` of the way along it. A loop with few
/// points (a polygon's corners) needs a point there, or its climb would
/// start at the point before.
pub fn climb_start(pos: &[Point3<f64>], length: f64) -> Option<(usize, f64)> {
    let steps: Vec<f64> = pos.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let total: f64 = steps.iter().sum();
    let mut left = total - length;
    if left.is_nan() || left <= 0.0 {
        return None;
    }
    for (j, &l) in steps.iter().enumerate() {
        if left < l {
            // Within a micrometre of a point, that point starts it.
            return (left > 1e-6 && l - left > 1e-6).then_some((j, left / l));
        }
        left -= l;
    }
    None
}

/// Where to put points on the first layer's climb so that no move's ends
/// lay heights more than `rise` (a share of their mean) apart: the climb
/// lays `1 + t` layer heights, rising along each move, and one move is laid
/// at one speed — the mean of its ends'. `t` holds each point's share up
/// the climb ([`shares`]; linear in arc length along each climbing move);
/// the cuts are `(move, share along it)`, in order.
pub fn first_climb_cuts(t: &[f64], rise: f64) -> Vec<(usize, f64)> {
    let mut cuts = Vec::new();
    if !(rise.is_finite() && rise > 0.0) {
        return cuts;
    }
    for (j, w) in t.windows(2).enumerate() {
        // (1 + t) ≥ 1: steps of `rise` in t keep each move within it.
        let pieces = ((w[1] - w[0]) / rise).ceil();
        if pieces > 1.0 && pieces < 1e6 {
            let n = pieces as usize;
            cuts.extend((1..n).map(|i| (j, i as f64 / n as f64)));
        }
    }
    cuts
}

/// How many layer heights a point `t` up layer `i`'s climb lays: one, or
/// `1 + t` on the first layer, whose climb rises off the plate.
pub fn laid(i: usize, t: f64) -> f64 {
    if i == 0 {
        1.0 + t
    } else {
        1.0
    }
}

/// Ends each layer's wall where the next one starts, to the bit: a spiral's
/// climb ends at the next layer's first point (computed the same way, but
/// with the nozzle following the wall the direction there is the next
/// layer's own), so the motion plan goes straight on into it.
pub fn join_layers(layers: &mut [Layer]) {
    for i in 1..layers.len() {
        let Some(&next) = layers[i].paths.first().and_then(|p| p.points.first()) else {
            continue;
        };
        if let Some(end) = layers[i - 1]
            .paths
            .last_mut()
            .and_then(|p| p.points.last_mut())
        {
            end.pos = next.pos;
            end.normal = next.normal;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_climb_rises_linearly_over_its_length_of_arc() {
        // A 40 mm square loop, closed; the last 30 mm climb.
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let pos = [
            p(0.0, 0.0),
            p(10.0, 0.0),
            p(10.0, 10.0),
            p(0.0, 10.0),
            p(0.0, 0.0),
        ];
        let t = shares(&pos, 30.0);
        let want = [0.0, 0.0, 10.0 / 30.0, 20.0 / 30.0, 1.0];
        for (a, b) in t.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{t:?}");
        }
        // Longer than the loop: a helix over all of it.
        let all = shares(&pos, f64::INFINITY);
        assert!((all[2] - 0.5).abs() < 1e-12, "{all:?}");
        assert_eq!(climb_start(&pos, 30.0), None);
        let (j, u) = climb_start(&pos, 25.0).unwrap();
        assert_eq!(j, 1);
        assert!((u - 0.5).abs() < 1e-12);
        assert_eq!(climb_start(&pos, 50.0), None);
        assert_eq!(laid(0, 0.5), 1.5);
        // A climb over one move, cut so each piece lays within 3 % of its
        // mean: 34 pieces of 1/34 of a layer height each.
        let cuts = first_climb_cuts(&[0.0, 0.0, 1.0], 0.03);
        assert_eq!(cuts.len(), 33);
        assert!(cuts.iter().all(|&(j, _)| j == 1));
        let mut at = vec![0.0];
        at.extend(cuts.iter().map(|c| c.1));
        at.push(1.0);
        for w in at.windows(2) {
            let (a, b) = (1.0 + w[0], 1.0 + w[1]);
            assert!((b - a) / (0.5 * (a + b)) <= 0.03, "{w:?}");
        }
        assert_eq!(laid(3, 0.5), 1.0);
    }
}

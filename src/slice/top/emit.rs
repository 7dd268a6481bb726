//! The IR layers of a variable-top solid. Layer `i` (from 0) of `N` is laid
//! on the planned top of layer `i − 1`: its points sit at `z = B + i·H/N`
//! (`B` the scanned surface a repair starts on, or the level its levelling
//! passes reached, else 0) and
//! each lays `H/N` there (`layer_height`), so the layers' heights add up to
//! the top at every point. Speeds come from the bead map: each segment's
//! height `H_seg/N` gives the *horizontal* speed, and the nozzle, climbing
//! along the planned top of the layer below at the slope `s` of the
//! segment's chord, runs at the path speed `v_h·√(1 + s²)`
//! ([`crate::slice::variable::speed`]). Tracks alternate direction, one
//! layer to the next and one track to the next; the laser is on along each.

use super::follow::{Follow, Tilted};
use super::surface::Base;
use super::tracks::Track;
use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{Axis, Bead, Model};
use crate::slice::variable::speed::{path_speed, HeightMap};
use crate::units::{Length, Speed};
use std::num::NonZeroU32;

/// The process values every point shares, and the surface the first
/// layer lies on.
pub struct Process<'m> {
    powder: f32,
    defocus: f32,
    speeds: [f64; 2],
    base: Base<'m>,
    /// `follow = surface`: the nozzle along the scan's normal.
    follow: Option<Follow<'m>>,
    /// The bead's width, mm: what the scan's slope is fitted over.
    width: f64,
}

impl<'m> Process<'m> {
    /// The model's process block and bead speed range, and what the layers
    /// start on.
    pub fn of(model: &Model, bead: &Bead, base: Base<'m>) -> Self {
        Process {
            powder: model.process.powder.g_min() as f32,
            defocus: model.process.defocus.0 as f32,
            speeds: [bead.speed[0].0, bead.speed[1].0],
            base,
            follow: None,
            width: bead.width.0,
        }
    }

    /// This process with the nozzle along the scan's normal up to `max`
    /// rad from vertical, when given and the layers start on the scan (a
    /// level's layers are flat: vertical).
    /// Planned turned, `up` is the part's vertical in the planning frame:
    /// the nozzle's tilt from it is held to `max` too.
    pub fn following(mut self, max: Option<f64>, up: Option<[f64; 3]>) -> Self {
        self.follow = match (max, self.base) {
            (Some(m), Base::Scan(s)) => Some(Follow::new(s, m, self.width).turned(up)),
            _ => None,
        };
        self
    }

    /// The height the first layer lies on at `(x, y)`: the scan's, or the
    /// plate's 0. The tracks' points are where the scan has a surface (the
    /// count checked every one).
    fn base(&self, x: f64, y: f64) -> f64 {
        self.base.at([x, y]).unwrap_or(0.0)
    }
}

/// Layer `i` of `n` over `tracks`.
pub fn layer(
    model: &Model,
    maps: &[impl HeightMap],
    process: &Process<'_>,
    tracks: &[Track],
    scan: Axis,
    i: u32,
    n: NonZeroU32,
) -> Layer {
    let power = model.process.power.at(i as usize).watts() as f32;
    let nf = n.get() as f64;
    let paths = tracks
        .iter()
        .enumerate()
        .map(|(k, tr)| Path {
            kind: PathKind::Infill,
            points: track(
                tr,
                &maps[k],
                process,
                scan,
                i,
                nf,
                power,
                (i as usize + k) % 2 == 1,
            ),
        })
        .collect();
    Layer {
        index: i as usize,
        station: i as f64 / nf,
        frame: Frame::PART,
        paths,
        label: String::new(),
        on_plate: false,
    }
}

/// The points of one track on layer `i`, backwards when `reverse`.
#[allow(clippy::too_many_arguments)]
pub(super) fn track(
    tr: &Track,
    map: &impl HeightMap,
    process: &Process<'_>,
    scan: Axis,
    i: u32,
    n: f64,
    power: f32,
    reverse: bool,
) -> Vec<Point> {
    let xy: Vec<[f64; 2]> =
        tr.t.iter()
            .map(|&t| super::footprint::Footprint::point(scan, t, tr.c))
            .collect();
    along(tr, &xy, map, process, Some(scan), (i, n), power, reverse)
}

/// The unit direction (x–y) of the line through `xy` at point `j`: of the
/// move from it, or into it at the last point.
pub(in crate::slice) fn direction(xy: &[[f64; 2]], j: usize) -> [f64; 2] {
    let (a, b) = if j + 1 < xy.len() {
        (j, j + 1)
    } else {
        (j.saturating_sub(1), j)
    };
    let (dx, dy) = (xy[b][0] - xy[a][0], xy[b][1] - xy[a][1]);
    let len = dx.hypot(dy);
    if len > 0.0 {
        [dx / len, dy / len]
    } else {
        [0.0; 2]
    }
}

/// The points of one track on layer `i` of `n`, through `xy` (a point
/// for each of its `t`), backwards when `reverse`. `scan` is the axis its
/// line runs along, which a nozzle following the surface leans along; a
/// track along a path (`None`) leans along its own direction.
#[allow(clippy::too_many_arguments)]
pub(in crate::slice) fn along(
    tr: &Track,
    xy: &[[f64; 2]],
    map: &impl HeightMap,
    process: &Process<'_>,
    scan: Option<Axis>,
    (i, n): (u32, f64),
    power: f32,
    reverse: bool,
) -> Vec<Point> {
    let frac = i as f64 / n;
    let pos: Vec<[f64; 3]> = xy
        .iter()
        .zip(&tr.h)
        .map(|(&[x, y], &h)| [x, y, process.base(x, y) + frac * h])
        .collect();
    // Layer `i` lies on `B + (i/N)·(top − B)`: its slope is `1 − i/N` of the
    // scan's where the top is flat (module `follow`). A track along a path
    // leans along its own direction at each point.
    let tilts: Option<Vec<Tilted>> = process.follow.map(|f| {
        (0..pos.len())
            .map(|j| {
                let along = scan.map_or_else(|| direction(xy, j), Axis::unit);
                f.at([pos[j][0], pos[j][1]], 1.0 - frac, along)
            })
            .collect()
    });
    let segments = segment_speeds(tr, &pos, tilts.as_deref(), map, process.speeds, n);
    let m = pos.len();
    // Move j runs from point j to j + 1 in the track's own direction.
    let order: Vec<usize> = if reverse {
        (0..m).rev().collect()
    } else {
        (0..m).collect()
    };
    order
        .iter()
        .enumerate()
        .map(|(k, &j)| {
            // The move from this point on, or into it at the last point.
            let (a, b) = if k + 1 < m {
                (j, order[k + 1])
            } else {
                (order[k - 1], j)
            };
            let mv = if reverse { b } else { a };
            let d = [
                pos[b][0] - pos[a][0],
                pos[b][1] - pos[a][1],
                pos[b][2] - pos[a][2],
            ];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-12);
            let tilt = tilts.as_ref().map_or(Tilted::VERTICAL, |t| t[j]);
            let (speed, strip) = segments[tr.seg[mv.min(tr.seg.len() - 1)]];
            Point {
                pos: pos[j],
                normal: tilt.normal.map(|v| v as f32),
                tangent: d.map(|v| (v / len) as f32),
                layer_height: (tr.h[j] / n * tilt.along_normal) as f32,
                speed: speed as f32,
                power,
                powder: process.powder,
                defocus: process.defocus,
                laser_on: k + 1 < m,
                style: 0,
                pitch: strip as f32,
                rise: 0.0,
            }
        })
        .collect()
}

/// What a segment's moves add up with the nozzle tilted.
#[derive(Clone, Copy, Default)]
struct SegmentTilt {
    /// The sum of its points' normals (its mean's direction).
    normal: [f64; 3],
    /// `cos θ` integrated along it, and its length along the track.
    cos_len: f64,
    len: f64,
    /// The widest strip of its points.
    strip: f64,
}

/// Each segment's path speed on this layer and the strip its points fill:
/// the map's horizontal speed for `H_seg/N`, times `√(1 + s²)` with `s`
/// the slope of the segment's chord on this layer's path, over the track's
/// own pitch; kept where every move of the segment crosses the ground
/// within the bead's speed range (on a curved top the moves' slopes differ
/// a little from the chord's).
///
/// With the nozzle tilted (`tilts`, module `follow`) each point fills its
/// own strip `p·cos α / cos θ`, which changes a little along a segment.
/// A segment is laid at one speed: its points all carry one strip, the
/// widest of theirs (so none of them plans a layer thinner than the bead
/// lays over the strip it is said to fill), and the speed across the
/// nozzle is the one that lays the segment's mean thickness along the
/// nozzle, `H_seg/N·cos θ̄`, over that strip: the bead map's at the pitch
/// `p` for `H_seg/N·cos θ̄·(strip/p)` (the same metal per length). One
/// speed over one strip is what `lmd::deposit` holds to the mean of what
/// its points plan; a strip differing in the last digits from point to
/// point would hold each point alone to it. The path speed is that speed
/// over the chord's share across the segment's mean normal.
fn segment_speeds(
    tr: &Track,
    pos: &[[f64; 3]],
    tilts: Option<&[Tilted]>,
    map: &impl HeightMap,
    [v_lo, v_hi]: [f64; 2],
    n: f64,
) -> Vec<(f64, f64)> {
    let q_count = tr.heights.len();
    // Per segment: first and last point, and the steepest and flattest move;
    // with a tilted nozzle, its [`SegmentTilt`].
    let mut first = vec![usize::MAX; q_count];
    let mut last = vec![0usize; q_count];
    let mut steep = vec![1.0f64; q_count];
    let mut flat = vec![f64::INFINITY; q_count];
    let mut tilt_sum = vec![SegmentTilt::default(); q_count];
    for (j, &q) in tr.seg.iter().enumerate() {
        first[q] = first[q].min(j);
        last[q] = j + 1;
        let f = match tilts {
            None => climb(pos[j], pos[j + 1]),
            Some(t) => {
                let s = &mut tilt_sum[q];
                for (a, v) in s.normal.iter_mut().zip(t[j].normal) {
                    *a += v;
                }
                let len = (tr.t[j + 1] - tr.t[j]).abs();
                s.cos_len += len * 0.5 * (t[j].along_normal + t[j + 1].along_normal);
                s.len += len;
                s.strip = (s.strip)
                    .max(t[j].pitch(tr.pitch))
                    .max(t[j + 1].pitch(tr.pitch));
                climb_across(pos[j], pos[j + 1], t[j].normal)
            }
        };
        steep[q] = steep[q].max(f);
        flat[q] = flat[q].min(f);
    }
    (0..q_count)
        .map(|q| {
            let SegmentTilt {
                normal,
                cos_len,
                len,
                strip,
            } = tilt_sum[q];
            let tilted = tilts.is_some() && strip > 0.0;
            let (h, strip) = if tilted {
                let cos = if len > 0.0 { cos_len / len } else { 1.0 };
                (tr.heights[q] / n * cos * strip / tr.pitch, strip)
            } else {
                (tr.heights[q] / n, tr.pitch)
            };
            let h = Length(h);
            // The layer count keeps every height in the map's range.
            let v_h = map.horizontal_speed(h).unwrap_or_else(|e| {
                let r = e.heights;
                map.speed_within(Length(h.0.clamp(r.low().0, r.high().0)))
            });
            if first[q] == usize::MAX {
                return (v_h.0, strip);
            }
            let (a, b) = (pos[first[q]], pos[last[q]]);
            let v = if tilted {
                v_h.0 * climb_across(a, b, normal)
            } else {
                let run = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                let slope = if run > 0.0 { (b[2] - a[2]) / run } else { 0.0 };
                path_speed(v_h, slope).map_or(v_h.0, |v: Speed| v.0)
            };
            let (lo, hi) = (v_lo * steep[q], v_hi * flat[q]);
            (if lo <= hi { v.clamp(lo, hi) } else { v }, strip)
        })
        .collect()
}

/// Path length per unit of ground across the normal `n` (need not be
/// unit) from `a` to `b`: `|d| / |d ⊥ n|`, the vertical case's `√(1 + s²)`.
fn climb_across(a: [f64; 3], b: [f64; 3], n: [f64; 3]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if nn <= 0.0 || len2 <= 0.0 {
        return 1.0;
    }
    let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    let across2 = len2 - along * along / nn;
    if across2 > 1e-18 * len2 {
        (len2 / across2).sqrt()
    } else {
        1.0
    }
}

/// Path length per unit of ground from `a` to `b`: `√(1 + s²)`.
fn climb(a: [f64; 3], b: [f64; 3]) -> f64 {
    let run = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    if run > 0.0 {
        ((b[2] - a[2]) / run).hypot(1.0)
    } else {
        1.0
    }
}

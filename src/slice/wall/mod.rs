//! A wall along an open path (`wall NAME { along = … }`) in flat layers:
//! layer `k` (from 0) on the plane z = k·lift, each of its beads a parallel
//! offset of the path (`beads` of them, the slicing's `offset` apart, laid
//! on the path's `side`), flattened within the chord error.
//!
//! The beads run along the path with the laser on from its first point to
//! its last. With `direction = alternate` (the default) the layers and the
//! beads of a layer take turns, so every bead runs the other way from the
//! one below it and the starts and stops of each end alternate with the
//! layers (the ends build evenly); with `one_way` every bead runs from the
//! path's start and the nozzle travels back between them. With `ends =
//! lead(length)` each bead gets a lead-in path before it and a lead-out
//! after it ([`PathKind::Lead`]): straight on along the bead's direction at
//! its ends, `length` long, laser off, at the bead's speed, so the nozzle
//! is at speed where the laser switches ([`crate::plan`]).
//!
//! A wall on a scan is laid the same way in layers of variable thickness
//! (module `on_scan`).

mod level;
mod on_scan;

pub use on_scan::{slice as slice_on_scan, top_form};

use super::layers;
use super::MAX_TOTAL_POINTS;
use crate::diag::message::{self, wall::PathSpans};
use crate::diag::Diagnostics;
use crate::geometry::open_path::{OpenPath, PathFault};
use crate::ir::{Frame, Layer, Path, PathKind, Point};
use crate::sema::model::{Bead, Extent, Model, OpenWall, PlanarSlicing, WallEnds, MAX_POINTS};

/// One bead's centre line, flattened, and its directions at its ends.
struct Track {
    points: Vec<[f64; 2]>,
    start: [f64; 2],
    end: [f64; 2],
}

impl Track {
    fn of(path: &OpenPath, chord_error: f64) -> Track {
        Track {
            points: path.flatten(chord_error),
            start: path.start_direction(),
            end: path.end_direction(),
        }
    }

    /// The same bead run the other way.
    fn reversed(&self) -> Track {
        let mut points = self.points.clone();
        points.reverse();
        Track {
            points,
            start: self.end.map(|c| -c),
            end: self.start.map(|c| -c),
        }
    }
}

/// How every point of a layer is laid.
struct Laid {
    z: f64,
    lift: f32,
    pitch: f32,
    speed: f32,
    power: f32,
    powder: f32,
    defocus: f32,
}

/// Slices a wall along an open path into flat layers. Returns the layers
/// and any warnings (a height rounded up to whole layers), or every
/// diagnostic found.
pub fn slice(
    model: &Model,
    bead: &Bead,
    wall: &OpenWall,
    extent: Extent,
    slicing: &PlanarSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let mut diags = Diagnostics::new();
    let Some((lift, pitch, _)) = layers::lift(bead, slicing, &mut diags) else {
        return Err(diags);
    };
    let n = match extent {
        Extent::Layers(n, _) => Some(n),
        Extent::Height(h, at) => layers::whole_layers(h, at, lift, &mut diags),
    };
    let Some(n) = n else {
        return Err(diags);
    };
    let tracks = match tracks(wall, bead.width.0, slicing.offset.0, slicing.chord_error.0) {
        Ok(t) => t,
        Err(fault) => {
            diags.push(fault_at(wall, fault));
            return Err(diags);
        }
    };
    let lead = match wall.ends {
        // A lead-in and a lead-out of two points a bead.
        WallEnds::Lead(_) => 4,
        WallEnds::Stop => 0,
    };
    let per_layer: usize = tracks.iter().map(|t| t.points.len() + lead).sum();
    if per_layer > MAX_POINTS || per_layer.saturating_mul(n) > MAX_TOTAL_POINTS {
        diags.push(message::wall::too_many_plan_points(
            n,
            per_layer,
            [MAX_TOTAL_POINTS, MAX_POINTS],
            wall.span,
        ));
        return Err(diags);
    }
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let laid = Laid {
            z: k as f64 * lift.0,
            lift: lift.0 as f32,
            pitch: pitch.0 as f32,
            speed: slicing.speed.0 as f32,
            power: model.process.power.at(k).watts() as f32,
            powder: model.process.powder.g_min() as f32,
            defocus: model.process.defocus.0 as f32,
        };
        let paths = beads(wall, &tracks, k, |_, _, t| {
            path(PathKind::Wall, &t.points, &laid).points
        });
        let frame = Frame {
            origin: [0.0, 0.0, laid.z],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        };
        out.push(layer(k, n, paths, frame));
    }
    Ok((out, diags))
}

/// The path fault `fault` of `wall`, as the error.
fn fault_at(wall: &OpenWall, fault: PathFault) -> crate::diag::Diagnostic {
    let spans = PathSpans {
        along: wall.along_span,
        pieces: &wall.pieces,
    };
    message::wall::path_fault(fault, &spans)
}

/// Each bead's centre line, left to right across the wall, for beads `w`
/// wide `pitch` apart, flattened within `chord_error`.
fn tracks(wall: &OpenWall, w: f64, pitch: f64, chord_error: f64) -> Result<Vec<Track>, PathFault> {
    let ce = chord_error;
    wall.offsets(w, pitch)
        .into_iter()
        .map(|d| match wall.path.offset(d) {
            Some(p) => Ok(Track::of(&p, ce)),
            // The checker found no fault with the faces; a bead between
            // them collapses only where they do.
            None => Err(PathFault::Collapses {
                at: wall.path.start(),
                reach: d,
                other: None,
            }),
        })
        .collect()
}

/// The beads of layer `k` in the order laid, each the way the wall's
/// direction gives, with their leads: `lay(j, forward, t)` gives the
/// points of the bead on track `j`, forward or not, `t` that track run the
/// way it is laid.
fn beads(
    wall: &OpenWall,
    tracks: &[Track],
    k: usize,
    lay: impl Fn(usize, bool, &Track) -> Vec<Point>,
) -> Vec<Path> {
    let mut paths = Vec::with_capacity(tracks.len() * 3);
    for (j, forward) in order(wall, tracks.len(), k) {
        let track = if forward {
            None
        } else {
            Some(tracks[j].reversed())
        };
        let t = track.as_ref().unwrap_or(&tracks[j]);
        let points = lay(j, forward, t);
        with_leads(wall.ends, points, [t.start, t.end], &mut paths);
    }
    paths
}

/// The bead through `points` onto `paths`, with a lead before and after it
/// when the wall's `ends` ask for them: straight on from its ends along
/// its directions there, `[start, end]` (unit, in x–y).
fn with_leads(
    ends: WallEnds,
    points: Vec<Point>,
    [start, end]: [[f64; 2]; 2],
    paths: &mut Vec<Path>,
) {
    let ends = match ends {
        WallEnds::Lead(l) => Some(l.0),
        WallEnds::Stop => None,
    };
    if let (Some(l), Some(first)) = (ends, points.first()) {
        let p = first.pos;
        let from = [p[0] - l * start[0], p[1] - l * start[1], p[2]];
        paths.push(lead(from, first));
    }
    let last = points.last().copied();
    paths.push(Path {
        kind: PathKind::Wall,
        points,
    });
    if let (Some(l), Some(last)) = (ends, last) {
        let p = last.pos;
        let to = [p[0] + l * end[0], p[1] + l * end[1], p[2]];
        paths.push(lead(to, &last));
    }
}

/// The beads of layer `k` of a wall of `m` in the order laid: each one's
/// track and whether it runs forward. Alternating: every other layer
/// across the wall the other way, and every other bead laid the other way
/// (so each bead runs the other way from the one below it).
fn order(wall: &OpenWall, m: usize, k: usize) -> Vec<(usize, bool)> {
    (0..m)
        .map(|i| {
            if wall.one_way {
                (i, true)
            } else {
                let j = if k.is_multiple_of(2) { i } else { m - 1 - i };
                (j, (k * m + i).is_multiple_of(2))
            }
        })
        .collect()
}

/// A lead between `at` and the bead's end point `end`, laser off, laid as
/// that point is: into it from `at` before a bead, out of it to `at`
/// after one (`end`'s laser is on only at a bead's start).
fn lead(at: [f64; 3], end: &Point) -> Path {
    let into = end.laser_on;
    let (a, b) = if into { (at, end.pos) } else { (end.pos, at) };
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    // As a flat bead's own points: `hypot` over the ground, exactly.
    let len = d[0].hypot(d[1]).hypot(d[2]).max(1e-12);
    let tangent = d.map(|v| (v / len) as f32);
    let point = |pos| Point {
        pos,
        tangent,
        laser_on: false,
        ..*end
    };
    Path {
        kind: PathKind::Lead,
        points: vec![point(a), point(b)],
    }
}

/// Layer `k` of `n` in `frame`.
fn layer(k: usize, n: usize, paths: Vec<Path>, frame: Frame) -> Layer {
    Layer {
        index: k,
        station: k as f64 / n as f64,
        frame,
        paths,
        label: String::new(),
        on_plate: false,
    }
}

/// The path through `pts` (at least two, each apart from the next): a
/// bead's with the laser on from its first point to its last, a lead's
/// with it off.
fn path(kind: PathKind, pts: &[[f64; 2]], l: &Laid) -> Path {
    let m = pts.len();
    let laser = kind != PathKind::Lead;
    let points = (0..m)
        .map(|i| {
            let (a, b) = if i + 1 < m {
                (i, i + 1)
            } else {
                (i.saturating_sub(1), i)
            };
            let (dx, dy) = (pts[b][0] - pts[a][0], pts[b][1] - pts[a][1]);
            let len = dx.hypot(dy).max(1e-12);
            Point {
                pos: [pts[i][0], pts[i][1], l.z],
                normal: [0.0, 0.0, 1.0],
                tangent: [(dx / len) as f32, (dy / len) as f32, 0.0],
                layer_height: l.lift,
                speed: l.speed,
                power: l.power,
                powder: l.powder,
                defocus: l.defocus,
                laser_on: laser && i + 1 < m,
                style: 0,
                pitch: l.pitch,
                rise: 0.0,
            }
        })
        .collect();
    Path { kind, points }
}

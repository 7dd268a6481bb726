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
    slicing: &PlanarSlicing,
) -> Result<(Vec<Layer>, Diagnostics), Diagnostics> {
    let mut diags = Diagnostics::new();
    let Some((lift, pitch, _)) = layers::lift(bead, slicing, &mut diags) else {
        return Err(diags);
    };
    let n = match wall.extent {
        Extent::Layers(n, _) => Some(n),
        Extent::Height(h, at) => layers::whole_layers(h, at, lift, &mut diags),
    };
    let Some(n) = n else {
        return Err(diags);
    };
    let tracks = match tracks(wall, bead, slicing) {
        Ok(t) => t,
        Err(fault) => {
            let spans = PathSpans {
                along: wall.along_span,
                pieces: &wall.pieces,
            };
            diags.push(message::wall::path_fault(fault, &spans));
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
        out.push(layer(wall, &tracks, k, n, &laid));
    }
    Ok((out, diags))
}

/// Each bead's centre line, left to right across the wall.
fn tracks(wall: &OpenWall, bead: &Bead, slicing: &PlanarSlicing) -> Result<Vec<Track>, PathFault> {
    let w = bead.width.0;
    let ce = slicing.chord_error.0;
    wall.offsets(w, slicing.offset.0)
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

/// Layer `k` of `n`: its beads in the order laid, each way the wall's
/// direction gives, with their leads.
fn layer(wall: &OpenWall, tracks: &[Track], k: usize, n: usize, laid: &Laid) -> Layer {
    let m = tracks.len();
    let mut paths = Vec::with_capacity(m * 3);
    for i in 0..m {
        // Alternating: every other layer across the wall the other way,
        // and every other bead laid the other way (so each bead runs the
        // other way from the one below it).
        let (j, forward) = if wall.one_way {
            (i, true)
        } else {
            let j = if k.is_multiple_of(2) { i } else { m - 1 - i };
            (j, (k * m + i).is_multiple_of(2))
        };
        let track = if forward {
            None
        } else {
            Some(tracks[j].reversed())
        };
        let t = track.as_ref().unwrap_or(&tracks[j]);
        let ends = match wall.ends {
            WallEnds::Lead(l) => Some(l.0),
            WallEnds::Stop => None,
        };
        if let (Some(l), Some(&first)) = (ends, t.points.first()) {
            let from = [first[0] - l * t.start[0], first[1] - l * t.start[1]];
            paths.push(path(PathKind::Lead, &[from, first], laid));
        }
        paths.push(path(PathKind::Wall, &t.points, laid));
        if let (Some(l), Some(&last)) = (ends, t.points.last()) {
            let to = [last[0] + l * t.end[0], last[1] + l * t.end[1]];
            paths.push(path(PathKind::Lead, &[last, to], laid));
        }
    }
    Layer {
        index: k,
        station: k as f64 / n as f64,
        frame: Frame {
            origin: [0.0, 0.0, laid.z],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        },
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

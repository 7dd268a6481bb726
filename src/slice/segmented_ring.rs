//! Slicing a segmented ring: layer after layer of the points
//! [`control::Ring::layer`](crate::control::Ring::layer) lays out, each
//! layer's path going on into the next one's (the laser stays on from the
//! first point to the last), and the IR's [`Ring`] that tells a back end
//! which points belong to which segment and how the speeds are chosen.
//!
//! The points are the nominal plan: layer `i` on the working plane
//! `z = i·h_r`, each segment at its speed of that layer — the table's when
//! the loop runs on the machine (the machine changes them as it measures),
//! the simulated loop's with `run = schedule`, the table's on every layer
//! without a loop. Every layer has the same points in plan view, so a
//! program may loop over one.

use super::MAX_TOTAL_POINTS;
use crate::control::{self, simulate, Invalid, LayerSpec, RingPoint};
use crate::diag::{message, Diagnostics};
use crate::ir::{Frame, HeightLoop, Layer, Path, PathKind, Point, Ring, RingRun, RingSegment};
use crate::sema::model::{LoopRun, RingBuild};
use crate::units::{Length, Speed};

/// The layers of `r` and the IR's description of its segments and loop.
pub fn build(r: &RingBuild) -> Result<(Vec<Layer>, Ring), Diagnostics> {
    let n = r.ring.segments();
    let per = r.ring.moves(r.step).map_err(|e| too_many(r, e))?;
    let layers = r.layers.get();
    let per_layer = n * per.total() + 1;
    if layers.saturating_mul(per_layer) > MAX_TOTAL_POINTS {
        return Err(too_many(
            r,
            Invalid::TooLarge {
                what: "points of the plan",
                value: layers as f64 * per_layer as f64,
                max: MAX_TOTAL_POINTS as f64,
            },
        ));
    }
    let (speeds, run) = schedule(r).map_err(|e| invalid(r, e))?;
    let h = r.layer_height.0;
    let powder = r.powder.g_min() as f32;
    let mut out = Vec::with_capacity(layers);
    for (i, layer_speeds) in speeds.iter().enumerate() {
        let base = vec![Length(i as f64 * h); n];
        let next = (i + 1 < layers).then(|| Length((i + 1) as f64 * h));
        let spec = LayerSpec {
            speeds: layer_speeds,
            base: &base,
            next_start: next,
        };
        let pts = r
            .ring
            .layer(&r.table, &spec, r.step)
            .map_err(|e| invalid(r, e))?;
        out.push(layer(i, layers, h, powder, &pts));
    }
    let segments = r
        .table
        .rows()
        .iter()
        .enumerate()
        .map(|(j, row)| RingSegment {
            defocus: row.defocus.0,
            power: row.power.watts(),
            width: row.width.0,
            speed: row.speed.0,
            energy_density: row.energy_density().j_mm2(),
            first_point: j * per.total(),
            transition_point: j * per.total() + per.flat,
        })
        .collect();
    let ring = Ring {
        radius: r.ring.radius().0,
        transition: r.ring.transition().deg(),
        layer_height: h,
        flat_moves: per.flat,
        transition_moves: per.transition,
        segments,
        run,
    };
    Ok((out, ring))
}

/// Each layer's speeds, and how the IR says they were chosen.
fn schedule(r: &RingBuild) -> Result<(Vec<Vec<Speed>>, RingRun), Invalid> {
    let table = r.table.speeds();
    let layers = r.layers.get();
    let Some(c) = &r.control else {
        let speeds = vec![table; layers];
        let run = RingRun::Schedule {
            speeds: rows(&speeds),
            control: None,
        };
        return Ok((speeds, run));
    };
    let law = height_loop(&c.controller);
    match c.run {
        LoopRun::OnMachine => Ok((vec![table; layers], RingRun::OnMachine(law))),
        LoopRun::Schedule => {
            let sim = simulate(&c.controller, &c.plant, &table, r.layers)?;
            let speeds: Vec<Vec<Speed>> = sim
                .samples()
                .chunks(r.ring.segments())
                .map(|layer| layer.iter().map(|s| s.speed).collect())
                .collect();
            let run = RingRun::Schedule {
                speeds: rows(&speeds),
                control: Some(law),
            };
            Ok((speeds, run))
        }
    }
}

/// The IR's copy of a checked loop.
pub fn height_loop(c: &control::Controller) -> HeightLoop {
    HeightLoop {
        kp: c.kp().mm_s_per_mm(),
        ki: c.ki().mm_s_per_mm(),
        target: c.target().0,
        clamp: [c.clamp().low().0, c.clamp().high().0],
    }
}

fn rows(speeds: &[Vec<Speed>]) -> Vec<Vec<f64>> {
    speeds
        .iter()
        .map(|l| l.iter().map(|v| v.0).collect())
        .collect()
}

/// One layer's path: every point but the last deposits (the last is where
/// the next layer's path starts, or the build's end).
fn layer(i: usize, layers: usize, h: f64, powder: f32, pts: &[RingPoint]) -> Layer {
    let last = pts.len().saturating_sub(1);
    let points = pts
        .iter()
        .enumerate()
        .map(|(k, p)| {
            // Counter-clockwise about +z.
            let (x, y) = (p.pos[0], p.pos[1]);
            let r = x.hypot(y);
            let tangent = if r > 0.0 {
                [(-y / r) as f32, (x / r) as f32, 0.0]
            } else {
                [1.0, 0.0, 0.0]
            };
            Point {
                pos: p.pos,
                normal: [0.0, 0.0, 1.0],
                tangent,
                layer_height: h as f32,
                speed: p.speed.0 as f32,
                power: p.power.watts() as f32,
                powder,
                defocus: p.defocus.0 as f32,
                laser_on: k < last,
                style: 0,
                pitch: 0.0,
                rise: 0.0,
            }
        })
        .collect();
    let z = i as f64 * h;
    Layer {
        index: i,
        station: i as f64 / layers as f64,
        frame: Frame {
            origin: [0.0, 0.0, z],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        },
        paths: vec![Path {
            kind: PathKind::Wall,
            points,
        }],
        label: String::new(),
        on_plate: false,
    }
}

fn too_many(r: &RingBuild, e: Invalid) -> Diagnostics {
    message::slicing::ring_too_large(&e, r.origins.layers, r.origins.ring).into()
}

/// A value the checker let through that the ring cannot be laid out with (it
/// checks every one, so this is a bug).
fn invalid(r: &RingBuild, e: Invalid) -> Diagnostics {
    message::internal::ring_layout(&e, r.origins.ring).into()
}

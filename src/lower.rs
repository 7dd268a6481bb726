//! Lowering: the semantic model → the IR. Slices the solid and attaches the
//! limits, machines and the source spans the IR checks report at.

use crate::control::SegmentProcess;
use crate::diag::{message, Diagnostics};
use crate::ir::{self, Layer, Limits, Origins, Program, Style, Units, FORMAT};
use crate::sema::model::{Build, Model, RingBuild};
use crate::slice;
use crate::span::Span;
use crate::target::{self, POSITION_STEP};
use crate::units::Length;

pub mod heat;

/// Builds the IR of a checked model; returns it with the slicer's warnings, or
/// the errors that make the part unbuildable.
pub fn lower(model: &Model) -> Result<(Program, Diagnostics), Diagnostics> {
    if let Build::Calibration(c) = &model.build {
        return Ok((calibration(model, c), Diagnostics::new()));
    }
    let (layers, warnings, ring) = match &model.build {
        Build::Ring(r) => {
            let (layers, ring) = slice::segmented_ring::build(r)?;
            (layers, Diagnostics::new(), Some(ring))
        }
        _ => {
            let (mut layers, warnings) = slice::slice(model)?;
            // A ring's segments name its points by index: only the others
            // are merged.
            merge_short_moves(&mut layers);
            (layers, warnings, None)
        }
    };
    let (limits, bead_height, bead_speed) = match (&model.build, &model.bead) {
        (Build::Ring(r), _) => ring_limits(model, r),
        (_, Some(bead)) => (
            Limits {
                layer_height: layer_heights(&model.build, bead, &layers),
                speed: [bead.speed[0].0, bead.speed[1].0],
                power: [
                    model.process.power_range[0].watts(),
                    model.process.power_range[1].watts(),
                ],
                bead_width: bead.width.0,
                rise_tolerance: model.tolerance.rise,
                max_drift: model.tolerance.drift.0,
                max_overhang: max_overhang(&model.build),
            },
            Some(bead.height_span),
            Some(bead.speed_span),
        ),
        (_, None) => return Err(message::internal::no_bead_in_lowering().into()),
    };
    let machines: Vec<_> = model.machines.iter().map(|(m, _)| m.clone()).collect();
    let bead = match (&model.build, &model.bead) {
        (Build::Ring(_), _) | (_, None) => None,
        // The model as declared: each point carries its own feed.
        (_, Some(b)) => Some(ir_bead(b)),
    };
    let version = match &bead {
        Some(b) if b.needs_calibrated_version() => ir::VERSION_CALIBRATED,
        _ => ir::version_for(bead.is_some(), ring.is_some(), &machines),
    };
    let version = ir::with_positioner(version, &machines);
    let program = Program {
        format: FORMAT.into(),
        version,
        part: model.part.clone(),
        units: Units::default(),
        limits,
        machines,
        styles: styles(model),
        heat: model.process.heat,
        thermal: None,
        fixtures: model.fixtures.iter().map(|(f, _)| f.clone()).collect(),
        continuous: ring.is_some() || spiral(model),
        bead,
        ring,
        layers,
        origins: origins(model, bead_height, bead_speed),
    };
    let mut program = program;
    predict_rises(&mut program);
    if let Some((declared, at)) = &model.process.thermal {
        program.thermal = Some(heat::predict(&mut program, declared, *at)?);
        heat::scale_powers(&mut program);
    }
    program.version = ir::with_later(&program);
    Ok((program, warnings))
}

/// Where the IR's limits and parts are written in the source.
fn origins(model: &Model, bead_height: Option<Span>, bead_speed: Option<Span>) -> Origins {
    Origins {
        bead_height,
        bead_speed,
        bead: model
            .bead
            .as_ref()
            .map(|b| b.tilt.map_or(b.span, |(_, at)| at)),
        power: Some(model.process.power_span),
        spine: match &model.build {
            Build::Duct { loft, .. } => Some(loft.spine_span),
            _ => None,
        },
        top: match &model.build {
            Build::Variable { extrusion, .. } => Some(extrusion.top_span),
            Build::ScanWall { on, .. } => Some(on.top_span),
            _ => None,
        },
        slicing: Some(match &model.build {
            Build::Duct { slicing, .. } => slicing.span,
            Build::Block { slicing, .. } | Build::Wall { slicing, .. } => slicing.span,
            Build::Variable { slicing, .. } | Build::ScanWall { slicing, .. } => slicing.span,
            Build::Ring(r) => r.origins.layers,
            Build::Calibration(c) => c.span,
        }),
        ring: match &model.build {
            Build::Ring(r) => Some(r.origins),
            _ => None,
        },
        machines: model.machines.iter().map(|(_, o)| o.clone()).collect(),
        fixtures: model.fixtures.iter().map(|(_, at)| *at).collect(),
    }
}

/// Merges each path's moves shorter than the step programs write
/// positions at ([`POSITION_STEP`]), where the nozzle also stands as it
/// did (arcs that meet leave points a fraction of a µm apart, which print
/// as a move to where the nozzle is, or one digit off it). Of the two
/// places the one nearer its neighbours' line goes (a corner stays), and
/// the later point's values hold on, since the earlier one's hold only
/// over the move; the path's first and last points keep their places.
/// A chain of such points merges only while it stays within one step of
/// where it began, so a curve sampled finely keeps its shape. A path that
/// is all one place keeps its points; the verifier names such moves that remain
/// (`lmd::short-move`).
pub fn merge_short_moves(layers: &mut [Layer]) {
    for path in layers.iter_mut().flat_map(|l| &mut l.paths) {
        let points = &mut path.points;
        if points.len() < 3 || points.iter().all(|p| same_place(&points[0], p)) {
            continue;
        }
        let mut kept = 1;
        let mut anchor = points[0];
        for k in 1..points.len() {
            let p = points[k];
            if !same_place(&anchor, &p) {
                if kept != k {
                    points[kept] = p;
                }
                kept += 1;
                anchor = p;
            } else if kept == 1 {
                points[0] = ir::Point {
                    pos: points[0].pos,
                    ..p
                };
            } else {
                // The place that goes is the one its neighbours' line
                // passes nearer: beside a corner, the point on the edge
                // goes and the corner stays. The later point's values go
                // on (they hold over the move onward); the path's last
                // point keeps its place.
                let a = points[kept - 1];
                let keep_a = points.get(k + 1).is_some_and(|next| {
                    off_segment(a.pos, points[kept - 2].pos, p.pos)
                        > off_segment(p.pos, a.pos, next.pos)
                });
                points[kept - 1] = if keep_a {
                    ir::Point { pos: a.pos, ..p }
                } else {
                    p
                };
            }
        }
        points.truncate(kept);
    }
}

/// How far `x` lies from the segment from `u` to `v`, mm.
fn off_segment(x: [f64; 3], u: [f64; 3], v: [f64; 3]) -> f64 {
    let d = [v[0] - u[0], v[1] - u[1], v[2] - u[2]];
    let w = [x[0] - u[0], x[1] - u[1], x[2] - u[2]];
    let dd: f64 = d.iter().map(|c| c * c).sum();
    let t = if dd > 0.0 {
        ((0..3).map(|i| w[i] * d[i]).sum::<f64>() / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|i| (w[i] - t * d[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Whether a move from `a` to `b` is shorter than a printed step and keeps
/// the nozzle's direction within a printed step of a degree.
fn same_place(a: &ir::Point, b: &ir::Point) -> bool {
    let d2: f64 = (0..3).map(|i| (a.pos[i] - b.pos[i]).powi(2)).sum();
    if d2 >= POSITION_STEP * POSITION_STEP {
        return false;
    }
    target::same_direction(a.normal, b.normal)
}

/// The IR's statement of the bead model: as declared (each point carries
/// its own feed), with where it was measured and how it was fitted.
fn ir_bead(b: &crate::sema::model::Bead) -> ir::Bead {
    ir::Bead {
        measured: b.measured.map(|[lo, hi]| [lo.0, hi.0]),
        tilt: b.tilt.map(|(t, _)| t.map(f64::to_degrees)),
        powers: b
            .powers
            .as_ref()
            .map(|(v, _)| v.iter().map(|p| p.watts()).collect()),
        powders: b
            .powders
            .as_ref()
            .map(|(v, _)| v.iter().map(|f| f.g_min()).collect()),
        fit: b.fit.as_ref().map(|f| ir::BeadFit {
            data: f.data.clone(),
            model: f.kind.name().to_string(),
            points: f.points,
            speeds: f.speeds,
            r2: f.r2,
            rms: f.rms,
            unit: f.unit.to_string(),
        }),
        ..ir::Bead::of(
            &crate::deposit::Deposit {
                model: b.model.clone(),
                width: b.width,
                basis: b.basis,
                widths: b.widths.clone(),
            },
            b.speed,
        )
    }
}

/// The layer heights the plan's bead stacks: its rises over its speeds
/// where each deposit fills the strip the plan gives it (a wall: its width;
/// overlapped tracks: their offset), narrowed to the declared `height`.
/// A variable layer's tracks fill the strips the layout gives them: the
/// heights are what the bead stacks from the widest of them to the
/// narrowest.
fn layer_heights(build: &Build, bead: &crate::sema::model::Bead, layers: &[Layer]) -> [f64; 2] {
    let pitch = match build {
        Build::Block { slicing, .. } | Build::Wall { slicing, .. } if slicing.overlapped() => {
            slicing.offset
        }
        Build::ScanWall { pitch, .. } => *pitch,
        Build::Variable { .. } => {
            let Some([narrow, wide]) = pitches(layers) else {
                return bead.height.map(|h| h.0);
            };
            let lo = bead.heights(Length(wide))[0];
            let hi = bead.heights(Length(narrow))[1];
            return [lo.0, hi.0];
        }
        _ => bead.width,
    };
    bead.heights(pitch).map(|h| h.0)
}

/// The narrowest and the widest pitch of `layers`' laser-on points.
fn pitches(layers: &[Layer]) -> Option<[f64; 2]> {
    layers
        .iter()
        .flat_map(|l| &l.paths)
        .flat_map(|p| &p.points)
        .filter(|q| q.laser_on && q.pitch > 0.0)
        .map(|q| q.pitch as f64)
        .fold(None, |r, p| match r {
            None => Some([p, p]),
            Some([lo, hi]) => Some([lo.min(p), hi.max(p)]),
        })
}

/// Each laser-on point's `rise` by the plan's bead model: `A/pitch` at its
/// speed across the normal and its own powder feed.
fn predict_rises(p: &mut Program) {
    let Some(bead) = &p.bead else { return };
    let deposit = bead.deposit();
    for path in p.layers.iter_mut().flat_map(|l| &mut l.paths) {
        let n = path.points.len();
        for k in 0..n {
            let pt = &path.points[k];
            if !pt.laser_on || pt.pitch <= 0.0 {
                continue;
            }
            let rise = pt.predicted_rise(&deposit, path.points.get(k + 1));
            path.points[k].rise = rise as f32;
        }
    }
}

/// The declared `max_overhang` of a loft's normal slicing, the only
/// slicing that declares one.
fn max_overhang(build: &Build) -> Option<f64> {
    match build {
        // The IR's angles are degrees (`units.angle`).
        Build::Duct { slicing, .. } => slicing.max_overhang.map(f64::to_degrees),
        Build::Block { slicing, .. } | Build::Wall { slicing, .. } => {
            slicing.max_overhang.map(f64::to_degrees)
        }
        _ => None,
    }
}

/// A ring's limits: every layer `h_r` high; the speeds the loop may choose
/// (the clamp; the table's without a loop), the table's powers (or the
/// declared `power_range`), and its narrowest width as the bead the layers
/// are checked to lie on.
fn ring_limits(model: &Model, r: &RingBuild) -> (Limits, Option<Span>, Option<Span>) {
    let rows = r.table.rows();
    let fold = |f: fn(&SegmentProcess) -> f64| {
        rows.iter()
            .map(f)
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], x| {
                [lo.min(x), hi.max(x)]
            })
    };
    let table_speeds = fold(|row| row.speed.0);
    let speed = match &r.control {
        Some(c) => [c.controller.clamp().low().0, c.controller.clamp().high().0],
        None => table_speeds,
    };
    let h = r.layer_height.0;
    let limits = Limits {
        layer_height: [h, h],
        speed,
        power: [
            model.process.power_range[0].watts(),
            model.process.power_range[1].watts(),
        ],
        bead_width: fold(|row| row.width.0)[0],
        rise_tolerance: ir::RISE_TOLERANCE,
        max_drift: ir::MAX_DRIFT,
        max_overhang: None,
    };
    let speed_span = match &r.control {
        Some(_) => r.origins.clamp,
        None => r.origins.ring,
    };
    (limits, Some(r.origins.layers), Some(speed_span))
}

/// A calibration file's plan: its coupons, with no bead model (the
/// coupons are what measures it). Every laser-on point must lie within the
/// coupons' speeds, the laser's powers and the layer height declared.
fn calibration(model: &Model, c: &crate::sema::model::Calibration) -> Program {
    let speeds = c
        .coupons
        .iter()
        .map(|k| k.speed.0)
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| {
            [lo.min(v), hi.max(v)]
        });
    let machines: Vec<_> = model.machines.iter().map(|(m, _)| m.clone()).collect();
    let h = c.layer_height.0;
    Program {
        format: FORMAT.into(),
        version: ir::VERSION_COUPONS,
        part: model.part.clone(),
        units: Units::default(),
        limits: Limits {
            layer_height: [h, h],
            speed: speeds,
            power: [
                model.process.power_range[0].watts(),
                model.process.power_range[1].watts(),
            ],
            bead_width: c.width.0,
            rise_tolerance: ir::RISE_TOLERANCE,
            max_drift: ir::MAX_DRIFT,
            max_overhang: None,
        },
        machines,
        styles: Vec::new(),
        heat: model.process.heat,
        thermal: None,
        fixtures: model.fixtures.iter().map(|(f, _)| f.clone()).collect(),
        continuous: false,
        bead: None,
        ring: None,
        layers: slice::calibration::build(c, &model.process),
        origins: Origins {
            bead_height: Some(c.span),
            bead_speed: Some(c.span),
            bead: None,
            power: Some(model.process.power_span),
            spine: None,
            top: None,
            slicing: Some(c.span),
            ring: None,
            machines: model.machines.iter().map(|(_, o)| o.clone()).collect(),
            fixtures: model.fixtures.iter().map(|(_, at)| *at).collect(),
        },
    }
}

/// Whether the model's wall climbs from layer to layer with the laser on
/// (`layer_change = spiral`): its layers, like a ring's, go on into each
/// other.
fn spiral(model: &Model) -> bool {
    match &model.build {
        Build::Duct { slicing, .. } => slicing.layer_change.is_spiral(),
        Build::Block { slicing, .. } => slicing.layer_change.is_spiral(),
        _ => false,
    }
}

/// The style table as the IR holds it.
fn styles(model: &Model) -> Vec<Style> {
    model
        .styles
        .table
        .iter()
        .map(|s| Style {
            id: s.id,
            name: s.name.clone(),
            power: s.power.map(|p| p.watts()),
            speed: s.speed.map(|v| v.0),
            powder: s.powder.map(|m| m.g_min()),
            colour: s.colour.clone(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Frame, Path, PathKind, Point};

    fn point(x: f64, speed: f32) -> Point {
        at([x, 0.0], speed)
    }

    fn at([x, y]: [f64; 2], speed: f32) -> Point {
        Point {
            pos: [x, y, 0.0],
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            layer_height: 0.5,
            speed,
            power: 1000.0,
            powder: 10.0,
            defocus: 0.0,
            laser_on: true,
            style: 0,
            pitch: 2.0,
            rise: 0.0,
        }
    }

    fn merged(xs: &[(f64, f32)]) -> Vec<(f64, f32)> {
        let points = xs.iter().map(|&(x, v)| point(x, v)).collect();
        merged_path(points)
            .iter()
            .map(|p| (p.pos[0], p.speed))
            .collect()
    }

    fn merged_path(points: Vec<Point>) -> Vec<Point> {
        let mut layers = [Layer {
            index: 0,
            station: 0.0,
            frame: Frame::PART,
            paths: vec![Path {
                kind: PathKind::Contour,
                points,
            }],
            label: String::new(),
            on_plate: false,
        }];
        merge_short_moves(&mut layers);
        std::mem::take(&mut layers[0].paths[0].points)
    }

    /// Issue 38 item 5: arcs that meet left points 0.3 µm apart, written as
    /// `X-14.646` then `X-14.647`. The earlier point of such a move goes
    /// (the later one's values hold on), the path's ends keep their places,
    /// and a chain merges only within one step of where it began.
    #[test]
    fn moves_below_the_printed_step_are_merged() {
        let v = |x: f64| (x, 5.0);
        // Inside: the later point stays, with its own speed.
        assert_eq!(
            merged(&[v(0.0), (10.0, 5.0), (10.0003, 7.0), v(20.0)]),
            [v(0.0), (10.0003, 7.0), v(20.0)]
        );
        // At the start: the first place, the next point's values.
        assert_eq!(
            merged(&[v(0.0), (0.0003, 7.0), v(20.0)]),
            [(0.0, 7.0), v(20.0)]
        );
        // At the end: the last place.
        assert_eq!(merged(&[v(0.0), v(20.0), v(20.0004)]), [v(0.0), v(20.0004)]);
        // A fine chain keeps a point a step on from where it began.
        assert_eq!(
            merged(&[v(0.0), v(1.0), v(1.0006), v(1.0012), v(1.0018), v(5.0)]),
            [v(0.0), v(1.0006), v(1.0018), v(5.0)]
        );
        // A step or more, or a path that is all one place: as they were.
        let same = [v(0.0), v(0.001), v(0.002)];
        assert_eq!(merged(&same), same);
        let one = [v(1.0), v(1.0002), v(1.0001)];
        assert_eq!(merged(&one), one);
        // Beside a corner, the corner stays, with the later point's values.
        let corner = merged_path(vec![
            at([0.0, 0.0], 5.0),
            at([10.0, 0.0], 5.0),
            at([10.0, 0.0007], 7.0),
            at([10.0, 10.0], 5.0),
        ]);
        let got: Vec<_> = corner.iter().map(|p| (p.pos, p.speed)).collect();
        assert_eq!(
            got,
            [
                ([0.0, 0.0, 0.0], 5.0),
                ([10.0, 0.0, 0.0], 7.0),
                ([10.0, 10.0, 0.0], 5.0)
            ]
        );
    }
}

//! Lowering: the semantic model → the IR. Slices the solid and attaches the
//! limits, machines and the source spans the IR checks report at.

use crate::control::SegmentProcess;
use crate::diag::{message, Diagnostics};
use crate::ir::{self, Layer, Limits, Origins, Program, Style, Units, FORMAT};
use crate::sema::model::{Build, Model, RingBuild};
use crate::slice;
use crate::span::Span;
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
            let (layers, warnings) = slice::slice(model)?;
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
        origins: Origins {
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
                _ => None,
            },
            slicing: Some(match &model.build {
                Build::Duct { slicing, .. } => slicing.span,
                Build::Block { slicing, .. } | Build::Wall { slicing, .. } => slicing.span,
                Build::Variable { slicing, .. } => slicing.span,
                Build::Ring(r) => r.origins.layers,
                Build::Calibration(c) => c.span,
            }),
            ring: match &model.build {
                Build::Ring(r) => Some(r.origins),
                _ => None,
            },
            machines: model.machines.iter().map(|(_, o)| o.clone()).collect(),
            fixtures: model.fixtures.iter().map(|(_, at)| *at).collect(),
        },
    };
    let mut program = program;
    predict_rises(&mut program);
    if let Some((declared, at)) = &model.process.thermal {
        program.thermal = Some(heat::predict(&program, declared, *at)?);
        heat::scale_powers(&mut program);
    }
    Ok((program, warnings))
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

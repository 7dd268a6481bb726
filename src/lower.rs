//! Lowering: the semantic model → the IR. Slices the solid and attaches the
//! limits, machines and the source spans the IR checks report at.

use crate::diag::Diagnostics;
use crate::ir::{version_for, Limits, Origins, Program, Style, Units, FORMAT};
use crate::sema::model::{Model, Plan};
use crate::slice;

/// Builds the IR of a checked model; returns it with the slicer's warnings, or
/// the errors that make the part unbuildable.
pub fn lower(model: &Model) -> Result<(Program, Diagnostics), Diagnostics> {
    let (layers, warnings) = slice::slice(model)?;
    let bead = &model.bead;
    let machines: Vec<_> = model.machines.iter().map(|(m, _)| m.clone()).collect();
    let program = Program {
        format: FORMAT.into(),
        version: version_for(&machines),
        part: model.part.clone(),
        units: Units::default(),
        limits: Limits {
            layer_height: [bead.height[0].0, bead.height[1].0],
            speed: [bead.speed[0].0, bead.speed[1].0],
            power: [
                model.process.power_range[0].watts(),
                model.process.power_range[1].watts(),
            ],
            bead_width: bead.width.0,
        },
        machines,
        styles: model
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
            .collect(),
        heat: model.process.heat,
        layers,
        origins: Origins {
            bead_height: Some(bead.height_span),
            bead_speed: Some(bead.speed_span),
            power: Some(model.process.power_span),
            spine: match &model.plan {
                Plan::Duct { loft, .. } => Some(loft.spine_span),
                Plan::Block { .. } | Plan::Variable { .. } => None,
            },
            top: match &model.plan {
                Plan::Variable { extrusion, .. } => Some(extrusion.top_span),
                _ => None,
            },
            slicing: Some(match &model.plan {
                Plan::Duct { slicing, .. } => slicing.span,
                Plan::Block { slicing, .. } => slicing.span,
                Plan::Variable { slicing, .. } => slicing.span,
            }),
            machines: model.machines.iter().map(|(_, o)| o.clone()).collect(),
        },
    };
    Ok((program, warnings))
}

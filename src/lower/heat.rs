//! The thermal prediction of a lowered plan (docs/thermal.md): each
//! layer's load summed from its points, the model run over the layers,
//! the waits a `max_interpass` asks written into the IR.

use crate::diag::{message, Diagnostics};
use crate::ir::{Cooling, Heat, Layer, LayerHeat, Program, Thermal};
use crate::sema::schema::process::MAX_DWELL_S;
use crate::span::Span;
use crate::thermal::{self, Budget, Lever, Load, Material, Plate};

/// mm → m.
const M: f64 = 1e-3;

/// The IR's thermal block for `program`, its layers predicted, each wait
/// the least that keeps `max_interpass`; or the refusal of the first layer
/// no allowed cooling keeps within it, reported at `at`.
pub fn predict(program: &Program, declared: &Thermal, at: Span) -> Result<Thermal, Diagnostics> {
    let width = program.limits.bead_width;
    let loads: Vec<(Load, [f64; 3])> = program.layers.iter().map(|l| load(l, width)).collect();
    let (material, plate) = cell(declared);
    let heat = program.heat;
    let base = |i: usize| base_wait(heat, loads[i - 1].0.time);
    let least = least_power(program);
    let budget = declared.max_interpass.map(|max_interpass| Budget {
        max_interpass,
        lever: match declared.cooling {
            Cooling::Dwell => Lever::Dwell {
                longest: MAX_DWELL_S,
            },
            Cooling::Power => Lever::Power { least: &least },
        },
    });
    let just: Vec<Load> = loads.iter().map(|l| l.0).collect();
    let predicted = thermal::predict(material, plate, &just, base, budget).map_err(|o| {
        let limit = declared.max_interpass.unwrap_or(0.0);
        let cooling = match declared.cooling {
            Cooling::Dwell => "dwell",
            Cooling::Power => "power",
        };
        let o = message::thermal::Overheat {
            layer: o.layer + 1,
            interpass: o.interpass,
            limit,
            cooling,
            longest: MAX_DWELL_S,
            needs: o.needs,
            preheat: o.layer == 0,
            floor: match declared.cooling {
                Cooling::Power => Some(power_floor(program)),
                Cooling::Dwell => None,
            },
        };
        Diagnostics::from(message::thermal::interpass(o, at))
    })?;
    let layers = predicted
        .iter()
        .zip(&loads)
        .enumerate()
        .map(|(i, (p, (_, start)))| {
            let base = if i == 0 { 0.0 } else { base(i) };
            LayerHeat {
                at: *start,
                time: p.start,
                interpass: p.interpass,
                peak: p.peak,
                wait: p.wait,
                added: (p.wait - base).max(0.0),
                power: p.power,
            }
        })
        .collect();
    Ok(Thermal {
        layers,
        ..declared.clone()
    })
}

/// The model's material and plate as the IR's thermal block states them.
pub fn cell(t: &Thermal) -> (Material, Plate) {
    let material = Material {
        conductivity: t.conductivity,
        density: t.density,
        heat_capacity: t.heat_capacity,
        emissivity: t.emissivity,
        absorptivity: t.absorptivity,
        heat_transfer: t.heat_transfer,
    };
    let plate = Plate {
        size: t.plate.map(|x| x * M),
        temperature: t.preheat,
        ambient: t.ambient,
    };
    (material, plate)
}

/// Each layer's load as the model takes it, from the IR's points (their
/// powers as the plan lays them).
pub fn loads(program: &Program) -> Vec<Load> {
    let width = program.limits.bead_width;
    program.layers.iter().map(|l| load(l, width).0).collect()
}

/// The least share of its power each layer may be laid at: its lowest
/// laser-on power brought down to the bottom of the laser's range, or of
/// the bead's measured powers where they are known (lower would be
/// extrapolation, `lmd::extrapolation`).
fn least_power(program: &Program) -> Vec<f64> {
    let floor = power_floor(program);
    program
        .layers
        .iter()
        .map(|l| {
            let lowest = l
                .paths
                .iter()
                .flat_map(|p| &p.points)
                .filter(|p| p.laser_on)
                .map(|p| p.power as f64)
                .reduce(f64::min);
            match lowest {
                Some(p) if p > 0.0 => (floor / p).clamp(0.0, 1.0),
                _ => 1.0,
            }
        })
        .collect()
}

/// The least power a layer may be laid at, W: the bottom of the laser's
/// range, or of the bead's measured powers where they are known and higher.
fn power_floor(program: &Program) -> f64 {
    let bead = program
        .bead
        .as_ref()
        .and_then(|b| b.powers.as_ref())
        .and_then(|p| p.iter().copied().reduce(f64::min));
    bead.map_or(program.limits.power[0], |b| b.max(program.limits.power[0]))
}

/// Lays each layer at the share of its power the prediction chose.
pub fn scale_powers(program: &mut Program) {
    let Some(t) = &program.thermal else { return };
    let shares: Vec<f64> = t.layers.iter().map(|l| l.power).collect();
    for (layer, share) in program.layers.iter_mut().zip(shares) {
        if share == 1.0 {
            continue;
        }
        for p in layer.paths.iter_mut().flat_map(|p| &mut p.points) {
            if p.laser_on {
                p.power = (p.power as f64 * share) as f32;
            }
        }
    }
}

/// The wait the plan keeps before a layer whatever the budget, s: the
/// declared dwell, or what the layer before (`time` s) falls short of the
/// minimum layer time.
pub fn base_wait(heat: Heat, time: f64) -> f64 {
    heat.dwell.max(heat.min_layer_time - time).max(0.0)
}

/// A layer's load (SI) and where it starts (its first deposit point, mm):
/// the laser's energy and the time over its moves at their speeds (rapid
/// moves between paths instant), the metal its deposits lay (`rise ×
/// pitch`, else a bead's width times the layer height), its height (the
/// mean over its deposits' length) and its outline: the convex hull of its
/// points grown by half a bead (the perimeter of the hull plus `π·w`), the
/// outline of the part's outside for a solid layer, short of a hollow
/// part's inner faces (which makes the model cool it less than it cools).
fn load(layer: &Layer, width: f64) -> (Load, [f64; 3]) {
    let (mut energy, mut time, mut volume, mut length, mut heights) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut start = None;
    let mut plan = Vec::new();
    let f = &layer.frame;
    let on =
        |p: [f64; 3], axis: [f64; 3]| (0..3).map(|k| (p[k] - f.origin[k]) * axis[k]).sum::<f64>();
    for path in &layer.paths {
        for pair in path.points.windows(2) {
            let (p, q) = (&pair[0], &pair[1]);
            let d = (0..3)
                .map(|k| (q.pos[k] - p.pos[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let t = if p.speed > 0.0 {
                d / p.speed as f64
            } else {
                0.0
            };
            time += t;
            if !p.laser_on || d <= 0.0 {
                continue;
            }
            start.get_or_insert(p.pos);
            energy += p.power as f64 * t;
            let area = if p.rise > 0.0 && p.pitch > 0.0 {
                p.rise as f64 * p.pitch as f64
            } else {
                p.layer_height as f64 * width
            };
            volume += area * d;
            length += d;
            heights += p.layer_height as f64 * d;
            // Each deposit's start, and the end of a run: every point of
            // the deposits once.
            plan.push([on(p.pos, f.x), on(p.pos, f.y)]);
            if !q.laser_on || std::ptr::eq(q, path.points.last().expect("a pair")) {
                plan.push([on(q.pos, f.x), on(q.pos, f.y)]);
            }
        }
    }
    let corners = crate::slice::top::hull(plan);
    let outline: f64 = (0..corners.len())
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
        })
        .sum::<f64>()
        + std::f64::consts::PI * width;
    let height = if length > 0.0 { heights / length } else { 0.0 };
    (
        Load {
            energy,
            time,
            volume: volume * M * M * M,
            height: height * M,
            perimeter: outline * M,
        },
        start.unwrap_or(layer.frame.origin),
    )
}

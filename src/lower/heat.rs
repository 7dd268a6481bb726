//! The thermal prediction of a lowered plan (docs/thermal.md): each
//! layer's load summed from its points, the model run over the layers,
//! the waits a `max_interpass` asks written into the IR.

use crate::diag::{message, Diagnostics};
use crate::ir::{Cooling, Heat, IslandHeat, Layer, LayerHeat, PathKind, Program, Thermal};
use crate::sema::schema::process::MAX_DWELL_S;
use crate::span::Span;
use crate::thermal::{self, Budget, Lever, Levers, Load, Material, Plate};

/// mm → m.
const M: f64 = 1e-3;

/// The IR's thermal block for `program`, its layers predicted, each wait
/// the least that keeps `max_interpass`; or the refusal of the first layer
/// no allowed cooling keeps within it, reported at `at`. Where `cooling`
/// allows `order`, each layer's paths are reordered island by island as
/// the prediction chose.
pub fn predict(
    program: &mut Program,
    declared: &Thermal,
    at: Span,
) -> Result<Thermal, Diagnostics> {
    let parts = Parts::of(program);
    let (material, plate) = cell(declared);
    let heat = program.heat;
    let base = |i: usize| base_wait(heat, parts.time(i - 1));
    let least = least_power(program);
    let levers = declared
        .cooling
        .levers()
        .iter()
        .fold(Levers::default(), |l, c| {
            l.with(match c {
                Cooling::Dwell => Lever::Dwell {
                    longest: MAX_DWELL_S,
                },
                Cooling::Power => Lever::Power { least: &least },
                Cooling::Order => Lever::Order,
            })
        });
    let budget = declared.max_interpass.map(|max_interpass| Budget {
        max_interpass,
        levers,
    });
    let run = |budget| {
        let (loads, orders) = (&parts.loads, &parts.orders);
        thermal::predict_tree(material, plate, &parts.columns, loads, orders, base, budget)
    };
    let predicted = run(budget).map_err(|o| refusal(program, declared, &parts, o, at))?;
    // What waits alone would have cost, for the report to weigh the free
    // levers against.
    let alone = declared.cooling.levers() != [Cooling::Dwell];
    let dwell_alone = match budget {
        Some(b) if alone => run(Some(Budget {
            levers: Lever::Dwell {
                longest: MAX_DWELL_S,
            }
            .into(),
            ..b
        }))
        .ok()
        .map(|p| {
            p.iter()
                .enumerate()
                .skip(1)
                .map(|(i, l)| (l.layer.wait - base(i)).max(0.0))
                .sum::<f64>()
        }),
        _ => None,
    };
    let layers = predicted
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let base = if i == 0 { 0.0 } else { base(i) };
            let islands = parts.islands_heat(i, &p.islands);
            let start = islands.first().map_or(parts.starts[i][0], |s| s.at);
            LayerHeat {
                at: start,
                time: p.layer.start,
                interpass: p.layer.interpass,
                peak: p.layer.peak,
                wait: p.layer.wait,
                added: (p.layer.wait - base).max(0.0),
                power: p.layer.power,
                islands,
                reordered: p.layer.reordered,
            }
        })
        .collect();
    if declared.cooling.allows(Cooling::Order) {
        for (i, (layer, p)) in program.layers.iter_mut().zip(&predicted).enumerate() {
            let order: Vec<usize> = p.islands.iter().map(|i| i.island).collect();
            parts.reorder(layer, i, &order);
        }
    }
    Ok(Thermal {
        layers,
        dwell_alone,
        ..declared.clone()
    })
}

/// The refusal of the layer `o` names.
fn refusal(
    program: &Program,
    declared: &Thermal,
    parts: &Parts,
    o: thermal::Overheat,
    at: Span,
) -> Diagnostics {
    let limit = declared.max_interpass.unwrap_or(0.0);
    let cooling: Vec<&str> = declared.cooling.levers().iter().map(|c| c.word()).collect();
    let island = (parts.loads.get(o.layer).map_or(0, Vec::len) > 1)
        .then(|| parts.island_start(o.layer, o.island));
    let o = message::thermal::Overheat {
        layer: o.layer + 1,
        interpass: o.interpass,
        limit,
        cooling: &cooling,
        longest: MAX_DWELL_S,
        needs: o.needs,
        by_order: o.by_order,
        first_layer: (o.layer == 0).then_some(declared.preheat),
        floor: declared
            .cooling
            .allows(Cooling::Power)
            .then(|| power_floor(program)),
        island,
    };
    Diagnostics::from(message::thermal::interpass(o, at))
}

/// A plan's layers as the model takes them: each layer's islands in the
/// plan's order, the column each is laid on, their loads, where they
/// start and which paths they are.
struct Parts {
    /// `loads[i][g]`: island `g` of layer `i`.
    loads: Vec<Vec<Load>>,
    /// `orders[i]`: the islands in the order the slicer lays them.
    orders: Vec<Vec<usize>>,
    /// Which column each island is laid on, and where each column stands.
    columns: thermal::Columns,
    /// `starts[i][g]`: where island `g` of layer `i` starts, mm.
    starts: Vec<Vec<[f64; 3]>>,
    /// `paths[i][g]`: the paths of island `g` of layer `i`, in the plan's
    /// order (a run of them).
    paths: Vec<Vec<std::ops::Range<usize>>>,
}

impl Parts {
    /// The islands of `program`'s layers and the columns they stand on
    /// ([`columns`]); where they cannot be told apart ([`islands`]), each
    /// layer as one piece (the part as one column).
    fn of(program: &Program) -> Parts {
        let width = program.limits.bead_width;
        let found: Option<Vec<Vec<Island>>> =
            program.layers.iter().map(|l| islands(l, width)).collect();
        let columns = found.as_deref().and_then(|f| columns(f, width));
        let (Some(found), Some(columns)) = (found, columns) else {
            return Parts::whole(program, width);
        };
        let mut parts = Parts {
            loads: Vec::with_capacity(found.len()),
            orders: Vec::with_capacity(found.len()),
            columns,
            starts: Vec::with_capacity(found.len()),
            paths: Vec::with_capacity(found.len()),
        };
        for (layer, isl) in program.layers.iter().zip(&found) {
            let (loads, starts): (Vec<Load>, Vec<[f64; 3]>) = isl
                .iter()
                .map(|island| load(layer, island.paths.clone(), width))
                .unzip();
            parts.loads.push(loads);
            parts.orders.push((0..isl.len()).collect());
            parts.starts.push(starts);
            parts
                .paths
                .push(isl.iter().map(|i| i.paths.clone()).collect());
        }
        parts
    }

    /// Each layer as one piece: today's lumped column.
    fn whole(program: &Program, width: f64) -> Parts {
        let mut parts = Parts {
            loads: Vec::new(),
            orders: Vec::new(),
            columns: thermal::Columns {
                stands: vec![thermal::Stand::Plate],
                joins: Vec::new(),
                of: vec![vec![0]; program.layers.len()],
            },
            starts: Vec::new(),
            paths: Vec::new(),
        };
        for layer in &program.layers {
            let (load, start) = load(layer, 0..layer.paths.len(), width);
            parts.loads.push(vec![load]);
            parts.orders.push(vec![0]);
            parts.starts.push(vec![start]);
            let all = 0..layer.paths.len();
            parts.paths.push(vec![all]);
        }
        parts
    }

    /// How long layer `i` takes to lay, s (rapid moves instant).
    fn time(&self, i: usize) -> f64 {
        self.loads[i].iter().map(|l| l.time).sum()
    }

    /// Where island `c` of layer `i` starts, mm.
    fn island_start(&self, i: usize, c: usize) -> [f64; 3] {
        self.starts[i].get(c).copied().unwrap_or([0.0; 3])
    }

    /// The IR's islands of layer `i` as predicted (none for a layer of
    /// one piece).
    fn islands_heat(&self, i: usize, p: &[thermal::IslandPrediction]) -> Vec<IslandHeat> {
        if p.len() < 2 {
            return Vec::new();
        }
        p.iter()
            .map(|q| IslandHeat {
                at: self.island_start(i, q.island),
                time: q.start,
                interpass: q.interpass,
                peak: q.peak,
            })
            .collect()
    }

    /// Lays `layer`'s islands in `order`: their runs of paths
    /// one after the other. The motion plan joins them as it joins any
    /// two paths (a lift, a travel above what is built, the lowering).
    fn reorder(&self, layer: &mut Layer, i: usize, order: &[usize]) {
        let Some(runs) = self.paths.get(i) else {
            return;
        };
        if order.len() < 2 || runs.len() != order.len() {
            return;
        }
        let mut paths = Vec::with_capacity(layer.paths.len());
        for &c in order {
            paths.extend(layer.paths[runs[c].clone()].iter().cloned());
        }
        if paths.len() == layer.paths.len() {
            layer.paths = paths;
        }
    }
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
    program
        .layers
        .iter()
        .map(|l| load(l, 0..l.paths.len(), width).0)
        .collect()
}

/// Each layer's islands' loads as the model takes them from the IR's
/// points (`[i][g]`: island `g` of layer `i`, in the plan's order), the
/// order the layer's paths lay them in and the columns they are laid on:
/// what [`predict`] ran the model over, for a check to run it again (a
/// layer of one piece: one load).
pub fn island_loads(program: &Program) -> (Vec<Vec<Load>>, Vec<Vec<usize>>, thermal::Columns) {
    let parts = Parts::of(program);
    (parts.loads, parts.orders, parts.columns)
}

/// The most samples [`islands`] takes of a plan's layer (a bead apart
/// each half a bead along its deposits): past it the layer is taken as
/// one piece, so that finding islands stays cheap on a dense layer.
const MAX_ISLAND_SAMPLES: usize = 200_000;

/// The most islands a layer is taken as: past it (a lattice of pins, a
/// field of dots) the part is one column, so that telling them apart and
/// matching them to the layer below, which compares every pair, stays
/// cheap.
const MAX_ISLANDS: usize = 256;

/// One island of a layer: a run of its paths whose deposits touch (come
/// within about a bead of each other), and the box round them in the
/// layer's frame, mm.
#[derive(Clone, Debug)]
struct Island {
    paths: std::ops::Range<usize>,
    bounds: [f64; 4],
}

/// The islands of `layer`, in the order it lays them: its deposits
/// sampled every half a bead `w` along, each sample in a grid of cells `w`
/// wide, deposits in the same or neighbouring cells joined (so deposits
/// within a bead of each other always are, and islands about three beads
/// apart or more never). A laser-off path belongs to the deposit before
/// it, a lead onto a deposit to that deposit. `None` where an island's
/// paths are not one run of the layer's (its order is then not the model's
/// to change), the layer is too dense to sample (`MAX_ISLAND_SAMPLES`) or
/// has more than `MAX_ISLANDS` islands.
fn islands(layer: &Layer, w: f64) -> Option<Vec<Island>> {
    if w.is_nan() || w <= 0.0 || layer.on_plate {
        return None;
    }
    let f = &layer.frame;
    let on = |p: [f64; 3]| {
        let d = [p[0] - f.origin[0], p[1] - f.origin[1], p[2] - f.origin[2]];
        let dot = |a: [f64; 3]| d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
        [dot(f.x), dot(f.y)]
    };
    let n = layer.paths.len();
    let mut root: Vec<usize> = (0..n).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let mut cells: std::collections::HashMap<(i64, i64), usize> = Default::default();
    let mut bounds = vec![[f64::MAX, f64::MAX, f64::MIN, f64::MIN]; n];
    let mut deposits = vec![false; n];
    let mut samples = 0usize;
    for (i, path) in layer.paths.iter().enumerate() {
        for pair in path.points.windows(2).filter(|p| p[0].laser_on) {
            let (a, b) = (on(pair[0].pos), on(pair[1].pos));
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let k = (len / (0.5 * w)).ceil().max(1.0) as usize;
            samples += k + 1;
            if samples > MAX_ISLAND_SAMPLES || !len.is_finite() {
                return None;
            }
            deposits[i] = true;
            for j in 0..=k {
                let u = j as f64 / k as f64;
                let q = [a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u];
                let bx = &mut bounds[i];
                *bx = [
                    bx[0].min(q[0]),
                    bx[1].min(q[1]),
                    bx[2].max(q[0]),
                    bx[3].max(q[1]),
                ];
                let cell = ((q[0] / w).floor() as i64, (q[1] / w).floor() as i64);
                for dx in -1..=1 {
                    for dy in -1..=1 {
                        if let Some(&o) = cells.get(&(cell.0 + dx, cell.1 + dy)) {
                            let (r, s) = (find(&mut root, o), find(&mut root, i));
                            root[r.max(s)] = r.min(s);
                        }
                    }
                }
                cells.entry(cell).or_insert(i);
            }
        }
    }
    // Each path's island: a deposit's root; a laser-off path the deposit's
    // before it (the first deposit's, before any).
    let first = (0..n).find(|&i| deposits[i])?;
    let mut owner = Vec::with_capacity(n);
    let mut last = find(&mut root, first);
    for (i, deposit) in deposits.iter().enumerate() {
        // A lead onto a deposit belongs to that deposit.
        let lead_in = layer.paths[i].kind == PathKind::Lead && deposits.get(i + 1) == Some(&true);
        if *deposit || lead_in {
            last = find(&mut root, i + usize::from(lead_in));
        }
        owner.push(last);
    }
    let mut out: Vec<(usize, Island)> = Vec::new();
    for (i, &o) in owner.iter().enumerate() {
        let again = out.last().is_some_and(|(r, _)| *r == o);
        // An island met again after another: not one run.
        if !again && (out.len() == MAX_ISLANDS || out.iter().any(|(r, _)| *r == o)) {
            return None;
        }
        match out.last_mut() {
            Some((_, isl)) if again => {
                isl.paths.end = i + 1;
                let (b, c) = (&mut isl.bounds, bounds[i]);
                *b = [
                    b[0].min(c[0]),
                    b[1].min(c[1]),
                    b[2].max(c[2]),
                    b[3].max(c[3]),
                ];
            }
            _ => out.push((
                o,
                Island {
                    paths: i..i + 1,
                    bounds: bounds[i],
                },
            )),
        }
    }
    Some(out.into_iter().map(|(_, i)| i).collect())
}

/// The columns the islands of `found`'s layers are laid on: an island of
/// layer `i + 1` stands on the islands of layer `i` whose box it overlaps,
/// its own grown by a bead `w`. An island on one island that nothing else
/// of its layer stands on goes on its column; islands that split off one
/// (several on it) each on a column of their own on top of its column; an
/// island on several (islands that merge) on a column of its own on top
/// of the first's column, joined to the others'; an island on none on a
/// column of its own on the plate (a boss that starts on the plate; the
/// verifier refuses what would start in the air); an island that nothing
/// stands on ends its column.
fn columns(found: &[Vec<Island>], w: f64) -> Option<thermal::Columns> {
    use thermal::Stand;
    let mut stands: Vec<Stand> = vec![Stand::Plate; found.first()?.len()];
    let mut joins = Vec::new();
    let mut of: Vec<Vec<usize>> = vec![(0..stands.len()).collect()];
    let overlaps = |a: &Island, b: &Island| {
        let (p, q) = (a.bounds, b.bounds);
        p[0] - w <= q[2] && q[0] - w <= p[2] && p[1] - w <= q[3] && q[1] - w <= p[3]
    };
    for pair in found.windows(2) {
        let (below, above) = (&pair[0], &pair[1]);
        let cols = of.last()?.clone();
        // What each island above stands on, and how many stand on each
        // island below.
        let mut carried = vec![0usize; below.len()];
        let on: Vec<Vec<usize>> = above
            .iter()
            .map(|isl| {
                let under: Vec<usize> = (0..below.len())
                    .filter(|&g| overlaps(isl, &below[g]))
                    .collect();
                for &g in &under {
                    carried[g] += 1;
                }
                under
            })
            .collect();
        let mut col = Vec::with_capacity(above.len());
        for under in on {
            let c = match under[..] {
                [g] if carried[g] == 1 => cols[g],
                [] => {
                    stands.push(Stand::Plate);
                    stands.len() - 1
                }
                [g, ref others @ ..] => {
                    stands.push(Stand::On(cols[g]));
                    let c = stands.len() - 1;
                    joins.extend(others.iter().map(|&h| (c, cols[h])));
                    c
                }
            };
            col.push(c);
        }
        of.push(col);
    }
    Some(thermal::Columns { stands, joins, of })
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

/// The load (SI) of a layer's run of `paths` (all of them, or an
/// island's) and where it starts (its first deposit point, mm):
/// the laser's energy and the time over its moves at their speeds (rapid
/// moves between paths instant), the metal its deposits lay (`rise ×
/// pitch`, else a bead's width times the layer height), its height (the
/// mean over its deposits' length) and its outline: the convex hull of its
/// points grown by half a bead (the perimeter of the hull plus `π·w`), the
/// outline of the part's outside for a solid layer, short of a hollow
/// part's inner faces (which makes the model cool it less than it cools).
fn load(layer: &Layer, paths: std::ops::Range<usize>, width: f64) -> (Load, [f64; 3]) {
    let (mut energy, mut time, mut volume, mut length, mut heights) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut start = None;
    let mut plan = Vec::new();
    let f = &layer.frame;
    let on =
        |p: [f64; 3], axis: [f64; 3]| (0..3).map(|k| (p[k] - f.origin[k]) * axis[k]).sum::<f64>();
    for path in &layer.paths[paths] {
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

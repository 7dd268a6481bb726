//! A reduced-order thermal model of a part as it is built: how hot each
//! layer is where and when the nozzle starts it (the interpass
//! temperature), and the least cooling that keeps it within a limit.
//! docs/thermal.md gives the equations, what they neglect and where they
//! hold; this module is free of the language and of the IR (SI units: m,
//! kg, s, W, J; temperatures in °C).
//!
//! **The model.** The part is a fin standing on a plate. Each layer is a
//! node of the fin: its metal's heat capacity, its footprint (the area heat
//! flows down through) and its sides (the area it loses heat from by
//! convection and radiation). A layer appears at the ambient temperature
//! and takes the laser's absorbed energy spread evenly over the time it is
//! laid; heat flows down the fin by conduction, out through the sides and
//! the top, and into the plate, itself a chain of rings about the first
//! layer's footprint (Steiner's formula gives their areas) that conduct
//! outwards and lose heat from their top. The whole is one chain of nodes,
//! solved by implicit Euler steps (a tridiagonal system, linear in the
//! nodes), radiation linearised about each node's temperature at the step's
//! start.
//!
//! **Cost.** Layers deep in the fin, where the temperature varies slowly
//! with depth, are merged two by two (a node's layers at most a
//! [`COARSENING`]th of its depth), so the chain holds `O(log n)` nodes
//! after `n` layers and a plan's layers cost `O(n log n)` steps in all,
//! whatever their points (the loads are summed from the points once).

pub mod alloy;
mod build;
mod cg;
pub mod fit;

pub use alloy::{alloy, Alloy, ALLOYS};
pub use build::{Build, Stand};

/// Stefan–Boltzmann constant, W/(m²·K⁴).
const SIGMA: f64 = 5.670_374_419e-8;
/// 0 °C in kelvin.
const KELVIN: f64 = 273.15;
/// A node of the fin holds at most this share of its depth below the top,
/// in layers: 1/6 keeps the merged nodes' error under 1 % of the interpass
/// rise in the finite-difference comparison (tests).
pub const COARSENING: u32 = 6;
/// The first implicit step of a cooling, s; the next ones grow by
/// [`STEP_GROWTH`] as the fast modes (the top layer into the ones below:
/// tenths of a second) have died out.
pub const FIRST_STEP: f64 = 0.05;
/// How much each cooling step is longer than the last.
pub const STEP_GROWTH: f64 = 1.25;
/// The longest step while a layer is laid, s.
const DEPOSIT_STEP: f64 = 0.25;
/// The most steps a layer's deposit is split into.
const MAX_DEPOSIT_STEPS: usize = 64;

/// A material's thermal data, SI units, each taken as constant (the mean
/// over the interpass range, [`ALLOYS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Thermal conductivity, W/(m·K).
    pub conductivity: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Specific heat capacity, J/(kg·K).
    pub heat_capacity: f64,
    /// Total hemispherical emissivity of the part's surface.
    pub emissivity: f64,
    /// The share of the laser's power the part takes up.
    pub absorptivity: f64,
    /// Heat transfer coefficient to the cell's gas, W/(m²·K).
    pub heat_transfer: f64,
}

impl Material {
    /// Volumetric heat capacity, J/(m³·K).
    fn volumetric(&self) -> f64 {
        self.density * self.heat_capacity
    }

    /// Heat lost per m² and kelvin above ambient at `t` °C: convection and
    /// radiation linearised, `h + εσ(T² + T∞²)(T + T∞)`.
    fn loss(&self, t: f64, ambient: f64) -> f64 {
        let (t, a) = ((t + KELVIN).max(0.0), ambient + KELVIN);
        self.heat_transfer + self.emissivity * SIGMA * (t * t + a * a) * (t + a)
    }
}

/// The plate the part is built on, and the cell around it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plate {
    /// Length, width and thickness, m.
    pub size: [f64; 3],
    /// Its temperature when the build starts (preheat), °C.
    pub temperature: f64,
    /// The cell's gas and walls, °C.
    pub ambient: f64,
}

/// One layer as the model sees it: what the plan lays, summed from its
/// points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load {
    /// The laser's energy over the layer, J (before absorptivity).
    pub energy: f64,
    /// How long the layer takes to lay, s.
    pub time: f64,
    /// The metal it lays, m³.
    pub volume: f64,
    /// Its height, m.
    pub height: f64,
    /// The length of its outline that faces the gas, m.
    pub perimeter: f64,
}

impl Load {
    /// The area heat flows down through, m².
    fn footprint(&self) -> f64 {
        self.volume / self.height
    }

    /// Whether every figure is finite and the layer has metal.
    pub fn valid(&self) -> bool {
        [
            self.energy,
            self.time,
            self.volume,
            self.height,
            self.perimeter,
        ]
        .iter()
        .all(|x| x.is_finite() && *x >= 0.0)
            && self.volume > 0.0
            && self.height > 0.0
    }
}

/// A node of the chain: a layer of the fin, layers merged, or a ring of
/// the plate.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Heat capacity, J/K.
    capacity: f64,
    /// Area losing heat to the gas, m² (a fin node's top face is added
    /// while it is the top).
    surface: f64,
    /// Temperature, °C.
    t: f64,
    /// Conductance to the next node up the chain, W/K (the top: 0).
    up: f64,
    /// A fin node's layers (0: a plate ring).
    layers: u32,
    /// A fin node's height, m, and footprint, m².
    height: f64,
    footprint: f64,
}

/// One thing a budget may change to keep its limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lever<'a> {
    /// Wait before a layer, at most `longest` s.
    Dwell {
        /// The longest wait lmdc plans, s.
        longest: f64,
    },
    /// Lower the power of the layer before, each layer's at least the
    /// share `least[i]` of its own.
    Power {
        /// The least share of its power each layer may be laid at.
        least: &'a [f64],
    },
    /// Lay each layer's islands in the order that starts each the coolest
    /// (no wait beyond the declared ones).
    Order,
}

/// What a budget may change to keep its limit, any of them at once. They
/// are pulled in the order that costs the least time: the islands' order
/// (free), then the power of the layer before (free, within its range),
/// then the least wait for what is still too hot.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Levers<'a> {
    /// Whether each layer's islands may be reordered.
    pub order: bool,
    /// The least share of its power each layer may be laid at, if the
    /// power may be lowered.
    pub power: Option<&'a [f64]>,
    /// The longest wait lmdc plans, s, if it may wait.
    pub dwell: Option<f64>,
}

impl<'a> Levers<'a> {
    /// These levers with `lever` allowed too.
    pub fn with(self, lever: Lever<'a>) -> Levers<'a> {
        match lever {
            Lever::Dwell { longest } => Levers {
                dwell: Some(longest),
                ..self
            },
            Lever::Power { least } => Levers {
                power: Some(least),
                ..self
            },
            Lever::Order => Levers {
                order: true,
                ..self
            },
        }
    }
}

impl<'a> From<Lever<'a>> for Levers<'a> {
    fn from(lever: Lever<'a>) -> Levers<'a> {
        Levers::default().with(lever)
    }
}

/// The interpass temperature a plan keeps and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget<'a> {
    /// The interpass temperature no layer may start above, °C.
    pub max_interpass: f64,
    /// What may change to keep it.
    pub levers: Levers<'a>,
}

/// One layer's prediction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    /// The time from the build's start to the layer's, s.
    pub start: f64,
    /// The temperature of the top of the part when the layer starts, °C:
    /// under its first island.
    pub interpass: f64,
    /// The layer's temperature when it is laid, °C: its hottest island's.
    pub peak: f64,
    /// The wait before the layer, s (0 before the first).
    pub wait: f64,
    /// The share of its power the layer is laid at.
    pub power: f64,
    /// Whether its islands are laid in another order than the plan's.
    pub reordered: bool,
}

/// One island of a layer as predicted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IslandPrediction {
    /// The island: its index in the layer's loads.
    pub island: usize,
    /// When the nozzle starts it, s from the build's start.
    pub start: f64,
    /// The top of its column then, °C: its interpass temperature.
    pub interpass: f64,
    /// Its temperature when laid, °C.
    pub peak: f64,
}

/// A layer of islands as predicted: the layer's figures, and each island's
/// in the order they are laid (the order a [`Lever::Order`] chose).
#[derive(Clone, Debug, PartialEq)]
pub struct LayerPrediction {
    /// The layer as a whole.
    pub layer: Prediction,
    /// Its islands, in the order they are laid.
    pub islands: Vec<IslandPrediction>,
}

/// A layer whose start no allowed cooling brings within the budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overheat {
    /// The layer, 0-based.
    pub layer: usize,
    /// The island of it that starts too hot (0 for a layer of one piece).
    pub island: usize,
    /// Its interpass temperature after the most cooling allowed, °C.
    pub interpass: f64,
    /// The wait before the layer that would bring it within the limit, s,
    /// if one within ten hours does.
    pub needs: Option<f64>,
    /// Whether laying the layer's islands in the order that starts each
    /// the coolest would bring it within the limit with no more wait.
    pub by_order: bool,
}

/// The longest wait an [`Overheat`] looks for, s.
const LONGEST_ADVICE: f64 = 36_000.0;

/// Predicts every layer of a build of one island a layer laid with the
/// waits `base(i)` before layer `i` (i ≥ 1): [`predict_islands`] with one
/// column.
pub fn predict(
    material: Material,
    plate: Plate,
    loads: &[Load],
    base: impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> Result<Vec<Prediction>, Overheat> {
    let layers: Vec<Vec<Load>> = loads.iter().map(|l| vec![*l]).collect();
    let orders = vec![vec![0]; loads.len()];
    let p = predict_islands(material, plate, &layers, &orders, base, budget)?;
    Ok(p.into_iter().map(|l| l.layer).collect())
}

/// How a build's islands stand on each other: the model's columns and,
/// layer by layer, the column each island is laid on (docs/thermal.md,
/// *Islands*). A column stands on the plate or on the top of a column
/// made before it (an island that split); an island that ends leaves its
/// column cooling, one that appears on the plate has a column of its own;
/// islands that merge are a column standing on the top of one column
/// (its [`Stand`]) and joined to the tops of the others.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Columns {
    /// Where each column stands.
    pub stands: Vec<Stand>,
    /// `(c, p)`: column `c` (islands that merged) stands on column `p`'s
    /// top too, besides its [`Stand`].
    pub joins: Vec<(usize, usize)>,
    /// `of[i][g]`: the column island `g` of layer `i` is laid on.
    pub of: Vec<Vec<usize>>,
}

impl Columns {
    /// Island `c` of every layer on column `c`, each column on the plate
    /// (a layer of fewer islands leaves the last columns cooling; a
    /// column first laid on later has its foot from the start).
    pub fn side_by_side(layers: &[Vec<Load>]) -> Columns {
        let n = layers.iter().map(Vec::len).max().unwrap_or(0);
        Columns {
            stands: vec![Stand::Plate; n],
            joins: Vec::new(),
            of: layers.iter().map(|l| (0..l.len()).collect()).collect(),
        }
    }

    /// Every layer's islands on one column.
    fn one(layers: usize) -> Columns {
        Columns {
            stands: vec![Stand::Plate],
            joins: Vec::new(),
            of: vec![vec![0]; layers],
        }
    }

    /// Each column's first layer that lays metal, if every column has one.
    fn firsts(&self, layers: &[Vec<Load>]) -> Option<Vec<Load>> {
        let mut firsts: Vec<Option<Load>> = vec![None; self.stands.len()];
        for (loads, cols) in layers.iter().zip(&self.of) {
            for (load, &c) in loads.iter().zip(cols) {
                if let Some(f) = firsts.get_mut(c).filter(|f| f.is_none()) {
                    *f = load.valid().then_some(*load);
                }
            }
        }
        firsts.into_iter().collect()
    }
}

/// An island of a layer: its load and the column it is laid on.
#[derive(Clone, Copy, Debug)]
struct Isle {
    load: Load,
    column: usize,
}

/// The column of island `g` (none: past every column, which only lets
/// its time pass).
fn column(loads: &[Isle], g: usize) -> usize {
    loads.get(g).map_or(usize::MAX, |l| l.column)
}

/// Predicts every layer of a build whose layers are laid as islands
/// side by side ([`Columns::side_by_side`]: `layers[i][c]`, island `c` of
/// layer `i`, standing on island `c` of the layer below): see
/// [`predict_tree`].
pub fn predict_islands(
    material: Material,
    plate: Plate,
    layers: &[Vec<Load>],
    orders: &[Vec<usize>],
    base: impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> Result<Vec<LayerPrediction>, Overheat> {
    let columns = Columns::side_by_side(layers);
    predict_tree(material, plate, &columns, layers, orders, base, budget)
}

/// Predicts every layer of a build whose layers are laid as islands
/// (`layers[i][g]`: island `g` of layer `i`, laid on the column
/// `columns.of[i][g]`), in the order `orders[i]` (islands), with
/// the waits `base(i)` before layer `i` (i ≥ 1), each kept within a budget
/// where one is given: the islands reordered, the power of the layer
/// before lowered, the wait lengthened, as the levers allow and in that
/// order (the free ones first), to the least that keeps every island's
/// interpass temperature within it. Returns the predictions, or the first
/// layer nothing allowed keeps in. Where a step of columns that merged is
/// not solved to its tolerance ([`Build::solved`]), the whole prediction
/// is made again with each layer's islands as one load on one column
/// (`one_column`).
pub fn predict_tree(
    material: Material,
    plate: Plate,
    columns: &Columns,
    layers: &[Vec<Load>],
    orders: &[Vec<usize>],
    base: impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> Result<Vec<LayerPrediction>, Overheat> {
    let (predicted, solved) = predict_on(material, plate, columns, layers, orders, &base, budget);
    if solved {
        return predicted;
    }
    let one = one_column(layers);
    let orders = vec![vec![0]; one.len()];
    let columns = Columns::one(one.len());
    predict_on(material, plate, &columns, &one, &orders, &base, budget).0
}

/// Each layer's islands as one load: their energies, times, metal and
/// outlines summed, the height the one that keeps their footprints' sum.
fn one_column(layers: &[Vec<Load>]) -> Vec<Vec<Load>> {
    layers
        .iter()
        .map(|loads| {
            let valid = || loads.iter().filter(|l| l.valid());
            let volume: f64 = valid().map(|l| l.volume).sum();
            let footprint: f64 = valid().map(Load::footprint).sum();
            let height = if footprint > 0.0 {
                volume / footprint
            } else {
                0.0
            };
            vec![Load {
                energy: valid().map(|l| l.energy).sum(),
                time: loads
                    .iter()
                    .map(|l| l.time.max(0.0))
                    .filter(|t| t.is_finite())
                    .sum(),
                volume,
                height,
                perimeter: valid().map(|l| l.perimeter).sum(),
            }]
        })
        .collect()
}

/// [`predict_tree`] on the columns given, and whether every step was
/// solved to its tolerance.
fn predict_on(
    material: Material,
    plate: Plate,
    columns: &Columns,
    layers: &[Vec<Load>],
    orders: &[Vec<usize>],
    base: &impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> (Result<Vec<LayerPrediction>, Overheat>, bool) {
    let mut build = Build::new(material, plate);
    // The plate is set up under every column's first layer that lays
    // metal.
    if let Some(firsts) = columns.firsts(layers) {
        build.plant_merged(&columns.stands, &columns.joins, &firsts);
    }
    let predicted = predict_built(build.clone(), columns, layers, orders, base, budget);
    (predicted, build.solved())
}

/// [`predict_tree`] from `build`, set up.
fn predict_built(
    mut build: Build,
    columns: &Columns,
    layers: &[Vec<Load>],
    orders: &[Vec<usize>],
    base: &impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> Result<Vec<LayerPrediction>, Overheat> {
    let layers: Vec<Vec<Isle>> = layers
        .iter()
        .enumerate()
        .map(|(i, loads)| {
            let of = columns.of.get(i);
            let col = |g: usize| of.and_then(|o| o.get(g)).copied();
            (0..loads.len())
                .map(|g| Isle {
                    load: loads[g],
                    column: col(g).unwrap_or(usize::MAX),
                })
                .collect()
        })
        .collect();
    let mut out = Vec::with_capacity(layers.len());
    let mut clock = 0.0;
    for (i, loads) in layers.iter().enumerate() {
        let declared = if i == 0 { 0.0 } else { base(i).max(0.0) };
        let (order, wait, power) = match budget {
            Some(b) => {
                let then = base_after(base, i, layers.len()).map(|wait| Then {
                    laying: Laying {
                        loads: &layers[i + 1],
                        order: &orders[i + 1],
                    },
                    wait,
                });
                let layer = Choosing {
                    build: &build,
                    plan: &orders[i],
                    declared,
                    b,
                    layer: i,
                };
                levers(&layer, loads, then)?
            }
            None => (orders[i].clone(), declared, 1.0),
        };
        build.cool(wait);
        clock += wait;
        let islands = lay_layer(&mut build, loads, &order, power, clock);
        let first = islands.first().copied();
        out.push(LayerPrediction {
            layer: Prediction {
                start: clock,
                interpass: first.map_or(build.top(), |f| f.interpass),
                peak: islands.iter().map(|p| p.peak).fold(f64::MIN, f64::max),
                wait,
                power,
                reordered: order != orders[i],
            },
            islands,
        });
        clock += order.iter().map(|&c| loads[c].load.time).sum::<f64>();
    }
    Ok(out)
}

/// The layer after one and the wait before it.
#[derive(Clone, Copy)]
struct Then<'a> {
    laying: Laying<'a>,
    wait: f64,
}

/// A layer whose cooling is being chosen: the build before the wait
/// before it, the slicer's order of its islands, the declared wait, the
/// budget and its index.
#[derive(Clone, Copy)]
struct Choosing<'a> {
    build: &'a Build,
    plan: &'a [usize],
    declared: f64,
    b: Budget<'a>,
    layer: usize,
}

/// How many times [`levers`] settles a layer's wait against its power.
const SETTLE: usize = 8;

/// Layer `c`'s order, the wait before it and the share of its power it
/// is laid at, as its budget's levers allow, on its build. The
/// wait is found with the layer at full power, then the power that keeps
/// the layer after it (`then`) in, then the wait again with the layer at
/// that power (laying its first islands cooler lets its later ones start
/// cooler, so the wait may shrink), and so on until they settle: each
/// power is chosen after the wait it is laid after, and each wait
/// against a power no lower than the one laid, so the pair kept always
/// keeps the limit. Refuses where a layer starts above it after all.
fn levers(
    c: &Choosing<'_>,
    loads: &[Isle],
    then: Option<Then<'_>>,
) -> Result<(Vec<usize>, f64, f64), Overheat> {
    let Choosing {
        build, b, layer, ..
    } = *c;
    let (mut order, mut wait) = order_and_wait(c, loads)?;
    let mut power = 1.0;
    let Some(then) = then.filter(|_| b.levers.power.is_some()) else {
        return kept(c, loads, order, wait, power);
    };
    let least = b.levers.power.and_then(|l| l.get(layer)).copied();
    for round in 0..SETTLE {
        let mut after = build.clone();
        after.cool(wait);
        let now = Laying {
            loads,
            order: &order,
        };
        let share = least_power(
            &after,
            now,
            then.laying,
            then.wait,
            b,
            least.unwrap_or(1.0),
            layer + 1,
        )?;
        let settled = share >= power - 1e-4 && round > 0;
        power = share.min(power);
        if settled || power >= 1.0 || b.levers.dwell.is_none() || round + 1 == SETTLE {
            break;
        }
        let (o, w) = order_and_wait(c, &at_share(loads, power))?;
        if w >= wait && o == order {
            break;
        }
        (order, wait) = (o, w);
    }
    kept(c, loads, order, wait, power)
}

/// `order`, `wait` and `power` for layer `c` on its build, or its
/// refusal where an island starts above the limit after all (a wait found
/// to a thousandth of its step may land a rounding above).
fn kept(
    c: &Choosing<'_>,
    loads: &[Isle],
    order: Vec<usize>,
    wait: f64,
    power: f64,
) -> Result<(Vec<usize>, f64, f64), Overheat> {
    let Choosing {
        build, b, layer, ..
    } = *c;
    let mut after = build.clone();
    after.cool(wait);
    let scaled = at_share(loads, power);
    let (hottest, island) = starts(&after, &scaled, &order);
    if hottest > b.max_interpass + 1e-9 {
        let limit = b.max_interpass;
        return Err(overheat(
            &after, &scaled, &order, layer, island, hottest, limit,
        ));
    }
    Ok((order, wait, power))
}

/// A layer's islands laid at the share `power` of their power.
fn at_share(loads: &[Isle], power: f64) -> Vec<Isle> {
    loads
        .iter()
        .map(|isle| Isle {
            load: Load {
                energy: isle.load.energy * power,
                ..isle.load
            },
            ..*isle
        })
        .collect()
}

/// The order layer `c`'s islands are laid in on its build and the wait
/// before it, as its budget's levers allow: the order that starts each
/// the coolest, then the least wait (at least the declared) after which every
/// island starts within the limit. With both, the plan's own order where
/// it needs a shorter wait (a tie keeps the coolest first).
fn order_and_wait(c: &Choosing<'_>, loads: &[Isle]) -> Result<(Vec<usize>, f64), Overheat> {
    let Choosing {
        build,
        plan,
        declared,
        b,
        layer,
    } = *c;
    let mut candidates = vec![plan.to_vec()];
    if b.levers.order {
        let best = coolest_first(build, loads, plan);
        if best != plan {
            candidates.insert(0, best);
        }
    }
    let Some(longest) = b.levers.dwell.filter(|_| layer > 0) else {
        return Ok((candidates.remove(0), declared));
    };
    let mut chosen: Option<(Vec<usize>, f64)> = None;
    let mut refused = None;
    // The declared wait, where it is enough: the least wait is found to a
    // thousandth of its step, which may land a hair above a declared wait
    // the power was chosen to keep the limit with.
    let enough = |order: &[usize]| {
        let mut after = build.clone();
        after.cool(declared);
        starts(&after, loads, order).0 <= b.max_interpass
    };
    for order in candidates {
        let least = if enough(&order) {
            Ok(declared)
        } else {
            least_wait(build, loads, &order, b.max_interpass, longest, layer)
        };
        match least {
            Ok(w) => {
                let w = w.max(declared);
                if chosen.as_ref().is_none_or(|(_, c)| w < *c) {
                    chosen = Some((order, w));
                }
            }
            Err(o) => {
                refused.get_or_insert(o);
            }
        }
    }
    match (chosen, refused) {
        (Some(c), _) => Ok(c),
        (None, Some(o)) => Err(o),
        (None, None) => Ok((plan.to_vec(), declared)),
    }
}

/// Lays a layer's islands in `order` at the share `power` of their power,
/// from `clock` s; each island's start, interpass and peak.
fn lay_layer(
    build: &mut Build,
    loads: &[Isle],
    order: &[usize],
    power: f64,
    clock: f64,
) -> Vec<IslandPrediction> {
    let mut at = clock;
    let mut out = Vec::with_capacity(order.len());
    for &c in order {
        let interpass = build.top_of(column(loads, c));
        let load = &loads[c].load;
        let peak = build.lay_on(
            column(loads, c),
            &Load {
                energy: load.energy * power,
                ..*load
            },
        );
        out.push(IslandPrediction {
            island: c,
            start: at,
            interpass,
            peak,
        });
        at += load.time;
    }
    out
}

/// The hottest interpass temperature of a layer's islands laid in `order`
/// from `build` now, °C, and which island it is. A layer of one island
/// is not laid (its interpass is the top now).
fn starts(build: &Build, loads: &[Isle], order: &[usize]) -> (f64, usize) {
    let first = order.first().copied().unwrap_or(0);
    if order.len() < 2 {
        return (build.top_of(column(loads, first)), first);
    }
    let mut b = build.clone();
    let mut hottest = (f64::MIN, first);
    for (k, &c) in order.iter().enumerate() {
        let t = b.top_of(column(loads, c));
        if t > hottest.0 {
            hottest = (t, c);
        }
        if k + 1 < order.len() {
            b.lay_on(column(loads, c), &loads[c].load);
        }
    }
    hottest
}

/// The order of a layer's islands that starts each the coolest: the
/// island whose column's top is the coolest when the last is laid goes
/// next (the one that has cooled longest). Kept only where it starts the
/// layer's hottest island cooler than the plan's own `order`, which
/// equal temperatures keep.
fn coolest_first(build: &Build, loads: &[Isle], order: &[usize]) -> Vec<usize> {
    if order.len() < 2 {
        return order.to_vec();
    }
    let mut b = build.clone();
    let mut left = order.to_vec();
    let mut chosen = Vec::with_capacity(order.len());
    while !left.is_empty() {
        // `min_by` keeps the first of equals: the plan's order.
        let k = (0..left.len())
            .min_by(|&x, &y| {
                let top = |k: usize| b.top_of(column(loads, left[k]));
                top(x).total_cmp(&top(y))
            })
            .unwrap_or(0);
        let c = left.remove(k);
        if !left.is_empty() {
            b.lay_on(column(loads, c), &loads[c].load);
        }
        chosen.push(c);
    }
    if starts(build, loads, &chosen).0 < starts(build, loads, order).0 {
        chosen
    } else {
        order.to_vec()
    }
}

/// The wait before layer `i + 1`, if there is one.
fn base_after(base: &impl Fn(usize) -> f64, i: usize, n: usize) -> Option<f64> {
    (i + 1 < n).then(|| base(i + 1).max(0.0))
}

/// The least wait, at most `longest`, after which every island of the
/// layer `layer` laid in `order` on `build` starts within `limit`: the
/// first island's from [`Build::cooling_of`]; where a later one still
/// starts above it, bisected to a thousandth of itself.
fn least_wait(
    build: &Build,
    loads: &[Isle],
    order: &[usize],
    limit: f64,
    longest: f64,
    layer: usize,
) -> Result<f64, Overheat> {
    let refuse = || {
        let mut after = build.clone();
        after.cool(longest);
        let (t, c) = starts(&after, loads, order);
        overheat(build, loads, order, layer, c, t, limit)
    };
    let first = order.first().copied().unwrap_or(0);
    let w0 = build
        .cooling_of(column(loads, first), limit, longest)
        .ok_or_else(refuse)?;
    let after = |w: f64| {
        let mut b = build.clone();
        b.cool(w);
        starts(&b, loads, order).0
    };
    if order.len() < 2 || after(w0) <= limit {
        return Ok(w0);
    }
    if after(longest) > limit {
        return Err(refuse());
    }
    // To a thousandth of the wait (at least a microsecond): a wait of
    // milliseconds is found as closely, relative to itself, as one of
    // minutes.
    let (mut lo, mut hi) = (w0, longest);
    while hi - lo > (1e-3 * hi).max(1e-6) {
        let mid = 0.5 * (lo + hi);
        if after(mid) <= limit {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// The refusal of island `island` of layer `layer`, `interpass` °C after
/// the most cooling allowed, with the wait before the layer that would do
/// from `build`.
fn overheat(
    build: &Build,
    loads: &[Isle],
    order: &[usize],
    layer: usize,
    island: usize,
    interpass: f64,
    limit: f64,
) -> Overheat {
    let needs = if layer == 0 {
        None
    } else {
        least_wait(build, loads, order, limit, LONGEST_ADVICE, layer).ok()
    };
    let by_order = order.len() > 1 && {
        let best = coolest_first(build, loads, order);
        starts(build, loads, &best).0 <= limit
    };
    Overheat {
        layer,
        island,
        interpass,
        needs,
        by_order,
    }
}

/// A layer's islands and the order they are laid in.
#[derive(Clone, Copy)]
struct Laying<'a> {
    loads: &'a [Isle],
    order: &'a [usize],
}

/// The largest share of its power, from `least` to 1, at which laying
/// `now` on `build` and waiting `wait` leaves every island of `then`
/// within `b`'s limit when it starts (layer `next`; to a ten-thousandth),
/// `then`'s islands in the order they will be laid (the coolest first
/// where `b` may reorder them). Where even `least` does not and `b` may
/// wait, `least`: the wait before `next` makes up the rest.
fn least_power(
    build: &Build,
    now: Laying<'_>,
    then: Laying<'_>,
    wait: f64,
    b: Budget<'_>,
    least: f64,
    next: usize,
) -> Result<f64, Overheat> {
    let limit = b.max_interpass;
    let top = |share: f64| {
        let mut after = build.clone();
        lay_layer(&mut after, now.loads, now.order, share, 0.0);
        after.cool(wait);
        let order = if b.levers.order {
            coolest_first(&after, then.loads, then.order)
        } else {
            then.order.to_vec()
        };
        let (t, c) = starts(&after, then.loads, &order);
        (t, c, after, order)
    };
    if top(1.0).0 <= limit {
        return Ok(1.0);
    }
    let (at_least, c, after, order) = top(least);
    if at_least > limit {
        if b.levers.dwell.is_some() {
            return Ok(least);
        }
        return Err(overheat(
            &after, then.loads, &order, next, c, at_least, limit,
        ));
    }
    let (mut lo, mut hi) = (least, 1.0);
    while hi - lo > 1e-4 {
        let mid = 0.5 * (lo + hi);
        if top(mid).0 <= limit {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(lo)
}

#[cfg(test)]
mod tests;

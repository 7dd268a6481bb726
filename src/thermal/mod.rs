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
pub mod fit;

pub use alloy::{alloy, Alloy, ALLOYS};

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

/// The part as it is built: the plate's rings, then the fin's nodes from
/// the bottom up, one chain.
#[derive(Clone, Debug)]
pub struct Build {
    material: Material,
    plate: Plate,
    /// Plate rings from the outermost in, then the fin's nodes.
    nodes: Vec<Node>,
    /// How many of `nodes` are the plate's.
    rings: usize,
}

impl Build {
    /// A plate at its start temperature, nothing on it yet.
    pub fn new(material: Material, plate: Plate) -> Build {
        Build {
            material,
            plate,
            nodes: Vec::new(),
            rings: 0,
        }
    }

    /// The temperature of the top of the part, where the next layer goes,
    /// °C: the top layer's, or the plate's under the first.
    pub fn top(&self) -> f64 {
        self.nodes.last().map_or(self.plate.temperature, |n| n.t)
    }

    /// How many nodes the chain has (the cost of a step).
    pub fn nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Lays a layer: it appears at the ambient temperature on top and takes
    /// up the laser's absorbed energy evenly over its time. Returns the
    /// layer's temperature when it is laid (its peak: it cools from then
    /// on), °C.
    pub fn lay(&mut self, load: &Load) -> f64 {
        if !load.valid() {
            // Nothing laid (a layer of travel only): the time passes.
            self.cool(load.time.max(0.0));
            return self.top();
        }
        if self.nodes.is_empty() {
            self.rings = self.plate_rings(load);
        }
        self.push(load);
        let steps = ((load.time / DEPOSIT_STEP).ceil() as usize).clamp(1, MAX_DEPOSIT_STEPS);
        let dt = load.time / steps as f64;
        let heat = self.material.absorptivity * load.energy;
        if dt <= 0.0 {
            // Laid at once: the energy lands on the layer as it appears.
            let top = self.nodes.len() - 1;
            self.nodes[top].t += heat / self.nodes[top].capacity;
            return self.top();
        }
        for _ in 0..steps {
            self.step(dt, heat / load.time);
        }
        self.top()
    }

    /// Cools for `seconds`, nothing laid: steps from [`FIRST_STEP`]
    /// growing by [`STEP_GROWTH`], the last cut to what remains, so that a
    /// longer cooling repeats a shorter one's steps (the temperature it
    /// predicts never rises with the time allowed, and
    /// [`Build::cooling_to`]'s answer is what this cools to).
    pub fn cool(&mut self, seconds: f64) {
        let mut left = seconds;
        let mut dt = FIRST_STEP;
        while left > 0.0 {
            let d = left.min(dt);
            self.step(d, 0.0);
            left -= d;
            dt *= STEP_GROWTH;
        }
    }

    /// The least cooling, s, after which the top is at most `limit` °C, if
    /// one of at most `longest` s is; to a thousandth of the step it falls
    /// in. Leaves `self` untouched.
    pub fn cooling_to(&self, limit: f64, longest: f64) -> Option<f64> {
        if self.top() <= limit {
            return Some(0.0);
        }
        // March the same steps `cool` takes; bisect in the step it crosses
        // in, from the state at its start.
        let (mut at, mut done, mut dt) = (self.clone(), 0.0, FIRST_STEP);
        while done < longest {
            let d = dt.min(longest - done);
            let mut next = at.clone();
            next.step(d, 0.0);
            if next.top() <= limit {
                let (mut lo, mut hi) = (0.0, d);
                while hi - lo > 1e-3 * d {
                    let mid = 0.5 * (lo + hi);
                    let mut m = at.clone();
                    m.step(mid, 0.0);
                    if m.top() <= limit {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Some(done + hi);
            }
            at = next;
            done += d;
            dt *= STEP_GROWTH;
        }
        None
    }

    /// The plate's rings about the first layer's footprint (area `A₀`,
    /// outline `P₀`): the plate within `r` of it has the area
    /// `A(r) = A₀ + P₀·r + π·r²` (Steiner), the first ring reaching half
    /// the plate's thickness out (the cone heat spreads down in), each next
    /// twice as far, the last to the plate's area. Returns how many.
    fn plate_rings(&mut self, first: &Load) -> usize {
        let m = self.material;
        let [lx, ly, thick] = self.plate.size;
        let (a0, p0) = (first.footprint(), first.perimeter);
        let area = |r: f64| a0 + p0 * r + std::f64::consts::PI * r * r;
        let outline = |r: f64| p0 + 2.0 * std::f64::consts::PI * r;
        let total = (lx * ly).max(area(thick) * 2.0);
        // The radius at which the area is the plate's.
        let reach = {
            let (a, b, c) = (std::f64::consts::PI, p0, a0 - total);
            (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)
        };
        let mut radii = vec![0.5 * thick];
        while radii[radii.len() - 1] * 2.0 < reach {
            let r = radii[radii.len() - 1] * 2.0;
            radii.push(r);
        }
        radii.push(reach);
        // Innermost first, then reversed so the chain runs outside in.
        let mut rings = Vec::with_capacity(radii.len());
        for (j, &r) in radii.iter().enumerate() {
            let inner = if j == 0 { 0.0 } else { radii[j - 1] };
            let plan = area(r) - if j == 0 { 0.0 } else { area(inner) };
            let top = if j == 0 { plan - a0 } else { plan };
            let edge = if j + 1 == radii.len() {
                outline(r) * thick
            } else {
                0.0
            };
            // To the next ring out: across the boundary at `r`, between the
            // two rings' middles.
            let out = radii.get(j + 1).map_or(0.0, |&next| {
                m.conductivity * thick * outline(r) / (0.5 * (next - inner))
            });
            rings.push(Node {
                capacity: m.volumetric() * plan * thick,
                surface: top.max(0.0) + edge,
                t: self.plate.temperature,
                up: out,
                layers: 0,
                height: thick,
                footprint: plan,
            });
        }
        // The chain runs from the outermost ring in: a ring's `up` is the
        // conductance to the next inner one.
        rings.reverse();
        let n = rings.len();
        for i in 0..n - 1 {
            rings[i].up = rings[i + 1].up;
        }
        self.nodes = rings;
        n
    }

    /// Puts a new layer on top at the ambient temperature, joined to the
    /// node below, and merges what has grown deep.
    fn push(&mut self, load: &Load) {
        let m = self.material;
        let layer = Node {
            capacity: m.volumetric() * load.volume,
            surface: load.perimeter * load.height,
            t: self.plate.ambient,
            up: 0.0,
            layers: 1,
            height: load.height,
            footprint: load.footprint(),
        };
        let below = self.nodes.len() - 1;
        self.nodes[below].up = self.link(below, &layer);
        self.nodes.push(layer);
        self.merge();
    }

    /// Conductance from node `i` (the plate's innermost ring, or a fin
    /// node) up into `above`, W/K: their half-heights in series, the
    /// ring's down from its top through the cone under the footprint.
    fn link(&self, i: usize, above: &Node) -> f64 {
        let k = self.material.conductivity;
        let n = &self.nodes[i];
        let lower = if n.layers == 0 {
            0.5 * n.height / (k * 0.5 * (above.footprint + n.footprint))
        } else {
            0.5 * n.height / (k * n.footprint)
        };
        1.0 / (lower + 0.5 * above.height / (k * above.footprint))
    }

    /// Merges neighbouring fin nodes whose layers together are at most a
    /// [`COARSENING`]th of their depth below the top: energy kept, the
    /// temperature the mean weighted by heat capacity.
    fn merge(&mut self) {
        let mut depth = 0u32; // layers above node i
        let mut i = self.nodes.len() - 1;
        while i > self.rings + 1 {
            depth += self.nodes[i].layers;
            let (a, b) = (self.nodes[i - 2], self.nodes[i - 1]);
            // Node i−1 lies under `depth` layers; merge it with the one below.
            if (a.layers + b.layers) * COARSENING <= depth {
                let capacity = a.capacity + b.capacity;
                let height = a.height + b.height;
                let merged = Node {
                    capacity,
                    surface: a.surface + b.surface,
                    t: (a.t * a.capacity + b.t * b.capacity) / capacity,
                    up: 0.0,
                    layers: a.layers + b.layers,
                    height,
                    footprint: (a.footprint * a.height + b.footprint * b.height) / height,
                };
                self.nodes[i - 2] = merged;
                self.nodes.remove(i - 1);
                i -= 1;
                let below = i - 2;
                self.nodes[below].up = self.link(below, &self.nodes[i - 1].clone());
                let up = self.link(i - 1, &self.nodes[i].clone());
                self.nodes[i - 1].up = up;
            }
            i -= 1;
        }
    }

    /// One implicit Euler step of `dt` s with `power` W into the top node:
    /// `(C/dt + H + G₋ + G₊)·T' − G₋·T'₋ − G₊·T'₊ = C/dt·T + H·T∞ + Q`,
    /// solved by the Thomas algorithm.
    fn step(&mut self, dt: f64, power: f64) {
        let n = self.nodes.len();
        if n == 0 || dt <= 0.0 {
            return;
        }
        let (m, ambient) = (self.material, self.plate.ambient);
        let mut diag = vec![0.0; n];
        let mut rhs = vec![0.0; n];
        for (i, node) in self.nodes.iter().enumerate() {
            let top = if i + 1 == n { node.footprint } else { 0.0 };
            let h = m.loss(node.t, ambient) * (node.surface + top);
            let below = if i > 0 { self.nodes[i - 1].up } else { 0.0 };
            diag[i] = node.capacity / dt + h + below + node.up;
            rhs[i] = node.capacity / dt * node.t + h * ambient;
        }
        rhs[n - 1] += power;
        // Forward sweep: the sub- and super-diagonal are −up of the node
        // below.
        let mut c = vec![0.0; n];
        for i in 0..n {
            let (a, prev_c, prev_r) = if i > 0 {
                (-self.nodes[i - 1].up, c[i - 1], rhs[i - 1])
            } else {
                (0.0, 0.0, 0.0)
            };
            let d = diag[i] - a * prev_c;
            c[i] = -self.nodes[i].up / d;
            rhs[i] = (rhs[i] - a * prev_r) / d;
        }
        for i in (0..n).rev() {
            let next = if i + 1 < n { self.nodes[i + 1].t } else { 0.0 };
            self.nodes[i].t = rhs[i] - c[i] * next;
        }
    }
}

/// What a budget may change to keep its limit.
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
}

/// The interpass temperature a plan keeps and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget<'a> {
    /// The interpass temperature no layer may start above, °C.
    pub max_interpass: f64,
    /// How it is kept.
    pub lever: Lever<'a>,
}

/// One layer's prediction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    /// The time from the build's start to the layer's, s.
    pub start: f64,
    /// The temperature of the top of the part when the layer starts, °C.
    pub interpass: f64,
    /// The layer's temperature when it is laid, °C.
    pub peak: f64,
    /// The wait before the layer, s (0 before the first).
    pub wait: f64,
    /// The share of its power the layer is laid at.
    pub power: f64,
}

/// A layer whose start no allowed cooling brings within the budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overheat {
    /// The layer, 0-based.
    pub layer: usize,
    /// Its interpass temperature after the most cooling allowed, °C.
    pub interpass: f64,
    /// The wait that would bring it within the limit, s, if one within
    /// ten hours does.
    pub needs: Option<f64>,
}

/// The longest wait an [`Overheat`] looks for, s.
const LONGEST_ADVICE: f64 = 36_000.0;

/// Predicts every layer of a build laid with the waits `base(i)` before
/// layer `i` (i ≥ 1), each kept within a budget where one is given: the
/// wait lengthened, or the power of the layer before lowered, to the least
/// that keeps the layer's interpass temperature within it. Returns the
/// predictions, or the first layer nothing allowed keeps in.
pub fn predict(
    material: Material,
    plate: Plate,
    loads: &[Load],
    base: impl Fn(usize) -> f64,
    budget: Option<Budget<'_>>,
) -> Result<Vec<Prediction>, Overheat> {
    let mut build = Build::new(material, plate);
    let mut out = Vec::with_capacity(loads.len());
    let mut clock = 0.0;
    for (i, load) in loads.iter().enumerate() {
        let mut wait = if i == 0 { 0.0 } else { base(i).max(0.0) };
        if let (Some(b), true) = (budget, i > 0) {
            if let Lever::Dwell { longest } = b.lever {
                wait = wait.max(least_wait(&build, b.max_interpass, longest, i)?);
            }
        }
        build.cool(wait);
        clock += wait;
        let interpass = build.top();
        // A wait found to a thousandth of its step may land a rounding above.
        if let Some(b) = budget.filter(|b| interpass > b.max_interpass + 1e-9) {
            return Err(overheat(&build, i, interpass, b.max_interpass));
        }
        let power = match (budget, base_after(&base, i, loads.len())) {
            (
                Some(
                    b @ Budget {
                        lever: Lever::Power { least },
                        ..
                    },
                ),
                Some(next),
            ) => least_power(&build, load, next, b.max_interpass, least[i], i + 1)?,
            _ => 1.0,
        };
        let peak = build.lay(&Load {
            energy: load.energy * power,
            ..*load
        });
        out.push(Prediction {
            start: clock,
            interpass,
            peak,
            wait,
            power,
        });
        clock += load.time;
    }
    Ok(out)
}

/// The wait before layer `i + 1`, if there is one.
fn base_after(base: &impl Fn(usize) -> f64, i: usize, n: usize) -> Option<f64> {
    (i + 1 < n).then(|| base(i + 1).max(0.0))
}

/// The least wait, at most `longest`, that brings the top of `build`
/// within `limit` before layer `layer`.
fn least_wait(build: &Build, limit: f64, longest: f64, layer: usize) -> Result<f64, Overheat> {
    build.cooling_to(limit, longest).ok_or_else(|| {
        let mut after = build.clone();
        after.cool(longest);
        overheat(build, layer, after.top(), limit)
    })
}

/// The refusal of layer `layer`, `interpass` °C after the most cooling
/// allowed, with the wait that would do from `build`.
fn overheat(build: &Build, layer: usize, interpass: f64, limit: f64) -> Overheat {
    let needs = if layer == 0 {
        None
    } else {
        build.cooling_to(limit, LONGEST_ADVICE)
    };
    Overheat {
        layer,
        interpass,
        needs,
    }
}

/// The largest share of its power, from `least` to 1, at which laying
/// `load` on `build` and waiting `wait` leaves the top within `limit`
/// before layer `next` (to a ten-thousandth).
fn least_power(
    build: &Build,
    load: &Load,
    wait: f64,
    limit: f64,
    least: f64,
    next: usize,
) -> Result<f64, Overheat> {
    let top = |share: f64| {
        let mut b = build.clone();
        b.lay(&Load {
            energy: load.energy * share,
            ..*load
        });
        b.cool(wait);
        (b.top(), b)
    };
    if top(1.0).0 <= limit {
        return Ok(1.0);
    }
    let (at_least, b) = top(least);
    if at_least > limit {
        return Err(overheat(&b, next, at_least, limit));
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

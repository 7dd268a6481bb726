//! `process { thermal { … } }`: the alloy, the plate and the interpass
//! limit (docs/thermal.md), read into the IR's [`Thermal`] (its layers
//! left for the lowering to predict).

use crate::diag::{message, Diagnostics};
use crate::ir::{Cooling, Levers, Thermal};
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::schema::process::thermal::{self as t, MAX_TEMPERATURE};
use crate::sema::schema::process::{THERMAL, THERMAL_BLOCK};
use crate::sema::value::Value;
use crate::span::Span;
use crate::units::Dim;

/// The cell's gas and walls, °C.
pub const AMBIENT: f64 = 25.0;
/// The plate when none is declared, mm.
pub const PLATE: [f64; 3] = [200.0, 200.0, 20.0];
/// `heat_transfer`'s canonical units (g/(s³·°C)) per W/(m²·K).
const HEAT_TRANSFER_SI: f64 = 1e3;
/// `conductivity`'s canonical units (g·mm/(s³·°C)) per W/(m·K).
const CONDUCTIVITY_SI: f64 = 1e6;
/// `density`'s canonical units (g/mm³) per kg/m³.
const DENSITY_SI: f64 = 1e-6;
/// `heat_capacity`'s canonical units (mm²/(s²·°C)) per J/(kg·K).
const HEAT_CAPACITY_SI: f64 = 1e6;

/// The thermal block of the process block `f` and where it is written:
/// `Some(None)` when there is none, `None` when it is written wrong
/// (reported).
pub fn read<'a>(
    env: &mut Env<'a>,
    f: &Fields<'a>,
    diags: &mut Diagnostics,
) -> Option<Option<(Thermal, Span)>> {
    let Some((stmts, span)) = f.nested(&THERMAL_BLOCK) else {
        return Some(None);
    };
    let b = Fields::block(env, stmts, &THERMAL, "`thermal`".into(), span, diags);
    let material = b.optional(&t::MATERIAL, b.word(&t::MATERIAL, diags).map(|w| w.0));
    let share = |f: &'static crate::sema::schema::Field, diags: &mut Diagnostics| {
        let out = |v, at| message::thermal::share_range(f.key, v, at);
        b.optional(f, b.bounded(f, out, diags).map(|q| q.0))
    };
    let absorptivity = share(&t::ABSORPTIVITY, diags);
    let emissivity = share(&t::EMISSIVITY, diags);
    let mut si = |f: &'static crate::sema::schema::Field, per: f64| {
        b.optional(f, b.quantity(f, diags).map(|q| significant(q.0 / per)))
    };
    let heat_transfer = si(&t::HEAT_TRANSFER, HEAT_TRANSFER_SI);
    let conductivity = si(&t::CONDUCTIVITY, CONDUCTIVITY_SI);
    let density = si(&t::DENSITY, DENSITY_SI);
    let heat_capacity = si(&t::HEAT_CAPACITY, HEAT_CAPACITY_SI);
    let plate = plate(&b, diags);
    let mut temperature = |field: &'static crate::sema::schema::Field| {
        b.optional(
            field,
            b.bounded(
                field,
                |q, at| message::thermal::temperature_range(field.key, q, MAX_TEMPERATURE, at),
                diags,
            ),
        )
    };
    let preheat = temperature(&t::PREHEAT);
    let max_interpass = temperature(&t::MAX_INTERPASS);
    let cooling = cooling(&b, diags);
    let declared = Declared {
        conductivity: conductivity?,
        density: density?,
        heat_capacity: heat_capacity?,
        emissivity: emissivity?,
        absorptivity: absorptivity?,
    };
    let (name, m) = material_of(material?, &declared, span, diags)?;
    let at = max_interpass.flatten().map_or(span, |(_, at)| at);
    Some(Some((
        Thermal {
            material: name,
            conductivity: m.conductivity,
            density: m.density,
            heat_capacity: m.heat_capacity,
            emissivity: m.emissivity,
            absorptivity: m.absorptivity,
            heat_transfer: heat_transfer?.unwrap_or(m.heat_transfer),
            plate: plate?,
            preheat: preheat?.map_or(AMBIENT, |q| q.0),
            ambient: AMBIENT,
            max_interpass: max_interpass?.map(|q| q.0),
            cooling: cooling?,
            dwell_alone: None,
            layers: Vec::new(),
        },
        at,
    )))
}

/// `x` to 12 significant digits: a value as written, not the units'
/// conversion's last bits (7950 kg/m³, not 7950.000000000001).
fn significant(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(11 - x.abs().log10().floor() as i32);
    // Past f64's range (a value below about 1e-297): as it is.
    if !scale.is_finite() || scale == 0.0 {
        return x;
    }
    (x * scale).round() / scale
}

/// The properties a `thermal` block declares itself (SI units), each
/// overriding its alloy's.
struct Declared {
    conductivity: Option<f64>,
    density: Option<f64>,
    heat_capacity: Option<f64>,
    emissivity: Option<f64>,
    absorptivity: Option<f64>,
}

/// The material the model takes and its name for the report: the alloy
/// `material` names with what the block declares over it, or, without
/// one, what the block declares, which must then be every property
/// (the missing ones reported at the block `at`).
fn material_of(
    material: Option<&str>,
    d: &Declared,
    at: Span,
    diags: &mut Diagnostics,
) -> Option<(String, crate::thermal::Material)> {
    let own = [
        (t::CONDUCTIVITY.key, d.conductivity),
        (t::DENSITY.key, d.density),
        (t::HEAT_CAPACITY.key, d.heat_capacity),
        (t::EMISSIVITY.key, d.emissivity),
        (t::ABSORPTIVITY.key, d.absorptivity),
    ];
    let Some(key) = material else {
        let missing: Vec<&str> = own
            .iter()
            .filter(|(_, v)| v.is_none())
            .map(|(k, _)| *k)
            .collect();
        if !missing.is_empty() {
            diags.push(message::thermal::no_material(&missing, at));
            return None;
        }
        let m = crate::thermal::Material {
            conductivity: d.conductivity?,
            density: d.density?,
            heat_capacity: d.heat_capacity?,
            emissivity: d.emissivity?,
            absorptivity: d.absorptivity?,
            heat_transfer: crate::thermal::alloy::HEAT_TRANSFER,
        };
        return Some(("declared material".to_string(), m));
    };
    let base = crate::thermal::alloy(key)?.material;
    let name = if own.iter().any(|(_, v)| v.is_some()) {
        format!("{key}, with declared properties")
    } else {
        key.to_string()
    };
    Some((
        name,
        crate::thermal::Material {
            conductivity: d.conductivity.unwrap_or(base.conductivity),
            density: d.density.unwrap_or(base.density),
            heat_capacity: d.heat_capacity.unwrap_or(base.heat_capacity),
            emissivity: d.emissivity.unwrap_or(base.emissivity),
            absorptivity: d.absorptivity.unwrap_or(base.absorptivity),
            heat_transfer: base.heat_transfer,
        },
    ))
}

/// `cooling = order` or `cooling = [order, dwell]`, or the default: each
/// word a lever, each at most once, a list not empty (each wrong word
/// reported where it is written).
fn cooling(b: &Fields<'_>, diags: &mut Diagnostics) -> Option<Levers> {
    if !b.has(&t::COOLING) {
        return Some(Levers::default());
    }
    let v = b.value(&t::COOLING, diags)?;
    let Value::List(items) = &v.value else {
        let w = fields::word(v, t::COOLING.key, t::LEVERS, diags)?;
        return Some(Levers::One(lever(w)));
    };
    if items.is_empty() {
        diags.push(message::thermal::no_levers(v.span));
        return None;
    }
    let mut out: Vec<(Cooling, Span)> = Vec::with_capacity(items.len());
    let mut ok = true;
    for it in items {
        let Some(w) = fields::word(it, t::COOLING.key, t::LEVERS, diags) else {
            ok = false;
            continue;
        };
        let c = lever(w);
        if let Some((_, first)) = out.iter().find(|(o, _)| *o == c) {
            diags.push(message::thermal::lever_twice(w, it.span, *first));
            ok = false;
            continue;
        }
        out.push((c, it.span));
    }
    let levers: Vec<Cooling> = out.into_iter().map(|(c, _)| c).collect();
    ok.then(|| Levers::of(&levers))
}

/// The lever a word of `cooling` names.
fn lever(word: &str) -> Cooling {
    match word {
        "power" => Cooling::Power,
        "order" => Cooling::Order,
        _ => Cooling::Dwell,
    }
}

/// `plate = [l, w, t]`, mm, or the default.
fn plate(b: &Fields<'_>, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    if !b.has(&t::PLATE) {
        return Some(PLATE);
    }
    let v = b.value(&t::PLATE, diags)?;
    let Value::List(items) = &v.value else {
        diags.push(message::thermal::plate_not_three(v.value.got(), v.span));
        return None;
    };
    if items.len() != 3 {
        diags.push(message::thermal::plate_not_three(v.value.got(), v.span));
        return None;
    }
    let mut out = [0.0; 3];
    for (o, it) in out.iter_mut().zip(items) {
        *o = fields::quantity(it, Dim::LENGTH, t::PLATE.key, diags)?;
        if !(*o > 0.0 && *o <= crate::sema::schema::collision::MAX_SIZE_MM) {
            diags.push(message::thermal::plate_not_three(v.value.got(), v.span));
            return None;
        }
    }
    Some(out)
}

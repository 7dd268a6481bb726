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
    let material = b.word(&t::MATERIAL, diags).map(|w| w.0);
    let absorptivity = b.optional(
        &t::ABSORPTIVITY,
        b.bounded(
            &t::ABSORPTIVITY,
            message::thermal::absorptivity_range,
            diags,
        )
        .map(|q| q.0),
    );
    let heat_transfer = b.optional(
        &t::HEAT_TRANSFER,
        b.quantity(&t::HEAT_TRANSFER, diags)
            .map(|q| q.0 / HEAT_TRANSFER_SI),
    );
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
    let alloy = crate::thermal::alloy(material?)?;
    let m = alloy.material;
    let at = max_interpass.flatten().map_or(span, |(_, at)| at);
    Some(Some((
        Thermal {
            material: alloy.key.to_string(),
            conductivity: m.conductivity,
            density: m.density,
            heat_capacity: m.heat_capacity,
            emissivity: m.emissivity,
            absorptivity: absorptivity?.unwrap_or(m.absorptivity),
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

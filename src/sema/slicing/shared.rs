//! What more than one slicing strategy reads the same way: how closely the
//! layers must be laid (`rise_tolerance`, `max_drift`) and how a layer
//! changes to the next (`layer_change`).

use crate::diag::Diagnostics;
use crate::sema::fields::Fields;
use crate::sema::model::{LayerChange, Tolerance};
use crate::sema::schema::slicing::{self as schema, normal};
use crate::sema::value::Value;
use crate::units::Length;

/// `rise_tolerance` and `max_drift` of a strategy with a bead model.
pub fn tolerance(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Tolerance> {
    let rise = f.quantity_or_default(&schema::RISE_TOLERANCE, diags);
    let drift = f.quantity_or_default(&schema::MAX_DRIFT, diags);
    Some(Tolerance {
        rise: rise?,
        drift: Length(drift?),
    })
}

/// Reads `layer_change = lift | spiral | spiral(length)`.
pub fn layer_change(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<LayerChange> {
    match f.value(&normal::LAYER_CHANGE, diags) {
        Some(v) => match &v.value {
            Value::Call(c) if c.func == "spiral" => {
                let args = Fields::call(c, &schema::SPIRAL, diags);
                let length = args.optional(
                    &normal::LENGTH,
                    args.quantity(&normal::LENGTH, diags)
                        .map(|(l, _)| Length(l)),
                );
                length.map(|length| LayerChange::Spiral { length })
            }
            _ => f
                .word_or_default(&normal::LAYER_CHANGE, diags)
                .map(|w| match w {
                    "spiral" => LayerChange::Spiral { length: None },
                    _ => LayerChange::Lift,
                }),
        },
        None if f.has(&normal::LAYER_CHANGE) => None,
        None => Some(LayerChange::Lift),
    }
}

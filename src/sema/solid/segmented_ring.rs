//! `ring NAME { radius, segments, transition, table { defocus, power, width,
//! speed } }`: a segmented ring, split into equal segments, each with its own
//! row of process values, and its pairing with `slicing continuous { … }`
//! and `control height { … }` into a [`Build::Ring`].
//!
//! [`Build::Ring`]: crate::sema::model::Build::Ring

use crate::control::{self, Controller, Plant, SegmentProcess, SegmentTable};
use crate::diag::{message, Diagnostics};
use crate::ir::RingOrigins;
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::model::{HeightControl, RingBuild};
use crate::sema::process::control::ControlSpec;
use crate::sema::schema::solid::{ring, table, RING, TABLE};
use crate::sema::schema::{Bound, Field, Kind};
use crate::sema::slicing::continuous::ContinuousSpec;
use crate::sema::value::Value;
use crate::span::Span;
use crate::syntax::ast::Stmt;
use crate::units::{Angle, Length, MassFlow, Power, Speed};

/// A ring block as read: the parts that are right.
#[derive(Clone, Debug)]
pub struct Written {
    name: String,
    ring: Option<control::Ring>,
    table: Option<SegmentTable>,
    span: Span,
    transition_span: Span,
    /// The table's powers and where they are written, for the process block.
    pub powers: Option<([Power; 2], Span)>,
    /// Where the speeds are written.
    speed_span: Option<Span>,
    /// The number of segments and where it is written, if right.
    pub segments: Option<(usize, Span)>,
}

/// Reads `ring NAME { … }`.
pub fn read<'a>(
    env: &mut Env<'a>,
    name: &str,
    stmts: &'a [Stmt],
    span: Span,
    diags: &mut Diagnostics,
) -> Written {
    let what = format!("ring `{name}`");
    let f = Fields::block(env, stmts, &RING, what.clone(), span, diags);
    let radius = f.quantity(&ring::RADIUS, diags);
    let segments = f.count(&ring::SEGMENTS, diags);
    let transition = f.quantity_or_default(&ring::TRANSITION, diags).map(Angle);
    let transition_span = f.span(&ring::TRANSITION).unwrap_or(span);
    let ring = match (radius, segments, transition) {
        (Some((r, _)), Some((n, _)), Some(t)) => match control::Ring::new(Length(r), n, t) {
            Ok(ring) => Some(ring),
            Err(e) => {
                diags.push(message::segmented_ring::ring_layout(&e, transition_span, n));
                None
            }
        },
        _ => None,
    };
    let (table, powers, speed_span, width_span) = match f.nested(&ring::TABLE) {
        Some((inner, ts)) => table(env, inner, ts, segments, &what, diags),
        None => {
            diags.push(message::segmented_ring::ring_needs_table(&what, span));
            (None, None, None, None)
        }
    };
    let ring = match (ring, &table, radius, width_span) {
        (Some(r), Some(t), Some((_, at)), Some(ws)) => fits(r, t, at, ws, span, diags),
        (r, ..) => r,
    };
    Written {
        name: name.to_string(),
        ring,
        table,
        span,
        transition_span,
        powers,
        speed_span,
        segments,
    }
}

/// The rows of `table { … }`, its powers' range and where its speeds and
/// widths are.
type Table = (
    Option<SegmentTable>,
    Option<([Power; 2], Span)>,
    Option<Span>,
    Option<Span>,
);

/// The ring, if its beads fit it: none reaches the centre (an error, and the
/// ring is dropped); segments shorter than their beads are a warning.
fn fits(
    r: control::Ring,
    t: &SegmentTable,
    radius_at: Span,
    widths_at: Span,
    ring_at: Span,
    diags: &mut Diagnostics,
) -> Option<control::Ring> {
    let widest = t.rows().iter().map(|s| s.width.0).fold(0.0, f64::max);
    if r.radius().0 <= widest / 2.0 {
        diags.push(message::segmented_ring::ring_too_small(
            r.radius(),
            Length(widest),
            radius_at,
            widths_at,
        ));
        return None;
    }
    // A segment's length along the ring's centre line, transition included.
    let length = r.radius().0 * r.segment_angle().0;
    let short: Vec<f64> = t
        .rows()
        .iter()
        .map(|s| s.width.0)
        .filter(|&w| length < w)
        .collect();
    if let Some(&w) = short.iter().max_by(|a, b| a.total_cmp(b)) {
        diags.push(message::segmented_ring::short_segments(
            short.len(),
            Length(length),
            Length(w),
            ring_at,
        ));
    }
    Some(r)
}

fn table<'a>(
    env: &mut Env<'a>,
    stmts: &'a [Stmt],
    span: Span,
    segments: Option<(usize, Span)>,
    ring: &str,
    diags: &mut Diagnostics,
) -> Table {
    let f = Fields::block(
        env,
        stmts,
        &TABLE,
        format!("the table of {ring}"),
        span,
        diags,
    );
    let defocus = list(&f, &table::DEFOCUS, segments, diags);
    let power = list(&f, &table::POWER, segments, diags);
    let width = list(&f, &table::WIDTH, segments, diags);
    let speed = list(&f, &table::SPEED, segments, diags);
    let powers = power.as_ref().map(|(p, at)| {
        let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        ([Power(lo), Power(hi)], *at)
    });
    let speed_span = speed.as_ref().map(|s| s.1);
    let width_span = width.as_ref().map(|w| w.1);
    let rows = match (defocus, power, width, speed) {
        // Without a right `segments` (reported) the lists were not checked
        // against it, and may differ from each other.
        (Some((d, _)), Some((p, _)), Some((w, _)), Some((v, _)))
            if [p.len(), w.len(), v.len()].iter().all(|&n| n == d.len()) =>
        {
            Some(
                (0..d.len())
                    .map(|j| SegmentProcess {
                        defocus: Length(d[j]),
                        power: Power(p[j]),
                        width: Length(w[j]),
                        speed: Speed(v[j]),
                    })
                    .collect::<Vec<_>>(),
            )
        }
        _ => None,
    };
    // Every value is checked above; a table that still fails is empty.
    let table = rows.and_then(|r| SegmentTable::new(r).ok());
    (table, powers, speed_span, width_span)
}

/// One list of the table (`field`): one value per segment, of the
/// dimension and bounds its entry gives.
fn list(
    f: &Fields<'_>,
    field: &Field,
    segments: Option<(usize, Span)>,
    diags: &mut Diagnostics,
) -> Option<(Vec<f64>, Span)> {
    let Some((dim, bound)) = (match field.kind {
        Kind::List(item, _) => item.quantity(),
        _ => None,
    }) else {
        unreachable!("`{}` is a list of quantities", field.key)
    };
    let positive = matches!(bound, Bound::Positive);
    let (key, example) = (field.key, f.example(field));
    let v = f.value(field, diags)?;
    let Value::List(items) = &v.value else {
        diags.push(message::segmented_ring::table_not_a_list(
            key,
            v.span,
            &v.value.describe(),
            example,
        ));
        return None;
    };
    let mut ok = true;
    let mut out = Vec::with_capacity(items.len());
    for it in items {
        match fields::quantity(it, dim, key, diags) {
            Some(x) if positive && x <= 0.0 => {
                diags.push(message::segmented_ring::table_not_positive(
                    key,
                    it.span,
                    &fields::shown(x, dim),
                ));
                ok = false;
            }
            Some(x) => out.push(x),
            None => ok = false,
        }
    }
    if let Some((n, at)) = segments {
        if items.len() != n {
            diags.push(message::segmented_ring::table_length(
                key,
                items.len(),
                v.span,
                n,
                at,
            ));
            ok = false;
        }
    }
    if items.is_empty() {
        ok = false;
    }
    ok.then_some((out, v.span))
}

/// Pairs a ring with its slicing and loop. `control` is `Some(None)` when no
/// `control` block is written, `None` when one is written but wrong.
pub fn assemble(
    w: Written,
    slicing: ContinuousSpec,
    control: Option<Option<ControlSpec>>,
    powder: Option<MassFlow>,
    diags: &mut Diagnostics,
) -> Option<RingBuild> {
    let (ring, table) = (w.ring?, w.table.clone()?);
    let control = match control? {
        Some(c) => Some(loop_of(&w, &table, &slicing, c, diags)?),
        None => None,
    };
    let origins = RingOrigins {
        ring: w.span,
        transition: w.transition_span,
        layers: slicing.layers_span,
        ..control.as_ref().map(|c| c.1).unwrap_or_default()
    };
    Some(RingBuild {
        name: w.name,
        ring,
        table,
        layers: slicing.layers,
        layer_height: slicing.layer_height,
        step: slicing.step,
        control: control.map(|c| c.0),
        powder: powder?,
        origins,
    })
}

/// The checked loop and where its fields are (the rest of the origins filled
/// by the caller).
fn loop_of(
    w: &Written,
    table: &SegmentTable,
    slicing: &ContinuousSpec,
    c: ControlSpec,
    diags: &mut Diagnostics,
) -> Option<(HeightControl, RingOrigins)> {
    let h = slicing.layer_height;
    let target = match c.target {
        Some((t, at)) if (t.0 - h.0).abs() > 1e-9 * h.0 => {
            diags.push(message::segmented_ring::target_not_layer_height(
                t,
                h,
                at,
                slicing.layer_height_span,
            ));
            return None;
        }
        _ => h,
    };
    let controller = match Controller::new(c.kp, c.ki, target, c.clamp) {
        Ok(ctl) => ctl,
        Err(e) => {
            diags.push(message::segmented_ring::loop_cannot_run(&e, c.span));
            return None;
        }
    };
    let mut ok = true;
    for (j, row) in table.rows().iter().enumerate() {
        if !c.clamp.contains(row.speed) {
            diags.push(message::segmented_ring::start_outside_clamp(
                j + 1,
                row.speed,
                c.clamp.low(),
                c.clamp.high(),
                w.speed_span,
                c.clamp_span,
            ));
            ok = false;
        }
    }
    let plant = plant(w, table, slicing, &c, target, diags);
    if !ok {
        return None;
    }
    let origins = RingOrigins {
        control: c.span,
        kp: c.kp_span,
        ki: c.ki_span,
        clamp: c.clamp_span,
        run: c.run_span,
        ..RingOrigins::default()
    };
    Some((
        HeightControl {
            controller,
            run: c.run,
            plant: plant?,
        },
        origins,
    ))
}

/// `plant = inverse_speed(drift, factors)`: calibrated so that each segment's
/// table speed lays the target, times its factor, drifting per layer.
fn plant(
    w: &Written,
    table: &SegmentTable,
    slicing: &ContinuousSpec,
    c: &ControlSpec,
    target: Length,
    diags: &mut Diagnostics,
) -> Option<Plant> {
    let p = &c.plant;
    let layers = slicing.layers.get();
    let last = 1.0 + p.drift * (layers - 1) as f64;
    if last <= 0.0 {
        diags.push(message::segmented_ring::drift_exhausts_plant(
            p.drift, layers, p.span,
        ));
        return None;
    }
    let calibrated = Plant::calibrated(target, &table.speeds(), p.drift).ok()?;
    match &p.factors {
        None => Some(calibrated),
        Some((f, at)) if f.len() != table.len() => {
            let seg_at = w.segments.map(|s| s.1).unwrap_or(w.span);
            diags.push(message::segmented_ring::table_length(
                crate::sema::schema::control::plant::FACTORS.key,
                f.len(),
                *at,
                table.len(),
                seg_at,
            ));
            None
        }
        Some((f, _)) => calibrated.scaled(f).ok(),
    }
}

#[cfg(test)]
mod tests {
    use crate::diag::Code;

    #[test]
    fn lists_of_unequal_length_without_segments_are_no_table() {
        let src = "part p\nring wall {\n  radius = 40 mm\n  table {\n    \
                   defocus = [-8 mm, -7 mm]\n    power = [1200 W, 1050 W]\n    \
                   width = [6 mm, 5 mm]\n    speed = [4 mm/s]\n  }\n}\n";
        let file = crate::syntax::parse(src).expect("parses");
        let (_, diags) = crate::sema::check(&file);
        // `segments` is reported missing; the table is not built.
        assert!(diags.iter().any(|d| d.code == Code::MissingField));
    }
}

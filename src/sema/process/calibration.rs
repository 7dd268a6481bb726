//! A calibration file: `part`, a `bead` (its width), `process`, the
//! machines and a `calibration { … }` block — the coupons `lmdc calibrate`
//! lays to measure the bead, laid out on the plate.

use crate::diag::{message, Diagnostics};
use crate::sema::eval::{unknown_name, Env};
use crate::sema::fields::{self, Fields};
use crate::sema::model::{
    Build, Calibration, Coupon, CouponKind, Model, PowerSchedule, Process, Styles, Tolerance,
};
use crate::sema::schema::bead as bead_schema;
use crate::sema::schema::calibration::{self as schema, coupon, CALIBRATION, PAD, WALL};
use crate::sema::statement::{shape_error, single, Statements};
use crate::sema::value::Value;
use crate::sema::{machine::statements as machines, process};
use crate::span::Span;
use crate::syntax::ast::Body;
use crate::units::{Length, MassFlow, Power, Speed};

/// The statements a calibration file has no use for: those of a part.
const PART_ONLY: &[&str] = &[
    "section",
    "profile",
    "loft",
    "extrude",
    "ring",
    "wall",
    "slicing",
    "control",
    "style",
    "inheritance",
];

/// Most coupons a calibration lays (a plate holds far fewer).
pub const MAX_COUPONS: usize = 10_000;

/// Checks a file with a `calibration` block (its constants already read).
pub fn check<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    part: Option<String>,
    diags: &mut Diagnostics,
) -> Option<Model> {
    for kind in PART_ONLY {
        for s in st.get(kind) {
            diags.push(message::calib::calibration_with_part(kind, s.kind.span));
        }
    }
    let process = process::statement(env, st, None, diags).process;
    let machines = machines::read(env, st, diags);
    let calibration = statement(env, st, process.as_ref(), diags);
    Some(Model {
        part: part?,
        build: Build::Calibration(calibration?),
        bead: None,
        process: process?,
        machines,
        fixtures: Vec::new(),
        styles: Styles::default(),
        tolerance: Tolerance::default(),
    })
}

/// The `calibration { … }` block, its coupons laid out.
fn statement<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    process: Option<&Process>,
    diags: &mut Diagnostics,
) -> Option<Calibration> {
    let s = single(
        st.get("calibration"),
        "calibration",
        "calibration { … }",
        diags,
    )?;
    let (None, Body::Block(stmts, _)) = (&s.name, &s.body) else {
        diags.push(shape_error(
            s,
            "calibration { … }",
            "calibration { bead = track  speeds = 4 mm/s .. 8 mm/s  count = 5 … }",
        ));
        return None;
    };
    let f = Fields::block(
        env,
        stmts,
        &CALIBRATION,
        "calibration".into(),
        s.span,
        diags,
    );
    let bead = bead(env, st, &f, diags);
    let speeds = speeds(&f, diags);
    let powers =
        list(&f, &schema::POWERS, diags).map(|l| l.map(|v| v.into_iter().map(Power).collect()));
    let powders = list(&f, &schema::POWDERS, diags)
        .map(|l| l.map(|v| v.into_iter().map(MassFlow).collect::<Vec<_>>()));
    let repeat = f.count_or_default(&schema::REPEAT, diags);
    let random = f
        .word_or_default(&schema::ORDER, diags)
        .map(|w| w == "random");
    let seed = f.count_or_default(&schema::SEED, diags);
    let kind = kind(&f, diags);
    let length = f.quantity(&schema::LENGTH, diags).map(|(l, _)| Length(l));
    let spacing = f.quantity(&schema::SPACING, diags).map(|(l, _)| Length(l));
    let layer_height = f
        .quantity(&schema::LAYER_HEIGHT, diags)
        .map(|(h, _)| Length(h));
    let origin = match f.value(&schema::ORIGIN, diags) {
        Some(v) => crate::sema::solid::profile::point(v, diags).map(|[x, y]| [x.0, y.0]),
        None => (!f.has(&schema::ORIGIN)).then_some([0.0, 0.0]),
    };
    let plate = plate(&f, diags);
    let (name, width, height) = bead?;
    let layer_height = match (layer_height, height) {
        (Some(h), _) => h,
        (None, Some([lo, hi])) if !f.has(&schema::LAYER_HEIGHT) => Length((lo + hi) / 2.0),
        (None, _) => {
            f.require(&schema::LAYER_HEIGHT, diags);
            return None;
        }
    };
    let process = process?;
    let powers = powers_or_process(powers?, process, diags)?;
    let powders = powders?.unwrap_or_else(|| vec![process.powder]);
    let (kind, length, spacing) = (kind?, length?, spacing?);
    let (speeds, repeat) = (speeds?, repeat?);
    let counts = [speeds.len(), powers.len(), powders.len(), repeat];
    within_count(counts, s.span, diags)?;
    let mut coupons = matrix(&speeds, &powers, &powders, repeat);
    if random? {
        shuffle(&mut coupons, seed? as u64);
    }
    let footprint = kind.footprint(width);
    let (plate, plate_span) = plate?;
    let room = Room {
        origin: origin?,
        plate,
        length: length.0,
        footprint: footprint.0,
        spacing: spacing.0,
    };
    if let Err(d) = room.lay(&mut coupons, width, plate_span) {
        diags.push(d);
        return None;
    }
    Some(Calibration {
        bead: name,
        width,
        layer_height,
        kind,
        length,
        coupons,
        span: s.span,
    })
}

/// The powers written, or the process's one constant power (a ramp gives no
/// single power to lay coupons at).
fn powers_or_process(
    written: Option<Vec<Power>>,
    process: &Process,
    diags: &mut Diagnostics,
) -> Option<Vec<Power>> {
    match (written, process.power) {
        (Some(p), _) => Some(p),
        (None, PowerSchedule::Constant(p)) => Some(vec![p]),
        (None, PowerSchedule::Ramp { .. }) => {
            diags.push(message::calib::ramp_without_powers(process.power_span));
            None
        }
    }
}

/// The coupon count (speeds × powers × powders × repeats), counted before
/// any is made: lists long enough to exhaust memory are refused, not
/// allocated.
fn within_count(counts: [usize; 4], span: Span, diags: &mut Diagnostics) -> Option<()> {
    let n = counts
        .iter()
        .try_fold(1usize, |a, &b| a.checked_mul(b))
        .unwrap_or(usize::MAX);
    if n > MAX_COUPONS {
        diags.push(message::calib::too_many_coupons(n, MAX_COUPONS, span));
        return None;
    }
    Some(())
}

/// `bead = NAME`: the bead's name, its width and its declared heights, if
/// any (its model is what the coupons measure, and is not read).
fn bead<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    f: &Fields<'_>,
    diags: &mut Diagnostics,
) -> Option<(String, Length, Option<[f64; 2]>)> {
    let v = f.value(&schema::BEAD, diags)?;
    let Value::Symbol(name) = &v.value else {
        diags.push(message::bead::bead_not_a_name(
            "bead",
            "calibration",
            v.span,
            &v.value.describe(),
        ));
        return None;
    };
    let declared = st.get("bead");
    let Some(s) = declared
        .iter()
        .find(|s| s.name.as_ref().is_some_and(|n| &n.node == name))
    else {
        let names: Vec<&str> = declared
            .iter()
            .filter_map(|s| s.name.as_ref().map(|n| n.node.as_str()))
            .collect();
        diags.push(unknown_name(name, v.span, "bead", &names));
        return None;
    };
    let Body::Block(stmts, _) = &s.body else {
        diags.push(shape_error(
            s,
            "bead NAME { … }",
            "bead track { width = 2.4 mm }",
        ));
        return None;
    };
    let b = Fields::block(
        env,
        stmts,
        &bead_schema::BEAD,
        format!("bead `{name}`"),
        s.span,
        diags,
    );
    let width = b.quantity(&bead_schema::WIDTH, diags);
    let height = b.range(&bead_schema::HEIGHT, diags).map(|(h, _)| h);
    Some((name.clone(), Length(width?.0), height))
}

/// The speeds: a list, or a range split into `count`.
fn speeds(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<Vec<Speed>> {
    let v = f.value(&schema::SPEEDS, diags)?;
    match &v.value {
        Value::List(items) if items.is_empty() => {
            diags.push(message::calib::empty_list("speeds", v.span));
            None
        }
        Value::List(items) => {
            let read: Vec<Option<f64>> = items
                .iter()
                .map(|it| positive(it, crate::units::Dim::SPEED, "speeds", diags))
                .collect();
            read.into_iter().map(|s| s.map(Speed)).collect()
        }
        Value::Range(a, _) if a.dim != crate::units::Dim::SPEED => {
            diags.push(message::field::wrong_unit(
                v.span,
                "speeds",
                crate::units::Dim::SPEED,
                a.dim,
            ));
            None
        }
        Value::Range(a, b) => {
            let [lo, hi] = [a.value, b.value];
            if lo <= 0.0 {
                diags.push(message::bead::speed_not_positive(v.span));
                return None;
            }
            f.require(&schema::COUNT, diags);
            let (n, _) = f.count(&schema::COUNT, diags)?;
            Some(
                (0..n)
                    .map(|i| Speed(lo + (hi - lo) * i as f64 / (n - 1) as f64))
                    .collect(),
            )
        }
        other => {
            diags.push(message::calib::speeds_not_a_list(&other.describe(), v.span));
            None
        }
    }
}

/// A quantity of `dim` greater than zero.
fn positive(
    v: &crate::sema::value::Spanned,
    dim: crate::units::Dim,
    key: &str,
    diags: &mut Diagnostics,
) -> Option<f64> {
    let q = fields::quantity(v, dim, key, diags)?;
    if q > 0.0 && q.is_finite() {
        return Some(q);
    }
    diags.push(message::field::not_positive(
        key,
        &fields::shown(q, dim),
        &format!("each of `{key}`"),
        v.span,
    ));
    None
}

/// A list field: `Some(None)` when not written, `None` when wrong.
fn list(
    f: &Fields<'_>,
    field: &'static crate::sema::schema::Field,
    diags: &mut Diagnostics,
) -> Option<Option<Vec<f64>>> {
    if !f.has(field) {
        return Some(None);
    }
    let dim = field.kind.dim().expect("a list of quantities");
    let v = f.value(field, diags)?;
    let Value::List(items) = &v.value else {
        diags.push(message::bead::table_not_a_list(
            field.key,
            v.span,
            &v.value.describe(),
            "[1000 W, 1200 W]",
        ));
        return None;
    };
    if items.is_empty() {
        diags.push(message::calib::empty_list(field.key, v.span));
        return None;
    }
    let read: Vec<Option<f64>> = items
        .iter()
        .map(|it| positive(it, dim, field.key, diags))
        .collect();
    read.into_iter().collect::<Option<Vec<_>>>().map(Some)
}

/// `coupon = track | wall(layers) | pad(tracks, offset)`.
fn kind(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<CouponKind> {
    if !f.has(&schema::COUPON) {
        return Some(CouponKind::Track);
    }
    let v = f.value(&schema::COUPON, diags)?;
    match &v.value {
        Value::Symbol(w) if w == "track" => Some(CouponKind::Track),
        Value::Call(c) if c.func == "wall" => {
            let a = Fields::call(c, &WALL, diags);
            let (layers, _) = a.count(&coupon::LAYERS, diags)?;
            Some(CouponKind::Wall { layers })
        }
        Value::Call(c) if c.func == "pad" => {
            let a = Fields::call(c, &PAD, diags);
            let tracks = a.count(&coupon::TRACKS, diags);
            let offset = a.quantity(&coupon::OFFSET, diags);
            Some(CouponKind::Pad {
                tracks: tracks?.0,
                offset: Length(offset?.0),
            })
        }
        _ => {
            // Lists `wall(…)` and `pad(…)` too (`Fields::word`).
            f.word(&schema::COUPON, diags);
            None
        }
    }
}

/// `plate = [x, y]` and where it is written.
fn plate(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<([f64; 2], Span)> {
    let span = f.span(&schema::PLATE);
    let l = list(f, &schema::PLATE, diags)?;
    let Some(l) = l else {
        f.require(&schema::PLATE, diags);
        return None;
    };
    let span = span.unwrap_or_else(|| f.block_span());
    match l[..] {
        [x, y] => Some(([x, y], span)),
        _ => {
            diags.push(message::calib::plate_not_two(l.len(), span));
            None
        }
    }
}

/// Every speed at every power at every powder feed, `repeat` times each,
/// numbered `c01`, `c02`, … (not yet placed).
fn matrix(speeds: &[Speed], powers: &[Power], powders: &[MassFlow], repeat: usize) -> Vec<Coupon> {
    let n = speeds.len() * powers.len() * powders.len() * repeat;
    let digits = n.to_string().len().max(2);
    let mut out = Vec::with_capacity(n);
    for &powder in powders {
        for &power in powers {
            for &speed in speeds {
                for _ in 0..repeat {
                    out.push(Coupon {
                        id: format!("c{:0digits$}", out.len() + 1),
                        speed,
                        power,
                        powder,
                        start: [0.0, 0.0],
                    });
                }
            }
        }
    }
    out
}

/// Shuffles `coupons` by `seed` (Fisher–Yates over SplitMix64, written out
/// here so that a seed lays the same order whatever crate versions lmdc is
/// built with) and numbers them again in the order they are laid: `c01`
/// is the first laid. Laid in speed order, a plate that warms up or a
/// feeder that drifts would look like a speed effect; shuffled, it is
/// scatter the fit sees as such.
fn shuffle(coupons: &mut [Coupon], seed: u64) {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    for i in (1..coupons.len()).rev() {
        // Unbiased enough: 2⁶⁴ over at most 10 000 coupons.
        let j = (next() % (i as u64 + 1)) as usize;
        coupons.swap(i, j);
    }
    let ids: Vec<String> = {
        let mut v: Vec<String> = coupons.iter().map(|c| c.id.clone()).collect();
        v.sort();
        v
    };
    for (c, id) in coupons.iter_mut().zip(ids) {
        c.id = id;
    }
}

/// The plate and the room a coupon takes on it.
struct Room {
    origin: [f64; 2],
    plate: [f64; 2],
    length: f64,
    footprint: f64,
    spacing: f64,
}

impl Room {
    /// Places `coupons` in columns along +y from the plate's corner,
    /// `spacing` from its edges and from each other: a column holds as many
    /// as fit across the plate, the next column is a coupon's length and a
    /// spacing further along x. An error with the numbers when they do not
    /// fit.
    fn lay(
        &self,
        coupons: &mut [Coupon],
        width: Length,
        at: Span,
    ) -> Result<(), crate::diag::Diagnostic> {
        let (s, pitch_y, pitch_x) = (
            self.spacing,
            self.footprint + self.spacing,
            self.length + self.spacing,
        );
        let n = coupons.len();
        // Coupons a column holds; at least one, to report what they need.
        let per_column = (((self.plate[1] - s) / pitch_y).floor() as usize).clamp(1, n.max(1));
        let columns = n.div_ceil(per_column);
        let need = [
            s + columns as f64 * pitch_x,
            s + per_column as f64 * pitch_y,
        ];
        if need[0] > self.plate[0] + 1e-9 || need[1] > self.plate[1] + 1e-9 {
            return Err(message::calib::coupons_off_plate(
                n,
                [self.length, self.footprint, s],
                need,
                self.plate,
                at,
            ));
        }
        for (k, c) in coupons.iter_mut().enumerate() {
            let (col, row) = (k / per_column, k % per_column);
            c.start = [
                self.origin[0] + s + col as f64 * pitch_x,
                self.origin[1] + s + row as f64 * pitch_y + width.0 / 2.0,
            ];
        }
        Ok(())
    }
}

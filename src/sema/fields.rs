//! Reading the fields of a block (`bead b { width = 6 mm }`) or the arguments of
//! a call (`circle(diameter = 60 mm)`) with the types the reader expects. Every
//! problem — unknown field, duplicate, missing, wrong unit, out of range — is
//! reported, and reading goes on.

use super::eval::Env;
use super::suggest::did_you_mean;
use super::value::{Call, Spanned, Value};
use crate::diag::{message, Diagnostics};

use crate::span::Span;
use crate::syntax::ast::{Body, Expr, Stmt};
use crate::units::{short, Angle, Density, Dim, Length, MassFlow, Power, Quantity, Speed, Time};

/// One field: its key and its evaluated value (`None` if evaluation failed and was
/// reported already), or the statements of a nested block.
struct Entry<'a> {
    key: String,
    key_span: Span,
    value: Option<Spanned>,
    block: Option<(&'a [Stmt], Span)>,
    /// The unevaluated expression of a deferred field.
    expr: Option<&'a Expr>,
}

/// The fields of one block or call.
pub struct Fields<'a> {
    entries: Vec<Entry<'a>>,
    /// What the block is, for messages: "bead `wall`".
    what: String,
    /// Where to point when a field is missing.
    at: Span,
}

/// The result of looking a field up.
enum Lookup<'b> {
    Missing,
    Failed,
    Found(&'b Spanned),
}

impl<'a> Fields<'a> {
    /// Reads `stmts` as `key = value` fields (or `key { … }` where the key is in
    /// `blocks`), reporting keys not in `allowed` and duplicates.
    pub fn block(
        env: &mut Env<'a>,
        stmts: &'a [Stmt],
        allowed: &[&str],
        blocks: &[&str],
        what: String,
        at: Span,
        diags: &mut Diagnostics,
    ) -> Self {
        Self::block_with_repeats(env, stmts, allowed, blocks, &[], what, at, diags)
    }

    /// Like [`Fields::block`], and the blocks in `repeated` may be given any
    /// number of times (`when { … }` rules of a style); read them with
    /// [`Fields::nested_all`].
    #[allow(clippy::too_many_arguments)]
    pub fn block_with_repeats(
        env: &mut Env<'a>,
        stmts: &'a [Stmt],
        allowed: &[&str],
        blocks: &[&str],
        repeated: &[&str],
        what: String,
        at: Span,
        diags: &mut Diagnostics,
    ) -> Self {
        Self::read(env, stmts, allowed, blocks, repeated, &[], what, at, diags)
    }

    /// Like [`Fields::block`], but the fields in `deferred` (among
    /// `allowed`) are not evaluated: their expressions are kept for the
    /// reader, which evaluates them itself ([`Fields::expr`]) — an
    /// extrusion's `top`, a function of the position.
    pub fn block_deferring(
        env: &mut Env<'a>,
        stmts: &'a [Stmt],
        allowed: &[&str],
        deferred: &[&str],
        what: String,
        at: Span,
        diags: &mut Diagnostics,
    ) -> Self {
        Self::read(env, stmts, allowed, &[], &[], deferred, what, at, diags)
    }

    #[allow(clippy::too_many_arguments)]
    fn read(
        env: &mut Env<'a>,
        stmts: &'a [Stmt],
        allowed: &[&str],
        blocks: &[&str],
        repeated: &[&str],
        deferred: &[&str],
        what: String,
        at: Span,
        diags: &mut Diagnostics,
    ) -> Self {
        let blocks: Vec<&str> = blocks.iter().chain(repeated).copied().collect();
        let blocks = blocks.as_slice();
        let mut entries: Vec<Entry<'a>> = Vec::new();
        for s in stmts {
            let key = s.kind.node.as_str();
            if !allowed.contains(&key) && !blocks.contains(&key) {
                let fields: Vec<&str> = allowed.iter().chain(blocks).copied().collect();
                diags.push(message::field::unknown_field(
                    &what,
                    key,
                    s.kind.span,
                    did_you_mean(key, fields.iter().copied()),
                    &fields,
                ));
                continue;
            }
            if let Some(prev) = entries
                .iter()
                .find(|e| e.key == key && !repeated.contains(&key))
            {
                diags.push(message::field::duplicate_field(
                    key,
                    &what,
                    s.kind.span,
                    prev.key_span,
                ));
                continue;
            }
            if let Some(n) = &s.name {
                diags.push(message::field::name_after_key(&n.node, key, n.span));
                continue;
            }
            let is_block = blocks.contains(&key);
            let entry = match (&s.body, is_block) {
                (Body::Assign(e), false) if deferred.contains(&key) => Entry {
                    key: key.into(),
                    key_span: s.kind.span,
                    value: None,
                    block: None,
                    expr: Some(e),
                },
                (Body::Assign(e), false) => {
                    let before = env.layer_reads();
                    let value = env.eval(e, diags);
                    // Only a profile is evaluated per layer; anywhere else the
                    // layer builtins would silently read 0.
                    if env.layer_reads() > before && key != "profile" {
                        diags.push(message::field::layer_outside_profile(key, &what, e.span));
                    }
                    Entry {
                        key: key.into(),
                        key_span: s.kind.span,
                        value,
                        block: None,
                        expr: None,
                    }
                }
                (Body::Block(inner, span), true) => Entry {
                    key: key.into(),
                    key_span: s.kind.span,
                    value: None,
                    block: Some((inner.as_slice(), *span)),
                    expr: None,
                },
                (_, true) => {
                    diags.push(message::field::needs_block(key, s.span));
                    continue;
                }
                (_, false) => {
                    diags.push(message::field::needs_value(key, s.span));
                    continue;
                }
            };
            entries.push(entry);
        }
        Fields { entries, what, at }
    }

    /// Reads the arguments of `call`. Positional arguments take the names in
    /// `positional` in order.
    pub fn call(
        call: &Call,
        positional: &[&str],
        allowed: &[&str],
        diags: &mut Diagnostics,
    ) -> Self {
        let what = format!("`{}(…)`", call.func);
        let mut entries: Vec<Entry<'a>> = Vec::new();
        let mut next_pos = 0;
        for a in &call.args {
            let (key, key_span) = match &a.name {
                Some((n, s)) => (n.clone(), *s),
                None => {
                    if next_pos >= positional.len() {
                        diags.push(message::field::too_many_unnamed(
                            &what,
                            a.value.span,
                            allowed,
                        ));
                        continue;
                    }
                    next_pos += 1;
                    (positional[next_pos - 1].to_string(), a.value.span)
                }
            };
            if !allowed.contains(&key.as_str()) {
                diags.push(message::field::unknown_argument(
                    &what,
                    &key,
                    key_span,
                    did_you_mean(&key, allowed.iter().copied()),
                    allowed,
                ));
                continue;
            }
            if let Some(prev) = entries.iter().find(|e| e.key == key) {
                diags.push(message::field::duplicate_argument(
                    &key,
                    &what,
                    key_span,
                    prev.key_span,
                ));
                continue;
            }
            entries.push(Entry {
                key,
                key_span,
                value: Some(a.value.clone()),
                block: None,
                expr: None,
            });
        }
        Fields {
            entries,
            what,
            at: call.func_span,
        }
    }

    fn lookup(&self, key: &str) -> Lookup<'_> {
        match self.entries.iter().find(|e| e.key == key) {
            None => Lookup::Missing,
            Some(Entry { value: None, .. }) => Lookup::Failed,
            Some(Entry { value: Some(v), .. }) => Lookup::Found(v),
        }
    }

    /// Where field `key` is written, if it is.
    pub fn span(&self, key: &str) -> Option<Span> {
        self.entries
            .iter()
            .find(|e| e.key == key)
            .map(|e| match (&e.value, e.expr) {
                (Some(v), _) => e.key_span.join(v.span),
                (None, Some(x)) => e.key_span.join(x.span),
                (None, None) => e.key_span,
            })
    }

    /// The unevaluated expression of the deferred field `key`, if written.
    pub fn expr(&self, key: &str) -> Option<&'a Expr> {
        self.entries
            .iter()
            .find(|e| e.key == key)
            .and_then(|e| e.expr)
    }

    /// Is `key` written?
    pub fn has(&self, key: &str) -> bool {
        self.entries.iter().any(|e| e.key == key)
    }

    /// The statements of the nested block `key`, if written.
    pub fn nested(&self, key: &str) -> Option<(&'a [Stmt], Span)> {
        self.entries
            .iter()
            .find(|e| e.key == key)
            .and_then(|e| e.block)
    }

    /// An optional field as read: `Some(None)` when the block does not write
    /// `key`, `None` when it is written but wrong (reported already), else
    /// `Some(Some(value))`.
    pub fn optional<T>(&self, key: &str, read: Option<T>) -> Option<Option<T>> {
        match read {
            Some(v) => Some(Some(v)),
            None if self.has(key) => None,
            None => Some(None),
        }
    }

    /// The statements of every `key { … }` block, in source order.
    pub fn nested_all(&self, key: &str) -> Vec<(&'a [Stmt], Span)> {
        self.entries
            .iter()
            .filter(|e| e.key == key)
            .filter_map(|e| e.block)
            .collect()
    }

    fn missing(&self, key: &str, example: &str, diags: &mut Diagnostics) {
        diags.push(message::field::missing_field(
            &self.what, key, self.at, example,
        ));
    }

    /// The raw value of `key`; `None` if missing (reported when `example` is
    /// given, i.e. the field is required) or failed.
    pub fn value(
        &self,
        key: &str,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<&Spanned> {
        match self.lookup(key) {
            Lookup::Found(v) => Some(v),
            Lookup::Failed => None,
            Lookup::Missing => {
                if let Some(example) = required {
                    self.missing(key, example, diags);
                }
                None
            }
        }
    }

    /// A quantity of dimension `dim` (canonical units).
    pub fn quantity(
        &self,
        key: &str,
        dim: Dim,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<(f64, Span)> {
        let v = self.value(key, required, diags)?;
        quantity(v, dim, key, diags).map(|q| (q, v.span))
    }

    /// A quantity of dimension `dim` that must be > 0.
    pub fn positive(
        &self,
        key: &str,
        dim: Dim,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<(f64, Span)> {
        let (q, span) = self.quantity(key, dim, required, diags)?;
        if q > 0.0 && q.is_finite() {
            Some((q, span))
        } else {
            diags.push(message::field::not_positive(
                key,
                &shown(q, dim),
                &self.what,
                span,
            ));
            None
        }
    }

    /// A range `lo .. hi` of dimension `dim`.
    pub fn range(
        &self,
        key: &str,
        dim: Dim,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<([f64; 2], Span)> {
        let v = self.value(key, required, diags)?;
        match &v.value {
            Value::Range(a, b) if a.dim == dim => Some(([a.value, b.value], v.span)),
            Value::Range(a, _) => {
                diags.push(message::field::wrong_unit(v.span, key, dim, a.dim));
                None
            }
            other => {
                diags.push(message::field::expected_range(key, dim, other, v.span));
                None
            }
        }
    }

    /// A whole number within `lo..=hi`.
    pub fn count(
        &self,
        key: &str,
        lo: usize,
        hi: usize,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<(usize, Span)> {
        let v = self.value(key, required, diags)?;
        count(v, key, lo, hi, diags).map(|n| (n, v.span))
    }

    /// One of the words in `choices`.
    pub fn symbol(
        &self,
        key: &str,
        choices: &[&str],
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<(String, Span)> {
        let v = self.value(key, required, diags)?;
        symbol(v, key, choices, diags).map(|s| (s, v.span))
    }

    /// A text.
    pub fn text(
        &self,
        key: &str,
        required: Option<&str>,
        diags: &mut Diagnostics,
    ) -> Option<(String, Span)> {
        let v = self.value(key, required, diags)?;
        match &v.value {
            Value::Str(s) => Some((s.clone(), v.span)),
            other => {
                diags.push(message::field::expected_text(key, other, v.span));
                None
            }
        }
    }
}

/// A value of dimension `dim` for a message, in the unit that kind of value
/// is written in (W, g/min, deg, …), not in lmdc's internal units.
pub fn shown(value: f64, dim: Dim) -> String {
    match dim {
        Dim::NONE => short(value),
        Dim::LENGTH => Length(value).to_string(),
        Dim::ANGLE => Angle(value).to_string(),
        Dim::SPEED => Speed(value).to_string(),
        Dim::POWER => Power(value).to_string(),
        Dim::MASS_FLOW => MassFlow(value).to_string(),
        Dim::DENSITY => Density(value).to_string(),
        Dim::TIME => Time(value).to_string(),
        other => format!("{} {}", short(value), other.unit_string()),
    }
}

/// `v` as a quantity of dimension `dim`.
pub fn quantity(v: &Spanned, dim: Dim, key: &str, diags: &mut Diagnostics) -> Option<f64> {
    match &v.value {
        Value::Quantity(Quantity { value, dim: d }) if *d == dim => {
            // Plausibility bounds keep absurd inputs from reaching the geometry
            // (a 1e300 mm defocus would overflow every machine format).
            let bound = match dim {
                Dim::LENGTH => Some((1e5, "100 m")),
                Dim::SPEED => Some((1e5, "100 m/s")),
                _ => None,
            };
            match bound {
                Some((b, text)) if value.abs() > b => {
                    diags.push(message::field::too_large(
                        key,
                        text,
                        &shown(*value, dim),
                        v.span,
                    ));
                    None
                }
                _ => Some(*value),
            }
        }
        Value::Quantity(q) => {
            diags.push(message::field::wrong_unit(v.span, key, dim, q.dim));
            None
        }
        other => {
            if let Some(d) = super::eval::position_outside_top(other, v.span) {
                diags.push(d);
                return None;
            }
            diags.push(message::field::expected_number(key, dim, other, v.span));
            None
        }
    }
}

/// `v` as a whole number within `lo..=hi`.
pub fn count(
    v: &Spanned,
    key: &str,
    lo: usize,
    hi: usize,
    diags: &mut Diagnostics,
) -> Option<usize> {
    match &v.value {
        Value::Quantity(Quantity { value, dim }) if *dim == Dim::NONE && value.fract() == 0.0 => {
            if *value >= lo as f64 && *value <= hi as f64 {
                Some(*value as usize)
            } else {
                diags.push(message::field::count_range(key, lo, hi, *value, v.span));
                None
            }
        }
        other => {
            diags.push(message::field::expected_whole_number(key, other, v.span));
            None
        }
    }
}

/// `v` as one of the words in `choices`.
pub fn symbol(v: &Spanned, key: &str, choices: &[&str], diags: &mut Diagnostics) -> Option<String> {
    if let Value::Symbol(s) = &v.value {
        if choices.contains(&s.as_str()) {
            return Some(s.clone());
        }
    }
    let suggestion = match &v.value {
        Value::Symbol(s) => did_you_mean(s, choices.iter().copied()),
        _ => None,
    };
    diags.push(message::field::bad_choice(
        key, choices, &v.value, v.span, suggestion,
    ));
    None
}

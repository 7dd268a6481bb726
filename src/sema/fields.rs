//! Reading the fields of a block (`bead b { width = 6 mm }`) or the arguments of
//! a call (`circle(diameter = 60 mm)`) with the types the reader expects. Every
//! problem — unknown field, duplicate, missing, wrong unit, out of range — is
//! reported, and reading goes on.

use crate::diag::{message, Diagnostic, Diagnostics};
use crate::sema::eval::Env;
use crate::sema::schema::{Block, Bound, DefaultValue, Field, Need};
use crate::sema::suggest::did_you_mean;
use crate::sema::value::{Call, Spanned, Value};
pub use crate::units::shown;

use crate::span::Span;
use crate::syntax::ast::{Body, Expr, Stmt};
use crate::units::{Dim, Quantity};

/// One field: its key and its evaluated value (`None` if evaluation failed and was
/// reported already), or the statements of a nested block.
struct Entry<'a> {
    field: &'static Field,
    key_span: Span,
    value: Option<Spanned>,
    block: Option<(&'a [Stmt], Span)>,
    /// The unevaluated expression of a deferred field.
    expr: Option<&'a Expr>,
}

impl Entry<'_> {
    /// Where the field is written: its key and value (a nested block: its
    /// key).
    fn span(&self) -> Span {
        match (&self.value, self.expr) {
            (Some(v), _) => self.key_span.join(v.span),
            (None, Some(x)) => self.key_span.join(x.span),
            (None, None) => self.key_span,
        }
    }
}

/// The fields of one block or call, as its table ([`Block`]) allows them.
/// Every read goes through a field's entry in that table: its kind, whether
/// it is required and with which example, its bounds, its default.
pub struct Fields<'a> {
    entries: Vec<Entry<'a>>,
    /// The table the block or call was read with.
    block: &'static Block,
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
    /// Reads `stmts` as the fields of `block`: `key = value`, or `key { … }`
    /// for a nested block (any number of times when the table says so),
    /// a deferred field's expression kept unevaluated ([`Fields::expr`]).
    /// Reports keys the table does not have, duplicates, and values given
    /// the wrong shape.
    pub fn block(
        env: &mut Env<'a>,
        stmts: &'a [Stmt],
        block: &'static Block,
        what: String,
        at: Span,
        diags: &mut Diagnostics,
    ) -> Self {
        let mut entries: Vec<Entry<'a>> = Vec::new();
        for s in stmts {
            let key = s.kind.node.as_str();
            let Some(field) = block.accepted().find(|f| f.key == key) else {
                let fields: Vec<&str> = block.accepted().map(|f| f.key).collect();
                // A value written as a key (`spiral = true`) is pointed to
                // the field that takes it.
                let taken = block.field_taking(key).map(|(_, written)| written);
                diags.push(message::field::unknown_field(
                    &what,
                    key,
                    s.kind.span,
                    taken
                        .as_deref()
                        .or_else(|| did_you_mean(key, fields.iter().copied())),
                    &fields,
                ));
                continue;
            };
            let repeated = matches!(field.kind, crate::sema::schema::Kind::Blocks(_));
            if let Some(prev) = entries.iter().find(|e| e.field == field && !repeated) {
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
            let mut entry = Entry {
                field,
                key_span: s.kind.span,
                value: None,
                block: None,
                expr: None,
            };
            match (&s.body, field.kind.is_block()) {
                (Body::Assign(e), false) if field.deferred() => entry.expr = Some(e),
                (Body::Assign(e), false) => {
                    let before = env.layer_reads();
                    entry.value = env.eval(e, diags);
                    // Only a profile is evaluated per layer; anywhere else the
                    // layer builtins would silently read 0.
                    if env.layer_reads() > before && !field.layered() {
                        diags.push(message::field::layer_outside_profile(key, &what, e.span));
                    }
                }
                (Body::Block(inner, span), true) => entry.block = Some((inner.as_slice(), *span)),
                (_, true) => {
                    diags.push(message::field::needs_block(key, s.span));
                    continue;
                }
                (_, false) => {
                    diags.push(message::field::needs_value(key, s.span));
                    continue;
                }
            }
            entries.push(entry);
        }
        Fields {
            entries,
            block,
            what,
            at,
        }
    }

    /// Reads the arguments of `call` as the fields of `block`: unnamed
    /// arguments take the names of its positional fields, in order.
    pub fn call(call: &Call, block: &'static Block, diags: &mut Diagnostics) -> Self {
        let what = format!("`{}(…)`", call.func);
        let allowed: Vec<&str> = block.accepted().map(|f| f.key).collect();
        let positional = &block.fields[..block.positional];
        let mut entries: Vec<Entry<'a>> = Vec::new();
        let mut next_pos = 0;
        for a in &call.args {
            let (key, key_span) = match &a.name {
                Some((n, s)) => (n.as_str(), *s),
                None => {
                    let Some(f) = positional.get(next_pos) else {
                        diags.push(message::field::too_many_unnamed(
                            &what,
                            a.value.span,
                            &allowed,
                        ));
                        continue;
                    };
                    next_pos += 1;
                    (f.key, a.value.span)
                }
            };
            let Some(field) = block.accepted().find(|f| f.key == key) else {
                diags.push(message::field::unknown_argument(
                    &what,
                    key,
                    key_span,
                    did_you_mean(key, allowed.iter().copied()),
                    &allowed,
                ));
                continue;
            };
            if let Some(prev) = entries.iter().find(|e| e.field == field) {
                diags.push(message::field::duplicate_argument(
                    key,
                    &what,
                    key_span,
                    prev.key_span,
                ));
                continue;
            }
            entries.push(Entry {
                field,
                key_span,
                value: Some(a.value.clone()),
                block: None,
                expr: None,
            });
        }
        Fields {
            entries,
            block,
            what,
            at: call.func_span,
        }
    }

    /// The entry of `f`, if written. `f` must be a field of the block's
    /// table: reading another block's field is a mistake of the reader.
    fn entry(&self, f: &Field) -> Option<&Entry<'a>> {
        debug_assert!(
            self.block.owns(f),
            "`{}` is not a field of `{}`",
            f.key,
            self.block.name
        );
        self.entries.iter().find(|e| e.field == f)
    }

    fn lookup(&self, f: &Field) -> Lookup<'_> {
        match self.entry(f) {
            None => Lookup::Missing,
            Some(Entry { value: None, .. }) => Lookup::Failed,
            Some(Entry { value: Some(v), .. }) => Lookup::Found(v),
        }
    }

    /// Where field `f` is written, if it is.
    pub fn span(&self, f: &Field) -> Option<Span> {
        self.entry(f).map(Entry::span)
    }

    /// Every field written, with where, in source order.
    pub fn written(&self) -> impl Iterator<Item = (&'static Field, Span)> + '_ {
        self.entries.iter().map(|e| (e.field, e.span()))
    }

    /// The unevaluated expression of the deferred field `f`, if written.
    pub fn expr(&self, f: &Field) -> Option<&'a Expr> {
        self.entry(f).and_then(|e| e.expr)
    }

    /// Is `f` written?
    pub fn has(&self, f: &Field) -> bool {
        self.entry(f).is_some()
    }

    /// The statements of the nested block `f`, if written.
    pub fn nested(&self, f: &Field) -> Option<(&'a [Stmt], Span)> {
        self.entry(f).and_then(|e| e.block)
    }

    /// The statements of every `f { … }` block, in source order.
    pub fn nested_all(&self, f: &Field) -> Vec<(&'a [Stmt], Span)> {
        debug_assert!(self.block.owns(f));
        self.entries
            .iter()
            .filter(|e| e.field == f)
            .filter_map(|e| e.block)
            .collect()
    }

    /// Where the block is: what a check points at when the field it is
    /// about is not written.
    pub fn block_span(&self) -> Span {
        self.at
    }

    /// An optional field as read: `Some(None)` when the block does not write
    /// `f`, `None` when it is written but wrong (reported already), else
    /// `Some(Some(value))`.
    pub fn optional<T>(&self, f: &Field, read: Option<T>) -> Option<Option<T>> {
        match read {
            Some(v) => Some(Some(v)),
            None if self.has(f) => None,
            None => Some(None),
        }
    }

    /// A field as read, or `default` when the block does not write it;
    /// `None` when it is written but wrong (reported already).
    pub fn or_default<T>(&self, f: &Field, read: Option<T>, default: T) -> Option<T> {
        match read {
            Some(x) => Some(x),
            None if self.has(f) => None,
            None => Some(default),
        }
    }

    /// The example a missing `f` is suggested with: the block's, else the
    /// field's.
    pub fn example(&self, f: &Field) -> &'static str {
        self.block.example(f).unwrap_or("…")
    }

    /// Reports `f` missing when it is not written: for a field required
    /// unless something else holds, which its reader decides.
    pub fn require(&self, f: &Field, diags: &mut Diagnostics) {
        if !self.has(f) {
            self.missing(f, diags);
        }
    }

    fn missing(&self, f: &Field, diags: &mut Diagnostics) {
        diags.push(message::field::missing_field(
            &self.what,
            f.key,
            self.at,
            self.example(f),
        ));
    }

    /// The raw value of `f`; `None` if missing (reported when the table
    /// says it is required) or failed.
    pub fn value(&self, f: &Field, diags: &mut Diagnostics) -> Option<&Spanned> {
        match self.lookup(f) {
            Lookup::Found(v) => Some(v),
            Lookup::Failed => None,
            Lookup::Missing => {
                if let Need::Required(_) = f.need {
                    self.missing(f, diags);
                }
                None
            }
        }
    }

    /// A quantity of the field's dimension (canonical units), within the
    /// bounds that have a message of their own: greater than zero, a time
    /// within its limit.
    pub fn quantity(&self, f: &Field, diags: &mut Diagnostics) -> Option<(f64, Span)> {
        let (dim, bound) = quantity_kind(f);
        debug_assert!(
            matches!(bound, Bound::Any | Bound::Positive)
                || matches!(bound, Bound::ZeroUpTo(_)) && dim == Dim::TIME,
            "`{}`'s bound is worded by its reader: read it with `bounded`",
            f.key
        );
        let (q, span) = self.raw_quantity(f, dim, diags)?;
        match bound {
            Bound::Positive => self.positive(f, q, dim, span, diags),
            Bound::ZeroUpTo(max) if !(0.0..=max).contains(&q) => {
                diags.push(message::field::time_out_of_range(f.key, q, max, span));
                None
            }
            _ => Some((q, span)),
        }
    }

    /// A quantity whose bounds the reader words: `out` makes the report of
    /// a value outside them (below zero for a bound that is only "greater
    /// than zero and at most", the generic "must be greater than zero").
    pub fn bounded(
        &self,
        f: &Field,
        out: impl FnOnce(f64, Span) -> Diagnostic,
        diags: &mut Diagnostics,
    ) -> Option<(f64, Span)> {
        let (dim, bound) = quantity_kind(f);
        let (q, span) = self.raw_quantity(f, dim, diags)?;
        let inside = match bound {
            Bound::PositiveUpTo(max) => {
                self.positive(f, q, dim, span, diags)?;
                q <= max
            }
            Bound::NonNegative => q >= 0.0,
            Bound::Negative => q < 0.0,
            Bound::Within(max) => q > 0.0 && q <= max,
            Bound::ZeroUpTo(max) => (0.0..=max).contains(&q),
            Bound::Magnitude(max) => q.abs() <= max,
            Bound::Any | Bound::Positive => {
                debug_assert!(false, "`{}` has no bound of its own", f.key);
                true
            }
        };
        if inside {
            Some((q, span))
        } else {
            diags.push(out(q, span));
            None
        }
    }

    /// A quantity, or the table's default when not written; `None` when
    /// written wrong (reported).
    pub fn quantity_or_default(&self, f: &Field, diags: &mut Diagnostics) -> Option<f64> {
        let read = self.quantity(f, diags).map(|q| q.0);
        self.or_default(f, read, default_quantity(f))
    }

    /// A quantity whose bounds the reader words ([`Fields::bounded`]), or
    /// the table's default when not written; `None` when written wrong
    /// (reported).
    pub fn bounded_or_default(
        &self,
        f: &Field,
        out: impl FnOnce(f64, Span) -> Diagnostic,
        diags: &mut Diagnostics,
    ) -> Option<f64> {
        let read = self.bounded(f, out, diags).map(|q| q.0);
        self.or_default(f, read, default_quantity(f))
    }

    fn raw_quantity(&self, f: &Field, dim: Dim, diags: &mut Diagnostics) -> Option<(f64, Span)> {
        let v = self.value(f, diags)?;
        quantity(v, dim, f.key, diags).map(|q| (q, v.span))
    }

    fn positive(
        &self,
        f: &Field,
        q: f64,
        dim: Dim,
        span: Span,
        diags: &mut Diagnostics,
    ) -> Option<(f64, Span)> {
        if q > 0.0 && q.is_finite() {
            Some((q, span))
        } else {
            diags.push(message::field::not_positive(
                f.key,
                &shown(q, dim),
                &self.what,
                span,
            ));
            None
        }
    }

    /// A range `lo .. hi` of the field's dimension.
    pub fn range(&self, f: &Field, diags: &mut Diagnostics) -> Option<([f64; 2], Span)> {
        let Some(dim) = f.kind.dim() else {
            panic!("`{}` is not a range", f.key)
        };
        let v = self.value(f, diags)?;
        match &v.value {
            Value::Range(a, b) if a.dim == dim => Some(([a.value, b.value], v.span)),
            Value::Range(a, _) => {
                diags.push(message::field::wrong_unit(v.span, f.key, dim, a.dim));
                None
            }
            other => {
                diags.push(message::field::expected_range(
                    f.key,
                    dim,
                    other.got(),
                    v.span,
                ));
                None
            }
        }
    }

    /// A whole number within the field's bounds.
    pub fn count(&self, f: &Field, diags: &mut Diagnostics) -> Option<(usize, Span)> {
        let Some((lo, hi)) = f.kind.count() else {
            panic!("`{}` is not a count", f.key)
        };
        self.count_in(f, lo, hi, diags)
    }

    /// A whole number within `lo..=hi`: an input or output, whose bounds
    /// are the machine's control's.
    pub fn count_in(
        &self,
        f: &Field,
        lo: usize,
        hi: usize,
        diags: &mut Diagnostics,
    ) -> Option<(usize, Span)> {
        let v = self.value(f, diags)?;
        count(v, f.key, lo, hi, diags).map(|n| (n, v.span))
    }

    /// A whole number, or the table's default when not written; `None`
    /// when written wrong (reported).
    pub fn count_or_default(&self, f: &Field, diags: &mut Diagnostics) -> Option<usize> {
        let read = self.count(f, diags).map(|n| n.0);
        let Need::Default(DefaultValue::Count(n)) = f.need else {
            panic!("`{}` has no whole-number default", f.key)
        };
        self.or_default(f, read, n)
    }

    /// One of the field's words. Where the field takes calls too
    /// (`coupon = track | wall(…)`), the error lists them with their
    /// arguments, and a word near a call's name suggests the call.
    pub fn word(&self, f: &Field, diags: &mut Diagnostics) -> Option<(&'static str, Span)> {
        let Some(words) = f.kind.words() else {
            panic!("`{}` takes no words", f.key)
        };
        let v = self.value(f, diags)?;
        let calls = f.kind.calls();
        if calls.is_empty() {
            return word(v, f.key, words, diags).map(|w| (w, v.span));
        }
        if let Value::Symbol(s) = &v.value {
            if let Some(w) = words.iter().find(|w| **w == s.as_str()) {
                return Some((w, v.span));
            }
        }
        let shown = |b: &Block| {
            let args: Vec<String> = b.fields.iter().map(|a| format!("{} = …", a.key)).collect();
            format!("{}({})", b.name, args.join(", "))
        };
        let mut choices: Vec<String> = words.iter().map(|w| w.to_string()).collect();
        choices.extend(calls.iter().map(|b| shown(b)));
        let suggestion = match &v.value {
            Value::Symbol(s) => did_you_mean(
                s,
                words.iter().chain(calls.iter().map(|b| &b.name)).copied(),
            )
            .map(|m| {
                calls
                    .iter()
                    .find(|b| b.name == m)
                    .map_or(m.to_string(), |b| shown(b))
            }),
            _ => None,
        };
        let refs: Vec<&str> = choices.iter().map(String::as_str).collect();
        diags.push(message::field::bad_choice(
            f.key,
            &refs,
            v.value.got(),
            v.span,
            suggestion.as_deref(),
        ));
        None
    }

    /// One of the field's words, or the table's default when not written;
    /// `None` when written wrong (reported).
    pub fn word_or_default(&self, f: &Field, diags: &mut Diagnostics) -> Option<&'static str> {
        let read = self.word(f, diags).map(|w| w.0);
        let Need::Default(DefaultValue::Word(w)) = f.need else {
            panic!("`{}` has no word as its default", f.key)
        };
        self.or_default(f, read, w)
    }

    /// A text.
    pub fn text(&self, f: &Field, diags: &mut Diagnostics) -> Option<(String, Span)> {
        let v = self.value(f, diags)?;
        match &v.value {
            Value::Str(s) => Some((s.clone(), v.span)),
            other => {
                diags.push(message::field::expected_text(f.key, other.got(), v.span));
                None
            }
        }
    }
}

/// The dimension and bounds of a field that takes a quantity.
fn quantity_kind(f: &Field) -> (Dim, Bound) {
    match f.kind.quantity() {
        Some(q) => q,
        None => panic!("`{}` takes no quantity", f.key),
    }
}

/// The default of a field whose default is a quantity.
fn default_quantity(f: &Field) -> f64 {
    match f.need {
        Need::Default(DefaultValue::Quantity(q)) => q,
        _ => panic!("`{}` has no quantity as its default", f.key),
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
            if let Some(d) = crate::sema::eval::position_outside_top(other, v.span) {
                diags.push(d);
                return None;
            }
            diags.push(message::field::expected_number(
                key,
                dim,
                other.got(),
                v.span,
            ));
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
            diags.push(message::field::expected_whole_number(
                key,
                other.got(),
                v.span,
            ));
            None
        }
    }
}

/// `v` as one of the words in `choices`.
pub fn word(
    v: &Spanned,
    key: &str,
    choices: &'static [&'static str],
    diags: &mut Diagnostics,
) -> Option<&'static str> {
    if let Value::Symbol(s) = &v.value {
        if let Some(w) = choices.iter().find(|w| **w == s.as_str()) {
            return Some(w);
        }
    }
    let suggestion = match &v.value {
        Value::Symbol(s) => did_you_mean(s, choices.iter().copied()),
        _ => None,
    };
    diags.push(message::field::bad_choice(
        key,
        choices,
        v.value.got(),
        v.span,
        suggestion,
    ));
    None
}

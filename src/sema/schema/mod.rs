//! The language's blocks as data: every block (`bead NAME { … }`, `limits
//! { … }`) and every call with named arguments (`circle(diameter = …)`) is a
//! [`Block`], a table of [`Field`]s — the key, the kind of value, the default
//! (or required, with the example a missing-field message suggests), bounds
//! and a line of help.
//!
//! One table per block, read by everything that needs to know what a block
//! may contain: the readers (`sema::fields::Fields` takes a block's table,
//! allows its keys and nothing else, and reads each field through its entry),
//! the source spans of a machine's fields ([`crate::ir::MachineOrigin`] is
//! keyed by the entries), the field tables of `docs/language.md` (generated
//! from these, `tests/docs.rs`), and an editor's completion and hover.
//!
//! A field's identity is its entry: the statics here have one address each,
//! and a block shares an entry with another when the field means the same in
//! both (a machine's `max_speed`, the height sensor's fields, `gas` and
//! `powder`), so a check can ask where "the machine's `max_speed`" is written
//! whatever the machine's kind.

pub mod bead;
pub mod calibration;
pub mod collision;
pub mod control;
pub mod machine;
pub mod process;
pub mod shape;
pub mod slicing;
pub mod solid;
pub mod style;
pub mod wall;

use crate::units::shown;
use crate::units::Dim;

/// An angle in degrees, in radians as [`f64::to_radians`] gives it (so a
/// bound or default in the tables is the value the same angle written in
/// `deg` has).
pub const fn deg(d: f64) -> f64 {
    d * (std::f64::consts::PI / 180.0)
}

/// One field of a block, or one named argument of a call.
#[derive(Debug)]
pub struct Field {
    /// What is written before `=` (or before `{` for a nested block).
    pub key: &'static str,
    /// The kind of value it takes.
    pub kind: Kind,
    /// Whether it must be written, and what holds when it is not.
    pub need: Need,
    /// One line saying what it is for.
    pub help: &'static str,
}

/// The kind of value a field takes.
#[derive(Debug)]
pub enum Kind {
    /// A quantity of a dimension, within bounds (in canonical units: mm, g,
    /// s, rad; see [`crate::units`]).
    Quantity(Dim, Bound),
    /// A range `low .. high` of a dimension.
    Range(Dim),
    /// A whole number from the first to the second, both included.
    Count(usize, usize),
    /// An input or output number, in the range the machine's control numbers
    /// them ([`Io`]).
    Io(Io),
    /// One of these words.
    Word(&'static [&'static str]),
    /// A text in quotes.
    Text,
    /// A text, or a list of texts: program lines.
    Lines,
    /// The name of a declaration of this kind (`"bead"`).
    Name(&'static str),
    /// A shape: a section, an `outline(…)`, a `region(…)` or a `place(…)`.
    Shape,
    /// A point `[x, y]` of two lengths.
    Point,
    /// One of these calls.
    Call(&'static [&'static Block]),
    /// A list of values of one kind.
    List(&'static Kind, Len),
    /// Any one of these kinds.
    Either(&'static [Kind]),
    /// A value that may follow `layer` (a profile): it is evaluated on every
    /// layer, where anywhere else `layer` is refused.
    Layered(&'static Kind),
    /// An expression its reader evaluates itself: a gain, whose units are
    /// read as written, or a top, a function of the position.
    Deferred(&'static Kind),
    /// A nested block, written once: `limits { … }`.
    Block(&'static Block),
    /// A nested block that may be written any number of times: `when { … }`.
    Blocks(&'static Block),
}

/// How many entries a [`Kind::List`] has.
#[derive(Clone, Copy, Debug)]
pub enum Len {
    /// Exactly this many.
    Exactly(usize),
    /// One per segment of the ring.
    PerSegment,
    /// Any number.
    Any,
}

/// Which numbered signal an [`Kind::Io`] field names.
#[derive(Clone, Copy, Debug)]
pub enum Io {
    /// A digital output.
    DigitalOut,
    /// An analog output.
    AnalogOut,
    /// An analog input.
    AnalogIn,
}

/// The bounds of a quantity, in canonical units. [`Bound::Any`],
/// [`Bound::Positive`] and a time's [`Bound::ZeroUpTo`] are checked by
/// the reading of a field itself (`Fields::quantity`); the others have a
/// message of their own, which the reader words (`Fields::bounded`).
#[derive(Clone, Copy, Debug)]
pub enum Bound {
    /// Any value.
    Any,
    /// Greater than zero.
    Positive,
    /// Zero or more.
    NonNegative,
    /// Less than zero.
    Negative,
    /// Greater than zero and at most this.
    PositiveUpTo(f64),
    /// Greater than zero and at most this, one message for either end.
    Within(f64),
    /// From zero to this, both included.
    ZeroUpTo(f64),
    /// At most this far either side of zero.
    Magnitude(f64),
}

/// Whether a field must be written, and what holds when it is not.
#[derive(Debug)]
pub enum Need {
    /// It must be written; the missing-field message suggests `key =
    /// example`.
    Required(&'static str),
    /// It must be written unless the second text holds (its reader decides);
    /// the first is the example.
    RequiredUnless(&'static str, &'static str),
    /// It may be left out, and then has this value.
    Default(DefaultValue),
    /// It may be left out, and then there is none (its help says what that
    /// means).
    Optional,
}

/// The value of a field that is not written.
#[derive(Debug)]
pub enum DefaultValue {
    /// A quantity, in canonical units of the field's dimension.
    Quantity(f64),
    /// A whole number.
    Count(usize),
    /// A word.
    Word(&'static str),
    /// A value that depends on others, in words.
    Described(&'static str),
}

/// The fields of a block or the arguments of a call.
#[derive(Debug)]
pub struct Block {
    /// Its name in `docs/language.md`'s markers and for lookups (`"robot"`,
    /// `"limits"`, `"circle"`): unique among [`BLOCKS`].
    pub name: &'static str,
    /// How it is written: `bead NAME { … }`, `circle(…)`.
    pub syntax: &'static str,
    /// What it is, in a line.
    pub help: &'static str,
    /// The fields it takes, in the order messages list them: values first,
    /// nested blocks last.
    pub fields: &'static [&'static Field],
    /// Fields it knows but refuses, each reported by its reader with why
    /// (a ring's process block takes no `power`: its table gives one per
    /// segment).
    pub refused: &'static [&'static Field],
    /// For a call: how many of the first fields may be given without a name,
    /// in order.
    pub positional: usize,
    /// The examples its missing-field messages show instead of the fields'
    /// own (a CNC's typical `max_speed` is not a robot's).
    pub examples: &'static [(&'static Field, &'static str)],
}

impl Block {
    /// A block of `fields`, written as `syntax`.
    pub const fn new(
        name: &'static str,
        syntax: &'static str,
        help: &'static str,
        fields: &'static [&'static Field],
    ) -> Block {
        Block {
            name,
            syntax,
            help,
            fields,
            refused: &[],
            positional: 0,
            examples: &[],
        }
    }

    /// The same block, its first `n` fields positional.
    pub const fn positional(self, n: usize) -> Block {
        Block {
            positional: n,
            ..self
        }
    }

    /// The same block, refusing `fields`.
    pub const fn refusing(self, fields: &'static [&'static Field]) -> Block {
        Block {
            refused: fields,
            ..self
        }
    }

    /// The same block, with its own missing-field examples.
    pub const fn with_examples(self, examples: &'static [(&'static Field, &'static str)]) -> Block {
        Block { examples, ..self }
    }

    /// Whether it is a call with named arguments (`circle(…)`), not a block.
    pub fn is_call(&self) -> bool {
        self.syntax.ends_with(')')
    }

    /// Every field the block accepts: those it takes, then those it refuses.
    pub fn accepted(&self) -> impl Iterator<Item = &'static Field> + '_ {
        self.fields.iter().chain(self.refused).copied()
    }

    /// The field written `key`, if the block takes it.
    pub fn field(&self, key: &str) -> Option<&'static Field> {
        self.fields.iter().copied().find(|f| f.key == key)
    }

    /// The field of this block that takes `word` as its value, a word
    /// (`spiral`) or a call (`spiral(…)`), with how it is written there:
    /// `layer_change = spiral(…)`. For a word written as a key by mistake
    /// (`spiral = true`).
    pub fn field_taking(&self, word: &str) -> Option<(&'static Field, String)> {
        self.fields.iter().copied().find_map(|f| {
            let value = match takes_word(&f.kind, word)? {
                Some(call) => call.syntax.to_string(),
                None => word.to_string(),
            };
            Some((f, format!("{} = {value}", f.key)))
        })
    }

    /// Whether `f` is one of the block's entries (taken or refused).
    pub fn owns(&self, f: &Field) -> bool {
        self.accepted().any(|g| g == f)
    }

    /// The example a missing `f` is suggested with in this block.
    pub fn example(&self, f: &Field) -> Option<&'static str> {
        self.examples
            .iter()
            .find(|(g, _)| *g == f)
            .map(|(_, e)| *e)
            .or(match f.need {
                Need::Required(e) | Need::RequiredUnless(e, _) => Some(e),
                _ => None,
            })
    }
}

/// A field is its entry: two are equal when they are the same static, so
/// a lookup by field cannot find another block's field of the same key.
impl PartialEq for Field {
    fn eq(&self, other: &Field) -> bool {
        std::ptr::eq(self, other)
    }
}

impl Eq for Field {}

impl Field {
    /// A field written `key`, taking `kind`.
    pub const fn new(key: &'static str, kind: Kind, need: Need, help: &'static str) -> Field {
        Field {
            key,
            kind,
            need,
            help,
        }
    }

    /// Whether a value of this field is read by its reader rather than
    /// evaluated with the block.
    pub fn deferred(&self) -> bool {
        matches!(self.kind, Kind::Deferred(_))
    }

    /// Whether the field may follow `layer`.
    pub fn layered(&self) -> bool {
        matches!(self.kind, Kind::Layered(_))
    }

    /// The field's value in words, with its unit and bounds: `a length (mm),
    /// > 0`.
    pub fn value_text(&self) -> String {
        self.kind.describe()
    }

    /// What holds when the field is not written: `required`, `10 mm`, `none`.
    pub fn default_text(&self) -> String {
        match &self.need {
            Need::Required(_) => "required".into(),
            Need::RequiredUnless(_, unless) => format!("required unless {unless}"),
            Need::Optional => "none".into(),
            Need::Default(d) => match d {
                DefaultValue::Quantity(v) => shown(*v, self.kind.dim().unwrap_or(Dim::NONE)),
                DefaultValue::Count(n) => n.to_string(),
                DefaultValue::Word(w) => format!("`{w}`"),
                DefaultValue::Described(s) => (*s).to_string(),
            },
        }
    }
}

impl Kind {
    /// Whether the field is a nested block.
    pub fn is_block(&self) -> bool {
        matches!(self, Kind::Block(_) | Kind::Blocks(_))
    }

    /// The dimension and bounds of a quantity, also as one choice of an
    /// [`Kind::Either`].
    pub fn quantity(&self) -> Option<(Dim, Bound)> {
        match self {
            Kind::Quantity(d, b) => Some((*d, *b)),
            Kind::Either(kinds) => kinds.iter().find_map(Kind::quantity),
            Kind::Layered(k) | Kind::Deferred(k) => k.quantity(),
            _ => None,
        }
    }

    /// The dimension of a quantity or a range.
    pub fn dim(&self) -> Option<Dim> {
        match self {
            Kind::Range(d) => Some(*d),
            Kind::List(k, _) => k.dim(),
            k => k.quantity().map(|q| q.0),
        }
    }

    /// The bounds of a whole number, also as one choice of an
    /// [`Kind::Either`].
    pub fn count(&self) -> Option<(usize, usize)> {
        match self {
            Kind::Count(lo, hi) => Some((*lo, *hi)),
            Kind::Either(kinds) => kinds.iter().find_map(Kind::count),
            _ => None,
        }
    }

    /// The calls a field of this kind takes besides its words
    /// (`coupon = track | wall(…) | pad(…)`).
    pub fn calls(&self) -> &'static [&'static Block] {
        match self {
            Kind::Call(c) => c,
            Kind::Either(kinds) => kinds
                .iter()
                .map(Kind::calls)
                .find(|c| !c.is_empty())
                .unwrap_or(&[]),
            _ => &[],
        }
    }

    /// The words a field takes, also as one choice of an [`Kind::Either`].
    pub fn words(&self) -> Option<&'static [&'static str]> {
        match self {
            Kind::Word(w) => Some(w),
            Kind::Either(kinds) => kinds.iter().find_map(Kind::words),
            _ => None,
        }
    }

    /// The value in words: `a length (mm) > 0`, `` `robot` or `cnc` ``.
    pub fn describe(&self) -> String {
        match self {
            Kind::Word(_) | Kind::Call(_) | Kind::Either(_) => {
                or_list(&choices(std::slice::from_ref(self)))
            }
            Kind::Quantity(d, b) => bounded(dim_text(*d), *b, *d),
            Kind::Range(d) => format!("a range `low .. high` of {}", plural(*d)),
            Kind::Count(lo, hi) => format!("a whole number from {lo} to {hi}"),
            Kind::Io(io) => io.describe(),
            Kind::Text => "a text in quotes".into(),
            Kind::Lines => "a text or a list of texts, each a program line".into(),
            Kind::Name(what) => format!("the name of a {what}"),
            Kind::Shape => "a shape (a section, `outline(…)`, `region(…)`, `place(…)`)".into(),
            Kind::Point => "a point `[x, y]` of lengths (mm)".into(),
            Kind::List(k, len) => {
                let what = match k {
                    Kind::Quantity(d, b) => bounded(plural(*d), *b, *d),
                    other => other.describe(),
                };
                match len {
                    Len::Exactly(n) => format!("a list of {n} {what}"),
                    Len::PerSegment => format!("a list of {what}, one per segment"),
                    Len::Any => format!("a list of {what}"),
                }
            }
            Kind::Layered(k) => format!("{}; may follow `layer`", k.describe()),
            Kind::Deferred(k) => k.describe(),
            Kind::Block(b) => format!("a block `{}`", b.syntax),
            Kind::Blocks(b) => format!("blocks `{}`, any number", b.syntax),
        }
    }
}

/// The choices of a kind, each word and call on its own: `` `auto` ``, `a
/// whole number …`.
fn choices(kinds: &[Kind]) -> Vec<String> {
    kinds
        .iter()
        .flat_map(|k| match k {
            Kind::Word(w) => w.iter().map(|w| format!("`{w}`")).collect(),
            Kind::Call(calls) => calls.iter().map(|c| format!("`{}`", c.syntax)).collect(),
            Kind::Either(inner) => choices(inner),
            other => vec![other.describe()],
        })
        .collect()
}

/// `what` with its bounds: `a length (mm) > 0`.
fn bounded(what: String, b: Bound, dim: Dim) -> String {
    let bound = b.describe(dim);
    if bound.is_empty() {
        what
    } else {
        format!("{what} {bound}")
    }
}

/// A dimension in words, with its unit: `a length (mm)`.
fn dim_text(d: Dim) -> String {
    if d == crate::control::SpeedPerLength::DIM {
        "a speed per length of height error (mm/s/mm)".into()
    } else {
        d.describe()
    }
}

impl Bound {
    /// The bounds in words, in the unit `dim` is written in (empty for
    /// [`Bound::Any`]).
    pub fn describe(self, dim: Dim) -> String {
        let s = |v: f64| shown(v, dim);
        match self {
            Bound::Any => String::new(),
            Bound::Positive => "> 0".into(),
            Bound::NonNegative => "≥ 0".into(),
            Bound::Negative => "< 0".into(),
            Bound::PositiveUpTo(hi) | Bound::Within(hi) => format!("> 0 and ≤ {}", s(hi)),
            Bound::ZeroUpTo(hi) => format!("from 0 to {}", s(hi)),
            Bound::Magnitude(hi) => format!("from −{} to {}", s(hi), s(hi)),
        }
    }
}

impl Io {
    /// The signal and the numbers each control gives it.
    pub fn describe(self) -> String {
        use crate::target::outputs::{KUKA, LINUXCNC, OTHER_CNC};
        use crate::target::{gcode, kuka};
        let range = |(lo, hi): (usize, usize)| format!("{lo}–{hi}");
        match self {
            Io::DigitalOut => format!(
                "a digital output: a robot's {}, LinuxCNC's {}, another CNC's {}",
                range(KUKA.digital),
                range(LINUXCNC.digital),
                range(OTHER_CNC.digital)
            ),
            Io::AnalogOut => format!(
                "an analog output: a robot's {}, LinuxCNC's {}, another CNC's {}",
                range(KUKA.analog),
                range(LINUXCNC.analog),
                range(OTHER_CNC.analog)
            ),
            Io::AnalogIn => format!(
                "an analog input: a robot's {}, a CNC's {}",
                range((1, kuka::MAX_ANIN)),
                range((0, gcode::MAX_ANALOG_INPUT))
            ),
        }
    }
}

/// A dimension's values, for a range or a list: `lengths (mm)`.
fn plural(d: Dim) -> String {
    let one = dim_text(d);
    let one = one
        .strip_prefix("a ")
        .or_else(|| one.strip_prefix("an "))
        .unwrap_or(&one);
    let (noun, unit) = match one.split_once(" (") {
        Some((noun, unit)) => (noun, format!(" ({unit}")),
        None => (one, String::new()),
    };
    // `moment of inertia`: the head noun takes the plural.
    match noun.split_once(" of ") {
        Some((head, of)) => format!("{head}s of {of}{unit}"),
        None => format!("{noun}s{unit}"),
    }
}

/// `a, b or c` (`a, or b` when a choice has an "or" of its own).
fn or_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => {
            let or = if items.iter().any(|i| i.contains(" or ")) {
                ", or"
            } else {
                " or"
            };
            format!("{}{or} {last}", rest.join(", "))
        }
    }
}

/// Every block and call, in the order `docs/language.md` shows them.
pub static BLOCKS: &[&Block] = &[
    &bead::BEAD,
    &bead::LINEAR,
    &bead::MASS_BALANCE,
    &bead::MEASURED,
    &bead::POWER,
    &bead::TABLE,
    &bead::FIT,
    &bead::LAYER,
    &solid::LOFT,
    &solid::LINE,
    &solid::ARC,
    &solid::EXTRUDE,
    &solid::MESH,
    &solid::SCAN,
    &solid::SCAN_SECTION,
    &solid::EDGES,
    &solid::PLANE,
    &wall::WALL,
    &wall::POLYLINE,
    &wall::ARC,
    &wall::CHAIN,
    &wall::LEAD,
    &shape::CIRCLE,
    &shape::ELLIPSE,
    &shape::SQUARE,
    &shape::RECTANGLE,
    &shape::ROUNDED_RECTANGLE,
    &shape::POLYGON,
    &shape::ARC,
    &shape::REGION,
    &shape::PLACE,
    &shape::BOLT_CIRCLE,
    &slicing::NORMAL,
    &slicing::PLANAR,
    &slicing::RASTER,
    &slicing::ROTATING,
    &slicing::RANDOM,
    &slicing::STAGGERED,
    &slicing::SPIRAL,
    &slicing::VARIABLE,
    &slicing::SEGMENTS,
    &slicing::CONTINUOUS,
    &solid::RING,
    &solid::TABLE,
    &control::CONTROL,
    &control::INVERSE_SPEED,
    &process::PROCESS,
    &process::RING_PROCESS,
    &process::RAMP,
    &process::THERMAL,
    &style::STYLE,
    &style::WHEN,
    &style::INHERITANCE,
    &machine::ROBOT,
    &machine::FRAME,
    &machine::LOAD_DATA,
    &machine::CNC,
    &machine::LIMITS,
    &machine::GAS,
    &machine::POWDER,
    &machine::POSITIONER,
    &machine::CONE,
    &machine::FIXED,
    &collision::HEAD,
    &collision::FRUSTUM,
    &collision::CYLINDER,
    &collision::FIXTURE,
    &collision::BOX,
    &calibration::CALIBRATION,
    &calibration::WALL,
    &calibration::PAD,
];

/// Whether a value of `kind` may be the call `word(…)` (`Some(Some(call))`,
/// which wins) or the word `word` (`Some(None)`).
fn takes_word(kind: &Kind, word: &str) -> Option<Option<&'static Block>> {
    match kind {
        Kind::Call(bs) => bs.iter().copied().find(|b| b.name == word).map(Some),
        Kind::Word(ws) => ws.contains(&word).then_some(None),
        Kind::Either(ks) => {
            let all: Vec<_> = ks.iter().filter_map(|k| takes_word(k, word)).collect();
            all.iter()
                .copied()
                .find(Option::is_some)
                .or(all.first().copied())
        }
        Kind::Layered(k) | Kind::Deferred(k) | Kind::List(k, _) => takes_word(k, word),
        _ => None,
    }
}

/// Where a top-level word that starts no statement is a value: the
/// statement and field that take it (`mesh` → `extrude NAME { profile =
/// mesh(…) }`), as that statement's syntax and the field written.
pub fn statement_taking(word: &str) -> Option<(&'static str, String)> {
    BLOCKS
        .iter()
        .filter(|b| !b.is_call() && b.syntax.ends_with('}'))
        .find_map(|b| b.field_taking(word).map(|(_, written)| (b.syntax, written)))
}

/// The block or call named `name` in [`BLOCKS`].
pub fn block(name: &str) -> Option<&'static Block> {
    BLOCKS.iter().copied().find(|b| b.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fields any of `blocks` accepts, each key once: values first, nested
    /// blocks last, each in the order of the first block that has it. What a
    /// block whose kind is unknown or wrong is checked against (a machine without
    /// `kind`, `slicing` without a strategy), so a misspelt field shows in the
    /// same run.
    fn union(blocks: &[&'static Block]) -> Vec<&'static Field> {
        let mut out: Vec<&'static Field> = Vec::new();
        for nested in [false, true] {
            for f in blocks.iter().flat_map(|b| b.accepted()) {
                if f.kind.is_block() == nested && !out.iter().any(|g| g.key == f.key) {
                    out.push(f);
                }
            }
        }
        out
    }

    #[test]
    fn the_blocks_of_an_unknown_kind_take_what_any_kind_takes() {
        for (any, kinds) in [
            (&machine::MACHINE, &[&machine::ROBOT, &machine::CNC][..]),
            (&slicing::ANY, slicing::STRATEGIES),
        ] {
            let want: Vec<_> = union(kinds).iter().map(|f| f.key).collect();
            let mut got: Vec<_> = any.fields.iter().map(|f| f.key).collect();
            let mut sorted = want.clone();
            sorted.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, sorted, "{}", any.name);
        }
        // Slicing's list is the union's order, values first.
        let keys: Vec<_> = slicing::ANY.fields.iter().map(|f| f.key).collect();
        let want: Vec<_> = union(slicing::STRATEGIES).iter().map(|f| f.key).collect();
        assert_eq!(keys, want);
    }

    #[test]
    fn names_and_keys_are_unique() {
        for (i, b) in BLOCKS.iter().enumerate() {
            assert!(
                BLOCKS[..i].iter().all(|o| o.name != b.name),
                "{} twice",
                b.name
            );
            let keys: Vec<_> = b.accepted().map(|f| f.key).collect();
            for (j, k) in keys.iter().enumerate() {
                assert!(!keys[..j].contains(k), "{}: `{k}` twice", b.name);
            }
            // Values first, nested blocks last: the order messages list them.
            let first_block = b.fields.iter().position(|f| f.kind.is_block());
            if let Some(n) = first_block {
                assert!(
                    b.fields[n..].iter().all(|f| f.kind.is_block()),
                    "{}",
                    b.name
                );
            }
            assert!(b.positional <= b.fields.len());
        }
    }

    #[test]
    fn a_default_is_of_its_fields_kind() {
        for b in BLOCKS {
            for f in b.accepted() {
                match &f.need {
                    Need::Default(DefaultValue::Quantity(_)) => {
                        assert!(f.kind.quantity().is_some(), "{}.{}", b.name, f.key)
                    }
                    Need::Default(DefaultValue::Count(n)) => {
                        let (lo, hi) = f.kind.count().expect("a count");
                        assert!((lo..=hi).contains(n), "{}.{}", b.name, f.key)
                    }
                    Need::Default(DefaultValue::Word(w)) => {
                        let words = f.kind.words().expect("words");
                        assert!(words.contains(w), "{}.{}", b.name, f.key)
                    }
                    _ => {}
                }
            }
        }
    }
}

//! What the checker says about values: numbers and their units, operators,
//! constants and the names a value refers to.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Dim};

/// What a value is, as a message says it ("this is a length (mm)"): its
/// kind, and the word itself when it is a bare name, for "did you mean" and
/// "declare it with `let`". The checker makes one from each value it refuses
/// (`sema::value::Value::got`), so a message needs no type of the checker's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Got<'a> {
    /// A number of this dimension.
    Quantity(Dim),
    /// A range of numbers of this dimension.
    Range(Dim),
    /// A bare name that is not a constant.
    Name(&'a str),
    /// A text in quotes.
    Text,
    /// A call of the named function.
    Call(&'a str),
    /// A list.
    List,
}

impl Got<'_> {
    /// The value in words: "a length (mm)", "the name `auto`", "a list".
    pub fn describe(&self) -> String {
        match self {
            Got::Quantity(dim) => dim.describe(),
            Got::Range(dim) => format!("a range of {}", plural(&dim.describe())),
            Got::Name(s) => format!("the name `{s}`"),
            Got::Text => "a text".into(),
            Got::Call(func) => format!("`{func}(…)`"),
            Got::List => "a list".into(),
        }
    }
}

/// The plural of a kind of value ("a length (mm)" → "lengths (mm)").
fn plural(d: &str) -> String {
    let d = d
        .trim_start_matches("a ")
        .trim_start_matches("an ")
        .to_string();
    match d.find(" (") {
        Some(i) => format!("{}s{}", &d[..i], &d[i..]),
        None => format!("{d}s"),
    }
}

/// A constant is used while it is being computed (`let a = b`, `let b = a`).
pub fn cycle(name: &str, at: Span, decl: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Cycle,
        format!("the constant `{name}` is defined in terms of itself"),
    )
    .label(at, "used here while it is being computed")
    .label(decl, "defined here")
    .help("break the cycle: give one of the constants a value that does not use the others")
}

/// A chain of constants, each using the next, is longer than lmdc evaluates.
pub fn chain_too_long(name: &str, max: usize, at: Span, decl: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConstantChain,
        format!(
            "computing this needs a chain of more than {max} constants, each using the next"
        ),
    )
    .label(
        at,
        format!("`{name}` is constant number {} of the chain", max + 1),
    )
    .label(decl, "declared here")
    .help("compute the value in fewer steps, e.g. `let a100 = a0 + 100 * 1 mm` instead of a hundred `let`s that each add 1 mm")
}

/// An evaluation nests deeper than lmdc evaluates.
pub fn too_deep(max: usize, span: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ConstantChain,
        format!(
            "computing this value nests more than {max} steps of constants and operators"
        ),
    )
    .label(span, "the limit is reached here")
    .help("compute the value in fewer steps: fewer constants that each use the next, shorter chains of operators")
}

/// A number is written with a unit lmdc does not know.
/// `meant` is the unit as written with the unknown part replaced by the one
/// most likely meant (`1.5 KW` → `kW`), if there is one.
pub fn unknown_unit(unit: &str, meant: Option<&str>, at: Span) -> Diagnostic {
    const UNITS: &str = "units: mm cm m um in, deg rad, s ms min h, g mg kg, W kW, J, Hz, %; combine with / * and ^, e.g. g/min or g/cm^3";
    Diagnostic::error(
        Code::UnknownUnit,
        format!("`{unit}` is not a unit lmdc knows"),
    )
    .label(at, "unknown unit")
    .help(match meant {
        Some(m) => format!("did you mean `{m}`? ({UNITS})"),
        None => UNITS.to_string(),
    })
}

/// A minus sign stands before something that is not a number.
pub fn cannot_negate(other: Got<'_>, span: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedNumber,
        format!("cannot negate {}", other.describe()),
    )
    .label(span, "this is not a number")
}

/// A computed number is infinite or not a number.
pub fn not_finite(span: Span) -> Diagnostic {
    Diagnostic::error(Code::Overflow, "this number is too large to compute with")
        .label(span, "not a finite number")
        .help("check the value and its unit")
}

/// An operator (`op`, as written) has something other than a number on one
/// side (`bad`).
pub fn operand_not_number(op: &str, bad: Got<'_>, at: Span) -> Diagnostic {
    let d = Diagnostic::error(
        Code::ExpectedNumber,
        format!("`{op}` needs numbers on both sides"),
    )
    .label(at, format!("this is {}", bad.describe()));
    match bad {
        Got::Name(s) => d.help(match crate::units::unit_meant(s) {
            // `6 mm/sec`: a unit lmdc knows by another name.
            Some(u) => format!(
                "`{s}` is not a unit lmdc knows: write `{u}`; a constant would be declared with `let {s} = …`"
            ),
            None => format!("`{s}` is not a constant; declare it with `let {s} = …`"),
        }),
        _ => d,
    }
}

/// The operands of `+`, `-` or `..` (`op`, as written) have different
/// dimensions.
pub fn operand_units_differ(op: &str, l: (Dim, Span), r: (Dim, Span)) -> Diagnostic {
    let what = match op {
        ".." => "the ends of a range",
        "+" => "added values",
        _ => "subtracted values",
    };
    Diagnostic::error(
        Code::UnitMismatch,
        format!(
            "{what} must have the same unit: {} and {}",
            l.0.describe(),
            r.0.describe()
        ),
    )
    .label(l.1, l.0.describe())
    .label(r.1, r.0.describe())
    .help("give both operands the same kind of unit, e.g. `60 mm + 2 mm` or `45 deg + 5 deg`")
}

/// A range's lower end is above its upper end.
pub fn empty_range(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::EmptyRange,
        "the range's lower end is above its upper end",
    )
    .label(at, "write the smaller value first")
    .help("ranges are written `low .. high`, e.g. `7 mm/s .. 10 mm/s`")
}

/// A value is divided by zero.
pub fn division_by_zero(at: Span) -> Diagnostic {
    Diagnostic::error(Code::DivisionByZero, "division by zero").label(at, "this is zero")
}

/// An exponent is not a plain whole number within ±16.
pub fn bad_exponent(n: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadExponent,
        format!(
            "exponent {} is not a whole number between -16 and 16",
            short(n)
        ),
    )
    .label(at, "exponent")
    .help("write powers with whole-number exponents such as `^2` or `^-1`")
}

/// `min` or `max` is given a named argument or one that is not a number.
pub fn min_max_not_number(func: &str, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedNumber,
        format!("`{func}` takes numbers, without names"),
    )
    .label(at, format!("this is {}", got.describe()))
    .help(format!("e.g. `{func}(layer + 2, 10)`"))
}

/// A math function is given the wrong number of values, or named ones.
pub fn math_arity(func: &str, n: usize, at: Span) -> Diagnostic {
    let example = match func {
        "sin" | "cos" | "tan" => "30 deg",
        "asin" | "acos" => "0.5",
        "abs" => "-3 mm",
        _ => "2",
    };
    let (what, e) = if n == 2 {
        (
            "two values, without names",
            "`atan2(3 mm, 4 mm)`".to_string(),
        )
    } else {
        ("one value, without a name", format!("`{func}({example})`"))
    };
    Diagnostic::error(Code::Argument, format!("`{func}` takes {what}"))
        .label(at, "here")
        .help(format!("e.g. {e}"))
}

/// A math function is given something that is not a number.
pub fn math_not_number(func: &str, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(Code::ExpectedNumber, format!("`{func}` takes numbers"))
        .label(at, format!("this is {}", got.describe()))
}

/// A math function is given a value of the wrong kind (`sin(30)`).
pub fn math_unit(func: &str, want: Dim, got: Dim, at: Span) -> Diagnostic {
    let help = if want == Dim::ANGLE {
        format!("`{func}` takes an angle: write its unit, e.g. `{func}(30 deg)`")
    } else {
        format!("`{func}` takes a plain number, e.g. `{func}(0.5)` or a ratio `{func}(3 mm / 6 mm)`, and gives an angle")
    };
    Diagnostic::error(
        Code::UnitMismatch,
        format!("`{func}` takes {}, not {}", want.describe(), got.describe()),
    )
    .label(at, format!("this is {}", got.describe()))
    .help(help)
}

/// `sqrt` of a value whose unit has an odd power (`sqrt(4 mm)`).
pub fn math_sqrt_unit(got: Dim, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::UnitMismatch,
        format!(
            "`sqrt` of {} has no unit: its powers are not all even",
            got.describe()
        ),
    )
    .label(at, "this value")
    .help("take the root of an area (`sqrt(9 mm^2)` is `3 mm`) or of a plain number")
}

/// A math function's value lies outside its domain (`asin(2)`).
pub fn math_domain(func: &str, what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Domain,
        format!("`{func}` of {what} has no real value"),
    )
    .label(at, "this value")
}

/// `asin` or `acos` of `v`, outside −1 .. 1.
pub fn math_outside_one(func: &str, v: f64, at: Span) -> Diagnostic {
    math_domain(func, &format!("{} (outside -1 .. 1)", short(v)), at)
        .help("a sine or cosine lies between -1 and 1: is it a ratio of the right lengths?")
}

/// `min` or `max` is given values of different dimensions.
pub fn min_max_units_differ(func: &str, first: Dim, this: Dim, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::UnitMismatch,
        format!(
            "`{func}` compares values of one kind: {} and {}",
            first.describe(),
            this.describe()
        ),
    )
    .label(at, this.describe())
    .help("give every argument the same kind of unit")
}

/// `min` or `max` is given no value.
pub fn min_max_empty(func: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Argument, format!("`{func}` needs at least one value"))
        .label(at, "nothing to compare")
}

/// `x` or `y` is used as a number outside an extrusion's `top`.
pub fn position_outside_top(name: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::PositionOutsideTop,
        format!("`{name}` is a point's position only inside an extrusion's `top`"),
    )
    .label(at, "not a number here")
    .help(format!(
        "write the expression in the extrusion itself, e.g. `top = 20 mm + 16 % * {name}`; elsewhere give a number with a unit"
    ))
}

/// A name refers to no declared `what` (`suggestion` is a close one, if any;
/// `candidates` are all of them).
pub fn unknown_name(
    name: &str,
    span: Span,
    what: &str,
    suggestion: Option<&str>,
    candidates: &[&str],
) -> Diagnostic {
    let d = Diagnostic::error(
        Code::UnknownName,
        format!("there is no {what} called `{name}`"),
    )
    .label(span, "not declared");
    match suggestion {
        Some(s) => d.help(format!("did you mean `{s}`?")),
        None if candidates.is_empty() => d.help(format!("declare the {what} first")),
        None => d.help(format!("known: {}", candidates.join(", "))),
    }
}

/// Whether `d` is one of the arithmetic failures evaluation reports (a
/// division by zero, a number too large, a bad exponent): what fails at one
/// point of a function of the position.
pub fn is_arithmetic_failure(d: &Diagnostic) -> bool {
    matches!(
        d.code,
        Code::DivisionByZero | Code::Overflow | Code::BadExponent | Code::Domain
    )
}

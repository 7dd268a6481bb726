//! What the checker says when reading the fields of a block or the arguments
//! of a call: unknown, duplicate, missing, of the wrong kind or out of range.

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{short, Dim};

/// A block has no field named `key` (`suggestion` is a close field name, if any).
pub fn unknown_field(
    what: &str,
    key: &str,
    at: Span,
    suggestion: Option<&str>,
    fields: &[&str],
) -> Diagnostic {
    let d = Diagnostic::error(Code::UnknownField, format!("{what} has no field `{key}`"))
        .label(at, "unknown field");
    match suggestion {
        Some(m) => d.help(format!("did you mean `{m}`?")),
        None => d.help(format!("fields of {what}: {}", fields.join(", "))),
    }
}

/// A field is written twice in one block.
pub fn duplicate_field(key: &str, what: &str, at: Span, prev: Span) -> Diagnostic {
    Diagnostic::error(
        Code::DuplicateField,
        format!("`{key}` is given twice in {what}"),
    )
    .label(at, "second time")
    .label(prev, "first time")
    .help("keep one of them")
}

/// A field's key is followed by a name (`width w = …`).
pub fn name_after_key(name: &str, key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("unexpected `{name}` after `{key}`"))
        .label(at, "not expected here")
        .help(format!("write `{key} = value`"))
}

/// A field other than a profile reads `layer` or `layer_z`.
pub fn layer_outside_profile(key: &str, what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LayerOutsideProfile,
        format!("`{key}` uses `layer` or `layer_z`, which only a profile follows"),
    )
    .label(at, "depends on the layer")
    .help(if key == "power" {
        "schedule power over layers with `ramp(from = …, to = …, layers = …)`".to_string()
    } else {
        format!("give {what} a value that does not change with the layer")
    })
}

/// A field that takes a block is given something else.
pub fn needs_block(key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("`{key}` takes a block"))
        .label(at, "expected `{ … }`")
        .help(format!("write `{key} {{ … }}`"))
}

/// A field that takes a value is given a block or nothing.
pub fn needs_value(key: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::Syntax, format!("`{key}` needs a value"))
        .label(at, "expected `= value`")
        .help(format!("write `{key} = value`"))
}

/// A call has more unnamed arguments than positional parameters.
pub fn too_many_unnamed(what: &str, at: Span, allowed: &[&str]) -> Diagnostic {
    Diagnostic::error(
        Code::Argument,
        format!("too many unnamed arguments for {what}"),
    )
    .label(at, "name this argument")
    .help(format!("arguments of {what}: {}", allowed.join(", ")))
}

/// A call has no argument named `key` (`suggestion` is a close name, if any).
pub fn unknown_argument(
    what: &str,
    key: &str,
    at: Span,
    suggestion: Option<&str>,
    allowed: &[&str],
) -> Diagnostic {
    let d = Diagnostic::error(Code::Argument, format!("{what} has no argument `{key}`"))
        .label(at, "unknown argument");
    match suggestion {
        Some(m) => d.help(format!("did you mean `{m}`?")),
        None => d.help(format!("arguments of {what}: {}", allowed.join(", "))),
    }
}

/// An argument is given twice to one call.
pub fn duplicate_argument(key: &str, what: &str, at: Span, prev: Span) -> Diagnostic {
    Diagnostic::error(
        Code::DuplicateField,
        format!("`{key}` is given twice to {what}"),
    )
    .label(at, "second time")
    .label(prev, "first time")
}

/// A required field is not written (`example` is a value to suggest).
pub fn missing_field(what: &str, key: &str, at: Span, example: &str) -> Diagnostic {
    Diagnostic::error(Code::MissingField, format!("{what} needs `{key}`"))
        .label(at, format!("`{key}` is missing"))
        .help(format!("add `{key} = {example}`"))
}

/// A field that must be positive is zero, negative or not finite (`shown`
/// is its value as written for the user).
pub fn not_positive(key: &str, shown: &str, what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NotPositive,
        format!("`{key}` must be greater than zero"),
    )
    .label(at, format!("this is {shown}"))
    .help(format!("give {what} a positive value"))
}

/// A field that takes a range is given something else.
pub fn expected_range(key: &str, dim: Dim, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedRange,
        format!("`{key}` must be a range of {}", dim.describe()),
    )
    .label(at, format!("this is {}", got.describe()))
    .help("write a range as `low .. high`, e.g. `7 mm/s .. 10 mm/s`")
}

/// A field that takes a text is given something else.
pub fn expected_text(key: &str, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedText,
        format!("`{key}` must be a text in quotes"),
    )
    .label(at, format!("this is {}", got.describe()))
    .help(format!("write `{key} = \"…\"`"))
}

/// A length or speed is beyond the plausibility bound `bound` (`shown` is
/// the value as written for the user).
pub fn too_large(key: &str, bound: &str, shown: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooLarge,
        format!("`{key}` is beyond what lmdc plans ({bound})"),
    )
    .label(at, format!("this is {shown}"))
    .help("check the value and its unit")
}

/// A field that takes a quantity of `dim` is given something that is not a number.
pub fn expected_number(key: &str, dim: Dim, got: Got<'_>, at: Span) -> Diagnostic {
    let d = Diagnostic::error(
        Code::ExpectedNumber,
        format!("`{key}` must be {}", dim.describe()),
    )
    .label(at, format!("this is {}", got.describe()));
    match got {
        Got::Name(s) => d.help(format!(
            "`{s}` is not a constant; declare it with `let {s} = …` or write a number with a unit"
        )),
        _ => d,
    }
}

/// A quantity has dimension `got` where `want` is expected.
pub fn wrong_unit(span: Span, key: &str, want: Dim, got: Dim) -> Diagnostic {
    let help = if got == Dim::NONE {
        format!("add a unit: `{key}` is {}", want.describe())
    } else {
        format!("`{key}` is {}; check the unit", want.describe())
    };
    Diagnostic::error(
        Code::UnitMismatch,
        format!(
            "`{key}` must be {}, not {}",
            want.describe(),
            got.describe()
        ),
    )
    .label(span, got.describe())
    .help(help)
}

/// A whole number lies outside `lo..=hi`.
pub fn count_range(key: &str, lo: usize, hi: usize, value: f64, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::CountRange,
        format!("`{key}` must be between {lo} and {hi}"),
    )
    .label(at, format!("this is {}", short(value)))
}

/// A field that takes a whole number is given something else.
pub fn expected_whole_number(key: &str, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedWholeNumber,
        format!("`{key}` must be a whole number"),
    )
    .label(at, format!("this is {}", got.describe()))
}

/// A field that takes one of `choices` is given something else
/// (`suggestion` is a close choice, if any).
pub fn bad_choice(
    key: &str,
    choices: &[&str],
    got: Got<'_>,
    at: Span,
    suggestion: Option<&str>,
) -> Diagnostic {
    let d = Diagnostic::error(
        Code::BadChoice,
        format!("`{key}` must be one of: {}", choices.join(", ")),
    )
    .label(at, format!("this is {}", got.describe()));
    match suggestion {
        Some(m) => d.help(format!("did you mean `{m}`?")),
        None => d,
    }
}

/// The time `key` is `t` s, outside 0 to `max` s: negative, or longer than
/// lmdc allows. The help says what the field is, with an example.
pub fn time_out_of_range(key: &str, t: f64, max: f64, at: Span) -> Diagnostic {
    let (code, message) = if t < 0.0 {
        (
            Code::NotPositive,
            format!("`{key}` is {} s: a time cannot be negative", short(t)),
        )
    } else {
        (
            Code::OutOfRange,
            format!(
                "`{key}` is {} s, more than the {} s lmdc allows",
                short(t),
                short(max)
            ),
        )
    };
    let help = match key {
        "min_layer_time" => "the time a layer must take to cool, e.g. `min_layer_time = 30 s`".to_string(),
        "dwell" => "the wait between layers, e.g. `dwell = 5 s`".to_string(),
        "height_delay" => "how long after a segment's end the sensor holds its mean height, e.g. `height_delay = 150 ms`".to_string(),
        _ => format!("give `{key}` in seconds as the cell needs it, e.g. `{key} = 2 s`"),
    };
    Diagnostic::error(code, message)
        .label(at, format!("a time from 0 to {} s", short(max)))
        .help(help)
}

//! What the checker says about a file's statements as such — unknown,
//! missing, repeated or misshapen ones — about the names they declare, and
//! about the texts written verbatim into a program.

use crate::diag::{Code, Diagnostic};
use crate::span::Span;

/// A statement starts with a word that starts no statement (`suggestion` is
/// a close kind, if any).
pub fn unknown_statement(
    kind: &str,
    at: Span,
    suggestion: Option<&str>,
    kinds: &[&str],
) -> Diagnostic {
    let d = Diagnostic::error(
        Code::UnknownStatement,
        format!("`{kind}` does not start a statement"),
    )
    .label(at, "unknown");
    match suggestion {
        Some(m) => d.help(format!("did you mean `{m}`?")),
        None => d.help(format!("a file is made of: {}", kinds.join(", "))),
    }
}

/// A top-level word that is a value of a field of the statement written
/// `syntax` (`mesh` in `extrude NAME { profile = mesh(…) }`).
pub fn value_as_statement(kind: &str, at: Span, syntax: &str, written: &str) -> Diagnostic {
    Diagnostic::error(
        Code::UnknownStatement,
        format!("`{kind}` does not start a statement: it is a value"),
    )
    .label(at, "a value, not a statement")
    .help(format!("write it as `{written}` in `{syntax}`"))
}

/// A file lacks a statement it needs (`example` shows one).
pub fn missing_statement(kind: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::MissingStatement,
        format!("the file has no `{kind}` statement"),
    )
    .label(Span::new(0, 0), format!("`{kind}` is missing"))
    .help(format!("add `{example}`"))
}

/// A statement that may appear once appears again.
pub fn duplicate_statement(kind: &str, at: Span, first: Span) -> Diagnostic {
    Diagnostic::error(Code::DuplicateStatement, format!("`{kind}` is given twice"))
        .label(at, "second time")
        .label(first, "first time")
        .help("keep one of them")
}

/// A statement of `kind` is not written in the shape its kind takes.
pub fn statement_shape(kind: &str, at: Span, shape: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Syntax,
        format!("a `{kind}` statement is written `{shape}`"),
    )
    .label(at, "not in that shape")
    .help(format!("e.g. `{example}`"))
}

/// What is declared twice, for [`duplicate_name`].
#[derive(Clone, Copy, Debug)]
pub enum Declaration {
    /// A constant (`let`).
    Constant,
    /// A section.
    Section,
    /// A profile.
    Profile,
    /// A bead model.
    Bead,
    /// A style.
    Style,
}

/// A name is declared twice.
pub fn duplicate_name(name: &str, what: Declaration, at: Span, prev: Span) -> Diagnostic {
    let kind = match what {
        Declaration::Constant | Declaration::Profile => "",
        Declaration::Section => "section ",
        Declaration::Bead => "bead ",
        Declaration::Style => "style ",
    };
    let d = Diagnostic::error(
        Code::DuplicateName,
        format!("{kind}`{name}` is declared twice"),
    )
    .label(at, "second declaration")
    .label(prev, "first declaration");
    match what {
        Declaration::Constant => d.help("rename one of them"),
        _ => d,
    }
}

/// A section's value reads `layer` or `layer_z`.
pub fn section_follows_layer(name: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::LayerOutsideProfile,
        format!("section `{name}` uses `layer` or `layer_z`, which only a profile follows"),
    )
    .label(at, "depends on the layer")
    .help(format!(
        "declare it as `profile {name} = …` to let it change from layer to layer"
    ))
}

/// A section's value is not a shape (`got` describes it).
pub fn section_not_shape(name: &str, got: &str, at: Span, shapes: &[&str]) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedShape,
        format!("section `{name}` must be a shape"),
    )
    .label(at, format!("this is {got}"))
    .help(format!("shapes: {}", shapes.join(", ")))
}

/// A text written into the program holds the character `c` at (1-based)
/// character `position`, which is not printable ASCII.
pub fn program_text_character(key: &str, c: char, position: usize, at: Span) -> Diagnostic {
    let what = match c {
        '\r' => "a carriage return (a line end to the control)".to_string(),
        '\t' => "a tab".to_string(),
        c if c.is_control() => format!("the control character U+{:04X}", c as u32),
        c => format!("`{c}`, which is not ASCII"),
    };
    Diagnostic::error(
        Code::ProgramText,
        format!("`{key}` holds {what} at character {position}"),
    )
    .label(at, "written into the program as it is")
    .help(format!(
        "`{key}` must be one line of printable ASCII; give several lines as a list, \
         e.g. `preamble = [\"G21 G90\", \"G94\"]`"
    ))
}

/// A text written into the program is longer than `max` characters.
pub fn program_text_too_long(key: &str, len: usize, max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ProgramText,
        format!("`{key}` is {len} characters long"),
    )
    .label(at, "one program line")
    .help(format!(
        "controls read lines of limited length (LinuxCNC: 255); keep it under {max}"
    ))
}

/// A laser switch line (`laser_on` or `laser_off`) is empty.
pub fn empty_switch(key: &str, at: Span) -> Diagnostic {
    let does = if key == "laser_on" { "on" } else { "off" };
    Diagnostic::error(Code::ProgramText, format!("`{key}` is empty"))
        .label(
            at,
            format!("the program would never switch the laser {does}"),
        )
        .help(format!(
            "give the control's laser-{does} command, e.g. `{key} = \"{}\"`",
            if does == "on" { "M3" } else { "M5" }
        ))
}

/// A dwell line does not hold `{s}` exactly once.
pub fn dwell_without_seconds(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ProgramText,
        "`dwell` must hold `{s}` once, where the seconds go",
    )
    .label(at, "dwell line")
    .help("e.g. `dwell = \"G4 P{s}\"` (LinuxCNC: P in seconds)")
}

/// A `control` block in a file that builds no ring.
pub fn control_without_ring(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Unsupported,
        "a height loop corrects each segment of a ring; this file builds no ring",
    )
    .label(at, "control")
    .help("remove `control`, or build a `ring NAME { … }` with `slicing continuous { … }`")
}

/// An `allow` statement whose code is no code of lmdc's; `suggestion` is
/// the nearest one.
pub fn allow_unknown_code(code: &str, at: Span, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(Code::Allow, format!("`{code}` is no code of lmdc's"))
        .label(at, "no such code");
    match suggestion {
        Some(m) => d.help(format!(
            "did you mean `{m}`? docs/diagnostics.md lists every code"
        )),
        None => d.help("docs/diagnostics.md lists every code; a warning's report names its own"),
    }
}

/// An `allow` statement that names an error's code: only a warning can be
/// expected; `also` are the codes outside the Warnings group that warn.
pub fn allow_error_code(code: &str, also: &[Code], at: Span) -> Diagnostic {
    let also: Vec<String> = also.iter().map(|c| format!("`{}`", c.as_str())).collect();
    Diagnostic::error(
        Code::Allow,
        format!("`{code}` stops the build; only a warning can be allowed"),
    )
    .label(at, "not a warning")
    .help(format!(
        "fix what the error says; `allow` takes the code of a warning: those of docs/diagnostics.md's Warnings, and {}",
        also.join(", ")
    ))
}

/// An `allow` statement not written `allow "lmd::CODE" = "why"`, or with an
/// empty reason.
pub fn allow_shape(at: Span, what: &str) -> Diagnostic {
    Diagnostic::error(Code::Allow, format!("an `allow` needs {what}"))
        .label(at, "here")
        .help(
            "write `allow \"lmd::height-rounded\" = \"why this warning is expected\"`: \
             the code its report names, and the reason, which every report of it then shows",
        )
}

//! The statements of a file, grouped by kind, and what holds for a statement
//! whatever its kind: its shape (`kind NAME { … }`, `kind NAME = value`) and
//! how often it may appear.

use crate::diag::{message, Diagnostic, Diagnostics};
use crate::sema::suggest;
use crate::syntax::ast::{Body, File, Stmt};
use std::collections::BTreeMap;

/// Top-level statement kinds.
pub const KINDS: &[&str] = &[
    "part",
    "let",
    "section",
    "profile",
    "bead",
    "loft",
    "extrude",
    "ring",
    "wall",
    "slicing",
    "control",
    "process",
    "style",
    "inheritance",
    "machine",
    "fixture",
    "calibration",
    "allow",
];

/// A file's statements by kind, each kind in source order.
pub struct Statements<'f> {
    by_kind: BTreeMap<&'f str, Vec<&'f Stmt>>,
}

impl<'f> Statements<'f> {
    /// Groups the statements of `file`, reporting those that start with a
    /// word that is no statement.
    pub fn group(file: &'f File, diags: &mut Diagnostics) -> Self {
        let mut by_kind: BTreeMap<&str, Vec<&Stmt>> = BTreeMap::new();
        for s in &file.stmts {
            let k = s.kind.node.as_str();
            if !KINDS.contains(&k) {
                let d = match crate::sema::schema::statement_taking(k) {
                    // A value written as a statement (`mesh "part.stl"`).
                    Some((syntax, written)) => {
                        message::statement::value_as_statement(k, s.kind.span, syntax, &written)
                    }
                    None => message::statement::unknown_statement(
                        k,
                        s.kind.span,
                        suggest::did_you_mean(k, KINDS.iter().copied()),
                        KINDS,
                    ),
                };
                diags.push(d);
                continue;
            }
            by_kind.entry(k).or_default().push(s);
        }
        Statements { by_kind }
    }

    /// The statements of one kind, in source order.
    pub fn get(&self, kind: &str) -> &[&'f Stmt] {
        self.by_kind.get(kind).map_or(&[], Vec::as_slice)
    }
}

/// The one statement of `kind` a file needs: a missing one is reported (the
/// help shows `example`), and so is each one after the first.
pub fn single<'s>(
    stmts: &[&'s Stmt],
    kind: &str,
    example: &str,
    diags: &mut Diagnostics,
) -> Option<&'s Stmt> {
    if stmts.is_empty() {
        diags.push(message::statement::missing_statement(kind, example));
    }
    single_optional(stmts, kind, diags)
}

/// At most one statement of `kind`; extra ones are reported.
pub fn single_optional<'s>(
    stmts: &[&'s Stmt],
    kind: &str,
    diags: &mut Diagnostics,
) -> Option<&'s Stmt> {
    let (first, rest) = stmts.split_first()?;
    for extra in rest {
        diags.push(message::statement::duplicate_statement(
            kind,
            extra.kind.span,
            first.kind.span,
        ));
    }
    Some(first)
}

/// A statement not written in the shape its kind takes.
pub fn shape_error(s: &Stmt, shape: &str, example: &str) -> Diagnostic {
    message::statement::statement_shape(&s.kind.node, s.span, shape, example)
}

/// `part NAME`: the part's name.
pub fn part(stmts: &Statements<'_>, diags: &mut Diagnostics) -> Option<String> {
    let s = single(stmts.get("part"), "part", "part my_part", diags)?;
    match (&s.name, &s.body) {
        (Some(n), Body::None) => Some(n.node.clone()),
        _ => {
            diags.push(shape_error(s, "part NAME", "part twisted_duct"));
            None
        }
    }
}

//! The checker: typed AST → [`Model`]. Resolves names, evaluates constants with
//! units, checks every block's fields and ranges, and reports every problem it
//! finds (pest stops at the first syntax error; this stage never stops early).

mod bead;
mod extrude;
mod fields;
mod loft;
mod machine;
pub mod model;
mod process;
mod profile;
mod program_text;
mod section;
pub mod slicing;
mod style;
mod suggest;
pub mod value;

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::MachineOrigin;
use crate::span::Span;
use crate::syntax::ast::{Body, Expr, File, Stmt};
use model::{Model, Plan, Section};
use std::collections::BTreeMap;
use value::{Env, Value};

/// Top-level statement kinds.
const KINDS: &[&str] = &[
    "part",
    "let",
    "section",
    "profile",
    "bead",
    "loft",
    "extrude",
    "slicing",
    "process",
    "style",
    "inheritance",
    "machine",
];

/// Checks a parsed file. Returns every diagnostic (errors and warnings) found,
/// and the model when every part of it could be read — even if some other
/// statement had errors (an unused constant, a machine that is dropped), so the
/// later stages can report their own problems in the same run. A model that
/// comes with errors is never built into a program.
pub fn check(file: &File) -> (Option<Model>, Diagnostics) {
    let mut diags = Diagnostics::new();
    let model = check_into(file, &mut diags);
    (model, diags)
}

fn check_into(file: &File, diags: &mut Diagnostics) -> Option<Model> {
    let mut env = Env::new();
    let mut by_kind: BTreeMap<&str, Vec<&Stmt>> = BTreeMap::new();
    for s in &file.stmts {
        let k = s.kind.node.as_str();
        if !KINDS.contains(&k) {
            let mut d = Diagnostic::error(
                Code::UnknownStatement,
                format!("`{k}` does not start a statement"),
            )
            .label(s.kind.span, "unknown");
            d = match suggest::did_you_mean(k, KINDS.iter().copied()) {
                Some(m) => d.help(format!("did you mean `{m}`?")),
                None => d.help(format!("a file is made of: {}", KINDS.join(", "))),
            };
            diags.push(d);
            continue;
        }
        by_kind.entry(k).or_default().push(s);
    }
    let get = |k: &str| by_kind.get(k).cloned().unwrap_or_default();

    // Constants first: everything else may use them, in any order.
    for s in get("let") {
        match (&s.name, &s.body) {
            (Some(n), Body::Assign(e)) => {
                if let Some(prev) = env.declare(&n.node, n.span, e) {
                    diags.push(
                        Diagnostic::error(
                            Code::Duplicate,
                            format!("`{}` is declared twice", n.node),
                        )
                        .label(n.span, "second declaration")
                        .label(prev, "first declaration")
                        .help("rename one of them"),
                    );
                }
            }
            _ => diags.push(shape_error(s, "let NAME = value", "let R1 = 250 mm")),
        }
    }
    env.eval_all(diags);

    let part = single(&get("part"), "part", "part my_part", diags).and_then(|s| {
        match (&s.name, &s.body) {
            (Some(n), Body::None) => Some(n.node.clone()),
            _ => {
                diags.push(shape_error(s, "part NAME", "part twisted_duct"));
                None
            }
        }
    });

    let mut sections: BTreeMap<String, (Section, Span)> = BTreeMap::new();
    for s in get("section") {
        let (Some(n), Body::Assign(e)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "section NAME = shape(…)",
                "section inlet = circle(diameter = 60 mm)",
            ));
            continue;
        };
        let before = env.layer_reads();
        let Some(v) = env.eval(e, diags) else {
            continue;
        };
        if env.layer_reads() > before {
            diags.push(
                Diagnostic::error(
                    Code::LayerOutsideProfile,
                    format!(
                        "section `{}` uses `layer` or `layer_z`, which only a profile follows",
                        n.node
                    ),
                )
                .label(e.span, "depends on the layer")
                .help(format!(
                    "declare it as `profile {} = …` to let it change from layer to layer",
                    n.node
                )),
            );
            continue;
        }
        let sec = match &v.value {
            Value::Call(c) if section::SHAPES.contains(&c.func.as_str()) => section::read(c, diags),
            other => {
                diags.push(
                    Diagnostic::error(Code::Type, format!("section `{}` must be a shape", n.node))
                        .label(v.span, format!("this is {}", other.describe()))
                        .help(format!("shapes: {}", section::SHAPES.join(", "))),
                );
                None
            }
        };
        if let Some(prev) = sections.get(&n.node) {
            diags.push(
                Diagnostic::error(
                    Code::Duplicate,
                    format!("section `{}` is declared twice", n.node),
                )
                .label(n.span, "second declaration")
                .label(prev.1, "first declaration"),
            );
        } else if let Some(sec) = sec {
            sections.insert(n.node.clone(), (sec, n.span));
        }
    }

    let mut profiles: BTreeMap<String, (&Expr, Span)> = BTreeMap::new();
    for s in get("profile") {
        let (Some(n), Body::Assign(e)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "profile NAME = outline(…)",
                "profile tooth = outline([0 mm, 0 mm], [40 mm, 0 mm], [40 mm, 20 mm])",
            ));
            continue;
        };
        // Checked once here (at layer 0); the extrusion evaluates it per layer.
        let ok = env
            .eval(e, diags)
            .and_then(|v| profile::shape(&v, &format!("profile `{}`", n.node), diags))
            .is_some();
        let prev = profiles
            .get(&n.node)
            .map(|p| p.1)
            .or(sections.get(&n.node).map(|p| p.1));
        if let Some(prev) = prev {
            diags.push(
                Diagnostic::error(Code::Duplicate, format!("`{}` is declared twice", n.node))
                    .label(n.span, "second declaration")
                    .label(prev, "first declaration"),
            );
        } else if ok {
            profiles.insert(n.node.clone(), (e, n.span));
        }
    }

    let mut beads = BTreeMap::new();
    for s in get("bead") {
        let (Some(n), Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "bead NAME { … }",
                "bead wall { width = 6 mm … }",
            ));
            continue;
        };
        if let Some(b) = bead::read(&mut env, &n.node, stmts, s.span, diags) {
            beads.insert(n.node.clone(), b);
        }
    }

    let declared: Vec<String> = get("section")
        .iter()
        .chain(&get("profile"))
        .chain(&get("bead"))
        .filter_map(|s| s.name.as_ref().map(|n| n.node.clone()))
        .collect();
    let scope = loft::Scope {
        sections: &sections,
        beads: &beads,
        declared: &declared,
    };
    let escope = extrude::Scope {
        sections: &sections,
        profiles: &profiles,
        beads: &beads,
        declared: &declared,
    };
    let mut solids: Vec<&Stmt> = get("loft");
    solids.extend(get("extrude"));
    solids.sort_by_key(|s| s.span.start);
    let solid = match solids.as_slice() {
        [] => {
            diags.push(
                Diagnostic::error(
                    Code::MissingSolid,
                    "the file does not describe a solid to build",
                )
                .label(Span::new(0, 0), "no `loft` or `extrude` here")
                .help("add `loft NAME { from = …, to = …, spine = …, wall = BEAD }` or `extrude NAME { profile = …, bead = BEAD }`"),
            );
            None
        }
        [s, rest @ ..] => {
            for extra in rest {
                diags.push(
                    Diagnostic::error(Code::Duplicate, "lmdc builds one solid per file")
                        .label(extra.kind.span, "second solid")
                        .label(s.kind.span, "first solid")
                        .help("put each part in its own file"),
                );
            }
            match (s.kind.node.as_str(), &s.name, &s.body) {
                ("loft", Some(n), Body::Block(stmts, _)) => {
                    loft::read(&mut env, &n.node, stmts, s.span, &scope, diags).map(Solid::Loft)
                }
                ("extrude", Some(n), Body::Block(stmts, _)) => {
                    extrude::read(&mut env, &n.node, stmts, s.span, &escope, diags)
                        .map(Solid::Extrude)
                }
                ("loft", _, _) => {
                    diags.push(shape_error(
                        s,
                        "loft NAME { … }",
                        "loft duct { from = inlet … }",
                    ));
                    None
                }
                _ => {
                    diags.push(shape_error(
                        s,
                        "extrude NAME { … }",
                        "extrude tooth { profile = tooth, bead = track }",
                    ));
                    None
                }
            }
        }
    };

    let slicing = single(
        &get("slicing"),
        "slicing",
        "slicing normal { layers = auto }",
        diags,
    )
    .and_then(|s| match &s.body {
        Body::Block(stmts, _) => slicing::read(&mut env, s.name.as_ref(), stmts, s.span, diags),
        _ => {
            diags.push(shape_error(
                s,
                "slicing STRATEGY { … }",
                "slicing normal { layers = auto }",
            ));
            None
        }
    });
    let process = single(
        &get("process"),
        "process",
        "process { powder = 45.9 g/min, power = 2100 W }",
        diags,
    )
    .and_then(|s| match (&s.name, &s.body) {
        (None, Body::Block(stmts, _)) => process::read(&mut env, stmts, s.span, diags),
        _ => {
            diags.push(shape_error(
                s,
                "process { … }",
                "process { power = 2100 W }",
            ));
            None
        }
    });

    let mut machines = Vec::new();
    let mut seen: BTreeMap<String, Span> = BTreeMap::new();
    for s in get("machine") {
        let (Some(n), Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "machine NAME { … }",
                "machine kr60 { kind = robot … }",
            ));
            continue;
        };
        if let Some(prev) = seen.insert(n.node.clone(), n.span) {
            diags.push(
                Diagnostic::error(
                    Code::Duplicate,
                    format!("machine `{}` is declared twice", n.node),
                )
                .label(n.span, "second declaration")
                .label(prev, "first declaration"),
            );
        }
        if let Some((m, mut fields)) = machine::read(&mut env, &n.node, stmts, s.span, diags) {
            fields.push(("name".into(), n.span));
            machines.push((
                m,
                MachineOrigin {
                    block: s.span,
                    fields,
                },
            ));
        }
    }
    if get("machine").is_empty() {
        diags.push(
            Diagnostic::error(
                Code::MissingMachine,
                "the file declares no machine to write a program for",
            )
            .label(Span::new(0, 0), "no `machine` here")
            .help("add `machine NAME { kind = robot … }` or `machine NAME { kind = cnc … }`"),
        );
    }

    let styles = style::read(&mut env, &get("style"), diags);
    let inheritance_stmt = single_optional(&get("inheritance"), "inheritance", diags);
    let inheritance = inheritance_stmt.and_then(|s| style::inheritance(&mut env, s, diags));
    let inheritance_ok = inheritance_stmt.is_none() || inheritance.is_some();

    let process = process?;
    let (plan, bead) = match (solid?, slicing?) {
        (Solid::Loft((loft, bead)), slicing::Spec::Normal(slicing)) => {
            (Plan::Duct { loft, slicing }, bead)
        }
        (Solid::Extrude(w), slicing::Spec::Planar(spec)) => {
            let bead = w.bead.clone();
            let (extrusion, slicing) = extrude::assemble(&mut env, w, spec, &process, diags)?;
            (Plan::Block { extrusion, slicing }, bead)
        }
        (solid, spec) => {
            let (solid_kind, strategy) = match (&solid, &spec) {
                (Solid::Loft(_), _) => ("a loft", "planar"),
                (Solid::Extrude(_), _) => ("an extrusion", "normal"),
            };
            let at = get("slicing")
                .first()
                .map(|s| s.span)
                .unwrap_or(Span::new(0, 0));
            diags.push(
                Diagnostic::error(
                    Code::BadChoice,
                    format!("{strategy} slicing does not build {solid_kind}"),
                )
                .label(at, "slicing")
                .help(match solid {
                    Solid::Loft(_) => "slice a loft with `slicing normal { … }`",
                    Solid::Extrude(_) => "slice an extrusion with `slicing planar { … }`",
                }),
            );
            return None;
        }
    };
    let styles = style::assemble(
        &plan,
        styles,
        inheritance,
        inheritance_stmt.map(|s| s.span),
        &bead,
        &process,
        diags,
    )?;
    if !inheritance_ok {
        return None;
    }
    bead::check_feed(&bead, &process, diags);
    Some(Model {
        part: part?,
        plan,
        bead,
        process,
        machines,
        styles,
    })
}

/// The solid a file describes, as read.
enum Solid<'a> {
    Loft((model::Loft, model::Bead)),
    Extrude(extrude::Written<'a>),
}

fn single<'s>(
    stmts: &[&'s Stmt],
    kind: &str,
    example: &str,
    diags: &mut Diagnostics,
) -> Option<&'s Stmt> {
    if stmts.is_empty() {
        diags.push(
            Diagnostic::error(
                Code::MissingStatement,
                format!("the file has no `{kind}` statement"),
            )
            .label(Span::new(0, 0), format!("`{kind}` is missing"))
            .help(format!("add `{example}`")),
        );
    }
    single_optional(stmts, kind, diags)
}

/// At most one statement of `kind`; extra ones are reported.
fn single_optional<'s>(
    stmts: &[&'s Stmt],
    kind: &str,
    diags: &mut Diagnostics,
) -> Option<&'s Stmt> {
    let (first, rest) = stmts.split_first()?;
    for extra in rest {
        diags.push(
            Diagnostic::error(Code::Duplicate, format!("`{kind}` is given twice"))
                .label(extra.kind.span, "second time")
                .label(first.kind.span, "first time")
                .help("keep one of them"),
        );
    }
    Some(first)
}

fn shape_error(s: &Stmt, shape: &str, example: &str) -> Diagnostic {
    Diagnostic::error(
        Code::Syntax,
        format!("a `{}` statement is written `{shape}`", s.kind.node),
    )
    .label(s.span, "not in that shape")
    .help(format!("e.g. `{example}`"))
}

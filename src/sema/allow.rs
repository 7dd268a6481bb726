//! `allow "lmd::CODE" = "why"`: a warning the file expects, with the
//! reason. Its reports are still made, each marked with the reason
//! ([`crate::diag::Diagnostic::allowed`]), and fail no run
//! (`--deny-warnings`, `--deny`): a CI gate stays strict for every other
//! warning (docs/diagnostics.md, "Expected warnings").

use crate::diag::{message, Code, Diagnostics, Group};
use crate::sema::statement::Statements;
use crate::sema::suggest;
use crate::syntax::ast::{Body, ExprKind};

/// Reads every `allow` statement, telling `diags` which warnings the file
/// expects.
pub fn read(st: &Statements<'_>, diags: &mut Diagnostics) {
    for s in st.get("allow") {
        let (Some(name), Body::Assign(why)) = (&s.name, &s.body) else {
            diags.push(message::statement::allow_shape(
                s.span,
                "a code and a reason, `allow \"lmd::CODE\" = \"why\"`",
            ));
            continue;
        };
        let ExprKind::Str(reason) = &why.kind else {
            diags.push(message::statement::allow_shape(
                why.span,
                "its reason in quotes",
            ));
            continue;
        };
        if reason.trim().is_empty() {
            diags.push(message::statement::allow_shape(
                why.span,
                "a reason that says why",
            ));
            continue;
        }
        let Some(code) = code(&name.node) else {
            let names = Code::ALL.iter().map(|c| c.as_str());
            let near = suggest::did_you_mean(&full(&name.node), names);
            diags.push(message::statement::allow_unknown_code(
                &name.node, name.span, near,
            ));
            continue;
        };
        if !warns(code) {
            diags.push(message::statement::allow_error_code(
                code.as_str(),
                ALSO_WARNINGS,
                name.span,
            ));
            continue;
        }
        diags.allow(code, reason.trim());
    }
}

/// The code written `lmd::name` or `name`.
pub fn code(text: &str) -> Option<Code> {
    let text = full(text);
    Code::ALL.iter().copied().find(|c| c.as_str() == text)
}

fn full(text: &str) -> String {
    let t = text.trim();
    if t.starts_with("lmd::") {
        t.to_string()
    } else {
        format!("lmd::{t}")
    }
}

/// The codes outside docs/diagnostics.md's Warnings group that lmdc also
/// reports as warnings (a test holds this list to the messages).
pub const ALSO_WARNINGS: &[Code] = &[
    Code::Extrapolation,
    Code::Overlap,
    Code::Overhang,
    Code::UnstableLoop,
    Code::SlowLoop,
    Code::Scan,
    Code::ScanRegistration,
    Code::Finish,
];

/// Whether `code` is ever a warning.
pub fn warns(code: Code) -> bool {
    code.group() == Group::Warnings || ALSO_WARNINGS.contains(&code)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Every code a message makes a warning of (`Diagnostic::warning(Code::X`,
    /// and the height loop's findings) can be allowed: `ALSO_WARNINGS` keeps
    /// up with the messages.
    #[test]
    fn every_code_reported_as_a_warning_can_be_allowed() {
        let mut files = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src/diag/message")];
        let mut warned = Vec::new();
        while let Some(p) = files.pop() {
            if p.is_dir() {
                files.extend(std::fs::read_dir(&p).unwrap().map(|e| e.unwrap().path()));
                continue;
            }
            let text = std::fs::read_to_string(&p).unwrap();
            for (i, _) in text.match_indices("Diagnostic::warning(") {
                let rest = text[i + 20..].trim_start();
                if let Some(name) = rest.strip_prefix("Code::") {
                    let end = name.find(|c: char| !c.is_alphanumeric()).unwrap();
                    warned.push(name[..end].to_string());
                }
            }
        }
        warned.extend(["SlowLoop".to_string(), "UnstableLoop".to_string()]);
        assert!(warned.len() > 10, "{warned:?}");
        for name in warned {
            let code = Code::ALL.iter().find(|c| format!("{c:?}") == name).unwrap();
            assert!(
                warns(*code),
                "{name} is reported as a warning: add it to ALSO_WARNINGS"
            );
        }
        assert_eq!(code("height-rounded"), Some(Code::HeightRounded));
        assert_eq!(code("lmd::height-rounded"), Some(Code::HeightRounded));
        assert_eq!(code("lmd::nope"), None);
    }
}

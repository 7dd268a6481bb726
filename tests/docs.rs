//! The documentation keeps up with the code: the code tables of
//! docs/diagnostics.md are generated from `lmdc::diag::Code` (one table, one
//! place), and every code the compiler has is used somewhere in `src/`.

use lmdc::diag::{Code, Group};

const START: &str = "<!-- codes -->\n";
const END: &str = "<!-- end codes -->";

/// The tables as `Code` describes them.
fn tables() -> String {
    let mut out = String::new();
    for g in Group::ALL {
        if !Code::ALL.iter().any(|c| c.group() == g) {
            continue;
        }
        out.push_str(&format!(
            "## {}\n\n| code | meaning |\n|---|---|\n",
            g.title()
        ));
        for c in Code::ALL.iter().filter(|c| c.group() == g) {
            out.push_str(&format!("| `{}` | {} |\n", c.as_str(), c.meaning()));
        }
        out.push('\n');
    }
    out
}

#[test]
fn diagnostics_doc_lists_every_code() {
    let path = "docs/diagnostics.md";
    let text = std::fs::read_to_string(path).unwrap();
    let (Some(a), Some(b)) = (text.find(START), text.find(END)) else {
        panic!("{path} lost its `{START}` / `{END}` markers");
    };
    let want = tables();
    if text[a + START.len()..b] == want {
        return;
    }
    if std::env::var_os("LMDC_UPDATE_DOCS").is_some() {
        let new = format!("{}{START}{want}{}", &text[..a], &text[b..]);
        std::fs::write(path, new).unwrap();
        return;
    }
    panic!("{path} is out of date with src/diag/code.rs: run LMDC_UPDATE_DOCS=1 cargo test --test docs");
}

fn sources(dir: &std::path::Path, out: &mut String) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") && !p.ends_with("diag/code.rs") {
            out.push_str(&std::fs::read_to_string(&p).unwrap());
        }
    }
}

#[test]
fn every_code_is_emitted_somewhere() {
    let mut text = String::new();
    sources(std::path::Path::new("src"), &mut text);
    let unused: Vec<_> = Code::ALL
        .iter()
        .filter(|c| {
            let name = format!("{c:?}");
            !text.contains(&format!("Code::{name}")) && !text.contains(&format!("{name},"))
        })
        .collect();
    assert!(unused.is_empty(), "codes no diagnostic uses: {unused:?}");
}

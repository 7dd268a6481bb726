//! The documentation keeps up with the code: the code tables of
//! docs/diagnostics.md are generated from `lmdc::diag::Code` (one table, one
//! place), and every code the compiler has is used somewhere in `src/`; the
//! field tables of docs/language.md are generated from the blocks' tables
//! (`lmdc::sema::schema`).

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

/// The field tables of docs/language.md: each block's fields as
/// `lmdc::sema::schema` describes them, between `<!-- fields: NAME -->`
/// and `<!-- end fields -->`.
mod fields {
    use lmdc::sema::schema::{self, Block, Field};

    const START: &str = "<!-- fields: ";
    const END: &str = "<!-- end fields -->";

    fn row(f: &Field, refused: bool) -> String {
        let default = if refused {
            "refused".to_string()
        } else {
            f.default_text()
        };
        let cells = [
            format!("`{}`", f.key),
            f.value_text(),
            default,
            f.help.to_string(),
        ];
        for c in &cells {
            assert!(!c.contains('|'), "`{}`: a `|` would split its row", f.key);
        }
        format!("| {} |\n", cells.join(" | "))
    }

    /// The table of `b`, as the doc shows it.
    fn table(b: &Block) -> String {
        let mut out = format!(
            "\n`{}`: {}.\n\n| field | value | if left out | meaning |\n|---|---|---|---|\n",
            b.syntax, b.help
        );
        for f in b.fields {
            out.push_str(&row(f, false));
        }
        for f in b.refused {
            out.push_str(&row(f, true));
        }
        out.push('\n');
        out
    }

    /// The doc with every table generated anew, and the blocks it shows.
    fn regenerate(text: &str) -> (String, Vec<&'static str>) {
        let mut out = String::new();
        let mut shown = Vec::new();
        let mut rest = text;
        while let Some(a) = rest.find(START) {
            let open_end = a + rest[a..].find("-->").expect("a marker ends with -->") + 3;
            let name = rest[a + START.len()..open_end - 3].trim();
            let Some(b) = schema::block(name) else {
                panic!("docs/language.md names no block `{name}` of sema::schema::BLOCKS")
            };
            let Some(end) = rest[open_end..].find(END) else {
                panic!("the table of `{name}` has no `{END}`")
            };
            out.push_str(&rest[..open_end]);
            out.push_str(&table(b));
            out.push_str(END);
            shown.push(b.name);
            rest = &rest[open_end + end + END.len()..];
        }
        out.push_str(rest);
        (out, shown)
    }

    #[test]
    fn language_doc_shows_every_blocks_fields() {
        let path = "docs/language.md";
        let text = std::fs::read_to_string(path).unwrap();
        let (want, shown) = regenerate(&text);
        let missing: Vec<_> = schema::BLOCKS
            .iter()
            .filter(|b| !b.is_call() && !shown.contains(&b.name))
            .map(|b| b.name)
            .collect();
        assert!(
            missing.is_empty(),
            "{path} has no field table for {missing:?}: add `{START}NAME -->` `{END}` where each block is described"
        );
        if text == want {
            return;
        }
        if std::env::var_os("LMDC_UPDATE_DOCS").is_some() {
            std::fs::write(path, want).unwrap();
            return;
        }
        panic!("{path}'s field tables are out of date with src/sema/schema/: run LMDC_UPDATE_DOCS=1 cargo test --test docs");
    }
}

//! The editor grammar (editors/vscode/syntaxes/lmd.tmLanguage.json) loads,
//! its patterns compile (with Oniguruma's lookahead, as editors run them),
//! and tokenising every example and test input the way a TextMate engine does
//! (the earliest match wins, ties to the first pattern; `begin`/`end` across
//! lines) gives every character but blanks a scope from the standard roots;
//! every statement word the language server offers is a `storage.type`.

use fancy_regex::Regex;
use serde_json::Value;
use std::path::{Path, PathBuf};

const GRAMMAR: &str = "editors/vscode/syntaxes/lmd.tmLanguage.json";
const ROOTS: &[&str] = &[
    "comment",
    "string",
    "constant",
    "keyword",
    "storage",
    "entity",
    "variable",
    "support",
    "punctuation",
];

enum Rule {
    Match {
        re: Regex,
        name: Option<String>,
        captures: Vec<(usize, String)>,
    },
    Block {
        begin: Regex,
        end: Regex,
        name: String,
    },
}

fn re(v: &Value) -> Regex {
    let s = v.as_str().expect("a pattern is a string");
    Regex::new(s).unwrap_or_else(|e| panic!("pattern {s}: {e}"))
}

fn scope(name: &str) -> String {
    let root = name.split('.').next().unwrap();
    assert!(ROOTS.contains(&root), "scope {name} has no standard root");
    assert!(name.ends_with(".lmd"), "scope {name} does not end in .lmd");
    name.to_string()
}

/// The grammar's patterns in the order an engine tries them.
fn rules(g: &Value, patterns: &Value, out: &mut Vec<Rule>) {
    for p in patterns.as_array().expect("patterns is a list") {
        if let Some(inc) = p.get("include").and_then(Value::as_str) {
            let key = inc.strip_prefix('#').expect("includes name the repository");
            rules(g, &g["repository"][key]["patterns"], out);
        } else if let Some(m) = p.get("match") {
            let captures = p
                .get("captures")
                .and_then(Value::as_object)
                .map(|c| {
                    c.iter()
                        .map(|(k, v)| (k.parse().unwrap(), scope(v["name"].as_str().unwrap())))
                        .collect()
                })
                .unwrap_or_default();
            out.push(Rule::Match {
                re: re(m),
                name: p.get("name").and_then(Value::as_str).map(scope),
                captures,
            });
        } else {
            out.push(Rule::Block {
                begin: re(&p["begin"]),
                end: re(&p["end"]),
                name: scope(p["name"].as_str().unwrap()),
            });
        }
    }
}

fn grammar() -> Vec<Rule> {
    let g: Value = serde_json::from_str(&std::fs::read_to_string(GRAMMAR).unwrap()).unwrap();
    assert_eq!(g["scopeName"], "source.lmd");
    let mut out = Vec::new();
    rules(&g, &g["patterns"], &mut out);
    assert!(out.len() > 10);
    out
}

/// Each byte's scope in each line of `text` (None: no scope).
fn tokenise(rules: &[Rule], text: &str) -> Vec<Vec<Option<String>>> {
    let mut open: Option<(&Regex, &str)> = None;
    let mut out = Vec::new();
    for line in text.lines() {
        let mut scopes = vec![None; line.len()];
        let mut pos = 0;
        let mark = |scopes: &mut Vec<Option<String>>, a: usize, b: usize, s: &str| {
            for x in &mut scopes[a..b] {
                *x = Some(s.to_string());
            }
        };
        while pos <= line.len() {
            if let Some((end, name)) = open {
                match end.find_from_pos(line, pos).unwrap() {
                    Some(m) => {
                        mark(&mut scopes, pos, m.end(), name);
                        pos = m.end();
                        open = None;
                        continue;
                    }
                    None => {
                        mark(&mut scopes, pos, line.len(), name);
                        break;
                    }
                }
            }
            // The earliest match of any rule; ties to the first.
            let mut best: Option<(usize, usize, &Rule, Option<fancy_regex::Captures>)> = None;
            for r in rules {
                let (re, caps) = match r {
                    Rule::Match { re, .. } => (re, true),
                    Rule::Block { begin, .. } => (begin, false),
                };
                let Some(c) = re.captures_from_pos(line, pos).unwrap() else {
                    continue;
                };
                let m = c.get(0).unwrap();
                if best.as_ref().is_none_or(|b| m.start() < b.0) {
                    best = Some((m.start(), m.end(), r, caps.then_some(c)));
                }
            }
            let Some((start, end, rule, caps)) = best else {
                break;
            };
            match rule {
                Rule::Match { name, captures, .. } => {
                    if let Some(n) = name {
                        mark(&mut scopes, start, end, n);
                    }
                    let caps = caps.unwrap();
                    for (i, n) in captures {
                        if let Some(g) = caps.get(*i) {
                            mark(&mut scopes, g.start(), g.end(), n);
                        }
                    }
                }
                Rule::Block { end: e, name, .. } => {
                    mark(&mut scopes, start, end, name);
                    open = Some((e, name));
                }
            }
            // An empty match moves on by a character.
            pos = if end > start {
                end
            } else {
                line[end..]
                    .chars()
                    .next()
                    .map_or(line.len() + 1, |c| end + c.len_utf8())
            };
        }
        out.push(scopes);
    }
    out
}

fn inputs() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "lmd") {
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    walk(Path::new("examples"), &mut out);
    walk(Path::new("tests/cases"), &mut out);
    out.sort();
    out
}

#[test]
fn every_character_of_every_input_gets_a_standard_scope() {
    let rules = grammar();
    let files = inputs();
    assert!(files.len() > 20);
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        for (n, (line, scopes)) in text.lines().zip(tokenise(&rules, &text)).enumerate() {
            for (i, c) in line.char_indices() {
                assert!(
                    c.is_whitespace() || scopes[i].is_some(),
                    "{}:{}:{}: `{c}` has no scope in `{line}`",
                    f.display(),
                    n + 1,
                    i + 1
                );
            }
        }
    }
}

#[test]
fn the_grammar_scopes_what_it_means_to() {
    let rules = grammar();
    let line = "  speed = 7 mm/s .. 10 mm/s  seam = 90 deg // a comment";
    let s = &tokenise(&rules, line)[0];
    let at = |needle: &str| s[line.find(needle).unwrap()].clone().unwrap();
    assert_eq!(at("speed"), "variable.other.property.lmd");
    assert_eq!(at("7"), "constant.numeric.lmd");
    assert_eq!(at("mm/s"), "keyword.other.unit.lmd");
    assert_eq!(at(".."), "keyword.operator.range.lmd");
    // `seam` after a number is a field, not the unit `s` and a name.
    assert_eq!(at("seam"), "variable.other.property.lmd");
    assert_eq!(at("// a"), "comment.line.double-slash.lmd");
    let s = &tokenise(&rules, "bead wall_bead {")[0];
    assert_eq!(s[0].as_deref(), Some("storage.type.lmd"));
    assert_eq!(s[5].as_deref(), Some("entity.name.type.lmd"));
}

#[test]
fn every_statement_the_language_server_offers_is_highlighted_as_one() {
    let rules = grammar();
    let offered = lmdc::lsp::completion("", 0);
    assert!(offered.len() > 8);
    for c in offered {
        let line = format!("{} x {{", c.label);
        let s = &tokenise(&rules, &line)[0];
        assert_eq!(
            s[0].as_deref(),
            Some("storage.type.lmd"),
            "`{}` is not highlighted as a statement",
            c.label
        );
    }
}

#[test]
fn the_extension_manifest_names_the_grammar_and_the_server() {
    let p: Value =
        serde_json::from_str(&std::fs::read_to_string("editors/vscode/package.json").unwrap())
            .unwrap();
    let g = &p["contributes"]["grammars"][0];
    assert_eq!(g["scopeName"], "source.lmd");
    assert!(Path::new("editors/vscode")
        .join(g["path"].as_str().unwrap())
        .exists());
    assert_eq!(p["contributes"]["languages"][0]["extensions"][0], ".lmd");
    // vsce packages the licence it names from beside the manifest (issue
    // 38 item 6: there was none).
    assert_eq!(p["license"], "MIT");
    let text = |f: &str| std::fs::read_to_string(f).unwrap();
    assert_eq!(text("editors/vscode/LICENSE"), text("LICENSE-MIT"));
    let js = std::fs::read_to_string("editors/vscode/extension.js").unwrap();
    assert!(js.contains("args: [\"lsp\"]"));
    let conf: Value = serde_json::from_str(
        &std::fs::read_to_string("editors/vscode/language-configuration.json").unwrap(),
    )
    .unwrap();
    assert_eq!(conf["comments"]["lineComment"], "//");
}

//! `lmdc fmt`: over every example and over generated files, the formatted
//! text parses to the same tree as the input (spans aside), formatting it
//! again changes nothing, and every comment is still there, in order. The
//! examples are formatted (CI runs `lmdc fmt --check` over them too).

use lmdc::fmt::{format, without_spans};
use lmdc::syntax::parse;
use proptest::prelude::*;
use std::path::Path;
use std::process::Command;

/// The comments of `src` in order, as the formatter must keep them
/// (texts in quotes skipped), each trimmed.
fn comment_texts(src: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = src;
    let mut in_str = false;
    while let Some(c) = rest.chars().next() {
        if in_str {
            in_str = !(c == '"' || c == '\n');
            rest = &rest[c.len_utf8()..];
        } else if c == '"' {
            in_str = true;
            rest = &rest[1..];
        } else if rest.starts_with("//") {
            let end = rest.find('\n').unwrap_or(rest.len());
            out.push(rest[..end].trim().to_string());
            rest = &rest[end..];
        } else if rest.starts_with("/*") {
            let end = rest.find("*/").map_or(rest.len(), |e| e + 2);
            // Inside a block comment only the indentation may change.
            let words: Vec<&str> = rest[..end].split_whitespace().collect();
            out.push(words.join(" "));
            rest = &rest[end..];
        } else {
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// The properties for one text that parses.
fn holds(src: &str) -> Result<(), String> {
    let before = parse(src).map_err(|d| d.message)?;
    let out = format(src).map_err(|e| format!("{e:?}\n{src}"))?;
    let after = parse(&out).map_err(|d| format!("{}\n{out}", d.message))?;
    if without_spans(before) != without_spans(after) {
        return Err(format!("another tree:\n{src}\n---\n{out}"));
    }
    let again = format(&out).map_err(|e| format!("{e:?}"))?;
    if again != out {
        return Err(format!("not idempotent:\n{out}\n---\n{again}"));
    }
    if comment_texts(src) != comment_texts(&out) {
        return Err(format!("comments moved or lost:\n{src}\n---\n{out}"));
    }
    Ok(())
}

fn lmd_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lmd"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_example_keeps_its_meaning_and_comments() {
    let mut n = 0;
    for dir in [
        "examples",
        "examples/bench",
        "examples/errors",
        "tests/codes",
    ] {
        for f in lmd_files(Path::new(dir)) {
            let src = std::fs::read_to_string(&f).unwrap();
            if parse(&src).is_err() {
                continue;
            }
            holds(&src).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            n += 1;
        }
    }
    assert!(n > 30, "{n} files");
}

/// The examples people read are formatted: `lmdc fmt --check` passes.
#[test]
fn the_examples_are_formatted() {
    let mut files: Vec<String> = Vec::new();
    for dir in ["examples", "examples/bench"] {
        files.extend(
            lmd_files(Path::new(dir))
                .iter()
                .map(|p| p.display().to_string()),
        );
    }
    let o = Command::new(env!("CARGO_BIN_EXE_lmdc"))
        .arg("fmt")
        .arg("--check")
        .args(&files)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "run `lmdc fmt examples/*.lmd examples/bench/*.lmd`: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn the_command_formats_in_place_checks_and_reads_stdin() {
    let dir = std::env::temp_dir().join(format!("lmdc-fmt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("p.lmd");
    let messy = "part   p\nlet R=3mm // r\n";
    std::fs::write(&f, messy).unwrap();
    let lmdc = |args: &[&str], stdin: Option<&str>| {
        use std::io::Write;
        let mut c = Command::new(env!("CARGO_BIN_EXE_lmdc"))
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let mut input = c.stdin.take().unwrap();
        input.write_all(stdin.unwrap_or("").as_bytes()).unwrap();
        drop(input);
        c.wait_with_output().unwrap()
    };
    let p = f.to_str().unwrap();
    let o = lmdc(&["fmt", "--check", p], None);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not formatted"));
    assert_eq!(
        std::fs::read_to_string(&f).unwrap(),
        messy,
        "--check writes nothing"
    );
    let o = lmdc(&["fmt", p], None);
    assert_eq!(o.status.code(), Some(0));
    let want = "part p\nlet R = 3 mm  // r\n";
    assert_eq!(std::fs::read_to_string(&f).unwrap(), want);
    assert_eq!(lmdc(&["fmt", "--check", p], None).status.code(), Some(0));
    let o = lmdc(&["fmt"], Some(messy));
    assert_eq!(String::from_utf8(o.stdout).unwrap(), want);
    // A file that does not parse is left alone, with the error drawn.
    std::fs::write(&f, "let = (").unwrap();
    let o = lmdc(&["fmt", p], None);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("lmd::syntax"));
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "let = (");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Blanks between tokens: none, a space, spaces, a line end, a comment.
fn blank() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        Just(" ".to_string()),
        Just("   ".to_string()),
        Just("\n  ".to_string()),
        Just("\r\n".to_string()),
        Just(" /* c */ ".to_string()),
        Just(" // note\n".to_string()),
    ]
}

fn number() -> impl Strategy<Value = String> {
    let units = prop_oneof![
        Just(""),
        Just(" mm"),
        Just("mm"),
        Just(" deg"),
        Just(" mm/s"),
        Just(" %"),
        Just(" g/cm^3"),
        Just(" KW"),
        Just(" m/s/mm"),
    ];
    (
        prop_oneof![
            Just("0"),
            Just("1.5"),
            Just("30"),
            Just("2e3"),
            Just("0.00300")
        ],
        units,
    )
        .prop_map(|(n, u)| format!("{n}{u}"))
}

/// Expressions written with random blanks and brackets.
fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        number(),
        Just("R".to_string()),
        Just("auto".to_string()),
        Just("\"a b\"".to_string()),
    ];
    leaf.prop_recursive(4, 24, 4, |inner| {
        prop_oneof![
            (
                inner.clone(),
                prop_oneof![
                    Just("+"),
                    Just("-"),
                    Just("*"),
                    Just("/"),
                    Just("^"),
                    Just(".."),
                    Just("·")
                ],
                inner.clone(),
                blank(),
                blank()
            )
                .prop_map(|(a, op, b, s1, s2)| format!("{a}{s1}{op}{s2}{b}")),
            (prop_oneof![Just("-"), Just("+")], inner.clone())
                .prop_map(|(op, a)| format!("{op}{a}")),
            (inner.clone(), blank()).prop_map(|(a, s)| format!("({s}{a})")),
            (
                prop::collection::vec((inner.clone(), blank()), 0..4),
                any::<bool>()
            )
                .prop_map(|(xs, trailing)| {
                    let items: Vec<String> =
                        xs.into_iter().map(|(x, s)| format!("{x}{s}")).collect();
                    format!(
                        "[{}{}]",
                        items.join(","),
                        if trailing && !items.is_empty() {
                            ","
                        } else {
                            ""
                        }
                    )
                }),
            prop::collection::vec((any::<bool>(), inner, blank()), 0..4).prop_map(|args| {
                let items: Vec<String> = args
                    .into_iter()
                    .map(|(named, x, s)| {
                        if named {
                            format!("k = {x}{s}")
                        } else {
                            format!("{x}{s}")
                        }
                    })
                    .collect();
                format!("f({})", items.join(","))
            }),
        ]
    })
}

/// Files of statements and blocks, with blanks, blank lines and comments
/// anywhere between tokens.
fn file() -> impl Strategy<Value = String> {
    let stmt = statement().boxed();
    let block = (
        prop::collection::vec(stmt.clone(), 0..5),
        blank(),
        prop_oneof![Just("bead b"), Just("table")],
    )
        .prop_map(|(body, s, head)| format!("{head} {{{s}\n{}}}\n", body.concat()));
    prop::collection::vec(prop_oneof![stmt, block], 1..6).prop_map(|v| v.concat())
}

fn statement() -> impl Strategy<Value = String> {
    (
        prop_oneof![
            Just("let R"),
            Just("width"),
            Just("section \"s 1\""),
            Just("part p")
        ],
        prop::option::of(expr()),
        blank(),
        prop_oneof![
            Just("\n"),
            Just("\n\n\n"),
            Just(" // end\n"),
            Just("  "),
            Just("\n// own line\n")
        ],
    )
        .prop_map(|(head, e, s, end)| match e {
            Some(e) if !head.starts_with("part") => format!("{head}{s}={s}{e}{end}"),
            _ => format!("{head}{end}"),
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn generated_files_keep_their_meaning_and_comments(src in file()) {
        prop_assume!(parse(&src).is_ok());
        if let Err(e) = holds(&src) {
            prop_assert!(false, "{}", e);
        }
    }
}

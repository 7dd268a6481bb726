//! `lmdc lsp` driven over JSON-RPC on stdio as an editor drives it: the
//! handshake, diagnostics on open and on change (the compiler's codes at the
//! places its reports point to), hover from the block tables and from the
//! compiled plan, definition, references, completion in a file that does not
//! parse yet, and a clean shutdown.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

struct Client {
    child: Child,
    stdin: ChildStdin,
    stdout: BufReader<ChildStdout>,
    next: i64,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_lmdc"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("lmdc lsp starts");
        let stdin = child.stdin.take().unwrap();
        let stdout = BufReader::new(child.stdout.take().unwrap());
        Client {
            child,
            stdin,
            stdout,
            next: 1,
        }
    }

    fn send(&mut self, msg: Value) {
        let body = msg.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn read(&mut self) -> Value {
        let mut len = 0usize;
        loop {
            let mut line = String::new();
            assert!(
                self.stdout.read_line(&mut line).unwrap() > 0,
                "the server hung up"
            );
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(n) = line.strip_prefix("Content-Length: ") {
                len = n.parse().unwrap();
            }
        }
        let mut body = vec![0; len];
        self.stdout.read_exact(&mut body).unwrap();
        serde_json::from_slice(&body).unwrap()
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next;
        self.next += 1;
        self.send(json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        loop {
            let m = self.read();
            if m.get("id") == Some(&json!(id)) {
                assert!(m.get("error").is_none(), "{method}: {m}");
                return m["result"].clone();
            }
        }
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// The diagnostics published next for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        loop {
            let m = self.read();
            if m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri {
                return m["params"]["diagnostics"].as_array().unwrap().clone();
            }
        }
    }

    fn open(&mut self, uri: &str, text: &str) -> Vec<Value> {
        self.notify(
            "textDocument/didOpen",
            json!({ "textDocument": { "uri": uri, "languageId": "lmd", "version": 1, "text": text } }),
        );
        self.diagnostics(uri)
    }

    fn at(&mut self, method: &str, uri: &str, (line, character): (usize, usize)) -> Value {
        self.request(
            method,
            json!({
                "textDocument": { "uri": uri },
                "position": { "line": line, "character": character },
                "context": { "includeDeclaration": true },
            }),
        )
    }
}

fn started() -> Client {
    let mut c = Client::start();
    let init = c.request("initialize", json!({ "capabilities": {} }));
    assert_eq!(init["capabilities"]["hoverProvider"], true);
    assert_eq!(init["capabilities"]["positionEncoding"], "utf-16");
    c.notify("initialized", json!({}));
    c
}

fn stop(mut c: Client) {
    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    let status = c.child.wait().unwrap();
    assert!(status.success(), "lmdc lsp exited with {status}");
}

/// The labels of a completion list.
fn labels(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|c| c["label"].as_str().unwrap().to_string())
        .collect()
}

/// The line and UTF-16 column of the `n`-th (from 0) occurrence of `needle`,
/// plus `skip` characters.
fn pos(text: &str, needle: &str, n: usize, skip: usize) -> (usize, usize) {
    let at = text.match_indices(needle).nth(n).expect("in the text").0 + skip;
    let line = text[..at].matches('\n').count();
    let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    (line, text[start..at].encode_utf16().count())
}

fn duct() -> String {
    std::fs::read_to_string("examples/twisted_duct.lmd").unwrap()
}

#[test]
fn diagnostics_come_on_open_and_change_with_the_compilers_codes_and_places() {
    let mut c = started();
    let text = duct();
    let uri = "file:///duct.lmd";
    let d = c.open(uri, &text);
    assert!(d.iter().all(|d| d["severity"] != 1), "{d:?}");
    // A power in the wrong unit: the unit-mismatch error, at the value.
    let broken = text.replacen("width = 6 mm", "width = 6 W", 1);
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": 2 }, "contentChanges": [{ "text": broken }] }),
    );
    let d = c.diagnostics(uri);
    let e = d
        .iter()
        .find(|d| d["code"] == "lmd::unit-mismatch")
        .unwrap_or_else(|| panic!("{d:?}"));
    assert_eq!(e["severity"], 1);
    let (line, ch) = pos(&broken, "6 W", 0, 0);
    assert_eq!(e["range"]["start"]["line"], line);
    assert_eq!(e["range"]["start"]["character"], ch);
    // What `lmdc check` says, word for word.
    let compiled = lmdc::pipeline::compile(&broken, &mut ());
    let want = compiled
        .diagnostics
        .iter()
        .find(|d| d.code.as_str() == "lmd::unit-mismatch")
        .unwrap();
    assert!(e["message"].as_str().unwrap().starts_with(&want.message));
    stop(c);
}

#[test]
fn hover_explains_fields_names_and_what_auto_chose() {
    let mut c = started();
    let text = duct();
    let uri = "file:///duct.lmd";
    c.open(uri, &text);
    let h = c.at("textDocument/hover", uri, pos(&text, "width = 6 mm", 0, 1));
    let md = h["contents"]["value"].as_str().unwrap();
    let field = lmdc::sema::schema::block("bead")
        .unwrap()
        .field("width")
        .unwrap();
    assert!(md.contains(field.help), "{md}");
    assert!(md.contains(&field.value_text()), "{md}");
    // A name: its declaration.
    let h = c.at(
        "textDocument/hover",
        uri,
        pos(&text, "wall = wall_bead", 0, 8),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(
        md.contains("bead `wall_bead`") && md.contains("width = 6 mm"),
        "{md}"
    );
    // `layers = auto`: what the plan chose, from the compiled IR.
    let ir = lmdc::pipeline::compile(&text, &mut ())
        .program
        .unwrap()
        .into_ir();
    let h = c.at(
        "textDocument/hover",
        uri,
        pos(&text, "layers = auto", 0, 10),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.contains(&format!("{} layers", ir.layers.len())), "{md}");
    stop(c);
}

/// `spin = auto` on a robot whose arm needs the tool turned: the hover says
/// the turn the compile chose.
#[test]
fn hover_on_spin_auto_gives_the_turn_chosen() {
    let mut c = started();
    let text = crate::support::example::edited(
        "ramp_wall.lmd",
        &[(
            "arm = kr60ha ",
            "arm = opw(a1 = 350 mm, a2 = -145 mm, c1 = 815 mm, c2 = 850 mm, c3 = 820 mm, c4 = 170 mm,
    limits = [-185 deg .. 185 deg, -135 deg .. 35 deg, -120 deg .. 158 deg,
              -350 deg .. 350 deg, -119 deg .. 119 deg, -135 deg .. 135 deg],
    speeds = [128 deg/s, 102 deg/s, 128 deg/s, 260 deg/s, 245 deg/s, 322 deg/s])
  spin = auto //",
        )],
    );
    let uri = "file:///wall.lmd";
    c.open(uri, &text);
    let ir = lmdc::pipeline::compile(&text, &mut ())
        .program
        .unwrap()
        .into_ir();
    let deg = ir
        .machines
        .iter()
        .find_map(|m| match m {
            lmdc::ir::Machine::Robot(r) => Some(r.spin.deg()),
            _ => None,
        })
        .unwrap();
    assert!(deg != 0.0);
    let h = c.at("textDocument/hover", uri, pos(&text, "spin = auto", 0, 8));
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.contains(&format!("by {deg}° on `kr30`")), "{md}");
    stop(c);
}

#[test]
fn definition_and_references_follow_names() {
    let mut c = started();
    let text = duct();
    let uri = "file:///duct.lmd";
    c.open(uri, &text);
    let d = c.at(
        "textDocument/definition",
        uri,
        pos(&text, "wall = wall_bead", 0, 8),
    );
    let (line, ch) = pos(&text, "bead wall_bead", 0, 5);
    assert_eq!(d["range"]["start"]["line"], line);
    assert_eq!(d["range"]["start"]["character"], ch);
    let r = c.at("textDocument/references", uri, pos(&text, "feed", 0, 0));
    // `let feed = …` and each `= feed` in the file.
    let uses = text.matches("= feed").count();
    assert!(uses >= 1);
    assert_eq!(r.as_array().unwrap().len(), uses + 1, "{r}");
    stop(c);
}

/// A unit is what the grammar reads after a number, whatever the file
/// declares: `W` in `1800 W` is watts beside `let W = 3 mm`, and the
/// constant's references are only its own uses.
#[test]
fn a_unit_spelt_as_a_constant_is_the_unit() {
    let mut c = started();
    let uri = "file:///units.lmd";
    let text = "let W = 3 mm\nlet s = 2\nbead b {\n  width = W\n  power = 1800 W\n  speed = 5 mm/s * s\n}\n";
    c.open(uri, text);
    let at_power = pos(text, "1800 W", 0, 5);
    assert_eq!(
        c.at("textDocument/definition", uri, at_power),
        Value::Null,
        "a unit has no declaration"
    );
    let refs = c.at("textDocument/references", uri, at_power);
    assert!(refs.as_array().is_none_or(|r| r.is_empty()), "{refs}");
    let h = c.at("textDocument/hover", uri, at_power);
    let md = h["contents"]["value"].as_str().unwrap_or_default();
    assert!(md.contains("a power"), "{h}");
    let h = c.at("textDocument/hover", uri, pos(text, "mm/s", 0, 3));
    let md = h["contents"]["value"].as_str().unwrap_or_default();
    assert!(md.contains("`mm/s`") && md.contains("a speed"), "{h}");
    // The constant's own: its declaration and `width = W`, not the unit.
    let refs = c.at("textDocument/references", uri, pos(text, "= W", 0, 2));
    let lines: Vec<u64> = refs
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["range"]["start"]["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, [0, 3], "{refs}");
    // `s` after `*` is the constant, `s` in `mm/s` the second.
    let d = c.at("textDocument/definition", uri, pos(text, "* s", 0, 2));
    assert_eq!(d["range"]["start"]["line"], 1, "{d}");
    assert_eq!(
        c.at("textDocument/definition", uri, pos(text, "mm/s", 0, 3)),
        Value::Null
    );
    stop(c);
}

/// After `=`, completion offers the field's own choices from the block
/// tables, and only the names that field can take.
#[test]
fn completion_after_equals_offers_the_fields_choices() {
    let mut c = started();
    let uri = "file:///kind.lmd";
    let text = "bead b {\n  width = 3 mm\n}\nlet d = 2 mm\nmachine m {\n  kind = \n}\n";
    c.open(uri, text);
    let got = labels(&c.at("textDocument/completion", uri, pos(text, "kind = ", 0, 7)));
    assert_eq!(got, ["robot", "cnc"], "the kind's words, no names");
    // Inside the machine before its kind: either kind's fields.
    let text2 = "machine m {\n  \n}\n";
    c.open("file:///m.lmd", text2);
    let got = labels(&c.at("textDocument/completion", "file:///m.lmd", (1, 2)));
    for f in ["kind", "tool", "dialect", "head"] {
        assert!(got.contains(&f.to_string()), "{f}: {got:?}");
    }
    stop(c);
}

#[test]
fn completion_works_in_a_file_that_does_not_parse_yet() {
    let mut c = started();
    let uri = "file:///new.lmd";
    let text = "part p\n\nbead b {\n  wi\n  height = 6 \n}\n\n";
    let d = c.open(uri, text);
    assert!(
        d.iter().any(|d| d["severity"] == 1),
        "an unfinished file has errors"
    );
    let fields = labels(&c.at("textDocument/completion", uri, pos(text, "wi", 0, 2)));
    for f in ["width", "speed", "model"] {
        assert!(fields.contains(&f.to_string()), "{fields:?}");
    }
    let units = labels(&c.at("textDocument/completion", uri, pos(text, "6 ", 0, 2)));
    assert!(units.contains(&"mm".to_string()), "{units:?}");
    let top = labels(&c.at("textDocument/completion", uri, (7, 0)));
    for k in ["bead", "machine", "loft", "let"] {
        assert!(top.contains(&k.to_string()), "{top:?}");
    }
    stop(c);
}

#[test]
fn every_unit_completion_offers_is_one_lmdc_reads() {
    for u in lmdc::lsp::UNITS {
        assert!(
            lmdc::units::parse_unit(u).is_ok(),
            "`{u}` is not a unit lmdc reads"
        );
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    /// Whatever is typed, wherever the cursor: an answer, never a panic.
    #[test]
    fn no_text_and_no_offset_panics(
        text in "(bead b \\{|machine m \\{ kind = cnc |limits \\{|model = mass_balance\\(|width = 6 |µm|𝜌|\"q\\{|/\\*|//x\n|\\}|\\)|\\[|=|auto|layers|\n| ){0,30}",
        frac in 0.0..=1.0f64,
    ) {
        let offset = (text.len() as f64 * frac) as usize;
        let none = |_: &str| None;
        let _ = lmdc::lsp::hover(&text, offset, &none);
        let _ = lmdc::lsp::completion(&text, offset);
        let _ = lmdc::lsp::definition(&text, offset);
        let _ = lmdc::lsp::references(&text, offset, true);
        let ix = lmdc::lsp::LineIndex::new(&text, lmdc::lsp::Encoding::Utf16);
        let (l, c) = ix.position(&text, offset);
        let back = ix.offset(&text, l, c);
        proptest::prop_assert!(back <= offset && text.is_char_boundary(back));
    }
}

#[test]
fn a_bead_fitted_to_a_sheet_reads_the_sheet_beside_the_file() {
    let mut c = started();
    let path = std::fs::canonicalize("tests/cases/calib/seed_003_fit/input.lmd").unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let uri = format!("file://{}", path.display()).replace(' ', "%20");
    let d = c.open(&uri, &text);
    assert!(d.iter().all(|d| d["severity"] != 1), "{d:?}");
    // Unsaved, the same text has no sheet to read: the compiler says so.
    let d = c.open("untitled:Untitled-1", &text);
    assert!(d.iter().any(|d| d["severity"] == 1), "{d:?}");
    stop(c);
}

#[test]
fn formatting_is_lmdc_fmt_as_one_edit() {
    let mut c = started();
    let uri = "file:///f.lmd";
    let text = "part p\nlet   w =  6 mm   // wide\n";
    c.open(uri, text);
    let edits = c.request(
        "textDocument/formatting",
        json!({ "textDocument": { "uri": uri }, "options": { "tabSize": 2, "insertSpaces": true } }),
    );
    let want = lmdc::fmt::format(text).unwrap();
    assert_ne!(want, text);
    assert_eq!(edits.as_array().unwrap().len(), 1, "{edits}");
    assert_eq!(edits[0]["newText"], want);
    assert_eq!(
        edits[0]["range"]["start"],
        json!({ "line": 0, "character": 0 })
    );
    assert_eq!(
        edits[0]["range"]["end"],
        json!({ "line": 2, "character": 0 })
    );
    stop(c);
}

impl Client {
    /// Sends `body` framed as it is, whatever it holds.
    fn send_raw(&mut self, body: &[u8]) {
        write!(self.stdin, "Content-Length: {}\r\n\r\n", body.len()).unwrap();
        self.stdin.write_all(body).unwrap();
        self.stdin.flush().unwrap();
    }

    /// The error code and id of the next message, which must be an error.
    fn error(&mut self) -> (i64, Value) {
        let m = self.read();
        let code = m["error"]["code"].as_i64();
        (
            code.unwrap_or_else(|| panic!("no error: {m}")),
            m["id"].clone(),
        )
    }
}

/// Issue 39: a framed `[]`, `null`, `{`, invalid UTF-8 or a
/// `Content-Length` of 3·10⁹ stopped the server (exit 2, or an abort after
/// allocating 2.8 GiB). Each is answered with the protocol's error, and the
/// session goes on.
#[test]
fn malformed_messages_are_answered_and_the_session_goes_on() {
    let mut c = started();
    for body in [&b"[]"[..], b"null", b"42", b"{\"jsonrpc\": \"2.0\"}"] {
        c.send_raw(body);
        assert_eq!(c.error(), (-32600, Value::Null), "{body:?}");
    }
    for body in [&b"{"[..], b"\xff\xfe{}", b"{\"a\": \"\xc3\x28\"}"] {
        c.send_raw(body);
        assert_eq!(c.error(), (-32700, Value::Null), "{body:?}");
    }
    // Past the cap: its bytes are skipped as they come, never held, and
    // the frame after them is read.
    let n = lmdc::lsp::transport::MAX_MESSAGE + 1;
    write!(c.stdin, "Content-Length: {n}\r\n\r\n").unwrap();
    let chunk = vec![b' '; 1 << 20];
    let mut left = n as usize;
    while left > 0 {
        let k = left.min(chunk.len());
        c.stdin.write_all(&chunk[..k]).unwrap();
        left -= k;
    }
    assert_eq!(c.error(), (-32700, Value::Null));
    // Headers without `Content-Length`; a body without headers, the next
    // frame's glued to it: answered, and that frame read (issue 38 item 2).
    write!(c.stdin, "Content-Type: application/vscode-jsonrpc\r\n\r\n").unwrap();
    c.stdin.flush().unwrap();
    assert_eq!(c.error(), (-32700, Value::Null));
    write!(c.stdin, "{{\"jsonrpc\": \"2.0\", \"id\": 5}}").unwrap();
    c.send(json!({ "jsonrpc": "2.0", "id": 78, "method": "lmd/unknown", "params": {} }));
    assert_eq!(c.error(), (-32700, Value::Null));
    assert_eq!(c.error(), (-32601, json!(78)));
    // An unknown method, with its id.
    c.send(json!({ "jsonrpc": "2.0", "id": 77, "method": "lmd/unknown", "params": {} }));
    assert_eq!(c.error(), (-32601, json!(77)));
    // Still serving.
    let d = c.open("file:///m.lmd", "part p\nlet x = 1 mm +\n");
    assert!(!d.is_empty());
    stop(c);
}

/// Issue 39: a request before `initialize`, between `initialize` and
/// `initialized`, or after `shutdown` stopped the server (exit 2). Before
/// `initialize` it is refused with -32002, after `shutdown` with -32600;
/// between the two handshake messages it is answered.
#[test]
fn requests_in_every_state_are_answered() {
    let mut c = Client::start();
    let hover = |id: i64| {
        json!({ "jsonrpc": "2.0", "id": id, "method": "textDocument/hover",
                "params": { "textDocument": { "uri": "file:///x.lmd" },
                            "position": { "line": 0, "character": 0 } } })
    };
    c.send(hover(1));
    assert_eq!(c.error(), (-32002, json!(1)));
    c.request("initialize", json!({ "capabilities": {} }));
    let r = c.request("textDocument/hover", hover(0)["params"].clone());
    assert_eq!(r, Value::Null);
    c.notify("initialized", json!({}));
    c.send(json!({ "jsonrpc": "2.0", "id": "again", "method": "initialize", "params": {} }));
    assert_eq!(c.error(), (-32600, json!("again")));
    c.request("shutdown", Value::Null);
    c.send(hover(9));
    assert_eq!(c.error(), (-32600, json!(9)));
    c.notify("exit", Value::Null);
    assert_eq!(c.child.wait().unwrap().code(), Some(0));
}

/// `exit` without `shutdown`, or the input ending, ends the server with
/// status 1, as the protocol asks.
#[test]
fn exit_without_shutdown_is_status_1() {
    let mut c = started();
    c.notify("exit", Value::Null);
    assert_eq!(c.child.wait().unwrap().code(), Some(1));
    let c = started();
    drop(c.stdin);
    let mut child = c.child;
    assert_eq!(child.wait().unwrap().code(), Some(1));
}

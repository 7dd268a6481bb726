//! `lmdc lsp`: a language server on stdio. Diagnostics as you type (the
//! compiler's own: codes, labels, help), hover (a field's meaning, what it
//! takes and its default from the block tables; a name's declaration; what
//! `auto` chose), go to definition and references of names, completion of
//! fields, statements, words, names and units, and formatting (`lmdc fmt`).
//!
//! The framing is lmdc's own ([`transport`]: capped, and every malformed
//! message answered), the messages `lsp-server`'s (rust-analyzer's); the
//! few LSP types it answers with are built as JSON here. Every request is
//! answered from the latest text of the document (full sync).

mod features;
mod names;
mod scan;
mod text;
pub mod transport;

pub use features::{completion, definition, hover, references, Completion, Hover, UNITS};
pub use text::{Encoding, LineIndex};

use crate::diag::{Diagnostic, Severity};
use crate::pipeline;
use lsp_server::{Message, Notification, Request, Response};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::error::Error;
use std::io::{BufRead, Write};

/// What can end the server: its output failing (the client gone).
pub type ServerError = Box<dyn Error + Send + Sync>;

/// Runs the server on stdin/stdout until the client says `exit` (or its
/// input ends); the exit status the protocol asks for: 0 after
/// `shutdown`, 1 without.
pub fn run_stdio() -> Result<u8, ServerError> {
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    Ok(serve(&mut stdin.lock(), &mut stdout.lock())?)
}

/// An open document.
struct Doc {
    text: String,
    index: LineIndex,
    /// What `auto` chose in the last compile that succeeded for this text
    /// (kept so a hover does not compile the file again).
    chosen: Option<Chosen>,
}

/// What a compiled plan chose: its layer count and the ranges its deposits
/// lay (heights, track spacing), as shown.
struct Chosen {
    layers: usize,
    heights: Option<String>,
    pitch: Option<String>,
    /// Each robot's turn about the beam (`spin`), as `name: N°`.
    spin: Option<String>,
}

/// Where the session is: before `initialize`, serving, or after
/// `shutdown` (only `exit` is heeded then).
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Uninitialized,
    Running(Encoding),
    ShutDown,
}

/// Serves one client from `input` to `output` until `exit` or the end of
/// the input; the exit status (0 after `shutdown`, else 1). Nothing the
/// client sends ends it earlier: a frame that is no JSON is answered with
/// a parse error (-32700), a value that is no request, response or
/// notification with an invalid request (-32600), an unknown method with
/// -32601, a request before `initialize` with -32002 and one after
/// `shutdown` with an invalid request; only failing to write ends it
/// with an error.
pub fn serve(input: &mut impl BufRead, output: &mut impl Write) -> std::io::Result<u8> {
    let mut state = State::Uninitialized;
    let mut docs: HashMap<String, Doc> = HashMap::new();
    loop {
        let mut incoming = transport::read(input)?;
        if let transport::Incoming::Behind(why, frame) = incoming {
            transport::write(output, &error(Value::Null, PARSE_ERROR, &why))?;
            incoming = *frame;
        }
        let msg = match incoming {
            transport::Incoming::End => return Ok(exit_status(state)),
            // `read` puts nothing behind a frame but a frame.
            transport::Incoming::Behind(..) => continue,
            transport::Incoming::Malformed(why) => {
                transport::write(output, &error(Value::Null, PARSE_ERROR, &why))?;
                continue;
            }
            transport::Incoming::Value(v) => match message(v) {
                Ok(m) => m,
                Err(reply) => {
                    transport::write(output, &reply)?;
                    continue;
                }
            },
        };
        // A bug the compiler panics on fails the one request (an internal
        // error), not the session.
        match msg {
            Message::Request(req) => {
                let id = serde_json::to_value(&req.id).unwrap_or(Value::Null);
                let reply = guarded(|| request(&mut state, &docs, req)).unwrap_or_else(|| {
                    error(
                        id,
                        INTERNAL_ERROR,
                        "lmdc stopped on an internal error (a bug)",
                    )
                });
                transport::write(output, &reply)?;
            }
            Message::Notification(n) if n.method == "exit" => return Ok(exit_status(state)),
            Message::Notification(n) => {
                let State::Running(encoding) = state else {
                    continue;
                };
                let note = guarded(|| {
                    let uri = update(&mut docs, n, encoding)?;
                    let params = docs.get_mut(&uri).map(|d| publish(&uri, d));
                    Some(Notification::new(
                        "textDocument/publishDiagnostics".into(),
                        params,
                    ))
                });
                if let Some(note) = note.flatten() {
                    transport::write(output, &to_value(Message::Notification(note)))?;
                }
            }
            Message::Response(_) => {}
        }
    }
}

/// `f`'s result, or `None` if it panicked (the panic's message went to
/// stderr, as the command line's does).
fn guarded<T>(f: impl FnOnce() -> T) -> Option<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).ok()
}

/// The exit status for ending in `state`: 0 after `shutdown`, else 1.
fn exit_status(state: State) -> u8 {
    match state {
        State::ShutDown => 0,
        _ => 1,
    }
}

/// JSON-RPC's codes for a frame that is no JSON and a value that is no
/// message.
const PARSE_ERROR: i32 = lsp_server::ErrorCode::ParseError as i32;
const INVALID_REQUEST: i32 = lsp_server::ErrorCode::InvalidRequest as i32;
/// JSON-RPC's code for a request the server failed on.
const INTERNAL_ERROR: i32 = lsp_server::ErrorCode::InternalError as i32;

/// An error response to the request `id` (`null` when it has none).
fn error(id: Value, code: i32, message: &str) -> Value {
    json!({ "jsonrpc": "2.0", "id": id, "error": { "code": code, "message": message } })
}

/// A message as JSON, with the protocol's `"jsonrpc": "2.0"`.
fn to_value(m: Message) -> Value {
    let mut v = serde_json::to_value(m).unwrap_or(Value::Null);
    if let Some(o) = v.as_object_mut() {
        o.insert("jsonrpc".into(), json!("2.0"));
    }
    v
}

/// The message `v` is, or the invalid-request error to answer it with:
/// a request has a method and an id (a number or a text), a notification
/// a method and no id, a response an id and a result or an error.
fn message(v: Value) -> Result<Message, Value> {
    let id = v.get("id").cloned().unwrap_or(Value::Null);
    let invalid = |why: &str| error(id.clone(), INVALID_REQUEST, why);
    let Some(o) = v.as_object() else {
        return Err(invalid(
            "a message is a JSON object (lmdc takes no batches)",
        ));
    };
    let kind = match (o.get("method"), o.contains_key("id")) {
        (Some(Value::String(_)), true) => "request",
        (Some(Value::String(_)), false) => "notification",
        (None, true) if o.contains_key("result") || o.contains_key("error") => "response",
        _ => {
            return Err(invalid(
                "a message has a `method` (a request or a notification) or is a response",
            ))
        }
    };
    let id = match &id {
        Value::String(_) | Value::Number(_) | Value::Null => id.clone(),
        _ => Value::Null,
    };
    serde_json::from_value::<Message>(v)
        .ok()
        .filter(|m| match m {
            Message::Request(_) => kind == "request",
            Message::Notification(_) => kind == "notification",
            Message::Response(_) => kind == "response",
        })
        .ok_or_else(|| {
            error(
                id,
                INVALID_REQUEST,
                &format!("this is no {kind} lmdc reads"),
            )
        })
}

/// Answers a request in `state`, which `initialize` and `shutdown` move on.
fn request(state: &mut State, docs: &HashMap<String, Doc>, req: Request) -> Value {
    let id = serde_json::to_value(&req.id).unwrap_or(Value::Null);
    match (*state, req.method.as_str()) {
        (State::Uninitialized, "initialize") => {
            let encoding = negotiate(&req.params);
            *state = State::Running(encoding);
            json!({ "jsonrpc": "2.0", "id": id, "result": capabilities(encoding) })
        }
        (State::Uninitialized, _) => error(
            id,
            lsp_server::ErrorCode::ServerNotInitialized as i32,
            "the server is not initialized: `initialize` comes first",
        ),
        (State::ShutDown, _) => error(
            id,
            INVALID_REQUEST,
            "the server is shut down: only `exit` is heeded",
        ),
        (State::Running(_), "initialize") => {
            error(id, INVALID_REQUEST, "`initialize` was already received")
        }
        (State::Running(_), "shutdown") => {
            *state = State::ShutDown;
            json!({ "jsonrpc": "2.0", "id": id, "result": null })
        }
        (State::Running(_), _) => to_value(Message::Response(answer(docs, req))),
    }
}

/// What the server offers, answering `initialize`.
fn capabilities(encoding: Encoding) -> Value {
    let name = match encoding {
        Encoding::Utf8 => "utf-8",
        Encoding::Utf16 => "utf-16",
    };
    json!({
        "capabilities": {
            "positionEncoding": name,
            "textDocumentSync": 1,
            "hoverProvider": true,
            "definitionProvider": true,
            "referencesProvider": true,
            "completionProvider": { "triggerCharacters": [" ", "="] },
            "documentFormattingProvider": true,
        },
        "serverInfo": { "name": "lmdc", "version": env!("CARGO_PKG_VERSION") },
    })
}

/// UTF-8 positions if the client offers them, else the protocol's UTF-16.
fn negotiate(params: &Value) -> Encoding {
    let offered = params
        .pointer("/capabilities/general/positionEncodings")
        .and_then(Value::as_array);
    match offered {
        Some(e) if e.iter().any(|x| x == "utf-8") => Encoding::Utf8,
        _ => Encoding::Utf16,
    }
}

/// Applies `didOpen`, `didChange` and `didClose`; the document to publish
/// diagnostics for, if any.
fn update(docs: &mut HashMap<String, Doc>, n: Notification, encoding: Encoding) -> Option<String> {
    let uri = n.params.pointer("/textDocument/uri")?.as_str()?.to_string();
    let text = match n.method.as_str() {
        "textDocument/didOpen" => n.params.pointer("/textDocument/text")?.as_str()?,
        // Full sync: the last change holds the whole text.
        "textDocument/didChange" => n
            .params
            .pointer("/contentChanges")?
            .as_array()?
            .last()?
            .get("text")?
            .as_str()?,
        "textDocument/didClose" => {
            docs.remove(&uri);
            return None;
        }
        _ => return None,
    };
    let index = LineIndex::new(text, encoding);
    docs.insert(
        uri.clone(),
        Doc {
            text: text.to_string(),
            index,
            chosen: None,
        },
    );
    Some(uri)
}

/// The `publishDiagnostics` parameters for a document: the compiler's
/// diagnostics, each at its first label, the other labels as related
/// information.
fn publish(uri: &str, doc: &mut Doc) -> Value {
    // A document past what `lmdc check` reads is not compiled either.
    let max = crate::sema::data::MAX_SOURCE;
    if doc.text.len() as u64 > max {
        let why = format!("it is larger than {} MB", max >> 20);
        let d = crate::diag::message::usage::unreadable(uri, &why);
        return json!({ "uri": uri, "diagnostics": [diagnostic(uri, doc, &d)] });
    }
    let c = compile(uri, &doc.text);
    doc.chosen = c.program.as_ref().map(|p| chosen_by(p.ir()));
    let items: Vec<Value> = c
        .diagnostics
        .iter()
        .map(|d| diagnostic(uri, doc, d))
        .collect();
    json!({ "uri": uri, "diagnostics": items })
}

fn diagnostic(uri: &str, doc: &Doc, d: &Diagnostic) -> Value {
    let range = |s: crate::span::Span| range(doc, s.start, s.end);
    let first = d.labels.first();
    let mut message = d.message.clone();
    if let Some(l) = first.filter(|l| !l.text.is_empty()) {
        message.push_str(&format!("\n{}", l.text));
    }
    if let Some(h) = &d.help {
        message.push_str(&format!("\nhelp: {h}"));
    }
    let related: Vec<Value> = d
        .labels
        .iter()
        .skip(1)
        .map(|l| json!({ "location": { "uri": uri, "range": range(l.span) }, "message": l.text }))
        .collect();
    json!({
        "range": first.map_or_else(|| range(crate::span::Span::new(0, 0)), |l| range(l.span)),
        "severity": match d.severity { Severity::Error => 1, Severity::Warning => 2 },
        "code": d.code.as_str(),
        "source": "lmdc",
        "message": message,
        "relatedInformation": related,
    })
}

fn range(doc: &Doc, start: usize, end: usize) -> Value {
    let (l0, c0) = doc.index.position(&doc.text, start);
    let (l1, c1) = doc.index.position(&doc.text, end);
    json!({ "start": { "line": l0, "character": c0 }, "end": { "line": l1, "character": c1 } })
}

/// The requests the server answers (after `initialize`, before
/// `shutdown`).
const METHODS: [&str; 5] = [
    "textDocument/hover",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/completion",
    "textDocument/formatting",
];

/// Answers one request.
fn answer(docs: &HashMap<String, Doc>, req: Request) -> Response {
    if !METHODS.contains(&req.method.as_str()) {
        return Response::new_err(
            req.id,
            lsp_server::ErrorCode::MethodNotFound as i32,
            format!("lmdc does not answer {}", req.method),
        );
    }
    let doc = req
        .params
        .pointer("/textDocument/uri")
        .and_then(Value::as_str)
        .and_then(|u| docs.get(u).map(|d| (u.to_string(), d)));
    let Some((uri, doc)) = doc else {
        return Response::new_ok(req.id, Value::Null);
    };
    if req.method == "textDocument/formatting" {
        return format(req.id, doc);
    }
    let offset = || {
        let line = req.params.pointer("/position/line")?.as_u64()? as u32;
        let ch = req.params.pointer("/position/character")?.as_u64()? as u32;
        Some(doc.index.offset(&doc.text, line, ch))
    };
    let Some(at) = offset() else {
        return Response::new_ok(req.id, Value::Null);
    };
    let result = match req.method.as_str() {
        "textDocument/hover" => {
            let chosen = |key: &str| chosen(doc.chosen.as_ref()?, key);
            hover(&doc.text, at, &chosen).map_or(Value::Null, |h| {
                json!({
                    "contents": { "kind": "markdown", "value": h.markdown },
                    "range": range(doc, h.span.start, h.span.end),
                })
            })
        }
        "textDocument/definition" => definition(&doc.text, at).map_or(
            Value::Null,
            |s| json!({ "uri": uri, "range": range(doc, s.start, s.end) }),
        ),
        "textDocument/references" => {
            let with = req
                .params
                .pointer("/context/includeDeclaration")
                .and_then(Value::as_bool)
                .unwrap_or(true);
            let spans = references(&doc.text, at, with);
            Value::Array(
                spans
                    .iter()
                    .map(|s| json!({ "uri": uri, "range": range(doc, s.start, s.end) }))
                    .collect(),
            )
        }
        "textDocument/completion" => Value::Array(
            completion(&doc.text, at)
                .into_iter()
                .map(|c| {
                    json!({
                        "label": c.label,
                        "kind": c.kind,
                        "detail": c.detail,
                        "documentation": { "kind": "markdown", "value": c.documentation },
                        "insertText": c.insert,
                    })
                })
                .collect(),
        ),
        _ => {
            return Response::new_err(
                req.id,
                lsp_server::ErrorCode::MethodNotFound as i32,
                format!("lmdc does not answer {}", req.method),
            )
        }
    };
    Response::new_ok(req.id, result)
}

/// `textDocument/formatting`: `lmdc fmt`'s layout as one edit of the whole
/// text (none when it is formatted already); a file that does not parse is
/// refused with the reason, as `lmdc fmt` refuses it.
fn format(id: lsp_server::RequestId, doc: &Doc) -> Response {
    match crate::fmt::format(&doc.text) {
        Ok(new) if new == doc.text => Response::new_ok(id, json!([])),
        Ok(new) => Response::new_ok(
            id,
            json!([{ "range": range(doc, 0, doc.text.len()), "newText": new }]),
        ),
        Err(e) => {
            let why = match e {
                crate::fmt::FmtError::Syntax(d) => {
                    format!("the file does not parse: {}", d.message)
                }
                crate::fmt::FmtError::Changed => "the layout would change the meaning".into(),
            };
            Response::new_err(
                id,
                lsp_server::ErrorCode::RequestFailed as i32,
                format!("lmdc fmt: {why}"),
            )
        }
    }
}

/// Compiles a document as `lmdc check` would: the data files it names
/// (`fit(…, data = "…")`) read beside it when it is a file on disk.
fn compile(uri: &str, text: &str) -> pipeline::Compiled {
    let dir = file_path(uri).and_then(|p| p.parent().map(std::path::Path::to_path_buf));
    let reader: crate::sema::DataReader = std::rc::Rc::new(move |name: &str, kind| match &dir {
        Some(d) => crate::sema::data::read_file(&d.join(name), kind),
        None => Err("the document is not a file on disk".into()),
    });
    match pipeline::compile_reading(text, None, &mut (), reader) {
        Ok((c, _)) => c,
        Err(_) => unreachable!("no machine was named"),
    }
}

/// The path of a `file://` URI (its `%XX` escapes decoded).
fn file_path(uri: &str) -> Option<std::path::PathBuf> {
    let rest = uri.strip_prefix("file://")?;
    let b = rest.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |k: usize| b.get(k).and_then(|c| (*c as char).to_digit(16));
        match (b[i], hex(i + 1), hex(i + 2)) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, _, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    Some(std::path::PathBuf::from(String::from_utf8(out).ok()?))
}

/// What the compiled plan chose for `key = auto`: the layer count and the
/// heights it lays, or the track spacing.
fn chosen(c: &Chosen, key: &str) -> Option<String> {
    match key {
        "layers" | "layer_height" => Some(format!(
            "{} layers, {} thick",
            c.layers,
            c.heights.as_deref()?
        )),
        "offset" => Some(format!("tracks {} apart", c.pitch.as_deref()?)),
        "spin" => Some(format!(
            "the tool turned about the beam by {}",
            c.spin.as_deref()?
        )),
        _ => None,
    }
}

/// What `ir` chose, from its laser-on points.
fn chosen_by(ir: &crate::ir::Program) -> Chosen {
    let on = || {
        ir.layers
            .iter()
            .flat_map(|l| &l.paths)
            .flat_map(|p| &p.points)
            .filter(|p| p.laser_on)
    };
    let span = |f: &dyn Fn(&crate::ir::Point) -> f32| {
        let (lo, hi) = on().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(f(p)), hi.max(f(p)))
        });
        (lo.is_finite() && hi.is_finite()).then(|| {
            if (hi - lo).abs() < 5e-4 {
                format!("{} mm", crate::units::short(lo as f64))
            } else {
                format!(
                    "{} … {} mm",
                    crate::units::short(lo as f64),
                    crate::units::short(hi as f64)
                )
            }
        })
    };
    let spins: Vec<String> = ir
        .machines
        .iter()
        .filter_map(|m| match m {
            crate::ir::Machine::Robot(r) => Some(format!(
                "{}° on `{}`",
                crate::units::short(r.spin.deg()),
                r.name
            )),
            _ => None,
        })
        .collect();
    Chosen {
        layers: ir.layers.len(),
        heights: span(&|p| p.layer_height),
        pitch: span(&|p| p.pitch),
        spin: (!spins.is_empty()).then(|| spins.join(", ")),
    }
}

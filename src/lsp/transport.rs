//! The language server's framing: `Content-Length` headers and a JSON body,
//! read with hard caps, so that what a client sends cannot stop the server
//! or take its memory. A header line is at most [`MAX_HEADER`] bytes and a
//! body at most [`MAX_MESSAGE`]; a body past it is skipped, not held. What
//! cannot be read as one JSON value is [`Incoming::Malformed`], for the
//! server to answer and go on; only the end of the input ends it.
//! (`lsp-server`'s reader allocated whatever `Content-Length` said and
//! stopped the server at the first frame it could not read.)

use serde_json::Value;
use std::io::{self, BufRead, Read, Write};

/// Most bytes of one message's body: a document of the most a source may
/// have ([`crate::sema::data::MAX_SOURCE`]), escaped in JSON, with room.
pub const MAX_MESSAGE: u64 = 4 * crate::sema::data::MAX_SOURCE;

/// Most bytes of one header line (the protocol's two headers take less
/// than a hundred).
pub const MAX_HEADER: u64 = 8 << 10;

/// What the next frame of the input holds.
#[derive(Debug)]
pub enum Incoming {
    /// A JSON value.
    Value(Value),
    /// A frame that holds no JSON value, and why: to be answered with a
    /// parse error.
    Malformed(String),
    /// Bytes that were no frame (a body sent without its headers), and why,
    /// then the frame whose `Content-Length` followed them on their line:
    /// the bytes are answered with a parse error, the frame as it reads.
    Behind(String, Box<Incoming>),
    /// The input ended.
    End,
}

/// Reads the next frame from `r`.
pub fn read(r: &mut impl BufRead) -> io::Result<Incoming> {
    let mut length: Option<Result<u64, String>> = None;
    let mut any = false;
    // Bytes before a `Content-Length` on its line: the headers were left
    // out of a message, and the next frame's are glued to its body.
    let mut junk = None;
    loop {
        let Some(line) = header_line(r)? else {
            return Ok(Incoming::End);
        };
        let line = line.trim_ascii();
        if line.is_empty() {
            // Blank lines before a frame's headers are not its end.
            if any {
                break;
            }
            continue;
        }
        any = true;
        let line = match glued_header(line) {
            Some(k) => {
                junk = Some(k);
                &line[k..]
            }
            None => line,
        };
        let text = String::from_utf8_lossy(line);
        if let Some((name, value)) = text.split_once(':') {
            if name.trim().eq_ignore_ascii_case("content-length") {
                length = Some(
                    value
                        .trim()
                        .parse::<u64>()
                        .map_err(|_| format!("`Content-Length: {}` is no length", value.trim())),
                );
            }
        }
    }
    let frame = frame(r, length)?;
    Ok(match junk {
        Some(n) => Incoming::Behind(
            format!("{n} bytes without `Content-Length` before a frame"),
            Box::new(frame),
        ),
        None => frame,
    })
}

/// Where a `Content-Length` header starts in a line that holds something
/// else before it (the end of a body sent without headers), if it does.
fn glued_header(line: &[u8]) -> Option<usize> {
    const NAME: &[u8] = b"content-length:";
    let k = line
        .windows(NAME.len())
        .position(|w| w.eq_ignore_ascii_case(NAME))?;
    // A header's name at the line's start is the header itself.
    (k > 0).then_some(k)
}

/// The body a frame's headers announce, read from `r`.
fn frame(r: &mut impl BufRead, length: Option<Result<u64, String>>) -> io::Result<Incoming> {
    let n = match length {
        None => {
            return Ok(Incoming::Malformed(
                "a frame without `Content-Length`".into(),
            ))
        }
        Some(Err(why)) => return Ok(Incoming::Malformed(why)),
        Some(Ok(n)) => n,
    };
    if n > MAX_MESSAGE {
        // Skipped as it comes, never held: the next frame follows it.
        io::copy(&mut r.take(n), &mut io::sink())?;
        return Ok(Incoming::Malformed(format!(
            "a message of {n} bytes, more than the {MAX_MESSAGE} lmdc reads"
        )));
    }
    let mut body = Vec::new();
    r.take(n).read_to_end(&mut body)?;
    if (body.len() as u64) < n {
        return Ok(Incoming::End);
    }
    Ok(match serde_json::from_slice(&body) {
        Ok(v) => Incoming::Value(v),
        Err(e) => Incoming::Malformed(format!("the message is no JSON: {e}")),
    })
}

/// The next header line (its end included), at most [`MAX_HEADER`] bytes
/// kept of it; `None` at the end of the input.
fn header_line(r: &mut impl BufRead) -> io::Result<Option<Vec<u8>>> {
    let mut line = Vec::new();
    let n = r.take(MAX_HEADER).read_until(b'\n', &mut line)?;
    if n == 0 {
        return Ok(None);
    }
    if !line.ends_with(b"\n") && n as u64 == MAX_HEADER {
        // The rest of an overlong line, dropped a buffer at a time.
        loop {
            let buf = r.fill_buf()?;
            if buf.is_empty() {
                break;
            }
            match buf.iter().position(|&b| b == b'\n') {
                Some(k) => {
                    r.consume(k + 1);
                    break;
                }
                None => {
                    let k = buf.len();
                    r.consume(k);
                }
            }
        }
    }
    Ok(Some(line))
}

/// Writes `v` as one frame to `w`.
pub fn write(w: &mut impl Write, v: &Value) -> io::Result<()> {
    let body = v.to_string();
    write!(w, "Content-Length: {}\r\n\r\n{body}", body.len())?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(input: &[u8]) -> Vec<String> {
        let mut r = io::BufReader::new(input);
        let mut out = Vec::new();
        loop {
            match read(&mut r).unwrap() {
                Incoming::Value(v) => out.push(v.to_string()),
                Incoming::Malformed(why) => out.push(format!("malformed: {why}")),
                Incoming::Behind(why, then) => {
                    out.push(format!("malformed: {why}"));
                    match *then {
                        Incoming::Value(v) => out.push(v.to_string()),
                        other => out.push(format!("{other:?}")),
                    }
                }
                Incoming::End => return out,
            }
        }
    }

    #[test]
    fn frames_past_a_broken_one_are_read() {
        let big = format!("Content-Length: {}\r\n\r\n", MAX_MESSAGE + 1);
        let mut input = big.into_bytes();
        input.extend(vec![b' '; (MAX_MESSAGE + 1) as usize]);
        input.extend(b"Content-Length: 1\r\n\r\n{");
        input.extend(b"Content-Length: 2\r\n\r\n\xff\xfe");
        input.extend(b"Content-Length: x\r\n\r\n");
        input.extend(b"Content-Length: 4\r\n\r\nnull");
        input.extend(b"Content-Length: 2\r\n\r\n[]");
        let got = frames(&input);
        assert_eq!(got.len(), 6, "{got:?}");
        assert!(got[0].starts_with("malformed: a message of"), "{got:?}");
        assert!(got[1].starts_with("malformed: the message is no JSON"));
        assert!(got[2].starts_with("malformed: the message is no JSON"));
        assert!(got[3].starts_with("malformed: `Content-Length: x`"));
        assert_eq!(got[4..], ["null", "[]"]);
    }

    #[test]
    fn an_endless_header_line_is_dropped() {
        let mut input = vec![b'a'; 3 * MAX_HEADER as usize];
        input.extend(b"\r\nContent-Length: 2\r\n\r\n{}");
        assert_eq!(frames(&input), ["{}"]);
    }

    #[test]
    fn a_body_without_headers_is_malformed_and_the_next_frame_read() {
        let input = b"{\"id\": 1}Content-Length: 2\r\n\r\n[]Content-Type: x\r\n\r\nContent-Length: 4\r\n\r\nnull";
        assert_eq!(
            frames(input),
            [
                "malformed: 9 bytes without `Content-Length` before a frame",
                "[]",
                "malformed: a frame without `Content-Length`",
                "null"
            ]
        );
    }
}

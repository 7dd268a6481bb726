//! Fuzz target: any bytes as what a client sends the language server — the
//! session is served to its end, every malformed frame answered (issue 39:
//! a framed `[]`, invalid UTF-8 or a huge `Content-Length` stopped it):
//! never a panic, a hang or a runaway allocation. Run with
//! `cargo fuzz run lsp`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = data;
    let status = lmdc::lsp::serve(&mut input, &mut std::io::sink());
    assert!(matches!(status, Ok(0 | 1)), "{status:?}");
});

//! Fuzz target: any text through parse, check, slicing, IR checks and both back
//! ends must end in a program or diagnostics — never a panic, hang or runaway
//! allocation. Run with `cargo fuzz run compile` (nightly).
#![no_main]

use libfuzzer_sys::fuzz_target;
use lmdc::back::{MemorySink, Templates};
use lmdc::pipeline::{compile, emit};

fuzz_target!(|data: &[u8]| {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let c = compile(src, &mut ());
    let _ = lmdc::diag::render(&c.diagnostics, "fuzz.lmd", src, false);
    if let Some(p) = c.program {
        if p.ir().point_count() > 200_000 {
            return; // valid but slow to emit in a fuzz loop
        }
        let mut sink = MemorySink::default();
        let _ = emit(&p, &Templates::builtin().unwrap(), &mut sink, &mut ());
    }
});

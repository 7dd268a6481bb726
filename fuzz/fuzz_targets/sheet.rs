//! Fuzz target: any bytes as a measurement sheet, read and fitted as
//! `lmdc fit` and `fit(…, data = …)` do — diagnostics or fits, never a
//! panic, a hang or a runaway allocation. Run with `cargo fuzz run sheet`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lmdc::bead::fit::{self, Given, Kind};
use lmdc::bead::sheet;
use lmdc::units::{Density, MassFlow};

fuzz_target!(|data: &[u8]| {
    let Ok(bytes) = lmdc::sema::data::read_capped(data, lmdc::sema::data::Data::Sheet) else {
        return;
    };
    let Ok(text) = String::from_utf8(bytes) else {
        return;
    };
    let Ok(s) = sheet::read(&text) else {
        return;
    };
    let given = Given {
        density: Some(Density(0.0079)),
        feed: Some(MassFlow(0.2)),
    };
    for k in Kind::ALL {
        if let Err(e) = fit::fit(&s, k, given) {
            let _ = lmdc::diag::sheet::fault(&e, k, s.header);
        }
    }
});

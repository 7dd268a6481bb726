//! `src/back/names.rs` is not wired into the library yet (src/back/mod.rs is
//! being rewritten): compiled here so its tests run. Remove this file once
//! `pub mod names;` is in src/back/mod.rs.

#[path = "../src/back/names.rs"]
mod names;

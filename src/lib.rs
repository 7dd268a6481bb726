#![doc = include_str!("../ARCHITECTURE.md")]
#![warn(missing_docs)]

pub mod back;
pub mod bead;
pub mod collision;
pub mod control;
pub mod deposit;
pub mod diag;
pub mod fill;
pub mod fmt;
pub mod geometry;
pub mod invalid;
pub mod ir;
#[cfg(all(test, feature = "json-schema"))]
mod json_schema;
pub mod lower;
pub mod lsp;
pub mod numbers;
pub mod overrides;
pub mod pipeline;
pub mod plan;
pub mod preview;
pub mod provenance;
pub mod report;
pub mod sema;
pub mod slice;
pub mod span;
pub mod style;
pub mod syntax;
pub mod target;
#[cfg(test)]
mod test_random;
pub mod thermal;
pub mod units;
pub mod verify;

pub use pipeline::Options;

/// Compiles `source` as `options` say (`--machine`, `--set`, the file the
/// headers name) — the library's front door for tools and property tests
/// (docs/testing.md): the verified program — its IR ([`verify::Verified::ir`]),
/// each machine's motion plan ([`verify::VerifiedMachine::plan`], walked
/// with a [`plan::Visit`]) and its warnings — or every diagnostic when it has
/// errors or the options do not fit the file (`lmd::no-such-machine`,
/// `lmd::bad-set`).
///
/// ```
/// let src = std::fs::read_to_string("examples/flange.lmd").unwrap();
/// let options = lmdc::Options {
///     set: vec!["OD=90 mm".parse().unwrap()],
///     ..Default::default()
/// };
/// let program = lmdc::compile(&src, &options).unwrap();
/// assert_eq!(program.ir().part, "flange");
/// for m in program.machines() {
///     let mut deposits = 0;
///     m.plan().walk(&mut |mv: &lmdc::plan::Move| deposits += mv.deposits() as usize);
///     assert!(deposits > 0);
/// }
/// ```
pub fn compile(source: &str, options: &Options) -> Result<verify::Verified, diag::Diagnostics> {
    match pipeline::compile_with(source, options, &mut ()) {
        Ok(c) => c.program.ok_or(c.diagnostics),
        Err(e) => {
            let mut d = diag::Diagnostics::new();
            d.push(diag::usage::refused(&e));
            Err(d)
        }
    }
}

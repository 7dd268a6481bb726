//! Deterministic random numbers for the crate's own tests: a xorshift
//! generator, so a test's random cases are the same on every run and
//! every machine without a crate for it.

/// Uniform numbers in `[0, 1)` from `seed` (53 bits each), xorshift64.
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

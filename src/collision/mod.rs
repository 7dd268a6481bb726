//! Nothing the machine carries hits anything (docs/collision.md): the head's
//! solids ([`head`]) against the plate, the fixtures and the part as it grows
//! ([`material`]), at every pose of the plan.

pub mod arm;
pub mod capsule;
pub mod head;
pub mod material;
pub mod sample_tree;
pub mod surface;

/// Halving between `good` (where `ok` holds) and `bad` (where it does not)
/// until they are within `tol`: the last value found to hold, the nearest
/// `bad` — the largest clear diameter, the least clear raise.
pub fn bisect(mut good: f64, mut bad: f64, tol: f64, ok: impl Fn(f64) -> bool) -> f64 {
    while (bad - good).abs() > tol {
        let mid = (good + bad) / 2.0;
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}

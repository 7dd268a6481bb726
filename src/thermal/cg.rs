//! Preconditioned conjugate gradients for a step of a graph of columns
//! (islands that merged, docs/thermal.md, *Islands*): the implicit step's
//! matrix is symmetric and positive definite (the heat capacities over the
//! step on a weighted graph Laplacian), and the tree's exact solve with
//! the joins left out differs from it by a matrix of rank the number of
//! joins, so the iteration converges in about as many steps as there are
//! joins, each linear in the nodes.

/// The residual the iteration stops at, relative to the right-hand side's
/// (2-norms): far below what a temperature is known to, and reached in a
/// step or two past the number of joins.
pub const TOLERANCE: f64 = 1e-12;

/// The most iterations a step takes: past it the step is unsolved and the
/// prediction falls back to one column (docs/thermal.md, *Islands*).
pub const MAX_ITERATIONS: usize = 64;

#[cfg(test)]
thread_local! {
    /// The most iterations, lowered by a test to reach the fallback.
    pub static ITERATIONS: std::cell::Cell<usize> = const { std::cell::Cell::new(MAX_ITERATIONS) };
}

/// The most iterations a step takes here ([`MAX_ITERATIONS`]; a test's
/// own limit under test).
fn most() -> usize {
    #[cfg(test)]
    return ITERATIONS.with(|c| c.get());
    #[cfg(not(test))]
    MAX_ITERATIONS
}

/// Solves `A·x = b` for a symmetric positive definite `A` (`apply`: `x ↦
/// A·x`) by conjugate gradients preconditioned by `precondition` (`r ↦
/// M⁻¹·r`, `M` symmetric positive definite), from `M⁻¹·b`. Returns the
/// solution and whether its residual is within [`TOLERANCE`] of `b`'s
/// norm by [`MAX_ITERATIONS`] (else the last iterate, or the start where
/// an iterate is not finite).
pub fn solve(
    b: &[f64],
    precondition: impl Fn(&[f64]) -> Vec<f64>,
    apply: impl Fn(&[f64]) -> Vec<f64>,
) -> (Vec<f64>, bool) {
    let goal = TOLERANCE * norm(b);
    let mut x = precondition(b);
    let mut r: Vec<f64> = b.iter().zip(apply(&x)).map(|(b, a)| b - a).collect();
    if norm(&r) <= goal {
        return (x, true);
    }
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let start = x.clone();
    for _ in 0..most() {
        let ap = apply(&p);
        let pap = dot(&p, &ap);
        // A breakdown (rounding past convergence, or a matrix not as
        // assumed): stop with what there is.
        if pap.is_nan() || pap <= 0.0 || !rz.is_finite() {
            break;
        }
        let alpha = rz / pap;
        for ((x, r), (p, ap)) in x.iter_mut().zip(&mut r).zip(p.iter().zip(&ap)) {
            *x += alpha * p;
            *r -= alpha * ap;
        }
        if norm(&r) <= goal {
            return (x, true);
        }
        z = precondition(&r);
        let next = dot(&r, &z);
        let beta = next / rz;
        rz = next;
        for (p, z) in p.iter_mut().zip(&z) {
            *p = z + beta * *p;
        }
    }
    if x.iter().all(|v| v.is_finite()) {
        (x, false)
    } else {
        (start, false)
    }
}

/// The dot product of two vectors.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}

/// The 2-norm of a vector.
fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

//! The motion writer's number formatting: the same text as
//! [`push_fixed`](crate::numbers::push_fixed) and
//! [`push_trimmed`](crate::numbers::push_trimmed) (tests hold them equal), but
//! written in place into a preallocated slice. Over millions of lines the `Vec`
//! appends of the general versions cost more than the digits: every
//! `extend_from_slice` of a runtime length is a `memcpy` call, and `f64::round` is a
//! libm call on baseline x86-64.

pub(crate) use crate::numbers::POW10;

/// "00" "01" … "99".
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Most bytes [`put_fixed`] writes: sign, 19 digits, point, 9 decimals.
pub(crate) const MAX_NUMBER: usize = 30;

/// `s` rounded half away from zero, as `f64::round` does, without the libm call:
/// the fractional part `s − trunc(s)` of a double is exact, so the comparison with
/// one half is too. Only for `|s| < 2^63`.
#[inline(always)]
fn round_i64(s: f64) -> i64 {
    let i = s as i64;
    let frac = s - i as f64;
    // Branch-free: the fractions of coordinates are random, a branch would
    // mispredict half the time.
    i + (frac >= 0.5) as i64 - (frac <= -0.5) as i64
}

/// Whether scaled value `s` prints as a number: finite and within i64 (NaN fails
/// the comparison).
#[inline(always)]
fn in_range(s: f64) -> bool {
    s.abs() < 9.0e18
}

/// Number of decimal digits of `n` (at least 1), without a loop: from the bit
/// length (log10(2) ≈ 1233/4096), corrected by one comparison.
#[inline(always)]
fn digits(n: u64) -> usize {
    let bits = 64 - (n | 1).leading_zeros() as usize;
    let d = (bits * 1233) >> 12; // ≤ the digit count, ≥ it minus one
    d + ((n | 1) >= POW10_U64[d]) as usize
}

/// 10^0 … 10^19.
const POW10_U64: [u64; 20] = {
    let mut t = [1u64; 20];
    let mut i = 1;
    while i < 20 {
        t[i] = t[i - 1] * 10;
        i += 1;
    }
    t
};

/// Writes `n` at `out[at..]`; returns the new end. `out` must have room for 20 bytes.
#[inline(always)]
fn put_u64(out: &mut [u8], at: usize, mut n: u64) -> usize {
    let end = at + digits(n);
    let mut i = end;
    while n >= 100 {
        let r = (n % 100) as usize * 2;
        n /= 100;
        i -= 2;
        out[i..i + 2].copy_from_slice(&PAIRS[r..r + 2]);
    }
    if n >= 10 {
        let r = n as usize * 2;
        out[i - 2..i].copy_from_slice(&PAIRS[r..r + 2]);
    } else {
        out[i - 1] = b'0' + n as u8;
    }
    end
}

/// Writes `v` with exactly `decimals` (≤ 9) decimals at `out[at..]`, as
/// `push_fixed` would; returns the new end. `out` needs [`MAX_NUMBER`] bytes of room.
#[inline(always)]
pub(crate) fn put_fixed(out: &mut [u8], at: usize, v: f64, decimals: usize) -> usize {
    let decimals = decimals.min(9);
    let scale = POW10[decimals];
    let s = v * scale as f64;
    if !in_range(s) {
        out[at] = b'0';
        return at + 1;
    }
    let n = round_i64(s);
    // Branch-free sign: write '-' always, keep it only for negative numbers.
    out[at] = b'-';
    let mut at = at + (n < 0) as usize;
    let n = n.unsigned_abs();
    at = put_u64(out, at, n / scale);
    if decimals > 0 {
        out[at] = b'.';
        let mut f = n % scale;
        let end = at + 1 + decimals;
        let mut i = end;
        while i > at + 1 {
            i -= 1;
            out[i] = b'0' + (f % 10) as u8;
            f /= 10;
        }
        at = end;
    }
    at
}

/// Like [`put_fixed`] without trailing zeros (and without the point if nothing is
/// left after it), as `push_trimmed` would.
#[inline(always)]
pub(crate) fn put_trimmed(out: &mut [u8], at: usize, v: f64, decimals: usize) -> usize {
    let mut end = put_fixed(out, at, v, decimals);
    // A point was written unless the value was not finite (then "0").
    if decimals > 0 && end - at > 1 {
        while out[end - 1] == b'0' {
            end -= 1;
        }
        if out[end - 1] == b'.' {
            end -= 1;
        }
    }
    end
}

/// The key of `v`'s printed value at `decimals`: equal keys print equal text.
#[inline(always)]
pub(crate) fn key(v: f64, decimals: usize) -> i64 {
    let s = v * POW10[decimals.min(9)] as f64;
    if !in_range(s) {
        return 0;
    }
    round_i64(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::{push_fixed, push_trimmed};
    use proptest::prelude::*;

    fn ours(v: f64, d: usize, trim: bool) -> String {
        let mut b = [0u8; 64];
        let end = if trim {
            put_trimmed(&mut b, 3, v, d)
        } else {
            put_fixed(&mut b, 3, v, d)
        };
        String::from_utf8(b[3..end].to_vec()).unwrap()
    }

    fn theirs(v: f64, d: usize, trim: bool) -> String {
        let mut b = Vec::new();
        if trim {
            push_trimmed(&mut b, v, d)
        } else {
            push_fixed(&mut b, v, d)
        }
        String::from_utf8(b).unwrap()
    }

    #[test]
    fn edge_cases_match_push_fixed() {
        let vals = [
            0.0,
            -0.0,
            0.5,
            0.0005,
            -0.0005,
            -0.0004,
            0.49999999999999994,
            2.5,
            -2.5,
            1e-300,
            123456.7895,
            9.0e15,
            -9.0e15,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            4503599627370495.5,
            99.9996,
        ];
        for v in vals {
            for d in 0..=10 {
                for trim in [false, true] {
                    assert_eq!(ours(v, d, trim), theirs(v, d, trim), "{v} {d} {trim}");
                }
            }
        }
    }

    proptest! {
        #[test]
        fn matches_push_fixed(v in -1.0e7f64..1.0e7, d in 0usize..10, trim: bool) {
            prop_assert_eq!(ours(v, d, trim), theirs(v, d, trim));
        }

        #[test]
        fn matches_push_fixed_on_ties(n in -10_000_000i64..10_000_000, d in 0usize..5) {
            // Values on (or next to) a rounding tie of the last decimal.
            let v = (n as f64 + 0.5) / 10f64.powi(d as i32);
            let step = |x: f64, k: i64| f64::from_bits((x.to_bits() as i64 + k) as u64);
            for w in [v, step(v, 1), step(v, -1)] {
                prop_assert_eq!(ours(w, d, false), theirs(w, d, false));
            }
        }

        #[test]
        fn equal_keys_print_equal_text(a in -1.0e5f64..1.0e5, d in 0usize..4) {
            let b = a + 10f64.powi(-(d as i32)) * 0.3;
            prop_assert_eq!(key(a, d) == key(b, d), ours(a, d, false) == ours(b, d, false));
        }
    }
}

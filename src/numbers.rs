//! How lmdc writes numbers: with fixed decimals for the programs, and as
//! rounded quantities for people (the report, the programs' summary line).
//! A leaf: the back ends and the report both write numbers.
//!
//! `format!("{:.3}")` goes through the generic float machinery and is ~8×
//! slower over millions of coordinates; scaling to an integer and printing
//! that with `itoa`-style digit loops is exact for the magnitudes a machine
//! can reach (the back ends' motion writer has an in-place version of these,
//! `back::fmt`).

/// Powers of ten up to 10⁹, the scale of each number of decimals.
pub(crate) const POW10: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// Appends `v` with exactly `decimals` digits after the point (0–9). Values are
/// rounded half away from zero; `-0.000` is written as `0.000`. Non-finite values
/// never reach a back end (the checks refuse them), but would be written as `0`.
pub fn push_fixed(out: &mut Vec<u8>, v: f64, decimals: usize) {
    let decimals = decimals.min(9);
    let scale = POW10[decimals];
    let scaled = (v * scale as f64).round();
    if !scaled.is_finite() || scaled.abs() >= 9.0e18 {
        out.push(b'0');
        return;
    }
    let mut n = scaled as i64;
    if n < 0 {
        out.push(b'-');
        n = -n;
    }
    let n = n as u64;
    let int = n / scale;
    let frac = n % scale;
    push_u64(out, int);
    if decimals > 0 {
        out.push(b'.');
        let mut digits = [b'0'; 9];
        let mut f = frac;
        for i in (0..decimals).rev() {
            digits[i] = b'0' + (f % 10) as u8;
            f /= 10;
        }
        out.extend_from_slice(&digits[..decimals]);
    }
}

/// Like [`push_fixed`] but drops trailing zeros (and the point if nothing is left),
/// for controls that prefer short words: `12.500` → `12.5`, `3.000` → `3`.
pub fn push_trimmed(out: &mut Vec<u8>, v: f64, decimals: usize) {
    let start = out.len();
    push_fixed(out, v, decimals);
    if out[start..].contains(&b'.') {
        while out.last() == Some(&b'0') {
            out.pop();
        }
        if out.last() == Some(&b'.') {
            out.pop();
        }
    }
    if &out[start..] == b"-0" {
        out.truncate(start);
        out.push(b'0');
    }
}

/// Appends an unsigned integer.
pub fn push_u64(out: &mut Vec<u8>, mut n: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&buf[i..]);
}

/// Formats into a new `String` (for templates and tests).
pub fn trimmed(v: f64, decimals: usize) -> String {
    let mut b = Vec::new();
    push_trimmed(&mut b, v, decimals);
    String::from_utf8(b).unwrap_or_default()
}

/// `v` with exactly `decimals` decimals, as a string.
pub fn fixed(v: f64, decimals: usize) -> String {
    let mut b = Vec::new();
    push_fixed(&mut b, v, decimals);
    String::from_utf8(b).unwrap_or_default()
}

// Quantities for people.

/// A length in m (mm below a metre).
pub fn length(mm: f64) -> String {
    if mm.abs() < 1000.0 {
        format!("{mm:.1} mm")
    } else {
        format!("{:.2} m", mm / 1000.0)
    }
}

/// A duration as `2 h 26 min`, `4 min 12 s` or `12.3 s`.
pub fn duration(s: f64) -> String {
    if !s.is_finite() || s < 60.0 {
        return format!("{:.1} s", if s.is_finite() { s } else { 0.0 });
    }
    let whole = s.round() as u64;
    let (h, m, sec) = (whole / 3600, whole / 60 % 60, whole % 60);
    if h > 0 {
        format!("{h} h {m} min")
    } else {
        format!("{m} min {sec} s")
    }
}

/// An energy in kJ or MJ.
pub fn energy(j: f64) -> String {
    if j.abs() < 1e6 {
        format!("{:.1} kJ", j / 1e3)
    } else {
        format!("{:.2} MJ", j / 1e6)
    }
}

/// A mass in g or kg.
pub fn mass(g: f64) -> String {
    if g.abs() < 10.0 {
        format!("{g:.2} g")
    } else if g.abs() < 1000.0 {
        format!("{g:.1} g")
    } else {
        format!("{:.3} kg", g / 1000.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn examples() {
        assert_eq!(fixed(1.0, 3), "1.000");
        assert_eq!(fixed(-0.0004, 3), "0.000");
        assert_eq!(fixed(-0.0005, 3), "-0.001");
        assert_eq!(fixed(123.4567, 2), "123.46");
        assert_eq!(fixed(0.007, 6), "0.007000");
        assert_eq!(fixed(-42.0, 0), "-42");
        let mut b = Vec::new();
        push_trimmed(&mut b, 12.5, 3);
        assert_eq!(b, b"12.5");
    }

    proptest! {
        // Agrees with std's formatting whenever the value is not on a rounding tie.
        #[test]
        fn agrees_with_std(v in -1.0e6f64..1.0e6, d in 0usize..7) {
            let s = v * 10f64.powi(d as i32);
            prop_assume!((s - s.trunc()).abs() - 0.5 > 1e-6 || (s - s.trunc()).abs() < 0.49);
            let ours = fixed(v, d);
            let std = format!("{:.*}", d, v);
            let std = if std.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                std.trim_start_matches('-').to_string()
            } else { std };
            prop_assert_eq!(ours, std);
        }
    }
}

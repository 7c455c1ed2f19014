//! Fixed-point number formatting, the one place numbers become text: [`fixed`] for programs,
//! drawings and templates (each caller adds only its presentation: a typographic minus, trimmed
//! zeros), and [`push_fixed`] for CSV files (fast, and identical on every platform).

use std::io::Write;

/// `value` with `decimals` decimals, never `-0.000` (a negative value that rounds to zero is
/// written without its sign).
pub fn fixed(value: f64, decimals: usize) -> String {
    let s = format!("{value:.decimals$}");
    match s.strip_prefix('-') {
        Some(abs) if abs.chars().all(|c| c == '0' || c == '.') => abs.to_string(),
        _ => s,
    }
}

/// Appends `x` with exactly `decimals` digits after the point, rounding half away from zero.
/// Much faster than `format!` and identical on every platform.
pub fn push_fixed(out: &mut Vec<u8>, x: f64, decimals: u32) {
    let scale = 10f64.powi(decimals as i32);
    let scaled = (x * scale).round();
    // Beyond 2^53 the integer path would lose digits; such values never occur in a recording,
    // but are still written faithfully.
    if scaled.is_nan() || scaled.abs() >= 9.0e15 {
        let _ = write!(out, "{x:.prec$}", prec = decimals as usize);
        return;
    }
    let mut n = scaled as i64;
    if n < 0 {
        out.push(b'-');
        n = -n;
    }
    // Digits right to left into a stack buffer, the point after `decimals` of them, and at
    // least one digit before the point.
    let mut buf = [0u8; 24];
    let mut i = buf.len();
    let mut written = 0;
    loop {
        if written == decimals && decimals > 0 {
            i -= 1;
            buf[i] = b'.';
        }
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        written += 1;
        if n == 0 && written > decimals {
            break;
        }
    }
    out.extend_from_slice(&buf[i..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_never_writes_negative_zero() {
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-0.0, 2), "0.00");
        assert_eq!(fixed(-1.26, 1), "-1.3");
    }

    fn fixed(x: f64, d: u32) -> String {
        let mut v = Vec::new();
        push_fixed(&mut v, x, d);
        String::from_utf8(v).unwrap()
    }

    #[test]
    fn fixed_point_matches_format() {
        let table = [
            (0.0, 6, "0.000000"),
            (1.5, 4, "1.5000"),
            (-0.25, 2, "-0.25"),
            (-0.000_000_4, 6, "0.000000"),
            (2.999_999_96, 6, "3.000000"),
            (1_234.567_89, 4, "1234.5679"),
            (-17.745, 0, "-18"),
            (0.002, 6, "0.002000"),
        ];
        for (x, d, s) in table {
            assert_eq!(fixed(x, d), s, "{x}");
        }
        for i in 0..10_000 {
            let x = (i as f64 - 5000.0) * 0.001_234_567;
            let ours: f64 = fixed(x, 6).parse().unwrap();
            assert!((ours - x).abs() <= 5e-7 + 1e-12, "{x}");
        }
    }
}

//! How every summary prints a number: as people write them (`8.5`, `2.0125`, `3.2e-14`).

/// `x` rounded to `digits` significant digits (at least 1), trailing zeros dropped, so a value
/// that needs fewer digits prints exactly and as short as it reads (`8.5`, not `8.50000e0`).
/// Plain notation for moderate magnitudes (`1e-4 ≤ |x| < 10^digits`, as C's `%g`), scientific
/// with a bare exponent otherwise (`3.2e-14`, `1.5e12`). NaN and infinities print as `NaN`,
/// `inf` and `-inf`.
#[must_use]
pub fn sig(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".to_string();
    }
    let digits = digits.max(1);
    // Rust rounds the decimal expansion correctly: `d.ddd…e±X`.
    let sci = format!("{:.*e}", digits - 1, x);
    let (mantissa, exp) = sci.split_once('e').expect("`{:e}` writes an exponent");
    let exp: i32 = exp.parse().expect("`{:e}` writes an integer exponent");
    let (sign, mantissa) = match mantissa.strip_prefix('-') {
        Some(m) => ("-", m),
        None => ("", mantissa),
    };
    let all: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let kept = all.trim_end_matches('0');
    let kept = if kept.is_empty() { "0" } else { kept };
    if exp < -4 || exp >= digits as i32 {
        let (first, rest) = kept.split_at(1);
        let dot = if rest.is_empty() { "" } else { "." };
        return format!("{sign}{first}{dot}{rest}e{exp}");
    }
    if exp < 0 {
        let zeros = "0".repeat((-exp - 1) as usize);
        return format!("{sign}0.{zeros}{kept}");
    }
    let int_len = exp as usize + 1;
    if kept.len() <= int_len {
        let zeros = "0".repeat(int_len - kept.len());
        format!("{sign}{kept}{zeros}")
    } else {
        let (int, frac) = kept.split_at(int_len);
        format!("{sign}{int}.{frac}")
    }
}

/// [`sig`] with 6 significant digits: the summaries' default.
#[must_use]
pub fn num(x: f64) -> String {
    sig(x, 6)
}

#[cfg(test)]
mod tests {
    use super::{num, sig};

    #[test]
    fn exact_values_print_short() {
        assert_eq!(num(8.5), "8.5");
        assert_eq!(num(2.0125), "2.0125");
        assert_eq!(num(0.53125), "0.53125");
        assert_eq!(num(10.0), "10");
        assert_eq!(num(-3.0), "-3");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(417.0), "417");
        assert_eq!(sig(8.500000000000002, 10), "8.5");
    }

    #[test]
    fn long_values_are_rounded_to_significant_digits() {
        assert_eq!(num(2.7079334), "2.70793");
        assert_eq!(num(1.0276774), "1.02768");
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(123_456.7), "123457");
        assert_eq!(num(999_999.7), "1e6");
        assert_eq!(sig(-5.0249e-15, 3), "-5.02e-15");
    }

    #[test]
    fn tiny_and_huge_values_are_scientific() {
        assert_eq!(num(3.2e-14), "3.2e-14");
        assert_eq!(num(1.5e12), "1.5e12");
        assert_eq!(num(2e-5), "2e-5");
        assert_eq!(num(1e-4), "0.0001");
        assert_eq!(num(0.00012345678), "0.000123457");
        assert_eq!(num(1_234_567.0), "1.23457e6");
        assert_eq!(num(f64::MAX), "1.79769e308");
        assert_eq!(num(f64::MIN_POSITIVE * 0.5), "1.11254e-308");
    }

    #[test]
    fn non_finite_values() {
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num(f64::NEG_INFINITY), "-inf");
    }

    #[test]
    fn every_result_reads_back_within_its_rounding() {
        for &x in &[
            1.0 / 3.0,
            2.0f64.sqrt() * 1e-9,
            -7.77e200,
            6.02214076e23,
            0.999_999_5,
        ] {
            for digits in 1..=17 {
                let s = sig(x, digits);
                let back: f64 = s.parse().unwrap();
                let tol = 10f64.powi(1 - digits as i32) * x.abs();
                assert!((back - x).abs() <= tol, "{x} at {digits}: {s}");
            }
        }
    }
}

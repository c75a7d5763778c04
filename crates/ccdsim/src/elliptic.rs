//! Carlson's symmetric elliptic integral of the first kind, `R_F`, and the Legendre forms
//! built on it: the times of a pendulum's swing ([`crate::motion::pivot`]) are such integrals.
//!
//! `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z))` is computed by Carlson's duplication
//! (B. C. Carlson, "Numerical computation of real or complex elliptic integrals", Numerical
//! Algorithms 10, 1995): each step maps the arguments to ones a quarter as far apart with the
//! same `R_F`, and once they agree to 10⁻³ a fifth-order series finishes, its truncation
//! error below 10⁻¹⁷ relative. It needs no special cases near the singular ends (an argument
//! near zero, or the modulus near one) that trouble Landen's and Gauss's transformations,
//! which is why the pendulum is written in terms of it.

/// `R_F(x, y, z)` for non-negative arguments of which at most one is zero, to a few ulps;
/// `+∞` when two are zero (the integral diverges) and NaN for a negative or NaN argument.
/// Symmetric in its arguments and homogeneous of degree −½: `R_F(λx, λy, λz) =
/// R_F(x, y, z)/√λ`.
#[must_use]
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    if x.is_nan() || y.is_nan() || z.is_nan() || x < 0.0 || y < 0.0 || z < 0.0 {
        return f64::NAN;
    }
    let zeros = [x, y, z].iter().filter(|&&v| v == 0.0).count();
    if zeros >= 2 {
        return f64::INFINITY;
    }
    let (mut x, mut y, mut z) = (x, y, z);
    // Every step shrinks the spread by 4; arguments 10⁻³⁰⁰ and 10³⁰⁰ apart need about 500.
    for _ in 0..2000 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = (1.0 - x / mean, 1.0 - y / mean, 1.0 - z / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    unreachable!("Carlson's duplication converges for finite non-negative arguments")
}

/// The incomplete elliptic integral of the first kind, `F(φ | m) = ∫₀^φ dϑ / √(1 − m sin²ϑ)`,
/// for `0 ≤ φ ≤ π/2` and parameter `m ≤ 1` (`m < 1` at `φ = π/2`).
#[must_use]
pub fn elliptic_f(phi: f64, m: f64) -> f64 {
    let (s, c) = phi.sin_cos();
    s * carlson_rf(c * c, 1.0 - m * s * s, 1.0)
}

/// The complete elliptic integral of the first kind, `K(m) = F(π/2 | m)`, for `m < 1`.
#[must_use]
pub fn elliptic_k(m: f64) -> f64 {
    carlson_rf(0.0, 1.0 - m, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs().max(f64::MIN_POSITIVE)
    }

    /// Values from Carlson (1995), section 3, and Abramowitz & Stegun table 17.1.
    #[test]
    fn known_values() {
        assert!(close(carlson_rf(1.0, 2.0, 0.0), 1.311_028_777_146_1, 1e-13));
        assert!(close(
            carlson_rf(2.0, 3.0, 4.0),
            0.584_082_841_677_15,
            1e-13
        ));
        assert!(close(carlson_rf(0.5, 1.0, 0.0), 1.854_074_677_301_4, 1e-13));
        assert!(close(elliptic_k(0.0), std::f64::consts::FRAC_PI_2, 1e-15));
        assert!(close(elliptic_k(0.5), 1.854_074_677_301_372, 1e-14));
        assert!(close(elliptic_k(0.9), 2.578_092_113_348_173, 1e-14));
        // F(φ | 0) = φ; F(φ | 1) = atanh(sin φ).
        assert!(close(elliptic_f(0.7, 0.0), 0.7, 1e-15));
        assert!(close(elliptic_f(0.7, 1.0), 0.7f64.sin().atanh(), 1e-14));
    }

    #[test]
    fn two_zero_arguments_diverge_and_bad_ones_are_nan() {
        assert_eq!(carlson_rf(0.0, 0.0, 1.0), f64::INFINITY);
        assert!(carlson_rf(-1.0, 1.0, 1.0).is_nan());
        assert!(carlson_rf(f64::NAN, 1.0, 1.0).is_nan());
    }

    /// Simpson's rule on the smooth integrand of `F`, with many panels: the reference.
    fn f_by_quadrature(phi: f64, m: f64) -> f64 {
        let n = 20_000;
        let h = phi / f64::from(n);
        let f = |t: f64| 1.0 / (1.0 - m * t.sin().powi(2)).sqrt();
        let mut sum = f(0.0) + f(phi);
        for k in 1..n {
            sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(h * f64::from(k));
        }
        sum * h / 3.0
    }

    proptest! {
        #[test]
        fn f_matches_quadrature(phi in 0.0f64..1.5, m in -20.0f64..0.95) {
            let (got, want) = (elliptic_f(phi, m), f_by_quadrature(phi, m));
            prop_assert!(close(got, want, 1e-12), "F({phi} | {m}) = {got}, want {want}");
        }

        #[test]
        fn homogeneous_and_symmetric(
            x in 1e-6f64..1e3, y in 1e-6f64..1e3, z in 0.0f64..1e3, l in 1e-8f64..1e8
        ) {
            let r = carlson_rf(x, y, z);
            prop_assert!(close(carlson_rf(z, x, y), r, 1e-15));
            prop_assert!(close(carlson_rf(l * x, l * y, l * z) * l.sqrt(), r, 1e-14));
        }
    }
}

//! First contact of a point moving on a parabola with a ball: a ball under uniform gravity
//! against a fixed point (a wall segment's end point), or two balls with different
//! accelerations; and every later one ([`contacts_accelerating`]), for the side of a rod,
//! whose projected parabola may enter the cylinder around it twice ([`crate::contact::rod`]).
//!
//! # A quartic
//!
//! The offset `x(t) = dp + dv·t + ½·acc·t²` is within `σ` of the origin when
//! `f(t) = |x(t)|² − σ² ≤ 0`, a quartic with leading coefficient `¼|acc|² > 0`; the pair
//! approaches when `f'(t) = 2·x·ẋ < 0`. No closed form is safe to use (the quartic formula
//! cancels catastrophically), so the roots are isolated through the derivative chain: the
//! roots of `f''` (a quadratic, solved without cancellation) cut `[0, T]` into pieces on which
//! `f'` is monotone, so each holds at most one root of `f'`; those roots cut it further into
//! pieces on which `f` is monotone, so each holds at most one sign change of `f`, bracketed by
//! the values at its ends. Every root is then narrowed to adjacent floats by safeguarded
//! Newton steps with bisection of the float bit patterns as the fallback, which ends after a
//! bounded number of evaluations on any scale. `T` is four times a Fujiwara-type bound on the
//! roots, where `f`, `f'` and `f''` are all positive by a wide margin. A root can be missed
//! only where `f` dips below zero by no more than its rounding error (a graze).
//!
//! # Growing radii
//!
//! With growing radii ([`crate::contact::growth`]) the contact distance is linear in time,
//! `σ(t) = σ + σ̇·t`, and `f(t) = |x(t)|² − σ(t)²` is still a quartic with the same leading
//! coefficient: `σ̇` only lowers the coefficients of `t²` and `t` by `σ̇²` and `2σσ̇`, and the
//! derivative chain isolates its roots as before ([`first_contact_accelerating_growing`]).
//! With `σ̇ = 0` every value computed is the fixed-radius one bit for bit (the terms it adds
//! are exact zeros). Growth rates are positive, so `σ(t) > 0` and `f = 0` means `|x| = σ`.
//!
//! # Scale
//!
//! Lengths are divided by a power of two above `max(|dp|∞, σ)` and times by one near the
//! free-fall time `√(length / |acc|)`, so the coefficients sit near 1 whatever the units.
//! Multiplying by powers of two commutes with every rounding, so a problem scaled by powers
//! of two in length and time gets the scaled answer bit for bit, and nothing overflows.

use crate::contact::growth::{first_contact_growing, first_exit_growing};
use crate::contact::narrow::first_contact;
use crate::geom::Vector;

/// Time offset `t ≥ 0`, seconds, at which a point at offset `dp` (metres) from the origin,
/// moving at relative velocity `dv` (m/s) with constant relative acceleration `acc` (m/s²),
/// is first within `sigma` (metres) of the origin while approaching it: the first time the
/// pair is in contact and approaching, as for [`first_contact`] and
/// [`crate::contact::growth::first_contact_growing`]. `None` when that never happens.
///
/// With `f(t) = |dp + dv·t + ½·acc·t²|² − σ²`:
/// - in contact and approaching now (`f(0) ≤ 0`, `dp·dv < 0`): `0`;
/// - apart (`f(0) > 0`): the first root where `f` turns negative; a graze, where `f` only
///   touches zero, may count or not, but no sign change is ever skipped;
/// - in contact but not approaching, as rounding leaves a pair after a collision: the first
///   time it turns to approach while still in contact (`f'` turns negative while `f ≤ 0`),
///   or, if it leaves contact first, the first time it comes back.
///
/// An `acc` of exactly zero gives [`first_contact`]'s answer bit for bit. Non-finite inputs
/// (with `acc ≠ 0`), and contacts later than the largest float, give `None`; no answer is NaN
/// or negative. A relative speed over 2²⁰⁰ times the free-fall speed `√(|acc|·max(|dp|, σ))`
/// gets [`first_contact`]'s answer, since the quartic's coefficients would overflow: the
/// acceleration bends such a flight by under 2⁻⁴⁰⁰·max(|dp|, σ) near the ball, and turns it
/// back only 2⁴⁰⁰ times as far away.
#[must_use]
pub fn first_contact_accelerating<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
) -> Option<f64> {
    first_turn(dp, dv, acc, sigma, 0.0, 1.0, first_contact)
}

/// [`first_contact_accelerating`] for a contact distance that grows linearly in time,
/// `sigma + sigma_dot·t` (metres; `sigma_dot` ≥ 0, m/s): two growing balls with different
/// accelerations, or a growing ball falling onto a fixed point (see the module docs). With
/// `acc` exactly zero it is [`crate::contact::growth::first_contact_growing`] bit for bit; with
/// `sigma_dot` zero, [`first_contact_accelerating`] bit for bit.
#[must_use]
pub fn first_contact_accelerating_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> Option<f64> {
    first_turn(dp, dv, acc, sigma, sigma_dot, 1.0, |p, v, s| {
        first_contact_growing(p, v, s, sigma_dot)
    })
}

/// Time offset `t ≥ 0`, seconds, at which a point at offset `dp` (metres) from the origin,
/// moving at relative velocity `dv` (m/s) with constant relative acceleration `acc` (m/s²),
/// is first at least `sigma` (metres) from the origin while moving away from it: the time it
/// leaves the ball of radius `sigma`. [`first_contact_accelerating`]'s contract for
/// `g(t) = σ² − |x(t)|²` (where that one's is for `−g`): `0` for a point outside the ball and
/// moving away; otherwise the first root where `g` turns negative; `None` when that never
/// happens (a point at rest inside, without acceleration). With `acc` exactly zero it is
/// [`first_exit`].
#[must_use]
pub fn first_exit_accelerating<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
) -> Option<f64> {
    first_turn(dp, dv, acc, sigma, 0.0, -1.0, first_exit)
}

/// [`first_exit_accelerating`] from a ball whose radius grows linearly in time,
/// `sigma + sigma_dot·t` (metres; `sigma_dot` ≥ 0, m/s): a growing body leaving a sensor
/// under gravity. With `acc` exactly zero it is [`crate::contact::growth::first_exit_growing`] bit
/// for bit; with `sigma_dot` zero, [`first_exit_accelerating`] bit for bit.
#[must_use]
pub fn first_exit_accelerating_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> Option<f64> {
    first_turn(dp, dv, acc, sigma, sigma_dot, -1.0, |p, v, s| {
        first_exit_growing(p, v, s, sigma_dot)
    })
}

/// Time offset `t ≥ 0` at which a point at offset `dp` moving in a straight line at `dv` is
/// first at least `sigma` from the origin while moving away: `0` when it already is, else
/// the later root of `|dp + dv·t| = σ` (solved without cancellation), `0` when its path
/// misses the ball (it is outside and will only pass by) or it rests outside or on the
/// sphere, `None` for a point at rest inside.
#[must_use]
pub fn first_exit<const D: usize>(dp: Vector<D>, dv: Vector<D>, sigma: f64) -> Option<f64> {
    let b = dp.dot(dv);
    let c = dp.norm_sq() - sigma * sigma;
    if c >= 0.0 && b > 0.0 {
        return Some(0.0);
    }
    let a = dv.norm_sq();
    if a == 0.0 {
        // At rest: out already (on the sphere or beyond), or never.
        return (c >= 0.0).then_some(0.0);
    }
    let disc = b * b - a * c;
    if disc.is_nan() || disc < 0.0 {
        return Some(0.0);
    }
    let root = disc.sqrt();
    let t = if b <= 0.0 {
        (root - b) / a
    } else {
        -c / (b + root)
    };
    Some(t.max(0.0)).filter(|t| t.is_finite())
}

/// Time offsets `t ≥ 0`, seconds, at which a point at offset `dp` (metres) from the origin,
/// moving at relative velocity `dv` (m/s) with constant relative acceleration `acc` (m/s²),
/// comes into contact with the ball of radius `sigma` (metres) while approaching it, each time
/// it does, in increasing order: the start of every stretch of time during which
/// `f(t) = |dp + dv·t + ½·acc·t²|² − σ² ≤ 0` and `f'(t) < 0`. The first is
/// [`first_contact_accelerating`]'s answer bit for bit; a later one is where the point enters
/// again after leaving the ball (or turns back towards the centre inside it), found on the
/// same isolated pieces of the quartic, by the same rules. A parabola approaches along at most
/// two stretches (`f'` is a cubic with a positive leading coefficient); the third slot is
/// for rounding at a double root of `f'`. With `acc` exactly zero the path is straight and
/// enters once: [`first_contact`]'s answer alone.
///
/// What the side of a rod needs under gravity ([`crate::contact::gravity`]): the ball meets the rod's
/// side at an entry into the infinite cylinder around its line whose foot lies on the rod, and
/// a parabola may enter the cylinder beyond an end, leave it, and come back over the rod.
#[must_use]
pub fn contacts_accelerating<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
) -> [Option<f64>; 3] {
    every_contact(dp, dv, acc, sigma, 0.0, first_contact)
}

/// [`contacts_accelerating`] against a contact distance that grows linearly in time,
/// `sigma + sigma_dot·t` (metres; `sigma_dot` ≥ 0, m/s): the side of a rod met by a growing
/// ball under gravity ([`crate::contact::rod`]). With `acc` exactly zero the path is straight and
/// enters once: [`crate::contact::growth::first_contact_growing`]'s answer alone; with `sigma_dot`
/// zero, [`contacts_accelerating`] bit for bit; the first is always
/// [`first_contact_accelerating_growing`]'s answer bit for bit.
#[must_use]
pub fn contacts_accelerating_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> [Option<f64>; 3] {
    every_contact(dp, dv, acc, sigma, sigma_dot, |p, v, s| {
        first_contact_growing(p, v, s, sigma_dot)
    })
}

/// The common body of [`contacts_accelerating`] and its growing form; `straight` is the
/// straight-line answer, for a zero acceleration and for flights too fast for the quartic.
#[inline]
fn every_contact<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
    straight: impl Fn(Vector<D>, Vector<D>, f64) -> Option<f64>,
) -> [Option<f64>; 3] {
    match quartic(dp, dv, acc, sigma, sigma_dot, 1.0) {
        Quartic::Straight => [straight(dp, dv, sigma), None, None],
        Quartic::Known(t) => [t, None, None],
        Quartic::Scaled { parabola, m } => parabola
            .contacts()
            .map(|t| t.map(|t| ldexp(t, m)).filter(|t| t.is_finite())),
    }
}

/// The common body of [`first_contact_accelerating`] (`sign` 1) and
/// [`first_exit_accelerating`] (`sign` −1, the sign of `f` flipped), and of their growing
/// forms (`sigma_dot` > 0); `straight` is the straight-line answer, for a zero acceleration
/// and for flights too fast for the quartic.
#[inline]
fn first_turn<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
    sign: f64,
    straight: impl Fn(Vector<D>, Vector<D>, f64) -> Option<f64>,
) -> Option<f64> {
    match quartic(dp, dv, acc, sigma, sigma_dot, sign) {
        Quartic::Straight => straight(dp, dv, sigma),
        Quartic::Known(t) => t,
        Quartic::Scaled { parabola, m } => parabola
            .first_contact()
            .map(|t| ldexp(t, m))
            .filter(|t| t.is_finite()),
    }
}

/// How [`quartic`] sets a problem up.
enum Quartic<const D: usize> {
    /// The straight-line function answers: a zero acceleration, or a flight too fast for the
    /// quartic's coefficients.
    Straight,
    /// The answer is known without solving: non-finite inputs, or a point at the origin
    /// against a ball of radius zero.
    Known(Option<f64>),
    /// The scaled quartic, and the power of two of its unit of time (seconds).
    Scaled {
        /// The scaled problem.
        parabola: Parabola<D>,
        /// Times in its units are `2^m` seconds.
        m: i32,
    },
}

/// The problem of [`first_turn`] and [`contacts_accelerating`] in scaled units (see the module
/// docs), against a contact distance `sigma + sigma_dot·t`, or what answers it without the
/// quartic.
#[inline]
fn quartic<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
    sign: f64,
) -> Quartic<D> {
    if acc.0.iter().all(|&a| a == 0.0) {
        return Quartic::Straight;
    }
    if !(dp.is_finite()
        && dv.is_finite()
        && acc.is_finite()
        && sigma.is_finite()
        && sigma_dot.is_finite())
    {
        return Quartic::Known(None);
    }
    let reach = max_abs(dp).max(sigma.abs());
    if reach == 0.0 {
        // f = |x|² ≥ 0 only touches zero: never a contact that approaches; the point
        // leaves at once.
        return Quartic::Known((sign < 0.0).then_some(0.0));
    }
    // Lengths in units of 2^e > reach, times in units of 2^m with |acc|∞ in [1, 4) after.
    let e = exponent(reach) + 1;
    let m = (e - exponent(max_abs(acc)) + 1).div_euclid(2);
    let v = scaled(dv, m - e);
    // A speed, scaled like the velocity.
    let rd = ldexp(sigma_dot, m - e);
    if max_abs(v).max(rd.abs()) > MAX_SCALED_SPEED {
        return Quartic::Straight;
    }
    let r = ldexp(sigma, -e);
    Quartic::Scaled {
        parabola: Parabola {
            p: scaled(dp, -e),
            v,
            h: scaled(acc, 2 * m - e - 1),
            r,
            rd,
            r_sq: r * r,
            sign,
        },
        m,
    }
}

/// Above this scaled speed (2²⁰⁰) `f(T)` could overflow: `T ~ |v|`, `f(T) ~ T⁴`.
const MAX_SCALED_SPEED: f64 = 1.606_938_044_258_990_3e60;

/// `x(t) = p + v·t + h·t²` in scaled units (`h` is half the acceleration, `|h|∞` in
/// `[½, 2)`, `|p|∞, r < 1`), against the contact distance `r + rd·t`.
struct Parabola<const D: usize> {
    p: Vector<D>,
    v: Vector<D>,
    h: Vector<D>,
    /// The contact distance at `t = 0`.
    r: f64,
    /// Its growth speed (0 for fixed radii).
    rd: f64,
    /// `r²`, as the fixed-radius evaluation always took it.
    r_sq: f64,
    /// 1 for contacts; −1 for exits, whose `f` is flipped (`σ² − |x|²`).
    sign: f64,
}

impl<const D: usize> Parabola<D> {
    /// `[f, f', f'']` at `t`, from `x(t)` and `ẋ(t)` in Horner form rather than from the
    /// expanded coefficients: near a contact `|x| ≈ σ`, so the rounding error is of order
    /// `ε·σ·|terms of x|`, not `ε·|terms of x|²` (a point arriving from far away).
    /// A growing contact distance `s = r + rd·t` subtracts `s²`, `2·rd·s` and `2·rd²`; with
    /// `rd = 0` the fixed-radius values are kept as they were computed, bit for bit.
    #[inline]
    fn eval(&self, t: f64) -> [f64; 3] {
        let x = self.p + (self.v + self.h * t) * t;
        let xd = self.v + self.h * (2.0 * t);
        if self.rd == 0.0 {
            return [
                self.sign * (x.norm_sq() - self.r_sq),
                self.sign * (2.0 * x.dot(xd)),
                self.sign * (2.0 * (xd.norm_sq() + 2.0 * x.dot(self.h))),
            ];
        }
        let s = self.r + self.rd * t;
        [
            self.sign * (x.norm_sq() - s * s),
            self.sign * (2.0 * (x.dot(xd) - self.rd * s)),
            self.sign * (2.0 * (xd.norm_sq() + 2.0 * x.dot(self.h) - self.rd * self.rd)),
        ]
    }

    /// The contract of [`first_contact_accelerating`] in scaled time.
    fn first_contact(&self) -> Option<f64> {
        let cuts = self.cuts();
        cuts.windows(2).find_map(|w| self.piece_contact(w[0], w[1]))
    }

    /// The contract of [`contacts_accelerating`] in scaled time: every piece's contact, less
    /// one found at a piece's start (a cut) where the pair was already in contact and
    /// approaching at the end of the piece before, whose contact started there already.
    fn contacts(&self) -> [Option<f64>; 3] {
        let cuts = self.cuts();
        let mut found = [None; 3];
        let mut k = 0;
        for (i, w) in cuts.windows(2).enumerate() {
            let Some(t) = self.piece_contact(w[0], w[1]) else {
                continue;
            };
            // Only a contact in contact and approaching at the piece's start is found at it,
            // and the piece before, which ends there in the same state, found its own.
            if i > 0 && t == w[0] {
                continue;
            }
            found[k] = Some(t);
            k += 1;
        }
        found
    }

    /// The cuts of `[0, T]` at the roots of `f''`, between which `f'` is monotone (see the
    /// module docs): four, non-decreasing, the first `0` and the last `T`.
    fn cuts(&self) -> [f64; 4] {
        let a4 = self.h.norm_sq();
        let a3 = 2.0 * self.v.dot(self.h);
        // The growth's terms are exact zeros for fixed radii: the bits stay.
        let a2 = self.v.norm_sq() + 2.0 * self.p.dot(self.h) - self.rd * self.rd;
        let a1 = 2.0 * (self.p.dot(self.v) - self.r * self.rd);
        let a0 = self.p.norm_sq() - self.r_sq;
        // With |a_i| ≤ a4·M^(4−i), every root of f (and, by Gauss–Lucas, of f' and f'') lies
        // below 2M; at 4M the leading term outweighs the rest threefold, so rounding cannot
        // flip the signs there.
        let bound = (a3.abs() / a4)
            .max((a2.abs() / a4).sqrt())
            .max((a1.abs() / a4).cbrt())
            .max((a0.abs() / a4).sqrt().sqrt());
        let t_max = 4.0 * bound;
        // Roots of f''/2 = 6·a4·t² + 3·a3·t + a2; `clip` also maps −0.0 and NaN to +0.0, as the
        // bit-pattern bisection needs.
        let clip = |r: f64| if r > 0.0 { r.min(t_max) } else { 0.0 };
        let mut cuts = [0.0, t_max, t_max, t_max];
        let (qa, qb) = (6.0 * a4, 3.0 * a3);
        let disc = qb * qb - 4.0 * qa * a2;
        if disc > 0.0 {
            let q = -0.5 * (qb + disc.sqrt().copysign(qb));
            let (r1, r2) = (q / qa, a2 / q);
            cuts[1] = clip(r1.min(r2));
            cuts[2] = clip(r1.max(r2));
        }
        cuts
    }

    /// On the piece `[l, r]` between two cuts, where `f'` is monotone: the first time the pair
    /// is in contact and approaching, if it is there.
    fn piece_contact(&self, l: f64, r: f64) -> Option<f64> {
        let [approach_l, approach_r] = [l, r].map(|t| self.eval(t)[1] < 0.0);
        match (approach_l, approach_r) {
            (true, true) => self.descent(l, r),
            (false, false) => None,
            _ => {
                // f' is monotone here: one turn, narrowed to adjacent floats.
                let slope = |t| {
                    let [_, d1, d2] = self.eval(t);
                    (d1, d2)
                };
                let (lo, hi) = refine(slope, |d1| (d1 < 0.0) == approach_r, l, r);
                if approach_l {
                    self.descent(l, lo)
                } else {
                    self.descent(hi, r)
                }
            }
        }
    }

    /// On `[a, b]`, where the pair approaches throughout (`f` decreasing): the first time it is
    /// in contact, if it is by `b`.
    fn descent(&self, a: f64, b: f64) -> Option<f64> {
        if self.eval(a)[0] <= 0.0 {
            return Some(a);
        }
        if self.eval(b)[0] > 0.0 {
            return None;
        }
        let value = |t| {
            let [f, d1, _] = self.eval(t);
            (f, d1)
        };
        // The first float at which the pair is in contact.
        Some(refine(value, |f| f <= 0.0, a, b).1)
    }
}

/// Narrows `[lo, hi]` (`0 ≤ lo < hi`), where `inside` is false for `g`'s value at `lo` and
/// true at `hi`, to two adjacent floats. `g(t)` is `(value, slope)`.
///
/// Newton steps from `lo` while they stay in the bracket and at least halve, at most 8 in a
/// row; otherwise the bracket is bisected in its bit patterns (ordered like the values for
/// non-negative floats), which halves the float count, below 2⁶³, whatever the scale: at
/// most about 600 evaluations, typically under 10. Newton approaches a root from one side;
/// once it stalls there, it probes the next float inward, which decides the other end.
fn refine(
    g: impl Fn(f64) -> (f64, f64),
    inside: impl Fn(f64) -> bool,
    mut lo: f64,
    mut hi: f64,
) -> (f64, f64) {
    let (mut x, mut run, mut step_old) = (lo, 0, f64::INFINITY);
    let (mut gx, mut slope) = g(lo);
    loop {
        let gap = hi.to_bits() - lo.to_bits();
        if gap <= 1 {
            return (lo, hi);
        }
        let newton = x - gx / slope;
        let step = (newton - x).abs();
        let t = if run < 8 && step <= 0.5 * step_old && newton >= lo && newton <= hi {
            run += 1;
            step_old = step;
            let inward = |end: f64, by: i64| f64::from_bits(end.to_bits().wrapping_add_signed(by));
            newton.clamp(inward(lo, 1), inward(hi, -1))
        } else {
            run = 0;
            step_old = f64::INFINITY;
            f64::from_bits(lo.to_bits() + gap / 2)
        };
        x = t;
        (gx, slope) = g(t);
        if inside(gx) {
            hi = t;
        } else {
            lo = t;
        }
    }
}

/// Largest absolute component.
fn max_abs<const D: usize>(v: Vector<D>) -> f64 {
    v.0.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `⌊log₂ x⌋` for finite `x > 0`, subnormals included.
fn exponent(x: f64) -> i32 {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i32;
    if biased == 0 {
        exponent(x * 18_446_744_073_709_551_616.0) - 64 // 2⁶⁴
    } else {
        biased - 1023
    }
}

/// `x·2^k`, exact unless the result leaves the normal range; in steps of 2^±1000, so a
/// finite result never passes through an infinite one.
fn ldexp(mut x: f64, mut k: i32) -> f64 {
    let pow2 = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while k > 1000 {
        x *= pow2(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= pow2(-1000);
        k += 1000;
    }
    x * pow2(k)
}

/// `v·2^k` component-wise.
fn scaled<const D: usize>(v: Vector<D>, k: i32) -> Vector<D> {
    Vector(v.0.map(|x| ldexp(x, k)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{One, Signed, Zero};
    use proptest::array::{uniform2, uniform3};
    use proptest::prelude::*;

    fn v2(x: f64, y: f64) -> Vector<2> {
        Vector([x, y])
    }

    fn rat(x: f64) -> BigRational {
        BigRational::from_float(x).expect("finite")
    }

    /// Polynomials over the rationals, lowest degree first, no trailing zeros.
    fn derivative(p: &[BigRational]) -> Vec<BigRational> {
        let k = |i: usize| BigRational::from_integer(i.into());
        p.iter()
            .enumerate()
            .skip(1)
            .map(|(i, c)| c * k(i))
            .collect()
    }

    /// The Sturm chain of `p`, each term scaled by a positive integer to integer coefficients:
    /// signs are all it is for, and integers spare every operation a gcd.
    fn sturm(p: Vec<BigRational>) -> Vec<Vec<BigInt>> {
        let mut chain = vec![derivative(&p), p];
        chain.swap(0, 1);
        loop {
            let (a, b) = (&chain[chain.len() - 2], &chain[chain.len() - 1]);
            let mut r = a.clone();
            while r.len() >= b.len() {
                let (shift, q) = (r.len() - b.len(), r.last().unwrap() / b.last().unwrap());
                for (i, c) in b.iter().enumerate() {
                    r[shift + i] -= &q * c;
                }
                r.pop();
                while r.last().is_some_and(Zero::is_zero) {
                    r.pop();
                }
            }
            if r.is_empty() {
                break;
            }
            chain.push(r.into_iter().map(|c| -c).collect());
        }
        let integral = |p: &Vec<BigRational>| {
            let l = p.iter().fold(BigInt::one(), |l, c| {
                if (&l % c.denom()).is_zero() {
                    l
                } else {
                    l * c.denom()
                }
            });
            p.iter().map(|c| (c * &l).to_integer()).collect()
        };
        chain.iter().map(integral).collect()
    }

    /// Sign changes along the chain at `x = n/d`, `d > 0`: of `Σ c_i·n^i·d^(k−i)`, by Horner.
    fn variations(chain: &[Vec<BigInt>], x: &BigRational) -> usize {
        let (n, d) = (x.numer(), x.denom());
        let signs: Vec<bool> = chain
            .iter()
            .map(|p| {
                let mut d_pow = BigInt::one();
                p.iter()
                    .rev()
                    .skip(1)
                    .fold(p.last().unwrap().clone(), |acc, c| {
                        d_pow *= d;
                        acc * n + c * &d_pow
                    })
            })
            .filter(|v| !v.is_zero())
            .map(|v| v.is_positive())
            .collect();
        signs.windows(2).filter(|w| w[0] != w[1]).count()
    }

    /// Distinct real roots in `(a, b]` of the chain's (square-free) polynomial.
    fn roots(chain: &[Vec<BigInt>], a: &BigRational, b: &BigRational) -> usize {
        if a >= b {
            0
        } else {
            variations(chain, a) - variations(chain, b)
        }
    }

    /// The function's answer, after checking it against the exact quartic of the exact inputs
    /// (every f64 is a dyadic rational) by Sturm counts, to `tol = 1e-9·(unit + t)` seconds.
    /// With inputs of order 1 and `unit = 1`, a computed root is off by about ε·|terms of
    /// f| / |f'| ≲ 1e-15 / |f'|: 1e-9 leaves room for grazes down to |f'| ~ 1e-6 (dips 1e-12
    /// deep, rare at random), while a missed root is off by O(1). `unit = 0` makes it relative,
    /// for times of any scale.
    fn checked<const D: usize>(
        dp: Vector<D>,
        dv: Vector<D>,
        acc: Vector<D>,
        sigma: f64,
        unit: f64,
    ) -> Option<f64> {
        let got = first_contact_accelerating(dp, dv, acc, sigma);
        assert!(got.is_none_or(|t| t >= 0.0 && t.is_finite()), "{got:?}");
        if acc.0.iter().all(|&a| a == 0.0) {
            let want = first_contact(dp, dv, sigma);
            assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
            return got;
        }
        let dot = |a: Vector<D>, b: Vector<D>| -> BigRational {
            (0..D).map(|k| rat(a[k]) * rat(b[k])).sum()
        };
        let (zero, two) = (BigRational::zero(), rat(2.0));
        let f = vec![
            dot(dp, dp) - rat(sigma) * rat(sigma),
            &two * dot(dp, dv),
            dot(dv, dv) + dot(dp, acc),
            dot(dv, acc),
            dot(acc, acc) / rat(4.0),
        ];
        let [f0, d0, dd0] = [0, 1, 2].map(|i| f[i].cmp(&zero));
        // The function sees f(0) and f'(0) rounded: exact ties are outside what it decides.
        let rounded = [dp.norm_sq() - sigma * sigma, dp.dot(dv)].map(|x| x.partial_cmp(&0.0));
        let (sf, sd) = (sturm(f.clone()), sturm(derivative(&f)));
        // So is a repeated root of f or f' (a tangency).
        if rounded != [Some(f0), Some(d0)] || f0.is_eq() || sf[sf.len() - 1].len() > 1 {
            return got;
        }
        if sd[sd.len() - 1].len() > 1 || (f0.is_le() && d0.is_eq() && dd0.is_eq()) {
            return got;
        }
        let bound = f[..4]
            .iter()
            .fold(rat(1.0), |m, c| m.max((c / &f[4]).abs()))
            + rat(1.0);
        let window = got.map(|t| {
            let (t, tol) = (rat(t), rat(1e-9) * (rat(unit) + rat(t)));
            (&t - &tol, t + tol)
        });
        if f0.is_le() && (d0.is_lt() || (d0.is_eq() && dd0.is_lt())) {
            // Approaching now, or from the next instant on.
            assert!(
                got.is_some_and(|t| t <= 1e-9 * unit),
                "approaches now: {got:?}"
            );
            assert!(d0.is_eq() || got == Some(0.0));
            return got;
        }
        let start = if f0.is_gt() {
            zero
        } else {
            // Exit from the overlap: the first root of f, to 2⁻⁷⁰ of itself (from zero, by
            // steps of 2¹⁰ first: the bound may be far above it).
            let (mut lo, mut hi, rel) = (zero.clone(), bound.clone(), rat(ldexp(1.0, -70)));
            while &hi - &lo > &hi * &rel {
                let mid = if lo.is_zero() {
                    &hi / rat(1024.0)
                } else {
                    (&lo + &hi) / &two
                };
                if roots(&sf, &zero, &mid) > 0 {
                    hi = mid
                } else {
                    lo = mid
                }
            }
            if roots(&sd, &zero, &lo) > 0 {
                // Turns to approach inside the overlap: the answer is that turn.
                let (a, b) = window.expect("turns while in contact");
                assert_eq!(roots(&sd, &zero, &a), 0, "turn before {got:?}");
                assert!(roots(&sd, &a, &b) >= 1 && b < lo, "no turn at {got:?}");
                return got;
            }
            hi
        };
        match window {
            None => assert_eq!(roots(&sf, &start, &bound), 0, "missed contact"),
            Some((a, b)) => {
                let a = a.max(start.clone());
                assert_eq!(roots(&sf, &start, &a), 0, "contact before {got:?}");
                assert!(roots(&sf, &a, &b) >= 1, "no contact at {got:?}");
            }
        }
        got
    }

    /// [`contacts_accelerating`] for a point outside the ball (`f(0) > 0`), checked against
    /// the exact quartic: its first answer is [`first_contact_accelerating`]'s bit for bit;
    /// every answer is, within `1e-9·(1 + t)`, either the next root where `f` turns negative
    /// (the roots alternate, down then up) or, inside the ball, a root of `f'` where the point
    /// turns back towards the centre; and every root where `f` turns negative has its answer.
    /// Tangencies (a repeated root of `f` or `f'`) are outside what rounding decides and
    /// skipped.
    fn checked_contacts<const D: usize>(dp: Vector<D>, dv: Vector<D>, acc: Vector<D>, sigma: f64) {
        let all = contacts_accelerating(dp, dv, acc, sigma);
        let first = first_contact_accelerating(dp, dv, acc, sigma);
        assert_eq!(all[0].map(f64::to_bits), first.map(f64::to_bits));
        let got: Vec<f64> = all.iter().flatten().copied().collect();
        assert_eq!(
            got.len(),
            all.iter().take_while(|t| t.is_some()).count(),
            "{all:?}"
        );
        assert!(
            got.windows(2).all(|w| w[0] < w[1]),
            "not increasing: {got:?}"
        );
        let dot = |a: Vector<D>, b: Vector<D>| -> BigRational {
            (0..D).map(|k| rat(a[k]) * rat(b[k])).sum()
        };
        let f = vec![
            dot(dp, dp) - rat(sigma) * rat(sigma),
            rat(2.0) * dot(dp, dv),
            dot(dv, dv) + dot(dp, acc),
            dot(dv, acc),
            dot(acc, acc) / rat(4.0),
        ];
        let zero = BigRational::zero();
        if f[0] <= zero || acc.0.iter().all(|&a| a == 0.0) || dp.norm_sq() <= sigma * sigma {
            return;
        }
        let (sf, sd) = (sturm(f.clone()), sturm(derivative(&f)));
        if sf[sf.len() - 1].len() > 1 || sd[sd.len() - 1].len() > 1 {
            return;
        }
        let bound = f[..4]
            .iter()
            .fold(rat(1.0), |m, c| m.max((c / &f[4]).abs()))
            + rat(1.0);
        let value = |t: &BigRational| f.iter().rev().fold(zero.clone(), |acc, c| acc * t + c);
        let mut entries = 0;
        for &t in &got {
            let tol = rat(1e-9) * (rat(1.0) + rat(t));
            let (a, b) = ((rat(t) - &tol).max(zero.clone()), rat(t) + &tol);
            if roots(&sf, &a, &b) >= 1 {
                assert_eq!(roots(&sf, &zero, &a), 2 * entries, "entry at {t}: {got:?}");
                entries += 1;
            } else {
                assert!(
                    value(&rat(t)) < zero,
                    "{t} is no entry and not inside: {got:?}"
                );
                assert!(
                    roots(&sd, &a, &b) >= 1,
                    "{t} is no entry and no turn: {got:?}"
                );
            }
        }
        let total = roots(&sf, &zero, &bound);
        assert_eq!(entries, total / 2, "{got:?}: {total} roots");
    }

    #[test]
    fn a_point_thrown_through_the_ball_and_back_enters_twice() {
        // x = −3 + 3t − t²/2 along the axis, against the ball of radius 1: in through x = −1
        // at t = 3 − √5, out through x = 1 at t = 2, turned at x = 1.5 (t = 3), and back in
        // through x = 1 at t = 4.
        let (dp, dv, acc) = (v2(-3.0, 0.0), v2(3.0, 0.0), v2(-1.0, 0.0));
        let all = contacts_accelerating(dp, dv, acc, 1.0);
        assert!(close(all[0], 3.0 - 5f64.sqrt()), "{all:?}");
        assert!(close(all[1], 4.0), "{all:?}");
        assert_eq!(all[2], None);
        checked_contacts(dp, dv, acc, 1.0);
        // Zero acceleration: the straight line's one contact.
        let straight = contacts_accelerating(dp, dv, Vector::ZERO, 1.0);
        assert_eq!(straight, [first_contact(dp, dv, 1.0), None, None]);
    }

    fn close(t: Option<f64>, want: f64) -> bool {
        t.is_some_and(|t| (t - want).abs() <= 8.0 * f64::EPSILON * want)
    }

    #[test]
    fn dropped_ball_meets_point_below_at_free_fall_time() {
        // The ball falls from rest, its centre 3 m above the point: relative to the ball the
        // point rises at g, and the gap of 2 m closes when ½·g·t² = 2.
        let g = 9.81f64;
        let t = checked(v2(0.0, -3.0), Vector::ZERO, v2(0.0, g), 1.0, 1.0);
        assert!(close(t, (4.0 / g).sqrt()), "{t:?}");
        let t = checked(
            Vector([0.0, 0.0, -3.0]),
            Vector::ZERO,
            Vector([0.0, 0.0, g]),
            1.0,
            1.0,
        );
        assert!(close(t, (4.0 / g).sqrt()), "{t:?}");
    }

    #[test]
    fn acceleration_bends_a_miss_into_a_hit() {
        // Straight, the point passes 2 m from the centre; bent down, x(1) = (0, 1).
        let (dp, dv, acc) = (v2(-5.0, 2.0), v2(5.0, 0.0), v2(0.0, -2.0));
        assert_eq!(first_contact(dp, dv, 1.0), None);
        assert!(close(checked(dp, dv, acc, 1.0, 1.0), 1.0));
    }

    #[test]
    fn pulled_back_after_receding_or_passing() {
        // x = 2 + t − t²/2 recedes to 2.5, then returns to 1 at t = 1 + √3.
        let t = checked(v2(2.0, 0.0), v2(1.0, 0.0), v2(-1.0, 0.0), 1.0, 1.0);
        assert!(close(t, 1.0 + 3f64.sqrt()), "{t:?}");
        // Passes over the ball 1.4 m from its centre, turns at t = 3, hits on the way back.
        let t = checked(v2(-3.0, 1.5), v2(3.0, 0.0), v2(-1.0, -0.1), 1.0, 1.0);
        assert!(t.is_some_and(|t| t > 3.0 && t < 5.0), "{t:?}");
    }

    #[test]
    fn overlapping_pairs_that_recede() {
        // Leaves the overlap, turns outside at x = 1.4 and comes back to x = 1 at 1 + √0.8.
        let t = checked(v2(0.9, 0.0), v2(1.0, 0.0), v2(-1.0, 0.0), 1.0, 1.0);
        assert!(close(t, 1.0 + 0.8f64.sqrt()), "{t:?}");
        // Turns at t = 0.1 still inside (x = 0.505): that turn is the contact, or the point
        // would pass through the ball and out the far side.
        let t = checked(v2(0.5, 0.0), v2(0.1, 0.0), v2(-1.0, 0.0), 1.0, 1.0);
        assert!(close(t, 0.1), "{t:?}");
        let away = checked(v2(0.9, 0.0), v2(1.0, 0.0), v2(1.0, 0.0), 1.0, 1.0);
        assert_eq!(away, None);
        let now = checked(v2(0.9, 0.0), v2(-1.0, 0.0), v2(5.0, 0.0), 1.0, 1.0);
        assert_eq!(now, Some(0.0));
    }

    #[test]
    fn zero_acceleration_is_first_contact_bit_for_bit() {
        for (dp, dv) in [
            (v2(3.0, 0.5), v2(-1.0, 0.1)),
            (v2(3.0, 0.5), v2(1.0, 0.1)),
            (v2(0.5, 0.5), v2(-1.0, 0.0)),
            (v2(3.0, 0.0), v2(-1e-200, 0.0)),
            (v2(3.0, 2.0), v2(-1.0, 0.0)),
        ] {
            for acc in [v2(0.0, 0.0), v2(-0.0, 0.0)] {
                let got = first_contact_accelerating(dp, dv, acc, 1.0).map(f64::to_bits);
                assert_eq!(got, first_contact(dp, dv, 1.0).map(f64::to_bits));
            }
        }
    }

    #[test]
    fn powers_of_two_in_length_and_time_scale_the_answer_exactly() {
        for (dp, dv, acc, sigma) in [
            (v2(0.0, -3.0), v2(0.0, 0.0), v2(0.0, 9.81), 1.0),
            (v2(-3.0, 1.5), v2(3.0, 0.0), v2(-1.0, -0.1), 1.0),
            (v2(0.5, 0.0), v2(0.1, 0.0), v2(-1.0, 0.0), 1.0),
            (v2(0.9, 0.0), v2(1.0, 0.0), v2(-1.0, 0.0), 1.0),
            (v2(-5.0, 2.0), v2(5.0, 0.0), v2(0.0, -2.0), 1.5),
        ] {
            let t = first_contact_accelerating(dp, dv, acc, sigma).unwrap();
            for (k, j) in [-300, -7, 0, 300, 500]
                .map(|k| [-200, 3, 100].map(|j| (k, j)))
                .concat()
            {
                let (dp, dv, acc) = (scaled(dp, k), scaled(dv, k - j), scaled(acc, k - 2 * j));
                let got = first_contact_accelerating(dp, dv, acc, ldexp(sigma, k));
                assert_eq!(
                    got.map(f64::to_bits),
                    Some(ldexp(t, j).to_bits()),
                    "{k} {j}"
                );
            }
        }
    }

    #[test]
    fn extreme_inputs_give_no_nan() {
        let (a, nan) = (v2(0.0, -9.81), v2(f64::NAN, 0.0));
        assert_eq!(first_contact_accelerating(nan, a, a, 1.0), None);
        assert_eq!(first_contact_accelerating(Vector::ZERO, a, a, 0.0), None);
        // Falls 9·10²⁹⁹ m from rest: at 10⁻³⁰⁰ m/s² in 1.34·10³⁰⁰ s; at 10⁻³²⁰ m/s², later
        // than the largest float.
        let fall = |g: f64| first_contact_accelerating(v2(0.0, 1e300), a * 0.0, v2(0.0, g), 1e299);
        let want = 1.8e300f64.sqrt() * 1e150;
        assert!(fall(-1e-300).is_some_and(|t| (t / want - 1.0).abs() < 1e-12));
        assert_eq!(fall(-1e-320), None);
        // Straight flight past, at 10⁹⁸ free-fall speeds.
        let fast = first_contact_accelerating(v2(-2.0, 0.5), v2(1e100, 0.0), a, 1.0);
        assert_eq!(fast, first_contact(v2(-2.0, 0.5), v2(1e100, 0.0), 1.0));
    }

    fn component(range: f64) -> impl Strategy<Value = f64> {
        prop_oneof![4 => -range..range, 1 => Just(0.0)]
    }

    fn vec2(range: f64) -> impl Strategy<Value = Vector<2>> {
        uniform2(component(range)).prop_map(Vector)
    }

    fn vec3(range: f64) -> impl Strategy<Value = Vector<3>> {
        uniform3(component(range)).prop_map(Vector)
    }

    /// `dv` such that `x(tau) = q·1.2·σ`, `|q|∞ ≤ 1`: mostly hits, some grazes and misses.
    fn aimed(dp: Vector<3>, acc: Vector<3>, sigma: f64, tau: f64, q: Vector<3>) -> Vector<3> {
        (q * (1.2 * sigma) - dp - acc * (0.5 * tau * tau)) * (1.0 / tau)
    }

    /// [`first_exit_accelerating`]'s answer for a point strictly inside the ball, checked
    /// against the exact quartic: no root of `f` before it, one within `1e-9·(1 + t)`.
    fn checked_exit<const D: usize>(dp: Vector<D>, dv: Vector<D>, acc: Vector<D>, sigma: f64) {
        let got = first_exit_accelerating(dp, dv, acc, sigma);
        let dot = |a: Vector<D>, b: Vector<D>| -> BigRational {
            (0..D).map(|k| rat(a[k]) * rat(b[k])).sum()
        };
        let f = vec![
            dot(dp, dp) - rat(sigma) * rat(sigma),
            rat(2.0) * dot(dp, dv),
            dot(dv, dv) + dot(dp, acc),
            dot(dv, acc),
            dot(acc, acc) / rat(4.0),
        ];
        let zero = BigRational::zero();
        if f[0] >= zero || acc.0.iter().all(|&a| a == 0.0) {
            return;
        }
        let sf = sturm(f);
        if sf[sf.len() - 1].len() > 1 {
            return; // a tangency: outside what rounding decides
        }
        // Inside under a non-zero acceleration, the point always leaves.
        let t = got.expect("an accelerated point leaves every ball");
        let tol = rat(1e-9) * (rat(1.0) + rat(t));
        let (a, b) = ((rat(t) - &tol).max(zero.clone()), rat(t) + &tol);
        assert_eq!(roots(&sf, &zero, &a), 0, "left before {t}");
        assert!(roots(&sf, &a, &b) >= 1, "no exit at {t}");
    }

    #[test]
    fn exits_of_straight_and_falling_points() {
        // From the centre at 1 m/s: out at 1 s. Outside and receding: at once. At rest
        // inside: never. Passing by outside: at once.
        assert_eq!(first_exit(v2(0.0, 0.0), v2(1.0, 0.0), 1.0), Some(1.0));
        assert_eq!(first_exit(v2(2.0, 0.0), v2(1.0, 0.0), 1.0), Some(0.0));
        assert_eq!(first_exit(v2(0.5, 0.0), v2(0.0, 0.0), 1.0), None);
        assert_eq!(first_exit(v2(-3.0, 2.0), v2(1.0, 0.0), 1.0), Some(0.0));
        // Entering from the left: out on the far side, 3 s on.
        assert_eq!(first_exit(v2(-2.0, 0.0), v2(1.0, 0.0), 1.0), Some(3.0));
        // Dropped from rest 0.5 m above the centre, falling at 2 m/s²: out when
        // 0.5 − t² = −1.
        let t = first_exit_accelerating(v2(0.0, 0.5), Vector::ZERO, v2(0.0, -2.0), 1.0);
        assert!(close(t, 1.5f64.sqrt()), "{t:?}");
        // Thrown up through the top, turned back inside, out through the bottom.
        let t = first_exit_accelerating(v2(0.0, 0.0), v2(0.0, 1.0), v2(0.0, -1.0), 1.0);
        // x = t − t²/2 reaches 0.5 at most: out at −1, t = 1 + √3.
        assert!(close(t, 1.0 + 3f64.sqrt()), "{t:?}");
        // Zero acceleration is the straight line, bit for bit.
        assert_eq!(
            first_exit_accelerating(v2(0.3, -0.2), v2(1.0, 0.5), Vector::ZERO, 1.0),
            first_exit(v2(0.3, -0.2), v2(1.0, 0.5), 1.0)
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn matches_exact_reference_2d(
            dp in vec2(5.0), dv in vec2(5.0), acc in vec2(10.0), sigma in 0.1..2.0f64,
        ) {
            checked(dp, dv, acc, sigma, 1.0);
        }

        #[test]
        fn matches_exact_reference_3d(
            dp in vec3(5.0), dv in vec3(5.0), acc in vec3(10.0), sigma in 0.1..2.0f64,
        ) {
            checked(dp, dv, acc, sigma, 1.0);
        }

        #[test]
        fn matches_exact_reference_from_overlap(
            dp in vec2(1.5), dv in vec2(2.0), acc in vec2(10.0), sigma in 0.1..2.0f64,
        ) {
            checked(dp, dv, acc, sigma, 1.0);
        }

        #[test]
        fn matches_exact_reference_aimed(
            dp in vec3(5.0), acc in vec3(10.0), sigma in 0.1..2.0f64,
            tau in 0.1..3.0f64, q in vec3(1.0),
        ) {
            checked(dp, aimed(dp, acc, sigma, tau, q), acc, sigma, 1.0);
        }

        #[test]
        fn matches_exact_reference_across_scales(
            dp in uniform3(-5.0..5.0f64), sigma in 0.1..2.0f64, q in uniform3(-1.0..1.0f64),
            acc in uniform3(-10.0..10.0f64), k in -40..40i32, r in -30..20i32,
        ) {
            // Aimed at 2^k s, 2^±40, with the free-fall time 2^-10..2^15 times that.
            let (dp, acc, q) = (Vector(dp), scaled(Vector(acc), r - 2 * k), Vector(q));
            let dv = aimed(dp, acc, sigma, ldexp(1.0, k), q);
            // Beyond 2^20·σ from the origin, positions in f64 err by over 1e-10·σ: whether the
            // path meets the ball there is not decided by the input floats. Roots lie below
            // twice the largest |a_i/a4|^(1/(4−i)) (Fujiwara).
            let (a4, a3, a2) = (0.25 * acc.norm_sq(), dv.dot(acc), dv.norm_sq() + dp.dot(acc));
            let (a1, a0) = (2.0 * dp.dot(dv), dp.norm_sq() - sigma * sigma);
            let bound = 2.0 * [a3 / a4, (a2 / a4).abs().sqrt(), (a1 / a4).abs().cbrt(),
                (a0 / a4).abs().sqrt().sqrt()].into_iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let t = first_contact_accelerating(dp, dv, acc, sigma).map_or(bound, |t| 1.1 * t);
            if dp.norm() + dv.norm() * t + 0.5 * acc.norm() * t * t <= 1_048_576.0 * sigma {
                checked(dp, dv, acc, sigma, 0.0);
            }
        }

        #[test]
        fn every_contact_matches_exact_reference(
            dp in vec3(5.0), dv in vec3(5.0), acc in vec3(10.0), sigma in 0.1..2.0f64,
        ) {
            checked_contacts(dp, dv, acc, sigma);
        }

        #[test]
        fn every_contact_matches_exact_reference_aimed(
            dp in vec3(5.0), acc in vec3(10.0), sigma in 0.1..2.0f64,
            tau in 0.1..3.0f64, q in vec3(1.0),
        ) {
            checked_contacts(dp, aimed(dp, acc, sigma, tau, q), acc, sigma);
        }

        #[test]
        fn exits_match_exact_reference(
            dp in vec3(1.5), dv in vec3(3.0), acc in vec3(10.0), sigma in 0.5..2.0f64,
        ) {
            checked_exit(dp, dv, acc, sigma);
        }

        #[test]
        fn exits_match_exact_reference_2d(
            dp in vec2(1.5), dv in vec2(3.0), acc in vec2(10.0), sigma in 0.5..2.0f64,
        ) {
            checked_exit(dp, dv, acc, sigma);
        }
    }
}

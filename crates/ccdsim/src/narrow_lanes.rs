//! Two pairs' times of impact at once: [`toi_circle_circle`] and
//! [`toi_circle_circle_shifted`] evaluated in the two lanes of one register, bit for bit.
//!
//! The lanes are `wide::f64x2`: packed SSE2 on x86-64, plain pairs of `f64` where a target
//! has no such instructions; safe code either way (the `core::arch` intrinsics themselves
//! can only be called without `unsafe` from functions marked `#[target_feature]`, and
//! plain `[f64; 2]` arithmetic left to LLVM's SLP vectoriser came out pairing a pair's
//! components rather than two pairs, and no cheaper than the scalar code).
//!
//! Why the lanes are exact: each lane performs the scalar function's operations, on the same
//! operands, in the same order (positions `pos + vel·(T − time)`, the displacement
//! `(x_b − x_a) + shift`, `dv = v_b − v_a`, the dot products summed `((0 + x₀y₀) + x₁y₁) + x₂y₂`,
//! `c = |dp|² − σ²`, `disc = b² − a·c`, `T + c / (−b + √disc)`), and SSE2's packed `add`, `sub`,
//! `mul`, `div` and `sqrt` round each lane exactly as the scalar instructions do (IEEE 754,
//! round to nearest; Rust never contracts into fused multiply-adds). A lane's result is used only when the scalar code
//! would take the same path: the pair recedes (`b ≥ 0`: none), or it approaches with `c > 0`,
//! `a ≥ 2⁻⁶⁰⁰` and then misses (`disc < 0`: none) or hits (the root above). Every other lane
//! (an overlap, a tiny relative speed, a NaN) is handed to the scalar function on that pair's
//! own arguments, so it is the scalar result by construction.
//!
//! One step differs, `T = max(t_a, t_b)`: the lanes take SSE2's `max` (one instruction; the
//! scalar `f64::max` adds a NaN fix-up). For times that are not NaN both give the larger
//! time, up to the sign of a zero when `t_a = t_b = 0` (which `f64::max` leaves unspecified
//! too). That sign changes no result: positions `pos + vel·(T − time)` and the displacement
//! then differ at most in the signs of zeros, which `b` (a sum of products: a zero only
//! matters when all terms are zero, and then `b = ±0` recedes either way), `c` and `a`
//! (squares) cannot see, and the time `T + dt` has `dt ≥ +0`, so `±0 + dt` is the same
//! float. A NaN time makes `T − time` or `T` NaN, so `b` is NaN and the lane goes to the
//! scalar function.

use crate::geom::Vector;
use crate::narrow::{toi_circle_circle, toi_circle_circle_shifted, Motion, MIN_UNSCALED_A};
use wide::{f64x2, CmpGe, CmpGt, CmpLt};

/// One pair's arguments, in the oracle's order: the first ball's motion and radius, the
/// second's, and (shifted evaluations only) the displacement of the second ball's image.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairArgs<'a, const D: usize> {
    /// First ball's stored motion.
    pub a: &'a Motion<D>,
    /// First ball's radius, metres.
    pub ra: f64,
    /// Second ball's stored motion.
    pub b: &'a Motion<D>,
    /// Second ball's radius, metres.
    pub rb: f64,
    /// Displacement of the second ball's image, metres (ignored unless `SHIFTED`).
    pub shift: &'a Vector<D>,
}

impl<const D: usize> PairArgs<'_, D> {
    /// The scalar time of impact: [`toi_circle_circle_shifted`] if `SHIFTED`, else
    /// [`toi_circle_circle`].
    #[inline(always)]
    pub fn scalar<const SHIFTED: bool>(&self) -> Option<f64> {
        if SHIFTED {
            toi_circle_circle_shifted(self.a, self.ra, self.b, self.rb, *self.shift)
        } else {
            toi_circle_circle(self.a, self.ra, self.b, self.rb)
        }
    }
}

/// [`PairArgs::scalar`] out of line, for the lanes left to the scalar function: rare, and
/// kept out of the scan loops, whose registers an inlined copy would cost.
#[cold]
#[inline(never)]
pub(crate) fn rare<const D: usize, const SHIFTED: bool>(p: PairArgs<'_, D>) -> Option<f64> {
    p.scalar::<SHIFTED>()
}

/// The outcome of the two lanes: per lane a time of impact (bit `k` of `hits`), none, or
/// a rare path left to the scalar function (bit `k` of `rare`: an overlap, a tiny relative
/// speed, a NaN).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lanes {
    /// Each lane's time of impact, where its bit of `hits` is set.
    pub times: [f64; 2],
    /// Lanes with a time of impact.
    pub hits: u32,
    /// Lanes left to the scalar function.
    pub rare: u32,
}

impl Lanes {
    /// Calls `f(k, t)` for each lane `k` (in order) whose pair meets, at time `t`; the time of
    /// a rare lane comes from `scalar(k)`.
    #[inline(always)]
    pub fn each_time(self, mut f: impl FnMut(usize, f64), scalar: impl Fn(usize) -> Option<f64>) {
        if self.rare == 0 {
            // The common case: two bit tests.
            if self.hits & 1 != 0 {
                f(0, self.times[0]);
            }
            if self.hits & 2 != 0 {
                f(1, self.times[1]);
            }
            return;
        }
        for k in 0..2 {
            let t = if self.rare >> k & 1 != 0 {
                scalar(k)
            } else {
                (self.hits >> k & 1 != 0).then_some(self.times[k])
            };
            if let Some(t) = t {
                f(k, t);
            }
        }
    }

    /// Each lane's time of impact, the rare lanes' from `scalar(k)`.
    #[cfg(test)]
    fn times(self, scalar: impl Fn(usize) -> Option<f64>) -> [Option<f64>; 2] {
        let mut out = [None; 2];
        self.each_time(|k, t| out[k] = Some(t), scalar);
        out
    }
}

/// One side of two pairs (their first balls, or their second balls), one pair per lane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side<const D: usize> {
    /// Reference positions, metres.
    pos: [f64x2; D],
    /// Velocities, metres per second.
    vel: [f64x2; D],
    /// Reference times, seconds.
    time: f64x2,
    /// Radii, metres.
    radius: f64x2,
}

/// `[x0, x1]` as lanes 0 and 1.
#[inline(always)]
fn lanes(x0: f64, x1: f64) -> f64x2 {
    f64x2::new([x0, x1])
}

/// The vectors `v[0]` and `v[1]` as lanes 0 and 1 of each component.
#[inline(always)]
pub(crate) fn vector_lanes<const D: usize>(v: [&Vector<D>; 2]) -> [f64x2; D] {
    std::array::from_fn(|k| lanes(v[0].0[k], v[1].0[k]))
}

impl<const D: usize> Side<D> {
    /// The balls of motions `m[0]`, `m[1]` and radii `r[0]`, `r[1]` in lanes 0 and 1.
    #[inline(always)]
    pub fn gather(m: [&Motion<D>; 2], r: [f64; 2]) -> Self {
        Side {
            pos: vector_lanes([&m[0].pos, &m[1].pos]),
            vel: vector_lanes([&m[0].vel, &m[1].vel]),
            time: lanes(m[0].time, m[1].time),
            radius: lanes(r[0], r[1]),
        }
    }

    /// One ball (motion `m`, radius `r`) in both lanes: built once for a scan that pairs a
    /// body with each of its neighbours.
    #[inline(always)]
    pub fn splat(m: &Motion<D>, r: f64) -> Self {
        Side::gather([m, m], [r, r])
    }
}

/// The times of impact of the pair in each lane, its first ball on side `sa` and its second
/// on side `sb`, displaced by `shift` if `SHIFTED`: in each lane the scalar function's result
/// bit for bit (see the module docs), a lane on a rare path left to the caller
/// ([`Lanes::rare`]).
#[inline(always)]
pub(crate) fn toi_sides<const D: usize, const SHIFTED: bool>(
    sa: &Side<D>,
    sb: &Side<D>,
    shift: &[f64x2; D],
) -> Lanes {
    let zero = f64x2::ZERO;
    let t0 = sa.time.fast_max(sb.time);
    let dta = t0 - sa.time;
    let dtb = t0 - sb.time;
    // `s = 0.0; s += x·y` per component, as `Vector::dot`.
    let (mut b, mut pp, mut vv) = (zero, zero, zero);
    for (k, &shift) in shift.iter().enumerate() {
        let (va, vb) = (sa.vel[k], sb.vel[k]);
        let xa = sa.pos[k] + va * dta;
        let xb = sb.pos[k] + vb * dtb;
        let mut dp = xb - xa;
        if SHIFTED {
            dp += shift;
        }
        let dv = vb - va;
        b += dp * dv;
        pp += dp * dp;
        vv += dv * dv;
    }
    // No early exit when both pairs recede: a branch taken about one time in four costs
    // more in mispredictions than the rest of the kernel (3D list mode, N = 10,976: +2 %
    // instructions, about 7 % more collisions per CPU second).
    let recedes = b.cmp_ge(zero);
    let sigma = sa.radius + sb.radius;
    let c = pp - sigma * sigma;
    let disc = b * b - vv * c;
    let neg_b = b ^ f64x2::splat(-0.0);
    let t = (t0 + c / (neg_b + disc.sqrt())).to_array();
    // The lanes on the scalar code's common path: approaching, apart, not tiny.
    let regular = c.cmp_gt(zero) & vv.cmp_ge(f64x2::splat(MIN_UNSCALED_A)) & b.cmp_lt(zero);
    let hits = (regular & disc.cmp_ge(zero)).move_mask() as u32;
    let misses = (recedes | (regular & disc.cmp_lt(zero))).move_mask() as u32;
    Lanes {
        times: t,
        hits,
        rare: !(hits | misses) & 0b11,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// [`toi_sides`] on two pairs' arguments.
    fn toi_pair_lanes<const D: usize, const SHIFTED: bool>(p: &[PairArgs<'_, D>; 2]) -> Lanes {
        let [p0, p1] = p;
        let sa = Side::gather([p0.a, p1.a], [p0.ra, p1.ra]);
        let sb = Side::gather([p0.b, p1.b], [p0.rb, p1.rb]);
        toi_sides::<D, SHIFTED>(&sa, &sb, &vector_lanes([p0.shift, p1.shift]))
    }

    fn motion<const D: usize>(pos: [f64; D], vel: [f64; D], time: f64) -> Motion<D> {
        Motion {
            pos: Vector(pos),
            vel: Vector(vel),
            time,
        }
    }

    /// Both pair orders and both shift modes, compared bit for bit with the scalar function.
    fn check<const D: usize>(m: [Motion<D>; 4], r: [f64; 4], shift: [Vector<D>; 2]) {
        let args = |x: usize, y: usize, s: usize| PairArgs {
            a: &m[x],
            ra: r[x],
            b: &m[y],
            rb: r[y],
            shift: &shift[s],
        };
        for (x0, y0, x1, y1) in [
            (0, 1, 2, 3),
            (1, 0, 3, 2),
            (0, 1, 0, 1),
            (2, 3, 1, 0),
            (0, 1, 0, 3),
        ] {
            let p = [args(x0, y0, 0), args(x1, y1, 1)];
            let bits = |t: Option<f64>| t.map(f64::to_bits);
            let plain = toi_pair_lanes::<D, false>(&p).times(|k| p[k].scalar::<false>());
            let shifted = toi_pair_lanes::<D, true>(&p).times(|k| p[k].scalar::<true>());
            for k in 0..2 {
                assert_eq!(bits(plain[k]), bits(p[k].scalar::<false>()), "{p:?}");
                assert_eq!(bits(shifted[k]), bits(p[k].scalar::<true>()), "{p:?}");
            }
            // One ball on one side of both lanes, as the neighbour scans pass it.
            if x0 == x1 {
                let sa = Side::splat(&m[x0], r[x0]);
                let sb = Side::gather([&m[y0], &m[y1]], [r[y0], r[y1]]);
                let s = vector_lanes([&shift[0], &shift[1]]);
                let lanes = toi_sides::<D, true>(&sa, &sb, &s);
                let times = lanes.times(|k| p[k].scalar::<true>());
                for k in 0..2 {
                    assert_eq!(bits(times[k]), bits(p[k].scalar::<true>()), "{p:?}");
                }
            }
        }
    }

    #[test]
    fn rare_branches_agree_with_the_scalar_function() {
        let head_on = motion([0.0, 0.0], [1.0, 0.0], 0.0);
        let towards = motion([10.0, 0.0], [-1.0, 0.0], 0.0);
        let overlapping = motion([1.5, 0.0], [-1.0, 0.0], 3.0);
        let tiny = motion([0.0, 3.0], [0.0, -1e-200], 0.0);
        let tinier = motion([0.0, 3.0], [0.0, -1e-320], 0.0);
        let still = motion([0.0, 0.0], [0.0, 0.0], 0.0);
        let grazing = motion([0.0, 2.0], [1.0, 0.0], -0.0); // b = 0 against `head_on`
        let r = [1.0, 1.0, 1.0, 1.0];
        let s = [Vector([0.0, 0.0]), Vector([-0.0, 5.0])];
        // A hit and a miss, an overlap and a tiny speed, b = 0, zero-signed times.
        check([head_on, towards, overlapping, still], r, s);
        check([still, tiny, still, tinier], r, s);
        check([head_on, grazing, still, still], r, s);
        check([grazing, towards, tiny, overlapping], r, s);
        // Underflowing speeds: |dv|² = 0 with b < 0.
        check([still, tinier, tinier, still], r, s);
        // Equal zero times of either sign, and NaN times (left to the scalar function).
        let zero_time = motion([10.0, 0.0], [-1.0, 0.0], 0.0);
        let nan_time = motion([10.0, 0.0], [-1.0, 0.0], f64::NAN);
        check([grazing, zero_time, zero_time, grazing], r, s);
        check([head_on, nan_time, nan_time, head_on], r, s);
        // The common path is taken where it applies; an overlap is left to the scalar code.
        let lanes = toi_pair_lanes::<2, false>(&[
            PairArgs {
                a: &head_on,
                ra: 1.0,
                b: &towards,
                rb: 1.0,
                shift: &s[0],
            },
            PairArgs {
                a: &still,
                ra: 1.0,
                b: &overlapping,
                rb: 1.0,
                shift: &s[0],
            },
        ]);
        assert_eq!((lanes.hits, lanes.rare, lanes.times[0]), (0b01, 0b10, 4.0));
    }

    /// Finite values from gentle to extreme, both signs, with zeros and tiny numbers.
    fn value() -> impl Strategy<Value = f64> {
        prop_oneof![
            6 => -10.0..10.0f64,
            1 => -1e150..1e150f64,
            1 => -1e-150..1e-150f64,
            1 => Just(0.0),
            1 => Just(-0.0),
            1 => (-1.0..1.0f64).prop_map(|x| x * 1e-200),
        ]
    }

    fn motion3() -> impl Strategy<Value = Motion<3>> {
        (
            proptest::array::uniform3(value()),
            proptest::array::uniform3(value()),
            prop_oneof![3 => 0.0..5.0f64, 1 => Just(0.0), 1 => Just(-0.0)],
        )
            .prop_map(|(p, v, t)| motion(p, v, t))
    }

    fn motion2() -> impl Strategy<Value = Motion<2>> {
        (
            proptest::array::uniform2(value()),
            proptest::array::uniform2(value()),
            prop_oneof![3 => 0.0..5.0f64, 1 => Just(0.0), 1 => Just(-0.0)],
        )
            .prop_map(|(p, v, t)| motion(p, v, t))
    }

    /// Near pairs: positions within a few radii and velocities of order one, so that hits,
    /// misses and overlaps all occur often.
    fn near2() -> impl Strategy<Value = Motion<2>> {
        (
            proptest::array::uniform2(-3.0..3.0f64),
            proptest::array::uniform2(-2.0..2.0f64),
            0.0..1.0f64,
        )
            .prop_map(|(p, v, t)| motion(p, v, t))
    }

    fn shift<const D: usize>() -> impl Strategy<Value = Vector<D>> {
        proptest::array::uniform::<_, D>(prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(20.0),
            Just(-20.0)
        ])
        .prop_map(Vector)
    }

    proptest! {
        #[test]
        fn lanes_agree_with_the_scalar_function_2d(
            m in proptest::array::uniform4(motion2()),
            r in proptest::array::uniform4(0.01..2.0f64),
            s in proptest::array::uniform2(shift::<2>()),
        ) {
            check(m, r, s);
        }

        #[test]
        fn lanes_agree_with_the_scalar_function_near_pairs(
            m in proptest::array::uniform4(near2()),
            r in proptest::array::uniform4(0.3..1.0f64),
            s in proptest::array::uniform2(shift::<2>()),
        ) {
            check(m, r, s);
        }

        #[test]
        fn lanes_agree_with_the_scalar_function_3d(
            m in proptest::array::uniform4(motion3()),
            r in proptest::array::uniform4(0.01..2.0f64),
            s in proptest::array::uniform2(shift::<3>()),
        ) {
            check(m, r, s);
        }
    }
}

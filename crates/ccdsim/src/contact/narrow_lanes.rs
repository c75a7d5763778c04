//! Four pairs' times of impact at once:
//! [`toi_circle_circle`](crate::contact::narrow::toi_circle_circle) and
//! [`toi_circle_circle_shifted`](crate::contact::narrow::toi_circle_circle_shifted) evaluated in
//! the four lanes of one register, bit for bit.
//!
//! The lanes are `wide::f64x4`: one AVX register (`ymm`) where the build targets AVX (the
//! default `x86-64-v3`), a pair of SSE2 registers on plain x86-64, plain `f64`s where a
//! target has neither; safe code in every case (the `core::arch` intrinsics themselves can
//! only be called without `unsafe` from functions marked `#[target_feature]`, and plain
//! `[f64; N]` arithmetic left to LLVM's SLP vectoriser came out pairing a pair's components
//! rather than pairs, and no cheaper than the scalar code). Four lanes rather than two
//! (3D list mode, N = 10,976, callgrind: the list scans' `recompute_listed` 3,135 → 2,920
//! instructions per collision): the fixed costs of a step (loop, masks, the offers' tests)
//! are paid once per four entries, and a list is one stream of quads, not two parts each
//! with a scalar remainder.
//!
//! Why the lanes are exact: each lane performs the scalar function's operations, on the same
//! operands, in the same order (positions `pos + vel·(T − time)`, the displacement
//! `(x_b − x_a) + shift`, `dv = v_b − v_a`, the dot products summed `((0 + x₀y₀) + x₁y₁) + x₂y₂`,
//! `c = |dp|² − σ²`, `disc = b² − a·c`, `T + c / (−b + √disc)`), and the packed `add`, `sub`,
//! `mul`, `div` and `sqrt` (AVX `vaddpd`, `vsubpd`, `vmulpd`, `vdivpd`, `vsqrtpd` on `ymm`, or
//! SSE2's on `xmm`) round each lane exactly as the scalar instructions do (IEEE 754, round
//! to nearest; Rust never contracts into fused multiply-adds, FMA or not). The lanes' inputs
//! are copies of the pair's operands: gathered from the records, put in all lanes
//! ([`Side::splat`]), or chosen lane by lane between two such sides ([`Side::select`], a
//! blend: bits moved, nothing computed), so a lane whose first ball is chosen from one side
//! and second ball from the other computes exactly its pair in the oracle's order; lanes
//! that only pad a short quad are dropped ([`Lanes::only`]): no time, no call to the scalar
//! function. A lane's result is used only when the scalar code
//! would take the same path: the pair recedes (`b ≥ 0`: none), or it approaches with `c > 0`,
//! `a ≥ 2⁻⁶⁰⁰` and then misses (`disc < 0`: none) or hits (the root above). Every other lane
//! (an overlap, a tiny relative speed, a NaN) is handed to the scalar function on that pair's
//! own arguments, so it is the scalar result by construction.
//!
//! One step differs, `T = max(t_a, t_b)`: the lanes take the packed `max` (`vmaxpd` or
//! `maxpd`, one instruction, the same rule per lane; the scalar `f64::max` adds a NaN
//! fix-up). For times that are not NaN both give the larger
//! time, up to the sign of a zero when `t_a = t_b = 0` (which `f64::max` leaves unspecified
//! too). That sign changes no result: positions `pos + vel·(T − time)` and the displacement
//! then differ at most in the signs of zeros, which `b` (a sum of products: a zero only
//! matters when all terms are zero, and then `b = ±0` recedes either way), `c` and `a`
//! (squares) cannot see, and the time `T + dt` has `dt ≥ +0`, so `±0 + dt` is the same
//! float. A NaN time makes `T − time` or `T` NaN, so `b` is NaN and the lane goes to the
//! scalar function.

use crate::contact::narrow::MIN_UNSCALED_A;
use crate::contact::{toi_pair, toi_pair_shifted};
use crate::geom::Vector;
use crate::motion::GrowthLaw;
use crate::motion::Laws;
use crate::motion::Motion;
use wide::{f64x4, CmpGe, CmpGt, CmpLe, CmpLt};

/// Pairs evaluated at once: the lanes of one register.
pub(crate) const LANES: usize = 4;

/// Bits of all lanes.
pub(crate) const ALL_LANES: u32 = (1 << LANES) - 1;

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
    /// The world's laws, if any is in force (see [`crate::motion::Laws`]).
    pub laws: Option<&'a Laws<D>>,
}

impl<const D: usize> PairArgs<'_, D> {
    /// The scalar time of impact: [`toi_pair_shifted`] if `SHIFTED`, else [`toi_pair`].
    #[inline(always)]
    pub fn scalar<const SHIFTED: bool>(&self) -> Option<f64> {
        if SHIFTED {
            toi_pair_shifted(self.a, self.ra, self.b, self.rb, *self.shift, self.laws)
        } else {
            toi_pair(self.a, self.ra, self.b, self.rb, self.laws)
        }
    }
}

/// The outcome of the lanes: per lane a time of impact (bit `k` of `hits`), none, or a rare
/// path left to the scalar function (bit `k` of `rare`: an overlap, a tiny relative speed, a
/// NaN).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lanes {
    /// Each lane's time of impact, where its bit of `hits` is set.
    pub times: [f64; LANES],
    /// Lanes with a time of impact.
    pub hits: u32,
    /// Lanes left to the scalar function.
    pub rare: u32,
}

impl Lanes {
    /// Every lane left to the scalar function (laws the kernels do not model: gravity).
    #[inline(always)]
    #[must_use]
    pub fn all_rare() -> Lanes {
        Lanes {
            times: [0.0; LANES],
            hits: 0,
            rare: ALL_LANES,
        }
    }

    /// The lanes of `valid` only (the others hold padding: no time, nothing rare).
    #[inline(always)]
    #[must_use]
    pub fn only(self, valid: u32) -> Lanes {
        Lanes {
            hits: self.hits & valid,
            rare: self.rare & valid,
            ..self
        }
    }

    /// Calls `f(k, t)` for each lane `k` (in order) whose pair meets, at time `t`; the time of
    /// a rare lane comes from `scalar(k)`.
    #[inline(always)]
    pub fn each_time(self, mut f: impl FnMut(usize, f64), scalar: impl Fn(usize) -> Option<f64>) {
        if self.rare == 0 {
            // The common case: one pass over the hit bits.
            let mut hits = self.hits;
            while hits != 0 {
                let k = hits.trailing_zeros() as usize;
                f(k, self.times[k]);
                hits &= hits - 1;
            }
            return;
        }
        for k in 0..LANES {
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
    fn times(self, scalar: impl Fn(usize) -> Option<f64>) -> [Option<f64>; LANES] {
        let mut out = [None; LANES];
        self.each_time(|k, t| out[k] = Some(t), scalar);
        out
    }
}

/// One side of four pairs (their first balls, or their second balls), one pair per lane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side<const D: usize> {
    /// Reference positions, metres.
    pos: [f64x4; D],
    /// Velocities, metres per second.
    vel: [f64x4; D],
    /// Reference times, seconds.
    time: f64x4,
    /// Radii, metres.
    radius: f64x4,
}

/// The vectors `v[k]` as lane `k` of each component.
#[inline(always)]
pub(crate) fn vector_lanes<const D: usize>(v: [&Vector<D>; LANES]) -> [f64x4; D] {
    std::array::from_fn(|d| f64x4::new(v.map(|v| v.0[d])))
}

/// A lane mask: all bits set in lanes `k < n`, clear in the others.
#[inline(always)]
pub(crate) fn first_lanes(n: usize) -> f64x4 {
    f64x4::new([0.0, 1.0, 2.0, 3.0]).cmp_lt(f64x4::splat(n as f64))
}

/// Component `c` of a ball of motion `m` and radius `r`: its position's, then its
/// velocity's, its time, its radius, then zeros.
#[inline(always)]
fn component<const D: usize>(m: &Motion<D>, r: f64, c: usize) -> f64 {
    if c < D {
        m.pos.0[c]
    } else if c < 2 * D {
        m.vel.0[c - D]
    } else if c == 2 * D {
        m.time
    } else if c == 2 * D + 1 {
        r
    } else {
        0.0
    }
}

/// Components `4·group` to `4·group + 3` of a ball (see [`component`]).
#[inline(always)]
fn row<const D: usize>(m: &Motion<D>, r: f64, group: usize) -> f64x4 {
    let c = LANES * group;
    f64x4::new([
        component(m, r, c),
        component(m, r, c + 1),
        component(m, r, c + 2),
        component(m, r, c + 3),
    ])
}

/// The transpose of four rows: lane `k` of column `c` is lane `c` of row `k` (values moved,
/// not computed).
#[inline(always)]
fn transpose(rows: [f64x4; LANES]) -> [f64x4; LANES] {
    let [a, b, c, d] = rows;
    let (a, b, c, d) = (a.to_array(), b.to_array(), c.to_array(), d.to_array());
    [
        f64x4::new([a[0], b[0], c[0], d[0]]),
        f64x4::new([a[1], b[1], c[1], d[1]]),
        f64x4::new([a[2], b[2], c[2], d[2]]),
        f64x4::new([a[3], b[3], c[3], d[3]]),
    ]
}

impl<const D: usize> Side<D> {
    /// The balls of motions `m[k]` and radii `r[k]` in lanes `k`.
    #[inline(always)]
    pub fn gather(m: [&Motion<D>; LANES], r: [f64; LANES]) -> Self {
        if 2 * D + 2 > 2 * LANES {
            return Side {
                pos: vector_lanes(m.map(|m| &m.pos)),
                vel: vector_lanes(m.map(|m| &m.vel)),
                time: f64x4::new(m.map(|m| m.time)),
                radius: f64x4::new(r),
            };
        }
        // Each ball's components (positions, velocities, time, radius, then zeros) four at a
        // time, one ball per row, then transposed. LLVM still emits one load per value (it
        // folds the shuffles back), but in an order that costs fewer instructions than
        // building the columns directly (callgrind, 3D N = 10,976: −23 per collision).
        let low = transpose([
            row(m[0], r[0], 0),
            row(m[1], r[1], 0),
            row(m[2], r[2], 0),
            row(m[3], r[3], 0),
        ]);
        let high = transpose([
            row(m[0], r[0], 1),
            row(m[1], r[1], 1),
            row(m[2], r[2], 1),
            row(m[3], r[3], 1),
        ]);
        let col = |c: usize| if c < LANES { low[c] } else { high[c - LANES] };
        Side {
            pos: std::array::from_fn(col),
            vel: std::array::from_fn(|d| col(D + d)),
            time: col(2 * D),
            radius: col(2 * D + 1),
        }
    }

    /// One ball (motion `m`, radius `r`) in all lanes: built once for a scan that pairs a
    /// body with each of its neighbours.
    #[inline(always)]
    pub fn splat(m: &Motion<D>, r: f64) -> Self {
        Side::gather([m; LANES], [r; LANES])
    }

    /// Lane by lane, `t`'s ball where `mask` is set, else `f`'s (a copy of the values: no
    /// arithmetic).
    #[inline(always)]
    pub fn select(mask: f64x4, t: &Self, f: &Self) -> Self {
        Side {
            pos: std::array::from_fn(|d| mask.blend(t.pos[d], f.pos[d])),
            vel: std::array::from_fn(|d| mask.blend(t.vel[d], f.vel[d])),
            time: mask.blend(t.time, f.time),
            radius: mask.blend(t.radius, f.radius),
        }
    }
}

/// Per lane, from `T = max(t_a, t_b)`: `T`, `dp·dv`, `|dp|²` and `|dv|²`, with `dp` the second
/// ball's position less the first's at `T` (plus `shift` if `SHIFTED`) and `dv` their relative
/// velocity; the dot products summed `s = 0.0; s += x·y` per component, as `Vector::dot`.
#[inline(always)]
fn relative<const D: usize, const SHIFTED: bool>(
    sa: &Side<D>,
    sb: &Side<D>,
    shift: &[f64x4; D],
) -> (f64x4, f64x4, f64x4, f64x4) {
    let zero = f64x4::ZERO;
    let t0 = sa.time.fast_max(sb.time);
    let dta = t0 - sa.time;
    let dtb = t0 - sb.time;
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
    (t0, b, pp, vv)
}

/// The times of impact of the pair in each lane, its first ball on side `sa` and its second
/// on side `sb`, displaced by `shift` if `SHIFTED`: in each lane the scalar function's result
/// bit for bit (see the module docs), a lane on a rare path left to the caller
/// ([`Lanes::rare`]).
#[inline(always)]
pub(crate) fn toi_sides<const D: usize, const SHIFTED: bool>(
    sa: &Side<D>,
    sb: &Side<D>,
    shift: &[f64x4; D],
) -> Lanes {
    let zero = f64x4::ZERO;
    let (t0, b, pp, vv) = relative::<D, SHIFTED>(sa, sb, shift);
    // No early exit when all pairs recede: a branch on the outcome costs more in
    // mispredictions than the rest of the kernel (two lanes, 3D list mode, N = 10,976: +2 %
    // instructions, about 7 % more collisions per CPU second).
    let recedes = b.cmp_ge(zero);
    let sigma = sa.radius + sb.radius;
    let c = pp - sigma * sigma;
    let disc = b * b - vv * c;
    let neg_b = b ^ f64x4::splat(-0.0);
    let t = (t0 + c / (neg_b + disc.sqrt())).to_array();
    // The lanes on the scalar code's common path: approaching, apart, not tiny.
    let regular = c.cmp_gt(zero) & vv.cmp_ge(f64x4::splat(MIN_UNSCALED_A)) & b.cmp_lt(zero);
    let hits = (regular & disc.cmp_ge(zero)).move_mask() as u32;
    let misses = (recedes | (regular & disc.cmp_lt(zero))).move_mask() as u32;
    Lanes {
        times: t,
        hits,
        rare: !(hits | misses) & ALL_LANES,
    }
}

/// The times of impact of four pairs of growing balls: in each lane
/// [`toi_circle_circle_growing`](crate::contact::growth::toi_circle_circle_growing)'s result bit
/// for bit, by the same operations in the same order (the contact distance `(r_a + r_b)·(1 + Γ·(T −
/// t₀))` and its speed `(r_a + r_b)·Γ`, then `B = dp·dv − σσ̇`, `C = |dp|² − σ²`, `A = |dv|² −
/// σ̇²`, `T + C / (−B + √(B² − AC))`). Unshifted lanes skip the scalar function's `+ 0` shift,
/// which changes at most the sign of a zero component of `dp`, which neither `B` (a zero product
/// only matters when every term is zero, and `σσ̇ > 0` is subtracted) nor the squares can see. A
/// lane is used when the scalar function takes the same path: the pair is apart (`C > 0`) and
/// misses (`disc < 0`, or `−B + √disc ≤ 0`) or hits at a finite time; every other lane (an overlap,
/// an infinite time, a NaN) is left to the scalar function.
#[inline(always)]
pub(crate) fn toi_sides_growing<const D: usize, const SHIFTED: bool>(
    sa: &Side<D>,
    sb: &Side<D>,
    shift: &[f64x4; D],
    law: &GrowthLaw,
) -> Lanes {
    let zero = f64x4::ZERO;
    let (t0, b, pp, vv) = relative::<D, SHIFTED>(sa, sb, shift);
    let rate = f64x4::splat(law.rate);
    let sum = sa.radius + sb.radius;
    let sigma = sum * (f64x4::splat(1.0) + rate * (t0 - f64x4::splat(law.origin)));
    let sigma_dot = sum * rate;
    let b = b - sigma * sigma_dot;
    let c = pp - sigma * sigma;
    let a = vv - sigma_dot * sigma_dot;
    let disc = b * b - a * c;
    let q = (b ^ f64x4::splat(-0.0)) + disc.sqrt();
    let dt = c / q;
    let t = (t0 + dt).to_array();
    let apart = c.cmp_gt(zero);
    let meets = apart & disc.cmp_ge(zero) & q.cmp_gt(zero);
    let hits = (meets & dt.cmp_lt(f64x4::splat(f64::INFINITY))).move_mask() as u32;
    let misses =
        (apart & (disc.cmp_lt(zero) | (disc.cmp_ge(zero) & q.cmp_le(zero)))).move_mask() as u32;
    Lanes {
        times: t,
        hits,
        rare: !(hits | misses) & ALL_LANES,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// [`toi_sides`] on four pairs' arguments.
    fn toi_quad<const D: usize, const SHIFTED: bool>(p: &[PairArgs<'_, D>; LANES]) -> Lanes {
        let sa = Side::gather(p.map(|p| p.a), p.map(|p| p.ra));
        let sb = Side::gather(p.map(|p| p.b), p.map(|p| p.rb));
        toi_sides::<D, SHIFTED>(&sa, &sb, &vector_lanes(p.map(|p| p.shift)))
    }

    fn motion<const D: usize>(pos: [f64; D], vel: [f64; D], time: f64) -> Motion<D> {
        Motion {
            pos: Vector(pos),
            vel: Vector(vel),
            time,
        }
    }

    fn bits(t: Option<f64>) -> Option<u64> {
        t.map(f64::to_bits)
    }

    /// Several pair orders and both shift modes, compared bit for bit with the scalar
    /// function; then, as the list scans pass them, one probe ball against three others in
    /// every mix of lanes with the probe first and lanes with the partner first (the
    /// partner's shift then `0 − shift`), with the last lanes masked off as padding.
    fn check<const D: usize>(m: [Motion<D>; 4], r: [f64; 4], shift: [Vector<D>; 4]) {
        fn args<'a, const D: usize>(
            m: &'a [Motion<D>; 4],
            r: [f64; 4],
            (x, y): (usize, usize),
            shift: &'a Vector<D>,
        ) -> PairArgs<'a, D> {
            PairArgs {
                a: &m[x],
                ra: r[x],
                b: &m[y],
                rb: r[y],
                shift,
                laws: None,
            }
        }
        let pair = |x: usize, y: usize, s| args(&m, r, (x, y), s);
        for pattern in [
            [(0, 1), (2, 3), (1, 0), (3, 2)],
            [(0, 1), (0, 1), (2, 3), (1, 0)],
            [(2, 3), (1, 0), (0, 3), (3, 0)],
            [(0, 1), (0, 2), (0, 3), (1, 2)],
            [(3, 1), (2, 0), (1, 3), (0, 2)],
        ] {
            let p: [PairArgs<'_, D>; LANES] =
                std::array::from_fn(|k| pair(pattern[k].0, pattern[k].1, &shift[k]));
            let plain = toi_quad::<D, false>(&p).times(|k| p[k].scalar::<false>());
            let shifted = toi_quad::<D, true>(&p).times(|k| p[k].scalar::<true>());
            for k in 0..LANES {
                assert_eq!(bits(plain[k]), bits(p[k].scalar::<false>()), "{p:?}");
                assert_eq!(bits(shifted[k]), bits(p[k].scalar::<true>()), "{p:?}");
            }
        }
        // Probe 0 against [1, 2, 3, 1]; lanes `k < first` put the probe first.
        let neg: [Vector<D>; 4] = shift.map(|s| Vector::ZERO - s);
        let others = [1, 2, 3, 1];
        let probe = Side::splat(&m[0], r[0]);
        let other = Side::gather(others.map(|y| &m[y]), others.map(|y| r[y]));
        for first in 0..=LANES {
            let lane_shift: [&Vector<D>; LANES] =
                std::array::from_fn(|k| if k < first { &shift[k] } else { &neg[k] });
            let p: [PairArgs<'_, D>; LANES] = std::array::from_fn(|k| {
                if k < first {
                    pair(0, others[k], lane_shift[k])
                } else {
                    pair(others[k], 0, lane_shift[k])
                }
            });
            let mask = first_lanes(first);
            let sa = Side::select(mask, &probe, &other);
            let sb = Side::select(mask, &other, &probe);
            let s = vector_lanes(lane_shift);
            for valid in [ALL_LANES, 0b0111, 0b0011, 0b0001] {
                let lanes = toi_sides::<D, true>(&sa, &sb, &s).only(valid);
                let times = lanes.times(|k| {
                    assert!(
                        valid >> k & 1 != 0,
                        "padding lane {k} handed to the scalar code"
                    );
                    p[k].scalar::<true>()
                });
                for k in 0..LANES {
                    let want = if valid >> k & 1 != 0 {
                        p[k].scalar::<true>()
                    } else {
                        None
                    };
                    assert_eq!(bits(times[k]), bits(want), "{p:?} first {first}");
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
        let s = [
            Vector([0.0, 0.0]),
            Vector([-0.0, 5.0]),
            Vector([-5.0, 0.0]),
            Vector([5.0, -5.0]),
        ];
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
        let pair = |a, b| PairArgs {
            a,
            ra: 1.0,
            b,
            rb: 1.0,
            shift: &s[0],
            laws: None,
        };
        let lanes = toi_quad::<2, false>(&[
            pair(&head_on, &towards),
            pair(&still, &overlapping),
            pair(&towards, &head_on),
            pair(&still, &grazing),
        ]);
        assert_eq!(
            (lanes.hits, lanes.rare, lanes.times[0], lanes.times[2]),
            (0b0101, 0b0010, 4.0, 4.0)
        );
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

    /// Near pairs in 3D, as the neighbour lists hold them: positions within a few radii,
    /// velocities of order one (some tiny), times a little apart.
    fn near3() -> impl Strategy<Value = Motion<3>> {
        (
            proptest::array::uniform3(-3.0..3.0f64),
            prop_oneof![
                8 => proptest::array::uniform3(-2.0..2.0f64),
                1 => proptest::array::uniform3((-1.0..1.0f64).prop_map(|x| x * 1e-95)),
                1 => Just([0.0; 3]),
            ],
            prop_oneof![4 => 0.0..1.0f64, 1 => Just(0.5)],
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

    /// [`toi_sides_growing`] against the scalar growing function, bit for bit, in several pair
    /// orders and both shift modes.
    fn check_growing<const D: usize>(
        m: [Motion<D>; 4],
        r: [f64; 4],
        shift: [Vector<D>; 4],
        law: GrowthLaw,
    ) {
        fn lanes<const D: usize, const SHIFTED: bool>(
            p: &[PairArgs<'_, D>; LANES],
            law: &GrowthLaw,
        ) -> [Option<f64>; LANES] {
            let sa = Side::gather(p.map(|p| p.a), p.map(|p| p.ra));
            let sb = Side::gather(p.map(|p| p.b), p.map(|p| p.rb));
            let s = vector_lanes(p.map(|p| p.shift));
            toi_sides_growing::<D, SHIFTED>(&sa, &sb, &s, law).times(|k| p[k].scalar::<SHIFTED>())
        }
        for pattern in [
            [(0, 1), (2, 3), (1, 0), (3, 2)],
            [(0, 2), (1, 3), (2, 0), (3, 1)],
            [(0, 1), (0, 2), (0, 3), (1, 2)],
        ] {
            let laws = Laws {
                growth: Some(law),
                gravity: None,
                kinematic: false,
                filtered: false,
                resting: false,
            };
            let p: [PairArgs<'_, D>; LANES] = std::array::from_fn(|k| {
                let (x, y) = pattern[k];
                PairArgs {
                    a: &m[x],
                    ra: r[x],
                    b: &m[y],
                    rb: r[y],
                    shift: &shift[k],
                    laws: Some(&laws),
                }
            });
            let (plain, shifted) = (lanes::<D, false>(&p, &law), lanes::<D, true>(&p, &law));
            for k in 0..LANES {
                assert_eq!(bits(plain[k]), bits(p[k].scalar::<false>()), "{p:?}");
                assert_eq!(bits(shifted[k]), bits(p[k].scalar::<true>()), "{p:?}");
            }
        }
    }

    fn law() -> impl Strategy<Value = GrowthLaw> {
        (1e-4..2.0f64, -5.0..5.0f64).prop_map(|(rate, origin)| GrowthLaw { rate, origin })
    }

    #[test]
    fn growing_lanes_on_hits_misses_and_overlaps() {
        let law = GrowthLaw {
            rate: 0.5,
            origin: 0.0,
        };
        let head_on = motion([0.0, 0.0], [1.0, 0.0], 0.0);
        let receding = motion([10.0, 0.0], [0.2, 0.0], 0.0); // A < 0: meets all the same
        let fleeing = motion([10.0, 0.0], [5.0, 0.0], 1.0); // never
        let overlapping = motion([1.5, 0.0], [0.1, 0.0], 3.0); // left to the scalar code
        let r = [1.0, 1.0, 1.0, 1.0];
        let s = [
            Vector([0.0, 0.0]),
            Vector([-0.0, 5.0]),
            Vector([-5.0, 0.0]),
            Vector([5.0, -5.0]),
        ];
        check_growing([head_on, receding, fleeing, overlapping], r, s, law);
    }

    proptest! {
        #[test]
        fn growing_lanes_agree_with_the_scalar_function(
            m in proptest::array::uniform4(motion2()),
            r in proptest::array::uniform4(0.01..2.0f64),
            s in proptest::array::uniform4(shift::<2>()),
            law in law(),
        ) {
            check_growing(m, r, s, law);
        }

        #[test]
        fn growing_lanes_agree_with_the_scalar_function_near_pairs_3d(
            m in proptest::array::uniform4(near3()),
            r in proptest::array::uniform4(0.3..1.0f64),
            s in proptest::array::uniform4(shift::<3>()),
            law in law(),
        ) {
            check_growing(m, r, s, law);
        }
    }

    proptest! {
        #[test]
        fn lanes_agree_with_the_scalar_function_2d(
            m in proptest::array::uniform4(motion2()),
            r in proptest::array::uniform4(0.01..2.0f64),
            s in proptest::array::uniform4(shift::<2>()),
        ) {
            check(m, r, s);
        }

        #[test]
        fn lanes_agree_with_the_scalar_function_near_pairs(
            m in proptest::array::uniform4(near2()),
            r in proptest::array::uniform4(0.3..1.0f64),
            s in proptest::array::uniform4(shift::<2>()),
        ) {
            check(m, r, s);
        }

        #[test]
        fn lanes_agree_with_the_scalar_function_near_pairs_3d(
            m in proptest::array::uniform4(near3()),
            r in proptest::array::uniform4(0.3..1.0f64),
            s in proptest::array::uniform4(shift::<3>()),
        ) {
            check(m, r, s);
        }

        #[test]
        fn lanes_agree_with_the_scalar_function_3d(
            m in proptest::array::uniform4(motion3()),
            r in proptest::array::uniform4(0.01..2.0f64),
            s in proptest::array::uniform4(shift::<3>()),
        ) {
            check(m, r, s);
        }
    }
}

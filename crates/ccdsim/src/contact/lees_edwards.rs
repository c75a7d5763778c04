//! Lees–Edwards boundaries: a periodic box under simple shear (sliding-brick images).
//!
//! The flow is along x (axis 0) and its gradient along y (axis 1). The copies of the box
//! stacked above it along y slide past it: the copy `s` layers up (`s ∈ ℤ`) is shifted along
//! x by `s · δ(t)`, with the strain offset `δ(t) = γ̇ L_y t mod L_x`, and its bodies move
//! `s · γ̇ L_y` faster along x. Body `b`'s images are therefore
//!
//! `b + s·(δ(t), L_y, 0) + k_x·L_x e_x + k_z·L_z e_z`, moving at `v_b + s·γ̇ L_y e_x`,
//!
//! each linear in time, so a pair's time of impact with an image is the straight-line one of
//! [`first_contact`]. As in an unsheared box ([`crate::contact::periodic`]) stored positions
//! stay in the box: a body leaving through a y face re-enters through the other one shifted
//! by `∓δ(t)` along x and with its x velocity changed by `∓γ̇ L_y` ([`ShearedBox::exit`]),
//! which is the image of it that lies in the box, so nothing physical happens at an exit.
//! At `t = 0` the stacked copies are aligned.
//!
//! [`toi_circle_circle_sheared`] is the pair function every finder evaluates in a sheared
//! box: a pure function of the stored states, like every narrow phase, so finders agree bit
//! for bit. Between exits of either body both centres stay in the box, so the layers
//! `s ∈ {−1, 0, 1}` and `k_z ∈ {−1, 0, 1}` hold every contact, and within the layer (`s = 0`)
//! `k_x ∈ {−1, 0, 1}` as in an unsheared box; along x, though, an image of another layer
//! sweeps past at `γ̇ L_y` and any `k_x` can come: they are visited in the order they pass,
//! starting from the first one that can still touch, and only where the closest approach (a
//! quadratic in `k_x`) comes within the contact distance.

use crate::contact::narrow::first_contact;
use crate::geom::Vector;
use crate::motion::{Body, Laws, Motion};

/// A periodic box of sides `size` sheared at `rate` (Lees–Edwards; see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearedBox<const D: usize> {
    /// Sides of the box `[0, L₁) × … × [0, L_D)`, metres.
    pub size: Vector<D>,
    /// Shear rate `γ̇ = ∂v_x/∂y`, 1/s: the flow is along x, its gradient along y.
    pub rate: f64,
}

impl<const D: usize> ShearedBox<D> {
    /// How much faster along x the bodies of the layer above move: `γ̇ L_y`, m/s.
    #[must_use]
    #[inline]
    pub fn layer_speed(&self) -> f64 {
        self.rate * self.size[1]
    }

    /// The strain offset at time `t`: how far along x the layer above is shifted,
    /// `γ̇ L_y t` reduced into `[0, L_x]`, metres.
    #[must_use]
    #[inline]
    pub fn offset(&self, t: f64) -> f64 {
        (self.layer_speed() * t).rem_euclid(self.size[0])
    }

    /// The nearest image of the displacement `dp = x_b − x_a` at time `t`, and the layer `s`
    /// of `b`'s image it uses (−1, 0 or 1 for a displacement between two bodies in the box):
    /// `b`'s image moves `s · γ̇ L_y` faster along x than `b` (see [`ShearedBox::image_velocity`]).
    #[must_use]
    #[inline]
    pub fn nearest_image(&self, mut dp: Vector<D>, t: f64) -> (Vector<D>, f64) {
        let s = -(dp[1] / self.size[1]).round();
        dp[1] += s * self.size[1];
        dp[0] += s * self.offset(t);
        dp[0] -= self.size[0] * (dp[0] / self.size[0]).round();
        for d in 2..D {
            dp[d] -= self.size[d] * (dp[d] / self.size[d]).round();
        }
        (dp, s)
    }

    /// The velocity of an image `s` layers up of a body moving at `v`.
    #[must_use]
    #[inline]
    pub fn image_velocity(&self, mut v: Vector<D>, s: f64) -> Vector<D> {
        v[0] += s * self.layer_speed();
        v
    }

    /// Where a body that reached face `face` ([`crate::contact::periodic::exit_face`]) of
    /// the box at time `t`, at `pos` moving at `vel`, re-enters: one period back along the
    /// face's axis, and through a y face also shifted by the strain offset along x (then
    /// wrapped into `[0, L_x)`) with its x velocity changed by the layer speed. Returns the
    /// new position and velocity, and how many whole periods `L_x` to add to the body's x
    /// image count so that its unwrapped position, `pos + k·L + k_y γ̇ L_y t e_x` with the
    /// image counts `k`, stays where it was (see [`ShearedBox::unwrapped_shift`]).
    #[must_use]
    pub fn exit(
        &self,
        mut pos: Vector<D>,
        mut vel: Vector<D>,
        face: usize,
        t: f64,
    ) -> (Vector<D>, Vector<D>, i64) {
        let axis = face / 2;
        // Leaving through the upper face is becoming one's own image a layer down.
        let s = if face % 2 == 1 { -1.0 } else { 1.0 };
        pos[axis] += s * self.size[axis];
        if axis != 1 {
            return (pos, vel, 0);
        }
        let offset = self.offset(t);
        pos[0] += s * offset;
        vel[0] += s * self.layer_speed();
        let mut wrapped = 0;
        if pos[0] < 0.0 {
            pos[0] += self.size[0];
            wrapped = 1;
        } else if pos[0] >= self.size[0] {
            pos[0] -= self.size[0];
            wrapped = -1;
        }
        // The offset is the strain `γ̇ L_y t` less `m` whole periods.
        let m = ((self.layer_speed() * t - offset) / self.size[0]).round() as i64;
        let step = if s < 0.0 { -m } else { m } - wrapped;
        (pos, vel, step)
    }

    /// The imposed flow at height `y` (metres, in the box): `γ̇ (y − L_y/2)` along x, m/s. A
    /// body's peculiar velocity is its velocity less the flow where it is; it does not jump
    /// when the body leaves through a y face.
    #[must_use]
    #[inline]
    pub fn flow(&self, y: f64) -> f64 {
        self.rate * (y - 0.5 * self.size[1])
    }

    /// How far along x the unwrapped position of a body `layers` image counts up along y
    /// lies from its stored one at time `t`, beyond whole periods: `layers · γ̇ L_y t`.
    #[must_use]
    pub fn unwrapped_shift(&self, layers: i64, t: f64) -> f64 {
        layers as f64 * self.layer_speed() * t
    }
}

/// Most passes of images along x that come within the contact distance yet miss, visited in
/// a row before a pair is given up: only passes that graze within rounding miss inside the
/// range [`x_images_within`] computes.
const MAX_GRAZES: u32 = 4;

/// Most passes of images along x evaluated for one pair and layer. Passes are visited in the
/// order they come, from the first that can still touch; once one touches, only those that
/// come within reach before that contact follow, which the box's width (above twice the
/// reach) limits to a few. Many more arise only where the offsets to evaluate exceed `f64`'s
/// resolution of the box (windows some 10¹⁵ box crossings away, from a relative velocity
/// across the flow of the size of rounding): nothing there is resolved, and any exit of either
/// body comes first.
const MAX_PASSES: u32 = 64;

/// Time of impact of two balls in a sheared periodic box: the earliest contact of `b`'s
/// images (see the module docs) with `a`, a pure function of the stored states.
#[must_use]
pub fn toi_circle_circle_sheared<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    bx: &ShearedBox<D>,
) -> Option<f64> {
    debug_assert!(D >= 2);
    let t0 = a.time.max(b.time);
    let raw = b.at(t0) - a.at(t0);
    let dv = b.vel - a.vel;
    let sigma = ra + rb;
    let reach = sigma * (1.0 + 1e-3);
    let size = bx.size;
    let mut best: Option<f64> = None;
    for s in [-1.0, 0.0, 1.0] {
        let mut dp = raw;
        dp[1] += s * size[1];
        let Some((lo, hi)) = window(dp[1], dv[1], reach) else {
            continue;
        };
        let mut vel = dv;
        if s != 0.0 {
            dp[0] += s * bx.offset(t0);
            vel[0] += s * bx.layer_speed();
        }
        // The images along the axes after y: each of {−1, 0, 1}, where it can come close.
        let mut code = 0usize;
        'images: while code < 3usize.pow(D.saturating_sub(2) as u32) {
            let (mut lo, mut hi, mut img) = (lo, hi, dp);
            let mut c = code;
            code += 1;
            for d in 2..D {
                img[d] += ((c % 3) as f64 - 1.0) * size[d];
                c /= 3;
                match window(img[d], vel[d], reach) {
                    Some((l, h)) => {
                        lo = lo.max(l);
                        hi = hi.min(h);
                    }
                    None => continue 'images,
                }
            }
            if lo > hi * (1.0 + 1e-9) {
                continue;
            }
            let limit = best.map_or(hi, |b| hi.min(b - t0));
            let found = if s == 0.0 {
                layer_x_image(img, vel, sigma, reach, size[0], lo, hi)
            } else {
                earliest_x_image(img, vel, sigma, reach, size[0], lo, limit)
            };
            if let Some(dt) = found {
                let t = t0 + dt;
                if best.is_none_or(|bt| t.total_cmp(&bt).is_lt()) {
                    best = Some(t);
                }
            }
        }
    }
    best
}

/// The time offsets during which a coordinate `x` moving at `v` stays within `reach` of 0,
/// from now on; `None` if never.
#[inline]
fn window(x: f64, v: f64, reach: f64) -> Option<(f64, f64)> {
    if v == 0.0 {
        return (x.abs() <= reach).then_some((0.0, f64::INFINITY));
    }
    let inv = 1.0 / v;
    let (s1, s2) = ((-reach - x) * inv, (reach - x) * inv);
    let (lo, hi) = (s1.min(s2).max(0.0), s1.max(s2));
    (lo <= hi).then_some((lo, hi))
}

/// Within the layer (`s = 0`): the earliest contact offset of the images `dp + k·L_x e_x`,
/// `k ∈ {−1, 0, 1}`, moving at `vel`, among those within `reach` along x at some offset of
/// `[lo, hi]`. As in an unsheared box, both centres stay in the box until either leaves it,
/// so no other x image of the same layer touches before an exit.
#[inline]
fn layer_x_image<const D: usize>(
    dp: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    reach: f64,
    lx: f64,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    for k in [-1.0, 0.0, 1.0] {
        let mut p = dp;
        p[0] += k * lx;
        let Some((l, h)) = window(p[0], vel[0], reach) else {
            continue;
        };
        if lo.max(l) > hi.min(h) * (1.0 + 1e-9) {
            continue;
        }
        if let Some(t) = first_contact(p, vel, sigma) {
            if best.is_none_or(|b| t.total_cmp(&b).is_lt()) {
                best = Some(t);
            }
        }
    }
    best
}

/// The earliest contact offset of the images `dp + k·L_x e_x` (`k ∈ ℤ`) moving at `vel`
/// with the origin (contact distance `sigma`), among those within `reach` along x at some
/// offset of `[lo, limit]`.
fn earliest_x_image<const D: usize>(
    dp: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    reach: f64,
    lx: f64,
    lo: f64,
    limit: f64,
) -> Option<f64> {
    let (x0, w) = (dp[0], vel[0]);
    let contact = |k: f64| {
        let mut p = dp;
        p[0] = x0 + k * lx;
        first_contact(p, vel, sigma)
    };
    let mut best: Option<f64> = None;
    let keep = |t: Option<f64>, best: &mut Option<f64>| {
        if let Some(t) = t {
            if best.is_none_or(|b| t.total_cmp(&b).is_lt()) {
                *best = Some(t);
            }
        }
    };
    if w == 0.0 {
        // At most one image is within reach along x (L_x exceeds twice the reach).
        let k = -(x0 / lx).round();
        for k in [k - 1.0, k, k + 1.0] {
            if (x0 + k * lx).abs() <= reach {
                keep(contact(k), &mut best);
            }
        }
        return best;
    }
    // Images pass in the order of decreasing `k` when w > 0, increasing when w < 0; the first
    // that can still touch is the first whose stay within reach ends at or after `lo`.
    let step = if w > 0.0 { -1.0 } else { 1.0 };
    let first = if w > 0.0 {
        ((reach - x0 - w * lo) / lx).floor()
    } else {
        ((-reach - x0 - w * lo) / lx).ceil()
    };
    let (kmin, kmax) = x_images_within(dp, vel, sigma, lx)?;
    let mut k = if w > 0.0 {
        first.min(kmax.floor())
    } else {
        first.max(kmin.ceil())
    };
    let (mut grazes, mut passes) = (0, 0);
    loop {
        passes += 1;
        if passes > MAX_PASSES {
            return best;
        }
        if k < kmin.floor() - 1.0 || k > kmax.ceil() + 1.0 {
            return best;
        }
        let enter = (-w.signum() * reach - (x0 + k * lx)) / w;
        if enter > limit || best.is_some_and(|b| enter > b) {
            return best;
        }
        match contact(k) {
            Some(t) => keep(Some(t), &mut best),
            None => {
                grazes += 1;
                if grazes >= MAX_GRAZES {
                    return best;
                }
            }
        }
        k += step;
    }
}

/// The range of `k` (reals; ±∞ for every `k`) for which the line `dp + k·L_x e_x + vel·τ`
/// comes within `sigma` of the origin: its squared closest distance is a quadratic in `k`.
/// `None` when no image comes that close.
fn x_images_within<const D: usize>(
    dp: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    lx: f64,
) -> Option<(f64, f64)> {
    let v2 = vel.norm_sq();
    if v2 == 0.0 {
        return Some((f64::NEG_INFINITY, f64::INFINITY));
    }
    // Across the flow: q = Σ_{d≥1} v_d², and p⊥·v⊥.
    let (mut q, mut pv) = (0.0, 0.0);
    for d in 1..D {
        q += vel[d] * vel[d];
        pv += dp[d] * vel[d];
    }
    // |p|²|v|² − (p·v)² by Lagrange's identity, free of cancellation.
    let mut cross = 0.0;
    for i in 0..D {
        for j in i + 1..D {
            let c = dp[i] * vel[j] - dp[j] * vel[i];
            cross += c * c;
        }
    }
    let a = lx * lx * q / v2;
    let b = 2.0 * lx * (dp[0] * q - pv * vel[0]) / v2;
    let c = cross / v2 - sigma * sigma;
    if a == 0.0 {
        // Moving along x only: every image passes at the same distance.
        return (c <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let r = disc.sqrt();
    Some(((-b - r) / (2.0 * a), (-b + r) / (2.0 * a)))
}

/// Time of impact of bodies `a` and `b` in a sheared box as every finder evaluates it:
/// [`toi_circle_circle_sheared`] of their records, or none for two kinematic bodies.
/// Sheared boxes have no gravity and no growth (scenes refuse them).
#[must_use]
#[inline]
pub fn toi_bodies_sheared<const D: usize>(
    a: &Body<D>,
    b: &Body<D>,
    bx: &ShearedBox<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    debug_assert!(laws.is_none_or(|l| l.gravity.is_none() && l.growth.is_none()));
    if laws.is_some_and(|l| l.kinematic) && a.is_kinematic() && b.is_kinematic() {
        return None;
    }
    toi_circle_circle_sheared(&a.motion, a.radius, &b.motion, b.radius, bx)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m<const D: usize>(p: [f64; D], v: [f64; D], time: f64) -> Motion<D> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time,
        }
    }

    /// Every image with `|k_x| ≤ 60`, `s, k_z ∈ {−1, 0, 1}`, by `first_contact`.
    fn brute<const D: usize>(
        a: &Motion<D>,
        ra: f64,
        b: &Motion<D>,
        rb: f64,
        bx: &ShearedBox<D>,
    ) -> Option<f64> {
        let t0 = a.time.max(b.time);
        let raw = b.at(t0) - a.at(t0);
        let mut best: Option<f64> = None;
        for s in [-1.0, 0.0, 1.0] {
            // Within the layer only the x images next to the box, as in an unsheared one.
            let reach = if s == 0.0 { 1 } else { 60 };
            for kx in -reach..=reach {
                for code in 0..3usize.pow(D as u32 - 2) {
                    let mut dp = raw;
                    dp[1] += s * bx.size[1];
                    dp[0] += s * bx.offset(t0);
                    dp[0] += kx as f64 * bx.size[0];
                    let mut c = code;
                    for d in 2..D {
                        dp[d] += ((c % 3) as f64 - 1.0) * bx.size[d];
                        c /= 3;
                    }
                    let vel = bx.image_velocity(b.vel - a.vel, s);
                    if let Some(dt) = first_contact(dp, vel, ra + rb) {
                        best = Some(best.map_or(t0 + dt, |bt: f64| bt.min(t0 + dt)));
                    }
                }
            }
        }
        best
    }

    #[test]
    fn layers_meet_as_they_slide() {
        // Two discs at rest, one near the bottom face, one near the top face 3 to its right.
        // The layer below slides along x at −γ̇L_y = −2, so b's image one layer down, at
        // (8 − δ, −0.3), comes towards a; vertical gap 0.8, so they touch 0.6 apart along x.
        let bx = ShearedBox {
            size: Vector([10.0, 10.0]),
            rate: 0.2,
        };
        let a = m([5.0, 0.5], [0.0, 0.0], 0.0);
        let b = m([8.0, 9.7], [0.0, 0.0], 0.0);
        let t = toi_circle_circle_sheared(&a, 0.5, &b, 0.5, &bx).unwrap();
        assert!((t - 1.2).abs() < 1e-12, "{t}");
        assert_eq!(brute(&a, 0.5, &b, 0.5, &bx), Some(t));
        // At t0 = 2 the offset is 4: that image, at x = 4, is past a and receding; the next
        // one, at 14, touches after 4.2 s.
        let a = m([5.0, 0.5], [0.0, 0.0], 2.0);
        let b = m([8.0, 9.7], [0.0, 0.0], 2.0);
        let t = toi_circle_circle_sheared(&a, 0.5, &b, 0.5, &bx).unwrap();
        assert!((t - 6.2).abs() < 1e-12, "{t}");
        assert_eq!(brute(&a, 0.5, &b, 0.5, &bx), Some(t));
        // Too far apart across the face: never.
        let b = m([8.0, 9.0], [0.0, 0.0], 2.0);
        assert_eq!(toi_circle_circle_sheared(&a, 0.5, &b, 0.4, &bx), None);
    }

    #[test]
    fn agrees_with_every_image_tried() {
        let mut hits = 0;
        for i in 0..3000u64 {
            let f = |k: u64| ((i * 2_654_435_761 + k * 40_503) % 1000) as f64 / 1000.0;
            let bx = ShearedBox {
                size: Vector([5.0 + 3.0 * f(20), 6.0, 7.0]),
                rate: 2.0 * f(21) - 1.0,
            };
            // Half the cases with integer coordinates and velocities along one axis only.
            let round = i % 2 == 0;
            let c = |x: f64| if round { (x * 4.0).round() / 4.0 } else { x };
            let a = m(
                [c(f(1) * 4.9), c(f(2) * 5.9), c(f(3) * 6.9)],
                [
                    c(f(4) - 0.5),
                    if i % 3 == 0 { 0.0 } else { c(f(5) - 0.5) },
                    c(f(6) - 0.5),
                ],
                c(f(7) * 3.0),
            );
            let b = m(
                [c(f(8) * 4.9), c(f(9) * 5.9), c(f(10) * 6.9)],
                [
                    c(f(11) * 4.0 - 2.0),
                    if i % 3 == 0 { 0.0 } else { c(f(12) - 0.5) },
                    c(f(13) * 3.0 - 1.5),
                ],
                c(f(14) * 3.0),
            );
            let (ra, rb) = (0.3 + 0.6 * f(15), 0.3 + 0.6 * f(16));
            let fast = toi_circle_circle_sheared(&a, ra, &b, rb, &bx);
            let slow = brute(&a, ra, &b, rb, &bx);
            assert_eq!(
                fast.map(f64::to_bits),
                slow.map(f64::to_bits),
                "3D case {i}"
            );
            let a2 = m([a.pos[0], a.pos[1]], [a.vel[0], a.vel[1]], a.time);
            let b2 = m([b.pos[0], b.pos[1]], [b.vel[0], b.vel[1]], b.time);
            let bx2 = ShearedBox {
                size: Vector([bx.size[0], bx.size[1]]),
                rate: bx.rate,
            };
            let fast2 = toi_circle_circle_sheared(&a2, ra, &b2, rb, &bx2);
            let slow2 = brute(&a2, ra, &b2, rb, &bx2);
            assert_eq!(
                fast2.map(f64::to_bits),
                slow2.map(f64::to_bits),
                "2D case {i}"
            );
            hits += usize::from(fast.is_some()) + usize::from(fast2.is_some());
        }
        assert!(hits > 1500, "{hits}");
    }

    #[test]
    fn nearest_image_and_exit_agree() {
        let bx = ShearedBox {
            size: Vector([4.0, 2.0]),
            rate: 0.75,
        };
        // At t = 1: δ = 1.5. A body leaving through the top at x = 3.5 re-enters at the bottom
        // at x = 3.5 − 1.5 = 2, 1.5 slower along x.
        let (p, v, step) = bx.exit(Vector([3.5, 2.0]), Vector([0.25, 1.0]), 3, 1.0);
        assert_eq!((p.0, v.0, step), ([2.0, 0.0], [-1.25, 1.0], 0));
        // Through the bottom at x = 3: up and 1.5 along: 4.5 wraps to 0.5.
        let (p, v, step) = bx.exit(Vector([3.0, 0.0]), Vector([0.0, -1.0]), 2, 1.0);
        assert_eq!((p.0, v.0, step), ([0.5, 2.0], [1.5, -1.0], 1));
        // The unwrapped x stays put through exits, whatever the strain: at t = 7 the strain
        // is 10.5 (offset 2.5, two periods).
        for (face, pos, vel) in [
            (3, [3.5, 2.0], [0.25, 1.0]),
            (2, [0.5, 0.0], [0.0, -1.0]),
            (2, [3.0, 0.0], [0.0, -1.0]),
        ] {
            let t = 7.0;
            let (p, _, step) = bx.exit(Vector(pos), Vector(vel), face, t);
            let layers = if face == 3 { 1 } else { -1 };
            let unwrapped = p[0] + step as f64 * 4.0 + bx.unwrapped_shift(layers, t);
            assert!(
                (unwrapped - pos[0]).abs() < 1e-12,
                "{face} {pos:?}: {unwrapped}"
            );
        }
        // The nearest image of a displacement across the top face at t = 1.
        let (dp, s) = bx.nearest_image(Vector([0.5, 1.9]), 1.0);
        assert_eq!(s, -1.0);
        assert!((dp[0] - (0.5 - 1.5)).abs() < 1e-15 && (dp[1] + 0.1).abs() < 1e-15);
        assert_eq!(bx.image_velocity(Vector([0.0, 0.0]), s).0, [-1.5, 0.0]);
    }
}

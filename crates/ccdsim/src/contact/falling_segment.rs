//! A ball on a parabola against a segment wall in 2D, its radius fixed or growing linearly in
//! time: the set-up that gravity ([`crate::contact::gravity`]) and gravity with growing radii
//! ([`crate::contact::falling_growth`]) share. In 3D a segment is a rod
//! ([`crate::contact::rod`]).
//!
//! The centre's signed distance from the segment's line is a quadratic,
//! `h(t) = h₀ + h_v·t + h_a·t²`, against the half-width `ρ(t) = ρ + ρ̇·t` of the slab around
//! the line (`ρ̇ = 0` for fixed radii). The ball meets the segment's interior where it comes
//! into contact with the line while its foot lies on the segment, and an end point at the
//! first root of the quartic `|w + v·t + ½·g·t²|² = ρ(t)²`
//! ([`first_contact_accelerating_growing`]). A parabola may enter the slab beyond an end,
//! stay in it and carry its foot onto the segment, so every way into contact with the line is
//! a candidate, kept if its foot lies on the segment:
//! - touching the line now while approaching it;
//! - each entry into the slab: falling through `+ρ(t)`, rising through `−ρ(t)` (in the
//!   cancellation-free forms of [`super::quadratic`]);
//! - in the slab and not approaching, the time the gap turns to shrink, if the ball is still
//!   in the slab then.
//!
//! With `ρ̇ = 0` every value computed is the fixed-radius one: the terms the growth adds are
//! exact zeros.

use crate::contact::accelerated_contact::first_contact_accelerating_growing;
use crate::contact::quadratic::crossing;
use crate::contact::rod::earliest_at;
use crate::geom::Vector;
use crate::motion::Motion;

/// Time of impact (absolute, seconds) of a ball (motion `m`; radius `radius` metres at the
/// ball's reference time, growing at `speed` ≥ 0 m/s) falling under `g` (m/s², not zero) with
/// the 2D segment `[a, b]` (metres), its end points counted only where `ends` says; `None`
/// when it never meets it. See the module docs.
#[must_use]
#[inline(always)]
pub(crate) fn toi_circle_segment_on_parabola<const D: usize>(
    m: &Motion<D>,
    radius: f64,
    speed: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    ends: [bool; 2],
) -> Option<f64> {
    debug_assert_eq!(D, 2, "in 3D a segment is a rod");
    let u = b - a;
    let l2 = u.norm_sq();
    let w = m.pos - a;
    // The signed distance from the line, along the unit normal n: h(t) = h0 + hv·t + ha·t².
    let len = l2.sqrt();
    let mut n = Vector::<D>::ZERO;
    n[0] = -u[1] / len;
    n[1] = u[0] / len;
    let (h0, hv, ha) = (w.dot(n), m.vel.dot(n), 0.5 * g.dot(n));
    let foot = |dt: f64| {
        let s = (w + m.vel * dt + *g * (0.5 * dt * dt)).dot(u) / l2;
        (0.0..=1.0).contains(&s)
    };
    let inside = h0.abs() <= radius;
    // By signs: the product of a tiny speed and a short distance may underflow to zero.
    let approaching = (h0 < 0.0 && hv > -speed) || (h0 > 0.0 && hv < speed);
    let mut candidates = [
        (inside && approaching).then_some(0.0),
        crossing(h0 - radius, hv - speed, ha, 0.0, true),
        crossing(h0 + radius, hv + speed, ha, 0.0, false),
        None,
    ];
    // The gap on the ball's side shrinks again once s·h turns back faster than the slab grows.
    let side = if h0 >= 0.0 { 1.0 } else { -1.0 };
    let turns_inward = side * ha < 0.0;
    if inside && !approaching && turns_inward {
        let turn = (side * hv - speed) / (-2.0 * side * ha);
        let h_turn = h0 + hv * turn + ha * turn * turn;
        // At rest in contact and pressed inward, the turn is now.
        if turn >= 0.0 && h_turn.abs() <= radius + speed * turn {
            candidates[3] = Some(turn);
        }
    }
    let interior = candidates
        .into_iter()
        .flatten()
        .filter(|&dt| dt >= 0.0 && dt.is_finite() && foot(dt))
        .reduce(f64::min);
    let end_a = ends[0]
        .then(|| first_contact_accelerating_growing(w, m.vel, *g, radius, speed))
        .flatten();
    let end_b = ends[1]
        .then(|| first_contact_accelerating_growing(m.pos - b, m.vel, *g, radius, speed))
        .flatten();
    earliest_at(m.time, [interior, end_a, end_b])
}

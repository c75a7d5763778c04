//! When a body moving in a straight line enters or leaves a sensor seen through the images of
//! a periodic box, while its radius may grow: the pure functions behind
//! [`crate::sim::SensorTracker`] in periodic and growing worlds.
//!
//! # Which images matter
//!
//! In a periodic box of sides `L` a body overlaps a sensor (centre `c`, radius `R`) while its
//! centre is within `R + r` of some image `c + k·L`, `k` a vector of integers. Between two box
//! exits the body's stored position stays in the box, and the sensor's centre is in it too
//! (scenes require it), so the offset `x − c` stays in `(−L, L)` on every axis and only the
//! `3^D` images `k ∈ {−1, 0, 1}^D` can come within `L` of it; a box exit moves the body by a
//! period and its crossings are computed anew. Scenes also require `2·(R + r) < L` on every
//! axis, so that a body overlaps at most one image at a time and the sensor's images do not
//! overlap one another; as radii grow that may stop holding (as the pairs' condition may, see
//! [`crate::contact::periodic`]), and a body may then overlap two images at once: it is inside while it
//! overlaps any, so it leaves when it leaves their union, which [`leave_time`] follows from
//! image to image. Every time is still a root of one image's equation, found by the same
//! solvers as collisions; nothing is skipped while `R + r < L`.
//!
//! # Growing radii
//!
//! With `r(t) = r·(1 + Γ·(t − t₀))` the contact distance `σ(t) = R + r(t)` is linear in time,
//! `σ + σ̇·t` with `σ̇ = Γ·r` (the sensor does not grow), so entering is
//! [`first_contact_growing`] and leaving [`first_exit_growing`]: quadratics, as for fixed
//! radii. Without growth (`σ̇ = 0`) they are [`first_contact`] and [`first_exit`], exactly the
//! functions used outside periodic boxes.

use crate::contact::accelerated_contact::first_exit;
use crate::contact::growth::{first_contact_growing, first_exit_growing};
use crate::contact::narrow::first_contact;
use crate::contact::periodic::min_image;
use crate::geom::Vector;

/// The offset `raw` (body centre less sensor centre) of the image nearest to the body: `raw`
/// itself outside a periodic box, else its minimum image (see [`min_image`]), which is one of
/// the `3^D` images [`enter_time`] and [`leave_time`] try, bit for bit.
#[must_use]
#[inline]
pub fn nearest_image<const D: usize>(raw: Vector<D>, period: Option<&Vector<D>>) -> Vector<D> {
    match period {
        Some(size) => min_image(raw, size),
        None => raw,
    }
}

/// True when a body at offset `dp` from a sensor's centre, moving at `vel`, overlaps it now
/// (contact distance `sigma`, growing at `sigma_dot`): strictly inside, or on the sphere and
/// going in.
#[must_use]
#[inline]
pub fn overlaps<const D: usize>(dp: Vector<D>, vel: Vector<D>, sigma: f64, sigma_dot: f64) -> bool {
    let c = dp.norm_sq() - sigma * sigma;
    c < 0.0 || (c == 0.0 && dp.dot(vel) - sigma * sigma_dot < 0.0)
}

/// Time offset, seconds, after which a body outside a sensor first overlaps one of its images:
/// the earliest first contact over the images (one without a box), each by [`first_contact`]
/// or, when the contact distance grows (`sigma_dot > 0`), [`first_contact_growing`]. `raw` is
/// the body's centre less the sensor's, metres, `vel` its velocity, m/s, `sigma` the contact
/// distance `R + r` now, metres. `None` when it never enters.
#[must_use]
pub fn enter_time<const D: usize>(
    raw: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
    period: Option<&Vector<D>>,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    for_each_image(raw, period, |dp| {
        if let Some(t) = contact(dp, vel, sigma, sigma_dot) {
            if best.is_none_or(|b| t < b) {
                best = Some(t);
            }
        }
    });
    best
}

/// Time offset, seconds, after which a body inside a sensor (overlapping some image) first
/// overlaps none: it leaves the nearest image at the root of [`first_exit`] (or
/// [`first_exit_growing`]); if it then overlaps another image it leaves that one in turn, and
/// so on. Arguments as for [`enter_time`]. `None` when it never leaves.
///
/// The image just left is not tried again at the instant it is left, where rounding may still
/// find the body on its sphere: without growth and with `2·(R + r) < L`, no other image is
/// within reach there either, so the answer is the nearest image's exit, bit for bit the one a
/// sensor outside a box would give.
#[must_use]
pub fn leave_time<const D: usize>(
    raw: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
    period: Option<&Vector<D>>,
) -> Option<f64> {
    let mut last = nearest_image(raw, period);
    let mut s = exit(last, vel, sigma, sigma_dot)?;
    if period.is_none() {
        return Some(s);
    }
    // Each turn hands the body on to an image it overlaps when it leaves the one before, which
    // it leaves later; `3^D` images can take turns at most that many times between box exits
    // while `R + r < L` (images do not come back without growth, and with it an image
    // entered for good ends the search). The bound only guards against rounding.
    for _ in 0..2 * 3usize.pow(D as u32) {
        let (at, reach) = (vel * s, sigma + sigma_dot * s);
        let mut next: Option<(f64, Vector<D>)> = None;
        let mut forever = false;
        for_each_image(raw, period, |dp| {
            let x = dp + at;
            if forever || dp == last || !overlaps(x, vel, reach, sigma_dot) {
                return;
            }
            match exit(x, vel, reach, sigma_dot) {
                None => forever = true,
                Some(dt) => {
                    let t = s + dt;
                    if next.is_none_or(|(b, _)| t > b) {
                        next = Some((t, dp));
                    }
                }
            }
        });
        if forever {
            return None;
        }
        match next {
            None => return Some(s),
            Some((t, dp)) => {
                s = t.max(s);
                last = dp;
            }
        }
    }
    Some(s)
}

/// Calls `f` with every image of `raw` that can matter: `raw + k·L`, `k ∈ {−1, 0, 1}^D`, in a
/// periodic box of sides `L` (lowest `k` first, axis 0 fastest), `raw` alone without one.
fn for_each_image<const D: usize>(
    raw: Vector<D>,
    period: Option<&Vector<D>>,
    mut f: impl FnMut(Vector<D>),
) {
    let Some(size) = period else {
        return f(raw);
    };
    for code in 0..3usize.pow(D as u32) {
        let mut dp = raw;
        let mut rest = code;
        for d in 0..D {
            match rest % 3 {
                0 => dp[d] += -size[d],
                2 => dp[d] += size[d],
                _ => {}
            }
            rest /= 3;
        }
        f(dp);
    }
}

fn contact<const D: usize>(
    dp: Vector<D>,
    vel: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> Option<f64> {
    if sigma_dot == 0.0 {
        first_contact(dp, vel, sigma)
    } else {
        first_contact_growing(dp, vel, sigma, sigma_dot)
    }
    .filter(|t| t.is_finite())
}

fn exit<const D: usize>(dp: Vector<D>, vel: Vector<D>, sigma: f64, sigma_dot: f64) -> Option<f64> {
    if sigma_dot == 0.0 {
        first_exit(dp, vel, sigma)
    } else {
        first_exit_growing(dp, vel, sigma, sigma_dot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOX: Vector<2> = Vector([10.0, 8.0]);

    #[test]
    fn a_sensor_straddling_a_face_is_entered_and_left_through_its_image() {
        // Sensor at x = 0.3 (radius 1), body of radius 0.2 at x = 8 moving at +1: it meets
        // the image at x = 10.3 when x = 9.1 (t = 1.1), through the image's own equation.
        let raw = Vector([8.0 - 0.3, 0.0]);
        let v = Vector([1.0, 0.0]);
        let sigma = 1.2;
        let t = enter_time(raw, v, sigma, 0.0, Some(&BOX));
        assert_eq!(t, first_contact(raw + Vector([-10.0, 0.0]), v, sigma));
        assert!((t.unwrap() - 1.1).abs() < 1e-14, "{t:?}");
        // Without the box only the sensor itself counts: it is behind the body.
        assert_eq!(enter_time(raw, v, sigma, 0.0, None), None);
        // From x = 9.5 it would leave the image at x = 11.5 (t = 2), after the box exit at
        // x = 10, which the simulation applies first; from x = 0 after it (inside the sensor
        // itself) it leaves at x = 1.5.
        let inside = Vector([9.5 - 0.3, 0.0]);
        let t = leave_time(inside, v, sigma, 0.0, Some(&BOX)).unwrap();
        assert!((t - 2.0).abs() < 1e-14, "{t}");
        let wrapped = Vector([0.0 - 0.3, 0.0]);
        let t = leave_time(wrapped, v, sigma, 0.0, Some(&BOX)).unwrap();
        assert!((t - 1.5).abs() < 1e-14, "{t}");
        // Moving the other way from x = 9.5, it leaves the image at x = 9.1.
        let t = leave_time(inside, -v, sigma, 0.0, Some(&BOX)).unwrap();
        assert!((t - 0.4).abs() < 1e-14, "{t}");
    }

    #[test]
    fn the_nearest_image_is_one_of_the_images_tried() {
        for raw in [
            [-9.7, 7.9],
            [9.7, -7.9],
            [-0.0, 0.0],
            [5.0, -4.0],
            [-5.0, 4.0],
            [4.9, 3.9],
        ] {
            let raw = Vector(raw);
            let near = nearest_image(raw, Some(&BOX));
            let mut found = false;
            for_each_image(raw, Some(&BOX), |dp| found |= dp == near);
            assert!(found, "{raw:?}");
        }
    }

    #[test]
    fn a_body_overlapping_two_images_leaves_when_it_leaves_both() {
        // Along x in a box of side 4: the sensor (centre 0) and its image at 4. A point moving
        // at +1 from x = 1 with σ = 1.5 is in the sensor until x = 1.5 and in the image from
        // x = 2.5: it leaves at 0.5.
        let size = Vector([4.0, 100.0]);
        let v = Vector([1.0, 0.0]);
        let from = Vector([1.0, 0.0]);
        let t = leave_time(from, v, 1.5, 0.0, Some(&size)).unwrap();
        assert!((t - 0.5).abs() < 1e-15, "{t}");
        // With σ = 2.5 the two overlap from x = 1.5 to 2.5: it stays inside, and leaves the
        // image at x = 6.5.
        let t = leave_time(from, v, 2.5, 0.0, Some(&size)).unwrap();
        assert!((t - 5.5).abs() < 1e-14, "{t}");
        // Growing, σ = 1.5 + 0.25·t: out of the sensor when 1 + t = σ, at 2/3, before the
        // image (3 − t = σ at 1.2) takes it.
        let t = leave_time(from, v, 1.5, 0.25, Some(&size)).unwrap();
        assert!((t - 2.0 / 3.0).abs() < 1e-15, "{t}");
        // σ = 1.5 + 0.75·t: the image takes it at 6/7, before it would leave the sensor (at
        // 2); it leaves the image when t − 3 = σ, at 18 (in a simulation the box exit at
        // t = 3 comes first).
        let t = leave_time(from, v, 1.5, 0.75, Some(&size)).unwrap();
        assert!((t - 18.0).abs() < 1e-13, "{t}");
        // σ̇ = 2 outgrows the point's speed: it never leaves.
        assert_eq!(leave_time(from, v, 1.5, 2.0, Some(&size)), None);
    }

    /// The gap to the nearest of the images `k ∈ {−2, …, 2}^D` (wider than the `3^D` the
    /// functions try) at offset `t` on the line, against a contact distance `σ + σ̇·t`.
    fn gap<const D: usize>(
        raw: Vector<D>,
        v: Vector<D>,
        (s, sd): (f64, f64),
        size: &Vector<D>,
        t: f64,
    ) -> f64 {
        let mut best = f64::INFINITY;
        for code in 0..5usize.pow(D as u32) {
            let mut dp = raw + v * t;
            let mut rest = code;
            for d in 0..D {
                dp[d] += ((rest % 5) as f64 - 2.0) * size[d];
                rest /= 5;
            }
            best = best.min(dp.norm());
        }
        best - (s + sd * t)
    }

    /// Checks [`enter_time`] or [`leave_time`] (whichever applies) for a body at `pos` in the
    /// box and a sensor centred at `c`, against dense sampling of the brute-force gap, up to
    /// the time the body leaves the box (where a simulation asks again) or the contact
    /// distance reaches the smallest side (beyond which more images would matter).
    fn check<const D: usize>(
        pos: Vector<D>,
        c: Vector<D>,
        v: Vector<D>,
        (s, sd): (f64, f64),
        size: &Vector<D>,
    ) -> Result<(), String> {
        let raw = pos - c;
        let start = gap(raw, v, (s, sd), size, 0.0);
        if start.abs() < 1e-6 {
            return Ok(()); // on the sphere: either answer is right
        }
        let going_in = start > 0.0;
        let answer = if going_in {
            enter_time(raw, v, s, sd, Some(size))
        } else {
            leave_time(raw, v, s, sd, Some(size))
        };
        let mut horizon = 50.0f64;
        let mut side = f64::INFINITY;
        for d in 0..D {
            side = side.min(size[d]);
            if v[d] > 0.0 {
                horizon = horizon.min((size[d] - pos[d]) / v[d]);
            } else if v[d] < 0.0 {
                horizon = horizon.min(pos[d] / -v[d]);
            }
        }
        if sd > 0.0 {
            horizon = horizon.min((0.99 * side - s) / sd);
        }
        let tol = |t: f64| 1e-9 * (1.0 + t) * (s + sd * t + size.norm());
        // `g` turns negative when the body crosses.
        let sign = if going_in { 1.0 } else { -1.0 };
        let g = |t: f64| sign * gap(raw, v, (s, sd), size, t);
        let end = answer.map_or(horizon, |t| t.min(horizon));
        for k in 0..4000 {
            let t = end * f64::from(k) / 4000.0;
            if g(t) < -tol(t) {
                return Err(format!(
                    "{} at {t}, before the answer {answer:?}",
                    if going_in { "in" } else { "out" }
                ));
            }
        }
        if let Some(t) = answer.filter(|&t| t <= horizon) {
            if g(t).abs() > tol(t) {
                return Err(format!("gap {} at the answer {t}", g(t)));
            }
        }
        Ok(())
    }

    proptest::proptest! {
        #[test]
        fn enter_and_leave_times_match_brute_force_images_2d(
            c in proptest::array::uniform2(0.0..1.0f64),
            p in proptest::array::uniform2(0.0..1.0f64),
            v in proptest::array::uniform2(-3.0..3.0f64),
            size in proptest::array::uniform2(2.0..6.0f64),
            s_frac in 0.05..0.49f64,
            sd in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0..0.5f64],
        ) {
            let size = Vector(size);
            let s = s_frac * size[0].min(size[1]);
            let c = Vector([c[0] * size[0], c[1] * size[1]]);
            let p = Vector([p[0] * size[0], p[1] * size[1]]);
            let result = check(p, c, Vector(v), (s, sd), &size);
            proptest::prop_assert!(result.is_ok(), "{result:?}");
        }

        #[test]
        fn enter_and_leave_times_match_brute_force_images_3d(
            c in proptest::array::uniform3(0.0..1.0f64),
            p in proptest::array::uniform3(0.0..1.0f64),
            v in proptest::array::uniform3(-3.0..3.0f64),
            s in 0.1..1.45f64,
            sd in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0..0.5f64],
        ) {
            let size = Vector([3.0, 4.0, 5.0]);
            let scale = |u: [f64; 3]| Vector([u[0] * 3.0, u[1] * 4.0, u[2] * 5.0]);
            let result = check(scale(p), scale(c), Vector(v), (s, sd), &size);
            proptest::prop_assert!(result.is_ok(), "{result:?}");
        }
    }
}

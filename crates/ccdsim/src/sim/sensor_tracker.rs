//! The sensors of a running simulation (see [`crate::sensor`] for what a sensor reports and
//! how its crossings are found): which bodies overlap which sensor, and each body's next
//! sensor event in a priority queue.

use crate::contact::accelerated_contact::{
    first_contact_accelerating, first_contact_accelerating_growing, first_exit_accelerating,
    first_exit_accelerating_growing,
};
use crate::contact::sensor_crossing::{enter_time, leave_time, nearest_image};
use crate::geom::Vector;
use crate::motion::Motion;
use crate::sensor::{Sensor, SensorChange, SensorEvent};
use crate::world::World;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// One body's next sensor event, queued: ordered by time, then body, then sensor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Pending {
    /// The time's bits (times are non-negative or ordered as such, see `ordered`).
    time: u64,
    body: u32,
    sensor: u32,
    /// The body's epoch when it was queued: stale once the body is recomputed.
    epoch: u32,
}

/// The sensors of a running simulation: which bodies are inside which, and each body's next
/// sensor event.
#[derive(Clone, Debug)]
pub struct SensorTracker<const D: usize> {
    sensors: Vec<Sensor<D>>,
    /// `inside[i · s + k]`: body `i` overlaps sensor `k` (`s` sensors).
    inside: Vec<bool>,
    /// Per body, how many times its next event was recomputed.
    epoch: Vec<u32>,
    queue: BinaryHeap<Reverse<Pending>>,
    /// Events reported and not yet taken.
    out: Vec<SensorEvent>,
    /// Enter and leave counts per sensor since the start.
    counts: Vec<[u64; 2]>,
    /// The last flip [`SensorTracker::advance_to`] made: body, sensor, time (ordered bits).
    grazed: Option<(usize, usize, u64)>,
}

/// `t`'s bits, ordered like the values for the finite non-negative and negative floats alike.
fn ordered(t: f64) -> u64 {
    let b = t.to_bits();
    if b >> 63 == 0 {
        b | 1 << 63
    } else {
        !b
    }
}

fn unordered(b: u64) -> f64 {
    f64::from_bits(if b >> 63 == 1 { b & !(1 << 63) } else { !b })
}

impl<const D: usize> SensorTracker<D> {
    /// Tracks `sensors` in `world`: bodies overlapping one now enter it now (reported by the
    /// first [`SensorTracker::advance_to`]).
    #[must_use]
    pub fn new(world: &World<D>, sensors: Vec<Sensor<D>>) -> Self {
        let (n, s) = (world.len(), sensors.len());
        let mut tracker = SensorTracker {
            inside: vec![false; n * s],
            epoch: vec![0; n],
            queue: BinaryHeap::with_capacity(n),
            out: Vec::new(),
            counts: vec![[0; 2]; s],
            grazed: None,
            sensors,
        };
        for i in 0..n {
            tracker.body_changed(world, i);
        }
        tracker
    }

    /// The sensors.
    #[must_use]
    pub fn sensors(&self) -> &[Sensor<D>] {
        &self.sensors
    }

    /// True when body `i` overlaps sensor `k` as of the last event reported.
    #[must_use]
    pub fn is_inside(&self, i: usize, k: usize) -> bool {
        self.inside[i * self.sensors.len() + k]
    }

    /// Bodies overlapping sensor `k` as of the last event reported, by index.
    #[must_use]
    pub fn bodies_in(&self, k: usize) -> Vec<usize> {
        (0..self.epoch.len())
            .filter(|&i| self.is_inside(i, k))
            .collect()
    }

    /// Enters and leaves of sensor `k` reported so far.
    #[must_use]
    pub fn counts(&self, k: usize) -> (u64, u64) {
        let [e, l] = self.counts[k];
        (e, l)
    }

    /// Takes the events reported since the last call, in time order.
    pub fn take_events(&mut self) -> Vec<SensorEvent> {
        std::mem::take(&mut self.out)
    }

    /// Body `i`'s stored motion was replaced (a collision, an edit), or what it meets changed
    /// (its radius, when growth stops; the finder rebuilt): its next sensor event is computed
    /// anew from its origin (its reference time, or the current time if that is
    /// later), where a body found strictly inside a sensor it is not known to overlap enters it
    /// at once, and one found strictly outside a sensor it is known to overlap leaves it at
    /// once. A removed body (a vacant slot) leaves every sensor at once. (On the sphere, the
    /// contact and exit functions decide, as they do at every crossing: the two rules never
    /// disagree, so events at one instant cannot repeat.)
    pub fn body_changed(&mut self, world: &World<D>, i: usize) {
        let mut m = world.motion(i);
        if world.is_vacant(i) {
            return self.body_removed(i, m.time);
        }
        let t = Self::origin(world, i);
        if t > m.time {
            // What the tracker holds is true now: the body may have entered or left a sensor
            // since its reference time, and must not be found where it was then.
            m = Motion {
                pos: world.position_at(i, t),
                vel: world.velocity_at(i, t),
                time: t,
            };
        }
        // The radius then (it grows in a growing world); in a periodic box the nearest image
        // decides, the only one a body can overlap while `2·(R + r) < L`.
        let r = world.radius_at(i, m.time);
        let period = world.periodic();
        let s = self.sensors.len();
        let mut best: Option<(f64, usize)> = None;
        for (k, sensor) in self.sensors.iter().enumerate() {
            let dp = nearest_image(m.pos - sensor.center, period.as_ref());
            let sigma = sensor.radius + r;
            let c = dp.norm_sq() - sigma * sigma;
            let inside = self.inside[i * s + k];
            let t = if (c < 0.0 && !inside) || (c > 0.0 && inside) {
                Some(m.time)
            } else {
                self.crossing(world, i, k, m.pos, m.vel, m.time)
            };
            if let Some(t) = t {
                if best.is_none_or(|(b, _)| t < b) {
                    best = Some((t, k));
                }
            }
        }
        self.queue_next(i, best);
    }

    /// The time body `i`, at `pos` with velocity `vel` at time `t0`, next enters (if it is
    /// outside) or leaves (if inside) sensor `k`.
    fn crossing(
        &self,
        world: &World<D>,
        i: usize,
        k: usize,
        pos: Vector<D>,
        vel: Vector<D>,
        t0: f64,
    ) -> Option<f64> {
        let sensor = &self.sensors[k];
        let inside = self.inside[i * self.sensors.len() + k];
        if world.has_resting() {
            if let Some((pivot, _)) = world.pivot(i) {
                return pivot_crossing(world, i, pivot, sensor, inside, t0);
            }
        }
        let raw = pos - sensor.center;
        let period = world.periodic();
        let growth = world.growth();
        let dt = if period.is_none() && growth.is_none() {
            let sigma = sensor.radius + world.radius(i);
            let acc = world.gravity_of(i).unwrap_or(Vector::ZERO);
            if inside {
                first_exit_accelerating(raw, vel, acc, sigma)
            } else {
                first_contact_accelerating(raw, vel, acc, sigma)
            }
        } else if let (None, Some(law), Some(acc)) = (period, growth, world.gravity_of(i)) {
            // Gravity and growth: a parabola against a growing sphere, the quartic's roots.
            let sigma = sensor.radius + world.radius_at(i, t0);
            let sigma_dot = law.speed(world.radius(i));
            if inside {
                first_exit_accelerating_growing(raw, vel, acc, sigma, sigma_dot)
            } else {
                first_contact_accelerating_growing(raw, vel, acc, sigma, sigma_dot)
            }
        } else {
            // Periodic boxes have no gravity (scenes refuse it), nor do kinematic bodies
            // fall: straight lines, seen through the box's images, with a contact distance
            // that may grow.
            debug_assert!(world.gravity_of(i).is_none());
            let sigma = sensor.radius + world.radius_at(i, t0);
            let sigma_dot = growth.map_or(0.0, |law| law.speed(world.radius(i)));
            if inside {
                leave_time(raw, vel, sigma, sigma_dot, period.as_ref())
            } else {
                enter_time(raw, vel, sigma, sigma_dot, period.as_ref())
            }
        }?;
        Some(t0 + dt).filter(|t| t.is_finite())
    }

    /// The instant from which [`SensorTracker::body_changed`] looks at body `i`: its reference
    /// time, or the current time when that is later (the tracker has been advanced to it, so
    /// what it holds is true then).
    fn origin(world: &World<D>, i: usize) -> f64 {
        world.time(i).max(world.now())
    }

    /// Body `i` left the periodic box through a face and came back through the opposite one
    /// (its stored position moved by a period, its path the same): its next event is computed
    /// anew from its new stored state, on what it overlaps now. Unlike
    /// [`SensorTracker::body_changed`], nothing is entered or left at once: the body is where
    /// it was, so a sensor straddling the face it crossed is neither left nor entered there
    /// (the crossing functions decide a body on a sensor's sphere, as at every crossing).
    /// Call [`SensorTracker::advance_to`] the exit's time first.
    pub fn body_wrapped(&mut self, world: &World<D>, i: usize) {
        let m = world.motion(i);
        let next = self.next_crossing(world, i, m.pos, m.vel, m.time);
        self.queue_next(i, next);
    }

    /// Body `i`'s first crossing of any sensor, at `pos` with velocity `vel` at time `t0`, on
    /// the inside flags as they are: `(time, sensor)`, the lower sensor index on a tie.
    fn next_crossing(
        &self,
        world: &World<D>,
        i: usize,
        pos: Vector<D>,
        vel: Vector<D>,
        t0: f64,
    ) -> Option<(f64, usize)> {
        self.next_crossing_but(world, i, pos, vel, t0, None)
    }

    /// [`SensorTracker::next_crossing`], passing over sensor `grazed` if its crossing comes
    /// at `t0` itself: see [`SensorTracker::advance_to`].
    fn next_crossing_but(
        &self,
        world: &World<D>,
        i: usize,
        pos: Vector<D>,
        vel: Vector<D>,
        t0: f64,
        grazed: Option<usize>,
    ) -> Option<(f64, usize)> {
        let mut best: Option<(f64, usize)> = None;
        for k in 0..self.sensors.len() {
            if let Some(t) = self
                .crossing(world, i, k, pos, vel, t0)
                .filter(|&t| !(grazed == Some(k) && t == t0))
            {
                if best.is_none_or(|(b, _)| t < b) {
                    best = Some((t, k));
                }
            }
        }
        best
    }

    /// Makes room for `n` body slots (bodies added to a running simulation); new slots are
    /// inside no sensor and have no event until [`SensorTracker::body_changed`].
    pub fn resize(&mut self, n: usize) {
        self.inside.resize(n * self.sensors.len(), false);
        self.epoch.resize(n, 0);
    }

    /// Body `i` was removed (its slot is vacant): it leaves every sensor it overlaps now, at
    /// its reference time, and has no more events.
    fn body_removed(&mut self, i: usize, t: f64) {
        let s = self.sensors.len();
        for k in 0..s {
            if self.inside[i * s + k] {
                self.inside[i * s + k] = false;
                self.counts[k][1] += 1;
                self.out.push(SensorEvent {
                    time: t,
                    body: i,
                    sensor: k,
                    change: SensorChange::Leave,
                });
            }
        }
        self.queue_next(i, None);
    }

    /// Queues body `i`'s next event `(time, sensor)`, dropping the one queued before.
    fn queue_next(&mut self, i: usize, next: Option<(f64, usize)>) {
        self.epoch[i] = self.epoch[i].wrapping_add(1);
        if let Some((t, k)) = next {
            self.queue.push(Reverse(Pending {
                time: ordered(t),
                body: i as u32,
                sensor: k as u32,
                epoch: self.epoch[i],
            }));
        }
    }

    /// Reports, in time order, every sensor event at or before `t` on the bodies' current
    /// motions. Call it before a body's motion changes at `t`, and before the clock moves to
    /// `t`.
    pub fn advance_to(&mut self, world: &World<D>, t: f64) {
        while let Some(&Reverse(p)) = self.queue.peek() {
            let time = unordered(p.time);
            if time > t {
                break;
            }
            self.queue.pop();
            let i = p.body as usize;
            if p.epoch != self.epoch[i] {
                continue;
            }
            let (k, s) = (p.sensor as usize, self.sensors.len());
            let was_inside = self.inside[i * s + k];
            self.inside[i * s + k] = !was_inside;
            self.counts[k][usize::from(was_inside)] += 1;
            self.out.push(SensorEvent {
                time,
                body: i,
                sensor: k,
                change: if was_inside {
                    SensorChange::Leave
                } else {
                    SensorChange::Enter
                },
            });
            // The next event from here on, on the same motion. A body whose last two events
            // flipped sensor `k` at this very instant (entered and left, or left and entered)
            // grazed its sphere: at the touch, rounding can have the entry test say "touching
            // and approaching" and the exit test "touching and moving away" from the same
            // state, for ever. One touch is two flips; the sensor's crossing at this instant
            // is then passed over (and so its later crossings on this motion, until the
            // body's motion changes: a second crossing of the same sphere on one parabola
            // right after a graze goes unreported).
            let grazed = (self.grazed == Some((i, k, p.time))).then_some(k);
            self.grazed = if grazed.is_some() {
                None
            } else {
                Some((i, k, p.time))
            };
            if time == Self::origin(world, i) && grazed.is_none() {
                // Still at the instant the body was last looked at anew: other sensors may
                // disagree with the geometry there too.
                self.body_changed(world, i);
                continue;
            }
            let (pos, vel) = (world.position_at(i, time), world.velocity_at(i, time));
            let next = self.next_crossing_but(world, i, pos, vel, time, grazed);
            self.queue_next(i, next);
        }
    }
}

/// [`SensorTracker`]'s next crossing of `sensor` by body `i`, which turns with `pivot` (see
/// [`crate::motion::pivot`]), from `t0` until its turn ends: the first entry (or exit, `inside`)
/// found by [`crate::contact::pivot_contact`]'s search, which skips no root.
fn pivot_crossing<const D: usize>(
    world: &World<D>,
    i: usize,
    pivot: &crate::motion::pivot::Pivot,
    sensor: &Sensor<D>,
    inside: bool,
    t0: f64,
) -> Option<f64> {
    use crate::contact::pivot_contact::{first_contact_points, first_exit_points, Parabola};
    let center = Parabola {
        pos: crate::world::to_2d(sensor.center),
        vel: Vector::ZERO,
        acc: Vector::ZERO,
        time: t0,
    };
    let hi = crate::sim::pivot_events::turn_end(world, i).map_or(f64::INFINITY, |e| e.time());
    let reach = sensor.radius + world.radius(i);
    if inside {
        first_exit_points(pivot, &center, reach, t0, hi)
    } else {
        first_contact_points(pivot, &center, reach, t0, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordered_times_round_trip_and_sort() {
        let ts = [-2.0, -0.5, 0.0, 1e-300, 0.5, 3.0, 1e300];
        for w in ts.windows(2) {
            assert!(ordered(w[0]) < ordered(w[1]), "{w:?}");
        }
        for t in ts {
            assert_eq!(unordered(ordered(t)), t);
        }
    }
}

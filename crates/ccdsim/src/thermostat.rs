//! The Andersen thermostat: random velocity resets that hold a run at a set temperature (NVT).
//!
//! Each body has its velocity replaced, at the events of a Poisson process of rate `ν` per
//! body, by a fresh draw from the Maxwell distribution at `kT` (each component normal with
//! variance `kT / m`). The whole sequence (times, bodies and the standard normal draws) comes
//! from a ChaCha8 generator seeded by the scene and depends on nothing else: it is the same
//! for every finder, so thermostatted runs stay bit for bit identical across finders, and
//! `verify` regenerates it to check a run file's resets.
//!
//! In a sheared box (see [`crate::contact::lees_edwards`]) the draw is the body's peculiar
//! velocity: the imposed flow where it is, `γ̇ (y − L_y/2)` along x, is added to it, so the
//! thermostat removes the heat the shear makes.
//!
//! Reset times are `t_{k+1} = t_k + Exp(ν N)` from the scene's start time; the reset's body is
//! uniform over the `N` bodies. A reset at the same time as a collision comes after it.
//!
//! # Slots that take no reset
//!
//! `N` counts *slots*: kinematic bodies, whose velocity their program sets, and vacant slots
//! (bodies removed, or room reserved for bodies to come, see
//! [`crate::Simulation::add_body`]) are drawn like the others, and such a draw is passed over
//! when the clock reaches it, leaving no trace. Thinning a Poisson process this way keeps it
//! Poisson: each body that moves freely is still reset at rate `ν`, whatever the others are,
//! and a slot filled by an added body takes its resets from the moment it is filled. A draw
//! due at or before an edit's time is judged before the edit. When the world appends slots
//! (at time `t`, to `N'`), the draw pending then is dropped and the sequence goes on from
//! `t` at rate `ν N'` ([`ResetClock::grow`]); memorylessness makes that the same process.
//! Runs without kinematic bodies or edits draw exactly the sequence they always did.

use crate::geom::Vector;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Exp, StandardNormal};
use serde::{Deserialize, Serialize};

/// The thermostat's settings (`settings.thermostat` in a scene file).
///
/// ```json
/// "settings": { "thermostat": { "temperature": 1.0, "rate": 0.1, "seed": 7 } }
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Thermostat {
    /// The temperature `kT` the bodies are reset to, joules (Boltzmann's constant is 1).
    pub temperature: f64,
    /// Resets per body per second, `ν`.
    pub rate: f64,
    /// Seed of the reset sequence.
    #[serde(default)]
    pub seed: u64,
}

impl Thermostat {
    /// The first field that is not a positive finite number, by its scene-file name.
    #[must_use]
    pub fn invalid_field(&self) -> Option<&'static str> {
        let bad = |x: f64| !(x.is_finite() && x > 0.0);
        if bad(self.temperature) {
            Some("settings.thermostat.temperature")
        } else if bad(self.rate) {
            Some("settings.thermostat.rate")
        } else {
            None
        }
    }
}

/// One velocity reset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reset<const D: usize> {
    /// When, seconds.
    pub time: f64,
    /// Which body (index).
    pub body: usize,
    /// Its new velocity, metres per second.
    pub velocity: Vector<D>,
}

/// The sequence of resets of one run, drawn ahead one at a time.
#[derive(Clone, Debug)]
pub struct ResetClock {
    rng: ChaCha8Rng,
    temperature: f64,
    /// `ν`, resets per slot per second.
    rate: f64,
    gap: Option<Exp<f64>>,
    /// `N`: the slots drawn from.
    slots: usize,
    /// The next reset: time, body and standard normal draws (scaled by the mass when taken).
    next_time: f64,
    next_body: usize,
    next_normals: [f64; 3],
}

impl ResetClock {
    /// The resets of `slots` slots (bodies) from time `start` on (none without slots).
    #[must_use]
    pub fn new(thermostat: &Thermostat, slots: usize, start: f64) -> Self {
        let mut clock = ResetClock {
            rng: ChaCha8Rng::seed_from_u64(thermostat.seed),
            temperature: thermostat.temperature,
            rate: thermostat.rate,
            gap: None,
            slots: 0,
            next_time: start,
            next_body: 0,
            next_normals: [0.0; 3],
        };
        clock.restart(slots, start);
        clock
    }

    /// Draws over `slots` slots from time `now` on, dropping the pending draw: the world
    /// appended slots at `now` (see the module docs). Nothing changes when the count does not.
    pub fn grow(&mut self, slots: usize, now: f64) {
        if slots != self.slots {
            self.restart(slots, now);
        }
    }

    fn restart(&mut self, slots: usize, now: f64) {
        let total = self.rate * slots as f64;
        self.gap = (slots > 0 && total.is_finite() && total > 0.0)
            .then(|| Exp::new(total).expect("a positive finite rate"));
        self.slots = slots;
        self.next_time = now;
        self.draw();
    }

    /// Passes over the next draw (its slot takes no reset, see the module docs) and draws the
    /// one after it.
    pub fn skip(&mut self) {
        self.draw();
    }

    /// Time of the next reset, seconds (`+∞` when there is none).
    #[must_use]
    pub fn next_time(&self) -> f64 {
        self.next_time
    }

    /// Body of the next reset.
    #[must_use]
    pub fn next_body(&self) -> usize {
        self.next_body
    }

    /// The next reset, for a body of mass `mass` (kg), and draws the one after it.
    pub fn take<const D: usize>(&mut self, mass: f64) -> Reset<D> {
        let scale = (self.temperature / mass).sqrt();
        let mut velocity = Vector([0.0; D]);
        for d in 0..D {
            velocity[d] = scale * self.next_normals[d];
        }
        let reset = Reset {
            time: self.next_time,
            body: self.next_body,
            velocity,
        };
        self.draw();
        reset
    }

    fn draw(&mut self) {
        let Some(gap) = self.gap else {
            self.next_time = f64::INFINITY;
            return;
        };
        self.next_time += gap.sample(&mut self.rng);
        self.next_body = self.rng.random_range(0..self.slots);
        for x in &mut self.next_normals {
            *x = StandardNormal.sample(&mut self.rng);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sequence_depends_on_the_seed_alone_and_has_the_right_statistics() {
        let th = Thermostat {
            temperature: 2.0,
            rate: 0.5,
            seed: 3,
        };
        let mut a = ResetClock::new(&th, 100, 10.0);
        let mut b = ResetClock::new(&th, 100, 10.0);
        let (mut last, mut sum_v2, k) = (10.0, 0.0, 20_000);
        for _ in 0..k {
            let ra = a.take::<3>(4.0);
            assert_eq!(ra, b.take::<3>(4.0));
            assert!(ra.time > last && ra.body < 100);
            last = ra.time;
            sum_v2 += ra.velocity.norm_sq();
        }
        // Mean gap 1 / (ν N) = 0.02 s; ⟨m v²⟩ = D kT.
        let mean_gap = (last - 10.0) / k as f64;
        assert!((mean_gap - 0.02).abs() < 0.02 * 0.03, "{mean_gap}");
        let mv2 = 4.0 * sum_v2 / k as f64;
        assert!((mv2 - 6.0).abs() < 6.0 * 0.03, "{mv2}");
    }

    #[test]
    fn growing_the_slots_restarts_the_sequence_from_then_over_all_of_them() {
        let th = Thermostat {
            temperature: 1.0,
            rate: 0.5,
            seed: 8,
        };
        let mut clock = ResetClock::new(&th, 10, 0.0);
        let same = ResetClock::new(&th, 10, 0.0);
        clock.grow(10, 3.0); // the same count: nothing changes
        assert_eq!(
            (clock.next_time(), clock.next_body()),
            (same.next_time(), same.next_body())
        );
        clock.grow(40, 3.0);
        let (k, mut last, mut seen_high) = (8000, 3.0, false);
        for _ in 0..k {
            let r = clock.take::<2>(1.0);
            assert!(r.time > last && r.body < 40);
            seen_high |= r.body >= 10;
            last = r.time;
        }
        assert!(seen_high);
        // Mean gap 1 / (ν · 40) = 0.05 s.
        let mean_gap = (last - 3.0) / f64::from(k);
        assert!((mean_gap - 0.05).abs() < 0.05 * 0.04, "{mean_gap}");
        // Skipping a draw moves on to the next one.
        let before = clock.next_time();
        clock.skip();
        assert!(clock.next_time() > before);
    }

    #[test]
    fn no_bodies_no_resets() {
        let th = Thermostat {
            temperature: 1.0,
            rate: 1.0,
            seed: 0,
        };
        assert_eq!(ResetClock::new(&th, 0, 0.0).next_time(), f64::INFINITY);
        assert_eq!(th.invalid_field(), None);
        let bad = Thermostat { rate: 0.0, ..th };
        assert_eq!(bad.invalid_field(), Some("settings.thermostat.rate"));
    }
}

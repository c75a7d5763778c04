//! The replay of rough bodies' spins and the check of the rough-sphere rule (see
//! [`crate::motion::spin`]).
//!
//! Run files do not record spins: each collision's impulse on a body, `m·Δv` from its
//! recorded velocities, acts at the contact point, so its spin changes by
//! `(n × Δv)/(q·r)` (`n` the unit vector from the body's centre to the contact point).
//! Replaying spins this way keeps each body's angular momentum about the contact point
//! exactly when its linear momentum is (which `verify` checks); what is left to check is
//! the tangential rule (the contact points' tangential velocity `g_t` becomes `−β·g_t`, or
//! stays as it was when the bodies were already parting) and the energy rule (translational
//! plus rotational energy kept when `e = 1` and `β = ±1`, never made otherwise). This code
//! shares nothing with the simulation's collision response.

use super::{beyond, magnitude, Verifier, Violation};
use crate::geom::Vector;
use crate::scene::Scene;
use crate::sim::Collision;

/// A collision's rotational energy before and after, and how far they may be from the
/// simulation's (the replayed spins' slack), joules.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Turned {
    pub(super) before: f64,
    pub(super) after: f64,
    pub(super) slack: f64,
}

/// Spins, inertia factors and tangential restitutions of a rotational scene's slots.
#[derive(Clone, Debug)]
pub(super) struct Spins {
    spin: Vec<Vector<3>>,
    /// A bound on how far each replayed spin may be from the simulation's, rad/s: the two
    /// sum the same changes with their own rounding, and an error made while a body spun
    /// fast stays when it has slowed down (a cooling gas loses ten orders of magnitude).
    slack: Vec<f64>,
    inertia: Vec<f64>,
    tangential: Vec<f64>,
    default_inertia: f64,
    default_tangential: f64,
}

fn cross(a: Vector<3>, b: Vector<3>) -> Vector<3> {
    Vector([
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ])
}

fn to3<const D: usize>(v: Vector<D>) -> Vector<3> {
    let mut w = Vector::<3>::ZERO;
    for k in 0..D {
        w[k] = v[k];
    }
    w
}

impl Spins {
    /// The scene's spins at its start; `None` unless the scene is rotational.
    pub(super) fn of<const D: usize>(scene: &Scene<D>) -> Option<Self> {
        let r = scene.body_rotations()?;
        Some(Spins {
            slack: vec![0.0; r.spins.len()],
            spin: r.spins,
            inertia: r.inertia,
            tangential: r.tangential,
            default_inertia: r.default_inertia,
            default_tangential: r.default_tangential,
        })
    }

    /// A new slot (reserved or added): no spin, the scene's defaults.
    pub(super) fn push(&mut self) {
        self.spin.push(Vector::ZERO);
        self.slack.push(0.0);
        self.inertia.push(self.default_inertia);
        self.tangential.push(self.default_tangential);
    }

    /// Slot `i` emptied: its body, its spin and its own inertia factor and tangential
    /// restitution are gone; a body added there has the scene's defaults.
    pub(super) fn vacate(&mut self, i: usize) {
        self.spin[i] = Vector::ZERO;
        self.slack[i] = 0.0;
        self.inertia[i] = self.default_inertia;
        self.tangential[i] = self.default_tangential;
    }

    /// Sets slot `i`'s replayed spin to `w`, computed from `before` with velocity changes
    /// of speeds up to `speed` (m/s) at lever `lever` (`q·r`, metres), growing its slack by
    /// the rounding of that step.
    fn replay(&mut self, i: usize, before: Vector<3>, w: Vector<3>, speed: f64, lever: f64) {
        self.slack[i] += 8.0 * f64::EPSILON * (before.norm() + w.norm() + speed / lever);
        self.spin[i] = w;
    }

    /// Rotational energy of slot `i` of mass `m` (0 for kinematic or vacant) and radius `r`,
    /// joules.
    pub(super) fn energy(&self, i: usize, m: f64, r: f64) -> f64 {
        0.5 * self.inertia[i] * m * r * r * self.spin[i].norm_sq()
    }

    /// How far [`Spins::energy`] may be from the simulation's, joules: the energy of the
    /// spin's slack around the spin.
    fn energy_slack(&self, i: usize, m: f64, r: f64) -> f64 {
        let (w, slack) = (self.spin[i].norm(), self.slack[i]);
        self.inertia[i] * m * r * r * (2.0 * w + slack) * slack
    }
}

impl<const D: usize> Verifier<D> {
    /// Tangential restitution of a collision of bodies `i` and `j` (−1 without spins).
    pub(super) fn pair_tangential(&self, i: usize, j: usize) -> f64 {
        self.spins.as_ref().map_or(-1.0, |s| {
            let (a, b) = (s.tangential[i], s.tangential[j]);
            if a == b {
                a
            } else {
                0.5 * (a + b)
            }
        })
    }

    /// Tangential restitution of body `i` at a wall (−1 without spins).
    pub(super) fn wall_tangential(&self, i: usize) -> f64 {
        self.spins.as_ref().map_or(-1.0, |s| s.tangential[i])
    }

    /// Rotational energy of every slot now, joules (0 without spins).
    pub(super) fn rotational_energy(&self, t: f64) -> f64 {
        self.spins.as_ref().map_or(0.0, |s| {
            (0..self.motion.len())
                .map(|i| s.energy(i, self.mass[i], self.radius_at(i, t)))
                .sum()
        })
    }

    /// Replays the spins of bodies `i` and `j` through their collision `c` (velocities
    /// `(vi, vj)` just before it) and checks the tangential rule; returns the pair's
    /// rotational energy before and after (zero without spins).
    pub(super) fn spin_pair(
        &mut self,
        c: &Collision<D>,
        (i, j): (usize, usize),
        (vi, vj): (Vector<D>, Vector<D>),
        grow: f64,
    ) -> Result<Turned, Violation> {
        let t = c.event.time;
        let (ri, rj) = (self.radius_at(i, t), self.radius_at(j, t));
        let (mi, mj) = (self.mass[i], self.mass[j]);
        let d = self.image(c.pos[1] - c.pos[0], t);
        let Some(s) = &self.spins else {
            return Ok(Turned::default());
        };
        let n = to3(d * (1.0 / d.norm()));
        let (dvi, dvj) = (to3(c.vel[0] - vi), to3(c.vel[1] - vj));
        let (si, sj) = (s.spin[i], s.spin[j]);
        let (qi, qj) = (s.inertia[i], s.inertia[j]);
        // Body i is pushed at r_i·n, body j at −r_j·n; a kinematic body's Δv is zero.
        let si2 = si + cross(n, dvi) * (1.0 / (qi * ri));
        let sj2 = sj - cross(n, dvj) * (1.0 / (qj * rj));
        let beta = self.pair_tangential(i, j);
        let before = s.energy(i, mi, ri) + s.energy(j, mj, rj);
        let contact = |vi: Vector<D>, vj: Vector<D>, si: Vector<3>, sj: Vector<3>| {
            to3(vi) - to3(vj) + cross(si * ri + sj * rj, n)
        };
        let g0 = contact(vi, vj, si, sj);
        let g1 = contact(c.vel[0], c.vel[1], si2, sj2);
        let speeds = magnitude(vi) + magnitude(vj) + magnitude(c.vel[0]) + magnitude(c.vel[1]);
        let scale = speeds + (si.norm() + si2.norm()) * ri + (sj.norm() + sj2.norm()) * rj + grow;
        // The replayed spins' own rounding, at the contact points (both enter g twice: the
        // spin and its change).
        let slack = 4.0 * (s.slack[i] * ri + s.slack[j] * rj);
        // The pair closes when (v_j − v_i)·n < σ̇, that is g·n > −σ̇.
        let margin = g0.dot(n) + grow;
        let who = format!("bodies {i} and {j}");
        self.check_tangential(t, (n, g0, g1), beta, margin, (scale, slack), &who)?;
        let s = self.spins.as_mut().expect("spins");
        s.replay(i, si, si2, speeds, qi * ri);
        s.replay(j, sj, sj2, speeds, qj * rj);
        Ok(Turned {
            before,
            after: s.energy(i, mi, ri) + s.energy(j, mj, rj),
            slack: 2.0 * (s.energy_slack(i, mi, ri) + s.energy_slack(j, mj, rj)),
        })
    }

    /// [`Verifier::spin_pair`] for body `i` (velocity `v` just before) at a wall of unit
    /// normal `n` (towards the body) moving at `wall_velocity`.
    pub(super) fn spin_wall(
        &mut self,
        c: &Collision<D>,
        i: usize,
        (v, wall_velocity): (Vector<D>, Vector<D>),
        n: Vector<D>,
        grow: f64,
    ) -> Result<Turned, Violation> {
        let t = c.event.time;
        let r = self.radius_at(i, t);
        let m = self.mass[i];
        let Some(s) = &self.spins else {
            return Ok(Turned::default());
        };
        let n = to3(n * (1.0 / n.norm()));
        let (w, q, beta) = (s.spin[i], s.inertia[i], s.tangential[i]);
        // Pushed at −r·n.
        let w2 = w - cross(n, to3(c.vel[0] - v)) * (1.0 / (q * r));
        let contact = |v: Vector<D>, w: Vector<3>| to3(v - wall_velocity) - cross(w * r, n);
        let (g0, g1) = (contact(v, w), contact(c.vel[0], w2));
        let speeds = magnitude(v) + magnitude(c.vel[0]) + magnitude(wall_velocity);
        let scale = speeds + (w.norm() + w2.norm()) * r + grow;
        let slack = 4.0 * s.slack[i] * r;
        let before = s.energy(i, m, r);
        // The body closes on the wall when (v − w)·n < Γ·r.
        let margin = grow - g0.dot(n);
        let who = format!("body {i} at a wall");
        self.check_tangential(t, (n, g0, g1), beta, margin, (scale, slack), &who)?;
        let s = self.spins.as_mut().expect("spins");
        s.replay(i, w, w2, speeds, q * r);
        Ok(Turned {
            before,
            after: s.energy(i, m, r),
            slack: 2.0 * s.energy_slack(i, m, r),
        })
    }

    /// The contact points' velocity `g0 → g1` (first body less second, or body less wall,
    /// `n` the collision's unit normal) obeys the tangential rule with `β`: its tangential
    /// part becomes `−β·g_t` when the surfaces approached (`margin > 0`, the normal speed at
    /// which they close beyond the contact distance's growth) and stays as it was when they
    /// were already parting; within rounding of `scale` of the boundary, either. Rounding is
    /// relative to `scale` (m/s) plus `slack` (m/s), what the replayed spins may be off by.
    fn check_tangential(
        &self,
        t: f64,
        (n, g0, g1): (Vector<3>, Vector<3>, Vector<3>),
        beta: f64,
        margin: f64,
        (scale, slack): (f64, f64),
        who: &str,
    ) -> Result<(), Violation> {
        let (t0, t1) = (g0 - n * g0.dot(n), g1 - n * g1.dot(n));
        let tol = 1e-9 * (scale + f64::MIN_POSITIVE) + slack;
        let reversed = !beyond((t1 + t0 * beta).norm(), tol);
        let kept = !beyond((t1 - t0).norm(), tol);
        let ok = if margin.abs() <= tol {
            reversed || kept
        } else if margin > 0.0 {
            reversed
        } else {
            kept
        };
        if ok {
            return Ok(());
        }
        Err(self.fail(
            t,
            format!(
                "{who}: the contact points' tangential velocity {:?} becomes {:?}, the rough \
                 rule with tangential restitution {beta} asks for {:?}",
                t0.0,
                t1.0,
                (if margin > 0.0 { t0 * -beta } else { t0 }).0
            ),
        ))
    }
}

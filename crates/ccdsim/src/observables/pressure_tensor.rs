//! The pressure tensor of a hard-body fluid from its collisions.

use crate::contact::periodic::min_image;
use crate::event::EventKind;
use crate::geom::Vector;
use crate::sim::{Collision, Simulation};

/// Accumulates the pressure tensor over a stretch of a run, exactly:
///
/// `P_ab = ( ∫ Σ_i m_i v_ia v_ib dt + Σ_collisions r_ij,a J_i,b ) / (V t)`
///
/// The kinetic part is integrated piecewise (velocities change only at events); the virial
/// part sums, over body–body collisions, the line of centres (nearest image) times the
/// impulse, as [`Stats::virial`](crate::Stats::virial) does for the trace. In a periodic world
/// the kinetic part is taken in the centre-of-mass frame. Wall impulses are left out (the bulk
/// pressure, as in [`thermodynamic`](super::thermodynamic)). Its trace over `D` is the scalar
/// pressure of [`Simulation::observables`] for an elastic run. Not for worlds with gravity,
/// whose velocities change between events.
///
/// Feed it every collision of the stretch, in order (e.g. from
/// [`Simulation::run_until_with`]), then read [`PressureTensor::tensor`]:
///
/// ```
/// use ccdsim::observables::PressureTensor;
/// use ccdsim::{generate, Simulation};
/// let scene = generate::gas::<2>(&generate::GasConfig { n: 100, packing: 0.3, periodic: true,
///     seed: 1, ..Default::default() }).unwrap();
/// let mut sim = Simulation::new(&scene, "cells").unwrap();
/// let mut p = PressureTensor::new(&sim).unwrap();
/// sim.run_until_with(5.0, |c| p.observe(c));
/// let tensor = p.tensor(sim.time());
/// let scalar = sim.observables().pressure.unwrap();
/// assert!(((tensor[0][0] + tensor[1][1]) / 2.0 - scalar).abs() < 1e-9 * scalar);
/// ```
#[derive(Clone, Debug)]
pub struct PressureTensor<const D: usize> {
    velocities: Vec<Vector<D>>,
    masses: Vec<f64>,
    periodic: Option<Vector<D>>,
    volume: f64,
    start: f64,
    last: f64,
    /// Σ m v vᵀ now.
    kinetic: [[f64; D]; D],
    /// ∫ Σ m v vᵀ dt up to `last`.
    kinetic_integral: [[f64; D]; D],
    virial: [[f64; D]; D],
    /// Centre-of-mass term `P Pᵀ / M`, constant in a periodic world.
    centre_of_mass: [[f64; D]; D],
}

impl<const D: usize> PressureTensor<D> {
    /// Starts at the simulation's current time; an error if the world has no volume (no
    /// periodic box and no walls).
    pub fn new(sim: &Simulation<D>) -> Result<Self, String> {
        let world = sim.world();
        let volume = super::thermodynamic::world_volume(world)
            .ok_or("the pressure needs a volume: a periodic box or walls")?;
        let velocities: Vec<Vector<D>> = world.velocities().collect();
        let masses: Vec<f64> = world.masses().collect();
        let mut kinetic = [[0.0; D]; D];
        for (v, m) in velocities.iter().zip(&masses) {
            add_outer(&mut kinetic, *m, v, v);
        }
        let mut centre_of_mass = [[0.0; D]; D];
        if world.periodic().is_some() {
            let p = world.momentum();
            let total: f64 = masses.iter().sum();
            add_outer(&mut centre_of_mass, 1.0 / total, &p, &p);
        }
        Ok(PressureTensor {
            velocities,
            masses,
            periodic: world.periodic(),
            volume,
            start: sim.time(),
            last: sim.time(),
            kinetic,
            kinetic_integral: [[0.0; D]; D],
            virial: [[0.0; D]; D],
            centre_of_mass,
        })
    }

    /// Takes in one collision (the next of the run).
    pub fn observe(&mut self, c: &Collision<D>) {
        let t = c.event.time;
        self.integrate_to(t);
        let a = c.event.a as usize;
        let (ma, va) = (self.masses[a], self.velocities[a]);
        add_outer(&mut self.kinetic, -ma, &va, &va);
        add_outer(&mut self.kinetic, ma, &c.vel[0], &c.vel[0]);
        self.velocities[a] = c.vel[0];
        if c.event.kind == EventKind::Body {
            let b = c.event.b as usize;
            let (mb, vb) = (self.masses[b], self.velocities[b]);
            add_outer(&mut self.kinetic, -mb, &vb, &vb);
            add_outer(&mut self.kinetic, mb, &c.vel[1], &c.vel[1]);
            self.velocities[b] = c.vel[1];
            let mut r = c.pos[0] - c.pos[1];
            if let Some(size) = self.periodic {
                r = min_image(r, &size);
            }
            let impulse = (c.vel[0] - va) * ma;
            add_outer(&mut self.virial, 1.0, &r, &impulse);
        }
    }

    /// The pressure tensor (force per length in 2D, per area in 3D) over the stretch from the
    /// start to `now` (no earlier than the last collision observed); zeros for an empty stretch.
    #[must_use]
    pub fn tensor(&self, now: f64) -> [[f64; D]; D] {
        let span = now.max(self.last) - self.start;
        let mut out = [[0.0; D]; D];
        if span <= 0.0 {
            return out;
        }
        let tail = now.max(self.last) - self.last;
        for (a, row) in out.iter_mut().enumerate() {
            for (b, p) in row.iter_mut().enumerate() {
                let kinetic = self.kinetic_integral[a][b] + self.kinetic[a][b] * tail;
                *p = (kinetic / span - self.centre_of_mass[a][b] + self.virial[a][b] / span)
                    / self.volume;
            }
        }
        out
    }

    fn integrate_to(&mut self, t: f64) {
        let dt = t - self.last;
        if dt > 0.0 {
            for a in 0..D {
                for b in 0..D {
                    self.kinetic_integral[a][b] += self.kinetic[a][b] * dt;
                }
            }
            self.last = t;
        }
    }
}

/// `m += s · x yᵀ`.
fn add_outer<const D: usize>(m: &mut [[f64; D]; D], s: f64, x: &Vector<D>, y: &Vector<D>) {
    for a in 0..D {
        for b in 0..D {
            m[a][b] += s * x[a] * y[b];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{gas, GasConfig};

    #[test]
    fn trace_is_the_scalar_pressure_and_the_tensor_is_isotropic() {
        let scene = gas::<3>(&GasConfig {
            n: 500,
            packing: 0.3,
            periodic: true,
            seed: 9,
            ..Default::default()
        })
        .unwrap();
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        let mut p = PressureTensor::new(&sim).unwrap();
        sim.run_until_with(20.0, |c| p.observe(c));
        let t = p.tensor(sim.time());
        let scalar = sim.observables().pressure.unwrap();
        let trace = (t[0][0] + t[1][1] + t[2][2]) / 3.0;
        assert!(
            (trace - scalar).abs() < 1e-9 * scalar,
            "{trace} vs {scalar}"
        );
        for a in 0..3 {
            assert!((t[a][a] - scalar).abs() < 0.05 * scalar, "{t:?}");
            for b in 0..3 {
                if a != b {
                    assert!(t[a][b].abs() < 0.05 * scalar, "{t:?}");
                    // Each collision adds r Jᵀ with J ∥ r: the tensor is symmetric.
                    assert!((t[a][b] - t[b][a]).abs() < 1e-9 * scalar);
                }
            }
        }
    }
}

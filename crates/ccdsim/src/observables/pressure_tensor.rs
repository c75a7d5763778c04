//! The pressure tensor of a hard-body fluid from its collisions.

use crate::contact::lees_edwards::ShearedBox;
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
/// the kinetic part is taken in the centre-of-mass frame, and in a sheared box (see
/// [`crate::contact::lees_edwards`]) in peculiar velocities, relative to the imposed flow
/// `γ̇ (y − L_y/2) e_x` where each body is: `−P_xy / γ̇` is the shear viscosity. Wall impulses are left out (the bulk
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
    /// Each body's velocity; in a sheared box its peculiar velocity at the start, extended
    /// along its motion: `c(t) = c₀ + ċ·(t − start)` (see `slopes`).
    velocities: Vec<Vector<D>>,
    masses: Vec<f64>,
    periodic: Option<Vector<D>>,
    /// The sheared box, if the world is one: the kinetic part is then taken in peculiar
    /// velocities, which change between events as bodies move across the flow.
    shear: Option<ShearedBox<D>>,
    /// Sheared boxes: each body's `ċ = −γ̇ v_y e_x`, how its peculiar velocity changes.
    slopes: Vec<Vector<D>>,
    volume: f64,
    start: f64,
    last: f64,
    /// Σ m v vᵀ now (in a sheared box, Σ m c₀ c₀ᵀ).
    kinetic: [[f64; D]; D],
    /// Sheared boxes: `Σ m (c₀ ċᵀ + ċ c₀ᵀ)` and `Σ m ċ ċᵀ`, the terms of `Σ m c cᵀ` linear
    /// and quadratic in `t − start`.
    kinetic_slope: [[[f64; D]; D]; 2],
    /// ∫ Σ m v vᵀ dt up to `last`.
    kinetic_integral: [[f64; D]; D],
    virial: [[f64; D]; D],
    /// Centre-of-mass term `P Pᵀ / M`, constant in a periodic world (zero in a sheared one).
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
        let shear = world.shear();
        let mut tensor = PressureTensor {
            velocities,
            masses,
            periodic: world.periodic(),
            shear,
            slopes: Vec::new(),
            volume,
            start: sim.time(),
            last: sim.time(),
            kinetic: [[0.0; D]; D],
            kinetic_slope: [[[0.0; D]; D]; 2],
            kinetic_integral: [[0.0; D]; D],
            virial: [[0.0; D]; D],
            centre_of_mass: [[0.0; D]; D],
        };
        if shear.is_some() {
            tensor.slopes = vec![Vector::ZERO; tensor.velocities.len()];
            for i in 0..tensor.velocities.len() {
                let v = tensor.velocities[i];
                let y = world.position_at(i, sim.time())[1];
                tensor.set_peculiar(i, y, v, sim.time());
                tensor.add_body(i, 1.0);
            }
            return Ok(tensor);
        }
        for (v, m) in tensor.velocities.iter().zip(&tensor.masses) {
            add_outer(&mut tensor.kinetic, *m, v, v);
        }
        if world.periodic().is_some() {
            let p = world.momentum();
            let total: f64 = tensor.masses.iter().sum();
            add_outer(&mut tensor.centre_of_mass, 1.0 / total, &p, &p);
        }
        Ok(tensor)
    }

    /// Sheared boxes: stores body `i`'s peculiar velocity as `c₀` and `ċ`, from its height
    /// `y` and velocity `v` at time `t`.
    fn set_peculiar(&mut self, i: usize, y: f64, v: Vector<D>, t: f64) {
        let bx = self.shear.expect("sheared boxes only");
        // Its height at the start, continued along its motion (exits leave `c` unchanged).
        let y0 = y - v[1] * (t - self.start);
        let mut c0 = v;
        c0[0] -= bx.flow(y0);
        let mut slope = Vector::ZERO;
        slope[0] = -bx.rate * v[1];
        self.velocities[i] = c0;
        self.slopes[i] = slope;
    }

    /// Sheared boxes: adds `sign` times body `i`'s terms to the kinetic sums.
    fn add_body(&mut self, i: usize, sign: f64) {
        let (m, c0, slope) = (self.masses[i] * sign, self.velocities[i], self.slopes[i]);
        add_outer(&mut self.kinetic, m, &c0, &c0);
        add_outer(&mut self.kinetic_slope[0], m, &c0, &slope);
        add_outer(&mut self.kinetic_slope[0], m, &slope, &c0);
        add_outer(&mut self.kinetic_slope[1], m, &slope, &slope);
    }

    /// Sheared boxes: body `i`'s peculiar velocity at time `t`.
    fn peculiar_at(&self, i: usize, t: f64) -> Vector<D> {
        self.velocities[i] + self.slopes[i] * (t - self.start)
    }

    /// Sheared boxes: takes in one collision.
    fn observe_sheared(&mut self, c: &Collision<D>, bx: &ShearedBox<D>) {
        let t = c.event.time;
        let a = c.event.a as usize;
        let before = self.peculiar_at(a, t);
        self.add_body(a, -1.0);
        self.set_peculiar(a, c.pos[0][1], c.vel[0], t);
        self.add_body(a, 1.0);
        if c.event.kind == EventKind::Body {
            let b = c.event.b as usize;
            self.add_body(b, -1.0);
            self.set_peculiar(b, c.pos[1][1], c.vel[1], t);
            self.add_body(b, 1.0);
            let r = bx.nearest_image(c.pos[0] - c.pos[1], t).0;
            let impulse = (self.peculiar_at(a, t) - before) * self.masses[a];
            add_outer(&mut self.virial, 1.0, &r, &impulse);
        }
    }

    /// Takes in one collision (the next of the run).
    pub fn observe(&mut self, c: &Collision<D>) {
        let t = c.event.time;
        self.integrate_to(t);
        if let Some(bx) = self.shear {
            self.observe_sheared(c, &bx);
            return;
        }
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
        let end = now.max(self.last);
        for (a, row) in out.iter_mut().enumerate() {
            for (b, p) in row.iter_mut().enumerate() {
                let kinetic = self.kinetic_integral[a][b] + self.kinetic_over(a, b, self.last, end);
                *p = (kinetic / span - self.centre_of_mass[a][b] + self.virial[a][b] / span)
                    / self.volume;
            }
        }
        out
    }

    fn integrate_to(&mut self, t: f64) {
        if t > self.last {
            for a in 0..D {
                for b in 0..D {
                    self.kinetic_integral[a][b] += self.kinetic_over(a, b, self.last, t);
                }
            }
            self.last = t;
        }
    }

    /// `∫ Σ m v_a v_b dt` from `t1` to `t2` on the current velocities (peculiar ones, which
    /// change linearly in time, in a sheared box).
    fn kinetic_over(&self, a: usize, b: usize, t1: f64, t2: f64) -> f64 {
        let mut k = self.kinetic[a][b] * (t2 - t1);
        if self.shear.is_some() {
            let (s1, s2) = (t1 - self.start, t2 - self.start);
            k += self.kinetic_slope[0][a][b] * (s2 * s2 - s1 * s1) / 2.0
                + self.kinetic_slope[1][a][b] * (s2 * s2 * s2 - s1 * s1 * s1) / 3.0;
        }
        k
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

//! Thermodynamic observables of a run: kinetic temperature, collision rate, pressure and the
//! compressibility factor, in 2D and 3D.
//!
//! Units are the scene's: Boltzmann's constant is 1, so a temperature is an energy (joules
//! with masses in kilograms); pressure is force per length in 2D and per area in 3D.
//!
//! * **Temperature** `kT = 2K / (D N)`, from the kinetic energy `K` of the `N` bodies. In a
//!   periodic world, where total momentum is conserved, `K` is measured in the frame of the
//!   centre of mass; in a walled world, in the walls' frame; in a sheared box, in the frame
//!   of the imposed flow (peculiar velocities, see
//!   [`ShearedBox::flow`](crate::contact::lees_edwards::ShearedBox::flow)).
//! * **Collision rate** `2C / (N t)`: body–body collisions `C` per body per unit time (every
//!   collision involves two bodies) over a duration `t`.
//! * **Pressure** from the virial theorem for hard bodies,
//!   `P V = N kT + W / (D t)`, where `W` is [`Stats::virial`](crate::Stats::virial), the sum
//!   over collisions of the line of centres dotted with the impulse, and `V` the volume (area
//!   in 2D).
//! * **Compressibility factor** `Z = P V / (N kT) = 1 + W / (D t N kT)`.
//!
//! The volume is that of the periodic box; for a walled world it is the volume of the box
//! bounding the walls' points (right for the boxes of [`gas`](crate::generate::gas), where the
//! result is the bulk virial pressure up to wall corrections of relative order `σ / L`), and
//! there is none for a world without walls.

use crate::contact::lees_edwards::ShearedBox;
use crate::wall::walls_bounds;
use crate::world::World;

/// Observables over a stretch of a run; see the module docs.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Observables {
    /// Kinetic temperature `kT`, joules.
    pub temperature: f64,
    /// Rotational temperature `kT_rot = 2·K_rot / (f·N)`, joules, with `f` the rotational
    /// degrees of freedom (1 for discs, 3 for spheres); `None` in a world that keeps no
    /// spins (see [`crate::motion::spin`]).
    pub rotational_temperature: Option<f64>,
    /// Body–body collisions per body per second.
    pub collision_rate: f64,
    /// Volume (area in 2D) used for the pressure, if the world has one.
    pub volume: Option<f64>,
    /// Pressure, if the world has a volume.
    pub pressure: Option<f64>,
    /// Compressibility factor `Z = P V / (N kT)`, if the pressure is known and `kT > 0`.
    pub compressibility: Option<f64>,
}

/// The volume the pressure refers to: the periodic box, or the box bounding the walls' points.
#[must_use]
pub fn world_volume<const D: usize>(world: &World<D>) -> Option<f64> {
    if let Some(size) = world.periodic() {
        return Some(size.0.iter().product());
    }
    let (lo, hi) = walls_bounds(world.walls())?;
    Some((0..D).map(|d| hi[d] - lo[d]).product())
}

/// Kinetic temperature `kT` of the world now (centre-of-mass frame in periodic worlds).
///
/// Over the bodies that move freely: kinematic bodies and vacant slots have no temperature.
#[must_use]
pub fn temperature<const D: usize>(world: &World<D>) -> f64 {
    let (n, m) = world
        .masses()
        .filter(|m| m.is_finite())
        .fold((0usize, 0.0), |(n, sum), m| (n + 1, sum + m));
    if n == 0 {
        return 0.0;
    }
    if let Some(bx) = world.shear() {
        return 2.0 * peculiar_kinetic_energy(world, &bx) / (D as f64 * n as f64);
    }
    let mut k = world.kinetic_energy_at(world.now());
    if world.periodic().is_some() {
        k -= 0.5 * world.momentum().norm_sq() / m;
    }
    2.0 * k.max(0.0) / (D as f64 * n as f64)
}

/// Kinetic energy of the bodies that move freely in the frame of the imposed flow of a
/// sheared box (see [`ShearedBox::flow`]): `Σ ½ m |v − γ̇ (y − L_y/2) e_x|²`, joules.
fn peculiar_kinetic_energy<const D: usize>(world: &World<D>, bx: &ShearedBox<D>) -> f64 {
    let now = world.now();
    (0..world.len())
        .filter(|&i| !world.is_kinematic(i) && !world.is_vacant(i))
        .map(|i| {
            let mut v = world.velocity(i);
            v[0] -= bx.flow(world.position_at(i, now)[1]);
            0.5 * world.mass(i) * v.norm_sq()
        })
        .sum()
}

/// Rotational temperature `kT_rot = 2·K_rot / (f·N)` of the world now, joules: `K_rot` the
/// rotational energy of the `N` bodies that move freely, `f` 1 for discs and 3 for spheres;
/// `None` in a world that keeps no spins.
#[must_use]
pub fn rotational_temperature<const D: usize>(world: &World<D>) -> Option<f64> {
    if !world.is_rotational() {
        return None;
    }
    let n = free_bodies(world);
    if n == 0 {
        return Some(0.0);
    }
    let f = crate::motion::spin::rotational_freedom::<D>() as f64;
    Some(2.0 * world.rotational_energy() / (f * n as f64))
}

/// Number of bodies that move freely: neither kinematic nor vacant slots.
fn free_bodies<const D: usize>(world: &World<D>) -> usize {
    world.masses().filter(|m| m.is_finite()).count()
}

/// The observables of `world` over a stretch of `duration` seconds during which
/// `body_collisions` collisions happened and the collision virial grew by `virial`.
#[must_use]
pub fn observables<const D: usize>(
    world: &World<D>,
    body_collisions: u64,
    virial: f64,
    duration: f64,
) -> Observables {
    let n = free_bodies(world) as f64;
    let kt = temperature(world);
    let collision_rate = if n > 0.0 && duration > 0.0 {
        2.0 * body_collisions as f64 / (n * duration)
    } else {
        0.0
    };
    let volume = world_volume(world);
    let pressure = match volume {
        Some(v) if duration > 0.0 => Some((n * kt + virial / (D as f64 * duration)) / v),
        _ => None,
    };
    let compressibility = match (pressure, volume) {
        (Some(p), Some(v)) if kt > 0.0 && n > 0.0 => Some(p * v / (n * kt)),
        _ => None,
    };
    Observables {
        temperature: kt,
        rotational_temperature: rotational_temperature(world),
        collision_rate,
        volume,
        pressure,
        compressibility,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;
    use crate::scene::{BodySpec, Scene};
    use crate::sim::Simulation;
    use crate::wall::Wall;

    #[test]
    fn ideal_gas_in_a_periodic_box() {
        // Bodies that never meet: Z = 1 exactly, P V = N kT.
        let scene = Scene::<2> {
            bodies: vec![
                BodySpec {
                    mass: Some(2.0),
                    ..BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5)
                },
                BodySpec {
                    mass: Some(2.0),
                    ..BodySpec::new(Vector([1.0, 5.0]), Vector([-1.0, 0.0]), 0.5)
                },
            ],
            periodic: Some(Vector([10.0, 10.0])),
            ..Scene::default()
        };
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        sim.run_until(7.0);
        let o = sim.observables();
        // K = 2 (zero total momentum): kT = 2K/(D N) = 1.
        assert_eq!(o.temperature, 1.0);
        assert_eq!(o.collision_rate, 0.0);
        assert_eq!(o.volume, Some(100.0));
        assert_eq!(o.pressure, Some(2.0 / 100.0));
        assert_eq!(o.compressibility, Some(1.0));
    }

    #[test]
    fn head_on_virial() {
        // Two unit masses meet head on at relative speed 2 once: J = 2, r·J = σ·2 = 2.
        let scene = Scene::<2> {
            bodies: vec![
                BodySpec {
                    mass: Some(1.0),
                    ..BodySpec::new(Vector([2.0, 5.0]), Vector([1.0, 0.0]), 0.5)
                },
                BodySpec {
                    mass: Some(1.0),
                    ..BodySpec::new(Vector([6.0, 5.0]), Vector([-1.0, 0.0]), 0.5)
                },
            ],
            periodic: Some(Vector([20.0, 10.0])),
            ..Scene::default()
        };
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        sim.run_until(4.0);
        assert_eq!(sim.stats().body_collisions, 1);
        assert!((sim.stats().virial - 2.0).abs() < 1e-12);
        let o = sim.observables();
        // K = 1, kT = 2K/(D N) = 0.5; Z = 1 + W/(D t N kT) = 1 + 2/(2·4·2·0.5) = 1.25.
        assert_eq!(o.temperature, 0.5);
        assert!((o.compressibility.unwrap() - 1.25).abs() < 1e-12);
        assert_eq!(o.collision_rate, 2.0 / (2.0 * 4.0));
    }

    #[test]
    fn walled_volume_is_the_box() {
        let scene: Scene<3> = crate::generate::gas(&crate::generate::GasConfig {
            n: 20,
            ..Default::default()
        })
        .unwrap();
        let w = World::from_scene(&scene).unwrap();
        let Wall::Plane { point, .. } = scene.walls[1] else {
            panic!()
        };
        assert!((world_volume(&w).unwrap() - point[0].powi(3)).abs() < 1e-9);
        let open = Scene::<3> {
            walls: Vec::new(),
            ..scene
        };
        assert_eq!(world_volume(&World::from_scene(&open).unwrap()), None);
    }
}

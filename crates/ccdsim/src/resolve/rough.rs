//! The rough-sphere collision rule: the tangential impulse of a collision of rough bodies
//! and the spins it changes.
//!
//! At contact the surfaces' relative velocity `g` has a normal part, which the restitution
//! `e` reverses (the rest of [`crate::resolve`]), and a tangential part `g_t`, which a
//! tangential restitution `β` turns into `−β·g_t` (β = −1: smooth, nothing changes; β = 1:
//! perfectly rough, the tangential velocity reversed). The impulse
//! `J_t = −(1 + β)·g_t / (1/m_i + 1/m_j + 1/(q_i m_i) + 1/(q_j m_j))` acts at the contact
//! point, so it changes the velocities by `±J_t/m` and the spins by `(n × J_t)/(q·m·r)`.
//! Linear momentum and the angular momentum about the contact point are kept; with `e = 1`
//! and `β = ±1` so is the total (translational and rotational) kinetic energy, and otherwise
//! it only decreases. This is the standard rule of Walton's rough spheres as used in
//! Luding, Huthmann, McNamara & Zippelius, Phys. Rev. E 58 (1998).

use crate::geom::Vector;
use crate::motion::spin::{moment, surface_velocity};
use crate::world::World;

/// What a rough collision adds to two bodies: velocity changes (m/s) and new spins (rad/s).
pub(crate) struct TangentialKick<const D: usize> {
    pub(crate) dv: [Vector<D>; 2],
    pub(crate) spins: [Vector<3>; 2],
}

/// The tangential part of a collision of bodies `i` and `j` at time `t`, with velocities
/// `vi`, `vj` just before it and `n` the unit vector from `i` to `j`; `None` when the pair
/// is smooth (β = −1) or both bodies are kinematic.
pub(crate) fn pair_kick<const D: usize>(
    world: &World<D>,
    (i, vi): (usize, Vector<D>),
    (j, vj): (usize, Vector<D>),
    n: Vector<D>,
    t: f64,
) -> Option<TangentialKick<D>> {
    let beta = world.pair_tangential_restitution(i, j);
    if beta == -1.0 {
        return None;
    }
    let (wi, wj) = (1.0 / world.mass(i), 1.0 / world.mass(j));
    let (qi, qj) = (world.inertia_factor(i), world.inertia_factor(j));
    let resistance = wi + wj + wi / qi + wj / qj;
    if resistance == 0.0 {
        return None;
    }
    let (ri, rj) = (world.radius_at(i, t), world.radius_at(j, t));
    let (si, sj) = (world.spin(i), world.spin(j));
    // The contact point is at r_i·n from i and −r_j·n from j.
    let g = vi - vj + surface_velocity(si * ri + sj * rj, n);
    let g_t = g - n * g.dot(n);
    let impulse = g_t * (-(1.0 + beta) / resistance);
    let turn = moment(n, impulse);
    Some(TangentialKick {
        dv: [impulse * wi, impulse * (-wj)],
        spins: [si + turn * (wi / (qi * ri)), sj + turn * (wj / (qj * rj))],
    })
}

/// The tangential part of a collision of body `i` (velocity `v` just before it) with a wall
/// moving at `wall_velocity` at time `t`, `n` the wall's unit normal towards the body: the
/// body's velocity change and new spin; `None` for a smooth body.
pub(crate) fn wall_kick<const D: usize>(
    world: &World<D>,
    (i, v): (usize, Vector<D>),
    wall_velocity: Vector<D>,
    n: Vector<D>,
    t: f64,
) -> Option<(Vector<D>, Vector<3>)> {
    let beta = world.wall_tangential_restitution(i);
    if beta == -1.0 {
        return None;
    }
    let q = world.inertia_factor(i);
    let r = world.radius_at(i, t);
    let s = world.spin(i);
    // The contact point is at −r·n from the centre.
    let g = v - wall_velocity - surface_velocity(s * r, n);
    let g_t = g - n * g.dot(n);
    // 1/m cancels: J_t/m = −(1 + β)·g_t·q/(1 + q).
    let dv = g_t * (-(1.0 + beta) * q / (1.0 + q));
    Some((dv, s - moment(n, dv) * (1.0 / (q * r))))
}

#[cfg(test)]
mod tests {
    use crate::geom::Vector;
    use crate::motion::Spin;
    use crate::scene::{BodySpec, Scene, Settings};
    use crate::wall::Wall;
    use crate::world::World;

    fn rough_scene(beta: f64) -> Scene<3> {
        let mut a = BodySpec::new(Vector([0.0, 0.0, 0.0]), Vector([1.0, 0.3, -0.2]), 0.5);
        a.spin = Some(Spin::Spatial([0.4, -2.0, 1.0]));
        let mut b = BodySpec::new(Vector([0.6, 0.8, 0.0]), Vector([-0.5, 0.1, 0.7]), 0.5);
        b.mass = Some(2.5);
        b.inertia = Some(0.3);
        Scene {
            settings: Settings {
                tangential_restitution: Some(beta),
                ..Settings::default()
            },
            bodies: vec![a, b],
            ..Scene::default()
        }
    }

    /// Contact velocity of the pair (i at the origin side, n from i to j).
    fn contact_velocity(world: &World<3>, n: Vector<3>) -> Vector<3> {
        let (ri, rj) = (world.radius(0), world.radius(1));
        world.velocity(0) - world.velocity(1)
            + crate::motion::spin::surface_velocity(world.spin(0) * ri + world.spin(1) * rj, n)
    }

    fn angular_momentum(world: &World<3>, about: Vector<3>) -> Vector<3> {
        (0..2)
            .map(|i| {
                let m = world.mass(i);
                let r = world.radius(i);
                crate::motion::spin::moment(world.position(i) - about, world.velocity(i) * m)
                    + world.spin(i) * (world.inertia_factor(i) * m * r * r)
            })
            .fold(Vector::ZERO, |a, b| a + b)
    }

    fn energy(world: &World<3>) -> f64 {
        world.kinetic_energy() + world.rotational_energy()
    }

    #[test]
    fn the_rule_reverses_the_tangential_contact_velocity_and_keeps_momenta() {
        for beta in [-0.5, 0.0, 0.5, 1.0] {
            let mut world = World::from_scene(&rough_scene(beta)).unwrap();
            let n = Vector([0.6, 0.8, 0.0]);
            let contact = n * 0.5;
            let g0 = contact_velocity(&world, n);
            let l0 = angular_momentum(&world, contact);
            let p0 = world.velocity(0) * world.mass(0) + world.velocity(1) * world.mass(1);
            crate::resolve::resolve_body_body(&mut world, 0, 1, 0.0);
            let g1 = contact_velocity(&world, n);
            let (t0, t1) = (g0 - n * g0.dot(n), g1 - n * g1.dot(n));
            assert!((t1 + t0 * beta).norm() < 1e-14, "β {beta}: {t0:?} → {t1:?}");
            assert!((g1.dot(n) + g0.dot(n)).abs() < 1e-14);
            let p1 = world.velocity(0) * world.mass(0) + world.velocity(1) * world.mass(1);
            assert!((p1 - p0).norm() < 1e-14);
            let l1 = angular_momentum(&world, contact);
            assert!((l1 - l0).norm() < 1e-13, "β {beta}: {l0:?} → {l1:?}");
        }
    }

    #[test]
    fn perfectly_rough_and_smooth_elastic_collisions_keep_total_energy() {
        for (beta, keeps) in [(1.0, true), (-1.0, true), (0.0, false)] {
            let mut world = World::from_scene(&rough_scene(beta)).unwrap();
            let e0 = energy(&world);
            let spins = (world.spin(0), world.spin(1));
            crate::resolve::resolve_body_body(&mut world, 0, 1, 0.0);
            let e1 = energy(&world);
            if keeps {
                assert!((e1 - e0).abs() < 1e-14 * e0, "β {beta}: {e0} → {e1}");
            } else {
                assert!(e1 < e0 * (1.0 - 1e-6));
            }
            if beta == -1.0 {
                assert_eq!((world.spin(0), world.spin(1)), spins);
            }
        }
    }

    #[test]
    fn a_perfectly_rough_ball_at_a_wall_reverses_its_contact_velocity() {
        let mut body = BodySpec::new(Vector([0.0, 0.5]), Vector([1.0, -1.0]), 0.5);
        body.spin = Some(Spin::Planar(3.0));
        let scene = Scene::<2> {
            settings: Settings {
                tangential_restitution: Some(1.0),
                ..Settings::default()
            },
            bodies: vec![body],
            walls: vec![Wall::Segment {
                a: Vector([-10.0, 0.0]),
                b: Vector([10.0, 0.0]),
            }],
            ..Scene::default()
        };
        let mut world = World::from_scene(&scene).unwrap();
        let e0 = energy2(&world);
        // Contact point velocity along x: v_x − r·(ω × n)_x with n = (0, 1): v_x + r·ω.
        let g0 = world.velocity(0)[0] + 0.5 * world.spin(0)[2];
        crate::resolve::resolve_body_wall(&mut world, 0, 0, 0.0);
        let g1 = world.velocity(0)[0] + 0.5 * world.spin(0)[2];
        assert!((g1 + g0).abs() < 1e-14, "{g0} → {g1}");
        assert_eq!(world.velocity(0)[1], 1.0);
        assert!((energy2(&world) - e0).abs() < 1e-14 * e0);
    }

    fn energy2(world: &World<2>) -> f64 {
        world.kinetic_energy() + world.rotational_energy()
    }
}

//! Analytic cases with known contact times and outgoing velocities, 2D and 3D.

use ccdsim::{BodySpec, EventKind, Scene, Simulation, Vector, Wall};

fn body<const D: usize>(pos: [f64; D], vel: [f64; D], r: f64, m: f64) -> BodySpec<D> {
    BodySpec {
        mass: Some(m),
        ..BodySpec::new(Vector(pos), Vector(vel), r)
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

fn assert_vec<const D: usize>(got: Vector<D>, want: [f64; D]) {
    for k in 0..D {
        assert!(
            close(got[k], want[k], 1e-12),
            "got {:?}, want {want:?}",
            got.0
        );
    }
}

#[test]
fn head_on_equal_masses_exchange_velocities() {
    let scene = Scene::<2> {
        bodies: vec![
            body([0.0, 0.0], [2.0, 0.0], 1.0, 1.0),
            body([10.0, 0.0], [-1.0, 0.0], 1.0, 1.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    // Gap 8 closes at 3 m/s.
    assert!(close(c.event.time, 8.0 / 3.0, 1e-15));
    assert_eq!(c.vel, [Vector([-1.0, 0.0]), Vector([2.0, 0.0])]);
    assert!(sim.step_event().is_none());
}

#[test]
fn head_on_unequal_masses() {
    // m1 = 1 at 2 m/s onto m2 = 3 at rest: v1' = (m1−m2)/(m1+m2)·u = −1, v2' = 2m1/(m1+m2)·u = 1.
    let scene = Scene::<2> {
        bodies: vec![
            body([0.0, 0.0], [2.0, 0.0], 0.5, 1.0),
            body([5.0, 0.0], [0.0, 0.0], 1.5, 3.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    assert!(close(c.event.time, 1.5, 1e-15));
    assert_vec(c.vel[0], [-1.0, 0.0]);
    assert_vec(c.vel[1], [1.0, 0.0]);
}

#[test]
fn glancing_equal_masses_leave_at_right_angles() {
    let b = 1.0; // impact parameter, radius 1 each: contact distance 2
    let scene = Scene::<2> {
        bodies: vec![
            body([0.0, 0.0], [1.0, 0.0], 1.0, 1.0),
            body([10.0, b], [0.0, 0.0], 1.0, 1.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    let dx = (4.0f64 - b * b).sqrt();
    assert!(close(c.event.time, 10.0 - dx, 1e-14));
    // Line of centres n = (dx, b)/2; target takes the normal component (u·n) n.
    let n = [dx / 2.0, b / 2.0];
    let un = n[0];
    assert_vec(c.vel[1], [un * n[0], un * n[1]]);
    assert_vec(c.vel[0], [1.0 - un * n[0], -un * n[1]]);
    assert!(c.vel[0].dot(c.vel[1]).abs() < 1e-12);
}

#[test]
fn ball_bounces_between_two_walls() {
    let scene = Scene::<2> {
        bodies: vec![body([5.0, 0.0], [1.0, 0.0], 1.0, 1.0)],
        walls: vec![
            Wall::Segment {
                a: Vector([0.0, -10.0]),
                b: Vector([0.0, 10.0]),
            },
            Wall::Segment {
                a: Vector([10.0, -10.0]),
                b: Vector([10.0, 10.0]),
            },
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    for k in 0..6 {
        let c = sim.step_event().unwrap();
        assert_eq!(c.event.kind, EventKind::Wall);
        assert_eq!(c.event.b as usize, if k % 2 == 0 { 1 } else { 0 });
        assert!(
            close(c.event.time, 4.0 + 8.0 * k as f64, 1e-14),
            "bounce {k} at {}",
            c.event.time
        );
        assert_vec(c.vel[0], [if k % 2 == 0 { -1.0 } else { 1.0 }, 0.0]);
    }
}

#[test]
fn corner_hit_reflects_about_the_end_point() {
    // Falling past the end point (10, 0) with an offset of 0.5: contact when the distance to the
    // corner is 1, i.e. at height √0.75, normal (0.5, √0.75).
    let scene = Scene::<2> {
        bodies: vec![body([10.5, 3.0], [0.0, -1.0], 1.0, 1.0)],
        walls: vec![Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([10.0, 0.0]),
        }],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    let h = 0.75f64.sqrt();
    assert!(close(c.event.time, 3.0 - h, 1e-14));
    let n = [0.5, h];
    let vn = -n[1];
    assert_vec(c.vel[0], [-2.0 * vn * n[0], -1.0 - 2.0 * vn * n[1]]);
    assert!(sim.step_event().is_none());
}

fn cradle<const D: usize>(resting: usize, axis: usize) -> Scene<D> {
    let at = |x: f64| {
        let mut p = [0.0; D];
        p[axis] = x;
        p
    };
    let mut v = [0.0; D];
    v[axis] = 1.0;
    let mut bodies = vec![body(at(-5.0), v, 1.0, 1.0)];
    for k in 0..resting {
        bodies.push(body(at(2.0 * k as f64), [0.0; D], 1.0, 1.0));
    }
    Scene {
        bodies,
        ..Scene::default()
    }
}

fn check_cradle<const D: usize>(scene: Scene<D>, axis: usize) {
    let n = scene.bodies.len();
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut events = Vec::new();
    while let Some(c) = sim.step_event() {
        events.push(c);
        assert!(events.len() <= 100, "the chain must terminate");
    }
    // One hit per neighbouring pair, in order along the chain, all at t = 3 (gap 5 − 2).
    assert_eq!(events.len(), n - 1);
    for (k, c) in events.iter().enumerate() {
        assert_eq!((c.event.a as usize, c.event.b as usize), (k, k + 1));
        assert_eq!(c.event.time, 3.0);
    }
    let world = sim.world();
    for i in 0..n - 1 {
        assert_eq!(world.velocity(i), Vector::ZERO, "ball {i} must rest");
    }
    let mut v = [0.0; D];
    v[axis] = 1.0;
    assert_eq!(world.velocity(n - 1), Vector(v), "the last ball leaves");
}

#[test]
fn newtons_cradle_2d() {
    check_cradle(cradle::<2>(5, 0), 0);
    check_cradle(cradle::<2>(4, 1), 1);
}

#[test]
fn newtons_cradle_3d() {
    check_cradle(cradle::<3>(5, 2), 2);
}

#[test]
fn head_on_3d_along_a_diagonal() {
    let d = 1.0 / 3f64.sqrt();
    let scene = Scene::<3> {
        bodies: vec![
            body([0.0, 0.0, 0.0], [d, d, d], 1.0, 1.0),
            body([4.0 * d, 4.0 * d, 4.0 * d], [0.0, 0.0, 0.0], 1.0, 1.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    assert!(close(c.event.time, 2.0, 1e-14));
    assert_vec(c.vel[0], [0.0, 0.0, 0.0]);
    assert_vec(c.vel[1], [d, d, d]);
}

#[test]
fn glancing_3d_unequal_masses_conserve_momentum_and_energy() {
    let scene = Scene::<3> {
        bodies: vec![
            body([0.0, 0.0, 0.0], [3.0, 0.0, 0.0], 1.0, 2.0),
            body([8.0, 0.6, 0.8], [-1.0, 0.0, 0.0], 1.0, 5.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let p0 = sim.world().momentum();
    let e0 = sim.world().kinetic_energy();
    let c = sim.step_event().unwrap();
    // Impact parameter 1 (|(0.6, 0.8)|), contact distance 2: x-gap √3 at contact.
    assert!(close(c.event.time, (8.0 - 3f64.sqrt()) / 4.0, 1e-14));
    let p1 = sim.world().momentum();
    for k in 0..3 {
        assert!(close(p0[k], p1[k], 1e-14));
    }
    assert!(close(e0, sim.world().kinetic_energy(), 1e-14));
}

#[test]
fn ball_between_two_planes_3d() {
    let scene = Scene::<3> {
        bodies: vec![body([0.0, 0.0, 5.0], [0.0, 0.0, -2.0], 1.0, 1.0)],
        walls: vec![
            Wall::Plane {
                point: Vector([0.0, 0.0, 0.0]),
                normal: Vector([0.0, 0.0, 1.0]),
            },
            Wall::Plane {
                point: Vector([0.0, 0.0, 10.0]),
                normal: Vector([0.0, 0.0, -1.0]),
            },
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let times: Vec<f64> = (0..4)
        .map(|_| sim.step_event().unwrap().event.time)
        .collect();
    assert_eq!(times, vec![2.0, 6.0, 10.0, 14.0]);
}

#[test]
fn inelastic_restitution_scales_the_normal_velocity() {
    let mut scene = Scene::<2> {
        bodies: vec![
            body([0.0, 0.0], [2.0, 0.0], 1.0, 1.0),
            body([5.0, 0.0], [0.0, 0.0], 1.0, 1.0),
        ],
        ..Scene::default()
    };
    scene.settings.restitution = 0.5;
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let c = sim.step_event().unwrap();
    // Relative normal velocity −2 becomes +1; momentum 2 is kept.
    assert_vec(c.vel[0], [0.5, 0.0]);
    assert_vec(c.vel[1], [1.5, 0.0]);
}

#[test]
fn advance_returns_the_frames_collisions_and_time_moves_on() {
    let scene = Scene::<2> {
        bodies: vec![
            body([0.0, 0.0], [1.0, 0.0], 0.5, 1.0),
            body([3.0, 0.0], [-1.0, 0.0], 0.5, 1.0),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut seen = Vec::new();
    for _ in 0..120 {
        seen.extend(sim.advance(1.0 / 60.0));
    }
    assert_eq!(seen.len(), 1);
    assert_eq!(seen[0].event.time, 1.0);
    assert!(close(sim.time(), 2.0, 1e-12));
    assert!(close(sim.position(0)[0], 0.0, 1e-12));
    sim.set_velocity(0, Vector([2.0, 0.0])).unwrap();
    assert!(sim.set_velocity(7, Vector([0.0, 0.0])).is_err());
    assert!(sim.set_velocity(0, Vector([f64::NAN, 0.0])).is_err());
}

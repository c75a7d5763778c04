//! Degenerate and special scenes: no bodies, one body, no walls, everything at rest, simultaneous
//! collisions, touching bodies, exact ties, Newton's cradle, the billiard break, tables of many
//! walls, grazing contacts, far from the origin, inelastic runs and inelastic collapse,
//! thermostats, memory reports.

use super::*;

fn at_rest<const D: usize>(scene: Scene<D>) -> Scene<D> {
    Scene {
        bodies: scene
            .bodies
            .into_iter()
            .map(|b| BodySpec {
                vel: Vector::ZERO,
                ..b
            })
            .collect(),
        ..scene
    }
}

/// `k` pairs meeting head-on at exactly t = 1 (all numbers exact in binary), and four bodies
/// converging on one point, plus bodies reaching walls at the same instant.
fn simultaneous_2d(k: usize) -> Scene<2> {
    let mut bodies = Vec::new();
    for p in 0..k {
        let y = 2.0 + 2.0 * p as f64;
        bodies.push(BodySpec::new(Vector([2.0, y]), Vector([1.0, 0.0]), 0.5));
        bodies.push(BodySpec::new(Vector([5.0, y]), Vector([-1.0, 0.0]), 0.5));
    }
    let top = 2.0 + 2.0 * k as f64 + 4.0;
    // Four bodies converging on (10, top − 4), each 2 away at speed 1: the two opposite
    // pairs touch at the same instant by symmetry.
    for (p, v) in [
        ([10.0, top - 2.0], [0.0, -1.0]),
        ([10.0, top - 6.0], [0.0, 1.0]),
        ([8.0, top - 4.0], [1.0, 0.0]),
        ([12.0, top - 4.0], [-1.0, 0.0]),
    ] {
        bodies.push(BodySpec::new(Vector(p), Vector(v), 0.5));
    }
    // Wall hits at t = 1: 1.5 from the right wall moving right at 1.
    bodies.push(BodySpec::new(Vector([18.5, 3.0]), Vector([1.0, 0.0]), 0.5));
    bodies.push(BodySpec::new(Vector([18.5, 5.0]), Vector([1.0, 0.0]), 0.5));
    Scene {
        bodies,
        walls: box_walls(Vector([20.0, top + 2.0])),
        ..Scene::default()
    }
}

/// Exactly tied events: in the left half of a 20 × 10 box, five bodies bounce vertically in
/// step between floor and ceiling; in the right half, behind a dividing wall, four rows of two
/// bodies bounce off each other and the side walls in step. Positions, radii and speeds are
/// binary fractions, so tied events are truly equal and only the tie-break (kind, a, b) orders
/// them.
fn tie_scene() -> Scene<2> {
    let mut bodies = Vec::new();
    for k in 0..5 {
        let up = if k % 2 == 0 { 1.0 } else { -1.0 };
        bodies.push(BodySpec::new(
            Vector([1.0 + 2.0 * k as f64, 5.0]),
            Vector([0.0, up]),
            0.5,
        ));
    }
    for row in 0..4 {
        let y = 1.5 + 2.0 * row as f64;
        bodies.push(BodySpec::new(Vector([13.0, y]), Vector([1.0, 0.0]), 0.5));
        bodies.push(BodySpec::new(Vector([17.0, y]), Vector([-1.0, 0.0]), 0.5));
    }
    let mut walls = box_walls(Vector([20.0, 10.0]));
    walls.push(Wall::Segment {
        a: Vector([10.0, 0.0]),
        b: Vector([10.0, 10.0]),
    });
    Scene {
        bodies,
        walls,
        ..Scene::default()
    }
}

/// A square lattice of bodies at twice their radius apart with axis-aligned velocities: many
/// collisions at identical times, and bodies exactly on grid lines.
fn lattice_scene() -> Scene<2> {
    let mut bodies = Vec::new();
    for x in 0..8 {
        for y in 0..8 {
            let v = match (x + y) % 4 {
                0 => [1.0, 0.0],
                1 => [0.0, 1.0],
                2 => [-1.0, 0.0],
                _ => [0.0, -1.0],
            };
            bodies.push(BodySpec::new(
                Vector([1.0 + 2.0 * x as f64, 1.0 + 2.0 * y as f64]),
                Vector(v),
                0.5,
            ));
        }
    }
    Scene {
        bodies,
        walls: box_walls(Vector([16.0, 16.0])),
        ..Scene::default()
    }
}

/// Events of the all-pairs run of `scene` (up to `max_events`) that share their time with the
/// event before: a tie test is only meaningful if ties really happen.
fn tied_events(scene: &Scene<2>, max_events: u64) -> u64 {
    let mut sim = Simulation::new(scene, "all-pairs").expect("valid scene");
    let (mut ties, mut last) = (0, f64::NAN);
    sim.run_events_with(max_events, |c| {
        if c.event.time == last {
            ties += 1;
        }
        last = c.event.time;
    });
    ties
}

/// Newton's cradle: five equal balls in a touching row; ball 0 comes in at speed 1
/// (`incoming` balls moving, the rest at rest), optionally in a box.
fn cradle<const D: usize>(incoming: usize, walls: bool) -> Scene<D> {
    let mut bodies = Vec::new();
    for k in 0..5 {
        let mut p = Vector::<D>::splat(2.0);
        let mut v = Vector::<D>::ZERO;
        p[0] = 10.0 + k as f64;
        if k < incoming {
            p[0] -= 4.0;
            v[0] = 1.0;
        }
        bodies.push(BodySpec::new(p, v, 0.5));
    }
    let mut size = Vector::<D>::splat(4.0);
    size[0] = 20.0;
    Scene {
        bodies,
        walls: if walls { box_walls(size) } else { Vec::new() },
        ..Scene::default()
    }
}

#[test]
fn no_bodies_and_one_body() {
    let walled = Scene::<2> {
        walls: box_walls(Vector([4.0, 3.0])),
        ..Scene::default()
    };
    assert_eq!(check_all("no bodies, walls", &walled, 10), 0);
    assert_eq!(
        check_all("no bodies, no walls", &Scene::<3>::default(), 10),
        0
    );
    let one = |walls| Scene::<2> {
        bodies: vec![BodySpec::new(Vector([1.0, 1.0]), Vector([0.7, -0.3]), 0.25)],
        walls,
        ..Scene::default()
    };
    assert_eq!(
        check_all("one body, walls", &one(box_walls(Vector([4.0, 3.0]))), 200),
        200
    );
    assert_eq!(check_all("one body, no walls", &one(Vec::new()), 10), 0);
    let one3 = Scene::<3> {
        bodies: vec![BodySpec::new(
            Vector([1.0, 2.0, 1.5]),
            Vector([0.7, -0.3, 1.1]),
            0.5,
        )],
        walls: box_walls(Vector([3.0, 4.0, 5.0])),
        ..Scene::default()
    };
    assert_eq!(check_all("one body 3D, walls", &one3, 200), 200);
}

#[test]
fn everything_at_rest() {
    assert_eq!(
        check_all(
            "at rest 2D",
            &at_rest(gas_scene::<2>(200, 0.4, (0.2, 1.0), 3)),
            10
        ),
        0
    );
    assert_eq!(
        check_all(
            "at rest 3D",
            &at_rest(gas_scene::<3>(100, 0.2, (0.5, 0.5), 3)),
            10
        ),
        0
    );
}

#[test]
fn no_walls_runs_until_bodies_fly_apart() {
    for &seed in &SMALL_SEEDS {
        let s2 = without_walls(gas_scene::<2>(80, 0.4, (0.2, 1.0), seed));
        let events = check_all("open 2D", &s2, 50_000);
        assert!((1..50_000).contains(&events), "{events}");
        let s3 = without_walls(gas_scene::<3>(60, 0.25, (0.5, 0.5), seed));
        let events = check_all("open 3D", &s3, 50_000);
        assert!((1..50_000).contains(&events), "{events}");
    }
}

#[test]
fn simultaneous_collisions() {
    for k in [1, 2, 7, 16] {
        let scene = simultaneous_2d(k);
        check_all(&format!("simultaneous k={k}"), &scene, 400);
    }
    // 3D: pairs along each axis meeting at t = 1, in rows that never overlap.
    let mut bodies = Vec::new();
    for axis in 0..3 {
        for s in 0..3 {
            let mut a = Vector([3.0 + 5.0 * s as f64, 3.0 + 6.0 * axis as f64, 5.0]);
            if axis == 2 {
                a[2] = 2.0;
            }
            let mut v = Vector::<3>::ZERO;
            v[axis] = 1.0;
            let mut b = a;
            b[axis] += 3.0;
            bodies.push(BodySpec::new(a, v, 0.5));
            bodies.push(BodySpec::new(b, -v, 0.5));
        }
    }
    let scene = Scene::<3> {
        bodies,
        walls: box_walls(Vector([20.0, 20.0, 10.0])),
        ..Scene::default()
    };
    check_all("simultaneous 3D", &scene, 400);
}

#[test]
fn touching_bodies() {
    // Rows of touching balls, every other row pushed together (contact at once, t = now),
    // the others at rest or separating.
    let mut bodies = Vec::new();
    for row in 0..6 {
        for k in 0..6 {
            let x = 2.0 + k as f64;
            let y = 2.0 + 2.0 * row as f64;
            let v = match row % 3 {
                0 => [if k % 2 == 0 { 0.5 } else { -0.5 }, 0.0],
                1 => [0.0, 0.0],
                _ => [if k % 2 == 0 { -0.25 } else { 0.25 }, 0.125],
            };
            bodies.push(BodySpec::new(Vector([x, y]), Vector(v), 0.5));
        }
    }
    // A ball touching a wall and moving into it.
    bodies.push(BodySpec::new(Vector([0.5, 15.0]), Vector([-1.0, 0.0]), 0.5));
    let scene = Scene::<2> {
        bodies,
        walls: box_walls(Vector([12.0, 16.0])),
        ..Scene::default()
    };
    check_all("touching 2D", &scene, 1500);
    let cube = |i: usize| (i % 3) as f64 + 1.0;
    let bodies3 = (0..27)
        .map(|i| {
            let p = Vector([cube(i), cube(i / 3), cube(i / 9)]);
            let v = Vector([
                0.25 - 0.125 * (i % 4) as f64,
                0.0,
                0.125 * (i % 3) as f64 - 0.125,
            ]);
            BodySpec::new(p, v, 0.5)
        })
        .collect();
    let scene3 = Scene::<3> {
        bodies: bodies3,
        walls: box_walls(Vector([6.0, 6.0, 6.0])),
        ..Scene::default()
    };
    check_all("touching 3D", &scene3, 1500);
}

#[test]
fn exact_ties_resolve_in_the_oracle_order() {
    let ties = tie_scene();
    assert!(tied_events(&ties, 600) > 300);
    assert_eq!(check_all("ties", &ties, 600), 600);
    let lattice = lattice_scene();
    let lattice_ties = tied_events(&lattice, 3000);
    // The first waves of collisions tie (73 of the first 3000 events); later ones drift apart.
    assert!(lattice_ties > 50, "{lattice_ties} ties");
    assert_eq!(check_all("lattice", &lattice, 3000), 3000);
}

#[test]
fn memory_reports_are_consistent() {
    let scene: Scene<2> = gas_scene(200, 0.3, (0.2, 1.0), 4);
    for name in finders() {
        let mut sim = Simulation::new(&scene, name).expect("finder");
        sim.run_events(1000);
        let (finder, _) = sim.finder_mut();
        assert_eq!(finder.name(), name);
        if let Some(mem) = finder.memory() {
            assert!(
                mem.peak_bytes >= mem.bytes && mem.bytes > 0,
                "{name}: {mem:?}"
            );
        }
    }
}

#[test]
fn newtons_cradle() {
    for incoming in [1, 2] {
        assert!(check_all("cradle 2D box", &cradle::<2>(incoming, true), 600) == 600);
        assert!(check_all("cradle 3D box", &cradle::<3>(incoming, true), 600) == 600);
        let open = check_all("cradle 2D open", &cradle::<2>(incoming, false), 600);
        assert!((4..600).contains(&open), "{open}");
        check_all("cradle 3D open", &cradle::<3>(incoming, false), 600);
    }
}

#[test]
fn billiard_break() {
    for offset in [0.0, 0.002, -0.0137] {
        let scene = rack(&RackConfig {
            offset,
            ..RackConfig::default()
        });
        check_all(&format!("rack offset={offset}"), &scene, 3000);
    }
}

/// The thesis's table with each side cut into many collinear segments (hundreds of walls;
/// bodies reaching a joint touch two walls at once, a tie the wall indices decide).
#[test]
fn tables_of_many_walls() {
    for (n, pieces, seed) in [(64, 100, 1), (200, 40, 2), (30, 250, 3)] {
        let cfg = ThesisConfig {
            wall_pieces: pieces,
            ..ThesisConfig::new(n, seed)
        };
        let scene = thesis::<2>(&cfg).expect("thesis table");
        assert_eq!(scene.walls.len(), 4 * pieces);
        let label = format!("thesis table n={n}, {} walls", 4 * pieces);
        assert_eq!(check_all(&label, &scene, 1200), 1200, "{label}");
    }
}

/// Pairs passing each other with a perpendicular offset within a hair of the contact
/// distance, from differing reference times: the cases where rounding matters most.
#[test]
fn grazing_contacts() {
    let mut bodies = Vec::new();
    let rels = [-1e-6, -1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9, 1e-6];
    for (k, rel) in rels.iter().enumerate() {
        for (m, speed) in [0.3, 1.0, 7.0].iter().enumerate() {
            let y = 3.0 + 3.0 * (k * 3 + m) as f64;
            let r = 0.5 + 0.1 * m as f64;
            let offset = 2.0 * r * (1.0 + rel);
            bodies.push(BodySpec::new(Vector([3.0, y]), Vector([*speed, 0.0]), r));
            bodies.push(BodySpec::new(
                Vector([3.0 + 20.0 * speed / 7.0, y + offset]),
                Vector([-speed, 0.0]),
                r,
            ));
        }
    }
    let h = 3.0 + 3.0 * (rels.len() * 3) as f64 + 3.0;
    let scene = Scene::<2> {
        bodies,
        walls: box_walls(Vector([30.0, h])),
        ..Scene::default()
    };
    check_all("grazing", &scene, 2000);
}

#[test]
fn far_from_the_origin_and_late() {
    let shift = |s: Scene<2>, by: f64, t0: f64| Scene {
        bodies: s
            .bodies
            .into_iter()
            .map(|b| BodySpec {
                pos: b.pos + Vector([by, -by]),
                ..b
            })
            .collect(),
        walls: s
            .walls
            .into_iter()
            .map(|w| match w {
                Wall::Segment { a, b } => Wall::Segment {
                    a: a + Vector([by, -by]),
                    b: b + Vector([by, -by]),
                },
                p => p,
            })
            .collect(),
        start_time: t0,
        ..s
    };
    let base = gas_scene::<2>(100, 0.3, (0.2, 1.0), SMALL_SEEDS[1]);
    check_all("shifted 1e4, t0 1e5", &shift(base.clone(), 1e4, 1e5), 800);
    // As far out as f64 resolves bodies of radius 0.2 (see `ccdsim::resolution`): about
    // 2·10⁶ r = 4·10⁵ m. Further out, at 3·10⁶ m, positions round to 4.7·10⁻¹⁰ m, more than
    // 10⁻⁹ of a contact distance of 0.4 m, and the scene is refused.
    check_all(
        "shifted -3e5, t0 -7e3",
        &shift(base.clone(), -3e5, -7e3),
        800,
    );
    assert!(matches!(
        shift(base, -3e6, -7e3).validate(),
        Err(SceneError::Resolution { .. })
    ));
}

#[test]
fn inelastic_dense() {
    for restitution in [0.0, 0.3, 0.9] {
        let s2 = Scene {
            settings: Settings {
                restitution,
                ..Settings::default()
            },
            ..gas_scene::<2>(150, 0.45, (0.5, 0.5), SMALL_SEEDS[2])
        };
        check_all(&format!("inelastic e={restitution} 2D"), &s2, 1500);
        let s3 = Scene {
            settings: Settings {
                restitution,
                ..Settings::default()
            },
            ..gas_scene::<3>(100, 0.3, (0.2, 1.0), SMALL_SEEDS[2])
        };
        check_all(&format!("inelastic e={restitution} 3D"), &s3, 1500);
    }
}

#[test]
fn thermostatted_gases() {
    // Andersen resets interleaved with collisions, checked against the oracle before every
    // step; run files (resets included) byte-identical across finders.
    let thermostat = Some(ccdsim::thermostat::Thermostat {
        temperature: 1.5,
        rate: 0.3,
        seed: 21,
    });
    for (k, &seed) in SMALL_SEEDS.iter().take(3).enumerate() {
        // Walls, a periodic box, and an open world (the bodies would fly apart for ever but
        // for the resets).
        let (mut s2, mut s3) = (
            any_gas::<2>(120, 0.4, (0.3, 0.6), seed, k == 1),
            any_gas::<3>(100, 0.3, (0.5, 0.5), seed, k == 1),
        );
        if k == 2 {
            s2 = without_walls(s2);
            s3 = without_walls(s3);
        }
        s2.settings.thermostat = thermostat;
        s3.settings.thermostat = thermostat;
        check_all(&format!("thermostat 2D seed {seed}"), &s2, 2000);
        check_all(&format!("thermostat 3D seed {seed}"), &s3, 2000);
    }
}

/// A proptest case found in CI: a heavy ball bouncing between two walls with restitution 0.11
/// slows down by a factor of about 9 per bounce, so after 170 events the clock is near 10¹⁶²
/// and speeds near 10⁻¹⁶¹; a light ball rests in its way.
#[test]
fn inelastic_collapse_to_huge_times() {
    let body =
        |pos: [f64; 2], vel: [f64; 2], radius: f64| BodySpec::new(Vector(pos), Vector(vel), radius);
    let corner = |x: f64, y: f64| Vector([x, y]);
    let scene = Scene::<2> {
        settings: Settings {
            restitution: 0.11307834162367694,
            ..Settings::default()
        },
        bodies: vec![
            body([2.0, 2.0], [0.0, 0.0], 0.05),
            body([5.0, 2.0], [0.0, -0.8133087383228662], 0.7800648306522086),
        ],
        walls: vec![
            Wall::Segment {
                a: corner(0.0, 0.0),
                b: corner(7.0, 0.0),
            },
            Wall::Segment {
                a: corner(7.0, 0.0),
                b: corner(7.0, 7.0),
            },
            Wall::Segment {
                a: corner(7.0, 7.0),
                b: corner(0.0, 7.0),
            },
            Wall::Segment {
                a: corner(0.0, 7.0),
                b: corner(0.0, 0.0),
            },
        ],
        ..Scene::default()
    };
    check_all("inelastic collapse", &scene, 300);
}

/// A proptest case found in CI: a ball bouncing between two walls with restitution 0.017
/// slows down by a factor of about 58 per bounce until its next contact time overflows to
/// infinity. A contact at an infinite time never happens (`finite_event`): every finder
/// stops there, where resolving it used to give later predictions undefined times.
#[test]
fn inelastic_collapse_to_infinite_time() {
    let e = 0.01733112181355497;
    let s3 = Scene::<3> {
        settings: Settings {
            restitution: e,
            ..Settings::default()
        },
        bodies: vec![BodySpec::new(
            Vector([2.0, 2.0, 2.0]),
            Vector([0.0, 0.0, 2.8198125128649347]),
            0.05,
        )],
        walls: box_walls(Vector([4.0, 4.0, 4.0])),
        ..Scene::default()
    };
    let s2 = Scene::<2> {
        settings: Settings {
            restitution: e,
            ..Settings::default()
        },
        bodies: vec![BodySpec::new(
            Vector([2.0, 2.0]),
            Vector([0.0, 2.8198125128649347]),
            0.05,
        )],
        walls: box_walls(Vector([4.0, 4.0])),
        ..Scene::default()
    };
    let n3 = check_all("collapse to infinity 3D", &s3, 1000);
    let n2 = check_all("collapse to infinity 2D", &s2, 1000);
    for n in [n3, n2] {
        assert!((100..1000).contains(&n), "{n} events: the run must end");
    }
    let mut sim = Simulation::new(&s3, "cells").unwrap();
    assert_eq!(sim.run_events(1000), n3);
    assert!(sim.time().is_finite() && sim.peek_event().is_none());
}

//! Uniform gravity: peg boards, edits and frames, restitution and the TC model, growing radii,
//! kinematic bodies, moving walls, and rods (3D segments).

use super::*;

/// [`check_all`], and the oracle's run file passes verify.
fn check_all_verified<const D: usize>(label: &str, scene: &Scene<D>, max_events: u64) {
    verifies(label, scene, &check_all_run(label, scene, max_events));
}

/// `scene` (a 3D gas in a walled box) with rods (segment walls) across it: level ones along
/// the first and second axes, one tilted corner to corner, one along the last axis, a short
/// one whose end points are met often, and, with `moving`, a level rod translating across the
/// box; bodies touching a rod are left out.
fn with_rods(mut scene: Scene<3>, moving: bool) -> Scene<3> {
    let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).expect("a walled scene");
    let at = |f: [f64; 3]| Vector(std::array::from_fn(|d| lo[d] + f[d] * (hi[d] - lo[d])));
    let rod = |a: [f64; 3], b: [f64; 3]| Wall::Segment { a: at(a), b: at(b) };
    let rods = [
        rod([0.2, 0.5, 0.35], [0.8, 0.5, 0.35]),
        rod([0.5, 0.15, 0.6], [0.5, 0.7, 0.6]),
        rod([0.1, 0.1, 0.2], [0.9, 0.9, 0.8]),
        rod([0.3, 0.75, 0.1], [0.3, 0.75, 0.9]),
        rod([0.6, 0.3, 0.45], [0.75, 0.35, 0.5]),
    ];
    scene.walls.extend(rods);
    if moving {
        let mut velocity = Vector::ZERO;
        velocity[1] = 0.6;
        scene.moving_walls.push(ccdsim::MovingWall {
            wall: rod([0.15, 0.2, 0.5], [0.85, 0.2, 0.5]),
            velocity,
        });
    }
    let moving_walls: Vec<_> = scene.moving_walls.iter().map(|m| m.wall).collect();
    scene.bodies.retain(|b| {
        scene
            .walls
            .iter()
            .chain(&moving_walls)
            .all(|w| ccdsim::wall::wall_clearance(w, b.pos) > b.radius)
    });
    scene
}

/// How many collisions with a rod (a static or moving segment) a 3D run file of `scene` holds.
fn rod_hits(scene: &Scene<3>, run: &Recorded) -> usize {
    let mut r =
        ccdsim::record::RunReader::<_, 3>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    let walls: Vec<_> = (scene.walls.iter().copied())
        .chain(scene.moving_walls.iter().map(|m| m.wall))
        .collect();
    events
        .iter()
        .filter(|c| c.event.kind == EventKind::Wall)
        .filter(|c| matches!(walls.get(c.event.b as usize), Some(Wall::Segment { .. })))
        .count()
}

#[test]
fn gravity() {
    // Parabolic motion: pairs through the falling pair function, walls through the plane's
    // quadratic and the segments' slab entries and end-point quartics, cells crossings by
    // the face roots, bvh boxes around parabolic arcs; against the oracle before every step
    // and with byte-identical run files.
    for (k, &seed) in SMALL_SEEDS.iter().enumerate() {
        let g2 = [[0.0, -9.81], [0.3, -1.0], [-2.0, 0.0]][k];
        let g3 = [[0.0, 0.0, -9.81], [0.5, -1.0, 2.0], [0.0, -0.2, 0.0]][k];
        for (disp, radii) in DISPERSITIES {
            let s2 = falling(gas_scene::<2>(100, 0.3, radii, seed), g2);
            let s3 = falling(gas_scene::<3>(70, 0.15, radii, seed), g3);
            check_all(&format!("gravity {disp} 2D seed {seed}"), &s2, 2000);
            check_all(&format!("gravity {disp} 3D seed {seed}"), &s3, 1500);
        }
        let open = falling(without_walls(gas_scene::<2>(40, 0.2, (0.3, 0.6), seed)), g2);
        check_all(&format!("gravity open 2D seed {seed}"), &open, 600);
        let board = peg_board(4, 24, seed);
        check_all(&format!("peg board seed {seed}"), &board, 1500);
    }
}

#[test]
fn gravity_with_edits_frames_and_restitution() {
    let mut s2 = falling(
        gas_scene::<2>(90, 0.3, (0.2, 0.6), SMALL_SEEDS[0]),
        [0.0, -3.0],
    );
    s2.settings.restitution = 0.9;
    let s3 = falling(
        gas_scene::<3>(60, 0.15, (0.3, 0.5), SMALL_SEEDS[1]),
        [0.0, -2.0, 0.0],
    );
    let o = FinderOptions::default();
    for drive in [Drive::Kicks { every: 9 }, Drive::Frames { dt: 1.0 / 60.0 }] {
        let (o2, o3) = (
            reference("gravity edits 2D", &s2, 1200, drive),
            reference("gravity edits 3D", &s3, 1000, drive),
        );
        for name in finders() {
            check_run("gravity edits 2D", &s2, name, &o, 1200, drive, &o2);
            check_run("gravity edits 3D", &s3, name, &o, 1000, drive, &o3);
        }
    }
    let board = peg_board(5, 32, 7);
    let oracle = reference("peg board frames", &board, 2000, Drive::Frames { dt: 0.02 });
    for name in finders() {
        check_run(
            "peg board frames",
            &board,
            name,
            &o,
            2000,
            Drive::Frames { dt: 0.02 },
            &oracle,
        );
    }
}

#[test]
fn inelastic_gravity_with_the_tc_model_and_per_body_restitution() {
    // Bounces die away and then stay at the TC model's elastic limit; restitution differs
    // body by body (pairs take the mean).
    let mut board = peg_board(5, 40, 11);
    board.settings.restitution = 0.7;
    board.settings.tc = Some(1e-3);
    for (k, b) in board.bodies.iter_mut().enumerate() {
        b.restitution = Some([0.2, 0.9, 1.0, 0.5][k % 4]);
    }
    check_all("inelastic peg board", &board, 3000);
    let mut s3 = falling(
        gas_scene::<3>(60, 0.2, (0.3, 0.5), SMALL_SEEDS[2]),
        [0.0, 0.0, -9.81],
    );
    s3.settings.restitution = 0.6;
    s3.settings.tc = Some(1e-4);
    check_all("inelastic gravity 3D", &s3, 3000);
}

#[test]
fn gravity_with_growing_radii() {
    // Sedimented packings: bodies fall on parabolas while their radii grow. Pairs through
    // growth's quadratic from the later reference time, planes through the growing gap's
    // quadratic, segments through the growing slab's entries and the end points' growing
    // quartic; cells crossings by the face roots and grids rebuilt at growth horizons, bvh
    // boxes around parabolic arcs at the grown radii. Against the oracle before every step,
    // run files byte-identical across finders and passing verify.
    for (k, &seed) in SMALL_SEEDS.iter().enumerate() {
        let rate = [0.02, 0.1, 0.5][k];
        let g2 = [[0.0, -9.81], [0.3, -1.0], [-2.0, 0.0]][k];
        let g3 = [[0.0, 0.0, -9.81], [0.5, -1.0, 2.0], [0.0, -0.2, 0.0]][k];
        for (disp, radii) in DISPERSITIES {
            let s2 = growing(falling(gas_scene::<2>(100, 0.3, radii, seed), g2), rate);
            let s3 = growing(falling(gas_scene::<3>(70, 0.15, radii, seed), g3), rate);
            let label = format!("gravity growth {disp} 2D seed {seed}");
            check_all_verified(&label, &s2, 2000);
            let label = format!("gravity growth {disp} 3D seed {seed}");
            check_all_verified(&label, &s3, 1500);
        }
        let board = growing(peg_board(4, 24, seed), rate);
        let label = format!("gravity growth peg board seed {seed}");
        check_all_verified(&label, &board, 1500);
    }
}

#[test]
fn gravity_with_growing_radii_kinematic_inelastic_and_moving_walls() {
    // Kinematic bodies do not fall but grow (the quartic of a growing contact distance),
    // bounces lose energy (restitution below 1, the growth rule's e), and moving walls meet
    // falling, growing bodies in their frames; kicks and frames interleave.
    for (k, &seed) in SMALL_SEEDS[..2].iter().enumerate() {
        let rate = [0.05, 0.2][k];
        let kin2 = growing(
            falling(
                with_kinematic(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed), 4),
                [0.0, -9.81],
            ),
            rate,
        );
        let kin3 = growing(
            falling(
                with_kinematic(gas_scene::<3>(60, 0.15, (0.3, 0.5), seed), 3),
                [0.0, 0.0, -9.81],
            ),
            rate,
        );
        let board = growing(with_kinematic(peg_board(4, 24, seed), 2), rate);
        let inel2 = growing(
            inelastic(
                falling(gas_scene::<2>(100, 0.3, (0.2, 1.0), seed), [0.0, -4.0]),
                None,
            ),
            rate,
        );
        let walls2 = growing(
            falling(
                with_moving_walls(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed)),
                [0.0, -3.0],
            ),
            rate,
        );
        let walls3 = growing(
            falling(
                with_moving_walls(gas_scene::<3>(50, 0.15, (0.5, 0.5), seed)),
                [0.0, 0.0, -3.0],
            ),
            rate,
        );
        for drive in [
            Drive::Events,
            Drive::Kicks { every: 7 },
            Drive::FrameWalls { dt: 0.05 },
        ] {
            for (label, scene, events) in [
                ("gravity growth kinematic 2D", &kin2, 1500),
                ("gravity growth kinematic peg board", &board, 1500),
                ("gravity growth inelastic 2D", &inel2, 2000),
                ("gravity growth moving walls 2D", &walls2, 1200),
            ] {
                let label = format!("{label} seed {seed} {drive:?}");
                let oracle = check_all_driven(&label, scene, events, drive);
                verifies(&label, scene, &oracle);
            }
            let label = format!("gravity growth kinematic 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &kin3, 1200, drive);
            verifies(&label, &kin3, &oracle);
            let label = format!("gravity growth moving walls 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &walls3, 1000, drive);
            verifies(&label, &walls3, &oracle);
        }
    }
}

#[test]
fn rods_under_gravity() {
    // Segment walls in 3D under gravity: the rods' sides (the quartic of the motion across
    // each rod, every entry into its cylinder a candidate), their end caps, a rod along
    // gravity (straight across it) and a moving rod steered frame by frame; elastic, and
    // inelastic with bodies resting on the floor (rods hold none: they bounce there); and with
    // growing radii (the side's and end points' quartics against the growing radius), static
    // and moving. Every finder and cells mode writes the oracle's run file, whose runs verify,
    // and rods are hit.
    for (k, &seed) in SMALL_SEEDS.iter().enumerate() {
        let g = [[0.0, 0.0, -9.81], [0.8, -0.5, -9.81], [0.0, -3.0, 0.0]][k];
        let base = gas_scene::<3>(60, 0.1, (0.3, 0.6), seed);
        let fixed = falling(with_rods(base.clone(), false), g);
        let moving = falling(with_rods(base.clone(), true), g);
        // With the TC model, so that no bounces die away on a rod (which halts the run, see
        // `tests/rods.rs`) and the runs go on.
        let mut inelastic = resting(with_rods(base, false), g);
        inelastic.settings.tc = Some(1e-3);
        let rate = [0.05, 0.2, 0.1][k];
        let (fixed_growing, moving_growing) =
            (growing(fixed.clone(), rate), growing(moving.clone(), rate));
        let runs = [
            ("static", &fixed, Drive::Events),
            ("static kicks", &fixed, Drive::Kicks { every: 37 }),
            ("moving", &moving, Drive::Events),
            ("moving frames", &moving, Drive::FrameWalls { dt: 0.05 }),
            ("inelastic resting", &inelastic, Drive::Events),
            ("growing", &fixed_growing, Drive::Events),
            (
                "growing moving frames",
                &moving_growing,
                Drive::FrameWalls { dt: 0.05 },
            ),
        ];
        for (what, scene, drive) in runs {
            let label = format!("rods {what} seed {seed} g {g:?}");
            let oracle = check_all_driven(&label, scene, 1500, drive);
            verifies(&label, scene, &oracle);
            let hits = rod_hits(scene, &oracle);
            assert!(hits >= 10, "{label}: {hits} rod hits");
        }
    }
}

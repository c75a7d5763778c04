//! Sheared periodic boxes (Lees–Edwards): every finder that serves them gives the oracle's
//! run file byte for byte — gases in and out of the imposed flow, both signs of the rate,
//! bodies at rest that only the sliding layers bring together, integer coordinates on cell
//! faces, pairs touching across the sheared face, boxes too short for three cells, with a
//! thermostat, inelastic, rough and kinematic bodies, kicks and frames — and `verify` accepts
//! the oracle's runs.

use super::*;

/// `scene` sheared at `rate`; with `in_flow`, each body's velocity gets the imposed flow
/// `γ̇ (y − L_y/2)` where it starts.
fn sheared<const D: usize>(mut scene: Scene<D>, rate: f64, in_flow: bool) -> Scene<D> {
    scene.settings.shear_rate = Some(rate);
    let ly = scene.periodic.expect("a periodic scene")[1];
    if in_flow {
        for b in &mut scene.bodies {
            b.vel[0] += rate * (b.pos[1] - 0.5 * ly);
        }
    }
    scene
}

/// How many of a run's body collisions meet across the sheared (y) faces.
fn across_the_faces<const D: usize>(scene: &Scene<D>, run: &Recorded) -> usize {
    let ly = scene.periodic.expect("periodic")[1];
    let mut r =
        ccdsim::record::RunReader::<_, D>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    events
        .iter()
        .filter(|c| c.event.kind == EventKind::Body && (c.pos[1][1] - c.pos[0][1]).abs() > 0.5 * ly)
        .count()
}

/// Runs the sheared `scene` through every finder, driven by `drive`, and verifies the oracle's
/// run; returns that run.
fn check_sheared<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    max_events: u64,
    drive: Drive,
) -> Recorded {
    let oracle = check_all_driven(label, scene, max_events, drive);
    verifies(label, scene, &oracle);
    oracle
}

fn check_sheared_gases<const D: usize>(ns: &[usize]) {
    let mut across = 0;
    for (k, &n) in ns.iter().enumerate() {
        let seed = SMALL_SEEDS[k % SMALL_SEEDS.len()];
        for (rate, in_flow) in [(0.3, true), (-1.5, false), (4.0, true)] {
            let scene = sheared(periodic_gas::<D>(n, 0.3, (0.3, 0.6), seed), rate, in_flow);
            let events = (EVENTS_PER_BODY * n as u64).min(MAX_EVENTS);
            let label = format!("sheared gas n={n} rate {rate} seed={seed}");
            let run = check_sheared(&label, &scene, events, Drive::Events);
            across += across_the_faces(&scene, &run);
        }
    }
    assert!(
        across > 50,
        "only {across} collisions across the sheared faces"
    );
}

#[test]
fn sheared_gases_2d() {
    check_sheared_gases::<2>(&[2, 5, 17, 64, 200]);
}

#[test]
fn sheared_gases_3d() {
    check_sheared_gases::<3>(&[2, 5, 17, 64, 150]);
}

/// Bodies at rest in rows on integer coordinates, on cell faces and on the box's faces: only
/// the sliding layers move anything at first; pairs touching across the sheared face; a box
/// too short for three cells; the same in 3D.
#[test]
fn sheared_lattices_at_rest_and_touching() {
    let b2 = |p: [f64; 2], v: [f64; 2]| BodySpec::new(Vector(p), Vector(v), 0.5);
    let mut rows = Vec::new();
    for x in 0..8 {
        rows.push(b2([x as f64 + 0.5, 0.0], [0.0, 0.0]));
        rows.push(b2([x as f64 + 0.5, 3.0], [0.0, 0.0]));
        if x % 2 == 0 {
            rows.push(b2([x as f64, 6.0], [0.0, 0.0]));
        }
    }
    let lattice = Scene::<2> {
        bodies: rows,
        periodic: Some(Vector([8.0, 7.0])),
        ..Scene::default()
    };
    // Touching across the top face at t = 0 and approaching; one pair of discs stacked on
    // the face at rest.
    let touching = Scene::<2> {
        bodies: vec![
            b2([2.0, 0.5], [0.0, -1.0]),
            b2([2.0, 9.5], [0.0, 1.0]),
            b2([6.0, 0.0], [0.0, 0.0]),
            b2([7.0, 0.0], [0.0, 0.0]),
        ],
        periodic: Some(Vector([10.0, 10.0])),
        ..Scene::default()
    };
    let short = Scene::<2> {
        bodies: vec![b2([0.5, 0.5], [1.0, 0.25]), b2([1.75, 1.5], [-0.5, 0.0])],
        periodic: Some(Vector([2.5, 2.25])),
        ..Scene::default()
    };
    for (label, scene) in [
        ("lattice", &lattice),
        ("touching", &touching),
        ("short box", &short),
    ] {
        for rate in [1.0, -0.25] {
            let scene = sheared(scene.clone(), rate, false);
            scene.validate().unwrap();
            let run = check_sheared(
                &format!("sheared {label} rate {rate}"),
                &scene,
                400,
                Drive::Events,
            );
            assert!(run.events > 10, "{label}: {} events", run.events);
        }
    }
    let b3 = |p: [f64; 3], v: [f64; 3]| BodySpec::new(Vector(p), Vector(v), 0.5);
    let mut bodies = Vec::new();
    for x in 0..4 {
        for z in 0..3 {
            bodies.push(b3([x as f64 * 1.5, 0.0, z as f64 * 1.5], [0.0, 0.0, 0.0]));
            bodies.push(b3(
                [x as f64 * 1.5 + 0.75, 4.0, z as f64 * 1.5],
                [0.0, 0.25, 0.0],
            ));
        }
    }
    let scene3 = sheared(
        Scene::<3> {
            bodies,
            periodic: Some(Vector([6.0, 5.0, 4.5])),
            ..Scene::default()
        },
        0.5,
        false,
    );
    scene3.validate().unwrap();
    let run = check_sheared("sheared 3D lattice", &scene3, 600, Drive::Events);
    assert!(run.events > 10, "{}", run.events);
}

/// Shear with every feature a periodic box takes: a thermostat (resets around the flow),
/// inelastic collisions with the TC model, rough bodies, kinematic bodies, kicks and frames.
#[test]
fn sheared_with_every_feature() {
    let base2 = sheared(
        periodic_gas::<2>(60, 0.3, (0.3, 0.6), SMALL_SEEDS[1]),
        0.8,
        true,
    );
    let base3 = sheared(
        periodic_gas::<3>(50, 0.25, (0.3, 0.6), SMALL_SEEDS[2]),
        -0.6,
        true,
    );
    let thermostat = Some(ccdsim::thermostat::Thermostat {
        temperature: 1.0,
        rate: 0.5,
        seed: 5,
    });
    let mut warm2 = base2.clone();
    warm2.settings.thermostat = thermostat;
    let mut warm3 = base3.clone();
    warm3.settings.thermostat = thermostat;
    check_sheared("sheared thermostat 2D", &warm2, 800, Drive::Events);
    check_sheared("sheared thermostat 3D", &warm3, 800, Drive::Events);
    check_sheared(
        "sheared inelastic 2D",
        &inelastic(base2.clone(), Some(1e-3)),
        800,
        Drive::Events,
    );
    check_sheared(
        "sheared inelastic 3D",
        &inelastic(base3.clone(), Some(1e-3)),
        800,
        Drive::Events,
    );
    let mut rough2 = base2.clone();
    rough2.settings.tangential_restitution = Some(0.5);
    let mut rough3 = base3.clone();
    rough3.settings.tangential_restitution = Some(0.5);
    check_sheared("sheared rough 2D", &rough2, 800, Drive::Events);
    check_sheared("sheared rough 3D", &rough3, 800, Drive::Events);
    check_sheared(
        "sheared kinematic 2D",
        &with_kinematic(base2.clone(), 3),
        600,
        Drive::Events,
    );
    for drive in [Drive::Kicks { every: 5 }, Drive::Frames { dt: 0.21 }] {
        check_sheared("sheared, steered 2D", &base2, 600, drive);
        check_sheared("sheared, steered 3D", &base3, 600, drive);
    }
}

/// `verify` holds a run to the shear of its scene: the run of the same gas without shear,
/// checked against the sheared scene, fails (its bodies pass through each other's images
/// across the sliding faces), and so does the sheared run checked against the scene without.
#[test]
fn verify_tells_a_sheared_run_from_an_unsheared_one() {
    for rate in [2.0, -2.0] {
        let flat = periodic_gas::<2>(80, 0.35, (0.3, 0.6), SMALL_SEEDS[0]);
        let shear = sheared(flat.clone(), rate, false);
        let unsheared_run = reference("unsheared", &flat, 1500, Drive::Events);
        let sheared_run = reference("sheared", &shear, 1500, Drive::Events);
        for (scene, run, what) in [
            (&shear, &unsheared_run, "an unsheared run as sheared"),
            (&flat, &sheared_run, "a sheared run as unsheared"),
        ] {
            let mut r = ccdsim::record::RunReader::<_, 2>::new(&run.bytes[..], "run".into())
                .expect("header");
            let (events, end) = r.read_events().expect("records");
            let mut v = ccdsim::verify::Verifier::new(scene);
            let failed = events.iter().any(|c| v.check(c).is_err())
                || v.finish(end.expect("an end")).is_err();
            assert!(failed, "verify accepts {what} (rate {rate})");
        }
    }
}

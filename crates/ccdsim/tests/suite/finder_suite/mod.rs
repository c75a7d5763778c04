//! The generic finder suite: every finder in [`FINDER_NAMES`] other than the all-pairs oracle
//! (so finders added later join automatically) is run through whole simulations, recorded,
//! and its run file must be byte-identical to that of a reference run of the same scene,
//! ending alike (the same halt, the same next event). The reference run, made once per scene
//! and shared by the finders, is checked on EVERY event against [`all_pairs_next_event`]
//! (with the moving walls' and turning bodies' events) on the same world, bit for bit, so it
//! is event for event the all-pairs run, and every finder's every event equals the oracle's.
//! When a finder's run differs, it is run again with that per-event check, which names the
//! first event that differs.
//!
//! Scenes: 2D and 3D gases with n from 1 to 500, monodisperse and polydisperse, dilute and
//! dense, several seeds; proptest-generated scenes; and degenerate ones (no bodies, one
//! body, no walls, everything at rest, simultaneous collisions, touching bodies, Newton's
//! cradle, the billiard break, exact ties, a lattice of equal bodies, grazing contacts, far
//! from the origin, inelastic, velocity kicks, frame-by-frame stepping, non-default finder
//! options); periodic boxes, thermostats and inelastic collapse; growing radii alone and with
//! moving walls, per-body restitution and kinematic bodies; gravity alone, with edits and
//! frames, the TC model, growing radii, and rods (3D segments); kinematic bodies, teleports,
//! collision filters, bodies added and removed, moving walls, resting, sliding and ledges.
//!
//! This file is the harness (recording runs, the per-event check, the drives that steer a
//! run, the gas generators); each kind of scene has a file of its own.

mod arrivals;
mod gases;
mod generated;
mod gravity;
mod growth;
mod periodic;
mod resting;
mod rough;
mod shear;
mod special_scenes;
mod steering;

use ccdsim::finder::{all_pairs_next_event, make_finder, FinderOptions, FINDER_NAMES};

use ccdsim::generate::{
    box_walls, gas, rack, thesis, GasConfig, GenerateError, RackConfig, ThesisConfig,
};

use ccdsim::record::RunWriter;

use ccdsim::{
    BodySpec, CollisionFilter, Event, EventKind, Halt, Scene, SceneError, Settings, Simulation,
    Vector, Wall,
};

use proptest::prelude::*;

/// Seeds of the small gases (n ≤ 64): each scene is run once per seed.
const SMALL_SEEDS: [u64; 3] = [1, 4242, 31_337];

/// Events checked per gas run: `EVENTS_PER_BODY · n`, at most `MAX_EVENTS`.
const EVENTS_PER_BODY: u64 = 30;

/// See `EVENTS_PER_BODY`.
const MAX_EVENTS: u64 = 1200;

/// Seed of the deterministic velocity kicks.
const KICK_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// Every finder under test: all but the oracle.
fn finders() -> Vec<&'static str> {
    let names: Vec<_> = FINDER_NAMES
        .iter()
        .copied()
        .filter(|&n| n != "all-pairs")
        .collect();
    assert!(!names.is_empty(), "no finder besides the oracle to test");
    names
}

/// Every finder under test with every mode its options select: each finder with the default
/// options, and `cells` also without neighbour lists (skin 0), with a small skin (many
/// rebuilds) and the largest (long lists). Lists are used in periodic worlds only.
fn variants() -> Vec<(&'static str, FinderOptions)> {
    let mut out = Vec::new();
    for name in finders() {
        out.push((name, FinderOptions::default()));
        if name == "cells" {
            for cells_skin in [0.0, 0.02, 1.0] {
                out.push((
                    name,
                    FinderOptions {
                        cells_skin: Some(cells_skin),
                        ..FinderOptions::default()
                    },
                ));
            }
        }
    }
    out
}

/// Panics unless `got` and `want` are the same event bit for bit.
#[track_caller]
fn assert_same(got: Option<Event>, want: Option<Event>, context: impl Fn() -> String) {
    let same = match (got, want) {
        (Some(g), Some(w)) => {
            g.time.to_bits() == w.time.to_bits() && g.kind == w.kind && g.a == w.a && g.b == w.b
        }
        (None, None) => true,
        _ => false,
    };
    assert!(
        same,
        "{}: finder said {got:?}, the oracle {want:?}",
        context()
    );
}

/// How a run is driven besides plain stepping.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drive {
    /// `step_event` until `max_events` or no event.
    Events,
    /// Every `every` events, give one body a new velocity with `set_velocity`.
    Kicks { every: u64 },
    /// Frames of `dt` seconds: resolve the events inside, then `run_until` the frame's end.
    Frames { dt: f64 },
    /// Every `every` events, bring the kinetic energy back to its start value by
    /// `rescale_velocities` (growing worlds heat up).
    Rescale { every: u64 },
    /// Every `every` events, move one body to a random spot inside the scene's bounds with
    /// `set_position` (refused spots, overlapping a body or a wall, are skipped alike in
    /// every run).
    Teleports { every: u64 },
    /// Every `every` events, give one body a random collision group and mask from
    /// [`FILTERS`] with `set_collision_filter` (refused ones, which would make overlapping
    /// bodies collide, are skipped alike in every run).
    Filters { every: u64 },
    /// Frames of `dt` seconds as [`Drive::Frames`], and at the end of each frame one body
    /// moved to a random spot (as [`Drive::Teleports`]): the finders have looked past the
    /// frame's end by then (to the next event), and must take back what they did there.
    FrameTeleports { dt: f64 },
    /// Every `every` events, add or remove a body ([`edit_slots`]).
    Slots { every: u64 },
    /// Frames of `dt` seconds as [`Drive::Frames`], and at the end of each frame a body
    /// added or removed (as [`Drive::Slots`]), after the finders looked past the frame.
    FrameSlots { dt: f64 },
    /// Frames of `dt` seconds as [`Drive::Frames`], and at the end of each frame every
    /// moving wall given a new velocity ([`steer_walls`]).
    FrameWalls { dt: f64 },
}

impl Drive {
    /// True for the drives whose runs record their edits (steered run files).
    fn steered(self) -> bool {
        matches!(
            self,
            Drive::Kicks { .. }
                | Drive::Rescale { .. }
                | Drive::Teleports { .. }
                | Drive::FrameTeleports { .. }
                | Drive::Filters { .. }
                | Drive::Slots { .. }
                | Drive::FrameSlots { .. }
                | Drive::FrameWalls { .. }
        )
    }
}

/// The collision filters random scenes and edits draw from: the default, groups that ignore
/// each other, a body in no group, and one that collides only with its own group.
const FILTERS: [CollisionFilter; 5] = [
    CollisionFilter::DEFAULT,
    CollisionFilter { group: 2, mask: !1 },
    CollisionFilter { group: 4, mask: !2 },
    CollisionFilter { group: 0, mask: 0 },
    CollisionFilter { group: 8, mask: 8 },
];

/// A recorded run: the run file's bytes, the number of events, and how it ended (the halt,
/// if any, and the next event it would take).
struct Recorded {
    bytes: Vec<u8>,
    events: u64,
    end: String,
}

/// Drives a simulation of `scene` with finder `name` for at most `max_events` events,
/// recording it. With `check`, asserts before each step that the finder's next event equals
/// [`all_pairs_next_event`] on the simulation's own world, bit for bit.
fn record_run<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    name: &str,
    options: &FinderOptions,
    max_events: u64,
    drive: Drive,
    check: bool,
) -> Recorded {
    let finder = make_finder::<D>(name, options).expect("finder");
    let mut sim = Simulation::with_finder(scene, finder).expect("valid scene");
    // Runs steered by velocity kicks and teleports record their edits too: the run files
    // then compare the edits as well, and the oracle's can be verified.
    // A scene's arrivals are recorded as the additions they are, in a steered run file too.
    let mut rec = if drive.steered() || !scene.arrivals.is_empty() {
        sim.record_edits(true);
        RunWriter::new_steered(Vec::new(), name.into(), scene).expect("header")
    } else {
        RunWriter::new(Vec::new(), name.into(), scene).expect("header")
    };
    let mut events = 0u64;
    let mut kick = KICK_SEED;
    let mut frame_end = scene.start_time;
    // `peek_event` gives up after this many box exits in a row without a collision (bodies
    // that never meet in a periodic box; see its docs).
    let exit_guard = 1024 + 64 * scene.bodies.len() as u64;
    while events < max_events {
        let exits_before = sim.stats().exits;
        let got = sim.peek_event();
        // Arrivals that came before this event.
        for edit in sim.take_edits() {
            rec.write_event(&edit).expect("write");
        }
        if check {
            let mut want = Event::earliest(
                Event::earliest(
                    all_pairs_next_event(sim.world()),
                    moving_wall_oracle(sim.world()),
                ),
                pivot_oracle(sim.world()),
            );
            let gave_up = got.is_none() && sim.stats().exits - exits_before == exit_guard;
            if gave_up
                && want
                    .is_some_and(|w| w.kind == EventKind::Wall && w.b as usize >= scene.walls.len())
            {
                // The oracle's next event is one more exit, which the simulation declined.
                want = None;
            }
            if let (None, Some(Halt::Resolution { time, .. })) = (got, sim.halt()) {
                // The simulation refused the oracle's next event because f64 no longer
                // resolves its bodies there: it must be that very event, and the run ends
                // (the run files, compared across finders, show it ends alike).
                assert!(
                    want.is_some_and(|w| w.time.to_bits() == time.to_bits()),
                    "{label} [{name}]: halted at {time} but the oracle's next event is {want:?}"
                );
                want = None;
            }
            if let (None, Some(Halt::Resting { time, body, wall })) = (got, sim.halt()) {
                // The same wall event came again after a collision that changed nothing: the
                // simulation stops there, and the oracle names that very event.
                assert_eq!(
                    want,
                    Some(Event::wall(time, body, wall)),
                    "{label} [{name}]"
                );
                want = None;
            }
            if let (None, Some(Halt::RestingOnBody { time, a, b })) = (got, sim.halt()) {
                // Two bodies pressed together without normal speed (see `resting`): the same.
                assert_eq!(want, Some(Event::body(time, a, b)), "{label} [{name}]");
                want = None;
            }
            if let (None, Some(Halt::ArrivalBlocked { time, .. })) = (got, sim.halt()) {
                // An arrival found its place taken: the run stopped at its time, after every
                // event before it.
                assert!(want.is_none_or(|w| w.time >= time), "{label} [{name}]");
                want = None;
            }
            if let (None, Some(Halt::InelasticCollapse { time, .. })) = (got, sim.halt()) {
                // An inelastic collapse (restitution below 1, no `settings.tc`): the run
                // stopped right after the collision that closed a body's window of collisions,
                // at this very time; the oracle's next event is not taken (the run files,
                // compared across finders, show it stops alike).
                assert_eq!(time.to_bits(), sim.time().to_bits(), "{label} [{name}]");
                want = None;
            }
            match got {
                // A thermostat reset comes from the simulation, not the finder: it must come
                // strictly before the oracle's next collision (a collision wins a tie).
                Some(r) if r.kind == EventKind::Reset => assert!(
                    want.is_none_or(|w| w.time > r.time),
                    "{label} [{name}]: reset at {} after the oracle's {want:?}",
                    r.time
                ),
                _ => assert_same(got, want, || {
                    format!(
                        "{label} [{name}, {D}D, {drive:?}] before event {events} at t = {}",
                        sim.time()
                    )
                }),
            }
        }
        if let Drive::Frames { dt }
        | Drive::FrameTeleports { dt }
        | Drive::FrameSlots { dt }
        | Drive::FrameWalls { dt } = drive
        {
            match got {
                None => break,
                Some(e) if e.time > frame_end => {
                    // Nothing left in this frame: move the clock to its end (no event is
                    // resolved unchecked) and start the next frame.
                    assert_eq!(sim.run_until(frame_end), 0);
                    frame_end += dt;
                    if let Drive::FrameTeleports { .. } = drive {
                        teleport_one(&mut sim, scene, &mut kick);
                    }
                    if let Drive::FrameSlots { .. } = drive {
                        edit_slots(&mut sim, scene, &mut kick);
                    }
                    if let Drive::FrameWalls { .. } = drive {
                        steer_walls(&mut sim, scene, &mut kick);
                    }
                    {
                        for edit in sim.take_edits() {
                            rec.write_event(&edit).expect("write");
                        }
                    }
                    continue;
                }
                Some(_) => {}
            }
        }
        let Some(c) = sim.step_event() else {
            break;
        };
        rec.write_event(&c).expect("write");
        events += 1;
        if let Drive::Kicks { every } = drive {
            if events % every == 0 {
                kick = kick
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let i = (kick >> 33) as usize % scene.bodies.len();
                let mut v = Vector::<D>::ZERO;
                for k in 0..D {
                    v[k] = ((kick >> (8 * k)) & 0xff) as f64 / 64.0 - 2.0;
                }
                sim.set_velocity(i, v).expect("kick");
            }
        }
        if let Drive::Teleports { every } = drive {
            if events % every == 0 {
                teleport_one(&mut sim, scene, &mut kick);
            }
        }
        if let Drive::Slots { every } = drive {
            if events % every == 0 {
                edit_slots(&mut sim, scene, &mut kick);
            }
        }
        if let Drive::Filters { every } = drive {
            if events % every == 0 {
                kick = kick
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let i = (kick >> 33) as usize % scene.bodies.len();
                let f = FILTERS[(kick >> 13) as usize % FILTERS.len()];
                let _ = sim.set_collision_filter(i, f);
            }
        }
        if let Drive::Rescale { every } = drive {
            if events % every == 0 {
                let k0 = sim.stats().kinetic_energy_start;
                let factor = (k0 / sim.world().kinetic_energy()).sqrt();
                sim.rescale_velocities(factor).expect("rescale");
            }
        }
        for edit in sim.take_edits() {
            rec.write_event(&edit).expect("write");
        }
    }
    let bytes = rec.finish(sim.time()).expect("finish");
    let next = sim
        .peek_event()
        .map(|e| (e.time.to_bits(), e.kind, e.a, e.b));
    Recorded {
        bytes,
        events,
        end: format!("halt {:?}, next event {next:?}", sim.halt()),
    }
}

/// Moves one body, drawn by the generator state `kick`, to a random spot inside the scene's
/// bounds (a refused spot, overlapping a body or a wall, changes nothing, alike in every run).
fn teleport_one<const D: usize>(sim: &mut Simulation<D>, scene: &Scene<D>, kick: &mut u64) {
    *kick = kick
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    let i = (*kick >> 33) as usize % scene.bodies.len();
    let (lo, hi) = teleport_bounds(scene);
    let mut p = Vector::<D>::ZERO;
    for k in 0..D {
        let u = ((*kick >> (7 * k + 3)) & 0x7f) as f64 / 128.0;
        p[k] = lo[k] + (hi[k] - lo[k]) * u;
    }
    let _ = sim.set_position(i, p);
}

/// Adds or removes one body, drawn by the generator state `kick`: a vacant slot drawn gets a
/// body, an occupied one loses its body or (half the time) a new body is added, appending
/// slots when none is vacant. New bodies land at a random spot inside the scene's bounds,
/// with a random velocity, a radius up to 1.5 times the scene's largest (the finder must
/// then be re-initialised), now and then kinematic or in a group from [`FILTERS`]. A refused
/// add (overlapping a body or a wall) changes nothing, alike in every run.
fn edit_slots<const D: usize>(sim: &mut Simulation<D>, scene: &Scene<D>, kick: &mut u64) {
    let mut next = || {
        *kick = kick
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        *kick >> 11
    };
    let i = next() as usize % sim.world().len().max(1);
    if !sim.world().is_empty() && !sim.world().is_vacant(i) && next() % 2 == 0 {
        sim.remove_body(i).expect("remove");
        return;
    }
    let (lo, hi) = teleport_bounds(scene);
    let r_max = scene.bodies.iter().fold(0.0f64, |m, b| m.max(b.radius));
    let unit = |x: u64| (x % 1024) as f64 / 1024.0;
    let mut spec = BodySpec::new(
        Vector::ZERO,
        Vector::ZERO,
        r_max * (0.3 + 1.2 * unit(next())),
    );
    for k in 0..D {
        spec.pos[k] = lo[k] + (hi[k] - lo[k]) * unit(next());
        spec.vel[k] = 4.0 * unit(next()) - 2.0;
    }
    match next() % 8 {
        0 => spec.kinematic = true,
        1 | 2 => {
            let f = FILTERS[next() as usize % FILTERS.len()];
            (spec.group, spec.mask) = (Some(f.group), Some(f.mask));
        }
        _ => {}
    }
    let _ = sim.add_body(spec);
}

/// The first contact of any body with any moving wall, by brute force over every pair of
/// them (the oracle of the simulation's queue of moving-wall contacts).
fn moving_wall_oracle<const D: usize>(world: &ccdsim::World<D>) -> Option<Event> {
    let first = world.walls().len();
    // A body turning about a segment's end is the pivot oracle's.
    (0..world.len())
        .filter(|&i| world.pivot(i).is_none())
        .flat_map(|i| (0..world.moving_wall_count()).map(move |k| (i, k)))
        .filter_map(|(i, k)| {
            ccdsim::world::toi_body_moving_wall(world, i, k)
                .filter(|t| t.is_finite())
                .map(|t| Event::wall(t, i, first + k))
        })
        .min()
}

/// The first event of the bodies turning about segment ends, which the finders do not see
/// (see `ccdsim::motion::pivot`), from scratch over every body and wall with the public functions
/// of `ccdsim::contact::pivot_end` and `ccdsim::contact::pivot_contact` (the oracle of the simulation's own,
/// incremental, pivot events): each search starts at the later of the two motions'
/// reference times and ends where a turn ends by itself.
fn pivot_oracle<const D: usize>(world: &ccdsim::World<D>) -> Option<Event> {
    use ccdsim::contact::pivot_contact::{first_contact_points, toi_pivot_wall, Parabola};
    use ccdsim::contact::pivot_end::{pivot_end, PivotEnd};
    use ccdsim::motion::pivot::{to_2d as two, wall_2d};
    if D != 2 || world.pivoting().next().is_none() {
        return None;
    }
    let walls: Vec<Wall<2>> = world.walls().iter().map(wall_2d).collect();
    let end_of = |i: usize| {
        let (p, w) = world.pivot(i).expect("turning");
        pivot_end(p, &walls, w)
    };
    let until = |i: usize| end_of(i).map_or(f64::INFINITY, |e| e.time());
    let mut best = None;
    for i in world.pivoting() {
        let (p, w) = world.pivot(i).expect("turning");
        let (lo, hi, r) = (p.start_time(), until(i), world.radius(i));
        let end = end_of(i).map(|e| match e {
            PivotEnd::Release { time } | PivotEnd::Back { time } => Event::wall(time, i, w),
            PivotEnd::Land { time, wall } => Event::wall(time, i, wall),
        });
        best = Event::earliest(best, end);
        for (k, wall) in walls.iter().enumerate() {
            let t = toi_pivot_wall(p, r, wall, Vector::ZERO, lo, lo, hi);
            best = Event::earliest(best, t.map(|t| Event::wall(t, i, k)));
        }
        for k in 0..world.moving_wall_count() {
            let idx = walls.len() + k;
            let from = lo.max(world.wall_motion(k).time);
            let (wall, vel) = (
                wall_2d(&world.wall_at(idx, from)),
                two(world.wall_velocity(idx)),
            );
            let t = toi_pivot_wall(p, r, &wall, vel, from, from, hi);
            best = Event::earliest(best, t.map(|t| Event::wall(t, i, idx)));
        }
        for j in (0..world.len()).filter(|&j| j != i && !world.is_vacant(j)) {
            if !world.filter(i).collides(&world.filter(j)) {
                continue;
            }
            let from = lo.max(world.time(j));
            let reach = r + world.radius(j);
            let t = match world.pivot(j) {
                Some((q, _)) => first_contact_points(p, q, reach, from, hi.min(until(j))),
                None => {
                    let m = world.motion(j);
                    let falls = Parabola {
                        pos: two(m.pos),
                        vel: two(m.vel),
                        acc: two(world.acceleration(j)),
                        time: m.time,
                    };
                    first_contact_points(p, &falls, reach, from, hi)
                }
            };
            best = Event::earliest(best, t.map(|t| Event::body(t, i, j)));
        }
    }
    best
}

/// Gives every moving wall a new velocity drawn by the generator state `kick`: up to 1 m/s
/// along its first axis of motion in the scene (`moving_walls[k].velocity`'s direction),
/// turned back when it has moved more than a third of the scene's extent from its start.
fn steer_walls<const D: usize>(sim: &mut Simulation<D>, scene: &Scene<D>, kick: &mut u64) {
    let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).expect("a walled scene");
    let reach = (0..D).map(|d| hi[d] - lo[d]).fold(f64::INFINITY, f64::min) / 3.0;
    for (k, m) in scene.moving_walls.iter().enumerate() {
        *kick = kick
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let axis = m.velocity * (1.0 / m.velocity.norm());
        let mut speed = (*kick >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        let along = sim.world().wall_motion(k).offset_at(sim.time()).dot(axis);
        if along < 0.0 {
            speed = speed.abs();
        } else if along > reach {
            speed = -speed.abs();
        }
        sim.set_wall_velocity(k, axis * speed)
            .expect("wall velocity");
    }
}

/// `scene` (a walled box) with two moving walls: a piston, a plane where the box's side
/// across the last axis is, moving into the box; and a paddle, a segment lying along the
/// box's first side, moving across the box along the first axis (2D only: 3D rods, moving
/// and not, have their own family, [`rods_under_gravity`]). Bodies clear both, as they clear
/// the box's walls.
fn with_moving_walls<const D: usize>(mut scene: Scene<D>) -> Scene<D> {
    let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).expect("a walled scene");
    let top = D - 1;
    let mut normal = Vector::<D>::ZERO;
    normal[top] = -1.0;
    let mut point = lo;
    point[top] = hi[top];
    scene.moving_walls.push(ccdsim::MovingWall {
        wall: Wall::Plane { point, normal },
        velocity: normal * 0.5,
    });
    if D == 2 {
        let (mut a, mut b) = (lo, lo);
        a[1] = lo[1] + 0.55 * (hi[1] - lo[1]);
        b[1] = lo[1] + 0.85 * (hi[1] - lo[1]);
        let mut v = Vector::<D>::ZERO;
        v[0] = 0.7;
        scene.moving_walls.push(ccdsim::MovingWall {
            wall: Wall::Segment { a, b },
            velocity: v,
        });
    }
    scene
}

/// The finder of the reference runs: checked against the oracle on every event, so its run is
/// the all-pairs run (see [`reference`]).
const REFERENCE_FINDER: &str = "cells";

/// The run of `scene` that every finder's run file must equal byte for byte: made with
/// [`REFERENCE_FINDER`], checked before every event against [`all_pairs_next_event`] (with
/// the moving walls' and turning bodies' oracles) on the simulation's own world, bit for bit.
/// Every event of it being the oracle's on the same world, it is event for event the run the
/// all-pairs finder makes (which is `all_pairs_next_event` and nothing else), and it costs one
/// oracle search per event instead of the two of an all-pairs run checked the same way.
fn reference<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    max_events: u64,
    drive: Drive,
) -> Recorded {
    let options = FinderOptions::default();
    let run = record_run(
        label,
        scene,
        REFERENCE_FINDER,
        &options,
        max_events,
        drive,
        true,
    );
    // A steered run replays: its edit records say what the program (or the scene's arrivals)
    // did.
    if drive.steered() || !scene.arrivals.is_empty() {
        let mut r =
            ccdsim::record::RunReader::<_, D>::new(&run.bytes[..], label.into()).expect("header");
        let (events, end) = r.read_events().expect("records");
        let mut v = ccdsim::verify::Verifier::new(scene);
        for c in &events {
            v.check(c).unwrap_or_else(|e| {
                panic!("{label} [{drive:?}]: the oracle's run fails verify: {e}")
            });
        }
        v.finish(end.expect("an end record"))
            .unwrap_or_else(|e| panic!("{label} [{drive:?}]: the oracle's run fails verify: {e}"));
    }
    run
}

/// Runs `scene` with finder `name` and asserts that its run file and its end equal those of
/// the reference run `oracle` (made with the same `max_events` and `drive`, and checked
/// against the oracle on every event); when they differ, runs it again checking every event
/// against the oracle, to name the first that differs. Returns the number of events.
fn check_run<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    name: &str,
    options: &FinderOptions,
    max_events: u64,
    drive: Drive,
    oracle: &Recorded,
) -> u64 {
    if name == REFERENCE_FINDER && *options == FinderOptions::default() {
        // The reference run itself, made and checked on every event already.
        return oracle.events;
    }
    let run = record_run(label, scene, name, options, max_events, drive, false);
    if run.events != oracle.events || run.bytes != oracle.bytes || run.end != oracle.end {
        record_run(label, scene, name, options, max_events, drive, true);
    }
    assert_eq!(
        run.end, oracle.end,
        "{label} [{name}, {D}D]: how the runs end"
    );
    assert_eq!(
        run.events, oracle.events,
        "{label} [{name}, {D}D]: event counts"
    );
    assert!(
        run.bytes == oracle.bytes,
        "{label} [{name}, {D}D]: run files differ ({} vs {} bytes)",
        run.bytes.len(),
        oracle.bytes.len()
    );
    run.events
}

/// Runs `scene` through every finder under test with default options.
fn check_all<const D: usize>(label: &str, scene: &Scene<D>, max_events: u64) -> u64 {
    check_all_run(label, scene, max_events).events
}

/// [`check_all`], returning the oracle's run.
fn check_all_run<const D: usize>(label: &str, scene: &Scene<D>, max_events: u64) -> Recorded {
    let oracle = reference(label, scene, max_events, Drive::Events);
    for name in finders() {
        let options = FinderOptions::default();
        check_run(
            label,
            scene,
            name,
            &options,
            max_events,
            Drive::Events,
            &oracle,
        );
    }
    oracle
}

/// A gas (open with walls, or `periodic`); when random placement cannot reach `packing`
/// (small boxes, dense polydisperse mixtures), the packing is lowered until it can.
fn any_gas<const D: usize>(
    n: usize,
    packing: f64,
    radii: (f64, f64),
    seed: u64,
    periodic: bool,
) -> Scene<D> {
    let mut packing = packing;
    loop {
        match gas(&GasConfig {
            n,
            packing,
            radius_min: radii.0,
            radius_max: radii.1,
            speed_min: 0.0,
            speed_max: 1.0,
            seed,
            periodic,
            ..GasConfig::default()
        }) {
            Ok(scene) => return scene,
            Err(GenerateError::Jammed { .. }) => packing *= 0.8,
            // Few bodies make a small periodic box: a lower packing makes it wider.
            Err(e) if periodic && e.to_string().contains("must be wider") => packing *= 0.5,
            Err(e) => panic!("{e}"),
        }
    }
}

/// A gas in a walled box; see [`any_gas`].
fn gas_scene<const D: usize>(n: usize, packing: f64, radii: (f64, f64), seed: u64) -> Scene<D> {
    any_gas(n, packing, radii, seed, false)
}

/// Monodisperse and polydisperse radii.
const DISPERSITIES: [(&str, (f64, f64)); 2] = [("mono", (0.5, 0.5)), ("poly", (0.2, 1.0))];

/// Dilute and dense packings, 2D then 3D.
fn packings(dim: usize) -> [(&'static str, f64); 2] {
    if dim == 2 {
        [("dilute", 0.05), ("dense", 0.45)]
    } else {
        [("dilute", 0.03), ("dense", 0.3)]
    }
}

/// Calls `check(label, n, packing, radii, seed)` for every size, seed, packing and
/// dispersity.
fn for_each_gas<const D: usize>(
    ns: &[usize],
    seeds: &[u64],
    mut check: impl FnMut(&str, usize, f64, (f64, f64), u64),
) {
    for &n in ns {
        for &seed in seeds {
            for (pack_name, packing) in packings(D) {
                for (disp_name, radii) in DISPERSITIES {
                    let label = format!("n={n} {pack_name} {disp_name} seed={seed}");
                    check(&label, n, packing, radii, seed);
                }
            }
        }
    }
}

fn without_walls<const D: usize>(scene: Scene<D>) -> Scene<D> {
    Scene {
        walls: Vec::new(),
        ..scene
    }
}

/// True when finder `name` with `options` serves periodic worlds (a finder that cannot
/// refuses them at `init`; every finder here serves them).
fn serves_periodic(name: &str, options: &FinderOptions) -> bool {
    let scene = Scene::<2> {
        periodic: Some(Vector([10.0, 10.0])),
        ..Scene::default()
    };
    Simulation::with_finder(&scene, make_finder::<2>(name, options).expect("finder")).is_ok()
}

/// Runs the periodic `scene` through every variant, each of which must serve periodic
/// worlds, driven by `drive`; returns the number of events.
fn check_periodic<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    max_events: u64,
    drive: Drive,
) -> u64 {
    for (name, options) in variants() {
        assert!(
            serves_periodic(name, &options),
            "finder {name} refuses periodic worlds"
        );
    }
    check_all_driven(label, scene, max_events, drive).events
}

/// A gas in a periodic box; see [`any_gas`].
fn periodic_gas<const D: usize>(n: usize, packing: f64, radii: (f64, f64), seed: u64) -> Scene<D> {
    any_gas(n, packing, radii, seed, true)
}

/// `scene` with radii growing at `rate` per second (see `ccdsim::contact::growth`).
fn growing<const D: usize>(mut scene: Scene<D>, rate: f64) -> Scene<D> {
    scene.settings.growth = Some(ccdsim::Growth { rate });
    scene
}

/// `scene` with restitution 0.8, bodies' own restitutions from 0.2 to 1 and, with `tc`, the
/// TC model.
fn inelastic<const D: usize>(mut scene: Scene<D>, tc: Option<f64>) -> Scene<D> {
    scene.settings.restitution = 0.8;
    scene.settings.tc = tc;
    for (k, b) in scene.bodies.iter_mut().enumerate() {
        b.restitution = [Some(0.2), Some(0.9), None, Some(1.0), Some(0.5)][k % 5];
    }
    scene
}

/// `scene` under uniform gravity `g` (see `ccdsim::contact::gravity`).
fn falling<const D: usize>(mut scene: Scene<D>, g: [f64; D]) -> Scene<D> {
    scene.settings.gravity = ccdsim::Gravity::new(&g);
    scene
}

/// A 2D board of pegs (short segments, so the end points' quartic is exercised) inside a
/// walled box, with balls dropped from above.
fn peg_board(rows: usize, balls: usize, seed: u64) -> Scene<2> {
    let width = 12.0;
    let mut walls = box_walls(Vector([width, 16.0]));
    for row in 0..rows {
        let y = 3.0 + 1.5 * row as f64;
        let shift = if row % 2 == 0 { 0.0 } else { 0.75 };
        let mut x = 1.0 + shift;
        while x < width - 1.0 {
            walls.push(Wall::Segment {
                a: Vector([x - 0.2, y]),
                b: Vector([x + 0.2, y + 0.1]),
            });
            x += 1.5;
        }
    }
    let mut bodies = Vec::new();
    let mut state = seed;
    for k in 0..balls {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let jitter = (state >> 11) as f64 / (1u64 << 53) as f64;
        let x = 0.6 + (k % 16) as f64 * 0.68 + 0.05 * jitter;
        let y = 4.0 + 1.5 * rows as f64 + 0.7 * (k / 16) as f64;
        bodies.push(BodySpec::new(
            Vector([x, y]),
            Vector([jitter - 0.5, 0.0]),
            0.25,
        ));
    }
    falling(
        Scene {
            bodies,
            walls,
            ..Scene::default()
        },
        [0.0, -9.81],
    )
}

/// `scene` with its first `k` bodies made kinematic (infinite mass; see `BodySpec::kinematic`).
fn with_kinematic<const D: usize>(mut scene: Scene<D>, k: usize) -> Scene<D> {
    for b in scene.bodies.iter_mut().take(k) {
        b.kinematic = true;
        b.mass = None;
    }
    scene
}

/// The box teleports land in: the periodic box, or the walls' bounds.
fn teleport_bounds<const D: usize>(scene: &Scene<D>) -> (Vector<D>, Vector<D>) {
    match scene.periodic {
        Some(size) => (Vector::ZERO, size),
        None => ccdsim::wall::walls_bounds(&scene.walls).expect("a walled scene"),
    }
}

/// Runs `scene` driven by `drive` through every finder and cells mode against the oracle;
/// returns the oracle's run.
fn check_all_driven<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    max_events: u64,
    drive: Drive,
) -> Recorded {
    let oracle = reference(label, scene, max_events, drive);
    for (name, options) in variants() {
        let label = format!("{label} (cells_skin {:?})", options.cells_skin);
        check_run(&label, scene, name, &options, max_events, drive, &oracle);
    }
    oracle
}

/// How many collisions with each moving wall a run file of `scene` holds.
fn moving_wall_hits<const D: usize>(scene: &Scene<D>, run: &Recorded) -> Vec<usize> {
    let mut r =
        ccdsim::record::RunReader::<_, D>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    let mut hits = vec![0; scene.moving_walls.len()];
    for c in events.iter().filter(|c| c.event.kind == EventKind::Wall) {
        if let Some(k) = (c.event.b as usize).checked_sub(scene.walls.len()) {
            hits[k] += 1;
        }
    }
    hits
}

/// `scene` under gravity `g` with bodies resting on walls (restitution 0.5, `rest_speed`
/// 0.5 m/s): in 2D its box becomes four planes (bodies rest on planes only) and an incline
/// across its lower left corner, bodies crossing it left out.
fn resting<const D: usize>(mut scene: Scene<D>, g: [f64; D]) -> Scene<D> {
    scene.settings.gravity = ccdsim::Gravity::new(&g);
    scene.settings.restitution = 0.5;
    scene.settings.rest_speed = Some(0.5);
    if D == 2 {
        let mut lo = Vector::<D>::splat(f64::INFINITY);
        let mut hi = Vector::<D>::splat(f64::NEG_INFINITY);
        for w in &scene.walls {
            if let Wall::Segment { a, b } = w {
                lo = lo.min(a.min(*b));
                hi = hi.max(a.max(*b));
            }
        }
        let plane = |point: Vector<D>, d: usize, sign: f64| {
            let mut normal = Vector::<D>::ZERO;
            normal[d] = sign;
            Wall::Plane { point, normal }
        };
        let mut walls: Vec<Wall<D>> = (0..D)
            .flat_map(|d| [plane(lo, d, 1.0), plane(hi, d, -1.0)])
            .collect();
        let mut corner = lo;
        corner[1] = lo[1] + 0.25 * (hi[1] - lo[1]);
        let mut normal = Vector::<D>::splat(1.0);
        normal[1] = 1.5;
        let incline = Wall::Plane {
            point: corner,
            normal,
        };
        scene
            .bodies
            .retain(|b| ccdsim::wall::wall_clearance(&incline, b.pos) > b.radius);
        walls.push(incline);
        scene.walls = walls;
    }
    scene
}

/// Verify accepts the run file `run` of `scene`.
fn verifies<const D: usize>(label: &str, scene: &Scene<D>, run: &Recorded) {
    let mut r =
        ccdsim::record::RunReader::<_, D>::new(&run.bytes[..], label.into()).expect("header");
    let (events, end) = r.read_events().expect("records");
    let mut v = ccdsim::verify::Verifier::new(scene);
    for c in &events {
        v.check(c)
            .unwrap_or_else(|e| panic!("{label}: the oracle's run fails verify: {e}"));
    }
    v.finish(end.expect("an end record"))
        .unwrap_or_else(|e| panic!("{label}: the oracle's run fails verify: {e}"));
}

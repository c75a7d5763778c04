//! Internal checks: the structures stay consistent (`validate`) on every step of runs that
//! also compare each event with the oracle.

use super::{Cells, CellsStats};
use crate::finder::{all_pairs_next_event, Finder, FinderOptions};
use crate::generate::{gas, GasConfig};
use crate::geom::Vector;
use crate::motion::Growth;
use crate::resolve::{resolve_body_body, resolve_body_wall, resolve_exit};
use crate::scene::{BodySpec, Scene};
use crate::world::World;
use crate::{Event, EventKind};
use std::sync::{Arc, Mutex};

/// Resolves event `e` (a collision or a box exit) on `world` and tells `finder`.
fn resolve_and_update<const D: usize>(world: &mut World<D>, finder: &mut Cells<D>, e: Event) {
    let changed = resolve_event(world, e);
    finder.update(world, &changed);
}

/// Resolves event `e` (a collision or a box exit) on `world`; returns the bodies it changed.
fn resolve_event<const D: usize>(world: &mut World<D>, e: Event) -> Vec<usize> {
    world.set_now(e.time.max(world.now()));
    let (a, b) = (e.a as usize, e.b as usize);
    match e.kind {
        EventKind::Body => {
            resolve_body_body(world, a, b, e.time);
            vec![a, b]
        }
        EventKind::Wall if b >= world.walls().len() => {
            let face = b - world.walls().len();
            resolve_exit(world, a, face, e.time);
            vec![a]
        }
        EventKind::Wall => {
            resolve_body_wall(world, a, b, e.time);
            vec![a]
        }
        EventKind::Reset | EventKind::Edit => panic!("finders never predict resets or edits"),
    }
}

/// The oracle's next event before each of the first `events` steps of a run of `scene` (up to
/// and including the first `None`), from [`all_pairs_next_event`], each event resolved as
/// [`resolve_event`] does. Computed once per scene and length, and shared by the runs that
/// compare a finder with it (every skin and hint setting of one scene): a run's world goes
/// through the same events as long as its finder agrees with the oracle, so the oracle's
/// `k`-th event is the one it would find on that run's world before step `k`.
fn oracle_events<const D: usize>(scene: &Scene<D>, events: usize) -> Arc<Vec<Option<Event>>> {
    type Cache = Mutex<Vec<(String, Arc<Vec<Option<Event>>>)>>;
    static CACHE: Cache = Mutex::new(Vec::new());
    let key = format!("{D} {events} {scene:?}");
    let cached = |cache: &Cache| {
        let cache = cache.lock().unwrap_or_else(|e| e.into_inner());
        cache
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.clone())
    };
    if let Some(hit) = cached(&CACHE) {
        return hit;
    }
    let mut world = World::from_scene(scene).unwrap();
    let mut out = Vec::new();
    for _ in 0..events {
        let e = all_pairs_next_event(&world);
        out.push(e);
        let Some(e) = e else { break };
        resolve_event(&mut world, e);
    }
    let out = Arc::new(out);
    CACHE
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push((key, out.clone()));
    out
}

/// A finder with the neighbour-list skin `skin`.
fn with_skin<const D: usize>(skin: f64) -> Cells<D> {
    Cells::with_options(&FinderOptions {
        cells_skin: Some(skin),
        ..FinderOptions::default()
    })
    .unwrap()
}

/// Runs `events` events resolving them by hand, validating the finder after each.
fn validated_run<const D: usize>(scene: &Scene<D>, events: usize) {
    let stats = validated_run_with(scene, events, 0.0);
    assert_eq!(stats.rebuilds, 0);
}

/// Like `validated_run`, with the neighbour-list skin `skin` (0: crossings).
fn validated_run_with<const D: usize>(scene: &Scene<D>, events: usize, skin: f64) -> CellsStats {
    validated_run_hinted(scene, events, skin, None)
}

/// Like `validated_run_with`, with the prefetch hints forced on or off (`hints`) instead of
/// chosen by the working set's size.
fn validated_run_hinted<const D: usize>(
    scene: &Scene<D>,
    events: usize,
    skin: f64,
    hints: Option<bool>,
) -> CellsStats {
    let mut world = World::from_scene(scene).unwrap();
    let mut finder = with_skin::<D>(skin);
    finder.init(&world).unwrap();
    if let Some(hints) = hints {
        finder.hints = hints;
    }
    finder.validate(&world).unwrap();
    let oracle = oracle_events(scene, events);
    for k in 0..events {
        let got = finder.next_event(&world);
        finder
            .validate(&world)
            .unwrap_or_else(|e| panic!("event {k}: {e}"));
        let want = oracle[k];
        assert_eq!(
            got.map(|e| (e.time.to_bits(), e.kind, e.a, e.b)),
            want.map(|e| (e.time.to_bits(), e.kind, e.a, e.b)),
            "event {k}"
        );
        let Some(e) = got else {
            return finder.stats();
        };
        resolve_and_update(&mut world, &mut finder, e);
        finder
            .validate(&world)
            .unwrap_or_else(|e| panic!("after event {k}: {e}"));
    }
    finder.stats()
}

fn cfg(n: usize, packing: f64, rmin: f64, rmax: f64, seed: u64) -> GasConfig {
    GasConfig {
        n,
        packing,
        radius_min: rmin,
        radius_max: rmax,
        speed_min: 0.0,
        speed_max: 3.0,
        seed,
        ..GasConfig::default()
    }
}

/// `c` in a periodic box.
fn periodic(c: GasConfig) -> GasConfig {
    GasConfig {
        periodic: true,
        ..c
    }
}

#[test]
fn structures_stay_consistent_2d() {
    for seed in [3, 4] {
        validated_run::<2>(&gas(&cfg(150, 0.35, 0.5, 0.5, seed)).unwrap(), 1500);
        validated_run::<2>(&gas(&cfg(100, 0.2, 0.1, 1.0, seed)).unwrap(), 1500);
    }
}

#[test]
fn periodic_structures_and_every_exit() {
    for seed in [5, 6] {
        validated_run::<2>(
            &gas(&periodic(cfg(150, 0.35, 0.5, 0.5, seed))).unwrap(),
            2000,
        );
        validated_run::<2>(
            &gas(&periodic(cfg(80, 0.05, 0.2, 0.9, seed))).unwrap(),
            2000,
        );
        validated_run::<3>(
            &gas(&periodic(cfg(100, 0.2, 0.5, 0.5, seed))).unwrap(),
            1500,
        );
    }
}

/// Small worlds get no hints; the hinted paths (large worlds) must find the same events.
#[test]
fn prefetch_hints_change_no_event() {
    let small = gas(&periodic(cfg(150, 0.35, 0.5, 0.5, 7))).unwrap();
    let mut finder = with_skin::<2>(0.0);
    finder.init(&World::from_scene(&small).unwrap()).unwrap();
    assert!(!finder.hints, "150 bodies fit in any cache");
    for skin in [0.0, 0.2] {
        validated_run_hinted::<2>(&small, 1500, skin, Some(true));
        validated_run_hinted::<3>(
            &gas(&periodic(cfg(100, 0.25, 0.3, 0.6, 7))).unwrap(),
            1000,
            skin,
            Some(true),
        );
    }
    validated_run_hinted::<2>(
        &gas(&cfg(100, 0.2, 0.1, 1.0, 7)).unwrap(),
        1500,
        0.0,
        Some(true),
    );
    validated_run_hinted::<3>(
        &gas(&cfg(120, 0.25, 0.5, 0.5, 7)).unwrap(),
        1000,
        0.0,
        Some(true),
    );
    // A large world gets them.
    let large = gas(&periodic(cfg(40_000, 0.5, 0.5, 0.5, 7))).unwrap();
    finder.init(&World::from_scene(&large).unwrap()).unwrap();
    assert!(finder.hints, "40,000 bodies take more than 2 MiB");
}

#[test]
fn open_worlds_until_nothing_happens() {
    for seed in [1, 2] {
        let mut scene: Scene<2> = gas(&cfg(150, 0.3, 0.3, 0.8, seed)).unwrap();
        scene.walls.clear();
        validated_run::<2>(&scene, 100_000);
    }
}

#[test]
fn structures_stay_consistent_3d() {
    for seed in [3, 4] {
        validated_run::<3>(&gas(&cfg(120, 0.25, 0.5, 0.5, seed)).unwrap(), 1200);
    }
}

#[test]
fn edits_behind_the_clock_undo_crossings() {
    let scene: Scene<2> = gas(&cfg(120, 0.1, 0.5, 0.5, 9)).unwrap();
    edits_behind_the_clock(&scene, 0.0);
}

#[test]
fn list_mode_edits_behind_the_clock_redo_rebuilds() {
    for skin in [0.01, 0.2] {
        let scene: Scene<2> = gas(&periodic(cfg(120, 0.3, 0.3, 0.6, 9))).unwrap();
        edits_behind_the_clock(&scene, skin);
    }
}

/// List mode in 3D with small bodies among large ones: cells (sized for the largest) hold
/// more bodies than their slots, so rebuilds read overflow lists and moves refill slots from
/// them; the structures, slot records included, stay consistent and every event is the
/// oracle's.
#[test]
fn list_mode_with_overflowing_cells() {
    for seed in [8, 9] {
        let scene = gas(&periodic(cfg(150, 0.3, 0.15, 0.6, seed))).unwrap();
        let world = World::from_scene(&scene).unwrap();
        let mut finder = with_skin::<3>(0.4);
        finder.init(&world).unwrap();
        let lists = finder.lists();
        assert!(lists.slots.overflowing() > 0, "no cell overflows");
        let stats = validated_run_with::<3>(&scene, 1500, 0.4);
        assert!(stats.rebuilds > 0, "{stats:?}");
    }
}

#[test]
fn list_mode_structures_stay_consistent() {
    for seed in [5, 6] {
        for skin in [0.001, 0.1, 1.0] {
            let runs = [
                validated_run_with::<2>(
                    &gas(&periodic(cfg(150, 0.4, 0.5, 0.5, seed))).unwrap(),
                    1500,
                    skin,
                ),
                validated_run_with::<2>(
                    &gas(&periodic(cfg(80, 0.05, 0.2, 0.9, seed))).unwrap(),
                    1500,
                    skin,
                ),
                validated_run_with::<3>(
                    &gas(&periodic(cfg(100, 0.25, 0.3, 0.6, seed))).unwrap(),
                    1000,
                    skin,
                ),
            ];
            for stats in runs {
                assert!(stats.rebuilds > 0 && stats.crossings == 0, "{stats:?}");
            }
        }
    }
    // Lists are used in periodic worlds only.
    let mut finder = with_skin::<2>(0.2);
    let walled = gas(&cfg(50, 0.2, 0.5, 0.5, 1)).unwrap();
    finder.init(&World::from_scene(&walled).unwrap()).unwrap();
    assert!(!finder.uses_lists());
    let periodic = gas(&periodic(cfg(50, 0.2, 0.5, 0.5, 1))).unwrap();
    let world = World::from_scene(&periodic).unwrap();
    finder.init(&world).unwrap();
    assert!(finder.uses_lists());
    finder.validate(&world).unwrap();
}

#[test]
fn cells_skin_is_checked() {
    for bad in [-0.1, 0.0005, 1.5, f64::NAN, f64::INFINITY] {
        let err = Cells::<2>::with_options(&FinderOptions {
            cells_skin: Some(bad),
            ..FinderOptions::default()
        });
        assert!(
            matches!(
                err,
                Err(crate::finder::FinderError::Option {
                    option: "cells_skin",
                    ..
                })
            ),
            "{bad}"
        );
    }
    for good in [0.0, 0.001, 0.3, 1.0] {
        assert!(Cells::<2>::with_options(&FinderOptions {
            cells_skin: Some(good),
            ..FinderOptions::default()
        })
        .is_ok());
    }
}

/// Peeks (internal work up to the next event is done), then edits a body at a time before
/// that, 200 times, comparing with the oracle and validating after each edit.
fn edits_behind_the_clock(scene: &Scene<2>, skin: f64) {
    let mut world = World::from_scene(scene).unwrap();
    let mut finder = with_skin::<2>(skin);
    finder.init(&world).unwrap();
    for k in 0..200usize {
        // Peek (crossings up to the next event are processed), then edit a body at `now`.
        let next = finder.next_event(&world).unwrap();
        let i = (k * 37) % world.len();
        let t = world.now() + (next.time - world.now()) * 0.25;
        world.set_now(t);
        let p = world.position_at(i, t);
        let v = crate::geom::Vector([(k % 7) as f64 - 3.0, (k % 5) as f64 - 2.0]);
        world.set_state(i, p, v, t);
        finder.update(&world, &[i]);
        finder
            .validate(&world)
            .unwrap_or_else(|e| panic!("edit {k}: {e}"));
        let got = finder.next_event(&world).unwrap();
        let want = all_pairs_next_event(&world).unwrap();
        assert_eq!(
            (got.time.to_bits(), got.kind, got.a, got.b),
            (want.time.to_bits(), want.kind, want.a, want.b)
        );
        // Resolve it, so that the run goes on (box exits included).
        resolve_and_update(&mut world, &mut finder, got);
    }
    assert!(finder.stats().undone > 0);
}

/// The state of `finder` that a recompute writes: every body's records and queue key, and the
/// counters.
fn records<const D: usize>(
    finder: &Cells<D>,
) -> (Vec<super::Cached<D>>, Vec<super::Key>, CellsStats) {
    let keys = (0..finder.cached.len())
        .map(|i| finder.queue.key(i))
        .collect();
    (finder.cached.clone(), keys, finder.stats)
}

/// `recompute_pair(i, j)` leaves every record, queue key and counter exactly as
/// `recompute(i)` then `recompute(j)` do (keys, hence times bit for bit, images, second
/// events, partner counts, crossings), on pairs of bodies in the same or neighbouring interior
/// cells, after both were given random velocities as a collision would; and it declines
/// (doing nothing) exactly when the cells are not both interior neighbours.
fn pair_recompute_matches_two_recomputes<const D: usize>(scene: &Scene<D>, seed: u64) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut world = World::from_scene(scene).unwrap();
    let mut finder = with_skin::<D>(0.0);
    finder.init(&world).unwrap();
    let n = world.len();
    let (mut taken, mut declined, mut differs_from_before) = (0usize, 0usize, 0usize);
    for _round in 0..12 {
        // Move on: a few events, so that states and cells vary.
        for _ in 0..40 {
            let e = finder.next_event(&world).unwrap();
            resolve_and_update(&mut world, &mut finder, e);
        }
        let t = world.now();
        for _ in 0..15 {
            let i = rng.random_range(0..n);
            for j in 0..n {
                if j == i {
                    continue;
                }
                let (ki, kj) = (finder.cached[i].coords, finder.cached[j].coords);
                let near = (0..D).all(|d| ki[d].abs_diff(kj[d]) <= 1);
                let interior = finder.grid.interior_pair(&ki, &kj).is_some();
                if !near && rng.random_range(0..8) != 0 {
                    continue;
                }
                let mut w = world.clone();
                for b in [i, j] {
                    let p = w.position_at(b, t);
                    let v = Vector(std::array::from_fn(|_| rng.random_range(-3.0..3.0)));
                    w.set_state(b, p, v, t);
                }
                let mut one = finder.clone();
                let mut two = finder.clone();
                let took = one.recompute_pair(&w, i, j);
                assert_eq!(took, near && interior, "bodies {i}, {j} in {ki:?}, {kj:?}");
                if !took {
                    declined += 1;
                    assert_eq!(records(&one), records(&finder), "declined, yet changed");
                    continue;
                }
                taken += 1;
                two.recompute(&w, i);
                two.recompute(&w, j);
                assert_eq!(records(&one), records(&two), "bodies {i}, {j}");
                if records(&one).0 != records(&finder).0 {
                    differs_from_before += 1;
                }
                one.validate(&w).unwrap();
            }
        }
    }
    assert!(
        taken > 100 && declined > 10,
        "taken {taken}, declined {declined}"
    );
    assert!(
        differs_from_before * 2 > taken,
        "{differs_from_before} of {taken}"
    );
}

#[test]
fn pair_recompute_is_two_recomputes() {
    for seed in [11, 12] {
        let dense = gas(&cfg(300, 0.45, 0.5, 0.5, seed)).unwrap();
        pair_recompute_matches_two_recomputes::<2>(&dense, seed);
        let poly = gas(&cfg(250, 0.3, 0.2, 1.0, seed)).unwrap();
        pair_recompute_matches_two_recomputes::<2>(&poly, seed);
        let periodic2 = gas(&periodic(cfg(300, 0.45, 0.5, 0.5, seed))).unwrap();
        pair_recompute_matches_two_recomputes::<2>(&periodic2, seed);
        let spheres = gas(&cfg(400, 0.3, 0.5, 0.5, seed)).unwrap();
        pair_recompute_matches_two_recomputes::<3>(&spheres, seed);
        let periodic3 = gas(&periodic(cfg(400, 0.3, 0.4, 0.6, seed))).unwrap();
        pair_recompute_matches_two_recomputes::<3>(&periodic3, seed);
    }
}

#[test]
fn growing_bodies_too_far_apart_to_be_paired_still_meet() {
    // Two balls at rest, 16 contact distances apart, in an open world: a grid sized for the
    // first horizon never pairs them, and the queue holds nothing at a finite time. They
    // still grow into each other (at t = 300 s).
    let mut scene = Scene::<3>::default();
    for x in [0.0, 8.0] {
        scene
            .bodies
            .push(BodySpec::new(Vector([x, 0.0, 0.0]), Vector::ZERO, 0.25));
    }
    scene.settings.growth = Some(Growth { rate: 0.05 });
    validated_run::<3>(&scene, 1);
    let world = World::from_scene(&scene).unwrap();
    let mut finder = with_skin::<3>(0.0);
    finder.init(&world).unwrap();
    let e = finder.next_event(&world).expect("the balls meet");
    assert_eq!((e.kind, e.a, e.b), (EventKind::Body, 0, 1));
    assert_eq!(Some(e.time), all_pairs_next_event(&world).map(|e| e.time));
}

#[test]
fn the_automatic_skin_lists_only_dense_3d_periodic_worlds() {
    let mut finder = Cells::<3>::with_options(&FinderOptions::default()).unwrap();
    let gas_at = |packing: f64, lattice: bool| {
        let scene = gas::<3>(&GasConfig {
            n: 500,
            packing,
            radius_min: 0.5,
            radius_max: 0.5,
            periodic: true,
            lattice: lattice.then_some(crate::generate::Lattice::Densest),
            ..GasConfig::default()
        })
        .unwrap();
        World::from_scene(&scene).unwrap()
    };
    // Dilute: a body would leave its shell many times per collision.
    finder.init(&gas_at(0.05, false)).unwrap();
    assert!(!finder.uses_lists());
    // Dense: lists pay.
    let dense = gas_at(0.45, true);
    finder.init(&dense).unwrap();
    assert!(finder.uses_lists());
    finder.validate(&dense).unwrap();
    // A skin the program chose is kept whatever the packing.
    let mut chosen = with_skin::<3>(0.3);
    chosen.init(&gas_at(0.05, false)).unwrap();
    assert!(chosen.uses_lists());
}

//! Internal checks: the structures stay consistent (`validate`) on every step of runs that
//! also compare each event with the oracle.

use super::Cells;
use crate::finder::{all_pairs_next_event, Finder};
use crate::generate::{gas, GasConfig};
use crate::resolve::{resolve_body_body, resolve_body_wall, resolve_exit};
use crate::scene::Scene;
use crate::world::World;
use crate::EventKind;

/// Runs `events` events resolving them by hand, validating the finder after each.
fn validated_run<const D: usize>(scene: &Scene<D>, events: usize) {
    let mut world = World::from_scene(scene).unwrap();
    let mut finder = Cells::<D>::new();
    finder.init(&world).unwrap();
    finder.validate(&world).unwrap();
    for k in 0..events {
        let got = finder.next_event(&world);
        finder
            .validate(&world)
            .unwrap_or_else(|e| panic!("event {k}: {e}"));
        let want = all_pairs_next_event(&world);
        assert_eq!(
            got.map(|e| (e.time.to_bits(), e.kind, e.a, e.b)),
            want.map(|e| (e.time.to_bits(), e.kind, e.a, e.b)),
            "event {k}"
        );
        let Some(e) = got else { return };
        world.set_now(e.time.max(world.now()));
        let (a, b) = (e.a as usize, e.b as usize);
        match e.kind {
            EventKind::Body => {
                resolve_body_body(&mut world, a, b, e.time);
                finder.update(&world, &[a, b]);
            }
            EventKind::Wall if b >= world.walls().len() => {
                let face = b - world.walls().len();
                resolve_exit(&mut world, a, face, e.time);
                finder.update(&world, &[a]);
            }
            EventKind::Wall => {
                resolve_body_wall(&mut world, a, b, e.time);
                finder.update(&world, &[a]);
            }
        }
        finder
            .validate(&world)
            .unwrap_or_else(|e| panic!("after event {k}: {e}"));
    }
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
        let periodic = |c: GasConfig| GasConfig {
            periodic: true,
            ..c
        };
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

#[test]
fn structures_stay_consistent_3d() {
    for seed in [3, 4] {
        validated_run::<3>(&gas(&cfg(120, 0.25, 0.5, 0.5, seed)).unwrap(), 1200);
    }
}

#[test]
fn edits_behind_the_clock_undo_crossings() {
    let scene: Scene<2> = gas(&cfg(120, 0.1, 0.5, 0.5, 9)).unwrap();
    let mut world = World::from_scene(&scene).unwrap();
    let mut finder = Cells::<2>::new();
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
    }
    assert!(finder.stats().undone > 0);
}

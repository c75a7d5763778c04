//! What a game's edits cost on 2D gases of n = 10³ … 10⁵ bodies (packing 0.3, `cells`):
//!
//! - `wall_velocity`: one `Simulation::set_wall_velocity` of a paddle (a moving segment),
//!   which recomputes every body's next moving-wall contact: O(n · moving walls);
//! - `remove_add`: `remove_body` then `add_body` of the same body where it was, whose
//!   overlap check is O(n);
//! - `step_moving` and `step_static`: one `step_event` with the paddle moving, and in the same
//!   gas without moving walls: the moving walls' queue costs O(walls + log n) per event.
//!
//! From the repository's root: `cargo bench --manifest-path bench/criterion/Cargo.toml
//! --bench game_edits -- --warm-up-time 1 --measurement-time 3`

use ccdsim::generate::{gas, GasConfig};
use ccdsim::{BodySpec, MovingWall, Scene, Simulation, Vector, Wall};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

/// Body counts.
const NS: [usize; 3] = [1_000, 10_000, 100_000];

fn gas_with_paddle(n: usize, paddle: bool) -> Scene<2> {
    let mut scene = gas::<2>(&GasConfig {
        n,
        packing: 0.3,
        radius_min: 0.5,
        radius_max: 0.5,
        speed_min: 0.0,
        speed_max: 1.0,
        seed: 2026,
        ..GasConfig::default()
    })
    .expect("gas");
    if paddle {
        // Along the left wall, clear of every body as the wall is.
        let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).expect("a walled box");
        let h = hi[1] - lo[1];
        scene.moving_walls.push(MovingWall {
            wall: Wall::Segment {
                a: Vector([lo[0], lo[1] + 0.4 * h]),
                b: Vector([lo[0], lo[1] + 0.6 * h]),
            },
            velocity: Vector([0.5, 0.0]),
        });
    }
    scene
}

fn game_edits(c: &mut Criterion) {
    let mut group = c.benchmark_group("game_edits_2d");
    group.sample_size(10);
    for n in NS {
        let scene = gas_with_paddle(n, true);
        let mut sim = Simulation::new(&scene, "cells").expect("simulation");
        sim.run_events(1000);
        let mut sign = 1.0;
        group.bench_with_input(BenchmarkId::new("wall_velocity", n), &n, |b, _| {
            b.iter(|| {
                sign = -sign;
                sim.set_wall_velocity(0, Vector([0.5 * sign, 0.0]))
                    .expect("velocity")
            });
        });
        let mut k = 0;
        group.bench_with_input(BenchmarkId::new("remove_add", n), &n, |b, _| {
            b.iter(|| {
                k = (k + 7919) % n;
                while sim.world().is_vacant(k) {
                    k = (k + 1) % n;
                }
                let (pos, vel, r) = (sim.position(k), sim.world().velocity(k), sim.radius(k));
                sim.remove_body(k).expect("remove");
                // Refused when a body touches it now (rounding puts them a hair too close):
                // the body is then gone, as a game's would be.
                black_box(sim.add_body(BodySpec::new(pos, vel, r)).ok())
            });
        });
        group.bench_with_input(BenchmarkId::new("step_moving", n), &n, |b, _| {
            b.iter(|| black_box(sim.step_event()));
        });
        let mut still = Simulation::new(&gas_with_paddle(n, false), "cells").expect("sim");
        still.run_events(1000);
        group.bench_with_input(BenchmarkId::new("step_static", n), &n, |b, _| {
            b.iter(|| black_box(still.step_event()));
        });
    }
    group.finish();
}

criterion_group!(benches, game_edits);
criterion_main!(benches);

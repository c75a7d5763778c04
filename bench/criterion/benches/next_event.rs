//! Next-event search of the all-pairs oracle and the thesis's `bvh` on 2D gases,
//! n = 64 … 4096.
//!
//! Each iteration is one `Simulation::step_event`: the finder's search for the next event
//! plus its O(1) resolution, so the state evolves as in a real run and the `bvh`'s adaptive Δ
//! is what a run would have. Compare medians across finders at the same n.
//!
//! From the repository's root: `cargo bench --manifest-path bench/criterion/Cargo.toml
//! --bench next_event -- --warm-up-time 1 --measurement-time 3`

use ccdsim::generate::{gas, GasConfig};
use ccdsim::Simulation;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

/// Seed of the benchmark gases.
const SEED: u64 = 2024;
/// Body counts.
const NS: [usize; 7] = [64, 128, 256, 512, 1024, 2048, 4096];
/// Finders compared.
const FINDERS: [&str; 2] = ["all-pairs", "bvh"];

fn next_event(c: &mut Criterion) {
    let mut group = c.benchmark_group("next_event_gas2d");
    group.sample_size(10);
    for n in NS {
        let scene = gas::<2>(&GasConfig {
            n,
            packing: 0.2,
            radius_min: 0.5,
            radius_max: 0.5,
            speed_min: 0.0,
            speed_max: 1.0,
            seed: SEED,
            ..GasConfig::default()
        })
        .expect("gas");
        for finder in FINDERS {
            let mut sim = Simulation::new(&scene, finder).expect("simulation");
            group.bench_with_input(BenchmarkId::new(finder, n), &n, |b, _| {
                b.iter(|| black_box(sim.step_event()));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, next_event);
criterion_main!(benches);

//! Every finder in `FINDER_NAMES` on the thesis benchmark scene (§5.2) at n = 64, 256, 1024:
//! the cost of one event in the steady state (find the next event, resolve it, update the
//! finder) and the cost of setting a finder up for a fresh scene (the BVH's build, the queue's
//! first fill). `next_event.rs` compares all-pairs and bvh on gases up to n = 4096.
//!
//! From the repository's root: `cargo bench --manifest-path bench/criterion/Cargo.toml
//! --bench thesis_scene`

use ccdsim::generate::{thesis, ThesisConfig};
use ccdsim::{Simulation, FINDER_NAMES};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;

const SEED: u64 = 1;
const SIZES: [usize; 3] = [64, 256, 1024];

fn per_event(c: &mut Criterion) {
    let mut g = c.benchmark_group("event");
    g.throughput(Throughput::Elements(1));
    g.measurement_time(Duration::from_secs(4));
    g.warm_up_time(Duration::from_secs(1));
    for &n in &SIZES {
        let scene = thesis::<2>(&ThesisConfig::new(n, SEED)).unwrap();
        for &finder in FINDER_NAMES {
            let mut sim = Simulation::new(&scene, finder).unwrap();
            // Out of the initial transient: a few events per body.
            sim.run_events(4 * n as u64);
            g.bench_with_input(BenchmarkId::new(finder, n), &n, |b, _| {
                b.iter(|| {
                    sim.step_event()
                        .expect("a walled table never runs out of events")
                })
            });
        }
    }
    g.finish();
}

fn setup(c: &mut Criterion) {
    // Building a finder for a fresh scene (the BVH's build, the queue's first fill).
    let mut g = c.benchmark_group("init");
    g.measurement_time(Duration::from_secs(3));
    for &n in &SIZES {
        let scene = thesis::<2>(&ThesisConfig::new(n, SEED)).unwrap();
        for &finder in FINDER_NAMES {
            g.bench_with_input(BenchmarkId::new(finder, n), &n, |b, _| {
                b.iter(|| Simulation::new(&scene, finder).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, per_event, setup);
criterion_main!(benches);

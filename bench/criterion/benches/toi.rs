//! Time-of-impact throughput per pair kind: pairs per second of the pure narrow-phase
//! functions on random approaching and non-approaching motions.

use ccdsim::contact::narrow::{toi_circle_circle, toi_circle_plane, toi_circle_segment};

use ccdsim::Motion;
use ccdsim::Vector;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

const PAIRS: usize = 4096;
const SEED: u64 = 42;

fn motions<const D: usize>(rng: &mut ChaCha8Rng, k: usize) -> Vec<Motion<D>> {
    (0..k)
        .map(|_| {
            let (mut pos, mut vel) = (Vector::<D>::ZERO, Vector::<D>::ZERO);
            for d in 0..D {
                pos[d] = rng.random_range(0.0..50.0);
                vel[d] = rng.random_range(-10.0..10.0);
            }
            Motion {
                pos,
                vel,
                time: rng.random_range(0.0..1.0),
            }
        })
        .collect()
}

fn circle_circle<const D: usize>(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let a = motions::<D>(&mut rng, PAIRS);
    let b = motions::<D>(&mut rng, PAIRS);
    let mut g = c.benchmark_group("toi");
    g.throughput(Throughput::Elements(PAIRS as u64));
    g.bench_function(
        BenchmarkId::new("circle_circle", format!("{D}d")),
        |bench| {
            bench.iter(|| {
                let mut hits = 0u32;
                for (x, y) in a.iter().zip(&b) {
                    hits += u32::from(
                        toi_circle_circle(black_box(x), 1.0, black_box(y), 0.5).is_some(),
                    );
                }
                hits
            })
        },
    );
    g.finish();
}

fn circle_segment(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let m = motions::<2>(&mut rng, PAIRS);
    let ends: Vec<(Vector<2>, Vector<2>)> = motions::<2>(&mut rng, PAIRS)
        .iter()
        .zip(motions::<2>(&mut rng, PAIRS))
        .map(|(p, q)| (p.pos, q.pos))
        .collect();
    let mut g = c.benchmark_group("toi");
    g.throughput(Throughput::Elements(PAIRS as u64));
    g.bench_function(BenchmarkId::new("circle_segment", "2d"), |bench| {
        bench.iter(|| {
            let mut hits = 0u32;
            for (x, &(a, b)) in m.iter().zip(&ends) {
                hits += u32::from(toi_circle_segment(black_box(x), 1.0, a, b).is_some());
            }
            hits
        })
    });
    g.finish();
}

fn circle_plane(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let m = motions::<3>(&mut rng, PAIRS);
    let planes: Vec<(Vector<3>, Vector<3>)> = motions::<3>(&mut rng, PAIRS)
        .iter()
        .map(|p| (p.pos, p.vel))
        .collect();
    let mut g = c.benchmark_group("toi");
    g.throughput(Throughput::Elements(PAIRS as u64));
    g.bench_function(BenchmarkId::new("circle_plane", "3d"), |bench| {
        bench.iter(|| {
            let mut hits = 0u32;
            for (x, &(p, n)) in m.iter().zip(&planes) {
                hits += u32::from(toi_circle_plane(black_box(x), 1.0, p, n).is_some());
            }
            hits
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    circle_circle::<2>,
    circle_circle::<3>,
    circle_segment,
    circle_plane
);
criterion_main!(benches);

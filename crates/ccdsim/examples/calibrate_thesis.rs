//! Calibration of the thesis scene's constants against Table 5.1: runs the scene for 5 simulated
//! seconds at each size over several seeds with the `sedgewick` finder and prints the mean
//! body–body, body–wall and total collision counts beside the thesis's.
//!
//! `cargo run --release -p ccdsim --example calibrate_thesis -- [key=value ...]` with keys
//! `density`, `rmin`, `rmax`, `slowest`, `aspect`, `seeds` (count), `sizes` (comma list),
//! `dim` (2 or 3); unspecified keys keep [`ThesisConfig::default`]'s values.

use ccdsim::generate::{thesis, ThesisConfig, THESIS_DURATION, THESIS_TABLE_5_1};
use ccdsim::{Scene, Simulation};
use std::time::Instant;

fn main() {
    let mut cfg = ThesisConfig::default();
    let mut seeds = 8u64;
    let mut sizes: Vec<usize> = THESIS_TABLE_5_1.iter().map(|r| r.0).collect();
    let mut dim = 2;
    for arg in std::env::args().skip(1) {
        let (k, v) = arg.split_once('=').expect("arguments are key=value");
        match k {
            "density" => cfg.density = v.parse().unwrap(),
            "rmin" => cfg.radius_min = v.parse().unwrap(),
            "rmax" => cfg.radius_max = v.parse().unwrap(),
            "slowest" => cfg.slowest = v.parse().unwrap(),
            "aspect" => cfg.aspect = v.parse().unwrap(),
            "seeds" => seeds = v.parse().unwrap(),
            "dim" => dim = v.parse().unwrap(),
            "sizes" => sizes = v.split(',').map(|s| s.parse().unwrap()).collect(),
            _ => panic!("unknown key {k}"),
        }
    }
    println!("{cfg:?} seeds={seeds}");
    println!(
        "{:>6} {:>10} {:>10} {:>10} {:>10} {:>7} {:>8}",
        "n", "body", "wall", "total", "thesis", "ratio", "seconds"
    );
    for &n in &sizes {
        let (mut body, mut wall, mut secs) = (0.0, 0.0, 0.0);
        for seed in 1..=seeds {
            let c = ThesisConfig {
                n,
                seed,
                ..cfg.clone()
            };
            let t0 = Instant::now();
            let (b, w) = if dim == 2 {
                count(&thesis::<2>(&c).unwrap())
            } else {
                count(&thesis::<3>(&c).unwrap())
            };
            secs += t0.elapsed().as_secs_f64();
            body += b as f64;
            wall += w as f64;
        }
        let k = seeds as f64;
        let (body, wall) = (body / k, wall / k);
        let reference = THESIS_TABLE_5_1
            .iter()
            .find(|r| r.0 == n)
            .map_or(f64::NAN, |r| r.1);
        println!(
            "{n:>6} {body:>10.1} {wall:>10.1} {:>10.1} {reference:>10.1} {:>7.3} {:>8.3}",
            body + wall,
            (body + wall) / reference,
            secs / k
        );
    }
}

/// The body–body and body–wall collision counts of `scene` over the thesis's 5 simulated seconds.
pub fn count<const D: usize>(scene: &Scene<D>) -> (u64, u64) {
    let mut sim = Simulation::new(scene, "sedgewick").unwrap();
    sim.run_until(THESIS_DURATION);
    if std::env::var_os("SHOW_MEMORY").is_some() {
        let (f, w) = sim.finder_mut();
        eprintln!("n={} memory {:?}", w.len(), f.memory());
    }
    (sim.stats().body_collisions, sim.stats().wall_collisions)
}

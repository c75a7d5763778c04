//! The `gas` benchmark: hard discs or spheres in a periodic box started on a lattice with
//! Maxwell velocities, run for a fixed number of collisions. It measures collisions per second
//! and the equation of state: the compressibility factor `Z` and the collision rate with
//! their statistical errors, against the Henderson (2D) and Carnahan–Starling (3D) equations.
//!
//! The run has two phases: `equilibrate` collisions to melt the lattice (not timed, not
//! measured), then `collisions` collisions, timed, split into `blocks` blocks of equal
//! collision counts. Each block gives an estimate of `Z` and of the collision rate; their
//! standard error is the spread of the block estimates over √blocks (block averaging: blocks
//! much longer than the correlation time are independent).
//!
//! Peak memory is the caller's business (the library has no portable way to read it); to keep
//! it low the scene is dropped as soon as the world is built, before the finder allocates.

use ccdsim::finder::{make_finder, FinderMemory, FinderOptions};
use ccdsim::generate::{gas, GasConfig, GenerateError, Lattice};
use ccdsim::geom::ball_volume;
use ccdsim::observables::{observables, temperature};
use ccdsim::sim::{SimError, Simulation};
use ccdsim::world::World;
use std::time::Instant;

/// Parameters of [`gas_bench`].
#[derive(Clone, Debug, PartialEq)]
pub struct GasBenchConfig {
    /// Number of bodies.
    pub n: usize,
    /// Packing fraction in `(0, 1)`.
    pub packing: f64,
    /// Timed and measured collisions.
    pub collisions: u64,
    /// Collisions before the measurement (to melt the lattice); `None`: 20 per body.
    pub equilibrate: Option<u64>,
    /// Blocks the measured collisions are split into for the error estimates (≥ 2).
    pub blocks: usize,
    /// Finder name.
    pub finder: String,
    /// The finder's options.
    pub finder_options: FinderOptions,
    /// Random seed of the velocities.
    pub seed: u64,
}

impl Default for GasBenchConfig {
    fn default() -> Self {
        GasBenchConfig {
            n: 10_000,
            packing: 0.5,
            collisions: 1_000_000,
            equilibrate: None,
            blocks: 20,
            finder: "cells".into(),
            finder_options: FinderOptions::default(),
            seed: 1,
        }
    }
}

/// What [`gas_bench`] measured.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct GasBenchReport {
    /// Dimension.
    pub dim: usize,
    /// Number of bodies.
    pub n: usize,
    /// Packing fraction.
    pub packing: f64,
    /// Finder name.
    pub finder: String,
    /// Collisions run before measuring.
    pub equilibrated: u64,
    /// Collisions timed and measured.
    pub collisions: u64,
    /// Wall-clock seconds of the measured collisions.
    pub seconds: f64,
    /// Measured collisions per wall-clock second.
    pub collisions_per_second: f64,
    /// CPU seconds of the measured collisions, when the caller supplied a CPU clock.
    pub cpu_seconds: Option<f64>,
    /// Measured collisions per CPU second, when known.
    pub collisions_per_cpu_second: Option<f64>,
    /// Simulated time spanned by the measured collisions, seconds.
    pub sim_time: f64,
    /// Kinetic temperature kT.
    pub temperature: f64,
    /// Compressibility factor Z over the measurement.
    pub compressibility: f64,
    /// Standard error of Z from the block estimates.
    pub compressibility_error: f64,
    /// Z from the Henderson (2D) or Carnahan–Starling (3D) equation of state.
    pub compressibility_eos: f64,
    /// Pressure over the measurement.
    pub pressure: f64,
    /// Collisions per body per unit time.
    pub collision_rate: f64,
    /// Standard error of the collision rate.
    pub collision_rate_error: f64,
    /// Collision rate the equation of state implies (Enskog: from `Z_eos`).
    pub collision_rate_eos: f64,
    /// Blocks used for the errors.
    pub blocks: usize,
    /// Memory of the finder's structures, if it reports it.
    pub finder_bytes: Option<usize>,
    /// Box exits applied during the measurement (not collisions).
    pub exits: u64,
    /// The finder's internal work during the measurement (see
    /// [`Finder::counters`](ccdsim::Finder::counters)): name and count.
    pub finder_counters: std::collections::BTreeMap<String, u64>,
}

/// Why the benchmark could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GasBenchError {
    /// The scene could not be generated.
    #[error(transparent)]
    Generate(#[from] GenerateError),
    /// The simulation could not be set up.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A parameter is out of range.
    #[error("{0}")]
    Param(String),
}

/// Henderson's equation of state for hard discs at area fraction `eta`:
/// `Z = (1 + η²/8) / (1 − η)²`.
#[must_use]
pub fn henderson_z(eta: f64) -> f64 {
    (1.0 + eta * eta / 8.0) / ((1.0 - eta) * (1.0 - eta))
}

/// The Carnahan–Starling equation of state for hard spheres at volume fraction `eta`:
/// `Z = (1 + η + η² − η³) / (1 − η)³`.
#[must_use]
pub fn carnahan_starling_z(eta: f64) -> f64 {
    (1.0 + eta + eta * eta - eta * eta * eta) / (1.0 - eta).powi(3)
}

/// The equation of state for dimension `D`: Henderson in 2D, Carnahan–Starling in 3D.
#[must_use]
pub fn eos_z<const D: usize>(eta: f64) -> f64 {
    if D == 2 {
        henderson_z(eta)
    } else {
        carnahan_starling_z(eta)
    }
}

/// The collision rate per body of equal hard bodies of diameter `sigma` and mass `m` at
/// temperature `kt` whose compressibility factor is `z` (Enskog):
/// `Γ = (Z − 1) · (2D / σ) · √(kT / (π m))`.
///
/// It follows from the virial, each collision contributing `σ` times the normal relative
/// momentum, whose mean over colliding pairs at contact is `√(π m kT)`.
#[must_use]
pub fn enskog_collision_rate<const D: usize>(z: f64, sigma: f64, kt: f64, m: f64) -> f64 {
    (z - 1.0) * (2.0 * D as f64 / sigma) * (kt / (std::f64::consts::PI * m)).sqrt()
}

/// Runs the gas benchmark in `D` dimensions: `n` unit-radius-½ bodies (diameter 1, unit
/// density) at kT = 1 in a periodic box, lattice start. `cpu_clock`, if given, reads the
/// process's CPU time in seconds; `progress(done, total)` is called now and then.
pub fn gas_bench<const D: usize>(
    cfg: &GasBenchConfig,
    cpu_clock: Option<&dyn Fn() -> f64>,
    mut progress: impl FnMut(u64, u64),
) -> Result<GasBenchReport, GasBenchError> {
    if cfg.blocks < 2 || cfg.collisions < cfg.blocks as u64 {
        return Err(GasBenchError::Param(
            "need at least 2 blocks and one collision per block".into(),
        ));
    }
    let radius = 0.5;
    let scene = gas::<D>(&GasConfig {
        n: cfg.n,
        packing: cfg.packing,
        radius_min: radius,
        radius_max: radius,
        seed: cfg.seed,
        periodic: true,
        lattice: Some(Lattice::Densest),
        temperature: Some(1.0),
        ..GasConfig::default()
    })?;
    let world = World::from_owned_scene(scene).map_err(SimError::from)?;
    let finder = make_finder::<D>(&cfg.finder, &cfg.finder_options).map_err(SimError::from)?;
    let mut sim = Simulation::from_world(world, finder)?;
    let equilibrate = cfg.equilibrate.unwrap_or(20 * cfg.n as u64);
    let total = equilibrate + cfg.collisions;
    let chunk = (total / 200).max(1000);
    let mut done = 0;
    while done < equilibrate {
        let step = chunk.min(equilibrate - done);
        let ran = sim.run_events(step);
        done += ran;
        progress(done, total);
        if ran < step {
            return Err(GasBenchError::Param("the gas stopped colliding".into()));
        }
    }
    let start = *sim.stats();
    let counters_start = sim.finder_mut().0.counters();
    let t_start = sim.time();
    let clock = Instant::now();
    let cpu_start = cpu_clock.map(|c| c());
    let mut block_z = Vec::with_capacity(cfg.blocks);
    let mut block_rate = Vec::with_capacity(cfg.blocks);
    let mut measured = 0u64;
    for b in 0..cfg.blocks {
        let target = cfg.collisions * (b as u64 + 1) / cfg.blocks as u64;
        let (before, t0) = (*sim.stats(), sim.time());
        while measured < target {
            let step = chunk.min(target - measured);
            let ran = sim.run_events(step);
            measured += ran;
            progress(equilibrate + measured, total);
            if ran < step {
                return Err(GasBenchError::Param("the gas stopped colliding".into()));
            }
        }
        let after = sim.stats();
        let o = observables(
            sim.world(),
            after.body_collisions - before.body_collisions,
            after.virial - before.virial,
            sim.time() - t0,
        );
        block_z.push(o.compressibility.unwrap_or(f64::NAN));
        block_rate.push(o.collision_rate);
    }
    let seconds = clock.elapsed().as_secs_f64();
    let cpu_seconds = match (cpu_clock, cpu_start) {
        (Some(c), Some(s)) => Some(c() - s),
        _ => None,
    };
    let end = *sim.stats();
    let finder_counters = sim
        .finder_mut()
        .0
        .counters()
        .into_iter()
        .map(|(name, count)| {
            let before = counters_start
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(0, |c| c.1);
            (name.to_string(), count - before)
        })
        .collect();
    let span = sim.time() - t_start;
    let whole = observables(
        sim.world(),
        end.body_collisions - start.body_collisions,
        end.virial - start.virial,
        span,
    );
    let kt = temperature(sim.world());
    let z_eos = eos_z::<D>(cfg.packing);
    let mass = ball_volume::<D>(radius);
    Ok(GasBenchReport {
        dim: D,
        n: cfg.n,
        packing: cfg.packing,
        finder: cfg.finder.clone(),
        equilibrated: equilibrate,
        collisions: measured,
        seconds,
        collisions_per_second: measured as f64 / seconds,
        cpu_seconds,
        collisions_per_cpu_second: cpu_seconds.map(|c| measured as f64 / c),
        sim_time: span,
        temperature: kt,
        compressibility: whole.compressibility.unwrap_or(f64::NAN),
        compressibility_error: standard_error(&block_z),
        compressibility_eos: z_eos,
        pressure: whole.pressure.unwrap_or(f64::NAN),
        collision_rate: whole.collision_rate,
        collision_rate_error: standard_error(&block_rate),
        collision_rate_eos: enskog_collision_rate::<D>(z_eos, 2.0 * radius, kt, mass),
        blocks: cfg.blocks,
        finder_bytes: sim
            .finder_mut()
            .0
            .memory()
            .map(|m: FinderMemory| m.peak_bytes),
        exits: end.exits - start.exits,
        finder_counters,
    })
}

/// Standard error of the mean of independent estimates: their sample standard deviation over
/// √count.
#[must_use]
pub fn standard_error(values: &[f64]) -> f64 {
    let k = values.len() as f64;
    if k < 2.0 {
        return f64::NAN;
    }
    let mean = values.iter().sum::<f64>() / k;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (k - 1.0);
    (var / k).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equations_of_state() {
        assert!((henderson_z(0.5) - 4.125).abs() < 1e-12);
        assert!((carnahan_starling_z(0.45) - 1.561375 / 0.166375).abs() < 1e-12);
        assert_eq!(eos_z::<2>(0.0), 1.0);
        assert_eq!(enskog_collision_rate::<3>(1.0, 1.0, 1.0, 1.0), 0.0);
        assert!((standard_error(&[1.0, 3.0]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn small_gas_matches_the_equation_of_state_roughly() {
        // A short run: Z within 5 % of Henderson, and the collision rate consistent with Z
        // (the Enskog relation holds for the measured Z up to the measured errors).
        let report = gas_bench::<2>(
            &GasBenchConfig {
                n: 400,
                packing: 0.3,
                collisions: 200_000,
                ..GasBenchConfig::default()
            },
            None,
            |_, _| {},
        )
        .unwrap();
        assert_eq!(report.collisions, 200_000);
        assert!((report.temperature - 1.0).abs() < 1e-9);
        let z = report.compressibility;
        assert!(
            (z / report.compressibility_eos - 1.0).abs() < 0.05,
            "Z = {z}"
        );
        assert!(report.compressibility_error > 0.0 && report.compressibility_error < 0.05);
        let mass = ball_volume::<2>(0.5);
        let implied = enskog_collision_rate::<2>(z, 1.0, report.temperature, mass);
        assert!((report.collision_rate / implied - 1.0).abs() < 0.02);
    }
}

//! The `rough-cooling` check: a homogeneous cooling gas of rough spheres (3D, periodic box)
//! against kinetic theory (Huthmann & Zippelius, Phys. Rev. E 56, R6275, 1997; Luding,
//! Huthmann, McNamara & Zippelius, Phys. Rev. E 58, 3416, 1998), in the Maxwellian
//! approximation: velocities and spins Gaussian and uncorrelated.
//!
//! Spheres of mass `m`, radius `a` and inertia `q·m·a²` collide with normal restitution `e`
//! and tangential restitution `β`. With `η = q(1+β)/(2(1+q))` the theory's coefficients are
//! `A = (1−e²)/4 + η(1−η)`, `B = η²/q` and `C = (η/q)(1−η/q)`: averaged over collisions, a
//! collision changes the pair's translational energy by `−4(A·T_tr − B·T_rot)` and its
//! rotational energy by `4(B·T_tr − C·T_rot)` (colliding pairs meet with a mean square
//! normal velocity `4T_tr/m`, and carry `4T_tr/m` of tangential relative velocity and
//! `4T_rot/(q m)` from the spins). Spheres hold `3/2·T` in each kind of energy, and `N/2`
//! collisions make one collision per body, so in collisions per body (`τ = 2C/N`)
//!
//! * `dT_tr/dτ = −(4/3)(A·T_tr − B·T_rot)` and `dT_rot/dτ = (4/3)(B·T_tr − C·T_rot)`;
//! * the ratio `r = T_rot/T_tr` settles at the positive root of `B r² + (C − A) r − B = 0`,
//!   `r = h + √(1 + h²)` with `h = (A − C)/(2B)` (the same equations with the rotational one
//!   doubled, `B r² + (2C − A) r − 2B = 0`, weigh rotation as one degree of freedom against
//!   three, which is not a sphere's);
//! * then `T_tr` decays as `exp(−λτ)` with `λ = (4/3)(A − B·r)` (for smooth spheres
//!   `(1 − e²)/3`), and, the collision rate being proportional to `√T_tr`, both temperatures
//!   follow Haff's law `T(t) = T(0)/(1 + t/t₀)²`: `1/√T_tr` grows linearly in time.
//!
//! The gas starts in equipartition (`T_rot = T_tr = 1`, spins Maxwell distributed) at random
//! positions; the ratio is measured over the last half of the run, the decay rate `λ` fitted
//! to `ln T_tr` against `τ` there, and Haff's law checked by the straightness (R²) of
//! `1/√T_tr` against `t` over the same stretch.

use crate::check_error::CheckError;
use crate::line_fit::line_fit;
use ccdsim::generate::{gas, GasConfig};
use ccdsim::motion::Spin;
use ccdsim::observables::{rotational_temperature, temperature};
use ccdsim::sim::Simulation;
use ccdsim::Scene;

/// Parameters of [`rough_cooling`].
#[derive(Clone, Debug, PartialEq)]
pub struct CoolingConfig {
    /// Number of spheres (radius ½, unit density).
    pub n: usize,
    /// Volume fraction.
    pub packing: f64,
    /// Normal restitution `e`.
    pub restitution: f64,
    /// Tangential restitution `β`.
    pub tangential_restitution: f64,
    /// Moment-of-inertia factor `q`.
    pub inertia: f64,
    /// The TC model's time, seconds (the gas starts at kT = 1, where a sphere's mean free
    /// time is about 1 s).
    pub tc: f64,
    /// Collisions per body run before measuring, for the ratio to settle; `None`:
    /// [`default_settle`].
    pub settle: Option<f64>,
    /// Collisions per body measured after settling.
    pub collisions_per_body: f64,
    /// Temperature samples over the run.
    pub samples: usize,
    /// Seed of positions, velocities and spins.
    pub seed: u64,
}

impl Default for CoolingConfig {
    fn default() -> Self {
        CoolingConfig {
            n: 10_000,
            packing: 0.01,
            restitution: 0.9,
            tangential_restitution: 0.0,
            inertia: 0.4,
            tc: 1e-4,
            settle: None,
            collisions_per_body: 20.0,
            samples: 40,
            seed: 1,
        }
    }
}

/// One sample of a cooling run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CoolingSample {
    /// Body–body collisions per body so far, `2C/N`.
    pub collisions_per_body: f64,
    /// Simulated time, seconds.
    pub time: f64,
    /// Translational temperature kT_tr.
    pub temperature: f64,
    /// Rotational temperature kT_rot.
    pub rotational_temperature: f64,
}

/// What [`rough_cooling`] measured, beside the theory.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CoolingReport {
    /// Number of spheres.
    pub n: usize,
    /// Volume fraction.
    pub packing: f64,
    /// Normal restitution `e`.
    pub restitution: f64,
    /// Tangential restitution `β`.
    pub tangential_restitution: f64,
    /// Inertia factor `q`.
    pub inertia: f64,
    /// The samples, from the start.
    pub samples: Vec<CoolingSample>,
    /// Collisions per body run before measuring.
    pub settle: f64,
    /// `T_rot/T_tr` averaged over the samples measured (after settling).
    pub ratio: f64,
    /// The ratio kinetic theory predicts ([`huthmann_zippelius_ratio`]).
    pub ratio_theory: f64,
    /// Fitted decay rate of `T_tr` per collision per body over the samples measured.
    pub decay: f64,
    /// The theory's decay rate `(4/3)(A − B r)` ([`cooling_decay`]).
    pub decay_theory: f64,
    /// R² of the straight line through `1/√T_tr` against time over the samples measured (1
    /// for Haff's law).
    pub haff_r2: f64,
    /// Relative change of the total kinetic energy (translational plus rotational) over the
    /// run: 0 to rounding when `e = 1` and `β = ±1`.
    pub energy_change: f64,
    /// Collisions run.
    pub collisions: u64,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
}

/// Why the check could not run (see [`CheckError`]).
pub type CoolingError = CheckError;

/// The coefficients `(A, B, C)` of the theory for restitution `e`, tangential restitution
/// `β` and inertia factor `q` (see the module docs).
#[must_use]
pub fn cooling_coefficients(e: f64, beta: f64, q: f64) -> (f64, f64, f64) {
    let eta = q * (1.0 + beta) / (2.0 * (1.0 + q));
    let a = (1.0 - e * e) / 4.0 + eta * (1.0 - eta);
    let b = eta * eta / q;
    let c = (eta / q) * (1.0 - eta / q);
    (a, b, c)
}

/// The ratio `T_rot/T_tr` a homogeneous cooling gas of rough spheres settles at: the positive
/// root of `B r² + (C − A) r − B = 0`, `h + √(1 + h²)` with `h = (A − C)/(2B)` (see the
/// module docs; for smooth spheres, `B = 0`, spins decouple and there is no such ratio: NaN).
#[must_use]
pub fn huthmann_zippelius_ratio(e: f64, beta: f64, q: f64) -> f64 {
    let (a, b, c) = cooling_coefficients(e, beta, q);
    if b == 0.0 {
        return f64::NAN;
    }
    let h = (a - c) / (2.0 * b);
    h + (1.0 + h * h).sqrt()
}

/// The decay rate of `T_tr` per collision per body once the ratio has settled,
/// `(4/3)·(A − B·r)` (for smooth spheres `(1 − e²)/3`).
#[must_use]
pub fn cooling_decay(e: f64, beta: f64, q: f64) -> f64 {
    let (a, b, _) = cooling_coefficients(e, beta, q);
    let r = huthmann_zippelius_ratio(e, beta, q);
    let r = if r.is_nan() { 0.0 } else { r };
    4.0 / 3.0 * (a - b * r)
}

/// The rate, per collision per body, at which `T_rot/T_tr` relaxes to its settled value
/// (the linearised theory): `(4/3)·2B·√(1 + h²)`; 0 for smooth spheres.
#[must_use]
pub fn ratio_relaxation(e: f64, beta: f64, q: f64) -> f64 {
    let (a, b, c) = cooling_coefficients(e, beta, q);
    if b == 0.0 {
        return 0.0;
    }
    let h = (a - c) / (2.0 * b);
    4.0 / 3.0 * 2.0 * b * (1.0 + h * h).sqrt()
}

/// Collisions per body a gas starting in equipartition needs for its ratio `T_rot/T_tr` to
/// settle: eight of the ratio's relaxation times ([`ratio_relaxation`]; the linearised rate
/// overstates the pace far from the settled ratio, as from 1 to 4 at `e = 0.7`, `β = −0.5`),
/// at least 10.
#[must_use]
pub fn default_settle(e: f64, beta: f64, q: f64) -> f64 {
    let rate = ratio_relaxation(e, beta, q);
    if rate > 0.0 {
        (8.0 / rate).max(10.0)
    } else {
        10.0
    }
}

/// The scene: `n` spheres at random positions, Maxwell velocities and spins at kT = 1.
fn cooling_scene(cfg: &CoolingConfig) -> Result<Scene<3>, CoolingError> {
    let gas_of = |seed| {
        gas::<3>(&GasConfig {
            n: cfg.n,
            packing: cfg.packing,
            radius_min: 0.5,
            radius_max: 0.5,
            seed,
            periodic: true,
            temperature: Some(1.0),
            ..GasConfig::default()
        })
    };
    let mut scene = gas_of(cfg.seed)?;
    // A second gas's Maxwell velocities, at the same kT, scaled by 1/(√q·a), are Maxwell
    // spins at kT_rot = 1: q·m·a²·ω² = m·v².
    let spins = gas_of(cfg.seed.wrapping_add(0x5eed))?;
    let scale = 1.0 / (cfg.inertia.sqrt() * 0.5);
    for (b, s) in scene.bodies.iter_mut().zip(&spins.bodies) {
        b.spin = Some(Spin::Spatial((s.vel * scale).0));
        b.inertia = Some(cfg.inertia);
    }
    scene.settings.restitution = cfg.restitution;
    scene.settings.tangential_restitution = Some(cfg.tangential_restitution);
    scene.settings.tc = Some(cfg.tc);
    Ok(scene)
}

/// Runs one homogeneous cooling gas; `progress(done, total)` is called now and then with
/// collisions.
pub fn rough_cooling(
    cfg: &CoolingConfig,
    mut progress: impl FnMut(u64, u64),
) -> Result<CoolingReport, CoolingError> {
    if cfg.samples < 4 || cfg.collisions_per_body.is_nan() || cfg.collisions_per_body <= 0.0 {
        return Err(CoolingError::Param(
            "need at least 4 samples and a positive number of collisions per body".into(),
        ));
    }
    let scene = cooling_scene(cfg)?;
    let start = std::time::Instant::now();
    let mut sim = Simulation::new(&scene, "cells")?;
    drop(scene);
    let energy = |sim: &Simulation<3>| {
        let w = sim.world();
        w.kinetic_energy_at(sim.time()) + w.rotational_energy()
    };
    let e0 = energy(&sim);
    let n = cfg.n as f64;
    let (e, beta, q) = (cfg.restitution, cfg.tangential_restitution, cfg.inertia);
    let settle = cfg.settle.unwrap_or_else(|| default_settle(e, beta, q));
    let to_collisions = |per_body: f64| (per_body * n / 2.0).ceil() as u64;
    let settled = to_collisions(settle);
    let total = to_collisions(settle + cfg.collisions_per_body);
    let sample = |sim: &Simulation<3>| CoolingSample {
        collisions_per_body: 2.0 * sim.stats().body_collisions as f64 / n,
        time: sim.time(),
        temperature: temperature(sim.world()),
        rotational_temperature: rotational_temperature(sim.world()).unwrap_or(0.0),
    };
    // As many samples while settling as while measuring, per collision.
    let before = ((cfg.samples as f64 * settle / cfg.collisions_per_body).ceil() as u64).max(1);
    let targets: Vec<u64> = (1..=before)
        .map(|k| settled * k / before)
        .chain(
            (1..=cfg.samples as u64).map(|k| settled + (total - settled) * k / cfg.samples as u64),
        )
        .collect();
    let mut samples = vec![sample(&sim)];
    for target in targets {
        while sim.stats().body_collisions < target {
            let want = target - sim.stats().body_collisions;
            if sim.run_events(want) == 0 {
                return Err(CoolingError::Param(
                    "the gas stopped colliding (collapse: raise --tc)".into(),
                ));
            }
        }
        samples.push(sample(&sim));
        progress(sim.stats().body_collisions, total);
    }
    let late = &samples[samples.len() - cfg.samples - 1..];
    let ratio = late
        .iter()
        .map(|s| s.rotational_temperature / s.temperature)
        .sum::<f64>()
        / late.len() as f64;
    let by_collisions: Vec<(f64, f64)> = late
        .iter()
        .map(|s| (s.collisions_per_body, s.temperature.ln()))
        .collect();
    let by_time: Vec<(f64, f64)> = late
        .iter()
        .map(|s| (s.time, 1.0 / s.temperature.sqrt()))
        .collect();
    Ok(CoolingReport {
        settle,
        n: cfg.n,
        packing: cfg.packing,
        restitution: e,
        tangential_restitution: beta,
        inertia: q,
        ratio,
        ratio_theory: huthmann_zippelius_ratio(e, beta, q),
        decay: -line_fit(&by_collisions).slope,
        decay_theory: cooling_decay(e, beta, q),
        haff_r2: line_fit(&by_time).r2,
        energy_change: (energy(&sim) - e0) / e0,
        collisions: sim.stats().body_collisions,
        seconds: start.elapsed().as_secs_f64(),
        samples,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ratio_solves_the_quadratic_and_perfectly_rough_elastic_spheres_equipartition() {
        let r = huthmann_zippelius_ratio(1.0, 1.0, 0.4);
        assert!((r - 1.0).abs() < 1e-12, "{r}");
        for (e, beta) in [(0.7, -0.5), (0.9, 0.0), (0.99, 0.5)] {
            let (a, b, c) = cooling_coefficients(e, beta, 0.4);
            let r = huthmann_zippelius_ratio(e, beta, 0.4);
            assert!(r > 0.0);
            assert!((b * r * r + (c - a) * r - b).abs() < 1e-12);
        }
        // Smooth spheres: Haff's decay (1 − e²)/3 per collision per body.
        assert!((cooling_decay(0.9, -1.0, 0.4) - 0.19 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn a_small_cooling_gas_runs_and_loses_energy() {
        let report = rough_cooling(
            &CoolingConfig {
                n: 200,
                settle: Some(2.0),
                collisions_per_body: 4.0,
                samples: 4,
                ..CoolingConfig::default()
            },
            |_, _| {},
        )
        .unwrap();
        assert_eq!(report.samples.len(), 7);
        assert!((report.samples[0].rotational_temperature - 1.0).abs() < 1e-12);
        assert!(report.energy_change < 0.0);
        assert!(report.samples[6].temperature < report.samples[0].temperature);
        assert!((report.samples[6].collisions_per_body - 6.0).abs() < 0.01);
    }
}

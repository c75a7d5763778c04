//! The `shear` check: hard spheres in simple shear (Lees–Edwards boundaries, 3D) against
//! kinetic theory.
//!
//! Units: diameter `σ = 1`, mass `m = π/6` (unit density), `kT = 1` at the start; a shear
//! rate is given reduced, `γ̇* = γ̇ σ √(m/kT)`, and a viscosity is reported reduced,
//! `η* = η σ² / √(m kT)`, which for hard spheres depends on the volume fraction `φ` and `γ̇*`
//! only.
//!
//! * **Elastic spheres**: the viscosity `η = −P_xy / γ̇` (collision virial plus kinetic part in
//!   peculiar velocities, [`ccdsim::observables::PressureTensor`]) against Enskog's,
//!   `η_E = η₀ [1/g + (4/5)·4φ + 0.7614·(4φ)²·g]`, with the dilute viscosity at its second
//!   Sonine approximation `η₀ = 1.016 · (5/16) √(m kT/π) / σ²` and the Carnahan–Starling
//!   contact value `g = (1 − φ/2)/(1 − φ)³` (Chapman & Cowling, *The Mathematical Theory of
//!   Non-uniform Gases*, ch. 16). The heat the shear makes is taken out by rescaling the
//!   peculiar velocities to `kT = 1` after every block of collisions (an isokinetic
//!   thermostat; the run files of such a run record these rescalings as velocity edits).
//!   Runs at several rates give `η*(γ̇*)`, extrapolated linearly to `γ̇* → 0`.
//! * **Granular spheres** (`e < 1`, no thermostat): the gas settles where the shear's heating
//!   `−P_xy γ̇ V` balances what the collisions dissipate. Both are measured, independently:
//!   the heating from the stress, the dissipation from each collision's energy loss in the
//!   frame of the images that met. Their ratio must be 1; the temperature is given beside
//!   the Navier–Stokes estimate `η(T) γ̇² = (3/2) n T ζ(T)`, `ζ = (1 − e²) ω_E / 3`,
//!   `ω_E = 4 n σ² g √(π kT/m)` (Enskog's collision frequency), which neglects the
//!   non-Newtonian effects of strong shear.
//! * The velocity profile: the mean `v_x` in ten slabs along y, sampled after every block,
//!   and its least-squares slope against the imposed `γ̇`.

use crate::check_error::CheckError;
use crate::line_fit::line_fit;
use ccdsim::contact::lees_edwards::ShearedBox;
use ccdsim::generate::{gas, GasConfig};
use ccdsim::observables::{temperature, PressureTensor};
use ccdsim::sim::Simulation;
use ccdsim::{Collision, EventKind, Vector};

/// Mass of a sphere of diameter 1 at unit density.
const MASS: f64 = std::f64::consts::PI / 6.0;

/// Slabs of the velocity profile.
const SLABS: usize = 10;

/// Parameters of [`shear_run`].
#[derive(Clone, Debug, PartialEq)]
pub struct ShearConfig {
    /// Number of spheres (diameter 1, unit density).
    pub n: usize,
    /// Volume fraction.
    pub packing: f64,
    /// Reduced shear rate `γ̇*`.
    pub rate: f64,
    /// Normal restitution `e` (1: elastic, thermostatted; below 1: granular, free).
    pub restitution: f64,
    /// The TC model's time, seconds (granular runs).
    pub tc: f64,
    /// Collisions per body before measuring.
    pub settle: f64,
    /// Collisions per body measured.
    pub collisions_per_body: f64,
    /// Collisions per body in a block (a rescaling and a profile sample after each).
    pub block: f64,
    /// Seed of the start.
    pub seed: u64,
}

impl Default for ShearConfig {
    fn default() -> Self {
        ShearConfig {
            n: 2000,
            packing: 0.1,
            rate: 0.1,
            restitution: 1.0,
            tc: 1e-4,
            settle: 20.0,
            collisions_per_body: 200.0,
            block: 1.0,
            seed: 1,
        }
    }
}

/// What [`shear_run`] measured.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ShearReport {
    /// Spheres.
    pub n: usize,
    /// Volume fraction.
    pub packing: f64,
    /// Reduced shear rate `γ̇*` imposed.
    pub rate: f64,
    /// Normal restitution.
    pub restitution: f64,
    /// Mean temperature over the measurement (peculiar velocities), kT.
    pub temperature: f64,
    /// Reduced viscosity `η* = −P_xy / (γ̇ √(m kT))` with the mean temperature.
    pub viscosity: f64,
    /// Its standard error (ten batches of blocks).
    pub viscosity_error: f64,
    /// Enskog's reduced viscosity at this volume fraction ([`enskog_viscosity`]).
    pub enskog: f64,
    /// Slope of the measured velocity profile over the imposed rate.
    pub profile_slope: f64,
    /// Largest deviation of a slab's mean `v_x` from the imposed flow, over `γ̇ L_y`.
    pub profile_deviation: f64,
    /// The mean `v_x` per slab (centre `y`, `v_x`), m/s.
    pub profile: Vec<(f64, f64)>,
    /// Heating by the shear per sphere, `−P_xy γ̇ V / N`, J/s.
    pub heating: f64,
    /// Energy the collisions dissipated per sphere and second (granular runs; 0 elastic).
    pub dissipation: f64,
    /// Granular runs: the Navier–Stokes estimate of the steady temperature (see the module
    /// docs); `None` for elastic ones.
    pub temperature_theory: Option<f64>,
    /// Body collisions measured.
    pub collisions: u64,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
}

/// Why the check could not run (see [`CheckError`]).
pub type ShearError = CheckError;

/// The Carnahan–Starling contact value of the pair correlation at volume fraction `phi`.
#[must_use]
pub fn contact_value(phi: f64) -> f64 {
    (1.0 - phi / 2.0) / (1.0 - phi).powi(3)
}

/// Enskog's reduced shear viscosity `η σ²/√(m kT)` of hard spheres at volume fraction `phi`
/// (see the module docs).
#[must_use]
pub fn enskog_viscosity(phi: f64) -> f64 {
    let eta0 = 1.016 * 5.0 / (16.0 * std::f64::consts::PI.sqrt());
    let (y, g) = (4.0 * phi, contact_value(phi));
    eta0 * (1.0 / g + 0.8 * y + 0.7614 * y * y * g)
}

/// The Navier–Stokes estimate of a sheared granular gas's steady temperature, kT, for
/// spheres of diameter 1 and mass `π/6` at volume fraction `phi`, restitution `e` and shear
/// rate `rate` (1/s, not reduced).
#[must_use]
pub fn granular_temperature(phi: f64, e: f64, rate: f64) -> f64 {
    let n = 6.0 * phi / std::f64::consts::PI;
    let g = contact_value(phi);
    // η* √(m T) γ̇² = (3/2) n T (1 − e²)/3 · 4 n g √(π T / m):  T = η* m γ̇² / (2 n² g (1 − e²) √π).
    enskog_viscosity(phi) * MASS * rate * rate
        / (2.0 * n * n * g * (1.0 - e * e) * std::f64::consts::PI.sqrt())
}

/// Each body's last recorded state, to take the energy a collision dissipates in the frame
/// of the images that met.
struct Dissipation {
    last: Vec<(Vector<3>, Vector<3>, f64)>,
    bx: ShearedBox<3>,
    lost: f64,
}

impl Dissipation {
    fn new(sim: &Simulation<3>, bx: ShearedBox<3>) -> Self {
        let w = sim.world();
        let last = (0..w.len())
            .map(|i| (sim.position(i), w.velocity(i), sim.time()))
            .collect();
        Dissipation {
            last,
            bx,
            lost: 0.0,
        }
    }

    /// Body `i`'s velocity just before `t`, in the frame of its image recorded at `at`.
    fn before(&self, i: usize, at: Vector<3>, t: f64) -> Vector<3> {
        let (p, v, t0) = self.last[i];
        let layer = self.bx.nearest_image(at - (p + v * (t - t0)), t).1;
        self.bx.image_velocity(v, -layer)
    }

    fn observe(&mut self, c: &Collision<3>) {
        let t = c.event.time;
        let a = c.event.a as usize;
        if c.event.kind == EventKind::Body {
            let b = c.event.b as usize;
            let (va, vb) = (self.before(a, c.pos[0], t), self.before(b, c.pos[1], t));
            let layer = self.bx.nearest_image(c.pos[1] - c.pos[0], t).1;
            let (vb, vb2) = (
                self.bx.image_velocity(vb, layer),
                self.bx.image_velocity(c.vel[1], layer),
            );
            let change = c.vel[0].norm_sq() - va.norm_sq() + vb2.norm_sq() - vb.norm_sq();
            self.lost -= 0.5 * MASS * change;
            self.last[b] = (c.pos[1], c.vel[1], t);
        }
        self.last[a] = (c.pos[0], c.vel[0], t);
    }
}

/// Mean and standard error of `values` from `batches` batch means.
fn batch_mean(values: &[f64], batches: usize) -> (f64, f64) {
    let n = values.len();
    let mean = values.iter().sum::<f64>() / n as f64;
    let size = n / batches;
    if size == 0 || batches < 2 {
        return (mean, f64::NAN);
    }
    let means: Vec<f64> = (0..batches)
        .map(|b| values[b * size..(b + 1) * size].iter().sum::<f64>() / size as f64)
        .collect();
    let m = means.iter().sum::<f64>() / batches as f64;
    let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (batches - 1) as f64;
    (mean, (var / batches as f64).sqrt())
}

/// Runs one sheared gas; `progress(done, total)` is called after every block with
/// collisions.
pub fn shear_run(
    cfg: &ShearConfig,
    mut progress: impl FnMut(u64, u64),
) -> Result<ShearReport, ShearError> {
    let bad = |what: &str| Err(ShearError::Param(what.into()));
    if !(cfg.rate > 0.0 && cfg.rate.is_finite()) {
        return bad("the shear rate must be positive");
    }
    if !(cfg.block > 0.0 && cfg.collisions_per_body >= 10.0 * cfg.block && cfg.settle >= 0.0) {
        return bad("need blocks of positive length and at least ten of them measured");
    }
    let mut scene = gas::<3>(&GasConfig {
        n: cfg.n,
        packing: cfg.packing,
        radius_min: 0.5,
        radius_max: 0.5,
        seed: cfg.seed,
        periodic: true,
        temperature: Some(1.0),
        ..GasConfig::default()
    })?;
    let rate = cfg.rate / MASS.sqrt();
    let size = scene.periodic.expect("a periodic gas");
    let bx = ShearedBox { size, rate };
    for b in &mut scene.bodies {
        b.vel[0] += bx.flow(b.pos[1]);
    }
    scene.settings.shear_rate = Some(rate);
    let elastic = cfg.restitution >= 1.0;
    if !elastic {
        scene.settings.restitution = cfg.restitution;
        scene.settings.tc = Some(cfg.tc);
    }
    let start = std::time::Instant::now();
    let mut sim = Simulation::new(&scene, "cells")?;
    drop(scene);
    let n = cfg.n as f64;
    let volume: f64 = size.0.iter().product();
    let to_collisions = |per_body: f64| (per_body * n / 2.0).ceil() as u64;
    let block = to_collisions(cfg.block).max(1);
    let settled = to_collisions(cfg.settle);
    let total = settled + to_collisions(cfg.collisions_per_body);
    // The isokinetic thermostat: peculiar velocities scaled back to kT = 1.
    let rescale = |sim: &mut Simulation<3>| -> Result<(), ShearError> {
        let scale = (1.0 / temperature(sim.world())).sqrt();
        for i in 0..sim.world().len() {
            let y = sim.position(i)[1];
            let mut v = sim.world().velocity(i);
            v[0] = bx.flow(y) + (v[0] - bx.flow(y)) * scale;
            sim.set_velocity(i, v)?;
        }
        Ok(())
    };
    let (mut stresses, mut temperatures) = (Vec::new(), Vec::new());
    let mut profile = [(0.0f64, 0u64); SLABS];
    let (mut heating, mut span) = (0.0, 0.0);
    let mut dissipation = Dissipation::new(&sim, bx);
    let mut measure_start = None;
    while sim.stats().body_collisions < total {
        let measuring = sim.stats().body_collisions >= settled;
        if measuring && measure_start.is_none() {
            measure_start = Some(sim.time());
            dissipation = Dissipation::new(&sim, bx);
        }
        let mut p = PressureTensor::new(&sim).map_err(ShearError::Param)?;
        let (t0, kt0) = (sim.time(), temperature(sim.world()));
        let target = sim.stats().body_collisions + block;
        while sim.stats().body_collisions < target {
            let want = target - sim.stats().body_collisions;
            let done = sim.run_events_with(want, |c| {
                p.observe(c);
                // Elastic runs dissipate nothing, and their rescalings are not collisions.
                if measuring && !elastic {
                    dissipation.observe(c);
                }
            });
            if done == 0 {
                return bad("the gas stopped colliding (collapse: raise --tc)");
            }
        }
        let t = p.tensor(sim.time());
        let stress = -0.5 * (t[0][1] + t[1][0]);
        let kt = 0.5 * (kt0 + temperature(sim.world()));
        if measuring {
            let dt = sim.time() - t0;
            stresses.push(stress / (rate * (MASS * kt).sqrt()));
            temperatures.push(kt);
            heating += stress * rate * volume / n * dt;
            span += dt;
            for i in 0..sim.world().len() {
                let y = sim.position(i)[1];
                let slab = ((y / size[1] * SLABS as f64) as usize).min(SLABS - 1);
                profile[slab].0 += sim.world().velocity(i)[0];
                profile[slab].1 += 1;
            }
        }
        if elastic {
            rescale(&mut sim)?;
        }
        progress(sim.stats().body_collisions, total);
    }
    let (viscosity, viscosity_error) = batch_mean(&stresses, 10);
    let temperature = temperatures.iter().sum::<f64>() / temperatures.len() as f64;
    let profile: Vec<(f64, f64)> = profile
        .iter()
        .enumerate()
        .map(|(k, &(sum, count))| {
            (
                (k as f64 + 0.5) / SLABS as f64 * size[1],
                sum / count.max(1) as f64,
            )
        })
        .collect();
    let slope = line_fit(&profile).slope;
    let deviation = profile
        .iter()
        .map(|&(y, v)| (v - bx.flow(y)).abs())
        .fold(0.0, f64::max)
        / bx.layer_speed();
    let measured = sim.time() - measure_start.unwrap_or(sim.time());
    Ok(ShearReport {
        n: cfg.n,
        packing: cfg.packing,
        rate: cfg.rate,
        restitution: cfg.restitution,
        temperature,
        viscosity,
        viscosity_error,
        enskog: enskog_viscosity(cfg.packing),
        profile_slope: slope / rate,
        profile_deviation: deviation,
        profile,
        heating: heating / span,
        dissipation: if measured > 0.0 {
            dissipation.lost / (n * measured)
        } else {
            0.0
        },
        temperature_theory: (!elastic)
            .then(|| granular_temperature(cfg.packing, cfg.restitution, rate)),
        collisions: sim.stats().body_collisions - settled.min(sim.stats().body_collisions),
        seconds: start.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enskog_at_low_density_is_the_dilute_viscosity() {
        let dilute = 1.016 * 5.0 / (16.0 * std::f64::consts::PI.sqrt());
        assert!((enskog_viscosity(1e-9) - dilute).abs() < 1e-8);
        // Hand-computed: φ = 0.1, g = 0.95/0.729, factor 1/g + 0.32 + 0.7614·0.16·g.
        let g = 0.95 / 0.729;
        let want = dilute * (1.0 / g + 0.32 + 0.7614 * 0.16 * g);
        assert!((enskog_viscosity(0.1) - want).abs() < 1e-12);
    }

    #[test]
    fn a_small_sheared_gas_runs() {
        let report = shear_run(
            &ShearConfig {
                n: 300,
                settle: 2.0,
                collisions_per_body: 10.0,
                rate: 0.3,
                ..ShearConfig::default()
            },
            |_, _| {},
        )
        .unwrap();
        // Rescaled to kT = 1 after every block: the mean is a little above.
        assert!((report.temperature - 1.0).abs() < 0.1, "{report:?}");
        assert!(
            (report.viscosity / report.enskog - 1.0).abs() < 0.3,
            "{report:?}"
        );
        assert!((report.profile_slope - 1.0).abs() < 0.2, "{report:?}");
        assert_eq!(report.dissipation, 0.0);
        let granular = shear_run(
            &ShearConfig {
                n: 300,
                settle: 20.0,
                collisions_per_body: 40.0,
                rate: 0.3,
                restitution: 0.9,
                ..ShearConfig::default()
            },
            |_, _| {},
        )
        .unwrap();
        // Heating and dissipation, measured apart, balance in the steady state.
        let ratio = granular.heating / granular.dissipation;
        assert!((ratio - 1.0).abs() < 0.2, "{granular:?}");
    }
}

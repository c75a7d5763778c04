//! Jammed packings by compression: the Lubachevsky–Stillinger algorithm.
//!
//! [`compress`] runs a scene with growing radii ([`crate::contact::growth`]: every radius grows at
//! `Γ` times its start value per second) in blocks of events. After each block it measures
//! the reduced pressure `Z = P V / (N kT)` over the block from the collision virial, and
//! brings the kinetic temperature back to the target (growth collisions heat the packing).
//! It stops when `Z` passes the target (jammed: `10¹²` by default), then stops the growth
//! and reports the packing fraction, the contact network ([`contacts`]) and the rattlers.
//!
//! Fast growth (large `Γ` relative to thermal speeds over radii) jams early, at lower
//! packing fractions; slow growth lets the packing order or crystallise (monodisperse
//! discs do, which is why 2D packings are made bidisperse).
//!
//! ```
//! use ccdsim::generate::{gas, GasConfig};
//! use ccdsim::packing::{compress, CompressConfig};
//! let scene = gas::<2>(&GasConfig { n: 60, packing: 0.3, periodic: true,
//!                                   temperature: Some(1.0), ..GasConfig::default() }).unwrap();
//! let config = CompressConfig { rate: 0.05, until_pressure: 1e4, ..CompressConfig::default() };
//! let packed = compress(&scene, "cells", &config, |_| {}).unwrap();
//! assert!(packed.reduced_pressure >= 1e4);
//! assert!(packed.packing_fraction > 0.7);
//! ```

pub mod contacts;
pub mod isostatic;
pub(crate) mod soft;
pub mod start;

pub use contacts::{contact_network, ContactNetwork};
pub use isostatic::{finish_isostatic, IsostaticConfig, IsostaticFinish};
pub use start::{dilute_start, SizeMix};

use crate::finder::{make_finder, FinderOptions};
use crate::geom::Vector;
use crate::halt::Halt;
use crate::motion::Growth;
use crate::observables::pair_correlation::ball_volume;
use crate::observables::{temperature, world_volume};
use crate::scene::{BodySpec, Scene};
use crate::sim::{SimError, Simulation};
use crate::world::World;

/// How [`compress`] compresses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompressConfig {
    /// `Γ`, per second: radii grow by `Γ` times their start value each second.
    pub rate: f64,
    /// The kinetic temperature `kT` the velocities are brought back to after each block.
    pub temperature: f64,
    /// Stop when the reduced pressure `Z` of a block reaches this.
    pub until_pressure: f64,
    /// Events per block; 0 picks `20 · N`.
    pub block_events: u64,
    /// Stop after this many events at the most (`None`: no limit).
    pub max_events: Option<u64>,
    /// Contacts are gaps within this fraction of the contact distance; 0 picks
    /// `100 · D / until_pressure` (typical gaps at a reduced pressure `Z` are `D / Z` of a
    /// contact distance), at most [`MAX_DEFAULT_CONTACT_TOLERANCE`].
    pub contact_tolerance: f64,
}

impl Default for CompressConfig {
    fn default() -> Self {
        CompressConfig {
            rate: 1e-2,
            temperature: 1.0,
            until_pressure: 1e12,
            block_events: 0,
            max_events: None,
            contact_tolerance: 0.0,
        }
    }
}

/// Why [`compress`] stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CompressStop {
    /// The reduced pressure passed the target: jammed.
    Pressure,
    /// The event limit was reached first.
    MaxEvents,
    /// No event will ever happen (no bodies, or they fly apart faster than they grow).
    NoEvents,
    /// The simulation halted (see [`Halt`]).
    Halt(Halt),
}

/// The state after one block of [`compress`], for progress reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompressBlock {
    /// Events so far.
    pub events: u64,
    /// Simulated time now, seconds.
    pub time: f64,
    /// Packing fraction now.
    pub packing_fraction: f64,
    /// Reduced pressure `Z = P V / (N kT)` over the block.
    pub reduced_pressure: f64,
}

/// A compressed packing.
#[derive(Clone, Debug, PartialEq)]
pub struct Packed<const D: usize> {
    /// The final state as a scene: radii grown and fixed (less `10⁻¹³` of themselves, so that
    /// a pair that has just collided, touching up to rounding, does not overlap when the scene
    /// is read back: far below the gaps of any pressure short of `10¹³`), velocities as at
    /// the end, masses as they were (given explicitly), start time the final time.
    pub scene: Scene<D>,
    /// Fraction of the volume (periodic box, or the box bounding the walls) the bodies fill.
    pub packing_fraction: f64,
    /// Reduced pressure of the last block.
    pub reduced_pressure: f64,
    /// Events resolved.
    pub events: u64,
    /// Simulated time at the end, seconds.
    pub time: f64,
    /// Why compression stopped.
    pub stop: CompressStop,
    /// The contacts, rattlers and mean contact number.
    pub contacts: ContactNetwork,
    /// The contact tolerance used, relative to the contact distance.
    pub contact_tolerance: f64,
    /// What the isostatic finish did, when the packing had one ([`finish_isostatic`]).
    pub finish: Option<IsostaticFinish>,
}

/// The largest contact tolerance [`compress`] picks by itself, relative to the contact
/// distance: below a reduced pressure of `1000 · D` the rule `100 · D / Z` would count as
/// contacts gaps of whole diameters (thousands a body at `Z = 30`), which no one means by a
/// contact.
pub const MAX_DEFAULT_CONTACT_TOLERANCE: f64 = 0.1;

/// Why [`compress`] cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompressError {
    /// The scene or finder was refused.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A setting is out of range.
    #[error("{0}")]
    Config(String),
}

/// Fraction of the world's volume (periodic box, or the box bounding the walls) that the
/// bodies (kinematic ones too, not vacant slots) fill at time `t`; `None` for a world without
/// a volume.
#[must_use]
pub fn packing_fraction<const D: usize>(world: &World<D>, t: f64) -> Option<f64> {
    let v = world_volume(world)?;
    let filled: f64 = (0..world.len())
        .filter(|&i| !world.is_vacant(i))
        .map(|i| ball_volume::<D>(world.radius_at(i, t)))
        .sum();
    Some(filled / v)
}

/// Compresses `scene` (a periodic box, or walls around the bodies) with finder `finder` by
/// growing its radii (see the module docs) until the reduced pressure passes
/// `config.until_pressure`, calling `on_block` after each block of events.
pub fn compress<const D: usize>(
    scene: &Scene<D>,
    finder: &str,
    config: &CompressConfig,
    mut on_block: impl FnMut(&CompressBlock),
) -> Result<Packed<D>, CompressError> {
    let bad = |what: &str| Err(CompressError::Config(what.to_string()));
    if !(config.rate.is_finite() && config.rate > 0.0) {
        return bad("the growth rate must be a positive number");
    }
    if !(config.temperature.is_finite() && config.temperature > 0.0) {
        return bad("the temperature must be a positive number");
    }
    if config.until_pressure.is_nan() || config.until_pressure <= 1.0 {
        return bad("the target reduced pressure must exceed 1 (an ideal gas's)");
    }
    if !(config.contact_tolerance.is_finite() && config.contact_tolerance >= 0.0) {
        return bad("the contact tolerance must be a non-negative number");
    }
    if scene.periodic.is_none() && scene.walls.is_empty() {
        return bad("compression needs a volume: a periodic box or walls");
    }
    let mut growing = scene.clone();
    growing.settings.growth = Some(Growth { rate: config.rate });
    let finder = make_finder::<D>(finder, &FinderOptions::default()).map_err(SimError::from)?;
    let mut sim = Simulation::with_finder(&growing, finder)?;
    let n = sim.world().len();
    let block = if config.block_events > 0 {
        config.block_events
    } else {
        20 * n.max(1) as u64
    };
    let cool = |sim: &mut Simulation<D>| -> Result<(), SimError> {
        let kt = temperature(sim.world());
        if kt > 0.0 {
            sim.rescale_velocities((config.temperature / kt).sqrt())?;
        }
        Ok(())
    };
    cool(&mut sim)?;
    let mut events = 0u64;
    let mut reduced_pressure = 1.0;
    let stop = loop {
        let limit = config.max_events.map_or(block, |m| block.min(m - events));
        if limit == 0 {
            break CompressStop::MaxEvents;
        }
        let (t0, w0, kt0) = (sim.time(), sim.stats().virial, temperature(sim.world()));
        let done = sim.run_events(limit);
        events += done;
        let dt = sim.time() - t0;
        let kt = 0.5 * (kt0 + temperature(sim.world()));
        if dt > 0.0 && kt > 0.0 && n > 0 {
            let virial = sim.stats().virial - w0;
            reduced_pressure = 1.0 + virial / (D as f64 * n as f64 * kt * dt);
        }
        on_block(&CompressBlock {
            events,
            time: sim.time(),
            packing_fraction: packing_fraction(sim.world(), sim.time()).unwrap_or(0.0),
            reduced_pressure,
        });
        if done < limit {
            break match sim.halt() {
                Some(h) => CompressStop::Halt(h),
                None => CompressStop::NoEvents,
            };
        }
        if reduced_pressure >= config.until_pressure {
            break CompressStop::Pressure;
        }
        cool(&mut sim)?;
    };
    sim.stop_growth()?;
    let tolerance = if config.contact_tolerance > 0.0 {
        config.contact_tolerance
    } else {
        (100.0 * D as f64 / config.until_pressure).min(MAX_DEFAULT_CONTACT_TOLERANCE)
    };
    let world = sim.world();
    let positions: Vec<Vector<D>> = (0..n).map(|i| sim.position(i)).collect();
    let radii: Vec<f64> = (0..n).map(|i| sim.radius(i)).collect();
    let contacts = contact_network(
        &positions,
        &radii,
        world.walls(),
        world.periodic(),
        tolerance,
    );
    let bodies = (0..n)
        .map(|i| BodySpec {
            id: scene.bodies[i].id,
            pos: positions[i],
            vel: world.velocity(i),
            radius: radii[i] * (1.0 - 1e-13),
            mass: Some(world.mass(i)),
            restitution: scene.bodies[i].restitution,
            kinematic: false,
            group: scene.bodies[i].group,
            mask: scene.bodies[i].mask,
            inertia: None,
            spin: None,
            tangential_restitution: None,
        })
        .collect();
    let mut settings = scene.settings;
    settings.growth = None;
    Ok(Packed {
        scene: Scene {
            settings,
            start_time: sim.time(),
            bodies,
            walls: scene.walls.clone(),
            periodic: scene.periodic,
            sensors: scene.sensors.clone(),
            moving_walls: scene.moving_walls.clone(),
            arrivals: Vec::new(),
            histogram: scene.histogram.clone(),
        },
        packing_fraction: packing_fraction(world, sim.time()).unwrap_or(0.0),
        reduced_pressure,
        events,
        time: sim.time(),
        stop,
        contacts,
        contact_tolerance: tolerance,
        finish: None,
    })
}

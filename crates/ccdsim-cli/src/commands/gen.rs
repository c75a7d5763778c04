//! `ccdsim gen`: write a generated scene as JSON.

use anyhow::{Context, Result};
use ccdsim::billiards::{Game, PoolBallBall, PoolScene};
use ccdsim::generate::{
    galton, galton_duration, gas, pegs, rack, thesis, GaltonConfig, GasConfig, Lattice, PegsConfig,
    RackConfig, ThesisConfig,
};
use ccdsim::Gravity;
use ccdsim::{AnyScene, Scene, Settings};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim gen`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    kind: Kind,
    /// Write the scene here instead of to standard output.
    #[arg(long, global = true)]
    out: Option<PathBuf>,
    /// Uniform gravity for the scene, one component per dimension, m/s² (e.g. `0,-9.81`);
    /// sets `settings.gravity` (walled scenes only).
    #[arg(long, global = true, value_delimiter = ',', allow_hyphen_values = true)]
    gravity: Option<Vec<f64>>,
}

#[derive(clap::Subcommand)]
enum Kind {
    /// Non-overlapping bodies in a walled or periodic box, at random or on a lattice.
    Gas(GasArgs),
    /// A 15-ball billiard rack with the cue ball shot into it (2D).
    Rack(RackArgs),
    /// A pool table (pooltool's default 7-foot table) racked for nine-ball or eight-ball, and
    /// the break, or the shot given: a pool scene for `ccdsim run`.
    Table(TableArgs),
    /// The thesis's benchmark scene (§5.2): a walled table of constant body density, sized for
    /// n; the constants are calibrated against its Table 5.1 (docs/benchmarks.md).
    Thesis(ThesisArgs),
    /// A peg board under gravity (2D): balls dropped through staggered rows of pegs.
    Pegs(PegsArgs),
    /// A Galton board (2D): a funnel releases balls one at a time onto a triangle of pegs;
    /// `ccdsim run` prints what each bin holds at the end (run it for the time printed).
    Galton(GaltonArgs),
}

#[derive(clap::Args)]
struct GaltonArgs {
    /// Rows of pegs (the board has one bin more).
    #[arg(long, default_value_t = GaltonConfig::default().rows)]
    rows: usize,
    /// Balls released.
    #[arg(long, default_value_t = GaltonConfig::default().balls)]
    balls: usize,
    /// Seconds between one ball's release and the next (at least 0.25).
    #[arg(long, default_value_t = GaltonConfig::default().interval)]
    interval: f64,
    /// Coefficient of restitution, in [0, 1).
    #[arg(long, default_value_t = GaltonConfig::default().restitution)]
    restitution: f64,
    /// Random seed of where each ball is released.
    #[arg(long, default_value_t = GaltonConfig::default().seed)]
    seed: u64,
}

#[derive(clap::Args)]
struct PegsArgs {
    /// Rows of pegs.
    #[arg(long, default_value_t = PegsConfig::default().rows)]
    rows: usize,
    /// Number of balls.
    #[arg(long, default_value_t = PegsConfig::default().balls)]
    balls: usize,
    /// Ball radius, metres (at most 0.3).
    #[arg(long, default_value_t = PegsConfig::default().radius)]
    radius: f64,
    /// Coefficient of restitution, in [0, 1].
    #[arg(long, default_value_t = PegsConfig::default().restitution)]
    restitution: f64,
    /// Bins along the floor, each a sensor that counts the balls landing on it (`ccdsim run`
    /// reports what each holds at the end; `gen galton` is a Galton board). 0: none.
    #[arg(long, default_value_t = PegsConfig::default().bins)]
    bins: usize,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

#[derive(clap::Args)]
struct ThesisArgs {
    /// Number of bodies.
    #[arg(long, default_value_t = 1024)]
    n: usize,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Dimension, 2 (the thesis's 4-wall table) or 3 (a box of 6 planes).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// 2D: each side of the table as this many collinear segments (1: the thesis's four
    /// walls), for a table of many walls with the same bodies.
    #[arg(long, default_value_t = 1)]
    wall_pieces: usize,
}

#[derive(clap::Args)]
struct GasArgs {
    /// Number of bodies.
    #[arg(long, default_value_t = 1000)]
    n: usize,
    /// Fraction of the box covered by bodies, in (0, 1).
    #[arg(long, default_value_t = 0.2)]
    packing: f64,
    /// Smallest radius, metres.
    #[arg(long, default_value_t = 0.5)]
    radius_min: f64,
    /// Largest radius, metres.
    #[arg(long, default_value_t = 0.5)]
    radius_max: f64,
    /// Smallest speed, m/s.
    #[arg(long, default_value_t = 0.0)]
    speed_min: f64,
    /// Largest speed, m/s.
    #[arg(long, default_value_t = 1.0)]
    speed_max: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Dimension, 2 or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// A periodic box (opposite faces identified) instead of walls.
    #[arg(long)]
    periodic: bool,
    /// Start on a lattice (for dense packings); alone, the densest one: hex in 2D, fcc in 3D.
    #[arg(long, value_enum, num_args = 0..=1, default_missing_value = "densest")]
    lattice: Option<LatticeArg>,
    /// Maxwell velocities at this temperature kT (k = 1) with zero total momentum, instead
    /// of uniform speeds.
    #[arg(long)]
    temperature: Option<f64>,
    /// Coefficient of restitution of every collision (`settings.restitution`), in [0, 1].
    #[arg(long)]
    restitution: Option<f64>,
    /// Rough bodies: the tangential restitution of every collision
    /// (`settings.tangential_restitution`), in [-1, 1]; −1 is smooth, 1 perfectly rough.
    #[arg(long, allow_negative_numbers = true)]
    tangential_restitution: Option<f64>,
    /// The TC model's time (`settings.tc`), seconds: keeps an inelastic gas from collapsing.
    #[arg(long)]
    tc: Option<f64>,
    /// Lees–Edwards shear at this rate γ̇ (`settings.shear_rate`, 1/s; flow along x, gradient
    /// along y) of a --periodic box; the bodies start in the flow γ̇ (y − L_y/2).
    #[arg(long, allow_negative_numbers = true)]
    shear_rate: Option<f64>,
}

/// Lattices of `--lattice`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum LatticeArg {
    /// Hexagonal in 2D, face-centred cubic in 3D.
    Densest,
    /// Hexagonal (2D).
    Hex,
    /// Square (2D).
    Square,
    /// Face-centred cubic (3D).
    Fcc,
    /// Simple cubic (3D).
    Cubic,
}

impl From<LatticeArg> for Lattice {
    fn from(l: LatticeArg) -> Self {
        match l {
            LatticeArg::Densest => Lattice::Densest,
            LatticeArg::Hex => Lattice::Hexagonal,
            LatticeArg::Square => Lattice::Square,
            LatticeArg::Fcc => Lattice::Fcc,
            LatticeArg::Cubic => Lattice::Cubic,
        }
    }
}

/// The racks `gen table` knows.
#[derive(Clone, Copy, clap::ValueEnum)]
enum GameArg {
    NineBall,
    EightBall,
}

#[derive(clap::Args)]
struct TableArgs {
    /// The rack.
    #[arg(long, value_enum, default_value = "nine-ball")]
    game: GameArg,
    /// Seed of the rack's small random offsets.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The shot: `V0,phi[,theta,a,b]` (m/s, degrees, degrees, ball radii, ball radii). Without
    /// it, the break: 8 m/s from the cue ball straight at the apex ball.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    shot: Option<Vec<f64>>,
    /// Balls meet with friction and restitution 0.95 (pooltool 0.4's `frictional_inelastic`,
    /// Alciatore's friction curve) instead of without friction, elastically (pooltool 0.3.3's
    /// default). The scene's `ball_ball` field sets other coefficients.
    #[arg(long)]
    frictional: bool,
}

/// The pool scene of `gen table`.
fn pool_table(t: &TableArgs) -> Result<PoolScene> {
    let game = match t.game {
        GameArg::NineBall => Game::NineBall,
        GameArg::EightBall => Game::EightBall,
    };
    let mut scene = PoolScene::racked(game, t.seed);
    let shot = &mut scene.pool.shot;
    match t.shot.as_deref() {
        None => {}
        Some(&[v, phi]) => (shot.speed, shot.phi) = (v, phi),
        Some(&[v, phi, theta, a, b]) => {
            (shot.speed, shot.phi, shot.theta, shot.a, shot.b) = (v, phi, theta, a, b);
        }
        Some(other) => anyhow::bail!(
            "--shot takes V0,phi or V0,phi,theta,a,b; {} numbers given",
            other.len()
        ),
    }
    if t.frictional {
        scene.pool.ball_ball = Some(PoolBallBall {
            restitution: 0.95,
            friction: None,
        });
    }
    // Refuse a shot that cannot be played (a tip that misses, a speed that is not finite).
    scene.shot().context("--shot")?;
    Ok(scene)
}

#[derive(clap::Args)]
struct RackArgs {
    /// Cue ball speed, m/s.
    #[arg(long, default_value_t = RackConfig::default().speed)]
    speed: f64,
    /// Sideways offset of the cue ball's aim, metres (0 = dead centre).
    #[arg(long, default_value_t = RackConfig::default().offset)]
    offset: f64,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    if let Kind::Table(t) = &args.kind {
        anyhow::ensure!(
            args.gravity.is_none(),
            "--gravity: a pool table has its own (the cloth's friction laws)"
        );
        let json = pool_table(t)?.to_json();
        match &args.out {
            Some(path) => {
                std::fs::write(path, json).with_context(|| format!("writing {}", path.display()))?
            }
            None => out!("{json}")?,
        }
        return Ok(ExitCode::SUCCESS);
    }
    let scene: AnyScene = match args.kind {
        Kind::Table(_) => unreachable!("written above"),
        Kind::Gas(g) => {
            let cfg = GasConfig {
                n: g.n,
                packing: g.packing,
                radius_min: g.radius_min,
                radius_max: g.radius_max,
                speed_min: g.speed_min,
                speed_max: g.speed_max,
                seed: g.seed,
                periodic: g.periodic,
                lattice: g.lattice.map(Lattice::from),
                temperature: g.temperature,
            };
            let mut settings = Settings::default();
            if let Some(e) = g.restitution {
                settings.restitution = e;
            }
            settings.tangential_restitution = g.tangential_restitution;
            settings.tc = g.tc;
            settings.shear_rate = g.shear_rate;
            if g.dim == 2 {
                with_settings(gas::<2>(&cfg)?, settings)?.into()
            } else {
                with_settings(gas::<3>(&cfg)?, settings)?.into()
            }
        }
        Kind::Rack(r) => {
            let scene = rack(&RackConfig {
                speed: r.speed,
                offset: r.offset,
                ..RackConfig::default()
            });
            scene.validate().context("rack")?;
            scene.into()
        }
        Kind::Pegs(p) => pegs(&PegsConfig {
            rows: p.rows,
            balls: p.balls,
            radius: p.radius,
            restitution: p.restitution,
            bins: p.bins,
            seed: p.seed,
            ..PegsConfig::default()
        })?
        .into(),
        Kind::Galton(g) => {
            let cfg = GaltonConfig {
                rows: g.rows,
                balls: g.balls,
                interval: g.interval,
                restitution: g.restitution,
                seed: g.seed,
            };
            let scene = galton(&cfg)?;
            eprintln!(
                "a Galton board: the last ball arrives at {} s; run it with `--until {}` to \
                 let every ball settle",
                (cfg.balls - 1) as f64 * cfg.interval,
                galton_duration(&cfg)
            );
            scene.into()
        }
        Kind::Thesis(t) => {
            let cfg = ThesisConfig {
                wall_pieces: t.wall_pieces,
                ..ThesisConfig::new(t.n, t.seed)
            };
            if t.dim == 2 {
                thesis::<2>(&cfg)?.into()
            } else {
                thesis::<3>(&cfg)?.into()
            }
        }
    };
    let scene = match args.gravity {
        None => scene,
        Some(g) => with_gravity(scene, &g)?,
    };
    let json = scene.to_json();
    match args.out {
        Some(path) => std::fs::write(&path, json + "\n")
            .with_context(|| format!("writing {}", path.display()))?,
        None => outln!("{json}")?,
    }
    Ok(ExitCode::SUCCESS)
}

/// `scene` with `settings.gravity` set to `g`, validated (a wrong number of components, a
/// periodic box or growth are refused with the scene's own message).
fn with_gravity(scene: AnyScene, g: &[f64]) -> Result<AnyScene> {
    let gravity = Gravity::new(g).with_context(|| {
        format!(
            "--gravity: {} components given, one per dimension (2 or 3) expected",
            g.len()
        )
    })?;
    let scene = match scene {
        AnyScene::D2(mut s) => {
            s.settings.gravity = Some(gravity);
            s.validate().context("--gravity")?;
            AnyScene::D2(s)
        }
        AnyScene::D3(mut s) => {
            s.settings.gravity = Some(gravity);
            s.validate().context("--gravity")?;
            AnyScene::D3(s)
        }
    };
    Ok(scene)
}

/// `scene` with the collision settings of `settings` (restitution, tangential restitution,
/// TC time, shear rate: the bodies then start in the flow), validated.
fn with_settings<const D: usize>(mut scene: Scene<D>, settings: Settings) -> Result<Scene<D>> {
    scene.settings.restitution = settings.restitution;
    scene.settings.tangential_restitution = settings.tangential_restitution;
    scene.settings.tc = settings.tc;
    scene.settings.shear_rate = settings.shear_rate;
    if let (Some(rate), Some(size)) = (settings.shear_rate, scene.periodic) {
        for b in &mut scene.bodies {
            b.vel[0] += rate * (b.pos[1] - 0.5 * size[1]);
        }
    }
    scene.validate().context("gas")?;
    Ok(scene)
}

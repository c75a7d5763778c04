//! `ccdsim run`: simulate a scene, optionally recording a run file, and print a summary.

use super::finder_args::FinderArgs;
use crate::number::{num, sig};
use crate::progress::Progress;
use anyhow::{Context, Result};
use ccdsim::generate::{rack, RackConfig};
use ccdsim::observables::{EnergyBalance, PressureTensor};
use ccdsim::record::RunWriter;
use ccdsim::trajectory::{Frame, SampleTimes, TrajectoryFormat, TrajectoryWriter};
use ccdsim::{make_finder, AnyScene, Scene, Simulation};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `ccdsim run`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (JSON): a ccdsim scene, or a pool scene (`ccdsim gen table`). Without it,
    /// the built-in billiard break is run.
    scene: Option<PathBuf>,
    /// Next-event finder (broad phase).
    #[arg(long, default_value = "cells")]
    finder: String,
    /// Simulate until this time, seconds (default 10 when --events is not given).
    #[arg(long, conflicts_with = "events", allow_negative_numbers = true)]
    until: Option<f64>,
    /// Simulate this many events.
    #[arg(long)]
    events: Option<u64>,
    /// Write a run file here.
    #[arg(long)]
    record: Option<PathBuf>,
    /// Sample a frame every this many seconds of simulated time (with --trajectory).
    #[arg(
        long,
        requires = "trajectory",
        conflicts_with = "events",
        allow_negative_numbers = true
    )]
    frames: Option<f64>,
    /// Write the sampled frames here: extended XYZ (.xyz, .extxyz) or GSD (.gsd).
    #[arg(long, requires = "frames")]
    trajectory: Option<PathBuf>,
    /// Write the scene's sensor events here as JSON lines (`t`, `body` id, `sensor` index,
    /// `change`: "enter" or "leave"), in time order.
    #[arg(long)]
    sensor_log: Option<PathBuf>,
    /// Print one JSON object instead of the readable summary.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
    #[command(flatten)]
    finder_options: FinderArgs,
}

/// The `--json` summary; field names are an interface (DESIGN.md): extend, never rename.
#[derive(Serialize)]
struct Summary {
    finder: String,
    dim: usize,
    bodies: usize,
    events: u64,
    body_collisions: u64,
    wall_collisions: u64,
    /// Thermostat resets (counted in `events`).
    resets: u64,
    sim_time: f64,
    wall_seconds: f64,
    events_per_second: f64,
    kinetic_energy_start: f64,
    kinetic_energy_end: f64,
    kinetic_energy_drift: f64,
    momentum_start: Vec<f64>,
    momentum_end: Vec<f64>,
    max_overlap: f64,
    record: Option<String>,
    /// The trajectory file written with --frames, or null.
    trajectory: Option<String>,
    /// Frames written to it.
    frames: u64,
    /// Kinetic temperature kT at the end (k = 1, the scene's units).
    temperature: f64,
    /// Rotational temperature kT_rot at the end (2·K_rot/(f·N), f = 1 in 2D, 3 in 3D); null
    /// unless the scene's bodies spin (rough bodies).
    rotational_temperature: Option<f64>,
    /// Body–body collisions per body per unit time.
    collision_rate: f64,
    /// Pressure from the collision virial; null without a volume (no periodic box or walls).
    pressure: Option<f64>,
    /// Compressibility factor Z = PV/(NkT); null when the pressure is.
    compressibility: Option<f64>,
    /// The finder's internal work (e.g. `cells`: crossings, stale predictions, rescans), by
    /// name; empty for finders that keep no counters.
    finder_counters: std::collections::BTreeMap<String, u64>,
    /// Why the run stopped before `--until`/`--events` while events remained (a contact
    /// beyond the largest time, or f64 no longer resolving a body), or null.
    halt: Option<String>,
    /// Potential energy in the gravity field at the start, joules (−Σ m g·x; 0 without
    /// gravity).
    potential_energy_start: f64,
    /// Potential energy at the end, joules.
    potential_energy_end: f64,
    /// The relative energy drift ([`EnergyBalance::relative_drift`], what `verify` prints):
    /// the change of kinetic + potential energy less the moving walls' work, against the
    /// larger of the start and end kinetic energies.
    energy_drift: f64,
    /// Per sensor of the scene (empty without sensors): bodies that entered and left it, and
    /// those inside at the end.
    sensors: Vec<SensorSummary>,
    /// The sensor log written with --sensor-log, or null.
    sensor_log: Option<String>,
    /// Work the moving walls did on the bodies, joules (0 without moving walls): with
    /// elastic collisions, the energy at the end less this is the energy at the start.
    wall_work: f64,
    /// Bodies the scene's `arrivals` brought in during the run.
    arrivals: u64,
    /// The energy they brought in, joules (kinetic plus potential at entry); the drift
    /// leaves it out.
    arrival_energy: f64,
    /// What the scene's `histogram` bins hold at the end, or null without one.
    histogram: Option<HistogramSummary>,
    /// Sheared boxes (`settings.shear_rate`): the shear stress −P_xy over the run (collision
    /// virial plus kinetic part in peculiar velocities), or null without shear.
    shear_stress: Option<f64>,
    /// Sheared boxes: the shear viscosity η = −P_xy / γ̇ over the run, or null (no shear, or
    /// a rate of 0).
    viscosity: Option<f64>,
    /// Sheared boxes: the velocity profile, `[y, mean v_x]` for ten slabs along y (their
    /// centres, m, and m/s), sampled every 4096 events and at the end; null without shear.
    velocity_profile: Option<Vec<[f64; 2]>>,
}

/// Slabs of a sheared run's velocity profile.
const PROFILE_SLABS: usize = 10;

/// A sheared run's velocity profile: per slab along y, the sum of `v_x` and the count of
/// bodies over the samples taken.
struct Profile {
    slabs: [(f64, u64); PROFILE_SLABS],
    height: f64,
}

impl Profile {
    fn of<const D: usize>(sim: &Simulation<D>) -> Option<Self> {
        let bx = sim.world().shear()?;
        Some(Profile {
            slabs: [(0.0, 0); PROFILE_SLABS],
            height: bx.size[1],
        })
    }

    /// Adds the bodies' `v_x` where they are now.
    fn sample<const D: usize>(&mut self, sim: &Simulation<D>) {
        let w = sim.world();
        for i in (0..w.len()).filter(|&i| !w.is_vacant(i) && !w.is_kinematic(i)) {
            let y = sim.position(i)[1] / self.height;
            let k = ((y * PROFILE_SLABS as f64) as usize).min(PROFILE_SLABS - 1);
            self.slabs[k].0 += w.velocity(i)[0];
            self.slabs[k].1 += 1;
        }
    }

    fn mean(&self) -> Vec<[f64; 2]> {
        (0..PROFILE_SLABS)
            .map(|k| {
                let (sum, count) = self.slabs[k];
                let y = (k as f64 + 0.5) / PROFILE_SLABS as f64 * self.height;
                [y, if count > 0 { sum / count as f64 } else { 0.0 }]
            })
            .collect()
    }
}

/// The `--json` summary's `histogram`: the bins' edges and what each holds at the end.
#[derive(Serialize)]
struct HistogramSummary {
    axis: usize,
    edges: Vec<f64>,
    counts: Vec<u64>,
    /// Free bodies outside every bin.
    outside: u64,
}

/// One sensor's counts in the `--json` summary.
#[derive(Serialize)]
struct SensorSummary {
    enters: u64,
    leaves: u64,
    inside: usize,
}

/// Writes sensor events as JSON lines.
struct SensorLog {
    out: std::io::BufWriter<std::fs::File>,
}

impl SensorLog {
    /// Appends the events `sim` reported since the last call (and forgets them either way).
    fn drain<const D: usize>(log: &mut Option<Self>, sim: &mut Simulation<D>) -> Result<()> {
        use std::io::Write;
        let events = sim.take_sensor_events();
        let Some(log) = log else { return Ok(()) };
        for e in events {
            let change = match e.change {
                ccdsim::SensorChange::Enter => "enter",
                ccdsim::SensorChange::Leave => "leave",
            };
            // Ids as they are now: bodies may have arrived since the run began.
            let id = sim.world().ids()[e.body];
            let line = serde_json::json!({
                "t": e.time, "body": id, "sensor": e.sensor, "change": change,
            });
            writeln!(log.out, "{line}")?;
        }
        Ok(())
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    if let Some(path) = &args.scene {
        let text = std::fs::read_to_string(path).with_context(|| format!("{}", path.display()))?;
        if ccdsim::billiards::PoolScene::is_pool_json(&text) {
            let finder: ccdsim::billiards::PoolFinder =
                args.finder.parse().map_err(anyhow::Error::msg)?;
            let given = [
                (
                    "finder options (--bvh-grow, …)",
                    args.finder_options.any_given(),
                ),
                ("--until", args.until.is_some()),
                ("--events", args.events.is_some()),
                ("--frames", args.frames.is_some()),
                ("--sensor-log", args.sensor_log.is_some()),
            ];
            let unsupported = super::run_pool::Unsupported(
                given
                    .iter()
                    .filter(|(_, on)| *on)
                    .map(|(f, _)| *f)
                    .collect(),
            );
            super::run_pool::run(
                &text,
                &unsupported,
                finder,
                args.record.as_deref(),
                args.json,
            )
            .with_context(|| format!("{}", path.display()))?;
            return Ok(ExitCode::SUCCESS);
        }
    }
    let scene = match &args.scene {
        Some(path) => AnyScene::from_file(path).with_context(|| format!("{}", path.display()))?,
        None => AnyScene::D2(rack(&RackConfig::default())),
    };
    if let Some(t) = args.until {
        anyhow::ensure!(t.is_finite(), "--until must be a finite time");
    }
    let summary = match &scene {
        AnyScene::D2(s) => simulate(s, &args)?,
        AnyScene::D3(s) => simulate(s, &args)?,
    };
    if args.json {
        outln!("{}", serde_json::to_string(&summary)?)?;
    } else {
        print_summary(&summary, args.scene.is_none())?;
    }
    Ok(ExitCode::SUCCESS)
}

fn simulate<const D: usize>(scene: &Scene<D>, args: &Args) -> Result<Summary> {
    if let Some(t) = args.until {
        anyhow::ensure!(
            t >= scene.start_time,
            "--until {t} lies before the scene's start time {} s",
            scene.start_time
        );
    }
    anyhow::ensure!(
        args.sensor_log.is_none() || !scene.sensors.is_empty(),
        "--sensor-log: the scene has no sensors"
    );
    let finder = make_finder::<D>(&args.finder, &args.finder_options.options()?)?;
    let mut sim = Simulation::with_finder(scene, finder)?;
    let mut frames = match (args.frames, &args.trajectory) {
        (Some(every), Some(path)) => {
            let format = TrajectoryFormat::from_path(path).map_err(anyhow::Error::msg)?;
            let times = SampleTimes::new(sim.time(), every, args.until.unwrap_or(10.0))
                .map_err(|e| anyhow::anyhow!("--frames: {e}"))?;
            Some((times.peekable(), format, path))
        }
        _ => None,
    };
    let momentum_start = sim.world().momentum().0.to_vec();
    let potential_start = sim.world().potential_energy_at(sim.time());
    let rotational_start = sim.world().rotational_energy();
    // Everything is validated before the run file is created: bad input leaves no file.
    // Arrivals are recorded as the additions they are: a steered run file.
    let steered = !scene.arrivals.is_empty();
    let mut profile = Profile::of(&sim);
    let mut sink = Sink {
        writer: match &args.record {
            Some(path) if steered => Some(RunWriter::record_steered(&mut sim, path, scene)?),
            Some(path) => Some(RunWriter::create(path, scene)?),
            None => None,
        },
        error: None,
        stress: match sim.world().shear() {
            Some(_) => Some(PressureTensor::new(&sim).map_err(anyhow::Error::msg)?),
            None => None,
        },
    };
    let rotational = sim.world().is_rotational();
    let mut trajectory = match &frames {
        Some((_, format, path)) => match TrajectoryWriter::create_for(path, *format, rotational) {
            Ok(w) => Some(w),
            Err(e) => {
                // No partial output: the run file just created goes too.
                if let Some(record) = &args.record {
                    let _ = std::fs::remove_file(record);
                }
                return Err(anyhow::Error::new(e).context(format!("{}", path.display())));
            }
        },
        None => None,
    };
    let mut sensor_log = match &args.sensor_log {
        Some(path) => {
            let file = match std::fs::File::create(path) {
                Ok(f) => f,
                Err(e) => {
                    // No partial output: the files just created go too.
                    for p in [&args.record, &args.trajectory].into_iter().flatten() {
                        let _ = std::fs::remove_file(p);
                    }
                    return Err(anyhow::Error::new(e)
                        .context(format!("creating the sensor log {}", path.display())));
                }
            };
            Some(SensorLog {
                out: std::io::BufWriter::new(file),
            })
        }
        None => None,
    };
    let start = Instant::now();
    let t0 = sim.time();
    let mut count: u64 = 0;
    let mut frames_written: u64 = 0;
    match args.events {
        Some(n) => {
            let mut progress = Progress::new(n, "events", args.quiet);
            while count < n {
                let batch = (n - count).min(4096);
                let done = if steered {
                    let mut done = 0;
                    while done < batch {
                        let Some(c) = sim.step_event() else { break };
                        sink.take_edits(&mut sim);
                        sink.take(&c);
                        done += 1;
                    }
                    done
                } else {
                    sim.run_events_with(batch, |c| sink.take(c))
                };
                count += done;
                progress.set(count);
                if let Some(p) = profile.as_mut() {
                    p.sample(&sim);
                }
                SensorLog::drain(&mut sensor_log, &mut sim)?;
                if done < batch || sink.error.is_some() {
                    break;
                }
            }
            progress.finish();
        }
        None => {
            let until = args.until.unwrap_or(10.0);
            let span = (until - t0).max(0.0);
            let mut progress = Progress::without_eta(1000, "simulated time", args.quiet);
            // `step_event_until` never goes past `until`, not even for the box exits of a
            // periodic world.
            loop {
                // The next stop: the next frame's time, or the end.
                let (stop, is_frame) = match frames.as_mut().and_then(|f| f.0.peek()) {
                    Some(&t) => (t, true),
                    None => (until, false),
                };
                while sink.error.is_none() {
                    let Some(c) = sim.step_event_until(stop) else {
                        break;
                    };
                    if steered {
                        sink.take_edits(&mut sim);
                    }
                    sink.take(&c);
                    count += 1;
                    if count % 4096 == 0 {
                        if let Some(p) = profile.as_mut() {
                            p.sample(&sim);
                        }
                        SensorLog::drain(&mut sensor_log, &mut sim)?;
                        if span > 0.0 {
                            progress.set(((sim.time() - t0) / span * 1000.0) as u64);
                        }
                    }
                }
                if sink.error.is_some() {
                    break;
                }
                sim.run_until(stop);
                sink.take_edits(&mut sim);
                SensorLog::drain(&mut sensor_log, &mut sim)?;
                // A halted run stands still before `stop`: no frame claims a time it missed.
                if !is_frame || sim.time() < stop {
                    break;
                }
                if let (Some(w), Some(f)) = (trajectory.as_mut(), frames.as_mut()) {
                    f.0.next();
                    frames_written += 1;
                    w.write(&Frame::of(&sim))
                        .with_context(|| format!("writing the trajectory {}", f.2.display()))?;
                }
            }
            progress.finish();
        }
    }
    sink.take_edits(&mut sim);
    if let Some(e) = sink.error {
        return Err(e.into());
    }
    SensorLog::drain(&mut sensor_log, &mut sim)?;
    if let Some(log) = sensor_log.as_mut() {
        use std::io::Write;
        log.out.flush()?;
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    if let Some(w) = sink.writer {
        w.finish(sim.time())?;
    }
    if let Some(w) = trajectory {
        w.finish()?;
    }
    if let Some(halt) = sim.halt() {
        eprintln!("warning: {halt}");
    }
    let stats = *sim.stats();
    let observables = sim.observables();
    if let Some(p) = profile.as_mut() {
        p.sample(&sim);
    }
    let shear_stress = sink.stress.as_ref().map(|p| {
        let t = p.tensor(sim.time());
        -0.5 * (t[0][1] + t[1][0])
    });
    let viscosity = sim
        .world()
        .shear()
        .zip(shear_stress)
        .and_then(|(bx, s)| (bx.rate != 0.0).then(|| s / bx.rate));
    let ke_end = sim.world().kinetic_energy_at(sim.time());
    let potential_end = sim.world().potential_energy_at(sim.time());
    // The one relative drift (`ccdsim verify` prints the same): what the collisions changed
    // of the total energy, the moving walls' work aside.
    let energy_drift = EnergyBalance {
        kinetic_start: stats.kinetic_energy_start,
        kinetic_end: ke_end,
        potential_start,
        potential_end,
        work: stats.wall_work + stats.arrival_energy,
        rotational_start,
        rotational_end: sim.world().rotational_energy(),
    }
    .relative_drift();
    let drift = if stats.kinetic_energy_start > 0.0 {
        (ke_end - stats.kinetic_energy_start) / stats.kinetic_energy_start
    } else {
        0.0
    };
    Ok(Summary {
        finder: sim.finder_name().to_string(),
        dim: D,
        bodies: sim.world().len(),
        events: stats.events,
        body_collisions: stats.body_collisions,
        wall_collisions: stats.wall_collisions,
        resets: stats.resets,
        sim_time: sim.time(),
        wall_seconds,
        events_per_second: if wall_seconds > 0.0 {
            stats.events as f64 / wall_seconds
        } else {
            0.0
        },
        kinetic_energy_start: stats.kinetic_energy_start,
        kinetic_energy_end: ke_end,
        kinetic_energy_drift: drift,
        momentum_start,
        momentum_end: sim.world().momentum().0.to_vec(),
        max_overlap: stats.max_overlap,
        record: args.record.as_ref().map(|p| p.display().to_string()),
        trajectory: args.trajectory.as_ref().map(|p| p.display().to_string()),
        frames: frames_written,
        temperature: observables.temperature,
        rotational_temperature: observables.rotational_temperature,
        collision_rate: observables.collision_rate,
        pressure: observables.pressure,
        compressibility: observables.compressibility,
        finder_counters: sim
            .finder_mut()
            .0
            .counters()
            .into_iter()
            .map(|(name, count)| (name.to_string(), count))
            .collect(),
        halt: sim.halt().map(|h| h.to_string()),
        potential_energy_start: potential_start,
        potential_energy_end: potential_end,
        energy_drift,
        sensors: sim.sensors().map_or_else(Vec::new, |s| {
            (0..s.sensors().len())
                .map(|k| {
                    let (enters, leaves) = s.counts(k);
                    SensorSummary {
                        enters,
                        leaves,
                        inside: s.bodies_in(k).len(),
                    }
                })
                .collect()
        }),
        sensor_log: args.sensor_log.as_ref().map(|p| p.display().to_string()),
        wall_work: stats.wall_work,
        arrivals: stats.arrivals,
        arrival_energy: stats.arrival_energy,
        histogram: scene.histogram.as_ref().map(|h| {
            let held = sim.histogram(h);
            HistogramSummary {
                axis: h.axis,
                edges: h.edges.clone(),
                counts: held.counts,
                outside: held.outside,
            }
        }),
        shear_stress,
        viscosity,
        velocity_profile: profile.map(|p| p.mean()),
    })
}

/// Where events go: the run file, if any; the first write error stops the run.
struct Sink<const D: usize> {
    writer: Option<RunWriter<std::fs::File, D>>,
    error: Option<ccdsim::record::RecordError>,
    /// Sheared boxes: the pressure tensor over the run, for the shear stress.
    stress: Option<PressureTensor<D>>,
}

impl<const D: usize> Sink<D> {
    /// Writes the edits `sim` journaled since the last call (the arrivals it brought in).
    fn take_edits(&mut self, sim: &mut Simulation<D>) {
        for e in sim.take_edits() {
            self.take(&e);
        }
    }

    fn take(&mut self, c: &ccdsim::Collision<D>) {
        if let Some(p) = self.stress.as_mut() {
            p.observe(c);
        }
        if let (Some(w), None) = (self.writer.as_mut(), &self.error) {
            if let Err(e) = w.write_event(c) {
                self.error = Some(e);
            }
        }
    }
}

fn print_summary(s: &Summary, builtin: bool) -> std::io::Result<()> {
    if builtin {
        outln!("Built-in example: a billiard break (16 balls, 4 cushions).")?;
    }
    outln!("{}D, {} bodies, finder {}", s.dim, s.bodies, s.finder)?;
    let resets = if s.resets > 0 {
        format!(", {} thermostat resets", s.resets)
    } else {
        String::new()
    };
    outln!(
        "simulated {} s in {} s of wall time: {} events ({} body-body, {} body-wall{resets}), {:.0} events/s",
        sig(s.sim_time, 10), sig(s.wall_seconds, 3), s.events, s.body_collisions, s.wall_collisions, s.events_per_second
    )?;
    // One relative drift, the library's (`EnergyBalance`, what `verify` prints): under gravity
    // it is the total energy's, printed with it.
    let gravity = s.potential_energy_start != 0.0 || s.potential_energy_end != 0.0;
    let drift = format!("relative drift {}", sig(s.energy_drift, 3));
    outln!(
        "kinetic energy {} -> {} J{}; largest overlap {} of a contact distance",
        sig(s.kinetic_energy_start, 10),
        sig(s.kinetic_energy_end, 10),
        if gravity {
            String::new()
        } else {
            format!(" ({drift})")
        },
        sig(s.max_overlap, 3)
    )?;
    if s.wall_work != 0.0 {
        outln!(
            "moving walls did {} J of work on the bodies (the drift leaves it out)",
            sig(s.wall_work, 10)
        )?;
    }
    if gravity {
        outln!(
            "under gravity: kinetic + potential energy {} -> {} J ({drift})",
            sig(s.kinetic_energy_start + s.potential_energy_start, 10),
            sig(s.kinetic_energy_end + s.potential_energy_end, 10),
        )?;
    }
    if let Some(rot) = s.rotational_temperature {
        outln!(
            "rough bodies: rotational temperature kT_rot {}; the drift counts rotational energy",
            num(rot)
        )?;
    }
    out!(
        "temperature kT {}; {} collisions per body per unit time",
        num(s.temperature),
        num(s.collision_rate)
    )?;
    match (s.pressure, s.compressibility) {
        (Some(p), Some(z)) => outln!("; pressure {}, compressibility factor Z {}", num(p), num(z))?,
        _ => outln!()?,
    }
    if let Some(stress) = s.shear_stress {
        match s.viscosity {
            Some(eta) => outln!(
                "sheared box: shear stress −P_xy {}, viscosity {} (temperature from peculiar velocities)",
                num(stress),
                num(eta)
            )?,
            None => outln!("sheared box: shear stress −P_xy {}", num(stress))?,
        }
    }
    if let Some(r) = &s.record {
        outln!("run file written to {r}")?;
    }
    if let Some(t) = &s.trajectory {
        outln!("{} frames written to {t}", s.frames)?;
    }
    for (k, c) in s.sensors.iter().enumerate() {
        outln!(
            "sensor {k}: {} entered, {} left, {} inside at the end",
            c.enters,
            c.leaves,
            c.inside
        )?;
    }
    if let Some(l) = &s.sensor_log {
        outln!("sensor events written to {l}")?;
    }
    if s.arrivals > 0 {
        outln!(
            "{} bodies arrived, bringing {} J (the drift leaves it out)",
            s.arrivals,
            sig(s.arrival_energy, 10)
        )?;
    }
    if let Some(h) = &s.histogram {
        print_histogram(h)?;
    }
    Ok(())
}

/// The histogram as rows of bars, one per bin: its edges, its count, a bar scaled to the
/// fullest bin.
fn print_histogram(h: &HistogramSummary) -> std::io::Result<()> {
    let total: u64 = h.counts.iter().sum();
    let axis = ["x", "y", "z"].get(h.axis).copied().unwrap_or("?");
    outln!(
        "histogram along {axis}: {total} bodies in {} bins, {} outside",
        h.counts.len(),
        h.outside
    )?;
    let most = h.counts.iter().copied().max().unwrap_or(0).max(1);
    for (k, &c) in h.counts.iter().enumerate() {
        let bar = "#".repeat(((c * 50).div_ceil(most)) as usize);
        outln!(
            "  [{:>9}, {:>9}) {c:>6} {bar}",
            sig(h.edges[k], 4),
            sig(h.edges[k + 1], 4)
        )?;
    }
    Ok(())
}

//! `ccdsim pack`: compress a dilute random gas into a jammed packing (Lubachevsky–Stillinger)
//! and write it as a scene and an extended XYZ frame.

use crate::number::{num, sig};
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use ccdsim::packing::{
    compress, dilute_start, finish_isostatic, CompressConfig, CompressStop, IsostaticConfig,
    Packed, SizeMix,
};
use ccdsim::trajectory::{Frame, TrajectoryFormat, TrajectoryWriter};
use ccdsim::Simulation;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `ccdsim pack`.
#[derive(clap::Args)]
pub struct Args {
    /// Dimension, 2 or 3.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// Number of bodies.
    #[arg(long, default_value_t = 1000)]
    n: usize,
    /// Two sizes, half the bodies this many times larger than the others (2D glasses: 1.4).
    #[arg(long, conflicts_with = "polydisperse")]
    bidisperse: Option<f64>,
    /// Radii uniform in 0.5·[1 − W, 1 + W] metres (default: all 0.5).
    #[arg(long)]
    polydisperse: Option<f64>,
    /// Growth rate Γ: every radius grows by Γ times its start value per second (kT = 1,
    /// unit-density masses). Faster growth jams at lower packing fractions.
    #[arg(long, default_value_t = 0.01)]
    rate: f64,
    /// A periodic box instead of walls.
    #[arg(long)]
    periodic: bool,
    /// Stop compressing when the reduced pressure P V / (N kT) passes this (default 10^12,
    /// or 10^4 with --isostatic).
    #[arg(long)]
    until_pressure: Option<f64>,
    /// Then take the packing to its jamming point, where its contacts hold it rigid
    /// (isostatic): soft-sphere energy minimisation, O'Hern et al. 2003.
    #[arg(long)]
    isostatic: bool,
    /// With --isostatic: stop when the mean overlap of the jammed soft packing is at most
    /// this fraction of a contact distance (the gaps of the packing written).
    #[arg(long, default_value_t = 1e-6, requires = "isostatic")]
    overlap: f64,
    /// Packing fraction of the random start.
    #[arg(long)]
    start_packing: Option<f64>,
    /// Contacts are gaps within this fraction of a contact distance (default 100·D divided
    /// by --until-pressure, at most 0.1: typical gaps are D / Z of a contact distance).
    #[arg(long)]
    contact_tolerance: Option<f64>,
    /// Stop after this many events at the most.
    #[arg(long)]
    max_events: Option<u64>,
    /// Random seed of the start.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Next-event finder (broad phase).
    #[arg(long, default_value = "cells")]
    finder: String,
    /// Write the packing to PREFIX.json (scene) and PREFIX.xyz (extended XYZ).
    #[arg(long, default_value = "packing")]
    out: PathBuf,
    /// Print one JSON object instead of the readable summary.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// The `--json` summary.
#[derive(Serialize)]
struct Summary {
    dim: usize,
    bodies: usize,
    packing_fraction: f64,
    reduced_pressure: f64,
    /// Why compression stopped: `pressure`, `max_events`, `no_events` or `halt`.
    stop: &'static str,
    events: u64,
    sim_time: f64,
    wall_seconds: f64,
    contacts: usize,
    wall_contacts: usize,
    rattlers: usize,
    mean_contacts: f64,
    contact_tolerance: f64,
    /// Contacts among the bodies that are not rattlers.
    held_contacts: usize,
    /// The fewest contacts that can hold those bodies rigid.
    isostatic_contacts: usize,
    /// Whether `held_contacts` reaches `isostatic_contacts`.
    rigid: bool,
    /// The isostatic finish, with --isostatic.
    #[serde(skip_serializing_if = "Option::is_none")]
    finish: Option<FinishSummary>,
    scene: String,
    xyz: String,
}

/// The `--json` summary's account of the isostatic finish.
#[derive(Serialize)]
struct FinishSummary {
    minimizations: usize,
    steps: u64,
    mean_overlap: f64,
    max_overlap: f64,
    radius_scale: f64,
    /// Packing fraction of the compressed packing, before the finish.
    compressed_packing_fraction: f64,
    wall_seconds: f64,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    if args.dim == 2 {
        pack::<2>(&args)
    } else {
        pack::<3>(&args)
    }
}

fn pack<const D: usize>(args: &Args) -> Result<ExitCode> {
    let mix = match (args.bidisperse, args.polydisperse) {
        (Some(r), _) => SizeMix::Bidisperse(r),
        (_, Some(w)) => SizeMix::Polydisperse(w),
        _ => SizeMix::Monodisperse,
    };
    let start_packing = args.start_packing.unwrap_or(if D == 2 { 0.3 } else { 0.2 });
    if args.n == 0 {
        bail!("--n: a packing needs at least one body");
    }
    let scene = dilute_start::<D>(args.n, start_packing, mix, args.periodic, args.seed)?;
    let until_pressure = args
        .until_pressure
        .unwrap_or(if args.isostatic { 1e4 } else { 1e12 });
    let config = CompressConfig {
        rate: args.rate,
        until_pressure,
        max_events: args.max_events,
        contact_tolerance: args.contact_tolerance.unwrap_or(0.0),
        ..CompressConfig::default()
    };
    let scene_path = with_extension(&args.out, "json");
    let xyz_path = with_extension(&args.out, "xyz");
    let started = Instant::now();
    // Progress: the decades of pressure climbed, out of those to the target.
    let decades = until_pressure.log10().max(1e-9);
    let mut progress = Progress::without_eta(1000, "compressing", args.quiet);
    let packed = compress(&scene, &args.finder, &config, |block| {
        let done = block.reduced_pressure.max(1.0).log10() / decades;
        progress.set((done.clamp(0.0, 1.0) * 1000.0) as u64);
    })?;
    progress.finish();
    let mut finish = None;
    let packed = if args.isostatic {
        let finish_started = Instant::now();
        // Progress: the decades of overlap shed, from 10^-3 down to the target.
        let mut bar = Progress::without_eta(1000, "finding the jamming point", args.quiet);
        let decades = (1e-3 / args.overlap).log10().max(1e-9);
        let compressed_fraction = packed.packing_fraction;
        let done = finish_isostatic(
            &packed,
            &IsostaticConfig {
                overlap: args.overlap,
                ..IsostaticConfig::default()
            },
            |overlap| {
                let done = (1e-3 / overlap).log10() / decades;
                bar.set((done.clamp(0.0, 1.0) * 1000.0) as u64);
            },
        )?;
        bar.finish();
        let f = done.finish.expect("the finish reports");
        finish = Some(FinishSummary {
            minimizations: f.minimizations,
            steps: f.steps,
            mean_overlap: f.mean_overlap,
            max_overlap: f.max_overlap,
            radius_scale: f.radius_scale,
            compressed_packing_fraction: compressed_fraction,
            wall_seconds: finish_started.elapsed().as_secs_f64(),
        });
        done
    } else {
        packed
    };
    let wall_seconds = started.elapsed().as_secs_f64();
    write_outputs(&packed, &scene_path, &xyz_path)?;
    let stop = match packed.stop {
        CompressStop::Pressure => "pressure",
        CompressStop::MaxEvents => "max_events",
        CompressStop::NoEvents => "no_events",
        CompressStop::Halt(h) => {
            eprintln!("warning: compression stopped early: {h}");
            "halt"
        }
    };
    let summary = Summary {
        dim: D,
        bodies: packed.scene.bodies.len(),
        packing_fraction: packed.packing_fraction,
        reduced_pressure: packed.reduced_pressure,
        stop,
        events: packed.events,
        sim_time: packed.time,
        wall_seconds,
        contacts: packed.contacts.pairs.len(),
        wall_contacts: packed.contacts.walls.len(),
        rattlers: packed.contacts.rattlers.len(),
        mean_contacts: packed.contacts.mean_contacts,
        contact_tolerance: packed.contact_tolerance,
        held_contacts: packed.contacts.held_contacts,
        isostatic_contacts: packed.contacts.isostatic_contacts,
        rigid: packed.contacts.is_rigid(),
        finish,
        scene: scene_path.display().to_string(),
        xyz: xyz_path.display().to_string(),
    };
    if args.json {
        outln!("{}", serde_json::to_string(&summary)?)?;
    } else {
        let s = &summary;
        outln!(
            "{}D, {} bodies, {}: packing fraction {}, reduced pressure {} ({})",
            s.dim,
            s.bodies,
            if args.periodic {
                "periodic box"
            } else {
                "walls"
            },
            num(s.packing_fraction),
            sig(s.reduced_pressure, 4),
            s.stop
        )?;
        outln!(
            "{} events in {} s of wall time; {} contacts ({} with walls) within {} of a \
             contact distance; {} rattlers; mean contact number {} without them",
            s.events,
            sig(s.wall_seconds, 3),
            s.contacts,
            s.wall_contacts,
            sig(s.contact_tolerance, 2),
            s.rattlers,
            sig(s.mean_contacts, 5)
        )?;
        if let Some(f) = &s.finish {
            outln!(
                "isostatic finish: {} minimisations, {} steps, {} s; packing fraction {} before; \
                 mean overlap {} at the jamming point",
                f.minimizations,
                f.steps,
                sig(f.wall_seconds, 3),
                num(f.compressed_packing_fraction),
                sig(f.mean_overlap, 2)
            )?;
        }
        if s.rigid {
            outln!(
                "rigid: {} contacts hold the {} bodies that are not rattlers (isostatic: {})",
                s.held_contacts,
                s.bodies - s.rattlers,
                s.isostatic_contacts
            )?;
        } else {
            outln!(
                "NOT RIGID: {} contacts among the {} bodies that are not rattlers, fewer than the \
                 {} that can hold them (try --isostatic)",
                s.held_contacts,
                s.bodies - s.rattlers,
                s.isostatic_contacts
            )?;
        }
        outln!("wrote {} and {}", s.scene, s.xyz)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// `PREFIX.EXT`, keeping any dots of the prefix.
fn with_extension(prefix: &Path, ext: &str) -> PathBuf {
    let mut s = prefix.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// Writes the packing's scene (JSON) and one extended XYZ frame of it; the scene must read
/// back as a valid scene.
fn write_outputs<const D: usize>(
    packed: &Packed<D>,
    scene_path: &Path,
    xyz_path: &Path,
) -> Result<()> {
    let sim = Simulation::new(&packed.scene, "all-pairs")
        .context("the packing does not read back as a valid scene")?;
    let json = packed.scene.to_json();
    std::fs::write(scene_path, json + "\n")
        .with_context(|| format!("cannot write {}", scene_path.display()))?;
    let mut xyz = TrajectoryWriter::create(xyz_path, TrajectoryFormat::ExtendedXyz)
        .with_context(|| format!("cannot write {}", xyz_path.display()))?;
    xyz.write(&Frame::of(&sim))?;
    xyz.finish()?;
    Ok(())
}

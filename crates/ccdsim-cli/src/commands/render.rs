//! `ccdsim render`: draw a run without a browser, as a PNG frame or an animated GIF.

use super::finder_args::FinderArgs;
use anyhow::{bail, Result};
use ccdsim_viewer::{render_gif, render_png, ColourBy, GifOptions, RenderOptions};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim render`.
#[derive(clap::Args)]
#[command(group = clap::ArgGroup::new("what").required(true).args(["at", "gif"]))]
pub struct Args {
    /// The run file.
    run: PathBuf,
    /// Draw one frame at this simulated time, seconds (with --out).
    #[arg(long, requires = "out", allow_negative_numbers = true)]
    at: Option<f64>,
    /// The PNG file --at writes.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write an animated GIF here.
    #[arg(long, conflicts_with_all = ["at", "out"])]
    gif: Option<PathBuf>,
    /// GIF frames per second.
    #[arg(long, default_value_t = 20.0)]
    fps: f64,
    /// Simulated seconds per second of GIF.
    #[arg(long, default_value_t = 1.0)]
    speed: f64,
    /// GIF start, simulated seconds [default: the run's start].
    #[arg(long, allow_negative_numbers = true)]
    from: Option<f64>,
    /// GIF end, simulated seconds [default: the run's end].
    #[arg(long, allow_negative_numbers = true)]
    to: Option<f64>,
    /// Draw the finder's boxes (swept leaves and inner nodes by depth).
    #[arg(long)]
    boxes: bool,
    /// Finder whose boxes --boxes draws.
    #[arg(long, default_value = "bvh")]
    finder: String,
    /// Image width, pixels.
    #[arg(long, default_value_t = 800)]
    width: u32,
    /// Image height, pixels [default: the run's aspect in 2D, square in 3D].
    #[arg(long)]
    height: Option<u32>,
    /// Body colours: id or speed.
    #[arg(long, default_value = "id")]
    colour: String,
    /// 3D camera: turn about the y axis, degrees.
    #[arg(long, default_value_t = 35.0)]
    yaw: f64,
    /// 3D camera: tilt, degrees.
    #[arg(long, default_value_t = 25.0)]
    pitch: f64,
    /// Leave out the simulated time drawn in each frame's top-left corner.
    #[arg(long)]
    no_time_label: bool,
    #[command(flatten)]
    finder_options: FinderArgs,
}

/// Runs the command and prints what was written.
pub fn run(args: Args) -> Result<ExitCode> {
    let colour: ColourBy = match args.colour.parse() {
        Ok(c) => c,
        Err(e) => bail!("--colour: {e}"),
    };
    let render = RenderOptions {
        width: args.width,
        height: args.height,
        colour,
        boxes: args.boxes,
        finder: args.finder.clone(),
        finder_options: args.finder_options.options()?,
        yaw_deg: args.yaw,
        pitch_deg: args.pitch,
        time_label: !args.no_time_label,
        ..RenderOptions::default()
    };
    if let (Some(at), Some(out)) = (args.at, &args.out) {
        let r = render_png(&args.run, at, out, &render)?;
        outln!(
            "wrote {} ({}×{} px, t = {} s, {} event{} before)",
            out.display(),
            r.width,
            r.height,
            r.from,
            r.events,
            if r.events == 1 { "" } else { "s" }
        )?;
    } else if let Some(gif) = &args.gif {
        let o = GifOptions {
            fps: args.fps,
            speed: args.speed,
            from: args.from,
            to: args.to,
            render,
        };
        let r = render_gif(&args.run, gif, &o)?;
        outln!(
            "wrote {} ({} frames, {}×{} px, t = {} … {} s, {} events)",
            gif.display(),
            r.frames,
            r.width,
            r.height,
            r.from,
            r.to,
            r.events
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

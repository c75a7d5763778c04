//! Headless rendering of runs: one PNG frame at a time, or an animated GIF.

mod camera;
pub mod colour;
mod draw;
mod gif_out;
mod palette;
mod pool_frame;
mod time_label;

pub use camera::Camera;
pub use colour::ColourBy;
pub use draw::{draw_frame, FrameInput};

use crate::error::ViewerError;
use crate::keyframes::KeyframeOptions;
use crate::playback::{Playback, Snapshot};
use ccdsim::finder::DebugBox;
use ccdsim::FinderOptions;
use std::path::Path;

/// How frames look.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width, pixels (at least 16).
    pub width: u32,
    /// Image height, pixels; `None` follows the run's aspect (2D) or makes a square (3D).
    pub height: Option<u32>,
    /// Body colouring.
    pub colour: ColourBy,
    /// Draw the finder's boxes.
    pub boxes: bool,
    /// Finder whose boxes are drawn; `bvh` by default.
    pub finder: String,
    /// Options of that finder.
    pub finder_options: FinderOptions,
    /// 3D camera: turn about the world's y axis, degrees.
    pub yaw_deg: f64,
    /// 3D camera: tilt about the camera's x axis, degrees.
    pub pitch_deg: f64,
    /// Keyframe density of the playback index.
    pub keyframes: KeyframeOptions,
    /// Draw each frame's simulated time in its top-left corner (`t = 1.250 s`); on by default.
    pub time_label: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: None,
            colour: ColourBy::Id,
            boxes: false,
            finder: "bvh".to_string(),
            finder_options: FinderOptions::default(),
            yaw_deg: 35.0,
            pitch_deg: 25.0,
            keyframes: KeyframeOptions::default(),
            time_label: true,
        }
    }
}

/// Options of [`render_gif`].
#[derive(Clone, Debug, PartialEq)]
pub struct GifOptions {
    /// Frames per second of the animation (> 0; GIF delays are whole centiseconds).
    pub fps: f64,
    /// Simulated seconds per second of animation (> 0).
    pub speed: f64,
    /// First frame's simulated time, seconds; the run's start by default.
    pub from: Option<f64>,
    /// Last frame's simulated time at most, seconds; the run's end by default.
    pub to: Option<f64>,
    /// How the frames look.
    pub render: RenderOptions,
}

impl Default for GifOptions {
    fn default() -> Self {
        GifOptions {
            fps: 20.0,
            speed: 1.0,
            from: None,
            to: None,
            render: RenderOptions::default(),
        }
    }
}

/// What a render wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderReport {
    /// Frames written (1 for a PNG).
    pub frames: u64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Simulated time of the first frame, seconds.
    pub from: f64,
    /// Simulated time of the last frame, seconds.
    pub to: f64,
    /// Events in the run at or before the last frame.
    pub events: u64,
}

/// Number of frames a GIF from `from` to `to` has: one every `speed / fps` simulated seconds,
/// both ends included when the span is a whole number of steps.
#[must_use]
pub fn gif_frame_count(from: f64, to: f64, fps: f64, speed: f64) -> u64 {
    let steps = ((to - from) * fps / speed * (1.0 + 1e-12)).floor();
    if steps.is_finite() && steps > 0.0 {
        steps as u64 + 1
    } else {
        1
    }
}

/// The finder's boxes at `snap`, or none when not asked for.
pub(crate) fn boxes_for<const D: usize>(
    p: &Playback<D>,
    snap: &Snapshot<D>,
    o: &RenderOptions,
) -> Result<Vec<DebugBox<D>>, ViewerError> {
    if o.boxes {
        p.finder_boxes(snap, &o.finder, &o.finder_options)
    } else {
        Ok(Vec::new())
    }
}

pub(crate) fn camera<const D: usize>(
    p: &Playback<D>,
    o: &RenderOptions,
) -> Result<Camera, ViewerError> {
    if o.width < 16 || o.width > 8192 {
        return Err(ViewerError::param(
            "width",
            format!("{} is not in 16..=8192 pixels", o.width),
        ));
    }
    if let Some(h) = o.height {
        if !(16..=8192).contains(&h) {
            return Err(ViewerError::param(
                "height",
                format!("{h} is not in 16..=8192 pixels"),
            ));
        }
    }
    let height = o.height.or(if D == 3 { Some(o.width) } else { None });
    Ok(Camera::fit(
        &p.extent().bounds,
        o.width,
        height,
        o.yaw_deg,
        o.pitch_deg,
    ))
}

pub(crate) fn frame_input<'a, const D: usize>(
    p: &'a Playback<D>,
    snap: &'a Snapshot<D>,
    boxes: &'a [DebugBox<D>],
    o: &RenderOptions,
    flash_window: f64,
) -> FrameInput<'a, D> {
    let span = p.end_time() - p.start_time();
    FrameInput {
        scene: p.scene(),
        snap,
        boxes,
        colour: o.colour,
        max_speed: p.extent().max_speed,
        flash_window,
        progress: (span > 0.0).then(|| (snap.time - p.start_time()) / span),
        bounds: p.extent().bounds,
        time_label: o.time_label,
    }
}

/// Renders the state of `p` at time `at` to a PNG image in memory; bodies colliding exactly
/// at `at` are highlighted.
pub fn png_bytes<const D: usize>(
    p: &mut Playback<D>,
    at: f64,
    o: &RenderOptions,
) -> Result<(Vec<u8>, RenderReport), ViewerError> {
    if !at.is_finite() {
        return Err(ViewerError::param("at", "is not a finite time"));
    }
    // Outside the recorded span nothing is known of the bodies: an empty table would be a
    // picture of nothing that looks like an answer.
    let (start, end) = (p.start_time(), p.end_time());
    if at < start || at > end {
        return Err(ViewerError::param(
            "at",
            format!("{at} s lies outside the run, which covers {start} … {end} s"),
        ));
    }
    let cam = camera(p, o)?;
    let snap = p.snapshot_at(at)?;
    let boxes = boxes_for(p, &snap, o)?;
    let pm = draw_frame(&cam, &frame_input(p, &snap, &boxes, o, 0.0));
    let bytes = pm.encode_png().map_err(|e| ViewerError::Encode {
        path: "PNG".into(),
        why: e.to_string(),
    })?;
    let report = RenderReport {
        frames: 1,
        width: cam.width,
        height: cam.height,
        from: at,
        to: at,
        events: snap.applied,
    };
    Ok((bytes, report))
}

/// Whether the run file at `run` is a pool shot's (format version 16).
fn is_pool_shot(run: &Path) -> Result<bool, ViewerError> {
    Ok(ccdsim::record::run_file_version(run)? == ccdsim::record::VERSION_POOL)
}

/// Renders the run at `run` at simulated time `at` (seconds) to the PNG file `out`. Nothing
/// is written when anything fails. A pool shot's run file is drawn as its table seen from
/// above, `at` seconds after the strike (no finder boxes; the balls in their own colours).
pub fn render_png(
    run: &Path,
    at: f64,
    out: &Path,
    o: &RenderOptions,
) -> Result<RenderReport, ViewerError> {
    if is_pool_shot(run)? {
        return pool_frame::pool_png(run, at, out, o);
    }
    let (bytes, report) = match crate::AnyPlayback::open(run, &o.keyframes)? {
        crate::AnyPlayback::D2(mut p) => png_bytes(&mut p, at, o)?,
        crate::AnyPlayback::D3(mut p) => png_bytes(&mut p, at, o)?,
    };
    std::fs::write(out, bytes).map_err(|source| ViewerError::Io {
        what: out.display().to_string(),
        source,
    })?;
    Ok(report)
}

/// Renders the run at `run` to the animated GIF `out`: frames every `speed / fps` simulated
/// seconds from `from` to `to` (see [`gif_frame_count`]), each showing the bodies that
/// collided since the frame before (or within the last 0.15 s of animation) flashing. The
/// file appears only when complete. A pool shot's run file is drawn as in [`render_png`],
/// from the strike to the shot's end by default.
pub fn render_gif(run: &Path, out: &Path, o: &GifOptions) -> Result<RenderReport, ViewerError> {
    if is_pool_shot(run)? {
        return pool_frame::pool_gif(run, out, o);
    }
    match crate::AnyPlayback::open(run, &o.render.keyframes)? {
        crate::AnyPlayback::D2(mut p) => gif_out::gif_file(&mut p, out, o),
        crate::AnyPlayback::D3(mut p) => gif_out::gif_file(&mut p, out, o),
    }
}

//! Writing animated GIFs: frames rendered one after the other as the run is replayed
//! forward, each stored as the rectangle that changed since the frame before.

use super::{
    boxes_for, camera, draw_frame, frame_input, gif_frame_count, palette, GifOptions, RenderReport,
};
use crate::error::ViewerError;
use crate::playback::Playback;
use ccdsim::Collision;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use tiny_skia::Pixmap;

/// A rectangle of a frame, pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Rect {
    left: u16,
    top: u16,
    width: u16,
    height: u16,
}

/// The smallest rectangle holding every pixel that differs between two `w`×`h` frames; a
/// single pixel when none does (a GIF frame cannot be empty).
fn changed_rect(a: &[u8], b: &[u8], w: u16, h: u16) -> Rect {
    let (w, h) = (usize::from(w), usize::from(h));
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        let (ra, rb) = (&a[y * w..(y + 1) * w], &b[y * w..(y + 1) * w]);
        if ra == rb {
            continue;
        }
        let first = ra
            .iter()
            .zip(rb)
            .position(|(p, q)| p != q)
            .expect("rows differ");
        let last = ra
            .iter()
            .zip(rb)
            .rposition(|(p, q)| p != q)
            .expect("rows differ");
        (x0, x1, y0, y1) = (x0.min(first), x1.max(last), y0.min(y), y);
    }
    if x0 > x1 {
        return Rect {
            left: 0,
            top: 0,
            width: 1,
            height: 1,
        };
    }
    let n = |v: usize| u16::try_from(v).expect("frames are at most 8192 px");
    Rect {
        left: n(x0),
        top: n(y0),
        width: n(x1 - x0 + 1),
        height: n(y1 - y0 + 1),
    }
}

/// Checks `o`'s frame rate and speed of time, and that `from ≤ to` are finite.
pub(crate) fn check_gif_options(o: &GifOptions, from: f64, to: f64) -> Result<(), ViewerError> {
    if !(o.fps.is_finite() && o.fps > 0.0 && o.fps <= 100.0) {
        return Err(ViewerError::param(
            "fps",
            format!("{} is not in (0, 100]", o.fps),
        ));
    }
    if !(o.speed.is_finite() && o.speed > 0.0) {
        return Err(ViewerError::param(
            "speed",
            format!("{} is not a positive number", o.speed),
        ));
    }
    if !(from.is_finite() && to.is_finite() && to >= from) {
        return Err(ViewerError::param(
            "from/to",
            format!("need finite from ≤ to, got {from} and {to}"),
        ));
    }
    Ok(())
}

/// Runs `write` on a temporary file beside `out` and renames it to `out` when it succeeds,
/// so that `out` appears only when complete; removes it when it fails.
pub(crate) fn write_atomically<R>(
    out: &Path,
    write: impl FnOnce(&Path) -> Result<R, ViewerError>,
) -> Result<R, ViewerError> {
    let tmp: PathBuf = {
        let mut s = out.as_os_str().to_owned();
        s.push(".partial");
        s.into()
    };
    match write(&tmp) {
        Ok(report) => {
            std::fs::rename(&tmp, out).map_err(|source| ViewerError::Io {
                what: out.display().to_string(),
                source,
            })?;
            Ok(report)
        }
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

pub(crate) fn gif_file<const D: usize>(
    p: &mut Playback<D>,
    out: &Path,
    o: &GifOptions,
) -> Result<RenderReport, ViewerError> {
    let from = o.from.unwrap_or(p.start_time());
    let to = o.to.unwrap_or(p.end_time());
    check_gif_options(o, from, to)?;
    write_atomically(out, |tmp| write_gif(p, tmp, from, to, o))
}

fn write_gif<const D: usize>(
    p: &mut Playback<D>,
    path: &Path,
    from: f64,
    to: f64,
    o: &GifOptions,
) -> Result<RenderReport, ViewerError> {
    let cam = camera(p, &o.render)?;
    let frames = gif_frame_count(from, to, o.fps, o.speed);
    let step = o.speed / o.fps;
    let flash_window = step.max(0.15 * o.speed);
    // One snapshot, then events applied forward as the frames' time advances.
    let mut snap = p.snapshot_at(from)?;
    let mut events = EventCursor::new(snap.applied);
    let mut last_t = from;
    encode_gif(path, cam.width, cam.height, o.fps, frames, |k| {
        let t = from + k as f64 * step;
        while let Some(c) = events.peek(p)?.filter(|c| c.event.time <= t) {
            snap.states.apply(&c);
            snap.applied += 1;
            snap.last = Some(c);
            events.advance();
        }
        snap.time = t;
        last_t = t;
        let boxes = boxes_for(p, &snap, &o.render)?;
        Ok(draw_frame(
            &cam,
            &frame_input(p, &snap, &boxes, &o.render, flash_window),
        ))
    })?;
    Ok(RenderReport {
        frames,
        width: cam.width,
        height: cam.height,
        from,
        to: last_t,
        events: snap.applied,
    })
}

/// Writes an animated GIF of `frames` frames of `width`×`height` pixels, `fps` a second,
/// looping, to `path`: frame `k` is what `draw(k)` paints, mapped to the fixed palette.
pub(crate) fn encode_gif(
    path: &Path,
    width: u32,
    height: u32,
    fps: f64,
    frames: u64,
    mut draw: impl FnMut(u64) -> Result<Pixmap, ViewerError>,
) -> Result<(), ViewerError> {
    let io = |source| ViewerError::Io {
        what: path.display().to_string(),
        source,
    };
    let enc_err = |e: gif::EncodingError| ViewerError::Encode {
        path: path.display().to_string(),
        why: e.to_string(),
    };
    let file = BufWriter::new(File::create(path).map_err(io)?);
    let (w, h) = (width as u16, height as u16);
    let mut enc = gif::Encoder::new(file, w, h, &palette::palette()).map_err(enc_err)?;
    enc.set_repeat(gif::Repeat::Infinite).map_err(enc_err)?;
    let delay = (100.0 / fps).round().max(1.0) as u16;
    let mut indices = vec![0u8; usize::from(w) * usize::from(h)];
    let mut previous = indices.clone();
    for k in 0..frames {
        let pm = draw(k)?;
        for (dst, px) in indices.iter_mut().zip(pm.pixels()) {
            let c = px.demultiply();
            *dst = palette::index_of([c.red(), c.green(), c.blue()]);
        }
        // Only the rectangle that changed since the frame before is stored: the rest of the
        // picture stays on screen (GIF frames are drawn over the previous ones by default).
        let r = if k == 0 {
            Rect {
                left: 0,
                top: 0,
                width: w,
                height: h,
            }
        } else {
            changed_rect(&previous, &indices, w, h)
        };
        let mut sub = Vec::with_capacity(usize::from(r.width) * usize::from(r.height));
        for y in r.top..r.top + r.height {
            let row = usize::from(y) * usize::from(w);
            sub.extend_from_slice(
                &indices[row + usize::from(r.left)..row + usize::from(r.left + r.width)],
            );
        }
        std::mem::swap(&mut previous, &mut indices);
        let frame = gif::Frame {
            left: r.left,
            top: r.top,
            width: r.width,
            height: r.height,
            delay,
            buffer: std::borrow::Cow::Owned(sub),
            ..gif::Frame::default()
        };
        enc.write_frame(&frame).map_err(enc_err)?;
    }
    enc.into_inner()
        .map_err(io)?
        .into_inner()
        .map_err(|e| io(e.into_error()))?;
    Ok(())
}

/// Reads a run's events in order, a window at a time (a seek per event would throw the
/// reader's buffer away each time).
struct EventCursor<const D: usize> {
    next: u64,
    window: std::collections::VecDeque<Collision<D>>,
}

impl<const D: usize> EventCursor<D> {
    const WINDOW: u64 = 4096;

    fn new(first: u64) -> Self {
        EventCursor {
            next: first,
            window: std::collections::VecDeque::new(),
        }
    }

    /// The next event, if the run has one.
    fn peek(&mut self, p: &mut Playback<D>) -> Result<Option<Collision<D>>, ViewerError> {
        if self.window.is_empty() {
            self.window
                .extend(p.events_window(self.next, Self::WINDOW)?);
        }
        Ok(self.window.front().copied())
    }

    /// Moves past the event [`EventCursor::peek`] returned.
    fn advance(&mut self) {
        if self.window.pop_front().is_some() {
            self.next += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn changed_rect_bounds_the_differences() {
        let a = vec![0u8; 6 * 4];
        let mut b = a.clone();
        assert_eq!(
            changed_rect(&a, &b, 6, 4),
            Rect {
                left: 0,
                top: 0,
                width: 1,
                height: 1
            }
        );
        b[6 + 4] = 1; // (4, 1)
        b[2 * 6 + 2] = 1; // (2, 2)
        assert_eq!(
            changed_rect(&a, &b, 6, 4),
            Rect {
                left: 2,
                top: 1,
                width: 3,
                height: 2
            }
        );
    }
}

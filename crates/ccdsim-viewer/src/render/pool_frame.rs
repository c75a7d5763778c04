//! Pool shots drawn headless, to a PNG frame or an animated GIF: the table seen from above
//! with its long side left to right (as on the pool page, `assets/pool.js`, in its colours),
//! the balls where the cloth's motion laws put them, a pocketed ball gone from the moment it
//! drops.

use super::colour::Rgb;
use super::gif_out::{check_gif_options, encode_gif, write_atomically};
use super::time_label::draw_time_label;
use super::{gif_frame_count, ColourBy, GifOptions, RenderOptions, RenderReport};
use crate::error::ViewerError;
use crate::pool::PoolPlayback;
use ccdsim::billiards::Table;
use std::path::Path;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

const CLOTH: Rgb = [29, 107, 58];
const RAIL: Rgb = [90, 58, 34];
const CUSHION: Rgb = [47, 138, 79];
const POCKET: Rgb = [5, 5, 5];
const CUE: Rgb = [244, 241, 230];
const UNKNOWN: Rgb = [192, 192, 192];
/// Balls 1–8 (9–15 are the striped 1–7).
const NUMBERED: [Rgb; 8] = [
    [242, 195, 24],
    [31, 71, 199],
    [209, 49, 43],
    [94, 42, 140],
    [240, 122, 20],
    [22, 128, 74],
    [122, 31, 36],
    [20, 20, 20],
];
/// Room around the table's playing area, metres.
const MARGIN: f64 = 0.12;
/// Width of the rail drawn around the playing area, metres.
const RAIL_WIDTH: f64 = 0.09;

/// A ball's colour, and whether it is striped, by its name.
fn ball_colour(name: &str) -> (Rgb, bool) {
    if name == "cue" {
        return (CUE, false);
    }
    match name.parse::<usize>() {
        Ok(k @ 1..=8) => (NUMBERED[k - 1], false),
        Ok(k @ 9..=15) => (NUMBERED[k - 9], true),
        _ => (UNKNOWN, false),
    }
}

fn paint(c: Rgb) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], 255));
    p.anti_alias = true;
    p
}

/// Table coordinates (x across, y along the long side, metres) to pixels: a quarter turn
/// that puts the long side left to right.
#[derive(Clone, Copy, Debug)]
struct TableView {
    width: u32,
    height: u32,
    scale: f64,
    ox: f64,
    oy: f64,
}

impl TableView {
    /// The whole table with its margin in `width` pixels, and `height` pixels (by default the
    /// table's aspect).
    fn fit(table: &Table, width: u32, height: Option<u32>) -> Result<TableView, ViewerError> {
        let (w, h) = (table.length + 2.0 * MARGIN, table.width + 2.0 * MARGIN);
        if !(16..=8192).contains(&width) {
            return Err(ViewerError::param(
                "width",
                format!("{width} is not in 16..=8192 pixels"),
            ));
        }
        let height = height.unwrap_or(((f64::from(width) * h / w).round() as u32).max(16));
        if !(16..=8192).contains(&height) {
            return Err(ViewerError::param(
                "height",
                format!("{height} is not in 16..=8192 pixels"),
            ));
        }
        let scale = (f64::from(width) / w).min(f64::from(height) / h);
        Ok(TableView {
            width,
            height,
            scale,
            ox: (f64::from(width) - table.length * scale) / 2.0,
            oy: (f64::from(height) - table.width * scale) / 2.0,
        })
    }

    fn pixel_of(&self, x: f64, y: f64) -> (f32, f32) {
        (
            (self.ox + y * self.scale) as f32,
            (self.oy + x * self.scale) as f32,
        )
    }
}

fn fill_circle(pm: &mut Pixmap, (x, y): (f32, f32), r: f32, c: Rgb) {
    if let Some(path) = PathBuilder::from_circle(x, y, r) {
        pm.fill_path(
            &path,
            &paint(c),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// The band of a striped ball: the disc at `(x, y)` of radius `r` between the chords at
/// `±0.55 r` from its centre.
fn stripe(x: f32, y: f32, r: f32) -> Option<tiny_skia::Path> {
    const SIDE: usize = 12;
    let half = 0.55 * r;
    let reach = (half / r).asin();
    let mut pb = PathBuilder::new();
    for k in 0..=SIDE {
        let a = -reach + 2.0 * reach * k as f32 / SIDE as f32;
        let (s, c) = a.sin_cos();
        if k == 0 {
            pb.move_to(x + r * c, y + r * s);
        } else {
            pb.line_to(x + r * c, y + r * s);
        }
    }
    for k in 0..=SIDE {
        let a = std::f32::consts::PI - reach + 2.0 * reach * k as f32 / SIDE as f32;
        let (s, c) = a.sin_cos();
        pb.line_to(x + r * c, y + r * s);
    }
    pb.close();
    pb.finish()
}

/// The table, and the balls at `balls` (`None`: pocketed), named `names`, of radius
/// `radius` metres; the time `t` in the corner when `time_label`.
fn draw_pool_frame(
    view: &TableView,
    table: &Table,
    radius: f64,
    names: &[String],
    balls: &[Option<[f64; 2]>],
    t: f64,
    time_label: bool,
) -> Pixmap {
    let mut pm = Pixmap::new(view.width, view.height).expect("a view is at least 16×16");
    let bg = super::colour::BACKGROUND;
    pm.fill(Color::from_rgba8(bg[0], bg[1], bg[2], 255));
    let s = view.scale;
    let (x0, y0) = view.pixel_of(0.0, 0.0);
    let rect = |pad: f64| {
        Rect::from_xywh(
            x0 - (pad * s) as f32,
            y0 - (pad * s) as f32,
            ((table.length + 2.0 * pad) * s) as f32,
            ((table.width + 2.0 * pad) * s) as f32,
        )
    };
    for (pad, c) in [(RAIL_WIDTH, RAIL), (0.035, CLOTH)] {
        if let Some(r) = rect(pad) {
            pm.fill_rect(r, &paint(c), Transform::identity(), None);
        }
    }
    for p in &table.pockets {
        fill_circle(
            &mut pm,
            view.pixel_of(p.center[0], p.center[1]),
            (p.radius * s) as f32,
            POCKET,
        );
    }
    let line = Stroke {
        width: (0.004 * s).max(1.5) as f32,
        line_cap: tiny_skia::LineCap::Round,
        ..Stroke::default()
    };
    let mut pb = PathBuilder::new();
    for c in &table.cushions {
        let (a, b) = view.pixel_of(c.p1[0], c.p1[1]);
        let (e, f) = view.pixel_of(c.p2[0], c.p2[1]);
        pb.move_to(a, b);
        pb.line_to(e, f);
    }
    for j in &table.jaws {
        let (x, y) = view.pixel_of(j.center[0], j.center[1]);
        pb.push_circle(x, y, (j.radius * s) as f32);
    }
    if let Some(path) = pb.finish() {
        pm.stroke_path(&path, &paint(CUSHION), &line, Transform::identity(), None);
    }
    let r = (radius * s) as f32;
    let rim = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    for (name, at) in names.iter().zip(balls) {
        let Some([x, y]) = *at else { continue };
        let (sx, sy) = view.pixel_of(x, y);
        let (colour, striped) = ball_colour(name);
        fill_circle(&mut pm, (sx, sy), r, if striped { CUE } else { colour });
        if striped {
            if let Some(band) = stripe(sx, sy, r) {
                pm.fill_path(
                    &band,
                    &paint(colour),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
        if let Some(edge) = PathBuilder::from_circle(sx, sy, r) {
            pm.stroke_path(&edge, &paint([0, 0, 0]), &rim, Transform::identity(), None);
        }
    }
    if time_label {
        draw_time_label(&mut pm, t);
    }
    pm
}

/// What a pool shot cannot be drawn with: the finder's boxes, colouring by speed.
fn check_pool_options(o: &RenderOptions) -> Result<(), ViewerError> {
    if o.boxes {
        return Err(ViewerError::param(
            "boxes",
            "a pool shot is drawn without finder boxes",
        ));
    }
    if o.colour != ColourBy::Id {
        return Err(ViewerError::param(
            "colour",
            "a pool shot's balls keep their own colours",
        ));
    }
    Ok(())
}

/// Renders the pool shot's run file at `run` at `at` seconds after the strike to the PNG
/// file `out`. Nothing is written when anything fails.
pub(crate) fn pool_png(
    run: &Path,
    at: f64,
    out: &Path,
    o: &RenderOptions,
) -> Result<RenderReport, ViewerError> {
    check_pool_options(o)?;
    let p = PoolPlayback::open(run)?;
    if !(at.is_finite() && (0.0..=p.end()).contains(&at)) {
        return Err(ViewerError::param(
            "at",
            format!(
                "{at} s lies outside the shot, which covers 0 … {} s",
                p.end()
            ),
        ));
    }
    let view = TableView::fit(p.table(), o.width, o.height)?;
    let pm = draw_pool_frame(
        &view,
        p.table(),
        p.radius(),
        &p.names(),
        &p.balls_at(at),
        at,
        o.time_label,
    );
    let bytes = pm.encode_png().map_err(|e| ViewerError::Encode {
        path: "PNG".into(),
        why: e.to_string(),
    })?;
    std::fs::write(out, bytes).map_err(|source| ViewerError::Io {
        what: out.display().to_string(),
        source,
    })?;
    Ok(RenderReport {
        frames: 1,
        width: view.width,
        height: view.height,
        from: at,
        to: at,
        events: events_until(&p, at),
    })
}

/// Renders the pool shot's run file at `run` to the animated GIF `out` (frames every
/// `speed / fps` seconds from `from`, by default the strike, to `to`, by default the shot's
/// end). The file appears only when complete.
pub(crate) fn pool_gif(
    run: &Path,
    out: &Path,
    o: &GifOptions,
) -> Result<RenderReport, ViewerError> {
    check_pool_options(&o.render)?;
    let p = PoolPlayback::open(run)?;
    let from = o.from.unwrap_or(0.0);
    let to = o.to.unwrap_or(p.end());
    check_gif_options(o, from, to)?;
    if from < 0.0 || to > p.end() {
        return Err(ViewerError::param(
            "from/to",
            format!(
                "{from} … {to} s is not within the shot, which covers 0 … {} s",
                p.end()
            ),
        ));
    }
    let view = TableView::fit(p.table(), o.render.width, o.render.height)?;
    let frames = gif_frame_count(from, to, o.fps, o.speed);
    let step = o.speed / o.fps;
    let names = p.names();
    let time = |k: u64| (from + k as f64 * step).min(to);
    write_atomically(out, |tmp| {
        encode_gif(tmp, view.width, view.height, o.fps, frames, |k| {
            let t = time(k);
            Ok(draw_pool_frame(
                &view,
                p.table(),
                p.radius(),
                &names,
                &p.balls_at(t),
                t,
                o.render.time_label,
            ))
        })
    })?;
    let last = time(frames.saturating_sub(1));
    Ok(RenderReport {
        frames,
        width: view.width,
        height: view.height,
        from,
        to: last,
        events: events_until(&p, last),
    })
}

/// Records of the shot (the strike included) at or before `t`.
fn events_until(p: &PoolPlayback, t: f64) -> u64 {
    p.records()
        .iter()
        .filter(|r| !matches!(r, ccdsim::billiards::PoolRecord::End(_)) && r.time() <= t)
        .count() as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use ccdsim::billiards::{record_shot, Game, PoolRunWriter, PoolScene};

    fn pixel(pm: &Pixmap, (x, y): (f32, f32)) -> [u8; 3] {
        let c = pm
            .pixel(x.round() as u32, y.round() as u32)
            .expect("inside")
            .demultiply();
        [c.red(), c.green(), c.blue()]
    }

    fn recorded_break(dir: &Path) -> std::path::PathBuf {
        let path = dir.join("break.ccd");
        let scene = PoolScene::racked(Game::NineBall, 1);
        let (_shot, _records) = record_shot(
            &scene,
            PoolRunWriter::create(&path, &scene).unwrap(),
            10_000,
        )
        .unwrap();
        path
    }

    #[test]
    fn every_ball_is_drawn_in_its_colour_where_the_shot_has_it() {
        let dir = tempfile::tempdir().unwrap();
        let p = PoolPlayback::open(&recorded_break(dir.path())).unwrap();
        let view = TableView::fit(p.table(), 900, None).unwrap();
        assert!(view.width == 900 && view.height < 600, "{view:?}");
        let names = p.names();
        for t in [0.0, 0.5 * p.end(), p.end()] {
            let balls = p.balls_at(t);
            let pm = draw_pool_frame(&view, p.table(), p.radius(), &names, &balls, t, false);
            for (name, at) in names.iter().zip(&balls) {
                let Some([x, y]) = *at else { continue };
                let (colour, _) = ball_colour(name);
                // The centre of a striped ball is its band, of the same colour.
                assert_eq!(
                    pixel(&pm, view.pixel_of(x, y)),
                    colour,
                    "ball {name} at {t} s"
                );
            }
        }
    }

    #[test]
    fn a_pocketed_ball_is_gone_from_the_moment_it_drops() {
        let dir = tempfile::tempdir().unwrap();
        // A break that pockets a ball: the first seed whose shot does.
        let (path, ball, time) = (1..40)
            .find_map(|seed| {
                let path = dir.path().join(format!("b{seed}.ccd"));
                let scene = PoolScene::racked(Game::NineBall, seed);
                let (shot, _) = record_shot(
                    &scene,
                    PoolRunWriter::create(&path, &scene).unwrap(),
                    10_000,
                )
                .unwrap();
                shot.events().iter().find_map(|e| match e.kind {
                    ccdsim::billiards::ShotEventKind::Pocket { ball, .. } => {
                        Some((path.clone(), ball, e.time))
                    }
                    _ => None,
                })
            })
            .expect("some break pockets a ball");
        let p = PoolPlayback::open(&path).unwrap();
        assert!(p.balls_at(time * (1.0 - 1e-9))[ball].is_some());
        assert!(p.balls_at(time)[ball].is_none());
        assert!(p.balls_at(p.end())[ball].is_none());
    }

    #[test]
    fn a_break_renders_to_a_png_and_a_gif_and_bad_options_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let run = recorded_break(dir.path());
        let png = dir.path().join("at.png");
        let r = pool_png(&run, 0.3, &png, &RenderOptions::default()).unwrap();
        assert_eq!((r.frames, r.width), (1, 800));
        assert!(r.events >= 1);
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        let gif = dir.path().join("break.gif");
        let o = GifOptions {
            fps: 10.0,
            to: Some(1.0),
            render: RenderOptions {
                width: 320,
                ..RenderOptions::default()
            },
            ..GifOptions::default()
        };
        let r = pool_gif(&run, &gif, &o).unwrap();
        assert_eq!(r.frames, 11);
        assert!((r.to - 1.0).abs() < 1e-12);
        assert_eq!(&std::fs::read(&gif).unwrap()[..6], b"GIF89a");
        let boxes = RenderOptions {
            boxes: true,
            ..RenderOptions::default()
        };
        assert!(pool_png(&run, 0.3, &png, &boxes).is_err());
        assert!(pool_png(&run, -1.0, &png, &RenderOptions::default()).is_err());
        let late = GifOptions { to: Some(1e9), ..o };
        let gone = dir.path().join("late.gif");
        assert!(pool_gif(&run, &gone, &late).is_err());
        assert!(!gone.exists());
    }
}

//! Headless rendering: bodies land on the pixels they should, GIFs have the frames asked for.

use crate::common;

use ccdsim::generate::box_walls;
use ccdsim::{BodySpec, Scene, Vector};
use ccdsim_viewer::render::colour::{self, Rgb};
use ccdsim_viewer::{render_gif, render_png, GifOptions, RenderOptions};
use tiny_skia::Pixmap;

/// Two discs on a 2 m × 1 m table: body 7 at (0.5, 0.5) moving right at 1 m/s, body 9 at
/// rest at (1.5, 0.5); both of radius 0.1 m. They touch at t = 0.8 s.
fn two_discs() -> Scene<2> {
    let body = |id, x, vx| BodySpec {
        id: Some(id),
        ..BodySpec::new(Vector([x, 0.5]), Vector([vx, 0.0]), 0.1)
    };
    Scene {
        bodies: vec![body(7, 0.5, 1.0), body(9, 1.5, 0.0)],
        walls: box_walls(Vector([2.0, 1.0])),
        ..Scene::default()
    }
}

/// With a width of 216 px the 2 m table is drawn at 100 px/m inside an 8 px margin, y up.
fn pixel(pm: &Pixmap, x: f64, y: f64) -> Rgb {
    let (px, py) = (
        (8.0 + 100.0 * x).floor() as u32,
        (108.0 - 100.0 * y).floor() as u32,
    );
    let c = pm.pixel(px, py).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

fn id_colour(id: u64) -> Rgb {
    colour::id_colour(colour::id_bucket(id))
}

fn options() -> RenderOptions {
    RenderOptions {
        width: 216,
        ..RenderOptions::default()
    }
}

#[test]
fn a_png_has_body_pixels_where_the_bodies_are() {
    let dir = common::temp_dir("render-png");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let out = dir.join("frame.png");
    let report = render_png(&run, 0.3, &out, &options()).unwrap();
    assert_eq!((report.width, report.height), (216, 116));
    let pm = Pixmap::load_png(&out).unwrap();
    assert_eq!((pm.width(), pm.height()), (216, 116));
    // Body 7 has moved 0.3 m to x = 0.8; body 9 has not moved.
    assert_eq!(pixel(&pm, 0.8, 0.5), id_colour(7));
    assert_eq!(pixel(&pm, 0.8 + 0.07, 0.5 + 0.05), id_colour(7));
    assert_eq!(pixel(&pm, 1.5, 0.5), id_colour(9));
    // Where body 7 started is empty now, and so is a point between them.
    assert_eq!(pixel(&pm, 0.5, 0.5), colour::BACKGROUND);
    assert_eq!(pixel(&pm, 1.15, 0.5), colour::BACKGROUND);
    assert_eq!(pixel(&pm, 0.8, 0.75), colour::BACKGROUND);
    // The bottom wall runs along y = 0 (a 1.5 px anti-aliased line: mostly wall colour).
    let wall = pixel(&pm, 1.0, 0.0);
    assert!(wall.iter().all(|&c| c > 120), "{wall:?}");
    assert_eq!(pixel(&pm, 1.0, 0.05), colour::BACKGROUND);
}

#[test]
fn a_png_at_an_event_shows_the_pair_touching_and_flashing() {
    let dir = common::temp_dir("render-flash");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let out = dir.join("frame.png");
    // The first event: body 7's right side meets body 9's left side at x = 1.4, at t = 0.8
    // up to rounding; bodies flash at the exact time of their event.
    let mut p = ccdsim_viewer::Playback::<2>::open(&run, &Default::default()).unwrap();
    let hit = p.event(0).unwrap();
    assert_eq!((hit.event.a, hit.event.b), (0, 1));
    assert!((hit.event.time - 0.8).abs() < 1e-12);
    render_png(&run, hit.event.time, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    assert_eq!(pixel(&pm, 1.3, 0.5), colour::FLASH_FILL);
    assert_eq!(pixel(&pm, 1.5, 0.5), colour::FLASH_FILL);
    // Where they touch, two anti-aliased edges meet: nearly full white, no background gap.
    let joint = pixel(&pm, 1.4, 0.5);
    assert!(
        joint.iter().all(|&c| c >= 230),
        "gap where they touch: {joint:?}"
    );
    // Later, body 9 has taken the velocity and nothing flashes.
    render_png(&run, 1.0, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    assert_eq!(pixel(&pm, 1.3, 0.5), id_colour(7));
    assert_eq!(pixel(&pm, 1.7, 0.5), id_colour(9));
    assert_eq!(pixel(&pm, 1.5, 0.5), colour::BACKGROUND);
}

#[test]
fn a_3d_png_draws_a_sphere_at_the_centre() {
    let dir = common::temp_dir("render-3d");
    let scene = Scene::<3> {
        bodies: vec![BodySpec {
            id: Some(3),
            ..BodySpec::new(Vector([1.0, 1.0, 1.0]), Vector([0.0; 3]), 0.2)
        }],
        walls: box_walls(Vector([2.0, 2.0, 2.0])),
        ..Scene::default()
    };
    let run = dir.join("one.ccd");
    common::record(&scene, 1.0, &run);
    let out = dir.join("frame.png");
    let report = render_png(&run, 0.5, &out, &options()).unwrap();
    assert_eq!((report.width, report.height), (216, 216));
    let pm = Pixmap::load_png(&out).unwrap();
    // The sphere is at the box's centre, which the camera puts at the image centre; its
    // highlight is up and to the left, so a point down and to the right has the body colour.
    let c = pm.pixel(108 + 5, 108 + 5).unwrap().demultiply();
    assert_eq!([c.red(), c.green(), c.blue()], id_colour(3));
    let c = pm.pixel(4, 108).unwrap().demultiply();
    assert_eq!([c.red(), c.green(), c.blue()], colour::BACKGROUND);
}

fn gif_frames(path: &std::path::Path) -> (usize, u16, u16) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut d = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let (w, h) = (d.width(), d.height());
    let mut n = 0;
    while d.read_next_frame().unwrap().is_some() {
        n += 1;
    }
    (n, w, h)
}

#[test]
fn a_gif_has_the_requested_frames() {
    let dir = common::temp_dir("render-gif");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let out = dir.join("anim.gif");
    // 1 simulated second at 10 frames per second of real time: frames at 0, 0.1, …, 1.0.
    let o = GifOptions {
        fps: 10.0,
        speed: 1.0,
        from: Some(0.0),
        to: Some(1.0),
        render: options(),
    };
    let report = render_gif(&run, &out, &o).unwrap();
    assert_eq!(report.frames, 11);
    assert_eq!(gif_frames(&out), (11, 216, 116));
    // Twice as fast: half the frames over the same span; the whole run by default.
    let o = GifOptions {
        fps: 10.0,
        speed: 2.0,
        from: None,
        to: None,
        render: options(),
    };
    let report = render_gif(&run, &out, &o).unwrap();
    assert_eq!((report.from, report.to, report.frames), (0.0, 2.0, 11));
    assert_eq!(gif_frames(&out).0, 11);
    let o = GifOptions {
        fps: 7.0,
        speed: 0.5,
        from: Some(0.25),
        to: Some(0.75),
        render: options(),
    };
    assert_eq!(render_gif(&run, &out, &o).unwrap().frames, 8);
    assert_eq!(gif_frames(&out).0, 8);
}

#[test]
fn a_gif_frame_matches_the_png_at_its_time() {
    let dir = common::temp_dir("render-gif-png");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let out = dir.join("anim.gif");
    let o = GifOptions {
        fps: 10.0,
        speed: 1.0,
        from: Some(0.3),
        to: Some(0.3),
        render: options(),
    };
    render_gif(&run, &out, &o).unwrap();
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut d = opts.read_info(std::fs::File::open(&out).unwrap()).unwrap();
    let frame = d.read_next_frame().unwrap().unwrap().buffer.to_vec();
    let at = |x: f64, y: f64| {
        let (px, py) = (
            (8.0 + 100.0 * x).round() as usize,
            (108.0 - 100.0 * y).round() as usize,
        );
        let k = 4 * (py * 216 + px);
        [frame[k], frame[k + 1], frame[k + 2]]
    };
    // The GIF's fixed palette rounds colours to a 6×7×6 cube: compare within its step.
    let close = |a: Rgb, b: Rgb| {
        a.iter()
            .zip(b)
            .all(|(x, y)| (i32::from(*x) - i32::from(y)).abs() <= 26)
    };
    assert!(close(at(0.8, 0.5), id_colour(7)), "{:?}", at(0.8, 0.5));
    assert!(close(at(1.5, 0.5), id_colour(9)));
    assert!(close(at(0.5, 0.5), colour::BACKGROUND));
}

#[test]
fn bad_options_write_nothing() {
    let dir = common::temp_dir("render-bad");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let out = dir.join("frame.png");
    let err = render_png(
        &run,
        0.3,
        &out,
        &RenderOptions {
            width: 3,
            ..options()
        },
    )
    .unwrap_err();
    assert!(err.to_string().starts_with("width:"), "{err}");
    assert!(!out.exists());
    let gif = dir.join("anim.gif");
    let o = GifOptions {
        fps: 0.0,
        ..GifOptions::default()
    };
    assert!(render_gif(&run, &gif, &o)
        .unwrap_err()
        .to_string()
        .starts_with("fps:"));
    let o = GifOptions {
        from: Some(1.0),
        to: Some(0.5),
        ..GifOptions::default()
    };
    assert!(render_gif(&run, &gif, &o).is_err());
    // Boxes of a finder that does not exist: a clear message and no file.
    let o = GifOptions {
        render: RenderOptions {
            boxes: true,
            finder: "nope".into(),
            ..options()
        },
        ..GifOptions::default()
    };
    let err = render_gif(&run, &gif, &o).unwrap_err();
    assert!(err.to_string().contains("unknown finder `nope`"), "{err}");
    assert!(!gif.exists());
    assert!(std::fs::read_dir(&dir).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .ends_with(".partial")));
}

#[test]
fn gif_frames_composite_to_the_png_at_their_time() {
    // Frames after the first store only what changed: drawn one over the other they must
    // give the full picture, the same as a PNG of the same instant up to the GIF palette.
    let dir = common::temp_dir("render-gif-composite");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let gif_path = dir.join("anim.gif");
    // At t = 1.05 the last collision (t = 0.8) is past the GIF's flash window, so the two
    // pictures show the same.
    let o = GifOptions {
        fps: 10.0,
        speed: 1.0,
        from: Some(0.05),
        to: Some(1.05),
        render: options(),
    };
    render_gif(&run, &gif_path, &o).unwrap();
    let png = dir.join("last.png");
    render_png(&run, 1.05, &png, &options()).unwrap();
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut d = opts
        .read_info(std::fs::File::open(&gif_path).unwrap())
        .unwrap();
    let palette = d.global_palette().unwrap().to_vec();
    let (w, h) = (usize::from(d.width()), usize::from(d.height()));
    let mut canvas = vec![0u8; w * h];
    let mut partial = 0;
    while let Some(f) = d.read_next_frame().unwrap() {
        assert_eq!(f.dispose, gif::DisposalMethod::Keep);
        if usize::from(f.width) * usize::from(f.height) < w * h {
            partial += 1;
        }
        for y in 0..usize::from(f.height) {
            for x in 0..usize::from(f.width) {
                let k = (usize::from(f.top) + y) * w + usize::from(f.left) + x;
                canvas[k] = f.buffer[y * usize::from(f.width) + x];
            }
        }
    }
    assert!(partial > 0, "later frames store only their changes");
    let pm = Pixmap::load_png(&png).unwrap();
    for (k, px) in pm.pixels().iter().enumerate() {
        let c = px.demultiply();
        let i = usize::from(canvas[k]);
        let g = [palette[3 * i], palette[3 * i + 1], palette[3 * i + 2]];
        for (a, b) in g.iter().zip([c.red(), c.green(), c.blue()]) {
            // The cube's coarsest step is 51: a colour is at most half of it away.
            assert!(
                (i32::from(*a) - i32::from(b)).abs() <= 26,
                "pixel {k}: {g:?} vs {c:?}"
            );
        }
    }
}

#[test]
fn boxes_are_drawn_around_the_bodies() {
    let dir = common::temp_dir("render-boxes");
    let run = dir.join("two.ccd");
    common::record(&two_discs(), 2.0, &run);
    let plain = dir.join("plain.png");
    let boxed = dir.join("boxes.png");
    render_png(&run, 0.3, &plain, &options()).unwrap();
    render_png(
        &run,
        0.3,
        &boxed,
        &RenderOptions {
            boxes: true,
            ..options()
        },
    )
    .unwrap();
    let (a, b) = (
        Pixmap::load_png(&plain).unwrap(),
        Pixmap::load_png(&boxed).unwrap(),
    );
    assert_ne!(a.data(), b.data());
    // The swept leaf box of body 9 (at rest at (1.5, 0.5), radius 0.1) is its disc's box:
    // its left edge, x = 1.4 (pixel 148), shows in leaf green beside the disc above and
    // below the centre row, where the disc curves away from it. The line straddles two
    // pixel columns, so each is a blend with the background: green must dominate.
    let leafish = (145..=150).any(|x| {
        (46..=52).any(|y| {
            let c = b.pixel(x, y).unwrap().demultiply();
            let (r, g, bl) = (
                i32::from(c.red()),
                i32::from(c.green()),
                i32::from(c.blue()),
            );
            g - r > 30 && g - bl > 20
        })
    });
    assert!(leafish, "a leaf box edge left of body 9");
    // Nothing changes inside the discs: boxes are outlines.
    assert_eq!(pixel(&b, 1.5, 0.5), id_colour(9));
    assert_eq!(pixel(&b, 0.8, 0.5), id_colour(7));
}

/// The two discs, steered: at t = 0.2 a body of id 42 and radius 0.15 m is added at rest at
/// (1.0, 0.2) (clear of body 7's path along y = 0.5), at t = 0.4 body 9 is removed, before
/// body 7 reaches it; recorded until t = 2.
fn two_discs_edited(path: &std::path::Path) {
    use ccdsim::record::RunWriter;
    use ccdsim::Simulation;
    let scene = two_discs();
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut w = RunWriter::record_steered(&mut sim, path, &scene).unwrap();
    let mut write = |records: Vec<ccdsim::Collision<2>>| {
        for r in &records {
            w.write_event(r).unwrap();
        }
    };
    write(sim.advance(0.2));
    let spec = BodySpec {
        id: Some(42),
        ..BodySpec::new(Vector([1.0, 0.2]), Vector([0.0, 0.0]), 0.15)
    };
    assert_eq!(sim.add_body(spec).unwrap(), 2);
    write(sim.take_edits());
    write(sim.advance(0.2));
    sim.remove_body(1).unwrap();
    write(sim.take_edits());
    write(sim.advance(1.6));
    w.finish(sim.time()).unwrap();
}

/// The GIF at `gif_path` ends on the picture `pm`, up to its palette's rounding.
fn assert_gif_ends_as(gif_path: &std::path::Path, pm: &Pixmap) {
    let (canvas, w) = gif_canvas(gif_path);
    for (k, px) in pm.pixels().iter().enumerate() {
        let c = px.demultiply();
        for (a, b) in canvas[k].iter().zip([c.red(), c.green(), c.blue()]) {
            // The palette cube's coarsest step is 51: a colour is at most half of it away.
            assert!(
                (i32::from(*a) - i32::from(b)).abs() <= 26,
                "pixel ({}, {}): {:?} vs {c:?}",
                k % w,
                k / w,
                canvas[k]
            );
        }
    }
}

/// The picture a GIF's frames composite to, and its size.
fn gif_canvas(path: &std::path::Path) -> (Vec<Rgb>, usize) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut d = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let palette = d.global_palette().unwrap().to_vec();
    let (w, h) = (usize::from(d.width()), usize::from(d.height()));
    let mut canvas = vec![0u8; w * h];
    while let Some(f) = d.read_next_frame().unwrap() {
        for y in 0..usize::from(f.height) {
            for x in 0..usize::from(f.width) {
                let k = (usize::from(f.top) + y) * w + usize::from(f.left) + x;
                canvas[k] = f.buffer[y * usize::from(f.width) + x];
            }
        }
    }
    let rgb = canvas
        .iter()
        .map(|&i| {
            let i = usize::from(i);
            [palette[3 * i], palette[3 * i + 1], palette[3 * i + 2]]
        })
        .collect();
    (rgb, w)
}

#[test]
fn added_bodies_are_drawn_with_their_radius_and_removed_ones_not_at_all() {
    let dir = common::temp_dir("render-slots");
    let run = dir.join("edited.ccd");
    two_discs_edited(&run);
    let out = dir.join("frame.png");
    // Before the edits: both discs, nothing at (1.0, 0.2).
    render_png(&run, 0.1, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    assert_eq!(pixel(&pm, 1.5, 0.5), id_colour(9));
    assert_eq!(pixel(&pm, 1.0, 0.2), colour::BACKGROUND);
    // After them: body 42 in its colour out to its own radius (past the scene's 0.1 m), body
    // 9 gone, body 7 moving on at x = 1.1.
    render_png(&run, 0.6, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    assert_eq!(pixel(&pm, 1.0, 0.2), id_colour(42));
    assert_eq!(pixel(&pm, 1.0 + 0.12, 0.2), id_colour(42));
    assert_eq!(pixel(&pm, 1.0 + 0.18, 0.2), colour::BACKGROUND);
    assert_eq!(pixel(&pm, 1.5, 0.5), colour::BACKGROUND);
    assert_eq!(pixel(&pm, 1.1, 0.5), id_colour(7));
    // A GIF plays the edits forward to the same picture.
    let gif_path = dir.join("anim.gif");
    let o = GifOptions {
        fps: 10.0,
        speed: 1.0,
        from: Some(0.0),
        to: Some(0.6),
        render: options(),
    };
    assert_eq!(render_gif(&run, &gif_path, &o).unwrap().frames, 7);
    assert_gif_ends_as(&gif_path, &pm);
}

#[test]
fn sensors_are_outlined_and_light_up_while_a_body_is_in_them() {
    // A sensor of radius 0.2 m around (1.0, 0.5): body 7 (x = 0.5 + t, radius 0.1) overlaps
    // it while its centre is within 0.3 m, from t = 0.2 to t = 0.8.
    let scene = Scene {
        sensors: vec![ccdsim::Sensor {
            center: Vector([1.0, 0.5]),
            radius: 0.2,
        }],
        ..two_discs()
    };
    let dir = common::temp_dir("render-sensor");
    let run = dir.join("sensor.ccd");
    common::record(&scene, 2.0, &run);
    let ring = |t: f64| {
        let out = dir.join(format!("sensor-{t}.png"));
        render_png(&run, t, &out, &options()).unwrap();
        let pm = Pixmap::load_png(&out).unwrap();
        // The outline's top, just inside the 1.5 px stroke centred on the circle.
        (pixel(&pm, 1.0, 0.7 - 0.003), pixel(&pm, 1.0, 0.5))
    };
    // That pixel is three quarters under the stroke: three quarters outline colour, a
    // quarter background.
    let near = |got: Rgb, want: Rgb| {
        (0..3).all(|k| {
            let blend = 0.75 * f64::from(want[k]) + 0.25 * f64::from(colour::BACKGROUND[k]);
            (f64::from(got[k]) - blend).abs() < 6.0
        })
    };
    let (outline, inside) = ring(0.1);
    assert!(near(outline, colour::SENSOR), "{outline:?}");
    assert_eq!(inside, colour::BACKGROUND, "the region is not filled");
    let (outline, _) = ring(0.5);
    assert!(near(outline, colour::SENSOR_HELD), "{outline:?}");
}

/// The two discs with two moving walls: a segment from (0.2, 0.9) to (0.6, 0.9) sliding right
/// at 1 m/s and, from t = 0.5, steered to (0.4, −0.3) m/s (it stays above the discs, whose
/// tops are at y = 0.6); and the line x = 1.9 facing left, coming in at 0.1 m/s (never
/// steered), which body 9 meets at t = 1. Recorded until t = 1.2.
fn two_discs_with_moving_walls(path: &std::path::Path) {
    use ccdsim::record::RunWriter;
    use ccdsim::{MovingWall, Simulation, Wall};
    let scene = Scene {
        moving_walls: vec![
            MovingWall {
                wall: Wall::Segment {
                    a: Vector([0.2, 0.9]),
                    b: Vector([0.6, 0.9]),
                },
                velocity: Vector([1.0, 0.0]),
            },
            MovingWall {
                wall: Wall::Plane {
                    point: Vector([1.9, 0.0]),
                    normal: Vector([-1.0, 0.0]),
                },
                velocity: Vector([-0.1, 0.0]),
            },
        ],
        ..two_discs()
    };
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut w = RunWriter::record_steered(&mut sim, path, &scene).unwrap();
    let mut write = |records: Vec<ccdsim::Collision<2>>| {
        for r in &records {
            w.write_event(r).unwrap();
        }
    };
    write(sim.advance(0.5));
    sim.set_wall_velocity(0, Vector([0.4, -0.3])).unwrap();
    write(sim.take_edits());
    let rest = sim.advance(0.7);
    assert!(
        rest.iter()
            .any(|c| c.event.kind == ccdsim::EventKind::Wall && c.event.b == 5),
        "body 9 meets the moving line"
    );
    write(rest);
    w.finish(sim.time()).unwrap();
}

#[test]
fn moving_walls_are_drawn_where_they_are_at_the_frames_time() {
    let dir = common::temp_dir("render-walls");
    let run = dir.join("walls.ccd");
    two_discs_with_moving_walls(&run);
    let out = dir.join("frame.png");
    // A 1.5 px anti-aliased line along a pixel boundary: mostly wall colour.
    let wall = |c: Rgb| c.iter().all(|&x| x > 120);
    // At t = 0.3 the segment spans x = 0.5 … 0.9 at y = 0.9, and the line is at x = 1.87.
    render_png(&run, 0.3, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    for x in [0.55, 0.7, 0.85] {
        assert!(
            wall(pixel(&pm, x, 0.9)),
            "segment at x = {x}: {:?}",
            pixel(&pm, x, 0.9)
        );
    }
    assert_eq!(pixel(&pm, 0.3, 0.9), colour::BACKGROUND, "where it started");
    assert!(wall(pixel(&pm, 1.87, 0.8)), "{:?}", pixel(&pm, 1.87, 0.8));
    assert_eq!(
        pixel(&pm, 1.9, 0.8),
        colour::BACKGROUND,
        "where the line started"
    );
    // At t = 1, steered since t = 0.5: displaced by (0.5 + 0.2, −0.15), so from x = 0.9 to
    // 1.3 at y = 0.75; the line at x = 1.8.
    render_png(&run, 1.0, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    for x in [0.95, 1.1, 1.25] {
        assert!(
            wall(pixel(&pm, x, 0.75)),
            "segment at x = {x}: {:?}",
            pixel(&pm, x, 0.75)
        );
    }
    assert_eq!(
        pixel(&pm, 0.7, 0.9),
        colour::BACKGROUND,
        "where it was at t = 0.3"
    );
    assert_eq!(
        pixel(&pm, 1.1, 0.9),
        colour::BACKGROUND,
        "where it would be unsteered"
    );
    assert!(wall(pixel(&pm, 1.8, 0.8)), "{:?}", pixel(&pm, 1.8, 0.8));
    assert_eq!(pixel(&pm, 1.87, 0.8), colour::BACKGROUND);
    // A GIF plays the wall's edit forward to the same picture (at t = 0.7, when no body
    // flashes: the GIF's flashes last 0.15 s, the PNG's only the instant of their event).
    render_png(&run, 0.7, &out, &options()).unwrap();
    let pm = Pixmap::load_png(&out).unwrap();
    let gif_path = dir.join("anim.gif");
    let o = GifOptions {
        fps: 10.0,
        speed: 1.0,
        from: Some(0.0),
        to: Some(0.7),
        render: options(),
    };
    assert_eq!(render_gif(&run, &gif_path, &o).unwrap().frames, 8);
    assert_gif_ends_as(&gif_path, &pm);
}

#[test]
fn a_moving_plane_in_3d_is_drawn_where_it_cuts_the_room() {
    use ccdsim::{MovingWall, Wall};
    // A 2 m room and a ceiling coming down at 0.4 m/s from y = 1.8, seen straight along z
    // (yaw = pitch = 0: the x–y view at 100 px/m, as in 2D): its section is a line across
    // the room at its height.
    let scene = Scene::<3> {
        bodies: vec![BodySpec::new(
            Vector([1.0, 0.5, 1.0]),
            Vector([0.0; 3]),
            0.1,
        )],
        walls: box_walls(Vector([2.0, 2.0, 2.0])),
        moving_walls: vec![MovingWall {
            wall: Wall::Plane {
                point: Vector([0.0, 1.8, 0.0]),
                normal: Vector([0.0, -1.0, 0.0]),
            },
            velocity: Vector([0.0, -0.4, 0.0]),
        }],
        ..Scene::default()
    };
    let dir = common::temp_dir("render-walls-3d");
    let run = dir.join("room.ccd");
    common::record(&scene, 1.0, &run);
    let o = RenderOptions {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        height: Some(216),
        ..options()
    };
    let out = dir.join("frame.png");
    let at = |t: f64, x: f64, y: f64| {
        render_png(&run, t, &out, &o).unwrap();
        let pm = Pixmap::load_png(&out).unwrap();
        let c = pm
            .pixel(
                (8.0 + 100.0 * x).floor() as u32,
                (208.0 - 100.0 * y).floor() as u32,
            )
            .unwrap()
            .demultiply();
        [c.red(), c.green(), c.blue()]
    };
    let wall = |c: Rgb| c.iter().all(|&x| x > 120);
    assert!(wall(at(0.0, 1.0, 1.8)), "{:?}", at(0.0, 1.0, 1.8));
    assert!(wall(at(1.0, 1.0, 1.4)), "{:?}", at(1.0, 1.0, 1.4));
    assert!(wall(at(1.0, 0.3, 1.4)), "across the room");
    assert_eq!(
        at(1.0, 1.0, 1.8),
        colour::BACKGROUND,
        "no longer where it started"
    );
}

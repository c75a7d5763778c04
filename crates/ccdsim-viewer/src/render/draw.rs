//! Drawing one frame with tiny-skia: walls, the finder's boxes, bodies, collision flashes, a
//! progress bar and the time.

use super::camera::Camera;
use super::colour::{self, ColourBy, Rgb, BUCKETS};
use crate::playback::Snapshot;
use ccdsim::finder::DebugBox;
use ccdsim::{Aabb, Scene, Vector, Wall};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

/// Everything one frame shows.
pub struct FrameInput<'a, const D: usize> {
    /// The run's scene (walls, settings; the bodies' radii and ids are the snapshot's).
    pub scene: &'a Scene<D>,
    /// The state to draw, at its time.
    pub snap: &'a Snapshot<D>,
    /// The finder's boxes at that time (empty to draw none).
    pub boxes: &'a [DebugBox<D>],
    /// How bodies are coloured.
    pub colour: ColourBy,
    /// The run's top speed, m/s, for [`ColourBy::Speed`].
    pub max_speed: f64,
    /// Bodies whose last collision is at most this long before the frame's time flash,
    /// seconds (0: only those colliding exactly at it).
    pub flash_window: f64,
    /// Where the frame's time lies in the run, 0 to 1, drawn as a bar; `None` for no bar.
    pub progress: Option<f64>,
    /// The run's bounds (3D runs draw them as a wire box).
    pub bounds: Aabb<D>,
    /// Draw the frame's simulated time in its top-left corner (`t = 1.250 s`).
    pub time_label: bool,
}

fn paint(c: Rgb, alpha: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], alpha));
    p.anti_alias = true;
    p
}

fn stroke(width: f32) -> Stroke {
    Stroke {
        width,
        ..Stroke::default()
    }
}

/// Draws a frame into a new pixmap of the camera's size.
#[must_use]
pub fn draw_frame<const D: usize>(cam: &Camera, f: &FrameInput<'_, D>) -> Pixmap {
    let mut pm = Pixmap::new(cam.width, cam.height).expect("camera size is at least 16×16");
    let bg = colour::BACKGROUND;
    pm.fill(Color::from_rgba8(bg[0], bg[1], bg[2], 255));
    draw_walls(&mut pm, cam, f);
    draw_sensors(&mut pm, cam, f);
    draw_boxes(&mut pm, cam, f.boxes);
    draw_bodies(&mut pm, cam, f);
    if let Some(p) = f.progress {
        let w = (f64::from(cam.width) * p.clamp(0.0, 1.0)) as f32;
        if let Some(r) = Rect::from_xywh(0.0, cam.height as f32 - 3.0, w.max(1.0), 3.0) {
            pm.fill_rect(
                r,
                &paint(colour::PROGRESS, 255),
                Transform::identity(),
                None,
            );
        }
    }
    if f.time_label {
        super::time_label::draw_time_label(&mut pm, f.snap.time);
    }
    pm
}

/// Adds the segment `a`–`b` to a path.
fn segment<const D: usize>(pb: &mut PathBuilder, cam: &Camera, a: Vector<D>, b: Vector<D>) {
    let (x0, y0, _) = cam.project(a);
    let (x1, y1, _) = cam.project(b);
    pb.move_to(x0, y0);
    pb.line_to(x1, y1);
}

/// Corner `bits` of box `b`: bit `k` set takes its upper bound along axis `k`.
fn box_corner<const D: usize>(b: &Aabb<D>, bits: usize) -> Vector<D> {
    let mut p = Vector::<D>::ZERO;
    for k in 0..D {
        p[k] = if bits >> k & 1 == 1 {
            b.max[k]
        } else {
            b.min[k]
        };
    }
    p
}

/// Adds the edges of a box to a path: 4 in 2D, 12 in 3D.
fn box_edges<const D: usize>(pb: &mut PathBuilder, cam: &Camera, b: &Aabb<D>) {
    let corner = |bits: usize| box_corner(b, bits);
    for c in 0..(1usize << D) {
        for k in 0..D {
            if c >> k & 1 == 0 {
                segment(pb, cam, corner(c), corner(c | 1 << k));
            }
        }
    }
}

/// The static walls, and the moving walls where they are at the frame's time. A 3D plane
/// has no edges: static ones are shown by the wire box of the run's bounds, and a moving one
/// also by the polygon where it cuts that box, so that it is seen to move.
fn draw_walls<const D: usize>(pm: &mut Pixmap, cam: &Camera, f: &FrameInput<'_, D>) {
    let mut pb = PathBuilder::new();
    let span = (f.bounds.max - f.bounds.min).norm().max(1e-9);
    let mut planes = false;
    let s = &f.snap.states;
    let fixed = f.scene.walls.iter().map(|&w| (w, false));
    let moving = (0..s.wall_count()).map(|k| (s.moving_wall_at(k, f.snap.time), true));
    for (w, moves) in fixed.chain(moving) {
        match w {
            Wall::Segment { a, b } => segment(&mut pb, cam, a, b),
            Wall::Plane { point, normal } if D == 2 => {
                // A line in 2D: draw it across the whole view.
                let mut dir = Vector::<D>::ZERO;
                dir[0] = -normal[1];
                dir[1] = normal[0];
                let dir = dir * (10.0 * span / dir.norm());
                segment(&mut pb, cam, point - dir, point + dir);
            }
            Wall::Plane { point, normal } => {
                planes = true;
                if moves {
                    let section = plane_section(&f.bounds, point, normal);
                    for (j, &p) in section.iter().enumerate() {
                        segment(&mut pb, cam, p, section[(j + 1) % section.len()]);
                    }
                }
            }
        }
    }
    if planes || (D == 3 && f.scene.walls.is_empty()) {
        // Planes have no edges to draw; a wire box of the run's bounds shows the room.
        box_edges(&mut pb, cam, &f.bounds);
    }
    if let Some(path) = pb.finish() {
        pm.stroke_path(
            &path,
            &paint(colour::WALL, 255),
            &stroke(1.5),
            Transform::identity(),
            None,
        );
    }
}

/// The corners of the polygon where the plane through `point` with normal `normal` cuts the
/// box `b`, in order around it; fewer than three (nothing to draw) when it misses the box or
/// only touches it. For 3D (in 2D a plane is a line, drawn across the view instead).
#[must_use]
pub(crate) fn plane_section<const D: usize>(
    b: &Aabb<D>,
    point: Vector<D>,
    normal: Vector<D>,
) -> Vec<Vector<D>> {
    let corner = |bits: usize| box_corner(b, bits);
    let side = |p: Vector<D>| normal.dot(p - point);
    let mut pts: Vec<Vector<D>> = Vec::new();
    for c in 0..(1usize << D) {
        for k in 0..D {
            if c >> k & 1 == 1 {
                continue;
            }
            let (p, q) = (corner(c), corner(c | 1 << k));
            let (sp, sq) = (side(p), side(q));
            if (sp <= 0.0 && sq >= 0.0) || (sp >= 0.0 && sq <= 0.0) {
                let x = if sp == sq {
                    p
                } else {
                    p + (q - p) * (sp / (sp - sq))
                };
                // A plane through a corner meets its three edges there: one point.
                if !pts
                    .iter()
                    .any(|y| (*y - x).norm() <= 1e-12 * (1.0 + x.norm()))
                {
                    pts.push(x);
                }
            }
        }
    }
    if pts.len() < 3 {
        return Vec::new();
    }
    // Around the centroid, by angle in two directions across the normal.
    let c = pts.iter().fold(Vector::ZERO, |s, &p| s + p) * (1.0 / pts.len() as f64);
    let u = pts
        .iter()
        .map(|&p| p - c)
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .expect("three points");
    let v = cross_in_plane(normal, u);
    pts.sort_by(|&p, &q| {
        let angle = |p: Vector<D>| (p - c).dot(v).atan2((p - c).dot(u));
        angle(p).total_cmp(&angle(q))
    });
    pts
}

/// `n × u` in 3D (a direction across `n`, at right angles to `u`); zero otherwise.
fn cross_in_plane<const D: usize>(n: Vector<D>, u: Vector<D>) -> Vector<D> {
    let mut v = Vector::<D>::ZERO;
    if D == 3 {
        v[0] = n[1] * u[2] - n[2] * u[1];
        v[1] = n[2] * u[0] - n[0] * u[2];
        v[2] = n[0] * u[1] - n[1] * u[0];
    }
    v
}

/// The scene's sensor regions as outlines, brighter while a body overlaps one (its centre
/// within the sum of the radii, the simulation's rule).
fn draw_sensors<const D: usize>(pm: &mut Pixmap, cam: &Camera, f: &FrameInput<'_, D>) {
    let s = &f.snap.states;
    let t = f.snap.time;
    for sensor in &f.scene.sensors {
        let held = (0..s.len()).any(|i| {
            !s.is_vacant(i)
                && (s.position_at(i, t) - sensor.center).norm() < sensor.radius + s.radius(i)
        });
        let (x, y, _) = cam.project(sensor.center);
        let r = (sensor.radius * cam.scale).max(1.0) as f32;
        if let Some(path) = PathBuilder::from_circle(x, y, r) {
            let c = if held {
                colour::SENSOR_HELD
            } else {
                colour::SENSOR
            };
            pm.stroke_path(
                &path,
                &paint(c, 255),
                &stroke(1.5),
                Transform::identity(),
                None,
            );
        }
    }
}

fn draw_boxes<const D: usize>(pm: &mut Pixmap, cam: &Camera, boxes: &[DebugBox<D>]) {
    let max_depth = boxes.iter().map(|b| b.depth).max().unwrap_or(0) as usize;
    let mut inner: Vec<PathBuilder> = (0..=max_depth).map(|_| PathBuilder::new()).collect();
    let mut leaves = PathBuilder::new();
    for b in boxes {
        if b.leaf {
            box_edges(&mut leaves, cam, &b.aabb);
        } else {
            box_edges(&mut inner[b.depth as usize], cam, &b.aabb);
        }
    }
    for (depth, pb) in inner.into_iter().enumerate() {
        if let Some(path) = pb.finish() {
            let c = colour::depth_colour(depth as u32);
            pm.stroke_path(
                &path,
                &paint(c, 200),
                &stroke(1.0),
                Transform::identity(),
                None,
            );
        }
    }
    if let Some(path) = leaves.finish() {
        pm.stroke_path(
            &path,
            &paint(colour::LEAF_BOX, 220),
            &stroke(1.0),
            Transform::identity(),
            None,
        );
    }
}

fn draw_bodies<const D: usize>(pm: &mut Pixmap, cam: &Camera, f: &FrameInput<'_, D>) {
    let s = &f.snap.states;
    let t = f.snap.time;
    let start = f.scene.start_time;
    let flashing =
        |i: usize| s.time[i] > start && s.time[i] <= t && t - s.time[i] <= f.flash_window;
    let bucket = |i: usize| match f.colour {
        ColourBy::Id => colour::id_bucket(s.id(i)),
        ColourBy::Speed => colour::speed_bucket(s.velocity_at(i, t).norm(), f.max_speed),
    };
    let bucket_colour = |b: usize| match f.colour {
        ColourBy::Id => colour::id_colour(b),
        ColourBy::Speed => colour::speed_colour(b),
    };
    // Growing runs: radii at the frame's time.
    let grown = f
        .scene
        .settings
        .growth
        .map_or(1.0, |g| 1.0 + g.rate * (t - f.scene.start_time));
    let disc = |i: usize| {
        let (x, y, z) = cam.project(s.position_at(i, t));
        let r = (s.radius(i) * grown * cam.scale).max(0.75) as f32;
        (x, y, z, r)
    };
    let mut flashes = Vec::new();
    // Vacant slots (bodies removed, or slots not filled yet) are not drawn.
    let present = || (0..s.len()).filter(|&i| !s.is_vacant(i));
    if D == 2 {
        // Bodies never overlap in 2D, so drawing order is free: one path per colour.
        let mut paths: Vec<PathBuilder> = (0..BUCKETS).map(|_| PathBuilder::new()).collect();
        for i in present() {
            if flashing(i) {
                flashes.push(i);
                continue;
            }
            let (x, y, _, r) = disc(i);
            paths[bucket(i)].push_circle(x, y, r);
        }
        for (b, pb) in paths.into_iter().enumerate() {
            if let Some(path) = pb.finish() {
                pm.fill_path(
                    &path,
                    &paint(bucket_colour(b), 255),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
    } else {
        // 3D: far bodies first (painter's order), each shaded with a highlight.
        let mut order: Vec<(f64, usize)> = present().map(|i| (disc(i).2, i)).collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, i) in order {
            if flashing(i) {
                flashes.push(i);
                continue;
            }
            let (x, y, _, r) = disc(i);
            let c = bucket_colour(bucket(i));
            fill_circle(pm, x, y, r, c);
            let light = [c[0] / 2 + 128, c[1] / 2 + 128, c[2] / 2 + 128];
            fill_circle(pm, x - 0.3 * r, y - 0.3 * r, 0.35 * r, light);
        }
    }
    for i in flashes {
        let (x, y, _, r) = disc(i);
        fill_circle(pm, x, y, r, colour::FLASH_FILL);
        if let Some(path) = PathBuilder::from_circle(x, y, r + 2.0) {
            pm.stroke_path(
                &path,
                &paint(colour::FLASH_RING, 255),
                &stroke(2.0),
                Transform::identity(),
                None,
            );
        }
    }
}

fn fill_circle(pm: &mut Pixmap, x: f32, y: f32, r: f32, c: Rgb) {
    if let Some(path) = PathBuilder::from_circle(x, y, r) {
        pm.fill_path(
            &path,
            &paint(c, 255),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Aabb<3> {
        Aabb {
            min: Vector([0.0; 3]),
            max: Vector([2.0; 3]),
        }
    }

    #[test]
    fn a_plane_cuts_the_box_in_a_polygon_in_order() {
        // y = 0.5 across the cube: a square, each corner next to the one before.
        let sq = plane_section(&cube(), Vector([7.0, 0.5, -3.0]), Vector([0.0, -2.0, 0.0]));
        assert_eq!(sq.len(), 4);
        for (j, p) in sq.iter().enumerate() {
            assert_eq!(p[1], 0.5);
            assert!(
                [0.0, 2.0].contains(&p[0]) && [0.0, 2.0].contains(&p[2]),
                "{p:?}"
            );
            // Neighbours share a side of the square: they differ in x or in z, not both.
            let q = sq[(j + 1) % 4];
            assert!((p[0] == q[0]) != (p[2] == q[2]), "{p:?} {q:?}");
        }
        // Through three corners (x + y + z = 2): a triangle, each corner once.
        let tri = plane_section(&cube(), Vector([2.0, 0.0, 0.0]), Vector([1.0, 1.0, 1.0]));
        assert_eq!(tri.len(), 3, "{tri:?}");
        // Across the middle (x + y + z = 3): a hexagon.
        let hex = plane_section(&cube(), Vector([1.0, 1.0, 1.0]), Vector([1.0, 1.0, 1.0]));
        assert_eq!(hex.len(), 6, "{hex:?}");
        for (j, p) in hex.iter().enumerate() {
            // In order around it: neighbours are one edge of the hexagon (√2) apart.
            let d = (*p - hex[(j + 1) % 6]).norm();
            assert!((d - 2f64.sqrt()).abs() < 1e-12, "{d}");
        }
        // Past the box, or touching it at one corner: nothing to draw.
        assert!(
            plane_section(&cube(), Vector([0.0, 3.0, 0.0]), Vector([0.0, 1.0, 0.0])).is_empty()
        );
        assert!(plane_section(&cube(), Vector([0.0; 3]), Vector([1.0, 1.0, 1.0])).is_empty());
    }
}

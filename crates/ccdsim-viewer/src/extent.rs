//! Where and how fast things go over a whole run, for framing views and colouring by speed.

use ccdsim::motion::pivot::Pivot;
use ccdsim::motion::translated;
use ccdsim::{Aabb, Collision, EventKind, Scene, Vector, Wall};

use crate::states::{edit_code, BodyStates};

/// The space a run uses and its top speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extent<const D: usize> {
    /// A box holding every body over the whole run (at the start or when added, at each of
    /// its collisions and edits, and at the end or when removed: motion is straight in
    /// between; under gravity, also at the vertices of the parabolas in between, per axis,
    /// a resting body's under the acceleration it slides with; for a body turning about a
    /// segment's end point, also where its arc is furthest along each axis),
    /// the segment walls and the offsets of axis-aligned planes, and the moving walls
    /// likewise wherever they are at the start, at each of their edits and at the end
    /// (they move straight in between), metres.
    pub bounds: Aabb<D>,
    /// The largest body speed at the start or after any collision or edit (under gravity, also just
    /// before each collision and at the end: a falling body's speed is largest at an end of
    /// its arc), metres per second.
    pub max_speed: f64,
}

/// Accumulates an [`Extent`] over the records of a run; radii and kinematic flags are read
/// from the states each record ends (so bodies added during the run count with theirs).
pub(crate) struct ExtentBuilder<const D: usize> {
    extent: Extent<D>,
    /// The moving walls' scene geometry.
    moving: Vec<Wall<D>>,
    /// The box of the moving segments' places so far.
    moving_segments: Aabb<D>,
    /// Per axis, the span of the offsets of the moving planes normal to it so far (a box
    /// that is empty along an axis no such plane is normal to). Kept apart from the bounds
    /// because, like the static planes', they count only once there are bodies or segments.
    moving_planes: Aabb<D>,
}

impl<const D: usize> ExtentBuilder<D> {
    /// Starts from the scene's bodies.
    pub(crate) fn new(scene: &Scene<D>) -> Self {
        let mut extent = Extent {
            bounds: Aabb::EMPTY,
            max_speed: 0.0,
        };
        for b in &scene.bodies {
            extent.bounds = extent.bounds.union(Aabb::of_ball(b.pos, b.radius));
            extent.max_speed = extent.max_speed.max(b.vel.norm());
        }
        let mut builder = ExtentBuilder {
            extent,
            moving: scene.moving_walls.iter().map(|m| m.wall).collect(),
            moving_segments: Aabb::EMPTY,
            moving_planes: Aabb::EMPTY,
        };
        for k in 0..builder.moving.len() {
            builder.add_moving_wall(k, Vector::ZERO);
        }
        builder
    }

    /// Takes in moving wall `k` displaced by `offset` from its scene geometry.
    fn add_moving_wall(&mut self, k: usize, offset: Vector<D>) {
        match translated(&self.moving[k], offset) {
            Wall::Segment { a, b } => {
                self.moving_segments = self.moving_segments.union(Aabb {
                    min: a.min(b),
                    max: a.max(b),
                });
            }
            Wall::Plane { point, normal } => {
                if let Some(k) = single_axis(&normal) {
                    let span = &mut self.moving_planes;
                    span.min[k] = span.min[k].min(point[k]);
                    span.max[k] = span.max[k].max(point[k]);
                }
            }
        }
    }

    /// Under gravity: takes in body `i`'s arc from its reference time to `t` (as `states`
    /// hold it, under its own acceleration: a resting body's slide along its wall), the
    /// vertex of the parabola on each axis where it lies in between, and its speed at `t`.
    /// The ends of the arc are taken in elsewhere. A body turning about a point: its arc
    /// along its circle ([`ExtentBuilder::add_turn`]).
    fn add_arc(&mut self, states: &BodyStates<D>, i: usize, t: f64) {
        if let Some(&p) = states.turn(i) {
            self.add_turn(&p, states.motion(i).pos, states.radius(i), t);
            return;
        }
        let Some(g) = states.acceleration(i) else {
            return;
        };
        let (m, r) = (states.motion(i), states.radius(i));
        for d in 0..D {
            if g[d] != 0.0 {
                let vertex = m.time - m.vel[d] / g[d];
                if vertex > m.time && vertex < t {
                    let ball = Aabb::of_ball(m.falling_at(vertex, &g), r);
                    self.extent.bounds.min[d] = self.extent.bounds.min[d].min(ball.min[d]);
                    self.extent.bounds.max[d] = self.extent.bounds.max[d].max(ball.max[d]);
                }
            }
        }
        let speed = m.falling_velocity(t, &g).norm();
        self.extent.max_speed = self.extent.max_speed.max(speed);
    }

    /// Takes in the arc of a body of radius `r` turning with `p` (2D), which started at
    /// `start`, from its start to `t`: where it is furthest along each axis on the way, and
    /// its speed at `t`. The angle goes one way, or (a ball swinging back) up to its turn
    /// and back, so the arc covers the angles between the start, the turn if passed, and
    /// `t`; its speed is largest at one of those ends (it grows with the distance from the
    /// top), and zero at the turn.
    fn add_turn(&mut self, p: &Pivot, start: Vector<D>, r: f64, t: f64) {
        let point = p.point();
        let mut lo = p.angle_of(Vector([start[0], start[1]]) - point);
        let mut hi = lo;
        let t0 = p.start_time();
        let mut take = |theta: f64| {
            lo = lo.min(theta);
            hi = hi.max(theta);
        };
        take(p.angle_and_rate(t).0);
        if let Some(back) = p.return_time() {
            let turn = t0 + 0.5 * (back - t0);
            if turn < t {
                take(p.angle_and_rate(turn).0);
            }
        }
        for dir in [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]] {
            let theta = p.angle_of(Vector(dir));
            if (lo..=hi).contains(&theta) {
                let c = point + Vector(dir) * p.radius();
                let mut centre = Vector::<D>::ZERO;
                centre[0] = c[0];
                centre[1] = c[1];
                self.extent.bounds = self.extent.bounds.union(Aabb::of_ball(centre, r));
            }
        }
        let speed = p.velocity(t).norm();
        self.extent.max_speed = self.extent.max_speed.max(speed);
    }

    /// Takes in a body of radius `r` at `p` moving at `v`.
    fn add_ball(&mut self, p: Vector<D>, r: f64, v: Vector<D>) {
        self.extent.bounds = self.extent.bounds.union(Aabb::of_ball(p, r));
        self.extent.max_speed = self.extent.max_speed.max(v.norm());
    }

    /// Takes in the states a collision or edit left its bodies in, and the arcs that led
    /// there from `before`, the states it ends. An added body has no arc before (its slot
    /// held none) and its radius from its record; an id record holds no state.
    pub(crate) fn add(&mut self, c: &Collision<D>, before: &BodyStates<D>) {
        let t = c.event.time;
        let (a, b) = (c.event.a as usize, c.event.b as usize);
        match c.event.kind {
            EventKind::Body => {
                for (s, i) in [(0, a), (1, b)] {
                    self.add_arc(before, i, t);
                    self.add_ball(c.pos[s], before.radius(i), c.vel[s]);
                }
            }
            EventKind::Edit if c.event.b == edit_code::ADD => {
                self.add_ball(c.pos[0], c.pos[1][0], c.vel[0]);
            }
            EventKind::Edit if c.event.b == edit_code::ADD_ID => {}
            // A moving wall's edit names no body: the wall is where the record says (its
            // motion is straight before and after, so its places at the edits, the start
            // and the end hold its whole sweep).
            EventKind::Edit if c.event.b == edit_code::WALL_MOTION => {
                self.add_moving_wall(a, c.pos[0]);
            }
            // Walls, resets, and edits of a body present (a motion, a filter, a removal).
            _ => {
                self.add_arc(before, a, t);
                self.add_ball(c.pos[0], before.radius(a), c.vel[0]);
            }
        }
    }

    /// Adds every body's position at the run's end `end` (vacant slots have none) and the
    /// walls.
    pub(crate) fn finish(mut self, last: &BodyStates<D>, end: f64, walls: &[Wall<D>]) -> Extent<D> {
        for i in (0..last.len()).filter(|&i| !last.is_vacant(i)) {
            let at = end.max(last.time[i]);
            self.add_arc(last, i, at);
            let ball = Aabb::of_ball(last.position_at(i, at), last.radius(i));
            self.extent.bounds = self.extent.bounds.union(ball);
        }
        let b = &mut self.extent.bounds;
        for w in walls {
            match *w {
                Wall::Segment { a, b: e } => {
                    *b = b.union(Aabb {
                        min: a.min(e),
                        max: a.max(e),
                    })
                }
                Wall::Plane { point, normal } => {
                    if let (Some(k), true) = (single_axis(&normal), b.min[0] <= b.max[0]) {
                        b.min[k] = b.min[k].min(point[k]);
                        b.max[k] = b.max[k].max(point[k]);
                    }
                }
            }
        }
        // The moving walls where they end, then all their places (after the static walls, so
        // that runs without moving walls keep their bounds exactly).
        for k in 0..self.moving.len() {
            self.add_moving_wall(k, last.wall_motion(k).offset_at(end));
        }
        let b = &mut self.extent.bounds;
        *b = b.union(self.moving_segments);
        if b.min[0] <= b.max[0] {
            for k in 0..D {
                if self.moving_planes.min[k] <= self.moving_planes.max[k] {
                    b.min[k] = b.min[k].min(self.moving_planes.min[k]);
                    b.max[k] = b.max[k].max(self.moving_planes.max[k]);
                }
            }
        }
        if b.min[0] > b.max[0] {
            // No bodies and no segments: a unit view around the origin.
            *b = Aabb {
                min: Vector::splat(-1.0),
                max: Vector::splat(1.0),
            };
        }
        self.extent
    }
}

/// The axis a plane's `normal` lies along, if it lies along one.
fn single_axis<const D: usize>(normal: &Vector<D>) -> Option<usize> {
    let mut axes = (0..D).filter(|&k| normal[k] != 0.0);
    match (axes.next(), axes.next()) {
        (Some(k), None) => Some(k),
        _ => None,
    }
}

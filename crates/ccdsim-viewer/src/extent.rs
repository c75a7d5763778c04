//! Where and how fast things go over a whole run, for framing views and colouring by speed.

use ccdsim::narrow::Motion;
use ccdsim::{Aabb, Collision, EventKind, Scene, Vector, Wall};

use crate::states::BodyStates;

/// The space a run uses and its top speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extent<const D: usize> {
    /// A box holding every body over the whole run (at the start, at each of its collisions
    /// and at the end: motion is straight in between; under gravity, also at the vertices of
    /// the parabolas in between, per axis), the segment walls and the offsets of axis-aligned
    /// planes, metres.
    pub bounds: Aabb<D>,
    /// The largest body speed at the start or after any collision (under gravity, also just
    /// before each collision and at the end: a falling body's speed is largest at an end of
    /// its arc), metres per second.
    pub max_speed: f64,
}

/// Accumulates an [`Extent`] over the records of a run.
pub(crate) struct ExtentBuilder<const D: usize> {
    radius: Vec<f64>,
    extent: Extent<D>,
    gravity: Option<Vector<D>>,
    /// Which bodies are kinematic (they do not fall).
    kinematic: Vec<bool>,
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
        ExtentBuilder {
            radius: scene.bodies.iter().map(|b| b.radius).collect(),
            extent,
            gravity: scene.gravity(),
            kinematic: scene.bodies.iter().map(|b| b.kinematic).collect(),
        }
    }

    /// Under gravity: takes in body `i`'s arc from its reference time to `t` (moving as `m`),
    /// the vertex of the parabola on each axis where it lies in between, and its speed at
    /// `t`. The ends of the arc are taken in elsewhere.
    fn add_arc(&mut self, i: usize, m: &Motion<D>, t: f64) {
        let Some(g) = self.gravity.filter(|_| !self.kinematic[i]) else {
            return;
        };
        let r = self.radius[i];
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

    /// Takes in the states a collision left its bodies in, and the arcs that led there from
    /// `before`, the states it ends.
    pub(crate) fn add(&mut self, c: &Collision<D>, before: &BodyStates<D>) {
        let slots = if c.event.kind == EventKind::Body {
            2
        } else {
            1
        };
        let ids = [c.event.a as usize, c.event.b as usize];
        for (s, &i) in ids.iter().enumerate().take(slots) {
            self.add_arc(i, &before.motion(i), c.event.time);
            let ball = Aabb::of_ball(c.pos[s], self.radius[i]);
            self.extent.bounds = self.extent.bounds.union(ball);
            self.extent.max_speed = self.extent.max_speed.max(c.vel[s].norm());
        }
    }

    /// Adds every body's position at the run's end `end` and the walls.
    pub(crate) fn finish(mut self, last: &BodyStates<D>, end: f64, walls: &[Wall<D>]) -> Extent<D> {
        for i in 0..last.len() {
            let m = last.motion(i);
            let at = end.max(m.time);
            self.add_arc(i, &m, at);
            let ball = Aabb::of_ball(last.position_at(i, at), self.radius[i]);
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
                    let axes: Vec<usize> = (0..D).filter(|&k| normal[k] != 0.0).collect();
                    if let (&[k], true) = (&axes[..], b.min[0] <= b.max[0]) {
                        b.min[k] = b.min[k].min(point[k]);
                        b.max[k] = b.max[k].max(point[k]);
                    }
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

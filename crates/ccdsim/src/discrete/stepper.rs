//! The discrete-time stepper of the thesis's §5.3 comparison: fixed time step, move, find
//! overlaps with a BVH over the bodies' boxes, push apart and resolve with the same impulse as
//! the exact simulation.

use super::overlap_tree::OverlapTree;
use super::wall_contact::{home_side, wall_push_out};
use crate::contact::narrow::{toi_circle_circle, toi_circle_wall};
use crate::geom::{Aabb, Vector};
use crate::motion::Motion;
use crate::resolve::{resolve_body_body, resolve_body_wall};
use crate::scene::{Scene, SceneError};
use crate::world::World;

/// Counters of a [`DiscreteStepper`] since it was made.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DiscreteStats {
    /// Steps taken.
    pub steps: u64,
    /// Overlapping body pairs found and resolved (a pair overlapping over several frames counts
    /// once per frame).
    pub body_contacts: u64,
    /// Body–wall contacts found and resolved.
    pub wall_contacts: u64,
    /// Body pairs that touched during a step (exact swept test) without overlapping at its end;
    /// counted only while miss counting is on.
    pub body_misses: u64,
    /// Body–wall pairs likewise.
    pub wall_misses: u64,
}

impl DiscreteStats {
    /// Body and wall misses together.
    #[must_use]
    pub fn misses(&self) -> u64 {
        self.body_misses + self.wall_misses
    }
}

/// What one step found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Overlapping body pairs at the end of the move.
    pub body_contacts: u32,
    /// Body–wall contacts at the end of the move.
    pub wall_contacts: u32,
    /// Body pairs missed in this step (0 unless miss counting is on).
    pub body_misses: u32,
    /// Body–wall pairs missed in this step (0 unless miss counting is on).
    pub wall_misses: u32,
}

/// A fixed-time-step simulation of a scene, the usual game-engine loop.
///
/// Each [`DiscreteStepper::step`] moves every body in a straight line for `dt`, builds an
/// [`OverlapTree`] over the bodies' boxes, and for every overlapping pair (in index order)
/// pushes the two apart along the line of centres, inversely to their masses, then applies
/// the simulation's body–body impulse; then every body in contact with a wall (see
/// [`wall_push_out`]) is pushed out and given the simulation's body–wall impulse.
///
/// With miss counting on, each step also asks the exact swept test — the continuous
/// simulation's own [`toi_circle_circle`] and [`toi_circle_wall`] on the states at the start of
/// the step — which pairs touched during the step, and counts as missed those the step did not
/// see overlapping at its end: they tunnelled through each other or grazed between frames.
/// Miss counting does not change the trajectory.
#[derive(Clone, Debug)]
pub struct DiscreteStepper<const D: usize> {
    world: World<D>,
    /// `home[i · walls + w]`: body i's side of wall w (see [`home_side`]).
    home: Vec<i8>,
    count_misses: bool,
    tree: OverlapTree<D>,
    boxes: Vec<Aabb<D>>,
    pairs: Vec<(u32, u32)>,
    contacts: Vec<(u32, u32)>,
    wall_contacts: Vec<(u32, u32)>,
    start: Vec<Motion<D>>,
    stats: DiscreteStats,
}

impl<const D: usize> DiscreteStepper<D> {
    /// A stepper at the scene's start, with miss counting off. Scenes with moving walls or
    /// resting bodies (`settings.rest_speed`) are refused: the stepper knows neither.
    pub fn new(scene: &Scene<D>) -> Result<Self, SceneError> {
        if !scene.moving_walls.is_empty() {
            return Err(SceneError::Unsupported {
                field: "moving_walls".into(),
                why: "the discrete stepper has static walls only".into(),
            });
        }
        if scene.settings.rest_speed.is_some() {
            return Err(SceneError::Unsupported {
                field: "settings.rest_speed".into(),
                why: "the discrete stepper does not rest bodies on walls".into(),
            });
        }
        let world = World::from_scene(scene)?;
        let walls = world.walls().to_vec();
        let home = (0..world.len())
            .flat_map(|i| {
                let p = world.position(i);
                walls.iter().map(move |w| home_side(w, p))
            })
            .collect();
        Ok(DiscreteStepper {
            world,
            home,
            count_misses: false,
            tree: OverlapTree::new(),
            boxes: Vec::new(),
            pairs: Vec::new(),
            contacts: Vec::new(),
            wall_contacts: Vec::new(),
            start: Vec::new(),
            stats: DiscreteStats::default(),
        })
    }

    /// Turns miss counting on or off (it costs a second tree over swept boxes per step).
    pub fn set_count_misses(&mut self, on: bool) {
        self.count_misses = on;
    }

    /// The bodies and walls; every body's stored time is the current time.
    #[must_use]
    pub fn world(&self) -> &World<D> {
        &self.world
    }

    /// Current simulated time, seconds.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.world.now()
    }

    /// Counters so far.
    #[must_use]
    pub fn stats(&self) -> &DiscreteStats {
        &self.stats
    }

    /// Takes steps of `dt` seconds until the time reaches `t` (the last step is shortened to
    /// land on `t` exactly). Returns the number of steps.
    pub fn run_until(&mut self, t: f64, dt: f64) -> u64 {
        assert!(dt > 0.0, "the time step must be positive");
        let mut steps = 0;
        while self.time() < t {
            let h = dt.min(t - self.time());
            // Land exactly on t despite rounding of the running sum.
            let h = if self.time() + h >= t || t - (self.time() + h) < 1e-12 * dt {
                t - self.time()
            } else {
                h
            };
            self.step(h);
            steps += 1;
        }
        steps
    }

    /// Advances by one step of `dt` seconds.
    pub fn step(&mut self, dt: f64) -> StepReport {
        let n = self.world.len();
        let t1 = self.world.now() + dt;
        if self.count_misses {
            self.start.clear();
            self.start.extend((0..n).map(|i| self.world.motion(i)));
        }
        // Move.
        for i in 0..n {
            let m = self.world.motion(i);
            self.world.set_state(i, m.at(t1), m.vel, t1);
        }
        self.world.set_now(t1);
        // Detect body pairs: boxes, tree, exact overlap.
        let bodies = self.world.bodies();
        let (pos, radius) = (|i: usize| bodies[i].motion.pos, |i: usize| bodies[i].radius);
        self.boxes.clear();
        self.boxes
            .extend((0..n).map(|i| Aabb::of_ball(pos(i), radius(i))));
        self.tree.build(&self.boxes);
        self.pairs.clear();
        self.tree.overlapping_pairs(&mut self.pairs);
        self.contacts.clear();
        for &(i, j) in &self.pairs {
            let (i, j) = (i as usize, j as usize);
            let sigma = radius(i) + radius(j);
            if (pos(j) - pos(i)).norm_sq() < sigma * sigma {
                self.contacts.push((i as u32, j as u32));
            }
        }
        // Detect wall contacts.
        let walls = self.world.walls();
        let nw = walls.len();
        self.wall_contacts.clear();
        for i in 0..n {
            for (w, wall) in walls.iter().enumerate() {
                if wall_push_out(wall, self.home[i * nw + w], pos(i), radius(i)).is_some() {
                    self.wall_contacts.push((i as u32, w as u32));
                }
            }
        }
        let mut report = StepReport {
            body_contacts: self.contacts.len() as u32,
            wall_contacts: self.wall_contacts.len() as u32,
            ..StepReport::default()
        };
        if self.count_misses {
            let (body, wall) = self.count_step_misses(t1);
            report.body_misses = body;
            report.wall_misses = wall;
        }
        self.resolve(t1);
        self.stats.steps += 1;
        self.stats.body_contacts += u64::from(report.body_contacts);
        self.stats.wall_contacts += u64::from(report.wall_contacts);
        self.stats.body_misses += u64::from(report.body_misses);
        self.stats.wall_misses += u64::from(report.wall_misses);
        report
    }

    /// Pairs the exact swept test says touched in `[start, t1]` that the step did not detect.
    fn count_step_misses(&mut self, t1: f64) -> (u32, u32) {
        let world = &self.world;
        // Candidates: bodies whose boxes swept over the step overlap.
        self.boxes.clear();
        self.boxes.extend(
            self.start
                .iter()
                .zip(world.radii())
                .map(|(m, r)| Aabb::of_ball(m.pos, r).union(Aabb::of_ball(m.at(t1), r))),
        );
        self.tree.build(&self.boxes);
        self.pairs.clear();
        self.tree.overlapping_pairs(&mut self.pairs);
        let mut body = 0;
        for &(i, j) in &self.pairs {
            let (a, b) = (i as usize, j as usize);
            let touched = toi_circle_circle(
                &self.start[a],
                world.radius(a),
                &self.start[b],
                world.radius(b),
            )
            .is_some_and(|t| t <= t1);
            // Both lists are sorted, so detection is a binary search.
            if touched && self.contacts.binary_search(&(i, j)).is_err() {
                body += 1;
            }
        }
        let mut wall = 0;
        for (i, m) in self.start.iter().enumerate() {
            for (w, wall_w) in self.world.walls().iter().enumerate() {
                let touched = toi_circle_wall(m, world.radius(i), wall_w).is_some_and(|t| t <= t1);
                if touched
                    && self
                        .wall_contacts
                        .binary_search(&(i as u32, w as u32))
                        .is_err()
                {
                    wall += 1;
                }
            }
        }
        (body, wall)
    }

    /// Pushes apart and resolves every detected contact, body pairs first, in index order.
    fn resolve(&mut self, t1: f64) {
        for k in 0..self.contacts.len() {
            let (i, j) = self.contacts[k];
            let (i, j) = (i as usize, j as usize);
            let (pi, pj) = (self.world.position(i), self.world.position(j));
            let sigma = self.world.radius(i) + self.world.radius(j);
            let d = pj - pi;
            let dist = d.norm();
            // Coincident centres have no line of centres; separate them along x.
            let normal = if dist > 0.0 {
                d * (1.0 / dist)
            } else {
                let mut x = Vector::<D>::ZERO;
                x[0] = 1.0;
                x
            };
            let depth = sigma - dist;
            if depth > 0.0 {
                let (mi, mj) = (self.world.mass(i), self.world.mass(j));
                let (vi, vj) = (self.world.velocity(i), self.world.velocity(j));
                let push = normal * depth;
                self.world
                    .set_state(i, pi - push * (mj / (mi + mj)), vi, t1);
                self.world
                    .set_state(j, pj + push * (mi / (mi + mj)), vj, t1);
            }
            resolve_body_body(&mut self.world, i, j, t1);
        }
        let nw = self.world.walls().len();
        for k in 0..self.wall_contacts.len() {
            let (i, w) = self.wall_contacts[k];
            let (i, w) = (i as usize, w as usize);
            let wall = self.world.walls()[w];
            let (p, v, r) = (
                self.world.position(i),
                self.world.velocity(i),
                self.world.radius(i),
            );
            if let Some(out) = wall_push_out(&wall, self.home[i * nw + w], p, r) {
                self.world.set_state(i, out, v, t1);
            }
            resolve_body_wall(&mut self.world, i, w, t1);
        }
    }
}

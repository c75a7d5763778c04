//! The naive all-pairs finder: the reference every other finder is tested against.

use super::{finite_event, Finder, FinderError};
use crate::contact::lees_edwards::toi_bodies_sheared;
use crate::contact::periodic::{toi_bodies_periodic, toi_box_exit};
use crate::event::Event;
use crate::world::World;
use crate::world::{toi_bodies_in, toi_body_wall_in};

/// Checks every body pair and every (body, wall) pair on every query: O(n²) per event,
/// O(1) extra memory, obviously correct.
#[derive(Clone, Debug, Default)]
pub struct AllPairs;

impl AllPairs {
    /// A new all-pairs finder.
    #[must_use]
    pub fn new() -> Self {
        AllPairs
    }
}

/// The minimum event over all pairs of `world`: the definition of a correct answer (`None`
/// when there is none, or when it lies at an infinite time, see [`finite_event`]).
///
/// In a periodic world (see [`crate::contact::periodic`]) a pair's time is
/// [`crate::contact::periodic::toi_circle_circle_periodic`], and every body's box exit is an event too (a wall event
/// naming face `f` as wall `walls.len() + f`); in a sheared one (see
/// [`crate::contact::lees_edwards`]) it is [`toi_bodies_sheared`]. Pairs whose collision filters keep them apart
/// ([`World::collides`]) have no event. In a growing world (see [`crate::contact::growth`]) the
/// functions are the growing forms ([`toi_pair`](crate::contact::toi_pair),
/// [`toi_bodies_periodic`], [`toi_body_wall`](crate::contact::toi_body_wall)).
#[must_use]
pub fn all_pairs_next_event<const D: usize>(world: &World<D>) -> Option<Event> {
    let n = world.len();
    let laws = world.laws();
    let mut best: Option<Event> = None;
    if let Some(size) = world.periodic() {
        let faces_from = world.walls().len();
        for i in 0..n {
            let mi = world.motion(i);
            for j in i + 1..n {
                if !world.collides(i, j) {
                    continue;
                }
                let bodies = world.bodies();
                let t = match world.shear() {
                    None => toi_bodies_periodic(&bodies[i], &bodies[j], &size, laws),
                    Some(bx) => toi_bodies_sheared(&bodies[i], &bodies[j], &bx, laws),
                };
                if let Some(t) = t {
                    best = Event::earliest(best, Some(Event::body(t, i, j)));
                }
            }
            if let Some((t, face)) = toi_box_exit(&mi, &size) {
                best = Event::earliest(best, Some(Event::wall(t, i, faces_from + face)));
            }
        }
        return finite_event(best);
    }
    for i in 0..n {
        for j in i + 1..n {
            if !world.collides(i, j) {
                continue;
            }
            if let Some(t) = toi_bodies_in(world, i, j) {
                best = Event::earliest(best, Some(Event::body(t, i, j)));
            }
        }
        for w in 0..world.walls().len() {
            if let Some(t) = toi_body_wall_in(world, i, w) {
                best = Event::earliest(best, Some(Event::wall(t, i, w)));
            }
        }
    }
    finite_event(best)
}

impl<const D: usize> Finder<D> for AllPairs {
    fn name(&self) -> &'static str {
        "all-pairs"
    }

    fn init(&mut self, _world: &World<D>) -> Result<(), FinderError> {
        Ok(())
    }

    fn update(&mut self, _world: &World<D>, _changed: &[usize]) {}

    fn next_event(&mut self, world: &World<D>) -> Option<Event> {
        all_pairs_next_event(world)
    }
}

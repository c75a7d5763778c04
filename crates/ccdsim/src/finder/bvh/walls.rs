//! Body–wall events: each body's earliest wall event (in a periodic box, its box exit too),
//! cached and recomputed only for bodies whose stored state changed.

use crate::contact::periodic::toi_box_exit;
use crate::event::Event;
use crate::world::toi_body_wall_in;
use crate::world::World;

/// Each body's earliest wall event and the [`World::change_count`] it was computed at.
///
/// In a periodic world a body's exit from the box counts as a wall event, naming face `f` as
/// wall `walls.len() + f`, as the oracle names it ([`crate::contact::periodic`]).
///
/// A body's wall events depend on its stored state alone (walls never move), so the cached
/// value stays exact until the body's change count moves. After a collision only the one or
/// two bodies involved are recomputed, O(walls) each; the minimum over bodies is a linear scan.
#[derive(Clone, Debug, Default)]
pub(crate) struct WallCache {
    earliest: Vec<Option<Event>>,
    seen: Vec<u64>,
    fresh: Vec<bool>,
}

impl WallCache {
    /// Forgets everything: every body will be recomputed.
    pub fn clear(&mut self) {
        self.earliest.clear();
        self.seen.clear();
        self.fresh.clear();
    }

    /// Recomputes the bodies whose stored state changed since the last call (all of them the
    /// first time); returns how many were recomputed.
    pub fn refresh<const D: usize>(&mut self, world: &World<D>) -> usize {
        let n = world.len();
        if self.earliest.len() != n {
            self.earliest = vec![None; n];
            self.seen = vec![0; n];
            self.fresh = vec![false; n];
        }
        let mut recomputed = 0;
        let (period, faces_from) = (world.periodic(), world.walls().len());
        for i in 0..world.len() {
            let count = world.change_count(i);
            if self.fresh[i] && self.seen[i] == count {
                continue;
            }
            let m = world.motion(i);
            let mut best = None;
            for w in 0..world.walls().len() {
                if let Some(t) = toi_body_wall_in(world, i, w) {
                    best = Event::earliest(best, Some(Event::wall(t, i, w)));
                }
            }
            if let Some((t, face)) = period.and_then(|size| toi_box_exit(&m, &size)) {
                best = Event::earliest(best, Some(Event::wall(t, i, faces_from + face)));
            }
            self.earliest[i] = best;
            self.seen[i] = count;
            self.fresh[i] = true;
            recomputed += 1;
        }
        recomputed
    }

    /// The earliest wall event of all bodies under the total order, as of the last refresh.
    pub fn earliest(&self) -> Option<Event> {
        self.earliest
            .iter()
            .fold(None, |acc, &e| Event::earliest(acc, e))
    }
}

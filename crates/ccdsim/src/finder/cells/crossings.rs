//! Crossing mode of the `cells` finder: bodies are filed in the cell holding their centre and
//! move to the next cell when they cross a face (a crossing, an internal event never
//! returned). A body's events are found among the bodies of the 3^D block of cells around its
//! own; a crossing offers it the layer of cells that became its neighbours. Crossings are
//! logged, so that a state changed behind them (an edit, or a collision at an earlier time
//! than a crossing already processed) undoes them. See the module docs of `cells` for why
//! this finds the oracle's events.

use super::candidate::{Best, Probe};
use super::key::Key;
use super::{Cells, KEY_IS_CROSSING, NO_CROSSING};
use crate::motion::Motion;
use crate::world::World;

impl<const D: usize> Cells<D> {
    /// `recompute` in crossing mode: the 3^D block of cells around the body's, its walls and
    /// box exit; then its next crossing is scheduled.
    pub(super) fn recompute_in_cells<const FALLING: bool>(
        &mut self,
        world: &World<D>,
        p: &Probe<D>,
    ) {
        let i = p.i;
        let mut best = Best::NONE;
        self.scan_neighbours(world, p, &mut best);
        self.scan_walls(world, p, &mut best);
        self.scan_exit(world, p, &mut best);
        self.store(world, i, &best, true);
        self.schedule_crossing::<FALLING>(i, &p.b.motion);
    }

    /// `schedule` in crossing mode: the queue key is the body's next crossing or its cached
    /// event, whichever is first.
    /// Under gravity (`FALLING`, the mode `FallingCrossings`) crossings are the roots of
    /// quadratics, from the finder's clock on.
    pub(super) fn schedule_crossing<const FALLING: bool>(&mut self, i: usize, mi: &Motion<D>) {
        let k = self.cached[i].coords;
        let crossing = if FALLING {
            self.next_crossing_falling(i, &k, mi)
        } else {
            self.grid.next_crossing(&k, mi)
        };
        let key = match crossing {
            Some((t, code)) => {
                let crossing = Key::crossing(t, i);
                if crossing < self.cached[i].best {
                    self.cached[i].cross = code | KEY_IS_CROSSING;
                    crossing
                } else {
                    self.cached[i].cross = code;
                    self.cached[i].best
                }
            }
            None => {
                self.cached[i].cross = NO_CROSSING;
                self.cached[i].best
            }
        };
        self.queue.set(i, key);
    }

    /// The next crossing of a body with motion `mi` filed at `k` under gravity (see
    /// [`Grid::next_crossing_falling`](super::grid::Grid::next_crossing_falling)), from the
    /// finder's clock on.
    #[cold]
    #[inline(never)]
    fn next_crossing_falling(&self, i: usize, k: &[u32; D], mi: &Motion<D>) -> Option<(f64, u8)> {
        let g = self.gravity.expect("a world with gravity");
        if self.kinematic.get(i).copied().unwrap_or(false) {
            // Kinematic bodies do not fall.
            return self.grid.next_crossing(k, mi);
        }
        // A body resting on a wall slides with its own acceleration.
        let g = self.accels.get(i).copied().unwrap_or(g);
        self.grid.next_crossing_falling(k, mi, &g, self.clock)
    }

    /// `update` in crossing mode: crossings after the earliest changed state are undone, the
    /// changed bodies filed in the cells holding them, and recomputed (the two of a collision
    /// in one scan when it applies, see `pair`). Inlined into `update`, whose body it was
    /// before the modes had modules: out of line it cost a call's register saves per event.
    #[inline(always)]
    pub(super) fn update_crossing_mode(&mut self, world: &World<D>, t: f64, changed: &[usize]) {
        // The clock goes back first: a body stepped back by an undone crossing schedules its
        // next one from `t`, and under gravity a face's roots count only from the clock on
        // (the undone crossing itself, between `t` and the old clock, must come again).
        self.clock = t;
        self.undo_crossings_after(world, t);
        for &i in changed {
            // A body still in its cell (the two of a collision: every crossing before it has
            // been processed) stays filed there, even on a face shared with the next cell: it
            // lies in its cell, as the module docs ask.
            let p = world.position(i);
            if !self.grid.holds(&self.cached[i].coords, &p) {
                let k = self.grid.coords_of_point(&p);
                self.grid.relocate(i, &mut self.cached[i].coords, k);
            }
        }
        // The two bodies of a collision: one scan of their neighbourhoods when it applies
        // (see `pair`), the same records as two recomputes.
        if let [i, j] = *changed {
            if self.recompute_pair(world, i, j) {
                return;
            }
        }
        for &i in changed {
            self.recompute(world, i);
        }
    }

    /// Processes body `i`'s crossing, due at `time`: the body moves to the next cell and is
    /// offered the layer of cells that became its neighbours, and its new cell's walls.
    pub(super) fn cross(&mut self, world: &World<D>, i: usize, time: f64) {
        self.stats.crossings += 1;
        self.clock = self.clock.max(time);
        let code = self.cached[i].cross & !KEY_IS_CROSSING;
        let (axis, up) = ((code >> 1) as usize, code & 1 == 1);
        let from = self.grid.cell_at(&self.cached[i].coords);
        let from_border = self.grid.is_border(&self.cached[i].coords);
        self.grid.step(i, &mut self.cached[i].coords, axis, up);
        self.log.push((i as u32, code, time));
        let p = Probe::of(world, i);
        let mut best = self.records(i);
        self.scan_entered_layer(world, &p, axis, up, &mut best);
        self.scan_entered_walls(world, &p, from, &mut best);
        if self.periodic && !from_border {
            self.scan_exit(world, &p, &mut best);
        }
        self.store(world, i, &best, false);
        self.schedule(i, &p.b.motion);
    }

    /// Undoes the crossings processed after time `t`, latest first.
    pub(super) fn undo_crossings_after(&mut self, world: &World<D>, t: f64) {
        while let Some(&(i, code, time)) = self.log.last() {
            if time <= t {
                break;
            }
            self.log.pop();
            self.stats.undone += 1;
            let i = i as usize;
            let (axis, up) = ((code >> 1) as usize, code & 1 == 1);
            self.grid.step(i, &mut self.cached[i].coords, axis, !up);
            self.recompute(world, i);
        }
        self.log.clear();
    }

    /// `validate` in crossing mode: every key the minimum of the body's cached event and next
    /// crossing, and every body lying in its cell (up to rounding) at the finder's clock.
    pub(super) fn validate_crossing_mode(&self, world: &World<D>) -> Result<(), String> {
        let clock = self.clock;
        for i in 0..world.len() {
            let m = world.motion(i);
            let k = self.cached[i].coords;
            let crossing = match &world.gravity_of(i) {
                Some(g) => self.grid.next_crossing_falling(&k, &m, g, clock),
                None => self.grid.next_crossing(&k, &m),
            }
            .map_or(Key::NEVER, |(t, _)| Key::crossing(t, i));
            let key = self.queue.key(i);
            if key != crossing.min(self.cached[i].best) {
                return Err(format!("body {i}: queue key is not min(event, crossing)"));
            }
            if key.is_crossing() != (self.cached[i].cross & KEY_IS_CROSSING != 0) {
                return Err(format!(
                    "body {i}: crossing flag does not match its queue key"
                ));
            }
            self.validate_cached(world, i)?;
            let p = world.stored_position_at(i, clock);
            let (lo, hi) = self.grid.cell_box(&k.map(|x| x as usize));
            for d in 0..D {
                let dt = (clock - m.time).abs();
                let fall = world.gravity_of(i).map_or(0.0, |g| g[d].abs() * dt * dt);
                let tol = 1e-9 * (1.0 + p[d].abs() + m.vel[d].abs() * dt + fall);
                if p[d] < lo[d] - tol || p[d] > hi[d] + tol {
                    return Err(format!(
                        "body {i} at {:?} (t = {clock}) is outside its cell {:?}..{:?}",
                        p.0, lo.0, hi.0
                    ));
                }
            }
        }
        Ok(())
    }
}

//! Predictions of the `cells` finder: scanning a body's neighbour cells and walls for its
//! earliest event, checking that a cached event is still live, and scheduling the body's next
//! cell crossing.

use super::candidate::{Best, Probe};
use super::gather::{offer_time, Gathered, GATHER_2D, GATHER_3D};
use super::grid::Grid;
use super::key::{ordered, Key};
use super::{Cells, Mode, NO_CROSSING, SECOND_KNOWN};
use crate::collision_filter::{pair_collides, CollisionFilter};
use crate::contact::lees_edwards::toi_bodies_sheared;
use crate::contact::narrow_lanes::Side;
use crate::contact::periodic::toi_box_exit;
use crate::contact::{toi_bodies_shifted, toi_body_wall_of, toi_pair_accelerated, toi_pair_bodies};
use crate::geom::Vector;
use crate::motion::Body;
use crate::motion::Laws;
use crate::motion::Motion;
use crate::prefetch::prefetch;
use crate::world::toi_body_wall_resting;
use crate::world::World;

/// What the finder caches about one body, in one record: read and written together whenever
/// the body is predicted, scheduled or popped (one or two cache lines, not five).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Cached<const D: usize> {
    /// Cached earliest event.
    pub best: Key,
    /// Second earliest cached event (see [`Best`]).
    pub second: Key,
    /// Image code of the partner of `best` (body events).
    pub image: u8,
    /// Image code of the partner of `second`, with the flag `SECOND_KNOWN`.
    pub second_image: u8,
    /// Code `2·axis + up` of the next crossing, or `NO_CROSSING`, with the flag
    /// `KEY_IS_CROSSING` when the crossing is the body's queue key.
    pub cross: u8,
    /// For a body–body `best`: its partner's change count (`World::change_count`) when
    /// `best` was computed, or `UNKNOWN_CHANGES` (after a promotion, or for other keys).
    /// While the partner's count is unchanged `best` is live (see `is_live`).
    pub partner_changes: u64,
    /// Coordinates of the cell the body is filed in (see `Grid`): kept here, not in the
    /// grid, because whoever reads them also reads the prediction, so they share its lines.
    pub coords: [u32; D],
}

/// `Cached::partner_changes` of a `best` whose partner's count is not known.
pub(super) const UNKNOWN_CHANGES: u64 = u64::MAX;

impl<const D: usize> Cached<D> {
    /// Nothing cached yet, filed nowhere.
    pub const NONE: Cached<D> = Cached {
        best: Key::NEVER,
        second: Key::NEVER,
        image: 0,
        second_image: SECOND_KNOWN,
        cross: NO_CROSSING,
        partner_changes: UNKNOWN_CHANGES,
        coords: [u32::MAX; D],
    };
}

impl<const D: usize> Cells<D> {
    /// True where bodies rest on walls (see [`crate::contact::resting`]): pairs then take each
    /// body's own acceleration, body by body (the four-lane kernel knows one acceleration only).
    #[inline(always)]
    pub(super) fn resting(&self) -> bool {
        self.laws.is_some_and(|l| l.resting)
    }

    /// Time of impact of body `p` with body `j` (record `bj`; image displaced by `shift`),
    /// computed exactly as the oracle does: by the same pure function, lower index first.
    #[inline(always)]
    pub(super) fn pair_toi(
        &self,
        p: &Probe<D>,
        j: usize,
        bj: &Body<D>,
        shift: &Vector<D>,
    ) -> Option<f64> {
        if self.laws.is_some_and(|l| l.filtered) && !pair_collides(&self.filters, p.i, j) {
            return None;
        }
        let (i, bi) = (p.i, &p.b);
        let (a, b) = if i < j { (bi, bj) } else { (bj, bi) };
        if self.resting() {
            let (ga, gb) = (&self.accels[i.min(j)], &self.accels[i.max(j)]);
            return toi_pair_accelerated(a, ga, b, gb);
        }
        if let Some(bx) = &self.shear {
            return toi_bodies_sheared(a, b, bx, self.laws.as_ref());
        }
        if self.periodic {
            let s = if i < j { *shift } else { Vector::ZERO - *shift };
            toi_bodies_shifted(a, b, s, self.laws.as_ref())
        } else {
            toi_pair_bodies(a, b, self.laws.as_ref())
        }
    }

    /// Offers body `p` its pair with body `j` (record `bj`, a body other than `p`'s) seen
    /// through the image of shift `shift` (`neg = 0 − shift`, code `image`): the oracle's
    /// function on the oracle's arguments, lower index first.
    ///
    /// Times come from the oracle's narrow phase with the oracle's arguments, lower index
    /// first: [`toi_circle_circle`](crate::contact::narrow::toi_circle_circle) in open worlds,
    /// [`toi_circle_circle_shifted`](crate::contact::narrow::toi_circle_circle_shifted) in periodic
    /// ones (`PERIODIC`, through [`toi_bodies_shifted`], which passes kinematic pairs by), the
    /// shift negated when the partner comes first (`0 − s` keeps zero components +0 where `−s`
    /// would make them −0). The order is chosen by selecting references, not by branching on data.
    /// `law` is the world's growth law, if radii grow.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn offer_body<const PERIODIC: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        p: &Probe<D>,
        j: usize,
        bj: &Body<D>,
        shift: &Vector<D>,
        neg: &Vector<D>,
        image: u8,
        best: &mut Best,
    ) {
        let i = p.i;
        if law.is_some_and(|l| l.filtered) && !pair_collides(filters, i, j) {
            return;
        }
        // One pointer select, not one per field: the records share a layout.
        let probe_first = i < j;
        let (a, c) = if probe_first { (&p.b, bj) } else { (bj, &p.b) };
        let t = if PERIODIC {
            let s = if probe_first { *shift } else { *neg };
            toi_bodies_shifted(a, c, s, law)
        } else {
            toi_pair_bodies(a, c, law)
        };
        if let Some(t) = t {
            let bits = ordered(t);
            if bits <= best.threshold() {
                best.offer(Key::body_bits(bits, i.min(j), i.max(j)), image);
            }
        }
    }

    /// Offers body `p` every pair with a body in its neighbour cells. Inlined into its one
    /// caller, `recompute_in_cells`, which it was part of: out of line it cost a call's
    /// register saves per recompute.
    #[inline(always)]
    pub(super) fn scan_neighbours(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        if self.shear.is_some() {
            self.scan_sheared(world, p, best);
            return;
        }
        let k = self.cached[p.i].coords;
        let bodies = world.bodies();
        if let Some(cells) = self.grid.interior_neighbours(&k) {
            self.scan_interior::<true>(bodies, p, cells, best);
        } else {
            // Border cells: list the cells first, so that the scan below is inlined once.
            let mut cells = [(0u32, 0u8); 27];
            let mut n = 0;
            self.grid.visit_neighbours(&k, |cell, _, image| {
                cells[n] = (cell, image);
                n += 1;
            });
            self.scan_listed(bodies, p, &cells[..n], best);
        }
    }

    /// Offers body `p`, just moved into its cell along `axis` in direction `up`, every pair
    /// with a body in the layer of cells that became its neighbours.
    pub(super) fn scan_entered_layer(
        &self,
        world: &World<D>,
        p: &Probe<D>,
        axis: usize,
        up: bool,
        best: &mut Best,
    ) {
        if self.shear.is_some() {
            let k = self.cached[p.i].coords;
            let last = self.grid.dims()[1] as u32 - 1;
            if k[1] == 0 || k[1] == last {
                // The cells across a y face that neighbour a border row change as the rows
                // slide: the whole new neighbourhood is scanned.
                self.scan_sheared(world, p, best);
            } else {
                // Off the border rows the layer entered is the unsheared one, none of it
                // across a y face.
                let mut cells = Vec::with_capacity(9);
                self.grid
                    .visit_entered_layer(&k, axis, up, |cell, shift, _| {
                        if shift[1] == 0.0 {
                            cells.push(cell);
                        }
                    });
                self.scan_sheared_cells(world, p, &cells, best);
            }
            return;
        }
        let k = self.cached[p.i].coords;
        let bodies = world.bodies();
        if let Some(cells) = self.grid.interior_entered_layer(&k, axis, up) {
            // The layer lies beyond the body's own cell: it does not hold the body.
            self.scan_interior::<false>(bodies, p, cells, best);
        } else {
            let mut cells = [(0u32, 0u8); 9];
            let mut n = 0;
            self.grid
                .visit_entered_layer(&k, axis, up, |cell, _, image| {
                    cells[n] = (cell, image);
                    n += 1;
                });
            self.scan_listed(bodies, p, &cells[..n], best);
        }
    }

    /// Sheared boxes: the cells whose bodies can touch a body filed at coordinates `k` before
    /// it leaves its cell: its neighbours not across a y face and, for a body in the first or
    /// last row along y, every cell of the opposite row in its own and the neighbouring z
    /// layers (see the module docs). Sorted, each once.
    fn sheared_neighbours(&self, k: &[u32; D]) -> Vec<u32> {
        let mut cells = Vec::with_capacity(27);
        self.grid.visit_neighbours(k, |cell, shift, _| {
            if shift[1] == 0.0 {
                cells.push(cell);
            }
        });
        let dims = self.grid.dims();
        let last = dims[1] as u32 - 1;
        if k[1] == 0 || k[1] == last {
            let opposite = if k[1] == 0 { last } else { 0 };
            let layers: Vec<u32> = if D == 3 {
                let nz = dims[D - 1] as i64;
                (-1..=1)
                    .map(|dz| (i64::from(k[D - 1]) + dz).rem_euclid(nz) as u32)
                    .collect()
            } else {
                vec![0]
            };
            for x in 0..dims[0] as u32 {
                for &z in &layers {
                    let mut c = *k;
                    c[0] = x;
                    c[1] = opposite;
                    if D == 3 {
                        c[D - 1] = z;
                    }
                    cells.push(self.grid.cell_at(&c));
                }
            }
        }
        cells.sort_unstable();
        cells.dedup();
        cells
    }

    /// Sheared boxes: offers body `p` every pair with a body of its neighbourhood
    /// ([`Cells::sheared_neighbours`]), each by the oracle's sheared function.
    #[inline(never)]
    fn scan_sheared(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let cells = self.sheared_neighbours(&self.cached[p.i].coords);
        self.scan_sheared_cells(world, p, &cells, best);
    }

    /// Sheared boxes: offers body `p` every pair with a body of the cells `cells`, each by
    /// the oracle's sheared function.
    fn scan_sheared_cells(&self, world: &World<D>, p: &Probe<D>, cells: &[u32], best: &mut Best) {
        let bodies = world.bodies();
        let zero = Vector::ZERO;
        for &c in cells {
            for j in self.grid.bodies_in(c) {
                let j = j as usize;
                if j == p.i {
                    continue;
                }
                if let Some(t) = self.pair_toi(p, j, &bodies[j], &zero) {
                    offer_time(best, p.i, j, t, Grid::<D>::ZERO_IMAGE);
                }
            }
        }
    }

    /// Offers body `p` every pair with a body of the cells `cells` (cell, image code).
    #[inline(never)]
    fn scan_listed(&self, bodies: &[Body<D>], p: &Probe<D>, cells: &[(u32, u8)], best: &mut Best) {
        if self.periodic {
            self.scan_cells::<true>(bodies, p, cells, best);
        } else {
            self.scan_cells::<false>(bodies, p, cells, best);
        }
    }

    /// [`Cells::scan_listed`], body by body.
    #[inline(always)]
    fn scan_cells<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        cells: &[(u32, u8)],
        best: &mut Best,
    ) {
        for &(c, image) in cells {
            if self.grid.cell(c).len == 0 {
                continue;
            }
            let shift = &self.shifts[image as usize];
            let neg = Vector::ZERO - *shift;
            for j in self.grid.bodies_in(c) {
                let j = j as usize;
                if j != p.i && self.resting() {
                    if let Some(t) = self.pair_toi(p, j, &bodies[j], shift) {
                        offer_time(best, p.i, j, t, image);
                    }
                } else if j != p.i {
                    let law = self.laws.as_ref();
                    let filters = &self.filters[..];
                    Self::offer_body::<PERIODIC>(
                        law, filters, p, j, &bodies[j], shift, &neg, image, best,
                    );
                }
            }
        }
    }

    /// Offers body `p` every pair with a body of the interior cells `cells` (zero image
    /// shift): gathered from the cells' slots and evaluated four at a time (see `gather`),
    /// or, when a cell overflows its slots, body by body. `OWN`: the cells may hold `p`
    /// (its own cell is among them), which is then dropped from the candidates.
    #[inline(always)]
    fn scan_interior<const OWN: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        cells: impl Iterator<Item = u32> + Clone,
        best: &mut Best,
    ) {
        if D == 2 {
            self.scan_interior_in::<GATHER_2D, OWN>(bodies, p, cells, best);
        } else {
            self.scan_interior_in::<GATHER_3D, OWN>(bodies, p, cells, best);
        }
    }

    /// [`Cells::scan_interior`] with a buffer of `CAP` candidates.
    #[inline(always)]
    fn scan_interior_in<const CAP: usize, const OWN: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        cells: impl Iterator<Item = u32> + Clone,
        best: &mut Best,
    ) {
        let mut g = Gathered::<CAP>::new();
        for c in cells.clone() {
            g.push(self.grid.cell(c));
        }
        if g.overflow() || self.resting() {
            let mut listed = [(0u32, Grid::<D>::ZERO_IMAGE); 27];
            let mut n = 0;
            for c in cells {
                listed[n].0 = c;
                n += 1;
            }
            self.scan_listed(bodies, p, &listed[..n], best);
            return;
        }
        if OWN {
            g.drop_probes(p.i as u32, p.i as u32);
        }
        let ids = &g.ids[..g.n];
        if self.hints {
            // A hint for each candidate's record before the evaluation: the loads are
            // independent, so their misses overlap.
            for &j in ids {
                prefetch(&bodies[j as usize]);
            }
        }
        let probe = Side::splat(&p.b.motion, p.b.radius);
        let ids = &g.ids;
        let law = self.laws.as_ref();
        let filters = &self.filters[..];
        match (self.periodic, law.is_some()) {
            (true, false) => Self::scan_gathered::<true, false>(
                law, filters, bodies, p, &probe, ids, 0, g.n, best,
            ),
            (false, false) => Self::scan_gathered::<false, false>(
                law, filters, bodies, p, &probe, ids, 0, g.n, best,
            ),
            (true, true) => Self::scan_gathered::<true, true>(
                law, filters, bodies, p, &probe, ids, 0, g.n, best,
            ),
            (false, true) => Self::scan_gathered::<false, true>(
                law, filters, bodies, p, &probe, ids, 0, g.n, best,
            ),
        }
    }

    /// Offers body `p` every wall within reach of its cell.
    #[inline(always)]
    pub(super) fn scan_walls(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let walls = self
            .grid
            .walls_of(self.grid.cell_at(&self.cached[p.i].coords));
        if !walls.is_empty() {
            self.offer_walls(world, p, walls, &[], best);
        }
    }

    /// Offers body `p`, just moved into its cell from cell `from`, every wall within reach of
    /// its new cell that the old one did not list (the others are covered since the last
    /// time its walls were scanned, see the module docs).
    #[inline(always)]
    pub(super) fn scan_entered_walls(
        &self,
        world: &World<D>,
        p: &Probe<D>,
        from: u32,
        best: &mut Best,
    ) {
        let walls = self
            .grid
            .walls_of(self.grid.cell_at(&self.cached[p.i].coords));
        if !walls.is_empty() {
            self.offer_walls(world, p, walls, self.grid.walls_of(from), best);
        }
    }

    /// Offers body `p` the walls of the sorted list `walls` that are not in the sorted list
    /// `skip`.
    #[inline(never)]
    pub(super) fn offer_walls(
        &self,
        world: &World<D>,
        p: &Probe<D>,
        walls: &[u32],
        skip: &[u32],
        best: &mut Best,
    ) {
        let mut skip = skip.iter().peekable();
        for &w in walls {
            while skip.next_if(|&&s| s < w).is_some() {}
            if skip.next_if_eq(&&w).is_some() {
                continue;
            }
            let wall = &world.walls()[w as usize];
            let t = if self.resting() {
                toi_body_wall_resting(world, p.i, w as usize)
            } else {
                toi_body_wall_of(&p.b, wall, self.laws.as_ref())
            };
            if let Some(t) = t {
                best.offer(Key::wall(t, p.i, w as usize), Grid::<D>::ZERO_IMAGE);
            }
        }
    }

    /// Offers body `p` its exit from the periodic box, if the world is periodic and the body
    /// is filed in a border cell (the box's faces count as walls listed by the border cells
    /// only, see the module docs).
    #[inline]
    pub(super) fn scan_exit(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        if self.periodic && self.grid.is_border(&self.cached[p.i].coords) {
            if let Some(key) = self.box_exit(world, p) {
                best.offer(key, Grid::<D>::ZERO_IMAGE);
            }
        }
    }

    /// Body `p`'s exit from the periodic box as a key, if the world is periodic and the body
    /// moves. Out of line and returning the key rather than offering it: most recomputes skip
    /// it, and a `&mut Best` passed out of line keeps the scan's records in memory instead of
    /// registers (callgrind, 2D N = 10⁴: +100 instructions per collision).
    #[inline(never)]
    pub(super) fn box_exit(&self, world: &World<D>, p: &Probe<D>) -> Option<Key> {
        let size = world.periodic()?;
        toi_box_exit(&p.b.motion, &size).map(|(t, face)| Key::wall(t, p.i, self.faces_from + face))
    }

    /// True when body `i`'s cached event is still a live term: a wall event depends on `i`
    /// alone (recomputed whenever `i` changes); a body event is live while its partner has
    /// not changed since it was computed (the same function of the same states: `i` itself
    /// is recomputed whenever it changes), which its change count tells when it was recorded.
    /// When it was not (a promoted second event), the event is evaluated again, for the same
    /// image, on the current stored states and must come out bit for bit the same.
    ///
    /// A partner that changed makes the event stale even if its time happens to come out the
    /// same: the pair is then covered by the partner, recomputed when it changed (see the
    /// module docs), so dropping it from `i`'s records loses nothing.
    #[inline]
    pub(super) fn is_live(&self, world: &World<D>, i: usize) -> bool {
        let c = &self.cached[i];
        let Some(j) = c.best.partner(i) else {
            return true;
        };
        if c.partner_changes != UNKNOWN_CHANGES {
            return c.partner_changes == world.change_count(j);
        }
        self.evaluates_the_same(world, i)
    }

    /// True when body `i`'s cached body–body event, evaluated again for the same image on
    /// the current stored states, comes out bit for bit the same.
    pub(super) fn evaluates_the_same(&self, world: &World<D>, i: usize) -> bool {
        let key = self.cached[i].best;
        let Some(j) = key.partner(i) else {
            return true;
        };
        let shift = self.shifts[self.cached[i].image as usize];
        let t = self.pair_toi(&Probe::of(world, i), j, &world.bodies()[j], &shift);
        t.is_some_and(|t| Key::body(t, i.min(j), i.max(j)) == key)
    }

    /// Recomputes body `i`'s earliest event from scratch (after its state changed, or when its
    /// cached event went stale) and reschedules it.
    pub(super) fn recompute(&mut self, world: &World<D>, i: usize) {
        self.stats.recomputes += 1;
        let p = Probe::of(world, i);
        match self.mode {
            Mode::Crossings => self.recompute_in_cells::<false>(world, &p),
            Mode::FallingCrossings => self.recompute_in_cells::<true>(world, &p),
            Mode::Lists(_) => self.recompute_listed(world, &p),
        }
    }

    /// Body `i`'s records.
    #[inline]
    pub(super) fn records(&self, i: usize) -> Best {
        Best {
            key: self.cached[i].best,
            image: self.cached[i].image,
            second: self.cached[i].second,
            second_image: self.cached[i].second_image & !SECOND_KNOWN,
            known: self.cached[i].second_image & SECOND_KNOWN != 0,
        }
    }

    /// Stores body `i`'s records. `best` was computed on the current states if it comes from
    /// a full scan (`rescanned`) or is not the cached one, and then records its partner's
    /// change count; the cached `best` carried over by a crossing keeps the count of when it
    /// was computed (a count taken now would call it live after a change of its partner).
    #[inline]
    pub(super) fn store(&mut self, world: &World<D>, i: usize, best: &Best, rescanned: bool) {
        if rescanned || best.key != self.cached[i].best {
            self.cached[i].partner_changes = best
                .key
                .partner(i)
                .map_or(UNKNOWN_CHANGES, |j| world.change_count(j));
        }
        self.cached[i].best = best.key;
        self.cached[i].image = best.image;
        self.cached[i].second = best.second;
        self.cached[i].second_image = best.second_image | if best.known { SECOND_KNOWN } else { 0 };
    }

    /// Replaces body `i`'s stale cached event by its second one, if that is known, and
    /// reschedules it; false when a full rescan is needed.
    pub(super) fn promote_second(&mut self, world: &World<D>, i: usize) -> bool {
        let mut best = self.records(i);
        if !best.known {
            return false;
        }
        best.key = best.second;
        best.image = best.second_image;
        best.known = false;
        self.store(world, i, &best, false);
        // The second event was computed earlier: its partner's count then is not known.
        self.cached[i].partner_changes = UNKNOWN_CHANGES;
        self.schedule(i, &world.motion(i));
        true
    }

    /// Sets body `i`'s queue key: its next crossing or its cached event, whichever is first.
    pub(super) fn schedule(&mut self, i: usize, mi: &Motion<D>) {
        match self.mode {
            Mode::Crossings => self.schedule_crossing::<false>(i, mi),
            Mode::FallingCrossings => self.schedule_crossing::<true>(i, mi),
            Mode::Lists(_) => self.schedule_listed(i),
        }
    }
}

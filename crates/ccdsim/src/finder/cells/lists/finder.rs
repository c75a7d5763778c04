//! The `cells` finder's code for list mode: scans of a body's neighbour list, list rebuilds
//! when a body leaves its shell, and the list mode's `recompute`, `schedule`, `update` and
//! `validate`.

use super::super::candidate::{Best, Probe};
use super::super::grid::Grid;
use super::super::key::Key;
use super::super::slots::SLOTS;
use super::super::{Cells, Mode, KEY_IS_CROSSING};
use super::*;
use crate::collision_filter::{colliding_lanes, pair_collides};
use crate::contact::narrow_lanes::{
    first_lanes, toi_sides, toi_sides_growing, vector_lanes, Lanes, PairArgs, Side, ALL_LANES,
    LANES,
};
use crate::contact::{toi_bodies_shifted, toi_pair};
use crate::geom::Vector;
use crate::motion::Body;
use crate::prefetch::prefetch;
use crate::world::World;
use wide::{f64x4, i32x4};

impl<const D: usize> Cells<D> {
    /// The list mode's structures (list-mode code runs in list mode only).
    #[inline(always)]
    pub(in super::super) fn lists(&self) -> &Lists<D> {
        match &self.mode {
            Mode::Lists(lists) => lists,
            Mode::Crossings | Mode::FallingCrossings => {
                unreachable!("list-mode code runs in list mode only")
            }
        }
    }

    /// The list mode's structures, mutable (list mode only).
    #[inline(always)]
    fn lists_mut(&mut self) -> &mut Lists<D> {
        match &mut self.mode {
            Mode::Lists(lists) => lists,
            Mode::Crossings | Mode::FallingCrossings => {
                unreachable!("list-mode code runs in list mode only")
            }
        }
    }

    /// Hints that the records of body `i`'s listed partners will be read soon: asked for
    /// together, their misses overlap. Not the first quad's: the scan reads those at once.
    #[inline(always)]
    pub(in super::super) fn prefetch_partners(&self, world: &World<D>, i: usize) {
        let bodies = world.bodies();
        for &e in self.lists().list(i).get(LANES..).unwrap_or_default() {
            prefetch(&bodies[entry_body(e)]);
        }
    }

    /// Offers body `p` every pair of its neighbour list, each by the oracle's narrow phase
    /// with the oracle's arguments (see `scan_list`): the partners of higher index (listed
    /// first) with `p` first, the rest with the partner first. Inlined into its one caller,
    /// `recompute_listed`: out of line it cost a call's register saves per recompute.
    #[inline(always)]
    pub(in super::super) fn scan_neighbour_list(
        &self,
        world: &World<D>,
        p: &Probe<D>,
        best: &mut Best,
    ) {
        let lists = self.lists();
        let above = lists.parts(p.i).0.len();
        let entries = lists.list(p.i);
        let bodies = world.bodies();
        if self.hints {
            self.prefetch_partners(world, p.i);
        }
        match (self.periodic, self.laws.is_some()) {
            (true, false) => self.scan_quads::<true, false>(bodies, p, entries, above, best),
            (false, false) => self.scan_quads::<false, false>(bodies, p, entries, above, best),
            (true, true) => self.scan_quads::<true, true>(bodies, p, entries, above, best),
            (false, true) => self.scan_quads::<false, true>(bodies, p, entries, above, best),
        }
    }

    /// Offers body `p` the pairs of the list entries `entries`, of which the first `above`
    /// have a higher body index than `p`'s (`p` goes first in their pairs, the partner in
    /// the others'). The entries go four at a time, in list order, through the lane kernel
    /// ([`crate::contact::narrow_lanes::toi_sides`], each lane the scalar function's times bit for
    /// bit): `p` is put in all lanes once; a quad of one part has `p` on one side, the quad where
    /// the parts meet selects each lane's sides by its part, and the last quad is padded with
    /// copies of the last entry, whose lanes are dropped (no time, never handed to the scalar
    /// function).
    #[inline(always)]
    fn scan_quads<const PERIODIC: bool, const GROW: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        entries: &[u32],
        above: usize,
        best: &mut Best,
    ) {
        let n = entries.len();
        let probe = Side::splat(&p.b.motion, p.b.radius);
        let mut k = 0;
        while k < n {
            let (quad, valid) = if let Some(q) = entries.get(k..k + LANES) {
                ([q[0], q[1], q[2], q[3]], ALL_LANES)
            } else {
                // Past the end, the last entry again (its lanes are dropped).
                let q = std::array::from_fn(|l| entries[(k + l).min(n - 1)]);
                (q, (1 << (n - k)) - 1)
            };
            // Collision filters drop the lanes of pairs that pass through each other, and so
            // does a kinematic probe the lanes of its kinematic partners.
            let valid = if GROW && !self.filters.is_empty() {
                valid & colliding_lanes(&self.filters, p.i, quad.map(|e| entry_body(e) as u32))
            } else {
                valid
            };
            let valid = if GROW && self.kinematic.get(p.i).copied().unwrap_or(false) {
                valid & self.moving_lanes(quad)
            } else {
                valid
            };
            if k + LANES <= above {
                self.scan_quad::<PERIODIC, GROW, 0>(bodies, p, &probe, quad, LANES, valid, best);
            } else if k >= above {
                self.scan_quad::<PERIODIC, GROW, 1>(bodies, p, &probe, quad, 0, valid, best);
            } else {
                let first = above - k;
                self.scan_quad::<PERIODIC, GROW, 2>(bodies, p, &probe, quad, first, valid, best);
            }
            k += LANES;
        }
    }

    /// The lane mask of the entries of `quad` whose bodies are not kinematic (a kinematic
    /// probe meets only those, see [`toi_bodies_shifted`]).
    #[cold]
    #[inline(never)]
    fn moving_lanes(&self, quad: [u32; LANES]) -> u32 {
        (0..LANES)
            .filter(|&l| !self.kinematic[entry_body(quad[l])])
            .fold(0, |mask, l| mask | 1 << l)
    }

    /// Offers body `p` (in all lanes of `probe`) the pairs of the list entries `quad` whose
    /// bits are set in `valid`: `p` first in all lanes (`ORDER` 0), in none (1), or in the
    /// lanes below `first` (2).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn scan_quad<const PERIODIC: bool, const GROW: bool, const ORDER: u8>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        probe: &Side<D>,
        quad: [u32; LANES],
        first: usize,
        valid: u32,
        best: &mut Best,
    ) {
        let lists = self.lists();
        let b = quad.map(|e| &bodies[entry_body(e)]);
        let other = Side::gather(b.map(|b| &b.motion), b.map(|b| b.radius));
        // Each lane's shift as the oracle writes it for its order.
        let shift_of = |table: [&[Vector<D>; 1 << IMAGE_BITS]; LANES]| {
            if PERIODIC {
                vector_lanes(std::array::from_fn(|l| {
                    &table[l][usize::from(entry_image(quad[l]))]
                }))
            } else {
                [f64x4::ZERO; D]
            }
        };
        let law = if GROW {
            self.laws.as_ref().and_then(|l| l.growth.as_ref())
        } else {
            None
        };
        // The fixed-radius kernel, or (growing radii) its growing form.
        let kernel = |sa: &Side<D>, sb: &Side<D>, shift: &[f64x4; D]| match law {
            Some(law) => toi_sides_growing::<D, PERIODIC>(sa, sb, shift, law),
            None => toi_sides::<D, PERIODIC>(sa, sb, shift),
        };
        let lanes = match ORDER {
            0 => kernel(probe, &other, &shift_of([&lists.shifts; LANES])),
            1 => kernel(&other, probe, &shift_of([&lists.neg_shifts; LANES])),
            _ => {
                let mask = first_lanes(first);
                let sa = Side::select(mask, probe, &other);
                let sb = Side::select(mask, &other, probe);
                let tables = std::array::from_fn(|l| {
                    if l < first {
                        &lists.shifts
                    } else {
                        &lists.neg_shifts
                    }
                });
                kernel(&sa, &sb, &shift_of(tables))
            }
        }
        .only(valid);
        if lanes.rare != 0 {
            self.offer_rare_quad::<PERIODIC>(bodies, p, quad, lanes, best);
            return;
        }
        let mut hits = lanes.hits;
        while hits != 0 {
            let l = hits.trailing_zeros() as usize;
            offer_entry(best, p.i, quad[l], lanes.times[l]);
            hits &= hits - 1;
        }
    }

    /// [`Cells::scan_quad`]'s offers when a lane is left to the scalar function (rare: out of
    /// line, so that the scan keeps its registers).
    #[cold]
    #[inline(never)]
    fn offer_rare_quad<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        quad: [u32; LANES],
        lanes: Lanes,
        best: &mut Best,
    ) {
        lanes.each_time(
            |l, t| offer_entry(best, p.i, quad[l], t),
            |l| self.list_pair(bodies, p, quad[l]).scalar::<PERIODIC>(),
        );
    }

    /// The pair of body `p` and list entry `e` in the oracle's argument order.
    #[inline(always)]
    fn list_pair<'a>(&'a self, bodies: &'a [Body<D>], p: &'a Probe<D>, e: u32) -> PairArgs<'a, D> {
        let lists = self.lists();
        let j = entry_body(e);
        let image = usize::from(entry_image(e));
        let b = &bodies[j];
        if p.i < j {
            PairArgs {
                a: &p.b.motion,
                ra: p.b.radius,
                b: &b.motion,
                rb: b.radius,
                shift: &lists.shifts[image],
                laws: self.laws.as_ref(),
            }
        } else {
            PairArgs {
                a: &b.motion,
                ra: b.radius,
                b: &p.b.motion,
                rb: p.b.radius,
                shift: &lists.neg_shifts[image],
                laws: self.laws.as_ref(),
            }
        }
    }

    /// Offers body `p` the pairs of the list entries `entries`.
    #[inline(always)]
    fn scan_entries<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        entries: &[u32],
        best: &mut Best,
    ) {
        let i = p.i;
        let shifts = &self.lists().shifts;
        for &e in entries {
            let j = entry_body(e);
            if !pair_collides(&self.filters, i, j) {
                continue;
            }
            let image = entry_image(e);
            let b = &bodies[j];
            let probe_first = i < j;
            let (a, c) = if probe_first { (&p.b, b) } else { (b, &p.b) };
            let t = if PERIODIC {
                let shift = shifts[usize::from(image)];
                // The partner's shift as the oracle writes it: `0 − s` keeps zeros +0.
                let s = if probe_first {
                    shift
                } else {
                    Vector::ZERO - shift
                };
                toi_bodies_shifted(a, c, s, self.laws.as_ref())
            } else {
                toi_pair(&a.motion, a.radius, &c.motion, c.radius, self.laws.as_ref())
            };
            if let Some(t) = t {
                let bits = super::super::key::ordered(t);
                if bits <= best.threshold() {
                    best.offer(
                        super::super::key::Key::body_bits(bits, i.min(j), i.max(j)),
                        image,
                    );
                }
            }
        }
    }

    /// Builds every body's list from scratch (at `init`, shell centres set).
    pub(in super::super) fn build_all_lists(&mut self, n: usize) {
        for i in 0..n {
            let (na, nb) = self.collect_overlapping(i);
            let lists = self.lists_mut();
            let (above, below) = (
                std::mem::take(&mut lists.fresh),
                std::mem::take(&mut lists.fresh_below),
            );
            lists.set(i, &above[..na], &below[..nb]);
            lists.fresh = above;
            lists.fresh_below = below;
        }
    }

    /// Fills the scratch lists `fresh` (bodies of higher index) and `fresh_below` (lower) with
    /// every body whose shell overlaps body `i`'s, from
    /// the neighbour cells of `i`'s cell whose box comes within the overlap distance of its
    /// shell centre (see `Lists::near_cells`).
    ///
    /// The centres come from the cells' slot records ([`CellSlots`]), each cell's slots
    /// tested together, lane by lane, without a branch on any test's outcome (only a cell's
    /// overflow, rare, takes one): a first pass keeps one bit per slot and part, a second
    /// copies the kept entries. Returns the numbers of entries of higher and of lower body
    /// index (the scratch lists' lengths).
    ///
    /// The entries come in slot order, which swap-removes reshuffle: the order of a list is
    /// not the order of its bodies' filing. No result depends on it: a scan offers every
    /// entry to `Best`, which keeps the smallest keys, and keys are totally ordered, so two
    /// entries tie only when they are the same pair through two images (an axis of a single
    /// cell lists a pair once per overlapping image). Then the images' times are equal bit
    /// for bit, the event returned (time, kind, bodies) is the same whichever image is kept,
    /// and the kept image is only used to evaluate a promoted event again, to tell whether it
    /// is live: on unchanged states either image gives that same time, and otherwise the
    /// proof of the module docs holds whichever image was kept (a live key is returned, a
    /// stale one replaced by its body's live minimum), so the events returned are the same
    /// and only the `stale`/`recomputes` counters could tell.
    fn collect_overlapping(&mut self, i: usize) -> (usize, usize) {
        let mut above = std::mem::take(&mut self.lists_mut().fresh);
        let mut below = std::mem::take(&mut self.lists_mut().fresh_below);
        above.clear();
        below.clear();
        let mut near = std::mem::take(&mut self.lists_mut().near);
        let mut slot_entries = std::mem::take(&mut self.lists_mut().slot_entries);
        let lists = self.lists();
        let xi = lists.centre[i];
        let cells: &mut [(u32, u8); 27] = near.as_mut_slice().try_into().expect("27 cells");
        let count = lists.near_cells(&self.grid, &self.cached[i].coords, &xi, cells);
        if self.hints {
            for &(c, _) in &cells[..count] {
                lists.slots.prefetch_cell(c);
            }
        }
        // First pass, without a branch on any test: each cell's slot entries go to `entries`,
        // and one bit per slot (bit `SLOTS·a + k` for slot `k` of the `a`-th cell of a
        // group of 16) says whether it is kept in the part of higher body index or of lower.
        let entries: &mut [[u32; SLOTS]; 27] =
            slot_entries.as_mut_slice().try_into().expect("27 cells");
        let probe = CellProbe {
            x: std::array::from_fn(|d| f64x4::splat(xi[d])),
            me: i32x4::splat(i as i32),
            cut: f64x4::splat(lists.cut_sq),
        };
        let mut kept = [(0u64, 0u64); 2];
        let mut any_overflow = false;
        for (group, bits) in kept.iter_mut().enumerate() {
            let from = (16 * group).min(count);
            let to = (16 * group + 16).min(count);
            for (at, (&(c, image), out)) in cells[from..to]
                .iter()
                .zip(&mut entries[from..to])
                .enumerate()
            {
                let rec = lists.slots.cell(c);
                let (up, down) = lists.test_cell(rec, image, &probe, out);
                bits.0 |= u64::from(up) << (SLOTS * at);
                bits.1 |= u64::from(down) << (SLOTS * at);
                any_overflow |= rec.len as usize > SLOTS;
            }
        }
        // Second pass: the kept entries, in cell and slot order.
        for (group, &(up, down)) in kept.iter().enumerate() {
            let flat = entries[(16 * group).min(27)..].as_flattened();
            for (mut bits, part) in [(up, &mut above), (down, &mut below)] {
                while bits != 0 {
                    part.push(flat[bits.trailing_zeros() as usize]);
                    bits &= bits - 1;
                }
            }
        }
        if any_overflow {
            // Full cells: their other bodies are in their overflow lists (rare), with their
            // centres.
            for &(c, image) in &cells[..count] {
                let shift = &lists.shifts[usize::from(image) & IMAGE_MASK as usize];
                for j in lists.slots.overflow(c) {
                    let ju = j as usize;
                    if lists.overlap(&xi, &lists.centre[ju], shift) && ju != i {
                        let e = entry(ju, image);
                        if ju > i {
                            above.push(e);
                        } else {
                            below.push(e);
                        }
                    }
                }
            }
        }
        let (na, nb) = (above.len(), below.len());
        let lists = self.lists_mut();
        lists.fresh = above;
        lists.fresh_below = below;
        lists.near = near;
        lists.slot_entries = slot_entries;
        (na, nb)
    }

    /// Moves body `i`'s shell centre to its position at `t`, files it in the cell of that
    /// point and rebuilds its list, keeping the lists symmetric: `i` joins the lists of its
    /// new neighbours and leaves those of the bodies it no longer overlaps. With `best`, body
    /// `i` is offered the pairs new to its list and the walls new to its cell (the others are
    /// covered since they became responsible, see the module docs).
    pub(in super::super) fn relist(
        &mut self,
        world: &World<D>,
        i: usize,
        t: f64,
        best: Option<&mut Best>,
    ) {
        let x = world.motion(i).at(t);
        let was_at = self.lists().centre[i];
        self.lists_mut().centre[i] = x;
        let from = self.grid.cell_at(&self.cached[i].coords);
        let from_border = self.grid.is_border(&self.cached[i].coords);
        let k = self.grid.coords_of_point(&x);
        self.grid.relocate(i, &mut self.cached[i].coords, k);
        let to = self.grid.cell_at(&self.cached[i].coords);
        let lists = self.lists_mut();
        if to == from {
            lists.slots.set_centre(i, to, &x);
        } else {
            lists.slots.remove(i, from, &lists.centre);
            lists.slots.insert(i, to, &x);
        }
        let (na, nb) = self.collect_overlapping(i);
        let lists = self.lists_mut();
        let (above, below) = (
            std::mem::take(&mut lists.fresh),
            std::mem::take(&mut lists.fresh_below),
        );
        // The old list (a copy: partners' lists change below) and the new one, part by part
        // (an entry's part is fixed by its body index): entries only in the old one leave
        // their partner's list, entries only in the new one join it and go to `added`. The
        // lists equal the overlap relation on the centres before this rebuild and after it,
        // and only `i`'s centre moved, so an old entry is not in the new list exactly when its
        // partner's shell fails `Lists::overlap` with the new centre, and a new entry was not
        // in the old list exactly when it fails it with the old centre `was_at`: one test per
        // entry instead of a sweep of the other list.
        let mut old = std::mem::take(&mut lists.old);
        let (old_above, old_below) = lists.parts(i);
        let split = old_above.len();
        old.clear();
        old.extend_from_slice(old_above);
        old.extend_from_slice(old_below);
        let mut added = std::mem::take(&mut lists.added);
        added.clear();
        let parts = [(&old[..split], &above[..na]), (&old[split..], &below[..nb])];
        for (was, now) in parts {
            for &e in was {
                let (j, image) = (entry_body(e), entry_image(e));
                if !lists.overlap(&x, &lists.centre[j], &lists.shifts[usize::from(image)]) {
                    lists.remove(j, entry(i, opposite::<D>(image)));
                }
            }
            for &e in now {
                let (j, image) = (entry_body(e), entry_image(e));
                if !lists.overlap(&was_at, &lists.centre[j], &lists.shifts[usize::from(image)]) {
                    lists.push(j, entry(i, opposite::<D>(image)));
                    added.push(e);
                }
            }
        }
        let (above_new, below_new) = (&above[..na], &below[..nb]);
        lists.set(i, above_new, below_new);
        if let Some(best) = best {
            let p = Probe::of(world, i);
            if self.periodic {
                self.scan_entries::<true>(world.bodies(), &p, &added, best);
            } else {
                self.scan_entries::<false>(world.bodies(), &p, &added, best);
            }
            let walls = self
                .grid
                .walls_of(self.grid.cell_at(&self.cached[i].coords));
            if !walls.is_empty() {
                self.offer_walls(world, &p, walls, self.grid.walls_of(from), best);
            }
            if !from_border {
                self.scan_exit(world, &p, best);
            }
        }
        let lists = self.lists_mut();
        lists.fresh = above;
        lists.fresh_below = below;
        lists.old = old;
        lists.added = added;
    }

    /// Processes body `i`'s shell exit, due at `time`: its list is rebuilt around its
    /// position then, it is offered what became responsible, and its next exit is scheduled.
    #[inline(never)]
    pub(in super::super) fn exit_shell(&mut self, world: &World<D>, i: usize, time: f64) {
        self.stats.rebuilds += 1;
        let t = time.max(self.clock);
        self.clock = t;
        let mut best = self.records(i);
        self.relist(world, i, t, Some(&mut best));
        // Like a crossing: the cached event carries over with the partner count it had.
        self.store(world, i, &best, false);
        let m = world.motion(i);
        let lists = self.lists_mut();
        lists.exit[i] = shell_exit_time(&m, &lists.centre[i], lists.half, t);
        lists.log.push((i as u32, t));
        self.schedule_listed(i);
    }

    /// True when body `i`'s stored position lies outside its shell (after a state change; a
    /// box exit moves the position by a period, far outside).
    pub(in super::super) fn outside_shell(&self, world: &World<D>, i: usize) -> bool {
        let lists = self.lists();
        (world.position(i) - lists.centre[i]).norm_sq() > lists.half * lists.half
    }

    /// Before an update whose earliest change is at `t`: rebuilds again at `t` the lists of
    /// the bodies (other than `changed`) rebuilt after `t`, so that every body lies in its
    /// shell from `t` on, and recomputes them.
    pub(in super::super) fn redo_rebuilds_after(
        &mut self,
        world: &World<D>,
        t: f64,
        changed: &[usize],
    ) {
        let mut log = std::mem::take(&mut self.lists_mut().log);
        log.retain(|&(i, time)| time > t && !changed.contains(&(i as usize)));
        log.sort_unstable_by_key(|&(i, _)| i);
        log.dedup_by_key(|&mut (i, _)| i);
        for &(i, _) in &log {
            self.stats.undone += 1;
            self.relist(world, i as usize, t, None);
        }
        for &(i, _) in &log {
            self.recompute(world, i as usize);
        }
        log.clear();
        self.lists_mut().log = log;
    }

    /// Checks the list mode's structures at the finder's clock: every body within its shell
    /// (up to rounding); every list entry mirrored in its partner's list and listed once; the
    /// lists holding exactly the pairs (images included) whose shells overlap (checked
    /// against every pair and every image, not the grid); every body filed in the cell of its
    /// shell centre, in the grid and in the slot records (see `CellSlots::validate`).
    pub(in super::super) fn validate_lists(&self, world: &World<D>) -> Result<(), String> {
        let lists = self.lists();
        let n = world.len();
        lists
            .slots
            .validate(&lists.centre, |i| self.grid.cell_at(&self.cached[i].coords))?;
        let clock = self.clock;
        for i in 0..n {
            let m = world.motion(i);
            let p = m.at(clock.max(m.time));
            let tol = 1e-9 * (1.0 + p.norm() + m.vel.norm() * (clock - m.time).abs());
            let dist = (p - lists.centre[i]).norm();
            if dist > lists.half + tol {
                return Err(format!(
                    "body {i} is {dist} from its shell centre at t = {clock} (shell radius {})",
                    lists.half
                ));
            }
            let k = self
                .grid
                .coords_of_point(&lists.centre[i])
                .map(|x| x as u32);
            if k != self.cached[i].coords {
                return Err(format!(
                    "body {i} is not filed in the cell of its shell centre"
                ));
            }
            let (above, below) = lists.parts(i);
            if above.iter().any(|&e| entry_body(e) <= i) || below.iter().any(|&e| entry_body(e) > i)
            {
                return Err(format!(
                    "body {i}: list entries of higher body index do not come first"
                ));
            }
            let list = lists.list(i);
            for (a, &e) in list.iter().enumerate() {
                if list[..a].contains(&e) {
                    return Err(format!("body {i} lists {} twice", entry_body(e)));
                }
                let j = entry_body(e);
                if j == i || j >= n {
                    return Err(format!("body {i} lists body {j}"));
                }
                if !lists
                    .list(j)
                    .contains(&entry(i, opposite::<D>(entry_image(e))))
                {
                    return Err(format!("body {i} lists {j} but not the other way round"));
                }
            }
        }
        // Every overlapping pair and image is listed, and nothing else.
        let images = 3usize.pow(D as u32);
        let mut count = 0usize;
        // `a`'s list as marks over (body, image), so each pair is looked up in constant time.
        let mut marked = vec![false; n * images];
        for a in 0..n {
            for &e in lists.list(a) {
                if entry_body(e) < n {
                    marked[entry_body(e) * images + usize::from(entry_image(e))] = true;
                }
            }
            for b in a + 1..n {
                for image in 0..images {
                    if !self.periodic && image != Grid::<D>::ZERO_IMAGE as usize {
                        continue;
                    }
                    let shift = self.shifts[image];
                    let listed = marked[b * images + image];
                    let overlaps = lists.overlap(&lists.centre[a], &lists.centre[b], &shift);
                    let mirrored = lists.overlap(
                        &lists.centre[b],
                        &lists.centre[a],
                        &self.shifts[usize::from(opposite::<D>(image as u8))],
                    );
                    if overlaps != mirrored {
                        return Err(format!("bodies {a} and {b}: overlap is not symmetric"));
                    }
                    if listed != overlaps {
                        return Err(format!(
                            "bodies {a} and {b} (image {image}): listed {listed}, shells overlap \
                             {overlaps}"
                        ));
                    }
                    count += usize::from(listed);
                }
            }
            for &e in lists.list(a) {
                if entry_body(e) < n {
                    marked[entry_body(e) * images + usize::from(entry_image(e))] = false;
                }
            }
        }
        let total: usize = (0..n).map(|i| lists.list(i).len()).sum();
        if total != 2 * count {
            return Err(format!(
                "{total} list entries for {count} overlapping pairs"
            ));
        }
        Ok(())
    }
}

impl<const D: usize> Cells<D> {
    /// `update` in list mode: rebuilds done after the earliest changed state are redone, the
    /// changed bodies out of their shells relisted, and every changed body recomputed.
    pub(in super::super) fn update_list_mode(
        &mut self,
        world: &World<D>,
        t: f64,
        changed: &[usize],
    ) {
        self.clock = t;
        self.redo_rebuilds_after(world, t, changed);
        for &i in changed {
            if self.outside_shell(world, i) {
                self.relist(world, i, world.time(i), None);
            }
        }
        for &i in changed {
            self.recompute(world, i);
        }
    }

    /// `recompute` in list mode: the neighbour list instead of the cells, and the shell exit.
    #[inline(never)]
    pub(in super::super) fn recompute_listed(&mut self, world: &World<D>, p: &Probe<D>) {
        let i = p.i;
        let mut best = Best::NONE;
        self.scan_neighbour_list(world, p, &mut best);
        self.scan_walls(world, p, &mut best);
        self.scan_exit(world, p, &mut best);
        self.store(world, i, &best, true);
        let t_ref = p.b.motion.time.max(self.clock);
        let lists = self.lists_mut();
        lists.exit[i] = shell_exit_time(&p.b.motion, &lists.centre[i], lists.half, t_ref);
        self.schedule_listed(i);
    }

    /// `schedule` in list mode: the shell exit plays the crossing's part (never for a body
    /// at rest).
    #[inline(never)]
    pub(in super::super) fn schedule_listed(&mut self, i: usize) {
        let exit = self.lists().exit[i];
        let key = if exit != f64::INFINITY && Key::crossing(exit, i) < self.cached[i].best {
            self.cached[i].cross = KEY_IS_CROSSING;
            Key::crossing(exit, i)
        } else {
            self.cached[i].cross = 0;
            self.cached[i].best
        };
        self.queue.set(i, key);
    }

    /// `validate` in list mode: the queue keys (minimum of the cached event and the shell
    /// exit), the cached events, and the lists (see `validate_lists`).
    pub(in super::super) fn validate_list_mode(&self, world: &World<D>) -> Result<(), String> {
        let lists = self.lists();
        for i in 0..world.len() {
            let exit = lists.exit[i];
            let exit_key = if exit == f64::INFINITY {
                Key::NEVER
            } else {
                Key::crossing(exit, i)
            };
            let key = self.queue.key(i);
            if key != exit_key.min(self.cached[i].best) {
                return Err(format!("body {i}: queue key is not min(event, shell exit)"));
            }
            if key.is_crossing() != (self.cached[i].cross & KEY_IS_CROSSING != 0) {
                return Err(format!("body {i}: exit flag does not match its queue key"));
            }
            self.validate_cached(world, i)?;
            let m = world.motion(i);
            let again = shell_exit_time(&m, &lists.centre[i], lists.half, m.time.max(self.clock));
            let tol = 1e-9 * (1.0 + again.abs());
            if exit != again && (exit - again).abs() > tol {
                return Err(format!(
                    "body {i}: shell exit at {exit}, its motion leaves at {again}"
                ));
            }
        }
        self.validate_lists(world)
    }
}

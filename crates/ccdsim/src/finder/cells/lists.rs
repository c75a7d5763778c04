//! The list mode of the `cells` finder: Verlet neighbour lists with a skin, per-body shells
//! and shell exits (see the module docs of `cells` for why it is exact).
//!
//! Each body `i` has a *shell centre* `X_i`, its position when its list was last built, and
//! a shell, the ball of radius `h = s/2` around it (`s` the skin). Its list `N(i)` holds every
//! body `j` (with the image code of the shift that brings `j` next to `i`) whose shell may
//! overlap `i`'s: `|X_j − X_i + shift| ≤ σ_max + s + slack` (a bound of `r_i + r_j + s` the
//! same for all pairs), a relation symmetric bit for bit, and lists are kept equal to it:
//! when `i`'s list is rebuilt, `i` is added to the lists of its new neighbours and taken out
//! of those of the bodies it no longer overlaps. Nothing else moves a shell centre, so the
//! lists always hold exactly the overlapping pairs of the current centres.
//!
//! Lists are one flat array with a per-body stride (the first slot of a block holds the
//! list's length); when a list outgrows the stride, all lists are laid out again with a
//! stride a quarter larger (amortised: the stride grows a logarithmic number of times).

use super::grid::Grid;
use super::key::NONE;
use super::predict::{Best, Probe};
use super::Cells;
use crate::geom::Vector;
use crate::narrow::{toi_circle_circle, toi_circle_circle_shifted, Motion};
use crate::world::{Body, World};

/// Low bits of a list entry holding the image code (`3^3 = 27` codes fit in 5 bits).
const IMAGE_BITS: u32 = 5;
/// Mask of the image code in a list entry.
const IMAGE_MASK: u32 = (1 << IMAGE_BITS) - 1;
/// Most bodies the list mode serves: an entry packs the body index above the image code.
pub(super) const MAX_LIST_BODIES: usize = 1 << (32 - IMAGE_BITS);

/// A list entry: body `j` seen through image code `image`.
#[inline(always)]
fn entry(j: usize, image: u8) -> u32 {
    ((j as u32) << IMAGE_BITS) | u32::from(image)
}

/// The body of a list entry.
#[inline(always)]
pub(super) fn entry_body(e: u32) -> usize {
    (e >> IMAGE_BITS) as usize
}

/// The image code of a list entry.
#[inline(always)]
pub(super) fn entry_image(e: u32) -> u8 {
    (e & IMAGE_MASK) as u8
}

/// The image code of the opposite shift (every base-3 digit `k` becomes `2 − k`).
#[inline(always)]
fn opposite<const D: usize>(image: u8) -> u8 {
    (3u8.pow(D as u32) - 1) - image
}

/// Time at which a body with motion `m`, inside the shell of radius `h` around `centre` at
/// time `t_ref`, reaches the shell's surface on its way out: the later root of
/// `|m.at(t) − centre| = h`, solved from `t_ref` without cancellation; infinity for a body at
/// rest. Between `t_ref` and that time the body is within `h` of `centre` (up to rounding).
/// A body already outside the shell and moving away gets a time at or before `t_ref`.
#[must_use]
pub(super) fn shell_exit_time<const D: usize>(
    m: &Motion<D>,
    centre: &Vector<D>,
    h: f64,
    t_ref: f64,
) -> f64 {
    let a = m.vel.norm_sq();
    if a == 0.0 {
        return f64::INFINITY;
    }
    let d = m.at(t_ref) - *centre;
    let b = d.dot(m.vel);
    let c = d.norm_sq() - h * h;
    let disc = b * b - a * c;
    if disc.is_nan() || disc < 0.0 {
        // The path misses the shell: only possible for a body already outside it.
        return t_ref;
    }
    let root = disc.sqrt();
    let tau = if b <= 0.0 {
        (root - b) / a
    } else {
        -c / (b + root)
    };
    t_ref + tau
}

/// The neighbour lists, shell centres and shell exit times of every body.
#[derive(Clone, Debug)]
pub(super) struct Lists<const D: usize> {
    /// The shell radius `h = s/2`, metres.
    pub half: f64,
    /// Square of the overlap distance `σ_max + s + slack` (slack against rounding).
    cut_sq: f64,
    /// Slots per body block: the length, then up to `stride − 1` entries.
    stride: usize,
    /// The blocks.
    entries: Vec<u32>,
    /// Shell centre of each body.
    pub centre: Vec<Vector<D>>,
    /// Shell exit time of each body (infinity: never).
    pub exit: Vec<f64>,
    /// Lists rebuilt since the last `update`: body, time.
    pub log: Vec<(u32, f64)>,
    /// Scratch: a list being built.
    fresh: Vec<u32>,
    /// Scratch: a list being replaced.
    old: Vec<u32>,
}

impl<const D: usize> Lists<D> {
    /// Lists for `n` bodies with the skin `skin`, listing pairs whose centres are at most
    /// `cut` apart (all empty, centres at the origin).
    pub fn new(n: usize, skin: f64, cut: f64) -> Self {
        let stride = 8;
        Lists {
            half: 0.5 * skin,
            cut_sq: cut * cut,
            stride,
            entries: vec![0; n * stride],
            centre: vec![Vector::ZERO; n],
            exit: vec![f64::INFINITY; n],
            log: Vec::new(),
            fresh: Vec::new(),
            old: Vec::new(),
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        4 * (self.entries.capacity() + self.fresh.capacity() + self.old.capacity())
            + std::mem::size_of::<Vector<D>>() * self.centre.capacity()
            + 8 * self.exit.capacity()
            + std::mem::size_of::<(u32, f64)>() * self.log.capacity()
    }

    /// Longest list the layout holds.
    #[cfg(test)]
    pub fn capacity(&self) -> usize {
        self.stride - 1
    }

    /// Body `i`'s list.
    #[inline(always)]
    pub fn list(&self, i: usize) -> &[u32] {
        let at = i * self.stride;
        let len = self.entries[at] as usize;
        &self.entries[at + 1..at + 1 + len]
    }

    /// Lays all lists out again so that one of `len` entries fits, in place (the array
    /// grows, then blocks move up from the last one down: a block's new place is never below
    /// its old one, so no block is overwritten before it moves), so that the peak memory is
    /// the new array only (large reallocations extend in place or are remapped).
    fn grow(&mut self, len: usize) {
        let old = self.stride;
        let stride = (len + 1).max(old + old / 4 + 1);
        let n = self.centre.len();
        self.entries.resize(n * stride, 0);
        for i in (1..n).rev() {
            let used = 1 + self.entries[i * old] as usize;
            self.entries
                .copy_within(i * old..i * old + used, i * stride);
        }
        self.stride = stride;
    }

    /// Appends `e` to body `i`'s list.
    fn push(&mut self, i: usize, e: u32) {
        let len = self.list(i).len();
        if len + 1 >= self.stride {
            self.grow(len + 1);
        }
        let at = i * self.stride;
        self.entries[at + 1 + len] = e;
        self.entries[at] += 1;
    }

    /// Takes `e` out of body `i`'s list, where it is.
    fn remove(&mut self, i: usize, e: u32) {
        let at = i * self.stride;
        let len = self.entries[at] as usize;
        let block = &mut self.entries[at + 1..at + 1 + len];
        let k = block.iter().position(|&x| x == e);
        debug_assert!(k.is_some(), "entry {e} not in the list of body {i}");
        if let Some(k) = k {
            block[k] = block[len - 1];
            self.entries[at] -= 1;
        }
    }

    /// Replaces body `i`'s list by `new`.
    fn set(&mut self, i: usize, new: &[u32]) {
        if new.len() >= self.stride {
            self.grow(new.len());
        }
        let at = i * self.stride;
        self.entries[at] = new.len() as u32;
        self.entries[at + 1..at + 1 + new.len()].copy_from_slice(new);
    }

    /// True when the shells of two bodies with centres `xa` and `xb` may overlap through the
    /// shift `shift` added to `b`'s displacement: `|xb − xa + shift| ≤ σ_max + s + slack`, a
    /// bound of `r_a + r_b + s` the same for every pair. Seen from `b` (centres swapped, the
    /// opposite shift, which is the exact negation) the displacement is the exact negation
    /// of this one (rounding to nearest is symmetric), so both sides agree bit for bit.
    #[inline(always)]
    pub fn overlap(&self, xa: &Vector<D>, xb: &Vector<D>, shift: &Vector<D>) -> bool {
        let d = (*xb - *xa) + *shift;
        d.norm_sq() <= self.cut_sq
    }
}

impl<const D: usize> Cells<D> {
    /// The list mode's structures (list mode only).
    #[inline(always)]
    fn lists(&self) -> &Lists<D> {
        self.lists.as_ref().expect("list mode")
    }

    /// The list mode's structures, mutable (list mode only).
    #[inline(always)]
    fn lists_mut(&mut self) -> &mut Lists<D> {
        self.lists.as_mut().expect("list mode")
    }

    /// Offers body `p` every pair of its neighbour list, each by the oracle's narrow phase
    /// with the oracle's arguments (see `scan_list`).
    pub(super) fn scan_neighbour_list(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let lists = self.lists();
        let bodies = world.bodies();
        if self.periodic {
            self.scan_entries::<true>(bodies, p, lists.list(p.i), best);
        } else {
            self.scan_entries::<false>(bodies, p, lists.list(p.i), best);
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
        for &e in entries {
            let j = entry_body(e);
            let image = entry_image(e);
            let b = &bodies[j];
            let probe_first = i < j;
            let (a, c) = if probe_first { (&p.b, b) } else { (b, &p.b) };
            let t = if PERIODIC {
                let shift = self.shifts[image as usize];
                // The partner's shift as the oracle writes it: `0 − s` keeps zeros +0.
                let s = if probe_first {
                    shift
                } else {
                    Vector::ZERO - shift
                };
                toi_circle_circle_shifted(&a.motion, a.radius, &c.motion, c.radius, s)
            } else {
                toi_circle_circle(&a.motion, a.radius, &c.motion, c.radius)
            };
            if let Some(t) = t {
                let bits = super::key::ordered(t);
                if bits <= best.threshold() {
                    best.offer(super::key::Key::body_bits(bits, i.min(j), i.max(j)), image);
                }
            }
        }
    }

    /// Builds every body's list from scratch (at `init`, shell centres set).
    pub(super) fn build_all_lists(&mut self, n: usize) {
        for i in 0..n {
            self.collect_overlapping(i);
            let lists = self.lists_mut();
            let fresh = std::mem::take(&mut lists.fresh);
            lists.set(i, &fresh);
            lists.fresh = fresh;
        }
    }

    /// Fills the scratch list `fresh` with every body whose shell overlaps body `i`'s, from
    /// the neighbour cells of `i`'s cell.
    fn collect_overlapping(&mut self, i: usize) {
        let k = self.grid.coords_of(i);
        let mut fresh = std::mem::take(&mut self.lists_mut().fresh);
        fresh.clear();
        let lists = self.lists();
        let xi = lists.centre[i];
        let grid = &self.grid;
        let mut scan = |c: u32, shift: &Vector<D>, image: u8| {
            let mut j = grid.first(c);
            while j != NONE {
                let ju = j as usize;
                if lists.overlap(&xi, &lists.centre[ju], shift) && ju != i {
                    fresh.push(entry(ju, image));
                }
                j = grid.next_in_cell(j);
            }
        };
        if let Some(cells) = grid.interior_neighbours(&k) {
            for c in cells {
                scan(c, &Vector::ZERO, Grid::<D>::ZERO_IMAGE);
            }
        } else {
            grid.visit_neighbours(&k, scan);
        }
        self.lists_mut().fresh = fresh;
    }

    /// Moves body `i`'s shell centre to its position at `t`, files it in the cell of that
    /// point and rebuilds its list, keeping the lists symmetric: `i` joins the lists of its
    /// new neighbours and leaves those of the bodies it no longer overlaps. With `best`, body
    /// `i` is offered the pairs new to its list and the walls new to its cell (the others are
    /// covered since they became responsible, see the module docs).
    pub(super) fn relist(&mut self, world: &World<D>, i: usize, t: f64, best: Option<&mut Best>) {
        let x = world.motion(i).at(t);
        self.lists_mut().centre[i] = x;
        let from = self.grid.cell_of(i);
        let k = self.grid.coords_of_point(&x);
        self.grid.relocate(i, k);
        self.collect_overlapping(i);
        let lists = self.lists_mut();
        let fresh = std::mem::take(&mut lists.fresh);
        let mut old = std::mem::take(&mut lists.old);
        old.clear();
        old.extend_from_slice(lists.list(i));
        for &e in &old {
            if !fresh.contains(&e) {
                lists.remove(entry_body(e), entry(i, opposite::<D>(entry_image(e))));
            }
        }
        // Entries new to the list go to the front of `old`'s tail: reuse `old` for them.
        let gone = old.len();
        for &e in &fresh {
            if !old[..gone].contains(&e) {
                lists.push(entry_body(e), entry(i, opposite::<D>(entry_image(e))));
                old.push(e);
            }
        }
        lists.set(i, &fresh);
        if let Some(best) = best {
            let p = Probe::of(world, i);
            let added = &old[gone..];
            if self.periodic {
                self.scan_entries::<true>(world.bodies(), &p, added, best);
            } else {
                self.scan_entries::<false>(world.bodies(), &p, added, best);
            }
            let walls = self.grid.walls_of(self.grid.cell_of(i));
            if !walls.is_empty() {
                self.offer_walls(world, &p, walls, self.grid.walls_of(from), best);
            }
        }
        let lists = self.lists_mut();
        lists.fresh = fresh;
        lists.old = old;
    }

    /// Processes body `i`'s shell exit, due at `time`: its list is rebuilt around its
    /// position then, it is offered what became responsible, and its next exit is scheduled.
    #[inline(never)]
    pub(super) fn exit_shell(&mut self, world: &World<D>, i: usize, time: f64) {
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
    pub(super) fn outside_shell(&self, world: &World<D>, i: usize) -> bool {
        let lists = self.lists();
        (world.position(i) - lists.centre[i]).norm_sq() > lists.half * lists.half
    }

    /// Before an update whose earliest change is at `t`: rebuilds again at `t` the lists of
    /// the bodies (other than `changed`) rebuilt after `t`, so that every body lies in its
    /// shell from `t` on, and recomputes them.
    pub(super) fn redo_rebuilds_after(&mut self, world: &World<D>, t: f64, changed: &[usize]) {
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
    /// shell centre.
    pub(super) fn validate_lists(&self, world: &World<D>) -> Result<(), String> {
        let lists = self.lists();
        let n = world.len();
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
            if k != self.grid.coords_of(i) {
                return Err(format!(
                    "body {i} is not filed in the cell of its shell centre"
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
        for a in 0..n {
            for b in a + 1..n {
                for image in 0..images {
                    if !self.periodic && image != Grid::<D>::ZERO_IMAGE as usize {
                        continue;
                    }
                    let shift = self.shifts[image];
                    let listed = lists.list(a).contains(&entry(b, image as u8));
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn motion(pos: [f64; 2], vel: [f64; 2], time: f64) -> Motion<2> {
        Motion {
            pos: Vector(pos),
            vel: Vector(vel),
            time,
        }
    }

    #[test]
    fn shell_exit_times() {
        // From the centre at unit speed: h later.
        let m = motion([1.0, 2.0], [0.0, -1.0], 3.0);
        assert_eq!(shell_exit_time(&m, &Vector([1.0, 2.0]), 0.25, 3.0), 3.25);
        // Referenced later on the same path: the same exit.
        let t = shell_exit_time(&m, &Vector([1.0, 2.0]), 0.25, 3.1);
        assert!((t - 3.25).abs() < 1e-12, "{t}");
        // Entering from behind the shell's far side: the later root.
        let m = motion([0.0, 0.0], [2.0, 0.0], 0.0);
        let t = shell_exit_time(&m, &Vector([1.0, 0.0]), 0.5, 0.5);
        assert!((t - 0.75).abs() < 1e-12, "{t}");
        // At rest: never.
        let m = motion([0.0, 0.0], [0.0, 0.0], 0.0);
        assert_eq!(
            shell_exit_time(&m, &Vector([0.1, 0.0]), 0.5, 0.0),
            f64::INFINITY
        );
        // Outside and moving away: at once (or earlier).
        let m = motion([2.0, 0.0], [1.0, 0.0], 0.0);
        assert!(shell_exit_time(&m, &Vector([0.0, 0.0]), 0.5, 0.0) <= 0.0);
        // Far along a long flight (no cancellation): h / |v| after the reference point.
        let m = motion([0.0, 0.0], [3.0, 4.0], 0.0);
        let c = m.at(1e6);
        let t = shell_exit_time(&m, &c, 0.05, 1e6);
        assert!((t - (1e6 + 0.01)).abs() < 1e-8, "{t}");
    }

    #[test]
    fn entries_and_images() {
        let e = entry(123_456, 26);
        assert_eq!((entry_body(e), entry_image(e)), (123_456, 26));
        assert_eq!(opposite::<2>(0), 8);
        assert_eq!(opposite::<2>(4), 4);
        assert_eq!(opposite::<3>(13), 13);
        assert_eq!(opposite::<3>(1), 25);
        let mut lists = Lists::<2>::new(3, 0.1, 1.1);
        for j in 0..20 {
            lists.push(1, entry(j, 4));
        }
        assert_eq!(lists.list(1).len(), 20);
        assert!(lists.capacity() >= 20);
        for j in 0..30 {
            lists.push(2, entry(j, 3));
        }
        let want: Vec<u32> = (0..30).map(|j| entry(j, 3)).collect();
        assert_eq!(lists.list(2), &want[..]);
        assert_eq!(lists.list(1).len(), 20);
        assert!(lists.list(1).iter().all(|&e| entry_image(e) == 4));
        lists.remove(1, entry(5, 4));
        assert_eq!(lists.list(1).len(), 19);
        assert!(!lists.list(1).contains(&entry(5, 4)));
        assert!(lists.list(0).is_empty());
        assert_eq!(lists.list(2), &want[..]);
    }

    #[test]
    fn overlap_is_symmetric() {
        let mut lists = Lists::<2>::new(2, 0.1, 1.1);
        let shift = Vector([-10.0, 0.0]);
        let mirrored = Vector::ZERO - shift;
        for (x0, x1, want) in [
            ([0.1, 0.3], [9.35, 0.7], true),
            ([0.1, 0.3], [9.0, 0.7], false),
            ([0.1 + 1e-17, 0.3], [9.2 + 0.1 * 3.0, 0.3], true),
        ] {
            lists.centre[0] = Vector(x0);
            lists.centre[1] = Vector(x1);
            let a = lists.overlap(&lists.centre[0], &lists.centre[1], &shift);
            let b = lists.overlap(&lists.centre[1], &lists.centre[0], &mirrored);
            assert_eq!((a, b), (want, want), "{x0:?} {x1:?}");
        }
    }

    proptest! {
        /// Up to its exit time, a body stays within the shell (up to rounding), and at the
        /// exit it is on the shell's surface.
        #[test]
        fn bodies_stay_in_their_shell_until_the_exit(
            px in -50.0f64..50.0, py in -50.0f64..50.0,
            vx in -5.0f64..5.0, vy in -5.0f64..5.0,
            h in 0.001f64..1.0, t0 in -10.0f64..100.0, lead in 0.0f64..3.0,
            frac in 0.0f64..1.0, u in 0.0f64..1.0,
        ) {
            let m = motion([px, py], [vx, vy], t0);
            prop_assume!(vx * vx + vy * vy > 1e-6);
            // A centre the body passes at t0 + lead, moved off its path by up to h·frac.
            let tc = t0 + lead;
            let off = Vector([-vy, vx]) * (h * frac / (vx * vx + vy * vy).sqrt());
            let centre = m.at(tc) + off;
            // Reference time: the body is inside the shell then.
            let t_ref = tc;
            let exit = shell_exit_time(&m, &centre, h, t_ref);
            prop_assert!(exit >= t_ref);
            let tol = 1e-9 * (1.0 + m.at(exit).norm());
            for k in 0..=16 {
                let t = t_ref + (exit - t_ref) * f64::from(k) / 16.0;
                prop_assert!((m.at(t) - centre).norm() <= h + tol);
            }
            let t = t_ref + (exit - t_ref) * u;
            prop_assert!((m.at(t) - centre).norm() <= h + tol);
            prop_assert!(((m.at(exit) - centre).norm() - h).abs() <= tol);
        }
    }
}

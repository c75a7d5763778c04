//! The shell centres of the list mode of the `cells` finder, filed cell by cell in fixed-shape
//! slots, so that a list rebuild reads each nearby cell's centres as one flat run (coordinates
//! axis by axis) and tests them lane by lane, instead of following a linked list from body to
//! body and loading each centre on its own.
//!
//! Each cell has a record of [`SLOTS`] slots (one or two cache lines): the coordinates of the
//! shell centres of its first bodies, their body indices, the number of bodies filed in the
//! cell and the head of an *overflow* list. A cell holding more than [`SLOTS`] bodies keeps
//! the others in that list (linked through the bodies), whose centres are read from the
//! shell centres themselves: exact, and rare (at packing 0.45 a cell holds 2.7 bodies on
//! average, and hard spheres spread far more evenly than at random). The slots of a cell are
//! always full before anything overflows: removing a body from a slot fills the hole from the
//! overflow list, or else with the cell's last slot (swap-remove, with each body's slot index
//! stored), so the used slots are the first `min(len, SLOTS)` ones.

use super::key::NONE;
use crate::geom::Vector;
use crate::prefetch::prefetch;

/// Slots per cell record: 4 make a record of two cache lines in 3D (centres 96 bytes, body
/// indices 16, length and overflow head 8).
pub(super) const SLOTS: usize = 4;

// A rebuild compares a cell's body indices in one four-lane vector and keeps one bit per slot
// of up to 16 cells in a `u64`.
const _: () = assert!(SLOTS == 4);

/// Slot index of a body kept in its cell's overflow list.
const OVERFLOW: u8 = u8::MAX;

/// The centres filed in one cell.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct CellRecord<const D: usize> {
    /// Coordinates of the shell centres in the slots, axis by axis: `pos[d][k]` is axis `d`
    /// of slot `k`. Unused slots hold +∞ on every axis: no distance test passes for them,
    /// so a rebuild needs no count of used slots.
    pub pos: [[f64; SLOTS]; D],
    /// Body index in each slot.
    pub body: [u32; SLOTS],
    /// Number of bodies filed in the cell, the overflowing ones included.
    pub len: u32,
    /// First body of the overflow list, or `NONE`.
    pub over: u32,
}

impl<const D: usize> CellRecord<D> {
    const EMPTY: Self = CellRecord {
        pos: [[f64::INFINITY; SLOTS]; D],
        body: [0; SLOTS],
        len: 0,
        over: NONE,
    };

    /// Number of used slots.
    #[inline(always)]
    pub fn used(&self) -> usize {
        (self.len as usize).min(SLOTS)
    }
}

/// Shell centres per cell: the records, and each body's slot and overflow link.
#[derive(Clone, Debug, Default)]
pub(super) struct CellSlots<const D: usize> {
    /// One record per cell (linear cell index).
    cells: Vec<CellRecord<D>>,
    /// Slot index of each body in its cell's record, or `OVERFLOW`.
    slot: Vec<u8>,
    /// Next body in the same overflow list, or `NONE`.
    next_over: Vec<u32>,
}

impl<const D: usize> CellSlots<D> {
    /// Empty cells for `cells` cells and `n` bodies (none filed yet).
    pub fn new(cells: usize, n: usize) -> Self {
        CellSlots {
            cells: vec![CellRecord::EMPTY; cells],
            slot: vec![OVERFLOW; n],
            next_over: vec![NONE; n],
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<CellRecord<D>>() * self.cells.capacity()
            + self.slot.capacity()
            + 4 * self.next_over.capacity()
    }

    /// The record of cell `c`.
    #[inline(always)]
    pub fn cell(&self, c: u32) -> &CellRecord<D> {
        &self.cells[c as usize]
    }

    /// Hints that the record of cell `c` will be read soon.
    #[inline(always)]
    pub fn prefetch_cell(&self, c: u32) {
        let rec = &self.cells[c as usize];
        prefetch(&rec.pos[0][0]);
        if std::mem::size_of::<CellRecord<D>>() > 64 {
            prefetch(&rec.body);
        }
    }

    /// The overflowing bodies of cell `c`, in overflow-list order.
    #[inline]
    pub fn overflow(&self, c: u32) -> impl Iterator<Item = u32> + '_ {
        let mut at = self.cells[c as usize].over;
        std::iter::from_fn(move || {
            (at != NONE).then(|| {
                let j = at;
                at = self.next_over[j as usize];
                j
            })
        })
    }

    /// Number of cells holding more bodies than their slots.
    #[cfg(test)]
    pub fn overflowing(&self) -> usize {
        self.cells.iter().filter(|r| r.len as usize > SLOTS).count()
    }

    /// Files body `i`, not filed anywhere, with shell centre `x` in cell `c`.
    pub fn insert(&mut self, i: usize, c: u32, x: &Vector<D>) {
        let rec = &mut self.cells[c as usize];
        let k = rec.len as usize;
        if k < SLOTS {
            for d in 0..D {
                rec.pos[d][k] = x[d];
            }
            rec.body[k] = i as u32;
            self.slot[i] = k as u8;
        } else {
            self.next_over[i] = rec.over;
            rec.over = i as u32;
            self.slot[i] = OVERFLOW;
        }
        rec.len += 1;
    }

    /// Takes body `i` out of cell `c`, where it is filed; `centres` are the shell centres of
    /// every body (an overflowing body moving into the freed slot brings its own).
    pub fn remove(&mut self, i: usize, c: u32, centres: &[Vector<D>]) {
        let rec = &mut self.cells[c as usize];
        let len = rec.len as usize;
        rec.len -= 1;
        let k = self.slot[i];
        self.slot[i] = OVERFLOW;
        if k == OVERFLOW {
            // Unlink it from the overflow list (a handful of bodies at most).
            let after = self.next_over[i];
            self.next_over[i] = NONE;
            if rec.over == i as u32 {
                rec.over = after;
            } else {
                let mut at = rec.over;
                while self.next_over[at as usize] != i as u32 {
                    at = self.next_over[at as usize];
                    debug_assert!(at != NONE, "body {i} not in the overflow of cell {c}");
                }
                self.next_over[at as usize] = after;
            }
            return;
        }
        let k = usize::from(k);
        // The body that fills the hole: the first overflowing one, else the last slot's.
        let (j, from) = if len > SLOTS {
            let j = rec.over as usize;
            rec.over = self.next_over[j];
            self.next_over[j] = NONE;
            (j, centres[j].0)
        } else {
            let last = len - 1;
            let j = rec.body[last] as usize;
            let from = std::array::from_fn(|d| rec.pos[d][last]);
            for d in 0..D {
                rec.pos[d][last] = f64::INFINITY;
            }
            (j, from)
        };
        if j != i {
            for (row, &x) in rec.pos.iter_mut().zip(&from) {
                row[k] = x;
            }
            rec.body[k] = j as u32;
            self.slot[j] = k as u8;
        }
    }

    /// Records that body `i`, filed in cell `c`, has the shell centre `x` now.
    #[inline]
    pub fn set_centre(&mut self, i: usize, c: u32, x: &Vector<D>) {
        let k = self.slot[i];
        if k != OVERFLOW {
            let rec = &mut self.cells[c as usize];
            for d in 0..D {
                rec.pos[d][usize::from(k)] = x[d];
            }
        }
    }

    /// Checks the records: `cell_of(i)` is the cell body `i` is filed in; every body is in
    /// its cell's used slots or overflow list exactly once, and a slot holds its body's
    /// centre bit for bit.
    pub fn validate(
        &self,
        centres: &[Vector<D>],
        cell_of: impl Fn(usize) -> u32,
    ) -> Result<(), String> {
        let n = centres.len();
        let mut seen = vec![false; n];
        let mut mark = |i: usize, c: usize| -> Result<(), String> {
            if i >= n || seen[i] {
                return Err(format!("cell {c}: body {i} filed twice or unknown"));
            }
            seen[i] = true;
            if cell_of(i) as usize != c {
                return Err(format!("body {i} filed in cell {c}, not its own"));
            }
            Ok(())
        };
        for (c, rec) in self.cells.iter().enumerate() {
            for k in 0..rec.used() {
                let i = rec.body[k] as usize;
                mark(i, c)?;
                if usize::from(self.slot[i]) != k {
                    return Err(format!(
                        "body {i} in slot {k} of cell {c}, recorded elsewhere"
                    ));
                }
                if (0..D).any(|d| rec.pos[d][k].to_bits() != centres[i][d].to_bits()) {
                    return Err(format!("body {i}: its slot does not hold its centre"));
                }
            }
            for k in rec.used()..SLOTS {
                if (0..D).any(|d| rec.pos[d][k] != f64::INFINITY) {
                    return Err(format!("cell {c}: unused slot {k} is not at infinity"));
                }
            }
            let mut over = 0;
            for i in self.overflow(c as u32) {
                let i = i as usize;
                mark(i, c)?;
                if self.slot[i] != OVERFLOW {
                    return Err(format!("body {i} overflows cell {c} but has a slot"));
                }
                over += 1;
            }
            if rec.used() + over != rec.len as usize {
                return Err(format!(
                    "cell {c}: length {} does not count its bodies",
                    rec.len
                ));
            }
            if over > 0 && rec.used() < SLOTS {
                return Err(format!("cell {c} overflows with free slots"));
            }
        }
        match seen.iter().position(|s| !s) {
            Some(i) => Err(format!("body {i} is in no cell")),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Files and moves bodies between a few cells (most overflow) with random centres, and
    /// checks the records against a plain model after every step.
    fn run(cells: usize, n: usize, moves: &[(usize, usize, f64, bool)]) {
        let mut slots = CellSlots::<3>::new(cells, n);
        let mut centres: Vec<Vector<3>> = (0..n)
            .map(|i| Vector([i as f64, 0.5 * i as f64, -(i as f64)]))
            .collect();
        let mut cell_of: Vec<u32> = (0..n).map(|i| (i % cells) as u32).collect();
        for i in 0..n {
            slots.insert(i, cell_of[i], &centres[i]);
        }
        slots.validate(&centres, |i| cell_of[i]).unwrap();
        for &(i, to, y, same) in moves {
            let (i, to) = (i % n, (to % cells) as u32);
            let x = Vector([y, y + 1.0, y * 0.25]);
            centres[i] = x;
            if same || to == cell_of[i] {
                slots.set_centre(i, cell_of[i], &x);
            } else {
                slots.remove(i, cell_of[i], &centres);
                slots.insert(i, to, &x);
                cell_of[i] = to;
            }
            slots.validate(&centres, |i| cell_of[i]).unwrap();
            // Per cell, the bodies filed equal the model's, centres included.
            for c in 0..cells as u32 {
                let rec = slots.cell(c);
                let mut got: Vec<u32> = rec.body[..rec.used()].to_vec();
                got.extend(slots.overflow(c));
                got.sort_unstable();
                let want: Vec<u32> = (0..n as u32)
                    .filter(|&i| cell_of[i as usize] == c)
                    .collect();
                assert_eq!(got, want, "cell {c}");
                for k in 0..SLOTS {
                    let want = if k < rec.used() {
                        centres[rec.body[k] as usize].0
                    } else {
                        [f64::INFINITY; 3]
                    };
                    assert_eq!([rec.pos[0][k], rec.pos[1][k], rec.pos[2][k]], want);
                }
            }
        }
    }

    #[test]
    fn slots_fill_before_overflow_and_refill_from_it() {
        // Three cells, eleven bodies: cells of 4, 4, 3, then moves that empty and refill.
        let moves: Vec<_> = (0..40)
            .map(|k| (k * 7 + 3, k % 3, k as f64 * 0.1, k % 5 == 0))
            .collect();
        run(3, 11, &moves);
        // Everything into one cell, then out again.
        let all: Vec<_> = (0..11).map(|i| (i, 0, 1.0 + i as f64, false)).collect();
        let out: Vec<_> = (0..11).map(|i| (i, 1 + i % 2, 2.0, false)).collect();
        run(3, 11, &[all, out].concat());
    }

    proptest! {
        #[test]
        fn random_moves_keep_every_cell_exact(
            cells in 1usize..6,
            n in 1usize..30,
            moves in proptest::collection::vec(
                (0usize..64, 0usize..8, -5.0f64..5.0, proptest::bool::weighted(0.2)),
                0..120,
            ),
        ) {
            run(cells, n, &moves);
        }
    }
}

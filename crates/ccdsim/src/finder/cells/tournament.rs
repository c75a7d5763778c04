//! The event queue of the `cells` finder as a tournament tree (the complete tree over the
//! bodies of Marin, Risso & Cordero 1993, here with eight keys per leaf and four children per
//! node above): every node holds the smallest key of the bodies below it, inline.
//!
//! The bodies' keys are kept by eights (*octets*, two cache lines each). Above them is an
//! implicit 4-ary tree: node `0` is the root, node `k` has the children `4k + 1 ..= 4k + 4`,
//! and with `m` internal nodes the smallest key of octet `j` is node `m + j`
//! (`m = ⌈(k − 1)/3⌉` for `k` octets, so that the `4m` children hold the `m − 1` internal
//! nodes and the `k` octets; spare nodes hold never). The four children of a node are one
//! 64-byte line. Setting a key rewrites it in its octet, takes the octet's minimum and, if
//! that changed, walks towards the root, recomputing each node from its children; it stops as
//! soon as a node comes out unchanged (its ancestors, which depend on it only through its
//! key, are then still right). The minimum is the root, O(1).
//!
//! Keys are stored whole (time word and tie word, see [`super::key`]) as one 128-bit integer,
//! so a comparison is one wide compare on data in hand: no index to follow, no tie word to
//! look up. A node's key is the smallest of its leaves under [`Key`]'s order, which is the
//! full event order, ties included. Which body owns the root key is read off the key itself
//! ([`Key::holders`]): the body of a crossing or wall event, or either body of a body–body
//! event (both may hold the same key; the lower index is taken then).
//!
//! Why this queue: against the calendar queue it replaced there is nothing to tune (no bucket
//! width that fits one time scale and not another), and an update is a few comparisons per
//! level: most keys are not their octet's smallest and stop there; only the body just popped
//! walks to the top, `1 + ⌈log₄(n/8)⌉` levels of one cache line each. Against the calendar
//! queue it took 3–10 % fewer instructions per event; a calendar front (Paul 2007, as in
//! Smallenburg's code) and a binary heap with lazy invalidation were measured against it and
//! lost (the heap by 3.7–12 % instructions and up to 56 % on the clock at 10⁶ bodies), and
//! binary or 8-ary trees took 3.5–4.4 % more instructions. The whole queue takes about 18.7
//! bytes per body. The measurements, and what else was tried, are in
//! `bench/results/amd-epyc-2vcpu/cells-history.md`.

use super::key::Key;

/// A tournament tree holding one key per body.
#[derive(Clone, Debug)]
pub(super) struct TournamentQueue {
    /// Number of bodies.
    n: usize,
    /// The bodies' keys by eights: body `i` is `octets[i / 8].0[i % 8]`; keys past the last
    /// body are [`Key::NEVER`].
    octets: Vec<Octet>,
    /// Number of internal nodes of the tree over the octets, the root included: the smallest
    /// key of octet `j` is node `m + j`.
    m: usize,
    /// The root, node `0`.
    root: u128,
    /// Nodes `1..=4m` by sibling groups: group `g` holds the children `4g + 1 ..= 4g + 4` of
    /// node `g`. Nodes past the last octet hold [`Key::NEVER`].
    groups: Vec<Group>,
}

/// Eight bodies' keys, in two aligned cache lines (fetched together by the adjacent-line
/// prefetch).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(128))]
struct Octet([u128; 8]);

/// The four children of one node, in one aligned cache line: a node is recomputed from one
/// line, and a walk to the root touches one line per level.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Group([u128; 4]);

/// A key as one integer of the same order: time word above the tie word. A comparison is then
/// a single wide compare, and the minimum of two keys needs no branch.
#[inline(always)]
fn pack(key: Key) -> u128 {
    (u128::from(key.time) << 64) | u128::from(key.tie)
}

/// The key packed by [`pack`].
#[inline(always)]
fn unpack(x: u128) -> Key {
    Key {
        time: (x >> 64) as u64,
        tie: x as u64,
    }
}

/// The smallest of four packed keys.
#[inline(always)]
fn min4(c: &[u128; 4]) -> u128 {
    c[0].min(c[1]).min(c[2].min(c[3]))
}

/// The smallest of eight packed keys.
#[inline(always)]
fn min8(c: &[u128; 8]) -> u128 {
    let (lo, hi) = (
        c[0].min(c[1]).min(c[2].min(c[3])),
        c[4].min(c[5]).min(c[6].min(c[7])),
    );
    lo.min(hi)
}

impl Default for TournamentQueue {
    fn default() -> Self {
        Self::new(0)
    }
}

impl TournamentQueue {
    /// A queue of `n` bodies, all with the key never.
    pub fn new(n: usize) -> Self {
        let k = n.div_ceil(8).max(1);
        // `m` internal nodes have `4m` children, of which `m - 1` are internal: room for
        // `3m + 1` octets.
        let m = (k - 1).div_ceil(3).max(1);
        TournamentQueue {
            n,
            octets: vec![Octet([pack(Key::NEVER); 8]); k],
            m,
            root: pack(Key::NEVER),
            groups: vec![Group([pack(Key::NEVER); 4]); m],
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Octet>() * self.octets.capacity()
            + std::mem::size_of::<Group>() * self.groups.capacity()
    }

    /// Node `k` of the tree over the octets.
    #[inline(always)]
    fn node(&self, k: usize) -> u128 {
        if k == 0 {
            self.root
        } else {
            self.groups[(k - 1) >> 2].0[(k - 1) & 3]
        }
    }

    /// Body `i`'s key.
    #[inline]
    pub fn key(&self, i: usize) -> Key {
        unpack(self.octets[i >> 3].0[i & 7])
    }

    /// Hints that body `i`'s key will be set soon: its octet and the three lowest nodes on
    /// its path to the root (their addresses depend on `i` alone; the levels above hold at
    /// most a 64th of the nodes and stay in the cache).
    #[inline(always)]
    pub fn prefetch_path(&self, i: usize) {
        crate::prefetch::prefetch(&self.octets[i >> 3]);
        let mut g = (self.m + (i >> 3) - 1) >> 2;
        for _ in 0..3 {
            crate::prefetch::prefetch(&self.groups[g]);
            g = g.saturating_sub(1) >> 2;
        }
    }

    /// Sets body `i`'s key to `key` ([`Key::NEVER`] takes it out).
    #[inline(always)]
    pub fn set(&mut self, i: usize, key: Key) {
        debug_assert!(i < self.n);
        let new = pack(key);
        let octet = &mut self.octets[i >> 3].0;
        let slot = &mut octet[i & 7];
        if *slot == new {
            return;
        }
        *slot = new;
        let v = min8(octet);
        self.set_octet(i >> 3, v);
    }

    /// Sets the smallest key of octet `j` to `v` and updates its ancestors.
    #[inline(always)]
    fn set_octet(&mut self, j: usize, mut v: u128) {
        let groups = &mut self.groups[..];
        let leaf = self.m + j - 1;
        // `g` is the node whose children changed.
        let mut g = leaf >> 2;
        let slot = &mut groups[g].0[leaf & 3];
        let old = *slot;
        if v == old {
            // Most keys that change are not their octet's smallest, before or after.
            return;
        }
        *slot = v;
        // When the octet held the smallest key, every node on its path holds it: each one
        // changes (or keeps an equal key of another body) and is rewritten without asking.
        // Other keys mostly lose within a level or two: stop at the first node that keeps
        // its key, since its ancestors depend on it through its key only.
        let to_root = old == self.root;
        v = min4(&groups[g].0);
        while g > 0 {
            let up = g - 1;
            g = up >> 2;
            let siblings = &mut groups[g].0;
            let node = &mut siblings[up & 3];
            if !to_root && *node == v {
                return;
            }
            *node = v;
            v = min4(siblings);
        }
        self.root = v;
    }

    /// A key close behind the smallest, for hints: the smallest key other than the root's
    /// among the siblings of the root's path in the two top levels (keys equal to the
    /// root's are passed over, so the root event's other holder does not count). Those
    /// siblings hold 15/16 of the keys, so this is mostly the second smallest distinct key;
    /// going further down would cost more than the rare miss.
    pub fn runner_up(&self) -> Key {
        let root = self.root;
        let mut best = pack(Key::NEVER);
        let mut k = 0usize;
        for _ in 0..2 {
            let Some(group) = self.groups.get(k) else {
                break;
            };
            let mut down = 0;
            for (x, &v) in group.0.iter().enumerate().rev() {
                let on_path = v == root;
                down = if on_path { x } else { down };
                best = best.min(if on_path { u128::MAX } else { v });
            }
            k = 4 * k + 1 + down;
            if k >= self.m {
                break;
            }
        }
        unpack(best)
    }

    /// The smallest key (the key of [`TournamentQueue::top`]'s body when there is one).
    #[inline]
    pub fn top_key(&self) -> Key {
        unpack(self.root)
    }

    /// The body with the smallest key, or `None` when every key is never.
    #[inline]
    pub fn top(&self) -> Option<usize> {
        let root = unpack(self.root);
        if root.is_never() {
            return None;
        }
        let (a, b) = root.holders();
        if a == b {
            // A crossing or wall event: one holder, no need to look at its key.
            return Some(a);
        }
        Some(if self.key(a) == root { a } else { b })
    }

    /// Checks that every node holds the smallest key below it, and that the keys and nodes
    /// past the last body hold never (for tests).
    pub fn validate(&self) -> Result<(), String> {
        let never = pack(Key::NEVER);
        for i in self.n..8 * self.octets.len() {
            if self.octets[i >> 3].0[i & 7] != never {
                return Err(format!("tournament padding key {i} is not never"));
            }
        }
        for (j, octet) in self.octets.iter().enumerate() {
            if self.node(self.m + j) != min8(&octet.0) {
                return Err(format!("tournament octet {j} is not its keys' minimum"));
            }
        }
        for (g, group) in self.groups.iter().enumerate() {
            if self.node(g) != min4(&group.0) {
                return Err(format!("tournament node {g} is not its children's minimum"));
            }
        }
        for k in self.m + self.octets.len()..=4 * self.m {
            if self.node(k) != never {
                return Err(format!("tournament padding node {k} holds a key"));
            }
        }
        if let Some(i) = self.top() {
            if self.key(i) != unpack(self.root) {
                return Err(format!("the root's key is not body {i}'s"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The body an exhaustive search picks: the smallest key, lowest index among equals.
    fn min_body(keys: &[Key]) -> Option<usize> {
        (0..keys.len())
            .filter(|&j| !keys[j].is_never())
            .min_by_key(|&j| (keys[j], j))
    }

    /// Random sets, some never, many at equal times (ties decided by the tie word: crossings,
    /// then body events, then wall events, each by indices), some shared body–body keys.
    fn random_run(n: usize, rounds: usize, seed: u64) {
        let mut keys = vec![Key::NEVER; n];
        let mut q = TournamentQueue::new(n);
        let mut x = seed;
        let mut rnd = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for round in 0..rounds {
            let i = (rnd() % n as u64) as usize;
            let t = ((rnd() % 8) as f64) * 0.25;
            let j = (rnd() % n as u64) as usize;
            let key = match rnd() % 6 {
                0 => Key::NEVER,
                1 => Key::crossing(t, i),
                2 => Key::wall(t, i, (rnd() % 3) as usize),
                _ if j != i => Key::body(t, i.min(j), i.max(j)),
                _ => Key::crossing(t, i),
            };
            keys[i] = key;
            q.set(i, key);
            // Sometimes the partner holds the same key, like a pair that predicted each other.
            if key.partner(i).is_some() && rnd() % 2 == 0 {
                keys[j] = key;
                q.set(j, key);
            }
            q.validate().unwrap();
            let top = q.top();
            assert_eq!(top, min_body(&keys), "round {round}");
            if let Some(t) = top {
                assert_eq!(q.key(t), keys[t]);
            }
        }
        for i in 0..n {
            assert_eq!(q.key(i), keys[i]);
            q.set(i, Key::NEVER);
            keys[i] = Key::NEVER;
            q.validate().unwrap();
            assert_eq!(q.top(), min_body(&keys));
        }
        assert_eq!(q.top(), None);
    }

    #[test]
    fn pops_in_key_order_for_every_size() {
        for n in 1..=17 {
            random_run(n, 400, 7 + n as u64);
        }
        let keys = [
            Key::NEVER,
            Key::crossing(-1.0, 3),
            Key::crossing(1.0, 2),
            Key::body(1.0, 1, 2),
            Key::wall(1.0, 0, 1),
            Key::body(f64::INFINITY, 1, 2),
        ];
        for k in keys {
            assert_eq!(unpack(pack(k)), k);
            for l in keys {
                assert_eq!(pack(k).cmp(&pack(l)), k.cmp(&l));
            }
        }
        random_run(300, 20_000, 11);
        random_run(1000, 5_000, 13);
        random_run(100, 20_000, 17);
    }

    #[test]
    fn runner_up_is_mostly_the_second_smallest_distinct_key() {
        let n = 5000;
        let mut q = TournamentQueue::new(n);
        let mut keys = vec![Key::NEVER; n];
        assert!(q.runner_up().is_never());
        let mut x = 99u64;
        let mut rnd = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut exact = 0;
        let trials = 2000;
        for _ in 0..trials {
            let i = (rnd() % n as u64) as usize;
            let j = (rnd() % n as u64) as usize;
            let t = (rnd() % 1_000_000) as f64;
            let key = if i == j {
                Key::crossing(t, i)
            } else {
                Key::body(t, i.min(j), i.max(j))
            };
            keys[i] = key;
            q.set(i, key);
            if i != j {
                // The partner holds the same key, as after a pair predicted each other.
                keys[j] = key;
                q.set(j, key);
            }
            let root = q.top_key();
            let second = keys.iter().copied().filter(|&k| k != root).min().unwrap();
            let got = q.runner_up();
            assert!(got != root || got.is_never(), "never the root's key");
            assert!(got >= second, "a key of the queue, not before the second");
            assert!(got.is_never() || keys.contains(&got), "a key of the queue");
            exact += usize::from(got == second);
        }
        // The two top levels hold 15/16 of the keys.
        assert!(exact * 100 >= trials * 85, "{exact} of {trials}");
    }

    #[test]
    fn ties_at_equal_times_follow_the_event_order() {
        let mut q = TournamentQueue::new(6);
        q.set(5, Key::wall(1.0, 5, 0));
        assert_eq!(q.top(), Some(5));
        q.set(4, Key::body(1.0, 3, 4));
        assert_eq!(q.top(), Some(4));
        q.set(3, Key::body(1.0, 3, 4));
        assert_eq!(q.top(), Some(3), "equal keys: the lower index");
        q.set(2, Key::body(1.0, 1, 2));
        assert_eq!(q.top(), Some(2));
        q.set(1, Key::crossing(1.0, 1));
        assert_eq!(
            q.top(),
            Some(1),
            "a crossing goes before events at the same time"
        );
        q.set(0, Key::crossing(1.0, 0));
        assert_eq!(q.top(), Some(0));
        q.set(0, Key::NEVER);
        q.set(1, Key::NEVER);
        assert_eq!(q.top(), Some(2));
        q.set(2, Key::body(f64::INFINITY, 1, 2));
        assert_eq!(q.top(), Some(3));
        for i in 3..6 {
            q.set(i, Key::NEVER);
        }
        assert_eq!(q.top(), Some(2), "an infinite time is still before never");
        q.validate().unwrap();
        q.set(2, Key::NEVER);
        assert_eq!(q.top(), None);
        assert_eq!(TournamentQueue::new(0).top(), None);
    }
}

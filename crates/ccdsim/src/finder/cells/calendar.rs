//! The event queue of the `cells` finder as a calendar queue (R. Brown 1988; the layout EDMD
//! codes use): one entry per body, bucketed by time.
//!
//! Time is cut into buckets of width `Δ`; bucket `k` holds the bodies whose key time is in
//! `[kΔ, (k+1)Δ)`. Buckets after the current one are doubly linked lists in a ring of `B`
//! heads, bucket `k` in slot `k mod B` (a slot may also hold keys of later "years",
//! `k + B`, `k + 2B`, …, which stay there when the slot is emptied); keys in or before the
//! current bucket are in a small indexed binary heap (the *near* heap), the only place where
//! keys are compared. Setting a key is O(1) (unlink, link) unless it lands in the near heap;
//! taking the minimum moves to the next non-empty bucket and heapifies it. With `Δ` tuned so
//! that a bucket holds a few keys, both are O(1) on average and touch a handful of cache lines
//! where a heap of a million bodies touches twenty. `Δ` is retuned from the observed time per
//! pop whenever it is off by more than a factor of four (a rebuild in O(n)).
//!
//! Keys compare by their time word, then by the tie word, which the owner supplies (see
//! [`super::queue`]); bucketing uses the time alone, so the order is exactly the keys'.

use super::key::Key;

const NIL: u32 = u32::MAX;
const IDLE: u8 = 0;
const NEAR: u8 = 1;
const BUCKET: u8 = 2;

/// Keys per bucket aimed at.
const PER_BUCKET: f64 = 2.0;

/// A calendar queue holding one key per body.
#[derive(Clone, Debug, Default)]
pub(super) struct CalendarQueue {
    /// Key time word of each body.
    time: Vec<u64>,
    /// Where each body is: `IDLE` (key never), `NEAR` or `BUCKET`.
    state: Vec<u8>,
    /// In a list: the previous body (`NIL` for the first); in the near heap: its slot.
    prev: Vec<u32>,
    /// In a list: the next body (`NIL` for the last).
    next: Vec<u32>,
    /// Heads of the bucket lists, `B` of them (a power of two).
    heads: Vec<u32>,
    /// Bodies in bucket lists.
    bucketed: usize,
    /// The near heap: bodies whose keys are in or before the current bucket.
    near: Vec<u32>,
    /// Index of the current bucket.
    cur: i64,
    /// Buckets advanced over since a key was found.
    empty_run: usize,
    /// Bucket width, seconds.
    width: f64,
    /// Pops since the last tuning, and the time of the first of them.
    pops: u64,
    tune_from: f64,
    last_top: f64,
}

impl CalendarQueue {
    /// A queue of `n` bodies, all idle (key never), with bucket width `width` seconds and
    /// current time `now`.
    pub fn new(n: usize, width: f64, now: f64) -> Self {
        let b = n.max(16).next_power_of_two();
        let width = if width.is_finite() && width > 0.0 {
            width
        } else {
            1.0
        };
        CalendarQueue {
            time: vec![Key::NEVER.time; n],
            state: vec![IDLE; n],
            prev: vec![NIL; n],
            next: vec![NIL; n],
            heads: vec![NIL; b],
            bucketed: 0,
            near: Vec::new(),
            cur: bucket_of(now, width),
            empty_run: 0,
            width,
            pops: 0,
            tune_from: now,
            last_top: now,
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        8 * self.time.capacity()
            + self.state.capacity()
            + 4 * (self.prev.capacity()
                + self.next.capacity()
                + self.heads.capacity()
                + self.near.capacity())
    }

    /// The time word of body `i`'s key.
    #[inline]
    pub fn time_of(&self, i: usize) -> u64 {
        self.time[i]
    }

    #[inline]
    fn mask(&self) -> i64 {
        self.heads.len() as i64 - 1
    }

    /// Sets body `i`'s key to `key`; `tie(j)` gives the tie word of every other body's key.
    #[inline]
    pub fn set(&mut self, i: usize, key: Key, tie: impl Fn(u32) -> u64) {
        self.remove(i, &tie);
        self.time[i] = key.time;
        if key.time == Key::NEVER.time {
            self.state[i] = IDLE;
            return;
        }
        self.file(i, key.tie, &tie);
    }

    /// Files body `i`, whose time word is set, where its key belongs.
    #[inline]
    fn file(&mut self, i: usize, tie_i: u64, tie: &impl Fn(u32) -> u64) {
        let k = bucket_of(
            Key {
                time: self.time[i],
                tie: 0,
            }
            .seconds(),
            self.width,
        );
        if k <= self.cur {
            self.push_near(i, tie_i, tie);
        } else {
            self.link_bucket(i, k);
        }
    }

    /// The body with the smallest key, or `None` when every key is never.
    #[inline]
    pub fn top(&mut self, tie: impl Fn(u32) -> u64) -> Option<usize> {
        loop {
            if let Some(&i) = self.near.first() {
                let t = Key {
                    time: self.time[i as usize],
                    tie: 0,
                }
                .seconds();
                if t != self.last_top {
                    self.last_top = t;
                    self.pops += 1;
                    if self.pops >= self.time.len() as u64 + 64 {
                        self.retune(&tie);
                        continue;
                    }
                }
                return Some(i as usize);
            }
            if self.bucketed == 0 {
                return None;
            }
            self.advance(&tie);
        }
    }

    /// Moves to the next bucket and files its keys in the near heap; after a whole year of
    /// empty buckets, jumps to the earliest key instead.
    fn advance(&mut self, tie: &impl Fn(u32) -> u64) {
        self.empty_run += 1;
        if self.empty_run > self.heads.len() {
            let first = (0..self.time.len())
                .filter(|&i| self.state[i] == BUCKET)
                .map(|i| self.bucket(i))
                .min()
                .expect("bucketed keys exist");
            self.cur = first - 1;
            self.empty_run = 0;
        }
        self.cur += 1;
        let b = (self.cur & self.mask()) as usize;
        let mut j = self.heads[b];
        while j != NIL {
            let i = j as usize;
            j = self.next[i];
            if self.bucket(i) == self.cur {
                self.unlink(i);
                self.push_near(i, tie(i as u32), tie);
                self.empty_run = 0;
            }
        }
    }

    /// The bucket index of body `i`'s key.
    #[inline]
    fn bucket(&self, i: usize) -> i64 {
        bucket_of(
            Key {
                time: self.time[i],
                tie: 0,
            }
            .seconds(),
            self.width,
        )
    }

    fn link_bucket(&mut self, i: usize, k: i64) {
        let b = (k & self.mask()) as usize;
        let head = self.heads[b];
        self.prev[i] = NIL;
        self.next[i] = head;
        if head != NIL {
            self.prev[head as usize] = i as u32;
        }
        self.heads[b] = i as u32;
        self.state[i] = BUCKET;
        self.bucketed += 1;
    }

    fn remove(&mut self, i: usize, tie: &impl Fn(u32) -> u64) {
        match self.state[i] {
            NEAR => self.remove_near(i, tie),
            BUCKET => self.unlink(i),
            _ => {}
        }
        self.state[i] = IDLE;
    }

    /// Takes body `i` out of its bucket list.
    fn unlink(&mut self, i: usize) {
        let (p, n) = (self.prev[i], self.next[i]);
        if n != NIL {
            self.prev[n as usize] = p;
        }
        if p != NIL {
            self.next[p as usize] = n;
        } else {
            let b = (self.bucket(i) & self.mask()) as usize;
            self.heads[b] = n;
        }
        self.bucketed -= 1;
        self.state[i] = IDLE;
    }

    #[inline]
    fn less(&self, a: u32, ta: u64, b: u32, tie: &impl Fn(u32) -> u64) -> bool {
        let (x, y) = (self.time[a as usize], self.time[b as usize]);
        x < y || (x == y && ta < tie(b))
    }

    fn push_near(&mut self, i: usize, tie_i: u64, tie: &impl Fn(u32) -> u64) {
        self.state[i] = NEAR;
        self.near.push(i as u32);
        let s = self.near.len() - 1;
        self.sift_up(s, tie_i, tie);
    }

    fn remove_near(&mut self, i: usize, tie: &impl Fn(u32) -> u64) {
        let s = self.prev[i] as usize;
        let last = self.near.pop().expect("near heap holds the body");
        if last as usize != i {
            self.near[s] = last;
            self.prev[last as usize] = s as u32;
            self.sift_up(s, tie(last), tie);
            let s = self.prev[last as usize] as usize;
            self.sift_down(s, tie);
        }
    }

    fn sift_up(&mut self, mut s: usize, tie_i: u64, tie: &impl Fn(u32) -> u64) {
        let i = self.near[s];
        while s > 0 {
            let p = (s - 1) / 2;
            let pi = self.near[p];
            if !self.less(i, tie_i, pi, tie) {
                break;
            }
            self.near[s] = pi;
            self.prev[pi as usize] = s as u32;
            s = p;
        }
        self.near[s] = i;
        self.prev[i as usize] = s as u32;
    }

    fn sift_down(&mut self, mut s: usize, tie: &impl Fn(u32) -> u64) {
        let i = self.near[s];
        let n = self.near.len();
        loop {
            let l = 2 * s + 1;
            if l >= n {
                break;
            }
            let mut c = l;
            if l + 1 < n {
                let r = l + 1;
                let (nr, nl) = (self.near[r], self.near[l]);
                if self.less(nr, tie(nr), nl, tie) {
                    c = r;
                }
            }
            let ci = self.near[c];
            if !self.less(ci, tie(ci), i, tie) {
                break;
            }
            // ci < i: move it up (ties go to the smaller key, so equality keeps i).
            self.near[s] = ci;
            self.prev[ci as usize] = s as u32;
            s = c;
        }
        self.near[s] = i;
        self.prev[i as usize] = s as u32;
    }

    /// Rebuilds the buckets with a width fitted to the time per pop observed, if the current
    /// one is off by more than a factor of four.
    fn retune(&mut self, tie: &impl Fn(u32) -> u64) {
        let span = self.last_top - self.tune_from;
        let ideal = PER_BUCKET * span / self.pops as f64;
        self.pops = 0;
        self.tune_from = self.last_top;
        if ideal.is_finite() && ideal > 0.0 && (ideal / self.width).ln().abs() > 4f64.ln() {
            self.rebuild(ideal, self.last_top, tie);
        }
    }

    /// Sets a bucket width fitted to the keys held, from now on: half of them fall due within
    /// the median key time, so a key is due every `(median − now) / (n/2)` seconds.
    pub fn fit(&mut self, now: f64, tie: impl Fn(u32) -> u64) {
        let mut times: Vec<f64> = (0..self.time.len())
            .filter(|&i| self.state[i] != IDLE)
            .map(|i| {
                Key {
                    time: self.time[i],
                    tie: 0,
                }
                .seconds()
                    - now
            })
            .filter(|t| t.is_finite())
            .collect();
        if times.len() < 2 {
            return;
        }
        let m = times.len() / 2;
        let median = *times.select_nth_unstable_by(m, f64::total_cmp).1;
        let width = PER_BUCKET * median / m as f64;
        if width.is_finite() && width > 0.0 {
            self.rebuild(width, now, &tie);
        }
        self.tune_from = now;
        self.last_top = now;
        self.pops = 0;
    }

    fn rebuild(&mut self, width: f64, now: f64, tie: &impl Fn(u32) -> u64) {
        let n = self.time.len();
        let filed: Vec<u32> = (0..n as u32)
            .filter(|&i| self.state[i as usize] != IDLE)
            .collect();
        for &i in &filed {
            self.state[i as usize] = IDLE;
        }
        self.heads.iter_mut().for_each(|h| *h = NIL);
        self.near.clear();
        self.bucketed = 0;
        self.empty_run = 0;
        self.width = width;
        self.cur = bucket_of(now, width);
        for i in filed {
            self.file(i as usize, tie(i), tie);
        }
    }

    /// Checks the near heap order, the slots and the lists (for tests).
    pub fn validate(&self, tie: impl Fn(u32) -> u64) -> Result<(), String> {
        for s in 1..self.near.len() {
            let (p, c) = (self.near[(s - 1) / 2], self.near[s]);
            if (self.time[c as usize], tie(c)) < (self.time[p as usize], tie(p)) {
                return Err(format!("near heap order broken at slot {s}"));
            }
        }
        for (s, &i) in self.near.iter().enumerate() {
            if self.prev[i as usize] as usize != s || self.state[i as usize] != NEAR {
                return Err(format!("near slot of body {i} is wrong"));
            }
        }
        let mut count = 0;
        for (b, &h) in self.heads.iter().enumerate() {
            let mut j = h;
            let mut p = NIL;
            while j != NIL {
                let i = j as usize;
                let k = self.bucket(i);
                if self.state[i] != BUCKET || (k & self.mask()) as usize != b || k <= self.cur {
                    return Err(format!("body {i} misfiled in bucket {b}"));
                }
                if self.prev[i] != p {
                    return Err(format!("broken link before body {i}"));
                }
                count += 1;
                p = j;
                j = self.next[i];
            }
        }
        if count != self.bucketed {
            return Err("bucket count is wrong".into());
        }
        Ok(())
    }

    /// The keys of the near heap's top and of every filed body are at least the current
    /// bucket's start, except those in the near heap; for tests: the minimum over all keys.
    #[cfg(test)]
    pub fn min_body(&self, tie: impl Fn(u32) -> u64) -> Option<usize> {
        (0..self.time.len())
            .filter(|&i| self.state[i] != IDLE)
            .min_by_key(|&i| (self.time[i], tie(i as u32)))
    }
}

/// Index of the bucket of width `width` holding time `t`: `⌊t / width⌋`, saturating.
#[inline]
fn bucket_of(t: f64, width: f64) -> i64 {
    // `f64::floor` is a library call on the baseline x86-64 target; truncation and a
    // correction for negative quotients is the same floor, inline.
    let q = t / width;
    let k = q as i64;
    if (k as f64) > q {
        k.saturating_sub(1)
    } else {
        k
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_floor() {
        for (t, w, k) in [
            (0.0, 1.0, 0),
            (0.99, 1.0, 0),
            (1.0, 1.0, 1),
            (-0.5, 1.0, -1),
            (-1.0, 1.0, -1),
            (-1.5, 0.5, -3),
            (1e300, 1e-300, i64::MAX),
            (f64::INFINITY, 1.0, i64::MAX),
            (f64::NEG_INFINITY, 1.0, i64::MIN),
        ] {
            assert_eq!(bucket_of(t, w), k, "{t} / {w}");
        }
    }

    #[test]
    fn pops_in_key_order() {
        // Many equal times (ties decided by the tie word), far keys, retuning.
        let n = 300;
        let mut keys = vec![Key::NEVER; n];
        let mut q = CalendarQueue::new(n, 0.01, 0.0);
        let mut x: u64 = 7;
        let mut rnd = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut now = 0.0f64;
        for round in 0..20_000 {
            let i = (rnd() % n as u64) as usize;
            let t = now + ((rnd() % 1000) as f64) * if round % 7 == 0 { 1.0 } else { 0.001 };
            let t = (t * 64.0).round() / 64.0;
            keys[i] = if rnd() % 11 == 0 {
                Key::NEVER
            } else {
                Key::body(t.max(now), i, n + (rnd() % 3) as usize)
            };
            let snap = keys.clone();
            q.set(i, keys[i], |j| snap[j as usize].tie);
            let snap = keys.clone();
            let top = q.top(|j| snap[j as usize].tie);
            q.validate(|j| snap[j as usize].tie).unwrap();
            let want = (0..n)
                .filter(|&j| !keys[j].is_never())
                .min_by_key(|&j| keys[j]);
            assert_eq!(top.map(|j| keys[j]), want.map(|j| keys[j]), "round {round}");
            if let Some(j) = top {
                now = keys[j].seconds();
            }
            assert_eq!(
                q.min_body(|j| snap[j as usize].tie).map(|j| keys[j]),
                want.map(|j| keys[j])
            );
        }
    }
}

//! The fixed times at which a run is sampled.

/// The times `start + k · every` for `k = 0, 1, …` up to and including `until`, seconds.
///
/// Each time is computed from `k` directly, so no rounding accumulates over many frames.
///
/// ```
/// use ccdsim::trajectory::SampleTimes;
/// let t: Vec<f64> = SampleTimes::new(1.0, 0.5, 2.2).unwrap().collect();
/// assert_eq!(t, [1.0, 1.5, 2.0]);
/// ```
#[derive(Clone, Debug)]
pub struct SampleTimes {
    start: f64,
    every: f64,
    until: f64,
    k: u64,
}

impl SampleTimes {
    /// The sample times from `start` every `every` seconds up to `until`; an error names the
    /// bad argument (a step that is not finite and positive, or a span that is not finite).
    pub fn new(start: f64, every: f64, until: f64) -> Result<Self, String> {
        if !(every.is_finite() && every > 0.0) {
            return Err(format!(
                "the frame interval must be a positive number of seconds, not {every}"
            ));
        }
        if !start.is_finite() || !until.is_finite() {
            return Err("the sampled span must have finite ends".to_string());
        }
        if start + every == start {
            return Err(format!(
                "a frame interval of {every} s does not move time on from {start} s"
            ));
        }
        Ok(SampleTimes {
            start,
            every,
            until,
            k: 0,
        })
    }

    /// Number of sample times (frames) in all.
    #[must_use]
    pub fn frame_count(&self) -> u64 {
        if self.until < self.start {
            return 0;
        }
        let mut n = ((self.until - self.start) / self.every).floor() as u64 + 1;
        // The division rounds: settle the last one on the times themselves.
        while n > 0 && self.start + (n - 1) as f64 * self.every > self.until {
            n -= 1;
        }
        while self.start + n as f64 * self.every <= self.until {
            n += 1;
        }
        n
    }
}

impl Iterator for SampleTimes {
    type Item = f64;

    fn next(&mut self) -> Option<f64> {
        let t = self.start + self.k as f64 * self.every;
        if t > self.until {
            return None;
        }
        self.k += 1;
        Some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_matches_the_iterator() {
        for (start, every, until) in [
            (0.0, 0.1, 1.0),
            (0.0, 0.1, 0.3),
            (1e3, 1e-3, 1e3 + 1.0),
            (0.0, 1.0, -1.0),
            (0.0, 0.7, 7.0),
        ] {
            let s = SampleTimes::new(start, every, until).unwrap();
            assert_eq!(
                s.frame_count(),
                s.clone().count_by_iterating(),
                "{start} {every} {until}"
            );
        }
    }

    #[test]
    fn bad_intervals_are_refused() {
        assert!(SampleTimes::new(0.0, 0.0, 1.0).is_err());
        assert!(SampleTimes::new(0.0, -1.0, 1.0).is_err());
        assert!(SampleTimes::new(0.0, f64::NAN, 1.0).is_err());
        assert!(SampleTimes::new(1e17, 1.0, 2e17).is_err());
    }

    impl SampleTimes {
        fn count_by_iterating(self) -> u64 {
            Iterator::count(self) as u64
        }
    }
}

//! A histogram of where the bodies are: bins along one axis that count the bodies whose
//! centres lie in them (a scene's `histogram`, counted by `ccdsim run` at the end of a run, a
//! Galton board's bins).

use serde::{Deserialize, Serialize};

/// Bins along axis `axis`: bin `k` holds the free (not kinematic) bodies whose centre
/// coordinate `x` along the axis has `edges[k] ≤ x < edges[k + 1]`, metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Histogram {
    /// The axis the bins divide (0 is x).
    #[serde(default)]
    pub axis: usize,
    /// The bins' edges, increasing, at least two, metres.
    pub edges: Vec<f64>,
}

/// What a [`Histogram`]'s bins hold.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct HistogramCounts {
    /// Bodies in each bin.
    pub counts: Vec<u64>,
    /// Free bodies outside every bin (below the first edge or at or above the last).
    pub outside: u64,
}

impl Histogram {
    /// Why these bins cannot serve a `dim`-dimensional scene, if they cannot: the axis is
    /// not one of its axes, or the edges are not finite and strictly increasing (two at
    /// least).
    pub fn check(&self, dim: usize) -> Result<(), String> {
        if self.axis >= dim {
            return Err(format!(
                "axis {} is not an axis of a {dim}D scene (0 to {})",
                self.axis,
                dim - 1
            ));
        }
        if self.edges.len() < 2 {
            return Err("needs at least two edges (one bin)".into());
        }
        if self.edges.iter().any(|e| !e.is_finite()) {
            return Err("edges must be finite".into());
        }
        if let Some(k) = self.edges.windows(2).position(|w| w[0] >= w[1]) {
            return Err(format!(
                "edges must increase: edges[{}] = {} is not below edges[{}] = {}",
                k,
                self.edges[k],
                k + 1,
                self.edges[k + 1]
            ));
        }
        Ok(())
    }

    /// The bin holding coordinate `x`, if one does.
    #[must_use]
    pub fn bin_of(&self, x: f64) -> Option<usize> {
        let k = self.edges.partition_point(|&e| e <= x);
        (k >= 1 && k < self.edges.len()).then(|| k - 1)
    }

    /// What the bins hold of bodies whose coordinates along the axis are `coords`.
    #[must_use]
    pub fn count(&self, coords: impl IntoIterator<Item = f64>) -> HistogramCounts {
        let mut out = HistogramCounts {
            counts: vec![0; self.edges.len() - 1],
            outside: 0,
        };
        for x in coords {
            match self.bin_of(x) {
                Some(k) => out.counts[k] += 1,
                None => out.outside += 1,
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_coordinate_falls_in_the_bin_whose_edges_hold_it() {
        let h = Histogram {
            axis: 0,
            edges: vec![0.0, 1.0, 3.0],
        };
        assert_eq!(h.bin_of(-0.1), None);
        assert_eq!(h.bin_of(0.0), Some(0));
        assert_eq!(h.bin_of(0.999), Some(0));
        assert_eq!(h.bin_of(1.0), Some(1));
        assert_eq!(h.bin_of(3.0), None);
    }

    #[test]
    fn bad_bins_are_refused_with_the_reason() {
        let bins = |axis, edges: &[f64]| Histogram {
            axis,
            edges: edges.to_vec(),
        };
        assert!(bins(2, &[0.0, 1.0])
            .check(2)
            .unwrap_err()
            .contains("axis 2"));
        assert!(bins(0, &[0.0]).check(2).unwrap_err().contains("two edges"));
        assert!(bins(0, &[0.0, f64::NAN])
            .check(2)
            .unwrap_err()
            .contains("finite"));
        assert!(bins(0, &[0.0, 1.0, 1.0])
            .check(3)
            .unwrap_err()
            .contains("increase"));
        assert!(bins(1, &[0.0, 1.0]).check(2).is_ok());
    }
}

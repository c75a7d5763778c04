//! Least-squares straight lines, shared by the physics checks.

/// A least-squares line `y = slope·x + intercept` through points, with its R².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFit {
    /// Slope.
    pub slope: f64,
    /// Value at `x = 0`.
    pub intercept: f64,
    /// Coefficient of determination (1 when every `y` is the same).
    pub r2: f64,
}

/// The least-squares line through `points` `(x, y)` (at least two distinct `x`).
#[must_use]
pub fn line_fit(points: &[(f64, f64)]) -> LineFit {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
    let slope = sxy / sxx;
    let r2 = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        1.0
    };
    LineFit {
        slope,
        intercept: my - slope * mx,
        r2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_through_exact_points() {
        let f = line_fit(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]);
        assert_eq!((f.slope, f.intercept, f.r2), (2.0, 1.0, 1.0));
    }
}

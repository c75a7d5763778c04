//! Time correlations over a trajectory, averaged over every time origin.
//!
//! For frames `0 … F−1` at equal intervals and a lag of `m` frames,
//!
//! * MSD(m) = ⟨|r_i(k+m) − r_i(k)|²⟩ and
//! * VACF(m) = ⟨v_i(k+m) · v_i(k)⟩,
//!
//! where ⟨·⟩ averages over the `N` bodies and the `F − m` origins `k` (the "window" mode of
//! freud's `msd.MSD`). Positions must be unwrapped ([`Frame::unwrapped_positions`]). Both are
//! computed by FFT: per body and axis, the autocorrelation `Σ_k x(k) x(k+m)` is the inverse
//! transform of `|X|²` of the sequence padded to `2F` (no wrap-around), and the MSD follows as
//! `S1(m) − 2 S2(m)` with `S1` from running sums of `x²` (Calandrini et al., nMoldyn).
//!
//! [`Frame::unwrapped_positions`]: crate::trajectory::Frame::unwrapped_positions

use crate::geom::Vector;
use rustfft::num_complex::Complex;
use rustfft::FftPlanner;

/// Mean-square displacement (m²) for lags `0 … F−1` frames; `frames[k][i]` is body `i`'s
/// unwrapped position in frame `k`. Every frame must hold the same bodies.
///
/// ```
/// use ccdsim::observables::mean_square_displacement;
/// use ccdsim::Vector;
/// // One body moving at 2 m per frame: MSD(m) = 4 m².
/// let frames: Vec<Vec<Vector<1>>> = (0..5).map(|k| vec![Vector([2.0 * k as f64])]).collect();
/// let msd = mean_square_displacement(&frames).unwrap();
/// for (m, x) in msd.iter().enumerate() {
///     assert!((x - 4.0 * (m * m) as f64).abs() < 1e-9);
/// }
/// ```
pub fn mean_square_displacement<const D: usize>(
    frames: &[Vec<Vector<D>>],
) -> Result<Vec<f64>, String> {
    // Displacements are differences: taken relative to frame 0, since sums of squares of
    // coordinates far from the origin would cancel catastrophically.
    let mut total = sum_over_series(frames, true, |x, s2, total| {
        let f = x.len();
        // S1(m) = Σ_{k=0}^{F−m−1} x(k)² + x(k+m)², by shrinking the sum from both ends.
        let mut q: f64 = 2.0 * x.iter().map(|v| v * v).sum::<f64>();
        for m in 0..f {
            if m > 0 {
                q -= x[m - 1] * x[m - 1] + x[f - m] * x[f - m];
            }
            total[m] += q - 2.0 * s2[m];
        }
    })?;
    // No displacement at lag 0, by definition; the FFT leaves a rounding there.
    total[0] = 0.0;
    Ok(total)
}

/// Velocity autocorrelation (m²/s²) for lags `0 … F−1` frames; `frames[k][i]` is body `i`'s
/// velocity in frame `k`.
pub fn velocity_autocorrelation<const D: usize>(
    frames: &[Vec<Vector<D>>],
) -> Result<Vec<f64>, String> {
    sum_over_series(frames, false, |_, s2, total| {
        for (t, c) in total.iter_mut().zip(s2) {
            *t += c;
        }
    })
}

/// For every body and axis, the series `x(k)` (relative to frame 0 if `relative`) and its
/// autocorrelation `S2`, handed to `add(x, S2, totals)`; then each lag's total divided by its
/// `N (F − m)` terms.
fn sum_over_series<const D: usize>(
    frames: &[Vec<Vector<D>>],
    relative: bool,
    mut add: impl FnMut(&[f64], &[f64], &mut [f64]),
) -> Result<Vec<f64>, String> {
    let (f, n) = shape(frames)?;
    let mut total = vec![0.0; f];
    let mut corr = Autocorrelation::new(f);
    let mut x = vec![0.0; f];
    for i in 0..n {
        for d in 0..D {
            let origin = if relative { frames[0][i][d] } else { 0.0 };
            for (k, frame) in frames.iter().enumerate() {
                x[k] = frame[i][d] - origin;
            }
            add(&x, corr.of(&x), &mut total);
        }
    }
    for (m, t) in total.iter_mut().enumerate() {
        *t /= (n * (f - m)) as f64;
    }
    Ok(total)
}

/// Frames and bodies, checked: at least one frame, the same number of bodies in each.
fn shape<const D: usize>(frames: &[Vec<Vector<D>>]) -> Result<(usize, usize), String> {
    let Some(first) = frames.first() else {
        return Err("no frames".to_string());
    };
    let n = first.len();
    if n == 0 {
        return Err("no bodies".to_string());
    }
    if let Some(k) = frames.iter().position(|fr| fr.len() != n) {
        return Err(format!(
            "frame {k} has {} bodies, frame 0 has {n}",
            frames[k].len()
        ));
    }
    Ok((frames.len(), n))
}

/// `Σ_{k=0}^{F−m−1} x(k) x(k+m)` for every lag `m`, by FFT; plans and buffers reused.
struct Autocorrelation {
    f: usize,
    forward: std::sync::Arc<dyn rustfft::Fft<f64>>,
    inverse: std::sync::Arc<dyn rustfft::Fft<f64>>,
    buffer: Vec<Complex<f64>>,
    out: Vec<f64>,
}

impl Autocorrelation {
    fn new(f: usize) -> Self {
        let len = (2 * f).next_power_of_two();
        let mut planner = FftPlanner::new();
        Autocorrelation {
            f,
            forward: planner.plan_fft_forward(len),
            inverse: planner.plan_fft_inverse(len),
            buffer: vec![Complex::new(0.0, 0.0); len],
            out: vec![0.0; f],
        }
    }

    fn of(&mut self, x: &[f64]) -> &[f64] {
        let len = self.buffer.len();
        for (b, v) in self
            .buffer
            .iter_mut()
            .zip(x.iter().chain(std::iter::repeat(&0.0)))
        {
            *b = Complex::new(*v, 0.0);
        }
        self.forward.process(&mut self.buffer);
        for b in &mut self.buffer {
            *b = Complex::new(b.norm_sqr(), 0.0);
        }
        self.inverse.process(&mut self.buffer);
        for m in 0..self.f {
            self.out[m] = self.buffer[m].re / len as f64;
        }
        &self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definitions, summed directly.
    fn direct<const D: usize>(frames: &[Vec<Vector<D>>], msd: bool) -> Vec<f64> {
        let (f, n) = (frames.len(), frames[0].len());
        (0..f)
            .map(|m| {
                let mut s = 0.0;
                for (early, late) in frames.iter().zip(&frames[m..]) {
                    for (&a, &b) in early.iter().zip(late) {
                        s += if msd { (b - a).norm_sq() } else { a.dot(b) };
                    }
                }
                s / (n * (f - m)) as f64
            })
            .collect()
    }

    fn random_walk(f: usize, n: usize) -> Vec<Vec<Vector<3>>> {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut p = vec![Vector([0.0; 3]); n];
        (0..f)
            .map(|_| {
                for q in &mut p {
                    let step = Vector([next(), next(), next()]);
                    *q += step;
                }
                p.clone()
            })
            .collect()
    }

    #[test]
    fn fft_sums_match_the_definitions() {
        for f in [1, 2, 7, 64, 100] {
            let frames = random_walk(f, 5);
            for (fast, slow) in [
                (
                    mean_square_displacement(&frames).unwrap(),
                    direct(&frames, true),
                ),
                (
                    velocity_autocorrelation(&frames).unwrap(),
                    direct(&frames, false),
                ),
            ] {
                for (a, b) in fast.iter().zip(&slow) {
                    assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{f}: {a} vs {b}");
                }
            }
        }
    }

    #[test]
    fn ragged_or_empty_input_is_refused() {
        assert!(mean_square_displacement::<2>(&[]).is_err());
        assert!(mean_square_displacement(&[vec![Vector([0.0, 0.0])], vec![]]).is_err());
        assert!(velocity_autocorrelation::<2>(&[vec![]]).is_err());
    }
}

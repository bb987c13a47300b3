//! Scalar metrics of one run, from its samples on a uniform time grid.
//!
//! * `max |theta(z_k, t)|` and the RMS of `theta(z_k, t)` over the samples;
//! * the dominant frequency of `theta(z_k, t)`: Hann window (`0.5 - 0.5 cos(2 pi j/(n-1))`),
//!   window-weighted mean removed, zero-padded by [`PAD`] to a power of two, real FFT, the
//!   strongest interior local maximum of `|X|`, refined by a parabola through the logarithms
//!   of the three bins around it (the algorithm of `drillstring.analysis.dominant_frequencies`);
//! * modal energy exchange: the quadratic energy of mode `i`,
//!   `E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`, its share `E_i / sum_j E_j` at every sample
//!   (samples whose total is not positive are skipped) and the largest share each mode
//!   reached. With a negative `K_i` (the rigid mode under rotation, or a mode above its
//!   critical speed) `E_i` may be negative and the other shares may exceed 1;
//! * the energy drift `max |H(t) - H(0)| / |H(0)|` with `H` = [`ModalSystem::energy`]
//!   (0 when `H(0) = 0`); with damping the error of the energy balance,
//!   `max |H(t) + D(t) - H(0)| / |H(0)|` with `D` the dissipated energy of the solve;
//! * the number of linearly unstable modes at the equilibrium, `#{K_i < 0}`.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{RealFftPlanner, RealToComplex};

use crate::modal::ModalSystem;

/// Zero-padding factor of the FFT (`drillstring.analysis.DEFAULT_PAD`).
pub const PAD: usize = 8;

/// The metrics of one successful run.
#[derive(Debug, Clone, PartialEq)]
pub struct Metrics {
    pub max_theta: f64,
    pub rms_theta: f64,
    /// Hz; NaN when the record has no spectral peak (e.g. a run at rest).
    pub dominant_frequency_hz: f64,
    pub energy_drift: f64,
    /// Largest share of the quadratic energy each mode reached (NaN if no sample had a
    /// positive total).
    pub max_share: Vec<f64>,
}

/// The Hann window and FFT plan for records of `n` samples (shared by all threads).
pub struct FrequencyEstimator {
    n: usize,
    nfft: usize,
    window: Vec<f64>,
    window_sum: f64,
    fft: Arc<dyn RealToComplex<f64>>,
}

/// Per-thread FFT buffers of a [`FrequencyEstimator`].
pub struct FftBuffers {
    input: Vec<f64>,
    output: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl FrequencyEstimator {
    /// For records of `n >= 1` samples.
    pub fn new(n: usize) -> Self {
        let nfft = (n.max(1) * PAD).next_power_of_two();
        let window: Vec<f64> = if n == 1 {
            vec![1.0]
        } else {
            let denom = (n - 1) as f64;
            (0..n).map(|j| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * j as f64 / denom).cos()).collect()
        };
        let window_sum = window.iter().sum();
        let fft = RealFftPlanner::<f64>::new().plan_fft_forward(nfft);
        FrequencyEstimator { n, nfft, window, window_sum, fft }
    }

    pub fn buffers(&self) -> FftBuffers {
        FftBuffers {
            input: self.fft.make_input_vec(),
            output: self.fft.make_output_vec(),
            scratch: self.fft.make_scratch_vec(),
        }
    }

    /// The dominant frequency (Hz) of `x`, sampled every `dt` seconds; `x` must have the
    /// `n` samples this estimator was made for (else NaN). NaN for fewer than 4 samples, a
    /// non-finite record or a spectrum without an interior peak (a constant record).
    pub fn dominant_frequency(&self, x: &[f64], dt: f64, buf: &mut FftBuffers) -> f64 {
        let n = self.n;
        if x.len() != n || n < 4 || !x.iter().all(|v| v.is_finite()) || dt.is_nan() || dt <= 0.0 {
            return f64::NAN;
        }
        let mean = x.iter().zip(&self.window).map(|(v, w)| v * w).sum::<f64>() / self.window_sum;
        for ((out, v), w) in buf.input.iter_mut().zip(x).zip(&self.window) {
            *out = (v - mean) * w;
        }
        buf.input[n..].fill(0.0);
        if self.fft.process_with_scratch(&mut buf.input, &mut buf.output, &mut buf.scratch).is_err() {
            return f64::NAN;
        }
        // |X|^2: the same maxima, and the log-parabola's offset is unchanged by the square
        let mag = |k: usize| buf.output[k].norm_sqr();
        let bins = buf.output.len();
        let (mut best, mut best_mag) = (0usize, 0.0f64);
        let mut left = mag(0);
        let mut here = mag(1);
        for k in 1..bins - 1 {
            let right = mag(k + 1);
            if here > left && here >= right && here > best_mag {
                best = k;
                best_mag = here;
            }
            left = here;
            here = right;
        }
        if best == 0 || best_mag <= 0.0 {
            return f64::NAN;
        }
        let ln = |v: f64| v.max(1e-300).ln();
        let (a, b, c) = (ln(mag(best - 1)), ln(best_mag), ln(mag(best + 1)));
        let denom = a - 2.0 * b + c;
        let delta = if denom < 0.0 { 0.5 * (a - c) / denom } else { 0.0 };
        (best as f64 + delta) / (self.nfft as f64 * dt)
    }
}

/// `theta(z_k, t_j) = sum_i basis_i q_i(t_j)` for the row-major states `y` (`[q, qdot]`
/// per sample, `2 m` values).
pub fn section_twist(y: &[f64], basis: &[f64]) -> Vec<f64> {
    let m = basis.len();
    y.chunks_exact(2 * m).map(|s| s[..m].iter().zip(basis).map(|(q, b)| q * b).sum()).collect()
}

/// The metrics of a run of `sys` whose row-major states `[q, qdot]` are `y`, sampled every
/// `dt` seconds, with `theta` = [`section_twist`] at the section.
/// `dissipated`: the energy dissipated up to each sample ([`crate::Solution::dissipated`]),
/// empty for an undamped run.
#[allow(clippy::too_many_arguments)]
pub fn compute(
    sys: &ModalSystem,
    y: &[f64],
    dissipated: &[f64],
    theta: &[f64],
    dt: f64,
    estimator: &FrequencyEstimator,
    buf: &mut FftBuffers,
) -> Metrics {
    let m = sys.modes();
    let samples = theta.len();
    let max_theta = theta.iter().fold(0.0f64, |acc, v| acc.max(v.abs()));
    let rms_theta =
        if samples == 0 { f64::NAN } else { (theta.iter().map(|v| v * v).sum::<f64>() / samples as f64).sqrt() };
    let dominant_frequency_hz = estimator.dominant_frequency(theta, dt, buf);

    let (mass, stiffness) = (sys.mass(), sys.stiffness());
    let mut max_share = vec![f64::NEG_INFINITY; m];
    let mut energies = vec![0.0; m];
    let mut any_share = false;
    let mut h0 = f64::NAN;
    let mut drift = 0.0f64;
    for (j, state) in y.chunks_exact(2 * m).enumerate() {
        let (q, v) = state.split_at(m);
        let mut total = 0.0;
        for i in 0..m {
            energies[i] = 0.5 * (mass[i] * v[i] * v[i] + stiffness[i] * q[i] * q[i]);
            total += energies[i];
        }
        if total > 0.0 {
            any_share = true;
            for i in 0..m {
                max_share[i] = max_share[i].max(energies[i] / total);
            }
        }
        let h = sys.energy(q, v) + dissipated.get(j).copied().unwrap_or(0.0);
        if j == 0 {
            h0 = h;
        } else if h0 != 0.0 {
            drift = drift.max((h - h0).abs() / h0.abs());
        }
    }
    if !any_share {
        max_share.fill(f64::NAN);
    }
    Metrics { max_theta, rms_theta, dominant_frequency_hz, energy_drift: drift, max_share }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::QuarticTerm;

    #[test]
    fn frequency_of_a_sine() {
        let n = 1024;
        let dt = 1.0 / (n - 1) as f64;
        let est = FrequencyEstimator::new(n);
        let mut buf = est.buffers();
        for f in [7.3, 31.3, 97.0] {
            let x: Vec<f64> = (0..n).map(|j| (2.0 * std::f64::consts::PI * f * j as f64 * dt).sin() + 0.3).collect();
            let got = est.dominant_frequency(&x, dt, &mut buf);
            assert!((got - f).abs() < 2e-3 * f, "{got} vs {f}");
        }
        assert!(est.dominant_frequency(&vec![1.0; n], dt, &mut buf).is_nan());
        assert!(est.dominant_frequency(&[1.0, 2.0], dt, &mut buf).is_nan());
    }

    #[test]
    fn shares_and_drift() {
        let sys = ModalSystem::new(vec![1.0, 1.0], vec![1.0, 4.0], vec![QuarticTerm { idx: [0, 0, 0, 0], coef: 0.0 }])
            .unwrap();
        // mode 0 holds all energy at sample 0, half at sample 1; H constant = 1
        let y = vec![0.0, 0.0, 2f64.sqrt(), 0.0, 1.0, 0.0, 0.0, 1.0];
        let theta = section_twist(&y, &[1.0, -1.0]);
        assert_eq!(theta, vec![0.0, 1.0]);
        let est = FrequencyEstimator::new(2);
        let mut buf = est.buffers();
        let m = compute(&sys, &y, &[], &theta, 0.1, &est, &mut buf);
        assert!((m.max_share[0] - 1.0).abs() < 1e-15);
        assert!((m.max_share[1] - 0.5).abs() < 1e-15);
        assert!(m.energy_drift < 1e-15);
        assert_eq!(m.max_theta, 1.0);
        assert!((m.rms_theta - 0.5f64.sqrt()).abs() < 1e-15);
        assert!(m.dominant_frequency_hz.is_nan());
    }
}

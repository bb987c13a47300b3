//! Scalar metrics of a sampled run, used by single solves (through the bindings), the PDE and
//! sweeps alike. Records are sampled on a uniform time grid.
//!
//! * [`max_abs`] and [`rms`] of a record;
//! * the spectral peaks of a record ([`FrequencyEstimator::spectral_peaks`]): Hann window
//!   (`0.5 - 0.5 cos(2 pi j/(n-1))`), window-weighted mean removed, zero-padded by `pad`
//!   (default [`PAD`]) to a power of two, real FFT, the interior local maxima of `|X|` at least
//!   `threshold` (default [`PEAK_THRESHOLD`]) times the largest `|X|`, strongest first; a peak
//!   closer than [`HANN_HALF_WIDTH`] unpadded bins to a stronger one, or not above twice the
//!   summed Hann side-lobe envelope of the stronger ones (and of their images at negative
//!   frequency), is dropped; each is refined by a parabola through the logarithms of the three
//!   bins around it (frequency and sine amplitude). The dominant frequency is the first peak;
//! * modal energy exchange ([`modal_energy`], [`modal_energy_history`], [`max_modal_shares`]):
//!   the quadratic energy of mode `i`, `E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`, its share
//!   `E_i / sum_j E_j` at every sample (samples whose total is not positive are skipped) and the
//!   largest share each mode reached. With a negative `K_i` (the rigid mode under rotation, or a mode above its
//!   critical speed) `E_i` may be negative and the other shares may exceed 1;
//! * the quartic energy share ([`quartic_share`], [`quartic_share_of`]) `max |V(t)| / |H(0)|`;
//! * the energy drift ([`energy_drift`], [`EnergyDrift`]) `max |H(t) - H(0)| / |H(0)|` of the
//!   energies `H` of the samples (0 when `H(0) = 0`, NaN when a term is NaN); with damping the
//!   error of the energy balance, `max |H(t) + D(t) - H(0)| / |H(0)|` with `D` the energy
//!   dissipated up to each sample;
//! * [`compute`]: all of them for one run of a [`ModalSystem`] (what a sweep reports);
//! * [`stickslip`]: stick-slip metrics of any bit-speed and motor-torque series, and the
//!   static break-off torque of a well;
//! * [`signal`]: the phase, growth, modulation and phase-plane metrics of a response and the
//!   exact one-mode (Duffing) amplitude and frequency that the paper report reads.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{RealFftPlanner, RealToComplex};

use crate::error::{Error, Result};
use crate::modal::ModalSystem;
use crate::system::{potential_history, Energy};

pub mod signal;
pub mod stickslip;
pub use stickslip::{break_off_torque, stick_slip, verdict, StickSlip, Verdict, STICK_SLIP_CRITERION, STICK_SPEED};

/// Default zero-padding factor of the FFT (the bin spacing is `1 / (pad * duration)`).
pub const PAD: usize = 8;

/// Default relative threshold of a spectral peak: weaker than this times the largest `|X|`
/// is ignored.
pub const PEAK_THRESHOLD: f64 = 1e-3;

/// Hann main-lobe half width in bins of the unpadded record: peaks closer than this to a
/// stronger one are not resolved from it.
pub const HANN_HALF_WIDTH: f64 = 2.0;

/// Largest FFT length (`next_power_of_two(n pad)`) a [`FrequencyEstimator`] accepts.
pub const MAX_FFT_LEN: usize = 1 << 32;

/// `max |x|` over the record (0 for an empty one).
pub fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |acc, v| acc.max(v.abs()))
}

/// Root mean square of the record (NaN for an empty one).
pub fn rms(x: &[f64]) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// One peak of the windowed spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralPeak {
    /// Interpolated peak frequency, Hz.
    pub frequency: f64,
    /// Amplitude of the sine it corresponds to (window-gain corrected), in the units of `x`.
    pub amplitude: f64,
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
    candidates: Vec<usize>,
}

/// Side-lobe envelope of the Hann window relative to its peak, `distance` in unpadded bins.
fn hann_leakage(distance: f64) -> f64 {
    1.0 / (std::f64::consts::PI * distance * (distance * distance - 1.0).abs())
}

impl FrequencyEstimator {
    /// For records of `n >= 1` samples, zero-padded by [`PAD`].
    pub fn new(n: usize) -> Self {
        Self::build(n.max(1), (n.max(1) * PAD).next_power_of_two())
    }

    /// For records of `n >= 1` samples, zero-padded by `pad >= 1`; an error when the FFT
    /// length would exceed [`MAX_FFT_LEN`].
    pub fn with_pad(n: usize, pad: usize) -> Result<Self> {
        if n == 0 {
            return Err(Error::invalid("x", "0 samples", "at least 1 sample"));
        }
        if pad == 0 {
            return Err(Error::invalid("pad", pad, "an integer >= 1"));
        }
        match n.checked_mul(pad).and_then(usize::checked_next_power_of_two) {
            Some(nfft) if nfft <= MAX_FFT_LEN => Ok(Self::build(n, nfft)),
            _ => Err(Error::invalid(
                "pad",
                pad,
                format!("an integer >= 1 with samples * pad <= {MAX_FFT_LEN} ({n} samples)"),
            )),
        }
    }

    fn build(n: usize, nfft: usize) -> Self {
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

    /// The FFT length.
    pub fn fft_len(&self) -> usize {
        self.nfft
    }

    pub fn buffers(&self) -> FftBuffers {
        FftBuffers {
            input: self.fft.make_input_vec(),
            output: self.fft.make_output_vec(),
            scratch: self.fft.make_scratch_vec(),
            candidates: Vec::new(),
        }
    }

    /// The dominant frequency (Hz) of `x`: the first of [`Self::spectral_peaks`] with the
    /// default threshold; NaN when there is none.
    pub fn dominant_frequency(&self, x: &[f64], dt: f64, buf: &mut FftBuffers) -> f64 {
        self.spectral_peaks(x, dt, 1, PEAK_THRESHOLD, buf).first().map_or(f64::NAN, |p| p.frequency)
    }

    /// The `count` strongest peaks of the Hann-windowed spectrum of `x`, sampled every `dt`
    /// seconds, strongest first (see the module). Empty when `x` does not have the `n` samples
    /// this estimator was made for, for fewer than 4 samples, a non-finite record or `dt`, and
    /// a spectrum without an interior peak (a constant record).
    pub fn spectral_peaks(
        &self,
        x: &[f64],
        dt: f64,
        count: usize,
        threshold: f64,
        buf: &mut FftBuffers,
    ) -> Vec<SpectralPeak> {
        let n = self.n;
        let mut peaks = Vec::new();
        if count == 0 || x.len() != n || n < 4 || !x.iter().all(|v| v.is_finite()) || !dt.is_finite() || dt <= 0.0 {
            return peaks;
        }
        // relative to the first sample: a constant record is then exactly zero (no peaks from
        // the rounding of its mean)
        let x0 = x[0];
        let mean = x.iter().zip(&self.window).map(|(v, w)| (v - x0) * w).sum::<f64>() / self.window_sum;
        for ((out, v), w) in buf.input.iter_mut().zip(x).zip(&self.window) {
            *out = ((v - x0) - mean) * w;
        }
        buf.input[n..].fill(0.0);
        if self.fft.process_with_scratch(&mut buf.input, &mut buf.output, &mut buf.scratch).is_err() {
            return peaks;
        }
        let spectrum = &buf.output;
        // |X|^2 to find the maxima (the same ones, without a square root per bin)
        let power = |k: usize| spectrum[k].norm_sqr();
        let mag = |k: usize| spectrum[k].norm();
        let bins = spectrum.len();
        let top = spectrum.iter().fold(0.0f64, |acc, c| acc.max(c.norm_sqr())).sqrt();
        if top.is_nan() || top <= 0.0 {
            return peaks;
        }
        // compared with |X|^2: a threshold <= 0 keeps every maximum (NaN none)
        let floor = threshold * top;
        let floor2 = if floor > 0.0 || floor.is_nan() { floor * floor } else { 0.0 };
        let is_candidate = |k: usize| {
            let here = power(k);
            here > power(k - 1) && here >= power(k + 1) && here >= floor2
        };
        buf.candidates.clear();
        if count == 1 {
            // the strongest candidate is always kept: one pass, no sort
            let mut best: Option<usize> = None;
            for k in 1..bins.saturating_sub(1) {
                if is_candidate(k) && best.is_none_or(|b| power(k) > power(b)) {
                    best = Some(k);
                }
            }
            buf.candidates.extend(best);
        } else {
            buf.candidates.extend((1..bins.saturating_sub(1)).filter(|&k| is_candidate(k)));
            buf.candidates.sort_by(|&a, &b| power(b).total_cmp(&power(a)));
        }
        let ratio = self.nfft as f64 / n as f64; // padded bins per unpadded bin
        let bin_hz = 1.0 / (self.nfft as f64 * dt);
        let gain = self.window_sum / 2.0; // |X| of a unit sine at its bin
        let mut chosen: Vec<usize> = Vec::new();
        for &k in &buf.candidates {
            let distance = |j: usize| k.abs_diff(j) as f64 / ratio;
            if chosen.iter().any(|&j| distance(j) < HANN_HALF_WIDTH) {
                continue;
            }
            let leakage: f64 = chosen
                .iter()
                .map(|&j| mag(j) * (hann_leakage(distance(j)) + hann_leakage((k + j) as f64 / ratio)))
                .sum();
            if mag(k) <= 2.0 * leakage {
                continue;
            }
            chosen.push(k);
            let ln = |v: f64| v.max(1e-300).ln();
            let (a, b, c) = (ln(mag(k - 1)), ln(mag(k)), ln(mag(k + 1)));
            let denom = a - 2.0 * b + c;
            let delta = if denom < 0.0 { 0.5 * (a - c) / denom } else { 0.0 };
            let log_peak = b - 0.25 * (a - c) * delta;
            peaks.push(SpectralPeak { frequency: (k as f64 + delta) * bin_hz, amplitude: log_peak.exp() / gain });
            if peaks.len() == count {
                break;
            }
        }
        peaks
    }
}

/// Running `max |H + D - H(0)| / |H(0)|` over the samples pushed in order.
#[derive(Debug, Clone, Default)]
pub struct EnergyDrift {
    h0: Option<f64>,
    worst: f64,
    nan: bool,
}

impl EnergyDrift {
    /// The next sample: its energy `h` and the energy dissipated up to it (0 undamped).
    pub fn push(&mut self, h: f64, dissipated: f64) {
        let total = h + dissipated;
        match self.h0 {
            None => {
                self.nan = total.is_nan();
                self.h0 = Some(total);
            }
            Some(h0) => {
                let error = (total - h0).abs() / h0.abs();
                if error.is_nan() {
                    self.nan = true;
                } else {
                    self.worst = self.worst.max(error);
                }
            }
        }
    }

    /// The drift so far: 0 without samples or when `H(0) = 0`, NaN if a term was NaN.
    pub fn value(&self) -> f64 {
        if self.h0 == Some(0.0) {
            0.0
        } else if self.nan {
            f64::NAN
        } else {
            self.worst
        }
    }
}

/// `max |H(t) + D(t) - H(0)| / |H(0)|` of the energies `energy` and the dissipated energies
/// `dissipated` (empty for an undamped run, else one per sample; missing ones count as 0).
pub fn energy_drift(energy: &[f64], dissipated: &[f64]) -> f64 {
    let mut drift = EnergyDrift::default();
    for (j, &h) in energy.iter().enumerate() {
        drift.push(h, dissipated.get(j).copied().unwrap_or(0.0));
    }
    drift.value()
}

/// The quartic energy share `max_t |V(t)| / |H(0)|`: the largest share of the initial energy
/// in the quartic (nonlinear) potential, from the potentials `potential` of the samples and
/// the energy `energy0` of the first; NaN when `H(0) = 0`, without samples, or if a `V` is NaN.
pub fn quartic_share(potential: &[f64], energy0: f64) -> f64 {
    if energy0 == 0.0 || potential.is_empty() {
        return f64::NAN;
    }
    let largest =
        potential.iter().fold(0.0f64, |acc, v| if acc.is_nan() || v.is_nan() { f64::NAN } else { acc.max(v.abs()) });
    largest / energy0.abs()
}

/// [`quartic_share`] of a run of `sys`: the potentials ([`crate::system::potential_history`])
/// of the row-major `(dof, samples)` positions `q`, over the energy `energy0` of the first
/// sample. An error naming `q` for a bad shape.
pub fn quartic_share_of<S: Energy + ?Sized>(sys: &S, q: &[f64], energy0: f64) -> Result<f64> {
    Ok(quartic_share(&potential_history(sys, q)?, energy0))
}

/// The quadratic energy `(M v^2 + K q^2) / 2` of one mode of mass `M` and stiffness `K`.
#[inline]
pub fn modal_energy(mass: f64, stiffness: f64, q: f64, v: f64) -> f64 {
    0.5 * (mass * v * v + stiffness * q * q)
}

/// [`modal_energy`] of each mode at one state, written into `out`.
pub fn modal_energies(mass: &[f64], stiffness: &[f64], q: &[f64], v: &[f64], out: &mut [f64]) {
    for ((((e, &m), &k), &q), &v) in out.iter_mut().zip(mass).zip(stiffness).zip(q).zip(v) {
        *e = modal_energy(m, k, q, v);
    }
}

/// [`modal_energy`] of each mode (rows) at each sample (columns): `q` and `v` row-major
/// `(m, samples)` with `m = mass.len()`; the result has the same layout. An error unless the
/// lengths agree.
pub fn modal_energy_history(mass: &[f64], stiffness: &[f64], q: &[f64], v: &[f64]) -> Result<Vec<f64>> {
    let m = mass.len();
    if stiffness.len() != m {
        return Err(Error::invalid("stiffness", format!("length {}", stiffness.len()), format!("length {m}")));
    }
    if q.len() != v.len() || (m == 0 && !q.is_empty()) || (m > 0 && q.len() % m != 0) {
        return Err(Error::invalid(
            "q",
            format!("{} and {} values", q.len(), v.len()),
            format!("q and qdot of equal shape ({m}, samples)"),
        ));
    }
    let samples = q.len().checked_div(m).unwrap_or(0);
    let mut out = Vec::with_capacity(q.len());
    for (i, (qi, vi)) in q.chunks_exact(samples.max(1)).zip(v.chunks_exact(samples.max(1))).enumerate() {
        out.extend(qi.iter().zip(vi).map(|(&q, &v)| modal_energy(mass[i], stiffness[i], q, v)));
    }
    Ok(out)
}

/// The largest share `E_i / sum_j E_j` ([`modal_energies`]) each mode reached over the
/// row-major states `y` (`[q, qdot]` per sample, `2 m` values); samples whose total is not
/// positive are skipped; all NaN if no sample had a positive total.
pub fn max_modal_shares(mass: &[f64], stiffness: &[f64], y: &[f64]) -> Vec<f64> {
    let m = mass.len();
    let mut max_share = vec![f64::NEG_INFINITY; m];
    if m == 0 {
        return max_share;
    }
    let mut energies = vec![0.0; m];
    let mut any_share = false;
    for state in y.chunks_exact(2 * m) {
        let (q, v) = state.split_at(m);
        modal_energies(mass, stiffness, q, v, &mut energies);
        let total: f64 = energies.iter().sum();
        if total > 0.0 {
            any_share = true;
            for (share, e) in max_share.iter_mut().zip(&energies) {
                *share = share.max(e / total);
            }
        }
    }
    if !any_share {
        max_share.fill(f64::NAN);
    }
    max_share
}

/// `theta(z_k, t_j) = sum_i basis_i q_i(t_j)` for the row-major states `y` (`[q, qdot]`
/// per sample, `2 m` values).
pub fn section_twist(y: &[f64], basis: &[f64]) -> Vec<f64> {
    let m = basis.len();
    y.chunks_exact(2 * m).map(|s| s[..m].iter().zip(basis).map(|(q, b)| q * b).sum()).collect()
}

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

/// The metrics of a run of `sys` whose row-major states `[q, qdot]` are `y`, sampled every
/// `dt` seconds, with `theta` = [`section_twist`] at the section; `H` = [`ModalSystem::energy`].
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
    let mut drift = EnergyDrift::default();
    for (j, state) in y.chunks_exact(2 * m).enumerate() {
        let (q, v) = state.split_at(m);
        drift.push(sys.energy(q, v), dissipated.get(j).copied().unwrap_or(0.0));
    }
    Metrics {
        max_theta: max_abs(theta),
        rms_theta: rms(theta),
        dominant_frequency_hz: estimator.dominant_frequency(theta, dt, buf),
        energy_drift: drift.value(),
        max_share: max_modal_shares(sys.mass(), sys.stiffness(), y),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::QuarticTerm;

    fn sine(n: usize, dt: f64, f: f64, amp: f64, phase: f64) -> Vec<f64> {
        (0..n).map(|j| amp * (2.0 * std::f64::consts::PI * f * j as f64 * dt + phase).sin()).collect()
    }

    #[test]
    fn frequency_of_a_sine() {
        let n = 1024;
        let dt = 1.0 / (n - 1) as f64;
        let est = FrequencyEstimator::new(n);
        let mut buf = est.buffers();
        for f in [7.3, 31.3, 97.0] {
            let x: Vec<f64> = sine(n, dt, f, 1.0, 0.0).iter().map(|v| v + 0.3).collect();
            let got = est.dominant_frequency(&x, dt, &mut buf);
            assert!((got - f).abs() < 2e-3 * f, "{got} vs {f}");
        }
        assert!(est.dominant_frequency(&vec![1.0; n], dt, &mut buf).is_nan());
        assert!(est.spectral_peaks(&vec![3.0; n], dt, 3, 0.0, &mut buf).is_empty());
        assert!(est.dominant_frequency(&[1.0, 2.0], dt, &mut buf).is_nan());
        let mut bad = sine(n, dt, 7.3, 1.0, 0.0);
        bad[3] = f64::NAN;
        assert!(est.dominant_frequency(&bad, dt, &mut buf).is_nan());
        assert!(est.dominant_frequency(&sine(n, dt, 7.3, 1.0, 0.0), 0.0, &mut buf).is_nan());
    }

    #[test]
    fn two_sines_strongest_first_with_amplitudes() {
        let n = 4001;
        let dt = 1.0 / 4000.0;
        let est = FrequencyEstimator::with_pad(n, PAD).unwrap();
        let mut buf = est.buffers();
        let (a, b) = (sine(n, dt, 31.6, 1e-3, 0.0), sine(n, dt, 62.3, 2e-4, 1.0));
        let x: Vec<f64> = a.iter().zip(&b).map(|(a, b)| a + b + 5e-5).collect();
        let peaks = est.spectral_peaks(&x, dt, 3, PEAK_THRESHOLD, &mut buf);
        assert_eq!(peaks.len(), 2, "{peaks:?}"); // side lobes are not peaks
        assert!((peaks[0].frequency / 31.6 - 1.0).abs() < 1e-4);
        assert!((peaks[1].frequency / 62.3 - 1.0).abs() < 1e-4);
        assert!((peaks[0].amplitude / 1e-3 - 1.0).abs() < 1e-3);
        assert!((peaks[1].amplitude / 2e-4 - 1.0).abs() < 1e-2);
        assert_eq!(est.spectral_peaks(&x, dt, 1, PEAK_THRESHOLD, &mut buf), peaks[..1]);
        assert_eq!(est.spectral_peaks(&x, dt, 2, -1.0, &mut buf), est.spectral_peaks(&x, dt, 2, 0.0, &mut buf));
        assert!(est.spectral_peaks(&x, dt, 2, f64::NAN, &mut buf).is_empty());
    }

    #[test]
    fn pad_limits() {
        assert!(FrequencyEstimator::with_pad(10, 0).is_err());
        assert!(FrequencyEstimator::with_pad(0, 8).is_err());
        assert!(FrequencyEstimator::with_pad(usize::MAX / 2, 8).is_err());
        assert_eq!(FrequencyEstimator::with_pad(1000, 1).unwrap().fft_len(), 1024);
        assert_eq!(FrequencyEstimator::new(1000).fft_len(), 8192);
    }

    #[test]
    fn drift_and_balance() {
        assert_eq!(energy_drift(&[], &[]), 0.0);
        assert_eq!(energy_drift(&[0.0, 1.0], &[]), 0.0);
        assert_eq!(energy_drift(&[2.0, 2.5, 1.0], &[]), 0.5);
        // damped: H + D is constant
        assert!(energy_drift(&[2.0, 1.5, 1.0], &[0.0, 0.5, 1.0]).abs() < 1e-16);
        assert!(energy_drift(&[2.0, f64::NAN, 2.0], &[]).is_nan());
        assert!(energy_drift(&[f64::NAN, 1.0], &[]).is_nan());
        assert_eq!(max_abs(&[1.0, -3.0, 2.0]), 3.0);
        assert!((rms(&[3.0, -4.0]) - 12.5f64.sqrt()).abs() < 1e-15);
        assert!(rms(&[]).is_nan());
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
        assert!(max_modal_shares(&[1.0], &[1.0], &[0.0, 0.0]).iter().all(|s| s.is_nan()));
        // rows are modes: q = [[1, 0], [0, 2]], v = [[0, 1], [1, 0]]
        let e = modal_energy_history(&[2.0, 1.0], &[4.0, -1.0], &[1.0, 0.0, 0.0, 2.0], &[0.0, 1.0, 1.0, 0.0]);
        assert_eq!(e.unwrap(), vec![2.0, 1.0, 0.5, -2.0]);
        assert!(modal_energy_history(&[1.0], &[1.0, 2.0], &[], &[]).is_err());
        assert!(modal_energy_history(&[1.0, 1.0], &[1.0, 2.0], &[1.0; 3], &[1.0; 3]).is_err());
        assert_eq!(modal_energy_history(&[], &[], &[], &[]).unwrap(), Vec::<f64>::new());
    }
}

#[cfg(test)]
mod quartic_share_tests {
    use super::*;
    use crate::modal::QuarticTerm;

    #[test]
    fn quartic_share_is_the_largest_potential_over_the_initial_energy() {
        assert_eq!(quartic_share(&[0.1, -0.3, 0.2], -2.0), 0.15);
        assert!(quartic_share(&[0.1], 0.0).is_nan());
        assert!(quartic_share(&[], 1.0).is_nan());
        assert!(quartic_share(&[0.1, f64::NAN, 0.2], 1.0).is_nan());
        // V = 2 q0^4 on one mode, samples q0 = 1, -0.5 (row-major (1, 2))
        let sys = ModalSystem::new(vec![1.0], vec![1.0], vec![QuarticTerm { idx: [0; 4], coef: 2.0 }]).unwrap();
        assert_eq!(quartic_share_of(&sys, &[1.0, -0.5], 4.0).unwrap(), 0.5);
    }
}

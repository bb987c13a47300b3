//! The pseudo-spectral evaluation of the quartic potential and its gradient: `O(n log n)` per
//! evaluation instead of one product per merged cubic monomial (`~n^3`).
//!
//! With `s = z / l` and the basis `cos(i_k pi s)` (`i_k` strictly increasing, `0` for the rigid
//! mode), the field and its slope at a point are
//!
//! ```text
//! th(s)   = sum_k q_k cos(i_k pi s)
//! th_z(s) = -(pi / l) sum_k i_k q_k sin(i_k pi s)
//! ```
//!
//! and, `e(th, th_z) = sum_t weight_t th^p_t th_z^r_t` the density of the model's quartic terms
//! (`p + r = 4`, `r` even; [`crate::terms::EnergyTerm`], their partial derivatives
//! [`crate::terms::EnergyTerm::partials`]),
//!
//! ```text
//! V(q)       = l int_0^1 e ds
//! dV/dq_k    = l int_0^1 [e_th cos(i_k pi s) - (pi / l) i_k e_thz sin(i_k pi s)] ds.
//! ```
//!
//! Both integrals are taken with the midpoint rule on `M` points `s_j = (j + 1/2) / M`, which is
//! **exact** for `M > 2 N`, `N = max i_k`:
//!
//! * Each integrand is a trigonometric polynomial `sum_{m=0}^{4N} a_m cos(m pi s)`. `e` and
//!   `e_th cos` and `e_thz sin` are products of four factors, each `cos(i pi s)` or
//!   `sin(i pi s)` with `i <= N`, with an even number of sines (`r` even: `th_z` contributes
//!   `r` sines to `e`, `r - 1` plus the basis sine to `e_thz sin`, `r` to `e_th cos`); a
//!   product of cosines and an even number of sines is a combination of `cos(m pi s)`, `m` the
//!   sum of the four frequencies with signs, `|m| <= 4N`.
//! * `int_0^1 cos(m pi s) ds` is `1` for `m = 0` and `0` for `m >= 1`. The midpoint rule gives
//!   `1` for `m = 0` and, for `1 <= m < 2M`,
//!   `(1/M) Re sum_j exp(i pi m (2j + 1) / (2M)) = (1/M) Re [(1 - (-1)^m) / (-2i sin(pi m / (2M)))]`,
//!   which is `0` for even `m` and purely imaginary for odd `m`: `0`, exact. `4N < 2M` is
//!   `M > 2N`.
//!
//! So the result is the exact Galerkin gradient (the term-by-term sum of
//! [`crate::sweep::GalerkinIntegrals`]) up to rounding: no aliasing. The tests check it to
//! `~1e-13` relative for 1..40 modes with and without the rigid mode, for both model variants.
//!
//! Both transforms are one real FFT of length `L = 2M` each (`realfft`):
//!
//! * to the points: the inverse real transform of `X_i = (q_i - i b_i) exp(i pi i / L) / 2`
//!   (`b_i = -(pi / l) i q_i`, `X_0 = q_0`) is `x_j = th(s_j) + th_z(s_j)` and
//!   `x_{L-1-j} = th(s_j) - th_z(s_j)` for `j < M` (cosines are even, sines odd about `s = 1`);
//! * back: the forward transform `Y` of `y_j = F_j + G_j`, `y_{L-1-j} = F_j - G_j`
//!   (`F = e_th`, `G = e_thz` at the points) gives `exp(-i pi i / L) Y_i
//!   = 2 sum_j F_j cos(i pi s_j) - 2i sum_j G_j sin(i pi s_j)`.
//!
//! `M` is the smallest 5-smooth number `> 2N` (fast transform lengths). Scratch buffers are
//! per thread, so a system is shared read-only between threads (sweeps, the Python binding).

use std::cell::RefCell;
use std::f64::consts::PI;
use std::fmt;
use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};

use crate::error::{Error, Result};
use crate::terms::EnergyTerm;

/// The quartic potential of a model's quartic terms on the cosine basis `indices`, evaluated
/// pseudo-spectrally (module docs).
#[derive(Clone)]
pub struct SpectralQuartic {
    indices: Vec<u32>,
    length: f64,
    terms: Vec<EnergyTerm>,
    points: usize,
    /// `exp(i pi i_k / L)` per basis position.
    phase: Vec<Complex<f64>>,
    forward: Arc<dyn RealToComplex<f64>>,
    inverse: Arc<dyn ComplexToReal<f64>>,
}

impl fmt::Debug for SpectralQuartic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SpectralQuartic")
            .field("modes", &self.indices.len())
            .field("length", &self.length)
            .field("terms", &self.terms)
            .field("points", &self.points)
            .finish()
    }
}

impl PartialEq for SpectralQuartic {
    fn eq(&self, other: &Self) -> bool {
        self.indices == other.indices && self.length == other.length && self.terms == other.terms
    }
}

/// The smallest `m >= n` whose prime factors are 2, 3 and 5.
fn smooth_at_least(n: usize) -> usize {
    (n.max(1)..)
        .find(|&m| {
            let mut r = m;
            for p in [2, 3, 5] {
                while r % p == 0 {
                    r /= p;
                }
            }
            r == 1
        })
        .unwrap_or(n)
}

/// Per-thread buffers of the transforms.
#[derive(Default)]
struct Scratch {
    spectrum: Vec<Complex<f64>>,
    values: Vec<f64>,
    fft: Vec<Complex<f64>>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

impl SpectralQuartic {
    /// The quartic potential of `terms` (each `p + r = 4` with `r` even, else an error naming
    /// its coefficient) on the basis `cos(i pi z / length)`, `i` in `indices` (strictly
    /// increasing, at least one), `length` finite and `> 0`.
    pub fn new(indices: Vec<u32>, length: f64, terms: Vec<EnergyTerm>) -> Result<Self> {
        if indices.is_empty() {
            return Err(Error::invalid("indices", "an empty basis", "at least one mode"));
        }
        if let Some(k) = (1..indices.len()).find(|&k| indices[k] <= indices[k - 1]) {
            return Err(Error::invalid(
                "indices",
                format!("indices[{k}] = {} after {}", indices[k], indices[k - 1]),
                "strictly increasing mode numbers",
            ));
        }
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid("length", crate::error::Num(length), "a finite number > 0"));
        }
        for term in &terms {
            let (p, r) = term.exponents();
            if p + r != 4 || r % 2 != 0 {
                return Err(Error::invalid(
                    term.spec().coefficient,
                    format!("the {} term th^{p} th_z^{r}", term.name()),
                    "a quartic energy monomial (p + r = 4, r even)",
                ));
            }
        }
        let top = *indices.last().unwrap_or(&0) as usize;
        let points = smooth_at_least(2 * top + 1);
        let len = 2 * points;
        let mut planner = RealFftPlanner::<f64>::new();
        let phase =
            indices.iter().map(|&i| Complex::from_polar(1.0, PI * f64::from(i) / len as f64)).collect::<Vec<_>>();
        Ok(SpectralQuartic {
            forward: planner.plan_fft_forward(len),
            inverse: planner.plan_fft_inverse(len),
            indices,
            length,
            terms,
            points,
            phase,
        })
    }

    /// The quadrature points `M` (`> 2 max i`).
    pub fn points(&self) -> usize {
        self.points
    }

    /// Number of basis functions.
    pub fn modes(&self) -> usize {
        self.indices.len()
    }

    /// The quartic terms.
    pub fn terms(&self) -> &[EnergyTerm] {
        &self.terms
    }

    /// `th(s_j)` into `values[j]` and `th_z(s_j)` into `values[L - 1 - j]` mixed as
    /// `th +- th_z` (module docs); the caller separates them.
    fn to_points(&self, q: &[f64], s: &mut Scratch) {
        let len = 2 * self.points;
        s.spectrum.clear();
        s.spectrum.resize(len / 2 + 1, Complex::new(0.0, 0.0));
        s.values.clear();
        s.values.resize(len, 0.0);
        s.fft.resize(self.inverse.get_scratch_len().max(self.forward.get_scratch_len()), Complex::new(0.0, 0.0));
        let slope = -PI / self.length;
        for ((&i, &phase), &qk) in self.indices.iter().zip(&self.phase).zip(q) {
            if i == 0 {
                s.spectrum[0] = Complex::new(qk, 0.0);
            } else {
                let b = slope * f64::from(i) * qk;
                // (q - i b) e^{i phi} / 2
                s.spectrum[i as usize] = Complex::new(0.5 * qk, -0.5 * b) * phase;
            }
        }
        // the imaginary parts of the first and last bins are zero by construction
        let _ = self.inverse.process_with_scratch(&mut s.spectrum, &mut s.values, &mut s.fft);
    }

    /// `V(q)`: the midpoint rule (exact, module docs) of the quartic density.
    pub fn potential(&self, q: &[f64]) -> f64 {
        SCRATCH.with(|cell| {
            let s = &mut *cell.borrow_mut();
            self.to_points(q, s);
            let (m, len) = (self.points, 2 * self.points);
            let mut sum = 0.0;
            for j in 0..m {
                let (a, b) = (s.values[j], s.values[len - 1 - j]);
                let (th, th_z) = (0.5 * (a + b), 0.5 * (a - b));
                for term in &self.terms {
                    sum += term.density(th, th_z);
                }
            }
            self.length / m as f64 * sum
        })
    }

    /// Adds `grad V(q)` to `out`.
    pub fn add_gradient(&self, q: &[f64], out: &mut [f64]) {
        SCRATCH.with(|cell| {
            let s = &mut *cell.borrow_mut();
            self.to_points(q, s);
            let (m, len) = (self.points, 2 * self.points);
            for j in 0..m {
                let (a, b) = (s.values[j], s.values[len - 1 - j]);
                let (th, th_z) = (0.5 * (a + b), 0.5 * (a - b));
                let (mut f, mut g) = (0.0, 0.0);
                for term in &self.terms {
                    let (d_th, d_thz) = term.partials(th, th_z);
                    f += d_th;
                    g += d_thz;
                }
                s.values[j] = f + g;
                s.values[len - 1 - j] = f - g;
            }
            let _ = self.forward.process_with_scratch(&mut s.values, &mut s.spectrum, &mut s.fft);
            // sum_j F cos = Re / 2, sum_j G sin = -Im / 2, each times l / M; the slope factor
            // -(pi / l) i of d th_z / d q
            let scale = 0.5 * self.length / m as f64;
            let slope = PI / self.length;
            for ((&i, &phase), o) in self.indices.iter().zip(&self.phase).zip(out.iter_mut()) {
                let y = s.spectrum[i as usize] * phase.conj();
                *o += scale * (y.re + slope * f64::from(i) * y.im);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_sizes() {
        assert_eq!(smooth_at_least(7), 8);
        assert_eq!(smooth_at_least(513), 540);
        assert_eq!(smooth_at_least(1), 1);
        assert_eq!(smooth_at_least(11), 12);
    }

    #[test]
    fn refuses_other_shapes_and_bad_bases() {
        let t = crate::terms::energy::LINEAR_ELASTIC.with(1.0).unwrap();
        assert_eq!(SpectralQuartic::new(vec![1], 1.0, vec![t]).unwrap_err().field(), "k2");
        assert_eq!(SpectralQuartic::new(vec![], 1.0, vec![]).unwrap_err().field(), "indices");
        assert_eq!(SpectralQuartic::new(vec![2, 1], 1.0, vec![]).unwrap_err().field(), "indices");
        assert_eq!(SpectralQuartic::new(vec![1], 0.0, vec![]).unwrap_err().field(), "length");
    }

    /// The fields at the points against their direct sums.
    #[test]
    fn the_points_carry_the_field_and_its_slope() {
        let sys = SpectralQuartic::new(vec![0, 1, 2, 5], 3.0, vec![]).unwrap();
        let q = [0.3, -0.7, 0.25, 1.1];
        SCRATCH.with(|cell| {
            let s = &mut *cell.borrow_mut();
            sys.to_points(&q, s);
            let (m, len) = (sys.points(), 2 * sys.points());
            for j in 0..m {
                let x = (j as f64 + 0.5) / m as f64;
                let th: f64 = sys.indices.iter().zip(&q).map(|(&i, &qk)| qk * (f64::from(i) * PI * x).cos()).sum();
                let th_z: f64 = sys
                    .indices
                    .iter()
                    .zip(&q)
                    .map(|(&i, &qk)| -PI / 3.0 * f64::from(i) * qk * (f64::from(i) * PI * x).sin())
                    .sum();
                let (a, b) = (s.values[j], s.values[len - 1 - j]);
                assert!((0.5 * (a + b) - th).abs() < 1e-13 && (0.5 * (a - b) - th_z).abs() < 1e-13);
            }
        });
    }
}

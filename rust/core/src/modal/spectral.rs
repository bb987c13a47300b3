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
//! The quartic monomials with `r` even are `th^4`, `th^2 th_z^2` and `th_z^4`, so the terms'
//! weights are summed by shape once, at construction, and `e`, `e_th`, `e_thz` at a point are
//! three polynomials of those sums (equal to the sums of [`crate::terms::EnergyTerm::density`]
//! and [`crate::terms::EnergyTerm::partials`] over the terms, tested): a new quartic term needs
//! no code here.
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
    /// The weights of the terms summed by shape: `e = w[0] th^4 + w[1] th^2 th_z^2 + w[2] th_z^4`
    /// (the only quartic monomials with `r` even).
    shape: [f64; 3],
    points: usize,
    /// Per basis position, the bin `X_i / q_k` of the transform to the points (module docs):
    /// `(1 + i (pi / l) i_k) exp(i pi i_k / L) / 2`, `1` for `i_k = 0`.
    to_spectrum: Vec<Complex<f64>>,
    /// Per basis position, `(alpha, beta)` with `dV/dq_k = alpha Re Y_i + beta Im Y_i`: the
    /// phase `exp(-i pi i_k / L)`, the slope factor `-(pi / l) i_k` and the weight `l / (2 M)`.
    from_spectrum: Vec<(f64, f64)>,
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
        let mut shape = [0.0; 3];
        for term in &terms {
            let (p, r) = term.exponents();
            if p + r == 4 && r % 2 == 0 {
                shape[r as usize / 2] += term.weight();
            } else {
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
        let (mut to_spectrum, mut from_spectrum) = (Vec::with_capacity(indices.len()), Vec::new());
        let weight = 0.5 * length / points as f64;
        for &i in &indices {
            let phase = Complex::from_polar(1.0, PI * f64::from(i) / len as f64);
            let wave = PI / length * f64::from(i);
            // X_i = (q - i b) phase / 2 with b = -(pi / l) i q; the rigid bin is real, whole
            to_spectrum.push(if i == 0 { Complex::new(1.0, 0.0) } else { Complex::new(0.5, 0.5 * wave) * phase });
            // y = Y conj(phase): dV/dq = weight (Re y + wave Im y)
            from_spectrum.push((weight * (phase.re - wave * phase.im), weight * (phase.im + wave * phase.re)));
        }
        Ok(SpectralQuartic {
            forward: planner.plan_fft_forward(len),
            inverse: planner.plan_fft_inverse(len),
            indices,
            length,
            terms,
            shape,
            points,
            to_spectrum,
            from_spectrum,
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

    /// The quartic density `e(th, th_z)`: the sum of the terms' [`EnergyTerm::density`], with
    /// their weights summed by shape.
    #[inline]
    fn density(&self, th: f64, th_z: f64) -> f64 {
        let [w4, w22, w04] = self.shape;
        let (th2, thz2) = (th * th, th_z * th_z);
        th2 * (w4 * th2 + w22 * thz2) + w04 * thz2 * thz2
    }

    /// `(de/dth, de/dth_z)`: the sum of the terms' [`EnergyTerm::partials`].
    #[inline]
    fn partials(&self, th: f64, th_z: f64) -> (f64, f64) {
        let [w4, w22, w04] = self.shape;
        let (th2, thz2) = (th * th, th_z * th_z);
        (th * (4.0 * w4 * th2 + 2.0 * w22 * thz2), th_z * (2.0 * w22 * th2 + 4.0 * w04 * thz2))
    }

    /// `th(s_j)` into `values[j]` and `th_z(s_j)` into `values[L - 1 - j]` mixed as
    /// `th +- th_z` (module docs); the caller separates them.
    fn to_points(&self, q: &[f64], s: &mut Scratch) {
        let len = 2 * self.points;
        s.spectrum.clear();
        s.spectrum.resize(len / 2 + 1, Complex::new(0.0, 0.0));
        // fully overwritten by the transform
        s.values.resize(len, 0.0);
        s.fft.resize(self.inverse.get_scratch_len().max(self.forward.get_scratch_len()), Complex::new(0.0, 0.0));
        for ((&i, &factor), &qk) in self.indices.iter().zip(&self.to_spectrum).zip(q) {
            s.spectrum[i as usize] = factor * qk;
        }
        // the imaginary parts of the first and last bins are zero by construction
        let _ = self.inverse.process_with_scratch(&mut s.spectrum, &mut s.values, &mut s.fft);
    }

    /// `V(q)`: the midpoint rule (exact, module docs) of the quartic density.
    pub fn potential(&self, q: &[f64]) -> f64 {
        SCRATCH.with(|cell| {
            let s = &mut *cell.borrow_mut();
            self.to_points(q, s);
            let m = self.points;
            let (lo, hi) = s.values.split_at_mut(m);
            let mut sum = 0.0;
            for (&a, &b) in lo.iter().zip(hi.iter().rev()) {
                sum += self.density(0.5 * (a + b), 0.5 * (a - b));
            }
            self.length / m as f64 * sum
        })
    }

    /// Adds `grad V(q)` to `out`.
    pub fn add_gradient(&self, q: &[f64], out: &mut [f64]) {
        SCRATCH.with(|cell| {
            let s = &mut *cell.borrow_mut();
            self.to_points(q, s);
            let m = self.points;
            let (lo, hi) = s.values.split_at_mut(m);
            for (a, b) in lo.iter_mut().zip(hi.iter_mut().rev()) {
                let (f, g) = self.partials(0.5 * (*a + *b), 0.5 * (*a - *b));
                *a = f + g;
                *b = f - g;
            }
            let _ = self.forward.process_with_scratch(&mut s.values, &mut s.spectrum, &mut s.fft);
            // sum_j F cos = Re y / 2, sum_j G sin = -Im y / 2 (y = Y conj(phase)), times l / M;
            // the slope factor -(pi / l) i of d th_z / d q: folded into from_spectrum
            for ((&i, &(alpha, beta)), o) in self.indices.iter().zip(&self.from_spectrum).zip(out.iter_mut()) {
                let y = s.spectrum[i as usize];
                *o += alpha * y.re + beta * y.im;
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

    #[test]
    fn the_density_and_its_partials_are_the_sums_over_the_terms() {
        let terms: Vec<EnergyTerm> = crate::terms::EQ18_TERMS
            .iter()
            .zip([3.0, 5.0, -7.0, 11.0, 13.0])
            .filter(|(spec, _)| spec.p + spec.r == 4)
            .map(|(spec, k)| spec.with(k).unwrap())
            .collect();
        assert_eq!(terms.len(), 3);
        let sys = SpectralQuartic::new(vec![1, 2], 2.0, terms.clone()).unwrap();
        for (th, th_z) in [(0.3, -0.7), (-1.1, 0.4), (0.0, 0.9), (2.0, 0.0)] {
            let density: f64 = terms.iter().map(|t| t.density(th, th_z)).sum();
            let (f, g) = terms.iter().fold((0.0, 0.0), |(f, g), t| {
                let (a, b) = t.partials(th, th_z);
                (f + a, g + b)
            });
            let (sf, sg) = sys.partials(th, th_z);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * (1.0 + b.abs());
            assert!(close(sys.density(th, th_z), density) && close(sf, f) && close(sg, g));
        }
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

//! Explicit Runge-Kutta tableaux as data, and the stage storage they act on.
//!
//! An explicit `s`-stage method (Hairer, Norsett, Wanner, *Solving ODEs I*, sec. II.1) is
//!
//! ```text
//! k_i   = f(t + c_i h, y + h sum_{j<i} a_ij k_j),   i = 0 .. s-1
//! y_new = y + h sum_i b_i k_i
//! ```
//!
//! [`Tableau`] stores `c`, the strictly lower triangle of `a` row by row and `b`; the
//! evaluation skips zero coefficients, so the sparse DOP853 rows cost only their
//! non-zeros. [`Stages`] holds the `k_i` contiguously and is allocated once per solve.

use crate::simd::{dispatch, Kernel, MulAdd, MIN_DISPATCH_LEN};
use crate::system::OdeSystem;

/// The Butcher tableau of an explicit Runge-Kutta method.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tableau {
    /// Nodes `c_i`, one per stage (`c_0 = 0`).
    pub c: &'static [f64],
    /// Row `i` holds `a_i0 .. a_i,i-1` (row 0 is empty).
    pub a: &'static [&'static [f64]],
    /// Weights `b_i` of the propagated solution.
    pub b: &'static [f64],
}

/// The classical fourth-order Runge-Kutta method (Kutta 1901).
pub(crate) const RK4: Tableau = Tableau {
    c: &[0.0, 0.5, 0.5, 1.0],
    a: &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

impl Tableau {
    /// Number of stages.
    pub fn stages(&self) -> usize {
        self.c.len()
    }

    /// Evaluates stages `1 .. s` of a step `(t, y) -> t + h`; `k` row 0 must already hold
    /// `f(t, y)`. Returns the number of right-hand-side evaluations (`s - 1`).
    pub fn eval_stages<S: OdeSystem + ?Sized>(
        &self,
        sys: &S,
        t: f64,
        h: f64,
        y: &[f64],
        k: &mut Stages,
        ytmp: &mut [f64],
    ) -> u64 {
        for s in 1..self.stages() {
            k.eval_stage(sys, s, t + self.c[s] * h, h, y, self.a[s], ytmp);
        }
        (self.stages() - 1) as u64
    }

    /// `y_new = y + h sum_i b_i k_i`.
    pub fn advance(&self, h: f64, y: &[f64], k: &Stages, y_new: &mut [f64]) {
        k.axpy_combine(y, h, self.b, y_new);
    }
}

/// Components per block of the stage combinations, baseline code: sixteen partial sums in
/// eight SSE2 registers keep both floating-point add ports busy.
const BLOCK: usize = 16;

/// Components per block with AVX2 + FMA: eight 4-wide accumulators cover the FMA latency
/// on both ports.
const WIDE_BLOCK: usize = 32;

/// The kernel of [`Stages::combine`] and [`Stages::axpy_combine`].
struct Combination<'a> {
    k: &'a Stages,
    coef: &'a [f64],
    /// `(y, h)`: `out = y + h sum`; `None`: `out = sum`.
    base: Option<(&'a [f64], f64)>,
    /// `(x, c)`: `c x` added to the result.
    extra: Option<(&'a [f64], f64)>,
    out: &'a mut [f64],
}

impl Kernel for Combination<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: MulAdd>(self) {
        let Combination { k, coef, base, extra, out } = self;
        if M::WIDE {
            k.chunked::<M, WIDE_BLOCK>(coef, base, extra, out)
        } else {
            k.chunked::<M, BLOCK>(coef, base, extra, out)
        }
    }
}

/// Most terms of a combination (the rows of the largest stage storage, RKN12's 17).
const MAX_TERMS: usize = 17;

/// The non-zero coefficients of a combination `sum_j coef_j k_j` and their rows.
struct Terms {
    rows: [usize; MAX_TERMS],
    coefs: [f64; MAX_TERMS],
    len: usize,
}

impl Terms {
    #[inline(always)]
    fn new(coef: &[f64]) -> Self {
        assert!(coef.len() <= MAX_TERMS, "a combination of {} stages exceeds {MAX_TERMS}", coef.len());
        let mut terms = Terms { rows: [0; MAX_TERMS], coefs: [0.0; MAX_TERMS], len: 0 };
        for (j, &a) in coef.iter().enumerate() {
            if a != 0.0 {
                terms.rows[terms.len] = j;
                terms.coefs[terms.len] = a;
                terms.len += 1;
            }
        }
        terms
    }
}

/// The stage vectors `k_0, k_1, ...` of one step, `rows x dim`, contiguous.
#[derive(Debug, Clone)]
pub(crate) struct Stages {
    data: Vec<f64>,
    dim: usize,
}

impl Stages {
    pub fn new(rows: usize, dim: usize) -> Self {
        Stages { data: vec![0.0; rows * dim], dim }
    }

    pub fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.dim..(i + 1) * self.dim]
    }

    pub fn row_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.dim..(i + 1) * self.dim]
    }

    /// Copies row `from` into row `to`.
    pub fn copy_row(&mut self, from: usize, to: usize) {
        let dim = self.dim;
        self.data.copy_within(from * dim..(from + 1) * dim, to * dim);
    }

    /// `out = sum_j coef_j k_j`, skipping zero coefficients.
    pub fn combine(&self, coef: &[f64], out: &mut [f64]) {
        if self.dim < MIN_DISPATCH_LEN {
            self.small(coef, out, |_, acc| acc);
        } else {
            dispatch(Combination { k: self, coef, base: None, extra: None, out });
        }
    }

    /// `out = y + h sum_j coef_j k_j`, skipping zero coefficients.
    pub fn axpy_combine(&self, y: &[f64], h: f64, coef: &[f64], out: &mut [f64]) {
        if self.dim < MIN_DISPATCH_LEN {
            let y = &y[..self.dim];
            self.small(coef, out, |i, acc| y[i] + h * acc);
        } else {
            dispatch(Combination { k: self, coef, base: Some((y, h)), extra: None, out });
        }
    }

    /// `out = y + c x + h sum_j coef_j k_j`, skipping zero coefficients.
    #[allow(clippy::too_many_arguments)]
    pub fn axpy_combine_plus(&self, y: &[f64], h: f64, coef: &[f64], x: &[f64], c: f64, out: &mut [f64]) {
        if self.dim < MIN_DISPATCH_LEN {
            let (y, x) = (&y[..self.dim], &x[..self.dim]);
            self.small(coef, out, |i, acc| y[i] + c * x[i] + h * acc);
        } else {
            dispatch(Combination { k: self, coef, base: Some((y, h)), extra: Some((x, c)), out });
        }
    }

    /// The combinations of a few components (a modal system of a few modes): in chunks of
    /// up to four whose partial sums stay in registers, zero coefficients skipped inline,
    /// `out[i] = finish(i, sum_j coef_j k_j[i])`. Without the set-up of the blocked
    /// [`Combination`] (its list of non-zero terms): the 3-mode DOP853 bench
    /// (`cargo bench --bench integrators dop853/3-mode`) takes 1.94-2.15 ms with this path
    /// and 2.30-2.39 ms with `Combination` run inline as baseline code.
    #[inline(always)]
    fn small(&self, coef: &[f64], out: &mut [f64], finish: impl Fn(usize, f64) -> f64) {
        let dim = self.dim;
        let k = &self.data[..coef.len() * dim];
        // The first-order form `[q, v]` of a system of two to four coordinates in two halves:
        // each half is stored (and loaded) as the system's evaluation loads (and stores) it.
        // Chunks of four and two put `v` of three coordinates across two stores.
        if dim % 2 == 0 && (4..=8).contains(&dim) {
            let half = dim / 2;
            for i0 in [0, half] {
                match half {
                    2 => Self::chunk::<2>(k, dim, i0, coef, out, &finish),
                    3 => Self::chunk::<3>(k, dim, i0, coef, out, &finish),
                    _ => Self::chunk::<4>(k, dim, i0, coef, out, &finish),
                };
            }
            return;
        }
        let mut i0 = 0;
        while i0 < dim {
            // Fixed-size chunks: the loops over the chunk unroll (a chunk of run-time width
            // was a loop of its own for every stage row, measured 2-3 times the cost of the
            // 3-mode RKN12 step's combinations).
            i0 += match dim - i0 {
                1 => Self::chunk::<1>(k, dim, i0, coef, out, &finish),
                2 => Self::chunk::<2>(k, dim, i0, coef, out, &finish),
                3 => Self::chunk::<3>(k, dim, i0, coef, out, &finish),
                _ => Self::chunk::<4>(k, dim, i0, coef, out, &finish),
            };
        }
    }

    /// Components `i0 .. i0 + W` of [`Stages::small`]; returns `W`.
    #[inline(always)]
    fn chunk<const W: usize>(
        k: &[f64],
        dim: usize,
        i0: usize,
        coef: &[f64],
        out: &mut [f64],
        finish: &impl Fn(usize, f64) -> f64,
    ) -> usize {
        let mut acc = [0.0; W];
        for (j, &a) in coef.iter().enumerate() {
            if a != 0.0 {
                let row: &[f64; W] = k[j * dim + i0..j * dim + i0 + W].try_into().expect("chunk of W components");
                for (s, &kj) in acc.iter_mut().zip(row) {
                    *s += a * kj;
                }
            }
        }
        // One store of the chunk, not one per component: the evaluation that reads it next
        // loads pairs of components, and a load spanning two stores waits until both have
        // been written to the cache (about a fifth of a 3-mode RKN12 step before this).
        let done: [f64; W] = std::array::from_fn(|l| finish(i0 + l, acc[l]));
        out[i0..i0 + W].copy_from_slice(&done);
        W
    }

    /// `out = sum_j coef_j k_j` or, with `base = (y, h)`, `out = y + h sum_j coef_j k_j`;
    /// zero coefficients skipped.
    ///
    /// The components go in blocks of `B` whose partial sums stay in registers while the
    /// stage rows stream past: enough independent sums to hide the latency of the
    /// floating-point adds (a block of four is latency-bound, a row-outer loop sends every
    /// partial sum through memory). A tail shorter than a block goes in sixteens, fours, then ones.
    #[inline(always)]
    fn chunked<M: MulAdd, const B: usize>(
        &self,
        coef: &[f64],
        base: Option<(&[f64], f64)>,
        extra: Option<(&[f64], f64)>,
        out: &mut [f64],
    ) {
        let mut terms = Terms::new(coef);
        let dim = self.dim;
        let out = &mut out[..dim];
        // y + h sum_j a_j k_j is summed as y + sum_j (h a_j) k_j: no separate final pass.
        let base = base.map(|(y, h)| {
            terms.coefs.iter_mut().for_each(|a| *a *= h);
            &y[..dim]
        });
        let extra = extra.map(|(x, c)| (&x[..dim], c));
        let mut i0 = 0;
        while i0 + B <= dim {
            self.block::<M, B>(&terms, i0, base, extra, out);
            i0 += B;
        }
        if B > 16 && i0 + 16 <= dim {
            self.block::<M, 16>(&terms, i0, base, extra, out);
            i0 += 16;
        }
        while i0 + 4 <= dim {
            self.block::<M, 4>(&terms, i0, base, extra, out);
            i0 += 4;
        }
        while i0 < dim {
            self.block::<M, 1>(&terms, i0, base, extra, out);
            i0 += 1;
        }
    }

    /// Components `i0 .. i0 + B` of [`Stages::chunked`]: the partial sums start from the
    /// base (`y`, or zero) and take the (already `h`-scaled) terms; fixed-size arrays
    /// throughout, so the loops unroll into vector instructions without run-time checks.
    #[inline(always)]
    fn block<M: MulAdd, const B: usize>(
        &self,
        terms: &Terms,
        i0: usize,
        base: Option<&[f64]>,
        extra: Option<(&[f64], f64)>,
        out: &mut [f64],
    ) {
        let mut acc: [f64; B] = match base {
            Some(y) => *<&[f64; B]>::try_from(&y[i0..i0 + B]).expect("block of B components"),
            None => [0.0; B],
        };
        if let Some((x, c)) = extra {
            let x: &[f64; B] = x[i0..i0 + B].try_into().expect("block of B components");
            for (s, &xi) in acc.iter_mut().zip(x) {
                *s = M::mul_add(c, xi, *s);
            }
        }
        for (&row, &a) in terms.rows[..terms.len].iter().zip(&terms.coefs[..terms.len]) {
            let start = row * self.dim + i0;
            let k: &[f64; B] = self.data[start..start + B].try_into().expect("block of B components");
            for (s, &kj) in acc.iter_mut().zip(k) {
                *s = M::mul_add(a, kj, *s);
            }
        }
        *<&mut [f64; B]>::try_from(&mut out[i0..i0 + B]).expect("block of B components") = acc;
    }

    /// Stage `s`: `k_s = f(t_s, y + h sum_{j < a.len()} a_j k_j)` with `a.len() <= s`.
    #[allow(clippy::too_many_arguments)]
    pub fn eval_stage<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        s: usize,
        t_s: f64,
        h: f64,
        y: &[f64],
        a: &[f64],
        ytmp: &mut [f64],
    ) {
        debug_assert!(a.len() <= s);
        self.axpy_combine(y, h, a, ytmp);
        sys.rhs(t_s, ytmp, self.row_mut(s));
    }
}

/// Whether every component is finite.
pub(crate) fn all_finite(y: &[f64]) -> bool {
    y.iter().all(|v| v.is_finite())
}

/// Test helper: the row sums of `a` equal `c` and the weights sum to one (order-1 conditions).
#[cfg(test)]
pub(crate) fn check_consistency(tab: &Tableau, tol: f64) {
    assert_eq!(tab.a.len(), tab.stages());
    for (i, row) in tab.a.iter().enumerate() {
        assert!(row.len() <= i, "row {i} is not strictly lower triangular");
        let sum: f64 = row.iter().sum();
        assert!((sum - tab.c[i]).abs() < tol, "row {i}: sum {sum} vs c {}", tab.c[i]);
    }
    let bsum: f64 = tab.b.iter().sum();
    assert!((bsum - 1.0).abs() < tol, "sum b = {bsum}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rk4_is_consistent() {
        check_consistency(&RK4, 1e-15);
    }

    #[test]
    fn combine_sums() {
        let mut k = Stages::new(3, 2);
        k.row_mut(0).copy_from_slice(&[1.0, 2.0]);
        k.row_mut(1).copy_from_slice(&[-4.0, 8.0]);
        k.row_mut(2).copy_from_slice(&[10.0, 20.0]);
        let mut out = [0.0; 2];
        k.combine(&[2.0, 0.0, 0.5], &mut out);
        assert_eq!(out, [7.0, 14.0]);
        k.axpy_combine(&[1.0, -1.0], 2.0, &[2.0, 1.0], &mut out);
        assert_eq!(out, [1.0 + 2.0 * (2.0 - 4.0), -1.0 + 2.0 * (4.0 + 8.0)]);
        k.copy_row(2, 0);
        assert_eq!(k.row(0), &[10.0, 20.0]);
    }

    /// Every block width and tail (dims across multiples of 32, 16 and 4), the small
    /// systems' chunks (halves for dims 4 to 8) and both code paths of [`crate::simd`], against
    /// a plain row-by-row sum.
    #[test]
    fn blocked_combinations_match_the_plain_sum() {
        let coef = [0.3, 0.0, -1.25, 0.0, 2.5, 1e-3, 0.0, -0.7, 0.9, 0.0, 0.0, 4.0, -2.0, 0.5, 0.0, 1.5];
        for dim in [1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 32, 33, 36, 63, 64, 67, 480, 483] {
            let mut k = Stages::new(coef.len(), dim);
            for j in 0..coef.len() {
                for (i, v) in k.row_mut(j).iter_mut().enumerate() {
                    *v = ((j * 131 + i * 17) as f64 * 0.013).sin();
                }
            }
            let y: Vec<f64> = (0..dim).map(|i| (i as f64 * 0.7).cos()).collect();
            let h = 0.37;
            let expected_sum: Vec<f64> =
                (0..dim).map(|i| coef.iter().enumerate().map(|(j, &a)| a * k.row(j)[i]).sum()).collect();
            let mut out = vec![f64::NAN; dim];
            for terms in [&coef[..], &coef[..7], &coef[..1]] {
                let plain: Vec<f64> =
                    (0..dim).map(|i| terms.iter().enumerate().map(|(j, &a)| a * k.row(j)[i]).sum()).collect();
                k.combine(terms, &mut out);
                assert_close(&out, &plain, dim);
                crate::simd::baseline(Combination { k: &k, coef: terms, base: None, extra: None, out: &mut out });
                assert_close(&out, &plain, dim);
            }
            let expected_axpy: Vec<f64> = y.iter().zip(&expected_sum).map(|(&yi, &s)| yi + h * s).collect();
            k.axpy_combine(&y, h, &coef, &mut out);
            assert_close(&out, &expected_axpy, dim);
            crate::simd::baseline(Combination { k: &k, coef: &coef, base: Some((&y, h)), extra: None, out: &mut out });
            assert_close(&out, &expected_axpy, dim);
            let x: Vec<f64> = (0..dim).map(|i| (i as f64 * 0.3).sin()).collect();
            let expected_plus: Vec<f64> = expected_axpy.iter().zip(&x).map(|(&e, &xi)| e - 0.6 * xi).collect();
            k.axpy_combine_plus(&y, h, &coef, &x, -0.6, &mut out);
            assert_close(&out, &expected_plus, dim);
            let extra = Some((&x[..], -0.6));
            crate::simd::baseline(Combination { k: &k, coef: &coef, base: Some((&y, h)), extra, out: &mut out });
            assert_close(&out, &expected_plus, dim);
        }
    }

    fn assert_close(got: &[f64], expected: &[f64], dim: usize) {
        for (i, (g, e)) in got.iter().zip(expected).enumerate() {
            assert!((g - e).abs() <= 1e-14 * (1.0 + e.abs()), "dim {dim}, component {i}: {g} vs {e}");
        }
    }
}

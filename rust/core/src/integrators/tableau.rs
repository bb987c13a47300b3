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
        self.chunked(coef, out, |_, acc| acc);
    }

    /// `out = y + h sum_j coef_j k_j`, skipping zero coefficients.
    pub fn axpy_combine(&self, y: &[f64], h: f64, coef: &[f64], out: &mut [f64]) {
        let y = &y[..self.dim];
        self.chunked(coef, out, |i, acc| y[i] + h * acc);
    }

    /// `out[i] = finish(i, sum_j coef_j k_j[i])` in chunks of four components whose partial
    /// sums stay in registers (a plain row-outer loop sends every partial sum through
    /// memory); zero coefficients, frequent in DOP853, are skipped.
    #[inline(always)]
    fn chunked(&self, coef: &[f64], out: &mut [f64], finish: impl Fn(usize, f64) -> f64) {
        const W: usize = 4;
        let dim = self.dim;
        let k = &self.data[..coef.len() * dim];
        let mut i0 = 0;
        while i0 < dim {
            let w = W.min(dim - i0);
            let mut acc = [0.0; W];
            for (j, &a) in coef.iter().enumerate() {
                if a != 0.0 {
                    let row = &k[j * dim + i0..j * dim + i0 + w];
                    for (s, &kj) in acc.iter_mut().zip(row) {
                        *s += a * kj;
                    }
                }
            }
            for (l, &s) in acc[..w].iter().enumerate() {
                out[i0 + l] = finish(i0 + l, s);
            }
            i0 += w;
        }
    }

    /// Component `i` of `sum_j coef_j k_j`.
    #[inline]
    pub fn combine_at(&self, coef: &[f64], i: usize) -> f64 {
        let k = &self.data[..coef.len() * self.dim];
        let mut sum = 0.0;
        for (j, &a) in coef.iter().enumerate() {
            sum += a * k[j * self.dim + i];
        }
        sum
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
        assert_eq!(k.combine_at(&[2.0, 0.0, 0.5], 1), 14.0);
        k.axpy_combine(&[1.0, -1.0], 2.0, &[2.0, 1.0], &mut out);
        assert_eq!(out, [1.0 + 2.0 * (2.0 - 4.0), -1.0 + 2.0 * (4.0 + 8.0)]);
        k.copy_row(2, 0);
        assert_eq!(k.row(0), &[10.0, 20.0]);
    }
}

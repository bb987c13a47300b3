//! Dormand-Prince 5(4) (`DOPRI5`): coefficients, error estimate and the 4th-order
//! continuous extension (Hairer, Norsett, Wanner, *Solving ODEs I*, sec. II.5-II.6;
//! Dormand & Prince 1980, dense output of Shampine 1986).
//!
//! Seven stages with FSAL: stage 6 is `f(t + h, y_new)` (its `a` row equals `b`). The
//! error `e = h sum_i E_i k_i` over all seven stages is measured in Hairer's scaled RMS
//! norm. Coefficients as in scipy's `RK45` (`scipy/integrate/_ivp/rk.py`).

use super::adaptive::{scaled_sums, Attempt, Control, Scheme};
use super::form::Form;
use super::tableau::{Stages, Tableau};

/// Selects `k_6 = f(t + h, y_new)` (the FSAL row) in a combination.
const F1: [f64; 7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];

/// The Dormand-Prince 5(4) pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dopri5;

const C: [f64; 6] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];

const A: [&[f64]; 6] = [
    &[],
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0],
    &[9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0],
];

/// 5th-order weights (also the `a` row of the FSAL stage).
const B: [f64; 6] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0];

/// Error weights `b_hat - b` over the seven stages (scipy's `E`; Hairer's `e1..e7` up to sign).
pub(crate) const E: [f64; 7] =
    [-71.0 / 57600.0, 0.0, 71.0 / 16695.0, -71.0 / 1920.0, 17253.0 / 339200.0, -22.0 / 525.0, 1.0 / 40.0];

/// The dense-output matrix `P` of scipy's `RK45`: `y(t + theta h) = y + h sum_i k_i
/// sum_j P[i][j] theta^(j+1)`.
#[cfg(test)]
pub(crate) const P: [[f64; 4]; 7] = [
    [1.0, -8048581381.0 / 2820520608.0, 8663915743.0 / 2820520608.0, -12715105075.0 / 11282082432.0],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200.0 / 32700410799.0, -68118460800.0 / 10900136933.0, 87487479700.0 / 32700410799.0],
    [0.0, -1754552775.0 / 470086768.0, 14199869525.0 / 1410260304.0, -10690763975.0 / 1880347072.0],
    [0.0, 127303824393.0 / 49829197408.0, -318862633887.0 / 49829197408.0, 701980252875.0 / 199316789632.0],
    [0.0, -282668133.0 / 205662961.0, 2019193451.0 / 616988883.0, -1453857185.0 / 822651844.0],
    [0.0, 40617522.0 / 29380423.0, -110615467.0 / 29380423.0, 69997945.0 / 29380423.0],
];

/// Hairer's `d1 .. d7`: the `theta^4` coefficients of the interpolant, i.e. the last
/// column of scipy's `P`.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

impl Scheme for Dopri5 {
    const TABLEAU: Tableau = Tableau { c: &C, a: &A, b: &B };
    /// Hairer's defaults: `safe = 0.9`, `fac1 = 0.2`, `fac2 = 10`, `beta = 0.04`,
    /// `expo1 = 1/5 - 0.75 beta`.
    const CONTROL: Control =
        Control { safe: 0.9, fac1: 0.2, fac2: 10.0, beta: 0.04, expo1: 0.2 - 0.04 * 0.75, hinit_order: 5 };
    const ROWS: usize = 7;
    const FSAL: usize = 6;
    const FSAL_IN_ERROR: bool = true;
    const DENSE_ROWS: usize = 4;
    const EXTRA_INPUTS: &'static [&'static [f64]] = &[];

    /// `err = sqrt(1/n sum_i (h sum_j E_j k_j,i / sc_i)^2)`.
    fn error_norm<F: Form>(form: &F, k: &Stages, step: &Attempt<'_>, work: &mut [f64]) -> f64 {
        let Attempt { h, y, y_new, rtol, atol } = *step;
        let e = &mut work[..y.len()];
        form.combine(k, &E, h, y, e);
        let (sum, _) = scaled_sums(e, e, y, y_new, rtol, atol);
        let sum = h * h * sum;
        (sum / y.len() as f64).sqrt()
    }

    /// Hairer's `cont5`: with `D = y_new - y`,
    /// `r1 = D`, `r2 = h f_0 - D`, `r3 = D - h f_1 - r2`, `r4 = h sum_j d_j k_j`.
    fn dense_prepare<F: Form>(
        form: &F,
        _t: f64,
        h: f64,
        y: &[f64],
        y_new: &[f64],
        k: &mut Stages,
        _ytmp: &mut [f64],
        dense: &mut Stages,
    ) -> u64 {
        // f_0 and f_1 = f(t + h, y_new) into rows 1 and 2, then the rows in place.
        form.combine(k, &[1.0], h, y, dense.row_mut(1));
        form.combine(k, &F1, h, y, dense.row_mut(2));
        for i in 0..y.len() {
            let d = y_new[i] - y[i];
            let r2 = h * dense.row(1)[i] - d;
            let f1 = dense.row(2)[i];
            dense.row_mut(0)[i] = d;
            dense.row_mut(1)[i] = r2;
            dense.row_mut(2)[i] = d - h * f1 - r2;
        }
        form.combine(k, &D, h, y, dense.row_mut(3));
        dense.row_mut(3).iter_mut().for_each(|v| *v *= h);
        0
    }

    /// `u(theta) = y + theta (r1 + (1 - theta) (r2 + theta (r3 + (1 - theta) r4)))`.
    fn dense_eval(dense: &Stages, y: &[f64], theta: f64, out: &mut [f64]) {
        let theta1 = 1.0 - theta;
        let n = out.len();
        let (r1, r2, r3, r4) = (&dense.row(0)[..n], &dense.row(1)[..n], &dense.row(2)[..n], &dense.row(3)[..n]);
        let y = &y[..n];
        for i in 0..n {
            out[i] = y[i] + theta * (r1[i] + theta1 * (r2[i] + theta * (r3[i] + theta1 * r4[i])));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::form::Plain;
    use crate::integrators::tableau::check_consistency;

    #[test]
    fn tableau_is_consistent() {
        check_consistency(&Dopri5::TABLEAU, 1e-14);
        let e_sum: f64 = E.iter().sum();
        assert!(e_sum.abs() < 1e-15);
        // FSAL: the last stage is at c = 1 and its row equals b.
        assert_eq!(C[5], 1.0);
        assert_eq!(B.len(), 6);
    }

    /// Hairer's nested form with `d = P[:, 3]` is the same polynomial as scipy's `P` form.
    #[test]
    fn dense_output_matches_scipy_p_matrix() {
        let dim = 2;
        let mut k = Stages::new(7, dim);
        for j in 0..7 {
            k.row_mut(j).copy_from_slice(&[(j as f64 * 0.7).sin(), (j as f64 * 1.3).cos()]);
        }
        let h = 0.3;
        let y = [0.4, -1.2];
        let mut y_new = [0.0; 2];
        Dopri5::TABLEAU.advance(h, &y, &k, &mut y_new);
        let mut dense = Stages::new(4, dim);
        let mut ytmp = [0.0; 2];
        let sys = crate::integrators::tests::Decay;
        Dopri5::dense_prepare(&Plain(&sys), 0.0, h, &y, &y_new, &mut k, &mut ytmp, &mut dense);
        let mut out = [0.0; 2];
        for step in 0..=8 {
            let theta = step as f64 / 8.0;
            Dopri5::dense_eval(&dense, &y, theta, &mut out);
            for i in 0..dim {
                let mut p = 0.0;
                for (j, row) in P.iter().enumerate() {
                    let poly: f64 = row.iter().enumerate().map(|(m, c)| c * theta.powi(m as i32 + 1)).sum();
                    p += k.row(j)[i] * poly;
                }
                let expected = y[i] + h * p;
                assert!((out[i] - expected).abs() < 1e-14, "theta {theta}: {} vs {expected}", out[i]);
            }
        }
    }
}

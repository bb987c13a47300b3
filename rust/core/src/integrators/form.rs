//! The two forms in which the adaptive pairs advance a system.
//!
//! * [`Plain`]: any first-order system `y' = f(t, y)`; stage row `j` holds `k_j` over the
//!   whole state.
//! * [`Nystrom`]: an autonomous second-order system `q'' = a(q)` advanced as the first-order
//!   system `y = [q, v]`, `y' = [v, a(q)]`, without ever forming the `q`-half of a stage.
//!   Stage row `j` holds only `K_j = a(Q_j)`. With `A^` the coefficients that build the input
//!   of every stored row (the tableau's `a`, `b` for the FSAL row, the dense-output stages)
//!   the `q`-half of `k_j` is `V_j = v + h sum_l A^_jl K_l`, hence
//!
//!   ```text
//!   Q_i             = q + h c_i v + h^2 sum_l (A^ A^)_il K_l,
//!   sum_j w_j k_j   = [ (sum_j w_j) v + h sum_l (w A^)_l K_l ,  sum_j w_j K_j ],
//!   ```
//!
//!   the Runge-Kutta-Nystrom form of the same method (Hairer, Norsett, Wanner, *Solving
//!   ODEs I*, sec. II.14): equal to the first-order form up to rounding, with stage rows half
//!   as long and only the positions combined per stage.
//!
//! The adaptive loop ([`super::adaptive`]) and the pairs' error estimates and dense outputs
//! see only this interface; every combination they form is over the whole state.

use super::tableau::Stages;
use crate::system::{OdeSystem, SecondOrderSystem};

/// How the stages of an explicit Runge-Kutta step are evaluated, stored and combined.
pub(crate) trait Form {
    /// Length of the state `y`.
    fn dim(&self) -> usize;
    /// Length of a stage row.
    fn row_len(&self) -> usize;
    /// `dydt = f(t, y)` over the whole state.
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]);
    /// Row `row` of `k`: the stage derivative at the state `y` (time `t`).
    fn eval_at(&self, k: &mut Stages, row: usize, t: f64, y: &[f64]);
    /// Row `s` of `k`: the derivative at `y + h sum_j a_j k_j`, where `a` is the input row
    /// `s` of the scheme (see [`Nystrom::new`]). `ytmp` (length `dim`) is scratch.
    #[allow(clippy::too_many_arguments)]
    fn eval_stage(&self, k: &mut Stages, s: usize, t_s: f64, h: f64, y: &[f64], a: &[f64], ytmp: &mut [f64]);
    /// `out = sum_j coef_j k_j` over the whole state, for the step of size `h` from `y`.
    fn combine(&self, k: &Stages, coef: &[f64], h: f64, y: &[f64], out: &mut [f64]);
    /// `out = y + h sum_j coef_j k_j`; `scratch` (length `dim`) is overwritten.
    fn advance(&self, k: &Stages, coef: &[f64], h: f64, y: &[f64], out: &mut [f64], scratch: &mut [f64]);
}

/// A first-order system, stages over the whole state.
pub(crate) struct Plain<'a, S: ?Sized>(pub &'a S);

impl<S: OdeSystem + ?Sized> Form for Plain<'_, S> {
    fn dim(&self) -> usize {
        self.0.dim()
    }

    fn row_len(&self) -> usize {
        self.0.dim()
    }

    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        self.0.rhs(t, y, dydt);
    }

    fn eval_at(&self, k: &mut Stages, row: usize, t: f64, y: &[f64]) {
        self.0.rhs(t, y, k.row_mut(row));
    }

    #[inline]
    fn eval_stage(&self, k: &mut Stages, s: usize, t_s: f64, h: f64, y: &[f64], a: &[f64], ytmp: &mut [f64]) {
        k.eval_stage(self.0, s, t_s, h, y, a, ytmp);
    }

    fn combine(&self, k: &Stages, coef: &[f64], _h: f64, _y: &[f64], out: &mut [f64]) {
        k.combine(coef, out);
    }

    fn advance(&self, k: &Stages, coef: &[f64], h: f64, y: &[f64], out: &mut [f64], _scratch: &mut [f64]) {
        k.axpy_combine(y, h, coef, out);
    }
}

/// Most stored rows of a scheme (DOP853: 12 stages, the FSAL row, 3 dense-output stages).
const MAX_ROWS: usize = 16;

/// A second-order system `q'' = a(q)`, state `y = [q, v]`, stage rows `K_j = a(Q_j)`.
pub(crate) struct Nystrom<'a, S: ?Sized> {
    sys: &'a S,
    dof: usize,
    rows: usize,
    /// `A^`, `rows x rows`, row-major: the input coefficients of every stored row.
    a_hat: [[f64; MAX_ROWS]; MAX_ROWS],
    /// `A^ A^`, the `h^2` coefficients of the stage positions.
    a_hat2: [[f64; MAX_ROWS]; MAX_ROWS],
    /// Row sums of `A^` (the nodes `c_i`, as the first-order form sums them).
    c: [f64; MAX_ROWS],
}

impl<'a, S: SecondOrderSystem + ?Sized> Nystrom<'a, S> {
    /// `inputs[r]` builds the input of stored row `r` (`inputs[r].len() <= r`): the tableau's
    /// rows for the stages, `b` for the FSAL row, the extra rows of a dense output; an
    /// empty slice for a row that is only ever evaluated at a given state (row 0).
    pub fn new(sys: &'a S, inputs: &[&[f64]]) -> Self {
        let rows = inputs.len();
        assert!(rows <= MAX_ROWS, "{rows} stored rows exceed {MAX_ROWS}");
        let mut a_hat = [[0.0; MAX_ROWS]; MAX_ROWS];
        let mut c = [0.0; MAX_ROWS];
        for (r, input) in inputs.iter().enumerate() {
            assert!(input.len() <= r, "row {r} is not strictly lower triangular");
            a_hat[r][..input.len()].copy_from_slice(input);
            c[r] = input.iter().sum();
        }
        let mut a_hat2 = [[0.0; MAX_ROWS]; MAX_ROWS];
        for i in 0..rows {
            for l in 0..rows {
                a_hat2[i][l] = (0..rows).map(|j| a_hat[i][j] * a_hat[j][l]).sum();
            }
        }
        Nystrom { sys, dof: sys.dof(), rows, a_hat, a_hat2, c }
    }

    /// `(w A^, sum_j w_j)` for the weights `w` of a combination.
    fn position_weights(&self, coef: &[f64]) -> ([f64; MAX_ROWS], f64) {
        let mut wa = [0.0; MAX_ROWS];
        for (&w, row) in coef.iter().zip(&self.a_hat) {
            if w != 0.0 {
                for (s, &a) in wa.iter_mut().zip(&row[..self.rows]) {
                    *s += w * a;
                }
            }
        }
        (wa, coef.iter().sum())
    }
}

impl<S: SecondOrderSystem + ?Sized> Form for Nystrom<'_, S> {
    fn dim(&self) -> usize {
        2 * self.dof
    }

    fn row_len(&self) -> usize {
        self.dof
    }

    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let (q, v) = y.split_at(self.dof);
        let (dq, dv) = dydt.split_at_mut(self.dof);
        dq.copy_from_slice(v);
        self.sys.acceleration(q, dv);
    }

    fn eval_at(&self, k: &mut Stages, row: usize, _t: f64, y: &[f64]) {
        self.sys.acceleration(&y[..self.dof], k.row_mut(row));
    }

    /// `Q_s = q + h c_s v + h^2 sum_l (A^ A^)_sl K_l`, then `K_s = a(Q_s)`.
    #[inline]
    fn eval_stage(&self, k: &mut Stages, s: usize, _t_s: f64, h: f64, y: &[f64], a: &[f64], ytmp: &mut [f64]) {
        debug_assert!(a.iter().zip(&self.a_hat[s]).all(|(x, y)| x == y), "row {s} is not the scheme's");
        let (q, v) = y.split_at(self.dof);
        let q_s = &mut ytmp[..self.dof];
        k.axpy_combine_plus(q, h * h, &self.a_hat2[s][..self.rows], v, h * self.c[s], q_s);
        self.sys.acceleration(q_s, k.row_mut(s));
    }

    fn combine(&self, k: &Stages, coef: &[f64], h: f64, y: &[f64], out: &mut [f64]) {
        let (out_q, out_v) = out.split_at_mut(self.dof);
        k.combine(coef, out_v);
        let (wa, sum) = self.position_weights(coef);
        k.combine(&wa[..self.rows], out_q);
        for (o, &vi) in out_q.iter_mut().zip(&y[self.dof..]) {
            *o = sum * vi + h * *o;
        }
    }

    fn advance(&self, k: &Stages, coef: &[f64], h: f64, y: &[f64], out: &mut [f64], _scratch: &mut [f64]) {
        let (q, v) = y.split_at(self.dof);
        let (out_q, out_v) = out.split_at_mut(self.dof);
        k.axpy_combine(v, h, coef, out_v);
        let (wa, sum) = self.position_weights(coef);
        k.axpy_combine_plus(q, h * h, &wa[..self.rows], v, h * sum, out_q);
    }
}

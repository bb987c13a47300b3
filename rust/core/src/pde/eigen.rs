//! Linear frequencies of the discretised PDE.
//!
//! Linearised about `th = 0` the nodal system is `M q'' + K q = 0` with the lumped mass
//! `M = diag(w_j k1)` and `K = (k2 / h) L - diag(w_j k6)`, `L` the path-graph Laplacian
//! (`L_jj` = 1 at the ends, 2 inside, `L_{j,j+1} = -1`). Its squared frequencies are the
//! eigenvalues of the symmetric tridiagonal `A = M^{-1/2} K M^{-1/2}`. Since
//! `diag(w_j k6)` is `k6 / k1` times `M`,
//!
//! ```text
//! A = c B - (k6 / k1) I,   c = k2 / (k1 h^2),   B = W^{-1/2} L W^{-1/2},   W = diag(w_j / h),
//! ```
//!
//! and `B = R^T R` with the weighted gradient `R = G W^{-1/2}` (`G` the `(N-1) x N`
//! difference matrix, `R_{c,c} = -1/sqrt(w_c/h)`, `R_{c,c+1} = 1/sqrt(w_{c+1}/h)`). So the
//! spectrum of `B` is `0` (the uniform twist, mode `i = 0`, exactly) together with the
//! spectrum of the `(N-1) x (N-1)` positive definite tridiagonal
//!
//! ```text
//! R R^T = tridiag(-1, [3, 2, ..., 2, 3], -1)    (N - 1 >= 2)
//! ```
//!
//! whose eigenvalues faer's tridiagonal QR algorithm computes to high relative accuracy.
//! Working with `R R^T` instead of `B` keeps the rigid-body eigenvalue `-k6 / k1` exact
//! (a direct eigen-solve of `A` would only get it to `eps ||A|| ~ eps k2 / (k1 h^2)`
//! absolutely) and costs `O(N^2)`.

use faer::diag::{DiagMut, DiagRef};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::tridiagonal_self_adjoint_evd;
use faer::linalg::temp_mat_scratch;
use faer::Par;

use super::PdeSystem;
use crate::error::{Error, Result};

impl PdeSystem {
    /// The lowest `count` squared linear frequencies `w^2` of the discretised PDE
    /// (eigenvalues of `K v = w^2 M v`, see the module docs), ascending. The first is
    /// `-k6 / k1` (the uniform twist, negative for a rotating string); mode `i` tends to
    /// `(k2 (i pi / l)^2 - k6) / k1` as `h -> 0`, with an `O(h^2)` error.
    /// `count` must be in `1..=nodes` (field `"count"`).
    pub fn linear_frequencies_squared(&self, count: usize) -> Result<Vec<f64>> {
        let n = self.nodes();
        if !(1..=n).contains(&count) {
            return Err(Error::invalid("count", count, format!("an integer in 1..={n} (the number of nodes)")));
        }
        let k = self.coefficients();
        let c = k.k2 / (k.k1 * self.spacing() * self.spacing());
        let shift = k.k6 / k.k1;
        let mut out = Vec::with_capacity(count);
        out.push(-shift);
        if count > 1 {
            let mu = gradient_gram_eigenvalues(n - 1)?;
            out.extend(mu[..count - 1].iter().map(|&m| c * m - shift));
        }
        Ok(out)
    }

    /// The lowest `count` linear angular frequencies: `w = sqrt(w^2)` for stable modes and,
    /// for unstable ones (`w^2 < 0`, e.g. the uniform twist of a rotating string), the
    /// negated growth rate `-sqrt(-w^2)`. Ascending, like
    /// [`PdeSystem::linear_frequencies_squared`].
    pub fn linear_frequencies(&self, count: usize) -> Result<Vec<f64>> {
        Ok(self
            .linear_frequencies_squared(count)?
            .into_iter()
            .map(|w2| if w2 >= 0.0 { w2.sqrt() } else { -(-w2).sqrt() })
            .collect())
    }
}

/// The eigenvalues, ascending, of the `m x m` tridiagonal `tridiag(-1, [3, 2, .., 2, 3], -1)`
/// (`m >= 2`).
fn gradient_gram_eigenvalues(m: usize) -> Result<Vec<f64>> {
    let mut diag = vec![2.0; m];
    diag[0] = 3.0;
    diag[m - 1] = 3.0;
    let sub = vec![-1.0; m - 1];
    let mut eig = vec![0.0; m];
    let mut buf = MemBuffer::new(temp_mat_scratch::<f64>(m, 1).array(2));
    tridiagonal_self_adjoint_evd(
        DiagRef::from_slice(&diag),
        DiagRef::from_slice(&sub),
        DiagMut::from_slice_mut(&mut eig),
        None,
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|e| {
        Error::invalid(
            "nodes",
            m + 1,
            format!("a grid whose linear operator the tridiagonal QR algorithm diagonalises ({e:?})"),
        )
    })?;
    eig.sort_by(f64::total_cmp);
    Ok(eig)
}

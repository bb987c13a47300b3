//! The dimensionless Galerkin integrals of a basis, scaled to a [`ModalSystem`] per run.
//!
//! The modal system of eq. 18 depends on the parameters only through `k1..k6` and `l`
//! (`drillstring.galerkin`, module docs):
//!
//! ```text
//! M_kk = k1 l / 2            (k1 l for the rigid mode i = 0)
//! K_kk = k2 (i pi)^2 / (2 l) - k6 l / 2        (-k6 l for i = 0)
//! C_t  = k3 l / 4 cos4_t + k4 pi^2 / (2 l) mixed_t + k5 pi^4 / (4 l^3) sin4_t
//! ```
//!
//! with `cos4`, `mixed`, `sin4` exact dimensionless integrals of the `cos(i pi s)` basis,
//! generated once per basis (`drillstring.galerkin.dimensionless_integrals`). Scaling them
//! is a few multiplications per term, so the per-run set-up of a sweep is negligible.
//! [`GalerkinIntegrals::scale`] is the one place of this scaling: sweeps call it per run and
//! single solves through `drillstring.galerkin.project` (`_core.scale_integrals`).

use std::f64::consts::PI;

use crate::error::Num;
use crate::error::{Error, Result};
use crate::modal::{ModalSystem, QuarticTerm};

/// The dimensionless quartic integrals of the retained basis `cos(i_k pi z / l)`.
#[derive(Debug, Clone, PartialEq)]
pub struct GalerkinIntegrals {
    /// Mode numbers `i_k` of the retained basis, strictly increasing (`0` first for the
    /// rigid mode).
    pub indices: Vec<u32>,
    /// Positions `a <= b <= c <= d` (into `indices`) of each quartic term.
    pub quartic_index: Vec<[u32; 4]>,
    /// `mult_t int_0^1 c_a c_b c_c c_d ds` per term.
    pub cos4: Vec<f64>,
    /// The mixed `c c s s` integral per term (see `drillstring.galerkin`).
    pub mixed: Vec<f64>,
    /// `mult_t i_a i_b i_c i_d int_0^1 s_a s_b s_c s_d ds` per term.
    pub sin4: Vec<f64>,
}

impl GalerkinIntegrals {
    /// Checks the shapes and values: at least one mode, strictly increasing mode numbers,
    /// positions inside the basis, equal lengths and finite integrals.
    pub fn new(
        indices: Vec<u32>,
        quartic_index: Vec<[u32; 4]>,
        cos4: Vec<f64>,
        mixed: Vec<f64>,
        sin4: Vec<f64>,
    ) -> Result<Self> {
        let m = indices.len();
        if m == 0 {
            return Err(Error::invalid("indices", "an empty basis", "at least one mode"));
        }
        if let Some(k) = (1..m).find(|&k| indices[k] <= indices[k - 1]) {
            return Err(Error::invalid(
                "indices",
                format!("indices[{k}] = {} after {}", indices[k], indices[k - 1]),
                "strictly increasing mode numbers",
            ));
        }
        let terms = quartic_index.len();
        for (name, values) in [("cos4", &cos4), ("mixed", &mixed), ("sin4", &sin4)] {
            if values.len() != terms {
                return Err(Error::invalid(
                    name,
                    format!("length {}", values.len()),
                    format!("length {terms} (one per quartic term)"),
                ));
            }
            if let Some(t) = values.iter().position(|v| !v.is_finite()) {
                return Err(Error::invalid(format!("{name}[{t}]"), Num(values[t]), "a finite number"));
            }
        }
        for (t, idx) in quartic_index.iter().enumerate() {
            if let Some(&bad) = idx.iter().find(|&&p| p as usize >= m) {
                return Err(Error::invalid(format!("quartic_index[{t}]"), bad, format!("positions in 0..{m}")));
            }
        }
        Ok(GalerkinIntegrals { indices, quartic_index, cos4, mixed, sin4 })
    }

    /// Number of retained modal coordinates.
    pub fn modes(&self) -> usize {
        self.indices.len()
    }

    /// `int_0^l cos^2(i pi z / l) dz`: `l` for `i = 0`, else `l / 2`.
    fn norm(i: u32, length: f64) -> f64 {
        if i == 0 {
            length
        } else {
            length / 2.0
        }
    }

    /// The diagonal of `M` for `k1` and `l`.
    pub fn mass(&self, k1: f64, length: f64) -> Vec<f64> {
        self.indices.iter().map(|&i| k1 * Self::norm(i, length)).collect()
    }

    /// The diagonal of `K` for `k2`, `k6` and `l` (negative entries: linearly unstable modes).
    pub fn stiffness(&self, k2: f64, k6: f64, length: f64) -> Vec<f64> {
        self.indices
            .iter()
            .map(|&i| {
                let norm = Self::norm(i, length);
                let wave = f64::from(i) * PI / length;
                k2 * (wave * wave) * norm - k6 * norm
            })
            .collect()
    }

    /// The modal system for `k = (k1, ..., k6)` and length `l` (the formulas of the module
    /// docs), for sweeps and single solves alike.
    ///
    /// Errors for non-finite `k`, `k1 <= 0` or `l <= 0` (and whatever [`ModalSystem::new`]
    /// refuses).
    pub fn scale(&self, k: &[f64; 6], length: f64) -> Result<ModalSystem> {
        if let Some(j) = k.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(format!("k{}", j + 1), Num(k[j]), "a finite number"));
        }
        if k[0] <= 0.0 {
            return Err(Error::invalid("k1", Num(k[0]), "a finite number > 0"));
        }
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid("length", Num(length), "a finite number > 0"));
        }
        let [k1, k2, k3, k4, k5, k6] = *k;
        let c3 = k3 * length / 4.0;
        let c4 = k4 * PI.powi(2) / (2.0 * length);
        let c5 = k5 * PI.powi(4) / (4.0 * length.powi(3));
        let terms = (0..self.quartic_index.len())
            .map(|t| QuarticTerm {
                idx: self.quartic_index[t],
                coef: c3 * self.cos4[t] + c4 * self.mixed[t] + c5 * self.sin4[t],
            })
            .collect();
        ModalSystem::new(self.mass(k1, length), self.stiffness(k2, k6, length), terms)
    }

    /// `cos(i_k pi z / l)` for every retained mode: theta at section `z` is the dot product
    /// of this with `q`.
    pub fn basis(&self, z: f64, length: f64) -> Vec<f64> {
        self.indices.iter().map(|&i| (f64::from(i) * PI / length * z).cos()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Modes 1, 2 with the integrals of `drillstring.galerkin.dimensionless_integrals(2)`.
    fn two_modes() -> GalerkinIntegrals {
        GalerkinIntegrals::new(
            vec![1, 2],
            vec![[0, 0, 0, 0], [0, 0, 1, 1], [1, 1, 1, 1]],
            vec![0.375, 1.5, 0.375],
            vec![0.125, 1.25, 0.5],
            vec![0.375, 6.0, 6.0],
        )
        .unwrap()
    }

    #[test]
    fn scales_by_the_documented_formulas() {
        let g = two_modes();
        let k = [2.0, 3.0, 5.0, 7.0, 11.0, 13.0];
        let l = 1.7;
        let sys = g.scale(&k, l).unwrap();
        assert_eq!(sys.mass(), &[2.0 * l / 2.0, 2.0 * l / 2.0]);
        let expect_k2 = 3.0 * (2.0 * PI / l).powi(2) * l / 2.0 - 13.0 * l / 2.0;
        assert!((sys.stiffness()[1] - expect_k2).abs() <= 1e-14 * expect_k2.abs());
        let t = sys.terms()[1];
        let expect =
            5.0 * l / 4.0 * 1.5 + 7.0 * PI * PI / (2.0 * l) * 1.25 + 11.0 * PI.powi(4) / (4.0 * l.powi(3)) * 6.0;
        assert!((t.coef - expect).abs() <= 1e-14 * expect.abs());
    }

    #[test]
    fn rigid_mode_norm_is_the_length() {
        let g = GalerkinIntegrals::new(vec![0, 1], vec![], vec![], vec![], vec![]).unwrap();
        let sys = g.scale(&[2.0, 1.0, 0.0, 0.0, 0.0, 3.0], 10.0).unwrap();
        assert_eq!(sys.mass(), &[20.0, 10.0]);
        assert_eq!(sys.stiffness()[0], -30.0);
    }

    #[test]
    fn rejects_bad_input() {
        assert_eq!(GalerkinIntegrals::new(vec![], vec![], vec![], vec![], vec![]).unwrap_err().field(), "indices");
        assert_eq!(GalerkinIntegrals::new(vec![2, 1], vec![], vec![], vec![], vec![]).unwrap_err().field(), "indices");
        let e = GalerkinIntegrals::new(vec![1], vec![[0, 0, 0, 1]], vec![1.0], vec![1.0], vec![1.0]).unwrap_err();
        assert_eq!(e.field(), "quartic_index[0]");
        let e = GalerkinIntegrals::new(vec![1], vec![[0; 4]], vec![1.0], vec![], vec![1.0]).unwrap_err();
        assert_eq!(e.field(), "mixed");
        let g = two_modes();
        assert_eq!(g.scale(&[0.0, 1.0, 1.0, 1.0, 1.0, 1.0], 1.0).unwrap_err().field(), "k1");
        assert_eq!(g.scale(&[1.0, 1.0, f64::NAN, 1.0, 1.0, 1.0], 1.0).unwrap_err().field(), "k3");
        assert_eq!(g.scale(&[1.0; 6], -1.0).unwrap_err().field(), "length");
    }
}

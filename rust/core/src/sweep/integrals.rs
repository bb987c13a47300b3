//! The dimensionless Galerkin integrals of a basis, and the discretisation of a model's terms
//! with them into a [`ModalSystem`], per run.
//!
//! The modal system of a [`ModelTerms`] depends on the parameters only through its
//! coefficients and `l` (`drillstring.galerkin`, module docs). Term by term
//! ([`GalerkinIntegrals::discretise`]), with `N_i = int_0^l phi_i^2 dz` (`l / 2`, `l` for the
//! rigid mode `i = 0`):
//!
//! ```text
//! M_ii  = k1 N_i
//! K_ii  = sum over terms with p + r = 2 of 2 weight (i pi / l)^r N_i
//!       = k2 (i pi)^2 / (2 l) - k6 l / 2          (eq. 18; -k6 l for i = 0)
//! C_t   = sum over terms with p + r = 4 of weight l (pi / l)^r I^(p,r)_t
//!       = k3 l / 4 cos4_t + k4 pi^2 / (2 l) mixed_t + k5 pi^4 / (4 l^3) sin4_t
//! ```
//!
//! with `I^(4,0) = cos4`, `I^(2,2) = mixed`, `I^(0,4) = sin4` the exact dimensionless integrals of
//! the basis, generated once per basis in [`crate::galerkin`]. Scaling them is a few
//! multiplications per term, so the per-run set-up of a sweep is negligible.
//! [`GalerkinIntegrals::discretise`] is the one place of this scaling: sweeps call it per run
//! (through [`GalerkinIntegrals::scale`]) and single solves through `drillstring.galerkin.project`
//! (`_core.scale_integrals`, [`GalerkinIntegrals::coefficients`]).
//!
//! From [`crate::modal::SPECTRAL_MIN_MODES`] retained modes on ([`QuarticEvaluation::Auto`]) the
//! quartic terms are not scaled to `C_t` at all: [`discretise_spectral`] hands the model's quartic
//! energy terms to the pseudo-spectral evaluation ([`crate::modal::spectral`]), which needs only
//! the mode numbers of the basis (single solves: `_core.ModalSystem.spectral`).

use std::f64::consts::PI;

use crate::error::Num;
use crate::error::{Error, Result};
use serde::Serialize;

use crate::modal::{check_model, ModalSystem, QuarticEvaluation, QuarticTerm, SpectralQuartic};
use crate::terms::{Boundary, EnergyTerm, ModelTerms};

/// The dimensionless quartic integrals of the retained basis `cos(i_k pi z / l)` (serialised
/// without the boundary).
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// The boundary conditions whose basis these are the integrals of.
    #[serde(skip)]
    pub boundary: Boundary,
}

impl GalerkinIntegrals {
    /// The integrals of the cosine basis of free ends ([`Boundary::Free`]) from their arrays.
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
        Ok(GalerkinIntegrals { indices, quartic_index, cos4, mixed, sin4, boundary: Boundary::Free })
    }

    /// Number of retained modal coordinates.
    pub fn modes(&self) -> usize {
        self.indices.len()
    }

    /// The diagonal of `M` for `k1` and `l`.
    pub fn mass(&self, k1: f64, length: f64) -> Vec<f64> {
        mass(&self.indices, k1, length)
    }

    /// The dimensionless integrals `I^(p,r)` of a quartic monomial, `None` unless `p + r = 4`
    /// with `r` even.
    pub fn quartic_integrals(&self, p: u32, r: u32) -> Option<&[f64]> {
        match (p, r) {
            (4, 0) => Some(&self.cos4),
            (2, 2) => Some(&self.mixed),
            (0, 4) => Some(&self.sin4),
            _ => None,
        }
    }

    /// The modal system for `k = (k1, ..., k6)` and length `l`: [`GalerkinIntegrals::discretise`]
    /// of [`ModelTerms::from_coefficients`], for sweeps and single solves alike.
    ///
    /// Errors for non-finite `k`, `k1 <= 0` or `l <= 0` (and whatever [`ModalSystem::new`]
    /// refuses).
    pub fn scale(&self, k: &[f64; 6], length: f64) -> Result<ModalSystem> {
        self.discretise(&ModelTerms::from_coefficients(*k)?, length)
    }

    /// The modal system of `model` on `[0, length]` (the formulas of the module docs), term by
    /// term: each term with `p + r = 2` adds to the diagonal stiffness, each with `p + r = 4`
    /// to the quartic coefficients; the damping is the model's.
    ///
    /// Errors: `l` not finite and `> 0` (`"length"`), a model whose boundary is not the one of
    /// the basis (`"boundary"`), a term of another shape (field: its coefficient, naming the
    /// term), and whatever [`ModalSystem::new`] refuses.
    pub fn discretise(&self, model: &ModelTerms, length: f64) -> Result<ModalSystem> {
        self.discretise_with(model, length, QuarticEvaluation::Auto)
    }

    /// [`GalerkinIntegrals::discretise`] with the quartic force evaluated as `evaluation` asks
    /// ([`QuarticEvaluation::resolve`] for the number of modes): the merged monomials of the
    /// coefficients `C_t`, or pseudo-spectrally ([`discretise_spectral`], which needs only the
    /// basis: the integrals are not used, the coefficients not formed).
    pub fn discretise_with(
        &self,
        model: &ModelTerms,
        length: f64,
        evaluation: QuarticEvaluation,
    ) -> Result<ModalSystem> {
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid("length", Num(length), "a finite number > 0"));
        }
        if model.boundary() != self.boundary {
            return Err(Error::invalid(
                "boundary",
                model.boundary().name(),
                format!("the boundary of the basis, {}", self.boundary.name()),
            ));
        }
        if evaluation.resolve(self.modes()) == QuarticEvaluation::Spectral {
            return discretise_spectral(&self.indices, model, length);
        }
        let (mass, stiffness, terms) = self.coefficients(model, length)?;
        ModalSystem::new(mass, stiffness, terms)?.with_damping(model.damping().rate())
    }

    /// The diagonals of `M` and `K` and the quartic terms `C_t` of `model` on `[0, length]` (the
    /// formulas of the module docs), checked as [`ModalSystem::new`] checks them, without
    /// building the system (its merged gradient rows): the coefficients `drillstring.galerkin`
    /// exposes (`_core.scale_integrals`). Errors as [`GalerkinIntegrals::discretise`].
    #[allow(clippy::type_complexity)]
    pub fn coefficients(&self, model: &ModelTerms, length: f64) -> Result<(Vec<f64>, Vec<f64>, Vec<QuarticTerm>)> {
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid("length", Num(length), "a finite number > 0"));
        }
        if model.boundary() != self.boundary {
            return Err(Error::invalid(
                "boundary",
                model.boundary().name(),
                format!("the boundary of the basis, {}", self.boundary.name()),
            ));
        }
        let mut quadratic = Vec::new();
        let mut quartic: Vec<(f64, &[f64])> = Vec::new();
        for term in model.conservative() {
            let (p, r) = term.exponents();
            match (p + r, self.quartic_integrals(p, r)) {
                (2, _) if r % 2 == 0 => quadratic.push(term),
                (4, Some(integrals)) => {
                    // weight l (pi / l)^r, evaluated as eq. 18's hand-written k l / 4,
                    // k pi^2 / (2 l), k pi^4 / (4 l^3) (same rounding, same overflow)
                    let (k, d) = (term.coefficient(), term.spec().divisor());
                    let scale = match r {
                        0 => k * length / d,
                        2 => k * PI.powi(2) / (d * length),
                        _ => k * PI.powi(4) / (d * length.powi(3)),
                    };
                    quartic.push((scale, integrals));
                }
                _ => {
                    return Err(Error::invalid(
                        term.spec().coefficient,
                        format!("the {} term th^{p} th_z^{r}", term.name()),
                        "a Galerkin energy monomial with p + r = 2 or 4 and r even",
                    ))
                }
            }
        }
        let terms: Vec<QuarticTerm> = (0..self.quartic_index.len())
            .map(|t| QuarticTerm {
                idx: self.quartic_index[t],
                coef: quartic.iter().fold(0.0, |acc, &(scale, integrals)| acc + scale * integrals[t]),
            })
            .collect();
        let (mass, stiffness) = (self.mass(model.inertia(), length), stiffness(&self.indices, &quadratic, length));
        check_model(&mass, &stiffness, &terms)?;
        Ok((mass, stiffness, terms))
    }

    /// `cos(i_k pi z / l)` for every retained mode: theta at section `z` is the dot product
    /// of this with `q`.
    pub fn basis(&self, z: f64, length: f64) -> Vec<f64> {
        self.indices.iter().map(|&i| mode_shape(i, z, length)).collect()
    }
}

/// The mode shape `phi_i(z) = cos(i pi z / l)` of the free-free basis (eq. 15), evaluated as
/// `cos(z (i (pi / l)))`: the one evaluation of the basis (sweeps, single solves, plots).
pub fn mode_shape(i: u32, z: f64, length: f64) -> f64 {
    (z * (f64::from(i) * (PI / length))).cos()
}

/// Its slope `phi_i'(z) = -(i pi / l) sin(i pi z / l)`, zero at both ends (eq. 14).
pub fn mode_slope(i: u32, z: f64, length: f64) -> f64 {
    let wave = f64::from(i) * (PI / length);
    -wave * (z * wave).sin()
}

/// `int_0^l cos^2(i pi z / l) dz`: `l` for `i = 0`, else `l / 2`.
fn norm(i: u32, length: f64) -> f64 {
    if i == 0 {
        length
    } else {
        length / 2.0
    }
}

/// The diagonal of `M` of the basis `indices` for `k1` and `l`.
fn mass(indices: &[u32], k1: f64, length: f64) -> Vec<f64> {
    indices.iter().map(|&i| k1 * norm(i, length)).collect()
}

/// The diagonal of `K` of the quadratic terms, `sum 2 weight (i pi / l)^r N_i` (negative
/// entries: linearly unstable modes).
fn stiffness(indices: &[u32], quadratic: &[&EnergyTerm], length: f64) -> Vec<f64> {
    indices
        .iter()
        .map(|&i| {
            let norm = norm(i, length);
            let wave = f64::from(i) * PI / length;
            quadratic.iter().fold(0.0, |acc, term| {
                let wave_r = if term.spec().r == 2 { wave * wave } else { 1.0 };
                // 2 factor is +-1: exactly +-k
                acc + 2.0 * term.spec().factor() * term.coefficient() * wave_r * norm
            })
        })
        .collect()
}

/// The modal system of `model` on the cosine basis `indices` (mode numbers, strictly
/// increasing) of `[0, length]` with the quartic force evaluated pseudo-spectrally
/// ([`SpectralQuartic`]): `M` and `K` as [`GalerkinIntegrals::discretise`] forms them, the quartic
/// terms taken as they are (no integrals). The builder of
/// [`GalerkinIntegrals::discretise_with`] for [`QuarticEvaluation::Spectral`], and of single
/// solves above the crossover (`_core.ModalSystem.spectral`).
///
/// Errors: as [`GalerkinIntegrals::discretise`] (`"length"`, a term of another shape naming its
/// coefficient; the boundary must be [`Boundary::Free`], the basis of these cosines), and
/// `"indices"` for an empty or not strictly increasing basis.
pub fn discretise_spectral(indices: &[u32], model: &ModelTerms, length: f64) -> Result<ModalSystem> {
    if !(length.is_finite() && length > 0.0) {
        return Err(Error::invalid("length", Num(length), "a finite number > 0"));
    }
    if model.boundary() != Boundary::Free {
        return Err(Error::invalid("boundary", model.boundary().name(), "free ends (the cosine basis)"));
    }
    let mut quadratic = Vec::new();
    let mut quartic = Vec::new();
    for term in model.conservative() {
        let (p, r) = term.exponents();
        match p + r {
            2 if r % 2 == 0 => quadratic.push(term),
            4 if r % 2 == 0 => quartic.push(*term),
            _ => {
                return Err(Error::invalid(
                    term.spec().coefficient,
                    format!("the {} term th^{p} th_z^{r}", term.name()),
                    "a Galerkin energy monomial with p + r = 2 or 4 and r even",
                ))
            }
        }
    }
    let spectral = SpectralQuartic::new(indices.to_vec(), length, quartic)?;
    ModalSystem::spectral(mass(indices, model.inertia(), length), stiffness(indices, &quadratic, length), spectral)?
        .with_damping(model.damping().rate())
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
    fn mode_shapes_are_the_free_free_cosines() {
        let l = 3.0;
        for i in 0..5u32 {
            let w = f64::from(i) * PI / l;
            for z in [0.0, 0.7, 1.5, 3.0] {
                assert!((mode_shape(i, z, l) - (w * z).cos()).abs() <= 1e-15);
                assert!((mode_slope(i, z, l) + w * (w * z).sin()).abs() <= 1e-14);
            }
            // eq. 14: no slope at the free ends; the slope is the derivative of the shape
            assert!(mode_slope(i, 0.0, l) == 0.0 && mode_slope(i, l, l).abs() <= 1e-14 * (1.0 + w));
            let h = 1e-6;
            let fd = (mode_shape(i, 1.1 + h, l) - mode_shape(i, 1.1 - h, l)) / (2.0 * h);
            assert!((fd - mode_slope(i, 1.1, l)).abs() <= 1e-8);
        }
        assert_eq!(two_modes().basis(0.7, l), [mode_shape(1, 0.7, l), mode_shape(2, 0.7, l)]);
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

    /// The scaling as written before the terms existed: eq. 18's coefficients by hand.
    fn scale_by_hand(g: &GalerkinIntegrals, k: &[f64; 6], length: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let [k1, k2, k3, k4, k5, k6] = *k;
        let norm = |i: u32| if i == 0 { length } else { length / 2.0 };
        let mass = g.indices.iter().map(|&i| k1 * norm(i)).collect();
        let stiffness = g
            .indices
            .iter()
            .map(|&i| {
                let wave = f64::from(i) * PI / length;
                k2 * (wave * wave) * norm(i) - k6 * norm(i)
            })
            .collect();
        let c3 = k3 * length / 4.0;
        let c4 = k4 * PI.powi(2) / (2.0 * length);
        let c5 = k5 * PI.powi(4) / (4.0 * length.powi(3));
        let coef = (0..g.quartic_index.len()).map(|t| c3 * g.cos4[t] + c4 * g.mixed[t] + c5 * g.sin4[t]).collect();
        (mass, stiffness, coef)
    }

    #[test]
    fn composing_the_terms_reproduces_the_hand_written_system_bit_for_bit() {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let paper = [0.369, 5.4e9, 3.3e8, 1.6e9, -2.2e5, 3.64];
        let consistent = [0.369, 1.35e9, 0.0, 0.0, 7.7e5, 0.0];
        for (modes, rigid) in [(1, false), (3, false), (5, true), (16, true)] {
            let g = crate::galerkin::integrals(Boundary::Free, modes, rigid).unwrap();
            for k in [paper, consistent, [2.0, 3.0, 5.0, 7.0, 11.0, 13.0]] {
                for length in [100.0, 1.7, 2000.0] {
                    let model = ModelTerms::from_coefficients(k).unwrap();
                    let sys = g.discretise_with(&model, length, QuarticEvaluation::TermSum).unwrap();
                    let (mass, stiffness, coef) = scale_by_hand(&g, &k, length);
                    assert_eq!(bits(sys.mass()), bits(&mass));
                    assert_eq!(bits(sys.stiffness()), bits(&stiffness), "{modes} {rigid} {k:?} {length}");
                    let got: Vec<f64> = sys.terms().iter().map(|t| t.coef).collect();
                    // the sign of a zero may differ (0 + -0)
                    let got: Vec<f64> = got.iter().map(|&c| if c == 0.0 { 0.0 } else { c }).collect();
                    let coef: Vec<f64> = coef.iter().map(|&c| if c == 0.0 { 0.0 } else { c }).collect();
                    assert_eq!(bits(&got), bits(&coef), "{modes} {rigid} {k:?} {length}");
                }
            }
        }
    }

    #[test]
    fn overflow_is_refused_where_the_hand_written_system_overflowed() {
        let g = crate::galerkin::integrals(Boundary::Free, 3, true).unwrap();
        for k in [
            [1.0, 1e305, 1e307, 1e300, 1e300, 1.0],
            [1.0, 1e300, 0.0, 0.0, 1e305, 0.0],
            [1.0, 1e307, 1.0, 1.0, 1.0, 1.0],
        ] {
            for length in [100.0, 1e-3] {
                let (mass, stiffness, coef) = scale_by_hand(&g, &k, length);
                let finite = mass.iter().chain(&stiffness).chain(&coef).all(|x| x.is_finite());
                assert_eq!(g.scale(&k, length).is_ok(), finite, "{k:?} {length}");
            }
        }
    }

    #[test]
    fn damping_and_refusals_come_from_the_model() {
        let g = two_modes();
        let model = ModelTerms::from_coefficients([2.0, 3.0, 5.0, 7.0, 11.0, 13.0]).unwrap().with_damping(0.5).unwrap();
        let sys = g.discretise(&model, 1.7).unwrap();
        assert_eq!(sys.damping_rate(), 0.5);
        assert_eq!(g.discretise(&model, f64::NAN).unwrap_err().field(), "length");
        static SLOPE: crate::terms::TermSpec = crate::terms::TermSpec {
            name: "slope",
            equation: "none (a test shape)",
            coefficient: "k7",
            factor: (1, 2),
            p: 3,
            r: 1,
        };
        let odd = ModelTerms::new(1.0, vec![SLOPE.with(1.0).unwrap()]).unwrap();
        let err = g.discretise(&odd, 1.0).unwrap_err();
        assert!(err.field() == "k7" && err.to_string().contains("slope"), "{err}");
    }

    /// Deterministic pseudo-random numbers in [-1, 1).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut unit = crate::test_support::uniform(seed);
        move || 2.0 * unit() - 1.0
    }

    /// The largest relative difference of the spectral and the term-sum force and potential over
    /// random states of `modes` modes.
    fn spectral_vs_terms(modes: u32, rigid: bool, k: [f64; 6], length: f64, draws: usize) -> (f64, f64) {
        let g = crate::galerkin::integrals(Boundary::Free, modes, rigid).unwrap();
        let model = ModelTerms::from_coefficients(k).unwrap();
        let sum = g.discretise_with(&model, length, QuarticEvaluation::TermSum).unwrap();
        let spec = g.discretise_with(&model, length, QuarticEvaluation::Spectral).unwrap();
        assert_eq!((sum.evaluation(), spec.evaluation()), (QuarticEvaluation::TermSum, QuarticEvaluation::Spectral));
        assert_eq!(sum.mass(), spec.mass());
        assert_eq!(sum.stiffness(), spec.stiffness());
        let m = g.modes();
        let mut next = uniform(0x9e37_79b9_7f4a_7c15 ^ u64::from(modes) << 1 ^ u64::from(rigid));
        let (mut force_err, mut potential_err) = (0.0f64, 0.0f64);
        for draw in 0..draws {
            // amplitudes from 1e-3 to 1, decaying with the mode number in half the draws
            let scale = 10f64.powf(-3.0 * (draw as f64 / draws as f64));
            let q: Vec<f64> =
                (0..m).map(|k| scale * next() / if draw % 2 == 0 { 1.0 } else { 1.0 + k as f64 }).collect();
            let (mut a, mut b) = (vec![0.0; m], vec![0.0; m]);
            sum.quartic_gradient(&q, &mut a);
            spec.quartic_gradient(&q, &mut b);
            let norm = a.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let diff = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            force_err = force_err.max(diff / norm);
            let (va, vb) = (sum.quartic_potential(&q), spec.quartic_potential(&q));
            potential_err = potential_err.max((va - vb).abs() / va.abs());
        }
        (force_err, potential_err)
    }

    #[test]
    fn the_spectral_force_and_potential_equal_the_term_sum_to_rounding() {
        let paper = [0.369, 5.4e9, 3.3e8, 1.6e9, -2.2e5, 3.64];
        let consistent = [0.369, 1.35e9, 0.0, 0.0, 7.7e5, 0.0];
        let (mut worst_force, mut worst_potential) = (0.0f64, 0.0f64);
        for modes in 1..=40 {
            for rigid in [false, true] {
                for (k, length) in [(paper, 100.0), (consistent, 100.0), (paper, 1.7)] {
                    let (f, v) = spectral_vs_terms(modes, rigid, k, length, 6);
                    assert!(f < 2e-13 && v < 2e-13, "{modes} modes, rigid {rigid}, {k:?}: {f:e} {v:e}");
                    worst_force = worst_force.max(f);
                    worst_potential = worst_potential.max(v);
                }
            }
        }
        println!("largest relative difference: force {worst_force:e}, potential {worst_potential:e}");
    }

    #[test]
    fn auto_is_spectral_from_the_crossover() {
        let model = ModelTerms::from_coefficients([0.369, 5.4e9, 3.3e8, 1.6e9, -2.2e5, 3.64]).unwrap();
        let below = crate::modal::SPECTRAL_MIN_MODES as u32 - 2;
        let g = crate::galerkin::integrals(Boundary::Free, below, true).unwrap();
        assert_eq!(g.discretise(&model, 100.0).unwrap().evaluation(), QuarticEvaluation::TermSum);
        let g = crate::galerkin::integrals(Boundary::Free, below + 1, true).unwrap();
        let sys = g.discretise(&model, 100.0).unwrap();
        assert_eq!(sys.evaluation(), QuarticEvaluation::Spectral);
        assert!(sys.terms().is_empty());
        // the basis alone builds the same system
        let direct = discretise_spectral(&g.indices, &model, 100.0).unwrap();
        assert_eq!(direct, sys);
        assert_eq!(discretise_spectral(&g.indices, &model, 0.0).unwrap_err().field(), "length");
    }
}

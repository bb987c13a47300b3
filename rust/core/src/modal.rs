//! The modal (Bubnov-Galerkin) system `M q'' + c M q' + K q + N(q) = 0`.
//!
//! With the twist expanded as `theta(z, t) = sum_i q_i(t) cos(i pi z / l)` the basis is
//! orthogonal, so the mass matrix `M` and the linear stiffness `K` are diagonal:
//! `M_ii = k1 * int cos^2`, `K_ii = (k2 (i pi / l)^2 - k6) * int cos^2`. The cubic force is
//! the gradient of the quartic potential
//!
//! ```text
//! V(q) = int_0^l [k3/4 th^4 + k4/2 th^2 th_z^2 + k5/4 th_z^4] dz
//!      = sum_t c_t q_a q_b q_c q_d      (a <= b <= c <= d, one term per index set)
//! ```
//!
//! which is the compact, symmetry-exploiting form of the cubic coupling tensor. The
//! coefficients come from the model's terms ([`crate::terms`]) discretised with the exact
//! dimensionless integrals of the basis ([`crate::galerkin`]) by
//! [`crate::sweep::GalerkinIntegrals::discretise`].
//!
//! Two evaluations of `grad V` and `V` ([`QuarticEvaluation`]), equal to rounding:
//!
//! * the term sum ([`ModalSystem::new`]): the merged cubic monomials of the coefficients, one
//!   product each, `~n^3` of them (32k terms at 64 modes, ~1.9 million at 256);
//! * pseudo-spectral ([`ModalSystem::spectral`], [`spectral`]): the field and its slope at
//!   `M > 2 max i` midpoints by one real FFT, the pointwise partial derivatives of the model's
//!   quartic energy terms, one real FFT back; the midpoint rule is exact for the quartic
//!   integrands (no aliasing), `O(n log n)`, and needs no coefficients.
//!
//! The force of a term-sum system of at most four modes (the paper's three) runs
//! through `SmallCubic`: every cubic monomial in a fixed order and a dense coefficient
//! matrix, one code path per mode count with constant indices, the same sums to rounding
//! (the RKN12 steps of the reference case, 10,746 evaluations, took 0.45-0.73 ms against
//! 0.48-0.87 ms through the rows, faster in 6 of 7 alternating runs of
//! `python benchmarks/compare_scipy.py --method rkn12 --samples 2`).
//!
//! [`QuarticEvaluation::Auto`] (what the builder uses for single solves and sweeps alike) takes
//! the term sum below [`SPECTRAL_MIN_MODES`] retained modes, so small models (the paper's
//! three modes) are evaluated exactly as before, and the spectral evaluation from there on.
//!
//! Viscous damping `-k1 c th_t` per unit length projects, like the inertia `k1 th_tt`, onto
//! the mass: the modal damping force is `-c M_i q_i'` ([`ModalSystem::with_damping`]), and
//! the power it dissipates is `c q'^T M q'`.

pub mod spectral;

use crate::error::Num;
use crate::error::{Error, Result};
use crate::system::{Energy, SecondOrderSystem};
use crate::terms::ViscousDamping;

pub use spectral::SpectralQuartic;

/// The number of retained modes (the rigid mode counted) from which
/// [`QuarticEvaluation::Auto`] evaluates the quartic force pseudo-spectrally
/// ([`SpectralQuartic`]) instead of by its merged monomials.
///
/// Measured with `python benchmarks/spectral_crossover.py` (the cost of one right-hand-side
/// evaluation inside the Rust solver, fixed-step RK4 minus a null system, `_evalcost.py`;
/// aluminium preset, `n` elastic modes + the rigid mode, the same model built both ways;
/// release build, x86_64 with AVX2 + FMA, 2 cores shared), us per evaluation:
///
/// ```text
/// retained modes     4     6     7     8     9    10    11    17    33     65    129    257
/// term sum       0.026 0.077 0.121 0.180 0.256 0.382 0.470 1.712 13.17  103.8 1414.1 8397.0
/// spectral       0.072 0.090 0.158 0.155 0.143 0.212 0.169 0.212 0.745  0.931  2.036  4.050
/// ```
///
/// The two cost about the same at 7 retained modes (ratio 0.8-1.0 over repeated runs); from 8
/// on the spectral evaluation is faster (1.2-1.3x at 8, 2.8x at 11, 8x at 17, 110x at 65,
/// 2000x at 257). The paper's three modes (four with the rigid mode) stay on the term sum.
pub const SPECTRAL_MIN_MODES: usize = 8;

/// How a [`ModalSystem`] evaluates its quartic potential and its gradient.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuarticEvaluation {
    /// [`QuarticEvaluation::TermSum`] below [`SPECTRAL_MIN_MODES`] retained modes,
    /// [`QuarticEvaluation::Spectral`] from there on.
    Auto,
    /// The merged cubic monomials of the quartic terms, one product each (`~n^3`).
    TermSum,
    /// The exact (de-aliased) quadrature of the model's quartic density ([`SpectralQuartic`],
    /// `O(n log n)`).
    Spectral,
}

impl QuarticEvaluation {
    /// `TermSum` or `Spectral` for a system of `modes` retained modes.
    pub fn resolve(self, modes: usize) -> QuarticEvaluation {
        match self {
            QuarticEvaluation::Auto if modes >= SPECTRAL_MIN_MODES => QuarticEvaluation::Spectral,
            QuarticEvaluation::Auto => QuarticEvaluation::TermSum,
            other => other,
        }
    }

    /// `"auto"`, `"terms"` or `"spectral"`.
    pub fn name(self) -> &'static str {
        match self {
            QuarticEvaluation::Auto => "auto",
            QuarticEvaluation::TermSum => "terms",
            QuarticEvaluation::Spectral => "spectral",
        }
    }

    /// The evaluation of [`QuarticEvaluation::name`] (field `"evaluation"` otherwise).
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "auto" => Ok(QuarticEvaluation::Auto),
            "terms" => Ok(QuarticEvaluation::TermSum),
            "spectral" => Ok(QuarticEvaluation::Spectral),
            other => Err(Error::invalid("evaluation", other, "\"auto\", \"terms\" or \"spectral\"")),
        }
    }
}

/// One term `coef * q[a] q[b] q[c] q[d]` of the quartic potential.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuarticTerm {
    pub idx: [u32; 4],
    pub coef: f64,
}

/// One monomial `coef * q[b] q[c] q[d]` of a component of `grad V`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct CubicMonomial {
    idx: [u32; 3],
    coef: f64,
}

/// `M q'' + c M q' + K q + grad V(q) = 0` with diagonal `M`, `K` and damping rate `c >= 0`
/// (0 unless set by [`ModalSystem::with_damping`]).
///
/// The gradient is stored row by row (compressed rows: `grad_start[j] .. grad_start[j + 1]`
/// index the monomials of `dV/dq_j`, duplicates merged), so each component is accumulated
/// in a register and written once: no read-modify-write chains through memory.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalSystem {
    inv_mass: Vec<f64>,
    mass: Vec<f64>,
    stiffness: Vec<f64>,
    terms: Vec<QuarticTerm>,
    grad: Vec<CubicMonomial>,
    grad_start: Vec<usize>,
    /// For a system of at most [`SMALL_MAX_MODES`] modes: the coefficients of every cubic
    /// monomial in every component ([`SmallCubic`], used by [`ModalSystem::force`] instead of
    /// the rows).
    small: Option<SmallCubic>,
    /// The pseudo-spectral quartic force, used instead of `terms` when set.
    spectral: Option<SpectralQuartic>,
    damping: ViscousDamping,
}

/// The monomials of `grad V` grouped by component: `d/dq_j` of each term, merged.
///
/// One stable sort of all `4 T` derivative monomials by `(row, indices)`: duplicates are then
/// adjacent and are summed in the order of `terms` (`O(T log T)`; 256 modes have ~1.9 million
/// terms).
fn gradient_rows(n: usize, terms: &[QuarticTerm]) -> (Vec<CubicMonomial>, Vec<usize>) {
    let mut entries: Vec<(u32, CubicMonomial)> = Vec::with_capacity(4 * terms.len());
    for term in terms {
        for k in 0..4 {
            let mut rest = [0u32; 3];
            let mut r = 0;
            for (m, &i) in term.idx.iter().enumerate() {
                if m != k {
                    rest[r] = i;
                    r += 1;
                }
            }
            rest.sort_unstable();
            entries.push((term.idx[k], CubicMonomial { idx: rest, coef: term.coef }));
        }
    }
    entries.sort_by_key(|(row, mono)| (*row, mono.idx));
    let mut merged: Vec<(u32, CubicMonomial)> = Vec::with_capacity(entries.len());
    for (row, mono) in entries {
        match merged.last_mut() {
            Some((last_row, last)) if *last_row == row && last.idx == mono.idx => last.coef += mono.coef,
            _ => merged.push((row, mono)),
        }
    }
    merged.retain(|(_, mono)| mono.coef != 0.0);
    let mut grad = Vec::with_capacity(merged.len());
    let mut start = Vec::with_capacity(n + 1);
    let mut next = merged.into_iter().peekable();
    for j in 0..n {
        start.push(grad.len());
        while let Some((_, mono)) = next.next_if(|(row, _)| *row as usize == j) {
            grad.push(mono);
        }
    }
    start.push(grad.len());
    (grad, start)
}

/// Systems of up to this many modes (the paper's three, or two with the rigid mode, ...)
/// evaluate their force through [`SmallCubic`].
const SMALL_MAX_MODES: usize = 4;
/// The cubic monomials of [`SMALL_MAX_MODES`] variables.
const SMALL_MONOMIALS: usize = monomial_count(SMALL_MAX_MODES);

/// The number of cubic monomials `q_b q_c q_d` (`b <= c <= d < n`) of `n` variables,
/// `C(n + 2, 3)`.
const fn monomial_count(n: usize) -> usize {
    n * (n + 1) * (n + 2) / 6
}

/// The force of a system of at most [`SMALL_MAX_MODES`] modes with every cubic
/// monomial in a fixed order and a dense matrix of their coefficients (zeros included), so
/// that the evaluation has no index lookups: for `N` modes a code path of its own with
/// constant indices ([`SmallCubic::force`]); the monomials in `(b, c, d)` lexicographic order. The rows of [`gradient_rows`] cost
/// about 20 ns per evaluation of the 3-mode reference case, mostly loads of indices and
/// values. The same sums in the same order of monomials, equal to the rows to rounding (the
/// products associate as `coef (q_b q_c q_d)` instead of `((coef q_b) q_c) q_d`).
#[derive(Debug, Clone, PartialEq)]
struct SmallCubic {
    /// `coef[j][k]`: the coefficient of monomial `k` in component `j`.
    coef: [[f64; SMALL_MONOMIALS]; SMALL_MAX_MODES],
}

impl SmallCubic {
    /// From the rows of [`gradient_rows`]; `None` above [`SMALL_MAX_MODES`] modes and without
    /// cubic terms (a linear system: the rows are then `K q` alone).
    fn new(n: usize, grad: &[CubicMonomial], start: &[usize]) -> Option<Self> {
        if n > SMALL_MAX_MODES || grad.is_empty() {
            return None;
        }
        let mut order = Vec::with_capacity(monomial_count(n));
        for b in 0..n {
            for c in b..n {
                for d in c..n {
                    order.push([b as u32, c as u32, d as u32]);
                }
            }
        }
        let mut coef = [[0.0; SMALL_MONOMIALS]; SMALL_MAX_MODES];
        for (j, row) in coef.iter_mut().enumerate().take(n) {
            for mono in &grad[start[j]..start[j + 1]] {
                let k = order.binary_search(&mono.idx).expect("sorted indices below n");
                row[k] = mono.coef;
            }
        }
        Some(SmallCubic { coef })
    }

    /// `finish(j, f_j)` into `out[j]` for the force `f = K q + grad V(q)` of `n = q.len()`
    /// modes ([`ModalSystem::force_with`]).
    #[inline]
    fn force_with(&self, stiffness: &[f64], q: &[f64], out: &mut [f64], finish: impl Fn(usize, f64) -> f64) {
        match q.len() {
            1 => self.fixed::<1>(stiffness, q, out, finish),
            2 => self.fixed::<2>(stiffness, q, out, finish),
            3 => self.fixed::<3>(stiffness, q, out, finish),
            _ => self.fixed::<4>(stiffness, q, out, finish),
        }
    }

    #[inline(always)]
    fn fixed<const N: usize>(&self, stiffness: &[f64], q: &[f64], out: &mut [f64], finish: impl Fn(usize, f64) -> f64) {
        let q: [f64; N] = q[..N].try_into().expect("N modes");
        let stiffness: &[f64; N] = stiffness[..N].try_into().expect("N modes");
        let mut m = [0.0; SMALL_MONOMIALS];
        let mut k = 0;
        for b in 0..N {
            for c in b..N {
                let qbc = q[b] * q[c];
                for &qd in &q[c..] {
                    m[k] = qbc * qd;
                    k += 1;
                }
            }
        }
        let f: [f64; N] = std::array::from_fn(|j| {
            let mut f = stiffness[j] * q[j];
            for (&c, &mk) in self.coef[j][..monomial_count(N)].iter().zip(&m) {
                f += c * mk;
            }
            finish(j, f)
        });
        out[..N].copy_from_slice(&f);
    }
}

impl ModalSystem {
    /// Builds the system from the diagonal of `M` (finite, > 0), the diagonal of `K`
    /// (finite; negative entries are linearly unstable modes) and the quartic terms
    /// (indices < n, finite coefficients).
    pub fn new(mass: Vec<f64>, stiffness: Vec<f64>, terms: Vec<QuarticTerm>) -> Result<Self> {
        check_model(&mass, &stiffness, &terms)?;
        let n = mass.len();
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        let (grad, grad_start) = gradient_rows(n, &terms);
        let small = SmallCubic::new(n, &grad, &grad_start);
        Ok(ModalSystem {
            inv_mass,
            mass,
            stiffness,
            terms,
            grad,
            grad_start,
            small,
            spectral: None,
            damping: ViscousDamping::default(),
        })
    }

    /// The system of diagonal `M` and `K` (checked as by [`ModalSystem::new`]) whose quartic
    /// potential is evaluated pseudo-spectrally by `quartic` (of the same number of modes, else
    /// an error naming `"quartic"`). [`ModalSystem::terms`] is then empty.
    pub fn spectral(mass: Vec<f64>, stiffness: Vec<f64>, quartic: SpectralQuartic) -> Result<Self> {
        check_diagonals(&mass, &stiffness)?;
        let n = mass.len();
        if quartic.modes() != n {
            return Err(Error::invalid("quartic", format!("{} modes", quartic.modes()), format!("{n} modes")));
        }
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        Ok(ModalSystem {
            inv_mass,
            mass,
            stiffness,
            terms: Vec::new(),
            grad: Vec::new(),
            grad_start: vec![0; n + 1],
            small: None,
            spectral: Some(quartic),
            damping: ViscousDamping::default(),
        })
    }

    /// How the quartic force is evaluated: [`QuarticEvaluation::TermSum`] or
    /// [`QuarticEvaluation::Spectral`].
    pub fn evaluation(&self) -> QuarticEvaluation {
        if self.spectral.is_some() {
            QuarticEvaluation::Spectral
        } else {
            QuarticEvaluation::TermSum
        }
    }
}

/// The checks of [`ModalSystem::new`]: the diagonals ([`check_diagonals`]) and the quartic
/// terms (positions `< n`, finite coefficients).
pub fn check_model(mass: &[f64], stiffness: &[f64], terms: &[QuarticTerm]) -> Result<()> {
    check_diagonals(mass, stiffness)?;
    let n = mass.len();
    for (t, term) in terms.iter().enumerate() {
        if let Some(&bad) = term.idx.iter().find(|&&i| i as usize >= n) {
            return Err(Error::invalid(format!("quartic_index[{t}]"), bad, format!("mode positions in 0..{n}")));
        }
        if !term.coef.is_finite() {
            return Err(Error::invalid(format!("quartic_coef[{t}]"), Num(term.coef), "a finite number"));
        }
    }
    Ok(())
}

/// The checks of the diagonals of `M` (finite, `> 0`) and `K` (finite, as many) shared by the
/// constructors.
fn check_diagonals(mass: &[f64], stiffness: &[f64]) -> Result<()> {
    let n = mass.len();
    if n == 0 {
        return Err(Error::invalid("mass", "an empty vector", "at least one mode"));
    }
    if stiffness.len() != n {
        return Err(Error::invalid(
            "stiffness",
            format!("length {}", stiffness.len()),
            format!("length {n} (the number of modes)"),
        ));
    }
    for (i, &m) in mass.iter().enumerate() {
        if !(m.is_finite() && m > 0.0) {
            return Err(Error::invalid(format!("mass[{i}]"), Num(m), "a finite number > 0"));
        }
    }
    for (i, &k) in stiffness.iter().enumerate() {
        if !k.is_finite() {
            return Err(Error::invalid(format!("stiffness[{i}]"), Num(k), "a finite number"));
        }
    }
    Ok(())
}

impl ModalSystem {
    /// The same system with the viscous damping rate `c` (1/s, finite, `>= 0`; field
    /// `"damping_rate"`): the damping force `-c M q'`, so every linear mode decays as
    /// `exp(-c t / 2)`. `c = 0` is the undamped system, solved exactly as without this call.
    pub fn with_damping(mut self, c: f64) -> Result<Self> {
        self.damping = ViscousDamping::new(c)?;
        Ok(self)
    }

    /// The viscous damping rate `c`, 1/s.
    pub fn damping_rate(&self) -> f64 {
        self.damping.rate()
    }

    /// Number of modal coordinates.
    pub fn modes(&self) -> usize {
        self.mass.len()
    }

    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// The quartic terms (empty for a [`ModalSystem::spectral`] system).
    pub fn terms(&self) -> &[QuarticTerm] {
        &self.terms
    }

    /// The generalised force `K q + grad V(q)` into `out`.
    #[inline]
    pub fn force(&self, q: &[f64], out: &mut [f64]) {
        self.force_with(q, out, |_, f| f);
    }

    /// `finish(j, f_j)` into `out[j]` for the generalised force `f = K q + grad V(q)`: the
    /// force itself ([`ModalSystem::force`]) or the acceleration (`finish` divides by the
    /// mass). The term sums apply `finish` before storing: a second pass over `out` loads
    /// values the first has just stored, and a load spanning two of those stores waits for
    /// both (about a sixth of a 3-mode RKN12 step).
    #[inline]
    fn force_with(&self, q: &[f64], out: &mut [f64], finish: impl Fn(usize, f64) -> f64) {
        let n = self.modes();
        let (q, out) = (&q[..n], &mut out[..n]);
        if let Some(spectral) = &self.spectral {
            for ((o, &k), &x) in out.iter_mut().zip(&self.stiffness).zip(q) {
                *o = k * x;
            }
            spectral.add_gradient(q, out);
            for (j, o) in out.iter_mut().enumerate() {
                *o = finish(j, *o);
            }
            return;
        }
        if let Some(small) = &self.small {
            small.force_with(&self.stiffness, q, out, finish);
            return;
        }
        for j in 0..n {
            let mut acc = self.stiffness[j] * q[j];
            for mono in &self.grad[self.grad_start[j]..self.grad_start[j + 1]] {
                let [b, c, d] = mono.idx;
                acc += mono.coef * q[b as usize] * q[c as usize] * q[d as usize];
            }
            out[j] = finish(j, acc);
        }
    }

    /// `grad V(q)` alone into `out` (the force without `K q`).
    pub fn quartic_gradient(&self, q: &[f64], out: &mut [f64]) {
        let n = self.modes();
        let (q, out) = (&q[..n], &mut out[..n]);
        if let Some(spectral) = &self.spectral {
            out.fill(0.0);
            spectral.add_gradient(q, out);
            return;
        }
        for (j, o) in out.iter_mut().enumerate() {
            let mut acc = 0.0;
            for mono in &self.grad[self.grad_start[j]..self.grad_start[j + 1]] {
                let [b, c, d] = mono.idx;
                acc += mono.coef * q[b as usize] * q[c as usize] * q[d as usize];
            }
            *o = acc;
        }
    }

    /// The quartic potential `V(q)`.
    pub fn quartic_potential(&self, q: &[f64]) -> f64 {
        if let Some(spectral) = &self.spectral {
            return spectral.potential(&q[..self.modes()]);
        }
        self.terms
            .iter()
            .map(|t| t.coef * q[t.idx[0] as usize] * q[t.idx[1] as usize] * q[t.idx[2] as usize] * q[t.idx[3] as usize])
            .sum()
    }

    /// The energy `H = q'^T M q' / 2 + q^T K q / 2 + V(q)` (model notes), i.e. the PDE energy
    /// evaluated on the Galerkin expansion: conserved without damping, decreasing by the
    /// dissipated energy ([`SecondOrderSystem::dissipated_power`]) with it.
    pub fn energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let quadratic: f64 =
            (0..self.modes()).map(|i| 0.5 * (self.mass[i] * v[i] * v[i] + self.stiffness[i] * q[i] * q[i])).sum();
        quadratic + self.quartic_potential(q)
    }
}

impl Energy for ModalSystem {
    fn energy(&self, q: &[f64], v: &[f64]) -> f64 {
        ModalSystem::energy(self, q, v)
    }

    /// The quartic potential [`ModalSystem::quartic_potential`].
    fn potential(&self, q: &[f64]) -> f64 {
        self.quartic_potential(q)
    }
}

impl SecondOrderSystem for ModalSystem {
    fn dof(&self) -> usize {
        self.modes()
    }

    #[inline]
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        let n = self.modes();
        let inv_mass = &self.inv_mass[..n];
        let finish = |j: usize, f: f64| -f * inv_mass[j];
        match &self.small {
            // The small systems' path inline, the others through the call.
            Some(small) => small.force_with(&self.stiffness, &q[..n], acc, finish),
            None => self.force_with(q, acc, finish),
        }
    }

    fn velocity_dependent(&self) -> bool {
        self.damping.is_active()
    }

    /// `-M^-1 (K q + grad V(q)) - c q'`.
    #[inline]
    fn acceleration_full(&self, _t: f64, q: &[f64], v: &[f64], acc: &mut [f64]) {
        self.acceleration(q, acc);
        self.damping.add_acceleration(v, acc);
    }

    /// `c q'^T M q'`.
    fn dissipated_power(&self, _q: &[f64], v: &[f64]) -> f64 {
        self.damping.power(self.mass.iter().copied(), v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two coupled modes with a few terms, including repeated indices.
    fn sample() -> ModalSystem {
        ModalSystem::new(
            vec![2.0, 3.0],
            vec![5.0, -1.0],
            vec![
                QuarticTerm { idx: [0, 0, 0, 0], coef: 0.7 },
                QuarticTerm { idx: [0, 0, 1, 1], coef: -0.3 },
                QuarticTerm { idx: [0, 1, 1, 1], coef: 0.2 },
            ],
        )
        .unwrap()
    }

    #[test]
    fn force_is_gradient_of_energy() {
        let sys = sample();
        let q = [0.3, -0.7];
        let v = [0.0, 0.0];
        let mut f = [0.0; 2];
        sys.force(&q, &mut f);
        for i in 0..2 {
            let h = 1e-6;
            let mut qp = q;
            let mut qm = q;
            qp[i] += h;
            qm[i] -= h;
            let fd = (sys.energy(&qp, &v) - sys.energy(&qm, &v)) / (2.0 * h);
            assert!((fd - f[i]).abs() < 1e-8, "mode {i}: {fd} vs {}", f[i]);
        }
    }

    #[test]
    fn gradient_rows_merge_duplicates() {
        // V = 0.7 q0^4: one monomial 2.8 q0^3 in row 0
        let sys = ModalSystem::new(vec![1.0], vec![0.0], vec![QuarticTerm { idx: [0, 0, 0, 0], coef: 0.7 }]).unwrap();
        assert_eq!(sys.grad.len(), 1);
        assert!((sys.grad[0].coef - 2.8).abs() < 1e-15);
        // V = -0.3 q0^2 q1^2: rows 0 and 1 each get one merged monomial of weight -0.6
        let sys = sample();
        assert_eq!(sys.grad_start, vec![0, 3, 5]);
    }

    /// The straightforward merge (a linear search per monomial), for comparison.
    fn gradient_rows_by_search(n: usize, terms: &[QuarticTerm]) -> (Vec<CubicMonomial>, Vec<usize>) {
        let mut rows: Vec<Vec<CubicMonomial>> = vec![Vec::new(); n];
        for term in terms {
            for k in 0..4 {
                let mut rest: Vec<u32> = term.idx.to_vec();
                rest.remove(k);
                rest.sort_unstable();
                let rest = [rest[0], rest[1], rest[2]];
                let row = &mut rows[term.idx[k] as usize];
                match row.iter_mut().find(|mono| mono.idx == rest) {
                    Some(mono) => mono.coef += term.coef,
                    None => row.push(CubicMonomial { idx: rest, coef: term.coef }),
                }
            }
        }
        let mut grad = Vec::new();
        let mut start = Vec::new();
        for mut row in rows {
            start.push(grad.len());
            row.retain(|mono| mono.coef != 0.0);
            row.sort_by_key(|mono| mono.idx);
            grad.extend(row);
        }
        start.push(grad.len());
        (grad, start)
    }

    /// A deterministic xorshift sequence of `u64`.
    fn xorshift() -> impl FnMut() -> u64 {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    #[test]
    fn gradient_rows_match_the_straightforward_merge_bit_for_bit() {
        // Deterministic pseudo-random terms with many repeated index sets and cancellations.
        let mut next = xorshift();
        let n = 5;
        let terms: Vec<QuarticTerm> = (0..400)
            .map(|_| {
                let mut idx = [0u32; 4];
                for i in &mut idx {
                    *i = (next() % n as u64) as u32;
                }
                let coef = match next() % 4 {
                    0 => 1.0,
                    1 => -1.0,
                    _ => (next() % 1000) as f64 / 7.0 - 70.0,
                };
                QuarticTerm { idx, coef }
            })
            .collect();
        let (grad, start) = gradient_rows(n, &terms);
        let (want_grad, want_start) = gradient_rows_by_search(n, &terms);
        assert_eq!(start, want_start);
        assert_eq!(grad.len(), want_grad.len());
        for (a, b) in grad.iter().zip(&want_grad) {
            assert_eq!(a.idx, b.idx);
            assert_eq!(a.coef.to_bits(), b.coef.to_bits());
        }
    }

    /// Small systems (at most `SMALL_MAX_MODES` modes) evaluate the force with every cubic
    /// monomial and a dense coefficient matrix: equal to the rows (`K q` plus
    /// `quartic_gradient`) to rounding, for random coefficients on every index pattern of 1 to
    /// 4 modes; larger systems use the rows.
    #[test]
    fn small_systems_force_equals_the_rows() {
        let mut next = xorshift();
        let mut rand = move || (next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        for n in 1..=SMALL_MAX_MODES + 1 {
            let mut terms = Vec::new();
            for a in 0..n as u32 {
                for b in a..n as u32 {
                    for c in b..n as u32 {
                        for d in c..n as u32 {
                            terms.push(QuarticTerm { idx: [a, b, c, d], coef: rand() });
                        }
                    }
                }
            }
            let mass: Vec<f64> = (0..n).map(|_| 1.0 + rand().abs()).collect();
            let stiffness: Vec<f64> = (0..n).map(|_| rand()).collect();
            let sys = ModalSystem::new(mass.clone(), stiffness.clone(), terms).unwrap();
            assert_eq!(sys.small.is_some(), n <= SMALL_MAX_MODES, "{n} modes");
            for _ in 0..20 {
                let q: Vec<f64> = (0..n).map(|_| 3.0 * rand()).collect();
                let (mut f, mut g) = (vec![0.0; n], vec![0.0; n]);
                sys.force(&q, &mut f);
                sys.quartic_gradient(&q, &mut g);
                let scale: f64 = q.iter().map(|x| x.abs()).fold(0.0, f64::max).powi(3) * 20.0 + 1.0;
                for j in 0..n {
                    let rows = stiffness[j] * q[j] + g[j];
                    assert!((f[j] - rows).abs() <= 1e-14 * scale, "{n} modes, component {j}: {} vs {rows}", f[j]);
                }
                // The small path divides by the mass before storing: the same numbers.
                let mut acc = vec![0.0; n];
                sys.acceleration(&q, &mut acc);
                for j in 0..n {
                    assert_eq!(acc[j], -f[j] * (1.0 / mass[j]), "{n} modes, component {j}");
                }
            }
        }
    }

    #[test]
    fn acceleration_divides_by_mass() {
        let sys = sample();
        let q = [0.1, 0.2];
        let mut f = [0.0; 2];
        let mut a = [0.0; 2];
        sys.force(&q, &mut f);
        sys.acceleration(&q, &mut a);
        assert_eq!(a[0], -f[0] / 2.0);
        assert!((a[1] + f[1] / 3.0).abs() < 1e-16);
    }

    #[test]
    fn spectral_force_is_gradient_of_energy() {
        let terms = crate::terms::EQ18_TERMS
            .iter()
            .zip([3.0, 5.0, -7.0, 11.0, 13.0])
            .filter(|(spec, _)| spec.p + spec.r == 4)
            .map(|(spec, k)| spec.with(k).unwrap())
            .collect();
        let quartic = SpectralQuartic::new(vec![0, 1, 2, 3], 1.3, terms).unwrap();
        let sys = ModalSystem::spectral(vec![1.0, 2.0, 2.0, 2.0], vec![-1.0, 2.0, 5.0, 9.0], quartic).unwrap();
        assert!(sys.terms().is_empty() && sys.evaluation() == QuarticEvaluation::Spectral);
        let q = [0.3, -0.7, 0.2, 0.1];
        let v = [0.0; 4];
        let mut f = [0.0; 4];
        sys.force(&q, &mut f);
        for i in 0..4 {
            let h = 1e-6;
            let (mut qp, mut qm) = (q, q);
            qp[i] += h;
            qm[i] -= h;
            let fd = (sys.energy(&qp, &v) - sys.energy(&qm, &v)) / (2.0 * h);
            assert!((fd - f[i]).abs() < 1e-7 * (1.0 + f[i].abs()), "mode {i}: {fd} vs {}", f[i]);
        }
        let three = SpectralQuartic::new(vec![1, 2, 3], 1.0, vec![]).unwrap();
        assert_eq!(ModalSystem::spectral(vec![1.0; 2], vec![1.0; 2], three.clone()).unwrap_err().field(), "quartic");
        assert_eq!(ModalSystem::spectral(vec![0.0; 3], vec![1.0; 3], three).unwrap_err().field(), "mass[0]");
        assert_eq!(QuarticEvaluation::from_name("fft").unwrap_err().field(), "evaluation");
        for e in [QuarticEvaluation::Auto, QuarticEvaluation::TermSum, QuarticEvaluation::Spectral] {
            assert_eq!(QuarticEvaluation::from_name(e.name()).unwrap(), e);
        }
        assert_eq!(QuarticEvaluation::Auto.resolve(SPECTRAL_MIN_MODES - 1), QuarticEvaluation::TermSum);
        assert_eq!(QuarticEvaluation::Auto.resolve(SPECTRAL_MIN_MODES), QuarticEvaluation::Spectral);
        assert_eq!(QuarticEvaluation::TermSum.resolve(1000), QuarticEvaluation::TermSum);
    }

    #[test]
    fn rejects_bad_input() {
        assert_eq!(ModalSystem::new(vec![], vec![], vec![]).unwrap_err().field(), "mass");
        assert_eq!(ModalSystem::new(vec![1.0], vec![1.0, 2.0], vec![]).unwrap_err().field(), "stiffness");
        assert_eq!(ModalSystem::new(vec![-1.0], vec![1.0], vec![]).unwrap_err().field(), "mass[0]");
        assert_eq!(ModalSystem::new(vec![1.0], vec![f64::NAN], vec![]).unwrap_err().field(), "stiffness[0]");
        let bad = vec![QuarticTerm { idx: [0, 0, 0, 1], coef: 1.0 }];
        assert_eq!(ModalSystem::new(vec![1.0], vec![1.0], bad).unwrap_err().field(), "quartic_index[0]");
        let bad = vec![QuarticTerm { idx: [0, 0, 0, 0], coef: f64::INFINITY }];
        assert_eq!(ModalSystem::new(vec![1.0], vec![1.0], bad).unwrap_err().field(), "quartic_coef[0]");
    }
}

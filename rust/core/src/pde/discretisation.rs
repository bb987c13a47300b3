//! The nodal system [`PdeSystem`]: grid, discrete energy `H_h` and its Euler-Lagrange
//! accelerations (derivation in the module docs of [`crate::pde`]).
//!
//! [`PdeSystem::discretise`] takes a [`ModelTerms`] and discretises every conservative term by
//! one rule, the cell energy `h weight (a^p + b^p) / 2 g^r` ([`EnergyTerm::cell_energy`]), and
//! collects the terms' coefficients into the fused kernel ([`PdeSystem::force`]) once, at
//! construction: the kernel evaluates the shapes `th^2`, `th^4` (nodal), `th_z^2`, `th_z^4`
//! and `th^2 th_z^2` (cell), whatever the number of terms; a term of another shape is refused.

use crate::error::Num;
use crate::error::{Error, Result};
use crate::simd::{dispatch_len, Kernel, MulAdd};
use crate::system::{Energy, SecondOrderSystem};
use crate::terms::{Boundary, EnergyTerm, ModelTerms, ViscousDamping};

/// Largest number of nodes [`PdeSystem::new`] accepts (a solve holds a few dozen vectors of
/// this length; far beyond any grid an explicit method can step through).
pub const MAX_NODES: usize = 10_000_000;

/// The coefficients `k1 .. k6` of the PDE (model notes, eq. 18).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PdeCoefficients {
    pub k1: f64,
    pub k2: f64,
    pub k3: f64,
    pub k4: f64,
    pub k5: f64,
    pub k6: f64,
}

impl From<[f64; 6]> for PdeCoefficients {
    fn from([k1, k2, k3, k4, k5, k6]: [f64; 6]) -> Self {
        PdeCoefficients { k1, k2, k3, k4, k5, k6 }
    }
}

impl PdeCoefficients {
    /// `[k1, k2, k3, k4, k5, k6]`.
    pub fn to_array(&self) -> [f64; 6] {
        [self.k1, self.k2, self.k3, self.k4, self.k5, self.k6]
    }

    /// `k1`, `k2` finite and > 0, `k3 .. k6` finite.
    pub fn validate(&self) -> Result<()> {
        for (i, &k) in self.to_array().iter().enumerate() {
            let field = ["k1", "k2", "k3", "k4", "k5", "k6"][i];
            if i < 2 {
                if !(k.is_finite() && k > 0.0) {
                    return Err(Error::invalid(field, Num(k), "a finite number > 0"));
                }
            } else if !k.is_finite() {
                return Err(Error::invalid(field, Num(k), "a finite number"));
            }
        }
        Ok(())
    }
}

/// `nodes` in `3..=MAX_NODES` (`"nodes"`), `length` finite and `> 0` (`"length"`).
fn check_grid(length: f64, nodes: usize) -> Result<()> {
    if !(3..=MAX_NODES).contains(&nodes) {
        return Err(Error::invalid("nodes", nodes, format!("an integer in 3..={MAX_NODES}")));
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(Error::invalid("length", Num(length), "a finite number > 0"));
    }
    Ok(())
}

/// Adds `term` to the kernel coefficients `k` (eq. 18's names) by its shape: the
/// Euler-Lagrange force of the cell energy `h weight (a^p + b^p) / 2 g^r` is what the kernel
/// evaluates with `k3 = 4 weight` (`th^4`), `k6 = -2 weight` (`th^2`), `k2 = 2 weight`
/// (`th_z^2`), `k5 = 4 weight` (`th_z^4`), `k4 = 2 weight` (`th^2 th_z^2`).
fn collect(k: &mut PdeCoefficients, term: &EnergyTerm) -> Result<()> {
    // n weight as (n factor) k: n factor is +-1 for eq. 18's terms, so the slot is exactly +-k
    let times = |n: f64| n * term.spec().factor() * term.coefficient();
    match term.exponents() {
        (4, 0) => k.k3 += times(4.0),
        (2, 0) => k.k6 -= times(2.0),
        (0, 2) => k.k2 += times(2.0),
        (0, 4) => k.k5 += times(4.0),
        (2, 2) => k.k4 += times(2.0),
        (p, r) => {
            return Err(Error::invalid(
                term.spec().coefficient,
                format!("the {} term th^{p} th_z^{r}", term.name()),
                "a shape of the finite-difference kernel: th^2, th^4, th_z^2, th_z^4 or th^2 th_z^2",
            ))
        }
    }
    Ok(())
}

/// The semi-discrete PDE on `N` nodes: `q_j = th(z_j)`, `q_j'' = -(dV_h/dth_j) / (w_j k1)`.
///
/// Holds only scalars: [`SecondOrderSystem::acceleration`] is one allocation-free pass over
/// the cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PdeSystem {
    k: PdeCoefficients,
    length: f64,
    nodes: usize,
    /// The spacing `h = l / (N - 1)`.
    h: f64,
    /// Viscous damping rate `c`, 1/s (force `-k1 c th_t` per unit length).
    damping: ViscousDamping,
}

impl PdeSystem {
    /// The discretisation of the PDE with coefficients `k` on `[0, length]` with `nodes`
    /// nodes (ends included): [`PdeSystem::discretise`] of [`ModelTerms::from_coefficients`].
    /// Refuses `nodes < 3` or `> MAX_NODES` (field `"nodes"`), a non-finite or non-positive
    /// `length` (`"length"`), non-finite `k` (`"k1"` .. `"k6"`) and `k1 <= 0` or `k2 <= 0`.
    pub fn new(k: impl Into<PdeCoefficients>, length: f64, nodes: usize) -> Result<Self> {
        let k = k.into();
        check_grid(length, nodes)?;
        k.validate()?;
        PdeSystem::discretise(&ModelTerms::from_coefficients(k)?, length, nodes)
    }

    /// The finite differences of `model` on `[0, length]` with `nodes` nodes (ends included):
    /// each term's cell energy, its coefficient collected into the kernel slot of its shape;
    /// the model's damping, lumped like the inertia; the model's boundary at the end nodes
    /// ([`Boundary::Free`]: natural ends).
    ///
    /// Errors: the grid (as [`PdeSystem::new`]), a term of a shape the kernel does not
    /// evaluate (field: its coefficient, naming the term), and collected coefficients with
    /// `k2 <= 0` (no wave propagation: field `"k2"`).
    pub fn discretise(model: &ModelTerms, length: f64, nodes: usize) -> Result<Self> {
        check_grid(length, nodes)?;
        match model.boundary() {
            // the kernel's end nodes drop the missing cells: th_z = 0 is natural
            Boundary::Free => {}
        }
        let mut k = PdeCoefficients { k1: model.inertia(), k2: 0.0, k3: 0.0, k4: 0.0, k5: 0.0, k6: 0.0 };
        for term in model.conservative() {
            collect(&mut k, term)?;
        }
        k.validate()?;
        let h = length / (nodes - 1) as f64;
        if !(1.0 / (h * k.k1)).is_finite() {
            return Err(Error::invalid(
                "length",
                length,
                format!("a grid spacing h = l / {} with 1 / (h k1) finite", nodes - 1),
            ));
        }
        Ok(PdeSystem { k, length, nodes, h, damping: model.damping() })
    }

    /// The same system with viscous damping: the force `-k1 c th_t` per unit length, lumped
    /// like the inertia (`-w_j k1 c v_j` on node `j`), so `q_j'' = ... - c v_j` and the
    /// dissipated power is `c sum_j w_j k1 v_j^2`. `c` (1/s) finite and `>= 0` (field
    /// `"damping_rate"`); `c = 0` is the undamped system, solved exactly as without this call.
    pub fn with_damping(mut self, c: f64) -> Result<Self> {
        self.damping = ViscousDamping::new(c)?;
        Ok(self)
    }

    /// The viscous damping rate `c`, 1/s.
    pub fn damping_rate(&self) -> f64 {
        self.damping.rate()
    }

    pub fn coefficients(&self) -> PdeCoefficients {
        self.k
    }

    /// The length `l`.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The number of nodes `N` (the number of unknowns).
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// The node spacing `h = l / (N - 1)`.
    pub fn spacing(&self) -> f64 {
        self.h
    }

    /// The node position `z_j = j h` (`z_{N-1} = l` exactly).
    pub fn z(&self, j: usize) -> f64 {
        if j + 1 >= self.nodes {
            self.length
        } else {
            j as f64 * self.h
        }
    }

    /// All node positions.
    pub fn positions(&self) -> Vec<f64> {
        (0..self.nodes).map(|j| self.z(j)).collect()
    }

    /// The trapezoid weight `w_j` (`h / 2` at the ends, `h` inside).
    pub fn weight(&self, j: usize) -> f64 {
        if j == 0 || j + 1 == self.nodes {
            0.5 * self.h
        } else {
            self.h
        }
    }

    /// All node weights (they sum to `l`).
    pub fn weights(&self) -> Vec<f64> {
        (0..self.nodes).map(|j| self.weight(j)).collect()
    }

    /// The nodal velocities `th_t(z_j) = sum_i c[i - 1] cos(i pi z_j / l)` of a modal
    /// initial condition (`c[0]` is the amplitude of mode `i = 1`; paper eq. 13).
    pub fn initial_velocity_from_modes(&self, c: &[f64]) -> Vec<f64> {
        let kz = std::f64::consts::PI / self.length;
        (0..self.nodes)
            .map(|j| {
                let z = self.z(j);
                c.iter().enumerate().map(|(m, &ci)| ci * ((m + 1) as f64 * kz * z).cos()).sum()
            })
            .collect()
    }

    /// The piecewise-linear (finite-element) interpolant of the nodal values `q` at `z`
    /// (clamped to `[0, l]`).
    pub fn interpolate(&self, q: &[f64], z: f64) -> f64 {
        let n = self.nodes;
        let s = (z / self.h).clamp(0.0, (n - 1) as f64);
        let c = (s.floor() as usize).min(n - 2);
        let frac = s - c as f64;
        (1.0 - frac) * q[c] + frac * q[c + 1]
    }

    /// The discrete potential `V_h(q)` (everything in `H_h` but the kinetic term).
    pub fn potential(&self, q: &[f64]) -> f64 {
        let PdeCoefficients { k2, k3, k4, k5, k6, .. } = self.k;
        let q = &q[..self.nodes];
        let nodal: f64 = q
            .iter()
            .enumerate()
            .map(|(j, &th)| {
                let th2 = th * th;
                self.weight(j) * (0.25 * k3 * th2 * th2 - 0.5 * k6 * th2)
            })
            .sum();
        let inv_h = 1.0 / self.h;
        let cells: f64 = q
            .windows(2)
            .map(|pair| {
                let (a, b) = (pair[0], pair[1]);
                let g = (b - a) * inv_h;
                let g2 = g * g;
                g2 * (0.5 * k2 + 0.25 * k4 * (a * a + b * b) + 0.25 * k5 * g2)
            })
            .sum();
        nodal + self.h * cells
    }

    /// The discrete energy `H_h(q, v)`, conserved by the semi-discrete system without damping.
    pub fn energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let kinetic: f64 =
            v[..self.nodes].iter().enumerate().map(|(j, &vj)| self.weight(j) * 0.5 * self.k.k1 * vj * vj).sum();
        kinetic + self.potential(q)
    }

    /// The generalised force `dV_h/dth` (the gradient of [`PdeSystem::potential`]) into
    /// `out`: one pass over the cells, no allocation.
    #[inline]
    pub fn force(&self, q: &[f64], out: &mut [f64]) {
        dispatch_len(self.nodes, Sweep { sys: self, q, out, scale: 1.0, end_factor: 1.0 });
    }

    /// `scale * dV_h/dth_j` for interior nodes and `end_factor * scale * dV_h/dth_j` at the ends.
    ///
    /// With the flux `F_c = g (k2 + k4/2 (a^2 + b^2) + k5 g^2)` and `S_c = h k4/2 g^2` of
    /// cell `c` (nodes `a = q_c`, `b = q_c+1`, `g = (b - a)/h`), the force on node `j` is
    /// `w_j th_j (k3 th_j^2 - k6) + (F_{j-1} + S_{j-1} th_j) - (F_j - S_j th_j)`, the cell
    /// terms present where the cell exists. Interior nodes go in blocks of [`NODE_BLOCK`]:
    /// the fluxes of the block's cells into a small stack array, then the nodes, two
    /// loops without a carried dependency that the compiler vectorises.
    #[inline(always)]
    fn sweep(&self, q: &[f64], out: &mut [f64], scale: f64, end_factor: f64) {
        let n = self.nodes;
        let (q, out) = (&q[..n], &mut out[..n]);
        let cells = self.cell_terms();
        let half_h = 0.5 * self.h;
        // (F, S) of the cell left of the next node.
        let mut left = cells.flux(q[0], q[1]);
        out[0] = (half_h * cells.nodal(q[0]) - left.0 + left.1 * q[0]) * (scale * end_factor);
        let mut j0 = 1;
        while j0 + NODE_BLOCK < n {
            left = node_block::<NODE_BLOCK>(&cells, q, out, j0, left, scale);
            j0 += NODE_BLOCK;
        }
        while j0 + 1 < n {
            left = node_block::<1>(&cells, q, out, j0, left, scale);
            j0 += 1;
        }
        out[n - 1] = (half_h * cells.nodal(q[n - 1]) + left.0 + left.1 * q[n - 1]) * (scale * end_factor);
    }

    /// The coefficient combinations of [`PdeSystem::sweep`].
    #[inline(always)]
    fn cell_terms(&self) -> CellTerms {
        let PdeCoefficients { k2, k3, k4, k5, k6, .. } = self.k;
        CellTerms { h: self.h, inv_h: 1.0 / self.h, k2, k3, half_k4: 0.5 * k4, k5, k6 }
    }
}

/// Interior nodes `j0 .. j0 + B` of [`PdeSystem::sweep`], given `(F, S)` of cell `j0 - 1`;
/// returns those of cell `j0 + B - 1`.
#[inline(always)]
fn node_block<const B: usize>(
    cells: &CellTerms,
    q: &[f64],
    out: &mut [f64],
    j0: usize,
    left: (f64, f64),
    scale: f64,
) -> (f64, f64) {
    // Index l + 1 holds cell j0 + l; index 0 the cell on the left of the block.
    let mut flux = [0.0; NODE_BLOCK + 1];
    let mut s = [0.0; NODE_BLOCK + 1];
    (flux[0], s[0]) = left;
    let a: &[f64; B] = q[j0..j0 + B].try_into().expect("B nodes");
    let b: &[f64; B] = q[j0 + 1..j0 + B + 1].try_into().expect("B nodes");
    for l in 0..B {
        let (f, sl) = cells.flux(a[l], b[l]);
        flux[l + 1] = f;
        s[l + 1] = sl;
    }
    let out: &mut [f64; B] = (&mut out[j0..j0 + B]).try_into().expect("B nodes");
    for l in 0..B {
        let th = a[l];
        out[l] = (cells.h * cells.nodal(th) + (s[l] + s[l + 1]) * th + (flux[l] - flux[l + 1])) * scale;
    }
    (flux[B], s[B])
}

/// The kernel of [`PdeSystem::force`] and the acceleration.
struct Sweep<'a> {
    sys: &'a PdeSystem,
    q: &'a [f64],
    out: &'a mut [f64],
    scale: f64,
    end_factor: f64,
}

impl Kernel for Sweep<'_> {
    type Output = ();

    /// Plain products: with `mul_add` the compiler keeps this loop scalar, so the kernel uses
    /// the dispatch only for the wider vectors (`cargo bench --bench pde`: 277 ns for the
    /// acceleration at N = 240 on AVX2).
    #[inline(always)]
    fn run<M: MulAdd>(self) {
        self.sys.sweep(self.q, self.out, self.scale, self.end_factor);
    }
}

/// Interior nodes per block of [`PdeSystem::sweep`].
const NODE_BLOCK: usize = 16;

/// `h`, `1/h` and the coefficients, as [`PdeSystem::sweep`] uses them.
#[derive(Clone, Copy)]
struct CellTerms {
    h: f64,
    inv_h: f64,
    k2: f64,
    k3: f64,
    half_k4: f64,
    k5: f64,
    k6: f64,
}

impl CellTerms {
    /// `th (k3 th^2 - k6)`, the nodal force per unit weight.
    #[inline(always)]
    fn nodal(&self, th: f64) -> f64 {
        th * (self.k3 * th * th - self.k6)
    }

    /// `(F_c, S_c)` of the cell with end values `a`, `b`.
    #[inline(always)]
    fn flux(&self, a: f64, b: f64) -> (f64, f64) {
        let g = (b - a) * self.inv_h;
        let g2 = g * g;
        let flux = g * (self.k2 + self.half_k4 * (a * a + b * b) + self.k5 * g2);
        (flux, self.h * self.half_k4 * g2)
    }
}

impl Energy for PdeSystem {
    fn energy(&self, q: &[f64], v: &[f64]) -> f64 {
        PdeSystem::energy(self, q, v)
    }

    /// The discrete potential [`PdeSystem::potential`].
    fn potential(&self, q: &[f64]) -> f64 {
        PdeSystem::potential(self, q)
    }
}

impl SecondOrderSystem for PdeSystem {
    fn dof(&self) -> usize {
        self.nodes
    }

    /// `q_j'' = -(dV_h/dth_j) / (w_j k1)`.
    #[inline]
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        // 1 / (w_j k1): 1 / (h k1) inside, twice that at the ends.
        dispatch_len(self.nodes, Sweep { sys: self, q, out: acc, scale: -1.0 / (self.h * self.k.k1), end_factor: 2.0 });
    }

    fn velocity_dependent(&self) -> bool {
        self.damping.is_active()
    }

    /// `-(dV_h/dth_j) / (w_j k1) - c v_j`.
    #[inline]
    fn acceleration_full(&self, _t: f64, q: &[f64], v: &[f64], acc: &mut [f64]) {
        self.acceleration(q, acc);
        self.damping.add_acceleration(&v[..self.nodes], &mut acc[..self.nodes]);
    }

    /// `c k1 sum_j w_j v_j^2`.
    fn dissipated_power(&self, _q: &[f64], v: &[f64]) -> f64 {
        let masses = (0..self.nodes).map(|j| self.k.k1 * self.weight(j));
        self.damping.power(masses, &v[..self.nodes])
    }
}

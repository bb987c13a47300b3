//! A field on the string: one wave equation in its two Riemann invariants, on the cells of
//! every section, with each section's wave speed (through its Courant number) and impedance.
//!
//! The torsional field is `(omega, tau)` with inertia per length `rho J` and impedance
//! `J sqrt(G rho)`; an axial field is the same type with `(v, N)`, `rho A` and `A sqrt(E rho)`
//! (wave speed `sqrt(E / rho)`): [`FieldSection::new`] takes the inertia per length and the
//! impedance, nothing torsional. The state is padded per section, `[ghost, cells..., ghost]`;
//! the boundaries and junctions set the ghosts ([`Field::set_top`], [`Field::set_bottom`],
//! [`Field::junctions`]) and [`super::kernel`] advances the cells.
//!
//! With the `consistent` nonlinearity the torsional field holds `(omega, eps)` per cell
//! ([`Nonlinear`]) and the ghosts are face values; the ends and junctions see it through the
//! same [`Arriving`] characteristics.

use super::boundary::Arriving;
use super::energy::Ledger;
use super::sampler::Channel;
use crate::drilling::grid::{Grid, SectionProps};

/// What a field on the string does in a step and in sampling: the characteristic arriving at
/// each end, the ends and the junctions set for the step, its cells advanced over the step
/// with its own sources (their work booked), its stored energies, its cells for the
/// snapshots and the output channels its ends fill. Implemented by the torsional field
/// ([`super::torsion::Torsion`]) and the axial one ([`super::axial_field::Axial`]); the run
/// calls them in a fixed order ([`super::run::Simulation`]'s step), never per cell.
pub trait StringField {
    /// The series' channels of this field and its ends ([`super::sampler`]).
    fn channels() -> &'static [Channel];
    /// The field's cells (the ends, junctions and energies below act on them).
    fn field(&self) -> &Field;
    fn field_mut(&mut self) -> &mut Field;
    /// The characteristic arriving at the top end.
    #[inline]
    fn arriving_top(&self) -> Arriving {
        self.field().arriving_top()
    }
    /// The characteristic arriving at the bottom end.
    #[inline]
    fn arriving_bottom(&self) -> Arriving {
        self.field().arriving_bottom()
    }
    /// Sets the top end for the step: its speed `w` and the load `load` it carries.
    #[inline]
    fn set_top(&mut self, arriving: Arriving, w: f64, load: f64) {
        self.field_mut().set_top(arriving, w, load);
    }
    /// Sets the bottom end for the step: its speed `w`.
    #[inline]
    fn set_bottom(&mut self, arriving: Arriving, w: f64) {
        self.field_mut().set_bottom(arriving, w);
    }
    /// Sets the junctions between sections for the step.
    #[inline]
    fn junctions(&mut self) {
        self.field_mut().junctions();
    }
    /// The cells over a step of `dt` (the transport and the field's sources), the work booked
    /// in `ledger` when `booked` (`numerics.energy_balance`); the new state made current.
    fn advance(&mut self, dt: f64, ledger: &mut Ledger, booked: bool);
    /// The kinetic and elastic energies stored in the cells, J.
    #[inline]
    fn stored(&self) -> (f64, f64) {
        self.field().energies()
    }
    /// Calls `f(speed, load)` for every cell from the top down, as the snapshots store them.
    fn each_cell(&self, f: impl FnMut(f64, f64));
}

/// One section's slice of the padded state: `[ghost alpha, cells..., ghost beta]`.
#[derive(Debug, Clone, Copy)]
pub struct FieldSection {
    /// Index of the top ghost.
    pub offset: usize,
    pub cells: usize,
    /// `c dt / h`.
    pub courant: f64,
    /// `m h / 4` with `m` the inertia per length (`rho J`; axial `rho A`): a cell's energy is
    /// `e (alpha^2 + beta^2)`.
    pub e: f64,
    /// `Z` (torsional `J sqrt(G rho)`, axial `A sqrt(E rho)`).
    pub impedance: f64,
    /// Cell length, m.
    pub h: f64,
    /// Inertia per length (`rho J`, axial `rho A`).
    pub inertia_per_length: f64,
}

impl FieldSection {
    /// A section of `cells` cells of length `h` at padded index `offset`.
    pub fn new(offset: usize, cells: usize, courant: f64, h: f64, inertia_per_length: f64, impedance: f64) -> Self {
        FieldSection { offset, cells, courant, e: 0.25 * inertia_per_length * h, impedance, h, inertia_per_length }
    }

    /// The padded range `[ghost, cells, ghost]`.
    #[inline]
    pub fn padded(&self) -> std::ops::Range<usize> {
        self.offset..self.offset + self.cells + 2
    }
}

/// The state of the `consistent` scheme: cell speed and twist per length, padded like the
/// invariants (`[ghost, cells, ghost]` per section, ghosts unused), and the face values
/// `(omega*, tau*)` at padded index `offset + j` for the face below cell `j` (`offset`: the
/// section's top face).
#[derive(Clone)]
pub struct Nonlinear {
    /// The finite-strain torque-twist law of each section.
    pub laws: Vec<SectionProps>,
    pub omega: Vec<f64>,
    pub strain: Vec<f64>,
    pub omega_next: Vec<f64>,
    pub strain_next: Vec<f64>,
    pub face_omega: Vec<f64>,
    pub face_torque: Vec<f64>,
    /// Per cell in a step: tangent impedance and torque.
    pub cell_impedance: Vec<f64>,
    pub cell_torque: Vec<f64>,
    /// Largest `|eps|` of each section's cells so far.
    pub peak_strain: Vec<f64>,
}

/// A field: its sections and its state.
#[derive(Clone)]
pub struct Field {
    pub sections: Vec<FieldSection>,
    /// The invariants `alpha = w + s / Z` (down) and `beta = w - s / Z` (up), padded, and the
    /// next step's.
    pub alpha: Vec<f64>,
    pub beta: Vec<f64>,
    pub alpha_next: Vec<f64>,
    pub beta_next: Vec<f64>,
    /// `Some` for the `consistent` nonlinearity (then `alpha`, `beta` are unused).
    pub nl: Option<Nonlinear>,
}

impl Field {
    /// The torsional field of a grid at rest (`consistent`: the finite-strain state).
    pub fn torsional(grid: &Grid, consistent: bool) -> Self {
        let mut sections = Vec::with_capacity(grid.props.len());
        let mut offset = 0;
        for (s, p) in grid.props.iter().enumerate() {
            let n = grid.counts[s];
            sections.push(FieldSection::new(
                offset,
                n,
                grid.courant[s],
                grid.spacing[s],
                p.inertia_per_length,
                p.impedance,
            ));
            offset += n + 2;
        }
        let len = offset;
        let nl = consistent.then(|| Nonlinear {
            laws: grid.props.clone(),
            omega: vec![0.0; len],
            strain: vec![0.0; len],
            omega_next: vec![0.0; len],
            strain_next: vec![0.0; len],
            face_omega: vec![0.0; len],
            face_torque: vec![0.0; len],
            cell_impedance: vec![0.0; len],
            cell_torque: vec![0.0; len],
            peak_strain: vec![0.0; grid.props.len()],
        });
        Field {
            sections,
            alpha: vec![0.0; len],
            beta: vec![0.0; len],
            alpha_next: vec![0.0; len],
            beta_next: vec![0.0; len],
            nl,
        }
    }

    /// Padded length.
    pub fn padded_len(&self) -> usize {
        self.alpha.len()
    }

    /// Cells of all sections.
    pub fn cells(&self) -> usize {
        self.sections.iter().map(|s| s.cells).sum()
    }

    /// The first and the last section.
    #[inline]
    pub fn first(&self) -> FieldSection {
        self.sections[0]
    }

    #[inline]
    pub fn last(&self) -> FieldSection {
        *self.sections.last().expect("at least one section")
    }

    /// Sets cell `k` (0-based over the string) of section `s` to speed `w` and load `tau`.
    pub fn set_cell(&mut self, s: usize, j: usize, w: f64, tau: f64) {
        let sp = self.sections[s];
        match &mut self.nl {
            Some(nl) => {
                nl.omega[sp.offset + j] = w;
                nl.strain[sp.offset + j] = nl.laws[s].strain(tau);
            }
            None => {
                let r = tau / sp.impedance;
                self.alpha[sp.offset + j] = w + r;
                self.beta[sp.offset + j] = w - r;
            }
        }
    }

    /// Speed and load of cell `j` (1-based) of section `s`.
    #[inline]
    pub fn cell(&self, s: usize, j: usize) -> (f64, f64) {
        let sp = &self.sections[s];
        match &self.nl {
            Some(nl) => (nl.omega[sp.offset + j], nl.laws[s].torque(nl.strain[sp.offset + j])),
            None => {
                let (a, b) = (self.alpha[sp.offset + j], self.beta[sp.offset + j]);
                (0.5 * (a + b), 0.5 * sp.impedance * (a - b))
            }
        }
    }

    /// Calls `f(speed, load)` for every cell from the top down.
    pub fn each_cell(&self, mut f: impl FnMut(f64, f64)) {
        for (s, sp) in self.sections.iter().enumerate() {
            for j in 1..=sp.cells {
                let (w, tau) = self.cell(s, j);
                f(w, tau);
            }
        }
    }

    /// The characteristic leaving cell `j` of section `s` towards a face and the impedance it
    /// travels with: downwards (`down`) `omega + tau / Z`, else `omega - tau / Z`
    /// (`consistent`: `Z` the tangent impedance of the cell's twist).
    #[inline]
    pub fn outgoing(&self, s: usize, j: usize, down: bool) -> Arriving {
        let sp = &self.sections[s];
        match &self.nl {
            Some(nl) => {
                let law = &nl.laws[s];
                let eps = nl.strain[sp.offset + j];
                let z = law.tangent_impedance(eps);
                let r = law.torque(eps) / z;
                let w = nl.omega[sp.offset + j];
                Arriving { value: if down { w + r } else { w - r }, impedance: z }
            }
            None => Arriving {
                value: if down { self.alpha[sp.offset + j] } else { self.beta[sp.offset + j] },
                impedance: sp.impedance,
            },
        }
    }

    /// The characteristic arriving at the top end (`beta_1`).
    #[inline]
    pub fn arriving_top(&self) -> Arriving {
        self.outgoing(0, 1, false)
    }

    /// The characteristic arriving at the bottom end (`alpha_n`).
    #[inline]
    pub fn arriving_bottom(&self) -> Arriving {
        let s = self.sections.len() - 1;
        self.outgoing(s, self.sections[s].cells, true)
    }

    /// Sets the top end for the step: its speed `w` and the load `tau` it carries.
    #[inline]
    pub fn set_top(&mut self, arriving: Arriving, w: f64, tau: f64) {
        let first = self.first();
        match &mut self.nl {
            Some(nl) => {
                nl.face_omega[first.offset] = w;
                nl.face_torque[first.offset] = tau;
            }
            None => self.alpha[first.offset] = 2.0 * w - arriving.value,
        }
    }

    /// Sets the bottom end for the step: its speed `w` (the load follows from `arriving`).
    #[inline]
    pub fn set_bottom(&mut self, arriving: Arriving, w: f64) {
        let last = self.last();
        match &mut self.nl {
            Some(nl) => {
                nl.face_omega[last.offset + last.cells] = w;
                nl.face_torque[last.offset + last.cells] = arriving.impedance * (arriving.value - w);
            }
            None => self.beta[last.offset + last.cells + 1] = 2.0 * w - arriving.value,
        }
    }

    /// The junctions between sections: continuity of speed and load,
    /// `w = (Z_a alpha_a + Z_b beta_b) / (Z_a + Z_b)`; each sets the ghost invariant entering
    /// its neighbouring cells (`consistent`: both faces).
    pub fn junctions(&mut self) {
        for k in 1..self.sections.len() {
            let (a, b) = (self.sections[k - 1], self.sections[k]);
            let down = self.outgoing(k - 1, a.cells, true);
            let up = self.outgoing(k, 1, false);
            let (za, zb) = (down.impedance, up.impedance);
            let w = (za * down.value + zb * up.value) / (za + zb);
            match &mut self.nl {
                Some(nl) => {
                    let tau = za * (down.value - w);
                    for face in [a.offset + a.cells, b.offset] {
                        nl.face_omega[face] = w;
                        nl.face_torque[face] = tau;
                    }
                }
                None => {
                    self.beta[a.offset + a.cells + 1] = 2.0 * w - down.value;
                    self.alpha[b.offset] = 2.0 * w - up.value;
                }
            }
        }
    }

    /// `(kinetic, elastic)` energy of the field, J.
    pub fn energies(&self) -> (f64, f64) {
        let (mut kin, mut ela) = (0.0, 0.0);
        if let Some(nl) = &self.nl {
            for (sp, law) in self.sections.iter().zip(&nl.laws) {
                let (mut k, mut e) = (0.0, 0.0);
                for j in 1..=sp.cells {
                    let w = nl.omega[sp.offset + j];
                    k += w * w;
                    e += law.elastic_energy(nl.strain[sp.offset + j]);
                }
                kin += 0.5 * law.inertia_per_length * sp.h * k;
                ela += sp.h * e;
            }
        } else {
            for sp in &self.sections {
                let (mut k, mut e) = (0.0, 0.0);
                for j in 1..=sp.cells {
                    let (a, b) = (self.alpha[sp.offset + j], self.beta[sp.offset + j]);
                    k += (a + b) * (a + b);
                    e += (a - b) * (a - b);
                }
                kin += 0.5 * sp.e * k;
                ela += 0.5 * sp.e * e;
            }
        }
        (kin, ela)
    }

    /// The speed of the cell at padded index `k`.
    #[inline]
    pub fn speed(&self, k: usize) -> f64 {
        match &self.nl {
            Some(nl) => nl.omega[k],
            None => 0.5 * (self.alpha[k] + self.beta[k]),
        }
    }

    /// The speeds at every padded index into `out` (the ghosts' values meaningless).
    pub fn speeds(&self, out: &mut [f64]) {
        match &self.nl {
            Some(nl) => out.copy_from_slice(&nl.omega),
            None => {
                for ((o, a), b) in out.iter_mut().zip(&self.alpha).zip(&self.beta) {
                    *o = 0.5 * (a + b);
                }
            }
        }
    }

    /// Changes the speed of the cell at padded index `k` by `d`, its load kept; with `stop`, sets
    /// it exactly to rest instead (the load kept).
    #[inline]
    pub fn change_speed(&mut self, k: usize, d: f64, stop: bool) {
        match &mut self.nl {
            Some(nl) => nl.omega[k] = if stop { 0.0 } else { nl.omega[k] + d },
            None if stop => {
                let s = 0.5 * (self.alpha[k] - self.beta[k]);
                self.alpha[k] = s;
                self.beta[k] = -s;
            }
            None => {
                self.alpha[k] += d;
                self.beta[k] += d;
            }
        }
    }

    /// Makes the next state the current one.
    #[inline]
    pub fn swap(&mut self) {
        match &mut self.nl {
            Some(nl) => {
                std::mem::swap(&mut nl.omega, &mut nl.omega_next);
                std::mem::swap(&mut nl.strain, &mut nl.strain_next);
            }
            None => {
                std::mem::swap(&mut self.alpha, &mut self.alpha_next);
                std::mem::swap(&mut self.beta, &mut self.beta_next);
            }
        }
    }
}

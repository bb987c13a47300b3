//! The coupled wall friction of a coupled run (`friction.coupling = "axial_torsional"`): the
//! wall's Coulomb friction against the contact's sliding velocity `(v, r omega)` (the axial
//! speed and the contact radius times the angular speed), shared by the axial and the
//! torsional field, with one stick phase. A rotating string slides axially with little drag.
//!
//! The law, [`slide`] (the one place of the convention): per length of contact, the normal
//! force `N` (the one the torsional wall friction uses, [`crate::drilling::grid::Grid::limit`]
//! over `mu_s r`) limits the friction force `f = (f_a, f_t)` (axial, tangential at the contact)
//! to `|f| <= mu_s N`. With the speeds after the transport and the other sources (damping, the
//! buoyed weight) `u = (v, r omega)` and the angular sliding speed `s = |u| / r`:
//!
//! * slow, `s < friction.stick_speed` (or the contact at rest): the force that stops both
//!   speeds in the step, `-(rho A v, rho J omega / r) / dt`, if within `mu_s N` (stick: both
//!   stop exactly, the loads kept), else that force scaled to `mu_s N` (the stop force
//!   clipped to the static limit, as the torsional law's);
//! * sliding: the kinetic force `mu_k N` against `u`, `f = -mu_k N u / |u|`, its axial part
//!   `-mu_k N v / |u|` and its torque per length `-mu_k N r (r omega) / |u|`; a component that
//!   would reverse its speed in the step stops instead (exactly, the load kept);
//! * `regularised`: `f = -mu_k N tanh(s / v_r) u / |u|`, no stick, a component never reversed.
//!
//! The changes of speed over a step are `dt f_a / (rho A)` and `dt r f_t / (rho J)`: with the
//! static-limit changes `la = dt mu_s N / (rho A)` and `lt = dt mu_s N r / (rho J)` (the
//! torsional wall friction's `stop`, [`super::sources::WallFriction`]) the law needs no other
//! property. Without axial speed the sliding branch is the torsional law's (`-mu_k N r sign
//! omega` per length).
//!
//! The two fields have their own cells (the axial cells are longer: the axial wave is faster
//! on the common time step). The friction acts on the overlay of both grids: each segment
//! (the intersection of a torsional and an axial cell, length `l`) slides at its torsional
//! cell's angular speed and its axial cell's axial speed with its torsional cell's normal
//! force; a cell's change is the length-weighted mean of its segments' changes (`l / h`), and
//! a cell sticks (set exactly to rest) when all its segments stick. Every segment's change is
//! against its cell's speed and never reverses it, so the friction's work on each cell,
//! `m h delta (w + delta / 2)`, is a loss; it is booked as `friction_loss` (the axial part also
//! as `axial_friction_loss`).

use crate::drilling::config::{DrillConfig, FrictionModel};
use crate::drilling::grid::Grid;

use super::field::Field;

/// The constants of [`slide`].
#[derive(Debug, Clone, Copy)]
pub struct Law {
    /// The angular sliding speed below which a contact is slow (`friction.stick_speed`, or the
    /// least positive double when it is 0: then only a contact at rest is slow), rad/s.
    pub slow_below: f64,
    /// `friction.kinetic_ratio`.
    pub kinetic_ratio: f64,
    /// `Some(1 / v_r)` for the regularised law.
    pub inv_regularisation: Option<f64>,
}

impl Law {
    pub fn new(cfg: &DrillConfig) -> Self {
        let fr = &cfg.friction;
        Law {
            slow_below: if fr.stick_speed > 0.0 { fr.stick_speed } else { f64::from_bits(1) },
            kinetic_ratio: fr.kinetic_ratio,
            inv_regularisation: (fr.model == FrictionModel::Regularised).then(|| 1.0 / fr.regularisation_speed),
        }
    }
}

/// The friction's changes of a contact's speeds over a step and which speeds it stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slide {
    /// Change of the axial speed, m/s, and of the angular speed, rad/s.
    pub dv: f64,
    pub dw: f64,
    /// The axial and the angular speed stopped exactly (the set-valued stick).
    pub stuck_axial: bool,
    pub stuck_torsional: bool,
}

/// A contact's constants for [`slide`]: its radius and the speed changes `la`, `lt` (axial,
/// torsional) of the static limit over a step, with their inverses and kinetic parts.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    inv_radius: f64,
    la: f64,
    lt: f64,
    inv_la: f64,
    inv_lt: f64,
    /// `kinetic_ratio la`, `kinetic_ratio lt`.
    kla: f64,
    klt: f64,
    /// Whether the wall holds it at all (`la, lt > 0`).
    touching: bool,
}

impl Contact {
    pub fn new(radius: f64, la: f64, lt: f64, law: &Law) -> Self {
        let touching = la > 0.0 && lt > 0.0;
        Contact {
            inv_radius: 1.0 / radius,
            la,
            lt,
            inv_la: if touching { 1.0 / la } else { 0.0 },
            inv_lt: if touching { 1.0 / lt } else { 0.0 },
            kla: law.kinetic_ratio * la,
            klt: law.kinetic_ratio * lt,
            touching,
        }
    }
}

/// The coupled wall friction of a contact `c` moving at the axial speed `v` and the angular
/// speed `w` (after the step's transport and other sources): see the module.
#[inline]
pub fn slide(v: f64, w: f64, c: &Contact, law: &Law) -> Slide {
    let none = Slide { dv: 0.0, dw: 0.0, stuck_axial: false, stuck_torsional: false };
    if !c.touching {
        return none;
    }
    let vr = v * c.inv_radius;
    // (No overflow at drilling speeds: plain square roots, several times faster than `hypot`.)
    let s = (vr * vr + w * w).sqrt();
    // `-x` when the change `d` would reverse `x`, and whether it does.
    let clip = |d: f64, x: f64| if d.abs() >= x.abs() { (-x, true) } else { (d, false) };
    if let Some(inv) = law.inv_regularisation {
        if s == 0.0 {
            return none;
        }
        let f = law.kinetic_ratio * (s * inv).tanh() / s;
        let (dv, _) = clip(-f * c.la * vr, v);
        let (dw, _) = clip(-f * c.lt * w, w);
        return Slide { dv, dw, stuck_axial: false, stuck_torsional: false };
    }
    if s < law.slow_below {
        // The stop force over the static limit.
        let (qa, qt) = (v * c.inv_la, w * c.inv_lt);
        let q = (qa * qa + qt * qt).sqrt();
        if q <= 1.0 {
            return Slide { dv: -v, dw: -w, stuck_axial: true, stuck_torsional: true };
        }
        return Slide { dv: -v / q, dw: -w / q, stuck_axial: false, stuck_torsional: false };
    }
    // The direction cosines by division (without axial speed `w / s` is exactly +-1: the
    // torsional law's kinetic change, bit for bit).
    let (dv, stuck_axial) = clip(-c.kla * (vr / s), v);
    let (dw, stuck_torsional) = clip(-c.klt * (w / s), w);
    Slide { dv, dw, stuck_axial, stuck_torsional }
}

/// A segment of the overlay of the two grids (padded indices, weights `l / h`, the limits).
#[derive(Debug, Clone, Copy)]
struct Segment {
    torsional: usize,
    axial: usize,
    wt: f64,
    wa: f64,
    contact: Contact,
}

/// The per-cell sums of a step.
#[derive(Debug, Clone, Default)]
struct Cells {
    /// The speeds before the friction (padded).
    speed: Vec<f64>,
    change: Vec<f64>,
    /// Segments of the cell not stuck in the step.
    moving: Vec<u32>,
}

impl Cells {
    fn new(len: usize) -> Self {
        Cells { speed: vec![0.0; len], change: vec![0.0; len], moving: vec![0; len] }
    }

    fn add(&mut self, k: usize, w: f64, d: f64, stuck: bool) {
        self.change[k] += w * d;
        self.moving[k] += u32::from(!stuck);
    }
}

/// The coupled wall friction of a run: the overlay's segments and the law.
pub struct CoupledFriction {
    segments: Vec<Segment>,
    law: Law,
    torsional: Cells,
    axial: Cells,
    /// The static limit of the friction on the last half axial cell, N.
    end_hold: f64,
}

/// Two face positions closer than this fraction of a cell are the same face.
const SAME_FACE: f64 = 1e-9;

impl CoupledFriction {
    /// The overlay of the torsional `field` (of `grid`) and the axial field `axial`, with the
    /// torsional wall friction's static-limit changes `stop` (padded) and the axial sections'
    /// masses per length in `axial.sections`; None when the wall has no friction anywhere.
    pub fn new(cfg: &DrillConfig, grid: &Grid, torsion: &Field, stop: &[f64], axial: &Field) -> Option<Self> {
        let law = Law::new(cfg);
        let mut segments = Vec::new();
        let mut cell = 0;
        let mut end_hold = 0.0;
        for (s, (st, sa)) in torsion.sections.iter().zip(&axial.sections).enumerate() {
            let p = &grid.props[s];
            let length = grid.spacing[s] * st.cells as f64;
            let (ht, ha) = (length / st.cells as f64, length / sa.cells as f64);
            let (mut i, mut j, mut pos) = (0, 0, 0.0);
            while i < st.cells && j < sa.cells {
                let (et, ea) = ((i + 1) as f64 * ht, (j + 1) as f64 * ha);
                let last = i + 1 == st.cells && j + 1 == sa.cells;
                let end = if last { length } else { et.min(ea) };
                let kt = st.offset + 1 + i;
                let lt = stop[kt];
                // mu_s N per metre from the torsional limit mu_s N r per metre.
                let force = lt * p.inertia_per_length / (grid.dt * p.contact_radius);
                let la = grid.dt * force / sa.inertia_per_length;
                if end > pos {
                    let l = end - pos;
                    segments.push(Segment {
                        torsional: kt,
                        axial: sa.offset + 1 + j,
                        wt: l / ht,
                        wa: l / ha,
                        contact: Contact::new(p.contact_radius, la, lt, &law),
                    });
                }
                pos = end;
                end_hold = 0.5 * force * ha;
                let tol = SAME_FACE * ht.min(ha);
                if et <= end + tol {
                    i += 1;
                    cell += 1;
                }
                if ea <= end + tol {
                    j += 1;
                }
            }
        }
        debug_assert_eq!(cell, grid.cells());
        if segments.iter().all(|g| !g.contact.touching) {
            return None;
        }
        Some(CoupledFriction {
            segments,
            law,
            torsional: Cells::new(torsion.padded_len()),
            axial: Cells::new(axial.padded_len()),
            end_hold,
        })
    }

    /// The static limit of the wall friction on the half of the last axial cell below its
    /// centre (`mu_s N h / 2`), N: it holds the free end of a stuck string at rest
    /// ([`super::axial::Axial::end_hold`]).
    pub fn end_hold(&self) -> f64 {
        self.end_hold
    }

    /// The friction over a step on the fields' current speeds; returns its work on the
    /// torsional and on the axial field, J (negative).
    pub fn apply(&mut self, torsion: &mut Field, axial: &mut Field) -> (f64, f64) {
        let (ct, ca) = (&mut self.torsional, &mut self.axial);
        ct.change.fill(0.0);
        ct.moving.fill(0);
        ca.change.fill(0.0);
        ca.moving.fill(0);
        torsion.speeds(&mut ct.speed);
        axial.speeds(&mut ca.speed);
        for g in &self.segments {
            let f = slide(ca.speed[g.axial], ct.speed[g.torsional], &g.contact, &self.law);
            ct.add(g.torsional, g.wt, f.dw, f.stuck_torsional);
            ca.add(g.axial, g.wa, f.dv, f.stuck_axial);
        }
        (apply_cells(torsion, ct), apply_cells(axial, ca))
    }
}

/// A field's cells' changes applied (a cell whose segments all stuck set exactly to rest);
/// returns their work, J.
fn apply_cells(field: &mut Field, cells: &Cells) -> f64 {
    let mut work = 0.0;
    for s in 0..field.sections.len() {
        let sp = field.sections[s];
        let m = sp.inertia_per_length * sp.h;
        for k in sp.offset + 1..=sp.offset + sp.cells {
            let w = cells.speed[k];
            let d = if cells.moving[k] == 0 { -w } else { cells.change[k] };
            if d == 0.0 && cells.moving[k] != 0 {
                continue;
            }
            work += m * d * (w + 0.5 * d);
            field.change_speed(k, d, cells.moving[k] == 0);
        }
    }
    work
}

#[cfg(test)]
#[path = "coupled_friction_tests.rs"]
pub(super) mod tests;

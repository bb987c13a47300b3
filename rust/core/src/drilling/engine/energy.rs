//! The energy ledger of a run: the work of every boundary and source as it is done, the
//! stored energies at the start and the end, and the balance that closes to rounding (see
//! [`super`], "Energy").

use serde::Serialize;

/// The energy balance of a run, J (from the start to the end reached).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// `sum dt tau_m Omega'`.
    pub motor_work: f64,
    /// Total energy at the start (string, top drive, BHA).
    pub initial: f64,
    /// At the end: string kinetic and elastic, top-drive and BHA kinetic.
    pub kinetic: f64,
    pub elastic: f64,
    pub top_drive: f64,
    pub bha: f64,
    /// The wall friction's work on the string (both fields in a coupled run), J.
    pub friction_loss: f64,
    /// The part of `friction_loss` on the axial field (coupled runs with
    /// `friction.coupling = "axial_torsional"`; else 0), J.
    pub axial_friction_loss: f64,
    pub damping_loss: f64,
    pub bit_loss: f64,
    /// `upwind_loss + inertia_loss`.
    pub numerical_loss: f64,
    /// Dissipation of the first-order upwind transport: `linear`, `e C (1 - C) (d alpha^2 +
    /// d beta^2)` per cell and step (0 at Courant number 1); `consistent`, the energy the
    /// Godunov fluxes bring into a cell less its energy change in the transport.
    pub upwind_loss: f64,
    /// Dissipation of the implicit Euler steps of the top-drive and BHA inertias,
    /// `I (Omega' - Omega)^2 / 2` per step: first order in `dt` (the coupled wall friction's
    /// step with the gravity kick leaves only rounding here, [`super::coupled_friction`]).
    pub inertia_loss: f64,
    /// The coupled run's work of the hoist on the string (`dt F v` at the top, `F` the
    /// compression) and of the buoyed weight, J (0 without a hoist).
    pub hoist_work: f64,
    pub gravity_work: f64,
    /// At the end: the axial field's kinetic and elastic energies, J (0 without a hoist).
    pub axial_kinetic: f64,
    pub axial_elastic: f64,
    /// `(motor_work + hoist_work + gravity_work - (final - initial) - losses) / scale`, `scale` the largest of
    /// `|motor_work|`, the energies and the losses.
    pub balance_error: f64,
}

impl EnergyBalance {
    /// The balance of a run without the ledger (`numerics.energy_balance = false`): every
    /// term NaN.
    pub fn not_kept() -> Self {
        let n = f64::NAN;
        EnergyBalance {
            motor_work: n,
            initial: n,
            kinetic: n,
            elastic: n,
            top_drive: n,
            bha: n,
            friction_loss: n,
            axial_friction_loss: n,
            damping_loss: n,
            bit_loss: n,
            numerical_loss: n,
            upwind_loss: n,
            inertia_loss: n,
            hoist_work: n,
            gravity_work: n,
            axial_kinetic: n,
            axial_elastic: n,
            balance_error: n,
        }
    }
}

/// The warning of a run without the ledger.
pub const NOT_KEPT: &str =
    "numerics.energy_balance = false: the energy balance was not kept (every energy output is NaN)";

/// The work done so far, J: by the motor (in), and lost to each sink.
#[derive(Debug, Clone, Copy, Default)]
pub struct Ledger {
    pub motor: f64,
    /// Both fields'; `axial_friction` the axial field's part.
    pub friction: f64,
    pub axial_friction: f64,
    pub damping: f64,
    pub bit: f64,
    pub upwind: f64,
    pub inertia: f64,
    /// The hoist's and the buoyed weight's work on the axial field (coupled runs).
    pub hoist: f64,
    pub gravity: f64,
}

/// The energies stored in the system, J.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stored {
    /// The string's (the fields').
    pub kinetic: f64,
    pub elastic: f64,
    /// The lumped inertias at the ends.
    pub top_drive: f64,
    pub bha: f64,
    /// The axial field's (coupled runs).
    pub axial_kinetic: f64,
    pub axial_elastic: f64,
}

impl Stored {
    pub fn total(&self) -> f64 {
        self.kinetic + self.elastic + self.top_drive + self.bha + self.axial_kinetic + self.axial_elastic
    }
}

impl Ledger {
    /// The work of the linear transport's energy terms on a section with cell energy factor
    /// `e` and Courant number `c` ([`super::kernel::Sums`]).
    #[inline]
    pub fn transport(&mut self, e: f64, c: f64, sums: &super::kernel::Sums) {
        self.upwind += e * c * (1.0 - c) * sums.jumps;
        self.friction -= 4.0 * e * sums.friction;
        self.damping -= 4.0 * e * sums.damping;
    }

    /// The same for the `consistent` scheme, whose sums are in J.
    #[inline]
    pub fn godunov(&mut self, sums: &super::kernel::Sums) {
        self.upwind += sums.jumps;
        self.friction -= sums.friction;
        self.damping -= sums.damping;
    }

    /// The balance from the stored energy `initial` at the start to `end`, and whether it is
    /// finite (its residual and scale).
    pub fn balance(&self, initial: f64, end: Stored) -> (EnergyBalance, bool) {
        let l = self;
        let change = end.total() - initial;
        let numerical = l.upwind + l.inertia;
        let residual = l.motor + l.hoist + l.gravity - change - l.friction - l.damping - l.bit - numerical;
        let scale = [l.motor, initial, end.total(), l.friction, l.damping, l.bit, numerical, l.hoist, l.gravity]
            .iter()
            .fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
        let balance = EnergyBalance {
            motor_work: l.motor,
            initial,
            kinetic: end.kinetic,
            elastic: end.elastic,
            top_drive: end.top_drive,
            bha: end.bha,
            friction_loss: l.friction,
            axial_friction_loss: l.axial_friction,
            damping_loss: l.damping,
            bit_loss: l.bit,
            numerical_loss: numerical,
            upwind_loss: l.upwind,
            inertia_loss: l.inertia,
            hoist_work: l.hoist,
            gravity_work: l.gravity,
            axial_kinetic: end.axial_kinetic,
            axial_elastic: end.axial_elastic,
            balance_error: residual / scale,
        };
        (balance, residual.is_finite() && scale.is_finite())
    }
}

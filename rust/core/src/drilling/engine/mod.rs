//! The drilling engine: the string's dynamics as composable parts, each in one module.
//!
//! * [`field`]: a field on the string ([`field::Field`]): per section the Courant number (wave
//!   speed), impedance and inertia per length, the two Riemann invariants per cell, padded per
//!   section with ghosts; the junctions between sections; its energies; and what a field does in
//!   a step and in sampling, the trait [`field::StringField`]. The torsional field is
//!   `(omega, tau)` with `rho J` and `J sqrt(G rho)`; an axial field is the same type with
//!   `(v, N)`, `rho A` and `A sqrt(E rho)` (wave speed `sqrt(E / rho)`);
//! * [`kernel`]: the one transport kernel in Riemann invariants (first-order upwind, the exact
//!   shift at Courant number 1) with the sources, and the `consistent` Godunov update;
//! * [`kernel_published`]: the same transport with the sources at the speed before it
//!   (`numerics.source_speed = "before_transport"`, the scheme of torsionalWaveStep.m);
//! * [`sources`]: wall friction with its stick phase and viscous damping, per cell, one place
//!   each (the wall friction's law [`sources::WallLaw`]), and the sources of a step on both
//!   fields ([`sources::StepSource`]);
//! * [`torsion`]: the torsional field as a [`field::StringField`] ([`torsion::Torsion`]: the
//!   field, its wall friction and sources, its cells' update over a step);
//! * [`boundary`]: the ends, as what they do with the characteristic arriving at them
//!   ([`boundary::Arriving`]): the top drive ([`boundary::TopDriveEnd`]) carrying out a
//!   controller's command, the bit ([`boundary::BitEnd`]) with a law of the torsional field alone;
//! * [`bit_law`]: the bit law's interface, [`bit_law::BitRock`], one for the laws of the
//!   torsional field alone and those that meet the axial field too, and the laws registered;
//! * [`axial_field`]: a coupled run's axial field (`[hoist]` with `bit.law` `detournay` or `rgd`): the
//!   same [`field::Field`] and [`kernel`] with the axial sections' speeds and impedances, the
//!   buoyed weight as a source, the static tension as the initial state, the hoist at the top and
//!   the bit on bottom as the set-valued boundary of both fields (the run's
//!   [`bit_law::Law`] at the step's depth of cut) in place of [`boundary::BitEnd`];
//! * [`coupled_friction`]: a coupled run's wall friction against the sliding velocity of both
//!   fields (`friction.coupling = "axial_torsional"`, the default with a hoist), one stick phase;
//! * [`controller`]: what drives the top ([`controller::TopCommand`]: the controllers, the
//!   measured surface speed) and the setpoint;
//! * [`sampler`]: the output series and field snapshots;
//! * [`energy`]: the energy ledger and the balance;
//! * [`run`]: the [`run::Simulation`] and its step, the result [`run::DrillRun`];
//! * [`session`]: the one loop of every run, [`session::Session`] (interrupt, the configuration's
//!   changes, runaway guard, sampling, status; values changed between chunks, the result of
//!   what was stepped); the batch run is a session stepped to the duration.
//!
//! A step: the setpoint, the top drive against the characteristic arriving at the top, the bit
//! against the one arriving at the bottom, the junctions (each sets the ghost invariant of its
//! neighbouring cells), then the kernel over every section's cells, whose energy terms go to
//! the ledger, then the sources of the step on both fields of a coupled run.
//!
//! # The seams
//!
//! What the run composes, and where a new one plugs in (dispatched once per step, outside the
//! cell loops; the kernels are functions over slices, generic over the wall friction's law):
//!
//! * the bit law: the trait [`bit_law::BitRock`], one interface for the laws of the torsional
//!   field alone and those meeting the axial field too (what a law needs from the axial field
//!   it declares, [`bit_law::BitRock::AXIAL`]), the laws registered in [`bit_law::Law`];
//! * the top boundary: the trait [`controller::TopCommand`], what drives the top (a controller,
//!   or the measured surface speed [`controller::SpeedSeries`]), giving a
//!   [`controller::Command`] that [`boundary::TopDriveEnd`] carries out; the implementations
//!   registered in [`controller::Top`], which the run holds (a new controller is one
//!   implementation, its variant of [`controller::Top`] with its line in
//!   [`controller::Top::new`], and its `top_drive.controller.type` name and keys);
//! * the hoist: the trait [`crate::drilling::axial::hoist_mode::HoistRule`], one implementation
//!   per `hoist.mode` (its target, where its setpoint starts, its command per step, what it
//!   holds in steady drilling), registered in [`crate::drilling::axial::hoist_mode::rule`];
//!   [`crate::drilling::axial::hoist::HoistState`] holds what the modes share and gives the
//!   axial field's top its [`crate::drilling::axial::hoist::HoistCommand`]
//!   ([`axial_field::Axial::top`]);
//! * the wall friction per cell: the trait [`sources::WallLaw`] (the friction's speed change
//!   and whether the cell sticks; the damping is common), one zero-sized implementation per
//!   `friction.model` ([`sources::SetValued`], [`sources::Regularised`]), matched to its name
//!   once in [`sources::Sources::with_law`]; the kernels ([`kernel`], [`kernel_published`]) are
//!   generic over it and compiled once per law (no dynamic dispatch in the cell loops);
//! * the sources of a step: the trait [`sources::StepSource`], applied to both fields after
//!   both transports and booking its own work, implemented by [`coupled_friction`]'s
//!   [`coupled_friction::CoupledFriction`] (the run's `coupled_friction`, called through the
//!   trait); the axial field's buoyed weight is its own source, in its cells' pass;
//! * the fields: the trait [`field::StringField`] (the characteristic arriving at each end, the
//!   ends and junctions set, the cells advanced over a step with their sources and booking, the
//!   stored energies, the snapshot's cells, the channels declared), implemented by the
//!   torsional field [`torsion::Torsion`] and the axial field [`axial_field::Axial`], both on
//!   the one type [`field::Field`]; the run's step and stored energies, the sampler's
//!   snapshots and held channels go through it (the channels' values after a step come from
//!   the ends: [`run::Simulation`]'s `sample`, [`axial_field::Axial::sample`]);
//! * the output series: named channels ([`sampler::Channel`]) each field declares where it is
//!   ([`sampler::TORSIONAL`], [`axial_field::CHANNELS`]), returned by
//!   [`field::StringField::channels`].
//!
//! The files a new one touches:
//!
//! * a bit law: one file in `bit_law/` implementing [`bit_law::BitRock`], its registration in
//!   `bit_law/mod.rs`, its name and keys in `config/bit.rs`;
//! * a hoist mode: one struct implementing [`crate::drilling::axial::hoist_mode::HoistRule`] and
//!   its line in [`crate::drilling::axial::hoist_mode::rule`] (`axial/hoist_mode.rs`), its name
//!   and keys in `config/hoist.rs`;
//! * a controller: one struct implementing [`controller::TopCommand`] and its registration in
//!   [`controller::Top`] (`controller.rs`), its name and keys in `config/top_drive.rs`;
//! * a wall friction law (e.g. a Stribeck curve): one zero-sized type implementing
//!   [`sources::WallLaw`] in `sources.rs` and its line in [`sources::Sources::with_law`], its
//!   `friction.model` name and keys in `config/friction.rs` (a constant of its own a field of
//!   [`sources::Consts`]), tests against [`sources::SetValued`] or its closed form;
//! * another source per cell: `sources.rs` (a field of [`sources::Sources`]), its limit per cell
//!   in `drilling/grid.rs`, its work in `energy.rs`; one on the axial field alone in
//!   `axial_field.rs` (its cells' pass); one on both fields: a type implementing
//!   [`sources::StepSource`] (as `coupled_friction.rs`), held by the run and applied in
//!   `Simulation::step` (`run.rs`);
//! * a field: a type implementing [`field::StringField`] on a [`field::Field`], built beside its
//!   ends and sources as `axial_field.rs` or `torsion.rs`, stepped and sampled from `run.rs`
//!   (`Simulation::step`, `Simulation::stored`, `Simulation::sample`) and `sampler.rs`, its
//!   energies in `energy.rs` ([`energy::Stored`]), its channels declared beside it;
//! * a metric: `metrics/stickslip.rs` and its entry in the crate's `outputs.rs` (a coupled one a
//!   field of [`run::CoupledMetrics`]).

//! # The scheme
//!
//! With `tau` the torque carried down the string (`tau = -G J theta_z`) and `Z = J sqrt(G rho)`
//! the impedance, the invariants `alpha = omega + tau / Z` (travelling down at `c`) and
//! `beta = omega - tau / Z` (travelling up) obey
//! `alpha_t + c alpha_z = beta_t - c beta_z = -(f / (rho J) + d omega)` with `f` the friction
//! torque per metre and `d` the damping rate (Aarsnes & Shor 2018, eqs. 5-8 and
//! torsionalWaveStep.m). Each step (`dt`, common to all sections):
//!
//! 1. boundaries from the state at `t_n`: the top speed `Omega'` (top-drive inertia, implicit
//!    in the string torque `Z (Omega' - beta_1)`, or imposed by an ideal controller), the
//!    bit speed (BHA inertia, implicit likewise; on bottom the Navarro-Lopez torque
//!    `W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)` at the speed of the step start, with a
//!    stick phase: below `bit.stick_speed`, or when the slip torque would reverse the bit, the
//!    torque that stops it in this step if within `W r mu_s`, else `W r mu_s`), the junctions
//!    (continuity of speed and torque: `omega = (Z_a alpha_a + Z_b beta_b) / (Z_a + Z_b)`);
//!    each gives the ghost invariant entering its neighbouring cell (`alpha = 2 omega - beta`);
//! 2. first-order upwind transport, `alpha_j <- alpha_j - C (alpha_j - alpha_{j-1})` (exact
//!    shift at Courant number `C = 1`);
//! 3. the sources, added to both invariants, evaluated at the transported speed
//!    `omega*_j = (alpha*_j + beta*_j) / 2` (the material now in the cell): damping
//!    `-dt d omega*_j`, and friction: when `|omega*_j| < stick_speed` the torque that stops the
//!    cell in this step, clipped to the static limit (a stopped cell gets `omega = 0` exactly,
//!    its torque kept), else the kinetic limit against `omega*_j` (the set-valued resolution
//!    of torsionalWaveStep.m, which evaluates the threshold and direction at the speed before
//!    transport; with the speed after it, friction cannot pump energy into the grid-scale
//!    mode that the exact shift at Courant 1 leaves undamped), or `tanh(omega*_j / v_r)` times
//!    the kinetic limit (regularised). `numerics.source_speed = "before_transport"` takes the
//!    threshold, the kinetic direction and the damping at the speed before transport instead,
//!    as torsionalWaveStep.m ([`kernel_published`]).
//!
//! A stopped cell's new torque comes from its neighbours' invariants: at `C = 1` it is
//! `(tau_{j-1} + tau_{j+1}) / 2 + Z (omega_{j-1} - omega_{j+1}) / 2`, so inside a stuck region
//! the torque relaxes towards a linear profile (over `n` stuck cells in ~`n^2` steps) instead of
//! staying frozen as in the continuum; the scheme of torsionalWaveStep.m does the same.
//!
//! # The `consistent` nonlinearity
//!
//! With `nonlinearity = "consistent"` the torque is the finite-strain law of
//! [`crate::model::Model::Consistent`], `tau(eps) = k2 eps + k5 eps^3` (`eps = -theta_z` the
//! twist per length, `k2 = G J`, `k5 = M J4 / 2`), and the string is the p-system
//! `rho J omega_t = -tau(eps)_z - f - rho J d omega`, `eps_t = -omega_z`, whose local wave speed is
//! the tangent speed `sqrt((k2 + 3 k5 eps^2) / (rho J))` (hardening). The cells hold
//! `(omega, eps)` and the scheme is the first-order Godunov finite-volume scheme with the
//! acoustic (two-wave, Suliciu relaxation) Riemann solver: at a face between states `l` and
//! `r` the outgoing characteristics `omega_l + tau_l / Z_l` and `omega_r - tau_r / Z_r` meet,
//! `omega* = (Z_l (omega_l + tau_l / Z_l) + Z_r (omega_r - tau_r / Z_r)) / (Z_l + Z_r)`,
//! `tau* = Z_l (omega_l + tau_l / Z_l - omega*)`, with `Z_l = Z_r` the larger tangent impedance
//! `sqrt(rho J (k2 + 3 k5 eps^2))` of the two cells inside a section, each side's own at a
//! junction (continuity of speed and torque), and the cell's at the top drive and the bit,
//! which are solved exactly as above with `beta_1 = omega_1 - tau_1 / Z_1` and
//! `alpha_n = omega_n + tau_n / Z_n`. Then
//! `omega_j += dt (tau*_{j-1/2} - tau*_{j+1/2}) / (rho J h)`,
//! `eps_j += dt (omega*_{j-1/2} - omega*_{j+1/2}) / h`, and the same sources (damping, friction
//! with its stick phase: a stuck cell keeps its twist) at the transported speed. With `k5 = 0`
//! the face values are those of the invariants and the update is the upwind scheme above
//! (to rounding). The time step is made for the tangent speed at `numerics.max_shear_strain`
//! (Courant number `<= 1` at that strain; every section's wave speed is raised by the largest
//! hardening factor of the sections, so that sections of equal wave speeds keep whole numbers
//! of steps per travel time, [`crate::drilling::grid::Grid::speed`]); the run reports the largest tangent Courant number
//! met ([`run::DrillStats::courant_peak`]). The elastic energy is `sum h (k2 eps^2 / 2 + k5 eps^4 / 4)`
//! and the transport's dissipation (`upwind_loss`) is measured per cell as the energy the face
//! fluxes bring in (`dt tau* omega*`) less the cell's energy change, so the balance closes to
//! rounding and the scheme's first-order dissipation is reported (positive; it vanishes at
//! first order with `h` on smooth solutions).
//!
//! # Controllers
//!
//! * `pi`: `tau_m = kp e + ki int e`, `e = setpoint - Omega`, sampled in a zero-order hold at
//!   `control_interval`, as MAIN.m of Aarsnes & Shor (their `38e3`, `100e3`);
//! * `soft_torque`: the same PI with `kp = z_factor Z_top` and `ki = (2 pi f)^2 I_TD`, so that
//!   at the tuning frequency `f` the top drive's inertia and the integral cancel and it presents
//!   the damping `kp` to the string (Kyllingstad & Nessjøen, SPE/IADC 119660, 2009); the gains
//!   as in Open-Source-Drilling-Community/Simulator4nDOF, `Simulator/TopdriveController.cs`
//!   (commit b14d6c2, controller type 2, without its inertia compensation), `f` by default the
//!   string's first natural frequency;
//! * `z_torque`: impedance matching (ZTorque, Dwars, SPE/IADC 173037, 2015; Simulator4nDOF
//!   controller type 3, whose speed setpoint is lowered by the high-passed string torque over
//!   `Z`): here the ideal form, the top speed `Omega = w_ref - (tau_top - tau_slow) / (z Z_top)`
//!   every step (`tau_slow` the string torque low-passed with `torque_highpass_time`), which
//!   absorbs an incident torque wave completely at `z_factor = 1`;
//! * `speed`: the top speed is the setpoint.
//!
//! `speed` and `z_torque` ask for a top speed, which the motor's speed loop follows as a
//! first-order lag of time constant `1 / (2 pi top_drive.motor_bandwidth)` (exact over the
//! step), and infer the motor torque (`I_TD dOmega/dt + tau_top`, bounded as the grid is
//! refined); with `top_drive.torque_limit` exceeded they fall back to the clipped torque. The
//! `pi` and `soft_torque` gains are checked against the sampled loop's stability bound
//! `kp < 2 I_TD / max(dt, control_interval) + Z` before a run. The setpoint approaches its target (`rpm`, then `steps`) as a first-order lag of time
//! constant `ramp_time`, exactly over each step.
//!
//! # Energy
//!
//! With `e = rho J h / 4` per cell the discrete energy is `sum e (alpha^2 + beta^2)` (kinetic
//! `e (alpha + beta)^2 / 2`, elastic `e (alpha - beta)^2 / 2`) plus the top-drive and BHA
//! kinetic energies. Every step satisfies exactly (up to rounding)
//! `dt tau_m Omega' = dE + dt T_bit omega_bit' + friction + damping + numerical`, where the
//! friction and damping terms are the work of their sources (`4 e delta (omega* + delta / 2)`
//! per cell), and `numerical` the upwind dissipation `e C (1 - C) (d alpha^2 + d beta^2)` (0 at
//! `C = 1`) plus the implicit-Euler dissipation `I (Omega' - Omega)^2 / 2` of the top drive and
//! BHA (in a step where the bit sticks, the BHA's term counts as bit loss: the bit torque stops
//! it). The motor work is `sum dt tau_m Omega'`. A coupled run ([`axial_field`]) adds the axial field's
//! energies (`e (alpha^2 + beta^2)` with `e = rho A h / 4`), the hoist's work `dt F v` at the top
//! and the buoyed weight's work as inputs, and the bit's `dt (W v' + T w')` as its loss; the
//! coupled wall friction's work on each cell of both fields, `m h delta (w + delta / 2)`, goes
//! to `friction_loss` (its axial part also to `axial_friction_loss`), a BHA mass's kinetic
//! energy to `bha`, its weight's work to `gravity_work`.

pub mod axial_field;
pub mod bit_law;
pub mod boundary;
pub mod controller;
pub mod coupled_friction;
pub mod energy;
pub mod field;
pub mod kernel;
pub mod kernel_published;
pub mod run;
pub mod sampler;
pub mod session;
pub mod sources;
#[cfg(test)]
mod top_tests;
pub mod torsion;

pub use energy::EnergyBalance;
pub use run::{CoupledMetrics, DrillRun, DrillStats, Simulation, RUNAWAY_FACTOR};
pub use session::{duration_steps, Session, SessionState};

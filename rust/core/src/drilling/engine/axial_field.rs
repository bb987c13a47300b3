//! The coupled run's axial field and its ends: the string's axial waves `(v, F)` (speed down
//! positive, `F` the compression carried down) on the same [`Field`] type and [`transport`]
//! kernel as the torsion, the hoist at the top ([`HoistState`], [`crate::drilling::axial::hoist::HoistCommand::incoming`]) and the
//! bit on bottom as the set-valued boundary of both fields ([`solve_bit`]) with the Detournay law.
//!
//! * Cells: each section gets `floor(L / (c_a dt)) >= 1` cells of the torsional step `dt`
//!   (`c_a = sqrt(E / rho)`, Courant number `c_a dt / h <= 1`; below 1 the upwind transport
//!   dissipates, booked as `upwind_loss`); a section shorter than `c_a dt` is refused.
//! * Sources: the viscous damping `damping_rate` (the torsion's, on the axial speed) through the
//!   kernel, the buoyed weight
//!   `(1 - rho_mud / rho) g cos(inc)` per cell ([`AxialSection::buoyed_gravity`], `inc` at the
//!   cell centre), added to both invariants after the transport; its work
//!   `m h g dt (v* + g dt / 2)` is booked as `gravity_work`; then the wall friction of
//!   [`super::coupled_friction`] on both fields (`friction.coupling = "axial_torsional"`; with
//!   `torsion_only` the axial field has none).
//! * Initial state: at rest under the static tension of the hanging string with no weight on
//!   bit ([`static_tension`] at the cell centres, along the configuration's one trajectory,
//!   [`crate::drilling::well::trajectory`]), the bit just touching flat rock; with the coupled
//!   wall friction every cell at half its gravity kick ([`Axial::start_at_rest`]: the speed at
//!   the middle of the kick, the string's, is 0).
//! * Top: the hoist's command for the step gives the ghost `alpha_0`; the top speed
//!   `(alpha_0 + beta_1) / 2` and the compression `Z (v - beta_1)` (the hook load is its
//!   negative); the hoist's work `dt F v` is booked as `hoist_work`.
//! * Bit: the depth of cut per revolution `d` of the step, from the state at its start: `detournay`
//!   `2 pi v' / omega` with the step's axial speed `v'` (implicit) and the angular speed at the
//!   step start ([`rate_depth`]), `rgd` `n` times the
//!   cut surface's depth of cut of a blade ([`CutSurface`], the exact delay, the deepest-surface
//!   rule; or with `bit.detournay.cut_surface = "upwind"` the last cell of their upwind chain,
//!   [`UpwindCutSurface`], advanced after the step with the bit's new speeds); then [`solve_bit`]
//!   with the axial end of the string (with `bit.bha_mass` a lumped
//!   mass, [`Port::lumped`], pushed by its buoyed weight, which the initial static tension
//!   carries) and the torsional end with the BHA inertia `bit.bha_inertia`; the bit's work
//!   `dt (W v' + T w')` is booked as `bit_loss`, the BHA's implicit-Euler terms as in the
//!   torsional bit, its weight's work as `gravity_work` and its axial kinetic energy in `bha`.

use std::f64::consts::TAU;

use super::bit_law::{AxialEnd, BitEnds, Law};
use super::boundary::{Arriving, EndLine};
use super::energy::Ledger;
use super::field::{Field, FieldSection, StringField};
use super::kernel::{transport_kicked, Kick, Wall};
use super::sampler::{Channel, Point};
use super::sources::Sources;
use crate::drilling::axial::bit_boundary::{BitContact, BitPhase, Port};
use crate::drilling::axial::cut_surface::{CutSurface, SurfaceRule, UpwindCutSurface};
use crate::drilling::axial::hoist::{HoistMeasurement, HoistState};
use crate::drilling::axial::hoist_mode::{rule, HoistReading, HoistReference};
use crate::drilling::axial::section::{static_tension, AxialSection};
use crate::drilling::config::Hoist;
use crate::drilling::config::{BitRockLaw, CutSurfaceScheme, DrillConfig, FrictionModel};
use crate::drilling::grid::Grid;
use crate::drilling::well;
use crate::error::{Error, Num, Result};

/// The bit's axial speed, m/s (down positive).
pub const BIT_AXIAL_SPEED: Channel = Channel { column: 5, held: false };
/// The rate of penetration, m/h.
pub const ROP: Channel = Channel { column: 6, held: false };
/// The weight on bit of the step, N.
pub const WEIGHT_ON_BIT: Channel = Channel { column: 7, held: true };
/// The hook load, N.
pub const HOOK_LOAD: Channel = Channel { column: 8, held: false };
/// The bit's depth below its start, m.
pub const BIT_DEPTH: Channel = Channel { column: 9, held: false };
/// The depth of cut per revolution the bit law used in the step, m (0 when infinite).
pub const DEPTH_OF_CUT: Channel = Channel { column: 10, held: true };
/// A coupled run's channels of the series ([`super::sampler`]; 0 without a hoist).
/// The block's position from its start, m, down positive (the top of the string's).
pub const BLOCK_POSITION: Channel = Channel { column: 11, held: false };
pub const CHANNELS: [Channel; 7] =
    [BIT_AXIAL_SPEED, ROP, WEIGHT_ON_BIT, HOOK_LOAD, BIT_DEPTH, DEPTH_OF_CUT, BLOCK_POSITION];

/// How the depth of cut of a step is found.
#[derive(Clone)]
enum DepthOfCut {
    /// `2 pi v / omega` of the bit's speeds at the step start.
    Rate,
    /// The regenerative delay.
    Regenerative(CutSurface),
    /// Aarsnes & van de Wouw's upwind cut surface.
    Upwind(UpwindCutSurface),
}

/// The values of the bit and the hoist after a step (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialState {
    pub contact: BitContact,
    /// Depth of cut per revolution used in the step, m (`+-inf` for the rate form without rotation).
    pub depth: f64,
    /// Hook load (the tension at the top), N.
    pub hook_load: f64,
    /// The bit's axial position from its start, m, down positive.
    pub position: f64,
    /// The top of the string's (the block's) axial position from its start, m, down positive.
    pub block: f64,
    /// The deepest position reached (the hole's depth below the start), m.
    pub hole: f64,
    /// The rate the hole deepened over the step, m/s.
    pub rop: f64,
}

/// The axial field, its sources and ends.
#[derive(Clone)]
pub struct Axial {
    pub field: Field,
    sources: Sources,
    /// `g dt` per padded index (0 at ghosts).
    gravity: Vec<f64>,
    hoist: HoistState,
    /// The bit law ([`super::bit_law`], one that needs the axial field) and its blades (the
    /// depth of cut of one blade pass, `bit.detournay.blades`).
    law: Law,
    blades: u32,
    rule: DepthOfCut,
    angle: f64,
    /// The rate form's depth of cut in the last step that began with the bit turning (0 at the
    /// start: flat rock just touched).
    turning_depth: f64,
    pub state: AxialState,
    /// Courant numbers of the sections.
    pub courant: Vec<f64>,
    /// Measured depths of the cell centres, m.
    pub z: Vec<f64>,
    /// With the coupled wall friction, the static limit of the friction on the half of the last
    /// cell below its centre, N (else 0): a bit off the rock below a stuck last cell (speed
    /// exactly 0) is at rest (its position kept, its speed reported 0) while the load the free
    /// end's speed stands for, `Z alpha_n`, is within it. The end's ghost keeps the free end's
    /// speed `alpha_n`: the creep of the torsional bit below a stuck cell
    /// ([`super::run`], `bit_speed`), a speed of the order of the stuck cell's load over the
    /// impedance, proportional to the cell size (inside a stuck region the load relaxes
    /// towards a linear profile, zero at the free end); its position would integrate it.
    pub end_hold: f64,
    /// The lumped BHA mass at the bit, kg (`bit.bha_mass`, 0: none), and its buoyed weight along
    /// the hole at the bit, N.
    bha_mass: f64,
    bha_weight: f64,
    /// The travelling block's weight, N (`torque_drag.block_weight`): in the hook load the
    /// weight indicator reads and `hook_load` mode's setpoint.
    block_weight: f64,
}

impl Axial {
    /// The axial field of a coupled run (`cfg.hoist` given) on the torsional grid's step.
    pub fn new(cfg: &DrillConfig, grid: &Grid, hoist: &crate::drilling::config::Hoist) -> Result<Self> {
        let dt = grid.dt;
        let (mud, g) = (cfg.well.mud_density, cfg.well.gravity);
        // The one trajectory of the configuration's well (stations, survey file or plan), as
        // the torsional grid, the wall contact and torque and drag read it.
        let traj = well::trajectory(cfg)?;
        let inclination = |md: f64| traj.at(md).inc;
        let parts: Vec<AxialSection> = cfg.sections.iter().map(AxialSection::from_section).collect();
        let mut sections = Vec::with_capacity(parts.len());
        let mut gravity = Vec::new();
        let mut centres = Vec::new();
        let (mut offset, mut top) = (0, 0.0);
        let mut courant = Vec::with_capacity(parts.len());
        for (i, p) in parts.iter().enumerate() {
            let c = p.wave_speed();
            let cells = (p.length / (c * dt) * (1.0 + 1e-12)).floor();
            if cells < 1.0 {
                return Err(Error::invalid(
                    format!("sections[{i}].length"),
                    Num(p.length),
                    format!(
                        "at least one axial cell, c_a dt = {} m at this time step (more numerics.cells)",
                        Num(c * dt)
                    ),
                ));
            }
            let n = cells as usize;
            let h = p.length / cells;
            courant.push((c * dt / h).min(1.0));
            sections.push(FieldSection::new(offset, n, courant[i], h, p.mass_per_length(), p.impedance()));
            gravity.push(0.0);
            for j in 0..n {
                let z = top + (j as f64 + 0.5) * h;
                centres.push(z);
                gravity.push(dt * p.buoyed_gravity(mud, g, inclination(z)));
            }
            gravity.push(0.0);
            offset += n + 2;
            top += p.length;
        }
        let len = offset;
        let mut field = Field {
            sections,
            alpha: vec![0.0; len],
            beta: vec![0.0; len],
            alpha_next: vec![0.0; len],
            beta_next: vec![0.0; len],
            nl: None,
        };
        let bha_mass = cfg.bit.bha_mass;
        let bha_weight = crate::drilling::limits::bha_weight(cfg);
        // The BHA hangs from the string: a negative weight on bit.
        let tension = static_tension(&parts, mud, g, &inclination, -bha_weight, &centres);
        let mut k = 0;
        for s in 0..field.sections.len() {
            for j in 1..=field.sections[s].cells {
                field.set_cell(s, j, 0.0, -tension[k]);
                k += 1;
            }
        }
        let params = hoist.clone();
        let hanging = crate::drilling::limits::hanging_hook_load(cfg);
        // The hook load of `hook_load` mode as the weight indicator reads it: the string's
        // tension at the top and the travelling block's weight (`torque_drag.block_weight`).
        let block_weight = cfg.torque_drag.block_weight;
        let reference = HoistReference { hanging, block_weight };
        let initial = rule(params.mode).at_rest(reference);
        let law = Law::new(cfg);
        let blades = cfg.bit.detournay.blades;
        let rule = match (cfg.bit.law, cfg.bit.detournay.cut_surface) {
            (BitRockLaw::Rgd, CutSurfaceScheme::ExactDelay) => {
                DepthOfCut::Regenerative(CutSurface::steady(blades, SurfaceRule::Deepest, 0.0, 0.0, 0.0))
            }
            (BitRockLaw::Rgd, CutSurfaceScheme::Upwind) => {
                DepthOfCut::Upwind(UpwindCutSurface::new(blades, cfg.bit.detournay.cut_surface_cells as usize, 0.0))
            }
            _ => DepthOfCut::Rate,
        };
        let src = Sources::new(cfg, dt);
        Ok(Axial {
            sources: Sources { stick_speed: 0.0, kinetic_ratio: 0.0, model: FrictionModel::SetValued, ..src },
            gravity,
            hoist: HoistState::new(params, initial).referred_to(reference),
            law,
            blades,
            rule,
            angle: 0.0,
            turning_depth: 0.0,
            state: AxialState {
                contact: BitContact {
                    axial_speed: 0.0,
                    angular_speed: 0.0,
                    weight_on_bit: 0.0,
                    torque_on_bit: 0.0,
                    contact_weight: 0.0,
                    contact_torque: 0.0,
                    phase: BitPhase::LiftOff,
                },
                depth: 0.0,
                hook_load: hanging + block_weight,
                position: 0.0,
                block: 0.0,
                hole: 0.0,
                rop: 0.0,
            },
            courant,
            field,
            z: centres,
            end_hold: 0.0,
            bha_mass,
            bha_weight,
            block_weight,
        })
    }

    /// Sets the hoist's table to `params` during a run (its state kept). A new mode starts
    /// where the hoist is: its setpoint the present block velocity, hook load, weight on bit
    /// (as the weight indicator reads it) or the autodriller's measurement, the autodriller's
    /// integral the one that keeps the block velocity.
    pub fn set_hoist(&mut self, params: Hoist) {
        let h = &mut self.hoist;
        if params.mode != h.params.mode {
            let sp = &self.field.sections[0];
            let block = self.field.cell(0, 1).0 - 0.5 * self.gravity[sp.offset + 1];
            let now = HoistReading {
                block,
                hook_load: self.state.hook_load,
                weight_on_bit: self.state.contact.weight_on_bit,
                rop: self.state.rop,
            };
            let mode = rule(params.mode);
            h.setpoint = mode.current(&params, now, h.reference);
            h.integral = mode.integral_on_change(&params, h.setpoint, block);
        }
        h.params = params;
    }

    /// Half the buoyed weight's speed change over a step at padded index `k`, `g cos(inc) dt / 2`,
    /// m/s (0 at ghosts): the state of a cell at rest (the speed at the middle of the kick is 0).
    pub fn half_kick(&self, k: usize) -> f64 {
        0.5 * self.gravity[k]
    }

    /// Whether the cell at padded index `k` is at rest in the coupled wall friction's sense:
    /// its speed half its gravity kick (set so by a stick: `(F / Z + s, s - F / Z)`, whose
    /// mean is `s` to the rounding of the invariants).
    fn at_rest(&self, k: usize) -> bool {
        let (a, b) = (self.field.alpha[k], self.field.beta[k]);
        (0.5 * (a + b) - self.half_kick(k)).abs() <= 2.0 * f64::EPSILON * a.abs().max(b.abs())
    }

    /// Sets every cell to rest in the coupled wall friction's sense (speed half its gravity
    /// kick, so that the speed at the middle of the first step's kick is 0), the loads kept: the
    /// initial state of a run with the coupled wall friction.
    pub fn start_at_rest(&mut self) {
        for sp in &self.field.sections {
            for k in sp.offset + 1..=sp.offset + sp.cells {
                let s = 0.5 * self.gravity[k];
                self.field.alpha[k] += s;
                self.field.beta[k] += s;
            }
        }
    }

    /// [`Axial::half_kick`] of every padded index.
    pub fn half_kicks(&self) -> Vec<f64> {
        self.gravity.iter().map(|g| 0.5 * g).collect()
    }

    /// The lumped BHA's axial kinetic energy, J (0 without `bit.bha_mass`).
    pub fn bha_kinetic(&self) -> f64 {
        let v = self.state.contact.axial_speed;
        0.5 * self.bha_mass * v * v
    }

    /// The hoist's end for a step of `dt`: sets the top ghost, books the hoist's work.
    pub fn top(&mut self, dt: f64, ledger: &mut Ledger) {
        let arriving = self.field.arriving_top();
        let measured = HoistMeasurement { weight_on_bit: self.state.contact.weight_on_bit, rop: self.state.rop };
        let command = self.hoist.step(dt, measured);
        let alpha0 = command.incoming(arriving.value, arriving.impedance);
        let v = 0.5 * (alpha0 + arriving.value);
        let force = arriving.impedance * (v - arriving.value);
        ledger.hoist += dt * force * v;
        self.state.hook_load = self.block_weight - force;
        self.state.block += v * dt;
        self.field.set_top(arriving, v, force);
    }

    /// The bit for a step of `dt` against the torsional field's arriving characteristic
    /// `torsion`, the BHA inertia `inertia` turning at `omega` at the step start: sets the axial
    /// bottom ghost, books the bit's work; returns the new bit speed and the torque on bit (the
    /// torsional field's bottom is set by the caller).
    pub fn bit(&mut self, torsion: Arriving, inertia: f64, omega: f64, dt: f64, ledger: &mut Ledger) -> (f64, f64) {
        let arriving = self.field.arriving_bottom();
        let (m, v0) = (self.bha_mass, self.state.contact.axial_speed);
        let axial = if m > 0.0 {
            Port::lumped(arriving.value, arriving.impedance, m, v0, dt, self.bha_weight)
        } else {
            Port::string(arriving.value, arriving.impedance)
        };
        let turning = EndLine::new(inertia, omega, dt, torsion);
        let depth = match &self.rule {
            DepthOfCut::Rate => rate_depth(&self.law, axial, turning, omega, self.turning_depth),
            DepthOfCut::Regenerative(s) => f64::from(self.blades) * s.depth_per_blade(self.angle, self.state.position),
            DepthOfCut::Upwind(s) => f64::from(self.blades) * s.depth_per_blade(),
        };
        let mut c =
            self.law.resolve(&BitEnds { torsion: turning, omega, axial: Some(AxialEnd { port: axial, depth }) });
        ledger.bit += dt * c.power();
        let w1 = c.angular_speed;
        let stop = 0.5 * inertia * (w1 - omega) * (w1 - omega);
        if w1 == 0.0 && c.torque_on_bit != 0.0 {
            ledger.bit += stop;
        } else {
            ledger.inertia += stop;
        }
        if m > 0.0 {
            // The BHA's weight's work and its implicit-Euler term (the rock's when it stops it).
            let v1 = c.axial_speed;
            ledger.gravity += dt * self.bha_weight * v1;
            let stop = 0.5 * m * (v1 - v0) * (v1 - v0);
            if v1 == 0.0 && c.weight_on_bit != 0.0 {
                ledger.bit += stop;
            } else {
                ledger.inertia += stop;
            }
        }
        self.field.set_bottom(arriving, c.axial_speed);
        let last = self.field.last();
        if self.end_hold > 0.0
            && m == 0.0
            && c.phase == BitPhase::LiftOff
            && self.at_rest(last.offset + last.cells)
            && (arriving.impedance * arriving.value).abs() <= self.end_hold
        {
            c.axial_speed = 0.0;
        }
        self.angle += w1 * dt;
        let s = &mut self.state;
        s.position += c.axial_speed * dt;
        match &mut self.rule {
            DepthOfCut::Regenerative(surface) => surface.record(self.angle, s.position),
            DepthOfCut::Upwind(surface) => surface.advance(dt, w1, c.axial_speed),
            DepthOfCut::Rate => {}
        }
        let hole = s.hole.max(s.position);
        s.rop = (hole - s.hole) / dt;
        s.hole = hole;
        s.contact = c;
        s.depth = depth;
        if omega > 0.0 {
            self.turning_depth = depth;
        }
        (w1, c.torque_on_bit)
    }

    /// Sets the axial channels of `point` ([`CHANNELS`]) after a step.
    pub fn sample(&self, point: &mut Point) {
        let s = &self.state;
        point[BIT_AXIAL_SPEED] = s.contact.axial_speed;
        point[ROP] = s.rop * 3600.0;
        point[WEIGHT_ON_BIT] = s.contact.weight_on_bit;
        point[HOOK_LOAD] = s.hook_load;
        point[BIT_DEPTH] = s.position;
        point[BLOCK_POSITION] = s.block;
        point[DEPTH_OF_CUT] = if s.depth.is_finite() { s.depth } else { 0.0 };
    }
}

impl StringField for Axial {
    #[inline]
    fn channels() -> &'static [Channel] {
        &CHANNELS
    }

    #[inline]
    fn field(&self) -> &Field {
        &self.field
    }

    #[inline]
    fn field_mut(&mut self) -> &mut Field {
        &mut self.field
    }

    /// The cells over a step (the grid's `dt`, in the buoyed weight's kicks): the transport
    /// with damping, then the buoyed weight, in one pass ([`transport_kicked`]); the work
    /// booked in `ledger` when `booked` (`numerics.energy_balance`).
    fn advance(&mut self, _dt: f64, ledger: &mut Ledger, booked: bool) {
        let Field { sections, alpha, beta, alpha_next, beta_next, .. } = &mut self.field;
        for sp in sections.iter() {
            let r = sp.padded();
            let sums = transport_kicked(
                &alpha[r.clone()],
                &beta[r.clone()],
                Wall::OffZeros,
                &mut alpha_next[r.clone()],
                &mut beta_next[r.clone()],
                sp.courant,
                &self.sources,
                Kick { dv: &self.gravity[r.clone()], booked },
            );
            if booked {
                ledger.transport(sp.e, sp.courant, &sums);
                ledger.gravity += 4.0 * sp.e * sums.kick;
            }
        }
        self.field.swap();
    }

    /// Calls `f(speed, force)` for every cell from the top down: the speed at the middle of the
    /// step's gravity kick (the state less half the cell's `g dt`: in steady drilling every cell
    /// moves at the rate of penetration, where the state after the kick is `g dt / 2` faster)
    /// and the compression.
    fn each_cell(&self, mut f: impl FnMut(f64, f64)) {
        for (s, sp) in self.field.sections.iter().enumerate() {
            for j in 1..=sp.cells {
                let (v, force) = self.field.cell(s, j);
                f(v - 0.5 * self.gravity[sp.offset + j], force);
            }
        }
    }
}

/// The depth of cut per revolution of the rate form, m: for a bit turning at `omega > 0` at the
/// step start, the root of `d = 2 pi v'(d) / omega` with `v'(d)` the axial speed the law `law`
/// gives at `d` on the ends `axial` and `torsion` (implicit in the axial speed: the law's `dW/dv = 2 pi a zeta eps / omega` is far
/// stiffer than the string's impedance, and an explicit `v` diverges), found by bisection
/// between `0+` and `2 pi v_free / omega` (`v'` falls as `d` grows); a bit pressed but held at
/// `v' = 0` by the contact gets the least positive depth (contact, no cutting). A bit rising
/// unloaded (`v_free < 0`) is off the rock (`-inf`). A bit not turning: the depth of the last
/// step it turned in, `last` (at least `0+`: the torque that breaks it free is the law's there).
pub fn rate_depth(law: &Law, axial: Port, torsion: EndLine, omega: f64, last: f64) -> f64 {
    if axial.free_speed < 0.0 {
        return f64::NEG_INFINITY;
    }
    let least = f64::MIN_POSITIVE;
    if omega <= 0.0 {
        return last.max(least);
    }
    let speed =
        |d: f64| law.resolve(&BitEnds { torsion, omega, axial: Some(AxialEnd { port: axial, depth: d }) }).axial_speed;
    let (mut lo, mut hi) = (least, TAU * axial.free_speed / omega);
    if hi <= lo || TAU * speed(lo) / omega <= lo {
        return least;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if TAU * speed(mid) / omega > mid {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
#[path = "axial_field_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "axial_field_bha_tests.rs"]
mod bha_tests;

#[path = "axial_field_steady.rs"]
mod steady;

//! The axial field in steady drilling ([`crate::drilling::start`]): `Axial::set_steady`.

use super::{Axial, DepthOfCut};
use crate::drilling::axial::cut_surface::{CutSurface, SurfaceRule, UpwindCutSurface};
use crate::drilling::axial::hoist_mode::rule;
use crate::drilling::axial::section::{static_tension, AxialSection};
use crate::drilling::config::DrillConfig;
use crate::drilling::start::{SteadyPoint, Wall};
use crate::error::{Error, Result};

impl Axial {
    /// Sets the field, the bit and the hoist in the steady drilling state `s` of `cfg` with the
    /// wall `wall`: every cell moving at the rate of penetration (the state after a step's
    /// gravity kick, [`Axial::each_cell`]) under the static tension with the BHA hanging, less
    /// the weight on bit and the axial resistance below it; the bit cutting at the steady depth
    /// of cut (the cut surface the steady helix, [`CutSurface::steady`], or the upwind chain's
    /// discrete steady profile); the hoist at its setpoint (an autodriller on weight on bit
    /// with the integral of the steady rate).
    pub fn set_steady(&mut self, cfg: &DrillConfig, s: &SteadyPoint, wall: &Wall) -> Result<()> {
        let (mud, g) = (cfg.well.mud_density, cfg.well.gravity);
        let parts: Vec<AxialSection> = cfg.sections.iter().map(AxialSection::from_section).collect();
        let traj = crate::drilling::well::trajectory(cfg)?;
        let inc = |md: f64| traj.at(md).inc;
        let w = s.bit.weight_on_bit - self.bha_weight;
        let tension = static_tension(&parts, mud, g, &inc, w, &self.z);
        let mut k = 0;
        for sec in 0..self.field.sections.len() {
            let (offset, cells) = (self.field.sections[sec].offset, self.field.sections[sec].cells);
            for j in 1..=cells {
                let n = tension[k] - wall.axial_resistance_below(self.z[k], s.rop, s.omega);
                self.field.set_cell(sec, j, s.rop + 0.5 * self.gravity[offset + j], -n);
                k += 1;
            }
        }
        let top = static_tension(&parts, mud, g, &inc, w, &[0.0])[0] - wall.axial_resistance_below(0.0, s.rop, s.omega);
        let Some((_, contact)) = self.law.steady(s.rop, s.omega) else {
            return Err(Error::invalid(
                "numerics.initial_state",
                "\"steady\"",
                "\"rest\" for a bit law without a steady drilling state",
            ));
        };
        self.state.contact = contact;
        self.state.depth = s.bit.depth;
        self.state.rop = s.rop;
        self.state.hook_load = top + self.block_weight;
        self.turning_depth = s.bit.depth;
        let blades = self.blades;
        match &mut self.rule {
            DepthOfCut::Regenerative(c) => *c = CutSurface::steady(blades, SurfaceRule::Deepest, 0.0, 0.0, s.bit.depth),
            DepthOfCut::Upwind(u) => *u = UpwindCutSurface::new(blades, u.cells(), s.bit.depth),
            DepthOfCut::Rate => {}
        }
        let p = &self.hoist.params;
        self.hoist.setpoint = p.target(0.0);
        if let Some(integral) = rule(p.mode).steady_integral(p, s.rop) {
            self.hoist.integral = integral;
        }
        Ok(())
    }
}

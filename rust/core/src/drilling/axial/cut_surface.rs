//! The regenerative depth of cut: the rock surface the blades leave behind, as a record of the
//! bit's axial position against its angle, looked up one blade pass (`2 pi / n`) back.
//!
//! Richard, Germay & Detournay, J. Sound Vib. 305 (2007) 432-456: the depth of cut of
//! a blade is `d_n(t) = x(t) - x(t - t_n)` with `x` the bit's axial position (down positive) and
//! `t_n` the state-dependent delay of the previous blade, `phi(t) - phi(t - t_n) = 2 pi / n`;
//! Aarsnes & van de Wouw, J. Sound Vib. 444 (2019) 127-151, write the same delay as a transport
//! equation for the cut surface (`l_t + (n omega / 2 pi) l_s = v_b`, `l(0) = 0`), advected by
//! first-order upwind in their code. Here the delay is exact: the record holds pairs
//! `(angle, surface depth)` in increasing angle, and the surface under a blade is the record
//! interpolated linearly in the angle at `phi - 2 pi / n`. Within a time step where the bit's
//! axial and angular speeds are constant (the transport scheme's boundary values), the position
//! is linear in the angle, so the interpolation reproduces the discrete motion exactly; a step
//! turning the bit more than one blade angle interpolates to the current state itself.
//!
//! # Rules
//!
//! * **Stick** (the angle does not advance): the bit's position is merged into the last record
//!   at that angle ([`SurfaceRule::Deepest`]: the deepest; [`SurfaceRule::PreviousPass`]: the
//!   latest, as the published transport scheme, whose surface at the inlet is frozen while
//!   `omega = 0`); the depth of cut keeps looking one blade angle back.
//! * **Reverse rotation** (the angle falls below the largest angle reached, `phi_max`): nothing
//!   is recorded (the cutters face away from the rock and do not cut). With
//!   [`SurfaceRule::Deepest`] the blade is back over rock it has cut itself, so its depth of cut
//!   is measured against the latest record of the place under it, the record at the angle
//!   `phi + k 2 pi / n` closest below `phi_max` (`k >= 0`); it is `<= 0` unless the bit moved
//!   below its own groove. With [`SurfaceRule::PreviousPass`] the angle is taken as `phi_max`
//!   (reverse rotation counts as stick, as in the published transport scheme, which advects at
//!   `max(omega, 0)`; give it the forward angle `int max(omega, 0) dt` to reproduce that code).
//! * **Lift-off** (bit bounce, `d_n < 0`): with [`SurfaceRule::Deepest`] the surface is the
//!   deepest cut of all passes, so a blade passing in the air leaves the rock as it was (the
//!   record at an angle is `max(x, surface one blade angle back)`); with
//!   [`SurfaceRule::PreviousPass`] it is the pure delay `x(t) - x(t - t_n)` of Richard et al. and
//!   Aarsnes & van de Wouw, which compares with the previous pass even when that pass was in the
//!   air. The two agree while every blade cut (`d_n > 0`) during the last blade angle.
//!
//! Memory: one record per step that turns the bit, over one blade angle, i.e. about
//! `2 pi / (n omega dt)` records at the angular speed `omega` (a stuck bit adds none).

use std::collections::VecDeque;

/// How the rock surface remembers passes that did not cut (see the module).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceRule {
    /// The surface is the deepest cut of every pass (lift-off leaves the rock unchanged).
    Deepest,
    /// The pure delay `x(t) - x(t - t_n)`: the previous pass, cut or not (the published codes).
    PreviousPass,
}

/// The cut surface: a ring buffer of `(angle rad, surface depth m)` pairs spanning at least one
/// blade angle behind the largest angle reached.
#[derive(Debug, Clone, PartialEq)]
pub struct CutSurface {
    blade_angle: f64,
    rule: SurfaceRule,
    record: VecDeque<(f64, f64)>,
}

impl CutSurface {
    /// The surface left by steady drilling at `depth_per_revolution` (m) with `blades` blades,
    /// the bit at the angle `angle` (rad) and position `position` (m): the helix
    /// `x(psi) = position - (angle - psi) depth / (2 pi)`, so that the depth of cut per revolution
    /// at the start is `depth_per_revolution` (0: flat rock just touched).
    pub fn steady(blades: u32, rule: SurfaceRule, angle: f64, position: f64, depth_per_revolution: f64) -> Self {
        let blade_angle = std::f64::consts::TAU / f64::from(blades.max(1));
        let mut record = VecDeque::with_capacity(64);
        record.push_back((angle - blade_angle, position - depth_per_revolution / f64::from(blades.max(1))));
        record.push_back((angle, position));
        CutSurface { blade_angle, rule, record }
    }

    /// The angle between blades `2 pi / n`, rad.
    pub fn blade_angle(&self) -> f64 {
        self.blade_angle
    }

    /// The largest angle the bit has reached, rad.
    pub fn max_angle(&self) -> f64 {
        self.record.back().map_or(f64::NEG_INFINITY, |r| r.0)
    }

    /// Records held (at least two).
    pub fn len(&self) -> usize {
        self.record.len()
    }

    /// Never empty (kept for the `len` convention).
    pub fn is_empty(&self) -> bool {
        self.record.is_empty()
    }

    /// The surface depth (m) recorded at the angle `key` (rad), linear in the angle between
    /// records; beyond the last record, linear towards the bit's current `(angle, position)`.
    fn surface_at(&self, key: f64, angle: f64, position: f64) -> f64 {
        let r = &self.record;
        let last = r[r.len() - 1];
        if key >= last.0 {
            return if angle > last.0 {
                last.1 + (position - last.1) * ((key - last.0) / (angle - last.0))
            } else {
                last.1
            };
        }
        let k = r.partition_point(|p| p.0 <= key);
        if k == 0 {
            return r[0].1;
        }
        let (a, b) = (r[k - 1], r[k]);
        a.1 + (b.1 - a.1) * ((key - a.0) / (b.0 - a.0))
    }

    /// The depth of cut of a blade, `d_n` (m, negative when the bit is above the surface), with
    /// the bit at `angle` (rad, cumulative) and axial `position` (m, down positive); the depth per
    /// revolution is `n d_n`. Does not change the record.
    pub fn depth_per_blade(&self, angle: f64, position: f64) -> f64 {
        let top = self.max_angle();
        let key = if angle >= top {
            angle - self.blade_angle
        } else {
            match self.rule {
                SurfaceRule::PreviousPass => top - self.blade_angle,
                // The latest angle <= top of the place under the blade.
                SurfaceRule::Deepest => angle + self.blade_angle * ((top - angle) / self.blade_angle).floor(),
            }
        };
        position - self.surface_at(key, angle, position)
    }

    /// Records the bit at `angle` and `position` (after the step's depth of cut is used): a new
    /// record when the angle advances, merged into the last one at an equal angle, nothing when
    /// the bit has turned back. Records more than one blade angle behind are dropped (one is kept
    /// before that for the interpolation).
    pub fn record(&mut self, angle: f64, position: f64) {
        let top = self.max_angle();
        if angle < top {
            return;
        }
        let surface = match self.rule {
            SurfaceRule::PreviousPass => position,
            SurfaceRule::Deepest => position.max(self.surface_at(angle - self.blade_angle, angle, position)),
        };
        if angle == top {
            let last = self.record.back_mut().expect("at least two records");
            last.1 = match self.rule {
                SurfaceRule::PreviousPass => surface,
                SurfaceRule::Deepest => last.1.max(surface),
            };
            return;
        }
        self.record.push_back((angle, surface));
        let keep = angle - self.blade_angle;
        while self.record.len() > 2 && self.record[1].0 <= keep {
            self.record.pop_front();
        }
    }
}

/// Aarsnes & van de Wouw's cut surface (2019, their `waveStep_transportBRI.m`): the depth of cut
/// of a blade as a field `l(s)` over one blade angle (`s` from 0, the blade now cutting, to 1, the
/// place the previous blade cut), transported by `l_t + (n omega / 2 pi) l_s = v_b` with `l = 0`
/// entering at `s = 0`, on `cells` cells by first-order upwind: per (sub-)step
/// `l_j <- l_j - C (l_j - l_{j-1}) + dt v_b`, `C = dt cells n max(omega, 0) / (2 pi)`. The depth of
/// cut of a blade is the last cell's value. The step is split into `ceil(C)` sub-steps when `C > 1`
/// (stable: `C <= 1`; their code sizes its cells from `5 omega_0` and runs at `C ~ 0.13` at the
/// set-point). Stick and reverse rotation freeze the transport (`max(omega, 0)`), the bit's axial
/// motion still deepening (or, rising, lifting) every cell; a blade above the rock has `l < 0`,
/// the previous pass's surface kept (the pure delay, as [`SurfaceRule::PreviousPass`]).
///
/// At a constant `omega` the chain is `cells` identical discrete first-order stages, whose
/// delays add up to `t_n = 2 pi / (n omega)` on average with the variance `t_n^2 (1 - C) / cells`:
/// numerical diffusion that damps the delay's response at the frequency `f` by about
/// `exp(-(2 pi f t_n)^2 (1 - C) / (2 cells))`, an error first order in `1 / cells` (the
/// `upwind_converges_to_the_exact_delay_at_first_order` test).
#[derive(Debug, Clone, PartialEq)]
pub struct UpwindCutSurface {
    blades: f64,
    depth: Vec<f64>,
}

impl UpwindCutSurface {
    /// `cells >= 1` cells holding the discrete steady profile of drilling at
    /// `depth_per_revolution`, `l_j = (j + 1) / cells depth / n` (0: flat rock just touched; their
    /// `l0 = linspace(0, 1, cells) dNom` is steady only as `cells` grows).
    pub fn new(blades: u32, cells: usize, depth_per_revolution: f64) -> Self {
        let n = f64::from(blades.max(1));
        let cells = cells.max(1);
        let depth = (0..cells).map(|j| (j + 1) as f64 / cells as f64 * depth_per_revolution / n).collect();
        UpwindCutSurface { blades: n, depth }
    }

    /// The depth of cut of a blade, m: the last cell (negative: the blade above the rock).
    pub fn depth_per_blade(&self) -> f64 {
        self.depth[self.depth.len() - 1]
    }

    /// Cells over one blade angle.
    pub fn cells(&self) -> usize {
        self.depth.len()
    }

    /// Advances the surface over `dt` with the bit turning at `angular_speed` (rad/s) and moving
    /// down at `axial_speed` (m/s).
    pub fn advance(&mut self, dt: f64, angular_speed: f64, axial_speed: f64) {
        let courant = dt * self.depth.len() as f64 * self.blades * angular_speed.max(0.0) / std::f64::consts::TAU;
        crate::simd::dispatch(Stages { depth: &mut self.depth, courant, dv: dt * axial_speed });
    }
}

/// The sub-steps of [`UpwindCutSurface::advance`] at Courant number `courant` over the step
/// and the bit's advance `dv` in it, as a [`crate::simd::Kernel`] (the stages in vector code;
/// no fused multiply-adds: the same bits on every path).
struct Stages<'a> {
    depth: &'a mut [f64],
    courant: f64,
    dv: f64,
}

impl crate::simd::Kernel for Stages<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) {
        let sub = self.courant.ceil().max(1.0);
        let (c, dv) = (self.courant / sub, self.dv / sub);
        for _ in 0..sub as usize {
            upwind_stage(self.depth, c, dv);
        }
    }
}

/// Cells of [`upwind_stage`] updated side by side.
const STAGE_BLOCK: usize = 8;

/// One upwind stage of the cut surface in place, `l_j += dv - c (l_j - l_{j-1})` from the
/// old values (`l_{-1} = 0`): from the last cell down, [`STAGE_BLOCK`] cells at a time from
/// the old values below them (so that the block vectorises), the rest one by one.
#[inline(always)]
fn upwind_stage(depth: &mut [f64], c: f64, dv: f64) {
    let mut top = depth.len();
    while top > STAGE_BLOCK {
        let low = top - STAGE_BLOCK;
        let mut new = [0.0; STAGE_BLOCK];
        let (below, block) = (&depth[low - 1..top - 1], &depth[low..top]);
        for k in 0..STAGE_BLOCK {
            new[k] = block[k] + (dv - c * (block[k] - below[k]));
        }
        depth[low..top].copy_from_slice(&new);
        top = low;
    }
    for j in (1..top).rev() {
        depth[j] += dv - c * (depth[j] - depth[j - 1]);
    }
    depth[0] += dv - c * depth[0];
}

#[cfg(test)]
mod stage_tests {
    /// [`super::upwind_stage`] against the stage cell by cell from the last: the same bits on
    /// surfaces below, at and above a block, at Courant numbers up to 1.
    #[test]
    fn the_blocked_stage_gives_the_bits_of_the_cell_by_cell_stage() {
        for cells in [1, 2, 7, 8, 9, 16, 17, 169] {
            for (c, dv) in [(0.13, 1e-6), (0.999, -3e-7), (1.0, 0.0)] {
                let start: Vec<f64> = (0..cells).map(|j| 1e-3 * ((j as f64 * 0.37).sin() + 1.5)).collect();
                let mut blocked = start.clone();
                super::upwind_stage(&mut blocked, c, dv);
                let mut serial = start.clone();
                for j in (1..cells).rev() {
                    serial[j] += dv - c * (serial[j] - serial[j - 1]);
                }
                serial[0] += dv - c * serial[0];
                let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&blocked), bits(&serial), "cells {cells} c {c}");
                assert_ne!(bits(&blocked), bits(&start));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    /// Steps a trajectory `(angle(t), position(t))` at `dt`, returning the depth per blade
    /// before each record.
    fn run(cs: &mut CutSurface, dt: f64, steps: usize, traj: impl Fn(f64) -> (f64, f64)) -> Vec<(f64, f64)> {
        let mut out = Vec::with_capacity(steps);
        for k in 1..=steps {
            let t = k as f64 * dt;
            let (phi, x) = traj(t);
            out.push((t, cs.depth_per_blade(phi, x)));
            cs.record(phi, x);
        }
        out
    }

    /// The upwind surface and the exact delay under a motion at a constant angular speed.
    fn upwind_run(cells: usize, dt: f64, steps: usize, omega: f64, x: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
        let v = |t: f64| (x(t + dt) - x(t)) / dt; // the step's mean speed: positions exact at step ends
        let mut up = UpwindCutSurface::new(4, cells, 0.0);
        let mut out = Vec::with_capacity(steps);
        for k in 0..steps {
            let t = k as f64 * dt;
            up.advance(dt, omega, v(t));
            out.push((t + dt, up.depth_per_blade()));
        }
        out
    }

    #[test]
    fn upwind_steady_profile_stick_and_sub_steps() {
        // Steady drilling at 30 rpm, 30 m/h from the steady profile: the depth stays V t_n.
        let (omega, v) = (PI, 30.0 / 3600.0);
        let d = TAU * v / omega;
        let mut up = UpwindCutSurface::new(4, 169, d);
        for _ in 0..5000 {
            up.advance(6.45e-4, omega, v);
        }
        assert!((4.0 * up.depth_per_blade() - d).abs() < 1e-15 * 5000.0);
        // Stick: no transport, every cell deepens by the axial advance.
        let before = up.clone();
        up.advance(0.01, 0.0, 0.02);
        assert!((up.depth_per_blade() - before.depth_per_blade() - 2e-4).abs() < 1e-16);
        // Reverse rotation counts as stick.
        let mut back = before.clone();
        back.advance(0.01, -3.0, 0.02);
        assert_eq!(back, up);
        // C = 2.5: three sub-steps of dt / 3, each at C = 5/6 (stable).
        let mut a = UpwindCutSurface::new(4, 10, 0.0);
        let mut b = a.clone();
        let dt = 2.5 * TAU / (10.0 * 4.0 * omega);
        a.advance(dt, omega, 0.01);
        for _ in 0..3 {
            b.advance(dt / 3.0, omega, 0.01);
        }
        for (x, y) in a.depth.iter().zip(&b.depth) {
            assert!((x - y).abs() < 1e-17);
        }
        // From flat rock at constant speeds: the front of the new surface reaches the last cell
        // after about one blade period, the depth then V t_n (to the chain's spread).
        let mut up = UpwindCutSurface::new(4, 169, 0.0);
        let tn = TAU / (4.0 * omega);
        let steps = (3.0 * tn / 6.45e-4) as usize;
        for _ in 0..steps {
            up.advance(6.45e-4, omega, v);
        }
        assert!((up.depth_per_blade() - v * tn).abs() < 1e-12 * v * tn);
    }

    #[test]
    fn upwind_converges_to_the_exact_delay_at_first_order() {
        // x = V t + A sin(2 pi f t) at 30 rpm, 4 blades (t_n = 0.5 s), f = 2 Hz (the blade-pass
        // frequency, where the regenerative oscillation lives), the torsional step of 1000 cells
        // on 2000 m of their pipe. Once periodic, the miss of the chain's depth of cut against the
        // exact delay (the CutSurface with the same motion) over the amplitude A is
        // 1 - exp(-(2 pi f t_n)^2 (1 - C) / (2 cells)) to within 10 %, C the sub-step's Courant
        // number (0.22, 0.44, 0.87, 0.87 in 2 sub-steps): 0.087, 0.032, 0.0037, 0.0019, first
        // order in 1 / cells at a given C (676 -> 1352 cells: half).
        let (omega, v, amp, f) = (PI, 30.0 / 3600.0, 1e-4, 2.0);
        let tn = TAU / (4.0 * omega);
        let dt = 2.0 / (77e9f64 / 8000.0).sqrt();
        let x = |t: f64| v * t + amp * (TAU * f * t).sin();
        let steps = (8.0 / dt) as usize;
        let mut misses = Vec::new();
        for cells in [169usize, 338, 676, 1352] {
            let up = upwind_run(cells, dt, steps, omega, x);
            let mut exact = CutSurface::steady(4, SurfaceRule::PreviousPass, 0.0, 0.0, 0.0);
            let mut miss: f64 = 0.0;
            for (k, &(t, d)) in up.iter().enumerate() {
                let phi = omega * (k + 1) as f64 * dt;
                let de = exact.depth_per_blade(phi, x(t));
                exact.record(phi, x(t));
                if t > 4.0 {
                    miss = miss.max((d - de).abs());
                }
            }
            let courant = dt * cells as f64 * 4.0 * omega / TAU;
            let c = courant / courant.ceil();
            let expect = 1.0 - (-(TAU * f * tn).powi(2) * (1.0 - c) / (2.0 * cells as f64)).exp();
            assert!((miss / amp / expect - 1.0).abs() < 0.1, "{cells} cells: {} vs {expect}", miss / amp);
            misses.push(miss);
        }
        assert!(misses.windows(2).all(|w| w[1] < w[0]), "{misses:?}");
        assert!((misses[2] / misses[3] - 2.0).abs() < 0.2, "{misses:?}");
    }

    #[test]
    fn steady_drilling_gives_rop_over_rotary_speed_per_revolution() {
        // 4 blades, 30 rpm (pi rad/s), 30 m/h: d = V / (Omega / 2 pi) = 1/60 m per revolution.
        let (n, omega, v) = (4u32, PI, 30.0 / 3600.0);
        for rule in [SurfaceRule::Deepest, SurfaceRule::PreviousPass] {
            // From flat rock: d = n v t while t < t_n = 0.5 s, then V 2 pi / Omega.
            let mut cs = CutSurface::steady(n, rule, 0.0, 0.0, 0.0);
            let dt = 0.5 / 97.3; // not a divisor of the blade period
            let out = run(&mut cs, dt, 2000, |t| (omega * t, v * t));
            for (t, dn) in out {
                let expect = if t < 0.5 { v * t } else { v * 0.5 };
                assert!((f64::from(n) * dn - f64::from(n) * expect).abs() < 1e-15, "t {t}: {dn} vs {expect}");
            }
            assert!(cs.len() < 110, "records beyond one blade angle are dropped: {}", cs.len());
            // Started on the steady helix: exact from the first step.
            let mut cs = CutSurface::steady(n, rule, 0.0, 0.0, 1.0 / 60.0);
            for (_, dn) in run(&mut cs, 1e-3, 1500, |t| (omega * t, v * t)) {
                assert!((4.0 * dn - 1.0 / 60.0).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn sinusoidal_motion_gives_the_delayed_difference() {
        // x = V t + A sin(w t) at constant Omega: d_n(t) = x(t) - x(t - tau), tau = 2 pi/(n Omega).
        let (n, omega, v, amp, w) = (3u32, 2.0 * PI, 0.01, 2e-3, 2.0 * PI * 1.7);
        let tau = TAU / (f64::from(n) * omega);
        let x = |t: f64| v * t + amp * (w * t).sin();
        let dt = 1e-4;
        let mut cs = CutSurface::steady(n, SurfaceRule::PreviousPass, 0.0, x(0.0), 0.0);
        // History before t = 0: the surface is flat at x(0) (d = x(t) - x(0) for t < tau).
        let out = run(&mut cs, dt, 30_000, |t| (omega * t, x(t)));
        // Linear interpolation of a smooth x between samples: error <= A w^2 dt^2 / 8.
        let bound = amp * w * w * dt * dt / 8.0 + 1e-15;
        for (t, dn) in out {
            let exact = if t < tau { x(t) - x(0.0) } else { x(t) - x(t - tau) };
            assert!((dn - exact).abs() <= bound, "t {t}: {dn} vs {exact}");
        }
        // A motion linear in each step (piecewise constant speeds) is reproduced to rounding,
        // whatever the delay falls on.
        let speeds = |k: usize| 0.01 + 0.004 * ((k * 7919) % 13) as f64 / 13.0;
        let dt = 1.0 / 1234.0;
        let mut xs = vec![0.0];
        for k in 0..4000 {
            xs.push(xs[k] + dt * speeds(k));
        }
        let xp = |t: f64| {
            let k = ((t / dt).floor() as usize).min(3999);
            xs[k] + (t - k as f64 * dt) * speeds(k)
        };
        let mut cs = CutSurface::steady(n, SurfaceRule::Deepest, 0.0, 0.0, 0.0);
        for (k, &x) in xs.iter().enumerate().skip(1) {
            let t = k as f64 * dt;
            let dn = cs.depth_per_blade(omega * t, x);
            let exact = if t < tau { x } else { x - xp(t - tau) };
            assert!((dn - exact).abs() < 1e-15, "step {k}: {dn} vs {exact}");
            cs.record(omega * t, x);
        }
    }

    #[test]
    fn stick_holds_the_angle_and_the_depth_grows_with_the_advance() {
        let (n, omega, v) = (4u32, PI, 0.01);
        let mut cs = CutSurface::steady(n, SurfaceRule::Deepest, 0.0, 0.0, 4.0 * v * 0.5);
        let dt = 1e-3;
        run(&mut cs, dt, 1000, |t| (omega * t, v * t));
        // Stuck at angle pi for 300 steps while the string pushes the bit 1 mm further down.
        let t = 1000.0 * dt;
        let (phi, x0) = (omega * t, v * t);
        let before = cs.depth_per_blade(phi, x0);
        assert!((before - v * 0.5).abs() < 1e-15);
        for k in 1..=300 {
            let x = x0 + 1e-3 * k as f64 / 300.0;
            let dn = cs.depth_per_blade(phi, x);
            assert!((dn - (before + (x - x0))).abs() < 1e-15);
            cs.record(phi, x);
        }
        let len = cs.len();
        // The angle did not advance: one record, merged.
        assert_eq!(cs.max_angle(), phi);
        // Rotation resumes: the previous blade's surface one blade angle back, continuous.
        let x1 = x0 + 1e-3;
        let dn = cs.depth_per_blade(phi + 1e-6, x1);
        assert!((dn - (x1 - (phi + 1e-6 - PI / 2.0) / omega * v)).abs() < 1e-12);
        assert_eq!(cs.len(), len);
    }

    #[test]
    fn lift_off_keeps_the_deepest_surface_and_the_pure_delay_does_not() {
        let (n, omega) = (1u32, TAU); // one blade, one revolution per second
        let dt = 1e-3;
        // Down at 1 cm/s for 1 s, up 8 mm at 2 cm/s, then down at 1 cm/s: the pure delay goes
        // negative from t = 4/3 s to t = 2.0667 s (the bit in the air).
        let x = |t: f64| {
            if t <= 1.0 {
                0.01 * t
            } else if t <= 1.4 {
                0.01 - 0.02 * (t - 1.0)
            } else {
                0.002 + 0.01 * (t - 1.4)
            }
        };
        // Before t = 0 the steady helix of 1 cm per revolution.
        let x_ext = |t: f64| if t < 0.0 { 0.01 * t } else { x(t) };
        let mut deep = CutSurface::steady(n, SurfaceRule::Deepest, 0.0, 0.0, 0.01);
        let mut pure = CutSurface::steady(n, SurfaceRule::PreviousPass, 0.0, 0.0, 0.01);
        let d = run(&mut deep, dt, 3000, |t| (omega * t, x(t)));
        let p = run(&mut pure, dt, 3000, |t| (omega * t, x(t)));
        for ((t, dd), (_, dp)) in d.iter().zip(&p) {
            let t = *t;
            // Pure delay: x(t) - x(t - 1).
            let exact = x(t) - x_ext(t - 1.0);
            assert!((dp - exact).abs() < 1e-13, "t {t}: {dp} vs {exact}");
            // Deepest: the deepest of all earlier passes, max_k x(t - k), k >= 1.
            let mut s = f64::NEG_INFINITY;
            let mut k = 1.0;
            loop {
                s = s.max(x_ext(t - k));
                if t - k < 0.0 {
                    break;
                }
                k += 1.0;
            }
            assert!((dd - (x(t) - s)).abs() < 1e-13, "t {t}: {dd} vs {}", x(t) - s);
        }
        let at = |v: &[(f64, f64)], t: f64| v[(t / dt).round() as usize - 1].1;
        // Cutting while rising (t = 1.2): both 10 - 6 + ... = x(1.2) - x(0.2) = 4 mm.
        assert!((at(&d, 1.2) - 0.004).abs() < 1e-12 && (at(&p, 1.2) - 0.004).abs() < 1e-12);
        // In the air (t = 1.6): both x(1.6) - x(0.6) = -2 mm.
        assert!((at(&d, 1.6) + 0.002).abs() < 1e-12 && (at(&p, 1.6) + 0.002).abs() < 1e-12);
        // t = 2.4: the pass at 1.4 was in the air (2 mm), the rock is at x(0.4) = 4 mm: the
        // deepest surface gives 12 - 4 = 8 mm, the pure delay 12 - 2 = 10 mm.
        assert!((at(&d, 2.4) - 0.008).abs() < 1e-12);
        assert!((at(&p, 2.4) - 0.010).abs() < 1e-12);
    }

    #[test]
    fn reverse_rotation_measures_against_the_own_groove() {
        let (n, omega, v) = (2u32, PI, 0.01);
        let dt = 1e-3;
        let mut cs = CutSurface::steady(n, SurfaceRule::Deepest, 0.0, 0.0, 2.0 * v * 1.0);
        run(&mut cs, dt, 2000, |t| (omega * t, v * t));
        let t = 2000.0 * dt;
        let (top, x0) = (omega * t, v * t);
        // Turn back 0.1 rad at the same depth: the blade is over its own groove, cut when the
        // bit was at x = v (top - 0.1) / omega, 0.1 v / omega above its present depth.
        let back = top - 0.1;
        let dn = cs.depth_per_blade(back, x0);
        assert!((dn - 0.1 * v / omega).abs() < 1e-12, "{dn}");
        // Lifted by 1 mm first: above the groove.
        assert!(cs.depth_per_blade(back, x0 - 1e-3) < 0.0);
        // Nothing recorded while behind.
        let len = cs.len();
        cs.record(back, x0 - 1e-3);
        assert_eq!((cs.len(), cs.max_angle()), (len, top));
        // Turned back more than a blade angle (pi + 0.1): the place under the blade was last cut
        // by the other blade, at the angle top - 0.1 as well.
        let dn2 = cs.depth_per_blade(top - PI - 0.1, x0);
        assert!((dn2 - dn).abs() < 1e-12);
        // Back at the front: the previous blade's surface again, as before the reversal.
        let front = cs.depth_per_blade(top, x0);
        assert!((front - v * 1.0).abs() < 1e-12);
        // PreviousPass treats the reversal as stick: the depth at the front.
        let mut pp = CutSurface::steady(n, SurfaceRule::PreviousPass, 0.0, 0.0, 2.0 * v * 1.0);
        run(&mut pp, dt, 2000, |t| (omega * t, v * t));
        assert!((pp.depth_per_blade(back, x0) - v * 1.0).abs() < 1e-12);
    }

    #[test]
    fn more_than_a_blade_angle_in_one_step_interpolates_to_the_present() {
        // 8 blades, a step of 1 rad (> pi/4): the surface pi/4 back lies inside this step.
        let mut cs = CutSurface::steady(8, SurfaceRule::Deepest, 0.0, 0.0, 0.0);
        let dn = cs.depth_per_blade(1.0, 0.01);
        // Linear from (0, 0) to (1, 0.01): the surface at 1 - pi/4 is 0.01 (1 - pi/4).
        assert!((dn - 0.01 * PI / 4.0).abs() < 1e-15);
        cs.record(1.0, 0.01);
        assert_eq!(cs.len(), 2);
    }
}

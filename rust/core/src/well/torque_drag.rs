//! Static soft-string torque and drag (Johancsik, Friesen & Dawson 1984, SPE 11380): the string
//! lies on the low or high side of the hole along the well's path, carries an effective
//! tension (buoyed weight, so the mud's pressure is in the weight and not in the tension)
//! and no bending moment; each element presses on the wall with the normal force that
//! balances its weight and the pull of the tension around the curve, and the wall's Coulomb
//! friction on it opposes the axial motion (tripping) or the rotation (rotating, where all the
//! friction is taken as torque: the usual limit of a rotary speed far above the axial speed).
//!
//! An element from `md_a` (top) to `md_b` (bottom) of directions `t_a`, `t_b` carries the
//! tension `T_b` at its bottom. Its normal force is
//! `N = |T_b (t_b - t_a) + w L z_perp|`, with `w` the buoyed weight per length, `L` its
//! length and `z_perp` the component of the downward unit vector normal to the element's mean
//! direction (Johancsik's `sqrt((T da sin i)^2 + (T di + W sin i)^2)` written as a vector, so
//! that builds, drops and turns need no sign rules). Then, stepping up from the bit,
//! `T_a = T_b + w L cos(i) + s mu N` (`s = +1` picking up, `-1` slacking off, 0 rotating) and,
//! rotating, `M_a = M_b + mu r N` (`r` the contact radius). The continuous form is the limit of
//! short elements: `-dT/ds = w cos(i) + s mu n`, `-dM/ds = mu r n`,
//! `n = |T dt/ds + w z_perp|` per length, integrated here by the classical Runge-Kutta
//! method on the same nodes.
//!
//! Hook load = the tension at the surface plus the travelling block's weight (no sheave
//! friction). On bottom the bit carries the compression `-WOB` and the torque on bit.

use serde::Serialize;

use super::buckling::{self, Body, Hole, Mode};
use super::{dot, Trajectory};
use crate::error::{Error, Num, Result};

/// The largest element the torque-and-drag steps take by default, m.
pub const DEFAULT_STEP: f64 = 1.0;

/// The most elements of one profile (the string's length over `step`): each is a few values in
/// each of the four operations' profiles, so this bounds the memory of an analysis (about
/// 200 MB) before it is allocated.
pub const MAX_ELEMENTS: usize = 1_000_000;

/// A compression beyond any string's strength, N: a helically buckled string's compression
/// past it has diverged (its wall contact grows with the square of it), the string locked up.
pub const DIVERGED: f64 = 1e12;

/// A piece of the string of uniform properties, from the bit up (the order is from the top,
/// like the configuration's sections).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub length: f64,
    /// Buoyed weight per length, N/m.
    pub weight: f64,
    /// The radius the wall's friction acts at, m.
    pub contact_radius: f64,
    /// The pipe body: buckling (with a hole) and the limits.
    pub body: Body,
}

impl Piece {
    /// A piece without a pipe body's properties (no buckling, no limits).
    pub fn new(length: f64, weight: f64, contact_radius: f64) -> Piece {
        Piece { length, weight, contact_radius, body: Body::default() }
    }
}

/// A sliding friction factor over a depth interval `[top_md, bottom_md)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlidingInterval {
    pub top_md: f64,
    pub bottom_md: f64,
    pub mu: f64,
}

/// The sliding (kinetic) friction factor along the hole: `mu` where no interval covers a depth.
#[derive(Debug, Clone, PartialEq)]
pub struct SlidingFriction {
    pub mu: f64,
    pub intervals: Vec<SlidingInterval>,
}

impl SlidingFriction {
    pub fn uniform(mu: f64) -> SlidingFriction {
        SlidingFriction { mu, intervals: Vec::new() }
    }

    /// The factor at `md` (the first interval holding it; intervals are half-open, top
    /// included).
    pub fn at(&self, md: f64) -> f64 {
        self.intervals.iter().find(|iv| md >= iv.top_md && md < iv.bottom_md).map_or(self.mu, |iv| iv.mu)
    }
}

/// The five operations of a torque-and-drag analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Operation {
    /// Tripping out (moving up), off bottom, not rotating.
    PickUp,
    /// Tripping in (moving down), off bottom, not rotating.
    SlackOff,
    /// Rotating off bottom, no axial motion.
    RotatingOffBottom,
    /// Rotating on bottom: the bit carries `-WOB` and the torque on bit.
    RotatingOnBottom,
    /// Sliding (oriented drilling with a motor): lowering without rotation with the bit
    /// carrying `-WOB`.
    Sliding,
}

impl Operation {
    pub const ALL: [Operation; 5] = [
        Operation::PickUp,
        Operation::SlackOff,
        Operation::RotatingOffBottom,
        Operation::RotatingOnBottom,
        Operation::Sliding,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Operation::PickUp => "pickup",
            Operation::SlackOff => "slackoff",
            Operation::RotatingOffBottom => "rotating",
            Operation::RotatingOnBottom => "rotating_on_bottom",
            Operation::Sliding => "sliding",
        }
    }

    /// The sign of the axial friction in `T_a = T_b + W cos i + s mu N`.
    fn drag_sign(self) -> f64 {
        match self {
            Operation::PickUp => 1.0,
            Operation::SlackOff | Operation::Sliding => -1.0,
            _ => 0.0,
        }
    }

    fn rotating(self) -> bool {
        matches!(self, Operation::RotatingOffBottom | Operation::RotatingOnBottom)
    }
}

/// How the profile is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileMethod {
    /// Johancsik's elements, stepped from the bit up with the tension at each element's bottom.
    Stepwise,
    /// The continuous equations by the classical Runge-Kutta method between the nodes.
    Continuous,
}

/// The string in the hole and the loads on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// From the top of the string; their lengths sum to the bit's depth.
    pub pieces: Vec<Piece>,
    pub friction: SlidingFriction,
    /// N (on bottom).
    pub weight_on_bit: f64,
    /// N m (on bottom).
    pub bit_torque: f64,
    /// N, added to the surface tension in hook loads.
    pub block_weight: f64,
    /// The longest element, m.
    pub step: f64,
    /// The hole (None: no buckling).
    pub hole: Option<Hole>,
    /// The mud's hydrostatic pressure gradient `rho_mud g`, Pa/m: the true axial force is the
    /// effective tension less the pressure at the depth times the body's area.
    pub pressure_gradient: f64,
}

/// The profile of one operation, at nodes from the surface (md 0) to the bit.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Profile {
    pub md: Vec<f64>,
    /// Effective tension, N (negative: compression).
    #[serde(rename = "tension_N")]
    pub tension: Vec<f64>,
    /// N m.
    #[serde(rename = "torque_Nm")]
    pub torque: Vec<f64>,
    /// Normal force per length of the element below each node (the bit's: the element above), N/m.
    #[serde(rename = "normal_force_N_per_m")]
    pub normal_force: Vec<f64>,
    /// The normal force times the joint length, N (like `normal_force`).
    #[serde(rename = "side_force_per_joint_N")]
    pub side_force_per_joint: Vec<f64>,
    /// Sinusoidal critical load of the element below each node, N (compressive; empty without a hole).
    #[serde(rename = "sinusoidal_buckling_load_N")]
    pub sinusoidal_load: Vec<f64>,
    /// Helical critical load, N (like `sinusoidal_load`).
    #[serde(rename = "helical_buckling_load_N")]
    pub helical_load: Vec<f64>,
    /// The buckled state at each node (empty without a hole).
    pub buckling: Vec<Mode>,
    /// Von Mises stress of the true axial force and the torque over the yield strength (NaN
    /// in a piece without one; empty when none has one).
    pub utilisation: Vec<f64>,
}

impl Profile {
    /// The hook load of this operation with the block weight `block`, N.
    pub fn surface_tension(&self) -> f64 {
        self.tension.first().copied().unwrap_or(0.0)
    }

    pub fn surface_torque(&self) -> f64 {
        self.torque.first().copied().unwrap_or(0.0)
    }

    /// Whether the bit's load needs the surface to push (the surface tension below 0, or a
    /// compression diverging in a helically buckled string): the string locks up.
    pub fn locked_up(&self) -> bool {
        let t = self.surface_tension();
        t.is_nan() || t < 0.0
    }

    /// The first (shallowest) depth of buckling `mode` or worse.
    pub fn first_buckled(&self, mode: Mode) -> Option<f64> {
        let worse = |m: &Mode| *m == mode || (mode == Mode::Sinusoidal && *m == Mode::Helical);
        self.buckling.iter().position(worse).map(|k| self.md[k])
    }

    /// The largest normal force per length and its depth.
    pub fn max_normal_force(&self) -> (f64, f64) {
        self.normal_force.iter().zip(&self.md).fold((0.0, 0.0), |best, (&n, &d)| if n > best.0 { (n, d) } else { best })
    }
}

/// The nodes of a string whose bit is at `bit_md`: every piece end, survey station and
/// friction-interval end within, and at most `step` apart.
fn nodes(traj: &Trajectory, setup: &Setup, bit_md: f64) -> Vec<f64> {
    let mut breaks = vec![0.0, bit_md];
    let mut d = 0.0;
    for p in &setup.pieces {
        d += p.length;
        breaks.push(d);
    }
    breaks.extend(traj.survey.md.iter().copied());
    for iv in &setup.friction.intervals {
        breaks.push(iv.top_md);
        breaks.push(iv.bottom_md);
    }
    breaks.retain(|&x| (0.0..=bit_md).contains(&x));
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|b, a| *b - *a <= 1e-9 * bit_md.max(1.0));
    *breaks.last_mut().unwrap() = bit_md;
    let mut out = Vec::with_capacity((bit_md / setup.step) as usize + breaks.len() + 1);
    for w in breaks.windows(2) {
        let n = ((w[1] - w[0]) / setup.step).ceil().max(1.0) as usize;
        for k in 0..n {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / n as f64);
        }
    }
    out.push(bit_md);
    out
}

/// The piece at `md` from the top (the last one at and below its end).
pub(crate) fn piece_at(pieces: &[Piece], md: f64) -> &Piece {
    let mut d = 0.0;
    for p in pieces {
        d += p.length;
        if md < d {
            return p;
        }
    }
    pieces.last().expect("at least one piece")
}

/// The string's elements with the bit at one depth: the nodes, the direction at each and, with
/// a hole, each element's bending stiffness, radial clearance and critical loads. These depend
/// on the geometry alone, not on the operation, the friction factor or the bit's load, so every
/// profile at one bit depth shares them ([`Setup::elements`] once, then
/// [`Setup::profile_on`]): the five operations and the lock-up's bisection, each bit depth's
/// lines of the broomstick, the bisection of an implied friction factor.
#[derive(Debug, Clone, PartialEq)]
pub struct Elements {
    bit_md: f64,
    md: Vec<f64>,
    tangent: Vec<[f64; 3]>,
    /// `(E I, r_c, (sinusoidal, helical))` of the element below each node but the bit's (empty
    /// without a hole).
    buckling: Vec<(f64, f64, (f64, f64))>,
}

impl Setup {
    /// The elements of the string with the bit at `bit_md` (see [`Elements`]).
    pub fn elements(&self, traj: &Trajectory, bit_md: f64) -> Elements {
        let offset = self.depth() - bit_md;
        let md = nodes(traj, self, bit_md);
        let tangent: Vec<[f64; 3]> = md.iter().map(|&d| traj.at(d).tangent).collect();
        let buckling = match &self.hole {
            None => Vec::new(),
            Some(h) => (0..md.len() - 1)
                .map(|j| {
                    let mid = 0.5 * (md[j] + md[j + 1]);
                    let p = piece_at(&self.pieces, mid + offset);
                    let length = md[j + 1] - md[j];
                    let (ta, tb) = (tangent[j], tangent[j + 1]);
                    let (ei, rc) = (p.body.bending_stiffness(), buckling::clearance(h.at(mid), p.body.outer_diameter));
                    let mut mean = [ta[0] + tb[0], ta[1] + tb[1], ta[2] + tb[2]];
                    let m = dot(mean, mean).sqrt();
                    mean.iter_mut().for_each(|x| *x /= m);
                    let kappa = [(tb[0] - ta[0]) / length, (tb[1] - ta[1]) / length, (tb[2] - ta[2]) / length];
                    (ei, rc, buckling::critical_loads(ei, p.weight, rc, mean, kappa))
                })
                .collect(),
        };
        Elements { bit_md, md, tangent, buckling }
    }

    /// The bit's tension and torque in `op`, N and N m: `-WOB` and the torque on bit rotating on
    /// bottom, `-WOB` sliding, none off bottom.
    pub fn bit_load(&self, op: Operation) -> (f64, f64) {
        match op {
            Operation::RotatingOnBottom => (-self.weight_on_bit, self.bit_torque),
            Operation::Sliding => (-self.weight_on_bit, 0.0),
            _ => (0.0, 0.0),
        }
    }

    /// Checks the setup against the trajectory: pieces, friction factors, loads and step, and
    /// that the survey reaches the bit (a survey of one station is a straight hole).
    pub fn validate(&self, traj: &Trajectory) -> Result<()> {
        self.validate_string()?;
        let depth = self.depth();
        // a survey of one station is a straight hole, of any length
        if traj.survey.len() > 1 && depth > traj.survey.depth() * (1.0 + 1e-12) {
            return Err(Error::invalid(
                "well.survey",
                format!("stations to {} m", Num(traj.survey.depth())),
                format!(
                    "a survey reaching the bit at {} m (well.extend = true continues the last station straight on)",
                    Num(depth)
                ),
            ));
        }
        Ok(())
    }

    /// Checks pieces, friction factors, loads and step.
    pub fn validate_string(&self) -> Result<()> {
        if self.pieces.is_empty() {
            return Err(Error::invalid("sections", "none", "at least one section"));
        }
        for (i, p) in self.pieces.iter().enumerate() {
            if !(p.length.is_finite() && p.length > 0.0) {
                return Err(Error::invalid(format!("sections[{i}].length"), Num(p.length), "a finite length > 0 m"));
            }
            if !(p.weight.is_finite() && p.contact_radius.is_finite() && p.contact_radius > 0.0) {
                return Err(Error::invalid(
                    format!("sections[{i}]"),
                    Num(p.weight),
                    "a finite buoyed weight and contact radius > 0",
                ));
            }
        }
        let mu_ok = |m: f64| m.is_finite() && m >= 0.0;
        if !mu_ok(self.friction.mu) {
            return Err(Error::invalid("friction.static", Num(self.friction.mu), "a finite friction factor >= 0"));
        }
        for (j, iv) in self.friction.intervals.iter().enumerate() {
            if !mu_ok(iv.mu) {
                return Err(Error::invalid(
                    format!("friction.intervals[{j}].static"),
                    Num(iv.mu),
                    "a finite friction factor >= 0",
                ));
            }
            if !(iv.top_md.is_finite() && iv.top_md >= 0.0 && iv.bottom_md.is_finite() && iv.bottom_md > iv.top_md) {
                return Err(Error::invalid(
                    format!("friction.intervals[{j}].bottom_md"),
                    Num(iv.bottom_md),
                    format!("a finite depth > top_md = {} m (top_md >= 0)", Num(iv.top_md)),
                ));
            }
        }
        for (name, v) in [
            ("bit.weight_on_bit", self.weight_on_bit),
            ("torque_drag.bit_torque", self.bit_torque),
            ("torque_drag.block_weight", self.block_weight),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(name, Num(v), "a finite number >= 0"));
            }
        }
        let min_step = self.depth() / MAX_ELEMENTS as f64;
        if !(self.step.is_finite() && self.step > 0.0 && self.step >= min_step) {
            return Err(Error::invalid(
                "torque_drag.step",
                Num(self.step),
                format!(
                    "a finite element length of at least {} m (at most {MAX_ELEMENTS} elements over the string's {} m)",
                    Num(min_step),
                    Num(self.depth())
                ),
            ));
        }
        Ok(())
    }

    /// The string's length: the bit's depth with the string all in the hole, m.
    pub fn depth(&self) -> f64 {
        self.pieces.iter().map(|p| p.length).sum()
    }

    /// The profile of `op` along `traj` with the bit at the string's depth.
    pub fn solve(&self, traj: &Trajectory, op: Operation, scheme: ProfileMethod) -> Profile {
        self.solve_at(traj, op, scheme, self.depth(), None)
    }

    /// The profile with the bit at `bit_md` (`<=` the string's length: the string's top pieces
    /// out of the hole; the bottom `bit_md` metres of it in), with the friction factor `mu`
    /// everywhere if given.
    pub fn solve_at(
        &self,
        traj: &Trajectory,
        op: Operation,
        scheme: ProfileMethod,
        bit_md: f64,
        mu: Option<f64>,
    ) -> Profile {
        self.profile(traj, op, scheme, bit_md, mu, self.bit_load(op))
    }

    /// The profile from the bit's tension and torque `bit`, N and N m.
    pub(crate) fn profile(
        &self,
        traj: &Trajectory,
        op: Operation,
        scheme: ProfileMethod,
        bit_md: f64,
        mu: Option<f64>,
        bit: (f64, f64),
    ) -> Profile {
        self.profile_on(traj, &self.elements(traj, bit_md), op, scheme, mu, bit)
    }

    /// The profile of `op` on the elements `el` ([`Setup::elements`] of this setup and `traj`)
    /// with the friction factor `mu` everywhere if given, from the bit's tension and torque
    /// `bit`, N and N m ([`Setup::bit_load`]).
    pub fn profile_on(
        &self,
        traj: &Trajectory,
        el: &Elements,
        op: Operation,
        scheme: ProfileMethod,
        mu: Option<f64>,
        bit: (f64, f64),
    ) -> Profile {
        let offset = self.depth() - el.bit_md;
        let pieces = &self.pieces;
        let piece = |md: f64| piece_at(pieces, md + offset);
        let friction = |md: f64| mu.unwrap_or_else(|| self.friction.at(md));
        let md = el.md.clone();
        let n = md.len();
        let mut tension = vec![0.0; n];
        let mut torque = vec![0.0; n];
        let mut normal = vec![0.0; n];
        let buckles = self.hole.is_some();
        // the element at which a helically buckled string locked up
        let mut locked = None;
        (tension[n - 1], torque[n - 1]) = bit;
        let sign = op.drag_sign();
        let rotating = op.rotating();
        for j in (0..n - 1).rev() {
            let mid = 0.5 * (md[j] + md[j + 1]);
            let p = piece(mid);
            let mu = friction(mid);
            let length = md[j + 1] - md[j];
            let (ta, tb) = (el.tangent[j], el.tangent[j + 1]);
            // the element's bending stiffness, clearance and critical loads
            let buckling = el.buckling.get(j).copied();
            // Mitchell's contact of a helically buckled string under the compression -t
            let helical = |t: f64| match buckling {
                Some((ei, rc, (_, fh))) if -t >= fh => buckling::helical_contact(ei, -t, rc),
                _ => 0.0,
            };
            match scheme {
                ProfileMethod::Stepwise => {
                    let mut mean = [ta[0] + tb[0], ta[1] + tb[1], ta[2] + tb[2]];
                    let m = dot(mean, mean).sqrt();
                    mean.iter_mut().for_each(|x| *x /= m);
                    let w = p.weight * length;
                    let cos_i = mean[2];
                    let t = tension[j + 1];
                    let v = [
                        t * (tb[0] - ta[0]) - w * cos_i * mean[0],
                        t * (tb[1] - ta[1]) - w * cos_i * mean[1],
                        t * (tb[2] - ta[2]) + w * (1.0 - cos_i * mean[2]),
                    ];
                    let mut nf = dot(v, v).sqrt();
                    if buckles {
                        nf += helical(t) * length;
                    }
                    tension[j] = t + w * cos_i + sign * mu * nf;
                    torque[j] = torque[j + 1] + if rotating { mu * p.contact_radius * nf } else { 0.0 };
                    normal[j] = nf / length;
                }
                ProfileMethod::Continuous => {
                    // y = (T, M) against the depth going up, s = md[j + 1] -> md[j]
                    let arc = traj.interval(mid);
                    let rhs = |s: f64, t: f64| -> (f64, f64, f64) {
                        let q = traj.at_on(s, arc);
                        let k = traj.curvature_vector_on(s, arc);
                        let z = [
                            -q.tangent[2] * q.tangent[0],
                            -q.tangent[2] * q.tangent[1],
                            1.0 - q.tangent[2] * q.tangent[2],
                        ];
                        let mut nf = normal_force(t, k, [p.weight * z[0], p.weight * z[1], p.weight * z[2]]);
                        if buckles {
                            nf += helical(t);
                        }
                        // d/d(-s): tension and torque grow going up
                        (
                            p.weight * q.tangent[2] + sign * mu * nf,
                            if rotating { mu * p.contact_radius * nf } else { 0.0 },
                            nf,
                        )
                    };
                    let (s0, h) = (md[j + 1], length);
                    let (t0, m0) = (tension[j + 1], torque[j + 1]);
                    let k1 = rhs(s0, t0);
                    let k2 = rhs(s0 - h / 2.0, t0 + h / 2.0 * k1.0);
                    let k3 = rhs(s0 - h / 2.0, t0 + h / 2.0 * k2.0);
                    let k4 = rhs(s0 - h, t0 + h * k3.0);
                    tension[j] = t0 + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                    torque[j] = m0 + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
                    normal[j] = (k1.2 + 2.0 * k2.2 + 2.0 * k3.2 + k4.2) / 6.0;
                }
            }
            if buckles && (tension[j].is_nan() || tension[j] <= -DIVERGED) {
                // the compression of a helically buckled string diverges: locked up above
                tension[..=j].fill(f64::NEG_INFINITY);
                normal[..=j].fill(f64::INFINITY);
                locked = Some(j);
                break;
            }
        }
        normal[n - 1] = if n > 1 { normal[n - 2] } else { 0.0 };
        let mut profile = Profile { md, tension, torque, normal_force: normal, ..Profile::default() };
        if buckles {
            let mut loads: Vec<(f64, f64)> = el.buckling.iter().map(|b| b.2).collect();
            // above a lock-up the string was not followed: no critical loads there
            if let Some(j) = locked {
                loads[..j].fill((0.0, 0.0));
            }
            loads.push(loads.last().copied().unwrap_or((0.0, 0.0)));
            profile.buckling = loads.iter().zip(&profile.tension).map(|(l, t)| Mode::of(-t, l.0, l.1)).collect();
            (profile.sinusoidal_load, profile.helical_load) = loads.into_iter().unzip();
        }
        self.limits(traj, &mut profile, offset);
        profile
    }

    /// The side force per joint and the utilisation of a profile (`offset`: the string's
    /// length above the surface).
    fn limits(&self, traj: &Trajectory, profile: &mut Profile, offset: f64) {
        let n = profile.md.len();
        let body = |k: usize| {
            // the element below each node, the bit's the one above
            let at = if k + 1 < n { 0.5 * (profile.md[k] + profile.md[k + 1]) } else { profile.md[k] };
            piece_at(&self.pieces, at + offset).body
        };
        profile.side_force_per_joint = (0..n).map(|k| profile.normal_force[k] * body(k).joint_length).collect();
        if self.pieces.iter().all(|p| p.body.yield_strength.is_none()) {
            return;
        }
        profile.utilisation = (0..n)
            .map(|k| {
                let b = body(k);
                b.yield_strength.map_or(f64::NAN, |y| {
                    let tvd = traj.at(profile.md[k]).position[2];
                    let f = profile.tension[k] - self.pressure_gradient * tvd * b.area;
                    buckling::von_mises(f, profile.torque[k], b.area, b.polar_moment, b.outer_diameter / 2.0) / y
                })
            })
            .collect();
    }
}

/// The soft-string normal force per length, N/m: `|T kappa + wz|` with the tension `T` (N),
/// the trajectory's curvature vector `kappa` (1/m) and `wz = w (e_z - (e_z . t) t)`, the buoyed
/// weight per length `w` times the part of the vertical `e_z` across the direction `t` (the
/// lateral balance of a string element, `d(T t)/ds + w e_z + N = 0` across `t`). The continuous
/// equations here and the coupled run's wall contact
/// ([`crate::drilling::engine::coupled_friction`]) take it.
#[inline(always)]
pub fn normal_force(tension: f64, kappa: [f64; 3], wz: [f64; 3]) -> f64 {
    let v = [tension * kappa[0] + wz[0], tension * kappa[1] + wz[1], tension * kappa[2] + wz[2]];
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The summary of the five operations (serialised under the names of `torque_drag.json`,
/// `hook_load_pickup_N`, ..., and the profiles by operation name). The largest normal force
/// is that of the four operations other than sliding.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TorqueDrag {
    #[serde(rename = "hook_load_pickup_N")]
    pub hook_load_pickup_n: f64,
    #[serde(rename = "hook_load_slackoff_N")]
    pub hook_load_slackoff_n: f64,
    #[serde(rename = "hook_load_rotating_N")]
    pub hook_load_rotating_n: f64,
    #[serde(rename = "hook_load_rotating_on_bottom_N")]
    pub hook_load_rotating_on_bottom_n: f64,
    #[serde(rename = "hook_load_sliding_N")]
    pub hook_load_sliding_n: f64,
    #[serde(rename = "surface_torque_off_bottom_Nm")]
    pub surface_torque_off_bottom_nm: f64,
    #[serde(rename = "surface_torque_on_bottom_Nm")]
    pub surface_torque_on_bottom_nm: f64,
    #[serde(rename = "max_normal_force_N_per_m")]
    pub max_normal_force_n_per_m: f64,
    pub max_normal_force_md: f64,
    pub max_normal_force_operation: &'static str,
    #[serde(flatten)]
    pub limits: super::td_limits::Limits,
    /// In the order of [`Operation::ALL`].
    #[serde(serialize_with = "by_operation")]
    pub profiles: Vec<Profile>,
}

fn by_operation<S: serde::Serializer>(profiles: &[Profile], s: S) -> std::result::Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = s.serialize_map(Some(profiles.len()))?;
    for (op, p) in Operation::ALL.iter().zip(profiles) {
        map.serialize_entry(op.name(), p)?;
    }
    map.end()
}

/// All four operations; the survey must reach the bit ([`Setup::validate`]).
pub fn analyse(traj: &Trajectory, setup: &Setup, scheme: ProfileMethod) -> Result<TorqueDrag> {
    setup.validate(traj)?;
    Ok(analyse_unchecked(traj, setup, scheme))
}

/// [`analyse`] of a setup already checked ([`Setup::validate_string`]; the trajectory
/// continues straight on below its last station).
pub fn analyse_unchecked(traj: &Trajectory, setup: &Setup, scheme: ProfileMethod) -> TorqueDrag {
    let el = setup.elements(traj, setup.depth());
    let profiles: Vec<Profile> =
        Operation::ALL.iter().map(|&op| setup.profile_on(traj, &el, op, scheme, None, setup.bit_load(op))).collect();
    let hook = |k: usize| profiles[k].surface_tension() + setup.block_weight;
    let (mut best, mut at, mut which) = (0.0, 0.0, Operation::ALL[0].name());
    for (op, p) in Operation::ALL[..4].iter().zip(&profiles) {
        let (n, d) = p.max_normal_force();
        if n > best {
            (best, at, which) = (n, d, op.name());
        }
    }
    TorqueDrag {
        hook_load_pickup_n: hook(0),
        hook_load_slackoff_n: hook(1),
        hook_load_rotating_n: hook(2),
        hook_load_rotating_on_bottom_n: hook(3),
        hook_load_sliding_n: hook(4),
        surface_torque_off_bottom_nm: profiles[2].surface_torque(),
        surface_torque_on_bottom_nm: profiles[3].surface_torque(),
        max_normal_force_n_per_m: best,
        max_normal_force_md: at,
        max_normal_force_operation: which,
        limits: super::td_limits::limits(traj, setup, &el, scheme, &profiles),
        profiles,
    }
}

/// Hook loads against bit depth while tripping (the broomstick plot): for each friction factor
/// in `mus` and each bit depth in `depths` (each within `(0, string length]`), the pick-up,
/// slack-off and rotating hook loads, N, and the rotating surface torque, N m, as `[mu][depth]`
/// rows of `(pickup, slackoff, rotating, torque)`.
pub fn broomstick(traj: &Trajectory, setup: &Setup, depths: &[f64], mus: &[f64]) -> Result<Vec<Vec<[f64; 4]>>> {
    setup.validate_string()?;
    let length = setup.depth();
    for (j, &d) in depths.iter().enumerate() {
        if !(d.is_finite() && d > 0.0 && d <= length) {
            return Err(Error::invalid(
                format!("depths[{j}]"),
                Num(d),
                format!("a bit depth in (0, {}] m", Num(length)),
            ));
        }
    }
    for (j, &m) in mus.iter().enumerate() {
        if !(m.is_finite() && (0.0..=10.0).contains(&m)) {
            return Err(Error::invalid(format!("friction_factors[{j}]"), Num(m), "a friction factor in [0, 10]"));
        }
    }
    let mut rows = vec![vec![[0.0; 4]; depths.len()]; mus.len()];
    for (k, &d) in depths.iter().enumerate() {
        // the elements at this bit depth, shared by every friction factor's lines
        let el = setup.elements(traj, d);
        for (row, &mu) in rows.iter_mut().zip(mus) {
            let solve = |op| setup.profile_on(traj, &el, op, ProfileMethod::Stepwise, Some(mu), (0.0, 0.0));
            let rotating = solve(Operation::RotatingOffBottom);
            row[k] = [
                solve(Operation::PickUp).surface_tension() + setup.block_weight,
                solve(Operation::SlackOff).surface_tension() + setup.block_weight,
                rotating.surface_tension() + setup.block_weight,
                rotating.surface_torque(),
            ];
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::well::{Survey, Trajectory};

    fn traj(md: &[f64], inc: &[f64], azi: &[f64]) -> Trajectory {
        Trajectory::new(Survey::from_degrees("well", md, inc, azi).unwrap())
    }

    fn setup(length: f64, weight: f64, mu: f64) -> Setup {
        Setup {
            pieces: vec![Piece::new(length, weight, 0.1)],
            friction: SlidingFriction::uniform(mu),
            weight_on_bit: 0.0,
            bit_torque: 0.0,
            block_weight: 0.0,
            step: 1.0,
            hole: None,
            pressure_gradient: 0.0,
        }
    }

    /// A straight inclined hole: `T = w L (cos i +- mu sin i)`, `M = mu r w L sin i`.
    #[test]
    fn straight_inclined_section() {
        let (l, w, mu, inc) = (2000.0, 300.0, 0.25, 40f64);
        let t = traj(&[0.0, l], &[inc, inc], &[10.0, 10.0]);
        let s = setup(l, w, mu);
        let i = inc.to_radians();
        for scheme in [ProfileMethod::Stepwise, ProfileMethod::Continuous] {
            let td = analyse(&t, &s, scheme).unwrap();
            let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
            assert!(rel(td.hook_load_pickup_n, w * l * (i.cos() + mu * i.sin())) < 1e-12);
            assert!(rel(td.hook_load_slackoff_n, w * l * (i.cos() - mu * i.sin())) < 1e-12);
            assert!(rel(td.hook_load_rotating_n, w * l * i.cos()) < 1e-12);
            assert!(rel(td.surface_torque_off_bottom_nm, mu * 0.1 * w * l * i.sin()) < 1e-12);
            assert!(rel(td.max_normal_force_n_per_m, w * i.sin()) < 1e-12);
        }
    }

    /// A weightless string around an arc of angle beta with a pull at its end: the capstan
    /// `T2 = T1 exp(mu beta)` picking up, `T1 exp(-mu beta)` slacking off; the stepped form
    /// converges at first order, the continuous one at fourth.
    #[test]
    fn capstan_on_a_weightless_arc() {
        let (r, beta_deg, mu, pull) = (300.0, 90f64, 0.3, 1e5);
        let beta = beta_deg.to_radians();
        let l = r * beta;
        let t = traj(&[0.0, l], &[90.0, 90.0], &[0.0, beta_deg]);
        let err = |scheme, step: f64, op: Operation| {
            let mut s = setup(l, 0.0, mu);
            s.step = step;
            let p = s.profile(&t, op, scheme, l, None, (pull, 0.0));
            let exact = pull * (op.drag_sign() * mu * beta).exp();
            (p.surface_tension() - exact).abs() / exact
        };
        for op in [Operation::PickUp, Operation::SlackOff] {
            let (e1, e2) = (err(ProfileMethod::Stepwise, 10.0, op), err(ProfileMethod::Stepwise, 5.0, op));
            let order = (e1 / e2).log2();
            assert!((order - 1.0).abs() < 0.1, "stepwise order {order} ({e1}, {e2})");
            let (c1, c2) = (err(ProfileMethod::Continuous, 40.0, op), err(ProfileMethod::Continuous, 20.0, op));
            let order = (c1 / c2).log2();
            assert!(c1 < 1e-6 && (order - 4.0).abs() < 0.3, "continuous order {order} ({c1}, {c2})");
        }
    }

    /// In a vertical build the tension pulls the string to the high side and the weight to
    /// the low side: the normal force is their difference, `|T / R - w sin i|`, in a drop
    /// their sum.
    #[test]
    fn tension_and_weight_oppose_in_a_build_and_add_in_a_drop() {
        let (r, w) = (1000.0, 200.0);
        let l = r * 30f64.to_radians();
        let build = traj(&[0.0, 100.0, 100.0 + l, 3000.0], &[0.0, 0.0, 30.0, 30.0], &[0.0; 4]);
        let drop = traj(&[0.0, 100.0, 100.0 + l, 3000.0], &[60.0, 60.0, 30.0, 30.0], &[0.0; 4]);
        let s = setup(3000.0, w, 0.0);
        for (t, sign) in [(&build, -1.0), (&drop, 1.0)] {
            let p = s.solve(t, Operation::RotatingOffBottom, ProfileMethod::Continuous);
            let k = p.md.iter().position(|&d| d >= 100.0 + l / 2.0).unwrap();
            let q = t.at(p.md[k]);
            let expect = (p.tension[k] / r + sign * w * q.inc.sin()).abs();
            assert!((p.normal_force[k] - expect).abs() / expect < 1e-2, "{} vs {expect}", p.normal_force[k]);
        }
    }

    /// The stepped model converges to the continuous one at first order on a 3-D well.
    #[test]
    fn stepwise_converges_to_continuous() {
        let t = traj(
            &[0.0, 400.0, 1200.0, 2000.0, 2600.0, 4000.0],
            &[0.0, 0.0, 45.0, 45.0, 20.0, 20.0],
            &[0.0, 0.0, 30.0, 80.0, 120.0, 120.0],
        );
        let mut s = setup(4000.0, 250.0, 0.3);
        s.pieces = vec![Piece::new(3700.0, 250.0, 0.08), Piece::new(300.0, 1200.0, 0.1)];
        s.weight_on_bit = 1e5;
        s.bit_torque = 5e3;
        s.step = 0.25;
        let fine = s.solve(&t, Operation::PickUp, ProfileMethod::Continuous).surface_tension();
        let mut errs = Vec::new();
        for step in [20.0, 10.0] {
            s.step = step;
            errs.push((s.solve(&t, Operation::PickUp, ProfileMethod::Stepwise).surface_tension() - fine).abs() / fine);
        }
        let order = (errs[0] / errs[1]).log2();
        assert!((order - 1.0).abs() < 0.2, "order {order} {errs:?}");
    }

    #[test]
    fn friction_intervals_and_short_surveys() {
        let t = traj(&[0.0, 1000.0], &[50.0, 50.0], &[0.0, 0.0]);
        let mut s = setup(1000.0, 100.0, 0.2);
        s.friction.intervals.push(SlidingInterval { top_md: 0.0, bottom_md: 600.0, mu: 0.1 });
        let td = analyse(&t, &s, ProfileMethod::Stepwise).unwrap();
        let sin = 50f64.to_radians().sin();
        let expect = 0.1 * 100.0 * sin * (0.1 * 600.0 + 0.2 * 400.0);
        assert!((td.surface_torque_off_bottom_nm - expect).abs() / expect < 1e-12);
        s.pieces[0].length = 1200.0;
        assert_eq!(analyse(&t, &s, ProfileMethod::Stepwise).unwrap_err().field(), "well.survey");
    }

    #[test]
    fn broomstick_hook_loads_bracket_the_rotating_one() {
        let t = traj(&[0.0, 500.0, 1500.0, 3000.0], &[0.0, 0.0, 60.0, 60.0], &[0.0; 4]);
        let s = setup(3000.0, 300.0, 0.25);
        let depths: Vec<f64> = (1..=30).map(|k| k as f64 * 100.0).collect();
        let b = broomstick(&t, &s, &depths, &[0.0, 0.2, 0.4]).unwrap();
        for row in &b[0] {
            assert!((row[0] - row[2]).abs() < 1e-9 && (row[1] - row[2]).abs() < 1e-9);
        }
        for (lo, hi) in b[1].iter().zip(&b[2]) {
            assert!(hi[0] >= lo[0] && hi[1] <= lo[1] && lo[1] <= lo[2] && lo[2] <= lo[0]);
        }
        // vertical part: no drag at any friction
        assert!((b[2][3][0] - 300.0 * 400.0).abs() < 1e-6);
    }
}

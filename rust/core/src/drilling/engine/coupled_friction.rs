//! The coupled wall friction of a coupled run (`friction.coupling = "axial_torsional"`): the
//! wall's Coulomb friction against the contact's sliding velocity `(v, r omega)` (the axial
//! speed and the contact radius times the angular speed), shared by the axial and the
//! torsional field, with one stick phase. A rotating string slides axially with little drag.
//!
//! The normal force per length follows the string's live axial force: the soft-string contact
//! `N = |T kappa + w (e_z - (e_z . t) t)|` ([`crate::well::torque_drag::normal_force`], the
//! equation of the torque-and-drag module) with `T` the tension of the segment's axial cell in
//! the step (the negative of its compression), `kappa` the curvature vector and `t` the
//! direction of the trajectory at the segment, `w` the buoyed weight per length; with
//! `friction.contact = "weight"` the buoyed weight times the sine of the inclination alone
//! (`kappa` taken as 0). The static factor `mu_s` of `friction.static` (or its interval) limits
//! the friction force `f = (f_a, f_t)` (axial, tangential at the contact) to `|f| <= mu_s N`.
//!
//! The law, [`slide`] (the one place of the convention), is the implicit (Moreau) Coulomb step
//! on the speeds after the transport and the other sources, `u = (v, r omega)`, `v` the axial
//! speed at the middle of the step's gravity kick (the stored speed less half of it,
//! [`super::axial_field::Axial::half_kick`]: the speed the string moves at, so that gravity and
//! friction enter the step together and a slow direction never flips however large the kick):
//!
//! * stick, decided by the step's impulse balance and by no speed threshold: if the force that
//!   stops both speeds in the step, `-(rho A v, rho J omega / r) / dt`, is within `mu_s N`, both
//!   stop exactly (the loads kept; the axial cell at rest is the speed at the middle of the
//!   kick at 0);
//! * else sliding: the kinetic force `mu_k N` (`mu_k = kinetic_ratio mu_s`) against `u`,
//!   `f = -mu_k N u / |u|`, its axial part `-mu_k N v / |u|` and its torque per length
//!   `-mu_k N r (r omega) / |u|`; a component that would reverse its speed in the step stops
//!   instead (exactly, the load kept);
//! * `regularised`: `f = -mu_k N tanh(s / v_r) u / |u|` (`s = |u| / r`), no stick, a component
//!   never reversed.
//!
//! The changes of speed over a step are `dt f_a / (rho A)` and `dt r f_t / (rho J)`: with the
//! static-limit changes `la = dt mu_s N / (rho A)` and `lt = dt mu_s N r / (rho J)` the law
//! needs no other property. Without axial speed the sliding branch is the torsional law's
//! (`-mu_k N r sign omega` per length). `friction.stick_speed` is the torsional wall friction's
//! threshold ([`super::sources`], the published scheme's); the coupled law has none.
//!
//! The two fields have their own cells (the axial cells are longer: the axial wave is faster
//! on the common time step). The friction acts on the overlay of both grids: each segment
//! (the intersection of a torsional and an axial cell, length `l`) slides at its torsional
//! cell's angular speed and its axial cell's axial speed with the normal force at its
//! torsional cell's centre; a cell's change is the length-weighted mean of its segments'
//! changes (`l / h`), and a cell sticks (set exactly to rest) when all its segments stick.
//!
//! Energy: on the torsional field the friction's work is the kinetic energy it takes,
//! `m h d (w + d / 2)` per cell (`d` the change). On the axial field the buoyed weight's kick
//! `g dt` and the friction's change `d` follow each other within the step: both are booked at
//! the mean speed of that part of the step, `v_m = (v* + v') / 2` (`v*` the speed after the
//! transport, before the kick, `v'` after the friction): the friction's work `m h d v_m`, the
//! weight's `m h g dt v_m` (the kick's own work at the middle of the kick,
//! [`super::axial_field::Axial`]'s `advance`, corrected here by `m h d g dt / 2`). Their sum is the
//! kinetic energy the two changes make, exactly, so the split leaves nothing to the numerical
//! loss, and in a steady slide (where `v_m` is the speed the string moves at: the transport
//! takes away what the sources add) it books `mu_k N v` per length and the weight's `w v cos i`
//! on any grid.
//!
//! The Coulomb law runs over all touching segments at once ([`slide_coulomb`], the branches of
//! [`slide`] as selects, under [`crate::simd::dispatch`]): the same operations, so the same
//! bits as [`slide`] segment by segment (a test holds them equal). Segments without contact
//! force anywhere (a straight vertical stretch) change nothing and count as moving: they are
//! left out of the pass and counted once.

use crate::drilling::config::{Contact, DrillConfig, FrictionModel};
use crate::drilling::grid::Grid;
use crate::drilling::well;
use crate::error::Result;
use crate::well::torque_drag::normal_force;

use super::field::Field;

/// The least normal force per length a touching segment keeps, N/m (a force of exactly 0 would
/// make the static limit's inverse infinite).
const LEAST_NORMAL_FORCE: f64 = 1e-200;

/// The constants of [`slide`].
#[derive(Debug, Clone, Copy)]
pub struct Law {
    /// `friction.kinetic_ratio`.
    pub kinetic_ratio: f64,
    /// `Some(1 / v_r)` for the regularised law.
    pub inv_regularisation: Option<f64>,
}

impl Law {
    pub fn new(cfg: &DrillConfig) -> Self {
        let fr = &cfg.friction;
        Law {
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
pub struct ContactStep {
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

impl ContactStep {
    pub fn new(radius: f64, la: f64, lt: f64, law: &Law) -> Self {
        let (inv_la, inv_lt, kla, klt, touching) = limits(la, lt, law.kinetic_ratio);
        ContactStep { inv_radius: 1.0 / radius, la, lt, inv_la, inv_lt, kla, klt, touching }
    }
}

/// A contact's static-limit changes `la`, `lt` as [`ContactStep`] keeps them: their inverses
/// (0 where the wall does not hold it), their kinetic parts (`kinetic_ratio` times them) and
/// whether it touches (`la, lt > 0`).
#[inline(always)]
fn limits(la: f64, lt: f64, kinetic_ratio: f64) -> (f64, f64, f64, f64, bool) {
    let touching = la > 0.0 && lt > 0.0;
    let inv_la = if touching { 1.0 / la } else { 0.0 };
    let inv_lt = if touching { 1.0 / lt } else { 0.0 };
    (inv_la, inv_lt, kinetic_ratio * la, kinetic_ratio * lt, touching)
}

/// The coupled wall friction of a contact `c` moving at the axial speed `v` and the angular
/// speed `w` (after the step's transport and other sources): see the module.
#[inline]
pub fn slide(v: f64, w: f64, c: &ContactStep, law: &Law) -> Slide {
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
    // The stop force over the static limit: stick when it is at most 1 (`sqrt(x) <= 1` exactly
    // when `x <= 1 + 2^-52`).
    let (qa, qt) = (v * c.inv_la, w * c.inv_lt);
    if qa * qa + qt * qt <= 1.0 + f64::EPSILON {
        return Slide { dv: -v, dw: -w, stuck_axial: true, stuck_torsional: true };
    }
    // The direction cosines by division (without axial speed `w / s` is exactly +-1: the
    // torsional law's kinetic change, bit for bit).
    let (dv, stuck_axial) = clip(-c.kla * (vr / s), v);
    let (dw, stuck_torsional) = clip(-c.klt * (w / s), w);
    Slide { dv, dw, stuck_axial, stuck_torsional }
}

/// [`slide`] of a touching contact (`inv_radius`, `inv_la`, `inv_lt`, `kla`, `klt` of its
/// [`ContactStep`]) under the Coulomb law (not `regularised`), written without branches (the
/// branches computed and one selected) so that a loop over contacts vectorises, with the same
/// operations as [`slide`]'s: the same bits. Returns `(dv, dw, stuck_axial, stuck_torsional)`.
#[inline(always)]
fn slide_coulomb(v: f64, w: f64, [inv_radius, inv_la, inv_lt, kla, klt]: [f64; 5]) -> (f64, f64, bool, bool) {
    let vr = v * inv_radius;
    let s = (vr * vr + w * w).sqrt();
    let (qa, qt) = (v * inv_la, w * inv_lt);
    let stick = qa * qa + qt * qt <= 1.0 + f64::EPSILON;
    // sliding: the kinetic force against the sliding velocity, a reversal clipped
    let (ka, kt) = (-kla * (vr / s), -klt * (w / s));
    let (clip_a, clip_t) = (ka.abs() >= v.abs(), kt.abs() >= w.abs());
    let dv_kinetic = if clip_a { -v } else { ka };
    let dw_kinetic = if clip_t { -w } else { kt };
    if stick {
        (-v, -w, true, true)
    } else {
        (dv_kinetic, dw_kinetic, clip_a, clip_t)
    }
}

/// The touching segments' contacts and weights, a vector per constant (the operands of
/// [`SlideMany`]), and the constants their static limits are made of each step.
#[derive(Debug, Clone, Default)]
struct ContactSteps {
    inv_radius: Vec<f64>,
    inv_la: Vec<f64>,
    inv_lt: Vec<f64>,
    kla: Vec<f64>,
    klt: Vec<f64>,
    wt: Vec<f64>,
    wa: Vec<f64>,
}

impl ContactSteps {
    fn new(segments: &[Segment]) -> Self {
        let mut out = ContactSteps::default();
        for g in segments {
            let c = &g.contact;
            out.inv_radius.push(c.inv_radius);
            out.inv_la.push(c.inv_la);
            out.inv_lt.push(c.inv_lt);
            out.kla.push(c.kla);
            out.klt.push(c.klt);
            out.wt.push(g.wt);
            out.wa.push(g.wa);
        }
        out
    }

    fn len(&self) -> usize {
        self.inv_radius.len()
    }
}

/// [`slide_coulomb`] of every contact `i` of `contacts` at the speeds `v[i]`, `w[i]`: its
/// changes weighted by its shares of its cells, `pt[i] = wt[i] dw`, `pa[i] = wa[i] dv`, and
/// whether it moves (1, or 0 stuck) in each field, `free_t[i]`, `free_a[i]`.
struct SlideMany<'a> {
    contacts: &'a ContactSteps,
    v: &'a [f64],
    w: &'a [f64],
    out: &'a mut Shares,
}

impl crate::simd::Kernel for SlideMany<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) {
        let c = self.contacts;
        let n = c.len();
        let (ir, ia, it, ka, kt) = (&c.inv_radius[..n], &c.inv_la[..n], &c.inv_lt[..n], &c.kla[..n], &c.klt[..n]);
        let (wt, wa) = (&c.wt[..n], &c.wa[..n]);
        let (v, w) = (&self.v[..n], &self.w[..n]);
        let o = self.out;
        let (pt, pa, ft, fa) = (&mut o.pt[..n], &mut o.pa[..n], &mut o.free_t[..n], &mut o.free_a[..n]);
        for i in 0..n {
            let (dv, dw, stuck_a, stuck_t) = slide_coulomb(v[i], w[i], [ir[i], ia[i], it[i], ka[i], kt[i]]);
            pt[i] = wt[i] * dw;
            pa[i] = wa[i] * dv;
            ft[i] = if stuck_t { 0.0 } else { 1.0 };
            fa[i] = if stuck_a { 0.0 } else { 1.0 };
        }
    }
}

/// The touching segments' cells and contact geometry, a vector per component (the operands of
/// [`Contacts`]).
#[derive(Debug, Clone, Default)]
struct Overlay {
    /// The segments' axial and torsional cells (padded indices).
    axial: Vec<u32>,
    torsional: Vec<u32>,
    /// [`Geometry`]'s `kappa`, `wz` (by component), `ca` and `ct`.
    kappa: [Vec<f64>; 3],
    wz: [Vec<f64>; 3],
    ca: Vec<f64>,
    ct: Vec<f64>,
}

impl Overlay {
    fn new(segments: &[Segment]) -> Self {
        let mut out = Overlay::default();
        for g in segments {
            out.axial.push(g.axial as u32);
            out.torsional.push(g.torsional as u32);
            for d in 0..3 {
                out.kappa[d].push(g.geometry.kappa[d]);
                out.wz[d].push(g.geometry.wz[d]);
            }
            out.ca.push(g.geometry.ca);
            out.ct.push(g.geometry.ct);
        }
        out
    }
}

/// The axial cells' speeds at the middle of the gravity kick, `v[k] = speed[k] - half_kick[k]`,
/// and tensions `tension[k] = -half_impedance[k] (alpha[k] - beta[k])`, per padded index.
struct AxialCells<'a> {
    speed: &'a [f64],
    half_kick: &'a [f64],
    half_impedance: &'a [f64],
    alpha: &'a [f64],
    beta: &'a [f64],
    v: &'a mut [f64],
    tension: &'a mut [f64],
}

impl crate::simd::Kernel for AxialCells<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) {
        let n = self.speed.len();
        let (speed, kick, imp) = (&self.speed[..n], &self.half_kick[..n], &self.half_impedance[..n]);
        let (alpha, beta, v, tension) = (&self.alpha[..n], &self.beta[..n], &mut self.v[..n], &mut self.tension[..n]);
        for k in 0..n {
            v[k] = speed[k] - kick[k];
            tension[k] = -imp[k] * (alpha[k] - beta[k]);
        }
    }
}

/// Each touching segment's speeds of the step (`v` of its axial cell from [`AxialCells`], `w`
/// of its torsional cell) and its contact at its axial cell's tension: the normal force
/// ([`Geometry::normal_force`]) and the static limits' inverses and kinetic parts of
/// [`ContactStep::new`] into `out`, the same operations, so the same bits.
struct Contacts<'a> {
    overlay: &'a Overlay,
    kinetic_ratio: f64,
    v_cell: &'a [f64],
    tension_cell: &'a [f64],
    speed_t: &'a [f64],
    v: &'a mut [f64],
    w: &'a mut [f64],
    /// Scratch: the segments' tensions.
    tension: &'a mut [f64],
    out: &'a mut ContactSteps,
}

impl crate::simd::Kernel for Contacts<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) {
        let g = self.overlay;
        let n = g.axial.len();
        let (ax, tor, ca, ct) = (&g.axial[..n], &g.torsional[..n], &g.ca[..n], &g.ct[..n]);
        let [k0, k1, k2] = [&g.kappa[0][..n], &g.kappa[1][..n], &g.kappa[2][..n]];
        let [z0, z1, z2] = [&g.wz[0][..n], &g.wz[1][..n], &g.wz[2][..n]];
        let (v, w, tension) = (&mut self.v[..n], &mut self.w[..n], &mut self.tension[..n]);
        let (v_cell, tension_cell, speed_t) = (self.v_cell, self.tension_cell, self.speed_t);
        // The cells' values gathered first (loads only), then the contacts' arithmetic over
        // contiguous vectors (a loop with gathers in it is left scalar).
        for i in 0..n {
            let (ka, kt) = (ax[i] as usize, tor[i] as usize);
            v[i] = v_cell[ka];
            w[i] = speed_t[kt];
            tension[i] = tension_cell[ka];
        }
        let o = &mut *self.out;
        let (inv_la, inv_lt, kla, klt) = (&mut o.inv_la[..n], &mut o.inv_lt[..n], &mut o.kla[..n], &mut o.klt[..n]);
        let kr = self.kinetic_ratio;
        for i in 0..n {
            let nf = contact_force(tension[i], [k0[i], k1[i], k2[i]], [z0[i], z1[i], z2[i]]);
            (inv_la[i], inv_lt[i], kla[i], klt[i], _) = limits(ca[i] * nf, ct[i] * nf, kr);
        }
    }
}

/// Where a segment's normal force comes from: `N = |T kappa + wz|` with the tension `T` of its
/// axial cell, and its static-limit changes per newton of it, `la = ca N`, `lt = ct N`.
#[derive(Debug, Clone, Copy, Default)]
struct Geometry {
    /// The trajectory's curvature vector at the segment, 1/m (0 with `friction.contact = "weight"`).
    kappa: [f64; 3],
    /// The buoyed weight per length times the part of the vertical across the hole, N/m.
    wz: [f64; 3],
    /// `dt mu_s / (rho A)` and `dt mu_s r / (rho J)`.
    ca: f64,
    ct: f64,
    radius: f64,
}

impl Geometry {
    /// The normal force per length at the tension `tension`, N/m (at least
    /// [`LEAST_NORMAL_FORCE`]).
    #[inline(always)]
    fn normal_force(&self, tension: f64) -> f64 {
        contact_force(tension, self.kappa, self.wz)
    }
}

/// The normal force per length of a contact at the tension `tension` ([`normal_force`]), at
/// least [`LEAST_NORMAL_FORCE`], N/m.
#[inline(always)]
fn contact_force(tension: f64, kappa: [f64; 3], wz: [f64; 3]) -> f64 {
    normal_force(tension, kappa, wz).max(LEAST_NORMAL_FORCE)
}

/// A segment of the overlay of the two grids (padded indices, weights `l / h`, the contact at
/// the initial state and its geometry).
#[derive(Debug, Clone, Copy)]
struct Segment {
    torsional: usize,
    axial: usize,
    wt: f64,
    wa: f64,
    contact: ContactStep,
    geometry: Geometry,
}

/// The touching segments' contributions of a step to their cells, one more element at the end
/// that adds nothing (`0`: the empty slots of [`Slots`] point to it).
#[derive(Debug, Clone, Default)]
struct Shares {
    /// Weighted changes of the angular and the axial speed.
    pt: Vec<f64>,
    pa: Vec<f64>,
    /// 1 where the segment moves (not stuck), torsionally and axially.
    free_t: Vec<f64>,
    free_a: Vec<f64>,
}

impl Shares {
    fn new(n: usize) -> Self {
        Shares { pt: vec![0.0; n + 1], pa: vec![0.0; n + 1], free_t: vec![0.0; n + 1], free_a: vec![0.0; n + 1] }
    }

    /// Segment `i`'s (`g`) contributions from its friction `f`.
    fn set(&mut self, i: usize, g: &Segment, f: Slide) {
        self.pt[i] = g.wt * f.dw;
        self.pa[i] = g.wa * f.dv;
        self.free_t[i] = if f.stuck_torsional { 0.0 } else { 1.0 };
        self.free_a[i] = if f.stuck_axial { 0.0 } else { 1.0 };
    }
}

/// A field's cells' segments: `slot[s][k]`, the `s`-th touching segment of the cell at padded
/// index `k` in the segments' order (the empty element of [`Shares`] where the cell has fewer),
/// and `untouched[k]`, its segments without contact force (they change nothing and never stick).
#[derive(Debug, Clone)]
struct Slots {
    slot: Vec<Vec<u32>>,
    untouched: Vec<f64>,
}

impl Slots {
    /// The slots of a field of `len` padded cells with the touching segments' cells `cells`
    /// (in order) and the untouched segments' cells `untouched`.
    fn new(len: usize, cells: &[usize], untouched: impl Iterator<Item = usize>) -> Self {
        let empty = cells.len() as u32;
        let mut count = vec![0usize; len];
        let mut slot: Vec<Vec<u32>> = Vec::new();
        for (i, &k) in cells.iter().enumerate() {
            if count[k] == slot.len() {
                slot.push(vec![empty; len]);
            }
            slot[count[k]][k] = i as u32;
            count[k] += 1;
        }
        let mut free = vec![0.0; len];
        for k in untouched {
            free[k] += 1.0;
        }
        Slots { slot, untouched: free }
    }
}

/// The work of the coupled friction over a step, J: on the torsional and the axial field (both
/// negative or 0), the correction of the buoyed weight's work to the mean speed of the step's
/// sources, and what the kinetic energy differs from the two by (rounding; see the module).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FrictionWork {
    pub torsional: f64,
    pub axial: f64,
    pub gravity: f64,
    pub numerical: f64,
}

/// The coupled wall friction of a run: the overlay's segments and the law.
#[derive(Clone)]
pub struct CoupledFriction {
    /// The segments with contact force (the others are counted in [`Slots::untouched`]).
    segments: Vec<Segment>,
    /// Their contacts, for the vector pass, and their cells and geometry, for [`Contacts`].
    contacts: ContactSteps,
    overlay: Overlay,
    law: Law,
    /// The step's speeds at the segments and their contributions to their cells.
    v: Vec<f64>,
    w: Vec<f64>,
    tension: Vec<f64>,
    shares: Shares,
    /// The cells' segments, torsional and axial.
    torsional: Slots,
    axial: Slots,
    /// The fields' speeds before the friction (padded), and scratch of the cell pass.
    speed_t: Vec<f64>,
    speed_a: Vec<f64>,
    scratch: CellScratch,
    /// The axial cells' speeds at the middle of the kick and tensions ([`AxialCells`]).
    v_cell: Vec<f64>,
    tension_cell: Vec<f64>,
    /// Half the axial field's gravity kick per padded index (0 at ghosts), m/s, and half its
    /// impedance (`F = Z (alpha - beta) / 2`), N s/m.
    half_kick: Vec<f64>,
    half_impedance: Vec<f64>,
    /// The axial cells' masses `rho A h` per padded index (0 at ghosts), kg.
    mass_a: Vec<f64>,
    /// The last segment's contact geometry and `mu_s h / 2` of the last axial cell, for
    /// [`CoupledFriction::end_hold`].
    last: Option<(Geometry, f64)>,
    /// The static limit of the friction on the last half axial cell at the last step, N.
    end_hold: f64,
}

/// Two face positions closer than this fraction of a cell are the same face.
const SAME_FACE: f64 = 1e-9;

impl CoupledFriction {
    /// The overlay of the torsional `field` (of `grid`) and the axial field `axial` (with the
    /// half gravity kicks `half_kick` per padded index); None when the wall has no friction
    /// anywhere.
    pub fn new(
        cfg: &DrillConfig,
        grid: &Grid,
        torsion: &Field,
        axial: &Field,
        half_kick: &[f64],
    ) -> Result<Option<Self>> {
        let law = Law::new(cfg);
        let traj = well::trajectory(cfg)?;
        let gravity = cfg.well.gravity;
        let mut segments = Vec::new();
        let mut cell = 0;
        let mut last = None;
        for (s, (st, sa)) in torsion.sections.iter().zip(&axial.sections).enumerate() {
            let p = &grid.props[s];
            let length = grid.spacing[s] * st.cells as f64;
            let (ht, ha) = (length / st.cells as f64, length / sa.cells as f64);
            let w = p.buoyed_mass_per_length * gravity;
            let (mut i, mut j, mut pos) = (0, 0, 0.0);
            while i < st.cells && j < sa.cells {
                let (et, ea) = ((i + 1) as f64 * ht, (j + 1) as f64 * ha);
                let end = if i + 1 == st.cells && j + 1 == sa.cells { length } else { et.min(ea) };
                let kt = st.offset + 1 + i;
                let zc = grid.z[cell];
                let mu = well::friction_factor(cfg, zc);
                let q = traj.at(zc);
                let t = q.tangent;
                let kappa = match cfg.friction.contact {
                    Contact::SoftString => traj.curvature_vector_on(zc, traj.interval(zc)),
                    Contact::Weight => [0.0; 3],
                };
                let wz = [-w * t[2] * t[0], -w * t[2] * t[1], w * (1.0 - t[2] * t[2])];
                let geometry = Geometry {
                    kappa,
                    wz,
                    ca: grid.dt * mu / sa.inertia_per_length,
                    ct: grid.dt * mu * p.contact_radius / p.inertia_per_length,
                    radius: p.contact_radius,
                };
                let touches = mu > 0.0 && kappa.iter().chain(&wz).any(|&x| x != 0.0);
                let ja = sa.offset + 1 + j;
                // the static limit at the initial state's tension
                let contact = if touches {
                    let tension = -0.5 * sa.impedance * (axial.alpha[ja] - axial.beta[ja]);
                    let n = geometry.normal_force(tension);
                    ContactStep::new(p.contact_radius, geometry.ca * n, geometry.ct * n, &law)
                } else {
                    ContactStep::new(p.contact_radius, 0.0, 0.0, &law)
                };
                if end > pos {
                    let l = end - pos;
                    segments.push(Segment { torsional: kt, axial: ja, wt: l / ht, wa: l / ha, contact, geometry });
                }
                pos = end;
                last = Some((geometry, 0.5 * mu * ha));
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
            return Ok(None);
        }
        let (lt, la) = (torsion.padded_len(), axial.padded_len());
        let idle = |axial: bool| {
            segments.iter().filter(|g| !g.contact.touching).map(move |g| if axial { g.axial } else { g.torsional })
        };
        let (idle_t, idle_a): (Vec<usize>, Vec<usize>) = (idle(false).collect(), idle(true).collect());
        segments.retain(|g| g.contact.touching);
        let n = segments.len();
        let cells_t: Vec<usize> = segments.iter().map(|g| g.torsional).collect();
        let cells_a: Vec<usize> = segments.iter().map(|g| g.axial).collect();
        let (mut half_impedance, mut mass_a) = (vec![0.0; la], vec![0.0; la]);
        for sa in &axial.sections {
            for k in sa.offset + 1..=sa.offset + sa.cells {
                half_impedance[k] = 0.5 * sa.impedance;
                mass_a[k] = sa.inertia_per_length * sa.h;
            }
        }
        let mut cf = CoupledFriction {
            contacts: ContactSteps::new(&segments),
            overlay: Overlay::new(&segments),
            torsional: Slots::new(lt, &cells_t, idle_t.into_iter()),
            axial: Slots::new(la, &cells_a, idle_a.into_iter()),
            segments,
            law,
            v: vec![0.0; n],
            w: vec![0.0; n],
            tension: vec![0.0; n],
            shares: Shares::new(n),
            speed_t: vec![0.0; lt],
            speed_a: vec![0.0; la],
            scratch: CellScratch::new(lt.max(la)),
            v_cell: vec![0.0; la],
            tension_cell: vec![0.0; la],
            half_kick: half_kick.to_vec(),
            half_impedance,
            mass_a,
            last,
            end_hold: 0.0,
        };
        cf.end_hold = cf.hold_at(axial);
        Ok(Some(cf))
    }

    /// The static limit of the wall friction on the half of the last axial cell below its
    /// centre (`mu_s N h / 2` at the last cell's tension), N: it holds the free end of a stuck
    /// string at rest ([`super::axial_field::Axial::end_hold`]).
    pub fn end_hold(&self) -> f64 {
        self.end_hold
    }

    fn hold_at(&self, axial: &Field) -> f64 {
        let Some((geometry, mu_h)) = self.last else { return 0.0 };
        let sa = axial.last();
        let k = sa.offset + sa.cells;
        let tension = -self.half_impedance[k] * (axial.alpha[k] - axial.beta[k]);
        if geometry.ca > 0.0 {
            mu_h * geometry.normal_force(tension)
        } else {
            0.0
        }
    }

    /// The touching segments' speeds and contacts of the step (the Coulomb law's operands in
    /// `v`, `w` and `contacts`) from the fields' speeds `speed_t`, `speed_a` and the axial
    /// field's tensions.
    fn contacts(&mut self, axial: &Field) {
        crate::simd::dispatch(AxialCells {
            speed: &self.speed_a,
            half_kick: &self.half_kick,
            half_impedance: &self.half_impedance,
            alpha: &axial.alpha,
            beta: &axial.beta,
            v: &mut self.v_cell,
            tension: &mut self.tension_cell,
        });
        crate::simd::dispatch(Contacts {
            overlay: &self.overlay,
            kinetic_ratio: self.law.kinetic_ratio,
            v_cell: &self.v_cell,
            tension_cell: &self.tension_cell,
            speed_t: &self.speed_t,
            v: &mut self.v,
            w: &mut self.w,
            tension: &mut self.tension,
            out: &mut self.contacts,
        });
    }

    /// The friction over a step on the fields' current speeds, with the normal forces of the
    /// axial field's current tensions; returns its work (see [`FrictionWork`]).
    pub fn apply(&mut self, torsion: &mut Field, axial: &mut Field) -> FrictionWork {
        torsion.speeds(&mut self.speed_t);
        axial.speeds(&mut self.speed_a);
        if self.law.inv_regularisation.is_some() {
            let sh = &mut self.shares;
            for (i, g) in self.segments.iter().enumerate() {
                let k = g.axial;
                let v = self.speed_a[k] - self.half_kick[k];
                let tension = -self.half_impedance[k] * (axial.alpha[k] - axial.beta[k]);
                let n = g.geometry.normal_force(tension);
                let contact = ContactStep::new(g.geometry.radius, g.geometry.ca * n, g.geometry.ct * n, &self.law);
                sh.set(i, g, slide(v, self.speed_t[g.torsional], &contact, &self.law));
            }
        } else {
            self.contacts(axial);
            crate::simd::dispatch(SlideMany {
                contacts: &self.contacts,
                v: &self.v,
                w: &self.w,
                out: &mut self.shares,
            });
        }
        let sh = &self.shares;
        let torsional =
            apply_cells(torsion, &self.speed_t, &self.torsional, &sh.pt, &sh.free_t, None, &mut self.scratch);
        let kinetic = apply_cells(
            axial,
            &self.speed_a,
            &self.axial,
            &sh.pa,
            &sh.free_a,
            Some(&self.half_kick),
            &mut self.scratch,
        );
        // The friction's and the weight's work at the mean speed of the sources' part of the
        // step (see the module); what is left is rounding.
        let (mut work, mut gravity) = (0.0, 0.0);
        for k in 0..self.mass_a.len() {
            let m = self.mass_a[k];
            if m == 0.0 {
                continue;
            }
            let after = 0.5 * (axial.alpha[k] + axial.beta[k]);
            let d = after - self.speed_a[k];
            let s = self.half_kick[k];
            work += m * d * (after - s - 0.5 * d);
            gravity += m * d * s;
        }
        self.end_hold = self.hold_at(axial);
        FrictionWork { torsional, axial: work, gravity, numerical: work + gravity - kinetic }
    }
}

/// The scratch of [`apply_cells`]: each cell's change, moving segments and work.
#[derive(Debug, Clone)]
struct CellScratch {
    change: Vec<f64>,
    moving: Vec<f64>,
    work: Vec<f64>,
}

impl CellScratch {
    fn new(len: usize) -> Self {
        CellScratch { change: vec![0.0; len], moving: vec![0.0; len], work: vec![0.0; len] }
    }
}

/// The cells' changes applied to `field` (speeds `speed` before the friction): a cell's change
/// is the sum of its segments' shares `p` (from 0, in the segments' order), a cell whose
/// segments all stuck (none `free`, none untouched) is set exactly to rest (the speed
/// `rest[k]`, or 0 without it), a cell with no change left as it is. Returns their kinetic
/// energy change `m h d (w + d / 2)`, J, summed in lanes.
fn apply_cells(
    field: &mut Field,
    speed: &[f64],
    slots: &Slots,
    p: &[f64],
    free: &[f64],
    rest: Option<&[f64]>,
    scratch: &mut CellScratch,
) -> f64 {
    let mut total = 0.0;
    for s in 0..field.sections.len() {
        let sp = field.sections[s];
        let r = sp.offset + 1..sp.offset + 1 + sp.cells;
        let state = match (&mut field.nl, rest) {
            (Some(nl), _) => State::Nonlinear(&mut nl.omega[r.clone()]),
            (None, None) => State::Linear(&mut field.alpha[r.clone()], &mut field.beta[r.clone()]),
            (None, Some(rest)) => {
                State::Resting(&mut field.alpha[r.clone()], &mut field.beta[r.clone()], &rest[r.clone()])
            }
        };
        total += crate::simd::dispatch(CellPass {
            mass: sp.inertia_per_length * sp.h,
            speed: &speed[r.clone()],
            slots: slots.slot.iter().map(|slot| &slot[r.clone()]).collect(),
            untouched: &slots.untouched[r.clone()],
            p,
            free,
            state,
            change: &mut scratch.change[..sp.cells],
            moving: &mut scratch.moving[..sp.cells],
            work: &mut scratch.work[..sp.cells],
        });
    }
    total
}

/// A section's speeds: the invariants `alpha`, `beta` (at rest: speed 0, or the speeds `rest`),
/// or the `consistent` scheme's speeds.
enum State<'a> {
    Linear(&'a mut [f64], &'a mut [f64]),
    Resting(&'a mut [f64], &'a mut [f64], &'a [f64]),
    Nonlinear(&'a mut [f64]),
}

/// [`apply_cells`] on one section, as a [`crate::simd::Kernel`].
struct CellPass<'a> {
    mass: f64,
    speed: &'a [f64],
    slots: Vec<&'a [u32]>,
    untouched: &'a [f64],
    p: &'a [f64],
    free: &'a [f64],
    state: State<'a>,
    change: &'a mut [f64],
    moving: &'a mut [f64],
    work: &'a mut [f64],
}

impl crate::simd::Kernel for CellPass<'_> {
    type Output = f64;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> f64 {
        let n = self.speed.len();
        let (change, moving, work) = (&mut self.change[..n], &mut self.moving[..n], &mut self.work[..n]);
        let untouched = &self.untouched[..n];
        match self.slots[..] {
            [a] => sum_slots([a], self.p, self.free, untouched, change, moving),
            [a, b] => sum_slots([a, b], self.p, self.free, untouched, change, moving),
            [a, b, c] => sum_slots([a, b, c], self.p, self.free, untouched, change, moving),
            [a, b, c, d] => sum_slots([a, b, c, d], self.p, self.free, untouched, change, moving),
            _ => {
                change.fill(0.0);
                moving.copy_from_slice(untouched);
                for slot in &self.slots {
                    for ((c, m), &i) in change.iter_mut().zip(moving.iter_mut()).zip(&slot[..n]) {
                        *c += self.p[i as usize];
                        *m += self.free[i as usize];
                    }
                }
            }
        }
        let (m, speed) = (self.mass, &self.speed[..n]);
        // (the selects keep a skipped cell's bits, a zero's sign included)
        match self.state {
            State::Nonlinear(omega) => {
                for ((((o, &w), &c), &k), e) in
                    omega[..n].iter_mut().zip(speed).zip(&*change).zip(&*moving).zip(work.iter_mut())
                {
                    let stop = k == 0.0;
                    let d = if stop { -w } else { c };
                    let skip = d == 0.0 && !stop;
                    *e = if skip { 0.0 } else { m * d * (w + 0.5 * d) };
                    let next = if stop { 0.0 } else { *o + d };
                    *o = if skip { *o } else { next };
                }
            }
            State::Linear(alpha, beta) => {
                for (((((a, b), &w), &c), &k), e) in alpha[..n]
                    .iter_mut()
                    .zip(beta[..n].iter_mut())
                    .zip(speed)
                    .zip(&*change)
                    .zip(&*moving)
                    .zip(work.iter_mut())
                {
                    let stop = k == 0.0;
                    let d = if stop { -w } else { c };
                    let skip = d == 0.0 && !stop;
                    *e = if skip { 0.0 } else { m * d * (w + 0.5 * d) };
                    let half = 0.5 * (*a - *b);
                    let (na, nb) = if stop { (half, -half) } else { (*a + d, *b + d) };
                    (*a, *b) = if skip { (*a, *b) } else { (na, nb) };
                }
            }
            State::Resting(alpha, beta, rest) => {
                for ((((((a, b), &w), &c), &k), e), &r) in alpha[..n]
                    .iter_mut()
                    .zip(beta[..n].iter_mut())
                    .zip(speed)
                    .zip(&*change)
                    .zip(&*moving)
                    .zip(work.iter_mut())
                    .zip(&rest[..n])
                {
                    let stop = k == 0.0;
                    let d = if stop { r - w } else { c };
                    let skip = d == 0.0 && !stop;
                    *e = if skip { 0.0 } else { m * d * (w + 0.5 * d) };
                    let half = 0.5 * (*a - *b);
                    let (na, nb) = if stop { (half + r, r - half) } else { (*a + d, *b + d) };
                    (*a, *b) = if skip { (*a, *b) } else { (na, nb) };
                }
            }
        }
        super::kernel::lane_sum(work)
    }
}

/// Each cell's shares summed over its `S` slots in order, `change[k] = 0 + p[slot[k]] + ...`
/// and `moving[k] = base[k] + free[slot[k]] + ...`, one cell at a time in registers (the
/// operations of the slot-by-slot passes, in their order).
#[inline(always)]
fn sum_slots<const S: usize>(
    slots: [&[u32]; S],
    p: &[f64],
    free: &[f64],
    base: &[f64],
    change: &mut [f64],
    moving: &mut [f64],
) {
    let n = change.len();
    // (indices clamped to the last element, which they never exceed: no bounds check in the loop)
    let last = p.len().min(free.len()) - 1;
    let (p, free, base, moving) = (&p[..=last], &free[..=last], &base[..n], &mut moving[..n]);
    let slots = slots.map(|slot| &slot[..n]);
    for k in 0..n {
        let (mut c, mut m) = (0.0, base[k]);
        for slot in &slots {
            let i = (slot[k] as usize).min(last);
            c += p[i];
            m += free[i];
        }
        change[k] = c;
        moving[k] = m;
    }
}

#[cfg(test)]
#[path = "coupled_friction_tests.rs"]
pub(super) mod tests;

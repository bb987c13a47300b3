//! The string discretised in cells: section properties, the common time step, the friction
//! limit of every cell, the survey, and the string's first natural frequency.

use std::f64::consts::PI;

use crate::error::{Error, Num, Result};
use crate::model::{consistent_k5, p_wave_modulus, youngs_modulus};

use super::config::{Contact, DrillConfig, Nonlinearity, Section};
use super::well;

/// Subdivisions of each interval between breakpoints (section ends, survey stations) in the
/// quadrature of the break-off torque (trapezoidal on this and half as many, extrapolated:
/// relative error ~ `(b h)^4` for an inclination changing at `b` rad/m).
const BREAKOFF_SUBDIVISIONS: usize = 512;

/// The properties of one section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionProps {
    pub length: f64,
    /// Polar moment J, m^4.
    pub polar_moment: f64,
    /// Cross-section A, m^2.
    pub area: f64,
    /// Wave speed `c = sqrt(G / rho)`, m/s.
    pub wave_speed: f64,
    /// Impedance `Z = J sqrt(G rho)`, N m s.
    pub impedance: f64,
    /// Rotational inertia per length `rho J`, kg m.
    pub inertia_per_length: f64,
    /// Friction lever arm, m ([`super::pipe::contact_radius`]).
    pub contact_radius: f64,
    /// `(rho - rho_mud) A`, kg/m.
    pub buoyed_mass_per_length: f64,
    /// Torsional stiffness `k2 = G J`, N m^2.
    pub stiffness: f64,
    /// Quartic coefficient of the `consistent` torque-twist law, `k5 = M J4 / 2`
    /// ([`crate::model::consistent_k5`], `J4 = int r^4 dA`: the section's `quartic_moment`, else
    /// that of the annulus of its diameters; `M` the P-wave modulus of `shear_modulus` and
    /// `poisson_ratio`), N m^4.
    pub quartic: f64,
}

impl SectionProps {
    pub fn new(s: &Section, mud_density: f64) -> Self {
        let (od, id) = (s.outer_diameter, s.inner_diameter);
        let j = s.polar_moment.unwrap_or(PI / 32.0 * (od.powi(4) - id.powi(4)));
        let a = s.area.unwrap_or(PI / 4.0 * (od * od - id * id));
        let (g, rho) = (s.shear_modulus, s.density);
        let j4 =
            s.quartic_moment.unwrap_or_else(|| crate::model::CrossSection::annulus(od, id).map_or(f64::NAN, |a| a.j4));
        let nu = s.poisson_ratio;
        SectionProps {
            length: s.length,
            polar_moment: j,
            area: a,
            wave_speed: (g / rho).sqrt(),
            impedance: j * (g * rho).sqrt(),
            inertia_per_length: rho * j,
            contact_radius: super::pipe::contact_radius(s),
            buoyed_mass_per_length: (rho - mud_density) * a,
            stiffness: g * j,
            quartic: consistent_k5(p_wave_modulus(youngs_modulus(g, nu), nu), j4),
        }
    }

    /// The torque of the `consistent` law at the twist per length `eps` (1/m),
    /// `tau = k2 eps + k5 eps^3`, N m.
    #[inline(always)]
    pub fn torque(&self, eps: f64) -> f64 {
        eps * (self.stiffness + self.quartic * eps * eps)
    }

    /// The tangent stiffness `d tau / d eps = k2 + 3 k5 eps^2`, N m^2.
    #[inline(always)]
    pub fn tangent_stiffness(&self, eps: f64) -> f64 {
        self.stiffness + 3.0 * self.quartic * eps * eps
    }

    /// The tangent impedance `sqrt(rho J (k2 + 3 k5 eps^2))`, N m s (`Z` at `eps = 0`).
    #[inline(always)]
    pub fn tangent_impedance(&self, eps: f64) -> f64 {
        (self.inertia_per_length * self.tangent_stiffness(eps)).sqrt()
    }

    /// The tangent wave speed `sqrt((k2 + 3 k5 eps^2) / (rho J))`, m/s.
    pub fn tangent_speed(&self, eps: f64) -> f64 {
        (self.tangent_stiffness(eps) / self.inertia_per_length).sqrt()
    }

    /// The elastic energy per length of the `consistent` law, `k2 eps^2 / 2 + k5 eps^4 / 4`, J/m.
    #[inline(always)]
    pub fn elastic_energy(&self, eps: f64) -> f64 {
        let e2 = eps * eps;
        e2 * (0.5 * self.stiffness + 0.25 * self.quartic * e2)
    }

    /// The twist per length carrying the torque `tau` under the `consistent` law (the inverse
    /// of [`SectionProps::torque`], increasing and odd): Newton from `tau / k2`, which lies on
    /// the far side of the root of the convex branch, so the iterates approach it monotonically.
    pub fn strain(&self, tau: f64) -> f64 {
        let mut eps = tau / self.stiffness;
        for _ in 0..100 {
            let next = eps - (self.torque(eps) - tau) / self.tangent_stiffness(eps);
            if next.abs() >= eps.abs() {
                break;
            }
            eps = next;
        }
        eps
    }

    /// Static friction limit per metre at inclination `inc` (rad), N m/m: the soft-string
    /// normal force `g sin(inc) (rho - rho_mud) A` times `mu_s` times the contact radius
    /// (Aarsnes & Shor 2018, parameters_WellB.m `P_thresProfile`).
    pub fn friction_limit(&self, mu_static: f64, gravity: f64, inc: f64) -> f64 {
        (mu_static * gravity * inc.sin() * self.buoyed_mass_per_length * self.contact_radius).max(0.0)
    }
}

/// The cells of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub props: Vec<SectionProps>,
    /// The common time step, s.
    pub dt: f64,
    /// Cells of each section.
    pub counts: Vec<usize>,
    /// Courant number `c_i dt / h_i` of each section at its design speed `speed[i]` (`<= 1`;
    /// exactly 1 when the section's travel time is a whole number of steps).
    pub courant: Vec<f64>,
    /// The wave speed the step is made for, m/s: `sqrt(G / rho)` (`linear`); for `consistent`
    /// that times the largest hardening factor of the sections, `max_i c_t,i / c_i` with `c_t,i`
    /// the tangent speed at the twist per length `strain_bound[i]` (at least each section's
    /// tangent speed there; sections of equal wave speeds keep equal ones).
    pub speed: Vec<f64>,
    /// `consistent`: the twist per length of `numerics.max_shear_strain` at the outer surface,
    /// `2 max_shear_strain / OD`, 1/m (0 for `linear`).
    pub strain_bound: Vec<f64>,
    /// Cell length of each section, m.
    pub spacing: Vec<f64>,
    /// Cell centres (measured depth from the top), m.
    pub z: Vec<f64>,
    /// Section of each cell.
    pub section_of: Vec<usize>,
    /// Static friction limit per metre at each cell centre, N m/m.
    pub limit: Vec<f64>,
    /// The wall's normal force per metre at each cell centre, N/m (`friction.contact`'s: the
    /// soft-string contact force, or the buoyed weight times sin(inclination)); `limit` is
    /// `mu_s` times it times the contact radius.
    pub normal: Vec<f64>,
}

impl Grid {
    /// The discretisation of a configuration whose values are valid (see
    /// [`DrillConfig::validate`]); an error names `numerics.cells` when the cells exceed
    /// `numerics.max_cells`.
    pub fn new(cfg: &DrillConfig) -> Result<Grid> {
        let props: Vec<SectionProps> =
            cfg.sections.iter().map(|s| SectionProps::new(s, cfg.well.mud_density)).collect();
        let mut strain_bound = vec![0.0; props.len()];
        // consistent: every section's speed raised by the largest hardening factor of the
        // sections (so that sections of equal wave speeds keep equal cells and Courant numbers).
        let mut factor: f64 = 1.0;
        if cfg.nonlinearity == Nonlinearity::Consistent {
            for (i, (p, s)) in props.iter().zip(&cfg.sections).enumerate() {
                strain_bound[i] = 2.0 * cfg.numerics.max_shear_strain / s.outer_diameter;
                let c = p.tangent_speed(strain_bound[i]);
                if !(p.quartic.is_finite() && c.is_finite() && c > 0.0) {
                    return Err(Error::invalid(
                        format!("sections[{i}].outer_diameter"),
                        Num(s.outer_diameter),
                        "diameters whose fourth polar moment and tangent wave speed are finite",
                    ));
                }
                factor = factor.max(c / p.wave_speed);
            }
        }
        let speed: Vec<f64> = match cfg.nonlinearity {
            Nonlinearity::Linear => props.iter().map(|p| p.wave_speed).collect(),
            Nonlinearity::Consistent => props.iter().map(|p| p.wave_speed * factor).collect(),
        };
        let travel: f64 = props.iter().zip(&speed).map(|(p, c)| p.length / c).sum();
        // Every section gets at least one cell at a Courant number <= 1: the step is also
        // limited by the shortest section's travel time.
        let shortest = props.iter().zip(&speed).map(|(p, c)| p.length / c).fold(f64::INFINITY, f64::min);
        let dt = (travel / cfg.numerics.cells as f64).min(shortest);
        let mut counts = Vec::with_capacity(props.len());
        let mut courant = Vec::with_capacity(props.len());
        let mut spacing = Vec::with_capacity(props.len());
        for (p, &speed) in props.iter().zip(&speed) {
            let exact = p.length / (speed * dt);
            let n = ((exact * (1.0 + 1e-9)).floor()).max(1.0);
            let mut c = n / exact;
            if (c - 1.0).abs() < 1e-9 {
                c = 1.0;
            }
            // Cannot happen with dt <= the shortest travel time (a guard against rounding).
            if c > 1.0 {
                return Err(Error::invalid(
                    "numerics.cells",
                    cfg.numerics.cells,
                    format!(
                        "more cells: a section of travel time {} s is shorter than the time step {} s",
                        Num(p.length / speed),
                        Num(dt)
                    ),
                ));
            }
            counts.push(n as usize);
            courant.push(c);
            spacing.push(p.length / n);
        }
        // A Courant number below 1 asked for: a shorter step on the same cells.
        let target = cfg.numerics.courant;
        let dt = dt * target;
        courant.iter_mut().for_each(|c| *c *= target);
        let total: usize = counts.iter().sum();
        if total > cfg.numerics.max_cells {
            return Err(Error::invalid(
                "numerics.cells",
                cfg.numerics.cells,
                format!(
                    "a count giving at most numerics.max_cells = {} cells ({total} needed; the time step is at most \
                     the travel time of the shortest section, {} s)",
                    cfg.numerics.max_cells,
                    Num(shortest)
                ),
            ));
        }
        let mut z = Vec::with_capacity(total);
        let mut section_of = Vec::with_capacity(total);
        let mut limit = Vec::with_capacity(total);
        let mut normal = Vec::with_capacity(total);
        let mut top = 0.0;
        let traj = well::trajectory(cfg)?;
        let contact = match cfg.friction.contact {
            Contact::SoftString => Some(well::contact_profile(cfg, &traj)?),
            Contact::Weight => None,
        };
        for (s, p) in props.iter().enumerate() {
            let h = spacing[s];
            for j in 0..counts[s] {
                let zc = top + (j as f64 + 0.5) * h;
                z.push(zc);
                section_of.push(s);
                let mu = well::friction_factor(cfg, zc);
                limit.push(match &contact {
                    None => p.friction_limit(mu, cfg.well.gravity, traj.at(zc).inc),
                    Some(profile) => (mu * p.contact_radius * well::normal_force_at(profile, zc)).max(0.0),
                });
                normal.push(match &contact {
                    None => p.friction_limit(1.0, cfg.well.gravity, traj.at(zc).inc) / p.contact_radius,
                    Some(profile) => well::normal_force_at(profile, zc).max(0.0),
                });
            }
            top += p.length;
        }
        Ok(Grid { props, dt, counts, courant, speed, strain_bound, spacing, z, section_of, limit, normal })
    }

    /// Total number of cells.
    pub fn cells(&self) -> usize {
        self.z.len()
    }

    /// Total length, m.
    pub fn length(&self) -> f64 {
        self.props.iter().map(|p| p.length).sum()
    }
}

/// The static break-off torque, N m: the integral of the friction limit over the string,
/// section by section (limits jump at section ends) through
/// [`crate::metrics::break_off_torque`] on grids refined between the survey stations
/// (two grids, Richardson-extrapolated).
pub fn breakoff_torque(cfg: &DrillConfig) -> Result<f64> {
    let traj = well::trajectory(cfg)?;
    if cfg.friction.contact == Contact::SoftString {
        // the rotating soft-string torque at the surface without a torque on bit: the sum of
        // mu r N over the elements, the limit integrated element by element
        return Ok(well::contact_profile(cfg, &traj)?.torque[0]);
    }
    let mut top = 0.0;
    let mut total = 0.0;
    let mut stations: Vec<f64> = traj.survey.md.clone();
    for iv in &cfg.friction.intervals {
        stations.extend([iv.top_md, iv.bottom_md]);
    }
    stations.sort_by(f64::total_cmp);
    for s in &cfg.sections {
        let p = SectionProps::new(s, cfg.well.mud_density);
        let bottom = top + p.length;
        let mut breaks = vec![top];
        breaks.extend(stations.iter().copied().filter(|&d| d > top && d < bottom));
        breaks.push(bottom);
        // Trapezoidal rule on n and n/2 subdivisions, Richardson-extrapolated (Simpson's rule).
        let mut fine = 0.0;
        let mut coarse = 0.0;
        for (n, sum) in [(BREAKOFF_SUBDIVISIONS, &mut fine), (BREAKOFF_SUBDIVISIONS / 2, &mut coarse)] {
            let mut depth = Vec::with_capacity((breaks.len() - 1) * n + 1);
            for w in breaks.windows(2) {
                for k in 0..n {
                    depth.push(w[0] + (w[1] - w[0]) * k as f64 / n as f64);
                }
            }
            depth.push(bottom);
            // a station within rounding of a section's end (800 against 800.0000000000001 m)
            // gives equal depths: keep them strictly increasing
            depth.dedup_by(|later, earlier| *later <= *earlier);
            let limit: Vec<f64> = depth
                .iter()
                .map(|&d| p.friction_limit(well::friction_factor(cfg, d), cfg.well.gravity, traj.at(d).inc))
                .collect();
            *sum = crate::metrics::break_off_torque(&depth, &limit)?;
        }
        total += (4.0 * fine - coarse) / 3.0;
        top = bottom;
    }
    Ok(total)
}

/// The minimum motor torque of a stick-slip cycle implied by break-off, N m:
/// `2 K - S` with `S = wall_breakoff + bit_static` the static torque the string holds at
/// break-off and `K = kinetic_ratio wall_breakoff + bit_kinetic` the torque of the same
/// contacts slipping.
///
/// Derivation: at break-off the string is wound up to hold `S`. Once it slips, the load it
/// turns against drops from static to kinetic, `K`: the twist in excess of the new balance,
/// `S - K`, is released and, without damping, the string overshoots the balance by as much (an
/// undamped spring preloaded to `S` and released against a constant load `K` oscillates
/// between `S` and `2 K - S`). The top torque thus falls by twice the released difference,
/// `S - 2 (S - K) = S (1 - 2 (1 - K / S))`. Without a bit torque this is
/// `tauMax (1 - 2 (1 - fRat))` of the published code of Aarsnes & Shor (MAIN.m, `tauMin`).
/// Assumptions: no damping and a quick release (the whole string slips within one
/// round trip of the wave), the bit (if on bottom) at its kinetic torque `W r mu_k` (the
/// law's fast limit: a slower bit has a larger torque and a larger minimum). The value can be
/// negative (the motor would have to brake).
pub fn min_cycle_torque_from(wall_breakoff: f64, kinetic_ratio: f64, bit_static: f64, bit_kinetic: f64) -> f64 {
    let static_torque = wall_breakoff + bit_static;
    let kinetic_torque = kinetic_ratio * wall_breakoff + bit_kinetic;
    2.0 * kinetic_torque - static_torque
}

/// The bit's static torque, N m: `W r mu_s` with the bit on bottom, 0 off bottom.
pub fn bit_static_torque(cfg: &DrillConfig) -> f64 {
    let b = &cfg.bit;
    if b.on_bottom && b.weight_on_bit > 0.0 {
        b.weight_on_bit * b.radius * b.mu_static
    } else {
        0.0
    }
}

/// The static torque the motor must exceed to break the string free, N m: the wall's
/// break-off torque `breakoff` ([`breakoff_torque`]) and, with the bit on bottom, its static
/// torque ([`bit_static_torque`]).
pub fn static_torque(cfg: &DrillConfig, breakoff: f64) -> f64 {
    breakoff + bit_static_torque(cfg)
}

/// [`min_cycle_torque_from`] of a configuration whose wall break-off torque is `breakoff`
/// ([`breakoff_torque`]): the wall's kinetic ratio `friction.kinetic_ratio` and, with the bit
/// on bottom, its static and kinetic torques `W r mu_s`, `W r mu_k`.
pub fn min_cycle_torque(cfg: &DrillConfig, breakoff: f64) -> f64 {
    let b = &cfg.bit;
    let (bit_static, bit_kinetic) = if b.on_bottom && b.weight_on_bit > 0.0 {
        let wr = b.weight_on_bit * b.radius;
        (wr * b.mu_static, wr * b.mu_kinetic)
    } else {
        (0.0, 0.0)
    };
    min_cycle_torque_from(breakoff, cfg.friction.kinetic_ratio, bit_static, bit_kinetic)
}

/// The lowest natural angular frequency (rad/s) of the string with the top fixed and the bit
/// free (or carrying the BHA inertia `bha_inertia`): the first root of the transfer-matrix
/// frequency equation `q(L) - I_bha w^2 theta(L) = 0` from `theta(0) = 0`, `q(0) = 1`
/// (`q = G J theta_z`; across a section of wave speed `c` and impedance `Z`,
/// `theta' = theta cos(kL) + q sin(kL)/(Z w)`, `q' = -Z w theta sin(kL) + q cos(kL)`, `k = w/c`).
pub fn first_natural_frequency(props: &[SectionProps], bha_inertia: f64) -> f64 {
    let residual = |w: f64| {
        let (mut theta, mut q) = (0.0, 1.0);
        for p in props {
            let (s, c) = (w * p.length / p.wave_speed).sin_cos();
            let zw = p.impedance * w;
            (theta, q) = (theta * c + q * s / zw, -zw * theta * s + q * c);
        }
        q - bha_inertia * w * w * theta
    };
    let travel: f64 = props.iter().map(|p| p.length / p.wave_speed).sum();
    let quarter = PI / (2.0 * travel);
    let step = quarter / 100.0;
    let mut lo = step * 1e-3;
    let mut r_lo = residual(lo);
    // Scan up to 100 times the uniform string's (pi / 2) / travel (the first root of a string
    // of any impedances lies far below), in steps of 1/100 of it, then bisect.
    for _ in 0..100 * 100 {
        let hi = lo + step;
        let r_hi = residual(hi);
        if r_lo == 0.0 {
            return lo;
        }
        if r_lo.signum() != r_hi.signum() {
            let (mut a, mut b, mut ra) = (lo, hi, r_lo);
            for _ in 0..100 {
                let m = 0.5 * (a + b);
                let rm = residual(m);
                if rm.signum() == ra.signum() {
                    (a, ra) = (m, rm);
                } else {
                    b = m;
                }
            }
            return 0.5 * (a + b);
        }
        (lo, r_lo) = (hi, r_hi);
    }
    quarter
}

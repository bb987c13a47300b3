//! Axial section properties, the static effective tension of a hanging or drilling string,
//! and the axial natural frequencies of a multi-section string.
//!
//! Conventions: `z` is the measured depth from the top (m), the axial speed `v` is positive
//! downwards (m/s), the effective tension `N` is positive in tension (N). The force the axial
//! field carries towards the bit is the compression `F = -N`, so that the axial field reads like
//! the torsional one (`tau` carried down): the invariants `alpha = v + F / Z` (travelling down
//! at `c`) and `beta = v - F / Z` (travelling up), and at the bit `F = WOB`,
//! `v = alpha - WOB / Z` (Aarsnes & van de Wouw 2019, whose strain is compressive;
//! their `waveStep_transportBRI.m`, `AbetaPp1 = Aalpha(P) - 2 wb c_a / (A_p E)`).

use std::f64::consts::PI;

use crate::error::{Error, Num, Result};
use crate::model::{bar_speed, youngs_modulus};

use super::super::config::Section;
use super::super::grid::SectionProps;

/// One section of the string as the axial field sees it (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialSection {
    /// m.
    pub length: f64,
    /// Steel cross-section `A`, m^2.
    pub area: f64,
    /// Young's modulus `E`, Pa.
    pub youngs_modulus: f64,
    /// Density `rho`, kg/m^3.
    pub density: f64,
}

impl AxialSection {
    /// A section of the drilling configuration: its area as the torsional field takes it
    /// ([`SectionProps`]: `area`, else `pi/4 (OD^2 - ID^2)`) and `E = 2 G (1 + nu)`
    /// ([`youngs_modulus`]).
    pub fn from_section(s: &Section) -> Self {
        let props = SectionProps::new(s, 0.0);
        AxialSection {
            length: s.length,
            area: props.area,
            youngs_modulus: youngs_modulus(s.shear_modulus, s.poisson_ratio),
            density: s.density,
        }
    }

    /// Refuses a non-positive or non-finite length, area, modulus or density, naming
    /// `sections[index].<field>`.
    pub fn validate(&self, index: usize) -> Result<()> {
        for (name, value) in [
            ("length", self.length),
            ("area", self.area),
            ("youngs_modulus", self.youngs_modulus),
            ("density", self.density),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(format!("sections[{index}].{name}"), Num(value), "a finite number > 0"));
            }
        }
        Ok(())
    }

    /// The bar wave speed `c = sqrt(E / rho)`, m/s ([`bar_speed`]; Graff, *Wave Motion in
    /// Elastic Solids*, 1975, ch. 2).
    pub fn wave_speed(&self) -> f64 {
        bar_speed(self.youngs_modulus, self.density)
    }

    /// The axial impedance `Z = A sqrt(E rho) = E A / c = rho A c`, N s/m: the force per unit
    /// speed of a travelling wave, `F = Z v` (Graff 1975, ch. 2; Aarsnes & van de Wouw 2019,
    /// `A_p E / c_a`).
    pub fn impedance(&self) -> f64 {
        self.area * (self.youngs_modulus * self.density).sqrt()
    }

    /// The axial stiffness `E A`, N.
    pub fn stiffness(&self) -> f64 {
        self.youngs_modulus * self.area
    }

    /// Mass per length `rho A`, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.density * self.area
    }

    /// The buoyed weight per length `(rho - rho_mud) A g`, N/m (the effective-tension rule with
    /// the same mud inside and outside, Lubinski 1950, as `SectionProps::buoyed_mass_per_length`).
    pub fn buoyed_weight(&self, mud_density: f64, gravity: f64) -> f64 {
        (self.density - mud_density) * self.area * gravity
    }

    /// The axial acceleration of the buoyed weight along a hole of inclination `inclination`
    /// (rad), `(1 - rho_mud / rho) g cos(inc)`, m/s^2: the gravity source of the axial field
    /// (`rho A v_t = N_z + (rho - rho_mud) A g cos(inc)`), whose static balance is
    /// [`static_tension`].
    pub fn buoyed_gravity(&self, mud_density: f64, gravity: f64, inclination: f64) -> f64 {
        self.buoyed_weight(mud_density, gravity) * inclination.cos() / self.mass_per_length()
    }

    /// The travel time of an axial wave through the section, `length / c`, s.
    pub fn travel_time(&self) -> f64 {
        self.length / self.wave_speed()
    }
}

/// Gauss-Legendre nodes (on `[-1, 1]`) and weights, 3 points: exact for polynomials of degree 5.
const GAUSS3: [(f64, f64); 3] =
    [(-0.774_596_669_241_483_4, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)];

/// The longest panel of the quadrature of [`static_tension`], m (3-point Gauss-Legendre on
/// panels this long: error `~ (b h)^6` for an inclination changing at `b` rad/m).
const TENSION_PANEL: f64 = 10.0;

/// The static effective tension at the measured depths `depths` (m from the top, each within
/// `[0, L]`), N, positive in tension: the buoyed weight of the string below each depth along the
/// hole, less the weight on bit,
/// `N(z) = -WOB + int_z^L (rho - rho_mud) A g cos(inc(s)) ds`
/// (the soft-string effective tension without wall friction: Aadnoy, Fazaelizadeh & Hareland,
/// "A 3D analytical model for wellbore friction", J. Can. Pet. Technol. 49 (2010) 25-36,
/// with `mu = 0`; buoyancy by the effective-tension rule with the same mud inside and outside,
/// Lubinski 1950, as `SectionProps::buoyed_mass_per_length`). `inclination(md)` gives the
/// inclination in rad at a measured depth; the integral is 3-point Gauss-Legendre on panels of at
/// most 10 m inside each section (exact for an inclination constant per section). The hook load
/// is `N(0)` and the neutral point the depth where `N = 0`. Wall friction (drag) is the
/// torque-and-drag model's (`well::torque_drag`).
pub fn static_tension(
    sections: &[AxialSection],
    mud_density: f64,
    gravity: f64,
    inclination: &dyn Fn(f64) -> f64,
    weight_on_bit: f64,
    depths: &[f64],
) -> Vec<f64> {
    // Section tops, and the weight of everything below each section's bottom.
    let mut tops = Vec::with_capacity(sections.len());
    let mut top = 0.0;
    for s in sections {
        tops.push(top);
        top += s.length;
    }
    let weight = |s: &AxialSection| s.buoyed_weight(mud_density, gravity);
    // int_a^b cos(inc) ds on panels.
    let integral = |a: f64, b: f64| -> f64 {
        if b <= a {
            return 0.0;
        }
        let panels = ((b - a) / TENSION_PANEL).ceil().max(1.0);
        let h = (b - a) / panels;
        let mut sum = 0.0;
        for k in 0..panels as usize {
            let mid = a + (k as f64 + 0.5) * h;
            for (x, w) in GAUSS3 {
                sum += w * inclination(mid + 0.5 * h * x).cos();
            }
        }
        0.5 * h * sum
    };
    let mut below = vec![0.0; sections.len()];
    let mut acc = 0.0;
    for i in (0..sections.len()).rev() {
        below[i] = acc;
        acc += weight(&sections[i]) * integral(tops[i], tops[i] + sections[i].length);
    }
    depths
        .iter()
        .map(|&z| {
            let i = tops.partition_point(|&t| t <= z).saturating_sub(1);
            let s = &sections[i];
            let bottom = tops[i] + s.length;
            -weight_on_bit + below[i] + weight(s) * integral(z.max(tops[i]), bottom)
        })
        .collect()
}

/// The end condition of the axial string for [`natural_frequencies`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AxialEnd {
    /// No displacement (the bit held by the rock, the top by a stiff hoist).
    Fixed,
    /// No force (the bit off bottom, the top free).
    Free,
    /// A rigid mass, kg (the BHA lumped at the bit, the travelling block).
    Mass(f64),
}

/// The axial natural frequency `k >= 1` (Hz) of a uniform section with the ends `top` and
/// `bottom` in closed form (Graff 1975, ch. 2; Rao, *Vibration of Continuous Systems*, 2007,
/// longitudinal vibration of bars): `(2k - 1) c / (4 L)` for fixed-free and free-fixed, `k c / (2 L)` for fixed-fixed
/// and free-free (the rigid-body mode of free-free not counted); `None` with a mass end
/// (transcendental) or `k = 0`.
pub fn uniform_frequency(section: &AxialSection, top: AxialEnd, bottom: AxialEnd, k: usize) -> Option<f64> {
    if k == 0 {
        return None;
    }
    let (c, l, k) = (section.wave_speed(), section.length, k as f64);
    match (top, bottom) {
        (AxialEnd::Fixed, AxialEnd::Free) | (AxialEnd::Free, AxialEnd::Fixed) => Some((2.0 * k - 1.0) * c / (4.0 * l)),
        (AxialEnd::Fixed, AxialEnd::Fixed) | (AxialEnd::Free, AxialEnd::Free) => Some(k * c / (2.0 * l)),
        _ => None,
    }
}

/// Scan steps per `pi / tau` (`tau` the total travel time) of the root search of
/// [`natural_frequencies`]; the characteristic function of `n` sections is a sum of harmonics
/// of frequencies up to `tau`, whose roots lie about `pi / tau` apart.
const SCAN_PER_SPACING: f64 = 32.0;

/// The first `count` axial natural frequencies (Hz) of the string `sections` (top first) with
/// the end conditions `top` and `bottom`, by the transfer matrix of the bar (Pestel & Leckie,
/// *Matrix Methods in Elastomechanics*, 1963; Rao 2007): over a section of length `l`
/// at angular frequency `w`, with `k = w / c`, `theta = k l` and the state
/// `(u, N / (w Z_ref))` (`N = E A u_z` the tension),
/// `u(l) = cos(theta) u(0) + sin(theta) (Z_ref / Z) F(0)`,
/// `F(l) = -(Z / Z_ref) sin(theta) u(0) + cos(theta) F(0)` (continuity of displacement and force
/// at the junctions). The top state is `(0, 1)` fixed, `(1, 0)` free, `(1, -M w / Z_ref)` with a
/// mass `M` (`M u_tt = N`); the frequencies are the roots of the bottom condition, `u`, `F` or
/// `F - M w u / Z_ref` (`M u_tt = -N`), found by a scan at `pi / (32 tau)` and bisection to
/// rounding. The rigid-body mode (free-free, or free with masses) at 0 is not listed. The scan
/// stops at `4 (count + 2) pi / tau` (the `k`-th root lies near `k pi / tau` or below), so
/// non-finite properties give fewer frequencies rather than no end.
pub fn natural_frequencies(sections: &[AxialSection], top: AxialEnd, bottom: AxialEnd, count: usize) -> Vec<f64> {
    if sections.is_empty() || count == 0 {
        return Vec::new();
    }
    let z_ref = sections[0].impedance();
    let tau: f64 = sections.iter().map(AxialSection::travel_time).sum();
    let f = |w: f64| -> f64 {
        let (mut u, mut fo) = match top {
            AxialEnd::Fixed => (0.0, 1.0),
            AxialEnd::Free => (1.0, 0.0),
            AxialEnd::Mass(m) => (1.0, -m * w / z_ref),
        };
        for s in sections {
            let (sn, cs) = (w * s.travel_time()).sin_cos();
            let r = s.impedance() / z_ref;
            (u, fo) = (cs * u + sn / r * fo, -r * sn * u + cs * fo);
        }
        match bottom {
            AxialEnd::Fixed => u,
            AxialEnd::Free => fo,
            AxialEnd::Mass(m) => fo - m * w * u / z_ref,
        }
    };
    let step = PI / (SCAN_PER_SPACING * tau);
    let mut out = Vec::with_capacity(count);
    let mut a = 0.5 * step;
    let mut fa = f(a);
    let end = 4.0 * (count as f64 + 2.0) * PI / tau;
    while out.len() < count && a < end {
        let b = a + step;
        let fb = f(b);
        if fa == 0.0 {
            out.push(a / (2.0 * PI));
        } else if fa * fb < 0.0 {
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let fm = f(mid);
                if fm == 0.0 {
                    (lo, hi) = (mid, mid);
                    break;
                }
                if (fm < 0.0) == (flo < 0.0) {
                    (lo, flo) = (mid, fm);
                } else {
                    hi = mid;
                }
            }
            out.push(0.5 * (lo + hi) / (2.0 * PI));
        }
        a = b;
        fa = fb;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The drill pipe of Aarsnes & van de Wouw's `parameters.m` (their "inner" and "outer" radii
    /// swapped back): 2000 m, r_o = 0.0635, r_i = 0.0540, E = 200 GPa, rho = 8000.
    fn pipe(length: f64) -> AxialSection {
        AxialSection { length, area: PI * (0.0635f64.powi(2) - 0.054f64.powi(2)), youngs_modulus: 200e9, density: 8e3 }
    }

    fn collar(length: f64) -> AxialSection {
        AxialSection { length, area: PI * (0.0762f64.powi(2) - 0.0286f64.powi(2)), youngs_modulus: 200e9, density: 8e3 }
    }

    #[test]
    fn speed_and_impedance() {
        let s = pipe(2000.0);
        // sqrt(200e9 / 8e3) = sqrt(25e6) = 5000 m/s.
        assert!((s.wave_speed() - 5000.0).abs() < 1e-9);
        // Z = A sqrt(E rho) = A * 4e7 = rho A c.
        assert!((s.impedance() - s.area * 4.0e7).abs() < 1e-6 * s.impedance());
        assert!((s.impedance() - s.mass_per_length() * 5000.0).abs() < 1e-9 * s.impedance());
        assert!((s.impedance() - s.stiffness() / 5000.0).abs() < 1e-9 * s.impedance());
        assert!(s.validate(0).is_ok());
        let bad = AxialSection { density: 0.0, ..s };
        assert_eq!(bad.validate(2).unwrap_err().field(), "sections[2].density");
    }

    #[test]
    fn from_the_configuration_section() {
        let cfg = Section { length: 100.0, outer_diameter: 0.127, inner_diameter: 0.1086, ..Section::default() };
        let s = AxialSection::from_section(&cfg);
        assert_eq!(s.length, 100.0);
        assert!((s.area - PI / 4.0 * (0.127f64.powi(2) - 0.1086f64.powi(2))).abs() < 1e-15);
        assert!((s.youngs_modulus - 2.0 * cfg.shear_modulus * (1.0 + cfg.poisson_ratio)).abs() < 1e-3);
        assert_eq!(s.density, cfg.density);
    }

    #[test]
    fn tension_of_a_vertical_and_an_inclined_string() {
        let (rho_m, g) = (1200.0, 9.81);
        let sections = [pipe(1500.0), collar(200.0)];
        let w = |s: &AxialSection| (s.density - rho_m) * s.area * g;
        let (wp, wc) = (w(&sections[0]), w(&sections[1]));
        let wob = 60e3;
        // Vertical: hook load = buoyed weight - WOB, linear in each section.
        let z = [0.0, 750.0, 1500.0, 1600.0, 1700.0];
        let n = static_tension(&sections, rho_m, g, &|_| 0.0, wob, &z);
        let expect =
            [1500.0 * wp + 200.0 * wc - wob, 750.0 * wp + 200.0 * wc - wob, 200.0 * wc - wob, 100.0 * wc - wob, -wob];
        for (a, b) in n.iter().zip(expect) {
            assert!((a - b).abs() < 1e-9 * b.abs().max(1.0), "{a} vs {b}");
        }
        // The gravity source balances the tension's gradient: rho A g_b = -dN/dz.
        let g_b = sections[0].buoyed_gravity(rho_m, g, 0.0);
        assert!((g_b * sections[0].mass_per_length() - wp).abs() < 1e-9 * wp);
        assert!((g_b - (1.0 - rho_m / 8e3) * g).abs() < 1e-12);
        // Constant 30 degrees: times cos(30 deg).
        let inc = 30f64.to_radians();
        let n = static_tension(&sections, rho_m, g, &|_| inc, 0.0, &[0.0]);
        assert!((n[0] - (1500.0 * wp + 200.0 * wc) * inc.cos()).abs() < 1e-9 * n[0]);
        // A build from 0 at the top at b rad/m: int_z^L cos(b s) ds = (sin(b L) - sin(b z)) / b.
        let b = 0.9f64.to_radians() / 30.0;
        let one = [pipe(1700.0)];
        let n = static_tension(&one, rho_m, g, &|s| b * s, 0.0, &[0.0, 333.3]);
        for (k, z0) in [0.0, 333.3].into_iter().enumerate() {
            let exact = wp * ((b * 1700.0).sin() - (b * z0).sin()) / b;
            assert!((n[k] - exact).abs() < 1e-10 * exact, "{} vs {exact}", n[k]);
        }
    }

    #[test]
    fn uniform_string_matches_closed_forms() {
        let s = pipe(2000.0);
        // c / (4 L) = 5000 / 8000 = 0.625 Hz.
        let ff = natural_frequencies(&[s], AxialEnd::Fixed, AxialEnd::Free, 5);
        let fx = natural_frequencies(&[s], AxialEnd::Free, AxialEnd::Fixed, 5);
        let cc = natural_frequencies(&[s], AxialEnd::Fixed, AxialEnd::Fixed, 5);
        let oo = natural_frequencies(&[s], AxialEnd::Free, AxialEnd::Free, 5);
        for k in 1..=5 {
            let odd = (2 * k - 1) as f64 * 0.625;
            let even = k as f64 * 1.25;
            assert!((ff[k - 1] - odd).abs() < 1e-12 * odd, "{} vs {odd}", ff[k - 1]);
            assert!((fx[k - 1] - odd).abs() < 1e-12 * odd);
            assert!((cc[k - 1] - even).abs() < 1e-12 * even);
            assert!((oo[k - 1] - even).abs() < 1e-12 * even);
            assert_eq!(uniform_frequency(&s, AxialEnd::Fixed, AxialEnd::Free, k), Some(odd));
            assert_eq!(uniform_frequency(&s, AxialEnd::Free, AxialEnd::Free, k), Some(even));
        }
        assert_eq!(uniform_frequency(&s, AxialEnd::Fixed, AxialEnd::Mass(1.0), 1), None);
        let broken = AxialSection { density: f64::NAN, ..s };
        assert!(natural_frequencies(&[broken], AxialEnd::Fixed, AxialEnd::Free, 3).is_empty());
        // Two sections of the same pipe are one section.
        let two = natural_frequencies(&[pipe(700.0), pipe(1300.0)], AxialEnd::Fixed, AxialEnd::Free, 5);
        for (a, b) in two.iter().zip(&ff) {
            assert!((a - b).abs() < 1e-12 * b);
        }
    }

    /// The root of `g` in `(lo, hi)` by bisection (the test's own oracle).
    fn bisect(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
        let glo = g(lo);
        assert!(glo * g(hi) < 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if (g(mid) < 0.0) == (glo < 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn two_sections_and_a_tip_mass_match_their_characteristic_equations() {
        // Fixed top, free bottom, pipe over collar: Z1 cot(k1 l1) = Z2 tan(k2 l2), i.e.
        // Z1 cos(t1) cos(t2) - Z2 sin(t1) sin(t2) = 0 with t_i = w l_i / c_i.
        let (p, c) = (pipe(1800.0), collar(200.0));
        let freqs = natural_frequencies(&[p, c], AxialEnd::Fixed, AxialEnd::Free, 6);
        let g = |w: f64| {
            let (t1, t2) = (w * p.travel_time(), w * c.travel_time());
            p.impedance() * t1.cos() * t2.cos() - c.impedance() * t1.sin() * t2.sin()
        };
        let mut roots = Vec::new();
        let mut w = 1e-6;
        while roots.len() < 6 {
            if g(w) * g(w + 1e-3) < 0.0 {
                roots.push(bisect(g, w, w + 1e-3) / (2.0 * PI));
            }
            w += 1e-3;
        }
        for (a, b) in freqs.iter().zip(&roots) {
            assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
        }
        // Fixed top, mass M at the bit: (w L / c) tan(w L / c) = rho A L / M.
        let s = pipe(2000.0);
        let m = 12e3;
        let ratio = s.mass_per_length() * s.length / m;
        let freqs = natural_frequencies(&[s], AxialEnd::Fixed, AxialEnd::Mass(m), 4);
        for (k, f) in freqs.iter().enumerate() {
            let lo = k as f64 * PI + 1e-12;
            let x = bisect(|x| x * x.sin() - ratio * x.cos(), lo, lo + PI / 2.0 - 2e-12);
            let exact = x * s.wave_speed() / s.length / (2.0 * PI);
            assert!((f - exact).abs() < 1e-9 * exact, "{f} vs {exact}");
        }
        // Mass at the top of a free-bottom bar is the mirror image of the above.
        let top = natural_frequencies(&[s], AxialEnd::Mass(m), AxialEnd::Fixed, 4);
        for (a, b) in top.iter().zip(&freqs) {
            assert!((a - b).abs() < 1e-10 * b);
        }
    }
}

//! Buckling of the soft string in compression, the wall contact of a helically buckled string,
//! and the pipe's strength limits (the equations of [`super::torque_drag`]'s buckling, lock-up
//! and utilisation; each written once here).
//!
//! Critical loads (positive compressive effective axial forces, N), with `E I` the bending
//! stiffness of the pipe body, `r_c` the radial clearance between the hole and the pipe body
//! (`(D_hole - OD) / 2`) and `n` the lateral load per length that holds the pipe on the wall:
//!
//! * sinusoidal, Dawson & Paslay (1984, SPE 11167): `F_s = 2 sqrt(E I n / r_c)`;
//! * helical, Chen, Lin & Cheatham (1990, SPE 19176): `F_h = 2 sqrt(2) sqrt(E I n / r_c)`.
//!
//! In a straight inclined hole `n = w sin(i)`, the buoyed weight's part across the hole. In a
//! curved hole (build, drop, turn) the convention here is the soft-string lateral balance of
//! [`super::torque_drag::normal_force`] at the critical compression itself: `n = |w z_perp -
//! F kappa|` (`kappa` the curvature vector, `F` the compression), so the critical load solves
//! `F = c sqrt(E I |w z_perp - F kappa| / r_c)`. In a build a compressed string is pressed
//! onto the low side by both its weight and the curve, and in a vertical plane this gives
//! `F_s = (2 E I / (r_c R)) (1 + sqrt(1 + r_c R^2 w sin(i) / (E I)))`; in a drop the curve
//! lifts the string off the low side and lowers the load. The same idea as the constant-
//! curvature criteria of He & Kyllingstad (1995, SPE 28210) and Mitchell (1999, SPE 52899),
//! whose curvature term is `4 E I / (r_c R)`: the convention here predicts buckling at a lower
//! load in a build (on the safe side) and reduces to Dawson & Paslay and Chen et al. in a
//! straight hole. Near vertical, where `w sin(i)` vanishes, the load is not below the vertical
//! string's own-weight loads (Lubinski 1950; Wu & Juvkam-Wold 1993): `2.55 (E I w^2)^(1/3)`
//! sinusoidal and `5.55 (E I w^2)^(1/3)` helical.
//!
//! A helically buckled string presses on the wall with the extra contact force per length
//! `N = r_c F^2 / (4 E I)` (Mitchell 1986, SPE 13064), added to the soft-string normal force
//! and so to the drag and the torque.
//!
//! Strength (API RP 7G, ISO 10407): the von Mises stress of the true axial force `F` and the
//! torque `M` on the pipe body, `sqrt((F / A)^2 + 3 (M r_o / J)^2)`, over the grade's minimum
//! yield strength.

use serde::Serialize;
use std::f64::consts::SQRT_2;

/// The vertical string's sinusoidal buckling load over `(E I w^2)^(1/3)` (Lubinski 1950,
/// Wu & Juvkam-Wold 1993).
pub const VERTICAL_SINUSOIDAL: f64 = 2.55;
/// The vertical string's helical buckling load over `(E I w^2)^(1/3)` (Wu & Juvkam-Wold 1993).
pub const VERTICAL_HELICAL: f64 = 5.55;

/// The buckled state of the string at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    None,
    Sinusoidal,
    Helical,
}

impl Mode {
    pub const NAMES: [&'static str; 3] = ["none", "sinusoidal", "helical"];

    /// The mode of the compression `f` (N, > 0 compressive) against the critical loads.
    pub fn of(f: f64, sinusoidal: f64, helical: f64) -> Mode {
        if f >= helical {
            Mode::Helical
        } else if f >= sinusoidal {
            Mode::Sinusoidal
        } else {
            Mode::None
        }
    }
}

/// The pipe body of a piece of the string: what buckling and the limits take.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Body {
    /// Outer diameter of the pipe body, m.
    pub outer_diameter: f64,
    /// Steel area of the pipe body, m^2.
    pub area: f64,
    /// Polar moment of area of the pipe body, m^4 (the bending moment of area is half).
    pub polar_moment: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Minimum yield strength, Pa (None: no utilisation).
    pub yield_strength: Option<f64>,
    /// Make-up torque of the tool joints, N m (None: not checked).
    pub makeup_torque: Option<f64>,
    /// Length of one joint, m (the side force per joint is the normal force times it).
    pub joint_length: f64,
}

impl Body {
    /// `E I`, N m^2.
    pub fn bending_stiffness(&self) -> f64 {
        self.youngs_modulus * self.polar_moment / 2.0
    }
}

/// The hole: diameters from the surface down (`sections`: each `(bottom_md, diameter)`, in
/// order) and `diameter` below the last.
#[derive(Debug, Clone, PartialEq)]
pub struct Hole {
    pub sections: Vec<(f64, f64)>,
    pub diameter: f64,
}

impl Hole {
    /// The hole's diameter at `md`, m.
    pub fn at(&self, md: f64) -> f64 {
        self.sections.iter().find(|s| md < s.0).map_or(self.diameter, |s| s.1)
    }
}

/// The radial clearance between a hole of diameter `hole` and a pipe body of diameter `od`, m.
pub fn clearance(hole: f64, od: f64) -> f64 {
    (hole - od) / 2.0
}

/// Dawson & Paslay's sinusoidal buckling load `2 sqrt(E I n / r_c)`, N, of the bending
/// stiffness `ei` (N m^2), lateral load per length `n` (N/m) and radial clearance `rc` (m).
pub fn sinusoidal_load(ei: f64, n: f64, rc: f64) -> f64 {
    2.0 * (ei * n / rc).sqrt()
}

/// Chen, Lin & Cheatham's helical buckling load `2 sqrt(2) sqrt(E I n / r_c)`, N.
pub fn helical_load(ei: f64, n: f64, rc: f64) -> f64 {
    2.0 * SQRT_2 * (ei * n / rc).sqrt()
}

/// Mitchell's extra wall contact force per length of a helically buckled string under the
/// compression `f` (N), `r_c f^2 / (4 E I)`, N/m.
pub fn helical_contact(ei: f64, f: f64, rc: f64) -> f64 {
    rc * f * f / (4.0 * ei)
}

/// The von Mises stress of the axial force `f` (N) and torque `m` (N m) on a body of area `a`,
/// polar moment `j` and outer radius `r`: `sqrt((f / a)^2 + 3 (m r / j)^2)`, Pa.
pub fn von_mises(f: f64, m: f64, a: f64, j: f64, r: f64) -> f64 {
    let (s, t) = (f / a, m * r / j);
    (s * s + 3.0 * t * t).sqrt()
}

/// The sinusoidal and helical critical loads (N) of a string of bending stiffness `ei`, buoyed
/// weight per length `w` and radial clearance `rc` at a point of direction `tangent` and
/// curvature vector `kappa` (see the module's convention).
pub fn critical_loads(ei: f64, w: f64, rc: f64, tangent: [f64; 3], kappa: [f64; 3]) -> (f64, f64) {
    let t = tangent;
    let a = [-w * t[2] * t[0], -w * t[2] * t[1], w * (1.0 - t[2] * t[2])];
    let vertical = (ei * w * w).abs().cbrt();
    let curved = kappa.iter().any(|&k| k != 0.0);
    let load = |c: f64| -> f64 {
        if !curved {
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            return c * (ei * n / rc).sqrt();
        }
        smallest_root(c * c * ei / rc, a, kappa)
    };
    let (s, h) = (load(2.0), load(2.0 * SQRT_2));
    (s.max(VERTICAL_SINUSOIDAL * vertical), h.max(VERTICAL_HELICAL * vertical))
}

/// The smallest `F > 0` with `F^2 = k |a - F b|`: scanned for the first sign change up to a
/// bound that holds it, then Newton's method on `g(F) = F^2 - k |a - F b|` kept inside the
/// bracket (a bisection where a step would leave it) to the rounding.
fn smallest_root(k: f64, a: [f64; 3], b: [f64; 3]) -> f64 {
    let norm = |f: f64| {
        let v = [a[0] - f * b[0], a[1] - f * b[1], a[2] - f * b[2]];
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    };
    let g = |f: f64| f * f - k * norm(f);
    let ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (na, bb) = ((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt(), b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    let nb = bb.sqrt();
    // F^2 <= k (|a| + F |b|) at a root
    let hi = 0.5 * (k * nb + (k * k * nb * nb + 4.0 * k * na).sqrt()) * (1.0 + 1e-12) + f64::MIN_POSITIVE;
    const SCAN: usize = 16;
    let (mut lo, mut up) = (0.0, hi);
    for s in 1..=SCAN {
        let f = hi * s as f64 / SCAN as f64;
        if g(f) >= 0.0 {
            up = f;
            break;
        }
        lo = f;
    }
    // g(lo) < 0 <= g(up); d|a - F b|/dF = (F |b|^2 - a.b) / |a - F b|
    let mut x = up;
    for _ in 0..200 {
        let r = norm(x);
        let gx = x * x - k * r;
        if gx >= 0.0 {
            up = x;
        } else {
            lo = x;
        }
        let mut next = x - gx / (2.0 * x - k * (x * bb - ab) / r);
        if !(next > lo && next < up) {
            next = 0.5 * (lo + up);
        }
        if (next - x).abs() <= 4.0 * f64::EPSILON * x || next <= lo || next >= up {
            return next.clamp(lo, up);
        }
        x = next;
    }
    up
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 5 in 19.50 lb/ft pipe (4.276 in bore), E 207 GPa, in an 8.5 in hole.
    fn pipe() -> (f64, f64) {
        let (od, id): (f64, f64) = (0.127, 4.276 * 0.0254);
        let i = std::f64::consts::PI / 64.0 * (od.powi(4) - id.powi(4));
        (207e9 * i, clearance(8.5 * 0.0254, od))
    }

    #[test]
    fn straight_hole_loads_are_dawson_paslay_and_chen() {
        let (ei, rc) = pipe();
        let (w, inc) = (240.0, 30f64.to_radians());
        let t = [inc.sin(), 0.0, inc.cos()];
        let (s, h) = critical_loads(ei, w, rc, t, [0.0; 3]);
        let ds = 2.0 * (ei * w * inc.sin() / rc).sqrt();
        assert_eq!(s, ds);
        assert!((h / s - 2f64.sqrt()).abs() < 1e-15);
        // vertical: the own-weight loads
        let (s, h) = critical_loads(ei, w, rc, [0.0, 0.0, 1.0], [0.0; 3]);
        assert!((s - 2.55 * (ei * w * w).cbrt()).abs() < 1e-9 * s && (h - 5.55 * (ei * w * w).cbrt()).abs() < 1e-9 * h);
    }

    /// In a build in a vertical plane the root is the quadratic's closed form; a drop lowers it.
    #[test]
    fn build_closed_form_and_drop_lower() {
        let (ei, rc) = pipe();
        let (w, inc, radius) = (240.0, 40f64.to_radians(), 300.0);
        let t = [inc.sin(), 0.0, inc.cos()];
        // a build turns the direction toward the horizontal: kappa points to the high side
        let up = [inc.cos() / radius, 0.0, -inc.sin() / radius];
        let (s, _) = critical_loads(ei, w, rc, t, up);
        let closed = 2.0 * ei / (rc * radius) * (1.0 + (1.0 + rc * radius * radius * w * inc.sin() / ei).sqrt());
        assert!((s - closed).abs() < 1e-12 * closed, "{s} vs {closed}");
        let (drop, _) = critical_loads(ei, w, rc, t, [-up[0], 0.0, -up[2]]);
        let (straight, _) = critical_loads(ei, w, rc, t, [0.0; 3]);
        assert!(drop < straight && straight < s);
    }

    /// In a horizontal turn the curve's pull is across the weight: `|a - F b|^2 = |a|^2 +
    /// F^2 |b|^2`, so `F^2 = (k^2 |b|^2 + sqrt(k^4 |b|^4 + 4 k^2 |a|^2)) / 2` with `k = 4 E I / r_c`.
    #[test]
    fn horizontal_turn_closed_form() {
        let (ei, rc) = pipe();
        let (w, radius) = (240.0, 250.0);
        let (s, h) = critical_loads(ei, w, rc, [1.0, 0.0, 0.0], [0.0, 1.0 / radius, 0.0]);
        for (load, c) in [(s, 2.0), (h, 2.0 * SQRT_2)] {
            let k = c * c * ei / rc;
            let kb = k / radius;
            let closed = (0.5 * (kb * kb + (kb.powi(4) + 4.0 * k * k * w * w).sqrt())).sqrt();
            assert!((load - closed).abs() < 1e-12 * closed, "{load} vs {closed}");
        }
    }

    #[test]
    fn von_mises_and_contact() {
        let (a, j, r) = (3.4e-3, 1.2e-5, 0.0635);
        assert_eq!(von_mises(1e6, 0.0, a, j, r), 1e6 / a);
        let tau = 3e4 * r / j;
        assert!((von_mises(0.0, 3e4, a, j, r) - 3f64.sqrt() * tau).abs() < 1e-6);
        assert_eq!(helical_contact(2.0, 4.0, 0.5), 1.0);
        assert_eq!(Mode::of(5.0, 4.0, 6.0), Mode::Sinusoidal);
    }
}

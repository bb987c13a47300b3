//! Bindings of the physical model: section properties and the coefficients `k1 .. k6`.

use drillstring_core::model::{self, CrossSection, K5Variant, Model, Physical};
use pyo3::prelude::*;

use crate::convert::{to_python, validation_error};

/// Section properties of the annulus `D`, `d` (m): `area`, `polar_moment`, `i_r`, `i_x2y2`, `j4`.
#[pyfunction]
pub(crate) fn section<'py>(py: Python<'py>, outer_diameter: f64, inner_diameter: f64) -> PyResult<Bound<'py, PyAny>> {
    let s = CrossSection::annulus(outer_diameter, inner_diameter).map_err(|e| validation_error(py, e))?;
    to_python(py, &s)
}

/// Shear modulus `G = E / (2 (1 + nu))`, Pa.
#[pyfunction]
pub(crate) fn shear_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    model::shear_modulus(youngs_modulus, poisson_ratio)
}

/// P-wave modulus `lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu))`, Pa.
#[pyfunction]
pub(crate) fn p_wave_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    model::p_wave_modulus(youngs_modulus, poisson_ratio)
}

/// Longitudinal bar speed `sqrt(E / rho)`, m/s.
#[pyfunction]
pub(crate) fn bar_speed(youngs_modulus: f64, density: f64) -> f64 {
    model::bar_speed(youngs_modulus, density)
}

/// The rotation term `k6 = (k6 / Omega^2) Omega^2` (0 without rotation softening), N.
#[pyfunction]
pub(crate) fn k6(k6_per_omega_squared: f64, omega: f64) -> f64 {
    model::k6(k6_per_omega_squared, omega)
}

/// The viscous damping rate `c` (1/s) if it is finite and `>= 0`, else a `ValidationError`
/// naming `damping_rate` (the rule of the damping term).
#[pyfunction]
pub(crate) fn check_damping_rate(py: Python<'_>, damping_rate: f64) -> PyResult<f64> {
    let term = drillstring_core::terms::ViscousDamping::new(damping_rate).map_err(|e| validation_error(py, e))?;
    Ok(term.rate())
}

/// `k1 .. k6` and `k6_per_omega_squared` of `model` (`"paper"`, `"consistent"`) for the
/// physical inputs, with the sign of `k5` of the paper model from `k5_variant`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn coefficients<'py>(
    py: Python<'py>,
    youngs_modulus: f64,
    density: f64,
    poisson_ratio: f64,
    outer_diameter: f64,
    inner_diameter: f64,
    omega: f64,
    k5_variant: &str,
    model: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let err = |e| validation_error(py, e);
    let which = Model::parse(model).map_err(err)?;
    let k5 = K5Variant::parse(k5_variant).map_err(err)?;
    let p = Physical { youngs_modulus, density, poisson_ratio, outer_diameter, inner_diameter, omega };
    to_python(py, &model::coefficients(&p, which, k5).map_err(err)?)
}

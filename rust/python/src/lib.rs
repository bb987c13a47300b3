//! `drillstring._core`: the PyO3 bindings of `drillstring-core`.
//!
//! This crate only converts: numpy arrays in and out, core errors to
//! `drillstring.errors.ValidationError`, panics to `RuntimeError`; every solve runs with the
//! GIL released. No numerics here. One file per bound concept. No `unsafe` code of its own
//! (denied below; PyO3's macros allow it in what they generate).

#![deny(unsafe_code)]

use pyo3::prelude::*;

mod config;
mod convert;
mod drill_map;
mod drilling;
mod galerkin;
mod lumped;
mod metrics;
mod modal;
mod model;
mod options;
mod pde;
mod session;
mod signal;
mod stability;
mod sweep;
mod tuning;
mod well;

/// The vector instruction path of the core's hot loops on this machine: `"avx512+fma"`,
/// `"avx2+fma"` or `"baseline"` (`DRILLSTRING_SIMD=avx2` or `=baseline` pins a narrower one).
#[pyfunction]
fn simd_path() -> &'static str {
    drillstring_core::simd::path()
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<modal::ModalSystem>()?;
    m.add_function(wrap_pyfunction!(modal::solve_modal, m)?)?;
    m.add_function(wrap_pyfunction!(modal::resolve_evaluation, m)?)?;
    m.add_function(wrap_pyfunction!(modal::resolve_method, m)?)?;
    m.add("AUTO_RKN12_MAX_RTOL", drillstring_core::integrators::AUTO_RKN12_MAX_RTOL)?;
    m.add_function(wrap_pyfunction!(model::section, m)?)?;
    m.add_function(wrap_pyfunction!(model::shear_modulus, m)?)?;
    m.add_function(wrap_pyfunction!(model::p_wave_modulus, m)?)?;
    m.add_function(wrap_pyfunction!(model::bar_speed, m)?)?;
    m.add_function(wrap_pyfunction!(model::coefficients, m)?)?;
    m.add_function(wrap_pyfunction!(model::k6, m)?)?;
    m.add_function(wrap_pyfunction!(model::check_damping_rate, m)?)?;
    m.add_function(wrap_pyfunction!(stability::frequency_squared, m)?)?;
    m.add_function(wrap_pyfunction!(stability::linear_frequencies, m)?)?;
    m.add_function(wrap_pyfunction!(stability::wave_speed, m)?)?;
    m.add_function(wrap_pyfunction!(stability::critical_speeds, m)?)?;
    m.add_function(wrap_pyfunction!(stability::wave_speed_squared_of_rates, m)?)?;
    m.add_function(wrap_pyfunction!(stability::modal_rates, m)?)?;
    m.add_function(wrap_pyfunction!(stability::duffing, m)?)?;
    m.add_function(wrap_pyfunction!(stability::modal_jacobian, m)?)?;
    m.add_function(wrap_pyfunction!(stability::modal_stability, m)?)?;
    m.add_function(wrap_pyfunction!(stability::mode_shapes, m)?)?;
    m.add_class::<pde::PdeSystem>()?;
    m.add_function(wrap_pyfunction!(pde::solve_pde, m)?)?;
    m.add("PDE_MAX_NODES", drillstring_core::pde::MAX_NODES)?;
    m.add_function(wrap_pyfunction!(sweep::batch_solve, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::batch_plan, m)?)?;
    m.add("MAX_THREADS", drillstring_core::sweep::MAX_THREADS)?;
    m.add_function(wrap_pyfunction!(sweep::scale_integrals, m)?)?;
    m.add_function(wrap_pyfunction!(galerkin::galerkin_integrals, m)?)?;
    m.add("GALERKIN_MAX_MODES", drillstring_core::galerkin::MAX_MODES)?;
    m.add("SPECTRAL_MIN_MODES", drillstring_core::modal::SPECTRAL_MIN_MODES)?;
    m.add_function(wrap_pyfunction!(metrics::spectral_peaks, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::energy_drift, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::modal_energies, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::stick_slip_metrics, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::break_off_torque, m)?)?;
    m.add_function(wrap_pyfunction!(tuning::recommend_controllers, m)?)?;
    m.add("STICK_SPEED", drillstring_core::metrics::STICK_SPEED)?;
    m.add("STICK_SLIP_CRITERION", drillstring_core::metrics::STICK_SLIP_CRITERION)?;
    m.add("SPECTRAL_PAD", drillstring_core::metrics::PAD)?;
    m.add("PEAK_THRESHOLD", drillstring_core::metrics::PEAK_THRESHOLD)?;
    m.add_function(wrap_pyfunction!(drilling::drill_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(drilling::drill_validate, m)?)?;
    m.add_function(wrap_pyfunction!(drilling::drill_profile, m)?)?;
    m.add_function(wrap_pyfunction!(drilling::drill_solve, m)?)?;
    m.add_class::<session::DrillSession>()?;
    m.add_function(wrap_pyfunction!(drilling::drill_compare, m)?)?;
    m.add_function(wrap_pyfunction!(drilling::drill_compare_tolerances, m)?)?;
    m.add_function(wrap_pyfunction!(drilling::drill_outputs, m)?)?;
    m.add_function(wrap_pyfunction!(config::drill_config_override, m)?)?;
    m.add_function(wrap_pyfunction!(config::drill_config_schema, m)?)?;
    m.add_function(wrap_pyfunction!(config::parameters_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(config::parameters_validate, m)?)?;
    m.add_function(wrap_pyfunction!(drill_map::drill_map, m)?)?;
    m.add_function(wrap_pyfunction!(drill_map::drill_map_check_axes, m)?)?;
    drill_map::add_constants(m)?;
    m.add_function(wrap_pyfunction!(lumped::lumped_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::lumped_solve, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::lumped_equilibria, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::min_cycle_torque, m)?)?;
    m.add_function(wrap_pyfunction!(well::well_trajectory, m)?)?;
    m.add_function(wrap_pyfunction!(well::well_torque_drag, m)?)?;
    m.add_function(wrap_pyfunction!(well::well_implied_friction, m)?)?;
    m.add_function(wrap_pyfunction!(signal::crossing_phase, m)?)?;
    m.add_function(wrap_pyfunction!(signal::phase_shift, m)?)?;
    m.add_function(wrap_pyfunction!(signal::amplitude_growth, m)?)?;
    m.add_function(wrap_pyfunction!(signal::is_bounded, m)?)?;
    m.add_function(wrap_pyfunction!(signal::modulation_depth, m)?)?;
    m.add_function(wrap_pyfunction!(signal::hull_area, m)?)?;
    m.add_function(wrap_pyfunction!(signal::phase_fill, m)?)?;
    m.add_function(wrap_pyfunction!(signal::ellipk, m)?)?;
    m.add_function(wrap_pyfunction!(signal::duffing_amplitude, m)?)?;
    m.add_function(wrap_pyfunction!(signal::duffing_frequency, m)?)?;
    m.add("BOUNDED_GROWTH", drillstring_core::metrics::signal::BOUNDED_GROWTH)?;
    m.add("PHASE_FILL_BINS", drillstring_core::metrics::signal::PHASE_FILL_BINS)?;
    m.add_function(wrap_pyfunction!(options::fixed_steps, m)?)?;
    m.add_function(wrap_pyfunction!(options::fastest_mode, m)?)?;
    m.add_function(wrap_pyfunction!(options::default_fixed_dt, m)?)?;
    m.add_function(wrap_pyfunction!(options::default_section, m)?)?;
    m.add("ADAPTIVE_MAX_STEPS", drillstring_core::options::ADAPTIVE_MAX_STEPS)?;
    m.add("FIXED_MAX_STEPS", drillstring_core::options::FIXED_MAX_STEPS)?;
    m.add("MAX_STEP_COUNT", drillstring_core::options::MAX_STEP_COUNT)?;
    m.add("DEFAULT_FIXED_DT", drillstring_core::options::DEFAULT_FIXED_DT)?;
    m.add("STEPS_PER_PERIOD", drillstring_core::options::STEPS_PER_PERIOD)?;
    m.add("PDE_CFL_SHARE", drillstring_core::pde::CFL_SHARE)?;
    m.add("PDE_MIN_RESOLVED_MODES", drillstring_core::pde::MIN_RESOLVED_MODES)?;
    m.add("PDE_MODE_CONTENT_SHARE", drillstring_core::pde::MODE_CONTENT_SHARE)?;
    m.add_function(wrap_pyfunction!(simd_path, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

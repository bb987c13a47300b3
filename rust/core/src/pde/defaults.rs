//! The defaults a PDE solve derives from its grid and initial state: the fixed step (a share of
//! the CFL limit) and the mode the default output times resolve.

use std::f64::consts::PI;

use realfft::RealFftPlanner;

use super::PdeSystem;
use crate::error::{Error, Result};

/// The default step of the fixed-step methods is this share of the CFL limit `h / c`.
pub const CFL_SHARE: f64 = 0.5;

/// The default output times of a PDE solve resolve at least this many modes.
pub const MIN_RESOLVED_MODES: usize = 3;

/// A cosine mode of the initial state counts (for the default output times) when its amplitude,
/// in velocity units, is at least this share of the largest one.
pub const MODE_CONTENT_SHARE: f64 = 1e-3;

impl PdeSystem {
    /// The default step of the fixed-step methods: [`CFL_SHARE`] of the CFL limit `h / c` of the
    /// explicit schemes, `c = sqrt(k2 / k1)` the linear wave speed.
    pub fn default_dt(&self) -> f64 {
        let k = self.coefficients();
        CFL_SHARE * self.spacing() / (k.k2 / k.k1).sqrt()
    }

    /// The linearised `w_i^2 = (k2 (i pi / l)^2 - k6) / k1` (rad^2/s^2) of the continuum mode
    /// `cos(i pi z / l)`, which bounds the grid's own.
    pub fn continuum_frequency_squared(&self, i: usize) -> f64 {
        let k = self.coefficients();
        let wavenumber = i as f64 * PI / self.length();
        (k.k2 * (wavenumber * wavenumber) - k.k6) / k.k1
    }

    /// The mode the default output times resolve and its rate (rad/s): the highest cosine mode
    /// `cos(i pi z / l)` of the initial state (the nodal fields' discrete cosine transform; the
    /// twist's amplitude times `w_i`, or the velocity's, at least [`MODE_CONTENT_SHARE`] of the
    /// largest; the rigid mode 0 left out), at least [`MIN_RESOLVED_MODES`] and at most
    /// `nodes - 1`, with its continuum rate `sqrt(|w_i^2|)`
    /// ([`PdeSystem::continuum_frequency_squared`]). `twist` and `velocity` hold one value per
    /// node (else refused, naming them).
    pub fn fastest_mode(&self, twist: &[f64], velocity: &[f64]) -> Result<(usize, f64)> {
        let n = self.nodes();
        for (field, values) in [("initial_twist", twist), ("initial_velocity", velocity)] {
            if values.len() != n {
                return Err(Error::invalid(
                    field,
                    format!("length {}", values.len()),
                    format!("length {n} (one per node)"),
                ));
            }
        }
        let rate = |i: usize| self.continuum_frequency_squared(i).abs().sqrt();
        let twist = cosine_amplitudes(twist);
        let velocity = cosine_amplitudes(velocity);
        let content: Vec<f64> =
            (0..n).map(|i| if i == 0 { 0.0 } else { (twist[i] * rate(i)).max(velocity[i]) }).collect();
        let top = content.iter().copied().fold(0.0f64, f64::max);
        let highest =
            if top > 0.0 { content.iter().rposition(|&c| c >= MODE_CONTENT_SHARE * top).unwrap_or(0) } else { 0 };
        let mode = highest.max(MIN_RESOLVED_MODES).min(n - 1);
        Ok((mode, rate(mode)))
    }
}

/// `|X_i|`, `i < n`, of the discrete cosine transform (type I) of the `n` nodal values: the real
/// FFT of their even extension `f_0 .. f_{n-1} f_{n-2} .. f_1`.
fn cosine_amplitudes(field: &[f64]) -> Vec<f64> {
    let n = field.len();
    let mut even: Vec<f64> = field.iter().chain(field[1..n - 1].iter().rev()).copied().collect();
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(even.len());
    let mut spectrum = fft.make_output_vec();
    fft.process(&mut even, &mut spectrum).expect("buffers of the planned lengths");
    spectrum.iter().take(n).map(|c| c.norm()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn system(nodes: usize) -> PdeSystem {
        // k1 = 2, k2 = 8: c = 2 m/s; k6 = 1
        PdeSystem::new([2.0, 8.0, 0.0, 0.0, 0.0, 1.0], 10.0, nodes).unwrap()
    }

    #[test]
    fn default_dt_is_half_the_cfl_limit() {
        // h = 10 / 20 = 0.5 m, h / c = 0.25 s
        assert_eq!(system(21).default_dt(), 0.125);
    }

    #[test]
    fn fastest_mode_is_the_highest_cosine_mode_present() {
        let sys = system(101);
        let z = sys.positions();
        let mode = |i: f64| z.iter().map(|&s| (i * PI * s / 10.0).cos()).collect::<Vec<f64>>();
        let zero = vec![0.0; z.len()];
        let w = |i: usize| ((8.0 * (i as f64 * PI / 10.0).powi(2) - 1.0) / 2.0f64).abs().sqrt();
        // a velocity in modes 1 and 7: mode 7
        let v: Vec<f64> = mode(1.0).iter().zip(mode(7.0)).map(|(a, b)| a + 0.01 * b).collect();
        let (m, rate) = sys.fastest_mode(&zero, &v).unwrap();
        assert_eq!(m, 7);
        assert!((rate - w(7)).abs() < 1e-12 * w(7));
        // a twist in mode 5, below the share in mode 9; at rest: mode 5
        let q: Vec<f64> = mode(5.0).iter().zip(mode(9.0)).map(|(a, b)| a + 1e-6 * b).collect();
        assert_eq!(sys.fastest_mode(&q, &zero).unwrap().0, 5);
        // mode 1 only, or nothing: at least MIN_RESOLVED_MODES
        assert_eq!(sys.fastest_mode(&zero, &mode(1.0)).unwrap().0, MIN_RESOLVED_MODES);
        assert_eq!(sys.fastest_mode(&zero, &zero).unwrap().0, MIN_RESOLVED_MODES);
        // the rigid mode (a constant velocity) does not count, however strong
        let spin: Vec<f64> = mode(6.0).iter().map(|b| 300.0 + 0.01 * b).collect();
        assert_eq!(sys.fastest_mode(&zero, &spin).unwrap().0, 6);
        // a three-node grid has modes 0..=2
        let small = system(3);
        assert_eq!(small.fastest_mode(&[0.0; 3], &[1.0, 0.0, -1.0]).unwrap().0, 2);
        assert_eq!(sys.fastest_mode(&zero[1..], &zero).unwrap_err().field(), "initial_twist");
    }
}

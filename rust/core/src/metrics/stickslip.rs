//! Stick-slip metrics of a sampled bit-speed (and motor-torque) series, uniformly or
//! non-uniformly sampled, from any source (a simulation or field data).
//!
//! * [`stick_slip`] over a window `[t_start, t_end]`: the samples with
//!   `t_start <= t <= t_end` (no interpolation at the window's ends; at least 2 samples);
//!   time-weighted means by the trapezoidal rule; the series is taken as linear between samples.
//!   - severity `SSI = (max - min) / (2 |mean|)` of the bit speed (NaN when the mean is 0);
//!   - stuck fraction: the fraction of the window's time with `|omega_bit| <= stick_speed`
//!     (exact for the piecewise-linear series);
//!   - bit speed min / max / mean in rpm (`rad/s * 60 / (2 pi)`);
//!   - motor torque min / max and cycle period: the mean interval between the upward crossings
//!     of the motor torque through its time-weighted mean (crossing times linearly
//!     interpolated), a crossing within 0.6 spectral periods (the strongest peak of the
//!     torque's spectrum) of the last one counted not counted: a wiggle on a slope of a
//!     stick-slip cycle crosses the mean too; NaN with fewer than three counted crossings (two
//!     full cycles). Without a torque series these are NaN.
//! * [`break_off_torque`]: the static break-off torque of a well, the integral over measured
//!   depth of the friction limit per metre (trapezoidal).

use crate::error::{Error, Num, Result};
use crate::metrics::FrequencyEstimator;

/// Default stick threshold speed, rad/s (about 0.1 rpm): the bit counts as stuck while
/// `|omega_bit|` is at most this.
pub const STICK_SPEED: f64 = 1e-2;

/// Radians per second to revolutions per minute.
const RPM_PER_RAD_S: f64 = 60.0 / (2.0 * std::f64::consts::PI);

/// The stick-slip metrics of one window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickSlip {
    /// First and last sample time in the window, s.
    pub t_start: f64,
    pub t_end: f64,
    /// `(max - min) / (2 |mean|)` of the bit speed; NaN when the mean is 0.
    pub severity: f64,
    /// Fraction of the window's time with `|omega_bit| <= stick_speed`.
    pub stuck_fraction: f64,
    pub rpm_min: f64,
    pub rpm_max: f64,
    /// Time-weighted (trapezoidal) mean, rpm.
    pub rpm_mean: f64,
    /// NaN without a motor torque series.
    pub torque_min: f64,
    pub torque_max: f64,
    /// Mean interval between upward mean-crossings of the motor torque (one per cycle: see
    /// the module), s; NaN with fewer than two full cycles or without a torque series.
    pub cycle_period: f64,
}

fn finite_values(field: &str, x: &[f64], n: usize) -> Result<()> {
    if x.len() != n {
        return Err(Error::invalid(field, format!("length {}", x.len()), format!("length {n} (one per time sample)")));
    }
    if let Some(v) = x.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid(field, format!("a value {}", Num(*v)), "finite values"));
    }
    Ok(())
}

fn increasing(field: &str, t: &[f64]) -> Result<()> {
    if t.len() < 2 {
        return Err(Error::invalid(field, format!("{} samples", t.len()), "at least 2 samples"));
    }
    if let Some(v) = t.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid(field, format!("a value {}", Num(*v)), "finite, strictly increasing values"));
    }
    if let Some(j) = t.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::invalid(
            field,
            format!("{} after {} at index {}", Num(t[j + 1]), Num(t[j]), j + 1),
            "finite, strictly increasing values",
        ));
    }
    Ok(())
}

/// Trapezoidal integral of `x` over the strictly increasing `t`.
fn trapezoid(t: &[f64], x: &[f64]) -> f64 {
    t.windows(2).zip(x.windows(2)).map(|(t, x)| 0.5 * (t[1] - t[0]) * (x[0] + x[1])).sum()
}

/// Time-weighted mean of `x` (trapezoidal) over `t` (at least 2 samples).
fn time_mean(t: &[f64], x: &[f64]) -> f64 {
    trapezoid(t, x) / (t[t.len() - 1] - t[0])
}

/// Time during which the linear interpolant of `x` has `|x| <= s`.
fn time_within(t: &[f64], x: &[f64], s: f64) -> f64 {
    t.windows(2)
        .zip(x.windows(2))
        .map(|(t, x)| {
            let (u, v, dt) = (x[0], x[1], t[1] - t[0]);
            if u == v {
                return if u.abs() <= s { dt } else { 0.0 };
            }
            let (a, b) = ((-s - u) / (v - u), (s - u) / (v - u));
            let (lo, hi) = (a.min(b).max(0.0), a.max(b).min(1.0));
            (hi - lo).max(0.0) * dt
        })
        .sum()
}

/// The cycle period of `x`: the mean interval between its upward crossings through its
/// time-weighted mean (linear interpolation), where a crossing less than 0.6 spectral
/// periods after the last one counted is not counted (a wiggle on a slope of the cycle, not a new
/// cycle); NaN with fewer than three counted crossings.
///
/// The spectral period is that of the strongest peak of the Hann-windowed spectrum
/// ([`FrequencyEstimator::dominant_frequency`]) of `x` on a uniform grid of as many samples
/// (linear interpolation when `t` is not uniform). Without a peak every crossing counts.
fn cycle_period(t: &[f64], x: &[f64]) -> f64 {
    let mean = time_mean(t, x);
    let min_gap = 0.6 * spectral_period(t, x);
    let mut first = None;
    let mut last = f64::NAN;
    let mut count = 0usize;
    for (t, x) in t.windows(2).zip(x.windows(2)) {
        let (u, v) = (x[0] - mean, x[1] - mean);
        if u < 0.0 && v >= 0.0 {
            let tc = t[0] + (t[1] - t[0]) * (-u) / (v - u);
            // NaN min_gap (no spectral peak): the comparison is false, every crossing counts
            if count > 0 && tc - last < min_gap {
                continue;
            }
            first.get_or_insert(tc);
            last = tc;
            count += 1;
        }
    }
    match first {
        Some(t0) if count >= 3 => (last - t0) / (count - 1) as f64,
        _ => f64::NAN,
    }
}

/// `1 / f` of the strongest spectral peak of `x` sampled at `t` (see [`cycle_period`]); NaN
/// without a peak.
fn spectral_period(t: &[f64], x: &[f64]) -> f64 {
    let n = t.len();
    if n < 4 {
        return f64::NAN;
    }
    let dt = (t[n - 1] - t[0]) / (n - 1) as f64;
    let uniform = t.iter().enumerate().all(|(j, &tj)| (tj - (t[0] + j as f64 * dt)).abs() <= 1e-9 * dt.max(tj.abs()));
    let resampled: Vec<f64>;
    let xs: &[f64] = if uniform {
        x
    } else {
        let mut k = 0;
        resampled = (0..n)
            .map(|j| {
                let tj = if j + 1 == n { t[n - 1] } else { t[0] + j as f64 * dt };
                while k + 2 < n && t[k + 1] < tj {
                    k += 1;
                }
                let s = ((tj - t[k]) / (t[k + 1] - t[k])).clamp(0.0, 1.0);
                x[k] + s * (x[k + 1] - x[k])
            })
            .collect();
        &resampled
    };
    let estimator = FrequencyEstimator::new(n);
    let f = estimator.dominant_frequency(xs, dt, &mut estimator.buffers());
    if f > 0.0 {
        1.0 / f
    } else {
        f64::NAN
    }
}

/// The stick-slip metrics (see the module) of the bit speed `omega_bit` (rad/s) and optionally
/// the motor torque (N m) sampled at the strictly increasing times `t` (s), over the samples in
/// `window = (t_start, t_end)` (None: all). An error naming the argument for: `t` not finite
/// and strictly increasing or with fewer than 2 samples, a series of another length or with
/// non-finite values, a window not `t_start < t_end` (finite) or holding fewer than 2 samples,
/// `stick_speed` not finite and `>= 0`.
pub fn stick_slip(
    t: &[f64],
    omega_bit: &[f64],
    motor_torque: Option<&[f64]>,
    window: Option<(f64, f64)>,
    stick_speed: f64,
) -> Result<StickSlip> {
    increasing("t", t)?;
    finite_values("omega_bit", omega_bit, t.len())?;
    if let Some(m) = motor_torque {
        finite_values("motor_torque", m, t.len())?;
    }
    if !(stick_speed.is_finite() && stick_speed >= 0.0) {
        return Err(Error::invalid("stick_speed", Num(stick_speed), "a finite speed >= 0 rad/s"));
    }
    let (lo, hi) = match window {
        None => (0, t.len()),
        Some((a, b)) => {
            if !(a.is_finite() && b.is_finite() && a < b) {
                return Err(Error::invalid(
                    "window",
                    format!("({}, {})", Num(a), Num(b)),
                    "finite (t_start, t_end) with t_start < t_end",
                ));
            }
            let lo = t.partition_point(|&v| v < a);
            let hi = t.partition_point(|&v| v <= b);
            if hi < lo + 2 {
                return Err(Error::invalid(
                    "window",
                    format!("({}, {}) holding {} samples", Num(a), Num(b), hi.saturating_sub(lo)),
                    format!("a window holding at least 2 samples of t in [{}, {}]", Num(t[0]), Num(t[t.len() - 1])),
                ));
            }
            (lo, hi)
        }
    };
    let tw = &t[lo..hi];
    let w = &omega_bit[lo..hi];
    let min = w.iter().copied().fold(f64::INFINITY, f64::min);
    let max = w.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mean = time_mean(tw, w);
    let span = tw[tw.len() - 1] - tw[0];
    let severity = if mean == 0.0 { f64::NAN } else { (max - min) / (2.0 * mean.abs()) };
    let (torque_min, torque_max, cycle_period) = match motor_torque {
        None => (f64::NAN, f64::NAN, f64::NAN),
        Some(m) => {
            let m = &m[lo..hi];
            (
                m.iter().copied().fold(f64::INFINITY, f64::min),
                m.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                cycle_period(tw, m),
            )
        }
    };
    Ok(StickSlip {
        t_start: tw[0],
        t_end: tw[tw.len() - 1],
        severity,
        stuck_fraction: (time_within(tw, w, stick_speed) / span).min(1.0),
        rpm_min: min * RPM_PER_RAD_S,
        rpm_max: max * RPM_PER_RAD_S,
        rpm_mean: mean * RPM_PER_RAD_S,
        torque_min,
        torque_max,
        cycle_period,
    })
}

/// The static break-off torque of a well, N m: the trapezoidal integral over the strictly
/// increasing measured depths `depth` (m) of the friction limit per metre `limit` (N m/m,
/// finite and `>= 0`, one per depth).
pub fn break_off_torque(depth: &[f64], limit: &[f64]) -> Result<f64> {
    increasing("depth", depth)?;
    finite_values("limit", limit, depth.len())?;
    if let Some(v) = limit.iter().find(|v| **v < 0.0) {
        return Err(Error::invalid("limit", format!("a value {}", Num(*v)), "finite values >= 0 N m/m"));
    }
    Ok(trapezoid(depth, limit))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn grid(n: usize, end: f64) -> Vec<f64> {
        (0..n).map(|j| end * j as f64 / (n - 1) as f64).collect()
    }

    /// A stick-slip-like torque: a slow build-up over 80 % of each 10 s cycle and a fast drop,
    /// with a wiggle that crosses the mean several times on the way up. One cycle counts once.
    #[test]
    fn wiggles_on_a_slope_are_not_cycles() {
        let period = 10.0;
        let t = grid(6001, 60.0);
        let torque: Vec<f64> = t
            .iter()
            .map(|&t| {
                let phase = (t / period).fract();
                let saw = if phase < 0.8 { -1.0 + 2.0 * phase / 0.8 } else { 1.0 - 2.0 * (phase - 0.8) / 0.2 };
                saw + 0.1 * (2.0 * PI * t / 0.5).sin()
            })
            .collect();
        let w = vec![1.0; t.len()];
        let mean = time_mean(&t, &torque);
        let crossings = t.windows(2).zip(torque.windows(2)).filter(|(_, x)| x[0] < mean && x[1] >= mean).count();
        assert!(crossings >= 12, "{crossings} upward crossings: the wiggle must cross the mean more than once a cycle");
        let m = stick_slip(&t, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.cycle_period - period).abs() < 1e-9 * period, "{}", m.cycle_period);
        // the same on a non-uniform grid (the spectral estimate resamples)
        let tn: Vec<f64> = t.iter().map(|&t| t + 0.003 * (t * 7.0).sin()).collect();
        let m = stick_slip(&tn, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.cycle_period - period).abs() < 2e-3 * period, "{}", m.cycle_period);
    }

    #[test]
    fn sinusoidal_speed() {
        // omega = w0 (1 + a sin(2 pi f t)) over 5 whole periods: SSI = a, never stuck
        let (w0, a, f) = (10.0, 0.6, 2.0);
        let t = grid(20001, 2.5);
        let w: Vec<f64> = t.iter().map(|t| w0 * (1.0 + a * (2.0 * PI * f * t).sin())).collect();
        let torque: Vec<f64> = t.iter().map(|t| 5.0 + 3.0 * (2.0 * PI * f * t).cos()).collect();
        let m = stick_slip(&t, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.severity - a).abs() < 1e-6, "{}", m.severity);
        assert_eq!(m.stuck_fraction, 0.0);
        assert!((m.rpm_mean - w0 * RPM_PER_RAD_S).abs() < 1e-9);
        assert!((m.rpm_max - w0 * (1.0 + a) * RPM_PER_RAD_S).abs() < 1e-6);
        assert!((m.torque_min - 2.0).abs() < 1e-6 && (m.torque_max - 8.0).abs() < 1e-6);
        assert!((m.cycle_period - 1.0 / f).abs() < 1e-9, "{}", m.cycle_period);
        assert!(stick_slip(&t, &w, None, None, STICK_SPEED).unwrap().cycle_period.is_nan());
    }

    #[test]
    fn clipped_speed_is_stuck_for_the_arccos_fraction() {
        // omega = max(0, w0 (1 + a sin)), a > 1: stuck while sin < -1/a
        let (w0, a, f) = (10.0, 2.0, 1.0);
        let t: Vec<f64> = (0..40001).map(|j| 4.0 * (j as f64 / 40000.0).powf(1.1)).collect(); // non-uniform
        let w: Vec<f64> = t.iter().map(|t| (w0 * (1.0 + a * (2.0 * PI * f * t).sin())).max(0.0)).collect();
        let m = stick_slip(&t, &w, None, None, 0.0).unwrap();
        let expected = (1.0 / a).acos() / PI;
        assert!((m.stuck_fraction - expected).abs() < 3e-4, "{} vs {expected}", m.stuck_fraction);
        // mean of max(0, 1 + a sin) over a period: (sqrt(a^2 - 1) + (pi - arccos(1/a))) / pi
        let mean = w0 * ((a * a - 1.0).sqrt() + PI - (1.0 / a).acos()) / PI;
        assert!((m.rpm_mean / RPM_PER_RAD_S - mean).abs() < 1e-4 * mean);
        assert!((m.severity - w0 * (1.0 + a) / (2.0 * mean)).abs() < 1e-4);
    }

    #[test]
    fn square_wave_and_window() {
        // 0 for a quarter, 4 rad/s for three quarters of each period (1 s), sharp edges
        let t = grid(40001, 4.0);
        let w: Vec<f64> = t.iter().map(|t| if t.fract() < 0.25 { 0.0 } else { 4.0 }).collect();
        let m = stick_slip(&t, &w, Some(&w), Some((0.0, 3.9999)), STICK_SPEED).unwrap();
        assert!((m.stuck_fraction - 0.25).abs() < 1e-3, "{}", m.stuck_fraction);
        assert!((m.severity - 4.0 / (2.0 * 3.0)).abs() < 2e-3, "{}", m.severity);
        assert!((m.cycle_period - 1.0).abs() < 1e-9);
        let late = stick_slip(&t, &w, None, Some((2.5, 2.9)), STICK_SPEED).unwrap();
        assert_eq!((late.stuck_fraction, late.t_start), (0.0, 2.5));
        assert!((late.t_end - 2.9).abs() < 1e-12);
        assert!(late.severity.abs() < 1e-15);
        let zero = stick_slip(&t, &vec![0.0; t.len()], None, None, STICK_SPEED).unwrap();
        assert!(zero.severity.is_nan());
        assert_eq!(zero.stuck_fraction, 1.0);
    }

    #[test]
    fn bad_input_names_the_argument() {
        let t = [0.0, 1.0, 2.0];
        let w = [1.0, 2.0, 3.0];
        let field = |r: Result<StickSlip>| r.unwrap_err().field().to_string();
        assert_eq!(field(stick_slip(&[0.0, 1.0, 1.0], &w, None, None, 0.1)), "t");
        assert_eq!(field(stick_slip(&[0.0], &[1.0], None, None, 0.1)), "t");
        assert_eq!(field(stick_slip(&t, &w[..2], None, None, 0.1)), "omega_bit");
        assert_eq!(field(stick_slip(&t, &[1.0, f64::NAN, 1.0], None, None, 0.1)), "omega_bit");
        assert_eq!(field(stick_slip(&t, &w, Some(&[1.0]), None, 0.1)), "motor_torque");
        assert_eq!(field(stick_slip(&t, &w, None, Some((1.5, 1.9)), 0.1)), "window");
        assert_eq!(field(stick_slip(&t, &w, None, Some((2.0, 1.0)), 0.1)), "window");
        assert_eq!(field(stick_slip(&t, &w, None, None, -0.1)), "stick_speed");
        assert_eq!(field(stick_slip(&t, &w, None, None, f64::NAN)), "stick_speed");
    }

    #[test]
    fn break_off_of_a_constant_and_a_linear_limit() {
        let depth = grid(11, 3000.0);
        assert!((break_off_torque(&depth, &[12.5; 11]).unwrap() - 12.5 * 3000.0).abs() < 1e-9);
        let linear: Vec<f64> = depth.iter().map(|d| 0.01 * d).collect();
        assert!((break_off_torque(&depth, &linear).unwrap() - 0.005 * 3000.0 * 3000.0).abs() < 1e-6);
        assert_eq!(break_off_torque(&[0.0, 0.0], &[1.0, 1.0]).unwrap_err().field(), "depth");
        assert_eq!(break_off_torque(&[0.0, 1.0], &[1.0]).unwrap_err().field(), "limit");
        assert_eq!(break_off_torque(&[0.0, 1.0], &[1.0, -1.0]).unwrap_err().field(), "limit");
    }
}

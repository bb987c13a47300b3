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
//!   - motor torque min / max;
//!   - cycle period ([`cycle_period`]): the lag of the first full peak of the motor torque's
//!     autocorrelation (unbiased, mean removed, on a uniform grid of at most
//!     [`PERIOD_SAMPLES`] samples, the peak refined by a parabola), searched up to half the
//!     window, so that it is NaN unless the window holds two cycles; it does not depend on
//!     where the window starts for a periodic signal. `periodicity` is the autocorrelation at
//!     that lag (1 for an exactly periodic series) and `period_cycles` the window's length in
//!     periods. Without a torque series, or for a bit stuck throughout the window (no cycle of
//!     the bit, whatever the torque does), these are NaN;
//!   - the cross-check `slip_period`: the mean interval between the bit's slip onsets (its
//!     speed rising through `stick_speed` in the direction of its mean, linearly
//!     interpolated, for a slip that carries it above its mean speed), NaN with fewer than
//!     three;
//!   - `stick_duration_mean_s` ([`stick_duration_mean`]): the mean duration of the bit's stick
//!     phases (its time with `|omega_bit| <= stick_speed` between two full slips, as the slip
//!     onsets count them: a partial slip inside a stick phase does not end it) that begin and
//!     end inside the window, NaN without a complete one;
//!   - the verdict `stick_slip`: the bit stops (`|omega_bit| <= stick_speed`) during part of
//!     the window, neither never nor always (stuck fraction strictly between 0 and 1);
//!   - the three-way verdict [`Verdict`] with its reason ([`verdict`], the criterion stated by
//!     [`STICK_SLIP_CRITERION`]): `yes` exactly when `stick_slip`, `no` only for a bit that
//!     never stops with SSI below 1 in a settled window (or one whose oscillation decays),
//!     `undetermined` otherwise;
//!   - `settled`: the window holds a steady regime: the first and the last whole periods of the
//!     window (as many as half the window holds; its two halves without a period) have the
//!     same bit-speed and motor-torque
//!     means and ranges, to 5 % of the ranges plus 1 % of the means (and `stick_speed` for
//!     the speed). A transient still decaying inside the window is not settled.
//! * [`StickSlip::warnings`]: what a reader should know before trusting the numbers.
//! * [`break_off_torque`]: the static break-off torque of a well, the integral over measured
//!   depth of the friction limit per metre (trapezoidal).

use std::borrow::Cow;

use serde::Serialize;

use crate::error::{Error, Num, Result};

/// Default stick threshold speed, rad/s (about 0.1 rpm): the bit counts as stuck while
/// `|omega_bit|` is at most this.
pub const STICK_SPEED: f64 = 1e-2;

/// The criterion of [`verdict`], as a report states it.
pub const STICK_SLIP_CRITERION: &str = "yes: the bit stops (|bit speed| <= stick_speed) during part of the \
     metrics window (0 < stuck_fraction < 1); no: the bit never stops (stuck_fraction = 0), the severity SSI is \
     below 1 and the window is settled (its first and last cycles agree) or its bit-speed oscillation decays; \
     undetermined: anything else (no metrics, an undefined SSI, the bit stuck throughout the window, SSI >= 1 \
     without the bit stopping, or a bit-speed oscillation growing through the window by more than 5 %: \
     lengthen the run)";

/// The stick-slip verdict of a window ([`verdict`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    Yes,
    No,
    Undetermined,
}

impl Verdict {
    /// `"yes"`, `"no"` or `"undetermined"`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Yes => "yes",
            Verdict::No => "no",
            Verdict::Undetermined => "undetermined",
        }
    }
}

/// The stick-slip verdict of a window from its stuck fraction, severity (SSI), whether it is
/// settled and whether the bit speed's oscillation grows through it (its range over the last
/// compared part more than 5 % above the first's), with the reason in a few words
/// ([`STICK_SLIP_CRITERION`]):
/// * `yes` when the bit stops during part of the window (`0 < stuck_fraction < 1`), settled
///   or not (it stopped; the `settled` warning says whether the cycle is steady);
/// * `no` when it never stops (`stuck_fraction = 0`), `SSI < 1` and the window is settled or
///   its oscillation decays (a transient dying out below SSI 1 does not stick later);
/// * `undetermined` otherwise: a metric not finite (no window, a mean speed of 0), the bit
///   stuck throughout (it never turns: no stick-slip cycle), `SSI >= 1` without a stop (a
///   severe oscillation the stick threshold does not catch), or an oscillation still growing
///   in the window (it may yet stick: lengthen the run).
pub fn verdict(stuck_fraction: f64, severity: f64, settled: bool, growing: bool) -> (Verdict, &'static str) {
    if !stuck_fraction.is_finite() {
        (Verdict::Undetermined, "no metrics in the window")
    } else if stuck_fraction >= 1.0 {
        (Verdict::Undetermined, "the bit is stuck throughout the window (it never turns)")
    } else if stuck_fraction > 0.0 {
        (Verdict::Yes, "the bit stops during part of the window")
    } else if !severity.is_finite() {
        (Verdict::Undetermined, "the SSI is undefined (mean bit speed 0)")
    } else if severity >= 1.0 {
        (Verdict::Undetermined, "SSI >= 1 but the bit never stops")
    } else if !settled && growing {
        (Verdict::Undetermined, "the bit never stops but its oscillation grows through the window")
    } else if !settled {
        (Verdict::No, "the bit never stops, SSI < 1, the oscillation decays")
    } else {
        (Verdict::No, "the bit never stops, SSI < 1, settled")
    }
}

/// Radians per second to revolutions per minute.
const RPM_PER_RAD_S: f64 = 60.0 / (2.0 * std::f64::consts::PI);

/// The stick-slip metrics of one window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StickSlip {
    /// First and last sample time in the window, s.
    pub window_start: f64,
    pub window_end: f64,
    /// `(max - min) / (2 |mean|)` of the bit speed; NaN when the mean is 0.
    pub ssi: f64,
    /// Fraction of the window's time with `|omega_bit| <= stick_speed`.
    pub stuck_fraction: f64,
    pub bit_rpm_min: f64,
    pub bit_rpm_max: f64,
    /// Time-weighted (trapezoidal) mean, rpm.
    pub bit_rpm_mean: f64,
    /// NaN without a motor torque series.
    #[serde(rename = "motor_torque_min_Nm")]
    pub motor_torque_min_nm: f64,
    #[serde(rename = "motor_torque_max_Nm")]
    pub motor_torque_max_nm: f64,
    /// The autocorrelation period of the motor torque (see the module), s; NaN with fewer than
    /// two cycles in the window, without a clear peak or without a torque series.
    pub period_s: f64,
    /// The window's length in periods (NaN without a period).
    pub period_cycles: f64,
    /// The normalised autocorrelation at the period (1: exactly periodic; NaN without one).
    pub periodicity: f64,
    /// Mean interval between the bit's slip onsets, s (NaN with fewer than three onsets).
    pub slip_period_s: f64,
    /// Slip onsets of the bit in the window.
    pub slip_onsets: usize,
    /// Mean duration of the complete stick phases in the window, s ([`stick_duration_mean`]).
    pub stick_duration_mean_s: f64,
    /// The bit stops during part of the window (stuck fraction strictly between 0 and 1).
    pub stick_slip: bool,
    /// The window holds a steady regime (see the module).
    pub settled: bool,
    /// The three-way verdict ([`verdict`]) and its reason (a drilling run may overrule it with
    /// its own, e.g. a motor at its torque limit: `drilling::plausibility::torque_limit_verdict`).
    pub stick_slip_verdict: Verdict,
    pub stick_slip_reason: Cow<'static, str>,
}

/// Most samples the period estimator uses: a longer window is resampled to this many (the
/// period's resolution is refined below a sample by the parabola), so that its memory is
/// bounded whatever the series' length.
pub const PERIOD_SAMPLES: usize = 1 << 14;

/// Relative agreement the cross-check between the autocorrelation period and the slip period
/// is held to before a warning.
pub const PERIOD_AGREEMENT: f64 = 0.05;

impl StickSlip {
    /// What a window without metrics (fewer than 2 samples) reports: NaN values, no slip
    /// onsets, neither verdict.
    pub const UNDEFINED: StickSlip = StickSlip {
        window_start: f64::NAN,
        window_end: f64::NAN,
        ssi: f64::NAN,
        stuck_fraction: f64::NAN,
        bit_rpm_min: f64::NAN,
        bit_rpm_max: f64::NAN,
        bit_rpm_mean: f64::NAN,
        motor_torque_min_nm: f64::NAN,
        motor_torque_max_nm: f64::NAN,
        period_s: f64::NAN,
        period_cycles: f64::NAN,
        periodicity: f64::NAN,
        slip_period_s: f64::NAN,
        slip_onsets: 0,
        stick_duration_mean_s: f64::NAN,
        stick_slip: false,
        settled: false,
        stick_slip_verdict: Verdict::Undetermined,
        stick_slip_reason: Cow::Borrowed("no metrics in the window"),
    };

    /// Short sentences on what in these metrics cannot be trusted as they stand (empty when
    /// every one can).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if !self.settled {
            out.push(
                "not settled: the first and the last cycle of the metrics window differ by more than 5 % \
                 (a transient, or an irregular motion); lengthen the run or start the window later"
                    .to_string(),
            );
        }
        if self.ssi.is_nan() {
            out.push("ssi undefined: the bit's mean speed over the window is 0".to_string());
        }
        if self.stuck_fraction >= 1.0 {
            out.push("the bit never turns in the window (stuck throughout)".to_string());
        }
        if self.period_s.is_nan()
            && self.stuck_fraction < 1.0
            && self.motor_torque_max_nm.is_finite()
            && self.motor_torque_max_nm > self.motor_torque_min_nm
        {
            out.push("period_s undefined: the window holds fewer than two cycles, or no periodic motion".to_string());
        }
        if self.period_s.is_finite()
            && self.slip_period_s.is_finite()
            && (self.slip_period_s - self.period_s).abs() > PERIOD_AGREEMENT * self.period_s
        {
            out.push(format!(
                "period_s = {} s and the mean interval between slip onsets, {} s, differ by more than {} %",
                Num(self.period_s),
                Num(self.slip_period_s),
                100.0 * PERIOD_AGREEMENT
            ));
        }
        out
    }
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
    t.windows(2).zip(x.windows(2)).map(|(t, x)| stuck_time(x[0], x[1], s, t[1] - t[0])).sum()
}

/// Time during which the linear interpolant of one segment from `u` to `v` over `dt` has
/// `|x| <= s`.
fn stuck_time(u: f64, v: f64, s: f64, dt: f64) -> f64 {
    if u == v {
        return if u.abs() <= s { dt } else { 0.0 };
    }
    let (a, b) = ((-s - u) / (v - u), (s - u) / (v - u));
    let (lo, hi) = (a.min(b).max(0.0), a.max(b).min(1.0));
    (hi - lo).max(0.0) * dt
}

/// The mean duration of the stick phases of `x` over `t` (the linear interpolant), as the slip
/// onsets count cycles: a phase is the time with `|x| <= s` between two full slips, slips that
/// carry the bit above its mean speed `|mean|` in the direction of `mean` (a partial slip, or
/// a short reversal at re-stick, does not end a phase: on fine grids the bit chatters around
/// the stick speed inside one stick phase). Only the phases between two full slips in the
/// window count (one cut by the window's start or end does not); NaN without one. The
/// complete phases and the cut phases' parts add up to the stuck time of [`time_within`].
pub fn stick_duration_mean(t: &[f64], x: &[f64], s: f64, mean: f64) -> f64 {
    let (sign, top) = (if mean < 0.0 { -1.0 } else { 1.0 }, mean.abs().max(s));
    let (mut total, mut count) = (0.0, 0usize);
    // a full slip seen (the next stuck time opens a complete phase), the open phase's stuck time
    let (mut slipped, mut open): (bool, Option<f64>) = (false, None);
    let mut full_slip = |open: &mut Option<f64>, slipped: &mut bool| {
        if let Some(stuck) = open.take().filter(|&stuck| stuck > 0.0) {
            total += stuck;
            count += 1;
        }
        *slipped = true;
    };
    for (t, x) in t.windows(2).zip(x.windows(2)) {
        let (u, v) = (sign * x[0], sign * x[1]);
        if u > top {
            full_slip(&mut open, &mut slipped);
        }
        let stuck = stuck_time(u, v, s, t[1] - t[0]);
        if stuck > 0.0 {
            match open.as_mut() {
                Some(phase) => *phase += stuck,
                None if slipped => open = Some(stuck),
                None => {}
            }
        }
        if v > top {
            full_slip(&mut open, &mut slipped);
        }
    }
    if count == 0 {
        f64::NAN
    } else {
        total / count as f64
    }
}

/// A vector of `n` zeros, or None when the memory cannot be had.
fn zeros<T: Clone + Default>(n: usize) -> Option<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).ok()?;
    v.resize(n, T::default());
    Some(v)
}

/// `x` (sampled at the strictly increasing `t`) on `m` uniform samples from `t[0]` to the last
/// `t`, linearly interpolated; None without memory.
fn resample(t: &[f64], x: &[f64], m: usize) -> Option<Vec<f64>> {
    let n = t.len();
    let dt = (t[n - 1] - t[0]) / (m - 1) as f64;
    let mut y = zeros(m)?;
    let mut k = 0;
    for (j, yj) in y.iter_mut().enumerate() {
        let tj = if j + 1 == m { t[n - 1] } else { t[0] + j as f64 * dt };
        while k + 2 < n && t[k + 1] < tj {
            k += 1;
        }
        let s = ((tj - t[k]) / (t[k + 1] - t[k])).clamp(0.0, 1.0);
        *yj = x[k] + s * (x[k + 1] - x[k]);
    }
    Some(y)
}

/// The autocorrelation period of `x` sampled at `t` and the similarity at it (see the
/// module); NaNs without a period.
///
/// The lag is that of the similarity `s[k] = 1 - mean((y_j - y_{j+k})^2) / (2 var)` over the
/// overlap of the series and its shift (the normalised autocorrelation with the energies of the
/// overlapping parts instead of the whole, as the YIN pitch estimator does, so that the
/// window's ends bias it not): the first local maximum, after `s` first falls below 0, within
/// 80 % of the highest up to half the window, refined by a parabola.
pub fn cycle_period(t: &[f64], x: &[f64]) -> (f64, f64) {
    let none = (f64::NAN, f64::NAN);
    let n = t.len();
    if n < 8 {
        return none;
    }
    let m = n.min(PERIOD_SAMPLES);
    let Some(mut y) = resample(t, x, m) else { return none };
    let dt = (t[n - 1] - t[0]) / (m - 1) as f64;
    let mean = y.iter().sum::<f64>() / m as f64;
    y.iter_mut().for_each(|v| *v -= mean);
    if y.iter().all(|v| v.abs() <= 1e-12 * mean.abs()) {
        return none;
    }
    // Autocorrelation by the real FFT of the series zero-padded to twice its length.
    let len = (2 * m).next_power_of_two();
    let mut planner = realfft::RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(len);
    let inverse = planner.plan_fft_inverse(len);
    let (Some(mut input), Some(mut spectrum)) = (zeros::<f64>(len), zeros(len / 2 + 1)) else { return none };
    input[..m].copy_from_slice(&y);
    if forward.process(&mut input, &mut spectrum).is_err() {
        return none;
    }
    for c in spectrum.iter_mut() {
        *c = realfft::num_complex::Complex::new(c.norm_sqr(), 0.0);
    }
    if inverse.process(&mut spectrum, &mut input).is_err() {
        return none;
    }
    let half = m / 2;
    // The similarity of the series with itself shifted by k samples, from the mean squared
    // difference over the overlap (free of the edge bias of the autocorrelation: exactly 1 at
    // the period of a periodic series): s[k] = 1 - sum (y_j - y_{j+k})^2 / (m - k) / (2 var).
    let mut prefix = Vec::new();
    if prefix.try_reserve_exact(m + 1).is_err() {
        return none;
    }
    prefix.push(0.0);
    let mut acc = 0.0;
    for v in &y {
        acc += v * v;
        prefix.push(acc);
    }
    let var = acc / m as f64;
    if var.is_nan() || var <= 0.0 {
        return none;
    }
    // input[k] = sum_j y_j y_{j+k} (unnormalised inverse FFT: times len).
    let scale = 1.0 / len as f64;
    let r: Vec<f64> = (0..=half)
        .map(|k| {
            let overlap = prefix[m - k] + (prefix[m] - prefix[k]) - 2.0 * input[k] * scale;
            1.0 - overlap / ((m - k) as f64 * 2.0 * var)
        })
        .collect();
    let Some(k0) = r.iter().position(|&v| v < 0.0) else { return none };
    let top = r[k0..half].iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if top.is_nan() || top <= 0.0 {
        return none;
    }
    // The first interior local maximum within 80 % of the highest (not a wiggle, not a
    // multiple of the period).
    let Some(k) = (k0.max(1)..half).find(|&k| r[k] >= 0.8 * top && r[k] >= r[k - 1] && r[k] >= r[k + 1]) else {
        return none;
    };
    let (a, b, c) = (r[k - 1], r[k], r[k + 1]);
    let curvature = a - 2.0 * b + c;
    let delta = if curvature < 0.0 { (0.5 * (a - c) / curvature).clamp(-0.5, 0.5) } else { 0.0 };
    ((k as f64 + delta) * dt, b - 0.25 * (a - c) * delta)
}

/// The slip onsets of the bit: times at which its speed rises through `stick_speed` in the
/// direction of its mean rotation `mean` (linearly interpolated) for a slip that carries it
/// above `|mean|` before it stops again (a partial slip, or a short reversal at re-stick, is
/// no cycle), as (count, mean interval; NaN with fewer than three).
fn slip_onsets(t: &[f64], w: &[f64], stick_speed: f64, mean: f64) -> (usize, f64) {
    let sign = if mean < 0.0 { -1.0 } else { 1.0 };
    let (mut count, mut first, mut last) = (0usize, f64::NAN, f64::NAN);
    let mut pending: Option<f64> = None;
    for (t, w) in t.windows(2).zip(w.windows(2)) {
        let (u, v) = (sign * w[0], sign * w[1]);
        if u <= stick_speed && v > stick_speed {
            pending = Some(t[0] + (t[1] - t[0]) * (stick_speed - u) / (v - u));
        } else if v <= stick_speed {
            pending = None;
        }
        if let Some(tc) = pending.filter(|_| v > mean.abs()) {
            if count == 0 {
                first = tc;
            }
            last = tc;
            count += 1;
            pending = None;
        }
    }
    (count, if count >= 3 { (last - first) / (count - 1) as f64 } else { f64::NAN })
}

/// Minimum, maximum and time-weighted mean of the linear interpolant of `x` over `[a, b]`
/// (inside `t`'s span, `a < b`).
fn segment(t: &[f64], x: &[f64], a: f64, b: f64) -> (f64, f64, f64) {
    let at = |s: f64| {
        let k = t.partition_point(|&v| v < s).clamp(1, t.len() - 1);
        let f = ((s - t[k - 1]) / (t[k] - t[k - 1])).clamp(0.0, 1.0);
        x[k - 1] + f * (x[k] - x[k - 1])
    };
    let lo = t.partition_point(|&v| v <= a);
    let hi = t.partition_point(|&v| v < b);
    let (xa, xb) = (at(a), at(b));
    let (mut min, mut max) = (xa.min(xb), xa.max(xb));
    let mut area = 0.0;
    let (mut tp, mut xp) = (a, xa);
    for j in lo..hi {
        min = min.min(x[j]);
        max = max.max(x[j]);
        area += 0.5 * (t[j] - tp) * (x[j] + xp);
        (tp, xp) = (t[j], x[j]);
    }
    area += 0.5 * (b - tp) * (xb + xp);
    (min, max, area / (b - a))
}

/// The first and the last part of the window that [`settled`] compares: as many whole periods
/// as each half holds (the two halves when `period` is NaN).
fn compared_parts(t: &[f64], period: f64) -> ((f64, f64), (f64, f64)) {
    let (t0, t1) = (t[0], t[t.len() - 1]);
    if period.is_finite() && period < t1 - t0 {
        // as many whole periods as each half holds (a motion that repeats every second cycle
        // compares alike)
        let k = (0.5 * (t1 - t0) / period).floor().max(1.0);
        ((t0, t0 + k * period), (t1 - k * period, t1))
    } else {
        let mid = 0.5 * (t0 + t1);
        ((t0, mid), (mid, t1))
    }
}

/// Whether the bit speed `w` oscillates more at the end of the window than at its start: the
/// range of the last part of [`compared_parts`] exceeds the first's by more than 5 % of it
/// plus `floor`.
fn growing(t: &[f64], w: &[f64], period: f64, floor: f64) -> bool {
    let (first, last) = compared_parts(t, period);
    let (min1, max1, _) = segment(t, w, first.0, first.1);
    let (min2, max2, _) = segment(t, w, last.0, last.1);
    (max2 - min2) > 1.05 * (max1 - min1) + floor
}

/// Whether the window holds a steady regime (see the module): the first and the last
/// `period` (the two halves when NaN) agree in mean and range, for every series.
fn settled(t: &[f64], series: &[(&[f64], f64)], period: f64) -> bool {
    let (first, last) = compared_parts(t, period);
    series.iter().all(|&(x, floor)| {
        let (min1, max1, mean1) = segment(t, x, first.0, first.1);
        let (min2, max2, mean2) = segment(t, x, last.0, last.1);
        let (r1, r2) = (max1 - min1, max2 - min2);
        let tol = 0.05 * r1.max(r2) + 0.01 * mean1.abs().max(mean2.abs()) + floor;
        (r1 - r2).abs() <= tol && (mean1 - mean2).abs() <= tol
    })
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
    let (torque_min, torque_max, (cycle_period, periodicity)) = match motor_torque {
        None => (f64::NAN, f64::NAN, (f64::NAN, f64::NAN)),
        Some(m) => {
            let m = &m[lo..hi];
            (
                m.iter().copied().fold(f64::INFINITY, f64::min),
                m.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                cycle_period(tw, m),
            )
        }
    };
    let stuck_fraction = (time_within(tw, w, stick_speed) / span).min(1.0);
    // a bit that never turns has no stick-slip cycle (the torque may still oscillate above it)
    let (cycle_period, periodicity) =
        if stuck_fraction >= 1.0 { (f64::NAN, f64::NAN) } else { (cycle_period, periodicity) };
    let (slip_onsets, slip_period) = slip_onsets(tw, w, stick_speed, mean);
    let mut series: Vec<(&[f64], f64)> = vec![(w, stick_speed)];
    if let Some(m) = motor_torque {
        series.push((&m[lo..hi], 0.0));
    }
    let settled = settled(tw, &series, cycle_period);
    let growing = !settled && growing(tw, w, cycle_period, stick_speed);
    let (verdict, verdict_reason) = verdict(stuck_fraction, severity, settled, growing);
    Ok(StickSlip {
        window_start: tw[0],
        window_end: tw[tw.len() - 1],
        ssi: severity,
        stuck_fraction,
        bit_rpm_min: min * RPM_PER_RAD_S,
        bit_rpm_max: max * RPM_PER_RAD_S,
        bit_rpm_mean: mean * RPM_PER_RAD_S,
        motor_torque_min_nm: torque_min,
        motor_torque_max_nm: torque_max,
        period_s: cycle_period,
        period_cycles: span / cycle_period,
        periodicity,
        slip_period_s: slip_period,
        slip_onsets,
        stick_duration_mean_s: stick_duration_mean(tw, w, stick_speed, mean),
        stick_slip: stuck_fraction > 0.0 && stuck_fraction < 1.0,
        settled,
        stick_slip_verdict: verdict,
        stick_slip_reason: Cow::Borrowed(verdict_reason),
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

    /// A stick-slip-like sawtooth of period `period`: from -1 up to 1 over the fraction `rise`
    /// of each cycle, then down; and the time since the cycle began.
    fn sawtooth(t: f64, period: f64, rise: f64) -> (f64, f64) {
        let phase = (t / period).fract();
        let saw = if phase < rise { -1.0 + 2.0 * phase / rise } else { 1.0 - 2.0 * (phase - rise) / (1.0 - rise) };
        (saw, phase * period)
    }

    /// A stick-slip-like torque: a slow build-up over 80 % of each 10 s cycle and a fast drop,
    /// with a wiggle that crosses the mean several times on the way up. One cycle counts once.
    #[test]
    fn wiggles_on_a_slope_are_not_cycles() {
        let period = 10.0;
        let t = grid(6001, 60.0);
        let torque: Vec<f64> =
            t.iter().map(|&t| sawtooth(t, period, 0.8).0 + 0.1 * (2.0 * PI * t / 0.5).sin()).collect();
        let w = vec![1.0; t.len()];
        let mean = time_mean(&t, &torque);
        let crossings = t.windows(2).zip(torque.windows(2)).filter(|(_, x)| x[0] < mean && x[1] >= mean).count();
        assert!(crossings >= 12, "{crossings} upward crossings: the wiggle must cross the mean more than once a cycle");
        let m = stick_slip(&t, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.period_s - period).abs() < 1e-6 * period, "{}", m.period_s);
        assert!(m.periodicity > 0.999 && (m.period_cycles - 6.0).abs() < 1e-5, "{m:?}");
        // the same on a non-uniform grid (the spectral estimate resamples)
        let tn: Vec<f64> = t.iter().map(|&t| t + 0.003 * (t * 7.0).sin()).collect();
        let m = stick_slip(&tn, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.period_s - period).abs() < 2e-3 * period, "{}", m.period_s);
    }

    #[test]
    fn sinusoidal_speed() {
        // omega = w0 (1 + a sin(2 pi f t)) over 5 whole periods: SSI = a, never stuck
        let (w0, a, f) = (10.0, 0.6, 2.0);
        let t = grid(20001, 2.5);
        let w: Vec<f64> = t.iter().map(|t| w0 * (1.0 + a * (2.0 * PI * f * t).sin())).collect();
        let torque: Vec<f64> = t.iter().map(|t| 5.0 + 3.0 * (2.0 * PI * f * t).cos()).collect();
        let m = stick_slip(&t, &w, Some(&torque), None, STICK_SPEED).unwrap();
        assert!((m.ssi - a).abs() < 1e-6, "{}", m.ssi);
        assert_eq!(m.stuck_fraction, 0.0);
        assert!((m.bit_rpm_mean - w0 * RPM_PER_RAD_S).abs() < 1e-9);
        assert!((m.bit_rpm_max - w0 * (1.0 + a) * RPM_PER_RAD_S).abs() < 1e-6);
        assert!((m.motor_torque_min_nm - 2.0).abs() < 1e-6 && (m.motor_torque_max_nm - 8.0).abs() < 1e-6);
        assert!((m.period_s - 1.0 / f).abs() < 1e-7, "{}", m.period_s);
        assert!(m.settled && !m.stick_slip && m.slip_onsets == 0 && m.slip_period_s.is_nan(), "{m:?}");
        assert!(stick_slip(&t, &w, None, None, STICK_SPEED).unwrap().period_s.is_nan());
    }

    /// The three-way verdict on series whose stuck fraction, SSI and settling are known by
    /// construction.
    #[test]
    fn the_verdict_follows_its_criterion() {
        let t = grid(20001, 10.0);
        let verdict_of = |w: &[f64]| stick_slip(&t, w, Some(w), None, STICK_SPEED).unwrap();
        // clipped sine (stuck a third of each cycle): yes, and the boolean agrees
        let clipped: Vec<f64> = t.iter().map(|t| (10.0 * (1.0 + 2.0 * (2.0 * PI * t).sin())).max(0.0)).collect();
        let m = verdict_of(&clipped);
        assert!(m.stick_slip && m.stick_slip_verdict == Verdict::Yes, "{m:?}");
        // steady sine with SSI 0.6, never stuck, settled: no
        let soft: Vec<f64> = t.iter().map(|t| 10.0 * (1.0 + 0.6 * (2.0 * PI * t).sin())).collect();
        let m = verdict_of(&soft);
        assert!(m.ssi < 1.0 && m.stuck_fraction == 0.0 && m.settled, "{m:?}");
        assert_eq!((m.stick_slip_verdict, m.stick_slip_verdict.name()), (Verdict::No, "no"));
        // an amplitude growing through the window: not settled, undetermined; decaying: no
        let growing: Vec<f64> = t.iter().map(|t| 10.0 * (1.0 + 0.06 * t * (2.0 * PI * t).sin())).collect();
        let m = verdict_of(&growing);
        assert!(!m.settled && m.stuck_fraction == 0.0 && m.stick_slip_verdict == Verdict::Undetermined, "{m:?}");
        let decaying: Vec<f64> = t.iter().map(|t| 10.0 * (1.0 + 0.06 * (10.0 - t) * (2.0 * PI * t).sin())).collect();
        let m = verdict_of(&decaying);
        assert!(!m.settled && m.ssi < 1.0 && m.stick_slip_verdict == Verdict::No, "{m:?}");
        // SSI above 1 without a stop (tall narrow spikes on a slow turn)
        let spiky: Vec<f64> = t.iter().map(|t| 1.0 + 30.0 * (2.0 * PI * t).sin().max(0.0).powi(8)).collect();
        let m = verdict_of(&spiky);
        assert!(m.ssi > 1.0 && m.stuck_fraction == 0.0 && m.stick_slip_verdict == Verdict::Undetermined, "{m:?}");
        // stuck throughout, and a window with a zero mean speed
        assert_eq!(verdict_of(&vec![0.0; t.len()]).stick_slip_verdict, Verdict::Undetermined);
        assert_eq!(StickSlip::UNDEFINED.stick_slip_verdict, Verdict::Undetermined);
        assert_eq!(verdict(f64::NAN, 0.5, true, false).0, Verdict::Undetermined);
        assert_eq!(verdict(0.0, f64::NAN, true, false).0, Verdict::Undetermined);
        assert_eq!(verdict(0.2, f64::NAN, false, true).0, Verdict::Yes);
        assert_eq!(verdict(0.0, 1.0, true, false).0, Verdict::Undetermined);
        assert_eq!(verdict(0.0, 0.999, true, false).0, Verdict::No);
        assert_eq!(verdict(0.0, 0.5, false, true).0, Verdict::Undetermined);
        assert_eq!(verdict(0.0, 0.5, false, false).0, Verdict::No);
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
        assert!((m.bit_rpm_mean / RPM_PER_RAD_S - mean).abs() < 1e-4 * mean);
        assert!((m.ssi - w0 * (1.0 + a) / (2.0 * mean)).abs() < 1e-4);
    }

    #[test]
    fn square_wave_and_window() {
        // 0 for a quarter, 4 rad/s for three quarters of each period (1 s), sharp edges
        let t = grid(40001, 4.0);
        let w: Vec<f64> = t.iter().map(|t| if t.fract() < 0.25 { 0.0 } else { 4.0 }).collect();
        let m = stick_slip(&t, &w, Some(&w), Some((0.0, 3.9999)), STICK_SPEED).unwrap();
        assert!((m.stuck_fraction - 0.25).abs() < 1e-3, "{}", m.stuck_fraction);
        assert!((m.ssi - 4.0 / (2.0 * 3.0)).abs() < 2e-3, "{}", m.ssi);
        assert!((m.period_s - 1.0).abs() < 1e-4, "{}", m.period_s);
        // slip onsets at 0.25 + k (k = 0..3): three intervals of 1 s
        assert_eq!(m.slip_onsets, 4);
        assert!((m.slip_period_s - 1.0).abs() < 1e-9 && m.stick_slip && m.settled, "{m:?}");
        let late = stick_slip(&t, &w, None, Some((2.5, 2.9)), STICK_SPEED).unwrap();
        assert_eq!((late.stuck_fraction, late.window_start), (0.0, 2.5));
        assert!((late.window_end - 2.9).abs() < 1e-12);
        assert!(late.ssi.abs() < 1e-15);
        let zero = stick_slip(&t, &vec![0.0; t.len()], None, None, STICK_SPEED).unwrap();
        assert!(zero.ssi.is_nan());
        assert_eq!(zero.stuck_fraction, 1.0);
    }

    /// A stick-slip-like torque (slow wind-up, fast drop, a wiggle that crosses the mean 1.4 s
    /// after the main crossing, as the motor torque of Well B does): the period is the same for
    /// every window start, and NaN when the window holds fewer than two cycles.
    #[test]
    fn period_does_not_depend_on_the_window_start() {
        let period = 7.25;
        let t = grid(60001, 60.0);
        let torque: Vec<f64> = t
            .iter()
            .map(|&t| {
                let (saw, since) = sawtooth(t, period, 0.85);
                saw + 0.6 * (-((since - 1.4) / 0.2).powi(2)).exp()
            })
            .collect();
        // the bit turns in the upper part of the cycle only (the wiggle does not free it)
        let w: Vec<f64> = torque.iter().map(|v| (2.0 * (v - 0.3)).max(0.0)).collect();
        for start in [20.0, 20.7, 25.0, 30.0, 33.3] {
            let m = stick_slip(&t, &w, Some(&torque), Some((start, 60.0)), STICK_SPEED).unwrap();
            assert!((m.period_s - period).abs() < 1e-4 * period, "start {start}: {}", m.period_s);
            assert!((m.slip_period_s - period).abs() < 1e-3 * period, "start {start}: {}", m.slip_period_s);
            assert!(m.settled && m.stick_slip, "start {start}: {m:?}");
            assert!(m.warnings().is_empty(), "{:?}", m.warnings());
        }
        // 1.9 cycles: no period, and a warning says why
        let m = stick_slip(&t, &w, Some(&torque), Some((40.0, 40.0 + 1.9 * period)), STICK_SPEED).unwrap();
        assert!(m.period_s.is_nan() && m.period_cycles.is_nan(), "{m:?}");
        assert!(m.warnings().iter().any(|s| s.contains("fewer than two cycles")), "{:?}", m.warnings());
    }

    /// A decaying oscillation is not settled; the same oscillation at constant amplitude is.
    #[test]
    fn a_decaying_transient_is_not_settled() {
        let t = grid(20001, 40.0);
        let decaying: Vec<f64> =
            t.iter().map(|&t| 10.0 + 5.0 * (-t / 10.0).exp() * (2.0 * PI * t / 3.0).sin()).collect();
        let steady: Vec<f64> = t.iter().map(|&t| 10.0 + 5.0 * (2.0 * PI * t / 3.0).sin()).collect();
        let m = stick_slip(&t, &decaying, Some(&decaying), Some((10.0, 40.0)), STICK_SPEED).unwrap();
        assert!(!m.settled && m.warnings().iter().any(|s| s.starts_with("not settled")), "{m:?}");
        let m = stick_slip(&t, &steady, Some(&steady), Some((10.0, 40.0)), STICK_SPEED).unwrap();
        assert!(m.settled && (m.period_s - 3.0).abs() < 1e-6, "{m:?}");
        // steady rotation (no oscillation) is settled, with no period and no warning about it
        let flat = vec![4.0; t.len()];
        let m = stick_slip(&t, &flat, Some(&flat), None, STICK_SPEED).unwrap();
        assert!(m.settled && m.period_s.is_nan() && m.warnings().is_empty(), "{m:?}");
    }

    /// Stick phases of known durations (0.5, 1 and 1.5 s at rest, ramps of 0.1 s to 5 rad/s
    /// between them): each lasts its rest plus the two ramps' parts below the stick speed,
    /// `2 s / 50 s^-1` (linear ramps); a phase cut by the window's start or end does not count.
    #[test]
    fn stick_durations_of_a_known_series() {
        let s = 0.01;
        let rests = [0.5, 1.0, 1.5];
        // knots: a slip of 0.4 s (up 0.1 s, 0.2 s at 5 rad/s, down 0.1 s), then a rest
        let (mut t, mut w) = (vec![0.0], vec![5.0]);
        let mut at = 0.0;
        for rest in rests {
            for (dt, v) in [(0.1, 5.0), (0.1, 0.0), (rest, 0.0)] {
                at += dt;
                t.push(at);
                w.push(v);
            }
        }
        for (dt, v) in [(0.1, 5.0), (0.2, 5.0)] {
            at += dt;
            t.push(at);
            w.push(v);
        }
        let ramp = 2.0 * s / 50.0;
        let expected = rests.iter().map(|r| r + ramp).sum::<f64>() / 3.0;
        let m = stick_slip(&t, &w, None, None, s).unwrap();
        assert!((m.stick_duration_mean_s - expected).abs() < 1e-12, "{} vs {expected}", m.stick_duration_mean_s);
        // the complete phases and the window's share: the same time as the stuck fraction
        let span = t[t.len() - 1] - t[0];
        assert!((3.0 * m.stick_duration_mean_s - m.stuck_fraction * span).abs() < 1e-12);
        // a window starting in the first rest: that phase is cut and does not count
        let late = stick_slip(&t, &w, None, Some((0.5, at)), s).unwrap();
        assert!((late.stick_duration_mean_s - (2.5 + 2.0 * ramp) / 2.0).abs() < 1e-12, "{late:?}");
        // never stuck, stuck throughout, a touch of no duration: NaN
        assert!(stick_slip(&t, &vec![5.0; t.len()], None, None, s).unwrap().stick_duration_mean_s.is_nan());
        assert!(stick_slip(&t, &vec![0.0; t.len()], None, None, s).unwrap().stick_duration_mean_s.is_nan());
        assert!(stick_duration_mean(&[0.0, 1.0, 2.0], &[1.0, s, 1.0], s, 0.5).is_nan());
        // a partial slip inside the second rest (to 0.5 rad/s, below the mean speed, 0.83 rad/s)
        // does not split it: still three phases, of all the stuck time (none is cut)
        let k = t.iter().position(|&x| x > 0.9).unwrap();
        let (mut tc, mut chatter) = (t.clone(), w.clone());
        tc.insert(k, 0.5 * (t[k - 1] + t[k]));
        chatter.insert(k, 0.5);
        let mc = stick_slip(&tc, &chatter, None, None, s).unwrap();
        assert!(mc.bit_rpm_mean / RPM_PER_RAD_S > 0.5, "{mc:?}");
        let within = time_within(&tc, &chatter, s);
        assert!(
            (mc.stick_duration_mean_s - within / 3.0).abs() < 1e-12,
            "{} vs {}",
            mc.stick_duration_mean_s,
            within / 3.0
        );
    }

    /// The period estimator's memory is bounded: a long series is resampled.
    #[test]
    fn a_long_series_is_resampled() {
        let n = 40 * PERIOD_SAMPLES + 1;
        let t = grid(n, 10.0);
        let x: Vec<f64> = t.iter().map(|&t| (2.0 * PI * t / 0.7).sin()).collect();
        assert!((cycle_period(&t, &x).0 - 0.7).abs() < 1e-5);
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

//! Signal metrics of a sampled response, what the paper report and its checks read:
//!
//! * [`crossing_phase`] and [`phase_shift`]: the accumulated phase of an oscillation from its
//!   zero crossings (`k pi` at the `k`-th crossing, linear between crossings) and the phase of
//!   one record relative to another;
//! * [`amplitude_growth`] and [`is_bounded`]: `max |x|` over the last half of a record over
//!   that of the first half, and whether the record looks bounded;
//! * [`modulation_depth`]: `1 - min/max` of the half-cycle peaks of each sign;
//! * [`hull_area`] and [`phase_fill`]: the area of the convex hull of a phase-plane
//!   trajectory, and the share of the cells of a grid over that hull the trajectory passes
//!   through;
//! * [`ellipk`], [`duffing_amplitude`], [`duffing_frequency`]: the exact turning point and
//!   frequency of the one-mode model `x'' + w2 x + beta x^3 = 0` (complete elliptic integral by
//!   the arithmetic-geometric mean).

use std::f64::consts::PI;

use crate::error::{Error, Num, Result};

/// Default cells per axis of the grid of [`phase_fill`].
pub const PHASE_FILL_BINS: usize = 32;

/// Default largest [`amplitude_growth`] that [`is_bounded`] accepts.
pub const BOUNDED_GROWTH: f64 = 1.5;

/// The zero-crossing times of `x(t)` and the phase (rad) there: `k pi` at the `k`-th crossing
/// (linear interpolation between the samples around it; a sample `x >= 0` counts as positive)
/// plus the phase at `t[0]`, extrapolated from the first half period,
/// `pi (1 - (t_1 - t[0]) / (t_2 - t_1))`. Both vectors start with `t[0]` and that phase.
/// Fewer than two crossings are refused (field `"x"`), and so are `t` and `x` of other lengths.
pub fn crossing_phase(t: &[f64], x: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    same_length(t, x)?;
    let crossings: Vec<usize> = (1..x.len()).filter(|&i| (x[i - 1] >= 0.0) != (x[i] >= 0.0)).map(|i| i - 1).collect();
    if crossings.len() < 2 {
        return Err(Error::invalid("x", format!("{} zero crossings", crossings.len()), "at least two zero crossings"));
    }
    let mut times = Vec::with_capacity(crossings.len() + 1);
    times.push(t[0]);
    times.extend(crossings.iter().map(|&i| {
        let (x0, x1) = (x[i], x[i + 1]);
        t[i] + (t[i + 1] - t[i]) * (x0 / (x0 - x1))
    }));
    let start = PI * (1.0 - (times[1] - t[0]) / (times[2] - times[1]));
    let phases = std::iter::once(start).chain((1..times.len()).map(|k| start + PI * k as f64)).collect();
    Ok((times, phases))
}

/// The phase of a crossing record ([`crossing_phase`]) at `at`: linear between the crossings,
/// the first phase before `t[0]`, extrapolated with the last half period after the last
/// crossing (interpolation as numpy's `interp`).
fn phase_at(times: &[f64], phases: &[f64], at: f64) -> f64 {
    let n = times.len();
    let last = n - 1;
    if at > times[last] {
        let slope = (phases[last] - phases[last - 1]) / (times[last] - times[last - 1]);
        return phases[last] + slope * (at - times[last]);
    }
    if at.is_nan() {
        return f64::NAN;
    }
    if at < times[0] {
        return phases[0];
    }
    let j = times.partition_point(|&s| s <= at) - 1;
    if j == last || times[j] == at {
        return phases[j];
    }
    let slope = (phases[j + 1] - phases[j]) / (times[j + 1] - times[j]);
    let value = slope * (at - times[j]) + phases[j];
    if !value.is_nan() {
        return value;
    }
    let other = slope * (at - times[j + 1]) + phases[j + 1];
    if other.is_nan() && phases[j] == phases[j + 1] {
        phases[j]
    } else {
        other
    }
}

/// The accumulated phase (rad) of `x` minus that of `x_ref` at each time of `at`, both sampled
/// at the times `t` ([`crossing_phase`]); positive when `x` runs ahead.
pub fn phase_shift(t: &[f64], x_ref: &[f64], x: &[f64], at: &[f64]) -> Result<Vec<f64>> {
    let (times_ref, phases_ref) = crossing_phase(t, x_ref)?;
    let (times_x, phases_x) = crossing_phase(t, x)?;
    Ok(at.iter().map(|&s| phase_at(&times_x, &phases_x, s) - phase_at(&times_ref, &phases_ref, s)).collect())
}

/// `max |x|` over the last half of the record (from sample `n / 2` on) divided by `max |x|`
/// over the first half: `inf` with a non-finite sample (a blown-up solution) or a first half
/// identically zero (NaN when both halves are). Fewer than 2 samples are refused (field `"x"`).
pub fn amplitude_growth(x: &[f64]) -> Result<f64> {
    if x.len() < 2 {
        return Err(Error::invalid("x", format!("{} samples", x.len()), "at least 2 samples"));
    }
    if !x.iter().all(|v| v.is_finite()) {
        return Ok(f64::INFINITY);
    }
    let (first, last) = x.split_at(x.len() / 2);
    let (first, last) = (super::max_abs(first), super::max_abs(last));
    if first == 0.0 {
        return Ok(if last == 0.0 { f64::NAN } else { f64::INFINITY });
    }
    Ok(last / first)
}

/// Whether the record looks bounded: finite, [`amplitude_growth`] `<= factor` (default
/// [`BOUNDED_GROWTH`]), and `max |x| <= limit` when a limit is given.
pub fn is_bounded(x: &[f64], factor: f64, limit: Option<f64>) -> Result<bool> {
    let growth = amplitude_growth(x)?;
    if !growth.is_finite() || growth > factor {
        return Ok(false);
    }
    Ok(limit.is_none_or(|limit| super::max_abs(x) <= limit))
}

/// Depth `1 - min/max` of the envelope of the half-cycle peaks: 0 for a constant envelope.
/// A half-cycle peak is the largest `|x|` between two successive zero crossings (the partial
/// half cycles at both ends are left out), positive and negative half cycles taken separately
/// and the larger depth returned. NaN with fewer than two complete half cycles of each sign.
pub fn modulation_depth(x: &[f64]) -> f64 {
    let cuts: Vec<usize> = (1..x.len()).filter(|&i| (x[i - 1] >= 0.0) != (x[i] >= 0.0)).collect();
    if cuts.len() < 5 {
        return f64::NAN;
    }
    let mut depth = f64::NEG_INFINITY;
    for positive in [true, false] {
        let peaks: Vec<f64> = cuts
            .windows(2)
            .filter(|w| (x[w[0]] >= 0.0) == positive)
            .map(|w| x[w[0]..w[1]].iter().fold(f64::NEG_INFINITY, |m, v| m.max(v.abs())))
            .collect();
        let top = peaks.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if peaks.len() < 2 || top <= 0.0 {
            return f64::NAN;
        }
        let low = peaks.iter().copied().fold(f64::INFINITY, f64::min);
        depth = depth.max(1.0 - low / top);
    }
    depth
}

/// Area of the convex hull of the points `(x_k, y_k)` (Andrew's monotone chain over the
/// distinct points; 0 for fewer than three), in units `x * y`. `x` and `y` of other lengths
/// are refused (field `"y"`).
pub fn hull_area(x: &[f64], y: &[f64]) -> Result<f64> {
    if x.len() != y.len() {
        return Err(Error::invalid("y", format!("length {}", y.len()), format!("length {} (as x)", x.len())));
    }
    // + 0.0 makes -0.0 equal to 0.0 for the ordering
    let mut points: Vec<(f64, f64)> = x.iter().zip(y).map(|(&a, &b)| (a + 0.0, b + 0.0)).collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    points.dedup();
    if points.len() < 3 {
        return Ok(0.0);
    }
    let chain = |points: &mut dyn Iterator<Item = (f64, f64)>| {
        let mut chain: Vec<(f64, f64)> = Vec::new();
        for (px, py) in points {
            while let [.., (ax, ay), (bx, by)] = chain[..] {
                if (bx - ax) * (py - ay) - (by - ay) * (px - ax) > 0.0 {
                    break;
                }
                chain.pop();
            }
            chain.push((px, py));
        }
        chain.pop();
        chain
    };
    let mut hull = chain(&mut points.iter().copied());
    hull.extend(chain(&mut points.iter().rev().copied()));
    // the shoelace formula: sum x_k y_{k+1} - sum y_k x_{k+1}, cyclically
    let next = hull.iter().cycle().skip(1);
    let (forward, backward) =
        hull.iter().zip(next).fold((0.0, 0.0), |(f, b), (&(x0, y0), &(x1, y1))| (f + x0 * y1, b + y0 * x1));
    Ok(0.5 * (forward - backward).abs())
}

/// Share of the cells of a `bins x bins` grid over the trajectory's convex hull that the
/// trajectory `(x_k, y_k)` passes through, samples joined by straight segments (each
/// subdivided into pieces shorter than half a cell). Scale-free: each axis is normalised to the
/// bounding box; about `2.5 / bins` for one closed curve such as an ellipse, approaching 1 for
/// an orbit that sweeps its whole region; 0 when either coordinate is constant. Refused: fewer
/// than 3 samples or `x`, `y` of other lengths (field `"x"`), `bins < 1` (field `"bins"`).
pub fn phase_fill(x: &[f64], y: &[f64], bins: usize) -> Result<f64> {
    if x.len() < 3 || x.len() != y.len() {
        return Err(Error::invalid("x", format!("{} samples", x.len()), "x and y of equal length >= 3"));
    }
    if bins == 0 {
        return Err(Error::invalid("bins", 0, "an integer >= 1"));
    }
    let scaled = |v: &[f64]| -> Option<Vec<f64>> {
        let low = v.iter().copied().fold(f64::INFINITY, f64::min);
        let span = v.iter().copied().fold(f64::NEG_INFINITY, f64::max) - low;
        (span != 0.0).then(|| v.iter().map(|&a| (a - low) / span * bins as f64 * (1.0 - 1e-12)).collect())
    };
    let (Some(u), Some(v)) = (scaled(x), scaled(y)) else {
        return Ok(0.0);
    };
    let widest = |w: &[f64]| w.windows(2).fold(f64::NEG_INFINITY, |m, p| m.max((p[1] - p[0]).abs()));
    let steps = (2.0 * widest(&u).max(widest(&v))).ceil() as usize + 1;
    let fraction = 1.0 / steps as f64;
    let mut visited = vec![false; bins * bins];
    let mut visit = |a: f64, b: f64| visited[(a as usize) * bins + b as usize] = true;
    for k in 0..u.len() - 1 {
        let (du, dv) = (u[k + 1] - u[k], v[k + 1] - v[k]);
        for s in 0..steps {
            let f = s as f64 * fraction;
            visit(u[k] + du * f, v[k] + dv * f);
        }
    }
    visit(u[u.len() - 1], v[v.len() - 1]);
    let count = visited.iter().filter(|&&c| c).count() as f64;
    // cells whose centre lies inside the hull: the hull's area in cells, approximately
    let hull_cells = hull_area(&u, &v)?.max(1.0);
    Ok((count / hull_cells).min(1.0))
}

/// The complete elliptic integral of the first kind `K(m) = int_0^{pi/2} (1 - m sin^2)^(-1/2)`
/// (parameter `m = k^2 < 1`, else refused, field `"m"`), by the arithmetic-geometric mean:
/// `pi / (2 agm(1, sqrt(1 - m)))`.
pub fn ellipk(m: f64) -> Result<f64> {
    if m.is_nan() || m >= 1.0 {
        return Err(Error::invalid("m", Num(m), "m < 1"));
    }
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..60 {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    Ok(PI / (2.0 * a))
}

/// The turning point `A` of `x'' + omega2 x + beta x^3 = 0` started at `x = 0`, `x' = v`,
/// from the energy `v^2/2 = omega2 A^2/2 + beta A^4/4`. A softening oscillator
/// (`beta < 0`) started above its separatrix has none (refused, field `"velocity"`).
pub fn duffing_amplitude(omega2: f64, beta: f64, velocity: f64) -> Result<f64> {
    if beta == 0.0 {
        return Ok(velocity.abs() / omega2.sqrt());
    }
    let disc = omega2 * omega2 + 2.0 * beta * velocity * velocity;
    if disc < 0.0 {
        return Err(Error::invalid("velocity", Num(velocity), "below the separatrix of the softening oscillator"));
    }
    // A^2 = (-omega2 + sqrt(disc)) / beta, written without cancellation
    Ok((2.0 * velocity * velocity / (omega2 + disc.sqrt())).sqrt())
}

/// The exact frequency (Hz) of `x'' + omega2 x + beta x^3 = 0` oscillating with amplitude `A`:
/// period `T = 4 K(m) / sqrt(omega2 + beta A^2)`, `m = beta A^2 / (2 (omega2 + beta A^2))`.
/// `omega2 + beta A^2 <= 0` (no oscillation) is refused (field `"amplitude"`).
pub fn duffing_frequency(omega2: f64, beta: f64, amplitude: f64) -> Result<f64> {
    let stiff = omega2 + beta * amplitude * amplitude;
    if stiff.is_nan() || stiff <= 0.0 {
        return Err(Error::invalid("amplitude", Num(amplitude), "omega2 + beta A^2 > 0"));
    }
    let m = beta * amplitude * amplitude / (2.0 * stiff);
    Ok(stiff.sqrt() / (4.0 * ellipk(m)?))
}

fn same_length(t: &[f64], x: &[f64]) -> Result<()> {
    if t.len() == x.len() {
        Ok(())
    } else {
        Err(Error::invalid("x", format!("length {}", x.len()), format!("length {} (one per time)", t.len())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize, t_end: f64) -> Vec<f64> {
        (0..n).map(|k| t_end * k as f64 / (n - 1) as f64).collect()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn crossing_phase_of_a_sine_and_a_cosine() {
        let t = grid(10001, 1.0);
        let sine: Vec<f64> = t.iter().map(|&s| (2.0 * PI * 5.0 * s + 0.3).sin()).collect();
        let (times, phases) = crossing_phase(&t, &sine).unwrap();
        // sin(w t + 0.3) crosses zero at w t + 0.3 = k pi: phase 0.3 at t = 0
        assert!((phases[0] - 0.3).abs() < 1e-6, "{}", phases[0]);
        assert_eq!(times.len(), 10 + 1);
        for (k, (&s, &p)) in times.iter().zip(&phases).enumerate().skip(1) {
            assert!((s - (k as f64 * PI - 0.3) / (2.0 * PI * 5.0)).abs() < 1e-8);
            assert!((p - (phases[0] + PI * k as f64)).abs() < 1e-15);
        }
        let flat = vec![1.0; t.len()];
        assert_eq!(crossing_phase(&t, &flat).unwrap_err().field(), "x");
        assert_eq!(crossing_phase(&t[1..], &sine).unwrap_err().field(), "x");
    }

    #[test]
    fn phase_shift_of_two_sines_is_the_frequency_difference() {
        let t = grid(40001, 10.0);
        let a: Vec<f64> = t.iter().map(|&s| (2.0 * PI * 31.0 * s).sin()).collect();
        let b: Vec<f64> = t.iter().map(|&s| (2.0 * PI * 31.5 * s).sin()).collect();
        let shifts = phase_shift(&t, &a, &b, &[1.0, 10.0, 12.0, -1.0]).unwrap();
        assert!(close(shifts[0], 2.0 * PI * 0.5, 1e-4), "{shifts:?}");
        assert!(close(shifts[1], 2.0 * PI * 5.0, 1e-4), "{shifts:?}");
        assert!(close(shifts[2], 2.0 * PI * 6.0, 1e-3), "{shifts:?}"); // extrapolated
        assert!(shifts[3].abs() < 1e-5, "{shifts:?}"); // before t[0]: the start phases, both about 0
    }

    #[test]
    fn growth_of_a_sine_and_an_exponential() {
        let t = grid(2001, 2.0);
        let sine: Vec<f64> = t.iter().map(|&s| (2.0 * PI * 10.0 * s).sin()).collect();
        assert!((amplitude_growth(&sine).unwrap() - 1.0).abs() < 1e-3);
        assert!(is_bounded(&sine, BOUNDED_GROWTH, None).unwrap());
        assert!(!is_bounded(&sine, BOUNDED_GROWTH, Some(0.5)).unwrap());
        let rising: Vec<f64> = t.iter().map(|&s| s.exp()).collect();
        // max over [1, 2] / max over [0, 1) = e^2 / e^(1 - 1/1000)
        assert!(close(amplitude_growth(&rising).unwrap(), (2.0f64 - 0.999).exp(), 1e-12));
        assert!(!is_bounded(&rising, BOUNDED_GROWTH, None).unwrap());
        assert_eq!(amplitude_growth(&[0.0, f64::NAN]).unwrap(), f64::INFINITY);
        assert_eq!(amplitude_growth(&[0.0, 1.0]).unwrap(), f64::INFINITY);
        assert!(amplitude_growth(&[0.0, 0.0]).unwrap().is_nan());
        assert_eq!(amplitude_growth(&[1.0]).unwrap_err().field(), "x");
    }

    #[test]
    fn modulation_depth_of_an_amplitude_modulated_sine() {
        let t = grid(20001, 2.0);
        let steady: Vec<f64> = t.iter().map(|&s| (2.0 * PI * 50.0 * s).sin()).collect();
        assert!(modulation_depth(&steady) < 1e-3);
        // envelope 1 + 0.5 sin: peaks between 0.5 and 1.5, depth 1 - 0.5/1.5
        let am: Vec<f64> =
            t.iter().map(|&s| (1.0 + 0.5 * (2.0 * PI * s).sin()) * (2.0 * PI * 50.0 * s).sin()).collect();
        assert!((modulation_depth(&am) - 2.0 / 3.0).abs() < 0.01, "{}", modulation_depth(&am));
        assert!(modulation_depth(&steady[..300]).is_nan()); // three half cycles
    }

    #[test]
    fn hull_of_a_square_and_an_ellipse() {
        let x = [0.0, 2.0, 2.0, 0.0, 1.0, 1.0, 0.0];
        let y = [0.0, 0.0, 3.0, 3.0, 1.5, 0.0, 0.0];
        assert_eq!(hull_area(&x, &y).unwrap(), 6.0);
        assert_eq!(hull_area(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]).unwrap(), 0.0); // collinear
        assert_eq!(hull_area(&[0.0, 1.0], &[0.0, 1.0]).unwrap(), 0.0);
        let n = 100_000;
        let angle = |k: usize| 2.0 * PI * k as f64 / n as f64;
        let ex: Vec<f64> = (0..n).map(|k| 3.0 * angle(k).cos()).collect();
        let ey: Vec<f64> = (0..n).map(|k| 0.5 * angle(k).sin()).collect();
        // the inscribed n-gon: (n / 2) a b sin(2 pi / n)
        let polygon = 0.5 * n as f64 * 1.5 * (2.0 * PI / n as f64).sin();
        assert!(close(hull_area(&ex, &ey).unwrap(), polygon, 1e-10));
        assert_eq!(hull_area(&ex, &ey[1..]).unwrap_err().field(), "y");
    }

    #[test]
    fn phase_fill_of_a_closed_curve_and_a_dense_orbit() {
        let t = grid(20001, 2.0 * PI);
        let (cx, cy): (Vec<f64>, Vec<f64>) = t.iter().map(|&s| (s.cos(), s.sin())).unzip();
        let fill = phase_fill(&cx, &cy, PHASE_FILL_BINS).unwrap();
        assert!(fill > 2.0 / 32.0 && fill < 0.2, "{fill}");
        let t = grid(200_001, 2000.0);
        let (ox, oy): (Vec<f64>, Vec<f64>) = t.iter().map(|&s| (s.sin(), (2f64.sqrt() * s).sin())).unzip();
        assert!(phase_fill(&ox, &oy, PHASE_FILL_BINS).unwrap() > 0.9);
        assert_eq!(phase_fill(&cx, &vec![1.0; cx.len()], PHASE_FILL_BINS).unwrap(), 0.0);
        assert_eq!(phase_fill(&cx, &cy, 0).unwrap_err().field(), "bins");
        assert_eq!(phase_fill(&cx[..2], &cy[..2], 8).unwrap_err().field(), "x");
    }

    #[test]
    fn ellipk_closed_forms() {
        assert_eq!(ellipk(0.0).unwrap(), PI / 2.0);
        // K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi))
        let gamma_quarter = 3.625_609_908_221_908;
        assert!(close(ellipk(0.5).unwrap(), gamma_quarter * gamma_quarter / (4.0 * PI.sqrt()), 1e-15));
        // K(-1) = K(1/2) / sqrt(2) (the imaginary-modulus transformation)
        assert!(close(ellipk(-1.0).unwrap(), ellipk(0.5).unwrap() / 2f64.sqrt(), 1e-15));
        assert_eq!(ellipk(1.0).unwrap_err().field(), "m");
        assert_eq!(ellipk(f64::NAN).unwrap_err().field(), "m");
    }

    #[test]
    fn duffing_closed_forms() {
        let (w2, beta, v) = (400.0, 3.0e4, 2.0);
        let a = duffing_amplitude(w2, beta, v).unwrap();
        assert!(close(0.5 * w2 * a * a + 0.25 * beta * a.powi(4), 0.5 * v * v, 1e-14));
        assert_eq!(duffing_amplitude(w2, 0.0, -v).unwrap(), v / 20.0);
        assert_eq!(duffing_amplitude(1.0, -1.0, 1.0).unwrap_err().field(), "velocity");
        // linear: w / 2 pi
        assert!(close(duffing_frequency(w2, 0.0, a).unwrap(), 20.0 / (2.0 * PI), 1e-15));
        // pure cubic x'' + x^3 = 0 with A = 1: m = 1/2, T = 4 K(1/2)
        assert!(close(duffing_frequency(0.0, 1.0, 1.0).unwrap(), 1.0 / (4.0 * ellipk(0.5).unwrap()), 1e-15));
        assert_eq!(duffing_frequency(1.0, -1.0, 1.0).unwrap_err().field(), "amplitude");
    }
}

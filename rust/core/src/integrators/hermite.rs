//! Cubic Hermite interpolation between two step points (dense output of the fixed-step
//! methods).
//!
//! On `[t_0, t_0 + h]` with `theta = (t - t_0) / h` the cubic matching `y_0, y_1` and the
//! derivatives `f_0, f_1` is, in the nested form of Hairer's dense output
//! (*Solving ODEs I*, sec. II.6),
//!
//! ```text
//! u(theta) = y_0 + theta (D + (1 - theta) (h f_0 - D + theta (2 D - h (f_0 + f_1)))),
//! D = y_1 - y_0,
//! ```
//!
//! which is `O(h^4)` accurate for smooth solutions.

/// Writes `u(theta)` into `out` (all slices of equal length).
pub(crate) fn hermite(theta: f64, h: f64, y0: &[f64], f0: &[f64], y1: &[f64], f1: &[f64], out: &mut [f64]) {
    let theta1 = 1.0 - theta;
    for i in 0..out.len() {
        let d = y1[i] - y0[i];
        let r1 = h * f0[i] - d;
        let r2 = 2.0 * d - h * (f0[i] + f1[i]);
        out[i] = y0[i] + theta * (d + theta1 * (r1 + theta * r2));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_cubics() {
        // p(t) = 1 - 2 t + 3 t^2 - 0.5 t^3 on [0.5, 2.0].
        let p = |t: f64| 1.0 - 2.0 * t + 3.0 * t * t - 0.5 * t * t * t;
        let dp = |t: f64| -2.0 + 6.0 * t - 1.5 * t * t;
        let (t0, t1) = (0.5, 2.0);
        let h = t1 - t0;
        let mut out = [0.0];
        for k in 0..=10 {
            let t = t0 + h * k as f64 / 10.0;
            hermite((t - t0) / h, h, &[p(t0)], &[dp(t0)], &[p(t1)], &[dp(t1)], &mut out);
            assert!((out[0] - p(t)).abs() < 1e-14, "t = {t}: {} vs {}", out[0], p(t));
        }
    }

    #[test]
    fn error_is_fourth_order() {
        let err = |h: f64| {
            let mut out = [0.0];
            hermite(0.5, h, &[1.0], &[1.0], &[h.exp()], &[h.exp()], &mut out);
            (out[0] - (0.5 * h).exp()).abs()
        };
        let ratio = err(0.1) / err(0.05);
        assert!((ratio.log2() - 4.0).abs() < 0.2, "ratio {ratio}");
    }
}

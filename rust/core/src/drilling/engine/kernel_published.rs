//! The transport kernel of `numerics.source_speed = "before_transport"`: the scheme of
//! torsionalWaveStep.m of Aarsnes & Shor (2018), for reproducing their published runs.
//!
//! The same first-order upwind transport as [`super::kernel::transport`], with the sources
//! evaluated at the speed before the transport, `omega_j = (alpha_j + beta_j) / 2`, where the
//! solver's scheme takes the transported speed `omega*_j`: the damping `-dt d omega_j`, and the
//! wall friction's stick threshold, `|omega_j| < stick_speed` (then the torque that stops the
//! cell at `omega*_j`, clipped to the static limit, [`source`] with the [`SetValued`] law), else the kinetic limit against
//! the sign of `omega_j`, not clipped (it may reverse a cell within a step, as in their code).
//! Scalar, cell by cell; the energy terms are those of [`super::kernel::Sums`] (a source's work
//! `4 e delta (omega* + delta / 2)` per cell holds for any change `delta`, so the ledger closes).

use super::kernel::Sums;
use super::sources::{source, Consts, SetValued, Sources};

/// Upwind transport and the sources at the speed before it of one section: `a`, `b`, `stop`,
/// `slip` padded (`[ghost, cells, ghost]`), the new invariants written to the cells of `an`,
/// `bn` (the arguments of [`super::kernel::transport`]).
#[allow(clippy::too_many_arguments)]
pub fn transport(
    a: &[f64],
    b: &[f64],
    stop: &[f64],
    slip: &[f64],
    an: &mut [f64],
    bn: &mut [f64],
    c: f64,
    src: &Sources,
) -> Sums {
    let n = a.len() - 2;
    let k = Consts::new(c, src);
    // [`source`] with every cell slow and no damping: the change that stops a cell at its
    // transported speed, clipped to the static limit, and whether it sticks.
    let stopping = Consts { c, damping: 0.0, slow_below: f64::INFINITY, kr: k.kr, inv_vr: 0.0 };
    let mut sums = Sums::default();
    for i in 1..=n {
        let (da, db) = (a[i] - a[i - 1], b[i] - b[i + 1]);
        let (a1, b1) = if c < 1.0 { (a[i] - c * da, b[i] - c * db) } else { (a[i - 1], b[i + 1]) };
        let w0 = 0.5 * (a[i] + b[i]);
        let w1 = 0.5 * (a1 + b1);
        let dd = -k.damping * w0;
        let (df, stuck) = if w0.abs() < k.slow_below {
            let (_, df, stuck) = source::<SetValued>(w1 + dd, stop[i], slip[i], &stopping);
            (df, stuck)
        } else if w0 > 0.0 {
            (slip[i], false)
        } else {
            (-slip[i], false)
        };
        let d = dd + df;
        let wbar = w1 + 0.5 * d;
        let s1 = 0.5 * (a1 - b1);
        (an[i], bn[i]) = if stuck { (s1, -s1) } else { (a1 + d, b1 + d) };
        sums.jumps += da * da + db * db;
        sums.friction += df * wbar;
        sums.damping += dd * wbar;
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::config::FrictionModel;

    /// The update of torsionalWaveStep.m written as it is there (per unit `rho J`: the torque
    /// `ci` that stops the cell, clipped to `+-Th`, or `sign(o) fRat Th` when `|o| >= oThres` with
    /// `o` the speed before transport; `alpha -= dt/dx c_t dA + dt S`, `beta += dt/dx c_t dB - dt S`,
    /// `S = kt (alpha + beta) dt + Fc`) against [`transport`]: the same to rounding, on stuck,
    /// slow and sliding cells, at Courant number 0.93 and 1, with and without damping.
    #[test]
    fn the_update_of_torsional_wave_step() {
        let n = 64;
        let len = n + 2;
        let (dts, fr, othr) = (1.0 / 1200.0, 0.65, 1.5);
        let a: Vec<f64> = (0..len).map(|i| (i as f64 * 0.77).sin() * 3.0 + 0.4).collect();
        let b: Vec<f64> = (0..len).map(|i| (i as f64 * 0.31).cos() * 3.0 - 0.2).collect();
        // Th per unit rho J, 1/s^2: from a few times below to above the speeds' changes per step
        let th: Vec<f64> = (0..len).map(|i| 20.0 + 400.0 * ((i * 7) % 11) as f64).collect();
        let stop: Vec<f64> = (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { dts * th[i] }).collect();
        let slip: Vec<f64> = stop.iter().map(|&s| -(fr * s)).collect();
        for (c, kt) in [(0.9291992153906069, 50.0), (1.0, 50.0), (0.93, 0.0)] {
            let src = Sources {
                damping: 2.0 * kt * dts * dts,
                stick_speed: othr,
                kinetic_ratio: fr,
                model: FrictionModel::SetValued,
                regularisation_speed: 0.0,
            };
            let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
            let sums = transport(&a, &b, &stop, &slip, &mut an, &mut bn, c, &src);
            let (mut slow, mut fast, mut stuck) = (0, 0, 0);
            let mut friction = 0.0;
            for i in 1..=n {
                let (d_a, d_b) = (a[i] - a[i - 1], b[i + 1] - b[i]);
                let o = 0.5 * (a[i] + b[i]);
                let vf = dts * kt * (a[i] + b[i]);
                let ci = (a[i] / dts - c / dts * d_a + b[i] / dts + c / dts * d_b - 2.0 * vf) / 2.0;
                let ci = ci.clamp(-th[i], th[i]);
                let fc = if o.abs() < othr { ci } else { o.signum() * th[i] * fr };
                let s = dts * (vf + fc);
                let (a2, b2) = (a[i] - c * d_a - s, b[i] + c * d_b - s);
                let scale = a[i].abs().max(b[i].abs()).max(1.0);
                assert!((an[i] - a2).abs() <= 1e-12 * scale && (bn[i] - b2).abs() <= 1e-12 * scale, "c {c} cell {i}");
                let w1 = 0.5 * (a[i] - c * d_a + b[i] + c * d_b);
                let w2 = 0.5 * (a2 + b2);
                friction += -dts * fc * (w1 + 0.5 * (w2 - w1));
                if o.abs() < othr {
                    slow += 1;
                    stuck += usize::from(an[i] + bn[i] == 0.0);
                } else {
                    fast += 1;
                }
            }
            assert!(slow > 5 && fast > 5 && stuck > 0 && stuck < slow, "{slow} {fast} {stuck}");
            // the friction's work term of the ledger, sum df (w* + d / 2), as their update gives it
            assert!(
                (sums.friction - friction).abs() <= 1e-12 * friction.abs().max(1.0),
                "{} {}",
                sums.friction,
                friction
            );
        }
    }
}

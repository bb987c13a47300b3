//! Sampling a solve at the requested output: every step, or given times through an
//! interpolant of the step that contains them.

use crate::options::Output;
use crate::solution::{Solution, Status};

/// Largest number of values preallocated for the samples (the vectors grow past it).
const MAX_PREALLOCATED_VALUES: usize = 1 << 24;

/// The position in the output request during a solve.
#[derive(Debug, Clone)]
pub(crate) struct Sampler<'a> {
    /// `None` for [`Output::EveryStep`].
    times: Option<&'a [f64]>,
    next: usize,
}

impl<'a> Sampler<'a> {
    pub fn new(output: &'a Output) -> Self {
        match output {
            Output::Times(times) => Sampler { times: Some(times), next: 0 },
            Output::EveryStep => Sampler { times: None, next: 0 },
        }
    }

    /// An empty solution sized for the request (`steps_hint` samples for every-step output),
    /// preallocating at most [`MAX_PREALLOCATED_VALUES`] values.
    pub fn solution(&self, dim: usize, steps_hint: usize) -> Solution {
        let wanted = self.times.map_or(steps_hint, <[f64]>::len);
        let cap = wanted.min(MAX_PREALLOCATED_VALUES / dim.max(1));
        Solution::with_capacity(dim, cap)
    }

    /// Records the initial state: every-step output and requested times equal to `t0`.
    pub fn start(&mut self, sol: &mut Solution, t0: f64, y0: &[f64]) {
        match self.times {
            None => sol.push(t0, y0),
            Some(times) => {
                while self.next < times.len() && times[self.next] <= t0 {
                    sol.push(times[self.next], y0);
                    self.next += 1;
                }
            }
        }
    }

    /// Whether a requested time lies strictly before `t_new` (among those not yet
    /// recorded), i.e. whether the step ending at `t_new` needs its interpolant.
    pub fn needs_interpolant(&self, t_new: f64) -> bool {
        match self.times {
            None => false,
            Some(times) => self.next < times.len() && times[self.next] < t_new,
        }
    }

    /// Records the step ending at `(t_new, y_new)`. Requested times equal to `t_new` get
    /// `y_new` exactly; earlier ones are evaluated by `interp(t, buf)` into `buf`.
    ///
    /// `Err(t)`: the interpolant was not finite at the requested time `t` (an overflow inside a
    /// step whose end points are finite); nothing is recorded from `t` on and the solve must
    /// end (see [`interpolation_failure`]).
    pub fn record(
        &mut self,
        sol: &mut Solution,
        t_new: f64,
        y_new: &[f64],
        buf: &mut [f64],
        mut interp: impl FnMut(f64, &mut [f64]),
    ) -> Result<(), f64> {
        let Some(times) = self.times else {
            sol.push(t_new, y_new);
            return Ok(());
        };
        while self.next < times.len() && times[self.next] <= t_new {
            let t = times[self.next];
            if t == t_new {
                sol.push(t, y_new);
            } else {
                interp(t, buf);
                if !buf.iter().all(|v| v.is_finite()) {
                    return Err(t);
                }
                sol.push(t, buf);
            }
            self.next += 1;
        }
        Ok(())
    }
}

/// The status and message of a solve whose output interpolant overflowed at `t_out` inside the
/// step `t -> t_new`.
pub(crate) fn interpolation_failure(t_out: f64, t: f64, t_new: f64) -> (Status, String) {
    (
        Status::NonFinite,
        format!("the interpolated state became non-finite at the output time {t_out} (step from t = {t} to {t_new})"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_times_exactly_at_step_ends_and_interpolates_inside() {
        let output = Output::Times(vec![0.0, 0.0, 0.5, 1.0, 1.5, 2.0]);
        let mut s = Sampler::new(&output);
        let mut sol = s.solution(1, 0);
        let mut buf = [0.0];
        s.start(&mut sol, 0.0, &[7.0]);
        assert_eq!(sol.t, [0.0, 0.0]);
        assert!(s.needs_interpolant(1.0));
        s.record(&mut sol, 1.0, &[1.0], &mut buf, |t, out| out[0] = -t).unwrap();
        assert!(!s.needs_interpolant(1.5));
        s.record(&mut sol, 1.5, &[3.0], &mut buf, |_, _| panic!("not needed")).unwrap();
        s.record(&mut sol, 2.0, &[4.0], &mut buf, |_, _| panic!("not needed")).unwrap();
        assert_eq!(sol.t, [0.0, 0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(sol.y, [7.0, 7.0, -0.5, 1.0, 3.0, 4.0]);
    }

    #[test]
    fn every_step_records_each_step() {
        let output = Output::EveryStep;
        let mut s = Sampler::new(&output);
        let mut sol = s.solution(1, 4);
        s.start(&mut sol, 0.0, &[1.0]);
        assert!(!s.needs_interpolant(1.0));
        s.record(&mut sol, 1.0, &[2.0], &mut [0.0], |_, _| panic!("no interpolation")).unwrap();
        assert_eq!(sol.t, [0.0, 1.0]);
        assert_eq!(sol.y, [1.0, 2.0]);
    }

    #[test]
    fn a_non_finite_interpolant_is_refused() {
        let output = Output::Times(vec![0.5, 0.7, 1.0]);
        let mut s = Sampler::new(&output);
        let mut sol = s.solution(1, 0);
        s.start(&mut sol, 0.0, &[0.0]);
        let got = s.record(&mut sol, 1.0, &[1.0], &mut [0.0], |t, out| out[0] = if t > 0.6 { f64::NAN } else { t });
        assert_eq!(got, Err(0.7));
        assert_eq!(sol.t, [0.5]);
        let (status, message) = interpolation_failure(0.7, 0.0, 1.0);
        assert_eq!(status, Status::NonFinite);
        assert!(message.contains("0.7"), "{message}");
    }
}

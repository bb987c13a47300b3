//! Sampling a solve at the requested output: every step, or given times through an
//! interpolant of the step that contains them.

use crate::options::Output;
use crate::solution::Solution;

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
    pub fn record(
        &mut self,
        sol: &mut Solution,
        t_new: f64,
        y_new: &[f64],
        buf: &mut [f64],
        mut interp: impl FnMut(f64, &mut [f64]),
    ) {
        let Some(times) = self.times else {
            sol.push(t_new, y_new);
            return;
        };
        while self.next < times.len() && times[self.next] <= t_new {
            let t = times[self.next];
            if t == t_new {
                sol.push(t, y_new);
            } else {
                interp(t, buf);
                sol.push(t, buf);
            }
            self.next += 1;
        }
    }
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
        s.record(&mut sol, 1.0, &[1.0], &mut buf, |t, out| out[0] = -t);
        assert!(!s.needs_interpolant(1.5));
        s.record(&mut sol, 1.5, &[3.0], &mut buf, |_, _| panic!("not needed"));
        s.record(&mut sol, 2.0, &[4.0], &mut buf, |_, _| panic!("not needed"));
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
        s.record(&mut sol, 1.0, &[2.0], &mut [0.0], |_, _| panic!("no interpolation"));
        assert_eq!(sol.t, [0.0, 1.0]);
        assert_eq!(sol.y, [1.0, 2.0]);
    }
}

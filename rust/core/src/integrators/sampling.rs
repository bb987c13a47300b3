//! Sampling a solve at the requested output: every step, or given times through an
//! interpolant of the step that contains them.

use crate::options::Output;
use crate::solution::{Solution, Status};
use crate::Num;

/// Why a sample could not be recorded; the solve must end (see [`record_failure`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RecordError {
    /// The interpolant was not finite at this output time (an overflow inside a step whose
    /// end points are finite).
    NonFinite(f64),
    /// The memory for the sample at this time could not be had (`bytes` of samples).
    OutOfMemory { t: f64, bytes: usize },
}

/// The result of recording the samples of a step.
pub(crate) type Recorded = Result<(), RecordError>;

/// Largest number of values preallocated for the samples (the vectors grow past it).
const MAX_PREALLOCATED_VALUES: usize = 1 << 24;

/// The position in the output request during a solve.
#[derive(Debug, Clone)]
pub(crate) struct OutputSampler<'a> {
    /// `None` for [`Output::EveryStep`].
    times: Option<&'a [f64]>,
    next: usize,
}

impl<'a> OutputSampler<'a> {
    pub fn new(output: &'a Output) -> Self {
        match output {
            Output::Times(times) => OutputSampler { times: Some(times), next: 0 },
            Output::EveryStep => OutputSampler { times: None, next: 0 },
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
    pub fn start(&mut self, sol: &mut Solution, t0: f64, y0: &[f64]) -> Result<(), RecordError> {
        match self.times {
            None => push(sol, t0, y0),
            Some(times) => {
                while self.next < times.len() && times[self.next] <= t0 {
                    push(sol, times[self.next], y0)?;
                    self.next += 1;
                }
                Ok(())
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
    /// `Err`: the interpolant was not finite at a requested time, or the memory for a sample
    /// could not be had; nothing is recorded from there on and the solve must end (see
    /// [`record_failure`]).
    pub fn record(
        &mut self,
        sol: &mut Solution,
        t_new: f64,
        y_new: &[f64],
        buf: &mut [f64],
        mut interp: impl FnMut(f64, &mut [f64]),
    ) -> Result<(), RecordError> {
        let Some(times) = self.times else {
            return push(sol, t_new, y_new);
        };
        while self.next < times.len() && times[self.next] <= t_new {
            let t = times[self.next];
            if t == t_new {
                push(sol, t, y_new)?;
            } else {
                interp(t, buf);
                if !buf.iter().all(|v| v.is_finite()) {
                    return Err(RecordError::NonFinite(t));
                }
                push(sol, t, buf)?;
            }
            self.next += 1;
        }
        Ok(())
    }
}

impl OutputSampler<'_> {
    /// [`OutputSampler::record`] for an interpolant evaluated in blocks: the requested times of the
    /// step strictly before `t_new` are handed to `fill(times, out)` at once, with `out` their
    /// `times.len() x dim` states, reserved in the solution up front and written in place;
    /// requested times equal to `t_new` get `y_new` exactly. Every-step output records `y_new`
    /// (`fill` is not called). Same errors as [`OutputSampler::record`]: samples before a
    /// non-finite one are kept.
    pub fn record_block(
        &mut self,
        sol: &mut Solution,
        t_new: f64,
        y_new: &[f64],
        fill: impl FnOnce(&[f64], &mut [f64]),
    ) -> Result<(), RecordError> {
        let Some(times) = self.times else {
            return push(sol, t_new, y_new);
        };
        let start = self.next;
        let end = start + count_before(&times[start..], t_new);
        if end > start {
            let (m, dim) = (end - start, sol.dim);
            let t_first = times[start];
            sol.t.try_reserve(m).map_err(|_| RecordError::OutOfMemory { t: t_first, bytes: 8 * (sol.t.len() + m) })?;
            let values = m * dim;
            sol.y
                .try_reserve(values)
                .map_err(|_| RecordError::OutOfMemory { t: t_first, bytes: 8 * (sol.y.len() + values) })?;
            let y0 = sol.y.len();
            sol.y.resize(y0 + values, 0.0);
            fill(&times[start..end], &mut sol.y[y0..]);
            if let Some(bad) = first_non_finite(&sol.y[y0..]) {
                let kept = bad / dim.max(1);
                sol.y.truncate(y0 + kept * dim);
                sol.t.extend_from_slice(&times[start..start + kept]);
                self.next = start + kept;
                return Err(RecordError::NonFinite(times[start + kept]));
            }
            sol.t.extend_from_slice(&times[start..end]);
            self.next = end;
        }
        while self.next < times.len() && times[self.next] <= t_new {
            push(sol, t_new, y_new)?;
            self.next += 1;
        }
        Ok(())
    }
}

/// How many of the sorted `times` lie before `t`: a galloping search from the front, whose
/// cost grows with the answer (a step's few samples), not with all the samples still to come
/// (a binary search over those missed the cache once per halving: about a tenth of the
/// sampling time at 200,001 samples).
fn count_before(times: &[f64], t: f64) -> usize {
    let mut hi = 1;
    while hi < times.len() && times[hi - 1] < t {
        hi *= 2;
    }
    let lo = hi / 2;
    let hi = hi.min(times.len());
    lo + times[lo..hi].partition_point(|&s| s < t)
}

/// The index of the first value that is not finite. The common case, all finite, is decided
/// with lanes of `v * 0` (NaN exactly for an infinite or NaN `v`) that vectorise; the
/// position is looked for only when one is not.
fn first_non_finite(values: &[f64]) -> Option<usize> {
    const LANES: usize = 8;
    let mut acc = [0.0_f64; LANES];
    let chunks = values.chunks_exact(LANES);
    let rest = chunks.remainder();
    for chunk in chunks {
        for (a, &v) in acc.iter_mut().zip(chunk) {
            *a += v * 0.0;
        }
    }
    if acc.iter().chain(rest).all(|v| v.is_finite()) {
        return None;
    }
    values.iter().position(|v| !v.is_finite())
}

fn push(sol: &mut Solution, t: f64, y: &[f64]) -> Result<(), RecordError> {
    sol.try_push(t, y).map_err(|e| RecordError::OutOfMemory { t, bytes: e.bytes })
}

/// The status and message of a solve that could not record a sample in the step `t -> t_new`.
pub(crate) fn record_failure(err: RecordError, t: f64, t_new: f64) -> (Status, String) {
    let (t, t_new) = (Num(t), Num(t_new));
    match err {
        RecordError::NonFinite(t_out) => (
            Status::NonFinite,
            format!(
                "the interpolated state became non-finite at the output time {} (step from t = {t} to {t_new})",
                Num(t_out)
            ),
        ),
        RecordError::OutOfMemory { t: t_out, bytes } => (
            Status::OutOfMemory,
            format!(
                "out of memory at the output time {}: the system refused {bytes} bytes for the samples; \
                 request fewer output samples",
                Num(t_out)
            ),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_times_exactly_at_step_ends_and_interpolates_inside() {
        let output = Output::Times(vec![0.0, 0.0, 0.5, 1.0, 1.5, 2.0]);
        let mut s = OutputSampler::new(&output);
        let mut sol = s.solution(1, 0);
        let mut buf = [0.0];
        s.start(&mut sol, 0.0, &[7.0]).unwrap();
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
        let mut s = OutputSampler::new(&output);
        let mut sol = s.solution(1, 4);
        s.start(&mut sol, 0.0, &[1.0]).unwrap();
        assert!(!s.needs_interpolant(1.0));
        s.record(&mut sol, 1.0, &[2.0], &mut [0.0], |_, _| panic!("no interpolation")).unwrap();
        assert_eq!(sol.t, [0.0, 1.0]);
        assert_eq!(sol.y, [1.0, 2.0]);
    }

    /// The block path records exactly what the per-sample path does: the same times, the same
    /// values, `y_new` at a time equal to the step end, the samples before a non-finite one.
    #[test]
    fn blocks_record_what_samples_record() {
        let times = vec![0.0, 0.1, 0.25, 0.25, 0.5, 0.9, 1.0, 1.0, 1.3, 2.0];
        let f = |t: f64, out: &mut [f64]| {
            out[0] = (3.0 * t).sin();
            out[1] = if t > 1.2 && t < 1.5 { f64::NAN } else { t * t };
        };
        let output = Output::Times(times);
        let ends = [(0.5, [5.0, 6.0]), (1.0, [7.0, 8.0]), (2.0, [9.0, 10.0])];
        let (mut a, mut b) = (OutputSampler::new(&output), OutputSampler::new(&output));
        let (mut sa, mut sb) = (a.solution(2, 0), b.solution(2, 0));
        a.start(&mut sa, 0.0, &[1.0, 2.0]).unwrap();
        b.start(&mut sb, 0.0, &[1.0, 2.0]).unwrap();
        for (t_new, y_new) in ends {
            let ra = a.record(&mut sa, t_new, &y_new, &mut [0.0; 2], f);
            let rb = b.record_block(&mut sb, t_new, &y_new, |ts, out| {
                for (&t, row) in ts.iter().zip(out.chunks_exact_mut(2)) {
                    f(t, row);
                }
            });
            assert_eq!(ra, rb);
            assert_eq!(sa, sb);
        }
        assert_eq!(sa.t, [0.0, 0.1, 0.25, 0.25, 0.5, 0.9, 1.0, 1.0]);
        assert_eq!(sa.state(7), [7.0, 8.0]);
    }

    /// The galloping search and the finiteness check agree with the plain ones.
    #[test]
    fn searches_agree_with_the_plain_ones() {
        let times: Vec<f64> = (0..100).map(|k| f64::from(k / 3)).collect();
        for len in [0, 1, 2, 3, 7, 64, 99, 100] {
            for t in [-1.0, 0.0, 0.5, 1.0, 5.0, 16.0, 31.0, 33.0, 40.0] {
                let ts = &times[..len];
                assert_eq!(count_before(ts, t), ts.partition_point(|&s| s < t), "len {len}, t {t}");
            }
        }
        let mut values = vec![1.0; 37];
        assert_eq!(first_non_finite(&values), None);
        for (at, bad) in [(0, f64::NAN), (7, f64::INFINITY), (8, f64::NEG_INFINITY), (36, f64::NAN)] {
            values[at] = bad;
            assert_eq!(first_non_finite(&values), Some(at));
            values[at] = f64::MAX;
        }
        assert_eq!(first_non_finite(&values), None);
    }

    #[test]
    fn a_non_finite_interpolant_is_refused() {
        let output = Output::Times(vec![0.5, 0.7, 1.0]);
        let mut s = OutputSampler::new(&output);
        let mut sol = s.solution(1, 0);
        s.start(&mut sol, 0.0, &[0.0]).unwrap();
        let got = s.record(&mut sol, 1.0, &[1.0], &mut [0.0], |t, out| out[0] = if t > 0.6 { f64::NAN } else { t });
        assert_eq!(got, Err(RecordError::NonFinite(0.7)));
        assert_eq!(sol.t, [0.5]);
        let (status, message) = record_failure(RecordError::NonFinite(0.7), 0.0, 1.0);
        assert_eq!(status, Status::NonFinite);
        assert!(message.contains("0.7"), "{message}");
    }
}

//! Fixed steps with located events, in the manner of diffsol's `root`: the system is in one of
//! several modes (a bit stuck or slipping), each a smooth vector field with a root function of
//! the state that is `<= 0` while the mode holds. A step of RK4 ([`super::rk4::rk4_step`]) whose
//! end has the root function `> 0` is shortened to the sign change, located by bisection on the
//! step length to the last bit ([`locate`]), either just before it or just after it as the mode
//! asks; the system then switches its mode there ([`EventSystem::switch`]) and the next step
//! restarts from that point. Steps are `dt`, shortened to land on every output time
//! `k * interval` (samples are step ends, never interpolated).

use crate::error::Num;
use crate::interrupt::{Interrupt, Poller};
use crate::solution::Status;

use super::rk4::rk4_step;

/// Consecutive steps located at their very start (no advance in time) before a run stops
/// with [`Status::StepSizeUnderflow`].
const MAX_STALLED: u32 = 16;

/// A system of `N` unknowns stepped by [`solve`].
pub(crate) trait EventSystem<const N: usize> {
    /// The vector field of the current mode.
    fn rhs(&self, y: &[f64; N]) -> [f64; N];
    /// The root function of the current mode: `<= 0` while it holds.
    fn root(&self, y: &[f64; N]) -> f64;
    /// Whether a step with a sign change stops at the last state before it (`true`) or at the
    /// first one past it (`false`).
    fn stop_before(&self) -> bool;
    /// At the end of every step (`crossed`: it ended at a located root): the switch of mode,
    /// which may also set the state.
    fn switch(&mut self, y: &mut [f64; N], crossed: bool);
}

/// The output times of [`solve`]: `k * interval` for `k < samples`, the last capped at
/// `duration`, from `t = 0`; steps of at most `dt`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Schedule {
    pub dt: f64,
    pub interval: f64,
    pub duration: f64,
    pub samples: usize,
}

/// How a run of [`solve`] ended, and the steps it took (a located event splits a step).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Outcome {
    pub steps: u64,
    pub status: Status,
    pub message: String,
}

/// One step of at most `h` from `y`, stopped at the root of the mode when the step would pass
/// it: the step taken, the new state and whether it ended at a root.
pub(crate) fn step<const N: usize, S: EventSystem<N>>(sys: &S, y: &[f64; N], h: f64) -> (f64, [f64; N], bool) {
    let rk4 = |h: f64| rk4_step(|s| sys.rhs(s), y, h);
    let y1 = rk4(h);
    if sys.root(&y1) > 0.0 {
        let (before, after) = locate(|h| sys.root(&rk4(h)), h);
        let h = if sys.stop_before() { before } else { after };
        (h, rk4(h), true)
    } else {
        (h, y1, false)
    }
}

/// The largest `h` in `[0, h_max]` with `root(h) <= 0` given `root(0) <= 0 < root(h_max)`, by
/// bisection to the last bit; returns `(h_before, h_after)`, adjacent step lengths around
/// the sign change.
pub(crate) fn locate(root: impl Fn(f64) -> f64, h_max: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (0.0, h_max);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if root(mid) <= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo, hi)
}

/// Steps `sys` from `(0, y)` through `schedule`, recording `record(sys, t, y)` at `t = 0` and
/// at every output time, polling `interrupt` before every step and reporting the fraction done
/// to `progress` about every 0.1 % of the duration. `y` is left at the last state reached.
pub(crate) fn solve<const N: usize, S: EventSystem<N>>(
    sys: &mut S,
    y: &mut [f64; N],
    schedule: Schedule,
    interrupt: &dyn Interrupt,
    record: &mut dyn FnMut(&S, f64, &[f64; N]),
    progress: &mut dyn FnMut(f64),
) -> Outcome {
    let mut out = Outcome { steps: 0, status: Status::Success, message: String::new() };
    record(sys, 0.0, y);
    let mut poller = Poller::new(interrupt);
    let mut t = 0.0;
    let mut k_out = 1usize;
    let mut next_progress = 0.0;
    let mut stalled = 0u32;
    while k_out < schedule.samples {
        let t_out = (k_out as f64 * schedule.interval).min(schedule.duration);
        if poller.poll(t) {
            out.status = Status::Interrupted;
            out.message = format!("interrupted at t = {} s", Num(t));
            break;
        }
        let span = t_out - t;
        let (h, mut y1, crossed) = step(sys, y, span.min(schedule.dt));
        sys.switch(&mut y1, crossed);
        let reached = h >= span;
        // An event located at the very start of the step again and again (a root function
        // grazing zero) would not advance: stop with a status instead of spinning.
        stalled = if t + h > t { 0 } else { stalled + 1 };
        if stalled > MAX_STALLED {
            out.status = Status::StepSizeUnderflow;
            out.message = format!("the events (stick and slip switches) did not advance at t = {} s", Num(t));
            break;
        }
        t = if reached { t_out } else { t + h };
        *y = y1;
        out.steps += 1;
        if !y.iter().all(|v| v.is_finite()) {
            out.status = Status::NonFinite;
            out.message = format!("the state became non-finite before t = {} s", Num(t));
            break;
        }
        if reached {
            record(sys, t, y);
            k_out += 1;
        }
        if t >= next_progress {
            progress(t / schedule.duration);
            next_progress = t + 1e-3 * schedule.duration;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solution::reserve_outputs;

    /// The bisection brackets the sign change of `h^2 - 2` in adjacent numbers around sqrt(2).
    #[test]
    fn locate_brackets_the_root_to_the_last_bit() {
        let (lo, hi) = locate(|h| h * h - 2.0, 4.0);
        assert!(lo * lo - 2.0 <= 0.0 && hi * hi - 2.0 > 0.0);
        assert_eq!(f64::from_bits(lo.to_bits() + 1), hi);
        assert!((lo - std::f64::consts::SQRT_2).abs() <= f64::EPSILON * 2.0);
    }

    /// Output storage the system cannot give is refused with its size, not an abort.
    #[test]
    fn an_impossible_output_reservation_is_refused_with_its_size() {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        assert!(reserve_outputs(&mut [(&mut a, 10), (&mut b, 20)]).is_ok());
        assert!(a.capacity() >= 10 && b.capacity() >= 20);
        let huge = usize::MAX / 16;
        let err = reserve_outputs(&mut [(&mut a, huge), (&mut b, 3)]).unwrap_err();
        assert_eq!(err.bytes, (huge + 3) * 8);
        assert!(err.outputs_message().starts_with("the outputs ("), "{}", err.outputs_message());
    }
}

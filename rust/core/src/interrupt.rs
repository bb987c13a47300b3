//! Cooperative cancellation of long solves.
//!
//! Every integrator consults an [`Interrupt`] hook while it steps (through [`Poller`]): when the
//! hook answers `true` the solve ends with [`crate::Status::Interrupted`], a message and the
//! samples recorded so far. The hook is polled cheaply: the clock is read every `stride` steps,
//! with `stride` adapted (1 ..= [`MAX_STRIDE`]) so that reads fall about every
//! 1-4 ms whatever a step costs, and the hook is asked at each read. A solve therefore stops
//! within a few milliseconds (or one step, when a single step takes longer) of the hook first
//! answering `true`; the stride adapts to the step cost, which is steady within a solve (at
//! most `MAX_STRIDE` steps pass between two reads).
//!
//! Hooks: [`Never`] (what the plain solve functions use), [`CancelFlag`] (an `AtomicBool` that
//! any thread may raise; share it by reference, e.g. across the threads of a batch solve) and any
//! `Fn() -> bool + Sync` closure (the Python bindings check for signals this way).
//! Polling never changes the numbers: a solve whose hook never fires is bit-identical to one
//! without a hook.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A cancellation request that the integrators poll while they step.
///
/// `interrupted` is called from the solving thread (from several threads at once when a hook is
/// shared by parallel solves), every few milliseconds; it should be cheap and must not panic.
/// Once it has returned `true` it is not asked again by that solve.
pub trait Interrupt: Sync {
    /// Whether the solve should stop now.
    fn interrupted(&self) -> bool;

    /// Whether the solve, which has reached time `t`, should stop now: integrators ask this
    /// (a hook may report the progress of the solve from it). By default
    /// [`Interrupt::interrupted`].
    fn interrupted_at(&self, t: f64) -> bool {
        let _ = t;
        self.interrupted()
    }
}

/// The hook that never interrupts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Never;

impl Interrupt for Never {
    #[inline]
    fn interrupted(&self) -> bool {
        false
    }
}

impl<F: Fn() -> bool + Sync> Interrupt for F {
    #[inline]
    fn interrupted(&self) -> bool {
        self()
    }
}

/// A flag that any thread can raise to stop every solve polling it.
///
/// ```
/// use drillstring_core::interrupt::{CancelFlag, Interrupt};
/// let flag = CancelFlag::new();
/// assert!(!flag.interrupted());
/// std::thread::scope(|s| {
///     s.spawn(|| flag.cancel());
/// });
/// assert!(flag.is_cancelled() && flag.interrupted());
/// flag.reset();
/// assert!(!flag.is_cancelled());
/// ```
#[derive(Debug, Default)]
pub struct CancelFlag {
    raised: AtomicBool,
}

impl CancelFlag {
    /// A flag that is not raised.
    pub const fn new() -> Self {
        CancelFlag { raised: AtomicBool::new(false) }
    }

    /// Raises the flag: every solve polling it ends with `Status::Interrupted`.
    pub fn cancel(&self) {
        self.raised.store(true, Ordering::Release);
    }

    /// Whether the flag has been raised.
    pub fn is_cancelled(&self) -> bool {
        self.raised.load(Ordering::Acquire)
    }

    /// Lowers the flag again.
    pub fn reset(&self) {
        self.raised.store(false, Ordering::Release);
    }
}

impl Interrupt for CancelFlag {
    #[inline]
    fn interrupted(&self) -> bool {
        self.is_cancelled()
    }
}

/// Largest number of steps between two reads of the clock.
pub const MAX_STRIDE: u32 = 1024;
/// Reads closer together than this double the stride.
const FAST: Duration = Duration::from_millis(1);
/// Reads further apart than this halve the stride.
const SLOW: Duration = Duration::from_millis(4);

/// Rate-limited polling of an [`Interrupt`] hook from an integrator's step loop.
///
/// [`Poller::poll`] is called once per step (attempt); it costs a decrement and a compare
/// except every `stride` steps, when it reads the clock, adapts `stride` and asks the hook.
pub struct Poller<'a> {
    hook: &'a dyn Interrupt,
    countdown: u32,
    stride: u32,
    last: Instant,
}

impl<'a> Poller<'a> {
    /// A poller asking `hook` first after one step.
    pub fn new(hook: &'a dyn Interrupt) -> Self {
        Poller { hook, countdown: 1, stride: 1, last: Instant::now() }
    }

    /// Counts one step of a solve that has reached time `t`; `true` when the hook asked to
    /// stop ([`Interrupt::interrupted_at`]).
    #[inline]
    pub fn poll(&mut self, t: f64) -> bool {
        self.countdown -= 1;
        if self.countdown > 0 {
            return false;
        }
        self.read_clock_and_ask(t)
    }

    #[cold]
    #[inline(never)]
    fn read_clock_and_ask(&mut self, t: f64) -> bool {
        let now = Instant::now();
        let elapsed = now.duration_since(self.last);
        self.last = now;
        if elapsed < FAST {
            self.stride = (self.stride * 2).min(MAX_STRIDE);
        } else if elapsed > SLOW {
            self.stride = (self.stride / 2).max(1);
        }
        self.countdown = self.stride;
        self.hook.interrupted_at(t)
    }
}

impl std::fmt::Debug for Poller<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Poller").field("stride", &self.stride).field("countdown", &self.countdown).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    #[test]
    fn never_and_closures_and_flags() {
        assert!(!Never.interrupted());
        let yes = || true;
        assert!(yes.interrupted());
        let flag = CancelFlag::new();
        assert!(!flag.interrupted());
        flag.cancel();
        assert!(flag.interrupted());
        flag.reset();
        assert!(!flag.interrupted());
    }

    #[test]
    fn poller_asks_at_most_every_max_stride_steps_and_at_least_once_a_few_ms() {
        let calls = AtomicU64::new(0);
        let hook = || {
            calls.fetch_add(1, Ordering::Relaxed);
            false
        };
        let mut poller = Poller::new(&hook);
        // Fast steps: the stride grows to MAX_STRIDE, so few calls.
        let steps = 1_000_000u64;
        for _ in 0..steps {
            assert!(!poller.poll(0.0));
        }
        let fast_calls = calls.load(Ordering::Relaxed);
        assert!(fast_calls >= steps / u64::from(MAX_STRIDE), "{fast_calls}");
        assert!(fast_calls < steps / 50, "{fast_calls}");
        // Slow steps (5 ms each): the stride stays 1, the hook is asked at every step.
        calls.store(0, Ordering::Relaxed);
        let mut poller = Poller::new(&hook);
        for _ in 0..20 {
            std::thread::sleep(Duration::from_millis(5));
            poller.poll(0.0);
        }
        assert!(calls.load(Ordering::Relaxed) >= 18, "{}", calls.load(Ordering::Relaxed));
    }

    #[test]
    fn poller_reports_the_hook() {
        let flag = CancelFlag::new();
        let mut poller = Poller::new(&flag);
        assert!(!poller.poll(0.0));
        flag.cancel();
        let mut n = 0;
        while !poller.poll(0.0) {
            n += 1;
            assert!(n <= MAX_STRIDE, "not noticed");
        }
    }
}

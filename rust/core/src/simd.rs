//! Runtime dispatch of the hot loops to AVX-512 or AVX2, with FMA.
//!
//! The crate is compiled for the baseline of its target (SSE2 on x86-64), so a wheel runs on
//! any machine. The few loops that dominate a solve (the Runge-Kutta stage combinations, the
//! finite-difference acceleration, the drilling solver's cell update) are written once as a
//! `Kernel`, generic over how a product is accumulated (`MulAdd`), and `dispatch` runs them
//! compiled for AVX-512 + FMA (x86-64-v4) or AVX2 + FMA (x86-64-v3), the best the processor
//! has, through the `pulp` crate's safe target-feature tokens, and as plain baseline code
//! otherwise. The kernels are written element by element (no reassociated sums), so the two
//! vector paths compute the same operations in the same order: their results are
//! bit-identical; only the vector width differs.
//!
//! A fused multiply-add rounds once where `a * b + c` rounds twice, so results computed on
//! machines with and without FMA may differ in the last bits; every method's accuracy and
//! the tests' tolerances are far above that.

use std::sync::OnceLock;

/// How `a * b + c` is evaluated inside a [`Kernel`].
pub(crate) trait MulAdd {
    /// Whether the kernel runs with 256-bit vectors (wider blocks pay off).
    const WIDE: bool;
    /// `a * b + c`.
    fn mul_add(a: f64, b: f64, c: f64) -> f64;
}

/// One rounding: `f64::mul_add`, a single instruction where FMA is enabled.
pub(crate) struct Fused;

impl MulAdd for Fused {
    const WIDE: bool = true;
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a.mul_add(b, c)
    }
}

/// Two roundings: `a * b + c` (a fused `mul_add` without FMA hardware is a slow library call).
pub(crate) struct Unfused;

impl MulAdd for Unfused {
    const WIDE: bool = false;
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
}

/// A loop to run under [`dispatch`]. `run` and everything it calls must be
/// `#[inline(always)]`: target features apply only to code inlined into the dispatched call.
pub(crate) trait Kernel {
    type Output;
    fn run<M: MulAdd>(self) -> Self::Output;
}

/// The environment variable that can pin every kernel to one path:
/// `DRILLSTRING_SIMD=baseline` (bit-identical results on every x86-64 machine, or a
/// benchmark of the fallback), `DRILLSTRING_SIMD=avx2` (no AVX-512, e.g. to compare the two).
/// Any other value, or none, selects the best path. Read once.
pub const SIMD_ENV: &str = "DRILLSTRING_SIMD";

/// The widest path [`SIMD_ENV`] allows.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pin {
    Best,
    Avx2,
    Baseline,
}

/// What [`SIMD_ENV`] says (read once per process).
fn pin() -> Pin {
    static PIN: OnceLock<Pin> = OnceLock::new();
    *PIN.get_or_init(|| match std::env::var(SIMD_ENV).map(|v| v.trim().to_ascii_lowercase()) {
        Ok(v) if v == "baseline" => Pin::Baseline,
        Ok(v) if v == "avx2" => Pin::Avx2,
        _ => Pin::Best,
    })
}

fn pinned_to_baseline() -> bool {
    pin() == Pin::Baseline
}

/// Runs `kernel` with AVX-512 + FMA or AVX2 + FMA, the best this processor has (x86-64-v4 or
/// v3, detected once and cached) and [`SIMD_ENV`] allows, else as baseline code.
#[inline(always)]
pub(crate) fn dispatch<K: Kernel>(kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(simd) = v4() {
        return simd.vectorize(InV3(kernel));
    }
    #[cfg(target_arch = "x86_64")]
    if let Some(simd) = v3() {
        return simd.vectorize(InV3(kernel));
    }
    kernel.run::<Unfused>()
}

/// The AVX2 + FMA token where the processor has it and [`SIMD_ENV`] allows (AVX-512 machines
/// included), for a kernel written with explicit 4-lane vectors (`pulp::f64x4`) and run with
/// `vectorize`; `None` means the caller's baseline code.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn avx2() -> Option<pulp::x86::V3> {
    v3()
}

/// Loops shorter than this run inline as baseline code: the call into the vector path
/// costs more than it saves on a handful of components (a modal system of a few modes),
/// and small systems then give bit-identical results on every machine.
pub(crate) const MIN_DISPATCH_LEN: usize = 32;

/// [`dispatch`] for a loop over `len` components, inline baseline code below
/// [`MIN_DISPATCH_LEN`].
#[inline(always)]
pub(crate) fn dispatch_len<K: Kernel>(len: usize, kernel: K) -> K::Output {
    if len < MIN_DISPATCH_LEN {
        kernel.run::<Unfused>()
    } else {
        dispatch(kernel)
    }
}

#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn v3() -> Option<pulp::x86::V3> {
    if pinned_to_baseline() {
        None
    } else {
        pulp::x86::V3::try_new()
    }
}

#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn v4() -> Option<pulp::x86::V4> {
    if pin() != Pin::Best {
        None
    } else {
        pulp::x86::V4::try_new()
    }
}

/// The code path `dispatch` takes on this machine: `"avx512+fma"`, `"avx2+fma"` or `"baseline"`.
pub fn path() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if v4().is_some() {
        return "avx512+fma";
    }
    #[cfg(target_arch = "x86_64")]
    if v3().is_some() {
        return "avx2+fma";
    }
    let _ = pinned_to_baseline();
    "baseline"
}

/// A kernel called inside pulp's AVX-512 or AVX2 context, with FMA.
#[cfg(target_arch = "x86_64")]
struct InV3<K>(K);

#[cfg(target_arch = "x86_64")]
impl<K: Kernel> pulp::NullaryFnOnce for InV3<K> {
    type Output = K::Output;
    #[inline(always)]
    fn call(self) -> K::Output {
        self.0.run::<Fused>()
    }
}

/// Runs `kernel` as baseline code, whatever the processor (tests compare both paths).
#[cfg(test)]
pub(crate) fn baseline<K: Kernel>(kernel: K) -> K::Output {
    kernel.run::<Unfused>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_path_is_named() {
        assert!(["avx512+fma", "avx2+fma", "baseline"].contains(&path()));
    }

    /// `sum_i a_i b_i` as a kernel.
    struct Dot<'a>(&'a [f64], &'a [f64]);

    impl Kernel for Dot<'_> {
        type Output = f64;
        #[inline(always)]
        fn run<M: MulAdd>(self) -> f64 {
            self.0.iter().zip(self.1).fold(0.0, |s, (&a, &b)| M::mul_add(a, b, s))
        }
    }

    #[test]
    fn both_paths_compute_the_same_sum() {
        let a: Vec<f64> = (0..37).map(|i| (i as f64 * 0.37).sin()).collect();
        let b: Vec<f64> = (0..37).map(|i| (i as f64 * 0.11).cos()).collect();
        let exact: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        for value in [dispatch(Dot(&a, &b)), baseline(Dot(&a, &b))] {
            assert!((value - exact).abs() < 1e-14 * exact.abs().max(1.0), "{value} vs {exact}");
        }
        // 0.1 * 10 - 1 with one rounding is the representation error of 0.1, with two zero.
        let fused = Fused::mul_add(0.1, 10.0, -1.0);
        assert_eq!(fused, 0.1_f64.mul_add(10.0, -1.0));
        assert_ne!(fused, 0.0);
        assert_eq!(Unfused::mul_add(0.1, 10.0, -1.0), 0.0);
    }
}

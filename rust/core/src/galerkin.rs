//! The exact dimensionless Galerkin integrals of the basis a [`Boundary`] asks for.
//!
//! Free ends: `phi_k = cos(i_k pi s)` on `s = z / l in [0, 1]`, mode numbers `i_k = 1..n` or
//! `0, 1..n` with the rigid mode. For sorted positions `a <= b <= c <= d` the quartic
//! integrals of an energy monomial `th^p th_z^r` (`p + r = 4`, `r` even) are, with
//! `c_k = cos(i_k pi s)`, `s_k = sin(i_k pi s)`,
//!
//! ```text
//! I^(p,r)_t = sum over the distinct orderings (p1..p4) of (a, b, c, d) of
//!             i_p(p+1) .. i_p4 int_0^1 c_p1 .. c_pp s_p(p+1) .. s_p4 ds
//! ```
//!
//! (`cos4 = I^(4,0)`, `mixed = I^(2,2)`, `sin4 = I^(0,4)`); the modal energy of the monomial is
//! `weight l (pi / l)^r sum_t I^(p,r)_t q_a q_b q_c q_d`. Writing `cos` and `sin` as
//! exponentials and using `int_0^1 cos(k pi s) ds = [k = 0]` for integers `k`, with signs
//! `e = (e_a, .., e_d) in {+-1}^4`, `e_a = +1`, and `N(e) = [sum e_k i_k = 0]`:
//!
//! ```text
//! int c_a c_b c_c c_d = 1/8 sum_e N(e),
//! int c_a c_b s_c s_d = 1/8 sum_e (-e_c e_d) N(e),
//! int s_a s_b s_c s_d = 1/8 sum_e e_b e_c e_d N(e),
//! ```
//!
//! so `8 I` is an integer, computed in `i64` and exact in `f64`. A term is nonzero only if
//! `i_d = +-i_a +- i_b +- i_c` (then `cos4_t > 0`): only those are generated, in lexicographic
//! order (the selection rule `i_a + i_b + i_c + i_d` even follows). The formulas are also
//! documented in `drillstring.galerkin`, which gets its numbers from here
//! (`_core.galerkin_integrals`); `tests/oracles.py` keeps the former numpy generator, equal to
//! this one exactly.

use crate::error::{Error, Result};
use crate::sweep::GalerkinIntegrals;
use crate::terms::Boundary;

/// Largest number of elastic modes `n` (256 modes: ~1.9 million quartic terms).
pub const MAX_MODES: u32 = 256;

/// The sign patterns `(e_b, e_c, e_d)` with `e_a = +1`.
const SIGNS: [[i64; 3]; 8] =
    [[1, 1, 1], [1, 1, -1], [1, -1, 1], [1, -1, -1], [-1, 1, 1], [-1, 1, -1], [-1, -1, 1], [-1, -1, -1]];

/// Distinct orderings of a sorted quadruple, indexed by `(a==b)*4 + (b==c)*2 + (c==d)`.
const MULTIPLICITY: [i64; 8] = [24, 12, 12, 4, 12, 6, 4, 1];

/// The position pairs `(i, j)`, `i < j`, of a quadruple.
const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// `8 (cos4, mixed, sin4)` of the sorted mode-number quadruple `quad`.
pub fn integer_integrals(quad: [i64; 4]) -> (i64, i64, i64) {
    let e = |s: &[i64; 3]| [1, s[0], s[1], s[2]];
    let mut hits = [false; 8];
    for (hit, s) in hits.iter_mut().zip(&SIGNS) {
        let s = e(s);
        *hit = (0..4).map(|k| s[k] * quad[k]).sum::<i64>() == 0;
    }
    let flags =
        usize::from(quad[0] == quad[1]) * 4 + usize::from(quad[1] == quad[2]) * 2 + usize::from(quad[2] == quad[3]);
    let mult = MULTIPLICITY[flags];
    let mut count = 0;
    let mut sign_product = 0;
    for (s, _) in SIGNS.iter().zip(&hits).filter(|(_, &h)| h) {
        count += 1;
        sign_product += s[0] * s[1] * s[2];
    }
    let mut pair_sum = 0;
    for &(i, j) in &PAIRS {
        let weight: i64 = SIGNS.iter().zip(&hits).filter(|(_, &h)| h).map(|(s, _)| -e(s)[i] * e(s)[j]).sum();
        pair_sum += quad[i] * quad[j] * weight;
    }
    // the sum over the 24 permutations is 4 pair_sum; the distinct orderings are mult / 24 of it
    let numerator = mult * pair_sum;
    debug_assert_eq!(numerator % 6, 0, "mixed quartic integral of {quad:?} is not a multiple of 1/8");
    (mult * count, numerator / 6, mult * quad.iter().product::<i64>() * sign_product)
}

/// The integrals of the basis of `boundary` with `modes` elastic modes (`1..=MAX_MODES`,
/// field `"modes"`), and the rigid mode first if `rigid_mode`.
pub fn integrals(boundary: Boundary, modes: u32, rigid_mode: bool) -> Result<GalerkinIntegrals> {
    if !(1..=MAX_MODES).contains(&modes) {
        return Err(Error::invalid("modes", modes, format!("an integer in 1..={MAX_MODES}")));
    }
    match boundary {
        Boundary::Free => Ok(cosine_integrals(modes, rigid_mode)),
    }
}

/// [`integrals`] of the `cos(i pi s)` basis of free ends.
fn cosine_integrals(modes: u32, rigid_mode: bool) -> GalerkinIntegrals {
    let first: i64 = if rigid_mode { 0 } else { 1 };
    let top = i64::from(modes);
    let mut quartic_index = Vec::new();
    let (mut cos4, mut mixed, mut sin4) = (Vec::new(), Vec::new(), Vec::new());
    let mut candidates = [0i64; 8];
    for a in first..=top {
        for b in a..=top {
            for c in b..=top {
                let mut n = 0;
                for s in &SIGNS {
                    let d = s[0] * a + s[1] * b + s[2] * c;
                    if (c..=top).contains(&d) {
                        candidates[n] = d;
                        n += 1;
                    }
                }
                let found = &mut candidates[..n];
                found.sort_unstable();
                let mut last = -1;
                for &d in found.iter() {
                    if d == last {
                        continue;
                    }
                    last = d;
                    let (c4, mx, s4) = integer_integrals([a, b, c, d]);
                    // positions: mode numbers minus the first (< 2^31: modes <= MAX_MODES)
                    quartic_index.push([a, b, c, d].map(|i| (i - first) as u32));
                    cos4.push(c4 as f64 / 8.0);
                    mixed.push(mx as f64 / 8.0);
                    sin4.push(s4 as f64 / 8.0);
                }
            }
        }
    }
    let indices = (first as u32..=modes).collect();
    GalerkinIntegrals::new(indices, quartic_index, cos4, mixed, sin4).expect("generated integrals are well formed")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// `int_0^1 f(s) ds` by the midpoint rule on 400 points (exact up to rounding for these
    /// trigonometric polynomials of frequency < 800 pi).
    fn quadrature(f: impl Fn(f64) -> f64) -> f64 {
        let n = 400;
        (0..n).map(|j| f((j as f64 + 0.5) / n as f64)).sum::<f64>() / n as f64
    }

    #[test]
    fn one_and_two_modes() {
        let g = integrals(Boundary::Free, 1, false).unwrap();
        assert_eq!((g.indices.clone(), g.quartic_index.clone()), (vec![1], vec![[0; 4]]));
        assert_eq!((g.cos4[0], g.mixed[0], g.sin4[0]), (0.375, 0.125, 0.375));
        let g = integrals(Boundary::Free, 2, false).unwrap();
        assert_eq!(g.quartic_index, vec![[0, 0, 0, 0], [0, 0, 1, 1], [1, 1, 1, 1]]);
        assert_eq!(g.cos4, vec![0.375, 1.5, 0.375]);
        assert_eq!(g.mixed, vec![0.125, 1.25, 0.5]);
        assert_eq!(g.sin4, vec![0.375, 6.0, 6.0]);
        assert_eq!(integrals(Boundary::Free, 0, true).unwrap_err().field(), "modes");
        assert_eq!(integrals(Boundary::Free, MAX_MODES + 1, true).unwrap_err().field(), "modes");
    }

    #[test]
    fn integrals_match_quadrature() {
        let g = integrals(Boundary::Free, 4, true).unwrap();
        let mut checked = 0;
        for (t, q) in g.quartic_index.iter().enumerate() {
            let i = q.map(|p| f64::from(g.indices[p as usize]));
            let c = |k: usize, s: f64| (i[k] * PI * s).cos();
            let sn = |k: usize, s: f64| i[k] * (i[k] * PI * s).sin();
            let perms: Vec<[usize; 4]> = {
                let mut all = Vec::new();
                for a in 0..4 {
                    for b in 0..4 {
                        for c in 0..4 {
                            for d in 0..4 {
                                let p = [a, b, c, d];
                                let mut sorted = p;
                                sorted.sort_unstable();
                                if sorted == [0, 1, 2, 3] {
                                    all.push(p);
                                }
                            }
                        }
                    }
                }
                all
            };
            // sum over all 24 permutations, divided by the repeats of each distinct ordering
            let repeats = 24.0 / {
                let flags = usize::from(q[0] == q[1]) * 4 + usize::from(q[1] == q[2]) * 2 + usize::from(q[2] == q[3]);
                MULTIPLICITY[flags] as f64
            };
            let (mut c4, mut mx, mut s4) = (0.0, 0.0, 0.0);
            for p in &perms {
                c4 += quadrature(|s| c(p[0], s) * c(p[1], s) * c(p[2], s) * c(p[3], s));
                mx += quadrature(|s| c(p[0], s) * c(p[1], s) * sn(p[2], s) * sn(p[3], s));
                s4 += quadrature(|s| sn(p[0], s) * sn(p[1], s) * sn(p[2], s) * sn(p[3], s));
            }
            let tol = 1e-9 * (1.0 + g.sin4[t].abs());
            assert!((c4 / repeats - g.cos4[t]).abs() < tol, "cos4 {q:?}");
            assert!((mx / repeats - g.mixed[t]).abs() < tol, "mixed {q:?}");
            assert!((s4 / repeats - g.sin4[t]).abs() < tol, "sin4 {q:?}");
            checked += 1;
        }
        assert!(checked > 20);
    }

    #[test]
    fn lexicographic_and_selection_rule() {
        let g = integrals(Boundary::Free, 12, true).unwrap();
        assert!(g.quartic_index.windows(2).all(|w| w[0] < w[1]));
        for (t, q) in g.quartic_index.iter().enumerate() {
            assert!(q.iter().map(|&p| g.indices[p as usize]).sum::<u32>() % 2 == 0);
            assert!(g.cos4[t] > 0.0);
        }
    }
}

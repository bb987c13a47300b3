//! RKN12(10): the 17-stage explicit Runge-Kutta-Nystrom pair of order 12 with an embedded
//! order-10 solution, of J. R. Dormand, M. E. A. El-Mikkawy and P. J. Prince, "High-order
//! embedded Runge-Kutta-Nystrom formulae", *IMA J. Numer. Anal.* 7 (1987) 423-430, for
//! `q'' = a(q)` (stepped by [`super::rkn`]).
//!
//! A step `(q, v) -> (q_new, v_new)` of size `h`:
//!
//! ```text
//! K_i   = a(q + c_i h v + h^2 sum_{j<i} a_ij K_j),   i = 0 .. 16
//! q_new = q + h v + h^2 sum_i b_i K_i,   v_new = v + h sum_i b'_i K_i
//! ```
//!
//! with the error estimate `(h^2 sum_i (b_i - b^_i) K_i, h sum_i (b'_i - b'^_i) K_i)` of the
//! embedded order-10 weights `b^, b'^`. `K_0 = a(q)` is the acceleration at the step's start,
//! so a step costs 16 new evaluations plus one at its end (the next step's `K_0`).
//!
//! The coefficients are the exact rationals of the paper as tabulated in the `DPRKN12`
//! tableau of OrdinaryDiffEq.jl (`lib/OrdinaryDiffEqRKN/src/rkn_tableaus.jl`), each rounded
//! once to the nearest `f64`; the error weights are the exact differences rounded once. The
//! tests below check the order conditions they satisfy.
#![allow(clippy::excessive_precision, clippy::unreadable_literal)]

use super::adaptive::Control;
use super::rkn::RknPair;

/// Nodes `c_i` of the 17 stages.
pub(crate) const C: [f64; 17] = [
    0.0,
    0.02,
    0.04,
    0.1,
    0.13333333333333333,
    0.16,
    0.05,
    0.2,
    0.25,
    0.3333333333333333,
    0.5,
    0.5555555555555556,
    0.75,
    0.8571428571428571,
    0.9452162222720143,
    1.0,
    1.0,
];
/// The coupling coefficients `a_ij` of the stage positions (strict lower triangle, row by row,
/// trailing zeros dropped).
pub(crate) const A: [&[f64]; 17] = [
    &[],
    &[0.0002],
    &[0.0002666666666666667, 0.0005333333333333334],
    &[0.002916666666666667, -0.004166666666666667, 0.00625],
    &[0.0016460905349794238, 0.0, 0.0054869684499314125, 0.0017558299039780521],
    &[0.0019456, 0.0, 0.007151746031746032, 0.0029127111111111113, 0.0007899428571428571],
    &[
        0.00056640625,
        0.0,
        0.0008809730489417989,
        -0.0004369212962962963,
        0.00033900669642857143,
        -9.946469907407407e-05,
    ],
    &[0.0030833333333333333, 0.0, 0.0, 0.0017777777777777779, 0.0027, 0.0015782828282828283, 0.01086060606060606],
    &[
        0.00365183937480113,
        0.0,
        0.003965171714072343,
        0.0031972582629306284,
        0.008221467306855435,
        -0.0013130926959572379,
        0.009771586968064868,
        0.003755769069232834,
    ],
    &[
        0.003707241068718501,
        0.0,
        0.005082045854555286,
        0.001174708002175412,
        -0.021147629915126993,
        0.06010463698107881,
        0.02010573476850619,
        -0.02835075012293358,
        0.014879568918581932,
    ],
    &[
        0.03512537656073344,
        0.0,
        -0.008615749195138479,
        -0.005791448051007917,
        1.945554823782616,
        -3.4351238674565137,
        -0.10930701107475221,
        2.3496383118995166,
        -0.7560094086870229,
        0.10952897222156927,
    ],
    &[
        0.020527792537482496,
        0.0,
        -0.00728644676448018,
        -0.0021153556079618403,
        0.9275807968723522,
        -1.6522824844257367,
        -0.02107956300568657,
        1.2065364326207872,
        -0.4137144770010661,
        0.09079873982809654,
        0.005355552600533985,
    ],
    &[
        -0.14324078875545515,
        0.0,
        0.012528703773091817,
        0.006826019163969827,
        -4.799555395574387,
        5.6986250439519415,
        0.7553430369523645,
        -0.12755487858281084,
        -1.9605926051117384,
        0.9185609056635262,
        -0.23880085505284432,
        0.15911081357234216,
    ],
    &[
        0.8045019205520489,
        0.0,
        -0.016658527067011247,
        -0.021415834042629735,
        16.827235928962466,
        -11.172835357176098,
        -3.377159297226324,
        -15.243326655360846,
        17.179835738215417,
        -5.437719239823995,
        1.3878671618364655,
        -0.5925827732652812,
        0.029603873171297354,
    ],
    &[
        -0.913296766697358,
        0.0,
        0.0024112725757805178,
        0.01765812269386174,
        -14.851649779720384,
        2.1589708670045757,
        3.99791558311788,
        28.434151800232232,
        -25.2593643549416,
        7.733878542362238,
        -1.8913028948478674,
        1.0014845070224718,
        0.004641199599109052,
        0.011218755022148957,
    ],
    &[
        -0.27519629720559396,
        0.0,
        0.03661188877915492,
        0.009789519688231562,
        -12.293062345886211,
        14.207226453937903,
        1.5866476906789537,
        2.4577735327595946,
        -8.935193694403273,
        4.373672731613407,
        -1.8347181765449492,
        1.1592085289061491,
        -0.017290253165383924,
        0.019325977904460768,
        0.005204442937554993,
    ],
    &[
        1.3076391847404059,
        0.0,
        0.017364109189745843,
        -0.018544456454265796,
        14.811522032867726,
        9.38317630848247,
        -5.2284261999445425,
        -48.95128052584765,
        38.297096034337926,
        -10.58738133697598,
        2.4332304376226275,
        -1.0453406042575444,
        0.0717732095086726,
        0.0021622109708082783,
        0.007009595759602514,
    ],
];
/// The 12th-order position weights `b_i`.
pub(crate) const B: [f64; 17] = [
    0.012127868517185414,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.08629746251568875,
    0.2525469581187147,
    -0.1974186799326823,
    0.2031869190789726,
    -0.020775808077714918,
    0.10967804874502014,
    0.038065132526466504,
    0.01163406880432423,
    0.0046580297040248785,
    0.0,
    0.0,
];
/// The 12th-order velocity weights `b'_i`.
pub(crate) const BP: [f64; 17] = [
    0.012127868517185414,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.09083943422704079,
    0.3156836976483934,
    -0.2632249065769097,
    0.3047803786184589,
    -0.041551616155429835,
    0.2467756096762953,
    0.15226053010586602,
    0.08143848163026961,
    0.08502571193890811,
    -0.009155189630077963,
    0.025,
];
/// Position error weights `b_i - b^_i` (the 10th-order embedded `b^`), exact differences rounded once.
pub(crate) const EQ: [f64; 17] = [
    -0.004880833389821577,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.014038126584857338,
    -0.11947921920803832,
    0.20440246507662121,
    -0.1322681492223791,
    0.11053069299761689,
    -0.07975385787102851,
    0.011224330486437457,
    -0.004671596801593694,
    0.0008580413473282841,
    0.0,
    0.0,
];
/// Velocity error weights `b'_i - b'^_i`, exact differences rounded once.
pub(crate) const EV: [f64; 17] = [
    -0.004880833389821577,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.014776975352481408,
    -0.1493490240100479,
    0.2725366201021616,
    -0.19840222383356862,
    0.22106138599523378,
    -0.17944618020981415,
    0.04489732194574983,
    -0.03270117761115586,
    0.015662325288859434,
    -0.029155189630077964,
    0.025,
];

/// The pair, with the step-size control of Hairer's `dop853.f` (`safe = 0.9`,
/// `fac1 = 0.333`, `fac2 = 6`, `beta = 0`) and the exponent `1/11` of an order-10 estimate.
pub(crate) const RKN12: RknPair = RknPair {
    c: &C,
    a: &A,
    b: &B,
    bp: &BP,
    eq: &EQ,
    ev: &EV,
    control: Control { safe: 0.9, fac1: 0.333, fac2: 6.0, beta: 0.0, expo1: 1.0 / 11.0, hinit_order: 12 },
};

#[cfg(test)]
mod tests {
    use super::*;

    /// `sum_i w_i c_i^k`.
    fn moment(w: &[f64], k: i32) -> f64 {
        w.iter().zip(&C).map(|(w, c)| w * c.powi(k)).sum()
    }

    #[test]
    fn stage_positions_are_consistent() {
        // Row sums sum_j a_ij = c_i^2 / 2 (the stage positions are exact for constant a).
        for (i, (row, &c)) in A.iter().zip(&C).enumerate() {
            assert!(row.len() <= i, "row {i} is not strictly lower triangular");
            let sum: f64 = row.iter().sum();
            assert!((sum - 0.5 * c * c).abs() < 1e-15 * (1.0 + row.iter().map(|a| a.abs()).sum::<f64>()), "row {i}");
        }
        // b_i = b'_i (1 - c_i), the same relation for the embedded weights.
        for i in 0..17 {
            assert!((B[i] - BP[i] * (1.0 - C[i])).abs() < 1e-16, "b_{i}");
            let (bh, bph) = (B[i] - EQ[i], BP[i] - EV[i]);
            assert!((bh - bph * (1.0 - C[i])).abs() < 1e-15, "embedded b_{i}");
        }
    }

    /// The quadrature conditions `sum b_i c_i^k = 1/((k+1)(k+2))` (`k <= 10`) and
    /// `sum b'_i c_i^k = 1/(k+1)` (`k <= 11`) of order 12; the embedded weights satisfy them
    /// up to `k <= 8` and `k <= 9` (order 10), and fail the next one, so the estimate is of
    /// exactly that order.
    #[test]
    fn quadrature_conditions_of_both_orders() {
        let (bh, bph): (Vec<f64>, Vec<f64>) = (0..17).map(|i| (B[i] - EQ[i], BP[i] - EV[i])).unzip();
        for k in 0..=11 {
            let (kq, kv) = (1.0 / f64::from((k + 1) * (k + 2)), 1.0 / f64::from(k + 1));
            if k <= 10 {
                assert!((moment(&B, k) - kq).abs() < 1e-14, "b, k = {k}");
            }
            assert!((moment(&BP, k) - kv).abs() < 1e-14, "b', k = {k}");
            if k <= 8 {
                assert!((moment(&bh, k) - kq).abs() < 1e-14, "b^, k = {k}");
            }
            if k <= 9 {
                assert!((moment(&bph, k) - kv).abs() < 1e-14, "b'^, k = {k}");
            }
        }
        assert!((moment(&bh, 9) - 1.0 / 110.0).abs() > 1e-8, "b^ is not of order 11");
        assert!((moment(&bph, 10) - 1.0 / 11.0).abs() > 1e-8, "b'^ is not of order 11");
        assert!((moment(&B, 11) - 1.0 / 156.0).abs() > 1e-10, "b is not of order 13");
        // The error weights are differences of consistent weights.
        assert!(moment(&EQ, 0).abs() < 1e-15 && moment(&EV, 0).abs() < 1e-15);
    }

    /// Two families of order conditions through the stage positions (trees of order `k + 4`
    /// and `k + 5`): `sum_i b'_i (A c^k)_i = 1/((k+1)(k+2)(k+3))` for `k <= 9` and
    /// `sum_i b'_i c_i (A c^k)_i = 1/((k+1)(k+2)(k+4))` for `k <= 8`, exact for the rationals.
    #[test]
    fn stage_conditions() {
        let a_ck = |i: usize, k: i32| A[i].iter().enumerate().map(|(j, a)| a * C[j].powi(k)).sum::<f64>();
        for k in 0..=9 {
            let got: f64 = (0..17).map(|i| BP[i] * a_ck(i, k)).sum();
            let kf = f64::from(k);
            let want = 1.0 / ((kf + 1.0) * (kf + 2.0) * (kf + 3.0));
            assert!((got - want).abs() < 1e-13, "k = {k}: {got} vs {want}");
            if k <= 8 {
                let got: f64 = (0..17).map(|i| BP[i] * C[i] * a_ck(i, k)).sum();
                let want = 1.0 / ((kf + 1.0) * (kf + 2.0) * (kf + 4.0));
                assert!((got - want).abs() < 1e-13, "c k = {k}: {got} vs {want}");
            }
        }
    }
}

//! DOP853: the explicit Runge-Kutta method of order 8 of Dormand & Prince with the
//! 5th/3rd-order error estimate and the 7th-order continuous extension of Hairer's
//! `dop853.f` (Hairer, Norsett, Wanner, *Solving ODEs I*, sec. II.5 (p. 254) and II.6).
//!
//! Twelve stages; `f(t + h, y_new)` is evaluated only on accepted steps and reused as
//! `k_0` of the next (FSAL). With `err5_i = sum_j E5_j k_j,i / sc_i` and
//! `err3_i = sum_j E3_j k_j,i / sc_i` (`E3 = b - b_hat3`), the error norm is
//!
//! ```text
//! err = |h| S5 / sqrt(n (S5 + 0.01 S3)),   S5 = sum_i err5_i^2,  S3 = sum_i err3_i^2,
//! ```
//!
//! an 8th-order-consistent estimate that behaves like the 5th-order one for large
//! steps. The dense output (Hairer's `contd8`) needs three more stages `k_13 .. k_15`,
//! computed only for accepted steps with output times inside them.
//!
//! Coefficients copied from `scipy/integrate/_ivp/dop853_coefficients.py` (Hairer's
//! values to 30 digits).
#![allow(clippy::excessive_precision)]

use super::adaptive::{scaled_sums, Attempt, Control, Scheme};
use super::form::Form;
use super::tableau::{Stages, Tableau};
use crate::simd::{dispatch, Kernel, MulAdd};

/// The DOP853 pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dop853;

/// Nodes `c_i` of the 12 stages of the step.
pub(crate) const C: [f64; 12] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
];
/// The coupling coefficients `a_ij` of the 12 stages (strict lower triangle, row by row).
pub(crate) const A: [&[f64]; 12] = [
    &[],
    &[5.26001519587677318785587544488e-2],
    &[1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2],
    &[2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2],
    &[2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1, 9.24834003261792003115737966543e-1],
    &[
        3.7037037037037037037037037037e-2,
        0.0,
        0.0,
        1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
    ],
    &[3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2, -1.7578125e-2],
    &[
        3.70920001185047927108779319836e-2,
        0.0,
        0.0,
        1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1,
        -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
    ],
    &[
        6.24110958716075717114429577812e-1,
        0.0,
        0.0,
        -3.36089262944694129406857109825,
        -8.68219346841726006818189891453e-1,
        2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1,
        -4.34898841810699588477366255144e1,
    ],
    &[
        4.77662536438264365890433908527e-1,
        0.0,
        0.0,
        -2.48811461997166764192642586468,
        -5.90290826836842996371446475743e-1,
        2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1,
        -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
    ],
    &[
        -9.3714243008598732571704021658e-1,
        0.0,
        0.0,
        5.18637242884406370830023853209,
        1.09143734899672957818500254654,
        -8.14978701074692612513997267357,
        -1.85200656599969598641566180701e1,
        2.27394870993505042818970056734e1,
        2.49360555267965238987089396762,
        -3.0467644718982195003823669022,
    ],
    &[
        2.27331014751653820792359768449,
        0.0,
        0.0,
        -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444,
        -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1,
        -2.85899827713502369474065508674,
        -8.87285693353062954433549289258,
        1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ],
];
/// The 8th-order weights `b_i` (row 12 of scipy's `A`).
pub(crate) const B: [f64; 12] = [
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
];
/// Nodes of the three extra dense-output stages 13, 14, 15 (`k14 .. k16` in Hairer).
pub(crate) const C_EXTRA: [f64; 3] = [0.1, 0.2, 0.777777777777777777777777777778];
/// Coefficients of the extra stages; column 12 multiplies `f(t + h, y_new)`.
pub(crate) const A_EXTRA: [&[f64]; 3] = [
    &[
        5.61675022830479523392909219681e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        2.53500210216624811088794765333e-1,
        -2.46239037470802489917441475441e-1,
        -1.24191423263816360469010140626e-1,
        1.5329179827876569731206322685e-1,
        8.20105229563468988491666602057e-3,
        7.56789766054569976138603589584e-3,
        -8.298e-3,
    ],
    &[
        3.18346481635021405060768473261e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        2.83009096723667755288322961402e-2,
        5.35419883074385676223797384372e-2,
        -5.49237485713909884646569340306e-2,
        0.0,
        0.0,
        -1.08347328697249322858509316994e-4,
        3.82571090835658412954920192323e-4,
        -3.40465008687404560802977114492e-4,
        1.41312443674632500278074618366e-1,
    ],
    &[
        -4.28896301583791923408573538692e-1,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.69762141536116384314449447206,
        7.68342119606259904184240953878,
        4.06898981839711007970213554331,
        3.56727187455281109270669543021e-1,
        0.0,
        0.0,
        0.0,
        -1.39902416515901462129418009734e-3,
        2.9475147891527723389556272149,
        -9.15095847217987001081870187138,
    ],
];
/// Hairer's `bhh1, bhh2, bhh3`: the 3rd-order weights at stages 0, 8, 11.
const BHH: [f64; 3] =
    [0.244094488188976377952755905512, 0.733846688281611857341361741547, 0.220588235294117647058823529412e-1];
/// `E5 = b - b_hat5`, the 5th-order error weights.
pub(crate) const E5: [f64; 12] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e+1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e+1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];
/// Rows 4..7 of the dense-output polynomial (Hairer's `d4* .. d7*`) over the 16 stages.
pub(crate) const D: [[f64; 16]; 4] = [
    [
        -0.84289382761090128651353491142e+1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.56671495351937776962531783590,
        -0.30689499459498916912797304727e+1,
        0.23846676565120698287728149680e+1,
        0.21170345824450282767155149946e+1,
        -0.87139158377797299206789907490,
        0.22404374302607882758541771650e+1,
        0.63157877876946881815570249290,
        -0.88990336451333310820698117400e-1,
        0.18148505520854727256656404962e+2,
        -0.91946323924783554000451984436e+1,
        -0.44360363875948939664310572000e+1,
    ],
    [
        0.10427508642579134603413151009e+2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.24228349177525818288430175319e+3,
        0.16520045171727028198505394887e+3,
        -0.37454675472269020279518312152e+3,
        -0.22113666853125306036270938578e+2,
        0.77334326684722638389603898808e+1,
        -0.30674084731089398182061213626e+2,
        -0.93321305264302278729567221706e+1,
        0.15697238121770843886131091075e+2,
        -0.31139403219565177677282850411e+2,
        -0.93529243588444783865713862664e+1,
        0.35816841486394083752465898540e+2,
    ],
    [
        0.19985053242002433820987653617e+2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.38703730874935176555105901742e+3,
        -0.18917813819516756882830838328e+3,
        0.52780815920542364900561016686e+3,
        -0.11573902539959630126141871134e+2,
        0.68812326946963000169666922661e+1,
        -0.10006050966910838403183860980e+1,
        0.77771377980534432092869265740,
        -0.27782057523535084065932004339e+1,
        -0.60196695231264120758267380846e+2,
        0.84320405506677161018159903784e+2,
        0.11992291136182789328035130030e+2,
    ],
    [
        -0.25693933462703749003312586129e+2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.15418974869023643374053993627e+3,
        -0.23152937917604549567536039109e+3,
        0.35763911791061412378285349910e+3,
        0.93405324183624310003907691704e+2,
        -0.37458323136451633156875139351e+2,
        0.10409964950896230045147246184e+3,
        0.29840293426660503123344363579e+2,
        -0.43533456590011143754432175058e+2,
        0.96324553959188282948394950600e+2,
        -0.39177261675615439165231486172e+2,
        -0.14972683625798562581422125276e+3,
    ],
];
/// `E3 = b - b_hat3`, the 3rd-order error weights.
pub(crate) const E3: [f64; 12] =
    [B[0] - BHH[0], B[1], B[2], B[3], B[4], B[5], B[6], B[7], B[8] - BHH[1], B[9], B[10], B[11] - BHH[2]];

/// Row of `f(t + h, y_new)` in the stage storage.
const FSAL: usize = 12;

/// Selects `k_0 = f(t, y)` in a combination.
const F0: [f64; 1] = [1.0];

/// Selects `k_FSAL = f(t + h, y_new)` in a combination.
const F1: [f64; FSAL + 1] = {
    let mut unit = [0.0; FSAL + 1];
    unit[FSAL] = 1.0;
    unit
};

impl Scheme for Dop853 {
    const TABLEAU: Tableau = Tableau { c: &C, a: &A, b: &B };
    /// Hairer's defaults: `safe = 0.9`, `fac1 = 0.333`, `fac2 = 6`, `beta = 0`,
    /// `expo1 = 1/8 - 0.2 beta`.
    const CONTROL: Control =
        Control { safe: 0.9, fac1: 0.333, fac2: 6.0, beta: 0.0, expo1: 1.0 / 8.0 - 0.0 * 0.2, hinit_order: 8 };
    const ROWS: usize = 16;
    const FSAL: usize = FSAL;
    const FSAL_IN_ERROR: bool = false;
    const DENSE_ROWS: usize = 7;
    const EXTRA_INPUTS: &'static [&'static [f64]] = &A_EXTRA;

    fn error_norm<F: Form>(form: &F, k: &Stages, step: &Attempt<'_>, work: &mut [f64]) -> f64 {
        let Attempt { h, y, y_new, rtol, atol } = *step;
        let (e5, e3) = work.split_at_mut(y.len());
        form.combine(k, &E5, h, y, e5);
        form.combine(k, &E3, h, y, e3);
        let (s5, s3) = scaled_sums(e5, e3, y, y_new, rtol, atol);
        let mut deno = s5 + 0.01 * s3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * s5 * (1.0 / (y.len() as f64 * deno)).sqrt()
    }

    /// Hairer's `contd8` coefficients, with `D = y_new - y`:
    /// `r1 = D`, `r2 = h f_0 - D`, `r3 = 2 D - h (f_0 + f_1)`, `r4..r7 = h sum_j d_*j k_j`
    /// over the 16 stages (the extra stages `k_13 .. k_15` are evaluated here).
    fn dense_prepare<F: Form>(
        form: &F,
        t: f64,
        h: f64,
        y: &[f64],
        y_new: &[f64],
        k: &mut Stages,
        ytmp: &mut [f64],
        dense: &mut Stages,
    ) -> u64 {
        for (s, (&c, &a)) in C_EXTRA.iter().zip(A_EXTRA.iter()).enumerate() {
            form.eval_stage(k, FSAL + 1 + s, t + c * h, h, y, a, ytmp);
        }
        for (r, d_row) in D.iter().enumerate() {
            form.combine(k, d_row, h, y, dense.row_mut(3 + r));
            dense.row_mut(3 + r).iter_mut().for_each(|v| *v *= h);
        }
        // f_0 and f_1 = f(t + h, y_new) into rows 1 and 2, then the rows in place.
        form.combine(k, &F0, h, y, dense.row_mut(1));
        form.combine(k, &F1, h, y, dense.row_mut(2));
        for i in 0..y.len() {
            let d = y_new[i] - y[i];
            let (f0, f1) = (dense.row(1)[i], dense.row(2)[i]);
            dense.row_mut(0)[i] = d;
            dense.row_mut(1)[i] = h * f0 - d;
            dense.row_mut(2)[i] = 2.0 * d - h * (f1 + f0);
        }
        C_EXTRA.len() as u64
    }

    /// `u(s) = y + s (r1 + s' (r2 + s (r3 + s' (r4 + s (r5 + s' (r6 + s r7))))))`,
    /// `s' = 1 - s`.
    fn dense_eval(dense: &Stages, y: &[f64], s: f64, out: &mut [f64]) {
        let s1 = 1.0 - s;
        let n = out.len();
        // The seven rows sliced once, to the length of `out` (no bounds checks in the loop).
        let r: [&[f64]; 7] = std::array::from_fn(|j| &dense.row(j)[..n]);
        let y = &y[..n];
        for i in 0..n {
            out[i] = dense_value(r.map(|r| r[i]), y[i], s, s1);
        }
    }

    /// Small systems ([`BLOCK_MAX_DIM`] unknowns or fewer) [`BLOCK_LANES`] samples at a time,
    /// side by side in vector registers ([`dispatch`]); sample by sample the few components
    /// of one sample filled a fraction of a register, and each value was a chain of seven
    /// dependent multiply-adds. The same operations per value: the same bits.
    fn dense_eval_block(dense: &Stages, y: &[f64], t: f64, h: f64, times: &[f64], out: &mut [f64]) {
        let n = y.len();
        if n > BLOCK_MAX_DIM {
            for (&t_out, row) in times.iter().zip(out.chunks_exact_mut(n)) {
                Self::dense_eval(dense, y, (t_out - t) / h, row);
            }
            return;
        }
        let r: [&[f64]; 7] = std::array::from_fn(|j| &dense.row(j)[..n]);
        dispatch(DenseBlock { r, y, t, h, times, out });
    }
}

/// One value of the continuous extension ([`Dop853::dense_eval`]) from the seven
/// coefficients `r` and `y` of its component, at `s` (`s1 = 1 - s`).
#[inline(always)]
fn dense_value(r: [f64; 7], y: f64, s: f64, s1: f64) -> f64 {
    let conpar = r[3] + s * (r[4] + s1 * (r[5] + s * r[6]));
    y + s * (r[0] + s1 * (r[1] + s * (r[2] + s1 * conpar)))
}

/// Samples evaluated side by side by [`Dop853::dense_eval_block`]. Four, not eight: a step
/// holds about a dozen samples of a dense output (the 3-mode case's 20,001 over 1,738 steps),
/// and eight lanes were a third empty (measured slower than the sample-by-sample loop).
const BLOCK_LANES: usize = 4;
/// The largest system evaluated in blocks of samples (larger ones fill the registers with
/// their own components, sample by sample).
const BLOCK_MAX_DIM: usize = 8;

/// The kernel of [`Dop853::dense_eval_block`].
struct DenseBlock<'a> {
    r: [&'a [f64]; 7],
    y: &'a [f64],
    t: f64,
    h: f64,
    times: &'a [f64],
    out: &'a mut [f64],
}

impl Kernel for DenseBlock<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: MulAdd>(self) {
        let DenseBlock { r, y, t, h, times, out } = self;
        let n = y.len();
        for (ts, rows) in times.chunks(BLOCK_LANES).zip(out.chunks_mut(BLOCK_LANES * n)) {
            let s: [f64; BLOCK_LANES] = std::array::from_fn(|lane| (ts[lane.min(ts.len() - 1)] - t) / h);
            let s1 = s.map(|s| 1.0 - s);
            let mut tile = [[0.0; BLOCK_LANES]; BLOCK_MAX_DIM];
            for (i, tile) in tile[..n].iter_mut().enumerate() {
                let ri = r.map(|r| r[i]);
                *tile = std::array::from_fn(|lane| dense_value(ri, y[i], s[lane], s1[lane]));
            }
            // Through memory, behind a barrier: taken out of the registers lane by lane into
            // the rows, the values above are no longer computed side by side.
            let tile = std::hint::black_box(&mut tile);
            for (lane, row) in rows.chunks_exact_mut(n).enumerate() {
                for (i, v) in row.iter_mut().enumerate() {
                    *v = tile[i][lane];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::tableau::check_consistency;

    #[test]
    fn tableau_is_consistent() {
        check_consistency(&Dop853::TABLEAU, 1e-13);
        for (row, &c) in A_EXTRA.iter().zip(&C_EXTRA) {
            let sum: f64 = row.iter().sum();
            assert!((sum - c).abs() < 1e-13, "extra row sum {sum} vs c {c}");
        }
        // Both error estimates are differences of consistent weights.
        assert!(E5.iter().sum::<f64>().abs() < 1e-13);
        assert!(E3.iter().sum::<f64>().abs() < 1e-13);
    }
}

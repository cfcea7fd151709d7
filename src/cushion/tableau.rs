//! The embedded explicit Runge-Kutta steps of the impact: classical RK4, Dormand-Prince
//! 5(4) and Dormand-Prince 8(5,3), one step at a time on the stack (no allocation), with the
//! error norm and the step-size control of Hairer, Nørsett and Wanner's codes DOPRI5 and
//! DOP853 (Solving ODEs I, 2nd ed., II.4-5 and II.10). The right-hand side is autonomous
//! (it does not depend on P_I), so the nodes c_i are not needed to step.

/// Length of the stepped state: the impact's state and the impulse P_I (the independent
/// variable is P_I or, while a slip runs out, the logarithm of that slip).
pub(crate) const DIM: usize = 9;

/// The stepped state.
pub(crate) type Z = [f64; DIM];

/// Dormand-Prince 5(4): a_ij, rows 2..7 (row 7 is the 5th-order solution, FSAL).
pub(crate) const DOPRI5_A: [[f64; 6]; 6] = [
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];

/// Dormand-Prince 5(4): the error weights, b_i - b*_i.
pub(crate) const DOPRI5_E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// DOP853's coefficients a_ij (rows 2..12, zero-padded to 11 columns; Hairer's DOP853).
#[allow(clippy::excessive_precision)]
const DOP853_A: [[f64; 11]; 11] = [
    [
        5.26001519587677318785587544488e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        1.97250569845378994544595329183e-2,
        5.91751709536136983633785987549e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        2.95875854768068491816892993775e-2,
        0.0,
        8.87627564304205475450678981324e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        2.41365134159266685502369798665e-1,
        0.0,
        -8.84549479328286085344864962717e-1,
        9.24834003261792003115737966543e-1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        3.7037037037037037037037037037e-2,
        0.0,
        0.0,
        1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        3.7109375e-2,
        0.0,
        0.0,
        1.70252211019544039314978060272e-1,
        6.02165389804559606850219397283e-2,
        -1.7578125e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        3.70920001185047927108779319836e-2,
        0.0,
        0.0,
        1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1,
        -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        6.24110958716075717114429577812e-1,
        0.0,
        0.0,
        -3.36089262944694129406857109825e0,
        -8.68219346841726006818189891453e-1,
        2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1,
        -4.34898841810699588477366255144e1,
        0.0,
        0.0,
        0.0,
    ],
    [
        4.77662536438264365890433908527e-1,
        0.0,
        0.0,
        -2.48811461997166764192642586468e0,
        -5.90290826836842996371446475743e-1,
        2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1,
        -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
        0.0,
        0.0,
    ],
    [
        -9.3714243008598732571704021658e-1,
        0.0,
        0.0,
        5.18637242884406370830023853209e0,
        1.09143734899672957818500254654e0,
        -8.14978701074692612513997267357e0,
        -1.85200656599969598641566180701e1,
        2.27394870993505042818970056734e1,
        2.49360555267965238987089396762e0,
        -3.0467644718982195003823669022e0,
        0.0,
    ],
    [
        2.27331014751653820792359768449e0,
        0.0,
        0.0,
        -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444e0,
        -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1,
        -2.85899827713502369474065508674e0,
        -8.87285693353062954433549289258e0,
        1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ],
];

/// DOP853's weights b_i of the 8th-order solution.
#[allow(clippy::excessive_precision)]
const DOP853_B: [f64; 12] = [
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566e0,
    1.89151789931450038304281599044e0,
    -5.8012039600105847814672114227e0,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
];

/// DOP853's 5th-order error weights (Hairer's er_i).
#[allow(clippy::excessive_precision)]
const DOP853_E5: [f64; 12] = [
    0.1312004499419488073250102996e-01,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e+01,
    -0.4957589496572501915214079952e+00,
    0.1664377182454986536961530415e+01,
    -0.3503288487499736816886487290e+00,
    0.3341791187130174790297318841e+00,
    0.8192320648511571246570742613e-01,
    -0.2235530786388629525884427845e-01,
];

/// DOP853's 3rd-order error weights on stages 1, 9 and 12 (Hairer's bhh_i).
#[allow(clippy::excessive_precision)]
const DOP853_BHH: [f64; 3] = [
    0.244094488188976377952755905512e+00,
    0.733846688281611857341361741547e+00,
    0.220588235294117647058823529412e-01,
];

/// DOP853's nodes c_2..c_12 (c_12 = 1; the right-hand side is autonomous, so they only
/// check the tableau: each row of a sums to its node).
#[allow(clippy::excessive_precision, dead_code)]
const DOP853_C: [f64; 11] = [
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510e+00,
    0.281649658092772603273242802490e+00,
    0.333333333333333333333333333333e+00,
    0.25e+00,
    0.307692307692307692307692307692e+00,
    0.651282051282051282051282051282e+00,
    0.6e+00,
    0.857142857142857142857142857142e+00,
    1.0,
];

/// Weight of DOP853's 3rd-order error estimate in its error norm (Hairer's 0.01).
const DOP853_ERR3_WEIGHT: f64 = 0.01;

/// The methods the kernel steps with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scheme {
    /// Classical RK4, fixed steps, no error estimate.
    Rk4,
    /// Dormand-Prince 5(4).
    Dopri5,
    /// Dormand-Prince 8(5,3).
    Dop853,
}

/// Step-size control of an embedded pair (the published constants of DOPRI5 and DOP853,
/// without DOPRI5's PI term: the impact's runs are a few dozen steps).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StepControl {
    /// Factor on the optimal step-size proposal.
    pub(crate) safety: f64,
    /// Smallest ratio of a new step to the old one.
    pub(crate) fac_min: f64,
    /// Largest ratio of a new step to the old one.
    pub(crate) fac_max: f64,
    /// Exponent of the error norm: 1 / (order of the error estimate + 1).
    pub(crate) exponent: f64,
}

/// DOPRI5's control: safety 0.9, ratios in [0.2, 10], error of order 4.
pub(crate) const DOPRI5_CONTROL: StepControl = StepControl {
    safety: 0.9,
    fac_min: 0.2,
    fac_max: 10.0,
    exponent: 0.2,
};

/// DOP853's control: safety 0.9, ratios in [0.333, 6], error exponent 1/8.
pub(crate) const DOP853_CONTROL: StepControl = StepControl {
    safety: 0.9,
    fac_min: 0.333,
    fac_max: 6.0,
    exponent: 0.125,
};

impl StepControl {
    /// The next step after a step of size `h` with error norm `err` (accepted when <= 1).
    pub(crate) fn next(&self, h: f64, err: f64) -> f64 {
        let fac = if err > 0.0 {
            self.safety * err.powf(-self.exponent)
        } else {
            self.fac_max
        };
        h * fac.clamp(self.fac_min, self.fac_max)
    }
}

/// One step: the new state, its error norm (0 for rk4) and the right-hand-side evaluations
/// it took.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Step {
    /// The state after the step.
    pub(crate) y: Z,
    /// Error norm (<= 1: acceptable).
    pub(crate) err: f64,
    /// Evaluations of the right-hand side.
    pub(crate) evals: u64,
    /// The derivative at the new state when the method computed it (DOPRI5's last stage,
    /// first same as last).
    pub(crate) last: Option<Z>,
}

/// Tolerances of the error norm.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tolerance {
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
}

/// y0 + h (a_1 k_1 + a_2 k_2 + ...), component by component.
macro_rules! combine {
    ($y0:expr, $h:expr; $a0:expr, $k0:expr $(, $a:expr, $k:expr)*) => {{
        let mut out = *$y0;
        for i in 0..DIM {
            out[i] += $h * ($a0 * $k0[i] $(+ $a * $k[i])*);
        }
        out
    }};
}

fn add_scaled(y: &Z, k: &[Z], a: &[f64], h: f64) -> Z {
    let mut out = *y;
    for (kj, &aj) in k.iter().zip(a) {
        if aj != 0.0 {
            for i in 0..DIM {
                out[i] += h * aj * kj[i];
            }
        }
    }
    out
}

/// One step of `scheme` of size `h` from `y0`, whose derivative is `k1`; `f` is the
/// right-hand side.
pub(crate) fn step<F: FnMut(&Z) -> Z>(
    scheme: Scheme,
    f: &mut F,
    y0: &Z,
    k1: &Z,
    h: f64,
    tol: Tolerance,
) -> Step {
    match scheme {
        Scheme::Rk4 => {
            let k2 = f(&add_scaled(y0, &[*k1], &[0.5], h));
            let k3 = f(&add_scaled(y0, &[k2], &[0.5], h));
            let k4 = f(&add_scaled(y0, &[k3], &[1.0], h));
            let y = add_scaled(
                y0,
                &[*k1, k2, k3, k4],
                &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
                h,
            );
            Step {
                y,
                err: 0.0,
                evals: 3,
                last: None,
            }
        }
        Scheme::Dopri5 => {
            // The stages written out (no zero coefficients, no loop over the stages):
            // the step is a chain of dependent evaluations, and the generic sums were a
            // fifth of the step's time between them.
            let a = &DOPRI5_A;
            let k2 = f(&combine!(y0, h; a[0][0], k1));
            let k3 = f(&combine!(y0, h; a[1][0], k1, a[1][1], k2));
            let k4 = f(&combine!(y0, h; a[2][0], k1, a[2][1], k2, a[2][2], k3));
            let k5 = f(&combine!(y0, h; a[3][0], k1, a[3][1], k2, a[3][2], k3, a[3][3], k4));
            let k6 = f(&combine!(
                y0, h; a[4][0], k1, a[4][1], k2, a[4][2], k3, a[4][3], k4, a[4][4], k5
            ));
            // b_2 = 0.
            let y =
                combine!(y0, h; a[5][0], k1, a[5][2], k3, a[5][3], k4, a[5][4], k5, a[5][5], k6);
            let k7 = f(&y);
            let e = &DOPRI5_E;
            let mut sum = 0.0;
            for i in 0..DIM {
                // e_2 = 0.
                let d = e[0] * k1[i]
                    + e[2] * k3[i]
                    + e[3] * k4[i]
                    + e[4] * k5[i]
                    + e[5] * k6[i]
                    + e[6] * k7[i];
                let sc = tol.atol + tol.rtol * y0[i].abs().max(y[i].abs());
                let q = h * d / sc;
                sum += q * q;
            }
            Step {
                y,
                err: (sum / DIM as f64).sqrt(),
                evals: 6,
                last: Some(k7),
            }
        }
        Scheme::Dop853 => {
            let mut k = [[0.0; DIM]; 12];
            k[0] = *k1;
            for s in 1..12 {
                let ys = add_scaled(y0, &k[..s], &DOP853_A[s - 1][..s], h);
                k[s] = f(&ys);
            }
            let y = add_scaled(y0, &k, &DOP853_B, h);
            let (mut err5, mut err3) = (0.0, 0.0);
            for i in 0..DIM {
                let mut e5 = 0.0;
                let mut b = 0.0;
                for s in 0..12 {
                    e5 += DOP853_E5[s] * k[s][i];
                    b += DOP853_B[s] * k[s][i];
                }
                let e3 = b
                    - DOP853_BHH[0] * k[0][i]
                    - DOP853_BHH[1] * k[8][i]
                    - DOP853_BHH[2] * k[11][i];
                let sc = tol.atol + tol.rtol * y0[i].abs().max(y[i].abs());
                err5 += (e5 / sc) * (e5 / sc);
                err3 += (e3 / sc) * (e3 / sc);
            }
            let mut deno = err5 + DOP853_ERR3_WEIGHT * err3;
            if deno <= 0.0 {
                deno = 1.0;
            }
            Step {
                y,
                err: h.abs() * err5 / (deno * DIM as f64).sqrt(),
                evals: 11,
                last: None,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cushion::rhs::{Friction, Modes, Rhs};

    /// The cushion's right-hand side for a stun shot at 45 degrees, both contacts sliding
    /// (their slips turn and neither stops before P_I = 0.3 in units of m v_ref), stepped
    /// with n fixed steps of each scheme: the state at P_I = 0.3.
    fn fixed_steps(scheme: Scheme, n: u32) -> Z {
        let s = 0.4f64;
        let rhs = Rhs {
            c: (1.0 - s * s).sqrt(),
            s,
            inv_alpha: 2.5,
            mu_i: 0.2,
            mu_c: 0.2,
        };
        let sliding = Friction::Sliding {
            seed: [1.0, 0.0],
            origin: [0.0, 0.0],
            floor: 0.0,
        };
        let modes = Modes {
            cushion: sliding,
            table: sliding,
            airborne: false,
        };
        let mut f = |z: &Z| {
            let mut y = [0.0; 8];
            y.copy_from_slice(&z[..8]);
            let e = rhs.eval(&modes, &y);
            let mut dz = [0.0; DIM];
            dz[..8].copy_from_slice(&e.dy);
            dz[DIM - 1] = 1.0;
            dz
        };
        let r = 0.5f64.sqrt();
        let mut z: Z = [r, r, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let h = 0.3 / f64::from(n);
        let tol = Tolerance {
            rtol: 1e-10,
            atol: 1e-10,
        };
        for _ in 0..n {
            let k1 = f(&z);
            z = step(scheme, &mut f, &z, &k1, h, tol).y;
        }
        z
    }

    /// Each scheme converges at its order on a right-hand side whose slip directions turn:
    /// halving the step divides the error by about 2^order (4, 5, 8).
    #[test]
    fn orders() {
        let reference = fixed_steps(Scheme::Dop853, 256);
        let err = |scheme, n| {
            let z = fixed_steps(scheme, n);
            (0..6)
                .map(|i| (z[i] - reference[i]).abs())
                .fold(0.0, f64::max)
        };
        for (scheme, n, order) in [
            (Scheme::Rk4, 8, 4.0),
            (Scheme::Dopri5, 4, 5.0),
            (Scheme::Dop853, 2, 8.0),
        ] {
            let (e1, e2) = (err(scheme, n), err(scheme, 2 * n));
            let observed = (e1 / e2).log2();
            // At least the order (DOPRI5's error falls as h^5.8 here: the leading term of
            // its global error is small on this right-hand side).
            assert!(
                observed > order - 0.5 && observed < order + 1.0,
                "{scheme:?}: {e1:e} {e2:e}, order {observed}"
            );
        }
    }

    /// Each row of a sums to its node (the tableaux are copied right).
    #[test]
    fn rows_sum_to_nodes() {
        let c5 = [0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
        for (row, c) in DOPRI5_A.iter().zip(c5) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14, "{row:?}");
        }
        for (row, c) in DOP853_A.iter().zip(DOP853_C) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-13, "{row:?}");
        }
        assert!((DOP853_B.iter().sum::<f64>() - 1.0).abs() < 1e-13);
        assert!(DOPRI5_E.iter().sum::<f64>().abs() < 1e-15);
        assert!(DOP853_E5.iter().sum::<f64>().abs() < 1e-13);
        assert!((DOP853_BHH.iter().sum::<f64>() - 1.0).abs() < 1e-13);
    }
}

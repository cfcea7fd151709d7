//! The tangential kernel's own adaptive step: Dormand and Prince's 5(4) pair (J. R. Dormand,
//! P. J. Prince, J. Comput. Appl. Math. 6 (1980) 19-26) with the error norm and step-size
//! control of Hairer, Nørsett and Wanner's code DOPRI5 (Solving ODEs I, 2nd ed., II.4, Table
//! 5.2 and II.4's "automatic step size control"). The coefficients are copied from that
//! table (the same ones as the cushion kernel's, which lives beside this one in the kernel
//! layer and so cannot be imported); the test below checks each row sums to its node.

/// Length of the stepped state: compression, its rate, ball 1's relative tangential velocity
/// (2), its spin (3), the tangential spring's force (2), the partner's spin (3) and the work
/// the tangential force has taken from the balls (1; error scale 0: a quadrature along the
/// path, which never steers the step).
pub(crate) const DIM: usize = 13;

/// The stepped state.
pub(crate) type Z = [f64; DIM];

/// Dormand-Prince 5(4): a_ij, rows 2..7 (row 7 is the 5th-order solution, FSAL).
const A: [[f64; 6]; 6] = [
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

/// Dormand-Prince 5(4): the error weights b_i - b*_i.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// DOPRI5's safety factor on the optimal step proposal.
const SAFETY: f64 = 0.9;
/// Smallest ratio of a new step to the old one.
const FAC_MIN: f64 = 0.2;
/// Largest ratio of a new step to the old one.
const FAC_MAX: f64 = 10.0;
/// Exponent of the error norm: 1 / (order of the error estimate + 1).
const EXPONENT: f64 = 0.2;

/// The step after a step of size `h` with error norm `err` (accepted when <= 1).
pub(crate) fn next_step(h: f64, err: f64) -> f64 {
    let fac = if err > 0.0 {
        SAFETY * err.powf(-EXPONENT)
    } else {
        FAC_MAX
    };
    h * fac.clamp(FAC_MIN, FAC_MAX)
}

/// One step of size `h` from `y0` under the right-hand side `f`: the new state and its error
/// norm, the root mean square of the local error over atol scale_i + rtol max|y_i|, taken over
/// the components of non-zero scale (a component of scale 0 is one that never moves: the
/// spin of a plane).
pub(crate) fn step<F: Fn(&Z) -> Z>(
    f: &F,
    y0: &Z,
    h: f64,
    scale: &Z,
    rtol: f64,
    atol: f64,
) -> (Z, f64) {
    let mut k = [[0.0; DIM]; 7];
    k[0] = f(y0);
    for s in 1..7 {
        let mut ys = *y0;
        for (kj, &aj) in k[..s].iter().zip(&A[s - 1][..s]) {
            for i in 0..DIM {
                ys[i] += h * aj * kj[i];
            }
        }
        k[s] = f(&ys);
    }
    let mut y = *y0;
    for (kj, &aj) in k[..6].iter().zip(&A[5]) {
        for i in 0..DIM {
            y[i] += h * aj * kj[i];
        }
    }
    let mut sum = 0.0;
    let mut active = 0usize;
    for i in 0..DIM {
        if scale[i] == 0.0 {
            continue;
        }
        active += 1;
        let e: f64 = k.iter().zip(E).map(|(ks, es)| es * ks[i]).sum();
        let sc = atol * scale[i] + rtol * y0[i].abs().max(y[i].abs());
        let q = h * e / sc;
        sum += q * q;
    }
    (y, (sum / active.max(1) as f64).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each row of a sums to its node, the error weights to 0 (the tableau is copied right),
    /// and a step of y' = -y is accurate to its order.
    #[test]
    fn tableau_and_one_step() {
        let c = [0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
        for (row, c) in A.iter().zip(c) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14, "{row:?}");
        }
        assert!(E.iter().sum::<f64>().abs() < 1e-15);
        let f = |y: &Z| {
            let mut d = [0.0; DIM];
            for i in 0..DIM {
                d[i] = -y[i];
            }
            d
        };
        let (y, err) = step(&f, &[1.0; DIM], 0.1, &[1.0; DIM], 1e-6, 1e-6);
        assert!((y[0] - (-0.1f64).exp()).abs() < 1e-8, "{}", y[0]);
        assert!(err < 1.0);
    }
}

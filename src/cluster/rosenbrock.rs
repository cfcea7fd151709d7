//! A linearly implicit (Rosenbrock-W) step for the stiff part of a cluster's right-hand side
//! (docs/cluster.md, "Stiff slips"): ROS34PW2 of J. Rang and L. Angermann, "New Rosenbrock
//! W-methods of order 3 for partial differential algebraic equations of index 1", BIT
//! Numerical Mathematics 45 (2005) 761-787 (its Table 4.2 in the form of E. Hairer and G.
//! Wanner, Solving Ordinary Differential Equations II, section IV.7: stage matrices alpha,
//! gamma). Four stages, order 3 with an embedded order 2, L-stable, stiffly accurate, and a
//! W-method: it keeps its order with any matrix in place of the Jacobian, so the step can
//! carry only the stiff directions' part of it, frozen at the step's start.

/// The diagonal gamma of ROS34PW2.
pub(super) const GAMMA: f64 = 4.358_665_215_084_59e-1;

/// Stage offsets alpha_ij (j < i): stage i is evaluated at y0 + sum_j alpha_ij k_j.
const ALPHA: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [8.717_330_430_169_18e-1, 0.0, 0.0],
    [8.445_706_001_536_942e-1, -1.129_906_423_648_418_5e-1, 0.0],
    [0.0, 0.0, 1.0],
];

/// Off-diagonal gamma_ij (j < i): stage i's right-hand side carries h J sum_j gamma_ij k_j.
const GAMMA_OFF: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [-8.717_330_430_169_18e-1, 0.0, 0.0],
    [-9.033_805_701_304_408e-1, 5.418_067_238_809_533e-2, 0.0],
    [
        2.421_238_070_609_534_6e-1,
        -1.223_250_583_904_514_7,
        5.452_602_553_351_021e-1,
    ],
];

/// Weights of the order-3 solution.
const B: [f64; 4] = [
    2.421_238_070_609_534_6e-1,
    -1.223_250_583_904_514_7,
    1.545_260_255_335_102,
    4.358_665_215_084_59e-1,
];

/// Weights of the embedded order-2 solution.
const B_HAT: [f64; 4] = [
    3.781_090_314_581_937e-1,
    -9.604_229_221_242_318e-2,
    5.0e-1,
    2.179_332_607_542_295e-1,
];

/// What one step needs of the problem: the right-hand side, and the matrix J standing for
/// its Jacobian (any matrix keeps the order; the stiff directions' part keeps it stable).
pub(super) trait Linearised {
    /// dy/dt at `y` into `out`.
    fn rhs(&mut self, y: &[f64], out: &mut [f64]);
    /// out += scale J x.
    fn add_jacobian_times(&self, x: &[f64], scale: f64, out: &mut [f64]);
    /// x <- (I - h gamma J)^(-1) x, for the step's h (fixed when the problem is built).
    fn solve(&self, x: &mut [f64]);
}

/// One ROS34PW2 step of size `h` from `y0`, `k0` the derivative there: the new state and the
/// difference between it and the embedded solution (the local error estimate, order 3).
pub(super) fn step<P: Linearised>(
    p: &mut P,
    y0: &[f64],
    k0: &[f64],
    h: f64,
) -> (Vec<f64>, Vec<f64>) {
    let n = y0.len();
    let mut k = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut ys = vec![0.0; n];
    let mut g = vec![0.0; n];
    let mut f = vec![0.0; n];
    for s in 0..4 {
        if s == 0 {
            f.copy_from_slice(k0);
        } else {
            ys.copy_from_slice(y0);
            for (kj, &a) in k[..s].iter().zip(&ALPHA[s][..s]) {
                if a != 0.0 {
                    for (yi, ki) in ys.iter_mut().zip(kj) {
                        *yi += a * ki;
                    }
                }
            }
            p.rhs(&ys, &mut f);
        }
        // h f + h J sum_j gamma_ij k_j, then solved with W = I - h gamma J.
        g.fill(0.0);
        for (kj, &c) in k[..s].iter().zip(&GAMMA_OFF[s][..s]) {
            for (gi, ki) in g.iter_mut().zip(kj) {
                *gi += c * ki;
            }
        }
        let mut r: Vec<f64> = f.iter().map(|v| h * v).collect();
        if s > 0 {
            p.add_jacobian_times(&g, h, &mut r);
        }
        p.solve(&mut r);
        k[s] = r;
    }
    let mut y1 = y0.to_vec();
    let mut err = vec![0.0; n];
    for (s, ks) in k.iter().enumerate() {
        let d = B[s] - B_HAT[s];
        for ((yi, ei), ki) in y1.iter_mut().zip(&mut err).zip(ks) {
            *yi += B[s] * ki;
            *ei += d * ki;
        }
    }
    (y1, err)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = A y + (0, -y1^2): a stiff linear part (eigenvalues -1 and -lambda) with a
    /// nonlinear coupling; `j` the matrix standing for the Jacobian.
    struct Problem {
        lambda: f64,
        j: [[f64; 2]; 2],
        h: f64,
    }

    impl Linearised for Problem {
        fn rhs(&mut self, y: &[f64], out: &mut [f64]) {
            out[0] = -y[0];
            out[1] = -self.lambda * (y[1] - y[0] * y[0]) + 2.0 * y[0] * (-y[0]);
        }
        fn add_jacobian_times(&self, x: &[f64], scale: f64, out: &mut [f64]) {
            for (o, row) in out.iter_mut().zip(&self.j) {
                *o += scale * (row[0] * x[0] + row[1] * x[1]);
            }
        }
        fn solve(&self, x: &mut [f64]) {
            let c = self.h * GAMMA;
            let m = [
                [1.0 - c * self.j[0][0], -c * self.j[0][1]],
                [-c * self.j[1][0], 1.0 - c * self.j[1][1]],
            ];
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            let (a, b) = (x[0], x[1]);
            x[0] = (m[1][1] * a - m[0][1] * b) / det;
            x[1] = (m[0][0] * b - m[1][0] * a) / det;
        }
    }

    /// The problem's exact solution from y(0) = (1, 1): y1 = e^-t, and y2 = y1^2 solves
    /// the second equation exactly (y2 - y1^2 = 0 stays 0, y2' = 2 y1 y1' = -2 y1^2), the
    /// slow manifold of the stiff component, at every lambda.
    fn exact(t: f64) -> [f64; 2] {
        let e = (-t).exp();
        [e, e * e]
    }

    /// The global error at t = 1 after `steps` steps, and the largest error estimate of a
    /// step; `jac` gives the matrix standing for the Jacobian at each step's start.
    fn run(lambda: f64, jac: impl Fn(&[f64]) -> [[f64; 2]; 2], steps: usize) -> (f64, f64) {
        let t_end = 1.0;
        let h = t_end / steps as f64;
        let mut p = Problem {
            lambda,
            j: [[0.0; 2]; 2],
            h,
        };
        let mut y = vec![1.0, 1.0];
        let mut est: f64 = 0.0;
        for _ in 0..steps {
            let mut k0 = vec![0.0; 2];
            p.rhs(&y, &mut k0);
            p.j = jac(&y);
            let (y1, e) = step(&mut p, &y, &k0, h);
            est = est.max(e[0].abs().max(e[1].abs()));
            y = y1;
        }
        let x = exact(t_end);
        ((y[0] - x[0]).abs().max((y[1] - x[1]).abs()), est)
    }

    #[test]
    fn third_order_with_any_jacobian_and_stable_where_it_is_stiff() {
        // Non-stiff, the matrix far from the Jacobian (zero; a wrong one): the global error
        // falls as h^3 (a factor 8 per halving), the error estimate as h^3 per step.
        for j in [[[0.0, 0.0], [0.0, 0.0]], [[0.3, -2.0], [1.0, 0.7]]] {
            let e: Vec<(f64, f64)> = [20, 40, 80].iter().map(|&n| run(2.0, |_| j, n)).collect();
            for w in e.windows(2) {
                let ratio = w[0].0 / w[1].0;
                assert!((6.5..10.0).contains(&ratio), "{e:?}");
                let est = w[0].1 / w[1].1;
                assert!((6.0..10.0).contains(&est), "{e:?}");
            }
        }
        // Stiff (lambda 1e8, the explicit step's limit 3e-8): with the stiff part of the
        // Jacobian (the terms in lambda, at the step's start) 20 steps of 0.05 stay on the
        // slow manifold, and the error falls as h^3 as for the non-stiff problem.
        let lambda = 1e8;
        let stiff = |y: &[f64]| [[0.0, 0.0], [2.0 * lambda * y[0], -lambda]];
        let e: Vec<(f64, f64)> = [20, 40, 80]
            .iter()
            .map(|&n| run(lambda, stiff, n))
            .collect();
        assert!(e[0].0 < 1e-4, "{e:?}");
        for w in e.windows(2) {
            assert!((6.5..10.0).contains(&(w[0].0 / w[1].0)), "{e:?}");
        }
    }
}

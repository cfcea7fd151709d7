//! The 1D Hertz chain, an independent reference for the cluster tests (tests/cluster.rs,
//! tests/cluster_scenes.rs): nothing of the crate is used.

/// The 1D Hertz chain m x_i'' = k [d_(i-1)]^(3/2) - k [d_i]^(3/2), d_i = x_i - x_(i+1) the
/// overlap of neighbours i, i + 1 (x from each ball's start, all touching; [.] the positive
/// part), integrated by classical RK4 at the fixed step h (s) until every overlap is gone and
/// the velocities are ordered (no pair approaches). Returns the final velocities (m/s).
pub fn hertz_chain_rk4(k: f64, m: f64, v0: &[f64], h: f64) -> Vec<f64> {
    let n = v0.len();
    let rate = |y: &[f64]| -> Vec<f64> {
        let mut d = vec![0.0; 2 * n];
        d[..n].copy_from_slice(&y[n..]);
        for i in 0..n - 1 {
            let o = y[i] - y[i + 1];
            if o > 0.0 {
                let f = k * o * o.sqrt();
                d[n + i] -= f / m;
                d[n + i + 1] += f / m;
            }
        }
        d
    };
    let mut y: Vec<f64> = vec![0.0; n];
    y.extend_from_slice(v0);
    let add = |a: &[f64], b: &[f64], s: f64| -> Vec<f64> {
        a.iter().zip(b).map(|(x, y)| x + s * y).collect()
    };
    loop {
        let k1 = rate(&y);
        let k2 = rate(&add(&y, &k1, h / 2.0));
        let k3 = rate(&add(&y, &k2, h / 2.0));
        let k4 = rate(&add(&y, &k3, h));
        for i in 0..2 * n {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        if (0..n - 1).all(|i| y[i] < y[i + 1] && y[n + i] <= y[n + i + 1]) {
            return y[n..].to_vec();
        }
    }
}

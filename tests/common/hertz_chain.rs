//! The 1D Hertz chain, an independent reference for the cluster tests (tests/cluster.rs,
//! tests/cluster_scenes.rs): nothing of the crate is used.

/// The 1D Hertz chain m x_i'' = k [d_(i-1)]^(3/2) - k [d_i]^(3/2), d_i = x_i - x_(i+1) the
/// overlap of neighbours i, i + 1 (x from each ball's start, all touching; [.] the positive
/// part), integrated by classical RK4 at the fixed step h (s) until every overlap is gone and
/// the velocities are ordered (no pair approaches). Returns the final velocities (m/s).
pub fn hertz_chain_rk4(k: f64, m: f64, v0: &[f64], h: f64) -> Vec<f64> {
    // The Kuwabara-Kono line without damping, each ball's centre at 0 with radius 0: the
    // overlap of neighbours is then x_i - x_(i+1), as written above.
    let n = v0.len();
    kuwabara_kono_line_rk4(
        &vec![m; n],
        &vec![0.0; n],
        &vec![k; n - 1],
        &vec![0.0; n - 1],
        &vec![0.0; n],
        v0,
        h,
        0.0,
    )
}

/// A line of balls along x under Kuwabara-Kono contacts between neighbours: ball i of mass
/// `m[i]` and radius `r[i]` at centre `x[i]` (increasing) moving at `v[i]`; neighbours i, i + 1
/// overlap by d = r_i + r_(i+1) - (x_(i+1) - x_i) and press with f = k_i sqrt(d) (d + gamma_i
/// d'), clipped at 0 (no pull) and nothing while apart. Integrated by classical RK4 at the
/// fixed step `h` (s) while some pair presses; while none does, the balls fly freely to the
/// next touch (a jump, solved in closed form). Returns the velocities once no pair presses
/// and none approaches faster than `end_below` (m/s; 0: none approaches at all).
#[allow(clippy::too_many_arguments)]
pub fn kuwabara_kono_line_rk4(
    m: &[f64],
    r: &[f64],
    k: &[f64],
    gamma: &[f64],
    x: &[f64],
    v: &[f64],
    h: f64,
    end_below: f64,
) -> Vec<f64> {
    let n = m.len();
    let overlap = |y: &[f64], i: usize| r[i] + r[i + 1] - (y[i + 1] - y[i]);
    let rate = |y: &[f64], dy: &mut [f64]| {
        dy[..n].copy_from_slice(&y[n..]);
        dy[n..].fill(0.0);
        for i in 0..n - 1 {
            let d = overlap(y, i);
            if d > 0.0 {
                let dd = y[n + i] - y[n + i + 1];
                let f = (k[i] * d.sqrt() * (d + gamma[i] * dd)).max(0.0);
                dy[n + i] -= f / m[i];
                dy[n + i + 1] += f / m[i + 1];
            }
        }
    };
    let mut y: Vec<f64> = x.iter().chain(v).copied().collect();
    let mut ks = vec![vec![0.0; 2 * n]; 4];
    let mut stage = vec![0.0; 2 * n];
    loop {
        // No force acts while every pair is apart or overlaps but separates faster than
        // d / gamma (then d + gamma d' only falls as d does): free flight to the earliest
        // touch of an approaching pair, or the end.
        let free = (0..n - 1).all(|i| {
            let (d, dd) = (overlap(&y, i), y[n + i] - y[n + i + 1]);
            d <= 0.0 || (dd < 0.0 && d + gamma[i] * dd <= 0.0)
        });
        if free {
            let next = (0..n - 1)
                .filter(|&i| y[n + i] > y[n + i + 1])
                .map(|i| -overlap(&y, i) / (y[n + i] - y[n + i + 1]))
                .fold(f64::INFINITY, f64::min);
            let fast = (0..n - 1).any(|i| y[n + i] - y[n + i + 1] > end_below);
            if next.is_infinite() || !fast {
                return y[n..].to_vec();
            }
            for i in 0..n {
                y[i] += next * y[n + i];
            }
        }
        for s in 0..4 {
            let c = [0.0, 0.5, 0.5, 1.0][s];
            for i in 0..2 * n {
                stage[i] = y[i] + c * h * if s == 0 { 0.0 } else { ks[s - 1][i] };
            }
            rate(&stage, &mut ks[s]);
        }
        for i in 0..2 * n {
            y[i] += h / 6.0 * (ks[0][i] + 2.0 * ks[1][i] + 2.0 * ks[2][i] + ks[3][i]);
        }
    }
}

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

/// [`hertz_chain_rk4`] at the step `h / 2`, and the largest difference (m/s) of its
/// velocities from the run at `h`: the reference and its own error's scale.
pub fn hertz_chain_rk4_halved(k: f64, m: f64, v0: &[f64], h: f64) -> (Vec<f64>, f64) {
    let coarser = hertz_chain_rk4(k, m, v0, h);
    let finer = hertz_chain_rk4(k, m, v0, 0.5 * h);
    let own = finer
        .iter()
        .zip(&coarser)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    (finer, own)
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

/// Published values (m/s): a chain of ten equal steel balls (r = 10 mm, density 7780
/// kg/m^3, E = 203 GPa, nu = 0.3), the first striking the other nine, touching and at rest,
/// head on at 1 m/s; Hertz contacts k = sqrt(r / 2) (2 / 3) E / (1 - nu^2) (Hertz's (4/3) E*
/// sqrt(R*)), no friction, no gravity. The chain of the Siconos platform's example
/// `examples/Mechanics/ChainOfBalls/MonodisperseChainOfBalls-LZBModel.cpp` (INRIA;
/// github.com/siconos/siconos), solved there by the multiple-impact model of Liu, Zhao and
/// Brogliato ("Frictionless multiple impacts in multibody systems", Proc. R. Soc. A 464
/// (2008) 3193-3211 and 465 (2009) 1-23) with restitution 1. That model steps the impulse,
/// not time: each contact's impulse grows with the primary contact's in the ratio of their
/// forces written through their potential energies, (k_j / k_i)^(2/5) (E_j / E_i)^(3/5),
/// which for Hertz's force is exact, so with restitution 1 it is the dynamics of the Hertz
/// chain; it is stepped at a fixed 1e-6 N s (about 33,000 steps for this impact). The values
/// are the row just after the impact in the example's reference output
/// `MonodisperseChainOfBalls-LZBModel.ref` (the file the example checks itself against),
/// balls 1 to 10. Their squares sum to 1.0000263: the step's kinetic energy ends 2.6e-5 high.
#[allow(clippy::excessive_precision)]
pub const SICONOS_CHAIN_10: [f64; 10] = [
    -7.105929287758861e-02,
    -3.018624045788600e-02,
    -1.574960308766378e-02,
    -8.808055289868551e-03,
    -5.062343781337067e-03,
    -2.936631945849190e-03,
    -1.701856524055756e-03,
    2.624517363818925e-03,
    1.469233855937676e-01,
    9.859561210066624e-01,
];

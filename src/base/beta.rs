//! The regularized incomplete Beta function, the special function behind the cumulative
//! impulse of the `sine-power` profile and the time axis of the `hertz` profile.

/// Complete Beta function B(a, b) = Gamma(a) Gamma(b) / Gamma(a + b), a, b > 0.
pub(crate) fn beta(a: f64, b: f64) -> f64 {
    if a + b < 150.0 {
        libm::tgamma(a) * libm::tgamma(b) / libm::tgamma(a + b)
    } else {
        (libm::lgamma(a) + libm::lgamma(b) - libm::lgamma(a + b)).exp()
    }
}

/// Regularized incomplete Beta function I_x(a, b) for x in [0, 1], given both `x` and
/// `y` = 1 - x (the caller computes 1 - x without cancellation where it can), and
/// `beta_ab` = B(a, b).
///
/// Evaluated by the continued fraction of DiDonato and Morris / Numerical Recipes
/// (modified Lentz) on the side of the symmetry I_x(a, b) = 1 - I_y(b, a) where it
/// converges fast; relative accuracy a few ulp on that side.
pub(crate) fn inc_beta(a: f64, b: f64, x: f64, y: f64, beta_ab: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if y <= 0.0 {
        return 1.0;
    }
    if x < (a + 1.0) / (a + b + 2.0) {
        front(a, b, x, y, beta_ab) * continued_fraction(a, b, x)
    } else {
        1.0 - front(b, a, y, x, beta_ab) * continued_fraction(b, a, y)
    }
}

/// x^a y^b / (a B(a, b)).
fn front(a: f64, b: f64, x: f64, y: f64, beta_ab: f64) -> f64 {
    x.powf(a) * y.powf(b) / (a * beta_ab)
}

/// The continued fraction of I_x(a, b) (Numerical Recipes `betacf`), modified Lentz.
fn continued_fraction(a: f64, b: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    const EPS: f64 = f64::EPSILON;
    let qab = a + b;
    let qap = a + 1.0;
    let qam = a - 1.0;
    let mut c = 1.0;
    let mut d = 1.0 - qab * x / qap;
    if d.abs() < TINY {
        d = TINY;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..=300 {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        h *= d * c;
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() <= EPS {
            break;
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Past a + b = 150 (the logarithmic branch): for a whole b = n, B(a, n) =
    /// (n - 1)! / (a (a + 1) ... (a + n - 1)), so B(150, 3) = 2 / (150 151 152) and
    /// B(200.5, 1) = 1 / 200.5.
    #[test]
    fn beta_of_large_arguments() {
        for (a, b, want) in [
            (150.0, 3.0, 2.0 / (150.0 * 151.0 * 152.0)),
            (200.5, 1.0, 1.0 / 200.5),
        ] {
            let got = beta(a, b);
            assert!(
                (got / want - 1.0).abs() < 1e-12,
                "B({a}, {b}) = {got}, not {want}"
            );
        }
    }

    /// Independent check by composite Gauss-Legendre quadrature of the integrand after
    /// the substitutions u = x v^(1/a), v = t^8, which remove the end singularity at 0.
    fn by_quadrature(a: f64, b: f64, x: f64) -> f64 {
        // integral_0^x u^(a-1) (1-u)^(b-1) du = (x^a / a) integral_0^1 (1 - x v^(1/a))^(b-1) dv
        //   = (x^a / a) integral_0^1 8 t^7 (1 - x t^(8/a))^(b-1) dt
        let n = 4000;
        let nodes = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let mut sum = 0.0;
        for i in 0..n {
            let lo = i as f64 / n as f64;
            let hw = 0.5 / n as f64;
            for (z, w) in nodes {
                let t: f64 = lo + hw * (1.0 + z);
                sum += hw * w * 8.0 * t.powi(7) * (1.0 - x * t.powf(8.0 / a)).powf(b - 1.0);
            }
        }
        x.powf(a) / a * sum / beta(a, b)
    }

    #[test]
    fn matches_quadrature() {
        for &(a, b) in &[(0.4, 0.5), (1.25, 0.5), (0.5, 0.4), (2.5, 0.5), (0.75, 0.5)] {
            let bab = beta(a, b);
            for &x in &[1e-6, 0.01, 0.2, 0.45, 0.5, 0.7] {
                let got = inc_beta(a, b, x, 1.0 - x, bab);
                let want = by_quadrature(a, b, x);
                assert!(
                    (got - want).abs() < 1e-13,
                    "a={a} b={b} x={x}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn closed_forms() {
        // I_x(a, 1) = x^a; I_x(1/2, 1/2) = (2/pi) asin(sqrt x).
        for &x in &[0.0, 1e-9, 0.1, 0.5, 0.9, 1.0] {
            let y: f64 = 1.0 - x;
            assert!((inc_beta(2.5, 1.0, x, y, beta(2.5, 1.0)) - x.powf(2.5)).abs() < 2e-16);
            let want = 2.0 / std::f64::consts::PI * x.sqrt().asin();
            let got = inc_beta(0.5, 0.5, x, y, beta(0.5, 0.5));
            assert!((got - want).abs() < 4e-16, "x={x}: {got} vs {want}");
        }
    }

    /// The examples of the documentation of `beta`.
    #[test]
    fn beta_examples() {
        // B(1/2, 1/2) = pi
        assert!((beta(0.5, 0.5) - std::f64::consts::PI).abs() < 1e-14);
    }

    /// The examples of the documentation of `inc_beta`.
    #[test]
    fn inc_beta_examples() {
        // I_x(1, 1) = x
        assert!((inc_beta(1.0, 1.0, 0.3, 0.7, beta(1.0, 1.0)) - 0.3).abs() < 1e-15);
    }
}

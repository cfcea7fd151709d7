//! The [`ForceProfile`] trait every profile implements, and the inverse of a cumulative
//! impulse that its default `time_at_cumulative` uses.

use crate::base::error::Error;
use crate::base::fields::DURATION_FIELD;
use crate::base::validate::positive;

/// A normal-force profile over the contact, normalised as in the module docs.
pub trait ForceProfile {
    /// Contact duration tau (s).
    fn duration(&self) -> f64;

    /// Normalised force phi(s) = f(s tau) tau / P (dimensionless) for s in [0, 1], the
    /// limit from inside at the ends; 0 outside [0, 1]. Integrates to 1 over [0, 1].
    fn shape(&self, s: f64) -> f64;

    /// Normalised cumulative impulse Phi(s) = p(s tau) / P in [0, 1]: 0 for s <= 0, 1 for
    /// s >= 1, non-decreasing.
    fn cumulative(&self, s: f64) -> f64;

    /// The smallest s in [0, 1] with Phi(s) = q, q in [0, 1]: the time (scaled) at which
    /// the impulse reaches q P. The default is a safeguarded Newton iteration on `cumulative`.
    fn time_at_cumulative(&self, q: f64) -> f64 {
        invert_cumulative(self, q)
    }

    /// Scaled times in (0, 1), sorted, where phi is not smooth (kinks, jumps): the
    /// integrators step exactly to them.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }

    /// The exponent n of the ends, for a pulse that is analytic inside (0, 1) and grows like
    /// s^n from both ends with n not an integer (phi ~ s^n near 0 and ~ (1 - s)^n near 1):
    /// there the force's higher derivatives are infinite, and the integrator smooths the
    /// ends by a change of the time variable (or, with that off, grades its steps toward
    /// them; docs/model.md#time-stepping). `None` (the default) when the ends are smooth
    /// or are where the integration starts and stops anyway.
    fn end_power(&self) -> Option<f64> {
        None
    }

    /// Force f(t) (N) for a total impulse `impulse` P (N s).
    fn force(&self, t: f64, impulse: f64) -> f64 {
        impulse / self.duration() * self.shape(t / self.duration())
    }

    /// Cumulative impulse p(t) (N s) for a total impulse `impulse` P (N s).
    fn impulse_until(&self, t: f64, impulse: f64) -> f64 {
        impulse * self.cumulative(t / self.duration())
    }
}

/// Safeguarded Newton iteration (bisection fallback) for Phi(s) = q on [0, 1].
pub fn invert_cumulative<P: ForceProfile + ?Sized>(profile: &P, q: f64) -> f64 {
    if q <= 0.0 {
        return 0.0;
    }
    if q >= 1.0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut s = q; // exact for a rectangle, a fair start for the rest
    for _ in 0..200 {
        let r = profile.cumulative(s) - q;
        if r == 0.0 {
            break;
        }
        if r < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let d = profile.shape(s);
        let newton = s - r / d;
        s = if d > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    // The smallest time: a zero-force plateau at level q resolves to its start.
    if profile.cumulative(lo) >= q {
        lo
    } else {
        s
    }
}

/// Checks a contact duration tau (s): finite and > 0.
pub(crate) fn valid_duration(duration: f64) -> Result<f64, Error> {
    positive(DURATION_FIELD, duration, "s")
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A caller's own profile, which keeps the default inverse: phi(s) = 3 s^2, Phi(s) = s^3,
    /// so Phi^-1(q) = q^(1/3) exactly.
    struct Cubic;

    impl ForceProfile for Cubic {
        fn duration(&self) -> f64 {
            1.0
        }
        fn shape(&self, s: f64) -> f64 {
            if (0.0..=1.0).contains(&s) {
                3.0 * s * s
            } else {
                0.0
            }
        }
        fn cumulative(&self, s: f64) -> f64 {
            let s = s.clamp(0.0, 1.0);
            s * s * s
        }
    }

    /// The default inverse keeps full relative accuracy down to tiny impulse fractions (a
    /// stick after a tiny slip): s from 0.9 down to 1e-30, against q^(1/3). The bracket's
    /// stop is relative to its upper end; a stop of 4 eps / hi would end the search at
    /// s ~ 2e-8, far above a root at 1e-10.
    #[test]
    fn default_inverse_is_relatively_accurate_at_tiny_fractions() {
        for s in [0.9, 0.5, 1e-2, 1e-5, 1e-8, 1e-10, 1e-15, 1e-30] {
            let q: f64 = s * s * s;
            let want = q.cbrt();
            let got = invert_cumulative(&Cubic, q);
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want,
                "q = {q:e}: s = {got:e}, q^(1/3) = {want:e}"
            );
            assert_eq!(Cubic.time_at_cumulative(q), got);
        }
    }

    /// The default inverse is Newton's method, safeguarded: from s = q it converges in a few
    /// steps where bisection alone (the fallback) would take about 50 to reach 4 eps.
    #[test]
    fn default_inverse_converges_like_newton() {
        struct Counted(std::cell::Cell<usize>);
        impl ForceProfile for Counted {
            fn duration(&self) -> f64 {
                1.0
            }
            fn shape(&self, s: f64) -> f64 {
                Cubic.shape(s)
            }
            fn cumulative(&self, s: f64) -> f64 {
                self.0.set(self.0.get() + 1);
                Cubic.cumulative(s)
            }
        }
        for q in [0.3, 0.05, 0.9] {
            let p = Counted(std::cell::Cell::new(0));
            let got = invert_cumulative(&p, q);
            assert!((got - q.cbrt()).abs() <= 4.0 * f64::EPSILON * got);
            assert!(p.0.get() <= 15, "q = {q}: {} evaluations", p.0.get());
        }
    }

    /// Composite Gauss-Legendre quadrature of phi over [a, b] (independent of `cumulative`),
    /// split at the profile's breakpoints and, for algebraic ends, at points graded toward
    /// them (2^-k and 1 - 2^-k, k = 2..20), with compensated summation.
    pub(crate) fn integrate_shape(p: &dyn ForceProfile, a: f64, b: f64, panels: usize) -> f64 {
        let graded: Vec<f64> = match p.end_power() {
            Some(_) => (2..=20)
                .map(|k| 0.5_f64.powi(k))
                .flat_map(|h| [h, 1.0 - h])
                .collect(),
            None => Vec::new(),
        };
        let mut cuts = vec![a];
        cuts.extend(
            p.breakpoints()
                .iter()
                .chain(&graded)
                .copied()
                .filter(|&x| x > a && x < b),
        );
        cuts.sort_by(f64::total_cmp);
        cuts.push(b);
        let nodes = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let (mut sum, mut carry) = (0.0_f64, 0.0_f64);
        for w in cuts.windows(2) {
            let h = (w[1] - w[0]) / panels as f64;
            for i in 0..panels {
                let lo = w[0] + h * i as f64;
                for (z, wt) in nodes {
                    let term = 0.5 * h * wt * p.shape(lo + 0.5 * h * (1.0 + z));
                    let t = sum + term;
                    carry += if sum.abs() >= term.abs() {
                        (sum - t) + term
                    } else {
                        (term - t) + sum
                    };
                    sum = t;
                }
            }
        }
        sum + carry
    }

    /// Checks the contract of a profile: Phi(0) = 0, Phi(1) = 1, Phi(s) agrees with the
    /// quadrature of phi, the inverse round-trips.
    pub(crate) fn check_profile(p: &dyn ForceProfile, tol: f64) {
        assert_eq!(p.cumulative(0.0), 0.0);
        assert!((p.cumulative(1.0) - 1.0).abs() <= 1e-15);
        assert_eq!(p.shape(-0.1), 0.0);
        assert_eq!(p.shape(1.1), 0.0);
        let mut last = 0.0;
        let mut prev_phi = 0.0;
        for i in 1..=40 {
            let s = i as f64 / 40.0;
            let want = integrate_shape(p, 0.0, s, 2000);
            let got = p.cumulative(s);
            assert!(
                (got - want).abs() < tol,
                "Phi({s}) = {got}, quadrature {want}"
            );
            assert!(got >= last, "Phi not monotone at {s}");
            last = got;
            let q = prev_phi + 0.37 * (got - prev_phi);
            let back = p.time_at_cumulative(q);
            assert!(
                (p.cumulative(back) - q).abs() < 1e-14,
                "inverse at q = {q}: s = {back}, Phi = {}",
                p.cumulative(back)
            );
            prev_phi = got;
        }
    }
}

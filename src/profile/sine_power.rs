//! Sine-power pulse f(t) = c sin^n(pi t / tau).

use crate::base::beta::{beta, inc_beta};
use crate::base::error::Error;
use crate::base::validate::finite;
use crate::profile::force::valid_duration;
use crate::profile::force::ForceProfile;
use std::f64::consts::PI;

/// Sine-power pulse, phi(s) = sin^n(pi s) pi / B((n+1)/2, 1/2).
///
/// With u = sin^2(pi s), integral_0^s sin^n(pi s') ds' = B(u; (n+1)/2, 1/2) / (2 pi), so
/// Phi(s) = I_u((n+1)/2, 1/2) / 2 for s <= 1/2 and 1 - Phi(1 - s) after (with
/// c = pi P / (tau B(5/4, 1/2)) ~= 1.7972104 P / tau for n = 1.5; docs/model.md#force-profiles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SinePower {
    duration: f64,
    exponent: f64,
    /// a = (n + 1)/2 of the incomplete Beta function.
    a: f64,
    /// B(a, 1/2).
    beta_ab: f64,
    /// Peak of phi, pi / B(a, 1/2).
    peak: f64,
}

impl SinePower {
    /// A sin^n pulse of `duration` tau (s), finite and > 0; `exponent` n must be finite
    /// and in (0, 64]. Else [`Error::InvalidParameter`] naming `contact.profile.duration` or
    /// `contact.profile.exponent`.
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, SinePower};
    /// let p = SinePower::new(1.0, 1.5)?;
    /// // peak pi / B(5/4, 1/2) (docs/model.md#force-profiles)
    /// assert!((p.shape(0.5) - 1.7972104).abs() < 1e-7);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(duration: f64, exponent: f64) -> Result<Self, Error> {
        let duration = valid_duration(duration)?;
        finite("contact.profile.exponent", exponent)?;
        if !(exponent > 0.0 && exponent <= 64.0) {
            return Err(Error::invalid(
                "contact.profile.exponent",
                exponent,
                "in (0, 64] (sin^n with n > 0; 1.5 approximates a Hertz pulse)",
            ));
        }
        let a = 0.5 * (exponent + 1.0);
        let beta_ab = beta(a, 0.5);
        Ok(SinePower {
            duration,
            exponent,
            a,
            beta_ab,
            peak: PI / beta_ab,
        })
    }

    /// The exponent n.
    pub fn exponent(&self) -> f64 {
        self.exponent
    }

    /// Phi for s in [0, 1/2].
    fn rising(&self, s: f64) -> f64 {
        let sin = (PI * s).sin();
        let cos = (PI * (0.5 - s)).sin(); // cos(pi s) without cancellation near s = 1/2
        0.5 * inc_beta(self.a, 0.5, sin * sin, cos * cos, self.beta_ab)
    }
}

impl ForceProfile for SinePower {
    fn duration(&self) -> f64 {
        self.duration
    }

    /// A fractional exponent n makes the force grow like t^n from the ends; an integer
    /// exponent gives an analytic pulse (`None`).
    fn end_power(&self) -> Option<f64> {
        (self.exponent.fract() != 0.0).then_some(self.exponent)
    }

    #[inline]
    fn shape(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        self.peak * (PI * s.min(1.0 - s)).sin().powf(self.exponent)
    }

    fn cumulative(&self, s: f64) -> f64 {
        if s <= 0.0 {
            0.0
        } else if s >= 1.0 {
            1.0
        } else if s <= 0.5 {
            self.rising(s)
        } else {
            1.0 - self.rising(1.0 - s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pulse is symmetric about its middle, to the bit where 1 - s is exact, so the force
    /// near the end keeps its relative precision: sin(pi s) itself would lose it as pi s
    /// nears pi (the rounding of pi s, 6e-9 relative at 1 - s = 2^-30, 5e-5 at 2^-40).
    #[test]
    fn symmetric_to_the_bit_near_the_ends() {
        for n in [1.0, 1.5, 4.0] {
            let p = SinePower::new(1.0, n).unwrap();
            for k in 2..=40 {
                let x = 0.5f64.powi(k);
                assert_eq!(p.shape(1.0 - x), p.shape(x), "n {n}, 1 - s = 2^-{k}");
            }
        }
    }

    /// The impulse still to come after 1 - s is the impulse delivered before s, to the bit
    /// (1 - s and 1 - (1 - s) are exact for s = k / 1024): the late half of the pulse is
    /// its early half mirrored, not the sines of arguments past pi.
    #[test]
    fn cumulative_symmetric_to_the_bit() {
        for n in [1.0, 1.5, 4.0] {
            let p = SinePower::new(1.0, n).unwrap();
            for k in 1..512 {
                let s = f64::from(k) / 1024.0;
                assert_eq!(
                    p.cumulative(1.0 - s),
                    1.0 - p.cumulative(s),
                    "n {n}, s = {s}"
                );
            }
        }
    }

    /// The accessor returns the exponent the pulse was built with.
    #[test]
    fn exponent_as_built() {
        for n in [0.5, 1.5, 4.0, 64.0] {
            assert_eq!(SinePower::new(2.5e-4, n).unwrap().exponent(), n);
        }
    }

    #[test]
    fn contract_for_several_exponents() {
        for (n, tol) in [(1.0, 1e-13), (1.5, 1e-10), (0.5, 1e-6), (4.0, 1e-13)] {
            crate::profile::force::tests::check_profile(&SinePower::new(1.0, n).unwrap(), tol);
        }
    }

    #[test]
    fn exponent_one_is_the_half_sine() {
        let p = SinePower::new(1.0, 1.0).unwrap();
        let h = crate::profile::half_sine::HalfSine::new(1.0).unwrap();
        for i in 0..=100 {
            let s = i as f64 / 100.0;
            assert!((p.shape(s) - h.shape(s)).abs() < 1e-15);
            assert!((p.cumulative(s) - h.cumulative(s)).abs() < 1e-15);
        }
    }

    #[test]
    fn rejects_bad_exponents() {
        assert!(SinePower::new(1.0, 0.0).is_err());
        assert!(SinePower::new(1.0, f64::NAN).is_err());
        assert!(SinePower::new(1.0, -1.0).is_err());
    }
}

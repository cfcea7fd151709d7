//! A contact law: the normal force from the compression itself, Hertz's elastic force with an
//! optional damping term (docs/contact-law.md).
//!
//! The compression delta (m) of the two balls grows at the relative approach rate,
//! delta' = 2 U (delta(0) = 0), and the normal force is
//!
//! ```text
//! none           f = k delta^(3/2)
//! hunt-crossley  f = k delta^(3/2) (1 + beta delta')          beta in s/m
//! kuwabara-kono  f = k delta^(3/2) + gamma k delta^(1/2) delta'   gamma in s
//! ```
//!
//! clipped at 0 (the balls never pull). The contact ends when the force returns to zero
//! during restitution: at delta = 0 for `none` and `hunt-crossley` (its factor
//! 1 + beta delta' stays positive, docs/contact-law.md#the-end-of-the-contact), at
//! delta + gamma delta' = 0 with delta > 0 for `kuwabara-kono`. The restitution, the
//! impulse and the contact time follow from the law; the damping coefficient is a user's
//! calibration, given directly or solved from a restitution at a speed
//! ([`ContactLaw::calibrated`]).

use crate::base::error::Error;
use crate::base::validate::{finite, positive};
use serde::{Deserialize, Serialize};
use std::fmt;

/// The field the stiffness is named by (as in the scene file).
pub(crate) const STIFFNESS_FIELD: &str = "contact.law.stiffness";
/// The field the damping coefficient is named by.
pub(crate) const COEFFICIENT_FIELD: &str = "contact.law.coefficient";
/// The field of the restitution a coefficient is calibrated to.
pub(crate) const RESTITUTION_FIELD: &str = "contact.law.restitution";
/// The field of the speed a coefficient is calibrated at.
pub(crate) const AT_SPEED_FIELD: &str = "contact.law.at_speed";

/// The damping term of the law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Damping {
    /// Elastic Hertz: no damping, restitution 1.
    None,
    /// Hunt & Crossley (1975): f = k delta^(3/2) (1 + beta delta'), beta (s/m). The
    /// restitution depends on beta v alone (v the approach speed).
    HuntCrossley,
    /// Kuwabara & Kono (1987), Brilliantov et al. (1996): the viscoelastic sphere,
    /// f = k delta^(3/2) + gamma k delta^(1/2) delta', gamma (s). 1 - e grows as v^(1/5).
    KuwabaraKono,
}

impl Damping {
    /// The name as the scene file writes it.
    pub fn name(self) -> &'static str {
        match self {
            Damping::None => "none",
            Damping::HuntCrossley => "hunt-crossley",
            Damping::KuwabaraKono => "kuwabara-kono",
        }
    }

    /// The unit of the coefficient.
    pub fn unit(self) -> &'static str {
        match self {
            Damping::None => "-",
            Damping::HuntCrossley => "s/m",
            Damping::KuwabaraKono => "s",
        }
    }
}

impl fmt::Display for Damping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The law of the normal force: stiffness, damping and its coefficient (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactLaw {
    stiffness: f64,
    damping: Damping,
    coefficient: f64,
}

impl ContactLaw {
    /// A validated law: `stiffness` k (N / m^(3/2)) finite and > 0, `coefficient` finite and
    /// >= 0 (beta in s/m for `hunt-crossley`, gamma in s for `kuwabara-kono`; 0 for `none`).
    ///
    /// ```
    /// use billiard_contact::{ContactLaw, Damping};
    /// let law = ContactLaw::new(4.5e8, Damping::HuntCrossley, 0.1)?;
    /// // f = k delta^1.5 (1 + beta delta'): at delta = 1e-4 m closing at 1 m/s.
    /// let f = 4.5e8 * 1e-6 * (1.0 + 0.1);
    /// assert!((law.force(1e-4, 1.0) - f).abs() < 1e-12 * f);
    /// assert_eq!(law.force(-1e-9, 1.0), 0.0); // apart: no force
    /// assert!(ContactLaw::new(4.5e8, Damping::None, 0.1).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(stiffness: f64, damping: Damping, coefficient: f64) -> Result<Self, Error> {
        positive(STIFFNESS_FIELD, stiffness, "N/m^1.5")?;
        finite(COEFFICIENT_FIELD, coefficient)?;
        if coefficient < 0.0 {
            return Err(Error::invalid(
                COEFFICIENT_FIELD,
                coefficient,
                format!(
                    ">= 0 {} (a damping that does not add energy)",
                    damping.unit()
                ),
            ));
        }
        if damping == Damping::None && coefficient != 0.0 {
            return Err(Error::invalid(
                COEFFICIENT_FIELD,
                format!("{coefficient} with contact.law.damping = \"none\""),
                "no coefficient with damping \"none\" (choose hunt-crossley or kuwabara-kono)",
            ));
        }
        Ok(ContactLaw {
            stiffness,
            damping,
            coefficient,
        })
    }

    /// Elastic Hertz of stiffness k (N / m^(3/2)).
    pub fn elastic(stiffness: f64) -> Result<Self, Error> {
        ContactLaw::new(stiffness, Damping::None, 0.0)
    }

    /// Stiffness k (N / m^(3/2)).
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The damping term.
    pub fn damping(&self) -> Damping {
        self.damping
    }

    /// The damping coefficient: beta (s/m), gamma (s), or 0.
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// The energy (J) Hertz's spring holds at compression `delta` (m): (2/5) k delta^(5/2),
    /// 0 while apart (the damping term holds none).
    #[inline]
    pub fn elastic_energy(&self, delta: f64) -> f64 {
        0.4 * self.stiffness * delta.max(0.0).powf(2.5)
    }

    /// The normal force f (N) at compression `delta` (m) closing at `delta_dot` (m/s),
    /// clipped at 0: no force while apart (delta <= 0) and no pull.
    #[inline]
    pub fn force(&self, delta: f64, delta_dot: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        let root = delta.sqrt();
        let k = self.stiffness;
        let f = match self.damping {
            Damping::None => k * delta * root,
            Damping::HuntCrossley => k * delta * root * (1.0 + self.coefficient * delta_dot),
            Damping::KuwabaraKono => k * root * (delta + self.coefficient * delta_dot),
        };
        f.max(0.0)
    }

    /// The rate df/dt (N/s) of the unclipped force along the motion, at compression `delta`
    /// (m > 0), rate `delta_dot` (m/s) and acceleration delta'' = -f / m* (`reduced_mass` m*
    /// in kg): its zero is the peak force. Under `kuwabara-kono` it is +inf at delta <= 0:
    /// the damped force rises as sqrt(delta) from first touch, and a positive rate keeps the
    /// start of contact from reading as the peak (gamma = 0 included).
    #[inline]
    pub fn force_rate(&self, delta: f64, delta_dot: f64, reduced_mass: f64) -> f64 {
        let d = delta.max(0.0);
        let root = d.sqrt();
        let (k, c, w) = (self.stiffness, self.coefficient, delta_dot);
        let accel = -self.force(delta, delta_dot) / reduced_mass;
        match self.damping {
            Damping::None => 1.5 * k * root * w,
            Damping::HuntCrossley => k * (1.5 * root * w * (1.0 + c * w) + d * root * c * accel),
            Damping::KuwabaraKono if d > 0.0 => {
                k * (1.5 * root * w + c * (0.5 * w * w / root + root * accel))
            }
            Damping::KuwabaraKono => f64::INFINITY,
        }
    }

    /// The separation function (m): positive while the balls press on each other, zero
    /// where the force returns to zero during restitution. delta for `none` and
    /// `hunt-crossley`, delta + gamma delta' for `kuwabara-kono`.
    #[inline]
    pub fn separation(&self, delta: f64, delta_dot: f64) -> f64 {
        match self.damping {
            Damping::None | Damping::HuntCrossley => delta,
            Damping::KuwabaraKono => delta + self.coefficient * delta_dot,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_bad_laws() {
        for (k, d, c, field) in [
            (0.0, Damping::None, 0.0, STIFFNESS_FIELD),
            (f64::NAN, Damping::None, 0.0, STIFFNESS_FIELD),
            (1e9, Damping::HuntCrossley, -0.1, COEFFICIENT_FIELD),
            (1e9, Damping::KuwabaraKono, f64::INFINITY, COEFFICIENT_FIELD),
            (1e9, Damping::None, 1e-3, COEFFICIENT_FIELD),
        ] {
            match ContactLaw::new(k, d, c) {
                Err(Error::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{k} {d} {c}: {other:?}"),
            }
        }
    }

    /// The Kuwabara-Kono force vanishes at delta + gamma delta' = 0 and is clipped beyond.
    #[test]
    fn kuwabara_kono_separates_at_the_force_zero() {
        let law = ContactLaw::new(1e9, Damping::KuwabaraKono, 1e-5).unwrap();
        let delta = 1e-5;
        let w = -delta / 1e-5;
        assert_eq!(law.separation(delta, w), 0.0);
        assert!(law.force(delta, w).abs() < 1e-9);
        assert_eq!(law.force(delta, 1.5 * w), 0.0);
    }

    /// Kuwabara-Kono's rate at first touch: +inf (the sqrt(delta) rise), not 0.5 w^2 / 0
    /// times gamma, which is NaN for gamma = 0 or w = 0.
    #[test]
    fn kuwabara_kono_rate_at_first_touch_is_infinite() {
        for gamma in [0.0, 2e-6] {
            let law = ContactLaw::new(1e9, Damping::KuwabaraKono, gamma).unwrap();
            for w in [0.0, 0.5] {
                assert_eq!(law.force_rate(0.0, w, 0.085), f64::INFINITY, "{gamma} {w}");
            }
        }
    }

    /// df/dt against a central difference of f along the motion delta(t), delta'(t).
    #[test]
    fn force_rate_is_the_derivative_along_the_motion() {
        let m = 0.085;
        for law in [
            ContactLaw::elastic(1e9).unwrap(),
            ContactLaw::new(1e9, Damping::HuntCrossley, 0.2).unwrap(),
            ContactLaw::new(1e9, Damping::KuwabaraKono, 2e-6).unwrap(),
        ] {
            let (d, w) = (5e-5, 0.3);
            let a = -law.force(d, w) / m;
            let h = 1e-9;
            let f = |t: f64| law.force(d + w * t + 0.5 * a * t * t, w + a * t);
            let fd = (f(h) - f(-h)) / (2.0 * h);
            let rate = law.force_rate(d, w, m);
            assert!((rate - fd).abs() < 1e-5 * rate.abs(), "{rate} vs {fd}");
        }
    }
}

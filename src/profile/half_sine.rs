//! Half-sine pulse f(t) = (pi P / (2 tau)) sin(pi t / tau).

use crate::base::error::Error;
use crate::profile::force::valid_duration;
use crate::profile::force::ForceProfile;
use std::f64::consts::{FRAC_2_PI, FRAC_PI_2, PI};

/// Half-sine pulse: phi(s) = (pi/2) sin(pi s), Phi(s) = sin^2(pi s / 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfSine {
    duration: f64,
}

impl HalfSine {
    /// A half-sine pulse of `duration` tau (s), finite and > 0 (else
    /// [`Error::InvalidParameter`] naming `contact.profile.duration`).
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, HalfSine};
    /// let p = HalfSine::new(2.5e-4)?;
    /// // peak force pi P / (2 tau) at mid-contact
    /// assert!((p.force(1.25e-4, 0.17) - std::f64::consts::PI * 0.17 / 5e-4).abs() < 1e-9);
    /// assert!(HalfSine::new(0.0).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(duration: f64) -> Result<Self, Error> {
        Ok(HalfSine {
            duration: valid_duration(duration)?,
        })
    }
}

impl HalfSine {
    /// Phi(s) and phi(s) together, from one sine and cosine of pi s' / 2 with s' the
    /// distance to the nearer end (phi = (pi/2) sin(pi s) = pi sin(pi s'/2) cos(pi s'/2)):
    /// the integrator's sin^2 time transform needs both at every evaluation. `s` in [0, 1].
    #[inline]
    pub fn cumulative_and_shape(&self, s: f64) -> (f64, f64) {
        let near = s.min(1.0 - s);
        let (sin, cos) = (FRAC_PI_2 * near).sin_cos();
        let from_end = sin * sin;
        let cumulative = if s <= 0.5 { from_end } else { 1.0 - from_end };
        (cumulative, PI * sin * cos)
    }
}

impl ForceProfile for HalfSine {
    fn duration(&self) -> f64 {
        self.duration
    }

    #[inline]
    fn shape(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        // sin(pi s) from the nearer end keeps full relative accuracy at both ends.
        FRAC_PI_2 * (PI * s.min(1.0 - s)).sin()
    }

    fn cumulative(&self, s: f64) -> f64 {
        if s <= 0.0 {
            0.0
        } else if s >= 1.0 {
            1.0
        } else if s <= 0.5 {
            let h = (FRAC_PI_2 * s).sin();
            h * h
        } else {
            let h = (FRAC_PI_2 * (1.0 - s)).sin();
            1.0 - h * h
        }
    }

    /// s = (2/pi) asin(sqrt(q)), from the nearer end (the arccos form loses digits for
    /// small q: docs/model.md#the-exact-state-during-the-contact).
    fn time_at_cumulative(&self, q: f64) -> f64 {
        if q <= 0.0 {
            0.0
        } else if q >= 1.0 {
            1.0
        } else if q <= 0.5 {
            FRAC_2_PI * q.sqrt().asin()
        } else {
            1.0 - FRAC_2_PI * (1.0 - q).sqrt().asin()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contract() {
        crate::profile::force::tests::check_profile(&HalfSine::new(1e-3).unwrap(), 1e-13);
    }

    /// Both at once agree with the separate formulas to round-off.
    #[test]
    fn cumulative_and_shape_together() {
        let p = HalfSine::new(1.0).unwrap();
        for i in 0..=200 {
            let s = i as f64 / 200.0;
            let (c, f) = p.cumulative_and_shape(s);
            assert!((c - p.cumulative(s)).abs() <= 2e-16, "s = {s}");
            assert!((f - p.shape(s)).abs() <= 4.0 * f64::EPSILON * f, "s = {s}");
        }
    }
}

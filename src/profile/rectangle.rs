//! Rectangular pulse: constant force P / tau over the contact.

use crate::base::error::Error;
use crate::profile::force::valid_duration;
use crate::profile::force::ForceProfile;

/// Constant force: phi(s) = 1, Phi(s) = s. The force jumps at both ends of the contact,
/// which lie on the integration interval's ends, so steppers never straddle them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    duration: f64,
}

impl Rectangle {
    /// A rectangular pulse of `duration` tau (s), finite and > 0 (else
    /// [`Error::InvalidParameter`] naming `contact.profile.duration`).
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, Rectangle};
    /// let p = Rectangle::new(2e-4)?;
    /// // constant force P / tau
    /// assert_eq!(p.force(1e-4, 0.2), 0.2 / 2e-4);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(duration: f64) -> Result<Self, Error> {
        Ok(Rectangle {
            duration: valid_duration(duration)?,
        })
    }
}

impl ForceProfile for Rectangle {
    fn duration(&self) -> f64 {
        self.duration
    }

    #[inline]
    fn shape(&self, s: f64) -> f64 {
        if (0.0..=1.0).contains(&s) {
            1.0
        } else {
            0.0
        }
    }

    fn cumulative(&self, s: f64) -> f64 {
        s.clamp(0.0, 1.0)
    }

    fn time_at_cumulative(&self, q: f64) -> f64 {
        q.clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contract() {
        crate::profile::force::tests::check_profile(&Rectangle::new(2.0).unwrap(), 1e-13);
    }
}

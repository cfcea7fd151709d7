//! Rectangular pulse: constant force P / tau over the contact.

use super::ForceProfile;

/// Constant force: phi(s) = 1, Phi(s) = s. The force jumps at both ends of the contact,
/// which lie on the integration interval's ends, so steppers never straddle them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    duration: f64,
}

impl Rectangle {
    /// A rectangular pulse of `duration` tau (s), validated by the caller.
    pub fn new(duration: f64) -> Self {
        Rectangle { duration }
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
        crate::profile::tests::check_profile(&Rectangle::new(2.0), 1e-13);
    }
}

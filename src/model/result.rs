//! What every method reports about one collision: the impulses, the sliding, the heat and
//! the outgoing state. The closed form, the time-stepping outcome, a batch row and the
//! JSON report all carry this one record.

use crate::model::state::CmState;
use crate::profile::force::ForceProfile;

/// The result of one collision in the paper's centre-of-mass frame (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactResult {
    /// Impulse P (N s); 0 when the balls do not approach.
    pub impulse: f64,
    /// Incoming sliding speed S(0) (m/s), eqs 5-6.
    pub s0: f64,
    /// Sliding direction theta (rad), eqs 5-6; `None` when S(0) = 0.
    pub theta: Option<f64>,
    /// Outgoing sliding speed, signed along the initial direction e0 (m/s): >= 0 with
    /// sticking, negative only when eq 57 fails with `stick = false`.
    pub s_out: f64,
    /// Whether sliding stopped during the contact.
    pub sticks: bool,
    /// p_stick (N s): the impulse at which sliding stops, or would stop after the contact;
    /// `None` when it never would (no collision, no friction, or an infinite p_stick).
    pub stick_impulse: Option<f64>,
    /// Tangential impulse J >= 0 (N s): along -e on A, +e on B.
    pub tangential_impulse: f64,
    /// Total heat H (J), eq 50.
    pub heat: f64,
    /// Heat of sliding friction H_sfr (J), eq 49 with the stick rule.
    pub heat_sliding: f64,
    /// Outgoing centre-of-mass state.
    pub out: CmState,
}

impl ContactResult {
    /// True when the balls approached (U(0) > 0) and collided: an impulse acted.
    pub fn collided(&self) -> bool {
        self.impulse > 0.0
    }

    /// The scaled time s = t / duration at which sliding stops under `profile`: where the
    /// profile's cumulative impulse reaches p_stick / P. `None` when sliding does not stop.
    pub fn stick_fraction<P: ForceProfile + ?Sized>(&self, profile: &P) -> Option<f64> {
        (self.sticks && self.collided())
            .then(|| profile.time_at_cumulative(self.stick_impulse.unwrap_or(0.0) / self.impulse))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// A pulse whose impulse grows like s^2: Phi(s) = s^2, so the impulse reaches q P at
    /// s = sqrt(q).
    struct Quadratic;

    impl ForceProfile for Quadratic {
        fn duration(&self) -> f64 {
            1e-4
        }
        fn shape(&self, s: f64) -> f64 {
            if (0.0..=1.0).contains(&s) {
                2.0 * s
            } else {
                0.0
            }
        }
        fn cumulative(&self, s: f64) -> f64 {
            s.clamp(0.0, 1.0).powi(2)
        }
    }

    fn result(impulse: f64, sticks: bool, stick_impulse: Option<f64>) -> ContactResult {
        let still = CmState::new(Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        ContactResult {
            impulse,
            s0: 0.1,
            theta: Some(0.0),
            s_out: 0.0,
            sticks,
            stick_impulse,
            tangential_impulse: 0.0,
            heat: 0.0,
            heat_sliding: 0.0,
            out: still,
        }
    }

    #[test]
    fn stick_fraction_inverts_the_cumulative_impulse() {
        // p_stick / P = 0.5 / 2 = 1/4 of the impulse, reached at s = sqrt(1/4) = 1/2.
        let s = result(2.0, true, Some(0.5))
            .stick_fraction(&Quadratic)
            .unwrap();
        assert!((s - 0.5).abs() < 1e-12, "{s}");
        // Sliding through (p_stick beyond P), or no collision: no stop.
        assert_eq!(
            result(2.0, false, Some(3.0)).stick_fraction(&Quadratic),
            None
        );
        assert_eq!(
            result(0.0, true, Some(0.0)).stick_fraction(&Quadratic),
            None
        );
        assert!(result(2.0, false, None).collided());
        assert!(!result(0.0, false, None).collided());
    }
}

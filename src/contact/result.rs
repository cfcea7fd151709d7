//! What every method reports about one collision: the impulses, the sliding, the heat and
//! the outgoing state. The closed form, the time-stepping outcome, a batch row and the
//! JSON report all carry this one record.

use crate::model::state::CmState;
use crate::profile::ForceProfile;

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

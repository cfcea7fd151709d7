//! From the integrator's scaled variables (docs/model.md#time-stepping) back to physical
//! states and trace rows.

use super::rhs::SlidingState;
use super::time_map::TimeMap;
use crate::model::collision::Collision;
use crate::model::state::CmState;
use crate::model::trace::TraceRow;
use crate::profile::force::ForceProfile;
use nalgebra::{Vector2, Vector3};

/// Converts scaled states to physical ones.
pub(super) struct Units<'a, P: ForceProfile + ?Sized> {
    c: &'a Collision,
    profile: &'a P,
    /// The integration variable's map to the scaled time.
    time_map: TimeMap,
    /// v_ref (m/s).
    v: f64,
    /// The change of each ball's spin per unit change of the scaled Omega (rad/s): half of
    /// v_ref / r for identical balls (eq 11); for balls of different size or inertia A takes
    /// the share i_A / (i_A + i_B) of the change of r_A Omega^A + r_B Omega^B and B the
    /// rest, over r_B (v_ref / r_A the spin scale).
    spin_share: [f64; 2],
    /// m v_ref^2 (J).
    e: f64,
    /// Initial sliding direction e0 (unit; zero without sliding): the sign of the slip
    /// speed in a trace row.
    e0: Vector2<f64>,
}

impl<'a, P: ForceProfile + ?Sized> Units<'a, P> {
    /// The units of collision `c` with force profile `profile`, integrated in the variable
    /// of `time_map`.
    pub(super) fn new(c: &'a Collision, profile: &'a P, time_map: TimeMap) -> Self {
        let sc = c.scales;
        Units {
            c,
            profile,
            time_map,
            v: sc.speed,
            spin_share: {
                let [ia, ib] = c.balls.scaled_inverse_alphas();
                [
                    ia / (ia + ib) * sc.spin,
                    ib / (ia + ib) * (sc.spin / c.balls.radius_ratio()),
                ]
            },
            e: sc.energy,
            e0: c.direction.unwrap_or_else(Vector2::zeros),
        }
    }

    /// The centre-of-mass state of scaled state `y`.
    pub(super) fn state(&self, y: &SlidingState) -> CmState {
        let mut s = self.c.incoming;
        let [du, dv, dw] = y.delta_u();
        let [doy, doz] = y.delta_omega_yz();
        s.u_cm += Vector3::new(du, dv, dw) * self.v;
        // Eq 11: both balls' spins change by half the change of Omega (the shares of unequal
        // balls: `spin_share`).
        let change = Vector3::new(0.0, doy, doz);
        s.omega_a += change * self.spin_share[0];
        s.omega_b += change * self.spin_share[1];
        s
    }

    /// Sliding heat H_sfr (J) of scaled state `y`.
    pub(super) fn heat(&self, y: &SlidingState) -> f64 {
        y.heat() * self.e
    }

    /// Signed slip speed along e0 (m/s) of scaled state `y`.
    pub(super) fn slip_along_e0(&self, y: &SlidingState) -> f64 {
        y.slip().dot(&self.e0) * self.v
    }

    /// The trace row of `y` at `time` (s; default the scaled time of its integration
    /// variable times the duration), with slip angle `theta` (rad).
    pub(super) fn row(&self, y: &SlidingState, time: Option<f64>, theta: Option<f64>) -> TraceRow {
        let s = self.time_map.time(self.profile, y.x());
        let tau = self.profile.duration();
        let p = self.c.impulse;
        let slip = y.slip();
        let sign = if slip.dot(&self.e0) < 0.0 { -1.0 } else { 1.0 };
        TraceRow {
            t: time.unwrap_or(s * tau),
            force: p / tau * self.profile.shape(s),
            impulse: p * self.time_map.impulse_fraction(self.profile, y.x()),
            state: self.state(y),
            slip_speed: sign * slip.x.hypot(slip.y) * self.v,
            theta,
            heat_sliding: self.heat(y),
            compression: None,
        }
    }
}

//! Equations 14-19 as `ode_solvers` systems, in scaled, autonomous form.
//!
//! Scaled variables (docs/model.md#scales-and-scaled-errors): time s = t / tau, velocities
//! over v_ref, spins times r / v_ref, heat over m v_ref^2, and pi = P / (m v_ref). With phi
//! the normalised
//! profile ([`crate::profile`]), n = pi phi(s) and mu from the current sliding speed,
//! eqs 14-19 and 20-21, 47 read (in s; stepping in x with s = g(x), every derivative but
//! that of x is multiplied by g'(x): [`super::time_map`])
//!
//! ```text
//! dU/ds  = -n                        (14)
//! dV/ds  = -mu n cos(theta)          (15)
//! dW/ds  = -mu n sin(theta)          (16)
//! dOmega_y/ds = (2 mu n / alpha) sin(theta)   (18)   (Omega = Omega^A + Omega^B)
//! dOmega_z/ds = -(2 mu n / alpha) cos(theta)  (19)
//! d slip/ds   = -2 mu n (1 + 1/alpha) e       (20-21)
//! dH_sfr/ds   = mu n (slip . e)               (47, signed)
//! ```
//!
//! For unequal balls (docs/unequal-balls.md) the scales use the pair mass M and r_A, the
//! carried "Omega" is (r_A Omega^A + r_B Omega^B) / r_A, and 2 / alpha becomes
//! i_A + i_B with i = M / (alpha m) per ball (each 1/alpha for identical balls):
//!
//! ```text
//! dOmega_y/ds = (i_A + i_B) mu n sin(theta),  d slip/ds = -(2 + i_A + i_B) mu n e
//! ```
//!
//! Eq 17 (Omega_x constant) needs no integration. The velocity and spin components are
//! carried as changes from the incoming state, so the outgoing spins of the two balls are
//! Omega^{A,B}(0) + Delta Omega / 2 (eq 11) without cancellation. The slip
//! (2V + r Omega_z, 2W - r Omega_y) is carried as well (eqs 20-21): it is the difference of
//! nearly equal terms when S is small, and carrying it keeps S(t) to full relative
//! precision, which the stick event needs; that it stays equal to the combination of the
//! other components is checked. The integration variable x (the scaled time s itself, or
//! s = g(x) with the time transform) is a state (dx/dx = 1) so that the right-hand side is
//! autonomous: `ode_solvers`' Dop853 has wrong nodes c12, c13 for right-hand sides that read
//! the time argument.
//!
//! The friction direction e comes from the current slip at every evaluation (eqs 5-8),
//! `sign(slip . e0) slip / |slip|`: before sliding stops this is slip / |slip|; past the
//! stop (only inside the step that crosses it) it continues the paper's formula, so that
//! the step that crosses is smooth and the event function slip . e0 changes sign there.

use super::time_map::TimeMap;
use crate::model::params::Friction;
use crate::model::state::planar_length;
use crate::profile::force::ForceProfile;
use nalgebra::{SVector, Vector2};

/// Number of components of the sliding state.
pub(crate) const SLIDING_DIM: usize = 9;
/// Number of components of the normal-only state.
pub(crate) const NORMAL_DIM: usize = 2;

/// A right-hand side in scaled, autonomous form (component 0 is the integration variable x).
pub trait ScaledRhs<const N: usize> {
    /// Writes dy/ds at `y`.
    fn derivative(&self, y: &SVector<f64, N>, dy: &mut SVector<f64, N>);
}

/// The sliding state: the integration variable x, changes of U, V, W, Omega_y, Omega_z, the
/// slip, and H_sfr, all scaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SlidingState(pub SVector<f64, SLIDING_DIM>);

impl SlidingState {
    const X: usize = 0;
    const DU: usize = 1;
    const DV: usize = 2;
    const DW: usize = 3;
    const DOY: usize = 4;
    const DOZ: usize = 5;
    const SY: usize = 6;
    const SZ: usize = 7;
    const H: usize = 8;

    /// The state at the start of contact: scaled slip `slip0`, all changes 0.
    #[inline]
    pub(crate) fn initial(slip0: Vector2<f64>) -> Self {
        let mut y = SVector::zeros();
        y[Self::SY] = slip0.x;
        y[Self::SZ] = slip0.y;
        SlidingState(y)
    }

    /// The integration variable x (the scaled time is s = g(x): [`TimeMap`]).
    #[inline]
    pub(crate) fn x(&self) -> f64 {
        self.0[Self::X]
    }
    /// Sets the integration variable.
    #[inline]
    pub(crate) fn set_x(&mut self, x: f64) {
        self.0[Self::X] = x;
    }
    /// Scaled change of (U, V, W).
    #[inline]
    pub(crate) fn delta_u(&self) -> [f64; 3] {
        [self.0[Self::DU], self.0[Self::DV], self.0[Self::DW]]
    }
    /// Scaled change of (Omega_y, Omega_z) of Omega = Omega^A + Omega^B.
    #[inline]
    pub(crate) fn delta_omega_yz(&self) -> [f64; 2] {
        [self.0[Self::DOY], self.0[Self::DOZ]]
    }
    /// Scaled slip (S cos theta, S sin theta).
    #[inline]
    pub(crate) fn slip(&self) -> Vector2<f64> {
        Vector2::new(self.0[Self::SY], self.0[Self::SZ])
    }
    /// Sets the scaled slip (to zero when the surfaces stick).
    #[inline]
    pub(crate) fn set_slip(&mut self, slip: Vector2<f64>) {
        self.0[Self::SY] = slip.x;
        self.0[Self::SZ] = slip.y;
    }
    /// Scaled sliding heat H_sfr.
    #[inline]
    pub(crate) fn heat(&self) -> f64 {
        self.0[Self::H]
    }
    /// Scaled change of U.
    #[inline]
    pub(crate) fn set_delta_u_normal(&mut self, du: f64) {
        self.0[Self::DU] = du;
    }
}

/// The normal-only state: the integration variable x and the scaled change of U.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalState(pub SVector<f64, NORMAL_DIM>);

impl NormalState {
    /// At integration variable `x` with scaled change of U `du`.
    #[inline]
    pub(crate) fn new(x: f64, du: f64) -> Self {
        NormalState(SVector::from([x, du]))
    }
    /// The integration variable x.
    #[inline]
    pub(crate) fn x(&self) -> f64 {
        self.0[0]
    }
    /// Scaled change of U.
    #[inline]
    pub(crate) fn delta_u(&self) -> f64 {
        self.0[1]
    }
}

/// How the sliding right-hand side takes the friction direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Direction {
    /// From the current slip (eqs 5-8), continued smoothly past a stop.
    CurrentSlip,
    /// Frozen along the initial direction e0: the paper's formulas literally, used after
    /// sliding stops with the effect `stick = false`.
    Frozen,
}

/// The scaled force n = pi phi(s) g'(x) at integration variable `x`: the rate of the
/// impulse in x ([`TimeMap::force`]).
#[inline]
fn scaled_force<P: ForceProfile + ?Sized>(profile: &P, map: &TimeMap, impulse: f64, x: f64) -> f64 {
    impulse * map.force(profile, x)
}

/// Eqs 14-19 (with 20-21 and 47) while the balls slide.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SlidingRhs<'a, P: ForceProfile + ?Sized> {
    /// Normal-force profile.
    pub profile: &'a P,
    /// The integration variable's map to the scaled time.
    pub time_map: TimeMap,
    /// pi = P / (m v_ref).
    pub impulse: f64,
    /// Friction law (mu of the sliding speed in m/s).
    pub friction: Friction,
    /// v_ref (m/s), to evaluate a speed-dependent mu.
    pub speed_scale: f64,
    /// M / (alpha_A m_A) and M / (alpha_B m_B) ([`crate::BallPair::scaled_inverse_alphas`]):
    /// both 1 / alpha for identical balls.
    pub inv_alpha: [f64; 2],
    /// Initial sliding direction e0 (unit).
    pub e0: Vector2<f64>,
    /// Direction rule.
    pub direction: Direction,
    /// Scaled slip magnitude at or below which the slip is round-off (see
    /// [`SLIP_ROUND_OFF`]): there its direction carries no information and e0 is used.
    pub slip_floor: f64,
}

/// Relative size, against |slip(0)|, below which the direction of a carried slip is
/// dominated by round-off.
///
/// The slip components are sums of terms of size |slip(0)|, so each carries an absolute
/// error of a few ulps of |slip(0)|, and the direction of a slip of size |slip| is uncertain
/// by about eps |slip(0)| / |slip|. The stages of the step that reaches the stop of
/// sliding evaluate the right-hand side at slips near zero, where that direction is random,
/// and with it those stages' friction (an S(0) = 1e-15 U(0) stun cut gets its tangential
/// impulse 1.5e-3 rad off e0 with rk4 without a floor, and 1e-8 rad with a 1e-12 floor). Below this floor the friction keeps the direction e0, which is the exact one
/// (theta is constant while sliding), so the exact solution is unchanged; above it the
/// direction noise is below 1e-9 rad.
pub(crate) const SLIP_ROUND_OFF: f64 = 1e-6;

impl<P: ForceProfile + ?Sized> SlidingRhs<'_, P> {
    /// The event function g = slip . e0 (scaled): positive while sliding, changes sign
    /// where sliding stops (S itself never does).
    #[inline]
    pub(crate) fn event(&self, y: &SlidingState) -> f64 {
        y.slip().dot(&self.e0)
    }
}

impl<P: ForceProfile + ?Sized> ScaledRhs<SLIDING_DIM> for SlidingRhs<'_, P> {
    #[inline]
    fn derivative(&self, y: &SVector<f64, SLIDING_DIM>, dy: &mut SVector<f64, SLIDING_DIM>) {
        let st = SlidingState(*y);
        let n = scaled_force(self.profile, &self.time_map, self.impulse, st.x());
        let slip = st.slip();
        let speed = planar_length(slip);
        // Past the stop (only inside the step that crosses it) both the direction and a
        // speed-dependent mu continue smoothly in the signed slip: mu(|S|) would put a kink
        // at S = 0 inside that step, costing rejected steps and slow event location. At the
        // located stop the two agree. Below the round-off floor the slip's direction is
        // noise and e0, the exact direction, is used. Frozen (stick = false) is physical
        // beyond the stop: mu of the sliding speed |S|. A signed slip past the stop takes
        // `mu_continued`, which stays bounded: the analytic continuation a + b e^(c |S|)
        // overflowed in the stages of a coarse rk4 step that overshot the stop.
        let (e, s_mu) = match self.direction {
            Direction::CurrentSlip if speed > self.slip_floor => {
                if slip.dot(&self.e0) < 0.0 {
                    (-slip * (1.0 / speed), -speed)
                } else {
                    (slip * (1.0 / speed), speed)
                }
            }
            Direction::CurrentSlip => (self.e0, slip.dot(&self.e0)),
            Direction::Frozen => (self.e0, speed),
        };
        let fr = self.friction.mu_continued(s_mu * self.speed_scale) * n;
        // For identical balls (ia = ib = 1/alpha) these are 2 fr / alpha and
        // 2 fr (1 + 1/alpha) bit for bit: both sums are exact doublings.
        let [ia, ib] = self.inv_alpha;
        let spin = fr * (ia + ib);
        let slip_rate = fr * ((1.0 + ia) + (1.0 + ib));
        *dy = SVector::from([
            1.0,
            -n,
            -fr * e.x,
            -fr * e.y,
            spin * e.y,
            -spin * e.x,
            -slip_rate * e.x,
            -slip_rate * e.y,
            fr * slip.dot(&e),
        ]);
    }
}

/// Eq 14 alone: the balls do not slide (friction off, or stuck).
#[derive(Debug, Clone, Copy)]
pub(crate) struct NormalRhs<'a, P: ForceProfile + ?Sized> {
    /// Normal-force profile.
    pub profile: &'a P,
    /// The integration variable's map to the scaled time.
    pub time_map: TimeMap,
    /// pi = P / (m v_ref).
    pub impulse: f64,
}

impl<P: ForceProfile + ?Sized> ScaledRhs<NORMAL_DIM> for NormalRhs<'_, P> {
    #[inline]
    fn derivative(&self, y: &SVector<f64, NORMAL_DIM>, dy: &mut SVector<f64, NORMAL_DIM>) {
        let n = scaled_force(self.profile, &self.time_map, self.impulse, y[0]);
        *dy = SVector::from([1.0, -n]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::rectangle::Rectangle;

    /// Eqs 20-21 follow from 15-16 and 18-19: the carried slip's derivative equals the
    /// derivative of (2V + Omega_z, 2W - Omega_y) (scaled, r = 1).
    #[test]
    fn slip_rate_is_consistent_with_15_19() {
        let profile = Rectangle::new(1.0).unwrap();
        let rhs = SlidingRhs {
            profile: &profile,
            time_map: TimeMap::Identity,
            impulse: 1.3,
            friction: Friction::constant(0.2).unwrap(),
            speed_scale: 1.0,
            inv_alpha: [2.5, 2.5],
            e0: Vector2::new(0.6, 0.8),
            direction: Direction::CurrentSlip,
            slip_floor: 0.0,
        };
        let y = SlidingState::initial(Vector2::new(0.3, 0.4));
        let mut dy = SVector::zeros();
        rhs.derivative(&y.0, &mut dy);
        let d = SlidingState(dy);
        let [_, dv, dw] = d.delta_u();
        let [doy, doz] = d.delta_omega_yz();
        let ds = d.slip();
        assert!((ds.x - (2.0 * dv + doz)).abs() < 1e-15);
        assert!((ds.y - (2.0 * dw - doy)).abs() < 1e-15);
        // eq 22: dS/ds = -2 mu n (1 + 1/alpha), along -e
        assert!((ds.norm() - 2.0 * 0.2 * 1.3 * 3.5).abs() < 1e-14);
        assert!((ds.normalize() + Vector2::new(0.6, 0.8)).norm() < 1e-15);
        // Heat rate mu n S
        assert!((d.heat() - 0.2 * 1.3 * 0.5).abs() < 1e-15);
    }
}

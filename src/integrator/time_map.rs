//! The variable the integrator steps in: the scaled time s = t / tau itself, or, for pulses
//! with algebraic ends, a change of variable under which the impulse follows the half-sine's
//! (docs/model.md#the-smoothing-change-of-time-variable).
//!
//! A Hertz pulse and a sin^n pulse with fractional n grow like s^n from both ends of the
//! contact: there the force's derivatives of order above n are infinite, so a step of size h
//! at an end errs like h^(n+1) whatever the method's order (rk4 falls to order 2.5 on
//! n = 1.5).
//!
//! Eqs 14-19 depend on time only through the force, and only as f(t) dt = dp: the state is
//! carried along by the impulse. So any monotone change of variable t = tau g(x) gives the
//! right-hand side in x as the one per unit impulse times dp/dx, and the smoothest choice
//! makes dp/dx the same for every pulse: the impulse of the half-sine pulse,
//!
//! ```text
//! p(x) / P = Phi_hs(x) = sin^2(pi x / 2),    dp/dx = P (pi / 2) sin(pi x),
//! s = g(x) = Phi^-1(Phi_hs(x)),              x = g^-1(s) = Phi_hs^-1(Phi(s))
//! ```
//!
//! with Phi the pulse's cumulative impulse (exact for hertz and sine-power). In x the
//! right-hand side is analytic over the whole contact whatever the pulse's ends, and the
//! stepping is the half-sine's step for step: a Hertz or sin^1.5 pulse costs what a
//! half-sine costs, and every method keeps its order. Near an end Phi(s) ~ s^(n+1) and
//! Phi_hs(x) ~ x^2, so g(x) ~ x^(2/(n+1)): g' is not bounded for n > 1, but it never enters
//! the stepping, only the force f(t(x)) g'(x) = dp/dx does.
//!
//! Everything the run reports stays in physical time: sample rows at t = i tau / N (the
//! segment ends are mapped by g^-1), trace rows at t = tau g(x) with the force the profile's
//! f(t), and the stop of sliding from the profile's exact p(t).

use crate::base::settings::SolverSettings;
use crate::profile::force::ForceProfile;
use crate::profile::half_sine::HalfSine;

/// Scaled times grading the steps toward both ends of a pulse with algebraic ends, used
/// when the time transform is off: 2^-10 .. 2^-2 and 1 - 2^-2 .. 1 - 2^-10, so that no step
/// is longer than twice its distance from the end it approaches.
///
/// The force is analytic inside the pulse but its expansion about a point converges only
/// up to the nearer end. A step that reaches from the middle of the pulse to near the end
/// leaves the region where the embedded error estimates hold: dop853 at rtol 1e-10 can take
/// a step from s = 0.567 to 0.969 of a hertz pulse with a true error of 5e-6. Used as
/// breakpoints, these points cost a few steps and keep the error
/// at the tolerance's level.
pub(crate) const GRADED_ENDS: [f64; 18] = [
    1.0 / 1024.0,
    1.0 / 512.0,
    1.0 / 256.0,
    1.0 / 128.0,
    1.0 / 64.0,
    1.0 / 32.0,
    1.0 / 16.0,
    1.0 / 8.0,
    1.0 / 4.0,
    1.0 - 1.0 / 4.0,
    1.0 - 1.0 / 8.0,
    1.0 - 1.0 / 16.0,
    1.0 - 1.0 / 32.0,
    1.0 - 1.0 / 64.0,
    1.0 - 1.0 / 128.0,
    1.0 - 1.0 / 256.0,
    1.0 - 1.0 / 512.0,
    1.0 - 1.0 / 1024.0,
];

/// The map from the integration variable x in [0, 1] to the scaled time s = g(x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum TimeMap {
    /// s = x: the integrator steps in the scaled time itself.
    Identity,
    /// s = Phi^-1(Phi_hs(x)): the impulse follows the unit half-sine pulse's cumulative
    /// impulse Phi_hs, whatever the pulse.
    HalfSineImpulse(HalfSine),
}

impl TimeMap {
    /// The map of a run of `profile` with `settings`: the half-sine impulse when the
    /// setting `time_transform` is on and the profile has algebraic ends, else the identity.
    pub(crate) fn for_run<P: ForceProfile + ?Sized>(
        profile: &P,
        settings: &SolverSettings,
    ) -> Self {
        match profile.end_power() {
            Some(_) if settings.time_transform() => Self::half_sine_impulse(),
            _ => TimeMap::Identity,
        }
    }

    /// The map under which the impulse follows the half-sine's.
    pub(crate) fn half_sine_impulse() -> Self {
        const UNIT: f64 = 1.0;
        TimeMap::HalfSineImpulse(HalfSine::new(UNIT).expect("a unit duration is valid"))
    }

    /// Whether the integration variable is the scaled time itself.
    pub(crate) fn is_identity(&self) -> bool {
        *self == TimeMap::Identity
    }

    /// The scaled force at integration variable `x`: phi(g(x)) g'(x), the rate of the
    /// impulse fraction in x (the pulse's phi(x) for the identity). x is clamped to [0, 1]:
    /// the last stage of the last step can land a rounding error beyond the end, where a
    /// profile that does not vanish there (rectangle, tables) would read 0.
    #[inline]
    pub(crate) fn force<P: ForceProfile + ?Sized>(&self, profile: &P, x: f64) -> f64 {
        match self {
            TimeMap::Identity => profile.shape(x.clamp(0.0, 1.0)),
            TimeMap::HalfSineImpulse(hs) => hs.shape(x.clamp(0.0, 1.0)),
        }
    }

    /// The impulse fraction p / P = Phi(g(x)) reached at integration variable `x`.
    pub(crate) fn impulse_fraction<P: ForceProfile + ?Sized>(&self, profile: &P, x: f64) -> f64 {
        match self {
            TimeMap::Identity => profile.cumulative(x),
            TimeMap::HalfSineImpulse(hs) => hs.cumulative(x),
        }
    }

    /// The integration variable at which the impulse fraction reaches `q` in [0, 1].
    pub(crate) fn at_impulse_fraction<P: ForceProfile + ?Sized>(&self, profile: &P, q: f64) -> f64 {
        match self {
            TimeMap::Identity => profile.time_at_cumulative(q),
            TimeMap::HalfSineImpulse(hs) => hs.time_at_cumulative(q),
        }
    }

    /// The scaled time s = g(x) (for the half-sine impulse, x clamped to [0, 1]).
    pub(crate) fn time<P: ForceProfile + ?Sized>(&self, profile: &P, x: f64) -> f64 {
        match self {
            TimeMap::Identity => x,
            TimeMap::HalfSineImpulse(hs) => {
                profile.time_at_cumulative(hs.cumulative(x.clamp(0.0, 1.0)))
            }
        }
    }

    /// The integration variable x = g^-1(s) at scaled time s in [0, 1].
    pub(crate) fn at_time<P: ForceProfile + ?Sized>(&self, profile: &P, s: f64) -> f64 {
        match self {
            TimeMap::Identity => s,
            TimeMap::HalfSineImpulse(hs) => hs.time_at_cumulative(profile.cumulative(s)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::method::Method;
    use crate::profile::hertz::Hertz;
    use crate::profile::rectangle::Rectangle;
    use crate::profile::sine_power::SinePower;
    use std::f64::consts::PI;

    /// The half-sine impulse map on a sin^1.5 pulse: the force in x is (pi / 2) sin(pi x),
    /// the impulse fraction sin^2(pi x / 2), whatever the pulse (written out here, not read
    /// from the half-sine profile); the time goes there and back, and the impulse reached at
    /// time g(x) is the fraction at x. The sin^1.5 pulse's own cumulative impulse is
    /// checked against its Beta-function formula in the profile's tests.
    #[test]
    fn half_sine_impulse_map() {
        let map = TimeMap::half_sine_impulse();
        let pulse = SinePower::new(1.0, 1.5).unwrap();
        for i in 0..=64 {
            let x = i as f64 / 64.0;
            let want_force = PI / 2.0 * (PI * x).sin();
            assert!((map.force(&pulse, x) - want_force).abs() < 1e-15, "x = {x}");
            let want_q = (PI * x / 2.0).sin().powi(2);
            let q = map.impulse_fraction(&pulse, x);
            assert!((q - want_q).abs() < 4e-16, "x = {x}: {q} vs {want_q}");
            let s = map.time(&pulse, x);
            assert!(
                (pulse.cumulative(s) - want_q).abs() < 1e-13,
                "x = {x}: s = {s}"
            );
            assert!((map.at_time(&pulse, s) - x).abs() < 1e-9, "x = {x}");
            assert!(
                (map.at_impulse_fraction(&pulse, q) - x).abs() < 1e-12,
                "x = {x}"
            );
        }
        assert_eq!(map.force(&pulse, -0.1), 0.0);
        assert_eq!(map.time(&pulse, 1.0 + 1e-12), 1.0);
    }

    /// The transform applies to profiles with algebraic ends when the setting is on.
    #[test]
    fn chosen_per_profile_and_setting() {
        let on = SolverSettings::new(Method::Dop853, 1e-10, 1e-10, 1000).unwrap();
        let off = on.with_time_transform(false);
        let hertz = Hertz::new(1.0).unwrap();
        assert!(!TimeMap::for_run(&hertz, &on).is_identity());
        assert!(TimeMap::for_run(&hertz, &off).is_identity());
        let sp = SinePower::new(1.0, 0.3).unwrap();
        assert!(!TimeMap::for_run(&sp, &on).is_identity());
        let sp2 = SinePower::new(1.0, 2.0).unwrap();
        assert!(TimeMap::for_run(&sp2, &on).is_identity());
        assert!(TimeMap::for_run(&Rectangle::new(1.0).unwrap(), &on).is_identity());
        assert!(TimeMap::for_run(&HalfSine::new(1.0).unwrap(), &on).is_identity());
    }

    /// The identity changes nothing, bit for bit.
    #[test]
    fn identity() {
        let map = TimeMap::Identity;
        let pulse = Hertz::new(1.0).unwrap();
        for x in [0.0, 0.3, 1.0, 1.0 + 1e-16] {
            assert_eq!(map.time(&pulse, x), x);
            assert_eq!(map.at_time(&pulse, x), x);
            assert_eq!(map.force(&pulse, x), pulse.shape(x));
            assert_eq!(map.impulse_fraction(&pulse, x), pulse.cumulative(x));
        }
    }
}

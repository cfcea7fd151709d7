//! The variable the integrator steps in: the scaled time s = t / tau itself, or a smoothing
//! change of variable s = g(x) for pulses with algebraic ends
//! (docs/model.md#the-smoothing-change-of-time-variable).
//!
//! A Hertz pulse and a sin^n pulse with fractional n grow like s^n from both ends of the
//! contact: there the force's derivatives of order above n are infinite, so a step of size h
//! at an end errs like h^(n+1) whatever the method's order (rk4 falls to order 2.5 on
//! n = 1.5). With s = g(x), x in [0, 1], the right-hand side in x is the one in s times
//! g'(x), and the force over an x-step is
//!
//! ```text
//! f(t) dt = (P / tau) phi(g(x)) g'(x) dx
//! ```
//!
//! The map is Sidi's sin^m transform, the normalised integral of sin^m:
//!
//! ```text
//! g_m(x) = integral_0^x sin^m(pi u) du / integral_0^1 sin^m(pi u) du,      g_m(1 - x) = 1 - g_m(x)
//! ```
//!
//! which is the cumulative impulse Phi of the `sine-power` pulse of exponent m (of the
//! half-sine for m = 1): g = Phi, g' = phi, g^-1 = Phi^-1 of that pulse. Near an end
//! g_m(x) ~ x^(m+1) and g_m'(x) ~ x^m, so phi(g(x)) g'(x) ~ x^((n+1)(m+1) - 1).
//!
//! - **m = 1**, g(x) = sin^2(pi x / 2) = (1 - cos(pi x)) / 2, when 2n is an integer (hertz:
//!   n = 3/2; sine-power 0.5, 1.5, 2.5, ...). Then s^(1/2) = sin(pi x / 2) and
//!   (1 - s)^(1/2) = cos(pi x / 2) are analytic, so every term of the pulse's expansion at an
//!   end, powers of s^(1/2) (the exact Hertz pulse has s^(3/2), s^4, s^(13/2), ...; sin^n(pi
//!   s) has s^n times a series in s^2), becomes analytic in x: the right-hand side in x is
//!   smooth over the whole contact and every method keeps its order.
//! - **other n**: the smallest m >= 1 with (n+1)(m+1) >= 9 ([`sidi_order`]). The transformed
//!   force still behaves like x^beta at the ends with beta = (n+1)(m+1) - 1 >= 8 not an
//!   integer, but the first step's error, of order h^(beta+1) <= h^9, is then no larger than
//!   the local error of a smooth step of the highest-order method (dop853, order 8), so the
//!   end no longer lowers any method's order.
//!
//! Everything the run reports stays in physical time: sample rows at t = i tau / N (the
//! segment ends are mapped by g^-1), trace rows at t = tau g(x), and the stop of sliding from
//! the profile's exact p(t).

use super::settings::SolverSettings;
use crate::profile::{ForceProfile, HalfSine, SinePower};

/// Scaled times grading the steps toward both ends of a pulse with algebraic ends, used
/// when the time transform is off: 2^-10 .. 2^-2 and 1 - 2^-2 .. 1 - 2^-10, so that no step
/// is longer than twice its distance from the end it approaches.
///
/// The force is analytic inside the pulse but its expansion about a point converges only
/// up to the nearer end. A step that reaches from the middle of the pulse to near the end
/// leaves the region where the embedded error estimates hold: dop853 at rtol 1e-10 took a
/// step from s = 0.567 to 0.969 of a hertz pulse with a true error of 5e-6 (found by the
/// property tests). Used as breakpoints, these points cost a few steps and keep the error
/// at the tolerance's level.
pub const GRADED_ENDS: [f64; 18] = [
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

/// The smallest integer with (n + 1)(m + 1) >= SIDI_SMOOTHNESS: the transformed force's
/// end behaviour x^beta then has beta + 1 >= 9 (see the module docs).
const SIDI_SMOOTHNESS: f64 = 9.0;

/// The order m of the sin^m transform for ends that grow like s^`n` (n > 0, not an
/// integer): 1 when 2n is an integer, else the smallest m >= 1 with (n + 1)(m + 1) >= 9.
///
/// ```text
/// n      0.1  0.3  0.5  0.7  1.2  1.5  2.3  2.5  3.6  >= 3.5
/// m        8    6    1    5    4    1    2    1    1       1
/// ```
pub fn sidi_order(n: f64) -> u32 {
    if (2.0 * n).fract() == 0.0 {
        return 1;
    }
    let m = (SIDI_SMOOTHNESS / (n + 1.0)).ceil() - 1.0;
    m.max(1.0) as u32
}

/// The map from the integration variable x in [0, 1] to the scaled time s = g(x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeMap {
    /// s = x: the integrator steps in the scaled time itself.
    Identity,
    /// Sidi's sin^1 transform, g(x) = sin^2(pi x / 2): the half-sine's Phi.
    SineSquared(HalfSine),
    /// Sidi's sin^m transform, m >= 2: the Phi of the sine-power pulse of exponent m.
    SinePower(SinePower),
}

impl TimeMap {
    /// The map of a run of `profile` with `settings`: a sin^m transform when the setting
    /// `time_transform` is on and the profile has algebraic ends, else the identity.
    pub fn for_run<P: ForceProfile + ?Sized>(profile: &P, settings: &SolverSettings) -> Self {
        match profile.end_power() {
            Some(n) if settings.time_transform() => Self::sidi(sidi_order(n)),
            _ => TimeMap::Identity,
        }
    }

    /// Sidi's sin^m transform of order `m` >= 1.
    pub fn sidi(m: u32) -> Self {
        const UNIT: f64 = 1.0;
        if m <= 1 {
            TimeMap::SineSquared(HalfSine::new(UNIT).expect("a unit duration is valid"))
        } else {
            TimeMap::SinePower(SinePower::new(UNIT, f64::from(m)).expect("m in [2, 64] is valid"))
        }
    }

    /// The order m of the sin^m transform (`None` for the identity).
    pub fn order(&self) -> Option<u32> {
        match self {
            TimeMap::Identity => None,
            TimeMap::SineSquared(_) => Some(1),
            TimeMap::SinePower(p) => Some(p.exponent() as u32),
        }
    }

    /// Whether the integration variable is the scaled time itself.
    pub fn is_identity(&self) -> bool {
        *self == TimeMap::Identity
    }

    /// The scaled time s = g(x), x clamped to [0, 1].
    #[inline]
    pub fn time(&self, x: f64) -> f64 {
        match self {
            TimeMap::Identity => x,
            TimeMap::SineSquared(p) => p.cumulative(x.clamp(0.0, 1.0)),
            TimeMap::SinePower(p) => p.cumulative(x.clamp(0.0, 1.0)),
        }
    }

    /// The scaled time s = g(x) and the rate ds/dx = g'(x), x clamped to [0, 1]; (x, 1)
    /// for the identity.
    #[inline]
    pub fn time_and_rate(&self, x: f64) -> (f64, f64) {
        match self {
            TimeMap::Identity => (x, 1.0),
            TimeMap::SineSquared(p) => p.cumulative_and_shape(x.clamp(0.0, 1.0)),
            TimeMap::SinePower(p) => {
                let x = x.clamp(0.0, 1.0);
                (p.cumulative(x), p.shape(x))
            }
        }
    }

    /// The integration variable x = g^-1(s) at scaled time s in [0, 1].
    pub fn at_time(&self, s: f64) -> f64 {
        match self {
            TimeMap::Identity => s,
            TimeMap::SineSquared(p) => p.time_at_cumulative(s),
            TimeMap::SinePower(p) => p.time_at_cumulative(s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Method;
    use crate::profile::{Hertz, Rectangle};
    use std::f64::consts::PI;

    /// The orders of the table in [`sidi_order`]'s docs, from (n + 1)(m + 1) >= 9 worked by
    /// hand: n = 0.3 needs m + 1 >= 9 / 1.3 = 6.9, so m = 6; n = 1.2: 9 / 2.2 = 4.1, m = 4.
    #[test]
    fn orders() {
        let table = [
            (0.1, 8),
            (0.3, 6),
            (0.5, 1),
            (0.7, 5),
            (1.2, 4),
            (1.5, 1),
            (2.3, 2),
            (2.5, 1),
            (3.6, 1),
            (7.3, 1),
        ];
        for (n, m) in table {
            assert_eq!(sidi_order(n), m, "n = {n}");
            if (2.0 * n).fract() != 0.0 {
                let m = f64::from(m);
                assert!((n + 1.0) * (m + 1.0) >= 9.0 || m == 1.0, "n = {n}");
                assert!(
                    (n + 1.0) * m < 9.0 || m == 1.0,
                    "n = {n}: m not the smallest"
                );
            }
        }
    }

    /// m = 1 is g(x) = sin^2(pi x / 2), g'(x) = (pi / 2) sin(pi x); its inverse
    /// x = (2 / pi) asin(sqrt(s)).
    #[test]
    fn sine_squared_map() {
        let map = TimeMap::sidi(1);
        assert_eq!(map.order(), Some(1));
        for i in 0..=64 {
            let x = i as f64 / 64.0;
            let (s, rate) = map.time_and_rate(x);
            let want = (PI * x / 2.0).sin().powi(2);
            assert!((s - want).abs() < 4e-16, "x = {x}: {s} vs {want}");
            assert!((rate - PI / 2.0 * (PI * x).sin()).abs() < 1e-15, "x = {x}");
            assert_eq!(map.time(x), s);
            let back = map.at_time(want);
            assert!((back - x).abs() < 1e-14, "x = {x}: {back}");
        }
        assert_eq!(map.time_and_rate(-0.1), (0.0, 0.0));
        assert_eq!(map.time(1.0 + 1e-12), 1.0);
    }

    /// m = 2 is g(x) = x - sin(2 pi x) / (2 pi), g'(x) = 2 sin^2(pi x) (the integral of
    /// sin^2 over [0, 1] is 1/2).
    #[test]
    fn sine_power_map() {
        let map = TimeMap::sidi(2);
        assert_eq!(map.order(), Some(2));
        for i in 0..=32 {
            let x = i as f64 / 32.0;
            let (s, rate) = map.time_and_rate(x);
            let want = x - (2.0 * PI * x).sin() / (2.0 * PI);
            assert!((s - want).abs() < 1e-14, "x = {x}: {s} vs {want}");
            assert!(
                (rate - 2.0 * (PI * x).sin().powi(2)).abs() < 1e-14,
                "x = {x}"
            );
            if x > 0.0 && x < 1.0 {
                assert!((map.at_time(want) - x).abs() < 1e-12, "x = {x}");
            }
        }
    }

    /// The transform applies to profiles with algebraic ends when the setting is on.
    #[test]
    fn chosen_per_profile_and_setting() {
        let on = SolverSettings::new(Method::Dop853, 1e-10, 1e-10, 1000).unwrap();
        let off = on.with_time_transform(false);
        let hertz = Hertz::new(1.0).unwrap();
        assert_eq!(TimeMap::for_run(&hertz, &on).order(), Some(1));
        assert!(TimeMap::for_run(&hertz, &off).is_identity());
        let sp = SinePower::new(1.0, 0.3).unwrap();
        assert_eq!(TimeMap::for_run(&sp, &on).order(), Some(6));
        let sp2 = SinePower::new(1.0, 2.0).unwrap();
        assert!(TimeMap::for_run(&sp2, &on).is_identity());
        assert!(TimeMap::for_run(&Rectangle::new(1.0).unwrap(), &on).is_identity());
        assert!(TimeMap::for_run(&HalfSine::new(1.0).unwrap(), &on).is_identity());
    }

    /// The identity changes nothing, bit for bit.
    #[test]
    fn identity() {
        let map = TimeMap::Identity;
        for x in [0.0, 0.3, 1.0 + 1e-16, -1e-300] {
            assert_eq!(map.time_and_rate(x), (x, 1.0));
            assert_eq!(map.at_time(x), x);
        }
    }
}

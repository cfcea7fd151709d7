//! Location of the stop of sliding inside the step that crossed it: regula falsi with the
//! Illinois modification in the impulse fraction q = Phi(s) (docs/model.md#locating-the-stop-of-sliding),
//! s = g(x) the scaled time of the integration variable.

use super::rhs::{SlidingRhs, SlidingState, SLIDING_DIM};
use super::stepping::{Stepper, WHOLE_SPAN};
use crate::base::error::Error;
use crate::base::root::{illinois_update, Bound, Side};
use crate::profile::force::ForceProfile;
use nalgebra::SVector;

/// The event function g = slip . e0 at or below which the slip counts as stopped, relative
/// to |slip(0)|: its round-off level (an impulse error of at most 1e-14 p_stick). A step
/// that lands there (a sample time, a breakpoint) is the stop itself.
pub(super) const STOP_FLOOR: f64 = 1e-14;

/// Bracket width in q (fraction of P) at which the location is done: a few ulps of 1.
const Q_TOL: f64 = 1e-14;

/// |g| at which the location is done, relative to the range of g over the crossing step:
/// its round-off level.
const G_TOL: f64 = 1e-14;

/// Most trials of the root finder. g is affine in q while mu is constant, so one or two
/// trials usually suffice; with a speed-dependent mu the Illinois iteration converges
/// superlinearly. The bound only guards against a pathological profile.
const MAX_TRIALS: usize = 100;

/// Locates the stop of sliding inside the step from `prev` (g > 0) to `cross` (g <= 0):
/// regula falsi (Illinois) in q = Phi(g(x)), each trial re-integrated from `prev` to the
/// integration variable where the impulse fraction is q ([`TimeMap::at_impulse_fraction`]).
///
/// The trials integrate with friction along e0 (the round-off branch of the right-hand
/// side). Every trial is aimed at the stop, so its last stages evaluate the right-hand side
/// where the slip is a rounding error of S(0) and its direction slip/|slip| is noise:
/// friction at full strength in a random direction, an error of order (step) x mu f in the
/// located state (3e-8 scaled for RK4 on a rectangle pulse) and a root finder that stalls.
/// For the exact flow the slip stays on its ray (theta constant, eq 23), so inside this one
/// step e0 is the direction the slip has; the accepted steps before it keep taking the
/// direction from the current slip, and theta_drift measures them.
pub(super) fn locate_stop<P: ForceProfile + ?Sized>(
    rhs: &SlidingRhs<'_, P>,
    stepper: &mut Stepper,
    profile: &P,
    prev: &SlidingState,
    cross: &SlidingState,
) -> Result<SlidingState, Error> {
    let map = rhs.time_map;
    let (x_lo0, x_hi0) = (prev.x(), cross.x());
    let mut lo = Bound {
        q: map.impulse_fraction(profile, x_lo0),
        g: rhs.event(prev),
    };
    let mut hi = Bound {
        q: map.impulse_fraction(profile, x_hi0),
        g: rhs.event(cross),
    };
    if hi.g >= 0.0 {
        // The step ended within round-off of the stop: that is the stop.
        return Ok(*cross);
    }
    let g_tol = G_TOL * (lo.g - hi.g);
    let mut best = *cross;
    let mut best_g = hi.g.abs();
    let mut side = Side::None;
    let mut no_stop = |_: &SVector<f64, SLIDING_DIM>| false;
    // Friction along e0 in every trial, with a speed-dependent mu continued in the signed
    // slip: an infinite round-off floor selects exactly that branch of the right-hand side.
    let frozen = SlidingRhs {
        slip_floor: f64::INFINITY,
        ..*rhs
    };
    for _ in 0..MAX_TRIALS {
        if best_g <= g_tol || hi.q - lo.q <= Q_TOL {
            break;
        }
        let q = lo.q + (hi.q - lo.q) * (lo.g / (lo.g - hi.g));
        let x = map.at_impulse_fraction(profile, q).clamp(x_lo0, x_hi0);
        let adv = stepper.advance(&frozen, x_lo0, prev.0, x, WHOLE_SPAN, &mut no_stop)?;
        let st = SlidingState(adv.y);
        let g = rhs.event(&st);
        if g.abs() < best_g || (g <= 0.0 && g.abs() <= best_g) {
            best = st;
            best_g = g.abs();
        }
        side = illinois_update(&mut lo, &mut hi, side, q, g);
    }
    Ok(best)
}

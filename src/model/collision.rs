//! One collision to resolve: balls, contact, effects and the incoming centre-of-mass state,
//! with the quantities every method derives from them (impulse, slip, reference scales).

use crate::base::error::Error;
use crate::model::effects::Effects;
use crate::model::params::{BallPair, Contact, Friction};
use crate::model::state::{planar_length, CmState};
use nalgebra::Vector2;

/// Below this speed (m/s) the squares of the norms may underflow (the square root of the
/// smallest normal double, 1.5e-154, with a margin), and the norms are taken with hypot.
const SQUARES_UNDERFLOW: f64 = 1e-150;

/// Natural scales of a collision (docs/model.md#scales-and-scaled-errors): errors are
/// reported relative to them and the integrator works in the variables they make
/// dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Reference speed v_ref = max(|U(0)|, S(0), |U(0)| (vector), r_A |Omega^A(0)|,
    /// r_B |Omega^B(0)|) (m/s); 0 only for balls at rest.
    pub speed: f64,
    /// Reference spin v_ref / r_A (rad/s).
    pub spin: f64,
    /// Reference impulse M v_ref (N s), M the pair mass (m for identical balls).
    pub impulse: f64,
    /// Reference energy M v_ref^2 (J).
    pub energy: f64,
    /// Reference angular momentum M v_ref r_A (kg m^2 / s).
    pub angular_momentum: f64,
}

/// A validated collision problem in the centre-of-mass frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Collision {
    /// Balls A and B (two identical balls in the paper's case).
    pub balls: BallPair,
    /// Friction and the impulse rule.
    pub contact: Contact,
    /// Simulated effects.
    pub effects: Effects,
    /// Incoming state (before contact).
    pub incoming: CmState,
    /// Impulse P of the collision (N s); 0 when the balls do not approach.
    pub impulse: f64,
    /// Sliding speed S(0) (m/s).
    pub s0: f64,
    /// Initial sliding direction e0 = (cos theta, sin theta); `None` when S(0) = 0.
    pub direction: Option<Vector2<f64>>,
    /// Reference scales.
    pub scales: Scales,
}

impl Collision {
    /// Validates the incoming state (finite) and fixes the impulse P from the contact's
    /// rule (an explicit impulse needs approaching balls and m U(0) <= P <= 2 m U(0), with
    /// the pair mass M in place of m for unequal balls). `balls` is one [`crate::Ball`] (two
    /// identical balls) or a [`BallPair`].
    ///
    /// ```
    /// use billiard_contact::{Ball, Collision, CmState, Contact, Effects, Friction, ImpulseRule};
    /// use billiard_contact::nalgebra::Vector3;
    /// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
    /// let contact = Contact { friction: Friction::constant(0.06).unwrap(),
    ///                         impulse: ImpulseRule::restitution(1.0).unwrap() };
    /// let s = CmState::new(Vector3::new(0.5, 0.25, 0.0), Vector3::zeros(), Vector3::zeros());
    /// let c = Collision::new(ball, contact, Effects::default(), s).unwrap();
    /// assert_eq!(c.impulse, 2.0 * 0.17 * 0.5); // eq 52
    /// assert_eq!(c.s0, 0.5); // 2 V
    /// ```
    #[inline]
    pub fn new(
        balls: impl Into<BallPair>,
        contact: Contact,
        effects: Effects,
        incoming: CmState,
    ) -> Result<Self, Error> {
        let balls = balls.into();
        if !incoming.is_finite() {
            return Err(non_finite_component(&incoming));
        }
        let u0 = incoming.u_cm.x;
        let m = balls.pair_mass();
        let impulse = contact.impulse.impulse(m, u0)?;
        let slip = incoming.slip_of(&balls);
        // A slip below the smallest normal double (a cut of 5e-309 degrees) has no digits
        // left, and its square, which the sliding equations take, underflows to 0: it is
        // no slip at all.
        let s0 = Some(planar_length(slip))
            .filter(|s| s.is_normal())
            .unwrap_or(0.0);
        let direction = if s0 > 0.0 { Some(slip / s0) } else { None };
        let r = balls.a.radius();
        let rb = balls.b.radius();
        // One square root for the three norms (sqrt is monotone, so the maximum is the
        // same); |U(0)| <= |U| needs no term of its own. Where the squares overflow (above
        // ~1e154) or underflow (below ~1e-154, where 1e-170 m/s squared is 0 and the ball
        // would pass for one at rest) the norms are taken with hypot instead.
        let mut speed = s0.max(
            incoming
                .u_cm
                .norm_squared()
                .max(r * r * incoming.omega_a.norm_squared())
                .max(rb * rb * incoming.omega_b.norm_squared())
                .sqrt(),
        );
        if !(speed.is_finite() && speed >= SQUARES_UNDERFLOW) {
            let norm = |v: &nalgebra::Vector3<f64>| v.x.hypot(v.y).hypot(v.z);
            speed = s0
                .max(norm(&incoming.u_cm))
                .max(r * norm(&incoming.omega_a))
                .max(rb * norm(&incoming.omega_b));
        }
        // Every scale the checks and the integrator divide by must be finite and, for balls
        // in motion, normal: r = 1e308 makes m v r infinite, r = 1e-300 overflows v / r, and
        // either makes the checks NaN.
        let scales_ok = [speed / r, m * speed, m * speed * speed, m * speed * r]
            .iter()
            .all(|x| x.is_finite() && (speed == 0.0 || x.is_normal()));
        if !(speed.is_finite() && scales_ok && impulse.is_finite()) {
            return Err(Error::invalid(
                "incoming",
                format!(
                    "speeds and r |Omega| up to {speed:e} m/s ({})",
                    balls.describe()
                ),
                format!(
                    "magnitudes whose scales v/r, m v, m v^2 and m v r are finite, normal \
                     double-precision numbers (here 0 or speeds from {:.1e} to {:.1e} m/s)",
                    (f64::MIN_POSITIVE / m)
                        .sqrt()
                        .max(f64::MIN_POSITIVE / (m * r))
                        .max(f64::MIN_POSITIVE * r),
                    (f64::MAX.sqrt() / m.sqrt())
                        .min(f64::MAX / (m * r))
                        .min(f64::MAX * r)
                ),
            ));
        }
        Ok(Collision {
            balls,
            contact,
            effects,
            incoming,
            impulse,
            s0,
            direction,
            scales: Scales {
                speed,
                spin: speed / r,
                impulse: m * speed,
                energy: m * speed * speed,
                angular_momentum: m * speed * r,
            },
        })
    }

    /// True when the balls approach (U(0) > 0) and an impulse acts.
    pub fn collides(&self) -> bool {
        self.impulse > 0.0
    }

    /// The friction law actually acting through this contact: `None` when friction is off
    /// (effect) or zero; a speed-dependent mu evaluated at the initial slip is the constant
    /// mu(S(0)) ([`Friction::acting_from`]).
    #[inline]
    pub fn active_friction(&self) -> Option<Friction> {
        let f = self.contact.friction.acting_from(self.s0);
        if self.effects.friction && !f.is_zero() {
            Some(f)
        } else {
            None
        }
    }

    /// Sliding direction theta (rad) in (-pi, pi]; `None` when S(0) = 0.
    pub fn theta(&self) -> Option<f64> {
        self.incoming.theta_of(&self.balls)
    }
}

/// The error for the first non-finite component of an incoming state (kept out of line: the
/// common path of [`Collision::new`] is a few dozen floating-point operations).
#[cold]
#[inline(never)]
fn non_finite_component(incoming: &CmState) -> Error {
    for (name, v) in [
        ("u", incoming.u_cm),
        ("omega_a", incoming.omega_a),
        ("omega_b", incoming.omega_b),
    ] {
        for (i, x) in v.iter().enumerate() {
            if !x.is_finite() {
                return Error::invalid(format!("incoming.cm.{name}[{i}]"), x, "a finite number");
            }
        }
    }
    Error::invalid("incoming.cm", "a finite state", "a non-finite component")
}

//! The exact solution: eqs 24-35 with the impulse of eq 52 / 56, extended by the stick rule
//! and the S(0) = 0 case (ERRATA.md, gaps 1-3).
//!
//! With J the tangential impulse ([`crate::friction`]; J = mu min(P, p_stick) for
//! constant mu) and e = (0, cos theta, sin theta):
//!
//! ```text
//! U(tau) = U(0) - P/m                           (24)
//! (V, W)(tau) = (V, W)(0) - (J/m) (cos, sin)    (25-26)
//! Omega^{A,B}_x unchanged                         (31)
//! Omega^{A,B}_y += J sin(theta) / (alpha m r)    (32)
//! Omega^{A,B}_z -= J cos(theta) / (alpha m r)    (33)
//! H = H_sfr + 2 U(0) P - P^2 / m                 (50)
//! ```
//!
//! While sliding, the state at time t is this solution at P = p(t) (ERRATA.md, gap 3);
//! [`ClosedForm::at_impulse`] gives it.

use crate::collision::Collision;
use crate::friction::{Sliding, SlidingLaw};
use crate::state::CmState;
use nalgebra::Vector2;

/// The state after part of the impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Partial {
    /// Centre-of-mass state.
    pub state: CmState,
    /// Sliding after that impulse.
    pub sliding: Sliding,
}

/// The exact outcome of a collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedForm {
    /// Impulse P (N s).
    pub impulse: f64,
    /// Tangential impulse J >= 0 (N s): along -e on A, +e on B.
    pub tangential_impulse: f64,
    /// Signed outgoing sliding speed along e (m/s): >= 0 with sticking.
    pub s_out: f64,
    /// Whether sliding stopped during the contact.
    pub sticks: bool,
    /// p_stick (N s): the impulse at which sliding stops (or would stop); `None` when it
    /// never would (no collision, no friction, or infinite).
    pub stick_impulse: Option<f64>,
    /// Heat of sliding friction H_sfr (J), eq 49 with the stick rule.
    pub heat_sliding: f64,
    /// Total heat H (J), eq 50.
    pub heat: f64,
    /// Outgoing state.
    pub out: CmState,
    law: Option<SlidingLaw>,
    incoming: CmState,
    direction: Vector2<f64>,
    mass: f64,
    spin_per_impulse: f64,
    u0: f64,
}

impl ClosedForm {
    /// Solves a collision exactly. No allocation; a few dozen floating-point operations.
    ///
    /// ```
    /// # use billiard_contact::*; use billiard_contact::effects::Effects; use nalgebra::Vector3;
    /// // The paper's special case (eqs 59-72): rolling ball (u, v) striking a ball at rest.
    /// let (m, r, mu, u, v) = (0.17, 0.028575, 0.06, 1.0, 0.5);
    /// let ball = Ball::new(m, r, 0.4).unwrap();
    /// let contact = Contact { friction: Friction::constant(mu).unwrap(),
    ///                         impulse: ImpulseRule::restitution(1.0).unwrap() };
    /// let incoming = CmState::new(Vector3::new(u / 2.0, v / 2.0, 0.0),
    ///                             Vector3::new(-v / r, u / r, 0.0), Vector3::zeros());
    /// let c = Collision::new(ball, contact, Effects::default(), incoming).unwrap();
    /// let out = ClosedForm::new(&c).out;
    /// let s = (u * u + v * v).sqrt();
    /// assert!((out.u_cm.x - (u / 2.0 - u)).abs() < 1e-15);             // eq 66
    /// assert!((out.u_cm.y - (v / 2.0 - mu * u * v / s)).abs() < 1e-15); // eq 67
    /// assert!((out.u_cm.z - mu * u * u / s).abs() < 1e-15);            // eq 68
    /// ```
    #[inline]
    pub fn new(c: &Collision) -> Self {
        let ball = c.ball;
        let m = ball.mass;
        let law = match (c.collides(), c.active_friction()) {
            (true, Some(f)) => Some(SlidingLaw::new(
                f,
                c.s0,
                ball.slip_rate_per_friction_impulse(),
                c.effects.stick,
            )),
            _ => None,
        };
        let mut cf = ClosedForm {
            impulse: c.impulse,
            tangential_impulse: 0.0,
            s_out: c.s0,
            sticks: false,
            stick_impulse: law.and_then(|l| l.stick_impulse()),
            heat_sliding: 0.0,
            heat: 0.0,
            out: c.incoming,
            law,
            incoming: c.incoming,
            direction: c.direction.unwrap_or_else(Vector2::zeros),
            mass: m,
            spin_per_impulse: 1.0 / (ball.alpha * m * ball.radius),
            u0: c.incoming.u_cm.x,
        };
        if !c.collides() {
            return cf;
        }
        let end = cf.at_impulse(c.impulse);
        cf.out = end.state;
        cf.tangential_impulse = end.sliding.tangential_impulse;
        cf.s_out = if law.is_some() {
            end.sliding.slip
        } else {
            c.s0
        };
        cf.heat_sliding = end.sliding.heat;
        cf.heat = cf.heat_sliding + c.impulse * (2.0 * cf.u0 - c.impulse / m);
        cf.sticks =
            c.effects.stick && law.is_some() && cf.stick_impulse.is_some_and(|ps| ps <= c.impulse);
        cf
    }

    /// The exact state after normal impulse `p` (N s), 0 <= p <= P.
    #[inline]
    pub fn at_impulse(&self, p: f64) -> Partial {
        let sliding = match self.law {
            Some(l) => l.at(p),
            None => Sliding {
                tangential_impulse: 0.0,
                slip: self.s_out,
                heat: 0.0,
            },
        };
        let m = self.mass;
        let j = sliding.tangential_impulse;
        let e = self.direction;
        let mut s = self.incoming;
        s.u_cm.x -= p / m;
        s.u_cm.y -= j / m * e.x;
        s.u_cm.z -= j / m * e.y;
        let dy = j * self.spin_per_impulse * e.y;
        let dz = -j * self.spin_per_impulse * e.x;
        s.omega_a.y += dy;
        s.omega_b.y += dy;
        s.omega_a.z += dz;
        s.omega_b.z += dz;
        Partial { state: s, sliding }
    }

    /// Whether eq 57 (S(tau) >= 0) fails: only possible with `stick = false`.
    pub fn violates_eq57(&self) -> bool {
        self.s_out < 0.0
    }
}

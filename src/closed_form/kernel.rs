//! The exact solution: eqs 24-35 with the impulse of eq 52 / 56, extended by the stick rule
//! and the S(0) = 0 case (docs/model.md#when-sliding-stops-during-contact,
//! docs/model.md#no-initial-sliding).
//!
//! With J the tangential impulse ([`crate::closed_form::sliding`]; J = mu min(P, p_stick) for
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
//! While sliding, the state at time t is this solution at P = p(t)
//! (docs/model.md#the-exact-state-during-the-contact); [`ClosedForm::at_impulse`] gives it.
//!
//! For balls of different mass, radius or alpha (docs/unequal-balls.md) m is the pair mass
//! M = 2 m_A m_B / (m_A + m_B), the slip rate k is K = 1/m_A + 1/m_B + r_A^2/I_A + r_B^2/I_B,
//! and each ball's spin changes with its own 1 / (alpha m r); for identical balls every one
//! of these equals the paper's coefficient bit for bit ([`BallPair`]).

use crate::base::error::Error;
use crate::closed_form::sliding::{Sliding, SlidingLaw};
use crate::model::collision::Collision;
use crate::model::effects::Effects;
use crate::model::params::{BallPair, Contact, Friction, FrictionLaw, ImpulseRule};
use crate::model::result::ContactResult;
use crate::model::state::{planar_length, slip_angle, CmState};
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
    /// The result: impulses, sliding, heat (eqs 49-50) and the outgoing state.
    pub result: ContactResult,
    law: Option<SlidingLaw>,
    incoming: CmState,
    direction: Vector2<f64>,
    mass: f64,
    spin_per_impulse: [f64; 2],
    u0: f64,
}

impl ClosedForm {
    /// Solves a collision exactly. No allocation; a few dozen floating-point operations.
    ///
    /// ```
    /// # use billiard_contact::*; use nalgebra::Vector3;
    /// // The paper's special case (eqs 59-72): rolling ball (u, v) striking a ball at rest.
    /// let (m, r, mu, u, v) = (0.17, 0.028575, 0.06, 1.0, 0.5);
    /// let ball = Ball::new(m, r, 0.4).unwrap();
    /// let contact = Contact { friction: Friction::constant(mu).unwrap(),
    ///                         impulse: ImpulseRule::restitution(1.0).unwrap() };
    /// let incoming = CmState::new(Vector3::new(u / 2.0, v / 2.0, 0.0),
    ///                             Vector3::new(-v / r, u / r, 0.0), Vector3::zeros());
    /// let c = Collision::new(ball, contact, Effects::default(), incoming).unwrap();
    /// let out = ClosedForm::new(&c).result.out;
    /// let s = (u * u + v * v).sqrt();
    /// assert!((out.u_cm.x - (u / 2.0 - u)).abs() < 1e-15);             // eq 66
    /// assert!((out.u_cm.y - (v / 2.0 - mu * u * v / s)).abs() < 1e-15); // eq 67
    /// assert!((out.u_cm.z - mu * u * u / s).abs() < 1e-15);            // eq 68
    /// ```
    #[inline]
    pub fn new(c: &Collision) -> Self {
        let balls = c.balls;
        let m = balls.pair_mass();
        let law = match (c.collides(), c.active_friction()) {
            (true, Some(f)) => Some(SlidingLaw::new(
                f,
                c.s0,
                balls.slip_rate_per_friction_impulse(),
                c.effects.stick,
            )),
            _ => None,
        };
        let mut cf = ClosedForm {
            result: ContactResult {
                impulse: c.impulse,
                s0: c.s0,
                theta: c.theta(),
                s_out: c.s0,
                sticks: false,
                stick_impulse: law.and_then(|l| l.stick_impulse()),
                tangential_impulse: 0.0,
                heat: 0.0,
                heat_sliding: 0.0,
                out: c.incoming,
            },
            law,
            incoming: c.incoming,
            direction: c.direction.unwrap_or_else(Vector2::zeros),
            mass: m,
            spin_per_impulse: [balls.spin_per_impulse_a(), balls.spin_per_impulse_b()],
            u0: c.incoming.u_cm.x,
        };
        if !c.collides() {
            return cf;
        }
        let end = cf.at_impulse(c.impulse);
        let r = &mut cf.result;
        r.out = end.state;
        r.tangential_impulse = end.sliding.tangential_impulse;
        r.s_out = if law.is_some() {
            end.sliding.slip
        } else {
            c.s0
        };
        r.heat_sliding = end.sliding.heat;
        r.heat = r.heat_sliding + c.impulse * (2.0 * cf.u0 - c.impulse / m);
        r.sticks =
            c.effects.stick && law.is_some() && r.stick_impulse.is_some_and(|ps| ps <= c.impulse);
        cf
    }

    /// The exact state after normal impulse `p` (N s), 0 <= p <= P.
    #[inline]
    pub fn at_impulse(&self, p: f64) -> Partial {
        let sliding = match self.law {
            Some(l) => l.at(p),
            None => Sliding {
                tangential_impulse: 0.0,
                slip: self.result.s_out,
                heat: 0.0,
            },
        };
        let s = apply_impulses(
            self.incoming,
            self.direction,
            self.mass,
            self.spin_per_impulse,
            p,
            sliding.tangential_impulse,
        );
        Partial { state: s, sliding }
    }

    /// Whether eq 57 (S(tau) >= 0) fails: only possible with `stick = false`.
    pub fn violates_eq57(&self) -> bool {
        self.result.s_out < 0.0
    }
}

/// Eqs 24-26 and 31-33: the state after normal impulse `p` and tangential impulse `j`
/// (N s) along -e on A (m/s, rad/s); `m` the pair mass, `spin_per_impulse` the
/// 1 / (alpha m r) of A and of B.
#[inline]
fn apply_impulses(
    mut s: CmState,
    e: Vector2<f64>,
    m: f64,
    spin_per_impulse: [f64; 2],
    p: f64,
    j: f64,
) -> CmState {
    s.u_cm.x -= p / m;
    s.u_cm.y -= j / m * e.x;
    s.u_cm.z -= j / m * e.y;
    apply_spin_changes(&mut s, e, spin_per_impulse, j);
    s
}

/// Eqs 32-33 for each ball: Omega' - Omega = -J r (e_x x e) / I = J (e_z, -e_y) / (alpha m r).
#[inline(always)]
fn apply_spin_changes(s: &mut CmState, e: Vector2<f64>, spin_per_impulse: [f64; 2], j: f64) {
    let [ka, kb] = spin_per_impulse;
    s.omega_a.y += j * ka * e.y;
    s.omega_a.z += -j * ka * e.x;
    s.omega_b.y += j * kb * e.y;
    s.omega_b.z += -j * kb * e.x;
}

/// The closed form of many centre-of-mass states that share balls, contact and effects:
/// the batch fast path. The same formulas as [`ClosedForm::new`] (the same results to a few
/// ulps: with constant mu it multiplies by precomputed reciprocals of m, k and k mu), without
/// the intermediate [`Collision`] and [`ClosedForm`] records (reference scales, the law kept
/// for [`ClosedForm::at_impulse`]), which a batch does not need.
///
/// ```
/// # use billiard_contact::*;
/// # use billiard_contact::details::ClosedFormBatch; use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// let contact = Contact { friction: Friction::constant(0.06).unwrap(),
///                         impulse: ImpulseRule::restitution(1.0).unwrap() };
/// let batch = ClosedFormBatch::new(ball, contact, Effects::default());
/// let s = CmState::new(Vector3::new(0.5, 0.25, 0.0), Vector3::zeros(), Vector3::zeros());
/// let r = batch.resolve(&s).unwrap();
/// assert_eq!(r.impulse, 2.0 * 0.17 * 0.5);               // eq 52
/// // eq 25 with J = mu P (p_stick = m S(0) / (2 mu (1 + 1/alpha)) = 0.202 > P = 0.17):
/// assert!((r.out.u_cm.y - (0.25 - 0.06 * 2.0 * 0.5)).abs() < 1e-15);
/// assert!(!r.sticks && r.theta == Some(0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormBatch {
    balls: BallPair,
    /// r_A (m) and r_B / r_A, for the slip.
    radius_a: f64,
    radius_ratio: f64,
    rule: ImpulseRule,
    /// The friction acting (`None`: off, or mu = 0).
    friction: Option<Friction>,
    stick: bool,
    contact: Contact,
    effects: Effects,
    /// k = 2 (1 + 1/alpha) / m (1/kg), K for unequal balls.
    k: f64,
    /// 1 / k (kg).
    inv_k: f64,
    /// 1 / (k mu) for constant mu (kg); infinite for mu = 0.
    inv_k_mu: f64,
    /// 1 / m (1/kg), 1 / M for unequal balls.
    inv_m: f64,
    /// 1 / (alpha m r) of A and of B.
    spin_per_impulse: [f64; 2],
}

impl ClosedFormBatch {
    /// The shared parameters of a batch: `balls` is one [`crate::Ball`] (two identical
    /// balls) or a [`BallPair`].
    pub fn new(balls: impl Into<BallPair>, contact: Contact, effects: Effects) -> Self {
        let balls = balls.into();
        let f = contact.friction;
        let k = balls.slip_rate_per_friction_impulse();
        ClosedFormBatch {
            balls,
            radius_a: balls.a.radius(),
            radius_ratio: balls.radius_ratio(),
            rule: contact.impulse,
            friction: (effects.friction && !f.is_zero()).then_some(f),
            stick: effects.stick,
            contact,
            effects,
            k,
            inv_k: 1.0 / k,
            inv_k_mu: match f.law() {
                FrictionLaw::Constant(mu) => 1.0 / (k * mu),
                FrictionLaw::SpeedDependent { .. } => f64::INFINITY,
            },
            inv_m: 1.0 / balls.pair_mass(),
            spin_per_impulse: [balls.spin_per_impulse_a(), balls.spin_per_impulse_b()],
        }
    }

    /// The closed form of one incoming state; the errors of [`Collision::new`].
    #[inline(always)]
    pub fn resolve(&self, s: &CmState) -> Result<ContactResult, Error> {
        self.resolve_theta::<true>(s)
    }

    /// [`ClosedFormBatch::resolve`] without the sliding direction: `theta` is `None` (its
    /// arctangent is a fifth of the cost), for callers that do not report it.
    #[inline(always)]
    pub(crate) fn resolve_without_theta(&self, s: &CmState) -> Result<ContactResult, Error> {
        self.resolve_theta::<false>(s)
    }

    /// The closed form, with theta when `THETA`.
    #[inline(always)]
    fn resolve_theta<const THETA: bool>(&self, s: &CmState) -> Result<ContactResult, Error> {
        if !s.is_finite() {
            return Err(self.invalid(s));
        }
        let m = self.balls.pair_mass();
        let u0 = s.u_cm.x;
        let p = self.rule.impulse(m, u0)?;
        if let (Some(FrictionLaw::Constant(mu)), true) = (self.friction.map(|f| f.law()), p > 0.0) {
            return Ok(self.resolve_constant_mu::<THETA>(s, mu, p));
        }
        let slip = s.slip_with(self.radius_a, self.radius_ratio);
        let s0 = planar_length(slip);
        let theta = (THETA && s0 > 0.0).then(|| slip_angle(slip));
        let law = match self.friction {
            Some(f) if p > 0.0 => Some(SlidingLaw::new(f.acting_from(s0), s0, self.k, self.stick)),
            _ => None,
        };
        let stick_impulse = law.and_then(|l| l.stick_impulse());
        if p <= 0.0 {
            return Ok(ContactResult {
                out: *s,
                impulse: p,
                s0,
                theta,
                sticks: false,
                stick_impulse,
                tangential_impulse: 0.0,
                s_out: s0,
                heat_sliding: 0.0,
                heat: 0.0,
            });
        }
        let (j, s_out, heat_sliding) = match law {
            Some(l) => {
                let sl = l.at(p);
                (sl.tangential_impulse, sl.slip, sl.heat)
            }
            None => (0.0, s0, 0.0),
        };
        let e = if s0 > 0.0 {
            slip / s0
        } else {
            Vector2::zeros()
        };
        Ok(ContactResult {
            out: apply_impulses(*s, e, m, self.spin_per_impulse, p, j),
            impulse: p,
            s0,
            theta,
            sticks: self.stick && law.is_some() && stick_impulse.is_some_and(|ps| ps <= p),
            stick_impulse,
            tangential_impulse: j,
            s_out,
            heat_sliding,
            heat: heat_sliding + p * (2.0 * u0 - p / m),
        })
    }

    /// The common case, constant mu and a collision: the same formulas with the
    /// reciprocals of m, k and k mu precomputed (multiplications instead of divisions).
    #[inline(always)]
    fn resolve_constant_mu<const THETA: bool>(
        &self,
        s: &CmState,
        mu: f64,
        p: f64,
    ) -> ContactResult {
        let slip = s.slip_with(self.radius_a, self.radius_ratio);
        let s0 = planar_length(slip);
        let (theta, e, p_stick) = if s0 > 0.0 {
            (
                THETA.then(|| slip_angle(slip)),
                slip * (1.0 / s0),
                s0 * self.inv_k_mu,
            )
        } else {
            (None, Vector2::zeros(), 0.0)
        };
        let sticks = self.stick && p_stick <= p;
        let (j, s_out) = if sticks {
            (s0 * self.inv_k, 0.0)
        } else {
            (mu * p, s0 - self.k * mu * p)
        };
        let heat_sliding = 0.5 * j * (s0 + s_out);
        let inv_m = self.inv_m;
        let mut out = *s;
        out.u_cm.x -= p * inv_m;
        out.u_cm.y -= j * inv_m * e.x;
        out.u_cm.z -= j * inv_m * e.y;
        apply_spin_changes(&mut out, e, self.spin_per_impulse, j);
        ContactResult {
            out,
            impulse: p,
            s0,
            theta,
            sticks,
            stick_impulse: p_stick.is_finite().then_some(p_stick),
            tangential_impulse: j,
            s_out,
            heat_sliding,
            heat: heat_sliding + p * (2.0 * s.u_cm.x - p * inv_m),
        }
    }

    /// The error [`Collision::new`] gives for this state (out of line).
    #[cold]
    #[inline(never)]
    fn invalid(&self, s: &CmState) -> Error {
        match Collision::new(self.balls, self.contact, self.effects, *s) {
            Err(e) => e,
            Ok(_) => Error::invalid("incoming.cm", "a non-finite state", "finite components"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::Ball;
    use nalgebra::Vector3;

    /// State number `i` of a varied sweep: approaching and separating, cut angles, spins;
    /// every 50th without slip at all.
    fn sweep_state(i: usize) -> CmState {
        let a = i as f64 * 0.37;
        let mut st = CmState::new(
            Vector3::new(1.5 * a.sin(), 0.5 * (0.7 * a).cos(), 0.1 * a.cos()),
            Vector3::new(5.0 * a.cos(), 30.0 * (1.1 * a).sin(), -7.0 * a.sin()),
            Vector3::new(0.0, 2.0 * a.sin(), 0.0),
        );
        if i % 50 == 0 {
            st.u_cm.y = 0.0;
            st.u_cm.z = 0.0;
            st.omega_a = Vector3::zeros();
            st.omega_b = Vector3::zeros();
        }
        st
    }

    /// The batch kernel's result `r` of collision `c` against ClosedForm::new: a few ulps
    /// of the scales (the kernel multiplies by precomputed reciprocals where ClosedForm
    /// divides); impulse, S(0), theta and the stick flag exactly.
    fn assert_agrees(r: &ContactResult, c: &Collision, i: usize) {
        let cf = ClosedForm::new(c).result;
        let sc = c.scales;
        let near = |a: f64, b: f64, scale: f64| (a - b).abs() <= 8.0 * f64::EPSILON * scale;
        let near3 =
            |a: Vector3<f64>, b: Vector3<f64>, scale: f64| (0..3).all(|k| near(a[k], b[k], scale));
        assert!(near3(r.out.u_cm, cf.out.u_cm, sc.speed), "{i}");
        assert!(near3(r.out.omega_a, cf.out.omega_a, sc.spin), "{i}");
        assert!(near3(r.out.omega_b, cf.out.omega_b, sc.spin), "{i}");
        assert_eq!(r.impulse, c.impulse);
        assert_eq!(r.s0, c.s0);
        assert_eq!(r.theta, c.theta());
        assert_eq!(r.sticks, cf.sticks);
        match (r.stick_impulse, cf.stick_impulse) {
            (Some(a), Some(b)) => assert!(near(a, b, b), "{i}"),
            (a, b) => assert_eq!(a, b, "{i}"),
        }
        assert!(near(
            r.tangential_impulse,
            cf.tangential_impulse,
            sc.impulse
        ));
        assert!(near(r.s_out, cf.s_out, sc.speed));
        assert!(near(r.heat_sliding, cf.heat_sliding, sc.energy));
        assert!(near(r.heat, cf.heat, sc.energy));
    }

    /// The batch kernel gives ClosedForm::new's numbers to a few ulps, over states that
    /// slide through, stick, start without slip and separate, for constant and
    /// speed-dependent friction, with and without the stick rule, and friction off.
    #[test]
    fn batch_kernel_equals_closed_form() {
        let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
        let frictions = [
            Friction::constant(0.06).unwrap(),
            Friction::speed_dependent(9.951e-3, 0.108, 1.088).unwrap(),
            Friction::constant(0.0).unwrap(),
        ];
        let rules = [
            ImpulseRule::restitution(0.9).unwrap(),
            ImpulseRule::restitution(1.0).unwrap(),
        ];
        let effects = [
            Effects::default(),
            Effects {
                stick: false,
                ..Effects::default()
            },
            Effects {
                friction: false,
                ..Effects::default()
            },
        ];
        let mut seen_stick = 0;
        for f in frictions {
            for rule in rules {
                for fx in effects {
                    let contact = Contact {
                        friction: f,
                        impulse: rule,
                    };
                    let batch = ClosedFormBatch::new(ball, contact, fx);
                    for i in 0..400 {
                        let st = sweep_state(i);
                        let c = Collision::new(ball, contact, fx, st).unwrap();
                        let r = batch.resolve(&st).unwrap();
                        assert_agrees(&r, &c, i);
                        seen_stick += usize::from(r.sticks);
                    }
                }
            }
        }
        assert!(seen_stick > 100, "{seen_stick}");
        let batch = ClosedFormBatch::new(
            ball,
            Contact {
                friction: frictions[0],
                impulse: rules[0],
            },
            Effects::default(),
        );
        let bad = CmState::new(
            Vector3::new(1.0, f64::NAN, 0.0),
            Vector3::zeros(),
            Vector3::zeros(),
        );
        let e = batch.resolve(&bad).unwrap_err().to_string();
        assert!(e.contains("incoming.cm.u[1]"), "{e}");
    }
}

//! The tests' one way to build the crate's input, a [`Collision`]: the balls (two identical,
//! or A and B each with its own mass, radius and alpha), friction, the impulse rule, the
//! effects and the incoming centre-of-mass state, each set by a call and checked by the
//! crate's constructors when the collision is built. Only the root re-exports of the
//! crate's public API are used. It builds inputs only: no expected value comes from here.
//!
//! ```ignore
//! let c = CollisionSpec::ball(0.17, 0.028575, 0.4)
//!     .mu(0.06)
//!     .restitution(1.0)
//!     .incoming(CmState::new(u, omega_a, omega_b))
//!     .build();
//! ```
#![allow(dead_code)]

use super::{Balls, Law, Pair, Rule};
use billiard_contact::{
    Ball, BallPair, CmState, Collision, Contact, Effects, Error, Friction, ImpulseRule,
};
use nalgebra::Vector3;

/// One ball: mass (kg), radius (m), I = alpha m r^2.
#[derive(Debug, Clone, Copy)]
struct BallSpec {
    m: f64,
    r: f64,
    alpha: f64,
}

impl BallSpec {
    fn ball(&self) -> Result<Ball, Error> {
        Ball::new(self.m, self.r, self.alpha)
    }
}

#[derive(Debug, Clone, Copy)]
enum FrictionSpec {
    Constant(f64),
    SpeedDependent(f64, f64, f64),
    Given(Friction),
}

#[derive(Debug, Clone, Copy)]
enum ImpulseSpec {
    Restitution(f64),
    Explicit(f64),
    Given(ImpulseRule),
}

/// A collision to build: the balls, then friction, the impulse rule and the incoming state
/// (each required), and the effects (the crate's default unless set).
#[derive(Debug, Clone, Copy)]
pub struct CollisionSpec {
    a: BallSpec,
    /// Ball B when it differs from A; `None`: two identical balls (one `Ball`).
    b: Option<BallSpec>,
    friction: Option<FrictionSpec>,
    impulse: Option<ImpulseSpec>,
    effects: Effects,
    incoming: Option<CmState>,
}

impl CollisionSpec {
    /// Two identical balls: mass m (kg), radius r (m), I = alpha m r^2.
    pub fn ball(m: f64, r: f64, alpha: f64) -> Self {
        CollisionSpec {
            a: BallSpec { m, r, alpha },
            b: None,
            friction: None,
            impulse: None,
            effects: Effects::default(),
            incoming: None,
        }
    }

    /// Balls A and B, each (mass (kg), radius (m), alpha), given as a `BallPair`.
    pub fn balls(a: (f64, f64, f64), b: (f64, f64, f64)) -> Self {
        let mut spec = Self::ball(a.0, a.1, a.2);
        spec.b = Some(BallSpec {
            m: b.0,
            r: b.1,
            alpha: b.2,
        });
        spec
    }

    /// The independent reference's description of a collision of identical balls
    /// (`common::resolve`): its balls, constant mu, rule, the effects friction and stick it
    /// names, and its centre-of-mass pair (n = e_x: U = v_A, the spins as they are).
    pub fn reference(balls: &Balls, law: &Law, pair: &Pair) -> Self {
        assert_eq!(pair.n, Vector3::x(), "centre-of-mass pairs only");
        Self::ball(balls.m, balls.r, balls.alpha)
            .mu(law.mu)
            .rule(law.rule)
            .effects(Effects {
                friction: law.friction,
                stick: law.stick,
                table: false,
            })
            .incoming(CmState::new(pair.va, pair.wa, pair.wb))
    }

    /// Constant friction mu.
    pub fn mu(mut self, mu: f64) -> Self {
        self.friction = Some(FrictionSpec::Constant(mu));
        self
    }

    /// Speed-dependent friction mu(S) = a + b exp(-c S).
    pub fn speed_dependent(mut self, a: f64, b: f64, c: f64) -> Self {
        self.friction = Some(FrictionSpec::SpeedDependent(a, b, c));
        self
    }

    /// Friction already built.
    pub fn friction(mut self, friction: Friction) -> Self {
        self.friction = Some(FrictionSpec::Given(friction));
        self
    }

    /// P = (1 + e) m U(0) (eq 52 for e = 1).
    pub fn restitution(mut self, e: f64) -> Self {
        self.impulse = Some(ImpulseSpec::Restitution(e));
        self
    }

    /// An explicit impulse P (N s), eq 56.
    pub fn explicit(mut self, p: f64) -> Self {
        self.impulse = Some(ImpulseSpec::Explicit(p));
        self
    }

    /// The reference's rule: restitution or explicit impulse.
    pub fn rule(self, rule: Rule) -> Self {
        match rule {
            Rule::Restitution(e) => self.restitution(e),
            Rule::Explicit(p) => self.explicit(p),
        }
    }

    /// An impulse rule already built.
    pub fn impulse(mut self, rule: ImpulseRule) -> Self {
        self.impulse = Some(ImpulseSpec::Given(rule));
        self
    }

    /// The effects (default: `Effects::default()`).
    pub fn effects(mut self, effects: Effects) -> Self {
        self.effects = effects;
        self
    }

    /// The incoming state in the centre-of-mass frame.
    pub fn incoming(mut self, incoming: CmState) -> Self {
        self.incoming = Some(incoming);
        self
    }

    /// The collision, or the first of the crate's refusals (the balls, the impulse rule,
    /// friction, then `Collision::new`'s own checks of the state and the impulse).
    pub fn try_build(&self) -> Result<Collision, Error> {
        let a = self.a.ball()?;
        let b = self.b.map(|b| b.ball()).transpose()?;
        let impulse = match self.impulse.expect("CollisionSpec: no impulse rule") {
            ImpulseSpec::Restitution(e) => ImpulseRule::restitution(e)?,
            ImpulseSpec::Explicit(p) => ImpulseRule::explicit(p)?,
            ImpulseSpec::Given(rule) => rule,
        };
        let friction = match self.friction.expect("CollisionSpec: no friction") {
            FrictionSpec::Constant(mu) => Friction::constant(mu)?,
            FrictionSpec::SpeedDependent(a, b, c) => Friction::speed_dependent(a, b, c)?,
            FrictionSpec::Given(friction) => friction,
        };
        let contact = Contact { friction, impulse };
        let incoming = self.incoming.expect("CollisionSpec: no incoming state");
        match b {
            None => Collision::new(a, contact, self.effects, incoming),
            Some(b) => Collision::new(BallPair::new(a, b), contact, self.effects, incoming),
        }
    }

    /// [`CollisionSpec::try_build`] for a collision the test expects to be valid.
    pub fn build(&self) -> Collision {
        self.try_build().unwrap()
    }
}

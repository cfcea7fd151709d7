//! Ball and contact parameters, validated on construction.

use crate::base::error::Error;
use crate::base::validate::{finite, positive};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Largest `alpha` of a sphere: a thin spherical shell has I = (2/3) m r^2, and no
/// radial mass distribution puts more of the mass farther out.
pub const ALPHA_MAX: f64 = 2.0 / 3.0;

/// Smallest `alpha` accepted: the spin equations scale with 1/alpha, and a subnormal alpha
/// such as 5e-324 makes 1/alpha infinite and the closed form NaN.
pub const ALPHA_MIN: f64 = 1e-12;

/// Smallest `alpha` the stepped contacts with a spin-coupled slip accept (the cushion, and
/// the compliant contacts of a ball against a plane or another ball): their slips change
/// 1/alpha times faster than the ball's velocity (for a compliant contact, the sticking
/// spring carries the spin, whose effective mass is about alpha m, and its period falls like
/// sqrt(alpha)), and the stepping follows them. Against a cushion at 6 m/s with 300 rad/s of
/// spin on every axis an impact took 1 ms at alpha = 0.4, 4 ms at 1e-4, 21 ms at 1e-5 and ran
/// past dop853's 100 000 steps at 1e-6; a magnesium-alloy ball at 573 m/s on an aluminium
/// plane (Kuwabara-Kono, mu 0.09, rtol 1e-11) took 384 steps at 0.4, 8,273 at 1e-4, 183,197
/// at 1e-7 and past 1e6 at 4.6e-10. No billiard ball comes near 1e-4 (a solid ball has 0.4,
/// a shell 2/3): the bound refuses at once what would otherwise end in a solver failure.
pub(crate) const STEPPED_ALPHA_MIN: f64 = 1e-4;

/// Refuses `ball` when its alpha is below [`STEPPED_ALPHA_MIN`], naming `field`; `context`
/// says where ("against a cushion", "in a compliant contact") and `why` what the slip does.
pub(crate) fn check_stepped_alpha(
    field: &str,
    ball: &Ball,
    context: &str,
    why: &str,
) -> Result<(), Error> {
    if ball.alpha() >= STEPPED_ALPHA_MIN {
        return Ok(());
    }
    Err(Error::invalid(
        field,
        ball.alpha(),
        format!(
            "at least {STEPPED_ALPHA_MIN:e} {context}: {why} and the stepping's work grows \
             with it (a solid ball has 0.4)"
        ),
    ))
}

/// Largest friction coefficient accepted (constant mu, and a, b of mu(S)): far beyond any
/// physical value, while the time stepping's intermediate slips and heat stay finite
/// (mu = 1e300 overflows the rk4 state to -inf).
pub const MU_MAX: f64 = 1e6;

/// Moment-of-inertia factor of a solid uniform ball, I = (2/5) m r^2.
pub const ALPHA_SOLID: f64 = 0.4;

/// Two identical balls: mass m, radius r, moment of inertia alpha m r^2; validated on
/// construction ([`Ball::new`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ball {
    mass: f64,
    radius: f64,
    alpha: f64,
}

impl Ball {
    /// A validated ball.
    ///
    /// `mass` (kg) and `radius` (m) must be finite and positive; `alpha` in
    /// [1e-12, 2/3] (0.4 for a solid ball, [`ALPHA_SOLID`]; see [`ALPHA_MIN`]).
    ///
    /// ```
    /// let ball = billiard_contact::Ball::new(0.17, 0.028575, 0.4).unwrap();
    /// assert_eq!(ball.inertia(), 0.4 * 0.17 * 0.028575 * 0.028575);
    /// assert!(billiard_contact::Ball::new(0.17, 0.028575, 0.7).is_err());
    /// ```
    pub fn new(mass: f64, radius: f64, alpha: f64) -> Result<Self, Error> {
        Ball::in_section("balls", mass, radius, alpha)
    }

    /// [`Ball::new`] with errors naming the fields of the scene section `section`
    /// (`balls`, `balls.a`, `balls.b`).
    pub fn in_section(section: &str, mass: f64, radius: f64, alpha: f64) -> Result<Self, Error> {
        positive(&format!("{section}.mass"), mass, "kg")?;
        positive(&format!("{section}.radius"), radius, "m")?;
        finite(&format!("{section}.alpha"), alpha)?;
        if !(alpha > 0.0 && alpha <= ALPHA_MAX) {
            return Err(Error::invalid(
                format!("{section}.alpha"),
                alpha,
                "in (0, 2/3]: I = alpha m r^2, and a sphere cannot exceed the thin shell's 2/3",
            ));
        }
        if alpha < ALPHA_MIN {
            return Err(Error::invalid(
                format!("{section}.alpha"),
                alpha,
                format!(
                    "at least {ALPHA_MIN:e}: the spins change like 1/alpha, and a smaller \
                     alpha (all the mass at the centre) overflows them"
                ),
            ));
        }
        // The equations divide by m and by alpha m r (eqs 25-33): both, and I, must be
        // normal numbers (mass = 5e-324 or radius = 1e308 would give NaN).
        let inertia = alpha * mass * radius * radius;
        if !(inertia.is_normal()
            && (1.0 / mass).is_normal()
            && (1.0 / (alpha * mass * radius)).is_normal()
            && (alpha * mass * radius * 1e6).is_finite())
        {
            return Err(Error::invalid(
                section,
                format!("mass = {mass} kg, radius = {radius} m, alpha = {alpha}"),
                "values whose m, 1/m, I = alpha m r^2 and 1/(alpha m r) are normal double-precision \
                 numbers (SI units)",
            ));
        }
        Ok(Ball {
            mass,
            radius,
            alpha,
        })
    }

    /// Mass m (kg), > 0.
    #[inline]
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Radius r (m), > 0.
    #[inline]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Moment-of-inertia factor alpha (dimensionless), in [1e-12, 2/3].
    #[inline]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Moment of inertia alpha m r^2 (kg m^2).
    pub fn inertia(&self) -> f64 {
        self.alpha * self.mass * self.radius * self.radius
    }

    /// The factor k = 2 (1 + 1/alpha) / m (1/kg) of eq 22: dS/dt = -mu f k.
    #[inline]
    pub fn slip_rate_per_friction_impulse(&self) -> f64 {
        BallPair::identical(*self).slip_rate_per_friction_impulse()
    }
}

/// The two balls of a collision: A (at -r_A along the line of centres from the contact
/// point) and B (at +r_B), each with its own mass, radius and alpha
/// (docs/unequal-balls.md).
///
/// Every coefficient of the contact is computed here, once, so that for identical balls
/// (A == B) it equals the paper's value bit for bit: the ratios m_A/m_B, r_B/r_A, I_B/I_A
/// are then exactly 1 and the weights m_A/(m_A + m_B) exactly 1/2.
///
/// ```
/// use billiard_contact::{Ball, BallPair};
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// let same = BallPair::identical(ball);
/// assert_eq!(same.pair_mass(), 0.17);
/// assert_eq!(same.slip_rate_per_friction_impulse(), 2.0 * (1.0 + 1.0 / 0.4) / 0.17);
/// let cue = Ball::new(0.184, 0.030163, 0.4).unwrap();
/// let pair = BallPair::new(cue, ball);
/// let reduced = 0.184 * 0.17 / (0.184 + 0.17);
/// assert!((pair.reduced_mass() - reduced).abs() < 1e-16);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallPair {
    /// Ball A.
    pub a: Ball,
    /// Ball B.
    pub b: Ball,
}

impl From<Ball> for BallPair {
    fn from(ball: Ball) -> Self {
        BallPair::identical(ball)
    }
}

impl BallPair {
    /// Two balls A and B.
    pub fn new(a: Ball, b: Ball) -> Self {
        BallPair { a, b }
    }

    /// Two identical balls (the paper's case).
    pub fn identical(ball: Ball) -> Self {
        BallPair { a: ball, b: ball }
    }

    /// True when A and B have the same mass, radius and alpha.
    pub fn is_identical(&self) -> bool {
        self.a == self.b
    }

    /// The pair mass M = 2 m* = 2 m_A m_B / (m_A + m_B) (kg), computed as
    /// m_A 2 / (1 + m_A/m_B): exactly m for identical balls. The centre-of-mass state's u
    /// (half the relative velocity) changes by -P/M under the normal impulse P, and its
    /// tangential part by -J/M under the tangential impulse J.
    #[inline]
    pub fn pair_mass(&self) -> f64 {
        self.a.mass * (2.0 / (1.0 + self.a.mass / self.b.mass))
    }

    /// The reduced mass m* = m_A m_B / (m_A + m_B) (kg), M / 2.
    #[inline]
    pub fn reduced_mass(&self) -> f64 {
        0.5 * self.pair_mass()
    }

    /// K = 1/m_A + 1/m_B + r_A^2/I_A + r_B^2/I_B (1/kg): the slip falls by K J under a
    /// tangential impulse J. Computed as (1 + 1/alpha_A)/m_A + (1 + 1/alpha_B)/m_B, which is
    /// the paper's k = 2 (1 + 1/alpha)/m (eq 22) bit for bit for identical balls.
    #[inline]
    pub fn slip_rate_per_friction_impulse(&self) -> f64 {
        // For A == B this is x/m + x/m = 2 (x/m), the correctly rounded 2 x / m of eq 22.
        (1.0 + 1.0 / self.a.alpha) / self.a.mass + (1.0 + 1.0 / self.b.alpha) / self.b.mass
    }

    /// Spin change of A per unit tangential impulse, r_A / I_A = 1 / (alpha_A m_A r_A).
    #[inline]
    pub fn spin_per_impulse_a(&self) -> f64 {
        1.0 / (self.a.alpha * self.a.mass * self.a.radius)
    }

    /// Spin change of B per unit tangential impulse, r_B / I_B = 1 / (alpha_B m_B r_B).
    #[inline]
    pub fn spin_per_impulse_b(&self) -> f64 {
        1.0 / (self.b.alpha * self.b.mass * self.b.radius)
    }

    /// M / (alpha_A m_A) and M / (alpha_B m_B): the rate at which r_A Omega^A and
    /// r_B Omega^B change per unit J / M; both 1/alpha for identical balls (the time
    /// stepping's scaled spin rates).
    #[inline]
    pub fn scaled_inverse_alphas(&self) -> [f64; 2] {
        let m = self.pair_mass();
        [
            1.0 / self.a.alpha * (m / self.a.mass),
            1.0 / self.b.alpha * (m / self.b.mass),
        ]
    }

    /// The radii [r_A, r_B] (m).
    #[inline]
    pub fn radii(&self) -> [f64; 2] {
        [self.a.radius, self.b.radius]
    }

    /// r_B / r_A (1 for identical balls).
    #[inline]
    pub fn radius_ratio(&self) -> f64 {
        self.b.radius / self.a.radius
    }

    /// The weights m_A / (m_A + m_B) and m_B / (m_A + m_B) (both 1/2 for identical balls):
    /// the centre-of-mass velocity is w_A v_A + w_B v_B, and A moves with 2 w_B u, B with
    /// -2 w_A u in the centre-of-mass frame.
    #[inline]
    pub fn mass_weights(&self) -> [f64; 2] {
        let total = self.a.mass + self.b.mass;
        [self.a.mass / total, self.b.mass / total]
    }

    /// The balls' masses and radii, for error messages.
    pub(crate) fn describe(&self) -> String {
        if self.is_identical() {
            format!("m = {} kg, r = {} m", self.a.mass, self.a.radius)
        } else {
            format!(
                "m_A = {} kg, r_A = {} m, m_B = {} kg, r_B = {} m",
                self.a.mass, self.a.radius, self.b.mass, self.b.radius
            )
        }
    }
}

/// Coefficient of sliding friction between the balls, validated on construction
/// ([`Friction::constant`], [`Friction::speed_dependent`]); [`Friction::law`] gives the law
/// and its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Friction {
    law: FrictionLaw,
}

/// The law of a [`Friction`], with its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum FrictionLaw {
    /// Coulomb friction with a constant coefficient mu >= 0.
    Constant(f64),
    /// mu(S) = a + b exp(-c S), S the sliding speed in m/s (the fit used in the
    /// billiards literature for ball-ball friction), evaluated as `evaluate` says.
    SpeedDependent {
        /// Speed-independent part a >= 0.
        a: f64,
        /// Amplitude b >= 0 of the speed-dependent part.
        b: f64,
        /// Decay rate c >= 0 (s/m).
        c: f64,
        /// At every instant of the contact, or once at the initial slip S(0).
        evaluate: Evaluate,
    },
}

/// When a speed-dependent mu(S) is evaluated (`contact.mu.evaluate` in scene files,
/// docs/model.md#speed-dependent-friction).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Evaluate {
    /// mu(S) at the current sliding speed S at every instant, as S falls (the default).
    #[default]
    AlongContact,
    /// mu(S(0)) once, at the initial sliding speed, held through the whole contact (the
    /// convention of Alciatore's throw analysis and of pooltool).
    Initial,
}

impl Evaluate {
    /// Every convention, in the order of their names in the help and errors.
    pub const ALL: [Evaluate; 2] = [Evaluate::AlongContact, Evaluate::Initial];

    /// The name in scene files and reports.
    pub fn name(&self) -> &'static str {
        match self {
            Evaluate::AlongContact => "along-contact",
            Evaluate::Initial => "initial",
        }
    }
}

impl Friction {
    /// Constant Coulomb friction, validated (finite, in [0, 1e6]).
    pub fn constant(mu: f64) -> Result<Self, Error> {
        finite("contact.mu", mu)?;
        if mu < 0.0 {
            return Err(Error::invalid("contact.mu", mu, "mu >= 0"));
        }
        if mu > MU_MAX {
            return Err(Error::invalid(
                "contact.mu",
                mu,
                format!("mu <= {MU_MAX:e} (ball-ball friction is below 1)"),
            ));
        }
        Ok(Friction {
            law: FrictionLaw::Constant(mu),
        })
    }

    /// Speed-dependent friction mu(S) = a + b exp(-c S), validated (all finite, >= 0; a
    /// and b <= 1e6).
    pub fn speed_dependent(a: f64, b: f64, c: f64) -> Result<Self, Error> {
        for (name, v) in [
            ("contact.mu.a", a),
            ("contact.mu.b", b),
            ("contact.mu.c", c),
        ] {
            finite(name, v)?;
            if v < 0.0 {
                return Err(Error::invalid(name, v, ">= 0"));
            }
        }
        for (name, v) in [("contact.mu.a", a), ("contact.mu.b", b)] {
            if v > MU_MAX {
                return Err(Error::invalid(name, v, format!("<= {MU_MAX:e}")));
            }
        }
        Ok(Friction {
            law: FrictionLaw::SpeedDependent {
                a,
                b,
                c,
                evaluate: Evaluate::AlongContact,
            },
        })
    }

    /// The law and its parameters.
    #[inline]
    pub fn law(&self) -> FrictionLaw {
        self.law
    }

    /// The same law evaluated as `evaluate` says (constant friction is unchanged).
    ///
    /// ```
    /// use billiard_contact::{Evaluate, Friction};
    /// let f = Friction::speed_dependent(9.951e-3, 0.108, 1.088).unwrap();
    /// let held = f.evaluated(Evaluate::Initial);
    /// assert_eq!(held.acting_from(2.0), Friction::constant(f.mu(2.0)).unwrap());
    /// assert_eq!(f.acting_from(2.0), f);
    /// ```
    pub fn evaluated(self, evaluate: Evaluate) -> Self {
        match self.law {
            FrictionLaw::SpeedDependent { a, b, c, .. } => Friction {
                law: FrictionLaw::SpeedDependent { a, b, c, evaluate },
            },
            FrictionLaw::Constant(_) => self,
        }
    }

    /// The law that acts through a contact whose sliding starts at speed `s0` (m/s): for a
    /// speed-dependent mu evaluated at the initial slip, the constant mu(S(0)); otherwise
    /// this law itself. Every method (closed form, batch kernel, integrators) takes its
    /// friction from here.
    #[inline]
    pub fn acting_from(self, s0: f64) -> Self {
        match self.law {
            // mu(S(0)) of a valid law is finite and >= 0.
            FrictionLaw::SpeedDependent {
                evaluate: Evaluate::Initial,
                ..
            } => Friction {
                law: FrictionLaw::Constant(self.mu(s0)),
            },
            _ => self,
        }
    }

    /// The coefficient at sliding speed `s` (m/s).
    #[inline]
    pub fn mu(&self, s: f64) -> f64 {
        match self.law {
            FrictionLaw::Constant(mu) => mu,
            FrictionLaw::SpeedDependent { a, b, c, .. } => a + b * (-c * s).exp(),
        }
    }

    /// True when no friction can act at any speed.
    pub fn is_zero(&self) -> bool {
        match self.law {
            FrictionLaw::Constant(mu) => mu == 0.0,
            FrictionLaw::SpeedDependent { a, b, .. } => a == 0.0 && b == 0.0,
        }
    }
}

/// How the impulse P of the collision is set, validated on construction
/// ([`ImpulseRule::restitution`], [`ImpulseRule::explicit`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct ImpulseRule {
    rule: Rule,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
enum Rule {
    /// P = (1 + e) m U(0), e in [0, 1] (eq 52 for e = 1, the family of eq 56 below).
    Restitution(f64),
    /// An explicit impulse P (N s) with m U(0) <= P <= 2 m U(0) (eq 56).
    Explicit(f64),
}

impl ImpulseRule {
    /// Restitution 1, P = 2 m U(0) (eq 52): only sliding friction dissipates. The scene's
    /// default.
    pub const ELASTIC: ImpulseRule = ImpulseRule {
        rule: Rule::Restitution(1.0),
    };

    /// The restitution e of a restitution rule; `None` for an explicit impulse.
    pub fn restitution_coefficient(&self) -> Option<f64> {
        match self.rule {
            Rule::Restitution(e) => Some(e),
            Rule::Explicit(_) => None,
        }
    }

    /// The impulse P (N s) of an explicit rule; `None` for a restitution rule.
    pub fn explicit_impulse(&self) -> Option<f64> {
        match self.rule {
            Rule::Explicit(p) => Some(p),
            Rule::Restitution(_) => None,
        }
    }

    /// A validated restitution rule (e finite, in [0, 1]).
    pub fn restitution(e: f64) -> Result<Self, Error> {
        finite("contact.restitution", e)?;
        if !(0.0..=1.0).contains(&e) {
            return Err(Error::invalid(
                "contact.restitution",
                e,
                "in [0, 1] (0: perfectly inelastic, 1: only sliding friction dissipates)",
            ));
        }
        Ok(ImpulseRule {
            rule: Rule::Restitution(e),
        })
    }

    /// A validated explicit impulse (finite, > 0); its range against m U(0) is
    /// checked by [`ImpulseRule::impulse`].
    pub fn explicit(p: f64) -> Result<Self, Error> {
        positive("contact.impulse", p, "N s")?;
        Ok(ImpulseRule {
            rule: Rule::Explicit(p),
        })
    }

    /// The rule of a restitution `e` or an explicit impulse `p` (N s), validated; `None`
    /// when neither is given. Both is an error naming `{prefix}restitution` and
    /// `{prefix}impulse` (the keys as the input spells them: `contact.` in a scene, none
    /// in a batch row).
    ///
    /// ```
    /// use billiard_contact::ImpulseRule;
    /// assert_eq!(ImpulseRule::from_either("", Some(0.9), None).unwrap(),
    ///            Some(ImpulseRule::restitution(0.9).unwrap()));
    /// assert_eq!(ImpulseRule::from_either("", None, None).unwrap(), None);
    /// let e = ImpulseRule::from_either("contact.", Some(1.0), Some(0.1)).unwrap_err();
    /// assert_eq!(e.to_string(), "contact.restitution = 1 together with contact.impulse = 0.1: \
    ///                            one of restitution or impulse, not both");
    /// ```
    pub fn from_either(
        prefix: &str,
        restitution: Option<f64>,
        impulse: Option<f64>,
    ) -> Result<Option<Self>, Error> {
        match (restitution, impulse) {
            (Some(e), None) => ImpulseRule::restitution(e).map(Some),
            (None, Some(p)) => ImpulseRule::explicit(p).map(Some),
            (None, None) => Ok(None),
            (Some(e), Some(p)) => Err(Error::invalid(
                format!("{prefix}restitution"),
                format!("{e} together with {prefix}impulse = {p}"),
                "one of restitution or impulse, not both",
            )),
        }
    }

    /// The impulse P (N s) for normal approach speed `u0` (m/s) and mass `m` (kg): the
    /// ball mass for identical balls, the pair mass M = 2 m* ([`BallPair::pair_mass`]) in
    /// general, where u0 is half the relative approach speed and P = (1 + e) m* v_n.
    ///
    /// Returns 0 for balls that do not approach (u0 <= 0) under a restitution rule;
    /// an explicit impulse requires u0 > 0 and m u0 <= P <= 2 m u0 (eq 56), with a
    /// relative slack of 1e-12 for round-off in the caller's arithmetic.
    #[inline]
    pub fn impulse(&self, mass: f64, u0: f64) -> Result<f64, Error> {
        match self.rule {
            Rule::Restitution(e) => Ok(if u0 > 0.0 { (1.0 + e) * mass * u0 } else { 0.0 }),
            Rule::Explicit(p) => {
                let (lo, hi) = (mass * u0, 2.0 * mass * u0);
                let slack = 1e-12 * hi;
                if u0 <= 0.0 || p < lo - slack || p > hi + slack {
                    return Err(explicit_impulse_error(p, mass, u0));
                }
                Ok(p)
            }
        }
    }
}

/// Why an explicit impulse does not fit the approach speed (out of line: the common path
/// of [`ImpulseRule::impulse`] is a multiplication).
#[cold]
#[inline(never)]
fn explicit_impulse_error(p: f64, mass: f64, u0: f64) -> Error {
    if u0 <= 0.0 {
        return Error::invalid(
            "contact.impulse",
            p,
            format!("no impulse: the balls do not approach (normal speed U(0) = {u0} m/s <= 0)"),
        );
    }
    let (lo, hi) = (mass * u0, 2.0 * mass * u0);
    Error::invalid(
        "contact.impulse",
        p,
        format!(
            "between m U(0) = {lo} and 2 m U(0) = {hi} N s (eq 56: below, the balls pass \
             through each other; above, the collision creates energy)"
        ),
    )
}

/// Contact parameters: friction and the impulse rule.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contact {
    /// Ball-ball sliding friction.
    pub friction: Friction,
    /// How the impulse P is fixed.
    pub impulse: ImpulseRule,
}

/// Kinetic energy (J) of `ball` at velocity `v` (m/s) and spin `w` (rad/s).
pub(crate) fn kinetic_energy(ball: &Ball, v: &Vector3<f64>, w: &Vector3<f64>) -> f64 {
    0.5 * ball.mass() * v.norm_squared() + 0.5 * ball.inertia() * w.norm_squared()
}

/// A ball coming into a contact: the ball, its velocity and spin, and their fields' names.
pub(crate) type IncomingBall<'a> = (
    &'a Ball,
    &'a Vector3<f64>,
    &'a Vector3<f64>,
    &'a str,
    &'a str,
);

/// The incoming kinetic energy (J) of the balls `(ball, velocity, spin, velocity's field,
/// spin's field)`, refused naming the first term that is not a finite number: the outcome
/// reports it, and a ball of 1e282 kg spinning at 1e34 rad/s gave infinity (found by
/// fuzzing).
pub(crate) fn energy_in(balls: &[IncomingBall<'_>]) -> Result<f64, Error> {
    let refused = |field: &str, x: &Vector3<f64>, e: f64| {
        Error::invalid(
            field,
            format!("[{}, {}, {}] (a kinetic energy of {e:e} J)", x.x, x.y, x.z),
            "velocities and spins whose kinetic energy is a finite number of joules",
        )
    };
    let mut total = 0.0;
    for &(ball, v, w, v_field, w_field) in balls {
        total += kinetic_energy(ball, v, w);
        if !total.is_finite() {
            // The spin's term when it alone overflows, else the velocity's.
            let e_w = 0.5 * ball.inertia() * w.norm_squared();
            let e_v = 0.5 * ball.mass() * v.norm_squared();
            return Err(if e_v.is_finite() && !e_w.is_finite() {
                refused(w_field, w, e_w)
            } else {
                refused(v_field, v, e_v)
            });
        }
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The last of the constructor's checks: alpha m r times 1e6 must stay finite. For
    /// m = 1e303 kg, r = 1 m, alpha = 0.4 the others pass (I = 4e302, 1/m = 1e-303 and
    /// 1/(alpha m r) = 2.5e-303 are normal numbers) and alpha m r 1e6 = 4e308 overflows, so
    /// the ball is refused; at m = 1e296 kg it is 4e301 and the ball is accepted.
    #[test]
    fn refuses_alpha_m_r_without_the_headroom() {
        let e = Ball::new(1e303, 1.0, 0.4).unwrap_err().to_string();
        assert!(
            e.contains("balls") && e.contains("normal double-precision"),
            "{e}"
        );
        assert!(Ball::new(1e296, 1.0, 0.4).is_ok());
    }

    /// 1/m must be a normal number: m = 5e307 kg (1/m = 2e-308, subnormal), r = 1e-6 m,
    /// alpha = 0.4 give I = 2e295, 1/(alpha m r) = 5e-302 and alpha m r 1e6 = 2e307, all
    /// normal, so only 1/m refuses the ball; at m = 4e307 kg (1/m = 2.5e-308, normal) it is
    /// accepted.
    #[test]
    fn refuses_a_subnormal_inverse_mass() {
        let e = Ball::new(5e307, 1e-6, 0.4).unwrap_err().to_string();
        assert!(e.contains("1/m"), "{e}");
        assert!(Ball::new(4e307, 1e-6, 0.4).is_ok());
        // Plain values pass whatever alpha m r is: exactly 1 and 1/2 here.
        assert!(Ball::new(2.0, 1.0, 0.5).is_ok());
        assert!(Ball::new(1.0, 1.0, 0.5).is_ok());
    }

    /// The moment of inertia I = alpha m r^2 must be a normal number: m = 2.5e-291 kg,
    /// r = 1e-9 m, alpha = 0.4 give I = 1e-309 (subnormal) while 1/m = 4e290 and
    /// 1/(alpha m r) = 1e300 are normal, so only I refuses the ball; at r = 1e-6 m,
    /// I = 1e-303 and the ball is accepted.
    #[test]
    fn refuses_a_subnormal_moment_of_inertia() {
        let e = Ball::new(2.5e-291, 1e-9, 0.4).unwrap_err().to_string();
        assert!(e.contains("I = alpha m r^2"), "{e}");
        assert!(Ball::new(2.5e-291, 1e-6, 0.4).is_ok());
    }

    /// 1/(alpha m r) must be a normal number, alpha m r itself need not be: m = 1e-308 kg
    /// (1/m = 1e308), r = 3 m, alpha = 0.5 give alpha m r = 1.5e-308 (below the least
    /// normal 2.2e-308) with 1/(alpha m r) = 6.7e307 and I = 4.5e-308 normal, and the ball
    /// is accepted; at r = 20 m, alpha = 0.01, alpha m r = 2e-309 and its inverse
    /// overflows, while I = 4e-308 and 1/m stay normal, so only 1/(alpha m r) refuses it.
    #[test]
    fn inverse_of_alpha_m_r_must_be_normal_not_alpha_m_r() {
        assert!(Ball::new(1e-308, 3.0, 0.5).is_ok());
        let e = Ball::new(1e-308, 20.0, 0.01).unwrap_err().to_string();
        assert!(e.contains("1/(alpha m r)"), "{e}");
        // At the other end: m = 1e299 kg, r = 1e4 m, alpha = 0.1 give m r = 1e303 (1e6 m r
        // overflows) but alpha m r = 1e302, I = 1e306 and their inverses normal: accepted.
        assert!(Ball::new(1e299, 1e4, 0.1).is_ok());
    }

    /// Friction's accepted range is closed at both ends: mu = 0 and mu = 1e6 are accepted,
    /// the next double above 1e6 is refused (for a constant mu and for a and b of the
    /// speed-dependent law, whose c has no upper limit).
    #[test]
    fn friction_limits_are_inclusive() {
        let above = f64::from_bits(MU_MAX.to_bits() + 1);
        assert!(Friction::constant(0.0).is_ok());
        assert!(Friction::constant(1e6).is_ok());
        let e = Friction::constant(above).unwrap_err().to_string();
        assert!(e.contains("contact.mu") && e.contains("mu <= 1e6"), "{e}");
        assert!(Friction::speed_dependent(1e6, 1e6, 0.0).is_ok());
        assert!(Friction::speed_dependent(0.0, 0.0, 1e300).is_ok());
        for (a, b, name) in [(above, 0.0, "contact.mu.a"), (0.0, above, "contact.mu.b")] {
            let e = Friction::speed_dependent(a, b, 1.0)
                .unwrap_err()
                .to_string();
            assert!(e.contains(name) && e.contains("<= 1e6"), "{e}");
        }
    }

    /// Each rule answers for its own kind and `None` for the other.
    #[test]
    fn rule_accessors() {
        let e = ImpulseRule::restitution(0.93).unwrap();
        assert_eq!(e.restitution_coefficient(), Some(0.93));
        assert_eq!(e.explicit_impulse(), None);
        let p = ImpulseRule::explicit(0.3).unwrap();
        assert_eq!(p.restitution_coefficient(), None);
        assert_eq!(p.explicit_impulse(), Some(0.3));
        assert_eq!(ImpulseRule::ELASTIC.restitution_coefficient(), Some(1.0));
    }

    /// The reduced mass m_A m_B / (m_A + m_B) and the pair mass M twice it: balls of 0.17 kg
    /// and 0.16 kg give 0.0272 / 0.33 = 0.0824242... kg and 0.1648484... kg; identical balls
    /// of m, m / 2 and exactly m.
    #[test]
    fn reduced_and_pair_mass() {
        let pair = BallPair::new(
            Ball::new(0.17, 0.028575, 0.4).unwrap(),
            Ball::new(0.16, 0.028, 0.4).unwrap(),
        );
        let m_star = 0.17 * 0.16 / 0.33;
        assert!((pair.reduced_mass() - m_star).abs() <= 1e-15 * m_star);
        assert!((pair.pair_mass() - 2.0 * m_star).abs() <= 1e-15 * m_star);
        let same = BallPair::identical(Ball::new(0.17, 0.028575, 0.4).unwrap());
        assert_eq!(same.pair_mass(), 0.17);
        assert_eq!(same.reduced_mass(), 0.085);
    }

    /// An explicit impulse is held to eq 56, m u0 <= P <= 2 m u0, with a slack of 1e-12 of
    /// the upper bound 2 m u0 (relative: the same at every scale), its edges included. At
    /// m u0 = 100 N s the slack is 2e-10 N s; at m u0 = 0.005 N s, 1e-14 N s.
    #[test]
    fn explicit_impulse_slack_is_relative() {
        for (m, u0) in [(100.0, 1.0), (0.01, 0.5)] {
            let (lo, hi) = (m * u0, 2.0 * m * u0);
            let slack = 1e-12 * hi;
            let at = |p: f64| ImpulseRule::explicit(p).unwrap().impulse(m, u0);
            // The slack's edges belong to it.
            for p in [lo - slack, lo - 0.5 * slack, hi + 0.5 * slack, hi + slack] {
                assert_eq!(at(p).unwrap(), p, "m u0 = {lo}: {p} inside the slack");
            }
            for p in [lo - 2.0 * slack, hi + 2.0 * slack] {
                assert!(at(p).is_err(), "m u0 = {lo}: {p} outside the slack");
            }
        }
    }

    /// Eq 22's k = 2 (1 + 1/alpha) / m for one ball: a pool ball (m = 0.17 kg, alpha = 2/5)
    /// has k = 2 (1 + 5/2) / 0.17 = 7 / 0.17 = 41.176... 1/kg; a thin shell (alpha = 2/3)
    /// 2 (1 + 3/2) / 0.17 = 5 / 0.17. Written out here, not through `BallPair`.
    #[test]
    fn slip_rate_is_eq_22s_k() {
        for (m, alpha, k) in [(0.17, 0.4, 7.0 / 0.17), (0.17, 2.0 / 3.0, 5.0 / 0.17)] {
            let got = Ball::new(m, 0.028575, alpha)
                .unwrap()
                .slip_rate_per_friction_impulse();
            assert!((got - k).abs() <= 4.0 * f64::EPSILON * k, "{got} vs {k}");
        }
    }
}

//! A sphere against a plane, by every method (docs/plane.md).
//!
//! A ball of mass m, radius r and alpha against a plane obeys the equations of two identical
//! balls of mass 2m (radius r, alpha) seen in their centre-of-mass frame, with
//!
//! ```text
//! e_x = -n,   U = v / 2,   Omega^A = Omega^B = w / 2       (components in the basis e)
//! ```
//!
//! Under the pair's impulse dp the ball's velocity 2U changes by 2 (-dp e_x - mu dp e)/(2m),
//! the ball's own law; the spin sum Omega^A + Omega^B changes by twice r e_x x (-mu dp e)/I_2m
//! with I_2m = 2 I, which is the ball's dw; the pair's slip 2U_t + r Omega x e_x is the
//! ball's slip v_t - r (w x n); the pair's P = (1 + e) 2m U(0) is the ball's
//! (1 + e) m |v.n|; the pair's reduced mass (2m)/2 = m is the ball's own mass, which a
//! contact law's compression obeys against a plane; and the kinetic energies agree, so the
//! heat does. So the closed form (eqs 24-35 with the stick rule, its speed-dependent
//! friction), every profile, contact law, method, trace and check of the pair apply to the
//! plane unchanged; the sphere-plane closed form of `closed_form::plane`, written directly
//! from the ball's equations, is the independent reference the tests compare against.

use crate::base::error::Error;
use crate::base::settings::{Sampling, SolverSettings};
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::effects::Effects;
use crate::model::params::{Ball, Contact};
use crate::model::state::CmState;
use crate::model::trace::TraceSink;
use crate::profile::force::ForceProfile;
use crate::solve::law_outcome::solve_law;
use crate::solve::outcome::{solve, Outcome};
use nalgebra::{Matrix3, Vector3};

/// A sphere meeting a plane: the ball, friction and impulse rule, the plane's unit normal,
/// the incoming velocity and spin, validated, with its equivalent pair (module docs).
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::profile::HalfSine;
/// use billiard_contact::*;
///
/// // A solid ball without spin hits the table at 1 m/s, 30 degrees from the vertical.
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let contact = Contact { friction: Friction::constant(0.2)?, impulse: ImpulseRule::restitution(0.5)? };
/// let v = Vector3::new(0.5, 0.0, -(0.75f64).sqrt());
/// let hit = PlaneCollision::new(ball, contact, Vector3::z(), v, Vector3::zeros())?;
/// let out = solve_plane(&hit, &HalfSine::new(1e-4)?, &SolverSettings::default(), None)?;
/// // tan 30 = 0.577 < (1 + 1/alpha) mu (1 + e) = 3.5 (0.2) (1.5) = 1.05: the slip stops, and
/// // the ball keeps 1/(1 + alpha) = 5/7 of its tangential velocity; v_z' = e |v_z|.
/// assert!((out.velocity.x - 0.5 * 5.0 / 7.0).abs() < 1e-10);
/// assert!((out.velocity.z - 0.5 * (0.75f64).sqrt()).abs() < 1e-10);
/// assert!(out.outcome.result.sticks);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneCollision {
    /// The ball.
    pub ball: Ball,
    /// Friction between ball and plane, and the impulse rule.
    pub contact: Contact,
    /// Unit normal of the plane, out of it towards the ball.
    pub normal: Vector3<f64>,
    /// Incoming velocity of the ball's centre (m/s).
    pub velocity: Vector3<f64>,
    /// Incoming spin (rad/s).
    pub spin: Vector3<f64>,
    /// Columns e_x = -n, e_y, e_z: the equivalent pair's axes.
    basis: Matrix3<f64>,
    /// The equivalent pair's collision.
    pair: Collision,
}

impl PlaneCollision {
    /// The ball with `velocity` and `spin` meeting the plane of normal `normal` (any
    /// non-zero length; made unit). Friction and impulse rule as for two balls; `effects`
    /// friction and stick apply, the table phase does not.
    ///
    /// Errors: a normal that is zero or not finite (field `plane.normal`), a velocity or spin
    /// that is not finite, or scales that overflow (as for two balls, field `incoming`).
    pub fn new(
        ball: Ball,
        contact: Contact,
        normal: Vector3<f64>,
        velocity: Vector3<f64>,
        spin: Vector3<f64>,
    ) -> Result<Self, Error> {
        PlaneCollision::with_effects(ball, contact, Effects::default(), normal, velocity, spin)
    }

    /// [`PlaneCollision::new`] with the effects `effects` (friction, stick; `table` must be
    /// off: the table phase is for two balls).
    pub fn with_effects(
        ball: Ball,
        contact: Contact,
        effects: Effects,
        normal: Vector3<f64>,
        velocity: Vector3<f64>,
        spin: Vector3<f64>,
    ) -> Result<Self, Error> {
        let length = normal.norm();
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid(
                "plane.normal",
                format!("[{}, {}, {}]", normal.x, normal.y, normal.z),
                "a non-zero, finite direction (out of the plane, towards the ball)",
            ));
        }
        if effects.table {
            return Err(Error::invalid(
                "effects.table",
                "true",
                "false for a plane (the table phase follows two balls)",
            ));
        }
        for (field, x) in [
            ("incoming.plane.velocity", velocity),
            ("incoming.plane.spin", spin),
        ] {
            // The length too: the equivalent pair's state is the vector turned into the
            // plane's axes, whose components overflow where |x| does (1.8e308 and -1.5e308
            // turned gave an infinite U, refused under the pair's own field name).
            if !(x.iter().all(|c| c.is_finite()) && x.norm().is_finite()) {
                return Err(Error::invalid(
                    field,
                    format!("[{}, {}, {}]", x.x, x.y, x.z),
                    "finite numbers with a finite length",
                ));
            }
        }
        let n = normal / length;
        let basis = basis_along(-n);
        let twin = Ball::new(2.0 * ball.mass(), ball.radius(), ball.alpha())?;
        let incoming = state_in(&basis, &velocity, &spin);
        let pair = Collision::new(twin, contact, effects, incoming)?;
        Ok(PlaneCollision {
            ball,
            contact,
            normal: n,
            velocity,
            spin,
            basis,
            pair,
        })
    }

    /// The equivalent pair's collision (module docs): what the solvers run.
    pub fn equivalent(&self) -> &Collision {
        &self.pair
    }

    /// The ball's velocity (m/s) in a state of the equivalent pair: 2 U in the lab axes.
    pub fn velocity_of(&self, s: &CmState) -> Vector3<f64> {
        self.basis * s.u_cm * 2.0
    }

    /// The ball's spin (rad/s) in a state of the equivalent pair: Omega^A + Omega^B in the
    /// lab axes.
    pub fn spin_of(&self, s: &CmState) -> Vector3<f64> {
        self.basis * s.omega_sum()
    }

    /// The normal velocity v.n (m/s) of the incoming ball: negative when it approaches.
    pub fn normal_speed(&self) -> f64 {
        self.velocity.dot(&self.normal)
    }

    fn outcome(&self, outcome: Outcome) -> PlaneOutcome {
        PlaneOutcome {
            velocity: self.velocity_of(&outcome.result.out),
            spin: self.spin_of(&outcome.result.out),
            outcome,
        }
    }
}

/// The equivalent pair's state (module docs) of a ball with `velocity` and `spin` against a
/// plane of unit normal `normal`.
pub(crate) fn equivalent_state(
    normal: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> CmState {
    state_in(&basis_along(-normal), velocity, spin)
}

/// U = v/2, Omega^A = Omega^B = w/2 in the axes `basis`.
fn state_in(basis: &Matrix3<f64>, velocity: &Vector3<f64>, spin: &Vector3<f64>) -> CmState {
    let t = basis.transpose();
    let half_w = t * spin * 0.5;
    CmState::new(t * velocity * 0.5, half_w, half_w)
}

/// A right-handed orthonormal basis with first axis `x` (unit): e_y from the lab axis least
/// aligned with x, e_z = e_x x e_y.
fn basis_along(x: Vector3<f64>) -> Matrix3<f64> {
    let axis = (0..3)
        .min_by(|&i, &j| x[i].abs().total_cmp(&x[j].abs()))
        .unwrap_or(0);
    let mut a = Vector3::zeros();
    a[axis] = 1.0;
    let y = (a - x * a.dot(&x)).normalize();
    let z = x.cross(&y);
    Matrix3::from_columns(&[x, y, z])
}

/// The outcome of a sphere against a plane: the ball's outgoing velocity and spin, and the
/// equivalent pair's outcome (impulse P, tangential impulse J, sliding, stick time, heat,
/// checks, stats; its states are the pair's, module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneOutcome {
    /// Outgoing velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Outgoing spin (rad/s).
    pub spin: Vector3<f64>,
    /// The equivalent pair's outcome.
    pub outcome: Outcome,
}

/// Resolves a sphere against a plane under the force `profile` with `settings.method()`
/// (the closed form or time stepping), optionally streaming the equivalent pair's trace
/// ([`PlaneCollision::velocity_of`] and [`PlaneCollision::spin_of`] read the ball's state
/// from a row).
pub fn solve_plane<P: ForceProfile + ?Sized>(
    c: &PlaneCollision,
    profile: &P,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<PlaneOutcome, Error> {
    Ok(c.outcome(solve(&c.pair, profile, settings, trace)?))
}

/// Resolves a sphere against a plane under the contact `law` (the compression of ball and
/// plane, reduced mass m: [`HertzContact::sphere_plane`](crate::HertzContact::sphere_plane)
/// gives Hertz's stiffness).
pub fn solve_plane_law(
    c: &PlaneCollision,
    law: &ContactLaw,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<PlaneOutcome, Error> {
    Ok(c.outcome(solve_law(&c.pair, law, settings, trace)?))
}

//! The compliant impact of two spheres (docs/tangential.md#two-spheres): the plane's kernel
//! with ball B as the partner, each ball with its own mass, radius, alpha and material.
//!
//! With n the unit normal from A's centre to B's, the kernel steps A's motion relative to
//! B's along the normal -n (from B towards A) with the reduced mass m* = m_A m_B / (m_A +
//! m_B), the effective radius 1/R* = 1/r_A + 1/r_B and Hertz's and Mindlin's effective
//! moduli, 1/E* = (1 - nu_A^2)/E_A + (1 - nu_B^2)/E_B and 1/G* = (2 - nu_A)/G_A + (2 -
//! nu_B)/G_B. The impulse on A is J = m* (g' - g), g = v_A - v_B, and the balls leave with
//! v_A' = v_A + J / m_A and v_B' = v_B - J / m_B, so the total momentum is the incoming one
//! to round-off.

use crate::base::error::Error;
use crate::base::settings::SolverSettings;
use crate::base::validate::positive;
use crate::model::contact_law::Damping;
use crate::model::material::{hertz_stiffness, reduced_mass, Material};
use crate::model::params::{energy_in, kinetic_energy, Ball};
use crate::tangential::impact::{
    check_alpha, check_mu, chi, finite_vector, run, shear_compliance, unit_normal, Bodies, Contact,
    Partner,
};
use crate::tangential::outcome::CompliantPairOutcome;
use nalgebra::Vector3;

/// The field naming the factor on Mindlin's tangential stiffness.
pub(crate) const SHEAR_FACTOR_FIELD: &str = "contact.shear_stiffness_factor";

/// One sphere of a compliant pair: the ball, its material and its incoming motion (lab
/// frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompliantSphere {
    /// Mass, radius and alpha (I = alpha m r^2).
    pub ball: Ball,
    /// Young's modulus and Poisson ratio.
    pub material: Material,
    /// Velocity of the centre (m/s).
    pub velocity: Vector3<f64>,
    /// Spin (rad/s).
    pub spin: Vector3<f64>,
}

/// Balls `a` and `b` meeting along `normal` (from A's centre to B's; normalised here) with
/// Coulomb friction `mu`, resolved with Hertz's normal force and Mindlin's no-slip
/// tangential spring of stiffness `shear_stiffness_factor` times 8 G* a under Coulomb's cap
/// (docs/tangential.md#two-spheres; factor 1 is Mindlin's spring, a larger factor a stiffer
/// one: the rigid stick rule is its limit). Elastic in the normal direction (restitution 1).
/// The stepping is the plane's (its rtol and atol from `settings`).
///
/// The outcome's `ball_a` is the contact as A sees it: A's velocity and spin, the impulses
/// of B on A, the slip of A's contact point over B's, and the kinetic energies of both
/// balls; `velocity_b` and `spin_b` are B's.
///
/// Errors: [`Error::InvalidParameter`] naming `friction.mu` (finite, in [0, 1e6]),
/// `contact.normal` (finite, not zero), `contact.shear_stiffness_factor` (finite, > 0),
/// `incoming.velocity_a`, `incoming.velocity_b` (finite, and approaching:
/// (v_A - v_B).n > 0), `incoming.spin_a`, `incoming.spin_b` (finite) or
/// `contact.profile.duration` (a material so extreme that Hertz's contact time is not a
/// normal number); [`Error::TooManySteps`] past 1e6 steps; [`Error::NonFinite`] when a
/// result is not finite.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// // Two resin pool balls head on at 1 m/s and at rest, without friction: equal masses
/// // exchange their velocities (elastic, e = 1).
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let resin = Material::new(5.4e9, 0.34)?;
/// let sphere = |v: f64| CompliantSphere {
///     ball,
///     material: resin,
///     velocity: Vector3::new(v, 0.0, 0.0),
///     spin: Vector3::zeros(),
/// };
/// let out = resolve_sphere_sphere_compliant(
///     &sphere(1.0), &sphere(0.0), Vector3::x(), 0.0, 1.0, &SolverSettings::default(),
/// )?;
/// assert!(out.ball_a.velocity.norm() < 1e-7 && (out.velocity_b.x - 1.0).abs() < 1e-7);
/// // Hertz's contact time of the pair: about 0.35 ms at 1 m/s.
/// let h = HertzContact::identical(&ball, &resin, 0.5)?;
/// assert!((out.ball_a.contact_time / h.duration - 1.0).abs() < 1e-6);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
pub fn resolve_sphere_sphere_compliant(
    a: &CompliantSphere,
    b: &CompliantSphere,
    normal: Vector3<f64>,
    mu: f64,
    shear_stiffness_factor: f64,
    settings: &SolverSettings,
) -> Result<CompliantPairOutcome, Error> {
    resolve_sphere_sphere_compliant_damped(
        a,
        b,
        (Damping::None, 0.0),
        normal,
        mu,
        shear_stiffness_factor,
        settings,
    )
}

/// [`resolve_sphere_sphere_compliant`] with a damped normal force, as
/// [`resolve_sphere_plane_compliant_damped`](crate::resolve_sphere_plane_compliant_damped)
/// on a plane: `damping` is the law and its coefficient (Hunt and Crossley's beta in s/m,
/// Kuwabara and Kono's gamma in s; docs/contact-law.md) on the pair's Hertz stiffness
/// k_n = (4/3) E* sqrt(R*); the contact ends where the force returns to zero, and
/// Coulomb's cap follows the damped force. To reach a restitution e at a relative approach
/// speed, calibrate the coefficient with [`ContactLaw::calibrated`](crate::ContactLaw::calibrated)
/// on that stiffness ([`HertzContact::of_pair`](crate::HertzContact::of_pair) for two balls
/// of one material) and the reduced mass m* = m_A m_B / (m_A + m_B).
/// `(Damping::None, 0.0)` is the elastic kernel, bit for bit.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// // Two resin pool balls head on at 2 m/s and at rest, damped to e = 0.9 at 2 m/s.
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let resin = Material::new(5.4e9, 0.34)?;
/// let pair = BallPair::identical(ball);
/// let k = HertzContact::of_pair(&pair, &resin, 1.0)?.stiffness;
/// let law = ContactLaw::calibrated(k, Damping::HuntCrossley, 0.9, 2.0, pair.reduced_mass())?;
/// let sphere = |v: f64| CompliantSphere {
///     ball,
///     material: resin,
///     velocity: Vector3::new(v, 0.0, 0.0),
///     spin: Vector3::zeros(),
/// };
/// let out = resolve_sphere_sphere_compliant_damped(
///     &sphere(2.0), &sphere(0.0), (law.damping(), law.coefficient()), Vector3::x(), 0.0, 1.0,
///     &SolverSettings::default(),
/// )?;
/// let e = (out.velocity_b.x - out.ball_a.velocity.x) / 2.0;
/// assert!((e - 0.9).abs() < 1e-6);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn resolve_sphere_sphere_compliant_damped(
    a: &CompliantSphere,
    b: &CompliantSphere,
    damping: (Damping, f64),
    normal: Vector3<f64>,
    mu: f64,
    shear_stiffness_factor: f64,
    settings: &SolverSettings,
) -> Result<CompliantPairOutcome, Error> {
    check_mu(mu)?;
    check_alpha("balls.a.alpha", &a.ball)?;
    check_alpha("balls.b.alpha", &b.ball)?;
    let n = unit_normal(
        "contact.normal",
        &normal,
        "a non-zero vector (from ball A's centre to ball B's)",
    )?;
    positive(
        SHEAR_FACTOR_FIELD,
        shear_stiffness_factor,
        "(1: Mindlin's stiffness)",
    )?;
    finite_vector("incoming.velocity_a", &a.velocity)?;
    finite_vector("incoming.spin_a", &a.spin)?;
    finite_vector("incoming.velocity_b", &b.velocity)?;
    finite_vector("incoming.spin_b", &b.spin)?;
    let g = a.velocity - b.velocity;
    let approach = g.dot(&n);
    if approach <= 0.0 {
        return Err(Error::invalid(
            "incoming.velocity_a",
            format!(
                "[{}, {}, {}] against ball B's [{}, {}, {}] ((v_A - v_B).n = {approach} m/s)",
                a.velocity.x, a.velocity.y, a.velocity.z, b.velocity.x, b.velocity.y, b.velocity.z
            ),
            "balls approaching each other: (v_A - v_B).n > 0",
        ));
    }
    let energy_in = energy_in(&[
        (
            &a.ball,
            &a.velocity,
            &a.spin,
            "incoming.velocity_a",
            "incoming.spin_a",
        ),
        (
            &b.ball,
            &b.velocity,
            &b.spin,
            "incoming.velocity_b",
            "incoming.spin_b",
        ),
    ])?;
    let (e_star, effective_radius, k_n) =
        hertz_stiffness((&a.ball, &a.material), (&b.ball, &b.material));
    let g_star = 1.0 / (shear_compliance(&a.material) + shear_compliance(&b.material));
    let mass = reduced_mass(&a.ball, &b.ball);
    let bodies = Bodies {
        mass,
        radius: a.ball.radius(),
        inertia: a.ball.inertia(),
        partner: Partner::Sphere {
            radius: b.ball.radius(),
            inertia: b.ball.inertia(),
        },
        k_n,
        effective_radius,
        g_star,
        shear_factor: shear_stiffness_factor,
        damping,
    };
    let r = run(&bodies, mu, g, a.spin, b.spin, -n, settings)?;
    let impulse = mass * (r.g_out() - g);
    let velocity_a = a.velocity + impulse / a.ball.mass();
    let velocity_b = b.velocity - impulse / b.ball.mass();
    let spin_b = Contact::partner_spin(&r.y);
    let energy_out = kinetic_energy(&a.ball, &velocity_a, &Contact::spin(&r.y))
        + kinetic_energy(&b.ball, &velocity_b, &spin_b);
    let ball_a = r.outcome(
        velocity_a,
        mass,
        chi(g_star, e_star, mu),
        (energy_in, energy_out),
    )?;
    for (name, x) in [("velocity_b", velocity_b.norm()), ("spin_b", spin_b.norm())] {
        crate::base::validate::finite_output(x, || name.to_string())?;
    }
    Ok(CompliantPairOutcome {
        ball_a,
        velocity_b,
        spin_b,
    })
}

//! The balls' material and Hertz's elastic contact between them: what sets the duration of
//! a `hertz` pulse when a scene gives the material instead of the duration
//! (docs/model.md#hertz-from-the-material).
//!
//! Two elastic spheres pressed together by a force F approach by delta with
//! F = k delta^(3/2) (H. Hertz 1882; L. D. Landau, E. M. Lifshitz, *Theory of Elasticity*,
//! section 9). Colliding at the relative normal speed v, their relative motion is that of
//! the reduced mass m* under this force, m* delta'' = -k delta^(3/2), so energy conservation,
//! m* v^2 / 2 = (2/5) k delta_max^(5/2), fixes the largest compression, and the time the
//! balls touch follows from integrating the motion (docs/model.md#force-profiles):
//!
//! ```text
//! 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b      effective modulus      (Pa)
//! 1/R  = 1/r_a + 1/r_b                            effective radius       (m)
//! m*   = m_a m_b / (m_a + m_b)                    reduced mass           (kg)
//! k    = (4/3) E* sqrt(R)                         stiffness              (N / m^(3/2))
//! delta_max = (5 m* v^2 / (4 k))^(2/5)            largest compression    (m)
//! tau  = (4/5) B(2/5, 1/2) delta_max / v          contact time           (s)
//! F_max = k delta_max^(3/2)                       peak force             (N)
//! a    = sqrt(R delta_max)                        contact radius at F_max (m)
//! ```
//!
//! For two identical balls (mass m, radius r, modulus E, Poisson ratio nu):
//! E* = E / (2 (1 - nu^2)), R = r / 2, m* = m / 2, and v = 2 U(0) in the centre-of-mass frame.
//! With a restitution below 1 the pulse keeps this elastic shape and duration and is scaled
//! to the collision's impulse.

use crate::base::beta::beta;
use crate::base::error::Error;
use crate::base::validate::finite;
use crate::base::validate::positive;
use crate::model::params::{Ball, BallPair};
use serde::Serialize;

use crate::base::fields::{POISSON_RATIO_FIELD, YOUNGS_MODULUS_FIELD};

/// An isotropic elastic material: Young's modulus and Poisson ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Material {
    youngs_modulus: f64,
    poisson_ratio: f64,
}

impl Material {
    /// A validated material: `youngs_modulus` E (Pa) finite and > 0, `poisson_ratio` nu
    /// finite and in (-1, 1/2] (the range of a stable isotropic solid; 1/2 is
    /// incompressible). Phenolic resin billiard balls: E about 5.4-5.8 GPa, nu = 0.34.
    ///
    /// ```
    /// use billiard_contact::Material;
    /// let resin = Material::new(5.4e9, 0.34)?;
    /// assert_eq!(resin.youngs_modulus(), 5.4e9);
    /// assert!(Material::new(5.4e9, 0.5).is_ok() && Material::new(5.4e9, 0.6).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, Error> {
        positive(YOUNGS_MODULUS_FIELD, youngs_modulus, "Pa")?;
        finite(POISSON_RATIO_FIELD, poisson_ratio)?;
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(Error::invalid(
                POISSON_RATIO_FIELD,
                poisson_ratio,
                "in (-1, 0.5]: the Poisson ratio of a stable isotropic solid (0.34 for \
                 phenolic resin)",
            ));
        }
        Ok(Material {
            youngs_modulus,
            poisson_ratio,
        })
    }

    /// Young's modulus E (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson ratio nu (dimensionless).
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// The compliance (1 - nu^2) / E (1/Pa): this body's share of 1/E*.
    fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }
}

/// Hertz's elastic impact of two balls at a given approach speed (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzContact {
    /// Effective modulus E* (Pa).
    pub effective_modulus: f64,
    /// Effective radius R (m).
    pub effective_radius: f64,
    /// Reduced mass m* (kg).
    pub reduced_mass: f64,
    /// Stiffness k (N / m^(3/2)): F = k delta^(3/2).
    pub stiffness: f64,
    /// Relative normal approach speed v (m/s).
    pub approach_speed: f64,
    /// Largest compression delta_max (m).
    pub max_compression: f64,
    /// Contact time tau (s).
    pub duration: f64,
    /// Peak force F_max = k delta_max^(3/2) (N) of the elastic impact.
    pub peak_force: f64,
    /// Radius sqrt(R delta_max) of the contact patch at the peak (m).
    pub contact_radius: f64,
}

impl HertzContact {
    /// Balls `a` and `b` of materials `material_a` and `material_b` colliding at the
    /// relative normal speed `approach_speed` v (m/s, finite and > 0).
    ///
    /// Errors: [`Error::InvalidParameter`] naming `incoming` when v is not > 0 (balls that do
    /// not approach have no contact time), or `contact.profile.duration` when the result is
    /// not a finite positive number (speeds or moduli so extreme that it under- or
    /// overflows).
    pub fn between(
        a: (&Ball, &Material),
        b: (&Ball, &Material),
        approach_speed: f64,
    ) -> Result<Self, Error> {
        let (effective_modulus, effective_radius, stiffness) = hertz_stiffness(a, b);
        let reduced_mass = reduced_mass(a.0, b.0);
        HertzContact::of_stiffness(
            effective_modulus,
            effective_radius,
            reduced_mass,
            stiffness,
            approach_speed,
        )
    }

    /// The elastic impact of the given effective modulus, radius, reduced mass and stiffness
    /// at `approach_speed`, checked.
    fn of_stiffness(
        effective_modulus: f64,
        effective_radius: f64,
        reduced_mass: f64,
        stiffness: f64,
        approach_speed: f64,
    ) -> Result<Self, Error> {
        if !(approach_speed.is_finite() && approach_speed > 0.0) {
            return Err(Error::invalid(
                "incoming",
                format!("a relative approach speed of {approach_speed} m/s"),
                "approaching balls (U(0) > 0): the contact time follows from the material and \
                 the approach speed",
            ));
        }
        let (max_compression, duration) = elastic_impact(stiffness, reduced_mass, approach_speed);
        let contact = HertzContact {
            effective_modulus,
            effective_radius,
            reduced_mass,
            stiffness,
            approach_speed,
            max_compression,
            duration,
            peak_force: stiffness * max_compression * max_compression.sqrt(),
            contact_radius: (effective_radius * max_compression).sqrt(),
        };
        let values = [
            contact.duration,
            contact.max_compression,
            contact.peak_force,
            contact.contact_radius,
        ];
        if !values.iter().all(|x| x.is_normal() && *x > 0.0) {
            return Err(Error::invalid(
                crate::base::fields::DURATION_FIELD,
                format!(
                    "{duration} s from the material at {approach_speed} m/s (compression \
                     {max_compression} m)"
                ),
                "a contact time, compression, force and contact radius that are normal \
                 positive numbers: the material and the approach speed are out of range",
            ));
        }
        Ok(contact)
    }

    /// Two identical `ball`s of `material` with incoming centre-of-mass normal velocity
    /// `u0` = U(0) (m/s): the relative approach speed is v = 2 U(0).
    ///
    /// ```
    /// use billiard_contact::{Ball, HertzContact, Material};
    /// // Pool balls (phenolic resin) meeting at 1 m/s: about 0.4 ms, 137 um, 777 N.
    /// let ball = Ball::new(0.17, 0.028575, 0.4)?;
    /// let h = HertzContact::identical(&ball, &Material::new(5.4e9, 0.34)?, 0.5)?;
    /// assert!((h.duration - 4.02e-4).abs() < 1e-6);
    /// assert!((h.max_compression - 1.37e-4).abs() < 1e-6);
    /// assert!((h.peak_force - 777.0).abs() < 1.0);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn identical(ball: &Ball, material: &Material, u0: f64) -> Result<Self, Error> {
        HertzContact::of_pair(&BallPair::identical(*ball), material, u0)
    }

    /// A `ball` of `material` meeting a plane of `plane` (`None`: a rigid plane, compliance
    /// 0) at the normal approach speed `approach_speed` (m/s, > 0): the effective radius is
    /// the ball's radius and the mass of the relative motion the ball's own mass (the plane is
    /// the partner of infinite radius and mass), E* = 1 / ((1 - nu^2)/E + (1 - nu_p^2)/E_p).
    ///
    /// ```
    /// use billiard_contact::{Ball, HertzContact, Material};
    /// // A resin ball on a steel plane at 1 m/s: R = r, m* = m.
    /// let ball = Ball::new(0.17, 0.028575, 0.4)?;
    /// let (resin, steel) = (Material::new(5.4e9, 0.34)?, Material::new(2.0e11, 0.3)?);
    /// let h = HertzContact::sphere_plane(&ball, &resin, Some(&steel), 1.0)?;
    /// let e_star = 1.0 / ((1.0 - 0.34f64.powi(2)) / 5.4e9 + (1.0 - 0.3f64.powi(2)) / 2.0e11);
    /// assert!((h.effective_modulus / e_star - 1.0).abs() < 1e-15);
    /// assert_eq!(h.effective_radius, 0.028575);
    /// assert_eq!(h.reduced_mass, 0.17);
    /// // Hertz: delta_max = (5 m v^2 / (4 k))^(2/5), k = (4/3) E* sqrt(r).
    /// let k = 4.0 / 3.0 * e_star * 0.028575f64.sqrt();
    /// assert!((h.max_compression / (5.0 * 0.17 / (4.0 * k)).powf(0.4) - 1.0).abs() < 1e-12);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn sphere_plane(
        ball: &Ball,
        material: &Material,
        plane: Option<&Material>,
        approach_speed: f64,
    ) -> Result<Self, Error> {
        let effective_modulus =
            1.0 / (material.compliance() + plane.map_or(0.0, |p| p.compliance()));
        let (radius, mass) = (ball.radius(), ball.mass());
        let stiffness = 4.0 / 3.0 * effective_modulus * radius.sqrt();
        HertzContact::of_stiffness(effective_modulus, radius, mass, stiffness, approach_speed)
    }

    /// Balls A and B of `balls`, both of `material`, with incoming centre-of-mass normal
    /// velocity `u0` = U(0) (m/s), half the relative approach speed v = 2 U(0)
    /// (docs/unequal-balls.md); [`HertzContact::identical`] for two identical balls.
    pub fn of_pair(balls: &BallPair, material: &Material, u0: f64) -> Result<Self, Error> {
        HertzContact::between((&balls.a, material), (&balls.b, material), 2.0 * u0)
    }
}

/// Hertz's stiffness of balls `a` and `b` of their materials: the effective modulus E* (Pa),
/// the effective radius R (m) and k = (4/3) E* sqrt(R) (N / m^(3/2)).
///
/// ```
/// use billiard_contact::{Ball, Material};
/// use billiard_contact::details::hertz_stiffness;
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let resin = Material::new(5.4e9, 0.34)?;
/// let (_, _, k) = hertz_stiffness((&ball, &resin), (&ball, &resin));
/// let e_star = 5.4e9 / (2.0 * (1.0 - 0.34 * 0.34));
/// assert!((k - 4.0 / 3.0 * e_star * (0.028575f64 / 2.0).sqrt()).abs() < 1e-6 * k);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
pub fn hertz_stiffness(a: (&Ball, &Material), b: (&Ball, &Material)) -> (f64, f64, f64) {
    let (ball_a, mat_a) = a;
    let (ball_b, mat_b) = b;
    let effective_modulus = 1.0 / (mat_a.compliance() + mat_b.compliance());
    let effective_radius = 1.0 / (1.0 / ball_a.radius() + 1.0 / ball_b.radius());
    let stiffness = 4.0 / 3.0 * effective_modulus * effective_radius.sqrt();
    (effective_modulus, effective_radius, stiffness)
}

/// The reduced mass m* = m_a m_b / (m_a + m_b) (kg) of balls `a` and `b`: the mass of
/// their relative motion along the line of centres.
pub(crate) fn reduced_mass(a: &Ball, b: &Ball) -> f64 {
    a.mass() * b.mass() / (a.mass() + b.mass())
}

/// Hertz's elastic impact of stiffness `stiffness` k (N / m^(3/2)) and reduced mass
/// `reduced_mass` m* (kg) at the relative approach speed `approach_speed` v (m/s): the
/// largest compression delta_max = (5 m* v^2 / (4 k))^(2/5) (m) and the contact time
/// tau = (4/5) B(2/5, 1/2) delta_max / v (s), about 2.9433 delta_max / v.
///
/// ```
/// use billiard_contact::details::elastic_impact;
/// // m* = 0.085 kg, k = 1e9 N/m^1.5, v = 1 m/s.
/// let (d, tau) = elastic_impact(1e9, 0.085, 1.0);
/// assert!((d - (5.0 * 0.085 / 4e9f64).powf(0.4)).abs() < 1e-18);
/// assert!((tau / (d / 1.0) - 2.9432).abs() < 1e-3);
/// ```
pub fn elastic_impact(stiffness: f64, reduced_mass: f64, approach_speed: f64) -> (f64, f64) {
    let v = approach_speed;
    let max_compression = (5.0 * reduced_mass * v * v / (4.0 * stiffness)).powf(0.4);
    (max_compression, 0.8 * beta(0.4, 0.5) * max_compression / v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The identical-ball specialisation: E* = E / (2 (1 - nu^2)), R = r / 2, m* = m / 2
    /// (to round-off of the general harmonic means).
    #[test]
    fn identical_balls_specialise_the_general_formulas() {
        let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
        let mat = Material::new(5.4e9, 0.34).unwrap();
        let h = HertzContact::identical(&ball, &mat, 0.5).unwrap();
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(h.effective_modulus, 5.4e9 / (2.0 * (1.0 - 0.34 * 0.34))) < 1e-15);
        assert!(rel(h.effective_radius, 0.028575 / 2.0) < 1e-15);
        assert!(rel(h.reduced_mass, 0.17 / 2.0) < 1e-15);
        assert_eq!(h.approach_speed, 1.0);
    }

    #[test]
    fn refuses_bad_materials_and_speeds() {
        for (e, nu, field) in [
            (0.0, 0.3, YOUNGS_MODULUS_FIELD),
            (-1e9, 0.3, YOUNGS_MODULUS_FIELD),
            (f64::NAN, 0.3, YOUNGS_MODULUS_FIELD),
            (5e9, -1.0, POISSON_RATIO_FIELD),
            (5e9, 0.51, POISSON_RATIO_FIELD),
            (5e9, f64::INFINITY, POISSON_RATIO_FIELD),
        ] {
            match Material::new(e, nu) {
                Err(Error::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                other => panic!("E = {e}, nu = {nu}: {other:?}"),
            }
        }
        let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
        let mat = Material::new(5.4e9, 0.34).unwrap();
        for u0 in [0.0, -0.5, f64::NAN] {
            match HertzContact::identical(&ball, &mat, u0) {
                Err(Error::InvalidParameter { field, .. }) => assert_eq!(field, "incoming"),
                other => panic!("U(0) = {u0}: {other:?}"),
            }
        }
        // A speed so small that the compression underflows.
        match HertzContact::identical(&ball, &mat, 1e-300) {
            Err(Error::InvalidParameter { field, .. }) => {
                assert_eq!(field, "contact.profile.duration")
            }
            other => panic!("{other:?}"),
        }
    }
}

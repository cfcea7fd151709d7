//! A scene built in code: [`SceneBuilder`] holds the decisions a scene file leaves to the
//! library (the contact duration from the profile or from the balls' material, a contact
//! law's stiffness from its value or from the material, its coefficient given or
//! calibrated to a restitution, the time unit of a law scene) and validates everything in
//! [`SceneBuilder::build`], naming each field as the scene file does. Reading a scene file
//! fills a builder.

use crate::base::error::Error;
use crate::base::fields::{DURATION_FIELD, POISSON_RATIO_FIELD, YOUNGS_MODULUS_FIELD};
use crate::base::settings::SolverSettings;
use crate::model::collision::Collision;
use crate::model::contact_law::{
    ContactLaw, Damping, AT_SPEED_FIELD, COEFFICIENT_FIELD, RESTITUTION_FIELD, STIFFNESS_FIELD,
};
use crate::model::effects::Effects;
use crate::model::material::{
    elastic_impact, hertz_stiffness, sphere_plane_stiffness, HertzContact, Material,
};
use crate::model::params::{Ball, BallPair, Contact, Friction, FrictionLaw, ImpulseRule};
use crate::profile::hertz::Hertz;
use crate::profile::spec::{Profile, ProfileSpec};
use crate::scene::overrides::SolverOverrides;
use crate::scene::types::{Incoming, PlaneIncoming, Scene, TangentialLaw};
use crate::table_phase::params::{TableParams, TableSize};
use std::path::{Path, PathBuf};

/// A contact law as a scene gives it (`[contact.law]`, Hertz's force k delta^(3/2) with a
/// damping term): the stiffness given or from the balls' material, the coefficient given
/// or calibrated to a restitution at an approach speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawSpec {
    /// Stiffness k (N/m^1.5); `None`: from the balls' material.
    pub stiffness: Option<f64>,
    /// The damping term (default none: elastic).
    pub damping: Damping,
    /// The damping coefficient (beta, s/m, or gamma, s); `None` with no restitution: 0.
    pub coefficient: Option<f64>,
    /// The restitution to calibrate the coefficient to (with `at_speed`).
    pub restitution: Option<f64>,
    /// The relative approach speed (m/s) at which the law has `restitution`.
    pub at_speed: Option<f64>,
}

/// Where the normal force comes from: a prescribed profile, or a contact law.
#[derive(Debug, Clone, PartialEq)]
pub enum ForceSpec {
    /// `[contact.profile]`: the force's shape and duration.
    Profile(ProfileSpec),
    /// `[contact.law]`: the force from the compression.
    Law(LawSpec),
}

/// A scene built in code, validated by [`SceneBuilder::build`].
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::profile::ProfileSpec;
/// use billiard_contact::*;
///
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let incoming = Incoming::Cm(CmState::new(Vector3::new(1.0, 0.5, 0.0), Vector3::zeros(), Vector3::zeros()));
/// let scene = SceneBuilder::new(ball.into(), Friction::constant(0.06)?, incoming)
///     .restitution(1.0)
///     .force(ForceSpec::Profile(ProfileSpec::HalfSine { duration: 2.5e-4 }))
///     .build()?;
/// let run = run_scene(&scene, &scene.solver, None)?;
/// // S(0) = 1 m/s never reaches 0: V' = V - mu P / m = 0.5 - 2 (0.06) (1) = 0.38 m/s (eq 25).
/// assert!((run.outcome.result.out.u_cm.y - 0.38).abs() < 1e-10);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[derive(Debug)]
pub struct SceneBuilder {
    name: String,
    balls: BallPair,
    material: Option<Material>,
    friction: Friction,
    restitution: Option<f64>,
    impulse: Option<f64>,
    force: Option<ForceSpec>,
    tangential: TangentialLaw,
    incoming: Result<Incoming, Error>,
    solver: SolverOverrides,
    effects: Effects,
    base: PathBuf,
    source: Option<PathBuf>,
    table: Result<Option<TableParams>, Error>,
    table_size: Result<Option<TableSize>, Error>,
}

impl SceneBuilder {
    /// A scene of the balls `balls` with friction `friction` and the incoming state
    /// `incoming`; the rest defaults to a scene file's defaults (restitution 1, default
    /// solver settings and effects, no material, no table), but the force: give it with
    /// [`SceneBuilder::force`].
    pub fn new(balls: BallPair, friction: Friction, incoming: Incoming) -> Self {
        SceneBuilder {
            name: "scene".into(),
            balls,
            material: None,
            friction,
            restitution: None,
            impulse: None,
            force: None,
            tangential: TangentialLaw::Rigid,
            incoming: Ok(incoming),
            solver: SolverOverrides::default(),
            effects: Effects::default(),
            base: PathBuf::from("."),
            source: None,
            table: Ok(None),
            table_size: Ok(None),
        }
    }

    /// The balls as a scene file gives them: `mass`, `radius` and `alpha` of two identical
    /// balls (`alpha` default 0.4), or balls of their own `a` and `b` (each the result of
    /// its own validation, reported after the form is checked); never both forms.
    pub fn balls(
        shared: [Option<f64>; 3],
        a: Option<Result<Ball, Error>>,
        b: Option<Result<Ball, Error>>,
    ) -> Result<BallPair, Error> {
        let [mass, radius, alpha] = shared;
        let any_shared = shared.iter().any(Option::is_some);
        match (a, b) {
            (Some(a), Some(b)) if !any_shared => Ok(BallPair::new(a?, b?)),
            (None, None) => {
                let missing = |key: &str| {
                    Error::invalid(
                        format!("balls.{key}"),
                        "missing",
                        "[balls] with mass and radius (two identical balls), or [balls.a] and \
                         [balls.b]",
                    )
                };
                let mass = mass.ok_or_else(|| missing("mass"))?;
                let radius = radius.ok_or_else(|| missing("radius"))?;
                let alpha = alpha.unwrap_or(crate::model::params::ALPHA_SOLID);
                Ok(BallPair::identical(Ball::new(mass, radius, alpha)?))
            }
            (Some(_), Some(_)) => Err(Error::invalid(
                "balls.mass/radius/alpha",
                "given together with [balls.a] and [balls.b]",
                "one form: [balls] keys for two identical balls, or [balls.a] and [balls.b]",
            )),
            (a, _) => Err(Error::invalid(
                if a.is_some() { "balls.b" } else { "balls.a" },
                "missing",
                "[balls.a] and [balls.b] together (or [balls] keys for identical balls)",
            )),
        }
    }

    /// The name shown in reports (default `scene`).
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// The balls' material (the same for both balls): a `hertz` or `sine-power` profile
    /// without a duration takes the Hertz contact time, a law without a stiffness Hertz's
    /// stiffness.
    pub fn material(mut self, material: Material) -> Self {
        self.material = Some(material);
        self
    }

    /// The restitution e of the impulse rule (not with [`SceneBuilder::impulse`]; neither:
    /// e = 1; not with a contact law, which decides the impulse).
    pub fn restitution(mut self, e: f64) -> Self {
        self.restitution = Some(e);
        self
    }

    /// A prescribed normal impulse P (N s) instead of a restitution.
    pub fn impulse(mut self, p: f64) -> Self {
        self.impulse = Some(p);
        self
    }

    /// Where the normal force comes from.
    pub fn force(mut self, force: ForceSpec) -> Self {
        self.force = Some(force);
        self
    }

    /// The tangential law (a scene file's `contact.tangential`; default rigid). `Mindlin`
    /// needs a contact law ([`ForceSpec::Law`]) without a stiffness, the balls' material
    /// (and for a plane the plane's, else the plane is rigid), a constant mu and the effect
    /// `stick` on (docs/tangential.md#scenes).
    pub fn tangential(mut self, law: TangentialLaw) -> Self {
        self.tangential = law;
        self
    }

    /// Solver settings over the defaults (a scene file's `[solver]`).
    pub fn solver(mut self, solver: SolverOverrides) -> Self {
        self.solver = solver;
        self
    }

    /// The effects to simulate.
    pub fn effects(mut self, effects: Effects) -> Self {
        self.effects = effects;
        self
    }

    /// The cloth's parameters (a scene file's `[table]`; defaults apply when the effect
    /// `table` is on and none are given).
    pub fn table(mut self, table: TableParams) -> Self {
        self.table = Ok(Some(table));
        self
    }

    /// The playing area drawn on the top view.
    pub fn table_size(mut self, size: TableSize) -> Self {
        self.table_size = Ok(Some(size));
        self
    }

    /// The directory a tabulated profile's file is relative to (default `.`).
    pub fn files_relative_to(mut self, base: impl Into<PathBuf>) -> Self {
        self.base = base.into();
        self
    }

    /// The file the scene was read from, and the name it gives when none was set.
    pub(crate) fn source(mut self, source: Option<&Path>) -> Self {
        self.source = source.map(Path::to_path_buf);
        self
    }

    /// The incoming state, table and playing area as the scene file's reading left them:
    /// their errors are reported in the order of the checks of [`SceneBuilder::build`].
    pub(crate) fn read(
        mut self,
        incoming: Result<Incoming, Error>,
        table: Result<Option<TableParams>, Error>,
        table_size: Result<Option<TableSize>, Error>,
    ) -> Self {
        self.incoming = incoming;
        self.table = table;
        self.table_size = table_size;
        self
    }

    /// The validated scene. The checks run in the order of a scene file's sections: the
    /// force and the impulse rule, the law or the profile's duration source, the profile,
    /// the incoming state, the solver, the duration from the material, the table, and last
    /// the collision and the cloth.
    pub fn build(self) -> Result<Scene, Error> {
        let balls = self.balls;
        let material = self.material;
        let force = self.force.ok_or_else(|| {
            Error::invalid(
                "contact.profile",
                "missing",
                "a section [contact.profile] (the force's shape and duration), or \
                 [contact.law] (the force from the compression)",
            )
        })?;
        if let ForceSpec::Law(_) = force {
            let given = [("restitution", self.restitution), ("impulse", self.impulse)];
            if let Some((key, Some(v))) = given.iter().find(|(_, v)| v.is_some()) {
                return Err(Error::invalid(
                    "contact.law",
                    format!("given together with contact.{key} = {v}"),
                    "one of them: the law decides the impulse (leave out \
                     contact.restitution and contact.impulse; calibrate the law with \
                     contact.law.restitution and at_speed)",
                ));
            }
        }
        let impulse = ImpulseRule::from_either("contact.", self.restitution, self.impulse)?
            .unwrap_or(ImpulseRule::ELASTIC);
        let plane = match &self.incoming {
            Ok(Incoming::Plane(p)) => Some(*p),
            _ => None,
        };
        if plane.is_some() && !balls.is_identical() {
            return Err(Error::invalid(
                "balls",
                "[balls.a] and [balls.b] with [plane]",
                "one ball, [balls] (mass, radius, alpha), meeting the plane",
            ));
        }
        if let (Some(p), None) = (&plane, &material) {
            if let Some(m) = &p.material {
                return Err(Error::invalid(
                    "plane.youngs_modulus",
                    format!("{} without the ball's material", m.youngs_modulus()),
                    "given with [balls] youngs_modulus and poisson_ratio (Hertz's contact needs                      both bodies' materials; leave the plane's out for a rigid plane)",
                ));
            }
        }
        if self.tangential == TangentialLaw::Mindlin {
            check_mindlin(&force, material.as_ref(), &self.friction, &self.effects)?;
        }
        let law = match &force {
            ForceSpec::Law(law) => Some(law.build(&balls, material.as_ref(), plane.as_ref())?),
            ForceSpec::Profile(spec) => {
                check_duration_source(spec, material.as_ref())?;
                None
            }
        };
        // Without the material the profile is built here, before the incoming state (whose
        // errors come second); with it, or with a law, once the approach speed is known.
        let given = match (&force, material) {
            (ForceSpec::Profile(spec), None) => Some(spec.build(&self.base)?),
            _ => None,
        };
        let incoming = self.incoming?;
        let solver = self.solver.apply(&SolverSettings::default())?;
        let contact = Contact {
            friction: self.friction,
            impulse,
        };
        let effects = self.effects;
        let profile = match (given, &force, &law) {
            (Some(p), _, _) => p,
            (None, _, Some(law)) => law_time_unit(law, &balls, &incoming)?,
            (None, ForceSpec::Profile(spec), None) if plane.is_some() => {
                let mat = material
                    .as_ref()
                    .expect("without the material the profile is built");
                let p = plane.expect("a plane scene");
                let hertz = HertzContact::sphere_plane(
                    &balls.a,
                    mat,
                    p.material.as_ref(),
                    approaching_plane(&p)?,
                )?;
                spec.build_with(&self.base, Some(hertz.duration))?
            }
            (None, ForceSpec::Profile(spec), None) => {
                let mat = material
                    .as_ref()
                    .expect("without the material the profile is built");
                let (cm, _) = incoming.to_cm(&balls)?;
                let c = Collision::new(balls, contact, effects, cm)?;
                let hertz = HertzContact::of_pair(&balls, mat, c.incoming.u_cm.x)?;
                spec.build_with(&self.base, Some(hertz.duration))?
            }
            (None, ForceSpec::Law(_), None) => unreachable!("a law section builds the law"),
        };
        let scene = Scene {
            name: self.name,
            balls,
            material,
            contact,
            profile,
            law,
            tangential: self.tangential,
            incoming,
            solver,
            solver_given: self.solver,
            effects,
            source: self.source,
            table: self.table?,
            table_size: self.table_size?,
        };
        // Validate the geometry and the impulse now, so a bad scene fails when built.
        scene.collision()?;
        scene.cloth()?;
        Ok(scene)
    }
}

impl LawSpec {
    /// The validated law for the balls `balls` of `material` (if given): the stiffness from
    /// exactly one of `stiffness` or the material, the coefficient given or calibrated.
    /// Against a plane (`plane`), the stiffness is the sphere-plane one and the mass of the
    /// relative motion the ball's.
    fn build(
        &self,
        balls: &BallPair,
        material: Option<&Material>,
        plane: Option<&PlaneIncoming>,
    ) -> Result<ContactLaw, Error> {
        let stiffness = match (self.stiffness, material) {
            (Some(k), None) => k,
            (None, Some(m)) => match plane {
                Some(p) => sphere_plane_stiffness(&balls.a, m, p.material.as_ref()).2,
                None => hertz_stiffness((&balls.a, m), (&balls.b, m)).2,
            },
            (Some(k), Some(m)) => {
                return Err(Error::invalid(
                    STIFFNESS_FIELD,
                    format!(
                        "{k} together with {YOUNGS_MODULUS_FIELD} = {}",
                        m.youngs_modulus()
                    ),
                    "one of them: the stiffness, or the balls' material it follows from",
                ))
            }
            (None, None) => {
                return Err(Error::invalid(
                    STIFFNESS_FIELD,
                    "missing",
                    "a stiffness k (N/m^1.5), or [balls] youngs_modulus and poisson_ratio",
                ))
            }
        };
        let damping = self.damping;
        match (self.coefficient, self.restitution, self.at_speed) {
            (c, None, None) => ContactLaw::new(stiffness, damping, c.unwrap_or(0.0)),
            (None, Some(e), Some(v)) => {
                let mass = match plane {
                    Some(_) => balls.a.mass(),
                    None => 0.5 * balls.pair_mass(),
                };
                ContactLaw::calibrated(stiffness, damping, e, v, mass)
            }
            (c, e, v) => Err(calibration_mismatch(c, e, v)),
        }
    }
}

/// The elastic Hertz pulse of `law` for the balls `balls` approaching as `incoming` gives it: the
/// time unit of a law scene. Balls that do not approach are refused (the law has no contact
/// to make).
fn law_time_unit(
    law: &ContactLaw,
    balls: &BallPair,
    incoming: &Incoming,
) -> Result<Profile, Error> {
    if let Incoming::Plane(p) = incoming {
        let v = approaching_plane(p)?;
        let (_, tau) = elastic_impact(law.stiffness(), balls.a.mass(), v);
        return Ok(Profile::Hertz(Hertz::new(tau)?));
    }
    let (cm, _) = incoming.to_cm(balls)?;
    let u0 = cm.u_cm.x;
    if u0.is_nan() || u0 <= 0.0 {
        return Err(Error::invalid(
            "incoming",
            format!("a normal speed U(0) = {u0} m/s with [contact.law]"),
            "approaching balls (U(0) > 0): a contact law needs a contact to make",
        ));
    }
    let (_, tau) = elastic_impact(law.stiffness(), 0.5 * balls.pair_mass(), 2.0 * u0);
    Ok(Profile::Hertz(Hertz::new(tau)?))
}

/// The normal approach speed of a ball meeting a plane, refused when it does not approach
/// (the contact time of a material or a law needs a contact to make).
fn approaching_plane(p: &PlaneIncoming) -> Result<f64, Error> {
    let v = p.approach_speed();
    if v.is_nan() || v <= 0.0 {
        return Err(Error::invalid(
            "incoming.plane.velocity",
            format!("a normal speed v.n = {} m/s", -v),
            "a ball moving into the plane (v.n < 0, n out of the plane towards the ball): \
             the contact time follows from the approach speed",
        ));
    }
    Ok(v)
}

/// The field naming the tangential law.
pub(crate) const TANGENTIAL_FIELD: &str = "contact.tangential";

/// What `contact.tangential = "mindlin"` needs: a contact law whose stiffness follows from
/// the balls' material (Hertz's, which Mindlin's spring shares), a constant mu (the spring's
/// cap) and the stick effect (the spring decides when the contact point sticks).
fn check_mindlin(
    force: &ForceSpec,
    material: Option<&Material>,
    friction: &Friction,
    effects: &Effects,
) -> Result<(), Error> {
    let refuse = |value: &str, accepted: &str| {
        Err(Error::invalid(
            TANGENTIAL_FIELD,
            format!("\"mindlin\" {value}"),
            accepted,
        ))
    };
    let ForceSpec::Law(law) = force else {
        return refuse(
            "with [contact.profile]",
            "\"mindlin\" with [contact.law] (model = \"hertz\"): Mindlin's spring needs the \
             compression, which a prescribed profile does not give; or \"rigid\"",
        );
    };
    if material.is_none() {
        return refuse(
            "without the balls' material",
            "\"mindlin\" with [balls] youngs_modulus and poisson_ratio (Hertz's and Mindlin's \
             stiffnesses follow from them); or \"rigid\"",
        );
    }
    if let Some(k) = law.stiffness {
        return refuse(
            &format!("with contact.law.stiffness = {k}"),
            "\"mindlin\" with the stiffness from [balls] youngs_modulus and poisson_ratio \
             (leave out contact.law.stiffness); or \"rigid\"",
        );
    }
    if let FrictionLaw::SpeedDependent { .. } = friction.law() {
        return refuse(
            "with a speed-dependent contact.mu",
            "\"mindlin\" with a constant contact.mu (a number: the spring's cap mu F_n); or \
             \"rigid\"",
        );
    }
    if !effects.stick {
        return refuse(
            "with [effects] stick = false",
            "\"mindlin\" with the effect stick on (the spring decides when the contact point \
             sticks); or \"rigid\"",
        );
    }
    Ok(())
}

/// The contact duration comes from exactly one place: the profile, or (for `hertz` and
/// `sine-power`) the balls' material.
fn check_duration_source(spec: &ProfileSpec, material: Option<&Material>) -> Result<(), Error> {
    let Some(material) = material else {
        return Ok(());
    };
    if !spec.takes_material_duration() {
        return Err(Error::invalid(
            YOUNGS_MODULUS_FIELD,
            material.youngs_modulus(),
            "only with contact.profile.shape = \"hertz\" or \"sine-power\", whose contact time \
             the material sets; other shapes take a duration",
        ));
    }
    if let Some(d) = spec.duration() {
        return Err(Error::invalid(
            DURATION_FIELD,
            format!(
                "{d} s together with {YOUNGS_MODULUS_FIELD} = {} and {POISSON_RATIO_FIELD} = {}",
                material.youngs_modulus(),
                material.poisson_ratio()
            ),
            "one of them: the material and the approach speed set the contact time of a hertz \
             or sine-power pulse; leave out the duration, or the material",
        ));
    }
    Ok(())
}

/// The refusal of a `[contact.law]` whose coefficient, restitution and at_speed do not go
/// together (both the coefficient and the restitution, or the restitution or its speed
/// alone): named as the scene file names them.
pub(crate) fn calibration_mismatch(
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
) -> Error {
    match (coefficient, restitution, at_speed) {
        (Some(c), Some(e), _) => Error::invalid(
            COEFFICIENT_FIELD,
            format!("{c} together with {RESTITUTION_FIELD} = {e}"),
            "one of them: the coefficient, or the restitution (with at_speed) it is \
             calibrated to",
        ),
        (_, None, Some(v)) => Error::invalid(
            RESTITUTION_FIELD,
            format!("missing, with {AT_SPEED_FIELD} = {v}"),
            "given together with at_speed: the restitution the law has at that speed",
        ),
        (_, e, _) => Error::invalid(
            AT_SPEED_FIELD,
            format!(
                "missing, with {RESTITUTION_FIELD} = {}",
                e.unwrap_or(f64::NAN)
            ),
            "given together with restitution: the relative approach speed (m/s) at which the \
             law has it",
        ),
    }
}

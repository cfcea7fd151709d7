//! Scene files (TOML, SI units): the contract users and `data/scenes/` rely on.
//!
//! ```toml
//! name = "rolling cue ball, 30 degree cut"
//! [balls]
//! mass = 0.17        # kg
//! radius = 0.028575  # m
//! alpha = 0.4        # I = alpha m r^2; default 0.4
//! # youngs_modulus = 5.4e9   # Pa; optional, with poisson_ratio: hertz and sine-power
//! # poisson_ratio = 0.34     # then take their duration from the material (none given)
//! [contact]
//! mu = 0.06          # or { model = "speed-dependent", a = 9.951e-3, b = 0.108, c = 1.088 }
//!                    # (+ evaluate = "initial": mu(S(0)) held; default "along-contact")
//! restitution = 1.0  # or: impulse = 0.17  (N s); not both; neither: restitution 1
//! [contact.profile]
//! shape = "half-sine"    # half-sine | hertz | sine-power (exponent, default 1.5) | rectangle
//!                        # | tabulated (file = "...", relative to the scene)
//! duration = 2.5e-4      # s (hertz, sine-power: or from the balls' material)
//! # [contact.law]        # instead of [contact.profile] and restitution / impulse: the force
//! # model = "hertz"      # from the compression (docs/contact-law.md)
//! # stiffness = 4.5e8    # N/m^1.5; or from [balls] youngs_modulus and poisson_ratio
//! # damping = "hunt-crossley"   # none (default) | hunt-crossley | kuwabara-kono
//! # coefficient = 0.1    # beta (s/m) or gamma (s); or restitution = 0.95 and at_speed = 1.0
//! [incoming.cm]          # either this ...
//! u = [0.5, 0.25, 0.0]   # velocity of ball A in the paper's frame; B has -u
//! omega_a = [0.0, 0.0, 0.0]   # default 0
//! omega_b = [0.0, 0.0, 0.0]   # default 0
//! # [incoming.lab]       # ... or this
//! # a = { position = [-0.028575, 0, 0], velocity = [1, 0.5, 0], spin = [-17.5, 35.0, 0] }
//! # b = { position = [0.028575, 0, 0], velocity = [0, 0, 0], spin = [0, 0, 0] }
//! # up = [0, 0, 1]       # default +z
//! [solver]               # optional; defaults below
//! method = "dop853"      # closed-form | rk4 | dopri5 | dop853
//! rtol = 1e-10
//! atol = 1e-10           # on the scaled variables (speeds over v_ref); default = rtol
//! steps = 1000           # rk4 only
//! time_transform = true  # smoothing change of time variable for hertz, sine-power
//! [effects]              # optional
//! friction = true
//! stick = true
//! table = false          # true needs [incoming.lab] with a horizontal line of centres
//! [table]                # optional; used with table = true; defaults below
//! mu = 0.2               # ball-cloth sliding friction
//! restitution = 0.0      # ball-cloth, in [0, 1)
//! g = 9.81               # m/s^2
//! rolling_resistance = 0.0   # a rolling ball decelerates at rolling_resistance g (0: off)
//! spin_decay = 0.0       # |w.up| falls at spin_decay g / (alpha r) on the cloth (0: off)
//! # height = 0.0         # cloth height along up (m); default: r below the balls' centres
//! # length = 2.54        # m, with width: the playing area between the cushions, centred
//! # width = 1.27         # on the lab origin, drawn by --plot (cushions not modelled)
//! ```

use crate::error::Error;
use crate::formats::names::did_you_mean;
use crate::integrator::law::pair_mass;
use crate::integrator::{Method, SolverSettings};
use crate::model::collision::Collision;
use crate::model::contact_law::{
    ContactLaw, Damping, AT_SPEED_FIELD, COEFFICIENT_FIELD, RESTITUTION_FIELD, STIFFNESS_FIELD,
};
use crate::model::effects::Effects;
use crate::model::frame::{Frame, LabScene};
use crate::model::material::{
    elastic_impact, hertz_stiffness, HertzContact, Material, POISSON_RATIO_FIELD,
    YOUNGS_MODULUS_FIELD,
};
use crate::model::params::{Ball, BallPair, Contact, Evaluate, Friction, ImpulseRule, ALPHA_SOLID};
use crate::model::state::{CmState, LabBall};
use crate::profile::{Hertz, Profile, ProfileSpec};
use crate::table_phase::{Table, TableParams, TableSettings, TableSize};
use nalgebra::Vector3;
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// The built-in default scene (`data/scenes/default.toml`): the paper's rolling ball
/// striking a ball at rest, at a 30 degree cut.
pub const DEFAULT_SCENE: &str = include_str!("../../data/scenes/default.toml");

/// The incoming state as a scene gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Incoming {
    /// Directly in the paper's centre-of-mass frame.
    Cm(CmState),
    /// Both balls in the lab frame.
    Lab(LabScene),
}

/// A lab scene with the frame between it and the paper's centre-of-mass frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabFrame<'a> {
    /// The change of frame.
    pub frame: Frame,
    /// The lab scene.
    pub lab: &'a LabScene,
}

impl Incoming {
    /// The paper's centre-of-mass state of the balls `balls`; for lab input also the lab
    /// scene with its frame (the balls must touch, see [`Frame::of_pair`]).
    pub fn to_cm(&self, balls: &BallPair) -> Result<(CmState, Option<LabFrame<'_>>), Error> {
        Ok(match self {
            Incoming::Cm(cm) => (*cm, None),
            Incoming::Lab(lab) => {
                let frame = Frame::of_pair(lab, balls)?;
                (frame.to_cm(lab), Some(LabFrame { frame, lab }))
            }
        })
    }
}

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name shown in reports.
    pub name: String,
    /// The balls: `[balls]` (identical; `Ball::into()` makes the pair) or `[balls.a]` and
    /// `[balls.b]`.
    pub balls: BallPair,
    /// The balls' material (`balls.youngs_modulus`, `balls.poisson_ratio`, the same for
    /// both balls), when given: the profile's duration then follows from it
    /// ([`Scene::hertz`]).
    pub material: Option<Material>,
    /// Friction and impulse rule.
    pub contact: Contact,
    /// Normal-force profile. With a contact law, the elastic Hertz pulse of the law's
    /// stiffness at the approach speed (the law's time unit; the law decides the force).
    pub profile: Profile,
    /// The contact law (`[contact.law]`), when the force comes from the compression.
    pub law: Option<ContactLaw>,
    /// Incoming state.
    pub incoming: Incoming,
    /// Solver settings (`[solver]`, defaults when absent).
    pub solver: SolverSettings,
    /// The `[solver]` section as written (what it overrides; empty when absent), for the
    /// warnings about keys the scene does not use.
    pub solver_given: SolverOverrides,
    /// Effects (`[effects]`).
    pub effects: Effects,
    /// The file it was read from (`None` for the built-in scene).
    pub source: Option<PathBuf>,
    /// The cloth (`[table]`) as given; `None` when the section is absent (defaults apply
    /// when the effect `table` is on).
    pub table: Option<TableParams>,
    /// The playing area between the cushions (`[table] length, width`), drawn on the top
    /// view; `None` when not given.
    pub table_size: Option<TableSize>,
}

/// Solver settings as a scene's `[solver]` section or the command line gives them: each
/// one given replaces the base's (the defaults for a scene, the scene's on the command
/// line).
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverOverrides {
    /// Method.
    #[serde(default, deserialize_with = "optional_name")]
    pub method: Option<Method>,
    /// Relative tolerance.
    pub rtol: Option<f64>,
    /// Absolute tolerance on the scaled variables; default: a new `rtol` when one is
    /// given, the base's otherwise.
    pub atol: Option<f64>,
    /// RK4 steps over the contact.
    pub steps: Option<u32>,
    /// The smoothing time transform of pulses with algebraic ends.
    pub time_transform: Option<bool>,
}

impl SolverOverrides {
    /// `base` with these overrides, validated by [`SolverSettings::new`]: a new rtol
    /// carries atol with it unless atol is given too; `breakpoints` stays the base's, and
    /// so does `time_transform` unless given.
    ///
    /// ```
    /// use billiard_contact::formats::scene::SolverOverrides;
    /// use billiard_contact::{Method, SolverSettings};
    /// let base = SolverSettings::new(Method::Dop853, 1e-10, 1e-12, 1000).unwrap();
    /// let tighter = SolverOverrides { rtol: Some(1e-12), ..Default::default() };
    /// let s = tighter.apply(&base).unwrap();
    /// assert_eq!((s.method(), s.rtol(), s.atol(), s.steps()), (Method::Dop853, 1e-12, 1e-12, 1000));
    /// let rk4 = SolverOverrides { method: Some(Method::Rk4), ..Default::default() };
    /// assert_eq!(rk4.apply(&base).unwrap().atol(), 1e-12);
    /// ```
    pub fn apply(&self, base: &SolverSettings) -> Result<SolverSettings, Error> {
        let rtol = self.rtol.unwrap_or(base.rtol());
        let atol = self.atol.unwrap_or(if self.rtol.is_some() {
            rtol
        } else {
            base.atol()
        });
        let settings = SolverSettings::new(
            self.method.unwrap_or(base.method()),
            rtol,
            atol,
            self.steps.unwrap_or(base.steps()),
        )?;
        Ok(settings
            .with_breakpoints(base.breakpoints())
            .with_time_transform(self.time_transform.unwrap_or(base.time_transform())))
    }

    /// The overrides given here that a run with `settings` does not use, each as its field
    /// (`rtol`, `atol`, `time_transform`) and what it has no effect with: tolerances with rk4
    /// and with the closed form of a profile (under a contact law, `law`, the closed form
    /// integrates the normal law with dop853 at them), the time transform with the closed
    /// form or under a contact law
    /// (`law`: a law finds the end of the contact as an event, so its runs step in their own
    /// time: docs/contact-law.md#time-stepping). `billiard-contact` warns on stderr, the
    /// Python package with a `UserWarning`.
    ///
    /// ```
    /// use billiard_contact::formats::scene::SolverOverrides;
    /// use billiard_contact::{Method, SolverSettings};
    /// let o = SolverOverrides { rtol: Some(1e-8), time_transform: Some(false), ..Default::default() };
    /// let dop853 = SolverSettings::default();
    /// assert!(o.unused(&dop853, false).is_empty());
    /// let unused = o.unused(&dop853, true);
    /// assert_eq!(unused.len(), 1);
    /// assert_eq!(unused[0].0, "time_transform");
    /// assert!(unused[0].1.starts_with("a contact law"));
    /// let cf = dop853.with_method(Method::ClosedForm);
    /// let names = |u: Vec<(&'static str, String)>| u.iter().map(|u| u.0).collect::<Vec<_>>();
    /// assert_eq!(names(o.unused(&cf, false)), ["rtol", "time_transform"]);
    /// assert_eq!(names(o.unused(&cf, true)), ["time_transform"]);
    /// ```
    pub fn unused(&self, settings: &SolverSettings, law: bool) -> Vec<(&'static str, String)> {
        let method = settings.method();
        let by_method = || {
            format!(
                "the method {method} (tolerances act on dopri5 and dop853; the time transform \
                 on the time-stepping methods)"
            )
        };
        let mut v = Vec::new();
        // Under a law the closed form integrates the normal law with dop853 at the run's
        // tolerances.
        let tolerances_unused = method == Method::Rk4 || (method == Method::ClosedForm && !law);
        for (field, given) in [("rtol", self.rtol.is_some()), ("atol", self.atol.is_some())] {
            if given && tolerances_unused {
                v.push((field, by_method()));
            }
        }
        if self.time_transform.is_some() {
            if method == Method::ClosedForm {
                v.push(("time_transform", by_method()));
            } else if law {
                v.push((
                    "time_transform",
                    "a contact law (a law finds the end of the contact as an event, so its \
                     runs step in their own time and need no transform: \
                     docs/contact-law.md#time-stepping)"
                        .to_string(),
                ));
            }
        }
        v
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<String>,
    balls: RawBalls,
    contact: RawContact,
    incoming: RawIncoming,
    solver: Option<SolverOverrides>,
    effects: Option<Effects>,
    table: Option<RawTable>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTable {
    mu: Option<f64>,
    restitution: Option<f64>,
    g: Option<f64>,
    rolling_resistance: Option<f64>,
    spin_decay: Option<f64>,
    height: Option<f64>,
    length: Option<f64>,
    width: Option<f64>,
}

impl RawTable {
    /// The cloth's parameters: the defaults where a key is absent.
    fn build(&self) -> Result<TableParams, Error> {
        let d = TableSettings::default();
        TableParams::new(TableSettings {
            mu: self.mu.unwrap_or(d.mu),
            restitution: self.restitution.unwrap_or(d.restitution),
            g: self.g.unwrap_or(d.g),
            rolling_resistance: self.rolling_resistance.unwrap_or(d.rolling_resistance),
            spin_decay: self.spin_decay.unwrap_or(d.spin_decay),
            height: self.height,
        })
    }

    /// The playing area when both `length` and `width` are given (`None` when neither is).
    fn size(&self) -> Result<Option<TableSize>, Error> {
        match (self.length, self.width) {
            (Some(l), Some(w)) => TableSize::new(l, w).map(Some),
            (None, None) => Ok(None),
            (Some(l), None) => Err(Error::invalid(
                "table.length",
                l,
                "given together with table.width (the playing area's width, m)",
            )),
            (None, Some(w)) => Err(Error::invalid(
                "table.width",
                w,
                "given together with table.length (the playing area's length, m)",
            )),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBalls {
    mass: Option<f64>,
    radius: Option<f64>,
    alpha: Option<f64>,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    a: Option<RawBall>,
    b: Option<RawBall>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBall {
    mass: f64,
    radius: f64,
    alpha: Option<f64>,
}

impl RawBalls {
    /// `[balls]` with mass, radius (and alpha): two identical balls; `[balls.a]` and
    /// `[balls.b]`: balls of their own; never both forms.
    fn build(&self) -> Result<BallPair, Error> {
        let shared = self.mass.is_some() || self.radius.is_some() || self.alpha.is_some();
        let own = |section: &str, b: &RawBall| {
            Ball::in_section(section, b.mass, b.radius, b.alpha.unwrap_or(ALPHA_SOLID))
        };
        match (&self.a, &self.b) {
            (Some(a), Some(b)) if !shared => {
                Ok(BallPair::new(own("balls.a", a)?, own("balls.b", b)?))
            }
            (None, None) => {
                let missing = |key: &str| {
                    Error::invalid(
                        format!("balls.{key}"),
                        "missing",
                        "[balls] with mass and radius (two identical balls), or [balls.a] and \
                         [balls.b]",
                    )
                };
                let mass = self.mass.ok_or_else(|| missing("mass"))?;
                let radius = self.radius.ok_or_else(|| missing("radius"))?;
                let ball = Ball::new(mass, radius, self.alpha.unwrap_or(ALPHA_SOLID))?;
                Ok(BallPair::identical(ball))
            }
            (Some(_), Some(_)) => Err(Error::invalid(
                "balls.mass/radius/alpha",
                "given together with [balls.a] and [balls.b]",
                "one form: [balls] keys for two identical balls, or [balls.a] and [balls.b]",
            )),
            (Some(_), None) | (None, Some(_)) => Err(Error::invalid(
                if self.a.is_some() {
                    "balls.b"
                } else {
                    "balls.a"
                },
                "missing",
                "[balls.a] and [balls.b] together (or [balls] keys for identical balls)",
            )),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    mu: FrictionSpec,
    restitution: Option<f64>,
    impulse: Option<f64>,
    profile: Option<ProfileSpec>,
    law: Option<RawLaw>,
}

/// `[contact.law]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLaw {
    #[serde(deserialize_with = "name")]
    model: LawModel,
    stiffness: Option<f64>,
    #[serde(default, deserialize_with = "optional_name")]
    damping: Option<Damping>,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
}

/// The contact laws by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum LawModel {
    /// Hertz's force k delta^(3/2), with the damping term of `damping`.
    Hertz,
}

impl RawLaw {
    /// The validated law for the balls `balls` of `material` (if given): the stiffness from
    /// exactly one of `stiffness` or the material, the coefficient given or calibrated.
    fn build(&self, balls: &BallPair, material: Option<&Material>) -> Result<ContactLaw, Error> {
        let LawModel::Hertz = self.model;
        let stiffness = match (self.stiffness, material) {
            (Some(k), None) => k,
            (None, Some(m)) => hertz_stiffness((&balls.a, m), (&balls.b, m)).2,
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
        let damping = self.damping.unwrap_or(Damping::None);
        match (self.coefficient, self.restitution, self.at_speed) {
            (c, None, None) => ContactLaw::new(stiffness, damping, c.unwrap_or(0.0)),
            (None, Some(e), Some(v)) => {
                ContactLaw::calibrated(stiffness, damping, e, v, 0.5 * pair_mass(balls))
            }
            (Some(c), Some(e), _) => Err(Error::invalid(
                COEFFICIENT_FIELD,
                format!("{c} together with {RESTITUTION_FIELD} = {e}"),
                "one of them: the coefficient, or the restitution (with at_speed) it is \
                 calibrated to",
            )),
            (_, None, Some(v)) => Err(Error::invalid(
                RESTITUTION_FIELD,
                format!("missing, with {AT_SPEED_FIELD} = {v}"),
                "given together with at_speed: the restitution the law has at that speed",
            )),
            (None, Some(e), None) => Err(Error::invalid(
                AT_SPEED_FIELD,
                format!("missing, with {RESTITUTION_FIELD} = {e}"),
                "given together with restitution: the relative approach speed (m/s) at which \
                 the law has it",
            )),
        }
    }
}

/// How a scene's contact sets the normal force: a prescribed profile, or a law.
enum ForceSource<'a> {
    Profile(&'a ProfileSpec),
    Law(&'a RawLaw),
}

impl RawContact {
    /// Exactly one of `[contact.profile]` or `[contact.law]`; a law without `restitution` or
    /// `impulse` (it decides the impulse).
    fn force_source(&self) -> Result<ForceSource<'_>, Error> {
        match (&self.profile, &self.law) {
            (Some(p), None) => Ok(ForceSource::Profile(p)),
            (None, Some(law)) => {
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
                Ok(ForceSource::Law(law))
            }
            (Some(_), Some(_)) => Err(Error::invalid(
                "contact.law",
                "given together with [contact.profile]",
                "one of them: [contact.profile] prescribes the force, [contact.law] makes it \
                 from the compression",
            )),
            (None, None) => Err(Error::invalid(
                "contact.profile",
                "missing",
                "a section [contact.profile] (the force's shape and duration), or \
                 [contact.law] (the force from the compression)",
            )),
        }
    }
}

/// What `contact.mu` accepts.
const MU_ACCEPTED: &str = "a number >= 0, or { model = \"speed-dependent\", a = .., b = .., \
     c = .., evaluate = \"along-contact\" (default) or \"initial\" }";

/// `contact.mu` as written: a number (constant friction) or a table naming the model. Its
/// values are checked by [`FrictionSpec::build`], through [`Friction`]'s constructors.
#[derive(Debug, Clone, Copy, PartialEq)]
enum FrictionSpec {
    /// `mu = 0.06`.
    Constant(f64),
    /// `mu = { model = "speed-dependent", a = .., b = .., c = .., evaluate = .. }`.
    Model(FrictionModelSpec),
}

/// `contact.mu` as a table.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct FrictionModelSpec {
    #[serde(deserialize_with = "name")]
    model: FrictionModel,
    a: f64,
    b: f64,
    c: f64,
    #[serde(default, deserialize_with = "optional_name")]
    evaluate: Option<Evaluate>,
}

/// The friction models by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum FrictionModel {
    /// mu(S) = a + b exp(-c S).
    SpeedDependent,
}

/// A number or a table, told apart by the TOML value's type. (serde's untagged enums
/// would do the same but replace the inner error, e.g. a misspelt `b`, by "did not match
/// any variant"; here the table's own errors come through with their key and line.)
impl<'de> Deserialize<'de> for FrictionSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NumberOrTable;
        impl<'de> Visitor<'de> for NumberOrTable {
            type Value = FrictionSpec;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(MU_ACCEPTED)
            }
            fn visit_f64<E: de::Error>(self, mu: f64) -> Result<FrictionSpec, E> {
                Ok(FrictionSpec::Constant(mu))
            }
            fn visit_i64<E: de::Error>(self, mu: i64) -> Result<FrictionSpec, E> {
                Ok(FrictionSpec::Constant(mu as f64))
            }
            fn visit_u64<E: de::Error>(self, mu: u64) -> Result<FrictionSpec, E> {
                Ok(FrictionSpec::Constant(mu as f64))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<FrictionSpec, A::Error> {
                FrictionModelSpec::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(FrictionSpec::Model)
            }
        }
        deserializer.deserialize_any(NumberOrTable)
    }
}

/// A value of a unit-variant enum, given by its name: a string first, so that another
/// type is reported as "expected a string" (TOML's own enum reading says only "wanted
/// string or table"), then the variant of that name.
fn name<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<T, D::Error> {
    let name = String::deserialize(deserializer)?;
    T::deserialize(de::IntoDeserializer::<D::Error>::into_deserializer(name))
}

/// [`name`] of an optional key.
fn optional_name<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    name(deserializer).map(Some)
}

impl FrictionSpec {
    /// The validated friction.
    fn build(self) -> Result<Friction, Error> {
        match self {
            FrictionSpec::Constant(mu) => Friction::constant(mu),
            FrictionSpec::Model(FrictionModelSpec {
                model: FrictionModel::SpeedDependent,
                a,
                b,
                c,
                evaluate,
            }) => Ok(Friction::speed_dependent(a, b, c)?.evaluated(evaluate.unwrap_or_default())),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawIncoming {
    cm: Option<RawCm>,
    lab: Option<RawLab>,
}

impl RawIncoming {
    /// Exactly one of the two frames, every component finite.
    fn build(self) -> Result<Incoming, Error> {
        match (self.cm, self.lab) {
            (Some(cm), None) => Ok(Incoming::Cm(CmState::new(
                vec3("incoming.cm.u", cm.u)?,
                vec3("incoming.cm.omega_a", cm.omega_a.unwrap_or_default())?,
                vec3("incoming.cm.omega_b", cm.omega_b.unwrap_or_default())?,
            ))),
            (None, Some(lab)) => Ok(Incoming::Lab(LabScene {
                a: lab_ball("incoming.lab.a", &lab.a)?,
                b: lab_ball("incoming.lab.b", &lab.b)?,
                up: vec3("incoming.lab.up", lab.up.unwrap_or([0.0, 0.0, 1.0]))?,
            })),
            (Some(_), Some(_)) => Err(Error::invalid(
                "incoming",
                "both [incoming.cm] and [incoming.lab]",
                "exactly one of [incoming.cm] or [incoming.lab]",
            )),
            (None, None) => Err(Error::invalid(
                "incoming",
                "empty",
                "a section [incoming.cm] (u, omega_a, omega_b) or [incoming.lab] (a, b, up)",
            )),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCm {
    u: [f64; 3],
    omega_a: Option<[f64; 3]>,
    omega_b: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLab {
    a: RawLabBall,
    b: RawLabBall,
    up: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLabBall {
    position: [f64; 3],
    velocity: [f64; 3],
    spin: Option<[f64; 3]>,
}

impl Scene {
    /// Reads and validates a scene file; relative profile files resolve beside it.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io_doing(path, "cannot read the scene file", e))?;
        let base = path.parent().unwrap_or(Path::new("."));
        Scene::parse(&text, base, Some(path))
    }

    /// The built-in default scene.
    pub fn default_scene() -> Self {
        Scene::parse(DEFAULT_SCENE, Path::new("data/scenes"), None)
            .expect("the embedded default scene is valid")
    }

    /// Parses scene text; `base` resolves relative file names, `source` names the file.
    pub fn parse(text: &str, base: &Path, source: Option<&Path>) -> Result<Self, Error> {
        let shown = source
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("<built-in scene>"));
        let raw: RawScene = serde_path_to_error::deserialize(toml::Deserializer::new(text))
            .map_err(|e| Error::Scene {
                path: shown.clone(),
                message: explain_toml_error(text, &e),
            })?;
        let balls = raw.balls.build()?;
        let material = material_of(&raw.balls)?;
        let friction = raw.contact.mu.build()?;
        let force = raw.contact.force_source()?;
        let impulse =
            ImpulseRule::from_either("contact.", raw.contact.restitution, raw.contact.impulse)?
                .unwrap_or(ImpulseRule::ELASTIC);
        let law = match force {
            ForceSource::Law(law) => Some(law.build(&balls, material.as_ref())?),
            ForceSource::Profile(spec) => {
                check_duration_source(spec, material.as_ref())?;
                None
            }
        };
        // Without the material the profile is built here, before the incoming state (whose
        // errors come second); with it, or with a law, once the approach speed is known.
        let given = match (&force, material) {
            (ForceSource::Profile(spec), None) => Some(spec.build(base)?),
            _ => None,
        };
        let incoming = raw.incoming.build()?;
        let solver_given = raw.solver.unwrap_or_default();
        let solver = solver_given.apply(&SolverSettings::default())?;
        let contact = Contact { friction, impulse };
        let effects = raw.effects.unwrap_or_default();
        let profile = match (given, &force, &law) {
            (Some(p), _, _) => p,
            (None, _, Some(law)) => law_time_unit(law, &balls, &incoming)?,
            (None, ForceSource::Profile(spec), None) => {
                let mat = material
                    .as_ref()
                    .expect("without the material the profile is built");
                let (cm, _) = incoming.to_cm(&balls)?;
                let c = Collision::new(balls, contact, effects, cm)?;
                let hertz = HertzContact::of_pair(&balls, mat, c.incoming.u_cm.x)?;
                spec.build_with(base, Some(hertz.duration))?
            }
            (None, ForceSource::Law(_), None) => unreachable!("a law section builds the law"),
        };
        let scene = Scene {
            name: raw.name.unwrap_or_else(|| {
                source
                    .and_then(|p| p.file_stem())
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "scene".into())
            }),
            balls,
            material,
            contact,
            profile,
            law,
            incoming,
            solver,
            solver_given,
            effects,
            source: source.map(Path::to_path_buf),
            table: raw.table.as_ref().map(RawTable::build).transpose()?,
            table_size: raw
                .table
                .as_ref()
                .map(RawTable::size)
                .transpose()?
                .flatten(),
        };
        // Validate the geometry and the impulse now, so a bad scene fails at load.
        scene.collision()?;
        scene.cloth()?;
        Ok(scene)
    }

    /// The cloth under the balls when the effect `table` is on (`None` when off): needs a
    /// lab scene whose line of centres is horizontal, both centres r above the cloth.
    pub fn cloth(&self) -> Result<Option<Table>, Error> {
        match &self.incoming {
            Incoming::Lab(lab) => self.cloth_under(lab),
            Incoming::Cm(_) if self.effects.table => Err(table_needs_lab_scene()),
            Incoming::Cm(_) => Ok(None),
        }
    }

    /// The cloth under the balls of the lab scene `lab` when the effect `table` is on
    /// (`None` when off).
    pub fn cloth_under(&self, lab: &LabScene) -> Result<Option<Table>, Error> {
        if !self.effects.table {
            return Ok(None);
        }
        Table::new(
            self.table.unwrap_or_default(),
            lab.up,
            [lab.a.position, lab.b.position],
            [self.balls.a.radius(), self.balls.b.radius()],
        )
        .map(Some)
    }

    /// The collision in the centre-of-mass frame; for lab scenes also the frame and the
    /// lab scene.
    pub fn collision(&self) -> Result<(Collision, Option<LabFrame<'_>>), Error> {
        let (cm, lab) = self.incoming.to_cm(&self.balls)?;
        Ok((
            Collision::new(self.balls, self.contact, self.effects, cm)?,
            lab,
        ))
    }

    /// Hertz's contact of the balls' material at the scene's approach speed, when the scene
    /// gives the material for a profile (`None` otherwise, and with a contact law): the profile's duration is its contact time.
    pub fn hertz(&self) -> Result<Option<HertzContact>, Error> {
        let (Some(material), None) = (&self.material, &self.law) else {
            return Ok(None);
        };
        let (c, _) = self.collision()?;
        HertzContact::of_pair(&self.balls, material, c.incoming.u_cm.x).map(Some)
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
    let (cm, _) = incoming.to_cm(balls)?;
    let u0 = cm.u_cm.x;
    if u0.is_nan() || u0 <= 0.0 {
        return Err(Error::invalid(
            "incoming",
            format!("a normal speed U(0) = {u0} m/s with [contact.law]"),
            "approaching balls (U(0) > 0): a contact law needs a contact to make",
        ));
    }
    let (_, tau) = elastic_impact(law.stiffness(), 0.5 * pair_mass(balls), 2.0 * u0);
    Ok(Profile::Hertz(Hertz::new(tau)?))
}

/// The balls' material, when `[balls]` gives it: `youngs_modulus` and `poisson_ratio`
/// together, or neither.
fn material_of(balls: &RawBalls) -> Result<Option<Material>, Error> {
    match (balls.youngs_modulus, balls.poisson_ratio) {
        (Some(e), Some(nu)) => Material::new(e, nu).map(Some),
        (None, None) => Ok(None),
        (Some(e), None) => Err(Error::invalid(
            POISSON_RATIO_FIELD,
            format!("missing, with {YOUNGS_MODULUS_FIELD} = {e}"),
            "given together with balls.youngs_modulus (the material needs both)",
        )),
        (None, Some(nu)) => Err(Error::invalid(
            YOUNGS_MODULUS_FIELD,
            format!("missing, with {POISSON_RATIO_FIELD} = {nu}"),
            "given together with balls.poisson_ratio (the material needs both)",
        )),
    }
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
            crate::profile::DURATION_FIELD,
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

/// The effect `table` in a centre-of-mass scene.
pub(crate) fn table_needs_lab_scene() -> Error {
    Error::invalid(
        "effects.table",
        true,
        "a scene with [incoming.lab]: the table needs the balls' positions and `up` \
         (the centre-of-mass frame has no cloth)",
    )
}

fn vec3(field: &str, v: [f64; 3]) -> Result<Vector3<f64>, Error> {
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return Err(Error::invalid(
                format!("{field}[{i}]"),
                x,
                "a finite number",
            ));
        }
    }
    Ok(Vector3::from(v))
}

fn lab_ball(field: &str, b: &RawLabBall) -> Result<LabBall, Error> {
    Ok(LabBall {
        position: vec3(&format!("{field}.position"), b.position)?,
        velocity: vec3(&format!("{field}.velocity"), b.velocity)?,
        spin: vec3(&format!("{field}.spin"), b.spin.unwrap_or_default())?,
    })
}

/// The TOML error in one line: where (line, column), which field (its dotted path, as in
/// the scene file), what is wrong and what is accepted, with a suggestion for a misspelt
/// key or name at any depth.
fn explain_toml_error(text: &str, e: &serde_path_to_error::Error<toml::de::Error>) -> String {
    let inner = e.inner();
    let plain = inner
        .message()
        .trim()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let at = inner
        .span()
        .map(|span| {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            format!("line {line}, column {col}: ")
        })
        .unwrap_or_default();
    if text.parse::<toml::Table>().is_err() {
        return not_a_scene(text, &at, &plain);
    }
    let path = e.path().to_string();
    // The TOML table (section or inline table) where the error is.
    let section = if path.is_empty() || path == "." {
        None
    } else {
        Some(path)
    };
    // The path of an unknown key already ends with it.
    let join = |key: &str| match &section {
        Some(t) if t == key || t.ends_with(&format!(".{key}")) => t.clone(),
        Some(t) => format!("{t}.{key}"),
        None => key.to_string(),
    };
    // unknown field `x`, expected one of `a`, `b` / unknown variant `x`, expected ...
    for what in ["field", "variant"] {
        if let Some(rest) = plain.strip_prefix(&format!("unknown {what} `")) {
            if let Some((name, expected)) = rest.split_once('`') {
                let candidates: Vec<&str> = expected
                    .split('`')
                    .enumerate()
                    .filter(|(i, _)| i % 2 == 1)
                    .map(|(_, s)| s)
                    .collect();
                let hint = did_you_mean(name, &candidates);
                return if what == "field" {
                    let expected = expected.trim_start_matches(',').trim();
                    format!("{at}{}: unknown key, {expected}{hint}", join(name))
                } else {
                    // Names are values: listed as they are written, without backticks.
                    let field = section.clone().unwrap_or_else(|| "value".into());
                    let names = match candidates.as_slice() {
                        [one] => one.to_string(),
                        many => format!("one of {}", many.join(", ")),
                    };
                    format!("{at}{field} = \"{name}\": unknown name, expected {names}{hint}")
                };
            }
        }
    }
    if let Some(rest) = plain.strip_prefix("missing field `") {
        if let Some((name, _)) = rest.split_once('`') {
            return match &section {
                None => format!("missing section [{name}]: a scene needs [balls], [contact], [contact.profile] and [incoming.cm] or [incoming.lab]"),
                Some(_) => format!("{at}{}: missing (required)", join(name)),
            };
        }
    }
    let plain = plain
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a whole number in [0, 4294967295]");
    match &section {
        Some(t) => format!("{at}{t}: {plain}"),
        None => format!("{at}{plain}"),
    }
}

/// The error for text that is not TOML: where the parser stopped and why; for text without
/// a scene's sections also that it does not look like a scene file, and what one is (a CSV,
/// e.g. a batch input, is told so).
fn not_a_scene(text: &str, at: &str, plain: &str) -> String {
    if ["[balls]", "[contact", "[incoming"]
        .iter()
        .any(|section| text.contains(section))
    {
        return format!("{at}{plain} (not valid TOML)");
    }
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    let csv = first.contains(',') && !first.contains('=') && !first.trim_start().starts_with('[');
    let what = if csv {
        "this looks like CSV (a batch input goes to `billiard-contact batch`), not a scene file"
    } else {
        "this does not look like a scene file"
    };
    format!(
        "{at}{plain}: {what}; a scene is TOML with [balls], [contact], [contact.profile] and \
         [incoming.cm] or [incoming.lab] (docs/formats.md#scene-file-toml)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::FrictionLaw;

    #[test]
    fn default_scene_parses() {
        let s = Scene::default_scene();
        assert!(matches!(s.incoming, Incoming::Lab(_)));
        assert_eq!(s.solver, SolverSettings::default());
    }

    /// The scene with `contact.mu` replaced by `mu`, parsed.
    fn with_mu(mu: &str) -> Result<Scene, Error> {
        let text = DEFAULT_SCENE.replacen("mu = 0.06", &format!("mu = {mu}"), 1);
        assert_ne!(text, DEFAULT_SCENE);
        Scene::parse(&text, Path::new("."), None)
    }

    #[test]
    fn typed_mu_takes_a_number_or_the_speed_dependent_model() {
        assert_eq!(
            with_mu("0.25").unwrap().contact.friction,
            Friction::constant(0.25).unwrap()
        );
        // A TOML integer is a number too.
        assert_eq!(
            with_mu("0").unwrap().contact.friction,
            Friction::constant(0.0).unwrap()
        );
        let s = with_mu("{ model = \"speed-dependent\", a = 0.01, b = 0.1, c = 1 }").unwrap();
        assert_eq!(
            s.contact.friction.law(),
            FrictionLaw::SpeedDependent {
                a: 0.01,
                b: 0.1,
                c: 1.0,
                evaluate: Evaluate::AlongContact,
            }
        );
        let s = with_mu(
            "{ model = \"speed-dependent\", a = 0.01, b = 0.1, c = 1, evaluate = \"initial\" }",
        )
        .unwrap();
        assert_eq!(
            s.contact.friction,
            Friction::speed_dependent(0.01, 0.1, 1.0)
                .unwrap()
                .evaluated(Evaluate::Initial)
        );
        let e = with_mu(
            "{ model = \"speed-dependent\", a = 0.01, b = 0.1, c = 1, evaluate = \"start\" }",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("contact.mu.evaluate")
                && e.contains("along-contact")
                && e.contains("initial"),
            "{e}"
        );
    }

    #[test]
    fn typed_mu_rejects_other_values_naming_the_key() {
        let e = with_mu("\"x\"").unwrap_err().to_string();
        assert!(e.contains("contact.mu: invalid type: string \"x\""), "{e}");
        assert!(
            e.contains("a number >= 0, or { model = \"speed-dependent\""),
            "{e}"
        );
        let e = with_mu("{ model = \"speed-dependent\", a = 0.01, bb = 0.1, c = 1 }")
            .unwrap_err()
            .to_string();
        assert!(e.contains("contact.mu.bb: unknown key"), "{e}");
        assert!(e.contains("did you mean `b`"), "{e}");
        let e = with_mu("{ model = \"constant\", a = 0.01, b = 0.1, c = 1 }")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("contact.mu.model = \"constant\": unknown name, expected speed-dependent"),
            "{e}"
        );
        // Validation through Friction's constructors, after the types.
        let e = with_mu("{ model = \"speed-dependent\", a = -0.01, b = 0.1, c = 1 }")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "contact.mu.a = -0.01: >= 0");
        let e = with_mu("-0.5").unwrap_err().to_string();
        assert_eq!(e, "contact.mu = -0.5: mu >= 0");
    }

    #[test]
    fn method_is_typed() {
        let with = |m: &str| {
            let text = format!("{DEFAULT_SCENE}\n[solver]\nmethod = {m}\n");
            Scene::parse(&text, Path::new("."), None)
        };
        assert_eq!(with("\"rk4\"").unwrap().solver.method(), Method::Rk4);
        let e = with("\"euler\"").unwrap_err().to_string();
        assert!(
            e.contains(
                "solver.method = \"euler\": unknown name, expected one of closed-form, rk4, \
                 dopri5, dop853"
            ),
            "{e}"
        );
        let e = with("3").unwrap_err().to_string();
        assert!(
            e.contains("solver.method: invalid type: integer `3`"),
            "{e}"
        );
    }
}

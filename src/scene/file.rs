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
//! # tangential = "rigid"   # rigid (default: the stick rule) | mindlin (Mindlin's spring,
//!                          # with [contact.law] and the balls' material: docs/tangential.md)
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

use crate::base::error::Error;
use crate::base::fields::{POISSON_RATIO_FIELD, YOUNGS_MODULUS_FIELD};
use crate::base::names::did_you_mean;
use crate::model::contact_law::Damping;
use crate::model::effects::Effects;
use crate::model::frame::LabScene;
use crate::model::material::Material;
use crate::model::params::{Ball, BallPair, Evaluate, Friction, ALPHA_SOLID};
use crate::model::state::{CmState, LabBall};
use crate::profile::spec::ProfileSpec;
use crate::scene::builder::{ForceSpec, LawSpec, SceneBuilder};
use crate::scene::overrides::{name, optional_name, SolverOverrides};
use crate::scene::types::{Incoming, PlaneIncoming, Scene, TangentialLaw};
use crate::table_phase::params::{TableParams, TableSettings, TableSize};
use nalgebra::Vector3;
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// The built-in default scene (`data/scenes/default.toml`): the paper's rolling ball
/// striking a ball at rest, at a 30 degree cut.
pub(crate) const DEFAULT_SCENE: &str = include_str!("../../data/scenes/default.toml");

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
    plane: Option<RawPlane>,
}

/// `[plane]`: a plane as the target instead of ball B (docs/plane.md).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlane {
    normal: V3,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
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
        let own = |section: &str, b: &RawBall| {
            Ball::in_section(section, b.mass, b.radius, b.alpha.unwrap_or(ALPHA_SOLID))
        };
        SceneBuilder::balls(
            [self.mass, self.radius, self.alpha],
            self.a.as_ref().map(|a| own("balls.a", a)),
            self.b.as_ref().map(|b| own("balls.b", b)),
        )
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
    #[serde(default, deserialize_with = "optional_name")]
    tangential: Option<TangentialLaw>,
}

/// `[contact.law]` as written (also a cluster scene's, `scene::cluster`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLaw {
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
    /// The law as the builder takes it.
    pub(crate) fn spec(&self) -> LawSpec {
        let LawModel::Hertz = self.model;
        LawSpec {
            stiffness: self.stiffness,
            damping: self.damping.unwrap_or(Damping::None),
            coefficient: self.coefficient,
            restitution: self.restitution,
            at_speed: self.at_speed,
        }
    }
}

impl RawContact {
    /// Exactly one of `[contact.profile]` or `[contact.law]`.
    fn force(&self) -> Result<ForceSpec, Error> {
        match (&self.profile, &self.law) {
            (Some(p), None) => Ok(ForceSpec::Profile(p.clone())),
            (None, Some(law)) => Ok(ForceSpec::Law(law.spec())),
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
    plane: Option<RawPlaneBall>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlaneBall {
    velocity: V3,
    spin: Option<V3>,
}

impl RawIncoming {
    /// Exactly one of the two frames, every component finite; `[incoming.plane]` exactly
    /// when the scene has `[plane]`.
    fn build(self, plane: Option<&RawPlane>) -> Result<Incoming, Error> {
        match (plane, self.plane) {
            (Some(p), Some(ball)) => {
                if self.cm.is_some() || self.lab.is_some() {
                    return Err(Error::invalid(
                        "incoming",
                        "[incoming.plane] together with [incoming.cm] or [incoming.lab]",
                        "only [incoming.plane] in a scene with [plane]",
                    ));
                }
                let normal = vec3("plane.normal", p.normal)?;
                let length = normal.norm();
                if !(length > 0.0 && length.is_finite()) {
                    return Err(Error::invalid(
                        "plane.normal",
                        format!("{:?}", p.normal.0),
                        "a non-zero direction, out of the plane towards the ball",
                    ));
                }
                return Ok(Incoming::Plane(PlaneIncoming {
                    normal: normal / length,
                    material: plane_material(p)?,
                    velocity: vec3("incoming.plane.velocity", ball.velocity)?,
                    spin: vec3("incoming.plane.spin", ball.spin.unwrap_or_default())?,
                }));
            }
            (Some(_), None) => {
                return Err(Error::invalid(
                    "incoming.plane",
                    "missing, with [plane]",
                    "a section [incoming.plane] (velocity, spin) for the ball meeting the plane",
                ))
            }
            (None, Some(_)) => {
                return Err(Error::invalid(
                    "plane",
                    "missing, with [incoming.plane]",
                    "a section [plane] (normal, and optionally youngs_modulus, poisson_ratio)",
                ))
            }
            (None, None) => {}
        }
        match (self.cm, self.lab) {
            (Some(cm), None) => Ok(Incoming::Cm(CmState::new(
                vec3("incoming.cm.u", cm.u)?,
                vec3("incoming.cm.omega_a", cm.omega_a.unwrap_or_default())?,
                vec3("incoming.cm.omega_b", cm.omega_b.unwrap_or_default())?,
            ))),
            (None, Some(lab)) => Ok(Incoming::Lab(LabScene {
                a: lab_ball("incoming.lab.a", &lab.a)?,
                b: lab_ball("incoming.lab.b", &lab.b)?,
                up: vec3("incoming.lab.up", lab.up.unwrap_or(V3([0.0, 0.0, 1.0])))?,
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
    u: V3,
    omega_a: Option<V3>,
    omega_b: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLab {
    a: RawLabBall,
    b: RawLabBall,
    up: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLabBall {
    position: V3,
    velocity: V3,
    spin: Option<V3>,
}

/// Three numbers of a scene file (a vector, x y z): exactly three. serde's own arrays take
/// the first three of a longer list and drop the rest without a word (`u = [0.5, 0.25, 0,
/// 7]` ran as (0.5, 0.25, 0)).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct V3(pub(crate) [f64; 3]);

impl<'de> Deserialize<'de> for V3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v: Vec<f64> = Vec::deserialize(d)?;
        <[f64; 3]>::try_from(v.as_slice())
            .map(V3)
            .map_err(|_| de::Error::invalid_length(v.len(), &"an array of length 3, [x, y, z]"))
    }
}

/// Whether scene text is a cushion scene (`scene::cushion`): it has a top-level `[cushion]`
/// table. Text that is not TOML is not (the two-ball reader then explains what is wrong).
pub fn is_cushion_scene(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.get("cushion").is_some_and(toml::Value::is_table))
}

/// Whether scene text is a cluster scene (`scene::cluster`): its `balls` is an array of
/// tables (`[[balls]]`), not the two-ball `[balls]` table. Text that is not TOML is not.
pub fn is_cluster_scene(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.get("balls").is_some_and(toml::Value::is_array))
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
        if is_cushion_scene(text) {
            return Err(Error::Scene {
                path: shown,
                message: "a cushion scene ([cushion], docs/cushion.md): `run` resolves it, \
                          `rebound` sweeps its incidence, `batch --scene` runs its rows; \
                          this needs a scene of two balls or a plane"
                    .into(),
            });
        }
        if is_cluster_scene(text) {
            return Err(Error::Scene {
                path: shown,
                message: "a cluster scene ([[balls]], docs/cluster.md): `run` resolves it; \
                          this needs a scene of two balls or a plane"
                    .into(),
            });
        }
        let raw: RawScene = serde_path_to_error::deserialize(toml::Deserializer::new(text))
            .map_err(|e| Error::Scene {
                path: shown.clone(),
                message: explain_toml_error(text, &e),
            })?;
        let balls = raw.balls.build()?;
        let material = material_of(&raw.balls)?;
        let friction = raw.contact.mu.build()?;
        let force = raw.contact.force()?;
        let mut builder = SceneBuilder::new(
            balls,
            friction,
            Incoming::Cm(CmState::new(
                Vector3::zeros(),
                Vector3::zeros(),
                Vector3::zeros(),
            )),
        )
        .name(raw.name.unwrap_or_else(|| {
            source
                .and_then(|p| p.file_stem())
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "scene".into())
        }))
        .force(force)
        .tangential(raw.contact.tangential.unwrap_or_default())
        .solver(raw.solver.unwrap_or_default())
        .effects(raw.effects.unwrap_or_default())
        .files_relative_to(base)
        .source(source)
        .read(
            raw.incoming.build(raw.plane.as_ref()),
            raw.table.as_ref().map(RawTable::build).transpose(),
            raw.table
                .as_ref()
                .map(RawTable::size)
                .transpose()
                .map(Option::flatten),
        );
        if let Some(m) = material {
            builder = builder.material(m);
        }
        if let Some(e) = raw.contact.restitution {
            builder = builder.restitution(e);
        }
        if let Some(p) = raw.contact.impulse {
            builder = builder.impulse(p);
        }
        builder.build()
    }
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

/// The plane's material, when `[plane]` gives it: both keys or neither.
fn plane_material(p: &RawPlane) -> Result<Option<Material>, Error> {
    match (p.youngs_modulus, p.poisson_ratio) {
        (Some(e), Some(nu)) => Material::in_section("plane", e, nu).map(Some),
        (None, None) => Ok(None),
        (Some(e), None) => Err(Error::invalid(
            "plane.poisson_ratio",
            format!("missing, with plane.youngs_modulus = {e}"),
            "given together with plane.youngs_modulus (the material needs both)",
        )),
        (None, Some(nu)) => Err(Error::invalid(
            "plane.youngs_modulus",
            format!("missing, with plane.poisson_ratio = {nu}"),
            "given together with plane.poisson_ratio (the material needs both)",
        )),
    }
}

/// The vector `v` of the field `field`, every component finite (else an error naming
/// `field[i]`).
pub(crate) fn vec3(field: &str, v: V3) -> Result<Vector3<f64>, Error> {
    let v = v.0;
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
pub(crate) fn explain_toml_error(
    text: &str,
    e: &serde_path_to_error::Error<toml::de::Error>,
) -> String {
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
    use crate::base::method::Method;
    use crate::base::settings::SolverSettings;
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

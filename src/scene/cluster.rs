//! Cluster scenes: 2 to 22 balls resolved together (docs/cluster.md; the keys in
//! docs/formats.md#cluster-scene). A scene whose `balls` is an array of tables is one.
//!
//! ```toml
//! name = "Newton's cradle, 3 balls"
//! [[balls]]                   # one table per ball, in order (balls[0], balls[1], ...)
//! mass = 0.17                 # kg
//! radius = 0.028575           # m
//! alpha = 0.4                 # I = alpha m r^2; default 0.4
//! youngs_modulus = 5.4e9      # Pa, with poisson_ratio: this ball's material
//! poisson_ratio = 0.34
//! position = [0.0, 0.0, 0.0]  # m, lab frame
//! velocity = [1.0, 0.0, 0.0]  # m/s
//! spin = [0.0, 0.0, 0.0]      # rad/s; default 0
//! # [[balls]] ... the next ball
//! [contact]
//! mu = 0.0                    # Coulomb's friction at every contact
//! # tangential = "rigid"      # rigid (default: the stick rule) | mindlin (Mindlin's spring at
//!                             # every contact, with every ball's material: docs/cluster.md)
//! [contact.law]               # as a two-ball scene's law (docs/contact-law.md)
//! model = "hertz"
//! # stiffness = 4.5e8         # N/m^1.5, every pair; or the balls' materials (each pair's E*)
//! # damping = "hunt-crossley" # none (default) | hunt-crossley | kuwabara-kono
//! # coefficient = 0.1         # or restitution = 0.93 and at_speed = 1.0
//! # [cloth]                   # optional: every ball rests on the cloth (docs/cluster.md)
//! # youngs_modulus = 5e10     # Pa, with poisson_ratio: the bed's material (slate)
//! # poisson_ratio = 0.25
//! # mu = 0.2                  # Coulomb's friction between ball and cloth; default 0.2
//! # height = -0.028575        # m, the cloth's z; default balls[0]'s z minus its radius
//! # gravity = 9.81            # m/s^2 along -z; default 9.81
//! # damping = "hunt-crossley" # each ball's contact with the bed: none (default: elastic) |
//!                             # hunt-crossley | kuwabara-kono, as [contact.law] names them
//! # restitution = 0.5         # with at_speed (m/s, the ball's drop speed); or coefficient
//! [solver]                    # optional
//! rtol = 1e-8                 # the kernel's default
//! [effects]                   # optional
//! stick = true
//! ```

use crate::base::error::Error;
use crate::cluster::params::{
    Cluster, ClusterBall, ClusterCloth, ClusterLaw, ClusterTangential, PairDamping,
    CLOTH_DEFAULT_GRAVITY, CLOTH_DEFAULT_MU,
};
use crate::cluster::resolve::{
    resolve_cluster, resolve_cluster_traced, ClusterOutcome, ClusterSettings, ClusterTrace,
    StopReason, CLUSTER_DEFAULT_RTOL,
};
use crate::model::contact_law::{Damping, STIFFNESS_FIELD};
use crate::model::material::Material;
use crate::model::params::{Ball, ALPHA_SOLID};
use crate::scene::builder::{LawSpec, TANGENTIAL_FIELD};
use crate::scene::file::{explain_toml_error, vec3, RawLaw, V3};
use crate::scene::overrides::optional_name;
use crate::scene::types::TangentialLaw;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The field a cluster scene's tolerance is named by (as in the scene file).
pub(crate) const CLUSTER_RTOL_FIELD: &str = "solver.rtol";

/// A cluster scene: the validated balls and laws, and how to run them.
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterScene {
    /// The scene's name (`name`, else the file's stem).
    pub name: String,
    /// The balls, the law of every pair, mu (validated by [`Cluster::new`]).
    pub cluster: Cluster,
    /// Each ball's material, in order, when the stiffness comes from them.
    pub materials: Option<Vec<Material>>,
    /// Tolerance and the stick rule (`[solver] rtol`, `[effects] stick`).
    pub settings: ClusterSettings,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClusterScene {
    name: Option<String>,
    balls: Vec<RawClusterBall>,
    contact: RawClusterContact,
    solver: Option<RawClusterSolver>,
    effects: Option<RawClusterEffects>,
    cloth: Option<RawCloth>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCloth {
    youngs_modulus: f64,
    poisson_ratio: f64,
    mu: Option<f64>,
    height: Option<f64>,
    gravity: Option<f64>,
    #[serde(default, deserialize_with = "optional_name")]
    damping: Option<Damping>,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
}

impl RawCloth {
    /// The damping of every ball's contact with the cloth, from the keys `[contact.law]`
    /// names the same way (elastic by default), its errors naming `cloth.<key>`.
    fn damping(&self) -> Result<PairDamping, Error> {
        pair_damping(&LawSpec {
            stiffness: None,
            damping: self.damping.unwrap_or(Damping::None),
            coefficient: self.coefficient,
            restitution: self.restitution,
            at_speed: self.at_speed,
        })
        .map_err(|e| e.moved("contact.law.", "cloth."))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClusterBall {
    mass: f64,
    radius: f64,
    alpha: Option<f64>,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    position: V3,
    velocity: V3,
    spin: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClusterContact {
    mu: f64,
    law: RawLaw,
    #[serde(default, deserialize_with = "optional_name")]
    tangential: Option<TangentialLaw>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClusterSolver {
    rtol: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClusterEffects {
    stick: Option<bool>,
}

/// The kernel's error `e` with its fields named as the scene file names them:
/// `cluster.balls[i]` is `balls[i]`, `cluster.mu` is `contact.mu`, `cluster.rtol` is
/// `rtol_field` (`solver.rtol`, or the option that set it).
pub(crate) fn scene_fields(e: Error, rtol_field: &str) -> Error {
    match e {
        Error::InvalidParameter {
            field,
            value,
            expected,
        } => {
            let field = match field.as_str() {
                "cluster.mu" => "contact.mu".to_string(),
                "cluster.rtol" => rtol_field.to_string(),
                "cluster.materials" => "balls".to_string(),
                // Two balls that overlap: their positions.
                other if other.contains(", ") => other
                    .split(", ")
                    .map(|b| format!("{}.position", b.trim_start_matches("cluster.")))
                    .collect::<Vec<_>>()
                    .join(", "),
                other => other.replace("cluster.", ""),
            };
            Error::InvalidParameter {
                field,
                value,
                expected,
            }
        }
        other => other,
    }
}

/// The TOML reader's message `m`, with a missing section explained for a cluster scene.
fn cluster_message(m: String) -> String {
    match m
        .strip_prefix("missing section [")
        .and_then(|r| r.split_once(']'))
    {
        Some((name, _)) => format!(
            "missing section [{name}]: a cluster scene needs [[balls]] (one per ball), \
             [contact] (mu) and [contact.law] (docs/formats.md#cluster-scene)"
        ),
        None => m,
    }
}

/// A ball's material: both keys or neither.
fn material_of(i: usize, b: &RawClusterBall) -> Result<Option<Material>, Error> {
    let section = format!("balls[{i}]");
    match (b.youngs_modulus, b.poisson_ratio) {
        (Some(e), Some(nu)) => Material::in_section(&section, e, nu).map(Some),
        (None, None) => Ok(None),
        (Some(e), None) => Err(Error::invalid(
            format!("{section}.poisson_ratio"),
            format!("missing, with {section}.youngs_modulus = {e}"),
            "given together with youngs_modulus (the material needs both)",
        )),
        (None, Some(nu)) => Err(Error::invalid(
            format!("{section}.youngs_modulus"),
            format!("missing, with {section}.poisson_ratio = {nu}"),
            "given together with poisson_ratio (the material needs both)",
        )),
    }
}

/// The damping of every pair from `[contact.law]`: the coefficient given (0 when a damping
/// is named without one), or the restitution with its speed.
fn pair_damping(spec: &LawSpec) -> Result<PairDamping, Error> {
    match (spec.coefficient, spec.restitution, spec.at_speed) {
        (None, None, None) if spec.damping == Damping::None => Ok(PairDamping::None),
        (c, None, None) => Ok(PairDamping::Coefficient(spec.damping, c.unwrap_or(0.0))),
        (None, Some(e), Some(v)) => Ok(PairDamping::Restitution {
            damping: spec.damping,
            restitution: e,
            at_speed: v,
        }),
        (c, e, v) => Err(crate::scene::builder::calibration_mismatch(c, e, v)),
    }
}

impl ClusterScene {
    /// Reads and validates a cluster scene file.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io_doing(path, "cannot read the scene file", e))?;
        ClusterScene::parse(&text, Some(path))
    }

    /// Parses cluster scene text; `source` names the file in errors and gives the default
    /// name. Every value is checked here, the balls' positions and courses and the pairs'
    /// calibrations too ([`Cluster::new`]).
    ///
    /// ```
    /// use billiard_contact::ClusterScene;
    ///
    /// let ball = |x: f64, v: f64| {
    ///     format!(
    ///         "[[balls]]\nmass = 0.17\nradius = 0.028575\nposition = [{x}, 0, 0]\n\
    ///          velocity = [{v}, 0, 0]\n"
    ///     )
    /// };
    /// let text = ball(0.0, 1.0)
    ///     + &ball(0.05715, 0.0)
    ///     + "[contact]\nmu = 0.0\n[contact.law]\nmodel = \"hertz\"\nstiffness = 4.5e8\n";
    /// let scene = ClusterScene::parse(&text, None)?;
    /// let out = scene.run(&scene.settings, "solver.rtol")?;
    /// // Two equal balls, elastic and head on: the velocities are exchanged.
    /// assert!(out.balls[0].velocity.norm() < 1e-7);
    /// assert!((out.balls[1].velocity.x - 1.0).abs() < 1e-7);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn parse(text: &str, source: Option<&Path>) -> Result<Self, Error> {
        let shown = source
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("<cluster scene>"));
        let raw: RawClusterScene = serde_path_to_error::deserialize(toml::Deserializer::new(text))
            .map_err(|e| Error::Scene {
                path: shown.clone(),
                message: cluster_message(explain_toml_error(text, &e)),
            })?;
        let mut balls = Vec::with_capacity(raw.balls.len());
        let mut materials = Vec::with_capacity(raw.balls.len());
        for (i, b) in raw.balls.iter().enumerate() {
            let section = format!("balls[{i}]");
            let ball =
                Ball::in_section(&section, b.mass, b.radius, b.alpha.unwrap_or(ALPHA_SOLID))?;
            materials.push(material_of(i, b)?);
            balls.push(ClusterBall {
                ball,
                position: vec3(&format!("{section}.position"), b.position)?,
                velocity: vec3(&format!("{section}.velocity"), b.velocity)?,
                spin: vec3(&format!("{section}.spin"), b.spin.unwrap_or_default())?,
            });
        }
        let spec = raw.contact.law.spec();
        let damping = pair_damping(&spec)?;
        let with_material = materials.iter().filter(|m| m.is_some()).count();
        let (law, materials) = match (spec.stiffness, with_material) {
            (Some(k), 0) => {
                let kinds: Vec<Ball> = balls.iter().map(|b| b.ball).collect();
                (ClusterLaw::same_stiffness(k, damping, &kinds)?, None)
            }
            (Some(k), _) => {
                let i = materials.iter().position(Option::is_some).unwrap_or(0);
                return Err(Error::invalid(
                    STIFFNESS_FIELD,
                    format!("{k} together with balls[{i}].youngs_modulus"),
                    "one of them: the stiffness of every pair, or every ball's material it \
                     follows from",
                ));
            }
            (None, n) if n == balls.len() && n > 0 => {
                let all: Vec<Material> = materials.into_iter().flatten().collect();
                (ClusterLaw::Materials(all.clone(), damping), Some(all))
            }
            (None, 0) => {
                return Err(Error::invalid(
                    STIFFNESS_FIELD,
                    "missing",
                    "a stiffness k (N/m^1.5) for every pair, or youngs_modulus and \
                     poisson_ratio for every ball",
                ))
            }
            (None, _) => {
                let i = materials.iter().position(Option::is_none).unwrap_or(0);
                return Err(Error::invalid(
                    format!("balls[{i}].youngs_modulus"),
                    "missing, while other balls give their material",
                    "a material (youngs_modulus and poisson_ratio) for every ball, or none \
                     and contact.law.stiffness",
                ));
            }
        };
        let tangential = raw.contact.tangential.unwrap_or_default();
        if tangential == TangentialLaw::Mindlin && materials.is_none() {
            return Err(Error::invalid(
                TANGENTIAL_FIELD,
                "\"mindlin\" without the balls' material",
                "\"mindlin\" with every ball's youngs_modulus and poisson_ratio (Mindlin's \
                 spring needs the shear moduli), and no contact.law.stiffness; or \"rigid\"",
            ));
        }
        let cluster = Cluster::new(balls, law, raw.contact.mu)
            .and_then(|c| {
                c.with_tangential(match tangential {
                    TangentialLaw::Rigid => ClusterTangential::Rigid,
                    TangentialLaw::Mindlin => ClusterTangential::Mindlin,
                })
            })
            .and_then(|c| match &raw.cloth {
                None => Ok(c),
                Some(cl) => {
                    let first = &c.balls()[0];
                    let cloth = ClusterCloth {
                        height: cl.height.unwrap_or(first.position.z - first.ball.radius()),
                        material: Material::in_section(
                            "cloth",
                            cl.youngs_modulus,
                            cl.poisson_ratio,
                        )?,
                        mu: cl.mu.unwrap_or(CLOTH_DEFAULT_MU),
                        gravity: cl.gravity.unwrap_or(CLOTH_DEFAULT_GRAVITY),
                    };
                    let damping = cl.damping()?;
                    let c = c.with_cloth(cloth)?;
                    if damping == PairDamping::None {
                        Ok(c)
                    } else {
                        c.with_cloth_damping(damping)
                    }
                }
            })
            .map_err(|e| scene_fields(e, CLUSTER_RTOL_FIELD))?;
        // The tolerance's range is the kernel's: `run` refuses a bad one, naming the field.
        let settings = ClusterSettings {
            rtol: raw
                .solver
                .and_then(|s| s.rtol)
                .unwrap_or(CLUSTER_DEFAULT_RTOL),
            stick: raw.effects.and_then(|e| e.stick).unwrap_or(true),
        };
        Ok(ClusterScene {
            name: raw.name.unwrap_or_else(|| {
                source
                    .and_then(|p| p.file_stem())
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "cluster".into())
            }),
            cluster,
            materials,
            settings,
        })
    }

    /// Resolves the cluster with `settings` (the scene's own, or `rtol` overridden by the
    /// option `rtol_field`, which errors then name). A run that ends before every contact
    /// opened (the step control stalled, or the work bound) is an error: nothing partial is
    /// returned.
    pub fn run(
        &self,
        settings: &ClusterSettings,
        rtol_field: &str,
    ) -> Result<ClusterOutcome, Error> {
        ended(resolve_cluster(&self.cluster, settings), rtol_field)
    }

    /// [`ClusterScene::run`] reporting to `trace` (docs/formats.md#the-cluster-trace).
    #[cfg_attr(not(feature = "cli"), allow(dead_code))]
    pub(crate) fn run_traced(
        &self,
        settings: &ClusterSettings,
        rtol_field: &str,
        trace: ClusterTrace<'_>,
    ) -> Result<ClusterOutcome, Error> {
        ended(
            resolve_cluster_traced(&self.cluster, settings, trace),
            rtol_field,
        )
    }
}

/// A run's result as a scene's: the kernel's errors named as the scene names its fields,
/// a run that did not separate an error.
fn ended(out: Result<ClusterOutcome, Error>, rtol_field: &str) -> Result<ClusterOutcome, Error> {
    let out = out.map_err(|e| scene_fields(e, rtol_field))?;
    match out.stop {
        StopReason::Separated => Ok(out),
        stop => Err(Error::ClusterStopped {
            stop: stop_name(stop),
            time: out.time,
            steps: out.stats.steps,
        }),
    }
}

/// A stop reason as the report writes it.
pub(crate) fn stop_name(s: StopReason) -> &'static str {
    match s {
        StopReason::Separated => "separated",
        StopReason::WorkBound => "work-bound",
        StopReason::StepTooSmall => "step-too-small",
    }
}

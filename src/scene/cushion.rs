//! Cushion scenes: one ball meeting a cushion of a pool table instead of ball B
//! (docs/cushion.md, the keys in docs/formats.md#a-ball-against-the-cushion).
//!
//! ```toml
//! name = "stun shot into the rail at 45 degrees"
//! [balls]                  # the ball: mass, radius, alpha (default 0.4)
//! mass = 0.17
//! radius = 0.028575
//! [cushion]
//! height = 0.0366          # m, of the contact above the cloth: r < height < 2r
//! mu_cushion = 0.2         # ball-cushion friction
//! mu_table = 0.2           # ball-cloth friction
//! restitution = 0.85       # in [0, 1]
//! rule = "stronge"         # stronge (work, default) | newton (normal velocity)
//! [incoming.cushion]       # the cushion's frame: x along it, y towards it, z up
//! velocity = [1.0, 1.0, 0.0]
//! spin = [0.0, 0.0, 0.0]   # default 0
//! [solver]                 # optional: dop853 (default) | dopri5 | rk4, rtol, steps
//! ```

use crate::base::error::Error;
use crate::base::settings::SolverSettings;
use crate::cushion::impact::resolve_cushion;
use crate::cushion::outcome::{CushionOutcome, CushionTraceRow};
use crate::cushion::params::{Cushion, CushionRestitution};
use crate::model::params::{Ball, ALPHA_SOLID};
use crate::scene::file::{explain_toml_error, V3};
use crate::scene::overrides::SolverOverrides;
use nalgebra::Vector3;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// A ball meeting a cushion: the ball, the cushion, the incoming state in the cushion's
/// frame (x along the cushion, y towards it, z up) and the solver settings.
#[derive(Debug, Clone, PartialEq)]
pub struct CushionScene {
    /// The scene's name (`name`, else the file's stem).
    pub name: String,
    /// The ball (`[balls]`).
    pub ball: Ball,
    /// The cushion (`[cushion]`).
    pub cushion: Cushion,
    /// The ball's incoming velocity (m/s, `incoming.cushion.velocity`).
    pub velocity: Vector3<f64>,
    /// The ball's incoming spin (rad/s, `incoming.cushion.spin`).
    pub spin: Vector3<f64>,
    /// Solver settings (`[solver]`; default dop853 at rtol 1e-10).
    pub solver: SolverSettings,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCushionScene {
    name: Option<String>,
    balls: RawCushionBall,
    cushion: RawCushion,
    incoming: RawCushionIncoming,
    solver: Option<SolverOverrides>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCushionBall {
    mass: f64,
    radius: f64,
    alpha: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCushion {
    height: f64,
    mu_cushion: f64,
    mu_table: f64,
    restitution: f64,
    rule: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCushionIncoming {
    cushion: RawCushionState,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCushionState {
    velocity: V3,
    spin: Option<V3>,
}

/// The restitution rule by its scene name (`cushion.rule`).
pub(crate) fn rule_named(name: &str) -> Result<CushionRestitution, Error> {
    match name {
        "stronge" => Ok(CushionRestitution::Stronge),
        "newton" => Ok(CushionRestitution::Newton),
        _ => Err(Error::invalid(
            "cushion.rule",
            format!("\"{name}\""),
            "\"stronge\" (the work of restitution is e^2 times that of compression) or \
             \"newton\" (the normal velocity at the cushion ends at -e times its start)",
        )),
    }
}

impl CushionScene {
    /// Reads and validates a cushion scene file.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io_doing(path, "cannot read the scene file", e))?;
        CushionScene::parse(&text, Some(path))
    }

    /// Parses cushion scene text; `source` names the file in errors and gives the default
    /// name.
    ///
    /// ```
    /// use billiard_contact::CushionScene;
    ///
    /// let scene = CushionScene::parse(
    ///     r#"
    ///     [balls]
    ///     mass = 0.17
    ///     radius = 0.028575
    ///     [cushion]
    ///     height = 0.04
    ///     mu_cushion = 0.0
    ///     mu_table = 0.0
    ///     restitution = 0.8
    ///     [incoming.cushion]
    ///     velocity = [0.5, 1.0, 0.0]
    ///     "#,
    ///     None,
    /// )?;
    /// let out = scene.run(&scene.solver, None)?;
    /// // Without friction only the normal part changes: the cloth takes the vertical part of
    /// // the cushion's push, so v_y' = -e v_y and v_x is kept.
    /// assert!((out.v.y + 0.8).abs() < 1e-9 && (out.v.x - 0.5).abs() < 1e-12);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn parse(text: &str, source: Option<&Path>) -> Result<Self, Error> {
        let shown = source
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("<cushion scene>"));
        let raw: RawCushionScene = serde_path_to_error::deserialize(toml::Deserializer::new(text))
            .map_err(|e| Error::Scene {
                path: shown.clone(),
                message: explain_toml_error(text, &e),
            })?;
        let b = &raw.balls;
        let ball = Ball::in_section("balls", b.mass, b.radius, b.alpha.unwrap_or(ALPHA_SOLID))?;
        let c = &raw.cushion;
        let rule = c
            .rule
            .as_deref()
            .map_or(Ok(CushionRestitution::Stronge), rule_named)?;
        let cushion = Cushion::new(c.height, c.mu_cushion, c.mu_table, c.restitution, rule)?;
        let vector = |field: &str, v: [f64; 3]| -> Result<Vector3<f64>, Error> {
            match v.iter().position(|x| !x.is_finite()) {
                Some(i) => Err(Error::invalid(
                    format!("{field}[{i}]"),
                    v[i],
                    "a finite number",
                )),
                None => Ok(Vector3::from(v)),
            }
        };
        let state = &raw.incoming.cushion;
        let scene = CushionScene {
            name: raw.name.unwrap_or_else(|| {
                source
                    .and_then(|p| p.file_stem())
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "cushion".into())
            }),
            ball,
            cushion,
            velocity: vector("incoming.cushion.velocity", state.velocity.0)?,
            spin: vector("incoming.cushion.spin", state.spin.unwrap_or_default().0)?,
            solver: raw
                .solver
                .unwrap_or_default()
                .apply(&SolverSettings::default())?,
        };
        Ok(scene)
    }

    /// Resolves the impact with `settings` (the scene's own, or overridden), streaming the
    /// trace rows to `trace`.
    pub fn run(
        &self,
        settings: &SolverSettings,
        trace: Option<&mut dyn FnMut(&CushionTraceRow)>,
    ) -> Result<CushionOutcome, Error> {
        resolve_cushion(
            &self.ball,
            &self.cushion,
            self.velocity,
            self.spin,
            settings,
            trace,
        )
    }
}

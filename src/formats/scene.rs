//! Scene files (TOML, SI units): the contract users and `data/scenes/` rely on.
//!
//! ```toml
//! name = "rolling cue ball, 30 degree cut"
//! [balls]
//! mass = 0.17        # kg
//! radius = 0.028575  # m
//! alpha = 0.4        # I = alpha m r^2; default 0.4
//! [contact]
//! mu = 0.06          # or { model = "speed-dependent", a = 9.951e-3, b = 0.108, c = 1.088 }
//! restitution = 1.0  # or: impulse = 0.17  (N s); not both; neither: restitution 1
//! [contact.profile]
//! shape = "half-sine"    # half-sine | hertz | sine-power (exponent, default 1.5) | rectangle
//!                        # | tabulated (file = "...", relative to the scene)
//! duration = 2.5e-4      # s
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
//! ```

use crate::error::Error;
use crate::integrator::{Method, SolverSettings, DEFAULT_RTOL, DEFAULT_STEPS};
use crate::model::collision::Collision;
use crate::model::effects::Effects;
use crate::model::frame::{Frame, LabScene};
use crate::model::params::{Ball, Contact, Friction, ImpulseRule, ALPHA_SOLID};
use crate::model::state::{CmState, LabBall};
use crate::profile::{Profile, ProfileSpec};
use crate::table_phase::{Table, TableParams, TableSettings};
use nalgebra::Vector3;
use serde::Deserialize;
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

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name shown in reports.
    pub name: String,
    /// The balls.
    pub ball: Ball,
    /// Friction and impulse rule.
    pub contact: Contact,
    /// Normal-force profile.
    pub profile: Profile,
    /// Incoming state.
    pub incoming: Incoming,
    /// Solver settings (`[solver]`, defaults when absent).
    pub solver: SolverSettings,
    /// Effects (`[effects]`).
    pub effects: Effects,
    /// The file it was read from (`None` for the built-in scene).
    pub source: Option<PathBuf>,
    /// The cloth (`[table]`) as given; `None` when the section is absent (defaults apply
    /// when the effect `table` is on).
    pub table: Option<TableParams>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<String>,
    balls: RawBalls,
    contact: RawContact,
    incoming: RawIncoming,
    solver: Option<RawSolver>,
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
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBalls {
    mass: f64,
    radius: f64,
    alpha: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    mu: toml::Value,
    restitution: Option<f64>,
    impulse: Option<f64>,
    profile: ProfileSpec,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawIncoming {
    cm: Option<RawCm>,
    lab: Option<RawLab>,
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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
    steps: Option<u32>,
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
        let ball = Ball::new(
            raw.balls.mass,
            raw.balls.radius,
            raw.balls.alpha.unwrap_or(ALPHA_SOLID),
        )?;
        let friction = parse_mu(&raw.contact.mu)?;
        let impulse = match (raw.contact.restitution, raw.contact.impulse) {
            (Some(e), None) => ImpulseRule::restitution(e)?,
            (None, Some(p)) => ImpulseRule::explicit(p)?,
            (None, None) => ImpulseRule::restitution(1.0)?,
            (Some(e), Some(p)) => {
                return Err(Error::invalid(
                    "contact.restitution",
                    format!("{e} together with contact.impulse = {p}"),
                    "one of restitution or impulse, not both",
                ))
            }
        };
        let profile = raw.contact.profile.build(base)?;
        let incoming =
            match (raw.incoming.cm, raw.incoming.lab) {
                (Some(cm), None) => Incoming::Cm(CmState::new(
                    vec3("incoming.cm.u", cm.u)?,
                    vec3("incoming.cm.omega_a", cm.omega_a.unwrap_or_default())?,
                    vec3("incoming.cm.omega_b", cm.omega_b.unwrap_or_default())?,
                )),
                (None, Some(lab)) => Incoming::Lab(LabScene {
                    a: lab_ball("incoming.lab.a", &lab.a)?,
                    b: lab_ball("incoming.lab.b", &lab.b)?,
                    up: vec3("incoming.lab.up", lab.up.unwrap_or([0.0, 0.0, 1.0]))?,
                }),
                (Some(_), Some(_)) => {
                    return Err(Error::invalid(
                        "incoming",
                        "both [incoming.cm] and [incoming.lab]",
                        "exactly one of [incoming.cm] or [incoming.lab]",
                    ))
                }
                (None, None) => return Err(Error::invalid(
                    "incoming",
                    "empty",
                    "a section [incoming.cm] (u, omega_a, omega_b) or [incoming.lab] (a, b, up)",
                )),
            };
        let solver = match raw.solver {
            None => SolverSettings::default(),
            Some(s) => {
                let method = match s.method {
                    Some(m) => m.parse::<Method>()?,
                    None => Method::Dop853,
                };
                let rtol = s.rtol.unwrap_or(DEFAULT_RTOL);
                SolverSettings::new(
                    method,
                    rtol,
                    s.atol.unwrap_or(rtol),
                    s.steps.unwrap_or(DEFAULT_STEPS),
                )?
            }
        };
        let scene = Scene {
            name: raw.name.unwrap_or_else(|| {
                source
                    .and_then(|p| p.file_stem())
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "scene".into())
            }),
            ball,
            contact: Contact { friction, impulse },
            profile,
            incoming,
            solver,
            effects: raw.effects.unwrap_or_default(),
            source: source.map(Path::to_path_buf),
            table: match raw.table {
                None => None,
                Some(t) => {
                    let d = TableSettings::default();
                    Some(TableParams::new(TableSettings {
                        mu: t.mu.unwrap_or(d.mu),
                        restitution: t.restitution.unwrap_or(d.restitution),
                        g: t.g.unwrap_or(d.g),
                        rolling_resistance: t.rolling_resistance.unwrap_or(d.rolling_resistance),
                        spin_decay: t.spin_decay.unwrap_or(d.spin_decay),
                        height: t.height,
                    })?)
                }
            },
        };
        // Validate the geometry and the impulse now, so a bad scene fails at load.
        scene.collision()?;
        scene.cloth()?;
        Ok(scene)
    }

    /// The cloth under the balls when the effect `table` is on (`None` when off): needs a
    /// lab scene whose line of centres is horizontal, both centres r above the cloth.
    pub fn cloth(&self) -> Result<Option<Table>, Error> {
        if !self.effects.table {
            return Ok(None);
        }
        match &self.incoming {
            Incoming::Cm(_) => Err(Error::invalid(
                "effects.table",
                true,
                "a scene with [incoming.lab]: the table needs the balls' positions and `up` \
                 (the centre-of-mass frame has no cloth)",
            )),
            Incoming::Lab(lab) => Ok(Some(Table::new(
                self.table.unwrap_or_default(),
                lab.up,
                lab.a.position,
                lab.b.position,
                self.ball.radius,
            )?)),
        }
    }

    /// The collision in the centre-of-mass frame, and the lab frame for lab scenes.
    pub fn collision(&self) -> Result<(Collision, Option<Frame>), Error> {
        let (cm, frame) = match &self.incoming {
            Incoming::Cm(cm) => (*cm, None),
            Incoming::Lab(lab) => {
                let frame = Frame::new(lab, self.ball.radius)?;
                (frame.to_cm(lab), Some(frame))
            }
        };
        Ok((
            Collision::new(self.ball, self.contact, self.effects, cm)?,
            frame,
        ))
    }
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

fn parse_mu(v: &toml::Value) -> Result<Friction, Error> {
    const EXPECTED: &str =
        "a number >= 0, or { model = \"speed-dependent\", a = .., b = .., c = .. }";
    match v {
        toml::Value::Float(x) => Friction::constant(*x),
        toml::Value::Integer(i) => Friction::constant(*i as f64),
        toml::Value::Table(t) => {
            let model = t.get("model").and_then(|m| m.as_str());
            if model != Some("speed-dependent") {
                return Err(Error::invalid(
                    "contact.mu.model",
                    t.get("model")
                        .map(|m| m.to_string())
                        .unwrap_or_else(|| "missing".into()),
                    "\"speed-dependent\" (mu(S) = a + b exp(-c S))",
                ));
            }
            for key in t.keys() {
                const KEYS: [&str; 4] = ["model", "a", "b", "c"];
                if !KEYS.contains(&key.as_str()) {
                    let hint = closest(key, &KEYS)
                        .map(|k| format!(" (did you mean `{k}`?)"))
                        .unwrap_or_default();
                    return Err(Error::invalid(
                        format!("contact.mu.{key}"),
                        t[key].to_string(),
                        format!("no such key: the speed-dependent model takes a, b, c{hint}"),
                    ));
                }
            }
            let get = |k: &str| -> Result<f64, Error> {
                match t.get(k) {
                    Some(toml::Value::Float(x)) => Ok(*x),
                    Some(toml::Value::Integer(i)) => Ok(*i as f64),
                    Some(other) => {
                        Err(Error::invalid(format!("contact.mu.{k}"), other, "a number"))
                    }
                    None => Err(Error::invalid(
                        format!("contact.mu.{k}"),
                        "missing",
                        "a number >= 0",
                    )),
                }
            };
            Friction::speed_dependent(get("a")?, get("b")?, get("c")?)
        }
        other => Err(Error::invalid("contact.mu", other, EXPECTED)),
    }
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
    let path = e.path().to_string();
    let table = if path.is_empty() || path == "." {
        None
    } else {
        Some(path)
    };
    // The path of an unknown key already ends with it.
    let join = |key: &str| match &table {
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
                let hint = closest(name, &candidates)
                    .map(|best| format!(" (did you mean `{best}`?)"))
                    .unwrap_or_default();
                let expected = expected.trim_start_matches(',').trim();
                return if what == "field" {
                    format!("{at}{}: unknown key, {expected}{hint}", join(name))
                } else {
                    let field = table.clone().unwrap_or_else(|| "value".into());
                    format!("{at}{field} = \"{name}\": unknown name, {expected}{hint}")
                };
            }
        }
    }
    if let Some(rest) = plain.strip_prefix("missing field `") {
        if let Some((name, _)) = rest.split_once('`') {
            return match &table {
                None => format!("missing section [{name}]: a scene needs [balls], [contact], [contact.profile] and [incoming.cm] or [incoming.lab]"),
                Some(_) => format!("{at}{}: missing (required)", join(name)),
            };
        }
    }
    let plain = plain
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a whole number in [0, 4294967295]");
    match &table {
        Some(t) => format!("{at}{t}: {plain}"),
        None => format!("{at}{plain}"),
    }
}

/// The candidate within edit distance 2 (or a third of the length) of `word`.
pub(crate) fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let limit = (word.len() / 3).max(2);
    candidates
        .iter()
        .map(|c| (edit_distance(word, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = if ca == *cb {
                prev
            } else {
                1 + prev.min(cur).min(row[j])
            };
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_scene_parses() {
        let s = Scene::default_scene();
        assert!(matches!(s.incoming, Incoming::Lab(_)));
        assert_eq!(s.solver, SolverSettings::default());
    }

    #[test]
    fn misspelt_key_gets_a_suggestion() {
        let text = DEFAULT_SCENE.replace("restitution", "restitutoin");
        let e = Scene::parse(&text, Path::new("."), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `restitution`"), "{e}");
    }

    #[test]
    fn both_restitution_and_impulse_is_an_error() {
        let text = DEFAULT_SCENE.replace("restitution = 1.0", "restitution = 1.0\nimpulse = 0.3");
        let e = Scene::parse(&text, Path::new("."), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("not both"), "{e}");
    }
}

//! A cluster scene's outputs (docs/formats.md#the-cluster-report): the JSON report and its
//! text summary, with the run's balances (momentum, energy against heat).

use crate::base::error::Error;
use crate::base::number::{count, decimal, sci, shortest, si};
use crate::cluster::params::{Cluster, ClusterBall, PairDamping};
use crate::cluster::resolve::{ClusterOutcome, ClusterSettings};
use crate::model::params::Ball;
use crate::outputs::report::{v3, Num};
use crate::scene::cluster::{stop_name, ClusterScene};
use nalgebra::Vector3;
use serde::Serialize;

/// Kinetic energy (J) of a ball of `ball` moving at `v` (m/s) and spinning at `w` (rad/s):
/// m v^2 / 2 + I w^2 / 2.
fn kinetic(ball: &Ball, v: &Vector3<f64>, w: &Vector3<f64>) -> f64 {
    0.5 * ball.mass() * v.norm_squared() + 0.5 * ball.inertia() * w.norm_squared()
}

/// The balances of a run: what came in and what went out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Balances {
    /// Kinetic energy before (J).
    pub energy_in: f64,
    /// Kinetic energy after (J).
    pub energy_out: f64,
    /// Heat of every contact (J), the cloth's included.
    pub heat: f64,
    /// On a cloth, the energy its contacts and gravity hold at the end beyond the start (J):
    /// the sum over the balls of V(delta_out) - V(delta_s), V(delta) = (2/5) k
    /// max(delta, 0)^(5/2) - m g delta, delta the ball's compression of the cloth (>= 0: the
    /// balls start at V's minimum); 0 without a cloth.
    pub held: f64,
    /// On a cloth, the impulse (N s) of the cloth's contacts and the weights over the run,
    /// which momentum_out - momentum_in equals; 0 without a cloth.
    pub external: Vector3<f64>,
    /// Total momentum before (N s).
    pub momentum_in: Vector3<f64>,
    /// Total momentum after (N s).
    pub momentum_out: Vector3<f64>,
    /// Largest component of momentum_out - momentum_in over sum m_i |v_i| in.
    pub momentum_error: f64,
    /// |energy_in - energy_out - heat - held| over energy_in.
    pub energy_balance_error: f64,
}

impl Balances {
    /// The balances of `out`, the run of `cluster`.
    pub(crate) fn new(cluster: &Cluster, out: &ClusterOutcome) -> Self {
        let balls: &[ClusterBall] = cluster.balls();
        let energy_in = balls
            .iter()
            .map(|b| kinetic(&b.ball, &b.velocity, &b.spin))
            .sum();
        let energy_out = balls
            .iter()
            .zip(&out.balls)
            .map(|(b, o)| kinetic(&b.ball, &o.velocity, &o.spin))
            .sum();
        let heat = out.contacts.iter().chain(&out.cloth).map(|c| c.heat).sum();
        let held = out.cloth_held(cluster);
        let mut external = Vector3::zeros();
        if let Some(cloth) = cluster.cloth {
            for b in balls {
                external -= Vector3::z() * (b.ball.mass() * cloth.gravity * out.time);
            }
            for c in &out.cloth {
                external += c.friction_impulse - c.normal * c.normal_impulse;
            }
        }
        let momentum_in = balls
            .iter()
            .fold(Vector3::zeros(), |s, b| s + b.ball.mass() * b.velocity);
        let momentum_out = balls
            .iter()
            .zip(&out.balls)
            .fold(Vector3::zeros(), |s, (b, o)| s + b.ball.mass() * o.velocity);
        let scale: f64 = balls
            .iter()
            .map(|b| b.ball.mass() * b.velocity.norm())
            .sum();
        let ratio = |d: f64, s: f64| if d == 0.0 { 0.0 } else { d / s };
        Balances {
            energy_in,
            energy_out,
            heat,
            held,
            external,
            momentum_in,
            momentum_out,
            momentum_error: ratio((momentum_out - momentum_in - external).amax(), scale),
            energy_balance_error: ratio((energy_in - energy_out - heat - held).abs(), energy_in),
        }
    }
}

#[derive(Serialize)]
struct BallJson {
    velocity: [Num; 3],
    spin: [Num; 3],
    position: [Num; 3],
}

#[derive(Serialize)]
struct ContactJson {
    pair: [usize; 2],
    impulse: Num,
    friction_impulse: [Num; 3],
    normal: [Num; 3],
    start: Num,
    duration: Num,
    heat: Num,
    stick_time: Option<Num>,
}

#[derive(Serialize)]
struct ClothContactJson {
    ball: usize,
    impulse: Num,
    friction_impulse: [Num; 3],
    start: Num,
    duration: Num,
    heat: Num,
    stick_time: Option<Num>,
}

#[derive(Serialize)]
struct ClothJson {
    height: Num,
    mu: Num,
    youngs_modulus: Num,
    poisson_ratio: Num,
    gravity: Num,
    /// The damping law of the balls' contacts with the bed (absent when elastic).
    #[serde(skip_serializing_if = "Option::is_none")]
    damping: Option<&'static str>,
    /// Each ball's damping coefficient on the bed (beta s/m or gamma s; absent when elastic).
    #[serde(skip_serializing_if = "Option::is_none")]
    coefficients: Option<Vec<Num>>,
    contacts: Vec<ClothContactJson>,
    held: Num,
    external_impulse: [Num; 3],
}

#[derive(Serialize)]
struct CheckJson {
    momentum_error: Num,
    energy_balance_error: Num,
}

/// The JSON report of a cluster scene (docs/formats.md#the-cluster-report), keys in order.
#[derive(Serialize)]
pub struct ClusterReport {
    name: String,
    target: &'static str,
    balls: Vec<BallJson>,
    contacts: Vec<ContactJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cloth: Option<ClothJson>,
    time: Num,
    steps: u64,
    evaluations: u64,
    stop: &'static str,
    rtol: Num,
    stick: bool,
    energy_in: Num,
    energy_out: Num,
    heat: Num,
    momentum_in: [Num; 3],
    momentum_out: [Num; 3],
    check: CheckJson,
}

impl ClusterReport {
    /// The report of `out`, the run of `scene` with `settings`.
    pub fn new(scene: &ClusterScene, settings: &ClusterSettings, out: &ClusterOutcome) -> Self {
        let b = Balances::new(&scene.cluster, out);
        let cloth = scene.cluster.cloth().map(|c| ClothJson {
            height: Num(c.height),
            mu: Num(c.mu),
            youngs_modulus: Num(c.material.youngs_modulus()),
            poisson_ratio: Num(c.material.poisson_ratio()),
            gravity: Num(c.gravity),
            damping: (scene.cluster.cloth_damping() != PairDamping::None)
                .then(|| scene.cluster.cloth_damping().damping().name()),
            coefficients: (scene.cluster.cloth_damping() != PairDamping::None).then(|| {
                (0..scene.cluster.balls().len())
                    .filter_map(|i| scene.cluster.cloth_law(i).map(|l| Num(l.coefficient())))
                    .collect()
            }),
            contacts: out
                .cloth
                .iter()
                .map(|c| ClothContactJson {
                    ball: c.pair.0,
                    impulse: Num(c.normal_impulse),
                    friction_impulse: v3(&c.friction_impulse),
                    start: Num(c.start),
                    duration: Num(c.duration),
                    heat: Num(c.heat),
                    stick_time: c.stick_time.map(Num),
                })
                .collect(),
            held: Num(b.held),
            external_impulse: v3(&b.external),
        });
        ClusterReport {
            name: scene.name.clone(),
            target: "cluster",
            balls: out
                .balls
                .iter()
                .map(|o| BallJson {
                    velocity: v3(&o.velocity),
                    spin: v3(&o.spin),
                    position: v3(&o.position),
                })
                .collect(),
            contacts: out
                .contacts
                .iter()
                .map(|c| ContactJson {
                    pair: [c.pair.0, c.pair.1],
                    impulse: Num(c.normal_impulse),
                    friction_impulse: v3(&c.friction_impulse),
                    normal: v3(&c.normal),
                    start: Num(c.start),
                    duration: Num(c.duration),
                    heat: Num(c.heat),
                    stick_time: c.stick_time.map(Num),
                })
                .collect(),
            cloth,
            time: Num(out.time),
            steps: out.stats.steps,
            evaluations: out.stats.evaluations,
            stop: stop_name(out.stop),
            rtol: Num(settings.rtol),
            stick: settings.stick,
            energy_in: Num(b.energy_in),
            energy_out: Num(b.energy_out),
            heat: Num(b.heat),
            momentum_in: v3(&b.momentum_in),
            momentum_out: v3(&b.momentum_out),
            check: CheckJson {
                momentum_error: Num(b.momentum_error),
                energy_balance_error: Num(b.energy_balance_error),
            },
        }
    }

    /// Pretty JSON; fails naming the field when a number is not finite.
    pub fn to_json(&self) -> Result<String, Error> {
        let mut out = Vec::new();
        let mut ser = serde_json::Serializer::pretty(&mut out);
        serde_path_to_error::serialize(self, &mut ser).map_err(|e| Error::NonFinite {
            field: e.path().to_string(),
            value: f64::NAN,
        })?;
        Ok(String::from_utf8_lossy(&out).into_owned())
    }
}

/// How the scene's pairs push: the law's name and where its stiffness comes from.
fn law_text(scene: &ClusterScene) -> String {
    let law = scene.cluster.law(0, 1);
    let damping = match law.damping().name() {
        "none" => "elastic Hertz".to_string(),
        name => format!("Hertz with {name} damping"),
    };
    match &scene.materials {
        Some(_) => format!("{damping}, stiffness of each pair from its balls' materials"),
        None => format!("{damping}, stiffness {} N/m^1.5", sci(law.stiffness(), 6)),
    }
}

/// The text summary of a cluster run: each ball going out, each contact, the balances.
pub(crate) fn cluster_summary(
    scene: &ClusterScene,
    settings: &ClusterSettings,
    out: &ClusterOutcome,
) -> String {
    let vec = |v: &Vector3<f64>| format!("[{:+.6}, {:+.6}, {:+.6}]", v.x, v.y, v.z);
    let b = Balances::new(&scene.cluster, out);
    let mut s = String::new();
    s += &format!("{}\n", scene.name);
    s += &format!(
        "  {}; {}; mu {}; stick {}; rtol {}\n",
        count(out.balls.len() as u64, "ball", "balls"),
        law_text(scene),
        decimal(scene.cluster.mu(), 6),
        if settings.stick { "on" } else { "off" },
        shortest(settings.rtol),
    );
    s += "  ball  velocity out (m/s)                      spin out (rad/s)\n";
    for (i, o) in out.balls.iter().enumerate() {
        s += &format!("  {i:>4}  {}  {}\n", vec(&o.velocity), vec(&o.spin));
    }
    s += &format!(
        "  contacts, in the order they opened ({}):\n",
        out.contacts.len()
    );
    for c in &out.contacts {
        let stick = c.stick_time.map_or("never sticks".to_string(), |t| {
            format!("sticks at {}", si(t, "s", 5))
        });
        s += &format!(
            "  ({}, {})  impulse {} N s  duration {}  heat {}  {stick}\n",
            c.pair.0,
            c.pair.1,
            decimal(c.normal_impulse, 7),
            si(c.duration, "s", 5),
            si(c.heat, "J", 5),
        );
    }
    if let Some(cloth) = scene.cluster.cloth() {
        s += &format!(
            "  on the cloth (mu {}, gravity {} m/s^2): cloth impulse per ball (N s, up; friction)\n",
            decimal(cloth.mu, 6),
            decimal(cloth.gravity, 6),
        );
        for c in &out.cloth {
            s += &format!(
                "  {:>4}  {}  {}  heat {}\n",
                c.pair.0,
                decimal(c.normal_impulse, 7),
                vec(&c.friction_impulse),
                si(c.heat, "J", 5),
            );
        }
        s += &format!(
            "  held by the cloth and gravity at the end {}\n",
            si(b.held, "J", 5)
        );
    }
    s += &format!(
        "  energy in {}, out {}, heat {} (balance error {}); momentum error {}\n",
        si(b.energy_in, "J", 7),
        si(b.energy_out, "J", 7),
        si(b.heat, "J", 5),
        sci(b.energy_balance_error, 2),
        sci(b.momentum_error, 2),
    );
    s += &format!(
        "  {} at t = {}: {} ({} rejected), {}, {}\n",
        stop_name(out.stop),
        si(out.time, "s", 5),
        count(out.stats.steps, "step", "steps"),
        out.stats.rejected,
        count(out.stats.evaluations, "evaluation", "evaluations"),
        count(out.stats.events, "event", "events"),
    );
    s
}

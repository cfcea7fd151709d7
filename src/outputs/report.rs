//! The report of a run as JSON: one object, the keys of docs/formats.md#json-report (the
//! text summary of the same report is `outputs::summary`).
//!
//! Every float is checked finite before output: a non-finite value fails the run, naming
//! the field, instead of turning into `null`. Only the fields documented as nullable
//! (docs/formats.md#nulls-and-absent-keys: `theta`, `stick_time`, `stick_impulse`,
//! `throw_angle_deg`) may be null; optional keys of extensions (`friction`, `lab_out`, `plane`, `table`, and in
//! `table` each ball's `direction_deg`, `deflection_deg` and `rest`) are left out when they
//! do not apply.

use crate::base::error::Error;
use crate::base::settings::{SolverSettings, Stats};
use crate::model::material::HertzContact;
use crate::model::params::{Evaluate, Friction, FrictionLaw};
use crate::model::state::{CmState, LabMotion};
use crate::profile::force::ForceProfile;
use crate::scene::compliant::CompliantRun;
use crate::scene::run::SceneOutcome;
use crate::scene::types::{Incoming, Scene};
use crate::solve::check::Checks;
use crate::solve::outcome::LawOutcome;
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::roll_out::RollOut;
use nalgebra::Vector3;
use serde::ser::{self, SerializeStruct};
use serde::{Serialize, Serializer};

/// A number that refuses to serialise when it is not finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Num(pub f64);

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.serialize_f64(self.0)
        } else {
            Err(ser::Error::custom(format_args!(
                "non-finite value {}",
                self.0
            )))
        }
    }
}

pub(crate) fn v3(v: &Vector3<f64>) -> [Num; 3] {
    [Num(v.x), Num(v.y), Num(v.z)]
}

/// A centre-of-mass state in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct CmJson {
    /// Velocity of A (m/s).
    pub u: [Num; 3],
    /// Spin of A (rad/s).
    pub omega_a: [Num; 3],
    /// Spin of B (rad/s).
    pub omega_b: [Num; 3],
}

impl From<&CmState> for CmJson {
    fn from(s: &CmState) -> Self {
        CmJson {
            u: v3(&s.u_cm),
            omega_a: v3(&s.omega_a),
            omega_b: v3(&s.omega_b),
        }
    }
}

/// A ball's lab motion in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct MotionJson {
    /// Velocity (m/s).
    pub velocity: [Num; 3],
    /// Spin (rad/s).
    pub spin: [Num; 3],
}

impl From<&LabMotion> for MotionJson {
    fn from(m: &LabMotion) -> Self {
        MotionJson {
            velocity: v3(&m.velocity),
            spin: v3(&m.spin),
        }
    }
}

/// Both balls' lab motions.
#[derive(Debug, Serialize)]
pub(crate) struct LabJson {
    /// Ball A.
    pub a: MotionJson,
    /// Ball B.
    pub b: MotionJson,
}

impl From<&(LabMotion, LabMotion)> for LabJson {
    fn from((a, b): &(LabMotion, LabMotion)) -> Self {
        LabJson {
            a: MotionJson::from(a),
            b: MotionJson::from(b),
        }
    }
}

/// A ball meeting a plane in JSON (lab axes); `cm_in` and `cm_out` are then those of the
/// equivalent pair (docs/plane.md).
#[derive(Debug, Serialize)]
pub(crate) struct PlaneJson {
    /// Unit normal, out of the plane towards the ball.
    pub normal: [Num; 3],
    /// The ball before the contact.
    pub ball_in: MotionJson,
    /// The ball after it.
    pub ball_out: MotionJson,
}

/// The friction law in JSON, written only when a speed-dependent mu is evaluated once at the
/// initial slip (docs/formats.md#json-report): the model, `evaluate` and the mu held.
#[derive(Debug, Serialize)]
pub(crate) struct HeldFrictionJson {
    model: &'static str,
    evaluate: &'static str,
    /// mu(S(0)), held through the contact.
    mu: Num,
}

impl HeldFrictionJson {
    /// The description of `friction` for a contact sliding from `s0` (m/s); `None` unless it
    /// is speed-dependent and evaluated at the initial slip.
    pub(crate) fn new(friction: &Friction, s0: f64) -> Option<Self> {
        match friction.law() {
            FrictionLaw::SpeedDependent {
                evaluate: Evaluate::Initial,
                ..
            } => Some(HeldFrictionJson {
                model: "speed-dependent",
                evaluate: Evaluate::Initial.name(),
                mu: Num(friction.mu(s0)),
            }),
            _ => None,
        }
    }
}

/// The checks in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct CheckJson {
    theta_drift: Num,
    closed_form_error: Num,
    momentum_error: Num,
    angular_momentum_error: Num,
    energy_balance_error: Num,
    slip_consistency: Num,
}

impl From<&Checks> for CheckJson {
    fn from(c: &Checks) -> Self {
        CheckJson {
            theta_drift: Num(c.theta_drift),
            closed_form_error: Num(c.closed_form_error),
            momentum_error: Num(c.momentum_error),
            angular_momentum_error: Num(c.angular_momentum_error),
            energy_balance_error: Num(c.energy_balance_error),
            slip_consistency: Num(c.slip_consistency),
        }
    }
}

/// Hertz's contact of the balls' material (when the duration comes from it), SI units.
#[derive(Debug, Serialize)]
pub(crate) struct HertzJson {
    /// Largest compression delta_max (m).
    pub max_compression: Num,
    /// Peak force k delta_max^(3/2) of the elastic impact (N).
    pub peak_force: Num,
    /// Radius of the contact patch at the peak (m).
    pub contact_radius: Num,
}

impl From<&HertzContact> for HertzJson {
    fn from(h: &HertzContact) -> Self {
        HertzJson {
            max_compression: Num(h.max_compression),
            peak_force: Num(h.peak_force),
            contact_radius: Num(h.contact_radius),
        }
    }
}

/// What a contact law decided (docs/contact-law.md), SI units.
#[derive(Debug, Serialize)]
pub(crate) struct ContactLawJson {
    /// The damping term's name.
    pub damping: &'static str,
    /// The realised restitution e = P / (m U(0)) - 1.
    pub restitution: Num,
    /// Largest compression delta_max (m).
    pub max_compression: Num,
    /// Peak force (N).
    pub peak_force: Num,
    /// The damping coefficient, given or calibrated: beta (s/m), gamma (s), 0 for `none`.
    pub coefficient: Num,
    /// Stiffness k (N / m^(3/2)).
    pub stiffness: Num,
}

impl From<&LawOutcome> for ContactLawJson {
    fn from(l: &LawOutcome) -> Self {
        ContactLawJson {
            damping: l.law.damping().name(),
            restitution: Num(l.restitution),
            max_compression: Num(l.max_compression),
            peak_force: Num(l.peak_force),
            coefficient: Num(l.law.coefficient()),
            stiffness: Num(l.law.stiffness()),
        }
    }
}

/// What Mindlin's spring adds to the report (`compliant`, docs/formats.md#json-report):
/// vectors in the frame of `cm_out` (the paper's, or a plane's equivalent pair's), SI units.
#[derive(Debug, Serialize)]
pub(crate) struct CompliantJson {
    /// Coulomb's mu of the spring's cap (0 with the effect friction off).
    pub mu: Num,
    /// The spring's elastic displacement xi = -F_t / k_t at the end of the contact (m).
    pub final_displacement: [Num; 3],
    /// Whether the contact point's slip leaves against its incoming direction (s_out < 0).
    pub slip_reversed: bool,
    /// The tangential impulse on ball A (N s).
    pub tangential_impulse: [Num; 3],
    /// The largest |F_t| among the steps (N).
    pub max_tangential_force: Num,
    /// The work the tangential force took from the balls, -integral of F_t.u dt (J).
    pub tangential_work: Num,
    /// The contact point's angle of incidence atan(|u(0)| / U_n) (rad).
    pub incidence_angle: Num,
    /// Its rebound angle atan2(u'.e0, U_n') (rad): negative when the slip reversed.
    pub rebound_angle: Num,
    /// Maw, Barber and Fawcett's normalised incidence Psi_1 (absent without friction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normalised_incidence: Option<Num>,
    /// Their normalised rebound Psi_2 (absent without friction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normalised_rebound: Option<Num>,
}

impl From<&CompliantRun> for CompliantJson {
    fn from(c: &CompliantRun) -> Self {
        let o = &c.outcome;
        let plane = |v: nalgebra::Vector2<f64>| [Num(0.0), Num(v.x), Num(v.y)];
        let finite = |x: f64| x.is_finite().then_some(Num(x));
        CompliantJson {
            mu: Num(c.mu),
            final_displacement: plane(c.final_displacement),
            slip_reversed: c.slip_reversed(),
            tangential_impulse: plane(c.tangential_impulse),
            max_tangential_force: Num(c.rows.iter().map(|r| r.force.norm()).fold(0.0, f64::max)),
            tangential_work: Num(o.tangential_work),
            incidence_angle: Num(o.incidence_angle),
            rebound_angle: Num(o.rebound_angle),
            normalised_incidence: finite(o.normalised_incidence),
            normalised_rebound: finite(o.normalised_rebound),
        }
    }
}

/// The name the report gives the force of a scene: the profile's, or `contact-law`.
pub(crate) const CONTACT_LAW_NAME: &str = "contact-law";

/// The name of the scene's force and its contact duration (s): the profile's, or the
/// duration a contact law realised.
pub(crate) fn force_and_duration(scene: &Scene, run: &SceneOutcome) -> (&'static str, f64) {
    match (&scene.law, &run.outcome.law) {
        (Some(_), Some(l)) => (CONTACT_LAW_NAME, l.duration),
        (Some(_), None) => (CONTACT_LAW_NAME, 0.0),
        (None, _) => (scene.profile.name(), scene.profile.duration()),
    }
}

/// Solver settings and work.
#[derive(Debug, Serialize)]
pub(crate) struct SolverJson {
    method: &'static str,
    rtol: Num,
    atol: Num,
    steps: u32,
    rhs_evaluations: u64,
    accepted_steps: u64,
    rejected_steps: u64,
}

impl SolverJson {
    /// The settings of a run and the work it did.
    pub(crate) fn new(settings: &SolverSettings, stats: &Stats) -> Self {
        SolverJson {
            method: settings.method().name(),
            rtol: Num(settings.rtol()),
            atol: Num(settings.atol()),
            steps: settings.steps(),
            rhs_evaluations: stats.rhs_evaluations,
            accepted_steps: stats.accepted_steps,
            rejected_steps: stats.rejected_steps,
        }
    }
}

/// The JSON report (`--json`) of a scene's run: a view of the scene and its outcome that
/// serialises to the keys of docs/formats.md#json-report, in that order.
#[derive(Debug, Clone, Copy)]
pub struct Report<'a> {
    pub(crate) scene: &'a Scene,
    pub(crate) run: &'a SceneOutcome,
}

/// The table phase in JSON: both balls from separation until they roll.
#[derive(Debug, Serialize)]
pub(crate) struct TableJson {
    /// Ball A.
    pub a: RollOutJson,
    /// Ball B.
    pub b: RollOutJson,
    /// Ball-cloth sliding friction.
    pub mu: Num,
    /// Ball-cloth restitution.
    pub restitution: Num,
    /// Gravity (m/s^2).
    pub g: Num,
    /// Rolling resistance (0: off).
    pub rolling_resistance: Num,
    /// Spin decay about the vertical (0: off).
    pub spin_decay: Num,
    /// Cloth height along up (m).
    pub height: Num,
    /// When both balls roll (or rest, with rolling resistance) (s).
    pub end_time: Num,
    /// Self-checks (scaled).
    pub check: TableCheckJson,
}

/// The table phase's checks in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct TableCheckJson {
    /// Largest energy increase (kinetic + gravitational), over m v_ref^2.
    pub energy_increase: Num,
    /// Momentum against the cloth's impulses and gravity, over m v_ref.
    pub momentum_error: Num,
}

/// One impact with the cloth in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct ImpactJson {
    /// When (s after separation).
    pub time: Num,
    /// Velocity after it (m/s).
    pub velocity: [Num; 3],
    /// Spin after it (rad/s).
    pub spin: [Num; 3],
    /// Normal impulse (N s).
    pub normal_impulse: Num,
    /// Tangential impulse J_t >= 0 (N s), against the slip.
    pub tangential_impulse: Num,
    /// Whether the impact stopped the slip.
    pub sticks: bool,
}

/// A ball once it rolls.
#[derive(Debug, Serialize)]
pub(crate) struct RollingJson {
    /// Velocity (m/s).
    pub velocity: [Num; 3],
    /// Spin (rad/s).
    pub spin: [Num; 3],
    /// Centre position where it starts to roll (m).
    pub position: [Num; 3],
}

/// Where a ball comes to rest (rolling resistance on).
#[derive(Debug, Serialize)]
pub(crate) struct RestJson {
    /// When (s after separation).
    pub time: Num,
    /// Centre position (m).
    pub position: [Num; 3],
}

/// One ball's roll-out in JSON.
#[derive(Debug, Serialize)]
pub(crate) struct RollOutJson {
    /// Duration of the hop (s), 0 when the ball does not leave the cloth.
    pub hop_time: Num,
    /// Height of the hop (m).
    pub hop_height: Num,
    /// The first impact with the cloth.
    pub impact: ImpactJson,
    /// Bounces after it (restitution > 0).
    pub bounces: u32,
    /// From when the ball stays on the cloth (s).
    pub settle_time: Num,
    /// Duration of the slide until rolling (s).
    pub slide_time: Num,
    /// Displacement during the slide (m).
    pub slide_displacement: [Num; 3],
    /// When it starts to roll (s after separation).
    pub roll_time: Num,
    /// Once rolling.
    pub rolling: RollingJson,
    /// Rolling direction (of `rolling.velocity`), degrees counter-clockwise about up from
    /// the line of centres; absent when that velocity is zero (the ball does not move once
    /// it stops sliding). A ball that rolls and then comes to rest with rolling resistance
    /// keeps it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub direction_deg: Option<Num>,
    /// From the incoming direction of travel to the rolling direction, degrees
    /// counter-clockwise about up; absent for a ball that came in at rest or whose
    /// `rolling.velocity` is zero (present when it rolls, then rests).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deflection_deg: Option<Num>,
    /// Where it rests (rolling resistance on); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rest: Option<RestJson>,
    /// Total impulse of the cloth on the ball until it rolls (or rests) (N s).
    pub table_impulse: [Num; 3],
}

impl TableJson {
    /// The JSON form of a table phase.
    pub(crate) fn new(t: &TableOutcome) -> Self {
        let ball = |i: usize, r: &RollOut| {
            let imp = r.impacts[0];
            RollOutJson {
                hop_time: Num(r.hop_time),
                hop_height: Num(r.hop_height),
                impact: ImpactJson {
                    time: Num(imp.time),
                    velocity: v3(&imp.velocity),
                    spin: v3(&imp.spin),
                    normal_impulse: Num(imp.normal_impulse),
                    tangential_impulse: Num(imp.tangential_impulse),
                    sticks: imp.sticks,
                },
                bounces: r.bounces,
                settle_time: Num(r.settle_time),
                slide_time: Num(r.slide_time),
                slide_displacement: v3(&r.slide_displacement),
                roll_time: Num(r.roll_time),
                rolling: RollingJson {
                    velocity: v3(&r.rolling.velocity),
                    spin: v3(&r.rolling.spin),
                    position: v3(&r.rolling.position),
                },
                direction_deg: t.direction_deg(r).map(Num),
                deflection_deg: t.deflection_deg(i, r).map(Num),
                rest: r.rest.map(|(time, p)| RestJson {
                    time: Num(time),
                    position: v3(&p),
                }),
                table_impulse: v3(&r.table_impulse),
            }
        };
        let p = &t.table.params;
        TableJson {
            a: ball(0, &t.a),
            b: ball(1, &t.b),
            mu: Num(p.mu()),
            restitution: Num(p.restitution()),
            g: Num(p.g()),
            rolling_resistance: Num(p.rolling_resistance()),
            spin_decay: Num(p.spin_decay()),
            height: Num(t.table.height),
            end_time: Num(t.end_time()),
            check: TableCheckJson {
                energy_increase: Num(t.check.energy_increase),
                momentum_error: Num(t.check.momentum_error),
            },
        }
    }
}

impl<'a> Report<'a> {
    /// The report of `run`, the outcome of `scene`.
    pub fn new(scene: &'a Scene, run: &'a SceneOutcome) -> Self {
        Report { scene, run }
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

/// The keys of the report, in order (docs/formats.md#json-report).
impl Serialize for Report<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (scene, run) = (self.scene, self.run);
        let o = &run.outcome;
        let r = &o.result;
        let mut m = s.serialize_struct("Report", 29)?;
        m.serialize_field("name", &scene.name)?;
        let (force, duration) = force_and_duration(scene, run);
        m.serialize_field("profile", force)?;
        m.serialize_field("duration", &Num(duration))?;
        match scene.hertz() {
            Ok(Some(h)) => m.serialize_field("hertz", &HertzJson::from(&h))?,
            _ => m.skip_field("hertz")?,
        }
        match &o.law {
            Some(l) => m.serialize_field("contact_law", &ContactLawJson::from(l))?,
            None => m.skip_field("contact_law")?,
        }
        match &run.compliant {
            Some(c) => {
                m.serialize_field("tangential", scene.tangential.name())?;
                m.serialize_field("compliant", &CompliantJson::from(c))?;
            }
            None => {
                m.skip_field("tangential")?;
                m.skip_field("compliant")?;
            }
        }
        m.serialize_field("effects", &scene.effects.simulated(&scene.contact.friction))?;
        match HeldFrictionJson::new(&scene.contact.friction, r.s0) {
            Some(f) => m.serialize_field("friction", &f)?,
            None => m.skip_field("friction")?,
        }
        m.serialize_field("collision", &r.collided())?;
        m.serialize_field("impulse", &Num(r.impulse))?;
        m.serialize_field("s0", &Num(r.s0))?;
        m.serialize_field("theta", &r.theta.map(Num))?;
        m.serialize_field("s_out", &Num(r.s_out))?;
        m.serialize_field("sticks", &r.sticks)?;
        m.serialize_field("stick_time", &o.stick_time.map(Num))?;
        m.serialize_field("stick_impulse", &r.stick_impulse.map(Num))?;
        m.serialize_field("tangential_impulse", &Num(r.tangential_impulse))?;
        m.serialize_field("heat", &Num(r.heat))?;
        m.serialize_field("heat_sliding", &Num(r.heat_sliding))?;
        m.serialize_field("cm_in", &CmJson::from(&run.cm_in))?;
        m.serialize_field("cm_out", &CmJson::from(&r.out))?;
        match &run.lab_out {
            Some(lab) => m.serialize_field("lab_out", &LabJson::from(lab))?,
            None => m.skip_field("lab_out")?,
        }
        match (&run.plane_out, &scene.incoming) {
            (Some(out), Incoming::Plane(p)) => m.serialize_field(
                "plane",
                &PlaneJson {
                    normal: v3(&p.normal),
                    ball_in: MotionJson {
                        velocity: v3(&p.velocity),
                        spin: v3(&p.spin),
                    },
                    ball_out: MotionJson::from(out),
                },
            )?,
            _ => m.skip_field("plane")?,
        }
        m.serialize_field("throw_angle_deg", &run.throw_angle_deg.map(Num))?;
        m.serialize_field("check", &CheckJson::from(&o.check))?;
        m.serialize_field("solver", &SolverJson::new(&run.settings, &o.stats))?;
        m.serialize_field("warnings", &o.warnings)?;
        match &run.table {
            Some(t) => m.serialize_field("table", &TableJson::new(t))?,
            None => m.skip_field("table")?,
        }
        m.end()
    }
}

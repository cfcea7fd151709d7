//! The report of a run: JSON (one object, the keys of docs/formats.md#json-report) and a
//! human summary.
//!
//! Every float is checked finite before output: a non-finite value fails the run, naming
//! the field, instead of turning into `null`. Only the fields documented as nullable
//! (docs/formats.md#nulls-and-absent-keys: `theta`, `stick_time`, `stick_impulse`,
//! `throw_angle_deg`) may be null; optional keys of extensions (`friction`, `lab_out`, `table`, and in
//! `table` each ball's `direction_deg`, `deflection_deg` and `rest`) are left out when they
//! do not apply.

use crate::apps::runner::SceneOutcome;
use crate::contact::check::Checks;
use crate::contact::law_outcome::LawOutcome;
use crate::contact::result::ContactResult;
use crate::error::Error;
use crate::formats::number::{count, decimal, sci, si};
use crate::formats::scene::Scene;
use crate::integrator::{SolverSettings, Stats};
use crate::model::material::HertzContact;
use crate::model::params::{Evaluate, Friction, FrictionLaw};
use crate::model::state::{CmState, LabMotion};
use crate::profile::ForceProfile;
use crate::table_phase::{RollOut, TableOutcome};
use nalgebra::Vector3;
use serde::ser::{self, SerializeStruct};
use serde::{Serialize, Serializer};

/// A number that refuses to serialise when it is not finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

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

fn v3(v: &Vector3<f64>) -> [Num; 3] {
    [Num(v.x), Num(v.y), Num(v.z)]
}

/// A centre-of-mass state in JSON.
#[derive(Debug, Serialize)]
pub struct CmJson {
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
pub struct MotionJson {
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
pub struct LabJson {
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

/// The friction law in JSON, written only when a speed-dependent mu is evaluated once at the
/// initial slip (docs/formats.md#json-report): the model, `evaluate` and the mu held.
#[derive(Debug, Serialize)]
pub struct HeldFrictionJson {
    model: &'static str,
    evaluate: &'static str,
    /// mu(S(0)), held through the contact.
    mu: Num,
}

impl HeldFrictionJson {
    /// The description of `friction` for a contact sliding from `s0` (m/s); `None` unless it
    /// is speed-dependent and evaluated at the initial slip.
    pub fn new(friction: &Friction, s0: f64) -> Option<Self> {
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
pub struct CheckJson {
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
pub struct HertzJson {
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
pub struct ContactLawJson {
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

/// The name the report gives the force of a scene: the profile's, or `contact-law`.
pub const CONTACT_LAW_NAME: &str = "contact-law";

/// The name of the scene's force and its contact duration (s): the profile's, or the
/// duration a contact law realised.
fn force_and_duration(scene: &Scene, run: &SceneOutcome) -> (&'static str, f64) {
    match (&scene.law, &run.outcome.law) {
        (Some(_), Some(l)) => (CONTACT_LAW_NAME, l.duration),
        (Some(_), None) => (CONTACT_LAW_NAME, 0.0),
        (None, _) => (scene.profile.name(), scene.profile.duration()),
    }
}

/// Solver settings and work.
#[derive(Debug, Serialize)]
pub struct SolverJson {
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
    pub fn new(settings: &SolverSettings, stats: &Stats) -> Self {
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
    scene: &'a Scene,
    run: &'a SceneOutcome,
}

/// The table phase in JSON: both balls from separation until they roll.
#[derive(Debug, Serialize)]
pub struct TableJson {
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
pub struct TableCheckJson {
    /// Largest energy increase (kinetic + gravitational), over m v_ref^2.
    pub energy_increase: Num,
    /// Momentum against the cloth's impulses and gravity, over m v_ref.
    pub momentum_error: Num,
}

/// One impact with the cloth in JSON.
#[derive(Debug, Serialize)]
pub struct ImpactJson {
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
pub struct RollingJson {
    /// Velocity (m/s).
    pub velocity: [Num; 3],
    /// Spin (rad/s).
    pub spin: [Num; 3],
    /// Centre position where it starts to roll (m).
    pub position: [Num; 3],
}

/// Where a ball comes to rest (rolling resistance on).
#[derive(Debug, Serialize)]
pub struct RestJson {
    /// When (s after separation).
    pub time: Num,
    /// Centre position (m).
    pub position: [Num; 3],
}

/// One ball's roll-out in JSON.
#[derive(Debug, Serialize)]
pub struct RollOutJson {
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
    pub fn new(t: &TableOutcome) -> Self {
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
        let mut m = s.serialize_struct("Report", 26)?;
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

/// A human-readable summary: numbers for people ([`crate::formats::number::si`] prefixes,
/// plain decimals), a heat within the run's round-off of zero as 0 (the checks line gives
/// the size of the round-off). The outcome's warnings are not part of it (the command
/// line prints them on stderr; they are in [`SceneOutcome`] and the JSON report).
pub fn summary(scene: &Scene, so: &SceneOutcome) -> String {
    use std::fmt::Write;
    let o = &so.outcome;
    let r = &o.result;
    let mut s = String::new();
    let _ = writeln!(s, "{}", scene.name);
    let (force, duration) = force_and_duration(scene, so);
    let _ = writeln!(
        s,
        "  profile {} over {}, method {}, effects: {}",
        force,
        si(duration, "s", 5),
        so.settings.method(),
        scene.effects.simulated(&scene.contact.friction).join(", ")
    );
    if let Some(l) = &o.law {
        s.push_str(&law_summary(l));
    }
    if let Ok(Some(h)) = scene.hertz() {
        let _ = writeln!(
            s,
            "  Hertz contact of the material: compression {}, peak force {}, contact radius {}",
            si(h.max_compression, "m", 5),
            si(h.peak_force, "N", 5),
            si(h.contact_radius, "m", 5)
        );
    }
    if HeldFrictionJson::new(&scene.contact.friction, r.s0).is_some() {
        let _ = writeln!(
            s,
            "  friction          mu(S(0)) = {:.6} held through the contact (evaluate = initial)",
            scene.contact.friction.mu(r.s0)
        );
    }
    if !r.collided() {
        let _ = writeln!(
            s,
            "  no collision: the balls do not approach (U(0) = {:.6} m/s); state unchanged",
            so.cm_in.u_cm.x
        );
        return s;
    }
    s.push_str(&contact_summary(r, o.stick_time, heat_round_off(scene, so)));
    let fmt = |v: &Vector3<f64>| vec3_text(v, 9);
    let _ = writeln!(s, "  centre-of-mass frame, out:");
    let _ = writeln!(s, "    U        {} m/s", fmt(&r.out.u_cm));
    let _ = writeln!(s, "    omega_A  {} rad/s", fmt(&r.out.omega_a));
    let _ = writeln!(s, "    omega_B  {} rad/s", fmt(&r.out.omega_b));
    if let Some((a, b)) = so.lab_out {
        let _ = writeln!(s, "  lab frame, out:");
        let _ = writeln!(s, "    v_A      {} m/s", fmt(&a.velocity));
        let _ = writeln!(s, "    spin_A   {} rad/s", fmt(&a.spin));
        let _ = writeln!(s, "    v_B      {} m/s", fmt(&b.velocity));
        let _ = writeln!(s, "    spin_B   {} rad/s", fmt(&b.spin));
    }
    if let Some(th) = so.throw_angle_deg {
        let _ = writeln!(s, "  throw angle       {th:.6} deg");
    }
    let c = &o.check;
    let _ = writeln!(
        s,
        "  checks (scaled): closed form {}, theta drift {}, momentum {}, angular momentum {}, \
         energy balance {}",
        sci(c.closed_form_error, 2),
        sci(c.theta_drift, 2),
        sci(c.momentum_error, 2),
        sci(c.angular_momentum_error, 2),
        sci(c.energy_balance_error, 2)
    );
    let _ = writeln!(
        s,
        "  solver: {}, {} accepted and {} rejected steps",
        count(o.stats.rhs_evaluations, "rhs evaluation", "rhs evaluations"),
        o.stats.accepted_steps,
        o.stats.rejected_steps
    );
    if let Some(t) = &so.table {
        s.push_str(&table_summary(t));
    }
    s
}

/// The contact law's line of the summary: its damping, the restitution it gave, the
/// largest compression and force.
fn law_summary(l: &LawOutcome) -> String {
    format!(
        "  contact law hertz, damping {} (coefficient {} {}): restitution {:.9}, compression \
         {}, peak force {}\n",
        l.law.damping(),
        decimal(l.law.coefficient(), 7),
        l.law.damping().unit(),
        l.restitution,
        si(l.max_compression, "m", 5),
        si(l.peak_force, "N", 5)
    )
}

/// The least round-off of a heat, relative to the energy scale m v_ref^2: a few ulps of the
/// kinetic energies whose difference it is (eq 38).
const HEAT_ROUND_OFF: f64 = 16.0 * f64::EPSILON;

/// The size of the energy's round-off in a run (J): the energy balance check's, and at
/// least a few ulps of the energy scale m v_ref^2.
fn heat_round_off(scene: &Scene, so: &SceneOutcome) -> f64 {
    scene.collision().map_or(0.0, |(c, _)| {
        so.outcome.check.energy_balance_error.max(HEAT_ROUND_OFF) * c.scales.energy
    })
}

/// A heat (J) for people: 0 within `round_off` (J) of zero, where its sign and digits are
/// the round-off of the difference of two kinetic energies.
fn heat_text(heat: f64, round_off: f64) -> String {
    si(if heat.abs() <= round_off { 0.0 } else { heat }, "J", 10)
}

/// The contact of a collision, human-readable: impulse, sliding, heat (within
/// `heat_round_off` J of zero: 0).
fn contact_summary(r: &ContactResult, stick_time: Option<f64>, heat_round_off: f64) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "  impulse P         {} N s", decimal(r.impulse, 10));
    if r.s0 == 0.0 {
        // docs/model.md#no-initial-sliding: the surfaces never slide.
        let _ = writeln!(
            s,
            "  sliding           none: S(0) = 0, theta undefined; purely normal throughout"
        );
    } else {
        let theta = r
            .theta
            .map(|t| format!("{:.6} deg", t.to_degrees()))
            .unwrap_or_else(|| "undefined (no slip)".into());
        let _ = writeln!(s, "  sliding S(0)      {:.9} m/s, theta {theta}", r.s0);
        match (r.sticks, stick_time) {
            (true, Some(t)) => {
                let _ = writeln!(
                    s,
                    "  sliding stops     at t = {}, p = {} N s; then purely normal",
                    si(t, "s", 7),
                    decimal(r.stick_impulse.unwrap_or(0.0), 7)
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "  sliding           throughout, S_out = {:.9} m/s",
                    r.s_out
                );
            }
        }
    }
    let _ = writeln!(
        s,
        "  tangential J      {} N s",
        decimal(r.tangential_impulse, 10)
    );
    let _ = writeln!(
        s,
        "  heat H            {} (sliding {})",
        heat_text(r.heat, heat_round_off),
        heat_text(r.heat_sliding, heat_round_off)
    );
    s
}

/// The table phase, human-readable.
fn table_summary(t: &TableOutcome) -> String {
    use std::fmt::Write;
    let p = &t.table.params;
    let mut s = String::new();
    let fmt = |v: &Vector3<f64>| vec3_text(v, 6);
    let _ = writeln!(
        s,
        "  table (cloth mu {}, restitution {}, g {} m/s^2): until both roll, {}",
        p.mu(),
        p.restitution(),
        p.g(),
        si(t.end_time(), "s", 7)
    );
    for (i, (name, r)) in [("A", &t.a), ("B", &t.b)].into_iter().enumerate() {
        let imp = &r.impacts[0];
        let _ = writeln!(s, "    {name}: {}", leaves_the_cloth(r, &t.table.up, p.g()));
        let _ = writeln!(
            s,
            "       impact: normal {} N s, tangential {} N s ({}), {}",
            decimal(imp.normal_impulse, 7),
            decimal(imp.tangential_impulse, 7),
            if imp.sticks {
                "slip stopped"
            } else {
                "slips on"
            },
            count(u64::from(r.bounces), "bounce", "bounces")
        );
        let _ = writeln!(
            s,
            "       slides {} over {} m, rolls from t = {}",
            si(r.slide_time, "s", 7),
            fmt(&r.slide_displacement),
            si(r.roll_time, "s", 7)
        );
        let _ = writeln!(
            s,
            "       rolling: v {} m/s, spin {} rad/s",
            fmt(&r.rolling.velocity),
            fmt(&r.rolling.spin)
        );
        let dir = t
            .direction_deg(r)
            .map(|d| format!("{d:.4} deg from the line of centres"))
            .unwrap_or_else(|| "at rest".into());
        let defl = t
            .deflection_deg(i, r)
            .map(|d| format!(", deflected {d:.4} deg from its incoming line"))
            .unwrap_or_default();
        let _ = writeln!(s, "       direction: {dir}{defl}");
        if let Some((time, pos)) = r.rest {
            let _ = writeln!(
                s,
                "       rests at t = {} at {} m",
                si(time, "s", 7),
                fmt(&pos)
            );
        }
    }
    let _ = writeln!(
        s,
        "    checks (scaled): energy increase {}, momentum {}",
        sci(t.check.energy_increase, 2),
        sci(t.check.momentum_error, 2)
    );
    s
}

/// How a ball leaves the contact with respect to the cloth (unit vertical `up`, gravity `g`
/// m/s^2): a hop when it moves up at separation; a bounce off the cloth at t = 0 when it is
/// pressed into a cloth with restitution (the flight the ball path shows, up to (v.n)^2 /
/// (2 g) after that first impact, docs/model.md#the-table-phase); else it stays on the cloth.
fn leaves_the_cloth(r: &RollOut, up: &Vector3<f64>, g: f64) -> String {
    let first = &r.impacts[0];
    if r.hop_time > 0.0 {
        format!(
            "hops {}, {} high, lands at t = {}",
            si(r.hop_time, "s", 7),
            si(r.hop_height, "m", 7),
            si(first.time, "s", 7)
        )
    } else if r.bounces > 0 {
        let vn = first.velocity.dot(up);
        format!(
            "pressed into the cloth at separation, bounces off it at t = 0, up to {} high",
            si(vn * vn / (2.0 * g), "m", 7)
        )
    } else {
        "stays on the cloth (no hop)".into()
    }
}

/// `[+x, +y, +z]` with `prec` decimals; a component that rounds to zero prints as +0 (not
/// as -0.000000000 for a round-off remainder of -1e-17).
fn vec3_text(v: &Vector3<f64>, prec: usize) -> String {
    let one = |x: f64| {
        let s = format!("{x:+.prec$}");
        if s[1..].chars().all(|c| c == '0' || c == '.') {
            format!("{:+.prec$}", 0.0)
        } else {
            s
        }
    };
    format!("[{}, {}, {}]", one(v.x), one(v.y), one(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A component that rounds to zero at the printed precision prints as +0, whatever its
    /// sign; others keep theirs.
    #[test]
    fn vectors_print_round_off_as_plus_zero() {
        let v = Vector3::new(-1e-17, -4e-10, -0.0);
        assert_eq!(
            vec3_text(&v, 9),
            "[+0.000000000, +0.000000000, +0.000000000]"
        );
        let v = Vector3::new(-6e-10, 1.25, -2.5);
        assert_eq!(
            vec3_text(&v, 9),
            "[-0.000000001, +1.250000000, -2.500000000]"
        );
        assert_eq!(
            vec3_text(&Vector3::new(-4e-7, 0.0, 3e-7), 6),
            "[+0.000000, +0.000000, +0.000000]"
        );
    }
}

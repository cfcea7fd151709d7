//! A cushion scene's outputs (docs/formats.md#a-ball-against-the-cushion): the JSON report,
//! its text summary, and the trace CSV, one row per [`CushionTraceRow`], streaming.

use crate::base::error::Error;
use crate::base::number::{decimal, shortest, si};
use crate::base::settings::SolverSettings;
use crate::base::validate::finite_output;
use crate::cushion::outcome::{CushionOutcome, CushionPhase, CushionTraceRow};
use crate::outputs::report::{v3, Num, SolverJson};
use crate::outputs::trace_csv::StreamingCsv;
use crate::scene::cushion::CushionScene;
use nalgebra::Vector3;
use serde::Serialize;
use std::io::Write;

/// The header cells of a cushion scene's trace CSV.
pub(crate) const CUSHION_HEADER: [&str; 15] = [
    "P_I (N s)",
    "P_C (N s)",
    "v_x (m/s)",
    "v_y (m/s)",
    "v_z (m/s)",
    "spin_x (rad/s)",
    "spin_y (rad/s)",
    "spin_z (rad/s)",
    "slip_cushion_x (m/s)",
    "slip_cushion_t (m/s)",
    "slip_table_x (m/s)",
    "slip_table_y (m/s)",
    "v_n (m/s)",
    "W (J)",
    "phase",
];

/// The numeric cells of a row, in [`CUSHION_HEADER`]'s order (all but `phase`).
pub(crate) fn row_values(r: &CushionTraceRow) -> [f64; 14] {
    [
        r.p_i,
        r.p_c,
        r.v.x,
        r.v.y,
        r.v.z,
        r.w.x,
        r.w.y,
        r.w.z,
        r.slip_cushion[0],
        r.slip_cushion[1],
        r.slip_table[0],
        r.slip_table[1],
        r.normal_velocity,
        r.work,
    ]
}

/// The name of a phase in the trace (`compression`, `restitution`).
pub(crate) fn phase_name(p: CushionPhase) -> &'static str {
    match p {
        CushionPhase::Compression => "compression",
        CushionPhase::Restitution => "restitution",
    }
}

/// Writes a cushion impact's trace rows as CSV, streaming; the first write error is kept
/// and returned by [`CushionCsv::finish`] (the kernel's trace callback cannot fail).
pub(crate) struct CushionCsv<W: Write> {
    out: StreamingCsv<W>,
}

impl<W: Write> CushionCsv<W> {
    /// A writer that starts with the header line.
    pub(crate) fn new(out: W) -> Result<Self, Error> {
        Ok(CushionCsv {
            out: StreamingCsv::new(out, CUSHION_HEADER)?,
        })
    }

    /// Writes one row (after an earlier error: nothing).
    pub(crate) fn row(&mut self, r: &CushionTraceRow) {
        self.out.row(|out| {
            for (name, v) in CUSHION_HEADER.iter().zip(row_values(r)) {
                let v = finite_output(v, || format!("trace column {name} at P_I = {}", r.p_i))?;
                out.write_field(shortest(v + 0.0))?;
            }
            Ok(out.write_field(phase_name(r.phase))?)
        });
    }

    /// Flushes and returns the underlying writer, or the first error.
    pub(crate) fn finish(self) -> Result<W, Error> {
        self.out.finish()
    }
}

/// The angle (degrees) of the horizontal velocity `v` from the cushion's normal: the
/// incidence (`towards` true: from +y, the direction towards the cushion) or the rebound
/// (from -y, away from it); positive along +x. `None` without horizontal velocity.
pub(crate) fn angle_from_normal(v: &Vector3<f64>, towards: bool) -> Option<f64> {
    let along_normal = if towards { v.y } else { -v.y };
    (v.x != 0.0 || v.y != 0.0).then(|| v.x.atan2(along_normal).to_degrees())
}

/// The horizontal speed |(v_x, v_y)| (m/s).
pub(crate) fn horizontal_speed(v: &Vector3<f64>) -> f64 {
    v.x.hypot(v.y)
}

#[derive(Serialize)]
struct BallJson {
    mass: Num,
    radius: Num,
    alpha: Num,
}

#[derive(Serialize)]
struct CushionJson {
    height: Num,
    contact_angle_deg: Num,
    mu_cushion: Num,
    mu_table: Num,
    restitution: Num,
    rule: &'static str,
}

#[derive(Serialize)]
struct MotionJson {
    velocity: [Num; 3],
    spin: [Num; 3],
}

#[derive(Serialize)]
struct EventJson {
    contact: crate::cushion::outcome::CushionContact,
    kind: crate::cushion::outcome::SlipChange,
    impulse: Num,
}

/// The JSON report of a cushion scene (docs/formats.md#the-cushion-report), keys in order.
#[derive(Serialize)]
pub struct CushionReport {
    name: String,
    target: &'static str,
    ball: BallJson,
    cushion: CushionJson,
    ball_in: MotionJson,
    ball_out: MotionJson,
    incidence_deg: Option<Num>,
    rebound_deg: Option<Num>,
    speed_in: Num,
    speed_out: Num,
    impulse_cushion: Num,
    impulse_compression: Num,
    impulse_table: Num,
    work_compression: Num,
    work_restitution: Num,
    energy_lost: Num,
    lifts_off: bool,
    events: Vec<EventJson>,
    solver: SolverJson,
}

/// The contact angle theta (degrees) of a cushion of height `h` for a ball of radius `r`:
/// sin theta = (h - r) / r.
pub(crate) fn contact_angle_deg(h: f64, r: f64) -> f64 {
    ((h - r) / r).clamp(-1.0, 1.0).asin().to_degrees()
}

impl CushionReport {
    /// The report of `out`, the outcome of `scene` run with `settings`.
    pub fn new(scene: &CushionScene, settings: &SolverSettings, out: &CushionOutcome) -> Self {
        let (b, c) = (&scene.ball, &scene.cushion);
        CushionReport {
            name: scene.name.clone(),
            target: "cushion",
            ball: BallJson {
                mass: Num(b.mass()),
                radius: Num(b.radius()),
                alpha: Num(b.alpha()),
            },
            cushion: CushionJson {
                height: Num(c.height()),
                contact_angle_deg: Num(contact_angle_deg(c.height(), b.radius())),
                mu_cushion: Num(c.mu_cushion()),
                mu_table: Num(c.mu_table()),
                restitution: Num(c.restitution()),
                rule: c.rule().name(),
            },
            ball_in: MotionJson {
                velocity: v3(&scene.velocity),
                spin: v3(&scene.spin),
            },
            ball_out: MotionJson {
                velocity: v3(&out.v),
                spin: v3(&out.w),
            },
            incidence_deg: angle_from_normal(&scene.velocity, true).map(Num),
            rebound_deg: angle_from_normal(&out.v, false).map(Num),
            speed_in: Num(horizontal_speed(&scene.velocity)),
            speed_out: Num(horizontal_speed(&out.v)),
            impulse_cushion: Num(out.impulse_cushion),
            impulse_compression: Num(out.impulse_compression),
            impulse_table: Num(out.impulse_table),
            work_compression: Num(out.work_compression),
            work_restitution: Num(out.work_restitution),
            energy_lost: Num(out.energy_lost),
            lifts_off: out.lifts_off,
            events: out
                .events
                .iter()
                .map(|e| EventJson {
                    contact: e.contact,
                    kind: e.kind,
                    impulse: Num(e.impulse),
                })
                .collect(),
            solver: SolverJson::new(settings, &out.stats),
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

/// The text summary of a cushion impact: what came in, what went out, the impulses and the
/// events, in the units people read.
pub(crate) fn cushion_summary(
    scene: &CushionScene,
    settings: &SolverSettings,
    out: &CushionOutcome,
) -> String {
    let (b, c) = (&scene.ball, &scene.cushion);
    let vec = |v: &Vector3<f64>| format!("[{:+.6}, {:+.6}, {:+.6}]", v.x, v.y, v.z);
    let angle = |a: Option<f64>| a.map_or("-".to_string(), |a| format!("{a:.3} deg"));
    let mut s = String::new();
    s += &format!("{}\n", scene.name);
    s += &format!(
        "  cushion at height {} (contact {:.3} deg above the equator), mu_cushion {}, mu_table \
         {}, restitution {} ({}), method {}\n",
        si(c.height(), "m", 5),
        contact_angle_deg(c.height(), b.radius()),
        decimal(c.mu_cushion(), 6),
        decimal(c.mu_table(), 6),
        decimal(c.restitution(), 6),
        c.rule().name(),
        settings.method(),
    );
    s += &format!(
        "  in    v {} m/s  spin {} rad/s  incidence {}, {} m/s\n",
        vec(&scene.velocity),
        vec(&scene.spin),
        angle(angle_from_normal(&scene.velocity, true)),
        decimal(horizontal_speed(&scene.velocity), 6),
    );
    s += &format!(
        "  out   v {} m/s  spin {} rad/s  rebound {}, {} m/s\n",
        vec(&out.v),
        vec(&out.w),
        angle(angle_from_normal(&out.v, false)),
        decimal(horizontal_speed(&out.v), 6),
    );
    s += &format!(
        "  impulse: cushion {} N s ({} in compression), table {} N s; energy lost {} J{}\n",
        decimal(out.impulse_cushion, 7),
        decimal(out.impulse_compression, 7),
        decimal(out.impulse_table, 7),
        decimal(out.energy_lost, 6),
        if out.lifts_off {
            "; the ball leaves the cloth"
        } else {
            ""
        },
    );
    if out.events.is_empty() {
        s += "  events: none (both contacts slide throughout)\n";
    } else {
        s += "  events:";
        for e in &out.events {
            s += &format!(
                " {} {} at P_I = {} N s;",
                contact_name(e.contact),
                change_name(e.kind),
                decimal(e.impulse, 6)
            );
        }
        s.pop();
        s += "\n";
    }
    s += &format!(
        "  solver: {} rhs evaluations, {} accepted and {} rejected steps\n",
        out.stats.rhs_evaluations, out.stats.accepted_steps, out.stats.rejected_steps
    );
    s
}

/// A contact's name in text (`cushion`, `table`).
pub(crate) fn contact_name(c: crate::cushion::outcome::CushionContact) -> &'static str {
    match c {
        crate::cushion::outcome::CushionContact::Cushion => "cushion",
        crate::cushion::outcome::CushionContact::Table => "table",
    }
}

/// A change of slip state in text (`sticks`, `reverses`, ...).
pub(crate) fn change_name(k: crate::cushion::outcome::SlipChange) -> &'static str {
    use crate::cushion::outcome::SlipChange;
    match k {
        SlipChange::Sticks => "sticks",
        SlipChange::Reverses => "reverses",
        SlipChange::Restarts => "restarts",
        SlipChange::LiftsOff => "lifts off",
        SlipChange::TouchesDown => "touches down",
    }
}

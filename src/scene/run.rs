//! Running a scene: the collision in the centre-of-mass frame, the outcome, and its lab
//! form.

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{check_samples, Sampling, SolverSettings};
use crate::model::frame::{Frame, LabScene};
use crate::model::state::{CmState, LabBall, LabMotion};
use crate::model::trace::TraceSink;
use crate::scene::compliant::{run_compliant, CompliantRun};
use crate::scene::types::{table_needs_lab_scene, LabFrame, Scene, TangentialLaw};
use crate::solve::law_outcome::solve_law;
use crate::solve::outcome::{solve, Outcome};
use crate::table_phase::outcome::TableOutcome;

/// The outcome of a scene, with the lab-frame motions for lab scenes.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOutcome {
    /// The centre-of-mass outcome and its checks.
    pub outcome: Outcome,
    /// Settings used.
    pub settings: SolverSettings,
    /// Incoming centre-of-mass state (for lab scenes, the lab state in the paper's frame).
    pub cm_in: CmState,
    /// Outgoing lab motions of A and B (lab scenes).
    pub lab_out: Option<(LabMotion, LabMotion)>,
    /// Throw angle (degrees), counter-clockwise about `up` (+z of the paper's frame for
    /// centre-of-mass scenes); `None` when undefined.
    pub throw_angle_deg: Option<f64>,
    /// The table phase after separation (effect `table`).
    pub table: Option<TableOutcome>,
    /// For a plane scene, the ball's outgoing velocity and spin (lab axes); the other fields
    /// are those of its equivalent pair (docs/plane.md).
    pub plane_out: Option<LabMotion>,
    /// With `contact.tangential = "mindlin"`, what the compliant kernel adds (its outcome,
    /// the spring's final displacement, the trace with the tangential force); `None` for the
    /// rigid contact.
    pub compliant: Option<CompliantRun>,
}

/// Runs `scene` with `settings`, optionally streaming a trace (centre-of-mass frame).
pub fn run_scene(
    scene: &Scene,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<SceneOutcome, Error> {
    if let Some((_, Sampling::Uniform(n))) = &trace {
        check_samples("samples", *n)?;
    }
    let (collision, lab) = scene.collision()?;
    let (mut outcome, compliant, settings) = match (scene.tangential, &scene.law) {
        (TangentialLaw::Mindlin, _) => {
            let (o, c) = run_compliant(scene, &collision, settings, trace)?;
            // The kernel steps with its own Dormand-Prince 5(4) at the settings' tolerances.
            (o, Some(c), settings.with_method(Method::Dopri5))
        }
        (TangentialLaw::Rigid, Some(law)) => (
            solve_law(&collision, law, settings, trace)?,
            None,
            *settings,
        ),
        (TangentialLaw::Rigid, None) => (
            solve(&collision, &scene.profile, settings, trace)?,
            None,
            *settings,
        ),
    };
    let out = outcome.result.out;
    if let Some(plane) = scene.plane()? {
        let plane_out = match &compliant {
            Some(c) => LabMotion {
                velocity: c.outcome.velocity,
                spin: c.outcome.spin,
            },
            None => LabMotion {
                velocity: plane.velocity_of(&out),
                spin: plane.spin_of(&out),
            },
        };
        return Ok(SceneOutcome {
            outcome,
            settings,
            cm_in: collision.incoming,
            lab_out: None,
            throw_angle_deg: None,
            table: None,
            plane_out: Some(plane_out),
            compliant,
        });
    }
    let (lab_out, throw, lab_momentum_error, table) = match lab {
        Some(LabFrame { frame, lab }) => {
            let (a, b, throw) = frame.outgoing(lab, &out, outcome.result.collided());
            // m_A (v_A + (m_B/m_A) v_B): m (v_A + v_B) exactly for identical balls.
            let (m, ratio) = (
                scene.balls.a.mass(),
                scene.balls.b.mass() / scene.balls.a.mass(),
            );
            let dp = (m * (a.velocity + ratio * b.velocity)
                - m * (lab.a.velocity + ratio * lab.b.velocity))
                .amax();
            let err = if dp == 0.0 {
                0.0
            } else {
                dp / collision.scales.impulse
            };
            let table = table_phase(scene, lab, (a, b), collision.scales.speed)?;
            (Some((a, b)), throw, err, table)
        }
        None => {
            if scene.effects.table {
                return Err(table_needs_lab_scene());
            }
            // B's velocity in the paper's frame is -U.
            let (b_in, b_out) = (-collision.incoming.u_cm, -out.u_cm);
            let throw = Frame::paper().throw_of(&(b_out - b_in), outcome.result.collided());
            (None, throw, 0.0, None)
        }
    };
    // The lab momentum of both balls is conserved: fold its error into the check.
    outcome.check.momentum_error = outcome.check.momentum_error.max(lab_momentum_error);
    if !scene.effects.table && scene.table.is_some() {
        outcome.warnings.push(
            "[table] is given but the effect table is off ([effects] table = false): the run \
             ends at separation"
                .into(),
        );
    }
    Ok(SceneOutcome {
        outcome,
        settings,
        cm_in: collision.incoming,
        lab_out,
        throw_angle_deg: throw,
        table,
        plane_out: None,
        compliant,
    })
}

/// The effect `table` of a lab scene: both balls from separation, with the outgoing lab
/// motions `a` and `b`, until they roll (`None` when the effect is off).
fn table_phase(
    scene: &Scene,
    lab: &LabScene,
    (a, b): (LabMotion, LabMotion),
    speed_scale: f64,
) -> Result<Option<TableOutcome>, Error> {
    let Some(table) = scene.cloth_under(lab)? else {
        return Ok(None);
    };
    let start = |p: &LabBall, m: LabMotion| LabBall {
        position: p.position,
        velocity: m.velocity,
        spin: m.spin,
    };
    Ok(Some(TableOutcome::new(
        &scene.balls,
        table,
        &start(&lab.a, a),
        &start(&lab.b, b),
        [lab.a.velocity, lab.b.velocity],
        speed_scale,
    )?))
}

//! Running a scene: the collision in the centre-of-mass frame, the outcome, and its lab
//! form.

use crate::contact::outcome::{solve, Outcome};
use crate::error::Error;
use crate::formats::scene::Scene;
use crate::formats::trace::TraceSink;
use crate::integrator::{Sampling, SolverSettings};
use crate::model::frame::Frame;
use crate::model::state::LabMotion;
use crate::table_phase::TableOutcome;
use nalgebra::{Matrix3, Vector3};

/// The outcome of a scene, with the lab-frame motions for lab scenes.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOutcome {
    /// The centre-of-mass outcome and its checks.
    pub outcome: Outcome,
    /// Settings used.
    pub settings: SolverSettings,
    /// Outgoing lab motions of A and B (lab scenes).
    pub lab_out: Option<(LabMotion, LabMotion)>,
    /// Throw angle (degrees), counter-clockwise about `up` (+z of the paper's frame for
    /// centre-of-mass scenes); `None` when undefined.
    pub throw_angle_deg: Option<f64>,
    /// The table phase after separation (effect `table`).
    pub table: Option<TableOutcome>,
}

/// Runs `scene` with `settings`, optionally streaming a trace (centre-of-mass frame).
pub fn run_scene(
    scene: &Scene,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<SceneOutcome, Error> {
    let (collision, frame) = scene.collision()?;
    let mut outcome = solve(&collision, &scene.profile, settings, trace)?;
    let du = outcome.out.u_cm - collision.incoming.u_cm;
    let (lab_out, throw, lab_momentum_error) = match frame {
        Some(f) => {
            let (a, b) = f.to_lab(&outcome.out);
            let (a0, b0) = match &scene.incoming {
                crate::formats::scene::Incoming::Lab(l) => (l.a.velocity, l.b.velocity),
                crate::formats::scene::Incoming::Cm(_) => {
                    unreachable!("a frame comes from a lab scene")
                }
            };
            let m = scene.ball.mass;
            let dp = (m * (a.velocity + b.velocity) - m * (a0 + b0)).amax();
            let err = if dp == 0.0 {
                0.0
            } else {
                dp / collision.scales.impulse
            };
            let dvb = b.velocity - b0;
            (Some((a, b)), f.throw_angle_deg(&dvb), err)
        }
        None => {
            let paper = Frame {
                basis: Matrix3::identity(),
                v_cm: Vector3::zeros(),
                up: Vector3::z(),
            };
            (None, paper.throw_angle_deg(&-du), 0.0)
        }
    };
    // The lab momentum of both balls is conserved: fold its error into the check.
    outcome.check.momentum_error = outcome.check.momentum_error.max(lab_momentum_error);
    let table = run_table(scene, &collision, lab_out, &mut outcome.warnings)?;
    Ok(SceneOutcome {
        outcome,
        settings: *settings,
        lab_out,
        throw_angle_deg: throw,
        table,
    })
}

/// The effect `table`: both balls from separation until they roll (`None` when off).
fn run_table(
    scene: &Scene,
    collision: &crate::model::collision::Collision,
    lab_out: Option<(LabMotion, LabMotion)>,
    warnings: &mut Vec<String>,
) -> Result<Option<TableOutcome>, Error> {
    let Some(table) = scene.cloth()? else {
        if scene.table.is_some() {
            warnings.push(
                "[table] is given but the effect table is off ([effects] table = false): the run \
                 ends at separation"
                    .into(),
            );
        }
        return Ok(None);
    };
    let (crate::formats::scene::Incoming::Lab(lab), Some((a, b))) = (&scene.incoming, lab_out)
    else {
        unreachable!("Scene::cloth accepts lab scenes only");
    };
    let start = |p: nalgebra::Vector3<f64>, m: LabMotion| crate::model::state::LabBall {
        position: p,
        velocity: m.velocity,
        spin: m.spin,
    };
    Ok(Some(TableOutcome::new(
        &scene.ball,
        table,
        &start(lab.a.position, a),
        &start(lab.b.position, b),
        [lab.a.velocity, lab.b.velocity],
        collision.scales.speed,
    )?))
}

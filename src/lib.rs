#![doc = "billiard-contact: the contact phase of billiard-ball collisions (Peskin 2020)."]
#![warn(missing_docs)]

mod apps;
mod contact;
mod error;
pub mod formats;
mod integrator;
mod model;
pub mod profile;
pub mod table_phase;

pub use apps::batch;
#[cfg(feature = "plots")]
pub use apps::plot;
pub use apps::work_precision;

pub use apps::runner::{run_scene, SceneOutcome};
pub use contact::closed_form::ClosedForm;
pub use contact::outcome::{solve, Outcome};
pub use contact::result::ContactResult;
pub use error::Error;
pub use formats::report::Report;
pub use formats::scene::{Incoming, Scene};
pub use formats::trace::{CsvTrace, TraceRow, TraceSink};
pub use integrator::{Method, Sampling, SolverSettings, Stats};
pub use model::collision::Collision;
pub use model::effects::Effects;
pub use model::frame::{Frame, LabScene};
pub use model::params::{Ball, Contact, Friction, ImpulseRule};
pub use model::state::{CmState, LabBall, LabMotion};
pub use nalgebra;
pub use profile::{ForceProfile, Profile};

/// For experts: the pieces under the entry points (the integrator driver, the closed-form
/// batch kernel, the checks), for callers who drive them directly.
pub mod details {
    pub use crate::contact::check::{checks, state_error, Checks};
    pub use crate::contact::closed_form::ClosedFormBatch;
    pub use crate::integrator::{integrate, Integrated, DEFAULT_RTOL, DEFAULT_STEPS};
    pub use crate::model::effects::{EffectInfo, CATALOGUE};
}

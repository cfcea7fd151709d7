#![doc = "billiard-contact: the contact phase of billiard-ball collisions (Peskin 2020)."]
#![warn(missing_docs)]

pub mod batch;
pub mod check;
pub mod closed_form;
pub mod collision;
pub mod dynamics;
pub mod effects;
pub mod error;
pub mod frame;
pub mod friction;
pub mod integrate;
pub mod outcome;
pub mod output;
pub mod params;
pub mod path;
pub mod profile;
pub mod state;
pub mod table;
pub mod trace;

pub use closed_form::ClosedForm;
pub use collision::Collision;
pub use effects::Effects;
pub use error::Error;
pub use integrate::{Method, Sampling, SolverSettings, Stats};
pub use outcome::{solve, Outcome};
pub use params::{Ball, Contact, Friction, ImpulseRule};
pub use profile::{ForceProfile, Profile};
pub use state::{CmState, LabBall, LabMotion};
pub use nalgebra;
pub use report::Report;
pub use runner::{run_scene, SceneOutcome};
pub use scene::{Incoming, Scene};
pub use trace::{CsvTrace, TraceRow, TraceSink};
#[cfg(feature = "plots")]
pub mod plot;
pub mod report;
pub mod runner;
pub mod scene;
pub mod study;

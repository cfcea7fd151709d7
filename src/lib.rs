//! # billiard-contact
//!
//! The contact phase of a collision between two billiard balls with spin and Coulomb friction,
//! after C. S. Peskin, *Collision of Billiard Balls in 3D with Spin and Friction* (2020): the
//! exact closed form of the paper (eqs 24-35 with the impulse of eqs 52 and 56), extended to
//! sliding that stops during the contact, and a time-stepping integrator of the paper's
//! eqs 14-19 under a chosen normal-force profile that checks itself against the closed form.
//! The model, with every equation the code numbers, is in `docs/model.md`; the file formats in
//! `docs/formats.md`.
//!
//! ## Where to start
//!
//! There are two entry points.
//!
//! **One collision in memory**: build a [`Collision`] from the balls ([`Ball`]), the contact
//! ([`Contact`]: friction and impulse rule), the [`Effects`] to simulate and the incoming
//! centre-of-mass state ([`CmState`]), then [`solve`] it with a force [`profile`] and
//! [`SolverSettings`]. The [`Outcome`] holds the [`ContactResult`] (outgoing state, impulse,
//! sliding, heat), the stick time and the checks.
//!
//! ```
//! use billiard_contact::nalgebra::Vector3;
//! use billiard_contact::profile::HalfSine;
//! use billiard_contact::*;
//!
//! let ball = Ball::new(0.17, 0.028575, 0.4)?; // kg, m, I = alpha m r^2
//! let contact = Contact {
//!     friction: Friction::constant(0.06)?,
//!     impulse: ImpulseRule::restitution(1.0)?,
//! };
//! // A stun cut: U = (1, 0.5, 0) m/s (ball A in the centre-of-mass frame), no spin.
//! let incoming = CmState::new(Vector3::new(1.0, 0.5, 0.0), Vector3::zeros(), Vector3::zeros());
//! let collision = Collision::new(ball, contact, Effects::default(), incoming)?;
//! let outcome = solve(&collision, &HalfSine::new(2.5e-4)?, &SolverSettings::default(), None)?;
//! // S(0) = 2V = 1 m/s never reaches 0 (p_stick = m S(0) / (2 mu (1 + 1/alpha)) > P = 2 m U(0)),
//! // so friction acts throughout: V' = V - mu P / m = 0.5 - 2 (0.06) (1) = 0.38 m/s (eqs 24-25).
//! assert!((outcome.result.out.u_cm.y - 0.38).abs() < 1e-10);
//! assert!((outcome.result.out.u_cm.x + 1.0).abs() < 1e-10);
//! # Ok::<(), billiard_contact::Error>(())
//! ```
//!
//! **A scene file** (TOML, `docs/formats.md`): [`Scene::load`] reads and validates it,
//! [`run_scene`] runs it with its own solver settings (or others), and [`Report`] is the JSON
//! the command line prints. A scene can also be built in code, key by key, with
//! [`SceneBuilder`], which validates it as the file reader does.
//!
//! ```
//! use billiard_contact::{run_scene, Scene};
//!
//! let scene = Scene::load("data/scenes/default.toml".as_ref())?;
//! let result = run_scene(&scene, &scene.solver, None)?;
//! // A cue ball rolling at 1.5 m/s into a 30 degree cut: the paper's special case gives the
//! // object ball's throw as tan(throw) = mu v sin(cut) / v = 0.06 (0.5) = 0.03.
//! let throw = result.throw_angle_deg.unwrap();
//! assert!((throw - 0.03f64.atan().to_degrees()).abs() < 1e-9);
//! # Ok::<(), billiard_contact::Error>(())
//! ```
//!
//! **The other contacts of a ball**: a plane (a wall, the table's bed) with
//! [`PlaneCollision`] and [`solve_plane`] (`docs/plane.md`); a cushion, touching the cloth at
//! the same time, with [`resolve_cushion`] or a cushion scene file, [`CushionScene`]
//! (`docs/cushion.md`); a plane with an elastic tangential compliance instead of the stick
//! rule, [`resolve_sphere_plane_compliant`], and two balls with it,
//! [`resolve_sphere_sphere_compliant`] (`docs/tangential.md`).
//!
//! Expert pieces (the integrator driver, the closed-form batch kernel, the checks) are in
//! [`details`]; many collisions at once in [`batch`]; the cost of accuracy in
//! [`work_precision`]; the balls' motion on the cloth after the contact in [`table_phase`].
//!
//! ## Units and frames
//!
//! | quantity | unit | frame and sign |
//! |---|---|---|
//! | mass, radius | kg, m | |
//! | `alpha` | 1 | moment of inertia I = alpha m r^2 (solid ball 2/5) |
//! | velocity, slip S | m/s | centre-of-mass frame: line of centres along +x, ball A at x = -r, B at +r; U is A's velocity, B's is -U; U > 0: the balls approach |
//! | spin Omega^A, Omega^B | rad/s | right-handed, same axes |
//! | force, impulse | N, N s | p(t) is the normal impulse so far, P the total |
//! | time, duration | s | the contact lasts (0, tau) |
//! | theta | rad | direction of sliding in the y-z plane, eqs 5-6 |
//! | heat | J | H total loss, H_sfr the sliding-friction part |
//! | lab frame | m, m/s, rad/s | any axes; `up` is the table's normal; throw is counter-clockwise about `up`, in degrees |
#![warn(missing_docs)]
#![warn(unreachable_pub)]

// The layers, lowest first (docs/architecture.md): base; model and profile; the kernels
// closed_form, integrator and table_phase; solve; scene; outputs; apps; cli. Each imports
// only itself and the layers below it, never through this file's re-exports
// (tests/layering.rs checks it). Without the command line some of the writers and the
// apps' helpers have no caller.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
mod apps;
mod base;
#[cfg(feature = "cli")]
pub mod cli;
mod closed_form;
mod cluster;
mod cushion;
mod integrator;
mod model;
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
mod outputs;
pub mod profile;
mod scene;
mod solve;
pub mod table_phase;
mod tangential;

pub use apps::batch;
#[cfg(feature = "plots")]
pub use apps::plot;
pub use apps::sweep;
pub use apps::work_precision;

pub use base::error::Error;
pub use base::method::Method;
pub use base::settings::{Sampling, SolverSettings, Stats};
pub use closed_form::kernel::ClosedForm;
pub use cluster::params::{
    Cluster, ClusterBall, ClusterCloth, ClusterLaw, ClusterTangential, PairDamping,
    CLOTH_DEFAULT_GRAVITY, CLOTH_DEFAULT_MU, CLUSTER_CLOTH_FIELD, CLUSTER_MAX_POSITION,
    CLUSTER_TANGENTIAL_FIELD, CLUSTER_TOUCH_TOLERANCE, MAX_CLUSTER_BALLS,
};
pub use cluster::resolve::{
    resolve_cluster, resolve_cluster_traced, BallOut, ClusterOutcome, ClusterSampling,
    ClusterSettings, ClusterStats, ClusterTrace, ClusterTraceRow, ContactRecord, ContactTrace,
    StopReason, CLUSTER_DEFAULT_RTOL, CLUSTER_MAX_STEPS,
};
pub use cushion::impact::resolve_cushion;
pub use cushion::outcome::{
    CushionContact, CushionOutcome, CushionPhase, CushionTraceRow, SlipChange, SlipEvent,
};
pub use cushion::params::{Cushion, CushionRestitution};
pub use model::collision::Collision;
pub use model::contact_law::{ContactLaw, Damping};
pub use model::effects::Effects;
pub use model::frame::{Frame, LabScene, TOUCH_TOLERANCE};
pub use model::material::{HertzContact, Material};
pub use model::params::{
    Ball, BallPair, Contact, Evaluate, Friction, FrictionLaw, ImpulseRule, ALPHA_MAX, ALPHA_MIN,
    ALPHA_SOLID, MU_MAX,
};
pub use model::result::ContactResult;
pub use model::state::{CmState, LabBall, LabMotion};
pub use model::trace::{TraceRow, TraceSink};
pub use nalgebra;
pub use outputs::cluster::ClusterReport;
pub use outputs::cushion::CushionReport;
pub use outputs::report::Report;
pub use outputs::trace_csv::CsvTrace;
pub use scene::builder::{ForceSpec, LawSpec, SceneBuilder};
pub use scene::cluster::ClusterScene;
pub use scene::compliant::{CompliantRow, CompliantRun};
pub use scene::cushion::CushionScene;
pub use scene::file::{is_cluster_scene, is_cushion_scene};
pub use scene::overrides::SolverOverrides;
pub use scene::run::{run_scene, SceneOutcome};
pub use scene::types::{Incoming, PlaneIncoming, Scene, TangentialLaw};
pub use solve::law_outcome::solve_law;
pub use solve::outcome::{solve, LawOutcome, Outcome};
pub use solve::plane::{solve_plane, solve_plane_law, PlaneCollision, PlaneOutcome};
pub use tangential::impact::{
    resolve_sphere_plane_compliant, resolve_sphere_plane_compliant_damped,
};
pub use tangential::outcome::{CompliantOutcome, CompliantPairOutcome, CompliantTraceRow};
pub use tangential::pair::{
    resolve_sphere_sphere_compliant, resolve_sphere_sphere_compliant_damped, CompliantSphere,
};

/// For experts: the pieces under the entry points (the integrator driver, the closed-form
/// batch kernel, the checks, a contact law's head-on run and calibration), for callers who
/// drive them directly.
pub mod details {
    pub use crate::base::settings::{DEFAULT_RTOL, DEFAULT_STEPS, MAX_SAMPLES, MAX_STEPS};
    pub use crate::closed_form::kernel::ClosedFormBatch;
    pub use crate::closed_form::plane::{plane_impact, plane_slip, PlaneImpact};
    pub use crate::integrator::calibrate::CALIBRATION_RTOL;
    pub use crate::integrator::driver::{integrate, Integrated};
    pub use crate::integrator::law::HeadOn;
    pub use crate::model::effects::{EffectInfo, CATALOGUE};
    pub use crate::model::material::{elastic_impact, hertz_stiffness, sphere_plane_stiffness};
    pub use crate::solve::check::{checks, state_error, Checks};
}

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
//! the command line prints.
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
pub use apps::sweep;
pub use apps::work_precision;

pub use apps::runner::{run_scene, SceneOutcome};
pub use contact::closed_form::ClosedForm;
pub use contact::law_outcome::{solve_law, LawOutcome};
pub use contact::outcome::{solve, Outcome};
pub use contact::result::ContactResult;
pub use error::Error;
pub use formats::report::Report;
pub use formats::scene::{Incoming, Scene};
pub use formats::trace::{CsvTrace, TraceRow, TraceSink};
pub use integrator::law::HeadOn;
pub use integrator::{Method, Sampling, SolverSettings, Stats};
pub use model::collision::Collision;
pub use model::contact_law::{ContactLaw, Damping};
pub use model::effects::Effects;
pub use model::frame::{Frame, LabScene, TOUCH_TOLERANCE};
pub use model::material::{HertzContact, Material};
pub use model::params::{
    Ball, BallPair, Contact, Evaluate, Friction, FrictionLaw, ImpulseRule, ALPHA_MAX, ALPHA_MIN,
    ALPHA_SOLID, MU_MAX,
};
pub use model::state::{CmState, LabBall, LabMotion};
pub use nalgebra;
pub use profile::{ForceProfile, Profile};

/// For experts: the pieces under the entry points (the integrator driver, the closed-form
/// batch kernel, the checks), for callers who drive them directly.
pub mod details {
    pub use crate::contact::check::{checks, state_error, Checks};
    pub use crate::contact::closed_form::ClosedFormBatch;
    pub use crate::integrator::law::{head_on, LAW_SPAN};
    pub use crate::integrator::{
        integrate, Integrated, TimeMap, DEFAULT_RTOL, DEFAULT_STEPS, GRADED_ENDS,
    };
    pub use crate::model::contact_law::CALIBRATION_RTOL;
    pub use crate::model::effects::{EffectInfo, CATALOGUE};
    pub use crate::model::material::{elastic_impact, hertz_stiffness, reduced_mass};
}

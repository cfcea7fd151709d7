//! The rows of a batch resolved: what every row shares, a row's overrides, input and
//! output, and the resolution of one row, a slice of rows, or bare closed-form states.

use crate::base::error::Error;
use crate::base::fields::YOUNGS_MODULUS_FIELD;
use crate::base::method::Method;
use crate::base::settings::SolverSettings;
use crate::closed_form::kernel::ClosedFormBatch;
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::effects::Effects;
use crate::model::material::{hertz_stiffness, HertzContact, Material};
use crate::model::params::{Ball, BallPair, Contact, Friction, ImpulseRule};
use crate::model::result::ContactResult;
use crate::model::state::{CmState, LabMotion};
use crate::profile::force::ForceProfile;
use crate::profile::spec::Profile;
use crate::scene::types::{Incoming, LabFrame, Scene};
use crate::solve::law_outcome::solve_law;
use crate::solve::outcome::solve;
use rayon::prelude::*;

/// What every row shares: the scene's parameters and the method.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchSetup {
    /// The balls (every row's, see [`Overrides`]).
    pub balls: BallPair,
    /// Friction and impulse rule.
    pub contact: Contact,
    /// Effects.
    pub effects: Effects,
    /// Normal-force profile (its duration is the default duration).
    pub profile: Profile,
    /// The balls' material, when the scene gives it: each row's duration is then its own
    /// Hertz contact time.
    pub material: Option<Material>,
    /// Method and tolerances.
    pub settings: SolverSettings,
    /// The scene's contact law (docs/contact-law.md), when the force comes from the
    /// compression: each row realises its own impulse and duration.
    pub law: Option<ContactLaw>,
}

impl BatchSetup {
    /// The parameters of `scene`, solved with `settings`.
    pub fn from_scene(scene: &Scene, settings: SolverSettings) -> Self {
        BatchSetup {
            balls: scene.balls,
            contact: scene.contact,
            effects: scene.effects,
            profile: scene.profile.clone(),
            material: scene.material,
            settings,
            law: scene.law,
        }
    }
}

/// Per-row overrides of the setup (`None`: the setup's value). `mass`, `radius` and `alpha`
/// change both balls of a setup of identical balls; a setup of unequal balls refuses them
/// (which ball they would change is ambiguous).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overrides {
    /// Mass (kg).
    pub mass: Option<f64>,
    /// Radius (m).
    pub radius: Option<f64>,
    /// I = alpha m r^2.
    pub alpha: Option<f64>,
    /// Constant friction coefficient.
    pub mu: Option<f64>,
    /// Restitution e (P = (1 + e) m U(0)).
    pub restitution: Option<f64>,
    /// Explicit impulse P (N s).
    pub impulse: Option<f64>,
    /// Contact duration (s).
    pub duration: Option<f64>,
}

impl Overrides {
    fn is_empty(&self) -> bool {
        *self == Overrides::default()
    }
}

/// One collision of a batch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchInput {
    /// Incoming state, centre-of-mass or lab frame.
    pub incoming: Incoming,
    /// Overrides of the setup.
    pub overrides: Overrides,
}

impl BatchInput {
    /// A centre-of-mass state with the setup's parameters.
    pub fn cm(state: CmState) -> Self {
        BatchInput {
            incoming: Incoming::Cm(state),
            overrides: Overrides::default(),
        }
    }
}

/// The result of one collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchOutput {
    /// Impulses, sliding, heat and the outgoing centre-of-mass state.
    pub result: ContactResult,
    /// When sliding stopped (s); `None` when it did not.
    pub stick_time: Option<f64>,
    /// Outgoing lab motions of A and B, and the throw angle (degrees), for lab input.
    pub lab: Option<(LabMotion, LabMotion, Option<f64>)>,
    /// Distance to the closed form (time stepping; 0 for the closed form).
    pub closed_form_error: f64,
    /// Right-hand-side evaluations (time stepping).
    pub rhs_evaluations: u64,
}

/// The ball and contact of a row: the setup's, or with the row's overrides.
pub(super) fn params_of(setup: &BatchSetup, o: &Overrides) -> Result<(BallPair, Contact), Error> {
    if o.is_empty() {
        return Ok((setup.balls, setup.contact));
    }
    let b = setup.balls.a;
    let ball_keys = [("mass", o.mass), ("radius", o.radius), ("alpha", o.alpha)];
    let balls = match ball_keys.iter().find_map(|(k, v)| v.map(|v| (k, v))) {
        None => setup.balls,
        Some((key, value)) if !setup.balls.is_identical() => {
            return Err(Error::invalid(
                *key,
                value,
                "no mass, radius or alpha column with a scene of unequal balls ([balls.a] and \
                 [balls.b] apply to every row)",
            ))
        }
        Some(_) => BallPair::identical(Ball::new(
            o.mass.unwrap_or(b.mass()),
            o.radius.unwrap_or(b.radius()),
            o.alpha.unwrap_or(b.alpha()),
        )?),
    };
    let friction = match o.mu {
        Some(mu) => Friction::constant(mu)?,
        None => setup.contact.friction,
    };
    let impulse =
        ImpulseRule::from_either("", o.restitution, o.impulse)?.unwrap_or(setup.contact.impulse);
    if let Some(d) = o.duration {
        crate::base::validate::positive("duration", d, "s")?;
    }
    Ok((balls, Contact { friction, impulse }))
}

/// The contact duration of a row (s): its `duration` column, else the Hertz contact time of
/// the setup's material for the row's balls and approach speed (balls that approach), else
/// the profile's.
pub(super) fn row_duration(
    setup: &BatchSetup,
    o: &Overrides,
    balls: &BallPair,
    cm: &CmState,
) -> Result<f64, Error> {
    match (o.duration, &setup.material) {
        (Some(d), Some(m)) => Err(Error::invalid(
            "duration",
            format!(
                "{d} s together with the scene's {YOUNGS_MODULUS_FIELD} = {}",
                m.youngs_modulus()
            ),
            "one of them: with the material each row's contact time follows from its balls and \
             approach speed; leave out the column, or the material",
        )),
        (Some(d), None) => Ok(d),
        (None, Some(m)) if cm.u_cm.x > 0.0 => {
            Ok(HertzContact::of_pair(balls, m, cm.u_cm.x)?.duration)
        }
        (None, _) => Ok(setup.profile.duration()),
    }
}

/// Resolves one collision with the setup's method. The closed form
/// ([`ClosedFormBatch`]: the same numbers as [`crate::ClosedForm`]) skips the checks (they hold to
/// round-off by construction) and computes the stick time only when sliding stops.
pub fn resolve(setup: &BatchSetup, input: &BatchInput) -> Result<BatchOutput, Error> {
    resolve_with(setup, None, input)
}

/// The closed-form kernel of the setup's own parameters, when the method is the closed form.
pub(super) fn shared_kernel(setup: &BatchSetup) -> Option<ClosedFormBatch> {
    (setup.settings.method() == Method::ClosedForm)
        .then(|| ClosedFormBatch::new(setup.balls, setup.contact, setup.effects))
}

/// [`resolve`] with the closed-form kernel of the setup's own parameters when the caller
/// made it once for many rows (`shared`; used for rows without overrides).
pub(crate) fn resolve_with(
    setup: &BatchSetup,
    shared: Option<&ClosedFormBatch>,
    input: &BatchInput,
) -> Result<BatchOutput, Error> {
    let (balls, contact) = params_of(setup, &input.overrides)?;
    let (cm, lab) = input.incoming.to_cm(&balls)?;
    if let Some(law) = &setup.law {
        let mut out = resolve_law(setup, law, &input.overrides, balls, contact, &cm)?;
        if let Some(LabFrame { frame, lab }) = lab {
            out.lab = Some(frame.outgoing(lab, &out.result.out, out.result.collided()));
        }
        return Ok(out);
    }
    let profile = &setup.profile;
    let time_scale = row_duration(setup, &input.overrides, &balls, &cm)?;
    let mut out = if setup.settings.method() == Method::ClosedForm {
        let own;
        let kernel = match shared {
            Some(k) if input.overrides.is_empty() => k,
            _ => {
                own = ClosedFormBatch::new(balls, contact, setup.effects);
                &own
            }
        };
        let mut result = kernel.resolve(&cm)?;
        let stick_time = result.stick_fraction(profile).map(|s| time_scale * s);
        if !result.collided() {
            result.stick_impulse = None;
        }
        BatchOutput {
            result,
            stick_time,
            lab: None,
            closed_form_error: 0.0,
            rhs_evaluations: 0,
        }
    } else {
        let c = Collision::new(balls, contact, setup.effects, cm)?;
        let o = solve(&c, profile, &setup.settings, None)?;
        BatchOutput {
            result: o.result,
            stick_time: o.stick_time.map(|t| t / profile.duration() * time_scale),
            lab: None,
            closed_form_error: o.check.closed_form_error,
            rhs_evaluations: o.stats.rhs_evaluations,
        }
    };
    if let Some(LabFrame { frame, lab }) = lab {
        out.lab = Some(frame.outgoing(lab, &out.result.out, out.result.collided()));
    }
    Ok(out)
}

/// One row under the setup's contact law: the row's restitution, impulse and duration
/// columns are refused (the law decides them); with the balls' material the stiffness
/// follows from the row's ball.
pub(super) fn resolve_law(
    setup: &BatchSetup,
    law: &ContactLaw,
    o: &Overrides,
    balls: BallPair,
    contact: Contact,
    cm: &CmState,
) -> Result<BatchOutput, Error> {
    let given = [
        ("restitution", o.restitution),
        ("impulse", o.impulse),
        ("duration", o.duration),
    ];
    if let Some((column, Some(v))) = given.iter().find(|(_, v)| v.is_some()) {
        return Err(Error::invalid(
            *column,
            format!("{v} with the scene's [contact.law]"),
            "no restitution, impulse or duration column: the law decides them for every row",
        ));
    }
    let law = match &setup.material {
        Some(m) if balls != setup.balls => ContactLaw::new(
            hertz_stiffness((&balls.a, m), (&balls.b, m)).2,
            law.damping(),
            law.coefficient(),
        )?,
        _ => *law,
    };
    let contact = Contact {
        impulse: ImpulseRule::ELASTIC,
        ..contact
    };
    let c = Collision::new(balls, contact, setup.effects, *cm)?;
    let o = solve_law(&c, &law, &setup.settings, None)?;
    Ok(BatchOutput {
        result: o.result,
        stick_time: o.stick_time,
        lab: None,
        closed_form_error: o.check.closed_form_error,
        rhs_evaluations: o.stats.rhs_evaluations,
    })
}

/// Resolves a slice of collisions in parallel (rayon's current pool), in order: element i
/// of the result belongs to `inputs[i]`.
///
/// ```
/// use billiard_contact::batch::{resolve_slice, BatchInput, BatchSetup};
/// use billiard_contact::{Scene, CmState, Method, SolverSettings};
/// use nalgebra::Vector3;
/// let setup = BatchSetup::from_scene(
///     &Scene::default_scene(),
///     SolverSettings::default().with_method(Method::ClosedForm),
/// );
/// let head_on = CmState::new(Vector3::new(1.0, 0.0, 0.0), Vector3::zeros(), Vector3::zeros());
/// let out = resolve_slice(&setup, &[BatchInput::cm(head_on)]);
/// let o = out[0].as_ref().unwrap();
/// assert_eq!(o.result.out.u_cm.x, -1.0); // eq 24, P = 2 m U(0)
/// // S(0) = 0: the surfaces never slide (docs/model.md#no-initial-sliding: sticks at
/// // t = 0, theta undefined).
/// assert!(o.result.sticks && o.result.theta.is_none() && o.stick_time == Some(0.0));
/// ```
pub fn resolve_slice(setup: &BatchSetup, inputs: &[BatchInput]) -> Vec<Result<BatchOutput, Error>> {
    let kernel = shared_kernel(setup);
    inputs
        .par_iter()
        .map(|i| resolve_with(setup, kernel.as_ref(), i))
        .collect()
}

/// Closed form of centre-of-mass states sharing the setup's balls and contact, one core, into
/// `out` (same length as `states`): the fast path the 50 ns target is measured on (the
/// outgoing state, impulse, S(0), theta, stick flag and p_stick; `benches/closed_form.rs`).
pub fn closed_form_into(
    setup: &BatchSetup,
    states: &[CmState],
    out: &mut [ContactResult],
) -> Result<(), Error> {
    if states.len() != out.len() {
        return Err(Error::invalid(
            "out",
            format!("{} results for {} states", out.len(), states.len()),
            "one result per state",
        ));
    }
    let kernel = ClosedFormBatch::new(setup.balls, setup.contact, setup.effects);
    for (s, o) in states.iter().zip(out.iter_mut()) {
        *o = kernel.resolve(s)?;
    }
    Ok(())
}

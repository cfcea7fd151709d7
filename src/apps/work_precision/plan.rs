//! The study's plan: the forces it compares (profiles and contact laws), the settings of
//! each method, the scenes, and the jobs (one scene, force and setting each).

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{SolverSettings, Stats};
use crate::model::contact_law::{ContactLaw, Damping};
use crate::model::material::{elastic_impact, hertz_stiffness, Material};
use crate::model::params::ImpulseRule;
use crate::profile::force::ForceProfile;
use crate::profile::half_sine::HalfSine;
use crate::profile::hertz::Hertz;
use crate::profile::rectangle::Rectangle;
use crate::profile::sine_power::SinePower;
use crate::profile::spec::{Profile, ProfileKind};
use crate::profile::tabulated::{parse_table, Tabulated};
use crate::scene::overrides::SolverOverrides;
use crate::scene::types::Scene;
use crate::solve::law_outcome::solve_law;
use crate::solve::outcome::{solve, Outcome};
use std::fmt;
use std::path::Path;
use std::time::Duration;

/// The built-in companion scene in which sliding stops during contact.
pub(crate) const STICKING_SCENE: &str = include_str!("../../../data/scenes/stun_cut_sticks.toml");

/// The (time, force) points the `tabulated` profile uses unless the scene has its own
/// (`data/profiles/measured_pulse.csv`, stretched to the scene's duration).
pub(crate) const MEASURED_PULSE: &str = include_str!("../../../data/profiles/measured_pulse.csv");

/// The profile of kind `kind` run by the study of `scene`: with the duration of the scene's
/// profile; the scene's own profile when it is of this kind (its points, its exponent 1.5);
/// `tabulated` without the scene's points uses [`MEASURED_PULSE`], `sine-power` exponent 1.5.
pub(crate) fn study_profile(kind: ProfileKind, scene: &Scene) -> Result<Profile, Error> {
    let own = &scene.profile;
    if own.kind() == kind {
        if let Profile::SinePower(p) = own {
            if p.exponent() == crate::profile::spec::DEFAULT_SINE_POWER_EXPONENT {
                return Ok(own.clone());
            }
        } else {
            return Ok(own.clone());
        }
    }
    let tau = own.duration();
    Ok(match kind {
        ProfileKind::HalfSine => Profile::HalfSine(HalfSine::new(tau)?),
        ProfileKind::Hertz => Profile::Hertz(Hertz::new(tau)?),
        ProfileKind::SinePower => Profile::SinePower(SinePower::new(
            tau,
            crate::profile::spec::DEFAULT_SINE_POWER_EXPONENT,
        )?),
        ProfileKind::Rectangle => Profile::Rectangle(Rectangle::new(tau)?),
        ProfileKind::Tabulated => {
            let source = Path::new("data/profiles/measured_pulse.csv");
            let points = parse_table(MEASURED_PULSE, source)?;
            Profile::Tabulated(Tabulated::new(&points, Some(tau), source)?)
        }
    })
}

/// What a line of the study applies as the normal force: a prescribed profile, or a contact
/// law (docs/contact-law.md), which decides the impulse and the contact time itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StudyForce {
    /// A force profile with the scene's impulse and duration.
    Profile(ProfileKind),
    /// A contact law of this damping (calibrated to e = 0.95 at 1 m/s on the scene's balls, pool-ball material).
    Law(Damping),
}

impl StudyForce {
    /// Every choice, in the order of the figure's panels: the profiles, then the laws.
    pub const ALL: [StudyForce; 8] = [
        StudyForce::Profile(ProfileKind::HalfSine),
        StudyForce::Profile(ProfileKind::Hertz),
        StudyForce::Profile(ProfileKind::SinePower),
        StudyForce::Profile(ProfileKind::Rectangle),
        StudyForce::Profile(ProfileKind::Tabulated),
        StudyForce::Law(Damping::None),
        StudyForce::Law(Damping::HuntCrossley),
        StudyForce::Law(Damping::KuwabaraKono),
    ];

    /// The default study of a scene with a profile: the five profiles.
    pub const PROFILES: [StudyForce; 5] = [
        StudyForce::Profile(ProfileKind::HalfSine),
        StudyForce::Profile(ProfileKind::Hertz),
        StudyForce::Profile(ProfileKind::SinePower),
        StudyForce::Profile(ProfileKind::Rectangle),
        StudyForce::Profile(ProfileKind::Tabulated),
    ];

    /// The name in `--profiles` and in the CSV's `profile` column: the profile's, `hertz-law`
    /// for the elastic law (the exact `hertz` profile's twin), the damping's for a damped law.
    pub fn name(&self) -> &'static str {
        match self {
            StudyForce::Profile(kind) => kind.name(),
            StudyForce::Law(Damping::None) => "hertz-law",
            StudyForce::Law(d) => d.name(),
        }
    }

    /// The default choices for `scene`: its own law when it has one (the profiles'
    /// comparison is asked for by name), else the five profiles.
    pub fn defaults_for(scene: &Scene) -> Vec<StudyForce> {
        match &scene.law {
            Some(law) => vec![StudyForce::Law(law.damping())],
            None => StudyForce::PROFILES.to_vec(),
        }
    }
}

impl fmt::Display for StudyForce {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The balls' material a law takes its stiffness from when the scene gives none: phenolic
/// resin pool balls, E = 5.4 GPa, nu = 0.34.
pub(crate) const POOL_BALL_MATERIAL: (f64, f64) = (5.4e9, 0.34);

/// The restitution a damped law of the study is calibrated to, at [`STUDY_AT_SPEED`], unless
/// the scene has a law of that damping.
pub(crate) const STUDY_RESTITUTION: f64 = 0.95;

/// The relative approach speed (m/s) of the calibration of [`STUDY_RESTITUTION`].
pub(crate) const STUDY_AT_SPEED: f64 = 1.0;

/// The law of `damping` run by the study of `scene`: the scene's own law when it is of this
/// damping; otherwise Hertz's stiffness of the scene's law, or of the balls' material, or of
/// pool balls ([`POOL_BALL_MATERIAL`]) of the scene's sizes, and the coefficient calibrated
/// to e = [`STUDY_RESTITUTION`] at [`STUDY_AT_SPEED`] (none for the elastic law).
pub(crate) fn study_law(damping: Damping, scene: &Scene) -> Result<ContactLaw, Error> {
    if let Some(law) = scene.law.filter(|l| l.damping() == damping) {
        return Ok(law);
    }
    let balls = &scene.balls;
    let stiffness = match (&scene.law, &scene.material) {
        (Some(law), _) => law.stiffness(),
        (None, Some(m)) => hertz_stiffness((&balls.a, m), (&balls.b, m)).2,
        (None, None) => {
            let (e, nu) = POOL_BALL_MATERIAL;
            let m = Material::new(e, nu)?;
            hertz_stiffness((&balls.a, &m), (&balls.b, &m)).2
        }
    };
    match damping {
        Damping::None => ContactLaw::elastic(stiffness),
        d => ContactLaw::calibrated(
            stiffness,
            d,
            STUDY_RESTITUTION,
            STUDY_AT_SPEED,
            0.5 * balls.pair_mass(),
        ),
    }
}

/// rtol = atol of the dop853 integration of the normal law that gives a damped law's
/// reference impulse ([`LawReference`]): the smallest the settings take. Measured on the
/// default scene and the sticking companion: the outgoing state at rtol 1e-12, 1e-13 and
/// 1e-14 lies 9.4e-12, 9.8e-13 and 1.0e-13 (scaled, Kuwabara-Kono the largest) from the
/// state at this rtol, tenfold per decade, so the reference is within about 1e-14 of the
/// converged state; on the elastic law, this integration lands within 2.5e-15 of the
/// exact `hertz` outcome.
pub(crate) const REFERENCE_RTOL: f64 = 1e-15;

/// What a law's runs are measured against in one scene.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LawReference {
    /// The law.
    pub law: ContactLaw,
    /// The reference outcome: for the elastic law the exact `hertz` profile's closed form
    /// (P = 2 m U(0), the elastic contact time); for a damped law the closed form at the
    /// impulse of the normal law integrated with dop853 at [`REFERENCE_RTOL`], its stick
    /// time where that integration's impulse reaches p_stick.
    pub outcome: Outcome,
    /// The reference contact time (s).
    pub duration: f64,
}

impl LawReference {
    /// The reference of `law` in `scene` (see the fields).
    pub(crate) fn new(law: ContactLaw, scene: &Scene) -> Result<Self, Error> {
        // The elastic impulse rule: the law decides the impulse, and the elastic law's
        // reference is P = 2 m U(0).
        let mut elastic = scene.clone();
        elastic.contact.impulse = ImpulseRule::ELASTIC;
        let (c, _) = elastic.collision()?;
        if law.damping() == Damping::None {
            let v = 2.0 * c.incoming.u_cm.x;
            let (_, tau) = elastic_impact(law.stiffness(), 0.5 * c.balls.pair_mass(), v);
            let closed = SolverSettings::default().with_method(Method::ClosedForm);
            let outcome = solve(&c, &Hertz::new(tau)?, &closed, None)?;
            return Ok(LawReference {
                law,
                outcome,
                duration: tau,
            });
        }
        let settings = SolverSettings::new(
            Method::ClosedForm,
            REFERENCE_RTOL,
            REFERENCE_RTOL,
            crate::base::settings::DEFAULT_STEPS,
        )?;
        let outcome = solve_law(&c, &law, &settings, None)?;
        let duration = outcome.law.map_or(f64::NAN, |l| l.duration);
        Ok(LawReference {
            law,
            outcome,
            duration,
        })
    }

    /// |t_stick - t_stick of the reference| / the reference's contact time, when the
    /// reference sticks; a stop the run missed counts as a stop at the end of the contact.
    pub(crate) fn stick_time_error(&self, outcome: &Outcome) -> Option<f64> {
        let exact = self.outcome.stick_time?;
        let run = outcome.stick_time.unwrap_or(self.duration);
        Some((run - exact).abs() / self.duration)
    }

    /// The scene with the law's realised impulse and contact time in place of its own: the
    /// profiles of a law scene are run at them.
    fn realised_in(&self, scene: &Scene) -> Result<Scene, Error> {
        let mut s = scene.clone();
        s.contact.impulse = ImpulseRule::explicit(self.outcome.result.impulse)?;
        s.profile = Profile::Hertz(Hertz::new(self.duration)?);
        Ok(s)
    }
}

/// What the study runs.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Profiles and contact laws (panels).
    pub profiles: Vec<StudyForce>,
    /// Relative tolerances of dopri5 and dop853 (atol = rtol).
    pub rtols: Vec<f64>,
    /// Step counts of rk4 over the contact.
    pub rk4_steps: Vec<u32>,
    /// Timed samples per setting (the median is reported), at least 1.
    pub repeats: usize,
    /// Wall time per sample: a sample repeats the solve until it lasts this long, so that
    /// fast solves are timed above the clock's resolution.
    pub sample_time: Duration,
    /// Wall-time budget of one setting: after it, no further samples are taken (at least
    /// three are, when `repeats` >= 3).
    pub setting_budget: Duration,
    /// Run the companion scene that sticks (`data/scenes/stun_cut_sticks.toml`) as well.
    pub sticking_scene: bool,
}

impl Default for StudyOptions {
    /// The five profiles ([`StudyForce::PROFILES`], no law); rtol = 1e-3, 1e-4, ..., 1e-13; rk4 with 4, 8, ..., 8192 steps;
    /// 9 samples of at least 1 ms each; 0.25 s per setting; the sticking
    /// companion scene on.
    fn default() -> Self {
        StudyOptions {
            profiles: StudyForce::PROFILES.to_vec(),
            rtols: (3..=13).map(|k| 10f64.powi(-k)).collect(),
            rk4_steps: (2..=13).map(|k| 1u32 << k).collect(),
            repeats: 9,
            sample_time: Duration::from_millis(1),
            setting_budget: Duration::from_millis(250),
            sticking_scene: true,
        }
    }
}

/// One setting to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Setting {
    /// Method.
    pub method: Method,
    /// rtol (= atol) of the adaptive methods.
    pub rtol: Option<f64>,
    /// rk4 steps over the contact.
    pub steps: Option<u32>,
    /// Step exactly to the profile's breakpoints.
    pub breakpoints: bool,
    /// The smoothing time transform of pulses with algebraic ends.
    pub time_transform: bool,
}

impl Setting {
    /// The solver settings of this setting: the defaults with its method, rtol (= atol)
    /// and steps.
    pub(crate) fn solver(&self) -> Result<SolverSettings, Error> {
        let overrides = SolverOverrides {
            method: Some(self.method),
            rtol: self.rtol,
            atol: None,
            steps: self.steps,
            time_transform: Some(self.time_transform),
        };
        let s = overrides.apply(&SolverSettings::default())?;
        Ok(s.with_breakpoints(self.breakpoints))
    }
}

/// One row of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyRow {
    /// Profile name.
    pub profile: String,
    /// Method name (`closed-form`, `rk4`, `dopri5`, `dop853`, or a peer's, e.g.
    /// `scipy-DOP853`).
    pub method: String,
    /// rtol (= atol) of adaptive methods.
    pub rtol: Option<f64>,
    /// rk4 steps over the contact.
    pub steps: Option<u32>,
    /// Largest scaled deviation of the outgoing state from the closed form (for a law, from
    /// its dop853 reference at rtol 1e-15); `None` when the run failed.
    pub error: Option<f64>,
    /// |t_stick - exact| / duration where sliding stops (for a law, against its
    /// reference); `None` when it does not.
    pub stick_time_error: Option<f64>,
    /// Work done.
    pub stats: Stats,
    /// Median wall time of one solve (s).
    pub seconds_per_contact: f64,
    /// Whether the integrator stepped to the profile's breakpoints.
    pub breakpoints: bool,
    /// Whether the time transform was on (it acts on pulses with algebraic ends only).
    pub time_transform: bool,
    /// Scene name.
    pub scene: String,
    /// Timed samples.
    pub samples: u32,
    /// Solves per timed sample.
    pub solves_per_sample: u32,
    /// Why the run failed (empty when it did not).
    pub note: String,
    /// The restitution the run's law realised (`None` for a profile).
    pub restitution: Option<f64>,
    /// The law's damping coefficient, given or calibrated: beta (s/m), gamma (s), 0 for
    /// the elastic law (`None` for a profile).
    pub coefficient: Option<f64>,
}

/// The variants (breakpoints, time transform) a profile is run with: the defaults; and
/// with the time transform off for algebraic ends (graded breakpoints instead), or with
/// the breakpoints off for a profile that has some.
pub(crate) fn variants(profile: &dyn ForceProfile) -> Vec<(bool, bool)> {
    let mut v = vec![(true, true)];
    if profile.end_power().is_some() {
        v.push((true, false));
    } else if !profile.breakpoints().is_empty() {
        v.push((false, true));
    }
    v
}

/// The settings run for one profile: the closed form, the rk4 ladder, the tolerance
/// ladders, for each of its [`variants`].
pub(crate) fn settings_for(profile: &dyn ForceProfile, options: &StudyOptions) -> Vec<Setting> {
    ladder(&variants(profile), options)
}

/// The closed form, then the rk4 ladder and the tolerance ladders for each of `variants`
/// (breakpoints, time transform).
fn ladder(variants: &[(bool, bool)], options: &StudyOptions) -> Vec<Setting> {
    let mut v = vec![Setting {
        method: Method::ClosedForm,
        rtol: None,
        steps: None,
        breakpoints: true,
        time_transform: true,
    }];
    for &(breakpoints, time_transform) in variants {
        for &n in &options.rk4_steps {
            v.push(Setting {
                method: Method::Rk4,
                rtol: None,
                steps: Some(n),
                breakpoints,
                time_transform,
            });
        }
        for method in [Method::Dopri5, Method::Dop853] {
            for &r in &options.rtols {
                v.push(Setting {
                    method,
                    rtol: Some(r),
                    steps: None,
                    breakpoints,
                    time_transform,
                });
            }
        }
    }
    v
}

/// The scenes of the study: `main`, and the sticking companion when asked for. A scene
/// with a contact law gets the law's realised impulse and contact time ([`LawReference`])
/// in place of its elastic time unit: the profiles run at them, the laws decide their own.
pub(crate) fn scenes(main: Scene, options: &StudyOptions) -> Result<Vec<Scene>, Error> {
    let mut v = vec![main];
    if options.sticking_scene {
        let s = Scene::parse(STICKING_SCENE, Path::new("data/scenes"), None)
            .expect("the embedded sticking scene is valid");
        v.push(s);
    }
    v.into_iter()
        .map(|s| match s.law {
            Some(law) => LawReference::new(law, &s)?.realised_in(&s),
            None => Ok(s),
        })
        .collect()
}

/// One unit of work: a scene, a profile or a law, a setting.
#[derive(Debug, Clone)]
pub(crate) struct Job {
    /// Index into the scenes.
    pub scene: usize,
    /// The profile; for a law, the `hertz` pulse of its reference contact time.
    pub profile: Profile,
    /// The law and its reference, when the force comes from a law.
    pub law: Option<LawReference>,
    /// The setting.
    pub setting: Setting,
}

impl Job {
    /// The `profile` column: the profile's name, or the law's ([`StudyForce::name`]).
    pub(crate) fn name(&self) -> &'static str {
        match &self.law {
            Some(r) => StudyForce::Law(r.law.damping()).name(),
            None => self.profile.name(),
        }
    }
}

/// Every job of the study, in the order of the CSV. A law runs with its defaults only
/// (it steps in the scaled time, has no breakpoints and takes no time transform:
/// docs/contact-law.md#time-stepping).
pub(crate) fn plan(scenes: &[Scene], options: &StudyOptions) -> Result<Vec<Job>, Error> {
    let mut jobs = Vec::new();
    for (i, scene) in scenes.iter().enumerate() {
        for force in &options.profiles {
            let (profile, law, settings) = match *force {
                StudyForce::Profile(kind) => {
                    let profile = study_profile(kind, scene)?;
                    let settings = settings_for(&profile, options);
                    (profile, None, settings)
                }
                StudyForce::Law(damping) => {
                    let reference = LawReference::new(study_law(damping, scene)?, scene)?;
                    let profile = Profile::Hertz(Hertz::new(reference.duration)?);
                    (profile, Some(reference), ladder(&[(true, true)], options))
                }
            };
            for setting in settings {
                jobs.push(Job {
                    scene: i,
                    profile: profile.clone(),
                    law: law.clone(),
                    setting,
                });
            }
        }
    }
    Ok(jobs)
}

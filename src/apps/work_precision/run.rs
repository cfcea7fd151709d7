//! Running the study: one job's error against the closed form and its timed solves.

use crate::apps::work_precision::plan::{plan, scenes, Job, StudyOptions, StudyRow};
use crate::base::error::Error;
use crate::base::settings::Stats;
use crate::model::collision::Collision;
use crate::profile::force::ForceProfile;
use crate::scene::types::Scene;
use crate::solve::check::state_error;
use crate::solve::law_outcome::solve_law;
use crate::solve::outcome::{solve, Outcome};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Runs one job: one solve for the error, then the timed samples.
pub(crate) fn run_job(scene: &Scene, job: &Job, options: &StudyOptions) -> Result<StudyRow, Error> {
    let (collision, _) = scene.collision()?;
    let settings = job.setting.solver()?;
    let profile = &job.profile;
    let solve_once = |c: &Collision| match &job.law {
        Some(r) => solve_law(c, &r.law, &settings, None),
        None => solve(c, profile, &settings, None),
    };
    let mut row = StudyRow {
        profile: job.name().to_string(),
        method: job.setting.method.name().to_string(),
        rtol: job.setting.rtol,
        steps: job.setting.steps,
        error: None,
        stick_time_error: None,
        stats: Stats::default(),
        seconds_per_contact: f64::NAN,
        breakpoints: job.setting.breakpoints,
        time_transform: job.setting.time_transform,
        scene: scene.name.clone(),
        samples: 0,
        solves_per_sample: 0,
        note: String::new(),
        restitution: None,
        coefficient: None,
    };
    // Warm-up, and the accuracy of the run.
    let outcome = match solve_once(&collision) {
        Ok(o) => o,
        Err(e) => {
            row.note = e.to_string();
            return Ok(row);
        }
    };
    match &job.law {
        Some(r) => {
            row.error = Some(state_error(
                &collision,
                &outcome.result.out,
                &r.outcome.result.out,
            ));
            row.stick_time_error = r.stick_time_error(&outcome);
            row.restitution = outcome.law.map(|l| l.restitution);
            row.coefficient = Some(r.law.coefficient());
        }
        None => {
            row.error = Some(outcome.check.closed_form_error);
            row.stick_time_error = stick_time_error(&outcome, profile);
        }
    }
    row.stats = outcome.stats;
    let timing = time_solves(
        || black_box(solve_once(black_box(&collision))).map(|_| ()),
        options,
    )?;
    row.seconds_per_contact = timing.seconds;
    row.samples = timing.samples;
    row.solves_per_sample = timing.solves_per_sample;
    Ok(row)
}

/// |t_stick - exact| / duration, when the exact solution sticks. A stop the run missed
/// counts as a stop at the end of the contact.
pub(crate) fn stick_time_error<P: ForceProfile + ?Sized>(
    outcome: &Outcome,
    profile: &P,
) -> Option<f64> {
    let s_exact = outcome.exact.result.stick_fraction(profile)?;
    let s_run = outcome
        .stick_time
        .map(|t| t / profile.duration())
        .unwrap_or(1.0);
    Some((s_run - s_exact).abs())
}

/// The result of [`time_solves`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Timing {
    /// Median seconds per call.
    pub seconds: f64,
    /// Timed samples taken.
    pub samples: u32,
    /// Calls per sample.
    pub solves_per_sample: u32,
}

/// Times `f`: calls per sample chosen so a sample lasts at least `options.sample_time`,
/// up to `options.repeats` samples within `options.setting_budget` (at least
/// min(3, repeats)); the median per call.
pub(crate) fn time_solves(
    mut f: impl FnMut() -> Result<(), Error>,
    options: &StudyOptions,
) -> Result<Timing, Error> {
    let start = Instant::now();
    f()?; // warm-up (caches, branch predictors)
    let once = start.elapsed().max(Duration::from_nanos(1));
    let per_sample = (options.sample_time.as_secs_f64() / once.as_secs_f64())
        .ceil()
        .clamp(1.0, 1e6) as u32;
    let repeats = options.repeats.max(1);
    let minimum = repeats.min(3);
    // Grown as samples are taken: the budget, not `repeats`, bounds them in practice.
    let mut times = Vec::with_capacity(repeats.min(64));
    while times.len() < repeats {
        let t0 = Instant::now();
        for _ in 0..per_sample {
            f()?;
        }
        times.push(t0.elapsed().as_secs_f64() / f64::from(per_sample));
        if times.len() >= minimum && start.elapsed() >= options.setting_budget {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let median = if n % 2 == 1 {
        times[n / 2]
    } else {
        0.5 * (times[n / 2 - 1] + times[n / 2])
    };
    Ok(Timing {
        seconds: median,
        samples: n as u32,
        solves_per_sample: per_sample,
    })
}

/// Runs the whole study, calling `progress(done, total, row)` after each job.
pub fn run_study(
    main: Scene,
    options: &StudyOptions,
    mut progress: impl FnMut(usize, usize, &StudyRow),
) -> Result<Vec<StudyRow>, Error> {
    if options.profiles.is_empty() {
        return Err(Error::invalid("--profiles", "none", "at least one profile"));
    }
    let scenes = scenes(main, options)?;
    let jobs = plan(&scenes, options)?;
    let total = jobs.len();
    let mut rows = Vec::with_capacity(total);
    for (i, job) in jobs.iter().enumerate() {
        let row = run_job(&scenes[job.scene], job, options)?;
        progress(i + 1, total, &row);
        rows.push(row);
    }
    Ok(rows)
}

//! The work-precision study: what accuracy costs in time, per force profile and method.
//!
//! For each profile (the scene's collision with its profile replaced, the duration kept) and
//! each method (the closed form; rk4 over a ladder of step counts; dopri5 and dop853 over a
//! ladder of tolerances with atol = rtol on the scaled variables), one run measures
//!
//! - `error`: the largest scaled deviation of the outgoing state from the closed form
//!   ([`crate::contact::check::Checks::closed_form_error`], with the scales of
//!   docs/model.md#scales-and-scaled-errors);
//! - `stick_time_error`: |t_stick - t_stick exact| / duration where sliding stops (`None`
//!   otherwise; a stop the integrator missed counts as a stop at the end of the contact);
//! - the work done ([`Stats`]);
//! - `seconds_per_contact`: the median, over timed samples after a warm-up, of the wall time
//!   of one [`solve`] (the whole call: closed form, integration and checks), in this process.
//!
//! Profiles with breakpoints (the knots of a tabulated profile) are run again with
//! [`SolverSettings::breakpoints`] off, so the study shows what stepping exactly to them
//! saves. By default the study also runs a companion scene in which sliding stops during
//! the contact (`data/scenes/stun_cut_sticks.toml`), which exercises the stick event.
//!
//! [`write_csv`] writes the rows with the columns of [`COLUMNS`] first (the format of
//! docs/formats.md#work-precision-csv) and [`EXTRA_COLUMNS`] after; [`read_csv`] reads such a file back, including rows
//! appended by the peers' script (`benches/peers/scipy_contact.py`), for the figure.

use crate::contact::outcome::{solve, Outcome};
use crate::error::Error;
use crate::formats::number::shortest;
use crate::formats::scene::{Scene, SolverOverrides};
use crate::integrator::{Method, SolverSettings, Stats};
use crate::profile::{
    parse_table, ForceProfile, HalfSine, Hertz, Profile, Rectangle, SinePower, Tabulated,
};
use std::hint::black_box;
use std::io::{Read, Write};
use std::path::Path;
use std::time::{Duration, Instant};

/// The columns every study CSV starts with, in this order (docs/formats.md#work-precision-csv).
pub const COLUMNS: [&str; 9] = [
    "profile",
    "method",
    "rtol",
    "steps",
    "error",
    "stick_time_error",
    "rhs_evaluations",
    "accepted_steps",
    "seconds_per_contact",
];

/// Columns after [`COLUMNS`]: whether the integrator stepped to the profile's breakpoints,
/// the scene, rejected steps, timed samples and solves per sample, and a note (why a run
/// failed).
pub const EXTRA_COLUMNS: [&str; 6] = [
    "breakpoints",
    "scene",
    "rejected_steps",
    "samples",
    "solves_per_sample",
    "note",
];

/// The built-in companion scene in which sliding stops during contact.
pub const STICKING_SCENE: &str = include_str!("../../data/scenes/stun_cut_sticks.toml");

/// The (time, force) points the `tabulated` profile uses unless the scene has its own
/// (`data/profiles/measured_pulse.csv`, stretched to the scene's duration).
pub const MEASURED_PULSE: &str = include_str!("../../data/profiles/measured_pulse.csv");

/// The profiles of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileKind {
    /// `half-sine`.
    HalfSine,
    /// `hertz`.
    Hertz,
    /// `sine-power` with exponent 1.5.
    SinePower,
    /// `rectangle`.
    Rectangle,
    /// `tabulated` (the scene's points, or [`MEASURED_PULSE`]).
    Tabulated,
}

impl ProfileKind {
    /// All profiles, in the order of the figure's panels.
    pub const ALL: [ProfileKind; 5] = [
        ProfileKind::HalfSine,
        ProfileKind::Hertz,
        ProfileKind::SinePower,
        ProfileKind::Rectangle,
        ProfileKind::Tabulated,
    ];

    /// The name in scene files and in the CSV.
    pub fn name(&self) -> &'static str {
        match self {
            ProfileKind::HalfSine => "half-sine",
            ProfileKind::Hertz => "hertz",
            ProfileKind::SinePower => "sine-power",
            ProfileKind::Rectangle => "rectangle",
            ProfileKind::Tabulated => "tabulated",
        }
    }

    /// The profile of this kind with the duration of `scene`'s profile; the scene's own
    /// profile when it is of this kind (its points, its exponent).
    pub fn build(&self, scene: &Scene) -> Result<Profile, Error> {
        let own = &scene.profile;
        if own.name() == self.name() {
            if let Profile::SinePower(p) = own {
                if p.exponent() == crate::profile::DEFAULT_SINE_POWER_EXPONENT {
                    return Ok(own.clone());
                }
            } else {
                return Ok(own.clone());
            }
        }
        let tau = own.duration();
        Ok(match self {
            ProfileKind::HalfSine => Profile::HalfSine(HalfSine::new(tau)),
            ProfileKind::Hertz => Profile::Hertz(Hertz::new(tau)),
            ProfileKind::SinePower => Profile::SinePower(SinePower::new(
                tau,
                crate::profile::DEFAULT_SINE_POWER_EXPONENT,
            )?),
            ProfileKind::Rectangle => Profile::Rectangle(Rectangle::new(tau)),
            ProfileKind::Tabulated => {
                let source = Path::new("data/profiles/measured_pulse.csv");
                let points = parse_table(MEASURED_PULSE, source)?;
                Profile::Tabulated(Tabulated::new(&points, Some(tau), source)?)
            }
        })
    }
}

/// What the study runs.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Profiles (panels).
    pub profiles: Vec<ProfileKind>,
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
    /// Run the companion scene that sticks ([`STICKING_SCENE`]) as well.
    pub sticking_scene: bool,
}

impl Default for StudyOptions {
    /// All five profiles; rtol = 1e-3, 1e-4, ..., 1e-13; rk4 with 4, 8, ..., 8192 steps;
    /// 9 samples of at least 1 ms each; 0.25 s per setting; the sticking
    /// companion scene on.
    fn default() -> Self {
        StudyOptions {
            profiles: ProfileKind::ALL.to_vec(),
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
pub struct Setting {
    /// Method.
    pub method: Method,
    /// rtol (= atol) of the adaptive methods.
    pub rtol: Option<f64>,
    /// rk4 steps over the contact.
    pub steps: Option<u32>,
    /// Step exactly to the profile's breakpoints.
    pub breakpoints: bool,
}

impl Setting {
    /// The solver settings of this setting: the defaults with its method, rtol (= atol)
    /// and steps.
    pub fn solver(&self) -> Result<SolverSettings, Error> {
        let overrides = SolverOverrides {
            method: Some(self.method),
            rtol: self.rtol,
            atol: None,
            steps: self.steps,
        };
        let mut s = overrides.apply(&SolverSettings::default())?;
        s.breakpoints = self.breakpoints;
        Ok(s)
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
    /// Largest scaled deviation of the outgoing state from the closed form; `None` when the
    /// run failed.
    pub error: Option<f64>,
    /// |t_stick - exact| / duration where sliding stops; `None` when it does not.
    pub stick_time_error: Option<f64>,
    /// Work done.
    pub stats: Stats,
    /// Median wall time of one solve (s).
    pub seconds_per_contact: f64,
    /// Whether the integrator stepped to the profile's breakpoints.
    pub breakpoints: bool,
    /// Scene name.
    pub scene: String,
    /// Timed samples.
    pub samples: u32,
    /// Solves per timed sample.
    pub solves_per_sample: u32,
    /// Why the run failed (empty when it did not).
    pub note: String,
}

/// The settings run for one profile: the closed form, the rk4 ladder, the tolerance
/// ladders, and the same without breakpoints when the profile has some.
pub fn settings_for(profile: &dyn ForceProfile, options: &StudyOptions) -> Vec<Setting> {
    let mut v = vec![Setting {
        method: Method::ClosedForm,
        rtol: None,
        steps: None,
        breakpoints: true,
    }];
    let has_breakpoints = !profile.breakpoints().is_empty();
    for breakpoints in [true, false] {
        if !breakpoints && !has_breakpoints {
            break;
        }
        for &n in &options.rk4_steps {
            v.push(Setting {
                method: Method::Rk4,
                rtol: None,
                steps: Some(n),
                breakpoints,
            });
        }
        for method in [Method::Dopri5, Method::Dop853] {
            for &r in &options.rtols {
                v.push(Setting {
                    method,
                    rtol: Some(r),
                    steps: None,
                    breakpoints,
                });
            }
        }
    }
    v
}

/// The scenes of the study: `main`, and the sticking companion when asked for.
pub fn scenes(main: Scene, options: &StudyOptions) -> Vec<Scene> {
    let mut v = vec![main];
    if options.sticking_scene {
        let s = Scene::parse(STICKING_SCENE, Path::new("data/scenes"), None)
            .expect("the embedded sticking scene is valid");
        v.push(s);
    }
    v
}

/// One unit of work: a scene, a profile, a setting.
#[derive(Debug, Clone)]
pub struct Job {
    /// Index into the scenes.
    pub scene: usize,
    /// The profile.
    pub profile: Profile,
    /// The setting.
    pub setting: Setting,
}

/// Every job of the study, in the order of the CSV.
pub fn plan(scenes: &[Scene], options: &StudyOptions) -> Result<Vec<Job>, Error> {
    let mut jobs = Vec::new();
    for (i, scene) in scenes.iter().enumerate() {
        for kind in &options.profiles {
            let profile = kind.build(scene)?;
            for setting in settings_for(&profile, options) {
                jobs.push(Job {
                    scene: i,
                    profile: profile.clone(),
                    setting,
                });
            }
        }
    }
    Ok(jobs)
}

/// Runs one job: one solve for the error, then the timed samples.
pub fn run_job(scene: &Scene, job: &Job, options: &StudyOptions) -> Result<StudyRow, Error> {
    let (collision, _) = scene.collision()?;
    let settings = job.setting.solver()?;
    let profile = &job.profile;
    let mut row = StudyRow {
        profile: profile.name().to_string(),
        method: job.setting.method.name().to_string(),
        rtol: job.setting.rtol,
        steps: job.setting.steps,
        error: None,
        stick_time_error: None,
        stats: Stats::default(),
        seconds_per_contact: f64::NAN,
        breakpoints: job.setting.breakpoints,
        scene: scene.name.clone(),
        samples: 0,
        solves_per_sample: 0,
        note: String::new(),
    };
    // Warm-up, and the accuracy of the run.
    let outcome = match solve(&collision, profile, &settings, None) {
        Ok(o) => o,
        Err(e) => {
            row.note = e.to_string();
            return Ok(row);
        }
    };
    row.error = Some(outcome.check.closed_form_error);
    row.stick_time_error = stick_time_error(&outcome, profile);
    row.stats = outcome.stats;
    let timing = time_solves(
        || {
            black_box(solve(
                black_box(&collision),
                black_box(profile),
                &settings,
                None,
            ))
            .map(|_| ())
        },
        options,
    )?;
    row.seconds_per_contact = timing.seconds;
    row.samples = timing.samples;
    row.solves_per_sample = timing.solves_per_sample;
    Ok(row)
}

/// |t_stick - exact| / duration, when the exact solution sticks. A stop the run missed
/// counts as a stop at the end of the contact.
pub fn stick_time_error<P: ForceProfile + ?Sized>(outcome: &Outcome, profile: &P) -> Option<f64> {
    let s_exact = outcome.exact.result.stick_fraction(profile)?;
    let s_run = outcome
        .stick_time
        .map(|t| t / profile.duration())
        .unwrap_or(1.0);
    Some((s_run - s_exact).abs())
}

/// The result of [`time_solves`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
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
pub fn time_solves(
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
    let mut times = Vec::with_capacity(repeats);
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
    let scenes = scenes(main, options);
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

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

/// Writes the rows as CSV: [`COLUMNS`], then [`EXTRA_COLUMNS`]. Empty cells: `rtol` of
/// rk4 and the closed form, `steps` of the adaptive methods and the closed form,
/// `stick_time_error` when sliding does not stop, `error` when the run failed.
pub fn write_csv<W: Write>(out: W, rows: &[StudyRow]) -> Result<W, Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(COLUMNS.iter().chain(EXTRA_COLUMNS.iter()))?;
    for r in rows {
        for (name, v) in [
            ("error", r.error),
            ("stick_time_error", r.stick_time_error),
            ("seconds_per_contact", Some(r.seconds_per_contact)),
        ] {
            if let Some(x) = v {
                if !x.is_finite() && r.note.is_empty() {
                    return Err(Error::NonFinite {
                        field: format!("{name} of {} {} {:?}", r.profile, r.method, r.rtol),
                        value: x,
                    });
                }
            }
        }
        let seconds = if r.seconds_per_contact.is_finite() {
            shortest(r.seconds_per_contact)
        } else {
            String::new()
        };
        w.write_record([
            r.profile.clone(),
            r.method.clone(),
            opt(r.rtol.map(shortest)),
            opt(r.steps),
            opt(r.error.map(shortest)),
            opt(r.stick_time_error.map(shortest)),
            r.stats.rhs_evaluations.to_string(),
            r.stats.accepted_steps.to_string(),
            seconds,
            r.breakpoints.to_string(),
            r.scene.clone(),
            r.stats.rejected_steps.to_string(),
            r.samples.to_string(),
            r.solves_per_sample.to_string(),
            r.note.clone(),
        ])?;
    }
    w.into_inner()
        .map_err(|e| Error::io("work_precision.csv", e.into_error()))
}

/// Reads a study CSV (ours, possibly with rows appended by a peer's script). The columns of
/// [`COLUMNS`] are required (by name); of the extra columns, missing ones or empty cells
/// read as breakpoints = true, scene = "", zero counts, no note. Errors name the line.
pub fn read_csv<R: Read>(input: R, path: &Path) -> Result<Vec<StudyRow>, Error> {
    let err = |line: u64, message: String| Error::BatchInput {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut rd = csv::ReaderBuilder::new().flexible(true).from_reader(input);
    let header = rd.headers().map_err(|e| err(1, e.to_string()))?.clone();
    let index = |name: &str| header.iter().position(|h| h.trim() == name);
    let mut required = [0usize; 9];
    for (slot, name) in required.iter_mut().zip(COLUMNS) {
        *slot = index(name).ok_or_else(|| err(1, format!("missing column `{name}`")))?;
    }
    let extra: Vec<Option<usize>> = EXTRA_COLUMNS.iter().map(|n| index(n)).collect();
    let mut rows = Vec::new();
    for rec in rd.records() {
        let rec = rec.map_err(|e| {
            let line = e.position().map(|p| p.line()).unwrap_or(0);
            err(line, e.to_string())
        })?;
        let line = rec.position().map(|p| p.line()).unwrap_or(0);
        let cell = |i: usize| rec.get(i).unwrap_or("").trim();
        let ext = |k: usize| extra[k].map(&cell).unwrap_or("");
        let float = |i: usize, name: &str| -> Result<Option<f64>, Error> {
            let c = cell(i);
            if c.is_empty() {
                return Ok(None);
            }
            c.parse::<f64>()
                .map(Some)
                .map_err(|_| err(line, format!("{name} `{c}` is not a number")))
        };
        let int = |c: &str, name: &str| -> Result<u64, Error> {
            if c.is_empty() {
                return Ok(0);
            }
            c.parse::<u64>()
                .map_err(|_| err(line, format!("{name} `{c}` is not a whole number")))
        };
        let steps = match cell(required[3]) {
            "" => None,
            c => Some(
                c.parse::<u32>()
                    .map_err(|_| err(line, format!("steps `{c}` is not a whole number")))?,
            ),
        };
        rows.push(StudyRow {
            profile: cell(required[0]).to_string(),
            method: cell(required[1]).to_string(),
            rtol: float(required[2], "rtol")?,
            steps,
            error: float(required[4], "error")?,
            stick_time_error: float(required[5], "stick_time_error")?,
            stats: Stats {
                rhs_evaluations: int(cell(required[6]), "rhs_evaluations")?,
                accepted_steps: int(cell(required[7]), "accepted_steps")?,
                rejected_steps: int(ext(2), "rejected_steps")?,
            },
            seconds_per_contact: float(required[8], "seconds_per_contact")?.unwrap_or(f64::NAN),
            breakpoints: !matches!(ext(0), "false" | "False" | "0"),
            scene: ext(1).to_string(),
            samples: int(ext(3), "samples")? as u32,
            solves_per_sample: int(ext(4), "solves_per_sample")? as u32,
            note: ext(5).to_string(),
        });
    }
    Ok(rows)
}

/// A line of the figure: the rows of one scene, profile, method and breakpoint setting.
#[derive(Debug, Clone, PartialEq)]
pub struct Series<'a> {
    /// Scene name.
    pub scene: &'a str,
    /// Profile name.
    pub profile: &'a str,
    /// Method name.
    pub method: &'a str,
    /// Breakpoints on.
    pub breakpoints: bool,
    /// The rows, in the order of the ladder (cheapest first).
    pub rows: Vec<&'a StudyRow>,
}

impl Series<'_> {
    /// The label of the line: the method, with "no breakpoints" when they were off.
    pub fn label(&self) -> String {
        if self.breakpoints {
            self.method.to_string()
        } else {
            format!("{} (no breakpoints)", self.method)
        }
    }

    /// The observed order: minus the least-squares slope of log(error) against
    /// log(rhs evaluations), over runs with error in [1e-13, 1e-2] (below, round-off
    /// dominates; above, the asymptotic regime has not started). `None` with fewer than
    /// three such runs or without evaluation counts.
    pub fn observed_order(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self
            .rows
            .iter()
            .filter_map(|r| {
                let e = r.error?;
                let n = r.stats.rhs_evaluations;
                ((1e-13..=1e-2).contains(&e) && n > 0).then(|| ((n as f64).ln(), e.ln()))
            })
            .collect();
        if pts.len() < 3 {
            return None;
        }
        let n = pts.len() as f64;
        let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
        let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
        let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        (sxx > 0.0).then(|| -sxy / sxx)
    }

    /// The cheapest run (seconds per contact) with error <= `target`, if any.
    pub fn cheapest_within(&self, target: f64) -> Option<&StudyRow> {
        self.rows
            .iter()
            .copied()
            .filter(|r| r.error.is_some_and(|e| e <= target) && r.seconds_per_contact.is_finite())
            .min_by(|a, b| a.seconds_per_contact.total_cmp(&b.seconds_per_contact))
    }
}

/// Groups rows into lines, in order of first appearance; within a line the rows are
/// ordered from the loosest setting to the tightest (rk4 by steps, others by decreasing
/// rtol, then by evaluations).
pub fn series(rows: &[StudyRow]) -> Vec<Series<'_>> {
    let mut out: Vec<Series<'_>> = Vec::new();
    for r in rows {
        let found = out.iter_mut().find(|s| {
            s.scene == r.scene
                && s.profile == r.profile
                && s.method == r.method
                && s.breakpoints == r.breakpoints
        });
        match found {
            Some(s) => s.rows.push(r),
            None => out.push(Series {
                scene: &r.scene,
                profile: &r.profile,
                method: &r.method,
                breakpoints: r.breakpoints,
                rows: vec![r],
            }),
        }
    }
    for s in &mut out {
        s.rows.sort_by(|a, b| {
            let ka = (a.steps.unwrap_or(0), -a.rtol.unwrap_or(0.0));
            let kb = (b.steps.unwrap_or(0), -b.rtol.unwrap_or(0.0));
            ka.0.cmp(&kb.0)
                .then(ka.1.total_cmp(&kb.1))
                .then(a.stats.rhs_evaluations.cmp(&b.stats.rhs_evaluations))
        });
    }
    out
}

/// A plain-text summary: per scene and profile, each method's observed order and the
/// cheapest cost (time per contact, evaluations) of reaching errors 1e-6, 1e-9, 1e-12.
pub fn summary(rows: &[StudyRow]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let mut scene = "";
    for line in series(rows) {
        if line.scene != scene {
            scene = line.scene;
            let _ = writeln!(s, "\nscene: {scene}");
            let _ = writeln!(
                s,
                "{:<11} {:<28} {:>6}  {:>21}  {:>21}  {:>21}",
                "profile", "method", "order", "error<=1e-6", "error<=1e-9", "error<=1e-12"
            );
        }
        let order = line
            .observed_order()
            .map(|o| format!("{o:.1}"))
            .unwrap_or_else(|| "-".into());
        let _ = write!(s, "{:<11} {:<28} {:>6}", line.profile, line.label(), order);
        for target in [1e-6, 1e-9, 1e-12] {
            let cell = match line.cheapest_within(target) {
                Some(r) => format!(
                    "{} ({} f)",
                    human_seconds(r.seconds_per_contact),
                    r.stats.rhs_evaluations
                ),
                None => "not reached".into(),
            };
            let _ = write!(s, "  {cell:>21}");
        }
        s.push('\n');
    }
    s
}

/// Seconds in ns, us or ms.
pub fn human_seconds(t: f64) -> String {
    if t < 1e-6 {
        format!("{:.0} ns", t * 1e9)
    } else if t < 1e-3 {
        format!("{:.2} us", t * 1e6)
    } else {
        format!("{:.2} ms", t * 1e3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quick() -> StudyOptions {
        StudyOptions {
            profiles: vec![ProfileKind::HalfSine, ProfileKind::Tabulated],
            rtols: vec![1e-4, 1e-7, 1e-10],
            rk4_steps: vec![8, 16, 32, 64],
            repeats: 1,
            sample_time: Duration::from_nanos(1),
            setting_budget: Duration::ZERO,
            sticking_scene: true,
        }
    }

    /// The CSV starts with the contract's columns, in order, and reads back to the rows.
    #[test]
    fn csv_columns_and_round_trip() {
        let rows = run_study(Scene::default_scene(), &quick(), |_, _, _| {}).unwrap();
        let bytes = write_csv(Vec::new(), &rows).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        let header = text.lines().next().unwrap();
        assert!(header.starts_with(
            "profile,method,rtol,steps,error,stick_time_error,rhs_evaluations,accepted_steps,seconds_per_contact,"
        ), "{header}");
        let back = read_csv(&bytes[..], Path::new("t.csv")).unwrap();
        assert_eq!(back, rows);
        // Closed form: no rtol, no steps, error exactly 0, no work.
        let cf = rows.iter().find(|r| r.method == "closed-form").unwrap();
        assert_eq!((cf.rtol, cf.steps, cf.error), (None, None, Some(0.0)));
        assert_eq!(cf.stats.rhs_evaluations, 0);
        let line = text.lines().nth(1).unwrap();
        assert!(
            line.starts_with("half-sine,closed-form,,,0.0,,0,0,"),
            "{line}"
        );
    }

    /// Two scenes, two profiles; the tabulated profile's knots give rows without breakpoints, with more
    /// evaluations at the same rk4 step count (RK4 stepping across a kink is order 2).
    #[test]
    fn plan_and_breakpoint_rows() {
        let opts = quick();
        let rows = run_study(Scene::default_scene(), &opts, |_, _, _| {}).unwrap();
        let per_profile = 1 + opts.rk4_steps.len() + 2 * opts.rtols.len();
        let with_off = per_profile + opts.rk4_steps.len() + 2 * opts.rtols.len();
        assert_eq!(rows.len(), 2 * (per_profile + with_off));
        let scene_names: std::collections::BTreeSet<_> = rows.iter().map(|r| &r.scene).collect();
        assert_eq!(scene_names.len(), 2);
        let pick = |bp: bool, n: u32| {
            rows.iter()
                .find(|r| {
                    r.profile == "tabulated"
                        && r.method == "rk4"
                        && r.breakpoints == bp
                        && r.steps == Some(n)
                })
                .unwrap()
        };
        // rk4 with steps at the knots is 4th order on the smooth pieces (f is linear there,
        // so quadrature of f is exact: the error is round-off).
        assert!(
            pick(true, 64).error.unwrap() < 1e-13,
            "{:?}",
            pick(true, 64)
        );
        assert!(
            pick(false, 64).error.unwrap() > 1e-9,
            "{:?}",
            pick(false, 64)
        );
    }

    /// The sticking companion scene reports stick-time errors, the default scene none;
    /// dop853 at rtol 1e-10 is within 1e-9 of the closed form on the half-sine.
    #[test]
    fn stick_time_errors_and_accuracy() {
        let rows = run_study(Scene::default_scene(), &quick(), |_, _, _| {}).unwrap();
        let main = &Scene::default_scene().name;
        for r in &rows {
            let sticking = &r.scene != main;
            assert_eq!(r.stick_time_error.is_some(), sticking, "{r:?}");
            assert!(r.note.is_empty(), "{r:?}");
        }
        let d = rows
            .iter()
            .find(|r| r.profile == "half-sine" && r.method == "dop853" && r.rtol == Some(1e-10))
            .unwrap();
        assert!(d.error.unwrap() < 1e-9, "{d:?}");
        assert!(d.seconds_per_contact > 0.0);
    }

    #[test]
    fn observed_order_of_a_known_power_law() {
        // error = 3 N^-4: slope -4 exactly.
        let rows: Vec<StudyRow> = [16u64, 32, 64, 128]
            .iter()
            .map(|&n| StudyRow {
                profile: "p".into(),
                method: "m".into(),
                rtol: None,
                steps: Some(n as u32),
                error: Some(3.0 * (n as f64).powi(-4)),
                stick_time_error: None,
                stats: Stats {
                    rhs_evaluations: n,
                    accepted_steps: n / 4,
                    rejected_steps: 0,
                },
                seconds_per_contact: n as f64 * 1e-9,
                breakpoints: true,
                scene: "s".into(),
                samples: 1,
                solves_per_sample: 1,
                note: String::new(),
            })
            .collect();
        let s = series(&rows);
        assert_eq!(s.len(), 1);
        assert!((s[0].observed_order().unwrap() - 4.0).abs() < 1e-12);
        assert_eq!(s[0].cheapest_within(1e-6).unwrap().steps, Some(64));
    }

    #[test]
    fn read_csv_names_the_bad_line() {
        let good = "profile,method,rtol,steps,error,stick_time_error,rhs_evaluations,accepted_steps,seconds_per_contact\n\
                    half-sine,scipy-RK45,1e-6,,2e-7,,120,20,1e-4\n";
        let rows = read_csv(good.as_bytes(), Path::new("w.csv")).unwrap();
        assert_eq!(rows.len(), 1);
        assert!(rows[0].breakpoints && rows[0].scene.is_empty());
        assert_eq!(rows[0].error, Some(2e-7));
        let bad = format!("{good}half-sine,scipy-RK45,1e-7,,oops,,150,25,1e-4\n");
        let e = read_csv(bad.as_bytes(), Path::new("w.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("w.csv:3:"), "{e}");
    }
}

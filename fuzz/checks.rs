//! The promises the fuzz targets check, one function per input surface, shared by the
//! cargo-fuzz targets (`fuzz/fuzz_targets/*.rs`) and their replay in `cargo test`
//! (`tests/fuzz_corpus.rs`), which include this file by path.
//!
//! Each function takes the raw input bytes and panics when a promise is broken:
//! - the input is refused with the crate's `Error`, as bad input (exit code 2), in one line,
//!   naming what was wrong (the field, option or line); or
//! - it runs, and every number of the result is finite and its checks are within the bounds
//!   below.
//!
//! The work of one input is capped here (rows, points, shots, steps, tolerances): inputs
//! over a cap are skipped, not run, and `Verdict::Skipped` says so.

use billiard_contact::batch::{run_csv, BatchSetup};
use billiard_contact::profile::{parse_table, ForceProfile, Profile, Tabulated};
use billiard_contact::sweep::{self, parse_list, Grid, Spin};
use billiard_contact::work_precision::{self, StudyForce, StudyOptions};
use billiard_contact::{
    run_scene, CushionRestitution, CushionScene, Error, Method, Report, Scene, SceneOutcome,
    SolverSettings,
};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// What became of one input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Refused with a bad-input error that met the promises.
    Refused,
    /// Ran, and the result met the promises.
    Ran,
    /// Over a work cap of the harness, or not text: not run.
    Skipped,
}

/// The largest input a target reads, in bytes (also libFuzzer's `-max_len` in
/// `fuzz/campaign`).
pub const MAX_LEN: usize = 4096;
/// rk4 steps of one run at most; the adaptive methods' tolerances at least this.
pub const MAX_RK4_STEPS: u32 = 20_000;
pub const MIN_RTOL: f64 = 1e-12;
/// Rows of a batch input, points of a table, shots of a sweep.
pub const MAX_ROWS: usize = 64;
pub const MAX_POINTS: usize = 512;
pub const MAX_SHOTS: usize = 8;
/// Closed form: momentum, angular momentum and energy balance hold to this (scaled).
pub const CLOSED_FORM_BALANCE: f64 = 1e-8;

/// The directory that holds `data/` (the root crate's or, from `fuzz/`, its parent's).
fn data_dir() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    for d in [here.join("data"), here.join("../data")] {
        if d.is_dir() {
            return d;
        }
    }
    here.join("data")
}

/// A refusal: bad input, one line, not empty, and naming where (`names` returns whether
/// the message names the field, option or line).
fn refused(e: &Error, what: &str, names: impl Fn(&Error, &str) -> bool) -> Verdict {
    let msg = e.to_string();
    assert!(e.is_bad_input(), "{what}: not bad input: {msg}");
    assert!(
        !msg.contains('\n'),
        "{what}: a refusal of more than one line: {msg:?}"
    );
    assert!(!msg.trim().is_empty(), "{what}: an empty refusal");
    assert!(
        names(e, &msg),
        "{what}: the refusal names no field or line: {msg}"
    );
    Verdict::Refused
}

/// A scene refusal names a field (`field = value: ...`), the touching rule, a line of the
/// text (`line L, column C`) or a file (a table the scene names).
fn names_scene_field(e: &Error, msg: &str) -> bool {
    match e {
        Error::InvalidParameter { field, .. } => !field.is_empty() && msg.starts_with(field),
        Error::NotTouching { .. } => msg.starts_with("incoming.lab.b.position"),
        Error::ProfileTable { line, .. } => *line >= 1,
        Error::Scene { message, .. } => !message.is_empty(),
        Error::Io { .. } => true,
        _ => false,
    }
}

/// Caps a parsed scene's work: rk4 steps and the adaptive tolerances (each moved toward the
/// middle of its range, so the setters accept it).
pub fn bounded(s: &SolverSettings) -> SolverSettings {
    s.with_steps(s.steps().min(MAX_RK4_STEPS))
        .and_then(|b| b.with_rtol(s.rtol().max(MIN_RTOL)))
        .and_then(|b| b.with_atol(s.atol().max(MIN_RTOL)))
        .unwrap_or(*s)
}

/// A run's result: every number finite, the JSON report serialises (it refuses non-finite
/// numbers), the checks finite and not negative, the closed form's balances to
/// [`CLOSED_FORM_BALANCE`], the stick time within the contact.
fn check_outcome(scene: &Scene, out: &SceneOutcome, what: &str) {
    let o = &out.outcome;
    let r = &o.result;
    assert!(r.out.is_finite(), "{what}: outgoing state {:?}", r.out);
    for (name, x) in [
        ("impulse", r.impulse),
        ("s0", r.s0),
        ("s_out", r.s_out),
        ("tangential_impulse", r.tangential_impulse),
        ("heat", r.heat),
        ("heat_sliding", r.heat_sliding),
    ] {
        assert!(x.is_finite(), "{what}: {name} = {x}");
    }
    assert!(
        r.impulse >= 0.0 && r.s0 >= 0.0 && r.s_out >= 0.0,
        "{what}: {r:?}"
    );
    let c = &o.check;
    for (name, x) in [
        ("theta_drift", c.theta_drift),
        ("closed_form_error", c.closed_form_error),
        ("momentum_error", c.momentum_error),
        ("angular_momentum_error", c.angular_momentum_error),
        ("energy_balance_error", c.energy_balance_error),
        ("slip_consistency", c.slip_consistency),
    ] {
        assert!(x.is_finite() && x >= 0.0, "{what}: check {name} = {x}");
    }
    if o.method == Method::ClosedForm && o.law.is_none() {
        for (name, x) in [
            ("momentum_error", c.momentum_error),
            ("angular_momentum_error", c.angular_momentum_error),
            ("energy_balance_error", c.energy_balance_error),
        ] {
            assert!(
                x <= CLOSED_FORM_BALANCE,
                "{what}: closed form {name} = {x:e}"
            );
        }
    }
    if let Some(t) = o.stick_time {
        assert!(t.is_finite() && t >= 0.0, "{what}: stick time {t}");
    }
    if let Some(a) = out.throw_angle_deg {
        assert!(a.is_finite() && a.abs() <= 180.0, "{what}: throw {a}");
    }
    if let Err(e) = Report::new(scene, out).to_json() {
        panic!("{what}: the report does not serialise: {e}");
    }
}

/// Runs a parsed scene with the closed form and with its own (bounded) method.
fn run_both(scene: &Scene, what: &str) {
    let own = bounded(&scene.solver);
    for settings in [own.with_method(Method::ClosedForm), own] {
        let what = format!("{what} ({})", settings.method());
        match run_scene(scene, &settings, None) {
            Ok(out) => check_outcome(scene, &out, &what),
            Err(e) => {
                refused(&e, &what, names_scene_field);
            }
        }
    }
}

/// Target `scene_toml`: scene text through `Scene::parse` and `run_scene`.
pub fn check_scene(data: &[u8]) -> Verdict {
    let Ok(text) = std::str::from_utf8(data) else {
        return Verdict::Skipped;
    };
    if data.len() > MAX_LEN {
        return Verdict::Skipped;
    }
    let base = data_dir().join("scenes");
    match Scene::parse(text, &base, None) {
        Err(e) => refused(&e, "scene", names_scene_field),
        Ok(scene) => {
            run_both(&scene, "scene");
            Verdict::Ran
        }
    }
}

/// Target `cushion_toml`: cushion scene text through `CushionScene::parse` and the impact,
/// with the scene's own (bounded) method and, if it is another, dop853. Promises beyond
/// finite numbers: the impulses are not negative and the cloth's balances at most the
/// vertical part of the cushion's push, P_table <= P_I (sin theta + mu_cushion cos theta)
/// (the normal impulse's share sin theta, friction's at most mu_cushion cos theta: the
/// cushion's tangent plane holds the x axis and (0, -sin theta, cos theta)); the compression's impulse is at
/// most the total; every event lies within the impact; with Stronge's rule the energy lost
/// is not negative (to 1e-9 of the kinetic energy brought in) and the work given back is
/// e^2 times the work of compression (to 1e-6 of it). Newton's rule may create energy with
/// friction (Kane and Levinson's paradox), so its energy is only checked finite.
pub fn check_cushion(data: &[u8]) -> Verdict {
    let Ok(text) = std::str::from_utf8(data) else {
        return Verdict::Skipped;
    };
    if data.len() > MAX_LEN {
        return Verdict::Skipped;
    }
    let scene = match CushionScene::parse(text, None) {
        Err(e) => return refused(&e, "cushion scene", names_scene_field),
        Ok(scene) => scene,
    };
    let own = bounded(&scene.solver);
    let mut runs = vec![own];
    if own.method() != Method::Dop853 {
        runs.push(own.with_method(Method::Dop853));
    }
    let (m, r, alpha) = (scene.ball.mass(), scene.ball.radius(), scene.ball.alpha());
    let sin_theta = (scene.cushion.height() - r) / r;
    let cos_theta = (1.0 - sin_theta * sin_theta).max(0.0).sqrt();
    let table_share = sin_theta + scene.cushion.mu_cushion() * cos_theta;
    let energy_in = 0.5 * m * scene.velocity.norm_squared()
        + 0.5 * alpha * m * r * r * scene.spin.norm_squared();
    for settings in runs {
        let what = format!("cushion ({})", settings.method());
        let out = match scene.run(&settings, None) {
            Ok(out) => out,
            Err(e) => {
                refused(&e, &what, names_scene_field);
                continue;
            }
        };
        assert!(
            out.v.iter().chain(out.w.iter()).all(|x| x.is_finite()),
            "{what}: {out:?}"
        );
        let p = out.impulse_cushion;
        for (name, x) in [
            ("impulse_cushion", p),
            ("impulse_compression", out.impulse_compression),
            ("impulse_table", out.impulse_table),
            ("work_compression", out.work_compression),
            ("work_restitution", out.work_restitution),
        ] {
            assert!(x.is_finite() && x >= 0.0, "{what}: {name} = {x}");
        }
        assert!(
            out.impulse_compression <= p * (1.0 + 1e-12),
            "{what}: {out:?}"
        );
        assert!(
            out.impulse_table <= p * table_share * (1.0 + 1e-9),
            "{what}: the cloth's impulse above P_I (sin theta + mu_cushion cos theta): {out:?}"
        );
        for e in &out.events {
            assert!(
                e.impulse.is_finite() && e.impulse >= 0.0 && e.impulse <= p * (1.0 + 1e-12),
                "{what}: event {e:?} outside the impact (P_I = {p})"
            );
        }
        assert!(
            out.energy_lost.is_finite(),
            "{what}: energy lost {}",
            out.energy_lost
        );
        // Newton's kinematic rule can create energy with friction (Kane and Levinson's
        // paradox; docs/cushion.md): the promise is Stronge's.
        if scene.cushion.rule() == CushionRestitution::Stronge {
            assert!(
                out.energy_lost >= -1e-9 * energy_in,
                "{what}: energy lost {} of {energy_in}",
                out.energy_lost
            );
            let e2 = scene.cushion.restitution().powi(2);
            let wc = out.work_compression;
            assert!(
                (out.work_restitution - e2 * wc).abs() <= 1e-6 * wc + 1e-300,
                "{what}: work of restitution {} against e^2 W_c = {}",
                out.work_restitution,
                e2 * wc
            );
        }
    }
    Verdict::Ran
}

/// A stun cut, the scene a table is run in.
const STUN_CUT: &str = "[balls]\nmass = 0.17\nradius = 0.028575\n[contact]\nmu = 0.2\n\
                        [contact.profile]\nshape = \"rectangle\"\nduration = 3e-4\n\
                        [incoming.cm]\nu = [1.0, 0.01, 0.0]\n";

/// Target `profile_csv`: a force table through `parse_table` and `Tabulated::new` (without
/// and with a duration), as a profile (Phi finite, monotone, 0 to 1; its inverse in
/// [0, 1]) and in a run with the closed form and dop853.
pub fn check_profile_csv(data: &[u8]) -> Verdict {
    let Ok(text) = std::str::from_utf8(data) else {
        return Verdict::Skipped;
    };
    if data.len() > MAX_LEN || text.lines().count() > MAX_POINTS {
        return Verdict::Skipped;
    }
    let path = Path::new("fuzz.csv");
    // A line's fault names the line (1 the header); a fault of the table as a whole (an
    // empty file, too few points, a point out of order or too close) is at line 0 and
    // names the point or the table.
    let names_line = |e: &Error, msg: &str| match e {
        Error::ProfileTable { line, message, .. } => {
            *line >= 1 || (msg.starts_with("fuzz.csv:0: ") && !message.is_empty())
        }
        Error::InvalidParameter { .. } => true,
        _ => false,
    };
    let points = match parse_table(text, path) {
        Ok(p) => p,
        Err(e) => return refused(&e, "table", names_line),
    };
    let mut verdict = Verdict::Refused;
    for duration in [None, Some(2.5e-4)] {
        let what = format!("table (duration {duration:?})");
        let t = match Tabulated::new(&points, duration, path) {
            Ok(t) => t,
            Err(e) => {
                refused(&e, &what, names_line);
                continue;
            }
        };
        let p = Profile::Tabulated(t);
        let mut last = 0.0;
        for i in 0..=64 {
            let s = i as f64 / 64.0;
            let (phi, cum) = (p.shape(s), p.cumulative(s));
            assert!(phi.is_finite() && phi >= 0.0, "{what}: phi({s}) = {phi}");
            assert!(
                cum.is_finite() && cum >= last - 1e-15 && cum <= 1.0 + 1e-15,
                "{what}: Phi({s}) = {cum} after {last}"
            );
            last = cum;
            let back = p.time_at_cumulative(s);
            assert!((0.0..=1.0).contains(&back), "{what}: inverse({s}) = {back}");
        }
        assert!(
            (p.cumulative(1.0) - 1.0).abs() <= 1e-12,
            "{what}: Phi(1) = {}",
            p.cumulative(1.0)
        );
        let mut scene = Scene::parse(STUN_CUT, Path::new("."), None).expect("stun cut");
        scene.profile = p;
        scene.solver = scene.solver.with_method(Method::Dop853);
        run_both(&scene, &what);
        verdict = Verdict::Ran;
    }
    verdict
}

/// Centre-of-mass header with every optional column: prepended to an input whose first
/// line does not name `u_x`.
pub const CM_HEADER: &str = "id,u_x,u_y,u_z,omega_a_x,omega_a_y,omega_a_z,omega_b_x,omega_b_y,\
                             omega_b_z,mass,radius,alpha,mu,restitution,impulse,duration\n";
/// Lab-frame header with every optional column: prepended to an input whose first line
/// does not name `a_px`.
pub const LAB_HEADER: &str = "id,a_px,a_py,a_pz,b_px,b_py,b_pz,a_vx,a_vy,a_vz,b_vx,b_vy,b_vz,\
                              a_wx,a_wy,a_wz,b_wx,b_wy,b_wz,up_x,up_y,up_z,mass,mu\n";

/// Targets `batch_cm` and `batch_lab`: CSV rows through `batch::run_csv` with the default
/// scene, with the closed form and with dop853, in chunks of 7 rows (so that chunks
/// split). Refusals are the line's (`Error::BatchInput`, line within the input); output
/// has a row per input row and every number cell finite; dop853's `closed_form_error` at
/// most 1e-6 (rtol = atol = 1e-10).
fn check_batch(data: &[u8], key: &str, header: &str) -> Verdict {
    if data.len() > MAX_LEN {
        return Verdict::Skipped;
    }
    let first = data.split(|&b| b == b'\n').next().unwrap_or(&[]);
    let own_header = first.windows(key.len()).any(|w| w == key.as_bytes());
    let mut input = Vec::with_capacity(header.len() + data.len());
    if !own_header {
        input.extend_from_slice(header.as_bytes());
    }
    input.extend_from_slice(data);
    let lines = input.split(|&b| b == b'\n' || b == b'\r').count() as u64;
    if lines > MAX_ROWS as u64 + 1 {
        return Verdict::Skipped;
    }
    let scene = Scene::default_scene();
    let mut verdict = Verdict::Refused;
    for method in [Method::ClosedForm, Method::Dop853] {
        let setup = BatchSetup::from_scene(&scene, scene.solver.with_method(method));
        let what = format!("batch {key} ({method})");
        match run_csv(
            &setup,
            &input[..],
            Path::new("fuzz.csv"),
            Vec::new(),
            7,
            |_, _| {},
        ) {
            Err(e) => {
                let names_line = |e: &Error, _: &str| matches!(e, Error::BatchInput { line, .. } if *line >= 1 && *line <= lines + 1);
                refused(&e, &what, names_line);
            }
            Ok((out, summary)) => {
                check_batch_output(&out, summary.rows, &what);
                verdict = Verdict::Ran;
            }
        }
    }
    verdict
}

/// The batch output: a header and one row per resolved row, every cell but `id` empty,
/// `true`/`false` or a finite number.
fn check_batch_output(out: &[u8], rows: u64, what: &str) {
    let mut rd = csv::ReaderBuilder::new().from_reader(out);
    let header = rd.headers().expect("output header").clone();
    let id = header.iter().position(|h| h == "id");
    let cfe = header.iter().position(|h| h == "closed_form_error");
    let mut n = 0;
    for rec in rd.records() {
        let rec = rec.unwrap_or_else(|e| panic!("{what}: output row: {e}"));
        for (i, cell) in rec.iter().enumerate() {
            if Some(i) == id || cell.is_empty() || cell == "true" || cell == "false" {
                continue;
            }
            let x: f64 = cell
                .parse()
                .unwrap_or_else(|_| panic!("{what}: cell {} = {cell:?}", &header[i]));
            assert!(x.is_finite(), "{what}: {} = {cell}", &header[i]);
            if Some(i) == cfe {
                assert!(x <= 1e-6, "{what}: closed_form_error = {cell}");
            }
        }
        n += 1;
    }
    assert_eq!(n, rows, "{what}: output rows");
}

/// Target `batch_cm`.
pub fn check_batch_cm(data: &[u8]) -> Verdict {
    check_batch(data, "u_x", CM_HEADER)
}

/// Target `batch_lab`.
pub fn check_batch_lab(data: &[u8]) -> Verdict {
    check_batch(data, "a_px", LAB_HEADER)
}

/// Target `sweep_options`: the text of `--spin`, `--speed`, `--side` and `--cut`, one a
/// line (missing lines take the command's defaults, but one shot each), through
/// `Spin::parse`, `parse_list` and `Grid::new`, then `run_sweep` of the default scene with
/// the closed form and dop853, and `write_csv` (which refuses non-finite numbers). A
/// refusal names its option; rows come in grid order, the throw and deflection in
/// [-180, 180] degrees, the stick time within the contact.
pub fn check_sweep(data: &[u8]) -> Verdict {
    let Ok(text) = std::str::from_utf8(data) else {
        return Verdict::Skipped;
    };
    if data.len() > MAX_LEN {
        return Verdict::Skipped;
    }
    let mut lines = text.split('\n');
    let mut next = |default: &'static str| lines.next().unwrap_or(default).to_string();
    let (spin, speed, side, cut) = (next("stun"), next("1.341"), next("0"), next("30"));
    let names_option = |option: &'static str| {
        move |e: &Error, msg: &str| {
            matches!(e, Error::InvalidParameter { field, .. } if field == option)
                && msg.starts_with(option)
        }
    };
    let spins = match spin
        .split(',')
        .map(Spin::parse)
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(s) => s,
        Err(e) => return refused(&e, "--spin", names_option("--spin")),
    };
    // parse_list holds up to a million values a range: more than a few are over the cap
    // of the shots anyway, so each list is parsed only when its ranges are short.
    let mut lists = Vec::new();
    for (option, t) in [("--speed", &speed), ("--side", &side), ("--cut", &cut)] {
        match parse_list(option, t) {
            Ok(v) => lists.push(v),
            Err(e) => return refused(&e, option, names_option(option)),
        }
    }
    let cuts = lists.pop().unwrap();
    let sides = lists.pop().unwrap();
    let speeds = lists.pop().unwrap();
    let shots = [spins.len(), speeds.len(), sides.len(), cuts.len()]
        .iter()
        .try_fold(1usize, |n, &k| n.checked_mul(k))
        .unwrap_or(usize::MAX);
    let grid = match Grid::new(spins, speeds, sides, cuts) {
        Ok(g) => g,
        Err(e) => {
            // One option, or the product of all four (`--spin x --speed x --side x --cut`:
            // too many shots).
            let names = |e: &Error, msg: &str| {
                matches!(e, Error::InvalidParameter { field, .. }
                    if ["--spin", "--speed", "--side", "--cut"].iter().any(|o| field.contains(o))
                        && msg.starts_with(field.as_str()))
            };
            return refused(&e, "grid", names);
        }
    };
    if shots > MAX_SHOTS {
        return Verdict::Skipped;
    }
    assert_eq!(grid.len(), shots);
    let scene = Scene::default_scene();
    for method in [Method::ClosedForm, Method::Dop853] {
        let settings = scene.solver.with_method(method);
        let what = format!("sweep ({method})");
        match sweep::run_sweep(&scene, &settings, &grid, |_| {}) {
            Err(e) => {
                refused(&e, &what, names_scene_field);
            }
            Ok(rows) => {
                assert_eq!(rows.len(), shots, "{what}");
                for (i, r) in rows.iter().enumerate() {
                    assert_eq!(r.shot, grid.shot(i), "{what}: row {i}");
                    for (name, x) in [
                        ("throw_deg", r.throw_deg),
                        ("cue_deflection_deg", r.cue_deflection_deg),
                    ] {
                        if let Some(x) = x {
                            assert!(x.is_finite() && x.abs() <= 180.0, "{what}: {name} {x}");
                        }
                    }
                    if let Some(t) = r.stick_time {
                        assert!(t.is_finite() && t >= 0.0, "{what}: stick time {t}");
                    }
                }
                if let Err(e) = sweep::write_csv(Vec::new(), &rows, scene.effects.table) {
                    panic!("{what}: the CSV refuses the rows: {e}");
                }
            }
        }
    }
    Verdict::Ran
}

/// Reads a little-endian f64 from `bytes` at `i` (zeros past the end).
fn f64_at(bytes: &[u8], i: usize) -> f64 {
    let mut b = [0u8; 8];
    for (k, x) in b.iter_mut().enumerate() {
        *x = bytes.get(i + k).copied().unwrap_or(0);
    }
    f64::from_le_bytes(b)
}

/// Target `work_precision_options`: `StudyOptions` decoded from the bytes (byte 0: the
/// profiles and laws, a bit each of `StudyForce::ALL`; byte 1: bits 0-1 the repeats
/// 0..=3, bit 2 the sticking companion scene, bits 3-4 how many rtols (0..=3), bits 5-6
/// how many rk4 step counts (0..=3); then the rtols as 8-byte floats and the step counts as
/// 2-byte integers), through `run_study` on the default scene with no timing
/// (`sample_time` and `setting_budget` zero). Valid but slow settings are skipped: rtol in
/// (0, 1e-9), more than 1024 steps. A refusal names the option; rows come with a finite,
/// non-negative error or a note of why the run failed, finite timings, and the study CSV
/// writes and reads back.
pub fn check_work_precision(data: &[u8]) -> Verdict {
    if data.len() < 2 || data.len() > 64 {
        return Verdict::Skipped;
    }
    let (mask, flags) = (data[0], data[1]);
    let profiles: Vec<StudyForce> = StudyForce::ALL
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, f)| *f)
        .collect();
    let n_rtols = ((flags >> 3) & 3) as usize;
    let n_steps = ((flags >> 5) & 3) as usize;
    let rtols: Vec<f64> = (0..n_rtols).map(|k| f64_at(data, 2 + 8 * k)).collect();
    let at = 2 + 8 * n_rtols;
    let steps: Vec<u32> = (0..n_steps)
        .map(|k| {
            u16::from_le_bytes([
                data.get(at + 2 * k).copied().unwrap_or(0),
                data.get(at + 2 * k + 1).copied().unwrap_or(0),
            ]) as u32
        })
        .collect();
    if rtols.iter().any(|&r| r > 0.0 && r < 1e-9) || steps.iter().any(|&s| s > 1024) {
        return Verdict::Skipped;
    }
    let options = StudyOptions {
        profiles,
        rtols,
        rk4_steps: steps,
        repeats: (flags & 3) as usize,
        sample_time: Duration::ZERO,
        setting_budget: Duration::ZERO,
        sticking_scene: flags & 4 != 0,
    };
    let what = format!("work-precision {options:?}");
    let names = |e: &Error, _: &str| matches!(e, Error::InvalidParameter { field, .. } if !field.is_empty());
    match work_precision::run_study(Scene::default_scene(), &options, |_, _, _| {}) {
        Err(e) => refused(&e, &what, names),
        Ok(rows) => {
            assert!(!rows.is_empty(), "{what}: no rows");
            for r in &rows {
                match r.error {
                    Some(x) => assert!(x.is_finite() && x >= 0.0, "{what}: error {x} in {r:?}"),
                    None => assert!(!r.note.is_empty(), "{what}: no error and no note: {r:?}"),
                }
                if let Some(x) = r.stick_time_error {
                    assert!(x.is_finite() && x >= 0.0, "{what}: stick time error {x}");
                }
                assert!(
                    r.seconds_per_contact.is_finite() && r.seconds_per_contact >= 0.0,
                    "{what}: seconds {}",
                    r.seconds_per_contact
                );
                for x in [r.restitution, r.coefficient].into_iter().flatten() {
                    assert!(x.is_finite(), "{what}: {r:?}");
                }
            }
            let csv = work_precision::write_csv(Vec::new(), &rows)
                .unwrap_or_else(|e| panic!("{what}: the CSV refuses the rows: {e}"));
            let back = work_precision::read_csv(&csv[..], Path::new("fuzz.csv"))
                .unwrap_or_else(|e| panic!("{what}: the CSV does not read back: {e}"));
            assert_eq!(back.len(), rows.len(), "{what}: rows read back");
            Verdict::Ran
        }
    }
}

/// A target's checking function.
pub type Check = fn(&[u8]) -> Verdict;

/// Every target by name, in the order of `fuzz/campaign`.
pub const TARGETS: [(&str, Check); 7] = [
    ("scene_toml", check_scene),
    ("cushion_toml", check_cushion),
    ("profile_csv", check_profile_csv),
    ("batch_cm", check_batch_cm),
    ("batch_lab", check_batch_lab),
    ("sweep_options", check_sweep),
    ("work_precision_options", check_work_precision),
];

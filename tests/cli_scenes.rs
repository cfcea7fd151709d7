//! The command as a user runs it: every scene in `data/scenes/` with every method, the JSON
//! contract (docs/formats.md), agreement with the independent first-principles
//! resolution (`common::resolve`, computed from the scene file as tests/common/scene_file.rs
//! reads it with `toml`, not through the crate's scene code; speed-dependent mu: the closed
//! form of tests/common/hard.rs), the table phase against its physics written out in
//! tests/common/table.rs, the trace CSV with its force and sliding-heat columns, and
//! failures that leave no file behind.

use crate::cli_common;
use crate::common;

use cli_common::fresh_dir;
use cli_common::json_contract::{check_contract, number, vector3};
use common::amax;
use common::scene_file::{read_scene, SceneRef};
use common::table::{Cloth, RollOut};
use common::Expected;
use nalgebra::Vector3;
use serde_json::Value;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Output;

/// What each method reaches on the scenes at `--rtol 1e-12` (rk4 at the scene's steps),
/// against the independent resolution: `cargo test --release --test suite
/// cli_scenes::every_scene -- --nocapture` prints the worst of each quantity. Each tolerance is about
/// ten times the measured worst (in the comment), so a regression of two orders of
/// magnitude fails.
struct Tol {
    /// Scaled state, impulses, slips and heats.
    state: f64,
    /// Stick time over the duration (the promise of docs/model.md#locating-the-stop-of-sliding
    /// is 1e-10 where the force is not small, 1e-8 for rk4).
    stick_time: f64,
    /// |stick_impulse - p_stick| / P (the promise is 1e-10).
    stick_impulse: f64,
    /// Throw angle (degrees). With speed-dependent mu (cut_speed_dependent.toml, a throw of
    /// 1 degree) the adaptive methods' state error of the nonlinear slide reaches the angle
    /// more: measured worst 5.65e-13 (dopri5) and 1.22e-12 (dop853) degrees there.
    throw_deg: f64,
    /// The table object (draw_table, jump_follow, cut_speed_dependent), scaled as in
    /// [`check_table`].
    table: f64,
    /// The table's directions and deflections (degrees).
    table_deg: f64,
    /// The trace's force at the default settings over P / duration: the row's time and force
    /// both come from the integration variable (the time transform's p/P for the half-sine
    /// and hertz), so near the ends the printed t carries the round-off of inverting it.
    trace_force: f64,
    /// The trace's cumulative impulse p at the default settings over P (the same t as the
    /// force).
    trace_impulse: f64,
    /// The trace's sliding heat at the default settings over m v_ref^2.
    trace_heat: f64,
}

/// Each tolerance ten times the measured worst over the scenes (the comment; the table
/// values over draw_table, jump_follow and cut_speed_dependent; the trace at the default
/// settings, the rest at --rtol 1e-12).
fn tol(method: &str, speed_dependent: bool) -> Tol {
    match method {
        // Measured worst: state 2.07e-16, stick time 1.81e-16, stick impulse 1.44e-16 P,
        // throw 1.78e-15 degrees; table 1.69e-16, table angles 3.55e-15 degrees; trace
        // force 1.27e-14, impulse 4.90e-16 P, heat 5.90e-17.
        "closed-form" => Tol {
            state: 2e-15,
            stick_time: 2e-15,
            stick_impulse: 2e-15,
            throw_deg: 2e-14,
            table: 2e-15,
            table_deg: 4e-14,
            trace_force: 1.5e-13,
            trace_impulse: 5e-15,
            trace_heat: 6e-16,
        },
        // Measured worst: state 1.33e-13, stick time 2.71e-16, stick impulse 2.89e-16 P,
        // throw 4.84e-14 degrees; table 4.63e-14, table angles 1.88e-12 degrees; trace
        // force 4.92e-14 over every row (8.9e-15 over the rows checked), impulse 1.22e-14
        // P, heat 1.30e-15.
        "rk4" => Tol {
            state: 1.5e-12,
            stick_time: 3e-15,
            stick_impulse: 3e-15,
            throw_deg: 5e-13,
            table: 5e-13,
            table_deg: 2e-11,
            trace_force: 5e-13,
            trace_impulse: 1.5e-13,
            trace_heat: 1.5e-14,
        },
        // Measured worst: state 6.68e-13, stick time 1.81e-16, stick impulse 1.44e-16 P,
        // throw 7.17e-14 degrees; table 7.59e-14, table angles 2.89e-12 degrees; trace
        // force 1.27e-11 (hertz_material), impulse 1.78e-11 P, heat 4.32e-12.
        "dopri5" => Tol {
            state: 7e-12,
            stick_time: 2e-15,
            stick_impulse: 2e-15,
            throw_deg: if speed_dependent { 6e-12 } else { 7e-13 },
            table: 8e-13,
            table_deg: 3e-11,
            trace_force: 1.5e-10,
            trace_impulse: 2e-10,
            trace_heat: 5e-11,
        },
        // dop853. Measured worst: state 2.75e-13, stick time 2.17e-16, stick impulse
        // 3.32e-16 P, throw 6.15e-14 degrees; table 1.63e-13, table angles 6.76e-12
        // degrees; trace force 3.97e-13, impulse 5.55e-13 P, heat 7.00e-12.
        _ => Tol {
            state: 3e-12,
            stick_time: 3e-15,
            stick_impulse: 3e-15,
            throw_deg: if speed_dependent { 1.2e-11 } else { 6e-13 },
            table: 2e-12,
            table_deg: 7e-11,
            trace_force: 4e-12,
            trace_impulse: 6e-12,
            trace_heat: 7e-11,
        },
    }
}

/// The largest value each quantity reached, per method (printed at the end of the test).
type Worst = std::collections::BTreeMap<String, f64>;

fn note(worst: &mut Worst, key: String, x: f64) {
    let w = worst.entry(key).or_insert(0.0);
    *w = w.max(x);
}
/// Samples of the trace tests.
const SAMPLES: u64 = 37;

const METHODS: [&str; 4] = ["closed-form", "rk4", "dopri5", "dop853"];

/// The trace header (docs/formats.md#trace-csv): time, force, cumulative impulse, U, V, W,
/// both balls' spins, S, theta, sliding heat, each `name (unit)`.
const TRACE_HEADER: [&str; 15] = [
    "t (s)",
    "f (N)",
    "p (N s)",
    "U (m/s)",
    "V (m/s)",
    "W (m/s)",
    "omega_a_x (rad/s)",
    "omega_a_y (rad/s)",
    "omega_a_z (rad/s)",
    "omega_b_x (rad/s)",
    "omega_b_y (rad/s)",
    "omega_b_z (rad/s)",
    "S (m/s)",
    "theta (rad)",
    "H_sfr (J)",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("data/scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        // Scenes of unequal balls ([balls.a]/[balls.b]) have their own reference in
        // tests/unequal_balls_*.rs; this file's reference is for identical balls.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("[balls.a]"))
        // Scenes of a ball against a plane ([plane]) have theirs in tests/plane_scenes.rs.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("[plane]"))
        // Cushion scenes ([cushion]) have theirs in tests/cushion_scenes.rs.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("[cushion]"))
        // Cluster scenes ([[balls]]) have theirs in tests/cluster_scenes.rs.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("[[balls]]"))
        .collect();
    v.sort();
    // The documented scenes must be there.
    for name in [
        "default",
        "paper_special_case",
        "head_on_stun",
        "stun_cut_slides",
        "stun_cut_sticks",
        "draw_side_spin",
        "tabulated_pulse",
        "separating",
    ] {
        assert!(
            v.iter().any(|p| p.file_stem().unwrap() == name),
            "data/scenes/{name}.toml missing"
        );
    }
    v
}

/// Runs the binary in the repository's root (scenes given relative to it).
fn run(args: &[&str]) -> Output {
    cli_common::bin_in(Some(&root()), args)
}

fn ok_stdout(args: &[&str]) -> String {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: exit {:?}, stderr {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn json(args: &[&str]) -> Value {
    let text = ok_stdout(args);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {text}"))
}

/// The scenes with a prescribed profile: a contact law's scene (`[contact.law]`) realises its
/// own impulse, which the reference here does not model; tests/contact_law_*.rs check them.
fn profile_scenes() -> Vec<PathBuf> {
    scenes()
        .into_iter()
        .filter(|p| {
            !std::fs::read_to_string(p)
                .unwrap()
                .contains("[contact.law]")
        })
        .collect()
}

/// The duration, and the `hertz` object exactly when the material sets the duration.
fn check_duration(sc: &SceneRef, j: &Value, what: &str) {
    let rel = |got: f64, want: f64| ((got - want) / want).abs();
    assert!(
        rel(number(j, "duration"), sc.duration) <= 1e-12,
        "{what}: duration"
    );
    match &sc.hertz {
        None => assert!(j.get("hertz").is_none(), "{what}: hertz without a material"),
        Some(h) => {
            let got = &j["hertz"];
            assert!(
                rel(number(got, "max_compression"), h.max_compression) <= 1e-12,
                "{what}"
            );
            assert!(
                rel(number(got, "peak_force"), h.peak_force) <= 1e-12,
                "{what}"
            );
            assert!(
                rel(number(got, "contact_radius"), h.contact_radius) <= 1e-12,
                "{what}"
            );
        }
    }
}

/// The scaled distance of a report from the reference; checks the scalar fields on the way.
fn compare(sc: &SceneRef, want: &Expected, j: &Value, method: &str, worst: &mut Worst) {
    let what = &format!("{} --method {method}", sc.name);
    let tol = tol(method, sc.speed_law.is_some());
    let b = &sc.balls;
    let v = sc.pair.v_ref(b.r);
    let (spin, imp, energy) = (v / b.r, b.m * v, b.m * v * v);
    assert_eq!(j["collision"], want.collision, "{what}");
    let (u, wa, wb) = sc.to_cm(&want.out);
    let cm = &j["cm_out"];
    let mut errs = vec![
        amax(&(vector3(&cm["u"]) - u)) / v,
        amax(&(vector3(&cm["omega_a"]) - wa)) / spin,
        amax(&(vector3(&cm["omega_b"]) - wb)) / spin,
        (number(j, "impulse") - want.impulse).abs() / imp,
        (number(j, "s0") - want.s0).abs() / v,
        (number(j, "s_out") - want.s_out).abs() / v,
        (number(j, "tangential_impulse") - want.tangential).abs() / imp,
        (number(j, "heat") - want.heat).abs() / energy,
        (number(j, "heat_sliding") - want.heat_sliding).abs() / energy,
    ];
    if sc.lab {
        let lab = &j["lab_out"];
        errs.extend([
            amax(&(vector3(&lab["a"]["velocity"]) - want.out.va)) / v,
            amax(&(vector3(&lab["b"]["velocity"]) - want.out.vb)) / v,
            amax(&(vector3(&lab["a"]["spin"]) - want.out.wa)) / spin,
            amax(&(vector3(&lab["b"]["spin"]) - want.out.wb)) / spin,
        ]);
    } else {
        assert!(
            j.get("lab_out").is_none(),
            "{what}: lab_out for a centre-of-mass scene"
        );
    }
    let largest = errs.iter().cloned().fold(0.0, f64::max);
    note(worst, format!("{method} state"), largest);
    assert!(
        largest <= tol.state,
        "{what}: scaled errors {errs:?} > {:e}",
        tol.state
    );
    assert!(
        (number(&j["check"], "closed_form_error") - errs[..3].iter().cloned().fold(0.0, f64::max))
            .abs()
            <= 1e-13,
        "{what}: check.closed_form_error differs from the independent one"
    );
    assert_eq!(j["sticks"], want.sticks, "{what}");
    // theta (CM basis): S0 (cos, sin) against the slip's e_y, e_z parts; null when S0 = 0.
    let slip = sc.basis().transpose() * sc.pair.slip(b.r);
    if want.s0 == 0.0 {
        assert!(j["theta"].is_null(), "{what}: theta with S0 = 0");
    } else {
        let th = number(j, "theta");
        assert!(th > -PI && th <= PI);
        let d = (want.s0 * th.cos() - slip.y)
            .abs()
            .max((want.s0 * th.sin() - slip.z).abs());
        // Every method reports the incoming slip's angle, exactly: measured worst 0.
        note(worst, format!("{method} theta"), d / v);
        assert!(d <= 4.0 * f64::EPSILON * v, "{what}: theta {th}");
    }
    // Throw angle: counter-clockwise about up from the horizontal line of centres to B's
    // horizontal velocity change (the paper's +z is up for centre-of-mass scenes).
    let dvb = want.out.vb - sc.pair.vb;
    let line = sc.pair.n - sc.up * sc.pair.n.dot(&sc.up);
    let dvh = dvb - sc.up * dvb.dot(&sc.up);
    if line.norm() < 1e-12 || dvh.norm() == 0.0 {
        assert!(j["throw_angle_deg"].is_null(), "{what}: throw angle");
    } else {
        let want_deg = line
            .cross(&dvh)
            .dot(&sc.up)
            .atan2(line.dot(&dvh))
            .to_degrees();
        let got = number(j, "throw_angle_deg");
        note(worst, format!("{method} throw_deg"), (got - want_deg).abs());
        assert!(
            (got - want_deg).abs() <= tol.throw_deg,
            "{what}: throw {got} vs {want_deg}"
        );
    }
}

/// Stick time and impulse against the profile's reference.
fn check_stick(sc: &SceneRef, want: &Expected, j: &Value, method: &str, worst: &mut Worst) {
    let what = &format!("{} --method {method}", sc.name);
    let tol = tol(method, sc.speed_law.is_some());
    if !want.collision {
        let none = j["stick_time"].is_null() && j["stick_impulse"].is_null();
        assert!(none, "{what}");
        return;
    }
    if !want.sticks {
        assert!(j["stick_time"].is_null(), "{what}");
        match want.p_stick {
            Some(p) => {
                // The impulse at which sliding would stop, past P: measured worst 1.83e-16.
                let d = (number(j, "stick_impulse") - p).abs() / p;
                note(worst, format!("{method} p_stick past P"), d);
                assert!(d <= 2e-15, "{what}: stick_impulse {d:e} off p_stick");
            }
            None => assert!(j["stick_impulse"].is_null(), "{what}"),
        }
        return;
    }
    let p_stick = want.p_stick.unwrap();
    let t = number(j, "stick_time");
    if want.s0 == 0.0 {
        assert_eq!(t, 0.0, "{what}");
        assert_eq!(number(j, "stick_impulse"), 0.0, "{what}");
        return;
    }
    let exact = sc.duration * sc.profile.time(p_stick / want.impulse);
    let dt = (t - exact).abs() / sc.duration;
    note(worst, format!("{method} stick_time"), dt);
    assert!(dt <= tol.stick_time, "{what}: stick time {t} vs {exact}");
    let dp = (number(j, "stick_impulse") - p_stick).abs() / want.impulse;
    note(worst, format!("{method} stick_impulse"), dp);
    assert!(
        dp <= tol.stick_impulse,
        "{what}: stick impulse {dp:e} P off"
    );
}

/// The JSON `table` object against the roll-out of tests/common/table.rs, started from the
/// reference's outgoing lab state at the contact positions: times over the later end, speeds
/// over v_ref, spins over v_ref / r, lengths over v_ref t_end, impulses over m v_ref + m g
/// t_end, angles in degrees; counts and flags exactly.
fn check_table(
    sc: &SceneRef,
    cloth: &Cloth,
    want: &Expected,
    j: &Value,
    method: &str,
    worst: &mut Worst,
) {
    let what = &format!("{} --method {method}", sc.name);
    let b = &sc.balls;
    let table = &j["table"];
    let outs: [RollOut; 2] = [
        cloth.roll_out(b, sc.positions[0], want.out.va, want.out.wa),
        cloth.roll_out(b, sc.positions[1], want.out.vb, want.out.wb),
    ];
    let end = outs[0].end_time.max(outs[1].end_time);
    let v = sc.pair.v_ref(b.r);
    let (time, speed, spin, length) = (end, v, v / b.r, v * end);
    let impulse = b.m * v + b.m * cloth.g * end;
    let mut errs = vec![(number(table, "end_time") - end).abs() / time];
    let (mut angles, mut heights) = (Vec::new(), Vec::new());
    let line = sc.pair.n;
    for (k, (key, x)) in ["a", "b"].iter().zip(&outs).enumerate() {
        let got = &table[key];
        let imp = &got["impact"];
        let d = |v: &Value, w: Vector3<f64>, scale: f64| amax(&(vector3(v) - w)) / scale;
        let t = |key: &str, w: f64| (number(got, key) - w).abs() / time;
        errs.extend([
            t("hop_time", x.hop_time),
            t("settle_time", x.settle_time),
            t("slide_time", x.slide_time),
            t("roll_time", x.roll_time),
            (number(imp, "time") - x.impact.time).abs() / time,
            d(&imp["velocity"], x.impact.velocity, speed),
            d(&imp["spin"], x.impact.spin, spin),
            (number(imp, "normal_impulse") - x.impact.normal_impulse).abs() / impulse,
            (number(imp, "tangential_impulse") - x.impact.tangential_impulse).abs() / impulse,
            d(&got["slide_displacement"], x.slide_displacement, length),
            d(&got["rolling"]["velocity"], x.rolling_velocity, speed),
            d(&got["rolling"]["spin"], x.rolling_spin, spin),
            d(&got["rolling"]["position"], x.rolling_position, length),
            d(&got["table_impulse"], x.table_impulse, impulse),
        ]);
        heights.push((number(got, "hop_height") - x.hop_height).abs() / (v * v / cloth.g));
        assert_eq!(
            got["bounces"].as_u64(),
            Some(x.bounces),
            "{what}: {key} bounces"
        );
        assert_eq!(
            imp["sticks"], x.impact.sticks,
            "{what}: {key} impact sticks"
        );
        match x.rest {
            Some((t_rest, at)) => {
                errs.push((number(&got["rest"], "time") - t_rest).abs() / time);
                errs.push(d(&got["rest"]["position"], at, length));
            }
            None => assert!(got.get("rest").is_none(), "{what}: {key} rest"),
        }
        // Directions: from the line of centres; the deflection from the incoming direction
        // of a ball that moved (B comes in at rest in every scene).
        angles.push(
            (number(got, "direction_deg") - cloth.angle_deg(&line, &x.rolling_velocity)).abs(),
        );
        let incoming = [sc.pair.va, sc.pair.vb][k];
        if incoming.cross(&cloth.up).norm() > 0.0 {
            let deflection = cloth.angle_deg(&incoming, &x.rolling_velocity);
            angles.push((number(got, "deflection_deg") - deflection).abs());
        } else {
            assert!(got.get("deflection_deg").is_none(), "{what}: {key}");
        }
    }
    for (key, x) in [
        ("mu", cloth.mu),
        ("restitution", cloth.restitution),
        ("g", cloth.g),
        ("rolling_resistance", cloth.rolling_resistance),
        ("spin_decay", cloth.spin_decay),
    ] {
        assert_eq!(number(table, key), x, "{what}: table.{key}");
    }
    let tol = tol(method, sc.speed_law.is_some());
    let largest = errs.iter().chain(&heights).cloned().fold(0.0, f64::max);
    note(worst, format!("{method} table"), largest);
    assert!(
        largest <= tol.table,
        "{what}: table errors {errs:?} {heights:?} > {:e}",
        tol.table
    );
    let largest = angles.iter().cloned().fold(0.0, f64::max);
    note(worst, format!("{method} table_deg"), largest);
    assert!(
        largest <= tol.table_deg,
        "{what}: table angles {angles:?} > {:e}",
        tol.table_deg
    );
}

#[test]
fn every_scene_runs_with_every_method_and_agrees_with_the_reference() {
    let mut worst = Worst::new();
    for path in profile_scenes() {
        let sc = read_scene(&path);
        let want = sc.expected();
        let p = path.to_str().unwrap();
        for method in METHODS {
            // The scene's own settings: runs, keeps the contract.
            let what = format!("{} --method {method}", path.display());
            let j = json(&["run", p, "--json", "--method", method]);
            check_contract(&j, sc.lab, method, &what);
            check_duration(&sc, &j, &what);
            // At rtol 1e-12: agrees with the reference.
            let j = json(&["run", p, "--json", "--method", method, "--rtol", "1e-12"]);
            check_contract(&j, sc.lab, method, &what);
            compare(&sc, &want, &j, method, &mut worst);
            check_stick(&sc, &want, &j, method, &mut worst);
            match &sc.cloth {
                Some(cloth) => check_table(&sc, cloth, &want, &j, method, &mut worst),
                None => assert!(j.get("table").is_none(), "{what}"),
            }
            if !want.collision {
                // No collision: the state is unchanged, exactly.
                assert_eq!(j["cm_out"], j["cm_in"], "{what}");
            }
        }
    }
    for (k, w) in &worst {
        eprintln!("scenes at rtol 1e-12, {k}: largest error {w:.2e}");
    }
}

/// `billiard-contact` with no arguments and `run` without a scene run the built-in default
/// scene, which is `data/scenes/default.toml` (docs/formats.md).
#[test]
fn default_runs() {
    let bare = ok_stdout(&[]);
    let run_only = ok_stdout(&["run"]);
    assert_eq!(bare, run_only);
    assert!(bare.contains("rolling cue ball"), "{bare}");
    let embedded = json(&["run", "--json"]);
    let file = json(&["run", "data/scenes/default.toml", "--json"]);
    assert_eq!(
        embedded, file,
        "the embedded default scene differs from the file"
    );
    check_contract(&embedded, true, "dop853", "default");
    let flat = json(&["--json", "--method", "closed-form"]);
    check_contract(&flat, true, "closed-form", "default --json");
}

fn read_trace(path: &Path) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|c| (!c.is_empty()).then(|| c.parse::<f64>().unwrap()))
                .collect()
        })
        .collect();
    (header, rows)
}

/// The trace's `f (N)`, `p (N s)` and `H_sfr (J)` columns at the row's time t (every row of
/// a sampled trace, every fifth of a trace by steps, and the last): the profile's force
/// P phi'(t / duration) / duration and impulse P phi(t / duration) by its formula
/// ([`ProfileRef::fraction_and_shape`]), and the heat of
/// sliding friction at the exact impulse p = P phi(t / duration), H_sfr(p) = integral_0^p
/// mu(S) S dp'. Along the slip dS/dp = -k mu(S) (k = 2 (1 + 1/alpha) / m), so
/// mu S dp = -S dS / k and H_sfr(p) = (S(0)^2 - S(p)^2) / (2 k) for any mu(S), with S(p)
/// from [`SceneRef::slip_at`]. Returns the largest scaled differences (force, impulse,
/// heat).
fn trace_values(sc: &SceneRef, want: &Expected, rows: &[Vec<Option<f64>>]) -> (f64, f64, f64) {
    let b = &sc.balls;
    let k = 2.0 * (1.0 + 1.0 / b.alpha) / b.m;
    let v = sc.pair.v_ref(b.r);
    let (mut force, mut impulse, mut heat) = (0.0f64, 0.0f64, 0.0f64);
    let stride = if rows.len() > 2 * SAMPLES as usize {
        5
    } else {
        1
    };
    let last = rows.len() - 1;
    for r in rows.iter().step_by(stride).chain(&rows[last..]) {
        let s = r[0].unwrap() / sc.duration;
        let (q, shape) = sc.profile.fraction_and_shape(s);
        let f_want = want.impulse / sc.duration * shape;
        force = force.max((r[1].unwrap() - f_want).abs() / (want.impulse / sc.duration));
        let p = want.impulse * q;
        impulse = impulse.max((r[2].unwrap() - p).abs() / want.impulse);
        let slip = sc.slip_at(want, p);
        let h_want = (want.s0 * want.s0 - slip * slip) / (2.0 * k);
        heat = heat.max((r[14].unwrap() - h_want).abs() / (b.m * v * v));
    }
    (force, impulse, heat)
}

/// Trace CSV: the contract header; with --samples N rows at exactly t = i duration / N plus
/// the stop once; time strictly increasing; S = 0 from the stop on; numbers finite; theta
/// empty only when S(0) = 0; the force, impulse and sliding heat of each row ([`trace_values`]).
#[test]
fn trace_csv_follows_the_contract() {
    let n = SAMPLES.to_string();
    let dir = fresh_dir("cli_scenes_trace");
    let mut worst = Worst::new();
    for path in profile_scenes() {
        let sc = read_scene(&path);
        let want = sc.expected();
        let p = path.to_str().unwrap();
        for method in METHODS {
            for sampled in [true, false] {
                let what = format!("{} {method} samples {sampled}", path.display());
                let file = dir.join(format!(
                    "{}-{method}-{sampled}.csv",
                    path.file_stem().unwrap().to_str().unwrap()
                ));
                let f_s = file.to_str().unwrap();
                let mut args = vec!["run", p, "--json", "--method", method, "--trace", f_s];
                if sampled {
                    args.extend(["--samples", n.as_str()]);
                }
                let j = json(&args);
                let (header, rows) = read_trace(&file);
                assert_eq!(header, TRACE_HEADER, "{what}");
                assert!(rows.iter().all(|r| r.len() == 15), "{what}: row width");
                let (force, impulse, heat) = trace_values(&sc, &want, &rows);
                note(&mut worst, format!("{method} trace f"), force);
                note(&mut worst, format!("{method} trace p"), impulse);
                note(&mut worst, format!("{method} trace H_sfr"), heat);
                let tol = tol(method, sc.speed_law.is_some());
                assert!(
                    force <= tol.trace_force
                        && impulse <= tol.trace_impulse
                        && heat <= tol.trace_heat,
                    "{what}: force {force:e}, p {impulse:e}, H_sfr {heat:e}"
                );
                let t: Vec<f64> = rows.iter().map(|r| r[0].unwrap()).collect();
                assert!(
                    t.windows(2).all(|w| w[0] < w[1]),
                    "{what}: time not increasing"
                );
                assert_eq!(t[0], 0.0, "{what}");
                let end = *t.last().unwrap();
                assert!(
                    (end - sc.duration).abs() <= 4.0 * f64::EPSILON * sc.duration,
                    "{what}: last row at {end}, not at the end"
                );
                for r in &rows {
                    for (k, x) in r.iter().enumerate() {
                        match x {
                            Some(x) => assert!(x.is_finite(), "{what}"),
                            None => assert!(k == 13 && j["theta"].is_null(), "{what}: empty cell"),
                        }
                    }
                }
                let stop = j["stick_time"].as_f64();
                if let Some(ts) = stop {
                    assert_eq!(
                        t.iter().filter(|&&x| x == ts).count(),
                        1,
                        "{what}: stop row"
                    );
                    for r in rows.iter().filter(|r| r[0].unwrap() >= ts) {
                        assert_eq!(r[12], Some(0.0), "{what}: S after the stop");
                    }
                }
                if sampled {
                    let want: Vec<f64> = (0..=SAMPLES)
                        .map(|i| i as f64 * sc.duration / SAMPLES as f64)
                        .collect();
                    // A stop that falls on a sample time is written once.
                    let samples: Vec<f64> = t
                        .iter()
                        .copied()
                        .filter(|x| Some(*x) != stop || want.contains(x))
                        .collect();
                    assert_eq!(samples, want, "{what}: sample times");
                } else if method == "closed-form" {
                    // 100 samples without --samples (docs/guide.md, "Trace CSV").
                    let extra = usize::from(stop.is_some_and(|x| x > 0.0));
                    assert_eq!(rows.len(), 101 + extra, "{what}");
                }
                // The final row is the outgoing state of the report.
                let last = rows.last().unwrap();
                let u = vector3(&j["cm_out"]["u"]);
                assert_eq!(
                    [last[3], last[4], last[5]],
                    [Some(u.x), Some(u.y), Some(u.z)],
                    "{what}"
                );
                std::fs::remove_file(&file).unwrap();
            }
        }
    }
    for (k, w) in &worst {
        eprintln!("traces at the default settings, {k}: largest error {w:.2e}");
    }
}

/// A failing run writes no trace: bad input (exit 2) and a run that fails after the trace
/// was written (a non-finite energy, exit 1) leave neither the file nor a temporary one, and
/// an existing file is left as it was.
#[test]
fn failed_runs_leave_no_trace_file() {
    let dir = fresh_dir("cli_scenes_failing");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[balls]\nmass = -1.0\n").unwrap();
    // Speeds whose squares overflow: the outgoing kinetic energy is not finite.
    let huge = dir.join("huge.toml");
    std::fs::write(
        &huge,
        "[balls]\nmass = 0.17\nradius = 0.028575\n[contact]\nmu = 0.06\n\
         [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
         [incoming.cm]\nu = [1.3e154, 3e153, 0.0]\n",
    )
    .unwrap();
    for (scene, code) in [(&bad, 2), (&huge, 1)] {
        for method in METHODS {
            let trace = dir.join("trace.csv");
            let _ = std::fs::remove_file(&trace);
            let args = [
                "run",
                scene.to_str().unwrap(),
                "--json",
                "--method",
                method,
                "--trace",
                trace.to_str().unwrap(),
            ];
            let out = run(&args);
            assert_eq!(out.status.code(), Some(code), "{args:?}");
            assert!(out.stdout.is_empty(), "{args:?}: printed a report");
            assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
            assert!(!trace.exists(), "{args:?} left a trace");
            // An existing file is not touched.
            std::fs::write(&trace, "old").unwrap();
            assert_eq!(run(&args).status.code(), Some(code));
            assert_eq!(std::fs::read_to_string(&trace).unwrap(), "old");
            std::fs::remove_file(&trace).unwrap();
            let left: Vec<_> = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().into_string().unwrap())
                .filter(|n| n.ends_with(".tmp"))
                .collect();
            assert!(left.is_empty(), "temporary files left: {left:?}");
        }
    }
    let err = String::from_utf8(run(&["run", huge.to_str().unwrap(), "--json"]).stderr).unwrap();
    assert!(err.contains("non-finite"), "{err}");
}

/// `--path FILE --path-samples N` (docs/formats.md#ball-path-csv): rows at t = i T / N,
/// i = 0..N (T = `table.end_time`), plus every change of phase of either ball (impacts,
/// the start of rolling, rest), and at each impact with the cloth two rows sharing the time.
/// The event times come from the roll-out of tests/common/table.rs.
#[test]
fn path_rows_are_the_samples_and_the_events() {
    let dir = fresh_dir("cli_scenes_path");
    for name in ["draw_table.toml", "jump_follow.toml"] {
        let path = root().join("data/scenes").join(name);
        let sc = read_scene(&path);
        let want = sc.expected();
        let cloth = sc.cloth.unwrap();
        let b = &sc.balls;
        let outs = [
            cloth.roll_out(b, sc.positions[0], want.out.va, want.out.wa),
            cloth.roll_out(b, sc.positions[1], want.out.vb, want.out.wb),
        ];
        let end = outs[0].end_time.max(outs[1].end_time);
        // Distinct times, equal within round-off of the end time.
        let distinct = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * end);
            v
        };
        let mut impacts = Vec::new();
        let mut events = Vec::new();
        for o in &outs {
            impacts.extend(&o.impacts);
            events.extend(&o.impacts);
            events.push(o.roll_time);
            events.extend(o.rest.map(|r| r.0));
        }
        let impacts = distinct(impacts);
        assert!(!impacts.is_empty(), "{name}: no impact");
        for n in [10u32, 37] {
            let file = dir.join(format!("path-{name}-{n}.csv"));
            let n_s = n.to_string();
            let args = [
                "run",
                path.to_str().unwrap(),
                "--method",
                "closed-form",
                "--path",
                file.to_str().unwrap(),
                "--path-samples",
                n_s.as_str(),
            ];
            ok_stdout(&args);
            let text = std::fs::read_to_string(&file).unwrap();
            let t: Vec<f64> = text
                .lines()
                .skip(1)
                .map(|l| l.split(',').next().unwrap().parse().unwrap())
                .collect();
            let samples: Vec<f64> = (0..=n).map(|i| f64::from(i) * end / f64::from(n)).collect();
            for s in &samples {
                assert!(
                    t.iter().any(|x| (x - s).abs() <= 1e-12 * end),
                    "{name} N = {n}: no row at t = {s}"
                );
            }
            let times = distinct(samples.into_iter().chain(events.clone()).collect());
            assert_eq!(
                t.len(),
                times.len() + impacts.len(),
                "{name} N = {n}: rows at {t:?}"
            );
            std::fs::remove_file(&file).unwrap();
        }
    }
}

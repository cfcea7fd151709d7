//! The trace of a cluster run (docs/formats.md#the-cluster-trace): the kernel's trace
//! (`resolve_cluster_traced`) and `run SCENE --trace / --samples / --plot-trace / --plot` on
//! the shipped cluster scenes.
//!
//! The expected values come from outside the trace: the 3-ball cradle's impulses from the 1D
//! Hertz chain integrated here by RK4 (tests/common/hertz_chain.rs); every ball's momentum
//! and spin change, from the report's velocities and spins (the kernel's ball state,
//! integrated apart from its impulse accumulators), against the trace's impulses along the
//! report's normals; Hertz's closed-form peak force of two equal balls; the cue ball's
//! flight time of the nine-ball break from its scene.

use crate::cli_common;
use crate::common::hertz_chain::hertz_chain_rk4;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;
use cli_common::json_contract::vector3;
use cli_common::{bin, fresh_dir, refused, scene, succeeded};
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;

/// The balls of the shipped scenes: phenolic resin pool balls.
const M: f64 = 0.17;
const R: f64 = 0.028575;
const E: f64 = 5.4e9;
const NU: f64 = 0.34;
/// I = alpha m r^2, alpha = 0.4 (the scenes' default).
const INERTIA: f64 = 0.4 * M * R * R;

/// The trace CSV: header and rows of cells (`None`: an empty cell).
struct Trace {
    header: Vec<String>,
    rows: Vec<Vec<Option<f64>>>,
}

impl Trace {
    fn read(path: &Path) -> Trace {
        let text = std::fs::read_to_string(path).unwrap();
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let header = r.headers().unwrap().iter().map(String::from).collect();
        let rows = r
            .records()
            .map(|rec| {
                rec.unwrap()
                    .iter()
                    .map(|c| (!c.is_empty()).then(|| c.parse::<f64>().unwrap()))
                    .collect()
            })
            .collect();
        Trace { header, rows }
    }

    fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    }

    /// The cells of pair (i, j)'s column `what` (e.g. `normal_force (N)`).
    fn pair(&self, (i, j): (usize, usize), what: &str) -> Vec<Option<f64>> {
        let k = self.col(&format!("c{i}_{j}_{what}"));
        self.rows.iter().map(|r| r[k]).collect()
    }

    /// The last row's value of pair (i, j)'s column `what`.
    fn last(&self, p: (usize, usize), what: &str) -> f64 {
        self.pair(p, what).last().unwrap().unwrap()
    }

    fn times(&self) -> Vec<f64> {
        self.rows.iter().map(|r| r[0].unwrap()).collect()
    }
}

/// Runs `args` (which must succeed) and parses the JSON report on stdout.
fn run_json(args: &[&str]) -> Value {
    let out = bin(args);
    succeeded(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A pair's normal impulse (N s), friction impulse on ball i (N s) and normal.
type PairTotal = (f64, Vector3<f64>, Vector3<f64>);

/// The report's contacts summed per pair: normal impulse (N s), friction impulse on ball i
/// (N s), and the normal of the pair's (last) contact.
fn contacts_by_pair(j: &Value) -> HashMap<(usize, usize), PairTotal> {
    let mut out: HashMap<(usize, usize), PairTotal> = HashMap::new();
    for c in j["contacts"].as_array().unwrap() {
        let p = (
            c["pair"][0].as_u64().unwrap() as usize,
            c["pair"][1].as_u64().unwrap() as usize,
        );
        let e = out
            .entry(p)
            .or_insert((0.0, Vector3::zeros(), Vector3::zeros()));
        e.0 += c["impulse"].as_f64().unwrap();
        e.1 += vector3(&c["friction_impulse"]);
        e.2 = vector3(&c["normal"]);
    }
    out
}

/// The checks every cluster trace passes: the header names each pair of the report (every
/// column of its group) and each ball; the rows' times rise; the last row's cumulative
/// impulses are the report's per pair; where a pair is apart (compression <= 0) or not in
/// contact (no slip), its forces are zero.
fn check_trace(t: &Trace, j: &Value) {
    let pairs = contacts_by_pair(j);
    assert!(!pairs.is_empty());
    for &p in pairs.keys() {
        for what in [
            "compression (m)",
            "normal_force (N)",
            "normal_impulse (N s)",
            "friction_force (N)",
            "friction_impulse_x (N s)",
            "friction_impulse_y (N s)",
            "friction_impulse_z (N s)",
            "slip_speed (m/s)",
            "stuck (-)",
            "heat (J)",
        ] {
            t.col(&format!("c{}_{}_{what}", p.0, p.1));
        }
    }
    let nb = j["balls"].as_array().unwrap().len();
    let groups = (t.header.len() - 1 - 6 * nb) / 10;
    assert_eq!(
        groups,
        pairs.len(),
        "a group per pair of the report, no more"
    );
    assert_eq!(t.header[0], "t (s)");
    t.col(&format!("b{}_spin_z (rad/s)", nb - 1));
    let times = t.times();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "times rise");
    assert_eq!(*times.last().unwrap(), j["time"].as_f64().unwrap());
    for (&p, &(impulse, friction, _)) in &pairs {
        let got = t.last(p, "normal_impulse (N s)");
        assert!(
            (got - impulse).abs() <= 1e-12 * impulse,
            "{p:?}: {got} vs {impulse}"
        );
        let fi = Vector3::new(
            t.last(p, "friction_impulse_x (N s)"),
            t.last(p, "friction_impulse_y (N s)"),
            t.last(p, "friction_impulse_z (N s)"),
        );
        assert!(
            (fi - friction).norm() <= 1e-12 * impulse,
            "{p:?}: {fi} vs {friction}"
        );
        let delta = t.pair(p, "compression (m)");
        let force = t.pair(p, "normal_force (N)");
        let friction = t.pair(p, "friction_force (N)");
        let slip = t.pair(p, "slip_speed (m/s)");
        let mut pressed = 0;
        for r in 0..t.rows.len() {
            let f = force[r].unwrap();
            assert!(f >= 0.0, "{p:?} row {r}: {f}");
            if delta[r].unwrap() <= 0.0 || slip[r].is_none() {
                assert_eq!(f, 0.0, "{p:?} row {r}: force where open");
                assert_eq!(friction[r], Some(0.0), "{p:?} row {r}: friction where open");
            }
            if f > 0.0 {
                pressed += 1;
            }
        }
        assert!(pressed > 2, "{p:?} presses in {pressed} rows");
    }
}

/// Each ball's momentum and spin change from the report (velocities and spins out) and the
/// scene (in) against the sums of the trace's impulses on it (normal along the report's
/// normal, on ball j; friction on ball i at r_i n, minus it on j at -r_j n): the largest
/// misfit over m |v_in| summed.
fn momentum_misfit(t: &Trace, j: &Value, v_in: &[Vector3<f64>]) -> (f64, f64) {
    let pairs = contacts_by_pair(j);
    let balls = j["balls"].as_array().unwrap();
    let mut dp = vec![Vector3::zeros(); balls.len()];
    let mut dl = vec![Vector3::zeros(); balls.len()];
    for (&(a, b), &(_, _, n)) in &pairs {
        let p = t.last((a, b), "normal_impulse (N s)");
        let fi = Vector3::new(
            t.last((a, b), "friction_impulse_x (N s)"),
            t.last((a, b), "friction_impulse_y (N s)"),
            t.last((a, b), "friction_impulse_z (N s)"),
        );
        dp[b] += n * p - fi;
        dp[a] += -n * p + fi;
        // Torques of the friction: r_i n x F on i, (-r_j n) x (-F) on j.
        dl[a] += (n * R).cross(&fi);
        dl[b] += (n * R).cross(&fi);
    }
    let scale: f64 = v_in.iter().map(|v| M * v.norm()).sum();
    let (mut worst_p, mut worst_l) = (0.0f64, 0.0f64);
    for (k, b) in balls.iter().enumerate() {
        let own = M * (vector3(&b["velocity"]) - v_in[k]);
        worst_p = worst_p.max((own - dp[k]).amax() / scale);
        let spin = INERTIA * vector3(&b["spin"]);
        worst_l = worst_l.max((spin - dl[k]).amax() / (scale * R));
    }
    (worst_p, worst_l)
}

/// The 3-ball cradle (equal balls, elastic Hertz, no friction): the trace's impulses against
/// the 1D Hertz chain integrated by RK4 here. Ball 2 is pushed by pair (1, 2) alone, so
/// p_12 = m v_2'; ball 0 by pair (0, 1) alone, so p_01 = m (1 - v_0'). The chain at
/// h = 0.5e-4 of the contact time is within 1e-11 m/s of the exact chain
/// (tests/cluster_scenes.rs), the kernel at rtol 1e-12 within 3.4e-11 m/s: 1e-10 m/s, 1.7e-11
/// N s, holds both.
#[test]
fn cradle_3_trace_impulses_match_the_hertz_chain() {
    let k = 4.0 / 3.0 * E / (2.0 * (1.0 - NU * NU)) * (R / 2.0).sqrt();
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let tau = 2.868 * ((M / 2.0).powi(2) / (R / 2.0 * e_star * e_star * 1.0)).powf(0.2);
    let chain = hertz_chain_rk4(k, M, &[1.0, 0.0, 0.0], 0.5e-4 * tau);
    let dir = fresh_dir("cluster_trace_cradle3");
    let csv = dir.join("t.csv");
    let path = scene("cluster_cradle_3.toml");
    let j = run_json(&[
        "run",
        &path,
        "--json",
        "--rtol",
        "1e-12",
        "--trace",
        csv.to_str().unwrap(),
    ]);
    let t = Trace::read(&csv);
    check_trace(&t, &j);
    let tol = 1e-10 * M;
    let p01 = t.last((0, 1), "normal_impulse (N s)");
    let p12 = t.last((1, 2), "normal_impulse (N s)");
    assert!(
        (p01 - M * (1.0 - chain[0])).abs() < tol,
        "{p01} vs {chain:?}"
    );
    assert!((p12 - M * chain[2]).abs() < tol, "{p12} vs {chain:?}");
    // The balls touch and close at the start: the first row is at t = 0, nothing pressed.
    assert_eq!(t.rows[0][0], Some(0.0));
    assert_eq!(t.pair((0, 1), "normal_impulse (N s)")[0], Some(0.0));
    let v_in = [Vector3::x(), Vector3::zeros(), Vector3::zeros()];
    let (p, l) = momentum_misfit(&t, &j, &v_in);
    assert!(p < 1e-12 && l < 1e-12, "momentum {p:e}, spin {l:e}");
    // Without friction: no friction force, no stuck contact, no spin.
    for pair in [(0, 1), (1, 2)] {
        assert!(t
            .pair(pair, "friction_force (N)")
            .iter()
            .all(|f| *f == Some(0.0)));
        assert!(t.pair(pair, "stuck (-)").iter().all(|f| *f == Some(0.0)));
    }
}

/// The nine-ball break (mu = 0.06, damped Hertz): every ball's momentum and spin change
/// from the report, against the trace's impulses; with `--samples 400`, 401 rows evenly
/// spaced from the cue ball's touch to the run's end, the cue ball's touch at
/// 0.2 m / 8 m/s = 0.025 s (it starts 0.25715 m behind the head ball's centre, 2 r =
/// 0.05715 m apart when touching).
#[test]
fn nine_ball_break_trace_balances_each_ball() {
    let dir = fresh_dir("cluster_trace_break");
    let path = scene("break_nine_ball.toml");
    let steps = dir.join("steps.csv");
    let j = run_json(&["run", &path, "--json", "--trace", steps.to_str().unwrap()]);
    let t = Trace::read(&steps);
    check_trace(&t, &j);
    assert_eq!(
        t.rows.len() as u64,
        j["steps"].as_u64().unwrap() + 1,
        "a row at the start and one per accepted step"
    );
    let mut v_in = vec![Vector3::zeros(); 10];
    v_in[0] = Vector3::new(8.0, 0.0, 0.0);
    let (p, l) = momentum_misfit(&t, &j, &v_in);
    assert!(p < 1e-12 && l < 1e-12, "momentum {p:e}, spin {l:e}");
    // Friction acted, and some contact stuck.
    assert!(t.last((1, 2), "friction_force (N)") == 0.0);
    assert!(t
        .pair((1, 2), "friction_force (N)")
        .iter()
        .any(|f| f.unwrap() > 10.0));
    let stuck: usize = contacts_by_pair(&j)
        .keys()
        .map(|&p| {
            t.pair(p, "stuck (-)")
                .iter()
                .filter(|s| **s == Some(1.0))
                .count()
        })
        .sum();
    assert!(stuck > 0);

    let sampled = dir.join("samples.csv");
    let j2 = run_json(&[
        "run",
        &path,
        "--json",
        "--trace",
        sampled.to_str().unwrap(),
        "--samples",
        "400",
    ]);
    assert_eq!(j2, j, "a trace changes nothing in the report");
    let s = Trace::read(&sampled);
    check_trace(&s, &j);
    let times = s.times();
    assert_eq!(times.len(), 401);
    let (t0, t1) = (0.2 / 8.0, j["time"].as_f64().unwrap());
    for (i, t) in times.iter().enumerate() {
        let want = t0 + (t1 - t0) * i as f64 / 400.0;
        assert!((t - want).abs() < 1e-12 * t1, "row {i}: {t} vs {want}");
    }
    // Nothing presses at the cue ball's touch; the cue ball still has its 8 m/s.
    let f01 = s.pair((0, 1), "normal_force (N)");
    assert_eq!(f01[0], Some(0.0));
    assert_eq!(s.rows[0][s.col("b0_v_x (m/s)")], Some(8.0));
    let (p, l) = momentum_misfit(&s, &j, &v_in);
    assert!(p < 1e-12 && l < 1e-12, "momentum {p:e}, spin {l:e}");
}

/// Hertz's closed form for two equal balls head on (elastic, k): the largest compression
/// delta_m = (5 m* v^2 / (4 k))^(2/5), m* = m / 2, and the peak force k delta_m^(3/2); the
/// force is symmetric in time about the peak (the elastic impact runs backwards the same).
/// Sampled at 2000 intervals of the contact time T by the kernel's continuous extension:
/// the sample nearest the peak is within T / 4000 of it, where the force (near a half sine
/// of period 2T) is below the peak by (pi / 4000)^2 / 2 = 3e-7 of it, so 1e-6 holds; no
/// sample is above it.
#[test]
fn sampled_two_ball_trace_meets_hertz_peak_force() {
    let k = 4.5e8;
    let ball = Ball::new(M, R, 0.4).unwrap();
    let at = |x: f64, v: f64| ClusterBall {
        ball,
        position: Vector3::new(x, 0.0, 0.0),
        velocity: Vector3::new(v, 0.0, 0.0),
        spin: Vector3::zeros(),
    };
    let cluster = Cluster::new(
        vec![at(-R, 1.0), at(R, 0.0)],
        ClusterLaw::Same(ContactLaw::elastic(k).unwrap()),
        0.0,
    )
    .unwrap();
    let settings = ClusterSettings {
        rtol: 1e-12,
        stick: true,
    };
    let plain = resolve_cluster(&cluster, &settings).unwrap();
    let n = 2000;
    let times: Vec<f64> = (0..=n).map(|i| plain.time * i as f64 / n as f64).collect();
    let mut rows: Vec<(f64, f64, f64)> = Vec::new();
    let mut sink = |r: &ClusterTraceRow<'_>| {
        let f = r.contacts.iter().map(|c| c.normal_force).sum();
        let p = r.contacts.iter().map(|c| c.normal_impulse).sum();
        rows.push((r.t, f, p));
    };
    let trace = ClusterTrace {
        sampling: ClusterSampling::Times(&times),
        sink: &mut sink,
    };
    let traced = resolve_cluster_traced(&cluster, &settings, trace).unwrap();
    assert_eq!(traced, plain, "a trace changes nothing");
    assert_eq!(rows.len(), n + 1);
    for (r, t) in rows.iter().zip(&times) {
        assert_eq!(r.0, *t);
    }
    let m_star = M / 2.0;
    let delta_m = (5.0 * m_star / (4.0 * k)).powf(0.4);
    let peak = k * delta_m.powf(1.5);
    let top = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    assert!(top <= peak * (1.0 + 1e-9), "{top} vs {peak}");
    assert!(top >= peak * (1.0 - 1e-6), "{top} vs {peak}");
    // Symmetric in time: f(t) = f(T - t), T the contact's duration (the run's time).
    for i in 0..=n {
        let (a, b) = (rows[i].1, rows[n - i].1);
        assert!((a - b).abs() < 1e-7 * peak, "{i}: {a} vs {b}");
    }
    // The last sample, at the end, holds the whole impulse: m v = 0.17 N s (the balls swap
    // velocities).
    let last = rows[n].2;
    assert!((last - M).abs() < 1e-9 * M, "{last}");

    // One row at the start and one per accepted step, the last the contact's record.
    let mut steps: Vec<(f64, f64)> = Vec::new();
    let mut sink = |r: &ClusterTraceRow<'_>| {
        steps.push((r.t, r.contacts.iter().map(|c| c.normal_impulse).sum()));
    };
    let trace = ClusterTrace {
        sampling: ClusterSampling::Steps,
        sink: &mut sink,
    };
    let again = resolve_cluster_traced(&cluster, &settings, trace).unwrap();
    assert_eq!(again, plain);
    assert_eq!(steps.len() as u64, plain.stats.steps + 1);
    assert_eq!(steps[0], (0.0, 0.0));
    assert_eq!(steps.last().unwrap().1, plain.contacts[0].normal_impulse);
}

/// `--plot-trace` and `--plot` write the figures (SVG naming the pairs and the balls, PNG),
/// with or without `--trace`; `--samples` needs a trace; a figure's name must end in .svg or
/// .png; the two-ball stepping's options are still refused.
#[test]
fn figures_are_written_and_options_checked() {
    let dir = fresh_dir("cluster_trace_figures");
    let path = scene("cluster_cradle_5.toml");
    let f = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let out = bin(&[
        "run",
        &path,
        "--plot-trace",
        &f("t.svg"),
        "--plot",
        &f("top.svg"),
        "--samples",
        "50",
    ]);
    succeeded(&out);
    let svg = std::fs::read_to_string(f("t.svg")).unwrap();
    for pair in ["0-1", "1-2", "2-3", "3-4", "normal force of each contact"] {
        assert!(svg.contains(pair), "{pair} missing in the trace figure");
    }
    let top = std::fs::read_to_string(f("top.svg")).unwrap();
    assert!(top.contains("top view") && top.contains("m/s"));
    let out = bin(&[
        "run",
        &path,
        "--plot-trace",
        &f("t.png"),
        "--plot",
        &f("top.png"),
    ]);
    succeeded(&out);
    for name in ["t.png", "top.png"] {
        let bytes = std::fs::read(f(name)).unwrap();
        assert!(bytes.starts_with(b"\x89PNG"), "{name}");
    }
    refused(
        &bin(&["run", &path, "--samples", "10"]),
        &["--samples = 10", "--trace"],
    );
    refused(
        &bin(&["run", &path, "--plot", &f("top.pdf")]),
        &["--plot", ".svg or .png"],
    );
    refused(
        &bin(&["run", &path, "--trace", &f("x.csv"), "--samples", "0"]),
        &["--samples = 0", "at least 1"],
    );
    refused(
        &bin(&["run", &path, "--method", "rk4"]),
        &["--method", "cluster"],
    );
    // A refused run leaves no trace file behind.
    assert!(!dir.join("x.csv").exists());
}

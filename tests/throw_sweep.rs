//! The `sweep` command's CSV against published throw formulas (docs/throw.md), over the
//! whole grid of Alciatore's chart: cuts 0..60 degrees by 1, speeds 0.447, 1.341 and
//! 3.129 m/s, mu(S) = 9.951e-3 + 0.108 exp(-1.088 S), e = 1, solid balls (alpha = 2/5).
//!
//! Expected values come from the paper's closed form worked by hand for these shots (the
//! derivations are next to each test), never from the code under test.

use crate::cli_common;
use std::path::{Path, PathBuf};

const A: f64 = 9.951e-3;
const B: f64 = 0.108;
const C: f64 = 1.088;
const SPEEDS: [f64; 3] = [0.447, 1.341, 3.129];

fn mu(s: f64) -> f64 {
    A + B * (-C * s).exp()
}

/// A scene with Alciatore's friction constants evaluated as `evaluate` says; the incoming
/// state is replaced by each shot's.
fn scene(dir: &Path, evaluate: &str) -> PathBuf {
    let path = dir.join(format!("alciatore-{evaluate}.toml"));
    std::fs::write(
        &path,
        format!(
            "name = \"Alciatore's constants\"\n\
             [balls]\nmass = 0.17\nradius = 0.028575\nalpha = 0.4\n\
             [contact]\nmu = {{ model = \"speed-dependent\", a = {A}, b = {B}, c = {C}, \
             evaluate = \"{evaluate}\" }}\nrestitution = 1.0\n\
             [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
             [incoming.cm]\nu = [1.0, 0.0, 0.0]\n"
        ),
    )
    .unwrap();
    path
}

/// One CSV row: the named columns as text.
struct Row(Vec<String>);

impl Row {
    fn num(&self, header: &[String], name: &str) -> f64 {
        let i = header.iter().position(|h| h == name).unwrap();
        self.0[i].parse().unwrap()
    }
}

/// Runs `sweep` with the closed form over the chart's grid for `spin` and reads its CSV.
fn sweep(evaluate: &str, spin: &str, method: &str) -> (Vec<String>, Vec<Row>) {
    // One directory per call: tests run in parallel and may sweep the same grid.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "bc-throw-{}-{call}-{evaluate}-{spin}-{method}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let out = cli_common::command()
        .arg("sweep")
        .arg(scene(&dir, evaluate))
        .args([
            "--cut",
            "0:60:1",
            "--speed",
            "0.447,1.341,3.129",
            "--spin",
            spin,
        ])
        .args(["--method", method, "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    cli_common::succeeded(&out);
    let mut reader = csv::Reader::from_path(dir.join("sweep.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Row> = reader
        .records()
        .map(|r| Row(r.unwrap().iter().map(String::from).collect()))
        .collect();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(rows.len(), 3 * 61);
    (header, rows)
}

/// The grid order: speed, then cut (one spin, one side).
fn shot(i: usize) -> (f64, f64) {
    (SPEEDS[i / 61], (i % 61) as f64)
}

/// Stun shot, mu held at its initial value, e = 1 (TP A-14's closed form).
///
/// Derivation from the paper's closed form: the cue ball (speed v, no spin) meets the
/// object ball at cut phi. In the centre-of-mass frame A has U(0) = v cos(phi) / 2 along
/// the line of centres and V = v sin(phi) / 2 across it, no spin, so the slip at the
/// contact is S(0) = 2 V = v sin(phi) = v_rel, the relative speed of the surfaces. With
/// e = 1, P = 2 m U(0) = m v cos(phi) (eq 52). With mu = mu(v_rel) constant, the
/// tangential impulse is J = mu P while sliding lasts and at most
/// J_stick = m S(0) / (2 (1 + 1/alpha)) = m v sin(phi) / 7 (alpha = 2/5; the stick rule,
/// docs/model.md#when-sliding-stops-during-contact). B leaves along P n + J t, so
///
///   tan(throw) = J / P = min(mu v cos(phi), v sin(phi) / 7) / (v cos(phi))
///              = min(mu(v_rel) v cos(phi) / v_rel, 1/7) v sin(phi) / (v cos(phi)),
///
/// TP A-14's formula.
#[test]
fn stun_throw_with_mu_held_is_tp_a14() {
    let (header, rows) = sweep("initial", "stun", "closed-form");
    let mut largest = 0.0f64;
    for (i, row) in rows.iter().enumerate() {
        let (v, cut) = shot(i);
        assert_eq!(
            (row.num(&header, "speed"), row.num(&header, "cut_deg")),
            (v, cut)
        );
        let phi = cut.to_radians();
        let v_rel = v * phi.sin();
        let want = if cut == 0.0 {
            0.0
        } else {
            let tan = (mu(v_rel) * v * phi.cos() / v_rel).min(1.0 / 7.0) * v * phi.sin()
                / (v * phi.cos());
            tan.atan().to_degrees()
        };
        let got = row.num(&header, "throw_deg");
        assert!(
            (got - want).abs() < 1e-10,
            "v = {v}, cut = {cut}: {got} vs {want}"
        );
        largest = largest.max(want);
    }
    // The chart's peak: about 5.3 degrees at the slow speed (the curves' kinks are where
    // sliding stops exactly at the end of the contact).
    assert!(largest > 5.0 && largest < 5.5, "{largest}");
}

/// Rolling (and drawn) cue ball, mu held, e = 1: the paper's special case (eqs 59-72).
///
/// A rolling ball's contact with the object ball slides at S(0) = |v_A| = v (the spin's
/// surface speed at the ball-ball contact is v cos(phi) vertically, the slip's vertical
/// part; its horizontal part is the tangential speed v_t = v sin(phi)), so
/// mu = mu(v) and the sliding direction has horizontal part v_t / |v_A|. Sliding does not
/// stop (p_stick / P = |v_A| / (7 mu v cos(phi)) >= 1 / (7 (a + b)) > 1), so J = mu P and
///
///   tan(throw) = mu v_t / |v_A| = mu(v) sin(phi).
///
/// Draw reverses the vertical slip only, so its throw is the same.
#[test]
fn rolling_and_drawn_throw_is_the_papers_special_case() {
    for spin in ["roll", "draw"] {
        let (header, rows) = sweep("initial", spin, "closed-form");
        for (i, row) in rows.iter().enumerate() {
            let (v, cut) = shot(i);
            let v_t = v * cut.to_radians().sin();
            let want = (mu(v) * v_t / v).atan().to_degrees();
            let got = row.num(&header, "throw_deg");
            assert!(
                (got - want).abs() < 1e-10,
                "{spin}, v = {v}, cut = {cut}: {got} vs {want}"
            );
            assert_eq!(
                row.0[header.iter().position(|h| h == "sticks").unwrap()],
                "false"
            );
        }
    }
}

/// G(S) = integral_0^S dS' / mu(S'), by composite Simpson (independent of the crate's
/// closed-form G).
fn slide_potential(s: f64) -> f64 {
    let n = 4000;
    let h = s / n as f64;
    let mut sum = 1.0 / mu(0.0) + 1.0 / mu(s);
    for i in 1..n {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } / mu(i as f64 * h);
    }
    sum * h / 3.0
}

/// Stun shot, mu(S) along the contact: dS/dp = -k mu(S) with k = 2 (1 + 1/alpha) / m =
/// 7 / m (eq 22), so G(S(p)) = G(S(0)) - k p (docs/model.md#speed-dependent-friction).
/// Sliding stops when G(S(0)) <= k P (then J = S(0) / k); otherwise S(P) solves
/// G(S) = G(S(0)) - k P (bisection here) and J = (S(0) - S(P)) / k. tan(throw) = J / P.
#[test]
fn stun_throw_along_the_contact_is_the_integral_closed_form() {
    let (header, rows) = sweep("along-contact", "stun", "closed-form");
    let (held_header, held) = sweep("initial", "stun", "closed-form");
    let m = 0.17;
    let k = 7.0 / m;
    let mut largest_gap = 0.0f64;
    for (i, row) in rows.iter().enumerate().filter(|(i, _)| i % 61 != 0) {
        let (v, cut) = shot(i);
        let phi = cut.to_radians();
        let (s0, p) = (v * phi.sin(), m * v * phi.cos());
        let g_end = slide_potential(s0) - k * p;
        let j = if g_end <= 0.0 {
            s0 / k
        } else {
            (s0 - crate::common::bisect(0.0, s0, |s| slide_potential(s) < g_end)) / k
        };
        let want = (j / p).atan().to_degrees();
        let got = row.num(&header, "throw_deg");
        assert!(
            (got - want).abs() < 1e-9,
            "v = {v}, cut = {cut}: {got} vs {want}"
        );
        // mu(S) rises as S falls, so integrating it gives at least the held throw.
        let held_throw = held[i].num(&held_header, "throw_deg");
        assert!(got >= held_throw - 1e-12, "v = {v}, cut = {cut}");
        largest_gap = largest_gap.max(got - held_throw);
    }
    assert!(largest_gap > 0.5, "{largest_gap}");
}

/// The integrators honour the held mu too: dop853 against the closed form's CSV.
#[test]
fn dop853_follows_the_held_mu() {
    let (header, exact) = sweep("initial", "roll", "closed-form");
    let (_, stepped) = sweep("initial", "roll", "dop853");
    for (e, s) in exact.iter().zip(&stepped) {
        let (a, b) = (e.num(&header, "throw_deg"), s.num(&header, "throw_deg"));
        assert!((a - b).abs() < 1e-7, "{a} vs {b}");
    }
}

/// Bad options: one line naming the option and what it accepts, exit code 2.
#[test]
fn bad_options_are_one_line_errors() {
    for (args, needle) in [
        (["--cut", "0:60:0"], "--cut"),
        (["--speed", "-1"], "--speed"),
        (["--spin", "masse"], "--spin"),
        (["--cut", "95"], "(-90, 90)"),
    ] {
        let out = cli_common::command()
            .arg("sweep")
            .args(args)
            .args(["--out", "/nonexistent-never-written"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{err}");
    }
}

//! A contact-law scene through the command line (docs/contact-law.md): the closed form's
//! trace marks the stop of sliding as the time-stepping methods' traces do, and the time
//! transform, which a law does not use, is said to have no effect (the run goes on, its
//! output unchanged), while the tolerances act on the closed form under a law (it
//! integrates the normal law with dop853 at them).

use crate::cli_common;
use cli_common::{bin, fresh_dir, json, scene, scene_path, warned};

/// The rows of a trace CSV: (t, p, S) and the header.
fn trace(path: &std::path::Path) -> (String, Vec<[f64; 3]>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let cols: Vec<&str> = header.split(',').collect();
    let at = |name: &str| cols.iter().position(|c| c.starts_with(name)).unwrap();
    let (t, p, s) = (at("t (s)"), at("p (N s)"), at("S (m/s)"));
    let rows = lines
        .map(|l| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect();
            [v[t], v[p], v[s]]
        })
        .collect();
    (header, rows)
}

/// An elastic Hertz law (`damping = "none"`) and a stun cut whose sliding stops at half the
/// impulse, so that the stop falls on the middle sample time of every even `--samples N`.
///
/// Independent derivation. Pool balls (m = 0.17 kg, alpha = 0.4, mu = 0.06), A at 1 m/s
/// along the line of centres and v_y across it, B at rest: in the centre-of-mass frame
/// U(0) = 0.5 m/s, V(0) = v_y / 2, S(0) = 2 V(0) = v_y (eqs 5-6). The undamped contact
/// m* delta'' = -k delta^(3/2) is reversible: delta(t) = delta(tau - t), so f(t) = f(tau - t)
/// and p(tau / 2) = P / 2, with P = 2 m U(0) = 0.17 N s (e = 1). Sliding stops at
/// p_stick = m S(0) / (2 mu (1 + 1/alpha)) (docs/model.md#when-sliding-stops-during-contact),
/// which is P / 2 = m U(0) when v_y = S(0) = 2 mu (1 + 1/alpha) U(0) = 0.21 m/s. Then
/// t_stick = tau / 2, and a trace with `--samples N` has the start, the sample times
/// k tau / N (k = 1..N, the last one the end of the contact) and the stop: N + 1 rows for
/// even N (the stop is the middle sample), N + 2 for odd N, no two closer than 1e-9 tau.
#[test]
fn a_stop_on_a_sample_time_is_one_row() {
    let d = fresh_dir("cli_contact_law_stop_on_sample");
    let file = d.join("elastic_half.toml");
    std::fs::write(
        &file,
        r#"name = "elastic Hertz law, sliding stops at half the impulse"
[balls]
mass = 0.17
radius = 0.028575
alpha = 0.4
youngs_modulus = 5.4e9
poisson_ratio = 0.34
[contact]
mu = 0.06
[contact.law]
model = "hertz"
damping = "none"
[incoming.lab]
a = { position = [-0.028575, 0.0, 0.028575], velocity = [1.0, 0.21, 0.0], spin = [0.0, 0.0, 0.0] }
b = { position = [0.028575, 0.0, 0.028575], velocity = [0.0, 0.0, 0.0], spin = [0.0, 0.0, 0.0] }
"#,
    )
    .unwrap();
    let (p_total, p_stick): (f64, f64) = (2.0 * 0.17 * 0.5, 0.17 * 0.21 / (2.0 * 0.06 * 3.5));
    assert!((p_stick - 0.5 * p_total).abs() < 1e-15);
    for method in ["closed-form", "rk4", "dopri5", "dop853"] {
        for n in [2usize, 3, 4, 7, 10] {
            let csv = d.join(format!("{method}.{n}.csv"));
            let samples = n.to_string();
            let j = json(&[
                "run",
                file.to_str().unwrap(),
                "--method",
                method,
                "--json",
                "--trace",
                csv.to_str().unwrap(),
                "--samples",
                &samples,
            ]);
            let what = format!("{method} --samples {n}");
            let (tau, t_stick) = (
                j["duration"].as_f64().unwrap(),
                j["stick_time"].as_f64().unwrap(),
            );
            // Measured: |t_stick / tau - 1/2| <= 1.0e-11 (the closed form; dop853 5.4e-12).
            assert!(
                (t_stick / tau - 0.5).abs() < 1e-10,
                "{what}: {t_stick} / {tau}"
            );
            let (_, rows) = trace(&csv);
            let want = if n % 2 == 0 { n + 1 } else { n + 2 };
            assert_eq!(rows.len(), want, "{what}: {rows:?}");
            assert!(
                rows.windows(2).all(|w| w[1][0] - w[0][0] > 1e-9 * tau),
                "{what}: {rows:?}"
            );
            stop_row(&rows, t_stick, p_stick, &what);
            assert!(
                (rows[want - 1][0] - tau).abs() < 1e-9 * tau,
                "{what}: {rows:?}"
            );
            println!("{what}: t_stick / tau - 1/2 = {:.1e}", t_stick / tau - 0.5);
        }
    }
}

/// The trace's stop of sliding: a row at the reported stick time with S = 0 and p = p_stick,
/// S > 0 before it and 0 after it.
fn stop_row(rows: &[[f64; 3]], t_stick: f64, p_stick: f64, what: &str) {
    let k = rows
        .iter()
        .position(|r| r[0] == t_stick)
        .unwrap_or_else(|| panic!("{what}: no row at {t_stick}: {rows:?}"));
    assert_eq!(rows[k][2], 0.0, "{what}: {:?}", rows[k]);
    assert!(
        (rows[k][1] - p_stick).abs() < 1e-9 * p_stick,
        "{what}: {:?}",
        rows[k]
    );
    assert!(rows[..k].iter().all(|r| r[2] > 0.0), "{what}: {rows:?}");
    assert!(rows[k..].iter().all(|r| r[2] == 0.0), "{what}: {rows:?}");
}

/// The Hunt-Crossley stun cut at 10 degrees (data/scenes/hertz_law_hunt_crossley.toml):
/// S(0) = 1 m/s tan(10 deg) = 0.17633 m/s, and sliding stops at
/// p_stick = m S(0) / (2 mu (1 + 1/alpha)) = 0.17 * 0.17633 / (0.12 * 3.5) = 0.071370 N s
/// (eq 35 for identical balls), before the impulse (1 + e) m U(0) = 0.16575 N s is complete.
/// Every method's trace has a row at the reported stick time with S = 0 and p = p_stick,
/// and S > 0 before it; the closed form's stop agrees with dop853's.
#[test]
fn every_method_marks_the_stop_of_sliding() {
    let d = fresh_dir("cli_contact_law_stop_row");
    let s = scene("hertz_law_hunt_crossley.toml");
    let p_stick = 0.17 * (10f64.to_radians().tan()) / (2.0 * 0.06 * 3.5);
    let mut stops = Vec::new();
    for method in ["closed-form", "rk4", "dopri5", "dop853"] {
        for samples in [None, Some("10")] {
            let file = d.join(format!("{method}.{}.csv", samples.unwrap_or("steps")));
            let f = file.to_str().unwrap();
            let mut args = vec![
                "run",
                s.as_str(),
                "--method",
                method,
                "--json",
                "--trace",
                f,
            ];
            if let Some(n) = samples {
                args.extend(["--samples", n]);
            }
            let j = json(&args);
            let t_stick = j["stick_time"].as_f64().unwrap();
            let p = j["stick_impulse"].as_f64().unwrap();
            assert!(
                (p - p_stick).abs() < 1e-9 * p_stick,
                "{method}: {p} vs {p_stick}"
            );
            let (header, rows) = trace(&file);
            assert!(header.ends_with("delta (m)"), "{header}");
            stop_row(&rows, t_stick, p_stick, &format!("{method} {samples:?}"));
            // No two rows at one time, times increasing. The closed form samples the
            // realised contact time: with --samples 10, the start, 10 sample times (the last
            // is the end, to round-off: one row) and the stop row.
            let contact = j["duration"].as_f64().unwrap();
            assert!(
                rows.windows(2).all(|w| w[1][0] - w[0][0] > 1e-9 * contact),
                "{method} {samples:?}: {rows:?}"
            );
            if method == "closed-form" && samples.is_some() {
                assert_eq!(rows.len(), 12, "{rows:?}");
            }
            stops.push((method, t_stick));
        }
    }
    let dop853 = stops.iter().find(|s| s.0 == "dop853").unwrap().1;
    for (method, t) in &stops {
        // The default tolerances (rtol 1e-10; rk4 1000 steps): within 1e-8 of the contact.
        assert!(
            (t - dop853).abs() < 1e-8 * 4e-4,
            "{method}: {t} vs {dop853}"
        );
    }
}

/// `--time-transform` with a law scene warns and changes nothing; with a profile scene it
/// acts silently.
#[test]
fn the_time_transform_is_said_to_have_no_effect_under_a_law() {
    let s = scene("hertz_law_kuwabara_kono.toml");
    let with = bin(&["run", &s, "--time-transform", "false", "--json"]);
    warned(
        &with,
        &["--time-transform has no effect with a contact law"],
    );
    let without = bin(&["run", &s, "--json"]);
    assert!(
        without.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&without.stderr)
    );
    assert_eq!(with.stdout, without.stdout);
    let profile = bin(&["run", "--time-transform", "false", "--method", "dop853"]);
    assert!(profile.status.success() && profile.stderr.is_empty());
    // batch: the same rule.
    let d = fresh_dir("cli_contact_law_batch_transform");
    let input = d.join("in.csv");
    std::fs::write(&input, "u_x,u_y,u_z\n1,0.5,0\n").unwrap();
    let out = d.join("out.csv");
    warned(
        &bin(&[
            "batch",
            input.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--scene",
            &s,
            "--method",
            "dop853",
            "--time-transform",
            "false",
        ]),
        &["--time-transform has no effect with a contact law"],
    );
}

/// A scene's own `[solver] time_transform` under a law warns too (on loading the scene,
/// whatever the method), and the report is the one without it; a profile scene's does not.
#[test]
fn a_scene_time_transform_under_a_law_warns() {
    let d = fresh_dir("cli_contact_law_scene_transform");
    let law = std::fs::read_to_string(scene_path("hertz_law_kuwabara_kono.toml")).unwrap();
    assert!(
        !law.contains("[solver]"),
        "the shipped scene has no [solver] section"
    );
    let with_key = d.join("law_transform.toml");
    std::fs::write(
        &with_key,
        format!("{law}\n[solver]\ntime_transform = false\n"),
    )
    .unwrap();
    let with_key = with_key.to_string_lossy().into_owned();
    let plain = scene("hertz_law_kuwabara_kono.toml");
    for method in ["closed-form", "dop853"] {
        let with = bin(&["run", &with_key, "--method", method, "--json"]);
        warned(
            &with,
            &["[solver] time_transform has no effect with", "warning: "],
        );
        let without = bin(&["run", &plain, "--method", method, "--json"]);
        assert_eq!(with.stdout, without.stdout, "{method}");
    }
    let profile = d.join("profile_transform.toml");
    let default = std::fs::read_to_string(scene_path("default.toml")).unwrap();
    assert!(!default.contains("[solver]"));
    std::fs::write(
        &profile,
        format!("{default}\n[solver]\ntime_transform = false\n"),
    )
    .unwrap();
    let out = bin(&["run", &profile.to_string_lossy(), "--method", "dop853"]);
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Under a law the closed form integrates the normal law with dop853 at --rtol: no warning,
/// and the realised impulse moves with the tolerance (by more than round-off at 1e-4).
#[test]
fn the_tolerances_act_on_the_closed_form_under_a_law() {
    let s = scene("hertz_law_kuwabara_kono.toml");
    let run = |rtol: &str| {
        let out = bin(&[
            "run",
            &s,
            "--method",
            "closed-form",
            "--rtol",
            rtol,
            "--json",
        ]);
        assert!(
            out.status.success() && out.stderr.is_empty(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        j["impulse"].as_f64().unwrap()
    };
    let (loose, tight) = (run("1e-4"), run("1e-12"));
    assert!((loose - tight).abs() > 1e-12 * tight, "{loose} {tight}");
    assert!((loose - tight).abs() < 1e-3 * tight, "{loose} {tight}");
}

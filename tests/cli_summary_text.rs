//! The summary (`run` without `--json`) reads as physics for people: a heat within the
//! run's round-off of zero is 0 (the checks line keeps the size of the round-off), S(0) = 0
//! says there was no sliding, the table summary agrees with the ball path CSV, numbers
//! carry SI prefixes or plain decimals without `e0`, and counts have their plural right.

use crate::cli_common;
use cli_common::scene;
use std::path::Path;
use std::process::Output;

/// Runs the binary with `args`; the run must succeed.
fn bin(args: &[&str]) -> Output {
    let out = cli_common::bin(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn text(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).unwrap()
}

/// The summary line starting with `key` (after its indent).
fn line<'a>(summary: &'a str, key: &str) -> &'a str {
    summary
        .lines()
        .map(str::trim_start)
        .find(|l| l.starts_with(key))
        .unwrap_or_else(|| panic!("no line `{key}` in:\n{summary}"))
}

/// Head-on stun (S(0) = 0, e = 1, no spin): no sliding and no heat (eq 50: H = H_sfr +
/// P (2 U(0) - P/m) = 0 + 2 m U (2 U - 2 U) = 0). dop853's H from the kinetic energies is a
/// round-off of about -1.6e-12 J: the summary prints 0 J, the JSON keeps the computed value
/// and the checks line its size.
#[test]
fn no_sliding_and_no_heat_in_a_head_on_stun() {
    for method in ["closed-form", "dop853", "rk4"] {
        let s = text(&bin(&[
            "run",
            &scene("head_on_stun.toml"),
            "--method",
            method,
        ]));
        assert_eq!(
            line(&s, "heat H"),
            "heat H            0 J (sliding 0 J)",
            "{method}"
        );
        assert_eq!(
            line(&s, "sliding"),
            "sliding           none: S(0) = 0, theta undefined; purely normal throughout"
        );
        assert!(!s.contains("sliding stops"), "{method}: {s}");
        assert!(line(&s, "checks").contains("energy balance"), "{s}");
    }
    let j: serde_json::Value =
        serde_json::from_slice(&bin(&["run", &scene("head_on_stun.toml"), "--json"]).stdout)
            .unwrap();
    let heat = j["heat"].as_f64().unwrap();
    assert!(
        heat != 0.0 && heat.abs() < 1e-10,
        "the round-off is still reported: {heat}"
    );
}

/// The round-off is that of the balls' own energy scale: a 7 kg ball (r = 0.109 m, a
/// bowling ball) head-on at U(0) = 5 m/s with friction off and e = 1 has H = 0 by eq 50,
/// like the pool balls above, and the time-stepping methods' kinetic energies differ by
/// round-off of that larger scale (measured: rk4 -2.3e-11 J, dop853 -2.8e-9 J, dopri5
/// -7.4e-9 J, each within its energy balance error times m v_ref^2). The summary prints
/// 0 J; the JSON keeps the computed value.
#[test]
fn round_off_heat_of_heavy_balls_is_zero() {
    let dir = cli_common::fresh_dir("cli_summary_heavy");
    let path = dir.join("bowling.toml");
    std::fs::write(
        &path,
        "[balls]\nmass = 7.0\nradius = 0.109\n[contact]\nmu = 0.06\nrestitution = 1.0\n\
         [contact.profile]\nshape = \"half-sine\"\nduration = 1e-3\n\
         [incoming.cm]\nu = [5.0, 0.0, 0.0]\n[effects]\nfriction = false\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    for method in ["rk4", "dopri5", "dop853"] {
        let s = text(&bin(&["run", p, "--method", method]));
        assert_eq!(
            line(&s, "heat H"),
            "heat H            0 J (sliding 0 J)",
            "{method}"
        );
        let j: serde_json::Value =
            serde_json::from_slice(&bin(&["run", p, "--method", method, "--json"]).stdout).unwrap();
        let heat = j["heat"].as_f64().unwrap();
        assert!(heat != 0.0 && heat.abs() < 1e-7, "{method}: {heat}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A heat well above round-off is printed as it is. stun_cut_sticks.toml: e = 1, A at 2 m/s
/// and 10 degrees onto B at rest, so U(0) = cos 10 deg, S(0) = 2 V(0) = 2 sin 10 deg m/s, and
/// sliding stops at p_stick = m S(0) / (2 mu (1 + 1/alpha)) before P = 2 m U(0). Then
/// J = mu p_stick = m S(0) / 7 (alpha = 0.4), H_sfr = J S(0) - (1 + 1/alpha) J^2 / m =
/// m S(0)^2 / 14 (eq 49 with the stick rule), and H = H_sfr + P (2 U(0) - P / m) = H_sfr
/// (eq 50, e = 1): 1.46460778 mJ. The summary says where sliding stops.
#[test]
fn a_heat_above_round_off_is_printed() {
    let s0 = 0.34729635533386066_f64;
    let want = 0.17 * s0 * s0 / 14.0;
    let mj = |x: &str| match x.trim().strip_suffix(" mJ").map(str::parse::<f64>) {
        Some(Ok(v)) => v * 1e-3,
        _ => panic!("not a heat in mJ: `{x}`"),
    };
    for method in ["closed-form", "dop853", "rk4"] {
        let s = text(&bin(&[
            "run",
            &scene("stun_cut_sticks.toml"),
            "--method",
            method,
        ]));
        let l = line(&s, "heat H").trim_start_matches("heat H");
        let (h, sliding) = l.split_once(" (sliding ").unwrap();
        let (h, sliding) = (mj(h), mj(sliding.trim_end_matches(')')));
        // 10 digits printed (5e-13 J); H is a difference of kinetic energies of about
        // 0.34 J, whose round-off (2e-12 J here) the printed value keeps.
        assert!((h - want).abs() < 1e-11, "{method}: H = {h} vs {want}");
        assert!(
            (sliding - want).abs() < 1e-12,
            "{method}: H_sfr = {sliding} vs {want}"
        );
        // Where sliding stops: p_stick = m S(0) / (2 mu (1 + 1/alpha)) = 0.14057 N s, of
        // P = 2 m U(0) = 0.33484 N s; the half-sine's p(t) = P (1 - cos(pi t / tau)) / 2
        // gives t = tau / pi acos(1 - 2 p_stick / P) = 112.18 us. Both printed to 7 digits.
        let p_stick = 0.17 * s0 / (2.0 * 0.06 * (1.0 + 1.0 / 0.4));
        let big_p = 2.0 * 0.17 * 1.969615506024416 / 2.0;
        let t_stick = 2.5e-4 / std::f64::consts::PI * (1.0 - 2.0 * p_stick / big_p).acos();
        let l = line(&s, "sliding stops").trim_start_matches("sliding stops");
        let (t, p) = l
            .trim()
            .strip_prefix("at t = ")
            .and_then(|r| r.strip_suffix(" N s; then purely normal"))
            .and_then(|r| r.split_once(", p = "))
            .unwrap_or_else(|| panic!("{method}: `{l}`"));
        let t: f64 = t.strip_suffix(" µs").unwrap().parse::<f64>().unwrap() * 1e-6;
        let p: f64 = p.parse().unwrap();
        assert!(
            (t / t_stick - 1.0).abs() < 1e-6,
            "{method}: {t} vs {t_stick}"
        );
        assert!(
            (p / p_stick - 1.0).abs() < 1e-6,
            "{method}: {p} vs {p_stick}"
        );
    }
}

/// jump_follow: B leaves the contact moving into the cloth (v_z = -0.2277 m/s) on a cloth
/// of restitution 0.5; it bounces at once with v_z = 0.5 * 0.2277 m/s and rises
/// (0.5 v_z)^2 / (2 g) = 0.66 mm, as its path shows: the summary says it bounces, with the
/// path's height.
/// A leaves moving up and hops: the summary's hop time, height and landing time are those
/// of a ballistic flight.
#[test]
fn the_table_summary_agrees_with_the_path() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("summary_text_jump");
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("path.csv");
    let s = text(&bin(&[
        "run",
        &scene("jump_follow.toml"),
        "--path",
        csv.to_str().unwrap(),
        "--path-samples",
        "20000",
    ]));
    let j: serde_json::Value =
        serde_json::from_slice(&bin(&["run", &scene("jump_follow.toml"), "--json"]).stdout)
            .unwrap();
    let vz = j["lab_out"]["b"]["velocity"][2].as_f64().unwrap();
    assert!(vz < 0.0, "B is pushed into the cloth: {vz}");
    let rise = (0.5 * vz).powi(2) / (2.0 * 9.81);
    let b = line(&s, "B:");
    assert!(
        b.starts_with("B: pressed into the cloth at separation, bounces off it at t = 0, up to "),
        "{b}"
    );
    // A leaves moving up (v_z > 0): a ballistic hop of 2 v_z / g, v_z^2 / (2 g) high,
    // landing at the hop's end (v_z = 0.2277 m/s: 46.42 ms, 2.642 mm).
    let az = j["lab_out"]["a"]["velocity"][2].as_f64().unwrap();
    assert!(az > 0.0, "A moves up at separation: {az}");
    let a = line(&s, "A:");
    let nums: Vec<f64> = a
        .strip_prefix("A: hops ")
        .unwrap_or_else(|| panic!("{a}"))
        .split(", ")
        .map(|part| {
            let part = part.trim_start_matches("lands at t = ");
            part.split(' ').next().unwrap().parse().unwrap()
        })
        .collect();
    assert_eq!(a.matches(" ms").count(), 2, "{a}");
    assert!(a.contains(" mm high, lands at t = "), "{a}");
    let (hop, height) = (2.0 * az / 9.81, az * az / (2.0 * 9.81));
    for (got, want) in [
        (nums[0] * 1e-3, hop),
        (nums[1] * 1e-3, height),
        (nums[2] * 1e-3, hop),
    ] {
        assert!((got / want - 1.0).abs() < 1e-6, "{a}: {got} vs {want}");
    }
    let printed: f64 = b
        .rsplit("up to ")
        .next()
        .unwrap()
        .trim_end_matches(" µm high")
        .parse()
        .unwrap();
    assert!(
        (printed * 1e-6 - rise).abs() < 1e-10,
        "{printed} um vs {rise} m"
    );
    // The path: B's centre rises above r (0.028575 m) by that much at most, and by nearly
    // that much at its highest sample (20000 intervals over 1.65 s: 83 us apart).
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut rows = text.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let bz = header.iter().position(|h| *h == "b_z (m)").unwrap();
    let top = rows
        .map(|r| r.split(',').nth(bz).unwrap().parse::<f64>().unwrap() - 0.028575)
        .fold(f64::MIN, f64::max);
    assert!(
        top <= rise * (1.0 + 1e-9) && top > 0.99 * rise,
        "{top} vs {rise}"
    );
    // 7 bounces: plural; "bounce(s)" is gone.
    assert!(s.contains(", 7 bounces") && !s.contains("bounce(s)"), "{s}");
}

/// draw_table: A leaves moving into the cloth (v_z < 0 in the JSON) and the cloth's
/// restitution is 0, so the impact takes its normal velocity and it neither hops nor
/// bounces: "stays on the cloth (no hop)"; B leaves moving up and hops.
#[test]
fn a_ball_pressed_into_a_dead_cloth_stays_on_it() {
    let text_of = std::fs::read_to_string(scene("draw_table.toml")).unwrap();
    assert!(text_of.contains("[table]") && text_of.contains("restitution = 0.0\n"));
    let j: serde_json::Value =
        serde_json::from_slice(&bin(&["run", &scene("draw_table.toml"), "--json"]).stdout).unwrap();
    assert!(j["lab_out"]["a"]["velocity"][2].as_f64().unwrap() < 0.0);
    assert_eq!(j["table"]["restitution"].as_f64(), Some(0.0));
    let s = text(&bin(&["run", &scene("draw_table.toml")]));
    assert_eq!(line(&s, "A:"), "A: stays on the cloth (no hop)", "{s}");
    assert!(line(&s, "B:").starts_with("B: hops "), "{s}");
}

/// A contact law's line: its damping and coefficient as the scene gives them, and for the
/// elastic law (`damping = "none"`, stiffness k = 4.5e8 N/m^1.5, U(0) = 1 m/s, so an
/// approach speed v = 2 m/s and m* = m/2 = 0.085 kg) restitution 1 and the textbook
/// largest compression delta = (5 m* v^2 / (4 k))^(2/5) and peak force k delta^(3/2),
/// printed to five significant digits.
#[test]
fn the_contact_law_line() {
    let kk = text(&bin(&["run", &scene("hertz_law_kuwabara_kono.toml")]));
    assert!(
        line(&kk, "contact law").starts_with(
            "contact law hertz, damping kuwabara-kono (coefficient 2e-6 s): restitution 0."
        ),
        "{kk}"
    );
    let dir = cli_common::fresh_dir("summary_text_law");
    let file = dir.join("elastic.toml");
    let kk_text = std::fs::read_to_string(scene("hertz_law_kuwabara_kono.toml")).unwrap();
    let elastic = kk_text
        .replace("damping = \"kuwabara-kono\"", "damping = \"none\"")
        .replace("coefficient = 2e-6", "");
    assert_ne!(elastic, kk_text);
    std::fs::write(&file, elastic).unwrap();
    let s = text(&bin(&["run", file.to_str().unwrap()]));
    let l = line(&s, "contact law");
    let rest = l
        .strip_prefix("contact law hertz, damping none (coefficient 0 -): restitution ")
        .unwrap_or_else(|| panic!("{l}"));
    let parts: Vec<&str> = rest.split(", ").collect();
    let e: f64 = parts[0].parse().unwrap();
    assert!((e - 1.0).abs() <= 2e-9, "{l}");
    let (k, m_star, v) = (4.5e8_f64, 0.085_f64, 2.0_f64);
    let delta = (5.0 * m_star * v * v / (4.0 * k)).powf(0.4);
    let force = k * delta.powf(1.5);
    let number = |part: &str, key: &str, unit: &str, scale: f64| -> f64 {
        part.strip_prefix(key)
            .and_then(|p| p.strip_suffix(unit))
            .unwrap_or_else(|| panic!("{l}"))
            .parse::<f64>()
            .unwrap()
            * scale
    };
    let got_delta = number(parts[1], "compression ", " µm", 1e-6);
    let got_force = number(parts[2], "peak force ", " kN", 1e3);
    assert!(
        (got_delta / delta - 1.0).abs() < 5e-5,
        "{l}: delta = {delta}"
    );
    assert!((got_force / force - 1.0).abs() < 5e-5, "{l}: f = {force}");
}

/// No `e0` exponents ("1.561453e0 s", "2.0000e-4 s", "0.0e0") in any scene's summary; the
/// duration of a 2.5e-4 s pulse reads 250 µs.
#[test]
fn numbers_for_people() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        // A cushion scene has no closed form; a cluster scene ([[balls]]) takes no method.
        let scene = std::fs::read_to_string(&p).unwrap();
        let cushion = scene.contains("[cushion]");
        let methods: &[&str] = if scene.contains("[[balls]]") {
            &[""]
        } else if cushion {
            &["dop853"]
        } else {
            &["closed-form", "dop853"]
        };
        for &method in methods {
            let mut args = vec!["run", p.to_str().unwrap()];
            if !method.is_empty() {
                args.extend(["--method", method]);
            }
            let s = text(&bin(&args));
            for (k, _) in s.match_indices("e0") {
                let before = s[..k].chars().last().unwrap();
                assert!(!before.is_ascii_digit(), "{}: {s}", p.display());
            }
        }
    }
    let s = text(&bin(&["run", &scene("default.toml")]));
    assert!(line(&s, "profile").contains("over 250 µs"), "{s}");
}

/// "1 rows", "1 threads": a one-row batch on one thread says "1 row (1 collision, ...)" and
/// "1 thread".
#[test]
fn counts_in_words() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("summary_text_counts");
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("in.csv");
    std::fs::write(&input, "u_x,u_y,u_z\n1,0.2,0\n").unwrap();
    let out = bin(&[
        "batch",
        input.to_str().unwrap(),
        "--out",
        dir.join("out.csv").to_str().unwrap(),
        "--threads",
        "1",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("1 row (1 collision, "), "{err}");
    assert!(err.contains(", 1 thread, "), "{err}");
}

/// The trace's rows as docs/formats.md#trace-csv words them: without a stop of sliding, the
/// start and one row per accepted step; with one, the step that crossed it and the steps
/// that locate it count as accepted but have no row, the stop has one (stun_cut_sticks with
/// dop853: 10 accepted steps, 9 rows, the docs' example).
#[test]
fn trace_rows_as_documented() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("summary_text_trace");
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("t.csv");
    let rows_and_steps = |name: &str| {
        let out = bin(&[
            "run",
            &scene(name),
            "--json",
            "--trace",
            trace.to_str().unwrap(),
        ]);
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let rows = std::fs::read_to_string(&trace).unwrap().lines().count() - 1;
        let accepted = j["solver"]["accepted_steps"].as_u64().unwrap() as usize;
        (rows, accepted, j["stick_time"].as_f64())
    };
    let (rows, accepted, stop) = rows_and_steps("default.toml");
    assert_eq!((rows, stop), (accepted + 1, None));
    let (rows, accepted, stop) = rows_and_steps("stun_cut_sticks.toml");
    assert_eq!((rows, accepted), (9, 10));
    let stop = stop.unwrap();
    let text = std::fs::read_to_string(&trace).unwrap();
    assert!(
        text.lines()
            .skip(1)
            .any(|l| l.split(',').next().unwrap().parse::<f64>().unwrap() == stop),
        "a row at the stop, t = {stop}"
    );
}

/// A speed-dependent mu held at the initial slip (`evaluate = "initial"`) is named in the
/// summary and in the JSON's `friction` object with mu(S(0)). A stun cut with U(0) = 1 m/s
/// and V(0) = 0.25 m/s, no spin: S(0) = 2 V(0) = 0.5 m/s (eqs 5-6), so with Alciatore's
/// constants mu = 9.951e-3 + 0.108 exp(-1.088 * 0.5) = 0.0725769...; along the contact
/// (the default) there is no `friction` object and no such line.
#[test]
fn a_held_mu_is_named_with_its_value() {
    let dir = cli_common::fresh_dir("cli_summary_held_mu");
    let want = 9.951e-3 + 0.108 * (-1.088f64 * 0.5).exp();
    for evaluate in ["initial", "along-contact"] {
        let path = dir.join(format!("{evaluate}.toml"));
        std::fs::write(
            &path,
            format!(
                "[balls]\nmass = 0.17\nradius = 0.028575\n[contact]\n\
                 mu = {{ model = \"speed-dependent\", a = 9.951e-3, b = 0.108, c = 1.088, \
                 evaluate = \"{evaluate}\" }}\n\
                 [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
                 [incoming.cm]\nu = [1.0, 0.25, 0.0]\n"
            ),
        )
        .unwrap();
        let p = path.to_str().unwrap();
        let s = text(&bin(&["run", p]));
        let j: serde_json::Value =
            serde_json::from_slice(&bin(&["run", p, "--json"]).stdout).unwrap();
        if evaluate == "along-contact" {
            assert!(j.get("friction").is_none_or(|f| f.is_null()), "{j}");
            assert!(!s.contains("held through the contact"), "{s}");
            continue;
        }
        let f = &j["friction"];
        assert_eq!(f["model"], "speed-dependent");
        assert_eq!(f["evaluate"], "initial");
        let mu = f["mu"].as_f64().unwrap();
        assert!((mu - want).abs() <= 1e-15 * want, "{mu} vs {want}");
        assert_eq!(
            line(&s, "friction"),
            format!("friction          mu(S(0)) = {want:.6} held through the contact (evaluate = initial)")
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

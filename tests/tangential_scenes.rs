//! Scenes with `contact.tangential = "mindlin"` (docs/tangential.md#scenes): the scene runs
//! the compliant kernel on its own numbers (checked against the kernel called here with
//! inputs built by hand from the scene file's values), the rigid default leaves every
//! shipped scene's run unchanged, bad combinations are refused in one line naming the key,
//! and the command's trace carries the tangential columns (|F_t| <= mu f, the last row's
//! impulses and state equal to the JSON report's).

use crate::cli_common::{bin, fresh_dir, refused, scene, scene_path};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;
use std::path::Path;

/// The resin ball of both scenes (data/scenes/stun_cut_mindlin.toml, plane_resin_on_steel_mindlin.toml).
fn resin_ball() -> (Ball, Material) {
    (
        Ball::new(0.17, 0.028575, 0.4).unwrap(),
        Material::new(5.4e9, 0.34).unwrap(),
    )
}

/// stun_cut_mindlin.toml by hand: two resin balls, Hertz's stiffness of the pair with
/// Hunt-Crossley damping calibrated to e = 0.95 at 1 m/s on the reduced mass m/2, mu = 0.06;
/// ball A at (1, tan 10 deg, 0) m/s in the lab, B at rest, centres along +x. The kernel is
/// called in the lab frame (the scene calls it in the centre-of-mass frame: the relative
/// motion is the same, the numbers differ by round-off), and the lab velocities and spins
/// agree to 1e-12 of the speed.
#[test]
fn mindlin_pair_scene_is_the_kernel_with_the_scene_numbers() {
    let s = Scene::load(&scene_path("stun_cut_mindlin.toml")).unwrap();
    assert_eq!(s.tangential, TangentialLaw::Mindlin);
    let run = run_scene(&s, &s.solver, None).unwrap();
    let (ball, resin) = resin_ball();
    let k = HertzContact::of_pair(&BallPair::identical(ball), &resin, 0.5)
        .unwrap()
        .stiffness;
    let law = ContactLaw::calibrated(k, Damping::HuntCrossley, 0.95, 1.0, 0.085).unwrap();
    let sphere = |v: Vector3<f64>| CompliantSphere {
        ball,
        material: resin,
        velocity: v,
        spin: Vector3::zeros(),
    };
    let a = sphere(Vector3::new(1.0, 0.17632698070846498, 0.0));
    let b = sphere(Vector3::zeros());
    let settings = SolverSettings::default();
    let out = resolve_sphere_sphere_compliant_damped(
        &a,
        &b,
        (law.damping(), law.coefficient()),
        Vector3::x(),
        0.06,
        1.0,
        &settings,
    )
    .unwrap();
    let (la, lb) = run.lab_out.unwrap();
    let close = |x: Vector3<f64>, y: Vector3<f64>, scale: f64| (x - y).norm() < 1e-12 * scale;
    assert!(
        close(la.velocity, out.ball_a.velocity, 1.0),
        "{} {}",
        la.velocity,
        out.ball_a.velocity
    );
    assert!(close(lb.velocity, out.velocity_b, 1.0));
    let r = ball.radius();
    assert!(
        close(la.spin * r, out.ball_a.spin * r, 1.0),
        "{} {}",
        la.spin,
        out.ball_a.spin
    );
    assert!(close(lb.spin * r, out.spin_b * r, 1.0));
    let o = &run.outcome;
    assert!((o.result.impulse - out.ball_a.normal_impulse).abs() < 1e-12 * 0.17);
    let l = o.law.unwrap();
    assert_eq!(
        (l.law.damping(), l.law.coefficient()),
        (law.damping(), law.coefficient())
    );
    assert!((l.duration / out.ball_a.contact_time - 1.0).abs() < 1e-9);
    let c = run.compliant.as_ref().unwrap();
    assert!((c.outcome.tangential_work - out.ball_a.tangential_work).abs() < 1e-12);
    // The slip reverses here; the rigid stick rule keeps it at 0 (docs/tangential.md).
    assert!(c.slip_reversed() && o.result.s_out < 0.0);
}

/// plane_resin_on_steel_mindlin.toml by hand: the resin ball on a steel plane (normal +z),
/// Hertz's sphere-plane stiffness with Hunt-Crossley calibrated to e = 0.8 at 0.866 m/s on
/// the ball's mass, mu = 0.2, the incoming velocity and backspin of the file: the same call
/// as the scene's, so the ball's outgoing motion is the kernel's bit for bit.
#[test]
fn mindlin_plane_scene_is_the_kernel_with_the_scene_numbers() {
    let s = Scene::load(&scene_path("plane_resin_on_steel_mindlin.toml")).unwrap();
    let run = run_scene(&s, &s.solver, None).unwrap();
    let (ball, resin) = resin_ball();
    let steel = Material::new(2.0e11, 0.3).unwrap();
    let vn = 0.8660254037844386;
    let k = HertzContact::sphere_plane(&ball, &resin, Some(&steel), vn)
        .unwrap()
        .stiffness;
    let law = ContactLaw::calibrated(k, Damping::HuntCrossley, 0.8, vn, 0.17).unwrap();
    let out = resolve_sphere_plane_compliant_damped(
        &ball,
        resin,
        Some(steel),
        (law.damping(), law.coefficient()),
        0.2,
        Vector3::new(0.5, 0.0, -vn),
        Vector3::new(0.0, -20.0, 0.0),
        Vector3::z(),
        &SolverSettings::default(),
    )
    .unwrap();
    let p = run.plane_out.unwrap();
    assert_eq!((p.velocity, p.spin), (out.velocity, out.spin));
    // The rebound is the calibrated e (to the calibration and the stepping, 1e-8).
    assert!(
        (p.velocity.z / vn - 0.8).abs() < 1e-8,
        "{}",
        p.velocity.z / vn
    );
    let o = &run.outcome;
    assert!((o.result.impulse - out.normal_impulse).abs() < 1e-12);
    assert!((o.result.heat - (out.kinetic_energy_in - out.kinetic_energy_out)).abs() < 1e-12);
}

/// `tangential = "rigid"` written out is the default: every shipped scene of two balls or a
/// plane runs to the same outcome, bit for bit, and reports neither key of the compliant run.
#[test]
fn rigid_is_the_default_for_every_shipped_scene() {
    let mut seen = 0;
    for entry in std::fs::read_dir(scene_path("")).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        if is_cushion_scene(&text) || is_cluster_scene(&text) || text.contains("tangential") {
            continue;
        }
        let base = path.parent().unwrap();
        let plain = Scene::parse(&text, base, Some(&path)).unwrap();
        let rigid = text.replacen("[contact]\n", "[contact]\ntangential = \"rigid\"\n", 1);
        assert_ne!(rigid, text, "{}", path.display());
        let written = Scene::parse(&rigid, base, Some(&path)).unwrap();
        assert_eq!(written, plain, "{}", path.display());
        let (a, b) = (
            run_scene(&plain, &plain.solver, None).unwrap(),
            run_scene(&written, &written.solver, None).unwrap(),
        );
        assert_eq!(a, b, "{}", path.display());
        assert!(a.compliant.is_none());
        let json = Report::new(&plain, &a).to_json().unwrap();
        assert!(!json.contains("\"tangential\":") && !json.contains("\"compliant\""));
        seen += 1;
    }
    assert!(seen >= 15, "{seen} scenes");
}

/// The shipped scene's text with `from` replaced by `to` (which must occur), parsed.
fn edited(name: &str, edits: &[(&str, &str)]) -> Result<Scene, Error> {
    let mut text = std::fs::read_to_string(scene_path(name)).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    Scene::parse(&text, Path::new("."), None)
}

/// A shipped scene, the edits of its text and the pieces its refusal must contain.
type Refusal = (
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static [&'static str],
);

/// Mindlin's spring with what it cannot use is refused in one line naming contact.tangential
/// and what it needs; a misspelt name is refused with the names accepted.
#[test]
fn mindlin_refuses_what_it_cannot_use() {
    let cases: [Refusal; 5] = [
        (
            "plane_resin_on_steel.toml",
            &[("[contact]\n", "[contact]\ntangential = \"mindlin\"\n")],
            &[
                "contact.tangential = \"mindlin\" with [contact.profile]",
                "[contact.law]",
            ],
        ),
        (
            "stun_cut_mindlin.toml",
            &[
                ("youngs_modulus = 5.4e9", ""),
                ("poisson_ratio = 0.34", ""),
                ("model = \"hertz\"", "model = \"hertz\"\nstiffness = 4.5e8"),
            ],
            &[
                "contact.tangential = \"mindlin\" without the balls' material",
                "youngs_modulus",
            ],
        ),
        (
            "stun_cut_mindlin.toml",
            &[(
                "mu = 0.06",
                "mu = { model = \"speed-dependent\", a = 0.01, b = 0.1, c = 1 }",
            )],
            &[
                "contact.tangential",
                "speed-dependent",
                "a constant contact.mu",
            ],
        ),
        (
            "stun_cut_mindlin.toml",
            &[(
                "[incoming.lab]",
                "[effects]\nstick = false\n\n[incoming.lab]",
            )],
            &["contact.tangential", "stick = false", "the effect stick on"],
        ),
        (
            "stun_cut_mindlin.toml",
            &[("tangential = \"mindlin\"", "tangential = \"mindlen\"")],
            &[
                "contact.tangential = \"mindlen\"",
                "rigid, mindlin",
                "did you mean",
            ],
        ),
    ];
    for (name, edits, want) in cases {
        let e = edited(name, edits).unwrap_err().to_string();
        assert_eq!(e.lines().count(), 1, "{e}");
        for w in want {
            assert!(e.contains(w), "`{w}` missing in: {e}");
        }
    }
    // A law with its own stiffness and the material is the law's refusal, as without Mindlin.
    let e = edited(
        "stun_cut_mindlin.toml",
        &[("model = \"hertz\"", "model = \"hertz\"\nstiffness = 4.5e8")],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("contact.tangential") && e.contains("stiffness = 450000000"),
        "{e}"
    );
    // The command refuses --samples with a row per step of the kernel.
    let out = bin(&[
        "run",
        &scene("stun_cut_mindlin.toml"),
        "--trace",
        "/dev/null",
        "--samples",
        "5",
    ]);
    refused(&out, &["--samples", "contact.tangential = \"mindlin\""]);
}

/// The trace of `run --trace --json` on both scenes: the tangential columns follow the
/// compression (and the plane's ball columns); in every row |F_t| <= mu f to 1e-12 of the
/// cap (the kernel caps the spring's force at mu F_n exactly; rounding of the norm), the cap
/// column is mu f and the displacement is 0 only where the force is; the last row's impulse,
/// state and tangential work are the report's impulse, cm_out and heat_sliding, and its
/// F_t-integral is the report's tangential impulse to 1e-3 (the trapezoid rule on the
/// kernel's steps).
#[test]
fn mindlin_trace_has_the_tangential_columns() {
    let dir = fresh_dir("tangential_scenes_trace");
    for (name, mu) in [
        ("stun_cut_mindlin.toml", 0.06),
        ("plane_resin_on_steel_mindlin.toml", 0.2),
    ] {
        let csv_path = dir.join(format!("{name}.csv"));
        let out = bin(&[
            "run",
            &scene(name),
            "--json",
            "--trace",
            csv_path.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["tangential"], "mindlin");
        assert_eq!(json["compliant"]["mu"], mu);
        let mut r = csv::Reader::from_path(&csv_path).unwrap();
        let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
        let tail: Vec<&str> = header[header.len() - 5..]
            .iter()
            .map(String::as_str)
            .collect();
        assert_eq!(
            tail,
            ["F_t_y (N)", "F_t_z (N)", "mu f (N)", "xi_y (m)", "xi_z (m)"]
        );
        assert_eq!(header[15], "delta (m)");
        let col = |h: &str| header.iter().position(|x| x == h).unwrap();
        let rows: Vec<Vec<f64>> = r
            .records()
            .map(|rec| {
                rec.unwrap()
                    .iter()
                    .map(|c| c.parse().unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        assert!(rows.len() > 100);
        let (f, fy, fz, cap) = (
            col("f (N)"),
            col("F_t_y (N)"),
            col("F_t_z (N)"),
            col("mu f (N)"),
        );
        let mut j = [0.0; 2];
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row[cap], mu * row[f], "row {k}");
            let ft = row[fy].hypot(row[fz]);
            assert!(
                ft <= row[cap] * (1.0 + 1e-12),
                "{name} row {k}: {ft} > {}",
                row[cap]
            );
            if k > 0 {
                let dt = row[0] - rows[k - 1][0];
                j[0] += 0.5 * dt * (row[fy] + rows[k - 1][fy]);
                j[1] += 0.5 * dt * (row[fz] + rows[k - 1][fz]);
            }
        }
        let last = rows.last().unwrap();
        let num = |v: &serde_json::Value| v.as_f64().unwrap();
        assert_eq!(last[col("p (N s)")], num(&json["impulse"]), "{name}");
        assert_eq!(last[col("H_sfr (J)")], num(&json["heat_sliding"]), "{name}");
        for (i, h) in ["U (m/s)", "V (m/s)", "W (m/s)"].iter().enumerate() {
            assert_eq!(last[col(h)], num(&json["cm_out"]["u"][i]), "{name} {h}");
        }
        let jt = &json["compliant"]["tangential_impulse"];
        let scale = num(&json["tangential_impulse"]).abs();
        assert!(
            (j[0] - num(&jt[1])).abs() < 1e-3 * scale,
            "{name}: {} {}",
            j[0],
            jt[1]
        );
        assert!((j[1] - num(&jt[2])).abs() < 1e-3 * scale, "{name}");
        // A in the paper's frame: the tangential impulse along -e0 is the report's J.
        assert!(
            (num(&jt[1]) + num(&json["tangential_impulse"])).abs() < 1e-12,
            "{name}"
        );
    }
}

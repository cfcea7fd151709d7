//! The plane scenes of `data/scenes/` as a user runs them: every method's JSON against the
//! sphere-plane closed form computed here from the scene's numbers (docs/plane.md: slip
//! u = v_t - r (w x n), J = min(mu P, m |u| / (1 + 1/alpha)), P = (1 + e) m |v.n|), the
//! trace's ball columns, and the figure.

use crate::cli_common;
use cli_common::json_contract::vector3;
use cli_common::{bin, fresh_dir, json, refused, scene};
use nalgebra::Vector3;

/// The closed form of a solid ball (m = 0.17 kg, r = 0.028575 m, alpha = 0.4) against the
/// plane of unit normal n, written out here from the ball's equations.
fn expected(
    n: Vector3<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
    mu: f64,
    e: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let (m, r, alpha) = (0.17, 0.028575, 0.4);
    let p = (1.0 + e) * m * -v.dot(&n);
    let u = v - n * v.dot(&n) - r * w.cross(&n);
    let j = (mu * p).min(m * u.norm() / (1.0 + 1.0 / alpha));
    let t = u / u.norm();
    (
        v + (n * p - t * j) / m,
        w + n.cross(&t) * (r * j / (alpha * m * r * r)),
    )
}

/// Both plane scenes, every method: the ball's outgoing velocity and spin within 1e-9 of
/// the closed form (over |v| and |v|/r), and the stick flag as the closed form says.
#[test]
fn plane_scenes_agree_with_the_closed_form() {
    let cases = [
        // name, n, v, w, mu, e, sticks
        (
            "plane_resin_on_steel",
            Vector3::z(),
            Vector3::new(0.5, 0.0, -0.8660254037844386),
            Vector3::new(0.0, -20.0, 0.0),
            0.2,
            0.8,
            true,
        ),
        (
            "plane_wall_side_spin",
            -Vector3::x(),
            Vector3::new(std::f64::consts::SQRT_2, std::f64::consts::SQRT_2, 0.0),
            Vector3::new(0.0, 0.0, 60.0),
            0.1,
            0.8,
            false,
        ),
    ];
    for (name, n, v, w, mu, e, sticks) in cases {
        let (ve, we) = expected(n, v, w, mu, e);
        for method in ["closed-form", "rk4", "dopri5", "dop853"] {
            let j = json(&[
                "run",
                &scene(&format!("{name}.toml")),
                "--method",
                method,
                "--rtol",
                "1e-12",
                "--json",
            ]);
            let out = &j["plane"]["ball_out"];
            let dv = (vector3(&out["velocity"]) - ve).amax() / v.norm();
            let dw = (vector3(&out["spin"]) - we).amax() * 0.028575 / v.norm();
            assert!(dv < 1e-9 && dw < 1e-9, "{name} {method}: {dv:e} {dw:e}");
            assert_eq!(j["sticks"].as_bool(), Some(sticks), "{name} {method}");
            assert_eq!(vector3(&j["plane"]["normal"]), n);
        }
    }
}

/// The trace of a plane scene ends with the ball's outgoing state in its own columns, and
/// starts with the incoming one; the figure is written.
#[test]
fn a_plane_trace_carries_the_ball() {
    let dir = fresh_dir("plane-trace");
    let (csv, png) = (dir.join("t.csv"), dir.join("t.png"));
    let j = json(&[
        "run",
        &scene("plane_resin_on_steel.toml"),
        "--trace",
        csv.to_str().unwrap(),
        "--plot-trace",
        png.to_str().unwrap(),
        "--json",
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let cells = |line: &str| -> Vec<f64> {
        line.split(',')
            .map(|c| c.parse().unwrap_or(f64::NAN))
            .collect()
    };
    let first = cells(text.lines().nth(1).unwrap());
    let last = cells(text.lines().last().unwrap());
    assert_eq!(first[col("v_z (m/s)")], -0.8660254037844386);
    assert_eq!(first[col("spin_y (rad/s)")], -20.0);
    let out = vector3(&j["plane"]["ball_out"]["velocity"]);
    assert!((last[col("v_x (m/s)")] - out.x).abs() < 1e-12);
    assert!((last[col("v_z (m/s)")] - out.z).abs() < 1e-12);
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
}

/// Bad plane input: one line naming the field.
#[test]
fn bad_plane_input_names_the_field() {
    let dir = fresh_dir("plane-bad");
    let base = std::fs::read_to_string(scene("plane_wall_side_spin.toml")).unwrap();
    for (from, to, want) in [
        (
            "normal = [-1.0, 0.0, 0.0]",
            "normal = [0.0, 0.0, 0.0]",
            "plane.normal",
        ),
        ("[incoming.plane]", "[incoming.elsewhere]", "incoming"),
        (
            "[contact]",
            "[effects]\ntable = true\n\n[contact]",
            "effects.table",
        ),
    ] {
        let text = base.replacen(from, to, 1);
        let path = dir.join("s.toml");
        std::fs::write(&path, &text).unwrap();
        refused(&bin(&["run", path.to_str().unwrap()]), &[want]);
    }
}

/// The commands that vary two balls' states refuse a plane scene instead of ignoring
/// `[plane]`.
#[test]
fn two_ball_commands_refuse_a_plane_scene() {
    let dir = fresh_dir("plane-sweep");
    let out = bin(&[
        "sweep",
        &scene("plane_wall_side_spin.toml"),
        "--out",
        dir.to_str().unwrap(),
    ]);
    refused(&out, &["[plane] scene given to sweep"]);
    assert!(!dir.join("sweep.csv").exists());
}

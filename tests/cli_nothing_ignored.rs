//! The command line never drops what the user asked for: an option that cannot act is
//! refused (exit code 2, one line on stderr naming the option, its value and what is
//! accepted, nothing written), and where refusing would be wrong a warning on stderr
//! (`warning: ...`) says what is not used while the run succeeds. Values far outside any
//! ball game warn with the likely unit slip.

use crate::cli_common;
use cli_common::{bin, fresh_dir, refused, scene, warned};
use std::path::Path;

fn dir(tag: &str) -> std::path::PathBuf {
    fresh_dir(&format!("nothing_ignored_{tag}"))
}

fn path(d: &Path, name: &str) -> String {
    d.join(name).to_string_lossy().into_owned()
}

/// `--samples` shapes the trace and `--path-samples` the path: without the file they are
/// refused. `--steps` is rk4's: refused with an adaptive method and the closed form.
#[test]
fn options_that_cannot_act_are_refused() {
    refused(
        &bin(&["run", "--samples", "5"]),
        &["--samples = 5", "only with --trace"],
    );
    refused(
        &bin(&["run", &scene("draw_table.toml"), "--path-samples", "50"]),
        &["--path-samples = 50", "only with --path"],
    );
    refused(
        &bin(&["run", "--steps", "100"]),
        &[
            "--steps = 100",
            "only with the method rk4",
            "dop853",
            "--method rk4",
        ],
    );
    refused(
        &bin(&["run", "--method", "closed-form", "--steps", "100"]),
        &["--steps = 100", "closed-form", "does not step"],
    );
    // With rk4 the steps act: the run succeeds, rk4 takes exactly 100 steps.
    let out = bin(&["run", "--method", "rk4", "--steps", "100", "--json"]);
    assert!(out.status.success());
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["solver"]["accepted_steps"], 100);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `--plot p.pdf` wrote SVG into a file named .pdf: any name but .svg and .png is refused,
/// and nothing is written.
#[test]
fn a_figure_name_says_its_format() {
    let d = dir("plot");
    let pdf = path(&d, "p.pdf");
    refused(
        &bin(&["run", &scene("draw_table.toml"), "--plot", &pdf]),
        &["--plot", "p.pdf", ".svg or .png"],
    );
    assert!(!Path::new(&pdf).exists());
    let svg = path(&d, "p.SVG");
    let out = bin(&["run", &scene("draw_table.toml"), "--plot", &svg]);
    assert!(out.status.success());
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}

/// Options the method does not use (tolerances with rk4 or the closed form, the time
/// transform with the closed form) and the outcome's own warnings (a `[table]` section
/// without the effect) are said on stderr; the run goes on.
#[test]
fn unused_settings_warn() {
    warned(
        &bin(&["run", "--method", "rk4", "--rtol", "1e-8"]),
        &["--rtol has no effect with the method rk4"],
    );
    warned(
        &bin(&["run", "--method", "closed-form", "--atol", "1e-8", "--json"]),
        &["--atol has no effect with the method closed-form"],
    );
    warned(
        &bin(&[
            "run",
            "--method",
            "closed-form",
            "--time-transform",
            "false",
        ]),
        &["--time-transform has no effect"],
    );
    let d = dir("table_section");
    let text = std::fs::read_to_string(scene("draw_table.toml"))
        .unwrap()
        .replace("table = true", "table = false");
    let s = path(&d, "scene.toml");
    std::fs::write(&s, text).unwrap();
    for json in [false, true] {
        let mut args = vec!["run", s.as_str()];
        if json {
            args.push("--json");
        }
        warned(
            &bin(&args),
            &["[table] is given but the effect table is off"],
        );
    }
}

/// A batch with a scene whose table effect is on resolves each row up to separation and
/// says that the table is not followed; `--rtol` with the closed form (batch's default
/// method) says it has no effect.
#[test]
fn batch_says_what_it_does_not_simulate() {
    let d = dir("batch");
    let input = path(&d, "in.csv");
    std::fs::write(&input, "u_x,u_y,u_z\n1,0.2,0\n").unwrap();
    let out = path(&d, "out.csv");
    warned(
        &bin(&[
            "batch",
            &input,
            "--out",
            &out,
            "--scene",
            &scene("draw_table.toml"),
        ]),
        &[
            "draw_table.toml",
            "the effect table is not simulated by batch",
        ],
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap().lines().count(), 2);
    warned(
        &bin(&["batch", &input, "--out", &out, "--rtol", "1e-8"]),
        &["--rtol has no effect with the method closed-form"],
    );
}

/// An unknown batch column (a misspelt spin that would silently be 0) is refused with a
/// did-you-mean; no output file appears.
#[test]
fn batch_refuses_unknown_columns() {
    let d = dir("columns");
    let input = path(&d, "in.csv");
    std::fs::write(&input, "u_x,u_y,u_z,omega_a_xx\n1,0.2,0,5\n").unwrap();
    let out = path(&d, "out.csv");
    refused(
        &bin(&["batch", &input, "--out", &out]),
        &[
            "in.csv:1: column `omega_a_xx`: unknown column, expected one of",
            "(did you mean `omega_a_x`?)",
        ],
    );
    assert!(!Path::new(&out).exists());
}

/// Unit slips, each in a scene that still runs: mass 170 (grams), radius
/// 28.575 (millimetres), duration 200 (microseconds); each warns, naming the field, and the
/// run goes on (the model holds for any positive values). The same scene through batch
/// warns too.
#[test]
fn implausible_values_warn_with_the_unit_slip() {
    let d = dir("units");
    let text = std::fs::read_to_string(scene("paper_special_case.toml")).unwrap();
    for (from, to, want) in [
        (
            "mass = 0.17",
            "mass = 170",
            "balls.mass = 170 kg lies far outside the range of any ball game (0.001 to 20 kg): \
             grams meant? (170 g = 0.17 kg)",
        ),
        (
            "radius = 0.028575",
            "radius = 28.575",
            "balls.radius = 28.575 m lies far outside the range of any ball game (0.005 to 0.5 \
             m): millimetres meant? (28.575 mm = 0.028575 m)",
        ),
        (
            "duration = 2.5e-4",
            "duration = 200",
            "contact.profile.duration = 200 s lies far outside the range of any ball game \
             (1e-6 to 0.1 s): microseconds meant? (200 µs = 0.0002 s)",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let s = path(&d, "scene.toml");
        std::fs::write(&s, text.replacen(from, to, 1)).unwrap();
        let out = bin(&["run", &s]);
        warned(&out, &[want]);
        assert!(!out.stdout.is_empty());
        let input = path(&d, "in.csv");
        std::fs::write(&input, "u_x,u_y,u_z\n1,0.2,0\n").unwrap();
        warned(
            &bin(&["batch", &input, "--out", &path(&d, "o.csv"), "--scene", &s]),
            &[want],
        );
    }
    // The shipped scenes are plausible: no warning.
    for name in ["default.toml", "hertz_material.toml", "jump_follow.toml"] {
        let out = bin(&["run", &scene(name)]);
        assert!(
            out.stderr.is_empty(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

//! Error messages that point at the cause: clap's errors keep their whole message (in one
//! line), negative numbers reach their option, a misspelt subcommand or value gets a
//! did-you-mean, a file that is not a scene says so, balls that do not touch name a radius
//! in millimetres; `help --help` and every subcommand's `--help` work.

use crate::cli_common;
use cli_common::{bin, bin_in, fresh_dir, refused};
use std::path::{Path, PathBuf};

fn dir(tag: &str) -> PathBuf {
    fresh_dir(&format!("error_messages_{tag}"))
}

/// `batch in.csv` without `--out`: the whole message, missing option and usage, in one line.
#[test]
fn a_missing_option_is_named() {
    let line = refused(
        &bin(&["batch", "in.csv"]),
        &[
            "the following required arguments were not provided: --out <OUTPUT.csv>",
            "usage: billiard-contact batch --out <OUTPUT.csv> <INPUT>",
        ],
    );
    assert!(line.ends_with("(see --help)"), "{line}");
    // Two missing arguments: both named.
    refused(
        &bin(&["batch"]),
        &["not provided: --out <OUTPUT.csv>, <INPUT>; usage:"],
    );
    refused(
        &bin(&["batch", "no_such_input.csv", "--out", "o.csv"]),
        &["no_such_input.csv: cannot read the batch input"],
    );
    refused(
        &bin(&["run", "--tarce", "t.csv"]),
        &["unexpected argument '--tarce'", "did you mean '--trace'?"],
    );
}

/// Negative numbers reach their option, which names its range, or for a count a whole number.
#[test]
fn negative_numbers_reach_their_option() {
    refused(
        &bin(&["run", "--rtol", "-1e-6"]),
        &["solver.rtol = -1e-6", "in [1e-15, 0.1]"],
    );
    refused(
        &bin(&["batch", "in.csv", "--out", "o.csv", "--rtol", "-1e-6"]),
        &["solver.rtol = -1e-6"],
    );
    refused(
        &bin(&["run", "--trace", "t.csv", "--samples", "-5"]),
        &["--samples = \"-5\": a whole number"],
    );
    refused(
        &bin(&["run", "--rtol", "abc"]),
        &["--rtol = \"abc\": a number such as 1e-10"],
    );
    refused(
        &bin(&["batch", "in.csv", "--out", "o.csv", "--threads", "-2"]),
        &["--threads = \"-2\": a whole number"],
    );
}

/// `runn base.toml` blamed `base.toml` as a subcommand: a first word close to a subcommand
/// (and not a file) gets a did-you-mean; a misspelt closed value too.
#[test]
fn misspelt_names_get_a_suggestion() {
    let d = dir("names");
    refused(
        &bin_in(Some(&d), &["runn", "base.toml"]),
        &[
            "`runn` is neither a subcommand nor a scene file",
            "(did you mean `run`?)",
        ],
    );
    refused(
        &bin_in(Some(&d), &["bach", "in.csv", "--out", "o.csv"]),
        &["(did you mean `batch`?)"],
    );
    // A file of that name is a scene: read as one, not second-guessed.
    std::fs::write(d.join("runn"), "not a scene").unwrap();
    refused(
        &bin_in(Some(&d), &["runn"]),
        &["runn: line 1", "does not look like a scene file"],
    );
    refused(
        &bin(&["work-precision", "--profiles", "halfsine"]),
        &["--profiles = \"halfsine\"", "(did you mean `half-sine`?)"],
    );
}

/// A CSV given as the scene is refused as CSV, saying what a scene is; a TOML slip is not.
#[test]
fn a_file_that_is_not_a_scene_says_so() {
    let d = dir("not_a_scene");
    let csv = d.join("in.csv");
    std::fs::write(&csv, "u_x,u_y,u_z\n1,0.2,0\n").unwrap();
    refused(
        &bin(&["run", csv.to_str().unwrap()]),
        &[
            "in.csv: line 1",
            "this looks like CSV",
            "not a scene file",
            "[balls], [contact], [contact.profile]",
        ],
    );
    let toml = d.join("slip.toml");
    std::fs::write(&toml, "[balls]\nmass = 0.17\nradius =\n").unwrap();
    let line = refused(
        &bin(&["run", toml.to_str().unwrap()]),
        &["line 3", "not valid TOML"],
    );
    assert!(!line.contains("not look like"), "{line}");
}

/// A lab scene with the radius in millimetres blamed the positions only: the message now
/// says the radius looks like millimetres (the positions fit 0.028575 m).
#[test]
fn a_radius_in_millimetres_is_named() {
    let d = dir("radius");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes/stun_cut_sticks.toml"),
    )
    .unwrap();
    let s = d.join("mm.toml");
    std::fs::write(&s, text.replacen("radius = 0.028575", "radius = 28.575", 1)).unwrap();
    refused(
        &bin(&["run", s.to_str().unwrap()]),
        &[
            "incoming.lab.b.position",
            "balls.radius = 28.575 m looks like millimetres (28.575 mm = 0.028575 m)",
            "the positions fit that radius",
        ],
    );
}

/// `help --help` failed; every subcommand's help works and shows its usage.
#[test]
fn help_works_everywhere() {
    for args in [
        vec!["--help"],
        vec!["help"],
        vec!["help", "--help"],
        vec!["help", "run"],
        vec!["run", "--help"],
        vec!["batch", "--help"],
        vec!["sweep", "--help"],
        vec!["work-precision", "--help"],
        vec!["-h"],
    ] {
        let out = bin(&args);
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("Usage: billiard-contact"), "{args:?}: {text}");
    }
}

//! Sizes and counts taken from the user are bounded before anything is allocated or run:
//! a chunk, trace or path sample count or rk4 step count beyond its bound gets the one-line
//! error of every bad input (exit code 2, naming the option, the value and the bound)
//! instead of an abort on a failed allocation or minutes of silence. And numbers in
//! messages are written as a person reads them: 1e300, not 1 followed by 300 zeros.

use std::path::PathBuf;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_billiard-contact");

/// A fresh directory under the target directory, with `files` written into it.
fn sandbox(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("sizes-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

/// Runs the command in `dir`; checks exit code 2, nothing on stdout, one line on stderr
/// starting `error: ` that holds every piece of `want`, and no new file in `dir`.
fn refused(dir: &PathBuf, args: &[&str], want: &[&str]) -> String {
    let before = std::fs::read_dir(dir).unwrap().count();
    let out = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(out.stdout.is_empty(), "{args:?}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{args:?}: not one line:\n{stderr}");
    assert!(lines[0].starts_with("error: "), "{stderr}");
    for w in want {
        assert!(lines[0].contains(w), "{args:?}: `{w}` missing in {stderr}");
    }
    assert_eq!(std::fs::read_dir(dir).unwrap().count(), before, "{args:?}");
    stderr
}

/// `--chunk 1000000000000` once asked for 8 TB for the chunk's line numbers up front and
/// aborted (SIGABRT, exit 134); now it is refused, and the largest accepted chunk on a
/// one-row file holds only that row.
#[test]
fn a_chunk_beyond_its_bound_is_refused() {
    let dir = sandbox("chunk", &[("in.csv", "u_x,u_y,u_z\n1,0.5,0\n")]);
    refused(
        &dir,
        &[
            "batch",
            "in.csv",
            "--out",
            "out.csv",
            "--chunk",
            "1000000000000",
        ],
        &["--chunk = 1000000000000", "at most 1048576 rows"],
    );
    refused(
        &dir,
        &["batch", "in.csv", "--out", "out.csv", "--chunk", "1048577"],
        &["--chunk = 1048577", "at most 1048576 rows"],
    );
    let out = Command::new(BIN)
        .args(["batch", "in.csv", "--out", "out.csv", "--chunk", "1048576"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("out.csv")).unwrap();
    assert_eq!(text.lines().count(), 2, "{text}");
}

/// Trace and path sample counts: at most 1e6 rows (a 1e12-row trace ran on silently toward
/// hundreds of terabytes; a 1e12-sample path aborted on its allocation).
#[test]
fn sample_counts_beyond_their_bound_are_refused() {
    let scenes = concat!(env!("CARGO_MANIFEST_DIR"), "/data/scenes/");
    let dir = sandbox("samples", &[]);
    let draw = format!("{scenes}draw_table.toml");
    refused(
        &dir,
        &["run", "--trace", "t.csv", "--samples", "1000000000000"],
        &["--samples = 1000000000000", "at most 1e6"],
    );
    refused(
        &dir,
        &["run", "--plot-trace", "t.svg", "--samples", "1000001"],
        &["--samples = 1000001", "at most 1e6"],
    );
    refused(
        &dir,
        &[
            "run",
            &draw,
            "--path",
            "p.csv",
            "--path-samples",
            "1000000000000",
        ],
        &["--path-samples = 1000000000000", "at most 1e6"],
    );
    // The bound comes before the other checks of the option, and 0 is still "at least 1".
    refused(
        &dir,
        &["run", "--samples", "0"],
        &["--samples = 0", "at least 1"],
    );
}

/// rk4 steps: at most 1e7. On the default scene the scaled difference from the closed form
/// is 2.8e-14 at 1e3 steps and 2.2e-10 at 1e7 (rounding, which grows with the steps), so
/// 1e9 steps (minutes with no word) only cost time and accuracy: refused, naming the
/// option as the user wrote it; in a scene file, naming its key.
#[test]
fn rk4_steps_beyond_their_bound_are_refused() {
    let dir = sandbox("steps", &[]);
    refused(
        &dir,
        &["run", "--method", "rk4", "--steps", "1000000000"],
        &["--steps = 1000000000", "in [1, 1e7]", "rounding"],
    );
    refused(
        &dir,
        &["run", "--method", "rk4", "--steps", "10000001"],
        &["--steps = 10000001", "in [1, 1e7]"],
    );
    let default = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/default.toml"
    ))
    .unwrap();
    assert!(!default.contains("[solver]"));
    let scene = format!("{default}\n[solver]\nmethod = \"rk4\"\nsteps = 20000000\n");
    let dir = sandbox("steps-scene", &[("s.toml", &scene)]);
    refused(
        &dir,
        &["run", "s.toml"],
        &["solver.steps = 20000000", "in [1, 1e7]"],
    );
}

/// Values in messages: Rust's `{}` of 5e-324 is "0." and 323 zeros then 5; the message
/// names it 5e-324, and no run of 20 zeros appears, in an error and in a warning.
#[test]
fn numbers_in_messages_are_readable() {
    let default = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/default.toml"
    ))
    .unwrap();
    assert!(default.contains("mass = 0.17"));
    let tiny = default.replacen("mass = 0.17", "mass = 5e-324", 1);
    let huge = default.replacen("mass = 0.17", "mass = 1e300", 1);
    let dir = sandbox("numbers", &[("tiny.toml", &tiny), ("huge.toml", &huge)]);
    let e = refused(&dir, &["run", "tiny.toml"], &["mass = 5e-324 kg"]);
    assert!(!e.contains(&"0".repeat(20)), "{e}");
    let out = Command::new(BIN)
        .args(["run", "huge.toml"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("balls.mass = 1e300 kg"), "{stderr}");
    assert!(!stderr.contains(&"0".repeat(20)), "{stderr}");
}

/// Sweep grids: every row stays in memory for the figure, so a grid is at most 1e6 shots.
/// Each list alone is bounded too (repeated ranges once grew without limit), and the
/// product of four long lists is refused before it is formed (1e6^4 passes usize).
#[test]
fn sweep_grids_beyond_their_bound_are_refused() {
    let dir = sandbox("sweep", &[]);
    refused(
        &dir,
        &["sweep", "--cut", "0:89:0.00001", "--out", "o"],
        &["--cut", "at most 1e6 values"],
    );
    let repeated = vec!["0:80:0.0001"; 20].join(",");
    refused(
        &dir,
        &["sweep", "--cut", &repeated, "--out", "o"],
        &["--cut", "at most 1e6 values in all"],
    );
    refused(
        &dir,
        &[
            "sweep",
            "--speed",
            "1:1000:1",
            "--side",
            "0:0.999:0.001",
            "--cut",
            "0:9:1",
            "--out",
            "o",
        ],
        &[
            "--spin x --speed x --side x --cut",
            "1000 x 1000 x 10 shots",
            "at most 1e6 shots",
        ],
    );
}

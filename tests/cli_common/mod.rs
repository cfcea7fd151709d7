//! What the command-line tests share: running the binary, the shipped scenes, a fresh
//! directory, the shapes of a refusal and of a warning, and the JSON report's contract
//! (`json_contract`). Each test file uses a part of it (hence `dead_code`).
#![allow(dead_code)]

pub mod json_contract;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary as a command, for arguments built from paths.
pub fn command() -> Command {
    Command::new(env!("CARGO_BIN_EXE_billiard-contact"))
}

/// Runs the binary with `args`, in `dir` when given.
pub fn bin_in(dir: Option<&Path>, args: &[&str]) -> Output {
    let mut c = command();
    if let Some(d) = dir {
        c.current_dir(d);
    }
    c.args(args).output().unwrap()
}

/// Runs the binary with `args`.
pub fn bin(args: &[&str]) -> Output {
    bin_in(None, args)
}

/// The path of a shipped scene, `data/scenes/NAME`.
pub fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(name)
}

/// [`scene_path`] as a string, for argument lists.
pub fn scene(name: &str) -> String {
    scene_path(name).to_string_lossy().into_owned()
}

/// A fresh, empty directory for the test `tag`.
pub fn fresh_dir(tag: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(tag);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Exit code 2, nothing on stdout, one line on stderr starting `error: ` with every piece
/// of `want`; returns the line.
pub fn refused(out: &Output, want: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "not one line:\n{stderr}");
    assert!(lines[0].starts_with("error: "), "{stderr}");
    for w in want {
        assert!(lines[0].contains(w), "`{w}` missing in: {}", lines[0]);
    }
    lines[0].to_string()
}

/// Exit code 0, and on stderr a line `warning: ...` containing every piece of `want`.
pub fn warned(out: &Output, want: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let line = stderr
        .lines()
        .find(|l| want.iter().all(|w| l.contains(w)))
        .unwrap_or_else(|| panic!("no warning with {want:?} in:\n{stderr}"));
    assert!(line.starts_with("warning: "), "{line}");
}

/// Exit code 0 (stderr in the failure message otherwise).
pub fn succeeded(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs the binary with `args`, which must succeed, and parses its stdout as JSON.
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = bin(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The rows of a CSV file, each a map from the header's column names to the cells.
pub fn csv_rows(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    r.records()
        .map(|rec| {
            header
                .iter()
                .cloned()
                .zip(rec.unwrap().iter().map(String::from))
                .collect()
        })
        .collect()
}

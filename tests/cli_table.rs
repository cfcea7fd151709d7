//! The command line with the table effect: `--path`, `--plot`, the JSON `table` object,
//! and clear errors when the table effect is missing.

use std::path::PathBuf;
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_billiard-contact"))
}

fn scene(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(name)
}

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("bc-cli-table-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The jump scene: A hops and bounces, B is pushed into the cloth; the path runs until both
/// roll, with two rows (before, after) at every impact; the plot is an SVG top view.
#[test]
fn jump_scene_writes_path_and_plot() {
    let dir = temp_dir("jump");
    let (csv, svg) = (dir.join("path.csv"), dir.join("paths.svg"));
    let out = bin()
        .arg("run")
        .arg(scene("jump_follow.toml"))
        .args(["--json", "--path"])
        .arg(&csv)
        .arg("--plot")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let a = &json["table"]["a"];
    let hop = a["hop_time"].as_f64().unwrap();
    assert!(hop > 0.0, "the cue ball jumps");
    // Hop time 2 v_z / g from the ball's lab velocity after the contact.
    let vz = json["lab_out"]["a"]["velocity"][2].as_f64().unwrap();
    assert!((hop - 2.0 * vz / 9.81).abs() <= 1e-15 * hop.max(1.0) * 10.0);
    assert!((a["hop_height"].as_f64().unwrap() - vz * vz / (2.0 * 9.81)).abs() <= 1e-15);
    assert!(
        a["bounces"].as_u64().unwrap() > 0,
        "restitution 0.5 bounces"
    );
    assert_eq!(json["table"]["b"]["hop_time"].as_f64(), Some(0.0));
    let end = json["table"]["end_time"].as_f64().unwrap();

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "t (s)");
    assert_eq!(header.len(), 21);
    assert!(header.contains(&"a_vz (m/s)") && header.contains(&"b_phase"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let last = rows.last().unwrap();
    assert_eq!(last[0].parse::<f64>().unwrap(), end);
    assert_eq!((last[10], last[20]), ("rolling", "rolling"));
    assert!(rows.iter().any(|r| r[10] == "flight"));
    // At the first landing of A the time appears twice: falling, then after the impact.
    let landing = a["impact"]["time"].as_f64().unwrap();
    let at: Vec<&Vec<&str>> = rows
        .iter()
        .filter(|r| r[0].parse::<f64>().unwrap() == landing)
        .collect();
    assert_eq!(at.len(), 2);
    assert!(at[0][6].parse::<f64>().unwrap() < 0.0, "falling before");
    assert!(at[1][6].parse::<f64>().unwrap() > 0.0, "bouncing after");

    let svg_text = std::fs::read_to_string(&svg).unwrap();
    assert!(svg_text.starts_with("<svg") && svg_text.contains("line of centres"));
    std::fs::remove_dir_all(&dir).ok();
}

/// `--path` / `--plot` without the table effect: a bad input (exit 2) that says what to set,
/// and no file is written.
#[test]
fn path_without_the_table_effect_is_a_clear_error() {
    let dir = temp_dir("off");
    let csv = dir.join("path.csv");
    let out = bin()
        .arg("run")
        .arg(scene("default.toml"))
        .arg("--path")
        .arg(&csv)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("table = true"), "{err}");
    assert!(!csv.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// The summary of a table scene prints the roll-out of both balls.
#[test]
fn summary_prints_the_roll_out_of_both_balls() {
    let out = bin()
        .arg("run")
        .arg(scene("draw_table.toml"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("table (cloth mu 0.2"), "{text}");
    assert!(text.contains("    A:") && text.contains("    B:"));
    assert!(text.contains("deflected"));
}

//! The command line with the table effect: `--path`, `--plot`, the JSON `table` object,
//! and clear errors when the table effect is missing.

use crate::cli_common;
use cli_common::{command, fresh_dir, scene_path as scene, succeeded};

/// The jump scene: A hops and bounces, B is pushed into the cloth; the path runs until both
/// roll, with two rows (before, after) at every impact; the plot is an SVG top view.
#[test]
fn jump_scene_writes_path_and_plot() {
    let dir = fresh_dir("cli_table_jump");
    let (csv, svg) = (dir.join("path.csv"), dir.join("paths.svg"));
    let out = command()
        .arg("run")
        .arg(scene("jump_follow.toml"))
        .args(["--json", "--path"])
        .arg(&csv)
        .arg("--plot")
        .arg(&svg)
        .output()
        .unwrap();
    succeeded(&out);
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
    let dir = fresh_dir("cli_table_off");
    let csv = dir.join("path.csv");
    let out = command()
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
    let out = command()
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

/// A stun cut through the command, frictionless elastic contact (mu = 0, e = 1): A leaves
/// along the tangent line with (0, s sin phi), B along the line of centres with
/// (s cos phi, 0), neither spinning, both on the cloth (no hop: settle_time 0). Derived here
/// for a ball sliding without spin at speed v on cloth friction mu_c (up +z): the friction
/// mu_c m g opposes v and its torque spins the ball up until v - mu_c g t = (5/2) mu_c g t,
/// so it rolls at t_s = 2 v / (7 mu_c g) with 5/7 v, having slid 12 v^2 / (49 mu_c g);
/// with rolling resistance mu_r it then rests after (5/7 v) / (mu_r g) more, another
/// (5/7 v)^2 / (2 mu_r g) on. The cloth's impulse until then is m (v_end - v) horizontally
/// and m g t_end upward (it carries the weight). Directions are counter-clockwise about up
/// from +x (the line of centres); a negative cut (v < 0) makes A's direction and
/// deflection negative.
#[test]
fn table_json_values_of_a_stun_cut() {
    const M: f64 = 0.17;
    const R: f64 = 0.028575;
    let (g, mu_c, mu_r, s) = (9.81, 0.2, 0.01, 2.0);
    let dir = fresh_dir("cli_table_stun");
    for (cut_deg, resistance) in [(30.0f64, 0.0), (-30.0, 0.0), (-30.0, mu_r)] {
        let cut = cut_deg.to_radians();
        let (u, v) = (s * cut.cos(), s * cut.sin());
        let table = format!("[table]\nmu = {mu_c}\nrolling_resistance = {resistance}\n");
        let json = stun_cut_report(&dir, [u, v], &table);
        let table = &json["table"];
        let num = |x: &serde_json::Value| x.as_f64().unwrap_or_else(|| panic!("{x}"));
        let close = |x: f64, want: f64, what: &str| {
            assert!(
                (x - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{cut_deg} {resistance} {what}: {x} vs {want}"
            )
        };
        let mut ends = Vec::new();
        // (ball, speed, its unit direction, start x, incoming direction (degrees) if moving)
        for (key, speed, (ex, ey), x0, incoming) in [
            ("a", v.abs(), (0.0, v.signum()), -R, Some(cut_deg)),
            ("b", u, (1.0, 0.0), R, None),
        ] {
            let b = &table[key];
            let t_s = 2.0 * speed / (7.0 * mu_c * g);
            close(num(&b["hop_time"]), 0.0, "hop_time");
            close(num(&b["settle_time"]), 0.0, "settle_time");
            close(num(&b["slide_time"]), t_s, "slide_time");
            close(num(&b["roll_time"]), t_s, "roll_time");
            let slid = 12.0 * speed * speed / (49.0 * mu_c * g);
            close(num(&b["slide_displacement"][0]), slid * ex, "slide x");
            close(num(&b["slide_displacement"][1]), slid * ey, "slide y");
            let roll = 5.0 / 7.0 * speed;
            let heading = ey.atan2(ex).to_degrees();
            // The direction is that of the rolling velocity, also when the ball then rests.
            close(num(&b["direction_deg"]), heading, "direction_deg");
            match incoming {
                Some(inc) => close(num(&b["deflection_deg"]), heading - inc, "deflection_deg"),
                None => assert!(b.get("deflection_deg").is_none(), "B came in at rest"),
            }
            let (end, v_end) = if resistance > 0.0 {
                let t_rest = t_s + roll / (resistance * g);
                let run = slid + roll * roll / (2.0 * resistance * g);
                let rest = &b["rest"];
                close(num(&rest["time"]), t_rest, "rest time");
                close(num(&rest["position"][0]), x0 + run * ex, "rest x");
                close(num(&rest["position"][1]), run * ey, "rest y");
                close(num(&rest["position"][2]), R, "rest z");
                (t_rest, 0.0)
            } else {
                assert!(b.get("rest").is_none());
                (t_s, roll)
            };
            let imp = &b["table_impulse"];
            close(num(&imp[0]), M * (v_end - speed) * ex, "table_impulse x");
            close(num(&imp[1]), M * (v_end - speed) * ey, "table_impulse y");
            close(num(&imp[2]), M * g * end, "table_impulse z");
            ends.push(end);
        }
        close(num(&table["end_time"]), ends[0].max(ends[1]), "end_time");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `run --json` of a frictionless, elastic stun shot with the table phase: A (0.17 kg,
/// 28.575 mm, alpha 0.4) at (-R, 0, R) with velocity (u, v, 0), B at rest at (R, 0, R),
/// up +z, the closed form; `table` is the scene's `[table]` section (empty: the defaults).
fn stun_cut_report(dir: &std::path::Path, [u, v]: [f64; 2], table: &str) -> serde_json::Value {
    const R: f64 = 0.028575;
    let path = dir.join("stun.toml");
    std::fs::write(
        &path,
        format!(
            r#"
name = "stun cut"
[balls]
mass = 0.17
radius = {R}
alpha = 0.4
[contact]
mu = 0.0
restitution = 1.0
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.lab]
a = {{ position = [{a:?}, 0.0, {R:?}], velocity = [{u:?}, {v:?}, 0.0] }}
b = {{ position = [{R:?}, 0.0, {R:?}], velocity = [0.0, 0.0, 0.0] }}
up = [0.0, 0.0, 1.0]
[solver]
method = "closed-form"
[effects]
table = true
{table}"#,
            a = -R
        ),
    )
    .unwrap();
    let out = command()
        .arg("run")
        .arg(&path)
        .arg("--json")
        .output()
        .unwrap();
    succeeded(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A full stun hit, frictionless and elastic: A stops dead (velocity and spin 0, so its
/// `rolling.velocity` is zero) and has neither `direction_deg` nor `deflection_deg`
/// (docs/formats.md#the-table-object); B takes A's velocity along the line of centres, so
/// its direction is 0 degrees.
#[test]
fn a_ball_that_stops_dead_has_no_direction() {
    let dir = fresh_dir("cli_table_dead");
    let json = stun_cut_report(&dir, [2.0, 0.0], "");
    let (a, b) = (&json["table"]["a"], &json["table"]["b"]);
    for k in 0..3 {
        assert_eq!(a["rolling"]["velocity"][k].as_f64(), Some(0.0), "{a}");
    }
    assert!(a.get("direction_deg").is_none() && a.get("deflection_deg").is_none());
    assert_eq!(b["direction_deg"].as_f64(), Some(0.0), "{b}");
    assert!(b.get("deflection_deg").is_none(), "B came in at rest");
}

//! The `work-precision` and `batch` commands end to end: files written, header contract,
//! figure, atomic output, exit codes.

use crate::cli_common;
use cli_common::{command, fresh_dir, succeeded};

#[test]
fn work_precision_writes_csv_svg_png_md() {
    let dir = fresh_dir("cli_study_batch_wp");
    // The study of two profiles, one timing each, into `dir`.
    let study = || {
        command()
            .args([
                "work-precision",
                "--profiles",
                "half-sine,rectangle",
                "--repeats",
                "1",
            ])
            .args(["--no-sticking", "--out"])
            .arg(&dir)
            .output()
            .unwrap()
    };
    let out = study();
    succeeded(&out);
    let csv = std::fs::read_to_string(dir.join("work_precision.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().starts_with(
        "profile,method,rtol,steps,error,stick_time_error,rhs_evaluations,accepted_steps,seconds_per_contact,"
    ));
    // 2 profiles x (closed form + 12 rk4 + 2 x 11 adaptive), no breakpoint rows.
    assert_eq!(lines.count(), 2 * (1 + 12 + 22));
    let svg = std::fs::read_to_string(dir.join("work_precision.svg")).unwrap();
    assert!(svg.contains("half-sine") && svg.contains("rectangle"));
    let png = std::fs::read(dir.join("work_precision.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("error<=1e-10"), "{summary}");
    // The cost tables: a row per line, the adaptive methods against the half-sine.
    let md = std::fs::read_to_string(dir.join("work_precision.md")).unwrap();
    assert!(md.contains("| rectangle | dop853 |"), "{md}");
    assert!(md.contains("Against the half-sine"), "{md}");
    // Redraw from the CSV alone.
    std::fs::remove_file(dir.join("work_precision.png")).unwrap();
    let re = command()
        .args(["work-precision", "--replot", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(re.status.success());
    assert!(dir.join("work_precision.png").exists());
    assert_eq!(
        std::fs::read_to_string(dir.join("work_precision.md")).unwrap(),
        md,
        "--replot rewrites the same tables from the CSV"
    );

    // A peer's row appended (as benches/peers/scipy_contact.py does) survives a new run
    // of the study into the same directory; one of a profile not run now is dropped.
    // The built-in default scene's name, quoted as the CSV writes it.
    let scene = "\"rolling cue ball, 30 degree cut\"";
    assert!(csv.contains(scene));
    let peer = format!("half-sine,scipy-RK45,1e-06,,2e-07,,120,20,0.0001,true,{scene},,,,,true");
    let gone = format!("hertz,scipy-RK45,1e-06,,2e-07,,120,20,0.0001,true,{scene},,,,,true");
    std::fs::write(
        dir.join("work_precision.csv"),
        format!("{csv}{peer}\n{gone}\n"),
    )
    .unwrap();
    let again = study();
    assert!(again.status.success());
    let text = String::from_utf8_lossy(&again.stdout);
    assert!(
        text.contains("kept 1 peer rows") && text.contains("dropped 1"),
        "{text}"
    );
    let csv2 = std::fs::read_to_string(dir.join("work_precision.csv")).unwrap();
    assert_eq!(csv2.lines().count(), 1 + 2 * (1 + 12 + 22) + 1);
    assert!(csv2.lines().any(|l| l.starts_with("half-sine,scipy-RK45,")));
    assert!(!csv2.contains("hertz,scipy-RK45"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn batch_writes_atomically_and_names_bad_lines() {
    let dir = fresh_dir("cli_study_batch_batch");
    let input = dir.join("in.csv");
    std::fs::write(&input, "id,u_x,u_y,u_z\na,1.0,0.2,0\nb,-0.5,0.1,0\n").unwrap();
    let output = dir.join("out.csv");
    let ok = command()
        .arg("batch")
        .arg(&input)
        .arg("--out")
        .arg(&output)
        .args(["--threads", "2"])
        .output()
        .unwrap();
    succeeded(&ok);
    let text = std::fs::read_to_string(&output).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 3);
    assert!(rows[1].starts_with("2,a,true,"));
    // Separating balls: no collision, no impulse.
    assert!(rows[2].starts_with("3,b,false,0.0,"), "{}", rows[2]);

    // A bad line: exit 2, the line named, the previous output untouched.
    std::fs::write(&input, "u_x,u_y,u_z\n1,0,0\n1,x,0\n").unwrap();
    let bad = command()
        .arg("batch")
        .arg(&input)
        .arg("--out")
        .arg(&output)
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("in.csv:3:"), "{err}");
    assert_eq!(std::fs::read_to_string(&output).unwrap(), text);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    std::fs::remove_dir_all(&dir).ok();
}

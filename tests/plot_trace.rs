//! `run --plot-trace`: the figure draws the trace CSV's columns (the data the figure is
//! drawn from, compared cell by cell with the CSV written by the same run) for every method
//! and profile, sliding, sticking and without sliding; the command writes a valid SVG or
//! PNG, and refuses any other extension for every figure option.

use crate::cli_common;

use billiard_contact::formats::scene::SolverOverrides;
use billiard_contact::formats::trace::{Tee, HEADER};
use billiard_contact::plot::trace::TraceFigure;
use billiard_contact::profile::ProfileKind;
use billiard_contact::work_precision::study_profile;
use billiard_contact::{run_scene, CsvTrace, Method, Sampling, Scene};
use cli_common::{command, fresh_dir, scene_path, succeeded};

/// The CSV's header and its columns, an empty cell as `None` (read with the csv crate,
/// independently of the figure).
fn parse(bytes: &[u8]) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
    let mut r = csv::Reader::from_reader(bytes);
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    let mut cols = vec![Vec::new(); header.len()];
    for rec in r.records() {
        for (j, cell) in rec.unwrap().iter().enumerate() {
            cols[j].push((!cell.is_empty()).then(|| cell.parse::<f64>().unwrap()));
        }
    }
    (header, cols)
}

/// Every curve of the figure is its CSV column against t: t in µs (these contacts last
/// 200-250 µs), theta in degrees, the rest in the CSV's units; every column but t is drawn;
/// the stop of sliding is where the CSV's S reaches 0.
#[test]
fn the_figure_draws_the_trace_csv_columns() {
    for name in [
        "stun_cut_slides.toml",
        "stun_cut_sticks.toml",
        "head_on_stun.toml",
    ] {
        for kind in ProfileKind::ALL {
            for method in Method::ALL {
                let mut scene = Scene::load(&scene_path(name)).unwrap();
                scene.profile = study_profile(kind, &scene).unwrap();
                let over = SolverOverrides {
                    method: Some(method),
                    ..Default::default()
                };
                let settings = over.apply(&scene.solver).unwrap();
                let mut csv = CsvTrace::new(Vec::new()).unwrap();
                let mut rows = Vec::new();
                let run = {
                    let mut both = Tee(&mut csv, &mut rows);
                    run_scene(&scene, &settings, Some((&mut both, Sampling::Steps))).unwrap()
                };
                let (header, cols) = parse(&csv.finish().unwrap());
                let fig = TraceFigure::new(&scene, &run, &rows);
                let case = format!("{name} {} {}", kind.name(), method.name());
                check_curves(&fig, &header, &cols, &case);
                check_stop(&fig, &header, &cols, name, &case);
            }
        }
    }
}

fn check_curves(fig: &TraceFigure, header: &[String], cols: &[Vec<Option<f64>>], case: &str) {
    assert_eq!(fig.time.unit, "µs", "{case}");
    let t = &cols[0];
    let mut drawn: Vec<&str> = Vec::new();
    for c in fig.panels.iter().flat_map(|p| &p.curves) {
        let j = header.iter().position(|h| h == c.column).unwrap();
        let factor = if c.column == "theta (rad)" {
            180.0 / std::f64::consts::PI
        } else {
            1.0
        };
        let expected: Vec<(f64, f64)> = t
            .iter()
            .zip(&cols[j])
            .filter_map(|(t, v)| Some((t.unwrap() * 1e6, (*v)? * factor)))
            .collect();
        assert_eq!(c.points, expected, "{case}: {}", c.column);
        drawn.push(c.column);
    }
    drawn.sort_unstable();
    let mut columns: Vec<&str> = HEADER[1..].to_vec();
    columns.sort_unstable();
    assert_eq!(drawn, columns, "{case}: every column but t, once");
}

fn check_stop(
    fig: &TraceFigure,
    header: &[String],
    cols: &[Vec<Option<f64>>],
    name: &str,
    case: &str,
) {
    let s = header.iter().position(|h| h == "S (m/s)").unwrap();
    let slip = &fig.panels[1];
    let note = slip.note.as_deref().unwrap_or_default();
    match name {
        "stun_cut_sticks.toml" => {
            let stop = fig.stick_time.unwrap_or_else(|| panic!("{case}: no stop"));
            let at = cols[0]
                .iter()
                .position(|t| t.unwrap() * 1e6 == stop)
                .unwrap_or_else(|| panic!("{case}: a row at the stop"));
            assert_eq!(cols[s][at], Some(0.0), "{case}");
            assert!(cols[s][..at].iter().all(|v| v.unwrap() > 0.0), "{case}");
            assert!(note.starts_with("sliding stops at t = "), "{case}: {note}");
        }
        "stun_cut_slides.toml" => {
            assert_eq!(fig.stick_time, None, "{case}");
            assert!(cols[s].iter().all(|v| v.unwrap() > 0.0), "{case}");
            assert_eq!(note, "slides throughout the contact", "{case}");
        }
        _ => {
            assert_eq!(fig.stick_time, None, "{case}: nothing to stop");
            assert_eq!(note, "no sliding: S(0) = 0", "{case}");
            assert!(
                fig.panels[2].curves[0].points.is_empty(),
                "{case}: no theta"
            );
        }
    }
}

/// The command writes a valid SVG (one document with the scene's name in its title) and a
/// PNG that decodes to the figure's size, for every method, sliding and sticking.
#[test]
fn the_command_writes_a_valid_svg_and_png() {
    let dir = fresh_dir("plot_trace_files");
    for name in ["stun_cut_slides.toml", "stun_cut_sticks.toml"] {
        let scene = Scene::load(&scene_path(name)).unwrap();
        for method in Method::ALL {
            let (svg, png) = (dir.join("t.svg"), dir.join("t.png"));
            for file in [&svg, &png] {
                let out = command()
                    .arg("run")
                    .arg(scene_path(name))
                    .args(["--method", method.name(), "--plot-trace"])
                    .arg(file)
                    .output()
                    .unwrap();
                succeeded(&out);
            }
            let text = std::fs::read_to_string(&svg).unwrap();
            assert!(
                text.starts_with("<svg width=\"1400\" height=\"1280\""),
                "{name} {method:?}"
            );
            assert_eq!(text.matches("<svg").count(), 1);
            assert!(text.trim_end().ends_with("</svg>"));
            assert!(
                text.contains(&scene.name),
                "{name}: the title names the scene"
            );
            let img = image::open(&png).unwrap();
            assert_eq!(
                (img.width(), img.height()),
                (1400, 1280),
                "{name} {method:?}"
            );
            std::fs::remove_file(&svg).unwrap();
            std::fs::remove_file(&png).unwrap();
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// With --trace, the CSV is written as without the figure.
#[test]
fn the_trace_csv_is_the_same_with_the_figure() {
    let dir = fresh_dir("plot_trace_same");
    let mut csvs = Vec::new();
    for plot in [false, true] {
        let csv = dir.join(format!("t{plot}.csv"));
        let mut cmd = command();
        cmd.arg("run")
            .arg(scene_path("stun_cut_sticks.toml"))
            .arg("--trace")
            .arg(&csv);
        if plot {
            cmd.arg("--plot-trace").arg(dir.join("t.svg"));
        }
        assert!(cmd.output().unwrap().status.success());
        csvs.push(std::fs::read(&csv).unwrap());
    }
    assert_eq!(csvs[0], csvs[1]);
    assert!(dir.join("t.svg").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// A figure file that is neither .svg nor .png is refused before the run (exit 2, one
/// line naming the option, the file and the accepted extensions), and nothing is written.
#[test]
fn other_extensions_are_refused_for_every_figure_option() {
    let dir = fresh_dir("plot_trace_ext");
    for (option, scene) in [
        ("--plot-trace", "default.toml"),
        ("--plot", "draw_table.toml"),
        ("--plot", "default.toml"),
    ] {
        for file in ["p.pdf", "p", "p.svg.txt"] {
            let path = dir.join(file);
            let out = command()
                .arg("run")
                .arg(scene_path(scene))
                .arg(option)
                .arg(&path)
                .output()
                .unwrap();
            assert_eq!(out.status.code(), Some(2), "{option} {file}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(
                err.starts_with(&format!("error: {option} = {}", path.display()))
                    && err.contains("a file name ending in .svg or .png"),
                "{err}"
            );
            assert!(!path.exists());
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

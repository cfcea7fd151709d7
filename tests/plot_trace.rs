//! `run --plot-trace`: the command writes a valid SVG or PNG, the trace CSV is the same
//! with the figure, and any other extension is refused for every figure option. That the
//! figure draws the trace CSV's columns is a unit test of the figure (src/apps/plot/trace.rs).

use crate::cli_common;

use billiard_contact::{Method, Scene};
use cli_common::{command, fresh_dir, scene_path, succeeded};

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

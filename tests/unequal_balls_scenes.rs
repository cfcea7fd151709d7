//! Scenes of balls of different mass and size: the `[balls.a]` / `[balls.b]` contract and its
//! errors, the lab frame (the balls touch at r_A + r_B, the tilted line of centres on a
//! table), the bar-table scene through every method with its table phase, batch rows with
//! the scene's balls, and the identical-ball limit given as a pair reproducing `[balls]`
//! byte for byte.

use crate::cli_common;
use crate::common;

use billiard_contact::batch::{resolve, BatchInput, BatchSetup, Overrides};
use billiard_contact::{run_scene, Incoming, Method, Report, Scene};
use common::unequal::{momentum, Sphere};
use common::{amax, Pair};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

fn bar_table() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/scenes/bar_table_cut.toml")
}

const REST: &str = r#"
[contact]
mu = 0.06
restitution = 0.95
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.cm]
u = [0.5, 0.25, 0.0]
"#;

fn parse(balls: &str) -> Result<Scene, billiard_contact::Error> {
    Scene::parse(&format!("{balls}\n{REST}"), Path::new("."), None)
}

#[test]
fn balls_a_and_b_are_read_and_their_errors_name_the_keys() {
    let s = parse(
        "[balls.a]\nmass = 0.184\nradius = 0.030163\n[balls.b]\nmass = 0.17\nradius = 0.028575\nalpha = 0.35",
    )
    .unwrap();
    assert_eq!(s.balls.a.mass(), 0.184);
    assert_eq!(s.balls.a.alpha(), 0.4); // default
    assert_eq!(s.balls.b.alpha(), 0.35);
    // Both forms, whichever shared key is given: an error naming both.
    for shared in ["mass = 0.17", "radius = 0.03", "alpha = 0.4"] {
        let e = parse(&format!(
            "[balls]\n{shared}\n[balls.a]\nmass = 0.184\nradius = 0.03\n[balls.b]\nmass = 0.17\nradius = 0.03"
        ))
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("balls.mass") && e.contains("[balls.a]") && e.contains("[balls.b]"),
            "{shared}: {e}"
        );
    }
    // [balls.a] alone.
    let e = parse("[balls.a]\nmass = 0.184\nradius = 0.03")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("balls.b = missing"), "{e}");
    let e = parse("[balls.b]\nmass = 0.184\nradius = 0.03")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("balls.a = missing"), "{e}");
    // A bad value names its section.
    let e = parse("[balls.a]\nmass = 0.184\nradius = 0.03\n[balls.b]\nmass = -1.0\nradius = 0.03")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("balls.b.mass = -1"), "{e}");
    let e = parse(
        "[balls.a]\nmass = 0.184\nradius = 0.03\nalpha = 0.9\n[balls.b]\nmass = 1.0\nradius = 0.03",
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("balls.a.alpha = 0.9"), "{e}");
    // [balls] without a mass.
    let e = parse("[balls]\nradius = 0.03").unwrap_err().to_string();
    assert!(e.starts_with("balls.mass = missing"), "{e}");
}

/// The same identical balls given the old way and as a pair: the same report, byte for byte,
/// for every method, centre-of-mass and lab (with the table).
#[test]
fn identical_balls_as_a_pair_give_the_same_report_to_the_last_byte() {
    let text = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/scenes/draw_table.toml"),
    )
    .unwrap();
    let old = "[balls]\nmass = 0.17\nradius = 0.028575\nalpha = 0.4\n";
    assert!(text.contains(old));
    let pair = text.replace(
        old,
        "[balls.a]\nmass = 0.17\nradius = 0.028575\nalpha = 0.4\n[balls.b]\nmass = 0.17\nradius = 0.028575\n",
    );
    for method in [
        Method::ClosedForm,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
    ] {
        let one = Scene::parse(&text, Path::new("."), None).unwrap();
        let two = Scene::parse(&pair, Path::new("."), None).unwrap();
        let s = one.solver.with_method(method);
        let (a, b) = (
            run_scene(&one, &s, None).unwrap(),
            run_scene(&two, &s, None).unwrap(),
        );
        let (ja, jb) = (
            Report::new(&one, &a).to_json().unwrap(),
            Report::new(&two, &b).to_json().unwrap(),
        );
        assert_eq!(ja, jb, "{method}");
    }
}

#[test]
fn the_bar_table_scene_runs_with_every_method_and_conserves_lab_momentum() {
    let scene = Scene::load(&bar_table()).unwrap();
    let Incoming::Lab(lab) = scene.incoming else {
        panic!("a lab scene");
    };
    // The balls touch at r_A + r_B, and the line of centres is tilted by r_A - r_B.
    let (ra, rb) = (scene.balls.a.radius(), scene.balls.b.radius());
    let d = lab.b.position - lab.a.position;
    assert!((d.norm() - (ra + rb)).abs() <= 1e-9 * (ra + rb));
    assert!((d.z - (rb - ra)).abs() < 1e-15);
    let a = Sphere {
        m: scene.balls.a.mass(),
        r: ra,
        alpha: scene.balls.a.alpha(),
    };
    let b = Sphere {
        m: scene.balls.b.mass(),
        r: rb,
        alpha: scene.balls.b.alpha(),
    };
    let incoming = Pair {
        n: d.normalize(),
        va: lab.a.velocity,
        vb: lab.b.velocity,
        wa: lab.a.spin,
        wb: lab.b.spin,
    };
    let mut exact = None;
    for (method, tol) in [
        (Method::ClosedForm, 0.0),
        (Method::Rk4, 1e-6),
        (Method::Dopri5, 1e-7),
        (Method::Dop853, 1e-9),
    ] {
        let s = scene.solver.with_method(method);
        let o = run_scene(&scene, &s, None).unwrap();
        let (oa, ob) = o.lab_out.unwrap();
        let out = Pair {
            va: oa.velocity,
            vb: ob.velocity,
            wa: oa.spin,
            wb: ob.spin,
            ..incoming
        };
        // Lab momentum m_A v_A + m_B v_B is conserved (computed here from the masses).
        let dp = amax(&(momentum(&a, &b, &out) - momentum(&a, &b, &incoming)));
        assert!(dp <= 1e-15, "{method}: {dp:e}");
        // Each ball on the cloth with its own radius: the table phase ends with both
        // rolling, v = r w x up.
        let t = o.table.as_ref().expect("table phase");
        for (r, ball) in [(&t.a, ra), (&t.b, rb)] {
            let roll = r.rolling.velocity - ball * r.rolling.spin.cross(&Vector3::z());
            assert!(amax(&roll) < 1e-9, "{method}: {roll}");
        }
        assert!(t.check.energy_increase < 1e-12 && t.check.momentum_error < 1e-12);
        // The line of centres points down from the larger A to the smaller B: the normal
        // impulse lifts the cue ball (it hops) and presses the object ball into the cloth.
        assert!(oa.velocity.z > 0.0 && ob.velocity.z < 0.0, "{method}");
        match exact {
            None => exact = Some(out),
            Some(e) => {
                let v = 1.5;
                let err = amax(&(out.va - e.va)).max(amax(&(out.vb - e.vb))) / v;
                assert!(err <= tol, "{method}: {err:e}");
            }
        }
    }
}

#[test]
fn batch_rows_use_the_scenes_balls_and_refuse_ball_overrides() {
    let scene = Scene::load(&bar_table()).unwrap();
    for method in [Method::ClosedForm, Method::Dop853] {
        let s = scene.solver.with_method(method);
        let setup = BatchSetup::from_scene(&scene, s);
        let row = BatchInput {
            incoming: scene.incoming,
            overrides: Overrides::default(),
        };
        let got = resolve(&setup, &row).unwrap();
        let want = run_scene(&scene, &s, None).unwrap();
        // The batch's closed-form kernel multiplies by precomputed reciprocals: a few ulps.
        let (g, w) = (got.result.out, want.outcome.result.out);
        let near = |x: Vector3<f64>, y: Vector3<f64>, scale: f64| amax(&(x - y)) <= 1e-14 * scale;
        let spin = 1.5 / scene.balls.a.radius();
        assert!(near(g.u_cm, w.u_cm, 1.5), "{method}");
        assert!(near(g.omega_a, w.omega_a, spin) && near(g.omega_b, w.omega_b, spin));
        let (a, b, _) = got.lab.unwrap();
        let (wa, wb) = want.lab_out.unwrap();
        assert!(near(a.velocity, wa.velocity, 1.5) && near(b.velocity, wb.velocity, 1.5));
        let bad = BatchInput {
            overrides: Overrides {
                mass: Some(0.2),
                ..Overrides::default()
            },
            ..row
        };
        let e = resolve(&setup, &bad).unwrap_err().to_string();
        assert!(
            e.starts_with("mass = 0.2") && e.contains("[balls.a]"),
            "{e}"
        );
        // Other overrides still apply.
        let mu = BatchInput {
            overrides: Overrides {
                mu: Some(0.1),
                ..Overrides::default()
            },
            ..row
        };
        assert!(resolve(&setup, &mu).is_ok());
    }
}

#[test]
fn lab_positions_that_do_not_touch_at_r_a_plus_r_b_are_refused() {
    let text = std::fs::read_to_string(bar_table()).unwrap();
    // B where identical balls of radius r_A would touch: 2 r_A from A is too far.
    let scene = text.replace(
        "[balls.b]          # the object ball\nmass = 0.17\nradius = 0.028575",
        "[balls.b]\nmass = 0.17\nradius = 0.0290",
    );
    let e = Scene::parse(&scene, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("incoming.lab.b.position") && e.contains("r_A + r_B"),
        "{e}"
    );
}

/// `billiard-contact run` on the bar-table scene with `--json` and `--{option} FILE`
/// (`name` in a directory of the test's own): the JSON report and the file's text.
fn run_bar_table_writing(option: &str, name: &str) -> (serde_json::Value, String) {
    let dir = std::env::temp_dir().join(format!("bc-unequal-{option}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(name);
    let out = cli_common::command()
        .arg("run")
        .arg(bar_table())
        .arg("--json")
        .arg(format!("--{option}"))
        .arg(&file)
        .output()
        .unwrap();
    cli_common::succeeded(&out);
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    (serde_json::from_slice(&out.stdout).unwrap(), text)
}

#[test]
fn the_command_runs_the_bar_table_scene_and_writes_its_ball_paths() {
    let (json, paths) = run_bar_table_writing("path", "paths.csv");
    assert_eq!(json["collision"], true);
    assert!(json["table"].is_object());
    assert!(paths.lines().count() > 10);
}

/// The material of `[balls]` with `[balls.a]` and `[balls.b]`: Hertz's contact of two
/// different spheres, written out from the textbook here (E* = E / (2 (1 - nu^2)) for one
/// material, 1/R = 1/r_A + 1/r_B, m* = m_A m_B / (m_A + m_B), k = (4/3) E* sqrt(R),
/// delta_max = (5 m* v^2 / (4 k))^(2/5), tau = (4/5) B(2/5, 1/2) delta_max / v at
/// v = 2 U(0)); a batch row's stick time is its own contact time times the stick fraction
/// p_stick / P = S(0) / (mu K) / ((1 + e) M U(0)) of the Hertz pulse.
#[test]
fn a_material_scene_of_unequal_balls_takes_the_two_spheres_contact_time() {
    let (ma, ra, aa, mb, rb, ab) = (0.184, 0.030163, 0.4, 0.17, 0.028575, 0.35);
    let (e, nu, mu) = (5.4e9, 0.34, 0.06);
    let tau = |u0: f64| {
        let v = 2.0 * u0;
        let e_star = e / (2.0 * (1.0 - nu * nu));
        let radius = ra * rb / (ra + rb);
        let m_star = ma * mb / (ma + mb);
        let k = 4.0 / 3.0 * e_star * f64::sqrt(radius);
        let delta = (5.0 * m_star * v * v / (4.0 * k)).powf(0.4);
        0.8 * common::beta_fn(0.4, 0.5) * delta / v
    };
    let text = format!(
        "[balls]\nyoungs_modulus = {e:e}\npoisson_ratio = {nu}\n\
         [balls.a]\nmass = {ma}\nradius = {ra}\nalpha = {aa}\n\
         [balls.b]\nmass = {mb}\nradius = {rb}\nalpha = {ab}\n\
         [contact]\nmu = {mu}\n[contact.profile]\nshape = \"hertz\"\n\
         [incoming.cm]\nu = [0.5, 0.02, 0.0]\n"
    );
    let scene = Scene::parse(&text, Path::new("."), None).unwrap();
    let rel = |got: f64, want: f64| ((got - want) / want).abs();
    let got = billiard_contact::profile::ForceProfile::duration(&scene.profile);
    assert!(rel(got, tau(0.5)) <= 1e-12, "{got} vs {}", tau(0.5));
    let hertz = scene.hertz().unwrap().unwrap();
    assert!(rel(hertz.reduced_mass, ma * mb / (ma + mb)) <= 1e-15);
    // Batch rows at two approach speeds, S(0) = 2 V = 0.08 U(0), elastic: P = 2 M U(0) with
    // M = 2 m*, K = (1 + 1/alpha_A)/m_A + (1 + 1/alpha_B)/m_B.
    let pair_mass = 2.0 * ma * mb / (ma + mb);
    let k = (1.0 + 1.0 / aa) / ma + (1.0 + 1.0 / ab) / mb;
    let q = 0.08 / (mu * k) / (2.0 * pair_mass);
    for method in [Method::ClosedForm, Method::Dop853] {
        let setup = BatchSetup::from_scene(&scene, scene.solver.with_method(method));
        for u0 in [0.01, 10.0] {
            let row = BatchInput::cm(billiard_contact::CmState::new(
                Vector3::new(u0, 0.04 * u0, 0.0),
                Vector3::zeros(),
                Vector3::zeros(),
            ));
            let t = resolve(&setup, &row).unwrap().stick_time.unwrap();
            let want = tau(u0) * common::hertz_time(q);
            assert!(rel(t, want) <= 1e-9, "{method}, U(0) = {u0}: {t} vs {want}");
        }
    }
}

/// The path figure (SVG) draws each ball's outline at contact with its own radius, and the
/// line of centres through both outlines' centres. Every line is drawn segment by segment
/// (two-point polylines in pixels); an outline is the one chain of segments in its ball's
/// colour that closes on itself (the paths are open chains). Its width in pixels is 2 r times
/// one scale, to a pixel of rounding each.
#[test]
fn the_path_figure_draws_each_ball_with_its_own_radius() {
    let (_, text) = run_bar_table_writing("plot", "paths.svg");
    type Px = (i64, i64);
    let segments = |colour: &str| -> Vec<(Px, Px)> {
        text.split("<polyline")
            .skip(1)
            .filter(|p| p.contains(&format!("stroke=\"{colour}\"")))
            .filter_map(|p| {
                let pts = p.split("points=\"").nth(1)?.split('"').next()?;
                let xy: Vec<Px> = pts
                    .split_whitespace()
                    .map(|xy| {
                        let (x, y) = xy.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect();
                (xy.len() == 2).then(|| (xy[0], xy[1]))
            })
            .collect()
    };
    // (width, centre) of the closed chain drawn in `colour`.
    let outline = |colour: &str| {
        let segs = segments(colour);
        let next: std::collections::HashMap<Px, Px> = segs.iter().copied().collect();
        let ring: Vec<Px> = segs
            .iter()
            .find_map(|&(start, _)| {
                let mut chain = vec![start];
                let mut at = start;
                while let Some(&to) = next.get(&at) {
                    if to == start {
                        return (chain.len() >= 24).then(|| chain.clone());
                    }
                    if chain.len() > 400 {
                        return None;
                    }
                    chain.push(to);
                    at = to;
                }
                None
            })
            .unwrap_or_else(|| panic!("no closed outline in {colour}"));
        let xs = ring.iter().map(|p| p.0 as f64);
        let ys = ring.iter().map(|p| p.1 as f64);
        let (x0, x1) = (
            xs.clone().fold(f64::MAX, f64::min),
            xs.fold(f64::MIN, f64::max),
        );
        let (y0, y1) = (
            ys.clone().fold(f64::MAX, f64::min),
            ys.fold(f64::MIN, f64::max),
        );
        (x1 - x0, (0.5 * (x0 + x1), 0.5 * (y0 + y1)))
    };
    let (wa, ca) = outline("#1F5AB4");
    let (wb, cb) = outline("#C83C1E");
    let ratio = 0.030163 / 0.028575;
    assert!(
        wa > wb && (wa / wb - ratio).abs() <= 2.0 / wb,
        "{wa} {wb} against {ratio}"
    );
    // The dashed line of centres (grey): the line through both outlines' centres carries
    // dashes on both sides beyond them, each within two pixels of it.
    let (dx, dy) = (cb.0 - ca.0, cb.1 - ca.1);
    let len = dx.hypot(dy);
    let along = |p: Px| ((p.0 as f64 - ca.0) * dx + (p.1 as f64 - ca.1) * dy) / len;
    let off = |p: Px| ((p.0 as f64 - ca.0) * dy - (p.1 as f64 - ca.1) * dx).abs() / len;
    let on_line: Vec<f64> = segments("#5A5A5A")
        .into_iter()
        .filter(|&(p, q)| off(p) <= 2.0 && off(q) <= 2.0)
        .map(|(p, _)| along(p))
        .collect();
    assert!(on_line.len() >= 10, "{} dashes on the line", on_line.len());
    assert!(on_line.iter().any(|&s| s < -wa), "no dash beyond A");
    assert!(on_line.iter().any(|&s| s > len + wb), "no dash beyond B");
}

/// A throw chart's shot with the bar-table balls: B stands on the cloth beside A (centres
/// r_A + r_B apart, B's centre r_B above the cloth at the cut angle), and the shot runs
/// through the table phase.
#[test]
fn a_sweep_shot_sets_the_smaller_object_ball_down_on_the_cloth() {
    use billiard_contact::sweep::{run_shot, Shot, Spin};
    let scene = Scene::load(&bar_table()).unwrap();
    let (ra, rb) = (scene.balls.a.radius(), scene.balls.b.radius());
    let shot = Shot {
        spin: Spin::Roll,
        speed: 1.0,
        side: 0.0,
        cut_deg: 30.0,
    };
    let lab = shot.lab_scene(scene.balls);
    let d = lab.b.position - lab.a.position;
    assert!((d.norm() - (ra + rb)).abs() <= 1e-15, "{}", d.norm());
    assert_eq!(lab.a.position.z, ra);
    assert!((lab.b.position.z - rb).abs() <= 1e-17);
    // The horizontal direction is the cut's: (sin 30, cos 30) from A.
    let h = d.x.hypot(d.y);
    assert!((d.x / h - 0.5).abs() <= 1e-15 && (d.y / h - 0.75f64.sqrt()).abs() <= 1e-15);
    let row = run_shot(&scene, &scene.solver, shot).unwrap();
    assert!(row.object_speed > 0.0 && row.throw_deg.is_some());
}

//! The fuzz harness (examples/fuzz_inputs.rs) on a few thousand inputs, so that it keeps
//! building and its guarantees hold in `cargo test`; and the inputs kept in
//! fuzz/regressions/: those of `refused/` must be refused as bad input in one line, those of
//! `run/` must run with finite output. The full run (1,000,000 inputs) is a documented
//! command, not part of `cargo test`.

#[path = "../examples/fuzz_inputs.rs"]
#[allow(dead_code)]
mod fuzz;

use billiard_contact::profile::{parse_table, Profile, Tabulated};
use billiard_contact::run_scene;
use billiard_contact::Method;
use billiard_contact::Report;
use billiard_contact::Scene;
use std::path::Path;

#[test]
fn a_few_thousand_inputs_without_panic_nan_or_hang() {
    let sum = fuzz::run(3000, 12345, None, false);
    assert_eq!(sum.inputs, 3000);
    assert!(sum.scenes_parsed > 100 && sum.tables_parsed > 50, "{sum:?}");
    assert_eq!(sum.panics, 0, "{:?}", sum.findings);
    assert_eq!(sum.non_finite, 0, "{:?}", sum.findings);
    assert_eq!(sum.failed_runs, 0, "{:?}", sum.findings);
    assert!(sum.findings.is_empty(), "{:?}", sum.findings);
}

#[test]
fn regressions_are_refused_in_one_line() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/refused");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let err = match path.extension().and_then(|e| e.to_str()) {
            Some("toml") => Scene::parse(&text, &dir, Some(&path)).unwrap_err(),
            Some("csv") => parse_table(&text, &path)
                .and_then(|pts| Tabulated::new(&pts, None, &path))
                .unwrap_err(),
            _ => continue,
        };
        seen += 1;
        assert!(err.is_bad_input(), "{}: {err}", path.display());
        assert!(!err.to_string().contains('\n'), "{}: {err}", path.display());
    }
    assert!(seen >= 9, "{seen} regression inputs");
}

#[test]
fn regressions_run_with_finite_output() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/run");
    let stun = "[balls]\nmass = 0.17\nradius = 0.028575\n[contact]\nmu = 0.2\n[contact.profile]\n\
                shape = \"rectangle\"\nduration = 3e-4\n[incoming.cm]\nu = [1.0, 0.01, 0.0]\n";
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = match path.extension().and_then(|e| e.to_str()) {
            Some("toml") => Scene::parse(&text, &dir, Some(&path)).unwrap(),
            Some("csv") => {
                let pts = parse_table(&text, &path).unwrap();
                let mut scene = Scene::parse(stun, &dir, None).unwrap();
                scene.profile = Profile::Tabulated(Tabulated::new(&pts, None, &path).unwrap());
                scene
            }
            _ => continue,
        };
        seen += 1;
        // The closed form is the reference for the integrator: dop853's outgoing state
        // against the closed-form run's, scaled by v_ref (default rtol 1e-10).
        let mut outs = Vec::new();
        for method in [Method::ClosedForm, Method::Dop853] {
            let settings = scene.solver.with_method(method);
            let out = run_scene(&scene, &settings, None)
                .unwrap_or_else(|e| panic!("{} ({method}): {e}", path.display()));
            Report::new(&scene, &out)
                .to_json()
                .unwrap_or_else(|e| panic!("{} ({method}): {e}", path.display()));
            assert!(out.outcome.result.out.is_finite(), "{}", path.display());
            outs.push(out);
        }
        let (cf, d) = (&outs[0].outcome, &outs[1].outcome);
        // v_ref of the collision (docs/model.md#scales-and-scaled-errors), the scale of the
        // integrator's tolerances: on mu_pure_exp_huge_slip.toml the slip, 3.7e14 m/s, sets
        // it, and dop853 in the smoothed time variable meets rtol 1e-10 in 3 steps with U
        // 7e-3 m/s off.
        let v = scene.collision().unwrap().0.scales.speed;
        let (a, b) = (&cf.result.out, &d.result.out);
        let w = v / scene.balls.a.radius();
        let err = ((a.u_cm - b.u_cm).amax() / v)
            .max((a.omega_a - b.omega_a).amax() / w)
            .max((a.omega_b - b.omega_b).amax() / w);
        assert!(
            err <= 1e-6,
            "{}: dop853 vs closed form {err:e}",
            path.display()
        );
    }
    assert!(seen >= 4, "{seen} regression inputs");
}

//! The fuzz harness (examples/fuzz_inputs.rs) on a few thousand inputs, so that it keeps
//! building and its guarantees hold in `cargo test`; and the inputs it found failing
//! (fuzz/regressions/), which must now be refused as bad input in one line. The full run
//! (1,000,000 inputs) is a documented command, not part of `cargo test`.

#[path = "../examples/fuzz_inputs.rs"]
#[allow(dead_code)]
mod fuzz;

use billiard_contact::profile::{parse_table, Tabulated};
use billiard_contact::scene::Scene;
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
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions");
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

//! The cargo-fuzz targets' inputs replayed on stable Rust: every file of
//! `fuzz/corpus/<target>/`, `fuzz/seeds/<target>/` and `fuzz/regressions/<target>/` through the same checking
//! function the target runs (`fuzz/checks.rs`, included by path), so an input a campaign
//! kept, or a crash it found and that was fixed, stays checked in `cargo test`.

#[path = "../fuzz/checks.rs"]
#[allow(dead_code)]
mod checks;

use std::path::Path;

/// Runs every file under `dir/<target>/` through its target's check; returns the count.
fn replay(dir: &str, target: &str, check: checks::Check) -> (usize, usize) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir).join(target);
    let Ok(entries) = std::fs::read_dir(&root) else {
        return (0, 0);
    };
    let (mut seen, mut ran) = (0, 0);
    let mut paths: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
    paths.sort();
    for path in paths.iter().filter(|p| p.is_file()) {
        let data = std::fs::read(path).unwrap();
        let verdict = std::panic::catch_unwind(|| check(&data))
            .unwrap_or_else(|_| panic!("{}: a promise is broken (message above)", path.display()));
        seen += 1;
        ran += usize::from(verdict == checks::Verdict::Ran);
    }
    (seen, ran)
}

#[test]
fn every_corpus_and_regression_input_keeps_the_promises() {
    let mut lines = Vec::new();
    for (target, check) in checks::TARGETS {
        let (corpus, ran) = replay("fuzz/corpus", target, check);
        let (seeds, _) = replay("fuzz/seeds", target, check);
        let (regressions, _) = replay("fuzz/regressions", target, check);
        // Every target has a committed corpus, and some of its inputs run (not all refused).
        assert!(corpus > 0, "{target}: no corpus in fuzz/corpus/{target}");
        assert!(ran > 0, "{target}: no corpus input runs");
        lines.push(format!(
            "{target}: {corpus} corpus inputs ({ran} run), {seeds} seeds, {regressions} regressions"
        ));
    }
    println!("{}", lines.join("\n"));
}
